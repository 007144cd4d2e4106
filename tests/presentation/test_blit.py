"""Blitting in the live demos (LiveDemo.animated, blit.Blitter): a blitted move paints what a full draw paints.

For each converted demo: after ``demo.set(...)`` (drawn by blitting: the cached background, then only the
animated artists) the canvas buffer is compared with a forced full draw of the same state (``demo.draw(force=True)``,
which goes through the same draw-event path) and with a full draw in which nothing is animated at all (the
picture the demo showed before blitting).  The two full draws differ only where a whole animated Axes overlaps a
later Axes' labels — those labels are animated too (blit._overlapping_axes_labels) — so they must be equal;
``ALLOWED`` lists the few pixels that are not, per demo, with the reason.
"""

import importlib

import numpy as np
import pytest

from aerophoto import blit, plots

pytestmark = pytest.mark.usefixtures("plot_style")

#: (module, class, moves): each move a dict for demo.set and whether it must be blitted (False: something static
#: changes — limits beyond the rounding, ticks — so it is a full draw; the picture must be right either way)
DEMOS = [
    # the floor of the browser benchmark: every move one blitted line
    ("ray", "RayDemo", [({"x_mm": 41.0}, True), ({"x_mm": -90.0}, True), ({"x_mm": 90.0}, True)]),
    # the plan's half-width is a round value (2, 2.5, 3.2 km …) around N: a move that outgrows it is a full draw
    ("footprint", "FootprintDemo", [({"f_mm": 150}, True), ({"alpha_deg": 8}, False), ({"m": 15000}, False),
                                    ({"lambda_deg": 30}, True), ({"kappa_deg": 45}, True), ({"alpha_deg": 8.5}, True)]),
    ("interpretation", "ConditionsDemo", [({"visibility_km": 5}, True), ({"sun_elevation_deg": 20}, True),
                                          ({"moisture_pct": 20}, True), ({"season": "winter"}, True)]),
    ("spectral_explorer", "SpectralExplorerDemo", [({"moisture_pct": 25}, True), ({"humus_pct": 6}, True)]),
    ("reduction", "ReductionDemo", [({"f_mm": 150}, True), ({"max_tilt_deg": 0.5}, True), ({"m": 14000}, False),
                                    ({"f_mm": 160}, True), ({"pricking_mm": 0.3}, None), ({"seed": 3}, None)]),
    ("interpretation", "KeyDemo", [({"row": 1}, True), ({"row": 5}, True), ({"camera": "colour-infrared film"}, True)]),
    # the glass: its field's outline over the photo and its picture move; another film redraws the whole photo
    ("loupe", "LoupeDemo", [({"x_mm": 20}, True), ({"power": 6}, True), ({"mark": "P"}, True),
                            ({"camera": "colour-infrared film"}, False), ({"y_mm": -10, "mark": "free"}, True)]),
    ("displacement", "ReliefDemo", [({"relief_m": 80}, None), ({"f_mm": 150}, None), ({"alpha_deg": 5}, None),
                                    ({"show": "relief"}, None)]),
    ("displacement", "TiltDemo", [({"alpha_deg": 4}, None), ({"lambda_deg": -30}, None), ({"f_mm": 200}, None)]),
    ("flight_plan", "FlightPlanDemo", [({"f_mm": 110}, None), ({"f_mm": 120}, None), ({"m": 15000}, None),
                                       ({"f_mm": 130}, None)]),
    # chapters 07, 09, 10, 11, 14, 16, 17: every slider blits but those that change the picture's frame (another
    # area, another block shape, the map's quantity and its colour bar)
    ("stereo", "FloatingMarkDemo", [({"p_mm": 72.8}, True), ({"x_mm": 3}, True), ({"view": "reverse"}, True),
                                    ({"area": "mast"}, False), ({"p_mm": 73}, True)]),
    ("stereo", "BaseHeightDemo", [({"B_m": 874}, True), ({"H_m": 1250}, True), ({"f_mm": 150}, True),
                                  ({"h_m": 30}, True)]),
    ("plan_correction", "PlanCorrectionDemo", [({"alpha_deg": 3.5}, True), ({"n": 5}, True),
                                               ({"method": "proportional"}, True), ({"spread_percent": 70}, True)]),
    ("control", "ControlDesignDemo", [({"m_eps_arcmin": 5}, True), ({"scheme": "dense"}, True), ({"m": 13000}, True),
                                      ({"n_strips": 4}, False), ({"m_allowed_mm": 0.3}, True)]),
    # the resection's frame is a round square around the known points (1, 1.25, 1.6, 2.5 km …): a station that
    # walks out of it is a full draw; the budget's mm axis ends at a round value beyond the longest bar
    ("control", "ResectionDemo", [({"north_m": -140}, True), ({"sigma_arcsec": 10}, True), ({"north_m": 1500}, False),
                                  ({"north_m": 1490}, True), ({"east_m": 1500}, True)]),
    ("rectification", "TransformerDemo", [({"step": 1}, True), ({"step": 5}, True), ({"alpha_deg": 4}, True),
                                          ({"step": 2}, True)]),
    ("block_accuracy", "BlockErrorDemo", [({"sigma_um": 8}, True), ({"every": 6}, True),
                                          ({"layout": "perimeter"}, True), ({"quantity": "height"}, False),
                                          ({"sigma_um": 12}, True)]),
    # chapter 15: σ, the blunder and a layout already factorised move the points, ellipses, arrows and |w| only
    ("block_adjustment_live", "BlockAdjustmentDemo", [({"sigma_um": 8}, True), ({"blunder": "off"}, True),
                                                      ({"blunder_mm": 0.3, "blunder": "on"}, True),
                                                      ({"layout": "corners"}, True), ({"sigma_um": 30}, True)]),
    ("dem_contours", "ContourDemo", [({"mz_m": 0.13}, True), ({"spacing_m": 40}, True), ({"structural": "on"}, True),
                                     ({"interval_m": 1.0}, True), ({"sheet": "plain (6–7 km E, 0.2–1.2 km N)"}, True)]),
    ("error_budget", "BudgetDemo", [({"M_c": 10500}, True), ({"P_um": 20}, True), ({"M_k": 5000.0}, True),
                                    ({"dtm": "plane"}, True), ({"extra": "on"}, True), ({"dtm": "instruction"}, True),
                                    ({"M_k": 500.0}, True), ({"M_c": 40000}, False), ({"dtm": "plane"}, False),
                                    ({"relief_m": 200}, False), ({"relief_m": 190}, True)]),
]

