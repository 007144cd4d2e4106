"""Answer checks for the lab tasks: pass/fail with a helpful message, never the answer.

A lab task's check cell computes the expected value for the student's variant
with the package and calls the checks below.  On success a check prints a ✓
line; on failure it raises :class:`WrongAnswer` (an AssertionError, so nbgrader
marks the test cell failed) whose message says *what kind* of mistake it looks
like — units (m vs km, mm vs cm), sign, rounding direction, order, another
student's variant — without printing the expected value.  In a notebook the
error shows as one red line, not a traceback.

=====================  ==================================================
check                  for
=====================  ==================================================
:func:`check_value`    one number (a length, a scale, a time, a count)
:func:`check_count`    a whole number with the guide's rounding rule
:func:`check_values`   a sequence or a table column of numbers
:func:`check_bool`     a yes/no verdict (``True`` / ``False``)
:func:`check_choice`   one answer picked from a few named options
:func:`check_task`     every answer of a graded task (:mod:`aerophoto.tasks`), then "✓ Task NN.k passed"
:func:`task_passed`    the last line of a hand-written check cell: "✓ Task NN.k passed"
:func:`report`         a summary of every check run in this session
=====================  ==================================================

Each check asks :mod:`aerophoto.course.verdict` for the verdict (the instructor's trusted scorer,
:func:`aerophoto.course.score.grade_task`, asks the same code) and then prints the ✓ line or raises;
:func:`check_task` first records the submitted values for the grader (:mod:`aerophoto.course.wire`).
Nothing here is imported by :mod:`aerophoto.course`: the answer's road from the notebook to the gradebook
runs one way (``checks`` → ``course.wire``/``course.verdict``/``course.probe``; ``course.trusted`` →
``course.wire``, ``course.score`` → ``course.verdict``, ``tasks``).

Tolerances
----------
A task accepts what a careful hand calculation reaches with the precision the
guide prints its tables in — half a unit of the last printed digit:

* derived quantities (heights, bases, scales, times, areas):
  ``rel=0.005`` (0.5 %), the default (:data:`TOL_REL`);
* distances measured or computed on the photo, printed to 0.1 mm
  (guide §3, §6, §13: "с точностью до 0,1 мм"): ``tol_abs=0.05`` mm
  (:data:`TOL_PHOTO_MM`);
* counts (strips, photos, points): exact, with the guide's rounding rule
  (``integer=True`` or :func:`check_count`);
* reduction coefficients printed to three decimals (guide §7, §13):
  ``tol_abs=0.0005`` (:data:`TOL_COEFF`).

A task states its own tolerance where it differs.

Conventions for check cells (see docs/CONTRIBUTING.md, "Graded tasks")
---------------------------------------------------------------------
Each check is a statement, and the cell ends with ``checks.task_passed("task-NN-k")``,
so that the cell's last line displays no value (nbgrader reads a test cell's
displayed value as partial credit) and the student sees one line per task.
Nothing here writes to ``stderr``: nbgrader gives 0 points to a test cell that
does.
"""

from __future__ import annotations

import json
import os
from collections.abc import Mapping
from dataclasses import dataclass

from .course import verdict as _verdict
from .course import wire as _wire
from .course.probe import evidence as _evidence
from .course.verdict import TOL_COEFF, TOL_PHOTO_MM, TOL_REL, Verdict
from .i18n import t
from .i18n import t as _t  # report() calls its loop variable t
from .tasks.base import own_answers

__all__ = [
    "WrongAnswer",
    "check_task",
    "TaskResult",
    "check_value",
    "check_count",
    "check_values",
    "check_bool",
    "check_choice",
    "task_passed",
    "results",
    "task_results",
    "passed",
    "report",
    "reset",
    "TOL_REL",
    "TOL_PHOTO_MM",
    "TOL_COEFF",
]


