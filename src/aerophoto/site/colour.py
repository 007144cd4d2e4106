"""Colour and multispectral photos of the interpretation site through the book's one camera.

:func:`render_colour` photographs :class:`aerophoto.site.cover.InterpretationSite` in the six bands of
:data:`aerophoto.spectral.BANDS` under the shooting conditions of guide §9
(:class:`aerophoto.interpretation.Conditions`), in two steps:

1. **Geometry** (:func:`colour_geometry`, cached): :func:`aerophoto.render.render` of the site — the exact central
   projection, the canopy, haystacks and bog pines ray-cast — once per camera and pose, with the normals of the
   object pixels (:func:`aerophoto.render.trace`); then, per sun, the *illumination* as the renderer computes it:
   1 on level ground in full sun, crowns shaded by Lambert's law with the ambient 0.35
   (:func:`aerophoto.site.raycast.light_factor`), cast shadows (:func:`aerophoto.site.raycast.in_shadow`) down to
   0.35; level ground further shaded by the DEM's slope and exposure (the formula of
   :func:`aerophoto.interpretation.slope_illumination` on the DEM's normal).  A new sun costs only the shadows.
   The ground point of each pixel gives its land-cover class (:func:`aerophoto.site.texture.pixel_classes`:
   boundaries interpolated between texels, roads drawn from their centre lines), an object's pixel its object's
   class (a roof, a haystack; a wall, a canopy pixel its crown's stand), and the cover's texture there
   (:func:`aerophoto.site.texture.ground_texture`; a crown's own tone on canopy pixels).
2. **Colour** (:func:`colour_photo`, cheap): per pixel, the class's band reflectance in the season
   (:func:`aerophoto.spectral.cover_bands`; the soil of arable land per pixel from its humus and moisture through
   :class:`aerophoto.spectral.SoilBandTable`, its share moved by the texture's bare patches and wheel tracks) ×
   the texture × illumination; then the haze of the air below the camera (:func:`aerophoto.interpretation.haze`)
   and the image motion blur δ = W·t/m along the photo's x (:func:`aerophoto.interpretation.motion_blur`).
   No vignetting: level, lit ground of a class shows its reflectance (the texture's mean is 1).

A **window** of the frame (``window_mm``, :func:`aerophoto.render.render`) is the same photo through a magnifier:
the same rays, finer pixels, the texture filtered to the finer footprint.

The other chapters' greyscale photos do not pass through here and are unchanged.  Data only (layer 3).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from .. import _validate as V
from .. import geometry as g
from .. import interpretation as ip
from .. import spectral as sp
from .cover import CLASSES, CLASS_CODES, InterpretationSite

__all__ = ["ColourGeometry", "ColourPhoto", "colour_geometry", "colour_photo", "render_colour", "class_band_table",
           "GAIN", "GAMMA", "CAMERA_GAIN", "to_display", "vertical_pose"]

#: the display stretch of every composite: value = (gain·ρ*)^(1/γ), the same for all conditions (no auto-stretch)
GAIN = 2.6
GAMMA = 1.8
#: the gain of each camera's three layers (red, green, blue of the picture), where it differs from :data:`GAIN`: a
#: colour-infrared film's infrared layer is exposed for vegetation's bright near infrared (ρ ≈ 0.4), which at
#: :data:`GAIN` would clip to one flat pink and lose its texture
CAMERA_GAIN = {"colour-infrared film": (1.8, GAIN, GAIN)}


@dataclass(frozen=True, eq=False)
class ColourGeometry:
    """What a photo sees, before colour: the :class:`aerophoto.render.Photo`, illumination, classes, soil per pixel."""

    photo: object
    illumination: np.ndarray  # (n, n) float32
    classes: np.ndarray  # (n, n) uint8
    humus_pct: np.ndarray
    moisture_pct: np.ndarray
    texture: np.ndarray  # (n, n) float32: the cover's texture, mean 1 per class (site.texture)
    H_m: float  # height of the camera above the mean ground, m
    shadow: np.ndarray  # (n, n) bool: in an object's or the canopy's cast shadow
    sun_elevation_deg: float
    sun_azimuth_deg: float
    soil_shift: np.ndarray | None = None  # (n, n) float32: bare soil's share moved (mean 0), or None
    footprint_m: float = 0.0  # a pixel's size on the ground, m


@dataclass(frozen=True, eq=False)
class ColourPhoto:
    """A multispectral photo: ``bands`` (n, n, 6) float32 apparent reflectance, :data:`aerophoto.spectral.BAND_NAMES`."""

    bands: np.ndarray
    geometry: ColourGeometry
    conditions: ip.Conditions
    blur_mm: float

    @property
    def photo(self):
        return self.geometry.photo

    @property
    def classes(self) -> np.ndarray:
        return self.geometry.classes

    def band(self, name: str) -> np.ndarray:
        """One band (n, n), apparent reflectance 0…1."""
        if name not in sp.BANDS:
            raise ValueError(f"band = {name!r} is not one of the bands {list(sp.BANDS)}")
        return self.bands[..., sp.BAND_NAMES.index(name)]

    def composite(self, camera: str = "colour film") -> np.ndarray:
        """An RGB image (n, n, 3) 0…1 of three bands (:data:`aerophoto.spectral.CAMERAS`), fixed stretch."""
        if camera not in sp.CAMERAS:
            raise ValueError(f"camera = {camera!r} is not one of {list(sp.CAMERAS)}")
        idx = [sp.BAND_NAMES.index(b) for b in sp.CAMERAS[camera]]
        return to_display(self.bands[..., idx], camera)

    def natural_colour(self) -> np.ndarray:
        return self.composite("colour film")

    def colour_infrared(self) -> np.ndarray:
        return self.composite("colour-infrared film")

    def panchromatic(self) -> np.ndarray:
        """A black-and-white (panchromatic, 0.5–0.9 µm) photo: the mean of green, red and near infrared."""
        i = [sp.BAND_NAMES.index(b) for b in ("green", "red", "nir")]
        return self.bands[..., i].mean(axis=-1)


@V.checked(rho=V.image(2, 3))
def to_display(rho, camera: str | None = None) -> np.ndarray:
    """Reflectance → display value: (gain·ρ)^(1/GAMMA), clipped to 0…1 (float32); the gain :data:`GAIN`, or per
    layer the ``camera``'s (:data:`CAMERA_GAIN`) for a composite (…, 3)."""
    rho = np.asarray(rho, np.float32)
    gain = CAMERA_GAIN.get(camera) if rho.ndim == 3 and rho.shape[-1] == 3 else None
    k = np.asarray(gain, np.float32) if gain is not None else np.float32(GAIN)
    a = np.clip(rho * k, 0.0, 1.0)
    return np.power(a, np.float32(1.0 / GAMMA))


