"""The catalogue of well-defined ground points of a virtual site (the last step of :mod:`aerophoto.site.build`).

The points come from the same vector data the texture was painted from, and
only those that stay visible in the texture are kept: road crossings (the
intersection of two road centre lines, road on both roads 10 m away), field
corners (T-junctions of boundaries with fields all round), building corners
(the south-west roof corner, not covered by a later house) and trees (crown
centres).  Control points (опознаки, guide §11, §13) are the road crossings and
field corners nearest to a 1.5 km lattice over the site.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from .model import COVER_CODES, KINDS, SiteParams
from .paint import bilinear, seg_intersection

__all__ = ["catalogue", "CONTROL_SPACING_M"]

_C = COVER_CODES

#: spacing of the lattice the control points are chosen from, m
CONTROL_SPACING_M = 1500.0


def catalogue(dem: np.ndarray, cover: np.ndarray, params: SiteParams, *, roads, corners, houses, trees) -> tuple:
    """The catalogue of ground points and the roof outlines.

    Parameters
    ----------
    dem : (ny_dem, nx_dem) heights, m, nodes ``params.dem_spacing_m`` apart
    cover : (ny, nx) land-cover codes on the texture grid
    roads : list of road dicts (``xy`` (2, 2) centre-line segment, metres)
    corners : list of field-corner candidates (2,), metres
    houses : (centres (n, 2), half sizes (n, 2), angles (n,)) of the roofs, metres and radians
    trees : (k, 2) crown centres, metres

    Returns
    -------
    catalogue : pandas.DataFrame with id, kind, X_m, Y_m, Z_m, control (sorted by kind, then X, Y)
    roofs : (n, 4, 2) roof corners, metres
    """
    W, Hs, t, s = params.width_m, params.height_m, params.texture_m, params.dem_spacing_m
    ny, nx = cover.shape
    houses_c, houses_h, houses_a = houses

    def height_at(xy):
        xy = np.asarray(xy, float).reshape(-1, 2)
        return bilinear(dem, xy[:, 0] / s, xy[:, 1] / s)

    def cover_of(xy):
        xy = np.asarray(xy, float).reshape(-1, 2)
        c = np.clip(np.floor(xy[:, 0] / t).astype(int), 0, nx - 1)
        r = np.clip(np.floor(xy[:, 1] / t).astype(int), 0, ny - 1)
        return cover[r, c]

    rows = []
    margin = 40.0
    inside = lambda p: margin < p[0] < W - margin and margin < p[1] < Hs - margin  # noqa: E731
    road_codes = (_C["dirt road"], _C["paved road"])
    # road crossings: pairwise intersections of road centre lines, visible on both roads
    seen = []
    for i1 in range(len(roads)):
        for i2 in range(i1 + 1, len(roads)):
            a1, b1 = roads[i1]["xy"]
            a2, b2 = roads[i2]["xy"]
            p = seg_intersection(a1, b1, a2, b2)
            if p is None or not inside(p):
                continue
            d1 = (b1 - a1) / np.hypot(*(b1 - a1))
            d2 = (b2 - a2) / np.hypot(*(b2 - a2))
            if abs(d1[0] * d2[1] - d1[1] * d2[0]) < math.sin(math.radians(20)):
                continue  # too oblique or collinear joints of a polyline
            if any(np.hypot(*(p - q)) < 25.0 for q in seen):
                continue
            probe = [p]
            for dd in (d1, d2):
                for sgn in (-1, 1):
                    q = p + sgn * 10.0 * dd
                    if 0 < q[0] < W and 0 < q[1] < Hs:
                        probe.append(q)
            if len(probe) < 4 or not np.all(np.isin(cover_of(probe), road_codes)):
                continue
            seen.append(p)
            rows.append(("road crossing", p[0], p[1]))
    # field corners: T-junctions of boundaries, with fields all round
    for p in corners:
        if not inside(p):
            continue
        ring = [p + 12.0 * np.array([math.cos(a), math.sin(a)]) for a in np.linspace(0, 2 * np.pi, 8, endpoint=False)]
        cc = cover_of([p] + ring)
        if np.all(np.isin(cc, [_C["arable field"], _C["field boundary"]])):
            rows.append(("field corner", p[0], p[1]))
    # building corners: the south-west-most roof corner (sunlit, free of the shadow)
    bcorners = []
    every = max(1, len(houses_c) // 24)  # about two dozen building corners, spread over the village
    for h_i, (c, (hw, hd), a) in enumerate(zip(houses_c, houses_h, houses_a)):
        du = np.array([math.cos(a), math.sin(a)])
        dv = np.array([-math.sin(a), math.cos(a)])
        cs = np.array([c + su * hw * du + sv * hd * dv for su in (-1, 1) for sv in (-1, 1)])
        bcorners.append(cs[[0, 2, 3, 1]])
        if h_i % every == 0:
            k = int(np.argmin(cs[:, 0] + cs[:, 1]))
            rows.append(("building corner", cs[k, 0], cs[k, 1]))
    bcorners = np.array(bcorners).reshape(-1, 4, 2)
    for p in trees:
        rows.append(("tree", p[0], p[1]))
    cat = pd.DataFrame(rows, columns=["kind", "X_m", "Y_m"])
    cat = cat[[inside(p) for p in cat[["X_m", "Y_m"]].to_numpy()]]
    # keep buildings' corners that ended up visible (not covered by a later house)
    vis = np.ones(len(cat), bool)
    isb = (cat["kind"] == "building corner").to_numpy()
    if isb.any():
        inward = cat.loc[isb, ["X_m", "Y_m"]].to_numpy() + 1.2 * t
        vis[isb] = cover_of(inward) == _C["building"]
    cat = cat[vis].reset_index(drop=True)
    cat["Z_m"] = height_at(cat[["X_m", "Y_m"]].to_numpy())
    # control points: road crossings and field corners nearest to a lattice over the site
    cat["control"] = False
    elig = np.flatnonzero(cat["kind"].isin(["road crossing", "field corner"]).to_numpy())
    if len(elig):
        spacing = CONTROL_SPACING_M
        gx_ = np.arange(spacing / 2, W, spacing)
        gy_ = np.arange(spacing / 2, Hs, spacing)
        pts = cat[["X_m", "Y_m"]].to_numpy()[elig]
        chosen = set()
        for yy in gy_:
            for xx in gx_:
                d = np.hypot(pts[:, 0] - xx, pts[:, 1] - yy)
                k = int(np.argmin(d))
                if d[k] < spacing / 2:
                    chosen.add(int(elig[k]))
        cat.loc[sorted(chosen), "control"] = True
    kind_order = {k: i for i, k in enumerate(KINDS)}
    cat["_k"] = cat["kind"].map(kind_order)
    cat = cat.sort_values(["_k", "X_m", "Y_m"], kind="stable").drop(columns="_k").reset_index(drop=True)
    cat.insert(0, "id", np.arange(1, len(cat) + 1))
    cat = cat[["id", "kind", "X_m", "Y_m", "Z_m", "control"]]
    return cat, bcorners
