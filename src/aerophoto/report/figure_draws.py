"""The chapters' figures for the note, each drawn with the plotting functions the demos and notebooks use.

One function per figure, ``draw(variant, own) -> Figure`` (``own``: the student's values it shows, plain data), registered in :data:`FIGURES` (chapter → specs, see
:class:`aerophoto.report.figures.FigureSpec`).  The base of every figure is the package's own view or figure
builder with ``ax`` given (:mod:`aerophoto.demos`); where the note shows the student's *own* numbers on it (the
points and displacements they measured and computed, their resected station), those are drawn over it from the
values the writer passes — never from a reference solution.  What would be a raster but is not a photo (a DEM's
error, a class map, a colour bar) is hidden or drawn as contours, so that the PDF holds the photos as its only
images.
"""

from __future__ import annotations

import numpy as np

from .figures import FigureSpec, new_figure

__all__ = ["FIGURES", "specs_for"]

def _hide_images(ax) -> None:
    for im in ax.images:
        im.set_visible(False)


# =========================================================================== §2 (chapter 01)
def flight_plan(v, own):
    from .. import flight
    from ..demos.flight_plan import FlightPlanView

    fig = new_figure((9.0, 4.6), layout="constrained")
    a1, a2 = fig.subplots(1, 2, gridspec_kw={"width_ratios": [1.25, 1]})
    view = FlightPlanView(flight.layout(flight.plan(v)), ax=(a1, a2))
    view.ax_plan.set_title("")
    handles = view.legend.legend_handles
    labels = [t.get_text() for t in view.legend.get_texts()]
    view.legend.remove()
    fig.legend(handles, labels, loc="outside lower center", ncol=3, fontsize=9, frameon=False)
    return fig


# =========================================================================== §3 (chapter 02)
def rough_mosaic(v, own):
    from .. import geometry as g
    from .. import quality as q
    from ..demos.quality import QualityResult, RoughMosaicView
    from ..labs.ch02 import lab_strip

    strip = lab_strip(v)
    dem = g.FlatTerrain(strip.ground_Z_m)
    cam = strip.camera
    outlines = np.array([g.footprint(cam, s.pose, strip.ground_Z_m)[:, :2] for s in strip.shots])
    outlines = np.concatenate([outlines, outlines[:, :1]], axis=1)
    o = np.array([g.photo_to_dem(cam, s.pose, np.zeros(2), dem)[:2] for s in strip.shots])
    lo, hi = outlines.reshape(-1, 2).min(axis=0), outlines.reshape(-1, 2).max(axis=0)
    pad = 0.05 * float(max(hi - lo))
    ext = (lo[0] - pad, hi[0] + pad, lo[1] - pad, hi[1] + pad)
    res = QualityResult(strip, q.assess_flight(strip, dem), np.ones((2, 2, 3)), ext, outlines, o)
    fig = new_figure((9.0, 4.2))
    view = RoughMosaicView(res, ax=fig.add_subplot())
    view.image.set_visible(False)
    view.title.set_text("")
    return fig


def crab_limit(v, own):
    from ..demos.quality import crab_limit_plot

    fig = new_figure((7.0, 3.6))
    crab_limit_plot(fig.add_subplot(), f_mm=float(v.f_mm))
    return fig


# =========================================================================== §4–§5 (chapters 03–04)
def _sheet_photo(ax, sheet):
    from ..demos.site_views import show_photo

    show_photo(sheet.photo(), ax, points=False, title="")


def relief_points(v, own):
    from .. import plots
    from ..labs.displacement import relief_sheet

    sheet = relief_sheet(int(v.i))
    fig = new_figure((6.4, 6.4))
    ax = fig.add_subplot()
    _sheet_photo(ax, sheet)
    _points_with_arrows(ax, sheet.names, own.get("xy"), own.get("centre"), own.get("d"), "n")
    plots.mark_points(ax, {"o": (0.0, 0.0)})
    return fig


