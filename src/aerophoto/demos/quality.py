"""Judging a flight on its rough mosaic (chapter 02, guide §3).

The pure part is :mod:`aerophoto.quality`; :func:`quality_model` flies a small
block (two strips of five photos at 1:10 000 — small enough that even the
sliders' worst imperfections keep every print on the default 10 × 5 km site;
the checks are percentages and angles, so the scale does not change them) over
the virtual site with the chosen
imperfections (:class:`aerophoto.simulate.Imperfections`) and assesses it
(:func:`aerophoto.quality.assess_flight`).  :class:`RoughMosaicView` lays the
photos on the plan as the technician lays the prints on the board (накидной
монтаж): the ground each print shows, tinted by how many prints cover it (so
the forward and side overlaps stand out), every print's outline, its principal
point and number, the bases between neighbours and the line of each strip —
with whatever fails a tolerance drawn in vermillion.  :class:`QualityDemo`
binds sliders for the imperfections to the view and to the verdict table.
"""

from __future__ import annotations

import html as _html
from dataclasses import dataclass

import numpy as np
from matplotlib.collections import LineCollection

from .. import geometry as g
from .. import plots
from .. import quality as q
from .. import simulate as sim
from ..widgets import LiveDemo, Param

__all__ = ["QualityResult", "quality_model", "rough_mosaic_raster", "RoughMosaicView", "QualityDemo",
           "verdict_html", "crab_limit_plot"]

#: tints of ground covered by 1, 2, 3, 4+ prints (RGB 0…1) and their weight
_TINTS = {1: ((1.0, 1.0, 1.0), 0.0), 2: ((0.34, 0.71, 0.91), 0.30), 3: ((0.0, 0.45, 0.70), 0.40),
          4: ((0.80, 0.47, 0.65), 0.45)}
_FAIL = plots.COLORS["vermillion"]
_STRIP_COLORS = (plots.COLORS["blue"], plots.COLORS["green"], plots.COLORS["orange"], plots.COLORS["purple"])


def _default_site():
    from .. import site

    return site.get_site()


@dataclass(frozen=True)
class QualityResult:
    """A simulated flight, its assessment and its rough mosaic on the plan.

    Attributes
    ----------
    flight : aerophoto.simulate.Block
    report : aerophoto.quality.QualityReport
    image : (ny, nx, 3) float RGB of the rough mosaic, row 0 at the south
    extent_m : (X_min, X_max, Y_min, Y_max) of the image, metres
    outlines_m : (N, k, 2) each print's outline on the ground (frame edges cut with the terrain), m
    o_ground_m : (N, 2) the principal points' ground positions, m
    """

    flight: object
    report: q.QualityReport
    image: np.ndarray
    extent_m: tuple
    outlines_m: np.ndarray
    o_ground_m: np.ndarray


def _outline(camera, pose, dem, k=6):
    c = camera.corners_mm()
    pts = []
    for i in range(4):
        a, b = c[i], c[(i + 1) % 4]
        for s in np.arange(k) / k:
            pts.append(a + (b - a) * s)
    pts.append(c[0])
    return g.photo_to_dem(camera, pose, np.array(pts), dem)[:, :2]


def rough_mosaic_raster(shots, site, outlines_m, *, pixel_m: float = 20.0, margin_m: float = 150.0):
    """The rough mosaic on the plan: ground brightness where a print covers it, tinted by the number of prints.

    Parameters
    ----------
    shots : the photos (each with ``camera`` and ``pose``)
    site : the virtual site (``height``, ``sample``, ``level_for``)
    outlines_m : (N, k, 2) the prints' ground outlines (for the extent), m
    pixel_m : ground size of a plan pixel, m

    Returns
    -------
    image : (ny, nx, 3) float RGB, row 0 at the south edge
    extent : (X_min, X_max, Y_min, Y_max), m
    count : (ny, nx) int, how many prints cover each pixel
    """
    allp = np.asarray(outlines_m).reshape(-1, 2)
    x0, y0 = allp.min(axis=0) - margin_m
    x1, y1 = allp.max(axis=0) + margin_m
    nx = int(np.ceil((x1 - x0) / pixel_m))
    ny = int(np.ceil((y1 - y0) / pixel_m))
    X = x0 + (np.arange(nx) + 0.5) * pixel_m
    Y = y0 + (np.arange(ny) + 0.5) * pixel_m
    XX, YY = np.meshgrid(X, Y)
    ZZ = site.height(XX, YY)
    P = np.stack([XX, YY, ZZ], axis=-1).reshape(-1, 3)
    count = np.zeros(P.shape[0], dtype=int)
    for s in shots:
        R = g.rotation_matrix(s.pose)
        front = ((P - s.pose.centre) @ R)[:, 2] < 0
        idx = np.flatnonzero(front)
        xy = g.ground_to_photo(s.camera, s.pose, P[idx])
        count[idx[s.camera.inside(xy)]] += 1
    grey = np.ones(P.shape[0], dtype=np.float32)
    cov = count > 0
    lev = site.level_for(pixel_m) if hasattr(site, "level_for") else 0
    if hasattr(site, "sample"):
        grey[cov] = site.sample(P[cov, 0], P[cov, 1], lev, outside=1.0)
    else:
        grey[cov] = 0.6
    rgb = np.repeat(grey[:, None], 3, axis=1)
    rgb[~cov] = 0.97
    for k, (col, w) in _TINTS.items():
        sel = count >= k if k == 4 else count == k
        if w > 0 and sel.any():
            rgb[sel] = (1 - w) * rgb[sel] + w * np.array(col)
    return rgb.reshape(ny, nx, 3), (float(x0), float(x0 + nx * pixel_m), float(y0), float(y0 + ny * pixel_m)), \
        count.reshape(ny, nx)


