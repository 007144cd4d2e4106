"""What a land cover looks like close up: the texture, pattern and fine shape of the interpretation site's covers.

A photo is interpreted by tone, texture, pattern, shadow, shape and size (guide §9, direct keys).  The class map of
:mod:`aerophoto.site.cover` gives each place its cover, and so its mean tone (its reflectance,
:mod:`aerophoto.spectral`); this module gives each cover the **marks** table 10 names, at the point each pixel
sees, so that they show at any scale — the photo's 1.5 m pixels or a magnifier's 0.3 m:

==========================  ======================================================================================
cover                       texture and pattern (periods and widths in metres on the ground)
==========================  ======================================================================================
ploughed field (пашня)      furrows 0.35, the plough's passes 1.75, dead furrows every 36 (darker), clods streaked
                            along the furrows, patches of lighter and darker soil 8–25
crop (посевы)               rows streaked along the drilling, tramlines every 18 (two wheel tracks 1.8 apart: the
                            soil shows), a headland 12 wide at the field's ends with rows across, patches of denser
                            and thinner crop 10–30
stubble (стерня)            light straw swaths every 6, patches
meadow, mown, wet (луг)     grass tufts 1.2, clumps 5, patches 30; a mown meadow's mower strips (2.1 each way) and
                            hay windrows every 8; a wet meadow's dark mottling
water (вода)                a river's currents streaked along the flow, foam below the islands' tails (table 10:
                            the speed of flow), wind ripples; a shallow bottom's patches
bogs (болота)               hummocks and hollows 2.5–8, a raised bog's ridges and pools
roads (дороги)              exact edges from the centre lines (carriageway, shoulders, ditches); asphalt's lighter
                            wheel paths and repairs, gravel's dark ruts; the railway's ballast with the darker band
                            of sleepers, two rails 1.52 apart, sleepers every 0.55
gardens (огороды)           vegetable beds 1.2 wide
==========================  ======================================================================================

Every pattern is a **zero-mean** variation around the cover's own tone — stripes and pulses have their mean taken
out, noise is zero-mean — so a cover's mean colour stays its reflectance (the chapter's physics test), and each is
**filtered to the pixel's ground footprint** (a box average for stripes, a blur for lines, a fade for noise finer
than the pixel), so a coarse photo shows a pattern's average tone rather than moiré.  The same ground point gives
the same texture whatever photo sees it: a magnifier's window shows what the whole photo shows, finer.

:func:`pixel_classes` also refines the class map at each pixel: class boundaries are interpolated between texels
(no stair steps at large magnification), and the roads, their shoulders and ditches and the railway are drawn from
their centre lines exactly (the map's 1 m texels round them).  Data only (layer 3); deterministic: seeded noise.
"""

from __future__ import annotations

import functools
import math

import numpy as np

__all__ = ["noise", "noise_gradient", "wave_gradient", "stripes", "pulses", "LineIndex", "pixel_classes", "ground_texture",
           "NOISE_CELLS"]

#: cells of the noise tables (each table is periodic over NOISE_CELLS × its scale)
NOISE_CELLS = 256


@functools.lru_cache(maxsize=64)
def _table(seed: int) -> np.ndarray:
    """Cubic-spline coefficients of a periodic table of seeded white noise, scaled so the interpolated field has a
    mean of 0 and a standard deviation of 1."""
    from scipy.ndimage import map_coordinates, spline_filter

    rng = np.random.default_rng([int(seed), 4242])
    t = rng.standard_normal((NOISE_CELLS, NOISE_CELLS))
    t -= t.mean()
    coef = spline_filter(t, order=3, mode="grid-wrap")
    probe = np.random.default_rng([int(seed), 4243]).random((2, 20000)) * NOISE_CELLS
    sd = float(map_coordinates(coef, probe, order=3, mode="grid-wrap", prefilter=False).std())
    coef /= sd
    coef.flags.writeable = False
    return coef