def tilt_points(v, own):
    from .. import plots
    from ..labs.displacement import tilt_sheet

    sheet = tilt_sheet(int(v.i))
    fig = new_figure((6.4, 6.4))
    ax = fig.add_subplot()
    _sheet_photo(ax, sheet)
    c = own.get("centre")
    if c is not None:
        u = np.asarray(c, float) / max(float(np.hypot(*c)), 1e-9)
        ax.plot([-95 * u[0], 95 * u[0]], [-95 * u[1], 95 * u[1]], color=plots.COLORS["nadir"], lw=1.0, ls=":",
                label="principal vertical")
        w = np.array([-u[1], u[0]])
        ax.plot([c[0] - 95 * w[0], c[0] + 95 * w[0]], [c[1] - 95 * w[1], c[1] + 95 * w[1]],
                color=plots.COLORS["isocentre"], lw=1.0, ls="--", label="line h_c h_c")
    _points_with_arrows(ax, sheet.names, own.get("xy"), c, own.get("d"), "c")
    plots.mark_points(ax, {"o": (0.0, 0.0)})
    ax.set_xlim(-90, 90)
    ax.set_ylim(-90, 90)
    return fig


def _points_with_arrows(ax, names, xy, centre, d, centre_name):
    """The student's points, the rays from ``centre`` and their displacements ``d`` along them (arrows ×k)."""
    from .. import plots

    if xy is None or centre is None:
        return
    P = np.asarray(xy, float)
    C = np.asarray(centre, float)
    col = plots.COLORS
    for p in P:
        ax.plot([C[0], p[0]], [C[1], p[1]], color=col["grey"], lw=0.7, ls="--")
    ax.plot(P[:, 0], P[:, 1], "o", ms=7, mfc="none", mec=col["yellow"], mew=1.8)
    for name, p in zip(names, P):
        ax.annotate(str(name), p, xytext=(6, 5), textcoords="offset points", color="white", fontsize=11,
                    fontweight="bold")
    plots.mark_points(ax, {centre_name: (float(C[0]), float(C[1]))})
    if d is not None:
        dd = np.asarray(d, float)
        r = P - C
        u = r / np.maximum(np.hypot(r[:, 0], r[:, 1]), 1e-9)[:, None]
        big = float(np.max(np.abs(dd))) if len(dd) else 0.0
        k = 10 ** int(np.floor(np.log10(12.0 / big))) if big > 0 else 1
        vec = u * (dd * k)[:, None]
        ax.quiver(P[:, 0], P[:, 1], vec[:, 0], vec[:, 1], angles="xy", scale_units="xy", scale=1.0,
                  color=col["relief"], width=0.006, zorder=6)
        ax.text(0.02, 0.02, f"× {k}", transform=ax.transAxes, color="white", fontsize=11, fontweight="bold")


# =========================================================================== §6 (chapter 05)
def prints(v, own):
    from ..demos import fotoschema as F

    photos = F.own_prints(v)
    fig = new_figure((10.0, 2.9))
    axes = fig.subplots(1, len(photos))
    for ax, ph in zip(axes, photos):
        ax.imshow(ph.image, cmap="gray", vmin=0, vmax=1, extent=ph.extent_mm, interpolation="none")
        ax.set_axis_off()
        ax.set_title(f"photo {ph.number}", fontsize=11)
    return fig


def fotoschema_cuts(v, own):
    from ..demos.fotoschema import own_sheet_figure

    fig = _one_axes(own_sheet_figure, v, (10.0, 5.2))
    fig.axes[0].images[0].set_interpolation("none")
    return fig


def correction(v, own):
    from ..demos.fotoschema import correction_sheet
    from ..labs.ch05 import own_fotoschema

    fig = new_figure((10.0, 4.4))
    ax = fig.add_subplot()
    correction_sheet(own_fotoschema(v).fs, ax, values=False)
    ax.set_title("")
    ax.set_xlabel("along the strip, mm")
    ax.set_ylabel("across, mm")
    return fig


# =========================================================================== §7 (chapter 06) and §13 (chapter 12)
def _one_axes(draw, v, figsize):
    """``draw(v, ax=…)`` of the demos on a figure of one axes, its title left to the note's caption."""
    fig = new_figure(figsize)
    ax = fig.add_subplot()
    draw(v, ax=ax)
    ax.set_title("")
    return fig


