"""Each chapter's live demos in JupyterLab: run all cells, move the headline sliders, see it change."""

from __future__ import annotations

import pytest

from . import harness as h
from .chapters import CHAPTERS
from .demo_checks import assert_clean, exercise_demo

pytestmark = [pytest.mark.browser, pytest.mark.timeout(1800)]


@pytest.mark.parametrize("chapter", CHAPTERS, ids=lambda c: c.name)
def test_demos_in_jupyterlab(chapter, lab, tab):
    page = tab.page
    h.open_lab_notebook(page, lab, chapter.notebook)
    h.run_all_cells(page)
    where = f"JupyterLab {chapter.notebook}"
    assert_clean(tab, where)
    # the "Jupyter news" question is switched off and no toast covers the notebook
    assert page.locator(".Toastify__toast", has_text="news").count() == 0
    for demo in chapter.demos:
        root = h.lab_demo_root(page, demo.cell)
        assert root.count() == 1, f"{where}: cell {demo.cell!r} shows no live demo (.aerophoto-demo)"
        exercise_demo(tab, root, demo, f"{where} [{demo.cell}]", after_move=lambda: h.lab_kernel_idle(page))
    assert_clean(tab, where)
