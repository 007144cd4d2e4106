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

__all__ = ["Verdict", "Hints", "value_verdict", "count_verdict", "values_verdict", "bool_verdict",
           "choice_verdict", "VERDICTS", "answer_call", "told_apart", "close", "tolerance", "MORE_DIGITS_WITHIN", "TOL_REL",
           "TOL_PHOTO_MM", "TOL_COEFF", "FLOAT_SLACK"]

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
    "exact": "count every one (a whole number)",
}


class Verdict(NamedTuple):
    """``ok``: the answer is accepted; ``text``: the ✓ line to print when it is, else what is wrong."""

    ok: bool
    text: str


def _wrong(text: str) -> Verdict:
    return Verdict(False, text)


FLOAT_SLACK = 1e-9
"""A difference this small relative to the values compared is none (binary representation, not the student): a
value written exactly half a printed unit off — 180.25 m written 180.2 against a tolerance of 0.05 m — is inside
the tolerance, as the rule "≤ tolerance" says, though 180.25 − 180.2 is 0.050000000000004 in floating point."""


def close(a: float, b: float, tol_abs: float | None, tol_rel: float | None) -> bool:
    """``|a − b| ≤ tol_abs`` or ``≤ tol_rel·|b|`` (neither given: the default :data:`TOL_REL`), both inclusive
    up to :data:`FLOAT_SLACK` of the values."""
    if tol_abs is None and tol_rel is None:
        tol_rel = TOL_REL
    d = abs(a - b) - FLOAT_SLACK * max(abs(a), abs(b))
    ok_abs = tol_abs is not None and d <= tol_abs
    ok_rel = tol_rel is not None and d <= tol_rel * abs(b)
    return ok_abs or ok_rel


def tolerance(b: float, tol_abs: float | None, tol_rel: float | None) -> float:
    """The width :func:`close` accepts around ``b``: the larger of ``tol_abs`` and ``tol_rel·|b|``."""
    if tol_abs is None and tol_rel is None:
        tol_rel = TOL_REL
    return max(tol_abs or 0.0, (tol_rel or 0.0) * abs(b))


def _unit_hint(ratio: float, tol_rel) -> str | None:
    for factor, hint in _UNIT_FACTORS.items():
        if abs(ratio / factor - 1) <= max(tol_rel or TOL_REL, TOL_REL) * 2:
            return hint
    return None


MORE_DIGITS_WITHIN = 2.0
""""keep more digits" is said only for an answer within this many tolerances of the expected value."""


class Hints(NamedTuple):
    """What a wrong answer is compared with, besides the expected value (all optional).

    ``alternatives`` — the task's catalogued slips ``{hint: value}``; ``quantities`` — other quantities of the
    chapter ``{what it is: value}`` (an answer that equals one is told so); ``of_variant``/``variant`` — to
    recognise another variant's answer, matched only within ``match`` (the student's rounding, not the whole
    tolerance) and only when nothing above explains the value; ``real`` — for a rounded count, the real
    quantity it rounds; ``hint`` — for an exact count, what to count again.
    """

    alternatives: dict | None = None
    quantities: dict | None = None
    of_variant: object = None
    variant: object = None
    match: float = 0.0
    real: float | None = None
    hint: str = ""


def _diagnose(answer: float, expected: float, tol_abs, tol_rel, integer: bool, h: Hints, rounding: str = "") -> str:
    """What kind of mistake ``answer`` looks like (never the expected value).

    In this order, the likeliest first: a catalogued slip of the task; the sign; for a count, the other rounding
    of its real quantity (or, for an exact count, a miscount); another quantity of the chapter; a unit factor;
    another variant's answer (an exact match only); "keep more digits" only within
    :data:`MORE_DIGITS_WITHIN` tolerances; else back to the formula.
    """
    for label, value in (h.alternatives or {}).items():
        if value is not None and close(answer, float(value), tol_abs, tol_rel):
            return t(label)  # a task's slip hint (aerophoto.i18n.slips)
    if expected != 0 and close(-answer, expected, tol_abs, tol_rel):
        return t("the size is right but the sign is wrong — check the guide's sign convention.")
    if integer:
        why = _count_mistake(answer, expected, rounding, h)
        if why:
            return why
    for label, value in (h.quantities or {}).items():
        if value is not None and close(answer, float(value), tol_abs, tol_rel):
            return t("that is {quantity}, not what this answer asks for — read the task again.", quantity=t(label))
    if expected != 0 and answer != 0:
        hint = _unit_hint(answer / expected, tol_rel)
        if hint is not None:
            return t("your value is off by {hint}", hint=t(hint))
    if h.of_variant is not None and h.variant is not None and not integer:
        match = max(float(h.match), 1e-9 * max(abs(answer), 1.0))
        other = _other_variant(h.variant, lambda w: abs(answer - float(h.of_variant(w))) <= match)
        if other is not None:
            return _variant_message(other, h.variant)
    if not integer and abs(answer - expected) <= MORE_DIGITS_WITHIN * tolerance(expected, tol_abs, tol_rel):
        return t("close, but outside the tolerance — keep more digits in the intermediate steps.")
    if integer and h.hint:
        return t(h.hint)
    return t("not right — go back to the formula and check each input.")


