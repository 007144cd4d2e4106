"""The grading sweep: every task × variants × honest forms of its answers, on screen and in the grader.

For one task and one variant, :func:`sweep_one` builds the honest submissions a student may hand in —

* ``reference``: the package's answers;
* ``4 digits``: every number rounded to four significant digits (an answer whose visible check that rounding
  would fail is left as it is: its task asks for more digits, and says so);
* ``printed``: every number rounded to its :attr:`~aerophoto.tasks.Answer.printed` unit;
* one per accepted method of :attr:`aerophoto.tasks.Task.methods` (and that method rounded to printed units);

and one submission per catalogued slip (the reference with that one answer replaced by the slip's value).  Each
is run through the student's check cell (:func:`aerophoto.checks.check_task`, what the screen shows) and the
instructor's trusted scorer (:func:`aerophoto.course.score.grade_task`).  An :class:`Outcome` records both.

:func:`cached_references` memoises every task's ``answers``/``slips``/``quantities`` per variant for a run
(the sweep computes each once per variant, however many forms and cross-variant look-ups need it).
"""

from __future__ import annotations

import contextlib
import copy
import io
import math
from dataclasses import dataclass, field

import numpy as np

from aerophoto import checks, tasks
from aerophoto.course import score
from aerophoto.tasks import rounding

FORMS = ("reference", "4 digits", "printed")


@dataclass
class Outcome:
    """One submission of one task for one variant: what the screen said and what the grader gave."""

    task: str
    variant: int
    form: str
    screen_ok: bool
    screen_text: str
    grade_score: float
    points: float
    grade_text: str
    hints: tuple = ()              # for a slip: the hints that name it (one must be told)
    deviation: dict = field(default_factory=dict)   # answer → |submitted − reference| (numbers only)

    @property
    def honest(self) -> bool:
        return not self.form.startswith("slip")

    @property
    def split(self) -> bool:
        """The screen and the grader disagree (passed on screen and marked down, or the reverse)."""
        return self.screen_ok != (self.grade_score == self.points)

    @property
    def full_marks(self) -> bool:
        return self.grade_score == self.points

    def problem(self) -> str | None:
        """Why this outcome is wrong for the sweep, or None."""
        if self.split:
            return f"split verdict: screen {'✓' if self.screen_ok else '✗'}, grader {self.grade_score:g}/{self.points:g}"
        if self.honest and not self.full_marks:
            return f"honest form marked down: {self.grade_score:g}/{self.points:g} — {self.grade_text}"
        if not self.honest:
            if self.full_marks:
                return "slip accepted"
            if self.hints and not any(_said(h, self.screen_text) for h in self.hints):
                return f"slip not named: {self.screen_text!r}"
        return None


# ------------------------------------------------------------------------------------------------ caching
@contextlib.contextmanager
def cached_references():
    """Within: every task's ``answers``, ``slips``, ``quantities`` and ``reals`` computed once per variant."""
    saved = []
    for task in tasks.all_tasks():
        cls = type(task)
        for meth in ("answers", "slips", "quantities", "reals"):
            if any(c is cls and m == meth for c, m, _ in saved):
                continue
            orig = getattr(cls, meth)
            memo: dict = {}

            def cached(self, v, *args, _orig=orig, _memo=memo, **kw):
                key = (type(self).__name__, int(v.i))
                if key not in _memo:
                    _memo[key] = _orig(self, v, *args, **kw)
                return copy.deepcopy(_memo[key])

            cached._aerophoto_recorded = True  # noqa: SLF001  (not re-wrapped by Task.__init_subclass__)
            saved.append((cls, meth, cls.__dict__.get(meth)))
            setattr(cls, meth, cached)
    try:
        yield
    finally:
        for cls, meth, orig in reversed(saved):
            if orig is None:
                delattr(cls, meth)
            else:
                setattr(cls, meth, orig)


# ------------------------------------------------------------------------------------------------ forms
def _is_number(x) -> bool:
    return isinstance(x, (int, float, np.integer, np.floating)) and not isinstance(x, (bool, np.bool_))


def _round_answer(a, x, how: str):
    """Answer ``x`` of spec ``a`` rounded the way ``how`` says (numbers only; counts, verdicts, names unchanged).

    "4 digits" rounds wherever four significant digits are within the answer's tolerance whatever the digits
    (:func:`aerophoto.tasks.rounding.four_digits`, the rule the hidden checks' allowances use); elsewhere the task
    asks for more digits and the value is left as it is."""
    if a.kind not in ("value", "values") or a.integer:
        return x
    if a.kind == "value" and not _is_number(x):
        return x
    arr = np.asarray(x, dtype=float)
    r = rounding.four_digits(arr, a) if how == "4 digits" else rounding.round_to(arr, a.printed)
    return float(r) if a.kind == "value" else [float(e) for e in np.ravel(r)]


