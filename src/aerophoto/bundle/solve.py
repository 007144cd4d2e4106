"""Bundle block adjustment (уравнивание по связкам): every photo's exterior orientation and every point's ground
coordinates from all image measurements and the control at once.

The unknowns are, per photo, X_S, Y_S, Z_S (m) and ω, φ, κ (rad) and, per ground
point, X, Y, Z (m): 6n + 3P in all (article 002, table 2 counts them: "the total
number of unknowns in the block").  Each measured photo coordinate gives one
equation — the collinearity equation (:mod:`.collinearity`) — weighted by its a
priori RMS error σ; each control point gives three more, its measured X, Y, Z
weighted by their σ.  With ``v`` the residuals divided by their σ the
adjustment minimises Σ v² (or a robust ρ(v), below).  Each row of the Jacobian
touches six photo columns and three point columns, so a 400-photo block's
Jacobian has a few hundred thousand non-zeros in a matrix of ~10⁸ cells.  Two
solvers reach the same minimum (``method``):

* ``"schur"`` (default) — Levenberg–Marquardt on the reduced normal equations:
  the points are eliminated point by point and only the photos' 6n × 6n system
  is factored (Cholesky).  This is what photogrammetric packages have always
  done, and it is fast and steady even on weakly controlled blocks.
* ``"scipy"`` — :func:`scipy.optimize.least_squares` (trust-region reflective)
  with the analytic Jacobian as a sparse matrix (its pattern is
  :meth:`_Problem.sparsity`, the ``jac_sparsity`` of a finite-difference run)
  and the LSMR inner solver.  It needs tight LSMR tolerances to converge and is
  3 to 100 times slower on the benchmark's blocks (benchmarks/bench_bundle.py); it is
  kept as the independent check and for the robust losses scipy offers.

No dedicated bundle-adjustment library is used: pyceres/pycolmap would add a
compiled dependency for blocks that the reduced system solves in seconds, and
the chapter needs the normal-equation blocks anyway for the covariances and
the redundancy numbers.

Precision.  At the solution the normal matrix N = JᵀJ has the block structure

    N = [[U, W], [Wᵀ, V]],   U: 6×6 per photo,  V: 3×3 per point,  W: photo–point couplings,

and the reduced (Schur-complement) system S = U − W V⁻¹ Wᵀ is only 6n × 6n.
Inverting S gives the photos' covariance; each point's 3×3 covariance is
V⁻¹ + V⁻¹Wᵀ S⁻¹ W V⁻¹ restricted to that point (:class:`Precision`) — the error
ellipses of the located field points.  The same blocks give each observation's
redundancy number r = 1 − h (h: the diagonal of the hat matrix J N⁻¹ Jᵀ) and
so Baarda's standardised residual w = v / (σ √r) for data snooping
(:func:`data_snooping`).  Covariances are a priori (unit weight σ₀ = 1, the
weights are 1/σ²); :attr:`Adjustment.sigma0` is the a posteriori σ̂₀ = √(Σv²/r).
"""

from __future__ import annotations

import math
import time
from dataclasses import dataclass, field

import numpy as np
import pandas as pd
import scipy.sparse as sp
from scipy.optimize import least_squares

from .. import _validate as V
from .._validate import check_finite_array, check_int_range, check_positive, check_range
from .block import Measurements
from .collinearity import _project as project
from .collinearity import _project_jacobian as project_jacobian

__all__ = ["LOSSES", "METHODS", "Adjustment", "Precision", "adjust", "precision", "Snooping", "data_snooping",
           "CRITICAL_W", "image_critical", "error_ellipse",
           "point_covariance", "rms_expectation"]

#: robust losses accepted by :func:`adjust` (``"soft_l1"`` and ``"cauchy"`` with ``method="scipy"`` only)
LOSSES = ("linear", "huber", "soft_l1", "cauchy")
#: solvers of :func:`adjust`
METHODS = ("schur", "scipy")
#: critical value of Baarda's |w| for data snooping: 4.0 (α₀ ≈ 0.006 % two-sided) — with the textbook
#: 3.29 (α₀ = 0.1 %) a block of a thousand observations would reject one or two good ones by chance
CRITICAL_W = 4.0


def _scatter(index, values, n: int) -> np.ndarray:
    """Σ of ``values`` (k, ...) into ``n`` bins by ``index`` (k,): ``np.add.at`` done by one bincount (much faster)."""
    values = np.asarray(values, dtype=float)
    shape = values.shape[1:]
    size = int(np.prod(shape)) if shape else 1
    flat = (np.asarray(index, dtype=np.intp)[:, None] * size + np.arange(size)).ravel()  # intp: wasm32 too
    return np.bincount(flat, weights=values.reshape(-1), minlength=n * size).reshape((n,) + shape)


