"""The three-stage procedure of article 002: strip models → joined strips → the block on its control.

A bundle adjustment is non-linear: it needs approximate values of every
unknown, and it is spoilt by blunders (грубые ошибки).  Article 002 gets both
from two cheaper stages before the bundle (третий этап):

1. **Strip models** (одномаршрутные сети).  Each strip is built on its own in an
   arbitrary scale and orientation by the method of continuation (метод
   продолжений, semi-dependent models): the first photo fixes the strip's
   frame; each next photo is oriented to the previous one by dependent
   relative orientation (взаимное ориентирование — five elements, from the
   transverse parallaxes q of the points the pair shares), and the new model
   is brought to the scale of the previous one through the points of their
   triple overlap.  :func:`relative_orientation`, :func:`form_strip`.
2. **Joined strips** (объединение маршрутов).  Every next strip is brought into
   the frame of the first by a 3-D similarity transformation (7 parameters)
   on the points of the side overlaps.  :func:`join_strips`.
3. **The block on its control** (внешнее ориентирование блока).  One more 3-D
   similarity, onto the control points' ground coordinates, gives
   approximate ground coordinates of every point and every photo — the start
   of the bundle adjustment.  :func:`three_stage`.

Each stage screens its data (the article: "quality controls with rejection of
erroneous results are built into the first two stages"): a pair's
observations whose transverse parallax exceeds ``k`` times the pair's robust
RMS are rejected and the orientation repeated; the points whose coordinates
from two models or two strips disagree beyond ``k`` robust RMS are not used
for the connection; control points whose residual after the block's
similarity fit exceeds ``k`` robust RMS are reported (a similarity cannot
absorb the block's bending, so this last screen catches only gross blunders —
the bundle's data snooping does the rest).

Model units: the first base of a strip is 1 (arbitrary scale).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import _validate as V
from .._validate import check_range
from .block import Measurements
from .collinearity import _rotation_opk as rotation_opk
from .collinearity import opk_from_matrix

__all__ = ["similarity_fit", "Similarity", "relative_orientation", "RelativeOrientation", "intersect",
           "StripModel", "form_strip", "join_strips", "ThreeStage", "three_stage"]


# =========================================================================== 3-D similarity
@dataclass(frozen=True)
class Similarity:
    """B ≈ s·R·A + t: scale ``s``, rotation ``R`` (3, 3), shift ``t`` (3,); ``rms`` of the fit's residuals."""

    s: float
    R: np.ndarray
    t: np.ndarray
    rms: float = 0.0

    def apply(self, A) -> np.ndarray:
        return self.s * np.asarray(A, dtype=float) @ self.R.T + self.t

    def rotate(self, R_model) -> np.ndarray:
        """Rotation matrices of photos, model → target frame: R·R_model."""
        return self.R @ np.asarray(R_model, dtype=float)


@V.checked(A=V.points(3, min_points=2), B=V.points(3, min_points=2), weights=V.optional(V.array(ndim=1)))
def similarity_fit(A, B, weights=None) -> Similarity:
    """Least-squares 3-D similarity (Helmert, 7 parameters) taking points ``A`` (k, 3) onto ``B`` (k, 3).

    Closed form (Umeyama 1991): centroids, the SVD of the cross-covariance, no reflection.
    Needs k ≥ 3 points not on one line.
    """
    A = np.asarray(A, dtype=float)
    B = np.asarray(B, dtype=float)
    if A.shape != B.shape or A.ndim != 2 or A.shape[1] != 3:
        raise ValueError(f"A and B must have the same shape (k, 3); got {A.shape} and {B.shape}")
    if len(A) < 3:
        raise ValueError(f"a 3-D similarity needs at least 3 common points; got {len(A)}")
    w = np.ones(len(A)) if weights is None else np.asarray(weights, dtype=float)
    w = w / w.sum()
    ca, cb = w @ A, w @ B
    a, b = A - ca, B - cb
    C = (b * w[:, None]).T @ a
    Uu, sv, Vt = np.linalg.svd(C)
    D = np.diag([1.0, 1.0, np.sign(np.linalg.det(Uu @ Vt)) or 1.0])
    R = Uu @ D @ Vt
    var_a = float(w @ np.sum(a * a, axis=1))
    if var_a <= 0 or sv[1] < 1e-9 * max(sv[0], 1e-300):
        raise ValueError("the common points lie on one line (or coincide): a 3-D similarity needs at least 3 "
                         "points not on one line")
    s = float(np.sum(sv * np.diag(D)) / var_a)
    t = cb - s * R @ ca
    res = B - (s * A @ R.T + t)
    return Similarity(s, R, t, float(np.sqrt(np.mean(np.sum(res**2, axis=1)))))


