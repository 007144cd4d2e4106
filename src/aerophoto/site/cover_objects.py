"""What stands on the interpretation site (:mod:`aerophoto.site.cover`): crowns, a village, haystacks, bog pines.

=====================  ============================================================================================
object                 how it is built (metres; seeded)
=====================  ============================================================================================
stands of forest       crowns on a jittered lattice over each stand (:data:`STANDS`): pine — domes of one height
                       (21–23 m, R 2.2–2.8 m, tone even); spruce — cones of uneven height (14–25 m, R 1.5–2.1 m,
                       in groups of taller and shorter, darker and lighter crowns some 20 m across: tone mottled); broadleaf — broad lumpy crowns (15–21 m, R 3.4–4.6 m); shrub — small low
                       crowns (1.8–3.5 m).  The crowns overhang their stand's edge (they are not cut at it)
sparse shrub           bushes scattered over the floodplain meadow and along the river's banks (table 10: a meadow's
                       marks are haystacks and sparse shrub)
village (деревня)      a street village along the gravel road: houses 6–10 m with gabled roofs (slate grey or
                       painted iron), a shed behind each, vegetable gardens and fruit trees behind; a farm of two long
                       barns to the north.  Roofs cast shadows; their two slopes take the light differently
haystacks, bog pines   ellipsoids (r 2.5–3 m, 3–4 m high; the bog's small pines 3–5 m)
=====================  ============================================================================================

The canopy raster the ray-caster marches is stamped from the crowns at :data:`CANOPY_TEXEL_M`; the crowns
themselves (:class:`aerophoto.site.crowns.Crowns`) shade it.  Each object's land-cover class (what colour its
pixels take) is in ``features["object_class"]``.  Data only (layer 3).
"""

from __future__ import annotations

import math

import numpy as np

from .crowns import Crowns
from .objects import OBJECT_KINDS, SiteObjects, _box_planes, _Poly

__all__ = ["STANDS", "CANOPY_TEXEL_M", "village_layout", "paint_village", "build_cover_objects"]

#: class: (lattice spacing m, crown radius m, top height m, shape code of aerophoto.site.crowns, tone spread)
STANDS = {
    "pine forest": (5.5, (2.2, 2.8), (21.0, 23.0), 1, 0.04),
    "spruce forest": (4.6, (1.5, 2.1), (14.0, 25.0), 0, 0.16),
    "deciduous forest": (7.5, (3.4, 4.6), (15.0, 21.0), 2, 0.10),
    "shrub": (3.0, (1.0, 1.6), (1.8, 3.5), 2, 0.08),
}
#: the canopy raster's texel, m (finer than the class map's 1 m: crowns of 2–5 m keep their round outline)
CANOPY_TEXEL_M = 0.5
_ROOFS = ("slate roof", "red iron roof")


