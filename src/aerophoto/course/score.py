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

from ..i18n import t
from .verdict import VERDICTS, answer_call, close
from .wire import as_sequence, is_bool, scalar

__all__ = ["TaskGrade", "grade_task", "hidden_ok", "hidden_message"]


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
        Every check run, visible and hidden (``message`` is "" for a check that passed).
    lines : tuple of str
        What the student's check cell shows for each visible check, in order: its ✓ line, or its ✗ message.
    partial : bool
        The task scores in proportion to the checks passed (:attr:`aerophoto.tasks.Task.partial`).
    """

    task: str
    points: float
    score: float
    checks: tuple = field(default_factory=tuple)
    lines: tuple = field(default_factory=tuple)
    partial: bool = False

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
        """The message of the first check that failed (visible checks come first), or ""."""
        return next((msg for _, ok, msg, _ in self.checks if not ok), "")

    @property
    def n_passed(self) -> int:
        return sum(ok for _, ok, _, _ in self.checks)


def hidden_ok(h) -> tuple[bool, str]:
    """(passed, name or why not) of one hidden check (:class:`aerophoto.tasks.base.Hidden`).

    A ``"value"`` check may compare sequences element by element (``answer``, ``expected`` and ``tol_abs`` of
    one length); a ``"count"`` check passes on ``expected`` or any of its ``accepted`` counts.
    """
    if h.answer is None:
        return False, f"{h.name}: no value to check"
    try:
        if h.kind == "bool":
            return (is_bool(h.answer) and bool(h.answer) == bool(h.expected)), h.name
        if h.kind == "value" and as_sequence(h.answer) is not None:
            return _sequence_ok(h), h.name
        a, e = float(scalar(h.answer)), float(h.expected)
    except (TypeError, ValueError):
        return False, f"{h.name}: not a number"
    if not (math.isfinite(a) and math.isfinite(e)):
        return False, f"{h.name}: not a finite number"
    if h.kind == "count":
        return (a == e or a in {float(x) for x in h.accepted}), h.name
    return close(a, e, h.tol_abs, h.tol_rel), h.name


def _sequence_ok(h) -> bool:
    a = [float(scalar(x)) for x in as_sequence(h.answer)]
    e = [float(x) for x in (as_sequence(h.expected) or [])]
    tol = as_sequence(h.tol_abs)
    tol = [float(x) for x in tol] if tol is not None else [h.tol_abs] * len(e)
    if len(a) != len(e) or len(tol) != len(e):
        return False
    return all(math.isfinite(x) and math.isfinite(y) and close(x, y, t, h.tol_rel) for x, y, t in zip(a, e, tol))


def _visible(task, got: Mapping, variant) -> list[tuple]:
    """(name, passed, message, False, shown) of each answer, by the verdicts the student's check cell reaches:
    ``message`` "" when it passed, ``shown`` the line the check cell prints for it (✓ or the mistake)."""
    expected = task.answers(variant)
    slips = task.slips(variant)
    quantities, reals, accepted = task.quantities(variant), task.reals(variant), task.accepted(variant)
    out = []
    for a in task.spec:
        try:
            kind, args, kw = answer_call(task, a, got[a.name], expected[a.name], slips, variant,
                                         quantities=quantities, reals=reals, accepted=accepted)
            v = VERDICTS[kind](*args, **kw)
            out.append((a.name, v.ok, "" if v.ok else v.text, False, v.text))
        except Exception as exc:  # a malformed answer must never stop the grader
            why = f"{a.name}: could not be checked ({type(exc).__name__})"
            out.append((a.name, False, why, False, why))
    return out


def hidden_message(name: str) -> str:
    """The line a failed hidden check shows: which of the student's answers do not agree, never a value."""
    return t("your answers do not agree with each other: {check} — each must follow from the others as the task "
             "says.", check=t(name))


def _slip_behind(task, h, got: Mapping, variant) -> str:
    """The catalogued slip a failed hidden check's answer (``h.about``) matches, as its message; "" if none."""
    if not h.about:
        return ""
    try:
        a = task.answer(h.about)
        for hint, value in (task.slips(variant).get(h.about) or {}).items():
            if value is not None and close(float(scalar(got.get(h.about))), float(value), a.tol_abs, a.tol_rel):
                return f"{h.about}: {t(hint)}"
    except (KeyError, TypeError, ValueError):
        return ""
    return ""


def _hidden(task, got: Mapping, variant) -> list[tuple]:
    """(name, passed, message, True) of each hidden check of the task."""
    try:
        hidden = list(task.hidden(variant, got))
    except Exception as exc:
        return [("hidden checks", False, t("your answers could not be compared with each other ({error}).",
                                           error=type(exc).__name__), True)]
    out = []
    for h in hidden:
        ok, msg = hidden_ok(h)
        out.append((h.name, ok, "" if ok else (_slip_behind(task, h, got, variant) or hidden_message(h.name)), True))
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
        visible = _visible(task, got, variant)
        results = [r[:4] for r in visible] + _hidden(task, got, variant)
    n_ok = sum(ok for _, ok, _, _ in results)
    if task.partial:
        score = task.points * n_ok / max(len(results), 1)
    else:
        score = float(task.points) if n_ok == len(results) else 0.0
    return TaskGrade(task.id, float(task.points), float(score), tuple(results), tuple(r[4] for r in visible),
                     bool(task.partial))
