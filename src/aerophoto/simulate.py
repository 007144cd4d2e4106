"""Simulated flights: strips and blocks of photos with seeded imperfections (guide §2–§3).

A *strip* (маршрут) is flown with the parameters of the flight plan (guide §2):

* the camera (:class:`aerophoto.geometry.Camera`: focal length f, frame l = 180 mm);
* the scale denominator m of 1/m, which fixes the flying height H = f·m (metres,
  f in metres) above a reference ground height ``ground_Z_m`` (the mean object
  plane, средняя предметная плоскость);
* the forward overlap p_x in %, which fixes the photo base
  (базис фотографирования) B_x = l·m·(1 − p_x/100) — with l = 0.18 m this is
  the guide's B_x = b_x·m, b_x = l(100 − p_x)/100;
* the number of photos, the ground point under the first photo and the
  direction of flight (azimuth, degrees counter-clockwise from ground +X, the
  same angle as :attr:`aerophoto.geometry.Pose.kappa_deg`).

A *block* (блок) is several parallel strips with side overlap p_y %, spaced
B_y = l·m·(1 − p_y/100) metres apart.

Imperfections
-------------
A real flight departs from the plan; guide §3 sets tolerances for each
departure.  :class:`Imperfections` describes them; every random part is
drawn from ``numpy.random.default_rng([seed, strip])`` and is **bounded** by
its stated maximum (uniform distributions), so a test or a student's check
can rely on the maxima:

=====================  ====================================================  ======================
field                  what it does (per photo)                              guide §3 tolerance
=====================  ====================================================  ======================
``max_tilt_deg``       tilt α uniform in [0, max]; direction λ uniform        α ≤ 3°
                       in [−180°, 180°)
``crab_deg``           constant crab (deviation of the photo's x axis from   5°/7°/10° for
                       the route, κ offset), degrees counter-clockwise        f = 100/140/200 mm
``max_crab_jitter_deg`` extra random crab, uniform in ±max
``max_height_percent`` flying-height deviation ΔH/H uniform in ±max %          ≤ 3 %
``curvature_percent``  route curvature: the photo centres lie on a            n = l/L·100 % ≤ 2 %
                       parabolic arc whose sagitta (largest deviation from     (H > 750 m)
                       the chord between the first and last centres) is
                       this % of the chord length L; positive bends left
``max_base_percent``   along-track jitter of each centre, uniform in ±max %   (scale difference
                       of the base B                                           Δm/m ≤ 2–3 %)
``seed``               the random stream (an int ≥ 0)
=====================  ====================================================  ======================

The random unit draws do not depend on the maxima: with the same seed,
doubling ``max_tilt_deg`` doubles every tilt and changes nothing else.  With
all maxima zero (the default) the strip is ideal: every photo vertical
(α = 0), κ equal to the route azimuth, the centres on a straight line exactly
B_x apart at Z = ground_Z_m + H.

Heading under curvature: the photo's x axis follows the tangent of the arc
(plus the crab), i.e. the aircraft heads along its track.

Public API
----------
``Imperfections(...)``
    frozen dataclass, see the table above.
``fly_strip(camera, m, px_percent, n_photos, *, start_m=(0, 0), azimuth_deg=0,
ground_Z_m=0, imperfections=None, strip=0, first_number=1) -> Strip``
``fly_block(camera, m, px_percent, py_percent, n_photos, n_strips, *, start_m=(0, 0),
azimuth_deg=0, ground_Z_m=0, imperfections=None, side="left", alternate=False,
first_number=1) -> Block``
``strip_over_site(site, camera, m, px_percent, n_photos, *, azimuth_deg=0,
imperfections=None) -> Strip`` and ``block_over_site(...) -> Block``
    centred on the virtual site (:mod:`aerophoto.site`), at its mean height;
    raise ValueError if the photos' footprints do not fit the site.
``variant_strip(variant, n_photos=4, *, site=None, ...) -> Strip`` and
``variant_block(variant, n_photos=4, n_strips=3, *, site=None, ...) -> Block``
    the student's variant (camera f, m, p_x, p_y of :class:`aerophoto.variants.Variant`);
    without a site the reference ground height is the mean of Z_min and Z_max.
``required_site_size(camera, m, px_percent, n_photos, *, n_strips=1, py_percent=30,
imperfections=None, margin_m=None) -> (width_m, height_m)``
    the site size a centred flight along +X needs (whole hundreds of metres).

Each :class:`Shot` knows its true orientation (``pose``) and the planned one
(``nominal``); ``Strip.table()`` / ``Block.table()`` list them as a DataFrame.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from . import _validate as V
from ._validate import check_int_range, check_percent, check_positive, check_range
from .geometry import Camera, Pose, flying_height_m, footprint
from .variants import as_variant

__all__ = [
    "Imperfections",
    "Shot",
    "Strip",
    "Block",
    "photo_base_m",
    "strip_spacing_m",
    "fly_strip",
    "fly_block",
    "strip_over_site",
    "block_over_site",
    "variant_strip",
    "variant_block",
    "required_site_size",
]

MAX_M = 1_000_000.0
MAX_PHOTOS = 1000
MAX_STRIPS = 200


# --------------------------------------------------------------------------- imperfections
@dataclass(frozen=True)
class Imperfections:
    """Seeded departures of a flight from its plan (see the module notes for the table).

    Parameters
    ----------
    max_tilt_deg : float
        Largest tilt α, degrees, 0 ≤ max ≤ 30.  Each photo gets α uniform in
        [0, max] and λ uniform in [−180, 180).
    crab_deg : float
        Constant crab, degrees, −45 ≤ crab ≤ 45: the photo's x axis is turned
        counter-clockwise from the route by this angle (κ = route + crab).
    max_crab_jitter_deg : float
        Random extra crab per photo, uniform in ±max, 0 ≤ max ≤ 20 degrees.
    max_height_percent : float
        Random flying-height deviation per photo, ΔH/H uniform in ±max %,
        0 ≤ max ≤ 50.
    curvature_percent : float
        Sagitta of the route's arc as % of its chord, −50 ≤ c ≤ 50 (guide §3.2:
        straightness n = l/L·100 %).  Positive bends to the left of the
        direction of flight.
    max_base_percent : float
        Along-track jitter of each photo centre, uniform in ±max % of B_x,
        0 ≤ max < 50.
    seed : int
        Seed of the random stream, 0 ≤ seed < 2**63.
    """

    max_tilt_deg: float = 0.0
    crab_deg: float = 0.0
    max_crab_jitter_deg: float = 0.0
    max_height_percent: float = 0.0
    curvature_percent: float = 0.0
    max_base_percent: float = 0.0
    seed: int = 0

    def __post_init__(self):
        s = object.__setattr__
        s(self, "max_tilt_deg", check_range("max_tilt_deg", self.max_tilt_deg, 0.0, 30.0, unit="degrees"))
        s(self, "crab_deg", check_range("crab_deg", self.crab_deg, -45.0, 45.0, unit="degrees"))
        s(self, "max_crab_jitter_deg",
          check_range("max_crab_jitter_deg", self.max_crab_jitter_deg, 0.0, 20.0, unit="degrees"))
        s(self, "max_height_percent", check_range("max_height_percent", self.max_height_percent, 0.0, 50.0, unit="%"))
        s(self, "curvature_percent", check_range("curvature_percent", self.curvature_percent, -50.0, 50.0, unit="%"))
        s(self, "max_base_percent",
          check_range("max_base_percent", self.max_base_percent, 0.0, 50.0, hi_open=True, unit="%"))
        s(self, "seed", check_int_range("seed", self.seed, 0, 2**63 - 1))

    @property
    def is_ideal(self) -> bool:
        """True when every departure is zero (the seed then does not matter)."""
        return (self.max_tilt_deg == 0 and self.crab_deg == 0 and self.max_crab_jitter_deg == 0
                and self.max_height_percent == 0 and self.curvature_percent == 0 and self.max_base_percent == 0)


# --------------------------------------------------------------------------- shots, strips, blocks
@dataclass(frozen=True)
class Shot:
    """One photo of a simulated flight, with its true and its planned orientation.

    Attributes
    ----------
    index : int
        Position in its strip, 0-based, in the order of flight.
    strip : int
        Strip number in the block, 0-based (0 for a single strip).
    number : int
        The photo's number (as printed on the frame), counting on through a block.
    camera : Camera
    pose : Pose
        True exterior orientation: projection centre S (metres) and α, λ, κ (degrees).
    nominal : Pose
        The planned orientation: vertical, on the straight route, exact base and height.
    ground_Z_m : float
        Reference ground height (mean object plane) the flying height refers to, m.
    """

    index: int
    strip: int
    number: int
    camera: Camera
    pose: Pose
    nominal: Pose
    ground_Z_m: float = 0.0

    @property
    def H_m(self) -> float:
        """True flying height over the reference ground height, m."""
        return self.pose.Z_m - self.ground_Z_m

    @property
    def height_error_percent(self) -> float:
        """ΔH/H·100 %: deviation of the true flying height from the planned one (guide §3.4)."""
        Hn = self.nominal.Z_m - self.ground_Z_m
        return (self.pose.Z_m - self.nominal.Z_m) / Hn * 100.0

    @property
    def crab_deg(self) -> float:
        """κ − κ_nominal wrapped to (−180, 180]: the turn of the photo's x axis from the planned route, °."""
        d = (self.pose.kappa_deg - self.nominal.kappa_deg + 180.0) % 360.0 - 180.0
        return 180.0 if d == -180.0 else d

    @property
    def m(self) -> float:
        """True scale denominator of the (levelled) photo over the reference plane, H/f."""
        return self.H_m / (self.camera.f_mm / 1000.0)