class WrongAnswer(AssertionError):
    """A failed answer check.  Shown in notebooks as one line, without a traceback."""

    def _render_traceback_(self):  # IPython hook: what to print instead of a traceback
        return [f"\x1b[31m✗ {self}\x1b[0m"]


@dataclass
class TaskResult:
    """The outcome of one check (``name`` is the checked quantity) or one task."""

    name: str
    passed: bool
    message: str = ""




_RESULTS: dict[str, TaskResult] = {}
_TASKS: dict[str, TaskResult] = {}
_UNCLAIMED: list[str] = []  # checks run since the last task_passed()


def results() -> dict[str, TaskResult]:
    """The checks run in this kernel session, name → result (latest run wins)."""
    return dict(_RESULTS)


def task_results() -> dict[str, TaskResult]:
    """The tasks whose check cell ran to its end (:func:`task_passed`) in this session."""
    return dict(_TASKS)


def passed(task: str) -> bool:
    """Whether ``task`` (``"task-03-1"``) passed in this session: a later cell may then show its results."""
    return str(task) in _TASKS


def reset() -> None:
    """Forget every check and task result of this session."""
    _RESULTS.clear()
    _TASKS.clear()
    _UNCLAIMED.clear()


class _Report(str):
    """The text of :func:`report`; already printed, so a notebook shows it once."""

    def _ipython_display_(self):  # printed by report(): nothing more to show
        pass


def report() -> str:
    """A pass/fail summary of every check run in this session (printed and returned)."""
    if not _RESULTS and not _TASKS:
        text = _t("No answers checked yet: run the check cell under each task.")
    else:
        lines = []
        for t in _TASKS.values():
            lines.append(_t("✓ {task} passed", task=_task_title(t.name)) + (f" ({t.message})" if t.message else ""))
        lines.extend(
            f"{'✓' if r.passed else '✗'} {r.name}" + ("" if r.passed else f" — {r.message}")
            for r in _RESULTS.values()
        )
        n = sum(r.passed for r in _RESULTS.values())
        lines.append(_t("{n} of {total} checks passed; {tasks} task(s) passed completely", n=n, total=len(_RESULTS),
                        tasks=len(_TASKS)))
        text = "\n".join(lines)
    print(text)
    return _Report(text)


def _task_title(task: str) -> str:
    """``"task-04-2"`` → ``"Task 04.2"``; other names unchanged."""
    parts = str(task).split("-")
    if len(parts) >= 3 and parts[0] == "task":
        return t("Task {nn}.{k}", nn=parts[1], k="-".join(parts[2:]))
    return str(task)


def task_passed(task: str, *, quiet: bool = False) -> None:
    """Record that every check of ``task`` passed; the last line of a check cell.

    A check cell reaches its last line only when no check raised, so this
    prints ``✓ Task NN.k passed`` and files the checks run since the previous
    task under it (for :func:`report`).  Returns None, so the cell displays no
    value (nbgrader would read a displayed value as partial credit).
    """
    claimed = list(dict.fromkeys(_UNCLAIMED))
    _UNCLAIMED.clear()
    _TASKS[str(task)] = TaskResult(str(task), True, t("{n} check(s)", n=len(claimed)) if claimed else "")
    if not quiet:
        print(t("✓ {task} passed", task=_task_title(task)))


def _settle(name: str, v: Verdict, quiet: bool) -> bool:
    """Record the verdict; print its ✓ line (unless ``quiet``) or raise :class:`WrongAnswer` with its message."""
    if not v.ok:
        return _fail(name, v.text)
    _pass(name)
    if not quiet:
        print(v.text)
    return True


