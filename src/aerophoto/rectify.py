"""Rectification of photos of flat ground (фототрансформирование, guide §12).

A tilted photo of flat ground differs from the plan by a projective
transformation.  The guide makes the rectified print on a photo transformer
(фототрансформатор ФТБ): the negative is projected onto a screen carrying the
base (основа) with four transformation points, and the operator moves the
projection until the images of the points fall on them — within 0.4 mm
(:data:`TOLERANCE_MM`).  This module does the same three ways:

* analytically, :func:`rectify_points`: the projective transformation fixed by
  four (or, least squares, more) control points, with the residuals at the
  control points and at independent check points against 0.4 mm;
* as the photo transformer's sequence of motions, :func:`transformer_sequence`:
  centre, orient, scale, find the principal horizontal hh, turn it onto the
  screen's axis, tilt the screen and rescale, repeated until the points fall
  within 0.4 mm (guide §12 step 3, figure 20);
* the paper's deformation and the substrate (подложка) that compensates it,
  table 11: K_d = [δl]/[l₀], t = K_d·f·(K_t + 1), K_t = m/M
  (:func:`paper_deformation`, :func:`substrate_thickness_mm`).

Resampling a whole photo through the fitted transformation is
:func:`aerophoto.projective.warp_photo`.

The photo transformer's model
-----------------------------
The screen image of a photo point is ``s·R(θ)·lev(x; ε, λ_t) + t`` (plan mm):
``lev`` projects the photo point through its centre onto a plane tilted by
ε in the direction λ_t (the equivalent vertical photo, photo mm, computed
with :func:`aerophoto.geometry.rotation_matrix`), R(θ) turns the cassette, s
is the enlargement (K_t = m/M when everything is right) and t the shift of
the negative (decentration).  Six numbers: exactly the freedom a photo of
flat ground needs once f is known; the true values are ε = α, λ_t = λ,
s = m/M.

Sign of t (table 11)
--------------------
δl = l₀ − l_i (the grid's length minus its print's), so K_d > 0 when the
paper shrinks and K_d < 0 when it stretches.  The substrate raises the base
planchet by t while the images are matched; the paper is exposed without it,
t further from the lens, so its image is larger by t/(f·(K_t + 1)) = K_d —
what a shrinking paper needs.  A negative t (stretching paper, the guide's
example) asks for the opposite: the paper, not the planchet, raised by |t|.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace

import numpy as np
import pandas as pd

from . import _validate as V
from . import geometry as g
from . import plane
from ._validate import check_finite_array, check_int_range, check_points, check_positive, check_range

__all__ = [
    "TOLERANCE_MM",
    "GRID_CELL_MM",
    "PaperDeformation",
    "paper_deformation",
    "control_grid_length_mm",
    "enlargement",
    "projection_distance_mm",
    "substrate_thickness_mm",
    "Rectification",
    "rectify_points",
    "TransformerState",
    "TransformerStep",
    "TransformerRun",
    "STEP_NAMES",
    "screen_image",
    "true_state",
    "principal_horizontal",
    "transformer_sequence",
]

#: the largest misfit of a matched point, mm on the base (guide §12 step 3)
TOLERANCE_MM = 0.4
#: the side of the control grid's squares on glass, mm (guide §12 step 2)
GRID_CELL_MM = 5.0


# --------------------------------------------------------------------------- paper deformation (table 11)
@dataclass(frozen=True)
class PaperDeformation:
    """Lengths on the control grid and on its contact print, and the mean deformation coefficient (table 11).

    Attributes
    ----------
    l0_mm : ndarray (k,)
        Lengths on the glass grid l₀ = 5 mm·n, mm.
    li_mm : ndarray (k,)
        The same lengths measured on the print l_i, mm (to 0.1 mm).
    """

    l0_mm: np.ndarray
    li_mm: np.ndarray

    @property
    def dl_mm(self) -> np.ndarray:
        """δl = l₀ − l_i, mm (the sign the guide's table prints)."""
        return self.l0_mm - self.li_mm

    @property
    def sum_l0_mm(self) -> float:
        return float(np.sum(self.l0_mm))

    @property
    def sum_li_mm(self) -> float:
        return float(np.sum(self.li_mm))

    @property
    def sum_dl_mm(self) -> float:
        return float(np.sum(self.dl_mm))

    @property
    def K_d(self) -> float:
        """K_d = [δl]/[l₀]: > 0 the paper shrinks, < 0 it stretches."""
        return self.sum_dl_mm / self.sum_l0_mm

    def table(self, names=None) -> pd.DataFrame:
        """Laid out like table 11: l₀, l_i, δl per line and the sums."""
        k = len(self.l0_mm)
        names = list(names) if names is not None else [f"l{j + 1}" for j in range(k)]
        df = pd.DataFrame({"l₀ on the grid, mm": self.l0_mm, "l_i on the print, mm": self.li_mm,
                           "δl = l₀ − l_i, mm": self.dl_mm}, index=pd.Index(names, name="line"))
        df.loc["Σ"] = [self.sum_l0_mm, self.sum_li_mm, self.sum_dl_mm]
        return df.round(4) + 0.0  # for display: 115.0 − 115.3 is −0.3, not −0.29999999999999716 (+ 0.0: no −0.0)


def paper_deformation(l0_mm, li_mm) -> PaperDeformation:
    """The mean systematic deformation of the photo paper, K_d = [δl]/[l₀] (guide §12 step 2, table 11).

    Parameters
    ----------
    l0_mm, li_mm : array_like (k,)
        Lengths between chosen points of the glass control grid (5 mm squares)
        and the same lengths on its contact print on the paper to be used, mm;
        every length 1…2000 mm.
    """
    l0 = check_finite_array("l0_mm", l0_mm, ndim=1, min_len=1, max_size=1000)
    li = check_finite_array("li_mm", li_mm, ndim=1, min_len=1, max_size=1000)
    if l0.shape != li.shape:
        raise ValueError(f"l0_mm has {len(l0)} lengths and li_mm {len(li)}; give one print length per grid length")
    for name, a in (("l0_mm", l0), ("li_mm", li)):
        bad = (a < 1.0) | (a > 2000.0)
        if np.any(bad):
            raise ValueError(f"{name} contains {a[bad][0]:g}; the valid range is 1 ≤ length ≤ 2000 mm")
    return PaperDeformation(l0, li)


def control_grid_length_mm(n_along: float, n_across: float = 0.0, cell_mm: float = GRID_CELL_MM) -> float:
    """A length on the control grid, mm: 5 mm · n along a line of squares, 5 mm · √(n₁² + n₂²) across a rectangle."""
    a = check_range("n_along", n_along, 0.0, 400.0)
    b = check_range("n_across", n_across, 0.0, 400.0)
    if a == 0 and b == 0:
        raise ValueError("n_along = n_across = 0: a length needs at least one square")
    return check_positive("cell_mm", cell_mm, unit="mm", hi=100.0) * math.hypot(a, b)


def enlargement(m: float, M: float) -> float:
    """The enlargement K_t = m/M from the photo (1:m) to the plan (1:M) (guide §12)."""
    return check_positive("m", m, hi=1e7) / check_positive("M", M, hi=1e7)


def projection_distance_mm(f_mm: float, K_t: float) -> float:
    """Lens-to-screen distance f·(K_t + 1), mm, for the enlargement K_t (thin-lens law)."""
    return check_positive("f_mm", f_mm, unit="mm", hi=2000.0) * (check_positive("K_t", K_t, hi=1000.0) + 1.0)


def substrate_thickness_mm(K_d: float, f_mm: float, K_t: float) -> float:
    """The substrate thickness t = K_d·f·(K_t + 1), mm, signed (guide §12 step 2; see the module notes).

    Parameters
    ----------
    K_d : float
        Mean paper deformation, |K_d| < 0.1 (:func:`paper_deformation`).
    f_mm : float
        Focal length f, mm (the guide's table 11: f = 108 mm).
    K_t : float
        Enlargement m/M (:func:`enlargement`).
    """
    k = check_range("K_d", K_d, -0.1, 0.1, lo_open=True, hi_open=True)
    return k * projection_distance_mm(f_mm, K_t)


# --------------------------------------------------------------------------- four-point rectification
@dataclass(frozen=True)
class Rectification:
    """A photo → plan projective transformation from control points, and its residuals (guide §12).

    Attributes
    ----------
    fit : :class:`aerophoto.plane.Fit`
        The transformation and its residuals at the control points (plan mm).
    check_residuals_mm : ndarray (j, 2)
        plan − transformed photo at the check points, plan mm (empty if none).
    tolerance_mm : float
        The largest residual allowed (0.4 mm).
    """

    fit: plane.Fit
    check_residuals_mm: np.ndarray
    tolerance_mm: float = TOLERANCE_MM

    @property
    def transform(self) -> plane.Projective2D:
        return self.fit.transform

    @property
    def control_lengths_mm(self) -> np.ndarray:
        return self.fit.residual_lengths

    @property
    def check_lengths_mm(self) -> np.ndarray:
        return np.hypot(*self.check_residuals_mm.T) if len(self.check_residuals_mm) else np.zeros(0)

    @property
    def max_residual_mm(self) -> float:
        """The largest residual at any control or check point, plan mm."""
        return float(np.max(np.r_[self.control_lengths_mm, self.check_lengths_mm]))

    @property
    def ok(self) -> bool:
        """Every residual within the tolerance."""
        return self.max_residual_mm <= self.tolerance_mm

    def table(self, control_names=None, check_names=None) -> pd.DataFrame:
        """One row per point: role, residual dx, dy and its length (plan mm, to 0.0001 mm) and whether it is within 0.4 mm."""
        nc, nk = len(self.control_lengths_mm), len(self.check_lengths_mm)
        names = list(control_names or [f"control {k + 1}" for k in range(nc)])
        names += list(check_names or [f"check {k + 1}" for k in range(nk)])
        R = np.round(np.vstack([self.fit.residuals, self.check_residuals_mm.reshape(-1, 2)]), 4) + 0.0
        L = np.round(np.r_[self.control_lengths_mm, self.check_lengths_mm], 4) + 0.0
        return pd.DataFrame({"role": ["control"] * nc + ["check"] * nk, "dx, mm": R[:, 0], "dy, mm": R[:, 1],
                             "|d|, mm": L, "≤ 0.4 mm": L <= self.tolerance_mm},
                            index=pd.Index(names, name="point"))


@V.checked(photo_control_mm=V.points(2, min_points=3), plan_control_mm=V.points(2, min_points=3),
           photo_check_mm=V.optional(V.points(2)), plan_check_mm=V.optional(V.points(2)))
def rectify_points(photo_control_mm, plan_control_mm, photo_check_mm=None, plan_check_mm=None, *,
                   tolerance_mm: float = TOLERANCE_MM) -> Rectification:
    """Fit the projective transformation photo → plan on control points and check it (guide §12).

    Parameters
    ----------
    photo_control_mm, plan_control_mm : array_like (k, 2), k ≥ 4
        Control (transformation) points measured on the photo, mm, and their
        positions on the base, plan mm.  Four give an exact fit (zero
        residuals); more give a least-squares fit.
    photo_check_mm, plan_check_mm : array_like (j, 2), optional
        Independent check points, not used in the fit.
    tolerance_mm : float
        Allowed residual, mm on the plan (guide: 0.4 mm).
    """
    f = plane.fit("projective", photo_control_mm, plan_control_mm)
    tol = check_positive("tolerance_mm", tolerance_mm, unit="mm", hi=100.0)
    if photo_check_mm is None and plan_check_mm is None:
        res = np.zeros((0, 2))
    else:
        if photo_check_mm is None or plan_check_mm is None:
            raise ValueError("give both photo_check_mm and plan_check_mm, or neither")
        P = check_points("photo_check_mm", photo_check_mm)
        Q = check_points("plan_check_mm", plan_check_mm)
        if P.shape != Q.shape:
            raise ValueError(f"photo_check_mm has {len(P)} points and plan_check_mm {len(Q)}; they must match")
        res = Q - f.transform.apply(P)
    return Rectification(f, res, tol)


# --------------------------------------------------------------------------- the photo transformer
@dataclass(frozen=True)
class TransformerState:
    """The settings of the photo transformer (see the module notes).

    Attributes
    ----------
    eps_deg : float
        Tilt ε of the projection (the screen's tilt), degrees, |ε| < 45.
    tilt_dir_deg : float
        Direction λ_t on the photo of the principal vertical the tilt acts along, degrees.
    theta_deg : float
        Turn θ of the cassette, degrees.
    scale : float
        Enlargement s (plan mm per mm of the levelled photo).
    tx_mm, ty_mm : float
        Shift of the image on the screen (decentration), plan mm.
    """

    eps_deg: float = 0.0
    tilt_dir_deg: float = 0.0
    theta_deg: float = 0.0
    scale: float = 1.0
    tx_mm: float = 0.0
    ty_mm: float = 0.0

    def __post_init__(self):
        for name, lo, hi in (("eps_deg", -90.0, 90.0), ("tilt_dir_deg", -1e4, 1e4), ("theta_deg", -1e4, 1e4),
                             ("scale", 0.0, 1e3), ("tx_mm", -1e6, 1e6), ("ty_mm", -1e6, 1e6)):
            opened = name in ("eps_deg", "scale")
            object.__setattr__(self, name, check_range(name, getattr(self, name), lo, hi, lo_open=opened,
                                                       hi_open=name == "eps_deg", unit="mm" if "mm" in name else ""))


def _level(xy, f_mm, eps_deg, dir_deg):
    """Photo points (k, 2) → the photo levelled by ε along the direction λ_t (photo mm)."""
    R = g.rotation_matrix(g.Pose(alpha_deg=eps_deg, lambda_deg=dir_deg))
    cam = np.column_stack([xy, np.full(len(xy), -f_mm)])
    G = cam @ R.T
    return -f_mm * G[:, :2] / G[:, 2:3]


@V.checked(state=TransformerState, xy_photo_mm=V.array(last=2))
def screen_image(state: TransformerState, xy_photo_mm, f_mm: float) -> np.ndarray:
    """Where photo points fall on the screen (plan mm) for a transformer ``state``: (k, 2)."""
    P = check_points("xy_photo_mm", xy_photo_mm)
    lev = _level(P, check_positive("f_mm", f_mm, unit="mm", hi=2000.0), state.eps_deg, state.tilt_dir_deg)
    th = math.radians(state.theta_deg)
    c, s = math.cos(th), math.sin(th)
    return state.scale * (lev @ np.array([[c, s], [-s, c]])) + np.array([state.tx_mm, state.ty_mm])


@V.checked(camera=g.Camera, pose=g.Pose)
def true_state(camera: g.Camera, pose: g.Pose, M: float, plan_origin_m=(0.0, 0.0), ground_Z_m: float = 0.0
               ) -> TransformerState:
    """The transformer's settings that map a photo of flat ground at ``ground_Z_m`` exactly onto the plan 1:M.

    ``plan_origin_m`` is the ground point (X, Y, m) at the plan's origin.
    """
    H = pose.flying_height(ground_Z_m)
    s = H * 1000.0 / (camera.f_mm * check_positive("M", M, hi=1e7))
    t = (np.array([pose.X_m, pose.Y_m]) - np.asarray(plan_origin_m, float)) * 1000.0 / M
    return TransformerState(pose.alpha_deg, pose.lambda_deg, pose.kappa_deg, s, float(t[0]), float(t[1]))


@dataclass(frozen=True)
class TransformerStep:
    """One motion of the operator and what it left on the screen.

    Attributes
    ----------
    name : str
        One of :data:`STEP_NAMES`.
    cycle : int
        Which repetition of the sequence (1, 2, …).
    state : :class:`TransformerState`
    images_mm : ndarray (k, 2)
        The points' images on the screen, plan mm.
    residuals_mm : ndarray (k, 2)
        plan − image, plan mm.
    hh : tuple (point (2,), direction (2,)) or None
        The principal horizontal found in this step (step "hh" only).
    hh_points : ndarray (j, 2)
        The crossings of corresponding lines it was drawn through.
    """

    name: str
    cycle: int
    state: TransformerState
    images_mm: np.ndarray
    residuals_mm: np.ndarray
    hh: tuple | None = None
    hh_points: np.ndarray | None = None

    @property
    def lengths_mm(self) -> np.ndarray:
        return np.hypot(*self.residuals_mm.T)

    @property
    def max_residual_mm(self) -> float:
        return float(np.max(self.lengths_mm))


#: the motions of one cycle (guide §12 step 3): what each does
STEP_NAMES = {
    "start": "the negative in the cassette, screen level, enlargement set from the scales",
    "centre": "the central point brought onto its place; the planchet turned to the image",
    "scale": "the enlargement changed until opposite corners miss by equal and opposite amounts",
    "hh": "the principal horizontal hh drawn through the crossings of corresponding lines",
    "turn": "cassette and planchet turned to put hh on the screen's axis of tilt",
    "tilt": "the screen tilted and the enlargement changed until the points fall on their places",
}


@dataclass(frozen=True)
class TransformerRun:
    """The whole sequence: every step's state and residuals.

    Attributes
    ----------
    steps : tuple of :class:`TransformerStep`
    tolerance_mm : float
    """

    steps: tuple
    tolerance_mm: float = TOLERANCE_MM

    @property
    def converged_step(self) -> int | None:
        """Index of the first step at the end of a cycle (a "tilt") with every residual within tolerance."""
        for k, s in enumerate(self.steps):
            if s.name == "tilt" and s.max_residual_mm <= self.tolerance_mm:
                return k
        return None

    @property
    def within_tolerance_step(self) -> int | None:
        """Index of the first step from which every residual stays within tolerance (this and all later steps);
        None if the last step is not within it.  Usually earlier than :attr:`converged_step`, which waits for
        the end of a cycle."""
        k = None
        for j in range(len(self.steps) - 1, -1, -1):
            if self.steps[j].max_residual_mm > self.tolerance_mm:
                break
            k = j
        return k

    def table(self) -> pd.DataFrame:
        """One row per step: cycle, step, ε, λ_t, θ, s, the largest residual and whether it is within 0.4 mm."""
        rows = [(k, s.cycle, s.name, s.state.eps_deg, s.state.tilt_dir_deg % 360.0, s.state.theta_deg, s.state.scale,
                 s.max_residual_mm, s.max_residual_mm <= self.tolerance_mm) for k, s in enumerate(self.steps)]
        return pd.DataFrame(rows, columns=["step", "cycle", "motion", "ε, °", "λ_t, °", "θ, °", "s", "max |d|, mm",
                                           "≤ 0.4 mm"]).set_index("step")


def _line_cross(p1, d1, p2, d2):
    den = d1[0] * d2[1] - d1[1] * d2[0]
    if abs(den) < 1e-15:
        return None
    s = ((p2 - p1)[0] * d2[1] - (p2 - p1)[1] * d2[0]) / den
    return p1 + s * d1


@V.checked(images_mm=V.points(2, min_points=2), plan_mm=V.points(2, min_points=2),
           min_angle_deg=V.number(0.0, 90.0, lo_open=True))
def principal_horizontal(images_mm, plan_mm, *, min_angle_deg: float = 0.05):
    """The guide's approximation of hh: the line through the crossings of corresponding lines (guide §12, fig. 20a).

    For every pair of points (i, j) the line through their images and the
    line through their places on the planchet are drawn; where they cross is
    (nearly) on the axis about which image and planchet differ by a tilt.
    Pairs whose lines meet at less than ``min_angle_deg`` are skipped.

    Returns ``(point, direction, crossings)`` — a point on hh, its unit
    direction and the crossings used (j, 2) — or None when fewer than two
    crossings are usable.
    """
    A = check_points("images_mm", images_mm)
    B = check_points("plan_mm", plan_mm)
    pts, wts = [], []
    for i in range(len(A)):
        for j in range(i + 1, len(A)):
            da, db = A[j] - A[i], B[j] - B[i]
            la, lb = np.hypot(*da), np.hypot(*db)
            if la == 0 or lb == 0:
                continue
            sin = abs(da[0] * db[1] - da[1] * db[0]) / (la * lb)
            if sin < math.sin(math.radians(min_angle_deg)):
                continue
            p = _line_cross(A[i], da / la, B[i], db / lb)
            if p is not None:
                pts.append(p)
                wts.append(sin)
    if len(pts) < 2:
        return None
    P = np.array(pts)
    w = np.array(wts) ** 2
    c = (w[:, None] * P).sum(axis=0) / w.sum()
    C = ((P - c) * w[:, None]).T @ (P - c)
    vals, vecs = np.linalg.eigh(C)
    d = vecs[:, -1]
    return c, d / np.hypot(*d), P


def _best_similarity_fixed_rotation(lev, plan, theta_deg, centre_index=None):
    """Least-squares scale and shift for a fixed turn θ: plan ≈ s·R(θ)·lev + t."""
    th = math.radians(theta_deg)
    c, s_ = math.cos(th), math.sin(th)
    rl = lev @ np.array([[c, s_], [-s_, c]])
    mr, mp = rl.mean(axis=0), plan.mean(axis=0)
    den = float(np.sum((rl - mr) ** 2))
    s = float(np.sum((rl - mr) * (plan - mp)) / den) if den > 0 else 1.0
    t = mp - s * mr
    return s, t


def _best_tilt(P, Q, f, st, tmax):
    """The screen tilt ε (with the best enlargement and shift for it) along ``st``'s direction: (ε, misfit)."""
    from scipy.optimize import minimize_scalar

    th = math.radians(st.theta_deg)
    rot = np.array([[math.cos(th), math.sin(th)], [-math.sin(th), math.cos(th)]])

    def misfit(eps):
        lv = _level(P, f, eps, st.tilt_dir_deg)
        s, t = _best_similarity_fixed_rotation(lv, Q, st.theta_deg)
        r = Q - (s * (lv @ rot) + t)
        return float(np.sum(r * r))

    opt = minimize_scalar(misfit, bounds=(-tmax, tmax), method="bounded", options={"xatol": 1e-7})
    return float(opt.x), float(opt.fun)


def _fine_turn(P, Q, f, st, tmax, span_deg: float = 20.0):
    """Turn the tilt's direction within ±``span_deg`` to where the best tilt matches the points best."""
    from scipy.optimize import minimize_scalar

    d0 = st.tilt_dir_deg
    opt = minimize_scalar(lambda d: _best_tilt(P, Q, f, replace(st, tilt_dir_deg=d0 + d), tmax)[1],
                          bounds=(-span_deg, span_deg), method="bounded", options={"xatol": 1e-3})
    if opt.fun < _best_tilt(P, Q, f, st, tmax)[1]:
        return replace(st, tilt_dir_deg=math.remainder(d0 + float(opt.x), 360.0))
    return st


def transformer_sequence(photo_mm, plan_mm, f_mm: float, *, centre_index: int = 0, start: TransformerState | None = None,
                         cycles: int = 3, tolerance_mm: float = TOLERANCE_MM, max_tilt_deg: float = 30.0) -> TransformerRun:
    """The photo transformer's sequence of motions (guide §12 step 3, figure 20), repeated ``cycles`` times.

    Parameters
    ----------
    photo_mm, plan_mm : array_like (k, 2), k ≥ 4
        The points on the photo (mm from the principal point) and their
        places on the base planchet (plan mm); one of them the central point.
    f_mm : float
        Focal length of the camera, mm.
    centre_index : int
        Which point is the central one (centred first).
    start : TransformerState, optional
        Where the operator starts; by default ε = 0, θ = 0, the enlargement of
        the least-squares similarity, centred.
    cycles : int
        Repetitions of the sequence (1…10); the sequence stops after the
        cycle in which every residual comes within ``tolerance_mm``.
    max_tilt_deg : float
        The transformer's largest screen tilt, degrees.

    Each motion changes only its own settings and chooses them as the
    operator would — by eye, i.e. here by least squares over the points:

    1. *centre*: shift so the central point falls on its place, turn the
       planchet (θ) to the image;
    2. *scale*: the enlargement about the central point;
    3. *hh*: :func:`principal_horizontal` through the crossings of corresponding lines;
    4. *turn*: the tilt acts along the perpendicular of hh (λ_t) — kept only
       if it matches the points better; in later cycles, when the misses
       are too small to draw hh well, the turn is refined by trial (±20°);
    5. *tilt*: the screen's tilt ε and, with it, the enlargement and the
       centring.
    """
    P = check_points("photo_mm", photo_mm, min_points=4)
    Q = check_points("plan_mm", plan_mm, min_points=4)
    if P.shape != Q.shape:
        raise ValueError(f"photo_mm has {len(P)} points and plan_mm {len(Q)}; give one plan place per photo point")
    f = check_positive("f_mm", f_mm, unit="mm", hi=2000.0)
    ci = check_int_range("centre_index", centre_index, 0, len(P) - 1)
    cycles = check_int_range("cycles", cycles, 1, 10)
    tol = check_positive("tolerance_mm", tolerance_mm, unit="mm", hi=100.0)
    tmax = check_range("max_tilt_deg", max_tilt_deg, 0.0, 45.0, lo_open=True, unit="°")
    if start is None:
        sim = plane.fit_similarity(P, Q, scale=True)
        st = TransformerState(0.0, 0.0, sim.rotation_deg, sim.scale, 0.0, 0.0)
        img = screen_image(st, P, f)
        st = replace(st, tx_mm=float(Q[ci, 0] - img[ci, 0]), ty_mm=float(Q[ci, 1] - img[ci, 1]))
    else:
        st = start
    steps = []

    def record(name, cycle, state, **kw):
        img = screen_image(state, P, f)
        steps.append(TransformerStep(name, cycle, state, img, Q - img, **kw))

    record("start", 0, st)
    for cyc in range(1, cycles + 1):
        # 1. centre and orient
        lev = _level(P, f, st.eps_deg, st.tilt_dir_deg)
        a = lev - lev[ci]
        b = Q - Q[ci]
        cc = float(np.sum(a[:, 0] * b[:, 0] + a[:, 1] * b[:, 1]))
        ss = float(np.sum(a[:, 0] * b[:, 1] - a[:, 1] * b[:, 0]))
        theta = math.degrees(math.atan2(ss, cc))
        st = replace(st, theta_deg=theta)
        img = screen_image(st, P, f)
        st = replace(st, tx_mm=st.tx_mm + float(Q[ci, 0] - img[ci, 0]), ty_mm=st.ty_mm + float(Q[ci, 1] - img[ci, 1]))
        record("centre", cyc, st)
        # 2. scale about the central point
        img = screen_image(st, P, f)
        a = img - Q[ci]
        den = float(np.sum(a * a))
        k = float(np.sum(a * (Q - Q[ci])) / den) if den > 0 else 1.0
        st = replace(st, scale=st.scale * k, tx_mm=float(Q[ci, 0] + k * (st.tx_mm - Q[ci, 0])),
                     ty_mm=float(Q[ci, 1] + k * (st.ty_mm - Q[ci, 1])))
        record("scale", cyc, st)
        # 3. the principal horizontal
        img = screen_image(st, P, f)
        hh = principal_horizontal(img, Q)
        record("hh", cyc, st, hh=None if hh is None else (hh[0], hh[1]),
               hh_points=None if hh is None else hh[2])
        # 4. turn: the tilt acts perpendicular to hh (hh's direction taken into the photo's frame); the operator
        #    keeps the turn only if tilting along it matches the points better than along the old direction
        #    (when the misses are already small, the crossings of nearly identical lines are unreliable)
        if hh is not None:
            phi = math.degrees(math.atan2(hh[1][1], hh[1][0]))
            new_dir = phi - st.theta_deg + 90.0
            # keep the current tilt's sense: the same tilt along the opposite direction is −ε
            if math.cos(math.radians(new_dir - st.tilt_dir_deg)) < 0:
                new_dir += 180.0
            cand = replace(st, tilt_dir_deg=math.remainder(new_dir, 360.0))
            if _best_tilt(P, Q, f, cand, tmax)[1] <= _best_tilt(P, Q, f, st, tmax)[1]:
                st = cand
        if cyc > 1:  # later cycles: the misses are too small to draw hh well — turn a little by trial
            st = _fine_turn(P, Q, f, st, tmax)
        record("turn", cyc, st)
        # 5. tilt the screen, rescale and re-centre
        eps, _ = _best_tilt(P, Q, f, st, tmax)
        lv = _level(P, f, eps, st.tilt_dir_deg)
        s, t = _best_similarity_fixed_rotation(lv, Q, st.theta_deg)
        st = replace(st, eps_deg=eps, scale=s, tx_mm=float(t[0]), ty_mm=float(t[1]))
        record("tilt", cyc, st)
        if steps[-1].max_residual_mm <= tol:
            break
    return TransformerRun(tuple(steps), tol)
