"""The web book's pieces that need no build: the site's own words, the pages made from executed notebooks (figures
to files, numbers, live links, untranslated notes, chapter links), the widgets' static pictures, the cache key, the
browser book's Russian contents and service worker, and the site check.  The built site is tested in
tests/browser/test_site.py (marked ``site``)."""

from __future__ import annotations

import base64
import io
import json
import re

import pytest

from aerophoto import book
from aerophoto.website import chrome, execute, live, pages, project, snapshot
from aerophoto import website
from aerophoto.website import check_site, page_title


def _png(w=4, h=3, colour=(255, 0, 0)) -> bytes:
    from PIL import Image

    buf = io.BytesIO()
    Image.new("RGB", (w, h), colour).save(buf, format="PNG")
    return buf.getvalue()


def test_every_word_of_the_site_has_its_russian():
    for key, ru in chrome.RU.items():
        assert ru.strip() and ru != key, key
        assert re.search("[а-яё]", ru, re.I), f"{key!r} → {ru!r} is not Russian"
    assert chrome.say("Table", "ru") == "Таблица" and chrome.say("Table", "en") == "Table"
    with pytest.raises(KeyError, match="no Russian"):
        chrome.say("a text nobody wrote")


def test_png_size_reads_the_header():
    assert pages.png_size(_png(7, 5)) == (7, 5)
    with pytest.raises(ValueError):
        pages.png_size(b"GIF89a....")


def test_chapter_links_outside_code_math_and_links():
    names = {"05_fotoschema", "16_dem_contours"}
    text = "See chapter 05 and `chapter 05` and $chapter 05$ and [chapter 16](16_dem_contours.ipynb); chapter 99."
    out = pages.chapter_links(text, "en", names)
    assert out.startswith("See [chapter 05](05_fotoschema.ipynb) and `chapter 05` and $chapter 05$ and "
                          "[chapter 16](16_dem_contours.ipynb); chapter 99.")
    assert pages.chapter_links("как в главе 16.", "ru", names) == "как в [главе 16](16_dem_contours.ipynb)."


def _executed(png: bytes) -> dict:
    data = base64.b64encode(png).decode()
    return {"cells": [
        {"cell_type": "markdown", "id": "title", "metadata": {}, "source": "# 05 · The mosaic\n\nAs in chapter 16."},
        {"cell_type": "code", "id": "figure-a", "metadata": {}, "execution_count": 1, "source": "plots.static(...)",
         "outputs": [{"output_type": "execute_result", "execution_count": 1, "metadata": {},
                      "data": {"text/html": f"<img src='data:image/png;base64,{data}' alt='a red square'>",
                               "image/png": data, "text/plain": "[figure: a red square]"}}]},
        {"cell_type": "code", "id": "example-1", "metadata": {}, "execution_count": 2, "source": "table",
         "outputs": [{"output_type": "execute_result", "execution_count": 2, "metadata": {},
                      "data": {"text/html": "<table class='x'><caption>Scales</caption><tr><td>1</td></tr></table>"
                                            "<table><tr><td>2</td></tr></table>", "text/plain": "t"}}]},
        {"cell_type": "code", "id": "demo-mosaic", "metadata": {}, "execution_count": 3, "source": "demo",
         "outputs": [{"output_type": "display_data", "metadata": {},
                      "data": {"text/html": f"<div class='aerophoto-snapshot' data-aerophoto-live='demo' "
                                            f"data-aerophoto-title='The mosaic'><img class='aerophoto-snapshot-figure'"
                                            f" src='data:image/png;base64,{data}' alt='x'></div>",
                               "text/plain": "[demo: The mosaic]"}}]},
        {"cell_type": "code", "id": "task-05-1-answer", "metadata": {}, "execution_count": 4, "source": "m = ...",
         "outputs": []},
        {"cell_type": "code", "id": "task-05-1-check", "metadata": {}, "execution_count": 5, "source": "check",
         "outputs": [{"output_type": "error", "ename": "WrongAnswer", "evalue": "\x1b[31m✗ m: no answer yet\x1b[0m",
                      "traceback": ["..."]}]},
    ], "metadata": {}, "nbformat": 4, "nbformat_minor": 5}


