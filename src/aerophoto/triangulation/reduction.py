"""Reducing a free strip to the plan: coefficients, corrections, the strip laid on the base (guide §7 steps 8–9, §13 steps 8–9).

The free strip (:func:`aerophoto.triangulation.strip.lay_free_strip`) has an
arbitrary scale.  Reduction (редуцирование) brings it to the plan's:

* :func:`reduction_coefficients` — k = l_base/l_template per base between
  control points, their mean and spread against 0.003 (0.006 on a short
  base): tables 8 and 12;
* :func:`reduction_corrections` — v = r·(k − 1) from a central working centre
  (formula 12.3 of §13): tables 9 and 13;
* :func:`reduce_strip` — both on a free strip, then the rotation and shift
  that lay the corrected control points on the base, with the control
  residuals checked against 0.4 mm.

Distances are plan mm at 1/M on the base and template mm on the free strip;
ground coordinates in metres.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import _validate as V
from .. import plane
from .._validate import check_int_range, check_range
from .strip import FreeStrip

__all__ = [
    "K_SPREAD_TOL",
    "K_SPREAD_TOL_SHORT",
    "SHORT_BASE_MM",
    "CONTROL_TOL_MM",
    "ReductionCoefficients",
    "ReductionCorrections",
    "Reduction",
    "reduction_coefficients",
    "reduction_corrections",
    "reduce_strip",
]

#: the largest deviation of a base's reduction coefficient from the mean (guide §7 step 8, §13 step 8)
K_SPREAD_TOL = 0.003
#: … on a short base (guide §13 step 8)
K_SPREAD_TOL_SHORT = 0.006
#: a base shorter than this (plan mm) is "short": there 0.003·l would be below the 0.4 mm the
#: graphical work can hold, so the guide's relaxed 0.006 applies.  0.4 / 0.003 = 133.3 mm.
SHORT_BASE_MM = 0.4 / K_SPREAD_TOL
#: the largest residual of a control point after the reduced strip is laid on the base (guide §13 step 9)
CONTROL_TOL_MM = 0.4


def _plan_mm(XY_m, M, origin_m):
    """Ground X, Y (m), shape (..., 2) → plan mm at 1/M from the plan's origin ``origin_m`` (m)."""
    return (np.asarray(XY_m, dtype=float) - origin_m) * 1000.0 / M


@dataclass(frozen=True)
class ReductionCoefficients:
    """Reduction coefficients per base (guide §7 table 8, §13 table 12).

    Attributes
    ----------
    bases : tuple of (str, str)
        The control-point pairs.
    l_base_mm : ndarray (B,)
        Distance on the base (основа), plan mm at 1/M, from the coordinates.
    l_template_mm : ndarray (B,)
        Distance on the free strip (общая восковка), template mm.
    k : ndarray (B,)
        k = l_base / l_template (guide's R in §7, k_ред in §13).
    k_mean : float
        Mean coefficient (the guide's "R составляет …", "средний k_ред").
    dk : ndarray (B,)
        Δk = k − k_mean (table 8's ΔK).
    short : ndarray of bool (B,)
        l_base < ``short_base_mm`` (see :data:`SHORT_BASE_MM`).
    tol : ndarray (B,)
        0.003, or 0.006 on a short base.
    """

    bases: tuple
    l_base_mm: np.ndarray
    l_template_mm: np.ndarray
    k: np.ndarray
    k_mean: float
    dk: np.ndarray
    short: np.ndarray
    tol: np.ndarray
    short_base_mm: float

    @property
    def ok(self) -> np.ndarray:
        """Per base: |Δk| within its tolerance."""
        return np.abs(self.dk) <= self.tol + 1e-12

    @property
    def spread(self) -> float:
        """The largest |Δk| (the guide's "колебания")."""
        return float(np.max(np.abs(self.dk)))

    @property
    def k_range(self) -> float:
        """max k − min k."""
        return float(np.max(self.k) - np.min(self.k))

    @property
    def all_ok(self) -> bool:
        return bool(np.all(self.ok))

    def table(self) -> pd.DataFrame:
        """Laid out like tables 8 and 12: base, l_осн, l_воск, k, Δk, tolerance, ok."""
        return pd.DataFrame(
            {
                "l_base (l_осн), mm": self.l_base_mm,
                "l_template (l_воск), mm": self.l_template_mm,
                "k": self.k,
                "Δk": self.dk,
                "short base": self.short,
                "tolerance": self.tol,
                "within": self.ok,
            },
            index=pd.Index([f"{a} – {b}" for a, b in self.bases], name="base"),
        )


