"""Relief and tilt displacement of photo points, and the scales of bases (guide §4–§5).

Two effects move a point's image away from where a vertical photo of flat
ground would put it:

* **Relief displacement** (смещение за рельеф, guide §4).  A point at height h
  above the mean object plane (средняя предметная плоскость) is imaged
  farther from the nadir point n than it would be if it lay on that plane:

      δh = r·h / H            (guide formula 4.1)

  r is the distance of the image from n (mm), H = m_cp·f the flying height
  above the plane (m).  The displacement is radial from n: positive away from
  n (the point is above the plane), negative towards n.  The correction is
  the opposite move — towards n for δh > 0, away from n for δh < 0 — and the
  guide applies it only when |δh| > 0.2 mm.

* **Tilt displacement** (смещение за угол наклона, guide §5).  On a photo
  tilted by α a point is displaced along the line from the isocentre c
  (точка нулевых искажений) by

      δα = −(r_c²·cos φ / f)·sin α          (the guide's approximate formula)

  with r_c the distance from c and φ the angle from the positive direction of
  the principal vertical, counter-clockwise.  The guide's positive direction
  points away from the nadir (see :mod:`aerophoto.geometry`): points on that
  far side (cos φ > 0) are pulled towards c (δα < 0), points on the nadir
  side pushed away (δα > 0).  Corrections: away from c for δα < 0, towards c
  for δα > 0, again only when |δα| > 0.2 mm.  The exact value comes from the
  camera model (:func:`aerophoto.geometry.tilt_displacement_exact`).

The scale of a photo is judged by *bases* (базисы), short segments between
pricked points, measured on the photo (l_сн) and on the photoplan (l_пл) of
scale 1:M:

      m_i = l_пл·M / l_сн                    (formula 5.1)
      m_част = (m_1 + m_2)/2                 (5.2, the partial scale of a zone)
      m_cp = mean of the zones' m_част,  Δm_i = m_част − m_cp,  Δm_i/m_cp = 1/N

:func:`partial_scales` computes tables 2, 4, 5 and 7, :func:`relief_corrections`
table 3 and :func:`tilt_corrections` table 6.  :func:`guide_table` reproduces
each of the guide's tables 2–7 from its printed inputs and compares every
printed number with the computed one (:class:`CellCheck`); the guide's slips
are listed, with the reason for each, by :func:`guide_discrepancies`, and the
reading of table 6's tilt displacements that its numbers do fit is found by
:func:`table6_fit`.  :func:`displacement_field` computes both displacements
exactly, by projection, for a grid of points over :class:`AnalyticHills`
(the live demo of chapters 03 and 04).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache
from typing import Sequence

import numpy as np
import pandas as pd

from . import geometry as g
from ._validate import check_positive, check_range

__all__ = [
    "THRESHOLD_MM",
    "GUIDE_F_MM",
    "GUIDE_ALPHA_DEG",
    "GUIDE_M_PLAN",
    "base_scale",
    "Base",
    "ScaleTable",
    "partial_scales",
    "zone_height",
    "mean_object_plane",
    "flying_height",
    "ReliefCorrections",
    "relief_corrections",
    "isocentre_offset",
    "nadir_offset",
    "point_from_polar",
    "polar_about_isocentre",
    "TiltCorrections",
    "tilt_corrections",
    "apply_radial_corrections",
    "relief_displacement_vectors",
    "AnalyticHills",
    "DisplacementField",
    "displacement_field",
    "ROUNDING_UNITS",
    "CellCheck",
    "GuideTable",
    "guide_table",
    "guide_discrepancies",
    "Table6Fit",
    "table6_fit",
    "ratio_text",
    "RELIEF_LAB_POINTS",
    "TILT_LAB_POINT_MM",
    "ReliefLab",
    "relief_lab",
    "TiltLab",
    "tilt_lab",
    "angle_answer",
]

#: corrections smaller than this are not applied (guide §4 step 5, §5 step 10), mm
THRESHOLD_MM = 0.2
#: the camera of the guide's worked example (§5 step 3: oc = −100·tg(3°/2)), mm
GUIDE_F_MM = 100.0
#: the tilt of the guide's worked example (§1, §5), degrees
GUIDE_ALPHA_DEG = 3.0
#: the photoplan scale denominator M (guide §1: 1/M = 1/10000)
GUIDE_M_PLAN = 10000.0


# =========================================================================== scales of bases
def base_scale(l_plan_mm, l_photo_mm, M: float = GUIDE_M_PLAN):
    """Scale denominator of a photo along one base (guide formula 5.1).

        m_i = l_пл · M / l_сн

    Parameters
    ----------
    l_plan_mm : float or array_like
        Length l_пл of the base on the photoplan, mm (> 0).
    l_photo_mm : float or array_like
        Length l_сн of the same base on the photo, mm (> 0).
    M : float
        Scale denominator of the photoplan (guide: 10000).

    Returns
    -------
    float or ndarray
        The photo's scale denominator m_i along the base.
    """
    M = check_positive("M", M)
    lp = np.asarray(l_plan_mm, dtype=float)
    ls = np.asarray(l_photo_mm, dtype=float)
    for name, arr in (("l_plan_mm", lp), ("l_photo_mm", ls)):
        if np.any(~np.isfinite(arr)) or np.any(arr <= 0):
            bad = arr[~(np.isfinite(arr) & (arr > 0))].ravel()[0]
            raise ValueError(f"{name} = {bad:g} is outside the valid range 0 < {name} (mm)")
    out = lp * M / ls
    return float(out) if out.ndim == 0 else out


def ratio_text(N: float) -> str:
    """Format a relative deviation 1/N the way the guide prints it ("1/71"); ∞ for Δm = 0."""
    if not np.isfinite(N):
        return "0"
    if N >= 1000:
        return f"1/{round(N, -2):.0f}"
    return f"1/{N:.0f}"


@dataclass(frozen=True)
class Base:
    """One base (базис): a segment between two pricked points, e.g. I-1.

    Attributes
    ----------
    name : str
        As in the guide, ``"I-1"``: the zone's main point, a dash, the other point.
    l_plan_mm, l_photo_mm : float
        Length on the photoplan (l_пл) and on the photo (l_сн), mm.
    zone : str
        The zone (зона) the base belongs to; by default the part of the name
        before the dash.
    """

    name: str
    l_plan_mm: float
    l_photo_mm: float
    zone: str = ""

    def __post_init__(self):
        check_positive("l_plan_mm", self.l_plan_mm, unit="mm")
        check_positive("l_photo_mm", self.l_photo_mm, unit="mm")
        if not self.zone:
            object.__setattr__(self, "zone", self.name.split("-")[0].strip())


@dataclass(frozen=True)
class ScaleTable:
    """Partial and mean scales of a photo from its bases (guide tables 2, 4, 5, 7).

    Attributes
    ----------
    bases : tuple of :class:`Base`
    M : float
        Photoplan scale denominator.
    m_i : ndarray, shape (n_bases,)
        Scale denominator along each base (formula 5.1).
    zones : tuple of str
        Zone names in order of first appearance.
    m_part : ndarray, shape (n_zones,)
        Partial scale denominator m_част of each zone: the mean of its bases' m_i (5.2).
    m_mean : float
        Mean scale denominator m_cp: the mean of the zones' m_част.
    dm : ndarray, shape (n_zones,)
        Deviations Δm_i = m_част − m_cp (guide §5 step 8).
    zone_heights_m : tuple or None
        Mean height of each zone's bases, m (tables 2 and 4 only).
    """

    bases: tuple
    M: float
    m_i: np.ndarray
    zones: tuple
    m_part: np.ndarray
    m_mean: float
    dm: np.ndarray
    zone_heights_m: tuple | None = None

    @property
    def ratio_N(self) -> np.ndarray:
        """N of the relative deviation |Δm_i|/m_cp = 1/N, per zone (∞ where Δm = 0)."""
        with np.errstate(divide="ignore"):
            return self.m_mean / np.abs(self.dm)

    @property
    def relative_dm(self) -> np.ndarray:
        """Δm_i/m_cp as a signed fraction, per zone."""
        return self.dm / self.m_mean

    @property
    def spread(self) -> float:
        """Largest |Δm_i|/m_cp, a fraction: how unequal the zones' scales are."""
        return float(np.max(np.abs(self.relative_dm)))

    def table(self) -> pd.DataFrame:
        """A DataFrame laid out like the guide's tables 2/4/5/7.

        One row per base; a zone's m_част, Δm_i and Δm_i/m_cp (and mean height)
        stand on the zone's last row, m_cp on the first row of the middle zone, as in the guide;
        other cells are NaN (blank).
        """
        n = len(self.bases)
        cols = {}
        if self.zone_heights_m is not None:
            cols["mean height of bases, m"] = np.full(n, np.nan)
        cols["l_пл, mm"] = np.array([b.l_plan_mm for b in self.bases])
        cols["l_сн, mm"] = np.array([b.l_photo_mm for b in self.bases])
        cols["m_i"] = np.asarray(self.m_i, dtype=float)
        cols["m_част"] = np.full(n, np.nan)
        cols["m_cp"] = np.full(n, np.nan)
        cols["Δm_i"] = np.full(n, np.nan)
        ratio = [""] * n
        for k, z in enumerate(self.zones):
            last = max(i for i, b in enumerate(self.bases) if b.zone == z)
            cols["m_част"][last] = self.m_part[k]
            cols["Δm_i"][last] = self.dm[k]
            ratio[last] = ratio_text(self.ratio_N[k])
            if self.zone_heights_m is not None:
                cols["mean height of bases, m"][last] = self.zone_heights_m[k]
        mid_zone = self.zones[len(self.zones) // 2]  # the guide prints m_cp on the middle zone's first row
        cols["m_cp"][min(i for i, b in enumerate(self.bases) if b.zone == mid_zone)] = self.m_mean
        cols["Δm_i/m_cp"] = ratio
        df = pd.DataFrame(cols, index=pd.Index([b.name for b in self.bases], name="base"))
        return df


def partial_scales(bases: Sequence, M: float = GUIDE_M_PLAN, zone_heights_m=None) -> ScaleTable:
    """Scales of bases, partial scales of zones and the mean scale (guide tables 2, 4, 5, 7).

    Parameters
    ----------
    bases : sequence of :class:`Base` or of tuples ``(name, l_plan_mm, l_photo_mm)``
        The bases, grouped by zone (``"I-1", "I-2", "II-3", ...``).
    M : float
        Photoplan scale denominator (guide: 10000).
    zone_heights_m : sequence of float, optional
        Mean height of each zone's bases (the first column of tables 2 and 4).

    Returns
    -------
    :class:`ScaleTable`
    """
    bs = tuple(b if isinstance(b, Base) else Base(*b) for b in bases)
    if not bs:
        raise ValueError("bases is empty; the valid input is at least one base (name, l_plan_mm, l_photo_mm)")
    M = check_positive("M", M)
    m_i = np.array([base_scale(b.l_plan_mm, b.l_photo_mm, M) for b in bs])
    zones = tuple(dict.fromkeys(b.zone for b in bs))
    m_part = np.array([np.mean([m for m, b in zip(m_i, bs) if b.zone == z]) for z in zones])
    m_mean = float(np.mean(m_part))
    heights = None
    if zone_heights_m is not None:
        heights = tuple(float(h) for h in zone_heights_m)
        if len(heights) != len(zones):
            raise ValueError(f"zone_heights_m has {len(heights)} values; the valid length is the number of zones, {len(zones)}")
    return ScaleTable(bs, M, m_i, zones, m_part, m_mean, m_part - m_mean, heights)


# =========================================================================== relief (guide §4)
def zone_height(base_end_heights_m) -> float:
    """Mean height of a zone, m: the mean of its bases' mean heights (guide §4 step 3).

    Parameters
    ----------
    base_end_heights_m : sequence of (Z_a, Z_b)
        The heights of the two ends of each base of the zone, m.
        For zone I of the guide: ``[(Z_I, Z_1), (Z_I, Z_2)]``, so
        Z_Icp = ((Z_I + Z_1)/2 + (Z_I + Z_2)/2)/2.
    """
    arr = np.asarray(base_end_heights_m, dtype=float)
    if arr.ndim != 2 or arr.shape[1] != 2 or len(arr) == 0:
        raise ValueError(f"base_end_heights_m has shape {arr.shape}; the valid shape is (n_bases ≥ 1, 2)")
    return float(arr.mean())


def mean_object_plane(zone_heights_m) -> float:
    """Height of the mean object plane Z_cp, m: the mean of the zones' heights (guide §4).

        Z_cp = (Z_Icp + Z_IIcp)/2
    """
    z = np.asarray(zone_heights_m, dtype=float).ravel()
    if len(z) == 0:
        raise ValueError("zone_heights_m is empty; the valid input is at least one zone height (m)")
    return float(z.mean())


def flying_height(m: float, f_mm: float) -> float:
    """H = m·f in metres (guide §4: H = m_cp·f), for scale 1:m and focal length f in mm."""
    return check_positive("m", m) * check_positive("f_mm", f_mm, unit="mm", hi=g.MAX_F_MM) / 1000.0


def _direction_words(delta, apply, towards: str, away: str):
    out = []
    for d, a in zip(np.ravel(delta), np.ravel(apply)):
        out.append((towards if d > 0 else away) if a else "not applied")
    return tuple(out)


@dataclass(frozen=True)
class ReliefCorrections:
    """Relief displacements of pricked points and the corrections to apply (guide table 3).

    Attributes
    ----------
    names : tuple of str
    Z_m : ndarray, shape (n,)
        Heights Z_i of the points, m.
    r_mm : ndarray, shape (n,)
        Distances r_n of the images from the nadir point n, mm.
    Z_mean_m : float
        Height of the mean object plane Z_cp, m.
    H_m : float
        Flying height above the mean object plane, m.
    h_m : ndarray, shape (n,)
        h_i = Z_i − Z_cp, m.
    delta_mm : ndarray, shape (n,)
        δh = r·h/H, mm: + away from n, − towards n.
    threshold_mm : float
    """

    names: tuple
    Z_m: np.ndarray
    r_mm: np.ndarray
    Z_mean_m: float
    H_m: float
    h_m: np.ndarray
    delta_mm: np.ndarray
    threshold_mm: float = THRESHOLD_MM

    @property
    def apply(self) -> np.ndarray:
        """Which corrections are applied: |δh| > threshold (0.2 mm)."""
        return np.abs(self.delta_mm) > self.threshold_mm

    @property
    def n_applied(self) -> int:
        return int(np.count_nonzero(self.apply))

    @property
    def directions(self) -> tuple:
        """'towards n' (δh > 0), 'away from n' (δh < 0) or 'not applied', per point."""
        return _direction_words(self.delta_mm, self.apply, "towards n", "away from n")

    def table(self) -> pd.DataFrame:
        """Laid out like the guide's table 3, with the correction's direction added."""
        return pd.DataFrame(
            {"Z_i, m": self.Z_m, "h, m": self.h_m, "r, mm": self.r_mm, "δh, mm": self.delta_mm,
             "correction": self.directions},
            index=pd.Index(self.names, name="point"),
        )


def relief_corrections(names, Z_m, r_mm, H_m: float, Z_mean_m: float | None = None,
                       *, threshold_mm: float = THRESHOLD_MM) -> ReliefCorrections:
    """Relief displacements δh = r·h/H of pricked points (guide §4, formula 4.1, table 3).

    Parameters
    ----------
    names : sequence of str
        Point names (``"I", "1", ...``).
    Z_m : array_like, shape (n,)
        Heights of the points, m.
    r_mm : array_like, shape (n,)
        Distances of the images from the nadir point n, mm (≥ 0).
    H_m : float
        Flying height above the mean object plane, m (guide: H = m_cp·f).
    Z_mean_m : float, optional
        Height Z_cp of the mean object plane, m; default: the mean of ``Z_m``.
    threshold_mm : float
        Corrections with |δh| ≤ threshold are not applied (guide: 0.2 mm).

    Uses :func:`aerophoto.geometry.relief_displacement`.
    """
    names = tuple(str(n) for n in names)
    Z = np.asarray(Z_m, dtype=float).ravel()
    r = np.asarray(r_mm, dtype=float).ravel()
    if not (len(names) == len(Z) == len(r)):
        raise ValueError(f"names, Z_m and r_mm have lengths {len(names)}, {len(Z)}, {len(r)}; they must be equal")
    bad = ~(np.isfinite(r) & (r >= 0))
    if np.any(bad):
        raise ValueError(f"r_mm = {r[bad][0]:g} is outside the valid range 0 ≤ r_mm (mm)")
    Zc = float(Z.mean()) if Z_mean_m is None else check_range("Z_mean_m", Z_mean_m, unit="m")
    h = Z - Zc
    d = g.relief_displacement(r, h, H_m)
    thr = check_range("threshold_mm", threshold_mm, 0.0, unit="mm")
    return ReliefCorrections(names, Z, r, Zc, float(H_m), h, np.asarray(d, dtype=float), thr)


def relief_displacement_vectors(camera: g.Camera, pose: g.Pose, XYZ_m, Z_mean_m: float = 0.0):
    """Exact relief displacement of ground points on a (possibly tilted) photo.

    Returns ``(xy_actual, xy_plane)``, each of shape (..., 2) in mm: the image
    of each point, and the image it would have if it lay on the mean object
    plane Z = ``Z_mean_m`` (same X, Y).  The vector ``xy_actual − xy_plane``
    lies on the line through the nadir point n (verticals converge to n), and
    on a vertical photo its length is exactly r·h/H with r measured to
    ``xy_actual`` and H = Z_S − Z_mean.
    """
    P = np.asarray(XYZ_m, dtype=float)
    Pm = P.copy()
    Pm[..., 2] = float(Z_mean_m)
    return g.ground_to_photo(camera, pose, P), g.ground_to_photo(camera, pose, Pm)


# =========================================================================== tilt (guide §5)
def isocentre_offset(f_mm: float, alpha_deg: float) -> float:
    """oc with the guide's sign, mm: −f·tg(α/2) along the principal vertical (§5 step 3).

    Guide: oc = −100·tg(3°/2) = −2.6 mm.  From :func:`aerophoto.geometry.isocentre`.
    """
    cam = g.Camera(f_mm)
    pose = g.Pose(alpha_deg=alpha_deg, lambda_deg=0.0)
    return float(g.isocentre(cam, pose)[0])


def nadir_offset(f_mm: float, alpha_deg: float) -> float:
    """on with the guide's sign, mm: −f·tg α along the principal vertical (n lies on the near side)."""
    cam = g.Camera(f_mm)
    pose = g.Pose(alpha_deg=alpha_deg, lambda_deg=0.0)
    return float(g.nadir_point(cam, pose)[0])


def point_from_polar(camera: g.Camera, pose: g.Pose, r_c_mm, phi_deg) -> np.ndarray:
    """Photo coordinates, shape (..., 2) mm, of points given by r_c and φ about the isocentre.

    φ is counted counter-clockwise from the positive direction of the
    principal vertical (away from n), as in the guide's table 6.
    """
    r = np.asarray(r_c_mm, dtype=float)
    a = np.radians(np.asarray(phi_deg, dtype=float)) + math.radians(pose.lambda_deg)
    c = g.isocentre(camera, pose)
    return np.stack([c[0] + r * np.cos(a), c[1] + r * np.sin(a)], axis=-1)


def polar_about_isocentre(camera: g.Camera, pose: g.Pose, xy_mm):
    """r_c (mm) and φ (degrees, 0 ≤ φ < 360) of photo points about the isocentre c.

    φ counter-clockwise from the positive principal vertical (the guide's table 6).
    Returns ``(r_c_mm, phi_deg)``, each of shape (...,).
    """
    xy = np.asarray(xy_mm, dtype=float)
    c = g.isocentre(camera, pose)
    d = xy - c
    r = np.hypot(d[..., 0], d[..., 1])
    phi = (np.degrees(np.arctan2(d[..., 1], d[..., 0])) - pose.lambda_deg) % 360.0
    return r, phi


@dataclass(frozen=True)
class TiltCorrections:
    """Tilt displacements of pricked points and the corrections to apply (guide table 6).

    Attributes
    ----------
    names : tuple of str
    r_c_mm, phi_deg : ndarray, shape (n,)
        Distance from the isocentre c (mm) and angle from the positive
        principal vertical, counter-clockwise (degrees).
    f_mm, alpha_deg : float
        Focal length and tilt.
    delta_approx_mm : ndarray, shape (n,)
        δα by the guide's formula −(r_c²·cos φ/f)·sin α, mm.
    delta_exact_mm : ndarray, shape (n,)
        The exact value −r_c²·cos φ·sin α/(f − r_c·cos φ·sin α), mm.
    threshold_mm : float
    """

    names: tuple
    r_c_mm: np.ndarray
    phi_deg: np.ndarray
    f_mm: float
    alpha_deg: float
    delta_approx_mm: np.ndarray
    delta_exact_mm: np.ndarray
    threshold_mm: float = THRESHOLD_MM

    @property
    def cos_phi(self) -> np.ndarray:
        return np.cos(np.radians(self.phi_deg))

    @property
    def oc_mm(self) -> float:
        """oc = −f·tg(α/2), mm (the guide's sign)."""
        return isocentre_offset(self.f_mm, self.alpha_deg)

    @property
    def apply(self) -> np.ndarray:
        """Which corrections the guide applies: |δα| > threshold, by its formula."""
        return np.abs(self.delta_approx_mm) > self.threshold_mm

    @property
    def n_applied(self) -> int:
        return int(np.count_nonzero(self.apply))

    @property
    def directions(self) -> tuple:
        """'towards c' (δα > 0), 'away from c' (δα < 0) or 'not applied', per point (§5 step 10)."""
        return _direction_words(self.delta_approx_mm, self.apply, "towards c", "away from c")

    def table(self) -> pd.DataFrame:
        """Laid out like the guide's table 6, with the exact value and the correction added."""
        return pd.DataFrame(
            {"r_c, mm": self.r_c_mm, "φ, °": self.phi_deg, "cos φ": self.cos_phi,
             "δα, mm": self.delta_approx_mm, "δα exact, mm": self.delta_exact_mm,
             "correction": self.directions},
            index=pd.Index(self.names, name="point"),
        )


def tilt_corrections(names, r_c_mm, phi_deg, *, f_mm: float = GUIDE_F_MM, alpha_deg: float = GUIDE_ALPHA_DEG,
                     threshold_mm: float = THRESHOLD_MM) -> TiltCorrections:
    """Tilt displacements of points given by r_c and φ (guide §5 step 9, table 6).

    Parameters
    ----------
    names : sequence of str
    r_c_mm : array_like, shape (n,)
        Distances from the isocentre c, mm (≥ 0).
    phi_deg : array_like, shape (n,)
        Angles from the positive principal vertical, counter-clockwise, degrees.
    f_mm : float
        Focal length f, mm (guide's example: 100).
    alpha_deg : float
        Tilt α, degrees, |α| < 90 (guide: 3).
    threshold_mm : float
        Corrections with |δα| ≤ threshold are not applied (guide: 0.2 mm).

    The displacements come from :func:`aerophoto.geometry.tilt_displacement_approx`
    and :func:`aerophoto.geometry.tilt_displacement_exact` at the photo points
    the polar coordinates describe.
    """
    names = tuple(str(n) for n in names)
    r = np.asarray(r_c_mm, dtype=float).ravel()
    phi = np.asarray(phi_deg, dtype=float).ravel()
    if not (len(names) == len(r) == len(phi)):
        raise ValueError(f"names, r_c_mm and phi_deg have lengths {len(names)}, {len(r)}, {len(phi)}; they must be equal")
    bad = ~(np.isfinite(r) & (r >= 0))
    if np.any(bad):
        raise ValueError(f"r_c_mm = {r[bad][0]:g} is outside the valid range 0 ≤ r_c_mm (mm)")
    if not np.all(np.isfinite(phi)):
        raise ValueError(f"phi_deg = {phi[~np.isfinite(phi)][0]:g} is not a finite angle in degrees")
    cam = g.Camera(f_mm)
    pose = g.Pose(alpha_deg=alpha_deg, lambda_deg=0.0)
    xy = point_from_polar(cam, pose, r, phi)
    approx = g.tilt_displacement_approx(cam, pose, xy)
    exact = g.tilt_displacement_exact(cam, pose, xy)
    thr = check_range("threshold_mm", threshold_mm, 0.0, unit="mm")
    return TiltCorrections(names, r, phi, cam.f_mm, pose.alpha_deg, np.asarray(approx), np.asarray(exact), thr)


def apply_radial_corrections(xy_mm, centre_mm, delta_mm, threshold_mm: float = THRESHOLD_MM) -> np.ndarray:
    """Move photo points radially to undo a displacement (guide §4 step 5, §5 step 10).

    Each point is moved by −δ along the line from ``centre_mm`` (n for relief,
    c for tilt) through the point: towards the centre if δ > 0, away from it if
    δ < 0.  Points with |δ| ≤ ``threshold_mm`` are left where they are.

    Parameters
    ----------
    xy_mm : array_like, shape (..., 2)
    centre_mm : array_like, shape (2,)
    delta_mm : array_like, shape (...,)
        Signed radial displacements, mm (+ = displaced away from the centre).

    Returns
    -------
    ndarray, shape (..., 2): the corrected points, mm.
    """
    xy = np.asarray(xy_mm, dtype=float)
    c = np.asarray(centre_mm, dtype=float)
    d = np.asarray(delta_mm, dtype=float)
    thr = check_range("threshold_mm", threshold_mm, 0.0, unit="mm")
    v = xy - c
    r = np.hypot(v[..., 0], v[..., 1])
    with np.errstate(invalid="ignore", divide="ignore"):
        u = np.where(r[..., None] > 0, v / r[..., None], 0.0)
    move = np.where(np.abs(d) > thr, d, 0.0)
    return xy - u * move[..., None]


# =========================================================================== analytic terrain
# a few smooth hills and a valley in normalised coordinates (u, v) ∈ [−1, 1]²:
# (u_k, v_k, sigma_k, amplitude_k)
_HILLS = ((-0.45, 0.40, 0.32, 1.00), (0.50, 0.55, 0.25, 0.70), (0.35, -0.50, 0.30, 0.85), (-0.60, -0.55, 0.22, 0.45))
# the valley: a Gaussian trough along the line v = 0.35·u − 0.05, width 0.16, depth 0.9
_VALLEY = (0.35, -0.05, 0.16, 0.9)


def _raw_shape(u, v):
    s = np.zeros(np.broadcast(u, v).shape)
    for uk, vk, sk, ak in _HILLS:
        s = s + ak * np.exp(-((u - uk) ** 2 + (v - vk) ** 2) / (2.0 * sk * sk))
    a, b, w, depth = _VALLEY
    dist = (v - (a * u + b)) / math.sqrt(1.0 + a * a)
    return s - depth * np.exp(-(dist * dist) / (2.0 * w * w))


@lru_cache(maxsize=1)
def _shape_norm():
    """Mean and half-range of the raw shape over the square [−1, 1]² (computed once, on first use)."""
    t = np.linspace(-1.0, 1.0, 201)
    U, V = np.meshgrid(t, t)
    s = _raw_shape(U, V)
    mean = float(s.mean())
    half = float(max(s.max() - mean, mean - s.min()))
    bound = (sum(a for *_, a in _HILLS) + _VALLEY[3] + abs(mean)) / half
    return mean, half, bound


@dataclass(frozen=True)
class AnalyticHills:
    """Deterministic hilly terrain: four smooth hills and a valley (for the displacement demo).

    Heights are ``Z0_m + relief_m · s(u, v)`` with u = (X − X0)/L, v = (Y − Y0)/L
    and a fixed shape s whose mean over the square |u|, |v| ≤ 1 is zero and
    whose extreme inside it is ±1: so ``Z0_m`` is the mean object plane of
    that square and ``relief_m`` the largest height above or below it.

    Parameters
    ----------
    relief_m : float
        Relief amplitude, m (≥ 0).
    half_side_m : float
        L: half the side of the square the hills are laid out on, m (> 0).
    X0_m, Y0_m, Z0_m : float
        Centre of the square and the mean height, m.

    The object provides ``height(X, Y)`` and the bounds ``z_min_m``/``z_max_m``,
    so it can be passed to :func:`aerophoto.geometry.photo_to_dem`.
    """

    relief_m: float = 50.0
    half_side_m: float = 1000.0
    X0_m: float = 0.0
    Y0_m: float = 0.0
    Z0_m: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "relief_m", check_range("relief_m", self.relief_m, 0.0, 1e5, unit="m"))
        object.__setattr__(self, "half_side_m", check_positive("half_side_m", self.half_side_m, unit="m"))

    def shape(self, u, v) -> np.ndarray:
        """The normalised shape s(u, v) (zero mean and extreme ±1 over [−1, 1]²)."""
        mean, half, _ = _shape_norm()
        return (_raw_shape(np.asarray(u, float), np.asarray(v, float)) - mean) / half

    def height(self, X, Y) -> np.ndarray:
        """Terrain height Z at ground points X, Y (any matching shapes), m."""
        u = (np.asarray(X, float) - self.X0_m) / self.half_side_m
        v = (np.asarray(Y, float) - self.Y0_m) / self.half_side_m
        return self.Z0_m + self.relief_m * self.shape(u, v)

    __call__ = height

    @property
    def z_min_m(self) -> float:
        return self.Z0_m - self.relief_m * _shape_norm()[2]

    @property
    def z_max_m(self) -> float:
        return self.Z0_m + self.relief_m * _shape_norm()[2]


