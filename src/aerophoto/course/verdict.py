"""The verdict on one answer: right, or what kind of mistake it looks like — never the expected value.

One function per kind of answer (:data:`VERDICTS`); each returns a :class:`Verdict` and never raises for a
wrong or malformed answer (only for a task written wrongly: ``ValueError``).  The student's check cell
(:mod:`aerophoto.checks`, which prints the ✓ line or raises ``WrongAnswer`` with the message) and the
instructor's trusted scorer (:func:`aerophoto.course.score.grade_task`) reach the same verdict through the
same code: :func:`answer_call` turns a task's answer spec into the call both make.

Kernel side: imported in the student's kernel by :mod:`aerophoto.checks`; needs only :mod:`aerophoto.i18n`,
:mod:`aerophoto.variants` (another variant's answer) and :mod:`.wire` — not nbgrader, not the rest of
:mod:`aerophoto.course`.  The tolerances are described in :mod:`aerophoto.checks`.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from numbers import Real
from typing import NamedTuple

from ..i18n import t, translate_unit
from .wire import as_sequence, is_bool, scalar

__all__ = ["Verdict", "value_verdict", "count_verdict", "values_verdict", "bool_verdict", "choice_verdict",
           "VERDICTS", "answer_call", "close", "TOL_REL", "TOL_PHOTO_MM", "TOL_COEFF"]

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

_ROUNDING = {
    "up": "the guide rounds this count up (to the larger whole number)",
    "down": "the guide rounds this count down (whole items only)",
    "nearest": "the guide rounds this count to the nearest whole number",
}


class Verdict(NamedTuple):
    """``ok``: the answer is accepted; ``text``: the ✓ line to print when it is, else what is wrong."""

    ok: bool
    text: str


def _wrong(text: str) -> Verdict:
    return Verdict(False, text)


def close(a: float, b: float, tol_abs: float | None, tol_rel: float | None) -> bool:
    """``|a − b| ≤ tol_abs`` or ``≤ tol_rel·|b|`` (neither given: the default :data:`TOL_REL`)."""
    if tol_abs is None and tol_rel is None:
        tol_rel = TOL_REL
    ok_abs = tol_abs is not None and abs(a - b) <= tol_abs
    ok_rel = tol_rel is not None and abs(a - b) <= tol_rel * abs(b)
    return ok_abs or ok_rel


def _unit_hint(ratio: float, tol_rel) -> str | None:
    for factor, hint in _UNIT_FACTORS.items():
        if abs(ratio / factor - 1) <= max(tol_rel or TOL_REL, TOL_REL) * 2:
            return hint
    return None


def _diagnose(answer: float, expected: float, tol_abs, tol_rel, integer, of_variant, variant, alternatives) -> str:
    if expected != 0 and close(-answer, expected, tol_abs, tol_rel):
        return t("the size is right but the sign is wrong — check the guide's sign convention.")
    if integer:
        if answer == math.floor(expected - 1e-9) and answer != expected:
            return t("one too few — the guide rounds this count up (to the larger whole number).")
        if abs(answer - expected) == 1:
            return t("off by one — did you forget the '+ 1' in the formula, or round the wrong way?")
    for label, value in (alternatives or {}).items():
        if value is not None and close(answer, value, tol_abs, tol_rel):
            return t(label)  # a task's slip hint (aerophoto.i18n.slips)
    if expected != 0 and answer != 0:
        hint = _unit_hint(answer / expected, tol_rel)
        if hint is not None:
            return t("your value is off by {hint}", hint=t(hint))
    if of_variant is not None and variant is not None:
        other = _other_variant(variant, lambda w: close(answer, float(of_variant(w)), tol_abs, tol_rel))
        if other is not None:
            return _variant_message(other, variant)
    if expected != 0:
        off = abs(answer - expected) / abs(expected)
        if off <= 0.05:
            return t("close, but outside the tolerance — keep more digits in the intermediate steps.")
    return t("not right — go back to the formula and check each input.")


def _other_variant(variant, matches):
    """The index of the first other variant 00–99 for which ``matches(Variant)`` holds, or None."""
    from ..variants import variant_for_index

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


def _unit_txt(unit: str) -> str:
    return t(" (in {unit})", unit=translate_unit(unit)) if unit else ""


# ---------------------------------------------------------------------------------------------- one number
def _number(name: str, answer, unit_txt: str) -> float | Verdict:
    """``answer`` as one finite float, or the verdict on why it is not one."""
    if answer is None or answer is Ellipsis:
        return _wrong(t("{name}: no answer yet — replace the ... with your value{unit_txt}.", name=name,
                        unit_txt=unit_txt))
    if is_bool(answer):
        return _wrong(t("{name}: {answer} is a yes/no verdict — this task asks for a number{unit_txt}.", name=name,
                        answer=answer, unit_txt=unit_txt))
    if getattr(answer, "size", 1) != 1 or isinstance(answer, (list, tuple, dict, set)):
        return _wrong(t("{name}: give a single value{unit_txt}, not a list of values.", name=name, unit_txt=unit_txt))
    try:
        a = float(answer)
    except (TypeError, ValueError):
        return _wrong(t("{name}: {answer!r} is not a number — give a single value{unit_txt}.", name=name,
                        answer=answer, unit_txt=unit_txt))
    if math.isnan(a):
        return _wrong(t("{name}: the answer is nan — an operation went wrong before this line.", name=name))
    if math.isinf(a):
        return _wrong(t("{name}: the answer is infinite — a division by zero before this line?", name=name))
    return a


def value_verdict(name: str, answer, expected: float, *, tol_abs: float | None = None, tol_rel: float | None = None,
                  unit: str = "", integer: bool = False, of_variant=None, variant=None,
                  alternatives: dict | None = None) -> Verdict:
    """One numeric answer (parameters as :func:`aerophoto.checks.check_value`)."""
    unit_txt = _unit_txt(unit)
    answer = scalar(answer)
    a = _number(name, answer, unit_txt)
    if isinstance(a, Verdict):
        return a
    e = float(expected)
    if integer:
        ok = a == e and not (isinstance(answer, float) and not a.is_integer())
    else:
        ok = close(a, e, tol_abs, tol_rel)
    if ok:
        return Verdict(True, t("✓ {name}: correct", name=name))
    if integer and not a.is_integer():
        return _wrong(t("{name}: {a:g} is not a whole number — a count of strips or photos must be rounded{unit_txt}.",
                        name=name, a=a, unit_txt=unit_txt))
    why = _diagnose(a, e, tol_abs, None if integer else tol_rel, integer, of_variant, variant, alternatives)
    return _wrong(f"{name}: {why}")


def count_verdict(name: str, answer, expected: int, *, rounding: str = "up", unit: str = "", of_variant=None,
                  variant=None, alternatives: dict | None = None) -> Verdict:
    """A whole-number answer, exact, with the guide's rounding rule (as :func:`aerophoto.checks.check_count`)."""
    if rounding not in _ROUNDING:
        raise ValueError(f"rounding = {rounding!r} is not valid; expected one of {sorted(_ROUNDING)}")
    unit_txt = _unit_txt(unit)
    a = scalar(answer)
    if a is None or a is Ellipsis:
        return _wrong(t("{name}: no answer yet — replace the ... with your count{unit_txt}.", name=name,
                        unit_txt=unit_txt))
    if is_bool(a):
        return _wrong(t("{name}: {a} is a yes/no verdict — this task asks for a count.", name=name, a=a))
    try:
        x = float(a)
    except (TypeError, ValueError):
        return _wrong(t("{name}: {a!r} is not a number — give a whole number{unit_txt}.", name=name, a=a,
                        unit_txt=unit_txt))
    if math.isnan(x) or math.isinf(x):
        return _wrong(t("{name}: the answer is {x} — an operation went wrong before this line.", name=name, x=x))
    e = float(expected)
    if x == e:
        return Verdict(True, t("✓ {name}: correct", name=name))
    if not x.is_integer():
        return _wrong(t("{name}: {x:g} is not a whole number — {rule}.", name=name, x=x, rule=t(_ROUNDING[rounding])))
    if (rounding == "up" and x == e - 1) or (rounding == "down" and x == e + 1):
        key = "{name}: one too few — {rule}." if x < e else "{name}: one too many — {rule}."
        return _wrong(t(key, name=name, rule=t(_ROUNDING[rounding])))
    why = _diagnose(x, e, None, None, True, of_variant, variant, alternatives)
    return _wrong(f"{name}: {why}")