def test_page_notebook_files_numbers_and_links(tmp_path):
    png = _png()
    demo = book.Demo("demo-mosaic", "aerophoto.demos.x.X", "Live mosaic", "move", "the strips glue")
    page, info = pages.page_notebook(_executed(png), chapter="05", lang="en", figdir=tmp_path, rel="_static/fig",
                                     live_url="../live/lab/index.html?path=05_fotoschema.ipynb",
                                     pages={"05_fotoschema", "16_dem_contours"}, demos={"demo-mosaic": demo})
    name = f"{__import__('hashlib').sha256(png).hexdigest()[:16]}.png"
    assert (tmp_path / name).read_bytes() == png and info["files"] == [name]  # one picture, one file
    assert info["figures"] == 2 and info["tables"] == 2
    fig = page["cells"][1]["outputs"][0]["data"]["text/html"]
    assert f'src="_static/fig/{name}" width="4" height="3"' in fig and "alt='a red square'" in fig
    assert "id='fig-05-1'" in fig and "Figure 05.1" in fig and "base64" not in fig
    tables = page["cells"][2]["outputs"][0]["data"]["text/html"]
    assert "id='table-05-1'" in tables and "Table 05.1</span> — Scales" in tables
    assert "<caption><span class='aerophoto-num'>Table 05.2</span></caption>" in tables
    live_out = page["cells"][3]["outputs"][0]["data"]["text/html"]
    assert "Figure 05.2" in live_out and "live demo: Live mosaic" in live_out
    assert "alt='Live demo “Live mosaic” at the guide&#x27;s example values: the strips glue.'" in live_out
    assert "href='../live/lab/index.html?path=05_fotoschema.ipynb'" in live_out and "Open this demo live" in live_out
    assert page["cells"][4]["metadata"]["tags"] == ["aerophoto-answer"]
    assert page["cells"][5]["outputs"] == [{"output_type": "stream", "name": "stdout", "text": "✗ m: no answer yet\n"}]
    assert "[chapter 16](16_dem_contours.ipynb)" in page["cells"][0]["source"]
    assert page_title(page, "x") == "05 · The mosaic"


def test_an_untranslated_cell_stays_english_with_a_note(tmp_path):
    page, _ = pages.page_notebook(_executed(_png()), chapter="05", lang="ru", figdir=tmp_path, rel="f", live_url="l",
                                  pages=set(), untranslated=["title"])
    src = page["cells"][0]["source"]
    assert src.startswith("<p class='aerophoto-untranslated' role='note'>Этот фрагмент ещё не переведён")
    assert "# 05 · The mosaic" in src
    assert "Рис. 05.1" in page["cells"][1]["outputs"][0]["data"]["text/html"]


def test_a_widget_becomes_its_static_picture():
    import ipywidgets as w
    import matplotlib

    matplotlib.use("module://ipympl.backend_nbagg")
    from aerophoto.demos.footprint import FootprintDemo

    demo = FootprintDemo()
    try:
        bundle = snapshot._bundle(demo.widget())
    finally:
        demo.close()
    text = bundle["text/html"]
    assert "data-aerophoto-live='demo'" in text and "application/vnd.jupyter.widget-view+json" not in bundle
    (img,) = re.findall(r"<img class='aerophoto-snapshot-figure' src='data:image/png;base64,([^']+)' alt='([^']+)'",
                        text)
    assert pages.png_size(base64.b64decode(img[0]))[0] > 300 and img[1].strip()
    assert "f, mm: <b>100</b>" in text and "m (scale 1:m): <b>12\u202f000</b>" in text  # the book's number format
    assert "<button" not in text and ">Reset<" not in text  # buttons do nothing on a page: dropped
    tool = snapshot._bundle(w.VBox([w.HTML("<b>x</b>"), w.Dropdown(options=["a", "b"], value="b", description="p")]))
    assert "data-aerophoto-live='tool'" in tool["text/html"] and "p: <b>b</b>" in tool["text/html"]


def test_the_execution_key_follows_what_decides_the_outputs():
    nb = {"cells": [{"cell_type": "code", "source": "1"}]}
    d = execute.package_digest()
    assert len(d) == 64 and d == execute.package_digest()
    k = execute.execution_key(nb, "en", d)
    assert k != execute.execution_key(nb, "ru", d)
    assert k != execute.execution_key({"cells": [{"cell_type": "code", "source": "2"}]}, "en", d)
    assert k != execute.execution_key(nb, "en", "0" * 64)


