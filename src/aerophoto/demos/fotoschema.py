"""The live fotoschema: a single-strip photo mosaic, its seams and its scale (chapter 05, guide §6).

The pure part is :mod:`aerophoto.mosaic`; :func:`fotoschema_model` flies a
strip over the virtual site (:mod:`aerophoto.site`, :mod:`aerophoto.simulate`)
with the chosen camera, scale, tilt, relief and overlap, assembles it
(:func:`aerophoto.mosaic.assemble`) and glues the working areas onto a sheet
raster (:func:`aerophoto.mosaic.sheet_raster`).  :class:`FotoschemaView` draws
the sheet with the cuts and the mismatch markers and, below it, the
mismatches ΔI of every cut against the 0.5 mm tolerance; :class:`FotoschemaDemo`
binds sliders to both.

Preview while dragging, full resolution on release
--------------------------------------------------
Gluing the sheet at full resolution takes 0.1–0.3 s, too slow to follow a
slider.  The demo therefore renders every slider event at the
*preview* resolution (``preview_px_per_mm``, about 20 ms of gluing) and
starts a short *settle timer* (``settle_s`` = 0.35 s) on the kernel's event
loop; each new event restarts the timer, and when the slider has been still
for that long the sheet is glued once more at the *full* resolution
(``full_px_per_mm``), a band of rows per turn of the event loop, so that a
slider moved again meanwhile is answered within one band (about 15 ms)
instead of after the whole sheet.  This debounce needs nothing from the browser — an
ipywidgets slider does not report "released" separately — and works the same
for keyboard steps.  Outside a running event loop (a script, a test) there is
no timer: a slider event is followed at once by the full render.  From code,
``demo.set(...)`` renders at full resolution and ``demo.set(..., preview=True)``
at the preview one; ``demo.render_full()`` turns a shown preview into the full
picture at once (what the timer does); ``demo.result.preview`` says which is shown.

Both are blitted (``LiveDemo.animated``, :class:`aerophoto.blit.Blitter`): a
move redraws the sheet, its marks, the title and the ΔI stems over a cached
picture of the axes, whose limits are snapped (the sheet's to 20 mm, the ΔI
chart's to round values) so that most moves leave them alone; the tables
follow the picture (:func:`aerophoto.widgets.table_after_picture`).

Static figures for the notebook: :func:`correction_sheet` (the корректурный
лист with the ΔI values written along each cut), :func:`sheet_figure` (the
finished sheet with the guide's marginalia, at true scale on an ISO paper
size) and :func:`export_sheet` (PNG and PDF, never overwriting silently).

The student's own fotoschema (chapter 05's lab, :mod:`aerophoto.labs.ch05`):
:func:`own_sheet_figure` draws it for measuring (the glued prints, the cuts,
the numbered check points and the four points of the mean scale — no
mismatch and no scale: those are the student's answers);
:func:`student_sheet` returns the finished sheet of a variant signed with the
mean scale and the student's name and record book (for the report);
:func:`finished_sheet` shows and writes it in the notebook once the task is
answered.

The demo opens on the guide's worked example, variant 00 (f = 100 mm,
1:12 000), and its sliders reach every variant (f up to 1100 mm, m up to
22 000).  A strip of four photos, like the guide's four prints, fits the
10 × 5 km site at every scale; at large H = f·m a tilt could carry the
photos off the site, and then the tilt is reduced to the largest that keeps
them on it — the table says so (:func:`aerophoto.labs.own.tilt_that_fits`).
"""

from __future__ import annotations

import dataclasses
import datetime
import functools
import math
import time
from dataclasses import dataclass
from pathlib import Path

import numpy as np
import pandas as pd
from matplotlib import patheffects
from matplotlib.collections import LineCollection

from .. import geometry as g
from ..i18n.numfmt import fmt_count, fmt_number, fmt_scale, fmt_signed, fmt_spec
from .. import mosaic as mo
from .. import plots
from ..blit import nearest_pixels
from .. import simulate as sim
from ..terrain import RescaledRelief
from ..i18n import t as _t  # functions here name a local t
from ..widgets import LiveDemo, Param, pending_html, running_loop, table_after_picture

