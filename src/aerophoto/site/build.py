"""Building a virtual site, step by step: relief, river, fields, forest, village, roads, texture, catalogue.

:func:`build_site` runs the named steps below in a fixed order.  The order is
part of the result: the steps draw from four seeded random streams
(``layout``, ``dem``, ``tex``, ``noise``, spawned from ``(seed, 20140)``), so
the same :class:`~aerophoto.site.model.SiteParams` give the same arrays, bit
for bit, only if every step draws the same numbers in the same order.  A step
may be changed only together with the test that pins the default site
(``tests/world/test_site.py``).

=====================  =====================================================  ============
step                   what it makes                                          streams
=====================  =====================================================  ============
:func:`river_line`     the river's centre line y_r(X): two sine waves         layout
:func:`relief`         the DEM: hills north and west, valley, plain           dem
:func:`fields`         two field systems (north and south of the river)       layout, tex
:func:`soil_noise`     soil-moisture mottling and the fine grain              noise
:func:`field_network`  field boundaries, shelter belts, dirt roads, corners   layout
:func:`shelter_belts`  the forest texture tile and the belts painted with it  tex
:func:`highways`       the village centre and the two paved roads through it  layout
:func:`floodplain`     the meadow along the river and its bushes              layout, tex
:func:`forest`         forest patches off the village and the river           noise
:func:`river_water`    wet margins, sand bars, water of varying width         layout
:func:`oxbow_lake`     an oxbow lake (старица) away from the paved roads      layout
:func:`paint_roads`    dirt and paved roads on top (bridges)                  —
:func:`village`        side streets, houses with shadows, gardens             layout, tex
:func:`isolated_trees` single trees in open fields and meadows                layout, tex
:func:`texture`        relief shading, grain and quantisation to uint8        —
:func:`pyramid`        2×2-mean levels of the texture                         —
catalogue              :func:`aerophoto.site.catalogue.catalogue`             —
objects                :func:`aerophoto.site.objects.build_objects`: houses,  objects
                       trees, canopy, chimney, mast, water tower, embankment
=====================  =====================================================  ============

The objects step comes last and draws only from a fifth stream (``objects``,
spawned after the other four), so adding it left the DEM, the texture, the land
cover and the catalogue bit for bit as they were (``tests/world/test_site.py`` pins them).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .catalogue import catalogue
from .model import COVER_CODES, Site, SiteParams
from .objects import build_objects
from .paint import Canvas, FieldSystem, crown_tile, seg_distance, smooth_noise

__all__ = ["build_site", "River", "Builder", "river_line", "relief", "fields", "soil_noise", "field_network",
           "shelter_belts", "highways", "floodplain", "forest", "river_water", "oxbow_lake", "paint_roads",
           "village", "isolated_trees", "texture", "pyramid"]

_C = COVER_CODES


# --------------------------------------------------------------------------- what the steps share
@dataclass(frozen=True)
class River:
    """The river's centre line y_r(X) = y₀ + a₁·sin(2πX/L₁ + φ₁) + a₂·sin(2πX/L₂ + φ₂), metres."""

    y0: float
    amp1: float
    amp2: float
    len1: float
    len2: float
    ph1: float
    ph2: float

    def y(self, X):
        """Y of the centre line at ground X (metres, array_like)."""
        X = np.asarray(X, float)
        return (self.y0 + self.amp1 * np.sin(2 * np.pi * X / self.len1 + self.ph1)
                + self.amp2 * np.sin(2 * np.pi * X / self.len2 + self.ph2))

    def side(self, p) -> float:
        """Signed distance along Y of point p from the centre line (+ north)."""
        return float(p[1] - self.y(p[0]))

    def pieces_beside(self, seg, sign, gap=0.0):
        """Pieces of a segment on one side of the river (sign +1 north, −1 south), ``gap`` m from it."""
        p0, p1 = np.asarray(seg[0], float), np.asarray(seg[1], float)
        L = float(np.hypot(*(p1 - p0)))
        k = max(int(L / 10.0), 1)
        s = np.linspace(0.0, 1.0, k + 1)
        pts = p0 + s[:, None] * (p1 - p0)
        ok = sign * (pts[:, 1] - self.y(pts[:, 0])) > gap
        pieces = []
        i = 0
        while i <= k:
            if ok[i]:
                j = i
                while j + 1 <= k and ok[j + 1]:
                    j += 1
                if j > i:
                    pieces.append((pts[i], pts[j]) if (i, j) != (0, k) else (p0, p1))
                i = j + 1
            else:
                i += 1
        return pieces