def rounded(task, v, ref: dict, how: str) -> dict:
    """The reference ``ref`` of ``task`` rounded (``how``: "4 digits" or "printed")."""
    return {a.name: _round_answer(a, ref[a.name], how) for a in task.spec}


def forms(task, v) -> list[tuple[str, dict]]:
    """The honest submissions of ``task`` for variant ``v``: (form name, {answer: value})."""
    ref = task.answers(v)
    out = [("reference", ref), ("4 digits", rounded(task, v, ref, "4 digits")),
           ("printed", rounded(task, v, ref, "printed"))]
    for m in getattr(task, "methods", ()):
        if m.submit is None:
            continue
        sub = m.submission(task, v)
        out.append((f"method: {m.name}", sub))
        out.append((f"method: {m.name}, printed", rounded(task, v, sub, "printed")))
    return out


def slip_forms(task, v) -> list[tuple[str, tuple, dict]]:
    """(form name, hints, submission) of every catalogued slip of ``task`` that ``v`` tells apart from the answer
    (:func:`aerophoto.course.verdict.told_apart`); ``hints`` are the hints of every slip of that answer with the
    same value (any of them names the mistake)."""
    from aerophoto.course.verdict import close, told_apart

    ref = task.answers(v)
    out = []
    for name, hints in (task.slips(v) or {}).items():
        a = task.answer(name)
        live = {h: x for h, x in hints.items() if told_apart(a, x, ref[name])}
        for hint, value in live.items():
            same = tuple(h for h, x in live.items() if h == hint or (a.kind == "value" and not a.integer and close(
                float(x), float(value), a.tol_abs, a.tol_rel)) or (a.kind != "value" and x == value))
            out.append((f"slip: {name}: {hint[:40]}", same, {**ref, name: value}))
    return out


# ------------------------------------------------------------------------------------------------ running
def _screen(task_id: str, v, sub: dict) -> tuple[bool, str]:
    """What the check cell shows: (passed, its text)."""
    buf = io.StringIO()
    try:
        with contextlib.redirect_stdout(buf):
            checks.check_task(task_id, v, **sub)
    except checks.WrongAnswer as exc:
        return False, buf.getvalue() + str(exc)
    return True, buf.getvalue()


def _deviation(task, ref: dict, sub: dict) -> dict:
    dev = {}
    for a in task.spec:
        x, r = sub.get(a.name), ref.get(a.name)
        if a.kind == "value" and _is_number(x) and _is_number(r):
            dev[a.name] = abs(float(x) - float(r))
        elif a.kind == "values":
            try:
                dev[a.name] = float(np.max(np.abs(np.asarray(x, float) - np.asarray(r, float))))
            except (TypeError, ValueError):
                pass
    return dev


def _said(hint: str, text: str) -> bool:
    from aerophoto.i18n import t

    return t(hint) in text


def run(task, v, form: str, sub: dict, hints: tuple = ()) -> Outcome:
    ok, text = _screen(task.id, v, sub)
    g = score.grade_task(task.id, v, sub)
    return Outcome(task.id, int(v.i), form, ok, text, g.score, g.points, g.first_failure, tuple(hints),
                   _deviation(task, task.answers(v), sub))


def sweep_one(task, v) -> list[Outcome]:
    """Every honest form and every slip of ``task`` for variant ``v``, on screen and in the grader."""
    checks.reset()
    out = [run(task, v, form, sub) for form, sub in forms(task, v)]
    out += [run(task, v, form, sub, hints) for form, hints, sub in slip_forms(task, v)]
    checks.reset()
    return out


def summary(outcomes) -> dict:
    """Counts: submissions, split verdicts, honest marked down, slips accepted or not named."""
    outcomes = list(outcomes)
    return {"submissions": len(outcomes), "split": sum(o.split for o in outcomes),
            "honest marked down": sum(o.honest and not o.full_marks for o in outcomes),
            "slips accepted": sum((not o.honest) and o.full_marks for o in outcomes),
            "slips not named": sum((not o.honest) and not o.full_marks and bool(o.hints)
                                   and not any(_said(h, o.screen_text) for h in o.hints) for o in outcomes)}


def is_finite_number(x) -> bool:
    return _is_number(x) and math.isfinite(float(x))
