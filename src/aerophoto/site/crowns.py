"""Tree crowns as solids: what a photo of a stand shows when it is looked at closely (guide §9, table 10).

The forest canopy a ray meets (:meth:`aerophoto.site.objects.SiteObjects.canopy_at`) is a raster of columns; on
its own it shades every crown as a little stepped block.  :class:`Crowns` keeps the crowns the raster was stamped
from — centre, radius, top, shape, the stand they belong to and a tone of their own — so that

* the renderer shades each canopy pixel by the **normal of its crown's surface** (:meth:`Crowns.normal_at`),
  which gives the marks table 10 names: pine's convex crowns of one height lit evenly on their sunny side,
  spruce's pointed cones — bright on the side facing the sun, dark on the other, so that the stand looks mottled —
  and the grainy, lumpy surface of broadleaf crowns;
* the colour step knows which stand a canopy pixel belongs to and the crown's own tone (:meth:`Crowns.lookup`).

Shapes (height above the ground h at a distance r from the crown's axis, q = r/R, top H):

=====  ================  ==========================================================================
code   shape             h(q)
=====  ================  ==========================================================================
0      cone (spruce)     H − 0.75·H·q: a pointed top, steep sides
1      dome (pine)       H − 3·q²: a flat, convex top 3 m deep
2      round (broadleaf  H − 0.35·H·q²: a broad soft dome; its surface is lumpy (:data:`BUMP`)
       and shrub)
=====  ================  ==========================================================================

Where crowns overlap, the higher surface is the one seen (the raster takes the maximum too).  Data and geometry
only (layer 3); deterministic.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

__all__ = ["Crowns", "SHAPES", "BUMP", "SIDE_M", "DEPTH_M", "crown_height"]

#: crown shapes by code
SHAPES = ("cone", "dome", "round")
#: lumpiness of each shape's surface: (amplitude, m; scale of the lumps, m) — branch clumps on the crown
BUMP = {0: (0.10, 0.7), 1: (0.18, 1.0), 2: (0.45, 1.1)}
#: a point this far (m) below its crown's surface is on the crown's flank (:meth:`Crowns.normal_at`)
SIDE_M = 0.6
#: the depth into the canopy over which the foliage's light falls to 1/e, m (the colour step's shade of depth)
DEPTH_M = 6.0


def crown_height(shape: np.ndarray, H: np.ndarray, q: np.ndarray) -> np.ndarray:
    """Height of a crown's surface above the ground, m, at q = r/R (0 ≤ q ≤ 1; −inf outside), per shape code."""
    h = np.where(shape == 0, H - 0.75 * H * q, np.where(shape == 1, H - 3.0 * q ** 2, H - 0.35 * H * q ** 2))
    return np.where(q <= 1.0, h, -np.inf)


def _dh_dr(shape, H, R, q):
    """dh/dr of each shape, m per m (≤ 0)."""
    return np.where(shape == 0, -0.75 * H / R, np.where(shape == 1, -6.0 * q / R, -0.7 * H * q / R))