# =========================================================================== geometry
def _dem_normals(site):
    s = site.dem_spacing_m
    gy, gx = np.gradient(site.dem, s)
    return gx, gy


@functools.lru_cache(maxsize=8)
def _base(isite: InterpretationSite, camera: g.Camera, pose: g.Pose, n_px: int, objects: bool,
          window: tuple | None = None) -> tuple:
    """What does not depend on the sun: the render (no sun) with the surface normals of the object pixels, and
    each pixel's class and texture (see the module notes)."""
    from ..render import render
    from .texture import ground_texture, pixel_classes

    site = isite.site
    photo = render(site, camera, pose, n_px, vignetting=0.0, fiducials=False, level=0, keep_ground=True,
                   objects=objects, sun=None, background=0.0, window_mm=window, keep_normals=True)
    obj_pix = np.flatnonzero(photo.surface.ravel() != 0) if photo.surface is not None else np.zeros(0, np.int64)
    normals = photo.normal.reshape(-1, 3)[obj_pix].astype(float)
    Xg, Yg = photo.ground_m[..., 0], photo.ground_m[..., 1]
    cls, lines = pixel_classes(isite, Xg, Yg)
    cls = cls.ravel()
    H = float(pose.Z_m - site.mean_height_m)
    footprint = photo.pixel_mm * H / camera.f_mm
    gain, soil = ground_texture(isite, cls, Xg.ravel(), Yg.ravel(), footprint, lines)
    tone = np.ones(len(obj_pix), np.float32)
    if len(obj_pix):  # what an object's pixel shows: its object's class, a wall, a crown's stand and tone
        surf = photo.surface.ravel()[obj_pix]
        oid = photo.object_id.ravel()[obj_pix]
        oc = isite.features["object_class"]
        own = oid >= 0
        cls[obj_pix[own]] = oc[oid[own]]
        cls[obj_pix[surf == 2]] = CLASS_CODES["wall"]
        can = np.flatnonzero(surf == 4)
        crowns = isite.crowns
        if len(can) and crowns is not None:
            from .crowns import DEPTH_M

            xc, yc = Xg.ravel()[obj_pix[can]], Yg.ravel()[obj_pix[can]]
            k, _, _ = crowns.lookup(xc, yc)
            got = k >= 0
            cls[obj_pix[can[got]]] = crowns.cls[k[got]]
            # the crown's own tone, and the foliage deeper in the canopy in its neighbours' shade
            depth = crowns.surface_depth(xc, yc, photo.ground_m[..., 2].ravel()[obj_pix[can]] - site.height(xc, yc))
            tone[can] = np.where(got, crowns.tone[np.maximum(k, 0)], 1.0) * np.exp(-depth / DEPTH_M)
        gain[obj_pix] = tone * np.where(surf == 2, 1.0, gain[obj_pix])
        soil[obj_pix] = 0.0
    cls = cls.reshape(n_px, n_px)
    cls[~photo.valid] = 0
    for a in (cls, gain, soil, normals):
        a.flags.writeable = False
    return photo, obj_pix, normals, cls, gain.reshape(n_px, n_px), soil.reshape(n_px, n_px), footprint


