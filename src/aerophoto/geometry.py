"""The frame camera and central projection (guide §4–§5, figure 8).

Everything else in aerophoto builds on this module. It is pure numpy.

Coordinate systems and sign conventions
---------------------------------------
Ground (object space)
    X east, Y north, Z up, all in metres.

Photo (image space, the positive photo, in front of the lens)
    x, y in millimetres, origin at the principal point o, +x along the photo's
    x fiducial axis, +y 90° counter-clockwise from +x (looking down at the
    positive print).  The image vector of a photo point in the camera frame is
    (x, y, −f): the camera's third axis points from the photo back up through
    the projection centre S.

Exterior orientation (:class:`Pose`)
    The projection centre S = (X_m, Y_m, Z_m) and three angles:

    * ``alpha_deg`` — the tilt α (угол наклона), the angle between the optical
      axis So and the plumb line SN (guide §5).
    * ``lambda_deg`` — the direction of the principal vertical vv (главная
      вертикаль) on the photo: the angle, counter-clockwise from the photo's
      +x axis, of the **positive** direction of the principal vertical.  The
      guide's variant calls it λ = −60° + i ("rotation of the photo in its own
      plane", §1) and finds the principal vertical "by the angle χ" (§5).
    * ``kappa_deg`` — the heading κ: the azimuth, counter-clockwise from ground
      +X, of the photo's +x axis once the photo is levelled.  A strip flown
      along +X has κ = 0.

The guide's sign convention (§5), used everywhere in aerophoto
    The positive direction of the principal vertical points from o **away from
    the nadir**, towards the far (upper) side of the tilted photo.  Measured
    along it, the nadir point n lies at −f·tan α and the isocentre c
    (точка нулевых искажений) at −f·tan(α/2):

        on = f·tan α,  oc = −f·tg(α/2) = −2.6 mm for f = 100 mm, α = 3°

    The angle φ of a point is measured counter-clockwise from that positive
    direction, as seen from c.  Points with cos φ > 0 lie on the far side and
    are pulled towards c (tilt displacement δα < 0); points with cos φ < 0 lie
    on the near (nadir) side and are pushed away from c (δα > 0).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from functools import lru_cache
from typing import Callable, Protocol, runtime_checkable

import numpy as np

from ._validate import check_finite_array, check_int_range, check_positive, check_range, check_type, check_values

__all__ = [
    "Camera",
    "Pose",
    "FlatTerrain",
    "rotation_matrix",
    "principal_vertical",
    "principal_point",
    "nadir_point",
    "isocentre",
    "ground_to_photo",
    "photo_to_plane",
    "photo_to_dem",
    "transfer_points",
    "photo_axis_towards",
    "footprint",
    "tilt_displacement_exact",
    "tilt_displacement_vectors",
    "tilt_displacement_approx",
    "relief_displacement",
    "photo_scale_denominator",
    "Terrain",
    "as_terrain",
    "flying_height_m",
]

MAX_F_MM = 2000.0
MAX_FRAME_MM = 500.0


# --------------------------------------------------------------------------- camera
@dataclass(frozen=True)
class Camera:
    """A metric frame camera (аэрофотоаппарат, АФА).

    Parameters
    ----------
    f_mm : float
        Focal length (principal distance) f in mm, 0 < f ≤ 2000 (guide §1:
        f = 100 + 10i mm).
    frame_mm : float
        Side of the square frame in mm, 0 < frame ≤ 500 (guide §1: 18×18 cm,
        i.e. 180 mm).
    """

    f_mm: float = 100.0
    frame_mm: float = 180.0

    def __post_init__(self):
        object.__setattr__(self, "f_mm", check_positive("f_mm", self.f_mm, unit="mm", hi=MAX_F_MM))
        object.__setattr__(self, "frame_mm", check_positive("frame_mm", self.frame_mm, unit="mm", hi=MAX_FRAME_MM))

    @property
    def half_mm(self) -> float:
        """Half the frame side, mm (the photo spans −half…+half in x and y)."""
        return self.frame_mm / 2.0

    def corners_mm(self) -> np.ndarray:
        """The frame corners, shape (4, 2), counter-clockwise from (−half, −half), mm."""
        h = self.half_mm
        return np.array([[-h, -h], [h, -h], [h, h], [-h, h]], dtype=float)

    def inside(self, xy_mm) -> np.ndarray:
        """Boolean mask, shape (...,): which photo points fall inside the frame."""
        xy = np.asarray(xy_mm, dtype=float)
        return np.all(np.abs(xy) <= self.half_mm, axis=-1)

    @property
    def field_angle_deg(self) -> float:
        """Angle of field 2β across the diagonal, degrees (guide §3)."""
        return 2.0 * math.degrees(math.atan(self.half_mm * math.sqrt(2.0) / self.f_mm))


# --------------------------------------------------------------------------- pose
@dataclass(frozen=True)
class Pose:
    """Exterior orientation of one photo: projection centre S and the angles.

    Parameters
    ----------
    X_m, Y_m, Z_m : float
        Projection centre S in ground coordinates, metres.  ``Z_m`` is the
        absolute height of S; the flying height H over a ground plane at
        height Z0 is ``Z_m − Z0``.
    alpha_deg : float
        Tilt α in degrees, |α| < 90.  A negative α is the same photo as
        (|α|, λ + 180°).
    lambda_deg : float
        Direction λ of the positive principal vertical on the photo, degrees
        counter-clockwise from the photo's +x axis (see the module notes).
    kappa_deg : float
        Heading κ of the levelled photo's +x axis, degrees counter-clockwise
        from ground +X.
    """

    X_m: float = 0.0
    Y_m: float = 0.0
    Z_m: float = 1000.0
    alpha_deg: float = 0.0
    lambda_deg: float = 0.0
    kappa_deg: float = 0.0

    def __post_init__(self):
        for name in ("X_m", "Y_m", "Z_m", "lambda_deg", "kappa_deg"):  # noqa: B007
            v = check_range(name, getattr(self, name), -1e9, 1e9)
            object.__setattr__(self, name, v)
        a = check_range("alpha_deg", self.alpha_deg, -90.0, 90.0, lo_open=True, hi_open=True, unit="degrees")
        object.__setattr__(self, "alpha_deg", a)

    @classmethod
    def vertical(cls, X_m: float, Y_m: float, H_m: float, *, ground_Z_m: float = 0.0, kappa_deg: float = 0.0) -> "Pose":
        """A vertical photo (α = 0) taken from flying height H above a plane at ``ground_Z_m``."""
        check_positive("H_m", H_m, unit="m")
        return cls(X_m, Y_m, ground_Z_m + H_m, 0.0, 0.0, kappa_deg)

    @property
    def centre(self) -> np.ndarray:
        """Projection centre S, shape (3,), metres."""
        return np.array([self.X_m, self.Y_m, self.Z_m], dtype=float)

    def levelled(self) -> "Pose":
        """The equivalent vertical photo: same S, λ and κ, with α = 0."""
        return replace(self, alpha_deg=0.0)

    def with_(self, **changes) -> "Pose":
        """A copy with some fields changed (validated again)."""
        return replace(self, **changes)

    def flying_height(self, ground_Z_m: float = 0.0) -> float:
        """H = Z_S − Z_ground in metres; raises if S is not above the ground."""
        H = self.Z_m - check_range("ground_Z_m", ground_Z_m, unit="m")
        if H <= 0:
            raise ValueError(
                f"Z_m = {self.Z_m:g} is at or below the terrain (ground_Z_m = {float(ground_Z_m):g}); "
                f"the valid range is Z_m > {float(ground_Z_m):g} m"
            )
        return H


# --------------------------------------------------------------------------- terrain
@runtime_checkable
class Terrain(Protocol):
    """What every terrain offers: heights and their bounds (the one terrain interface).

    ``height(X, Y)`` is vectorised over matching arrays of ground coordinates
    (metres) and returns Z in metres; ``z_min_m`` ≤ Z ≤ ``z_max_m`` over the
    whole terrain.  :class:`FlatTerrain`, the virtual site
    (:class:`aerophoto.site.Site`) and the demo terrains of
    :mod:`aerophoto.terrain` implement it; :func:`photo_to_dem` needs nothing else.
    """

    @property
    def z_min_m(self) -> float: ...

    @property
    def z_max_m(self) -> float: ...

    def height(self, X, Y) -> np.ndarray: ...


@dataclass(frozen=True)
class FlatTerrain:
    """Horizontal ground at height ``z_m`` (a DEM with no relief)."""

    z_m: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "z_m", check_range("z_m", self.z_m, -1e5, 1e5, unit="m"))

    @property
    def z_min_m(self) -> float:
        return self.z_m

    @property
    def z_max_m(self) -> float:
        return self.z_m

    def height(self, X, Y) -> np.ndarray:
        return np.full(np.broadcast(np.asarray(X), np.asarray(Y)).shape, self.z_m, dtype=float)

    __call__ = height


def as_terrain(terrain=None, ground_Z_m: float = 0.0) -> Terrain:
    """The one converter to a :class:`Terrain`.

    Parameters
    ----------
    terrain : None, a number, or a Terrain
        None → flat ground at ``ground_Z_m``; a number → flat ground at that
        height (m); an object with ``height(X, Y)``, ``z_min_m`` and
        ``z_max_m`` → itself.
    ground_Z_m : float
        Height of the flat ground used when ``terrain`` is None, m.
    """
    if terrain is None:
        return FlatTerrain(check_range("ground_Z_m", ground_Z_m, -1e5, 1e5, unit="m"))
    if isinstance(terrain, (int, float, np.integer, np.floating)) and not isinstance(terrain, bool):
        return FlatTerrain(check_range("terrain", terrain, -1e5, 1e5, unit="m"))
    if isinstance(terrain, Terrain):
        return terrain
    raise ValueError(
        f"terrain = {terrain!r:.60} is not a terrain; expected None, a height in metres, or an object with "
        "height(X, Y), z_min_m and z_max_m"
    )


def flying_height_m(f_mm: float, m: float) -> float:
    """Flying height H = f·m in metres (guide §2, step 2), with f in mm and the photo scale 1:m."""
    return check_positive("f_mm", f_mm, unit="mm", hi=MAX_F_MM) / 1000.0 * check_positive("m", m, hi=1e7)


_NO_CAMERA = object()


def _cp(camera, pose, pose_name: str = "pose"):
    """Check the camera and pose arguments by type (TypeError naming the parameter)."""
    if camera is not _NO_CAMERA:
        check_type("camera", camera, Camera)
    check_type(pose_name, pose, Pose)


# --------------------------------------------------------------------------- rotation
def _dir(az_rad: float) -> np.ndarray:
    return np.array([math.cos(az_rad), math.sin(az_rad), 0.0])


def rotation_matrix(pose: Pose) -> np.ndarray:
    """Rotation R, shape (3, 3), taking camera-frame vectors to ground-frame vectors.

    Ground vector = R @ camera vector; a photo point (x, y) has the camera
    vector (x, y, −f).  Built so that the plumb line seen from S pierces the
    photo at the nadir n = −f·tan α along the positive principal vertical, and
    that for α = 0 the photo's +x axis points at azimuth κ on the ground.
    """
    _cp(_NO_CAMERA, pose)
    return _rotation(pose.alpha_deg, pose.lambda_deg, pose.kappa_deg)


@lru_cache(maxsize=256)
def _rotation(alpha_deg: float, lambda_deg: float, kappa_deg: float) -> np.ndarray:
    """:func:`rotation_matrix` of the three angles, read-only and remembered (a demo's move asks for the same few
    photos' R thousands of times: 35 µs each to build)."""
    a = math.radians(alpha_deg)
    lam = math.radians(lambda_deg)
    kap = math.radians(kappa_deg)
    u = np.array([math.cos(lam), math.sin(lam), 0.0])  # + principal vertical (camera frame)
    v = np.array([-math.sin(lam), math.cos(lam), 0.0])  # along the horizontals h-h
    w = np.array([0.0, 0.0, 1.0])
    zc = math.sin(a) * u + math.cos(a) * w  # ground "up" seen in the camera frame
    e1 = math.cos(a) * u - math.sin(a) * w  # horizontal direction of the principal plane
    L = np.column_stack([e1, v, zc])  # level frame, columns in camera coordinates
    G = np.column_stack([_dir(kap + lam), _dir(kap + lam + math.pi / 2), w])
    R = G @ L.T
    R.setflags(write=False)
    return R


def principal_vertical(pose: Pose) -> np.ndarray:
    """Unit vector, shape (2,), of the positive principal vertical on the photo (away from n)."""
    _cp(_NO_CAMERA, pose)
    lam = math.radians(pose.lambda_deg)
    return np.array([math.cos(lam), math.sin(lam)])


def principal_point(camera: Camera, pose: Pose) -> np.ndarray:
    """Principal point o, shape (2,), mm: the origin of photo coordinates."""
    _cp(camera, pose)
    return np.zeros(2)


def nadir_point(camera: Camera, pose: Pose) -> np.ndarray:
    """Nadir point n (точка надира), shape (2,), mm: at −f·tan α on the principal vertical."""
    _cp(camera, pose)
    return -camera.f_mm * math.tan(math.radians(pose.alpha_deg)) * principal_vertical(pose)


def isocentre(camera: Camera, pose: Pose) -> np.ndarray:
    """Isocentre c (точка нулевых искажений), shape (2,), mm: at oc = −f·tg(α/2) (guide §5)."""
    _cp(camera, pose)
    return -camera.f_mm * math.tan(math.radians(pose.alpha_deg) / 2.0) * principal_vertical(pose)


# --------------------------------------------------------------------------- projection
def ground_to_photo(camera: Camera, pose: Pose, XYZ_m) -> np.ndarray:
    """Exact central projection (collinearity) of ground points onto the photo.

    Parameters
    ----------
    XYZ_m : array_like, shape (..., 3)
        Ground points X, Y, Z in metres.

    Returns
    -------
    ndarray, shape (..., 2)
        Photo coordinates x, y in mm (they may fall outside the frame).

    Raises
    ------
    ValueError
        If a point lies at or above the plane through S parallel to the photo
        (it has no image on the positive photo).
    """
    _cp(camera, pose)
    P = check_finite_array("XYZ_m", XYZ_m, last=3)
    R = rotation_matrix(pose)
    d = P - pose.centre
    c = d @ R  # = (R.T @ d.T).T, camera-frame components
    cz = c[..., 2]
    if np.any(cz >= 0):
        n_bad = int(np.count_nonzero(cz >= 0))
        raise ValueError(
            f"{n_bad} ground point(s) lie behind the camera (not below the plane of S); "
            f"a ground point must be below S: Z < Z_m = {pose.Z_m:g} m along the view direction"
        )
    scale = -camera.f_mm / cz
    return np.stack([c[..., 0] * scale, c[..., 1] * scale], axis=-1)


def _rays(camera: Camera, pose: Pose, xy_mm) -> np.ndarray:
    xy = check_finite_array("xy_mm", xy_mm, last=2)
    cam = np.concatenate([xy, np.full(xy.shape[:-1] + (1,), -camera.f_mm)], axis=-1)
    return cam @ rotation_matrix(pose).T  # ground directions, shape (..., 3)


def photo_to_plane(camera: Camera, pose: Pose, xy_mm, Z_m: float = 0.0) -> np.ndarray:
    """Intersect the rays of photo points with the horizontal plane Z = ``Z_m``.

    Parameters
    ----------
    xy_mm : array_like, shape (..., 2)
        Photo coordinates in mm.
    Z_m : float
        Height of the plane in metres; it must lie below S.

    Returns
    -------
    ndarray, shape (..., 3)
        Ground points X, Y, Z in metres.
    """
    _cp(camera, pose)
    Zp = check_range("Z_m", Z_m, unit="m")
    pose.flying_height(Zp)  # raises if S is not above the plane
    g = _rays(camera, pose, xy_mm)
    gz = g[..., 2]
    if np.any(gz >= 0):
        raise ValueError(
            f"a photo ray points at or above the horizon (alpha_deg = {pose.alpha_deg:g}); "
            "it never meets the ground plane — use a smaller tilt or points nearer o"
        )
    t = (Zp - pose.Z_m) / gz
    return pose.centre + t[..., None] * g


def photo_to_dem(
    camera: Camera,
    pose: Pose,
    xy_mm,
    dem,
    *,
    tol_m: float = 1e-4,
    max_iter: int = 60,
    lattice_mm: float | None = None,
) -> np.ndarray:
    """Intersect photo rays with a digital elevation model (DEM).

    Parameters
    ----------
    xy_mm : array_like, shape (..., 2)
        Photo coordinates, mm.
    dem : object
        Terrain with a vectorised ``height(X, Y)`` (metres) and the bounds
        ``z_min_m`` ≤ Z ≤ ``z_max_m``, e.g. :class:`FlatTerrain` or
        :class:`aerophoto.site.Site`.  A plain callable ``dem(X, Y)`` is
        accepted too, with its bounds then found from the plane through the
        nadir point.
    tol_m : float
        Convergence tolerance along the ray, metres.
    lattice_mm : None or float, 0 < s ≤ 100
        None (default): every ray is cut with the terrain.  A step s in photo
        mm: the rays are cut only at the nodes of a square lattice of step s
        over the points' bounding box, and each point's ground point is
        interpolated bilinearly between its cell's four nodes — an
        approximate transformer (as GDAL's), for a preview: about s² times
        fewer cuts per photo mm²; its error grows with s² and the terrain's
        curvature (a fotoschema preview at s = 6 px: within 0.15 px on the sheet,
        ``tests/physics/test_mosaic.py``).  Used only where it saves work
        (fewer nodes than points).

    Returns
    -------
    ndarray, shape (..., 3)
        Ground points in metres.  The root is bracketed between the planes
        at ``z_max_m`` and ``z_min_m`` and refined by the Illinois
        (modified regula falsi) method, so it converges for any terrain whose
        heights stay within those bounds.
    """
    _cp(camera, pose)
    if lattice_mm is not None:
        step = check_positive("lattice_mm", lattice_mm, unit="mm", hi=100.0)
        xy = check_finite_array("xy_mm", xy_mm, last=2).reshape(-1, 2)
        x, y = np.ascontiguousarray(xy[:, 0]), np.ascontiguousarray(xy[:, 1])  # (a strided min is 100× slower)
        lo = (x.min(), y.min()) if xy.size else (0.0, 0.0)
        n = (int((x.max() - lo[0]) // step) + 2, int((y.max() - lo[1]) // step) + 2) if xy.size else (1, 1)
        if n[0] * n[1] < len(xy):
            nodes = np.stack(np.meshgrid(lo[0] + step * np.arange(n[0]), lo[1] + step * np.arange(n[1]),
                                         indexing="ij"), axis=-1)  # (n0, n1, 2)
            G = photo_to_dem(camera, pose, nodes, dem, tol_m=tol_m, max_iter=max_iter).reshape(-1, 3)
            u, v = (x - lo[0]) / step, (y - lo[1]) / step  # ≥ 0 by construction
            a, b = np.minimum(u.astype(np.intp), n[0] - 2), np.minimum(v.astype(np.intp), n[1] - 2)
            u -= a
            v -= b
            k = a * n[1] + b  # the cell's lower node, flat; its neighbours at +1 (along y) and +n1 (along x)
            out = np.empty((len(xy), 3))
            # bilinear by hand, one contiguous component at a time (four takes, no (n, 3) temporaries): the fotoschema's
            # preview glues in 7.8 ms so, in 11 ms with scipy's map_coordinates(order=1) — the same values to 1e-16
            for c in range(3):
                Gc = np.ascontiguousarray(G[:, c])
                low = Gc.take(k)
                low += (Gc.take(k + 1) - low) * v
                high = Gc.take(k + n[1])
                high += (Gc.take(k + n[1] + 1) - high) * v
                out[:, c] = low + (high - low) * u
            return out.reshape(np.shape(xy_mm)[:-1] + (3,))
    if not callable(getattr(dem, "height", dem)):
        raise TypeError(f"dem = {dem!r:.60} is a {type(dem).__name__}; expected a Terrain (an object with "
                        "height(X, Y), z_min_m and z_max_m)")
    height: Callable = getattr(dem, "height", dem)
    zmin = float(getattr(dem, "z_min_m", np.nan))
    zmax = float(getattr(dem, "z_max_m", np.nan))
    if not np.isfinite(zmin) or not np.isfinite(zmax):
        raise ValueError("dem must provide finite z_min_m and z_max_m bounds (metres)")
    pose.flying_height(zmax)
    g = _rays(camera, pose, xy_mm)
    shape = g.shape[:-1]
    g = g.reshape(-1, 3)
    # the ray S + t·g one component at a time (contiguous 1-D arrays): the same arithmetic, element for element,
    # as on the (n, 3) array, without its temporaries
    gx, gy, gz = (np.ascontiguousarray(g[:, k]) for k in range(3))
    if np.any(gz >= 0):
        raise ValueError(
            f"a photo ray points at or above the horizon (alpha_deg = {pose.alpha_deg:g}); it never meets the terrain"
        )
    Sx, Sy, Sz = (float(v) for v in pose.centre)
    t0 = (zmax - pose.Z_m) / gz  # ray at the top bound: above (or on) the terrain
    t1 = (zmin - pose.Z_m) / gz  # ray at the bottom bound: below (or on) the terrain

    def resid(t):
        return (Sz + t * gz) - height(Sx + t * gx, Sy + t * gy)

    tol_m = check_positive("tol_m", tol_m, unit="m", hi=1e3)
    max_iter = check_int_range("max_iter", max_iter, 1, 10_000)
    f0 = resid(t0)
    f1 = resid(t1)
    if zmax - zmin <= tol_m:
        t = t0
    else:
        g_len = np.sqrt(np.sum(g * g, axis=-1))  # |g|: the bracket's length along the ray is |t1 − t0|·|g|
        side = np.zeros(t0.shape, dtype=int)
        for _ in range(max_iter):
            d = f0 - f1
            flat = d == 0
            t = np.where(flat, t0, (f0 * t1 - f1 * t0) / np.where(flat, 1.0, d))
            ft = resid(t)
            if np.all((np.abs(ft) <= tol_m) | (np.abs(t1 - t0) * g_len <= tol_m)):
                break
            upper = ft * f0 > 0  # t replaces t0
            # Illinois: halve the retained end's residual when the same end is kept twice
            t0 = np.where(upper, t, t0)
            f0 = np.where(upper, ft, np.where(side == -1, f0 * 0.5, f0))
            t1 = np.where(upper, t1, t)
            f1 = np.where(upper, np.where(side == 1, f1 * 0.5, f1), ft)
            side = np.where(upper, 1, -1)
    out = np.empty(g.shape)
    out[:, 0] = Sx + t * gx
    out[:, 1] = Sy + t * gy
    out[:, 2] = Sz + t * gz
    return out.reshape(shape + (3,))


def transfer_points(camera: Camera, pose_from: Pose, pose_to: Pose, xy_mm, terrain=None) -> np.ndarray:
    """Transfer photo points to a neighbouring photo through their ground points (conjugate points).

    This is what pricking a point on one print and finding the same detail on
    the neighbour does: the ground point seen at ``xy_mm`` on the first photo
    (its ray cut with the terrain, :func:`photo_to_dem`) is projected into the
    second (:func:`ground_to_photo`).

    Parameters
    ----------
    xy_mm : array_like, shape (..., 2)
        Points on the photo taken from ``pose_from``, mm.
    terrain : None, a height in m, or a :class:`Terrain`
        The ground (see :func:`as_terrain`; None is flat ground at Z = 0).

    Returns
    -------
    ndarray, shape (..., 2) : the same ground details on the photo taken from ``pose_to``, mm.
    """
    _cp(camera, pose_from, "pose_from")
    _cp(_NO_CAMERA, pose_to, "pose_to")
    G = photo_to_dem(camera, pose_from, xy_mm, as_terrain(terrain))
    return ground_to_photo(camera, pose_to, G)


def photo_axis_towards(xy_mm) -> tuple[int, float]:
    """The photo axis (0 = x, 1 = y) and its sign (+1.0 or −1.0) pointing most nearly along the vector ``xy_mm``.

    E.g. the neighbour's principal point transferred onto this photo at
    (71.8, −2.1) mm lies along +x: ``(0, 1.0)``.  Used to tell "towards the
    next photo" from "across the strip" whatever the photos' numbering.
    """
    xy = check_finite_array("xy_mm", xy_mm, ndim=1)
    if xy.shape != (2,) or not xy.any():
        raise ValueError(f"xy_mm = {xy.tolist()} must be one non-zero vector (x, y) in mm")
    k = int(np.argmax(np.abs(xy)))
    return k, (1.0 if xy[k] >= 0 else -1.0)


def footprint(camera: Camera, pose: Pose, Z_m: float = 0.0, *, samples_per_side: int = 1) -> np.ndarray:
    """The photo frame projected onto the plane Z = ``Z_m``.

    Returns the ground polygon, shape (4·samples_per_side, 3), metres, going
    round the frame counter-clockwise from the (−half, −half) corner.  With
    ``samples_per_side`` > 1 the edges are sampled too (they stay straight on
    a plane, but not on a DEM).
    """
    _cp(camera, pose)
    c = camera.corners_mm()
    k = check_int_range("samples_per_side", samples_per_side, 1, 10_000)
    pts = []
    for i in range(4):
        a, b = c[i], c[(i + 1) % 4]
        for s in np.arange(k) / k:
            pts.append(a + (b - a) * s)
    return photo_to_plane(camera, pose, np.array(pts), Z_m)


def photo_scale_denominator(camera: Camera, H_m: float) -> float:
    """The scale denominator m of a vertical photo, 1/m = f/H (guide §2: H = f·m)."""
    check_type("camera", camera, Camera)
    H = check_positive("H_m", H_m, unit="m")
    return H / (camera.f_mm / 1000.0)


# --------------------------------------------------------------------------- displacements
def _polar_about_c(camera: Camera, pose: Pose, xy_mm):
    _cp(camera, pose)
    xy = check_finite_array("xy_mm", xy_mm, last=2)
    c = isocentre(camera, pose)
    u = principal_vertical(pose)
    v = np.array([-u[1], u[0]])
    d = xy - c
    a = d @ u
    b = d @ v
    r = np.hypot(a, b)
    phi = np.arctan2(b, a)  # counter-clockwise from the + principal vertical
    return r, phi


def tilt_displacement_approx(camera: Camera, pose: Pose, xy_mm) -> np.ndarray:
    """Tilt displacement by the guide's approximate formula (guide §5, table 6).

        δα = −(r_c² · cos φ / f) · sin α

    Parameters
    ----------
    xy_mm : array_like, shape (..., 2)
        Points on the tilted photo, mm.

    Returns
    -------
    ndarray, shape (...,)
        Signed radial displacement δα in mm, along the line from c through
        the point: negative = pulled towards c (far side, cos φ > 0),
        positive = pushed away from c (nadir side).  r_c is the distance from
        the isocentre c, φ the angle from the positive principal vertical.
    """
    r, phi = _polar_about_c(camera, pose, xy_mm)
    return -(r**2) * np.cos(phi) / camera.f_mm * math.sin(math.radians(pose.alpha_deg))


def tilt_displacement_exact(camera: Camera, pose: Pose, xy_mm) -> np.ndarray:
    """Exact tilt displacement of points of the tilted photo, in mm (radial from c).

        δα = −r_c² · cos φ · sin α / (f − r_c · cos φ · sin α)

    This is the closed form of what :func:`tilt_displacement_vectors` computes
    by projection: the difference between a point's distance from c on the
    tilted photo and on the equivalent vertical photo hinged about the
    isoline h_c h_c.  For small α it tends to :func:`tilt_displacement_approx`.
    Same shapes and signs as that function.
    """
    r, phi = _polar_about_c(camera, pose, xy_mm)
    s = math.sin(math.radians(pose.alpha_deg))
    return -(r**2) * np.cos(phi) * s / (camera.f_mm - r * np.cos(phi) * s)


def tilt_displacement_vectors(camera: Camera, pose: Pose, XYZ_m):
    """Exact tilt displacement of ground points, by projecting them twice.

    Each ground point is projected through the tilted photo (``pose``) and
    through the equivalent vertical photo (``pose.levelled()``); the vertical
    photo is then turned about the isoline h_c h_c into the plane of the
    tilted one, which shifts it by −2·f·tg(α/2) along the principal vertical.

    Returns
    -------
    xy_tilted : ndarray, shape (..., 2)
        Image on the tilted photo, mm.
    xy_vertical : ndarray, shape (..., 2)
        Where the point would be without tilt, in the same photo coordinates, mm.
    The displacement vector is ``xy_tilted − xy_vertical``; it points along
    the line from c (the isocentre keeps angles).
    """
    _cp(camera, pose)
    xy_t = ground_to_photo(camera, pose, XYZ_m)
    xy_v = ground_to_photo(camera, pose.levelled(), XYZ_m)
    shift = -2.0 * camera.f_mm * math.tan(math.radians(pose.alpha_deg) / 2.0) * principal_vertical(pose)
    return xy_t, xy_v + shift


def relief_displacement(r_mm, h_m, H_m):
    """Relief displacement δh = r·h/H (guide §4, formula 4.1).

    Parameters
    ----------
    r_mm : array_like
        Distance r_n of the point's image from the nadir point n, mm.
    h_m : array_like
        Height h of the point above the mean object plane (средняя предметная
        плоскость), metres; negative below it.
    H_m : float
        Flying height H above the mean object plane, metres (H > 0).

    Returns
    -------
    ndarray
        δh in mm, radial from n: positive = displaced away from n (the point
        is above the plane; the correction moves it towards n), negative =
        displaced towards n.  Exact on a vertical photo when r is measured to
        the point's actual image.
    """
    H = check_positive("H_m", H_m, unit="m")
    h = check_values("h_m", h_m, unit="m")
    r = check_values("r_mm", r_mm, 0.0, unit="mm")
    if np.any(h >= H):
        raise ValueError(f"h_m = {float(np.max(h)):g} is at or above the camera; the valid range is h_m < H_m = {H:g} m")
    return r * h / H
