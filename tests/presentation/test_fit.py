"""A demo sized by its page (aerophoto.fit, plots.scale_figure) and the tables' markup, without a browser."""

from __future__ import annotations

import matplotlib
import pandas as pd
import pytest

matplotlib.use("Agg")

from aerophoto import fit, plots  # noqa: E402


def test_page_box_reads_the_sensor_or_nothing():
    assert fit.PageBox.of([1250, 1280, 800, 140]) == fit.PageBox(1250, 1280, 800, 140)
    assert fit.PageBox.of([1250, 1280, 800, 140, 375, 300]).side_h == 300
    for bad in ([], None, [0, 1280, 800, 0], [1, 2, 3], ["a", 1, 2, 3]):
        assert fit.PageBox.of(bad) is None


def test_a_chapter_figure_goes_beside_the_sliders_or_under_them():
    box = fit.PageBox(848, 1280, 800)   # JupyterLab at 1280 px with its file browser open
    tall = fit.chapter_fit(box, (600, 590))   # chapter 03: fits beside at 446 px = 74 % of its size
    assert not tall.stacked and tall.width_px == 848 - fit.COLUMN_PX - fit.TOOLBAR_PX
    assert tall.text == fit.MIN_TEXT   # its text is not shrunk with it below 95 %
    wide = fit.chapter_fit(box, (860, 420))   # chapter 00: under the sliders at the column's width
    assert wide.stacked and wide.width_px == 848 - fit.TOOLBAR_PX and wide.height_px == round(420 * 808 / 860)
    roomy = fit.chapter_fit(fit.PageBox(1300, 1920, 1080), (860, 420))   # never larger than built
    assert (roomy.width_px, roomy.height_px, roomy.text, roomy.stacked) == (860, 420, 1.0, False)


def test_a_lecture_figure_takes_the_room_the_screen_leaves():
    small = fit.lecture_fit(fit.PageBox(1250, 1280, 800, 140), (880, 560))
    assert small.width_px + small.side_px + fit.TOOLBAR_PX + fit.GAP_PX <= 1250
    assert small.height_px <= 800 - 140 - fit.PAGE_TOP_PX - fit.BOTTOM_PX
    assert small.text == pytest.approx(small.width_px / 880, rel=1e-2)   # zoomed whole: no new layout
    big = fit.lecture_fit(fit.PageBox(1890, 1920, 1080, 150), (880, 560))
    assert big.width_px > 1.3 * small.width_px   # the view grows with the screen
    proj = fit.lecture_fit(fit.PageBox(1250, 1280, 800, 190), (880, 560), projector=True)
    assert proj.text >= fit.PROJECTOR_MIN and 11 * 100 * proj.text / 72 >= 18   # 11 pt ticks at ≥ 18 px
    assert proj.width_px < small.width_px   # the same room, larger text: the axes give way


def test_a_side_column_too_tall_for_the_screen_gets_wider():
    box = fit.PageBox(1250, 1280, 800, 190, side_w=425, side_h=700)   # room: 800 − 190 − 44 − 24 = 542 px
    wider = fit.lecture_fit(box, (880, 560), projector=True)
    assert wider.side_px >= 425 * 700 / 542 and wider.side_px <= 0.5 * 1250
    # once wide enough it stays (no back and forth while its content fills most of the room)
    held = fit.lecture_fit(fit.PageBox(1250, 1280, 800, 190, side_w=wider.side_px, side_h=540), (880, 560),
                           projector=True)
    assert held.side_px == wider.side_px


def _fixed_figure():
    fig = plots.figure(figsize=(8.0, 5.0), layout="none")
    ax = fig.add_axes([0.1, 0.12, 0.85, 0.8])
    ax.plot([0, 1000], [0, 1000])
    ax.set_xlabel("x, m")
    ax.set_ylabel("y, m")
    ax.set_title("a title")
    return fig, ax