def quality_model(f_mm: float = 100.0, max_tilt_deg: float = 1.0, crab_deg: float = 2.0, crab_jitter_deg: float = 1.0,
                  height_percent: float = 1.0, curvature_percent: float = 0.5, px_percent: float = 60.0,
                  py_percent: float = 30.0, seed: int = 3, *, m: float = 10000.0, n_photos: int = 5,
                  n_strips: int = 2, site=None, pixel_m: float = 20.0) -> QualityResult:
    """Fly a block with imperfections over the virtual site and assess it (guide §3).

    Parameters
    ----------
    f_mm : focal length f, mm (sets the crab-angle limit and H = f·m)
    max_tilt_deg, crab_deg, crab_jitter_deg, height_percent, curvature_percent, seed :
        the imperfections (:class:`aerophoto.simulate.Imperfections`: largest
        tilt α, constant crab, random crab ±, flying-height scatter ±%, route
        sagitta % of the chord, random stream)
    px_percent, py_percent : planned forward and side overlaps, %
    m : photo scale denominator; n_photos, n_strips : size of the block
    site : the virtual site (default :func:`aerophoto.site.get_site`)
    pixel_m : ground size of a pixel of the rough-mosaic image, m
    """
    site = _default_site() if site is None else site
    cam = g.Camera(f_mm)
    imp = sim.Imperfections(max_tilt_deg=max_tilt_deg, crab_deg=crab_deg, max_crab_jitter_deg=crab_jitter_deg,
                            max_height_percent=height_percent, curvature_percent=curvature_percent, seed=int(seed))
    flight = sim.block_over_site(site, cam, m, px_percent, py_percent, n_photos, n_strips, imperfections=imp,
                                 alternate=True)
    cat = site.catalogue[["X_m", "Y_m", "Z_m"]].to_numpy(dtype=float)
    report = q.assess_flight(flight, site, points_m=cat)
    shots = flight.shots
    outlines = np.array([_outline(cam, s.pose, site) for s in shots])
    o = np.array([g.photo_to_dem(cam, s.pose, np.zeros(2), site)[:2] for s in shots])
    image, extent, _ = rough_mosaic_raster(shots, site, outlines, pixel_m=pixel_m)
    return QualityResult(flight, report, image, extent, outlines, o)


def verdict_html(report: q.QualityReport, *, conclusion: bool = True) -> str:
    """The summary verdict table and (optionally) the written conclusion as HTML."""
    df = report.summary_table()
    hl = np.zeros(df.shape, dtype=bool)
    hl[:, -1] = df["verdict"].str.startswith("FAIL").to_numpy()
    out = plots.html_table(df, caption="Photogrammetric quality (guide §3)", highlight=hl)
    if conclusion:
        text = _html.escape(report.conclusion())
        out += (f"<div style='max-width:420px;font-size:12px;white-space:pre-wrap;margin-top:6px'>"
                f"<b>Conclusion</b>\n{text}</div>")
    return out


