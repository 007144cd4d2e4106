"""The contour demo of chapter 16 (aerophoto.demos.dem_contours): opens on the article's example and moves its
artists, refuses values out of range, works on every sheet, previews while dragging and settles in full; the
spacing study figure."""

import numpy as np
import pytest

from aerophoto import dem
from aerophoto.demos.dem_contours import SHEETS, ContourDemo, contour_frame, spacing_study_figure


def _segments(lc):
    return [np.asarray(s).copy() for s in lc.get_segments()]


def test_contour_demo_opens_on_the_articles_example_and_moves_its_artists():
    demo = ContourDemo()
    assert demo.values == {"spacing_m": 30, "structural": "off", "mz_m": 0.12, "interval_m": 0.5,
                           "sheet": SHEETS[0][0]}
    fig = demo.fig
    r = demo.result.result
    assert r.dem.kind == "grid" and r.dem.n_nodes == 35 * 35
    assert 0.07 < r.accuracy.rms_m < 0.09  # √(4/9)·12 cm: the nodes' errors, the 30 m grid follows the hills
    segs0 = _segments(demo.view.dem_lc)
    img0 = np.array(demo.view.image.get_array()).copy()
    assert len(segs0) == len(r.contours) and len(demo.view.valley_lc.get_segments()) == 0
    n0 = demo.n_updates
    demo.set(spacing_m=150, structural="on")
    assert demo.fig is fig and demo.n_updates == n0 + 1
    r1 = demo.result.result
    assert r1.dem.kind == "tin" and "line" in r1.dem.kinds
    assert len(demo.view.ridge_lc.get_segments()) > 0
    assert len(demo.view.nodes.get_offsets()) == r1.dem.n_nodes
    np.testing.assert_allclose(np.array(demo.view.image.get_array()), r1.Z_dem - r1.Z_true)
    assert not np.allclose(img0, np.array(demo.view.image.get_array()))
    assert f"{r1.accuracy.rms_m:.3f}" in demo.view.title.get_text()
    assert "grid + structural lines" in demo.table.value
    demo.set(mz_m=0.0, interval_m=1.0)
    assert demo.result.result.interval_m == 1.0 and demo.result.result.dem.mz_m == 0.0
    demo.reset()
    assert demo.values["spacing_m"] == 30 and demo.result.result.accuracy.rms_m == pytest.approx(r.accuracy.rms_m)
    demo.draw(force=True)
    demo.close()


def test_contour_demo_rejects_values_out_of_range():
    demo = ContourDemo()
    with pytest.raises(ValueError, match="spacing_m = 5"):
        demo.set(spacing_m=5)
    with pytest.raises(ValueError, match="structural"):
        demo.set(structural="maybe")
    with pytest.raises(ValueError, match="not a parameter"):
        demo.set(grid_m=30)
    demo.close()
    with pytest.raises(ValueError, match="sheet"):
        contour_frame("the moon")
    with pytest.raises(ValueError, match="interval_m"):
        contour_frame(interval_m=0.3)


def test_every_sheet_of_the_demo_works():
    for label, (x0, y0) in SHEETS:
        f = contour_frame(label, 60.0, True, 0.05, 0.5)
        assert f.cache.sheet == dem.Sheet(x0, y0, 1000.0)
        assert np.isfinite(f.result.accuracy.rms_m) and f.table().loc["nodes", "value"] == str(f.result.dem.n_nodes)


def test_spacing_study_figure_draws_each_column():
    study = dem.spacing_study(__import__("aerophoto.site", fromlist=["get_site"]).get_site(), dem.Sheet(2000, 3000),
                              spacings_m=(50.0, 150.0))
    fig = spacing_study_figure(study)
    assert len(fig.axes[0].get_lines()) == 4


def test_contour_demo_previews_while_dragging_and_settles_in_full():
    import asyncio

    async def drive():
        demo = ContourDemo()
        assert demo.result.cache.cell_m == 5.0
        demo.values["spacing_m"] = 60  # as a slider move does before calling on_slider
        status = demo.on_slider()
        assert "preview" in status and demo.result.cache.cell_m == 10.0
        assert demo.result.result.dem.n_nodes == 18 * 18  # 0, 60, …, 960 and the far edge
        demo.values["spacing_m"] = 70  # a second move cancels the pending full render
        demo.on_slider()
        await asyncio.sleep(demo.settle_s + 0.4)
        assert demo.result.cache.cell_m == 5.0 and demo.status.value == ""
        assert demo.result.result.dem.n_nodes == 16 * 16
        # Reset while a full render is pending: the start values in full, the note gone, nothing left to run
        demo.values["spacing_m"] = 90
        demo.status.value = demo.on_slider()  # as a slider move does
        assert "aerophoto-pending" in demo.status.value and demo._later is not None
        n = demo.n_updates
        demo._on_reset()  # what the Reset button does
        assert demo._later is None and demo.status.value == "" and demo.values["spacing_m"] == 30
        assert demo.result.cache.cell_m == 5.0 and demo.n_updates == n + 1
        await asyncio.sleep(demo.settle_s + 0.2)
        assert demo.n_updates == n + 1  # the dropped full render never ran
        demo.close()

    asyncio.run(drive())
    # without an event loop (a script) a slider move renders in full at once
    demo = ContourDemo()
    demo.values["spacing_m"] = 60
    assert demo.on_slider() == "" and demo.result.cache.cell_m == 5.0
    demo.close()
