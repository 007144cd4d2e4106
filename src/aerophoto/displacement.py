"""Relief and tilt displacement of photo points, and the scales of bases (guide §4–§5).

Two effects move a point's image away from where a vertical photo of flat
ground would put it:

* **Relief displacement** (смещение за рельеф, guide §4).  A point at height h
  above the mean object plane (средняя предметная плоскость) is imaged
  farther from the nadir point n than it would be if it lay on that plane:

      δh = r·h / H            (guide formula 4.1)

  r is the distance of the image from n (mm), H = m_cp·f the flying height
  above the plane (m, :func:`aerophoto.geometry.flying_height_m`).  The
  displacement is radial from n: positive away from n (the point is above the
  plane), negative towards n.  The correction is the opposite move — towards
  n for δh > 0, away from n for δh < 0 — and the guide applies it only when
  |δh| > 0.2 mm.

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
table 3 and :func:`tilt_corrections` table 6.  :func:`relief_work` and
:func:`tilt_work` run the whole procedure of §4 (tables 2 → 3 → 4) and §5
(tables 5 → 6 → 7) on one set of measurements: photo coordinates of the
pricked points and plan lengths of the bases.

Where the rest lives: the guide's printed tables 2–7 and their audits in
:mod:`aerophoto.guide.ch03` and :mod:`aerophoto.guide.ch04`; the lab tasks of
chapters 03 and 04 in :mod:`aerophoto.tasks.ch03` and :mod:`aerophoto.tasks.ch04`;
the demo terrain in :mod:`aerophoto.terrain` (:class:`~aerophoto.terrain.AnalyticHills`)
and the explorer's exact displacement field in :mod:`aerophoto.demos.displacement`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Sequence

import numpy as np
import pandas as pd

from . import _validate as V
from . import geometry as g
from ._validate import check_positive, check_range

__all__ = [
    "THRESHOLD_MM",
    "GUIDE_F_MM",
    "GUIDE_ALPHA_DEG",
    "GUIDE_M_PLAN",
    "base_scale",
    "ratio_text",
    "Base",
    "ScaleTable",
    "partial_scales",
    "zone_height",
    "mean_object_plane",
    "ReliefCorrections",
    "relief_corrections",
    "relief_displacement_vectors",
    "isocentre_offset",
    "nadir_offset",
    "point_from_polar",
    "polar_about_isocentre",
    "TiltCorrections",
    "tilt_corrections",
    "apply_radial_corrections",
    "base_lengths_mm",
    "ReliefWork",
    "relief_work",
    "TiltWork",
    "tilt_work",
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
@V.checked(l_plan_mm=V.values(0.0, lo_open=True), l_photo_mm=V.values(0.0, lo_open=True))
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
    N = V.check_range("N", N, 0.0, math.inf, lo_open=True) if N != math.inf else N
    if N == math.inf:
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
        V.check_type("name", self.name, str)
        V.check_type("zone", self.zone, str)
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


@V.checked(bases=V.sequence(min_len=1))
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
@V.checked(base_end_heights_m=V.array(last=2, min_len=1))
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


@V.checked(zone_heights_m=V.array(ndim=1, min_len=1))
def mean_object_plane(zone_heights_m) -> float:
    """Height of the mean object plane Z_cp, m: the mean of the zones' heights (guide §4).

        Z_cp = (Z_Icp + Z_IIcp)/2
    """
    z = np.asarray(zone_heights_m, dtype=float).ravel()
    if len(z) == 0:
        raise ValueError("zone_heights_m is empty; the valid input is at least one zone height (m)")
    return float(z.mean())


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


@V.checked(names=V.names(), Z_m=V.array(ndim=1), r_mm=V.array(ndim=1))
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
        Flying height above the mean object plane, m (guide: H = m_cp·f, see
        :func:`aerophoto.geometry.flying_height_m`).
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


@V.checked(camera=g.Camera, pose=g.Pose, XYZ_m=V.array(last=3))
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
    Pm[..., 2] = check_range("Z_mean_m", Z_mean_m, hi=pose.Z_m, hi_open=True, unit="m")  # below S
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


@V.checked(camera=g.Camera, pose=g.Pose, r_c_mm=V.values(0.0), phi_deg=V.values())
def point_from_polar(camera: g.Camera, pose: g.Pose, r_c_mm, phi_deg) -> np.ndarray:
    """Photo coordinates, shape (..., 2) mm, of points given by r_c and φ about the isocentre.

    φ is counted counter-clockwise from the positive direction of the
    principal vertical (away from n), as in the guide's table 6.
    """
    r = np.asarray(r_c_mm, dtype=float)
    a = np.radians(np.asarray(phi_deg, dtype=float)) + math.radians(pose.lambda_deg)
    c = g.isocentre(camera, pose)
    return np.stack([c[0] + r * np.cos(a), c[1] + r * np.sin(a)], axis=-1)


@V.checked(camera=g.Camera, pose=g.Pose, xy_mm=V.array(last=2))
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


@V.checked(names=V.names(), r_c_mm=V.array(ndim=1), phi_deg=V.array(ndim=1))
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


@V.checked(xy_mm=V.points(2, min_points=1), centre_mm=V.point(2), delta_mm=V.array(ndim=1))
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
    if d.shape != xy.shape[:-1]:
        raise ValueError(f"delta_mm has shape {d.shape}; expected one correction per point of xy_mm, {xy.shape[:-1]}")
    thr = check_range("threshold_mm", threshold_mm, 0.0, unit="mm")
    v = xy - c
    r = np.hypot(v[..., 0], v[..., 1])
    with np.errstate(invalid="ignore", divide="ignore"):
        u = np.where(r[..., None] > 0, v / r[..., None], 0.0)
    move = np.where(np.abs(d) > thr, d, 0.0)
    return xy - u * move[..., None]


# =========================================================================== the whole procedure on measurements
@V.checked(names=V.names(min_len=2), xy_mm=V.points(2, min_points=2), bases=V.pairs())
def base_lengths_mm(names, xy_mm, bases) -> np.ndarray:
    """Lengths, mm, of the bases ``(a, b)`` between named points with coordinates ``xy_mm`` (shape (n, 2)).

    Returns an array of shape (n_bases,).  Works for photo and plan coordinates alike.
    """
    names = tuple(str(n) for n in names)
    xy = np.asarray(xy_mm, dtype=float).reshape(-1, 2)
    if len(xy) != len(names):
        raise ValueError(f"xy_mm has {len(xy)} points for {len(names)} names; they must be equal")
    if not np.all(np.isfinite(xy)):
        raise ValueError("xy_mm contains a value that is not a finite number (mm)")
    idx = {n: k for k, n in enumerate(names)}
    out = []
    for a, b in bases:
        if a not in idx or b not in idx:
            raise ValueError(f"base {a}-{b} joins a point that is not among names {names}")
        out.append(float(np.hypot(*(xy[idx[a]] - xy[idx[b]]))))
    return np.array(out)


def _scale_bases(bases, l_plan_mm, l_photo_mm) -> list:
    lp = np.asarray(l_plan_mm, dtype=float).ravel()
    if len(lp) != len(bases):
        raise ValueError(f"l_plan_mm has {len(lp)} lengths for {len(bases)} bases; they must be equal")
    return [Base(f"{a}-{b}", float(p), float(s), zone=str(a)) for (a, b), p, s in zip(bases, lp, l_photo_mm)]


@dataclass(frozen=True)
class ReliefWork:
    """The guide's §4 on one set of measurements: tables 2, 3 and 4 (steps 3–6).

    Attributes
    ----------
    names : tuple of str
        The pricked points, e.g. ``("I", "1", "2", "II", "3", "4")``.
    bases : tuple of (str, str)
        The bases, each from a zone's main point, e.g. ``(("I", "1"), ("I", "2"), ...)``.
    photo_xy_mm : ndarray, shape (n, 2)
        Measured photo coordinates of the points, mm (origin o).
    l_plan_mm : ndarray, shape (n_bases,)
        Plan lengths l_пл of the bases, mm (photoplan 1:M).
    Z_m : ndarray, shape (n,)
        Heights Z_i of the points, m.
    f_mm, M : float
        Focal length and the plan's scale denominator.
    n_mm : ndarray, shape (2,)
        The nadir point n, mm.
    Z_mean_m : float
        The mean object plane Z_cp: the mean of the zones' heights, each the mean of its bases' mean heights.
    table2 : :class:`ScaleTable`
        Scales before the correction (l_сн from the measured points).
    H_m : float
        H = m_cp·f with m_cp from table 2, m (the guide's choice, §4 step 4).
    table3 : :class:`ReliefCorrections`
        δh = r·h/H with r from n.
    corrected_xy_mm : ndarray, shape (n, 2)
        The points moved back along the radius from n where |δh| > 0.2 mm (step 5).
    table4 : :class:`ScaleTable`
        Scales by the corrected points (step 6).
    """

    names: tuple
    bases: tuple
    photo_xy_mm: np.ndarray
    l_plan_mm: np.ndarray
    Z_m: np.ndarray
    f_mm: float
    M: float
    n_mm: np.ndarray
    Z_mean_m: float
    table2: ScaleTable
    H_m: float
    table3: ReliefCorrections
    corrected_xy_mm: np.ndarray
    table4: ScaleTable


@V.checked(names=V.names(min_len=2), photo_xy_mm=V.points(2, min_points=2), l_plan_mm=V.array(ndim=1),
           Z_m=V.array(ndim=1), bases=V.pairs(), n_mm=V.point(2))
def relief_work(names, photo_xy_mm, l_plan_mm, Z_m, bases, *, f_mm: float, n_mm, M: float = GUIDE_M_PLAN,
                threshold_mm: float = THRESHOLD_MM) -> ReliefWork:
    """Run the guide's §4 (tables 2 → 3 → 4) on measured photo coordinates and plan lengths.

    Parameters
    ----------
    names : sequence of str, length n
    photo_xy_mm : array_like, shape (n, 2)
        Photo coordinates of the pricked points, mm.
    l_plan_mm : array_like, shape (n_bases,)
        Plan lengths of the bases, mm.
    Z_m : array_like, shape (n,)
        Heights of the points, m.
    bases : sequence of (a, b)
        The bases; ``a`` is the zone's main point (its name names the zone).
    f_mm : float
        Focal length, mm (H = m_cp·f).
    n_mm : array_like, shape (2,)
        The nadir point on the photo, mm.
    M : float
        Plan scale denominator (guide: 10 000).

    Every step uses this module's functions: :func:`partial_scales`,
    :func:`zone_height`, :func:`mean_object_plane`, :func:`relief_corrections`,
    :func:`apply_radial_corrections`.
    """
    names = tuple(str(n) for n in names)
    bases = tuple((str(a), str(b)) for a, b in bases)
    xy = np.asarray(photo_xy_mm, dtype=float).reshape(-1, 2)
    Z = np.asarray(Z_m, dtype=float).ravel()
    if len(Z) != len(names):
        raise ValueError(f"Z_m has {len(Z)} heights for {len(names)} names; they must be equal")
    n = np.asarray(n_mm, dtype=float).reshape(2)
    f = check_positive("f_mm", f_mm, unit="mm")
    Zof = dict(zip(names, Z))
    zones = tuple(dict.fromkeys(a for a, _ in bases))
    z_heights = [zone_height([(Zof[a], Zof[b]) for a, b in bases if a == z]) for z in zones]
    Zcp = mean_object_plane(z_heights)
    l_plan = np.asarray(l_plan_mm, dtype=float).ravel()
    t2 = partial_scales(_scale_bases(bases, l_plan, base_lengths_mm(names, xy, bases)), M, zone_heights_m=z_heights)
    H = g.flying_height_m(f, t2.m_mean)
    r = np.hypot(*(xy - n).T)
    t3 = relief_corrections(names, Z, r, H, Zcp, threshold_mm=threshold_mm)
    corrected = apply_radial_corrections(xy, n, t3.delta_mm, threshold_mm)
    t4 = partial_scales(_scale_bases(bases, l_plan, base_lengths_mm(names, corrected, bases)), M,
                        zone_heights_m=z_heights)
    return ReliefWork(names, bases, xy, l_plan, Z, f, float(M), n, Zcp, t2, H, t3, corrected, t4)


@dataclass(frozen=True)
class TiltWork:
    """The guide's §5 on one set of measurements: tables 5, 6 and 7 (steps 6–11).

    Attributes
    ----------
    names, bases, photo_xy_mm, l_plan_mm, M : as :class:`ReliefWork`
    f_mm, alpha_deg, lambda_deg : float
        The camera and the tilt; λ is the direction of the positive principal vertical on the photo.
    c_mm : ndarray, shape (2,)
        The isocentre c, mm.
    table5 : :class:`ScaleTable`
    table6 : :class:`TiltCorrections`
        r_c and φ measured from c (φ from the positive principal vertical, counter-clockwise), δα.
    corrected_xy_mm : ndarray, shape (n, 2)
        The points moved along the line from c where |δα| > 0.2 mm (step 10).
    table7 : :class:`ScaleTable`
    """

    names: tuple
    bases: tuple
    photo_xy_mm: np.ndarray
    l_plan_mm: np.ndarray
    f_mm: float
    alpha_deg: float
    lambda_deg: float
    M: float
    c_mm: np.ndarray
    table5: ScaleTable
    table6: TiltCorrections
    corrected_xy_mm: np.ndarray
    table7: ScaleTable


@V.checked(names=V.names(min_len=2), photo_xy_mm=V.points(2, min_points=2), l_plan_mm=V.array(ndim=1), bases=V.pairs())
def tilt_work(names, photo_xy_mm, l_plan_mm, bases, *, f_mm: float, alpha_deg: float, lambda_deg: float,
              M: float = GUIDE_M_PLAN, threshold_mm: float = THRESHOLD_MM) -> TiltWork:
    """Run the guide's §5 (tables 5 → 6 → 7) on measured photo coordinates and plan lengths.

    Parameters as :func:`relief_work`, with the tilt α and the direction λ of
    the positive principal vertical instead of heights and n.  r_c and φ come
    from :func:`polar_about_isocentre`, δα from :func:`tilt_corrections`, the
    corrections from :func:`apply_radial_corrections` about c.
    """
    names = tuple(str(n) for n in names)
    bases = tuple((str(a), str(b)) for a, b in bases)
    xy = np.asarray(photo_xy_mm, dtype=float).reshape(-1, 2)
    cam = g.Camera(f_mm)
    pose = g.Pose(alpha_deg=alpha_deg, lambda_deg=lambda_deg)
    l_plan = np.asarray(l_plan_mm, dtype=float).ravel()
    t5 = partial_scales(_scale_bases(bases, l_plan, base_lengths_mm(names, xy, bases)), M)
    c = g.isocentre(cam, pose)
    r_c, phi = polar_about_isocentre(cam, pose, xy)
    t6 = tilt_corrections(names, r_c, phi, f_mm=cam.f_mm, alpha_deg=pose.alpha_deg, threshold_mm=threshold_mm)
    corrected = apply_radial_corrections(xy, c, t6.delta_approx_mm, threshold_mm)
    t7 = partial_scales(_scale_bases(bases, l_plan, base_lengths_mm(names, corrected, bases)), M)
    return TiltWork(names, bases, xy, l_plan, cam.f_mm, pose.alpha_deg, pose.lambda_deg, float(M), c, t5, t6,
                    corrected, t7)