class Builder:
    """The state a site is built in: sizes, the four random streams, the texture canvas, the noise layers.

    Mutable and short-lived: :func:`build_site` makes one, passes it through
    the steps and drops it.  Ground X east, Y north in metres; texture pixel
    (r, c) covers X ∈ [c·t, (c+1)·t], Y ∈ [r·t, (r+1)·t].
    """

    def __init__(self, params: SiteParams):
        P = self.params = params
        self.W, self.Hs, self.t = P.width_m, P.height_m, P.texture_m
        ss = np.random.SeedSequence([P.seed, 20140])
        self.rng_layout, self.rng_dem, self.rng_tex, self.rng_noise = (np.random.default_rng(s) for s in ss.spawn(4))
        # a fifth stream, spawned after the four: the objects' heights and places (the texture does not use it)
        self.rng_objects = np.random.default_rng(ss.spawn(1)[0])
        self.scale = math.sqrt(self.W * self.Hs / 5e7)  # 1 for the default 10 km × 5 km
        # the DEM grid
        s = self.s = P.dem_spacing_m
        self.nxd = int(math.ceil(self.W / s)) + 1
        self.nyd = int(math.ceil(self.Hs / s)) + 1
        self.Xd = np.arange(self.nxd) * s
        self.Yd = np.arange(self.nyd) * s
        # the texture grid
        t = self.t
        self.nx = int(math.ceil(self.W / t))
        self.ny = int(math.ceil(self.Hs / t))
        self.cv = Canvas(self.ny, self.nx, t)
        self.Xc = ((np.arange(self.nx) + 0.5) * t).astype(np.float32)
        self.Yc = ((np.arange(self.ny) + 0.5) * t).astype(np.float32)
        self.cx, self.cy = self.W / 2.0, self.Hs / 2.0
        self.mottle = None  # soil moisture, set by soil_noise
        self.grain = None  # fine grain 0…1, set by soil_noise
        # what the objects step reads back from the painting steps (set by village and isolated_trees)
        self.houses = (np.zeros((0, 2)), np.zeros((0, 2)), np.zeros(0))
        self.house_roof_tone = np.zeros(0)
        self.garden_crowns = (np.zeros((0, 2)), np.zeros(0), np.zeros(0))
        self.tree_crowns = (np.zeros((0, 2)), np.zeros(0), np.zeros(0))

    def clip_to_site(self, p0, p1, pad=0.0):
        """Liang–Barsky clip of a segment to the site rectangle (grown by ``pad``)."""
        W, Hs = self.W, self.Hs
        d = p1 - p0
        t0, t1 = 0.0, 1.0
        for pk, qk in ((-d[0], p0[0] + pad), (d[0], W + pad - p0[0]), (-d[1], p0[1] + pad), (d[1], Hs + pad - p0[1])):
            if pk == 0:
                if qk < 0:
                    return None
                continue
            r = qk / pk
            if pk < 0:
                t0 = max(t0, r)
            else:
                t1 = min(t1, r)
        if t0 >= t1:
            return None
        return p0 + t0 * d, p0 + t1 * d


# --------------------------------------------------------------------------- the steps
def river_line(b: Builder) -> River:
    """The river's centre line: a long meander and a short one about 0.36–0.42 of the way north."""
    rng, Hs = b.rng_layout, b.Hs
    r_amp1 = Hs * rng.uniform(0.06, 0.09)
    r_amp2 = Hs * rng.uniform(0.015, 0.03)
    r_len1 = rng.uniform(3500.0, 5000.0) * b.scale
    r_len2 = rng.uniform(900.0, 1400.0)
    r_ph1, r_ph2 = rng.uniform(0, 2 * math.pi, 2)
    r_y0 = Hs * rng.uniform(0.36, 0.42)
    return River(r_y0, r_amp1, r_amp2, r_len1, r_len2, r_ph1, r_ph2)


