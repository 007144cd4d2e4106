"""The trusted check: the submitted values, graded in the instructor's process for the roster's variant.

A check cell run while grading (``AEROPHOTO_GRADING`` set in the sandbox) emits the values it was given as
plain JSON data (:data:`.wire.ANSWERS_MIME`), before it checks anything.  Here, outside the
student's kernel, those records are read from the locked test cells of the executed notebook (nbgrader
restores the test cells before running them), decoded (:func:`.wire.decode_answers`) and graded
with :func:`.score.grade_task` — visible and hidden checks — for the variant of the *student's*
record-book number, never the one the kernel claims.  That score is the one written into nbgrader's
gradebook (:func:`write_scores`).

A task scores 0 when its record is missing (``no_answer_record``); nbgrader's in-kernel verdict that
differs from the trusted visible verdict is ``tampered``; the record's own variant differing from the
student's is ``variant_mismatch``; what the check saw of the kernel (exception and event hooks, patched
checks, a changed ``AEROPHOTO_*`` environment) is reported as behaviour flags.
"""

from __future__ import annotations

import json
from dataclasses import dataclass, field

from .common import COURSE_ID, Flag, digits, graded_tasks, is_test, nbg
from .outcomes import executed_outcomes
from .score import grade_task
from .wire import ANSWERS_MIME, decode_answers


@dataclass
class Verdict:
    """The trusted grade of one task of one submission."""

    task: str
    check_id: str
    points: float
    score: float = 0.0
    passed: bool = False
    message: str = ""
    in_kernel: bool | None = None     # nbgrader's reading of the executed test cell
    record: dict | None = None
    flags: list = field(default_factory=list)

    def as_dict(self) -> dict:
        return {"task": self.task, "check_id": self.check_id, "points": self.points, "score": self.score,
                "passed": self.passed, "message": self.message, "in_kernel": self.in_kernel,
                "flags": [[f.code, f.message] for f in self.flags]}


def answer_records(nb) -> dict[str, list[dict]]:
    """check grade_id → the answer records found in that test cell's outputs (in order).

    A check cell always leaves its record in its output (:func:`aerophoto.checks.check_task`, under
    :data:`.wire.ANSWERS_MIME`, beside a ``text/plain`` line), so this reads a student's *saved* notebook as well
    as one the grader executed.  Each record is plain JSON data: ``{"task": "task-09-2", "variant": 57,
    "values": {name: encoded value}}`` (and ``"evidence"`` while grading) — untrusted, as everything in a
    submission; decode it with :func:`.wire.decode_answers` or read it with :func:`saved_answers`.
    """
    out: dict[str, list[dict]] = {}
    for cell in nb["cells"]:
        if not is_test(cell):
            continue
        gid = str(nbg(cell).get("grade_id"))
        for o in cell.get("outputs", []):
            data = o.get("data") if isinstance(o.get("data"), dict) else {}
            if ANSWERS_MIME not in data:
                continue
            rec = data[ANSWERS_MIME]
            if isinstance(rec, str):
                try:
                    rec = json.loads(rec)
                except ValueError:
                    rec = None
            if isinstance(rec, dict):
                out.setdefault(gid, []).append(rec)
    return out


def saved_answers(nb) -> dict[str, dict]:
    """The values each task's check cell recorded in a saved notebook: ``{task id: {answer name: value}}``.

    For every check cell with a record (:func:`answer_records`; its first, as the grader takes), the values as
    the check was given them the last time it ran — numbers, strings, booleans, lists and dicts as plain Python
    data (:func:`.wire.decode_answers`); a value that was not plain data (an object, a long list) is an opaque
    string that no check accepts, and ``...`` stands for an answer not given yet.  Tasks whose check cell never
    ran (or ran before this book version) are absent, and so is a record that does not name its own check cell's
    task.  Nothing is executed; a malformed record is skipped.
    The course report (:mod:`aerophoto.report`) reads answers that needed package code from here.
    """
    out: dict[str, dict] = {}
    try:
        records = answer_records(nb)
    except Exception:  # a malformed notebook: nothing recorded that can be read
        return out
    for gid, recs in records.items():
        try:
            task_id, values = decode_answers(recs[0])
        except Exception:
            continue
        if task_id and gid == f"{task_id}-check" and task_id not in out:  # the record of this very check cell
            out[task_id] = values
    return out