class _Problem:
    """Index structure of one block's residual vector, Jacobian and normal equations (built once per block)."""

    def __init__(self, meas: Measurements):
        self.m = meas
        n, P, N = meas.n_photos, meas.n_points, meas.n_obs
        self.n, self.P, self.N = n, P, N
        self.ctrl = np.flatnonzero(meas.is_control)
        self.n_rows = 2 * N + 3 * len(self.ctrl)
        self.n_cols = 6 * n + 3 * P
        self.w_img = 1.0 / meas.sigma_mm
        self.w_ctrl = (1.0 / meas.control_sigma_m[self.ctrl]).ravel()
        self.wc2 = np.zeros((P, 3))
        self.wc2[self.ctrl] = (1.0 / meas.control_sigma_m[self.ctrl]) ** 2
        self._rows = None
        # pairs (a, b) of observations of one point (a = b included): the couplings of the reduced system
        pt = meas.obs_point
        order = np.argsort(pt, kind="stable")
        ps = pt[order]
        starts = np.flatnonzero(np.r_[True, ps[1:] != ps[:-1]]) if N else np.zeros(0, int)
        counts = np.diff(np.r_[starts, N])
        ia, ib = [np.zeros(0, int)], [np.zeros(0, int)]
        for c in np.unique(counts):
            s0 = starts[counts == c]
            grid = s0[:, None] + np.arange(c)[None, :]
            ia.append(order[np.repeat(grid, c, axis=1).ravel()])
            ib.append(order[np.tile(grid, (1, c)).ravel()])
        self.ia = np.concatenate(ia)
        self.ib = np.concatenate(ib)

    # ------------------------------------------------------------ residuals and the sparse Jacobian (scipy)
    def split(self, x):
        return x[: 6 * self.n].reshape(self.n, 6), x[6 * self.n:].reshape(self.P, 3)

    def residuals(self, x):
        """Weighted residuals (measured − computed)/σ: image x, y per observation, then control X, Y, Z."""
        eo, xyz = self.split(x)
        m = self.m
        xy = project(eo[m.obs_photo], xyz[m.obs_point], m.f_mm)
        v_img = (m.xy_mm - xy) * self.w_img[:, None]
        v_c = (m.control_XYZ_m[self.ctrl] - xyz[self.ctrl]).ravel() * self.w_ctrl
        return np.concatenate([v_img.ravel(), v_c])

    def _structure(self):
        if self._rows is None:
            m, N, n = self.m, self.N, self.n
            r = np.arange(2 * N).reshape(N, 2)
            cp = 6 * m.obs_photo[:, None] + np.arange(6)
            cq = 6 * n + 3 * m.obs_point[:, None] + np.arange(3)
            cols = np.concatenate([cp, cq], axis=1)
            rc = 2 * N + np.arange(3 * len(self.ctrl))
            cc = (6 * n + 3 * self.ctrl[:, None] + np.arange(3)).ravel()
            self._rows = np.concatenate([np.repeat(r[:, :, None], 9, axis=2).ravel(), rc])
            self._cols = np.concatenate([np.repeat(cols[:, None, :], 2, axis=1).ravel(), cc])
        return self._rows, self._cols

    def jacobian(self, x):
        """The Jacobian of :meth:`residuals` as a sparse CSR matrix (9 non-zeros per image row, 1 per control row)."""
        eo, xyz = self.split(x)
        m = self.m
        _, d_eo, d_pt = project_jacobian(eo[m.obs_photo], xyz[m.obs_point], m.f_mm)
        blocks = -np.concatenate([d_eo, d_pt], axis=2) * self.w_img[:, None, None]  # (N, 2, 9)
        data = np.concatenate([blocks.ravel(), -self.w_ctrl])
        rows, cols = self._structure()
        return sp.csr_matrix((data, (rows, cols)), shape=(self.n_rows, self.n_cols))

    def sparsity(self):
        """The Jacobian's pattern (``jac_sparsity`` of :func:`scipy.optimize.least_squares`)."""
        rows, cols = self._structure()
        return sp.csr_matrix((np.ones(len(rows)), (rows, cols)), shape=(self.n_rows, self.n_cols))

    # ------------------------------------------------------------ the normal equations in blocks
    def normal(self, eo, xyz, weights=None, weights_ctrl=None):
        """Blocks of the normal equations at (eo, xyz).

        Returns (A, B, r_img, r_ctrl, U, V, Wo, g_c, g_p): A (N, 2, 6) and B (N, 2, 3) the weighted
        derivatives of the computed photo coordinates; r the weighted residuals; U (n, 6, 6), V (P, 3, 3)
        and Wo (N, 6, 3) = AᵀB per observation; g_c (n, 6), g_p (P, 3) the right-hand sides Jᵀr.
        ``weights`` (N,) multiplies each image observation's weight, ``weights_ctrl`` (P, 3) each control
        coordinate's (robust re-weighting).
        """
        m = self.m
        ph, pt = m.obs_photo, m.obs_point
        xy, d_eo, d_pt = project_jacobian(eo[ph], xyz[pt], m.f_mm)
        w = self.w_img if weights is None else self.w_img * np.sqrt(weights)
        A = d_eo * w[:, None, None]
        B = d_pt * w[:, None, None]
        r_img = (m.xy_mm - xy) * w[:, None]
        r_ctrl = np.zeros((self.P, 3))
        r_ctrl[self.ctrl] = (m.control_XYZ_m[self.ctrl] - xyz[self.ctrl]) / m.control_sigma_m[self.ctrl]
        wc2 = self.wc2 if weights_ctrl is None else self.wc2 * weights_ctrl
        U = _scatter(ph, np.einsum("nri,nrj->nij", A, A), self.n)
        V = _scatter(pt, np.einsum("nri,nrj->nij", B, B), self.P)
        V[:, [0, 1, 2], [0, 1, 2]] += wc2
        Wo = np.einsum("nri,nrj->nij", A, B)
        g_c = _scatter(ph, np.einsum("nri,nr->ni", A, r_img), self.n)
        g_p = _scatter(pt, np.einsum("nri,nr->ni", B, r_img), self.P)
        g_p += r_ctrl * np.sqrt(self.wc2) * (1.0 if weights_ctrl is None else weights_ctrl)
        return A, B, r_img, r_ctrl, U, V, Wo, g_c, g_p

    def reduced(self, U, V, Wo, lam=0.0):
        """The reduced camera system S = U − W V⁻¹ Wᵀ (6n × 6n, dense) and V⁻¹, Y = W V⁻¹ per observation."""
        n = self.n
        m = self.m
        if lam:
            U = U + lam * np.einsum("nii->ni", U)[:, :, None] * np.eye(6)
            V = V + lam * np.einsum("pii->pi", V)[:, :, None] * np.eye(3)
        Vinv = np.linalg.inv(V)
        Y = Wo @ Vinv[m.obs_point]
        ph, ia, ib = m.obs_photo, self.ia, self.ib
        S = _scatter(ph[ia] * n + ph[ib], -np.einsum("kij,klj->kil", Y[ia], Wo[ib]), n * n).reshape(n, n, 6, 6)
        S[np.arange(n), np.arange(n)] += U
        S = S.transpose(0, 2, 1, 3).reshape(6 * n, 6 * n)
        return 0.5 * (S + S.T), Vinv, Y


