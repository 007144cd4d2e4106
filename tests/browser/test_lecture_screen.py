"""A lecture the back row can read: every lecture demo on one screen at 1280×800 and 1920×1080, nothing cut off,
projector mode at 19 px and over, and the demos inside JupyterLab's column with its file browser open.

* Lecture pages (Voilà) at both sizes: each demo scrolled to the top of the screen is at most a screen high; its
  figure and its table lie inside the demo and inside the window (no horizontal scroll bar); its text is at least
  15 px.  Projector mode (the button on the demo's title line) makes every text of the demo ≥ 18 px and draws the
  figure larger, and is remembered for the next page.
* JupyterLab at 1280×800 with its file browser open: each demo's figure and table lie inside the notebook column.

Screenshots of every state go to artifacts/ (``AEROPHOTO_SCREENSHOTS=1``, or on failure).
"""

from __future__ import annotations

import pytest

from aerophoto.book import lecture_page

from . import harness as h
from .chapters import CHAPTERS, core_params

pytestmark = [pytest.mark.browser, pytest.mark.timeout(1800)]

SIZES = ({"width": 1280, "height": 800}, {"width": 1920, "height": 1080})
#: the smallest text of a lecture demo, px, and in projector mode
MIN_FONT_PX, MIN_FONT_PROJECTOR_PX = 15.0, 18.0

MEASURE_JS = """(root) => {
  const box = (e) => { if (!e) return null; const b = e.getBoundingClientRect();
                       return {x: b.x, y: b.y, width: b.width, height: b.height}; };
  const sizes = [];
  root.querySelectorAll('.widget-label, .widget-readout, .widget-button, .widget-toggle-button, select, '
                        + '.aerophoto-table td, .aerophoto-table th, .aerophoto-table li, .aerophoto-legend, '
                        + '.aerophoto-lecture-title, .aerophoto-more summary').forEach((e) => {
    if (e.offsetParent && e.innerText.trim()) sizes.push([parseFloat(getComputedStyle(e).fontSize), e.innerText.trim().slice(0, 30)]); });
  sizes.sort((a, b) => a[0] - b[0]);
  const c = root.querySelector('.jupyter-matplotlib-canvas-div canvas');
  return {demo: box(root), canvas: box(root.querySelector('.jupyter-matplotlib-canvas-div')),
          table: box(root.querySelector('.aerophoto-table')), smallest: sizes[0] || [0, ''],
          scrollWidth: document.scrollingElement.scrollWidth, clientWidth: document.scrollingElement.clientWidth,
          canvasPx: c ? c.width : 0};
}"""


def _inside(inner, outer, what: str, where: str, slack: float = 1.0) -> None:
    assert inner is not None, f"{where}: the {what} is not displayed"
    assert inner["x"] >= outer["x"] - slack and inner["x"] + inner["width"] <= outer["x"] + outer["width"] + slack, (
        f"{where}: the {what} {inner} sticks out of {outer} sideways")


def _chapters():
    return core_params(CHAPTERS, core=("05", "08", "11", "16"))


@pytest.mark.parametrize("size", SIZES, ids=lambda s: f"{s['width']}x{s['height']}")
@pytest.mark.parametrize("chapter", _chapters())
def test_each_lecture_demo_fits_one_screen(chapter, size, voila, tab):
    page = tab.page
    page.set_viewport_size(size)
    url = lecture_page(chapter)
    h.open_voila(page, voila, url)
    roots = page.locator(".aerophoto-demo")
    roots.first.wait_for(state="visible", timeout=h.T_RUN)
    window = {"x": 0, "y": 0, "width": size["width"], "height": size["height"]}
    for k, demo in enumerate(chapter.demos):
        root = roots.nth(k)
        h.DemoProbe(page, root).wait_rendered()
        where = f"Voilà {url} [{demo.cell}] at {size['width']}×{size['height']}"
        m = root.evaluate(MEASURE_JS)
        tab.add(f"{demo.cell}-{size['width']}", page.screenshot())
        assert m["scrollWidth"] <= m["clientWidth"], f"{where}: a horizontal scroll bar ({m['scrollWidth']} px)"
        assert m["demo"]["height"] <= size["height"], f"{where}: the demo is {m['demo']['height']:.0f} px high"
        for what in ("canvas", "table"):
            _inside(m[what], m["demo"], what, where)
            _inside(m[what], window, what, where)
        assert m["smallest"][0] >= MIN_FONT_PX, f"{where}: text at {m['smallest']}"