def check_value(
    name: str,
    answer,
    expected: float,
    *,
    tol_abs: float | None = None,
    tol_rel: float | None = None,
    unit: str = "",
    integer: bool = False,
    of_variant=None,
    variant=None,
    alternatives: dict | None = None,
    quiet: bool = False,
) -> bool:
    """Check one numeric answer; print ✓ or raise :class:`WrongAnswer` with a hint.

    Parameters
    ----------
    name : str
        The quantity as the task names it, e.g. ``"H_m"`` or ``"K (strips)"``.
    answer : number
        The student's value.  ``None`` / ``...`` (not answered yet) fails with
        a message saying so.
    expected : float
        The correct value for the student's variant (computed by the package).
    tol_abs, tol_rel : float, optional
        Accept ``|answer − expected| ≤ tol_abs`` or ``≤ tol_rel·|expected|``.
        Default: ``tol_rel = 0.005``; with ``integer=True`` exact equality.
    unit : str
        Unit the task asks for (shown in messages).
    integer : bool
        A count: must be a whole number and equal exactly.
    of_variant : callable, optional
        ``of_variant(Variant) → expected value``; with ``variant`` it lets the
        check recognise an answer computed for another student's variant.
    alternatives : dict, optional
        ``{hint: value}``: values that typical mistakes give (e.g. the guide's
        misprinted factor), each with the hint to show when matched.
    quiet : bool
        Print nothing on success (hidden checks).

    Returns
    -------
    True when the answer is accepted (otherwise it raises).  In a check cell
    call it as a statement and end the cell with :func:`task_passed`.
    """
    return _settle(name, _verdict.value_verdict(name, answer, expected, tol_abs=tol_abs, tol_rel=tol_rel, unit=unit,
                                                  integer=integer, of_variant=of_variant, variant=variant,
                                                  alternatives=alternatives), quiet)


def check_count(
    name: str,
    answer,
    expected: int,
    *,
    rounding: str = "up",
    unit: str = "",
    of_variant=None,
    variant=None,
    alternatives: dict | None = None,
    quiet: bool = False,
) -> bool:
    """Check a whole-number answer (strips K, photos n, total N, points); exact.

    Parameters
    ----------
    rounding : {"up", "down", "nearest"}
        The guide's rounding rule for this count (e.g. strips and photos per
        strip are rounded up, guide §2); a count one off in the direction the
        rule forbids gets a message naming the rule.
    Other parameters as :func:`check_value`.
    """
    return _settle(name, _verdict.count_verdict(name, answer, expected, rounding=rounding, unit=unit,
                                                  of_variant=of_variant, variant=variant, alternatives=alternatives), quiet)


def check_values(
    name: str,
    answers,
    expected,
    *,
    tol_abs: float | None = None,
    tol_rel: float | None = None,
    unit: str = "",
    integer: bool = False,
    labels=None,
    of_variant=None,
    variant=None,
    quiet: bool = False,
) -> bool:
    """Check a sequence of numbers (a table row or column) against the expected values.

    Parameters
    ----------
    name : str
        The quantity as the task names it, e.g. ``"delta_h_mm"``.
    answers : sequence of numbers, or dict
        The student's values: a list, tuple, 1-D array or Series in the order
        the task gives; or a dict ``{label: value}`` when ``expected`` is one.
    expected : sequence of numbers, or dict
        The correct values for the student's variant.
    tol_abs, tol_rel, integer, unit
        As :func:`check_value`, applied to every element.
    labels : sequence of str, optional
        How the task names the entries (``"point 1"``, ``"base 2–3"``); shown
        in the message instead of ``entry 3``.
    of_variant : callable, optional
        ``of_variant(Variant) → expected sequence`` to recognise another
        variant's answers.

    The message names the entries that are wrong and, where the whole set
    shows one mistake (every entry off by a unit factor, every sign flipped,
    the order reversed, another variant), says so — never the values.
    """
    return _settle(name, _verdict.values_verdict(name, answers, expected, tol_abs=tol_abs, tol_rel=tol_rel, unit=unit,
                                                   integer=integer, labels=labels, of_variant=of_variant,
                                                   variant=variant), quiet)