def relief(b: Builder, river: River) -> np.ndarray:
    """The DEM, shape (ny_dem, nx_dem): scaled so its lowest node is base_height_m and its highest base + relief."""
    P, W, Hs, s = b.params, b.W, b.Hs, b.s
    nxd, nyd, Xd, Yd = b.nxd, b.nyd, b.Xd, b.Yd
    if P.relief_m <= 0:
        return np.full((nyd, nxd), P.base_height_m)
    rng_dem = b.rng_dem
    yr = river.y(Xd)
    dy = Yd[:, None] - yr[None, :]
    hills = np.zeros((nyd, nxd))
    n_hills = max(6, int(round(18 * b.scale**2)))
    for _ in range(n_hills):
        xc = rng_dem.uniform(-0.05, 1.05) * W
        yc = rng_dem.uniform(0.35, 1.1) * Hs
        sx = rng_dem.uniform(350.0, 1100.0)
        sy = sx * rng_dem.uniform(0.6, 1.5)
        amp = rng_dem.uniform(0.35, 1.0)
        hills += amp * np.outer(np.exp(-0.5 * ((Yd - yc) / sy) ** 2), np.exp(-0.5 * ((Xd - xc) / sx) ** 2))
    rough = smooth_noise(rng_dem, nyd, nxd, 250.0 / s).astype(float)
    north = 1.0 / (1.0 + np.exp(-(dy - 350.0) / 300.0))  # 0 south of the river, 1 north of it
    west = 0.45 + 0.55 / (1.0 + np.exp(-(0.72 * W - Xd) / 700.0))  # hills fade to the east
    hilly = north * west[None, :]
    valley = np.exp(-0.5 * (dy / 450.0) ** 2)
    plain = 0.03 * (1.0 - Yd[:, None] / Hs) + 0.01 * rough  # the gently sloping plain
    raw = hilly * (0.9 * hills + 0.06 * rough + 0.25) + (1 - hilly) * plain - 0.12 * valley
    raw -= raw.min()
    raw /= raw.max()
    return P.base_height_m + P.relief_m * raw


def fields(b: Builder, river: River) -> tuple:
    """Two field systems, north of the river (on the hills) and south of it (on the plain), painted.

    Each is made of bands along u with their own cross boundaries
    (rectangular parcels) and furrow patterns per parcel.  Returns
    ``(north, south)`` :class:`~aerophoto.site.paint.FieldSystem`.
    """
    rng, t, ny = b.rng_layout, b.t, b.ny
    R = 0.5 * math.hypot(b.W, b.Hs) + 50.0
    q = max(1.0, t / 2.0)  # LUT quantum, m
    theta_n = math.radians(rng.uniform(-25.0, 25.0))
    theta_s = theta_n + math.radians(rng.choice([-1.0, 1.0]) * rng.uniform(15.0, 40.0))
    north_sys = FieldSystem(rng, b.rng_tex, theta_n, b.cx, b.cy, R, q, (220.0, 520.0), (180.0, 650.0))
    south_sys = FieldSystem(rng, b.rng_tex, theta_s, b.cx, b.cy, R, q, (300.0, 700.0), (250.0, 800.0))
    Xc, Yc = b.Xc, b.Yc
    yr_c = river.y(Xc.astype(float))
    r_lo = max(min(int(math.floor(yr_c.min() / t)) - 1, ny), 0)
    r_hi = max(min(int(math.ceil(yr_c.max() / t)) + 1, ny), r_lo)
    img = b.cv.img
    chunk = 128
    for r0 in range(0, ny, chunk):
        r1 = min(r0 + chunk, ny)
        if r0 >= r_hi:
            img[r0:r1] = north_sys.values(Xc, Yc[r0:r1])
        elif r1 <= r_lo:
            img[r0:r1] = south_sys.values(Xc, Yc[r0:r1])
        else:
            north = Yc[r0:r1, None] > yr_c.astype(np.float32)[None, :]
            img[r0:r1] = np.where(north, north_sys.values(Xc, Yc[r0:r1]), south_sys.values(Xc, Yc[r0:r1]))
    b.cv.cover[:] = _C["arable field"]
    return north_sys, south_sys


def soil_noise(b: Builder) -> None:
    """Soil-moisture mottling (added to the fields) and the fine grain used by later steps (``b.mottle``, ``b.grain``)."""
    mottle = smooth_noise(b.rng_noise, b.ny, b.nx, 180.0 / b.t)
    mottle *= np.float32(0.03)
    b.cv.img += mottle
    b.mottle = mottle
    b.grain = b.rng_noise.random((b.ny, b.nx), dtype=np.float32)


def field_network(b: Builder, river: River, systems) -> tuple:
    """Field boundaries (painted), shelter belts, dirt field roads and field corners, clipped off the river.

    Returns ``(roads, corners, belts)``: road dicts (``kind``, ``xy`` (2, 2),
    ``width_m``), T-junction points (60 m or more from the river) and belt segments.
    """
    rng, cv = b.rng_layout, b.cv
    long_b, cross_b, corners, roads = [], [], [], []
    belts = []
    for sys_, sign in zip(systems, (1.0, -1.0)):
        lb, cb, cs = sys_.boundaries(b.clip_to_site)
        for seg in lb:
            pieces = river.pieces_beside(seg, sign)
            r = rng.random()
            if r < 0.28:
                belts += pieces
            else:
                long_b += pieces
                if r > 0.66:
                    roads += [{"kind": "dirt", "xy": np.array(p), "width_m": 4.5} for p in pieces]
        for seg in cb:
            pieces = river.pieces_beside(seg, sign)
            cross_b += pieces
            if rng.random() < 0.15:
                roads += [{"kind": "dirt", "xy": np.array(p), "width_m": 4.0} for p in pieces]
        corners += [p for p in cs if sign * river.side(p) > 60.0]
    cv.paint(cv.layer(long_b + cross_b, 1.4), 0.56, _C["field boundary"], opacity=0.85)
    return roads, corners, belts