__all__ = [
    "FotoschemaResult",
    "fotoschema_model",
    "default_ground",
    "FotoschemaView",
    "FotoschemaDemo",
    "correction_sheet",
    "sheet_figure",
    "export_sheet",
    "PAPER_MM",
    "TRIM_MM",
    "sheet_size_mm",
    "sheet_paper",
    "own_prints",
    "own_sheet_image",
    "own_sheet_figure",
    "student_sheet",
    "finished_sheet",
]

#: ISO A paper sizes, landscape (width, height) in mm
PAPER_MM = {"A4": (297.0, 210.0), "A3": (420.0, 297.0), "A2": (594.0, 420.0), "A1": (841.0, 594.0),
            "A0": (1189.0, 841.0)}

#: photos in the demo's strip: the guide's four prints (guide §1: "по контактным аэроснимкам 4 шт."), which fit
#: the 10 × 5 km site at every variant's scale (five do not beyond 1:19 500)
N_PHOTOS = 4


def default_ground(relief_m: float = 30.0):
    """The default virtual site with its relief rescaled to ``relief_m`` (:class:`aerophoto.terrain.RescaledRelief`)."""
    from .. import site as site_mod

    return RescaledRelief(site_mod.get_site(), relief_m)


@functools.lru_cache(maxsize=4)
def _ground_and_points(site, relief_m: float) -> tuple:
    """The site with its relief rescaled to ``relief_m`` and its catalogue points, shape (k, 3), m (read-only).

    Kept for the last few reliefs: a slider move that leaves the relief alone finds the same terrain and does
    not build the catalogue's DataFrame again.
    """
    gr = RescaledRelief(site, relief_m)
    pts = mo.catalogue_points(gr)
    if pts is not None:
        pts.flags.writeable = False
    return gr, pts


@dataclass(frozen=True)
class FotoschemaResult:
    """What the fotoschema demo shows.

    Attributes
    ----------
    fs : aerophoto.mosaic.Fotoschema
    image : (ny, nx) float32 sheet raster, row 0 at y_min
    extent_mm : (x_min, x_max, y_min, y_max) of the raster, sheet mm
    px_per_mm : resolution of the raster
    preview : True if rendered at the preview resolution
    strip : the simulated strip
    ground : the terrain (the site with rescaled relief)
    timings_s : dict of the stages' durations, seconds
    note : a remark on the inputs (a tilt reduced so the photos stay on the site), "" if none
    alpha_max_deg : the largest tilt actually flown, degrees
    """

    fs: mo.Fotoschema
    image: np.ndarray
    extent_mm: tuple
    px_per_mm: float
    preview: bool
    strip: object
    ground: object
    timings_s: dict
    note: str = ""
    alpha_max_deg: float = 0.0

    def table(self) -> pd.DataFrame:
        """The headline numbers: RMS m, worst cut-out, number of points, mean scale vs design, verdict."""
        fs = self.fs
        s = fs.scale
        rows = [
            ("m = √(ΣΔI²/n), RMS of the seams", "mm", fmt_number(fs.rms_mm, 2)),
            ("largest cut-out (вырез), allowed −0.5", "mm", fmt_signed(fs.worst_cutout_mm, 2)),
            ("largest duplicate (дублет)", "mm",
             fmt_signed(max(0.0, float(fs.dI_mm.max())) if fs.dI_mm.size else 0.0, 2)),
            ("check points n", "", fmt_count(fs.dI_mm.size)),
            ("mean scale 1:m (6.1), four bases", "1:", fmt_count(round(s.m))),
            ("design scale of the photos", "1:", fmt_count(round(fs.m_design))),
            ("spread of the partial scales m_i", "", fmt_count(round(float(np.ptp(s.m_i))))),
            ("seams", "", "pass" if fs.ok else "FAIL: cut-out > 0.5 mm"),
        ]
        return pd.DataFrame(rows, columns=["quantity", "unit", "value"]).set_index("quantity")


