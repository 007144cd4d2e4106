"""The interpretation site: a land-cover map with the objects of the guide's table 10 (§9), for colour photos.

The book's main site (:func:`aerophoto.site.get_site`) is greyscale and stays as it is: every other chapter's
photos and numbers are unchanged.  Chapter 08 photographs a second, smaller site built here — a separate
*edition* of the virtual world made for interpretation (дешифрирование).  What is where is a **land-cover class
map** (:data:`CLASSES`, the classes of :data:`aerophoto.spectral.COVERS`); what a class looks like in a band is
its reflectance (:func:`aerophoto.spectral.cover_bands`), rendered through the book's one camera by
:mod:`aerophoto.site.colour`.

The objects of table 10 (guide §9)
----------------------------------
=============================  ============================================================================
object (Russian)               how it is built (X east, Y north, metres; the site is 1600 m × 1600 m)
=============================  ============================================================================
river (река)                   flows **east** along a sine-shaped valley, 36 m wide widening to 46 m
                               downstream, deep water with a shallow margin
islands (острова)              two teardrops: a blunt head upstream, a long tail **narrowing downstream**,
                               with shallows and a sand spit on their downstream side (table 10)
tributary (приток)             a stream from the north-west entering at an **acute angle** (35°) that
                               points downstream
lake (озеро)                   a rotated ellipse with a shallow rim, south-west
pond with a dam (пруд,         a brook flowing north into the river; the pond is widest at the dam
плотина)                       (its downstream end), the dam an earth bank across the valley
raised bog (верховое болото)   on the northern watershed, far from streams, mottled tone, bog lakelets and
                               small sparse pines
low bog (низинное болото)      a ribbon along the river's valley floor, sedge and reed, shrub at its edges
pine / spruce / deciduous      stands of crowns (:mod:`aerophoto.site.cover_objects`): pine — even height, convex
forest (лес)                   crowns; spruce — pointed cones of uneven height (mottled, darker, long thin
                               shadows); deciduous — broad soft crowns, lighter
shrub (кустарник)              small low crowns (shorter shadows, finer grain); sparse bushes on the meadow
meadow with haystacks          floodplain meadow, mown strips, wet patches; haystacks are ellipsoids
(луг, стога сена)              (r 2.5–3 m, 3–4 m high) that cast shadows
village (деревня)              houses with gabled roofs along the gravel road, sheds, gardens, a farm
arable land (пашня)            straight-edged fields: ploughed (furrows), crops, stubble; their soil from
                               :mod:`aerophoto.site.soils` when it exists, else :func:`default_soil`
railway (железная дорога)      long straights joined by a curve of radius 700 m; ballast 8 m, two rail lines
roads (автомобильные дороги)   an asphalt road (dark) winding in curves of small radius and a gravel road
                               (light), both edged by ditches (кюветы)
=============================  ============================================================================

The site's greyscale ``texture`` is white (255): :func:`aerophoto.render.render` of this site therefore gives the
**illumination** of every pixel (shadows, the shading of crowns, roofs and haystacks), which
:mod:`aerophoto.site.colour` multiplies by the class reflectance and by the cover's texture at the pixel's ground
point (:mod:`aerophoto.site.texture`: furrows, tramlines, mowing strips, currents, wheel paths …, each a zero-mean
variation around the class's tone).  What the texture needs is kept here: each field's frame, the river's
coordinates (``river``), the class map before the roads were painted (``under_roads``) and the roads' centre
lines with their half-widths (:data:`LINEAR`).  Data only (layer 3); deterministic from the seed.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import spectral as sp
from .._validate import check_int_range, check_range
from .model import Site, SiteParams
from .cover_objects import build_cover_objects, paint_village, village_layout

__all__ = ["CLASSES", "CLASS_CODES", "CLASS_RU", "FLOW_AZIMUTH_DEG", "InterpretationSite", "interpretation_site",
           "build_interpretation_site", "default_soil", "SIZE_M", "LINEAR"]

#: the land-cover classes of the interpretation site (code = index + 1; 0 = nothing)
CLASSES = ("deep water", "shallow water", "sand bank", "ploughed field", "crop", "stubble", "meadow",
           "mown meadow", "wet meadow", "haystack", "pine forest", "spruce forest", "deciduous forest", "shrub",
           "raised bog", "low bog", "asphalt road", "gravel road", "dirt road", "railway", "ditch", "dam",
           "garden", "slate roof", "red iron roof", "wall")
#: the lines painted from centre lines: class → (its centre line in ``features``, half-width m); a road has a 1 m
#: shoulder (dirt road) and a 2 m ditch beyond it, the railway's ballast a ditch 1–3 m beyond its edge
LINEAR = {"gravel road": ("gravel", 3.0), "asphalt road": ("asphalt", 3.5), "railway": ("railway", 4.0)}
CLASS_CODES = {name: k + 1 for k, name in enumerate(CLASSES)}
CLASS_RU = {name: sp.COVERS[name][0] for name in CLASSES}
#: the river flows east: azimuth of the flow, degrees clockwise from north
FLOW_AZIMUTH_DEG = 90.0
SIZE_M = 1600.0
_T = 1.0  # texel, m
_C = CLASS_CODES


def default_soil(humus_pct: float = 3.0, moisture_pct: float = 12.0) -> dict:
    """The soil of the arable fields when :mod:`aerophoto.site.soils` does not provide one: a loam (spectral.py).

    humus_pct 0…100 %, moisture_pct 0…60 %; keywords of :func:`aerophoto.spectral.soil_reflectance`.
    """
    h = check_range("humus_pct", humus_pct, 0.0, 100.0, unit="%")
    m = check_range("moisture_pct", moisture_pct, 0.0, 60.0, unit="%")
    return dict(parent="loam", humus_pct=h, moisture_pct=m, particle_mm=0.1)


@dataclass(frozen=True, eq=False, repr=False)
class InterpretationSite:
    """The interpretation site (see the module notes).

    Attributes
    ----------
    site : :class:`aerophoto.site.Site`
        The DEM, a white texture and the objects (canopy, haystacks, bog pines): what
        :func:`aerophoto.render.render` ray-casts.
    classes : ndarray (n, n) uint8
        Land-cover code per texel (:data:`CLASS_CODES`), row 0 at the south edge, texel ``texel_m``.
    under_roads : ndarray (n, n) uint8
        The class map before the roads and the railway were painted over it (what lies beside them).
    river : dict of ndarray (n, n) float32
        The river's frame at each texel near it: ``s`` arc length along the centre line (downstream), ``off`` the
        signed offset from it (north +), ``half`` the half-width of the water (m).
    humus_pct, moisture_pct : ndarray (n, n) float32
        The topsoil's humus and moisture where soil shows (arable land): tied to relief (more humus and moisture
        low down), from :mod:`aerophoto.site.soils` if available.
    features : dict
        The truth of the objects (metres): ``river`` (k, 2) centre line (flowing east), ``river_width_m`` (k,),
        ``islands`` (list of dicts: head, tail, outline), ``tributary`` (k, 2) in flow order, ``lake`` (centre,
        axes, angle), ``pond`` (outline), ``dam`` (2, 2), ``brook`` (k, 2) in flow order, ``railway``,
        ``asphalt``, ``gravel`` (k, 2), ``stands`` (dict name → (x0, x1, y0, y1)), ``bogs``, ``haystacks`` (n, 3)
        X, Y, height, ``fields`` (kind, x0, x1, y0, y1, phase), ``village`` (its layout), ``object_class`` (the
        class code of each of ``site.objects``).
    """

    site: Site
    classes: np.ndarray
    under_roads: np.ndarray
    river: dict
    humus_pct: np.ndarray
    moisture_pct: np.ndarray
    features: dict
    seed: int

    def __repr__(self) -> str:
        return f"InterpretationSite({SIZE_M:g} m × {SIZE_M:g} m, {len(CLASSES)} classes, seed {self.seed})"

    @property
    def texel_m(self) -> float:
        return self.site.params.texture_m

    @property
    def crowns(self):
        """The crowns of the stands, bushes and fruit trees (:class:`aerophoto.site.crowns.Crowns`)."""
        return self.site.objects.crowns

    def class_at(self, X, Y) -> np.ndarray:
        """Class code of the texel holding each ground point (0 off the site)."""
        X = np.asarray(X, float)
        Y = np.asarray(Y, float)
        n = self.classes.shape[0]
        c = np.clip((X / self.texel_m).astype(np.int64), 0, n - 1)
        r = np.clip((Y / self.texel_m).astype(np.int64), 0, n - 1)
        inside = (X >= 0) & (X <= SIZE_M) & (Y >= 0) & (Y <= SIZE_M)
        return np.where(inside, self.classes[r, c], 0).astype(np.uint8)

    def class_table(self) -> pd.DataFrame:
        """Every class: code, Russian name and share of the site, %."""
        counts = np.bincount(self.classes.ravel(), minlength=len(CLASSES) + 1)
        return pd.DataFrame({"code": [_C[c] for c in CLASSES], "class": CLASSES, "Russian": [CLASS_RU[c] for c in CLASSES],
                             "share, %": 100.0 * counts[1:] / counts.sum()}).set_index("code")


# =========================================================================== geometry helpers
def _grid(n):
    x = (np.arange(n) + 0.5) * _T
    return x


def _polyline_sn(pts, n, reach):
    """For texels within ``reach`` of a polyline: distance d, signed offset (left +) and arc length s."""
    pts = np.asarray(pts, float)
    d = np.full((n, n), np.inf, np.float32)
    off = np.zeros((n, n), np.float32)
    s = np.zeros((n, n), np.float32)
    seg = np.diff(pts, axis=0)
    L = np.hypot(seg[:, 0], seg[:, 1])
    s0 = np.r_[0.0, np.cumsum(L)]
    for k in range(len(seg)):
        a, b = pts[k], pts[k + 1]
        x0, x1 = min(a[0], b[0]) - reach, max(a[0], b[0]) + reach
        y0, y1 = min(a[1], b[1]) - reach, max(a[1], b[1]) + reach
        c0, c1 = max(int(x0 / _T), 0), min(int(x1 / _T) + 1, n)
        r0, r1 = max(int(y0 / _T), 0), min(int(y1 / _T) + 1, n)
        if c0 >= c1 or r0 >= r1 or L[k] == 0:
            continue
        X = (np.arange(c0, c1) + 0.5) * _T
        Y = (np.arange(r0, r1) + 0.5) * _T
        px = X[None, :] - a[0]
        py = Y[:, None] - a[1]
        u = np.clip((px * seg[k, 0] + py * seg[k, 1]) / L[k] ** 2, 0.0, 1.0)
        dx = px - u * seg[k, 0]
        dy = py - u * seg[k, 1]
        dist = np.hypot(dx, dy).astype(np.float32)
        cross = (seg[k, 0] * py - seg[k, 1] * px) / L[k]
        win = d[r0:r1, c0:c1]
        better = dist < win
        win[better] = dist[better]
        off[r0:r1, c0:c1][better] = cross[better]
        s[r0:r1, c0:c1][better] = (s0[k] + u * L[k])[better]
    return d, off, s


def _ellipse(n, centre, a, b, angle_deg):
    """Normalised radius ρ of the ellipse (ρ ≤ 1 inside) at every texel."""
    x = _grid(n)
    X, Y = np.meshgrid(x - centre[0], x - centre[1])
    t = math.radians(angle_deg)
    u = X * math.cos(t) + Y * math.sin(t)
    v = -X * math.sin(t) + Y * math.cos(t)
    return np.sqrt((u / a) ** 2 + (v / b) ** 2).astype(np.float32)


def _arc_polyline(start, heading_deg, pieces, step=4.0):
    """A polyline of straights and circular arcs: pieces ("s", length) or ("a", radius, turn°, + left)."""
    p = np.array(start, float)
    h = math.radians(heading_deg)  # from the X axis, counter-clockwise
    out = [p.copy()]
    for piece in pieces:
        if piece[0] == "s":
            k = max(int(piece[1] / step), 1)
            for _ in range(k):
                p = p + piece[1] / k * np.array([math.cos(h), math.sin(h)])
                out.append(p.copy())
        else:
            R, turn = piece[1], math.radians(piece[2])
            length = abs(turn) * R
            k = max(int(length / step), 1)
            for _ in range(k):
                h += turn / k
                p = p + length / k * np.array([math.cos(h), math.sin(h)])
                out.append(p.copy())
    return np.array(out)


def _river_y(x):
    return 820.0 + 90.0 * np.sin(2 * np.pi * np.asarray(x, float) / 1100.0 + 0.6)


# =========================================================================== the build
def build_interpretation_site(seed: int = 0) -> InterpretationSite:
    """Build the interpretation site (about 4 s; seed 0 ≤ seed < 2**32); :func:`interpretation_site` caches it."""
    seed = check_int_range("seed", seed, 0, 2**32 - 1)
    rng = np.random.default_rng([int(seed), 9009])
    n = int(SIZE_M / _T)
    x = _grid(n)
    X, Y = np.meshgrid(x, x)
    c = _Canvas(X=X, Y=Y, cls=np.full((n, n), _C["meadow"], np.uint8), rng=rng)
    feats: dict = {}
    # the painting order matters: later classes paint over earlier ones, and the seeded draws follow it
    rv = _river_course(c, feats)
    dem, s_dem = _valley_dem()
    _paint_fields(c, feats)
    raised = _paint_forests_and_bogs(c, rv, feats)
    stacks = _paint_meadows(c, rv, feats)
    _paint_lake_brook_tributary(c, rv, feats)
    _paint_river_water(c, rv)
    feats["gravel"] = _gravel_line()
    layout = village_layout(feats["gravel"], seed)
    paint_village(X, Y, c.cls, _C, layout)
    feats["village"] = layout
    under = c.cls.copy()
    _paint_roads_and_railway(c, rv, feats)
    cls = c.cls

    # ---- soil: humus and moisture tied to relief (low ground: more of both)
    from scipy.ndimage import map_coordinates

    Zt = map_coordinates(dem, [Y.ravel() / s_dem, X.ravel() / s_dem], order=1).reshape(n, n).astype(np.float32)
    low_ness = np.clip((Zt.max() - Zt) / (Zt.max() - Zt.min() + 1e-9), 0, 1)
    humus, moist = _soil_fields(low_ness, X, Y)

    # ---- objects: the crowns, the village's houses, haystacks, bog pines
    avoid = np.array([p for pts in _candidate_points(feats) for p in pts], float).reshape(-1, 2)
    objs, feats["object_class"] = build_cover_objects(rng, cls, _C, dem, s_dem, stacks, raised, layout,
                                                      feats["river"], avoid, seed)
    params = SiteParams(width_m=SIZE_M, height_m=SIZE_M, relief_m=float(dem.max() - dem.min()),
                        base_height_m=float(dem.min()), seed=int(seed), texture_m=_T, dem_spacing_m=s_dem)
    tex = np.full((n, n), 255, np.uint8)
    cat = pd.DataFrame({"id": pd.Series([], dtype=np.int64), "kind": pd.Series([], dtype=object),
                        "X_m": pd.Series([], dtype=float), "Y_m": pd.Series([], dtype=float),
                        "Z_m": pd.Series([], dtype=float), "control": pd.Series([], dtype=bool)})
    site = Site(params=params, dem=dem, texture=tex, cover=cls, catalogue=cat, features=feats, _levels=[],
                objects=objs)
    river = {"s": rv.s.astype(np.float32), "off": rv.off.astype(np.float32), "half": rv.half.astype(np.float32)}
    for arr in (cls, under, humus, moist, *river.values()):
        arr.flags.writeable = False
    return InterpretationSite(site=site, classes=cls, under_roads=under, river=river, humus_pct=humus,
                              moisture_pct=moist, features=feats, seed=int(seed))


def _candidate_points(feats) -> list:
    """Where chapter 08's lab may put a mark (the haystacks, the lines' points): the meadow's bushes keep clear."""
    out = [feats["haystacks"][:, :2] + [12.0, 0.0]]
    for key in ("railway", "asphalt", "gravel"):
        if key in feats:
            line = feats[key]
            out.append(np.array([line[int(k * (len(line) - 1))] for k in (0.2, 0.35, 0.5, 0.65)]))
    return out