@functools.lru_cache(maxsize=24)
def _geometry(isite: InterpretationSite, camera: g.Camera, pose: g.Pose, n_px: int, sun_el: float, sun_az: float,
              objects: bool, relief_shading: bool, window: tuple | None = None) -> ColourGeometry:
    from scipy.ndimage import map_coordinates

    from ..render import Sun
    from .raycast import AMBIENT, in_shadow, light_factor

    site = isite.site
    photo, obj_pix, normals, cls, gain, soil, footprint = _base(isite, camera, pose, n_px, objects, window)
    sun = Sun(sun_az % 360.0, sun_el)
    L = sun.direction
    n = n_px
    illum = np.ones(n * n, np.float32)
    Xg = photo.ground_m[..., 0]
    Yg = photo.ground_m[..., 1]
    if len(obj_pix):  # crowns, haystacks, bog pines: Lambert with the renderer's ambient (as render does)
        illum[obj_pix] = light_factor(normals, L)
    if relief_shading:  # level ground: the DEM's slope and exposure
        gx, gy = _dem_normals(site)
        s = site.dem_spacing_m
        crd = [Yg.ravel() / s, Xg.ravel() / s]
        zx = map_coordinates(gx, crd, order=1, mode="nearest")
        zy = map_coordinates(gy, crd, order=1, mode="nearest")
        cos = np.clip((-zx * L[0] - zy * L[1] + L[2]) / np.sqrt(zx * zx + zy * zy + 1.0), 0.0, None)
        ground = np.ones(n * n, bool)
        ground[obj_pix] = False
        illum[ground] *= (ip.AMBIENT + (1.0 - ip.AMBIENT) * cos[ground] / max(L[2], 1e-6)).astype(np.float32)
    shadow = np.zeros(n * n, bool)
    if objects and site.objects is not None:  # cast shadows: down to the ambient light
        Zg = photo.ground_m[..., 2].ravel()
        shadow = in_shadow(site.objects, site, Xg.ravel(), Yg.ravel(), Zg, photo.object_id.ravel().astype(np.int64),
                           L, camera, pose, n, photo.raster)
        illum[shadow] = np.float32(AMBIENT)
    illum = illum.reshape(n, n)
    illum[~photo.valid] = 0.0
    t = isite.texel_m
    crd = [Yg.ravel() / t - 0.5, Xg.ravel() / t - 0.5]  # the soil's humus and moisture between texels
    humus = map_coordinates(isite.humus_pct, crd, order=1, mode="nearest").reshape(n, n).astype(np.float32)
    moist = map_coordinates(isite.moisture_pct, crd, order=1, mode="nearest").reshape(n, n).astype(np.float32)
    H = float(pose.Z_m - site.mean_height_m)
    shadow = shadow.reshape(n, n)
    for a in (illum, shadow, humus, moist):
        a.flags.writeable = False
    return ColourGeometry(photo=photo, illumination=illum, classes=cls, humus_pct=humus, moisture_pct=moist,
                          texture=gain, H_m=H, shadow=shadow, sun_elevation_deg=float(sun_el),
                          sun_azimuth_deg=float(sun_az), soil_shift=soil, footprint_m=float(footprint))


def colour_geometry(isite: InterpretationSite, camera: g.Camera, pose: g.Pose, n_px: int = 512, *,
                    sun_elevation_deg: float = 45.0, sun_azimuth_deg: float = 150.0, objects: bool = True,
                    relief_shading: bool = True, window_mm: tuple | None = None) -> ColourGeometry:
    """The geometry step (cached for the last 24 calls): see the module notes.

    ``window_mm`` ``(x, y, side)``: only that square of the frame, ``n_px`` pixels across it (a magnifier's view;
    :func:`aerophoto.render.render`).
    """
    if not isinstance(isite, InterpretationSite):
        raise ValueError(f"isite = {isite!r} must be an InterpretationSite (aerophoto.site.cover.interpretation_site)")
    ip.Conditions(sun_elevation_deg=sun_elevation_deg, sun_azimuth_deg=sun_azimuth_deg)  # validates
    window = None if window_mm is None else tuple(float(a) for a in np.asarray(window_mm, float).ravel())
    return _geometry(isite, camera, pose, int(n_px), float(sun_elevation_deg), float(sun_azimuth_deg), bool(objects),
                     bool(relief_shading), window)