#: a preview's lattice step, sheet pixels (:func:`fotoschema_model`)
PREVIEW_LATTICE_PX = 6


def fotoschema_model(f_mm: float = 100.0, m: float = 12000.0, alpha_max_deg: float = 1.0, relief_m: float = 30.0,
                     px_percent: float = 60.0, cut_shape: str = "straight", seed: int = 1, *,
                     n_photos: int = N_PHOTOS, px_per_mm: float = 2.5, preview: bool = False, ground=None,
                     prints=None) -> FotoschemaResult:
    """Fly a strip over the virtual site, assemble its fotoschema and glue the sheet.

    Parameters
    ----------
    f_mm : focal length f, mm (with m it fixes H = f·m)
    m : photo scale denominator (1/m)
    alpha_max_deg : largest tilt α of the photos; each gets α uniform in
        [0, α_max] with a random direction (seeded, :class:`aerophoto.simulate.Imperfections`)
    relief_m : height difference of the terrain, m (the site's hills rescaled)
    px_percent : forward overlap p_x, %
    cut_shape : "straight", "zigzag" or "curved"
    seed : random stream of the tilts
    px_per_mm : resolution of the sheet raster, pixels per sheet mm
    preview : recorded in the result (the caller chooses ``px_per_mm``); a preview's rays are cut with the
        terrain every :data:`PREVIEW_LATTICE_PX` pixels only and interpolated between
        (:func:`aerophoto.mosaic.sheet_raster`'s ``lattice_px``: half the gluing time, under 0.15 px off)
    ground : terrain to use (default :func:`default_ground` with ``relief_m``)
    prints : "render" to glue rendered prints (:func:`aerophoto.render.render_strip`,
        1024 px, with light fall-off and fiducial marks) instead of sampling the
        ground directly
    """
    from ..labs.own import tilt_that_fits

    t0 = time.perf_counter()
    if ground is None:
        from .. import site as site_mod

        gr, points = _ground_and_points(site_mod.get_site(), float(relief_m))
    else:
        gr, points = ground, mo.catalogue_points(ground)
    cam = g.Camera(f_mm)
    alpha = tilt_that_fits(gr, cam, m, px_percent, n_photos, alpha_max_deg)
    note = ""
    if alpha < alpha_max_deg - 1e-9:
        H = g.flying_height_m(f_mm, m)
        note = (f"α max reduced from {alpha_max_deg:g}° to {fmt_number(alpha, 2, lang='en')}°: at H = "
                f"{fmt_count(round(H), lang='en')} m a larger tilt would carry the photos off the 10 × 5 km site")
    asked = alpha
    while True:  # a large tilt at a small base can leave two neighbours no common strip for their tie points:
        strip = sim.strip_over_site(gr, cam, m, px_percent, n_photos,  # then fly a smaller one, 0.25° at a time
                                    imperfections=sim.Imperfections(max_tilt_deg=alpha, seed=int(seed)))
        t1 = time.perf_counter()
        try:
            fs = mo.assemble(strip, gr, cut_shape=cut_shape, points_m=points)
            break
        except ValueError as exc:
            if "do not overlap enough" not in str(exc) or alpha <= 0.0:
                raise
            alpha = max(0.0, math.ceil(alpha * 4.0 - 1.0 - 1e-9) / 4.0)
    if alpha < asked - 1e-9:
        note = (note + " " if note else "") + (f"α max reduced from {alpha_max_deg:g}° to {alpha:.2f}°: at p_x = "
                f"{px_percent:g} % a larger tilt leaves two neighbouring photos no common strip for their tie points")
    t2 = time.perf_counter()
    photos = None
    if prints == "render":
        from .. import render

        photos = render.render_strip(gr, strip, 1024)
    image, extent = mo.sheet_raster(fs, gr, px_per_mm, photos=photos,
                                    lattice_px=PREVIEW_LATTICE_PX if preview and photos is None else None)
    t3 = time.perf_counter()
    return FotoschemaResult(fs, image, extent, float(px_per_mm), bool(preview), strip, gr,
                            {"fly": t1 - t0, "assemble": t2 - t1, "glue": t3 - t2}, note, float(alpha))