@V.checked(names=V.names(min_len=2), base_mm=V.points(2, min_points=2), template_mm=V.points(2, min_points=2),
           short_base_mm=V.number(0.0, lo_open=True), tol=V.number(0.0, 1.0), tol_short=V.number(0.0, 1.0))
def reduction_coefficients(names, base_mm, template_mm, *, pairs="all", short_base_mm: float = SHORT_BASE_MM,
                           tol: float = K_SPREAD_TOL, tol_short: float = K_SPREAD_TOL_SHORT) -> ReductionCoefficients:
    """Reduction coefficients k = l_base / l_template over pairs of control points (guide §7, §13 step 8).

    Parameters
    ----------
    names : sequence of str, length C
    base_mm : array_like, shape (C, 2)
        Control points on the base (plan mm).
    template_mm : array_like, shape (C, 2)
        The same points on the free strip (template mm).
    pairs : "all", "perimeter" or a sequence of (i, j) / (name, name)
        "all" — every pair, like table 12; "perimeter" — the closed ring
        0–1–…–(C−1)–0 in the given order, like table 8.
    """
    names = [str(n) for n in names]
    B = np.asarray(base_mm, dtype=float).reshape(-1, 2)
    T = np.asarray(template_mm, dtype=float).reshape(-1, 2)
    C = len(names)
    if C < 2 or len(B) != C or len(T) != C:
        raise ValueError(f"reduction needs at least 2 control points with base and template positions; got {C}, {len(B)}, {len(T)}")
    if isinstance(pairs, str):
        if pairs == "all":
            pr = [(i, j) for i in range(C) for j in range(i + 1, C)]
        elif pairs == "perimeter":
            pr = [(i, (i + 1) % C) for i in range(C)] if C > 2 else [(0, 1)]
        else:
            raise ValueError(f"pairs = {pairs!r}; valid: 'all', 'perimeter' or a list of pairs")
    else:
        pr = []
        for a, b in pairs:
            ia = names.index(a) if isinstance(a, str) else int(a)
            ib = names.index(b) if isinstance(b, str) else int(b)
            pr.append((ia, ib))
    lb = np.array([np.hypot(*(B[j] - B[i])) for i, j in pr])
    lt = np.array([np.hypot(*(T[j] - T[i])) for i, j in pr])
    if np.any(lt <= 0):
        raise ValueError("two control points coincide on the template: a base of zero length")
    k = lb / lt
    km = float(np.mean(k))
    short = lb < short_base_mm
    return ReductionCoefficients(tuple((names[i], names[j]) for i, j in pr), lb, lt, k, km, k - km, short,
                                 np.where(short, tol_short, tol), float(short_base_mm))


@dataclass(frozen=True)
class ReductionCorrections:
    """Corrections for reduction v = r·(k − 1) (guide §7 table 9, §13 table 13, formula 12.3).

    Attributes
    ----------
    names : tuple of str, length P
    centre : str
        The working centre taken as the centre of the whole strip (полюс).
    k : float
    r_mm : ndarray (P,)
        Distance from the centre to each point on the free strip, mm.
    v_mm : ndarray (P,)
        v = r·(k − 1): laid off away from the centre when positive, towards it when negative.
    """

    names: tuple
    centre: str
    k: float
    r_mm: np.ndarray
    v_mm: np.ndarray

    def table(self, wide: bool = False) -> pd.DataFrame:
        """Table 13's layout (one row a point); ``wide=True`` gives table 9's (one column a point)."""
        df = pd.DataFrame({"r, mm": self.r_mm, "v, mm": self.v_mm},
                          index=pd.Index(list(self.names), name=f"from centre {self.centre}"))
        return df.T if wide else df