@dataclass(frozen=True, eq=False)
class Precision:
    """A priori precision of an adjusted block (unit weight σ₀ = 1; multiply by σ̂₀² for a posteriori).

    Attributes
    ----------
    cov_points : ndarray (P, 3, 3)
        Covariance of each point's X, Y, Z, m².
    cov_photos : ndarray (n, 6, 6)
        Covariance of each photo's X_S, Y_S, Z_S (m) and ω, φ, κ (rad).
    redundancy_img : ndarray (N, 2)
        Redundancy numbers r = 1 − h of each measured x and y (0 ≤ r ≤ 1; Σr = the degrees of freedom).
    redundancy_ctrl : ndarray (P, 3)
        The same for the control coordinates (NaN for points that are not control).
    """

    cov_points: np.ndarray
    cov_photos: np.ndarray
    redundancy_img: np.ndarray
    redundancy_ctrl: np.ndarray

    def sigma_points_m(self) -> np.ndarray:
        """(P, 3) standard deviations of X, Y, Z, m."""
        return np.sqrt(np.maximum(np.einsum("pii->pi", self.cov_points), 0.0))

    def plan_rms_m(self) -> np.ndarray:
        """(P,) √(σ_X² + σ_Y²), m: the expected plan error (средняя квадратическая ошибка в плане)."""
        c = self.cov_points
        return np.sqrt(np.maximum(c[:, 0, 0] + c[:, 1, 1], 0.0))


