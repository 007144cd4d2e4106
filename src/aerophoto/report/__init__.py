"""The student's explanatory note (guide §15) and their fotoschema sheet (guide §6, appendix 1), from their workbook.

::

    from aerophoto import report
    r = report.build("workbook/", student="Иванова А. А.", group="ЗиК 31", checked_by="Пресняков В. В.")
    r.pdf, r.html, r.sheet_pdf

or ``aerophoto-course report workbook/ --student "Иванова А. А."``.  The note is written in Russian (``lang="en"``
for English) in the guide's order: title page, contents, introduction (the task and the variant's inputs), §15's
13 sections and the four article chapters, conclusion, sources, appendices (:mod:`aerophoto.report.frame`).  Each
section is written from the student's own values — a few sentences per step, the formulas with their numbers, the
guide's tables 1–13 in their layout, the section's figures and a conclusion (:mod:`aerophoto.report.write_survey`
… :mod:`aerophoto.report.write_articles`); numbers in the book's format (:mod:`aerophoto.i18n.numfmt`).  A task
not answered says so and shows no number — never a reference value; a figure that shows a graded value appears
only once its task has passed.

Security: the workbook is read, never run (:mod:`aerophoto.report.answers`); what a check cell recorded is read as
plain data; no text of the student becomes Typst markup (the template reads JSON, :mod:`aerophoto.report.document`).
Speed: the slow parts (the reference worlds behind the checks, the tasks' data, the figures, the sheet) are kept in
the student's verified cache (:mod:`aerophoto.diskcache`), which the instructor's grading never reads.
"""

from __future__ import annotations

from .build import DEFAULTS, NOT_DONE, ChapterStatus, Report, TaskStatus, build, read_workbook

__all__ = ["build", "read_workbook", "Report", "TaskStatus", "ChapterStatus", "DEFAULTS", "NOT_DONE"]
