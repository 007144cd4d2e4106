"""The note as data, and its two renderings: PDF through Typst and a self-contained HTML page.

:class:`Document` is a list of blocks — headings, paragraphs, formulas, tables, figures, full pages — and a
title page.  It is written as ``report.json`` into the build folder; the Typst source (:data:`TEMPLATE`) reads
that file with Typst's own ``json()``, so no text of the student (a name, a value, a chosen option) is ever
spliced into markup and nothing needs escaping.  Mathematics is the package's own: a formula or a table header
is Typst math written in :mod:`aerophoto.report` with numbers substituted as quoted strings by
:func:`formula`, which accepts only numbers the book's formatter wrote (:mod:`aerophoto.i18n.numfmt`); the
template ``eval``s exactly those strings and nothing a student typed.

The layout follows the usual standard of a Russian university's explanatory note (ГОСТ 7.32 in the form
universities adopt it, as the guide's §15 asks with its СТП ПГУАС 1.2.1.003-2005): A4, margins 30/15/20/20 mm,
serif 13 pt with 1.25 cm indents, structural headings (ВВЕДЕНИЕ, ЗАКЛЮЧЕНИЕ …) centred in capitals, numbered
sections each on a new page, "Таблица N – …" above a table, "Рисунок N – …" under a figure, formulas centred
with their number at the right margin, page numbers at the foot from the contents on.

Typst (the PyPI package ``typst``, with fonts that cover Cyrillic: Libertinus Serif, New Computer Modern and
its mathematics) typesets offline in well under a second; figures are included as PDF (vector), the
fotoschema sheet as a page of its own size.  System fonts are ignored, so the PDF is the same on every machine.
"""

from __future__ import annotations

import html
import json
import re
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["Document", "TEMPLATE", "compile_pdf", "write_html", "typst_available", "formula", "math_text",
           "NUMBER_RE"]

#: what a number substituted into a formula may look like (the book's formatter's output, nothing else)
NUMBER_RE = re.compile(r"^[0-9\u202f\u00a0,.\u2212+\u2014\u221e/ ()−]*$")
_PLACEHOLDER = re.compile(r"\{([A-Za-z_][A-Za-z0-9_]*)\}")


def _seg(seg: dict) -> dict:
    """A copy of a text/math segment or cell, its math with thin spaces before the units."""
    out = dict(seg)
    if "math" in out:
        out["math"] = _thin_units(str(out["math"]))
    return out


def _thin_units(typst: str) -> str:
    """Quoted strings that open with a space (the units, ``" мм"``) become ``thin "мм"``; strings pair up from the
    start (the package's formulas have no escaped quotes)."""
    parts = typst.split('"')
    if len(parts) % 2 == 0:
        return typst
    out = []
    for k, p in enumerate(parts):
        if k % 2 == 0:
            out.append(p)
        elif p[:1].isspace() and p.strip():
            out.append('thin "' + p.strip() + '"')
        else:
            out.append('"' + p + '"')
    return "".join(out)


def formula(template: str, **numbers: str) -> str:
    """Typst math of ``template`` with each ``{name}`` replaced by the quoted formatted number ``numbers[name]``.

    The numbers must be strings the formatter wrote (:data:`NUMBER_RE`); anything else raises ValueError naming
    it, so no text of a student can reach the formula.
    """
    def sub(m):
        name = m.group(1)
        if name not in numbers:
            raise ValueError(f"formula: no number given for {{{name}}} in {template!r}")
        s = str(numbers[name])
        if not NUMBER_RE.match(s):
            raise ValueError(f"{name} = {s!r} is not a formatted number")
        before = template[:m.start()].rstrip()
        after = template[m.end():].lstrip()
        if s.startswith("\u2212") and (before.endswith(("-", "+", "dot", "times", "/")) or after.startswith("^")):
            return '("' + s + '")'  # a negative number after an operator, or raised to a power, in brackets
        return '"' + s + '"'
    return _PLACEHOLDER.sub(sub, template)


