"""Chapter 07's lab (guide §8): the student's own stereo pair, what is measured on it, its pictures and height model.

Each variant flies its own pair over the virtual site (:func:`stereo_lab`):
two photos with the variant's camera f and scale 1:m, p_x = 60 %, centred on
the site, with the small departures of a real flight seeded by i (tilts up to
0.7°, crab jitter ±1°, base jitter ±2 %; both stations at one height).  The
student works from what a photogrammetrist measures on such a pair
(:class:`StereoLab`):

* the principal points transferred to the neighbour photo (pricked by eye,
  σ = 0.02 mm, read to 0.01 mm) — the photo base;
* on the pair normalised along its base (the parallax bar's setting), the
  coordinates of a control point A of known height and of four objects of the
  site — a roof corner, a tree top, the chimney top, the mast top — with a
  ground point beside each (read to 0.01 mm, σ = 0.007 mm a coordinate);
* the air base B of the navigation record (to 0.1 m).

The truth comes from geometry (the objects' points projected through the
true orientations), never from image analysis.  :func:`lab_images` renders and
normalises the pair; :func:`height_model` matches it by correlation and holds
the heights against the truth.  :func:`example_lab` is the guide's example
(variant 00's camera and scale, its own seed) that the chapter's live demo
opens on.  The graded tasks are :mod:`aerophoto.tasks.ch07`.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from .. import geometry as g
from .. import simulate as sim
from .. import stereo as st
from .._validate import check_int_range, check_positive

__all__ = ["SIGMA_READ_MM", "SIGMA_PRICK_MM", "OBJECT_LABELS", "EXAMPLE_SEED", "PX_PERCENT", "StereoLab", "lab_for",
           "stereo_lab", "example_lab", "PairImages", "SUN", "PAIR_PX", "lab_images", "HM_CLASSES", "HeightModel",
           "height_model"]

#: reading error of one coordinate on the normalised pair, mm (a parallax bar reads parallaxes to ~0.01 mm)
SIGMA_READ_MM = 0.007
#: error of transferring a principal point to the neighbour photo by eye, mm
SIGMA_PRICK_MM = 0.02
#: the four objects of task 07.2, in order
OBJECT_LABELS = ("A: roof corner", "B: tree top", "C: chimney top", "D: mast top")
#: the seed of the guide's example pair (the live demo's)
EXAMPLE_SEED = 2014
PX_PERCENT = 60.0


def _imperfections(seed: int) -> sim.Imperfections:
    return sim.Imperfections(max_tilt_deg=0.7, max_crab_jitter_deg=1.0, max_base_percent=2.0, seed=int(seed))


@dataclass(frozen=True, eq=False)
class StereoLab:
    """One stereo pair with everything measured on it (see the module notes).

    Attributes
    ----------
    camera : Camera
    m : float
        The scale denominator the pair was planned for (H = f·m above the site's mean height).
    left, right : :class:`aerophoto.simulate.Shot`
        The two exposures (true orientations).
    R_n : ndarray (3, 3)
        The normalised orientation (:func:`aerophoto.stereo.normal_rotation`).
    B_m : float
        The true air base |S₁S₂|, m.
    B_record_m : float
        The air base of the navigation record (B to 0.1 m) — what the student gets.
    p0_mm : float
        Parallax of the site's mean ground on the normalised pair, mm (the anaglyph's zero).
    window_mm : tuple
        (x0, x1, y0, y1): the overlap on the left normalised photo, mm.
    principal : DataFrame
        The transferred principal points (measured): ``x, mm``, ``y, mm``.
    control : Series
        Control point A: ``x left``, ``y left``, ``x right``, ``y right`` (mm, measured) and ``Z, m``.
    points : DataFrame
        The objects' tops and feet: ``object``, ``point`` (top/foot), measured normalised coordinates, and
        the truth (``X, m``, ``Y, m``, ``Z, m`` — the instructor's side).
    """

    camera: g.Camera
    m: float
    left: sim.Shot
    right: sim.Shot
    R_n: np.ndarray
    B_m: float
    B_record_m: float
    p0_mm: float
    window_mm: tuple
    principal: pd.DataFrame
    control: pd.Series
    seed: int
    _measure_objects: object = field(default=None, repr=False)

    @functools.cached_property
    def points(self) -> pd.DataFrame:
        """The objects' tops and feet (see the class notes), measured on first use: finding four objects with a
        visible foot is most of a lab's cost, and task 07.1 (and the search for another variant's answer) needs
        the principal points and A only.  The same numbers as measuring them at once (the readings' noise is
        drawn in the same order)."""
        return self._measure_objects()

    # ---- geometry
    @property
    def f_mm(self) -> float:
        return self.camera.f_mm

    @property
    def Z_S_m(self) -> float:
        """Height of the projection centres (both stations fly at one height), m."""
        return self.left.pose.Z_m

    @property
    def H_m(self) -> float:
        """The planned flying height H = f·m, m (over the site's mean height)."""
        return g.flying_height_m(self.camera.f_mm, self.m)

    def normal_xy(self, XYZ_m) -> tuple:
        """Exact coordinates (…, 2) of ground points on the left and right normalised photos, mm."""
        P = np.asarray(XYZ_m, float)
        xl = st.to_normal(self.camera, self.left.pose, self.R_n, g.ground_to_photo(self.camera, self.left.pose, P))
        xr = st.to_normal(self.camera, self.right.pose, self.R_n, g.ground_to_photo(self.camera, self.right.pose, P))
        return xl, xr

    def model_to_ground(self, xy_left_mm, p_mm) -> np.ndarray:
        """Ground points (…, 3) of normalised left coordinates and x-parallaxes (the parallax equations), m."""
        xy = np.asarray(xy_left_mm, float)
        M = st.model_point(xy[..., 0], xy[..., 1], p_mm, self.B_m, self.camera.f_mm)
        return self.left.pose.centre + M @ self.R_n.T

    # ---- what the student reads
    def base_table(self) -> pd.DataFrame:
        """The principal points as pricked on the neighbour photos (mm, on the original photos)."""
        return self.principal.copy()

    def control_table(self) -> pd.DataFrame:
        """Control point A on the normalised pair (mm) and its height (m), and the air base of the record."""
        c = self.control
        return pd.DataFrame({"x left, mm": [c["x left"]], "y left, mm": [c["y left"]], "x right, mm": [c["x right"]],
                             "y right, mm": [c["y right"]], "Z, m": [c["Z, m"]]},
                            index=pd.Index(["A (control)"], name="point"))

    def objects_table(self) -> pd.DataFrame:
        """The four objects' tops and feet on the normalised pair, as measured (mm)."""
        cols = ["x left, mm", "y left, mm", "x right, mm", "y right, mm"]
        df = self.points.set_index(["object", "point"])[cols]
        return df

    def measured(self, obj: str, point: str) -> np.ndarray:
        """(x_l, y_l, x_r, y_r) of one measured point, mm."""
        r = self.points[(self.points["object"] == obj) & (self.points["point"] == point)].iloc[0]
        return r[["x left, mm", "y left, mm", "x right, mm", "y right, mm"]].to_numpy(float)

    # ---- the reference solution
    def photo_bases_mm(self) -> tuple:
        """(b₁, b₂): the transferred principal points' distances from o on each photo, mm."""
        P = self.principal
        b1 = math.hypot(P.loc["o₂ on the left photo", "x, mm"], P.loc["o₂ on the left photo", "y, mm"])
        b2 = math.hypot(P.loc["o₁ on the right photo", "x, mm"], P.loc["o₁ on the right photo", "y, mm"])
        return b1, b2

    @property
    def b_mm(self) -> float:
        """The photo base b = (b₁ + b₂)/2 from the pricked principal points, mm."""
        return float(np.mean(self.photo_bases_mm()))

    @property
    def b_flat_mm(self) -> float:
        """The base of the normalised pair, b₀ = B·f/H (the record's B, H = f·m): the parallax of a point on the
        mean plane, mm.  The pricked principal points (:attr:`b_mm`) carry the tilts' displacements as well —
        about f·tan α, 2.9 % at f = 730 mm with tilts of half a degree — so heights go with b₀ (task 07.3)."""
        return float(self.B_record_m * self.f_mm / self.H_m)

    @property
    def pA_mm(self) -> float:
        return float(self.control["x left"] - self.control["x right"])

    @property
    def ZS_from_A_m(self) -> float:
        """Z_S = Z_A + B·f/p_A (from the measured parallax and the record's B), m."""
        return float(st.flying_height_from_point(self.B_record_m, self.f_mm, self.pA_mm, float(self.control["Z, m"])))

    def parallaxes(self) -> pd.DataFrame:
        """Per object: p of the foot and the top, Δp, H over the foot and Δh, from the measured coordinates."""
        rows = []
        for name in OBJECT_LABELS:
            foot, top = self.measured(name, "foot"), self.measured(name, "top")
            pf, pt = foot[0] - foot[2], top[0] - top[2]
            Hf = self.B_record_m * self.f_mm / pf
            rows.append((name, pf, pt, pt - pf, Hf, float(st.height_difference_m(pt - pf, pf, Hf))))
        return pd.DataFrame(rows, columns=["object", "p foot, mm", "p top, mm", "Δp, mm", "H over the foot, m",
                                           "Δh, m"]).set_index("object")

    def truth(self) -> pd.DataFrame:
        """The objects' true heights (top above its foot point), m — the instructor's side."""
        t = self.points.pivot(index="object", columns="point", values="Z, m").loc[list(OBJECT_LABELS)]
        return pd.DataFrame({"true Δh, m": t["top"] - t["foot"]})


# =========================================================================== building a lab
def _visible_in_both(site, cam, poses, P, tol=0.3) -> np.ndarray:
    """Which points (n, 3) both photos see: inside each frame (2 mm from its edge) and nothing on the ray before them.

    A point is seen when the ray's first hit is no nearer the station than the point less ``tol`` (m).  Asking
    instead whether the hit lies *at* the point fails on the points the objects are measured at — a roof corner,
    a chimney or mast top are on the edge of their object, and a ray through such a point grazes it: whether
    it hits the corner or slips past to the ground behind is decided in the last bit of the arithmetic, which
    differs between machines (BLAS kernels), and one flip re-drew a whole variant's objects.
    """
    from ..render import trace

    ok = np.ones(len(P), bool)
    for pose in poses:
        xy = g.ground_to_photo(cam, pose, P)
        inside = np.all(np.abs(xy) < cam.half_mm - 2.0, axis=1)
        seen = np.zeros(len(P), bool)
        if inside.any():
            S = pose.centre
            hit = trace(site, cam, pose, xy[inside]).XYZ_m
            seen[inside] = np.linalg.norm(hit - S, axis=1) >= np.linalg.norm(P[inside] - S, axis=1) - tol
        ok &= seen
    return ok


def _window(cam, poses, R_n, p0) -> tuple:
    """The overlap on the left normalised photo: the rectangle inside both normalised frames, less 3 mm."""
    corners = cam.corners_mm()
    L = st.to_normal(cam, poses[0], R_n, corners)
    R = st.to_normal(cam, poses[1], R_n, corners) + np.array([p0, 0.0])
    x0 = max(L[[0, 3], 0].max(), R[[0, 3], 0].max()) + 3.0
    x1 = min(L[[1, 2], 0].min(), R[[1, 2], 0].min()) - 3.0
    y0 = max(L[[0, 1], 1].max(), R[[0, 1], 1].max()) + 3.0
    y1 = min(L[[2, 3], 1].min(), R[[2, 3], 1].min()) - 3.0
    return (float(x0), float(x1), float(y0), float(y1))


def _in_window(xy, w, margin=2.0):
    return (xy[:, 0] > w[0] + margin) & (xy[:, 0] < w[1] - margin) & (xy[:, 1] > w[2] + margin) & \
        (xy[:, 1] < w[3] - margin)


def lab_for(f_mm: float, m: float, seed: int) -> StereoLab:
    """The pair flown with focal length f, scale 1:m and the departures of ``seed``, and what is measured on it."""
    check_positive("f_mm", f_mm, unit="mm", hi=2000.0)
    check_positive("m", m, hi=1e6)
    seed = check_int_range("seed", seed, 0, 2**32 - 1)
    from ..render import trace
    from ..site import get_site

    site = get_site()
    cam = g.Camera(f_mm)
    strip = sim.strip_over_site(site, cam, m, PX_PERCENT, 2, imperfections=_imperfections(seed))
    left, right = strip.shots
    poses = (left.pose, right.pose)
    R_n = st.normal_rotation(*poses)
    B = float(np.linalg.norm(right.pose.centre - left.pose.centre))
    p0 = B * f_mm / (left.pose.Z_m - site.mean_height_m)
    w = _window(cam, poses, R_n, p0)
    rng = np.random.default_rng([int(seed), 8])

    def rd(x):
        return np.round(np.asarray(x, float), 2) + 0.0

    # the principal points, transferred through the surface they show
    o = np.zeros((1, 2))
    G1 = trace(site, cam, left.pose, o).XYZ_m
    G2 = trace(site, cam, right.pose, o).XYZ_m
    o1r = g.ground_to_photo(cam, right.pose, G1)[0] + rng.normal(0.0, SIGMA_PRICK_MM, 2)
    o2l = g.ground_to_photo(cam, left.pose, G2)[0] + rng.normal(0.0, SIGMA_PRICK_MM, 2)
    principal = pd.DataFrame({"x, mm": rd([o2l[0], o1r[0]]), "y, mm": rd([o2l[1], o1r[1]])},
                             index=pd.Index(["o₂ on the left photo", "o₁ on the right photo"], name="point"))

    def normal(P):
        xl = st.to_normal(cam, left.pose, R_n, g.ground_to_photo(cam, left.pose, P))
        xr = st.to_normal(cam, right.pose, R_n, g.ground_to_photo(cam, right.pose, P))
        return xl, xr

    def read(P):
        xl, xr = normal(np.atleast_2d(P))
        noise = rng.normal(0.0, SIGMA_READ_MM, (len(xl), 4))
        return rd(np.column_stack([xl, xr]) + noise)

    # control point A: a control point in the overlap, seen on both photos, near its middle
    cat = site.catalogue
    ctl = cat[cat["control"]]
    P = ctl[["X_m", "Y_m", "Z_m"]].to_numpy(float)
    xl, _ = normal(P)
    ok = _in_window(xl, w, 8.0)
    ok[ok] = _visible_in_both(site, cam, poses, P[ok])  # only the points in the overlap: fewer rays
    if not ok.any():  # pragma: no cover - the site's control lattice always reaches the overlap
        raise RuntimeError("no control point in the pair's overlap")
    mid = np.array([(w[0] + w[1]) / 2, (w[2] + w[3]) / 2])
    near = np.flatnonzero(ok)[np.argsort(np.hypot(*(xl[ok] - mid).T))][:3]
    a = int(rng.choice(near))
    A = read(P[a])[0]
    control = pd.Series({"x left": A[0], "y left": A[1], "x right": A[2], "y right": A[3], "Z, m": round(P[a, 2], 2),
                         "id": int(ctl["id"].iloc[a])})
    return StereoLab(cam, float(m), left, right, R_n, B, round(B, 1), float(p0), w, principal, control, int(seed),
                     functools.partial(_measure_objects, site, cam, poses, normal, rng, w))


def _object_feet(site, objs, kind, top, k) -> np.ndarray:
    """Candidate ground points beside an object's top (24: eight directions × three distances), in search order."""
    c = objs.centre_m[k]
    away = top[:2] - c if np.hypot(*(top[:2] - c)) > 0.5 else np.array([1.0, 0.0])
    away = away / np.hypot(*away)
    reach = 3.0 if kind == "roof corner" else (objs.ell_radii[k - objs.n_polyhedra, 0] + 1.5
                                              if kind == "tree top" else 4.0)
    feet = []
    for ang in np.radians([0, 45, -45, 90, -90, 135, -135, 180]):
        ca, sa = math.cos(ang), math.sin(ang)
        d = np.array([ca * away[0] - sa * away[1], sa * away[0] + ca * away[1]])
        for r in (reach, reach + 2.0, reach + 4.0):
            q = top[:2] + r * d
            feet.append([q[0], q[1], float(site.height(q[0], q[1]))])
    return np.array(feet)


def _measure_objects(site, cam, poses, normal, rng, w) -> pd.DataFrame:
    """The four objects of :data:`OBJECT_LABELS` and a ground point beside each, seen on both photos, measured.

    Per kind: the tops inside the overlap and seen by both photos, in an order drawn from ``rng``; the first whose
    foot search (:func:`_object_feet`, the first foot seen by both) succeeds.  The random draws do not depend on
    what the rays hit, so they are drawn first (per kind: the order, then the top's and the foot's reading
    noise, as :func:`lab_for` reads a point), and the ray casts are batched: every kind's tops in one, every
    kind's first candidate's feet in one (a later candidate only where the first has no visible foot).
    """
    objs = site.objects
    pts = site.object_points
    kinds = ("roof corner", "tree top", "chimney top", "mast top")
    tops = [pts[pts["kind"] == kind] for kind in kinds]
    T_all = [c[["X_m", "Y_m", "Z_m"]].to_numpy(float) for c in tops]
    inside = [_in_window(normal(T)[0], w, 4.0) for T in T_all]
    seen = _visible_in_both(site, cam, poses, np.concatenate([T[i] for T, i in zip(T_all, inside)]))
    orders, noise, at = [], [], 0
    for kind, T, i in zip(kinds, T_all, inside):
        ok = np.zeros(len(T), bool)
        ok[np.flatnonzero(i)] = seen[at:at + int(i.sum())]
        at += int(i.sum())
        good = np.flatnonzero(ok)
        if not len(good):
            raise RuntimeError(f"no {kind} in the overlap of the pair f = {cam.f_mm:g} mm")
        orders.append(list(rng.permutation(good)))
        noise.append([rng.normal(0.0, SIGMA_READ_MM, (1, 4)) for _part in ("top", "foot")])
    found: list = [None] * len(kinds)
    tried = [0] * len(kinds)
    while any(f is None for f in found):
        todo = [q for q in range(len(kinds)) if found[q] is None]
        for q in todo:
            if tried[q] >= len(orders[q]):  # pragma: no cover - every kind has a top with a visible foot
                raise RuntimeError(f"no {kinds[q]} with a visible foot in the pair f = {cam.f_mm:g} mm")
        cands = [(q, orders[q][tried[q]]) for q in todo]
        feet = [_object_feet(site, objs, kinds[q], T_all[q][j], int(tops[q]["object"].iloc[j])) for q, j in cands]
        F = np.concatenate(feet)
        vis = _in_window(normal(F)[0], w, 2.0)
        vis[vis] = _visible_in_both(site, cam, poses, F[vis])
        for (q, j), part in zip(cands, np.split(vis, np.cumsum([len(f) for f in feet])[:-1])):
            ok = np.flatnonzero(part)
            if len(ok):
                found[q] = (T_all[q][j], feet[cands.index((q, j))][ok[0]])
            else:
                tried[q] += 1
    rows = []
    for label, (top, foot), nz in zip(OBJECT_LABELS, found, noise):
        for part, Q, e in (("top", top, nz[0]), ("foot", foot, nz[1])):
            xl, xr = normal(np.atleast_2d(Q))
            r = (np.round(np.column_stack([xl, xr]) + e, 2) + 0.0)[0]
            rows.append({"object": label, "point": part, "x left, mm": r[0], "y left, mm": r[1], "x right, mm": r[2],
                         "y right, mm": r[3], "X, m": Q[0], "Y, m": Q[1], "Z, m": Q[2]})
    return pd.DataFrame(rows)


@functools.lru_cache(maxsize=128)
def _lab(f_mm: float, m: float, seed: int) -> StereoLab:
    return lab_for(f_mm, m, seed)


def stereo_lab(v) -> StereoLab:
    """The student's pair for variant ``v`` (its f, m and i)."""
    return _lab(float(v.f_mm), float(v.m), 700 + int(v.i))


def example_lab() -> StereoLab:
    """The guide's example: f = 100 mm, 1:12 000, p_x = 60 %, flown with the demo's own seed."""
    return _lab(100.0, 12000.0, EXAMPLE_SEED)


# =========================================================================== the pair's pictures
@dataclass(frozen=True, eq=False)
class PairImages:
    """The rendered pair and its normalised pieces over the overlap (left window; right shifted by p₀).

    ``photos`` are the two rendered :class:`aerophoto.render.Photo` up to 1024 pixels a side (with every pixel's
    surface point: the height model's truth); above that it is empty — only the normalised pieces are kept (the
    photos of a 1536-pixel pair would hold 50 MB more) and they come from the disk cache (:func:`lab_images`).
    """

    lab: StereoLab
    photos: tuple
    left: st.NormalImage
    right: st.NormalImage

    @property
    def p0_mm(self) -> float:
        return self.lab.p0_mm

    def anaglyph(self, reverse: bool = False) -> np.ndarray:
        """The red–cyan anaglyph of the overlap (``reverse``: the photos swapped, the reverse stereo effect)."""
        a, b = (self.right.image, self.left.image) if reverse else (self.left.image, self.right.image)
        return st.anaglyph(a, b)


#: the sun of the pair's photos (the site texture's light: south-west, 40° high)
SUN = (225.0, 40.0)
#: the pixels a side of the pair the chapter shows, measures on and prints (0.15 mm, 1.8 m on the ground at
#: 1:12 000): one rendering per pair serves the floating mark, the figures and the prints
PAIR_PX = 1536
#: above this size the photos' surface points are not kept and the pair is cached on disk
KEEP_GROUND_PX = 1024


def _render_pair(lab: StereoLab, n_px: int, keep_ground: bool) -> tuple:
    from ..render import Sun, render_shot
    from ..site import get_site

    site = get_site()
    photos = tuple(render_shot(site, s, n_px, vignetting=0.0, fiducials=False, sun=Sun(*SUN),
                               keep_ground=keep_ground) for s in (lab.left, lab.right))
    px = lab.camera.frame_mm / n_px
    x0, x1, y0, y1 = lab.window_mm
    L = st.normalise_image(photos[0].image, lab.camera, lab.left.pose, lab.R_n, (x0, x1, y0, y1), px)
    R = st.normalise_image(photos[1].image, lab.camera, lab.right.pose, lab.R_n,
                           (x0 - lab.p0_mm, x1 - lab.p0_mm, y0, y1), px)
    return photos, L, R


@functools.lru_cache(maxsize=3)
def _images(f_mm: float, m: float, seed: int, n_px: int) -> PairImages:
    from .. import cache

    lab = _lab(f_mm, m, seed)
    if n_px <= KEEP_GROUND_PX:
        return PairImages(lab, *_render_pair(lab, n_px, keep_ground=True))
    # the same for everyone who asks for this pair (the guide's example: every student): rendered once on the
    # machine, then read from the user's disk cache (aerophoto.cache — verified, keyed by the code and inputs)
    inputs = {"f_mm": f_mm, "m": m, "seed": seed, "n_px": n_px, "sun": list(SUN)}
    L, R = cache.load_or_build("stereo-pair", inputs, lambda: _render_pair(lab, n_px, keep_ground=False)[1:],
                               types=(st.NormalImage,))
    return PairImages(lab, (), L, R)


def lab_images(lab: StereoLab, n_px: int = PAIR_PX) -> PairImages:
    """Render the lab's pair (``n_px`` a side, cached; sun in the south-west, 40° high) and normalise the overlap.

    Up to 1024 pixels the photos keep every pixel's surface point (``ground_m``, for the height model); larger
    pairs keep the normalised pieces only and are cached on disk (:mod:`aerophoto.cache`).
    """
    return _images(lab.camera.f_mm, lab.m, lab.seed, int(n_px))


# =========================================================================== the height model by correlation
#: classes of the overlap for the height model's table: name → test on (surface code, land cover code)
HM_CLASSES = ("fields and meadows", "roads, sand banks", "water", "forest canopy", "houses, trees, structures")


@dataclass(frozen=True, eq=False)
class HeightModel:
    """A coarse height model of the pair's overlap by correlation, against the truth.

    Attributes
    ----------
    lab : StereoLab
        The pair it was matched on, rendered at ``n_px`` (:attr:`images`).
    n_px : int
    extent_mm : tuple
        (left, right, bottom, top) of the maps on the left normalised photo, mm.
    match : :class:`aerophoto.stereo.DenseParallax`
    p_mm, Z_m : ndarray (rows, cols)
        Parallax of each left pixel and the height it gives (parallax equations), NaN where unmatched.
    Z_true_m : ndarray
        Height of the surface point the left photo shows there.
    klass : ndarray of int
        Index into :data:`HM_CLASSES`.
    shadow, occluded : ndarray of bool
        In a cast shadow; hidden from the right photo (seen by the left only).
    """

    lab: StereoLab
    n_px: int
    extent_mm: tuple
    match: st.DenseParallax
    p_mm: np.ndarray
    Z_m: np.ndarray
    Z_true_m: np.ndarray
    klass: np.ndarray
    shadow: np.ndarray
    occluded: np.ndarray

    @property
    def images(self) -> PairImages:
        """The rendered pair it was matched on (:func:`lab_images`; rendered again if it is not in memory)."""
        return lab_images(self.lab, self.n_px)

    @property
    def error_m(self) -> np.ndarray:
        return self.Z_m - self.Z_true_m

    @property
    def reliable(self) -> np.ndarray:
        return self.match.reliable()

    def rms_m(self, mask=None) -> float:
        """RMS of the height error over reliable pixels (and ``mask``), m."""
        sel = self.reliable & np.isfinite(self.Z_true_m)
        if mask is not None:
            sel &= mask
        e = self.error_m[sel]
        return float(np.sqrt(np.mean(e**2))) if e.size else float("nan")

    @property
    def textured_ground(self) -> np.ndarray:
        """Fields and meadows in the sun, seen by both photos: where correlation should work."""
        return (self.klass == 0) & ~self.shadow & ~self.occluded

    def table(self) -> pd.DataFrame:
        """Per class of the overlap: its share, the share matched reliably, their RMS error and the gross errors."""
        rows = []
        fin = np.isfinite(self.Z_true_m)
        groups = [(name, (self.klass == k) & fin) for k, name in enumerate(HM_CLASSES)]
        groups += [("in cast shadows", self.shadow & fin), ("hidden from the right photo", self.occluded & fin),
                   ("textured ground (fields in the sun, seen twice)", self.textured_ground & fin)]
        n = fin.sum()
        for name, sel in groups:
            rel = sel & self.reliable
            e = self.error_m[rel]
            rows.append((name, 100.0 * sel.sum() / n, 100.0 * rel.sum() / max(sel.sum(), 1),
                         float(np.sqrt(np.mean(e**2))) if e.size else np.nan,
                         100.0 * float(np.mean(np.abs(e) > 5.0)) if e.size else np.nan))
        return pd.DataFrame(rows, columns=["part of the overlap", "share, %", "matched, %", "RMS error, m",
                                           "errors > 5 m, %"]).set_index("part of the overlap")


#: the arrays of a :class:`HeightModel` (what the disk cache keeps of it)
_HM_ARRAYS = ("p_mm", "Z_m", "Z_true_m", "klass", "shadow", "occluded")


def height_model(lab: StereoLab, n_px: int = 512, *, half_window: int = 9) -> HeightModel:
    """Match the lab's pair rendered at ``n_px`` along its epipolar lines and compare the heights with the truth.

    The same for everyone who asks for the same pair (the guide's example): computed once on a machine, then read
    from the user's disk cache (:mod:`aerophoto.cache`; the same arrays bit for bit).
    """
    from .. import cache

    inputs = {"f_mm": lab.f_mm, "m": lab.m, "seed": lab.seed, "n_px": int(n_px), "half_window": int(half_window),
              "sun": list(SUN)}

    def build():
        hm = _height_model(lab, int(n_px), half_window)
        return {"extent_mm": hm.extent_mm, "match": hm.match, **{k: getattr(hm, k) for k in _HM_ARRAYS}}

    got = cache.load_or_build("height-model", inputs, build, types=(st.DenseParallax,))
    return HeightModel(lab, int(n_px), tuple(got["extent_mm"]), got["match"], *(got[k] for k in _HM_ARRAYS))


def _height_model(lab: StereoLab, n_px: int, half_window: int) -> HeightModel:
    from ..site import COVER_CODES as C
    from ..site import get_site

    im = lab_images(lab, n_px)
    site = get_site()
    L, R = im.left, im.right
    px = L.pixel_mm
    zlo, zhi = site.z_min_m - 5.0, site.z_max_m + (site.objects.canopy_max_m if site.objects is not None else 0) + 10
    dp_lo = float(st.parallax_mm(lab.B_m, lab.f_mm, lab.Z_S_m - zlo)) - lab.p0_mm
    dp_hi = float(st.parallax_mm(lab.B_m, lab.f_mm, lab.Z_S_m - zhi)) - lab.p0_mm
    d = st.dense_parallax(L.image, R.image, half_window=half_window, d_min=int(math.floor(dp_lo / px)) - 1,
                          d_max=int(math.ceil(dp_hi / px)) + 1)
    p = lab.p0_mm + d.d_px * px
    rr, cc = np.mgrid[0:L.image.shape[0], 0:L.image.shape[1]]
    xy = L.pixel_to_mm(np.stack([rr, cc], axis=-1))
    with np.errstate(invalid="ignore"):
        Z = np.where(p > 0, lab.model_to_ground(xy, np.where(p > 0, p, 1.0))[..., 2], np.nan)
    # the truth: the surface point the left photo shows at each normalised pixel (nearest pixel of the render)
    left, right = im.photos
    src = st.from_normal(lab.camera, lab.left.pose, lab.R_n, xy)
    rc = np.rint(left.mm_to_pixel(src)).astype(int)
    inside = np.all((rc >= 0) & (rc < left.n_px), axis=-1)
    rc = np.clip(rc, 0, left.n_px - 1)
    G = left.ground_m[rc[..., 0], rc[..., 1]]
    surf = left.surface[rc[..., 0], rc[..., 1]]
    shadow = left.shadow[rc[..., 0], rc[..., 1]] & inside
    Zt = np.where(inside, G[..., 2], np.nan)
    cover = site.cover_at(G[..., 0], G[..., 1])
    klass = np.full(Zt.shape, 4)
    ground = surf == 0
    klass[ground & np.isin(cover, [C["arable field"], C["field boundary"], C["meadow"], C["garden"]])] = 0
    klass[ground & np.isin(cover, [C["dirt road"], C["paved road"], C["sand bank"]])] = 1
    klass[ground & (cover == C["water"])] = 2
    klass[(surf == 4) | (ground & (cover == C["forest"]))] = 3
    # hidden from the right photo: its pixel there shows another surface point
    xr = g.ground_to_photo(lab.camera, lab.right.pose, G.reshape(-1, 3)).reshape(G.shape[:-1] + (2,))
    rcr = np.rint(right.mm_to_pixel(xr)).astype(int)
    in_r = np.all((rcr >= 0) & (rcr < right.n_px), axis=-1)
    rcr = np.clip(rcr, 0, right.n_px - 1)
    Gr = right.ground_m[rcr[..., 0], rcr[..., 1]]
    tol = 1.5 * right.pixel_mm * (lab.Z_S_m - site.mean_height_m) / lab.f_mm  # a pixel and a half on the ground
    occluded = inside & (~in_r | (np.linalg.norm(Gr - G, axis=-1) > tol))
    return HeightModel(lab, n_px, L.extent_mm, d, p, Z, Zt, klass, shadow, occluded)
