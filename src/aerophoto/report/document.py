"""The report as data, and its two renderings: PDF through Typst and a self-contained HTML page.

:class:`Document` is a list of blocks (headings, paragraphs, notes, formulas, numbered tables and
figures) plus the title page.  It is written as ``report.json`` into the build folder; the Typst source
(:data:`TEMPLATE`) reads that file with Typst's own ``json()`` — so no text of the student (a name, a
value) is ever spliced into markup, and nothing needs escaping.  Formulas are the package's own strings
(``eval(…, mode: "math")`` of :mod:`aerophoto.report.sections`' constants), never the student's.

Typst (the PyPI package ``typst``, a self-contained binding with fonts that cover Cyrillic: Libertinus
Serif, New Computer Modern) typesets offline, in well under a second, with real mathematics; it was chosen
over WeasyPrint (needs Pango and has no mathematics) and nbconvert's LaTeX path (needs a TeX installation).
System fonts are ignored, so the PDF is the same on every machine.
"""

from __future__ import annotations

import html
import json
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["Document", "TEMPLATE", "compile_pdf", "write_html", "typst_available"]

_FONTS = ("Libertinus Serif", "New Computer Modern")


@dataclass
class Document:
    """The report's content: ``title_page`` (dict of strings), ``meta`` and ``blocks`` (see the module notes)."""

    title_page: dict
    meta: dict
    blocks: list = field(default_factory=list)
    n_tables: int = 0
    n_figures: int = 0

    # ---- building
    def heading(self, level: int, ru: str, en: str = "", num: str = "", anchor: str = "") -> None:
        self.blocks.append({"t": "heading", "level": int(level), "ru": ru, "en": en, "num": num,
                            "anchor": anchor or f"s{len(self.blocks)}"})

    def par(self, text: str, style: str = "normal") -> None:
        """A paragraph; ``style`` one of normal, note, missing, ok, bad."""
        self.blocks.append({"t": "par", "text": str(text), "style": style})

    def math(self, typst: str, text: str) -> None:
        self.blocks.append({"t": "math", "typst": typst, "text": text})

    def table(self, caption: str, header, rows, *, align=None, widths=None) -> int:
        """A numbered table ("Таблица n — caption"); cells are strings.  Returns its number."""
        self.n_tables += 1
        header = [str(h) for h in header]
        rows = [[str(c) for c in r] for r in rows]
        n = len(header)
        if any(len(r) != n for r in rows):
            raise ValueError(f"rows: every row needs {n} cells like the header")
        if widths is None:
            longest = [max([len(header[k])] + [len(r[k]) for r in rows]) for k in range(n)]
            widths = [min(max(w, 4), 40) for w in longest]
        self.blocks.append({"t": "table", "num": self.n_tables,
                            "caption": f"Таблица {self.n_tables} — {caption}",
                            "header": header, "rows": rows,
                            "align": list(align) if align else ["left"] * n,
                            "widths": [float(w) for w in widths]})
        return self.n_tables

    def figure(self, src: str, caption: str, width: float = 1.0) -> int:
        """A numbered figure ("Рисунок n — caption") of an image file relative to the build folder."""
        self.n_figures += 1
        self.blocks.append({"t": "figure", "num": self.n_figures, "src": str(src),
                            "caption": f"Рисунок {self.n_figures} — {caption}", "width": float(width)})
        return self.n_figures

    def pagebreak(self) -> None:
        self.blocks.append({"t": "pagebreak"})

    def as_json(self) -> str:
        return json.dumps({"title_page": self.title_page, "meta": self.meta, "blocks": self.blocks},
                          ensure_ascii=False, indent=1, sort_keys=True)


