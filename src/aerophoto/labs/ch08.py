"""Chapter 08's lab (guide §9): the student's own colour photo of the interpretation site, and its truth.

Each variant photographs :mod:`aerophoto.site.cover`'s site with its own crop and conditions (:func:`lab_setup`,
seeded by the variant number i): a frame camera f = 100 mm, 18×18 cm, at a scale 1:m between 1:8 000 and
1:9 500, the photo's x axis turned by κ = 0°, 90°, 180° or 270° from east, a small tilt (α ≤ 1.5°), a summer day
with the sun 35–60° high in the south-east to south-west, visibility 20–50 km, a little motion blur.

The student gets :class:`LabPhoto` (:func:`lab_photo`): the photo itself (six bands, shown as natural colour and
colour infrared), the photo coordinates (mm) of the numbered marks as read on it, the scale, and the names to
choose from — what the photo shows, never what is there.  The truth is the site's (:func:`truth`: the land
cover under each mark, the river's flow, the stands, the river's width in m).  The graded tasks are
:mod:`aerophoto.tasks.ch08`; the worked example is :func:`example_photo` / :func:`example_key`.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import geometry as g
from .. import interpretation as ip
from ..site import cover as cv
from .._validate import check_int_range, check_range

__all__ = ["OBJECT_NAMES", "FLOW_OPTIONS", "STAND_OPTIONS", "N_OBJECTS", "F_MM", "N_PX", "LabSetup", "setup_for",
           "lab_setup", "EXAMPLE_I", "example_setup", "REASONS", "example_photo", "example_key", "truth", "LabPhoto",
           "lab_photo", "photo_window", "LOUPE_PX"]
#: the names a numbered object can have (table 10's objects), English with Russian
OBJECT_NAMES = ("river (река)", "lake (озеро)", "pond (пруд)", "raised bog (верховое болото)",
                "low bog (низинное болото)", "pine forest (сосновый лес)", "spruce forest (еловый лес)",
                "deciduous forest (лиственный лес)", "arable land (пашня)", "meadow with haystacks (луг со стогами)",
                "railway (железная дорога)", "asphalt road (асфальтовая дорога)", "gravel road (гравийная дорога)")
FLOW_OPTIONS = ("towards +x (right)", "towards −x (left)", "towards +y (up)", "towards −y (down)")
STAND_OPTIONS = ("P", "Q")
N_OBJECTS = 6
F_MM = 100.0
N_PX = 1024
#: pixels across a magnifier's window (:func:`photo_window`)
LOUPE_PX = 400

# ground points of each object (m), several per object: a variant picks one inside its photo
_CANDIDATES = {
    "river (река)": [(x, float(cv._river_y(x))) for x in (250.0, 700.0, 900.0, 1450.0)],
    "lake (озеро)": [(270.0, 230.0), (330.0, 260.0), (300.0, 245.0)],
    "pond (пруд)": [(1322.0, 385.0), (1322.0, 400.0)],
    "raised bog (верховое болото)": [(1230.0, 1330.0), (1200.0, 1300.0), (1300.0, 1300.0)],
    "low bog (низинное болото)": [(1230.0, None), (1330.0, None), (1420.0, None)],
    "pine forest (сосновый лес)": [(230.0, 1200.0), (240.0, 1300.0), (220.0, 1150.0)],
    "spruce forest (еловый лес)": [(650.0, 1300.0), (760.0, 1250.0), (580.0, 1220.0)],
    "deciduous forest (лиственный лес)": [(700.0, 300.0), (800.0, 280.0), (650.0, 260.0)],
    "arable land (пашня)": [(1264.0, 415.0), (1404.0, 1060.0), (1150.0, 1060.0), (1124.0, 380.0)],
    "meadow with haystacks (луг со стогами)": [],  # at the haystacks (from the site's features)
    "railway (железная дорога)": [],  # on the railway's centre line
    "asphalt road (асфальтовая дорога)": [],
    "gravel road (гравийная дорога)": [],
}
_CLASS_OF = {
    "river (река)": ("deep water",), "lake (озеро)": ("deep water",), "pond (пруд)": ("deep water", "shallow water"),
    "raised bog (верховое болото)": ("raised bog",), "low bog (низинное болото)": ("low bog",),
    "pine forest (сосновый лес)": ("pine forest",), "spruce forest (еловый лес)": ("spruce forest",),
    "deciduous forest (лиственный лес)": ("deciduous forest",),
    "arable land (пашня)": ("ploughed field", "crop", "stubble"),
    "meadow with haystacks (луг со стогами)": ("meadow", "mown meadow", "wet meadow", "haystack"),
    "railway (железная дорога)": ("railway",), "asphalt road (асфальтовая дорога)": ("asphalt road",),
    "gravel road (гравийная дорога)": ("gravel road",),
}


def _candidates(isite) -> dict:
    f = isite.features
    out = {k: list(v) for k, v in _CANDIDATES.items()}
    out["low bog (низинное болото)"] = [(x, float(cv._river_y(x)) - 75.0) for x in (1230.0, 1330.0, 1420.0)]
    st = f["haystacks"]
    out["meadow with haystacks (луг со стогами)"] = [(float(x) + 12.0, float(y)) for x, y in st[[0, 4, 8], :2]]
    for key, name in (("railway (железная дорога)", "railway"), ("asphalt road (асфальтовая дорога)", "asphalt"),
                      ("gravel road (гравийная дорога)", "gravel")):
        line = f[name]
        out[key] = [tuple(map(float, line[int(k * (len(line) - 1))])) for k in (0.2, 0.35, 0.5, 0.65)]
    return out


@dataclass(frozen=True)
class LabSetup:
    """One variant's photo: where and how it is taken (no truth here; see :func:`truth`)."""

    i: int
    m: float
    X_m: float
    Y_m: float
    kappa_deg: float
    alpha_deg: float
    lambda_deg: float
    conditions: ip.Conditions

    @property
    def camera(self) -> g.Camera:
        return g.Camera(F_MM, 180.0)

    def pose(self, isite) -> g.Pose:
        H = g.flying_height_m(F_MM, self.m)
        return g.Pose(self.X_m, self.Y_m, isite.site.mean_height_m + H, self.alpha_deg, self.lambda_deg,
                      self.kappa_deg)


