"""The lecture pages in Voilà at 1280×800: each demo at the top of the screen with its figure and table in view.

Each chapter with demos has a generated lecture page, ``notebooks/lectures/NN_slug.ipynb``
(:func:`aerophoto.book.lecture_notebook`).  Served by ``voila notebooks/`` on a machine where a student's
record-book number is remembered (``19-0457``, variant 57), each page must show:

* the demos only: no code, no check output (no ✓/✗, no "Task … passed"), no student's number or variant;
* every demo starting from the guide's worked example, whatever number the machine remembers: each slider
  reads the value the page's own code gives in a process where ``AEROPHOTO_RECORD_BOOK`` names the student
  (``aerophoto.setup(lecture=True)`` ignores it);
* every demo, scrolled to the top of the screen as a lecturer would (the first one without scrolling), with its
  whole figure and its whole table inside the 1280×800 viewport;
* sliders that move the figure and the table, and a Reset (the checks of the chapters' demos).

The README's command shows the pages of :data:`SAMPLE`; the others are marked ``exhaustive`` (.ci/run's second
step), which keeps the README's command within its ~10 minutes.
"""

from __future__ import annotations

import json

import pytest

from aerophoto.i18n.numfmt import parse_number

from aerophoto.book import lecture_page

from . import harness as h
from .chapters import CHAPTERS, LECTURE_INDEX
from .demo_checks import assert_clean, exercise_demo

pytestmark = [pytest.mark.browser, pytest.mark.timeout(1800)]

STUDENT = "19-0457"  # remembered on the lecture machine: variant 57, f = 670 mm, 1:17 700, W = 770 km/h
#: the top of a demo at the top of the screen: Voilà's page margin, px
TOP_MARGIN = 40


def start_values(chapter) -> list[dict]:
    """For each demo of the chapter's lecture page, slider label → (value, step) as its code starts it.

    The page's code cells run here (static figures) with ``AEROPHOTO_RECORD_BOOK`` set to the student's
    number; ``lecture_view`` is replaced by a recorder of the demos it is given.
    """
    import os

    import matplotlib
    import nbformat

    matplotlib.use("Agg")
    nb = nbformat.read(str(h.NOTEBOOKS / lecture_page(chapter)), as_version=4)
    seen = []
    old = os.environ.get("AEROPHOTO_RECORD_BOOK")
    os.environ["AEROPHOTO_RECORD_BOOK"] = STUDENT
    try:
        ns: dict = {}
        for cell in nb.cells:
            if cell.cell_type != "code":
                continue
            exec(compile(cell.source, f"{lecture_page(chapter)}[{cell.get('id')}]", "exec"), ns)  # noqa: S102
            if cell.get("id") == "setup":
                assert ns["v"].i == 0, "aerophoto.setup(lecture=True) gave a variant other than 00"
                ns["lecture_view"] = lambda demo, *a, **k: seen.append(demo)
    finally:
        if old is None:
            os.environ.pop("AEROPHOTO_RECORD_BOOK", None)
        else:
            os.environ["AEROPHOTO_RECORD_BOOK"] = old
    out = [{p.label: (float(d.values[p.name]), float(p.step)) for p in d.params if p.kind != "choice"}
           for d in seen]
    for d in seen:
        d.close()
    return out


@pytest.fixture(scope="module")
def voila_remembering(browser):
    """``voila notebooks/`` on a machine that remembers a student's record-book number."""
    server = h.VoilaServer()
    (server.home / "student.json").write_text(json.dumps({"record_book": STUDENT}), encoding="utf-8")
    server.start()
    yield server
    server.__exit__(None, None, None)


def _inside(box, where: str, what: str) -> None:
    vw, vh = h.VIEWPORT["width"], h.VIEWPORT["height"]
    assert box is not None, f"{where}: the {what} is not displayed"
    assert box["x"] >= 0 and box["y"] >= 0 and box["x"] + box["width"] <= vw + 0.5 and \
        box["y"] + box["height"] <= vh + 0.5, f"{where}: the {what} {box} is not inside the {vw}×{vh} screen"


