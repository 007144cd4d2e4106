"""The chapters' prose in Russian: one translation file per notebook, checked against the English it translates.

The notebooks are written in English (the Russian term beside each key term).  Their Russian text lives beside
them, one Markdown file per chapter, ``notebooks/ru/NN_slug.md``, a block per Markdown cell of the English
notebook::

    <!-- cell: theory · en: 3f2a1c9e0b7d -->
    ## Смещение точек за рельеф
    …

``cell`` is the cell's id in the English notebook (the build scripts give every cell a stable, meaningful id), and
``en`` the first 12 hex digits of the SHA-256 of the English cell's source (:func:`cell_key`): when the English
text changes, its translation is *stale* and :func:`status` says so.  A block whose text still starts with
:data:`TODO` is not translated yet.  Code cells are not translated (the code is the same in both books).

:func:`russian_notebook` makes the Russian notebook from the English one (Markdown cells replaced, code cells
kept, the setup cell asked for Russian with ``lang="ru"``); :func:`skeleton` writes a chapter's file with a block
for every cell (keeping every translation that still fits, the previous text of a changed cell marked for
updating); ``python -m aerophoto.i18n.prose status`` lists what is missing or stale.

Reading and writing happen only when these functions are called; importing reads nothing.
"""

from __future__ import annotations

import copy
import hashlib
import json
import re
from dataclasses import dataclass, field
from pathlib import Path

__all__ = ["TODO", "UPDATE", "cell_key", "Block", "read_translations", "write_translations", "ChapterStatus",
           "status", "skeleton", "russian_notebook", "translation_path", "markdown_cells", "sync_block", "sync_file"]

#: the first line of a block not translated yet (the English text follows it)
TODO = "<!-- TODO translate -->"
#: the first line of a block whose English changed (the previous translation follows it)
UPDATE = "<!-- TODO update: the English text changed -->"

_HEAD = re.compile(r"^<!-- cell: (?P<cell>[^\s]+) · en: (?P<key>[0-9a-f]{12}) -->[ \t]*$")


def cell_key(source) -> str:
    """The first 12 hex digits of the SHA-256 of a cell's source (a string, or the notebook's list of lines)."""
    text = "".join(source) if isinstance(source, list) else str(source)
    return hashlib.sha256(text.strip().encode("utf-8")).hexdigest()[:12]


@dataclass(frozen=True)
class Block:
    """One translated cell: the English cell's id and key (:func:`cell_key`), and the Russian text."""

    cell: str
    key: str
    text: str

    @property
    def todo(self) -> bool:
        """Not translated yet, or not brought up to date with a changed English cell."""
        first = self.text.lstrip().splitlines()[:1]
        return not first or first[0].strip() in (TODO, UPDATE)


def read_translations(path) -> list[Block]:
    """The blocks of a translation file, in order (an empty list when the file does not exist)."""
    p = Path(path)
    if not p.exists():
        return []
    blocks: list[Block] = []
    cell = key = None
    lines: list[str] = []
    for line in p.read_text(encoding="utf-8").splitlines():
        m = _HEAD.match(line)
        if m:
            if cell is not None:
                blocks.append(Block(cell, key, "\n".join(lines).strip("\n")))
            cell, key, lines = m["cell"], m["key"], []
        elif cell is not None:
            lines.append(line)
        elif line.strip():
            raise ValueError(f"{p}: text before the first '<!-- cell: … · en: … -->' line: {line[:60]!r}")
    if cell is not None:
        blocks.append(Block(cell, key, "\n".join(lines).strip("\n")))
    return blocks


def write_translations(path, blocks) -> None:
    """Write ``blocks`` to a translation file (UTF-8, one blank line between blocks)."""
    out = []
    for b in blocks:
        out.append(f"<!-- cell: {b.cell} · en: {b.key} -->\n{b.text.strip(chr(10))}\n")
    Path(path).parent.mkdir(parents=True, exist_ok=True)
    Path(path).write_text("\n".join(out), encoding="utf-8")


def sync_block(path, cell: str, english: str, russian: str, *, write: bool = False) -> bool:
    """Whether block ``cell`` of the translation file ``path`` differs from ``russian`` keyed to ``english`` (a
    generated cell's Russian, :func:`aerophoto.book.sync_generated`); with ``write``, put it there (in place, or last
    when missing), the other blocks kept."""
    blocks = read_translations(path)
    want = Block(cell, cell_key(english), russian)
    if want in blocks:
        return False
    if write:
        found = any(b.cell == cell for b in blocks)
        write_translations(path, [want if b.cell == cell else b for b in blocks] + ([] if found else [want]))
    return True


def sync_file(path, blocks, *, write: bool = False) -> bool:
    """Whether the translation file ``path`` holds other blocks than ``blocks`` (a generated page's whole Russian
    text); with ``write``, write them."""
    blocks = list(blocks)
    if read_translations(path) == blocks:
        return False
    if write:
        write_translations(path, blocks)
    return True


def markdown_cells(nb: dict) -> list[tuple[str, str]]:
    """(cell id, source) of every Markdown cell of a notebook (nbformat JSON as a dict), in order."""
    out = []
    for i, c in enumerate(nb.get("cells", [])):
        if c.get("cell_type") != "markdown":
            continue
        src = "".join(c.get("source", [])) if isinstance(c.get("source"), list) else str(c.get("source", ""))
        out.append((str(c.get("id") or f"cell-{i}"), src))
    return out


