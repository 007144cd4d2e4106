"""Height densification by block phototriangulation: Lysenko's formula and a block simulated on a terrain.

Article 000 predicts how well a block of photos densifies the height network
(сгущение высотного обоснования) with a formula it credits to F. F. Lysenko:

.. math::

    m_z = m_p\\,\\frac{H}{b}\\,\\sqrt{\\frac{3\\,(2ns + mn - sr)}{2mns}}

with n photos in the block, m points measured on each photo, s images of each
point and r control points (опорные точки); H the flying height and b the
photo base (the article's ρ, "продольный параллакс", 70 mm).  Two parts of
the printed formula are garbled or ambiguous; this module reads them so
(and :mod:`aerophoto.guide.ch16` records why):

* **"zr" under the root is s·r.**  With s·r the root is exactly
  :math:`\\sqrt{u/N}` of a bundle block adjustment — u = 6n + 3(mn/s − r)
  unknowns (six elements of exterior orientation per photo, three
  coordinates per point, the r control points known), N = 2mn image
  coordinates measured — the identity "the adjusted observations are on
  average √(u/N) times as precise as the measured ones" (the trace of the
  hat matrix is u).  The OCR turned an italic s into z; "2r" would give no
  such count.  :func:`bundle_counts` and :func:`lysenko_ratio` hold it.
* **The leading "0,25" is the measurement-error term m_p.**  The root and
  H/b are pure numbers, so the factor in front carries the unit of m_z: it is
  a length on the photo.  Read as printed (0.25 mm) the formula gives 1.3 m —
  fifty times the stereocomparator's 0.005 mm and ten times the article's own
  result; read as 0.025 mm (a zero lost in the scan) it gives 12.8 cm beside
  the printed 14 cm and the measured 12 cm.  The simulation below says which
  error it is: with the image coordinates measured with σ each, the block's
  height errors follow the formula when m_p = √2·σ — the error of a
  *parallax*, a difference of two coordinates (:data:`PARALLAX_READING`).

:func:`block_precision` is the simulation: a block of vertical photos flown
over a terrain (the virtual site), the tie points on the ground at their true
heights, every image coordinate measured with error σ, the bundle
adjustment linearised at the truth (:func:`aerophoto.geometry.ground_to_photo`
differentiated numerically — the one camera model), and the height errors of
the densified points from the exact covariance and from a seeded Monte Carlo.

Units are in the names: mm on the photo, m on the ground.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import _validate as V
from .. import geometry as g
from .._validate import check_int_range, check_positive, check_range

__all__ = ["PARALLAX_READING", "ARTICLE_BLOCK", "bundle_counts", "lysenko_ratio", "lysenko_mz_m",
           "BlockLayout", "block_layout", "BlockPrecision", "block_precision", "STUDY_CASES", "lysenko_study"]

#: The reading of the measurement-error term: m_p is the RMS error of a measured x-parallax (mm),
#: √2 times the error σ of one image coordinate.
PARALLAX_READING = math.sqrt(2.0)

#: The block of article 000 (its "actual data"): H, n, m, r, s, the base ρ = b, and the printed result.
ARTICLE_BLOCK = dict(H_m=450.0, n=70, m=16, r=38, s=3, b_mm=70.0, f_mm=100.0, scale=4500.0, mz_printed_cm=14.0,
                     mz_measured_cm=12.0, mp_mm=0.025, stereocomparator_mm=0.005)

MAX_PHOTOS = 150


def bundle_counts(n: int, m: float, s: float, r: int) -> tuple[float, float]:
    """(u, N): unknowns and observations of a bundle block adjustment, Lysenko's counts.

    u = 6·n + 3·(m·n/s − r) — six elements of exterior orientation per photo and
    three coordinates of each of the m·n/s points, less the r control points;
    N = 2·m·n image coordinates.

    Parameters
    ----------
    n : int — photos in the block (n ≥ 1)
    m : float — points measured on each photo, on average (m ≥ 1)
    s : float — images of each point, on average (2 ≤ s ≤ n)
    r : int — control points (0 ≤ r; r < m·n/s)
    """
    n = check_int_range("n", n, 1, 100_000)
    m = check_range("m", m, 1.0, 10_000.0)
    s = check_range("s", s, 2.0, float(max(n, 2)))
    points = m * n / s
    r = check_int_range("r", r, 0, max(0, math.ceil(points) - 1))
    if r >= points:
        raise ValueError(f"r = {r} is outside the valid range 0 ≤ r < m·n/s = {points:g} (points in the block)")
    return 6.0 * n + 3.0 * (points - r), 2.0 * m * n


def lysenko_ratio(n: int, m: float, s: float, r: int) -> float:
    """The root of Lysenko's formula, √(3(2ns + mn − sr)/(2mns)) = √(u/N) (article 000).

    A pure number below 1: how much more precise the adjusted image coordinates are than the
    measured ones, on average.  Arguments as in :func:`bundle_counts`.
    """
    u, N = bundle_counts(n, m, s, r)
    return math.sqrt(u / N)


def lysenko_mz_m(H_m: float, b_mm: float, mp_mm: float, n: int, m: float, s: float, r: int) -> float:
    """Lysenko's predicted RMS error of densified heights m_z, metres (article 000).

    m_z = m_p · (H/b) · √(3(2ns + mn − sr)/(2mns)).

    Parameters
    ----------
    H_m : flying height H, m (> 0)
    b_mm : photo base b (the article's ρ), mm (> 0)
    mp_mm : the measurement-error term m_p: RMS error of a measured parallax, mm (> 0; the article's
        "0,25" read as 0.025 mm, see the module notes)
    n, m, s, r : the block's counts (:func:`bundle_counts`)
    """
    H = check_positive("H_m", H_m, unit="m", hi=1e6)
    b = check_positive("b_mm", b_mm, unit="mm", hi=1000.0)
    mp = check_positive("mp_mm", mp_mm, unit="mm", hi=10.0)
    return mp * H / b * lysenko_ratio(n, m, s, r)


# --------------------------------------------------------------------------- the simulated block
@dataclass(frozen=True)
class BlockLayout:
    """A block of vertical photos and its tie points over a terrain.

    Attributes
    ----------
    camera : :class:`aerophoto.geometry.Camera`
    poses : tuple of :class:`aerophoto.geometry.Pose` — n photos, strips along X
    points_m : ndarray (k, 3) — tie points on the terrain, X, Y, Z in metres
    visible : ndarray (k, n) bool — which photo images which point
    control : ndarray (k,) bool — control points (known X, Y, Z)
    strips, per_strip : int — the block's shape
    H_m : float — flying height above the block's mean ground, m
    b_mm : float — photo base b = l·(1 − p_x), mm
    """

    camera: g.Camera
    poses: tuple
    points_m: np.ndarray
    visible: np.ndarray
    control: np.ndarray
    strips: int
    per_strip: int
    H_m: float
    b_mm: float

    @property
    def n(self) -> int:
        """Photos in the block."""
        return len(self.poses)

    @property
    def m(self) -> float:
        """Points imaged per photo, on average (Lysenko's m)."""
        return float(self.visible.sum(axis=0).mean())

    @property
    def s(self) -> float:
        """Images per point, on average (Lysenko's s)."""
        return float(self.visible.sum(axis=1).mean())

    @property
    def r(self) -> int:
        """Control points (Lysenko's r)."""
        return int(self.control.sum())

    def counts(self) -> dict:
        """n, m, s, r, u, N of the layout."""
        u, N = bundle_counts(self.n, self.m, self.s, self.r)
        return {"n": self.n, "m": self.m, "s": self.s, "r": self.r, "u": u, "N": N}


def block_layout(terrain, *, strips: int = 7, per_strip: int = 10, f_mm: float = 100.0, scale: float = 4500.0,
                 frame_mm: float = 180.0, px_percent: float = 60.0, py_percent: float = 30.0, rows: int = 4,
                 control: str = "spread", control_every: int = 3, origin_m=None) -> BlockLayout:
    """Lay out a block of vertical photos and tie points over ``terrain``.

    Parameters
    ----------
    terrain : a :class:`aerophoto.geometry.Terrain` (the virtual site) or a height, m
    strips, per_strip : strips K and photos per strip (2 ≤ each; at most 150 photos in all)
    f_mm, frame_mm : the camera (f, frame side l), mm
    scale : photo-scale denominator m_c (1:m_c); H = f·m_c above the block's mean ground
    px_percent, py_percent : forward and side overlap, % (50 ≤ p_x < 90, 0 ≤ p_y < 90)
    rows : rows of tie points across each strip (1–12); points stand under every photo centre
        (a column per base), so a point in the middle of a strip is on three photos (p_x = 60 %)
    control : ``"spread"`` — every ``control_every``-th column and row of points over the whole block;
        ``"perimeter"`` — every ``control_every``-th point along the block's edge
    control_every : 1–20
    origin_m : (X, Y) of the first photo centre, m; default: 1.5 photo sides in from the terrain's
        south-west corner when it has an ``extent_m``, else (0, 0)
    """
    terrain = g.as_terrain(terrain)
    K = check_int_range("strips", strips, 1, MAX_PHOTOS)
    Ns = check_int_range("per_strip", per_strip, 2, MAX_PHOTOS)
    if K * Ns > MAX_PHOTOS:
        raise ValueError(f"strips × per_strip = {K * Ns} photos is outside the valid range ≤ {MAX_PHOTOS}")
    cam = g.Camera(f_mm, frame_mm)
    mc = check_range("scale", scale, 100.0, 1e6)
    px = check_range("px_percent", px_percent, 50.0, 90.0, hi_open=True, unit="%")
    py = check_range("py_percent", py_percent, 0.0, 90.0, hi_open=True, unit="%")
    rows = check_int_range("rows", rows, 1, 12)
    every = check_int_range("control_every", control_every, 1, 20)
    if control not in ("spread", "perimeter"):
        raise ValueError(f"control = {control!r} is not one of the valid choices ['spread', 'perimeter']")
    L = cam.frame_mm / 1000.0 * mc  # photo side on the ground, m
    B, By = L * (1 - px / 100.0), L * (1 - py / 100.0)
    if origin_m is None:
        ext = getattr(terrain, "extent_m", None)
        origin_m = (ext[0] + 1.5 * L, ext[2] + 1.5 * L) if ext is not None else (0.0, 0.0)
    X0, Y0 = (check_range("origin_m", c, -1e7, 1e7, unit="m") for c in origin_m)
    xs = X0 + np.arange(Ns) * B
    ys = np.concatenate([Y0 + k * By - By / 2 + (np.arange(rows) + 0.5) * By / rows for k in range(K)])
    gx, gy = np.meshgrid(xs, ys, indexing="ij")
    XY = np.column_stack([gx.ravel(), gy.ravel()])
    Z = np.asarray(terrain.height(XY[:, 0], XY[:, 1]), dtype=float)
    H = g.flying_height_m(cam.f_mm, mc)
    Zs = float(Z.mean()) + H
    poses = tuple(g.Pose(float(x), float(Y0 + k * By), Zs) for k in range(K) for x in xs)
    P = np.column_stack([XY, Z])
    vis = np.column_stack([cam.inside(g.ground_to_photo(cam, pose, P)) for pose in poses])
    keep = vis.sum(axis=1) >= 2  # a point on one photo cannot be intersected
    P, vis = P[keep], vis[keep]
    ix = np.searchsorted(xs, P[:, 0] - 1e-6)
    iy = np.searchsorted(ys, P[:, 1] - 1e-6)
    if control == "spread":
        ctl = (ix % every == 0) & (iy % every == 0)
        # the block's four corners always carry control
        for cx in (ix.min(), ix.max()):
            for cy in (iy.min(), iy.max()):
                ctl |= (ix == cx) & (iy == cy)
    else:
        edge = (ix == ix.min()) | (ix == ix.max()) | (iy == iy.min()) | (iy == iy.max())
        order = np.flatnonzero(edge)
        ctl = np.zeros(len(P), dtype=bool)
        ctl[order[::every]] = True
    if ctl.sum() < 3:
        raise ValueError(f"the layout has {int(ctl.sum())} control point(s); the valid range is at least 3 "
                         "(use a smaller control_every)")
    return BlockLayout(cam, poses, P, vis, ctl, K, Ns, H, cam.frame_mm * (1 - px / 100.0))


def _image_jacobians(camera, pose, P):
    """x (k, 2) and the derivatives of the images of P (k, 3): by the point and by small turns of the camera,
    each (k, 2, 3)."""
    x0 = g.ground_to_photo(camera, pose, P)
    S = np.array([pose.X_m, pose.Y_m, pose.Z_m])
    d = P - S
    h = 0.01  # m
    dP = np.empty((len(P), 2, 3))
    for a in range(3):
        e = np.zeros(3)
        e[a] = h
        dP[:, :, a] = (g.ground_to_photo(camera, pose, P + e) - g.ground_to_photo(camera, pose, P - e)) / (2 * h)
    t = 1e-6  # rad
    dR = np.empty((len(P), 2, 3))
    for a in range(3):
        b, c = [(1, 2), (2, 0), (0, 1)][a]

        def turned(sign, _b=b, _c=c):
            q = d.copy()
            ct, st = math.cos(sign * t), math.sin(sign * t)
            q[:, _b] = ct * d[:, _b] - st * d[:, _c]
            q[:, _c] = st * d[:, _b] + ct * d[:, _c]
            return g.ground_to_photo(camera, pose, S + q)

        dR[:, :, a] = (turned(+1) - turned(-1)) / (2 * t)
    return x0, dP, dR


@dataclass(frozen=True)
class BlockPrecision:
    """The densified heights of a simulated block against the truth.

    Attributes
    ----------
    layout : :class:`BlockLayout`
    sigma_mm : float — RMS error σ of one measured image coordinate, mm
    sd_Z_m, sd_XY_m : ndarray (k_free,) — standard errors of the densified (non-control) points'
        Z and plan position √(σ_X² + σ_Y²) from the adjustment's exact covariance, m
    mc_Z_m : ndarray (trials, k_free) — the Z errors of the Monte Carlo trials, m
    """

    layout: BlockLayout
    sigma_mm: float
    sd_Z_m: np.ndarray
    sd_XY_m: np.ndarray
    mc_Z_m: np.ndarray

    @property
    def rms_Z_m(self) -> float:
        """RMS height error of the densified points (exact covariance), m."""
        return float(np.sqrt(np.mean(self.sd_Z_m**2)))

    @property
    def rms_XY_m(self) -> float:
        """RMS plan error of the densified points (exact covariance), m."""
        return float(np.sqrt(np.mean(self.sd_XY_m**2)))

    @property
    def mc_rms_Z_m(self) -> float:
        """RMS height error over the Monte Carlo trials, m."""
        return float(np.sqrt(np.mean(self.mc_Z_m**2)))

    @property
    def single_pair_m(self) -> float:
        """(H/b)·√2·σ: the height error of one point measured once in one stereo pair, m."""
        return self.layout.H_m / self.layout.b_mm * PARALLAX_READING * self.sigma_mm

    def lysenko_m(self, reading: float = PARALLAX_READING) -> float:
        """Lysenko's m_z for this block with m_p = reading·σ (√2: parallax; 1: one coordinate), m."""
        c = self.layout.counts()
        return lysenko_mz_m(self.layout.H_m, self.layout.b_mm, reading * self.sigma_mm, c["n"], c["m"], c["s"],
                            c["r"])

    def summary(self) -> dict:
        c = self.layout.counts()
        return {**c, "u/N": c["u"] / c["N"], "sqrt(u/N)": math.sqrt(c["u"] / c["N"]), "H_m": self.layout.H_m,
                "b_mm": self.layout.b_mm, "sigma_mm": self.sigma_mm, "rms_Z_m": self.rms_Z_m,
                "mc_rms_Z_m": self.mc_rms_Z_m, "rms_XY_m": self.rms_XY_m,
                "lysenko_parallax_m": self.lysenko_m(PARALLAX_READING), "lysenko_coordinate_m": self.lysenko_m(1.0)}

    def table(self) -> pd.DataFrame:
        """The block's counts, the simulated height error and Lysenko's prediction (both readings)."""
        s = self.summary()
        rows = [
            ("photos n", "", s["n"]), ("points per photo m", "", s["m"]), ("images per point s", "", s["s"]),
            ("control points r", "", s["r"]), ("unknowns u = 6n + 3(mn/s − r)", "", s["u"]),
            ("observations N = 2mn", "", s["N"]), ("√(u/N) = Lysenko's root", "", s["sqrt(u/N)"]),
            ("σ of one image coordinate", "mm", s["sigma_mm"]),
            ("simulated RMS of densified Z (covariance)", "m", s["rms_Z_m"]),
            ("… Monte Carlo", "m", s["mc_rms_Z_m"]),
            ("Lysenko, m_p = √2·σ (parallax)", "m", s["lysenko_parallax_m"]),
            ("Lysenko, m_p = σ (one coordinate)", "m", s["lysenko_coordinate_m"]),
        ]
        return pd.DataFrame(rows, columns=["quantity", "unit", "value"]).set_index("quantity")


@V.checked(layout=BlockLayout, seed=V.whole(0, 2**32 - 1))
def block_precision(layout: BlockLayout, sigma_mm: float = 0.005, *, trials: int = 20,
                    seed: int = 0) -> BlockPrecision:
    """Adjust the block's heights: exact covariance and a seeded Monte Carlo (article 000's densification).

    Every image coordinate of every tie point is measured with independent errors of RMS σ; the
    bundle adjustment (6 exterior-orientation unknowns per photo, X, Y, Z per non-control point, the
    control points held fixed) is linearised at the truth, so the errors it leaves are exactly
    N⁻¹Aᵀe — what an iterated adjustment converges to for errors this small.

    Parameters
    ----------
    layout : :func:`block_layout`
    sigma_mm : σ, mm (0 < σ ≤ 1)
    trials : Monte Carlo repetitions (1–500)
    seed : the random seed (same seed, same errors)
    """
    sigma = check_positive("sigma_mm", sigma_mm, unit="mm", hi=1.0)
    trials = check_int_range("trials", trials, 1, 500)
    lay = layout
    n = lay.n
    free = np.flatnonzero(~lay.control)
    col = np.full(len(lay.points_m), -1)
    col[free] = np.arange(len(free))
    u = 6 * n + 3 * len(free)
    # the design matrix A (2·Σk × u) is sparse: a row touches its photo's 6 unknowns and its point's 3.  Built
    # as such and multiplied by scipy.sparse, the normal matrix costs what its non-zeros cost; the dense
    # Cholesky factor and its inverse go to LAPACK (scipy.linalg).  A dense numpy ``A.T @ A`` took 90 s in the
    # browser book (Pyodide's numpy multiplies without BLAS), against 0.1 s here.
    from scipy import linalg as sla
    from scipy import sparse

    rows, cols, vals, rows_total = [], [], [], 0
    for j, pose in enumerate(lay.poses):
        idx = np.flatnonzero(lay.visible[:, j])
        if len(idx) == 0:
            continue
        _, dP, dR = _image_jacobians(lay.camera, pose, lay.points_m[idx])
        k = len(idx)
        r = rows_total + np.arange(2 * k)
        for a in range(3):  # the photo's exterior orientation: moving S is moving every point the other way
            rows += [r, r]
            cols += [np.full(2 * k, 6 * j + a), np.full(2 * k, 6 * j + 3 + a)]
            vals += [-dP.reshape(2 * k, 3)[:, a], dR.reshape(2 * k, 3)[:, a]]
        has = col[idx] >= 0
        rr = r[np.repeat(has, 2)]
        for a in range(3):  # the point's X, Y, Z where it is not a control point
            rows.append(rr)
            cols.append(6 * n + 3 * np.repeat(col[idx][has], 2) + a)
            vals.append(dP[has].reshape(-1, 3)[:, a])
        rows_total += 2 * k
    A = sparse.csr_matrix((np.concatenate(vals), (np.concatenate(rows), np.concatenate(cols))),
                          shape=(rows_total, u))
    N = (A.T @ A).toarray()
    try:
        L = sla.cholesky(N, lower=True)
    except np.linalg.LinAlgError:
        raise ValueError("the block cannot be adjusted: its normal matrix is singular (too few control points or "
                         "a photo without ties)") from None
    Linv = sla.solve_triangular(L, np.eye(u), lower=True)
    var = np.einsum("ij,ij->j", Linv, Linv) * sigma**2  # diag of N⁻¹ = Σ_i (L⁻¹)_ij²
    vp = var[6 * n:].reshape(-1, 3)
    rng = np.random.default_rng(seed)
    e = rng.normal(0.0, sigma, size=(rows_total, trials))
    x = sla.cho_solve((L, True), A.T @ e)
    mc = x[6 * n:].reshape(len(free), 3, trials)[:, 2, :].T
    return BlockPrecision(lay, sigma, np.sqrt(vp[:, 2]), np.sqrt(vp[:, 0] + vp[:, 1]), mc)


#: the blocks of :func:`lysenko_study`: (label, keyword arguments of :func:`block_layout`)
STUDY_CASES = (
    ("article-size block, control spread (every 3rd)", dict(strips=7, per_strip=10, control="spread", control_every=3)),
    ("same, sparser control (every 4th)", dict(strips=7, per_strip=10, control="spread", control_every=4)),
    ("same, control on the edge only (every 2nd)", dict(strips=7, per_strip=10, control="perimeter", control_every=2)),
    ("small block 3 × 6, control spread", dict(strips=3, per_strip=6, control="spread", control_every=3)),
)


@V.checked(cases=V.sequence(V.sequence(min_len=2, max_len=2), min_len=1))
def lysenko_study(terrain, *, mp_mm: float = ARTICLE_BLOCK["mp_mm"], f_mm: float = 100.0, scale: float = 4500.0,
                  b_mm: float = ARTICLE_BLOCK["b_mm"], cases=STUDY_CASES, trials: int = 20,
                  seed: int = 0) -> pd.DataFrame:
    """Lysenko's formula against simulated blocks (article 000's camera and base; m_p = √2·σ).

    Each case is a :func:`block_layout` over ``terrain`` with p_x chosen so that the base is ``b_mm``;
    the image coordinates are measured with σ = m_p/√2.  One row per case: the counts, the simulated
    RMS of the densified heights (exact covariance and Monte Carlo), Lysenko's m_z with m_p (parallax)
    and with m_p/√2 (one coordinate), and the ratio simulated / Lysenko (parallax).
    """
    frame = 180.0
    px = 100.0 * (1.0 - check_positive("b_mm", b_mm, unit="mm", hi=frame - 1e-6) / frame)
    sigma = check_positive("mp_mm", mp_mm, unit="mm", hi=10.0) / PARALLAX_READING
    seed = check_int_range("seed", seed, 0, 2**63 - 1)
    rows = []
    for label, kw in cases:
        bp = block_precision(block_layout(terrain, f_mm=f_mm, scale=scale, px_percent=px, **kw), sigma,
                             trials=trials, seed=seed)
        s = bp.summary()
        rows.append({"block": label, "n": s["n"], "m": s["m"], "s": s["s"], "r": s["r"], "√(u/N)": s["sqrt(u/N)"],
                     "simulated m_z, cm": 100 * s["rms_Z_m"], "Monte Carlo, cm": 100 * s["mc_rms_Z_m"],
                     "Lysenko (parallax), cm": 100 * s["lysenko_parallax_m"],
                     "Lysenko (coordinate), cm": 100 * s["lysenko_coordinate_m"],
                     "simulated / Lysenko": s["rms_Z_m"] / s["lysenko_parallax_m"]})
    return pd.DataFrame(rows).set_index("block")
