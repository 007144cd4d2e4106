"""The web book (``aerophoto-course site``): built offline from its pinned inputs, served from 127.0.0.1 and read in
chromium with every request that would leave the machine trapped — every chapter page renders its pictures and
formulas in English and Russian, search finds terms of both languages, the language switch lands on the same
chapter, the launch button opens the chapter live and its first demo moves, a lecture page opens as an app, and
axe-core finds no serious or critical accessibility violation.

Marked ``site`` (and ``lite``: the site ships the browser book, built once per run for both); CI runs them in its
second step (``.ci/run``), the README's command leaves them out.  The whole book is built once per run without its
PDFs (printing both whole books took ~9 of the build's 25 minutes under load); the printing is tested on a book of
three pages built beside it from the same executed chapters (the build's cache).
"""

from __future__ import annotations

import html
import json
import re
import subprocess
from pathlib import Path

import pytest

from aerophoto import book, website
from aerophoto.i18n import translate

from . import harness as h
from . import lite_harness as L
from . import site_harness as S
from .chapters import CHAPTERS as DEMO_CHAPTERS

pytestmark = [pytest.mark.site, pytest.mark.lite, pytest.mark.browser, pytest.mark.timeout(3600)]

LANGS = ("en", "ru")
PAGES = [ch.name for ch in book.CHAPTERS] + ["glossary"]
#: the pages of the printed test book (a chapter without a live demo is not among them: 00 and 03 have demos)
PRINTED = ("00_start_here", "03_relief_displacement", "glossary")
#: the longest a live chapter may take to have its kernel ready and to run all its cells, ms: the browser book
#: loads Pyodide and the book's wheels and compiles them in the page — 20–30 s on an idle machine, measured at
#: 189 s with the machine's load at 12 (the test waits for the kernel's "idle", not for a time)
T_LIVE = 900_000


def _shared(tmp_path_factory) -> Path:
    base = tmp_path_factory.getbasetemp()
    return base.parent if base.name.startswith("popen-gw") else base


def _build_log(tmp_path_factory, name: str):
    """The build's lines (what ran, from the cache or not, and how long) into ``<name>.log`` beside the build."""
    path = _shared(tmp_path_factory) / f"{name}.log"

    def log(text: str) -> None:
        with open(path, "a", encoding="utf-8") as f:
            f.write(text + "\n")
    return log


@pytest.fixture(scope="session")
def lite_site(tmp_path_factory):
    """The browser book the lite tests build (one build per run, shared by the workers through a lock)."""
    site, _ = L.built_site(_shared(tmp_path_factory) / "aerophoto-lite-site")
    return site


@pytest.fixture(scope="session")
def web_book(tmp_path_factory, lite_site):
    """One build of the whole web book per test run, without the PDFs, shipping the browser book."""
    site, _seconds = S.built_book(_shared(tmp_path_factory) / "aerophoto-web-book", lite_site, pdf=False,
                                  log=_build_log(tmp_path_factory, "aerophoto-web-book"))
    return site


@pytest.fixture(scope="module")
def printed_book(tmp_path_factory, lite_site, web_book):
    """A web book of :data:`PRINTED` alone, with its PDFs; built after the whole book (``web_book``), so its
    chapters come from the build's cache of executed notebooks."""
    site, _seconds = S.built_book(_shared(tmp_path_factory) / "aerophoto-printed-book", lite_site, pdf=True,
                                  only=PRINTED, log=_build_log(tmp_path_factory, "aerophoto-printed-book"))
    return site


@pytest.fixture(scope="module")
def served(web_book):
    """(site server, egress trap, chromium whose non-loopback requests all go to the trap; no chromium: an error)."""
    with L.trapped_chromium(web_book) as trapped:
        yield trapped


_no_egress = L.assert_no_egress


