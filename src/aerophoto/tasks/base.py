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
  on the submitted values ``got``.

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

__all__ = ["Answer", "Hidden", "Task", "KINDS", "submitted_number", "answer_calls", "own_answers"]

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
        For counts: the guide's rule, ``"up"``, ``"down"`` or ``"nearest"``.
    labels : tuple of str
        For sequences: how the task names the entries.
    options : tuple of str
        For choices: every option offered.
    hint : str
        For verdicts and choices: what to compare when the answer is wrong.
    integer : bool
        For values/sequences: whole numbers compared exactly.
    period : float or None
        For angles: a number answer is brought into 0 ≤ value < period before
        it is checked (360 for degrees), so any whole turn is accepted.
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

    def __post_init__(self):
        if self.kind not in KINDS:
            raise ValueError(f"kind = {self.kind!r} is not valid; expected one of {KINDS}")
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

    ``kind`` is ``"value"`` (numbers within ``tol_abs``/``tol_rel``), ``"count"``
    (exact) or ``"bool"``.  ``answer`` may be None when the submitted values
    needed to derive it are missing or not numbers: the check then fails.
    """

    name: str
    answer: object
    expected: object
    tol_abs: float | None = None
    tol_rel: float | None = None
    kind: str = "value"


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

    def hidden(self, v, got: dict) -> list:
        """Hidden checks on the submitted values ``got`` (consistency, a second quantity): a list of :class:`Hidden`."""
        return []
