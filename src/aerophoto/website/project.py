"""The Sphinx source of one book of the web book (English or Russian): conf.py, the front page, the chapters, the
glossary, the lecture list and the guide for students, lecturers and instructors.

:func:`write_book` writes a folder that ``sphinx-build`` (in the site's build environment) turns into the book:
sphinx-book-theme, myst-nb rendering the executed chapters (``nb_execution_mode = "off"``: the builder executed
them, :mod:`aerophoto.website.execute`), MathJax 3 from the site's own copy (``mathjax_path``, npm ``mathjax``; no
CDN), Sphinx's search in the book's language (its Russian stemmer for the Russian book), the table of contents in
the order of :data:`aerophoto.book.CHAPTERS`, previous/next links (the theme's), and the bar of
:mod:`aerophoto.website.sphinx_ext` on every page.
"""

from __future__ import annotations

import html
import json
import shutil
from pathlib import Path

from .chrome import LANG_NAMES, say

__all__ = ["write_book", "conf_py", "front_page", "lectures_page", "MATHJAX", "MANUAL_DIR", "PDF_NAME",
           "live_path", "lecture_app_path"]

#: MathJax's entry point, relative to the site's root (one copy for both books)
MATHJAX = "_assets/mathjax/tex-svg.js"
#: the guide's pages in the repository (Markdown), rendered into each book under ``manual/``
MANUAL_DIR = "docs/manual"
#: the printable book, relative to the site's root
PDF_NAME = "aerophoto-{lang}.pdf"


def live_path(notebook: str, lang: str) -> str:
    """The browser book's URL of a chapter, relative to the site's root (Russian chapters live under ``ru/``)."""
    return f"live/lab/index.html?path={'ru/' if lang == 'ru' else ''}{notebook}"


def lecture_app_path(notebook: str, lang: str) -> str:
    """The lecture page as an app: the browser book's single-document view (Notebook 7's), code cells collapsed."""
    return f"live/notebooks/index.html?path={'ru/' if lang == 'ru' else ''}lectures/{notebook}"


def conf_py(lang: str, settings: dict) -> str:
    """The book's conf.py (Sphinx configuration), as text; ``settings`` holds the bar's links
    (:mod:`aerophoto.website.sphinx_ext`; ``"pdf": ""`` for a site built without the PDFs)."""
    words = {"run": say("Run this chapter in the browser", lang), "run_book": say("Open the book in the browser", lang),
             "hub": say("Open on the course hub", lang), "pdf": say("The whole book as PDF", lang),
             "bar": say("This page", lang)}
    other = "ru" if lang == "en" else "en"
    site = {"pdf": PDF_NAME.format(lang=lang), **settings, "other": other, "other_name": LANG_NAMES[other],
            "words": words}
    title = say("Aerial photogrammetry — an interactive workbook", lang)
    return f'''# The {LANG_NAMES[lang]} book of the aerophoto web book: written by aerophoto.website.project (do not edit)
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).parent / "_ext"))
project = {title!r}
author = "aerophoto"
copyright = "aerophoto developers"
language = {lang!r}
extensions = ["myst_nb", "aerophoto_site"]
root_doc = "index"
exclude_patterns = ["_build", "_ext", "**.ipynb_checkpoints"]
nb_execution_mode = "off"
nb_output_stderr = "remove"
nb_merge_streams = True
myst_enable_extensions = ["dollarmath", "amsmath", "colon_fence", "html_image"]
myst_heading_anchors = 3
suppress_warnings = ["myst.header", "myst.xref_missing", "misc.highlighting_failure", "myst.strikethrough"]
html_theme = "sphinx_book_theme"
html_title = "aerophoto"
html_favicon = "_static/favicon.png"
html_context = {{"default_mode": "light"}}
html_static_path = ["_static"]
templates_path = ["_templates"]
html_css_files = ["aerophoto-site.css"]
html_js_files = ["aerophoto-site.js"]
html_copy_source = False
html_show_sourcelink = False
html_last_updated_fmt = None
html_search_language = {lang!r}
mathjax_path = {("../../" + MATHJAX)!r}
mathjax3_config = {{"svg": {{"fontCache": "global"}}, "options": {{"enableMenu": False}}}}
html_theme_options = {{
    "home_page_in_toc": True,
    "show_navbar_depth": 1,
    "use_download_button": False,
    "use_fullscreen_button": False,
    "use_source_button": False,
    "search_bar_text": {say("Search the book…", lang)!r},
    "show_toc_level": 2,
}}
aerophoto_site = {json.dumps(site, ensure_ascii=False, indent=1)}
'''


def _chapter_rows(lang: str, titles: dict) -> str:
    from .. import book

    rows = [f"| {say('chapter', lang)} | {say('source', lang)} | {say('live demos', lang)} |", "|---|---|---|"]
    for ch in book.CHAPTERS:
        title = titles.get(ch.name, ch.title)
        demos = "; ".join(d.name for d in ch.demos) if lang == "en" else str(len(ch.demos))
        rows.append(f"| [{_md(title)}]({ch.name}.ipynb) | {ch.source.replace('guide', 'пособие' if lang == 'ru' else 'guide').replace('article', 'статья' if lang == 'ru' else 'article')} | {_md(demos)} |")
    return "\n".join(rows)


def _md(text: str) -> str:
    return str(text).replace("|", "\\|").replace("\n", " ")


