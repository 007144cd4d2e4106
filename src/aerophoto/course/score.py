"""The trusted score of one task: the submitted values graded in the instructor's process.

:func:`grade_task` runs, on the values a check cell recorded (:mod:`.wire`), the visible checks the
student's notebook runs — the same verdicts (:mod:`.verdict`) — and the task's hidden checks
(:mod:`aerophoto.tasks`), for the variant the grader says (:mod:`.trusted`: the roster's, never the
kernel's).  It never raises for a wrong or malformed answer, and touches no session state of
:mod:`aerophoto.checks`.
"""

from __future__ import annotations

import contextlib
import math
from collections.abc import Mapping
from dataclasses import dataclass, field

from .verdict import VERDICTS, answer_call, close
from .wire import is_bool, scalar

__all__ = ["TaskGrade", "grade_task", "hidden_ok"]


@dataclass(frozen=True)
class TaskGrade:
    """The instructor's verdict on one task, computed outside the student's kernel.

    Attributes
    ----------
    task : str
        The task id.
    points, score : float
        Points available and awarded.
    checks : tuple of (name, passed, message, hidden)
        Every check run, visible and hidden.
    """

    task: str
    points: float
    score: float
    checks: tuple = field(default_factory=tuple)

    @property
    def visible_ok(self) -> bool:
        """Every check the student's notebook runs passed (what nbgrader's in-kernel result should say)."""
        return all(ok for _, ok, _, hidden in self.checks if not hidden)

    @property
    def hidden_ok(self) -> bool:
        return all(ok for _, ok, _, hidden in self.checks if hidden)

    @property
    def passed(self) -> bool:
        return self.visible_ok and self.hidden_ok

    @property
    def first_failure(self) -> str:
        return next((msg for _, ok, msg, _ in self.checks if not ok), "")


def hidden_ok(h) -> tuple[bool, str]:
    """(passed, name or why not) of one hidden check (:class:`aerophoto.tasks.base.Hidden`)."""
    if h.answer is None:
        return False, f"{h.name}: no value to check"
    try:
        if h.kind == "bool":
            return (is_bool(h.answer) and bool(h.answer) == bool(h.expected)), h.name
        a, e = float(scalar(h.answer)), float(h.expected)
    except (TypeError, ValueError):
        return False, f"{h.name}: not a number"
    if not (math.isfinite(a) and math.isfinite(e)):
        return False, f"{h.name}: not a finite number"
    if h.kind == "count":
        return a == e, h.name
    return close(a, e, h.tol_abs, h.tol_rel), h.name


def _visible(task, got: Mapping, variant) -> list[tuple]:
    """(name, passed, message, False) of each answer, by the verdicts the student's check cell reaches."""
    expected = task.answers(variant)
    slips = task.slips(variant)
    out = []
    for a in task.spec:
        try:
            kind, args, kw = answer_call(task, a, got[a.name], expected[a.name], slips, variant)
            v = VERDICTS[kind](*args, **kw)
            out.append((a.name, v.ok, "" if v.ok else v.text, False))
        except Exception as exc:  # a malformed answer must never stop the grader
            out.append((a.name, False, f"{a.name}: could not be checked ({type(exc).__name__})", False))
    return out


def _hidden(task, got: Mapping, variant) -> list[tuple]:
    """(name, passed, message, True) of each hidden check of the task."""
    try:
        hidden = list(task.hidden(variant, got))
    except Exception as exc:
        return [("hidden checks", False, f"could not be derived from the answers ({type(exc).__name__})", True)]
    out = []
    for h in hidden:
        ok, msg = hidden_ok(h)
        out.append((h.name, ok, "" if ok else msg, True))
    return out


def grade_task(task_id: str, variant, values: Mapping) -> TaskGrade:
    """Grade one task on submitted values for ``variant`` — the trusted check, in the instructor's process.

    Runs the visible checks (as the notebook does) and the hidden checks of the task; never raises for a
    wrong or malformed answer.  All or nothing unless the task scores partially (``Task.partial``).
    """
    from .. import tasks as _tasks

    task = _tasks.get(task_id)
    got = {n: values.get(n, Ellipsis) for n in task.names}
    with contextlib.redirect_stdout(None):  # what task code prints is not the grader's output
        results = _visible(task, got, variant) + _hidden(task, got, variant)
    n_ok = sum(ok for _, ok, _, _ in results)
    if task.partial:
        score = task.points * n_ok / max(len(results), 1)
    else:
        score = float(task.points) if n_ok == len(results) else 0.0
    return TaskGrade(task.id, float(task.points), float(score), tuple(results))
