"""The virtual site's data types: land-cover codes, :class:`SiteParams` and :class:`Site`.

A :class:`Site` is data only — the DEM, the texture and its pyramid, the
land cover, the catalogue of ground points and the vector features the
texture was painted from — with the look-ups a renderer needs (``height``,
``sample``, ``cover_at``, …).  It is made by :func:`aerophoto.site.build.build_site`;
its map view is :func:`aerophoto.demos.site_views.plot_site` (presentation).
See :mod:`aerophoto.site` for the coordinates and conventions.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from .._validate import check_int_range, check_range

__all__ = ["COVER", "COVER_CODES", "KINDS", "MAX_PIXELS", "SiteParams", "Site"]

#: Land-cover codes of :attr:`Site.cover`.
COVER = {
    0: "none",
    1: "arable field",
    2: "field boundary",
    3: "meadow",
    4: "forest",
    5: "water",
    6: "sand bank",
    7: "dirt road",
    8: "paved road",
    9: "garden",
    10: "building",
    11: "tree",
}
#: The same, name → code.
COVER_CODES = {v: k for k, v in COVER.items()}

#: Kinds of catalogue points.
KINDS = ("road crossing", "field corner", "building corner", "tree")

MAX_PIXELS = 60_000_000


# --------------------------------------------------------------------------- parameters
@dataclass(frozen=True)
class SiteParams:
    """Everything that defines a virtual site (hashable: the cache key of :func:`get_site`).

    Parameters
    ----------
    width_m, height_m : float
        Extent along X (east) and Y (north), metres, 1000 ≤ size ≤ 100 000.
        The default 10 km × 5 km holds a strip of 7 photos at 1:12 000 with
        f = 100 mm and p_x = 60 % (photo side 2.16 km, base 0.864 km).
    relief_m : float
        Height difference between the lowest and highest ground, metres,
        0 ≤ relief ≤ 3000 (0 = flat).
    base_height_m : float
        Height of the lowest ground, metres, −500 ≤ base ≤ 8000.
    seed : int
        Seed of the layout, 0 ≤ seed < 2**32.
    texture_m : float
        Ground size of a texture pixel, metres, 0.5 ≤ t ≤ 20; the number of
        texture pixels may not exceed 60 million.
    dem_spacing_m : float
        Spacing of the DEM grid nodes, metres, 2 ≤ s ≤ 200.
    """

    width_m: float = 10000.0
    height_m: float = 5000.0
    relief_m: float = 30.0
    base_height_m: float = 170.0
    seed: int = 0
    texture_m: float = 2.0
    dem_spacing_m: float = 10.0

    def __post_init__(self):
        s = object.__setattr__
        s(self, "width_m", check_range("width_m", self.width_m, 1000.0, 100000.0, unit="m"))
        s(self, "height_m", check_range("height_m", self.height_m, 1000.0, 100000.0, unit="m"))
        s(self, "relief_m", check_range("relief_m", self.relief_m, 0.0, 3000.0, unit="m"))
        s(self, "base_height_m", check_range("base_height_m", self.base_height_m, -500.0, 8000.0, unit="m"))
        s(self, "seed", check_int_range("seed", self.seed, 0, 2**32 - 1))
        s(self, "texture_m", check_range("texture_m", self.texture_m, 0.5, 20.0, unit="m"))
        s(self, "dem_spacing_m", check_range("dem_spacing_m", self.dem_spacing_m, 2.0, 200.0, unit="m"))
        npx = math.ceil(self.width_m / self.texture_m) * math.ceil(self.height_m / self.texture_m)
        if npx > MAX_PIXELS:
            t_min = math.sqrt(self.width_m * self.height_m / MAX_PIXELS)
            raise ValueError(
                f"texture_m = {self.texture_m:g} gives {npx} texture pixels for a {self.width_m:g} m × "
                f"{self.height_m:g} m site; the valid range is texture_m ≥ {t_min:.2f} m "
                f"(at most {MAX_PIXELS} pixels)"
            )


# --------------------------------------------------------------------------- the site
@dataclass(frozen=True, eq=False, repr=False)
class Site:
    """A generated virtual site.  Build it with :func:`get_site`; see the module notes.

    Attributes
    ----------
    params : SiteParams
    dem : ndarray, shape (ny_dem, nx_dem), float64
        Heights of the grid nodes, metres (node (j, i) at X = i·s, Y = j·s).
    texture : ndarray, shape (ny, nx), uint8
        Brightness ×255 at level 0 (row 0 at the south edge).
    cover : ndarray, shape (ny, nx), uint8
        Land-cover codes (:data:`COVER`) on the texture grid.
    catalogue : pandas.DataFrame
        Ground points: id, kind, X_m, Y_m, Z_m, control (kinds :data:`KINDS`, Z on the DEM).
    objects : :class:`aerophoto.site.objects.SiteObjects` or None
        What stands on the ground with a height of its own (houses, trees, the
        forest canopy, a chimney, a mast, a water tower, an embankment and a
        bridge), ray-cast by :mod:`aerophoto.render`; their measurable points
        are :attr:`object_points`.
    features : dict
        The vector data the texture was painted from (metres): ``"river"``
        (k, 2) centre line; ``"roads"`` list of dicts (``kind``: "paved" or
        "dirt", ``xy``: (2, 2) segment end points, ``width_m``);
        ``"buildings"`` (n, 4, 2) roof corners; ``"trees"`` (n, 2) crown
        centres; ``"village"`` (2,) centre; ``"oxbow"`` (k, 2) centre line of
        the oxbow lake; ``"field_rotation_deg"`` (north, south): the turn of
        the two field systems from the X axis, degrees.
    """

    params: SiteParams
    dem: np.ndarray
    texture: np.ndarray
    cover: np.ndarray
    catalogue: pd.DataFrame
    features: dict
    _levels: list = field(repr=False, default_factory=list)
    objects: object = None

    def __repr__(self) -> str:
        p = self.params
        ny, nx = self.texture.shape
        return (f"Site({p.width_m:g} m × {p.height_m:g} m, Z {self.z_min_m:g}…{self.z_max_m:g} m, "
                f"texture {nx}×{ny} px at {p.texture_m:g} m, {len(self.catalogue)} ground points, seed {p.seed})")

    # ---- extent
    @property
    def extent_m(self) -> tuple:
        """(X_min, X_max, Y_min, Y_max) in metres."""
        return (0.0, self.params.width_m, 0.0, self.params.height_m)

    @property
    def centre_m(self) -> tuple:
        """Centre (X, Y) of the site, metres."""
        return (self.params.width_m / 2.0, self.params.height_m / 2.0)

    def inside(self, X, Y) -> np.ndarray:
        """Boolean mask (broadcast shape of X, Y): which ground points lie on the site."""
        X = np.asarray(X)
        Y = np.asarray(Y)
        return (X >= 0) & (X <= self.params.width_m) & (Y >= 0) & (Y <= self.params.height_m)

    # ---- terrain
    @property
    def dem_spacing_m(self) -> float:
        return self.params.dem_spacing_m

    @property
    def base_height_m(self) -> float:
        return self.params.base_height_m

    @property
    def relief_m(self) -> float:
        return self.params.relief_m

    @functools.cached_property
    def z_min_m(self) -> float:
        """Lowest terrain height, metres (exact bound of :meth:`height`; read once: a ray cut with the terrain
        asks for it, some 160 times in one assessment of a block)."""
        return float(self.dem.min())

    @functools.cached_property
    def z_max_m(self) -> float:
        """Highest terrain height, metres (exact bound of :meth:`height`; read once)."""
        return float(self.dem.max())

    @functools.cached_property
    def mean_height_m(self) -> float:
        """Mean terrain height over the site, metres (the mean object plane for flights over it)."""
        d = self.dem
        # trapezoidal mean of the bilinear surface
        w = np.ones(d.shape)
        w[0, :] *= 0.5
        w[-1, :] *= 0.5
        w[:, 0] *= 0.5
        w[:, -1] *= 0.5
        return float(np.sum(d * w) / np.sum(w))

    def height(self, X, Y) -> np.ndarray:
        """Terrain height Z in metres at ground points X, Y (metres), bilinear on the DEM grid.

        Vectorised: X and Y broadcast; the result has their broadcast shape,
        float64.  Outside the site the nearest edge node's height is used.
        """
        from scipy.ndimage import map_coordinates

        X = np.asarray(X, dtype=float)
        Y = np.asarray(Y, dtype=float)
        X, Y = np.broadcast_arrays(X, Y)
        s = self.params.dem_spacing_m
        out = map_coordinates(self.dem, [Y.ravel() / s, X.ravel() / s], order=1, mode="nearest")
        return out.reshape(X.shape)

    __call__ = height

    # ---- what stands on the ground
    def surface_height(self, X, Y) -> np.ndarray:
        """Height of the top surface at X, Y (metres): the DEM with every object on it (a DSM).

        The roof of a house, the top of a crown or of the forest canopy, the
        crest of the embankment — where nothing stands, the DEM (:meth:`height`,
        the bare earth, which every chapter's geometry uses).  Vectorised like
        :meth:`height`.
        """
        if self.objects is None:
            return self.height(X, Y)
        return self.objects.surface_height(self.height, X, Y)

    @property
    def surface_z_max_m(self) -> float:
        """The highest point of the surface (objects included), metres."""
        if self.objects is None:
            return self.z_max_m
        return max(self.z_max_m + self.objects.canopy_max_m, self.objects.z_max_m, self.z_max_m)

    @property
    def object_points(self) -> pd.DataFrame:
        """The objects' measurable points: roof corners, ridge ends, tree tops, tops of the structures.

        Columns as :attr:`catalogue` (ids continue after it, ``control``
        False) plus ``object`` (the row of ``objects.table()``),
        ``ground_Z_m`` (the DEM under the point) and ``height_m`` (Z − ground).
        Kinds: :data:`aerophoto.site.objects.POINT_KINDS`.
        """
        if self.objects is None or self.objects.points is None:
            cols = ["id", "kind", "X_m", "Y_m", "Z_m", "control", "object", "ground_Z_m", "height_m"]
            return pd.DataFrame({c: [] for c in cols})
        return self.objects.points.copy()

    @property
    def all_points(self) -> pd.DataFrame:
        """The ground catalogue followed by the object points (the catalogue's rows, order and ids unchanged).

        Ground rows get ``object`` −1, ``ground_Z_m`` = Z_m and ``height_m`` 0.
        :attr:`catalogue` itself keeps only the ground points, so code that
        takes "any catalogue point" picks the same points as before objects
        had heights.
        """
        cat = self.catalogue.copy()
        cat["object"] = -1
        cat["ground_Z_m"] = cat["Z_m"]
        cat["height_m"] = 0.0
        obj = self.object_points
        if not len(obj):
            return cat
        out = pd.concat([cat, obj], ignore_index=True)
        out["object"] = out["object"].astype(np.int64)
        out["control"] = out["control"].astype(bool)
        return out

    # ---- texture
    def texel_m(self, level: int = 0) -> float:
        """Ground size of a texture pixel at pyramid level k: t·2^k metres."""
        return self.params.texture_m * 2 ** int(level)

    @property
    def n_levels(self) -> int:
        """Number of pyramid levels (level 0 is :attr:`texture`)."""
        return 1 + len(self._levels)

    def texture_level(self, level: int = 0) -> np.ndarray:
        """The uint8 texture at pyramid level k (2×2 block means of level k − 1), rows = Y."""
        k = check_int_range("level", level, 0, self.n_levels - 1)
        return self.texture if k == 0 else self._levels[k - 1]

    def level_for(self, ground_pixel_m: float) -> int:
        """The coarsest pyramid level whose texels are no larger than ``ground_pixel_m``."""
        g = check_range("ground_pixel_m", ground_pixel_m, 0.0, math.inf, lo_open=True, unit="m")
        k = int(math.floor(math.log2(max(g / self.params.texture_m, 1.0)) + 1e-9))
        return min(max(k, 0), self.n_levels - 1)

    def sample(self, X, Y, level: int = 0, *, outside: float = np.nan) -> np.ndarray:
        """Ground brightness (0…1, float32) at X, Y (metres), bilinear on pyramid level ``level``.

        Points off the site get ``outside``.  This is exactly what
        :func:`aerophoto.render.render` puts into a photo's pixel (before
        vignetting and fiducial marks).
        """
        tex = self.texture_level(level)
        t = self.texel_m(level)
        X = np.asarray(X, dtype=float)
        Y = np.asarray(Y, dtype=float)
        X, Y = np.broadcast_arrays(X, Y)
        from scipy.ndimage import map_coordinates

        out = map_coordinates(tex, [Y.ravel() / t - 0.5, X.ravel() / t - 0.5], order=1, mode="nearest",
                              output=np.float32).reshape(X.shape)
        out *= np.float32(1.0 / 255.0)
        bad = ~self.inside(X, Y)
        if np.any(bad):
            out[bad] = outside
        return out

    def cover_at(self, X, Y) -> np.ndarray:
        """Land-cover code (:data:`COVER`) of the texture pixel containing each point (0 off the site)."""
        X = np.asarray(X, dtype=float)
        Y = np.asarray(Y, dtype=float)
        t = self.params.texture_m
        ny, nx = self.cover.shape
        c = np.clip(np.floor(X / t).astype(np.int64), 0, nx - 1)
        r = np.clip(np.floor(Y / t).astype(np.int64), 0, ny - 1)
        out = self.cover[r, c]
        return np.where(self.inside(X, Y), out, 0).astype(np.uint8)