_TEXT_SUBS = [(r'"([^"]*)"', r"\1"), (r"\bdot\b", "·"), (r"\btimes\b", "×"), (r"\bapprox\b", "≈"),
              (r"\bdelta\b", "δ"), (r"\bDelta\b", "Δ"), (r"\balpha\b", "α"), (r"\bphi\b", "φ"), (r"\btau\b", "τ"),
              (r"\bsigma\b", "σ"), (r"\brho\b", "ρ"), (r"\bbeta\b", "β"), (r"\bgamma\b", "γ"), (r"\blambda\b", "λ"),
              (r"\bkappa\b", "κ"), (r"\bpi\b", "π"), (r"\bsum\b", "Σ"), (r"\bsqrt\b", "√"), (r"\btg\b", "tg"),
              (r"\bcos\b", "cos"), (r"\bsin\b", "sin"), (r"\barrow\b", "→"), (r"\bquad\b", "  "), (r"<=", "≤"),
              (r">=", "≥"), (r"!=", "≠"), (r"\bceil\b", "⌈⌉"), (r"_", ""), (r"\^2", "²"), (r"\^3", "³"),
              (r"\s+", " ")]


def math_text(typst: str) -> str:
    """A plain-text reading of the package's Typst math (for the HTML page and the JSON)."""
    s = typst
    for pat, rep in _TEXT_SUBS:
        s = re.sub(pat, rep, s)
    return s.strip()


@dataclass
class Document:
    """The note's content: ``title_page`` (dict of strings), ``meta``, ``blocks`` (see the module notes).

    ``n_tables`` counts the tables numbered by the document (:meth:`table` with ``label=None``); the guide's
    tables keep the guide's numbers.  ``n_figures`` numbers the figures.
    """

    title_page: dict
    meta: dict
    blocks: list = field(default_factory=list)
    n_tables: int = 0
    n_figures: int = 0
    first_extra_table: int = 14

    # ---- headings and text
    def heading(self, level: int, text: str, *, num: str = "", structural: bool = False, newpage: bool = False,
                outline: bool = True) -> None:
        """A heading; ``structural`` ones (ВВЕДЕНИЕ …) are centred in capitals, sections open a new page."""
        self.blocks.append({"t": "heading", "level": int(level), "text": str(text), "num": str(num),
                            "structural": bool(structural), "newpage": bool(newpage), "outline": bool(outline),
                            "anchor": f"h{len(self.blocks)}"})

    def par(self, text, style: str = "normal") -> None:
        """A paragraph: ``text`` a string, or a list of segments ``{"text": …}`` / ``{"math": …}`` (math the
        package's own).  ``style``: normal, plain (no indent), note, missing, bad, ok."""
        segs = [{"text": str(text)}] if isinstance(text, str) else [_seg(s) for s in text]
        self.blocks.append({"t": "par", "segs": segs, "style": style})

    def items(self, entries, *, numbered: bool = False) -> None:
        """A list; each entry a string or a list of segments as in :meth:`par`."""
        out = [[{"text": str(e)}] if isinstance(e, str) else [_seg(s) for s in e] for e in entries]
        self.blocks.append({"t": "list", "items": out, "numbered": bool(numbered)})

    def math(self, typst: str, *, num: str = "", text: str = "") -> None:
        """A displayed formula (Typst math from :func:`formula`), with its number "(2.1)" at the right.

        A unit written as a quoted string with a leading space (``" мм"``) is set a thin space after its number.
        """
        typst = _thin_units(typst)
        self.blocks.append({"t": "math", "typst": typst, "text": text or math_text(typst), "num": str(num)})

    # ---- tables and figures
    def table(self, caption: str, header, rows, *, label: str | None = None, widths=None, align=None,
              size: float = 10.5) -> str:
        """A table "Таблица N – caption"; returns its label.

        ``label``: the guide's number ("2") for the guide's tables; None numbers it after the guide's
        (:attr:`first_extra_table`, 14, 15 …).  ``header``: a list of header rows; ``rows``: the body.  A cell
        is a string or ``{"text" | "math": …, "colspan": n, "rowspan": n}``; cells covered by a span are left
        out of the later rows, as in Typst.
        """
        if label is None:
            label = str(self.first_extra_table + self.n_tables)
            self.n_tables += 1
        cells = lambda r: [_seg(c) if isinstance(c, dict) else {"text": str(c)} for c in r]  # noqa: E731
        header = [cells(r) for r in header]
        rows = [cells(r) for r in rows]
        taken: set = set()
        for ri, r in enumerate(rows):  # each body cell's column, for its alignment (spans leave cells out)
            col = 0
            for c in r:
                while (ri, col) in taken:
                    col += 1
                c["col"] = col
                span_r, span_c = int(c.get("rowspan", 1)), int(c.get("colspan", 1))
                taken.update((ri + dr, col + dc) for dr in range(span_r) for dc in range(span_c))
                col += span_c
        n = sum(int(c.get("colspan", 1)) for c in header[0]) if header else len(rows[0])
        self.blocks.append({"t": "table", "label": str(label), "caption": str(caption), "header": header,
                            "rows": rows, "widths": [float(w) for w in (widths or [1] * n)],
                            "align": list(align or ["center"] * n), "size": float(size)})
        return str(label)

    def figure(self, src: str, caption: str, width: float = 1.0) -> int:
        """A numbered figure "Рисунок n – caption" of a PDF (or PNG) file relative to the build folder."""
        self.n_figures += 1
        self.blocks.append({"t": "figure", "num": self.n_figures, "src": str(src), "caption": str(caption),
                            "width": float(width)})
        return self.n_figures

    def page(self, src: str, width_mm: float, height_mm: float) -> None:
        """A page of its own size holding one PDF at 100 % (the fotoschema sheet at true size)."""
        self.blocks.append({"t": "page", "src": str(src), "w": float(width_mm), "h": float(height_mm)})

    def pagebreak(self) -> None:
        self.blocks.append({"t": "pagebreak"})

    def outline(self) -> None:
        """The contents (содержание) here."""
        self.blocks.append({"t": "outline"})

    def as_json(self) -> str:
        return json.dumps({"title_page": self.title_page, "meta": self.meta, "blocks": self.blocks},
                          ensure_ascii=False, indent=0, sort_keys=True)


