"""The student's own results, shown only once the task that asks for them has passed (issue 12).

No graded value of the student's own variant is displayed before it is answered.  A cell after a task's check
cell may show the student's own results — their plan, their footprint — only through :func:`after`, which asks
first whether the task passed in this session and otherwise shows a :class:`Locked` note, "Answer task 01.2
first: …".  The notebook hands in the question as a function, ``passed=aerophoto.checks.passed`` (this module
sits below :mod:`aerophoto.checks` in the package's layers and does not import it)::

    from aerophoto import checks
    own.after(checks.passed, ["task-01-1"], lambda: flight.plan(v).table(), "the table holds your H and bases")
"""

from __future__ import annotations

import html
from collections.abc import Callable, Iterable

__all__ = ["Locked", "task_label", "after"]


class Locked:
    """What a cell shows instead of the student's own results before their task has passed (text and HTML)."""

    def __init__(self, text: str):
        self.text = str(text)

    def __repr__(self) -> str:
        return self.text

    def _repr_html_(self) -> str:
        return f"<div class='aerophoto-locked' style='color:#0072B2'>🔒 {html.escape(self.text)}</div>"


def task_label(task_id: str) -> str:
    """``"task-01-2"`` → ``"01.2"`` (as the check cells print it: "Task 01.2 passed")."""
    parts = str(task_id).split("-")
    if len(parts) < 3 or parts[0] != "task":
        raise ValueError(f"task_id = {task_id!r} is not a task id; expected the form 'task-NN-k', e.g. 'task-01-2'")
    return f"{parts[1]}.{'-'.join(parts[2:])}"


def after(passed: Callable[[str], bool], task_ids: Iterable[str], make: Callable[[], object], what: str = ""):
    """``make()`` once every task of ``task_ids`` has passed (``passed(task_id)``), else a :class:`Locked` note.

    Parameters
    ----------
    passed : the notebook's ``aerophoto.checks.passed``
    task_ids : the tasks whose answers the result shows, e.g. ``["task-01-1", "task-01-2"]``
    make : builds what to show (called only when every task passed)
    what : why it waits, after "Answer task NN.k first: " (e.g. "the table holds your strip spacing")
    """
    missing = [t for t in task_ids if not passed(t)]
    if missing:
        names = " and ".join(task_label(t) for t in missing)
        return Locked(f"Answer task {names} first" + (f": {what}" if what else "."))
    return make()
