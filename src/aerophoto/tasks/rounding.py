"""Rounding: what an honest student writes down, and how far a value derived from written values may move.

A student writes each answer rounded — to the unit the task expects (:attr:`~aerophoto.tasks.base.Answer.printed`:
0.01 mm, 1 for a scale denominator, 0.1 %) or to four significant digits, whichever keeps more — and may compute
the next column from the written value or from the unrounded one.  A hidden check compares one of the student's
answers with what follows from their others (``m_cp`` from their ``m_част``, ``t`` from their ``K_d``), so it
must admit every such rounding of the values it uses, and nothing more.  One rule, in one place:

* the **allowance** of a written value x is the larger of half its printed unit and half a unit of its 4th
  significant digit (:func:`allowance`);
* the tolerance of a derived value is the sum of what moving each input by its allowance does to it (found by
  evaluating the formula, not by a derivative typed per check) plus the derived answer's own allowance
  (:func:`propagated`, :func:`consistency`).

The grading sweep rounds the reference answers with :func:`round_to` and :func:`round_sig` (the same rule), and
proves that every such submission is accepted.
"""

from __future__ import annotations

import math

import numpy as np

from .base import Hidden

__all__ = ["SIG_DIGITS", "sig_unit", "allowance", "width", "source", "round_to", "round_sig", "four_digits", "written",
           "numbers",
           "propagated",
           "consistency", "holds", "either", "count_range", "verdict_check"]

SIG_DIGITS = 4
"""A value is written with at least this many significant digits (or to its printed unit, if that keeps more)."""


def sig_unit(x, digits: int = SIG_DIGITS):
    """The unit of the ``digits``-th significant digit of |x| (0 for x = 0), element by element."""
    a = np.abs(np.asarray(x, dtype=float))
    with np.errstate(divide="ignore"):
        e = np.where(a > 0, np.floor(np.log10(np.where(a > 0, a, 1.0))) - (digits - 1), 0.0)
    out = np.where(a > 0, 10.0 ** e, 0.0)
    return float(out) if out.ndim == 0 else out


def allowance(x, printed: float | None, cap=None):
    """How far a written value may lie from the value it stands for: max(½·printed, ½ unit of the 4th digit).

    ``cap`` (a number or an array like ``x``: the answer's visible tolerance), when given, drops the four-digit
    rule where four digits would fail the visible check (a coordinate of 6 061 988 m to four digits is no honest
    form of it; the grading sweep leaves such an answer unrounded too): there only the printed unit counts.
    """
    half = 0.5 * float(printed) if printed else 0.0
    sig = 0.5 * np.asarray(sig_unit(x), dtype=float)
    if cap is not None:
        sig = np.where(sig <= np.asarray(cap, dtype=float), sig, 0.0)
    out = np.maximum(half, sig)
    return float(out) if np.ndim(out) == 0 else out


_TOL_REL = 0.005  # aerophoto.course.verdict.TOL_REL, the default relative tolerance (a test holds them equal)
_FLOAT_SLACK = 1e-9  # aerophoto.course.verdict.FLOAT_SLACK (the same test holds them equal)


def width(answer, ref):
    """The half-width of ``answer``'s visible tolerance around ``ref`` (None for counts, verdicts and names)."""
    if answer.kind not in ("value", "values") or answer.integer:
        return None
    tol_abs, tol_rel = answer.tol_abs, answer.tol_rel
    if tol_abs is None and tol_rel is None:
        tol_rel = _TOL_REL
    w = np.maximum(tol_abs or 0.0, (tol_rel or 0.0) * np.abs(np.asarray(ref, dtype=float)))
    return float(w) if np.ndim(w) == 0 else w


def source(task, got, name: str, n: int | None = None):
    """``(value, printed, cap)`` of the submitted answer ``name`` of ``task``, for :func:`consistency`: its
    printed unit and, as the cap of its allowance, its visible tolerance (None for the value if not a number)."""
    a = task.answer(name)
    x = numbers(got.get(name), n)
    return x, a.printed, None if x is None else width(a, x)


