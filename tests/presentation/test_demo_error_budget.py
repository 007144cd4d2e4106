"""The error-budget demo of chapter 17 (aerophoto.demos.error_budget): opens on the article's 1:2000 case and moves
its bars; the static figure is the demo's view."""

import numpy as np
import pytest

from aerophoto import budget as bu
from aerophoto.demos.error_budget import BAR_KEYS, BudgetDemo, budget_figure


def test_budget_demo_opens_on_the_articles_1_2000_case_and_moves_its_bars():
    demo = BudgetDemo()
    B = demo.result
    ref = bu.budget(10000, 16, 2000)
    assert B.total_m == pytest.approx(ref.total_m) and not B.meets_tolerance
    widths = np.array([b.get_width() for b in demo.view.bars])
    assert widths[BAR_KEYS.index("total")] == pytest.approx(ref.map_rms_mm)
    assert widths[BAR_KEYS.index("dtm")] == pytest.approx(0.375)
    assert widths[BAR_KEYS.index("interior")] == 0.0
    assert "fails" in demo.view.title.get_text()
    fig = demo.fig
    demo.set(dtm="dem", m_h_m=0.5)
    assert demo.fig is fig and demo.result.meets_tolerance
    assert "meets" in demo.view.title.get_text()
    dom = BAR_KEYS.index(demo.result.dominant.key)
    assert demo.view.bars[dom].get_facecolor()[:3] != demo.view.bars[BAR_KEYS.index("scanning")].get_facecolor()[:3]
    w2 = np.array([b.get_width() for b in demo.view.bars])
    demo.set(M_c=20000, P_um=40)
    w3 = np.array([b.get_width() for b in demo.view.bars])
    assert w3[BAR_KEYS.index("triangulation")] > w2[BAR_KEYS.index("triangulation")]
    demo.set(extra="on")
    assert demo.view.bars[BAR_KEYS.index("interior")].get_width() > 0
    demo.set(dtm="plane", relief_m=100)
    assert demo.result.dominant.key == "dtm"
    assert "a DEM is needed" in demo.table.value
    with pytest.raises(ValueError, match="P_um = 100"):
        demo.set(P_um=100)
    demo.reset()
    assert demo.values["dtm"] == "instruction" and demo.result.total_m == pytest.approx(ref.total_m)
    demo.draw(force=True)
    demo.close()


def test_budget_figure_is_the_demos_view():
    fig = budget_figure(bu.budget(15000, 42, 10000))
    assert len(fig.axes[0].patches) == len(BAR_KEYS)