@dataclass(frozen=True, eq=False)
class _Canvas:
    """What the painters of :func:`build_interpretation_site` share: the texel centres ``X``, ``Y`` (m, shape
    (n, n)), the class map ``cls`` they paint in place, and the seeded ``rng``."""

    X: np.ndarray
    Y: np.ndarray
    cls: np.ndarray
    rng: np.random.Generator


@dataclass(frozen=True, eq=False)
class _River:
    """The river on the texel grid: distance ``d`` from its centre line, signed offset ``off`` (m, north +),
    arc length ``s`` (m), half-width ``half`` (m, widened at the islands), the masks of the islands, of the
    shallows below them and of the water; all shape (n, n)."""

    d: np.ndarray
    off: np.ndarray
    s: np.ndarray
    half: np.ndarray
    islands: np.ndarray
    tails: np.ndarray
    water: np.ndarray


def _river_course(c: _Canvas, feats: dict) -> _River:
    """The river: centre line, width widening downstream (36 → 46 m), two teardrop islands (``feats``: river,
    river_width_m, islands).  Paints nothing: the water goes on last (:func:`_paint_river_water`)."""
    n = c.X.shape[0]
    rx = np.arange(-20.0, SIZE_M + 21.0, 6.0)
    river = np.column_stack([rx, _river_y(rx)])
    width = 36.0 + 10.0 * (rx + 20.0) / (SIZE_M + 40.0)
    d_r, off_r, s_r = _polyline_sn(river, n, 260.0)
    half = np.interp(s_r, np.r_[0.0, np.cumsum(np.hypot(*np.diff(river, axis=0).T))], width / 2.0).astype(np.float32)
    islands = []
    s_river = np.r_[0.0, np.cumsum(np.hypot(*np.diff(river, axis=0).T))]
    isl_mask = np.zeros((n, n), bool)
    tail_mask = np.zeros((n, n), bool)
    for x_head, L, B in ((430.0, 150.0, 16.0), (1120.0, 190.0, 19.0)):
        s_head = float(np.interp(x_head, rx, s_river))
        u = (s_r - s_head) / L
        b = B * np.sqrt(np.clip(u / 0.15, 0.0, 1.0)) * np.clip(1.0 - u, 0.0, 1.0) ** 0.9
        b = np.where((u >= 0) & (u <= 1), b, 0.0)
        half = half + np.where((u > -0.3) & (u < 1.35),
                               B * 1.05 * np.clip(np.minimum((u + 0.3) / 0.4, (1.35 - u) / 0.5), 0, 1), 0.0)
        inside = (np.abs(off_r) < b) & (d_r < 200)
        isl_mask |= inside
        tail = (u > 0.9) & (u < 1.45) & (np.abs(off_r) < 0.35 * B * np.clip((1.45 - u) / 0.55, 0, 1) + 1.0)
        tail_mask |= tail & ~inside & (d_r < 200)
        x_tail = float(np.interp(s_head + L, s_river, rx))
        islands.append({"head_m": (x_head, float(_river_y(x_head))), "tail_m": (x_tail, float(_river_y(x_tail))),
                        "length_m": L, "width_m": 2 * B * 0.96, "s_tail_m": s_head + L})
    feats["river"] = river
    feats["river_width_m"] = width
    feats["islands"] = islands
    return _River(d=d_r, off=off_r, s=s_r, half=half, islands=isl_mask, tails=tail_mask, water=d_r <= half)