@dataclass(frozen=True, eq=False, repr=False)
class Crowns:
    """The crowns of a site's stands (see the module notes).

    Attributes (shape (N,) each)
    ----------------------------
    x_m, y_m : crown centre, ground metres
    r_m : crown radius R, m
    top_m : crown top H above the ground, m
    shape : :data:`SHAPES` code
    cls : the land-cover class code of the stand (:data:`aerophoto.site.cover.CLASS_CODES`)
    tone : the crown's own brightness factor (mean 1 over a stand)
    seed : the seed of the lumps' pattern
    index : ndarray (n, n) int32 or None — which crown is seen from above in each canopy texel (−1: none), the
        raster of :meth:`rasters`, ``texel_m`` wide
    """

    x_m: np.ndarray
    y_m: np.ndarray
    r_m: np.ndarray
    top_m: np.ndarray
    shape: np.ndarray
    cls: np.ndarray
    tone: np.ndarray
    seed: int = 0
    index: np.ndarray | None = None
    texel_m: float = 1.0

    def __repr__(self) -> str:
        return f"Crowns({len(self.x_m)} crowns)"

    def __len__(self) -> int:
        return len(self.x_m)

    def lookup(self, X, Y) -> tuple:
        """The crown seen from above at ground points (X, Y): ``(index, height_m, q)``; index −1 where none.

        The crown is the one whose surface is highest in the point's texel of :attr:`index`; ``height_m`` is its
        surface's height above the ground at the point, ``q`` = r/R (clipped to 1 at the crown's rim).  Arrays of
        X's shape.
        """
        X = np.asarray(X, float)
        Y = np.asarray(Y, float)
        if self.index is None:
            raise ValueError("lookup needs the crowns' index raster (Crowns.with_rasters)")
        n = self.index.shape[0]
        inv = 1.0 / self.texel_m
        c = np.clip((X * inv).astype(np.int64), 0, n - 1)
        r = np.clip((Y * inv).astype(np.int64), 0, n - 1)
        idx = self.index[r, c].astype(np.int64)
        on = idx >= 0
        i = np.where(on, idx, 0)
        q = np.minimum(np.hypot(X - self.x_m[i], Y - self.y_m[i]) / self.r_m[i], 1.0) if len(self) else np.ones(X.shape)
        h = np.where(on, crown_height(self.shape[i], self.top_m[i], q), -np.inf) if len(self) else np.full(X.shape,
                                                                                                          -np.inf)
        return idx, h, q

    def normal_at(self, X, Y, h_m=None) -> np.ndarray:
        """Unit normal (…, 3) of the crown surface seen at ground points (X, Y); straight up where no crown.

        The crown's own slope (its shape) plus its lumps: the gradient of a seeded smooth noise of the shape's
        :data:`BUMP` amplitude and scale.  With ``h_m`` (the point's height above the ground, m), a point more
        than :data:`SIDE_M` below its crown's surface is on the crown's side — what a ray far from the nadir meets
        (the raster's column wall): its normal leans out from the crown's axis, the foliage's flank.
        """
        from .texture import wave_gradient

        X = np.asarray(X, float)
        Y = np.asarray(Y, float)
        idx, _, q = self.lookup(X, Y)
        out = np.zeros(X.shape + (3,))
        out[..., 2] = 1.0
        on = idx >= 0
        if not on.any():
            return out
        i = idx[on]
        x, y = X[on], Y[on]
        dx, dy = x - self.x_m[i], y - self.y_m[i]
        r = np.maximum(np.hypot(dx, dy), 1e-6)
        g = _dh_dr(self.shape[i], self.top_m[i], self.r_m[i], q[on])
        gx, gy = g * dx / r, g * dy / r
        for code, (amp, scale) in BUMP.items():
            m = self.shape[i] == code
            if m.any():
                bx, by = wave_gradient(x[m], y[m], scale, self.seed + 31 * code)
                gx[m] += amp * bx
                gy[m] += amp * by
        n = np.column_stack([-gx, -gy, np.ones(len(i))])
        if h_m is not None:  # on the crown's flank: the normal leans out, 70° from the vertical
            depth = self.surface_depth(X, Y, h_m)[on]
            side = depth > SIDE_M
            if side.any():
                ux, uy = dx[side] / r[side], dy[side] / r[side]
                n[side] = np.column_stack([2.75 * ux - gx[side] * 0.2, 2.75 * uy - gy[side] * 0.2, np.ones(int(side.sum()))])
        out[on] = n / np.linalg.norm(n, axis=1, keepdims=True)
        return out

    def surface_depth(self, X, Y, h_m) -> np.ndarray:
        """How far below its crown's surface a point at height ``h_m`` above the ground lies, m (0 on it or above;
        0 where no crown): the depth into the canopy, where the foliage is in its neighbours' shade."""
        idx, h, _ = self.lookup(X, Y)
        d = np.where(idx >= 0, h - np.asarray(h_m, float), 0.0)
        return np.clip(np.nan_to_num(d, nan=0.0, neginf=0.0, posinf=0.0), 0.0, None)

    def with_rasters(self, n: int, texel_m: float) -> tuple:
        """``(crowns, canopy_dm)``: the canopy raster the ray-caster marches — the crowns' surfaces as columns
        ``texel_m`` wide, decimetres (uint8, shape (n, n), row 0 at the south edge; 0 where no crown) — and these
        crowns with their :attr:`index` raster of the same grid."""
        from dataclasses import replace

        canopy = np.zeros((n, n), np.float32)
        index = np.full((n, n), -1, np.int32)
        for k in range(len(self)):
            _stamp(canopy, index, k, self.x_m[k] / texel_m, self.y_m[k] / texel_m, self.r_m[k] / texel_m,
                   float(self.top_m[k]), int(self.shape[k]))
        index.flags.writeable = False
        return replace(self, index=index, texel_m=float(texel_m)), np.clip(np.round(canopy * 10.0), 0,
                                                                           255).astype(np.uint8)


def _stamp(canopy, index, k, cx, cy, R, top, shape):
    """Raise ``canopy`` (m) to crown ``k`` (centre and radius in texels) where it is lower; mark it in ``index``."""
    n = canopy.shape[0]
    r0, r1 = max(int(cy - R), 0), min(int(cy + R) + 2, n)
    c0, c1 = max(int(cx - R), 0), min(int(cx + R) + 2, n)
    if r0 >= r1 or c0 >= c1:
        return
    yy = (np.arange(r0, r1) + 0.5)[:, None] - cy
    xx = (np.arange(c0, c1) + 0.5)[None, :] - cx
    q = np.sqrt(xx * xx + yy * yy) / R
    h = crown_height(np.int64(shape), np.float32(top), q)
    h = np.where(np.isfinite(h), h, 0.0)
    win = canopy[r0:r1, c0:c1]
    higher = h > win
    win[higher] = h[higher]
    index[r0:r1, c0:c1][higher] = k