@dataclass(frozen=True, eq=False)
class Adjustment:
    """The result of :func:`adjust`.

    Attributes
    ----------
    meas : Measurements
    eo : ndarray (n, 6)
        Adjusted exterior orientation (X_S, Y_S, Z_S m; ω, φ, κ rad).
    xyz_m : ndarray (P, 3)
        Adjusted ground coordinates of every point, m.
    v_img_mm : ndarray (N, 2)
        Image residuals, measured − computed, mm.
    v_ctrl_m : ndarray (P, 3)
        Control residuals, measured − adjusted, m (NaN for other points).
    sigma0 : float
        A posteriori unit-weight RMS σ̂₀ = √(Σ(v/σ)² / r) (≈ 1 when the a priori σ are right).
    dof : int
        Degrees of freedom r = equations − unknowns.
    n_iterations : int
        Function evaluations of the solver.
    time_s : float
        Wall time of the solve, s.
    loss : str
    """

    meas: Measurements
    eo: np.ndarray
    xyz_m: np.ndarray
    v_img_mm: np.ndarray
    v_ctrl_m: np.ndarray
    sigma0: float
    dof: int
    n_iterations: int
    time_s: float
    loss: str = "linear"
    _cache: dict = field(default_factory=dict, repr=False)

    def precision(self) -> Precision:
        """The a priori covariances and redundancy numbers at the solution (computed once)."""
        if "precision" not in self._cache:
            self._cache["precision"] = precision(self.meas, self.eo, self.xyz_m)
        return self._cache["precision"]

    def standardized_residuals(self) -> tuple:
        """Baarda's w = v/(σ√r): (w_img (N, 2), w_ctrl (P, 3) with NaN for non-control points)."""
        pr = self.precision()
        m = self.meas
        with np.errstate(divide="ignore", invalid="ignore"):
            w_img = self.v_img_mm / (m.sigma_mm[:, None] * np.sqrt(np.maximum(pr.redundancy_img, 1e-12)))
            w_ctrl = self.v_ctrl_m / (m.control_sigma_m * np.sqrt(np.maximum(pr.redundancy_ctrl, 1e-12)))
        return w_img, w_ctrl

    def points_table(self, truth_m=None) -> pd.DataFrame:
        """Adjusted points: id, kind, X, Y, Z (m), σ_X, σ_Y, σ_Z (m, a priori) and, with ``truth_m`` (P, 3),
        the true errors dX, dY, dZ (adjusted − true, m)."""
        s = self.precision().sigma_points_m()
        df = pd.DataFrame({"id": self.meas.point_ids, "kind": self.meas.point_kind,
                           "X, m": self.xyz_m[:, 0], "Y, m": self.xyz_m[:, 1], "Z, m": self.xyz_m[:, 2],
                           "σX, m": s[:, 0], "σY, m": s[:, 1], "σZ, m": s[:, 2]})
        if truth_m is not None:
            d = self.xyz_m - np.asarray(truth_m, dtype=float)
            df["dX, m"], df["dY, m"], df["dZ, m"] = d[:, 0], d[:, 1], d[:, 2]
        return df.set_index("id")


def _x0(meas, eo0, xyz0):
    eo = check_finite_array("eo0", eo0, ndim=2, last=6)
    xyz = check_finite_array("xyz0_m", xyz0, ndim=2, last=3)
    if eo.shape != (meas.n_photos, 6):
        raise ValueError(f"eo0 has shape {eo.shape}; expected ({meas.n_photos}, 6), one row per photo")
    if xyz.shape != (meas.n_points, 3):
        raise ValueError(f"xyz0_m has shape {xyz.shape}; expected ({meas.n_points}, 3), one row per point")
    return np.concatenate([eo.ravel(), xyz.ravel()])


