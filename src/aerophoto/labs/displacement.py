"""The student's own photo for chapters 03 and 04: pricked points on the virtual site, their plan, the truth.

The guide's §4 and §5 have each student prick points on their photo and on the
photoplan, measure the bases on both and compute the scales before and after a
correction.  Here every variant gets its own **lab sheet** (:class:`LabSheet`):
a photo of the virtual site (:func:`aerophoto.site.get_site`) taken with the
variant's camera — f, scale 1:m, tilt α, principal vertical at λ, heading κ = 0
— with points pricked in zones laid out as the guide asks, and the same points
pricked on a plan at 1:M (M = 10 000).

* **Relief sheet** (:func:`relief_sheet`, guide §4, chapter 03): six points in
  two zones (I, 1, 2 on low ground; II, 3, 4 on high ground).  Each zone's main
  point lies about 40 mm from the isocentre across the principal vertical, so
  the two zones sit at the same distance along it and the tilt changes both
  zones' scales alike; the bases leave it at about ±45° to the principal
  vertical (about 90° apart, 22–28 mm long).  The photo is placed on the site
  where the two zones differ most in height (the hills in the north, the plain
  in the south).
* **Tilt sheet** (:func:`tilt_sheet`, guide §5, chapter 04): nine points in
  three zones along the principal vertical (I on the far side, II near the
  isocentre c, III on the near side), each with two bases about 90° apart.  The
  photo is placed where the points' ground is flattest (the plain), so relief
  hardly disturbs the tilt.

The points are chosen on the site's DEM (not from its catalogue, which is too
sparse for three points 20–30 mm apart on the photo) and only on open ground
(fields, meadows, roads) where nothing stands (the site's surface is its bare
earth: no embankment, no crown) and nothing standing nearby hides them on the
photo (:func:`aerophoto.render.trace` of each image meets the ground at the point).
The layout is drawn from a generator seeded by the variant, and sheets whose
reference corrections would lie within ±0.02 mm of the guide's 0.2 mm threshold are
rejected, so the count of corrections does not hinge on a measuring error.

The truth is geometry, never image analysis: the photo coordinates are
:func:`aerophoto.geometry.ground_to_photo` of the points' X, Y, Z; the plan
coordinates their X, Y at 1:M; the reference tables are
:func:`aerophoto.displacement.relief_work` / :func:`~aerophoto.displacement.tilt_work`
on those error-free measurements.  The photo itself comes from
:func:`aerophoto.render.render`.

The heights handed to the student (:meth:`LabSheet.heights`) are the DEM's,
rounded to 0.1 m (read off the plan's contours in the guide).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import displacement as d
from .. import geometry as g
from .._validate import check_int_range, check_range
from .._digits import scale as fmt_scale

__all__ = ["RELIEF_NAMES", "RELIEF_BASES", "TILT_NAMES", "TILT_BASES", "PHOTO_PX", "M_PLAN", "OPEN_GROUND",
           "LabSheet", "PlanImage", "relief_sheet", "tilt_sheet", "sheet_for", "photo_of", "plan_of"]

RELIEF_NAMES = ("I", "1", "2", "II", "3", "4")
RELIEF_BASES = (("I", "1"), ("I", "2"), ("II", "3"), ("II", "4"))
TILT_NAMES = ("I", "1", "2", "II", "3", "4", "III", "5", "6")
TILT_BASES = (("I", "1"), ("I", "2"), ("II", "3"), ("II", "4"), ("III", "5"), ("III", "6"))
#: pixels across the student's photo (0.18 mm per pixel; the pricked marks are drawn exactly over it)
PHOTO_PX = 1024
#: the plan's scale denominator M (guide §1)
M_PLAN = 10000.0
#: land cover a point may be pricked on (site.COVER names)
OPEN_GROUND = ("arable field", "field boundary", "meadow", "dirt road", "paved road")
#: how far a reference correction must stay from the 0.2 mm threshold, mm
THRESHOLD_MARGIN_MM = 0.02
_FRAME_LIMIT_MM = 80.0
_SEED = 20140


# --------------------------------------------------------------------------- the sheet
@dataclass(frozen=True)
class PlanImage:
    """The plan (photoplan) of a sheet at 1:M: brightness and contours in plan millimetres.

    Attributes
    ----------
    image : ndarray, shape (rows, cols), float32
        Brightness 0…1, row 0 at the top (north); shown with ``imshow(image, extent=extent_mm)``.
    extent_mm : (left, right, bottom, top)
        The sheet in plan mm: x east, y north from the sheet's lower-left corner.
    contour_x_mm, contour_y_mm : ndarray, shape (k,), (l,)
        The grid of the contour heights, plan mm.
    contour_Z_m : ndarray, shape (l, k)
        Heights on that grid, m (draw contours with ``ax.contour``).
    """

    image: np.ndarray
    extent_mm: tuple
    contour_x_mm: np.ndarray
    contour_y_mm: np.ndarray
    contour_Z_m: np.ndarray


@dataclass(frozen=True, eq=False)
class LabSheet:
    """One variant's lab sheet: the photo's camera and pose and the pricked points (see the module notes).

    Attributes
    ----------
    kind : str
        ``"relief"`` (guide §4) or ``"tilt"`` (guide §5).
    i : int
        The variant.
    camera : Camera
        f of the variant, 18×18 cm frame.
    pose : Pose
        S above the points' mean object plane by H = f·m; α, λ of the variant; κ = 0.
    names : tuple of str
    bases : tuple of (str, str)
    XYZ_m : ndarray, shape (n, 3)
        The pricked points on the ground (on the DEM), m.
    M : float
        The plan's scale denominator.
    plan_origin_m : ndarray, shape (2,)
        Ground X, Y of the plan sheet's lower-left corner, m.
    plan_size_mm : ndarray, shape (2,)
        Width and height of the plan sheet, mm.
    """

    kind: str
    i: int
    camera: g.Camera
    pose: g.Pose
    names: tuple
    bases: tuple
    XYZ_m: np.ndarray
    M: float
    plan_origin_m: np.ndarray
    plan_size_mm: np.ndarray

    def __repr__(self) -> str:  # no coordinates: the points' positions are what the student measures
        return f"LabSheet({self.kind}, variant {self.i:02d}, {len(self.names)} points)"

    # ---- what the student works from
    @property
    def Z_given_m(self) -> np.ndarray:
        """The heights the student is given, m: the DEM's, rounded to 0.1 m (shape (n,))."""
        return np.round(self.XYZ_m[:, 2], 1)

    def heights(self) -> pd.DataFrame:
        """The points' heights Z, m, as read off the plan's contours (one row per point)."""
        return pd.DataFrame({"Z, m": self.Z_given_m}, index=pd.Index(self.names, name="point"))

    def bases_frame(self) -> pd.DataFrame:
        """The bases in the order of the tables: name and its two points."""
        return pd.DataFrame({"from": [a for a, _ in self.bases], "to": [b for _, b in self.bases]},
                            index=pd.Index([f"{a}-{b}" for a, b in self.bases], name="base"))

    # ---- the truth (geometry)
    @property
    def photo_xy_mm(self) -> np.ndarray:
        """The points' images, mm from o, shape (n, 2): ground_to_photo of their X, Y, Z."""
        return g.ground_to_photo(self.camera, self.pose, self.XYZ_m)

    @property
    def plan_xy_mm(self) -> np.ndarray:
        """The points on the plan sheet, mm from its lower-left corner, shape (n, 2)."""
        return (self.XYZ_m[:, :2] - self.plan_origin_m) * 1000.0 / self.M

    @property
    def l_plan_mm(self) -> np.ndarray:
        """Plan lengths l_пл of the bases, mm, shape (n_bases,)."""
        return d.base_lengths_mm(self.names, self.plan_xy_mm, self.bases)

    @property
    def l_photo_mm(self) -> np.ndarray:
        """Photo lengths l_сн of the bases, mm, shape (n_bases,)."""
        return d.base_lengths_mm(self.names, self.photo_xy_mm, self.bases)

    @property
    def n_mm(self) -> np.ndarray:
        """The nadir point n, mm."""
        return g.nadir_point(self.camera, self.pose)

    @property
    def c_mm(self) -> np.ndarray:
        """The isocentre c, mm."""
        return g.isocentre(self.camera, self.pose)

    @property
    def Z_mean_m(self) -> float:
        """The height of the points' mean object plane (the guide's Z_cp of the exact heights), m."""
        if self.kind == "relief":
            return _mean_plane(self.names, self.bases, self.XYZ_m[:, 2])
        return float(np.mean(self.XYZ_m[:, 2]))

    @property
    def H_m(self) -> float:
        """The flying height above the points' mean object plane, m (= f·m of the variant)."""
        return self.pose.Z_m - self.Z_mean_m

    @property
    def m(self) -> float:
        """The photo's scale denominator over the mean object plane, H/f (= the variant's m)."""
        return self.H_m / (self.camera.f_mm / 1000.0)

    def work(self, photo_xy_mm=None, l_plan_mm=None):
        """The guide's procedure on measurements (default: the error-free ones): tables 2–4 or 5–7.

        Returns :class:`aerophoto.displacement.ReliefWork` (relief sheet, with the given heights)
        or :class:`aerophoto.displacement.TiltWork` (tilt sheet).
        """
        xy = self.photo_xy_mm if photo_xy_mm is None else photo_xy_mm
        lp = self.l_plan_mm if l_plan_mm is None else l_plan_mm
        if self.kind == "relief":
            return d.relief_work(self.names, xy, lp, self.Z_given_m, self.bases, f_mm=self.camera.f_mm,
                                 n_mm=self.n_mm, M=self.M)
        return d.tilt_work(self.names, xy, lp, self.bases, f_mm=self.camera.f_mm, alpha_deg=self.pose.alpha_deg,
                           lambda_deg=self.pose.lambda_deg, M=self.M)

    def mean_plane_xy_mm(self) -> np.ndarray:
        """Where the points would be imaged if they lay on the mean object plane Z_cp (same X, Y), mm.

        What a perfect relief correction would give (relief sheet).
        """
        P = self.XYZ_m.copy()
        P[:, 2] = self.Z_mean_m
        return g.ground_to_photo(self.camera, self.pose, P)

    def vertical_xy_mm(self) -> np.ndarray:
        """Where the points would be on the equivalent vertical photo turned about the isoline, mm.

        What a perfect tilt correction would give (tilt sheet): :func:`aerophoto.geometry.tilt_displacement_vectors`.
        """
        return g.tilt_displacement_vectors(self.camera, self.pose, self.XYZ_m)[1]

    def marks(self, where: str = "photo") -> dict:
        """The pricked marks, name → (x, y) mm, on the ``"photo"`` or the ``"plan"`` (for a measuring tool)."""
        xy = self.photo_xy_mm if where == "photo" else self.plan_xy_mm if where == "plan" else None
        if xy is None:
            raise ValueError(f"where = {where!r} is not one of the valid choices ['photo', 'plan']")
        return {n: (float(x), float(y)) for n, (x, y) in zip(self.names, xy)}

    def photo(self, n_px: int = PHOTO_PX):
        """The student's photo (:class:`aerophoto.render.Photo`), rendered exactly; cached."""
        return photo_of(self.kind, self.i, n_px)

    def plan(self) -> PlanImage:
        """The plan sheet at 1:M with contours (:class:`PlanImage`); cached."""
        return plan_of(self.kind, self.i)

    def reference(self) -> dict:
        """The reference solution, laid out like the guide's tables, and how close the guide's corrections come.

        ``{"Table 2": …, "Table 3": …, "Table 4": …, "against the geometry": …}`` (tables 5–7 for a tilt
        sheet), text at the guide's precision.  The last table compares, point by point, the displacement the
        guide's formula gives with the exact one (the camera model), and how far each corrected point lies from
        where a perfect correction puts it.  For the instructor, or for a student whose tasks have passed.
        """
        from ..guide.ch03 import display_frame

        w = self.work()
        if self.kind == "relief":
            tables = {"Table 2": w.table2.table(), "Table 3": w.table3.table(), "Table 4": w.table4.table()}
            target = self.mean_plane_xy_mm()
            centre = w.n_mm
            formula = w.table3.delta_mm
            name = "δh"
        else:
            tables = {"Table 5": w.table5.table(), "Table 6": w.table6.table(), "Table 7": w.table7.table()}
            target = self.vertical_xy_mm()
            centre = w.c_mm
            formula = w.table6.delta_approx_mm
            name = "δα"
        xy = self.photo_xy_mm
        exact = np.hypot(*(xy - centre).T) - np.hypot(*(target - centre).T)
        left = np.hypot(*(w.corrected_xy_mm - target).T)
        check = pd.DataFrame({f"{name} formula, mm": formula, f"{name} exact, mm": exact,
                              "formula − exact, mm": formula - exact, "corrected point off by, mm": left},
                             index=pd.Index(self.names, name="point"))
        out = {k: display_frame(t) for k, t in tables.items()}
        out["against the geometry"] = check.round(3)
        return out

    def summary(self) -> pd.DataFrame:
        """The photo's inputs the student works from: f, 1:m, α, λ, the plan's 1:M (no results)."""
        rows = [("focal length f", "mm", f"{self.camera.f_mm:g}"),
                ("photo scale 1:m", "", fmt_scale(self.m)),
                ("tilt α", "°", f"{self.pose.alpha_deg:g}"),
                ("principal vertical λ (from +x, counter-clockwise)", "°", f"{self.pose.lambda_deg:g}"),
                ("plan scale 1:M", "", fmt_scale(self.M))]
        return pd.DataFrame(rows, columns=["quantity", "unit", "value"]).set_index("quantity")