# =========================================================================== PDF (Typst)
TEMPLATE = r"""
// aerophoto's course report: the content is report.json (written by aerophoto.report), nothing else.
#let data = json("report.json")
#let meta = data.meta
#let tp = data.title_page
#set document(title: meta.title, author: meta.author,
  date: datetime(year: meta.date.at(0), month: meta.date.at(1), day: meta.date.at(2)))
#set text(lang: "ru", font: ("Libertinus Serif", "New Computer Modern"), size: 12pt)
#set page(paper: "a4", margin: (left: 30mm, right: 15mm, top: 20mm, bottom: 22mm))
#set par(justify: true, leading: 0.62em)
#show heading: set block(above: 1.3em, below: 0.75em)
#show heading.where(level: 1): set text(size: 15pt)
#show heading.where(level: 2): set text(size: 13pt)
#show heading.where(level: 3): set text(size: 12pt)

#page(numbering: none)[
  #set align(center)
  #set par(justify: false)
  #text(size: 13pt)[#tp.ministry]
  #v(3mm)
  #text(size: 13pt, weight: "bold")[#tp.university]
  #v(2mm)
  #text(size: 12pt)[#tp.department]
  #v(1fr)
  #text(size: 22pt, weight: "bold")[#tp.work_ru]
  #v(2mm)
  #text(size: 14pt)[#tp.discipline_ru]
  #v(4mm)
  #text(size: 16pt, weight: "bold")[#tp.note_ru]
  #v(2mm)
  #text(size: 12pt, style: "italic")[#tp.work_en]
  #v(1fr)
  #set align(left)
  #pad(left: 45%)[
    #set par(justify: false)
    #for row in tp.rows [
      #text(weight: "bold")[#row.at(0):] #row.at(1) \
    ]
  ]
  #v(1fr)
  #set align(center)
  #tp.place \
  #text(size: 10pt, fill: luma(90))[#tp.generated]
]

#set page(numbering: "1")
#counter(page).update(2)
#outline(title: [Содержание (Contents)], depth: 2, indent: auto)
#pagebreak()

#for b in data.blocks {
  if b.t == "heading" {
    let en = if b.en != "" [ #text(weight: "regular", style: "italic", size: 0.85em)[(#b.en)]]
    heading(level: b.level)[#if b.num != "" [#b.num ]#b.ru#en]
  } else if b.t == "par" {
    if b.style == "missing" {
      block(fill: luma(238), inset: 7pt, radius: 2pt, width: 100%, breakable: false,
        text(fill: rgb("#a00000"), weight: "bold", b.text))
    } else if b.style == "note" {
      block(text(size: 10pt, fill: luma(70), b.text))
    } else if b.style == "bad" {
      block(text(fill: rgb("#a00000"), b.text))
    } else if b.style == "ok" {
      block(text(fill: rgb("#006040"), b.text))
    } else {
      par(b.text)
    }
  } else if b.t == "math" {
    math.equation(block: true, eval(b.typst, mode: "math"))
  } else if b.t == "table" {
    {
      set text(size: 9.5pt)
      set par(justify: false)
      figure(
        kind: table, supplement: none, numbering: none, gap: 4pt,
        caption: figure.caption(position: top, align(left, b.caption)),
        table(
          columns: b.widths.map(w => w * 1fr),
          align: (x, y) => if b.align.at(x) == "right" { right } else { left },
          stroke: 0.4pt,
          inset: 3.5pt,
          table.header(..b.header.map(h => strong(h))),
          ..b.rows.flatten(),
        ),
      )
    }
  } else if b.t == "figure" {
    figure(image(b.src, width: b.width * 100%), supplement: none, numbering: none,
      caption: figure.caption(text(size: 10pt, b.caption)))
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
        raise RuntimeError("the PDF needs the Python package typst (pip install 'aerophoto[report]' or "
                           "typst, see environment.txt); the HTML report is written without it") from exc
    build_dir = Path(build_dir)
    (build_dir / "report.json").write_text(doc.as_json() + "\n", encoding="utf-8")
    src = build_dir / "report.typ"
    src.write_text(TEMPLATE.lstrip(), encoding="utf-8")
    y, m, d = doc.meta["date"]
    import datetime as _dt

    stamp = int(_dt.datetime(y, m, d, 12, 0, tzinfo=_dt.timezone.utc).timestamp())
    data = typst.compile(str(src), root=str(build_dir), ignore_system_fonts=True, timestamp=stamp)
    pdf_path = Path(pdf_path)
    pdf_path.write_bytes(data)
    return pdf_path


# =========================================================================== HTML
_CSS = """
body{font-family:"Libertinus Serif","Times New Roman",serif;max-width:60em;margin:2em auto;padding:0 1em;
line-height:1.45;color:#111}
.title{text-align:center;border-bottom:1px solid #999;padding-bottom:1.5em;margin-bottom:2em}
.title .big{font-size:1.8em;font-weight:bold;margin:.6em 0}.title dl{display:inline-grid;
grid-template-columns:auto auto;gap:.2em 1em;text-align:left}.title dt{font-weight:bold}
h1 .en,h2 .en,h3 .en{font-weight:normal;font-style:italic;font-size:.85em}
table{border-collapse:collapse;margin:.3em 0 1.2em;font-size:.92em}td,th{border:1px solid #888;
padding:.2em .45em;vertical-align:top}td.right{text-align:right;font-variant-numeric:tabular-nums}
caption{caption-side:top;text-align:left;padding:.3em 0}figure{margin:1em 0;text-align:center}
figure img{max-width:100%}figcaption{font-size:.92em}.missing{background:#eee;color:#a00000;
font-weight:bold;padding:.5em .7em}.note{color:#444;font-size:.92em}.bad{color:#a00000}.ok{color:#006040}
.math{text-align:center;font-style:italic;margin:.8em 0}nav li{list-style:none}
"""


def write_html(doc: Document, path: Path, *, prefix: str = "") -> Path:
    """An HTML page of the report; figures are linked as ``prefix + src`` relative to its folder."""
    e = html.escape
    tp = doc.title_page
    out = ["<!DOCTYPE html>", '<html lang="ru"><head><meta charset="utf-8">',
           f"<title>{e(doc.meta['title'])}</title><style>{_CSS}</style></head><body>",
           '<header class="title">', f"<div>{e(tp['ministry'])}</div>", f"<div><b>{e(tp['university'])}</b></div>",
           f"<div>{e(tp['department'])}</div>", f'<div class="big">{e(tp["work_ru"])}</div>',
           f"<div>{e(tp['discipline_ru'])}</div>", f"<div><b>{e(tp['note_ru'])}</b></div>",
           f"<div><i>{e(tp['work_en'])}</i></div>", "<p><dl>"]
    for k, val in tp["rows"]:
        out.append(f"<dt>{e(k)}</dt><dd>{e(val)}</dd>")
    out += ["</dl></p>", f"<div>{e(tp['place'])}</div>", f'<div class="note">{e(tp["generated"])}</div>',
            "</header>", "<nav><h2>Содержание (Contents)</h2><ul>"]
    for b in doc.blocks:
        if b["t"] == "heading" and b["level"] <= 2:
            pad = "" if b["level"] == 1 else "&emsp;"
            out.append(f'<li>{pad}<a href="#{e(b["anchor"])}">{e((b["num"] + " ") if b["num"] else "")}'
                       f'{e(b["ru"])}</a></li>')
    out.append("</ul></nav>")
    for b in doc.blocks:
        t = b["t"]
        if t == "heading":
            lv = min(int(b["level"]), 3)
            num = e(b["num"] + " ") if b["num"] else ""
            en = f' <span class="en">({e(b["en"])})</span>' if b["en"] else ""
            out.append(f'<h{lv} id="{e(b["anchor"])}">{num}{e(b["ru"])}{en}</h{lv}>')
        elif t == "par":
            cls = "" if b["style"] == "normal" else f' class="{e(b["style"])}"'
            out.append(f"<p{cls}>{e(b['text'])}</p>")
        elif t == "math":
            out.append(f'<p class="math">{e(b["text"])}</p>')
        elif t == "table":
            out.append(f"<table><caption>{e(b['caption'])}</caption><thead><tr>"
                       + "".join(f"<th>{e(h)}</th>" for h in b["header"]) + "</tr></thead><tbody>")
            for r in b["rows"]:
                out.append("<tr>" + "".join(
                    f'<td class="{e(a)}">{e(c)}</td>' for c, a in zip(r, b["align"])) + "</tr>")
            out.append("</tbody></table>")
        elif t == "figure":
            out.append(f'<figure><img src="{e(prefix + b["src"])}" alt="{e(b["caption"])}" '
                       f'style="width:{b["width"] * 100:.0f}%"><figcaption>{e(b["caption"])}</figcaption></figure>')
    out.append("</body></html>")
    path = Path(path)
    path.write_text("\n".join(out) + "\n", encoding="utf-8")
    return path