def strip_site(v, own):
    from ..demos.reduction import own_site_figure

    return _one_axes(own_site_figure, v, (9.0, 4.6))


def free_strip(v, own):
    from ..demos.reduction import own_strip_figure

    return _one_axes(own_strip_figure, v, (9.0, 4.8))


def zhukov(v, own):
    from .. import triangulation as tri
    from ..demos.reduction import AccumulationView

    fig = new_figure((7.2, 4.2))
    b_mm = v.frame_mm * (100.0 - v.px_percent) / 100.0
    study = tri.accumulation_study(seeds=range(8), f_mm=float(v.f_mm), m=float(v.m), M=float(v.M),
                                   overlap_percent=float(v.px_percent))
    AccumulationView(study, ax=fig.add_subplot(), k_i=float(v.m) / float(v.M), b_mm=b_mm)
    return fig


# =========================================================================== §8 (chapter 07)
def anaglyph(v, own):
    from ..demos.stereo_figures import anaglyph_figure
    from ..labs.ch07 import lab_images, stereo_lab

    images = lab_images(stereo_lab(v), 1024)
    fig = new_figure((7.0, 4.8))
    ax = fig.add_subplot()
    anaglyph_figure(images, size_mm=(70.0, 50.0), ax=ax)
    ax.set_title("")
    for im in ax.images:
        im.set_interpolation("none")
    return fig


def pair_geometry(v, own):
    from ..demos.stereo_figures import pair_geometry_figure
    from ..labs.ch07 import stereo_lab

    lab = stereo_lab(v)
    fig = new_figure((8.6, 4.6))
    H = float(v.f_mm) / 1000.0 * float(v.m)
    pair_geometry_figure(fig.add_subplot(), B_m=float(lab.B_m), H_m=H, f_mm=float(v.f_mm), h_m=0.3 * H)
    fig.axes[0].set_title("")
    return fig


# =========================================================================== §9 (chapter 08)
def interpretation_photo(v, own):
    from ..demos.interpretation import lab_figure
    from ..labs.ch08 import lab_photo

    fig = new_figure((6.6, 6.6))
    lab_figure(lab_photo(v), ax=fig.add_subplot())
    return fig


# =========================================================================== §10 (chapter 09)
def grids(v, own):
    from .. import geometry as g
    from ..demos.plan_correction import PlanCorrectionResult, PlanCorrectionView
    from ..labs.ch09 import plan_correction_lab
    from ..projective import grids as pg
    from ..projective import locate

    lab = plan_correction_lab(v)
    pair = lab.grid_pair()
    k = 1000.0 / lab.M

    def photo(xy):
        return g.ground_to_photo(lab.camera, lab.pose, np.column_stack([xy, np.zeros(len(xy))]))

    changes = lab.scene.changes()
    photo_changes = [photo(f.outline_m()) for f in changes]
    loc = locate(pair.photo_nodes, np.vstack(photo_changes))
    flat = pg.place(pair.plan_nodes, loc)
    carried = np.split(flat, np.cumsum([len(p) for p in photo_changes])[:-1])
    truth = [f.outline_m() * k for f in changes]
    res = PlanCorrectionResult(lab.scene, lab.camera, lab.pose, lab.M, pair,
                               [photo(f.outline_m()) for f in lab.scene.features if f.status == "kept"],
                               photo_changes, [f.outline_m() * k for f in lab.scene.old()], carried, truth,
                               np.zeros(1), np.ones(1, bool), 0.0)
    fig = new_figure((9.6, 4.8))
    a1, a2 = fig.subplots(1, 2)
    view = PlanCorrectionView(ax=(a1, a2))
    view.update(res)
    a1.set_title("")
    a2.set_title("")
    return fig