# --------------------------------------------------------------------------------------------- the build
def test_the_site_is_built_whole_and_self_contained(web_book):
    """Both books have every chapter, the glossary, the lecture list and the guide; the live book is in the folder;
    no page names another host or links a PDF that is not there (this build has none); the manifest records what
    was built."""
    m = S.manifest(web_book)
    assert m["languages"] == list(LANGS) and m["pdf"] is False and m["pages"] is None
    for lang in LANGS:
        for name in PAGES + ["index", "lectures", "search", "manual/index", "manual/website"]:
            assert (web_book / lang / f"{name}.html").is_file(), f"{lang}/{name}.html"
        assert set(m["chapters"][lang]) == set(PAGES)
        assert 'class="aerophoto-pdf"' not in (web_book / lang / "03_relief_displacement.html").read_text("utf-8")
    assert not list(web_book.glob("*.pdf")) and ".pdf" not in (web_book / "index.html").read_text("utf-8")
    assert (web_book / "live" / "aerophoto-lite.json").is_file() and (web_book / "index.html").is_file()
    assert (web_book / ".nojekyll").is_file()
    assert website.check_site(web_book) == []
    figures = sum(c["figures"] for c in m["chapters"]["en"].values())
    assert figures >= 2 * len(book.CHAPTERS), figures
    assert m["bytes"]["live"] > 0 and m["site_bytes"] == sum(m["bytes"].values())


def _page_heading(site, lang: str, name: str) -> str:
    """The page's title as the book shows it (its <title> without " — aerophoto")."""
    text = (site / lang / f"{name}.html").read_text(encoding="utf-8")
    return html.unescape(re.search(r"<title>(.*?)</title>", text, re.S).group(1)).rsplit(" \u2014 ", 1)[0].strip()


def test_the_pdfs_hold_the_chapters_in_each_language(printed_book):
    """Each language's PDF is the book printed: its pages' titles in the book's order, formulas typeset (no TeX
    left); the bar and the front door link the PDF that is there."""
    m = S.manifest(printed_book)
    assert m["pdf"] is True and m["pages"] == sorted(PRINTED)
    assert website.check_site(printed_book) == []
    for lang, words in (("en", ("Relief displacement", "Glossary")), ("ru", ("смещение", "Словарь"))):
        pdf = printed_book / f"aerophoto-{lang}.pdf"
        assert pdf.read_bytes()[:5] == b"%PDF-"
        text = subprocess.run(["pdftotext", str(pdf), "-"], capture_output=True, text=True, check=True).stdout
        for w in words:
            assert w.lower() in text.lower(), f"aerophoto-{lang}.pdf lacks {w!r}"
        assert "\\frac" not in text and "\\delta" not in text, f"aerophoto-{lang}.pdf: TeX left untypeset"
        # after the contents (the first printed page), each page's title comes once, in the book's order
        body = " ".join(" ".join(page.split()) for page in text.split("\f")[1:])
        where = [body.find(" ".join(_page_heading(printed_book, lang, name).split())) for name in PRINTED]
        assert -1 not in where and where == sorted(where), f"aerophoto-{lang}.pdf: the titles of {PRINTED} at {where}"
        # and each chapter starts a printed page of its own (site.css: break-before in the theme's print layout)
        pages = [" ".join(page.split()) for page in text.split("\f")[1:]]
        for name in PRINTED:
            head = " ".join(_page_heading(printed_book, lang, name).split())
            assert any(p.startswith(head) for p in pages), f"aerophoto-{lang}.pdf: {head!r} does not start a page"
        info = subprocess.run(["pdfinfo", str(pdf)], capture_output=True, text=True, check=True).stdout
        assert int(re.search(r"Pages:\s+(\d+)", info).group(1)) > len(PRINTED), info
        bar = (printed_book / lang / "03_relief_displacement.html").read_text(encoding="utf-8")
        assert f'class="aerophoto-pdf" href="../aerophoto-{lang}.pdf"' in bar
        assert f"href='aerophoto-{lang}.pdf'" in (printed_book / "index.html").read_text(encoding="utf-8")