def variant_of(record_book):
    """The variant of a record-book number, or None when it has fewer than two digits."""
    from ..variants import variant

    if len(digits(record_book)) < 2:
        return None
    return variant(record_book)


_HOOK_KEYS = {
    "custom_exc": "set_custom_exc: exceptions are handled by the student's code",
    "event_hooks": "IPython event hooks registered",
    "shell_overrides": "IPython shell methods replaced",
    "excepthook": "sys.excepthook replaced",
}


def evidence_flags(record: dict, expected_record_book: str | None, where: str) -> list[Flag]:
    """Behaviour seen by the check in the kernel (the record's ``evidence``) as flags."""
    ev = record.get("evidence") or {}
    if not isinstance(ev, dict):
        return [Flag("tampered", f"{where}: the answer record's evidence is not what the check writes")]
    flags = []
    hooks = [f"{_HOOK_KEYS[k]} ({', '.join(map(str, ev[k]))[:120]})" if isinstance(ev[k], list) else _HOOK_KEYS[k]
             for k in _HOOK_KEYS if ev.get(k)]
    if hooks:
        flags.append(Flag("exception_hooks", f"{where}: " + "; ".join(hooks)))
    calls = ev.get("answer_calls") or []
    if calls:
        flags.append(Flag("uses_package_answers", f"{where}: the student's code asked the package for the reference "
                                                  f"answers in the kernel ({', '.join(map(str, calls))[:160]})"))
    odd = ev.get("value_types") or {}
    if odd:
        flags.append(Flag("tampered", f"{where}: answers of a class defined in the notebook, not numbers: "
                                      + ", ".join(f"{k} ({v})" for k, v in dict(odd).items())[:200]))
    patched = ev.get("patched") or []
    if patched:
        flags.append(Flag("patched_checks", f"{where}: replaced in the kernel: {', '.join(map(str, patched))[:200]}"))
    env = ev.get("env") or {}
    if isinstance(env, dict):
        rb = env.get("AEROPHOTO_RECORD_BOOK")
        changed = []
        if expected_record_book and rb != expected_record_book:
            changed.append(f"AEROPHOTO_RECORD_BOOK = {rb!r} (the grader set {expected_record_book!r})")
        if env.get("AEROPHOTO_GRADING") != "1":
            changed.append(f"AEROPHOTO_GRADING = {env.get('AEROPHOTO_GRADING')!r}")
        if env.get("AEROPHOTO_HOME") not in (None, "/sbx/.aerophoto") and not str(env.get("AEROPHOTO_HOME", "")
                                                                                   ).endswith(".aerophoto"):
            changed.append(f"AEROPHOTO_HOME = {env.get('AEROPHOTO_HOME')!r}")
        if changed:
            flags.append(Flag("variant_changed", f"{where}: the kernel's environment was changed: {'; '.join(changed)}"))
    return flags


def grade_executed(nb, record_book: str | None, *, tasks=None) -> list[Verdict]:
    """The trusted verdict on every task of an executed notebook (see the module notes).

    Never raises for what a submission holds: a task whose record cannot be read or graded (a malformed or
    forged record, a value that breaks the reading) scores 0 with a flag saying why (``unreadable_record``).
    """
    tasks = list(tasks) if tasks is not None else graded_tasks(nb)
    v = variant_of(record_book)
    try:
        records = answer_records(nb)
    except Exception as exc:
        records, broken = {}, f"{type(exc).__name__}: {str(exc)[:120]}"
    else:
        broken = None
    try:
        outcomes = {o.task: o for o in executed_outcomes(nb)[0]}
    except Exception:
        outcomes = {}
    verdicts = []
    for t in tasks:
        out = outcomes.get(t.task)
        vd = Verdict(t.task, t.check_id, float(t.points), in_kernel=None if out is None else out.passed)
        if broken is not None:
            vd.message = f"the answer records could not be read ({broken}); scored 0"
            vd.flags.append(Flag("unreadable_record", f"{t.task}: {vd.message}"))
            verdicts.append(vd)
            continue
        try:
            _grade_task(vd, t, v, out, records.get(t.check_id, []), record_book)
        except Exception as exc:  # the submission's record broke the reading: 0, and say why
            vd = Verdict(t.task, t.check_id, float(t.points), in_kernel=None if out is None else out.passed)
            vd.message = (f"the answer record could not be read or graded ({type(exc).__name__}: "
                          f"{str(exc)[:120]}); scored 0")
            vd.flags.append(Flag("unreadable_record", f"{t.task}: {vd.message}"))
        verdicts.append(vd)
    return verdicts


