"""The graded tasks of every chapter: one module per notebook, one frozen dataclass per task.

``aerophoto.tasks.ch03`` holds the tasks of ``notebooks/03_relief_displacement.ipynb``
(``TASKS = (MeanObjectPlane(), ReliefCorrections())``), each a
:class:`~aerophoto.tasks.base.Task` with ``inputs(v)``, ``answers(v)``,
``slips(v)`` and ``hidden(v, got)`` for the variant ``v``.

Look-ups by grade id::

    from aerophoto import tasks
    t = tasks.get("task-03-1")
    t.answers(v)            # the reference values for variant v
    tasks.inputs("task-03-1", v)

The student-facing checks (:func:`aerophoto.checks.check_task`) and the
instructor's grader (:func:`aerophoto.course.score.grade_task`) both read the task
from here; the notebooks only name the task and pass their variables.
Only the rubrics live here: the students' lab worlds the tasks are set on (the
own strip, the stereo pair, the photo to rectify, the survey block …) are
:mod:`aerophoto.labs`, which this package imports and which never imports it.
Submodules load on first use.
"""

from __future__ import annotations

import functools
import importlib
import re
from collections.abc import Mapping
from types import MappingProxyType

from .. import _chapters
from ..variants import as_variant
from . import rounding
from .base import KINDS, Answer, Hidden, Method, Task, Withheld

__all__ = ["Answer", "Hidden", "Method", "Task", "Withheld", "KINDS", "get", "all_tasks", "chapter_tasks", "inputs",
           "answers", "rounding", "CHAPTER_MODULES", "chapter_modules"]


@functools.cache
def chapter_modules() -> Mapping[str, str]:
    """The chapter modules by notebook number, ``{"00": "ch00", …}`` (read-only): the modules ``chNN`` on disk.

    The naming rule (:mod:`aerophoto._chapters`) replaces a list kept by hand (tests/course/test_chapter_key.py checks
    one module per chapter of :data:`aerophoto.book.CHAPTERS`); read on first use, importing the package reads
    nothing.  ``CHAPTER_MODULES`` is the same mapping.
    """
    return MappingProxyType({name[2:]: name for name in _chapters.chapter_modules(__path__)})


_ID = re.compile(r"^task-(\d\d)-(\d+)$")


def chapter_tasks(number: str) -> tuple:
    """The tasks of notebook ``number`` (``"03"``), in order."""
    number = f"{int(number):02d}" if str(number).isdigit() else str(number)
    mod = chapter_modules().get(number)
    if mod is None:
        raise ValueError(f"chapter {number!r} has no graded tasks; chapters with tasks: {sorted(chapter_modules())}")
    return tuple(importlib.import_module(f".{mod}", __name__).TASKS)


def get(task_id: str) -> Task:
    """The task with grade id stem ``task_id`` (``"task-03-1"``; a ``-answer``/``-check`` suffix is ignored)."""
    stem = re.sub(r"-(answer|check)$", "", str(task_id))
    m = _ID.match(stem)
    if not m:
        raise ValueError(f"task_id = {task_id!r} is not a task id; expected the form 'task-NN-k', e.g. 'task-03-1'")
    for t in chapter_tasks(m.group(1)):
        if t.id == stem:
            return t
    raise ValueError(f"task_id = {task_id!r}: chapter {m.group(1)} has no such task")


def all_tasks() -> tuple:
    """Every graded task of the book, chapter by chapter."""
    return tuple(t for n in chapter_modules() for t in chapter_tasks(n))


def inputs(task_id: str, v):
    """What the student works from in task ``task_id`` for variant ``v`` (shown in the task's data cell).

    ``v`` is a :class:`~aerophoto.variants.Variant` or a record-book number; anything else is an error naming ``v``
    (never the guide's example by default).  The inputs never carry a graded answer of the task (where the lab
    world knows one, a :class:`~aerophoto.tasks.base.Withheld` view leaves it out;
    tests/content/test_task_inputs.py compares every task's inputs with its answers)."""
    return get(task_id).inputs(as_variant(v, "v", none=False))


def answers(task_id: str, v) -> dict:
    """The reference answers of task ``task_id`` for variant ``v`` (the instructor's side; ``v`` as in :func:`inputs`)."""
    return get(task_id).answers(as_variant(v, "v", none=False))


def __getattr__(name: str):
    if name == "CHAPTER_MODULES":
        return chapter_modules()
    if _chapters.CHAPTER_MODULE.fullmatch(name) and name in chapter_modules().values():
        module = importlib.import_module(f".{name}", __name__)
        globals()[name] = module
        return module
    raise AttributeError(f"module 'aerophoto.tasks' has no attribute {name!r}")
