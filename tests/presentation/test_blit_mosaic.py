"""Blitting in the two mosaic demos (issue 20): the rough mosaic (QualityDemo) and the fotoschema (FotoschemaDemo).

Their photo, marks and title change on every move; the axes stay put (the rough mosaic lies on a fixed board,
the fotoschema's limits are snapped), so a move redraws only the animated artists over the cached rest.  As in
tests/presentation/test_blit.py, after every ``demo.set(...)`` the canvas must equal a forced full draw of the same state and a
full draw with nothing animated (the picture without blitting), and the moves that keep the axes must really be
blitted (``blitter.n_blit`` grows).
"""

import importlib

import numpy as np
import pytest

from aerophoto import plots
from .test_blit import _buffer, _demo, _ndiff, _unanimated  # the same comparisons as the other demos

pytestmark = pytest.mark.usefixtures("plot_style")

#: (module, class, moves): each move a dict for demo.set and whether it must be blitted (True), must be a full
#: draw (False), or may be either (None: a plan change that may or may not move the axes' limits)
DEMOS = [
    ("quality", "QualityDemo", [
        ({"max_tilt_deg": 1.25}, True), ({"max_tilt_deg": 1.0}, True), ({"crab_deg": 7.0}, True),  # crab fails
        ({"crab_jitter_deg": 5.0}, True), ({"height_percent": 6.0}, True), ({"curvature_percent": -4.0}, True),
        ({"seed": 11}, True), ({"f_mm": 90}, True),  # f within its hundred: the same board
        ({"f_mm": 350}, False), ({"px_percent": 51}, None), ({"py_percent": 44}, None), ({"max_tilt_deg": 5.0}, True),
    ]),
    ("fotoschema", "FotoschemaDemo", [
        ({"alpha_max_deg": 1.25, "preview": True}, True), ({"alpha_max_deg": 1.0, "preview": True}, True),
        ({"alpha_max_deg": 1.25}, True),  # full resolution, same limits
        ({"relief_m": 35, "preview": True}, True), ({"seed": 4, "preview": True}, None),
        ({"px_percent": 75, "preview": True}, False),  # a shorter strip: new limits
        ({"relief_m": 150, "preview": True}, None), ({"cut_shape": "zigzag", "preview": True}, None),
    ]),
]


def _check_picture(demo, what):
    blitted = _buffer(demo.fig)
    demo.draw(force=True)
    assert _ndiff(blitted, _buffer(demo.fig)) == 0, f"{what}: blitted ≠ forced full draw"
    n = _ndiff(blitted, _unanimated(demo))
    assert n == 0, f"{what}: {n} pixels differ from a draw without blitting"


@pytest.mark.parametrize(("module", "cls", "moves"), DEMOS, ids=[d[1] for d in DEMOS])
def test_blitted_move_paints_the_full_picture(module, cls, moves):
    demo = _demo(module, cls)
    assert demo.blitter is not None, f"{cls} declares no animated artists"
    demo.fig.canvas.draw()  # the first full draw takes the background
    n_blitted = 0
    for move, blit in moves:
        before = demo.blitter.n_blit
        demo.set(**move)
        if blit is not None:
            assert demo.blitter.n_blit == before + int(blit), f"{cls}.set({move}): blitted is not {blit}"
        n_blitted += demo.blitter.n_blit - before
        _check_picture(demo, f"{cls}.set({move})")
    assert n_blitted >= sum(1 for _m, b in moves if b)
    demo.close()


def test_fotoschema_full_picture_after_a_preview_is_blitted_and_right():
    demo = _demo("fotoschema", "FotoschemaDemo")
    demo.fig.canvas.draw()
    demo.set(alpha_max_deg=1.5, preview=True)
    assert demo.result.preview
    shape = demo.result.image.shape
    n = demo.blitter.n_blit
    demo.render_full()  # what the settle timer does when the slider rests
    assert not demo.result.preview and demo.blitter.n_blit == n + 1
    assert demo.result.image.shape[1] > 2 * shape[1]  # 2.5 px/mm instead of 1
    _check_picture(demo, "render_full()")
    n = demo.blitter.n_blit
    demo.render_full()  # the full picture is shown already: nothing to do
    assert demo.blitter.n_blit == n
    demo.close()