def noise(X, Y, scale_m: float, seed: int, *, along_m: float | None = None, angle_deg: float = 0.0,
          footprint_m: float = 0.0) -> np.ndarray:
    """Smooth seeded noise at ground points (X, Y) m: mean 0, standard deviation 1, features ``scale_m`` across.

    ``along_m`` stretches it along the direction ``angle_deg`` (counter-clockwise from east): streaks.  A pixel's
    ``footprint_m`` fades features finer than the pixel (factor exp(−½·(footprint/scale)²)).
    """
    from scipy.ndimage import map_coordinates

    att = math.exp(-0.5 * (footprint_m / scale_m) ** 2) if footprint_m > 0 else 1.0
    X = np.asarray(X, float)
    if att < 0.01 or X.size == 0:
        return np.zeros(X.shape, np.float32)
    Y = np.asarray(Y, float)
    a = math.radians(angle_deg)
    u = X * math.cos(a) + Y * math.sin(a)
    v = -X * math.sin(a) + Y * math.cos(a)
    off = (seed * 0.618034) % 1.0 * NOISE_CELLS
    cu = u / (along_m or scale_m) + off
    cv = v / scale_m + 0.5 * off
    out = map_coordinates(_table(seed), [np.mod(cv.ravel(), NOISE_CELLS), np.mod(cu.ravel(), NOISE_CELLS)],
                          order=3, mode="grid-wrap", prefilter=False)
    return (att * out).astype(np.float32).reshape(X.shape)


def noise_gradient(X, Y, scale_m: float, seed: int) -> tuple:
    """(∂/∂X, ∂/∂Y) of :func:`noise` (per metre), by central differences a quarter of ``scale_m`` apart."""
    h = 0.25 * scale_m
    X = np.asarray(X, float)
    Y = np.asarray(Y, float)
    gx = (noise(X + h, Y, scale_m, seed) - noise(X - h, Y, scale_m, seed)) / (2 * h)
    gy = (noise(X, Y + h, scale_m, seed) - noise(X, Y - h, scale_m, seed)) / (2 * h)
    return gx, gy


@functools.lru_cache(maxsize=32)
def _waves(seed: int, k: int = 9) -> tuple:
    """Directions (k, 2), wavenumber factors (k,) and phases (k,) of :func:`wave_gradient`'s plane waves."""
    rng = np.random.default_rng([int(seed), 4244])
    a = rng.uniform(0.0, np.pi, k)
    return np.column_stack([np.cos(a), np.sin(a)]), rng.uniform(0.7, 1.4, k), rng.uniform(0.0, 2 * np.pi, k)


def wave_gradient(X, Y, scale_m: float, seed: int) -> tuple:
    """(∂/∂X, ∂/∂Y), per metre, of a smooth seeded bumpiness of features ``scale_m`` across, standard deviation 1:
    a sum of nine plane waves of random direction, wavelength about π·``scale_m`` and phase (cheap and exact)."""
    d, kf, ph = _waves(int(seed))
    X = np.asarray(X, float)
    Y = np.asarray(Y, float)
    kk = kf / scale_m  # rad per metre
    arg = (X[..., None] * d[:, 0] + Y[..., None] * d[:, 1]) * kk + ph
    amp = math.sqrt(2.0 / len(kf))
    c = -amp * np.sin(arg) * kk
    return (c * d[:, 0]).sum(-1), (c * d[:, 1]).sum(-1)


def stripes(u, period_m: float, footprint_m: float = 0.0, phase: float = 0.0) -> np.ndarray:
    """sin(2π·u/P + φ) averaged over a pixel's footprint (the box filter's sinc; 0 once the pixel spans P)."""
    k = float(np.sinc(footprint_m / period_m)) if footprint_m < period_m else 0.0
    if k <= 0:
        return np.zeros(np.shape(u), np.float32)
    return (k * np.sin(2 * np.pi * np.asarray(u, float) / period_m + phase)).astype(np.float32)


def pulses(u, period_m: float, width_m: float, footprint_m: float = 0.0, *, offset_m: float = 0.0) -> np.ndarray:
    """Lines ``width_m`` wide (full width at half height) every ``period_m`` along u, minus their mean: zero-mean.

    A pixel's footprint blurs a line (wider and fainter, its area kept); lines blurred into each other fade out.
    """
    sig = width_m / 2.3548
    sig_b = math.hypot(sig, 0.2887 * footprint_m)
    fade = min(max((period_m / 4.0 - sig_b) / (period_m / 8.0), 0.0), 1.0)
    if fade <= 0:
        return np.zeros(np.shape(u), np.float32)
    d = np.mod(np.asarray(u, float) - offset_m + period_m / 2.0, period_m) - period_m / 2.0
    p = (sig / sig_b) * np.exp(-0.5 * (d / sig_b) ** 2)
    return (fade * (p - sig * math.sqrt(2 * math.pi) / period_m)).astype(np.float32)