@V.checked(meas=Measurements)
def adjust(meas: Measurements, eo0, xyz0_m, *, method: str = "schur", loss: str = "linear",
           f_scale: float = 3.0, max_iter: int = 50, tol: float = 1e-10) -> Adjustment:
    """Adjust the block by least squares from approximate values.

    Parameters
    ----------
    meas : Measurements
    eo0 : (n, 6) approximate exterior orientation (X, Y, Z m; ω, φ, κ rad), e.g. from
        :func:`aerophoto.bundle.stages.three_stage` (the three-stage procedure of article 002)
    xyz0_m : (P, 3) approximate ground coordinates, m
    method : ``"schur"`` — Levenberg–Marquardt on the reduced normal equations (the points eliminated,
        the 6n × 6n camera system solved by Cholesky: what photogrammetric packages have always done);
        ``"scipy"`` — :func:`scipy.optimize.least_squares` (trust-region reflective) with the analytic
        sparse Jacobian and the LSMR inner solver.  Both reach the same minimum; the reduced system is
        faster and more robust on weakly controlled blocks (benchmarks/bench_bundle.py measures both).
    loss : ``"linear"`` (least squares) or a robust loss applied to the σ-scaled residuals: ``"huber"``
        (both methods: observations beyond ``f_scale`` σ lose weight), ``"soft_l1"``, ``"cauchy"`` (scipy)
    f_scale : where the robust loss bends, in units of σ (0.5 ≤ f_scale ≤ 100)
    max_iter : most iterations (function evaluations for scipy), 1 ≤ max_iter ≤ 1000
    tol : stop when the relative decrease of Σv² and the largest step (in σ of the unknowns) fall below it

    Returns
    -------
    Adjustment
    """
    if method not in METHODS:
        raise ValueError(f"method = {method!r} is not valid; expected one of {METHODS}")
    if loss not in LOSSES:
        raise ValueError(f"loss = {loss!r} is not valid; expected one of {LOSSES}")
    if method == "schur" and loss not in ("linear", "huber"):
        raise ValueError(f"loss = {loss!r} needs method='scipy'; the reduced-system solver does 'linear' and 'huber'")
    fs = check_range("f_scale", f_scale, 0.5, 100.0)
    it = check_int_range("max_iter", max_iter, 1, 1000)
    tol = check_positive("tol", tol, hi=1e-2)
    prob = _Problem(meas)
    x0 = _x0(meas, eo0, xyz0_m)
    if prob.n_rows < prob.n_cols:
        raise ValueError(f"the block has {prob.n_rows} equations for {prob.n_cols} unknowns; the valid range is "
                         "at least as many equations as unknowns")
    t0 = time.perf_counter()
    if method == "scipy":
        res = least_squares(prob.residuals, x0, jac=prob.jacobian, method="trf", tr_solver="lsmr", x_scale="jac",
                            tr_options={"atol": 1e-12, "btol": 1e-12}, loss=loss, f_scale=fs, max_nfev=it,
                            xtol=tol, ftol=tol, gtol=1e-12)
        x, nit = res.x, int(res.nfev)
    else:
        x, nit = _schur_lm(prob, x0, loss, fs, it, tol)
    t = time.perf_counter() - t0
    return _result(meas, prob, x, nit, t, loss)


def _huber_weights(r_img, k):
    a = np.sqrt(np.sum(r_img**2, axis=1) / 2.0)  # per observation, in σ
    return np.where(a <= k, 1.0, k / np.maximum(a, 1e-300))


def _schur_lm(prob: _Problem, x0, loss, k, max_iter, tol):
    """Levenberg–Marquardt on the reduced camera system (points eliminated), with Huber re-weighting."""
    from scipy.linalg import LinAlgError, cho_factor, cho_solve

    n, P = prob.n, prob.P
    m = prob.m
    x = x0.copy()
    lam = 1e-6
    weights = None

    def cost_of(x, weights):
        r = prob.residuals(x)
        ri = r[: 2 * prob.N].reshape(-1, 2)
        rc = r[2 * prob.N:]
        if weights is not None:
            ri = ri * np.sqrt(weights[0])[:, None]
            rc = rc * np.sqrt(weights[1][prob.ctrl].ravel())
        return float(np.sum(ri**2) + np.sum(rc**2))

    eo, xyz = prob.split(x)
    it = 0
    for it in range(1, max_iter + 1):
        if loss == "huber":
            r = prob.residuals(x)
            wc = np.ones((P, 3))
            rc = np.abs(r[2 * prob.N:].reshape(-1, 3))
            wc[prob.ctrl] = np.where(rc <= k, 1.0, k / np.maximum(rc, 1e-300))
            weights = (_huber_weights(r[: 2 * prob.N].reshape(-1, 2), k), wc)
        cost = cost_of(x, weights)
        A, B, r_img, r_ctrl, U, V, Wo, g_c, g_p = prob.normal(eo, xyz, *(weights or (None, None)))
        accepted = False
        for _ in range(30):
            S, Vinv, Y = prob.reduced(U, V, Wo, lam)
            rhs = g_c.copy()
            rhs += _scatter(m.obs_photo, -np.einsum("nij,nj->ni", Y, g_p[m.obs_point]), n)
            try:
                dc = cho_solve(cho_factor(S), rhs.ravel()).reshape(n, 6)
            except (LinAlgError, ValueError):
                lam = max(lam * 10.0, 1e-6)
                continue
            t = g_p.copy()
            t += _scatter(m.obs_point, -np.einsum("nij,ni->nj", Wo, dc[m.obs_photo]), P)
            dp = np.einsum("pij,pj->pi", Vinv, t)
            xn = np.concatenate([(eo + dc).ravel(), (xyz + dp).ravel()])
            cn = cost_of(xn, weights)
            if cn <= cost * (1.0 + 1e-12) or not np.isfinite(cost):
                accepted = True
                break
            lam = max(lam * 10.0, 1e-6)
        if not accepted:
            break
        # step size in units of the unknowns' own precision (diag of the damped normal matrix)
        step = max(float(np.max(np.abs(dc) * np.sqrt(np.einsum("nii->ni", U) + 1e-30))) if n else 0.0,
                   float(np.max(np.abs(dp) * np.sqrt(np.einsum("pii->pi", V) + 1e-30))) if P else 0.0)
        x = xn
        eo, xyz = prob.split(x)
        lam = max(lam / 10.0, 1e-12)
        if step < max(tol, 1e-9) * 1e3 or (cost - cn) <= tol * max(cost, 1e-300):
            if step < 1e-4:
                break
    return x, it