# =========================================================================== the exact field (demo)
@dataclass(frozen=True)
class DisplacementField:
    """Relief and tilt displacement of a grid of points, computed exactly by projection.

    The grid is regular on the tilted photo: its nodes ``grid_mm`` are the
    images of ground points on the mean object plane Z = 0.  Each ground point
    is then lifted onto the terrain (:class:`AnalyticHills`).

    Attributes
    ----------
    camera, pose : the camera and orientation (H = Z_S above the mean plane)
    terrain : :class:`AnalyticHills`
    grid_mm : (N, 2) mean-plane images on the tilted photo, mm
    h_m : (N,) heights of the points above the mean plane, m
    xy_relief_mm : (N, 2) actual images of the terrain points, mm
    relief_formula_mm : (N,) δh = r·h/H with r from n to the actual image, mm
    xy_vertical_mm : (N, 2) images of the mean-plane points on the equivalent
        vertical photo, turned into the tilted photo's plane about the isoline, mm
    tilt_exact_mm : (N,) signed exact tilt displacement along the line from c, mm
    tilt_approx_mm : (N,) the guide's approximate δα at the same points, mm
    o_mm, n_mm, c_mm : (2,) principal point, nadir point, isocentre, mm
    """

    camera: g.Camera
    pose: g.Pose
    terrain: AnalyticHills
    grid_mm: np.ndarray
    h_m: np.ndarray
    xy_relief_mm: np.ndarray
    relief_formula_mm: np.ndarray
    xy_vertical_mm: np.ndarray
    tilt_exact_mm: np.ndarray
    tilt_approx_mm: np.ndarray
    o_mm: np.ndarray
    n_mm: np.ndarray
    c_mm: np.ndarray

    @property
    def H_m(self) -> float:
        """Flying height above the mean object plane, m."""
        return self.pose.Z_m

    @property
    def m(self) -> float:
        """Scale denominator of the equivalent vertical photo over the mean plane, H/f."""
        return self.H_m / (self.camera.f_mm / 1000.0)

    @property
    def relief_vectors_mm(self) -> np.ndarray:
        """(N, 2): from the mean-plane image to the actual image, mm (radial from n)."""
        return self.xy_relief_mm - self.grid_mm

    @property
    def relief_exact_mm(self) -> np.ndarray:
        """(N,) signed exact relief displacement: + away from n, mm."""
        rn1 = np.hypot(*(self.xy_relief_mm - self.n_mm).T)
        rn0 = np.hypot(*(self.grid_mm - self.n_mm).T)
        return rn1 - rn0

    @property
    def tilt_vectors_mm(self) -> np.ndarray:
        """(N, 2): from the (turned) vertical image to the tilted image, mm (radial from c)."""
        return self.grid_mm - self.xy_vertical_mm

    @property
    def tilt_approx_vectors_mm(self) -> np.ndarray:
        """(N, 2): the guide's δα along the line from c, ending at the tilted image, mm."""
        d = self.grid_mm - self.c_mm
        r = np.hypot(d[:, 0], d[:, 1])
        u = np.divide(d, r[:, None], out=np.zeros_like(d), where=r[:, None] > 0)
        return u * self.tilt_approx_mm[:, None]

    def summary(self) -> dict:
        """The numbers the demo's table shows (mm unless stated)."""
        te, ta = self.tilt_exact_mm, self.tilt_approx_mm
        err = np.abs(ta - te)
        max_te = float(np.max(np.abs(te)))
        re, rf = self.relief_exact_mm, self.relief_formula_mm
        return {
            "H_m": self.H_m,
            "m": self.m,
            "on_mm": float(np.hypot(*self.n_mm)),
            "oc_mm": isocentre_offset(self.camera.f_mm, self.pose.alpha_deg),
            "max_relief_exact_mm": float(np.max(np.abs(re))),
            "max_relief_formula_mm": float(np.max(np.abs(rf))),
            "max_relief_error_mm": float(np.max(np.abs(rf - re))),
            "n_relief_corrections": int(np.count_nonzero(np.abs(re) > THRESHOLD_MM)),
            "max_tilt_exact_mm": max_te,
            "max_tilt_approx_mm": float(np.max(np.abs(ta))),
            "max_tilt_error_mm": float(np.max(err)),
            "max_tilt_error_percent": float(100.0 * np.max(err) / max_te) if max_te > 1e-12 else 0.0,
            "n_tilt_corrections": int(np.count_nonzero(np.abs(te) > THRESHOLD_MM)),
        }

    def table(self) -> pd.DataFrame:
        s = self.summary()
        rows = [
            ("Flying height H (above the mean plane)", "m", s["H_m"]),
            ("on = f·tg α", "mm", s["on_mm"]),
            ("oc = −f·tg(α/2)", "mm", s["oc_mm"]),
            ("max |δh| exact", "mm", s["max_relief_exact_mm"]),
            ("max |δh| = r·h/H", "mm", s["max_relief_formula_mm"]),
            ("points with |δh| > 0.2 mm", "", s["n_relief_corrections"]),
            ("max |δα| exact", "mm", s["max_tilt_exact_mm"]),
            ("max |δα| guide's formula", "mm", s["max_tilt_approx_mm"]),
            ("max |formula − exact|", "mm", s["max_tilt_error_mm"]),
            ("… relative to max |δα|", "%", s["max_tilt_error_percent"]),
            ("points with |δα| > 0.2 mm", "", s["n_tilt_corrections"]),
        ]
        return pd.DataFrame(rows, columns=["quantity", "unit", "value"]).set_index("quantity")


