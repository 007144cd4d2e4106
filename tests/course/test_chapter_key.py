"""One chapter key: a maintainer finds chapter NN's guide tables, tasks, lab and demos from NN alone.

The registry (aerophoto.book.CHAPTERS) maps chapter ↔ guide section ↔ article in fields; the modules follow the
rule ``guide/chNN.py``, ``tasks/chNN.py`` (``labs/chNN.py``), and the lazily loaded lists of modules are either
derived from that rule or kept once and checked here against the files on disk, so nothing drifts.
"""

from __future__ import annotations

import ast
import importlib
import re
import subprocess
import sys
from pathlib import Path

import nbformat
import pytest

import aerophoto
from aerophoto import book, demos, guide, tasks
from conftest import NOTEBOOKS

PKG = Path(aerophoto.__file__).resolve().parent

# the sources as the seeds number them (/work/shared/seeds/README.md): the guide's §2…§14 are chapters 01…13,
# the four articles chapters 14…17 in the order the course reads them
SOURCES = {"00": "guide §1", "01": "guide §2", "02": "guide §3", "03": "guide §4", "04": "guide §5",
           "05": "guide §6", "06": "guide §7", "07": "guide §8", "08": "guide §9", "09": "guide §10",
           "10": "guide §11", "11": "guide §12", "12": "guide §13", "13": "guide §14", "14": "article 001",
           "15": "article 002", "16": "article 000", "17": "article 003"}


def test_the_registry_maps_chapter_to_section_or_article_in_fields():
    assert {c.number: c.source for c in book.CHAPTERS} == SOURCES
    for c in book.CHAPTERS:
        assert (c.section is None) != (c.article is None), c.number
        if c.section is not None:
            assert c.source == f"guide §{c.section}" and int(c.number) == c.section - 1
        else:
            assert re.fullmatch(r"\d{3}", c.article)
    with pytest.raises(ValueError, match="exactly one"):
        book.Chapter("99", "x", "x", "x", section=3, article="001")
    with pytest.raises(ValueError, match="exactly one"):
        book.Chapter("99", "x", "x", "x")


def test_every_chapter_has_its_guide_module_named_by_its_number():
    on_disk = {p.stem for p in (PKG / "guide").glob("ch*.py")}
    assert set(guide.CHAPTER_MODULES) == on_disk
    for c in book.CHAPTERS:
        if not c.tables:
            assert c.guide_module is None and f"ch{c.number}" not in on_disk, c.number
            continue
        assert c.guide_module == f"aerophoto.guide.ch{c.number}"
        mod = importlib.import_module(c.guide_module)
        assert getattr(guide, f"ch{c.number}") is mod
        # the module's docstring keeps the section or article it transcribes
        first = mod.__doc__.splitlines()[0]
        assert first.startswith(f"Chapter {c.number} · {c.source}"), (c.number, first)
    # and no guide module without a chapter
    assert on_disk == {f"ch{c.number}" for c in book.CHAPTERS if c.tables}
    assert not list((PKG / "guide").glob("s[0-9]*.py")) and not list((PKG / "guide").glob("a[0-9]*.py"))


def test_every_chapter_has_its_tasks_module_named_by_its_number():
    assert tasks.CHAPTER_MODULES == {c.number: f"ch{c.number}" for c in book.CHAPTERS}
    for c in book.CHAPTERS:
        assert c.tasks_module == f"aerophoto.tasks.ch{c.number}"
        mod = importlib.import_module(c.tasks_module)
        assert tasks.chapter_tasks(c.number) == tuple(mod.TASKS)
        assert all(t.id.startswith(f"task-{c.number}-") for t in mod.TASKS), c.number
    # the lab world follows the same rule (the module may not exist yet)
    from aerophoto import labs

    have = {c.number for c in book.CHAPTERS if c.lab_module}
    assert [c.lab_module for c in book.CHAPTERS if c.lab_module] == [f"aerophoto.labs.ch{n}" for n in sorted(have)]
    # every chapter lab module on disk belongs to a chapter of the registry, and the chapters without one are known
    assert {m[2:] for m in labs.chapter_modules()} == have
    assert {c.number for c in book.CHAPTERS} - have == {"00", "01", "12", "14", "17"}