def test_the_site_shows_the_guides_example_only(web_book):
    """Every chapter ran as variant 00 (the guide's example) with no record-book number, and every answer cell
    holds its template lines only: no page can show a graded answer of a student's variant (01–99)."""
    for lang in LANGS:
        for ch in book.CHAPTERS:
            where = f"{lang}/{ch.name}"
            text = (web_book / lang / f"{ch.name}.html").read_text(encoding="utf-8")
            variants = set(re.findall(r"(?:variant|вариант) i = (\d\d)", text))
            assert variants == {"00"}, f"{where}: the page shows variants {variants}"
            answers = re.findall(r'<div class="cell tag_aerophoto-answer.*?</pre>', text, re.S)
            nb = json.loads((h.ROOT / "notebooks" / ch.notebook).read_text(encoding="utf-8"))
            n = sum(1 for c in nb["cells"] if re.fullmatch(r"task-\d\d-\d+-answer", str(c.get("id", ""))))
            assert len(answers) == n, f"{where}: {len(answers)} answer cells on the page, {n} in the chapter"
            for answer in answers:
                code = html.unescape(re.sub(r"<[^>]+>", "", answer.split("<pre", 1)[1].split(">", 1)[1]))
                for line in code.splitlines():
                    line = line.split("#", 1)[0].strip()
                    assert not line or line.endswith("= ..."), f"{lang}/{ch.name}: an answer cell holds {line!r}"
        assert not any(p.is_file() for p in (web_book / lang / "_sources").rglob("*")), "the sources are shipped"


# --------------------------------------------------------------------------------------------- the pages
@pytest.mark.parametrize("lang", LANGS)
@pytest.mark.parametrize("name", PAGES)
def test_every_chapter_page_renders(name, lang, served):
    """The page loads with its pictures (each decoded, each with its text alternative), its formulas typeset by the
    site's own MathJax (none broken, no TeX left), the bar at the top, and no console error or request off the
    machine."""
    server, trap, browser = served
    page, log, requests = L.new_lite_page(browser, instrument=False)
    where = f"{lang}/{name}"
    try:
        page.goto(f"{server.base}/{lang}/{name}.html", wait_until="load")
        state = page.evaluate(S.PAGE_STATE_JS)
        broken = [i["src"] for i in state["images"] if not i["ok"]]
        assert not broken, f"{where}: pictures that did not load: {broken[:5]}"
        assert all(i["alt"].strip() for i in state["images"]), f"{where}: a picture without alt text"
        assert state["math_errors"] == 0 and state["raw_tex"] == 0, f"{where}: {state}"
        if name != "glossary":
            assert state["formulas"] > 0 and state["figures"] > 0, f"{where}: {state}"
        assert page.locator("nav.aerophoto-bar a.aerophoto-launch").count() == 1
        assert not log.relevant(), f"{where}: console errors {log.relevant()}"
        _no_egress(trap, requests, where)
    finally:
        page.context.close()


@pytest.mark.parametrize(("lang", "query", "expect"), [("en", "displacement", "03_relief_displacement"),
                                                       ("ru", "фотосхема", "05_fotoschema"),
                                                       ("en", "фотосхема", "05_fotoschema")])
def test_search_finds_a_term(lang, query, expect, served):
    server, trap, browser = served
    page, log, requests = L.new_lite_page(browser, instrument=False)
    try:
        page.goto(f"{server.base}/{lang}/search.html?q={query}", wait_until="load")
        page.wait_for_function("() => document.querySelectorAll('#search-results ul.search li a').length > 0",
                               timeout=h.T_PAGE)
        hrefs = page.eval_on_selector_all("#search-results ul.search li a", "els => els.map((a) => a.href)")
        assert any(f"/{lang}/{expect}.html" in u for u in hrefs), hrefs[:10]
        assert not log.relevant(), log.relevant()
        _no_egress(trap, requests, f"search {lang} {query}")
    finally:
        page.context.close()


def test_the_language_switch_lands_on_the_same_chapter(served):
    server, trap, browser = served
    page, log, requests = L.new_lite_page(browser, instrument=False)
    try:
        page.goto(f"{server.base}/en/05_fotoschema.html", wait_until="load")
        page.click("nav.aerophoto-bar a.aerophoto-lang")
        page.wait_for_url(lambda url: url.endswith("/ru/05_fotoschema.html"))
        assert page.locator("html").get_attribute("lang") == "ru"
        page.click("nav.aerophoto-bar a.aerophoto-lang")
        page.wait_for_url(lambda url: url.endswith("/en/05_fotoschema.html"))
        page.goto(f"{server.base}/ru/manual/website.html", wait_until="load")
        page.click("nav.aerophoto-bar a.aerophoto-lang")
        page.wait_for_url(lambda url: url.endswith("/en/manual/website.html"))
        _no_egress(trap, requests, "language switch")
    finally:
        page.context.close()