# =========================================================================== §11 (chapter 10)
def resection(v, own):
    from .. import control as c
    from ..demos.control import ResectionResult, ResectionView
    from ..labs.ch10 import resection_lab

    lab = resection_lab(v)
    K = lab.known[["X, m", "Y, m"]].to_numpy(float)
    P = np.asarray(own.get("station"), float) if own.get("station") is not None else K[:3].mean(axis=0)
    centre, radius = c.danger_circle(K[0], K[1], K[2])
    res = ResectionResult(K, P, np.zeros((0, 2)), None, "", None, centre, radius, 0.0)
    fig = new_figure((7.0, 6.0))
    view = ResectionView(ax=fig.add_subplot())
    view.origin = np.floor(K.min(axis=0) / 1000.0) * 1000.0
    view.update(res)
    for t, name in zip(view.labels, lab.known.index):
        t.set_text(str(name))
    view.ax.set_title("")
    x0, y0 = view.origin
    view.ax.set_xlabel(f"Y (east) − {y0:.0f}, m")
    view.ax.set_ylabel(f"X (north) − {x0:.0f}, m")
    view.ax.legend(handles=[view.circle, view.known, view.station], loc="upper left", fontsize=9)
    return fig


def control_design(v, own):
    from ..demos.control import ControlDesignView, control_design_model

    fig = new_figure((8.6, 4.4))
    view = ControlDesignView(ax=fig.add_subplot())
    view.update(control_design_model(m=float(v.m), f_mm=float(v.f_mm), M=float(v.M), n_strips=3, n_photos=12))
    view.ax.set_title("")
    view.ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.16), ncol=2, fontsize=9, frameon=False)
    return fig


# =========================================================================== §12 (chapter 11)
def rectified(v, own):
    from ..demos.rectification import rectified_figure
    from ..labs.ch11 import rectification_lab

    fig = rectified_figure(rectification_lab(v), n_px=768)
    for ax in list(fig.axes[2:]):  # the colour bar of the arrows' heights: a raster that is not a photo
        ax.remove()
    for ax in fig.axes:
        ax.set_title("")
        for im in ax.images:
            im.set_interpolation("none")
    if getattr(fig, "_suptitle", None) is not None:
        fig._suptitle.set_text("")
    return fig


# =========================================================================== §14 (chapter 13)
def soil_contours(v, own):
    from matplotlib.colors import ListedColormap

    from ..demos.spectral_explorer import plot_patch
    from ..labs.ch13 import patch_of
    from ..site.soils import SOIL_CLASSES

    patch = patch_of(v)
    fig = new_figure((10.0, 4.8))
    a, b = fig.subplots(1, 2)
    plot_patch(patch, ax=(a, b))
    _hide_images(b)
    X0, X1, Y0, Y1 = (e / 1000 for e in patch.extent_m)
    ny, nx = patch.soil_map.shape
    x = X0 + (np.arange(nx) + 0.5) * (X1 - X0) / nx
    y = Y0 + (np.arange(ny) + 0.5) * (Y1 - Y0) / ny
    levels = np.arange(-0.5, len(SOIL_CLASSES) + 0.5)
    cmap = ListedColormap([c.colour for c in SOIL_CLASSES.values()])
    b.contourf(x, y, patch.soil_map, levels=levels, cmap=cmap)
    b.contour(x, y, patch.soil_map, levels=levels, colors="black", linewidths=0.6)
    b.set_xlim(X0, X1)
    b.set_ylim(Y0, Y1)
    b.set_aspect("equal")
    a.set_title("")
    b.set_title("")
    for im in a.images:
        im.set_interpolation("none")
    return fig


def soil_facts(v, own):
    from ..demos.spectral_explorer import plot_soil_facts

    fig = new_figure((9.0, 6.4))
    plot_soil_facts(fig.subplots(2, 2))
    return fig


# =========================================================================== the articles (chapters 14–17)
def accumulation(v, own):
    from .. import gradebook
    from ..demos.bundle_views import accumulation_figure

    fig = new_figure((7.6, 4.6))
    accumulation_figure(gradebook.task_inputs("task-14-2", v), ax=fig.add_subplot())
    return fig


