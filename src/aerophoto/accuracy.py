"""Accuracy of phototriangulation: how errors accumulate along a strip, and control spacing (article 001; chapter 14).

Romanovsky's accumulation law (article 001, formulas 10.20–10.21)
------------------------------------------------------------------
A strip built by the method of continuation (метод продолжений: each model
oriented to the previous one and brought to its scale) carries every link's
error on into all later links: an error d_j made when link j is built changes
the scale (and azimuth, and longitudinal tilt) of every later base.  The
position of a point of link n is the sum of the bases, so its error is

    Δ_n = n·d₁ + (n − 1)·d₂ + … + 1·d_n,

and for equal independent errors (RMS d)

    m_n = d · √(1² + 2² + … + n²) = d · √(n(n + 1)(2n + 1)/6) ≈ d · √(n³/3)     (10.20)

— the "n³ law" (:func:`free_strip_factor`).  The scan lost the formula; the
sum follows from the accumulation scheme the article describes (its figure
10.7 is the curve of Δ_n).

For a strip held by control at both ends the article fits the strip to the
end points (its ends m, m′ coincide), which moves the middle by half the end
error, and estimates the middle's error by "replacing n by n/2 in (10.20) and
halving the result" (:func:`middle_factor_article`).  That recipe ignores that
the middle's error and the end's are correlated: the exact variance of
Δ_{n/2} − Δ_n/2 is (n³ + 2n)/48 · d² (:func:`middle_factor_exact`; the same sum
as :func:`aerophoto.triangulation.bridge_variance_factor`), √2 times the
recipe's RMS for large n.  The simulation (:func:`strip_monte_carlo`) decides
between them.

Formula (10.21) as reconstructed
--------------------------------
The article then replaces d by the errors of a single model (its formula
8.40, not reproduced) and prints, for n = 10, m_q = 0.01 mm, f = b = 70 mm:
m_X = m_Z = 0.08 mm, m_D = 0.11 mm, m_Y = 0.05 mm in the photo scale.  The
coefficients that reproduce m_X, m_Y, m_Z with the n³/3 form of (10.20) are

    m_X = 0.25·m·m_q·√n³,  m_Y = 0.16·m·m_q·√n³,  m_Z = 0.25·m·m_q·(f/b)·√n³,
    m_D = √(0.25² + 0.16²)·m·m_q·√n³ = 0.297·m·m_q·√n³                (10.21)

(0.25 = √6/√96: a single model's X error of √6·m_q, halved over n/2 links).
m_D is read as the article's legend names it, the plan error √(m_X² + m_Y²):
then the design examples follow as printed — n = 8.6 → 8 bases between plan
control, 2–3 between height control (:func:`plan_bases`, :func:`height_bases`)
— and only the example's printed m_D = 0.11 mm (= √2·m_X, 0.094 mm by the
legend) is a slip.  The other reading, m_D = √2·m_X = 0.35·m·m_q·√n³
(:data:`COEFF_D_SQRT2`), keeps the 0.11 but then gives 7.7 → 7 bases, not the
printed 8 — two numbers at odds instead of one; see :mod:`aerophoto.guide.ch14`.

Monte Carlo and covariance
--------------------------
:func:`strip_monte_carlo` builds strips by dependent relative orientations and
scale transfer (the method of continuation, batched over runs) from measured
photo coordinates with random errors, and reports the errors along the strip
for a strip held at its start (free) and one fitted to both ends.
:func:`block_precision` propagates the covariance of a bundle-adjusted block
(:mod:`aerophoto.bundle`) for a control layout — no random numbers, exact to
first order, and linear in the image error σ.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from . import _validate as V
from . import geometry as g
from ._validate import check_int_range, check_positive, check_range
from .bundle import collinearity as _col
from .bundle import design as _design
from .bundle import solve as _solve
from .bundle.block import simulate_measurements

__all__ = [
    "COEFF_10_21", "COEFF_D_SQRT2", "squares_sum", "free_strip_factor", "middle_factor_article", "middle_factor_exact",
    "strip_errors_mm", "allowed_height_error_m", "plan_bases", "height_bases", "whole_bases",
    "StripMonteCarlo", "strip_monte_carlo", "fit_accumulation", "control_rows", "BlockPrecision",
    "block_precision", "block_vs_strip", "block_monte_carlo",
]

#: the coefficients of the reconstructed formula (10.21), photo-scale errors per m_q·√n³ (Z also × f/b);
#: m_D is the plan error √(m_X² + m_Y²) (the article's legend): 0.297
COEFF_10_21 = {"X": 0.25, "Y": 0.16, "Z": 0.25, "D": math.hypot(0.25, 0.16)}
#: the other reading of m_D: √2·m_X (the article's printed 0.11 mm in its example), coefficient 0.35
COEFF_D_SQRT2 = 0.35

MAX_N = 1000


# =========================================================================== the laws
def squares_sum(n):
    """1² + 2² + … + n² = n(n + 1)(2n + 1)/6 (any real n ≥ 0, elementwise)."""
    n = np.asarray(n, dtype=float)
    if np.any(n < 0) or not np.all(np.isfinite(n)):
        raise ValueError(f"n = {n!r} must be finite with n ≥ 0")
    out = n * (n + 1.0) * (2.0 * n + 1.0) / 6.0
    return float(out) if out.ndim == 0 else out


def free_strip_factor(n, *, approx: bool = False):
    """(10.20): m_n / d = √(Σk²) for a free strip of n links (``approx``: √(n³/3))."""
    n = np.asarray(n, dtype=float)
    out = np.sqrt(n**3 / 3.0) if approx else np.sqrt(squares_sum(n))
    return float(out) if np.ndim(out) == 0 else out


def middle_factor_article(n, *, approx: bool = False):
    """The article's recipe for the middle of a strip fitted to both ends: (10.20) with n/2, halved.

    ½·√((n/2)(n/2 + 1)(n + 1)/6), or with ``approx`` ½·√((n/2)³/3) = √(n³/96).
    """
    return 0.5 * free_strip_factor(np.asarray(n, dtype=float) / 2.0, approx=approx)


def middle_factor_exact(n, k=None) -> float:
    """RMS/d at link k (default the middle, n/2) of a strip of n links fitted to both ends (exact).

    The error of link k is Δ_k = Σ_{j≤k} (k − j + 1)·d_j; fitting the strip to its two ends removes
    (k/n)·Δ_n.  Returns √(Σ_j (c_kj − (k/n)·c_nj)²); for even n and k = n/2 this is √((n³ + 2n)/48).
    """
    n = check_int_range("n", n, 1, MAX_N)
    k = n / 2.0 if k is None else check_range("k", k, 0.0, n)
    j = np.arange(1, n + 1)
    c_end = n - j + 1.0
    if float(k).is_integer():
        c_k = np.maximum(0.0, k - j + 1.0)
    else:  # between two links: the mean of their coefficients
        lo, hi = math.floor(k), math.ceil(k)
        c_k = 0.5 * (np.maximum(0.0, lo - j + 1.0) + np.maximum(0.0, hi - j + 1.0))
    return float(np.sqrt(np.sum((c_k - k / n * c_end) ** 2)))


def strip_errors_mm(n, mq_mm: float, *, f_mm: float = 70.0, b_mm: float = 70.0) -> dict:
    """The reconstructed (10.21): RMS errors in the middle of a strip held at both ends, photo-scale mm.

    Parameters
    ----------
    n : number of bases (photo bases, базисы фотографирования) between the control points (> 0)
    mq_mm : RMS error m_q of a measured transverse parallax, mm (0 < m_q ≤ 1)
    f_mm, b_mm : focal length and photo base, mm (only m_Z depends on f/b)

    Returns
    -------
    dict with ``"X"``, ``"Y"``, ``"Z"``, ``"D"`` (plan, m_D): errors in mm at the photo scale; multiply by
    the scale denominator m (and /1000) for metres on the ground, by m/M for mm on the map.
    """
    nn = np.asarray(n, dtype=float)
    if np.any(nn <= 0) or np.any(nn > MAX_N) or not np.all(np.isfinite(nn)):
        raise ValueError(f"n = {n!r} is outside the valid range 0 < n ≤ {MAX_N} (bases)")
    mq = check_positive("mq_mm", mq_mm, unit="mm", hi=1.0)
    f = check_positive("f_mm", f_mm, unit="mm", hi=2000.0)
    b = check_positive("b_mm", b_mm, unit="mm", hi=500.0)
    r = mq * np.sqrt(nn**3)
    out = {"X": COEFF_10_21["X"] * r, "Y": COEFF_10_21["Y"] * r, "Z": COEFF_10_21["Z"] * r * f / b,
           "D": COEFF_10_21["D"] * r}
    return {k: (float(v) if np.ndim(v) == 0 else v) for k, v in out.items()}


def allowed_height_error_m(contour_interval_m: float) -> float:
    """RMS height error allowed for densification: half the map's RMS height error, m (article 001).

    The map's mean height error is a third of the contour interval (сечение рельефа); an RMS error is
    1.25 × a mean error; densification gets half of it:  m_Z = 0.5 × (h/3) × 1.25 (0.52 m for h = 2.5 m).
    """
    h = check_positive("contour_interval_m", contour_interval_m, unit="m", hi=1000.0)
    return 0.5 * h / 3.0 * 1.25


def plan_bases(m: float, M: float, mq_mm: float, *, mD_map_mm: float = 0.3) -> float:
    """Real n at which the plan error m_D of (10.21) reaches ``mD_map_mm`` on the map of scale 1:M.

    m_D(photo) = 0.297·m_q·√n³ and m_D(map) = m_D(photo)·m/M  →  n = (mD_map·M/(m·0.297·m_q))^(2/3).
    Article 001: m = 20 000, M = 10 000, m_q = 0.02 mm, m_D ≤ 0.3 mm → n ≈ 8.6 (printed: 8; with the other
    reading m_D = √2·m_X, coefficient :data:`COEFF_D_SQRT2` = 0.35, n ≈ 7.7).
    """
    m = check_positive("m", m, hi=1e7)
    M = check_positive("M", M, hi=1e7)
    mq = check_positive("mq_mm", mq_mm, unit="mm", hi=1.0)
    mD = check_positive("mD_map_mm", mD_map_mm, unit="mm", hi=100.0)
    return (mD * M / m / (COEFF_10_21["D"] * mq)) ** (2.0 / 3.0)


def height_bases(m: float, mq_mm: float, *, contour_interval_m: float = 2.5, f_mm: float = 100.0,
                 b_mm: float = 100.0) -> float:
    """Real n at which m_Z of (10.21) reaches :func:`allowed_height_error_m` on the ground.

    m_Z(ground, m) = 0.25·m_q·(f/b)·√n³ · m/1000.  Article 001: h = 2.5 m, m = 20 000, f = b = 100 mm,
    m_q = 0.02 mm → n ≈ 3.0 ("every 2–3 bases").
    """
    m = check_positive("m", m, hi=1e7)
    mq = check_positive("mq_mm", mq_mm, unit="mm", hi=1.0)
    f = check_positive("f_mm", f_mm, unit="mm", hi=2000.0)
    b = check_positive("b_mm", b_mm, unit="mm", hi=500.0)
    mz_photo_mm = allowed_height_error_m(contour_interval_m) / m * 1000.0
    return (mz_photo_mm / (COEFF_10_21["Z"] * mq * f / b)) ** (2.0 / 3.0)


def whole_bases(n_real: float) -> int:
    """The largest whole number of bases not above ``n_real`` (control every n bases keeps the error within)."""
    return int(math.floor(check_range("n_real", n_real, 0.0, 1e9) + 1e-9))


# =========================================================================== Monte Carlo of strips
def _rot_b(opk):  # (R, 3) → (R, 3, 3)
    return _col._rotation_opk(opk[:, 0], opk[:, 1], opk[:, 2])


def _rays_b(R, xy, f):
    v = np.concatenate([xy, np.full(xy.shape[:-1] + (1,), -f)], axis=-1)
    return np.einsum("rij,rkj->rki", R, v)


def _base_frame_b(u):
    x = u / np.linalg.norm(u, axis=-1, keepdims=True)
    z0 = np.zeros_like(x)
    z0[:, 2] = 1.0
    y = np.cross(z0, x)
    y /= np.linalg.norm(y, axis=-1, keepdims=True)
    z = np.cross(x, y)
    return np.stack([x, y, z], axis=-1)


def _parallax_b(p, Rl, xl, xr, f):
    u = np.einsum("rij,rj->ri", Rl, np.column_stack([np.ones(len(p)), p[:, 0], p[:, 1]]))
    Rr = Rl @ _rot_b(p[:, 2:])
    Rb = _base_frame_b(u)
    vl = _rays_b(np.swapaxes(Rb, 1, 2) @ Rl, xl, f)
    vr = _rays_b(np.swapaxes(Rb, 1, 2) @ Rr, xr, f)
    return f * (vl[..., 1] / vl[..., 2] - vr[..., 1] / vr[..., 2]), u, Rr


def _relative_orientation_b(Rl, xl, xr, f, iters=8):
    """Batched dependent relative orientation (as :func:`aerophoto.bundle.relative_orientation`, no screening)."""
    R = len(Rl)
    p = np.zeros((R, 5))
    for _ in range(iters):
        q, _, _ = _parallax_b(p, Rl, xl, xr, f)
        J = np.empty(q.shape + (5,))
        for j in range(5):
            h = np.zeros(5)
            h[j] = 1e-7
            J[..., j] = (_parallax_b(p + h, Rl, xl, xr, f)[0] - q) / 1e-7
        N = np.einsum("rki,rkj->rij", J, J)
        rhs = -np.einsum("rki,rk->ri", J, q)
        dp = np.linalg.solve(N, rhs[..., None])[..., 0]
        p += dp
        if np.max(np.abs(dp)) < 1e-13:
            break
    q, u, Rr = _parallax_b(p, Rl, xl, xr, f)
    return Rr, u / np.linalg.norm(u, axis=-1, keepdims=True), q


def _intersect_b(S1, r1, S2, r2):
    d = S2[:, None, :] - S1[:, None, :]
    a = np.sum(r1 * r1, -1)
    b = np.sum(r1 * r2, -1)
    c = np.sum(r2 * r2, -1)
    e = np.sum(r1 * d, -1)
    gg = np.sum(r2 * d, -1)
    den = a * c - b * b
    t = (e * c - b * gg) / den
    u = (e * b - a * gg) / den
    return 0.5 * ((S1[:, None, :] + t[..., None] * r1) + (S2[:, None, :] + u[..., None] * r2))


def _similarity_b(A, B):
    """Batched Umeyama fit of A (R, k, 3) onto B (k, 3); returns a function applying it to (R, m, 3)."""
    ca = A.mean(axis=1)
    cb = B.mean(axis=0)
    a = A - ca[:, None, :]
    b = B - cb
    C = np.einsum("kj,rki->rji", b, a) / len(B)
    U, sv, Vt = np.linalg.svd(C)
    det = np.sign(np.linalg.det(U @ Vt))
    D = np.ones((len(A), 3))
    D[:, 2] = det
    Rm = U @ (D[:, :, None] * Vt)
    s = np.sum(sv * D, axis=1) / np.mean(np.sum(a * a, axis=2), axis=1)
    t = cb - s[:, None] * np.einsum("rij,rj->ri", Rm, ca)
    return lambda X: s[:, None, None] * np.einsum("rij,rkj->rki", Rm, X) + t[:, None, :]


@dataclass(frozen=True, eq=False)
class StripMonteCarlo:
    """Errors of strips built by the method of continuation, over many runs (:func:`strip_monte_carlo`).

    Attributes
    ----------
    n_bases : int
        Bases of the longest strip (photos 0 … n).
    sigma_mm : float
        RMS error of a measured photo coordinate, mm (m_q = σ·√2 for the transverse parallax).
    scale_m : float
        Metres on the ground per mm on the photo (m/1000): divide ground errors by it for photo mm.
    free_m : ndarray (runs, n, 3)
        Errors along (X′), across (Y′) and in height (Z), m, of the point at the principal point of
        photo k = 1 … n, in a strip held by errorless control on its first model (its model k value):
        that point has come through k − 1 scale transfers, so it is the end of a free strip of
        n = k − 1 links beyond the controlled model (:meth:`free_links`).
    mid_m : ndarray (runs, len(mid_n), 3)
        The same at the middle photo of strips of ``mid_n`` bases fitted (3-D similarity) to
        errorless control on their first and last models.
    mid_n : ndarray
        The even strip lengths of ``mid_m``.
    b_mm, f_mm : float
        Photo base and focal length of the strip, mm.
    """

    n_bases: int
    sigma_mm: float
    scale_m: float
    free_m: np.ndarray
    mid_m: np.ndarray
    mid_n: np.ndarray
    b_mm: float
    f_mm: float

    @property
    def mq_mm(self) -> float:
        """RMS error of a transverse parallax, m_q = σ·√2 (two independent coordinates), mm."""
        return self.sigma_mm * math.sqrt(2.0)

    def free_links(self) -> np.ndarray:
        """(n,): the number of links beyond the controlled model of each free-strip point, k − 1."""
        return np.arange(self.n_bases)

    def rms_free_mm(self) -> np.ndarray:
        """(n, 3): RMS over the runs of the free strip's errors at photo k = 1 … n, photo-scale mm."""
        return np.sqrt(np.mean(self.free_m**2, axis=0)) / self.scale_m

    def rms_mid_mm(self) -> np.ndarray:
        """(len(mid_n), 3): RMS of the middle errors of strips held at both ends, photo-scale mm."""
        return np.sqrt(np.mean(self.mid_m**2, axis=0)) / self.scale_m

    def table(self) -> pd.DataFrame:
        """One row per k: the free strip's errors at the point of photo k (n = k − 1 links beyond the controlled
        first model) and the middle errors of a strip of k bases held at both ends (where simulated), mm at the
        photo scale.  The index is labelled with both meanings: it is a photo number for the free-strip columns
        and a strip length for the middle ones."""
        f = self.rms_free_mm()
        rows = []
        mid = dict(zip(self.mid_n.tolist(), self.rms_mid_mm()))
        for k in range(1, self.n_bases + 1):
            mm = mid.get(k, [np.nan] * 3)
            rows.append((k, *f[k - 1], *mm))
        cols = ["k: photo (free) / bases (both ends)", "free, at photo k: X, mm", "free, at photo k: Y, mm",
                "free, at photo k: Z, mm", "both ends, k bases, middle: X, mm", "both ends, k bases, middle: Y, mm",
                "both ends, k bases, middle: Z, mm"]
        return pd.DataFrame(rows, columns=cols).set_index(cols[0])