def test_a_build_kernel_runs_as_a_student_who_typed_nothing(tmp_path):
    """The build's kernel: the book's language, an empty home (no record-book number: variant 00), widgets as
    static pictures, and the build's shared heavy-data cache (aerophoto.cache) — one real kernel."""
    nb = {"cells": [{"cell_type": "code", "id": "probe", "metadata": {}, "execution_count": None, "outputs": [],
                     "source": "import os, ipywidgets as w, aerophoto.cache as c\n"
                               "f = get_ipython().display_formatter.mimebundle_formatter\n"
                               "print(os.environ['AEROPHOTO_LANG'], c.cache_dir(), w.Widget in f.type_printers,\n"
                               "      os.environ.get('AEROPHOTO_RECORD_BOOK'), os.listdir(os.environ['AEROPHOTO_HOME']))"}],
          "metadata": {"kernelspec": {"name": "python3", "display_name": "Python 3", "language": "python"}},
          "nbformat": 4, "nbformat_minor": 5}
    done = execute.execute(nb, "ru", cwd=tmp_path, name="probe", data_cache=tmp_path / "data")
    text = "".join("".join(o.get("text", "")) for o in done["cells"][0]["outputs"])  # a stream's text: str or lines
    assert text.split() == ["ru", str(tmp_path / "data"), "True", "None", "[]"], done["cells"][0]["outputs"]
    assert nb["cells"][0]["outputs"] == []  # the notebook given is not changed


def test_only_a_check_cell_may_raise():
    nb = {"cells": [{"cell_type": "code", "id": "task-03-1-check", "outputs": [{"output_type": "error", "ename": "A",
                                                                                 "evalue": "no answer yet"}]},
                    {"cell_type": "code", "id": "example-1", "outputs": [{"output_type": "error", "ename": "KeyError",
                                                                           "evalue": "'x'"}]}]}
    assert execute.unexpected_errors(nb) == ["example-1: KeyError: 'x'"]


def test_the_bar_links_the_other_language_and_the_live_chapter():
    from aerophoto.website import sphinx_ext

    conf = {"__file__": "/nowhere/conf.py"}
    exec(compile(project.conf_py("en", {"live": {"03_relief_displacement": "live/lab/index.html?path=03.ipynb"},
                                       "live_default": "live/lab/index.html?path=00.ipynb", "hub": {}}), "conf", "exec"),
         conf)
    cfg = conf["aerophoto_site"]
    bar = sphinx_ext._bar(cfg, "03_relief_displacement")
    assert 'href="../live/lab/index.html?path=03.ipynb">▶ Run this chapter in the browser' in bar
    assert 'href="../ru/03_relief_displacement.html" hreflang="ru" lang="ru">Русский' in bar
    assert 'href="../aerophoto-en.pdf"' in bar and "aerophoto-hub" not in bar
    deep = sphinx_ext._bar(cfg, "manual/website")
    assert 'href="../../ru/manual/website.html"' in deep and "Open the book in the browser" in deep
    assert conf["language"] == "en" and conf["mathjax_path"] == "../../_assets/mathjax/tex-svg.js"
    assert project.live_path("03_relief_displacement.ipynb", "ru") == "live/lab/index.html?path=ru/03_relief_displacement.ipynb"
    printless = {**cfg, "pdf": ""}  # a site built without its PDFs (build(pdf=False)) links none
    assert "aerophoto-pdf" not in sphinx_ext._bar(printless, "03_relief_displacement")
    assert ".pdf" not in website._front_door(("en", "ru"), pdf=False)
    assert "href='aerophoto-ru.pdf'" in website._front_door(("en", "ru"), pdf=True)


def test_the_front_page_lists_the_chapters_in_the_guides_order():
    text = project.front_page("ru", {}, ["index"])
    names = re.findall(r"^(\d\d_\w+)$", text, re.M)
    assert names == [ch.name for ch in book.CHAPTERS]
    assert "## Главы" in text and "manual/index" in text