def displacement_field(f_mm: float = 100.0, m: float = 12000.0, alpha_deg: float = 3.0, lambda_deg: float = -60.0,
                       relief_m: float = 60.0, *, grid_n: int = 9, frame_mm: float = 180.0,
                       extent: float = 0.85) -> DisplacementField:
    """Relief and tilt displacement vectors over the analytic hills (chapters 03–04).

    Parameters
    ----------
    f_mm : focal length f, mm
    m : scale denominator of the equivalent vertical photo over the mean plane; H = f·m
    alpha_deg, lambda_deg : tilt α and direction λ of the principal vertical (see
        :mod:`aerophoto.geometry`), degrees; κ = 0
    relief_m : relief amplitude of :class:`AnalyticHills`, m (0 ≤ relief < H)
    grid_n : points per side of the photo grid
    extent : the grid spans ±extent·(frame/2) on the photo

    The hills are laid out on the vertical photo's footprint (L = frame/2·m),
    so they stay in view at every scale.  Everything is projected with
    :mod:`aerophoto.geometry`: mean-plane ground points under the grid by
    :func:`~aerophoto.geometry.photo_to_plane`, their terrain images by
    :func:`~aerophoto.geometry.ground_to_photo`, the vertical-photo images by
    :func:`~aerophoto.geometry.tilt_displacement_vectors`.
    """
    cam = g.Camera(f_mm, frame_mm)
    m = check_range("m", m, 100.0, 1e6)
    H = cam.f_mm / 1000.0 * m
    relief = check_range("relief_m", relief_m, 0.0, H, hi_open=True, unit="m")
    pose = g.Pose(0.0, 0.0, H, alpha_deg, lambda_deg, 0.0)
    n = int(grid_n)
    if n < 2 or n > 60:
        raise ValueError(f"grid_n = {grid_n} is outside the valid range 2 ≤ grid_n ≤ 60")
    t = np.linspace(-1.0, 1.0, n) * check_range("extent", extent, 0.0, 1.0, lo_open=True) * cam.half_mm
    gx, gy = np.meshgrid(t, t)
    grid = np.column_stack([gx.ravel(), gy.ravel()])
    terrain = AnalyticHills(relief, cam.half_mm / 1000.0 * m)
    P0 = g.photo_to_plane(cam, pose, grid, 0.0)
    h = terrain.height(P0[:, 0], P0[:, 1])
    P = P0.copy()
    P[:, 2] = h
    xy_actual, xy_plane = relief_displacement_vectors(cam, pose, P, 0.0)
    n_mm = g.nadir_point(cam, pose)
    c_mm = g.isocentre(cam, pose)
    r_n = np.hypot(*(xy_actual - n_mm).T)
    formula = g.relief_displacement(r_n, h, H)
    xy_t, xy_v = g.tilt_displacement_vectors(cam, pose, P0)
    exact = np.hypot(*(xy_t - c_mm).T) - np.hypot(*(xy_v - c_mm).T)
    approx = g.tilt_displacement_approx(cam, pose, xy_t)
    return DisplacementField(cam, pose, terrain, xy_plane, h, xy_actual, np.asarray(formula), xy_v,
                             exact, np.asarray(approx), g.principal_point(cam, pose), n_mm, c_mm)