@V.checked(names=V.names(), r_mm=V.array(ndim=1))
def reduction_corrections(names, r_mm, k: float, centre: str = "") -> ReductionCorrections:
    """v = r·(k − 1) for given distances r (mm) and coefficient k (guide formula 12.3)."""
    kk = check_range("k", k, 0.0, 100.0, lo_open=True)
    r = np.asarray(r_mm, dtype=float)
    if np.any(r < 0):
        raise ValueError(f"r_mm has a negative value {float(r.min()):g}; the valid range is r_mm ≥ 0 (a distance)")
    return ReductionCorrections(tuple(str(n) for n in names), str(centre), kk, r, r * (kk - 1.0))


@dataclass(frozen=True)
class Reduction:
    """A free strip reduced to the plan (guide §13 steps 8–9).

    Attributes
    ----------
    strip : FreeStrip
    M : float
        Plan scale denominator.
    origin_m : ndarray (2,)
        Ground X, Y of the plan's origin (plan mm = (ground − origin)·1000/M).
    control : ndarray of int
        Indices of the control points used.
    coefficients : ReductionCoefficients
    corrections : ReductionCorrections
    centre_index : int
        Point index of the chosen central working centre.
    reduced_mm : ndarray (P, 2)
        Points moved by their corrections (still in the free strip's frame).
    rotation_deg : float, translation_mm : ndarray (2,)
        The rigid motion laying the corrected control points on the base.
    plan_mm : ndarray (P, 2)
        Every point on the plan after reduction, mm.
    truth_plan_mm : ndarray (P, 2)
        True positions on the plan, mm.
    """

    strip: FreeStrip
    M: float
    origin_m: np.ndarray
    control: np.ndarray
    coefficients: ReductionCoefficients
    corrections: ReductionCorrections
    centre_index: int
    reduced_mm: np.ndarray
    rotation_deg: float
    translation_mm: np.ndarray
    plan_mm: np.ndarray
    truth_plan_mm: np.ndarray

    @property
    def k(self) -> float:
        return self.coefficients.k_mean

    @property
    def base_control_mm(self) -> np.ndarray:
        """The control points on the base, plan mm, shape (C, 2)."""
        return self.truth_plan_mm[self.control]

    @property
    def control_residuals_mm(self) -> np.ndarray:
        """Length of (reduced control point on the plan − base), mm, shape (C,)."""
        return np.hypot(*(self.plan_mm[self.control] - self.base_control_mm).T)

    @property
    def errors_mm(self) -> np.ndarray:
        """Length of (reduced position − truth) for every point on the plan, mm, shape (P,)."""
        return np.hypot(*(self.plan_mm - self.truth_plan_mm).T)

    @property
    def max_control_residual_mm(self) -> float:
        return float(np.max(self.control_residuals_mm))

    @property
    def control_ok(self) -> bool:
        return bool(self.max_control_residual_mm <= CONTROL_TOL_MM)

    def to_strip_frame(self, plan_mm) -> np.ndarray:
        """Plan mm → the free strip's frame (undoing the rigid motion and the scaling about the centre)."""
        a = math.radians(self.rotation_deg)
        R = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        red = (np.asarray(plan_mm, dtype=float) - self.translation_mm) @ R
        C = self.strip.points_mm[self.centre_index]
        return C + (red - C) / self.k

    def table(self) -> pd.DataFrame:
        """Every point after reduction: r, v, plan x, y, error against the truth; control residuals checked."""
        pts = self.strip.points
        ctl = set(self.control.tolist())
        err = self.errors_mm
        return pd.DataFrame(
            {
                "kind": list(pts.kinds),
                "r, mm": self.corrections.r_mm,
                "v, mm": self.corrections.v_mm,
                "x plan, mm": self.plan_mm[:, 0],
                "y plan, mm": self.plan_mm[:, 1],
                "error, mm": err,
                f"control ≤ {CONTROL_TOL_MM} mm": [bool(err[i] <= CONTROL_TOL_MM) if i in ctl else None for i in range(len(pts))],
            },
            index=pd.Index(list(pts.names), name="point"),
        )


@V.checked(strip=FreeStrip, short_base_mm=V.number(0.0, lo_open=True), control=V.optional(V.points(2)),
           origin_m=V.optional(V.point(2)))