# ------------------------------------------------------------------------------------------ several numbers
def _paired(name: str, answers, expected, labels, unit_txt: str):
    """(labels, expected, answers) in the task's order, or the verdict on an answer of the wrong shape."""
    if isinstance(expected, Mapping):
        if not isinstance(answers, Mapping):
            return _wrong(t("{name}: give a dict {{name: value}} with the entries {entries}.", name=name,
                            entries=list(expected)))
        missing = [k for k in expected if k not in answers]
        extra = [k for k in answers if k not in expected]
        if missing:
            return _wrong(t("{name}: no value for {missing}.", name=name, missing=", ".join(map(str, missing))))
        if extra:
            return _wrong(t("{name}: unexpected entries {extra} — use the names the task gives.", name=name,
                            extra=", ".join(map(str, extra))))
        return [str(k) for k in expected], [expected[k] for k in expected], [answers[k] for k in expected]
    exp = as_sequence(expected)
    if exp is None:
        raise ValueError(f"expected = {expected!r} is not a sequence or a dict of numbers")
    ans = as_sequence(answers)
    if answers is None or answers is Ellipsis:
        return _wrong(t("{name}: no answer yet — replace the ... with your {n} values{unit_txt}.", name=name,
                        n=len(exp), unit_txt=unit_txt))
    if ans is None:
        return _wrong(t("{name}: give a list of {n} values{unit_txt}, one per entry.", name=name, n=len(exp),
                        unit_txt=unit_txt))
    if len(ans) != len(exp):
        return _wrong(t("{name}: {n_given} values given, the task asks for {n}.", name=name, n_given=len(ans),
                        n=len(exp)))
    if labels is None:
        labels = [t("entry {k}", k=k + 1) for k in range(len(exp))]
    elif len(labels) != len(exp):
        raise ValueError(f"labels has {len(labels)} entries; expected {len(exp)} (one per value)")
    return list(labels), exp, ans


