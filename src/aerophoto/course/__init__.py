"""The instructor's command line over nbgrader: ``aerophoto-course``.

=====================================  ==============================================================
``aerophoto-course workbook``          the student book (``notebooks/``, no solutions in it) into
                                       ``workbook/``, never overwriting a student's file
``aerophoto-course teacher [DIR]``     the solved teacher's copy of every chapter (reference solutions
                                       computed by the package), default ``<course>/teacher``
``aerophoto-course check NB...``       run notebooks in the sandbox; pass/fail per task by the trusted
                                       check; exit 1 on a failure, 2 when nothing could be verified
``aerophoto-course generate``          nbgrader's source (reference solutions added) into
                                       ``<course>/source/``, nbgrader generate_assignment → ``release/``
``aerophoto-course import FOLDER``     an LMS export into ``submitted/`` (Moodle's and similar layouts,
                                       atomic per file); the export is never changed
``aerophoto-course autograde``         nbgrader autograde, every student × chapter, each in the sandbox;
                                       the trusted score goes into the gradebook; exit 1 if any
                                       submission could not be graded
``aerophoto-course gradebook``         a CSV: a column per task (grade_id), total, **flags**
``aerophoto-course feedback``          nbgrader's HTML feedback per student (sanitised)
``aerophoto-course strip-solutions``   maintenance: the solution blocks out of the notebooks' answer cells
=====================================  ==============================================================

The parts: :mod:`.common` (paths, config, cells), :mod:`.versions` (student book, nbgrader source, teacher's
copy), :mod:`.limits` (what a sandbox may use), :mod:`.bwrap` (the one bubblewrap recipe, also the hub's),
:mod:`.sandbox` (the host side of a sandbox), :mod:`.sandbox_kernel` (the kernel manager),
:mod:`.sandbox_execute` (nbgrader's Execute in the sandbox), :mod:`.outcomes` (nbgrader's view of an executed
notebook), :mod:`.flags`, :mod:`.lms`, :mod:`.grading` (the course folder, the lock), :mod:`.reports`,
:mod:`.check`, :mod:`.cli`.  Importing this package is cheap; the parts load on first use.

**The answer's road** from the notebook to the gradebook runs one way.  In the student's kernel
:mod:`aerophoto.checks` uses the kernel-side parts — :mod:`.wire` (the answer record; the standard library
only), :mod:`.verdict` (right, or what kind of mistake) and :mod:`.probe` (what the check saw of the kernel)
— none of which imports nbgrader or another part of this package but :mod:`.wire`.  In the instructor's
process :mod:`.trusted` reads the records (:mod:`.wire`) and scores them with :mod:`.score` (the same
:mod:`.verdict`, the hidden checks of :mod:`aerophoto.tasks`).  Nothing in this package imports
:mod:`aerophoto.checks`.

**Student id and record-book number.**  The student id (the name nbgrader and the LMS export use) is the
record-book number (номер зачётной книжки) unless a roster CSV (``course/roster.csv`` or ``--roster``;
columns ``student_id,record_book``) maps it to one.  The variant a submission is graded for is always that
number's — never the one the notebook declares or its kernel ran with (those are flagged).
"""

from __future__ import annotations

import importlib

_EXPORTS = {
    "COURSE_ID": "common", "DEFAULT_TIMEOUT_S": "common", "GradedTask": "common", "Flag": "common",
    "graded_tasks": "common", "release_digest": "common", "default_notebooks_dir": "common",
    "default_course_dir": "common", "chapters": "common", "notebook_problem": "common",
    "student_version": "versions", "source_version": "versions", "teacher_version": "versions",
    "strip_solutions": "versions", "strip_solutions_in": "versions", "write_workbook": "versions",
    "write_teacher": "versions",
    "check_notebook": "check", "CheckResult": "outcomes", "TaskOutcome": "outcomes", "executed_outcomes": "outcomes",
    "parse_record_book": "flags", "inspect_submission": "flags", "code_flags": "flags",
    "package_answer_functions": "flags",
    "scan_submissions": "lms", "Scan": "lms",
    "Course": "grading", "GradeResult": "grading", "CourseBusy": "grading", "course_lock": "grading",
    "grade_executed": "trusted", "answer_records": "trusted",
    "ANSWERS_MIME": "wire", "encode_answers": "wire", "decode_answers": "wire",
    "grade_task": "score", "TaskGrade": "score",
    "Limits": "limits", "BwrapOptions": "bwrap", "bwrap_argv": "bwrap", "sandbox_uid": "bwrap",
    "SandboxUnavailable": "sandbox", "SandboxKernelManager": "sandbox_kernel", "SandboxExecute": "sandbox_execute",
    "main": "cli",
}
"""Every public name of the package → the part that defines it (loaded on first use)."""

__all__ = sorted(_EXPORTS)


def __getattr__(name: str):
    mod = _EXPORTS.get(name)
    if mod is None:
        raise AttributeError(f"module 'aerophoto.course' has no attribute {name!r}")
    value = getattr(importlib.import_module(f".{mod}", __name__), name)
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(__all__))