def test_fotoschema_full_render_equals_the_model_at_full_resolution():
    from aerophoto.demos.fotoschema import fotoschema_model

    demo = _demo("fotoschema", "FotoschemaDemo")
    demo.set(relief_m=60, preview=True)
    demo.render_full()
    v = demo.values
    ref = fotoschema_model(v["f_mm"], v["m"], v["alpha_max_deg"], v["relief_m"], v["px_percent"], v["cut_shape"],
                           v["seed"], px_per_mm=demo.full_px_per_mm)
    assert demo.result.extent_mm == ref.extent_mm
    assert np.abs(demo.result.image - ref.image).max() < 1e-3
    demo.close()


def test_rough_mosaic_board_holds_every_print_at_the_sliders_extremes():
    """The board (the axes' limits) is fixed by the plan; the prints stay on it whatever the imperfections."""
    from aerophoto.demos.quality import board_extent_m, quality_model

    for f, px, py in ((70, 50, 10), (100, 60, 30), (250, 80, 45)):
        board = board_extent_m(f, px, py)
        for sign in (1, -1):
            r = quality_model(f_mm=f, px_percent=px, py_percent=py, max_tilt_deg=5, crab_deg=8 * sign,
                              crab_jitter_deg=5, height_percent=6, curvature_percent=4 * sign, seed=9,
                              extent_m=board)
            pts = r.outlines_m.reshape(-1, 2)
            assert r.extent_m == board
            assert pts[:, 0].min() > board[0] and pts[:, 0].max() < board[1]
            assert pts[:, 1].min() > board[2] and pts[:, 1].max() < board[3]
    assert board_extent_m(90, 60, 30) == board_extent_m(100, 60, 30)  # f within its hundred: the same board


def test_rough_mosaic_on_a_board_counts_as_the_prints_own_extent():
    """The raster on the fixed board is the same mosaic as the one on the prints' own extent, pixel for pixel."""
    from aerophoto import site
    from aerophoto.demos.quality import quality_model, rough_mosaic_raster

    r = quality_model(max_tilt_deg=2.5, crab_deg=-5, seed=7)
    s = site.get_site()
    img, ext, count = rough_mosaic_raster(r.flight.shots, s, r.outlines_m)
    x0 = ext[0] - 40 * 20.0
    y0 = ext[2] - 30 * 20.0
    board = (x0, x0 + (count.shape[1] + 60) * 20.0, y0, y0 + (count.shape[0] + 50) * 20.0)
    img_b, ext_b, count_b = rough_mosaic_raster(r.flight.shots, s, r.outlines_m, extent_m=board)
    assert ext_b == pytest.approx(board)
    inner = (slice(30, 30 + count.shape[0]), slice(40, 40 + count.shape[1]))
    assert np.array_equal(count_b[inner], count) and count_b.sum() == count.sum()
    assert np.allclose(img_b[inner], img, atol=1e-6)


def test_quality_demo_axes_stay_while_the_flight_is_broken():
    demo = _demo("quality", "QualityDemo")
    lims = (demo.view.ax.get_xlim(), demo.view.ax.get_ylim())
    for move in ({"max_tilt_deg": 5}, {"crab_deg": -8}, {"curvature_percent": 4}, {"height_percent": 6}):
        demo.set(**move)
        assert (demo.view.ax.get_xlim(), demo.view.ax.get_ylim()) == lims
    demo.close()


def test_table_follows_the_picture_in_a_running_kernel():
    """In a kernel (a running event loop) the table is set a moment after the picture was drawn; without one, at once."""
    import asyncio

    from aerophoto.demos import quality as Q

    demo = _demo("quality", "QualityDemo")
    before = demo.table.value
    seen = []

    async def drive():
        demo.set(crab_deg=7.0)  # the crab fails
        seen.append((demo.result.report.ok, demo.table.value == before))
        demo.set(crab_deg=7.5)  # a newer move replaces the pending table
        await asyncio.sleep(Q.TABLE_DELAY_S + 0.1)
        seen.append("FAIL" in demo.table.value and "7.5" in demo.table.value)

    asyncio.run(drive())
    assert seen == [(False, True), True]
    demo.set(crab_deg=0.0)
    assert "FAIL" not in demo.table.value
    demo.close()