@pytest.mark.parametrize("lang", LANGS)
def test_the_launch_button_opens_the_chapter_live_and_its_demo_moves(lang, served):
    """From chapter 00's page, "run this chapter in the browser" opens the same chapter (same language) in the
    browser book of the same folder; after Run All its first live demo answers a slider."""
    server, trap, browser = served
    page, log, requests = L.new_lite_page(browser)
    where = f"live {lang}"
    ch = next(c for c in DEMO_CHAPTERS if c.name == "00_start_here")
    demo = ch.demos[0]
    try:
        page.goto(f"{server.base}/{lang}/00_start_here.html", wait_until="load")
        page.click("nav.aerophoto-bar a.aerophoto-launch")
        path = ("ru/" if lang == "ru" else "") + "00_start_here.ipynb"
        page.wait_for_url(lambda url: url.endswith(f"/live/lab/index.html?path={path}"))
        h.wait_lab_notebook(page, path, timeout=T_LIVE)
        h.run_all_cells(page, timeout=T_LIVE)
        root = h.lab_demo_root(page, demo.cell)
        probe = h.DemoProbe(page, root, sized=L.demos_sized())
        probe.wait_rendered()
        label, key = demo.sliders[0]
        label = translate(label, lang)  # the Russian chapter's demo labels its sliders in Russian ("x, мм")
        r = probe.move(label, key)
        assert r["value_after"] != r["value_before"], f"{where}: {key} did not move {label!r}"
        # chapter 00's first demo is the floor (one ray moves one step: ~0.03 % of its pixels in the browser book)
        assert h.pixel_change(r["png_before"], r["png_after"]) > 0, f"{where}: the figure did not change"
        assert r["table_after"] != r["table_before"], f"{where}: the table did not follow"
        if lang == "ru":
            assert "Сброс" in root.inner_text(), f"{where}: the demo does not speak Russian"
        assert not log.relevant(), f"{where}: console errors {log.relevant()}"
        _no_egress(trap, requests, where)
    finally:
        page.context.close()


def test_a_lecture_page_opens_as_an_app_in_the_browser(served):
    """The lecture list links each lecture page to the browser book's single-document view, code collapsed; after
    Run All its demo is drawn."""
    server, trap, browser = served
    page, log, requests = L.new_lite_page(browser)
    try:
        page.goto(f"{server.base}/en/lectures.html", wait_until="load")
        link = page.locator("a[href*='live/notebooks/index.html?path=lectures/03_relief_displacement.ipynb']")
        assert link.count() == 1
        link.click()
        h.wait_lab_notebook(page, "lectures/03_relief_displacement.ipynb", timeout=T_LIVE)
        hidden = page.evaluate("""() => window.jupyterapp.shell.currentWidget.content.widgets
            .filter((c) => c.model.type === 'code').every((c) => c.inputHidden)""")
        assert hidden, "the lecture page shows its code"
        h.run_all_cells(page, timeout=T_LIVE)
        root = h.lab_demo_root(page, "demo-relief")
        h.DemoProbe(page, root, sized=L.demos_sized()).wait_rendered()
        _no_egress(trap, requests, "lecture app")
    finally:
        page.context.close()


# --------------------------------------------------------------------------------------------- accessibility
AXE_PAGES = ["index", "00_start_here", "03_relief_displacement", "08_interpretation", "16_dem_contours", "glossary",
             "lectures", "manual/index", "search"]


@pytest.mark.parametrize("lang", LANGS)
def test_no_serious_accessibility_violation(lang, served):
    """axe-core (npm, deploy/site's lock, injected by Playwright) over the book's pages: no serious or critical
    violation (images without alt text, contrast, headings, controls without labels …)."""
    server, trap, browser = served
    source = S.axe_source()
    found = {}
    for name in AXE_PAGES:
        page, log, requests = L.new_lite_page(browser, instrument=False)
        try:
            page.goto(f"{server.base}/{lang}/{name}.html", wait_until="load")
            page.evaluate(S.PAGE_STATE_JS)
            bad = [v for v in S.run_axe(page, source) if v["impact"] in ("serious", "critical")]
            if bad:
                found[name] = bad
        finally:
            page.context.close()
    assert not found, json.dumps(found, ensure_ascii=False, indent=1)[:4000]
