"""A submission made safe to show: no script, event handler, ``javascript:`` URL, external resource or form.

Everything the instructor opens is rendered from a student's notebook: the formgrader shows the autograded
notebook, the feedback HTML is made from it.  nbgrader 0.9.6's formgrade and feedback templates render a
markdown cell with ``markdown2html`` and never clean it, whatever ``HTMLExporter.sanitize_html`` says, so the
notebook itself is cleaned before nbgrader writes it (:class:`SanitizeNotebook`, the last of
``Autograde.autograde_preprocessors`` in every configuration the project ships) and again before feedback
is made (:func:`sanitize_file`).

The cleaning is bleach's (an allow-list HTML sanitiser, the one nbconvert uses), with a narrow allow-list:

* **markdown cells**: rendered to HTML (nbconvert's own ``markdown2html``), cleaned, and stored as that HTML —
  which markdown passes through unchanged; the result is checked by rendering it again as nbgrader will
  (:func:`_safe_markdown`), and a cell that does not come out clean is shown as plain text instead;
* **outputs**: ``text/plain``, PNG/JPEG/GIF images, cleaned ``text/html`` and ``text/markdown`` are kept;
  JavaScript, SVG, LaTeX (MathJax), widget views and every other type are dropped (a note says so); the
  answer records the trusted grader reads (:data:`aerophoto.checks.ANSWERS_MIME`) are kept — they are
  plain data no template renders;
* **attachments** of markdown cells: PNG/JPEG/GIF only; **raw cells**: escaped text; the notebook's widget
  state (which makes a page load the widget manager from a CDN) is dropped.

Links keep ``http``, ``https`` and ``mailto`` targets (a click, not a load); an image's source must be a
``data:`` PNG/JPEG/GIF; no ``style`` attribute (CSS can load URLs), no ``id`` (no clobbering the page's own).
"""

from __future__ import annotations

import copy
import html
import re

from nbconvert.preprocessors import Preprocessor
from traitlets import Bool

__all__ = ["clean_html", "sanitize_notebook", "sanitize_file", "SanitizeNotebook", "is_clean"]

TAGS = frozenset({
    "a", "abbr", "acronym", "b", "blockquote", "br", "caption", "code", "col", "colgroup", "dd", "del", "details",
    "div", "dl", "dt", "em", "h1", "h2", "h3", "h4", "h5", "h6", "hr", "i", "img", "ins", "kbd", "li", "mark",
    "ol", "p", "pre", "q", "s", "samp", "small", "span", "strike", "strong", "sub", "summary", "sup", "table",
    "tbody", "td", "tfoot", "th", "thead", "tr", "tt", "u", "ul", "var",
})
_COMMON = ("class", "title", "lang", "dir")
_IMAGE_DATA = re.compile(r"^data:image/(png|jpeg|jpg|gif|webp);base64,[A-Za-z0-9+/=\s]*$", re.IGNORECASE)
_LINK = re.compile(r"^(https?://|mailto:|#)", re.IGNORECASE)
KEEP_MIME = ("text/plain", "text/html", "text/markdown", "image/png", "image/jpeg", "image/gif")


def _attribute_ok(tag: str, name: str, value: str) -> bool:
    if name in _COMMON:
        return True
    if tag == "a" and name == "href":
        return bool(_LINK.match(value.strip()))
    if tag == "img":
        if name == "src":
            return bool(_IMAGE_DATA.match(value.strip()))
        return name in ("alt", "width", "height")
    if tag in ("td", "th"):
        return name in ("colspan", "rowspan", "align")
    if tag in ("ol",):
        return name in ("start", "type")
    if tag == "details":
        return name == "open"
    return False


def clean_html(text) -> str:
    """``text`` (HTML) with only the allowed tags and attributes left; everything else escaped or dropped."""
    import bleach

    text = text.decode("utf-8", "replace") if isinstance(text, bytes) else str(text)
    cleaner = bleach.sanitizer.Cleaner(tags=TAGS, attributes=_attribute_ok,
                                       protocols={"http", "https", "mailto", "data"}, strip=True,
                                       strip_comments=True)
    return cleaner.clean(text)


class _Audit:
    """Every start tag and attribute of an HTML text, as a parser sees it (stdlib ``html.parser``)."""

    def __init__(self):
        from html.parser import HTMLParser

        audit = self

        class _P(HTMLParser):
            def handle_starttag(self, tag, attrs):
                audit.check(tag, attrs)

            def handle_startendtag(self, tag, attrs):
                audit.check(tag, attrs)

            def handle_comment(self, data):
                audit.bad.append("comment")

            def handle_decl(self, decl):
                audit.bad.append("declaration")

            def handle_pi(self, data):
                audit.bad.append("processing instruction")

            def unknown_decl(self, data):
                audit.bad.append("declaration")

        self.bad: list[str] = []
        self.parser = _P(convert_charrefs=True)

    def check(self, tag, attrs):
        if tag not in TAGS:
            self.bad.append(f"<{tag}>")
        for name, value in attrs:
            if not _attribute_ok(tag, name, value or ""):
                self.bad.append(f"<{tag} {name}>")


