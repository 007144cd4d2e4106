"""Demo terrains of the virtual world: smooth analytic hills and the site with adjustable relief.

Layer 3 (the virtual world).  Each class implements :class:`aerophoto.geometry.Terrain`
(``height(X, Y)``, ``z_min_m``, ``z_max_m``), so it can be passed wherever a terrain is
expected (:func:`aerophoto.geometry.photo_to_dem`, :func:`aerophoto.geometry.as_terrain`).

* :class:`AnalyticHills` — four smooth hills and a valley with a chosen relief
  amplitude, laid out on a square whose mean height is the mean object plane
  (the displacement explorer of chapters 03 and 04, guide §4–§5).
* :class:`RescaledRelief` — the virtual site with its relief stretched to a
  chosen height difference (the fotoschema of chapter 05, guide §6).
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from functools import lru_cache

import numpy as np

from ._validate import check_positive, check_range

__all__: list[str] = ["AnalyticHills", "RescaledRelief"]

# =========================================================================== analytic hills (chapters 03, 04)
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
    """Deterministic hilly terrain: four smooth hills and a valley (for the displacement explorer).

    Heights are ``Z0_m + relief_m · s(u, v)`` with u = (X − X0)/L, v = (Y − Y0)/L
    and a fixed shape s whose mean over the square |u|, |v| ≤ 1 is zero and
    whose extreme inside it is ±1: so ``Z0_m`` is the mean object plane of
    that square (средняя предметная плоскость, guide §4) and ``relief_m`` the
    largest height h above or below it.

    Parameters
    ----------
    relief_m : float
        Relief amplitude, m (0 ≤ relief_m ≤ 10⁵).
    half_side_m : float
        L: half the side of the square the hills are laid out on, m (> 0).
    X0_m, Y0_m, Z0_m : float
        Centre of the square and the mean height, m.

    Implements :class:`aerophoto.geometry.Terrain` (``height(X, Y)``, ``z_min_m``,
    ``z_max_m``), so it can be passed to :func:`aerophoto.geometry.photo_to_dem`.
    """

    relief_m: float = 50.0
    half_side_m: float = 1000.0
    X0_m: float = 0.0
    Y0_m: float = 0.0
    Z0_m: float = 0.0

    def __post_init__(self):
        object.__setattr__(self, "relief_m", check_range("relief_m", self.relief_m, 0.0, 1e5, unit="m"))
        object.__setattr__(self, "half_side_m", check_positive("half_side_m", self.half_side_m, unit="m"))
        for name in ("X0_m", "Y0_m", "Z0_m"):
            object.__setattr__(self, name, check_range(name, getattr(self, name), -1e7, 1e7, unit="m"))

    def shape(self, u, v) -> np.ndarray:
        """The normalised shape s(u, v) (zero mean and extreme ±1 over [−1, 1]²), any matching shapes."""
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
        """A lower bound of every height, m (Terrain protocol)."""
        return self.Z0_m - self.relief_m * _shape_norm()[2]

    @property
    def z_max_m(self) -> float:
        """An upper bound of every height, m (Terrain protocol)."""
        return self.Z0_m + self.relief_m * _shape_norm()[2]


# =========================================================================== the site with adjustable relief (chapter 05)
class RescaledRelief:
    """The virtual site with its relief stretched to ``relief_m`` about its lowest ground.

        Z' = z₀ + k·(Z − z₀),  k = relief_m / site.relief_m,  z₀ = the site's lowest height

    so the hills keep their shape and the lowest ground its height while the
    height difference becomes ``relief_m`` (0 = flat).  The ground texture and
    the catalogue's X, Y are the site's; the catalogue's Z is rescaled the
    same way.  This lets a slider change the relief without rebuilding the
    site.  It offers what :func:`aerophoto.geometry.photo_to_dem`,
    :func:`aerophoto.simulate.strip_over_site`, :func:`aerophoto.render.render`
    and :func:`aerophoto.mosaic.sheet_raster` need (the Terrain protocol, the
    DEM grid, the texture pyramid and the catalogue).

    Parameters
    ----------
    site : aerophoto.site.Site, with relief > 0
    relief_m : float, 0 ≤ relief_m ≤ 3000, metres
    """

    def __init__(self, site, relief_m: float):
        if not all(hasattr(site, a) for a in ("height", "z_min_m", "z_max_m")):
            raise TypeError(f"site = {site!r:.60} is a {type(site).__name__}; "
                            "expected a Site (aerophoto.site.get_site())")
        self.site = site
        self.relief_m = check_range("relief_m", relief_m, 0.0, 3000.0, unit="m")
        r0 = float(site.z_max_m - site.z_min_m)
        if r0 <= 0:
            raise ValueError("the site is flat (relief 0 m); RescaledRelief needs a site with relief > 0 m")
        self.z0 = float(site.z_min_m)
        self.k = self.relief_m / r0
        self._dem = None

    def _scale(self, Z):
        return self.z0 + self.k * (np.asarray(Z, dtype=float) - self.z0)

    def height(self, X, Y) -> np.ndarray:
        """Terrain height Z', metres (vectorised over X, Y)."""
        return self._scale(self.site.height(X, Y))

    __call__ = height

    @property
    def z_min_m(self) -> float:
        return self.z0

    @property
    def z_max_m(self) -> float:
        return self.z0 + self.relief_m

    @property
    def mean_height_m(self) -> float:
        return float(self._scale(self.site.mean_height_m))

    @property
    def centre_m(self):
        return self.site.centre_m

    @property
    def extent_m(self):
        return self.site.extent_m

    def inside(self, X, Y):
        return self.site.inside(X, Y)

    def sample(self, X, Y, level: int = 0, **kw):
        return self.site.sample(X, Y, level, **kw)

    def level_for(self, ground_pixel_m: float) -> int:
        return self.site.level_for(ground_pixel_m)

    # what aerophoto.render needs besides: the DEM grid and the texture pyramid
    @property
    def dem(self) -> np.ndarray:
        """The rescaled DEM grid (same nodes as the site's), metres."""
        if getattr(self, "_dem", None) is None:
            self._dem = self._scale(self.site.dem)
            self._dem.flags.writeable = False
        return self._dem

    @property
    def dem_spacing_m(self) -> float:
        return self.site.dem_spacing_m

    @property
    def texture(self) -> np.ndarray:
        return self.site.texture

    @property
    def n_levels(self) -> int:
        return self.site.n_levels

    def texture_level(self, level: int = 0) -> np.ndarray:
        return self.site.texture_level(level)

    def texel_m(self, level: int = 0) -> float:
        return self.site.texel_m(level)

    @property
    def catalogue(self):
        """The site's catalogue (a pandas DataFrame) with Z_m rescaled."""
        cat = self.site.catalogue.copy()
        cat["Z_m"] = self._scale(cat["Z_m"].to_numpy())
        return cat

    def points_m(self) -> np.ndarray:
        """The catalogue as an array of X, Y, Z (rescaled), shape (k, 3), metres."""
        return self.catalogue[["X_m", "Y_m", "Z_m"]].to_numpy(dtype=float)