def _count_mistake(answer: float, expected: float, rounding: str, h: Hints) -> str:
    """For a count: the rounding hint (the other rounding of its real quantity), or a miscount; "" otherwise."""
    if rounding == "exact":
        if abs(answer - expected) == 1:
            return t("off by one — count again{hint}", hint=(" — " + t(h.hint)) if h.hint else ".")
        return ""
    if h.real is not None and math.isfinite(h.real):
        others = {math.floor(h.real), math.ceil(h.real), math.floor(h.real + 0.5)} - {expected}
        if answer in others:
            return t(_ROUNDING_MISTAKE.get(rounding, _ROUNDING_MISTAKE["up"]))
        return ""
    if rounding == "up" and answer == expected - 1:
        return t(_ROUNDING_MISTAKE["up"])
    if rounding == "down" and answer == expected + 1:
        return t(_ROUNDING_MISTAKE["down"])
    if abs(answer - expected) == 1:
        return t("off by one — did you forget the '+ 1' in the formula, or round the wrong way?")
    return ""


_ROUNDING_MISTAKE = {
    "up": "one too few — the guide rounds this count up (to the larger whole number).",
    "down": "one too many — the guide rounds this count down (whole items only).",
    "nearest": "rounded the wrong way — the guide rounds this count to the nearest whole number.",
}


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
                  alternatives: dict | None = None, quantities: dict | None = None, match: float = 0.0,
                  accepted: dict | None = None, rounding: str = "up") -> Verdict:
    """One numeric answer (parameters as :func:`aerophoto.checks.check_value`; ``quantities`` and ``match`` as
    :class:`Hints`; ``accepted`` — ``{note: value}``, other values the task accepts, e.g. another reading of an
    ambiguous source: a match passes, its ✓ line naming the note; ``rounding`` — for ``integer``, the count's rule
    as in :func:`count_verdict`)."""
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
    for note, alt in (accepted or {}).items():
        if alt is not None and (a == float(alt) if integer else close(a, float(alt), tol_abs, tol_rel)):
            return Verdict(True, t("✓ {name}: correct ({note})", name=name, note=t(note)))
    if integer and not a.is_integer():
        return _wrong(t("{name}: {a:g} is not a whole number — count them: a count is a whole number{unit_txt}.",
                        name=name, a=a, unit_txt=unit_txt))
    h = Hints(alternatives, quantities, of_variant, variant, match)
    why = _diagnose(a, e, tol_abs, None if integer else tol_rel, integer, h, rounding if integer else "")
    return _wrong(f"{name}: {why}")


