"""The book as a website: one static folder with the readable book in English and Russian, the live book and the PDFs.

``aerophoto-course site [--out _book]`` builds::

    _book/
      index.html            the front door: both books, the live book, the PDFs
      en/, ru/              the readable books (Sphinx + myst-nb + sphinx-book-theme): every chapter a page with its
                            prose, typeset formulas, the guide's example (variant 00) executed at build time, every
                            figure a static image with its text alternative, numbered figures and tables, search,
                            the glossary, the lecture list, the guide for students, lecturers and instructors
      live/                 the browser book (JupyterLite, :mod:`aerophoto.lite`), English and Russian chapters and the
                            lecture pages
      aerophoto-en.pdf, aerophoto-ru.pdf    the whole book printed
      _assets/mathjax/      MathJax 3 (npm), served from the folder
      aerophoto-site.json   what was built: versions, sizes, figures and tables per chapter, translation state

Every page has a bar: run this chapter in the browser (the same chapter and language in ``live/``), open it on the
course hub (``--hub-url``), the same page in the other language, the PDF.  The build is offline once its pinned
inputs are cached (``$AEROPHOTO_SITE_CACHE`` or ``~/.cache/aerophoto-site``, and the browser book's own cache):
Sphinx and its theme from ``deploy/site/requirements.txt`` in an environment of their own, MathJax from
``deploy/site/package-lock.json``; the chapters are executed in the book's environment and cached
(:mod:`aerophoto.website.execute`).  Nothing in the site names another host for a script, a style, a font or an
image (checked before the folder is replaced).
"""

from __future__ import annotations

import html
import json
import os
import re
import shutil
import tempfile
import time
from pathlib import Path

__all__ = ["build", "main", "cache_dir", "MANIFEST", "check_site", "chapter_notebooks", "page_title"]

#: the site's build record (also the mark that a folder is a built web book)
MANIFEST = "aerophoto-site.json"
#: a resource the browser would fetch from another host: a script, picture, frame or media source, a stylesheet or
#: preload, a CSS url() (plain links to other sites are fine: the reader follows them or not)
_REMOTE = re.compile(r"""<(?:script|img|iframe|source|video|audio|embed|track)\b[^>]*\s(?:src|srcset)\s*=\s*["']\s*(?:https?:)?//"""
                     r"""|<link\b[^>]*\shref\s*=\s*["']\s*(?:https?:)?//|url\(\s*["']?\s*(?:https?:)?//""", re.I)


def cache_dir() -> Path:
    """Where the site's build tools and executed chapters are kept: ``$AEROPHOTO_SITE_CACHE`` or
    ``~/.cache/aerophoto-site``."""
    return Path(os.environ.get("AEROPHOTO_SITE_CACHE") or Path.home() / ".cache" / "aerophoto-site")


def chapter_notebooks(notebooks: Path, lang: str, only=None) -> list[tuple[str, dict, list]]:
    """``[(name, notebook, untranslated cell ids)]`` of every chapter and the glossary in ``lang``: the English
    notebooks as they are, the Russian ones made by :func:`aerophoto.i18n.prose.russian_notebook` from
    ``notebooks/ru/NN_slug.md`` (whatever state the translations are in); ``only``: these names alone."""
    from .. import book
    from ..i18n import prose

    out = []
    for name in [ch.name for ch in book.CHAPTERS] + ["glossary"]:
        if only is not None and name not in only:
            continue
        path = Path(notebooks) / f"{name}.ipynb"
        nb = json.loads(path.read_text(encoding="utf-8"))
        if lang == "ru":
            nb, untranslated = prose.russian_notebook(nb, prose.read_translations(prose.translation_path(path)))
        else:
            untranslated = []
        out.append((name, nb, untranslated))
    return out


def page_title(nb: dict, default: str) -> str:
    """The text of the notebook's first Markdown heading (``# …``), without Markdown; ``default`` if none."""
    for c in nb.get("cells", []):
        if c.get("cell_type") == "markdown":
            src = "".join(c["source"]) if isinstance(c["source"], list) else c["source"]
            m = re.search(r"^#\s+(.+)$", src, re.M)
            if m:
                return re.sub(r"[*_`]", "", m.group(1)).strip()
    return default