def check_bool(name: str, answer, expected: bool, *, hint: str = "", quiet: bool = False) -> bool:
    """Check a yes/no verdict (e.g. "the overlap meets the guide's norm").

    Parameters
    ----------
    answer : bool
        ``True`` or ``False`` (numpy booleans too); anything else fails with a
        message asking for one of them.
    expected : bool
        The right verdict for the student's variant.
    hint : str
        What to compare on a wrong verdict, e.g. ``"compare P_x with the
        guide's 56 % minimum (§3)"`` — shown in the message.
    """
    return _settle(name, _verdict.bool_verdict(name, answer, expected, hint=hint), quiet)


def check_choice(name: str, answer, expected: str, options, *, hint: str = "", quiet: bool = False) -> bool:
    """Check one answer picked from a few named options (case and spaces ignored).

    Parameters
    ----------
    answer : str
        The student's pick, e.g. ``"reverse"``.
    expected : str
        The right option; must be one of ``options``.
    options : sequence of str
        Every option the task offers (listed in the message for an answer that
        is not one of them).
    hint : str
        What to reconsider on a wrong pick.
    """
    return _settle(name, _verdict.choice_verdict(name, answer, expected, options, hint=hint), quiet)


def _pass(name: str) -> None:
    _RESULTS[name] = TaskResult(name, True)
    _UNCLAIMED.append(name)


def _fail(name: str, message: str) -> bool:
    _RESULTS[name] = TaskResult(name, False, message)
    _UNCLAIMED.clear()
    raise WrongAnswer(message)


# =========================================================================== graded tasks (aerophoto.tasks)
_CHECKS = {"value": "check_value", "count": "check_count", "values": "check_values", "bool": "check_bool",
           "choice": "check_choice"}


def _record_text(task, values: Mapping) -> str:
    """The text/plain line of a check cell's answer record: what was handed in, never a verdict or a value."""
    given = [n for n in task.names if values.get(n, Ellipsis) is not Ellipsis]
    return t("{task} — checking {names}", task=_task_title(task.id), names=", ".join(given) or t("(no answers yet)"))


def _emit(task_id: str, values: Mapping, variant, task=None) -> None:
    """Put the submitted values into the cell's output, as plain data, before anything is checked.

    Always: the saved notebook keeps what each check cell was given (the course report reads it back,
    :func:`aerophoto.course.trusted.saved_answers`); while the instructor grades, the grader scores it.  The
    record (:func:`aerophoto.course.wire.encode_answers`) is an output under
    :data:`aerophoto.course.wire.ANSWERS_MIME` with a ``text/plain`` line (:func:`_record_text`), so JupyterLab
    shows that line.  While grading it also carries what the check saw of the kernel
    (:func:`aerophoto.course.probe.evidence`).  It is published before any reference value exists in this
    kernel's frames: nothing that runs while it is written can read one.
    """
    record = _wire.encode_answers(task_id, values, variant)
    if os.environ.get("AEROPHOTO_GRADING"):
        try:
            record["evidence"] = _evidence(task)
            odd = {str(k): f"{type(x).__module__}.{type(x).__qualname__}"[:80] for k, x in values.items()
                   if type(x).__module__ == "__main__"}
            if odd:  # an answer of a class the notebook defined (a float whose __float__ reads the check's frame)
                record["evidence"]["value_types"] = odd
        except Exception as exc:  # evidence is a courtesy; the values are what counts
            record["evidence"] = {"error": type(exc).__name__}
    try:
        from IPython import get_ipython
        from IPython.display import display

        if get_ipython() is None:
            return
        bundle = {"text/plain": _record_text(task, values) if task is not None else str(task_id),
                  _wire.ANSWERS_MIME: json.loads(json.dumps(record, default=str))}
        display(bundle, raw=True)
    except Exception:  # outside IPython: nothing to emit to
        pass


