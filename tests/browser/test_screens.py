"""The lecture pages at both projector sizes and in projector mode, JupyterLab with its file browser open, axe-core.

Issue 33's views, as a lecturer projects them (the 1280×800 lecture pages in normal mode are
``test_lectures.py``, in the README's command; these run in .ci/run's second step, marked ``exhaustive``):

* the lecture pages of chapters 05, 08, 11 and 16 (the issue's four) in Voilà at **1920×1080**, then with
  **Projector** on at 1920×1080 and 1280×800: every demo, scrolled to the top of the screen, has its whole figure
  and its whole table on the screen and the page does not scroll sideways — except that in projector mode at
  1280×800 a long table only has to start beside the figure and its side column scrolls inside the screen
  (chapter 11's 15 rows at 19 px are taller than the room left); in projector mode the text of the slider labels and readouts, the buttons and the table
  cells is at least 18 px (computed font size), and the mode is remembered by the next page;
* chapter 03 of the workbook in JupyterLab at 1280×800 **with the file browser open** (Lab's default): after
  Run All each demo's figure and table lie inside the notebook's column — nothing under the side bar, no
  horizontal scroll in the notebook;
* axe-core (npm, deploy/site's lock, injected by Playwright) over the lecture index, the lecture page of 05 and
  the JupyterLab chapter's text and outputs (Lab's own editors are JupyterLab's): no serious or critical violation.

Screenshots of every view go to artifacts/ with ``AEROPHOTO_SCREENSHOTS=1`` (always on failure).
"""

from __future__ import annotations

import json

import pytest

from aerophoto.book import chapter as book_chapter
from aerophoto.book import lecture_page

from . import harness as h
from .chapters import LECTURE_INDEX

pytestmark = [pytest.mark.browser, pytest.mark.exhaustive, pytest.mark.timeout(2400)]

NOTEBOOK = h.LAB_NOTEBOOK
#: what the book puts in it: the chapter's text and the cells' outputs
CONTENT = f"{NOTEBOOK} .jp-MarkdownOutput, {NOTEBOOK} .jp-OutputArea-output"
#: the issue's four lecture pages
LECTURE_CHAPTERS = ("05_fotoschema", "08_interpretation", "11_rectification", "16_dem_contours")
SCREENS = {"1280x800": {"width": 1280, "height": 800}, "1920x1080": {"width": 1920, "height": 1080}}
#: the smallest text of projector mode (issue 33: "≥ 18 px at 1280×800")
PROJECTOR_MIN_PX = 18.0
#: what projector mode must enlarge: slider labels and readouts, buttons, the tables' cells, the figures' keys
PROJECTOR_TEXT = (".widget-slider .widget-label", ".widget-readout", ".widget-button", ".widget-toggle-button",
                  ".aerophoto-table td", ".aerophoto-table th", ".aerophoto-legend")


def _inside(box, screen: dict, where: str, what: str) -> None:
    vw, vh = screen["width"], screen["height"]
    assert box is not None, f"{where}: the {what} is not displayed"
    assert box["x"] >= -0.5 and box["y"] >= -0.5 and box["x"] + box["width"] <= vw + 0.5 and \
        box["y"] + box["height"] <= vh + 0.5, f"{where}: the {what} {box} is not inside the {vw}×{vh} screen"


def _smallest_text(root) -> dict:
    """The smallest computed font size (px) of each kind of projector text inside the demo ``root``."""
    return root.evaluate("""(el, sels) => Object.fromEntries(sels.map((s) => {
        const sizes = [...el.querySelectorAll(s)].filter((e) => e.offsetParent !== null && e.textContent.trim())
                      .map((e) => parseFloat(getComputedStyle(e).fontSize));
        return [s, sizes.length ? Math.min(...sizes) : null]; }))""", list(PROJECTOR_TEXT))


def _demos_fit(tab, page, chapter, screen: dict, where: str, shot: str, *, whole_table: bool = True) -> None:
    roots = page.locator(".aerophoto-demo")
    roots.first.wait_for(state="visible", timeout=h.T_RUN)
    assert roots.count() == len(chapter.demos), f"{where}: {roots.count()} demos shown, {len(chapter.demos)} registered"
    for k, demo in enumerate(chapter.demos):
        probe = h.DemoProbe(page, roots.nth(k))
        probe.wait_rendered()  # scrolled to the top of the screen, sized for it
        tab.add(f"{demo.cell}-{shot}", page.screenshot())
        w = f"{where} [{demo.cell}]"
        _inside(probe.canvas().bounding_box(), screen, w, "figure")
        table = probe.table().bounding_box()
        if whole_table:
            _inside(table, screen, w, "table")
        else:  # projector mode at 1280×800: the table starts beside the figure; the side column holding it stays
            # on the screen, and a table taller than that column scrolls inside it (the page does not)
            _inside({**table, "height": min(table["height"], 2 * 19 * 1.3)}, screen, w, "table's first rows")
            side = roots.nth(k).locator(".aerophoto-side")
            _inside(side.bounding_box(), screen, w, "side column (key, status line, table)")
            room = side.evaluate("(el) => ({over: el.scrollHeight - el.clientHeight, "
                                 "scrolls: ['auto', 'scroll'].includes(getComputedStyle(el).overflowY)})")
            assert room["over"] <= 1 or room["scrolls"], f"{w}: the side column hides {room['over']} px of its table"
    h.assert_no_sideways_scroll(page, where)