def check_site(site: Path) -> list[str]:
    """What is wrong with a built site: a page naming another host for a resource, a picture that is missing, a
    link to a PDF that is not there."""
    problems = []
    for p in sorted(site.rglob("*.html")):
        if p.relative_to(site).parts[0] == "live":
            continue  # the browser book is checked by its own build (aerophoto.lite)
        text = p.read_text(encoding="utf-8", errors="replace")
        for m in _REMOTE.finditer(text):
            problems.append(f"{p.relative_to(site)}: {text[m.start():m.start() + 120]}")
        for src in re.findall(r"""<img[^>]+src=["']([^"'#?]+)""", text):
            if not src.startswith("data:") and not (p.parent / src).is_file():
                problems.append(f"{p.relative_to(site)}: missing picture {src}")
        for href in re.findall(r"""<a\b[^>]*\shref=["']([^"'#?:]+\.pdf)["']""", text):
            if not (p.parent / href).is_file():
                problems.append(f"{p.relative_to(site)}: missing PDF {href}")
    for p in sorted(site.rglob("*.css")):
        if p.relative_to(site).parts[0] != "live" and _REMOTE.search(p.read_text(encoding="utf-8", errors="replace")):
            problems.append(f"{p.relative_to(site)} names another host")
    return problems


def _front_door(langs, *, pdf: bool = True) -> str:
    from .chrome import LANG_NAMES, say
    from .project import PDF_NAME

    cards = []
    for lang in langs:
        t = html.escape(say("Aerial photogrammetry — an interactive workbook", lang))
        printed = (f"<p><a href='{PDF_NAME.format(lang=lang)}'>{html.escape(say('The whole book as PDF', lang))}</a></p>"
                   if pdf else "")
        cards.append(
            f"<section lang='{lang}'><h2>{t}</h2><p><a class='read' href='{lang}/index.html'>"
            f"{html.escape(say('Read the book', lang))} ({LANG_NAMES[lang]})</a></p>"
            f"<p><a href='{html.escape(_live_default(lang), quote=True)}'>▶ {html.escape(say('Open the book in the browser', lang))}"
            f"</a></p>{printed}</section>")
    return ("<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'>"
            "<meta name='viewport' content='width=device-width, initial-scale=1'>"
            f"<title>aerophoto — {html.escape(say('Aerial photogrammetry — an interactive workbook', 'en'))}</title>"
            "<style>body{font-family:system-ui,sans-serif;max-width:60rem;margin:2rem auto;padding:0 1rem;color:#1f2328}"
            "main{display:flex;flex-wrap:wrap;gap:2rem}section{flex:1 1 22rem}a{color:#005a8c;font-weight:600}"
            "a.read{font-size:1.2rem}h1{font-size:1.6rem}</style></head><body><main><h1 style='flex-basis:100%'>"
            "aerophoto</h1>" + "".join(cards) + "</main></body></html>\n")


def _live_default(lang: str) -> str:
    from .project import live_path

    return live_path("00_start_here.ipynb", lang)


def _live(tmp: Path, lite_dir, root: Path, out) -> tuple[Path, dict]:
    """The browser book: a copy of an already built one (``lite_dir``), or built here."""
    from .. import lite

    dest = tmp / "site" / "live"
    if lite_dir is not None:
        lite_dir = Path(lite_dir)
        if not (lite_dir / lite.MANIFEST).is_file():
            from .stack import SiteBuildError

            raise SiteBuildError(f"{lite_dir} is not a built browser book (aerophoto-course lite --out {lite_dir})")
        shutil.copytree(lite_dir, dest)
        out(f"site: the browser book copied from {lite_dir}")
    else:
        lite.build(dest, root=root, out=out)
    return dest, json.loads((dest / lite.MANIFEST).read_text(encoding="utf-8"))