# =========================================================================== lines: roads and the railway
class LineIndex:
    """Distance from a polyline and arc length along it, for many points (a k-d tree of its densified vertices)."""

    def __init__(self, pts, step_m: float = 0.5):
        from scipy.spatial import cKDTree

        pts = np.asarray(pts, float)
        seg = np.diff(pts, axis=0)
        L = np.hypot(seg[:, 0], seg[:, 1])
        s0 = np.r_[0.0, np.cumsum(L)]
        s = np.arange(0.0, s0[-1] + step_m, step_m)
        self.xy = np.column_stack([np.interp(s, s0, pts[:, 0]), np.interp(s, s0, pts[:, 1])])
        self.s = s
        self.tree = cKDTree(self.xy)

    def query(self, X, Y, reach_m: float) -> tuple:
        """``(d, s)``: distance (m; inf beyond ``reach_m``) and arc length of the nearest point of the line."""
        P = np.column_stack([np.ravel(X), np.ravel(Y)])
        d = np.full(len(P), np.inf)
        s = np.zeros(len(P))
        if not len(P):
            return d, s
        dist, j = self.tree.query(P, distance_upper_bound=reach_m + 1.0)
        ok = np.isfinite(dist)
        j = j[ok]
        Q = P[ok]
        best = np.full(len(Q), np.inf)
        best_s = np.zeros(len(Q))
        n = len(self.xy)
        for a, b in ((j - 1, j), (j, j + 1)):  # the two segments at the nearest vertex
            a = np.clip(a, 0, n - 1)
            b = np.clip(b, 0, n - 1)
            A, B = self.xy[a], self.xy[b]
            AB = B - A
            L2 = np.maximum(np.einsum("ij,ij->i", AB, AB), 1e-12)
            t = np.clip(np.einsum("ij,ij->i", Q - A, AB) / L2, 0.0, 1.0)
            C = A + t[:, None] * AB
            dd = np.hypot(*(Q - C).T)
            better = dd < best
            best[better] = dd[better]
            best_s[better] = (self.s[a] + t * (self.s[b] - self.s[a]))[better]
        d[ok] = np.where(best <= reach_m, best, np.inf)
        s[ok] = best_s
        return d.reshape(np.shape(X)), s.reshape(np.shape(X))


@functools.lru_cache(maxsize=2)
def _lines(isite) -> dict:
    """The site's roads and railway as :class:`LineIndex` es, by class name, with their half-widths (m)."""
    from .cover import LINEAR

    return {name: (LineIndex(isite.features[key]), w) for name, (key, w) in LINEAR.items()}


@functools.lru_cache(maxsize=2)
def _near_lines(isite) -> np.ndarray:
    """Texels within 3 m of a road, shoulder, ditch or the railway (bool, the class map's grid)."""
    from scipy.ndimage import binary_dilation

    from .cover import CLASS_CODES as C

    lin = np.isin(isite.classes, [C[k] for k in ("asphalt road", "gravel road", "dirt road", "railway", "ditch")])
    out = binary_dilation(lin, iterations=3)
    out.flags.writeable = False
    return out


def _interp_class(cmap: np.ndarray, X, Y, texel_m: float) -> np.ndarray:
    """The class at points between texels: of the (up to four) classes of the surrounding texel centres, the one
    with the largest bilinear weight — boundaries run smoothly between texels instead of in steps."""
    n = cmap.shape[0]
    fx = np.asarray(X, float) / texel_m - 0.5
    fy = np.asarray(Y, float) / texel_m - 0.5
    x0 = np.floor(fx)
    y0 = np.floor(fy)
    tx = fx - x0
    ty = fy - y0
    c0 = np.clip(x0.astype(np.int64), 0, n - 1)
    c1 = np.clip(c0 + 1, 0, n - 1)
    r0 = np.clip(y0.astype(np.int64), 0, n - 1)
    r1 = np.clip(r0 + 1, 0, n - 1)
    cs = [cmap[r0, c0], cmap[r0, c1], cmap[r1, c0], cmap[r1, c1]]
    ws = [(1 - tx) * (1 - ty), tx * (1 - ty), (1 - tx) * ty, tx * ty]
    best = cs[0].copy()
    best_w = np.full(best.shape, -1.0)
    for ck in cs:
        w = sum(wj * (cj == ck) for wj, cj in zip(ws, cs))
        better = w > best_w
        best[better] = ck[better]
        best_w[better] = w[better]
    return best


