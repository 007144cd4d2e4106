"""Maintenance tools for the book's notebooks: build, find cells by marker, strip outputs.

Cells are found by their **id** (nbformat ≥ 4.5 cell ids), which the book sets
to stable, readable markers: ``setup``, ``demo-footprint``, ``task-00-1``,
``task-00-1-check``...  Scripts that edit notebooks use :func:`set_cell` and
:func:`insert_after`, which look cells up by id, so running a script twice
gives the same notebook.

Typical use from a build script::

    from aerophoto.nbtools import md, code, notebook, write
    nb = notebook([md("# Title", id="title"), code("x = 1", id="setup")])
    write(nb, "notebooks/99_example.ipynb")
"""

from __future__ import annotations

import json
from pathlib import Path

import nbformat
from nbformat.v4 import new_code_cell, new_markdown_cell, new_notebook

__all__ = [
    "md",
    "code",
    "notebook",
    "write",
    "read",
    "strip_outputs",
    "find_cell",
    "set_cell",
    "insert_after",
    "has_outputs",
    "nbgrader_answer",
    "nbgrader_tests",
]

KERNELSPEC = {"display_name": "Python 3 (ipykernel)", "language": "python", "name": "python3"}


def md(text: str, *, id: str | None = None):
    """A markdown cell with a stable id."""
    cell = new_markdown_cell(text.strip("\n"))
    if id:
        cell["id"] = id
    return cell


def code(text: str, *, id: str | None = None, hide_input: bool = False, tags=()):
    """A code cell with a stable id (``hide_input`` tags it for lecture mode)."""
    cell = new_code_cell(text.strip("\n"))
    if id:
        cell["id"] = id
    tags = list(tags)
    if hide_input:
        tags.append("hide-input")
    if tags:
        cell["metadata"]["tags"] = tags
    return cell


def nbgrader_answer(cell, grade_id: str):
    """Mark a code cell as an nbgrader answer (solution) cell; returns the cell."""
    cell["metadata"]["nbgrader"] = {
        "grade": False, "grade_id": grade_id, "locked": False,
        "schema_version": 3, "solution": True, "task": False,
    }
    return cell


def nbgrader_tests(cell, grade_id: str, points: float):
    """Mark a code cell as a locked nbgrader autograder test cell worth ``points``."""
    cell["metadata"]["nbgrader"] = {
        "grade": True, "grade_id": grade_id, "locked": True, "points": points,
        "schema_version": 3, "solution": False, "task": False,
    }
    return cell


def notebook(cells, *, title: str | None = None):
    """A new notebook with the book's kernelspec."""
    nb = new_notebook(cells=list(cells))
    nb.metadata["kernelspec"] = dict(KERNELSPEC)
    nb.metadata["language_info"] = {"name": "python"}
    if title:
        nb.metadata["title"] = title
    return nb


def strip_outputs(nb):
    """Remove outputs and execution counts from every code cell (in place); returns nb."""
    for cell in nb.cells:
        if cell.cell_type == "code":
            cell.outputs = []
            cell.execution_count = None
        cell.metadata.pop("execution", None)
    return nb


def has_outputs(nb) -> bool:
    return any(c.cell_type == "code" and (c.get("outputs") or c.get("execution_count")) for c in nb.cells)


def write(nb, path) -> Path:
    """Validate, strip outputs and write a notebook (stable JSON formatting)."""
    path = Path(path)
    strip_outputs(nb)
    nbformat.validate(nb)
    path.parent.mkdir(parents=True, exist_ok=True)
    text = json.dumps(nb, indent=1, ensure_ascii=False, sort_keys=True) + "\n"
    path.write_text(text, encoding="utf-8")
    return path


def read(path):
    return nbformat.read(str(path), as_version=4)


def find_cell(nb, cell_id: str):
    """Return ``(index, cell)`` of the cell with this id; KeyError if absent."""
    for i, c in enumerate(nb.cells):
        if c.get("id") == cell_id:
            return i, c
    raise KeyError(f"no cell with id {cell_id!r}")


def set_cell(nb, cell_id: str, source: str) -> None:
    """Replace the source of the cell with this id (idempotent)."""
    _, c = find_cell(nb, cell_id)
    c.source = source.strip("\n")


def insert_after(nb, after_id: str, cell) -> None:
    """Insert ``cell`` after the cell ``after_id`` unless a cell with its id exists (idempotent)."""
    try:
        find_cell(nb, cell["id"])
        return
    except KeyError:
        pass
    i, _ = find_cell(nb, after_id)
    nb.cells.insert(i + 1, cell)