def _numbers(name: str, labels, ans, unit_txt: str) -> list[float] | Verdict:
    """Each entry of the answer as a float, or the verdict on the first that is not a number."""
    a = []
    for lab, x in zip(labels, ans):
        x = scalar(x)
        if x is None or x is Ellipsis:
            return _wrong(t("{name}: no value yet for {lab}{unit_txt}.", name=name, lab=lab, unit_txt=unit_txt))
        if is_bool(x):
            return _wrong(t("{name}: {lab} is a yes/no verdict — give a number{unit_txt}.", name=name, lab=lab,
                            unit_txt=unit_txt))
        try:
            xf = float(x)
        except (TypeError, ValueError):
            return _wrong(t("{name}: {lab} = {x!r} is not a number{unit_txt}.", name=name, lab=lab, x=x,
                            unit_txt=unit_txt))
        if math.isnan(xf):
            return _wrong(t("{name}: {lab} is nan — an operation went wrong before this line.", name=name, lab=lab))
        a.append(xf)
    return a


def _whole_set_mistake(a, e, wrong, ok, tol_rel, of_variant, variant) -> str | None:
    """One mistake that explains every entry (reversed, signs, a unit factor, the order, another variant)."""
    n = len(e)
    nonzero = [k for k in range(n) if e[k] != 0]
    if n > 1 and all(ok(a[k], e[n - 1 - k]) for k in range(n)):
        return t("the values are right but in reverse order — keep the order the task gives.")
    if nonzero and all(ok(-a[k], e[k]) for k in range(n)):
        return t("the sizes are right but every sign is wrong — check the guide's sign convention.")
    if nonzero and all(a[k] != 0 for k in nonzero):
        for factor, hint in _UNIT_FACTORS.items():
            if all(abs(a[k] / e[k] / factor - 1) <= max(tol_rel or TOL_REL, TOL_REL) * 2 for k in nonzero):
                return t("every value is off by {hint}", hint=t(hint))
    if len(wrong) > 1 and all(any(ok(a[k], y) for y in e) for k in range(n)):
        return t("the values are right but not in the order the task gives.")
    if of_variant is not None and variant is not None:
        def same(w):
            other = [float(x) for x in (as_sequence(of_variant(w)) or [])]
            return len(other) == len(a) and all(ok(a[k], other[k]) for k in range(len(a)))

        other = _other_variant(variant, same)
        if other is not None:
            return _variant_message(other, variant)
    return None


def values_verdict(name: str, answers, expected, *, tol_abs: float | None = None, tol_rel: float | None = None,
                   unit: str = "", integer: bool = False, labels=None, of_variant=None, variant=None) -> Verdict:
    """A sequence (or dict) of numbers (as :func:`aerophoto.checks.check_values`)."""
    unit_txt = _unit_txt(unit)
    paired = _paired(name, answers, expected, labels, unit_txt)
    if isinstance(paired, Verdict):
        return paired
    labels, exp, ans = paired
    e = [float(x) for x in exp]
    a = _numbers(name, labels, ans, unit_txt)
    if isinstance(a, Verdict):
        return a

    def ok(x, y):
        return x == y if integer else close(x, y, tol_abs, tol_rel)

    wrong = [k for k in range(len(e)) if not ok(a[k], e[k])]
    if not wrong:
        return Verdict(True, t("✓ {name}: all {n} values correct", name=name, n=len(e)))
    why = _whole_set_mistake(a, e, wrong, ok, tol_rel, of_variant, variant)
    if why is None:
        named = ", ".join(labels[k] for k in wrong[:5]) + (" …" if len(wrong) > 5 else "")
        flipped = [k for k in wrong if e[k] != 0 and ok(-a[k], e[k])]
        detail = t(" (the sign of {labels} is wrong)", labels=", ".join(labels[k] for k in flipped)) if flipped else ""
        why = t("{n_wrong} of {n} values are not right: {named}{detail}.", n_wrong=len(wrong), n=len(e), named=named,
                detail=detail)
    return _wrong(f"{name}: {why}")