def pixel_classes(isite, X, Y) -> tuple:
    """The land-cover class each pixel sees, at its ground point (X, Y) m (arrays of one shape).

    Returns ``(classes uint8, lines)``: the class map interpolated between texels, with the roads, shoulders,
    ditches and the railway redrawn from their centre lines (the painting rules of
    :mod:`aerophoto.site.cover`, at the point); ``lines`` maps each line's class name to ``(pixels, d, s)`` — the
    flat indices of the pixels near it, their distance from its centre line and arc length along it (m).
    Off the site: class 0.
    """
    from .cover import CLASS_CODES as C, SIZE_M

    X = np.asarray(X, float)
    Y = np.asarray(Y, float)
    t = isite.texel_m
    cls = _interp_class(isite.classes, X, Y, t)
    n = isite.classes.shape[0]
    near = _near_lines(isite)[np.clip((Y / t).astype(np.int64), 0, n - 1), np.clip((X / t).astype(np.int64), 0, n - 1)]
    idx = np.flatnonzero(near)
    lines = {}
    if len(idx):
        xs, ys = X.ravel()[idx], Y.ravel()[idx]
        under = _interp_class(isite.under_roads, xs, ys, t)
        water = np.isin(under, [C["deep water"], C["shallow water"]])
        new = under.copy()
        got = {}
        for name, (line, w) in _lines(isite).items():
            d, s = line.query(xs, ys, reach_m=8.0)
            got[name] = (d, s, w)
        for name in ("gravel road", "asphalt road"):  # the painting order of cover._paint_roads_and_railway
            d, _, w = got[name]
            new[(d >= w + 1.0) & (d < w + 3.0) & ~water] = C["ditch"]
            new[(d < w + 1.0) & ~water] = C["dirt road"]
            new[d < w] = C[name]
        d, _, w = got["railway"]
        new[(d >= w + 1.0) & (d < w + 3.0) & ~water & (new != C["asphalt road"])] = C["ditch"]
        new[d < w] = C["railway"]
        flat = cls.ravel().copy()
        flat[idx] = new
        cls = flat.reshape(X.shape)
        for name, (d, s, _) in got.items():
            keep = np.isfinite(d)
            lines[name] = (idx[keep], d[keep], s[keep])
    off = (X < 0) | (X > SIZE_M) | (Y < 0) | (Y > SIZE_M)
    cls = np.where(off, 0, cls).astype(np.uint8)
    return cls, lines


# =========================================================================== the covers' textures
def _field_frame(isite, X, Y):
    """For points in the arable fields: (field index or −1, u along the rows, v across them, distance to the
    field's nearer end) in metres."""
    k = np.full(X.shape, -1, np.int64)
    u = np.zeros(X.shape)
    v = np.zeros(X.shape)
    e = np.full(X.shape, np.inf)
    for j, f in enumerate(isite.features["fields"]):
        kind, x0, x1, y0, y1 = f[:5]
        rows_along_x = (x1 - x0) > (y1 - y0)
        m = (X >= x0) & (X <= x1) & (Y >= y0) & (Y <= y1)
        if not m.any():
            continue
        k[m] = j
        if rows_along_x:
            u[m], v[m] = X[m] - x0, Y[m] - y0
            e[m] = np.minimum(X[m] - x0, x1 - X[m])
        else:
            u[m], v[m] = Y[m] - y0, X[m] - x0
            e[m] = np.minimum(Y[m] - y0, y1 - Y[m])
    return k, u, v, e


def _river_frame(isite, X, Y):
    """(along the river's centre line s, offset from it, half-width) at the points, m (bilinear on the site's
    rasters; far from the river the offset is large)."""
    from scipy.ndimage import map_coordinates

    t = isite.texel_m
    crd = [np.asarray(Y, float).ravel() / t - 0.5, np.asarray(X, float).ravel() / t - 0.5]
    rv = isite.river
    out = [map_coordinates(a, crd, order=1, mode="nearest").reshape(np.shape(X)) for a in (rv["s"], rv["off"],
                                                                                           rv["half"])]
    return tuple(out)


