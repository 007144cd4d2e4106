"""The shape of a graded task: what it asks, and what it expects for each variant.

A chapter's graded tasks live in ``aerophoto/tasks/chNN.py``, one frozen
dataclass per task, subclassing :class:`Task`:

* ``id`` — the nbgrader grade id stem, ``"task-NN-k"``; ``points``; ``title``;
* ``spec`` — the answers, in the order of the notebook's answer cell: a tuple
  of :class:`Answer` (variable name, unit, kind, tolerance, …);
* ``inputs(v)`` — what the student works from for variant ``v`` (a DataFrame,
  a dict, or None when the variant itself is the input);
* ``answers(v)`` — the expected value of every answer, ``{name: value}``,
  computed with the package's physics (the reference solution);
* ``slips(v)`` — values that typical mistakes give, ``{name: {hint: value}}``,
  so a check can say *what kind* of mistake it sees;
* ``hidden(v, got)`` — checks the student never sees (consistency between
  their own answers, a second quantity): a list of :class:`Hidden`, evaluated
  on the submitted values ``got``; their tolerances are propagated from the
  rounding the answers they use may carry (:mod:`aerophoto.tasks.rounding`);
* ``methods`` — how the chapter teaches the task: a tuple of :class:`Method`,
  the reference's own and every other method it accepts (a small form, a rounded
  intermediate, the other reading of an article), each with the submission a
  student following it makes.  ``docs/grading_table.md`` is rendered from them
  (``python -m aerophoto.tasks``).

Nothing here imports the student-facing checks: :mod:`aerophoto.checks` runs a
task's visible checks in the notebook, and the instructor's grader runs visible
and hidden checks on values extracted from a sandboxed run.
"""

from __future__ import annotations

import contextlib
import functools
import math
import os
from dataclasses import dataclass
from typing import ClassVar

import numpy as np

__all__ = ["Answer", "Hidden", "Method", "Task", "Withheld", "KINDS", "ROUNDINGS", "submitted_number",
           "answer_calls", "own_answers"]

# ------------------------------------------------------------------ answers asked for while the instructor grades
_ANSWER_CALLS: list = []   # task ids whose answers() was called outside a check, in a grading kernel
_OWN = [0]                 # > 0 while a check computes its own reference values


def answer_calls() -> list:
    """The tasks whose reference answers student code asked for in this kernel while grading (a copy).

    Recorded only with ``AEROPHOTO_GRADING`` set (the grader's sandbox); a check's own use of them
    (:func:`own_answers`) is not recorded.  The check cell's answer record carries the list, and the grader flags
    it (``uses_package_answers``), however the call was made (an alias, an extra cell, a float subclass whose
    ``__float__`` reads the check's frame).
    """
    return list(_ANSWER_CALLS)


@contextlib.contextmanager
def own_answers():
    """The checks' own calls of :meth:`Task.answers` (and ``slips``) are made inside this: not recorded."""
    _OWN[0] += 1
    try:
        yield
    finally:
        _OWN[0] -= 1


def _recorded(fn):
    @functools.wraps(fn)
    def answers(self, v, *args, **kwargs):
        if not _OWN[0] and os.environ.get("AEROPHOTO_GRADING"):
            _ANSWER_CALLS.append(str(getattr(self, "id", "?")))
        return fn(self, v, *args, **kwargs)

    answers._aerophoto_recorded = True
    return answers

KINDS = ("value", "count", "values", "bool", "choice")
ROUNDINGS = ("up", "down", "nearest", "exact")
"""A count's rule: rounded up, down or to the nearest whole number from a real quantity (guide §2's K, n), or
``"exact"`` — a number of things counted or an identifier (points corrected, a cell's row, a point's id),
which has no other rounding."""


