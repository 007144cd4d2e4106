"""The student's course report (guide §15) and their fotoschema sheet (guide §6, appendix), from their workbook.

::

    from aerophoto import report
    r = report.build("workbook/", student="Иванов И. И.", group="ЗиК 31", date="2026-12-15")
    r.pdf, r.html, r.sheet_pdf

or ``aerophoto-course report workbook/ --student "Иванов И. И."``.  The explanatory note follows §15's 13
sections (Russian headings, English beside), after a title page and the assignment (the variant's inputs);
under each section are the book's chapters for that § of the guide (:mod:`aerophoto.report.sections`,
read from :data:`aerophoto.book.CHAPTERS`, so new chapters appear by themselves), each task with the
student's own values, numbered tables and figures of their own photos.  A task the student has not
answered shows "не выполнено (not done)" and no number — never a reference answer.  The fotoschema sheet
is drawn at true size on the A sheet that holds it, signed with the student's own mean scale (task 05.2).

Security: the workbook is read, never run (:mod:`aerophoto.report.answers`): the answer cells are parsed
and evaluated by a tiny evaluator (numbers, arithmetic, ``math.*``, ``v.<attr>``, earlier answers), and
each task is graded by the trusted check (:func:`aerophoto.course.score.grade_task`) for the variant of the
record book.  Typesetting: Typst (:mod:`aerophoto.report.document`).
"""

from __future__ import annotations

from .build import DEFAULTS, NOT_DONE, ChapterStatus, Report, TaskStatus, build, read_workbook

__all__ = ["build", "read_workbook", "Report", "TaskStatus", "ChapterStatus", "DEFAULTS", "NOT_DONE"]