#: pixels that may differ from a draw without animation, and why
ALLOWED = {
    # after a full-draw move (pricking 0.3 mm), 2 antialiased pixels where a v arrow (zorder 7) meets the
    # strip's right spine differ by ≤ 12 levels of 255 — cause not pinned down; the blitted moves match exactly
    "ReductionDemo": 20,
}


def _demo(module, cls, **values):
    import matplotlib

    matplotlib.use("Agg")
    mod = importlib.import_module(f"aerophoto.demos.{module}")
    return getattr(mod, cls)(**values)


def _buffer(fig):
    return np.asarray(fig.canvas.buffer_rgba()).copy()


def _unanimated(demo):
    """The canvas after a full draw with no artist animated (blitting switched off), then blitting back on."""
    demo.blitter.disconnect()
    demo.fig.canvas.draw()
    ref = _buffer(demo.fig)
    demo.blitter = blit.Blitter(demo.fig, demo.animated)
    demo.fig.canvas.draw()
    return ref


def _ndiff(a, b) -> int:
    return int((np.abs(a.astype(int) - b.astype(int)).max(axis=2) > 0).sum())


@pytest.mark.parametrize(("module", "cls", "moves"), DEMOS, ids=[d[1] for d in DEMOS])
def test_blitted_move_paints_the_full_picture(module, cls, moves):
    demo = _demo(module, cls)
    assert demo.blitter is not None, f"{cls} declares no animated artists"
    demo.fig.canvas.draw()  # the first full draw takes the background
    for move, blit in moves:
        before = demo.blitter.n_blit
        demo.set(**move)
        if blit is not None:
            assert demo.blitter.n_blit == before + int(blit), f"{cls}.set({move}): blitted is not {blit}"
        blitted = _buffer(demo.fig)
        demo.draw(force=True)
        assert _ndiff(blitted, _buffer(demo.fig)) == 0, f"{cls}.set({move}): blitted ≠ forced full draw"
        n = _ndiff(blitted, _unanimated(demo))
        assert n <= ALLOWED.get(cls, 0), f"{cls}.set({move}): {n} pixels differ from a draw without blitting"
    demo.close()