@dataclass(frozen=True)
class Answer:
    """One value a task asks for: a variable of the answer cell.

    Attributes
    ----------
    name : str
        The variable, units in the name (``"H_m"``, ``"dh1_mm"``, ``"n_corr"``).
    text : str
        The template line's comment: what it is and its unit ("flying height H = f·m, m").
    unit : str
        Unit shown in messages ("m", "mm", "%", "°"; "" for pure numbers).
    kind : str
        ``"value"`` (a number), ``"count"`` (a whole number, exact, with the
        guide's rounding rule), ``"values"`` (a sequence, a table row or
        column), ``"bool"`` (a verdict) or ``"choice"`` (one named option).
    tol_abs, tol_rel : float or None
        Tolerance (default 0.5 % relative for values; exact for counts).
    rounding : str
        For counts: the guide's rule, ``"up"``, ``"down"`` or ``"nearest"`` from a real quantity, or
        ``"exact"`` for a number of things counted or an identifier (:data:`ROUNDINGS`): only a rounded
        count gets the rounding hint.
    labels : tuple of str
        For sequences: how the task names the entries.
    options : tuple of str
        For choices: every option offered.
    hint : str
        For verdicts, choices and exact counts: what to compare (or count again) when the answer is wrong.
    integer : bool
        For values/sequences: whole numbers compared exactly.
    period : float or None
        For angles: a number answer is brought into 0 ≤ value < period before
        it is checked (360 for degrees), so any whole turn is accepted.
    printed : float or None
        For numbers: the unit of the last digit the task expects written (0.01 for mm to the hundredth, 1 for a
        scale denominator, 0.1 for a per cent to one decimal) — the guide's printed unit for the quantity, or a
        finer one where the task's text asks for more digits.  One number serves three ends: the rounded form
        of the honest submissions the grading sweep tries, the allowance every hidden check propagates from
        (:mod:`aerophoto.tasks.rounding`), and the least tolerance: the visible tolerance is at least half of it
        plus what the chapter's accepted methods need (tests/content/test_grading_methods.py).
    """

    name: str
    text: str = ""
    unit: str = ""
    kind: str = "value"
    tol_abs: float | None = None
    tol_rel: float | None = None
    rounding: str = "up"
    labels: tuple = ()
    options: tuple = ()
    hint: str = ""
    integer: bool = False
    period: float | None = None
    printed: float | None = None

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"kind = {self.kind!r} is not valid; expected one of {KINDS}")
        if self.rounding not in ROUNDINGS:
            raise ValueError(f"rounding = {self.rounding!r} is not valid; expected one of {ROUNDINGS}")
        if self.printed is not None and not (isinstance(self.printed, (int, float)) and self.printed > 0):
            raise ValueError(f"printed = {self.printed!r} is not valid; expected a positive unit (0.01, 1, 10 …)")
        if not self.name.isidentifier():
            raise ValueError(f"name = {self.name!r} is not a Python variable name")


def submitted_number(x) -> float | None:
    """A submitted answer as a float, or None when it is not one finite number (``...``, None, text, a list, a bool).

    For :meth:`Task.hidden`: derive a second quantity from the student's own
    answers only where they are numbers (a :class:`Hidden` with ``answer=None`` fails).
    """
    if getattr(x, "size", None) == 1 and hasattr(x, "item"):  # a one-element array or numpy scalar
        x = x.item()
    if x is None or x is Ellipsis or isinstance(x, (bool, str)):
        return None
    try:
        f = float(x)
    except (TypeError, ValueError):
        return None
    return f if math.isfinite(f) else None


@dataclass(frozen=True)
class Hidden:
    """One hidden check: a quantity derived from the submitted values against what it must equal.

    ``kind`` is ``"value"`` (numbers within ``tol_abs``/``tol_rel``), ``"count"`` (exact, or any of
    ``accepted``) or ``"bool"``.  ``answer`` may be None when the submitted values needed to derive it are
    missing or not numbers: the check then fails.  For ``"value"``, ``answer``, ``expected`` and ``tol_abs``
    may be sequences of one length (checked element by element): :func:`aerophoto.tasks.rounding.consistency`
    builds such a check with the tolerance the rounding of its inputs allows.  ``name`` says what is compared
    ("ZS_m from your own pA_mm"); the student's screen shows it when the check fails, never ``expected``.
    ``about`` names the answer the check holds to the others: when it fails and that answer is one of the task's
    catalogued slips, the screen names the slip instead.
    """

    name: str
    answer: object
    expected: object
    tol_abs: object = None
    tol_rel: float | None = None
    kind: str = "value"
    accepted: tuple = ()
    about: str = ""


@dataclass(frozen=True)
class Method:
    """One way the chapter teaches (or accepts) to reach a task's answers.

    Attributes
    ----------
    name : str
        Short, for the grading table: "exact formula Δp = b₀·h/(H − h)", "K_d rounded to 3 significant digits".
    note : str
        Where the chapter teaches it, or why it is accepted.
    submit : callable or None
        ``submit(task, v) -> {name: value}``: what a student following the method submits for variant ``v``
        (the answers it changes; the others are the reference's).  None: the reference method itself
        (:meth:`Task.answers`).
    reading : str
        For an ambiguous source: ``"adopted"`` (the reading the book takes) or ``"other"`` (the other
        reading, accepted as well); "" otherwise.
    """

    name: str
    note: str = ""
    submit: object = None
    reading: str = ""

    def __post_init__(self):
        if self.reading not in ("", "adopted", "other"):
            raise ValueError(f"reading = {self.reading!r} is not valid; expected '', 'adopted' or 'other'")
        if self.submit is not None and not callable(self.submit):
            raise TypeError(f"submit = {self.submit!r} is not callable; expected submit(task, v) -> dict or None")

    def submission(self, task, v) -> dict:
        """The whole submission of this method for ``v``: the reference answers with the method's changes."""
        ref = dict(task.answers(v))
        if self.submit is None:
            return ref
        return {**ref, **self.submit(task, v)}