def _result(meas, prob, x, nfev, t, loss):
    eo, xyz = prob.split(x)
    r = prob.residuals(x)
    N = meas.n_obs
    v_img = r[: 2 * N].reshape(N, 2) / prob.w_img[:, None]
    v_ctrl = np.full((meas.n_points, 3), np.nan)
    v_ctrl[prob.ctrl] = r[2 * N:].reshape(-1, 3) * meas.control_sigma_m[prob.ctrl]
    dof = prob.n_rows - prob.n_cols
    s0 = math.sqrt(float(r @ r) / dof) if dof > 0 else float("nan")
    return Adjustment(meas, eo.copy(), xyz.copy(), v_img, v_ctrl, s0, dof, int(nfev), t, loss)


def _shaped(name, value, shape):
    a = np.asarray(value, dtype=float)
    if a.size != shape[0] * shape[1]:
        raise ValueError(f"{name} has shape {a.shape}; expected {shape} (one row per "
                         + ("photo" if shape[1] == 6 else "point") + " of meas)")
    return a.reshape(shape)


@V.checked(meas=Measurements, eo=V.array(ndim=2, last=6), xyz_m=V.array(ndim=2, last=3))
def precision(meas: Measurements, eo, xyz_m, *, _problem=None) -> Precision:
    """Covariances (a priori, σ₀ = 1) and redundancy numbers at the given solution (see the module notes)."""
    prob = _problem or _Problem(meas)
    eo, xyz = _shaped("eo", eo, (prob.n, 6)), _shaped("xyz_m", xyz_m, (prob.P, 3))
    n, P, N = prob.n, prob.P, prob.N
    A, B, _, _, U, V, Wo, _, _ = prob.normal(eo, xyz)
    S, Vinv, Y = prob.reduced(U, V, Wo)
    Cc = np.linalg.inv(S)
    Cc4 = Cc.reshape(n, 6, n, 6).transpose(0, 2, 1, 3)  # [j1, j2] → 6×6
    cov_photos = Cc4[np.arange(n), np.arange(n)].copy()
    ph, pt, ia, ib = meas.obs_photo, meas.obs_point, prob.ia, prob.ib
    Cab = Cc4[ph[ia], ph[ib]]
    # point covariance: V⁻¹ + Σ_{a,b} Y_aᵀ C[ja, jb] Y_b over the observations a, b of the point
    cov_points = Vinv.copy()
    cov_points += _scatter(pt[ia], np.einsum("kia,kij,kjb->kab", Y[ia], Cab, Y[ib]), P)
    # photo–point cross covariance of each observation's own photo and point: C_jk = −Σ_b C[j, jb] Y_b
    Cjk = _scatter(ia, -np.einsum("kij,kjb->kib", Cab, Y[ib]), N)
    # hat-matrix diagonal of each image row: J_i C J_iᵀ with J_i = [A_i, B_i]
    h = (np.einsum("nri,nij,nrj->nr", A, cov_photos[ph], A) + 2.0 * np.einsum("nri,nij,nrj->nr", A, Cjk, B)
         + np.einsum("nri,nij,nrj->nr", B, cov_points[pt], B))
    red_ctrl = np.full((P, 3), np.nan)
    c = prob.ctrl
    red_ctrl[c] = 1.0 - np.einsum("pii->pi", cov_points[c]) * prob.wc2[c]
    return Precision(cov_points, cov_photos, 1.0 - h, red_ctrl)