def _mean_plane(names, bases, Z) -> float:
    Zof = dict(zip(names, Z))
    zones = tuple(dict.fromkeys(a for a, _ in bases))
    return d.mean_object_plane([d.zone_height([(Zof[a], Zof[b]) for a, b in bases if a == z]) for z in zones])


# --------------------------------------------------------------------------- layout on the photo
def _site():
    from ..site import get_site

    return get_site()


def _frame(v):
    cam = g.Camera(v.f_mm)
    pose0 = g.Pose(0.0, 0.0, g.flying_height_m(v.f_mm, v.m), v.alpha_deg, v.lambda_deg, 0.0)
    u = g.principal_vertical(pose0)
    w = np.array([-u[1], u[0]])
    return cam, pose0, g.isocentre(cam, pose0), u, w


def _relief_pattern(v, rng):
    """Six photo points (the mean-plane images) for the relief sheet, zone +w first; None if out of bounds."""
    cam, pose0, c, u, w = _frame(v)
    n = g.nadir_point(cam, pose0)
    out = []
    for s in (+1, -1):
        dP = rng.uniform(36.0, 46.0)
        L1, L2 = rng.uniform(22.0, 28.0, 2)
        beta = math.radians(rng.uniform(38.0, 52.0))
        along = rng.uniform(-4.0, 4.0)
        P = c + s * dP * w + along * u
        b1 = math.cos(beta) * u + math.sin(beta) * s * w
        b2 = -math.cos(beta) * u + math.sin(beta) * s * w
        out += [P, P + L1 * b1, P + L2 * b2]
    xy = np.array(out)
    rn = np.hypot(*(xy[[0, 3]] - n).T)
    if np.any(np.abs(xy) > _FRAME_LIMIT_MM) or np.any(rn < 38.0) or np.any(rn > 72.0):
        return None
    return xy