# =========================================================================== the guide's tables
# Printed values of the guide's tables 2–7 (§4–§5, worked example), OCR cleaned.
_T2 = dict(bases=(("I-1", 28.0, 18.4), ("I-2", 30.1, 19.8), ("II-3", 36.0, 24.3), ("II-4", 33.8, 22.9)),
           m_i=(15220, 15220, 14810, 14760), heights=(140, 180), m_part=(15210, 14790), m_mean=15000,
           dm=(-210, +210), N=(72, 70), unit=10)
_T4 = dict(bases=(("I-1", 28.0, 18.7), ("I-2", 30.1, 20.0), ("II-3", 36.0, 24.0), ("II-4", 33.8, 22.6)),
           m_i=(15010, 15050, 15000, 14950), heights=(140, 180), m_part=(15030, 14980), m_mean=15000,
           dm=(-30, +20), N=(500, 750), unit=10)
_T5 = dict(bases=(("I-1", 35.3, 26.8), ("I-2", 36.4, 28.2), ("II-3", 40.6, 32.5), ("II-4", 40.1, 31.9),
                  ("III-5", 29.0, 24.5), ("III-6", 32.1, 27.7)),
           m_i=(13172, 12880, 12492, 12570, 11837, 11758), m_part=(13026, 12531, 11798), m_mean=12451,
           dm=(-575, -80, +653), N=(23, 157, 18), unit=1)
