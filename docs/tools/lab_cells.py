"""Cells shared by the chapters' build scripts (03, 04, 05, 06, 09, 12–17): a task's answer cell and its check cell.

The answer cell holds the task's template lines only (``Task.template()``): the notebooks are the student book,
with no solution anywhere (docs/CONTRIBUTING.md, "Graded tasks"); ``aerophoto.course`` generates nbgrader's
source and the solved teacher's copy from them.  The check cell is the two-line ``checks.check_task`` call with
nbgrader's test metadata.
"""

from aerophoto import tasks
from aerophoto.nbtools import code, nbgrader_answer, nbgrader_tests


def answer_cell(task_id: str):
    """The answer cell: the task's template lines (``name = ...   # what, unit``), in the order of its spec."""
    t = tasks.get(task_id)
    return nbgrader_answer(code(t.template(), id=f"{task_id}-answer"), f"{task_id}-answer")


def check_cell(task_id: str):
    """The check cell: exactly two lines, nbgrader test metadata with the task's points."""
    t = tasks.get(task_id)
    args = ", ".join(f"{n}={n}" for n in t.names)
    src = f'from aerophoto import checks\nchecks.check_task("{task_id}", v, {args})'
    return nbgrader_tests(code(src, id=f"{task_id}-check"), f"{task_id}-check", t.points)
