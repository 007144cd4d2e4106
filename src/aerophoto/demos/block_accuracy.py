"""The error map of a block: control layout and measuring error against the predicted errors (chapter 14).

The pure part, :func:`block_geometry` and :func:`block_map`, flies a block of
vertical photos over the virtual site (1:5000, f = 100 mm, 12 bases per strip)
and propagates the covariance of its bundle adjustment
(:func:`aerophoto.accuracy.block_precision`) for a control layout; the
predicted errors are linear in the image error σ, so a σ slider only rescales
them.  :class:`BlockErrorView` draws the map (points coloured by the predicted
plan or height error, control triangles) and the profile along the strips;
:class:`BlockErrorDemo` binds the sliders.  Every (strips, spacing, layout)
combination is computed once and kept, so a slider move costs a look-up and
moving the artists.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import accuracy as acc
from .. import bundle as B
from .. import geometry as g
from .. import plots, simulate
from .. import site as _site
from ..i18n import t
from ..widgets import LiveDemo, Param

__all__ = ["F_MM", "M", "N_PHOTOS", "SPACINGS", "block_geometry", "block_map", "BlockMap", "BlockErrorView",
           "BlockErrorDemo"]

#: the demo's block: f = 100 mm at 1:5000, 13 photos (12 bases) per strip, p_x = 60 %, p_y = 30 %
F_MM, M, N_PHOTOS = 100.0, 5000.0, 13
#: the control spacings the demo offers, bases
SPACINGS = (2, 3, 4, 6, 12)
#: the colour scale's top, m (fixed, so that the map brightens as σ grows)
VMAX_M = {"plan": 0.25, "height": 0.45}


@functools.lru_cache(maxsize=8)
def block_geometry(n_strips: int):
    """(camera, poses, photo_strip, photo_order, standard points) of the demo block with ``n_strips`` strips."""
    st = _site.get_site()
    cam = g.Camera(F_MM)
    bl = simulate.block_over_site(st, cam, M, 60.0, 30.0, N_PHOTOS, int(n_strips))
    poses = tuple(s.pose for s in bl.shots)
    pts = B.standard_points(cam, poses, st)
    return cam, poses, np.array([s.strip for s in bl.shots]), np.array([s.index for s in bl.shots]), pts


@dataclass(frozen=True, eq=False)
class BlockMap:
    """What the view shows: the block's predicted errors at an image error σ.

    Attributes
    ----------
    precision : :class:`aerophoto.accuracy.BlockPrecision` at ``sigma_um``
    n_strips, every : int
    layout : str
    sigma_um : float
    profile_x_m : (k,) along-strip positions of the photo centres, m (from the block's start)
    profile_plan_m, profile_Z_m : (k,) largest predicted plan / height error across the block at each
        position, m
    """

    precision: acc.BlockPrecision
    n_strips: int
    every: int
    layout: str
    sigma_um: float
    profile_x_m: np.ndarray
    profile_plan_m: np.ndarray
    profile_Z_m: np.ndarray

    def table(self) -> pd.DataFrame:
        s = self.precision.summary()
        rows = [("plan RMS", s["plan RMS, m"] * 100), ("plan largest", s["plan max, m"] * 100),
                ("height RMS", s["height RMS, m"] * 100), ("height largest", s["height max, m"] * 100),
                ("σ on the ground = σ·m", self.sigma_um / 1000.0 * M / 10.0)]
        return pd.DataFrame(rows, columns=["predicted error", "cm"]).set_index("predicted error")


@functools.lru_cache(maxsize=64)
def _unit_map(n_strips: int, every: int, layout: str):
    cam, poses, strip, order, pts = block_geometry(n_strips)
    bp = acc.block_precision(cam, poses, strip, order, _site.get_site(), every=int(every), layout=layout,
                             sigma_mm=0.001, points_m=pts)
    X0 = float(min(p.X_m for p in poses))
    xs = np.array([p.X_m for p in poses[:N_PHOTOS]]) - X0
    # largest error across the block in each photo's stretch of ground
    xp = bp.XYZ_m[:, 0] - X0
    bins = np.clip(np.rint(xp / (xs[1] - xs[0])).astype(int), 0, N_PHOTOS - 1)
    tie = bp.kind != "control"
    plan = np.array([bp.sigma_plan_m[tie & (bins == k)].max(initial=0.0) for k in range(N_PHOTOS)])
    Z = np.array([bp.sigma_Z_m[tie & (bins == k)].max(initial=0.0) for k in range(N_PHOTOS)])
    return bp, xs, plan, Z


def block_map(n_strips: int = 3, every: int = 4, layout: str = "rows", sigma_um: float = 7.0) -> BlockMap:
    """The demo block's predicted errors (computed once per strips/spacing/layout, then scaled by σ)."""
    bp, xs, plan, Z = _unit_map(int(n_strips), int(every), str(layout))
    k = float(sigma_um)  # the unit map is for σ = 1 µm
    return BlockMap(bp.scaled(k / 1000.0), int(n_strips), int(every), str(layout), k, xs, plan * k, Z * k)


class BlockErrorView:
    """Map of the block coloured by the predicted error (left) and its profile along the strips (right)."""

    def __init__(self, result: BlockMap | None = None, ax=None, *, quantity: str = "plan"):
        if ax is None:
            # placed by hand, not by a layout engine: the engine, run once at the first draw (plots.freeze_layout),
            # squeezed the map, cut its title and pushed the profile off the right edge
            fig = plots.figure(figsize=(8.8, 4.0), layout="none")
            ax_map = fig.add_axes([0.075, 0.13, 0.50, 0.76])
            ax_prof = fig.add_axes([0.775, 0.13, 0.205, 0.76])
        else:
            ax_map, ax_prof = ax
            fig = ax_map.figure
        self.fig, self.ax_map, self.ax_prof = fig, ax_map, ax_prof
        self.quantity = quantity
        C = plots.COLORS
        a = ax_map
        a.set_aspect("equal")
        a.set_xlabel("X, km")
        a.set_ylabel("Y, km")
        self.pts = a.scatter([], [], c=[], s=26, cmap="viridis", vmin=0.0, vmax=1.0, label="tie points")
        (self.ctrl,) = a.plot([], [], "^", color=C["control"], ms=9, mec="black", mew=0.6,
                              label="control points (опознаки)", ls="none")
        (self.centres,) = a.plot([], [], ".", color=C["grey"], ms=4, label="photo centres", ls="none")
        self.cbar = fig.colorbar(self.pts, cax=a.inset_axes([1.02, 0.0, 0.035, 1.0]))
        # the colour bar lies beside the map, clear of its points: drawn before them (not after, as an inset is by
        # default), it stays in a live demo's cached background while the points are redrawn over it
        self.cbar.ax.set_zorder(0.5)
        self.title = a.set_title("", fontsize=11)
        a.legend(loc="upper right", fontsize=9)
        p = ax_prof
        p.set_xlabel("along the strips, km")
        p.set_ylabel("largest predicted error, m")
        (self.prof_plan,) = p.plot([], [], "-o", color=C["blue"], ms=4, label="plan")
        (self.prof_Z,) = p.plot([], [], "-s", color=C["vermillion"], ms=4, label="height")
        self.rows = p.vlines([], 0, 1, colors=C["control"], linestyles=":", label="control rows")
        p.legend(loc="upper left", fontsize=9)
        if result is not None:
            self.update(result)

    def update(self, r: BlockMap) -> None:
        bp = r.precision
        tie = bp.kind != "control"
        q = self.quantity
        val = bp.sigma_plan_m if q == "plan" else bp.sigma_Z_m
        vmax = VMAX_M[q]  # fixed in metres: a larger σ turns the whole map brighter
        self.pts.set_offsets(bp.XYZ_m[tie, :2] / 1000.0)
        self.pts.set_array(val[tie])
        self.pts.set_clim(0.0, vmax)
        label = t("plan error, m") if q == "plan" else t("height error, m")
        if self.cbar.ax.get_ylabel() != label:  # setting the same label again would still be a change of the axes
            self.cbar.set_label(label)
        c = bp.XYZ_m[~tie]
        self.ctrl.set_data(c[:, 0] / 1000.0, c[:, 1] / 1000.0)
        self.centres.set_data(bp.centres_m[:, 0] / 1000.0, bp.centres_m[:, 1] / 1000.0)
        lo, hi = bp.XYZ_m[:, :2].min(axis=0) / 1000.0, bp.XYZ_m[:, :2].max(axis=0) / 1000.0
        pad = 0.15
        self.ax_map.set_xlim(lo[0] - pad, hi[0] + pad)
        self.ax_map.set_ylim(lo[1] - pad - 0.3, hi[1] + pad + 0.6)
        key = ("{n} strips, control rows every {every} bases ({layout}), σ = {sigma:g} µm" if r.n_strips > 1 else
               "{n} strip, control rows every {every} bases ({layout}), σ = {sigma:g} µm")
        # set_text, not set_title: set_title restyles the axes' other titles too, which is a change of the axes
        self.title.set_text(t(key, n=r.n_strips, every=r.every, layout=t(r.layout), sigma=r.sigma_um))
        x = r.profile_x_m / 1000.0
        self.prof_plan.set_data(x, r.profile_plan_m)
        self.prof_Z.set_data(x, r.profile_Z_m)
        top = max(float(r.profile_Z_m.max()), float(r.profile_plan_m.max()), 1e-6) * 1.15
        self.rows.set_segments([[[x[k], 0.0], [x[k], top]] for k in bp.rows])
        self.ax_prof.set_xlim(x[0] - 0.1, x[-1] + 0.1)
        self.ax_prof.set_ylim(0.0, top)


class BlockErrorDemo(LiveDemo):
    """Live error map of a block: strips, control spacing and layout, image error σ."""

    title = "Where a block is weakest: predicted errors against the control layout"
    hint = ("Move the control rows apart (n) and watch the errors swell between them — faster in height; add "
            "strips and the same control holds a stiffer block.  σ scales every error.")
    params = (
        Param("n_strips", "K, strips", 1, 4, 1, 3, kind="int", group="Block", help="1 = a single strip"),
        Param("every", "n, bases between control rows", 2, 12, 1, 4, kind="choice", group="Control",
              options=tuple((str(s), s) for s in SPACINGS), help="control rows across the block every n bases"),
        Param("layout", "layout", kind="choice", default="rows", group="Control",
              options=(("rows across every strip", "rows"), ("perimeter only", "perimeter"))),
        Param("sigma_um", "σ, µm", 2, 30, 1, 7, group="Measuring", help="RMS error of a measured photo coordinate"),
        Param("quantity", "map shows", kind="choice", default="plan", group="View",
              options=(("plan error", "plan"), ("height error", "height"))),
    )

    def build(self):
        for K in range(1, 5):  # the heavy part once: every combination of the sliders that change geometry
            for e in SPACINGS:
                for lay in ("rows", "perimeter"):
                    _unit_map(K, e, lay)
        self.view = BlockErrorView()
        self.fig = self.view.fig
        v = self.view
        # a move recolours the map's points (over the cached axes and colour bar) and redraws the profile with its
        # error axis (σ moves its top on every step: an animated axis' new limits are no change of the rest) and
        # the map's title
        self.animated = (v.pts, v.ctrl, v.centres, v.title, v.ax_prof.yaxis, v.prof_plan, v.prof_Z, v.rows)
        for ax in (v.ax_map, v.ax_prof):
            plots.steady_limits(ax, snap=False)  # the same limits again are no change

    def compute(self, n_strips, every, layout, sigma_um, quantity):
        return block_map(n_strips, every, layout, sigma_um), quantity

    def render(self, result):
        r, quantity = result
        self.view.quantity = quantity
        self.view.update(r)
        self.table.value = plots.html_table(r.table(), caption="Predicted errors (tie points)", float_format="{:.1f}")