def _book(lang: str, executed: list, *, src: Path, root: Path, hub_url, pdf: bool, out) -> dict:
    """Write one book's Sphinx source from its executed notebooks (``pdf``: the bar links the printed book);
    returns its summary per chapter."""
    from .. import book
    from .pages import FIGURE_DIR, page_notebook
    from .project import PDF_NAME, live_path, write_book

    names = {ch.name for ch in book.CHAPTERS}
    demos = {d.cell: d for ch in book.CHAPTERS for d in ch.demos}
    pages, titles, summary, glossary = {}, {}, {}, None
    for (name, _nb, untranslated), done in executed:
        chapter = name[:2] if name in names else "G"
        live = "../" + (live_path(f"{name}.ipynb", lang) if name in names else _live_default(lang))
        page, info = page_notebook(done, chapter=chapter, lang=lang, figdir=src / FIGURE_DIR, rel=FIGURE_DIR,
                                   live_url=live, pages=names, untranslated=untranslated, demos=demos)
        titles[name] = page_title(page, name)
        summary[name] = {**info, "untranslated": list(untranslated)}
        if name in names:
            pages[name] = page
        else:
            glossary = page
    settings = {"live": {n: live_path(f"{n}.ipynb", lang) for n in pages}, "live_default": _live_default(lang),
                "hub": ({n: f"{hub_url.rstrip('/')}/hub/user-redirect/lab/tree/workbook/{n}.ipynb" for n in pages}
                        if hub_url else {}),
                "pdf": PDF_NAME.format(lang=lang) if pdf else ""}
    css = (Path(__file__).with_name("site.css")).read_text(encoding="utf-8")
    write_book(src, lang=lang, pages=pages, glossary=glossary, titles=titles, settings=settings, root=root, css=css)
    return summary


def _size(path: Path) -> int:
    return sum(p.stat().st_size for p in Path(path).rglob("*") if p.is_file()) if Path(path).is_dir() else \
        Path(path).stat().st_size


