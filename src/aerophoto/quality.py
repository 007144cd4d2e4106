"""Judging a finished aerial survey: the photogrammetric quality checks (guide §3).

After a flight the technician lays the contact prints of each strip on a board,
overlapping neighbours so that the same ground detail coincides (the rough
mosaic, накидной монтаж), and measures on it with a ruler, a protractor and the
circular level's image whether the survey meets the specification.  This
module does the same on simulated photos: every quantity is *measured* from
the photos' geometry as a technician would measure it on the prints (overlap
widths, principal points transferred to the neighbour through conjugate ground
points, angles between the print's side and the base) and set beside the
simulation's truth.

The criteria (guide §3, items 3.1–4)
------------------------------------
* forward overlap P_x = a/b·100 % (3.1): reject below 56 %;
* side overlap P_y = c/b·100 % (3.2): reject below 20 %;
* strip straightness n = l/L·100 % (3.3): at most 2 % when H > 750 m
  (3 % below, the book's assumption¹);
* crab angle φ (отклонение базиса), the angle between the print's long side
  and the base: at most 5° at f = 100 mm, 7° at 140 mm, 10° at 200 mm (other
  focal lengths: :func:`crab_limit_deg`);
* tilt α, read on the circular level in divisions of 30′: at most 3°;
* scale difference Δm/m = (b1 − b2)/b1·100 % (3.4): "up to 2–3 %" — the book
  rejects above 3 % and flags values above 2 % as near the limit;
* flying-height deviation (H − H₀)/H₀·100 %: at most 3 %.

¹ The guide states only the H > 750 m case (its "when H > 750 m" implies a
looser limit for lower flights without giving it).  The book assumes 3 % there
and marks it as an assumption in every table that uses it.

Here ``b`` is the side of the frame (18 cm), ``a`` and ``c`` the widths of
the forward and side overlap measured on the rough mosaic, ``L`` the distance
between the principal points of the first and last photos of a strip, ``l``
the deviation of a middle photo's principal point from that line, and b1, b2
the photo bases measured on the two photos of a pair (each from its own
principal point to the neighbour's principal point transferred onto it).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from . import _validate as V
from . import geometry as g
from ._validate import check_int_range, check_positive
from ._digits import whole

__all__ = [
    "PX_MIN_PERCENT",
    "PY_MIN_PERCENT",
    "STRAIGHTNESS_MAX_PERCENT",
    "STRAIGHTNESS_MAX_LOW_PERCENT",
    "STRAIGHTNESS_H_THRESHOLD_M",
    "CRAB_LIMITS_DEG",
    "TILT_MAX_DEG",
    "LEVEL_DIVISION_ARCMIN",
    "SCALE_DIFF_MAX_PERCENT",
    "SCALE_DIFF_WARN_PERCENT",
    "HEIGHT_DEV_MAX_PERCENT",
    "overlap_percent",
    "straightness_percent",
    "straightness_limit_percent",
    "crab_limit_deg",
    "level_reading_deg",
    "scale_difference_percent",
    "height_deviation_percent",
    "measure_overlap",
    "measure_base",
    "measure_crab_deg",
    "measure_straightness",
    "measure_flying_height",
    "PhotoCheck",
    "PairCheck",
    "StripCheck",
    "QualityReport",
    "assess_flight",
    "NA_SIMULATED",
    "NOT_MEASURED",
]

#: guide §3, item 3.1: negatives with a forward overlap below this are rejected (брак), %
PX_MIN_PERCENT = 56.0
#: guide §3, item 3.1: the side-overlap rejection threshold, %
PY_MIN_PERCENT = 20.0
#: guide §3, item 3.2: the largest relative deviation n of a strip when H > 750 m, %
STRAIGHTNESS_MAX_PERCENT = 2.0
#: not in the guide: the book's assumed limit for flights at H ≤ 750 m, %
STRAIGHTNESS_MAX_LOW_PERCENT = 3.0
#: the flying height above which the guide's 2 % applies, m
STRAIGHTNESS_H_THRESHOLD_M = 750.0
#: guide §3, item 3.3: crab-angle limits by focal length, f (mm) → φ_max (°)
CRAB_LIMITS_DEG = {100.0: 5.0, 140.0: 7.0, 200.0: 10.0}
#: guide §3, item 3.4: the largest tilt of a planimetric survey, °
TILT_MAX_DEG = 3.0
#: guide §3, item 3.4: one division of the camera's circular level, arc-minutes
LEVEL_DIVISION_ARCMIN = 30.0
#: guide §3, item 4: "up to 2–3 %" — the book rejects above 3 % and flags above 2 %
SCALE_DIFF_MAX_PERCENT = 3.0
SCALE_DIFF_WARN_PERCENT = 2.0
#: guide §3, item 4: the largest deviation of a photo's flying height from the design height, %
HEIGHT_DEV_MAX_PERCENT = 3.0


# =========================================================================== the formulas
@V.checked(a_mm=V.values(), b_mm=V.values(0.0, lo_open=True))
def overlap_percent(a_mm, b_mm=180.0):
    """Overlap in percent of the frame side, guide §3 formulas (3.1) and (3.2).

        P_x = a/b·100 %,   P_y = c/b·100 %

    Parameters
    ----------
    a_mm : float or array_like
        Width a (forward) or c (side) of the overlap measured on the rough
        mosaic, mm; 0 ≤ a ≤ b.
    b_mm : float
        Side b of the frame, mm (18 cm = 180 mm).

    Returns
    -------
    float or ndarray : the overlap P in %.
    """
    b = check_positive("b_mm", b_mm, unit="mm")
    a = np.asarray(a_mm, dtype=float)
    if np.any(~np.isfinite(a)) or np.any(a < 0) or np.any(a > b):
        bad = a[~((a >= 0) & (a <= b))] if a.ndim else a
        raise ValueError(f"a_mm = {np.ravel(bad)[0]:g} is outside the valid range 0 ≤ a_mm ≤ b_mm = {b:g} (mm)")
    out = a / b * 100.0
    return float(out) if out.ndim == 0 else out


@V.checked(l_mm=V.values(), L_mm=V.values(0.0, lo_open=True))
def straightness_percent(l_mm, L_mm):
    """Relative deviation of a strip from a straight line, guide §3 formula (3.3).

        n = l/L·100 %

    Parameters
    ----------
    l_mm : float or array_like
        Deviation l of a middle photo's principal point from the line joining
        the principal points of the first and last photos, mm (≥ 0).
    L_mm : float
        Length L of that line, mm (> 0).  Any common unit works: n is a ratio.
    """
    L = check_positive("L_mm", L_mm, unit="mm")
    l = np.asarray(l_mm, dtype=float)
    if np.any(~np.isfinite(l)) or np.any(l < 0):
        raise ValueError(f"l_mm = {np.ravel(l)[0]:g} is outside the valid range 0 ≤ l_mm (mm)")
    out = l / L * 100.0
    return float(out) if out.ndim == 0 else out


def straightness_limit_percent(H_m: float) -> float:
    """Tolerance on n: 2 % when H > 750 m (guide §3, item 3.2), else 3 % (the book's assumption)."""
    H = check_positive("H_m", H_m, unit="m")
    return STRAIGHTNESS_MAX_PERCENT if H > STRAIGHTNESS_H_THRESHOLD_M else STRAIGHTNESS_MAX_LOW_PERCENT


def crab_limit_deg(f_mm: float) -> float:
    """The largest allowed crab angle φ (отклонение базиса от направления маршрута) for focal length f.

    The guide (§3, item 3.3) lists three cameras: 5° for f = 100 mm, 7° for
    140 mm and 10° for 200 mm.  The three pairs lie exactly on one straight
    line, φ_max = f/20 (degrees, f in mm), so the book interpolates linearly
    between them — which is that line — and holds the end values outside the
    listed range: 5° for f < 100 mm and 10° for f > 200 mm (no more latitude
    than the guide grants its longest camera).

    Parameters
    ----------
    f_mm : float
        Focal length f, mm (> 0).

    Returns
    -------
    float : φ_max in degrees.
    """
    f = check_positive("f_mm", f_mm, unit="mm", hi=g.MAX_F_MM)
    fs = np.array(sorted(CRAB_LIMITS_DEG))
    lim = np.array([CRAB_LIMITS_DEG[k] for k in fs])
    return float(np.interp(f, fs, lim))


@V.checked(alpha_deg=V.values())
def level_reading_deg(alpha_deg, division_arcmin: float = LEVEL_DIVISION_ARCMIN):
    """The tilt as read from the circular level imaged on the photo (guide §3, item 3.4).

    The bubble's offset is read to the nearest division of the level (30′ on
    the guide's camera), so the reading is α rounded to a whole number of
    divisions.  A true tilt of 3.2° therefore reads 3°00′ and passes; the
    reading's own uncertainty is half a division (±15′).

    Parameters
    ----------
    alpha_deg : float or array_like
        True tilt α, degrees (|α| < 90).
    division_arcmin : float
        Value of one division, arc-minutes (> 0).

    Returns
    -------
    float or ndarray : the reading in degrees (a multiple of the division).
    """
    d = check_positive("division_arcmin", division_arcmin, unit="′", hi=600) / 60.0
    a = np.abs(np.asarray(alpha_deg, dtype=float))
    if np.any(~np.isfinite(a)) or np.any(a >= 90):
        raise ValueError(f"alpha_deg = {np.ravel(a)[0]:g} is outside the valid range -90 < alpha_deg < 90 (degrees)")
    out = np.floor(a / d + 0.5) * d  # round half up: 0.25° reads 0°30′
    return float(out) if out.ndim == 0 else out


@V.checked(b1_mm=V.values(0.0, lo_open=True), b2_mm=V.values(0.0, lo_open=True))
def scale_difference_percent(b1_mm, b2_mm):
    """Scale difference of two neighbouring photos, guide §3 formula (3.4).

        Δm/m = (b1 − b2)/b1·100 %

    Parameters
    ----------
    b1_mm, b2_mm : float or array_like
        The photo base measured on the first and on the second photo of the
        pair (from its principal point to the neighbour's principal point
        transferred onto it), mm, to 0.1 mm in the guide (> 0).

    Returns
    -------
    float or ndarray : Δm/m in %, signed (positive when the second photo is at
    the smaller scale, i.e. was taken from higher up).
    """
    b1 = np.asarray(b1_mm, dtype=float)
    b2 = np.asarray(b2_mm, dtype=float)
    for name, b in (("b1_mm", b1), ("b2_mm", b2)):
        if np.any(~np.isfinite(b)) or np.any(b <= 0):
            raise ValueError(f"{name} = {np.ravel(b)[0]:g} is outside the valid range 0 < {name} (mm)")
    out = (b1 - b2) / b1 * 100.0
    return float(out) if out.ndim == 0 else out


@V.checked(H_m=V.values(0.0, lo_open=True))
def height_deviation_percent(H_m, H_design_m: float):
    """Deviation of the flying height from the design height, in % of the design height (guide §3, item 4).

        ΔH/H₀ = (H − H₀)/H₀·100 %,  allowed up to 3 % in size.
    """
    H0 = check_positive("H_design_m", H_design_m, unit="m")
    H = np.asarray(H_m, dtype=float)
    if np.any(~np.isfinite(H)) or np.any(H <= 0):
        raise ValueError(f"H_m = {np.ravel(H)[0]:g} is outside the valid range 0 < H_m (m)")
    out = (H - H0) / H0 * 100.0
    return float(out) if out.ndim == 0 else out


# =========================================================================== measuring on the photos
def _o_ground(camera: g.Camera, pose: g.Pose, dem, cache: dict | None) -> np.ndarray:
    """The ground point of a photo's principal point o (its ray cut with the terrain), metres, shape (3,).

    ``cache`` (a dict, or None) is shared by the measurements of one assessment on one terrain, so that each
    photo's o is intersected once, not once per measurement that needs it; the values are the same.
    """
    if cache is None:
        return g.photo_to_dem(camera, pose, np.zeros(2), g.as_terrain(dem))
    G = cache.get(pose)
    if G is None:
        G = cache[pose] = g.photo_to_dem(camera, pose, np.zeros(2), g.as_terrain(dem))
    return G


def _o_in(camera: g.Camera, pose_from: g.Pose, pose_to: g.Pose, dem, cache: dict | None) -> np.ndarray:
    """``pose_from``'s principal point transferred onto the photo taken from ``pose_to``, mm (as
    :func:`aerophoto.geometry.transfer_points` of (0, 0))."""
    return g.ground_to_photo(camera, pose_to, _o_ground(camera, pose_from, dem, cache))


@V.checked(camera=g.Camera, pose_a=g.Pose, pose_b=g.Pose, dem=V.terrain(none=True))
def measure_overlap(camera: g.Camera, pose_a: g.Pose, pose_b: g.Pose, dem, *, samples: int = 41,
                    nadirs: dict | None = None) -> float:
    """Width of the overlap of photo A with its neighbour B, measured on A as on a rough mosaic, mm.

    On the rough mosaic the technician measures, along the line of the
    principal points, the distance between the edge of A nearest to B and
    the edge of B nearest to A (guide §3, item 3.1, figure 3).  Here the edge
    of B is transferred onto A point by point through the terrain
    (:func:`aerophoto.geometry.transfer_points`); the overlap a is the distance, along A's axis
    that points at B, from B's transferred edge to A's own edge, read on the
    line through A's principal point.  Works for the forward overlap (a) and
    for the side overlap between strips (c) alike.

    ``nadirs`` (optional dict) keeps the photos' principal ground points between calls on the same terrain.

    Returns
    -------
    float : a (or c) in mm; negative if the photos leave a gap.
    """
    h = camera.half_mm
    ob_in_a = _o_in(camera, pose_b, pose_a, dem, nadirs)
    oa_in_b = _o_in(camera, pose_a, pose_b, dem, nadirs)
    k, s = g.photo_axis_towards(ob_in_a)
    kb, sb = g.photo_axis_towards(oa_in_b)
    t = np.linspace(-h, h, check_int_range("samples", samples, 2, 10_001))
    edge_b = np.empty((t.size, 2))
    edge_b[:, kb] = sb * h
    edge_b[:, 1 - kb] = t
    edge_in_a = g.transfer_points(camera, pose_b, pose_a, edge_b, dem)
    across = edge_in_a[:, 1 - k]
    along = edge_in_a[:, k]
    order = np.argsort(across)
    across, along = across[order], along[order]
    if across[0] <= 0.0 <= across[-1]:
        pos = float(np.interp(0.0, across, along))
    else:  # the edge does not cross A's axis line inside the frame: take its nearest point
        pos = float(along[np.argmin(np.abs(across))])
    return h - s * pos


@V.checked(camera=g.Camera, pose_a=g.Pose, pose_b=g.Pose, dem=V.terrain(none=True))
def measure_base(camera: g.Camera, pose_a: g.Pose, pose_b: g.Pose, dem, *,
                 nadirs: dict | None = None) -> tuple[float, float]:
    """The photo bases b1 (on A) and b2 (on B) of a pair, mm (guide §3, item 4, figure 5).

    Each photo's principal point is transferred onto the neighbour through
    its ground point (the guide transfers it by linear intersection,
    линейная засечка); b1 is the distance on A from o_A to the transferred
    o_B, b2 the distance on B from o_B to the transferred o_A.  ``nadirs``: as in :func:`measure_overlap`.
    """
    ob_in_a = _o_in(camera, pose_b, pose_a, dem, nadirs)
    oa_in_b = _o_in(camera, pose_a, pose_b, dem, nadirs)
    return float(np.hypot(*ob_in_a)), float(np.hypot(*oa_in_b))


def _wrap180(a):
    return (np.asarray(a, dtype=float) + 180.0) % 360.0 - 180.0


@V.checked(camera=g.Camera, pose_a=g.Pose, pose_b=g.Pose, dem=V.terrain(none=True))
def measure_crab_deg(camera: g.Camera, pose_a: g.Pose, pose_b: g.Pose, dem, *, nadirs: dict | None = None) -> float:
    """Crab angle φ of photo A: the angle between A's long side and the base to B, degrees (guide §3, item 3.3).

    The base is the line from A's principal point to B's principal point
    transferred onto A; the "long side" is the frame side most nearly along
    it.  Sign: positive when the photo's side is turned counter-clockwise
    from the base (the sign of :attr:`aerophoto.simulate.Shot.crab_deg`).  ``nadirs``: as in :func:`measure_overlap`.
    """
    u = _o_in(camera, pose_b, pose_a, dem, nadirs)
    k, s = g.photo_axis_towards(u)
    # the base's direction in A's photo frame, measured from the side's direction (axis k, sign s)
    side_angle = math.degrees(math.atan2(s if k == 1 else 0.0, s if k == 0 else 0.0))
    base_angle = math.degrees(math.atan2(u[1], u[0]))
    return float(_wrap180(side_angle - base_angle))


@V.checked(camera=g.Camera, poses=V.sequence(V.of_type(g.Pose), min_len=3), dem=V.terrain(none=True))
def measure_straightness(camera: g.Camera, poses, dem, m: float) -> dict:
    """Straightness of a strip from its principal points (guide §3, item 3.2, formula 3.3).

    The principal points are placed where a well-built rough mosaic puts them:
    at their ground points (ray of o cut with the terrain), drawn at the
    photo scale 1:m.  L joins the first and the last, l is each middle
    photo's distance from that line.

    Returns
    -------
    dict with ``L_mm`` (float), ``l_mm`` (ndarray, one per photo, 0 for the
    ends), ``n_percent`` (ndarray, per photo) and ``n_max_percent`` (the
    largest over the middle photos; the guide measures one central photo).
    """
    m = check_positive("m", m)
    O = np.array([g.photo_to_dem(camera, p, np.zeros(2), dem)[:2] for p in poses])
    return _straightness_of_points(O, m)


def _straightness_of_points(P_m, m):
    d = P_m[-1] - P_m[0]
    L = float(np.hypot(*d))
    if L == 0:
        raise ValueError("the first and last principal points coincide; a strip needs at least two distinct photos")
    u = d / L
    l = np.abs((P_m - P_m[0]) @ np.array([-u[1], u[0]]))
    l[[0, -1]] = 0.0
    L_mm = L * 1000.0 / m
    l_mm = l * 1000.0 / m
    n = l_mm / L_mm * 100.0
    n_max = float(n[1:-1].max()) if len(n) > 2 else 0.0
    return {"L_mm": L_mm, "l_mm": l_mm, "n_percent": n, "n_max_percent": n_max}


@V.checked(camera=g.Camera, pose=g.Pose, dem=V.terrain(), points_m=V.optional(V.points(3)))
def measure_flying_height(camera: g.Camera, pose: g.Pose, dem, *, points_m=None, n_points: int = 3) -> dict:
    """Flying height of one photo from the radio altimeter and 2–3 identified points (guide §3, item 4).

    The radio altimeter gives the height of the aircraft above the ground
    directly below it, H_r = Z_S − Z(X_S, Y_S) (an ideal instrument here).
    The ground height under the aircraft is then taken, as the guide does,
    from 2–3 points identified on the photo and on the topographic map near
    the nadir point: their mean height Z̄.  The absolute height of the
    exposure is Z_S ≈ H_r + Z̄.

    Parameters
    ----------
    points_m : array_like, shape (k, 3), optional
        Catalogue of well-defined ground points (X, Y, Z in m) from which the
        ``n_points`` nearest to the nadir and imaged on the photo are taken.
        Without it the points are the ground points of three photo points
        25 mm from the nadir point n.

    Returns
    -------
    dict with ``H_radio_m``, ``Z_points_m`` (ndarray), ``Z_S_m`` (the estimate
    of the exposure's absolute height) and ``points_m`` (the points used).
    """
    n_points = check_int_range("n_points", n_points, 1, 10_000)
    Xs, Ys = pose.X_m, pose.Y_m
    Zg = float(np.asarray(dem.height(np.array([Xs]), np.array([Ys])))[0])
    H_radio = pose.Z_m - Zg
    pts = None
    if points_m is not None:
        P = np.asarray(points_m, dtype=float).reshape(-1, 3)
        front = ((P - pose.centre) @ g.rotation_matrix(pose))[:, 2] < 0
        P = P[front]
        if len(P):
            inside = camera.inside(g.ground_to_photo(camera, pose, P))
            P = P[inside]
        if len(P) >= 2:
            d = np.hypot(P[:, 0] - Xs, P[:, 1] - Ys)
            pts = P[np.argsort(d)[: int(n_points)]]
    if pts is None:
        n_xy = g.nadir_point(camera, pose)
        ang = np.radians([90.0, 210.0, 330.0])[: int(n_points)]
        xy = n_xy + 25.0 * np.column_stack([np.cos(ang), np.sin(ang)])
        pts = g.photo_to_dem(camera, pose, xy, dem)
    Zp = pts[:, 2]
    return {"H_radio_m": float(H_radio), "Z_points_m": Zp, "Z_S_m": float(H_radio + Zp.mean()), "points_m": pts}


# =========================================================================== the assessment
NA_SIMULATED = "n/a (simulated)"
#: shown in a table cell for a quantity a row does not have (the bases and scale difference of a side pair)
NOT_MEASURED = "—"


def _verdict(ok: bool, near: bool = False) -> str:
    if not ok:
        return "FAIL"
    return "pass (near limit)" if near else "pass"


@dataclass(frozen=True)
class PhotoCheck:
    """The checks of one photo (guide §3: tilt 3.4, crab 3.3, flying height 4).

    Angles in degrees, heights in metres, deviations in %.  ``*_true`` are the
    simulation's truth beside the measured values.
    """

    number: int
    strip: int
    alpha_read_deg: float
    alpha_true_deg: float
    crab_deg: float
    crab_true_deg: float
    crab_limit_deg: float
    H_radio_m: float
    H_est_m: float
    dH_percent: float
    dH_true_percent: float

    @property
    def tilt_ok(self) -> bool:
        return self.alpha_read_deg <= TILT_MAX_DEG

    @property
    def crab_ok(self) -> bool:
        return abs(self.crab_deg) <= self.crab_limit_deg

    @property
    def height_ok(self) -> bool:
        return abs(self.dH_percent) <= HEIGHT_DEV_MAX_PERCENT

    @property
    def ok(self) -> bool:
        return self.tilt_ok and self.crab_ok and self.height_ok


@dataclass(frozen=True)
class PairCheck:
    """The checks of a pair of neighbouring photos.

    ``kind`` is ``"forward"`` (same strip: overlap P_x and scale difference)
    or ``"side"`` (neighbouring strips: overlap P_y).  Lengths in mm on the
    photos, percentages in %.
    """

    kind: str
    numbers: tuple
    a_mm: float
    P_percent: float
    P_true_percent: float
    b1_mm: float = float("nan")
    b2_mm: float = float("nan")
    dm_percent: float = float("nan")
    dm_true_percent: float = float("nan")

    @property
    def overlap_limit_percent(self) -> float:
        return PX_MIN_PERCENT if self.kind == "forward" else PY_MIN_PERCENT

    @property
    def overlap_ok(self) -> bool:
        return self.P_percent >= self.overlap_limit_percent

    @property
    def scale_ok(self) -> bool:
        return self.kind != "forward" or abs(self.dm_percent) <= SCALE_DIFF_MAX_PERCENT

    @property
    def scale_near_limit(self) -> bool:
        return self.kind == "forward" and SCALE_DIFF_WARN_PERCENT < abs(self.dm_percent) <= SCALE_DIFF_MAX_PERCENT

    @property
    def ok(self) -> bool:
        return self.overlap_ok and self.scale_ok


@dataclass(frozen=True)
class StripCheck:
    """Straightness of one strip (guide §3, item 3.2): L and l in mm on the rough mosaic, n in %."""

    strip: int
    numbers: tuple
    L_mm: float
    l_mm: float
    n_percent: float
    n_true_percent: float
    limit_percent: float
    limit_from_guide: bool

    @property
    def ok(self) -> bool:
        return self.n_percent <= self.limit_percent


@dataclass(frozen=True)
class QualityReport:
    """The photogrammetric assessment of a flight (guide §3), with the verdicts and a conclusion.

    Attributes
    ----------
    photos : tuple[PhotoCheck, ...]
    pairs : tuple[PairCheck, ...]   forward pairs, then side pairs
    strips : tuple[StripCheck, ...]
    f_mm, H_design_m, m : the camera's focal length, the design flying height and scale
    """

    photos: tuple
    pairs: tuple
    strips: tuple
    f_mm: float
    H_design_m: float
    m: float
    photographic: dict = field(default_factory=dict)

    # ------------------------------------------------------------- verdicts
    @property
    def forward_pairs(self) -> list:
        return [p for p in self.pairs if p.kind == "forward"]

    @property
    def side_pairs(self) -> list:
        return [p for p in self.pairs if p.kind == "side"]

    def failures(self) -> list[str]:
        """One line per failed criterion (empty when the survey passes everything)."""
        out = []
        for p in self.forward_pairs:
            if not p.overlap_ok:
                out.append(f"forward overlap of photos {p.numbers[0]}–{p.numbers[1]} is {p.P_percent:.1f} % "
                           f"(< {PX_MIN_PERCENT:g} %)")
            if not p.scale_ok:
                out.append(f"scale difference of photos {p.numbers[0]}–{p.numbers[1]} is {p.dm_percent:+.1f} % "
                           f"(> {SCALE_DIFF_MAX_PERCENT:g} %)")
        for p in self.side_pairs:
            if not p.overlap_ok:
                out.append(f"side overlap of photos {p.numbers[0]}–{p.numbers[1]} is {p.P_percent:.1f} % "
                           f"(< {PY_MIN_PERCENT:g} %)")
        for s in self.strips:
            if not s.ok:
                out.append(f"strip {s.strip + 1} deviates from a straight line by n = {s.n_percent:.1f} % "
                           f"(> {s.limit_percent:g} %)")
        for ph in self.photos:
            if not ph.tilt_ok:
                out.append(f"photo {ph.number}: the level reads a tilt of {_dm(ph.alpha_read_deg)} (> {TILT_MAX_DEG:g}°)")
            if not ph.crab_ok:
                out.append(f"photo {ph.number}: crab angle {ph.crab_deg:+.1f}° (limit ±{ph.crab_limit_deg:g}° "
                           f"for f = {self.f_mm:g} mm)")
            if not ph.height_ok:
                out.append(f"photo {ph.number}: flying height off the design by {ph.dH_percent:+.1f} % "
                           f"(> {HEIGHT_DEV_MAX_PERCENT:g} %)")
        return out

    @property
    def ok(self) -> bool:
        return not self.failures()

    # ------------------------------------------------------------- tables
    def table(self) -> pd.DataFrame:
        """The guide's table 1 (visual control) extended by the photogrammetric checks of each photo."""
        rows = []
        for ph in self.photos:
            rows.append({
                "photo": ph.number,
                "sharpness": self.photographic.get("sharpness", NA_SIMULATED),
                "fine detail": self.photographic.get("detail", NA_SIMULATED),
                "defects": self.photographic.get("defects", NA_SIMULATED),
                "α read (level)": _dm(ph.alpha_read_deg),
                "α true, °": round(ph.alpha_true_deg, 2),
                "tilt ≤ 3°": _verdict(ph.tilt_ok),
                "φ crab, °": round(ph.crab_deg, 2),
                "φ limit, °": ph.crab_limit_deg,
                "crab": _verdict(ph.crab_ok),
                "ΔH, %": round(ph.dH_percent, 2),
                "ΔH true, %": round(ph.dH_true_percent, 2),
                "height ≤ 3 %": _verdict(ph.height_ok),
            })
        return pd.DataFrame(rows).set_index("photo")

    def pairs_table(self) -> pd.DataFrame:
        """Overlaps (3.1, 3.2) and scale differences (3.4) of neighbouring photos.

        One row per pair, forward pairs first.  The columns that a pair may
        lack — the bases b1, b2 and the scale differences of a side pair (they
        are measured along a strip only), a true overlap the flight does not
        know — are text at the precision shown (0.1 mm, 0.01 %, 0.1 %) with
        "—" where the pair has no such value.
        """
        rows = []
        for p in self.pairs:
            fwd = p.kind == "forward"
            rows.append({
                "pair": f"{p.numbers[0]}–{p.numbers[1]}",
                "kind": p.kind,
                "a (c), mm": round(p.a_mm, 1),
                "P, %": round(p.P_percent, 1),
                "P true, %": _text(p.P_true_percent, 1),
                "P limit, %": f"≥ {p.overlap_limit_percent:g}",
                "overlap": _verdict(p.overlap_ok),
                "b1, mm": _text(p.b1_mm, 1) if fwd else NOT_MEASURED,
                "b2, mm": _text(p.b2_mm, 1) if fwd else NOT_MEASURED,
                "Δm/m, %": _text(p.dm_percent, 2) if fwd else NOT_MEASURED,
                "Δm/m true, %": _text(p.dm_true_percent, 2) if fwd else NOT_MEASURED,
                "scale": _verdict(p.scale_ok, p.scale_near_limit) if fwd else NOT_MEASURED,
            })
        return pd.DataFrame(rows).set_index("pair")

    def strips_table(self) -> pd.DataFrame:
        """Straightness n = l/L·100 % of each strip (3.3)."""
        rows = []
        for s in self.strips:
            rows.append({
                "strip": s.strip + 1,
                "photos": f"{s.numbers[0]}–{s.numbers[-1]}",
                "L, mm": round(s.L_mm, 1),
                "l, mm": round(s.l_mm, 1),
                "n, %": round(s.n_percent, 2),
                "n true, %": round(s.n_true_percent, 2),
                "n limit, %": f"≤ {s.limit_percent:g}" + ("" if s.limit_from_guide else " (book's assumption, H ≤ 750 m)"),
                "straightness": _verdict(s.ok),
            })
        return pd.DataFrame(rows).set_index("strip")

    def summary_table(self) -> pd.DataFrame:
        """One row per criterion: the worst measured value, the tolerance and the verdict."""
        rows = []
        fp = self.forward_pairs
        if fp:
            worst = min(fp, key=lambda p: p.P_percent)
            rows.append(("forward overlap P_x (3.1)", f"{worst.P_percent:.1f} %", f"≥ {PX_MIN_PERCENT:g} %",
                         _verdict(all(p.overlap_ok for p in fp))))
        sp = self.side_pairs
        if sp:
            worst = min(sp, key=lambda p: p.P_percent)
            rows.append(("side overlap P_y (3.2)", f"{worst.P_percent:.1f} %", f"≥ {PY_MIN_PERCENT:g} %",
                         _verdict(all(p.overlap_ok for p in sp))))
        if self.strips:
            worst = max(self.strips, key=lambda s: s.n_percent)
            rows.append(("straightness n (3.3)", f"{worst.n_percent:.2f} %", f"≤ {worst.limit_percent:g} %",
                         _verdict(all(s.ok for s in self.strips))))
        if self.photos:
            lim = self.photos[0].crab_limit_deg
            worst = max(self.photos, key=lambda p: abs(p.crab_deg))
            rows.append(("crab angle φ", f"{worst.crab_deg:+.1f}°", f"≤ {lim:g}° (f = {self.f_mm:g} mm)",
                         _verdict(all(p.crab_ok for p in self.photos))))
            worst = max(self.photos, key=lambda p: p.alpha_read_deg)
            rows.append(("tilt α (level, 30′ divisions)", _dm(worst.alpha_read_deg), f"≤ {TILT_MAX_DEG:g}°",
                         _verdict(all(p.tilt_ok for p in self.photos))))
        if fp:
            worst = max(fp, key=lambda p: abs(p.dm_percent))
            rows.append(("scale difference Δm/m (3.4)", f"{worst.dm_percent:+.2f} %",
                         f"≤ {SCALE_DIFF_WARN_PERCENT:g}–{SCALE_DIFF_MAX_PERCENT:g} %",
                         _verdict(all(p.scale_ok for p in fp), any(p.scale_near_limit for p in fp))))
        if self.photos:
            worst = max(self.photos, key=lambda p: abs(p.dH_percent))
            rows.append(("flying-height deviation ΔH/H", f"{worst.dH_percent:+.2f} %", f"≤ {HEIGHT_DEV_MAX_PERCENT:g} %",
                         _verdict(all(p.height_ok for p in self.photos))))
        return pd.DataFrame(rows, columns=["criterion", "worst measured", "tolerance", "verdict"]).set_index("criterion")

    def conclusion(self) -> str:
        """The written conclusion on the survey's fitness (guide §3, items 5–6), generated from the verdicts."""
        n_ph = len(self.photos)
        n_st = len(self.strips)
        m_txt = whole(self.m)
        H_txt = whole(self.H_design_m)
        head = (f"{n_ph} photos in {n_st} strip{'s' if n_st != 1 else ''} were checked "
                f"(f = {self.f_mm:g} mm, design scale 1:{m_txt}, H = {H_txt} m).")
        photo_note = ("The photographic quality (sharpness, fine detail, defects) was not judged: the photos are "
                      "rendered from a virtual site and carry no photographic defects.")
        fails = self.failures()
        near = [p for p in self.forward_pairs if p.scale_near_limit]
        if not fails:
            text = [head, "Every photogrammetric criterion of guide §3 is met: overlaps, straightness of the strips, "
                          "crab angles, tilts, scale differences and flying heights are within tolerance."]
            if near:
                text.append("The scale difference of pair(s) " + ", ".join(f"{p.numbers[0]}–{p.numbers[1]}" for p in near)
                            + f" lies between {SCALE_DIFF_WARN_PERCENT:g} and {SCALE_DIFF_MAX_PERCENT:g} %, at the "
                              "edge of what the guide allows.")
            text += [photo_note, "Conclusion: the survey is photogrammetrically fit for land-management work "
                                 "(photo mosaics, photoplans, interpretation)."]
        else:
            text = [head, f"{len(fails)} criterion check{'s' if len(fails) != 1 else ''} failed:"]
            text += [f"  – {f};" for f in fails]
            reflight = any("overlap" in f or "strip" in f for f in fails)
            text.append(photo_note)
            if reflight:
                text.append("Conclusion: the survey is NOT fit as delivered — gaps in the overlaps or a bent strip "
                            "leave ground unphotographed or unusable for stereo; the affected strips must be re-flown.")
            else:
                text.append("Conclusion: the survey is NOT fit as delivered — the photos named above exceed the "
                            "tolerances and must be re-taken (or the work redone to a stricter standard, e.g. by "
                            "rectification, before a photoplan is made).")
        return "\n".join(text)


def _text(x: float, decimals: int) -> str:
    """A value of a table column that some rows lack: fixed decimals, or "—" when there is no value (NaN)."""
    x = float(x)
    return NOT_MEASURED if math.isnan(x) else f"{x:.{decimals}f}"


def _dm(deg: float) -> str:
    """Degrees as d°mm′ (for level readings)."""
    total = int(round(abs(deg) * 60.0))
    sign = "-" if deg < 0 else ""
    return f"{sign}{total // 60}°{total % 60:02d}′"


def _strips_of(flight):
    strips = getattr(flight, "strips", None)
    return tuple(strips) if strips is not None else (flight,)


def _nearest_neighbour_pairs(strip_a, strip_b):
    """For each photo of strip A, the photo of strip B whose centre is nearest (a side-overlap pair)."""
    ca = np.array([s.nominal.centre[:2] for s in strip_a.shots])
    cb = np.array([s.nominal.centre[:2] for s in strip_b.shots])
    d = np.hypot(ca[:, None, 0] - cb[None, :, 0], ca[:, None, 1] - cb[None, :, 1])
    return [(strip_a.shots[i], strip_b.shots[int(j)]) for i, j in enumerate(np.argmin(d, axis=1))]


@V.checked(flight=V.has_attrs("shots", what="a simulated flight (simulate.Strip or Block)"), dem=V.terrain(none=True),
           points_m=V.optional(V.points(3)))
def assess_flight(flight, dem=None, *, points_m=None, photographic: dict | None = None,
                  nadirs: dict | None = None) -> QualityReport:
    """Measure a simulated flight as the guide measures a rough mosaic (§3) and judge it.

    Parameters
    ----------
    flight : aerophoto.simulate.Strip or aerophoto.simulate.Block
        The photos (true orientations) and the design (f, m, H, p_x, p_y).
    dem : terrain, optional
        The ground the photos were taken of: anything with ``height(X, Y)``,
        ``z_min_m`` and ``z_max_m`` (the virtual site, or
        :class:`aerophoto.geometry.FlatTerrain`).  Default: flat ground at the
        flight's reference height.
    points_m : array_like, shape (k, 3), optional
        Catalogue of identified ground points (X, Y, Z in m) used for the
        flying-height check; default: ground points near each photo's nadir.
    photographic : dict, optional
        Values of the guide's visual-control columns ``sharpness``,
        ``detail``, ``defects``; default "n/a (simulated)".
    nadirs : dict, optional
        Filled with each photo's principal ground point (pose → X, Y, Z in m, shape (3,)), intersected once for
        all the measurements: a caller that draws the points reads them here instead of intersecting again.

    Returns
    -------
    QualityReport
    """
    strips = _strips_of(flight)
    if not strips or not strips[0].shots:
        raise ValueError("flight has no photos; the valid input is a Strip or Block with at least one photo")
    st0 = strips[0]
    cam = st0.camera
    z0 = st0.ground_Z_m
    dem = g.as_terrain(dem, z0)
    H0 = st0.H_m
    m = st0.m
    lim_crab = crab_limit_deg(cam.f_mm)
    nadirs = {} if nadirs is None else nadirs  # each photo's principal ground point, intersected once for all
    photos, pairs, strip_checks = [], [], []
    for st in strips:
        shots = st.shots
        n = len(shots)
        for i, s in enumerate(shots):
            j = i + 1 if i + 1 < n else i - 1
            if j >= 0 and j != i:
                crab = measure_crab_deg(cam, s.pose, shots[j].pose, dem, nadirs=nadirs)
                if j < i:  # the last photo: the base runs back to the previous one
                    crab = float(_wrap180(crab + 180.0)) if abs(crab) > 90 else crab
                dS = shots[j].pose.centre[:2] - s.pose.centre[:2]
                crab_true = float(_wrap180(s.pose.kappa_deg - math.degrees(math.atan2(dS[1], dS[0]))
                                           - (180.0 if j < i else 0.0)))
            else:
                crab, crab_true = 0.0, float(s.crab_deg)
            fh = measure_flying_height(cam, s.pose, dem, points_m=points_m)
            H_est = fh["Z_S_m"] - z0
            photos.append(PhotoCheck(
                number=s.number, strip=s.strip, alpha_read_deg=level_reading_deg(s.pose.alpha_deg),
                alpha_true_deg=abs(s.pose.alpha_deg), crab_deg=crab, crab_true_deg=crab_true,
                crab_limit_deg=lim_crab, H_radio_m=fh["H_radio_m"], H_est_m=H_est,
                dH_percent=height_deviation_percent(H_est, H0), dH_true_percent=s.height_error_percent))
        for a, b in zip(shots[:-1], shots[1:]):
            a_mm = measure_overlap(cam, a.pose, b.pose, dem, nadirs=nadirs)
            B = float(np.hypot(*(b.pose.centre[:2] - a.pose.centre[:2])))
            P_true = (1.0 - B / (cam.frame_mm / 1000.0 * a.m)) * 100.0
            b1, b2 = measure_base(cam, a.pose, b.pose, dem, nadirs=nadirs)
            pairs.append(PairCheck("forward", (a.number, b.number), a_mm, a_mm / cam.frame_mm * 100.0, P_true,
                                   b1, b2, scale_difference_percent(b1, b2), (b.H_m - a.H_m) / b.H_m * 100.0))
        if n >= 2:
            O = np.array([_o_ground(cam, s.pose, dem, nadirs)[:2] for s in shots])
            meas = _straightness_of_points(O, m)
            true = _straightness_of_points(st.centres_m[:, :2], m)
            k = int(np.argmax(meas["n_percent"]))
            strip_checks.append(StripCheck(
                strip=st.shots[0].strip, numbers=tuple(s.number for s in shots), L_mm=meas["L_mm"],
                l_mm=float(meas["l_mm"][k]), n_percent=meas["n_max_percent"], n_true_percent=true["n_max_percent"],
                limit_percent=straightness_limit_percent(H0), limit_from_guide=H0 > STRAIGHTNESS_H_THRESHOLD_M))
    py_design = getattr(flight, "py_percent", None)
    for sa, sb in zip(strips[:-1], strips[1:]):
        for a, b in _nearest_neighbour_pairs(sa, sb):
            c_mm = measure_overlap(cam, a.pose, b.pose, dem, nadirs=nadirs)
            side = cam.frame_mm / 1000.0 * a.m
            d = b.pose.centre[:2] - a.pose.centre[:2]
            across = abs(float(d @ np.array([-sa.direction[1], sa.direction[0]])))
            P_true = (1.0 - across / side) * 100.0 if py_design is not None else float("nan")
            pairs.append(PairCheck("side", (a.number, b.number), c_mm, c_mm / cam.frame_mm * 100.0, P_true))
    return QualityReport(tuple(photos), tuple(pairs), tuple(strip_checks), cam.f_mm, H0, m, dict(photographic or {}))