# =========================================================================== the view
_CUTOUT = plots.COLORS["vermillion"]
#: the cut lines: yellow with a dark edge (orange ones merged with the vermilion cut-out dots for a deuteranope)
_CUT = plots.COLORS["yellow"]
_CUT_EDGE = [patheffects.withStroke(linewidth=3.4, foreground="black")]
_DUPLICATE = plots.COLORS["blue"]


class FotoschemaView:
    """The sheet with cuts and mismatch markers (top) and ΔI along every cut (bottom).

    ``view = FotoschemaView(ax=None)`` builds the figure once (``ax`` may be a
    pair of axes); ``view.update(result)`` moves every artist in place.
    """

    def __init__(self, result: FotoschemaResult | None = None, ax=None, *, figsize=(8.8, 5.6)):
        if ax is None:
            fig = plots.figure(figsize=figsize, layout="constrained")
            gs = fig.add_gridspec(2, 1, height_ratios=[3.0, 1.25])
            ax_sheet, ax_d = fig.add_subplot(gs[0]), fig.add_subplot(gs[1])
        else:
            ax_sheet, ax_d = ax
            fig = ax_sheet.figure
        self.fig, self.ax_sheet, self.ax_dI = fig, ax_sheet, ax_d
        C = plots.COLORS
        a = ax_sheet
        a.set_aspect("equal")
        a.grid(False)
        a.set_xlabel("along the strip, sheet mm")
        a.set_ylabel("across, mm")
        self.image = nearest_pixels(a.imshow(np.ones((2, 2), np.float32), cmap="gray", vmin=0.0, vmax=1.0,
                                             origin="lower", extent=(0, 1, 0, 1), interpolation="antialiased",
                                             zorder=0))
        self.frames = LineCollection([], colors=C["skyblue"], linewidths=0.8, alpha=0.9, zorder=2)
        a.add_collection(self.frames)
        self.cuts = LineCollection([], colors=_CUT, linewidths=1.8, zorder=3, label="cuts (порезы)",
                                   path_effects=_CUT_EDGE)
        a.add_collection(self.cuts)
        self.points = a.scatter(np.zeros(0), np.zeros(0), s=np.zeros(0), facecolors=[], edgecolors="white",
                                linewidths=0.8, zorder=5)
        (self.ties,) = a.plot([], [], linestyle="none", marker="x", ms=6, mew=1.8, color=C["green"], zorder=6,
                              label="tie points a, b")
        (self.o,) = a.plot([], [], linestyle="none", marker="+", ms=10, mew=1.8, color=C["black"], zorder=6,
                           label="principal points o")
        self.numbers = plots.PointLabels(a, offset_pt=(4.0, -12.0), fontsize=10, zorder=7)
        # legend proxies for the markers
        a.plot([], [], "o", color=_CUTOUT, label="cut-out (вырез, −)")
        a.plot([], [], "o", color=_DUPLICATE, label="duplicate (дублет, +)")
        if ax is None:
            fig.legend(*a.get_legend_handles_labels(), loc="outside lower center", ncol=5, fontsize=9,
                       frameon=False)
        else:
            a.legend(loc="lower right", fontsize=8)
        self.title = a.set_title("", fontsize=12)
        d = ax_d
        d.set_ylabel("ΔI, mm")
        d.axhline(0.0, color=C["grey"], lw=1.0)
        self.tol = d.axhline(-mo.ALLOWED_CUTOUT_MM, color=_CUTOUT, lw=1.2, ls="--")
        d.text(1.0, -mo.ALLOWED_CUTOUT_MM, f" {fmt_number(-mo.ALLOWED_CUTOUT_MM, 1)} {_t('mm')}", color=_CUTOUT,
               fontsize=9, va="center", ha="left",
               transform=d.get_yaxis_transform())
        self.stems = LineCollection([], linewidths=2.2, zorder=3)
        d.add_collection(self.stems)
        self.tops = d.scatter(np.zeros(0), np.zeros(0), s=18, facecolors=[], zorder=4)
        self.separators = LineCollection([], colors=C["grey"], linewidths=0.8, linestyles=":", zorder=1)
        d.add_collection(self.separators)
        d.grid(True, axis="y")
        a.set_autoscale_on(False)
        d.set_autoscale_on(False)
        #: what a move changes (for blitting): the sheet and everything over it, the title, the ΔI stems
        self.moving = (self.image, self.frames, self.cuts, self.points, self.ties, self.o, *self.numbers.artists,
                       self.title, self.separators, self.stems, self.tops)
        if result is not None:
            self.update(result)

    def update(self, r: FotoschemaResult) -> None:
        fs = r.fs
        a = self.ax_sheet
        self.image.set_data(r.image)
        # a preview (1 px/mm on ~1.6 screen px) is enlarged by repeating pixels: 2 ms against the filter's 5 ms
        self.image.set_interpolation("nearest" if r.preview else "antialiased")
        if tuple(self.image.get_extent()) != tuple(r.extent_mm):
            self.image.set_extent(r.extent_mm)
        x0, x1, y0, y1 = _sheet_limits(fs.extent_mm)
        _set_limits(a, (x0, x1), (y0, y1))
        self.frames.set_segments(list(fs.frames_mm()))
        self.cuts.set_segments([s.cut_mm for s in fs.seams])
        pts = np.vstack([s.points_mm for s in fs.seams]) if fs.seams else np.zeros((0, 2))
        dI = fs.dI_mm
        cols = np.where(dI < 0, _CUTOUT, _DUPLICATE)
        self.points.set_offsets(pts)
        self.points.set_sizes(12.0 + 260.0 * np.minimum(np.abs(dI), 1.5))
        self.points.set_facecolors(cols)
        bad = np.round(dI, 2) < -mo.ALLOWED_CUTOUT_MM  # as read, to 0.01 mm
        edge = np.where(bad, "black", "white")
        self.points.set_edgecolors(edge)
        self.points.set_linewidths(np.where(bad, 2.0, 0.8))
        ties = np.vstack([T.apply(s.ties.photo_a_mm) for s, T in zip(fs.seams, fs.to_sheet[:-1])])
        self.ties.set_data(ties[:, 0], ties[:, 1])
        o = fs.principal_points_mm()
        self.o.set_data(o[:, 0], o[:, 1])
        self.numbers.set(o, fs.numbers)
        # the resolution is no news for the class: never written in the title (the picture just sharpens)
        self.title.set_text(_t("Fotoschema 1:{m} · m = {rms} mm · {verdict}", m=fmt_count(round(fs.scale.m)),
                              rms=fmt_number(fs.rms_mm, 2),
                              verdict=_t("seams pass") if fs.ok else _t("cut-out > 0.5 mm")))
        # ΔI chart: points grouped by cut
        xs, ticks, labels, seps = [], [], [], []
        x = 0.0
        for k, s in enumerate(fs.seams):
            n = len(s.dI_mm)
            xx = x + np.arange(1, n + 1)
            xs.append(xx)
            ticks.append(x + (n + 1) / 2.0)
            labels.append(_t("cut {a}/{b}", a=s.numbers[0], b=s.numbers[1]))
            x += n + 1.5
            if k < len(fs.seams) - 1:
                seps.append(x - 0.25)
        xs = np.concatenate(xs) if xs else np.zeros(0)
        self.stems.set_segments([np.array([[xi, 0.0], [xi, di]]) for xi, di in zip(xs, dI)])
        self.stems.set_colors(list(cols))
        self.tops.set_offsets(np.column_stack([xs, dI]) if len(xs) else np.zeros((0, 2)))
        self.tops.set_facecolors(cols)
        lim = _nice_up(max(0.7, float(np.max(np.abs(dI))) * 1.15 if dI.size else 0.7))
        self.separators.set_segments([np.array([[sx, -lim], [sx, lim]]) for sx in seps])
        d = self.ax_dI
        _set_limits(d, (0.0, max(x - 0.5, 1.0)), (-lim, lim))
        if getattr(self, "_dI_ticks", None) != (ticks, labels):  # (reading the axis' ticks would mark it changed)
            d.set_xticks(ticks)
            d.set_xticklabels(labels, fontsize=10)
            self._dI_ticks = (ticks, labels)


