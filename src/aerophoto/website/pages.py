"""An executed chapter made into a page of the web book: figures as files, numbered; tables numbered; live links.

:func:`page_notebook` takes an executed notebook (:mod:`aerophoto.website.execute`) and returns the notebook that
Sphinx renders (myst-nb, no execution there):

* every picture in an output — a static figure (:func:`aerophoto.plots.static`: ``<img alt=…>`` with a data URI),
  a PNG output, a live demo's or a tool's snapshot (:mod:`aerophoto.website.snapshot`) — is written once into the
  book's figure folder under the first 16 hex digits of its SHA-256 (the same picture, the same file: content-
  addressed, so a browser may keep it for good) and shown from there, with its text alternative, its pixel size
  and ``loading="lazy"``; each output with a picture is a numbered ``<figure id="fig-NN-k">`` ("Figure 03.2");
* every HTML table in an output gets its number in its caption ("Table 03.1 — …", ``id="table-NN-k"``);
* a live demo's picture is followed by one line, "open this demo live", to the same chapter in the browser book
  (JupyterLite, in the same folder), and the demo's text alternative says what it shows (the registry's
  :attr:`aerophoto.book.Demo.sees`, or the demo's own title and the figure's texts in Russian);
* a check cell's error (an unanswered task raises by design) keeps its ✗ lines and drops the traceback;
* "chapter NN" / "главе NN" in the prose links to that chapter's page;
* on the Russian page, a Markdown cell with no up-to-date translation keeps its English under a small note.

Pure functions on notebook dicts; only :func:`page_notebook` writes (the figure files).
"""

from __future__ import annotations

import base64
import copy
import hashlib
import html
import re
import struct
from pathlib import Path

from .chrome import say

__all__ = ["page_notebook", "png_size", "chapter_links", "FIGURE_DIR"]

#: where the figures go, relative to the book's root (a Sphinx static folder: copied as it is)
FIGURE_DIR = "_static/fig"
_DATA_IMG = re.compile(r"""src=(['"])data:image/png;base64,([A-Za-z0-9+/=\s]+)\1""")
_TABLE = re.compile(r"<table\b[^>]*>", re.I)
_CAPTION = re.compile(r"(<caption\b[^>]*>)", re.I)
_CHAPTER_EN = re.compile(r"(?<![\[\w/#])(chapters? )(\d\d)\b(?![\]\w(])")
_CHAPTER_RU = re.compile(r"(?<![\[\w/#])(глав[аеуыи]|главой|главам|главах) (\d\d)\b(?![\]\w(])")
_ANSI = re.compile(r"\x1b\[[0-9;]*m")
_CODE = re.compile(r"(```.*?```|`[^`\n]*`|\$\$.*?\$\$|\$[^$\n]*\$|\]\([^)]*\)|<[^>]+>)", re.S)


def png_size(data: bytes) -> tuple[int, int]:
    """(width, height) in pixels from a PNG's header."""
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise ValueError("not a PNG")
    return struct.unpack(">II", data[16:24])


class _Figures:
    """Writes the pictures of one page into the figure folder and numbers the page's figures and tables."""

    def __init__(self, chapter: str, figdir: Path, rel: str, lang: str):
        self.chapter, self.figdir, self.rel, self.lang = chapter, figdir, rel, lang
        self.n_fig = self.n_table = 0
        self.files: list[str] = []

    def file(self, data: bytes) -> tuple[str, int, int]:
        name = hashlib.sha256(data).hexdigest()[:16] + ".png"
        path = self.figdir / name
        if not path.is_file():
            path.write_bytes(data)
        self.files.append(name)
        w, h = png_size(data)
        return f"{self.rel}/{name}", w, h

    def images(self, text: str) -> tuple[str, int]:
        """Data-URI images → files (with width, height, lazy loading); returns (html, number of images)."""
        count = 0

        def one(m):
            nonlocal count
            count += 1
            src, w, h = self.file(base64.b64decode("".join(m.group(2).split())))
            return f'src="{src}" width="{w}" height="{h}" loading="lazy" decoding="async"'

        return _DATA_IMG.sub(one, text), count

    def tables(self, text: str) -> str:
        def one(m):
            self.n_table += 1
            label = say("Table", self.lang)
            num = f"<span class='aerophoto-num'>{label} {self.chapter}.{self.n_table}</span>"
            return f"{m.group(0)[:-1]} id='table-{self.chapter}-{self.n_table}'>" + f"\0{num}\0"

        text = _TABLE.sub(one, text)
        # a table that had a caption: the number goes into it; one without: a caption of its own
        parts = text.split("\0")
        out = [parts[0]]
        for i in range(1, len(parts), 2):
            num, rest = parts[i], parts[i + 1]
            m = _CAPTION.match(rest.lstrip())
            if m:
                rest = rest.lstrip()
                out.append(f"{m.group(1)}{num} — {rest[m.end():]}")
            else:
                out.append(f"<caption>{num}</caption>{rest}")
        return "".join(out)

    def figure(self, body: str, caption: str = "") -> str:
        self.n_fig += 1
        label = f"{say('Figure', self.lang)} {self.chapter}.{self.n_fig}"
        cap = f"<span class='aerophoto-num'>{label}</span>" + (f" — {caption}" if caption else "")
        return (f"<figure class='aerophoto-figure' id='fig-{self.chapter}-{self.n_fig}'>{body}"
                f"<figcaption>{cap}</figcaption></figure>")