def _tex_fields(isite, code, X, Y, fp, gain, soil):
    """Ploughed fields, crops and stubble: furrows, tramlines, swaths and headlands in each field's own frame."""
    from .cover import CLASS_CODES as C

    k, u, v, e = _field_frame(isite, X, Y)
    head = e < 12.0  # the headland: rows run across, parallel to the field's end
    uu = np.where(head, v, u)
    vv = np.where(head, e, v)
    ph = (k + 1) * 2.399  # each field its own phase (radians)
    if code == C["ploughed field"]:
        gain += 0.10 * stripes(vv, 0.35, fp, 0.0) + 0.07 * stripes(vv, 1.75, fp, 1.0)
        gain += -0.22 * pulses(vv, 36.0, 0.8, fp, offset_m=7.0)
        gain += 0.06 * noise(uu, vv, 0.6, 11, along_m=6.0, footprint_m=fp)
        gain += 0.06 * noise(X, Y, 25.0, 12, footprint_m=fp) + 0.04 * noise(X, Y, 8.0, 13, footprint_m=fp)
    elif code == C["crop"]:
        track = pulses(vv + 0.9, 18.0, 0.5, fp, offset_m=9.0 + 2 * ph) + pulses(vv - 0.9, 18.0, 0.5, fp,
                                                                                offset_m=9.0 + 2 * ph)
        soil += 0.7 * track
        soil += 0.05 * noise(X, Y, 30.0, 21, footprint_m=fp) + 0.03 * noise(X, Y, 10.0, 22, footprint_m=fp)
        gain += 0.03 * noise(uu, vv, 0.8, 23, along_m=30.0, footprint_m=fp)
        gain += 0.04 * stripes(vv, 0.6, fp, ph)
        gain += -0.04 * pulses(e, 1e3, 1.5, fp, offset_m=12.0)  # where the headland's turns meet the rows
    elif code == C["stubble"]:
        gain += 0.18 * pulses(vv, 6.0, 1.4, fp, offset_m=ph)
        gain += 0.05 * noise(X, Y, 20.0, 31, footprint_m=fp) + 0.04 * noise(X, Y, 3.0, 32, footprint_m=fp)
        gain += 0.05 * stripes(vv, 0.3, fp, ph)


def _tex_water(isite, code, X, Y, fp, gain):
    """Water: the river's currents and foam (faster in the narrows, foam below the islands), ripples, bottoms."""
    from .cover import CLASS_CODES as C

    s, off, half = _river_frame(isite, X, Y)
    river = np.abs(off) < half + 6.0
    gain += 0.03 * noise(X, Y, 1.5, 41, footprint_m=fp) + 0.03 * noise(X, Y, 12.0, 42, footprint_m=fp)
    if river.any():
        streak = noise(s[river], off[river], 1.2, 43, along_m=25.0, footprint_m=fp)
        speed = np.clip(22.0 / np.maximum(half[river], 5.0), 0.6, 1.6)  # narrower: faster, sharper pattern
        gain[river] += 0.06 * speed * streak
        foam = np.zeros(int(river.sum()), np.float32)
        for isl in isite.features["islands"]:
            s_tail = float(isl["s_tail_m"])
            zone = np.clip(1.0 - np.abs(s[river] - s_tail - 35.0) / 45.0, 0.0, 1.0) * (np.abs(off[river]) < 14.0)
            f = np.maximum(noise(s[river], off[river], 0.8, 44, along_m=6.0, footprint_m=fp), 0.0) - 0.399 * (
                math.exp(-0.5 * (fp / 0.8) ** 2) if fp > 0 else 1.0)
            foam += zone * f
        gain[river] += 0.9 * foam
    if code == C["shallow water"]:
        gain += 0.08 * noise(X, Y, 5.0, 45, footprint_m=fp) + 0.04 * noise(X, Y, 1.5, 46, footprint_m=fp)


def _across(d, centres, width_m, half_m, fp):
    """Lines along a road at distances ``centres`` from its axis (m), ``width_m`` wide, minus their mean over the
    road's half-width ``half_m``: zero-mean across the carriageway."""
    g = sum(pulses(d - c, 1e3, width_m, fp) for c in centres)
    return g - np.float32(len(centres) * width_m * 1.0645 / half_m)


def _tex_lines(code, d, s, fp):
    """Roads and the railway across and along their centre line: wheel paths, ruts, sleepers and rails."""
    from .cover import CLASS_CODES as C, LINEAR

    g = np.zeros(len(d), np.float32)
    if code == C["asphalt road"]:  # each lane's two wheel paths, lighter (polished)
        g += 0.06 * _across(d, (0.95, 2.55), 0.6, LINEAR["asphalt road"][1], fp)
        g += 0.05 * noise(d, s, 6.0, 51, footprint_m=fp) + 0.03 * noise(d, s, 0.5, 52, footprint_m=fp)
    elif code == C["gravel road"]:  # the ruts, darker
        g += -0.12 * _across(d, (0.8, 2.1), 0.45, LINEAR["gravel road"][1], fp)
        g += 0.06 * noise(d, s, 1.0, 53, footprint_m=fp)
    elif code == C["railway"]:
        w = LINEAR["railway"][1]
        band = 1.0 / (1.0 + np.exp((d - 1.35) / 0.12))  # the sleepers' band, 2.7 m wide, in the lighter ballast
        g += -0.20 * (band - 1.35 / w)
        g += band * 0.12 * stripes(s, 0.55, fp)  # sleepers
        g += -0.5 * _across(d, (0.76,), 0.07, w, fp)  # the two rails (d is the distance from the track's axis)
        g += 0.05 * noise(d, s, 0.4, 54, footprint_m=fp)
    return g