# =========================================================================== colour
_WET = ("wet meadow", "low bog", "raised bog")


@functools.lru_cache(maxsize=8)
def class_band_table(season: str) -> tuple:
    """(fixed (K+1, 6), soil share (K+1,)): each class's band values without its soil, and its soil fraction."""
    fixed = np.zeros((len(CLASSES) + 1, len(sp.BAND_NAMES)), np.float32)
    soil = np.zeros(len(CLASSES) + 1, np.float32)
    for name in CLASSES:
        k = CLASS_CODES[name]
        mix = sp.mixture(name, season)
        soil[k] = mix.pop("soil", 0.0)
        for member, f in mix.items():
            fixed[k] += f * np.asarray(sp.ENDMEMBERS[member][2], np.float32)
    fixed.flags.writeable = False
    soil.flags.writeable = False
    return fixed, soil


def colour_photo(geom: ColourGeometry, conditions: ip.Conditions | None = None) -> ColourPhoto:
    """The colour step: reflectance × grain × illumination, then haze and image motion (see the module notes)."""
    cond = conditions or ip.Conditions()
    fixed, soil_share = class_band_table(cond.season)
    cls = geom.classes
    refl = fixed[cls]  # (n, n, 6)
    fs = soil_share[cls]
    has_soil = fs > 0
    if has_soil.any():
        theta = geom.moisture_pct[has_soil] + sp.SEASON_MOISTURE_PCT[cond.season] + cond.moisture_pct
        sb = sp.soil_band_table().bands(theta, geom.humus_pct[has_soil], 0.1, sp.PARENTS["loam"])
        share = fs[has_soil]
        if geom.soil_shift is not None:  # bare patches and wheel tracks: more soil, less of the rest (mean 0)
            d = np.clip(geom.soil_shift[has_soil], -share, 1.0 - share)
            keep = np.where(share < 1.0, (1.0 - share - d) / np.maximum(1.0 - share, 1e-6), 1.0)
            refl[has_soil] *= keep[:, None]
            share = share + d
        refl[has_soil] += share[:, None] * sb
    if cond.moisture_pct > 0:  # standing water on wet meadows and bogs
        w = np.float32(min(cond.moisture_pct / 100.0, 0.3))
        water = np.asarray(sp.ENDMEMBERS["shallow water"][2], np.float32)
        wet = np.isin(cls, [CLASS_CODES[c] for c in _WET])
        refl[wet] = (1 - w) * refl[wet] + w * water
    refl *= (geom.texture * geom.illumination)[..., None]
    if cond.visibility_km is not None:
        for k, b in enumerate(sp.BAND_NAMES):
            refl[..., k] = ip.haze(refl[..., k], b, cond.visibility_km, geom.H_m)
    photo = geom.photo
    m = geom.H_m / (photo.camera.f_mm / 1000.0)
    blur_mm = float(ip.image_motion_mm(cond.speed_kmh, cond.exposure_ms, m))
    refl = ip.motion_blur(refl, min(blur_mm / photo.pixel_mm, 200.0), axis=1)
    refl = np.clip(refl, 0.0, 1.0).astype(np.float32)
    return ColourPhoto(bands=refl, geometry=geom, conditions=cond, blur_mm=blur_mm)


def render_colour(isite: InterpretationSite, camera: g.Camera, pose: g.Pose, n_px: int = 512,
                  conditions: ip.Conditions | None = None, *, objects: bool = True,
                  relief_shading: bool = True, window_mm: tuple | None = None) -> ColourPhoto:
    """A multispectral photo of the interpretation site under ``conditions`` (or a window of it, ``window_mm``).

    The tilt α of ``conditions`` (§9, condition 6), when not 0, replaces the pose's; otherwise the pose's stands.
    """
    cond = conditions or ip.Conditions()
    if cond.alpha_deg:
        pose = pose.with_(alpha_deg=cond.alpha_deg)
    geom = colour_geometry(isite, camera, pose, n_px, sun_elevation_deg=cond.sun_elevation_deg,
                           sun_azimuth_deg=cond.sun_azimuth_deg, objects=objects, relief_shading=relief_shading,
                           window_mm=window_mm)
    return colour_photo(geom, cond)


def vertical_pose(isite: InterpretationSite, X_m: float, Y_m: float, m: float, f_mm: float = 100.0, *,
                  alpha_deg: float = 0.0, lambda_deg: float = 0.0, kappa_deg: float = 0.0) -> g.Pose:
    """A pose over (X, Y) for scale 1:m above the site's mean ground (H = f·m), with tilt α and swing κ."""
    H = g.flying_height_m(f_mm, m)
    return g.Pose(X_m, Y_m, isite.site.mean_height_m + H, alpha_deg, lambda_deg, kappa_deg)