# =========================================================================== PDF (Typst)
TEMPLATE = r"""
// aerophoto's explanatory note: the content is report.json (written by aerophoto.report), nothing else.
#let data = json("report.json")
#let meta = data.meta
#let tp = data.title_page
#set document(title: meta.title, author: meta.author,
  date: datetime(year: meta.date.at(0), month: meta.date.at(1), day: meta.date.at(2)))
#set text(lang: meta.lang, font: ("Libertinus Serif", "New Computer Modern"), size: 13pt, hyphenate: true)
#show math.equation: set text(font: ("New Computer Modern Math",))
#set page(paper: "a4", margin: (left: 30mm, right: 15mm, top: 20mm, bottom: 20mm))
#set par(justify: true, leading: 0.75em, spacing: 0.75em, first-line-indent: (amount: 1.25cm, all: true))
#show heading: set text(size: 13pt, weight: "bold")
#show heading: set block(above: 1.4em, below: 1em)
#show heading: it => {
  set par(first-line-indent: 0pt, justify: false)
  set text(hyphenate: false)
  it
}

#let segs(s) = for g in s {
  if "math" in g { math.equation(block: false, eval(g.math, mode: "math")) }
  else if g.at("b", default: false) { strong(g.text) } else { g.text }
}
#let cellof(c, al) = {
  let body = if "math" in c { math.equation(block: false, eval(c.math, mode: "math")) } else { c.text }
  table.cell(colspan: c.at("colspan", default: 1), rowspan: c.at("rowspan", default: 1), align: al + horizon, body)
}
#let aligns = (left: left, right: right, center: center)

// ---------------------------------------------------------------- the title page
#page(numbering: none, margin: (left: 30mm, right: 15mm, top: 20mm, bottom: 20mm))[
  #set par(justify: false, first-line-indent: 0pt)
  #set text(hyphenate: false)
  #set align(center)
  #text(size: 12pt)[#upper(tp.ministry)]
  #v(2mm)
  #text(size: 12pt)[#tp.university_form]
  #v(1mm)
  #text(size: 13pt, weight: "bold")[#tp.university]
  #v(4mm)
  #text(size: 13pt)[#tp.department]
  #v(1fr)
  #text(size: 20pt, weight: "bold")[#upper(tp.work)]
  #v(3mm)
  #text(size: 14pt)[#tp.discipline]
  #v(3mm)
  #text(size: 14pt)[#tp.topic_label #linebreak() #text(weight: "bold")[«#tp.topic»]]
  #v(6mm)
  #text(size: 15pt, weight: "bold")[#upper(tp.note)]
  #v(1fr)
  #align(right)[
    #block(width: 72%)[
      #set align(left)
      #for row in tp.rows [
        #grid(columns: (36%, 64%), gutter: 2mm, text(weight: "bold")[#row.at(0)], row.at(1))
        #v(1.5mm)
      ]
    ]
  ]
  #v(1fr)
  #tp.place_year
]

#set page(numbering: "1", number-align: center)
#counter(page).update(2)

#for b in data.blocks {
  if b.t == "outline" {
    {
      set par(first-line-indent: 0pt)
      show outline.entry: it => it
      align(center, text(weight: "bold")[#meta.contents])
      outline(title: none, depth: 2, indent: 1.25cm)
    }
  } else if b.t == "heading" {
    if b.newpage { pagebreak(weak: true) }
    let body = if b.num != "" [#b.num #b.text] else [#b.text]
    if b.structural {
      block(sticky: true, width: 100%, align(center, heading(level: b.level, outlined: b.outline, upper(body))))
    } else {
      block(sticky: true, inset: (left: 1.25cm), heading(level: b.level, outlined: b.outline, body))
    }
  } else if b.t == "par" {
    if b.style == "missing" {
      block(fill: luma(238), inset: 7pt, width: 100%, breakable: false,
        par(first-line-indent: 0pt, text(weight: "bold")[#segs(b.segs)]))
    } else if b.style == "note" {
      par(first-line-indent: 0pt, text(size: 11pt)[#segs(b.segs)])
    } else if b.style == "bad" {
      block(stroke: (left: 1.5pt + luma(90)), inset: (left: 6pt, y: 2pt),
        par(first-line-indent: 0pt, text(size: 11pt)[#segs(b.segs)]))
    } else if b.style == "plain" {
      par(first-line-indent: 0pt)[#segs(b.segs)]
    } else {
      par[#segs(b.segs)]
    }
  } else if b.t == "list" {
    set par(first-line-indent: 0pt)
    if b.numbered { enum(indent: 1.25cm, ..b.items.map(s => [#segs(s)])) }
    else { list(indent: 1.25cm, marker: [–], ..b.items.map(s => [#segs(s)])) }
  } else if b.t == "math" {
    block(width: 100%, above: 0.9em, below: 0.9em, breakable: false, grid(columns: (3.2em, 1fr, 3.2em),
      align: (left, center, right + horizon),
      [], math.equation(block: true, numbering: none, eval(b.typst, mode: "math")),
      if b.num != "" [(#b.num)] else []))
  } else if b.t == "table" {
    {
      set par(first-line-indent: 0pt, justify: false)
      let small = b.rows.len() <= 24
      block(breakable: not small, width: 100%, above: 1em, below: 0.6em, {
      block(breakable: false, below: 0.4em, sticky: true, text[#meta.table_word #b.label – #b.caption])
      set text(size: b.size * 1pt)
      let al = b.align.map(a => aligns.at(a))
      table(
        columns: b.widths.map(w => w * 1fr),
        stroke: 0.5pt,
        inset: (x: 3pt, y: 3.2pt),
        table.header(..b.header.map(r => r.enumerate().map(((k, c)) => cellof(c, center))).flatten()),
        ..b.rows.map(r => r.map(c => cellof(c, al.at(calc.min(c.at("col", default: 0), al.len() - 1))))).flatten(),
      )
      })
    }
  } else if b.t == "figure" {
    block(breakable: false, width: 100%, above: 1em, below: 1em, {
      align(center, image(b.src, width: b.width * 100%))
      v(0.3em)
      set par(first-line-indent: 0pt, justify: false)
      align(center, text[#meta.figure_word #b.num – #b.caption])
    })
  } else if b.t == "page" {
    page(width: b.w * 1mm, height: b.h * 1mm, margin: 0mm, numbering: none, image(b.src, width: 100%, height: 100%))
  } else if b.t == "pagebreak" {
    pagebreak(weak: true)
  }
}
"""