@V.checked(camera=g.Camera, poses=V.sequence(V.of_type(g.Pose), min_len=2), terrain=V.terrain(none=True))
def strip_monte_carlo(camera: g.Camera, poses, terrain, *, sigma_mm: float = 0.01 / math.sqrt(2.0),
                      n_runs: int = 100, seed: int = 0, d_mm: float | None = None, halfway: bool = False,
                      margin_mm: float = 3.0) -> StripMonteCarlo:
    """Monte Carlo of strips built by the method of continuation (semi-dependent models).

    Parameters
    ----------
    camera : the camera (f, frame)
    poses : the strip's true photo orientations (:class:`aerophoto.geometry.Pose`), in the order of
        flight, at least 3 (2 bases); the strip direction is taken from the first to the last centre
    terrain : a :class:`aerophoto.geometry.Terrain` (e.g. the virtual site)
    sigma_mm : RMS error of each measured photo coordinate, mm (0 < σ ≤ 0.5)
    n_runs : number of runs (1 ≤ runs ≤ 5000)
    seed : the random stream
    d_mm : offset of the upper and lower tie points from the photo's x axis (default 0.4·frame)
    halfway : also measure three points halfway between the principal points (9 points per model
        instead of von Gruber's 6)

    Each run measures every tie point (three at each photo's principal point, see
    :func:`aerophoto.bundle.standard_points`: von Gruber's six points per model) on every photo with
    Gaussian errors,
    orients each photo to the previous one (dependent relative orientation, five elements from the
    transverse parallaxes) and carries the scale through the triple overlap.
    """
    if len(poses) < 3:
        raise ValueError(f"poses has {len(poses)} photo(s); the valid range is at least 3 (2 bases)")
    n = check_int_range("n_bases", len(poses) - 1, 2, 200)
    sig = check_range("sigma_mm", sigma_mm, 0.0, 0.5, lo_open=True, unit="mm")
    runs = check_int_range("n_runs", n_runs, 1, 5000)
    seed = check_int_range("seed", seed, 0, 2**63 - 1)
    margin_mm = check_range("margin_mm", margin_mm, 0.0, camera.half_mm, hi_open=True, unit="mm")
    f = camera.f_mm
    c0, c1 = poses[0].centre, poses[-1].centre
    Bm = float(np.linalg.norm(c1[:2] - c0[:2])) / n
    H = float(np.mean([p.Z_m for p in poses])) - float(np.mean(g.as_terrain(terrain).height(c0[0], c0[1])))
    b_mm = Bm * f / H
    pts = _design.standard_points(camera, poses, terrain, d_mm=d_mm, halfway_mm=b_mm / 2.0 if halfway else None)
    per = 6 if halfway else 3
    centre_pt = np.arange(len(poses)) * per + 1  # the principal point of each photo
    eo = _col.eo_from_poses(poses)
    half = camera.half_mm - margin_mm
    obs = {}
    for j in range(len(poses)):
        xy = _col._project(np.repeat(eo[j:j + 1], len(pts), axis=0), pts, f)
        inside = np.flatnonzero(np.all(np.abs(xy) <= half, axis=1))
        obs[j] = (inside, xy[inside])
    rng = np.random.default_rng(seed)
    noisy = {j: xy[None] + sig * rng.standard_normal((runs,) + xy.shape) for j, (k, xy) in obs.items()}
    # the strip's own frame: photo 0 fixed as in truth (a similarity to the control fixes the datum anyway)
    R0 = np.repeat(_col._rotation_opk(*eo[0, 3:])[None], runs, axis=0)
    S0 = np.repeat(eo[0:1, :3], runs, axis=0)
    Rs, Ss = [R0], [S0]
    models = []  # per model j = 1 … n: (point indices, coordinates (runs, k, 3))
    Bscale = Bm
    prev = None
    for a in range(n):
        ka, xa = obs[a][0], noisy[a]
        kb, xb = obs[a + 1][0], noisy[a + 1]
        common, ia, ib = np.intersect1d(ka, kb, return_indices=True)
        if len(common) < 6:
            raise ValueError(f"photos {a} and {a + 1} share {len(common)} tie point(s); at least 6 are needed "
                             "(use a larger forward overlap)")
        Rr, u, _ = _relative_orientation_b(Rs[-1], xa[:, ia], xb[:, ib], f)
        Sa = Ss[-1]
        Q = _intersect_b(Sa, _rays_b(Rs[-1], xa[:, ia], f), Sa + Bscale * u, _rays_b(Rr, xb[:, ib], f))
        if prev is not None:
            pk, pc = prev
            shared, i_new, i_old = np.intersect1d(common, pk, return_indices=True)
            if len(shared) < 1:
                raise ValueError(f"models {a} and {a + 1} share no point of the triple overlap")
            ratio = (np.linalg.norm(pc[:, i_old] - Sa[:, None], axis=2)
                     / np.linalg.norm(Q[:, i_new] - Sa[:, None], axis=2))
            s = ratio.mean(axis=1)
        else:
            s = np.ones(runs)
        Q = Sa[:, None] + s[:, None, None] * (Q - Sa[:, None])
        Rs.append(Rr)
        Ss.append(Sa + (s * Bscale)[:, None] * u)
        models.append((common, Q))
        prev = (common, Q)
    # the frame of along / across the strip
    az = math.atan2(c1[1] - c0[1], c1[0] - c0[0])
    rot = np.array([[math.cos(az), math.sin(az), 0.0], [-math.sin(az), math.cos(az), 0.0], [0.0, 0.0, 1.0]])

    def value(model_j, point):
        k, Q = models[model_j - 1]
        i = np.flatnonzero(k == point)
        return Q[:, i[0]] if len(i) else None

    # free strip: held by errorless control on model 1
    k1, Q1 = models[0]
    fit1 = _similarity_b(Q1, pts[k1])
    free = np.zeros((runs, n, 3))
    for k in range(1, n + 1):
        v = value(k, centre_pt[k])
        free[:, k - 1] = (fit1(v[:, None])[:, 0] - pts[centre_pt[k]]) @ rot.T
    mid_n = np.arange(2, n + 1, 2)
    mid = np.zeros((runs, len(mid_n), 3))
    for i, L in enumerate(mid_n):
        kL, QL = models[L - 1]
        fit = _similarity_b(np.concatenate([Q1, QL], axis=1), np.concatenate([pts[k1], pts[kL]]))
        c = L // 2
        vals = [v for v in (value(c, centre_pt[c]), value(c + 1, centre_pt[c])) if v is not None]
        v = np.mean(vals, axis=0)
        mid[:, i] = (fit(v[:, None])[:, 0] - pts[centre_pt[c]]) @ rot.T
    scale_m = H / f  # m on the ground per mm on the photo
    return StripMonteCarlo(n, sig, scale_m, free, mid, mid_n, b_mm, f)