def village_layout(gravel: np.ndarray, seed: int) -> dict:
    """Where the village's houses, sheds, barns, gardens and fruit trees go (seeded; metres).

    Houses stand on plots 26 m wide along the gravel road's straight between X 360 and 585, north of it (and four
    south of it, X 440–560): the house 14–17 m from the road's centre line, a shed 28 m, the garden 36–74 m.
    Returns ``houses`` (list of dicts: centre, axis angle, half length, half width, eaves, pitch, roof class),
    ``gardens`` (list of 4 corner arrays), ``trees`` (k, 4: X, Y, R, top) and ``yard`` (4 corners).
    """
    rng = np.random.default_rng([int(seed), 9011])
    g = np.asarray(gravel, float)
    seg = np.diff(g, axis=0)
    s0 = np.r_[0.0, np.cumsum(np.hypot(seg[:, 0], seg[:, 1]))]

    def frame(x):  # the road's point at X = x, its direction (westwards) and its northern normal
        j = int(np.argmin(np.abs(g[:, 0] - x)))
        j = min(max(j, 1), len(g) - 2)
        t = g[j + 1] - g[j - 1]
        t /= np.hypot(*t)
        nrm = np.array([-t[1], t[0]])
        if nrm[1] < 0:
            nrm = -nrm
        return g[j], t, nrm

    houses, gardens, trees = [], [], []

    def rect(c, t, nrm, a, b):  # corners of a rectangle: ±a along the road, from b[0] to b[1] across it
        return np.array([c + t * sa * a + nrm * sb for sa in (-1, 1) for sb in b])[[0, 1, 3, 2]]

    for side, xs in ((1.0, np.arange(372.0, 586.0, 26.0)), (-1.0, np.arange(452.0, 560.0, 26.0))):
        for x in xs:
            c, t, nrm = frame(float(x))
            nrm = nrm * side
            L, W = rng.uniform(4.0, 5.2), rng.uniform(3.0, 3.8)
            along = bool(rng.random() < 0.7)  # the ridge along the street (else the gable end faces it)
            off = rng.uniform(14.0, 17.0)
            hc = c + nrm * (off + (W if along else L))
            houses.append({"centre": hc, "axis": t if along else nrm, "half_len": L, "half_wid": W,
                           "eaves": rng.uniform(2.8, 3.4), "pitch_deg": rng.uniform(30.0, 40.0),
                           "roof": _ROOFS[int(rng.random() < 0.35)], "name": "house"})
            sc = c + nrm * 30.0 + t * rng.uniform(-6.0, 6.0)
            houses.append({"centre": sc, "axis": t, "half_len": rng.uniform(2.5, 3.5), "half_wid": 2.0,
                           "eaves": 2.4, "pitch_deg": 20.0, "roof": "slate roof", "name": "shed"})
            gardens.append(rect(c, t, nrm, 11.0, (36.0, 74.0 if side > 0 else 60.0)))
            for _ in range(int(rng.integers(2, 5))):
                p = c + t * rng.uniform(-10.0, 10.0) + nrm * rng.uniform(36.0, 72.0 if side > 0 else 58.0)
                trees.append((p[0], p[1], rng.uniform(1.4, 2.4), rng.uniform(4.0, 6.5)))
    c, t, nrm = frame(470.0)
    yard = rect(c, t, nrm, 48.0, (95.0, 160.0))
    for k, along in enumerate((112.0, 140.0)):
        houses.append({"centre": c + nrm * along, "axis": t, "half_len": 30.0, "half_wid": 6.0, "eaves": 4.0,
                       "pitch_deg": 25.0, "roof": "slate roof", "name": "barn"})
    return {"houses": houses, "gardens": gardens, "trees": np.array(trees, float).reshape(-1, 4), "yard": yard,
            "s_m": s0}


def _in_polygon(X, Y, poly):
    """Points inside a convex quadrilateral (corners in order)."""
    inside = np.ones(X.shape, bool)
    sign = None
    for k in range(4):
        a, b = poly[k], poly[(k + 1) % 4]
        cr = (b[0] - a[0]) * (Y - a[1]) - (b[1] - a[1]) * (X - a[0])
        if sign is None:
            c = (b[0] - a[0]) * (poly[(k + 2) % 4][1] - a[1]) - (b[1] - a[1]) * (poly[(k + 2) % 4][0] - a[0])
            sign = 1.0 if c > 0 else -1.0
        inside &= sign * cr >= 0
    return inside


def _house_corners(h) -> np.ndarray:
    a = np.asarray(h["axis"], float)
    b = np.array([-a[1], a[0]])
    c = np.asarray(h["centre"], float)
    return np.array([c + sa * h["half_len"] * a + sb * h["half_wid"] * b for sa, sb in ((-1, -1), (1, -1), (1, 1),
                                                                                    (-1, 1))])


def paint_village(X, Y, cls, codes: dict, layout: dict) -> None:
    """Paint the village on the class map: the farm's yard, the gardens, the roofs' footprints."""
    def box(poly):
        x0, x1 = poly[:, 0].min() - 1, poly[:, 0].max() + 1
        y0, y1 = poly[:, 1].min() - 1, poly[:, 1].max() + 1
        c0, c1 = max(int(x0), 0), min(int(x1) + 1, X.shape[1])
        r0, r1 = max(int(y0), 0), min(int(y1) + 1, X.shape[0])
        return slice(r0, r1), slice(c0, c1)

    def paint(poly, code):
        r, c = box(poly)
        m = _in_polygon(X[r, c], Y[r, c], poly)
        cls[r, c][m] = code

    paint(layout["yard"], codes["dirt road"])
    for gdn in layout["gardens"]:
        paint(gdn, codes["garden"])
    for h in layout["houses"]:
        paint(_house_corners(h), codes[h["roof"]])


