"""Live bundle block adjustment: the control layout, the measuring error and a blunder (chapter 15, article 002).

A small block of the mountain site (3 strips × 4 photos at 1:15 000, f = 200 mm, the article's camera and scale;
:func:`aerophoto.labs.ch15.survey_block`) is adjusted by the bundle method, linearised at the truth
(:func:`block_model`): with the design matrix A of the collinearity equations and of the control points'
coordinate observations, weights 1/σ², the corrections are dx = Q·AᵀP·ℓ with Q = (AᵀPA)⁻¹, the residuals
v = A·dx − ℓ, the redundancy numbers r = 1 − diag(A·Q·AᵀP) and Baarda's standardised residuals w = v/(σ√r)
(:mod:`aerophoto.bundle`, chapter 15).  For the linearised block this *is* the adjustment (one Gauss–Newton
step from the truth); the measurements ℓ are seeded noise plus, when switched on, one image blunder.

σ scales every a priori error together — the photo coordinates (σ), the gravimetric marks (6σ) and the control
points (0.5 m at σ = 5 µm) — so Q ∝ σ², the gain Q·AᵀP and the redundancy numbers do not change with σ, and a
move of σ costs a few vector operations.  What σ does change is how a blunder of fixed size stands out: its
w falls as 1/σ.  A change of the control layout refactors the block (about a second the first time, then
cached): the slider then shows a preview of the previous layout and the full result when it rests.

:class:`BlockAdjustmentView` draws the block (photo centres, control, check and gravimetric points; the error
ellipses of the gravimetric points and the true errors of the check points, magnified) and every observation's
|w| against the critical value; :class:`BlockAdjustmentDemo` binds the sliders to it.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
import pandas as pd
from matplotlib.collections import LineCollection

from .. import bundle as B
from .. import plots
from ..widgets import LiveDemo, Param

__all__ = ["LAYOUTS", "BLOCK_SEED", "CRITICAL_W", "BlockModel", "block_model", "AdjustmentResult", "adjust_live",
           "BlockAdjustmentView", "BlockAdjustmentDemo"]

#: the seed of the demo's block and of its measuring errors (not a student's variant)
BLOCK_SEED = 2002
#: the critical |w| of data snooping (as :func:`aerophoto.bundle.data_snooping`)
CRITICAL_W = 4.0
#: control layouts: name → which of the block's nine control points stay control (the rest become check points)
LAYOUTS = {"nine": "corners, sides and centre (9)", "perimeter": "corners and sides (8)",
           "corners": "four corners (4)", "three": "three corners (3)"}
#: σ of the demo's opening state, µm, and the ratios of the other a priori errors to it
SIGMA_REF_UM = 5.0
_FIELD_RATIO = 6.0               # gravimetric marks: 30 µm at 5 µm
_CONTROL_M_PER_UM = 0.5 / 5.0    # control: 0.5 m at 5 µm
#: the ellipses and error arrows on the map are magnified by this factor
MAGNIFY = 400.0

_C = plots.COLORS


@functools.lru_cache(maxsize=1)
def _block():
    """The demo's block (geometry and truth; its own measurements are simulated here)."""
    from ..labs import ch15

    return ch15.survey_block(15_000.0, 3, 4, seed=BLOCK_SEED, blunder_size_mm=0.0, control_dz_m=0.0, n_field=5)


def _control_roles(meas, truth):
    """Indices of the nine control points: (corners, sides, centre) by their distance from the block's middle."""
    ci = np.flatnonzero(meas.point_kind == "control")
    xy = truth[ci, :2]
    d = np.hypot(*(xy - xy.mean(axis=0)).T)
    order = ci[np.argsort(d)]
    centre, sides, corners = order[:1], order[1:len(order) - 4], order[len(order) - 4:]
    return corners, sides, centre