def shelter_belts(b: Builder, belts):
    """The forest texture (a tile of tree crowns with their shadows, repeated) and the shelter belts painted with it.

    Returns the forest texture as a function of flat pixel indices (used again by :func:`forest`).
    """
    tile = crown_tile(b.rng_tex, b.t)
    tn = tile.shape[0]
    nx, mottle = b.nx, b.mottle

    def forest_tex(idx):
        r, c = np.divmod(idx, nx)
        return tile[r % tn, c % tn] + mottle.reshape(-1)[idx] * np.float32(0.6)

    b.cv.paint(b.cv.layer(belts, 7.0), forest_tex, _C["forest"])
    return forest_tex


def highways(b: Builder, river: River, roads: list) -> np.ndarray:
    """The village centre on the north bank and the two paved roads through it (appended to ``roads``).

    Returns the village centre (X, Y), metres.
    """
    rng, W, Hs = b.rng_layout, b.W, b.Hs
    vx = W * rng.uniform(0.4, 0.6)
    vy = float(river.y(vx)) + rng.uniform(350.0, 550.0)
    vy = min(vy, Hs - 400.0)
    village_c = np.array([vx, vy])
    yw = vy + rng.uniform(-0.12, 0.12) * Hs
    ye = vy + rng.uniform(-0.12, 0.12) * Hs
    xm1 = vx - W * rng.uniform(0.18, 0.3)
    ym1 = vy + rng.uniform(-0.08, 0.08) * Hs
    main = [np.array([-10.0, yw]), np.array([xm1, ym1]), village_c, np.array([W + 10.0, ye])]
    for a, c in zip(main[:-1], main[1:]):
        roads.append({"kind": "paved", "xy": np.array([a, c]), "width_m": 8.0})
    xs = vx + rng.uniform(-0.1, 0.1) * W
    xn = vx + rng.uniform(-0.1, 0.1) * W
    second = [np.array([xs, -10.0]), village_c, np.array([xn, Hs + 10.0])]
    for a, c in zip(second[:-1], second[1:]):
        roads.append({"kind": "paved", "xy": np.array([a, c]), "width_m": 7.0})
    return village_c


@dataclass
class _Band:
    """The band of texture rows that holds the floodplain and the river, with distances from the centre line."""

    rows: slice
    signed: np.ndarray  # ≈ perpendicular distance from the centre line, + north, m (float32)
    dist: np.ndarray  # |signed|
    y2: np.ndarray  # curvature proxy d²y_r/dX² at the pixel columns
    Xc64: np.ndarray


def floodplain(b: Builder, river: River) -> _Band:
    """The floodplain meadow along the river (painted) and bushes along it; returns the river's band of rows."""
    rng, t, ny = b.rng_layout, b.t, b.ny
    Xc, Yc = b.Xc, b.Yc
    yr_c = river.y(Xc.astype(float))
    Xc64 = Xc.astype(float)
    fp_w = 170.0 + 70.0 * np.sin(2 * np.pi * Xc64 / rng.uniform(1500.0, 2500.0) + rng.uniform(0, 6.3))
    rb0 = max(int((yr_c.min() - 400.0) / t), 0)
    rb1 = min(int((yr_c.max() + 400.0) / t) + 1, ny)
    rows_b = slice(rb0, rb1)
    y1 = np.gradient(yr_c, Xc64)
    y2 = np.gradient(y1, Xc64)
    signed = Yc[rows_b, None] - yr_c.astype(np.float32)[None, :]  # + north of the centre line
    signed *= (1.0 / np.sqrt(1.0 + y1**2)).astype(np.float32)[None, :]  # ≈ perpendicular distance
    dist_r = np.abs(signed)
    mot_b = b.mottle[rows_b]
    g_b = b.grain[rows_b]
    sub = b.cv.img[rows_b]
    csub = b.cv.cover[rows_b]
    meadow = np.clip((fp_w.astype(np.float32)[None, :] + mot_b * np.float32(1700.0) - dist_r) / np.float32(25.0), 0, 1)
    meadow_tex = np.float32(0.50) + mot_b * np.float32(2.0) + (g_b - np.float32(0.5)) * np.float32(0.04)
    sub += (meadow_tex - sub) * meadow
    csub[meadow >= 0.5] = _C["meadow"]
    del meadow, meadow_tex
    # bushes along the river and in the meadow
    W = b.W
    n_b = int(900 * b.scale**2)
    bx = rng.uniform(0, W, n_b)
    by = river.y(bx) + rng.normal(0.0, 70.0, n_b)
    bush = np.column_stack([bx, by])
    bush = bush[np.abs(by - river.y(bx)) > 35.0]
    br = rng.uniform(2.0, 4.5, len(bush))
    b.cv.discs(bush + np.array([2.0, 2.0]), br, 0.10)
    b.cv.discs(bush, br, b.rng_tex.uniform(0.16, 0.28, len(bush)))
    return _Band(rows_b, signed, dist_r, y2, Xc64)