def typst_available() -> bool:
    try:
        import typst  # noqa: F401
    except ImportError:
        return False
    return True


def compile_pdf(doc: Document, build_dir: Path, pdf_path: Path) -> Path:
    """Write ``report.json`` and ``report.typ`` into ``build_dir`` and typeset ``pdf_path`` with Typst."""
    try:
        import typst
    except ImportError as exc:  # pragma: no cover - the environment pins it
        raise RuntimeError("the PDF needs the Python package typst (see environment.txt); "
                           "the HTML page is written without it (--html-only)") from exc
    import datetime as _dt

    build_dir = Path(build_dir)
    (build_dir / "report.json").write_text(doc.as_json() + "\n", encoding="utf-8")
    src = build_dir / "report.typ"
    src.write_text(TEMPLATE.lstrip(), encoding="utf-8")
    y, m, d = doc.meta["date"]
    stamp = int(_dt.datetime(y, m, d, 12, 0, tzinfo=_dt.timezone.utc).timestamp())
    data = typst.compile(str(src), root=str(build_dir), ignore_system_fonts=True, timestamp=stamp)
    pdf_path = Path(pdf_path)
    pdf_path.write_bytes(data)
    return pdf_path


# =========================================================================== HTML
_CSS = """
body{font-family:"Libertinus Serif","Times New Roman",serif;max-width:58em;margin:2em auto;padding:0 1em;
line-height:1.45;color:#111}p{text-indent:1.25cm;text-align:justify;margin:.4em 0}p.plain,p.note,p.missing,p.bad,p.ok
{text-indent:0}.title{text-align:center;border-bottom:1px solid #999;padding-bottom:1.5em;margin-bottom:2em}
.title .big{font-size:1.7em;font-weight:bold;margin:.6em 0}.title dl{display:inline-grid;
grid-template-columns:auto auto;gap:.2em 1em;text-align:left}.title dt{font-weight:bold}
h1.structural{text-align:center;text-transform:uppercase}h1,h2,h3{font-size:1.05em}
table{border-collapse:collapse;margin:.3em 0 1.2em;font-size:.9em}td,th{border:1px solid #555;
padding:.2em .45em;vertical-align:middle}td.right{text-align:right;font-variant-numeric:tabular-nums}
td.left{text-align:left}td.center{text-align:center}caption{caption-side:top;text-align:left;padding:.3em 0}
figure{margin:1em 0;text-align:center}figure embed,figure img{width:100%;min-height:20em}figcaption{font-size:.95em}
.missing{background:#eee;font-weight:bold;padding:.5em .7em}.note{color:#333;font-size:.92em}
.bad{border-left:2px solid #555;padding-left:.5em;font-size:.92em}.math{text-align:center;margin:.8em 0}
.math .num{float:right}nav li{list-style:none}
"""