def is_clean(rendered: str) -> bool:
    """True when HTML as a browser gets it holds only the allowed tags and attributes (and no comments)."""
    audit = _Audit()
    audit.parser.feed(str(rendered))
    audit.parser.close()
    return not audit.bad


_TEX_ACTIVE = re.compile(r"\\(href|url|require|style|class|cssId|unicode|data|html|bbox|mmlToken|action|toggle|"
                         r"texttip|tooltip|statusline|mathtip|fragment)(?![A-Za-z])")


def _defuse_tex(text: str) -> str:
    """TeX commands MathJax turns into links, styles or loaded extensions, shown as text instead."""
    return _TEX_ACTIVE.sub(r"\\backslash{}\1", text)


def _md2html(src: str) -> str:
    from nbconvert.filters.markdown import markdown2html

    return markdown2html(src)


def _as_text(src: str) -> str:
    return "<pre>" + html.escape(src, quote=True) + "</pre>"


def _safe_markdown(src: str) -> str:
    """A markdown cell's text replaced by cleaned HTML that renders (through markdown again) to clean HTML."""
    try:
        cleaned = clean_html(_md2html(_defuse_tex(src))).strip()
        if is_clean(_md2html(cleaned)):
            return cleaned
    except Exception:  # a renderer's failure: show the text, escaped
        pass
    text = _as_text(src)
    return text if is_clean(_md2html(text)) else html.escape(src)


def _clean_output(out, answers_mime: str) -> None:
    data = out.get("data")
    if not isinstance(data, dict):
        return
    dropped = []
    for mime in list(data):
        if mime == answers_mime or mime in KEEP_MIME:
            continue
        dropped.append(mime)
        del data[mime]
    if isinstance(data.get("text/html"), (str, list)):
        raw = "".join(data["text/html"]) if isinstance(data["text/html"], list) else data["text/html"]
        data["text/html"] = clean_html(_defuse_tex(raw))
    if isinstance(data.get("text/markdown"), (str, list)):
        raw = "".join(data["text/markdown"]) if isinstance(data["text/markdown"], list) else data["text/markdown"]
        data["text/markdown"] = _safe_markdown(raw)
    for mime in ("image/png", "image/jpeg", "image/gif"):
        if mime in data and not isinstance(data[mime], str):
            del data[mime]
    if dropped and "text/plain" not in data:
        data["text/plain"] = f"[{', '.join(dropped)} output not shown: the grader keeps no scripts or active content]"
    meta = out.get("metadata")
    if isinstance(meta, dict):
        for mime in list(meta):
            if mime not in data:
                del meta[mime]


def sanitize_notebook(nb) -> int:
    """Clean ``nb`` in place (see the module notes); returns how many cells or outputs were changed."""
    from .wire import ANSWERS_MIME

    changed = 0
    md = nb.get("metadata", {})
    if isinstance(md, dict) and "widgets" in md:
        del md["widgets"]
        changed += 1
    for cell in nb.get("cells", []):
        kind = cell.get("cell_type")
        src = cell.get("source", "")
        src = "".join(src) if isinstance(src, list) else str(src)
        if kind == "markdown":
            new = _safe_markdown(src)
            if new != src:
                cell["source"] = new
                changed += 1
            att = cell.get("attachments")
            if isinstance(att, dict):
                for name in list(att):
                    bundle = att[name] if isinstance(att[name], dict) else {}
                    keep = {m: d for m, d in bundle.items() if m in ("image/png", "image/jpeg", "image/gif")
                            and isinstance(d, str)}
                    if keep:
                        att[name] = keep
                    else:
                        del att[name]
        elif kind == "raw":
            cell["source"] = html.escape(src)
            cell.get("metadata", {}).pop("raw_mimetype", None)
            cell.get("metadata", {}).pop("format", None)
            changed += 1
        elif kind == "code":
            for out in cell.get("outputs", []) or []:
                before = copy.deepcopy(out.get("data"))
                _clean_output(out, ANSWERS_MIME)
                changed += out.get("data") != before
            meta = cell.get("metadata", {})
            if isinstance(meta, dict):
                meta.pop("widgets", None)
    return changed


def sanitize_file(path) -> int:
    """Clean the notebook at ``path`` in place (atomically, only if anything changed)."""
    from .common import read_nb, write_nb

    nb = read_nb(path)
    n = sanitize_notebook(nb)
    if n:
        write_nb(nb, path)
    return n


class SanitizeNotebook(Preprocessor):
    """nbconvert/nbgrader preprocessor: :func:`sanitize_notebook` on the whole notebook (on unless switched off:
    nbconvert's preprocessors are off by default, and nbgrader registers its lists without enabling them)."""

    enabled = Bool(True).tag(config=True)

    def preprocess(self, nb, resources):
        sanitize_notebook(nb)
        return nb, resources
