"""The plan-correction explorer: mutual projective grids on a new photo and an old plan (chapter 09, guide §10).

The model, :func:`plan_correction_model`, photographs a piece of farmland as
it is now (:func:`aerophoto.projective.land_use_scene`; flat ground) with a
tilted camera, picks four control points, builds the two grids with n cells
per side (by central directions or by proportional division) and carries
the changes — a farm, its road, a moved field boundary — from the photo onto
the old plan cell by cell; the truth is where the changes really are.
:class:`PlanCorrectionView` draws photo and plan side by side;
:class:`PlanCorrectionDemo` binds the sliders.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
import pandas as pd
from matplotlib.collections import LineCollection

from .. import geometry as g
from .. import plots
from ..i18n import t
from .. import projective as pj
from ..widgets import LiveDemo, Param

__all__ = ["PlanCorrectionResult", "plan_correction_model", "PlanCorrectionView", "PlanCorrectionDemo",
           "EXAMPLE_SEED", "plan_correction_figure", "grids_figure", "grid_node_misses", "similar_figures_transfer",
           "three_methods_study", "transfer_study_figure",
           "legend_html"]

#: the scene of the chapter's example (variants use seeds 0…99)
EXAMPLE_SEED = 2014
_C = plots.COLORS
#: the view's legend
_LEGEND = (
    (_C["black"], 1.0, "-", "the ground now (photo) / the old plan"),
    (_C["blue"], 0.8, "-", "grid cells"),
    (_C["vermillion"], 2.2, "-", "changes: on the photo / carried onto the plan"),
    (_C["truth"], 1.6, "--", "where the changes really are"),
)


@functools.lru_cache(maxsize=8)
def _scene(seed: int, size_m: float) -> pj.LandUseScene:
    return pj.land_use_scene(seed, size_m)


@dataclass(frozen=True)
class PlanCorrectionResult:
    """One state of the plan-correction explorer.

    Attributes
    ----------
    scene : LandUseScene
    camera, pose : the new photo's camera and orientation (flat ground Z = 0)
    M : float
        The plan's scale denominator.
    pair : :class:`aerophoto.projective.GridPair`
    photo_lines : list of (k, 2) arrays — the ground now, on the photo, mm
    photo_changes : list of (k, 2) arrays — the changes on the photo, mm
    plan_lines : list of (k, 2) arrays — the old plan, mm
    carried : list of (k, 2) arrays — the changes carried cell by cell, plan mm
    truth : list of (k, 2) arrays — where the changes belong, plan mm
    errors_mm : ndarray — |carried − truth| at every vertex, plan mm
    inside : ndarray of bool — which vertices lie inside the control quadrilateral
    grid_error_mm : float — the largest error of cell-by-cell transfer against the exact projective map,
        over an 8 × 8 lattice of points inside the four control points, plan mm
    """

    scene: pj.LandUseScene
    camera: g.Camera
    pose: g.Pose
    M: float
    pair: pj.GridPair
    photo_lines: list
    photo_changes: list
    plan_lines: list
    carried: list
    truth: list
    errors_mm: np.ndarray
    inside: np.ndarray
    grid_error_mm: float

    @property
    def max_error_mm(self) -> float:
        return float(np.max(self.errors_mm))

    def table(self) -> pd.DataFrame:
        e = self.errors_mm
        node = float(np.max(self.pair.node_error()))
        grid_err = self.grid_error_mm
        rows = [
            ("grid", "", f"{self.pair.n} × {self.pair.n}, {t(self.pair.method)}"),
            ("largest error of the carried changes", "mm on the plan", f"{e.max():.2f}"),
            ("… on the ground", "m", f"{e.max() * self.M / 1000:.1f}"),
            ("RMS error of the carried changes", "mm", f"{np.sqrt(np.mean(e**2)):.2f}"),
            ("… of those inside the four points", "mm",
             f"{np.sqrt(np.mean(e[self.inside] ** 2)):.2f}" if self.inside.any() else "—"),
            ("largest grid node off its image", "mm", f"{node:.2f}"),
            ("largest transfer error inside, this n", "mm", f"{grid_err:.3f}"),
            ("tilt α of the new photo", "°", f"{self.pose.alpha_deg:g}"),
        ]
        return pd.DataFrame(rows, columns=["quantity", "unit", "value"]).set_index("quantity")


def plan_correction_model(alpha_deg: float = 3.0, lambda_deg: float = -60.0, n: int = 4, spread_percent: float = 85.0,
                          method: str = "central", *, seed: int = EXAMPLE_SEED, f_mm: float = 100.0,
                          m: float = 12000.0, M: float = 10000.0, kappa_deg: float = 10.0,
                          size_m: float = 1600.0) -> PlanCorrectionResult:
    """Carry the changes of a scene from a tilted photo onto the old plan by mutual grids (guide §10).

    Parameters
    ----------
    alpha_deg, lambda_deg, kappa_deg : tilt α, direction λ of the principal vertical, heading κ of the new photo, °
    n : cells per side of the grids (1…64)
    spread_percent : how far out the four control points lie, % of the half-side (30…100)
    method : "central" (central directions) or "proportional" (proportional division)
    seed, size_m : the scene (the example's by default)
    f_mm, m : the camera and the photo scale 1:m (H = f·m over flat ground)
    M : the plan's scale denominator
    """
    scene = _scene(int(seed), float(size_m))
    cam = g.Camera(f_mm)
    pose = g.Pose(0.0, 0.0, g.flying_height_m(f_mm, m), alpha_deg, lambda_deg, kappa_deg)
    k = 1000.0 / M

    def photo(xy):
        return g.ground_to_photo(cam, pose, np.column_stack([xy, np.zeros(len(xy))]))

    cp = scene.control_points(spread_percent / 100.0)
    G = cp[["X_m", "Y_m"]].to_numpy()
    pair = pj.grid_pair(photo(G), G * k, n, method)
    photo_lines = [photo(f.outline_m()) for f in scene.features if f.status == "kept"]
    changes = scene.changes()
    photo_changes = [photo(f.outline_m()) for f in changes]
    plan_lines = [f.outline_m() * k for f in scene.old()]
    truth = [f.outline_m() * k for f in changes]
    allp = np.vstack(photo_changes)
    loc = pj.locate(pair.photo_nodes, allp)
    flat = pj.grids.place(pair.plan_nodes, loc)
    carried = np.split(flat, np.cumsum([len(p) for p in photo_changes])[:-1])
    err = np.hypot(*(flat - np.vstack(truth)).T)
    inside = loc["inside"].to_numpy()
    t = (np.arange(8) + 0.5) / 8
    U, V = np.meshgrid(t, t)
    probe = pj.unit_square_map(pair.photo_corners).apply(np.column_stack([U.ravel(), V.ravel()]))
    grid_err = float(np.max(np.hypot(*pair.transfer_error(probe).T)))
    return PlanCorrectionResult(scene, cam, pose, M, pair, photo_lines, photo_changes, plan_lines, carried, truth,
                                err, inside, grid_err)


def _grid_segments(nodes) -> list:
    segs = [nodes[j] for j in range(nodes.shape[0])] + [nodes[:, i] for i in range(nodes.shape[1])]
    return segs


class PlanCorrectionView:
    """New photo (left) and old plan (right) with their grids; ``update(result)`` moves the artists."""

    def __init__(self, ax=None):
        if ax is None:
            fig = plots.figure(figsize=(8.8, 4.6))
            ax_photo, ax_plan = fig.subplots(1, 2)
        else:
            ax_photo, ax_plan = ax
            fig = ax_photo.figure
        self.fig, self.ax_photo, self.ax_plan = fig, ax_photo, ax_plan
        for a, title, xl, yl in ((ax_photo, "New photo (tilted), mm", "x, mm", "y, mm"),
                                 (ax_plan, "Old plan 1:10 000, mm", "x (east), mm", "y (north), mm")):
            a.set_title(title)
            a.set_aspect("equal")
            a.set_xlabel(xl)
            a.set_ylabel(yl)
            a.grid(False)
        plots.photo_frame(ax_photo, g.Camera(), color=_C["grey"], lw=1.0)
        self.photo_lines = LineCollection([], colors=_C["black"], linewidths=0.8)
        self.photo_grid = LineCollection([], colors=_C["blue"], linewidths=0.7, alpha=0.8)
        self.photo_changes = LineCollection([], colors=_C["vermillion"], linewidths=2.2)
        self.plan_lines = LineCollection([], colors=_C["black"], linewidths=0.8)
        self.plan_grid = LineCollection([], colors=_C["blue"], linewidths=0.7, alpha=0.8)
        self.truth = LineCollection([], colors=_C["truth"], linewidths=1.6, linestyles="--")
        self.carried = LineCollection([], colors=_C["vermillion"], linewidths=2.2)
        for a, arts in ((ax_photo, (self.photo_lines, self.photo_grid, self.photo_changes)),
                        (ax_plan, (self.plan_lines, self.plan_grid, self.truth, self.carried))):
            for art in arts:
                a.add_collection(art)
        kw = dict(linestyle="none", marker="^", ms=10, mfc="none", mec=_C["control"], mew=2.2, zorder=6)
        (self.cp_photo,) = ax_photo.plot([], [], **kw)
        (self.cp_plan,) = ax_plan.plot([], [], **kw)
        self.labels = [[a.annotate(str(k + 1), (0, 0), xytext=(6, 4), textcoords="offset points",
                                   color=_C["control"], fontweight="bold", fontsize=11) for k in range(4)]
                       for a in (ax_photo, ax_plan)]
        ax_photo.set_xlim(-95, 95)
        ax_photo.set_ylim(-95, 95)

    def update(self, r: PlanCorrectionResult) -> None:
        self.photo_lines.set_segments(r.photo_lines)
        self.photo_changes.set_segments(r.photo_changes)
        self.photo_grid.set_segments(_grid_segments(r.pair.photo_nodes))
        self.plan_lines.set_segments(r.plan_lines)
        self.plan_grid.set_segments(_grid_segments(r.pair.plan_nodes))
        self.truth.set_segments(r.truth)
        self.carried.set_segments(r.carried)
        for art, P, labels in ((self.cp_photo, r.pair.photo_corners, self.labels[0]),
                               (self.cp_plan, r.pair.plan_corners, self.labels[1])):
            art.set_data(P[:, 0], P[:, 1])
            for t, p in zip(labels, P):
                t.xy = (p[0], p[1])
        h = r.scene.size_m / 2 * 1000.0 / r.M * 1.04
        self.ax_plan.set_xlim(-h, h)
        self.ax_plan.set_ylim(-h, h)


def legend_html() -> str:
    dash = {"-": "solid", "--": "dashed"}
    items = "".join(
        f"<div><span style='display:inline-block;width:28px;border-top:{max(2, lw * 1.5):.0f}px "
        f"{dash[ls]} {col};vertical-align:middle;margin-right:6px'></span>{t(lab)}</div>"
        for col, lw, ls, lab in _LEGEND)
    marks = f"<div><b style='color:{_C['control']}'>△ 1–4</b> {t('control (transformation) points')}</div>"
    return f"<div class='aerophoto-legend' style='font-size:13px;line-height:1.5;margin-bottom:6px'>{items}{marks}</div>"


class PlanCorrectionDemo(LiveDemo):
    """Carry a new photo's changes onto the old plan through mutual projective grids."""

    title = "Plan correction by mutual projective grids (guide §10)"
    hint = ("Tilt the new photo (α) and compare the two ways of drawing the grids: with central directions the "
            "carried changes (vermillion) sit on the truth (green) and get better as n grows; with proportional "
            "division they stay off however fine the grid.")
    params = (
        Param("alpha_deg", "α, °", 0.0, 15.0, 0.5, 3.0, group="New photo", help="tilt of the new photo"),
        Param("lambda_deg", "λ, °", -180.0, 180.0, 5.0, -60.0, group="New photo",
              help="direction of the principal vertical"),
        Param("n", "n (cells per side)", 1, 16, 1, 4, kind="int", group="Grids", help="cells per side of the grids"),
        Param("method", "grid drawn by", default="central", kind="choice", group="Grids",
              options=(("central directions", "central"), ("proportional division", "proportional"))),
        Param("spread_percent", "spread of 1–4, %", 40.0, 100.0, 5.0, 85.0, group="Grids",
              help="how far out the four control points lie"),
    )

    def build(self):
        self.view = PlanCorrectionView()
        self.fig = self.view.fig
        v = self.view
        # every slider moves the grids, the changes and the points on both sides (the old plan, too, is redrawn:
        # it lies under the carried changes); the frames, axes and titles stay in the cached background
        self.animated = (v.photo_lines, v.photo_grid, v.photo_changes, v.cp_photo, *v.labels[0],
                         v.plan_lines, v.plan_grid, v.truth, v.carried, v.cp_plan, *v.labels[1])
        plots.steady_limits(v.ax_plan, snap=False)  # the plan's limits are set again on every move: no change

    def compute(self, **v):
        return plan_correction_model(**v)

    def render(self, result):
        self.view.update(result)
        self.table.value = plots.html_table(result.table(), caption="Carried changes against the truth")
        self.legend.value = legend_html()


def _grid_pair_nodes(alpha_deg: float, n: int, lambda_deg: float):
    """The example's quadrilateral and, per method, (photo grid nodes, exact images of the plan grid's nodes)."""
    r = plan_correction_model(alpha_deg, lambda_deg, n, 85.0, "central")
    P, Q = r.pair.photo_corners, r.pair.plan_corners
    to_photo = r.pair.exact.inverse()
    return P, {method: (pj.grid(P, n, method), to_photo.apply(pj.grid(Q, n, method)))
               for method in ("central", "proportional")}


def grid_node_misses(alpha_deg: float = 10.0, n: int = 4, *, lambda_deg: float = -60.0) -> dict:
    """Largest miss, mm on the photo, between each method's grid on the new photo and the exact images of the
    plan's grid drawn the same way (guide §10): ``{"central": ~0, "proportional": …}``.

    The grid on the photo and the grid on the plan are drawn by the same method; the miss is how far the photo
    node is from the true image of its plan node.  Central directions are projectively exact (0 up to rounding);
    equal parts are not.  ``grids_figure``'s titles and chapter 09's text and alt text print these values.
    """
    _, pairs = _grid_pair_nodes(alpha_deg, n, lambda_deg)
    return {m: float(np.max(np.hypot(*(nodes - exact).reshape(-1, 2).T))) for m, (nodes, exact) in pairs.items()}


def grids_figure(alpha_deg: float = 10.0, n: int = 4, *, lambda_deg: float = -60.0):
    """The two ways of drawing the grid on the new photo's quadrilateral, each against the exact images of the
    plan's grid drawn the same way.

    Left: central directions — the grid lines run to the two centres where
    opposite sides meet, and the nodes coincide with the exact images of the
    plan's central grid (green).  Right: proportional division — equal parts
    of the sides on photo and plan; its nodes miss the exact images of the plan's
    equal-part nodes.  The titles print :func:`grid_node_misses`.
    """
    P, pairs = _grid_pair_nodes(alpha_deg, n, lambda_deg)
    misses = grid_node_misses(alpha_deg, n, lambda_deg=lambda_deg)
    fig = plots.figure(figsize=(9.6, 4.9))
    axes = fig.subplots(1, 2)
    for a, method, title in ((axes[0], "central", "central directions (exact)"),
                             (axes[1], "proportional", "proportional division (equal parts)")):
        nodes, exact_nodes = pairs[method]
        a.add_collection(LineCollection(_grid_segments(nodes), colors=_C["blue"], linewidths=1.0))
        a.plot(exact_nodes[..., 0].ravel(), exact_nodes[..., 1].ravel(), "o", mfc="none", mec=_C["truth"], ms=7,
               mew=1.6, label="images of the plan grid's nodes")
        a.plot(nodes[..., 0].ravel(), nodes[..., 1].ravel(), ".", color=_C["blue"], ms=5, label="grid nodes")
        a.plot(*np.vstack([P, P[:1]]).T, color=_C["control"], lw=2.0)
        if method == "central":  # the pencils: u-lines run to V_v, v-lines to V_u
            Vu, Vv = pj.vanishing_points(P)
            for V, ends in ((Vv, nodes[0, :]), (Vu, nodes[:, 0])):
                if abs(V[2]) > 1e-12 and np.hypot(*(V[:2] / V[2])) < 3000:
                    v = V[:2] / V[2]
                    for e in ends:
                        a.plot([v[0], e[0]], [v[1], e[1]], color=_C["grey"], lw=0.5, ls=":")
        a.set_title(f"{title}\nlargest node miss {misses[method]:.2f} mm")
        a.set_xlim(-95, 95)
        a.set_ylim(-95, 95)
        a.set_aspect("equal")
        a.set_xlabel("x, mm")
        a.grid(False)
    axes[0].set_ylabel("y, mm")
    axes[1].legend(loc="lower right", fontsize=9)
    return fig


def similar_figures_transfer(photo_corners, plan_corners, xy) -> np.ndarray:
    """The method of similar figures (способ подобных фигур, guide §10): carry photo points to the plan
    triangle by triangle, as if each triangle of the figure were similar (affine) to its image.

    The quadrilateral of the four control points is split by its diagonal 1–3 into two triangles; a point keeps its
    barycentric coordinates in its triangle.  ``photo_corners``, ``plan_corners`` (4, 2) mm, ``xy`` (k, 2) mm
    inside the photo quadrilateral; returns (k, 2) plan mm (NaN for a point outside both triangles).
    """
    P = np.asarray(photo_corners, float)
    Q = np.asarray(plan_corners, float)
    pts = np.atleast_2d(np.asarray(xy, float))
    out = np.full_like(pts, np.nan)
    for tri in ((0, 1, 2), (0, 2, 3)):
        A = np.column_stack([P[list(tri)], np.ones(3)])
        lam = np.linalg.solve(A.T, np.column_stack([pts, np.ones(len(pts))]).T).T  # barycentric, (k, 3)
        inside = np.all(lam >= -1e-9, axis=1) & np.isnan(out[:, 0])
        out[inside] = lam[inside] @ Q[list(tri)]
    return out


def three_methods_study(alphas=(1.0, 3.0, 8.0), n: int = 4, *, lambda_deg: float = -60.0) -> pd.DataFrame:
    """Largest transfer error on the plan, mm, of the guide's three ways of §10 over the example's quadrilateral
    (625 points inside it): similar figures (two triangles), proportional division and central directions with
    ``n`` cells per side, for each tilt α in ``alphas`` (°)."""
    u, w = np.meshgrid(np.linspace(0.02, 0.98, 25), np.linspace(0.02, 0.98, 25))
    rows = []
    for alpha in alphas:
        r = plan_correction_model(alpha, lambda_deg, n, 85.0, "central")
        P, Q = r.pair.photo_corners, r.pair.plan_corners
        xy = (((1 - u) * (1 - w))[..., None] * P[0] + (u * (1 - w))[..., None] * P[1] + (u * w)[..., None] * P[2]
              + ((1 - u) * w)[..., None] * P[3]).reshape(-1, 2)
        exact = r.pair.exact.apply(xy)
        prop = plan_correction_model(alpha, lambda_deg, n, 85.0, "proportional").pair.transfer(xy)
        err = lambda a: float(np.max(np.hypot(*(a - exact).T)))  # noqa: E731
        rows.append((alpha, err(similar_figures_transfer(P, Q, xy)), err(prop), err(r.pair.transfer(xy))))
    return pd.DataFrame(rows, columns=["α, °", "similar figures (2 triangles), mm",
                                       f"proportional division, n = {n}, mm",
                                       f"central directions, n = {n}, mm"]).set_index("α, °")


def transfer_study_figure(alphas=(1.0, 3.0, 8.0), ns=(1, 2, 4, 8, 16, 32)):
    """The error of cell-by-cell transfer against the exact map as the grid is refined, for a few tilts (log scales)."""
    fig, ax = plots.new_axes(None, figsize=(7.2, 4.4))
    colors = (_C["blue"], _C["orange"], _C["vermillion"])
    for a_deg, col in zip(alphas, colors):
        r = plan_correction_model(a_deg, -60.0, 1, 85.0, "central")
        st = pj.transfer_study(r.pair.photo_corners, r.pair.plan_corners, ns=ns, n_points=200)
        ax.loglog(st.index, st["central max, mm"], "o-", color=col, label=f"central directions, α = {a_deg:g}°")
        ax.loglog(st.index, st["proportional max, mm"], "s--", color=col, label=f"proportional division, α = {a_deg:g}°")
    ax.set_xlabel("cells per side n")
    ax.set_ylabel("largest transfer error, mm on the plan")
    ax.set_title("Transfer cell by cell against the exact projective map")
    ax.legend(fontsize=8, loc="lower left")
    return fig


def plan_correction_figure(result: PlanCorrectionResult | None = None):
    """A static figure of the explorer's state (for a notebook), default: the example at α = 3°."""
    view = PlanCorrectionView()
    view.update(result if result is not None else plan_correction_model())
    view.fig.legend(handles=[plots_line(c, lw, ls, lab) for c, lw, ls, lab in _LEGEND], loc="outside lower center",
                    ncol=2, fontsize=9)
    return view.fig


def plots_line(color, lw, ls, label):
    from matplotlib.lines import Line2D

    return Line2D([], [], color=color, lw=lw, ls=ls, label=label)