_T7 = dict(bases=(("I-1", 35.3, 27.8), ("I-2", 36.4, 28.9), ("II-3", 40.6, 32.5), ("II-4", 40.1, 31.9),
                  ("III-5", 29.0, 23.4), ("III-6", 32.1, 25.7)),
           m_i=(12698, 12595, 12492, 12570, 12393, 12490), m_part=(12646, 12531, 12442), m_mean=12540,
           dm=(-106, +9, +98), N=(118, 1400, 128), unit=1)
_T3 = dict(names=("I", "1", "2", "II", "3", "4"), Z=(141, 138, 141, 180, 178, 182), h=(-19, -22, -19, 20, 18, 22),
           r=(76, 78, 81, 83, 73, 78), delta=(-1.0, -1.1, -1.0, 1.1, 0.9, 1.1))
# the bases of tables 2 and 4 join the zone's main point to the other two points
_T3_BASES = (("I", "1"), ("I", "2"), ("II", "3"), ("II", "4"))
_T6 = dict(names=("I", "1", "2", "II", "3", "4", "III", "5", "6"),
           r_c=(67.0, 43.0, 59.0, 24.6, 9.5, 22.0, 36.4, 43.0, 32.1),
           phi=(7, 9, 343, 186, 135, 264, 196, 172, 195),
           cos=(0.992, 0.987, 0.956, -0.994, -0.707, -0.104, -0.961, -0.990, -0.965),
           delta=(-2.0, -0.8, -1.5, 0.3, 0.0, 0.0, 0.6, 0.8, 0.4))

_TITLES = {
    2: "Table 2. Partial and mean scales of the bases (guide §4)",
    3: "Table 3. Corrections for relief (guide §4)",
    4: "Table 4. Partial and mean scales by the corrected points (guide §4)",
    5: "Table 5. Partial and mean scales of the photo (guide §5, example)",
    6: "Table 6. Corrections of photo points for tilt (guide §5)",
    7: "Table 7. Partial and mean scales by points corrected for tilt (guide §5)",
}

#: How far a printed number may sit from the computed one and still "follow": this
#: fraction of a unit of its last printed digit — half a unit for the final rounding,
#: plus a little for the guide's rounding of intermediate values by hand.
ROUNDING_UNITS = 0.6

_SIGN = ("sign reversed: the guide printed m_cp − m_част, but its own definition (§5 step 8: "
         "Δm = m_част − m_cp, the deviation of the partial scale from the mean) gives {c:+.0f}")

# (table, row, column) → why the printed value does not follow from its inputs
_REASONS = {
    (2, "I-2", "m_i"): "30.1·10000/19.8 = 15202, not 15220: the value of I-1 was copied down (the printed "
                       "m_част = 15210 was computed with 15202)",
    (2, "I", "Δm_i"): _SIGN,
    (2, "II", "Δm_i"): _SIGN,
    (2, "I", "Δm_i/m_cp"): "divided by m_част instead of m_cp: 15210/210 = 72; m_cp/|Δm| = {c:.1f}, and the "
                           "two zones, with equal |Δm|, must show the same ratio",
    (2, "II", "Δm_i/m_cp"): "divided by m_част instead of m_cp: 14790/210 = 70; m_cp/|Δm| = {c:.1f}",
    (4, "I-1", "m_i"): "28.0·10000/18.7 = 14973, not 15010 (15010 = 28.0·10000/18.65: the corrected length "
                       "before it was rounded to 18.7)",
    (4, "I", "m_част"): "carried from the misprinted m_i of I-1: (14973 + 15050)/2 = {c:.0f}",
    (4, "I", "Δm_i"): "sign reversed (printed m_cp − m_част) and carried from the misprinted m_i of I-1: "
                      "Δm = m_част − m_cp = {c:+.1f}",
    (4, "II", "Δm_i"): "sign reversed (printed m_cp − m_част) and carried from the misprinted m_i of I-1: "
                       "Δm = {c:+.1f}",
    (4, "I", "Δm_i/m_cp"): "carried from the misprinted m_i of I-1: m_cp/|Δm| = {c:.0f}; after the relief "
                           "correction the two zones agree to 1/900, not 1/500",
    (4, "II", "Δm_i/m_cp"): "carried from the misprinted m_i of I-1: m_cp/|Δm| = {c:.0f}",
    (5, "I-2", "m_i"): "36.4·10000/28.2 = 12908, not 12880",
    (5, "III-6", "m_i"): "32.1·10000/27.7 = 11588, not 11758 (11758 = 32.1·10000/27.3: the photo length was "
                         "probably 27.3 mm, misprinted 27.7)",
    (5, "I", "m_част"): "carried from the misprinted m_i of I-2: (13172 + 12908)/2 = {c:.0f}",
    (5, "III", "m_част"): "carried from the misprinted m_i of III-6: (11837 + 11588)/2 = {c:.0f}",
    (5, "", "m_cp"): "carried from the two misprinted m_i: the mean of the zones is {c:.0f}",
    (5, "I", "Δm_i"): "sign reversed (printed m_cp − m_част) and carried from the misprinted m_i: Δm = {c:+.0f}",
    (5, "II", "Δm_i"): "sign reversed (printed m_cp − m_част) and carried from the misprinted m_cp: Δm = {c:+.0f}",
    (5, "III", "Δm_i"): "sign reversed (printed m_cp − m_част) and carried from the misprinted m_i: Δm = {c:+.0f}",
    (5, "I", "Δm_i/m_cp"): "divided by m_част instead of m_cp (13026/575 = 22.7) and carried: m_cp/|Δm| = {c:.1f}",
    (5, "II", "Δm_i/m_cp"): "divided by m_част instead of m_cp (12531/80 = 157) and carried: m_cp/|Δm| = {c:.0f}",
    (5, "III", "Δm_i/m_cp"): "divided by m_част instead of m_cp (11798/653 = 18.1) and carried: m_cp/|Δm| = {c:.1f}",
    (6, "I", "δα"): "with f = 100 mm and α = 3° the formula gives {c:.2f}; the printed column fits "
                    "sin α/f ≈ 4.5·10⁻⁴ mm⁻¹ (f ≈ 117 mm at α = 3°, or α ≈ 2.57° at f = 100 mm), see table6_fit()",
    (6, "1", "δα"): "with f = 100 mm and α = 3° the formula gives {c:.2f} (see I)",
    (6, "2", "δα"): "with f = 100 mm and α = 3° the formula gives {c:.2f} (see I)",
    (6, "III", "δα"): "with f = 100 mm and α = 3° the formula gives {c:+.2f} (see I)",
    (6, "5", "δα"): "with f = 100 mm and α = 3° the formula gives {c:+.2f} (see I)",
    (6, "6", "δα"): "with f = 100 mm and α = 3° the formula gives {c:+.2f} (see I)",
    (7, "I", "Δm_i"): _SIGN,
    (7, "II", "Δm_i"): _SIGN + "; |Δm| = 8.5 also rounds to 8, not 9",
    (7, "III", "Δm_i"): _SIGN,
    (7, "II", "Δm_i/m_cp"): "follows from |Δm| rounded up to 9 (12540/9 = 1393); with |Δm| = 8.46 it is "
                            "1/{c:.0f}, i.e. 1/1500",
    (7, "III-6", "l_сн"): "cannot follow from table 5: the corrections of III (δα = {a:+.2f}) and 6 ({b:+.2f}) "
                          "change the base by at most {s:.2f} mm, but it shrank from 27.7 to 25.7 mm",
}


@dataclass(frozen=True)
class CellCheck:
    """One printed number of a guide table against the number that follows from the inputs.

    Attributes
    ----------
    table : int
        The guide's table number (2–7).
    row : str
        Row label as printed (a base ``"I-2"``, a zone ``"I"``, a point ``"3"``; ``""`` for m_cp).
    column : str
        Column, e.g. ``"m_i"``, ``"Δm_i"``, ``"δα"``.
    printed : float
        The guide's value (for ratios 1/N: N).
    computed : float
        The value computed from the table's printed inputs at full precision (for
        interval checks: the admissible value nearest to the printed one).
    tol : float
        Largest |printed − computed| still explained by rounding.
    reason : str
        Why the printed value does not follow; empty if it does.
    bounds : tuple or None
        (lo, hi) for interval checks (a corrected length must lie in the range
        the corrections allow).
    """

    table: int
    row: str
    column: str
    printed: float
    computed: float
    tol: float
    reason: str = ""
    bounds: tuple | None = None

    @property
    def ok(self) -> bool:
        """The printed value follows from the inputs within rounding."""
        return abs(self.printed - self.computed) <= self.tol

    @property
    def key(self) -> tuple:
        return (self.table, self.row, self.column)


def _cell(table, row, column, printed, computed, unit, units=ROUNDING_UNITS, bounds=None, **fmt):
    tol = units * unit
    c = CellCheck(table, row, column, float(printed), float(computed), tol, "", bounds)
    if not c.ok:
        template = _REASONS.get(c.key, "does not follow from its printed inputs")
        reason = template.format(c=computed, **fmt) if "{" in template else template
        c = CellCheck(table, row, column, float(printed), float(computed), tol, reason, bounds)
    return c


def _ratio_unit(N: float) -> float:
    """Unit of the last significant digit of a printed 1/N (72 → 1, 750 → 10, 1400 → 100)."""
    N = int(round(N))
    if N < 100:
        return 1.0
    u = 1
    while N % (u * 10) == 0:
        u *= 10
    return float(u)


