"""Each chapter's live demos in JupyterLab: run all cells, move the headline sliders, see it change.

Chapters 00 and 05 run in the README's test command; the others are ``exhaustive`` (CI runs them in a step of
their own, see tests/browser/chapters.py), and every chapter's demos also run in Voilà on its lecture page, on the
same widget and figure front end (in the README's command those of 05, 08, 11 and 16)."""

from __future__ import annotations

import pytest

from . import harness as h
from .chapters import core_params
from .demo_checks import assert_clean, exercise_demo

pytestmark = [pytest.mark.browser, pytest.mark.timeout(1800)]


@pytest.mark.parametrize("chapter", core_params())
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