def setup_for(i: int) -> LabSetup:
    i = check_int_range("i", i, 0, 10**6)
    rng = np.random.default_rng([int(i), 808])
    cond = ip.Conditions(season="summer", sun_elevation_deg=float(rng.uniform(35, 60)),
                         sun_azimuth_deg=float(rng.uniform(110, 220)), visibility_km=float(rng.uniform(20, 50)),
                         moisture_pct=float(rng.uniform(0, 8)), speed_kmh=float(rng.uniform(180, 300)),
                         exposure_ms=float(rng.uniform(1.0, 2.5)))
    return LabSetup(i=int(i), m=float(8000 + 100 * rng.integers(0, 16)), X_m=float(800 + rng.uniform(-50, 50)),
                    Y_m=float(800 + rng.uniform(-50, 50)), kappa_deg=90.0 * int(rng.integers(0, 4)),
                    alpha_deg=float(rng.uniform(0, 1.5)), lambda_deg=float(rng.uniform(-180, 180)), conditions=cond)


def lab_setup(v) -> LabSetup:
    """The variant's photo set-up (its crop and conditions)."""
    return setup_for(int(v.i))


#: the worked example's set-up number (not a student's variant: those are 0…99)
EXAMPLE_I = 2014


def example_setup() -> LabSetup:
    """The chapter's worked example: a photo set up like a variant's, but no student's."""
    return setup_for(EXAMPLE_I)


#: why each object is what it is (table 10's keys, in our words)
REASONS = {
    "river (река)": "a long winding band of dark water with light shallow margins",
    "lake (озеро)": "closed shoreline, dark deep water inside a light shallow rim",
    "pond (пруд)": "water on a brook, widest at a straight bank across the valley: the dam",
    "raised bog (верховое болото)": "on the watershed, far from streams; mottled tone, small bog lakes",
    "low bog (низинное болото)": "a ribbon along the river's valley floor, shrub thick at its edges",
    "deciduous forest (лиственный лес)": "lighter than the conifers; coarse grain of broad soft crowns",
    "arable land (пашня)": "straight boundaries, even tone, furrows",
    "meadow with haystacks (луг со стогами)": "even grass tone with small bright heaps casting shadows",
    "railway (железная дорога)": "even width; long straights joined by a curve of large radius",
    "asphalt road (асфальтовая дорога)": "dark, winding in tight curves, edged by ditches",
    "gravel road (гравийная дорога)": "light, narrow, edged by ditches",
    "pine forest (сосновый лес)": "even grey tone; convex crowns of one height",
    "spruce forest (еловый лес)": "darker and mottled; pointed crowns of uneven height, long thin shadows",
}