@V.checked(n=V.array(ndim=1, min_len=2), rms=V.array(ndim=1, min_len=2), law=V.function('a function n → factor'))
def fit_accumulation(n, rms, law) -> tuple:
    """Least-squares coefficient d of ``rms ≈ d·law(n)`` through the origin, and the log-log slope of rms.

    Parameters
    ----------
    n : (k,) strip lengths; rms : (k,) RMS errors; law : callable n → factor (e.g. :func:`free_strip_factor`)

    Returns
    -------
    (d, slope) : the coefficient (units of ``rms``) and the exponent of the best power law rms ∝ n^slope.
    """
    n = np.asarray(n, dtype=float)
    r = np.asarray(rms, dtype=float)
    if n.shape != r.shape or len(n) < 2:
        raise ValueError("n and rms must be matching arrays of at least 2 values")
    L = np.asarray(law(n), dtype=float)
    d = float(np.sum(L * r) / np.sum(L * L))
    ok = (n > 0) & (r > 0)
    slope = float(np.polyfit(np.log(n[ok]), np.log(r[ok]), 1)[0])
    return d, slope


# =========================================================================== blocks: covariance propagation
def control_rows(n_photos: int, every: int) -> np.ndarray:
    """Photo positions 0 … n − 1 of the control rows across the block: 0, every, 2·every, …, and the last."""
    n = check_int_range("n_photos", n_photos, 2, MAX_N)
    e = check_int_range("every", every, 1, MAX_N)
    rows = list(range(0, n, e))
    if rows[-1] != n - 1:
        rows.append(n - 1)
    return np.array(rows)