def _grade_task(vd: Verdict, t, v, out, recs: list, record_book) -> None:
    """Fill ``vd``, the trusted verdict on task ``t`` from its answer records ``recs`` (may raise: the caller
    scores a task whose reading raised 0)."""
    where = t.task
    if v is None:
        vd.message = "no record-book number for this student: the variant, and so the answers, are unknown"
        return
    if not recs:
        why = out.message if out is not None and not out.passed else "the check cell ran no check"
        if out is None:
            why = "the check cell is missing"
        vd.message = f"no answers recorded by the check cell ({why}); scored 0"
        vd.flags.append(Flag("no_answer_record", f"{where}: {vd.message}"))
        if out is not None and out.passed:
            vd.flags.append(Flag("tampered", f"{where}: nbgrader saw the check cell pass, but the check never "
                                             "ran on the answers"))
        return
    rec = recs[0]
    if len(recs) > 1:
        vd.flags.append(Flag("tampered", f"{where}: {len(recs)} answer records in one check cell (the check "
                                         "writes one)"))
    if not isinstance(rec.get("values"), dict) or not all(isinstance(k, str) for k in rec["values"]):
        raise TypeError("the record's values are not a mapping of answer names")
    task_id, values = decode_answers(rec)
    if task_id != t.task:
        vd.flags.append(Flag("tampered", f"{where}: the answer record names {task_id!r}"))
    vd.record = rec
    try:
        grade = grade_task(t.task, v, values)
    except Exception as exc:  # the task itself could not be graded: the grader's problem, say so
        vd.message = f"could not be graded ({type(exc).__name__}: {exc})"
        vd.flags.append(Flag("not_graded", f"{where}: {vd.message}"))
        return
    scale = t.points / grade.points if grade.points else 0.0
    vd.score = round(grade.score * scale, 6)
    vd.passed = grade.passed
    vd.message = grade.first_failure
    claimed = rec.get("variant")
    other_variant = isinstance(claimed, int) and claimed != v.i
    if out is not None and out.passed and not grade.visible_ok and not other_variant:
        vd.flags.append(Flag("tampered", f"{where}: nbgrader saw the check pass in the student's kernel, but "
                                         f"the submitted values fail it ({grade.first_failure[:120]})"))
    elif out is not None and not out.passed and grade.visible_ok and out.ename == "WrongAnswer" and \
            not other_variant:
        vd.flags.append(Flag("tampered", f"{where}: the check failed in the student's kernel, but the "
                                         "submitted values pass it"))
    if other_variant:
        vd.flags.append(Flag("variant_mismatch", f"{where}: the kernel ran variant {claimed:02d}; the "
                                                 f"student's is {v.i:02d} (graded for {v.i:02d})"))
    vd.flags.extend(evidence_flags(rec, record_book, where))


def write_scores(db_url: str, assignment: str, student: str, notebook: str, verdicts) -> None:
    """Put the trusted scores into nbgrader's gradebook (each test cell's ``auto_score``)."""
    from nbgrader.api import Gradebook, MissingEntry

    with Gradebook(db_url, COURSE_ID) as gb:
        for vd in verdicts:
            try:
                g = gb.find_grade(vd.check_id, notebook, assignment, student)
            except MissingEntry:
                continue
            g.auto_score = float(vd.score)
            g.needs_manual_grade = g.manual_score is not None
        gb.db.commit()