def _stand_crowns(rng, cls, codes) -> list:
    """The crowns of every stand (:data:`STANDS`) on a jittered lattice over the stand's texels (metres)."""
    out = []
    for name, (sp_m, (r_lo, r_hi), (h_lo, h_hi), shape, spread) in STANDS.items():
        g = np.arange(0.5 * sp_m, cls.shape[0], sp_m)
        GX, GY = np.meshgrid(g, g)
        on = cls[GY.astype(np.int64), GX.astype(np.int64)] == codes[name]
        xs, ys = GX[on], GY[on]
        cx = xs + rng.uniform(-0.35, 0.35, len(xs)) * sp_m
        cy = ys + rng.uniform(-0.35, 0.35, len(ys)) * sp_m
        R = rng.uniform(r_lo, r_hi, len(xs))
        H = rng.uniform(h_lo, h_hi, len(xs))
        white = rng.standard_normal(len(xs))
        if shape == 0 and len(xs):  # spruce grows in groups: taller, darker and lighter clumps of some 10 m
            from .texture import noise

            clump = noise(cx, cy, 10.0, 91)
            H = np.clip(0.5 * (h_lo + h_hi) + 0.3 * (h_hi - h_lo) * (0.9 * clump + 0.45 * white), h_lo, h_hi)
            white = 0.9 * noise(cx, cy, 10.0, 92) + 0.45 * white
        tone = 1.0 + spread * white
        tone += 1.0 - tone.mean() if len(tone) else 0.0
        out.append((cx, cy, R, H, np.full(len(xs), shape), np.full(len(xs), codes[name]), tone))
    return out


def _meadow_bushes(rng, cls, codes, river, avoid) -> tuple:
    """Sparse shrub on the floodplain meadow and along the river's banks, clear of ``avoid`` (k, 2) by 15 m."""
    n = cls.shape[0]
    pts = []
    for _ in range(400):
        if len(pts) >= 90:
            break
        if rng.random() < 0.5:  # on the meadow
            p = rng.uniform([60.0, 450.0], [980.0, 900.0])
        else:  # on a bank: beside the river's centre line
            x = rng.uniform(0.0, 1600.0)
            y = float(np.interp(x, river[:, 0], river[:, 1]))
            p = np.array([x, y + rng.choice([-1.0, 1.0]) * rng.uniform(25.0, 32.0)])
        r_, c_ = int(np.clip(p[1], 0, n - 1)), int(np.clip(p[0], 0, n - 1))
        if cls[r_, c_] not in (codes["meadow"], codes["wet meadow"]):
            continue
        if len(avoid) and np.min(np.hypot(*(avoid - p).T)) < 15.0:
            continue
        pts.append(p)
    P = np.array(pts).reshape(-1, 2)
    k = len(P)
    return (P[:, 0], P[:, 1], rng.uniform(1.2, 2.6, k), rng.uniform(2.0, 4.5, k), np.full(k, 2),
            np.full(k, codes["shrub"]), 1.0 + 0.06 * rng.standard_normal(k))


