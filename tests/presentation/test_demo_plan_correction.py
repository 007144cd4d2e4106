"""The plan-correction demo of chapter 09 (aerophoto.demos.plan_correction): opens on the guide's example, moves its
artists in place, never fails inside its slider ranges, Reset returns; the chapter's static figures."""

import numpy as np
import pytest

from aerophoto.demos import plan_correction as pc

from .conftest import _extremes


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