@dataclass(frozen=True)
class Task:
    """Base class of a graded task (see the module notes).  Subclasses are frozen dataclasses."""

    id: ClassVar[str] = ""
    title: ClassVar[str] = ""
    points: ClassVar[int] = 1
    spec: ClassVar[tuple] = ()
    #: recognise an answer of another variant (runs ``answers`` for up to 99 variants on a wrong answer)
    cross_variant: ClassVar[bool] = True
    #: score in proportion to the checks passed (otherwise all or nothing, as nbgrader scores a test cell)
    partial: ClassVar[bool] = False
    #: the package's functions the task's text tells the student to work with (``"aerophoto.soilmap.contingency"``):
    #: the book's instruments for this task, so calling them in an answer cell is not flagged
    #: ``uses_package_answers`` (:func:`aerophoto.course.flags.package_answer_functions`)
    tools: ClassVar[tuple] = ()
    #: how the chapter teaches the task (:class:`Method`): the reference first, then every accepted alternative
    methods: ClassVar[tuple] = ()

    def __init_subclass__(cls, **kwargs):
        super().__init_subclass__(**kwargs)
        fn = cls.__dict__.get("answers")
        if fn is not None and not getattr(fn, "_aerophoto_recorded", False):
            cls.answers = _recorded(fn)  # see answer_calls()

    @property
    def chapter(self) -> str:
        """The notebook number, ``"03"`` for ``"task-03-1"``."""
        return self.id.split("-")[1]

    @property
    def names(self) -> tuple:
        """The answer variables, in order."""
        return tuple(a.name for a in self.spec)

    def answer(self, name: str) -> Answer:
        for a in self.spec:
            if a.name == name:
                return a
        raise KeyError(f"{self.id} has no answer {name!r}; its answers are {self.names}")

    def template(self) -> str:
        """The answer cell's template lines, ``name = ...  # text``, aligned."""
        w = max((len(a.name) for a in self.spec), default=0)
        return "\n".join(f"{a.name} = ...{' ' * (w - len(a.name))}   # {a.text}".rstrip() for a in self.spec)

    def inputs(self, v):
        """What the student works from for variant ``v`` (None: the variant's own inputs)."""
        return None

    def answers(self, v) -> dict:
        """The expected answers for variant ``v``: ``{name: value}`` for every name in ``spec``."""
        raise NotImplementedError

    def slips(self, v) -> dict:
        """Values typical mistakes give: ``{name: {hint: value}}`` (hints say what went wrong, never the answer)."""
        return {}

    def quantities(self, v) -> dict:
        """Other quantities of the chapter a wrong answer may be (``{"the base b₀ = B·f/H": 73.8}``).

        An answer equal to one of them is told so ("that is your …") before another variant's answer is
        suspected.  Inputs only, never a graded value of ``v``.
        """
        return {}

    def allowance(self, answer: Answer, value) -> float:
        """How far a written ``value`` of ``answer`` may lie from the value it stands for (its rounding:
        :func:`aerophoto.tasks.rounding.allowance`); the largest over a sequence; 0 for non-numbers."""
        from .rounding import allowance, numbers, width

        x = numbers(value) if answer.kind == "value" else numbers(value, len(value) if hasattr(value, "__len__") else 0)
        if x is None:
            return 0.0
        return float(max(np.ravel(allowance(x, answer.printed, width(answer, x))), default=0.0))

    def accepted(self, v) -> dict:
        """Other values the task accepts for an answer, ``{name: {note: value}}``: another reading of an ambiguous
        source (:class:`Method` with ``reading="other"``).  The ✓ line names the note."""
        return {}

    def reals(self, v) -> dict:
        """The real quantities behind rounded counts, ``{name: float}`` (K from L_y/B_y + 1): the rounding hint
        fires only for the other rounding of this quantity."""
        return {}

    def hidden(self, v, got: dict) -> list:
        """Hidden checks on the submitted values ``got`` (consistency, a second quantity): a list of :class:`Hidden`."""
        return []


class Withheld:
    """A task's inputs with the graded answers taken out: a read-only view of ``obj``.

    Attribute access passes through to ``obj`` except for the names in ``withheld`` (an AttributeError saying
    that this is what the task asks for) and those in ``replace`` (another value in their place, e.g. a view of
    a member).  :func:`aerophoto.tasks.inputs` returns such a view where the lab world itself knows an answer
    (chapter 15's planted blunders).
    """

    __slots__ = ("_obj", "_withheld", "_replace", "_why")

    def __init__(self, obj, withheld=(), replace=None, why: str = "it is what the task asks you to find"):
        object.__setattr__(self, "_obj", obj)
        object.__setattr__(self, "_withheld", frozenset(withheld))
        object.__setattr__(self, "_replace", dict(replace or {}))
        object.__setattr__(self, "_why", why)

    def __getattr__(self, name):
        if name in self._withheld:
            raise AttributeError(f"{name!r} is not given: {self._why}")
        if name in self._replace:
            return self._replace[name]
        return getattr(self._obj, name)

    def __setattr__(self, name, value):
        raise AttributeError(f"the task's inputs are read-only ({name!r})")

    def __dir__(self):
        return sorted((set(dir(self._obj)) | set(self._replace)) - self._withheld)

    def __repr__(self):
        return f"{type(self._obj).__name__}(…, inputs of the task: {', '.join(sorted(self._withheld))} withheld)"