@dataclass(frozen=True, eq=False)
class BlockPrecision:
    """Predicted errors of a bundle-adjusted block (covariance propagation, :func:`block_precision`).

    Attributes
    ----------
    XYZ_m : (P, 3) true ground coordinates of the block's points, m
    kind : (P,) ``"control"`` or ``"tie"``
    sigma_plan_m, sigma_Z_m : (P,) predicted RMS plan error √(σ_X² + σ_Y²) and height error, m, at
        image error ``sigma_mm``
    sigma_mm : the image error the σ refer to; both scale linearly with it (the control's σ scales too)
    centres_m : (n, 3) projection centres
    rows : photo positions of the control rows
    """

    XYZ_m: np.ndarray
    kind: np.ndarray
    sigma_plan_m: np.ndarray
    sigma_Z_m: np.ndarray
    sigma_mm: float
    centres_m: np.ndarray
    rows: np.ndarray

    def scaled(self, sigma_mm: float) -> "BlockPrecision":
        """The same block at another image error (covariances scale with σ²)."""
        k = check_positive("sigma_mm", sigma_mm, unit="mm", hi=1.0) / self.sigma_mm
        return BlockPrecision(self.XYZ_m, self.kind, self.sigma_plan_m * k, self.sigma_Z_m * k, sigma_mm,
                              self.centres_m, self.rows)

    def summary(self) -> dict:
        """RMS and largest predicted plan and height errors over the tie points, m."""
        t = self.kind != "control"
        return {"plan RMS, m": float(np.sqrt(np.mean(self.sigma_plan_m[t] ** 2))),
                "plan max, m": float(self.sigma_plan_m[t].max()),
                "height RMS, m": float(np.sqrt(np.mean(self.sigma_Z_m[t] ** 2))),
                "height max, m": float(self.sigma_Z_m[t].max())}


