"""The trusted scores written by any nbgrader autograde, not only by ``aerophoto-course autograde``.

nbgrader's ``SaveAutoGrades`` writes the score the student's kernel gave itself (a check cell that did not
raise is full marks).  :class:`TrustedScores`, right after it in ``Autograde.autograde_preprocessors`` (every
configuration the project ships: :func:`aerophoto.course.nbconfig.secure_nbgrader`), replaces those scores with
the trusted check's (:func:`aerophoto.course.trusted.grade_executed`, in this process, for the student's own
variant) — so the formgrader's *Autograde* button and a plain ``nbgrader autograde`` leave the same scores in
gradebook.db as ``aerophoto-course autograde`` (which switches this off and does the same with its report).

The student's record-book number: ``record_book`` if set, else the course folder's ``roster.csv``
(``student_id,record_book``), else the student id.  Whatever fails here scores the notebook 0 (never the
kernel's score) and is logged.
"""

from __future__ import annotations

from pathlib import Path

from nbgrader.preprocessors import NbGraderPreprocessor
from traitlets import Unicode

__all__ = ["TrustedScores"]


class TrustedScores(NbGraderPreprocessor):
    """nbgrader preprocessor: the gradebook's auto scores of this notebook := the trusted check's."""

    record_book = Unicode(None, allow_none=True).tag(config=True)

    def _record_book(self, student: str) -> str:
        if self.record_book:
            return self.record_book
        root = self.config.CourseDirectory.get("root") if "CourseDirectory" in self.config else None
        roster = Path(str(root or ".")) / "roster.csv"
        if roster.is_file():
            from .common import read_roster

            try:
                return read_roster(roster).get(student, student)
            except (OSError, ValueError):
                pass
        return student

    def preprocess(self, nb, resources):
        from .trusted import Verdict, grade_executed, write_scores
        from .common import graded_tasks

        nbr = resources["nbgrader"]
        student, assignment, notebook = nbr["student"], nbr["assignment"], nbr["notebook"]
        tasks = []
        try:
            tasks = graded_tasks(nb)
            verdicts = grade_executed(nb, self._record_book(student), tasks=tasks)
        except Exception as exc:  # never the kernel's score: 0, and say why
            self.log.error("TrustedScores: %s · %s could not be graded (%s: %s); scored 0", student, assignment,
                           type(exc).__name__, exc)
            verdicts = [Verdict(t.task, t.check_id, float(t.points)) for t in tasks]
        write_scores(nbr["db_url"], assignment, student, notebook, verdicts)
        return nb, resources