def _robust_fit(A, B, k):
    """A similarity with the points beyond k robust RMS left out (twice); returns (fit, mask of used points)."""
    use = np.ones(len(A), bool)
    for _ in range(3):
        fit = similarity_fit(A[use], B[use])
        d = np.linalg.norm(B - fit.apply(A), axis=1)
        scale = 1.4826 * np.median(d[use]) + 1e-12
        new = d <= k * max(scale, 1e-9 * (np.linalg.norm(B.std(axis=0)) + 1e-12))
        if new.sum() < 3 or np.array_equal(new, use):
            break
        use = new
    return similarity_fit(A[use], B[use]), use


# =========================================================================== relative orientation
def _rays(R, xy, f):
    v = np.column_stack([xy, np.full(len(xy), -f)])
    return v @ R.T


@V.checked(S1=V.array(last=3), r1=V.array(ndim=2, last=3), S2=V.array(last=3), r2=V.array(ndim=2, last=3))
def intersect(S1, r1, S2, r2) -> np.ndarray:
    """Forward intersection (прямая засечка) of ray pairs: the midpoints of the shortest segments, (k, 3)."""
    V.check_broadcast(S1=S1, r1=r1, S2=S2, r2=r2)
    S1, S2 = np.broadcast_to(S1, r1.shape), np.broadcast_to(S2, r2.shape)
    d = S2 - S1
    a = np.sum(r1 * r1, 1)
    b = np.sum(r1 * r2, 1)
    c = np.sum(r2 * r2, 1)
    e = np.sum(r1 * d, 1)
    g = np.sum(r2 * d, 1)
    den = a * c - b * b
    den = np.where(np.abs(den) < 1e-300, 1e-300, den)
    t = (e * c - b * g) / den
    u = (e * b - a * g) / den
    return 0.5 * ((S1 + t[:, None] * r1) + (S2 + u[:, None] * r2))


def _base_frame(u):
    """Rotation whose first column is the base direction u (normal case of the pair)."""
    x = u / math.sqrt(u[0] * u[0] + u[1] * u[1] + u[2] * u[2])
    y = np.array([-x[1], x[0], 0.0])  # (0, 0, 1) × x
    ny = math.hypot(y[0], y[1])
    y = np.array([0.0, 1.0, 0.0]) if ny < 1e-9 else y / ny
    z = np.array([x[1] * y[2] - x[2] * y[1], x[2] * y[0] - x[0] * y[2], x[0] * y[1] - x[1] * y[0]])
    return np.column_stack([x, y, z])


def _parallax(params, R_left, xy_l, xy_r, f):
    by, bz, dw, dp, dk = params
    u = R_left @ np.array([1.0, by, bz])
    Rr = R_left @ rotation_opk(dw, dp, dk)
    Rb = _base_frame(u)
    vl = _rays(Rb.T @ R_left, xy_l, f)
    vr = _rays(Rb.T @ Rr, xy_r, f)
    return f * (vl[:, 1] / vl[:, 2] - vr[:, 1] / vr[:, 2]), u, Rr


@dataclass(frozen=True)
class RelativeOrientation:
    """Dependent relative orientation of the right photo of a pair to the left one.

    Attributes
    ----------
    R_right : (3, 3) the right photo's rotation in the model frame
    base_dir : (3,) unit vector of the base S_left → S_right in the model frame
    q_mm : (k,) residual transverse parallaxes (поперечные параллаксы) of the pair's points, mm
    used : (k,) bool — points kept (the others rejected as blunders)
    elements : (5,) by, bz (in units of the base) and ω, φ, κ of the right photo relative to the left (rad)
    """

    R_right: np.ndarray
    base_dir: np.ndarray
    q_mm: np.ndarray
    used: np.ndarray
    elements: np.ndarray

    @property
    def rms_q_mm(self) -> float:
        q = self.q_mm[self.used]
        return float(np.sqrt(np.mean(q * q))) if len(q) else float("nan")


@V.checked(xy_left=V.points(2, min_points=5), xy_right=V.points(2, min_points=5),
           f_mm=V.number(0.0, 2000.0, lo_open=True),
           R_left=V.optional(V.shape(3, 3)), reject_k=V.number(0.0), max_iter=V.whole(1, 1000))