def test_static_change_falls_back_to_a_full_draw():
    demo = _demo("interpretation", "ConditionsDemo")
    demo.fig.canvas.draw()
    demo.view.ax_nat.set_title("another title")  # not animated: the background is stale
    n_blit, n_full = demo.blitter.n_blit, demo.blitter.n_full
    demo.draw()
    assert demo.blitter.n_blit == n_blit and demo.blitter.n_full == n_full + 1
    assert _ndiff(_buffer(demo.fig), _unanimated(demo)) == 0
    demo.close()


def test_figure_size_change_falls_back_to_a_full_draw():
    demo = _demo("spectral_explorer", "SpectralExplorerDemo")
    demo.fig.canvas.draw()
    w, h = demo.fig.get_size_inches()
    demo.fig.set_size_inches(w * 0.9, h * 0.9)
    demo.fig.stale = False  # even if nothing marked it stale, the size alone forces a full draw
    n_blit = demo.blitter.n_blit
    demo.set(moisture_pct=12)
    assert demo.blitter.n_blit == n_blit
    demo.close()


#: the first four (the floor's ray among them), and demos that animate an axis of their own (its limits follow the data)
SAVED = DEMOS[:4] + [d for d in DEMOS if d[1] in ("BaseHeightDemo", "ResectionDemo")]


def _registry_demos():
    from aerophoto import book

    return [(c.number, d.cell, d.cls) for c in book.CHAPTERS for d in c.demos]


@pytest.mark.parametrize(("chapter", "cell", "path"), _registry_demos(), ids=lambda v: str(v).rsplit(".", 1)[-1])
def test_every_live_figure_fits_its_column(chapter, cell, path):
    """A figure wider than the demo layout's right-hand column is cut off on the right on a lecturer's screen."""
    from aerophoto.widgets import FIGURE_MAX_PX

    module, cls = path.removeprefix("aerophoto.demos.").rsplit(".", 1)
    demo = _demo(module, cls)
    width_px = float(demo.fig.get_figwidth() * demo.fig.dpi)
    demo.close()
    assert width_px <= FIGURE_MAX_PX, f"chapter {chapter} {cell}: the figure is {width_px:.0f} px wide, the column {FIGURE_MAX_PX}"


@pytest.mark.parametrize(("module", "cls", "moves"), SAVED, ids=[d[1] for d in SAVED])
def test_savefig_shows_the_animated_artists(module, cls, moves):
    """A saved or inline figure (savefig) shows the whole picture, animated artists included."""
    import io

    from PIL import Image

    demo = _demo(module, cls)
    demo.set(**moves[0][0])

    def png():
        buf = io.BytesIO()
        demo.fig.savefig(buf, format="png", dpi=50)
        return np.asarray(Image.open(buf).convert("RGBA"))

    with_blitter = png()
    demo.blitter.disconnect()
    assert _ndiff(with_blitter, png()) == 0
    demo.close()


