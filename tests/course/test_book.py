"""The book's registry (aerophoto.book.CHAPTERS) is the one list of chapters, and the template keeps its shape."""

from __future__ import annotations

import re

import nbformat

import aerophoto
from aerophoto import book
from conftest import NOTEBOOKS, all_notebooks


def test_every_chapter_notebook_is_registered_and_every_registered_one_exists():
    on_disk = sorted(p.name for p in all_notebooks() if re.match(r"^\d\d_", p.name) and p.parent == NOTEBOOKS)
    assert on_disk == sorted(c.notebook for c in book.CHAPTERS)
    numbers = [c.number for c in book.CHAPTERS]
    assert numbers == sorted(numbers) and len(set(numbers)) == len(numbers)


def test_registered_demos_exist_in_their_notebooks_and_name_real_classes():
    import importlib

    for c in book.CHAPTERS:
        nb = nbformat.read(str(NOTEBOOKS / c.notebook), as_version=4)
        cells = {cell.get("id"): cell.source for cell in nb.cells}
        for d in c.demos:
            assert d.cell in cells, f"{c.notebook} has no cell {d.cell!r}"
            module, cls = d.cls.rsplit(".", 1)
            klass = getattr(importlib.import_module(module), cls)
            labels = [p.label for p in klass.params]
            assert all(label in labels for label, _key in d.sliders), (d.cls, labels)
            assert d.timed_slider in labels


def test_generated_tables_are_current():
    stale = book.sync_generated()
    assert not stale, f"regenerate with `python -m aerophoto.book`: {stale}"


def test_chapter_lookup_and_its_errors():
    assert book.chapter("03").notebook == "03_relief_displacement.ipynb"
    assert book.chapter("03_relief_displacement.ipynb").source == "guide §4"
    try:
        book.chapter("99")
    except ValueError as exc:
        assert "99" in str(exc)
    else:
        raise AssertionError("an unknown chapter must raise")


def test_the_package_reads_the_registry():
    assert [c.name for c in aerophoto.chapters()] == [c.name for c in book.CHAPTERS]


def test_the_template_keeps_the_chapter_shape():
    nb = nbformat.read(str(NOTEBOOKS / "_template.ipynb"), as_version=4)
    ids = [c.get("id") for c in nb.cells]
    order = ["title", "setup", "theory", "demo-name", "example-1", "task-NN-1", "task-NN-1-answer",
             "task-NN-1-check", "summary"]
    assert [i for i in ids if i in order] == order
    assert not any(c.get("outputs") for c in nb.cells if c.cell_type == "code")
    check = next(c for c in nb.cells if c.get("id") == "task-NN-1-check")
    assert 'checks.check_task("task-NN-1", v, x_m=x_m)' in check.source