# ---------------------------------------------------------------------------------------- verdicts, picks
def bool_verdict(name: str, answer, expected: bool, *, hint: str = "") -> Verdict:
    """A yes/no verdict (as :func:`aerophoto.checks.check_bool`)."""
    if answer is None or answer is Ellipsis:
        return _wrong(t("{name}: no answer yet — replace the ... with True or False.", name=name))
    if not is_bool(answer):
        return _wrong(t("{name}: {answer!r} is not a verdict — write True or False (without quotes).", name=name,
                        answer=answer))
    if bool(answer) == bool(expected):
        return Verdict(True, t("✓ {name}: correct", name=name))
    return _wrong(t("{name}: the verdict is wrong — {hint}", name=name,
                    hint=t(hint or "check your value against the guide's tolerance.")))


def choice_verdict(name: str, answer, expected: str, options, *, hint: str = "") -> Verdict:
    """One answer picked from named options, case and spaces ignored (as :func:`aerophoto.checks.check_choice`)."""
    opts = [str(o) for o in options]

    def norm(s):
        return " ".join(str(s).split()).casefold()

    if norm(expected) not in {norm(o) for o in opts}:
        raise ValueError(f"expected = {expected!r} is not one of the options {opts}")
    if answer is None or answer is Ellipsis:
        return _wrong(t("{name}: no answer yet — replace the ... with one of {opts}.", name=name, opts=opts))
    if not isinstance(answer, str) or norm(answer) not in {norm(o) for o in opts}:
        return _wrong(t("{name}: {answer!r} is not one of the options {opts}.", name=name, answer=answer, opts=opts))
    if norm(answer) == norm(expected):
        return Verdict(True, t("✓ {name}: correct", name=name))
    return _wrong(t("{name}: not this one — {hint}", name=name, hint=t(hint or "read the task's definitions again.")))


VERDICTS = {"value": value_verdict, "count": count_verdict, "values": values_verdict, "bool": bool_verdict,
            "choice": choice_verdict}
"""A task answer's ``kind`` → its verdict function."""


# ------------------------------------------------------------------------------------ a graded task's answer
def answer_call(task, a, value, expected, slips: Mapping, variant) -> tuple[str, tuple, dict]:
    """(kind, args, keywords) of the verdict on answer spec ``a`` of ``task`` (:mod:`aerophoto.tasks`).

    ``VERDICTS[kind](*args, **keywords)`` gives the verdict; :func:`aerophoto.checks.check_task` calls the
    check of that kind with the same arguments.  An angle (``a.period``) is brought into 0 ≤ value < period;
    a cross-variant task lets the verdict recognise another variant's answer; ``slips`` are the task's
    typical mistakes for this variant.
    """
    alt = {k: val for k, val in (slips.get(a.name) or {}).items() if val is not None} or None
    if a.period:  # an angle: any whole turn is the same answer
        v = scalar(value)
        if isinstance(v, Real) and not is_bool(v) and math.isfinite(v):
            value = float(v) % a.period
    of_variant = None
    if task.cross_variant and variant is not None:
        def of_variant(w, _n=a.name):
            return task.answers(w)[_n]
    args = (a.name, value, expected)
    if a.kind == "value":
        return "value", args, dict(tol_abs=a.tol_abs, tol_rel=a.tol_rel, unit=a.unit, integer=a.integer,
                                   of_variant=of_variant, variant=variant, alternatives=alt)
    if a.kind == "count":
        return "count", args, dict(rounding=a.rounding, unit=a.unit, of_variant=of_variant, variant=variant,
                                   alternatives=alt)
    if a.kind == "values":
        return "values", args, dict(tol_abs=a.tol_abs, tol_rel=a.tol_rel, unit=a.unit, integer=a.integer,
                                    labels=list(a.labels) or None, of_variant=of_variant, variant=variant)
    if a.kind == "bool":
        return "bool", args, dict(hint=a.hint)
    return "choice", args + (a.options,), dict(hint=a.hint)