def example_photo() -> LabPhoto:
    """The worked example's photo and marks (:data:`EXAMPLE_I`)."""
    return _lab_photo(EXAMPLE_I)


def example_key() -> pd.DataFrame:
    """The worked example interpreted: every mark, its name and the key that tells it."""
    t = truth(EXAMPLE_I)
    rows = [(str(k + 1), name, REASONS[name]) for k, (name, _, _) in enumerate(t["objects"])]
    rows += [(lab, name, REASONS[name]) for lab, (name, _, _) in zip(STAND_OPTIONS, t["stands"])]
    rows.append(("river", f"flows {t['flow']}", "the islands narrow downstream; the tributary meets it at an acute "
                 "angle pointing downstream"))
    return pd.DataFrame(rows, columns=["mark", "object", "key (table 10)"]).set_index("mark")


@functools.lru_cache(maxsize=8)
def truth(i: int) -> dict:
    """The answer key of variant i: the marks' ground points and names, the flow, the stands, the width."""
    su = setup_for(i)
    isite = cv.interpretation_site(0)
    cam, pose = su.camera, su.pose(isite)
    rng = np.random.default_rng([int(i), 809])
    lim = cam.half_mm - 5.0

    def on_photo(P):
        Z = isite.site.height(P[0], P[1])
        xy = g.ground_to_photo(cam, pose, np.array([P[0], P[1], float(Z)]))
        return xy if np.all(np.abs(xy) < lim) else None

    cands = _candidates(isite)
    pool = [k for k in OBJECT_NAMES if k not in ("pine forest (сосновый лес)", "spruce forest (еловый лес)")]
    names = [str(x) for x in rng.permutation(pool)]
    chosen = []
    # pine and spruce are marked as stands P and Q for task 08.2; task 08.1 draws from the rest
    for name in names:
        pts = [p for p in cands[name] if on_photo(p) is not None
               and cv.CLASSES[isite.class_at(*p) - 1] in _CLASS_OF[name]]
        if pts:
            p = pts[int(rng.integers(0, len(pts)))]
            chosen.append((name, p, on_photo(p)))
        if len(chosen) == N_OBJECTS:
            break
    stands = []
    for name in ("pine forest (сосновый лес)", "spruce forest (еловый лес)"):
        pts = [p for p in cands[name] if on_photo(p) is not None]
        p = pts[int(rng.integers(0, len(pts)))]
        stands.append((name, p, on_photo(p)))
    if rng.random() < 0.5:
        stands.reverse()
    # the river's flow: from where it enters the photo to where it leaves
    river = isite.features["river"]
    xy = np.array([g.ground_to_photo(cam, pose, np.array([x, y, float(isite.site.height(x, y))])) for x, y in river])
    inside = np.flatnonzero(np.all(np.abs(xy) < cam.half_mm, axis=1))
    d = xy[inside[-1]] - xy[inside[0]]
    if abs(d[0]) >= abs(d[1]):
        flow = FLOW_OPTIONS[0] if d[0] > 0 else FLOW_OPTIONS[1]
    else:
        flow = FLOW_OPTIONS[2] if d[1] > 0 else FLOW_OPTIONS[3]
    # the width section: a stretch away from the islands, across the centre line
    x_sec = float(rng.choice([300.0, 850.0, 900.0, 1500.0]))  # clear of the islands, the tributary, the bridge
    for x_try in (x_sec, 300.0, 850.0, 900.0, 1500.0):
        y0 = float(cv._river_y(x_try))
        t = np.array([1.0, float(np.gradient(cv._river_y(np.array([x_try - 1, x_try, x_try + 1])))[1])])
        t /= np.hypot(*t)
        nrm = np.array([-t[1], t[0]])
        w = float(np.interp(x_try, river[:, 0], isite.features["river_width_m"]))
        A = np.array([x_try, y0]) + nrm * w / 2
        B = np.array([x_try, y0]) - nrm * w / 2
        a, b = on_photo(A), on_photo(B)
        if a is not None and b is not None:
            break
    return {"objects": chosen, "stands": stands, "flow": flow, "width_m": w, "A": a, "B": b,
            "spruce": STAND_OPTIONS[[s[0] for s in stands].index("spruce forest (еловый лес)")]}