def translation_path(notebook) -> Path:
    """Where the Russian text of ``notebooks/NN_slug.ipynb`` lives: ``notebooks/ru/NN_slug.md``."""
    p = Path(notebook)
    return p.parent / "ru" / (p.stem + ".md")


@dataclass
class ChapterStatus:
    """How far a chapter's translation is: cells in all, and the ids of those missing, not done or stale."""

    notebook: str
    cells: int = 0
    missing: list = field(default_factory=list)
    todo: list = field(default_factory=list)
    stale: list = field(default_factory=list)

    @property
    def complete(self) -> bool:
        return not (self.missing or self.todo or self.stale)

    def line(self) -> str:
        done = self.cells - len(self.missing) - len(self.todo) - len(self.stale)
        bits = [f"{done}/{self.cells} cells"]
        for name in ("missing", "todo", "stale"):
            ids = getattr(self, name)
            if ids:
                bits.append(f"{name}: {', '.join(ids[:6])}{' …' if len(ids) > 6 else ''}")
        return f"{self.notebook}: " + "; ".join(bits)


def status(notebook, translations=None) -> ChapterStatus:
    """Compare the English notebook with its translation file (default :func:`translation_path`)."""
    nb = json.loads(Path(notebook).read_text(encoding="utf-8"))
    blocks = {b.cell: b for b in read_translations(translations or translation_path(notebook))}
    st = ChapterStatus(Path(notebook).name)
    for cell, src in markdown_cells(nb):
        st.cells += 1
        b = blocks.get(cell)
        if b is None:
            st.missing.append(cell)
        elif b.todo:
            st.todo.append(cell)
        elif b.key != cell_key(src):
            st.stale.append(cell)
    return st


def skeleton(notebook, translations=None) -> ChapterStatus:
    """(Re)write a chapter's translation file with a block for every Markdown cell, in the notebook's order.

    A translation whose English is unchanged is kept as it is; one whose English changed is kept under an
    :data:`UPDATE` line (the translator brings it up to date and removes the line); a new cell gets its English
    text under a :data:`TODO` line.  Blocks of cells no longer in the notebook are dropped.  Returns the status
    after writing.
    """
    path = Path(translations or translation_path(notebook))
    nb = json.loads(Path(notebook).read_text(encoding="utf-8"))
    old = {b.cell: b for b in read_translations(path)}
    blocks = []
    for cell, src in markdown_cells(nb):
        key = cell_key(src)
        b = old.get(cell)
        if b is not None and (b.key == key or b.todo):
            text = b.text if b.key == key else f"{TODO}\n{src}"
            blocks.append(Block(cell, key, text))
        elif b is not None:
            blocks.append(Block(cell, key, f"{UPDATE}\n{b.text}\n\n<!-- the English now reads:\n"
                                           f"{src.replace('-->', '--&gt;')}\n-->"))
        else:
            blocks.append(Block(cell, key, f"{TODO}\n{src}"))
    write_translations(path, blocks)
    return status(notebook, path)


_SETUP = re.compile(r"aerophoto\.setup\((?P<args>[^)\n]*)\)")


def russian_notebook(nb: dict, blocks) -> tuple[dict, list]:
    """The Russian notebook: ``nb`` (nbformat JSON as a dict, not changed) with its Markdown cells replaced by the
    translations in ``blocks`` and its ``aerophoto.setup(...)`` call given ``lang="ru"``.

    Returns (notebook, ids of the cells left in English because no up-to-date translation exists).
    """
    by_cell = {b.cell: b for b in blocks}
    out = copy.deepcopy(nb)
    untranslated = []
    for i, c in enumerate(out.get("cells", [])):
        cid = str(c.get("id") or f"cell-{i}")
        if c.get("cell_type") == "markdown":
            src = "".join(c.get("source", [])) if isinstance(c.get("source"), list) else str(c.get("source", ""))
            b = by_cell.get(cid)
            if b is None or b.todo or b.key != cell_key(src):
                untranslated.append(cid)
                continue
            c["source"] = b.text
        elif c.get("cell_type") == "code":
            src = "".join(c.get("source", [])) if isinstance(c.get("source"), list) else str(c.get("source", ""))

            def with_ru(m):
                args = m["args"].strip()
                if "lang=" in args:
                    return m.group(0)
                return f"aerophoto.setup({args + ', ' if args else ''}lang=\"ru\")"

            new = _SETUP.sub(with_ru, src)
            if new != src:
                c["source"] = new
    out.setdefault("metadata", {}).setdefault("aerophoto", {})["lang"] = "ru"
    return out, untranslated


def _main(argv=None) -> int:
    import argparse

    ap = argparse.ArgumentParser(prog="python -m aerophoto.i18n.prose",
                                 description="The chapters' Russian text: what is missing or stale, and skeletons.")
    ap.add_argument("command", choices=["status", "skeleton"])
    ap.add_argument("chapters", nargs="*", help="chapter numbers (00 … 17); default: every chapter")
    ap.add_argument("--notebooks", default="notebooks", help="the folder of the English notebooks")
    args = ap.parse_args(argv)
    folder = Path(args.notebooks)
    books = sorted(p for p in folder.glob("[0-9][0-9]_*.ipynb"))
    if args.chapters:
        want = {f"{int(c):02d}" for c in args.chapters}
        books = [p for p in books if p.name[:2] in want]
    incomplete = 0
    for p in books:
        st = skeleton(p) if args.command == "skeleton" else status(p)
        incomplete += not st.complete
        print(st.line())
    return 1 if incomplete and args.command == "status" else 0


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(_main())
