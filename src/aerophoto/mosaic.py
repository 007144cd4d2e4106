"""The single-strip photo mosaic (одномаршрутная фотосхема), guide §6.

A fotoschema (фотосхема) is made of the *working areas* (рабочие площади) of
the contact prints of one strip, cut along the middle of each forward overlap
and glued in order onto a sheet.  It is not rectified: tilt and relief
displacements stay in it, and where two prints meet along a cut the ground
either goes missing or is shown twice.  This module does what the technician
does, on simulated photos, and measures what the guide measures:

1. **Matching neighbours** (монтаж способом мельканий): on each pair, two
   conjugate points a, b of sharp detail are chosen near the middle of the
   double overlap, 1.5–2.5 cm from the upper and lower edges, on high ground
   (guide §6, steps 1–2).  The print of the right photo is laid on the left
   one so that the points coincide as well as they can — a rigid 2-D motion
   (shift and turn; contact prints cannot be rescaled), fitted by least
   squares, which splits the residual equally between the two points as the
   guide asks.  The chain of these motions places every photo on the sheet.
2. **Cuts** (порезы) through a and b, across the overlap: straight by default,
   with the guide's zigzag and curved forms as options (figure 12).
3. **Gluing**: each sheet point shows the photo whose working area it lies in
   (between its two cuts); :func:`sheet_raster` draws the sheet at a chosen
   resolution in sheet millimetres.
4. **Seam quality** (guide §6, step 8): at points every 2–3 cm along each
   cut the mismatch ΔI is measured along the strip, negative for a cut-out
   (вырез, ground missing between the two sides of the cut) and positive for
   a duplicate (дублет, ground shown twice); the quality is the RMS
   m = √(ΣΔI²/n) (6.2), and cut-outs larger than 0.5 mm are not allowed.
   Here ΔI is computed from truth: the ground point each of the two photos
   places at the sheet point (:func:`aerophoto.geometry.photo_to_dem`) and
   their difference along the strip, in sheet millimetres.
5. **Mean scale** (guide §6, step 7, formula 6.1): four points near the outer
   edges of the first and last working areas, identified on the mosaic and on
   the 1:M topographic plan; four bases l_i (mosaic) and L_i (plan) give the
   partial scales 1/m_i = l_i/(L_i·M) and their mean.

Coordinates: the *sheet* is in millimetres, x along the strip (the first
photo's principal point at the origin, the last one on the +x axis), y across
it (to the left of the direction of flight).  Ground is in metres (X east,
Y north, Z up), photos in mm as in :mod:`aerophoto.geometry`.

This is physics (layer 2): the strip (:class:`aerophoto.simulate.Strip` or
anything with ``shots``), the terrain (:class:`aerophoto.geometry.Terrain`,
e.g. the virtual site or :class:`aerophoto.terrain.RescaledRelief`) and the
rendered prints are taken as arguments, never imported.  The student's
fotoschema for a variant is built in :mod:`aerophoto.labs.ch05`; the live
demo and the finished sheet are in :mod:`aerophoto.demos.fotoschema`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from . import _validate as V
from . import geometry as g
from ._validate import check_int_range, check_positive, check_range
from .displacement import base_scale
from .plane import Similarity2D, fit_similarity

__all__ = ["ALLOWED_CUTOUT_MM", "CHECK_SPACING_MM", "CUT_SHAPES", "Similarity2D", "fit_similarity", "cut_line",
           "seam_rms", "partial_scales", "classify_mismatch", "TiePoints", "choose_tie_points", "Seam", "ScaleCheck",
           "Fotoschema", "assemble", "seam_mismatches", "mean_scale", "assign_working_areas", "catalogue_points",
           "sheet_raster", "sheet_raster_bands", "SIDE_OVERLAP_PERCENT", "SeamDetails", "seam_details"]

#: guide §6, step 8: the largest cut-out (вырез) allowed on a seam, mm
ALLOWED_CUTOUT_MM = 0.5
#: guide §6, step 8: points are pricked along a cut "every 2–3 cm"; the book uses 2.5 cm
CHECK_SPACING_MM = 25.0
#: the forms of cut the guide shows (figure 12)
CUT_SHAPES = ("straight", "zigzag", "curved")
#: guide §1: the side overlap p_y; the working area's upper and lower boundaries run along the middle
#: of the side overlaps (guide §6, after step 9)
SIDE_OVERLAP_PERCENT = 30.0


# =========================================================================== plane geometry
# Similarity2D and fit_similarity live in aerophoto.plane (shared with the triangulation);
# they are re-exported here, where the fotoschema uses them.


@V.checked(p_top=V.point(2), p_bottom=V.point(2), y_range=V.point(2), amplitude_mm=V.number(0.0, 50.0),
           period_mm=V.number(0.0, 1e3, lo_open=True), step_mm=V.number(0.0, 1e3, lo_open=True))
def cut_line(p_top, p_bottom, y_range, *, shape: str = "straight", amplitude_mm: float = 3.0,
             period_mm: float = 30.0, step_mm: float = 1.0) -> np.ndarray:
    """The line of a cut (порез) on the sheet, as a polyline monotone in y (guide §6, step 4, figure 12).

    Parameters
    ----------
    p_top, p_bottom : (2,) sheet points, mm
        The two pricked points a, b the ruler is laid on.
    y_range : (y_min, y_max)
        Extent of the cut across the strip, mm (y_min < y_max).
    shape : {"straight", "zigzag", "curved"}
        A straight cut through a and b (the book's default), or the guide's
        zigzag and curved cuts: the straight line plus a triangle or sine
        wave of ``amplitude_mm`` and ``period_mm`` along the strip, with a
        node at a (so the cut still passes through a).
    step_mm : float
        Spacing of the polyline's vertices across the strip (straight cuts
        have just their two end vertices).

    Returns
    -------
    ndarray, shape (k, 2) : sheet points (x, y) with increasing y.
    """
    if shape not in CUT_SHAPES:
        raise ValueError(f"shape = {shape!r} is not one of the valid choices {list(CUT_SHAPES)}")
    a = np.asarray(p_top, dtype=float)
    b = np.asarray(p_bottom, dtype=float)
    y0, y1 = (float(v) for v in y_range)
    if not y1 > y0:
        raise ValueError(f"y_range = ({y0:g}, {y1:g}) is not valid; it must satisfy y_min < y_max (mm)")
    if abs(a[1] - b[1]) < 1e-9:
        raise ValueError("the two points of a cut lie at the same height across the strip; they must differ in y")
    slope = (a[0] - b[0]) / (a[1] - b[1])  # dx/dy of the straight cut
    if shape == "straight":
        y = np.array([y0, y1])
        return np.column_stack([a[0] + slope * (y - a[1]), y])
    amp = check_range("amplitude_mm", amplitude_mm, 0.0, 50.0, unit="mm")
    per = check_positive("period_mm", period_mm, unit="mm", hi=1000.0)
    st = check_positive("step_mm", step_mm, unit="mm", hi=per)
    if shape == "zigzag":  # vertices exactly at the zigzag's corners
        k0, k1 = math.floor((y0 - a[1]) / (per / 2)) - 1, math.ceil((y1 - a[1]) / (per / 2)) + 1
        corners = a[1] + (np.arange(k0, k1 + 1) * 0.5 + 0.25) * per  # the wave turns at quarter periods
        y = np.unique(np.clip(np.concatenate([[y0, y1], corners]), y0, y1))
        wave = amp * _tri((y - a[1]) / per)
    else:
        V.check_work_size("step_mm", st, (y1 - y0) / st, limit=1e6, what="vertices")
        n = max(2, int(math.ceil((y1 - y0) / st)) + 1)
        y = np.linspace(y0, y1, n)
        wave = amp * np.sin(2.0 * math.pi * (y - a[1]) / per)
    return np.column_stack([a[0] + slope * (y - a[1]) + wave, y])


def _tri(u):
    """Triangle wave of period 1 and amplitude 1 with tri(0) = 0, rising first."""
    u = np.asarray(u, dtype=float)
    f = u - np.floor(u)
    return np.where(f < 0.25, 4 * f, np.where(f < 0.75, 2 - 4 * f, 4 * f - 4))


@V.checked(dI_mm=V.array())
def seam_rms(dI_mm) -> float:
    """Quality of a fotoschema, guide §6 formula (6.2): m = √(ΣΔI²/n), mm.

    Parameters
    ----------
    dI_mm : array_like, shape (n,)
        Mismatches ΔI along the cuts, mm (− cut-out, + duplicate), n ≥ 1.
    """
    d = np.asarray(dI_mm, dtype=float).ravel()
    if d.size == 0:
        raise ValueError("dI_mm is empty; the valid input has at least one mismatch (n ≥ 1)")
    if not np.all(np.isfinite(d)):
        raise ValueError("dI_mm holds a value that is not a finite number (mm)")
    return float(np.sqrt(np.mean(d * d)))


@V.checked(l_mm=V.values(0.0, lo_open=True), L_mm=V.values(0.0, lo_open=True))
def partial_scales(l_mm, L_mm, M: float = 10000.0) -> np.ndarray:
    """Partial scale denominators of a fotoschema, guide §6 formula (6.1).

        1/m_i = l_i / (L_i·M)   →   m_i = L_i·M / l_i

    Parameters
    ----------
    l_mm : array_like, shape (k,)
        Bases measured on the fotoschema, mm (> 0).
    L_mm : array_like, shape (k,)
        The same bases measured on the topographic plan, mm (> 0).
    M : float
        Scale denominator of the plan (guide: 1/M = 1/10000).

    Returns
    -------
    ndarray, shape (k,) : the denominators m_i.  The mean scale is 1/m with
    m the mean of the m_i (as the guide averages denominators in §4).

    It is formula (5.1) of guide §5, m = l_пл·M/l_сн, with the plan's base L_i
    for l_пл and the fotoschema's l_i for l_сн, computed by the one
    implementation :func:`aerophoto.displacement.base_scale`; this function
    keeps the fotoschema's order of arguments (mosaic first, plan second).
    """
    M = check_positive("M", M)
    l = np.asarray(l_mm, dtype=float)
    L = np.asarray(L_mm, dtype=float)
    if l.shape != L.shape:
        raise ValueError(f"l_mm has shape {l.shape} and L_mm {L.shape}; they must match")
    for name, v in (("l_mm", l), ("L_mm", L)):
        if np.any(~np.isfinite(v)) or np.any(v <= 0):
            raise ValueError(f"{name} = {np.ravel(v)[np.argmin(np.ravel(v))]:g} is outside the valid range 0 < {name} (mm)")
    return np.asarray(base_scale(L, l, M), dtype=float)


@V.checked(dI_mm=V.values())
def classify_mismatch(dI_mm):
    """'cut-out' (вырез) for ΔI < 0, 'duplicate' (дублет) for ΔI > 0, 'match' for 0; array of str."""
    d = np.asarray(dI_mm, dtype=float)
    return np.where(d < 0, "cut-out", np.where(d > 0, "duplicate", "match"))


# =========================================================================== matching neighbours
@dataclass(frozen=True)
class TiePoints:
    """The two conjugate points a (upper) and b (lower) of a pair (guide §6, step 2).

    Attributes
    ----------
    photo_a_mm : (2, 2) the points on the left photo A, rows a, b, mm
    photo_b_mm : (2, 2) the same ground details on the right photo B, mm
    ground_m : (2, 3) their ground points X, Y, Z, m
    """

    photo_a_mm: np.ndarray
    photo_b_mm: np.ndarray
    ground_m: np.ndarray


@V.checked(camera=g.Camera, pose_a=g.Pose, pose_b=g.Pose, dem=V.terrain(none=True))
def choose_tie_points(camera: g.Camera, pose_a: g.Pose, pose_b: g.Pose, dem, *,
                      margin_mm=(15.0, 25.0), half_width_mm: float = 8.0, samples: int = 7) -> TiePoints:
    """Choose the conjugate points a, b of a pair as the guide does (§6, step 2).

    Near the middle of the double overlap (half way along the base from o_A to
    the transferred o_B), 1.5–2.5 cm (``margin_mm``) from the upper and the
    lower edge, the point on the **highest ground** in each window is taken —
    on high ground, the guide says, so that the cut makes no cut-outs.  The
    candidates are a ``samples``×``samples`` grid in each window on photo A;
    only those imaged on B at least min(``margin_mm[0]``, 15 mm) inside its
    edges count (the window moves towards the middle if none does).

    Returns
    -------
    TiePoints
    """
    h = camera.half_mm
    ob = g.transfer_points(camera, pose_b, pose_a, np.zeros(2), dem)
    k, s = g.photo_axis_towards(ob)
    mid = ob[k] / 2.0
    lo, hi = (float(v) for v in margin_mm)
    half_width_mm = check_positive("half_width_mm", half_width_mm, unit="mm", hi=h)
    samples = check_int_range("samples", samples, 1, 201)
    along = mid + np.linspace(-half_width_mm, half_width_mm, samples)
    pts_a, pts_b, grd = [], [], []
    for side in (1.0, -1.0):  # a: upper (+ across), b: lower
        found = False
        shift = 0.0
        while not found and shift < h - hi:
            across = side * (h - np.linspace(lo, hi, samples) - shift)
            A, C = np.meshgrid(along, across)
            xy = np.empty(A.shape + (2,))
            xy[..., k] = A
            xy[..., 1 - k] = C
            xy = xy.reshape(-1, 2)
            G = g.photo_to_dem(camera, pose_a, xy, dem)
            xb = g.ground_to_photo(camera, pose_b, G)
            ok = np.all(np.abs(xb) <= h - min(lo, 15.0), axis=1) & np.all(np.abs(xy) <= h, axis=1)
            if ok.any():
                idx = np.flatnonzero(ok)
                j = idx[np.argmax(G[idx, 2])]
                pts_a.append(xy[j])
                pts_b.append(xb[j])
                grd.append(G[j])
                found = True
            shift += 10.0
        if not found:
            raise ValueError("the two photos do not overlap enough to choose tie points; "
                             "the forward overlap must leave a common strip at least 2.5 cm from the edges")
    return TiePoints(np.array(pts_a), np.array(pts_b), np.array(grd))


# =========================================================================== the fotoschema
@dataclass(frozen=True)
class Seam:
    """One cut between photo ``numbers[0]`` (left) and ``numbers[1]`` (right) and its check points.

    Attributes
    ----------
    index : int, 0-based seam number (between photos index and index + 1)
    numbers : (left, right) photo numbers
    ties : TiePoints used to lay the right print on the left one
    tie_misfit_mm : (2,) how far apart the two prints leave a and b after the fit, mm
    cut_mm : (k, 2) polyline of the cut on the sheet, mm
    points_mm : (n, 2) check points along the cut, sheet mm
    dI_mm : (n,) mismatches ΔI along the strip, mm (− cut-out, + duplicate)
    ground_left_m, ground_right_m : (n, 3) the ground each photo shows at the check points, m
    """

    index: int
    numbers: tuple
    ties: TiePoints
    tie_misfit_mm: np.ndarray
    cut_mm: np.ndarray
    points_mm: np.ndarray
    dI_mm: np.ndarray
    ground_left_m: np.ndarray
    ground_right_m: np.ndarray

    @property
    def rms_mm(self) -> float:
        return seam_rms(self.dI_mm) if len(self.dI_mm) else float("nan")


@dataclass(frozen=True)
class ScaleCheck:
    """The mean scale of the fotoschema from four bases (guide §6, step 7, formula 6.1).

    Attributes
    ----------
    names : the four points, e.g. ("1a", "1b", "5a", "5b")
    ground_m : (4, 3) their true ground coordinates (the plan's catalogue), m
    sheet_mm : (4, 2) where they are on the fotoschema, mm
    plan_mm : (4, 2) where they are on the 1:M plan, mm
    bases : the four bases as index pairs into the points
    l_mm, L_mm, m_i : (4,) bases on the mosaic and on the plan, mm, and the partial scale denominators
    M : plan scale denominator
    """

    names: tuple
    ground_m: np.ndarray
    sheet_mm: np.ndarray
    plan_mm: np.ndarray
    bases: tuple
    l_mm: np.ndarray
    L_mm: np.ndarray
    m_i: np.ndarray
    M: float

    @property
    def m(self) -> float:
        """Mean scale denominator m of the fotoschema (1/m)."""
        return float(np.mean(self.m_i))

    @property
    def m_rounded(self) -> int:
        """The mean scale as signed on the sheet, to whole hundreds (the guide's appendix: M 1:13000)."""
        return int(round(self.m / 100.0) * 100)

    def table(self) -> pd.DataFrame:
        rows = []
        for (i, j), l, L, mi in zip(self.bases, self.l_mm, self.L_mm, self.m_i):
            rows.append({"base": f"{self.names[i]}–{self.names[j]}", "l on mosaic, mm": round(float(l), 1),
                         "L on plan, mm": round(float(L), 1), "m_i = L·M/l": round(float(mi)),
                         "m_i − m": round(float(mi - self.m))})
        return pd.DataFrame(rows).set_index("base")


@dataclass(frozen=True)
class Fotoschema:
    """A single-strip fotoschema: where each photo lies on the sheet, the cuts, the seams and the scale.

    Attributes
    ----------
    camera : Camera
    poses : tuple[Pose, ...], the photos in strip order
    numbers : tuple[int, ...], photo numbers
    to_sheet : tuple[Similarity2D, ...], photo mm → sheet mm for each photo
    seams : tuple[Seam, ...], one per neighbouring pair
    scale : ScaleCheck
    m_design : design scale denominator of the photos (1/m); ΔI is converted with it
    extent_mm : (x_min, x_max, y_min, y_max) of all photos on the sheet
    cut_shape : the form of the cuts
    """

    camera: g.Camera
    poses: tuple
    numbers: tuple
    to_sheet: tuple
    seams: tuple
    scale: ScaleCheck
    m_design: float
    extent_mm: tuple
    cut_shape: str = "straight"
    strip_direction: np.ndarray = field(default_factory=lambda: np.array([1.0, 0.0]))

    @property
    def dI_mm(self) -> np.ndarray:
        """All mismatches ΔI, mm, seam after seam."""
        return np.concatenate([s.dI_mm for s in self.seams]) if self.seams else np.zeros(0)

    @property
    def rms_mm(self) -> float:
        """Quality m = √(ΣΔI²/n) over all cuts, mm (6.2)."""
        d = self.dI_mm
        return seam_rms(d) if d.size else 0.0

    @property
    def worst_cutout_mm(self) -> float:
        """The most negative ΔI (largest cut-out), mm; 0 if there is none."""
        d = self.dI_mm
        return float(min(0.0, d.min())) if d.size else 0.0

    @property
    def ok(self) -> bool:
        """True if no cut-out exceeds 0.5 mm (guide §6, step 8), ΔI read to 0.01 mm as the tables show it."""
        return _within(self.worst_cutout_mm)

    def principal_points_mm(self) -> np.ndarray:
        """The principal points o on the sheet, shape (n, 2), mm."""
        return np.array([T.apply([0.0, 0.0]) for T in self.to_sheet])

    def frames_mm(self) -> np.ndarray:
        """The frame outlines on the sheet, shape (n, 5, 2) (closed), mm."""
        c = self.camera.corners_mm()
        c = np.vstack([c, c[:1]])
        return np.array([T.apply(c) for T in self.to_sheet])

    def working_area_lines(self, py_percent: float = SIDE_OVERLAP_PERCENT) -> np.ndarray:
        """The upper and lower boundary of the working area on the sheet, shape (2, 2, 2): [upper, lower] × [start, end].

        Guide §6, after step 9: on the first and the last photo two points on the
        middle of the side overlap with the neighbouring strips — l/2 − p_y·l/200
        from o across the strip (63 mm for 18 cm at p_y = 30 %) — are joined by
        straight lines (here from frame edge to frame edge along the sheet's x);
        the sheet is trimmed 0.5–1 cm outside them.
        """
        py = check_range("py_percent", py_percent, 0.0, 100.0, hi_open=True, unit="%")
        d = self.camera.half_mm - py / 100.0 * self.camera.frame_mm / 2.0
        first, last = self.to_sheet[0], self.to_sheet[-1]
        o = self.principal_points_mm()
        along = o[-1] - o[0]
        along = along / np.hypot(*along) if np.hypot(*along) > 0 else np.array([1.0, 0.0])
        x0, x1 = self.extent_mm[0], self.extent_mm[1]
        out = []
        for side in (1.0, -1.0):
            # the two points: on photos 1 and n, d across the strip from o (across = the sheet's +y for side = +1)
            a = first.apply(side * d * _photo_across(first, along))  # the photo's o is its (0, 0)
            b = last.apply(side * d * _photo_across(last, along))
            t = (np.array([x0, x1]) - a[0]) / (b[0] - a[0]) if abs(b[0] - a[0]) > 1e-9 else np.array([0.0, 1.0])
            out.append(a + t[:, None] * (b - a))
        return np.array(out)

    def photo_index(self, xy_mm) -> np.ndarray:
        """Which photo's working area each sheet point lies in, shape (...,), int."""
        return assign_working_areas.__wrapped__(xy_mm, [s.cut_mm for s in self.seams])  # unchecked: per band

    def table(self) -> pd.DataFrame:
        """The correction sheet (корректурный лист) as a table: every check point of every cut."""
        rows = []
        for s in self.seams:
            for k, (p, d) in enumerate(zip(s.points_mm, s.dI_mm)):
                rows.append({"cut": f"{s.numbers[0]}/{s.numbers[1]}", "point": k + 1,
                             "x, mm": round(float(p[0]), 1), "y, mm": round(float(p[1]), 1),
                             "ΔI, mm": round(float(d), 2),
                             "kind": "cut-out (вырез)" if d < 0 else ("duplicate (дублет)" if d > 0 else "match")})
        return pd.DataFrame(rows).set_index(["cut", "point"])

    def seams_table(self) -> pd.DataFrame:
        """One row per cut: number of points, worst cut-out and duplicate, RMS, verdict."""
        rows = []
        for s in self.seams:
            d = s.dI_mm
            rows.append({"cut": f"{s.numbers[0]}/{s.numbers[1]}", "n": len(d),
                         "largest cut-out, mm": round(float(min(0.0, d.min())), 2) if len(d) else 0.0,
                         "largest duplicate, mm": round(float(max(0.0, d.max())), 2) if len(d) else 0.0,
                         "m, mm": round(s.rms_mm, 2) if len(d) else float("nan"),
                         "verdict": "pass" if (len(d) == 0 or _within(d.min())) else "FAIL (cut-out > 0.5 mm)"})
        d = self.dI_mm
        rows.append({"cut": "all", "n": len(d), "largest cut-out, mm": round(self.worst_cutout_mm, 2),
                     "largest duplicate, mm": round(float(max(0.0, d.max())), 2) if d.size else 0.0,
                     "m, mm": round(self.rms_mm, 2), "verdict": "pass" if self.ok else "FAIL (cut-out > 0.5 mm)"})
        return pd.DataFrame(rows).set_index("cut")

    def summary(self) -> dict:
        """Headline numbers: RMS m (mm), worst cut-out (mm), mean scale denominator, verdict."""
        return {"rms_mm": self.rms_mm, "worst_cutout_mm": self.worst_cutout_mm, "n_points": int(self.dI_mm.size),
                "mean_scale_m": self.scale.m, "design_m": self.m_design, "ok": self.ok}


def _within(worst_cutout_mm: float) -> bool:
    """The guide's test of a cut-out against −0.5 mm, on ΔI read to 0.01 mm."""
    return round(float(worst_cutout_mm), 2) >= -ALLOWED_CUTOUT_MM


def _photo_across(T: Similarity2D, along_sheet) -> np.ndarray:
    """The unit vector on a photo that ``T`` lays along the sheet's across direction (+90° from ``along_sheet``)."""
    n = np.array([-along_sheet[1], along_sheet[0]])
    M = T.matrix()[:2, :2]
    v = np.linalg.solve(M, n)
    return v / np.hypot(*v)


@V.checked(xy_mm=V.array(last=2), cuts=V.sequence(V.points(2)))
def assign_working_areas(xy_mm, cuts) -> np.ndarray:
    """Index of the working area each sheet point belongs to: the number of cuts to its left.

    Parameters
    ----------
    xy_mm : array_like, shape (..., 2), sheet points
    cuts : sequence of polylines, shape (k, 2), each monotone in y (as :func:`cut_line` returns)

    Returns
    -------
    ndarray of int, shape (...,) : 0 for the first photo's area, len(cuts) for the last.
    """
    p = np.asarray(xy_mm, dtype=float)
    idx = np.zeros(p.shape[:-1], dtype=int)
    for c in cuts:
        idx += p[..., 0] > np.interp(p[..., 1], c[:, 1], c[:, 0])
    return idx


def _resample_polyline(poly, spacing):
    seg = np.hypot(*np.diff(poly, axis=0).T)
    s = np.concatenate([[0.0], np.cumsum(seg)])
    if s[-1] == 0:
        return poly[:1]
    n = int(s[-1] // spacing)
    t = (np.arange(n + 1) * spacing) + (s[-1] - n * spacing) / 2.0  # centred on the cut
    return np.column_stack([np.interp(t, s, poly[:, 0]), np.interp(t, s, poly[:, 1])])


@V.checked(camera=g.Camera, pose_left=g.Pose, pose_right=g.Pose, T_left=Similarity2D, T_right=Similarity2D,
           points_mm=V.points(2), dem=V.terrain(none=True), direction_m=V.point(2), m=V.number(0.0, lo_open=True))
def seam_mismatches(camera: g.Camera, pose_left: g.Pose, pose_right: g.Pose, T_left: Similarity2D,
                    T_right: Similarity2D, points_mm, dem, direction_m, m: float):
    """Mismatches ΔI at sheet points on a cut, from truth (guide §6, step 8).

    For each sheet point, the left photo shows there the ground point G_L and
    the right photo the ground point G_R (rays of the photo points that the
    sheet point comes from, cut with the terrain).  Along the strip's ground
    direction d the mismatch in sheet mm is

        ΔI = (G_L − G_R)·d · 1000 / m

    negative when G_R lies ahead of G_L — the ground between them is on
    neither working area, a cut-out (вырез) — and positive when it lies
    behind, so that ground is shown twice, a duplicate (дублет).

    Returns
    -------
    dI_mm : (n,), G_L : (n, 3), G_R : (n, 3)
    """
    P = np.asarray(points_mm, dtype=float).reshape(-1, 2)
    GL = g.photo_to_dem(camera, pose_left, T_left.inverse().apply(P), dem)
    GR = g.photo_to_dem(camera, pose_right, T_right.inverse().apply(P), dem)
    d = np.asarray(direction_m, dtype=float)
    d = d / np.hypot(*d)
    dI = (GL[:, :2] - GR[:, :2]) @ d * 1000.0 / float(m)
    return dI, GL, GR


@dataclass(frozen=True)
class SeamDetails:
    """What the check with the cut-off strips measures along every cut (guide §6, step 8), from truth.

    At every check point a sharp detail ``inset_mm`` into the left print's glued
    piece is pricked through the right print's cut-off strip laid back in place:
    the prick sits where the *right* print shows it, the contour where the *left*
    one does.  Along the strip (sheet x) from the cut, positive into the left piece,
    ΔI = (contour from the cut) − (prick from the cut): negative — the contour
    between the cut and the prick — a cut-out (вырез), positive a duplicate (дублет).

    Attributes
    ----------
    seam : (n,) int, the cut (0-based, between photos seam and seam + 1)
    point : (n,) int, the check point's number along its cut (1-based)
    contour_mm : (n, 2) the detail on the left piece, sheet mm
    prick_mm : (n, 2) the prick: where the right print shows the detail, sheet mm
    contour_from_cut_mm, prick_from_cut_mm : (n,) distances from the cut along the strip, mm
    ground_m : (n, 3) the details on the ground, m
    """

    seam: np.ndarray
    point: np.ndarray
    contour_mm: np.ndarray
    prick_mm: np.ndarray
    contour_from_cut_mm: np.ndarray
    prick_from_cut_mm: np.ndarray
    ground_m: np.ndarray

    @property
    def dI_mm(self) -> np.ndarray:
        """ΔI = contour − prick distance from the cut, mm (− cut-out, + duplicate)."""
        return self.contour_from_cut_mm - self.prick_from_cut_mm


@V.checked(fs=Fotoschema, dem=V.terrain(none=True), inset_mm=V.values(0.0, 50.0))
def seam_details(fs: Fotoschema, dem=None, *, inset_mm=3.0) -> SeamDetails:
    """The details pricked through the cut-off strips at every check point of every cut (see :class:`SeamDetails`).

    Parameters
    ----------
    fs : Fotoschema
    dem : the photographed terrain (as given to :func:`assemble`); default flat at Z = 0
    inset_mm : how far into the left piece the detail lies, along the strip, mm (0 < inset ≤ 20): one
        value, or one per check point of all cuts in order (a technician pricks sharp details, not a ruled line)
    """
    n_all = sum(len(s.points_mm) for s in fs.seams)
    ins = np.asarray(inset_mm, dtype=float).reshape(-1)
    if ins.size == 1:
        ins = np.full(n_all, ins[0])
    if ins.shape != (n_all,):
        raise ValueError(f"inset_mm has {ins.size} values; the valid input is one value or one per check point ({n_all})")
    for x in ins:
        check_range("inset_mm", x, 0.0, 20.0, lo_open=True, unit="mm")
    dem = g.as_terrain(dem, 0.0)
    cam = fs.camera
    seam, point, A_all, B_all, dA, dB, G_all = [], [], [], [], [], [], []
    k0 = 0
    for s in fs.seams:
        i = s.index
        if not len(s.points_mm):
            continue
        k1 = k0 + len(s.points_mm)
        A = np.asarray(s.points_mm, dtype=float) - np.column_stack([ins[k0:k1], np.zeros(k1 - k0)])
        k0 = k1
        G = g.photo_to_dem(cam, fs.poses[i], fs.to_sheet[i].inverse().apply(A), dem)
        B = fs.to_sheet[i + 1].apply(g.ground_to_photo(cam, fs.poses[i + 1], G))
        cut = s.cut_mm
        seam.append(np.full(len(A), i))
        point.append(np.arange(1, len(A) + 1))
        A_all.append(A)
        B_all.append(B)
        dA.append(np.interp(A[:, 1], cut[:, 1], cut[:, 0]) - A[:, 0])
        dB.append(np.interp(B[:, 1], cut[:, 1], cut[:, 0]) - B[:, 0])
        G_all.append(G)
    if not seam:
        z = np.zeros(0)
        return SeamDetails(z.astype(int), z.astype(int), np.zeros((0, 2)), np.zeros((0, 2)), z, z, np.zeros((0, 3)))
    return SeamDetails(np.concatenate(seam), np.concatenate(point), np.vstack(A_all), np.vstack(B_all),
                       np.concatenate(dA), np.concatenate(dB), np.vstack(G_all))


@V.checked(camera=g.Camera, poses=V.sequence(V.of_type(g.Pose), min_len=2),
           to_sheet=V.sequence(V.of_type(Similarity2D), min_len=2), cuts=V.sequence(V.points(2)),
           dem=V.terrain(none=True), points_m=V.optional(V.points(3)), edge_mm=V.number(0.0, 90.0),
           across_mm=V.number(0.0, 90.0))
def mean_scale(camera: g.Camera, poses, to_sheet, cuts, dem, *, M: float = 10000.0, points_m=None,
               edge_mm: float = 15.0, across_mm: float = 20.0, numbers=None) -> ScaleCheck:
    """The fotoschema's mean scale from four points and four bases (guide §6, step 7, formula 6.1).

    Two points are identified near the outer edge of the first photo's working
    area (``edge_mm`` in from the edge, ``across_mm`` from the upper and
    lower edges) and two on the last photo; with a catalogue (``points_m``,
    shape (k, 3)) the catalogue point nearest to each spot and lying in that
    working area is used, as a student picks road crossings on the plan.
    Their positions on the fotoschema (sheet mm) and on the 1:M plan (mm)
    give four bases — the two along the strip and the two diagonals — and the
    partial scales m_i = L_i·M/l_i (:func:`partial_scales`).
    """
    M = check_positive("M", M)
    h = camera.half_mm
    n = len(poses)
    numbers = tuple(numbers) if numbers is not None else tuple(range(1, n + 1))
    spots = []
    for i, j in ((0, 1), (n - 1, n - 2)):
        towards = g.transfer_points(camera, poses[j], poses[i], np.zeros(2), dem)
        k, s = g.photo_axis_towards(towards)
        for side in (1.0, -1.0):
            xy = np.empty(2)
            xy[k] = -s * (h - edge_mm)
            xy[1 - k] = side * (h - across_mm)
            spots.append((i, xy))
    ground, sheet = [], []
    cat = None if points_m is None else np.asarray(points_m, dtype=float).reshape(-1, 3)
    for i, xy in spots:
        G = g.photo_to_dem(camera, poses[i], xy, dem)
        if cat is not None and len(cat):
            order = np.argsort(np.hypot(cat[:, 0] - G[0], cat[:, 1] - G[1]))[:50]
            for c in order:
                P = cat[c]
                if ((P - poses[i].centre) @ g.rotation_matrix(poses[i]))[2] >= 0:
                    continue
                p = g.ground_to_photo(camera, poses[i], P)
                if not camera.inside(p) or np.any(np.abs(p) > h - 3.0):
                    continue
                q = to_sheet[i].apply(p)
                if assign_working_areas.__wrapped__(q, cuts) == i:
                    G = P
                    break
        ground.append(G)
        sheet.append(to_sheet[i].apply(g.ground_to_photo(camera, poses[i], G)))
    ground = np.array(ground)
    sheet = np.array(sheet)
    plan = ground[:, :2] * 1000.0 / M
    bases = ((0, 2), (1, 3), (0, 3), (1, 2))
    l = np.array([np.hypot(*(sheet[j] - sheet[i])) for i, j in bases])
    L = np.array([np.hypot(*(plan[j] - plan[i])) for i, j in bases])
    names = (f"{numbers[0]}a", f"{numbers[0]}b", f"{numbers[-1]}a", f"{numbers[-1]}b")
    return ScaleCheck(names, ground, sheet, plan, bases, l, L, partial_scales(l, L, M), M)


@V.checked(strip=V.has_attrs("shots", "camera", what="a simulated strip (simulate.Strip)"), dem=V.terrain(none=True),
           amplitude_mm=V.number(0.0, 50.0), period_mm=V.number(0.0, 1e3, lo_open=True),
           points_m=V.optional(V.points(3)))
def assemble(strip, dem=None, *, cut_shape: str = "straight", amplitude_mm: float = 3.0, period_mm: float = 30.0,
             spacing_mm: float = CHECK_SPACING_MM, M: float = 10000.0, points_m=None,
             tie_margin_mm=(15.0, 25.0)) -> Fotoschema:
    """Assemble a single-strip fotoschema from a simulated strip (guide §6, steps 1–8).

    Parameters
    ----------
    strip : aerophoto.simulate.Strip
        The photos (true orientations), the camera and the design scale 1:m.
    dem : terrain, optional
        The photographed ground (the virtual site or a FlatTerrain); default
        flat ground at the strip's reference height.
    cut_shape : {"straight", "zigzag", "curved"}
        Form of the cuts (guide figure 12); ``amplitude_mm`` and ``period_mm``
        shape the zigzag and curved ones.
    spacing_mm : float
        Spacing of the check points along each cut (guide: 2–3 cm), mm.
    M : float
        Scale denominator of the topographic plan used for the mean scale.
    points_m : array_like (k, 3), optional
        Catalogue of ground points identifiable on photos and plan.

    Returns
    -------
    Fotoschema
    """
    shots = list(getattr(strip, "shots", strip))
    if len(shots) < 2:
        raise ValueError(f"the strip has {len(shots)} photo(s); a fotoschema needs at least 2")
    if cut_shape not in CUT_SHAPES:
        raise ValueError(f"cut_shape = {cut_shape!r} is not one of the valid choices {list(CUT_SHAPES)}")
    spacing = check_range("spacing_mm", spacing_mm, 1.0, 200.0, unit="mm")
    cam = shots[0].camera
    dem = g.as_terrain(dem, getattr(strip, "ground_Z_m", 0.0))
    poses = tuple(s.pose for s in shots)
    numbers = tuple(s.number for s in shots)
    m = float(getattr(strip, "m", shots[0].m))
    # 1. lay each print on its neighbour by the tie points (rigid motion)
    ties, rel = [], []
    for a, b in zip(poses[:-1], poses[1:]):
        tp = choose_tie_points(cam, a, b, dem, margin_mm=tie_margin_mm)
        ties.append(tp)
        rel.append(fit_similarity(tp.photo_b_mm, tp.photo_a_mm))
    T = [Similarity2D()]
    for R in rel:
        T.append(T[-1].compose(R))
    # 2. turn the sheet so that the strip runs along +x from o of the first photo
    o = np.array([t.apply([0.0, 0.0]) for t in T])
    d = o[-1] - o[0]
    th = -math.degrees(math.atan2(d[1], d[0]))
    F = Similarity2D.from_angle(th)
    F = Similarity2D(F.a, F.b, *(-F.apply(o[0])))
    T = tuple(F.compose(t) for t in T)
    corners = np.array([t.apply(cam.corners_mm()) for t in T]).reshape(-1, 2)
    extent = (float(corners[:, 0].min()), float(corners[:, 0].max()),
              float(corners[:, 1].min()), float(corners[:, 1].max()))
    y_range = (extent[2] - 5.0, extent[3] + 5.0)
    # ground direction of the strip: first to last principal point's ground point
    O = np.array([g.photo_to_dem(cam, p, np.zeros(2), dem)[:2] for p in (poses[0], poses[-1])])
    dir_m = (O[1] - O[0]) / np.hypot(*(O[1] - O[0]))
    # 3. cuts through a and b; 4. check points and mismatches
    seams = []
    h = cam.half_mm
    for i, tp in enumerate(ties):
        pa = T[i].apply(tp.photo_a_mm)
        pb = T[i + 1].apply(tp.photo_b_mm)
        misfit = np.hypot(*(pa - pb).T)
        top, bottom = (pa + pb) / 2.0
        cut = cut_line(top, bottom, y_range, shape=cut_shape, amplitude_mm=amplitude_mm, period_mm=period_mm)
        pts = _resample_polyline(cut, spacing)
        inside = (np.all(np.abs(T[i].inverse().apply(pts)) <= h - 2.0, axis=1)
                  & np.all(np.abs(T[i + 1].inverse().apply(pts)) <= h - 2.0, axis=1))
        pts = pts[inside]
        dI, GL, GR = seam_mismatches(cam, poses[i], poses[i + 1], T[i], T[i + 1], pts, dem, dir_m, m)
        seams.append(Seam(i, (numbers[i], numbers[i + 1]), tp, misfit, cut, pts, dI, GL, GR))
    cuts = [s.cut_mm for s in seams]
    # 5. the mean scale from four bases
    sc = mean_scale(cam, poses, T, cuts, dem, M=M, points_m=points_m, numbers=numbers)
    return Fotoschema(cam, poses, numbers, T, tuple(seams), sc, m, extent, cut_shape, dir_m)


# =========================================================================== catalogue
@V.checked(ground=V.terrain(none=True, number_ok=False))
def catalogue_points(ground) -> np.ndarray | None:
    """The ground points of a site's catalogue as an (k, 3) array in metres, or None if it has none."""
    if hasattr(ground, "points_m") and callable(ground.points_m):
        return ground.points_m()
    cat = getattr(ground, "catalogue", None)
    if cat is None:
        return None
    return cat[["X_m", "Y_m", "Z_m"]].to_numpy(dtype=float)


# =========================================================================== drawing the sheet
def _pattern(X, Y):
    """A plain ground pattern (200 m chequer with 50 m grid lines) for terrains without a texture."""
    X = np.asarray(X, dtype=float)
    Y = np.asarray(Y, dtype=float)
    chk = ((np.floor(X / 200.0) + np.floor(Y / 200.0)) % 2).astype(np.float32)
    grid = ((np.abs(((X + 25.0) % 50.0) - 25.0) < 2.0) | (np.abs(((Y + 25.0) % 50.0) - 25.0) < 2.0))
    return np.where(grid, 0.15, 0.55 + 0.3 * chk).astype(np.float32)


@V.checked(fs=Fotoschema, ground=V.terrain(none=True), background=V.number(), max_pixels=V.whole(1, 10**9),
           lattice_px=V.optional(V.whole(2, 64)))
def sheet_raster(fs: Fotoschema, ground=None, px_per_mm: float = 2.0, *, photos=None, extent_mm=None,
                 background: float = 1.0, max_pixels: int = 20_000_000, lattice_px: int | None = None):
    """Glue the working areas onto the sheet: a greyscale raster of the fotoschema.

    Every sheet pixel (centre P) is given to the photo whose working area it
    lies in (:meth:`Fotoschema.photo_index`); P is carried into that photo
    (the inverse of its placing motion), the photo's ray is cut with the
    terrain (:func:`aerophoto.geometry.photo_to_dem`) and the ground brightness
    there is read from the site's texture at the pyramid level matching the
    pixel (:meth:`aerophoto.site.Site.sample`) — exactly what
    :mod:`aerophoto.render` puts into that photo pixel, without resampling a
    rendered photo a second time.  Pixels outside every working area get
    ``background``.

    With ``photos`` (the strip's prints rendered by
    :func:`aerophoto.render.render_strip`, one per photo, in order) the
    pixels are read from the prints instead (bilinear,
    :meth:`aerophoto.render.Photo.value_at`): the sheet then carries the
    prints' light fall-off and fiducial marks, as a glued fotoschema does.

    Parameters
    ----------
    ground : the virtual site (or :class:`aerophoto.terrain.RescaledRelief`); a terrain without
        ``sample`` (e.g. FlatTerrain) gets a plain chequer pattern.
    px_per_mm : float
        Resolution, pixels per sheet millimetre, 0 < r ≤ 20 (1 for a preview,
        4–6 for print).
    lattice_px : None or int, 2…64 — a preview's shortcut: rays cut with the terrain every ``lattice_px``
        pixels only, interpolated between (:func:`aerophoto.geometry.photo_to_dem`'s ``lattice_mm``).

    Returns
    -------
    image : ndarray (ny, nx) float32 in 0…1, row 0 at y_min (``imshow(origin="lower")``)
    extent : (x_min, x_max, y_min, y_max) in sheet mm

    See :func:`sheet_raster_bands` for the same raster glued a band of rows at a time.
    """
    image = extent = None
    for image, extent, _done in sheet_raster_bands(fs, ground, px_per_mm, photos=photos, extent_mm=extent_mm,
                                                   background=background, max_pixels=max_pixels, band_px=None,
                                                   lattice_px=lattice_px):
        pass
    return image, extent


@V.checked(fs=Fotoschema, ground=V.terrain(none=True), px_per_mm=V.number(0.0, 20.0, lo_open=True),
           background=V.number(), max_pixels=V.whole(1, 10**9), band_px=V.optional(V.whole(1, 10**9)),
           lattice_px=V.optional(V.whole(2, 64)))
def sheet_raster_bands(fs: Fotoschema, ground=None, px_per_mm: float = 2.0, *, photos=None, extent_mm=None,
                       background: float = 1.0, max_pixels: int = 20_000_000, band_px: int | None = 60_000,
                       lattice_px: int | None = None):
    """:func:`sheet_raster` a band of rows at a time: a generator of ``(image, extent, rows_done)``.

    The image is allocated once (``background`` everywhere) and each step glues the next band of whole rows, about
    ``band_px`` pixels (at least one row; ``None``: everything in one step), and yields the same array.  After the
    last step the image is :func:`sheet_raster`'s (to the ray–terrain tolerance, 0.1 mm on the ground, far below a
    pixel).  A live demo glues a large sheet this way, one band per turn of the event loop, so that a slider moved
    meanwhile is served within one band (about 15 ms) and the rest can be abandoned.
    """
    r = check_positive("px_per_mm", px_per_mm, unit="px/mm", hi=20.0)
    x0, x1, y0, y1 = fs.extent_mm if extent_mm is None else extent_mm
    nx = max(1, int(math.ceil((x1 - x0) * r)))
    ny = max(1, int(math.ceil((y1 - y0) * r)))
    if nx * ny > max_pixels:
        raise ValueError(f"px_per_mm = {r:g} gives {nx * ny} pixels; the valid range is at most {max_pixels} "
                         f"(px_per_mm ≤ {math.sqrt(max_pixels / ((x1 - x0) * (y1 - y0))):.2f})")
    if photos is not None and len(photos) != len(fs.poses):
        raise ValueError(f"photos has {len(photos)} prints; the valid input is one per photo ({len(fs.poses)})")
    x1, y1 = x0 + nx / r, y0 + ny / r
    extent = (x0, x1, y0, y1)
    xs = x0 + (np.arange(nx) + 0.5) / r
    ys = y0 + (np.arange(ny) + 0.5) / r
    image = np.full((ny, nx), background, dtype=np.float32)
    h = fs.camera.half_mm
    sampler = getattr(ground, "sample", None)
    dem = g.as_terrain(ground, 0.0)
    level = 0
    if sampler is not None and hasattr(ground, "level_for"):
        level = ground.level_for(fs.m_design / r / 1000.0)  # ground size of a sheet pixel, m
    inverse = [T.inverse() for T in fs.to_sheet]
    cuts = [s.cut_mm for s in fs.seams]
    rows = ny if band_px is None else max(1, int(band_px) // nx)
    for r0 in range(0, ny, rows):
        r1 = min(ny, r0 + rows)
        # each pixel's working area (Fotoschema.photo_index): a row has one y, so a cut's x is found once a row
        idx = np.zeros((r1 - r0, nx), dtype=int)
        for c in cuts:
            idx += xs[None, :] > np.interp(ys[r0:r1], c[:, 1], c[:, 0])[:, None]
        out = image[r0:r1].reshape(-1)  # a view: written in place
        for i, (pose, T) in enumerate(zip(fs.poses, inverse)):
            sel = np.flatnonzero(idx == i)
            row, col = np.divmod(sel, nx)
            xy = T.apply(np.column_stack([xs[col], ys[r0 + row]]))  # photo mm
            ins = np.abs(xy) <= h
            ins = ins[:, 0] & ins[:, 1]  # (np.all(axis=1) on two columns costs 20× more)
            sel, xy = sel[ins], xy[ins]
            if not sel.size:
                continue
            if photos is not None:
                out[sel] = photos[i].value_at(xy)
                continue
            G = g.photo_to_dem(fs.camera, pose, xy, dem, lattice_mm=None if lattice_px is None else lattice_px / r)
            out[sel] = sampler(G[:, 0], G[:, 1], level, outside=background) if sampler is not None \
                else _pattern(G[:, 0], G[:, 1])
        yield image, extent, r1
