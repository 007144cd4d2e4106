"""Tools are tools (issue 27): every package name a task's text or data cells tell the student to use is one of
its ``Task.tools``, so an honest student who follows the text is never flagged ``uses_package_answers``.

The text of task ``task-NN-k`` is its markdown cell and its data cells (``task-NN-k-…``, not the answer and check
cells, nor the cell that shows the truth after the check) in the book's notebook; names are resolved with the
notebook's own imports, as the grader's scan does.
"""

from __future__ import annotations

import ast
import json
import re

import pytest

from aerophoto import tasks
from aerophoto.course import flags
from conftest import NOTEBOOKS

CODE_SPAN = re.compile(r"```(?:python)?\n(.*?)```|`([^`]+)`", re.S)
DOTTED = re.compile(r"(?<![\w.])([A-Za-z_]\w*(?:\.[A-Za-z_]\w*)+)")


AFTER = ("-answer", "-check", "-truth")
"""Cells that are not the task's text: the student's answer, the locked check, and the book's own cell that shows
the site's truth only once the check has passed (07.2's ``task-07-2-truth``: it builds the lab with
``labs.ch07.stereo_lab`` — the release's code, which the grader knows and never flags — and tells the student to
use nothing)."""


def _notebook(chapter: str) -> dict:
    path = next(p for p in sorted(NOTEBOOKS.glob(f"{chapter}_*.ipynb")))
    return json.loads(path.read_text(encoding="utf-8"))


def _aliases(nb) -> dict:
    out = {}
    for c in nb["cells"]:
        if c["cell_type"] == "code":
            tree, _ = flags.parse_code("".join(c["source"]))
            if tree is not None:
                out.update(flags._aliases(tree))  # noqa: SLF001 - the scan's own reading of imports
    return out


def _text(nb, task_id: str) -> list[str]:
    """The snippets of code the task's text and data cells hold."""
    out = []
    for c in nb["cells"]:
        cid = c.get("id", "")
        src = "".join(c["source"])
        if cid == task_id and c["cell_type"] == "markdown":
            out += [a or b for a, b in CODE_SPAN.findall(src)]
        elif cid.startswith(task_id + "-") and not cid.endswith(AFTER) and c["cell_type"] == "code":
            out.append(src)
    return out


def named(task_id: str) -> set[str]:
    """The aerophoto names task ``task_id``'s text names, resolved (``projective.locate`` → its dotted origin)."""
    t = tasks.get(task_id)
    nb = _notebook(t.chapter)
    aliases = _aliases(nb)
    out = set()
    for snippet in _text(nb, task_id):
        for name in DOTTED.findall(snippet):
            head, _, rest = name.partition(".")
            origin = aliases.get(head, head)
            full = f"{origin}.{rest}" if rest else origin
            if full.startswith("aerophoto."):
                out.add(full)
    return out


@pytest.mark.parametrize("task_id", [t.id for t in tasks.all_tasks()])
def test_every_package_name_in_a_tasks_text_is_a_tool(task_id):
    flagged = sorted(n for n in named(task_id) if flags.is_package_answer(n))
    assert not flagged, f"{task_id}: its text names {flagged}, which the grader flags; add them to Task.tools"


@pytest.mark.parametrize("task_id", [t.id for t in tasks.all_tasks() if t.tools])
def test_every_tool_is_named_in_its_tasks_text(task_id):
    text = named(task_id)
    stale = [tool for tool in tasks.get(task_id).tools if not any(n == tool or n.startswith(tool + ".") or
                                                                   tool.startswith(n + ".") for n in text)]
    assert not stale, f"{task_id}: tools its text never names: {stale}"


@pytest.mark.parametrize("task_id", [t.id for t in tasks.all_tasks()])
def test_an_honest_student_following_the_text_gets_no_flag(task_id):
    """An answer cell that calls every package name the text names (and assigns the answers) is not flagged."""
    t = tasks.get(task_id)
    nb = _notebook(t.chapter)
    aliases = _aliases(nb)
    reverse = {origin: alias for alias, origin in aliases.items()}
    lines = []
    for full in sorted(named(task_id)):
        mod, _, attr = full.rpartition(".")
        for origin, alias in reverse.items():
            if mod == origin or mod.startswith(origin + "."):
                lines.append(f"_x = {alias}{mod[len(origin):]}.{attr}")
                break
    lines += [f"{n} = 0" for n in t.names]
    code = "\n".join(lines)
    ast.parse(code)
    found = flags.code_flags(code, where="cell answer", answer_cell=True, aliases=aliases, known=set())
    assert not found, (code, found)


def test_the_issues_tools_are_tools():
    """The tools issue 27 names: chapters 09, 11, 13, 14, 15."""
    expect = {"task-09-1": {"aerophoto.projective.grid_pair", "aerophoto.projective.locate"},
              "task-09-2": {"aerophoto.projective.fit_projective"},
              "task-11-2": {"aerophoto.rectify.rectify_points", "aerophoto.projective.fit_projective"},
              "task-13-2": {"aerophoto.spectral.BAND_NAMES"},
              "task-14-2": {"aerophoto.accuracy.fit_accumulation"},
              "task-15-2": {"aerophoto.bundle.three_stage", "aerophoto.bundle.data_snooping"},
              "task-15-3": {"aerophoto.bundle.error_ellipse"}}
    for task_id, tools in expect.items():
        assert tools <= set(tasks.get(task_id).tools), task_id
        for tool in tools:
            assert not flags.is_package_answer(tool) and not flags.is_package_answer(tool + ".index")
    assert flags.is_package_answer("aerophoto.tasks.answers")
    assert not flags.is_package_answer("aerophoto.tasks.inputs")