#: the lecture pages the README's command shows (issue 33's four: the tallest tables, the most sliders, the largest
#: figure; chapter 00's demos run there whole in JupyterLab and in Voilà); CI's second step (``exhaustive``) shows
#: every one of them
SAMPLE = ("05_fotoschema", "08_interpretation", "11_rectification", "16_dem_contours")


@pytest.mark.parametrize("chapter", [pytest.param(c, id=c.name, marks=() if c.name in SAMPLE else pytest.mark.exhaustive)
                                     for c in CHAPTERS])
def test_lecture_page_shows_each_demo_on_one_screen(chapter, voila_remembering, tab):
    page = tab.page
    url = lecture_page(chapter)
    h.open_voila(page, voila_remembering, url)
    where = f"Voilà {url}"
    roots = page.locator(".aerophoto-demo")
    roots.first.wait_for(state="visible", timeout=h.T_RUN)
    assert roots.count() == len(chapter.demos), f"{where}: {roots.count()} demos shown, {len(chapter.demos)} registered"
    assert page.locator(".jp-InputArea-editor:visible").count() == 0, f"{where}: code is visible"
    # the first demo is at the top of the page as it opens
    starts = start_values(chapter)
    assert len(starts) == len(chapter.demos), f"{where}: the page's code builds {len(starts)} demos"
    first_top = roots.first.bounding_box()["y"]
    assert page.evaluate("window.scrollY") == 0 and first_top <= TOP_MARGIN, f"{where}: the first demo starts at {first_top} px"
    for k, demo in enumerate(chapter.demos):
        root = roots.nth(k)
        probe = h.DemoProbe(page, root)
        probe.wait_rendered()  # scrolls the demo's top to the top of the screen
        tab.add(f"{demo.cell}-lecture-screen", page.screenshot())
        w = f"{where} [{demo.cell}]"
        top = root.bounding_box()["y"]
        assert -1 <= top <= TOP_MARGIN, f"{w}: the demo's top is at {top} px after scrolling to it"
        _inside(probe.canvas().bounding_box(), w, "figure")
        _inside(probe.table().bounding_box(), w, "table")
        for label in probe.slider_labels():
            value, step = starts[k][label]
            shown = parse_number(probe.readout(label).replace(",", ""), lang="en")  # the slider's own readout
            assert abs(shown - value) <= step / 2 + 1e-9, (
                f"{w}: {label} starts at {shown}, not at {value:g} (the guide's example)")
    text = page.locator("body").inner_text()
    for mark in ("✓", "✗", "passed", STUDENT, "i = 57", "record book"):
        assert mark not in text, f"{where}: the page shows {mark!r}"
    for k, demo in enumerate(chapter.demos):
        exercise_demo(tab, roots.nth(k), demo, f"{where} [{demo.cell}]")
    assert_clean(tab, where)


def test_the_lecture_index_links_every_lecture_page(voila_remembering, tab):
    page = tab.page
    h.open_voila(page, voila_remembering, LECTURE_INDEX)
    for chapter in CHAPTERS:
        assert page.locator(f'a[href$="{lecture_page(chapter)}"]').count() >= 1, (
            f"the lecture index has no link to {lecture_page(chapter)}")
    assert STUDENT not in page.locator("body").inner_text()
    first = CHAPTERS[0]
    with page.expect_navigation(timeout=h.T_RUN):
        page.locator(f'a[href$="{lecture_page(first)}"]').first.click()
    assert page.url.split("?")[0].endswith(f"/voila/render/{lecture_page(first)}"), page.url
    h.wait_voila_ready(page)
    h.DemoProbe(page, page.locator(".aerophoto-demo").first).wait_rendered()
    assert_clean(tab, f"Voilà {LECTURE_INDEX} → {lecture_page(first)}")