class RoughMosaicView:
    """The prints laid on the plan (накидной монтаж), with failing items in vermillion.

    ``view = RoughMosaicView(ax=None)`` builds the artists once;
    ``view.update(result)`` changes them in place.
    """

    def __init__(self, result: QualityResult | None = None, ax=None, *, figsize=(8.4, 5.4)):
        own = ax is None
        if own:
            fig = plots.figure(figsize=figsize, layout="constrained")
            ax = fig.add_subplot(1, 1, 1)
        self.fig, self.ax = ax.figure, ax
        a = self.ax
        C = plots.COLORS
        a.set_aspect("equal")
        a.grid(False)
        a.set_xlabel("X (east), km")
        a.set_ylabel("Y (north), km")
        self.image = a.imshow(np.ones((2, 2, 3)), origin="lower", extent=(0, 1, 0, 1), interpolation="antialiased",
                              zorder=0)
        self.frames = LineCollection([], linewidths=1.2, zorder=3)
        a.add_collection(self.frames)
        self.bases = LineCollection([], linewidths=1.5, zorder=5)
        a.add_collection(self.bases)
        self.strips = LineCollection([], linewidths=1.3, linestyles=(0, (4, 3)), zorder=4)
        a.add_collection(self.strips)
        (self.o,) = a.plot([], [], linestyle="none", marker="+", ms=9, mew=1.8, color=C["black"], zorder=5)
        self.numbers = []
        # legend
        from matplotlib.patches import Patch

        def tint(k):
            col, w = _TINTS[k]
            return (1 - w) * 0.55 + w * np.array(col)

        handles = [Patch(fc=tint(2), label="2 prints"), Patch(fc=tint(3), label="3 prints"),
                   Patch(fc=tint(4), label="4 prints"),
                   a.plot([], [], color=C["grey"], lw=1.5, label="base o–o")[0],
                   a.plot([], [], color=C["black"], lw=1.5, ls="--", label="strip line L")[0],
                   a.plot([], [], color=_FAIL, lw=2.5, label="out of tolerance")[0]]
        if own:
            self.fig.legend(handles=handles, loc="outside lower center", ncol=6, fontsize=8, frameon=False,
                            handlelength=1.5, columnspacing=1.0)
        else:
            a.legend(handles=handles, loc="upper left", fontsize=8, framealpha=0.85)
        self.title = a.set_title("")
        if result is not None:
            self.update(result)

    def update(self, r: QualityResult) -> None:
        rep = r.report
        km = 1000.0
        self.image.set_data(r.image)
        self.image.set_extent(tuple(v / km for v in r.extent_m))
        x0, x1, y0, y1 = (v / km for v in r.extent_m)
        self.ax.set_xlim(x0, x1)
        self.ax.set_ylim(y0, y1)
        shots = r.flight.shots
        bad_photo = {p.number: not p.ok for p in rep.photos}
        cols, widths = [], []
        for s in shots:
            if bad_photo.get(s.number, False):
                cols.append(_FAIL)
                widths.append(2.6)
            else:
                cols.append(_STRIP_COLORS[s.strip % len(_STRIP_COLORS)])
                widths.append(1.2)
        self.frames.set_segments([ol / km for ol in r.outlines_m])
        self.frames.set_colors(cols)
        self.frames.set_linewidths(widths)
        pos = {s.number: r.o_ground_m[k] / km for k, s in enumerate(shots)}
        segs, bcols, bw = [], [], []
        for p in rep.forward_pairs:
            segs.append(np.array([pos[p.numbers[0]], pos[p.numbers[1]]]))
            bcols.append(plots.COLORS["grey"] if p.ok else _FAIL)
            bw.append(1.5 if p.ok else 3.0)
        for p in rep.side_pairs:
            if not p.ok:
                segs.append(np.array([pos[p.numbers[0]], pos[p.numbers[1]]]))
                bcols.append(_FAIL)
                bw.append(3.0)
        self.bases.set_segments(segs)
        self.bases.set_colors(bcols)
        self.bases.set_linewidths(bw)
        ssegs, scol = [], []
        for sc in rep.strips:
            ssegs.append(np.array([pos[sc.numbers[0]], pos[sc.numbers[-1]]]))
            scol.append(plots.COLORS["black"] if sc.ok else _FAIL)
        self.strips.set_segments(ssegs)
        self.strips.set_colors(scol)
        o = r.o_ground_m / km
        self.o.set_data(o[:, 0], o[:, 1])
        while len(self.numbers) < len(o):
            self.numbers.append(self.ax.annotate("", (0, 0), xytext=(4, 4), textcoords="offset points", fontsize=9,
                                                 fontweight="bold", zorder=6,
                                                 bbox=dict(boxstyle="round,pad=0.1", fc="white", ec="none", alpha=0.7)))
        for k, t in enumerate(self.numbers):
            if k < len(o):
                t.xy = (o[k, 0], o[k, 1])
                t.set_text(str(shots[k].number))
                t.set_color(_FAIL if bad_photo.get(shots[k].number, False) else plots.COLORS["black"])
                t.set_visible(True)
            else:
                t.set_visible(False)
        n_fail = len(rep.failures())
        self.title.set_text("Rough mosaic (накидной монтаж): " + ("all criteria met" if n_fail == 0 else
                                                                   f"{n_fail} check{'s' if n_fail > 1 else ''} failed"))