def build_cover_objects(rng, cls, codes, dem, s_dem, stacks, raised, layout, river, avoid, seed) -> tuple:
    """The objects (:class:`aerophoto.site.objects.SiteObjects`) and each object's class code.

    ``stacks`` the haystacks (X, Y, height, radius); ``raised`` the raised bog's mask (its small pines);
    ``layout`` :func:`village_layout`; ``avoid`` the points bushes keep clear of.
    """
    from scipy.ndimage import map_coordinates

    def ground(xy):
        xy = np.atleast_2d(xy)
        return map_coordinates(dem, [xy[:, 1] / s_dem, xy[:, 0] / s_dem], order=1, mode="nearest")

    parts = _stand_crowns(rng, cls, codes)
    parts.append(_meadow_bushes(rng, cls, codes, river, avoid))
    tr = layout["trees"]
    parts.append((tr[:, 0], tr[:, 1], tr[:, 2], tr[:, 3], np.full(len(tr), 2), np.full(len(tr), codes["deciduous forest"]),
                  np.ones(len(tr))))
    cat = [np.concatenate([p[j] for p in parts]) for j in range(7)]
    crowns = Crowns(x_m=cat[0], y_m=cat[1], r_m=cat[2], top_m=cat[3], shape=cat[4].astype(np.int64),
                    cls=cat[5].astype(np.uint8), tone=cat[6].astype(np.float32), seed=int(seed))
    n = int(round(cls.shape[0] * 1.0 / CANOPY_TEXEL_M))
    crowns, canopy_dm = crowns.with_rasters(n, CANOPY_TEXEL_M)

    poly = _Poly()
    obj_cls = []
    for h in layout["houses"]:
        corners = _house_corners(h)
        zc = ground(corners)
        z_bottom = float(zc.min()) - 0.5
        z_eaves = float(zc.max()) + h["eaves"]
        ridge = z_eaves + h["half_wid"] * math.tan(math.radians(h["pitch_deg"]))
        planes, faces = _box_planes(np.asarray(h["centre"], float), np.asarray(h["axis"], float), h["half_len"],
                                    h["half_wid"], z_bottom, z_eaves, ridge)
        c = np.asarray(h["centre"], float)
        R = math.hypot(h["half_len"], h["half_wid"])
        poly.add(planes, faces, [], (1.0, 1.0), "house", c, float(ground(c)[0]), ridge,
                 (c[0] - R, c[0] + R, c[1] - R, c[1] + R, z_bottom, ridge), f"{h['name']} {len(poly.planes) + 1}")
        obj_cls.append(codes[h["roof"]])

    ell = [(x, y, hh, r) for x, y, hh, r in stacks]
    names = [f"haystack {k + 1}" for k in range(len(stacks))]
    obj_cls += [codes["haystack"]] * len(stacks)
    ys, xs = np.nonzero(raised[::9, ::9])
    pick = rng.random(len(xs)) < 0.12
    for x, y in zip(xs[pick] * 9.0 + 4.5, ys[pick] * 9.0 + 4.5):
        if cls[int(y), int(x)] == codes["raised bog"]:
            ell.append((float(x), float(y), float(rng.uniform(3.0, 5.0)), float(rng.uniform(0.8, 1.3))))
            names.append(f"bog pine {len(names) + 1}")
            obj_cls.append(codes["pine forest"])
    E = np.array(ell, float)
    gz = ground(E[:, :2])
    cz = E[:, 2] / 2.0
    centre = np.column_stack([E[:, 0], E[:, 1], gz + cz])
    radii = np.column_stack([E[:, 3], cz])
    top = gz + 2 * cz
    e_bbox = np.column_stack([E[:, 0] - E[:, 3], E[:, 0] + E[:, 3], E[:, 1] - E[:, 3], E[:, 1] + E[:, 3], gz - 0.5, top])
    k_poly = len(poly.planes)
    tree = OBJECT_KINDS.index("tree")
    objs = SiteObjects(
        planes=np.array(poly.planes).reshape(-1, 14, 4), face=np.array(poly.face, np.uint8).reshape(-1, 14),
        textured=np.array(poly.tex, bool).reshape(-1, 14), albedo=np.array(poly.albedo, np.float32).reshape(-1, 2),
        kind=np.r_[np.array(poly.kind, np.int64), np.full(len(E), tree, np.int64)],
        centre_m=np.vstack([np.array(poly.centre, float).reshape(-1, 2), E[:, :2]]),
        ground_Z_m=np.r_[np.array(poly.ground, float), gz], top_Z_m=np.r_[np.array(poly.top, float), top],
        bbox=np.vstack([np.array(poly.bbox, float).reshape(-1, 6), e_bbox]), ell_centre=centre, ell_radii=radii,
        ell_albedo=np.ones(len(E), np.float32), canopy_dm=canopy_dm, texel_m=CANOPY_TEXEL_M,
        names=tuple(poly.names + names), crowns=crowns)
    assert objs.n_polyhedra == k_poly
    for a in (objs.planes, objs.face, objs.textured, objs.albedo, objs.kind, objs.centre_m, objs.ground_Z_m,
              objs.top_Z_m, objs.bbox, objs.ell_centre, objs.ell_radii, objs.ell_albedo, objs.canopy_dm):
        a.flags.writeable = False
    return objs, np.array(obj_cls, np.uint8)
