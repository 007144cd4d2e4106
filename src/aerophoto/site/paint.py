"""Painting tools of the virtual site's generator: noise, field systems, forest crowns, a canvas.

Private helpers of :mod:`aerophoto.site.build`: smooth value noise from cubic
B-splines, furrow profiles, the rotated field layouts (:class:`FieldSystem`),
a tile of tree crowns, the texture canvas with anti-aliased bands, rectangles
and discs (:class:`Canvas`), and small plane-geometry helpers.  Metres on
the ground, texture pixels ``t`` metres square, row 0 at the south edge.
"""

from __future__ import annotations

import math

import numpy as np

__all__ = ["bilinear", "bspline_matrix", "smooth_noise", "furrow_profiles", "FieldSystem", "crown_tile",
           "Canvas", "seg_distance", "seg_intersection"]


def bilinear(grid: np.ndarray, fx, fy) -> np.ndarray:
    """Bilinear interpolation of ``grid[j, i]`` at fractional indices (fx = i, fy = j), edge-clamped."""
    ny, nx = grid.shape
    fx = np.clip(fx, 0.0, nx - 1.0)
    fy = np.clip(fy, 0.0, ny - 1.0)
    i0 = np.minimum(fx.astype(np.int64), nx - 2) if nx > 1 else np.zeros(np.shape(fx), np.int64)
    j0 = np.minimum(fy.astype(np.int64), ny - 2) if ny > 1 else np.zeros(np.shape(fy), np.int64)
    tx = fx - i0
    ty = fy - j0
    g00 = grid[j0, i0]
    g01 = grid[j0, i0 + 1]
    g10 = grid[j0 + 1, i0]
    g11 = grid[j0 + 1, i0 + 1]
    return (g00 * (1 - tx) + g01 * tx) * (1 - ty) + (g10 * (1 - tx) + g11 * tx) * ty


def bspline_matrix(n_out: int, cell: float, n_grid: int) -> np.ndarray:
    """(n_out, n_grid) cubic B-spline interpolation weights for output pixels at cell spacing ``cell``."""
    p = np.arange(n_out) / cell + 1.0
    b = np.floor(p).astype(int)
    f = p - b
    w = np.stack([
        (1 - f) ** 3 / 6.0,
        (3 * f**3 - 6 * f**2 + 4) / 6.0,
        (-3 * f**3 + 3 * f**2 + 3 * f + 1) / 6.0,
        f**3 / 6.0,
    ], axis=1)
    M = np.zeros((n_out, n_grid), dtype=np.float32)
    rows = np.arange(n_out)
    for k in range(4):
        M[rows, np.clip(b - 1 + k, 0, n_grid - 1)] += w[:, k]
    return M


def smooth_noise(rng, ny: int, nx: int, cell: float) -> np.ndarray:
    """Smooth value noise of about unit standard deviation, shape (ny, nx), features ~``cell`` pixels."""
    gy = int(ny / cell) + 4
    gx = int(nx / cell) + 4
    G = rng.standard_normal((gy, gx)).astype(np.float32)
    Wy = bspline_matrix(ny, cell, gy)
    Wx = bspline_matrix(nx, cell, gx)
    out = (Wy @ G) @ Wx.T
    norm = float(np.sqrt(np.mean(np.sum(Wy**2, axis=1)) * np.mean(np.sum(Wx**2, axis=1))))
    out *= np.float32(1.0 / norm)
    return out


# furrow profiles over one period (256 samples), amplitude ±1: ploughed, crop with tramlines, stubble swaths,
# fallow (none), grass with broad mowing stripes
def furrow_profiles() -> np.ndarray:
    x = (np.arange(256) + 0.5) / 256.0
    two_pi = 2.0 * np.pi
    ploughed = np.sin(two_pi * x) + 0.35 * np.sin(2 * two_pi * x + 1.0)
    tram = -2.2 * np.exp(-(((x - 0.5) / 0.035) ** 2)) + 0.25 * np.sin(8 * two_pi * x) + 0.3
    swath = 2.0 * (0.5 + 0.5 * np.sin(two_pi * x)) ** 4 - 0.55
    grass = np.tanh(3.0 * np.sin(two_pi * x))
    prof = np.stack([ploughed / np.abs(ploughed).max(), tram / np.abs(tram).max(), swath / np.abs(swath).max(),
                     np.zeros(256), grass])
    return prof.astype(np.float32)