def _demo_imports(notebook: Path) -> set[str]:
    """The aerophoto.demos modules a notebook's code cells import (``from aerophoto.demos.x import …``,
    ``from aerophoto.demos import x as y``)."""
    nb = nbformat.read(str(notebook), as_version=4)
    out = set()
    for cell in nb.cells:
        if cell.cell_type != "code":
            continue
        for node in ast.walk(ast.parse(cell.source)):
            if isinstance(node, ast.ImportFrom) and node.module:
                if node.module.startswith("aerophoto.demos."):
                    out.add(node.module)
                elif node.module == "aerophoto.demos":
                    out.update(f"aerophoto.demos.{a.name}" for a in node.names)
            elif isinstance(node, ast.Import):
                out.update(a.name for a in node.names if a.name.startswith("aerophoto.demos."))
    return out


@pytest.mark.parametrize("c", book.CHAPTERS, ids=lambda c: c.number)
def test_the_registry_names_the_demo_modules_each_notebook_imports(c):
    assert set(c.demo_modules) == _demo_imports(NOTEBOOKS / c.notebook)
    for name in c.demo_modules:
        importlib.import_module(name)


def test_chapter_lookup_by_number_and_the_command_line():
    c = book.chapter("09")
    assert (c.guide_module, c.tasks_module, c.lab_module, c.demo_modules, c.source) == (
        "aerophoto.guide.ch09", "aerophoto.tasks.ch09", "aerophoto.labs.ch09",
        ("aerophoto.demos.plan_correction",), "guide §10")
    assert book.chapter(9) is c and book.chapter("9") is c and book.chapter("09_plan_correction.ipynb") is c
    assert book.chapter("06").demo_modules == book.chapter("12").demo_modules == ("aerophoto.demos.reduction",)
    out = subprocess.run([sys.executable, "-m", "aerophoto.book", "16"], capture_output=True, text=True,
                         check=True).stdout
    for text in ("article 000", "aerophoto.guide.ch16", "aerophoto.tasks.ch16", "aerophoto.labs.ch16",
                 "aerophoto.demos.dem_contours", "notebooks/16_dem_contours.ipynb"):
        assert text in out, (text, out)
    with pytest.raises(ValueError, match="no chapter"):
        book.chapter("18")


def _public_children(folder: Path) -> set[str]:
    """Public modules and subpackages in ``folder`` (no ``_private``, no data folder)."""
    mods = {p.stem for p in folder.glob("*.py") if not p.stem.startswith("_")}
    pkgs = {p.name for p in folder.iterdir() if p.is_dir() and (p / "__init__.py").exists() and not p.name.startswith("_")}
    return mods | pkgs


def test_the_package_lists_every_module_on_disk_once():
    listed = list(aerophoto._SUBMODULES)
    assert len(listed) == len(set(listed))
    assert set(listed) == _public_children(PKG) - {"course_data"}, "aerophoto/__init__.py _SUBMODULES is stale"


def test_the_demos_list_every_demo_module_on_disk_once():
    listed = list(demos._SUBMODULES)
    assert len(listed) == len(set(listed))
    assert set(listed) == _public_children(PKG / "demos"), "aerophoto/demos/__init__.py _SUBMODULES is stale"
    used = {m.rsplit(".", 1)[1] for c in book.CHAPTERS for m in c.demo_modules}
    assert used <= set(listed)


def test_every_listed_module_has_a_layer():
    from .test_layers import LAYER_OF

    assert set(aerophoto._SUBMODULES) <= set(LAYER_OF)
