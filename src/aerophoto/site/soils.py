"""The site's soil cover (почвенный покров): a soil map tied to the relief, with moisture, humus and particle size.

Guide §14 says soils follow the relief — the steepness of a slope, its exposure (экспозиция, the way it faces)
and the hollows and rises of flat ground — and that the vegetation and the floodplain are indicators of them
(the indirect keys, косвенные дешифровочные признаки).  This module lays a soil cover on the virtual site by
exactly those keys, so that a soil map can be "surveyed" (it is the truth) and photographed (through
:mod:`aerophoto.spectral`).  Layer 3: data only.

The soil classes (:data:`SOIL_CLASSES`, code → :class:`SoilClass`)
----------------------------------------------------------------
The site is a forest-steppe landscape like the guide's Penza region:

====  =====================================  ==========================================  ======================
code  class                                  where (the rule, in order of precedence)    topsoil (typical)
====  =====================================  ==========================================  ======================
0     leached chernozem                      everything else: flat and gentle            humus 7.5 %, crumbs
      (чернозём выщелоченный)                interfluves                                 of ~1 mm, θ ≈ 18 %
1     grey forest soil (серая лесная почва)  under the forest, and on the high hills     humus 3.5 %, θ ≈ 16 %
                                             north of the river
2     eroded slope soil                      slopes steeper than 1° (0.8° facing south,  humus 2–4 %, fine
      (смытая почва склонов)                 1.2° facing north: sunward slopes dry out   crust ~0.15 mm,
                                             and wash more)                              θ ≈ 12 %
3     alluvial meadow soil                   the floodplain: meadow, water and sand      humus 5 %, silt
      (аллювиальная луговая почва)           within 450 m of the river                   ~0.08 mm, θ ≈ 28 %
4     gleyed and bog soil                    closed hollows deeper than 3 % of the       humus 12 % (peaty),
      (глеевая и болотная почва)             relief below their surroundings             θ ≈ 38 %
====  =====================================  ==========================================  ======================

The numbers are the book's choices, typical of these soils in the Russian forest-steppe, not measurements;
the rules are §14's indirect keys.  Within a class the fields vary smoothly (seeded value noise of 150 m and
60 m cells) and with the relief: moisture rises in hollows (+0.8 % of θ per 1 % of relief of hollow depth) and
falls on sunward slopes; humus falls with the steepness of an eroded slope.

Grid
----
A :class:`SoilLayer` covers ``extent_m = (X0, X1, Y0, Y1)`` with square cells ``spacing_m`` wide; cell
(r, c) has its centre at X = X0 + (c + ½)·s, Y = Y0 + (r + ½)·s (row 0 at the south edge, as the site's
texture: show it with ``imshow(origin="lower")``).  Every field is a function of the position only (the noise
lives on a lattice fixed to the site), so two layers over overlapping extents agree where they overlap.  The
land cover that places the forest and floodplain soils is read with roads, field boundaries, shelter belts,
houses and single trees replaced by the nearest natural cover (looked for up to 60 m beyond the extent).

Public API
----------
``soil_layer(site=None, *, extent_m=None, spacing_m=None, seed=0) -> SoilLayer`` (cached),
``SOIL_CLASSES``, ``SOIL_NAMES``, :class:`SoilClass`, :class:`SoilLayer` (``code``, ``moisture_pct``,
``humus_pct``, ``particle_mm``, ``slope_deg``, ``aspect_deg``, ``hollow_m``, ``X_m``, ``Y_m``, ``bands(...)``,
``composite(...)``, ``class_at(X, Y)``, ``at(X, Y)``, ``shares()``, ``table()``).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import _validate as V
from .. import spectral
from .._validate import check_int_range, check_range

__all__ = ["SoilClass", "SOIL_CLASSES", "SOIL_NAMES", "SoilLayer", "soil_layer", "ERODED_SLOPE_DEG",
           "HOLLOW_SHARE", "FLOODPLAIN_M", "RELIEF_SHEET", "COVER_SHEET", "key_sheets"]


@dataclass(frozen=True)
class SoilClass:
    """A soil class of the site: its names, parent material and the typical topsoil (the book's choices).

    ``moisture_pct`` (volumetric θ, %), ``humus_pct`` (%), ``particle_mm`` (aggregate/particle diameter d, mm),
    ``parent`` (one of :data:`aerophoto.spectral.PARENTS`), ``where``: the relief key that places it.
    """

    code: int
    name: str
    ru: str
    moisture_pct: float
    humus_pct: float
    particle_mm: float
    parent: str
    where: str
    colour: str


#: the soil classes, code → class
SOIL_CLASSES = {
    0: SoilClass(0, "leached chernozem", "чернозём выщелоченный", 18.0, 7.5, 1.0, "loam",
                 "flat and gentle interfluves", "#3b2f2f"),
    1: SoilClass(1, "grey forest soil", "серая лесная почва", 16.0, 3.5, 0.4, "loam",
                 "under forest; high hills north of the river", "#8c8c8c"),
    2: SoilClass(2, "eroded slope soil", "смытая почва склонов", 12.0, 3.0, 0.15, "loam",
                 "slopes over 1° (0.8° facing south, 1.2° facing north)", "#E69F00"),
    3: SoilClass(3, "alluvial meadow soil", "аллювиальная луговая почва", 28.0, 5.0, 0.08, "loam",
                 "the floodplain", "#56B4E9"),
    4: SoilClass(4, "gleyed and bog soil", "глеевая и болотная почва", 38.0, 12.0, 0.25, "loam",
                 "closed hollows", "#0072B2"),
}
SOIL_NAMES = tuple(c.name for c in SOIL_CLASSES.values())

#: an arable slope steeper than this (°) carries eroded soil; ±0.2° by exposure (the book's choice)
ERODED_SLOPE_DEG = 1.0
#: a hollow deeper than this share of the site's relief below its surroundings holds gleyed soil
HOLLOW_SHARE = 0.03
#: the floodplain's soils reach this far from the river's centre line at most, m
FLOODPLAIN_M = 450.0
_HOLLOW_SIGMA_M = 200.0  # the "surroundings" of a point: the DEM smoothed with this Gaussian σ
_NOISE_CELLS_M = (150.0, 60.0)


@dataclass(frozen=True, eq=False, repr=False)
class SoilLayer:
    """The soil cover on a grid (see the module notes).  Arrays have shape (ny, nx), row 0 at the south edge.

    Attributes
    ----------
    extent_m : (X0, X1, Y0, Y1), metres
    spacing_m : cell size s, metres
    code : uint8, the soil class (:data:`SOIL_CLASSES`)
    moisture_pct : float32, volumetric moisture θ of the topsoil, % (3…55)
    humus_pct : float32, humus H, % (0.8…18)
    particle_mm : float32, particle (aggregate) diameter d, mm (0.03…3)
    slope_deg, aspect_deg : float32, the ground's steepness, ° and the way it faces, ° clockwise from north
    hollow_m : float32, how far the ground lies below its surroundings, m (negative on rises)
    seed : the seed of the within-class variation
    """

    extent_m: tuple
    spacing_m: float
    code: np.ndarray
    moisture_pct: np.ndarray
    humus_pct: np.ndarray
    particle_mm: np.ndarray
    slope_deg: np.ndarray
    aspect_deg: np.ndarray
    hollow_m: np.ndarray
    seed: int = 0

    def __repr__(self) -> str:
        ny, nx = self.shape
        X0, X1, Y0, Y1 = self.extent_m
        return f"SoilLayer({nx}×{ny} cells of {self.spacing_m:g} m over X {X0:g}…{X1:g}, Y {Y0:g}…{Y1:g} m)"

    @property
    def shape(self) -> tuple:
        return self.code.shape

    @property
    def classes(self) -> dict:
        """The class table (:data:`SOIL_CLASSES`)."""
        return SOIL_CLASSES

    @property
    def X_m(self) -> np.ndarray:
        """(nx,) X of the cell centres, m."""
        return self.extent_m[0] + (np.arange(self.shape[1]) + 0.5) * self.spacing_m

    @property
    def Y_m(self) -> np.ndarray:
        """(ny,) Y of the cell centres, m."""
        return self.extent_m[2] + (np.arange(self.shape[0]) + 0.5) * self.spacing_m

    def class_at(self, X, Y) -> np.ndarray:
        """The soil class code of the cell holding each point (X, Y, m; broadcast); points off the layer → 255."""
        X, Y = np.broadcast_arrays(np.asarray(X, float), np.asarray(Y, float))
        c = np.floor((X - self.extent_m[0]) / self.spacing_m).astype(np.int64)
        r = np.floor((Y - self.extent_m[2]) / self.spacing_m).astype(np.int64)
        ny, nx = self.shape
        ok = (c >= 0) & (c < nx) & (r >= 0) & (r < ny)
        out = np.full(X.shape, 255, np.uint8)
        out[ok] = self.code[r[ok], c[ok]]
        return out

    def at(self, X, Y) -> dict:
        """The fields at points (X, Y, m; broadcast) from the cells holding them (nearest cell; points off the layer
        take the nearest edge cell): ``code``, ``moisture_pct``, ``humus_pct``, ``particle_mm``, ``parent_peak``
        (ρ_p of :data:`aerophoto.spectral.PARENTS`) — the keywords of
        :meth:`aerophoto.spectral.SoilBandTable.bands` for a renderer that samples the soil itself."""
        X, Y = np.broadcast_arrays(np.asarray(X, float), np.asarray(Y, float))
        ny, nx = self.shape
        c = np.clip(np.floor((X - self.extent_m[0]) / self.spacing_m).astype(np.int64), 0, nx - 1)
        r = np.clip(np.floor((Y - self.extent_m[2]) / self.spacing_m).astype(np.int64), 0, ny - 1)
        code = self.code[r, c]
        peak = np.array([spectral.PARENTS[k.parent] for k in SOIL_CLASSES.values()], np.float32)[code]
        return {"code": code, "moisture_pct": self.moisture_pct[r, c], "humus_pct": self.humus_pct[r, c],
                "particle_mm": self.particle_mm[r, c], "parent_peak": peak}

    def bands(self, bands=spectral.BAND_NAMES, *, moisture_shift_pct: float = 0.0, humus_scale: float = 1.0,
              particle_scale: float = 1.0, roughness: float = 0.0, sun_elevation_deg: float = 45.0) -> np.ndarray:
        """Reflectance of the bare soil in ``bands`` (names of :data:`aerophoto.spectral.BANDS`): (ny, nx, k) float32.

        The soil model of guide §14 (:func:`aerophoto.spectral.soil_reflectance`, tabulated exactly by
        :func:`aerophoto.spectral.soil_band_table`) for every cell's θ, H, d and parent material.  The fields can
        be changed as a whole, as a different day would change them: ``moisture_shift_pct`` is added to θ
        (−40…+40 %, the result kept in 0…60 %), humus and particle size are multiplied by ``humus_scale`` (0…5)
        and ``particle_scale`` (0.01…5); ``roughness`` (clods, 0…0.3) and the sun's elevation (1…90°) as in
        :func:`aerophoto.spectral.clod_factor`.
        """
        names = (bands,) if isinstance(bands, str) else tuple(bands)
        idx = [spectral._band_index(b) for b in names]
        check_range("moisture_shift_pct", moisture_shift_pct, -40.0, 40.0, unit="%")
        check_range("humus_scale", humus_scale, 0.0, 5.0)
        check_range("particle_scale", particle_scale, 0.01, 5.0)
        check_range("roughness", roughness, 0.0, 0.3)
        check_range("sun_elevation_deg", sun_elevation_deg, 1.0, 90.0, unit="°")
        th = np.clip(self.moisture_pct + np.float32(moisture_shift_pct), 0.0, 60.0)
        H = np.clip(self.humus_pct * np.float32(humus_scale), 0.0, 100.0)
        d = np.clip(self.particle_mm * np.float32(particle_scale), 1e-3, 20.0)
        peak = np.array([spectral.PARENTS[c.parent] for c in SOIL_CLASSES.values()], np.float32)[self.code]
        return spectral.soil_band_table().bands(th, H, d, peak, roughness, sun_elevation_deg,
                                                band_index=idx).astype(np.float32)

    def composite(self, camera: str = "colour-infrared film", *, lo: float = 0.0, hi: float | None = None,
                  **conditions) -> np.ndarray:
        """A band composite (ny, nx, 3) in 0…1: the camera's bands (:data:`aerophoto.spectral.CAMERAS`) as red,
        green, blue, each stretched linearly from ``lo`` to ``hi`` (None: the largest value of the three bands
        under the default conditions, so a darker day looks darker).  ``conditions``: as :meth:`bands`.
        """
        if camera not in spectral.CAMERAS:
            raise ValueError(f"camera = {camera!r} is not one of the cameras {list(spectral.CAMERAS)}")
        rgb = self.bands(spectral.CAMERAS[camera], **conditions)
        if hi is None:
            hi = float(self.bands(spectral.CAMERAS[camera]).max()) if conditions else float(rgb.max())
        return np.clip((rgb - np.float32(lo)) / np.float32(max(hi - lo, 1e-6)), 0.0, 1.0)

    def shares(self) -> dict:
        """The share of each class's cells, % (classes absent from the layer included with 0)."""
        n = self.code.size
        return {k: 100.0 * np.count_nonzero(self.code == k) / n for k in SOIL_CLASSES}

    def table(self) -> pd.DataFrame:
        """Per class: Russian name, share of the area (%), mean θ (%), humus (%) and particle size (mm)."""
        rows = []
        for k, c in SOIL_CLASSES.items():
            m = self.code == k
            mean = (lambda a: float(a[m].mean()) if m.any() else float("nan"))  # noqa: E731
            rows.append((c.name, c.ru, 100.0 * m.mean(), mean(self.moisture_pct), mean(self.humus_pct),
                         mean(self.particle_mm), c.where))
        return pd.DataFrame(rows, columns=["soil", "почва", "area, %", "θ, %", "humus, %", "d, mm", "where"]
                            ).set_index("soil")


# --------------------------------------------------------------------------- building
def _noise(site, seed: int, k: int, X: np.ndarray, Y: np.ndarray) -> np.ndarray:
    """Value noise of about unit standard deviation fixed to the site (lattice of cell ``_NOISE_CELLS_M[k]``)."""
    from scipy.ndimage import map_coordinates

    cell = _NOISE_CELLS_M[k]
    W, Hs = site.params.width_m, site.params.height_m
    rng = np.random.default_rng([int(site.params.seed), int(seed), 14, k])
    lat = rng.standard_normal((int(Hs / cell) + 4, int(W / cell) + 4))
    return map_coordinates(lat, [Y / cell + 1.0, X / cell + 1.0], order=3, mode="nearest")


@functools.lru_cache(maxsize=2)
def _relief_fields(site) -> tuple:
    """(slope °, aspect °, hollow m) on the site's DEM nodes."""
    from scipy.ndimage import gaussian_filter

    s = site.dem_spacing_m
    dzdy, dzdx = np.gradient(site.dem, s)
    slope = np.degrees(np.arctan(np.hypot(dzdx, dzdy)))
    aspect = np.degrees(np.arctan2(-dzdx, -dzdy)) % 360.0  # the downhill direction, clockwise from north
    hollow = gaussian_filter(site.dem, _HOLLOW_SIGMA_M / s, mode="nearest") - site.dem
    return slope, aspect, hollow


_NATURAL = ("arable field", "meadow", "forest", "water", "sand bank")  # covers that tell the soil
_PAD_M = 60.0


def _ground_cover(site, xs: np.ndarray, ys: np.ndarray, spacing_m: float) -> np.ndarray:
    """The land cover at the cells, roads, field boundaries, shelter belts, houses, gardens and single trees
    replaced by the nearest natural cover (narrow features laid over the soil, not soil boundaries)."""
    from scipy.ndimage import distance_transform_edt, uniform_filter

    from .model import COVER_CODES

    pad = int(math.ceil(_PAD_M / spacing_m))
    xe = np.concatenate([xs[0] - spacing_m * np.arange(pad, 0, -1), xs, xs[-1] + spacing_m * np.arange(1, pad + 1)])
    ye = np.concatenate([ys[0] - spacing_m * np.arange(pad, 0, -1), ys, ys[-1] + spacing_m * np.arange(1, pad + 1)])
    W, Hs = site.params.width_m, site.params.height_m
    Xe, Ye = np.meshgrid(np.clip(xe, 0.0, W), np.clip(ye, 0.0, Hs))
    cov = site.cover_at(Xe, Ye)
    natural = np.isin(cov, [COVER_CODES[c] for c in _NATURAL])
    # shelter belts (лесополосы) are planted, not soil keys: forest narrower than ~50 m is no forest here
    forest = cov == COVER_CODES["forest"]
    wide = uniform_filter(forest.astype(np.float32), size=max(int(round(50.0 / spacing_m)), 1)) > 0.5
    natural &= ~forest | wide
    if not natural.any():
        out = np.full(cov.shape, COVER_CODES["arable field"], np.uint8)
    else:
        idx = distance_transform_edt(~natural, return_distances=False, return_indices=True)
        out = cov[idx[0], idx[1]]
    return out[pad:pad + len(ys), pad:pad + len(xs)]


def _build(site, extent_m: tuple, spacing_m: float, seed: int) -> SoilLayer:
    from scipy.ndimage import map_coordinates

    from .model import COVER_CODES

    X0, X1, Y0, Y1 = extent_m
    nx = max(int(round((X1 - X0) / spacing_m)), 1)
    ny = max(int(round((Y1 - Y0) / spacing_m)), 1)
    xs = X0 + (np.arange(nx) + 0.5) * spacing_m
    ys = Y0 + (np.arange(ny) + 0.5) * spacing_m
    X, Y = np.meshgrid(xs, ys)
    s = site.dem_spacing_m
    slope_n, aspect_n, hollow_n = _relief_fields(site)
    at = [Y.ravel() / s, X.ravel() / s]
    slope = map_coordinates(slope_n, at, order=1, mode="nearest").reshape(X.shape)
    ax = map_coordinates(np.sin(np.radians(aspect_n)), at, order=1, mode="nearest").reshape(X.shape)
    ay = map_coordinates(np.cos(np.radians(aspect_n)), at, order=1, mode="nearest").reshape(X.shape)
    aspect = np.degrees(np.arctan2(ax, ay)) % 360.0
    hollow = map_coordinates(hollow_n, at, order=1, mode="nearest").reshape(X.shape)
    Z = site.height(X, Y)
    relief = max(site.z_max_m - site.z_min_m, 1e-9)
    z_rel = (Z - site.z_min_m) / relief
    n1, n2 = _noise(site, seed, 0, X, Y), _noise(site, seed, 1, X, Y)
    river = site.features["river"]
    d_river = np.abs(Y - np.interp(X, river[:, 0], river[:, 1]))
    north = Y > np.interp(X, river[:, 0], river[:, 1])
    cover = _ground_cover(site, xs, ys, spacing_m)
    south_facing = np.cos(np.radians(aspect - 180.0))  # +1 facing south, −1 facing north

    code = np.zeros(X.shape, np.uint8)  # chernozem unless a key says otherwise
    forest = (cover == COVER_CODES["forest"]) | (north & (z_rel + 0.08 * n1 > 0.62))
    code[forest] = 1
    eroded = (slope > ERODED_SLOPE_DEG - 0.2 * south_facing + 0.08 * n2) & (cover != COVER_CODES["forest"])
    code[eroded] = 2
    gley = hollow > HOLLOW_SHARE * relief * (1.0 + 0.25 * n2) if site.z_max_m > site.z_min_m else np.zeros_like(eroded)
    code[gley] = 4
    wet_cover = np.isin(cover, [COVER_CODES["meadow"], COVER_CODES["water"], COVER_CODES["sand bank"]])
    code[(wet_cover & (d_river < FLOODPLAIN_M)) | (d_river < 60.0)] = 3

    base = {k: np.array([getattr(c, k) for c in SOIL_CLASSES.values()]) for k in
            ("moisture_pct", "humus_pct", "particle_mm")}
    hollow_pct = 100.0 * hollow / relief
    sun_dry = south_facing * np.clip(slope / 1.5, 0.0, 1.0)
    theta = base["moisture_pct"][code] + 0.8 * hollow_pct - 2.5 * sun_dry + 2.0 * n1 + 1.0 * n2
    steep = np.clip((slope - ERODED_SLOPE_DEG) / 1.0, 0.0, 1.0)
    humus = base["humus_pct"][code] * (1.0 + 0.12 * n1 + 0.05 * n2) - np.where(code == 2, 1.5 * steep, 0.0)
    particle = base["particle_mm"][code] * np.exp(0.2 * n2)

    def f32(a, lo, hi):
        out = np.clip(a, lo, hi).astype(np.float32)
        out.flags.writeable = False
        return out

    code.flags.writeable = False
    return SoilLayer(tuple(float(e) for e in extent_m), float(spacing_m), code, f32(theta, 3.0, 55.0),
                     f32(humus, 0.8, 18.0), f32(particle, 0.03, 3.0), f32(slope, 0, 90), f32(aspect, 0, 360),
                     f32(hollow, -1e6, 1e6), int(seed))


@functools.lru_cache(maxsize=8)
def _cached(site, extent_m: tuple, spacing_m: float, seed: int) -> SoilLayer:
    return _build(site, extent_m, spacing_m, seed)


@V.checked(site=V.optional(V.has_attrs("params", "dem", what="a Site (site.get_site())")))
def soil_layer(site=None, *, extent_m=None, spacing_m: float | None = None, seed: int = 0) -> SoilLayer:
    """The soil cover of ``site`` (default: :func:`aerophoto.site.get_site`) over ``extent_m`` (cached).

    Parameters
    ----------
    site : :class:`aerophoto.site.Site` or None
    extent_m : (X0, X1, Y0, Y1) in metres within the site, or None for the whole site
    spacing_m : cell size, m, 0.5…200 (None: the site's DEM spacing); at most 4 million cells
    seed : the within-class variation's seed, 0 ≤ seed < 2**32 (the classes follow the relief, not the seed,
        except near their borders)
    """
    if site is None:
        from . import get_site

        site = get_site()
    W, Hs = site.params.width_m, site.params.height_m
    if extent_m is None:
        extent_m = (0.0, W, 0.0, Hs)
    try:
        X0, X1, Y0, Y1 = (float(e) for e in extent_m)
    except (TypeError, ValueError):
        raise ValueError(f"extent_m = {extent_m!r} must be (X0, X1, Y0, Y1) in metres") from None
    X0 = check_range("extent_m[0]", X0, 0.0, W, unit="m")
    X1 = check_range("extent_m[1]", X1, X0, W, lo_open=True, unit="m")
    Y0 = check_range("extent_m[2]", Y0, 0.0, Hs, unit="m")
    Y1 = check_range("extent_m[3]", Y1, Y0, Hs, lo_open=True, unit="m")
    s = site.dem_spacing_m if spacing_m is None else check_range("spacing_m", spacing_m, 0.5, 200.0, unit="m")
    cells = math.ceil((X1 - X0) / s) * math.ceil((Y1 - Y0) / s)
    if cells > 4_000_000:
        raise ValueError(f"spacing_m = {s:g} gives {cells} cells over this extent; the valid range is at most "
                         f"4 000 000 cells (spacing_m ≥ {math.sqrt((X1 - X0) * (Y1 - Y0) / 4e6):.2f} m)")
    seed = check_int_range("seed", seed, 0, 2**32 - 1)
    return _cached(site, (X0, X1, Y0, Y1), float(s), seed)


#: the areas of the relief sheet (:func:`key_sheets`)
RELIEF_SHEET = ("level ground (ровные участки)", "slopes (склоны)", "hollows (западины)")
#: the areas of the vegetation and land-use sheet (:func:`key_sheets`)
COVER_SHEET = ("arable land (пашня)", "forest (лес)", "meadow (луг)", "water (вода)")


def key_sheets(layer: SoilLayer, site=None) -> dict:
    """The indirect keys of a soil layer's area as an interpreter outlines them on transparent sheets (guide §14).

    * ``relief`` (ny, nx) int: :data:`RELIEF_SHEET` — level ground, slopes steeper than :data:`ERODED_SLOPE_DEG`,
      closed hollows deeper than :data:`HOLLOW_SHARE` of the site's relief (read from the stereo model);
    * ``cover`` (ny, nx) int: :data:`COVER_SHEET` — arable land, forest, meadow, water (from the photo; roads,
      field boundaries, shelter belts and buildings are left out, as they are no soil boundaries).

    ``site`` is the layer's site (default :func:`aerophoto.site.get_site`).
    """
    from .model import COVER_CODES

    if not isinstance(layer, SoilLayer):
        raise TypeError(f"layer = {layer!r:.60} must be a SoilLayer (aerophoto.site.soils.soil_layer)")
    if site is None:
        from . import get_site

        site = get_site()
    V.check_type("site", site, object, what="a Site (aerophoto.site.get_site())")
    if not all(hasattr(site, a) for a in ("z_max_m", "z_min_m", "cover_at", "params")):
        raise TypeError(f"site = {site!r:.60} is not a Site; expected aerophoto.site.get_site() or None")
    relief = np.zeros(layer.shape, np.int64)
    relief[layer.slope_deg > ERODED_SLOPE_DEG] = 1
    span = max(site.z_max_m - site.z_min_m, 1e-9)
    relief[layer.hollow_m > HOLLOW_SHARE * span] = 2
    X0, _, Y0, _ = layer.extent_m
    s = layer.spacing_m
    ny, nx = layer.shape
    cov = _ground_cover(site, X0 + (np.arange(nx) + 0.5) * s, Y0 + (np.arange(ny) + 0.5) * s, s)
    cover = np.zeros(layer.shape, np.int64)
    cover[cov == COVER_CODES["forest"]] = 1
    cover[cov == COVER_CODES["meadow"]] = 2
    cover[np.isin(cov, [COVER_CODES["water"], COVER_CODES["sand bank"]])] = 3
    return {"relief": relief, "cover": cover}