def build(out_dir="_book", *, root=None, notebooks=None, cache=None, hub_url=None, lite_dir=None, pdf=True,
          langs=("en", "ru"), jobs=2, only=None, out=print) -> dict:
    """Build the web book into ``out_dir`` (replacing an earlier build); returns its manifest.

    ``lite_dir`` reuses a browser book already built (``aerophoto-course lite``) instead of building one;
    ``hub_url`` adds "open on the course hub" to every chapter; ``pdf=False`` skips the printed books.  Raises
    :class:`aerophoto.website.stack.SiteBuildError`.  ``only`` (chapter names, and ``"glossary"``) builds those
    pages alone — for trying a change; the book's table of contents then names pages that are not there.
    """
    from .. import __version__, lite
    from . import stack
    from .execute import execute_all
    from .project import MATHJAX, PDF_NAME

    t0 = time.monotonic()
    from ..course.common import repo_root

    root = Path(root) if root else repo_root()
    if root is None:
        raise stack.SiteBuildError("aerophoto-course site builds from a source checkout (notebooks/, deploy/site/)")
    deploy = stack.deploy_dir(root)
    notebooks = Path(notebooks) if notebooks else root / "notebooks"
    cache = Path(cache) if cache else cache_dir()
    cache.mkdir(parents=True, exist_ok=True)
    out_dir = Path(out_dir).resolve()
    bindir = stack.sphinx_bin(deploy, cache, out)
    node = stack.npm_assets(deploy, cache, out)
    times = {}
    with tempfile.TemporaryDirectory(prefix="aerophoto-site-") as tmp:
        tmp = Path(tmp)
        site = tmp / "site"
        site.mkdir()
        stack.copy_mathjax(node, site / Path(MATHJAX).parent)
        t = time.monotonic()
        _live_dir, live_manifest = _live(tmp, lite_dir, root, out)
        times["live_s"] = round(time.monotonic() - t, 1)
        t = time.monotonic()
        todo = [(lang, item) for lang in langs for item in chapter_notebooks(notebooks, lang, only)]
        done = execute_all([(name, lang, nb) for lang, (name, nb, _u) in todo], cache=cache, cwd=notebooks,
                           jobs=jobs, out=out)
        times["execute_s"] = round(time.monotonic() - t, 1)
        summary = {}
        for lang in langs:
            pairs = [(item, d) for (lg, item), d in zip(todo, done) if lg == lang]
            src = tmp / f"src-{lang}"
            summary[lang] = _book(lang, pairs, src=src, root=root, hub_url=hub_url, pdf=pdf, out=out)
            html_out = tmp / "html" / lang  # myst-nb writes jupyter_execute/ beside the output folder: not in the site
            times[f"sphinx_{lang}_s"] = round(stack.sphinx_build(bindir, src, html_out, jobs=jobs, out=out), 1)
            for p in html_out.rglob("*.map"):  # the theme's source maps: for its developers, 3.5 MB a book
                p.unlink()
            if not any(p.is_file() for p in (html_out / "_sources").rglob("*")):
                shutil.rmtree(html_out / "_sources", ignore_errors=True)  # Sphinx leaves it empty (no sources copied)
            shutil.move(str(html_out), str(site / lang))
            if pdf:
                single = tmp / "print" / lang
                stack.sphinx_build(bindir, src, single, builder="singlehtml", jobs=jobs, out=out)
                if not (tmp / "print" / Path(MATHJAX).parent).exists():
                    shutil.copytree(site / Path(MATHJAX).parent, tmp / "print" / Path(MATHJAX).parent)
                from .chrome import say

                times[f"pdf_{lang}_s"] = round(stack.print_pdf(single / "index.html", site / PDF_NAME.format(lang=lang),
                                                              title=say("Aerial photogrammetry — an interactive "
                                                                        "workbook", lang), out=out), 1)
        (site / "index.html").write_text(_front_door(langs, pdf=pdf), encoding="utf-8")
        (site / ".nojekyll").write_text("", encoding="utf-8")  # GitHub Pages: serve _static/, _assets/ as they are
        problems = check_site(site)
        if problems:
            raise stack.SiteBuildError("the built site failed its checks:\n- " + "\n- ".join(problems[:30]))
        sizes = {part.name: _size(part) for part in sorted(site.iterdir()) if not part.name.startswith(".")}
        manifest = {
            "aerophoto": __version__,
            "build_s": round(time.monotonic() - t0, 1),
            "steps_s": times,
            "site_bytes": _size(site),
            "bytes": sizes,
            "languages": list(langs),
            "hub_url": hub_url,
            "pdf": bool(pdf),
            "pages": sorted(only) if only is not None else None,
            "versions": {"sphinx": "9.0.4", "myst-nb": "1.4.0", "sphinx-book-theme": "1.4.0",
                         "pydata-sphinx-theme": "0.20.0", "mathjax": "3.2.2",
                         "jupyterlite-core": live_manifest.get("versions", {}).get("jupyterlite-core")},
            "chapters": summary,
        }
        (site / MANIFEST).write_text(json.dumps(manifest, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
        try:
            lite._replace(out_dir, site, marker=MANIFEST, what="an aerophoto web book")
        except lite.LiteBuildError as exc:
            raise stack.SiteBuildError(str(exc)) from None
    out(f"site: built {out_dir} in {manifest['build_s']:.0f} s: {manifest['site_bytes'] / 1e6:.1f} MB "
        f"({', '.join(f'{k} {v / 1e6:.1f} MB' for k, v in sizes.items())})")
    return manifest


def main(out_dir="_book", *, cache=None, hub_url=None, lite_dir=None, pdf=True, out=print) -> int:
    """``aerophoto-course site``: build the web book; exit 1 with the reason when it cannot be built."""
    from .execute import ExecutionError
    from .stack import SiteBuildError

    try:
        build(out_dir, cache=cache, hub_url=hub_url, lite_dir=lite_dir, pdf=pdf, out=out)
    except (SiteBuildError, ExecutionError) as exc:
        out(f"aerophoto-course site: {exc}")
        return 1
    out(f"Serve it with any static web server, e.g. `python -m http.server -d {out_dir} 8000 --bind 127.0.0.1`, "
        "and open http://127.0.0.1:8000/ (copy the folder as it is to any static host: see the guide, "
        "\"Publishing the book\")")
    return 0
