"""The live demos of chapters 09, 10, 11: they open on the guide's example, move their artists in place, never fail
inside their slider ranges, and Reset returns."""

import itertools

import numpy as np
import pytest

from aerophoto import rectify as rf
from aerophoto.demos import control as dc
from aerophoto.demos import plan_correction as pc
from aerophoto.demos import rectification as dr


def _extremes(demo_cls):
    """Every slider at its low and high end (choices: every option), one at a time."""
    out = []
    for p in demo_cls.params:
        if p.kind == "choice":
            out += [{p.name: o[1] if isinstance(o, tuple) else o} for o in p.options]
        else:
            out += [{p.name: p.lo}, {p.name: p.hi}]
    return out


# --------------------------------------------------------------------------- chapter 09
def test_plan_correction_demo_moves_in_place_and_resets():
    d = pc.PlanCorrectionDemo()
    d.draw(force=True)
    fig, carried0 = d.fig, [s.copy() for s in d.view.carried.get_segments()]
    table0 = d.table.value
    d.set(alpha_deg=8.0, n=8)
    assert d.fig is fig and d.table.value != table0
    assert not all(np.allclose(a, b) for a, b in zip(carried0, d.view.carried.get_segments()))
    d.reset()
    assert d.values["alpha_deg"] == 3.0 and d.table.value == table0
    d.close()


def test_plan_correction_demo_shows_the_two_constructions():
    d = pc.PlanCorrectionDemo(alpha_deg=6.0)
    central = d.result
    d.set(method="proportional")
    prop = d.result
    assert central.grid_error_mm < 0.2 < prop.grid_error_mm
    assert np.max(central.pair.node_error()) < 1e-8 < np.max(prop.pair.node_error())
    d.set(n=16)
    assert d.result.grid_error_mm == pytest.approx(prop.grid_error_mm, rel=1e-6)  # not refined away
    d.close()


@pytest.mark.parametrize("values", _extremes(pc.PlanCorrectionDemo))
def test_plan_correction_demo_never_fails_in_range(values):
    r = pc.plan_correction_model(**{**{p.name: p.default for p in pc.PlanCorrectionDemo.params}, **values})
    assert np.all(np.isfinite(r.errors_mm)) and r.table().shape[0] == 8


def test_the_static_figures_of_chapter_09():
    assert len(pc.grids_figure().axes) == 2
    assert len(pc.transfer_study_figure(alphas=(3.0,), ns=(1, 2, 4)).axes[0].lines) == 2


# --------------------------------------------------------------------------- chapter 10
def test_control_design_demo():
    d = dc.ControlDesignDemo()
    assert d.result.zhukov_n == 4 and d.result.design.n_points == 16 and d.result.dense_points == 48
    d.set(scheme="dense")
    assert d.result.design.dense and d.result.design.n_points == 48
    d.set(m=30000)  # k_i = 3: even one base is too many
    assert d.result.zhukov_n == 0
    d.reset()
    assert d.result.design.n_points == 16
    d.close()


@pytest.mark.parametrize("values", list(itertools.product((2.0, 8.0), (0.2, 0.6), (6000, 30000), (1, 5))))
def test_control_design_never_fails_in_range(values):
    e, m_allowed, m, k = values
    r = dc.control_design_model(e, m_allowed, m, k, 20)
    assert r.design.points_m.shape[1] == k + 1 and np.all(np.isfinite(r.design.points_m))


def test_resection_demo_and_its_danger_circle():
    d = dc.ResectionDemo()
    r0 = d.result
    assert r0.resection is not None and r0.cloud_rms_m < 0.5
    d.set(north_m=-270.0, east_m=-820.0)  # 3 m from the circle through I, II, III
    near = d.result
    assert near.cloud_rms_m > 50 * r0.cloud_rms_m
    assert any(q.startswith("shift of P per 1″") for q in near.table().index)
    d.set(sigma_arcsec=0.0)
    assert d.result.cloud_rms_m < 1e-3
    d.reset()
    d.close()


@pytest.mark.parametrize("north, east", list(itertools.product((-1500.0, 0.0, 1500.0), (-1500.0, 0.0, 1500.0))))
def test_resection_model_never_fails_in_range(north, east):
    r = dc.resection_model(north, east, 30.0)
    assert len(r.table()) >= 6


def test_resection_model_on_the_circle_reports_instead_of_failing():
    K = dc.guide_points().to_numpy()
    centre, R = dc.c.danger_circle(*K[:3])
    P = centre + R * np.array([0.0, -1.0])
    off = P - K[:3].mean(axis=0)
    r = dc.resection_model(off[0], off[1], 5.0)
    assert r.resection is None and "danger circle" in r.error
    assert r.table().loc["resection", "value"].startswith("undetermined")


def test_marking_figure():
    from aerophoto import geometry as g
    from aerophoto.render import render
    from aerophoto.site import get_site

    site = get_site()
    cx, cy = site.centre_m
    photo = render(site, g.Camera(100.0), g.Pose(cx + 700, cy, site.mean_height_m + 1200, 1.0, -60, 0), 128)
    fig = dc.marking_figure(photo)
    assert len(fig.axes) == 2 and len(fig.axes[0].patches) == 2 * int(
        (photo.points()["visible"] & photo.points()["control"]).sum())


# --------------------------------------------------------------------------- chapter 11
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