def count_verdict(name: str, answer, expected: int, *, rounding: str = "up", unit: str = "", of_variant=None,
                  variant=None, alternatives: dict | None = None, quantities: dict | None = None,
                  real: float | None = None, hint: str = "", accepted: dict | None = None) -> Verdict:
    """A whole-number answer, exact, with the guide's rounding rule (as :func:`aerophoto.checks.check_count`).

    ``rounding`` is ``"up"``, ``"down"``, ``"nearest"`` (a count rounded from a real quantity — ``real``, when
    given, is that quantity: only its other rounding gets the rounding hint) or ``"exact"`` (a number of things
    or an identifier: no rounding hint; ``hint`` says what to count again).  Another variant's count is never
    suggested: counts coincide between variants too often to tell.  ``accepted`` as in :func:`value_verdict`.
    """
    if rounding not in _ROUNDING:
        raise ValueError(f"rounding = {rounding!r} is not valid; expected one of {sorted(_ROUNDING)}")
    unit_txt = _unit_txt(unit)
    a = scalar(answer)
    noun = t("number") if rounding == "exact" else t("count")
    if a is None or a is Ellipsis:
        return _wrong(t("{name}: no answer yet — replace the ... with your {noun}{unit_txt}.", name=name, noun=noun,
                        unit_txt=unit_txt))
    if is_bool(a):
        return _wrong(t("{name}: {a} is a yes/no verdict — this task asks for a whole number.", name=name, a=a))
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
    for note, alt in (accepted or {}).items():
        if alt is not None and x == float(alt):
            return Verdict(True, t("✓ {name}: correct ({note})", name=name, note=t(note)))
    if not x.is_integer():
        return _wrong(t("{name}: {x:g} is not a whole number — {rule}.", name=name, x=x, rule=t(_ROUNDING[rounding])))
    h = Hints(alternatives, quantities, None, None, 0.0, real, hint)
    why = _diagnose(x, e, None, None, True, h, rounding)
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


def _whole_set_mistake(a, e, wrong, ok, tol_rel, h: Hints) -> str | None:
    """One mistake that explains every entry (a slip, reversed, signs, a unit factor, the order, another variant)."""
    n = len(e)
    for label, value in (h.alternatives or {}).items():
        alt = as_sequence(value)
        if alt is not None and len(alt) == n and all(ok(a[k], float(alt[k])) for k in range(n)):
            return t(label)
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
    if h.of_variant is not None and h.variant is not None:
        match = max(float(h.match), 1e-9)

        def same(w):
            other = [float(x) for x in (as_sequence(h.of_variant(w)) or [])]
            return len(other) == len(a) and all(abs(a[k] - other[k]) <= match * max(1.0, 1e-9) for k in range(len(a)))

        other = _other_variant(h.variant, same)
        if other is not None:
            return _variant_message(other, h.variant)
    return None


def values_verdict(name: str, answers, expected, *, tol_abs: float | None = None, tol_rel: float | None = None,
                   unit: str = "", integer: bool = False, labels=None, of_variant=None, variant=None,
                   alternatives: dict | None = None, match: float = 0.0) -> Verdict:
    """A sequence (or dict) of numbers (as :func:`aerophoto.checks.check_values`; ``alternatives`` are whole
    sequences a slip gives, ``match`` as :class:`Hints`)."""
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
    why = _whole_set_mistake(a, e, wrong, ok, tol_rel, Hints(alternatives, None, of_variant, variant, match))
    if why is None:
        named = ", ".join(labels[k] for k in wrong[:5]) + (" …" if len(wrong) > 5 else "")
        flipped = [k for k in wrong if e[k] != 0 and ok(-a[k], e[k])]
        detail = t(" (the sign of {labels} is wrong)", labels=", ".join(labels[k] for k in flipped)) if flipped else ""
        why = t("{n_wrong} of {n} values are not right: {named}{detail}.", n_wrong=len(wrong), n=len(e), named=named,
                detail=detail)
    return _wrong(f"{name}: {why}")


# ---------------------------------------------------------------------------------------- verdicts, picks
def bool_verdict(name: str, answer, expected: bool, *, hint: str = "", accepted: dict | None = None) -> Verdict:
    """A yes/no verdict (as :func:`aerophoto.checks.check_bool`; ``accepted`` as in :func:`value_verdict`)."""
    if answer is None or answer is Ellipsis:
        return _wrong(t("{name}: no answer yet — replace the ... with True or False.", name=name))
    if not is_bool(answer):
        return _wrong(t("{name}: {answer!r} is not a verdict — write True or False (without quotes).", name=name,
                        answer=answer))
    if bool(answer) == bool(expected):
        return Verdict(True, t("✓ {name}: correct", name=name))
    for note, alt in (accepted or {}).items():
        if alt is not None and bool(answer) == bool(alt):
            return Verdict(True, t("✓ {name}: correct ({note})", name=name, note=t(note)))
    return _wrong(t("{name}: the verdict is wrong — {hint}", name=name,
                    hint=t(hint or "check your value against the guide's tolerance.")))