def forest(b: Builder, band: _Band, village_c, forest_tex) -> None:
    """Large forest patches from low-frequency noise, kept off the village and the river, with ragged edges."""
    t, nx, ny = b.t, b.nx, b.ny
    Xc, Yc = b.Xc, b.Yc
    vx, vy = village_c
    fnoise = smooth_noise(b.rng_noise, ny, nx, 700.0 / t)
    fnoise += b.mottle * np.float32(9.0)
    fnoise[band.rows] -= np.clip(np.float32(1.0) - (band.dist - np.float32(45.0)) / np.float32(60.0), 0, 1) \
        * np.float32(3.0)
    vr0, vr1 = max(int((vy - 900) / t), 0), min(int((vy + 900) / t) + 1, ny)
    vc0, vc1 = max(int((vx - 900) / t), 0), min(int((vx + 900) / t) + 1, nx)
    vill_d = np.hypot(Xc[None, vc0:vc1] - np.float32(vx), Yc[vr0:vr1, None] - np.float32(vy))
    fnoise[vr0:vr1, vc0:vc1] -= np.clip(np.float32(1.0) - (vill_d - np.float32(500.0)) / np.float32(300.0), 0, 1) * 3
    canopy = fnoise
    canopy += smooth_noise(b.rng_noise, ny, nx, 45.0 / t) * np.float32(0.06)  # an irregular edge
    canopy -= np.float32(1.05)
    canopy *= np.float32(60.0)
    canopy += (b.grain - np.float32(0.5)) * np.float32(1.5)  # single crowns at the forest edge
    np.clip(canopy, 0, 1, out=canopy)
    b.cv.paint_mask(canopy, forest_tex, _C["forest"])


def river_water(b: Builder, band: _Band) -> None:
    """The river: wet margins, sand bars on the inner side of the bends, then water of varying width."""
    rng, t = b.rng_layout, b.t
    rows_b, signed, dist_r, y2, Xc64 = band.rows, band.signed, band.dist, band.y2, band.Xc64
    mot_b = b.mottle[rows_b]
    g_b = b.grain[rows_b]
    sub = b.cv.img[rows_b]
    csub = b.cv.cover[rows_b]
    half_w = (13.0 + 5.0 * np.sin(2 * np.pi * Xc64 / rng.uniform(1800.0, 2600.0)
                                  + rng.uniform(0, 6.3))).astype(np.float32)[None, :]
    inner = np.sign(y2).astype(np.float32)[None, :]  # the centre of curvature is on this side (+ north)
    bar_w = np.clip((np.abs(y2) - 5e-4) * 4e4, 0.0, 20.0).astype(np.float32)[None, :]
    ts = np.float32(t)
    margin = np.clip((half_w + np.float32(4.0) - dist_r) / ts + np.float32(0.5), 0, 1) * np.float32(0.6)
    sub += (np.float32(0.34) - sub) * margin
    bar = np.where(signed * inner > 0, half_w + bar_w - dist_r, half_w + np.float32(1.5) - dist_r)
    bar = np.clip(bar / ts + np.float32(0.5), 0, 1) * np.float32(0.95)
    sand = np.float32(0.80) + (g_b - np.float32(0.5)) * np.float32(0.08)
    sub += (sand - sub) * bar
    csub[bar >= 0.5] = _C["sand bank"]
    wat = np.clip((half_w - dist_r) / ts + np.float32(0.5), 0, 1)
    water_tex = np.float32(0.12) + mot_b * np.float32(0.5) + np.clip(np.float32(1.0) - dist_r / half_w, 0, 1) * 0.03
    sub += (water_tex - sub) * wat
    csub[wat >= 0.5] = _C["water"]