def relative_orientation(xy_left, xy_right, f_mm: float, R_left=None, *, reject_k: float = 4.0,
                         max_iter: int = 12) -> RelativeOrientation:
    """Dependent relative orientation (зависимое взаимное ориентирование) from conjugate points.

    Five elements — the base components by, bz (bx = 1) and the right photo's ω, φ, κ relative to the
    left photo, whose rotation ``R_left`` in the model frame is fixed — chosen to minimise the transverse
    parallaxes q = f·(y′/z′ − y″/z″) in the normal-case frame of the pair (Gauss–Newton).  Needs at
    least 6 points (5 elements + 1 check), the six standard (Gruber) points being the classical set.
    Points whose |q| exceeds ``reject_k`` × the robust RMS (and 3 µm) are rejected and the orientation
    repeated (``reject_k`` = 0 turns the screening off).
    """
    xl = np.asarray(xy_left, dtype=float)
    xr = np.asarray(xy_right, dtype=float)
    if xl.shape != xr.shape or xl.ndim != 2 or xl.shape[1] != 2:
        raise ValueError(f"xy_left and xy_right must have the same shape (k, 2); got {xl.shape}, {xr.shape}")
    if len(xl) < 6:
        raise ValueError(f"relative orientation has {len(xl)} conjugate point(s); the valid range is at least 6")
    kk = check_range("reject_k", reject_k, 0.0, 100.0)
    Rl = np.eye(3) if R_left is None else np.asarray(R_left, dtype=float)
    used = np.ones(len(xl), bool)
    p = np.zeros(5)
    for _round in range(4):
        for _ in range(max_iter):
            q, _, _ = _parallax(p, Rl, xl[used], xr[used], f_mm)
            J = np.empty((len(q), 5))
            for j in range(5):
                h = np.zeros(5)
                h[j] = 1e-7
                J[:, j] = (_parallax(p + h, Rl, xl[used], xr[used], f_mm)[0] - q) / 1e-7
            dp = np.linalg.lstsq(J, -q, rcond=None)[0]
            p = p + dp
            if np.max(np.abs(dp)) < 1e-10:  # 1e-10 of the base and rad: far below any measuring error
                break
        q_all, u, Rr = _parallax(p, Rl, xl, xr, f_mm)
        if kk == 0:
            break
        scale = max(1.4826 * np.median(np.abs(q_all[used])), 0.003)
        new = np.abs(q_all) <= kk * scale
        if new.sum() < 6 or np.array_equal(new, used):
            break
        used = new
    q_all, u, Rr = _parallax(p, Rl, xl, xr, f_mm)
    return RelativeOrientation(Rr, u / np.linalg.norm(u), q_all, used, p)


# =========================================================================== strips
@dataclass(frozen=True, eq=False)
class StripModel:
    """One strip built by the method of continuation, in its own frame (first photo: S = 0, R = I; first base 1).

    Attributes
    ----------
    photos : (k,) photo row indices of the block, in the order of flight
    R : (k, 3, 3) rotations of the photos in the strip frame
    S : (k, 3) projection centres in the strip frame
    point_index : (p,) point row indices of the block with strip coordinates
    xyz : (p, 3) their strip coordinates (mean over the models that contain them)
    rms_q_mm : (k − 1,) RMS transverse parallax of each pair after relative orientation, mm
    rejected_obs : (r,) indices of image observations rejected by the relative orientations
    """

    photos: np.ndarray
    R: np.ndarray
    S: np.ndarray
    point_index: np.ndarray
    xyz: np.ndarray
    rms_q_mm: np.ndarray
    rejected_obs: np.ndarray


def _obs_of(meas: Measurements, j: int) -> dict:
    sel = np.flatnonzero(meas.obs_photo == j)
    return {int(meas.obs_point[i]): int(i) for i in sel}