class FieldSystem:
    """A field layout in a frame (u, v) rotated by ``theta`` about the site centre.

    The v axis is cut into bands (band boundaries run along u), each band into
    parcels by its own cross boundaries (along v), so parcels are rectangles
    meeting in T-junctions.  Each parcel has a land use, a tone and a furrow
    pattern (a 256-sample profile along a direction, with a period); the
    brightness of a pixel is one look-up in a (parcel, phase) table.
    """

    KIND_P = (0.3, 0.3, 0.2, 0.1, 0.1)
    TONE = ((0.24, 0.36), (0.38, 0.52), (0.58, 0.74), (0.45, 0.58), (0.44, 0.56))
    AMP = ((0.05, 0.08), (0.05, 0.08), (0.04, 0.06), (0.0, 0.0), (0.02, 0.035))
    PERIOD = ((10.0, 16.0), (18.0, 28.0), (6.0, 10.0), (10.0, 10.0), (30.0, 50.0))

    def __init__(self, rng_layout, rng_tex, theta, cx, cy, R, q, band_w, cell_w):
        self.theta = theta  # turn of the layout from the X axis, radians
        self.ct, self.st = math.cos(theta), math.sin(theta)
        self.cx, self.cy, self.R, self.q = cx, cy, R, q
        v_edges = [-R - rng_layout.uniform(0.0, band_w[1])]
        while v_edges[-1] < R:
            v_edges.append(v_edges[-1] + rng_layout.uniform(*band_w))
        self.v_edges = np.array(v_edges)
        n_bands = len(v_edges) - 1
        self.u_edges = []
        for _ in range(n_bands):
            e = [-R - rng_layout.uniform(0, cell_w[1])]
            while e[-1] < R:
                e.append(e[-1] + rng_layout.uniform(*cell_w))
            self.u_edges.append(np.array(e))
        self.n_q = n_q = int(math.ceil(2 * R / q)) + 2
        centres = -R + (np.arange(n_q) + 0.5) * q
        self.band_lut = np.clip(np.searchsorted(self.v_edges, centres) - 1, 0, n_bands - 1).astype(np.int32)
        self.max_cells = max(len(e) for e in self.u_edges) - 1
        cell = np.zeros((n_bands, n_q), np.int32)
        for j, e in enumerate(self.u_edges):
            cell[j] = np.clip(np.searchsorted(e, centres) - 1, 0, len(e) - 2)
        self.cell_lut = cell.reshape(-1)
        n = self.n_parcels = n_bands * self.max_cells
        kind = rng_tex.choice(5, size=n, p=self.KIND_P)
        lo = np.array([self.TONE[k][0] for k in kind])
        hi = np.array([self.TONE[k][1] for k in kind])
        tone = lo + (hi - lo) * rng_tex.random(n)
        lo = np.array([self.AMP[k][0] for k in kind])
        hi = np.array([self.AMP[k][1] for k in kind])
        amp = lo + (hi - lo) * rng_tex.random(n)
        lo = np.array([self.PERIOD[k][0] for k in kind])
        hi = np.array([self.PERIOD[k][1] for k in kind])
        period = lo + (hi - lo) * rng_tex.random(n)
        # furrows along the parcel's long or short side, now and then diagonal
        ang = rng_tex.choice([0.0, 0.5 * np.pi, 0.25 * np.pi, -0.25 * np.pi], size=n, p=[0.45, 0.45, 0.05, 0.05])
        self.fu = (np.cos(ang) / period).astype(np.float32)  # cycles per metre along u and v
        self.fv = (np.sin(ang) / period).astype(np.float32)
        self.ph = (rng_tex.random(n) + 4096.0).astype(np.float32)  # + whole cycles: keeps the phase positive
        prof = furrow_profiles()
        self.table = (tone[:, None] + amp[:, None] * prof[kind]).astype(np.float32).reshape(-1)
        self.kind = kind

    def values(self, Xc, Yc) -> np.ndarray:
        """Brightness of the fields at pixel centres Xc (nx,) × Yc (ny,), float32 (ny, nx)."""
        ct, st, R = np.float32(self.ct), np.float32(self.st), np.float32(self.R)
        dx = Xc - np.float32(self.cx)
        dy = (Yc - np.float32(self.cy))[:, None]
        uR = dy * st + (dx * ct + R)[None, :]  # u + R ≥ 0
        vR = dy * ct + (R - dx * st)[None, :]  # v + R ≥ 0
        iq = np.float32(1.0 / self.q)
        qu = (uR * iq).astype(np.int32)
        qv = (vR * iq).astype(np.int32)
        band = self.band_lut[qv]
        pid = band * self.max_cells
        band *= self.n_q
        band += qu
        pid += self.cell_lut[band]
        w = uR * self.fu[pid]
        w += vR * self.fv[pid]
        w += self.ph[pid]
        w *= np.float32(256.0)
        i = w.astype(np.int32)
        i &= 255
        pid <<= 8
        pid |= i
        return self.table[pid]

    def uv_to_xy(self, u, v):
        return np.array([self.cx + u * self.ct - v * self.st, self.cy + u * self.st + v * self.ct])

    def boundaries(self, clip):
        """Band boundaries, cross boundaries (segments in X, Y) and their T-junctions (field corners)."""
        R = self.R
        n_bands = len(self.v_edges) - 1
        long_b = []
        for j in range(1, n_bands):
            seg = clip(self.uv_to_xy(-R, self.v_edges[j]), self.uv_to_xy(R, self.v_edges[j]), pad=20.0)
            if seg:
                long_b.append(seg)
        cross_b, corners = [], []
        for j, e in enumerate(self.u_edges):
            for k in range(1, len(e) - 1):
                seg = clip(self.uv_to_xy(e[k], self.v_edges[j]), self.uv_to_xy(e[k], self.v_edges[j + 1]), pad=20.0)
                if seg:
                    cross_b.append(seg)
                    if j > 0:
                        corners.append(self.uv_to_xy(e[k], self.v_edges[j]))
                    if j + 1 < n_bands:
                        corners.append(self.uv_to_xy(e[k], self.v_edges[j + 1]))
        return long_b, cross_b, corners