@dataclass(frozen=True)
class GuideTable:
    """One of the guide's tables 2–7: computed from its printed inputs, and compared.

    Attributes
    ----------
    number : int
    title : str
    result : :class:`ScaleTable`, :class:`ReliefCorrections` or :class:`TiltCorrections`
        The table computed by the package from the printed inputs.
    printed : pandas.DataFrame
        The table as printed in the guide (OCR cleaned).
    checks : tuple of :class:`CellCheck`
        Every printed number that can be computed, printed vs computed.
    notes : tuple of str
        Remarks on the table that are not single cells.
    """

    number: int
    title: str
    result: object
    printed: pd.DataFrame
    checks: tuple
    notes: tuple = ()

    def table(self) -> pd.DataFrame:
        """The computed table, laid out like the guide's."""
        return self.result.table()

    @property
    def discrepancies(self) -> tuple:
        """The checks whose printed value does not follow (more than rounding)."""
        return tuple(c for c in self.checks if not c.ok)

    def comparison(self, *, only_discrepancies: bool = True) -> pd.DataFrame:
        """Printed vs computed, one row per cell: row, column, printed, computed, verdict, reason."""
        rows = []
        for c in self.checks:
            if only_discrepancies and c.ok:
                continue
            rows.append({"row": c.row or "—", "column": c.column, "printed": _num(c.printed, c.column, printed=True),
                         "computed": _num(c.computed, c.column, c.bounds),
                         "verdict": "follows" if c.ok else "does not follow", "reason": c.reason})
        return pd.DataFrame(rows, columns=["row", "column", "printed", "computed", "verdict", "reason"])

    def display_table(self) -> pd.DataFrame:
        """The computed table with numbers formatted at the guide's precision (strings, blanks for empty)."""
        df = self.table()
        out = pd.DataFrame(index=df.index)
        for col in df.columns:
            out[col] = [_fmt_cell(v, col, self.number) for v in df[col]]
        return out

    def _repr_html_(self) -> str:
        from .plots import html_table

        left = html_table(self.display_table(), caption=self.title + " — computed by aerophoto")
        disc = self.comparison()
        if len(disc):
            right = html_table(disc.set_index("row"), caption="Printed vs computed: the cells that do not follow")
        else:
            right = "<p><b>Printed vs computed:</b> every printed number follows from its inputs.</p>"
        notes = "".join(f"<li>{_esc(n)}</li>" for n in self.notes)
        notes_html = f"<ul style='margin:4px 0 0 16px;padding:0;font-size:13px'>{notes}</ul>" if notes else ""
        return ("<div class='aerophoto-guide-table' style='display:flex;flex-wrap:wrap;gap:16px;"
                "align-items:flex-start'><style>.aerophoto-guide-table td{text-align:left}</style>"
                f"<div>{left}</div><div style='flex:1 1 420px;max-width:600px'>{right}{notes_html}</div></div>")


def _esc(s: str) -> str:
    import html

    return html.escape(s)


def _num(v, column, bounds=None, printed=False):
    """A cell value as text: printed values as the guide prints them, computed ones with a digit more."""
    if bounds is not None:
        return f"{bounds[0]:.2f} … {bounds[1]:.2f}"
    if column == "Δm_i/m_cp":
        return f"1/{v:.0f}" if printed or v >= 1000 else f"1/{v:.1f}"
    if column in ("δα", "δh"):
        return f"{v:+.1f}" if printed else f"{v:+.2f}"
    if column == "l_сн":
        return f"{v:.1f}" if printed else f"{v:.2f}"
    if column == "cos φ":
        return f"{v:+.3f}" if printed else f"{v:+.4f}"
    if column == "Δm_i":
        return f"{v:+.0f}" if printed else f"{v:+.1f}"
    if column.startswith("m_"):
        return f"{v:.0f}" if printed else f"{v:.1f}"
    return f"{v:g}" if printed else f"{v:.2f}"


def _fmt_cell(v, col, table):
    if isinstance(v, str):
        return v
    if v is None or (isinstance(v, float) and np.isnan(v)):
        return ""
    if col.startswith("l_"):
        return f"{v:.1f}"
    if col in ("m_i", "m_част", "m_cp"):
        return f"{v:.0f}"
    if col == "Δm_i":
        return f"{v:+.0f}"
    if col.startswith("mean height"):
        return f"{v:.0f}"
    if col in ("Z_i, m", "r, mm"):
        return f"{v:.0f}"
    if col == "h, m":
        return f"{v:+.1f}"
    if col.startswith("δ"):
        return f"{v:+.2f}"
    if col == "cos φ":
        return f"{v:+.3f}"
    if col == "r_c, mm":
        return f"{v:.1f}"
    if col == "φ, °":
        return f"{v:.0f}"
    return f"{v:g}"