def oxbow_lake(b: Builder, river: River, roads) -> np.ndarray:
    """An oxbow lake (старица) in the floodplain, away from the paved roads; its centre line (k, 2), or (0, 2)."""
    rng, cv, Hs = b.rng_layout, b.cv, b.Hs
    for _ in range(20):
        ox = rng.uniform(0.1, 0.9) * b.W
        side = rng.choice([-1.0, 1.0])
        oy = float(river.y(ox)) + side * rng.uniform(110.0, 160.0)
        rad = rng.uniform(60.0, 95.0)
        start = rng.uniform(0, 2 * np.pi)
        far = all(seg_distance(np.array([ox, oy]), *r["xy"]) > rad + 80.0 for r in roads if r["kind"] == "paved")
        if far and rad + 40.0 < oy < Hs - rad - 40.0:
            a = start + np.linspace(0.0, 1.25 * np.pi, 40)
            arc = np.column_stack([ox + rad * np.cos(a), oy + rad * np.sin(a)])
            cv.paint(cv.layer(list(zip(arc[:-1], arc[1:])), 9.0), 0.30, None, opacity=0.7)
            cv.paint(cv.layer(list(zip(arc[:-1], arc[1:])), 6.0), 0.13, _C["water"])
            return arc
    return np.zeros((0, 2))


def paint_roads(b: Builder, roads) -> None:
    """The roads on top of everything so far (bridges over the river): dirt roads, then paved ones with shoulders."""
    cv, grain = b.cv, b.grain
    dirt = [r for r in roads if r["kind"] == "dirt"]
    paved = [r for r in roads if r["kind"] == "paved"]
    cv.paint(cv.layer([r["xy"] for r in dirt], 2.25),
             lambda idx: np.float32(0.78) + (grain.reshape(-1)[idx] - np.float32(0.5)) * np.float32(0.08),
             _C["dirt road"])
    cv.paint(cv.layer([r["xy"] for r in paved], 6.0), 0.62, None, opacity=0.8)  # light shoulders
    cv.paint(cv.layer([r["xy"] for r in paved], 3.8), 0.36, _C["paved road"])


def village(b: Builder, river: River, village_c, roads) -> tuple:
    """The village: streets (the paved roads near the centre plus two side streets), houses and gardens.

    The side streets are appended to ``roads`` (dirt).  Returns the houses
    ``(centres (n, 2), half sizes (n, 2), angles (n,))``, metres and radians.
    """
    rng, cv, W, Hs = b.rng_layout, b.cv, b.W, b.Hs
    paved = [r for r in roads if r["kind"] == "paved"]
    street_segs = []
    for r in paved:
        a, c = r["xy"]
        d = c - a
        L = float(np.hypot(*d))
        dirv = d / L
        # the part of the road within 450 m of the village centre
        proj = float(np.dot(village_c - a, dirv))
        s0, s1 = max(proj - 450.0, 0.0), min(proj + 450.0, L)
        if s1 - s0 > 50:
            street_segs.append((a + s0 * dirv, a + s1 * dirv))
    # side streets: perpendicular to the first street, offset along it
    if street_segs:
        a, c = street_segs[0]
        d = (c - a) / np.hypot(*(c - a))
        nrm = np.array([-d[1], d[0]])
        for off in rng.uniform(-300.0, 300.0, 2):
            base = village_c + off * d
            side = 1.0 if rng.random() < 0.5 else -1.0
            seg = (base + 8.0 * side * nrm, base + side * rng.uniform(200.0, 320.0) * nrm)
            street_segs.append(seg)
            roads.append({"kind": "dirt", "xy": np.array(seg), "width_m": 5.0})
        cv.paint(cv.layer([np.array(sg) for sg in street_segs[-2:]], 2.5), 0.70, _C["dirt road"])
    houses_c, houses_h, houses_a = [], [], []
    gardens_c, gardens_h, gardens_a = [], [], []
    river_check = lambda p: abs(p[1] - float(river.y(p[0]))) > 110.0  # noqa: E731
    for k, (a, c_) in enumerate(street_segs):
        d = c_ - a
        L = float(np.hypot(*d))
        dirv = d / L
        nrm = np.array([-dirv[1], dirv[0]])
        ang = math.atan2(dirv[1], dirv[0])
        pos = 25.0
        while pos < L - 15.0:
            for side in (-1.0, 1.0):
                if rng.random() < 0.12:
                    continue
                hw = rng.uniform(4.0, 6.5)
                hd = rng.uniform(3.5, 5.0)
                setback = 13.0 + hd + rng.uniform(0.0, 3.0)
                c = a + pos * dirv + side * setback * nrm
                gc = a + pos * dirv + side * (setback + 30.0) * nrm
                if not (river_check(c) and river_check(gc) and 30 < c[0] < W - 30 and 30 < c[1] < Hs - 30):
                    continue
                # keep clear of the other streets
                clear = True
                for m2, (a2, b2) in enumerate(street_segs):
                    if m2 == k:
                        continue
                    d2 = b2 - a2
                    dd2 = float(d2 @ d2)
                    uu = min(max(float((gc - a2) @ d2) / dd2, 0.0), 1.0)
                    uc = min(max(float((c - a2) @ d2) / dd2, 0.0), 1.0)
                    if np.hypot(*(gc - a2 - uu * d2)) < 45.0 or np.hypot(*(c - a2 - uc * d2)) < 20.0:
                        clear = False
                        break
                if not clear:
                    continue
                houses_c.append(c)
                houses_h.append((hw, hd))
                houses_a.append(ang + rng.uniform(-0.04, 0.04))
                gardens_c.append(gc)
                gardens_h.append((13.0, 26.0))
                gardens_a.append(ang)
            pos += rng.uniform(27.0, 36.0)
    houses_c = np.array(houses_c).reshape(-1, 2)
    houses_h = np.array(houses_h).reshape(-1, 2)
    houses_a = np.array(houses_a).reshape(-1)
    gardens_c = np.array(gardens_c).reshape(-1, 2)
    # gardens: darker, mottled
    cv.rects(gardens_c, np.array(gardens_h).reshape(-1, 2), np.array(gardens_a),
             b.rng_tex.uniform(0.36, 0.48, len(gardens_c)),
             _C["garden"])
    # fruit trees in gardens
    if len(gardens_c):
        ft = []
        for gc, ga in zip(gardens_c, gardens_a):
            n_t = rng.integers(2, 6)
            lu = rng.uniform(-9.0, 9.0, n_t)
            lv = rng.uniform(-20.0, 20.0, n_t)
            ft.append(gc + np.outer(lu, [math.cos(ga), math.sin(ga)]) + np.outer(lv, [-math.sin(ga), math.cos(ga)]))
        ft = np.vstack(ft)
        cv.discs(ft + np.array([1.8, 1.8]), rng.uniform(2.0, 3.2, len(ft)), 0.08)
        crown_r = rng.uniform(2.0, 3.2, len(ft))
        crown_tone = b.rng_tex.uniform(0.16, 0.26, len(ft))
        cv.discs(ft, crown_r, crown_tone)
        b.garden_crowns = (ft, crown_r, crown_tone)
    # houses: shadow (sun in the south-west: shadows fall to the north-east), then roofs
    shadow_off = np.array([3.0, 3.0])
    cv.rects(houses_c + shadow_off, houses_h, houses_a, 0.10)
    roof = np.where(b.rng_tex.random(len(houses_c)) < 0.75, b.rng_tex.uniform(0.80, 0.95, len(houses_c)),
                    b.rng_tex.uniform(0.48, 0.6, len(houses_c)))
    cv.rects(houses_c, houses_h, houses_a, roof, _C["building"], soft=0.7)
    b.houses = (houses_c, houses_h, houses_a)
    b.house_roof_tone = roof
    return houses_c, houses_h, houses_a