def round_to(x, unit: float):
    """``x`` rounded to a multiple of ``unit`` (halves away from zero, as by hand), element by element."""
    q = np.asarray(x, dtype=float) / float(unit)
    r = np.sign(q) * np.floor(np.abs(q) + 0.5) * float(unit)
    # a unit like 0.01 leaves 0.30000000000000004: round to the unit's own decimals
    decimals = max(0, -int(math.floor(math.log10(float(unit)))) + 1)
    r = np.round(r, decimals)
    return float(r) if r.ndim == 0 else r


def round_sig(x, digits: int = SIG_DIGITS):
    """``x`` rounded to ``digits`` significant digits, element by element (0 stays 0)."""
    a = np.asarray(x, dtype=float)
    r = np.array([float(f"{e:.{digits}g}") for e in np.ravel(a)], dtype=float).reshape(a.shape)
    return float(r) if r.ndim == 0 else r


def four_digits(x, answer):
    """``x`` (a value of answer spec ``answer``) written to four significant digits wherever that rounding is
    within the answer's visible tolerance whatever the digits (half a unit of the 4th digit ≤ the tolerance),
    element by element; elsewhere unchanged — the task asks for more digits there (a coordinate of 6 061 988 m)."""
    a = np.asarray(x, dtype=float)
    w = np.asarray(width(answer, a), dtype=float)
    r = np.where(0.5 * np.asarray(sig_unit(a), dtype=float) <= w, np.asarray(round_sig(a), dtype=float), a)
    return float(r) if r.ndim == 0 else r


def written(x, printed: float | None):
    """``x`` as a student writes it: to the printed unit or to 4 significant digits, whichever keeps more."""
    if printed is None:
        return round_sig(x)
    a = np.asarray(x, dtype=float)
    by_unit = np.asarray(round_to(a, printed))
    by_sig = np.asarray(round_sig(a))
    keep_unit = np.abs(by_unit - a) <= np.abs(by_sig - a)
    r = np.where(keep_unit, by_unit, by_sig)
    return float(r) if r.ndim == 0 else r


def numbers(x, n: int | None = None):
    """A submitted value as a float (``n`` None) or a float array of length ``n``; None if it is not that.

    Never raises: ``...``, None, text, booleans, wrong lengths and non-finite numbers give None.
    """
    if x is None or x is Ellipsis or isinstance(x, (str, bytes, dict, bool, np.bool_)):
        return None
    if n is None:
        if getattr(x, "size", None) == 1 and hasattr(x, "item"):
            x = x.item()
        if isinstance(x, bool):
            return None
        try:
            f = float(x)
        except (TypeError, ValueError):
            return None
        return f if math.isfinite(f) else None
    try:
        seq = x.tolist() if hasattr(x, "tolist") else list(x)
        out = np.array([float(e) for e in seq], dtype=float)
    except (TypeError, ValueError):
        return None
    if out.ndim != 1 or len(out) != n or not np.all(np.isfinite(out)) or any(isinstance(e, bool) for e in seq):
        return None
    return out


def propagated(fn, sources):
    """(value, tolerance) of ``fn(*values)`` when each input may be off by its allowance.

    ``sources`` is a sequence of ``(value, printed)`` or ``(value, printed, cap)``: a float or a float array, its
    printed unit and the cap of its allowance (:func:`allowance`; :func:`source` gives all three).  The
    tolerance (same shape as the value) is the sum, over every input element, of the larger change that moving
    that element by its allowance either way makes — the formula is evaluated, never differentiated by hand.
    """
    sources = [tuple(s) + (None,) * (3 - len(s)) for s in sources]
    values = [np.asarray(x, dtype=float) for x, _, _ in sources]
    base = np.asarray(fn(*[float(x) if x.ndim == 0 else x for x in values]), dtype=float)
    tol = np.zeros_like(base)
    for j, ((x, printed, cap), arr) in enumerate(zip(sources, values)):
        a = np.broadcast_to(np.asarray(allowance(arr, printed, cap), dtype=float), arr.shape)
        for idx in np.ndindex(arr.shape):
            if a[idx] == 0:
                continue
            moved = []
            for sign in (1.0, -1.0):
                shifted = [v.copy() for v in values]
                shifted[j][idx] += sign * a[idx]
                out = np.asarray(fn(*[float(s) if s.ndim == 0 else s for s in shifted]), dtype=float)
                moved.append(np.abs(out - base))
            change = np.maximum(*moved)
            tol = tol + np.where(np.isfinite(change), change, np.inf)
    return (float(base) if base.ndim == 0 else base), (float(tol) if tol.ndim == 0 else tol)