def _phi_ok(r_c, phi) -> bool:
    off = np.minimum(phi % 360.0, 360.0 - phi % 360.0)  # distance from 0°/360°
    return bool(np.all(r_c >= 12.0) and np.all(off >= 7.0))


def _tilt_pattern(v, rng):
    """Nine photo points for the tilt sheet (zones I far, II near c, III near side); None if unsuitable."""
    cam, pose0, c, u, w = _frame(v)
    mains = (rng.uniform(44.0, 54.0) * u + rng.uniform(-12.0, 12.0) * w,
             rng.uniform(-8.0, 8.0) * u + rng.choice([-1.0, 1.0]) * rng.uniform(14.0, 20.0) * w,
             -rng.uniform(40.0, 50.0) * u + rng.uniform(-12.0, 12.0) * w)
    out = []
    for P in mains:
        th = rng.uniform(0.0, 2 * math.pi)
        th2 = th + math.radians(90.0 + rng.uniform(-12.0, 12.0)) * rng.choice([-1.0, 1.0])
        L1, L2 = rng.uniform(22.0, 28.0, 2)
        P = c + P
        out += [P, P + L1 * np.array([math.cos(th), math.sin(th)]), P + L2 * np.array([math.cos(th2), math.sin(th2)])]
    xy = np.array(out)
    if np.any(np.abs(xy) > _FRAME_LIMIT_MM):
        return None
    dd = np.hypot(*(xy[:, None, :] - xy[None, :, :]).transpose(2, 0, 1))
    if np.min(dd[np.triu_indices(len(xy), 1)]) < 10.0:
        return None
    r_c, phi = d.polar_about_isocentre(cam, pose0, xy)
    return xy if _phi_ok(r_c, phi) else None