def _set_projector(page, on: bool) -> None:
    """Click the first demo's Projector toggle (it switches every demo of the page) and wait for the re-fit."""
    root = page.locator(".aerophoto-demo").first
    toggle = root.locator(".widget-toggle-button", has_text="Projector").first
    pressed = "mod-active" in (toggle.get_attribute("class") or "")
    if pressed == on:
        return
    probes = [h.DemoProbe(page, page.locator(".aerophoto-demo").nth(k))
              for k in range(page.locator(".aerophoto-demo").count())]
    counts = [p.fit_count() for p in probes]
    toggle.click()
    page.wait_for_function("(el) => el.classList.contains('aerophoto-projector') === %s" % ("true" if on else "false"),
                           arg=root.element_handle(), timeout=h.T_RUN, polling=100)
    for p, n in zip(probes, counts):
        p.root.evaluate("(el) => el.scrollIntoView({block: 'start'})")
        p.wait_fitted(n)


@pytest.mark.parametrize("name", LECTURE_CHAPTERS)
def test_a_lecture_page_fits_1920x1080_and_projector_mode_is_large(name, voila, tab):
    chapter = book_chapter(name)
    page = tab.page
    url = lecture_page(chapter)
    # 1920×1080, normal mode
    big = SCREENS["1920x1080"]
    page.set_viewport_size(big)
    h.open_voila(page, voila, url)
    _demos_fit(tab, page, chapter, big, f"Voilà {url} at 1920×1080", "1920x1080")
    # projector mode at 1920×1080: larger text, still one screen
    _set_projector(page, True)
    try:
        _demos_fit(tab, page, chapter, big, f"Voilà {url} at 1920×1080, projector", "1920x1080-projector")
        # and at 1280×800 after a reload: the mode is remembered by the browser
        small = SCREENS["1280x800"]
        page.set_viewport_size(small)
        h.open_voila(page, voila, url)
        roots = page.locator(".aerophoto-demo")
        roots.first.wait_for(state="visible", timeout=h.T_RUN)
        page.wait_for_function("(el) => el.classList.contains('aerophoto-projector')",
                               arg=roots.first.element_handle(), timeout=h.T_RUN, polling=250)
        where = f"Voilà {url} at 1280×800, projector"
        _demos_fit(tab, page, chapter, small, where, "1280x800-projector", whole_table=False)
        for k, demo in enumerate(chapter.demos):
            sizes = _smallest_text(roots.nth(k))
            small_text = {s: px for s, px in sizes.items() if px is not None and px < PROJECTOR_MIN_PX}
            assert not small_text, f"{where} [{demo.cell}]: text under {PROJECTOR_MIN_PX:g} px: {small_text}"
            assert sizes[".widget-slider .widget-label"] is not None and sizes[".aerophoto-table td"] is not None, (
                f"{where} [{demo.cell}]: no slider label or table cell found ({sizes})")
    finally:
        _set_projector(page, False)  # the next test's page starts in normal mode (the mode is remembered)


def test_a_chapter_in_jupyterlab_fits_beside_the_open_file_browser(lab, tab):
    """Chapter 03 at 1280×800 with Lab's file browser open: the notebook column is ~950 px, the demos fit it."""
    from . import site_harness as S

    chapter = book_chapter("03_relief_displacement")
    page = tab.page
    h.open_lab_notebook(page, lab, chapter.notebook)
    if page.locator(".jp-FileBrowser:visible").count() == 0:  # Lab opens with it; open it if a setting closed it
        page.locator('.jp-SideBar .lm-TabBar-tab[data-id="filebrowser"]').click()
    page.locator(".jp-FileBrowser").first.wait_for(state="visible", timeout=h.T_PAGE)
    h.run_all_cells(page)
    column = page.locator(NOTEBOOK).first.bounding_box()
    side = page.locator(".jp-FileBrowser").first.bounding_box()
    assert side["width"] > 150 and column["x"] >= side["x"] + side["width"] - 1, (column, side)
    for demo in chapter.demos:
        root = h.lab_demo_root(page, demo.cell)
        probe = h.DemoProbe(page, root)
        probe.wait_rendered()
        tab.add(f"{demo.cell}-lab-filebrowser", page.screenshot())
        h.assert_demo_in_column(probe, column, f"JupyterLab {chapter.notebook} [{demo.cell}], file browser open")
    h.assert_no_sideways_scroll(page, f"JupyterLab {chapter.notebook}", f"document.querySelector({NOTEBOOK!r})")
    # the chapter's own content — its text and its outputs (the demos); the editors, prompts and the windowed list
    # around them are JupyterLab's (axe finds its CodeMirror content and heading buttons unnamed: not the book's)
    bad = [v for v in S.run_axe(page, S.axe_source(), within=CONTENT) if v["impact"] in ("serious", "critical")]
    assert not bad, f"JupyterLab {chapter.notebook}: " + json.dumps(bad, ensure_ascii=False)[:3000]


@pytest.mark.parametrize("url", [LECTURE_INDEX, lecture_page(book_chapter("05_fotoschema"))])
def test_no_serious_accessibility_violation_on_the_lecture_pages(url, voila, tab):
    from . import site_harness as S

    page = tab.page
    h.open_voila(page, voila, url)
    if url != LECTURE_INDEX:
        h.DemoProbe(page, page.locator(".aerophoto-demo").first).wait_rendered()
    tab.add("axe", page.screenshot())
    bad = [v for v in S.run_axe(page, S.axe_source()) if v["impact"] in ("serious", "critical")]
    assert not bad, f"Voilà {url}: " + json.dumps(bad, ensure_ascii=False, indent=1)[:4000]