def front_page(lang: str, titles: dict, manual: list) -> str:
    """The book's front page (MyST Markdown): what it is, the chapters, and the hidden tables of contents."""
    from .. import book

    title = say("Aerial photogrammetry — an interactive workbook", lang)
    chapters = "\n".join(ch.name for ch in book.CHAPTERS)
    guide = "\n".join(f"manual/{p}" for p in manual)
    parts = [f"# {title}", "", say("This book is the course design in photogrammetry for land-management and cadastre "
             "students, one chapter per section of the guide, with the formulas, the guide's worked example (variant 00) "
             "recomputed, and live demonstrations. Every page here is the chapter as the student book shows it, run once "
             "on the guide's example; the button at the top of a page runs the same chapter live in your browser, with "
             "nothing to install.", lang), "",
             say("Your own variant, the graded tasks and their checks are in the live book (the button at the top of "
                 "each page) or in the installed book (the guide for students).", lang), "",
             f"## {say('Chapters', lang)}", "", _chapter_rows(lang, titles), "",
             f"* [{say('The glossary', lang)}](glossary.ipynb)",
             f"* [{say('The lecture pages', lang)}](lectures.md)", ""]
    if manual:
        parts.append(f"* [{say('Guide for students, lecturers and instructors', lang)}](manual/{manual[0]}.md)")
    parts += ["", "```{toctree}", ":hidden:", f":caption: {say('Chapters', lang)}", "", chapters, "```", "",
              "```{toctree}", ":hidden:", f":caption: {say('Reference', lang)}", "", "glossary", "lectures", "```", ""]
    if manual:
        parts += ["```{toctree}", ":hidden:", f":caption: {say('Guide for students, lecturers and instructors', lang)}",
                  "", guide, "```", ""]
    return "\n".join(parts)


def lectures_page(lang: str, titles: dict) -> str:
    """The list of lecture pages, each opening as an app in the browser book."""
    from .. import book

    rows = [f"# {say('Lectures in the browser', lang)}", "",
            say("Each lecture page shows a chapter's live demos one screen each, for a projector, without the code: it "
                "opens in the browser book (JupyterLite) in the same folder, so a lecture needs no server and nothing "
                "installed. Choose Run ▸ Run All Cells once the page has opened; the demos start on the guide's worked "
                "example (variant 00).", lang), ""]
    for ch in book.CHAPTERS:
        if not ch.demos:
            continue
        url = "../" + lecture_app_path(ch.notebook, lang)
        title = html.escape(titles.get(ch.name, ch.title))
        rows.append(f"* <a href=\"{html.escape(url, quote=True)}\">{title}</a> — "
                    f"[{say('the whole chapter', lang)}]({ch.name}.ipynb)")
    return "\n".join(rows) + "\n"


def _favicon() -> bytes:
    """The site's icon: a 32 × 32 PNG, a blue frame (the camera's) with its principal point, drawn here."""
    import io

    from PIL import Image, ImageDraw

    img = Image.new("RGBA", (32, 32), (0, 0, 0, 0))
    d = ImageDraw.Draw(img)
    d.rectangle((3, 3, 28, 28), outline=(0, 90, 140, 255), width=3)
    d.ellipse((13, 13, 18, 18), fill=(213, 94, 0, 255))
    buf = io.BytesIO()
    img.save(buf, format="PNG", optimize=True)
    return buf.getvalue()


def write_book(dest: Path, *, lang: str, pages: dict, glossary: dict, titles: dict, settings: dict, root: Path,
               css: str) -> None:
    """Write one book's Sphinx source into ``dest`` (emptied first).

    ``pages`` maps a chapter's name to its page notebook (:func:`aerophoto.website.pages.page_notebook`; the
    figures are already in ``dest/_static/fig``), ``glossary`` is the glossary's notebook, ``titles`` the chapters'
    titles in this language, ``settings`` the bar's settings (:mod:`aerophoto.website.sphinx_ext`), ``root`` the
    repository (for ``docs/manual``), ``css`` the site's stylesheet.
    """
    dest.mkdir(parents=True, exist_ok=True)
    (dest / "_ext").mkdir(exist_ok=True)
    shutil.copy2(Path(__file__).with_name("sphinx_ext.py"), dest / "_ext" / "aerophoto_site.py")
    (dest / "_static").mkdir(exist_ok=True)
    (dest / "_static" / "aerophoto-site.css").write_text(css, encoding="utf-8")
    shutil.copy2(Path(__file__).with_name("site.js"), dest / "_static" / "aerophoto-site.js")
    (dest / "_static" / "favicon.png").write_bytes(_favicon())
    shutil.copytree(Path(__file__).with_name("templates"), dest / "_templates", dirs_exist_ok=True)  # theme overrides
    (dest / "conf.py").write_text(conf_py(lang, settings), encoding="utf-8")
    for name, nb in pages.items():
        (dest / f"{name}.ipynb").write_text(json.dumps(nb, ensure_ascii=False, indent=1), encoding="utf-8")
    (dest / "glossary.ipynb").write_text(json.dumps(glossary, ensure_ascii=False, indent=1), encoding="utf-8")
    manual = []
    src = Path(root) / MANUAL_DIR
    if src.is_dir():
        (dest / "manual").mkdir(exist_ok=True)
        order = json.loads((src / "order.json").read_text(encoding="utf-8")) if (src / "order.json").is_file() else \
            sorted(p.stem for p in src.glob("*.md"))
        for stem in order:
            text = (src / f"{stem}.md").read_text(encoding="utf-8")
            if lang == "ru":  # the guide is written in English: said at the top of each page, under its title
                head, _, rest = text.partition("\n")
                note = say("This guide is in English for now.", lang)
                text = f"{head}\n\n<p class='aerophoto-untranslated' role='note'>{note}</p>\n{rest}"
            (dest / "manual" / f"{stem}.md").write_text(text, encoding="utf-8")
            manual.append(stem)
    (dest / "index.md").write_text(front_page(lang, titles, manual), encoding="utf-8")
    (dest / "lectures.md").write_text(lectures_page(lang, titles), encoding="utf-8")