@V.checked(meas=Measurements, photos=V.indices(min_len=2))
def form_strip(meas: Measurements, photos, *, reject_k: float = 4.0) -> StripModel:
    """Build one strip by dependent relative orientations and scale transfer (stage 1, see the module notes).

    ``photos``: row indices of the block's photos in the order of flight (at least 2).  Each consecutive
    pair needs at least 6 common points, each model after the first at least 2 points shared with the
    previous model (the triple overlap) to carry the scale.
    """
    photos = np.asarray(photos, dtype=int)
    if len(photos) < 2:
        raise ValueError(f"a strip needs at least 2 photos; got {len(photos)}")
    f = meas.f_mm
    Rs = [np.eye(3)]
    Ss = [np.zeros(3)]
    coords: dict[int, list] = {}
    rms, rejected = [], []
    prev_model: dict[int, np.ndarray] = {}
    for a in range(len(photos) - 1):
        ja, jb = photos[a], photos[a + 1]
        oa, ob = _obs_of(meas, ja), _obs_of(meas, jb)
        common = sorted(set(oa) & set(ob))
        if len(common) < 6:
            raise ValueError(f"photos {int(meas.photo_ids[ja])} and {int(meas.photo_ids[jb])} share {len(common)} "
                             "point(s); the valid range is at least 6 for their relative orientation")
        ia = np.array([oa[k] for k in common])
        ib = np.array([ob[k] for k in common])
        ro = relative_orientation(meas.xy_mm[ia], meas.xy_mm[ib], f, Rs[-1], reject_k=reject_k)
        rms.append(ro.rms_q_mm)
        rejected.extend(ib[~ro.used].tolist())
        keep = np.array(common)[ro.used]
        ia, ib = ia[ro.used], ib[ro.used]
        S_a = Ss[-1]
        Q = intersect(S_a, _rays(Rs[-1], meas.xy_mm[ia], f), S_a + ro.base_dir, _rays(ro.R_right, meas.xy_mm[ib], f))
        if a == 0:
            scale = 1.0
        else:
            shared = [i for i, k in enumerate(keep) if k in prev_model]
            if len(shared) < 2:
                raise ValueError(f"the models before and after photo {int(meas.photo_ids[ja])} share "
                                 f"{len(shared)} point(s); the valid range is at least 2 (the triple overlap)")
            old = np.array([prev_model[int(keep[i])] for i in shared])
            ratio = np.linalg.norm(old - S_a, axis=1) / np.maximum(np.linalg.norm(Q[shared] - S_a, axis=1), 1e-300)
            med = np.median(ratio)
            good = np.abs(ratio - med) <= max(reject_k, 3.0) * max(1.4826 * np.median(np.abs(ratio - med)),
                                                                   1e-4 * med) if reject_k else np.ones(len(ratio), bool)
            scale = float(np.mean(ratio[good]))
        Q = S_a + scale * (Q - S_a)
        Rs.append(ro.R_right)
        Ss.append(S_a + scale * ro.base_dir)
        prev_model = {int(k): Q[i] for i, k in enumerate(keep)}
        for k, xyz in prev_model.items():
            coords.setdefault(k, []).append(xyz)
    idx = np.array(sorted(coords), dtype=int)
    xyz = np.array([np.mean(coords[k], axis=0) for k in idx]).reshape(-1, 3)
    return StripModel(photos, np.array(Rs), np.array(Ss), idx, xyz, np.array(rms), np.array(rejected, dtype=int))


def _transform_strip(st: StripModel, sim: Similarity) -> StripModel:
    return StripModel(st.photos, np.einsum("ij,njk->nik", sim.R, st.R), sim.apply(st.S), st.point_index,
                      sim.apply(st.xyz), st.rms_q_mm, st.rejected_obs)


@V.checked(strips=V.sequence(V.of_type(StripModel), min_len=1), reject_k=V.number(0.0))
def join_strips(strips, *, reject_k: float = 4.0):
    """Stage 2: bring every strip into the frame of the first by 3-D similarities on the shared points.

    Strips are joined in order, each to the union of those before it.  Returns (strips in the common
    frame, a DataFrame with one row per joined strip: ``strip``, ``common points``, ``used``, ``rms``).
    """
    out = [strips[0]]
    pool: dict[int, list] = {int(k): [x] for k, x in zip(strips[0].point_index, strips[0].xyz)}
    rows = []
    for s_i, st in enumerate(strips[1:], start=1):
        common = [i for i, k in enumerate(st.point_index) if int(k) in pool]
        if len(common) < 3:
            raise ValueError(f"strip {s_i} shares {len(common)} point(s) with the strips before it; the valid "
                             "range is at least 3 (points in the side overlap)")
        A = st.xyz[common]
        B = np.array([np.mean(pool[int(st.point_index[i])], axis=0) for i in common])
        sim, used = _robust_fit(A, B, reject_k) if reject_k else (similarity_fit(A, B), np.ones(len(A), bool))
        t = _transform_strip(st, sim)
        out.append(t)
        for k, x in zip(t.point_index, t.xyz):
            pool.setdefault(int(k), []).append(x)
        rows.append((s_i, len(common), int(used.sum()), sim.rms))
    return out, pd.DataFrame(rows, columns=["strip", "common points", "used", "rms"])