def test_scale_figure_zooms_or_lays_out_again():
    fig, ax = _fixed_figure()
    assert plots.natural_size_px(fig) == (800, 500)
    assert plots.scale_figure(fig, 600, 375, 0.75)   # pure zoom: the same layout, 75 % of everything
    assert fig.dpi == pytest.approx(75) and tuple(fig.get_size_inches()) == pytest.approx((8.0, 5.0))
    assert ax.get_position().bounds == pytest.approx((0.1, 0.12, 0.85, 0.8))
    assert not plots.scale_figure(fig, 600, 375, 0.75)   # nothing to change
    # larger text in the same picture: the margins grow with it, the axes keep at least 40 % of their size
    assert plots.scale_figure(fig, 800, 500, 1.3)
    x0, y0, w, h = ax.get_position().bounds
    assert x0 == pytest.approx(0.1 * 1.3) and y0 == pytest.approx(0.12 * 1.3) and 0.4 * 0.85 <= w < 0.85
    fig.canvas.draw()
    label = ax.yaxis.label.get_window_extent()
    assert label.x0 >= 0 and ax.xaxis.label.get_window_extent().y0 >= 0   # nothing cut off at the edges
    assert plots.scale_figure(fig, 800, 500, 1.0)   # back: as built
    assert ax.get_position().bounds == pytest.approx((0.1, 0.12, 0.85, 0.8))
    with pytest.raises(ValueError, match="width_px = 0"):
        plots.scale_figure(fig, 0, 500, 1.0)


def test_a_title_too_wide_for_the_figure_is_set_smaller():
    """In the book's style (its 13-pt titles: the run order of the tests decided before whether the style was on)."""
    import matplotlib

    with matplotlib.rc_context(plots.STYLE):
        fig = plots.figure(figsize=(6.0, 4.0), layout="constrained")
        ax = fig.add_subplot()
        ax.set_title("Fotoschema 1:12 043 · m = 0.19 mm · seams pass")
        ax.plot([0, 1], [0, 1])
        fig.canvas.draw()
        plots.freeze_layout(fig)
        fig.canvas.draw()
        plots.scale_figure(fig, 400, 267, 1.3)
        fig.canvas.draw()
        assert ax.title.get_window_extent().width <= fig.bbox.width
        assert ax.title.get_fontsize() < ax.title._aerophoto_size   # set smaller to fit, its own size kept
        plots.scale_figure(fig, 600, 400, 1.0)   # room again: its own size back
        assert ax.title.get_fontsize() == ax.title._aerophoto_size


def test_a_centred_title_over_axes_off_the_figures_centre_stays_on_the_figure():
    """Chapter 16's lecture demo in projector mode cut "(1225 nodes)" at the right: the title is centred on the
    axes, which a y label moves right of the figure's centre — its room is twice the nearer edge's distance."""
    import matplotlib

    with matplotlib.rc_context(plots.STYLE):
        fig = plots.figure(figsize=(6.0, 4.0), layout="constrained")
        ax = fig.add_subplot()
        ax.set_title("h = 0.5 m: RMS of contour heights 0.080 m (1225 nodes)")
        ax.set_ylabel("y, m")
        ax.plot([0, 1], [0, 1])
        fig.canvas.draw()
        plots.freeze_layout(fig)
        fig.canvas.draw()   # the layout frozen, as in a live demo
        plots.scale_figure(fig, 500, 500, 1.5)
        fig.canvas.draw()
        box = ax.title.get_window_extent()
        assert box.x0 >= 0 and box.x1 <= fig.bbox.width, (box, fig.bbox.width)


def test_the_figure_is_drawn_under_its_lock():
    fig, _ax = _fixed_figure()
    lock = plots.figure_lock(fig)
    assert plots.figure_lock(fig) is lock
    seen = []
    original = type(fig.canvas).draw

    def spy(canvas):
        seen.append(lock._is_owned())
        return original(canvas)

    type(fig.canvas).draw = spy
    try:
        plots.lock_canvas(fig)
        plots.lock_canvas(fig)   # idempotent: wrapped once
        fig.canvas.draw()
    finally:
        type(fig.canvas).draw = original
    assert seen == [True]


def test_tables_have_real_headers_and_numbers_that_do_not_break():
    df = pd.DataFrame({"value": [12043.0, 0.5], "verdict": ["pass", "regular grid (bilinear)"]},
                      index=pd.Index(["1a–4a", "mean scale"], name=""))
    html = plots.html_table(df, caption="Seams")
    assert "<th scope='col'>value</th>" in html and "<th scope='row' class='num'>1a–4a</th>" in html
    assert "<th></th>" not in html and "<td></td>" in html   # the corner cell is no empty header
    assert "<td class='num'>12\u202f043</td>" in html and "<td>regular grid (bilinear)</td>" in html
    folded = plots.html_table(df, caption="Seams", fold=True)
    assert "<details data-fold='Seams'><summary>Seams</summary>" in folded and "<caption" not in folded
    assert "<details data-fold='Seams' open>" in plots.html_table(df, caption="Seams", fold="open")
    nameless = plots.html_table(pd.DataFrame({"": ["a", "b"]}, index=["key", "признак"]))
    assert "<thead>" not in nameless   # no header row of empty cells