def _shot_rows(shots) -> list[dict]:
    rows = []
    for s in shots:
        p, n = s.pose, s.nominal
        rows.append({
            "number": s.number, "strip": s.strip, "index": s.index,
            "X_m": p.X_m, "Y_m": p.Y_m, "Z_m": p.Z_m, "H_m": s.H_m,
            "alpha_deg": p.alpha_deg, "lambda_deg": p.lambda_deg, "kappa_deg": p.kappa_deg,
            "crab_deg": s.crab_deg, "dH_percent": s.height_error_percent,
            "dX_m": p.X_m - n.X_m, "dY_m": p.Y_m - n.Y_m,
            "X_nominal_m": n.X_m, "Y_nominal_m": n.Y_m, "Z_nominal_m": n.Z_m,
        })
    return rows


@dataclass(frozen=True)
class Strip:
    """A simulated strip (маршрут): its shots and the parameters it was flown with.

    Attributes
    ----------
    shots : tuple[Shot, ...]
        In the order of flight.
    camera : Camera
    m : float
        Planned scale denominator (guide §2: 1/m).
    px_percent : float
        Planned forward overlap p_x, %.
    H_m : float
        Planned flying height H = f·m over ``ground_Z_m``, metres.
    B_m : float
        Planned photo base B_x = l·m·(1 − p_x/100), metres.
    azimuth_deg : float
        Direction of flight, degrees counter-clockwise from ground +X.
    start_m : tuple[float, float]
        Planned ground position (X, Y) of the first photo's centre, metres.
    ground_Z_m : float
        Reference ground height, metres.
    imperfections : Imperfections
    """

    shots: tuple
    camera: Camera
    m: float
    px_percent: float
    H_m: float
    B_m: float
    azimuth_deg: float
    start_m: tuple
    ground_Z_m: float
    imperfections: Imperfections = field(default_factory=Imperfections)

    def __len__(self) -> int:
        return len(self.shots)

    def __iter__(self):
        return iter(self.shots)

    def __getitem__(self, i):
        return self.shots[i]

    @property
    def n_photos(self) -> int:
        return len(self.shots)

    @property
    def poses(self) -> list:
        """True poses, in the order of flight."""
        return [s.pose for s in self.shots]

    @property
    def centres_m(self) -> np.ndarray:
        """True projection centres, shape (n, 3), metres."""
        return np.array([s.pose.centre for s in self.shots]).reshape(-1, 3)

    @property
    def nominal_centres_m(self) -> np.ndarray:
        """Planned projection centres, shape (n, 3), metres."""
        return np.array([s.nominal.centre for s in self.shots]).reshape(-1, 3)

    @property
    def direction(self) -> np.ndarray:
        """Unit vector of the direction of flight on the ground, shape (2,)."""
        a = math.radians(self.azimuth_deg)
        return np.array([math.cos(a), math.sin(a)])

    @property
    def length_m(self) -> float:
        """Planned distance between the first and the last centre, (n − 1)·B_x, metres."""
        return (self.n_photos - 1) * self.B_m

    def footprints(self, Z_m: float | None = None) -> np.ndarray:
        """Ground footprints of the true photos on the plane Z (default the reference), shape (n, 4, 3)."""
        z = self.ground_Z_m if Z_m is None else float(Z_m)
        return np.array([footprint(s.camera, s.pose, z) for s in self.shots])

    def table(self) -> pd.DataFrame:
        """One row per photo: true centre, H, α, λ, κ, crab, ΔH % and offsets from the plan."""
        return pd.DataFrame(_shot_rows(self.shots)).set_index("number")