@dataclass(frozen=True, eq=False)
class BlockModel:
    """The linearised bundle adjustment of the demo's block for one control layout, at σ = 1 µm.

    Attributes
    ----------
    layout : key of :data:`LAYOUTS`
    kind : (P,) point kinds in this layout ("tie", "control", "check", "field")
    gain : (U, L) Q·AᵀP — corrections of the unknowns per unit of observation misclosure (σ-free)
    A : (L, U) the design matrix (sparse, CSR): residuals v = A·dx − ℓ
    r : (L,) redundancy numbers
    sigma1 : (L,) a priori σ of every observation at σ = 1 µm (mm for images, m for control)
    cov1 : (P, 3, 3) covariance of every point at σ = 1 µm, m²
    n_img : number of image observations (rows 2k, 2k + 1 are observation k)
    ctrl_points : (C,) point indices of the control rows (3 rows each, after the image rows)
    """

    layout: str
    kind: np.ndarray
    gain: np.ndarray
    A: object
    r: np.ndarray
    sigma1: np.ndarray
    cov1: np.ndarray
    n_img: int
    ctrl_points: np.ndarray


#: the factorised layouts, layout → :class:`BlockModel` (filled on first use)
_MODELS: dict = {}


def block_model(layout: str = "nine") -> BlockModel:
    """The linearised adjustment of the demo's block with control ``layout`` (see the module notes); cached."""
    if layout not in LAYOUTS:
        raise ValueError(f"layout = {layout!r} is not one of the valid choices {list(LAYOUTS)}")
    if layout in _MODELS:
        return _MODELS[layout]
    sv = _block()
    m, eo, X = sv.meas, sv.eo_true, sv.truth_m
    corners, sides, centre = _control_roles(m, X)
    keep = {"nine": np.r_[corners, sides, centre], "perimeter": np.r_[corners, sides], "corners": corners,
            "three": corners[:3]}[layout]
    kind = m.point_kind.copy()
    kind[(kind == "control")] = "check"
    kind[keep] = "control"
    # a point seen on fewer than two photos is not determined without its control coordinates: out of the block
    # (its three unknowns get a weak prior, 10 km, that keeps the normal matrix regular and changes nothing else)
    seen = np.bincount(m.obs_point, minlength=m.n_points)
    loose = (seen < 2) & (kind != "control")
    kind[loose] = "unused"
    _, de, dp = B.project_jacobian(eo[m.obs_photo], X[m.obs_point], m.f_mm)
    n_obs, n_ph = len(m.obs_photo), m.n_photos
    n_unk = 6 * n_ph + 3 * m.n_points
    A = np.zeros((2 * n_obs + 3 * len(keep), n_unk))
    rows = np.arange(n_obs)
    for c in range(2):
        A[(2 * rows + c)[:, None], 6 * m.obs_photo[:, None] + np.arange(6)] = de[:, c, :]
        A[(2 * rows + c)[:, None], 6 * n_ph + 3 * m.obs_point[:, None] + np.arange(3)] = dp[:, c, :]
    ctrl_rows = 2 * n_obs + np.arange(3 * len(keep))
    A[ctrl_rows, (6 * n_ph + 3 * keep[:, None] + np.arange(3)).ravel()] = 1.0
    s_img = np.where(kind[m.obs_point] == "field", _FIELD_RATIO, 1.0) * 1e-3  # mm at σ = 1 µm
    sigma1 = np.r_[np.repeat(s_img, 2), np.full(3 * len(keep), _CONTROL_M_PER_UM)]
    Aw = A / sigma1[:, None]
    N = Aw.T @ Aw
    for p in np.flatnonzero(loose):
        i = 6 * n_ph + 3 * p
        N[i:i + 3, i:i + 3] += np.eye(3) / (1e4 / _CONTROL_M_PER_UM) ** 2
    Q = np.linalg.inv(N)
    gain = (Q @ Aw.T) / sigma1[None, :]                                  # Q·AᵀP
    r = np.clip(1.0 - np.einsum("ij,ji->i", A, gain), 0.0, 1.0)          # 1 − diag(A·Q·AᵀP)
    idx = 6 * n_ph + 3 * np.arange(m.n_points)
    cov1 = np.stack([Q[np.ix_(i + np.arange(3), i + np.arange(3))] for i in idx])
    from scipy.sparse import csr_matrix

    _MODELS[layout] = BlockModel(layout, kind, np.ascontiguousarray(gain), csr_matrix(A), r, sigma1, cov1, n_obs, keep)
    return _MODELS[layout]


