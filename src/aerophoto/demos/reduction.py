"""The reduction explorer: a free radial strip, its error triangles and its reduction (chapters 06, 12).

The pure part, :func:`reduction_model`, flies a strip over the virtual site
(:mod:`aerophoto.simulate`), pricks the points (:func:`aerophoto.triangulation.design_points`),
measures the direction templates with a pricking error, lays the free strip
and reduces it to the plan (guide §7, §13).  The views draw what the guide
draws on tracing paper:

* :class:`TemplateView` — one direction template (восковка направлений,
  guide figure 22): the rays from the working centre to every pricked point;
* :class:`StripView` — the laid strip (figures 23–24): the rays, the points,
  the error triangles (enlarged so they can be seen), the correction arrows
  v = r·(k − 1) from the central working centre, and the control points of
  the base carried back into the strip's frame;
* :class:`CoefficientView` — the reduction coefficient of every base with the
  mean and the tolerance band (table 12);
* :class:`ReductionView` — the strip and the coefficients side by side.

:class:`ReductionDemo` binds sliders for f, the photo scale, the free strip's
scale, the pricking error, the tilt and the central point to them.  It opens
on the guide's worked example, variant 00 (f = 100 mm, 1:12 000), on a strip
of four photos 36 … 39 as in guide §13, and its sliders reach every variant
(f up to 1100 mm, m up to 22 000); where a tilt would carry the photos off the
10 × 5 km site it is reduced to the largest that keeps them on it, and the table
says so.

For the student's own strip (chapters 06 and 12, :mod:`aerophoto.labs.ch06`):
:func:`own_site_figure`, :func:`own_templates_figure` and :func:`own_strip_figure`
draw what the student works from — their photos over the site, their
templates, their laid strip — without the error triangles, coefficients or
corrections they compute.  The student's tables are in the geodetic convention
(x up, y right along the strip); the laid strip is drawn with those axes.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
from matplotlib.collections import LineCollection, PolyCollection

from .. import geometry as g
from .. import plots
from .. import triangulation as tri
from .._validate import check_int_range, check_range
from ..i18n import t
from ..i18n.numfmt import fmt_number, fmt_scale
from ..widgets import LiveDemo, Param

__all__ = [
    "ReductionResult",
    "reduction_model",
    "strip_design",
    "TemplateView",
    "StripView",
    "CoefficientView",
    "ReductionView",
    "EndsView",
    "SiteStripView",
    "AccumulationView",
    "ReductionDemo",
    "TRIANGLE_ENLARGEMENT",
    "own_site_figure",
    "own_templates_figure",
    "own_strip_figure",
]

#: error triangles are drawn this many times larger than they are (about their centroid)
TRIANGLE_ENLARGEMENT = 100.0

_KIND_STYLE = {
    "centre": dict(marker="s", color=plots.COLORS["black"], ms=7, mfc="none", mew=1.8),
    "orienting": dict(marker="o", color=plots.COLORS["blue"], ms=7, mfc="none", mew=1.6),
    "tie": dict(marker=".", color=plots.COLORS["green"], ms=8),
    "control": dict(marker="^", color=plots.COLORS["control"], ms=10, mfc="none", mew=2.0),
}
_KIND_LABEL = {
    "centre": "working centres",
    "orienting": "orienting points",
    "tie": "tie points",
    "control": "control points",
}


# =========================================================================== model
@dataclass(frozen=True)
class ReductionResult:
    """What the reduction explorer shows.

    Attributes
    ----------
    strip : aerophoto.simulate.Strip
        The simulated flight (true poses).
    templates : triangulation.Templates
    free : triangulation.FreeStrip
    reduction : triangulation.Reduction
    params : dict
        The inputs (f_mm, m, scale_ratio, pricking_mm, centre, max_tilt_deg, n_photos, seed, M).
    note : str
        A remark on the inputs (e.g. a central point beyond the last photo).
    """

    strip: object
    templates: tri.Templates
    free: tri.FreeStrip
    reduction: tri.Reduction
    params: dict
    note: str = ""

    @property
    def k(self) -> float:
        return self.reduction.k

    def summary(self):
        """Headline numbers: k, spread, largest triangle side, largest control residual, RMS error."""
        import pandas as pd

        red, fs = self.reduction, self.free
        pts = fs.points
        inner = pts.mask("orienting") | pts.mask("centre")
        rows = [
            ("mean reduction coefficient k", "", red.k),
            ("largest |Δk| (spread)", "", red.coefficients.spread),
            ("bases within tolerance", "", t("{done} of {total}", done=int(red.coefficients.ok.sum()),
                                              total=len(red.coefficients.k))),
            ("largest error-triangle side", "mm", fs.max_triangle_side_mm),
            ("largest control residual", "mm", red.max_control_residual_mm),
            ("RMS error, orienting points and centres", "mm", float(np.sqrt(np.mean(red.errors_mm[inner] ** 2)))),
            ("largest correction v", "mm", float(np.max(np.abs(red.corrections.v_mm)))),
        ]
        return pd.DataFrame(rows, columns=["quantity", "unit", "value"]).set_index("quantity")


@functools.lru_cache(maxsize=16)
def strip_design(f_mm: float, m: float, max_tilt_deg: float = 0.0, n_photos: int = 5, seed: int = 0,
                 px_percent: float = 60.0, first_number: int = 1):
    """The strip over the virtual site and its pricked points (cached: sliders that do not change them are fast).

    Returns ``(site, strip, points)``: :func:`aerophoto.site.get_site`, a
    strip of ``n_photos`` flown along +X through the site's centre at 1:m
    with p_x = 60 % and tilts up to ``max_tilt_deg`` (seeded; reduced to the
    largest that keeps the photos on the site, :func:`aerophoto.labs.own.tilt_that_fits`
    — compare ``strip.imperfections.max_tilt_deg``), and
    :func:`aerophoto.triangulation.design_points` on it (the site's catalogue
    where it has a point at a design position).
    """
    from .. import simulate, site as site_mod
    from ..labs.own import tilt_that_fits

    s = site_mod.get_site()
    cam = g.Camera(f_mm)
    tilt = tilt_that_fits(s, cam, m, px_percent, n_photos, max_tilt_deg)
    imp = simulate.Imperfections(max_tilt_deg=tilt, seed=seed)
    strip = simulate.strip_over_site(s, cam, m, px_percent, n_photos, imperfections=imp, first_number=first_number)
    pts = tri.design_points(cam, strip.poses, s, catalogue=s.catalogue,
                            photo_numbers=[sh.number for sh in strip.shots])
    return s, strip, pts


def reduction_model(f_mm: float = 100.0, m: float = 12000.0, scale_ratio: float = 0.96, pricking_mm: float = 0.1,
                    centre: int = 3, max_tilt_deg: float = 0.0, n_photos: int = 5, seed: int = 0,
                    M: float = 10000.0, first_number: int = 1) -> ReductionResult:
    """A free strip over the virtual site, laid and reduced (guide §13 steps 2–9).

    Parameters
    ----------
    f_mm : focal length f, mm (50 … 1100: the variants reach 1090 mm)
    m : photo scale denominator (1:m), 5000 … 22000 (the variants reach 21 900); a strip of
        five photos fits the 10 × 5 km site up to 1:19 500, four up to 1:22 000
    scale_ratio : the free strip's scale as a fraction of the plan's (the
        template's arbitrary scale; k ≈ 1/scale_ratio), 0.5 … 1.5
    pricking_mm : RMS pricking error on the photos, mm (guide: 0.1), 0 … 0.5
    centre : the central working centre, 1 … n_photos (numbered along the
        strip; a larger number is taken as the last photo, with a note)
    max_tilt_deg : largest tilt α of the photos, degrees (0 … 5); reduced, with a note, where the
        photos would leave the site
    n_photos : photos in the strip, 3 … 7
    seed : seed of the tilts and the pricking errors
    M : plan scale denominator (1:M)
    first_number : the first photo's number (guide §13 numbers its photos 36 … 39)
    """
    check_range("f_mm", f_mm, 50.0, 1100.0, unit="mm")
    check_range("m", m, 5000.0, 22000.0)
    check_range("scale_ratio", scale_ratio, 0.5, 1.5)
    check_range("pricking_mm", pricking_mm, 0.0, 0.5, unit="mm")
    check_range("max_tilt_deg", max_tilt_deg, 0.0, 5.0, unit="degrees")
    n = check_int_range("n_photos", n_photos, 3, 7)
    c = check_int_range("centre", centre, 1, 7)
    note = ""
    if c > n:
        note = f"centre {c} is beyond the strip's {n} photos: the last working centre is used"
        c = n
    fn = check_int_range("first_number", first_number, 1, 100000)
    _site, strip, pts = strip_design(float(f_mm), float(m), float(max_tilt_deg), n, int(seed), 60.0, fn)
    flown = strip.imperfections.max_tilt_deg
    if flown < max_tilt_deg - 1e-9:
        H = g.flying_height_m(f_mm, m)
        tilt_note = (f"α max reduced from {max_tilt_deg:g}° to {flown:.2f}°: at H = {fmt_number(H, 0)} m a larger "
                     "tilt would carry the photos off the 10 × 5 km site")
        note = f"{note}; {tilt_note}" if note else tilt_note
    tm = tri.measure_templates(strip.camera, strip.poses, pts, pricking_mm=pricking_mm, seed=int(seed))
    fs = tri.lay_free_strip(tm, scale_ratio=scale_ratio, M=M)
    red = tri.reduce_strip(fs, M=M, centre=c - 1)
    params = dict(f_mm=f_mm, m=m, scale_ratio=scale_ratio, pricking_mm=pricking_mm, centre=c,
                  max_tilt_deg=max_tilt_deg, n_photos=n, seed=seed, M=M, first_number=fn)
    return ReductionResult(strip, tm, fs, red, params, note)


# =========================================================================== views
class TemplateView:
    """One direction template (guide figure 22): rays from the working centre, on the photo (mm)."""

    def __init__(self, templates: tri.Templates | None = None, t: int = 1, ax=None, labels: bool = True,
                 legend: bool = True):
        self.fig, self.ax = plots.new_axes(ax, figsize=(5.6, 5.4))
        a = self.ax
        a.set_aspect("equal")
        a.set_xlabel("x, mm")
        a.set_ylabel("y, mm")
        self.frame = plots.photo_frame(a, g.Camera(), label="photo frame", lw=1.0)
        self.rays = LineCollection([], colors=plots.COLORS["grey"], linewidths=1.0)
        a.add_collection(self.rays)
        self.initial = LineCollection([], colors=plots.COLORS["orange"], linewidths=2.4,
                                      label="initial directions (orange)")
        a.add_collection(self.initial)
        self.marks = {k: a.plot([], [], linestyle="none", label=_KIND_LABEL[k], **st)[0] for k, st in _KIND_STYLE.items()}
        (self.own,) = a.plot([], [], "s", color=plots.COLORS["black"], ms=11, mfc=plots.COLORS["yellow"], mew=1.8,
                             zorder=6)
        self.labels = labels
        self.texts = []
        if legend:
            a.legend(loc="upper center", fontsize=8, ncol=2, bbox_to_anchor=(0.5, -0.14), frameon=False)
        if templates is not None:
            self.update(templates, t)

    def update(self, templates: tri.Templates, t: int = 1) -> None:
        cam = templates.camera
        c = cam.corners_mm()
        c = np.vstack([c, c[:1]])
        self.frame.set_data(c[:, 0], c[:, 1])
        pts = templates.points
        xy = templates.xy_mm[t]
        own = pts.centre_index[t]
        C = xy[own]
        idx, _d = templates.rays(t)
        cent = set(pts.centre_index.tolist())
        self.rays.set_segments([[C, xy[i]] for i in idx if i not in cent])
        self.initial.set_segments([[C, xy[i]] for i in idx if i in cent])
        for k, line in self.marks.items():
            sel = [i for i in idx if pts.kinds[i] == k] + ([own] if k == "centre" else [])
            line.set_data(xy[sel, 0], xy[sel, 1])
        self.own.set_data([C[0]], [C[1]])
        items = [(pts.names[i], xy[i]) for i in list(idx) + [own]] if self.labels else []
        _place_labels(self.ax, self.texts, items, xytext=(4, 4), fontsize=9)
        h = cam.half_mm * 1.05
        self.ax.set_xlim(-h, h)
        self.ax.set_ylim(-h, h)
        self.ax.set_title(f"Template of photo {pts.photo_numbers[t]}")


def _place_labels(ax, pool: list, items, **kw) -> None:
    """Move the Text artists of ``pool`` to ``items`` = [(text, (x, y)), ...]; make more only if needed, hide extras."""
    for j, (text, xy) in enumerate(items):
        if j < len(pool):
            t = pool[j]
            t.set_text(text)
            t.xy = (float(xy[0]), float(xy[1]))
            t.set_visible(True)
        else:
            pool.append(ax.annotate(text, (float(xy[0]), float(xy[1])), textcoords="offset points", **kw))
    for t in pool[len(items):]:
        t.set_visible(False)


_MAX_ARROWS = 160


def _set_limits(ax, xlim, ylim, snap: bool = False) -> None:
    """Set the limits only where they change (unchanged limits keep a live demo's axes in its cached background);
    ``snap``: round them outwards (:func:`aerophoto.plots.snapped_limits`), so that small moves keep them."""
    if snap:
        xlim, ylim = plots.snapped_limits(*xlim), plots.snapped_limits(*ylim)
    if ax.get_autoscalex_on() or tuple(map(float, ax.get_xlim())) != tuple(map(float, xlim)):
        ax.set_xlim(*xlim)
    if ax.get_autoscaley_on() or tuple(map(float, ax.get_ylim())) != tuple(map(float, ylim)):
        ax.set_ylim(*ylim)


def _nice_factor(x: float) -> float:
    """The largest of 1, 2, 5 × 10^k not above x (at least 1): a readable exaggeration factor."""
    if not np.isfinite(x) or x <= 1.0:
        return 1.0
    e = math.floor(math.log10(x))
    for mnt in (5.0, 2.0, 1.0):
        if mnt * 10**e <= x:
            return mnt * 10**e
    return 10.0**e


def _set_arrows(q, xy, uv) -> None:
    """Move a quiver's arrows in place: positions ``xy`` (k, 2), vectors ``uv`` (k, 2), k ≤ its size.

    A Quiver keeps its number of arrows; the unused ones get NaN vectors (not drawn).
    """
    n = q.N
    k = min(len(xy), n)
    XY = np.zeros((n, 2))
    UV = np.full((n, 2), np.nan)
    XY[:k] = xy[:k]
    UV[:k] = uv[:k]
    if k:
        XY[k:] = xy[0]
    q.set_offsets(XY)
    q.XY = XY
    q.X, q.Y = XY[:, 0], XY[:, 1]
    q.set_UVC(UV[:, 0], UV[:, 1])


def _triangle_polys(fs: tri.FreeStrip, enlarge: float) -> list:
    polys = []
    for V in fs.triangle_mm:
        if not np.all(np.isfinite(V)):
            continue
        c = V.mean(axis=0)
        polys.append(c + enlarge * (V - c))
    return polys


class StripView:
    """The laid free strip (guide figures 23–24) with error triangles and reduction arrows.

    ``update(free_strip, reduction=None)`` moves every artist: template rays,
    the points by kind, the error triangles enlarged about their centroids
    (by a round factor that makes the largest about 5 % of the strip; shown
    in the corner; :data:`TRIANGLE_ENLARGEMENT` when they vanish), and — with a
    reduction — the correction arrows v = r·(k − 1) from the central working
    centre (exaggerated by a round factor so the longest is about a sixth of
    the strip) and the base's control points carried into the strip frame
    (where the reduced control points should land).  Also draws an
    :class:`~aerophoto.triangulation.EndsStrip` (guide §7) without a reduction.
    """

    def __init__(self, free: tri.FreeStrip | None = None, reduction: tri.Reduction | None = None, ax=None,
                 labels: bool = True, reduction_legend: bool = True, triangles: bool = True, geodetic: bool = False):
        self.fig, self.ax = plots.new_axes(ax, figsize=(8.0, 4.8))
        a = self.ax
        a.set_aspect("equal")
        #: draw the error triangles (enlarged); False for a student's own strip, whose triangles are an answer
        self.show_triangles = bool(triangles)
        if geodetic:  # the student's tables: x up, y right along the strip (triangulation.geodetic)
            a.set_xlabel("y on the strip, mm")
            a.set_ylabel("x on the strip, mm")
        else:
            a.set_xlabel("free strip x, mm")
            a.set_ylabel("free strip y, mm")
        self.rays = LineCollection([], colors=plots.COLORS["grey"], linewidths=0.6, alpha=0.6)
        a.add_collection(self.rays)
        self.triangles = PolyCollection([], facecolors="none", edgecolors=plots.COLORS["vermillion"], linewidths=1.6,
                                        label="error triangles", zorder=4)
        a.add_collection(self.triangles)
        self.marks = {k: a.plot([], [], linestyle="none", label=_KIND_LABEL[k], zorder=5, **st)[0]
                      for k, st in _KIND_STYLE.items()}
        (self.base,) = a.plot([], [], linestyle="none", marker="v", ms=9, mfc="none", mew=1.5,
                              color=plots.COLORS["orange"], label="control on the base", zorder=5)
        (self.centre,) = a.plot([], [], "o", ms=18, mfc="none", mew=2.0, color=plots.COLORS["orange"],
                                label="reduction centre", zorder=6)
        z = np.zeros(_MAX_ARROWS)
        self.arrows = a.quiver(z, z, z, z, angles="xy", scale_units="xy",
                               scale=1.0, color=plots.COLORS["purple"], width=0.004, zorder=7,
                               label="v = r(k − 1)")
        self.labels = labels
        self.texts = []
        self.exaggeration = 1.0
        self.enlargement = TRIANGLE_ENLARGEMENT
        self.note = a.text(0.01, 0.01, "", transform=a.transAxes, fontsize=9, va="bottom")
        handles = ([self.triangles] if self.show_triangles else []) + list(self.marks.values())
        if reduction_legend:
            handles += [self.base, self.centre, self.arrows]
        a.legend(handles=handles, loc="upper center", fontsize=8, ncol=3, bbox_to_anchor=(0.5, -0.14), frameon=False)
        if free is not None:
            self.update(free, reduction)

    def update(self, free, reduction: tri.Reduction | None = None) -> None:
        pts = free.points if hasattr(free, "points") else free.templates.points
        P = free.points_mm
        self.rays.set_segments(list(free.ray_segments()))
        ok = np.all(np.isfinite(P), axis=1)
        lo, hi = P[ok].min(axis=0), P[ok].max(axis=0)
        span = hi - lo
        if hasattr(free, "triangle_mm") and self.show_triangles:
            side = free.max_triangle_side_mm if hasattr(free, "max_triangle_side_mm") else 0.0
            self.enlargement = _nice_factor(0.05 * max(span) / side) if side > 1e-9 else TRIANGLE_ENLARGEMENT
            self.triangles.set_verts(_triangle_polys(free, self.enlargement))
        for k, line in self.marks.items():
            sel = pts.mask(k) & np.all(np.isfinite(P), axis=1)
            line.set_data(P[sel, 0], P[sel, 1])
        tri_txt = t("triangles ×{k:g}", k=self.enlargement) if self.show_triangles else ""
        if reduction is not None:
            C = P[reduction.centre_index]
            self.centre.set_data([C[0]], [C[1]])
            d = P - C
            r = np.hypot(d[:, 0], d[:, 1])
            unit = np.divide(d, r[:, None], out=np.zeros_like(d), where=r[:, None] > 0)
            v = reduction.corrections.v_mm
            vmax = float(np.max(np.abs(v[ok]))) if np.any(ok) else 0.0
            self.exaggeration = _nice_factor((max(span) / 6.0) / vmax) if vmax > 1e-9 else 1.0
            UV = unit * (v * self.exaggeration)[:, None]
            _set_arrows(self.arrows, P[ok], UV[ok])
            base = reduction.to_strip_frame(reduction.base_control_mm)
            self.base.set_data(base[:, 0], base[:, 1])
            self.note.set_text(t("{triangles}; arrows ×{x:g}; k = {k:.4f}", triangles=tri_txt, x=self.exaggeration,
                                 k=reduction.k))
        else:
            self.centre.set_data([], [])
            _set_arrows(self.arrows, np.zeros((0, 2)), np.zeros((0, 2)))
            self.base.set_data([], [])
            self.note.set_text(tri_txt)
        sel = np.flatnonzero(ok & (pts.mask("centre") | pts.mask("control"))) if self.labels else []
        _place_labels(self.ax, self.texts, [(pts.names[i], P[i]) for i in sel], xytext=(5, -12), fontsize=9)
        pad = 0.12 * max(span)
        _set_limits(self.ax, (lo[0] - pad, hi[0] + pad), (lo[1] - pad, hi[1] + pad), getattr(self, "snap", False))


class EndsView(StripView):
    """A strip built from both ends (guide §7, figure 16), with the middle template's two solutions.

    Adds to :class:`StripView` the middle centre from the left (3′) and from the
    right (3″) and the tie points m, n from each side; on the plan (mm at 1/M)
    they are a few tenths of a millimetre apart, so an inset axis shows them
    enlarged around the middle centre.
    """

    def __init__(self, ends: tri.EndsStrip | None = None, ax=None, labels: bool = True):
        if ax is None:  # the strip and, beside it, the middle centre enlarged: no empty plan between them
            fig = plots.figure(figsize=(10.5, 4.2))
            gs = fig.add_gridspec(1, 2, width_ratios=[3.3, 1.2])
            ax, self.inset = fig.add_subplot(gs[0]), fig.add_subplot(gs[1])
            self._inset_beside = True
        else:
            self.inset = None
            self._inset_beside = False
        super().__init__(None, None, ax=ax, labels=labels, reduction_legend=False)
        a = self.ax
        if self.inset is None:
            self.inset = a.inset_axes([0.74, 0.42, 0.25, 0.5])
        from matplotlib.ticker import MaxNLocator

        self.inset.xaxis.set_major_locator(MaxNLocator(3))
        self.inset.yaxis.set_major_locator(MaxNLocator(4))
        self.inset.set_aspect("equal")
        big = self._inset_beside
        self.inset.tick_params(labelsize=9 if big else 7)
        self.inset.set_title("middle centre, enlarged", fontsize=11 if big else 8)
        if big:
            self.inset.set_xlabel("plan x, mm", fontsize=10)
        (self.left,) = self.inset.plot([], [], "x", color=plots.COLORS["vermillion"], ms=9, mew=2, label="3′ (left)")
        (self.right,) = self.inset.plot([], [], "+", color=plots.COLORS["blue"], ms=11, mew=2, label="3″ (right)")
        (self.mid,) = self.inset.plot([], [], "s", color=plots.COLORS["black"], ms=7, mfc="none", mew=1.5,
                                      label="3 (mean)")
        (self.truth,) = self.inset.plot([], [], "*", color=plots.COLORS["green"], ms=10, label="truth")
        self.inset.legend(fontsize=9 if big else 7, loc="upper center", bbox_to_anchor=(0.5, -0.2 if big else -0.12),
                          ncol=2, frameon=False)
        if ends is not None:
            self.update(ends)

    def update(self, ends, reduction=None) -> None:
        super().update(ends, None)
        if not isinstance(ends, tri.EndsStrip):
            return
        c = ends.centres_mm[ends.mid]
        self.left.set_data([ends.mid_left_mm[0]], [ends.mid_left_mm[1]])
        self.right.set_data([ends.mid_right_mm[0]], [ends.mid_right_mm[1]])
        self.mid.set_data([c[0]], [c[1]])
        t = ends.truth_plan_mm[ends.templates.points.centre_index[ends.mid]]
        self.truth.set_data([t[0]], [t[1]])
        allp = np.vstack([ends.mid_left_mm, ends.mid_right_mm, c, t])
        half = max(0.15, float(np.max(np.abs(allp - c))) * 1.4)
        self.inset.set_xlim(c[0] - half, c[0] + half)
        self.inset.set_ylim(c[1] - half, c[1] + half)
        self.ax.set_xlabel("plan x, mm")
        self.ax.set_ylabel("plan y, mm")
        if not self._inset_beside:
            x0, x1 = self.ax.get_xlim()
            self.ax.set_xlim(x0, x1 + 0.45 * (x1 - x0))  # room for the inset right of the strip


class SiteStripView:
    """The strip's photos over the virtual site with the pricked points (guide figures 15 and 21)."""

    def __init__(self, strip=None, points: tri.StripPoints | None = None, site=None, ax=None):
        self.fig, self.ax = plots.new_axes(ax, figsize=(9.0, 4.6))
        self.site = site
        self._image = None
        self.frames = LineCollection([], colors=plots.COLORS["skyblue"], linewidths=1.6, label="photo footprints")
        self.ax.add_collection(self.frames)
        self.marks = {k: self.ax.plot([], [], linestyle="none", label=_KIND_LABEL[k], zorder=5, **st)[0]
                      for k, st in _KIND_STYLE.items()}
        self.texts = []
        self.ax.set_aspect("equal")
        self.ax.set_xlabel("X, m")
        self.ax.set_ylabel("Y, m")
        self.ax.legend(loc="upper center", fontsize=8, ncol=5, bbox_to_anchor=(0.5, -0.12), frameon=False)
        if strip is not None:
            self.update(strip, points)

    def update(self, strip, points: tri.StripPoints) -> None:
        if self._image is None and self.site is not None:
            from .site_views import plot_site

            self._image = plot_site(self.site, self.ax, points=False)["image"]
            self._image.set_alpha(0.75)
            self._image.set_zorder(0)
        fp = strip.footprints(strip.ground_Z_m)
        self.frames.set_segments([np.vstack([f[:, :2], f[:1, :2]]) for f in fp])
        P = points.XYZ_m
        for k, line in self.marks.items():
            sel = points.mask(k)
            line.set_data(P[sel, 0], P[sel, 1])
        _place_labels(self.ax, self.texts, [(points.names[i], P[i]) for i in range(len(points))],
                      xytext=(4, 4), fontsize=8)
        allp = np.vstack([f[:, :2] for f in fp])
        lo, hi = allp.min(axis=0), allp.max(axis=0)
        pad = 0.05 * max(hi - lo)
        self.ax.set_xlim(lo[0] - pad, hi[0] + pad)
        self.ax.set_ylim(lo[1] - pad, hi[1] + pad)


class AccumulationView:
    """Error of reduced free strips against the number of bases, with Zhukov's formula (13.1) read three ways.

    ``update(study, k_i, b_mm, m_eps_arcmin)``: ``study`` is
    :func:`aerophoto.triangulation.accumulation_study`'s table; the curves are
    (13.1) with the radicand n³ + 11n + 34 (the book's reading), n² + 11n + 34
    and n⁰ + 11n + 34 (as scanned).
    """

    _READINGS = (("n3", "(13.1) with n³ + 11n + 34", "-", "blue"),
                 ("n2", "… with n² + 11n + 34", "--", "orange"),
                 ("n0", "… with n⁰ + 11n + 34 (as scanned)", ":", "grey"))

    def __init__(self, study=None, ax=None, **zhukov):
        self.fig, self.ax = plots.new_axes(ax, figsize=(7.2, 4.4))
        a = self.ax
        a.set_xlabel("n, bases between the control points")
        a.set_ylabel("RMS error on the plan, mm")
        (self.sim,) = a.plot([], [], "o", color=plots.COLORS["vermillion"], ms=8,
                             label="simulated free strips, reduced")
        self.curves = {}
        for key, label, ls, col in self._READINGS:
            (self.curves[key],) = a.plot([], [], ls, color=plots.COLORS[col], lw=2, label=label)
        self.tol = a.axhline(0.35, color=plots.COLORS["black"], lw=1, ls="-.", label="m = 0.35 mm (guide)")
        a.legend(fontsize=9, loc="upper left")
        if study is not None:
            self.update(study, **zhukov)

    def update(self, study, *, k_i: float = 1.2, b_mm: float = 72.0, m_eps_arcmin: float | None = None) -> None:
        n = np.asarray(study.index, dtype=float)
        y = study["RMS error of points, mm"].to_numpy()
        self.sim.set_data(n, y)
        if m_eps_arcmin is None:
            m_eps_arcmin = tri.PRICKING_MM / b_mm * tri.RHO_ARCMIN
        nn = np.linspace(1.0, float(n.max()), 100)
        for key, *_ in self._READINGS:
            self.curves[key].set_data(nn, tri.zhukov_error_mm(nn, k_i=k_i, b_mm=b_mm, m_eps_arcmin=m_eps_arcmin,
                                                               reading=key))
        self.ax.set_xlim(0.5, float(n.max()) + 0.5)
        self.ax.set_ylim(0.0, max(float(y.max()), 0.4) * 1.15)


class CoefficientView:
    """Reduction coefficient per base with the mean and each base's tolerance (guide table 12)."""

    def __init__(self, coefficients: tri.ReductionCoefficients | None = None, ax=None):
        self.fig, self.ax = plots.new_axes(ax, figsize=(4.0, 4.4))
        a = self.ax
        a.set_ylabel("k = l_base / l_template")
        a.set_title("Reduction coefficients")
        self.band = LineCollection([], colors=plots.COLORS["skyblue"], linewidths=10, alpha=0.6,
                                   label="mean ± tolerance")
        a.add_collection(self.band)
        (self.mean,) = a.plot([], [], color=plots.COLORS["blue"], lw=1.5, label="mean k")
        self.points = a.scatter([], [], s=50, zorder=5, edgecolors=plots.COLORS["black"])
        a.legend(loc="upper right", fontsize=8)
        if coefficients is not None:
            self.update(coefficients)

    def update(self, c: tri.ReductionCoefficients) -> None:
        n = len(c.k)
        x = np.arange(n)
        self.band.set_segments([[(i, c.k_mean - t), (i, c.k_mean + t)] for i, t in zip(x, c.tol)])
        self.mean.set_data([-0.5, n - 0.5], [c.k_mean, c.k_mean])
        self.points.set_offsets(np.column_stack([x, c.k]))
        self.points.set_facecolors([plots.COLORS["green"] if ok else plots.COLORS["vermillion"] for ok in c.ok])
        if getattr(self, "_bases", None) != list(c.bases):  # new tick labels only for new bases (they are costly)
            self._bases = list(c.bases)
            self.ax.set_xticks(x)
            self.ax.set_xticklabels([f"{a}–{b}" for a, b in c.bases], rotation=60, fontsize=8)
        span = max(float(np.max(np.abs(c.dk))), float(np.max(c.tol))) * 1.6
        _set_limits(self.ax, (-0.5, n - 0.5), (c.k_mean - span, c.k_mean + span), getattr(self, "snap", False))


class ReductionView:
    """The strip (left) and the coefficients (right) of a :class:`ReductionResult`."""

    def __init__(self, result: ReductionResult | None = None, fig=None):
        if fig is None:
            fig = plots.figure(figsize=(8.6, 5.0))
        self.fig = fig
        gs = fig.add_gridspec(1, 2, width_ratios=[3.0, 1.15])
        self.strip = StripView(ax=fig.add_subplot(gs[0, 0]))
        self.coef = CoefficientView(ax=fig.add_subplot(gs[0, 1]))
        if result is not None:
            self.update(result)

    def update(self, r: ReductionResult) -> None:
        self.strip.update(r.free, r.reduction)
        self.strip.ax.set_title(t("Free strip, {n} templates; centre {centre}", n=r.params["n_photos"],
                                  centre=r.reduction.corrections.centre))
        self.coef.update(r.reduction.coefficients)


# =========================================================================== demo
class ReductionDemo(LiveDemo):
    """The reduction explorer (guide §7, §13): lay a free strip and reduce it to the plan."""

    title = "The reduction explorer: free strip, error triangles, reduction"
    hint = ("Change the free strip's scale: k follows 1/q and the arrows v = r(k − 1) grow, but the control "
            "residuals do not change. Raise the pricking error: the triangles and the spread of k grow. "
            "Move the centre: the corrections change, the result does not.")
    params = (
        Param("f_mm", "f, mm", 70, 1100, 10, 100, group="Camera", help="focal length f (the variants reach 1090 mm)"),
        Param("m", "m (photo 1:m)", 8000, 22000, 100, 12000, group="Camera",
              help="photo scale denominator (the variants reach 21 900)"),
        Param("max_tilt_deg", "α max, °", 0, 3, 0.25, 0, group="Camera",
              help="largest tilt of the photos (reduced, with a note, where it would carry them off the site)"),
        Param("scale_ratio", "q = free-strip / plan scale", 0.7, 1.3, 0.01, 0.96, group="Free strip",
              help="the template's arbitrary scale; k ≈ 1/q"),
        Param("pricking_mm", "m_p (pricking), mm", 0, 0.4, 0.01, 0.1, group="Free strip",
              help="RMS error of pricking a point on a photo (guide: 0.1 mm)"),
        Param("centre", "central centre (photo no.)", 36, 39, 1, 37, kind="int", group="Reduction",
              help="the working centre the corrections are measured from (guide §13: 37 or 38)"),
        Param("seed", "seed", 0, 20, 1, 0, kind="int", group="Reduction", help="another draw of the pricking errors"),
    )

    def build(self):
        self.view = ReductionView()
        self.fig = self.view.fig
        # a move redraws the strip's and the coefficients' artists over cached axes; rounded limits keep the axes
        # (and their ticks) unchanged on small moves, a title that stays the same does not count as a change
        v = self.view
        v.strip.snap = v.coef.snap = True
        plots.steady_title(v.strip.ax)
        self.animated = (v.strip.rays, v.coef.band)

    #: the strip of guide §13: four photos numbered 36 … 39 (five would not fit the site beyond 1:19 500)
    n_photos = 4
    first_number = 36

    def compute(self, **v):
        return reduction_model(f_mm=v["f_mm"], m=v["m"], scale_ratio=v["scale_ratio"], pricking_mm=v["pricking_mm"],
                               centre=v["centre"] - self.first_number + 1, max_tilt_deg=v["max_tilt_deg"],
                               n_photos=self.n_photos, seed=v["seed"], first_number=self.first_number)

    def render(self, result: ReductionResult):
        self.view.update(result)
        notes = [f"{t(k)}: {val:.4g} {t(u)}".strip() if isinstance(val, float) else f"{t(k)}: {val}"
                 for k, (u, val) in result.summary().iterrows()]
        if result.note:
            notes.append(result.note)
        df = result.reduction.coefficients.table()[["l_base (l_осн), mm", "l_template (l_воск), mm", "k", "Δk"]]
        df.index = df.index.map(lambda b: str(b).replace(" – ", "–"))  # the bases as the figure's ticks name them
        hl = np.zeros(df.shape, dtype=bool)
        hl[:, 3] = ~result.reduction.coefficients.ok
        # as the guide's table 12 prints them: lengths to 0.01 mm, k and Δk to 0.001 (and the table fits the
        # lecture page's column at 1280 px)
        prec = {"l_base (l_осн), mm": 2, "l_template (l_воск), mm": 2, "k": 3, "Δk": 3}
        self.table.value = plots.html_table(df, caption="Reduction coefficients (table 12)", precision=prec,
                                            notes=notes, highlight=hl)


# =========================================================================== the student's own strip
def own_site_figure(variant, ax=None):
    """The student's photos 36 … 39 over the virtual site with the points pricked on them (guide figure 21)."""
    from ..labs.ch06 import lab_strip

    lab = lab_strip(variant)
    from .. import site as site_mod

    from matplotlib.ticker import FuncFormatter

    view = SiteStripView(lab.strip, lab.free.points, site=site_mod.get_site(), ax=ax)
    view.ax.set_title(f"Your strip: photos {lab.strip.shots[0].number}–{lab.strip.shots[-1].number}, "
                      f"f = {lab.strip.camera.f_mm:g} mm, {fmt_scale(lab.strip.m)}")
    # the student's geodetic coordinates (triangulation.geodetic): Y east along the axis, X north up it
    X0, Y0 = tri.GEODETIC_ORIGIN_M
    view.ax.xaxis.set_major_formatter(FuncFormatter(lambda val, _pos: f"{val + Y0:.0f}"))
    view.ax.yaxis.set_major_formatter(FuncFormatter(lambda val, _pos: f"{val + X0:.0f}"))
    view.ax.tick_params(labelsize=9)
    view.ax.set_xlabel("Y (east), m")
    view.ax.set_ylabel("X (north), m")
    return view.fig


def own_templates_figure(variant):
    """The student's four direction templates (guide figure 22), side by side."""
    from ..labs.ch06 import lab_strip

    tm = lab_strip(variant).templates
    fig = plots.figure(figsize=(13.0, 4.4))
    axes = fig.subplots(1, tm.n_photos)
    for t, a in enumerate(axes):
        TemplateView(tm, t, ax=a, legend=False, labels=False)
        a.set_xlabel("x, mm", fontsize=10)
        a.set_ylabel("y, mm" if t == 0 else "", fontsize=10)
        a.tick_params(labelsize=9)
    if tm.n_photos:
        fig.legend(*axes[0].get_legend_handles_labels(), loc="outside lower center", ncol=6, fontsize=10,
                   frameon=False)
    return fig


def own_strip_figure(variant, ax=None):
    """The student's templates laid into the free strip (guide figures 23–24): rays, centres and points.

    Drawn in the student's geodetic axes (x up, y right along the strip) and
    without the error triangles, the coefficients and the corrections — those
    the student computes from the tables (:class:`aerophoto.labs.ch06.StripReadings`).
    """
    import dataclasses

    from ..labs.ch06 import lab_strip, tracing_frame

    lab = lab_strip(variant)
    phi, R, shift = tracing_frame(variant)  # drawn where the tables measure it: the tracing on the table
    fs = lab.free
    on_table = dataclasses.replace(fs, centres_mm=fs.centres_mm @ R.T + shift, theta_rad=fs.theta_rad + phi,
                                   points_mm=fs.points_mm @ R.T + shift, triangle_mm=fs.triangle_mm @ R.T + shift)
    view = StripView(on_table, None, ax=ax, triangles=False, geodetic=True, reduction_legend=False)
    view.ax.set_title("Your free strip, laid at a scale of its own")
    view.note.set_text("")
    return view.fig
