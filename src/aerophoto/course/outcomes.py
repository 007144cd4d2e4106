"""nbgrader's view of an executed notebook: pass/fail per test cell, the errors outside the tests.

nbgrader scores an executed test cell 0 when it raised or wrote to ``stderr`` (:func:`test_outcome`);
:func:`executed_outcomes` reads that verdict for every graded task of a notebook — the in-kernel result the
trusted score (:mod:`.trusted`) is compared with — and :class:`CheckResult` is what ``aerophoto-course check``
reports.  Plain notebook data: no nbgrader, no kernel.
"""

from __future__ import annotations

from dataclasses import dataclass, field
from pathlib import Path

from .common import graded_tasks, is_test, nbg, one_line

__all__ = ["TaskOutcome", "CheckResult", "error_outputs", "test_outcome", "executed_outcomes"]


@dataclass
class TaskOutcome:
    task: str
    passed: bool
    points: float
    message: str = ""
    ename: str = ""     # the exception of a failed check ("WrongAnswer" for a check's verdict)
    score: float | None = None


@dataclass
class CheckResult:
    path: Path
    tasks: list[TaskOutcome] = field(default_factory=list)
    errors: list[tuple[str, str]] = field(default_factory=list)  # (cell id, "Ename: value") outside tests
    flags: list = field(default_factory=list)
    problem: str = ""    # why nothing could be verified (unknown kernel, no record book, no tasks)

    @property
    def ok(self) -> bool:
        return bool(self.tasks) and not self.problem and all(t.passed for t in self.tasks) and not self.errors


def error_outputs(cell) -> list[dict]:
    return [o for o in cell.get("outputs", []) if o.get("output_type") == "error"]


def _stderr_text(cell) -> str:
    return "".join(
        "".join(o.get("text", "")) if isinstance(o.get("text"), list) else o.get("text", "")
        for o in cell.get("outputs", [])
        if o.get("output_type") == "stream" and o.get("name") == "stderr"
    )


def test_outcome(cell) -> tuple[bool, str, str]:
    """nbgrader's rule for an executed test cell: an error or any stderr output scores 0.

    Returns (passed, message, exception name)."""
    errs = error_outputs(cell)
    if errs:
        e = errs[0]
        msg = one_line(e.get("evalue", ""))
        ename = str(e.get("ename", ""))
        return False, (msg if ename == "WrongAnswer" and msg else f"{ename}: {msg}".rstrip(": ")), ename
    err = _stderr_text(cell)
    if err.strip():
        return False, "the check printed to stderr (nbgrader scores that 0): " + one_line(err), "stderr"
    return True, "", ""


def executed_outcomes(nb) -> tuple[list[TaskOutcome], list[tuple[str, str]]]:
    """Per-task pass/fail (nbgrader's in-kernel view) and the errors outside test cells of an executed notebook."""
    outcomes, errors = [], []
    tests = {t.check_id: t for t in graded_tasks(nb)}
    for cell in nb["cells"]:
        if cell.get("cell_type") != "code":
            continue
        if is_test(cell):
            gid = nbg(cell).get("grade_id")
            ok, msg, ename = test_outcome(cell)
            outcomes.append(TaskOutcome(tests[gid].task, ok, tests[gid].points, msg, ename))
        else:
            for e in error_outputs(cell):
                errors.append((cell.get("id", "?"), f"{e.get('ename')}: {one_line(e.get('evalue', ''))}".rstrip(": ")))
    return outcomes, errors
