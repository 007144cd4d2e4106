"""Planning an aerial survey: strips, photo centres and footprints over the area (chapter 01, guide §2).

The pure part is :mod:`aerophoto.flight` (:func:`~aerophoto.flight.plan` and
:func:`~aerophoto.flight.layout`); :class:`FlightPlanView` draws a
:class:`~aerophoto.flight.FlightLayout` — the whole area with its flight lines
on the left, a detail of one corner with the footprints, their overlaps and
the working areas on the right — and :class:`FlightPlanDemo` binds sliders for
the camera, the overlaps, the terrain, the area and the aircraft to both, with
the table of every quantity of the guide's calculation beside the figure.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pandas as pd
from matplotlib.collections import PolyCollection

from .. import flight
from .. import plots
from ..i18n import t
from ..i18n.numfmt import fmt_spec
from ..widgets import LiveDemo, Param
from .own import after, task_label

__all__ = ["FlightPlanView", "FlightPlanDemo", "format_value", "plan_table_html", "guide_example_html",
           "MAX_CENTRES", "OWN_TABLE_TASKS", "own_plan_table", "own_side_allowance", "own_overlaps"]

#: the overview draws at most this many strips and photos per strip (every s-th beyond it, with a note in the
#: title): about 15 px apart on the overview, so the strips of the largest plans (41 strips × 66 photos for
#: variant 57, ~10⁶ photos at the sliders' extremes) stay apart instead of merging into one block
MAX_STRIPS_DRAWN = 24
MAX_PHOTOS_DRAWN = 32
#: at most this many photo centres are drawn (the last strip and photo are always drawn: + 1 each)
MAX_CENTRES = (MAX_STRIPS_DRAWN + 1) * (MAX_PHOTOS_DRAWN + 1)
#: at most this many footprints per strip on the overview
MAX_FOOTPRINTS_PER_STRIP = MAX_PHOTOS_DRAWN


def format_value(v) -> str:
    """A table value as text in the book's number format (:mod:`aerophoto.i18n.numfmt`): whole numbers as
    counts, values of 1000 and more whole, else 4 significant digits."""
    from ..i18n.numfmt import fmt_count, fmt_number

    if isinstance(v, (int, np.integer)):
        return fmt_count(int(v))
    v = float(v)
    if abs(v) >= 1000:
        return fmt_number(v, 0)
    return fmt_number(v, sig=4)


#: compact labels of the demo's table (symbol first), by FlightPlan attribute
SHORT_LABELS = {
    "S_km2": "S, area", "H_m": "H, flying height", "h_m": "h, relief", "Px_percent": "Px, forward overlap",
    "Py_percent": "Py, side overlap", "bx_cm": "bx, working area", "by_cm": "by, working area",
    "Bx_km": "Bx, photo base", "By_km": "By, strip spacing", "K": "K, strips", "n": "n, photos per strip",
    "N": "N, photos in all", "LS_km": "LS, route length", "TS_h": "TS, flight time",
    "tmax_s": "tmax, longest exposure", "tau_s": "τ, interval",
}


def plan_table_html(p: flight.FlightPlan, lay: flight.FlightLayout | None = None, *, caption: str = "") -> str:
    """The plan's table (guide §2 steps, compact labels) as HTML for the demo's table widget."""
    df = p.table()[["quantity", "value", "unit"]].copy()
    df["quantity"] = [SHORT_LABELS[k] for k in flight.TABLE_ATTRS]
    df["value"] = [format_value(v) for v in df["value"]]
    notes = [f"40·h/H = {p.relief_allowance_percent:.2f} %", t("footprint l·m = {s:.2f} km", s=p.footprint_side_km)]
    if lay is not None:
        notes.append(t("drawn route {L:.0f} km (LS {LS:.0f} km)", L=lay.route_length_km, LS=p.LS_km))
    return plots.html_table(df, caption=caption or "Survey parameters (guide §2)", notes=notes)


def guide_example_html(audit=None) -> str:
    """The guide's §2 example recomputed (left) beside its line-by-line audit (right), as HTML.

    Reads the audit :func:`aerophoto.guide.ch01.worked_example` (or ``audit``):
    one row per printed line — the line as printed, the factors that follow
    from the line before, the value computed and rounded as the guide rounds —
    shaded where a printed factor or result does not follow, with the reasons
    under the table.
    """
    from .. import guide

    a = guide.ch01.worked_example() if audit is None else audit
    p = a.result
    left = p.table(rounded=True)[["quantity", "value", "unit"]].copy()
    left["quantity"] = [q.split(" (")[0] for q in left["quantity"]]
    left["value"] = [f"{x:.{flight.GUIDE_DECIMALS[k]}f}" if not isinstance(x, int) else str(x)
                     for k, x in zip(flight.TABLE_ATTRS, left["value"])]
    t = a.table
    differs = ~t["follows"].to_numpy(dtype=bool)
    right = pd.DataFrame({"step": t["step"].to_numpy(), "printed in the guide": t["printed"].to_numpy(),
                          "factors that follow": t["factors that follow"].to_numpy(),
                          "computed": t["as printed"].to_numpy(),
                          "": np.where(differs, "✗ slip", "✓")}).set_index("step")
    hl = np.zeros(right.shape, dtype=bool)
    hl[differs, :] = True
    notes = []
    for line in guide.ch01.LINES:
        reasons = [v.reason for v in a.discrepancies if v.where == guide.ch01.line_where(line)]
        if reasons:
            notes.append(f"step {line.step}, {line.quantity}: {' '.join(reasons)}")
    return ("<div style='display:flex;flex-wrap:wrap;gap:16px;align-items:flex-start'>"
            "<div style='flex:0 0 auto'>"
            + plots.html_table(left, caption="Recomputed by aerophoto (guide's rounding)")
            + "</div><div style='flex:1 1 480px;max-width:760px'>"
            + plots.html_table(right, caption="Printed vs computed (guide §2, variant 00)", highlight=hl,
                               notes=notes)
            + "</div></div>")


#: the graded task that asks for each result of the plan (chapter 01); the other rows are the variant's inputs
OWN_TABLE_TASKS = {
    "H_m": "task-01-1", "Px_percent": "task-01-1", "Py_percent": "task-01-1", "bx_cm": "task-01-1",
    "by_cm": "task-01-1", "Bx_km": "task-01-1", "By_km": "task-01-1",
    "K": "task-01-2", "n": "task-01-2", "N": "task-01-2",
    "LS_km": "task-01-3", "TS_h": "task-01-3", "tmax_s": "task-01-3", "tau_s": "task-01-3",
}


def own_plan_table(variant, passed) -> pd.DataFrame:
    """The plan of the student's own variant, step by step as in the guide — each result once its task has passed.

    ``passed`` is a function task id → bool: the notebook passes ``aerophoto.checks.passed``.  The rows a task
    asks for (:data:`OWN_TABLE_TASKS`; P_y, b_x, b_y go with task 01.1, from which they follow) say
    "answer task 01.k first" until that task has passed in the session; S and h, products of the inputs, are
    always shown.  Values rounded as the guide prints them (:meth:`aerophoto.flight.FlightPlan.table`).
    """
    df = flight.plan(variant).table(rounded=True)
    values = []
    for attr, value in zip(flight.TABLE_ATTRS, df["value"]):
        task = OWN_TABLE_TASKS.get(attr)
        values.append(value if task is None or passed(task) else f"answer task {task_label(task)} first")
    df["value"] = values
    return df


def own_side_allowance(variant, passed):
    """The guide's side-overlap allowance beside the exact one for the student's plan, once tasks 01.1–01.2 passed.

    ``passed``: as in :func:`own_plan_table`.  Returns :func:`aerophoto.guide.ch01.side_allowance_table` of the
    variant's plan, or a :class:`~aerophoto.demos.own.Locked` note (the table holds B_y and K, graded values).
    """
    from .. import guide

    return after(passed, ["task-01-1", "task-01-2"], lambda: guide.ch01.side_allowance_table(flight.plan(variant)),
                 "this table holds your strip spacing B_y and your number of strips K.")


def own_overlaps(variant, passed):
    """The forward and side overlaps of the student's plan on the lowest and the highest ground, once 01.1 passed.

    A DataFrame (rows: lowest ground Z_min, highest ground Z_max; columns: forward, side, %) from
    :func:`aerophoto.flight.overlaps_at`, or a :class:`~aerophoto.demos.own.Locked` note: on the lowest ground
    the forward overlap is P_x, a graded value.
    """
    def table():
        p = flight.plan(variant)
        rows = [(name, *flight.overlaps_at(p, Z)) for name, Z in (("lowest ground Z_min", p.Zmin_m),
                                                                 ("highest ground Z_max", p.Zmax_m))]
        return pd.DataFrame(rows, columns=["ground", "forward, %", "side, %"]).set_index("ground").round(2)

    return after(passed, ["task-01-1"], table, "on the lowest ground the forward overlap is your P_x.")


def _rect(x0, y0, x1, y1):
    return np.array([[x0, y0], [x1, y0], [x1, y1], [x0, y1], [x0, y0]], dtype=float)


def _stride(count: int, cap: int) -> int:
    return max(1, math.ceil(count / cap))


class FlightPlanView:
    """Overview (left) and corner detail (right) of a :class:`~aerophoto.flight.FlightLayout`.

    Parameters
    ----------
    layout : FlightLayout, optional
        Drawn at once if given; otherwise call :meth:`update`.
    ax : pair of Axes, optional
        ``(ax_plan, ax_detail)``; a new figure (860×460 px) if None.

    Everything is in ground kilometres, X along the flight lines (east), Y
    across them (north).  :meth:`update` only moves existing artists.
    """

    def __init__(self, layout: flight.FlightLayout | None = None, ax=None):
        if ax is None:
            # a fixed layout (no constrained layout): it is recomputed on every draw and would
            # double the time of a slider update
            fig = plots.figure(figsize=(8.6, 4.6), layout="none")
            ax_plan, ax_zoom = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.25, 1]})
            fig.subplots_adjust(left=0.075, right=0.985, bottom=0.22, top=0.9, wspace=0.18)
        else:
            ax_plan, ax_zoom = ax
            fig = ax_plan.figure
        self.fig, self.ax_plan, self.ax_zoom = fig, ax_plan, ax_zoom
        C = plots.COLORS
        a = ax_plan
        a.set_aspect("equal")
        a.set_xlabel("X (along the strips), km")
        a.set_ylabel("Y, km")
        self.footprints = PolyCollection([], facecolors=C["footprint"], edgecolors=C["blue"], alpha=0.25,
                                         linewidths=0.6, label="footprints (first strips)")
        a.add_collection(self.footprints)
        (self.route,) = a.plot([], [], color=C["blue"], lw=1.0, label="flight path")
        (self.area,) = a.plot([], [], color=C["black"], lw=2.0, label="survey area Lx × Ly")
        self.centres = a.scatter(np.zeros(0), np.zeros(0), s=5, color=C["vermillion"], zorder=4,
                                 label="photo centres")
        (self.arrows_e,) = a.plot([], [], ">", color=C["orange"], ms=6, zorder=5, linestyle="none")
        (self.arrows_w,) = a.plot([], [], "<", color=C["orange"], ms=6, zorder=5, linestyle="none")
        (self.zoom_box,) = a.plot([], [], ls="--", color=C["purple"], lw=1.5, label="detail (right)")
        z = ax_zoom
        z.set_aspect("equal")
        z.set_title("Detail: first strips and photos", fontsize=10)
        z.set_xlabel("X, km")
        self.z_fp = PolyCollection([], facecolors=C["footprint"], edgecolors=C["blue"], alpha=0.18,
                                   linewidths=1.0, label="footprint l·m")
        z.add_collection(self.z_fp)
        self.z_work = PolyCollection([], facecolors="none", edgecolors=C["green"], linewidths=1.4,
                                     linestyles="--", label="working area Bx × By")
        z.add_collection(self.z_work)
        (self.z_area,) = z.plot([], [], color=C["black"], lw=2.0)
        (self.z_route,) = z.plot([], [], color=C["blue"], lw=1.0)
        (self.z_centres,) = z.plot([], [], "+", color=C["vermillion"], ms=9, mew=2, linestyle="none")
        arrow = dict(arrowstyle="<->", color=C["black"], lw=1.3, shrinkA=0, shrinkB=0)
        self.bx_arrow = z.annotate("", xy=(0, 0), xytext=(0, 0), arrowprops=arrow, zorder=6)
        self.by_arrow = z.annotate("", xy=(0, 0), xytext=(0, 0), arrowprops=arrow, zorder=6)
        self.bx_label = z.text(0, 0, "", ha="center", va="top", fontsize=10, zorder=6,
                               bbox=dict(fc="white", ec="none", alpha=0.8, pad=1))
        self.by_label = z.text(0, 0, "", ha="left", va="center", fontsize=10, zorder=6,
                               bbox=dict(fc="white", ec="none", alpha=0.8, pad=1))
        handles = [self.area, self.route, self.centres, self.footprints, self.z_work, self.zoom_box]
        self.legend = fig.legend(handles=handles, labels=[h.get_label() for h in handles],
                                 loc="lower center", ncol=3, fontsize=9, frameon=False)
        self.shown = 0
        self.stride = 1
        if layout is not None:
            self.update(layout)

    def update(self, lay: flight.FlightLayout) -> None:
        p = lay.plan
        K, n = lay.K, lay.n
        Lx, Ly = p.Lx_km, p.Ly_km
        area = _rect(0, 0, Lx, Ly)
        # overview: every strip and photo, or for large plans a schematic of every s-th ---------------------
        self.area.set_data(area[:, 0], area[:, 1])
        sk, sj = _stride(K, MAX_STRIPS_DRAWN), _stride(n, MAX_PHOTOS_DRAWN)
        sk += sk > 1 and sk % 2 == 0   # an odd step: the drawn strips still alternate east and west
        ks, js = _every(K, sk), _every(n, sj)
        self.stride = max(sk, sj)
        self.centres.set_offsets(lay.centres_km(ks, js))
        self.shown = len(ks) * len(js)
        x0r, x1r = lay.photo_x_km[0], lay.photo_x_km[-1]
        if sk == 1:   # the whole route with its turns
            route = lay.route_km(turn_points=12)
        else:         # the drawn flight lines only (turns between strips that are not drawn would mislead)
            route = np.vstack([np.array([[x0r, y], [x1r, y], [np.nan, np.nan]]) for y in lay.strip_y_km[ks]])
        self.route.set_data(route[:, 0], route[:, 1])
        dirs = lay.directions()
        xm = (x0r + x1r) / 2
        sa = _stride(len(ks), 12)          # about a dozen direction arrows, on strips flown both ways
        ka = ks[:: sa + (sa > 1 and sa % 2 == 0)]
        east, west = ka[dirs[ka] > 0], ka[dirs[ka] < 0]
        self.arrows_e.set_data(np.full(len(east), xm), lay.strip_y_km[east])
        self.arrows_w.set_data(np.full(len(west), xm), lay.strip_y_km[west])
        self.footprints.set_verts(list(lay.footprints_km(ks[:2], js)))
        half = p.footprint_side_km / 2
        finite = route[np.isfinite(route[:, 0])]
        xs = np.concatenate([[0, Lx], finite[:, 0]])
        ys = np.concatenate([[0, Ly], finite[:, 1]])
        pad = 0.04 * max(Lx, Ly)
        self.ax_plan.set_xlim(min(xs.min(), lay.photo_x_km[0] - half) - pad, max(xs.max(), Lx) + pad)
        self.ax_plan.set_ylim(min(ys.min(), lay.strip_y_km[0] - half) - pad,
                              max(ys.max(), lay.strip_y_km[-1] + half) + pad)
        drawn = [t("1 in {st} " + what, st=st) for st, what in ((sk, "strips"), (sj, "photos")) if st > 1]
        shown = t("\n(schematic: {what} drawn)", what=t(" and ").join(drawn)) if drawn else ""
        self.ax_plan.set_title(t("K = {K} strips × n = {n} = N = {N} photos{shown}", K=K, n=n, N=_count_text(p.N),
                                 shown=shown), fontsize=10)
        # detail ---------------------------------------------------------------
        kz, jz = np.arange(min(K, 3)), np.arange(min(n, 4))
        self.z_fp.set_verts(list(lay.footprints_km(kz, jz)))
        self.z_work.set_verts(list(lay.working_areas_km(kz, jz)))
        c = lay.centres_km(kz, jz)
        self.z_centres.set_data(c[:, 0], c[:, 1])
        self.z_area.set_data(area[:, 0], area[:, 1])
        first = dataclasses.replace(lay, strip_y_km=lay.strip_y_km[: min(K, 4)])   # the detail's strips, turns
        z_route = first.route_km(turn_points=12)
        self.z_route.set_data(z_route[:, 0], z_route[:, 1])
        x0, x1 = lay.photo_x_km[jz[0]] - half, lay.photo_x_km[jz[-1]] + half
        y0, y1 = lay.strip_y_km[kz[0]] - half, lay.strip_y_km[kz[-1]] + half
        m = 0.06 * max(x1 - x0, y1 - y0)
        self.ax_zoom.set_xlim(x0 - m, x1 + m)
        self.ax_zoom.set_ylim(y0 - m, y1 + m)
        box = _rect(x0, y0, x1, y1)
        self.zoom_box.set_data(box[:, 0], box[:, 1])
        xa, ya = lay.photo_x_km[0], lay.strip_y_km[0]
        if n > 1:
            yb = ya - 0.72 * half
            self.bx_arrow.xy, self.bx_arrow.xyann = (xa, yb), (xa + p.Bx_km, yb)
            self.bx_label.set_position((xa + p.Bx_km / 2, yb - 0.04 * half))
            self.bx_label.set_text(f"Bx = {fmt_spec(p.Bx_km, '{:.3g}')} {t('km')}")
        if K > 1:
            xb = xa + 0.35 * half
            self.by_arrow.xy, self.by_arrow.xyann = (xb, ya), (xb, ya + p.By_km)
            self.by_label.set_position((xb + 0.04 * half, ya + p.By_km / 2))
            self.by_label.set_text(f"By = {fmt_spec(p.By_km, '{:.3g}')} {t('km')}")
        for art, ok in ((self.bx_arrow, n > 1), (self.bx_label, n > 1), (self.by_arrow, K > 1),
                        (self.by_label, K > 1)):
            art.set_visible(ok)


def _every(count: int, step: int) -> np.ndarray:
    """Indices 0, s, 2s, … of ``count`` items, ending on the last one (the drawn strips span the whole area):
    the last index is added, or replaces the one before it when that lies less than half a step away."""
    idx = np.arange(0, count, step)
    if count > 1 and idx[-1] != count - 1:
        if 2 * (count - 1 - idx[-1]) >= step or len(idx) == 1:
            idx = np.append(idx, count - 1)
        else:
            idx[-1] = count - 1
    return idx


def _count_text(N: int) -> str:
    from ..i18n.numfmt import fmt_count

    return fmt_count(N)


class FlightPlanDemo(LiveDemo):
    """Live survey plan: camera, overlaps, relief, area and aircraft → strips, photos and timing.

    The slider bounds keep every combination valid: H = f·m ≥ 100 mm·5000 =
    500 m > h ≤ 250 m, and the relief allowance 40·h/H ≤ 20 %, so Px ≤ 95 %
    and Py ≤ 80 %.  Construct with keyword values (``FlightPlanDemo(f_mm=150)``)
    or from a variant with :meth:`for_variant`.  ``Zmin_m`` (not a slider)
    fixes the lowest ground; the relief slider sets Zmax = Zmin + h.
    """

    title = "Planning the survey: strips, photos and time (guide §2)"
    hint = ("Raise the relief h or lower the scale denominator m and watch the number of strips and photos "
            "grow; a faster aircraft shortens the flight but also the longest admissible exposure.")
    params = (
        Param("f_mm", "f, mm", 100, 1100, 10, 100, group="Camera", help="focal length f"),
        Param("m", "m (scale 1:m)", 5000, 30000, 100, 12000, group="Camera", help="photo-scale denominator"),
        Param("px_percent", "px, %", 50, 75, 1, 60, group="Overlaps", help="normative forward overlap"),
        Param("py_percent", "py, %", 20, 60, 1, 30, group="Overlaps", help="normative side overlap"),
        Param("h_m", "h = Zmax − Zmin, m", 0, 250, 5, 30, group="Terrain and area", help="relief of the area"),
        Param("Lx_km", "Lx, km", 5, 150, 1, 25, group="Terrain and area", help="area along the strips"),
        Param("Ly_km", "Ly, km", 5, 150, 1, 30, group="Terrain and area", help="area across the strips"),
        Param("W_kmh", "W, km/h", 100, 1200, 10, 200, group="Aircraft", help="ground speed"),
        Param("M", "photoplan 1:M", kind="choice", default=10000.0, group="Aircraft",
              options=(("1:2 000", 2000.0), ("1:5 000", 5000.0), ("1:10 000", 10000.0), ("1:25 000", 25000.0)),
              help="photoplan scale: the blur δ = 0.1 mm is measured on it"),
    )

    def __init__(self, Zmin_m: float = 170.0, **values):
        self.Zmin_m = float(Zmin_m)
        self.clamped: dict = {}
        super().__init__(**values)

    @classmethod
    def for_variant(cls, v) -> "FlightPlanDemo":
        """A demo starting at variant ``v``'s values, each clamped to its slider's range.

        ``demo.clamped`` lists what had to move: name → (variant value, start value).
        The full, unclamped plan of the variant is :func:`aerophoto.flight.plan` (v).
        """
        wanted = dict(f_mm=v.f_mm, m=v.m, px_percent=v.px_percent, py_percent=v.py_percent,
                      h_m=v.Zmax_m - v.Zmin_m, Lx_km=v.Lx_km, Ly_km=v.Ly_km, W_kmh=v.W_kmh, M=v.M)
        start, clamped = {}, {}
        for p in cls.params:
            x = wanted[p.name]
            if p.kind == "choice":
                opts = [o[1] if isinstance(o, tuple) else o for o in p.options]
                y = min(opts, key=lambda o: abs(math.log(o / x)))
            else:
                y = min(max(x, p.lo), p.hi)
                y = p.lo + round((y - p.lo) / p.step) * p.step
                y = min(max(y, p.lo), p.hi)
            if abs(y - x) > 1e-9:
                clamped[p.name] = (x, y)
            start[p.name] = y
        demo = cls(Zmin_m=v.Zmin_m, **start)
        demo.clamped = clamped
        if clamped:
            moved = "; ".join(f"{name} = {a:g} → {b:g}" for name, (a, b) in clamped.items())
            demo.status.value = (f"<span style='color:#0072B2'>Your variant lies outside the sliders' range; "
                                 f"the demo starts at the nearest values ({moved}). The table of your own "
                                 "variant is computed with aerophoto.flight.plan(v), unclamped.</span>")
        return demo

    def build(self):
        self.view = FlightPlanView()
        self.fig = self.view.fig
        # a move redraws both panels' artists over cached axes; rounded limits (and a title set again to the
        # same text) keep the axes and their ticks on small moves
        v = self.view
        for ax in (v.ax_plan, v.ax_zoom):
            plots.steady_limits(ax)
            plots.steady_title(ax)
        self.animated = (v.footprints, v.z_fp)

    def compute(self, h_m, **v):
        p = flight.plan(Zmax_m=self.Zmin_m + h_m, Zmin_m=self.Zmin_m, **v)
        return flight.layout(p)

    def render(self, result):
        self.view.update(result)
        self.table.value = plan_table_html(result.plan, result)