SHEET_STEP_MM = 20.0  # the sheet's limits are multiples of this, mm: a tilt or relief move keeps them (and ticks)
_DI_LIMITS = (0.7, 1.0, 1.5, 2.0, 3.0, 4.0, 5.0, 7.0, 10.0, 15.0, 20.0, 30.0, 50.0, 70.0, 100.0)


def _sheet_limits(extent_mm) -> tuple:
    """The sheet axes' limits: the mosaic's extent with 3 mm of room, widened to multiples of SHEET_STEP_MM."""
    st = SHEET_STEP_MM
    x0, x1, y0, y1 = extent_mm
    return (math.floor((x0 - 3.0) / st) * st, math.ceil((x1 + 3.0) / st) * st,
            math.floor((y0 - 3.0) / st) * st, math.ceil((y1 + 3.0) / st) * st)


def _nice_up(v: float) -> float:  # the ΔI chart's half-range: the first round value ≥ v
    return next((c for c in _DI_LIMITS if c >= v), float(math.ceil(v)))


def _set_limits(ax, xlim, ylim) -> None:  # only when they change (matplotlib marks even the same as a change)
    if tuple(map(float, ax.get_xlim())) != tuple(map(float, xlim)):
        ax.set_xlim(*xlim, auto=False)
    if tuple(map(float, ax.get_ylim())) != tuple(map(float, ylim)):
        ax.set_ylim(*ylim, auto=False)