_GRASS = {  # class: ((amplitude, scale m, seed), ...) of the cover's noise
    "meadow": ((0.05, 1.2, 61), (0.05, 5.0, 62), (0.05, 30.0, 63)),
    "mown meadow": ((0.04, 3.0, 64),),
    "wet meadow": ((0.12, 4.0, 65), (0.05, 1.0, 66)),
    "haystack": ((0.05, 1.0, 67),),
    "pine forest": ((0.08, 2.0, 68),), "spruce forest": ((0.08, 2.0, 69),), "deciduous forest": ((0.08, 2.0, 70),),
    "shrub": ((0.08, 1.5, 71),),
    "raised bog": ((0.15, 2.5, 72), (0.10, 8.0, 73)),
    "low bog": ((0.10, 1.5, 74), (0.08, 6.0, 75)),
    "sand bank": ((0.06, 3.0, 76),),
    "dirt road": ((0.08, 1.0, 77),), "ditch": ((0.10, 1.0, 78),), "dam": ((0.06, 1.5, 79),),
    "garden": ((0.06, 2.0, 80),), "slate roof": ((0.03, 0.5, 81),), "red iron roof": ((0.03, 0.5, 82),),
}


def ground_texture(isite, cls, X, Y, footprint_m: float, lines: dict | None = None) -> tuple:
    """Each pixel's texture: ``(gain, soil_shift)`` float32 of the points' shape (see the module notes).

    ``gain`` multiplies the pixel's reflectance (mean 1 over a cover); ``soil_shift`` moves its share of bare soil
    (mean 0; arable land only).  ``cls`` from :func:`pixel_classes` (with its ``lines``), ``footprint_m`` the
    pixel's size on the ground (m).
    """
    from .cover import CLASS_CODES as C

    X = np.asarray(X, float)
    Y = np.asarray(Y, float)
    shape = X.shape
    cls = np.asarray(cls).ravel()
    Xf, Yf = X.ravel(), Y.ravel()
    gain = np.ones(len(cls), np.float32)
    soil = np.zeros(len(cls), np.float32)
    fp = float(footprint_m)
    order = np.argsort(cls, kind="stable")
    bounds = np.searchsorted(cls[order], np.arange(0, 256 + 1))
    for code in np.unique(cls):
        if code == 0:
            continue
        pix = order[bounds[code]:bounds[code + 1]]
        x, y = Xf[pix], Yf[pix]
        g = np.zeros(len(pix), np.float32)
        sl = np.zeros(len(pix), np.float32)
        name = next(k for k, c in C.items() if c == code)
        for amp, scale, seed in _GRASS.get(name, ()):
            g += amp * noise(x, y, scale, seed, footprint_m=fp)
        if name in ("ploughed field", "crop", "stubble"):
            _tex_fields(isite, code, x, y, fp, g, sl)
        elif name in ("deep water", "shallow water"):
            _tex_water(isite, code, x, y, fp, g)
        elif name == "mown meadow":
            g += 0.07 * stripes(x, 4.2, fp) + 0.12 * pulses(x, 8.0, 1.0, fp, offset_m=3.0)
        elif name == "garden":
            sl += 0.25 * stripes(x, 1.2, fp)
        elif name == "raised bog":
            g += 0.08 * noise(x, y, 4.0, 83, along_m=25.0, angle_deg=30.0, footprint_m=fp)
        if lines and name in ("asphalt road", "gravel road", "railway") and name in lines:
            at, d, s = lines[name]
            pos = np.searchsorted(at, pix)
            pos = np.minimum(pos, max(len(at) - 1, 0))
            hit = (len(at) > 0) & (at[pos] == pix) if len(at) else np.zeros(len(pix), bool)
            if np.any(hit):
                g[hit] += _tex_lines(code, d[pos[hit]], s[pos[hit]], fp)
        gain[pix] += g
        soil[pix] = sl
    np.maximum(gain, 0.05, out=gain)
    return gain.reshape(shape), soil.reshape(shape)