@dataclass(frozen=True)
class Block:
    """A block (блок) of parallel strips with side overlap p_y.

    Attributes
    ----------
    strips : tuple[Strip, ...]
    py_percent : float
        Planned side overlap p_y, %.
    By_m : float
        Planned distance between the strips' axes B_y = l·m·(1 − p_y/100), metres.
    """

    strips: tuple
    py_percent: float
    By_m: float

    def __len__(self) -> int:
        return len(self.strips)

    def __iter__(self):
        return iter(self.strips)

    def __getitem__(self, i):
        return self.strips[i]

    @property
    def shots(self) -> list:
        """All shots, strip after strip."""
        return [s for st in self.strips for s in st.shots]

    @property
    def camera(self) -> Camera:
        return self.strips[0].camera

    @property
    def m(self) -> float:
        return self.strips[0].m

    @property
    def H_m(self) -> float:
        return self.strips[0].H_m

    @property
    def B_m(self) -> float:
        return self.strips[0].B_m

    @property
    def ground_Z_m(self) -> float:
        return self.strips[0].ground_Z_m

    @property
    def imperfections(self) -> Imperfections:
        return self.strips[0].imperfections

    @property
    def centres_m(self) -> np.ndarray:
        """True projection centres of all shots, shape (N, 3), metres."""
        return np.array([s.pose.centre for s in self.shots]).reshape(-1, 3)

    def footprints(self, Z_m: float | None = None) -> np.ndarray:
        """Ground footprints of all photos, shape (N, 4, 3), metres."""
        return np.concatenate([st.footprints(Z_m) for st in self.strips])

    def table(self) -> pd.DataFrame:
        return pd.DataFrame(_shot_rows(self.shots)).set_index("number")