def block(v, own):
    from ..demos.bundle_views import block_figure
    from ..labs.ch15 import student_block

    fig = new_figure((8.6, 5.0))
    ax = fig.add_subplot()
    block_figure(student_block(v), ax=ax)
    _hide_images(ax)
    for other in fig.axes[1:]:
        other.remove()
    ax.set_title("")
    return fig


def dem_contours(v, own):
    from ..demos.dem_contours import ContourView, contour_frame
    from ..labs.ch16 import sheet_of

    sheet = sheet_of(v)
    frame = contour_frame((sheet.X0_m, sheet.Y0_m), spacing_m=0.007 * float(v.m), structural=True, mz_m=0.12,
                          interval_m=1.0)
    fig = new_figure((6.2, 6.0))
    view = ContourView(frame, ax=fig.add_subplot(), colorbar=False)
    _hide_images(view.ax)
    view.title.set_text("")
    return fig


def budget(v, own):
    from .. import gradebook
    from ..demos.error_budget import budget_figure

    fig = new_figure((8.0, 4.6), layout="none")
    ax = fig.add_axes([0.42, 0.12, 0.55, 0.8])
    budget_figure(gradebook.task_inputs("task-17-3", v).budget(), ax=ax)
    ax.set_title("")
    return fig


def _s(chapter, name, draw, **kw):
    return FigureSpec(chapter, name, draw, **kw)


#: chapter number → its figures, in the order the writers place them
FIGURES = {
    "01": (_s("01", "flight_plan", flight_plan, passed=("task-01-1", "task-01-2")),),
    "02": (_s("02", "rough_mosaic", rough_mosaic, passed=("task-02-1",)),
           _s("02", "crab_limit", crab_limit, passed=("task-02-2",), width=0.75)),
    "03": (_s("03", "relief_points", relief_points, photos=1, passed=("task-03-1", "task-03-2"), width=0.7),),
    "04": (_s("04", "tilt_points", tilt_points, photos=1, passed=("task-04-1", "task-04-2", "task-04-3"),
              width=0.7),),
    "05": (_s("05", "prints", prints, photos=4, attempted=("task-05-1",)),
           _s("05", "fotoschema_cuts", fotoschema_cuts, photos=1, attempted=("task-05-1",)),
           _s("05", "correction", correction, passed=("task-05-1",))),
    "06": (_s("06", "strip_site", strip_site, photos=1, attempted=("task-06-1",)),
           _s("06", "free_strip", free_strip, attempted=("task-06-1",))),
    "07": (_s("07", "anaglyph", anaglyph, photos=1, attempted=("task-07-1",), width=0.75),
           _s("07", "pair_geometry", pair_geometry, passed=("task-07-1",), width=0.85)),
    "08": (_s("08", "interpretation_photo", interpretation_photo, photos=1, attempted=("task-08-1",), width=0.7),),
    "09": (_s("09", "grids", grids, passed=("task-09-1", "task-09-2")),),
    "10": (_s("10", "resection", resection, passed=("task-10-1",), width=0.75),
           _s("10", "control_design", control_design, attempted=("task-10-1",))),
    "11": (_s("11", "rectified", rectified, photos=2, attempted=("task-11-2",)),),
    "12": (_s("12", "zhukov", zhukov, passed=("task-12-1",), width=0.8),
           _s("12", "free_strip", free_strip, attempted=("task-12-2",))),
    "13": (_s("13", "soil_contours", soil_contours, photos=1, attempted=("task-13-3",)),
           _s("13", "soil_facts", soil_facts, attempted=("task-13-2",), width=0.85)),
    "14": (_s("14", "accumulation", accumulation, passed=("task-14-2",), width=0.85),),
    "15": (_s("15", "block", block, attempted=("task-15-1",)),),
    "16": (_s("16", "dem_contours", dem_contours, attempted=("task-16-2",), width=0.7),),
    "17": (_s("17", "budget", budget, passed=("task-17-3",), width=0.85),),
}


def specs_for(chapter: str) -> dict:
    """``{name: FigureSpec}`` of a chapter (empty for a chapter without figures)."""
    return {s.name: s for s in FIGURES.get(str(chapter), ())}