def chapter_links(text: str, lang: str, pages: set) -> str:
    """Link "chapter NN" (Russian: "главе NN", …) to chapter NN's page, outside code, math, links and tags."""
    pattern = _CHAPTER_RU if lang == "ru" else _CHAPTER_EN
    by_num = {p[:2]: p for p in pages}

    def link(m):
        page = by_num.get(m.group(2))
        return f"[{m.group(0)}]({page}.ipynb)" if page else m.group(0)

    pieces = _CODE.split(text)
    return "".join(p if i % 2 else pattern.sub(link, p) for i, p in enumerate(pieces))


def _src(c) -> str:
    s = c.get("source", "")
    return "".join(s) if isinstance(s, list) else str(s)


def _demo_alt(demo, title: str, lang: str) -> str:
    if lang == "en" and demo is not None:
        return f"{say('Live demo', lang)} “{demo.name}” at the guide's example values: {demo.sees}."
    return f"{say('Live demo', lang)} «{title}» — {say('at the starting values of the guide example', lang)}."


def _live_line(live_url: str, lang: str) -> str:
    return (f"<p class='aerophoto-open-live'><a href='{html.escape(live_url, quote=True)}'>▶ "
            f"{say('Open this demo live', lang)}</a> <span>{say('in the browser, nothing to install', lang)}</span></p>")


def _output(o: dict, figs: _Figures, *, demo, live_url: str, lang: str) -> dict:
    """One output of a code cell, as the page shows it."""
    data = o.get("data")
    if not isinstance(data, dict):
        return o
    if "text/html" in data:
        text = _src({"source": data["text/html"]})
        kind = re.search(r"data-aerophoto-live='(demo|tool)'", text)
        if kind and kind.group(1) == "demo":
            title = html.unescape(re.search(r"data-aerophoto-title='([^']*)'", text).group(1))
            alt = html.escape(_demo_alt(demo, title, lang), quote=True)
            text = re.sub(r"(<img class='aerophoto-snapshot-figure'[^>]*?alt=')[^']*'", lambda m: m.group(1) + alt + "'",
                          text, count=1)
        text = figs.tables(text)
        text, n_img = figs.images(text)
        if n_img:
            caption = ""
            if kind:
                caption = (html.escape(demo.name) if demo is not None and lang == "en" else
                           html.escape(html.unescape(re.search(r"data-aerophoto-title='([^']*)'", text).group(1))))
                caption = f"{say('live demo' if kind.group(1) == 'demo' else 'interactive tool', lang)}" + \
                          (f": {caption}" if caption else "")
            text = figs.figure(text, caption)
        if kind:
            text += _live_line(live_url, lang)
        return {**o, "data": {"text/html": text, "text/plain": data.get("text/plain", "")}, "metadata": {}}
    if "image/png" in data:
        png = base64.b64decode("".join(_src({"source": data["image/png"]}).split()))
        src, w, h = figs.file(png)
        alt = html.escape(_src({"source": data.get("text/plain", "figure")}), quote=True)
        img = f'<img src="{src}" alt="{alt}" width="{w}" height="{h}" loading="lazy" decoding="async">'
        return {**o, "data": {"text/html": figs.figure(img), "text/plain": ""}, "metadata": {}}
    return o


def _code_outputs(c: dict, figs: _Figures, *, demo, live_url: str, lang: str) -> list:
    outs = []
    check = re.fullmatch(r"task-\d\d-\d+-check", str(c.get("id", "")))
    for o in c.get("outputs", []):
        if o.get("output_type") == "error":
            if check:  # an unanswered task's check raises by design: its message, without the traceback
                text = _ANSI.sub("", str(o.get("evalue", ""))).strip()
                outs.append({"output_type": "stream", "name": "stdout", "text": text + "\n"})
            else:
                outs.append(o)
            continue
        if "application/vnd.jupyter.widget-view+json" in (o.get("data") or {}):
            continue  # a widget the snapshot did not catch: nothing a page without a kernel can show
        outs.append(_output(o, figs, demo=demo, live_url=live_url, lang=lang))
    return outs


def page_notebook(nb: dict, *, chapter: str, lang: str, figdir: Path, rel: str, live_url: str, pages: set,
                  untranslated=(), demos: dict | None = None) -> tuple[dict, dict]:
    """The page's notebook (see the module notes) and a summary ``{"figures": n, "tables": n, "files": [...]}``.

    ``chapter`` is the number ("03"), ``figdir`` the folder the pictures go into, ``rel`` its path as the page
    links it, ``live_url`` the chapter in the browser book, ``pages`` the names of every chapter page,
    ``untranslated`` the ids of Markdown cells left in English (Russian book), ``demos`` the registry's
    :class:`aerophoto.book.Demo` by cell id.
    """
    out = copy.deepcopy(nb)
    figdir.mkdir(parents=True, exist_ok=True)
    figs = _Figures(chapter, figdir, rel, lang)
    demos = demos or {}
    untranslated = set(untranslated)
    for i, c in enumerate(out.get("cells", [])):
        cid = str(c.get("id") or f"cell-{i}")
        if c.get("cell_type") == "markdown":
            text = chapter_links(_src(c), lang, pages)
            if cid in untranslated:
                note = say("This part is not translated yet: it is shown in English.", lang)
                text = f"<p class='aerophoto-untranslated' role='note'>{note}</p>\n\n{text}"
            c["source"] = text
        elif c.get("cell_type") == "code":
            if re.fullmatch(r"task-\d\d-\d+-answer", cid):  # the page marks it (myst-nb: class tag_aerophoto-answer)
                tags = c.setdefault("metadata", {}).setdefault("tags", [])
                if "aerophoto-answer" not in tags:
                    tags.append("aerophoto-answer")
            c["outputs"] = _code_outputs(c, figs, demo=demos.get(cid), live_url=live_url, lang=lang)
            c.get("metadata", {}).pop("execution", None)
    return out, {"figures": figs.n_fig, "tables": figs.n_table, "files": sorted(set(figs.files))}