def _segs_html(segs) -> str:
    out = []
    for s in segs:
        if "math" in s:
            out.append(f"<i>{html.escape(math_text(s['math']))}</i>")
        elif s.get("b"):
            out.append(f"<b>{html.escape(s.get('text', ''))}</b>")
        else:
            out.append(html.escape(s.get("text", "")))
    return "".join(out)


def _cell_html(c: dict, tag: str, align: str = "center") -> str:
    span = ""
    if int(c.get("colspan", 1)) > 1:
        span += f' colspan="{int(c["colspan"])}"'
    if int(c.get("rowspan", 1)) > 1:
        span += f' rowspan="{int(c["rowspan"])}"'
    body = html.escape(math_text(c["math"])) if "math" in c else html.escape(c.get("text", ""))
    return f'<{tag}{span} class="{html.escape(align)}">{body}</{tag}>'


def _block_html(b: dict, prefix: str, meta: dict) -> list:
    e = html.escape
    t = b["t"]
    if t == "heading":
        lv = min(int(b["level"]), 3)
        cls = ' class="structural"' if b["structural"] else ""
        num = e(b["num"] + " ") if b["num"] else ""
        return [f'<h{lv} id="{e(b["anchor"])}"{cls}>{num}{e(b["text"])}</h{lv}>']
    if t == "par":
        cls = "" if b["style"] == "normal" else f' class="{e(b["style"])}"'
        return [f"<p{cls}>{_segs_html(b['segs'])}</p>"]
    if t == "list":
        tag = "ol" if b["numbered"] else "ul"
        return [f"<{tag}>" + "".join(f"<li>{_segs_html(s)}</li>" for s in b["items"]) + f"</{tag}>"]
    if t == "math":
        num = f'<span class="num">({e(b["num"])})</span>' if b["num"] else ""
        return [f'<p class="math plain">{num}{e(b["text"])}</p>']
    if t == "table":
        out = [f"<table><caption>{e(meta['table_word'])} {e(b['label'])} – {e(b['caption'])}</caption><thead>"]
        out += ["<tr>" + "".join(_cell_html(c, "th") for c in r) + "</tr>" for r in b["header"]]
        out.append("</thead><tbody>")
        for r in b["rows"]:
            out.append("<tr>" + "".join(_cell_html(c, "td", b["align"][min(int(c.get("col", 0)), len(b["align"]) - 1)])
                                        for c in r) + "</tr>")
        out.append("</tbody></table>")
        return out
    if t == "figure":
        src = e(prefix + b["src"])
        return [f'<figure><embed src="{src}" type="application/pdf"><figcaption>{e(meta["figure_word"])} '
                f'{int(b["num"])} – {e(b["caption"])} (<a href="{src}">PDF</a>)</figcaption></figure>']
    if t == "page":
        return [f'<p class="plain"><a href="{e(prefix + b["src"])}">{e(b["src"])}</a></p>']
    return []


