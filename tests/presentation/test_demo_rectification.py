"""The rectification demo of chapter 11 (aerophoto.demos.rectification): the transformer's state is the screen image,
the demo walks the sequence and converges, previews while dragging and settles in full (also in a kernel),
never fails inside its slider ranges; the rectified figure and the residual field."""

import numpy as np
import pytest

from aerophoto import rectify as rf
from aerophoto.demos import rectification as dr

from .conftest import _extremes


def test_transformer_state_matrix_is_the_screen_image():
    st = rf.TransformerState(4.0, 30.0, -7.0, 2.5, 12.0, -3.0)
    xy = np.array([[10.0, -20.0], [-60.0, 45.0], [0.0, 0.0]])
    M = dr._state_matrix(st, 108.0)
    h = np.column_stack([xy, np.ones(3)]) @ M.T
    np.testing.assert_allclose(h[:, :2] / h[:, 2:], rf.screen_image(st, xy, 108.0), atol=1e-9)


def test_transformer_demo_walks_the_sequence_and_converges():
    d = dr.TransformerDemo()
    assert d.result.step == 0 and d.result.current.name == "start"
    conv = d.result.run.converged_step
    assert conv is not None and d.result.run.steps[conv].max_residual_mm <= 0.4
    d.set(step=conv)
    assert d.result.current.max_residual_mm <= 0.4
    d.set(step=3)
    assert d.result.current.name == "hh" and d.view.hh.get_xdata().size == 2
    d.set(step=20)  # beyond the end: the last step
    assert d.result.step == len(d.result.run.steps) - 1
    d.reset()
    assert d.result.step == 0
    d.close()


def test_transformer_demo_preview_on_slider_then_full():
    d = dr.TransformerDemo()
    d.values["alpha_deg"] = 4.0
    d.on_slider()  # no event loop: preview, then full resolution at once
    assert not d.result.preview and d.result.screen.pixel == dr.SCREEN_PIXEL_MM
    d.close()


def test_transformer_demo_in_a_kernel_previews_then_settles_and_says_so():
    """A slider move in a running kernel: the preview now and its status note after the picture (TABLE_DELAY_S,
    so that the page paints the frame first), the full picture once the slider rests, then the note cleared."""
    import asyncio

    from aerophoto.widgets import TABLE_DELAY_S

    async def until(cond, what):
        t0 = asyncio.get_running_loop().time()
        while not cond():  # a loaded machine may take a while
            assert asyncio.get_running_loop().time() - t0 < 30, f"never: {what}"
            await asyncio.sleep(0.01)

    async def drive():
        d = dr.TransformerDemo()
        d.controls()["alpha_deg"].value = 4.0  # the slider moves
        seen = [d.result.preview, d.status.value, d._later is not None]
        await until(lambda: "aerophoto-pending" in d.status.value or d._later is None, "the note")
        seen += ["aerophoto-pending" in d.status.value]
        await until(lambda: d._later is None and d.status.value == "", "the full picture and the note cleared")
        seen += [d.result.preview, d.result.screen.pixel == dr.SCREEN_PIXEL_MM]
        d.close()
        return seen

    assert asyncio.run(drive()) == [True, "", True, True, False, True]
    assert TABLE_DELAY_S < 0.25  # the note comes before the full picture (the demo's settle delay)


def test_a_slider_move_in_a_kernel_that_is_superseded_shows_no_stale_note():
    """Reset right after a slider move (before the deferred note): the note never appears, nothing stays pending."""
    import asyncio

    from aerophoto.widgets import TABLE_DELAY_S

    async def drive():
        d = dr.TransformerDemo()
        d.controls()["alpha_deg"].value = 4.0
        d._on_reset()
        await asyncio.sleep(TABLE_DELAY_S + 0.4)  # past the note's and the full picture's delays
        out = [d.status.value, d._later, d._status_pending, d.result.preview, d.values["alpha_deg"]]
        d.close()
        return out

    assert asyncio.run(drive()) == ["", None, None, False, 3.0]


@pytest.mark.parametrize("values", _extremes(dr.TransformerDemo))
def test_transformer_model_never_fails_in_range(values):
    r = dr.transformer_model(**{**{p.name: p.default for p in dr.TransformerDemo.params}, **values}, preview=True)
    assert np.isfinite(r.current.max_residual_mm) and len(r.table()) > 8


def test_rectified_figure_and_residual_field():
    from aerophoto.labs import ch11

    lab = ch11.example_rectification_lab(False)
    f = dr.residual_field(lab, relief=False)
    assert len(f) > 20 and np.hypot(f["dx, mm"], f["dy, mm"]).max() < 0.6 and (f["h, m"].abs() < 1e-9).all()
    lab_r = ch11.example_rectification_lab(True)
    fr = dr.residual_field(lab_r, relief=True)
    # with relief: the residuals grow with |h|
    big = fr["h, m"].abs() > 5
    assert np.hypot(fr["dx, mm"], fr["dy, mm"])[big].mean() > np.hypot(f["dx, mm"], f["dy, mm"]).mean()
    fig = dr.rectified_figure(lab, relief=False, n_px=128, pixel_mm=3.0)
    assert len(fig.axes) == 3