@V.checked(camera=g.Camera, poses=V.sequence(V.of_type(g.Pose), min_len=2), photo_strip=V.indices(),
           photo_order=V.indices(), terrain=V.terrain(none=True))
def block_precision(camera: g.Camera, poses, photo_strip, photo_order, terrain, *, every: int = 4,
                    layout: str = "rows", sigma_mm: float = 0.01, control_factor: float = 1.0,
                    d_mm: float | None = None, halfway_mm: float | None = None, points_m=None) -> BlockPrecision:
    """Predicted errors of a bundle-adjusted block with a control layout (no random numbers).

    Parameters
    ----------
    camera, poses : the block's camera and true photo orientations
    photo_strip, photo_order : (n,) strip of each photo and its position in the strip (0-based)
    terrain : a :class:`aerophoto.geometry.Terrain`
    every : control rows every ``every`` bases (photo positions, :func:`control_rows`), ≥ 1
    layout : ``"rows"`` — a pair of control points (upper and lower tie position) on every strip at
        each row (the classical layout of article 001, figure 10.8); ``"perimeter"`` — the same
        rows on the outer strips only, plus full rows at the two ends (interior strips tied by the
        block alone)
    sigma_mm : RMS error of a measured photo coordinate, mm
    control_factor : the control's RMS error in units of σ·m (its identification on the photo)
    points_m : the block's standard points if already computed (:func:`aerophoto.bundle.standard_points`
        with the same ``d_mm`` and ``halfway_mm``), to save the ray–terrain intersections
    """
    if layout not in ("rows", "perimeter"):
        raise ValueError(f"layout = {layout!r} is not valid; expected 'rows' or 'perimeter'")
    sig = check_positive("sigma_mm", sigma_mm, unit="mm", hi=1.0)
    cf = check_positive("control_factor", control_factor, hi=1e4)
    strip = np.asarray(photo_strip, dtype=int)
    order = np.asarray(photo_order, dtype=int)
    n_per = int(order.max()) + 1
    rows = control_rows(n_per, every)
    pts = (_design.standard_points(camera, poses, terrain, d_mm=d_mm, halfway_mm=halfway_mm) if points_m is None
           else np.asarray(points_m, dtype=float))
    per = 3 if halfway_mm is None else 6
    if pts.shape != (per * len(poses), 3):
        raise ValueError(f"points_m has shape {pts.shape}; expected ({per * len(poses)}, 3), {per} per photo")
    kind = np.array(["tie"] * len(pts), dtype=object)
    K = int(strip.max()) + 1
    for j in range(len(poses)):
        if order[j] not in rows:
            continue
        outer = strip[j] in (0, K - 1)
        end = order[j] in (rows[0], rows[-1])
        if layout == "rows" or end or outer:
            kind[j * per + 0] = "control"
            kind[j * per + 2] = "control"
    eo = _col.eo_from_poses(poses)
    m_scale = float(np.mean([p.Z_m for p in poses]) - np.mean(pts[:, 2])) / camera.f_mm  # m per mm
    csig = cf * sig * m_scale
    meas = simulate_measurements(camera.f_mm, camera.frame_mm, eo, np.arange(1, len(poses) + 1), strip, order,
                                 pts, np.arange(1, len(pts) + 1), kind, sigma_mm=0.0, control_sigma_m=csig,
                                 margin_mm=3.0)
    meas = meas.replace(sigma_mm=np.full(meas.n_obs, sig))
    keep = np.isin(np.arange(1, len(pts) + 1), meas.point_ids)
    prec = _solve.precision(meas, eo, pts[keep])
    c = prec.cov_points
    return BlockPrecision(pts[keep], meas.point_kind, np.sqrt(c[:, 0, 0] + c[:, 1, 1]), np.sqrt(c[:, 2, 2]), sig,
                          eo[:, :3], rows)


