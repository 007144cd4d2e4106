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

Speed (a slider move is painted within 100 ms in the browser): the view lays
the prints on a fixed *board* (:func:`board_extent_m`) — the plan area of the
block flown without imperfections, widened to hold the prints at every
position of the imperfection sliders — so a move leaves the axes, their
limits and ticks alone and redraws only the mosaic, the outlines, the marks
and the title over a cached picture of the rest (``LiveDemo.animated``,
:class:`aerophoto.blit.Blitter`).  The board also lets the eye see a print
*move* when the flight is broken.  The raster's ground heights and brightness
on the board are read once per board (:func:`rough_mosaic_raster` with
``extent_m``), each print is projected only over its own neighbourhood, and
the site's height bounds are read once (:attr:`aerophoto.site.Site.z_min_m` is cached).
"""

from __future__ import annotations

import functools
import html as _html
import math
from dataclasses import dataclass

import numpy as np
from matplotlib.collections import LineCollection

from .. import geometry as g
from .. import plots
from ..blit import nearest_pixels
from ..i18n import t as _t
from .. import quality as q
from .. import simulate as sim
from ..widgets import TABLE_DELAY_S, LiveDemo, Param, table_after_picture  # noqa: F401 (TABLE_DELAY_S: importable from here, as before)

__all__ = ["QualityResult", "quality_model", "rough_mosaic_raster", "board_extent_m", "RoughMosaicView",
           "QualityDemo", "verdict_html", "crab_limit_plot", "table_after_picture"]

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
    extent_m : (X_min, X_max, Y_min, Y_max) of the image, metres (the board, when one was given)
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


def _footprint_box(shot, site, pad_m: float):
    """A box that surely holds the ground ``shot`` shows: its frame corners cut with the planes at the terrain's
    lowest and highest heights (every ray meets the terrain between them), widened by ``pad_m``."""
    c = shot.camera.corners_mm()
    pts = np.vstack([g.photo_to_plane(shot.camera, shot.pose, c, z)[:, :2] for z in (site.z_min_m, site.z_max_m)])
    return pts.min(axis=0) - pad_m, pts.max(axis=0) + pad_m


_GRIDS: dict = {}


def _plan_grid(site, extent_m: tuple, pixel_m: float):
    """Pixel centres, ground heights and ground brightness of the board (what does not change between moves)."""
    key = (id(site), tuple(float(v) for v in extent_m), float(pixel_m))
    hit = _GRIDS.get(key)
    if hit is not None and hit[0] is site:
        return hit[1]
    x0, x1, y0, y1 = key[1]
    nx = max(1, int(round((x1 - x0) / pixel_m)))
    ny = max(1, int(round((y1 - y0) / pixel_m)))
    X = x0 + (np.arange(nx) + 0.5) * pixel_m
    Y = y0 + (np.arange(ny) + 0.5) * pixel_m
    XX, YY = np.meshgrid(X, Y)
    P = np.stack([XX, YY, site.height(XX, YY)], axis=-1).reshape(-1, 3)
    if hasattr(site, "sample"):
        lev = site.level_for(pixel_m) if hasattr(site, "level_for") else 0
        grey = np.asarray(site.sample(P[:, 0], P[:, 1], lev, outside=1.0), dtype=np.float32)
    else:
        grey = np.full(P.shape[0], 0.6, dtype=np.float32)
    out = (P, grey, nx, ny, (x0, x0 + nx * pixel_m, y0, y0 + ny * pixel_m))
    if len(_GRIDS) > 6:
        _GRIDS.clear()
    _GRIDS[key] = (site, out)
    return out


def rough_mosaic_raster(shots, site, outlines_m, *, pixel_m: float = 20.0, margin_m: float = 150.0,
                        extent_m=None):
    """The rough mosaic on the plan: ground brightness where a print covers it, tinted by the number of prints.

    Parameters
    ----------
    shots : the photos (each with ``camera`` and ``pose``)
    site : the virtual site (``height``, ``sample``, ``level_for``)
    outlines_m : (N, k, 2) the prints' ground outlines (for the extent), m
    pixel_m : ground size of a plan pixel, m
    margin_m : room around the outlines when the extent follows them, m
    extent_m : (X_min, X_max, Y_min, Y_max) of the plan to draw, m (the demo's fixed board); default the
        outlines' extent plus ``margin_m``.  The board's heights and brightness are read once per board.

    Returns
    -------
    image : (ny, nx, 3) float RGB, row 0 at the south edge
    extent : (X_min, X_max, Y_min, Y_max), m
    count : (ny, nx) int, how many prints cover each pixel
    """
    if extent_m is None:
        allp = np.asarray(outlines_m).reshape(-1, 2)
        x0, y0 = allp.min(axis=0) - margin_m
        x1, y1 = allp.max(axis=0) + margin_m
        nx = int(np.ceil((x1 - x0) / pixel_m))
        ny = int(np.ceil((y1 - y0) / pixel_m))
        extent_m = (float(x0), float(x0 + nx * pixel_m), float(y0), float(y0 + ny * pixel_m))
    P, grey_all, nx, ny, extent = _plan_grid(site, extent_m, pixel_m)
    P2 = P.reshape(ny, nx, 3)
    count = np.zeros((ny, nx), dtype=np.int32)
    x0, y0 = extent[0], extent[2]
    for s in shots:
        # only the pixels near the print can be on it: a box that surely holds its footprint, as rows and columns
        lo, hi = _footprint_box(s, site, 2.0 * pixel_m)
        i0, i1 = max(0, int((lo[0] - x0) // pixel_m)), min(nx, int((hi[0] - x0) // pixel_m) + 1)
        j0, j1 = max(0, int((lo[1] - y0) // pixel_m)), min(ny, int((hi[1] - y0) // pixel_m) + 1)
        if i0 >= i1 or j0 >= j1:
            continue
        Q = P2[j0:j1, i0:i1].reshape(-1, 3)
        R = g.rotation_matrix(s.pose)
        front = ((Q - s.pose.centre) @ R)[:, 2] < 0
        hit = np.zeros(Q.shape[0], dtype=bool)
        hit[np.flatnonzero(front)[s.camera.inside(g.ground_to_photo(s.camera, s.pose, Q[front]))]] = True
        count[j0:j1, i0:i1] += hit.reshape(j1 - j0, i1 - i0)
    count = count.reshape(-1)
    cov = count > 0
    grey = np.where(cov, grey_all, np.float32(0.97))
    # tint by the number of prints: weight w and colour per count (0 and 1 print: none)
    w = np.zeros(5, dtype=np.float32)
    col = np.zeros((5, 3), dtype=np.float32)
    for k, (c, wk) in _TINTS.items():
        w[k], col[k] = wk, c
    k = np.minimum(count, 4)
    wk = w[k][:, None]
    rgb = (1 - wk) * grey[:, None] + wk * col[k]
    return rgb.reshape(ny, nx, 3), extent, count.reshape(ny, nx)


#: the largest imperfections the sliders reach (QualityDemo): the board holds the prints at all of them
_SLIDER_MAX = {"max_tilt_deg": 5.0, "crab_deg": 8.0, "crab_jitter_deg": 5.0, "height_percent": 6.0,
               "curvature_percent": 4.0}
#: the board's edges are multiples of this, m (a plan slider moved a step rarely moves them)
BOARD_STEP_M = 100.0


def board_extent_m(f_mm: float = 100.0, px_percent: float = 60.0, py_percent: float = 30.0, *,
                   m: float = 10000.0, n_photos: int = 5, n_strips: int = 2, site=None) -> tuple:
    """The board the rough mosaic is laid on: (X_min, X_max, Y_min, Y_max), m.

    The plan area of the block flown *without* imperfections (f rounded up to
    a whole 100 mm, the planned overlaps p_x, p_y), widened on every side by
    what the imperfection sliders can add at their largest — crab and random
    crab turning a print (φ = 13°), the flying-height scatter scaling it
    (6 %), the tilt carrying it (H·tan 5°), the bend of the route (4 % of its
    length) — and snapped outwards to :data:`BOARD_STEP_M`.  So the board does
    not change while an imperfection slider moves (nor, mostly, while f moves
    within its hundred).
    """
    site = _default_site() if site is None else site
    f_band = float(min(1100.0, 100.0 * math.ceil(float(f_mm) / 100.0 - 1e-9)))
    return _board(site, f_band, float(px_percent), float(py_percent), float(m), int(n_photos), int(n_strips))


@functools.lru_cache(maxsize=64)
def _board(site, f_band, px, py, m, n_photos, n_strips):
    cam = g.Camera(f_band)
    flight = sim.block_over_site(site, cam, m, px, py, n_photos, n_strips, alternate=True)
    pts = np.vstack([_outline(cam, s.pose, site) for s in flight.shots])
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    half = cam.frame_mm / 2000.0 * m  # half the side of a print on the ground, m
    phi = math.radians(_SLIDER_MAX["crab_deg"] + _SLIDER_MAX["crab_jitter_deg"])
    turned = half * ((1.0 + _SLIDER_MAX["height_percent"] / 100.0) * (math.cos(phi) + math.sin(phi)) - 1.0)
    H = g.flying_height_m(f_band, m)
    tilt = H * math.tan(math.radians(_SLIDER_MAX["max_tilt_deg"])) * 1.25  # the shift, and the far edge's stretch
    route = (n_photos - 1) * sim.photo_base_m(cam, m, px)  # the strips run along X
    bend = _SLIDER_MAX["curvature_percent"] / 100.0 * route
    pad = turned + tilt + bend + 50.0
    st = BOARD_STEP_M
    return (math.floor((lo[0] - pad) / st) * st, math.ceil((hi[0] + pad) / st) * st,
            math.floor((lo[1] - pad) / st) * st, math.ceil((hi[1] + pad) / st) * st)


def quality_model(f_mm: float = 100.0, max_tilt_deg: float = 1.0, crab_deg: float = 2.0, crab_jitter_deg: float = 1.0,
                  height_percent: float = 1.0, curvature_percent: float = 0.5, px_percent: float = 60.0,
                  py_percent: float = 30.0, seed: int = 3, *, m: float = 10000.0, n_photos: int = 5,
                  n_strips: int = 2, site=None, pixel_m: float = 20.0, extent_m=None) -> QualityResult:
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
    extent_m : the plan area to draw, (X_min, X_max, Y_min, Y_max) in m (the demo passes its fixed board,
        :func:`board_extent_m`); default the prints' outlines with a 150 m margin
    """
    site = _default_site() if site is None else site
    cam = g.Camera(f_mm)
    imp = sim.Imperfections(max_tilt_deg=max_tilt_deg, crab_deg=crab_deg, max_crab_jitter_deg=crab_jitter_deg,
                            max_height_percent=height_percent, curvature_percent=curvature_percent, seed=int(seed))
    flight = sim.block_over_site(site, cam, m, px_percent, py_percent, n_photos, n_strips, imperfections=imp,
                                 alternate=True)
    cat = site.catalogue[["X_m", "Y_m", "Z_m"]].to_numpy(dtype=float)
    nadirs: dict = {}
    report = q.assess_flight(flight, site, points_m=cat, nadirs=nadirs)
    shots = flight.shots
    outlines = np.array([_outline(cam, s.pose, site) for s in shots])
    o = np.array([nadirs[s.pose][:2] for s in shots])  # the principal ground points the assessment intersected
    image, extent, _ = rough_mosaic_raster(shots, site, outlines, pixel_m=pixel_m, extent_m=extent_m)
    return QualityResult(flight, report, image, extent, outlines, o)


def verdict_html(report: q.QualityReport, *, conclusion: bool = True) -> str:
    """The summary verdict table and (optionally) the written conclusion as HTML."""
    df = report.summary_table()
    hl = np.zeros(df.shape, dtype=bool)
    hl[:, -1] = df["verdict"].str.startswith("FAIL").to_numpy()
    out = plots.html_table(df, caption="Photogrammetric quality (guide §3)", highlight=hl)
    if conclusion:
        text = _html.escape(report.conclusion())
        # the conclusion is written by aerophoto.quality in English (not yet in Russian: issue 33's report)
        out += (f"<div class='aerophoto-conclusion' style='max-width:420px;font-size:12px;white-space:pre-wrap;"
                "margin-top:6px'>"
                f"<b>Conclusion</b>\n{text}</div>")
    return out


def _rgba8(rgb) -> np.ndarray:
    """Float RGB 0…1 as opaque 8-bit RGBA: what matplotlib would convert it to on every draw, done once."""
    out = np.empty((*rgb.shape[:2], 4), dtype=np.uint8)
    out[..., :3] = np.clip(np.asarray(rgb) * 255.0 + 0.5, 0, 255)
    out[..., 3] = 255
    return out


class RoughMosaicView:
    """The prints laid on the plan (накидной монтаж), with failing items in vermillion.

    ``view = RoughMosaicView(ax=None)`` builds the artists once;
    ``view.update(result)`` changes them in place.  The axes show the result's
    plan area (``result.extent_m``: in the demo a fixed board) and are left
    alone while it stays the same.  ``view.moving`` lists the artists a move
    changes (for blitting): the mosaic and everything drawn over it, and the title.
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
        # nearest: the plan pixels (20 m) upsampled about 2×, each a crisp block, gathered (blit.nearest_pixels)
        self.image = nearest_pixels(a.imshow(np.ones((2, 2, 3)), origin="lower", extent=(0, 1, 0, 1),
                                             interpolation="nearest", zorder=0))
        self.frames = LineCollection([], linewidths=1.2, zorder=3)
        a.add_collection(self.frames)
        self.bases = LineCollection([], linewidths=1.5, zorder=5)
        a.add_collection(self.bases)
        self.strips = LineCollection([], linewidths=1.3, linestyles=(0, (4, 3)), zorder=4)
        a.add_collection(self.strips)
        (self.o,) = a.plot([], [], linestyle="none", marker="+", ms=9, mew=1.8, color=C["black"], zorder=5)
        self.numbers = plots.PointLabels(a, offset_pt=(4.0, 4.0), fontsize=9, zorder=6)
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
        self.moving = (self.image, self.frames, self.bases, self.strips, self.o, *self.numbers.artists, self.title)
        if result is not None:
            self.update(result)

    def update(self, r: QualityResult) -> None:
        rep = r.report
        km = 1000.0
        self.image.set_data(_rgba8(r.image))
        x0, x1, y0, y1 = ext = tuple(v / km for v in r.extent_m)
        if tuple(self.image.get_extent()) != ext or tuple(self.ax.get_xlim()) != (x0, x1) \
                or tuple(self.ax.get_ylim()) != (y0, y1):
            # only when the plan area changes (a live demo's board stays put while the imperfections move):
            # new limits mean new ticks, a full draw
            self.image.set_extent(ext)
            self.ax.set_xlim(x0, x1, auto=False)
            self.ax.set_ylim(y0, y1, auto=False)
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
        self.numbers.set(o, [s.number for s in shots],
                         [_FAIL if bad_photo.get(s.number, False) else plots.COLORS["black"] for s in shots])
        n_fail = len(rep.failures())
        self.title.set_text(_t("Rough mosaic (накидной монтаж): all criteria met") if n_fail == 0 else
                            _t("Rough mosaic (накидной монтаж): checks failed: {n}", n=n_fail))


class QualityDemo(LiveDemo):
    """Live rough mosaic: the flight's imperfections → the prints on the plan and the §3 verdicts.

    It opens on the guide's camera (f = 100 mm, variant 00), never on the student's own: the crab limit in its
    table is task 02.2's answer.  f reaches 1100 mm, every variant of the guide's scheme (f = 100 + 10i mm);
    at 1:10 000 a block that its imperfections push over the site's edge is flown again centred
    (:func:`aerophoto.simulate.block_over_site`); only the very largest (f = 1100 mm, p_y ≈ 10 %, the worst bend,
    tilt and crab together — about 1 in 200 random extreme settings) stays too large, and the demo says so.
    The prints lie on a fixed board (:func:`board_extent_m`), so a move of an imperfection slider is blitted.
    """

    photo_frames = True  # a move changes the photo: its frames go as JPEG (plots.fast_frames; issue 32)
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
        # a move redraws the mosaic, the outlines, marks and numbers and the title over the cached axes: the
        # board (the axes' limits) changes only with the plan sliders (f by whole 100 mm, p_x, p_y)
        self.animated = self.view.moving

    def compute(self, **v):
        return quality_model(**v, extent_m=board_extent_m(v["f_mm"], v["px_percent"], v["py_percent"]))

    def render(self, result: QualityResult):
        self.view.update(result)

    def show(self, result: QualityResult) -> None:
        """Move the artists and draw, *then* refresh the table (:func:`aerophoto.widgets.table_after_picture`)."""
        super().show(result)
        table_after_picture(self, verdict_html, result.report)


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
