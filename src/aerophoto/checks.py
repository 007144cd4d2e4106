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

import contextlib
import json
import math
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from numbers import Real

from .i18n import t, translate_unit
from .i18n import t as _t  # report() calls its loop variable t
from .tasks.base import own_answers

__all__ = [
    "WrongAnswer",
    "check_task",
    "grade_task",
    "TaskGrade",
    "encode_answers",
    "decode_answers",
    "ANSWERS_MIME",
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

TOL_REL = 0.005
"""Default relative tolerance (0.5 %) for derived quantities."""
TOL_PHOTO_MM = 0.05
"""Absolute tolerance for photo distances in mm (half of the guide's 0.1 mm)."""
TOL_COEFF = 0.0005
"""Absolute tolerance for coefficients printed to three decimals (reduction R, k)."""

_UNIT_FACTORS = {
    1000.0: "a factor of 1000 — metres vs kilometres, or mm vs m?",
    0.001: "a factor of 1/1000 — kilometres vs metres, or m vs mm?",
    10.0: "a factor of 10 — centimetres vs millimetres?",
    0.1: "a factor of 1/10 — millimetres vs centimetres?",
    100.0: "a factor of 100 — a fraction vs a percentage?",
    0.01: "a factor of 1/100 — a percentage vs a fraction?",
    3600.0: "a factor of 3600 — seconds vs hours?",
    1 / 3600.0: "a factor of 1/3600 — hours vs seconds?",
    3.6: "a factor of 3.6 — km/h vs m/s?",
    1 / 3.6: "a factor of 1/3.6 — m/s vs km/h?",
    60.0: "a factor of 60 — minutes vs hours, or arc-minutes vs degrees?",
    1 / 60.0: "a factor of 1/60 — hours vs minutes?",
    180 / math.pi: "a factor of 57.3 — degrees vs radians?",
    math.pi / 180: "a factor of 1/57.3 — radians vs degrees?",
}


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


def _close(a: float, b: float, tol_abs: float | None, tol_rel: float | None) -> bool:
    if tol_abs is None and tol_rel is None:
        tol_rel = TOL_REL
    ok_abs = tol_abs is not None and abs(a - b) <= tol_abs
    ok_rel = tol_rel is not None and abs(a - b) <= tol_rel * abs(b)
    return ok_abs or ok_rel


def _diagnose(answer: float, expected: float, tol_abs, tol_rel, integer, of_variant, variant, alternatives) -> str:
    if expected != 0 and _close(-answer, expected, tol_abs, tol_rel):
        return t("the size is right but the sign is wrong — check the guide's sign convention.")
    if integer:
        if answer == math.floor(expected - 1e-9) and answer != expected:
            return t("one too few — the guide rounds this count up (to the larger whole number).")
        if abs(answer - expected) == 1:
            return t("off by one — did you forget the '+ 1' in the formula, or round the wrong way?")
    for label, value in (alternatives or {}).items():
        if value is not None and _close(answer, value, tol_abs, tol_rel):
            return t(label)  # a task's slip hint (aerophoto.i18n.slips)
    if expected != 0 and answer != 0:
        ratio = answer / expected
        for factor, hint in _UNIT_FACTORS.items():
            if abs(ratio / factor - 1) <= max(tol_rel or TOL_REL, TOL_REL) * 2:
                return t("your value is off by {hint}", hint=t(hint))
    if of_variant is not None and variant is not None:
        other = _other_variant(variant, lambda w: _close(answer, float(of_variant(w)), tol_abs, tol_rel))
        if other is not None:
            return _variant_message(other, variant)
    if expected != 0:
        off = abs(answer - expected) / abs(expected)
        if off <= 0.05:
            return t("close, but outside the tolerance — keep more digits in the intermediate steps.")
    return t("not right — go back to the formula and check each input.")


def _other_variant(variant, matches):
    """The index of the first other variant 00–99 for which ``matches(Variant)`` holds, or None."""
    from .variants import variant_for_index

    for i in range(100):
        if i == variant.i:
            continue
        try:
            if matches(variant_for_index(i)):
                return i
        except Exception:  # a task's of_variant may not apply to every variant
            continue
    return None


def _variant_message(other: int, variant) -> str:
    return t("this is the answer for variant {other:02d}, not yours ({mine:02d}) — "
             "check the record-book number in the first cell and use your own inputs.", other=other, mine=variant.i)


def _is_bool(x) -> bool:
    """True and False, also numpy's booleans."""
    t = type(x)
    return isinstance(x, bool) or (t.__module__ == "numpy" and t.__name__ in ("bool", "bool_"))


def _scalar(answer):
    """A one-element array or Series → its element; anything else unchanged."""
    size = getattr(answer, "size", None)
    if size == 1 and hasattr(answer, "item") and not isinstance(answer, (int, float)):
        try:
            return answer.item()
        except (TypeError, ValueError):
            return answer
    return answer


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
    unit_txt = t(" (in {unit})", unit=translate_unit(unit)) if unit else ""
    answer = _scalar(answer)
    if answer is None or answer is Ellipsis:
        return _fail(name, t("{name}: no answer yet — replace the ... with your value{unit_txt}.", name=name, unit_txt=unit_txt))
    if _is_bool(answer):
        return _fail(name, t("{name}: {answer} is a yes/no verdict — this task asks for a number{unit_txt}.", name=name,
                             answer=answer, unit_txt=unit_txt))
    if getattr(answer, "size", 1) != 1 or isinstance(answer, (list, tuple, dict, set)):
        return _fail(name, t("{name}: give a single value{unit_txt}, not a list of values.", name=name, unit_txt=unit_txt))
    try:
        a = float(answer)
    except (TypeError, ValueError):
        return _fail(name, t("{name}: {answer!r} is not a number — give a single value{unit_txt}.", name=name,
                             answer=answer, unit_txt=unit_txt))
    if math.isnan(a):
        return _fail(name, t("{name}: the answer is nan — an operation went wrong before this line.", name=name))
    if math.isinf(a):
        return _fail(name, t("{name}: the answer is infinite — a division by zero before this line?", name=name))
    e = float(expected)
    if integer:
        ok = a == e
        if ok and isinstance(answer, float) and not a.is_integer():
            ok = False
    else:
        ok = _close(a, e, tol_abs, tol_rel)
    if ok:
        _pass(name)
        if not quiet:
            print(t("✓ {name}: correct", name=name))
        return True
    if integer and not a.is_integer():
        return _fail(name, t("{name}: {a:g} is not a whole number — a count of strips or photos must be rounded{unit_txt}.",
                             name=name, a=a, unit_txt=unit_txt))
    why = _diagnose(a, e, tol_abs, None if integer else tol_rel, integer, of_variant, variant, alternatives)
    return _fail(name, f"{name}: {why}")


_ROUNDING = {
    "up": "the guide rounds this count up (to the larger whole number)",
    "down": "the guide rounds this count down (whole items only)",
    "nearest": "the guide rounds this count to the nearest whole number",
}


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
    if rounding not in _ROUNDING:
        raise ValueError(f"rounding = {rounding!r} is not valid; expected one of {sorted(_ROUNDING)}")
    unit_txt = t(" (in {unit})", unit=translate_unit(unit)) if unit else ""
    a = _scalar(answer)
    if a is None or a is Ellipsis:
        return _fail(name, t("{name}: no answer yet — replace the ... with your count{unit_txt}.", name=name, unit_txt=unit_txt))
    if _is_bool(a):
        return _fail(name, t("{name}: {a} is a yes/no verdict — this task asks for a count.", name=name, a=a))
    try:
        x = float(a)
    except (TypeError, ValueError):
        return _fail(name, t("{name}: {a!r} is not a number — give a whole number{unit_txt}.", name=name, a=a, unit_txt=unit_txt))
    if math.isnan(x) or math.isinf(x):
        return _fail(name, t("{name}: the answer is {x} — an operation went wrong before this line.", name=name, x=x))
    e = float(expected)
    if x == e:
        _pass(name)
        if not quiet:
            print(t("✓ {name}: correct", name=name))
        return True
    if not x.is_integer():
        return _fail(name, t("{name}: {x:g} is not a whole number — {rule}.", name=name, x=x, rule=t(_ROUNDING[rounding])))
    if (rounding == "up" and x == e - 1) or (rounding == "down" and x == e + 1):
        key = "{name}: one too few — {rule}." if x < e else "{name}: one too many — {rule}."
        return _fail(name, t(key, name=name, rule=t(_ROUNDING[rounding])))
    why = _diagnose(x, e, None, None, True, of_variant, variant, alternatives)
    return _fail(name, f"{name}: {why}")


def _as_sequence(values):
    """A list of the values of a list/tuple/array/Series; None if it is not a sequence."""
    if isinstance(values, (str, bytes, Mapping)) or values is None or values is Ellipsis:
        return None
    if hasattr(values, "tolist") and getattr(values, "ndim", 1) != 1:
        return None
    try:
        return list(values.tolist() if hasattr(values, "tolist") else values)
    except TypeError:
        return None


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
    unit_txt = t(" (in {unit})", unit=translate_unit(unit)) if unit else ""
    if isinstance(expected, Mapping):
        if not isinstance(answers, Mapping):
            return _fail(name, t("{name}: give a dict {{name: value}} with the entries {entries}.", name=name,
                                 entries=list(expected)))
        missing = [k for k in expected if k not in answers]
        extra = [k for k in answers if k not in expected]
        if missing:
            return _fail(name, t("{name}: no value for {missing}.", name=name, missing=", ".join(map(str, missing))))
        if extra:
            return _fail(name, t("{name}: unexpected entries {extra} — use the names the task gives.", name=name,
                                 extra=", ".join(map(str, extra))))
        labels = [str(k) for k in expected]
        exp = [expected[k] for k in expected]
        ans = [answers[k] for k in expected]
    else:
        exp = _as_sequence(expected)
        if exp is None:
            raise ValueError(f"expected = {expected!r} is not a sequence or a dict of numbers")
        ans = _as_sequence(answers)
        if answers is None or answers is Ellipsis:
            return _fail(name, t("{name}: no answer yet — replace the ... with your {n} values{unit_txt}.", name=name,
                                 n=len(exp), unit_txt=unit_txt))
        if ans is None:
            return _fail(name, t("{name}: give a list of {n} values{unit_txt}, one per entry.", name=name, n=len(exp),
                                 unit_txt=unit_txt))
        if len(ans) != len(exp):
            return _fail(name, t("{name}: {n_given} values given, the task asks for {n}.", name=name, n_given=len(ans),
                                 n=len(exp)))
    if labels is None:
        labels = [t("entry {k}", k=k + 1) for k in range(len(exp))]
    elif len(labels) != len(exp):
        raise ValueError(f"labels has {len(labels)} entries; expected {len(exp)} (one per value)")
    e = [float(x) for x in exp]
    a = []
    for lab, x in zip(labels, ans):
        x = _scalar(x)
        if x is None or x is Ellipsis:
            return _fail(name, t("{name}: no value yet for {lab}{unit_txt}.", name=name, lab=lab, unit_txt=unit_txt))
        if _is_bool(x):
            return _fail(name, t("{name}: {lab} is a yes/no verdict — give a number{unit_txt}.", name=name, lab=lab,
                                 unit_txt=unit_txt))
        try:
            xf = float(x)
        except (TypeError, ValueError):
            return _fail(name, t("{name}: {lab} = {x!r} is not a number{unit_txt}.", name=name, lab=lab, x=x, unit_txt=unit_txt))
        if math.isnan(xf):
            return _fail(name, t("{name}: {lab} is nan — an operation went wrong before this line.", name=name, lab=lab))
        a.append(xf)

    def ok(x, y):
        return x == y if integer else _close(x, y, tol_abs, tol_rel)

    wrong = [k for k in range(len(e)) if not ok(a[k], e[k])]
    if not wrong:
        _pass(name)
        if not quiet:
            print(t("✓ {name}: all {n} values correct", name=name, n=len(e)))
        return True
    nonzero = [k for k in range(len(e)) if e[k] != 0]
    why = None
    if len(e) > 1 and all(ok(a[k], e[len(e) - 1 - k]) for k in range(len(e))):
        why = t("the values are right but in reverse order — keep the order the task gives.")
    elif nonzero and all(ok(-a[k], e[k]) for k in range(len(e))):
        why = t("the sizes are right but every sign is wrong — check the guide's sign convention.")
    elif nonzero and all(a[k] != 0 for k in nonzero):
        for factor, hint in _UNIT_FACTORS.items():
            if all(abs(a[k] / e[k] / factor - 1) <= max(tol_rel or TOL_REL, TOL_REL) * 2 for k in nonzero):
                why = t("every value is off by {hint}", hint=t(hint))
                break
    if why is None and len(wrong) > 1 and all(any(ok(a[k], y) for y in e) for k in range(len(e))):
        why = t("the values are right but not in the order the task gives.")
    if why is None and of_variant is not None and variant is not None:
        def same(w):
            other = [float(x) for x in (_as_sequence(of_variant(w)) or [])]
            return len(other) == len(a) and all(ok(a[k], other[k]) for k in range(len(a)))
        other = _other_variant(variant, same)
        if other is not None:
            why = _variant_message(other, variant)
    if why is None:
        named = ", ".join(labels[k] for k in wrong[:5]) + (" …" if len(wrong) > 5 else "")
        flipped = [k for k in wrong if e[k] != 0 and ok(-a[k], e[k])]
        detail = t(" (the sign of {labels} is wrong)", labels=", ".join(labels[k] for k in flipped)) if flipped else ""
        why = t("{n_wrong} of {n} values are not right: {named}{detail}.", n_wrong=len(wrong), n=len(e), named=named,
                detail=detail)
    return _fail(name, f"{name}: {why}")


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
    if answer is None or answer is Ellipsis:
        return _fail(name, t("{name}: no answer yet — replace the ... with True or False.", name=name))
    if not (_is_bool(answer)):
        return _fail(name, t("{name}: {answer!r} is not a verdict — write True or False (without quotes).", name=name,
                             answer=answer))
    if bool(answer) == bool(expected):
        _pass(name)
        if not quiet:
            print(t("✓ {name}: correct", name=name))
        return True
    return _fail(name, t("{name}: the verdict is wrong — {hint}", name=name,
                         hint=t(hint or "check your value against the guide's tolerance.")))


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
    opts = [str(o) for o in options]

    def norm(s):
        return " ".join(str(s).split()).casefold()

    if norm(expected) not in {norm(o) for o in opts}:
        raise ValueError(f"expected = {expected!r} is not one of the options {opts}")
    if answer is None or answer is Ellipsis:
        return _fail(name, t("{name}: no answer yet — replace the ... with one of {opts}.", name=name, opts=opts))
    if not isinstance(answer, str) or norm(answer) not in {norm(o) for o in opts}:
        return _fail(name, t("{name}: {answer!r} is not one of the options {opts}.", name=name, answer=answer, opts=opts))
    if norm(answer) == norm(expected):
        _pass(name)
        if not quiet:
            print(t("✓ {name}: correct", name=name))
        return True
    return _fail(name, t("{name}: not this one — {hint}", name=name, hint=t(hint or "read the task's definitions again.")))


def _pass(name: str) -> None:
    _RESULTS[name] = TaskResult(name, True)
    _UNCLAIMED.append(name)


def _fail(name: str, message: str) -> bool:
    _RESULTS[name] = TaskResult(name, False, message)
    _UNCLAIMED.clear()
    raise WrongAnswer(message)


# =========================================================================== graded tasks (aerophoto.tasks)
ANSWERS_MIME = "application/vnd.aerophoto.answers+json"
"""The output a check cell adds while the instructor grades (``AEROPHOTO_GRADING`` set): the submitted values."""

_MAX_LIST = 2000
_MAX_STR = 200


def _plain(x, depth: int = 0):
    """A submitted value as plain JSON data: numbers, strings, booleans, short lists and dicts."""
    x = _scalar(x)
    if x is Ellipsis:
        return {"ellipsis": True}
    if x is None or isinstance(x, str) and len(x) <= _MAX_STR:
        return x
    if _is_bool(x):
        return bool(x)
    if isinstance(x, int):
        return int(x) if abs(x) < 2**63 else float(x)
    if isinstance(x, float) or type(x).__module__ == "numpy" and hasattr(x, "item") and getattr(x, "size", 0) == 1:
        f = float(x)
        return f if math.isfinite(f) else {"float": str(f)}
    if depth < 2 and isinstance(x, Mapping) and len(x) <= 200:
        return {"dict": [[_plain(k, depth + 1), _plain(v, depth + 1)] for k, v in x.items()]}
    seq = _as_sequence(x)
    if depth < 2 and seq is not None and len(seq) <= _MAX_LIST:
        return {"list": [_plain(v, depth + 1) for v in seq]}
    return {"repr": repr(x)[:_MAX_STR]}


def _unplain(d):
    if isinstance(d, dict):
        if d.get("ellipsis"):
            return Ellipsis
        if "float" in d:
            return float(d["float"])
        if "list" in d:
            return [_unplain(v) for v in d["list"]]
        if "dict" in d:
            return {_unplain(k): _unplain(v) for k, v in d["dict"]}
        if "repr" in d:
            return _Opaque(str(d["repr"]))
        return _Opaque(str(d)[:_MAX_STR])
    return d


class _Opaque(str):
    """A submitted value that was not plain data (its repr); every check rejects it as not a number."""

    def __repr__(self):
        return str.__str__(self)


def encode_answers(task_id: str, values: Mapping, variant=None) -> dict:
    """The submitted answers of one task as plain JSON data (what leaves a sandboxed grading run)."""
    return {"task": str(task_id), "variant": None if variant is None else int(getattr(variant, "i", -1)),
            "values": {str(k): _plain(v) for k, v in values.items()}}


def decode_answers(record: Mapping) -> tuple[str, dict]:
    """(task id, {name: value}) from :func:`encode_answers`'s record; values that were not plain data stay opaque."""
    values = record.get("values") or {}
    if not isinstance(values, Mapping):
        values = {}
    return str(record.get("task", "")), {str(k): _unplain(v) for k, v in values.items()}


def _emit(task_id: str, values: Mapping, variant, task=None) -> None:
    """While grading, put the submitted values into the cell's output (plain data) for the instructor's grader.

    The record also carries what the check saw of the kernel (:func:`aerophoto.course.probe.evidence`).
    """
    if not os.environ.get("AEROPHOTO_GRADING"):
        return
    record = encode_answers(task_id, values, variant)
    try:
        from .course.probe import evidence

        record["evidence"] = evidence(task)
        odd = {str(k): f"{type(x).__module__}.{type(x).__qualname__}"[:80] for k, x in values.items()
               if type(x).__module__ == "__main__"}
        if odd:
            record["evidence"]["value_types"] = odd
    except Exception as exc:  # evidence is a courtesy; the values are what counts
        record["evidence"] = {"error": type(exc).__name__}
    try:
        from IPython.display import display

        display({ANSWERS_MIME: json.loads(json.dumps(record, default=str))}, raw=True)
    except Exception:  # outside IPython: nothing to emit to
        pass


def _check_one(task, a, value, expected, slips: Mapping, variant, *, quiet: bool) -> bool:
    """Run the student-facing check of answer spec ``a`` (raises WrongAnswer on a wrong answer)."""
    alt = {k: val for k, val in (slips.get(a.name) or {}).items() if val is not None} or None
    if a.period:  # an angle: any whole turn is the same answer (brought into 0 ≤ value < period)
        v = _scalar(value)
        if isinstance(v, Real) and not _is_bool(v) and math.isfinite(v):
            value = float(v) % a.period
    of_variant = None
    if task.cross_variant and variant is not None:
        def of_variant(w, _n=a.name):
            with own_answers():
                return task.answers(w)[_n]
    if a.kind == "value":
        return check_value(a.name, value, expected, tol_abs=a.tol_abs, tol_rel=a.tol_rel, unit=a.unit,
                           integer=a.integer, of_variant=of_variant, variant=variant, alternatives=alt, quiet=quiet)
    if a.kind == "count":
        return check_count(a.name, value, expected, rounding=a.rounding, unit=a.unit, of_variant=of_variant,
                           variant=variant, alternatives=alt, quiet=quiet)
    if a.kind == "values":
        return check_values(a.name, value, expected, tol_abs=a.tol_abs, tol_rel=a.tol_rel, unit=a.unit,
                            integer=a.integer, labels=list(a.labels) or None, of_variant=of_variant, variant=variant,
                            quiet=quiet)
    if a.kind == "bool":
        return check_bool(a.name, value, expected, hint=a.hint, quiet=quiet)
    return check_choice(a.name, value, expected, a.options, hint=a.hint, quiet=quiet)


def _task_values(task, values: Mapping) -> dict:
    unknown = [k for k in values if k not in task.names]
    if unknown:
        raise TypeError(f"{task.id} has no answer(s) {unknown}; its answers are {list(task.names)}")
    return {n: values.get(n, Ellipsis) for n in task.names}


def check_task(task_id: str, variant, /, **values) -> None:
    """Check every answer of a graded task for the student's variant; the whole of a check cell.

    ``checks.check_task("task-03-1", v, Zcp_m=Zcp_m, H_m=H_m)`` runs one
    check per answer of the task (:mod:`aerophoto.tasks`), in order, each
    printing ✓ or stopping with one red line that names the kind of mistake;
    when all pass it prints "✓ Task 03.1 passed".  Returns None (nbgrader
    reads a displayed value as partial credit).
    """
    from . import tasks as _tasks

    task = _tasks.get(task_id)
    got = _task_values(task, values)
    _emit(task.id, got, variant, task)  # before the reference values exist anywhere in this kernel's frames
    with own_answers():
        expected = task.answers(variant)
        slips = task.slips(variant)
    for a in task.spec:
        _check_one(task, a, got[a.name], expected[a.name], slips, variant, quiet=False)
    task_passed(task.id)


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


@contextlib.contextmanager
def _isolated():
    """Run checks without touching this session's record (the instructor's process grades many students)."""
    saved = (dict(_RESULTS), dict(_TASKS), list(_UNCLAIMED))
    try:
        yield
    finally:
        _RESULTS.clear()
        _RESULTS.update(saved[0])
        _TASKS.clear()
        _TASKS.update(saved[1])
        _UNCLAIMED[:] = saved[2]


def _hidden_ok(h) -> tuple[bool, str]:
    if h.answer is None:
        return False, f"{h.name}: no value to check"
    try:
        if h.kind == "bool":
            return (_is_bool(h.answer) and bool(h.answer) == bool(h.expected)), h.name
        a, e = float(_scalar(h.answer)), float(h.expected)
    except (TypeError, ValueError):
        return False, f"{h.name}: not a number"
    if not (math.isfinite(a) and math.isfinite(e)):
        return False, f"{h.name}: not a finite number"
    if h.kind == "count":
        return a == e, h.name
    return _close(a, e, h.tol_abs, h.tol_rel), h.name


def grade_task(task_id: str, variant, values: Mapping) -> TaskGrade:
    """Grade one task on submitted values for ``variant`` — the trusted check, in the instructor's process.

    Runs the visible checks (as the notebook does) and the hidden checks of
    the task; never raises for a wrong or malformed answer.  All or nothing
    unless the task scores partially (``Task.partial``).
    """
    from . import tasks as _tasks

    task = _tasks.get(task_id)
    got = {n: values.get(n, Ellipsis) for n in task.names}
    results = []
    with _isolated(), contextlib.redirect_stdout(None), own_answers():
        expected = task.answers(variant)
        slips = task.slips(variant)
        for a in task.spec:
            try:
                _check_one(task, a, got[a.name], expected[a.name], slips, variant, quiet=True)
                results.append((a.name, True, "", False))
            except WrongAnswer as exc:
                results.append((a.name, False, str(exc), False))
            except Exception as exc:  # a malformed answer must never stop the grader
                results.append((a.name, False, f"{a.name}: could not be checked ({type(exc).__name__})", False))
        try:
            hidden = list(task.hidden(variant, got))
        except Exception as exc:
            hidden = []
            results.append(("hidden checks", False, f"could not be derived from the answers ({type(exc).__name__})",
                            True))
        for h in hidden:
            ok, msg = _hidden_ok(h)
            results.append((h.name, ok, "" if ok else msg, True))
    n_ok = sum(ok for _, ok, _, _ in results)
    if task.partial:
        score = task.points * n_ok / max(len(results), 1)
    else:
        score = float(task.points) if n_ok == len(results) else 0.0
    return TaskGrade(task.id, float(task.points), float(score), tuple(results))