def write_html(doc: Document, path: Path, *, prefix: str = "") -> Path:
    """An HTML page of the note; figures are linked as ``prefix + src`` relative to its folder."""
    e = html.escape
    tp, meta = doc.title_page, doc.meta
    out = ["<!DOCTYPE html>", f'<html lang="{e(meta["lang"])}"><head><meta charset="utf-8">',
           f"<title>{e(meta['title'])}</title><style>{_CSS}</style></head><body>",
           '<header class="title">', f"<div>{e(tp['ministry'])}</div>", f"<div>{e(tp['university_form'])}</div>",
           f"<div><b>{e(tp['university'])}</b></div>", f"<div>{e(tp['department'])}</div>",
           f'<div class="big">{e(tp["work"])}</div>', f"<div>{e(tp['discipline'])}</div>",
           f"<div>{e(tp['topic_label'])} <b>«{e(tp['topic'])}»</b></div>", f"<div><b>{e(tp['note'])}</b></div>",
           "<p class='plain'><dl>"]
    for k, val in tp["rows"]:
        out.append(f"<dt>{e(k)}</dt><dd>{e(val)}</dd>")
    out += ["</dl></p>", f"<div>{e(tp['place_year'])}</div>", "</header>",
            f"<nav><h2>{e(meta['contents'])}</h2><ul>"]
    for b in doc.blocks:
        if b["t"] == "heading" and b["level"] <= 2 and b["outline"]:
            pad = "" if b["level"] == 1 else "&emsp;"
            out.append(f'<li>{pad}<a href="#{e(b["anchor"])}">{e((b["num"] + " ") if b["num"] else "")}'
                       f'{e(b["text"])}</a></li>')
    out.append("</ul></nav>")
    for b in doc.blocks:
        out += _block_html(b, prefix, meta)
    out.append("</body></html>")
    path = Path(path)
    path.write_text("\n".join(out) + "\n", encoding="utf-8")
    return path