def consistency(name: str, target, target_printed: float | None, fn, sources, *, n: int | None = None,
                extra=0.0, about: str = "", target_cap=None) -> Hidden:
    """A hidden check that the submitted ``target`` follows from the submitted ``sources`` by ``fn``.

    ``target`` is the submitted answer (a number, or ``n`` numbers), ``sources`` a sequence of
    ``(submitted value, printed unit)`` (each a number or an array, already read with :func:`numbers`; any None
    makes the check fail: nothing to derive from).  The tolerance is :func:`propagated` from the sources plus the
    target's own allowance (its printed unit), plus ``extra`` for what an accepted method moves beyond rounding.
    ``about`` names the target answer (:attr:`Hidden.about`: a failure then names a matching slip).
    """
    got = numbers(target, n)
    if got is None or any(s[0] is None for s in sources):
        return Hidden(name, None, None, about=about)
    try:
        with np.errstate(all="ignore"):
            expected, tol = propagated(fn, sources)
    except (ValueError, ZeroDivisionError, FloatingPointError, TypeError):
        return Hidden(name, None, None, about=about)
    if not np.all(np.isfinite(expected)) or np.shape(expected) != np.shape(got):
        return Hidden(name, None, None, about=about)
    tol = np.asarray(tol, dtype=float) + np.asarray(allowance(got, target_printed, target_cap), dtype=float) + \
        np.asarray(extra, dtype=float)
    if n is None:
        return Hidden(name, float(got), float(expected), tol_abs=float(tol), about=about)
    return Hidden(name, [float(x) for x in got], [float(x) for x in np.ravel(expected)],
                  tol_abs=[float(x) for x in np.broadcast_to(tol, np.shape(got))], about=about)


def holds(h: Hidden) -> bool:
    """Whether a numeric hidden check from :func:`consistency` holds (|answer − expected| ≤ tol, element-wise)."""
    if h.answer is None or h.expected is None or h.kind != "value":
        return False
    a, e = np.asarray(h.answer, dtype=float), np.asarray(h.expected, dtype=float)
    tol = np.asarray(h.tol_abs if h.tol_abs is not None else 0.0, dtype=float)
    if a.shape != e.shape:
        return False
    slack = _FLOAT_SLACK * np.maximum(np.abs(a), np.abs(e))  # verdict.FLOAT_SLACK: "≤ tol" inclusive in floats
    return bool(np.all(np.abs(a - e) - slack <= tol))


def either(*checks: Hidden) -> Hidden:
    """The first of ``checks`` (one relation, several accepted forms of it) that holds, else the first."""
    return next((h for h in checks if holds(h)), checks[0])


def count_range(values, printed: float | None, threshold: float) -> tuple[int, int]:
    """(least, most) of ``count(|x| > threshold)`` when every x may be off by its allowance."""
    x = np.abs(np.asarray(values, dtype=float))
    a = np.asarray(allowance(x, printed), dtype=float)
    return int(np.count_nonzero(x - a > threshold)), int(np.count_nonzero(x + a > threshold))


def verdict_check(name: str, verdict, deviations, limits, allowances) -> Hidden:
    """A yes/no answer against the student's own numbers: True if every |d| ≤ its limit, False if one exceeds it.

    Where a deviation lies within its allowance of its limit, either verdict is consistent (the rounding of
    the student's numbers decides it).
    """
    d = np.abs(np.asarray(deviations, dtype=float))
    lim = np.asarray(limits, dtype=float)
    a = np.asarray(allowances, dtype=float)
    if not isinstance(verdict, (bool, np.bool_)):
        return Hidden(name, verdict, True, kind="bool")
    if np.all(d <= lim - a):
        expected = True
    elif np.any(d > lim + a):
        expected = False
    else:
        expected = bool(verdict)
    return Hidden(name, bool(verdict), expected, kind="bool")