@V.checked(meas=Measurements, eo=V.array(ndim=2, last=6), xyz_m=V.array(ndim=2, last=3),
           point_index=V.indices(ndim=None))
def point_covariance(meas: Measurements, eo, xyz_m, point_index) -> np.ndarray:
    """Full a priori covariance (3k × 3k, m²) of the points ``point_index`` (k row indices), cross terms included.

    C_pq = δ_pq·V_p⁻¹ + G_pᵀ S⁻¹ G_q with G_q = Σ over the observations b of point q of W_b V_q⁻¹ placed at
    the rows of photo j_b (see the module notes).  The cross terms carry what all the points share — the
    block's datum from its control, its bending — and decide how far an RMS over many points may stray.
    """
    prob = _Problem(meas)
    eo, xyz = _shaped("eo", eo, (prob.n, 6)), _shaped("xyz_m", xyz_m, (prob.P, 3))
    idx = np.asarray(point_index, dtype=int).ravel()
    _, _, _, _, U, V, Wo, _, _ = prob.normal(eo, xyz)
    S, Vinv, Y = prob.reduced(U, V, Wo)
    Cc = np.linalg.inv(S)
    pos = np.full(prob.P, -1)
    pos[idx] = np.arange(len(idx))
    G = np.zeros((prob.n, 6, len(idx), 3))
    sel = np.flatnonzero(pos[meas.obs_point] >= 0)
    np.add.at(G, (meas.obs_photo[sel], slice(None), pos[meas.obs_point[sel]]), Y[sel])
    G = G.reshape(6 * prob.n, 3 * len(idx))
    C = G.T @ Cc @ G
    for k, p in enumerate(idx):
        C[3 * k: 3 * k + 3, 3 * k: 3 * k + 3] += Vinv[p]
    return C


@V.checked(cov=V.array(ndim=2, min_len=1), components=V.indices())
def rms_expectation(cov, components) -> tuple:
    """Expected RMS of errors with covariance ``cov`` over the selected ``components``, and its standard deviation.

    Parameters
    ----------
    cov : (3k, 3k) covariance of k points' X, Y, Z (:func:`point_covariance`)
    components : which coordinates: e.g. (0, 1) for plan, (2,) for height

    Returns
    -------
    (rms, sd) : for plan the RMS is √(mean over points of dX² + dY²); E[Σd²] = tr C, Var[Σd²] = 2·tr C² for
    Gaussian errors, so rms = √(tr C / k) and sd ≈ √(2 tr C²) / (2 k rms) (to first order).
    """
    cov = np.asarray(cov, dtype=float)
    if cov.shape[0] != cov.shape[1] or cov.shape[0] % 3:
        raise ValueError(f"cov has shape {cov.shape}; expected a square (3k, 3k) covariance of k points")
    k = cov.shape[0] // 3
    sel = np.array([3 * i + c for i in range(k) for c in components])
    Cs = cov[np.ix_(sel, sel)]
    tr = float(np.trace(Cs))
    rms = math.sqrt(tr / k)
    sd = math.sqrt(2.0 * float(np.sum(Cs * Cs))) / (2.0 * k * rms) if rms > 0 else 0.0
    return rms, sd


@V.checked(cov_xy=V.shape(2, 2, stacked=True))
def error_ellipse(cov_xy, p: float | None = None) -> tuple:
    """Semi-axes and orientation of the standard error ellipse (эллипс ошибок) of a 2×2 covariance.

    Parameters
    ----------
    cov_xy : (..., 2, 2) covariance of X, Y, m²
    p : optional probability (0 < p < 1): scale the ellipse to contain the point with probability p
        (k = √(−2 ln(1 − p)); 0.95 → 2.45); default the standard ellipse (k = 1, 39.3 %)

    Returns
    -------
    a, b : (...,) semi-major and semi-minor axes, m
    theta_deg : (...,) direction of the major axis, degrees counter-clockwise from +X
    """
    C = np.asarray(cov_xy, dtype=float)
    k = 1.0 if p is None else math.sqrt(-2.0 * math.log(1.0 - check_range("p", p, 0.0, 1.0, lo_open=True,
                                                                            hi_open=True)))
    sxx, syy, sxy = C[..., 0, 0], C[..., 1, 1], C[..., 0, 1]
    mean = 0.5 * (sxx + syy)
    rad = np.sqrt(0.25 * (sxx - syy) ** 2 + sxy**2)
    a = k * np.sqrt(np.maximum(mean + rad, 0.0))
    b = k * np.sqrt(np.maximum(mean - rad, 0.0))
    theta = 0.5 * np.degrees(np.arctan2(2.0 * sxy, sxx - syy))
    return a, b, theta


