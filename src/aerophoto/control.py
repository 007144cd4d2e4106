"""Ground control (планово-высотная привязка): the design of control points and their resection (guide §11).

Control design (проект привязки)
--------------------------------
Control points (опорные точки, опознаки) are ground points identified on
the photos whose coordinates are measured in the field.  *Dense* control
(сплошная привязка) gives every model (stereo pair) its own points; *sparse*
control (разреженная) puts them in rows across the strips (рядами поперёк
маршрутов) every n bases and lets phototriangulation fill in between
(guide §11; n from Zhukov's formula (13.1) of guide §13,
:func:`aerophoto.triangulation.zhukov_max_bases`).  A row lies in the triple
forward overlap round one photo of every strip (where three consecutive
photos see it); its points sit in the middle of each side overlap between
neighbouring strips and on both outer edges of the block, so every strip
has two points in every row (:func:`design_control`).

Marking (guide §11 steps 1–2)
-----------------------------
A control point is identified on the ground within 0.1 mm at the plan's
scale (:data:`IDENTIFICATION_MM`; :func:`identification_tolerance_m`),
pricked on the photo within 0.1 mm, and ringed there by two red concentric
circles 8 and 10 mm across (:data:`MARKING_CIRCLES_MM`); on the ground it is
fixed with a stake 0.3–0.5 m long in a ditched triangle of 1.2–1.5 m sides.

Resection (обратная засечка, the Snellius–Pothenot problem)
-----------------------------------------------------------
From the station P to be determined, three known points A, B, C are sighted
and two horizontal angles measured: β₁ from A to B and β₂ from B to C.  P is
the second meeting point of the two circles through (A, B) and (B, C) on
which those angles are seen (:func:`resect`).  A third angle, from C to a
fourth known point D, checks the solution (:func:`check_resection`).  When P
lies on the circle through A, B, C — the *danger circle* (опасный круг) —
the two circles coincide and P is not determined; near it, small angle
errors move P far (:attr:`Resection.metres_per_arcsec`).

Coordinates and angles
----------------------
Geodetic plane coordinates, as in the guide's §11 table: X north, Y east,
metres.  A direction angle (дирекционный угол) is counted clockwise from
+X: α = atan2(ΔY, ΔX), 0 ≤ α < 360°.  A horizontal angle measured at P
"from A to B" is α(P→B) − α(P→A), clockwise as a theodolite reads it,
0 ≤ β < 360°.  The virtual site's X east, Y north become geodetic
(X, Y) = (site Y, site X) with :func:`geodetic_from_site`.
Degrees at the public surface; :func:`dms` and :func:`format_dms` for
degrees, minutes and seconds.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from . import _validate as V
from ._validate import check_int_range, check_points, check_positive, check_range
from .triangulation import zhukov as _zhukov

__all__ = [
    "IDENTIFICATION_MM",
    "PRICKING_MM",
    "MARKING_CIRCLES_MM",
    "RHO_ARCSEC",
    "identification_tolerance_m",
    "marking_circles_ground_m",
    "geodetic_from_site",
    "site_from_geodetic",
    "dms",
    "from_dms",
    "format_dms",
    "direction_angle_deg",
    "horizontal_angle_deg",
    "danger_circle",
    "Resection",
    "resect",
    "resect_many",
    "ResectionCheck",
    "check_tolerance_arcsec",
    "check_resection",
    "control_rows",
    "ControlDesign",
    "design_control",
    "control_spacing_bases",
]

#: the error allowed in identifying a control point, mm at the plan's scale (guide §11 step 1)
IDENTIFICATION_MM = 0.1
#: the error allowed in pricking a control point on the photo, mm (guide §11 step 2, §13 step 2)
PRICKING_MM = 0.1
#: diameters of the two red concentric circles round a pricked control point, mm on the photo (guide §11 step 2)
MARKING_CIRCLES_MM = (8.0, 10.0)
#: ρ″, arc-seconds in a radian (206 264.8″)
RHO_ARCSEC = 180.0 * 3600.0 / math.pi


# --------------------------------------------------------------------------- marking
def identification_tolerance_m(M: float, tol_mm: float = IDENTIFICATION_MM) -> float:
    """The identification tolerance on the ground, m: ``tol_mm`` at the plan scale 1:M (1 m at 1:10 000)."""
    return check_positive("tol_mm", tol_mm, unit="mm", hi=100.0) * check_positive("M", M, hi=1e7) / 1000.0


def marking_circles_ground_m(m: float) -> tuple:
    """The ground diameters, m, of the 8 and 10 mm marking circles on a photo of scale 1:m."""
    mm = check_positive("m", m, hi=1e7)
    return tuple(d * mm / 1000.0 for d in MARKING_CIRCLES_MM)


# --------------------------------------------------------------------------- frames and angles
@V.checked(xy_m=V.array(last=2))
def geodetic_from_site(xy_m) -> np.ndarray:
    """Site coordinates (X east, Y north) → geodetic (X north, Y east): the two columns swapped, (…, 2)."""
    p = np.asarray(xy_m, dtype=float)
    return p[..., ::-1].copy()


site_from_geodetic = geodetic_from_site  # the swap is its own inverse


def dms(angle_deg) -> tuple:
    """An angle in degrees → (degrees, minutes, seconds) with the sign on the degrees (seconds not rounded)."""
    a = check_range("angle_deg", angle_deg, -1e6, 1e6)
    sign = -1 if a < 0 else 1
    a = abs(a)
    d = int(math.floor(a + 1e-12))
    m = int(math.floor((a - d) * 60 + 1e-10))
    s = (a - d - m / 60) * 3600
    return sign * d, m, max(s, 0.0)


def from_dms(d, m=0.0, s=0.0) -> float:
    """Degrees, minutes, seconds → degrees (the sign of ``d`` applies to the whole angle)."""
    d = check_range("d", d, -1e6, 1e6)
    m = check_range("m", m, 0.0, 60.0, hi_open=True)
    s = check_range("s", s, 0.0, 60.0, hi_open=True)
    sign = -1.0 if d < 0 or (d == 0 and math.copysign(1, d) < 0) else 1.0
    return sign * (abs(d) + m / 60.0 + s / 3600.0)


def format_dms(angle_deg: float, decimals: int = 0) -> str:
    """``54.8528`` → ``"54°51′10″"`` (seconds to ``decimals`` places, carried correctly)."""
    decimals = check_int_range("decimals", decimals, 0, 4)
    a = check_range("angle_deg", angle_deg, -1e6, 1e6)
    sign = "−" if a < 0 else ""
    total = round(abs(a) * 3600.0, decimals)
    d = int(total // 3600)
    m = int((total - d * 3600) // 60)
    s = total - d * 3600 - m * 60
    sec = f"{s:0{3 + decimals if decimals else 2}.{decimals}f}"
    return f"{sign}{d}°{m:02d}′{sec}″"


@V.checked(from_xy=V.array(last=2), to_xy=V.array(last=2))
def direction_angle_deg(from_xy, to_xy) -> np.ndarray:
    """Direction angle α (дирекционный угол) from ``from_xy`` to ``to_xy``, degrees, 0 ≤ α < 360.

    Geodetic coordinates (X north, Y east): α = atan2(ΔY, ΔX), clockwise from
    +X.  Shapes broadcast over (…, 2); a scalar for single points.
    """
    V.check_broadcast(from_xy=from_xy, to_xy=to_xy)
    a = np.asarray(from_xy, dtype=float)
    b = np.asarray(to_xy, dtype=float)
    d = b - a
    if np.any(np.hypot(d[..., 0], d[..., 1]) == 0):
        raise ValueError("from_xy and to_xy coincide; a direction needs two distinct points")
    out = np.degrees(np.arctan2(d[..., 1], d[..., 0])) % 360.0
    return float(out) if np.ndim(out) == 0 else out


@V.checked(station_xy=V.array(last=2), from_xy=V.array(last=2), to_xy=V.array(last=2))
def horizontal_angle_deg(station_xy, from_xy, to_xy):
    """The angle measured at the station from one point to another, clockwise, degrees, 0 ≤ β < 360."""
    V.check_broadcast(station_xy=station_xy, from_xy=from_xy, to_xy=to_xy)
    out = (np.asarray(direction_angle_deg(station_xy, to_xy)) - direction_angle_deg(station_xy, from_xy)) % 360.0
    return float(out) if np.ndim(out) == 0 else out


@V.checked(A=V.point(2), B=V.point(2), C=V.point(2))
def danger_circle(A, B, C) -> tuple:
    """The circle through A, B, C (опасный круг): centre (2,) and radius, m; ValueError if they are collinear."""
    P = check_points("A, B, C", np.vstack([np.asarray(A, float).reshape(1, 2), np.asarray(B, float).reshape(1, 2),
                                           np.asarray(C, float).reshape(1, 2)]))
    a, b, c = P
    d = 2.0 * ((b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0]))
    scale = max(np.hypot(*(b - a)), np.hypot(*(c - a)), 1e-300)
    if abs(d) <= 1e-12 * scale * scale:
        raise ValueError("the known points A, B, C lie on one line; a resection needs three points not on a line")
    ba, ca = b - a, c - a
    bb, cc = ba @ ba, ca @ ca
    ux = (ca[1] * bb - ba[1] * cc) / d
    uy = (ba[0] * cc - ca[0] * bb) / d
    centre = a + np.array([ux, uy])
    return centre, float(np.hypot(ux, uy))


# --------------------------------------------------------------------------- resection
@dataclass(frozen=True)
class Resection:
    """The station found by resection from three known points and two angles.

    Attributes
    ----------
    point : ndarray (2,)
        The station P, geodetic X, Y, m.
    known : ndarray (3, 2)
        A, B, C.
    beta1_deg, beta2_deg : float
        The angles measured at P from A to B and from B to C, degrees.
    strength : float
        How firmly the two circles cross, 0…1: the sine of the angle between
        them (in the inverted plane); 0 on the danger circle.
    danger_centre, danger_radius_m : ndarray (2,), float
        The circle through A, B, C.
    metres_per_arcsec : float
        RMS shift of P for a 1″ random error of each angle, m.
    """

    point: np.ndarray
    known: np.ndarray
    beta1_deg: float
    beta2_deg: float
    strength: float
    danger_centre: np.ndarray
    danger_radius_m: float
    metres_per_arcsec: float

    @property
    def danger_distance_m(self) -> float:
        """Distance of P from the danger circle, m (0 on it)."""
        return abs(float(np.hypot(*(self.point - self.danger_centre))) - self.danger_radius_m)

    def distances_m(self) -> np.ndarray:
        """Distances from P to A, B, C, m."""
        return np.hypot(*(self.known - self.point).T)

    def table(self) -> pd.DataFrame:
        """The station and its quality as a small table (quantity, unit, value as text at a sensible precision)."""
        rows = [("X of the station", "m", f"{self.point[0]:.3f}"), ("Y of the station", "m", f"{self.point[1]:.3f}"),
                ("β₁ (A → B)", "", format_dms(self.beta1_deg, 1)), ("β₂ (B → C)", "", format_dms(self.beta2_deg, 1)),
                ("distance from the danger circle", "m", f"{self.danger_distance_m:.1f}"),
                ("shift of P per 1″ of angle error", "m", f"{self.metres_per_arcsec:.4f}"),
                ("strength of the intersection (0 on the danger circle)", "", f"{self.strength:.3f}")]
        return pd.DataFrame(rows, columns=["quantity", "unit", "value"]).set_index("quantity")


#: the strength below which the station is taken to lie on the danger circle (the solution is refused)
MIN_STRENGTH = 1e-9


def _solve(a, c, b1, b2):
    """w = 1/(P − B) from the two linear equations in the inverted plane; (u, v), normalised determinant."""
    ar, ai = a
    cr, ci = c
    M = np.array([[ai * math.cos(b1) + ar * math.sin(b1), ar * math.cos(b1) - ai * math.sin(b1)],
                  [ci * math.cos(b2) - cr * math.sin(b2), cr * math.cos(b2) + ci * math.sin(b2)]])
    rhs = np.array([math.sin(b1), -math.sin(b2)])
    det = float(np.linalg.det(M))
    strength = abs(det) / (math.hypot(ar, ai) * math.hypot(cr, ci))
    if strength < MIN_STRENGTH:
        return None, strength
    return np.linalg.solve(M, rhs), strength


def _point(Bp, a, c, b1, b2):
    w, strength = _solve(a, c, b1, b2)
    if w is None:
        return None, strength
    u, v = w
    r2 = u * u + v * v
    if r2 == 0:
        return None, strength
    return Bp + np.array([u / r2, -v / r2]), strength  # 1/w = conj(w)/|w|²


@V.checked(A=V.point(2), B=V.point(2), C=V.point(2))
def resect(A, B, C, beta1_deg: float, beta2_deg: float) -> Resection:
    """Resection (Snellius–Pothenot): the station P from three known points and the two angles measured at P.

    Parameters
    ----------
    A, B, C : array_like (2,)
        Known points, geodetic X (north), Y (east), m — in the order they
        are sighted, clockwise as seen from P.
    beta1_deg, beta2_deg : float
        The angles at P from A to B and from B to C, clockwise, degrees,
        0 < β < 360 (guide §11: "two angles measured at the station").

    Returns
    -------
    :class:`Resection`

    Raises
    ------
    ValueError
        If A, B, C are collinear or repeated, an angle is 0 or 180° (P on a
        line through two known points), P lies on the danger circle through
        A, B, C (the angles do not fix it), or the angles cannot be seen from
        any point (they do not fit the known points).

    Notes
    -----
    Put the origin at B and invert the plane in it (w = 1/(P − B), complex
    numbers z = X + iY): the circle through A and B on which the angle β₁ is
    seen becomes a straight line, and so does the circle through B and C.
    Two linear equations in w give P = B + 1/w directly.  The two lines are
    parallel exactly when the circles coincide — P on the danger circle.
    """
    K = check_points("A, B, C", np.vstack([np.asarray(p, float).reshape(1, 2) for p in (A, B, C)]))
    b1 = check_range("beta1_deg", beta1_deg, 0.0, 360.0, lo_open=True, hi_open=True, unit="°")
    b2 = check_range("beta2_deg", beta2_deg, 0.0, 360.0, lo_open=True, hi_open=True, unit="°")
    for name, b in (("beta1_deg", b1), ("beta2_deg", b2)):
        if abs(math.sin(math.radians(b))) < 1e-9:
            raise ValueError(f"{name} = {b:g}°: the station would lie on the line through two known points; "
                             "the valid range is 0 < β < 360° without 180°")
    centre, radius = danger_circle(*K)
    Ap, Bp, Cp = K
    a, c = Ap - Bp, Cp - Bp
    P, strength = _point(Bp, a, c, math.radians(b1), math.radians(b2))
    if P is None:
        raise ValueError(f"the station lies on the danger circle through A, B, C (centre X = {centre[0]:.1f}, "
                         f"Y = {centre[1]:.1f} m, radius {radius:.1f} m): the angles β₁ = {b1:g}°, β₂ = {b2:g}° are "
                         "seen from every point of it, so they do not fix the station; choose other known points")
    # the linear equations fix the angles modulo 180°: check the arcs
    got1 = horizontal_angle_deg(P, Ap, Bp)
    got2 = horizontal_angle_deg(P, Bp, Cp)
    if abs(math.remainder(got1 - b1, 360.0)) > 1e-5 or abs(math.remainder(got2 - b2, 360.0)) > 1e-5:
        raise ValueError(f"the angles beta1_deg = {b1:g}° and beta2_deg = {b2:g}° cannot both be seen from one "
                         "point at A, B, C in this order (clockwise): check the order of the points and the angles")
    # sensitivity: RMS shift for 1″ on each angle
    eps = math.radians(1.0 / 3600.0)
    shifts = []
    for d1, d2 in ((eps, 0.0), (0.0, eps)):
        Q, _ = _point(Bp, a, c, math.radians(b1) + d1, math.radians(b2) + d2)
        shifts.append(np.inf if Q is None else float(np.hypot(*(Q - P))))
    return Resection(P, K, b1, b2, float(strength), centre, radius, float(math.hypot(*shifts)))


@V.checked(A=V.point(2), B=V.point(2), C=V.point(2), beta1_deg=V.values(), beta2_deg=V.values())
def resect_many(A, B, C, beta1_deg, beta2_deg) -> np.ndarray:
    """Many resections at once (e.g. a Monte Carlo of angle errors): stations (k, 2), NaN where undetermined.

    The same solution as :func:`resect` (inverted plane), vectorised over
    ``beta1_deg`` and ``beta2_deg`` (arrays of one shape); no checks of the
    arcs and no quality measures.  A station on (or within rounding of) the
    danger circle is NaN.
    """
    K = check_points("A, B, C", np.vstack([np.asarray(p, float).reshape(1, 2) for p in (A, B, C)]))
    b1 = np.radians(np.asarray(beta1_deg, dtype=float))
    b2 = np.radians(np.asarray(beta2_deg, dtype=float))
    if b1.shape != b2.shape or not (np.all(np.isfinite(b1)) and np.all(np.isfinite(b2))):
        raise ValueError("beta1_deg and beta2_deg must be finite arrays of one shape")
    Bp = K[1]
    ar, ai = K[0] - Bp
    cr, ci = K[2] - Bp
    m11 = ai * np.cos(b1) + ar * np.sin(b1)
    m12 = ar * np.cos(b1) - ai * np.sin(b1)
    m21 = ci * np.cos(b2) - cr * np.sin(b2)
    m22 = cr * np.cos(b2) + ci * np.sin(b2)
    r1, r2 = np.sin(b1), -np.sin(b2)
    det = m11 * m22 - m12 * m21
    ok = np.abs(det) / (math.hypot(ar, ai) * math.hypot(cr, ci)) >= MIN_STRENGTH
    det = np.where(ok, det, 1.0)
    u = (r1 * m22 - m12 * r2) / det
    v = (m11 * r2 - r1 * m21) / det
    w2 = u * u + v * v
    ok &= w2 > 0
    w2 = np.where(ok, w2, 1.0)
    out = np.stack([Bp[0] + u / w2, Bp[1] - v / w2], axis=-1)
    out[~ok] = np.nan
    return out


@dataclass(frozen=True)
class ResectionCheck:
    """The check of a resection by a third angle, to a fourth known point (guide §11).

    Attributes
    ----------
    computed_deg : float
        The check angle computed from the resected station, degrees.
    measured_deg : float
        The check angle measured in the field, degrees.
    discrepancy_arcsec : float
        measured − computed, arc-seconds (signed, −648000…648000).
    tolerance_arcsec : float
        The largest discrepancy allowed (:func:`check_tolerance_arcsec`).
    distance_m : float
        From the station to the check point, m.
    """

    computed_deg: float
    measured_deg: float
    discrepancy_arcsec: float
    tolerance_arcsec: float
    distance_m: float

    @property
    def ok(self) -> bool:
        """The check holds: |discrepancy| ≤ tolerance."""
        return abs(self.discrepancy_arcsec) <= self.tolerance_arcsec

    def table(self) -> pd.DataFrame:
        """The check as a small table (quantity, unit, value as text)."""
        rows = [("check angle, measured", "", format_dms(self.measured_deg, 1)),
                ("check angle, computed from the station", "", format_dms(self.computed_deg, 1)),
                ("discrepancy Δγ = measured − computed", "″", f"{self.discrepancy_arcsec:+.1f}"),
                ("distance to the check point S", "m", f"{self.distance_m:.1f}"),
                ("tolerance ρ″·e/S", "″", f"{self.tolerance_arcsec:.1f}"),
                ("the check holds", "", "yes" if self.ok else "no")]
        return pd.DataFrame(rows, columns=["quantity", "unit", "value"]).set_index("quantity")


def check_tolerance_arcsec(distance_m: float, M: float = 10000.0, tol_mm: float = IDENTIFICATION_MM) -> float:
    """The tolerance of the check angle, arc-seconds: ρ″ · (tol_mm · M / 1000) / S.

    The guide prints no number for it.  The book holds the check to the
    guide's own accuracy of a control point: 0.1 mm at the plan's scale 1:M
    (guide §11 step 1), i.e. ``tol_mm·M/1000`` metres on the ground.  A
    station off by that much across the line of sight to the check point,
    ``distance_m`` away, turns the check direction by ρ″·e/S.
    """
    S = check_positive("distance_m", distance_m, unit="m", hi=1e7)
    return RHO_ARCSEC * identification_tolerance_m(M, tol_mm) / S


@V.checked(res=Resection, D=V.point(2))
def check_resection(res: Resection, D, measured_deg: float, *, M: float = 10000.0,
                    tol_mm: float = IDENTIFICATION_MM, from_index: int = 2) -> ResectionCheck:
    """Compare the measured check angle (from known point ``from_index`` — C by default — to D) with the computed one.

    Parameters
    ----------
    res : :class:`Resection`
    D : array_like (2,)
        The fourth known point, geodetic X, Y, m.
    measured_deg : float
        The check angle measured at P, clockwise from the known point
        ``from_index`` (0 = A, 1 = B, 2 = C) to D, degrees, 0 ≤ γ < 360.
    M : float
        The plan's scale denominator (the tolerance is 0.1 mm at 1:M).
    """
    Dp = check_points("D", D).reshape(2)
    g = check_range("measured_deg", measured_deg, 0.0, 360.0, hi_open=True, unit="°")
    k = check_int_range("from_index", from_index, 0, 2)
    comp = horizontal_angle_deg(res.point, res.known[k], Dp)
    disc = math.remainder(g - comp, 360.0) * 3600.0
    S = float(np.hypot(*(Dp - res.point)))
    return ResectionCheck(comp, g, disc, check_tolerance_arcsec(S, M, tol_mm), S)


# --------------------------------------------------------------------------- control design
def control_spacing_bases(m_allowed_mm: float = 0.35, *, k_i: float = 1.0, b_mm: float = 72.0,
                          m_eps_arcmin: float = 4.5) -> int:
    """Bases between rows of sparse control: the largest n with Zhukov's (13.1) error ≤ ``m_allowed_mm``, at least 1.

    (13.1) is read with n³ + 11n + 34 (:mod:`aerophoto.triangulation.zhukov`);
    when even one base exceeds the allowed error the control must be dense
    (every base): 1 is returned.
    """
    n = _zhukov.zhukov_max_bases(m_allowed_mm, k_i=k_i, b_mm=b_mm, m_eps_arcmin=m_eps_arcmin)
    return max(int(n), 1)


def control_rows(n_photos: int, spacing_bases: int) -> tuple:
    """Photo indices (0-based) of the rows of control across the strips: every ``spacing_bases`` photos, both ends.

    The first and last photos always get a row; when the strip's bases are
    not a whole number of spacings, the last row is moved to the last photo
    (never more than ``spacing_bases`` bases between rows).
    """
    n = check_int_range("n_photos", n_photos, 2, 10000)
    s = check_int_range("spacing_bases", spacing_bases, 1, 10000)
    rows = list(range(0, n - 1, s)) + [n - 1]
    return tuple(sorted(set(rows)))


@dataclass(frozen=True)
class ControlDesign:
    """A design of control points on a block of strips (guide §11).

    Attributes
    ----------
    spacing_bases : int
        Bases between neighbouring rows (1 = dense control).
    rows : tuple of int
        Photo indices of the rows.
    points_m : ndarray (n_rows, n_strips + 1, 2)
        Ground position (site X east, Y north, m) of every control point:
        row by row, from the block's first outer edge across to the last.
    """

    spacing_bases: int
    rows: tuple
    points_m: np.ndarray

    @property
    def n_points(self) -> int:
        return int(self.points_m.shape[0] * self.points_m.shape[1])

    @property
    def dense(self) -> bool:
        return self.spacing_bases == 1

    def table(self) -> pd.DataFrame:
        """One row per control point: row, position across (0 = first edge), X_m, Y_m."""
        r, k = np.meshgrid(np.arange(self.points_m.shape[0]), np.arange(self.points_m.shape[1]), indexing="ij")
        return pd.DataFrame({"row": np.asarray(self.rows)[r.ravel()], "across": k.ravel(),
                             "X_m": self.points_m[..., 0].ravel(), "Y_m": self.points_m[..., 1].ravel()})


@V.checked(centres_m=V.array(last=2, min_len=1))
def design_control(centres_m, spacing_bases: int, *, strip_spacing_m: float | None = None) -> ControlDesign:
    """Rows of control across the strips of a block, every ``spacing_bases`` bases (guide §11).

    Parameters
    ----------
    centres_m : array_like (n_strips, n_photos, 2)
        Ground positions of the photo centres (site X, Y, m), strip by strip,
        the strips side by side in order.
    spacing_bases : int
        Bases between rows (1 = dense control, every model).
    strip_spacing_m : float, optional
        Distance between neighbouring strips' axes B_y, m; needed for a
        single strip (otherwise taken from the centres).

    A row at photo j has its points in the middle of every side overlap
    (halfway between the photo centres j of neighbouring strips) and on both
    outer edges, half a strip spacing beyond the outer strips' centres.
    """
    C = np.asarray(centres_m, dtype=float)
    if C.ndim != 3 or C.shape[-1] != 2 or not np.all(np.isfinite(C)):
        raise ValueError(f"centres_m has shape {C.shape}; expected finite (n_strips, n_photos, 2) ground positions")
    K, n, _ = C.shape
    if n < 2:
        raise ValueError(f"centres_m has {n} photo(s) per strip; a strip needs at least 2")
    rows = control_rows(n, spacing_bases)
    if K >= 2:
        By = float(np.median(np.hypot(*(C[1:] - C[:-1]).reshape(-1, 2).T)))
    elif strip_spacing_m is None:
        raise ValueError("a single strip needs strip_spacing_m (the distance to a neighbouring strip, m)")
    else:
        By = check_positive("strip_spacing_m", strip_spacing_m, unit="m", hi=1e7)
    pts = np.empty((len(rows), K + 1, 2))
    for r, j in enumerate(rows):
        c = C[:, j, :]
        if K >= 2:
            across = c[-1] - c[0]
        else:  # perpendicular to the strip's direction
            d = C[0, -1] - C[0, 0]
            across = np.array([-d[1], d[0]])
        u = across / np.hypot(*across)
        pts[r, 0] = c[0] - 0.5 * By * u
        pts[r, K] = c[-1] + 0.5 * By * u
        for k in range(1, K):
            pts[r, k] = 0.5 * (c[k - 1] + c[k])
    return ControlDesign(int(spacing_bases), rows, pts)