def _candidates(site, cam, pose0, offsets, step_m: float = 100.0):
    """Projection centres S (X, Y) on a lattice whose photo footprint stays on the site; ground XY of the points."""
    x0, x1, y0, y1 = site.extent_m
    corners = g.photo_to_plane(cam, pose0, cam.corners_mm(), 0.0)[:, :2]
    lo = -corners.min(axis=0) + 20.0
    hi = -corners.max(axis=0) - 20.0
    Xs = np.arange(x0 + lo[0], x1 + hi[0], step_m)
    Ys = np.arange(y0 + lo[1], y1 + hi[1], step_m)
    SX, SY = np.meshgrid(Xs, Ys)
    S = np.column_stack([SX.ravel(), SY.ravel()])
    P = S[:, None, :] + offsets[None, :, :2]
    return S, P


def _open(site, P) -> np.ndarray:
    from ..site import COVER_CODES

    codes = [COVER_CODES[k] for k in OPEN_GROUND]
    cov = site.cover_at(P[..., 0], P[..., 1])
    # a little ring around each point must be open too (the point is not at a field's edge against a forest)
    ok = np.isin(cov, codes)
    for dx, dy in ((6, 0), (-6, 0), (0, 6), (0, -6)):
        ok &= np.isin(site.cover_at(P[..., 0] + dx, P[..., 1] + dy), codes)
    return np.all(ok, axis=-1)


