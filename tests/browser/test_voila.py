"""Lecture mode: each chapter served by Voilà (``voila notebooks/``) shows working demos without code."""

from __future__ import annotations

import pytest

from . import harness as h
from .chapters import CHAPTERS, CORE_VOILA, LECTURE_INDEX, core_params
from .demo_checks import assert_clean, exercise_demo

pytestmark = [pytest.mark.browser, pytest.mark.timeout(1800)]


def voila_demo_root(page, demo):
    """The demo showing all of ``demo``'s headline sliders (Voilà keeps no cell ids)."""
    loc = page.locator(".aerophoto-demo")
    for label, _key in demo.sliders:
        loc = loc.filter(has=page.locator(f'.widget-label:text-is("{label}")'))
    return loc.nth(demo.nth)


@pytest.mark.parametrize("chapter", core_params(core=CORE_VOILA))
def test_demos_in_voila(chapter, voila, tab):
    page = tab.page
    h.open_voila(page, voila, chapter.notebook)
    where = f"Voilà {chapter.notebook}"
    # lecture mode: outputs only, no code
    assert page.locator(".jp-InputArea-editor:visible").count() == 0, f"{where}: code is visible"
    for demo in chapter.demos:
        root = voila_demo_root(page, demo)
        root.wait_for(state="visible", timeout=h.T_RUN)
        exercise_demo(tab, root, demo, f"{where} [{demo.cell}]")
    assert_clean(tab, where)


def test_lecture_index_links_open_the_demos(voila, tab):
    """The lecture index links every chapter with a demo (beside its lecture page), and the link opens it."""
    page = tab.page
    h.open_voila(page, voila, LECTURE_INDEX)
    for chapter in CHAPTERS:
        link = page.locator(f'a[href="{chapter.notebook}"]')
        assert link.count() >= 1, f"the lecture index has no link to {chapter.notebook}"
    first = CHAPTERS[0]
    with page.expect_navigation(timeout=h.T_RUN):
        page.locator(f'a[href="{first.notebook}"]').first.click()
    assert page.url.split("?")[0].endswith(f"/voila/render/{first.notebook}"), page.url
    h.wait_voila_ready(page)
    root = voila_demo_root(page, first.demos[0])
    h.DemoProbe(page, root).wait_rendered()
    assert_clean(tab, f"Voilà {LECTURE_INDEX} → {first.notebook}")


def test_an_open_lecture_tab_keeps_its_kernel_and_a_closed_one_is_culled(browser, tab):
    """With voila.json's culling (here sped up to seconds): idle but connected → kept; tab closed → shut down."""
    first = CHAPTERS[0]
    fast = ["--MappingKernelManager.cull_idle_timeout=3", "--MappingKernelManager.cull_interval=1"]
    server = h.VoilaServer(extra_args=fast).start()
    try:
        page = tab.page
        h.open_voila(page, server, first.notebook)
        h.DemoProbe(page, voila_demo_root(page, first.demos[0])).wait_rendered()
        kernels = server.kernel_pids()
        assert len(kernels) == 1, f"expected one kernel for one open page, found {kernels}"
        # idle for longer than the cull timeout, several cull passes: the open tab keeps its kernel
        h.time.sleep(6)  # the condition here is elapsed time itself: twice the cull timeout, six cull passes
        assert server.kernel_pids() == kernels, "the kernel of an open lecture tab was culled"
        page.goto("about:blank")
        deadline = h.time.monotonic() + 120
        while server.kernel_pids() and h.time.monotonic() < deadline:
            h.time.sleep(0.5)  # polling the process table: there is no event to await
        assert not server.kernel_pids(), "the kernel of a closed Voilà page was not culled"
    finally:
        server.stop()
        h.shutil.rmtree(server.tmp, ignore_errors=True)