def _check_one(task, a, value, expected, slips: Mapping, variant, *, quiet: bool) -> bool:
    """Run the student-facing check of answer spec ``a`` (raises WrongAnswer on a wrong answer).

    The check is looked up by name at call time, as a notebook would call it: the same verdict the trusted
    scorer reaches (:func:`aerophoto.course.verdict.answer_call`).
    """
    kind, args, kw = _verdict.answer_call(task, a, value, expected, slips, variant)
    return globals()[_CHECKS[kind]](*args, **kw, quiet=quiet)


def _task_values(task, values: Mapping) -> dict:
    unknown = [k for k in values if k not in task.names]
    if unknown:
        raise TypeError(f"{task.id} has no answer(s) {unknown}; its answers are {list(task.names)}")
    return {n: values.get(n, Ellipsis) for n in task.names}


def _session_variant(variant, task_id: str):
    """The variant to check with: ``variant`` if it is one; else the setup cell's, with one line saying so.

    A cell that reuses the name ``v`` (chapter 09's ``u, v = …``) must not change whose answers are checked: the
    variant then comes from the number the setup cell remembered (:func:`aerophoto.book.remembered_record_book`,
    or the guide's example when none is), as ``setup`` found it.
    """
    from .variants import Variant, variant as _variant_of, variant_for_index

    if isinstance(variant, Variant):
        return variant
    from .book import remembered_record_book

    rb = remembered_record_book()
    try:
        own = _variant_of(rb) if rb else variant_for_index(0, "not given — the guide's worked example")
    except (TypeError, ValueError):
        own = variant_for_index(0, "not given — the guide's worked example")
    print(t("note: the check of {task} was given {what} instead of your variant — a cell has reused the name v "
            "(e.g. u, v = …); checked for your variant {i:02d} from the setup cell. Give that variable another name.",
            task=_task_title(task_id), what=f"{type(variant).__name__}", i=own.i))
    return own


def _show(grade) -> None:
    """Print what the trusted score says: a ✓ line per visible check that passed; raise with the first failure.

    A partial task (:attr:`aerophoto.tasks.Task.partial`) also says the share it earned — the points the grader
    gives, shown here.
    """
    for line, (name, ok, msg, hidden) in zip(grade.lines, grade.checks):
        if ok:
            _pass(name)
            print(line)
    failed = [(name, msg) for name, ok, msg, _ in grade.checks if not ok]
    if not failed:
        return
    name, msg = failed[0]
    if grade.partial:
        msg = t("{message} ({task}: {n} of {total} right, {score:g} of {points:g} points)", message=msg,
                task=_task_title(grade.task), n=grade.n_passed, total=len(grade.checks), score=grade.score,
                points=grade.points)
    elif len(failed) > 1:
        msg = t("{message} (and {more} more to put right)", message=msg, more=len(failed) - 1)
    _fail(name, msg)


def check_task(task_id: str, variant, /, **values) -> None:
    """Check every answer of a graded task for the student's variant; the whole of a check cell.

    ``checks.check_task("task-03-1", v, Zcp_m=Zcp_m, H_m=H_m)`` records the values in the cell's output
    (:func:`_emit`), then asks the trusted scorer — the very function the instructor's grader runs,
    :func:`aerophoto.course.score.grade_task`, visible and hidden checks — and shows its verdict: a ✓ per value
    and "✓ Task 03.1 passed" exactly when the grader gives full marks, else one red line naming the first
    mistake (or the answers that do not agree with each other) — never the answer.  Returns None (nbgrader
    reads a displayed value as partial credit).
    """
    from . import tasks as _tasks
    from .course import score as _score

    task = _tasks.get(task_id)
    got = _task_values(task, values)
    variant = _session_variant(variant, task.id)
    _emit(task.id, got, variant, task)  # before the reference values exist anywhere in this kernel's frames
    # the check's own use of the reference values (its expected values, a slip's or another variant's) is not
    # recorded as a student's call; the values scored were written (with what was called before) above
    with own_answers():
        grade = _score.grade_task(task.id, variant, got)
    _show(grade)
    task_passed(task.id)