def _plan_frame(XY: np.ndarray, M: float):
    """Plan sheet origin (ground, on a 100 m lattice) and size (mm) around the points with a 30 mm margin."""
    margin = 30.0 * M / 1000.0
    lo = np.floor((XY.min(axis=0) - margin) / 100.0) * 100.0
    hi = np.ceil((XY.max(axis=0) + margin) / 100.0) * 100.0
    return lo, (hi - lo) * 1000.0 / M


def _bare_and_seen(sheet, xy) -> bool:
    """Nothing stands on the points (the site's surface is its bare earth there, no embankment, no crown), and
    nothing standing nearby hides them on the photo: the ray of each image meets the ground at the point."""
    from ..render import trace

    site = _site()
    X, Y, Z = sheet.XYZ_m.T
    if np.any(np.abs(site.surface_height(X, Y) - Z) > 0.05):
        return False
    hit = trace(site, sheet.camera, sheet.pose, xy).XYZ_m
    return bool(np.all(np.linalg.norm(hit - sheet.XYZ_m, axis=1) <= 0.5))


def _margin_ok(values) -> bool:
    a = np.abs(np.asarray(values, dtype=float))
    return bool(np.all(np.abs(a - d.THRESHOLD_MM) >= THRESHOLD_MARGIN_MM))


def _build(kind: str, i: int) -> LabSheet:
    from ..variants import variant_for_index

    v = variant_for_index(i)
    site = _site()
    rng = np.random.default_rng([_SEED, 4 if kind == "relief" else 5, i])
    names, bases = (RELIEF_NAMES, RELIEF_BASES) if kind == "relief" else (TILT_NAMES, TILT_BASES)
    cam, pose0, *_ = _frame(v)
    H = pose0.Z_m
    for _attempt in range(400):
        xy = (_relief_pattern if kind == "relief" else _tilt_pattern)(v, rng)
        if xy is None:
            continue
        offsets = g.photo_to_plane(cam, pose0, xy, 0.0)
        S, P = _candidates(site, cam, pose0, offsets)
        Z = site.height(P[..., 0], P[..., 1])
        ok = _open(site, P)
        if kind == "relief":
            score = Z[:, :3].mean(axis=1) - Z[:, 3:].mean(axis=1)  # zone +w minus zone −w
            score = np.abs(score)
        else:
            r = np.hypot(*xy.T)
            score = -np.max(r[None, :] * np.abs(Z - Z.mean(axis=1, keepdims=True)) / H, axis=1)
        if not ok.any():
            continue
        best = np.max(score[ok])
        tol = 0.15 * abs(best) if kind == "relief" else 0.01
        pick = np.flatnonzero(ok & (score >= best - tol))
        for k in rng.permutation(pick)[:8]:
            sheet = _finish(kind, i, v, cam, names, bases, S[k], P[k], Z[k], H)
            if sheet is not None:
                return sheet
    raise RuntimeError(f"no {kind} sheet found for variant {i:02d}")  # pragma: no cover - every variant is tested


