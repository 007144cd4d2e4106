"""Contours from a DEM of the virtual site, against the true ground (chapter 16, article 000).

:class:`ContourView` draws a map sheet: the DEM's error DEM − truth as a colour image, the true
contours (thin grey), the contours drawn from the DEM (blue), the DEM's nodes and — when used — the
structural lines (thalwegs blue-green, watersheds brown).  :class:`ContourDemo` binds sliders for the
grid step d, the structural lines (on/off), the measurement error m_z of the node heights, the
contour interval h and the sheet; its table gives the RMS of the contours' heights against the true
surface beside the prediction √(m_interp² + k·m_z²) (:func:`aerophoto.dem.predicted_rms`).

The demo opens on the article's example: a 1:2000 sheet (1 km) in the site's hills, a 30 m grid,
h = 0.5 m and the article's measured densification error m_z = 12 cm.  Everything per sheet that does
not change with the sliders — the true surface on the raster, its contours, the structural lines —
is computed once and kept (:func:`sheet_cache`).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
import pandas as pd
from matplotlib.collections import LineCollection

from .. import dem
from .. import plots
from ..blit import nearest_pixels
from ..i18n import t
from ..i18n.numfmt import fmt_count, fmt_number, fmt_spec
from ..widgets import LiveDemo, Param

__all__ = ["SHEETS", "INTERVALS", "SheetCache", "sheet_cache", "ContourFrame", "contour_frame", "ContourView",
           "ContourDemo", "spacing_study_figure"]

#: the demo's sheets: (label, (X0, Y0) of the south-west corner, m); each 1 km square
SHEETS = (("hills (2–3 km E, 3–4 km N)", (2000.0, 3000.0)), ("valley side (4–5 km E, 1.5–2.5 km N)", (4000.0, 1500.0)),
          ("plain (6–7 km E, 0.2–1.2 km N)", (6000.0, 200.0)))
#: contour intervals offered, m
INTERVALS = (("0.25 m", 0.25), ("0.5 m", 0.5), ("1 m", 1.0), ("2 m", 2.0))
ERROR_CLIM_M = 0.3
_C = plots.COLORS
_VALLEY = "#009E73"
_RIDGE = "#E69F00"  # orange, dash-dotted: apart from the green thalwegs in colour and in shape (colour-blind safe)


def _site():
    from ..site import get_site

    return get_site()


@dataclass(frozen=True, eq=False)
class SheetCache:
    """What a sheet needs once: the true surface on the raster, its structural lines, its true contours by h."""

    sheet: dem.Sheet
    cell_m: float
    x: np.ndarray
    y: np.ndarray
    Z_true: np.ndarray
    lines: dem.StructuralLines
    true_contours: dict

    def line_points(self, spacing_m: float) -> np.ndarray:
        return _line_points(self, float(spacing_m))


@functools.lru_cache(maxsize=32)
def _line_points(cache: SheetCache, spacing_m: float) -> np.ndarray:
    return cache.lines.points(spacing_m)


@functools.lru_cache(maxsize=8)
def sheet_cache(X0_m: float, Y0_m: float, size_m: float = 1000.0, cell_m: float = 5.0) -> SheetCache:
    """The per-sheet data of the demo (cached; the site is :func:`aerophoto.site.get_site`'s default)."""
    site = _site()
    sheet = dem.Sheet(X0_m, Y0_m, size_m)
    x, y = sheet.raster(cell_m)
    Zt = np.asarray(site.height(*np.meshgrid(x, y)), dtype=float)
    lines = dem.structural_lines(site, sheet)
    true = {h: dem.contour_lines(x, y, Zt, dem.contour_levels(float(Zt.min()), float(Zt.max()), h))
            for _lab, h in INTERVALS}
    return SheetCache(sheet, cell_m, x, y, Zt, lines, true)


@dataclass(frozen=True, eq=False)
class ContourFrame:
    """What the view shows: the evaluated DEM, the sheet's cache and whether the lines are in."""

    result: dem.SheetResult
    cache: SheetCache
    structural: bool

    def table(self) -> pd.DataFrame:
        r, a = self.result, self.result.accuracy
        k = dem.NOISE_FACTOR[r.dem.kind]
        rows = [
            ("DEM", "", "grid + structural lines (TIN)" if self.structural else "regular grid (bilinear)"),
            ("nodes", "", f"{r.dem.n_nodes}"),
            ("contours drawn (h = {:g} m)".format(r.interval_m), "", f"{a.n_lines}"),
            ("RMS of contour heights", "m", f"{a.rms_m:.3f}"),
            ("mean |error| of contours", "m", f"{a.mean_abs_m:.3f}"),
            ("interpolation alone, m_interp", "m", f"{r.interp_rms_m:.3f}"),
            (f"predicted √(m_interp² + {k:.2f}·m_z²)", "m", f"{r.predicted_m:.3f}"),
            ("RMS of DEM − truth, whole sheet", "m", f"{r.raster_rms_m:.3f}"),
            ("article's requirement: mean error ≤ 0.3·h", "m", f"{0.3 * r.interval_m:.3f}"),
        ]
        return pd.DataFrame(rows, columns=["quantity", "unit", "value"]).set_index("quantity")


def contour_frame(sheet: str | tuple = SHEETS[0][1], spacing_m: float = 30.0, structural: bool = False,
                  mz_m: float = 0.12, interval_m: float = 0.5, *, seed: int = 0, cell_m: float = 5.0) -> ContourFrame:
    """Build and evaluate the DEM of a sheet (the demo's model; also for static figures).

    Parameters
    ----------
    sheet : (X0, Y0) of a 1 km sheet on the site, m, or a label of :data:`SHEETS`
    spacing_m : grid step d, m (5 ≤ d ≤ 500)
    structural : add the structural lines (points d/2 apart) and triangulate
    mz_m : RMS measurement error of the node heights, m
    interval_m : contour interval h, m (one of :data:`INTERVALS`)
    cell_m : the raster the DEM is evaluated and contoured on, m (the demo's preview uses 10 m)
    """
    if isinstance(sheet, str):
        labels = dict(SHEETS)
        if sheet not in labels:
            raise ValueError(f"sheet = {sheet!r} is not one of the valid choices {list(labels)}")
        sheet = labels[sheet]
    h = float(interval_m)
    if h not in dict((v, k) for k, v in INTERVALS):
        raise ValueError(f"interval_m = {interval_m!r} is not one of the valid choices {[v for _k, v in INTERVALS]}")
    cache = sheet_cache(float(sheet[0]), float(sheet[1]), 1000.0, float(cell_m))
    site = _site()
    if structural:
        d = float(spacing_m)
        dm = dem.grid_with_lines(site, cache.sheet, d, cache.lines, mz_m=mz_m, seed=seed,
                                 line_points=cache.line_points(max(d / 2.0, cache.lines.cell_m / 2.0)))
    else:
        dm = dem.grid_dem(site, cache.sheet, spacing_m, mz_m=mz_m, seed=seed)
    res = dem.evaluate(site, cache.sheet, dm, h, cell_m=cache.cell_m, Z_true=cache.Z_true)
    return ContourFrame(res, cache, bool(structural))


def _segments(lines: list, x0: float, y0: float) -> list:
    return [P - (x0, y0) for _z, P in lines]


class ContourView:
    """A 1 km sheet: DEM − truth (colour), true contours (grey), DEM contours (blue), nodes, structural lines.

    ``ContourView(ax=None)`` builds the artists once; ``update(frame)`` moves them.  Coordinates are
    metres from the sheet's south-west corner.
    """

    def __init__(self, frame: ContourFrame | None = None, ax=None, *, colorbar: bool = True):
        if ax is None:
            fig = plots.figure(figsize=(7.0, 6.2) if colorbar else (6.2, 6.2), layout="none")
            ax = fig.add_axes([0.1, 0.08, 0.72, 0.84] if colorbar else [0.12, 0.08, 0.84, 0.84])
            cax = fig.add_axes([0.85, 0.08, 0.03, 0.84]) if colorbar else None
        else:
            fig, cax = ax.figure, None
        self.fig, self.ax = fig, ax
        ax.grid(False)
        self.image = nearest_pixels(ax.imshow(np.zeros((2, 2)), extent=(0, 1000, 0, 1000), origin="lower",
                                              cmap="RdBu_r", vmin=-ERROR_CLIM_M, vmax=ERROR_CLIM_M,
                                              interpolation="nearest"))
        if cax is not None:
            cb = fig.colorbar(self.image, cax=cax, ticks=[-ERROR_CLIM_M, 0.0, ERROR_CLIM_M])
            cb.set_label("DEM − true height, m")
        self.true_lc = LineCollection([], colors=_C["grey"], linewidths=0.8, linestyles="dashed",
                                      label="true contours")
        # black: dark over the blue/red error field and its node dots (a blue line vanished over its blue half)
        self.dem_lc = LineCollection([], colors=_C["black"], linewidths=1.4, label="contours from the DEM")
        self.valley_lc = LineCollection([], colors=_VALLEY, linewidths=2.2, alpha=0.8, label="thalwegs (тальвеги)")
        self.ridge_lc = LineCollection([], colors=_RIDGE, linewidths=2.2, alpha=0.9, linestyles="dashdot",
                                       label="watersheds (водоразделы)")
        for lc in (self.true_lc, self.valley_lc, self.ridge_lc, self.dem_lc):
            ax.add_collection(lc)
        # the nodes small and grey under the contours: 1 225 of them must not hide the lines
        self.nodes = ax.scatter([], [], s=3, c=_C["grey"], zorder=2, linewidths=0)
        ax.set_xlim(0, 1000)
        ax.set_ylim(0, 1000)
        ax.set_xticks([0, 500, 1000])  # few tick labels: text is much of a redraw's cost
        ax.set_yticks([0, 500, 1000])
        ax.set_aspect("equal")
        ax.set_xlabel("x from the sheet's corner, m")
        ax.set_ylabel("y, m")
        self.title = ax.set_title("")
        if frame is not None:
            self.update(frame)

    def update(self, frame: ContourFrame) -> None:
        r, c = frame.result, frame.cache
        x0, y0 = c.sheet.X0_m, c.sheet.Y0_m
        self.image.set_data(r.Z_dem - r.Z_true)
        self.true_lc.set_segments(_segments(c.true_contours[r.interval_m], x0, y0))
        self.dem_lc.set_segments(_segments(r.contours, x0, y0))
        if frame.structural:
            self.valley_lc.set_segments(list(c.lines.valley_segments - (x0, y0)))
            self.ridge_lc.set_segments(list(c.lines.ridge_segments - (x0, y0)))
        else:
            self.valley_lc.set_segments([])
            self.ridge_lc.set_segments([])
        self.nodes.set_offsets(r.dem.nodes_m[:, :2] - (x0, y0))
        self.title.set_text(t("h = {h} m: RMS of contour heights {rms} m ({n} nodes)", h=fmt_spec(r.interval_m, "{:g}"),
                              rms=fmt_number(r.accuracy.rms_m, 3), n=fmt_count(r.dem.n_nodes)))


def legend_html() -> str:
    """The view's key as HTML (the live demo shows it beside the figure): the lines' swatches in their own dash
    patterns (watersheds dash-dotted, apart from the thalwegs in shape too), the error colours, the nodes."""
    items = ((_C["black"], "solid", "contours from the DEM"), (_C["grey"], "dashed", "true contours"),
             (_VALLEY, "solid", "thalwegs (тальвеги)"), (_RIDGE, "dotted", "watersheds (водоразделы)"))
    rows = "".join(f"<div><span style='display:inline-block;width:28px;border-top:3px {ls} {col};"
                   f"vertical-align:middle;margin-right:6px'></span>{t(lab)}</div>" for col, ls, lab in items)
    bar = ("<span style='display:inline-block;width:120px;height:10px;vertical-align:middle;margin:0 4px;"
           "background:linear-gradient(to right,#053061,#4393c3,#f7f7f7,#d6604d,#67001f)'></span>")
    lim = fmt_spec(ERROR_CLIM_M, "{:g}")
    return (f"<div class='aerophoto-legend' style='font-size:13px;line-height:1.5;margin-bottom:6px'>{rows}"
            f"<div>{t('colour: DEM − true height, −{lim} m', lim=lim)}{bar}{t('+{lim} m (red: DEM too high)', lim=lim)}"
            f"</div><div><span style='color:{_C['grey']}'>●</span> {t('DEM nodes')}</div></div>")


class ContourDemo(LiveDemo):
    """Live contours of a DEM of the site: grid step, structural lines, measurement error, interval, sheet.

    While a slider is dragged the DEM is evaluated and contoured on a ``preview_cell_m`` raster; once the
    slider has rested ``settle_s`` seconds, on the full ``cell_m`` raster.  ``demo.set(...)`` always renders
    in full.
    """

    title = "Contours from a DEM against the true ground (article 000)"
    hint = ("Black: contours drawn from the DEM; dashed grey: where they should be. Coarsen the grid until the "
            "interpolation shows, then switch the structural lines on; raise m_z and watch the contours wriggle.")
    params = (
        Param("spacing_m", "d, m", 10, 200, 10, 30, group="DEM", help="step of the regular grid"),
        Param("structural", "structural lines", kind="choice", options=(("off", "off"), ("on", "on")),
              default="off", group="DEM", help="add points along thalwegs and watersheds and triangulate (TIN)"),
        Param("mz_m", "m_z, m", 0.0, 0.5, 0.01, 0.12, group="Errors",
              help="RMS measurement error of the node heights (densification)"),
        Param("interval_m", "h, m", kind="choice", options=INTERVALS, default=0.5, group="Map",
              help="contour interval (сечение рельефа)"),
        Param("sheet", "sheet", kind="choice", options=tuple((lab, lab) for lab, _xy in SHEETS),
              default=SHEETS[0][0], group="Map"),
    )

    cell_m = 5.0
    preview_cell_m = 10.0
    settle_s = 0.35

    def build(self):
        self.view = ContourView(colorbar=False)  # the colour scale is in the HTML legend (no redraw)
        self.fig = self.view.fig
        # a move swaps the error image and the contours over the cached axes (the sheet's limits never change):
        # the image, everything drawn over it and the title are redrawn
        self.animated = (self.view.image, self.view.title)

    def compute(self, spacing_m, structural, mz_m, interval_m, sheet):
        cell = self.preview_cell_m if self._preview else self.cell_m
        return contour_frame(sheet, spacing_m, structural == "on", mz_m, interval_m, cell_m=cell)

    def on_slider(self) -> str:
        """A slider moved: the coarse raster now, the full one when the slider rests."""
        return self.preview_then_full(self.settle_s, "preview (10 m raster) — full resolution when the slider rests")

    def render(self, frame: ContourFrame):
        self.view.update(frame)
        self.table.value = legend_html() + plots.html_table(frame.table(), caption="Contours against the truth")


def spacing_study_figure(study: pd.DataFrame, ax=None):
    """RMS of contour heights against the grid step: regular grid vs grid + structural lines (a static figure).

    ``study`` has columns ``d, m``, ``grid``, ``grid + lines`` (and optionally ``… m_z = 0``), one row per step.
    """
    fig, ax = plots.new_axes(ax, figsize=(7.2, 4.4))
    for col, colour, style in (("grid", _C["blue"], "-o"), ("grid + lines", _C["vermillion"], "-s"),
                               ("grid, m_z = 0", _C["blue"], ":o"), ("grid + lines, m_z = 0", _C["vermillion"], ":s")):
        if col in study:
            ax.plot(study["d, m"], study[col], style, color=colour, label=col, ms=5)
    ax.set_xlabel("grid step d, m")
    ax.set_ylabel("RMS of contour heights, m")
    ax.legend()
    return fig