@functools.lru_cache(maxsize=1)
def _noise_and_blunder():
    """The seeded unit noise of every observation (image rows, then up to nine control points × 3) and the
    image observation that carries the blunder (a tie point seen on ≥ 3 photos, redundancy ≥ 0.4 with all nine
    control points), with the blunder's direction."""
    sv = _block()
    m = sv.meas
    rng = np.random.default_rng([BLOCK_SEED, 15, 3])
    z_img = rng.standard_normal(2 * len(m.obs_photo))
    z_ctrl = rng.standard_normal((m.n_points, 3))
    M = block_model("nine")
    per = np.bincount(m.obs_point, minlength=m.n_points)
    r_obs = np.minimum(M.r[0:2 * M.n_img:2], M.r[1:2 * M.n_img:2])
    ok = np.flatnonzero((M.kind[m.obs_point] == "tie") & (per[m.obs_point] >= 3) & (r_obs >= 0.4))
    k = int(rng.choice(ok))
    ang = rng.uniform(0.0, 2.0 * np.pi)
    return z_img, z_ctrl, k, np.array([np.cos(ang), np.sin(ang)])


@dataclass(frozen=True)
class AdjustmentResult:
    """One state of the demo: the adjusted block's errors, its precision and data snooping's verdict.

    Attributes
    ----------
    layout, sigma_um, blunder_mm : the sliders' values (blunder 0: off)
    xyz_err_m : (P, 3) adjusted − true coordinates of every point, m
    cov_m2 : (P, 3, 3) a priori covariances at this σ, m²
    kind : (P,) point kinds in this layout
    xy_m : (P, 2) true plan positions, m; centres_m : (n, 2) photo centres, m
    w : (L,) standardised residuals, image rows as |w| of the point (x and y), control rows per coordinate
    w_kind : (L,) "image" or "control"
    flagged : index into ``w`` of the largest |w| if it exceeds the critical value, else −1
    blunder_row : index into ``w`` of the blundered observation (−1: no blunder)
    check_rms_m : {"plan", "Z"} RMS true errors of the check points; predicted_rms_m : the same from the covariances
    """

    layout: str
    sigma_um: float
    blunder_mm: float
    xyz_err_m: np.ndarray
    cov_m2: np.ndarray
    kind: np.ndarray
    xy_m: np.ndarray
    centres_m: np.ndarray
    w: np.ndarray
    w_kind: np.ndarray
    flagged: int
    blunder_row: int
    check_rms_m: dict
    predicted_rms_m: dict
    field_axes_m: np.ndarray

    @property
    def verdict(self) -> str:
        if self.flagged < 0:
            if self.blunder_row >= 0:
                return "no |w| above the critical value: the blunder passes unseen"
            return "no |w| above the critical value: no blunder found"
        if self.flagged == self.blunder_row:
            return "the largest |w| is the planted blunder: rejected"
        return "the largest |w| is a good observation: a false alarm"

    def table(self) -> pd.DataFrame:
        wmax = float(np.max(self.w)) if len(self.w) else 0.0
        wb = float(self.w[self.blunder_row]) if self.blunder_row >= 0 else float("nan")
        from ..i18n import t

        rows = [("data snooping", "", t(self.verdict)),
                ("largest |w| (critical 4.0)", "", f"{wmax:.1f}"),
                ("|w| of the blundered observation", "", "—" if np.isnan(wb) else f"{wb:.1f}"),
                ("check points, plan RMS (true)", "m", f"{self.check_rms_m['plan']:.2f}"),
                ("… predicted by the covariances", "m", f"{self.predicted_rms_m['plan']:.2f}"),
                ("check points, height RMS (true)", "m", f"{self.check_rms_m['Z']:.2f}"),
                ("… predicted by the covariances", "m", f"{self.predicted_rms_m['Z']:.2f}"),
                ("gravimetric points, largest semi-axis a", "m", f"{np.max(self.field_axes_m[:, 0]):.2f}")]
        return pd.DataFrame(rows, columns=["quantity", "unit", "value"]).set_index("quantity")