def _valley_dem() -> tuple:
    """The DEM, 8 m spacing: a valley along the river falling east, the northern watershed, the brook's valley.

    Returns ``(dem, spacing_m)``, heights in metres, shape (201, 201).
    """
    s_dem = 8.0
    nd = int(SIZE_M / s_dem) + 1
    xd = np.arange(nd) * s_dem
    XD, YD = np.meshgrid(xd, xd)
    dist_dem = np.abs(YD - _river_y(XD))
    dem = (150.0 + 5.0 * (1.0 - XD / SIZE_M) + 12.0 * (1.0 - np.exp(-(dist_dem / 240.0) ** 2))
           + 9.0 / (1.0 + np.exp(-(YD - 1250.0) / 70.0)) - 3.0 * np.exp(-((XD - 1330.0) / 45.0) ** 2) * (YD < _river_y(XD)))
    return dem, s_dem


def _paint_fields(c: _Canvas, feats: dict) -> None:
    """Arable fields, south-east and two north of the river: straight edges, furrows, stubble rows (``feats``:
    fields, as (kind, x0, x1, y0, y1) in metres)."""
    X, Y, cls, rng = c.X, c.Y, c.cls, c.rng
    fields = []
    kinds = ("ploughed field", "crop", "stubble", "crop", "ploughed field", "stubble", "crop", "ploughed field")
    k = 0
    for fx0 in (1060.0, 1200.0, 1340.0, 1470.0):
        for fy0 in (40.0, 300.0, 960.0):
            fx1, fy1 = min(fx0 + 128.0, 1590.0), fy0 + (230.0 if fy0 < 900 else 200.0)
            m = (X > fx0) & (X < fx1) & (Y > fy0) & (Y < fy1)
            kind = kinds[k % len(kinds)]
            k += 1
            cls[m] = _C[kind]
            phase = float(rng.uniform(0, 2 * np.pi))  # the tramlines' and swaths' phase (site.texture)
            fields.append((kind, fx0, fx1, fy0, fy1, phase))
    for k, (kind, fx0, fx1) in enumerate((("ploughed field", 600.0, 722.0), ("crop", 730.0, 860.0))):  # north
        m = (X > fx0) & (X < fx1) & (Y > 905.0) & (Y < 1120.0)
        cls[m] = _C[kind]
        fields.append((kind, fx0, fx1, 905.0, 1120.0, 1.3 + 2.1 * k))
    feats["fields"] = fields