def reduce_strip(
    strip: FreeStrip,
    *,
    M: float = 10000.0,
    centre=None,
    pairs="all",
    control=None,
    origin_m=None,
    short_base_mm: float = SHORT_BASE_MM,
) -> Reduction:
    """Reduce a free strip to the plan scale and lay it on the base (guide §13 steps 8–9).

    1. the control points are plotted on the base from their coordinates
       (plan mm at 1/M); the distances between them on the base and on the
       free strip give k = l_base/l_template per base and the mean k
       (table 12), with the spread checked (≤ 0.003; ≤ 0.006 for short bases);
    2. one working centre is the centre of the whole strip (default: the
       middle one, "37 or 38"); from it every point's distance r and its
       correction v = r·(k − 1) (table 13) — positive v moves the point away
       from the centre, negative towards it: the points are scaled by k
       about the centre;
    3. the corrected strip is laid on the base by matching the corrected
       control points: the best rotation and shift (least squares; no further
       scaling), and the control residuals are checked against 0.4 mm.

    Where the centre is does not change the residuals — scaling about another
    point differs by a shift, which step 3 absorbs; it only changes the
    corrections one has to lay off (smallest about a middle centre).

    Parameters
    ----------
    strip : FreeStrip
    M : float
        Plan scale denominator (1/M; guide 1/10000), 100 ≤ M ≤ 1e6.
    centre : int or str, optional
        The central working centre: template index (0-based) or its name.
    pairs : see :func:`reduction_coefficients`.
    control : sequence of str, optional
        Names of the control points to use (default: all intersected ones).
    origin_m : (2,), optional
        Ground X, Y of the plan origin (default: the first control point
        rounded down to 100 m).
    """
    Mv = check_range("M", M, 100.0, 1e6, unit="plan scale denominator")
    pts = strip.points
    N = strip.templates.n_photos
    cidx = pts.centre_index
    if centre is None:
        ci = int(cidx[(N - 1) // 2])
    elif isinstance(centre, str):
        ci = pts.index(centre)
        if pts.kinds[ci] != "centre":
            raise ValueError(f"centre = {centre!r} is a {pts.kinds[ci]}; the reduction centre must be a working centre")
    else:
        t = check_int_range("centre", centre, 0, N - 1)
        ci = int(cidx[t])
    ok = np.all(np.isfinite(strip.points_mm), axis=1)
    if control is None:
        ctl = np.array([i for i in np.flatnonzero(pts.mask("control")) if ok[i]], dtype=int)
    else:
        ctl = np.array([pts.index(n) for n in control], dtype=int)
        bad = [pts.names[i] for i in ctl if not ok[i]]
        if bad:
            raise ValueError(f"control points {bad} are not intersected on the free strip (fewer than two rays)")
    if len(ctl) < 2:
        raise ValueError(f"{len(ctl)} control point(s) on the free strip; the reduction needs at least 2")
    XY = pts.XYZ_m[:, :2]
    if origin_m is None:
        origin = np.floor(XY[ctl[0]] / 100.0) * 100.0
    else:
        origin = np.asarray(origin_m, dtype=float).reshape(2)
    truth_plan = _plan_mm(XY, Mv, origin)
    coef = reduction_coefficients([pts.names[i] for i in ctl], truth_plan[ctl], strip.points_mm[ctl], pairs=pairs,
                                  short_base_mm=short_base_mm)
    k = coef.k_mean
    Cc = strip.points_mm[ci]
    r = np.hypot(*(strip.points_mm - Cc).T)
    corr = ReductionCorrections(pts.names, pts.names[ci], k, r, r * (k - 1.0))
    reduced = Cc + k * (strip.points_mm - Cc)
    T = plane.fit_similarity(reduced[ctl], truth_plan[ctl]).matrix()  # rotation + shift, no scale
    R, t = T[:2, :2], T[:2, 2]
    plan = reduced @ R.T + t
    rot = math.degrees(math.atan2(R[1, 0], R[0, 0]))
    return Reduction(strip, Mv, origin, ctl, coef, corr, ci, reduced, rot, t, plan, truth_plan)