def choice_verdict(name: str, answer, expected: str, options, *, hint: str = "", accepted: dict | None = None) -> Verdict:
    """One answer picked from named options, case and spaces ignored (as :func:`aerophoto.checks.check_choice`;
    ``accepted`` as in :func:`value_verdict`)."""
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
    for note, alt in (accepted or {}).items():
        if alt is not None and norm(answer) == norm(alt):
            return Verdict(True, t("✓ {name}: correct ({note})", name=name, note=t(note)))
    return _wrong(t("{name}: not this one — {hint}", name=name, hint=t(hint or "read the task's definitions again.")))


VERDICTS = {"value": value_verdict, "count": count_verdict, "values": values_verdict, "bool": bool_verdict,
            "choice": choice_verdict}
"""A task answer's ``kind`` → its verdict function."""


# ------------------------------------------------------------------------------------ a graded task's answer
def told_apart(a, value, expected) -> bool:
    """Whether a slip's ``value`` of answer spec ``a`` can be told from the ``expected`` one: outside the answer's
    tolerance (a number or a sequence), or different (a count).  A slip that cannot is no mistake for this
    variant — its hint is off there."""
    if value is None:
        return False
    try:
        if a.kind == "values":
            alt, exp = as_sequence(value), as_sequence(expected)
            if alt is None or exp is None or len(alt) != len(exp):
                return True
            return not all(close(float(x), float(y), a.tol_abs, a.tol_rel) for x, y in zip(alt, exp))
        if a.kind == "count" or a.integer:
            return float(value) != float(expected)
        if a.kind == "value":
            return not close(float(value), float(expected), a.tol_abs, a.tol_rel)
    except (TypeError, ValueError):
        return True
    return value != expected


def answer_call(task, a, value, expected, slips: Mapping, variant, *, quantities: Mapping | None = None,
                reals: Mapping | None = None, accepted: Mapping | None = None) -> tuple[str, tuple, dict]:
    """(kind, args, keywords) of the verdict on answer spec ``a`` of ``task`` (:mod:`aerophoto.tasks`).

    ``VERDICTS[kind](*args, **keywords)`` gives the verdict; :func:`aerophoto.checks.check_task` calls the
    check of that kind with the same arguments.  An angle (``a.period``) is brought into 0 ≤ value < period;
    a cross-variant task lets the verdict recognise another variant's answer (matched within the rounding a
    student may write the answer with, :meth:`aerophoto.tasks.Task.allowance`); ``slips`` are the task's
    typical mistakes for this variant, ``quantities`` the chapter's other quantities
    (:meth:`~aerophoto.tasks.Task.quantities`), ``reals`` the real quantities behind its rounded counts and
    ``accepted`` the other values it accepts (:meth:`~aerophoto.tasks.Task.accepted`).
    """
    alt = {k: val for k, val in (slips.get(a.name) or {}).items() if told_apart(a, val, expected)} or None
    if a.period:  # an angle: any whole turn is the same answer
        v = scalar(value)
        if isinstance(v, Real) and not is_bool(v) and math.isfinite(v):
            value = float(v) % a.period
    of_variant = None
    match = 0.0
    if task.cross_variant and variant is not None:
        def of_variant(w, _n=a.name):
            return task.answers(w)[_n]
        allow = getattr(task, "allowance", None)
        match = float(allow(a, expected)) if callable(allow) else 0.0
    qty = {k: val for k, val in (quantities or {}).items() if val is not None} or None
    acc = {k: val for k, val in ((accepted or {}).get(a.name) or {}).items() if val is not None} or None
    args = (a.name, value, expected)
    if a.kind == "value":
        return "value", args, dict(tol_abs=a.tol_abs, tol_rel=a.tol_rel, unit=a.unit, integer=a.integer,
                                   of_variant=of_variant, variant=variant, alternatives=alt, quantities=qty,
                                   match=match, accepted=acc, rounding="exact" if a.integer else "up")
    if a.kind == "count":
        return "count", args, dict(rounding=a.rounding, unit=a.unit, alternatives=alt, quantities=qty,
                                   real=(reals or {}).get(a.name), hint=a.hint, accepted=acc)
    if a.kind == "values":
        return "values", args, dict(tol_abs=a.tol_abs, tol_rel=a.tol_rel, unit=a.unit, integer=a.integer,
                                    labels=list(a.labels) or None, of_variant=of_variant, variant=variant,
                                    alternatives=alt, match=match)
    if a.kind == "bool":
        return "bool", args, dict(hint=a.hint, accepted=acc)
    return "choice", args + (a.options,), dict(hint=a.hint, accepted=acc)