@pytest.mark.parametrize("chapter", [c for c in CHAPTERS if c.number == "16"], ids=lambda c: c.name)
def test_projector_mode_is_large_and_remembered(chapter, voila, tab):
    page = tab.page
    url = lecture_page(chapter)
    h.open_voila(page, voila, url)
    root = page.locator(".aerophoto-demo").first
    h.DemoProbe(page, root).wait_rendered()
    before = root.evaluate(MEASURE_JS)
    button = root.locator(".widget-toggle-button", has_text="Projector")
    button.click()
    page.wait_for_function(
        "([el, w]) => { const c = el.querySelector('.jupyter-matplotlib-canvas-div canvas'); return c && c.width > w; }",
        arg=[root.element_handle(), before["canvasPx"]], timeout=h.T_MOVE, polling=100)
    h.settle(page, 800)
    root.evaluate("(el) => el.scrollIntoView({block: 'start'})")
    m = root.evaluate(MEASURE_JS)
    tab.add("projector-1280", page.screenshot())
    where = f"Voilà {url} in projector mode"
    assert m["smallest"][0] >= MIN_FONT_PROJECTOR_PX, f"{where}: text at {m['smallest']}"
    assert m["canvasPx"] >= 1.25 * before["canvasPx"], f"{where}: the figure is drawn at {m['canvasPx']} px"
    assert m["scrollWidth"] <= m["clientWidth"], f"{where}: a horizontal scroll bar"
    _inside(m["canvas"], {"x": 0, "width": 1280}, "figure", where)
    # remembered: the next page opens in projector mode, and the button switches it off again
    h.open_voila(page, voila, url)
    root = page.locator(".aerophoto-demo").first
    h.DemoProbe(page, root).wait_rendered()
    again = root.evaluate(MEASURE_JS)
    assert again["smallest"][0] >= MIN_FONT_PROJECTOR_PX, f"{where}: not remembered ({again['smallest']})"
    root.locator(".widget-toggle-button", has_text="Projector").click()
    page.wait_for_function(
        "([el, w]) => { const c = el.querySelector('.jupyter-matplotlib-canvas-div canvas'); return c && c.width < w; }",
        arg=[root.element_handle(), again["canvasPx"]], timeout=h.T_MOVE, polling=100)


@pytest.mark.parametrize("notebook", ["00_start_here.ipynb", "03_relief_displacement.ipynb"])
def test_demos_fit_jupyterlab_beside_its_file_browser(notebook, lab, tab):
    page = tab.page
    h.open_lab_notebook(page, lab, notebook)
    page.evaluate("() => window.jupyterapp.commands.execute('filebrowser:activate')")
    h.run_all_cells(page)
    assert not h.error_outputs(page), h.error_outputs(page)
    column = page.evaluate("""() => { const b = document.querySelector('.jp-NotebookPanel-notebook')
                                         .getBoundingClientRect(); return {x: b.x, width: b.width}; }""")
    sidebar = page.evaluate("() => { const s = document.querySelector('#jp-left-stack'); "
                            "return s ? s.getBoundingClientRect().width : 0; }")
    assert sidebar > 150, f"the file browser is not open ({sidebar} px)"
    roots = page.locator(".aerophoto-demo")
    assert roots.count() >= 1
    for k in range(roots.count()):
        root = roots.nth(k)
        h.DemoProbe(page, root).wait_rendered()
        m = root.evaluate(MEASURE_JS)
        tab.add(f"lab-{k}", page.screenshot())
        where = f"JupyterLab {notebook}, demo {k}, beside the file browser at 1280×800"
        for what in ("canvas", "table"):
            _inside(m[what], column, what, where)