def test_blitting_can_be_switched_off(monkeypatch):
    monkeypatch.setenv("AEROPHOTO_BLIT", "0")
    demo = _demo("footprint", "FootprintDemo")
    assert demo.blitter is None
    demo.set(f_mm=150)
    demo.close()


def test_animated_artists_must_belong_to_the_figure():
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    other, ax2 = plt.subplots()
    (line,) = ax2.plot([0, 1])
    with pytest.raises(ValueError, match="animated"):
        blit.Blitter(fig, [line])


def test_transformer_preview_and_full_resolution_both_blit():
    """A photo slider's preview (a coarser raster, ending up to a pixel further out) and the full render after it
    keep the screen's limits: both are blits, and the blitted pictures are those of full draws."""
    demo = _demo("rectification", "TransformerDemo")
    demo.fig.canvas.draw()
    n_blit = demo.blitter.n_blit
    demo._preview = True
    try:
        demo.set(alpha_deg=4)
    finally:
        demo._preview = False
    assert demo.result.preview and demo.blitter.n_blit == n_blit + 1
    blitted = _buffer(demo.fig)
    assert _ndiff(blitted, _unanimated(demo)) == 0
    n_blit = demo.blitter.n_blit
    demo.update()  # the slider rests: full resolution
    assert demo.blitter.n_blit == n_blit + 1
    assert _ndiff(_buffer(demo.fig), _unanimated(demo)) == 0
    demo.close()



@pytest.mark.parametrize(("reach", "half"), [(1.0, 1.0), (1.01, 1.25), (1.9, 2.0), (2.2, 2.5), (3.3, 4.0),
                                             (8.5, 10.0), (0.031, 0.032), (0.0, 1e-6)])
def test_coarse_ceil_is_the_next_round_value(reach, half):
    assert plots.coarse_ceil(reach) == pytest.approx(half)


# ------------------------------------------------------------------ images drawn by gathering pixels (blit.NearestImage)
def _drawn(data, fast, *, figsize=(6.0, 4.0), dpi=100, origin="lower", interpolation="nearest", **kw):
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=figsize, dpi=dpi)
    im = ax.imshow(data, origin=origin, interpolation=interpolation, extent=(3, 17, -2, 9.5), aspect="auto", **kw)
    if fast:
        assert blit.nearest_pixels(im) is im and isinstance(im, blit.NearestImage)
    fig.canvas.draw()
    px = np.asarray(fig.canvas.buffer_rgba()).astype(int)
    plt.close(fig)
    return px


@pytest.mark.parametrize("kind, shape, origin, figsize", [
    ("rgba8", (210, 290), "lower", (8.4, 5.4)),   # the rough mosaic's plan (quality demo)
    ("grey", (186, 401), "lower", (8.8, 5.6)),    # the fotoschema's preview
    ("rgb", (50, 70), "upper", (6.0, 4.0)),       # a float RGB photo, row 0 on top
    ("grey", (33, 20), "upper", (3.0, 5.0)),
])
def test_a_nearest_image_drawn_by_gathering_is_matplotlibs_picture(kind, shape, origin, figsize):
    """The same picture as matplotlib's resampler, except along a screen column or row whose pixel centres fall on
    a boundary between two array pixels (agg's fixed-point rounding takes the neighbour there): under 1 % of the
    pixels, each the colour of its neighbour in matplotlib's picture."""
    rng = np.random.default_rng(len(shape) + shape[0])
    if kind == "rgba8":
        data = rng.integers(0, 256, shape + (4,), dtype=np.uint8)
        data[..., 3] = 255
    else:
        data = rng.random(shape + ((3,) if kind == "rgb" else ())).astype(np.float32)
    _assert_same_but_boundaries(_drawn(data, False, figsize=figsize, origin=origin, cmap="gray", vmin=0, vmax=1),
                                _drawn(data, True, figsize=figsize, origin=origin, cmap="gray", vmin=0, vmax=1))