@functools.lru_cache(maxsize=1)
def _crit_img() -> float:
    return B.image_critical(CRITICAL_W)


def adjust_live(layout: str = "nine", sigma_um: float = SIGMA_REF_UM, blunder_mm: float = 0.1) -> AdjustmentResult:
    """The demo's block adjusted with control ``layout``, image σ ``sigma_um`` (µm; 1–30) and one image blunder of
    ``blunder_mm`` (mm on the photo; 0 = none) — see the module notes."""
    from .._validate import check_range

    s = check_range("sigma_um", sigma_um, 1.0, 30.0, unit="µm")
    b = check_range("blunder_mm", blunder_mm, 0.0, 1.0, unit="mm")
    M = block_model(layout)
    sv = _block()
    m = sv.meas
    z_img, z_ctrl, k_bl, direction = _noise_and_blunder()
    # the misclosures ℓ = measured − true: seeded noise at this σ, the blunder added to its observation
    ell = np.r_[z_img * M.sigma1[:2 * M.n_img] * s, (z_ctrl[M.ctrl_points] * _CONTROL_M_PER_UM * s).ravel()]
    if b > 0:
        ell[2 * k_bl:2 * k_bl + 2] += b * direction
    dx = M.gain @ ell
    v = M.A @ dx - ell
    sig = M.sigma1 * s
    with np.errstate(divide="ignore", invalid="ignore"):
        w_all = np.where(M.r > 1e-9, v / (sig * np.sqrt(M.r)), 0.0)
    # an image point is judged by √(w_x² + w_y²) on the same false-alarm rate as a single w (data snooping)
    crit_img = _crit_img()
    w_img = np.hypot(w_all[0:2 * M.n_img:2], w_all[1:2 * M.n_img:2]) * (CRITICAL_W / crit_img)
    w_ctl = np.abs(w_all[2 * M.n_img:])
    w = np.r_[w_img, w_ctl]
    w_kind = np.r_[np.full(len(w_img), "image", dtype=object), np.full(len(w_ctl), "control", dtype=object)]
    i = int(np.argmax(w))
    flagged = i if w[i] > CRITICAL_W else -1
    n_ph = m.n_photos
    err = dx[6 * n_ph:].reshape(-1, 3)
    cov = M.cov1 * s * s
    chk = M.kind == "check"
    check_rms = {"plan": float(np.sqrt(np.mean(err[chk, 0] ** 2 + err[chk, 1] ** 2))),
                 "Z": float(np.sqrt(np.mean(err[chk, 2] ** 2)))}
    pred = {"plan": float(np.sqrt(np.mean(cov[chk, 0, 0] + cov[chk, 1, 1]))),
            "Z": float(np.sqrt(np.mean(cov[chk, 2, 2])))}
    fld = np.flatnonzero(M.kind == "field")
    axes = np.array([B.error_ellipse(cov[p, :2, :2]) for p in fld])
    return AdjustmentResult(layout, s, b, err, cov, M.kind, sv.truth_m[:, :2], sv.eo_true[:, :2], w, w_kind, flagged,
                            k_bl if b > 0 else -1, check_rms, pred, axes)