def crown_tile(rng, t: float, size_m: float = 512.0) -> np.ndarray:
    """A square tile of forest seen from above: crowns (2–4.5 m radius) lit from the south-west, float32."""
    n = max(int(round(size_m / t)), 16)
    cv = Canvas(n, n, t)
    cv.img[:] = 0.06  # the dark floor between the crowns
    side = n * t
    k = int(side * side / 22.0)  # about one tree per 22 m²
    xy = rng.uniform(0.0, side, (k, 2))
    r = rng.uniform(2.0, 4.5, k)
    tone = rng.uniform(0.16, 0.32, k)
    for dx in (-side, 0.0, side):  # wrap around so that the tile repeats seamlessly
        for dy in (-side, 0.0, side):
            sel = ((xy[:, 0] + dx > -6) & (xy[:, 0] + dx < side + 6)
                   & (xy[:, 1] + dy > -6) & (xy[:, 1] + dy < side + 6))
            p = xy[sel] + [dx, dy]
            cv.discs(p + 1.5, r[sel] * 0.9, 0.05)  # shadow to the north-east
            cv.discs(p, r[sel], tone[sel])
            cv.discs(p - 0.35 * r[sel, None], r[sel] * 0.45, np.minimum(tone[sel] + 0.08, 0.45))  # sunlit side
    return cv.img