class QualityDemo(LiveDemo):
    """Live rough mosaic: the flight's imperfections → the prints on the plan and the §3 verdicts.

    It opens on the guide's camera (f = 100 mm, variant 00), never on the student's own: the crab limit in its
    table is task 02.2's answer.  f reaches 1100 mm, every variant of the guide's scheme (f = 100 + 10i mm);
    at 1:10 000 even f = 1100 mm with the sliders' worst imperfections keeps every print on the site.
    """

    title = "Is the survey fit for use? The rough mosaic and the checks of guide §3"
    hint = ("Push an imperfection past its tolerance — crab, tilt, height scatter, a bent route, a small overlap — "
            "and watch the print, pair or strip turn vermillion and the verdict change.")
    params = (
        Param("f_mm", "f, mm", 70, 1100, 10, 100, group="Camera", help="focal length (sets the crab limit)"),
        Param("px_percent", "p_x, %", 50, 80, 1, 60, group="Plan", help="planned forward overlap"),
        Param("py_percent", "p_y, %", 10, 45, 1, 30, group="Plan", help="planned side overlap"),
        Param("max_tilt_deg", "α max, °", 0, 5, 0.25, 1, group="Imperfections", help="largest tilt"),
        Param("crab_deg", "crab φ, °", -8, 8, 0.5, 2, group="Imperfections", help="constant crab angle"),
        Param("crab_jitter_deg", "crab ±, °", 0, 5, 0.5, 1, group="Imperfections", help="random extra crab"),
        Param("height_percent", "ΔH ±, %", 0, 6, 0.25, 1, group="Imperfections",
              help="flying-height scatter, % of H"),
        Param("curvature_percent", "bend, %", -4, 4, 0.25, 0.5, group="Imperfections",
              help="sagitta of the route, % of its length"),
        Param("seed", "seed", 0, 20, 1, 3, kind="int", group="Imperfections", help="random stream"),
    )

    def build(self):
        self.view = RoughMosaicView()
        self.fig = self.view.fig

    def compute(self, **v):
        return quality_model(**v)

    def render(self, result: QualityResult):
        self.view.update(result)
        self.table.value = verdict_html(result.report)


def crab_limit_plot(ax=None, f_mm: float | None = None, *, f_max_mm: float = 1100.0):
    """The crab-angle tolerance against focal length: the guide's three values and the book's rule.

    Draws φ_max(f) of :func:`aerophoto.quality.crab_limit_deg` for 50 mm to ``f_max_mm`` (default 1100 mm: every
    variant of the guide's scheme, f = 100 + 10i mm), the guide's points (100, 5°), (140, 7°), (200, 10°), the
    range beyond the longest real lenses (≈ 610 mm) shaded, and — only if ``f_mm`` is given — one camera
    marked.  The chapter's figure marks none: a student's own limit is task 02.2's answer.  Returns the Axes.
    """
    fig, ax = plots.new_axes(ax, figsize=(6.4, 3.4))
    C = plots.COLORS
    f = np.linspace(50.0, float(f_max_mm), 521)
    ax.axvspan(610.0, float(f_max_mm), color=C["grey"], alpha=0.15, lw=0,
               label="beyond real lenses (> 610 mm): the rule applied anyway")
    ax.plot(f, [q.crab_limit_deg(x) for x in f], color=C["blue"], label="book's rule: φ_max = f/20, held outside")
    g = f[f <= 400.0]
    ax.plot(g, g / 20.0, color=C["grey"], lw=1.0, ls=":", label="the line f/20 continued")
    fs = sorted(q.CRAB_LIMITS_DEG)
    ax.plot(fs, [q.CRAB_LIMITS_DEG[k] for k in fs], "o", color=C["vermillion"], ms=8, label="guide §3, item 3.3")
    if f_mm is not None:
        ax.plot([f_mm], [q.crab_limit_deg(f_mm)], "D", color=C["green"], ms=8, label=f"camera f = {f_mm:g} mm")
    ax.set_xlim(0, float(f_max_mm))
    ax.set_xlabel("focal length f, mm")
    ax.set_ylabel("largest crab φ_max, °")
    ax.set_ylim(0, 21)
    ax.legend(fontsize=9, loc="upper right")
    return ax