def _ellipse_polyline(centres, axes, scale, n=48):
    """Ellipses (a, b, θ°) at ``centres`` as one polyline with NaN breaks, magnified by ``scale``."""
    t = np.linspace(0.0, 2.0 * np.pi, n)
    out = []
    for (x, y), (a, b, th) in zip(centres, axes):
        c, s = np.cos(np.radians(th)), np.sin(np.radians(th))
        ex, ey = a * scale * np.cos(t), b * scale * np.sin(t)
        out.append(np.column_stack([x + c * ex - s * ey, y + s * ex + c * ey]))
        out.append([[np.nan, np.nan]])
    return np.vstack(out) if out else np.zeros((0, 2))


class BlockAdjustmentView:
    """Left: the block — photo centres, control (triangles), check points with their true plan errors (arrows) and
    gravimetric points with their standard error ellipses, both magnified; the flagged observation's point ringed.
    Right: every observation's |w|, sorted, against the critical value."""

    def __init__(self, ax=None):
        if ax is None:
            self.fig = plots.figure(figsize=(9.0, 4.4))
            self.ax_map, self.ax_w = self.fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.35, 1.0]})
        else:
            self.ax_map, self.ax_w = ax
            self.fig = self.ax_map.figure
        a = self.ax_map
        sv = _block()
        xy, cen = sv.truth_m[:, :2] / 1000.0, sv.eo_true[:, :2] / 1000.0
        # black, not grey: grey sat too close to the green ellipses with deuteranopia (tests/presentation/test_colours)
        a.plot(cen[:, 0], cen[:, 1], "+", color=_C["black"], ms=8, label="photo centres")
        (self.ties,) = a.plot([], [], ".", color=_C["black"], ms=3, label="tie points")
        (self.ctrl,) = a.plot([], [], "^", color=_C["control"], ms=9, label="control")
        (self.check,) = a.plot([], [], "o", mfc="none", mec=_C["blue"], ms=4, label="check points")
        self.arrows = LineCollection([], colors=_C["vermillion"], linewidths=1.2, label=f"true error × {MAGNIFY:g}")
        a.add_collection(self.arrows)
        (self.field,) = a.plot([], [], "*", color=_C["truth"], ms=11, label="gravimetric points")
        (self.ellipses,) = a.plot([], [], "-", color=_C["truth"], lw=1.3, label=f"standard ellipse × {MAGNIFY:g}")
        (self.flag,) = a.plot([], [], "o", mfc="none", mec=_C["vermillion"], ms=18, mew=2.0, label="flagged")
        pad = 1.0
        a.set_xlim(xy[:, 0].min() - pad, xy[:, 0].max() + pad)
        a.set_ylim(xy[:, 1].min() - pad, xy[:, 1].max() + pad)
        a.set_aspect("equal")
        a.set_xlabel("X, km")
        a.set_ylabel("Y, km")
        a.set_title("The adjusted block")
        b = self.ax_w
        (self.w_img,) = b.plot([], [], ".", color=_C["blue"], ms=4, label="image observations")
        (self.w_ctl,) = b.plot([], [], "s", color=_C["control"], ms=5, label="control coordinates")
        (self.w_bl,) = b.plot([], [], "o", mfc="none", mec=_C["vermillion"], ms=12, mew=2.0, label="the blunder")
        b.axhline(CRITICAL_W, color=_C["vermillion"], ls="--", lw=1.2, label="critical |w| = 4")
        b.set_yscale("log")
        b.set_ylim(0.01, 200.0)
        b.set_xlim(0, len(sv.meas.obs_photo) + 3 * 9 + 5)
        b.set_xlabel("observations, sorted by |w|")
        b.set_ylabel("|w|")
        b.set_title("Data snooping: standardised residuals")
        a.legend(loc="upper left", fontsize=8)
        b.legend(loc="upper left", fontsize=8)
        plots.steady_limits(a, snap=False)
        plots.steady_limits(b, snap=False)

    def update(self, r: AdjustmentResult) -> None:
        xy = r.xy_m / 1000.0
        for art, k in ((self.ties, "tie"), (self.ctrl, "control"), (self.check, "check"), (self.field, "field")):
            sel = r.kind == k
            art.set_data(xy[sel, 0], xy[sel, 1])
        chk = np.flatnonzero(r.kind == "check")
        tips = xy[chk] + r.xyz_err_m[chk, :2] * MAGNIFY / 1000.0
        self.arrows.set_segments(np.stack([xy[chk], tips], axis=1))
        fld = np.flatnonzero(r.kind == "field")
        poly = _ellipse_polyline(xy[fld], r.field_axes_m, MAGNIFY / 1000.0)
        self.ellipses.set_data(poly[:, 0], poly[:, 1]) if len(poly) else self.ellipses.set_data([], [])
        sv = _block()
        m = sv.meas
        if r.flagged >= 0:
            n_img = int(np.sum(r.w_kind == "image"))
            p = m.obs_point[r.flagged] if r.flagged < n_img else block_model(r.layout).ctrl_points[(r.flagged - n_img) // 3]
            self.flag.set_data([xy[p, 0]], [xy[p, 1]])
        else:
            self.flag.set_data([], [])
        order = np.argsort(r.w)
        ws = np.maximum(r.w[order], 0.011)
        x = np.arange(len(ws))
        img = r.w_kind[order] == "image"
        self.w_img.set_data(x[img], ws[img])
        self.w_ctl.set_data(x[~img], ws[~img])
        if r.blunder_row >= 0:
            pos = int(np.flatnonzero(order == r.blunder_row)[0])
            self.w_bl.set_data([pos], [ws[pos]])
        else:
            self.w_bl.set_data([], [])


class BlockAdjustmentDemo(LiveDemo):
    """Live: a bundle block adjustment with its control layout, measuring error and a planted image blunder."""

    title = "Bundle block adjustment: control, σ and a blunder"
    hint = ("Switch the blunder on and off, then raise σ: the same 0.1 mm blunder stands out at a few µm and hides "
            "in the noise at 30 µm. Take the control down to three corners: the ellipses and the check points' "
            "errors swell, most in height.")
    params = (
        Param("layout", "control layout", kind="choice", default="nine", group="Control",
              options=tuple((label, key) for key, label in LAYOUTS.items()),
              help="control points kept; the others become check points"),
        Param("sigma_um", "σ, µm", 1.0, 30.0, 1.0, SIGMA_REF_UM, group="Measuring",
              help="RMS error of a photo coordinate; the gravimetric marks 6σ, the control 0.1 m per µm"),
        Param("blunder", "blunder", kind="choice", default="on", group="Blunder",
              options=(("on", "on"), ("off", "off")), help="one image measurement moved on the photo"),
        Param("blunder_mm", "blunder, mm", 0.02, 0.5, 0.01, 0.1, group="Blunder",
              help="length of the image blunder on the photo"),
    )

    def build(self):
        block_model("nine")  # the heavy part of the opening layout once
        self.view = BlockAdjustmentView()
        self.fig = self.view.fig
        v = self.view
        self.animated = (v.ties, v.ctrl, v.check, v.arrows, v.field, v.ellipses, v.flag, v.w_img, v.w_ctl, v.w_bl)

    def compute(self, layout, sigma_um, blunder, blunder_mm):
        if self._preview and layout not in _MODELS and getattr(self, "result", None) is not None:
            return self.result  # the new layout is being factorised: keep the picture until it is
        return adjust_live(layout, sigma_um, blunder_mm if blunder == "on" else 0.0)

    def render(self, result):
        self.view.update(result)
        self.table.value = plots.html_table(result.table(), caption="The adjusted block")

    def on_slider(self) -> str:
        if self.values["layout"] in _cached_layouts():
            self.update()
            return ""
        return self.preview_then_full(0.05, note="adjusting the block for the new control layout…")


def _cached_layouts() -> set:
    """The layouts whose adjustment is factorised already (a move to them is instant)."""
    return set(_MODELS)
