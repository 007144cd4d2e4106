"""Exact photographs of the virtual site (:mod:`aerophoto.site`).

:func:`render` takes a frame camera (:class:`aerophoto.geometry.Camera`) and
an exterior orientation (:class:`aerophoto.geometry.Pose`) and computes, for
the centre of every pixel, the ray from the projection centre S through that
photo point (the camera model of :mod:`aerophoto.geometry`), intersects it
with the site's DEM and samples the ground texture there.  So the picture is
a true central projection of the terrain: relief displacement, tilt
displacement and scale variation are all in it, exactly as
:func:`aerophoto.geometry.ground_to_photo` predicts.

Pixel convention
----------------
A photo of ``n_px`` × ``n_px`` pixels covers the whole frame (side l =
``camera.frame_mm``); the pixel size is p = l/n_px mm.  ``image[row, col]``:
row 0 is the **top** of the photo (+y), column 0 its left edge (−x).  Integer
(row, col) are pixel **centres**:

    x = −l/2 + (col + 0.5)·p,    y = +l/2 − (row + 0.5)·p      (mm)

and :meth:`Photo.mm_to_pixel` / :meth:`Photo.pixel_to_mm` convert both ways
(fractional rows/columns allowed).  ``imshow(photo.image, extent=photo.extent_mm)``
with the default ``origin="upper"`` shows the photo in photo millimetres.

How a pixel is computed
-----------------------
1. Ray directions: the camera vectors (x, y, −f) of all pixel centres are
   cached per (f, l, n_px) and rotated by the pose (``R`` of
   :func:`aerophoto.geometry.rotation_matrix`).
2. Ray–DEM intersection, coarse to fine: on a coarse lattice of pixels
   (every 8th) the rays are intersected exactly with
   :func:`aerophoto.geometry.photo_to_dem` (bracketed Illinois method); the
   ground heights found are interpolated to every pixel and refined there by
   secant iterations on the bilinear DEM until the largest residual
   |Z − h(X, Y)| is below ``tol_m`` (default 1 mm; typically 2–3 DEM
   evaluations).  The final residual is kept in :attr:`Photo.dem_residual_m`.
3. Brightness: :meth:`aerophoto.site.Site.sample` (bilinear) at the ground
   point, on the texture-pyramid level whose texels best match the pixel's
   ground size at the principal point (less aliasing), then multiplied by the
   light fall-off 1 − v·(r/r_corner)² (``vignetting`` v, r the distance from
   o; v = 0 gives the texture values exactly).  Pixels whose ground point is
   off the site get ``background`` and ``valid`` False.
4. Optionally the four fiducial marks (координатные метки) at the middles of
   the frame sides are burnt in (black wedges with a white centre line on
   the x and y axes).

Objects with height
-------------------
With ``objects=True`` (the default, for a site that has them:
:attr:`aerophoto.site.Site.objects`) every ray is also cut with what stands
on the ground — houses, crowns, the chimney, the mast, the water tower, the
embankment and the bridge exactly (convex polyhedra and ellipsoids), the
forest canopy by marching its height field — and the nearest hit wins.  So a
tall object leans away from the nadir point by δh = r·h/H (guide §4) and hides
the ground behind it; :attr:`Photo.surface` says what each pixel shows
(:data:`aerophoto.site.objects.SURFACES`) and :attr:`Photo.object_id` which
object.  The ground stays the texture sampled at the hit (its relief shading
is the texture's: sun in the south-west, 45° high).  Objects are shaded by the
same light (:class:`Sun`); with ``sun=Sun(azimuth_deg, elevation_deg)`` they are
shaded by that sun and **cast shadows** on the ground, on each other and on
the canopy (:attr:`Photo.shadow`).  A wrapper of the site without ``objects``
(:class:`aerophoto.terrain.RescaledRelief`) renders bare ground.  The extra
cost: see ``benchmarks/bench_render.py`` (``render_512`` against
``render_512_bare``).

Public API
----------
``render(site, camera, pose, n_px=512, *, vignetting=0.15, fiducials=True,
level=None, background=0.5, keep_ground=False, tol_m=1e-3, number=None, objects=True, sun=None) -> Photo``
``trace(site, camera, pose, xy_mm, *, objects=True) -> Hits`` — what the rays of any photo points hit
``Sun(azimuth_deg=225, elevation_deg=45)`` — the light (azimuth clockwise from north)
``render_shot(site, shot, n_px=512, **kw) -> Photo`` (a :class:`aerophoto.simulate.Shot`)
``render_strip(site, strip, n_px=512, **kw) -> list[Photo]``
``Photo``: ``image`` (n, n) float32 0…1, ``camera``, ``pose``, ``pixel_mm``,
``mm_to_pixel``, ``pixel_to_mm``, ``pixel_centres_mm()``, ``project(XYZ)``,
``points(catalogue=None)``, ``value_at(xy_mm)``, ``light_falloff()``,
``valid``, ``ground_m``, ``level``, ``surface``, ``object_id``, ``shadow``, ``objects``, ``sun``.

This module is data only (layer 3).  A photo's view — the image in photo mm
with its points in the guide's symbols, updated in place — is
:class:`aerophoto.demos.site_views.PhotoView` (:func:`~aerophoto.demos.site_views.show_photo`).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from . import _validate as V
from . import geometry as g
from ._validate import check_int_range, check_range
from .site.raycast import AMBIENT, box_pixel_pairs, box_point_pairs, first_hits, in_shadow, light_factor

__all__ = ["Photo", "Sun", "Hits", "render", "render_shot", "render_strip", "trace", "AMBIENT"]

COARSE_STEP = 8
MAX_PX = 4096


@dataclass(frozen=True)
class Sun:
    """The sun: where it stands, for shading objects and casting their shadows.

    Parameters
    ----------
    azimuth_deg : float
        Azimuth of the sun, degrees clockwise from north (geographic), 0 ≤ A < 360;
        225 = south-west (the light of the site's texture).
    elevation_deg : float
        Height of the sun above the horizon, degrees, 1 ≤ h ≤ 90.
    """

    azimuth_deg: float = 225.0
    elevation_deg: float = 45.0

    def __post_init__(self):
        object.__setattr__(self, "azimuth_deg", check_range("azimuth_deg", self.azimuth_deg, 0.0, 360.0,
                                                             hi_open=True, unit="degrees"))
        object.__setattr__(self, "elevation_deg", check_range("elevation_deg", self.elevation_deg, 1.0, 90.0,
                                                               unit="degrees"))

    @property
    def direction(self) -> np.ndarray:
        """Unit vector from the ground towards the sun (X east, Y north, Z up)."""
        a, e = math.radians(self.azimuth_deg), math.radians(self.elevation_deg)
        return np.array([math.sin(a) * math.cos(e), math.cos(a) * math.cos(e), math.sin(e)])

    @property
    def shadow_azimuth_deg(self) -> float:
        """The direction shadows fall in, degrees clockwise from north."""
        return (self.azimuth_deg + 180.0) % 360.0

    def shadow_length_m(self, h_m):
        """Length of the shadow of a height h on level ground, L = h / tg(elevation), metres."""
        return np.asarray(h_m, dtype=float) / math.tan(math.radians(self.elevation_deg))


#: the light of the site's texture (its relief shading): objects are shaded by it when no sun is given
TEXTURE_LIGHT = Sun(225.0, 45.0)


@dataclass(frozen=True, eq=False)
class Hits:
    """What rays hit: the point, the kind of surface and the object.

    Attributes
    ----------
    XYZ_m : ndarray (N, 3)
        The first point on the surface along each ray, metres.
    surface : ndarray (N,) uint8
        :data:`aerophoto.site.objects.SURFACES` code (0 ground, 1 roof, 2 wall, 3 tree crown, 4 forest canopy,
        5 structure, 6 embankment).
    object_id : ndarray (N,) int64
        The row of ``site.objects.table()`` hit, −1 for the ground and the canopy.
    normal : ndarray (N, 3)
        Unit normal of the surface there (up for the ground).
    """

    XYZ_m: np.ndarray
    surface: np.ndarray
    object_id: np.ndarray
    normal: np.ndarray


# --------------------------------------------------------------------------- the photo
@dataclass(frozen=True, eq=False, repr=False)
class Photo:
    """A rendered photograph and everything needed to measure on it.

    Attributes
    ----------
    image : ndarray, shape (n_px, n_px), float32
        Brightness 0…1 (0 black); row 0 at the top (+y), column 0 at the left (−x).
    camera : Camera
    pose : Pose
        The true exterior orientation the photo was taken with.
    site : Site
        The site photographed.
    valid : ndarray, shape (n_px, n_px), bool
        True where the pixel's ground point lies on the site.
    level : int
        Texture-pyramid level sampled (texels ``site.texel_m(level)`` metres).
    vignetting : float
        Light fall-off v used (see :meth:`light_falloff`).
    fiducials : bool
        Whether fiducial marks were burnt in.
    dem_residual_m : float
        Largest |Z − h(X, Y)| of the pixels' ground points, metres.
    ground_m : ndarray, shape (n_px, n_px, 3), float64, or None
        Ground point (X, Y, Z) of every pixel centre, when rendered with ``keep_ground=True``.
    number : int or None
        The photo's number (e.g. from a simulated shot).
    dem_evaluations : int
        Full-resolution DEM evaluations the intersection needed (for profiling).
    surface : ndarray (n_px, n_px) uint8 or None
        What each pixel shows (:data:`aerophoto.site.objects.SURFACES`; 0 = ground), when rendered with objects.
    object_id : ndarray (n_px, n_px) int32 or None
        Which object each pixel shows (row of ``site.objects.table()``; −1 = ground or canopy).
    shadow : ndarray (n_px, n_px) bool or None
        Pixels in a cast shadow (rendered with a ``sun``).
    objects : bool
        Whether the objects with height were rendered (then :attr:`ground_m` holds the surface hit).
    sun : Sun or None
        The sun the photo was rendered with (None: the texture's light, no cast shadows).
    """

    image: np.ndarray
    camera: g.Camera
    pose: g.Pose
    site: object
    valid: np.ndarray
    level: int
    vignetting: float
    fiducials: bool
    dem_residual_m: float
    ground_m: np.ndarray | None = None
    number: int | None = None
    dem_evaluations: int = 0
    surface: np.ndarray | None = None
    object_id: np.ndarray | None = None
    shadow: np.ndarray | None = None
    objects: bool = False
    sun: Sun | None = None
    window_mm: tuple | None = None
    normal: np.ndarray | None = None

    def __repr__(self) -> str:
        p = self.pose
        num = f" {self.number}" if self.number is not None else ""
        win = "" if self.window_mm is None else (f", window {self.window_mm[2]:g} mm at ({self.window_mm[0]:g}, "
                                                 f"{self.window_mm[1]:g}) mm")
        return (f"Photo{num}({self.n_px}×{self.n_px} px, p = {self.pixel_mm:.4g} mm{win}, f = {self.camera.f_mm:g} mm, "
                f"S = ({p.X_m:.1f}, {p.Y_m:.1f}, {p.Z_m:.1f}) m, α = {p.alpha_deg:.3g}°, λ = {p.lambda_deg:.4g}°, "
                f"κ = {p.kappa_deg:.4g}°)")

    # ---- pixel geometry
    @property
    def n_px(self) -> int:
        """Pixels across the photo (the frame, or the window)."""
        return int(self.image.shape[0])

    @property
    def shape(self) -> tuple:
        return self.image.shape

    @property
    def raster(self) -> tuple | None:
        """``(x_left, y_top, p)`` mm of a window's pixel grid (see :func:`render`'s ``window_mm``); None: the frame."""
        return None if self.window_mm is None else _window_raster(self.window_mm, self.n_px)

    @property
    def pixel_mm(self) -> float:
        """Pixel size p = l/n_px (the frame) or side/n_px (a window), mm."""
        if self.window_mm is not None:
            return float(self.window_mm[2]) / self.n_px
        return self.camera.frame_mm / self.n_px

    def _origin(self) -> tuple:
        """(x of the left edge, y of the top edge, p), mm."""
        if self.window_mm is None:
            h = self.camera.half_mm
            return -h, h, self.pixel_mm
        return self.raster

    @property
    def extent_mm(self) -> tuple:
        """(left, right, bottom, top) in photo mm, for ``imshow(..., extent=...)``."""
        if self.window_mm is None:
            h = self.camera.half_mm
            return (-h, h, -h, h)
        x0, y0, p = self.raster
        s = p * self.n_px
        return (x0, x0 + s, y0 - s, y0)

    def mm_to_pixel(self, xy_mm) -> np.ndarray:
        """Photo coordinates (…, 2) in mm → (row, col) (…, 2), fractional; integers are pixel centres."""
        xy = np.asarray(xy_mm, dtype=float)
        x0, y0, p = self._origin()
        return np.stack([(y0 - xy[..., 1]) / p - 0.5, (xy[..., 0] - x0) / p - 0.5], axis=-1)

    def pixel_to_mm(self, rowcol) -> np.ndarray:
        """(row, col) (…, 2) → photo coordinates x, y (…, 2) in mm."""
        rc = np.asarray(rowcol, dtype=float)
        x0, y0, p = self._origin()
        return np.stack([x0 + (rc[..., 1] + 0.5) * p, y0 - (rc[..., 0] + 0.5) * p], axis=-1)

    def pixel_centres_mm(self) -> np.ndarray:
        """x, y of every pixel centre, shape (n_px, n_px, 2), mm."""
        return _pixel_grid_mm(self.camera.frame_mm, self.n_px, self.raster)

    def value_at(self, xy_mm) -> np.ndarray:
        """Image brightness at photo points (…, 2) mm, bilinear between pixel centres."""
        from scipy.ndimage import map_coordinates

        rc = self.mm_to_pixel(xy_mm)
        flat = rc.reshape(-1, 2).T
        return map_coordinates(self.image, flat, order=1, mode="nearest").reshape(rc.shape[:-1])

    def light_falloff(self) -> np.ndarray:
        """The factor 1 − v·(r/r_corner)² the texture was multiplied by, shape (n_px, n_px), float32."""
        return _falloff(self.camera.frame_mm, self.n_px, self.vignetting, self.raster)

    # ---- ground ↔ photo
    def project(self, XYZ_m) -> np.ndarray:
        """Photo coordinates (…, 2) mm of ground points (…, 3) m: :func:`aerophoto.geometry.ground_to_photo`."""
        return g.ground_to_photo(self.camera, self.pose, XYZ_m)

    def points(self, catalogue: pd.DataFrame | None = None, *, occlusion_tol_m: float = 0.5) -> pd.DataFrame:
        """Catalogue points as imaged on this photo.

        Returns the catalogue (default ``site.catalogue``) with the extra
        columns ``x_mm``, ``y_mm`` (exact projection), ``row``, ``col``
        (fractional pixel position) and ``visible``: inside the frame and
        not hidden by the terrain (the ray from S through the image point
        meets the DEM within ``occlusion_tol_m`` of the point) — nor, on a
        photo rendered with objects, by a house, a crown or the canopy (the
        ray's first hit, :func:`trace`).  Points behind the camera get NaN
        coordinates and ``visible`` False.  ``catalogue=site.all_points``
        includes the objects' roof corners and tops.
        """
        cat = self.site.catalogue if catalogue is None else catalogue
        df = cat.copy()
        P = df[["X_m", "Y_m", "Z_m"]].to_numpy(dtype=float)
        xy = np.full((len(df), 2), np.nan)
        if len(df):
            R = g.rotation_matrix(self.pose)
            front = (P - self.pose.centre) @ R[:, 2] < 0  # below the plane of S parallel to the photo
            if front.any():
                xy[front] = g.ground_to_photo(self.camera, self.pose, P[front])
        rc = self.mm_to_pixel(xy)
        left, right, bottom, top = self.extent_mm
        with np.errstate(invalid="ignore"):
            inside = ((xy[:, 0] >= left) & (xy[:, 0] <= right) & (xy[:, 1] >= bottom) & (xy[:, 1] <= top))
        visible = inside.copy()
        if inside.any():
            if self.objects:
                back = trace(self.site, self.camera, self.pose, xy[inside]).XYZ_m
            else:
                back = g.photo_to_dem(self.camera, self.pose, xy[inside], self.site)
            visible[inside] = np.linalg.norm(back - P[inside], axis=1) <= occlusion_tol_m
        df["x_mm"] = xy[:, 0]
        df["y_mm"] = xy[:, 1]
        df["row"] = rc[:, 0]
        df["col"] = rc[:, 1]
        df["visible"] = visible
        return df


# --------------------------------------------------------------------------- cached per-camera arrays
@functools.lru_cache(maxsize=16)
def _window_raster(window_mm: tuple, n_px: int) -> tuple:
    """``(x_left, y_top, p)`` mm of the pixel grid of a window ``(x_centre, y_centre, side)`` mm, ``n_px`` across."""
    xc, yc, side = (float(a) for a in window_mm)
    return (xc - side / 2.0, yc + side / 2.0, side / n_px)


def _pixel_grid_mm(frame_mm: float, n_px: int, raster: tuple | None = None) -> np.ndarray:
    """x, y (mm) of the pixel centres, shape (n_px, n_px, 2): the frame's, or a window's ``raster``."""
    if raster is None:
        p = frame_mm / n_px
        h = frame_mm / 2.0
        x = -h + (np.arange(n_px) + 0.5) * p
        y = h - (np.arange(n_px) + 0.5) * p
    else:
        x0, y0, p = raster
        x = x0 + (np.arange(n_px) + 0.5) * p
        y = y0 - (np.arange(n_px) + 0.5) * p
    out = np.empty((n_px, n_px, 2))
    out[..., 0] = x[None, :]
    out[..., 1] = y[:, None]
    out.flags.writeable = False
    return out


@functools.lru_cache(maxsize=16)
def _camera_vectors(f_mm: float, frame_mm: float, n_px: int, raster: tuple | None = None) -> np.ndarray:
    """(n_px², 3) camera-frame vectors (x, y, −f) of the pixel centres, read-only."""
    xy = _pixel_grid_mm(frame_mm, n_px, raster).reshape(-1, 2)
    out = np.empty((len(xy), 3))
    out[:, :2] = xy
    out[:, 2] = -f_mm
    out.flags.writeable = False
    return out


@functools.lru_cache(maxsize=16)
def _falloff(frame_mm: float, n_px: int, v: float, raster: tuple | None = None) -> np.ndarray:
    xy = _pixel_grid_mm(frame_mm, n_px, raster)
    r2 = (xy[..., 0] ** 2 + xy[..., 1] ** 2) / (2.0 * (frame_mm / 2.0) ** 2)
    out = (1.0 - v * r2).astype(np.float32)
    out.flags.writeable = False
    return out


@functools.lru_cache(maxsize=16)
def _coarse_plan(n_px: int, step: int):
    """Coarse lattice indices (every ``step``-th pixel, plus the last) and linear interpolation matrix."""
    idx = np.unique(np.r_[np.arange(0, n_px, step), n_px - 1])
    A = np.zeros((n_px, len(idx)))
    pos = np.arange(n_px)
    k = np.clip(np.searchsorted(idx, pos, side="right") - 1, 0, len(idx) - 2)
    w = (pos - idx[k]) / (idx[k + 1] - idx[k])
    A[pos, k] = 1.0 - w
    A[pos, k + 1] = w
    A.flags.writeable = False
    idx.flags.writeable = False
    return idx, A


def _fiducial_mask(n_px: int, frame_mm: float = 180.0, raster: tuple | None = None) -> tuple:
    """(dark, light) coverage masks of the four fiducial marks at the middles of the frame sides (of a window's
    ``raster`` of the frame ``frame_mm``: the parts of the marks inside it)."""
    return _fiducial_cached(n_px, float(frame_mm), raster)


@functools.lru_cache(maxsize=8)
def _fiducial_cached(n_px: int, frame_mm: float = 180.0, raster: tuple | None = None):
    # in units of the frame side: a wedge 4 % deep and 3 % wide at each side's middle, with a thin light axis line
    if raster is None:
        c = (np.arange(n_px) + 0.5) / n_px - 0.5  # −0.5 … 0.5 across
        X, Y = np.meshgrid(c, -c)  # x right, y up (row 0 at the top)
        line = max(0.6 / n_px, 0.002)
    else:
        xy = _pixel_grid_mm(frame_mm, n_px, raster) / frame_mm
        X, Y = xy[..., 0], xy[..., 1]
        line = max(0.6 * raster[2] / frame_mm, 0.002)
    depth, half_w = 0.04, 0.015
    dark = np.zeros((n_px, n_px), bool)
    light = np.zeros((n_px, n_px), bool)
    for along, across in ((X, Y), (-X, Y), (Y, X), (-Y, X)):
        d = 0.5 - along  # distance from this side
        wedge = (d <= depth) & (np.abs(across) <= half_w * (1.0 - d / depth) + (0.5 / n_px if raster is None else
                                                                               0.5 * raster[2] / frame_mm))
        dark |= wedge
        light |= wedge & (np.abs(across) <= line) & (d <= depth * 0.8)
    dark &= ~light
    dark.flags.writeable = False
    light.flags.writeable = False
    return dark, light


# --------------------------------------------------------------------------- rendering
def _ground_pixel_m(site, camera: g.Camera, pose: g.Pose, n_px: int, raster: tuple | None = None) -> float:
    H = max(pose.Z_m - site.mean_height_m, 1e-3)
    p = camera.frame_mm / n_px if raster is None else raster[2]
    return p * H / camera.f_mm


@V.checked(site=V.has_attrs("level_for", "height", what="a Site (aerophoto.site.get_site())"), camera=g.Camera,
           pose=g.Pose)
def render(
    site,
    camera: g.Camera,
    pose: g.Pose,
    n_px: int = 512,
    *,
    vignetting: float = 0.15,
    fiducials: bool = True,
    level: int | None = None,
    background: float = 0.5,
    keep_ground: bool = False,
    tol_m: float = 1e-3,
    number: int | None = None,
    objects: bool = True,
    sun: Sun | None = None,
    window_mm: tuple | None = None,
    keep_normals: bool = False,
) -> Photo:
    """Photograph the site with a frame camera at an exterior orientation, exactly.

    Parameters
    ----------
    site : aerophoto.site.Site
    camera : Camera
        f and the frame l, mm.
    pose : Pose
        Projection centre S (m) and α, λ, κ (degrees); S must be above the
        highest ground and every pixel's ray must point below the horizon.
    n_px : int
        Pixels across the frame, 16 ≤ n_px ≤ 4096 (pixel p = l/n_px mm).
    vignetting : float
        Light fall-off v, 0 ≤ v < 1: the brightness is multiplied by
        1 − v·(r/r_corner)² (0 = none).
    fiducials : bool
        Burn in the fiducial marks at the middles of the frame sides.
    level : int or None
        Texture-pyramid level; None chooses it from the ground pixel size.
    background : float
        Brightness of pixels whose ground point is off the site, 0 ≤ b ≤ 1.
    keep_ground : bool
        Keep every pixel's ground point in :attr:`Photo.ground_m`.
    tol_m : float
        Largest accepted |Z − h(X, Y)| of a pixel's ground point, metres
        (1e-6 ≤ tol ≤ 1).
    number : int or None
        A photo number to carry along.
    objects : bool
        Ray-cast the site's objects with height (houses, trees, canopy, …) when it has them
        (``site.objects``); False photographs the bare ground.
    sun : Sun or None
        Shade the objects by this sun and cast their shadows; None shades them by the
        texture's light (south-west, 45°) without cast shadows.
    window_mm : (x, y, side) or None
        Photograph only a square window of the frame: centre x, y and side in photo mm
        (0.5 mm ≤ side ≤ l, the window inside the frame), ``n_px`` pixels across it — the
        same central projection, finer pixels (a magnifier's view, chapter 08).
        None: the whole frame.
    keep_normals : bool
        Keep the unit surface normal of every pixel's hit in :attr:`Photo.normal`
        (n_px, n_px, 3) float32 (up for bare ground).

    Returns
    -------
    Photo
    """
    if not isinstance(camera, g.Camera):
        raise ValueError(f"camera = {camera!r} must be an aerophoto.geometry.Camera")
    if not isinstance(pose, g.Pose):
        raise ValueError(f"pose = {pose!r} must be an aerophoto.geometry.Pose")
    n = check_int_range("n_px", n_px, 16, MAX_PX)
    window, raster = _check_window(window_mm, camera, n)
    v = check_range("vignetting", vignetting, 0.0, 1.0, hi_open=True)
    bg = check_range("background", background, 0.0, 1.0)
    tol = check_range("tol_m", tol_m, 1e-6, 1.0, unit="m")
    if sun is not None and not isinstance(sun, Sun):
        raise ValueError(f"sun = {sun!r} must be an aerophoto.render.Sun or None")
    if level is None:
        lev = site.level_for(_ground_pixel_m(site, camera, pose, n, raster))
    else:
        lev = check_int_range("level", level, 0, site.n_levels - 1)
    zmax = float(site.z_max_m)
    pose.flying_height(zmax)  # S must be above the terrain

    ax, ay = _pixel_rays(camera, pose, n, raster)
    Xg, Yg, Z, residual, n_eval = _ground_under_rays(site, camera, pose, n, ax, ay, tol, raster)
    objs = getattr(site, "objects", None) if objects else None
    hits = None
    if objs is not None:
        hits, Xg, Yg, Z = _objects_on_rays(site, objs, camera, pose, n, ax, ay, Xg, Yg, Z, raster)
    img, valid, shadow = _brightness(site, lev, Xg, Yg, Z, hits, objs, sun, camera, pose, n, raster)
    img = _finish_image(img.reshape(n, n), valid.reshape(n, n), camera, n, v, bg, fiducials, raster)
    valid = valid.reshape(n, n)
    ground = None
    if keep_ground:
        ground = np.stack([Xg, Yg, Z], axis=-1).reshape(n, n, 3)
    surface = object_id = normal = None
    if hits is not None:
        surface = hits.surface.reshape(n, n)
        object_id = hits.object_id.astype(np.int32).reshape(n, n)
    if keep_normals:
        normal = np.zeros((n * n, 3), np.float32)
        normal[:, 2] = 1.0
        if hits is not None and len(hits.idx):
            normal[hits.idx] = hits.normal
        normal = normal.reshape(n, n, 3)
    return Photo(image=img, camera=camera, pose=pose, site=site, valid=valid, level=lev, vignetting=v,
                 fiducials=bool(fiducials), dem_residual_m=residual, ground_m=ground, number=number,
                 dem_evaluations=n_eval, surface=surface, object_id=object_id, shadow=shadow,
                 objects=hits is not None, sun=sun, window_mm=window, normal=normal)


def _check_window(window_mm, camera: g.Camera, n: int) -> tuple:
    """``(window, raster)``: the window ``(x, y, side)`` mm checked (None: the frame) and its pixel grid."""
    if window_mm is None:
        return None, None
    w = np.asarray(window_mm, dtype=float).ravel() if not isinstance(window_mm, str) else np.zeros(0)
    if w.shape != (3,) or not np.all(np.isfinite(w)):
        raise ValueError(f"window_mm = {window_mm!r} must be three finite numbers (x, y, side) in mm")
    h = camera.half_mm
    side = check_range("window_mm side", float(w[2]), 0.5, camera.frame_mm, unit="mm")
    lim = h - side / 2.0
    check_range("window_mm x", float(w[0]), -lim, lim, unit="mm")
    check_range("window_mm y", float(w[1]), -lim, lim, unit="mm")
    window = (float(w[0]), float(w[1]), side)
    return window, _window_raster(window, n)


def _pixel_rays(camera: g.Camera, pose: g.Pose, n: int, raster: tuple | None = None):
    """The ray of every pixel as slopes: ``(ax, ay)``, dX/dZ and dY/dZ, each shape (n·n,).

    Raises ValueError when a ray points at or above the horizon (the tilt is too large for the lens).
    """
    cam = _camera_vectors(camera.f_mm, camera.frame_mm, n, raster)
    R = g.rotation_matrix(pose)
    gz = cam @ R[2]
    if np.any(gz >= 0):
        raise ValueError(
            f"some pixels' rays point at or above the horizon (alpha_deg = {pose.alpha_deg:g}, f_mm = "
            f"{camera.f_mm:g}); the valid range is a tilt with every ray below the horizon, "
            f"|alpha_deg| < {90.0 - math.degrees(math.atan(camera.half_mm * math.sqrt(2) / camera.f_mm)):.1f}"
        )
    ax = (cam @ R[0]) / gz  # dX/dZ along each ray
    ay = (cam @ R[1]) / gz
    return ax, ay


def _ground_under_rays(site, camera: g.Camera, pose: g.Pose, n: int, ax, ay, tol: float,
                       raster: tuple | None = None):
    """Where every pixel's ray meets the bare ground (the DEM), to ``tol`` metres in height.

    Exact, bracketed intersections on a coarse lattice of pixels give a first height by interpolation; a secant
    iteration on the DEM (bilinear) refines every pixel; pixels still off by more than ``tol`` after 12 steps
    (pathological terrain) are solved by the bracketed solver.  Returns ``(X, Y, Z, residual_m, evaluations)``:
    ground coordinates in metres, shape (n·n,) each, the largest |Z − h(X, Y)| and the number of DEM look-ups.
    """
    from scipy.ndimage import map_coordinates

    s = float(site.dem_spacing_m)
    Sx, Sy, Sz = pose.X_m, pose.Y_m, pose.Z_m
    idx, A = _coarse_plan(n, COARSE_STEP)
    grid = _pixel_grid_mm(camera.frame_mm, n, raster)
    coarse = g.photo_to_dem(camera, pose, grid[np.ix_(idx, idx)], site, tol_m=min(tol, 1e-3) * 0.1)
    Z = (A @ coarse[..., 2] @ A.T).reshape(-1)

    dem = site.dem
    coords = np.empty((2, n * n))
    dz = np.empty(n * n)
    n_eval = [0]

    def height_on_ray(Zv):
        n_eval[0] += 1
        np.subtract(Zv, Sz, out=dz)
        np.multiply(ay, dz, out=coords[0])
        coords[0] += Sy
        coords[0] *= 1.0 / s
        np.multiply(ax, dz, out=coords[1])
        coords[1] += Sx
        coords[1] *= 1.0 / s
        return map_coordinates(dem, coords, order=1, mode="nearest")

    h = height_on_ray(Z)
    f = Z - h
    Z_prev = f_prev = None
    for _ in range(12):
        if float(np.max(np.abs(f))) <= tol:
            break
        if Z_prev is None:
            Z_new = h  # fixed-point step: move to the height found under the ray
        else:
            den = f - f_prev
            ok = np.abs(den) > 1e-12
            Z_new = np.where(ok, Z - f * (Z - Z_prev) / np.where(ok, den, 1.0), h)
        Z_prev, f_prev = Z, f
        Z = Z_new
        h = height_on_ray(Z)
        f = Z - h
    residual = float(np.max(np.abs(f)))
    if residual > tol:  # pathological terrain: fall back to the bracketed solver for the stragglers
        bad = np.abs(f) > tol
        P = g.photo_to_dem(camera, pose, grid.reshape(-1, 2)[bad], site, tol_m=tol * 0.1)
        Z[bad] = P[:, 2]
        h = height_on_ray(Z)
        f = Z - h
        residual = float(np.max(np.abs(f)))
    # ground coordinates of the final heights (coords holds Y/s, X/s of the last evaluation)
    return coords[1] * s, coords[0] * s, Z, residual, n_eval[0]


def _objects_on_rays(site, objs, camera: g.Camera, pose: g.Pose, n: int, ax, ay, Xg, Yg, Z,
                     raster: tuple | None = None):
    """What stands on the ground: the nearest hit of every ray on the site's objects.

    Returns ``(hits, X, Y, Z)``: the :class:`Hits` and the ground coordinates with the hit pixels moved onto the
    objects' surfaces (``Xg`` and ``Yg`` are changed in place; ``Z`` is copied).
    """
    Sx, Sy, Sz = pose.X_m, pose.Y_m, pose.Z_m
    k, pix = box_pixel_pairs(objs.bbox, camera, pose, n, raster)
    hits = first_hits(site, objs, pose.centre, ax, ay, Sz - Z, k, pix, Xg, Yg)
    moved = hits.idx
    u = hits.u
    Xg[moved] = Sx - ax[moved] * u
    Yg[moved] = Sy - ay[moved] * u
    Z = Z.copy()
    Z[moved] = Sz - u
    return hits, Xg, Yg, Z


def _brightness(site, lev: int, Xg, Yg, Z, hits, objs, sun, camera: g.Camera, pose: g.Pose, n: int,
                raster: tuple | None = None):
    """The brightness of every pixel: the texture at its ground point, the objects shaded, their shadows cast.

    Returns ``(img, valid, shadow)``: brightness 0…1 (float32, shape (n·n,)), whether the ground point is on the
    site (shape (n·n,)), and the pixels in a cast shadow (shape (n, n), or None without objects or sun).
    """
    from scipy.ndimage import map_coordinates

    coords = np.empty((2, n * n))
    t = site.texel_m(lev)
    tex = site.texture_level(lev)
    coords[0] = Yg / t - 0.5
    coords[1] = Xg / t - 0.5
    img = map_coordinates(tex, coords, order=1, mode="nearest", output=np.float32)
    img *= np.float32(1.0 / 255.0)
    x0, x1, y0, y1 = site.extent_m
    valid = (Xg >= x0) & (Xg <= x1) & (Yg >= y0) & (Yg <= y1)
    shadow = None
    if hits is not None:
        light = (sun or TEXTURE_LIGHT).direction
        on = hits.idx
        lit = light_factor(hits.normal, light)
        own = np.isfinite(hits.albedo)  # faces with a brightness of their own (not the texture)
        img[on[own]] = hits.albedo[own]
        img[on] *= lit
        if sun is not None:
            shadow = in_shadow(objs, site, Xg, Yg, Z, hits.object_id, light, camera, pose, n, raster)
            sh = np.flatnonzero(shadow)
            f = np.ones(len(sh), np.float32)
            pos = np.searchsorted(on, sh)  # pixels of objects in shadow: down to the ambient light
            is_on = (pos < len(on)) & (on[np.minimum(pos, len(on) - 1)] == sh)
            f[is_on] = np.float32(AMBIENT) / np.maximum(lit[pos[is_on]], np.float32(AMBIENT))
            f[~is_on] = np.float32(AMBIENT)
            img[sh] *= f
            shadow = shadow.reshape(n, n)
    return img, valid, shadow


def _finish_image(img, valid, camera: g.Camera, n: int, v: float, bg: float, fiducials: bool,
                  raster: tuple | None = None):
    """The camera's marks on the picture: light fall-off ``v``, background ``bg`` off the site, fiducials.

    ``img`` (n, n) is changed in place and returned.
    """
    if v > 0:
        img *= _falloff(camera.frame_mm, n, v, raster)
    if not valid.all():
        img[~valid] = bg
    if fiducials:
        dark, light_mask = _fiducial_mask(n, camera.frame_mm, raster)
        img[dark] = 0.0
        img[light_mask] = 1.0
    return img


@V.checked(site=V.has_attrs("height", what="a Site or a terrain"), camera=g.Camera, pose=g.Pose, xy_mm=V.points(2))
def trace(site, camera: g.Camera, pose: g.Pose, xy_mm, *, objects: bool = True) -> Hits:
    """What the rays of photo points hit first: the terrain or, with ``objects``, a house, a crown, the canopy, ….

    Parameters
    ----------
    xy_mm : array_like (..., 2)
        Photo points, mm.
    objects : bool
        Cut the rays with the site's objects (when it has them); False: the DEM only.

    Returns
    -------
    Hits with arrays of shape (..., 3) and (...) — the rays of a rendered photo's
    pixel centres hit exactly what its pixels show.
    """
    xy = np.asarray(xy_mm, dtype=float)
    shape = xy.shape[:-1]
    flat = xy.reshape(-1, 2)
    G = g.photo_to_dem(camera, pose, flat, site)
    N = len(flat)
    objs = getattr(site, "objects", None) if objects else None
    if objs is None or N == 0:
        nrm = np.zeros((N, 3))
        nrm[:, 2] = 1.0
        return Hits(G.reshape(shape + (3,)), np.zeros(shape, np.uint8), np.full(shape, -1, np.int64),
                    nrm.reshape(shape + (3,)))
    S = pose.centre
    D = (G - S) / (S[2] - G[:, 2])[:, None]  # per unit depth: D_z = −1
    k, ray = box_point_pairs(objs.bbox, camera, pose, flat)
    h = first_hits(site, objs, S, -D[:, 0], -D[:, 1], S[2] - G[:, 2], k, ray, G[:, 0], G[:, 1])
    P = G.copy()
    P[h.idx] = S + h.u[:, None] * D[h.idx]
    nrm = np.zeros((N, 3))
    nrm[:, 2] = 1.0
    nrm[h.idx] = h.normal
    return Hits(P.reshape(shape + (3,)), h.surface.reshape(shape), h.object_id.astype(np.int64).reshape(shape),
                nrm.reshape(shape + (3,)))


@V.checked(site=V.has_attrs("level_for", "height", what="a Site (aerophoto.site.get_site())"),
           shot=V.has_attrs("camera", "pose", "number", what="a Shot (simulate.Strip.shots[i])"))
def render_shot(site, shot, n_px: int = 512, **kwargs) -> Photo:
    """Render a simulated :class:`aerophoto.simulate.Shot` (its true pose; its number is carried along)."""
    kwargs.setdefault("number", shot.number)
    return render(site, shot.camera, shot.pose, n_px, **kwargs)


@V.checked(site=V.has_attrs("level_for", "height", what="a Site (aerophoto.site.get_site())"),
           strip=V.has_attrs("shots", what="a simulated Strip or Block"))
def render_strip(site, strip, n_px: int = 512, **kwargs) -> list:
    """Render every shot of a strip (or a block's ``shots``), in order; a list of :class:`Photo`."""
    shots = strip.shots if hasattr(strip, "shots") else list(strip)
    return [render_shot(site, s, n_px, **kwargs) for s in shots]