def _finish(kind, i, v, cam, names, bases, S, P, Z, H):
    """Name the zones, place S above the mean object plane, and accept the sheet if the truth keeps its margins."""
    XYZ = np.column_stack([P, Z])
    if kind == "relief" and Z[:3].mean() > Z[3:].mean():
        XYZ = XYZ[[3, 4, 5, 0, 1, 2]]  # zone I is the low one, as in the guide
    Zcp = _mean_plane(names, bases, XYZ[:, 2]) if kind == "relief" else float(np.mean(XYZ[:, 2]))
    pose = g.Pose(float(S[0]), float(S[1]), Zcp + H, v.alpha_deg, v.lambda_deg, 0.0)  # H above Z_cp
    origin, size = _plan_frame(XYZ[:, :2], M_PLAN)
    sheet = LabSheet(kind, i, cam, pose, names, bases, XYZ, M_PLAN, origin, size)
    xy = sheet.photo_xy_mm
    if np.any(np.abs(xy) > _FRAME_LIMIT_MM + 4.0) or not _bare_and_seen(sheet, xy):
        return None
    w = sheet.work()
    if kind == "relief":
        if not _margin_ok(w.table3.delta_mm):
            return None
    else:
        if not (_margin_ok(w.table6.delta_approx_mm) and _phi_ok(w.table6.r_c_mm, w.table6.phi_deg)):
            return None
    lengths = sheet.l_photo_mm
    if np.any(lengths < 19.0) or np.any(lengths > 31.0):
        return None
    return sheet


@functools.lru_cache(maxsize=128)
def relief_sheet(i: int) -> LabSheet:
    """The relief sheet (guide §4, chapter 03) of variant ``i`` (0–99); built once, cached."""
    return _build("relief", check_int_range("i", i, 0, 99))


@functools.lru_cache(maxsize=128)
def tilt_sheet(i: int) -> LabSheet:
    """The tilt sheet (guide §5, chapter 04) of variant ``i`` (0–99); built once, cached."""
    return _build("tilt", check_int_range("i", i, 0, 99))


def sheet_for(kind: str, v) -> LabSheet:
    """The sheet of ``kind`` (``"relief"`` or ``"tilt"``) for the variant ``v`` (anything with ``i``)."""
    return _sheet(kind, int(v.i))


def _sheet(kind: str, i: int) -> LabSheet:
    if kind == "relief":
        return relief_sheet(i)
    if kind == "tilt":
        return tilt_sheet(i)
    raise ValueError(f"kind = {kind!r} is not one of the valid choices ['relief', 'tilt']")


# --------------------------------------------------------------------------- pictures (cached)
@functools.lru_cache(maxsize=2)
def photo_of(kind: str, i: int, n_px: int = PHOTO_PX):
    """The rendered photo of a sheet (:func:`aerophoto.render.render`, fiducial marks burnt in)."""
    from ..render import render

    sheet = _sheet(kind, i)
    return render(_site(), sheet.camera, sheet.pose, n_px=n_px)


@functools.lru_cache(maxsize=2)
def plan_of(kind: str, i: int, px_mm: float = 0.25, contour_step_mm: float = 2.0) -> PlanImage:
    """The plan sheet of a sheet at 1:M: the site's ground texture seen from straight above, and its heights.

    ``px_mm`` is the plan pixel, mm (0.25 mm = 2.5 m on the ground at 1:10 000).
    """
    px = check_range("px_mm", px_mm, 0.05, 2.0, unit="mm")
    check_range("contour_step_mm", contour_step_mm, 0.1, 50.0, unit="mm")
    site = _site()
    sheet = _sheet(kind, i)
    W, Hh = sheet.plan_size_mm
    k = sheet.M / 1000.0  # ground metres per plan mm
    nx, ny = int(math.ceil(W / px)), int(math.ceil(Hh / px))
    xs = (np.arange(nx) + 0.5) * px
    ys = Hh - (np.arange(ny) + 0.5) * px
    X = sheet.plan_origin_m[0] + xs[None, :] * k
    Y = sheet.plan_origin_m[1] + ys[:, None] * k
    level = site.level_for(px * k)
    img = site.sample(X, Y, level, outside=0.5)
    cx = np.arange(0.0, W + 1e-9, contour_step_mm)
    cy = np.arange(0.0, Hh + 1e-9, contour_step_mm)
    Zc = site.height(sheet.plan_origin_m[0] + cx[None, :] * k, sheet.plan_origin_m[1] + cy[:, None] * k)
    return PlanImage(img.astype(np.float32), (0.0, float(W), 0.0, float(Hh)), cx, cy, Zc)