@dataclass(frozen=True, eq=False)
class LabPhoto:
    """What the student works from: the photo and the marks read on it (no truth).

    Attributes
    ----------
    bands : ndarray (n, n, 6) float32
        The photo in the six bands (apparent reflectance), :data:`aerophoto.spectral.BAND_NAMES`.
    pixel_mm : float
        Pixel size, mm; the photo spans ±90 mm.
    m : float
        The photo's scale denominator (1:m, for the mean ground).
    marks : DataFrame
        The numbered marks 1…6, the stands P and Q, and the bank points A and B: photo x, y, mm (read to 0.05 mm).
    options : tuple of str
        The names to choose from (:data:`OBJECT_NAMES`).
    """

    bands: np.ndarray
    pixel_mm: float
    m: float
    marks: pd.DataFrame
    options: tuple = OBJECT_NAMES

    def __repr__(self) -> str:
        n = self.bands.shape[0]
        return f"LabPhoto({n}×{n} px in 6 bands, p = {self.pixel_mm:.4g} mm, 1:{self.m:.0f}, marks {list(self.marks.index)})"

    def composite(self, camera: str = "colour film") -> np.ndarray:
        from ..site.colour import to_display
        from .. import spectral as sp

        if camera not in sp.CAMERAS:
            raise ValueError(f"camera = {camera!r} is not one of {list(sp.CAMERAS)}")
        return to_display(self.bands[..., [sp.BAND_NAMES.index(b) for b in sp.CAMERAS[camera]]], camera)

    @property
    def extent_mm(self) -> tuple:
        h = self.bands.shape[0] * self.pixel_mm / 2.0
        return (-h, h, -h, h)

    def marks_table(self) -> pd.DataFrame:
        return self.marks.copy()


@functools.lru_cache(maxsize=4)
def _lab_photo(i: int) -> LabPhoto:
    from ..site.colour import render_colour

    su = setup_for(i)
    isite = cv.interpretation_site(0)
    cp = render_colour(isite, su.camera, su.pose(isite), N_PX, su.conditions)
    tr = truth(i)
    rows = [(str(k + 1), *xy) for k, (_, _, xy) in enumerate(tr["objects"])]
    rows += [(lab, *xy) for lab, (_, _, xy) in zip(STAND_OPTIONS, tr["stands"])]
    rows += [("A", *tr["A"]), ("B", *tr["B"])]
    marks = pd.DataFrame([(r[0], round(r[1] / 0.05) * 0.05, round(r[2] / 0.05) * 0.05) for r in rows],
                         columns=["mark", "x, mm", "y, mm"]).set_index("mark")
    bands = cp.bands
    bands.flags.writeable = False
    return LabPhoto(bands=bands, pixel_mm=cp.photo.pixel_mm, m=su.m, marks=marks)


def lab_photo(v) -> LabPhoto:
    """The student's photo (rendered once per variant, about 1 s)."""
    return _lab_photo(int(v.i))


@functools.lru_cache(maxsize=48)
def _window(i: int, window: tuple, n_px: int):
    from ..site.colour import render_colour

    su = setup_for(i)
    isite = cv.interpretation_site(0)
    return render_colour(isite, su.camera, su.pose(isite), n_px, su.conditions, window_mm=window)


def photo_window(i: int, x_mm: float, y_mm: float, side_mm: float, n_px: int = LOUPE_PX):
    """A square of variant ``i``'s photo (or the worked example's, :data:`EXAMPLE_I`) seen through a magnifier.

    The same photo as :func:`lab_photo` — the same rays, light, air and image motion — rendered over the square
    centred at photo (x, y) mm with side ``side_mm`` (1…180 mm, inside the frame) at ``n_px`` pixels across
    (16…1024), so that finer detail than the photo's own 1024 pixels shows: crowns, rows, wheel tracks, rails.
    Returns a :class:`aerophoto.site.colour.ColourPhoto` (its ``photo.extent_mm`` is the square).  Cached.
    """
    i = check_int_range("i", i, 0, 10**6)
    side = check_range("side_mm", side_mm, 1.0, 180.0, unit="mm")
    lim = 90.0 - side / 2.0
    x = check_range("x_mm", x_mm, -lim, lim, unit="mm")
    y = check_range("y_mm", y_mm, -lim, lim, unit="mm")
    n = check_int_range("n_px", n_px, 16, 1024)
    return _window(int(i), (round(x, 6), round(y, 6), round(side, 6)), int(n))
