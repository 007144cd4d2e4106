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
:func:`task_passed`    the last line of a check cell: "✓ Task NN.k passed"
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

import math
from collections.abc import Mapping
from dataclasses import dataclass

__all__ = [
    "WrongAnswer",
    "TaskResult",
    "check_value",
    "check_count",
    "check_values",
    "check_bool",
    "check_choice",
    "task_passed",
    "results",
    "task_results",
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
        text = "No answers checked yet: run the check cell under each task."
    else:
        lines = []
        for t in _TASKS.values():
            lines.append(f"✓ {_task_title(t.name)} passed" + (f" ({t.message})" if t.message else ""))
        lines.extend(
            f"{'✓' if r.passed else '✗'} {r.name}" + ("" if r.passed else f" — {r.message}")
            for r in _RESULTS.values()
        )
        n = sum(r.passed for r in _RESULTS.values())
        lines.append(f"{n} of {len(_RESULTS)} checks passed; {len(_TASKS)} task(s) passed completely")
        text = "\n".join(lines)
    print(text)
    return _Report(text)


def _task_title(task: str) -> str:
    """``"task-04-2"`` → ``"Task 04.2"``; other names unchanged."""
    parts = str(task).split("-")
    if len(parts) >= 3 and parts[0] == "task":
        return f"Task {parts[1]}.{'-'.join(parts[2:])}"
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
    _TASKS[str(task)] = TaskResult(str(task), True, f"{len(claimed)} check(s)" if claimed else "")
    if not quiet:
        print(f"✓ {_task_title(task)} passed")


def _close(a: float, b: float, tol_abs: float | None, tol_rel: float | None) -> bool:
    if tol_abs is None and tol_rel is None:
        tol_rel = TOL_REL
    ok_abs = tol_abs is not None and abs(a - b) <= tol_abs
    ok_rel = tol_rel is not None and abs(a - b) <= tol_rel * abs(b)
    return ok_abs or ok_rel


def _diagnose(answer: float, expected: float, tol_abs, tol_rel, integer, of_variant, variant, alternatives) -> str:
    if expected != 0 and _close(-answer, expected, tol_abs, tol_rel):
        return "the size is right but the sign is wrong — check the guide's sign convention."
    if integer:
        if answer == math.floor(expected - 1e-9) and answer != expected:
            return "one too few — the guide rounds this count up (to the larger whole number)."
        if abs(answer - expected) == 1:
            return "off by one — did you forget the '+ 1' in the formula, or round the wrong way?"
    for label, value in (alternatives or {}).items():
        if value is not None and _close(answer, value, tol_abs, tol_rel):
            return label
    if expected != 0 and answer != 0:
        ratio = answer / expected
        for factor, hint in _UNIT_FACTORS.items():
            if abs(ratio / factor - 1) <= max(tol_rel or TOL_REL, TOL_REL) * 2:
                return f"your value is off by {hint}"
    if of_variant is not None and variant is not None:
        other = _other_variant(variant, lambda w: _close(answer, float(of_variant(w)), tol_abs, tol_rel))
        if other is not None:
            return _variant_message(other, variant)
    if expected != 0:
        off = abs(answer - expected) / abs(expected)
        if off <= 0.05:
            return "close, but outside the tolerance — keep more digits in the intermediate steps."
    return "not right — go back to the formula and check each input."


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
    return (f"this is the answer for variant {other:02d}, not yours ({variant.i:02d}) — "
            "check the record-book number in the first cell and use your own inputs.")


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
    unit_txt = f" (in {unit})" if unit else ""
    answer = _scalar(answer)
    if answer is None or answer is Ellipsis:
        return _fail(name, f"{name}: no answer yet — replace the ... with your value{unit_txt}.")
    if _is_bool(answer):
        return _fail(name, f"{name}: {answer} is a yes/no verdict — this task asks for a number{unit_txt}.")
    if getattr(answer, "size", 1) != 1 or isinstance(answer, (list, tuple, dict, set)):
        return _fail(name, f"{name}: give a single value{unit_txt}, not a list of values.")
    try:
        a = float(answer)
    except (TypeError, ValueError):
        return _fail(name, f"{name}: {answer!r} is not a number — give a single value{unit_txt}.")
    if math.isnan(a):
        return _fail(name, f"{name}: the answer is nan — an operation went wrong before this line.")
    if math.isinf(a):
        return _fail(name, f"{name}: the answer is infinite — a division by zero before this line?")
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
            print(f"✓ {name}: correct")
        return True
    if integer and not a.is_integer():
        return _fail(name, f"{name}: {a:g} is not a whole number — a count of strips or photos must be rounded{unit_txt}.")
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
    unit_txt = f" (in {unit})" if unit else ""
    a = _scalar(answer)
    if a is None or a is Ellipsis:
        return _fail(name, f"{name}: no answer yet — replace the ... with your count{unit_txt}.")
    if _is_bool(a):
        return _fail(name, f"{name}: {a} is a yes/no verdict — this task asks for a count.")
    try:
        x = float(a)
    except (TypeError, ValueError):
        return _fail(name, f"{name}: {a!r} is not a number — give a whole number{unit_txt}.")
    if math.isnan(x) or math.isinf(x):
        return _fail(name, f"{name}: the answer is {x} — an operation went wrong before this line.")
    e = float(expected)
    if x == e:
        _pass(name)
        if not quiet:
            print(f"✓ {name}: correct")
        return True
    if not x.is_integer():
        return _fail(name, f"{name}: {x:g} is not a whole number — {_ROUNDING[rounding]}.")
    if (rounding == "up" and x == e - 1) or (rounding == "down" and x == e + 1):
        return _fail(name, f"{name}: one {'too few' if x < e else 'too many'} — {_ROUNDING[rounding]}.")
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
    unit_txt = f" (in {unit})" if unit else ""
    if isinstance(expected, Mapping):
        if not isinstance(answers, Mapping):
            return _fail(name, f"{name}: give a dict {{name: value}} with the entries {list(expected)}.")
        missing = [k for k in expected if k not in answers]
        extra = [k for k in answers if k not in expected]
        if missing:
            return _fail(name, f"{name}: no value for {', '.join(map(str, missing))}.")
        if extra:
            return _fail(name, f"{name}: unexpected entries {', '.join(map(str, extra))} — use the names the task gives.")
        labels = [str(k) for k in expected]
        exp = [expected[k] for k in expected]
        ans = [answers[k] for k in expected]
    else:
        exp = _as_sequence(expected)
        if exp is None:
            raise ValueError(f"expected = {expected!r} is not a sequence or a dict of numbers")
        ans = _as_sequence(answers)
        if answers is None or answers is Ellipsis:
            return _fail(name, f"{name}: no answer yet — replace the ... with your {len(exp)} values{unit_txt}.")
        if ans is None:
            return _fail(name, f"{name}: give a list of {len(exp)} values{unit_txt}, one per entry.")
        if len(ans) != len(exp):
            return _fail(name, f"{name}: {len(ans)} values given, the task asks for {len(exp)}.")
    if labels is None:
        labels = [f"entry {k + 1}" for k in range(len(exp))]
    elif len(labels) != len(exp):
        raise ValueError(f"labels has {len(labels)} entries; expected {len(exp)} (one per value)")
    e = [float(x) for x in exp]
    a = []
    for lab, x in zip(labels, ans):
        x = _scalar(x)
        if x is None or x is Ellipsis:
            return _fail(name, f"{name}: no value yet for {lab}{unit_txt}.")
        if _is_bool(x):
            return _fail(name, f"{name}: {lab} is a yes/no verdict — give a number{unit_txt}.")
        try:
            xf = float(x)
        except (TypeError, ValueError):
            return _fail(name, f"{name}: {lab} = {x!r} is not a number{unit_txt}.")
        if math.isnan(xf):
            return _fail(name, f"{name}: {lab} is nan — an operation went wrong before this line.")
        a.append(xf)

    def ok(x, y):
        return x == y if integer else _close(x, y, tol_abs, tol_rel)

    wrong = [k for k in range(len(e)) if not ok(a[k], e[k])]
    if not wrong:
        _pass(name)
        if not quiet:
            print(f"✓ {name}: all {len(e)} values correct")
        return True
    nonzero = [k for k in range(len(e)) if e[k] != 0]
    why = None
    if len(e) > 1 and all(ok(a[k], e[len(e) - 1 - k]) for k in range(len(e))):
        why = "the values are right but in reverse order — keep the order the task gives."
    elif nonzero and all(ok(-a[k], e[k]) for k in range(len(e))):
        why = "the sizes are right but every sign is wrong — check the guide's sign convention."
    elif nonzero and all(a[k] != 0 for k in nonzero):
        for factor, hint in _UNIT_FACTORS.items():
            if all(abs(a[k] / e[k] / factor - 1) <= max(tol_rel or TOL_REL, TOL_REL) * 2 for k in nonzero):
                why = f"every value is off by {hint}"
                break
    if why is None and len(wrong) > 1 and all(any(ok(a[k], y) for y in e) for k in range(len(e))):
        why = "the values are right but not in the order the task gives."
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
        detail = " (the sign of " + ", ".join(labels[k] for k in flipped) + " is wrong)" if flipped else ""
        why = f"{len(wrong)} of {len(e)} values are not right: {named}{detail}."
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
        return _fail(name, f"{name}: no answer yet — replace the ... with True or False.")
    if not (_is_bool(answer)):
        return _fail(name, f"{name}: {answer!r} is not a verdict — write True or False (without quotes).")
    if bool(answer) == bool(expected):
        _pass(name)
        if not quiet:
            print(f"✓ {name}: correct")
        return True
    return _fail(name, f"{name}: the verdict is wrong — " + (hint or "check your value against the guide's tolerance."))


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
        return _fail(name, f"{name}: no answer yet — replace the ... with one of {opts}.")
    if not isinstance(answer, str) or norm(answer) not in {norm(o) for o in opts}:
        return _fail(name, f"{name}: {answer!r} is not one of the options {opts}.")
    if norm(answer) == norm(expected):
        _pass(name)
        if not quiet:
            print(f"✓ {name}: correct")
        return True
    return _fail(name, f"{name}: not this one — " + (hint or "read the task's definitions again."))


def _pass(name: str) -> None:
    _RESULTS[name] = TaskResult(name, True)
    _UNCLAIMED.append(name)


def _fail(name: str, message: str) -> bool:
    _RESULTS[name] = TaskResult(name, False, message)
    _UNCLAIMED.clear()
    raise WrongAnswer(message)
