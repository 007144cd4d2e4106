"""Answer checks for the lab tasks: pass/fail with a helpful message, never the answer.

A lab task's check cell computes the expected value for the student's variant
with the package and calls :func:`check_value`.  On success it prints a ✓ line;
on failure it raises :class:`WrongAnswer` (an AssertionError, so nbgrader marks
the test cell failed) whose message says *what kind* of mistake it looks like —
units (m vs km, mm vs cm), sign, rounding direction, another student's
variant — without printing the expected number.  In a notebook the error shows
as one red line, not a traceback.

Tolerances
----------
The default tolerance is the precision a careful hand calculation reaches with
the guide's printed rounding: ``rel=0.005`` (0.5 %) for derived quantities, and
exact equality for whole numbers (strips, photos).  Each task states its own
tolerance where it differs.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

__all__ = ["WrongAnswer", "check_value", "results", "report", "TaskResult"]

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
    name: str
    passed: bool
    message: str = ""


_RESULTS: dict[str, TaskResult] = {}


def results() -> dict[str, TaskResult]:
    """The checks run in this kernel session, name → result (latest run wins)."""
    return dict(_RESULTS)


def report() -> str:
    """A pass/fail summary of every check run in this session (printed and returned)."""
    if not _RESULTS:
        text = "No answers checked yet: run the check cell under each task."
    else:
        lines = [f"{'✓' if r.passed else '✗'} {r.name}" + ("" if r.passed else f" — {r.message}")
                 for r in _RESULTS.values()]
        n = sum(r.passed for r in _RESULTS.values())
        lines.append(f"{n} of {len(_RESULTS)} checks passed")
        text = "\n".join(lines)
    print(text)
    return text


def _close(a: float, b: float, tol_abs: float | None, tol_rel: float | None) -> bool:
    if tol_abs is None and tol_rel is None:
        tol_rel = 0.005
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
            if abs(ratio / factor - 1) <= max(tol_rel or 0.005, 0.005) * 2:
                return f"your value is off by {hint}"
    if of_variant is not None and variant is not None:
        for i in range(100):
            if i == variant.i:
                continue
            from .variants import variant_for_index

            try:
                other = float(of_variant(variant_for_index(i)))
            except Exception:
                continue
            if _close(answer, other, tol_abs, tol_rel):
                return (f"this is the answer for variant {i:02d}, not yours ({variant.i:02d}) — "
                        "check the record-book number in the first cell and use your own inputs.")
    if expected != 0:
        off = abs(answer - expected) / abs(expected)
        if off <= 0.05:
            return "close, but outside the tolerance — keep more digits in the intermediate steps."
    return "not right — go back to the formula and check each input."


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
    """
    unit_txt = f" (in {unit})" if unit else ""
    if answer is None or answer is Ellipsis:
        return _fail(name, f"{name}: no answer yet — replace the ... with your value{unit_txt}.")
    try:
        a = float(answer)
    except (TypeError, ValueError):
        return _fail(name, f"{name}: {answer!r} is not a number — give a single value{unit_txt}.")
    if math.isnan(a):
        return _fail(name, f"{name}: the answer is nan — an operation went wrong before this line.")
    e = float(expected)
    if integer:
        ok = a == e
        if ok and isinstance(answer, float) and not a.is_integer():
            ok = False
    else:
        ok = _close(a, e, tol_abs, tol_rel)
    if ok:
        _RESULTS[name] = TaskResult(name, True)
        if not quiet:
            print(f"✓ {name}: correct")
        return True
    if integer and not a.is_integer():
        return _fail(name, f"{name}: {a:g} is not a whole number — a count of strips or photos must be rounded{unit_txt}.")
    why = _diagnose(a, e, tol_abs, None if integer else tol_rel, integer, of_variant, variant, alternatives)
    return _fail(name, f"{name}: {why}")


def _fail(name: str, message: str) -> bool:
    _RESULTS[name] = TaskResult(name, False, message)
    raise WrongAnswer(message)
