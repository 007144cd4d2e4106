"""Objects with height on the virtual site: houses, trees, forest canopy, tall structures, an embankment.

The DEM (:meth:`aerophoto.site.Site.height`) is the bare earth.  What stands on
it is kept here, as exact 3-D geometry that :mod:`aerophoto.render` ray-casts,
so that a photo shows every object leaning away from the nadir point by
δh = r·h/H (guide §4) and hiding what stands behind it:

=====================  ==========================================================  ==================
object                 shape                                                       kind code
=====================  ==========================================================  ==================
house                  a box on its footprint (the village's roofs of the          ``house``
                       texture); the bright roofs gabled (ridge along the longer
                       side, pitch 25–40°, eaves 2.8–3.6 m), the dark ones flat
                       (3–7 m)
chimney                a tapered 12-sided prism, 42 m                              ``chimney``
mast                   a thin 12-sided prism (radio mast), 64 m                    ``mast``
water tower            a shaft (18 m) and a tank (18–24 m), two prisms             ``water tower``
embankment             the paved road on a 4 m embankment across the river's       ``embankment``
                       floodplain (trapezoid, slopes 1:1.5, ramps at the ends)
bridge                 the road's deck over the water (1.5 m thick)                ``bridge``
tree                   an ellipsoid crown on each single tree of the texture        ``tree``
                       (10–20 m)
garden tree            small ellipsoid crowns in the gardens (4–8 m)               ``garden tree``
forest canopy          a height field over the forest land cover: stands of        —
                       14–24 m, crowns higher where the texture's crowns are
                       bright (:attr:`SiteObjects.canopy_dm`, decimetres)
=====================  ==========================================================  ==================

Houses, structures, the embankment and the bridge are **convex polyhedra**: the
solid ``n·x ≤ d`` of up to :data:`MAX_PLANES` planes (``planes[k]``, rows
(n_x, n_y, n_z, d); unused rows are (0, 0, 0, 1)).  Each plane carries the
:data:`SURFACES` code of its face and whether its brightness comes from the
ground texture (the embankment and the deck show the road painted there).
Crowns are **ellipsoids** with a horizontal semi-axis r and a vertical one c.
Object numbers run over the polyhedra first, then the ellipsoids; the canopy
is not an object (its pixels carry object −1).

Heights: every object stands on the DEM; its ``height_m`` in :meth:`SiteObjects.table`
is its top above the ground at its centre.  The points a photogrammetrist
measures on them — roof corners, ridge ends, tree tops, the tops of the
chimney, the mast and the tower — are :func:`object_points`, appended after the
ground catalogue in :attr:`aerophoto.site.Site.all_points`.

The intersection functions here (:func:`hit_polyhedra`, :func:`hit_ellipsoids`,
:func:`march_canopy`) take rays ``S + u·D`` (S, D in ground metres, u ≥ 0) and
return the entry depth u; the renderer and :meth:`aerophoto.site.Site.surface_height`
use them.  Data and geometry only (layer 3).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass, field, replace

import numpy as np
import pandas as pd

from .paint import bilinear, seg_distance
from .raycast import hit_ellipsoids, hit_polyhedra, march_canopy, shading

__all__ = ["SURFACES", "OBJECT_KINDS", "POINT_KINDS", "MAX_PLANES", "CANOPY_DM_MAX", "SiteObjects",
           "build_objects", "object_points", "hit_polyhedra", "hit_ellipsoids", "march_canopy", "shading"]

#: what a ray hit (:attr:`aerophoto.render.Photo.surface`)
SURFACES = {0: "ground", 1: "roof", 2: "wall", 3: "tree crown", 4: "forest canopy", 5: "structure",
            6: "embankment", 7: "bottom"}
#: kinds of objects (:meth:`SiteObjects.table`)
OBJECT_KINDS = ("house", "chimney", "mast", "water tower", "embankment", "bridge", "tree", "garden tree")
#: kinds of the object points appended after the ground catalogue's kinds (:func:`object_points`)
POINT_KINDS = ("roof corner", "ridge end", "tree top", "chimney top", "mast top", "tower top")
MAX_PLANES = 14
#: the tallest canopy the uint8 raster holds, decimetres
CANOPY_DM_MAX = 255
_PAD = np.array([0.0, 0.0, 0.0, 1.0])
_CELL_M = 32.0  # cell of the object index and of the coarse canopy mask


# =========================================================================== the data
@dataclass(frozen=True, eq=False, repr=False)
class SiteObjects:
    """Everything on the site that has a height of its own (see the module notes).

    Attributes
    ----------
    planes : ndarray (K, 14, 4)
        Convex polyhedra ``n·x ≤ d``, ground metres; unused rows (0, 0, 0, 1).
    face : ndarray (K, 14) uint8
        :data:`SURFACES` code of each plane's face.
    textured : ndarray (K, 14) bool
        The face's brightness is the ground texture at the hit (embankment, deck).
    albedo : ndarray (K, 2) float32
        Brightness 0…1 of roof/top faces and of walls/sides.
    kind : ndarray (K + E,) int
        Index into :data:`OBJECT_KINDS`.
    centre_m : ndarray (K + E, 2)
        X, Y of each object's centre (of its top for the structures).
    ground_Z_m, top_Z_m : ndarray (K + E,)
        Ground height at the centre and the highest point, metres.
    bbox : ndarray (K + E, 6)
        X min, X max, Y min, Y max, Z min, Z max (Z min is the lowest ground under the object).
    ell_centre : ndarray (E, 3), ell_radii : ndarray (E, 2), ell_albedo : ndarray (E,) float32
        Crowns: centre, (horizontal r, vertical c) semi-axes, brightness.
    canopy_dm : ndarray (ny, nx) uint8
        Forest canopy height over the ground, decimetres, on the texture grid (0 off forest).
    texel_m : float
        Size of a canopy texel (the texture's), metres.
    names : tuple of str
        A name per object ("house 12", "chimney", …).
    crowns : :class:`aerophoto.site.crowns.Crowns` or None
        The crowns the canopy was stamped from, when the site keeps them (the interpretation site of chapter 08):
        the renderer then shades a canopy pixel by its crown's surface normal instead of the raster's slope.
    """

    planes: np.ndarray
    face: np.ndarray
    textured: np.ndarray
    albedo: np.ndarray
    kind: np.ndarray
    centre_m: np.ndarray
    ground_Z_m: np.ndarray
    top_Z_m: np.ndarray
    bbox: np.ndarray
    ell_centre: np.ndarray
    ell_radii: np.ndarray
    ell_albedo: np.ndarray
    canopy_dm: np.ndarray
    texel_m: float
    names: tuple
    points: pd.DataFrame = field(default=None)
    crowns: object = None
    _index: dict = field(default_factory=dict, repr=False)

    def __repr__(self) -> str:
        counts = pd.Series([OBJECT_KINDS[k] for k in self.kind]).value_counts()
        text = ", ".join(f"{n} {k}" for k, n in counts.items())
        return f"SiteObjects({text}; canopy up to {self.canopy_max_m:.1f} m)"

    # ---- sizes
    @property
    def n_polyhedra(self) -> int:
        return int(self.planes.shape[0])

    @property
    def n_ellipsoids(self) -> int:
        return int(self.ell_centre.shape[0])

    def __len__(self) -> int:
        return self.n_polyhedra + self.n_ellipsoids

    @functools.cached_property
    def canopy_max_m(self) -> float:
        """The tallest canopy, metres (found once: the raster is read-only)."""
        if "canopy_max" not in self._index:
            self._index["canopy_max"] = float(self.canopy_dm.max()) * 0.1 if self.canopy_dm.size else 0.0
        return self._index["canopy_max"]

    @property
    def height_m(self) -> np.ndarray:
        """Top above the ground at the centre, metres, per object."""
        return self.top_Z_m - self.ground_Z_m

    @property
    def z_max_m(self) -> float:
        """The highest point of any object, metres."""
        return float(self.top_Z_m.max()) if len(self) else -np.inf

    def table(self) -> pd.DataFrame:
        """One row per object: kind, name, centre X, Y, ground Z, top Z and height, metres (index ``object``)."""
        return pd.DataFrame({"kind": [OBJECT_KINDS[k] for k in self.kind], "name": list(self.names),
                             "X_m": self.centre_m[:, 0], "Y_m": self.centre_m[:, 1], "ground_Z_m": self.ground_Z_m,
                             "top_Z_m": self.top_Z_m, "height_m": self.height_m},
                            index=pd.RangeIndex(len(self), name="object"))

    # ---- the coarse look-ups
    def coarse_canopy(self, cell_m: float = 8.0, dilate: int = 2) -> tuple:
        """Where forest may be: ``(mask, cell)``, a bool raster of ``cell_m`` cells grown by ``dilate`` cells (cached)."""
        key = ("canopy", float(cell_m), int(dilate))
        if key not in self._index:
            from scipy.ndimage import maximum_filter

            base = ("canopy", float(cell_m), 0)
            if base not in self._index:
                k = max(int(round(cell_m / self.texel_m)), 1)
                ny, nx = self.canopy_dm.shape
                cy, cx = -(-ny // k), -(-nx // k)
                pad = np.zeros((cy * k, cx * k), np.uint8)
                pad[:ny, :nx] = self.canopy_dm
                coarse = pad.reshape(cy, k, cx, k).max(axis=(1, 3)) > 0
                coarse.flags.writeable = False
                self._index[base] = (coarse, k * self.texel_m)
            coarse, cell = self._index[base]
            if dilate > 0:
                coarse = maximum_filter(coarse, size=2 * int(dilate) + 1, mode="constant", cval=False)
                coarse.flags.writeable = False
            self._index[key] = (coarse, cell)
        return self._index[key]

    def near_canopy(self, X, Y, *, reach_m: float = 16.0) -> np.ndarray:
        """Bool mask: ground points (X, Y) that may lie within ``reach_m`` of a forest texel (8 m cells)."""
        cell = 8.0
        coarse, cell = self.coarse_canopy(cell, int(math.ceil(reach_m / cell)))
        cy, cx = coarse.shape
        c = np.clip(np.floor(np.asarray(X, float) / cell).astype(np.int64), 0, cx - 1)
        r = np.clip(np.floor(np.asarray(Y, float) / cell).astype(np.int64), 0, cy - 1)
        return coarse[r, c]

    def canopy_at(self, X, Y) -> np.ndarray:
        """Canopy height over the ground, metres: that of the texel holding (X, Y) (0 off the forest).

        The canopy is a raster of 2 m columns (the texture's texels); the
        renderer and :meth:`surface_height` use the same columns.  Off the
        site, the nearest edge texel's.  float32 for float32 input, else float64.
        """
        X = np.asarray(X)
        Y = np.asarray(Y)
        ny, nx = self.canopy_dm.shape
        inv = 1.0 / self.texel_m
        c = (X * inv).astype(np.int64)
        r = (Y * inv).astype(np.int64)
        np.clip(c, 0, nx - 1, out=c)
        np.clip(r, 0, ny - 1, out=r)
        out = self.canopy_dm[r, c].astype(np.float32 if X.dtype == np.float32 else np.float64)
        out *= 0.1
        return out

    def _grid(self):
        """CSR index of the objects' ground boxes on 32 m cells: (cells x, cells y, start, objects)."""
        if "grid" not in self._index:
            bb = self.bbox
            x0, y0 = float(bb[:, 0].min()), float(bb[:, 2].min())
            nx = int((bb[:, 1].max() - x0) // _CELL_M) + 1
            ny = int((bb[:, 3].max() - y0) // _CELL_M) + 1
            c0 = ((bb[:, 0] - x0) // _CELL_M).astype(np.int64)
            c1 = ((bb[:, 1] - x0) // _CELL_M).astype(np.int64)
            r0 = ((bb[:, 2] - y0) // _CELL_M).astype(np.int64)
            r1 = ((bb[:, 3] - y0) // _CELL_M).astype(np.int64)
            cells, objs = [], []
            for k in range(len(bb)):
                rr, cc = np.meshgrid(np.arange(r0[k], r1[k] + 1), np.arange(c0[k], c1[k] + 1), indexing="ij")
                cells.append((rr * nx + cc).ravel())
                objs.append(np.full(rr.size, k))
            cells = np.concatenate(cells)
            objs = np.concatenate(objs)
            order = np.argsort(cells, kind="stable")
            start = np.searchsorted(cells[order], np.arange(nx * ny + 1))
            self._index["grid"] = (x0, y0, nx, ny, start, objs[order])
        return self._index["grid"]

    def candidates_at(self, X, Y) -> tuple:
        """(object, point) pairs whose ground box may contain the points (X, Y) (flat arrays)."""
        x0, y0, nx, ny, start, objs = self._grid()
        X = np.asarray(X, float).ravel()
        Y = np.asarray(Y, float).ravel()
        c = np.floor((X - x0) / _CELL_M).astype(np.int64)
        r = np.floor((Y - y0) / _CELL_M).astype(np.int64)
        ok = (c >= 0) & (c < nx) & (r >= 0) & (r < ny)
        cell = np.where(ok, r * nx + c, 0)
        n = np.where(ok, start[cell + 1] - start[cell], 0).astype(np.intp)  # intp: repeat counts on wasm32 too
        pts = np.repeat(np.arange(len(X)), n)
        first = np.repeat(start[cell] - np.cumsum(n) + n, n)
        k = objs[first + np.arange(len(pts))]
        bb = self.bbox[k]
        inside = (X[pts] >= bb[:, 0]) & (X[pts] <= bb[:, 1]) & (Y[pts] >= bb[:, 2]) & (Y[pts] <= bb[:, 3])
        return k[inside], pts[inside]

    # ---- the surface
    def surface_height(self, dem_height, X, Y) -> np.ndarray:
        """The top of everything at X, Y (metres): max of the ground, the canopy and the objects.

        ``dem_height`` is the bare-earth ``height(X, Y)``.
        """
        X = np.asarray(X, float)
        Y = np.asarray(Y, float)
        X, Y = np.broadcast_arrays(X, Y)
        Xf, Yf = X.ravel(), Y.ravel()
        Z = np.asarray(dem_height(Xf, Yf), float)
        if self.canopy_dm.size:
            Z = Z + self.canopy_at(Xf, Yf)
        if len(self):
            k, i = self.candidates_at(Xf, Yf)
            top = self.top_Z_m.max() + 10.0
            S = np.column_stack([Xf[i], Yf[i], np.full(len(i), top)])
            D = np.broadcast_to(np.array([0.0, 0.0, -1.0]), S.shape)
            u = np.full(len(i), np.inf)
            poly = k < self.n_polyhedra
            if poly.any():
                u[poly] = hit_polyhedra(self.planes, k[poly], S[poly], D[poly])[0]
            if (~poly).any():
                e = k[~poly] - self.n_polyhedra
                u[~poly] = hit_ellipsoids(self.ell_centre[e], self.ell_radii[e], S[~poly], D[~poly])[0]
            hit = np.isfinite(u)
            np.maximum.at(Z, i[hit], top - u[hit])
        return Z.reshape(X.shape)


# =========================================================================== building them
class _Poly:
    """Collects convex polyhedra while the objects are built."""

    def __init__(self):
        self.planes, self.face, self.tex, self.albedo, self.kind, self.centre = [], [], [], [], [], []
        self.ground, self.top, self.bbox, self.names = [], [], [], []

    def add(self, planes, faces, textured, albedo, kind, centre, ground_z, top_z, bbox, name):
        P = np.tile(_PAD, (MAX_PLANES, 1))
        P[:len(planes)] = planes
        F = np.zeros(MAX_PLANES, np.uint8)
        F[:len(faces)] = faces
        T = np.zeros(MAX_PLANES, bool)
        T[:len(textured)] = textured
        self.planes.append(P)
        self.face.append(F)
        self.tex.append(T)
        self.albedo.append(albedo)
        self.kind.append(OBJECT_KINDS.index(kind))
        self.centre.append(centre)
        self.ground.append(ground_z)
        self.top.append(top_z)
        self.bbox.append(bbox)
        self.names.append(name)


def _plane(n, point):
    """Plane n·x ≤ n·point with the normal normalised."""
    n = np.asarray(n, float)
    n = n / np.linalg.norm(n)
    return np.r_[n, n @ np.asarray(point, float)]


def _box_planes(c, du, hw, hd, z_bottom, z_top, ridge=None):
    """Walls of a rotated box, its bottom and either a flat top or two gable roof planes (ridge along du)."""
    dv = np.array([-du[1], du[0]])
    c3 = np.r_[c, 0.0]
    planes = [_plane(np.r_[du, 0.0], c3 + np.r_[du * hw, 0.0]), _plane(np.r_[-du, 0.0], c3 - np.r_[du * hw, 0.0]),
              _plane(np.r_[dv, 0.0], c3 + np.r_[dv * hd, 0.0]), _plane(np.r_[-dv, 0.0], c3 - np.r_[dv * hd, 0.0]),
              _plane([0.0, 0.0, -1.0], [c[0], c[1], z_bottom])]
    faces = [2, 2, 2, 2, 7]
    if ridge is None:
        planes.append(_plane([0.0, 0.0, 1.0], [c[0], c[1], z_top]))
        faces.append(1)
    else:
        s = (ridge - z_top) / hd  # rise per metre across the ridge
        for sgn in (1.0, -1.0):
            planes.append(_plane(np.r_[sgn * s * dv, 1.0], [c[0], c[1], ridge]))
            faces.append(1)
    return np.array(planes), faces


def _prism_planes(c, r_bottom, r_top, z_bottom, z_top, sides=12):
    """A (tapered) regular prism about a vertical axis: ``sides`` side planes, bottom and top."""
    planes, faces = [], []
    for j in range(sides):
        a = 2 * math.pi * (j + 0.5) / sides
        e = np.array([math.cos(a), math.sin(a)])
        # the side through the edge at r_bottom (z_bottom) and r_top (z_top), apothems of the polygons
        ab, at = r_bottom * math.cos(math.pi / sides), r_top * math.cos(math.pi / sides)
        n = np.r_[e * (z_top - z_bottom), ab - at]
        planes.append(_plane(n, np.r_[c + e * ab, z_bottom]))
        faces.append(5)
    planes.append(_plane([0.0, 0.0, -1.0], [c[0], c[1], z_bottom]))
    planes.append(_plane([0.0, 0.0, 1.0], [c[0], c[1], z_top]))
    return np.array(planes), faces + [7, 5]


def _clear_spot(rng, centre, r_lo, r_hi, ok, tries=400):
    """A point r_lo…r_hi from ``centre`` for which ``ok(p)`` holds (the first of ``tries`` seeded draws)."""
    for _ in range(tries):
        a = rng.uniform(0, 2 * math.pi)
        r = rng.uniform(r_lo, r_hi)
        p = np.asarray(centre, float) + r * np.array([math.cos(a), math.sin(a)])
        if ok(p):
            return p
    return None


def build_objects(b, dem: np.ndarray, river, roads: list, village_c, tex: np.ndarray, cover: np.ndarray, *,
                  first_id: int = 1) -> SiteObjects:
    """Raise the site's objects on the DEM (the last step of :func:`aerophoto.site.build.build_site`).

    ``b`` is the :class:`~aerophoto.site.build.Builder` after the painting
    steps (it holds the houses', trees' and garden trees' sizes and tones);
    new random numbers come from its ``rng_objects`` stream only, so the
    ground texture, the land cover and the catalogue stay exactly as before.
    The objects' measurable points (:func:`object_points`) get ids from ``first_id``.
    """
    from .model import COVER_CODES as C

    rng = b.rng_objects
    P, W, Hs, t, s = b.params, b.W, b.Hs, b.t, b.s

    def ground(xy):
        xy = np.asarray(xy, float).reshape(-1, 2)
        return bilinear(dem, xy[:, 0] / s, xy[:, 1] / s)

    poly = _Poly()
    _raise_houses(poly, b, rng, ground)
    clear = _open_ground(b, river, roads, cover)
    _raise_structures(poly, rng, village_c, clear, ground, W, Hs)
    # ---- the embankment and bridge of the paved road that crosses the river
    _embankment(poly, [r for r in roads if r["kind"] == "paved"], river, ground)
    n_poly = len(poly.planes)
    ell_c, ell_r, ell_alb, ell_ground, ell_top, e_kind, e_names = _crowns(b, rng, ground)
    ell_bbox = np.column_stack([ell_c[:, 0] - ell_r[:, 0], ell_c[:, 0] + ell_r[:, 0], ell_c[:, 1] - ell_r[:, 0],
                                ell_c[:, 1] + ell_r[:, 0], ell_ground - 0.5, ell_top])
    # ---- the forest canopy: stands of 14–24 m; crowns higher where the texture's crowns are bright
    canopy = _canopy(rng, tex, cover == C["forest"], t)
    objs = SiteObjects(
        planes=np.array(poly.planes).reshape(-1, MAX_PLANES, 4),
        face=np.array(poly.face, np.uint8).reshape(-1, MAX_PLANES),
        textured=np.array(poly.tex, bool).reshape(-1, MAX_PLANES),
        albedo=np.array(poly.albedo, np.float32).reshape(-1, 2),
        kind=np.array(poly.kind + e_kind, np.int64),
        centre_m=np.vstack([np.array(poly.centre, float).reshape(-1, 2), ell_c[:, :2]]),
        ground_Z_m=np.r_[np.array(poly.ground, float), ell_ground],
        top_Z_m=np.r_[np.array(poly.top, float), ell_top],
        bbox=np.vstack([np.array(poly.bbox, float).reshape(-1, 6), ell_bbox]),
        ell_centre=ell_c, ell_radii=ell_r, ell_albedo=ell_alb, canopy_dm=canopy, texel_m=float(t),
        names=tuple(poly.names + e_names))
    assert objs.n_polyhedra == n_poly
    objs = replace(objs, points=object_points(objs, dem, P, first_id))
    for a in (objs.planes, objs.face, objs.textured, objs.albedo, objs.kind, objs.centre_m, objs.ground_Z_m,
              objs.top_Z_m, objs.bbox, objs.ell_centre, objs.ell_radii, objs.ell_albedo, objs.canopy_dm):
        a.flags.writeable = False
    return objs


def _raise_houses(poly: _Poly, b, rng, ground) -> None:
    """The houses: boxes on the painted roofs, gabled under the bright (slate, tin) roofs, flat under the dark
    ones; heights, pitch and wall tone from ``rng`` (the builder's object stream), in the houses' order."""
    hc, hh, ha = b.houses
    roof_tone = b.house_roof_tone
    for j, (c, (hw, hd), a) in enumerate(zip(hc, hh, ha)):
        du = np.array([math.cos(a), math.sin(a)])
        dv = np.array([-du[1], du[0]])
        corners = np.array([c + su * hw * du + sv * hd * dv for su in (-1, 1) for sv in (-1, 1)])
        zc = ground(corners)
        z_bottom = float(zc.min()) - 0.5
        gabled = roof_tone[j] > 0.7  # the bright (slate, tin) roofs; the dark ones are flat
        eaves_h = rng.uniform(2.8, 3.6) if gabled else rng.uniform(3.0, 7.0)
        pitch = math.radians(rng.uniform(25.0, 40.0))
        wall = rng.uniform(0.45, 0.75)
        z_eaves = float(zc.max()) + eaves_h
        if gabled:
            along, half_across, axis = (hw, hd, du) if hw >= hd else (hd, hw, dv)
            ridge = z_eaves + half_across * math.tan(pitch)
            planes, faces = _box_planes(c, axis, along, half_across, z_bottom, z_eaves, ridge)
            top = ridge
        else:
            planes, faces = _box_planes(c, du, hw, hd, z_bottom, z_eaves)
            top = z_eaves
        R = math.hypot(hw, hd)
        poly.add(planes, faces, [], (roof_tone[j], wall), "house", np.asarray(c, float), float(ground(c)[0]), top,
                 (c[0] - R, c[0] + R, c[1] - R, c[1] + R, z_bottom, top), f"house {j + 1}")


def _open_ground(b, river, roads: list, cover: np.ndarray):
    """A test of a place (X, Y in metres) for a tall structure: 300 m inside the site, 25 m from houses and
    roads, 150 m from the river, and fields, meadow or gardens all round (15 m)."""
    from .model import COVER_CODES as C

    W, Hs, t = b.W, b.Hs, b.t
    houses_xy = np.asarray(b.houses[0], float).reshape(-1, 2)

    def cover_near(p, radius):
        ring = [p] + [p + radius * np.array([math.cos(a), math.sin(a)]) for a in np.linspace(0, 2 * np.pi, 12, False)]
        xy = np.array(ring)
        c = np.clip(np.floor(xy[:, 0] / t).astype(int), 0, cover.shape[1] - 1)
        r = np.clip(np.floor(xy[:, 1] / t).astype(int), 0, cover.shape[0] - 1)
        return cover[r, c]

    def clear_of_things(p, min_house=25.0, min_road=25.0):
        if not (300.0 < p[0] < W - 300.0 and 300.0 < p[1] < Hs - 300.0):
            return False
        if len(houses_xy) and np.min(np.hypot(*(houses_xy - p).T)) < min_house:
            return False
        if any(seg_distance(p, *r["xy"]) < min_road for r in roads):
            return False
        if abs(p[1] - float(river.y(p[0]))) < 150.0:
            return False
        return bool(np.all(np.isin(cover_near(p, 15.0), [C["arable field"], C["meadow"], C["garden"]])))

    return clear_of_things


def _raise_structures(poly: _Poly, rng, village_c, clear_of_things, ground, W: float, Hs: float) -> None:
    """The tall structures: a chimney and a water tower near the village, a 64 m mast on open ground north of it
    (in the central photos' overlap), each at a random clear spot 120 m from the others."""
    vc = np.asarray(village_c, float)
    structures = (("chimney", 150.0, 450.0, dict(r_bottom=2.2, r_top=1.4, height=42.0, albedo=0.55)),
                  ("water tower", 150.0, 450.0, None),
                  ("mast", 500.0, 900.0, dict(r_bottom=1.2, r_top=1.2, height=64.0, albedo=0.75)))
    placed = []
    for kind, r_lo, r_hi, spec in structures:
        def ok(p):  # the mast: north of the village, near the middle of the site (in the central photos' overlap)
            return clear_of_things(p) and all(np.hypot(*(p - q)) > 120.0 for q in placed) and (
                kind != "mast" or (p[1] > vc[1] and abs(p[0] - W / 2) < 400.0 and p[1] < Hs / 2 + 700.0))
        p = _clear_spot(rng, vc, r_lo, r_hi, ok)
        if p is None:
            continue
        placed.append(p)
        z0 = float(ground(p)[0])
        zb = z0 - 0.5
        if kind == "water tower":
            planes, faces = _prism_planes(p, 1.6, 1.6, zb, z0 + 18.0)
            poly.add(planes, faces, [], (0.6, 0.6), kind, p, z0, z0 + 18.0,
                     (p[0] - 2, p[0] + 2, p[1] - 2, p[1] + 2, zb, z0 + 18.0), "water tower (shaft)")
            planes, faces = _prism_planes(p, 4.5, 4.5, z0 + 18.0, z0 + 24.0)
            poly.add(planes, faces, [], (0.62, 0.55), kind, p, z0, z0 + 24.0,
                     (p[0] - 5, p[0] + 5, p[1] - 5, p[1] + 5, z0 + 18.0, z0 + 24.0), "water tower (tank)")
        else:
            planes, faces = _prism_planes(p, spec["r_bottom"], spec["r_top"], zb, z0 + spec["height"])
            R = spec["r_bottom"] + 0.5
            poly.add(planes, faces, [], (spec["albedo"], spec["albedo"]), kind, p, z0, z0 + spec["height"],
                     (p[0] - R, p[0] + R, p[1] - R, p[1] + R, zb, z0 + spec["height"]), kind)


def _crowns(b, rng, ground) -> tuple:
    """The crowns of single trees (10–20 m) and garden trees (4–8 m) as ellipsoids on the ground.

    Returns ``(centre, radii, albedo, ground_Z, top_Z, kinds, names)``: shapes (E, 3) m, (E, 2) m (across, half
    depth), (E,) float32, (E,) m, (E,) m, and lists of E kind codes and names.
    """
    tr_xy, tr_r, tr_tone = b.tree_crowns
    gt_xy, gt_r, gt_tone = b.garden_crowns
    e_c, e_r, e_alb, e_kind, e_ground, e_top, e_names = [], [], [], [], [], [], []
    for label, xy, rad, tone, (h_lo, h_hi) in (("tree", tr_xy, tr_r, tr_tone, (10.0, 20.0)),
                                               ("garden tree", gt_xy, gt_r, gt_tone, (4.0, 8.0))):
        xy = np.asarray(xy, float).reshape(-1, 2)
        if not len(xy):
            continue
        z0 = ground(xy)
        h = rng.uniform(h_lo, h_hi, len(xy))
        depth = rng.uniform(0.45, 0.65, len(xy)) * h
        cz = z0 + h - depth / 2.0
        e_c.append(np.column_stack([xy, cz]))
        e_r.append(np.column_stack([rad, depth / 2.0]))
        e_alb.append(np.clip(np.asarray(tone) * 1.2, 0.0, 1.0))
        e_kind += [OBJECT_KINDS.index(label)] * len(xy)
        e_ground.append(z0)
        e_top.append(z0 + h)
        e_names += [f"{label} {j + 1}" for j in range(len(xy))]
    ell_c = np.vstack(e_c) if e_c else np.zeros((0, 3))
    ell_r = np.vstack(e_r) if e_r else np.zeros((0, 2))
    ell_alb = np.concatenate(e_alb).astype(np.float32) if e_alb else np.zeros(0, np.float32)
    ell_ground = np.concatenate(e_ground) if e_ground else np.zeros(0)
    ell_top = np.concatenate(e_top) if e_top else np.zeros(0)
    return ell_c, ell_r, ell_alb, ell_ground, ell_top, e_kind, e_names


def _canopy(rng, tex, forest, t) -> np.ndarray:
    """Canopy heights in decimetres (uint8) on the texture grid: stand height × crown relief from the texture."""
    ny, nx = tex.shape
    k = max(int(round(40.0 / t)), 1)  # stand heights vary over ~40 m cells, bilinear in between
    gy, gx = ny // k + 2, nx // k + 2
    stand = rng.uniform(14.0, 24.0, (gy, gx)).astype(np.float32)
    out = np.zeros((ny, nx), np.uint8)
    idx = np.flatnonzero(forest)
    if not len(idx):
        return out
    r, c = np.divmod(idx, nx)
    fy = (r.astype(np.float32) + 0.5) / k
    fx = (c.astype(np.float32) + 0.5) / k
    j0 = np.minimum(fy.astype(np.int64), gy - 2)
    i0 = np.minimum(fx.astype(np.int64), gx - 2)
    wy = fy - j0
    wx = fx - i0
    h = ((stand[j0, i0] * (1 - wx) + stand[j0, i0 + 1] * wx) * (1 - wy)
         + (stand[j0 + 1, i0] * (1 - wx) + stand[j0 + 1, i0 + 1] * wx) * wy)
    crown = np.clip((tex.reshape(-1)[idx].astype(np.float32) / 255.0 - 0.06) / 0.3, 0.0, 1.0)
    h *= 0.78 + 0.22 * crown
    out.reshape(-1)[idx] = np.rint(h * 10.0).astype(np.uint8)
    return out


def _embankment(poly: _Poly, paved: list, river, ground) -> None:
    """The paved road that crosses the river: a bridge deck over the water and embankments on the floodplain."""
    for road in paved:
        a, c = np.asarray(road["xy"][0], float), np.asarray(road["xy"][1], float)
        side_a, side_c = float(a[1] - river.y(a[0])), float(c[1] - river.y(c[0]))
        if side_a * side_c >= 0:
            continue
        L = float(np.hypot(*(c - a)))
        d = (c - a) / L
        lo, hi = 0.0, L
        for _ in range(60):  # the crossing of the river's centre line, by bisection
            mid = 0.5 * (lo + hi)
            p = a + mid * d
            if (p[1] - river.y(p[0])) * side_a > 0:
                lo = mid
            else:
                hi = mid
        s_c = 0.5 * (lo + hi)
        x_c = a + s_c * d
        z_top = float(ground(x_c)[0]) + 4.0  # the road's grade over the floodplain
        # the bridge spans the road's stretch within 25 m of the river's centre line (the water is ≤ 18 m wide
        # on each side), however obliquely the road crosses; the deck is 1.5 m thick
        ss = s_c + np.arange(-400.0, 400.5, 1.0)
        pts = a + ss[:, None] * d
        slope_r = np.gradient(river.y(pts[:, 0]), pts[:, 0])
        near = np.abs(pts[:, 1] - river.y(pts[:, 0])) / np.sqrt(1.0 + slope_r**2) < 25.0
        j = 400
        ja, jb = j, j
        while ja > 0 and near[ja - 1]:
            ja -= 1
        while jb < len(ss) - 1 and near[jb + 1]:
            jb += 1
        s_a, s_b = ss[ja] - 2.0, ss[jb] + 2.0
        deck = 1.5
        nrm = np.array([-d[1], d[0]])
        top_half, slope = 6.5, 1.5
        pieces = [("bridge", s_a, s_b, 0.0, 0.0)]
        for sgn in (-1.0, 1.0):  # embankments: 170 m level, then a 60 m ramp down to the floodplain
            s0 = s_b if sgn > 0 else s_a
            s1 = s0 + sgn * 170.0
            s2 = s1 + sgn * 60.0
            pieces.append(("embankment", min(s0, s1), max(s0, s1), 0.0, 0.0))
            pieces.append(("embankment ramp", min(s1, s2), max(s1, s2), sgn, 1.0))
        for name, s0, s1, sgn, ramp in pieces:
            s0, s1 = max(s0, 1.0), min(s1, L - 1.0)
            if s1 - s0 < 5.0:
                continue
            mid = a + 0.5 * (s0 + s1) * d
            z_lo = float(min(ground([a + s0 * d, a + s1 * d, mid]).min(), ground(x_c)[0])) - 1.0
            if name == "bridge":
                planes = [_plane(np.r_[d, 0.0], np.r_[a + s1 * d, 0.0]), _plane(np.r_[-d, 0.0], np.r_[a + s0 * d, 0.0]),
                          _plane(np.r_[nrm, 0.0], np.r_[x_c + nrm * 5.0, 0.0]),
                          _plane(np.r_[-nrm, 0.0], np.r_[x_c - nrm * 5.0, 0.0]),
                          _plane([0.0, 0.0, -1.0], [0.0, 0.0, z_top - deck]), _plane([0.0, 0.0, 1.0], [0.0, 0.0, z_top])]
                faces, textured = [6, 6, 6, 6, 7, 6], [False, False, False, False, False, True]
                albedo, kind, top, half = (0.4, 0.35), "bridge", z_top, 5.0
            else:
                # the crest falls by ``g`` per metre on a ramp (towards its outer end)
                g = 0.0
                s_ref = s0
                if ramp:
                    z_end = float(ground(a + (s1 if sgn > 0 else s0) * d)[0])
                    g = (z_top - z_end) / (s1 - s0)
                    s_ref = s0 if sgn > 0 else s1
                # crest: z ≤ z_top − g·sgn·(s − s_ref); sides: ±w ≤ top_half + slope·(crest − z)
                sl = np.r_[g * sgn * d, 1.0]
                crest = _plane(sl, np.r_[a + s_ref * d, z_top])
                planes = [_plane(np.r_[d, 0.0], np.r_[a + s1 * d, 0.0]), _plane(np.r_[-d, 0.0], np.r_[a + s0 * d, 0.0]),
                          crest, _plane([0.0, 0.0, -1.0], [0.0, 0.0, z_lo])]
                faces, textured = [6, 6, 6, 7], [False, False, True, False]
                for w in (nrm, -nrm):
                    # w·(x − x_ref) − slope·(z_top − g·sgn·(s − s_ref) − z) ≤ top_half
                    n = np.r_[w + slope * g * sgn * d, slope]
                    ref = np.r_[a + s_ref * d + w * top_half, z_top]
                    planes.append(_plane(n, ref))
                    faces.append(6)
                    textured.append(True)
                albedo, kind, top, half = (0.5, 0.5), "embankment", z_top, top_half + 4.0 * slope
            cz = float(ground(mid)[0])
            if name != "bridge":
                half = top_half + slope * (z_top - z_lo) + 0.5
            xs = [(a + s0 * d + sw * half * nrm) for sw in (-1, 1)] + [(a + s1 * d + sw * half * nrm) for sw in (-1, 1)]
            xs = np.array(xs)
            poly.add(np.array(planes), faces, textured, albedo, kind, mid, cz, top,
                     (xs[:, 0].min(), xs[:, 0].max(), xs[:, 1].min(), xs[:, 1].max(), z_lo, top), name)
        return


def object_points(objects: SiteObjects, dem: np.ndarray, params, first_id: int) -> pd.DataFrame:
    """The measurable points of the objects, as catalogue rows with the object's number and heights.

    Columns ``id`` (from ``first_id``), ``kind`` (:data:`POINT_KINDS`), ``X_m``,
    ``Y_m``, ``Z_m`` (the point itself), ``control`` (False), ``object`` (its
    row in :meth:`SiteObjects.table`), ``ground_Z_m`` (the DEM under it) and
    ``height_m`` (Z − ground).  Roof corners are the eaves corners of every
    house, ridge ends the ends of a gabled roof's ridge, tree tops the tops of
    the single trees (not the garden trees); points within 40 m of the site's
    edge are left out.  Sorted by kind, then X, Y, like the ground catalogue.
    """
    s = params.dem_spacing_m
    rows = []
    for k in range(objects.n_polyhedra):
        kind = OBJECT_KINDS[objects.kind[k]]
        P = objects.planes[k]
        if kind == "house":
            V = _vertices(P)
            top = objects.top_Z_m[k]
            eaves_z = V[:, 2][V[:, 2] > objects.bbox[k, 4] + 0.1].min()
            for v in V:
                if abs(v[2] - eaves_z) < 1e-6:
                    rows.append(("roof corner", v[0], v[1], v[2], k))
                elif abs(v[2] - top) < 1e-6 and top > eaves_z + 1e-6:
                    rows.append(("ridge end", v[0], v[1], v[2], k))
        elif kind in ("chimney", "mast") or objects.names[k] == "water tower (tank)":
            label = {"chimney": "chimney top", "mast": "mast top"}.get(kind, "tower top")
            rows.append((label, objects.centre_m[k, 0], objects.centre_m[k, 1], objects.top_Z_m[k], k))
    n_poly = objects.n_polyhedra
    for e in range(objects.n_ellipsoids):
        if OBJECT_KINDS[objects.kind[n_poly + e]] == "tree":
            c = objects.ell_centre[e]
            rows.append(("tree top", c[0], c[1], objects.top_Z_m[n_poly + e], n_poly + e))
    df = pd.DataFrame(rows, columns=["kind", "X_m", "Y_m", "Z_m", "object"])
    margin = 40.0
    keep = ((df["X_m"] > margin) & (df["X_m"] < params.width_m - margin) & (df["Y_m"] > margin)
            & (df["Y_m"] < params.height_m - margin))
    df = df[keep].copy()
    order = {k: i for i, k in enumerate(POINT_KINDS)}
    df["_k"] = df["kind"].map(order)
    df = df.sort_values(["_k", "X_m", "Y_m"], kind="stable").drop(columns="_k").reset_index(drop=True)
    gz = bilinear(dem, df["X_m"].to_numpy() / s, df["Y_m"].to_numpy() / s)
    df.insert(0, "id", np.arange(first_id, first_id + len(df)))
    df["control"] = False
    df["ground_Z_m"] = gz
    df["height_m"] = df["Z_m"] - gz
    return df[["id", "kind", "X_m", "Y_m", "Z_m", "control", "object", "ground_Z_m", "height_m"]]


def _vertices(planes) -> np.ndarray:
    """Vertices of a convex polyhedron given by its planes (triples of planes meeting inside all others)."""
    P = planes[np.any(planes[:, :3] != 0, axis=1)]
    out = []
    n = len(P)
    for i in range(n):
        for j in range(i + 1, n):
            for k in range(j + 1, n):
                A = P[[i, j, k], :3]
                if abs(np.linalg.det(A)) < 1e-9:
                    continue
                x = np.linalg.solve(A, P[[i, j, k], 3])
                if np.all(P[:, :3] @ x <= P[:, 3] + 1e-7):
                    out.append(x)
    V = np.array(out)
    # unique up to rounding
    key = np.round(V, 6)
    _, idx = np.unique(key, axis=0, return_index=True)
    return V[np.sort(idx)]