def isolated_trees(b: Builder) -> np.ndarray:
    """Single trees on open, bright fields and meadows (30 m of them all round); their crown centres (n, 2)."""
    rng, cv, W, Hs, t, nx, ny = b.rng_layout, b.cv, b.W, b.Hs, b.t, b.nx, b.ny
    cand = np.column_stack([rng.uniform(60, W - 60, int(400 * b.scale**2)),
                            rng.uniform(60, Hs - 60, int(400 * b.scale**2))])
    tx_ = np.clip((cand[:, 0] / t).astype(int), 0, nx - 1)
    ty_ = np.clip((cand[:, 1] / t).astype(int), 0, ny - 1)
    ok = np.ones(len(cand), bool)
    reach = int(math.ceil(30.0 / t))  # 30 m of open field or meadow all round
    for dr in (-reach, 0, reach):
        for dc in (-reach, 0, reach):
            cc = cv.cover[np.clip(ty_ + dr, 0, ny - 1), np.clip(tx_ + dc, 0, nx - 1)]
            ok &= np.isin(cc, [_C["arable field"], _C["meadow"]])
            # and bright enough ground for the dark crown to stand out
            ok &= cv.img[np.clip(ty_ + dr // 2, 0, ny - 1), np.clip(tx_ + dc // 2, 0, nx - 1)] > 0.32
    trees = cand[ok][: int(60 * b.scale**2)]
    tree_r = rng.uniform(3.0, 5.0, len(trees))
    cv.discs(trees + np.array([2.5, 2.5]), tree_r, 0.05)
    tone = b.rng_tex.uniform(0.08, 0.15, len(trees))
    cv.discs(trees, tree_r, tone, _C["tree"])
    b.tree_crowns = (trees, tree_r, tone)
    return trees


def texture(b: Builder, dem: np.ndarray) -> np.ndarray:
    """Shade the painted brightness by the relief (sun in the south-west, 45° high), add grain, quantise to uint8.

    Consumes the canvas image and the grain (``b.cv.img`` and ``b.grain`` are dropped).
    """
    P, s, nxd, nyd, ny, nx = b.params, b.s, b.nxd, b.nyd, b.ny, b.nx
    Xc, Yc = b.Xc, b.Yc
    img, grain = b.cv.img, b.grain
    if P.relief_m > 0:
        gy, gx = np.gradient(dem, s)
        sun_az, sun_el = math.radians(225.0), math.radians(45.0)  # from the south-west (azimuth from +X)
        lx, ly, lz = math.cos(sun_el) * math.cos(sun_az), math.cos(sun_el) * math.sin(sun_az), math.sin(sun_el)
        nrm = 1.0 / np.sqrt(1 + gx**2 + gy**2)
        shade = ((-gx * lx - gy * ly + lz) * nrm / lz).astype(np.float32)  # 1 on flat ground
        # bilinear up-sampling of the DEM-grid shade onto the texture pixel centres, one axis at a time
        fxs = Xc / np.float32(s)
        i0 = np.minimum(fxs.astype(np.int64), nxd - 2)
        wx = (fxs - i0).astype(np.float32)
        shade_x = shade[:, i0] * (1 - wx) + shade[:, i0 + 1] * wx  # (ny_dem, nx)
        fys = Yc / np.float32(s)
        j0 = np.minimum(fys.astype(np.int64), nyd - 2)
        wy = (fys - j0).astype(np.float32)[:, None]
    out = np.empty((ny, nx), np.uint8)
    for r0 in range(0, ny, 256):  # shade, grain and quantise, a block of rows at a time
        r1 = min(r0 + 256, ny)
        blk = img[r0:r1]
        if P.relief_m > 0:
            jj = j0[r0:r1]
            blk *= shade_x[jj] * (1 - wy[r0:r1]) + shade_x[jj + 1] * wy[r0:r1]
        g = grain[r0:r1]
        g -= np.float32(0.5)
        g *= np.float32(0.035 * 255.0)
        blk *= np.float32(255.0)
        blk += g
        blk += np.float32(0.5)
        np.clip(blk, 0.0, 255.0, out=blk)
        np.copyto(out[r0:r1], blk, casting="unsafe")
    b.cv.img = None
    b.grain = None
    return out


def pyramid(tex: np.ndarray) -> list:
    """Levels 1, 2, … of the texture pyramid: rounded 2×2 means, down to a side of 32–63 pixels."""
    levels = []
    cur = tex
    while min(cur.shape) >= 64:
        h2, w2 = cur.shape[0] // 2 * 2, cur.shape[1] // 2 * 2
        c16 = cur[:h2, :w2].astype(np.uint16)
        nxt = ((c16[0::2, 0::2] + c16[1::2, 0::2] + c16[0::2, 1::2] + c16[1::2, 1::2] + 2) // 4).astype(np.uint8)
        levels.append(nxt)
        cur = nxt
    return levels


# --------------------------------------------------------------------------- the whole
def build_site(params: SiteParams) -> Site:
    """Generate the site for ``params`` (no caching; see :func:`aerophoto.site.get_site`), step by step."""
    if not isinstance(params, SiteParams):
        raise ValueError(f"params = {params!r} must be a SiteParams")
    b = Builder(params)
    river = river_line(b)
    dem = relief(b, river)
    systems = fields(b, river)
    soil_noise(b)
    roads, corners, belts = field_network(b, river, systems)
    forest_tex = shelter_belts(b, belts)
    village_c = highways(b, river, roads)
    band = floodplain(b, river)
    forest(b, band, village_c, forest_tex)
    river_water(b, band)
    del band
    oxbow = oxbow_lake(b, river, roads)
    paint_roads(b, roads)
    houses = village(b, river, village_c, roads)
    trees = isolated_trees(b)
    tex = texture(b, dem)
    levels = pyramid(tex)
    cover = b.cv.cover
    cat, roofs = catalogue(dem, cover, params, roads=roads, corners=corners, houses=houses, trees=trees)
    objects = build_objects(b, dem, river, roads, village_c, tex, cover, first_id=int(cat["id"].max()) + 1
                            if len(cat) else 1)
    Xr = np.arange(-20.0, b.W + 20.0, 8.0)
    features = {
        "river": np.column_stack([Xr, river.y(Xr)]),
        "roads": roads,
        "buildings": roofs,
        "trees": trees,
        "village": village_c,
        "oxbow": oxbow,
        "field_rotation_deg": (math.degrees(systems[0].theta), math.degrees(systems[1].theta)),
    }
    return Site(params=params, dem=dem, texture=tex, cover=cover, catalogue=cat, features=features, _levels=levels,
                objects=objects)