class Canvas:
    """Texture under construction: brightness (float32), cover codes (uint8), painting helpers."""

    def __init__(self, ny, nx, t):
        self.ny, self.nx, self.t = ny, nx, t
        self.img = np.zeros((ny, nx), np.float32)
        self.cover = np.zeros((ny, nx), np.uint8)

    # -- linear features: returns (rows, cols, coverage) of a segment's band, anti-aliased
    def band(self, p0, p1, half_w):
        t = self.t
        p0 = np.asarray(p0, float)
        p1 = np.asarray(p1, float)
        d = p1 - p0
        L = float(np.hypot(*d))
        if L == 0:
            return None
        steep = abs(d[1]) > abs(d[0])
        a, b = (1, 0) if steep else (0, 1)  # a: the stepping axis (0 = X), b: the other
        lo = min(p0[a], p1[a]) - half_w - t
        hi = max(p0[a], p1[a]) + half_w + t
        n_a = self.ny if steep else self.nx
        n_b = self.nx if steep else self.ny
        k0 = max(int(math.floor(lo / t)), 0)
        k1 = min(int(math.ceil(hi / t)), n_a - 1)
        if k1 < k0:
            return None
        ks = np.arange(k0, k1 + 1)
        ca = (ks + 0.5) * t
        slope = d[b] / d[a]
        cb_line = p0[b] + (np.clip(ca, min(p0[a], p1[a]), max(p0[a], p1[a])) - p0[a]) * slope
        span = half_w * math.hypot(1.0, slope) + 1.5 * t
        m = int(math.ceil(span / t)) + 1
        kb = np.floor(cb_line / t).astype(np.int64)[:, None] + np.arange(-m, m + 1)[None, :]
        ka = np.broadcast_to(ks[:, None], kb.shape)
        ok = (kb >= 0) & (kb < n_b)
        ka = ka[ok]
        kb = kb[ok]
        pa = (ka + 0.5) * t
        pb = (kb + 0.5) * t
        if steep:
            px, py = pb, pa
            rows, cols = ka, kb
        else:
            px, py = pa, pb
            rows, cols = kb, ka
        u = np.clip(((px - p0[0]) * d[0] + (py - p0[1]) * d[1]) / (L * L), 0.0, 1.0)
        dist = np.hypot(px - (p0[0] + u * d[0]), py - (p0[1] + u * d[1]))
        cov = np.clip((half_w - dist) / t + 0.5, 0.0, 1.0).astype(np.float32)
        keep = cov > 0
        return rows[keep], cols[keep], cov[keep]

    def layer(self, segments, half_w):
        """Max-coverage layer of a list of segments (p0, p1) with half-width ``half_w`` (m): sparse form."""
        parts = [self.band(p0, p1, half_w) for p0, p1 in segments]
        parts = [p for p in parts if p is not None and len(p[0])]
        if not parts:
            return None
        r = np.concatenate([p[0] for p in parts])
        c = np.concatenate([p[1] for p in parts])
        a = np.concatenate([p[2] for p in parts])
        idx = r * self.nx + c
        order = np.lexsort((a, idx))
        idx = idx[order]
        a = a[order]
        last = np.ones(len(idx), bool)
        last[:-1] = idx[1:] != idx[:-1]
        return idx[last], a[last]

    def paint(self, sparse, value, cover_code=None, opacity=1.0):
        """Blend ``value`` (scalar or full-size array) into the image where a sparse layer covers."""
        if sparse is None:
            return
        idx, a = sparse
        a = a * np.float32(opacity)
        flat = self.img.reshape(-1)
        v = value(idx) if callable(value) else (value if np.isscalar(value) else value.reshape(-1)[idx])
        flat[idx] = flat[idx] * (1 - a) + v * a
        if cover_code is not None:
            sel = idx[a >= 0.5]
            self.cover.reshape(-1)[sel] = cover_code

    def paint_mask(self, mask, value, cover_code=None):
        """Blend ``value`` where a full-size coverage mask (0…1, float32) is positive."""
        sel = np.flatnonzero(mask > 0)
        a = mask.reshape(-1)[sel]
        flat = self.img.reshape(-1)
        v = value(sel) if callable(value) else (value if np.isscalar(value) else value.reshape(-1)[sel])
        flat[sel] = flat[sel] * (1 - a) + v * a
        if cover_code is not None:
            self.cover.reshape(-1)[sel[a >= 0.5]] = cover_code

    def _blend(self, rows, cols, a, value, cover_code) -> None:
        """Blend shapes' coverage ``a`` (n, k, k) at pixel (rows, cols) with their values; where
        shapes overlap a pixel, the one covering it most wins (one write per pixel)."""
        ok = (a > 0) & (rows >= 0) & (rows < self.ny) & (cols >= 0) & (cols < self.nx)
        idx = (rows * self.nx + cols)[ok]
        a = a[ok]
        vals = np.broadcast_to(np.asarray(value, np.float32).reshape(-1, 1, 1), ok.shape)[ok]
        order = np.lexsort((a, idx))
        idx, a, vals = idx[order], a[order], vals[order]
        last = np.ones(len(idx), bool)
        last[:-1] = idx[1:] != idx[:-1]
        idx, a, vals = idx[last], a[last], vals[last]
        flat = self.img.reshape(-1)
        flat[idx] = flat[idx] * (1 - a) + vals * a
        if cover_code is not None:
            self.cover.reshape(-1)[idx[a >= 0.5]] = cover_code

    def rects(self, centres, half_sizes, angles, value, cover_code=None, soft=1.0):
        """Paint filled rotated rectangles (centre (n,2) m, half sizes (n,2) m, angle (n,) rad)."""
        centres = np.asarray(centres, float).reshape(-1, 2)
        if len(centres) == 0:
            return
        half_sizes = np.asarray(half_sizes, float).reshape(-1, 2)
        angles = np.asarray(angles, float).reshape(-1)
        t = self.t
        R = float(np.max(np.hypot(half_sizes[:, 0], half_sizes[:, 1]))) + 2 * t
        m = int(math.ceil(R / t))
        off = np.arange(-m, m + 1)
        c0 = np.floor(centres[:, 0] / t).astype(np.int64)
        r0 = np.floor(centres[:, 1] / t).astype(np.int64)
        cols = c0[:, None, None] + off[None, None, :]
        rows = r0[:, None, None] + off[None, :, None]
        cols, rows = np.broadcast_arrays(cols, rows)
        px = (cols + 0.5) * t - centres[:, 0, None, None]
        py = (rows + 0.5) * t - centres[:, 1, None, None]
        ca = np.cos(angles)[:, None, None]
        sa = np.sin(angles)[:, None, None]
        lu = px * ca + py * sa
        lv = -px * sa + py * ca
        cu = np.clip((half_sizes[:, 0, None, None] - np.abs(lu)) / (t * soft) + 0.5, 0, 1)
        cv = np.clip((half_sizes[:, 1, None, None] - np.abs(lv)) / (t * soft) + 0.5, 0, 1)
        a = (cu * cv).astype(np.float32)
        self._blend(rows, cols, a, value, cover_code)

    def discs(self, centres, radii, value, cover_code=None):
        centres = np.asarray(centres, float).reshape(-1, 2)
        if len(centres) == 0:
            return
        radii = np.broadcast_to(np.asarray(radii, float), (len(centres),))
        t = self.t
        m = int(math.ceil(float(radii.max()) / t)) + 2
        off = np.arange(-m, m + 1)
        c0 = np.floor(centres[:, 0] / t).astype(np.int64)
        r0 = np.floor(centres[:, 1] / t).astype(np.int64)
        cols, rows = np.broadcast_arrays(c0[:, None, None] + off[None, None, :], r0[:, None, None] + off[None, :, None])
        px = (cols + 0.5) * t - centres[:, 0, None, None]
        py = (rows + 0.5) * t - centres[:, 1, None, None]
        a = np.clip((radii[:, None, None] - np.hypot(px, py)) / t + 0.5, 0, 1).astype(np.float32)
        self._blend(rows, cols, a, value, cover_code)


def seg_distance(p, a, b) -> float:
    """Distance from point p to the segment a–b."""
    d = b - a
    u = min(max(float((p - a) @ d) / float(d @ d), 0.0), 1.0)
    return float(np.hypot(*(p - a - u * d)))


def seg_intersection(p, p2, q, q2, tol=1e-9):
    """Intersection point of segments p–p2 and q–q2, or None (touching ends count)."""
    r = p2 - p
    s = q2 - q
    den = r[0] * s[1] - r[1] * s[0]
    if abs(den) < 1e-12:
        return None
    qp = q - p
    t = (qp[0] * s[1] - qp[1] * s[0]) / den
    u = (qp[0] * r[1] - qp[1] * r[0]) / den
    if -tol <= t <= 1 + tol and -tol <= u <= 1 + tol:
        return p + t * r
    return None

