"""Digital elevation models of a map sheet and the contours drawn from them (article 000).

Article 000 draws contours (горизонтали) at a 0.5 m interval (сечение рельефа) on a 1:2000 photoplan
from the points of a digital elevation model (цифровая модель рельефа, ЦМР) and compares two ways of
choosing those points:

* the **regular model** (регулярная модель): nodes on a square grid of fixed step (7 mm on the photo,
  about 30 m on the ground), heights interpolated linearly between them — :func:`grid_dem`;
* the **structural model** (нерегулярная модель, учитывающая морфологию): points on the structural
  lines of the relief (структурные линии) — thalwegs (тальвеги) and watersheds (водоразделы) — and at
  characteristic points (peaks, pits), joined into a triangulated irregular network (TIN) whose
  triangles follow the ground — :func:`tin_dem`, with the lines from :func:`structural_lines`.

Here the ground is a :class:`aerophoto.geometry.Terrain` (the virtual site), so each DEM and each of
its contours can be held against the true surface: :func:`contour_accuracy` samples the true height
along every contour the DEM gives — a contour at level z should lie where the ground is at z — and
:func:`dem_accuracy` compares heights at check points (контрольные точки), as the article did.

Every node height may carry a measurement error of RMS m_z (the densification error of
:mod:`aerophoto.dem.densification`), drawn from a seeded generator.  Linear interpolation averages the
errors of the surrounding nodes, so the DEM between nodes is more precise than its nodes: over a cell
the mean of the squared weights is 4/9 for bilinear interpolation on a grid and 1/2 on a triangle
(:data:`NOISE_FACTOR`, :func:`predicted_rms`).

Coordinates: ground X east, Y north, Z up, metres.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from .. import _validate as V
from .. import geometry as g
from .._validate import check_finite_array, check_int_range, check_points, check_positive, check_range

__all__ = ["Sheet", "NOISE_FACTOR", "STANDARD_INTERVALS_M", "grid_nodes", "StructuralLines", "structural_lines",
           "DEM", "grid_dem", "tin_dem", "grid_with_lines", "structural_dem", "contour_levels", "contour_lines",
           "ContourAccuracy", "contour_accuracy", "dem_accuracy", "predicted_rms", "correlated_noise_factor",
           "standard_interval", "SheetResult", "evaluate", "spacing_study"]

#: mean over a cell of Σ wᵢ² — the share of the nodes' error variance left between nodes by linear interpolation
NOISE_FACTOR = {"grid": 4.0 / 9.0, "tin": 0.5}
#: contour intervals (сечение рельефа) of topographic plans and maps, m
STANDARD_INTERVALS_M = (0.25, 0.5, 1.0, 2.0, 2.5, 5.0, 10.0, 20.0, 25.0, 50.0, 100.0)
MAX_NODES = 200_000
MAX_RASTER = 4_000_000


@dataclass(frozen=True)
class Sheet:
    """A square map sheet (трапеция) on the ground: X0 ≤ X ≤ X0 + size, Y0 ≤ Y ≤ Y0 + size, metres.

    A 1:2000 sheet of 50 × 50 cm covers 1 km × 1 km.
    """

    X0_m: float
    Y0_m: float
    size_m: float = 1000.0

    def __post_init__(self):
        object.__setattr__(self, "X0_m", check_range("X0_m", self.X0_m, -1e7, 1e7, unit="m"))
        object.__setattr__(self, "Y0_m", check_range("Y0_m", self.Y0_m, -1e7, 1e7, unit="m"))
        object.__setattr__(self, "size_m", check_range("size_m", self.size_m, 50.0, 20000.0, unit="m"))

    @property
    def extent_m(self) -> tuple:
        """(X_min, X_max, Y_min, Y_max), m."""
        return (self.X0_m, self.X0_m + self.size_m, self.Y0_m, self.Y0_m + self.size_m)

    def inside(self, XY) -> np.ndarray:
        """Boolean mask (k,): which points (k, 2) lie on the sheet."""
        P = np.asarray(XY, dtype=float).reshape(-1, 2)
        x0, x1, y0, y1 = self.extent_m
        return (P[:, 0] >= x0) & (P[:, 0] <= x1) & (P[:, 1] >= y0) & (P[:, 1] <= y1)

    def raster(self, cell_m: float) -> tuple:
        """(x, y): the coordinates of a raster over the sheet, ``cell_m`` apart, both edges included."""
        cell = check_range("cell_m", cell_m, self.size_m / 2000.0, self.size_m / 2.0, unit="m")
        n = int(round(self.size_m / cell)) + 1
        if n * n > MAX_RASTER:
            raise ValueError(f"cell_m = {cell:g} gives {n * n} raster cells; the valid range is at most {MAX_RASTER}")
        return (np.linspace(self.X0_m, self.X0_m + self.size_m, n),
                np.linspace(self.Y0_m, self.Y0_m + self.size_m, n))


def _edge_axis(start: float, size: float, spacing: float) -> np.ndarray:
    """start, start + d, …, and the far edge (the last interval may be shorter)."""
    k = int(math.floor(size / spacing + 1e-9))
    ax = start + spacing * np.arange(k + 1)
    if size - spacing * k > 1e-6 * spacing:
        ax = np.append(ax, start + size)
    return ax


@V.checked(sheet=Sheet)
def grid_nodes(sheet: Sheet, spacing_m: float) -> tuple:
    """(xs, ys): the node coordinates of a square grid of step d over the sheet, its far edges included, m."""
    d = check_range("spacing_m", spacing_m, sheet.size_m / 400.0, sheet.size_m / 2.0, unit="m")
    return _edge_axis(sheet.X0_m, sheet.size_m, d), _edge_axis(sheet.Y0_m, sheet.size_m, d)


# --------------------------------------------------------------------------- structural lines
def _principal_curvatures(Z: np.ndarray, cell: float) -> tuple:
    """Gradient and principal curvatures of a raster Z[j, i] (rows = Y): (gx, gy, l1, e1, l2, e2).

    l1 ≥ l2 are the eigenvalues of the Hessian (1/m), e1, e2 their unit eigenvectors as (ex, ey) arrays.
    """
    gy, gx = np.gradient(Z, cell)
    gyy, gyx = np.gradient(gy, cell)
    gxy, gxx = np.gradient(gx, cell)
    h = (gxy + gyx) / 2.0
    half_tr = (gxx + gyy) / 2.0
    disc = np.sqrt(np.maximum(half_tr**2 - (gxx * gyy - h * h), 0.0))
    l1, l2 = half_tr + disc, half_tr - disc

    def vec(lam):
        vx = np.where(np.abs(h) > 1e-15, h, np.where(np.abs(gxx - lam) <= np.abs(gyy - lam), 1.0, 0.0))
        vy = np.where(np.abs(h) > 1e-15, lam - gxx, np.where(np.abs(gxx - lam) <= np.abs(gyy - lam), 0.0, 1.0))
        n = np.hypot(vx, vy)
        return vx / n, vy / n

    return gx, gy, l1, vec(l1), l2, vec(l2)


def _thin(P: np.ndarray, spacing: float) -> np.ndarray:
    """Keep points in order, dropping any closer than ``spacing`` to one already kept (indices)."""
    if len(P) == 0:
        return np.zeros(0, dtype=int)
    cells: dict = {}
    kept = []
    d2 = spacing * spacing
    for i, (x, y) in enumerate(P):
        cx, cy = int(math.floor(x / spacing)), int(math.floor(y / spacing))
        ok = True
        for ax in (cx - 1, cx, cx + 1):
            for ay in (cy - 1, cy, cy + 1):
                for j in cells.get((ax, ay), ()):
                    if (P[j, 0] - x) ** 2 + (P[j, 1] - y) ** 2 < d2:
                        ok = False
                        break
                if not ok:
                    break
            if not ok:
                break
        if ok:
            kept.append(i)
            cells.setdefault((cx, cy), []).append(i)
    return np.array(kept, dtype=int)


@dataclass(frozen=True)
class StructuralLines:
    """The structural lines of the relief on a sheet, found on the true surface.

    Attributes
    ----------
    sheet : :class:`Sheet`
    cell_m : float — the raster the lines were traced on, m
    valley_xy, ridge_xy : ndarray (k, 2) — cells on thalwegs / on watersheds, the most sharply curved
        first, m
    valley_segments, ridge_segments : ndarray (k, 2, 2) — the lines as segments between neighbouring
        line cells, for drawing, m
    peaks_xy, pits_xy : ndarray (k, 2) — characteristic points: local maxima and minima, m
    """

    sheet: Sheet
    cell_m: float
    valley_xy: np.ndarray
    ridge_xy: np.ndarray
    valley_segments: np.ndarray
    ridge_segments: np.ndarray
    peaks_xy: np.ndarray
    pits_xy: np.ndarray

    def points(self, spacing_m: float) -> np.ndarray:
        """Points (k, 2) along the lines and at the characteristic points, no two closer than ``spacing_m``.

        Characteristic points first, then the line cells from the most sharply curved down.
        """
        d = check_range("spacing_m", spacing_m, self.cell_m / 2.0, self.sheet.size_m, unit="m")
        cand = np.vstack([self.peaks_xy, self.pits_xy, _interleave(self.valley_xy, self.ridge_xy)])
        return cand[_thin(cand, d)]


def _interleave(a: np.ndarray, b: np.ndarray) -> np.ndarray:
    n = max(len(a), len(b))
    out = []
    for i in range(n):
        if i < len(a):
            out.append(a[i])
        if i < len(b):
            out.append(b[i])
    return np.array(out).reshape(-1, 2)


@V.checked(sheet=Sheet)
def structural_lines(terrain, sheet: Sheet, *, cell_m: float = 10.0, smooth_cells: float = 1.5,
                     min_curvature_per_m: float = 2e-5, margin_m: float = 200.0) -> StructuralLines:
    """Trace the thalwegs and watersheds of ``terrain`` on ``sheet`` (the operator's structural lines).

    On a raster of ``cell_m`` (smoothed by a Gaussian of ``smooth_cells`` cells, as an operator sees the
    shape of the ground rather than its grain), a cell lies on a **thalweg** where the ground curves up
    across the line — the larger principal curvature exceeds ``min_curvature_per_m`` — and the height
    is lowest across it: the slope along that principal direction vanishes within the cell.  A
    **watershed** is the same with the ground curving down.  Characteristic points are the local maxima
    (peaks) and minima (pits) of the raster.  The raster reaches ``margin_m`` beyond the sheet; what
    lies on the sheet is returned, the most sharply curved line cells first.

    Parameters
    ----------
    terrain : a :class:`aerophoto.geometry.Terrain`
    sheet : :class:`Sheet`
    cell_m : raster cell, m (size/500 ≤ cell ≤ size/10)
    smooth_cells : Gaussian smoothing, cells (0 ≤ σ ≤ 10)
    min_curvature_per_m : least curvature across a line, 1/m (> 0; 2·10⁻⁵ is a slope change of 0.2 %
        per 100 m)
    margin_m : 0 ≤ margin ≤ size
    """
    from scipy.ndimage import gaussian_filter, maximum_filter, minimum_filter

    terrain = g.as_terrain(terrain)
    cell = check_range("cell_m", cell_m, sheet.size_m / 500.0, sheet.size_m / 10.0, unit="m")
    sm = check_range("smooth_cells", smooth_cells, 0.0, 10.0)
    kmin = check_positive("min_curvature_per_m", min_curvature_per_m, unit="1/m", hi=1.0)
    margin = check_range("margin_m", margin_m, 0.0, sheet.size_m, unit="m")
    x0, x1, y0, y1 = sheet.extent_m
    xs = np.arange(x0 - margin, x1 + margin + cell / 2, cell)
    ys = np.arange(y0 - margin, y1 + margin + cell / 2, cell)
    XX, YY = np.meshgrid(xs, ys)
    Z = np.asarray(terrain.height(XX, YY), dtype=float)
    Zs = gaussian_filter(Z, sm, mode="nearest") if sm > 0 else Z
    gx, gy, l1, e1, l2, e2 = _principal_curvatures(Zs, cell)
    on_sheet = sheet.inside(np.column_stack([XX.ravel(), YY.ravel()])).reshape(Z.shape)
    masks = {"valley": (l1 > kmin) & (np.abs(gx * e1[0] + gy * e1[1]) <= l1 * cell / 2.0),
             "ridge": (l2 < -kmin) & (np.abs(gx * e2[0] + gy * e2[1]) <= -l2 * cell / 2.0)}
    strength = {"valley": l1, "ridge": -l2}
    out = {}
    for name, mask in masks.items():
        keep = mask & on_sheet
        order = np.argsort(-strength[name][keep], kind="stable")
        out[f"{name}_xy"] = np.column_stack([XX[keep], YY[keep]])[order]
        segs = []
        jj, ii = np.nonzero(mask)
        ny, nx = mask.shape
        for dj, di in ((0, 1), (1, 0), (1, 1), (1, -1)):  # each neighbouring pair of line cells once
            j2, i2 = jj + dj, ii + di
            ok = (j2 < ny) & (i2 >= 0) & (i2 < nx)
            ok[ok] = mask[j2[ok], i2[ok]]
            segs.append(np.stack([np.column_stack([xs[ii[ok]], ys[jj[ok]]]),
                                  np.column_stack([xs[i2[ok]], ys[j2[ok]]])], axis=1))
        seg = np.concatenate(segs) if segs else np.zeros((0, 2, 2))
        inside = sheet.inside(seg[:, 0]) & sheet.inside(seg[:, 1])
        out[f"{name}_segments"] = seg[inside]
    peaks = (Zs == maximum_filter(Zs, size=3, mode="nearest")) & (Zs > minimum_filter(Zs, size=3, mode="nearest"))
    pits = (Zs == minimum_filter(Zs, size=3, mode="nearest")) & (Zs < maximum_filter(Zs, size=3, mode="nearest"))
    for name, mask in (("peaks_xy", peaks & on_sheet), ("pits_xy", pits & on_sheet)):
        out[name] = np.column_stack([XX[mask], YY[mask]])
    return StructuralLines(sheet, cell, out["valley_xy"], out["ridge_xy"], out["valley_segments"],
                           out["ridge_segments"], out["peaks_xy"], out["pits_xy"])


# --------------------------------------------------------------------------- the DEMs
@dataclass(frozen=True, eq=False)
class DEM:
    """A digital elevation model: nodes with measured heights and their linear interpolation.

    Attributes
    ----------
    kind : ``"grid"`` (bilinear between the nodes of a square grid) or ``"tin"`` (linear on a Delaunay
        triangulation of the nodes)
    nodes_m : ndarray (k, 3) — X, Y and the measured height Z of every node, m
    true_Z_m : ndarray (k,) — the true heights of the nodes, m
    mz_m : float — RMS of the measurement error put on the node heights, m
    kinds : ndarray (k,) of str — what each node is: ``"grid"``, ``"line"`` or ``"boundary"``
    """

    kind: str
    nodes_m: np.ndarray
    true_Z_m: np.ndarray
    mz_m: float
    kinds: np.ndarray
    _grid: tuple = field(default=None, repr=False)
    _tri: object = field(default=None, repr=False)

    @property
    def n_nodes(self) -> int:
        return len(self.nodes_m)

    @functools.cached_property
    def _values(self) -> np.ndarray:
        return np.column_stack([self.nodes_m[:, 2], self.true_Z_m])

    @functools.cached_property
    def _interp(self):
        from scipy.interpolate import RegularGridInterpolator

        xs, ys = self._grid
        return RegularGridInterpolator((ys, xs), self._values.reshape(len(ys), len(xs), 2), bounds_error=False,
                                       fill_value=None)

    @functools.cached_property
    def _trifinder(self):
        # matplotlib's trapezoid map: robust for points on the triangles' edges (a regular raster over a grid
        # has many), where a directed walk may fall back to searching every triangle
        from matplotlib.tri import Triangulation

        return Triangulation(self.nodes_m[:, 0], self.nodes_m[:, 1], self._tri.simplices).get_trifinder()

    def heights(self, X, Y) -> np.ndarray:
        """Both interpolations at X, Y (broadcast), shape (..., 2): through the measured node heights
        ([..., 0], the DEM) and through the true ones ([..., 1], the DEM without measurement errors), m.

        A TIN is evaluated with barycentric weights in the Delaunay triangle holding each point, found
        with matplotlib's trapezoid-map triangle finder (NaN outside the hull).
        """
        X, Y = np.broadcast_arrays(np.asarray(X, dtype=float), np.asarray(Y, dtype=float))
        if self.kind == "grid":
            return np.asarray(self._interp(np.column_stack([Y.ravel(), X.ravel()]))).reshape(X.shape + (2,))
        P = np.column_stack([X.ravel(), Y.ravel()])
        simplex = np.asarray(self._trifinder(P[:, 0], P[:, 1]))
        inside = simplex >= 0
        tri = self._tri.simplices[np.where(inside, simplex, 0)]
        A, B, C = (self.nodes_m[tri[:, k], :2] for k in range(3))
        v0, v1, v2 = B - A, C - A, P - A
        d00, d01, d11 = (v0 * v0).sum(1), (v0 * v1).sum(1), (v1 * v1).sum(1)
        d20, d21 = (v2 * v0).sum(1), (v2 * v1).sum(1)
        den = d00 * d11 - d01 * d01
        wb = (d11 * d20 - d01 * d21) / den
        wc = (d00 * d21 - d01 * d20) / den
        V = self._values
        out = ((1.0 - wb - wc)[:, None] * V[tri[:, 0]] + wb[:, None] * V[tri[:, 1]] + wc[:, None] * V[tri[:, 2]])
        out[~inside] = np.nan
        return out.reshape(X.shape + (2,))

    def height(self, X, Y) -> np.ndarray:
        """The DEM's height at ground points X, Y (broadcast), m; NaN outside a TIN's hull."""
        return self.heights(X, Y)[..., 0]

    @property
    def triangles(self):
        """The TIN's triangles (k, 3) node indices, or None for a grid."""
        return None if self._tri is None else self._tri.simplices


def _measured(Z: np.ndarray, mz_m: float, seed: int, stream: int) -> np.ndarray:
    seed = check_int_range("seed", seed, 0, 2**63 - 1)
    stream = check_int_range("stream", stream, 0, 2**63 - 1)
    if mz_m == 0:
        return Z.copy()
    rng = np.random.default_rng([int(seed), int(stream)])
    return Z + mz_m * rng.standard_normal(Z.shape)


@V.checked(sheet=Sheet)
def grid_dem(terrain, sheet: Sheet, spacing_m: float, *, mz_m: float = 0.0, seed: int = 0) -> DEM:
    """The regular model: nodes on a square grid of step d over the sheet, bilinear between them.

    Parameters
    ----------
    terrain : a :class:`aerophoto.geometry.Terrain`
    spacing_m : grid step d, m (size/400 ≤ d ≤ size/2; the article's 7 mm on a 1:4500 photo ≈ 30 m)
    mz_m : RMS measurement error of the node heights, m (0 ≤ m_z ≤ 100)
    seed : the errors' seed; the grid nodes draw from their own stream, so adding lines
        (:func:`grid_with_lines`) leaves their errors unchanged
    """
    terrain = g.as_terrain(terrain)
    mz = check_range("mz_m", mz_m, 0.0, 100.0, unit="m")
    xs, ys = grid_nodes(sheet, spacing_m)
    if len(xs) * len(ys) > MAX_NODES:
        raise ValueError(f"spacing_m = {spacing_m:g} gives {len(xs) * len(ys)} nodes; at most {MAX_NODES}")
    XX, YY = np.meshgrid(xs, ys)
    Zt = np.asarray(terrain.height(XX, YY), dtype=float).ravel()
    nodes = np.column_stack([XX.ravel(), YY.ravel(), _measured(Zt, mz, seed, 0)])
    return DEM("grid", nodes, Zt, mz, np.full(len(nodes), "grid"), _grid=(xs, ys))


def tin_dem(terrain, points_xy, *, kinds=None, mz_m: float = 0.0, seed: int = 0, stream: int = 1) -> DEM:
    """A TIN through the given points: heights from ``terrain`` (plus errors), linear on Delaunay triangles.

    Parameters
    ----------
    points_xy : (k, 2) node positions, m (k ≥ 3, not all on a line)
    kinds : (k,) labels of the nodes (default ``"line"``)
    mz_m, seed : as in :func:`grid_dem`; ``stream`` picks the error stream
    """
    from scipy.spatial import Delaunay, QhullError

    terrain = g.as_terrain(terrain)
    P = check_points("points_xy", points_xy, min_points=3)
    if len(P) > MAX_NODES:
        raise ValueError(f"points_xy has {len(P)} points; the valid range is at most {MAX_NODES}")
    mz = check_range("mz_m", mz_m, 0.0, 100.0, unit="m")
    Zt = np.asarray(terrain.height(P[:, 0], P[:, 1]), dtype=float)
    try:
        tri = Delaunay(P)
    except QhullError:
        raise ValueError("points_xy cannot be triangulated: the points lie on one line") from None
    labels = np.full(len(P), "line") if kinds is None else np.asarray(kinds)
    return DEM("tin", np.column_stack([P, _measured(Zt, mz, seed, stream)]), Zt, mz, labels, _tri=tri)


@V.checked(sheet=Sheet, lines=StructuralLines)
def grid_with_lines(terrain, sheet: Sheet, spacing_m: float, lines: StructuralLines, *,
                    line_spacing_m: float | None = None, mz_m: float = 0.0, seed: int = 0,
                    line_points=None) -> DEM:
    """The regular grid with the structural lines added as breaklines: one TIN through both.

    The line points are ``line_spacing_m`` apart (default d/2) and no closer than d/4 to a grid node;
    the grid nodes keep the errors they have in :func:`grid_dem` with the same seed.  ``line_points``
    may pass ``lines.points(...)`` computed beforehand (a cache).
    """
    d = check_range("spacing_m", spacing_m, sheet.size_m / 400.0, sheet.size_m / 2.0, unit="m")
    ls = d / 2.0 if line_spacing_m is None else line_spacing_m
    grid = grid_dem(terrain, sheet, d, mz_m=mz_m, seed=seed)
    if line_points is None:
        L = lines.points(max(ls, lines.cell_m / 2.0))
    else:
        L = check_points("line_points", line_points)
    if len(L):
        from scipy.spatial import cKDTree

        dist, _ = cKDTree(grid.nodes_m[:, :2]).query(L)
        L = L[dist > d / 4.0]
    Zl = np.asarray(g.as_terrain(terrain).height(L[:, 0], L[:, 1]), dtype=float) if len(L) else np.zeros(0)
    from scipy.spatial import Delaunay

    P = np.vstack([grid.nodes_m[:, :2], L])
    Zt = np.concatenate([grid.true_Z_m, Zl])
    Zm = np.concatenate([grid.nodes_m[:, 2], _measured(Zl, grid.mz_m, seed, 1)])
    kinds = np.concatenate([grid.kinds, np.full(len(L), "line")])
    return DEM("tin", np.column_stack([P, Zm]), Zt, grid.mz_m, kinds, _tri=Delaunay(P))


@V.checked(sheet=Sheet, lines=StructuralLines)
def structural_dem(terrain, sheet: Sheet, spacing_m: float, lines: StructuralLines, *, mz_m: float = 0.0,
                   seed: int = 0, n_nodes: int | None = None) -> DEM:
    """The structural model at the density of a grid of step d (the article's 164 vs 152 points per pair).

    Points on the structural lines and at the characteristic points d apart, the sheet's edge at
    step d (so the TIN covers the sheet), and the rest of the budget — ``n_nodes``, default the
    node count of :func:`grid_nodes` at step d — filling the largest gaps first (each new point the
    candidate, on a raster of d/2, farthest from every point so far).
    """
    d = check_range("spacing_m", spacing_m, sheet.size_m / 400.0, sheet.size_m / 2.0, unit="m")
    gx, gy = grid_nodes(sheet, d)
    target = len(gx) * len(gy) if n_nodes is None else check_int_range("n_nodes", n_nodes, 4, MAX_NODES)
    x0, x1, y0, y1 = sheet.extent_m
    E = np.vstack([np.column_stack([gx, np.full_like(gx, y0)]), np.column_stack([gx, np.full_like(gx, y1)]),
                   np.column_stack([np.full(len(gy) - 2, x0), gy[1:-1]]),
                   np.column_stack([np.full(len(gy) - 2, x1), gy[1:-1]])])
    L = lines.points(max(d, lines.cell_m / 2.0))
    L = L[~((np.isclose(L[:, 0], x0) | np.isclose(L[:, 0], x1) | np.isclose(L[:, 1], y0) | np.isclose(L[:, 1], y1)))]
    L = L[: max(0, target - len(E))]
    P = np.vstack([L, E])
    kinds = [np.full(len(L), "line"), np.full(len(E), "boundary")]
    need = target - len(P)
    if need > 0:
        cx, cy = _edge_axis(x0, sheet.size_m, d / 2.0), _edge_axis(y0, sheet.size_m, d / 2.0)
        C = np.column_stack([a.ravel() for a in np.meshgrid(cx[1:-1], cy[1:-1])])
        from scipy.spatial import cKDTree

        dist, _ = cKDTree(P).query(C)
        fill = []
        for _ in range(min(need, len(C))):
            k = int(np.argmax(dist))
            if dist[k] <= 0:
                break
            fill.append(k)
            dist = np.minimum(dist, np.hypot(C[:, 0] - C[k, 0], C[:, 1] - C[k, 1]))
        P = np.vstack([P, C[fill]])
        kinds.append(np.full(len(fill), "grid"))
    return tin_dem(terrain, P, kinds=np.concatenate(kinds), mz_m=mz_m, seed=seed, stream=2)


# --------------------------------------------------------------------------- contours and accuracy
def contour_levels(z_min: float, z_max: float, interval_m: float) -> np.ndarray:
    """The contour heights (multiples of the interval h) between z_min and z_max, m."""
    h = check_range("interval_m", interval_m, 0.01, 1000.0, unit="m")
    lo = check_range("z_min", z_min, -1e5, 1e5, unit="m")
    hi = check_range("z_max", z_max, lo, 1e5, unit="m")
    k0, k1 = math.ceil(lo / h - 1e-9), math.floor(hi / h + 1e-9)
    if k1 - k0 > 5000:
        raise ValueError(f"interval_m = {h:g} gives {k1 - k0 + 1} contours; the valid range is at most 5001")
    return h * np.arange(k0, k1 + 1)


@V.checked(x=V.array(ndim=1, min_len=2), y=V.array(ndim=1, min_len=2), Z=V.image(), levels=V.array(ndim=1))
def contour_lines(x, y, Z, levels) -> list:
    """Contours of a raster Z[j, i] at (x[i], y[j]): a list of (level, (k, 2) vertices) in metres.

    Traced by contourpy (matplotlib's contouring), linear along the raster's cell edges.
    """
    import contourpy

    Z = check_finite_array("Z", Z, ndim=2, max_size=MAX_RASTER)
    if np.shape(Z) != (len(y), len(x)):
        raise ValueError(f"Z has shape {np.shape(Z)}; expected (len(y), len(x)) = ({len(y)}, {len(x)})")
    gen = contourpy.contour_generator(np.asarray(x, float), np.asarray(y, float), Z, line_type="Separate")
    out = []
    for z in np.asarray(levels, dtype=float).ravel():
        for line in gen.lines(float(z)):
            if len(line) >= 2:
                out.append((float(z), np.asarray(line)))
    return out


@dataclass(frozen=True)
class ContourAccuracy:
    """How far the contours drawn from a DEM are from the true surface, in height.

    Along every contour (level z) the true height Z is sampled at the midpoints of its segments;
    Z − z is the contour's height error there, weighted by the segment's length.

    Attributes
    ----------
    rms_m, mean_abs_m, max_abs_m : RMS, mean |error| (средняя погрешность), largest |error|, m
    length_m : total length of the contours, m
    n_lines : number of contour lines
    """

    rms_m: float
    mean_abs_m: float
    max_abs_m: float
    length_m: float
    n_lines: int


@V.checked(lines=V.sequence())
def contour_accuracy(terrain, lines: list) -> ContourAccuracy:
    """The height errors of contours ``lines`` (from :func:`contour_lines`) against ``terrain``."""
    terrain = g.as_terrain(terrain)
    if not lines:
        return ContourAccuracy(math.nan, math.nan, math.nan, 0.0, 0)
    mids, lens, lev = [], [], []
    for z, P in lines:
        mids.append((P[1:] + P[:-1]) / 2.0)
        L = np.hypot(*(P[1:] - P[:-1]).T)
        lens.append(L)
        lev.append(np.full(len(L), z))
    M = np.vstack(mids)
    w = np.concatenate(lens)
    e = np.asarray(terrain.height(M[:, 0], M[:, 1]), dtype=float) - np.concatenate(lev)
    W = w.sum()
    if W <= 0:
        return ContourAccuracy(math.nan, math.nan, math.nan, 0.0, len(lines))
    return ContourAccuracy(float(np.sqrt(np.sum(w * e * e) / W)), float(np.sum(w * np.abs(e)) / W),
                           float(np.max(np.abs(e))), float(W), len(lines))


@V.checked(dem=DEM)
def dem_accuracy(terrain, dem: DEM, points_xy) -> np.ndarray:
    """Errors DEM − truth at check points (k, 2), m (k,)."""
    P = check_points("points_xy", points_xy, min_points=1)
    return dem.height(P[:, 0], P[:, 1]) - np.asarray(g.as_terrain(terrain).height(P[:, 0], P[:, 1]), dtype=float)


def predicted_rms(interp_rms_m: float, mz_m: float, kind: str) -> float:
    """√(m_interp² + k·m_z²): the expected RMS of a DEM between its nodes (k from :data:`NOISE_FACTOR`), m.

    ``interp_rms_m`` is the error the interpolation alone makes (error-free nodes), ``mz_m`` the RMS
    error of the node heights; the two are independent.
    """
    if kind not in NOISE_FACTOR:
        raise ValueError(f"kind = {kind!r} is not one of the valid choices {sorted(NOISE_FACTOR)}")
    a = check_range("interp_rms_m", interp_rms_m, 0.0, 1e4, unit="m")
    b = check_range("mz_m", mz_m, 0.0, 1e4, unit="m")
    return math.sqrt(a * a + NOISE_FACTOR[kind] * b * b)


def correlated_noise_factor(spacing_m: float, corr_length_m: float, *, samples: int = 40) -> float:
    """Mean over a grid square of Var(Σ wᵢ·εᵢ)/m_z² for bilinear interpolation when the node errors εᵢ are
    correlated, ρ(r) = exp(−r/L) between nodes r apart (article 000's densification, block deformation).

    ``corr_length_m`` L = 0 gives independent node errors, :data:`NOISE_FACTOR` ``["grid"]`` = 4/9; L ≫ the step
    gives 1 — a deformation common to neighbouring nodes is carried whole into the contours, interpolation
    averages nothing away.  ``spacing_m`` is the grid step d, m (> 0); the mean is taken over
    ``samples`` × ``samples`` cell midpoints of the square (exact for L = 0 up to O(1/samples²)).
    """
    d = check_range("spacing_m", spacing_m, 1e-3, 1e5, unit="m")
    L = check_range("corr_length_m", corr_length_m, 0.0, 1e9, unit="m")
    k = int(check_range("samples", samples, 4, 400))
    u = (np.arange(k) + 0.5) / k
    U, V = np.meshgrid(u, u)
    W = np.stack([(1 - U) * (1 - V), U * (1 - V), (1 - U) * V, U * V], axis=-1).reshape(-1, 4)  # (k², 4)
    corners = np.array([[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]]) * d
    r = np.hypot(*(corners[:, None, :] - corners[None, :, :]).transpose(2, 0, 1))
    C = np.eye(4) if L == 0.0 else np.exp(-r / L)
    return float(np.mean(np.einsum("pi,ij,pj->p", W, C, W)))


def standard_interval(mean_error_m: float, ratio: float = 0.3) -> float:
    """The smallest standard contour interval h with mean error ≤ ratio·h, m.

    Article 000 requires a mean error of 15 cm for h = 0.5 m, i.e. ratio = 0.3.
    """
    e = check_range("mean_error_m", mean_error_m, 0.0, 30.0, unit="m")
    k = check_range("ratio", ratio, 0.01, 1.0)
    for h in STANDARD_INTERVALS_M:
        if e <= k * h + 1e-12:
            return h
    raise ValueError(f"mean_error_m = {e:g} needs an interval above {STANDARD_INTERVALS_M[-1]:g} m; "
                     f"the valid range is mean_error_m ≤ {k * STANDARD_INTERVALS_M[-1]:g}")


# --------------------------------------------------------------------------- one DEM on one sheet
@dataclass(frozen=True, eq=False)
class SheetResult:
    """A DEM on a sheet, evaluated: its raster, its contours and their accuracy against the truth.

    Attributes
    ----------
    dem : :class:`DEM`
    x, y : raster coordinates, m
    Z_dem, Z_true : ndarray (ny, nx) — the DEM and the true surface on the raster, m
    interval_m : contour interval h, m
    contours : list of (level, (k, 2)) — the DEM's contours
    accuracy : :class:`ContourAccuracy` of those contours
    Z_interp : ndarray (ny, nx) — the DEM through the true node heights (interpolation error only), m
    """

    dem: DEM
    x: np.ndarray
    y: np.ndarray
    Z_dem: np.ndarray
    Z_true: np.ndarray
    interval_m: float
    contours: list
    accuracy: ContourAccuracy
    Z_interp: np.ndarray = None

    @property
    def raster_rms_m(self) -> float:
        """RMS of DEM − truth over the raster, m."""
        return float(np.sqrt(np.mean((self.Z_dem - self.Z_true) ** 2)))

    @property
    def interp_rms_m(self) -> float:
        """RMS over the raster of the DEM through the *true* node heights − truth: the interpolation alone, m."""
        return float(np.sqrt(np.mean((self.Z_interp - self.Z_true) ** 2)))

    @property
    def predicted_m(self) -> float:
        """:func:`predicted_rms` for this DEM: √(m_interp² + k·m_z²), m."""
        return predicted_rms(self.interp_rms_m, self.dem.mz_m, self.dem.kind)

    def table(self) -> pd.DataFrame:
        a = self.accuracy
        rows = [("DEM nodes", "", self.dem.n_nodes), ("contour interval h", "m", self.interval_m),
                ("contour lines", "", a.n_lines), ("RMS of contour heights", "m", a.rms_m),
                ("mean |error| of contour heights", "m", a.mean_abs_m), ("largest |error|", "m", a.max_abs_m),
                ("RMS of DEM − truth over the sheet", "m", self.raster_rms_m),
                ("… interpolation alone (error-free nodes)", "m", self.interp_rms_m),
                ("… predicted √(m_interp² + k·m_z²)", "m", self.predicted_m)]
        return pd.DataFrame(rows, columns=["quantity", "unit", "value"]).set_index("quantity")


@V.checked(sheet=Sheet, dem=DEM)
def evaluate(terrain, sheet: Sheet, dem: DEM, interval_m: float, *, cell_m: float = 5.0, Z_true=None) -> SheetResult:
    """Draw the DEM's contours at interval h on a raster of ``cell_m`` and measure them against ``terrain``.

    ``Z_true`` may pass the true surface on the same raster (to save its computation).
    """
    terrain = g.as_terrain(terrain)
    x, y = sheet.raster(cell_m)
    XX, YY = np.meshgrid(x, y)
    if Z_true is None:
        Z_true = np.asarray(terrain.height(XX, YY), dtype=float)
    both = dem.heights(XX, YY)
    Zd, Z0 = both[..., 0], both[..., 1]
    if not np.all(np.isfinite(Zd)):
        raise ValueError("the DEM does not cover the sheet (a TIN's hull falls short of its edge); "
                         "include the sheet's corners among the nodes")
    lv = contour_levels(float(np.min(Zd)), float(np.max(Zd)), interval_m)
    lines = contour_lines(x, y, Zd, lv)
    return SheetResult(dem, x, y, Zd, Z_true, float(interval_m), lines, contour_accuracy(terrain, lines), Z0)


@V.checked(terrain=V.terrain(), sheet=Sheet, spacings_m=V.sequence(V.number(1.0, 200.0), min_len=1))
def spacing_study(terrain, sheet: Sheet, spacings_m=(20.0, 30.0, 50.0, 100.0, 150.0), *, mz_m: float = 0.12,
                  interval_m: float = 0.5, cell_m: float = 5.0, seed: int = 0, lines: StructuralLines | None = None,
                  progress=None) -> pd.DataFrame:
    """RMS of contour heights against the grid step d: the regular grid, the grid with structural lines, and
    the structural model at about the grid's density — each with node errors m_z and without.

    Returns one row per step: ``d, m``; ``nodes (grid)``, ``nodes (grid + lines)``, ``nodes (structural)``;
    ``grid``, ``grid + lines``, ``structural`` (with m_z) and the same three with ``, m_z = 0``;
    ``predicted grid`` — √(m_interp² + 4/9·m_z²) from the error-free grid.  ``progress``, if given, is
    called with a line of text after each step (e.g. ``print``).
    """
    terrain = g.as_terrain(terrain)
    lines = structural_lines(terrain, sheet) if lines is None else lines
    x, y = sheet.raster(cell_m)
    Zt = np.asarray(terrain.height(*np.meshgrid(x, y)), dtype=float)
    rows = []
    for d in spacings_m:
        row = {"d, m": float(d)}
        for mz, suffix in ((mz_m, ""), (0.0, ", m_z = 0")):
            dems = {"grid": grid_dem(terrain, sheet, d, mz_m=mz, seed=seed),
                    "grid + lines": grid_with_lines(terrain, sheet, d, lines, mz_m=mz, seed=seed),
                    "structural": structural_dem(terrain, sheet, d, lines, mz_m=mz, seed=seed)}
            for name, dm in dems.items():
                r = evaluate(terrain, sheet, dm, interval_m, cell_m=cell_m, Z_true=Zt)
                row[name + suffix] = r.accuracy.rms_m
                if mz == mz_m:
                    row[f"nodes ({name})"] = dm.n_nodes
                    if name == "grid":
                        row["predicted grid"] = r.predicted_m
        rows.append(row)
        if progress is not None:
            progress(f"d = {float(d):g} m done ({len(rows)}/{len(spacings_m)})")
    cols = ["d, m", "nodes (grid)", "nodes (grid + lines)", "nodes (structural)", "grid", "grid + lines", "structural",
            "predicted grid", "grid, m_z = 0", "grid + lines, m_z = 0", "structural, m_z = 0"]
    return pd.DataFrame(rows)[cols]