def test_the_site_check_finds_remote_resources_and_missing_pictures(tmp_path):
    (tmp_path / "en").mkdir()
    (tmp_path / "en" / "a.html").write_text("<script src='https://cdn.example.org/x.js'></script>"
                                            "<img src='_static/fig/none.png' alt='x'>", encoding="utf-8")
    (tmp_path / "en" / "b.html").write_text("<a href='https://example.org/'>a link is fine</a>", encoding="utf-8")
    problems = check_site(tmp_path)
    assert len(problems) == 2 and "cdn.example.org" in problems[0] and "missing picture" in problems[1]
    (tmp_path / "en" / "c.html").write_text('<a class="aerophoto-pdf" href="../aerophoto-en.pdf">PDF</a>',
                                            encoding="utf-8")
    assert check_site(tmp_path)[2:] == ["en/c.html: missing PDF ../aerophoto-en.pdf"]
    (tmp_path / "aerophoto-en.pdf").write_bytes(b"%PDF-1.4")
    assert len(check_site(tmp_path)) == 2


def test_the_browser_book_gets_the_russian_chapters_glossary_and_lecture_apps(tmp_path):
    import re
    import shutil

    root = __import__("pathlib").Path(__file__).resolve().parents[2]
    contents = tmp_path / "contents"
    contents.mkdir()
    for ch in book.CHAPTERS:  # the student book as the browser book's contents hold it (lite._contents)
        shutil.copy2(root / "notebooks" / ch.notebook, contents / ch.notebook)
    (contents / "lectures").mkdir()
    for page in (book.LECTURE_INDEX, book.GLOSSARY_PAGE):
        shutil.copy2(root / "notebooks" / page, contents / page)
    src = root / "notebooks" / "lectures" / "03_relief_displacement.ipynb"
    (contents / "lectures" / src.name).write_text(src.read_text(encoding="utf-8"), encoding="utf-8")
    names = live.russian_contents(contents, root / "notebooks", out=lambda _t: None)
    assert "ru/00_start_here.ipynb" in names and "ru/lectures/03_relief_displacement.ipynb" in names
    ru = json.loads((contents / "ru" / "00_start_here.ipynb").read_text(encoding="utf-8"))
    setup = next(c for c in ru["cells"] if c.get("id") == "setup")
    assert 'lang="ru"' in "".join(setup["source"]) and ru["metadata"]["aerophoto"]["lang"] == "ru"
    assert "ru/glossary.ipynb" in names  # the glossary in Russian, its chapter links to the Russian chapters beside it
    gl = json.loads((contents / "ru" / "glossary.ipynb").read_text(encoding="utf-8"))
    text = "".join("".join(c["source"]) for c in gl["cells"] if c["cell_type"] == "markdown")
    assert text.startswith("# Словарь терминов") and "| Русский | English |" in text
    links = set(re.findall(r"\]\(([^)\s]+\.ipynb)\)", text))
    assert len(links) >= 15 and all((contents / "ru" / link).is_file() for link in links), links
    assert live.lecture_apps(contents) == 2
    lec = json.loads((contents / "ru" / "lectures" / "03_relief_displacement.ipynb").read_text(encoding="utf-8"))
    assert all(c["metadata"]["jupyter"]["source_hidden"] for c in lec["cells"] if c["cell_type"] == "code")


def test_the_service_worker_answers_first_and_cache_first(tmp_path):
    from aerophoto.lite import LiteBuildError

    with pytest.raises(LiteBuildError):
        live.cache_service_worker(tmp_path)
    (tmp_path / "static" / "pyodide").mkdir(parents=True)
    (tmp_path / "static" / "pyodide" / "a.whl").write_bytes(b"1")
    original = 'self.addEventListener("fetch",onFetch);'
    (tmp_path / "service-worker.js").write_text(original, encoding="utf-8")
    info = live.cache_service_worker(tmp_path)
    js = (tmp_path / "service-worker.js").read_text(encoding="utf-8")
    assert js.startswith(live.SW_MARK) and js.endswith(original) and js.count(live.SW_MARK) == 1
    assert js.index("stopImmediatePropagation") < js.index(original)
    assert f'"{info["cache"]}"' in js and info["cached"] == list(live.CACHED)
    assert live.cache_service_worker(tmp_path) == info  # idempotent: the same build, the same cache
    assert (tmp_path / "service-worker.js").read_text(encoding="utf-8") == js
    (tmp_path / "static" / "pyodide" / "a.whl").write_bytes(b"22")
    assert live.cache_service_worker(tmp_path)["cache"] != info["cache"]  # another build, another cache