@dataclass(frozen=True, eq=False)
class Snooping:
    """The result of :func:`data_snooping`.

    Attributes
    ----------
    adjustment : Adjustment
        The final adjustment, without the rejected observations.
    rejected : pandas.DataFrame
        One row per rejection, in order: ``round``, ``kind`` ("image" or "control"), ``photo`` (photo
        number or −1), ``point`` (point id), ``w`` (the largest |w| that round).
    rounds : int
        Adjustments run.
    """

    adjustment: Adjustment
    rejected: pd.DataFrame
    rounds: int


def image_critical(critical: float = CRITICAL_W) -> float:
    """The critical value of an image point's √(w_x² + w_y²) at the false-alarm rate of ``critical`` per coordinate.

    α = 2·(1 − Φ(critical)) for a single normal w; √(w_x² + w_y²) of two independent normal w is Rayleigh,
    P(> c) = exp(−c²/2), so c = √(−2 ln α): 4.40 for ``critical`` = 4.0, 3.72 for 3.29.
    """
    from scipy.stats import norm

    alpha = 2.0 * norm.sf(check_range("critical", critical, 1.0, 20.0))
    return math.sqrt(-2.0 * math.log(alpha))


@V.checked(meas=Measurements)
def data_snooping(meas: Measurements, eo0, xyz0_m, *, critical: float = CRITICAL_W, max_rejections: int = 10,
                  max_iter: int = 50) -> Snooping:
    """Baarda's data snooping: adjust, reject the observation with the largest |w| above ``critical``, repeat.

    An image observation is judged by √(w_x² + w_y²) against :func:`image_critical` (the same false-alarm
    rate), a control point by the largest |w| of its X, Y, Z (a rejected control point keeps its image
    measurements as a tie point).  The ``w`` reported is the statistic itself.  Stops when no |w| exceeds
    ``critical`` (default :data:`CRITICAL_W` = 4.0) or after ``max_rejections`` (0 ≤ … ≤ 100).
    """
    crit = check_range("critical", critical, 1.0, 20.0)
    mr = check_int_range("max_rejections", max_rejections, 0, 100)
    crit_img = image_critical(crit)
    adj = adjust(meas, eo0, xyz0_m, max_iter=max_iter)
    rows = []
    rounds = 1
    for rnd in range(1, mr + 1):
        w_img, w_ctrl = adj.standardized_residuals()
        # an image point is two coordinates: its test statistic is |w| = √(w_x² + w_y²), scaled so that both
        # kinds of observation are compared at the same false-alarm rate
        wi = np.hypot(w_img[:, 0], w_img[:, 1]) * (crit / crit_img) if len(w_img) else np.zeros(0)
        wc = np.nanmax(np.abs(np.nan_to_num(w_ctrl, nan=0.0)), axis=1)
        i_img = int(np.argmax(wi)) if len(wi) else -1
        i_c = int(np.argmax(wc))
        best_img = wi[i_img] if i_img >= 0 else 0.0
        if max(best_img, wc[i_c]) <= crit:
            break
        m = adj.meas
        eo, xyz = adj.eo, adj.xyz_m
        if best_img >= wc[i_c]:
            rows.append((rnd, "image", int(m.photo_ids[m.obs_photo[i_img]]), int(m.point_ids[m.obs_point[i_img]]),
                         float(best_img * crit_img / crit)))
            new = m.without_observations([i_img])
            idx = np.array([m.index_of_point(p) for p in new.point_ids], dtype=int)
            xyz = xyz[idx]
        else:
            rows.append((rnd, "control", -1, int(m.point_ids[i_c]), float(wc[i_c])))
            new = m.as_tie(m.point_ids[i_c])
            xyz = xyz[np.array([m.index_of_point(p) for p in new.point_ids], dtype=int)]
        adj = adjust(new, eo, xyz, max_iter=max_iter)
        rounds += 1
    rej = pd.DataFrame(rows, columns=["round", "kind", "photo", "point", "w"])
    return Snooping(adj, rej, rounds)