def _printed_scale_frame(t: dict) -> pd.DataFrame:
    bases = t["bases"]
    zones = list(dict.fromkeys(b[0].split("-")[0] for b in bases))
    df = pd.DataFrame(index=pd.Index([b[0] for b in bases], name="base"))
    if "heights" in t:
        df["mean height of bases, m"] = ""
    df["l_пл, mm"] = [f"{b[1]:.1f}" for b in bases]
    df["l_сн, mm"] = [f"{b[2]:.1f}" for b in bases]
    df["m_i"] = [str(v) for v in t["m_i"]]
    df["m_част"] = ""
    df["m_cp"] = ""
    df["Δm_i"] = ""
    df["Δm_i/m_cp"] = ""
    for k, z in enumerate(zones):
        last = max(i for i, b in enumerate(bases) if b[0].split("-")[0] == z)
        df.iloc[last, df.columns.get_loc("m_част")] = str(t["m_part"][k])
        df.iloc[last, df.columns.get_loc("Δm_i")] = f"{t['dm'][k]:+d}"
        df.iloc[last, df.columns.get_loc("Δm_i/m_cp")] = f"1/{t['N'][k]}"
        if "heights" in t:
            df.iloc[last, df.columns.get_loc("mean height of bases, m")] = str(t["heights"][k])
    mid_zone = zones[len(zones) // 2]
    first = min(i for i, b in enumerate(bases) if b[0].split("-")[0] == mid_zone)
    df.iloc[first, df.columns.get_loc("m_cp")] = str(t["m_mean"])
    return df


def _scale_checks(number: int, t: dict, res: ScaleTable) -> list:
    unit = t["unit"]
    checks = []
    for b, mp, mc in zip(res.bases, t["m_i"], res.m_i):
        checks.append(_cell(number, b.name, "m_i", mp, mc, unit))
    for z, mp, mc in zip(res.zones, t["m_part"], res.m_part):
        checks.append(_cell(number, z, "m_част", mp, mc, unit))
    checks.append(_cell(number, "", "m_cp", t["m_mean"], res.m_mean, unit))
    for z, dp, dc in zip(res.zones, t["dm"], res.dm):
        checks.append(_cell(number, z, "Δm_i", dp, dc, unit))
    for z, Np, Nc in zip(res.zones, t["N"], res.ratio_N):
        checks.append(_cell(number, z, "Δm_i/m_cp", Np, Nc, _ratio_unit(Np)))
    return checks


@lru_cache(maxsize=None)
def _table3_parts():
    names, Z = _T3["names"], dict(zip(_T3["names"], _T3["Z"]))
    zones = {}
    for a, b in _T3_BASES:
        zones.setdefault(a, []).append((Z[a], Z[b]))
    z_heights = tuple(zone_height(v) for v in zones.values())
    Zcp = mean_object_plane(z_heights)
    return names, z_heights, Zcp


@lru_cache(maxsize=None)
def guide_table(number: int) -> GuideTable:
    """The guide's table ``number`` (2–7) computed from its printed inputs and compared.

    Inputs taken as printed: the lengths l_пл and l_сн (tables 2, 4, 5, 7;
    M = 10000), the heights Z and distances r (table 3), the distances r_c and
    angles φ (table 6).  Everything else is computed at full precision and
    compared with the printed number; the flying height of table 3 is
    H = m_cp·f with m_cp from table 2 and f = 100 mm, and table 6 uses
    f = 100 mm and α = 3° (the guide's example).  Tables 4 and 7 are also
    checked against tables 2–3 and 5–6: a corrected length must be one the
    corrections can produce.  The result is computed once and cached: treat
    it as read-only.
    """
    number = int(check_range("number", number, 2, 7))
    if number in (2, 4):
        t = _T2 if number == 2 else _T4
        _, z_heights, _ = _table3_parts()
        res = partial_scales(t["bases"], GUIDE_M_PLAN, zone_heights_m=z_heights)
        checks = [_cell(number, z, "mean height", hp, hc, 1.0) for z, hp, hc in zip(res.zones, t["heights"], z_heights)]
        checks += _scale_checks(number, t, res)
        notes = []
        if number == 2:
            notes.append("The ratio column is Δm/m_част in the print (15210/210 = 72, 14790/210 = 70); the guide's "
                         "heading asks for Δm/m_cp, which is the same for both zones here.")
            notes.append("Step 3 of §4 says the partial scales come from formula (4.1); it means m = l_пл·M/l_сн, "
                         "numbered (5.1) in §5 — (4.1) is the relief formula.")
        else:
            checks += _table4_length_checks()
            notes.append("The corrected photo lengths l_сн follow from table 2 and table 3: moving both ends of a "
                         "base radially by δh shrinks or stretches it by the factor (1 − h/H) about n, so "
                         "l' ≈ l·(1 − h̄/H) — 18.4 → 18.65, 19.8 → 20.05, 24.3 → 23.99, 22.9 → 22.58 mm.")
            notes.append("m_i of II-4: 33.8·10000/22.6 = 14955.8, printed 14950 (rounded down; within rounding).")
        title = _TITLES[number]
        return GuideTable(number, title, res, _printed_scale_frame(t), tuple(checks), tuple(notes))
    if number == 3:
        names, z_heights, Zcp = _table3_parts()
        H = flying_height(guide_table(2).result.m_mean, GUIDE_F_MM)
        res = relief_corrections(names, _T3["Z"], _T3["r"], H, Zcp)
        checks = []
        for nm, hp, hc in zip(names, _T3["h"], res.h_m):
            checks.append(_cell(3, nm, "h", hp, hc, 1.0))
        for nm, dp, dc in zip(names, _T3["delta"], res.delta_mm):
            checks.append(_cell(3, nm, "δh", dp, dc, 0.1))
        printed = pd.DataFrame({"Z_i, m": _T3["Z"], "h, m": [f"{v:+d}" for v in _T3["h"]], "r, mm": _T3["r"],
                                "δh, mm": [f"{v:+.1f}" for v in _T3["delta"]]},
                               index=pd.Index(names, name="point"))
        notes = (
            f"Mean object plane: Z_Icp = {z_heights[0]:.2f} m, Z_IIcp = {z_heights[1]:.2f} m, "
            f"Z_cp = {Zcp:.3f} m (each zone: the mean of its two bases' mean heights).",
            f"H = m_cp·f = {guide_table(2).result.m_mean:.1f} × 0.100 m = {H:.1f} m, with m_cp from table 2 and "
            "f = 100 mm — not the §2 flight's H = 1200 m (with 1200 m every δh would be 25 % larger, "
            "e.g. −1.2 mm for I).",
            "All six |δh| exceed 0.2 mm, so all six points are corrected: zone I (below the plane) away from n, "
            "zone II (above it) towards n.",
        )
        return GuideTable(3, _TITLES[3], res, printed, tuple(checks), notes)
    if number == 6:
        res = tilt_corrections(_T6["names"], _T6["r_c"], _T6["phi"], f_mm=GUIDE_F_MM, alpha_deg=GUIDE_ALPHA_DEG)
        checks = []
        for nm, cp, cc in zip(res.names, _T6["cos"], res.cos_phi):
            # the guide truncates cos φ to three decimals: allow a whole unit
            checks.append(_cell(6, nm, "cos φ", cp, cc, 0.001, units=1.0))
        for nm, dp, dc in zip(res.names, _T6["delta"], res.delta_approx_mm):
            checks.append(_cell(6, nm, "δα", dp, dc, 0.1))
        printed = pd.DataFrame({"r_c, mm": [f"{v:.1f}" for v in _T6["r_c"]], "φ, °": _T6["phi"],
                                "cos φ": [f"{v:+.3f}" for v in _T6["cos"]],
                                "δα, mm": [f"{v:+.1f}" if v else "0" for v in _T6["delta"]]},
                               index=pd.Index(_T6["names"], name="point"))
        fit = table6_fit()
        notes = (
            f"oc = −f·tg(α/2) = {res.oc_mm:.2f} mm for f = 100 mm, α = 3° (guide: −2.6 mm).",
            f"The printed δα fit one constant k = sin α/f: least squares k = {fit.k_lsq:.3e} mm⁻¹; every printed "
            f"value is reproduced (after rounding to 0.1 mm) for {fit.k_lo:.3e} ≤ k ≤ {fit.k_hi:.3e}, i.e. "
            f"f = {fit.f_range_mm[0]:.1f}…{fit.f_range_mm[1]:.1f} mm at α = 3°, or α = "
            f"{fit.alpha_range_deg[0]:.2f}…{fit.alpha_range_deg[1]:.2f}° at f = 100 mm. f = 100 mm, α = 3° gives "
            f"k = {math.sin(math.radians(3)) / 100:.3e}: 6 of 9 values differ.",
            "cos φ agrees with φ everywhere, but is truncated to three decimals, not rounded (cos 9° = 0.9877 is "
            "printed 0.987). φ is counted counter-clockwise from the positive principal vertical; cos φ cannot "
            "tell the sense of rotation, so δα does not depend on it — only the direction of the move does.",
            "The continuation of this table is headed 'Окончание табл. 3' in the guide: it is the end of table 6.",
            "The points of table 6 are not the ends of table 5's bases: placed by r_c and φ, base II-3 would be "
            f"{_t6_distance('II', '3'):.1f} mm long on the photo (table 5: 32.5 mm) and III-6 "
            f"{_t6_distance('III', '6'):.1f} mm (27.7 mm).",
            "II (|δα| = 0.3 mm > 0.2 mm) is to be corrected, yet bases II-3 and II-4 keep their lengths in "
            "table 7 — possible only if the move is across the bases.",
        )
        return GuideTable(6, _TITLES[6], res, printed, tuple(checks), notes)
    # number 5 or 7
    t = _T5 if number == 5 else _T7
    res = partial_scales(t["bases"], GUIDE_M_PLAN)
    checks = _scale_checks(number, t, res)
    notes = []
    if number == 7:
        checks += _table7_length_checks()
        notes.append("The ratio column is Δm/m_cp here (12540/106 = 118), unlike tables 2 and 5.")
        notes.append("Bases II-3 and II-4 are copied from table 5 although II was to be corrected (δα = +0.3 mm).")
    else:
        notes.append("The ratio column is Δm/m_част in the print (13026/575 = 22.7, 12531/80 = 157, 11798/653 = 18.1).")
    return GuideTable(number, _TITLES[number], res, _printed_scale_frame(t), tuple(checks), tuple(notes))


def _t6_distance(a: str, b: str) -> float:
    names = _T6["names"]
    cam = g.Camera(GUIDE_F_MM)
    pose = g.Pose(alpha_deg=GUIDE_ALPHA_DEG)
    xy = point_from_polar(cam, pose, _T6["r_c"], _T6["phi"])
    return float(np.hypot(*(xy[names.index(a)] - xy[names.index(b)])))


def _table4_length_checks() -> list:
    """Corrected lengths of table 4 against table 2's lengths and table 3's δh (homothety about n)."""
    res3 = guide_table(3).result
    h = dict(zip(res3.names, res3.h_m))
    r = dict(zip(res3.names, res3.r_mm))
    checks = []
    for (name, _, l_before), (_, _, l_after), (a, b) in zip(_T2["bases"], _T4["bases"], _T3_BASES):
        hbar = (h[a] + h[b]) / 2.0
        pred = l_before * (1.0 - hbar / res3.H_m)
        # ends at different heights: the move is not a pure scaling; bound the difference
        spread = abs(h[a] - h[b]) / (2.0 * res3.H_m) * (r[a] + r[b])
        lo, hi = pred - spread, pred + spread
        nearest = min(max(l_after, lo), hi)
        checks.append(_cell(4, name, "l_сн", l_after, nearest, 0.1, bounds=(lo, hi)))
    return checks


def _table7_length_checks() -> list:
    """Corrected lengths of table 7 against table 5 and the corrections of table 6 (|Δl| ≤ |δa| + |δb|)."""
    res6 = guide_table(6).result
    d = dict(zip(res6.names, np.where(res6.apply, res6.delta_approx_mm, 0.0)))
    checks = []
    for (name, _, l_before), (_, _, l_after) in zip(_T5["bases"], _T7["bases"]):
        a, b = name.split("-")
        s = abs(d[a]) + abs(d[b])
        lo, hi = l_before - s, l_before + s
        nearest = min(max(l_after, lo), hi)
        checks.append(_cell(7, name, "l_сн", l_after, nearest, 0.1, bounds=(lo, hi), a=d[a], b=d[b], s=s))
    return checks


def guide_discrepancies() -> pd.DataFrame:
    """Every printed number of tables 2–7 that does not follow from its inputs, with the reason."""
    rows = []
    for n in range(2, 8):
        t = guide_table(n)
        for c in t.discrepancies:
            rows.append({"table": n, "row": c.row or "—", "column": c.column,
                         "printed": _num(c.printed, c.column, printed=True),
                         "computed": _num(c.computed, c.column, c.bounds), "reason": c.reason})
    return pd.DataFrame(rows, columns=["table", "row", "column", "printed", "computed", "reason"])


# --------------------------------------------------------------------------- table 6 hypotheses
@dataclass(frozen=True)
class Table6Fit:
    """Which reading of the guide's table 6 reproduces its printed δα column.

    The guide's formula is δα = −k·r_c²·cos φ with k = sin α/f.  Every printed
    δα (rounded to 0.1 mm) is reproduced exactly for k_lo ≤ k ≤ k_hi.

    Attributes
    ----------
    k_lsq : float
        Least-squares k over the nine points, mm⁻¹.
    k_lo, k_hi : float
        The range of k that reproduces every printed value after rounding, mm⁻¹.
    f_range_mm : (float, float)
        The f that does so with α = 3°.
    alpha_range_deg : (float, float)
        The α that does so with f = 100 mm.
    f_best_mm, alpha_best_deg : float
        The least-squares f (α = 3°) and α (f = 100 mm).
    candidates : pandas.DataFrame
        Readings tested, with how many of the nine printed values each
        reproduces and the residuals (printed − computed).
    """

    k_lsq: float
    k_lo: float
    k_hi: float
    f_range_mm: tuple
    alpha_range_deg: tuple
    f_best_mm: float
    alpha_best_deg: float
    candidates: pd.DataFrame = field(repr=False)


@lru_cache(maxsize=1)
def table6_fit() -> Table6Fit:
    """Test readings of the guide's table 6 against its printed δα column (see :class:`Table6Fit`)."""
    r = np.array(_T6["r_c"])
    cos_p = np.array(_T6["cos"])
    phi = np.array(_T6["phi"], dtype=float)
    printed = np.array(_T6["delta"])
    x = -(r**2) * cos_p  # δα = k·x
    k_lsq = float(x @ printed / (x @ x))
    lo, hi = 0.0, math.inf
    for xi, p in zip(x, printed):
        a, b = sorted(((p - 0.05) / xi, (p + 0.05) / xi))
        lo, hi = max(lo, a), min(hi, b)
    s3 = math.sin(math.radians(3.0))

    def rows():
        def approx(f, a):
            return tilt_corrections(_T6["names"], r, phi, f_mm=f, alpha_deg=a).delta_approx_mm

        def exact(f, a):
            return tilt_corrections(_T6["names"], r, phi, f_mm=f, alpha_deg=a).delta_exact_mm

        a_best = math.degrees(math.asin(k_lsq * 100.0))
        f_best = s3 / k_lsq
        yield "the guide's inputs: f = 100 mm, α = 3°", 100.0, 3.0, approx(100, 3)
        yield "the exact formula, f = 100 mm, α = 3°", 100.0, 3.0, exact(100, 3)
        yield "f = 100 mm, α = 2.5°", 100.0, 2.5, approx(100, 2.5)
        yield "f = 120 mm (variant 02), α = 3°", 120.0, 3.0, approx(120, 3)
        yield "f = 117 mm, α = 3°", 117.0, 3.0, approx(117, 3)
        yield f"least squares: f = {f_best:.1f} mm, α = 3°", f_best, 3.0, approx(f_best, 3)
        yield f"least squares: f = 100 mm, α = {a_best:.2f}°", 100.0, a_best, approx(100, a_best)
        # r and φ measured from o or from n instead of c (the same points, f = 100 mm, α = 3°)
        cam, pose = g.Camera(100.0), g.Pose(alpha_deg=3.0)
        xy = point_from_polar(cam, pose, r, phi)
        for label, centre in (("o", g.principal_point(cam, pose)), ("n", g.nadir_point(cam, pose))):
            dxy = xy - centre
            r2 = np.sum(dxy**2, axis=1)
            cosp = dxy[:, 0] / np.sqrt(r2)
            yield (f"r and φ measured from {label} instead of c, f = 100 mm, α = 3°", 100.0, 3.0,
                   -r2 * cosp / 100.0 * s3)

    out = []
    for label, f, a, d in rows():
        res = printed - d
        matched = int(np.count_nonzero(np.abs(printed - np.round(d + 1e-12, 1)) < 1e-9))
        out.append({"reading": label, "f, mm": f, "α, °": a, "10⁴·sin α/f, 1/mm": 1e4 * math.sin(math.radians(a)) / f,
                    "matches (of 9)": matched, "max |residual|, mm": float(np.max(np.abs(res))),
                    "rms residual, mm": float(np.sqrt(np.mean(res**2)))})
    cand = pd.DataFrame(out).set_index("reading")
    return Table6Fit(k_lsq, lo, hi, (s3 / hi, s3 / lo),
                     (math.degrees(math.asin(lo * 100)), math.degrees(math.asin(hi * 100))),
                     s3 / k_lsq, math.degrees(math.asin(k_lsq * 100)), cand)


# =========================================================================== lab tasks (chapters 03, 04)
#: The six pricked points of the relief lab (chapter 03): the guide's table 3 points, placed on the photo
#: (x, y in mm from the principal point o) about as far from the centre as the guide's r, with the
#: guide's heights Z (the student's variant adds i metres to every height).
RELIEF_LAB_POINTS = (
    ("I", -52.0, 55.0, 141.0),
    ("1", -70.0, 35.0, 138.0),
    ("2", -40.0, 70.0, 141.0),
    ("II", 60.0, -57.0, 180.0),
    ("3", 45.0, -57.0, 178.0),
    ("4", 70.0, -38.0, 182.0),
)
#: the point of the tilt lab (chapter 04): photo coordinates from o, mm
TILT_LAB_POINT_MM = (70.0, -15.0)


@dataclass(frozen=True)
class ReliefLab:
    """Inputs and answers of the chapter-03 relief task for one variant.

    The photo: the variant's f, scale 1:m and tilt α, λ; the flying height
    above the mean object plane is taken as H = f·m.  The points of
    :data:`RELIEF_LAB_POINTS` with heights Z = Z_guide + i.

    Attributes
    ----------
    names : tuple of str
    xy_mm : (6, 2) photo coordinates from o, mm
    Z_m : (6,) heights, m
    Z_mean_m : the mean object plane Z_cp, m (guide §4: mean of the zones' mean base heights)
    H_m : flying height above the mean plane, H = f·m, m
    n_mm : (2,) the nadir point of the variant's tilted photo, mm
    result : :class:`ReliefCorrections` with r measured from n
    r_from_o_mm : (6,) distances from o — the usual mistake
    """

    names: tuple
    xy_mm: np.ndarray
    Z_m: np.ndarray
    Z_mean_m: float
    H_m: float
    n_mm: np.ndarray
    result: ReliefCorrections
    r_from_o_mm: np.ndarray

    def inputs(self) -> pd.DataFrame:
        """The task's inputs: the points' photo coordinates and heights."""
        return pd.DataFrame({"x, mm": self.xy_mm[:, 0], "y, mm": self.xy_mm[:, 1], "Z, m": self.Z_m},
                            index=pd.Index(self.names, name="point"))

    def delta_from_o_mm(self) -> np.ndarray:
        """δh with r measured from o instead of n (a typical mistake), mm."""
        return self.r_from_o_mm * self.result.h_m / self.H_m

    def delta_absolute_h_mm(self) -> np.ndarray:
        """δh with h taken as the absolute height Z instead of Z − Z_cp (a typical mistake), mm."""
        return self.result.r_mm * self.Z_m / self.H_m


def relief_lab(variant) -> ReliefLab:
    """The chapter-03 relief task for a variant (any object with ``i``, ``f_mm``, ``m``, ``alpha_deg``, ``lambda_deg``)."""
    names = tuple(p[0] for p in RELIEF_LAB_POINTS)
    xy = np.array([[p[1], p[2]] for p in RELIEF_LAB_POINTS])
    Z = np.array([p[3] for p in RELIEF_LAB_POINTS]) + float(variant.i)
    Zd = dict(zip(names, Z))
    zones = [zone_height([(Zd[a], Zd[b]) for a, b in _T3_BASES if a == z]) for z in ("I", "II")]
    Zcp = mean_object_plane(zones)
    H = flying_height(variant.m, variant.f_mm)
    cam = g.Camera(variant.f_mm)
    pose = g.Pose(alpha_deg=variant.alpha_deg, lambda_deg=variant.lambda_deg)
    n = g.nadir_point(cam, pose)
    r = np.hypot(*(xy - n).T)
    res = relief_corrections(names, Z, r, H, Zcp)
    return ReliefLab(names, xy, Z, Zcp, H, n, res, np.hypot(*xy.T))


@dataclass(frozen=True)
class TiltLab:
    """Inputs and answers of the chapter-04 tilt tasks for one variant.

    Attributes
    ----------
    f_mm, alpha_deg, lambda_deg : the variant's camera and tilt
    oc_mm : oc = −f·tg(α/2) with the guide's sign, mm
    c_mm : (2,) photo coordinates of the isocentre c, mm
    point_mm : (2,) the task's point A, mm
    r_c_mm, phi_deg : polar coordinates of A about c (φ counter-clockwise from the + principal vertical)
    delta_mm, delta_exact_mm : δα of A, the guide's formula and exact, mm
    table6 : :class:`TiltCorrections` of the guide's nine table-6 points with the variant's f and α
    """

    f_mm: float
    alpha_deg: float
    lambda_deg: float
    oc_mm: float
    c_mm: np.ndarray
    point_mm: np.ndarray
    r_c_mm: float
    phi_deg: float
    delta_mm: float
    delta_exact_mm: float
    table6: TiltCorrections

    # typical mistakes, for the checks' hints
    @property
    def r_from_o_mm(self) -> float:
        return float(np.hypot(*self.point_mm))

    @property
    def phi_from_x_deg(self) -> float:
        """The angle of A about c counted from the photo's x axis instead of the principal vertical."""
        d_ = self.point_mm - self.c_mm
        return float(np.degrees(np.arctan2(d_[1], d_[0])) % 360.0)

    @property
    def delta_from_o_mm(self) -> float:
        """δα with r and φ measured from o instead of c."""
        u = g.principal_vertical(g.Pose(alpha_deg=self.alpha_deg, lambda_deg=self.lambda_deg))
        r = self.r_from_o_mm
        cosp = float(self.point_mm @ u) / r
        return -(r**2) * cosp / self.f_mm * math.sin(math.radians(self.alpha_deg))

    @property
    def delta_phi_from_x_mm(self) -> float:
        """δα with φ counted from the photo's x axis."""
        return -(self.r_c_mm**2) * math.cos(math.radians(self.phi_from_x_deg)) / self.f_mm * math.sin(
            math.radians(self.alpha_deg))


def tilt_lab(variant) -> TiltLab:
    """The chapter-04 tilt tasks for a variant (any object with ``f_mm``, ``alpha_deg``, ``lambda_deg``)."""
    cam = g.Camera(variant.f_mm)
    pose = g.Pose(alpha_deg=variant.alpha_deg, lambda_deg=variant.lambda_deg)
    c = g.isocentre(cam, pose)
    A = np.array(TILT_LAB_POINT_MM, dtype=float)
    r, phi = polar_about_isocentre(cam, pose, A)
    approx = float(g.tilt_displacement_approx(cam, pose, A))
    exact = float(g.tilt_displacement_exact(cam, pose, A))
    t6 = tilt_corrections(_T6["names"], _T6["r_c"], _T6["phi"], f_mm=variant.f_mm, alpha_deg=variant.alpha_deg)
    return TiltLab(cam.f_mm, pose.alpha_deg, pose.lambda_deg, isocentre_offset(cam.f_mm, pose.alpha_deg), c, A,
                   float(r), float(phi), approx, exact, t6)


def angle_answer(value):
    """A student's angle answer brought into 0…360° (other values — ``...``, None, text — unchanged)."""
    if isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool):
        return float(value) % 360.0
    return value
