"""The browser tests and the lecture index know every chapter that has a live demo (no browser needed)."""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path

import nbformat

from . import harness as h
from .chapters import CHAPTERS, LECTURE_INDEX


def _demo_cells(path: Path) -> list[str]:
    nb = nbformat.read(str(path), as_version=4)
    return [c.get("id", "") for c in nb.cells if c.cell_type == "code" and str(c.get("id", "")).startswith("demo-")]


def _chapters_with_demos() -> dict[str, list[str]]:
    out = {}
    for p in sorted(h.NOTEBOOKS.glob("[0-9]*.ipynb")):  # the book's chapters (not _template)
        cells = _demo_cells(p)
        if cells:
            out[p.name] = cells
    return out


def test_every_demo_cell_is_exercised_in_the_browser():
    found = _chapters_with_demos()
    listed = {c.notebook: [d.cell for d in c.demos] for c in CHAPTERS}
    missing = {nb: cells for nb, cells in found.items() if sorted(cells) != sorted(listed.get(nb, []))}
    assert not missing, (f"demo cells not (or not exactly) listed in tests/browser/chapters.py: {missing}; "
                         f"listed there: {listed}")
    gone = [nb for nb in listed if nb not in found]
    assert not gone, f"tests/browser/chapters.py lists chapters without demo cells: {gone}"


def test_each_listed_demo_names_the_class_its_cell_builds():
    for chapter in CHAPTERS:
        nb = nbformat.read(str(h.NOTEBOOKS / chapter.notebook), as_version=4)
        cells = {c.get("id"): c.source for c in nb.cells}
        for demo in chapter.demos:
            cls = demo.cls.rsplit(".", 1)[-1]
            assert cls and re.search(rf"\b{cls}\b", cells[demo.cell]), (
                f"{chapter.notebook} [{demo.cell}] does not build {demo.cls!r}; fix tests/browser/chapters.py")
            assert demo.timed_slider in [label for label, _key in demo.sliders]


def test_lecture_index_links_every_chapter_with_a_demo():
    index = h.NOTEBOOKS / LECTURE_INDEX
    nb = nbformat.read(str(index), as_version=4)
    text = "\n".join(c.source for c in nb.cells if c.cell_type == "markdown")
    missing = [name for name in _chapters_with_demos() if f"]({name})" not in text]
    assert not missing, f"{LECTURE_INDEX} has no link to {missing}"


def test_voila_config_denies_the_extensions_it_cannot_load_and_culls_kernels():
    cfg = json.loads((h.ROOT / "voila.json").read_text(encoding="utf-8"))
    installed = set()
    for base in (Path(sys.prefix) / "share" / "jupyter" / "labextensions",):
        for pkg in base.glob("**/package.json"):
            if "node_modules" in pkg.parts or "static" in pkg.parts:
                continue
            installed.add(json.loads(pkg.read_text(encoding="utf-8"))["name"])
    deny = set(cfg["VoilaConfiguration"]["extension_denylist"])
    # Lab-only extensions that log load errors in a Voilà page when present
    for name in ("@jupyter/nbgrader", "@jupyter-notebook/lab-extension"):
        if name in installed:
            assert name in deny, f"voila.json must deny-list {name}"
    # the widgets and live figures must stay
    assert not deny & {"@jupyter-widgets/jupyterlab-manager", "jupyter-matplotlib"}
    km = cfg["MappingKernelManager"]
    assert km["cull_idle_timeout"] > 0 and km["cull_interval"] > 0
    assert km.get("cull_connected", False) is False, "an open lecture tab must keep its kernel"