@dataclass(frozen=True, eq=False)
class ThreeStage:
    """Approximations from the three-stage procedure, and what each stage screened.

    Attributes
    ----------
    eo0 : (n, 6) approximate exterior orientation of every photo (X, Y, Z m; ω, φ, κ rad)
    xyz0_m : (P, 3) approximate ground coordinates of every point, m
    strips : list of :class:`StripModel` in the common (first strip's) frame
    rms_q_mm : (n_pairs,) RMS transverse parallax of every pair (stage 1), mm
    rejected_obs : (r,) image observations rejected at stage 1
    joins : DataFrame of stage 2 (one row per joined strip)
    control : DataFrame of stage 3: control id, residual dX, dY, dZ (m) of the block's similarity fit,
        and ``suspect`` (beyond ``reject_k`` robust RMS)
    to_ground : :class:`Similarity` of stage 3 (block frame → ground)
    """

    eo0: np.ndarray
    xyz0_m: np.ndarray
    strips: list
    rms_q_mm: np.ndarray
    rejected_obs: np.ndarray
    joins: pd.DataFrame
    control: pd.DataFrame
    to_ground: Similarity


@V.checked(meas=Measurements)
def three_stage(meas: Measurements, *, reject_k: float = 4.0) -> ThreeStage:
    """Article 002's procedure before the bundle: strip models, joined strips, the block on its control.

    The strips are the block's ``photo_strip`` groups, each in ``photo_order``.  Points that no strip
    model holds (e.g. control points measured on a single photo) get their approximate position from
    their control coordinates, or by intersecting their rays from the approximate photos.
    """
    strips = []
    for s in np.unique(meas.photo_strip):
        rows = np.flatnonzero(meas.photo_strip == s)
        rows = rows[np.argsort(meas.photo_order[rows], kind="stable")]
        strips.append(form_strip(meas, rows, reject_k=reject_k))
    joined, joins = join_strips(strips, reject_k=reject_k)
    # block coordinates of every point: mean over strips
    pool: dict[int, list] = {}
    for st in joined:
        for k, x in zip(st.point_index, st.xyz):
            pool.setdefault(int(k), []).append(x)
    ctrl = [k for k in np.flatnonzero(meas.is_control) if int(k) in pool]
    if len(ctrl) < 3:
        raise ValueError(f"{len(ctrl)} control point(s) are in the strip models; the valid range is at least 3 "
                         "to place the block")
    A = np.array([np.mean(pool[int(k)], axis=0) for k in ctrl])
    Bc = meas.control_XYZ_m[ctrl]
    sim, used = _robust_fit(A, Bc, reject_k) if reject_k else (similarity_fit(A, Bc), np.ones(len(A), bool))
    res = Bc - sim.apply(A)
    control = pd.DataFrame({"id": meas.point_ids[ctrl], "dX, m": res[:, 0], "dY, m": res[:, 1],
                            "dZ, m": res[:, 2], "suspect": ~used})
    eo0 = np.zeros((meas.n_photos, 6))
    for st in joined:
        g = _transform_strip(st, sim)
        eo0[g.photos, :3] = g.S
        eo0[g.photos, 3:] = opk_from_matrix(g.R)
    xyz0 = np.full((meas.n_points, 3), np.nan)
    for k, xs in pool.items():
        xyz0[k] = sim.apply(np.mean(xs, axis=0))
    missing = np.flatnonzero(np.isnan(xyz0[:, 0]))
    for k in missing:
        if meas.is_control[k]:
            xyz0[k] = meas.control_XYZ_m[k]
            continue
        obs = np.flatnonzero(meas.obs_point == k)
        j1, j2 = meas.obs_photo[obs[0]], meas.obs_photo[obs[-1]]
        R1, R2 = rotation_opk(*eo0[j1, 3:]), rotation_opk(*eo0[j2, 3:])
        xyz0[k] = intersect.__wrapped__(eo0[j1, :3], _rays(R1, meas.xy_mm[obs[:1]], meas.f_mm), eo0[j2, :3],
                            _rays(R2, meas.xy_mm[obs[-1:]], meas.f_mm))[0]
    rej = np.concatenate([st.rejected_obs for st in strips]) if strips else np.zeros(0, int)
    return ThreeStage(eo0, xyz0, joined, np.concatenate([st.rms_q_mm for st in strips]), rej, joins, control, sim)
