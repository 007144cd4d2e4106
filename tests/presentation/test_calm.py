"""Calm while sliding (issue 33): the status words never in a title, a status line of fixed height, the table never
behind the figure during a stream of moves, the transformer's discrete steps at full resolution, chapter 03's
arrows at a fixed ×2 (doubling the relief doubles every arrow), o/n/c labels that never overlap."""

from __future__ import annotations

import asyncio

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

from aerophoto.widgets import TABLE_DELAY_S  # noqa: E402


def test_a_stream_of_moves_faster_than_the_delay_keeps_the_table_with_the_figure():
    """Moves every TABLE_DELAY_S/2: the table follows within one delay (before, each move re-armed the timer and
    the table stayed on the first move's numbers while the figure moved on); it ends on the newest move."""
    from aerophoto.demos.dem_contours import ContourDemo

    async def drive():
        demo = ContourDemo()
        seen = []
        try:
            for d in (40, 50, 60, 70, 80, 90):
                demo.controls()["spacing_m"].value = d
                await asyncio.sleep(TABLE_DELAY_S / 2)
                seen.append(demo.table.value)
            await asyncio.sleep(TABLE_DELAY_S + 0.5)
            demo.cancel_later()
            final = demo.table.value, demo.view.title.get_text(), demo.result.result.dem.n_nodes
        finally:
            demo.close()
        return seen, final

    seen, (table, title, n_nodes) = asyncio.run(drive())
    assert len(set(seen[1:])) > 1  # the table changed while the slider moved (it was frozen before)
    from aerophoto.i18n.numfmt import fmt_count

    assert f"({fmt_count(n_nodes)} nodes)" in title and fmt_count(n_nodes) in table  # figure and table agree


def test_status_words_never_in_the_fotoschema_title():
    from aerophoto.demos.fotoschema import FotoschemaDemo

    d = FotoschemaDemo()
    try:
        full = d.view.title.get_text()
        d.set(preview=True, relief_m=d.values["relief_m"])
        assert d.result.preview and d.view.title.get_text() == full
        assert "preview" not in full and "resolution" not in full
    finally:
        d.close()


def test_the_status_line_keeps_its_height_and_one_line():
    from aerophoto.demos.footprint import FootprintDemo
    from aerophoto.widgets import pending_html

    d = FootprintDemo()
    try:
        assert d.status.layout.min_height == "24px"
        assert "white-space:nowrap" in pending_html()
    finally:
        d.close()


def test_the_transformer_step_draws_at_full_resolution_at_once():
    """In a kernel: a step move is drawn at full resolution at once with no status note; a photo slider previews."""
    from aerophoto.demos.rectification import TransformerDemo

    async def drive():
        d = TransformerDemo()
        try:
            d.controls()["step"].value = 3
            step = (d.result.preview, d.result.step, d._later is None, d.status.value)
            d.controls()["alpha_deg"].value = 4.0
            photo = d.result.preview
            d.controls()["step"].value = 4  # a step while the photo's full picture is pending: full at once
            after = (d.result.preview, d._later is None)
        finally:
            d.close()
        return step, photo, after

    step, photo, after = asyncio.run(drive())
    assert step == (False, 3, True, "")
    assert photo is True
    assert after == (False, True)


@pytest.mark.parametrize("cls", ["ReliefDemo", "DisplacementDemo"])
def test_doubling_the_relief_doubles_every_arrow(cls):
    from aerophoto.demos import displacement

    d = getattr(displacement, cls)()
    try:
        d.set(relief_m=60)
        u1 = np.asarray(d.view.q_relief.U).copy()
        title = d.view.title.get_text()
        d.set(relief_m=120)
        u2 = np.asarray(d.view.q_relief.U)
        assert d.factor == 2 and "×2" in title and d.view.title.get_text() == title
        assert np.max(np.abs(u2)) == pytest.approx(2 * np.max(np.abs(u1)), rel=0.15)
        d.reset()
        assert d.values["exaggeration"] == 2
    finally:
        d.close()


@pytest.mark.parametrize("alpha", [0.0, 1.0, 2.5, 4.0, 7.0, 10.0])
def test_o_n_c_labels_never_overlap(alpha):
    from aerophoto.demos.displacement import ReliefDemo
    from aerophoto.demos.footprint import FootprintDemo

    for demo in (FootprintDemo(alpha_deg=alpha), ReliefDemo(alpha_deg=alpha)):
        try:
            demo.draw(force=True)
            r = demo.fig.canvas.get_renderer()
            boxes = [demo.view.marks[n][1].get_window_extent(r) for n in "onc"]
            for i in range(3):
                for j in range(i + 1, 3):
                    assert not boxes[i].overlaps(boxes[j]), (alpha, "onc"[i], "onc"[j])
        finally:
            demo.close()