# --------------------------------------------------------------------------- flying
@V.checked(camera=Camera)
def photo_base_m(camera: Camera, m: float, px_percent: float) -> float:
    """Photo base B_x = l·m·(1 − p_x/100) in metres (guide §2, steps 4–5; l = frame)."""
    m = check_positive("m", m, hi=MAX_M)
    px = check_percent("px_percent", px_percent)
    return camera.frame_mm / 1000.0 * m * (1.0 - px / 100.0)


@V.checked(camera=Camera)
def strip_spacing_m(camera: Camera, m: float, py_percent: float) -> float:
    """Distance between strips B_y = l·m·(1 − p_y/100) in metres (guide §2, steps 4–5)."""
    m = check_positive("m", m, hi=MAX_M)
    py = check_percent("py_percent", py_percent)
    return camera.frame_mm / 1000.0 * m * (1.0 - py / 100.0)


def _check_xy(name, xy):
    try:
        a = np.asarray(xy, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {xy!r} must be a pair (X, Y) of numbers in metres") from None
    if a.shape != (2,):
        raise ValueError(f"{name} = {xy!r} must be a pair (X, Y) of numbers in metres")
    return (check_range(f"{name}[0]", a[0], -1e8, 1e8, unit="m"), check_range(f"{name}[1]", a[1], -1e8, 1e8, unit="m"))


@V.checked(camera=Camera)
def fly_strip(
    camera: Camera,
    m: float,
    px_percent: float,
    n_photos: int,
    *,
    start_m=(0.0, 0.0),
    azimuth_deg: float = 0.0,
    ground_Z_m: float = 0.0,
    imperfections: Imperfections | None = None,
    strip: int = 0,
    first_number: int = 1,
) -> Strip:
    """Fly one strip (guide §2 parameters) with seeded imperfections.

    Parameters
    ----------
    camera : Camera
        f and the frame l (mm).
    m : float
        Scale denominator of 1/m, 0 < m ≤ 10⁶.  Flying height H = f·m.
    px_percent : float
        Forward overlap p_x, 0 ≤ p_x < 100 %.
    n_photos : int
        Number of photos, 1 ≤ n ≤ 1000.
    start_m : (X, Y)
        Planned ground position of the first photo's centre, metres.
    azimuth_deg : float
        Direction of flight, degrees counter-clockwise from +X, −360 ≤ az ≤ 360.
    ground_Z_m : float
        Reference ground height the flying height refers to, metres.
    imperfections : Imperfections or None
        None = an ideal strip.
    strip : int
        Index of the strip in a block (also selects the random stream
        ``default_rng([seed, strip])``), 0 ≤ strip ≤ 200.
    first_number : int
        Number of the first photo, 0 ≤ first_number ≤ 10⁶.

    Returns
    -------
    Strip
    """
    if not isinstance(camera, Camera):
        raise ValueError(f"camera = {camera!r} must be an aerophoto.geometry.Camera")
    m = check_positive("m", m, hi=MAX_M)
    px = check_percent("px_percent", px_percent)
    n = check_int_range("n_photos", n_photos, 1, MAX_PHOTOS)
    sx, sy = _check_xy("start_m", start_m)
    az = check_range("azimuth_deg", azimuth_deg, -360.0, 360.0, unit="degrees")
    z0 = check_range("ground_Z_m", ground_Z_m, -1e4, 1e5, unit="m")
    k = check_int_range("strip", strip, 0, MAX_STRIPS)
    first = check_int_range("first_number", first_number, 0, 10**6)
    imp = Imperfections() if imperfections is None else imperfections
    if not isinstance(imp, Imperfections):
        raise ValueError(f"imperfections = {imperfections!r} must be an Imperfections or None")

    H = flying_height_m(camera.f_mm, m)
    B = photo_base_m(camera, m, px)
    a = math.radians(az)
    d = np.array([math.cos(a), math.sin(a)])  # along the route
    left = np.array([-d[1], d[0]])  # 90° counter-clockwise: to the left
    start = np.array([sx, sy])

    # unit draws first, in a fixed order, independent of the maxima
    rng = np.random.default_rng([imp.seed, k])
    u_tilt = rng.random(n)
    u_dir = rng.random(n)
    u_crab = rng.uniform(-1.0, 1.0, n)
    u_height = rng.uniform(-1.0, 1.0, n)
    u_base = rng.uniform(-1.0, 1.0, n)

    alpha = imp.max_tilt_deg * u_tilt
    lam = -180.0 + 360.0 * u_dir
    crab = imp.crab_deg + imp.max_crab_jitter_deg * u_crab
    dH = imp.max_height_percent / 100.0 * u_height
    s_nom = np.arange(n) * B
    s = s_nom + imp.max_base_percent / 100.0 * B * u_base
    L = (n - 1) * B
    c = imp.curvature_percent / 100.0
    if L > 0:
        lateral = 4.0 * c * s * (L - s) / L  # parabola through the ends, sagitta c·L
        slope = 4.0 * c * (L - 2.0 * s) / L
    else:
        lateral = np.zeros(n)
        slope = np.zeros(n)
    heading = az + np.degrees(np.arctan(slope))

    shots = []
    for i in range(n):
        xy_nom = start + s_nom[i] * d
        xy = start + s[i] * d + lateral[i] * left
        nominal = Pose(float(xy_nom[0]), float(xy_nom[1]), z0 + H, 0.0, 0.0, az)
        if imp.is_ideal:
            pose = nominal
        else:
            pose = Pose(float(xy[0]), float(xy[1]), z0 + H * (1.0 + dH[i]),
                        float(alpha[i]), float(lam[i]), float(heading[i] + crab[i]))
        shots.append(Shot(index=i, strip=k, number=first + i, camera=camera, pose=pose,
                          nominal=nominal, ground_Z_m=z0))
    return Strip(shots=tuple(shots), camera=camera, m=m, px_percent=px, H_m=H, B_m=B,
                 azimuth_deg=az, start_m=(sx, sy), ground_Z_m=z0, imperfections=imp)


@V.checked(camera=Camera)
def fly_block(
    camera: Camera,
    m: float,
    px_percent: float,
    py_percent: float,
    n_photos: int,
    n_strips: int,
    *,
    start_m=(0.0, 0.0),
    azimuth_deg: float = 0.0,
    ground_Z_m: float = 0.0,
    imperfections: Imperfections | None = None,
    side: str = "left",
    alternate: bool = False,
    first_number: int = 1,
) -> Block:
    """Fly a block of parallel strips with side overlap p_y.

    Strip k (0-based) is the strip of :func:`fly_strip` shifted k·B_y to the
    ``side`` ("left" or "right" of the direction of flight) and flown with
    its own random stream ``default_rng([seed, k])`` — so strip 0 of a block
    equals the single strip flown with the same arguments.  With
    ``alternate=True`` the odd strips are flown back (azimuth + 180°) from
    the far end, so the photo centres of all strips still line up across the
    block.  Photo numbers count on from strip to strip.

    Parameters as in :func:`fly_strip`, plus ``py_percent`` (0 ≤ p_y < 100 %)
    and ``n_strips`` (1 ≤ K ≤ 200).
    """
    py = check_percent("py_percent", py_percent)
    K = check_int_range("n_strips", n_strips, 1, MAX_STRIPS)
    if side not in ("left", "right"):
        raise ValueError(f"side = {side!r} is not valid; expected 'left' or 'right'")
    n = check_int_range("n_photos", n_photos, 1, MAX_PHOTOS)
    sx, sy = _check_xy("start_m", start_m)
    az = check_range("azimuth_deg", azimuth_deg, -360.0, 360.0, unit="degrees")
    first = check_int_range("first_number", first_number, 0, 10**6)
    By = strip_spacing_m(camera, m, py)
    B = photo_base_m(camera, m, px_percent)
    a = math.radians(az)
    d = np.array([math.cos(a), math.sin(a)])
    off = np.array([-d[1], d[0]]) * (1.0 if side == "left" else -1.0)
    strips = []
    number = first
    for k in range(K):
        start = np.array([sx, sy]) + k * By * off
        azk = az
        if alternate and k % 2 == 1:
            start = start + (n - 1) * B * d
            azk = az + 180.0 if az + 180.0 <= 360.0 else az - 180.0
        st = fly_strip(camera, m, px_percent, n, start_m=tuple(start), azimuth_deg=azk, ground_Z_m=ground_Z_m,
                       imperfections=imperfections, strip=k, first_number=number)
        strips.append(st)
        number += n
    return Block(strips=tuple(strips), py_percent=py, By_m=By)


# --------------------------------------------------------------------------- over the virtual site
@V.checked(camera=Camera)
def required_site_size(
    camera: Camera,
    m: float,
    px_percent: float,
    n_photos: int,
    *,
    n_strips: int = 1,
    py_percent: float = 30.0,
    imperfections: Imperfections | None = None,
    margin_m: float | None = None,
) -> tuple[float, float]:
    """Width (along +X, the route) and height (along Y) of a site that holds a centred flight.

    The flight is assumed along +X and centred on the site.  The size covers
    the planned photo footprints (side l·m), the route curvature, the base
    jitter, tilts (a footprint grows by about H·tan α per side) and height
    deviations, plus ``margin_m`` on every side (default: a fifth of the
    photo side).  Both sizes are rounded up to whole hundreds of metres so
    that the site cache (:func:`aerophoto.site.get_site`) is reused.

    Returns
    -------
    (width_m, height_m) : tuple of float
    """
    imp = Imperfections() if imperfections is None else imperfections
    m = check_positive("m", m, hi=MAX_M)
    n = check_int_range("n_photos", n_photos, 1, MAX_PHOTOS)
    K = check_int_range("n_strips", n_strips, 1, MAX_STRIPS)
    side = camera.frame_mm / 1000.0 * m
    H = flying_height_m(camera.f_mm, m)
    B = photo_base_m(camera, m, px_percent)
    By = strip_spacing_m(camera, m, py_percent)
    margin = side / 5.0 if margin_m is None else check_range("margin_m", margin_m, 0.0, 1e6, unit="m")
    # half-extents (along and across the route) of the worst footprint: highest, most tilted, most crabbed
    Hmax = H * (1.0 + imp.max_height_percent / 100.0)
    crab = abs(imp.crab_deg) + imp.max_crab_jitter_deg
    hx = hy = 0.0
    for lam in np.arange(0.0, 360.0, 15.0):
        for kap in (-crab, crab):
            fp = footprint(camera, Pose(0.0, 0.0, Hmax, imp.max_tilt_deg, float(lam), kap), 0.0)
            hx = max(hx, float(np.abs(fp[:, 0]).max()))
            hy = max(hy, float(np.abs(fp[:, 1]).max()))
    L = (n - 1) * B * (1.0 + imp.max_base_percent / 100.0)
    width = L + 2.0 * hx + 2.0 * margin
    lateral = abs(imp.curvature_percent) / 100.0 * (n - 1) * B
    height = (K - 1) * By + 2.0 * hy + lateral + 2.0 * margin
    return (math.ceil(width / 100.0) * 100.0, math.ceil(height / 100.0) * 100.0)


def _centred_start(site, n, B, K, By, az_deg, side="left"):
    cx, cy = site.centre_m
    a = math.radians(az_deg)
    d = np.array([math.cos(a), math.sin(a)])
    off = np.array([-d[1], d[0]]) * (1.0 if side == "left" else -1.0)
    return tuple(np.array([cx, cy]) - (n - 1) * B / 2.0 * d - (K - 1) * By / 2.0 * off)


def _check_fits(site, flight):
    x0, x1, y0, y1 = site.extent_m
    fp = flight.footprints(site.mean_height_m)
    fx0, fx1 = float(fp[..., 0].min()), float(fp[..., 0].max())
    fy0, fy1 = float(fp[..., 1].min()), float(fp[..., 1].max())
    if fx0 < x0 or fx1 > x1 or fy0 < y0 or fy1 > y1:
        raise ValueError(
            f"the flight's footprints (X {fx0:.0f}…{fx1:.0f} m, Y {fy0:.0f}…{fy1:.0f} m) do not fit the site "
            f"(X {x0:.0f}…{x1:.0f} m, Y {y0:.0f}…{y1:.0f} m); the valid range is inside the site: build a larger "
            "site (aerophoto.site.get_site(width_m=..., height_m=...), see required_site_size) or fly fewer photos "
            "(n_photos, n_strips), at a smaller scale denominator m or with more overlap (px_percent, py_percent)"
        )


@V.checked(site=V.has_attrs("height", "centre_m", what="a Site (aerophoto.site.get_site())"), camera=Camera,
           azimuth_deg=V.number(-1e4, 1e4))
def strip_over_site(
    site,
    camera: Camera,
    m: float,
    px_percent: float,
    n_photos: int,
    *,
    azimuth_deg: float = 0.0,
    imperfections: Imperfections | None = None,
    first_number: int = 1,
) -> Strip:
    """A strip centred on the virtual site, H = f·m above the site's mean height.

    ``site`` is an :class:`aerophoto.site.Site` (anything with ``centre_m``,
    ``extent_m`` and ``mean_height_m``).  Raises ValueError if the true
    photos' footprints (on the plane of the mean height) leave the site.
    """
    n = check_int_range("n_photos", n_photos, 1, MAX_PHOTOS)
    B = photo_base_m(camera, m, px_percent)
    start = _centred_start(site, n, B, 1, 0.0, azimuth_deg)
    st = fly_strip(camera, m, px_percent, n, start_m=start, azimuth_deg=azimuth_deg,
                   ground_Z_m=site.mean_height_m, imperfections=imperfections, first_number=first_number)
    _check_fits(site, st)
    return st


@V.checked(site=V.has_attrs("height", "centre_m", what="a Site (aerophoto.site.get_site())"), camera=Camera,
           azimuth_deg=V.number(-1e4, 1e4))
def block_over_site(
    site,
    camera: Camera,
    m: float,
    px_percent: float,
    py_percent: float,
    n_photos: int,
    n_strips: int,
    *,
    azimuth_deg: float = 0.0,
    imperfections: Imperfections | None = None,
    side: str = "left",
    alternate: bool = False,
    first_number: int = 1,
) -> Block:
    """A block centred on the virtual site, H = f·m above its mean height (see :func:`strip_over_site`).

    If imperfections push the flown footprints over an edge, the block is flown again with its footprints
    centred on the site; ValueError only if they do not fit even then.
    """
    n = check_int_range("n_photos", n_photos, 1, MAX_PHOTOS)
    K = check_int_range("n_strips", n_strips, 1, MAX_STRIPS)
    B = photo_base_m(camera, m, px_percent)
    By = strip_spacing_m(camera, m, py_percent)
    if side not in ("left", "right"):
        raise ValueError(f"side = {side!r} is not valid; expected 'left' or 'right'")
    start = np.asarray(_centred_start(site, n, B, K, By, azimuth_deg, side), float)

    def fly(at):
        return fly_block(camera, m, px_percent, py_percent, n, K, start_m=tuple(at), azimuth_deg=azimuth_deg,
                         ground_Z_m=site.mean_height_m, imperfections=imperfections, side=side,
                         alternate=alternate, first_number=first_number)

    bl = fly(start)
    try:
        _check_fits(site, bl)
    except ValueError:
        # a large block whose imperfections (bend, tilt, crab) push its footprints off-centre: fly it again with
        # its footprints centred on the site (on the mean-height plane they move with the start, exactly); if it
        # still does not fit, it is too large for the site and the error stands
        fp = bl.footprints(site.mean_height_m)
        mid = np.array([fp[..., 0].min() + fp[..., 0].max(), fp[..., 1].min() + fp[..., 1].max()]) / 2.0
        bl = fly(start + np.asarray(site.centre_m, float) - mid)
        _check_fits(site, bl)
    return bl


def variant_strip(variant, n_photos: int = 4, *, site=None, imperfections: Imperfections | None = None,
                  px_percent: float | None = None, azimuth_deg: float = 0.0, first_number: int = 1) -> Strip:
    """A strip flown with a student's variant (guide §1): camera f, 1/m and p_x.

    Without ``site`` the strip starts at (0, 0) and H refers to the mean of the
    variant's Z_min and Z_max; with a site it is centred on it
    (:func:`strip_over_site`).  ``px_percent`` overrides the variant's p_x
    (e.g. with the relief-corrected P_x of guide §2, step 3).
    """
    variant = as_variant(variant, "variant", none=False)
    px = variant.px_percent if px_percent is None else px_percent
    if site is not None:
        return strip_over_site(site, variant.camera, variant.m, px, n_photos, azimuth_deg=azimuth_deg,
                               imperfections=imperfections, first_number=first_number)
    z0 = (variant.Zmin_m + variant.Zmax_m) / 2.0
    return fly_strip(variant.camera, variant.m, px, n_photos, azimuth_deg=azimuth_deg, ground_Z_m=z0,
                     imperfections=imperfections, first_number=first_number)


def variant_block(variant, n_photos: int = 4, n_strips: int = 3, *, site=None,
                  imperfections: Imperfections | None = None, px_percent: float | None = None,
                  py_percent: float | None = None, azimuth_deg: float = 0.0, side: str = "left",
                  alternate: bool = False, first_number: int = 1) -> Block:
    """A block flown with a student's variant (f, 1/m, p_x, p_y); see :func:`variant_strip`."""
    variant = as_variant(variant, "variant", none=False)
    px = variant.px_percent if px_percent is None else px_percent
    py = variant.py_percent if py_percent is None else py_percent
    if site is not None:
        return block_over_site(site, variant.camera, variant.m, px, py, n_photos, n_strips, azimuth_deg=azimuth_deg,
                               imperfections=imperfections, side=side, alternate=alternate,
                               first_number=first_number)
    z0 = (variant.Zmin_m + variant.Zmax_m) / 2.0
    return fly_block(variant.camera, variant.m, px, py, n_photos, n_strips, azimuth_deg=azimuth_deg,
                     ground_Z_m=z0, imperfections=imperfections, side=side, alternate=alternate,
                     first_number=first_number)