# =========================================================================== the live demo
class FotoschemaDemo(LiveDemo):
    """Live single-strip fotoschema: f, scale, tilt, relief and overlap → sheet, seams, m and mean scale.

    While a slider is dragged the sheet is glued at ``preview_px_per_mm``;
    when it has been still for ``settle_s`` seconds, at ``full_px_per_mm``
    (see the module notes).  ``demo.set(...)`` renders at full resolution,
    ``demo.set(..., preview=True)`` at the preview one.
    """

    photo_frames = True  # a move changes the photo: its frames go as JPEG (plots.fast_frames; issue 32)
    title = "The single-strip fotoschema (одномаршрутная фотосхема)"
    hint = ("Raise the relief or the tilt and watch cut-outs (−, vermillion) and duplicates (+, blue) appear along "
            "the cuts; a longer focal length flies higher at the same scale and shrinks the relief mismatches.")
    params = (
        Param("f_mm", "f, mm", 70, 1100, 10, 100, group="Camera",
              help="focal length f; H = f·m (the variants reach 1090 mm)"),
        Param("m", "m (scale 1:m)", 8000, 22000, 100, 12000, group="Camera",
              help="photo scale denominator (the variants reach 21 900)"),
        Param("px_percent", "p_x, %", 56, 80, 1, 60, group="Flight", help="forward overlap"),
        Param("alpha_max_deg", "α max, °", 0, 5, 0.25, 1, group="Flight",
              help="largest tilt of the photos (each is tilted at random up to this)"),
        Param("seed", "seed", 0, 20, 1, 1, kind="int", group="Flight", help="random stream of the tilts"),
        Param("relief_m", "h, relief, m", 0, 200, 5, 30, group="Terrain",
              help="height difference of the ground (the site's hills rescaled)"),
        Param("cut_shape", "cut", kind="choice", options=(("straight", "straight"), ("zigzag", "zigzag"),
                                                           ("curved", "curved")),
              default="straight", group="Mosaic", help="form of the cuts (guide figure 12)"),
    )
    #: sheet resolution while dragging and after release, pixels per sheet mm
    preview_px_per_mm = 1.0
    full_px_per_mm = 2.5
    #: how long a slider must stay still before the full-resolution render, seconds
    settle_s = 0.35
    #: pixels glued per event-loop turn in the full-resolution render (see :meth:`_settle`)
    band_px = 60_000

    # ---- LiveDemo hooks
    def build(self):
        self.view = FotoschemaView()
        self.fig = self.view.fig
        # a move redraws the sheet, its marks, the title and the ΔI stems over the cached axes; the limits are
        # snapped (sheet: 20 mm, ΔI: round values), so most moves keep them and are blitted
        self.animated = self.view.moving

    def compute(self, **v):
        r = self.full_px_per_mm if not self._preview else self.preview_px_per_mm
        return fotoschema_model(v["f_mm"], v["m"], v["alpha_max_deg"], v["relief_m"], v["px_percent"],
                                v["cut_shape"], v["seed"], px_per_mm=r, preview=self._preview)

    def render(self, result: FotoschemaResult):
        self.view.update(result)

    def show(self, result: FotoschemaResult) -> None:
        """Move the artists and draw, then the tables (:func:`aerophoto.widgets.table_after_picture`)."""
        super().show(result)
        table_after_picture(self, self._tables, result)

    def _tables(self, result: FotoschemaResult) -> str:
        fs = result.fs
        H_m = g.flying_height_m(fs.camera.f_mm, fs.m_design)
        notes = [_t("H = f·m = {H} m above the mean ground", H=fmt_count(round(H_m))),
                 _t("ΔI from truth: the ground each neighbour shows at a point of the cut, along the strip")]
        if result.note:
            notes.insert(0, "⚠ " + result.note)
        return (plots.html_table(result.table(), caption="Seams and scale (guide §6)", float_format="{:.3g}",
                                 notes=notes)
                + plots.html_table(fs.seams_table(), caption="Mismatches by cut, mm", float_format="{:.2f}", fold=True)
                + plots.html_table(fs.scale.table(), caption="Partial scales (6.1), M = 10 000", float_format="{:.1f}",
                                   fold=True))

    # ---- preview / full resolution
    def update(self, preview: bool = False) -> None:
        """Recompute and redraw, at the preview resolution if ``preview`` else at full resolution."""
        self._preview = bool(preview)
        super().update()

    def set(self, preview: bool = False, **values):
        """Change parameters from code; full resolution unless ``preview=True``.  Returns self."""
        checked = self._checked(values)
        self.values.update(checked)
        self._sync_controls(checked)
        self.cancel_later()
        self.update(preview=preview)
        return self

    def on_slider(self) -> str:
        """A slider moved: preview now, full resolution once the slider rests (the previous move's note stays up)."""
        self._drop_later()
        self.update(preview=True)
        # without an event loop (a script or a test) the full picture is glued at once
        if self.later(self.settle_s, self._settle):
            return pending_html()
        return ""

    def render_full(self) -> None:
        """Glue the shown preview at full resolution now, in one go (what the settle timer does once the slider
        rests; deterministic, for tests and benchmarks).  Nothing happens if the full picture is shown already."""
        self.cancel_later()
        r = getattr(self, "result", None)
        if r is None or not r.preview:
            return
        steps = mo.sheet_raster_bands(r.fs, r.ground, self.full_px_per_mm, band_px=None)
        self._glue_step(r, steps, False, time.perf_counter())

    def _settle(self) -> None:
        """The slider rests: glue the shown fotoschema again at full resolution, a band per loop turn.

        The strip and its assembly are the preview's (same values, same
        result); only the sheet raster is redone, by
        :func:`aerophoto.mosaic.sheet_raster_bands`.  With a running event
        loop each band (about ``band_px`` pixels, some 20 ms) is one callback
        (:meth:`later`), so a slider moved meanwhile is served after at most
        one band and cancels the rest; without a loop all bands run at once.
        """
        r = getattr(self, "result", None)
        if r is None or not r.preview:
            return
        stepwise = running_loop() is not None
        steps = mo.sheet_raster_bands(r.fs, r.ground, self.full_px_per_mm,
                                      band_px=self.band_px if stepwise else None)
        self._glue_step(r, steps, stepwise, time.perf_counter())

    def _glue_step(self, r: FotoschemaResult, steps, stepwise: bool, t0: float) -> None:
        image, extent, rows_done = next(steps)
        if rows_done < image.shape[0]:
            if stepwise:
                self.later(0.0, lambda: self._glue_step(r, steps, stepwise, t0))
                return
            for image, extent, rows_done in steps:
                pass
        full = dataclasses.replace(r, image=image, extent_mm=extent, px_per_mm=float(self.full_px_per_mm),
                                   preview=False, timings_s={**r.timings_s, "glue": time.perf_counter() - t0})
        self.show(full)  # the note is cleared after it, by LiveDemo.later's callback


