"""The graded-task registry as the course layer reads it: which chapters have tasks, each task's spec and inputs.

:mod:`aerophoto.tasks` is the grading: rubrics, tolerances, slips and hidden
checks.  What lies above it and only *shows* the tasks — the student's course
report (:mod:`aerophoto.report`) — reads them through this module, so that no
presentation or report module reaches into the rubrics themselves
(``tests/course/test_layers.py`` holds that rule).  Grading a submission stays with
:func:`aerophoto.course.score.grade_task`.

Layer 6 (course), beside :mod:`aerophoto.checks`.
"""

from __future__ import annotations

from . import tasks as _tasks

__all__ = ["has_tasks", "chapter_tasks", "task", "task_inputs"]


def has_tasks(number: str) -> bool:
    """True if notebook ``number`` (``"03"``) has graded tasks in the registry."""
    return str(number) in _tasks.CHAPTER_MODULES


def chapter_tasks(number: str) -> tuple:
    """The graded tasks of notebook ``number`` (``"03"``), in order (:class:`aerophoto.tasks.Task` objects).

    Raises ValueError naming ``number`` when the chapter has no tasks.
    """
    return _tasks.chapter_tasks(number)


def task(task_id: str):
    """The task with grade id stem ``task_id`` (``"task-03-1"``): its ``id``, ``title``, ``points`` and ``spec``."""
    return _tasks.get(task_id)


def task_inputs(task_id: str, v):
    """What the student works from in task ``task_id`` for variant ``v`` (the task's data cell; never an answer)."""
    return _tasks.inputs(task_id, v)