def _assert_same_but_boundaries(stock, fast, array_shape=None):
    """Each differing pixel has the colour of its left/right neighbour in matplotlib's picture (a column on a
    boundary between array columns) or of its upper/lower one (a row on a boundary between array rows).  Under 1 %
    of the pixels differ — or, for a small array magnified a lot (``array_shape``), such columns and rows number at
    most one per array column and row."""
    assert stock.shape == fast.shape
    differ = np.any(stock != fast, axis=2)
    across = np.zeros(differ.shape, bool)  # explained by a column boundary
    along = np.zeros(differ.shape, bool)  # explained by a row boundary
    for shift in (1, -1):
        across |= np.all(np.roll(stock, shift, axis=1) == fast, axis=2)
        along |= np.all(np.roll(stock, shift, axis=0) == fast, axis=2)
    assert (across | along)[differ].all()
    if array_shape is None:
        assert differ.mean() < 0.01
    else:
        assert np.any(differ & across & ~along, axis=0).sum() <= array_shape[1]
        assert np.any(differ & along & ~across, axis=1).sum() <= array_shape[0]


def test_a_nearest_image_leaves_the_rest_to_matplotlib_and_follows_its_data():
    rng = np.random.default_rng(3)
    data = rng.random((40, 60)).astype(np.float32)
    # smoothing, shrinking (more array pixels than screen pixels) and an alpha of its own: matplotlib's own path
    assert np.array_equal(_drawn(data, True, interpolation="antialiased"), _drawn(data, False, interpolation="antialiased"))
    big = rng.random((900, 1300)).astype(np.float32)
    assert np.array_equal(_drawn(big, True), _drawn(big, False))
    assert np.array_equal(_drawn(data, True, alpha=0.5), _drawn(data, False, alpha=0.5))
    # savefig at another resolution gathers for that resolution
    at_200 = _drawn(data, True, dpi=200, cmap="gray", vmin=0, vmax=1)
    assert at_200.shape == (800, 1200, 4)
    _assert_same_but_boundaries(_drawn(data, False, dpi=200, cmap="gray", vmin=0, vmax=1), at_200, data.shape)
    # new data and a new colour scale are drawn, not a picture kept from before
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(4, 3), dpi=100)
    im = blit.nearest_pixels(ax.imshow(data, interpolation="nearest", cmap="gray", vmin=0, vmax=1))
    fig.canvas.draw()
    first = np.asarray(fig.canvas.buffer_rgba()).copy()
    im.set_data(1.0 - data)
    fig.canvas.draw()
    second = np.asarray(fig.canvas.buffer_rgba()).copy()
    im.set_clim(0.0, 4.0)
    fig.canvas.draw()
    third = np.asarray(fig.canvas.buffer_rgba()).copy()
    plt.close(fig)
    assert np.any(first != second) and np.any(second != third)
    with pytest.raises(TypeError, match="image = "):
        blit.nearest_pixels(ax)


def test_the_live_raster_demos_gather_their_nearest_images():
    """The demos whose moves redraw a raster (the rough mosaic, the fotoschema's preview, the shooting conditions,
    the spectral explorer, the DEM's error field) draw it with blit.NearestImage."""
    from aerophoto.demos.dem_contours import ContourDemo
    from aerophoto.demos.fotoschema import FotoschemaDemo
    from aerophoto.demos.interpretation import ConditionsDemo
    from aerophoto.demos.quality import QualityDemo
    from aerophoto.demos.spectral_explorer import SpectralExplorerDemo

    images = {QualityDemo: lambda d: [d.view.image], FotoschemaDemo: lambda d: [d.view.image],
              ConditionsDemo: lambda d: [d.view.im_nat, d.view.im_cir], SpectralExplorerDemo: lambda d: [d.view.img],
              ContourDemo: lambda d: [d.view.image]}
    for Cls, get in images.items():
        d = Cls()
        assert all(isinstance(im, blit.NearestImage) for im in get(d)), Cls.__name__