# =========================================================================== static sheets
def correction_sheet(fs: mo.Fotoschema, ax=None, *, values: bool = True):
    """The correction sheet (корректурный лист, guide §6, figure 13): the frames, the cuts and ΔI along each.

    Each check point carries its ΔI in mm with its sign (− cut-out,
    + duplicate), written beside the cut; cut-outs beyond 0.5 mm are boxed.
    Returns the Axes.
    """
    fig, ax = plots.new_axes(ax, figsize=(10.0, 4.6))
    C = plots.COLORS
    ax.set_aspect("equal")
    ax.grid(False)
    for fr in fs.frames_mm():
        ax.plot(fr[:, 0], fr[:, 1], color=C["grey"], lw=0.8)
    o = fs.principal_points_mm()
    for k, p in enumerate(o):
        ax.plot(*p, "+", color=C["black"], ms=9, mew=1.5)
        ax.annotate(str(fs.numbers[k]), p, xytext=(4, 4), textcoords="offset points", fontsize=10, fontweight="bold")
    for s in fs.seams:
        ax.plot(s.cut_mm[:, 0], s.cut_mm[:, 1], color=_CUT, lw=1.6, path_effects=_CUT_EDGE)
        for p, d in zip(s.points_mm, s.dI_mm):
            col = _CUTOUT if d < 0 else _DUPLICATE
            ax.plot(*p, "o", color=col, ms=4)
            if values:
                bad = round(float(d), 2) < -mo.ALLOWED_CUTOUT_MM
                ax.annotate(fmt_signed(d, 2), p, xytext=(5, 0), textcoords="offset points", va="center", fontsize=9,
                            color=col, fontweight="bold" if bad else "normal",
                            bbox=dict(boxstyle="square,pad=0.1", fc="white", ec=col) if bad else None)
    x0, x1, y0, y1 = fs.extent_mm
    ax.set_xlim(x0 - 5, x1 + 12)
    ax.set_ylim(y0 - 5, y1 + 5)
    ax.set_xlabel("sheet mm")
    ax.set_title(_t("Correction sheet (корректурный лист): ΔI in mm along each cut · m = {rms} mm, n = {n}",
                    rms=fmt_number(fs.rms_mm, 2), n=fmt_count(fs.dI_mm.size)))
    return ax


# the finished sheet lives in its own module; its names are this module's too (demos.fotoschema.sheet_figure)
from .fotoschema_sheet import (  # noqa: E402  (after the names it imports from here)
    TRIM_MM, _made_by, _own_prints, _own_sheet_image, _paper_for, export_sheet, finished_sheet, own_numbers, own_prints,
    own_sheet_figure, own_sheet_image, sheet_figure, sheet_paper, sheet_size_mm, student_sheet)