@V.checked(strip_precision=BlockPrecision, block_precision_=BlockPrecision)
def block_vs_strip(strip_precision: BlockPrecision, block_precision_: BlockPrecision) -> dict:
    """How much better the block is: ratios strip/block of the RMS plan and height errors of tie points."""
    a, b = strip_precision.summary(), block_precision_.summary()
    return {"plan": a["plan RMS, m"] / b["plan RMS, m"], "height": a["height RMS, m"] / b["height RMS, m"]}



@V.checked(camera=g.Camera, poses=V.sequence(V.of_type(g.Pose), min_len=2), photo_strip=V.indices(),
           photo_order=V.indices(), terrain=V.terrain(none=True), seed=V.whole(0, 2**32 - 1))
def block_monte_carlo(camera: g.Camera, poses, photo_strip, photo_order, terrain, *, every: int = 4,
                      layout: str = "rows", sigma_mm: float = 0.01, control_factor: float = 1.0, n_runs: int = 20,
                      seed: int = 0, points_m=None) -> dict:
    """Adjust the block ``n_runs`` times with random measuring and control errors; compare with the prediction.

    The same block and layout as :func:`block_precision`; each run draws new errors
    (:func:`aerophoto.bundle.simulate_measurements`), adjusts from the true values (the bundle converges
    to the same minimum from the three-stage approximations) and records the tie points' true errors.

    Returns
    -------
    dict: ``"plan RMS, m"``, ``"height RMS, m"`` (over runs and tie points), the predicted
    ``"plan RMS predicted, m"``, ``"height RMS predicted, m"`` and ``"runs"``.
    """
    runs = check_int_range("n_runs", n_runs, 1, 1000)
    pred = block_precision(camera, poses, photo_strip, photo_order, terrain, every=every, layout=layout,
                           sigma_mm=sigma_mm, control_factor=control_factor, points_m=points_m)
    strip = np.asarray(photo_strip, dtype=int)
    order = np.asarray(photo_order, dtype=int)
    eo = _col.eo_from_poses(poses)
    m_scale = float(np.mean([p.Z_m for p in poses]) - np.mean(pred.XYZ_m[:, 2])) / camera.f_mm
    ids = np.arange(1, len(pred.XYZ_m) + 1)
    e_plan, e_z = [], []
    for r in range(runs):
        meas = simulate_measurements(camera.f_mm, camera.frame_mm, eo, np.arange(1, len(poses) + 1), strip, order,
                                     pred.XYZ_m, ids, pred.kind, sigma_mm=sigma_mm,
                                     control_sigma_m=control_factor * sigma_mm * m_scale, margin_mm=3.0,
                                     seed=int(seed) * 100003 + r, drop_single=False)
        adj = _solve.adjust(meas, eo, pred.XYZ_m)
        d = adj.xyz_m - pred.XYZ_m
        tie = meas.point_kind != "control"
        e_plan.append(d[tie, 0] ** 2 + d[tie, 1] ** 2)
        e_z.append(d[tie, 2] ** 2)
    tie = pred.kind != "control"
    return {"plan RMS, m": float(np.sqrt(np.mean(e_plan))), "height RMS, m": float(np.sqrt(np.mean(e_z))),
            "plan RMS predicted, m": float(np.sqrt(np.mean(pred.sigma_plan_m[tie] ** 2))),
            "height RMS predicted, m": float(np.sqrt(np.mean(pred.sigma_Z_m[tie] ** 2))), "runs": runs}