def _paint_forests_and_bogs(c: _Canvas, rv: _River, feats: dict) -> np.ndarray:
    """Forest stands, the raised bog with its lakelets (seeded), the low bog edged by shrub (``feats``: stands,
    bogs).  Returns the raised bog's mask (its pines are objects, :func:`_objects`)."""
    X, Y, cls, rng = c.X, c.Y, c.cls, c.rng
    n = X.shape[0]
    off_r, half = rv.off, rv.half
    stands = {"pine forest": (40.0, 270.0, 1090.0, 1560.0), "spruce forest": (480.0, 860.0, 1150.0, 1570.0),
              "deciduous forest": (560.0, 930.0, 50.0, 350.0)}
    for name, (x0, x1, y0, y1) in stands.items():
        edge = 8.0 * np.sin(Y / 37.0) + 6.0 * np.cos(X / 29.0)
        m = (X > x0 + edge) & (X < x1 - edge) & (Y > y0 + edge) & (Y < y1 - edge)
        cls[m] = _C[name]
    feats["stands"] = stands
    bog_rho = _ellipse(n, (1300.0, 1400.0), 250.0, 150.0, 10.0)
    bog_rho = bog_rho + 0.06 * np.sin(X / 23.0) * np.cos(Y / 31.0)
    raised = bog_rho < 1.0
    cls[raised] = _C["raised bog"]
    lakelets = []
    for _ in range(6):
        while True:
            ctr = rng.uniform([1120, 1300], [1480, 1500])
            if ((ctr[0] - 1300) / 250) ** 2 + ((ctr[1] - 1400) / 150) ** 2 < 0.5:
                break
        r = rng.uniform(7.0, 16.0)
        m = (X - ctr[0]) ** 2 + (Y - ctr[1]) ** 2 < r * r
        cls[m] = _C["deep water"]
        lakelets.append((float(ctr[0]), float(ctr[1]), float(r)))
    feats["bogs"] = {"raised": {"centre_m": (1300.0, 1400.0), "axes_m": (250.0, 150.0), "lakelets": lakelets},
                     "low": {"x_m": (1150.0, 1500.0)}}
    low = (X > 1150 + 10 * np.sin(Y / 15)) & (X < 1500) & (off_r < -half - 25) & (off_r > -half - 125 - 20 * np.sin(X / 40))
    cls[low] = _C["low bog"]
    low_edge = low & ((off_r > -half - 35) | (off_r < -half - 110 - 20 * np.sin(X / 40)))
    cls[low_edge] = _C["shrub"]
    return raised


def _paint_meadows(c: _Canvas, rv: _River, feats: dict) -> list:
    """Meadows on the floodplain: mown strips, wet patches, and 14 haystacks (seeded; ``feats``: haystacks).
    Returns the haystacks as (X, Y, height, radius) in metres."""
    X, Y, cls, rng = c.X, c.Y, c.cls, c.rng
    off_r, half = rv.off, rv.half
    mead = (X > 80) & (X < 820) & (off_r < -half - 20) & (off_r > -half - 230) & (cls == _C["meadow"])
    mown = mead & (((X - 80) // 60) % 3 == 1)
    cls[mown] = _C["mown meadow"]
    wet = mead & (off_r > -half - 60) & (np.sin(X / 35.0) > 0.2)
    cls[wet] = _C["wet meadow"]
    stacks = []
    while len(stacks) < 14:
        p = rng.uniform([100, 0], [800, 1])
        yc = float(_river_y(p[0])) - rng.uniform(80, 200)
        if all((p[0] - q[0]) ** 2 + (yc - q[1]) ** 2 > 900 for q in stacks):
            stacks.append((float(p[0]), yc, float(rng.uniform(3.0, 4.0)), float(rng.uniform(2.5, 3.0))))
    feats["haystacks"] = np.array(stacks)
    for xs_, ys_, _h, r_ in stacks:
        cls[(X - xs_) ** 2 + (Y - ys_) ** 2 < r_ * r_] = _C["haystack"]
    return stacks


def _paint_lake_brook_tributary(c: _Canvas, rv: _River, feats: dict) -> None:
    """The lake; the brook with the pond and its dam; the tributary entering at 35° (``feats``: lake, brook,
    pond, dam, tributary)."""
    X, Y, cls = c.X, c.Y, c.cls
    n = X.shape[0]
    lake_rho = _ellipse(n, (270.0, 230.0), 170.0, 95.0, 20.0)
    cls[lake_rho < 1.0] = _C["shallow water"]
    cls[lake_rho < 0.88] = _C["deep water"]
    feats["lake"] = {"centre_m": (270.0, 230.0), "axes_m": (170.0, 95.0), "angle_deg": 20.0}
    y_join = float(_river_y(1330.0))
    brook = np.array([[1290.0, -5.0], [1300.0, 150.0], [1320.0, 300.0], [1325.0, 420.0], [1330.0, 560.0],
                      [1335.0, y_join - 40], [1330.0, y_join]])
    d_b, _, _ = _polyline_sn(brook, n, 70.0)
    brook_w = (d_b < 3.0) & (Y < y_join)
    pond = (Y > 300) & (Y < 420) & (np.abs(X - 1322.0) < 8.0 + (Y - 300.0) * 0.42)
    fields_mask = np.isin(cls, [_C["ploughed field"], _C["crop"], _C["stubble"]])
    cls[(d_b < 12.0) & fields_mask] = _C["meadow"]  # the brook's banks are grass
    cls[pond & ~(Y > 412)] = _C["deep water"]
    cls[pond & (np.abs(X - 1322.0) > 2.0 + (Y - 300.0) * 0.42)] = _C["shallow water"]
    cls[brook_w & ~pond] = _C["shallow water"]
    dam = (Y >= 420) & (Y < 432) & (np.abs(X - 1322.0) < 75.0)
    cls[dam] = _C["dam"]
    feats["brook"] = brook
    feats["pond"] = {"y_m": (300.0, 420.0), "x_m": 1322.0}
    feats["dam"] = np.array([[1247.0, 426.0], [1397.0, 426.0]])
    a = math.radians(35.0)
    x_j = 760.0
    join = np.array([x_j, float(_river_y(x_j))])
    trib = np.array([[300.0, 1610.0], [330.0, 1380.0], [380.0, 1150.0], join + 260 * np.array([-math.cos(a), math.sin(a)]),
                     join + 140 * np.array([-math.cos(a), math.sin(a)]), join])
    d_t, _, _ = _polyline_sn(trib, n, 30.0)
    cls[(d_t < 5.0) & ~rv.water] = _C["shallow water"]
    cls[(d_t < 3.0) & ~rv.water] = _C["deep water"]
    feats["tributary"] = trib


def _paint_river_water(c: _Canvas, rv: _River) -> None:
    """The river's water over everything: deep with a shallow margin; the islands (meadow, shrub in the middle),
    the shallows and sand spits below them."""
    cls = c.cls
    water, d_r, off_r, half = rv.water, rv.d, rv.off, rv.half
    cls[water] = _C["deep water"]
    cls[water & (d_r > half - 4.0)] = _C["shallow water"]
    cls[rv.tails] = _C["shallow water"]
    cls[rv.islands] = _C["meadow"]
    cls[rv.islands & (np.abs(off_r) < 0.5 * np.max(half))] = _C["shrub"]
    spit = rv.tails & (np.abs(off_r) < 2.0)
    cls[spit] = _C["sand bank"]


def _gravel_line() -> np.ndarray:
    """The gravel road's centre line (m): from the asphalt road westwards, three tight bends, then a long straight."""
    return _arc_polyline((1000.0, 400.0), 180.0, [("s", 120), ("a", 60, 40), ("s", 90), ("a", 50, -70),
                                                  ("s", 100), ("a", 70, 35), ("s", 700)])


def _paint_roads_and_railway(c: _Canvas, rv: _River, feats: dict) -> None:
    """The roads with shoulders and ditches, then the railway, painted last, by :data:`LINEAR`'s widths
    (``feats``: asphalt, gravel, railway, railway_radius_m, flow_azimuth_deg).  The same rules, at a pixel's
    point, are :func:`aerophoto.site.texture.pixel_classes`."""
    cls = c.cls
    n = cls.shape[0]
    yy = np.arange(-5.0, SIZE_M + 6.0, 5.0)
    feats["asphalt"] = np.column_stack([1000.0 + 38.0 * np.sin(yy / 55.0) + 20.0 * np.sin(yy / 23.0), yy])
    feats["gravel"] = _gravel_line()
    feats["railway"] = _arc_polyline((-10.0, 560.0), 0.0, [("s", 460), ("a", 700, -25), ("s", 1300)])
    d = {name: _polyline_sn(feats[key], n, 20.0)[0] for name, (key, _) in LINEAR.items()}
    not_water = ~rv.water
    for road in ("gravel road", "asphalt road"):
        w = LINEAR[road][1]
        cls[(d[road] >= w + 1.0) & (d[road] < w + 3.0) & not_water] = _C["ditch"]
        cls[(d[road] < w + 1.0) & not_water] = _C["dirt road"]  # shoulders
        cls[d[road] < w] = _C[road]  # the asphalt crosses the river by a bridge
    w = LINEAR["railway"][1]
    cls[(d["railway"] >= w + 1.0) & (d["railway"] < w + 3.0) & not_water & (cls != _C["asphalt road"])] = _C["ditch"]
    cls[d["railway"] < w] = _C["railway"]
    feats["railway_radius_m"] = 700.0
    feats["flow_azimuth_deg"] = FLOW_AZIMUTH_DEG


def _soil_fields(low_ness, X, Y):
    """Humus and moisture of the topsoil, % — from :mod:`aerophoto.site.soils` when it provides them.

    The hook: a function ``soils.interpretation_fields(low_ness, X, Y) -> (humus_pct, moisture_pct)`` (arrays as
    ``X``).  Without it, the default soil of :func:`default_soil`: humus 2…6 % and moisture 10…24 % rising towards
    low ground (the guide's indirect key, §14: soils follow relief and wetness).
    """
    try:
        from . import soils  # the soil engineer's module (chapter 13)

        fn = getattr(soils, "interpretation_fields", None)
    except ImportError:
        fn = None
    if fn is not None:
        h, m = fn(low_ness, X, Y)
        return np.asarray(h, np.float32), np.asarray(m, np.float32)
    base = default_soil()
    h = (base["humus_pct"] - 1.0 + 4.0 * low_ness).astype(np.float32)
    m = (base["moisture_pct"] - 2.0 + 14.0 * low_ness ** 2).astype(np.float32)
    return h, m


@functools.lru_cache(maxsize=2)
def interpretation_site(seed: int = 0) -> InterpretationSite:
    """The interpretation site for ``seed`` (0 ≤ seed < 2**32), built once and cached: in memory, and on the
    user's disk (:mod:`aerophoto.cache`: verified, keyed by the package's code and the seed, the same arrays bit
    for bit), so chapter 08's first demo reads it in ~0.1 s instead of building it for ~4 s on every Run All."""
    from .. import cache
    from .crowns import Crowns
    from .objects import SiteObjects

    seed = check_int_range("seed", seed, 0, 2**32 - 1)
    return cache.load_or_build("interpretation-site", {"seed": seed}, lambda: build_interpretation_site(seed),
                               types=(InterpretationSite, Site, SiteObjects, SiteParams, Crowns))
