"""End to end with real nbgrader, its sqlite gradebook and the sandbox: a synthetic class hands in chapter 00.

Everything runs in temporary folders.  The class: a correct answer, a blank notebook, wrong units, a wrong
sign, another student's variant (declared and copied), an infinite loop after a correct answer, an
exception, an edited locked test cell, a deleted and a metadata-stripped test cell, a missing and a
corrupted notebook, an nbformat-3 file, a student id that is not a record-book number (roster), and an LMS
export mixing flat files, a Moodle participant folder and two students' files in one folder.
(The hostile class — students attacking the grader — is test_grading_hostile.py.)
"""

from __future__ import annotations

import copy
import hashlib
import math
import os
import subprocess
import sys
from pathlib import Path

import nbformat
import pandas as pd
import pytest

from aerophoto import course, nbtools
from aerophoto.course.versions import strip_solutions
from aerophoto.variants import variant, variant_for_index
from conftest import NOTEBOOKS

pytestmark = pytest.mark.slow

A = "00_start_here"
TIMEOUT = 8  # s per cell: the infinite loop is cut after this


def _elements(v):
    return (v.f_mm / 1000 * v.m, v.f_mm * math.tan(math.radians(v.alpha_deg)),
            -v.f_mm * math.tan(math.radians(v.alpha_deg / 2)))


def _literal_answer(h, on, oc):
    return f"H_m = {h!r}\non_mm = {on!r}\noc_mm = {oc!r}\n"



def SOLUTION(sid):
    """A student's own working (the formulas of guide §1, §5), not the package's answer functions; each
    student's differs a little (identical answer code is flagged ``same_code_as``)."""
    return (f"me = {sid!r}\nimport math\nH_m = v.f_mm / 1000 * v.m\n"
            "on_mm = v.f_mm * math.tan(math.radians(v.alpha_deg))\n"
            "oc_mm = -v.f_mm * math.tan(math.radians(v.alpha_deg) / 2)\n")


# student id → (what they hand in, expected score, expected flag codes)
EXPECTED = {
    "19-0401": ("correct", 3.0, []),
    "19-0402": ("blank", 0.0, []),
    "19-0403": ("units (Moodle folder)", 0.0, []),
    "19-0404": ("sign (two students in one folder)", 0.0, []),
    "19-0405": ("declares record book 19-0477 and answers for it", 0.0, ["record_book_mismatch",
                                                                        "variant_mismatch"]),
    "19-0406": ("copies variant 77's numbers (two students in one folder)", 0.0, []),
    "19-0407": ("infinite loop after a correct answer", 3.0, ["answer_error"]),
    "19-0408": ("exception before the answer", 0.0, ["answer_error", "no_answer_record"]),
    "19-0409": ("edited test cell", 0.0, ["test_cell_edited"]),
    "19-0410": ("deleted test cell", 0.0, ["no_answer_record", "test_cell_deleted"]),
    "19-0411": ("stripped test cell", 0.0, ["no_answer_record", "test_cell_stripped"]),
    "19-0412": ("nothing", 0.0, ["missing"]),
    "19-0413": ("corrupted file", 0.0, ["corrupt"]),
    "19-0414": ("correct, saved as nbformat 3", 3.0, []),
    "ivanov": ("correct for variant 15 (roster: 20-0115), RECORD_BOOK left at None", 3.0, []),
}


def _digest(path: Path):
    st = path.stat()
    return hashlib.sha256(path.read_bytes()).hexdigest(), st.st_mtime_ns


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    """The class graded once: (course, export folder, digests of the export, scan, autograde results, log)."""
    top = tmp_path_factory.mktemp("e2e")
    book = top / "notebooks"
    book.mkdir()
    nbtools.write(strip_solutions(nbtools.read(NOTEBOOKS / f"{A}.ipynb"))[0], book / f"{A}.ipynb")
    (top / "course").mkdir()
    (top / "course" / "roster.csv").write_text("student_id,record_book\nivanov,20-0115\n19-0412,19-0412\n",
                                               encoding="utf-8")
    log: list[str] = []
    c = course.Course(top / "course", book, timeout=TIMEOUT, out=log.append)
    assert c.generate() == {A: True}
    release = nbformat.read(str(c.path("release", A)), as_version=4)

    def hand_in(record_book=None, answer=None, edit=None):
        nb = copy.deepcopy(release)
        if record_book is not None:
            setup = nbtools.find_cell(nb, "setup")[1]
            setup.source = setup.source.replace("RECORD_BOOK = None", f'RECORD_BOOK = "{record_book}"')
        if answer is not None:
            nbtools.find_cell(nb, "task-00-1-answer")[1].source = answer
        if edit is not None:
            edit(nb)
        return nb

    def delete(nb):
        del nb.cells[nbtools.find_cell(nb, "task-00-1-check")[0]]

    def strip(nb):
        del nbtools.find_cell(nb, "task-00-1-check")[1].metadata["nbgrader"]

    def edit(nb):
        nbtools.find_cell(nb, "task-00-1-check")[1].source = 'print("✓ all correct")'

    h, on, oc = _elements(variant("19-0403"))
    units = _literal_answer(h / 1000, on, oc)
    h, on, oc = _elements(variant("19-0404"))
    sign = _literal_answer(h, on, -oc)
    copied = _literal_answer(*_elements(variant_for_index(77)))
    ivanov = _literal_answer(*_elements(variant("20-0115")))
    subs = {
        "19-0401_00_start_here.ipynb": hand_in("19-0401", SOLUTION("19-0401")),
        "19-0402_00_start_here.ipynb": hand_in(),
        "Petr Petrov_555001_assignsubmission_file_/19-0403_00_start_here.ipynb": hand_in("19-0403", units),
        "group 2/19-0404_00_start_here.ipynb": hand_in("19-0404", sign),
        "19-0405_00_start_here.ipynb": hand_in("19-0477", SOLUTION("19-0477")),
        "group 2/19-0406_00_start_here.ipynb": hand_in("19-0406", copied),
        "19-0407_00_start_here.ipynb": hand_in("19-0407", SOLUTION("19-0407") + "\nwhile True:\n    pass\n"),
        "19-0408_00_start_here.ipynb": hand_in("19-0408", "raise ValueError('oops')\n" + SOLUTION("19-0408")),
        "19-0409_00_start_here.ipynb": hand_in("19-0409", None, edit),
        "19-0410/00_start_here.ipynb": hand_in("19-0410", SOLUTION("19-0410"), delete),
        "19-0411_00_start_here (1).ipynb": hand_in("19-0411", SOLUTION("19-0411"), strip),
        "ivanov_00_start_here.ipynb": hand_in(None, ivanov),
    }
    export = top / "lms-export"
    for name, nb in subs.items():
        (export / name).parent.mkdir(parents=True, exist_ok=True)
        nbformat.write(nb, str(export / name))
    nbformat.write(nbformat.convert(hand_in("19-0414", SOLUTION("19-0414")), 3), str(export / f"19-0414_{A}.ipynb"), version=3)
    (export / "19-0413_00_start_here.ipynb").write_text('{"cells": [{"cell_type": "code", "sour', encoding="utf-8")
    (export / "notes.txt").write_text("collected on Monday", encoding="utf-8")
    (export / "19-0401_99_unknown.ipynb").write_text("{}", encoding="utf-8")
    before = {p: _digest(p) for p in export.rglob("*") if p.is_file()}

    scan = c.import_submissions(export)
    results = c.autograde()
    return c, export, before, scan, results, log


def test_generate_writes_the_reference_and_releases_without_it(graded):
    c = graded[0]
    source = nbformat.read(str(c.path("source", A)), as_version=4)
    src_answer = nbtools.find_cell(source, "task-00-1-answer")[1].source
    assert "### BEGIN SOLUTION" in src_answer and '_tasks.answers("task-00-1", v)' in src_answer
    release = nbformat.read(str(c.path("release", A)), as_version=4)
    text = "\n".join(cell.source for cell in release.cells)
    assert "SOLUTION" not in text and "_ref" not in text and "HIDDEN TESTS" not in text
    book = nbformat.read(str(c.notebooks_dir / f"{A}.ipynb"), as_version=4)
    assert [x.source for x in book.cells if x.get("id") != "task-00-1-answer"] == [
        x.source for x in release.cells if x.get("id") != "task-00-1-answer"]


def test_import_copies_and_leaves_the_export_untouched(graded):
    c, export, before, scan, _, log = graded
    assert {p: _digest(p) for p in export.rglob("*") if p.is_file()} == before
    assert set(scan.found) == {(sid, A) for sid in set(EXPECTED) - {"19-0412"}}
    for (sid, a), src in scan.found.items():
        if sid != "19-0414":
            assert c.path("submitted", a, sid).read_bytes() == src.read_bytes()
    assert nbformat.reads(c.path("submitted", A, "19-0414").read_text(encoding="utf-8"), as_version=4).nbformat == 4
    assert sorted(p.name for p, _ in scan.unrecognised) == ["19-0401_99_unknown.ipynb", "notes.txt"]
    assert any("unrecognised: notes.txt" in line for line in log)
    assert any("19-0413 · 00_start_here" in line and "not valid JSON" in line for line in log)
    again: list[str] = []
    c.out = again.append
    try:
        c.import_submissions(export)
    finally:
        c.out = log.append
    assert again[-1].startswith("import: 0 new, 0 updated, 14 unchanged")


def test_autograde_batch_runs_through_with_progress(graded):
    _, _, _, _, results, log = graded
    assert [(r.student, r.assignment) for r in results] == sorted((s, A) for s in EXPECTED if s != "19-0412")
    status = {r.student: r.status for r in results}
    assert status.pop("19-0413") == "corrupt"
    assert set(status.values()) == {"graded"}
    progress = [line for line in log if line.startswith("[") and "/14] " in line and "←" not in line]
    assert len(progress) == 14
    assert progress[0].startswith("[1/14] 19-0401 · 00_start_here: graded 3/3 (")
    assert "19-0405 · 00_start_here: graded 0/3" in progress[4] and "record_book_mismatch" in progress[4]
    assert log[-1].startswith("autograde: 14 submission(s)") and "0 could not be graded" in log[-1]


def _csv(c, tmp_path, *extra):
    out = tmp_path / "grades.csv"
    assert course.main(["--course", str(c.root), "--notebooks", str(c.notebooks_dir), "gradebook", "--out", str(out),
                        *extra]) == 0
    return pd.read_csv(out, dtype={"student_id": str, "record_book": str, "flags": str}).fillna(
        {"flags": "", "record_book": ""})


def test_gradebook_has_every_student_with_the_trusted_score_and_flags(graded, tmp_path):
    c = graded[0]
    df = _csv(c, tmp_path)
    assert list(df.columns) == ["student_id", "record_book", "assignment", "task-00-1-check", "score", "max_score",
                                "flags"]
    got = {r.student_id: (float(r.score), sorted({f.split(":")[0] for f in r.flags.split(" | ") if f}))
           for r in df.itertuples()}
    assert got == {sid: (score, flags) for sid, (_, score, flags) in EXPECTED.items()}
    assert (df["max_score"] == 3.0).all() and (df["task-00-1-check"] == df["score"]).all()
    a = df.set_index("student_id")
    assert a.loc["ivanov", "record_book"] == "20-0115"
    assert "timed out" in a.loc["19-0407", "flags"] and "its check still passed" in a.loc["19-0407", "flags"]
    assert "raised ValueError" in a.loc["19-0408", "flags"]
    assert "'19-0477'" in a.loc["19-0405", "flags"] and "variant 77" in a.loc["19-0405", "flags"]


def test_every_graded_submission_has_a_trusted_report(graded):
    c = graded[0]
    for sid, (_, score, _) in EXPECTED.items():
        if sid in ("19-0412", "19-0413"):
            continue
        import json

        rep = json.loads(c.report_path(A, sid).read_text(encoding="utf-8"))
        assert rep["sandbox"] == "bubblewrap" and rep["verdicts"][0]["score"] == score


def test_students_see_what_kind_of_mistake_it_is(graded):
    c = graded[0]

    def check_message(sid):
        nb = nbformat.read(str(c.path("autograded", A, sid)), as_version=4)
        (t,), _ = course.executed_outcomes(nb)
        return t.message

    assert "factor of 1/1000" in check_message("19-0403")
    assert "sign is wrong" in check_message("19-0404")
    assert "variant 77" in check_message("19-0406")
    assert "no answer yet" in check_message("19-0402")
    assert "no answer yet" in check_message("19-0409")  # the restored test cell ran, not the edited one


def test_gradebook_per_student(graded):
    df = graded[0].gradebook(by="student").set_index("student_id")
    assert sorted(df.index) == sorted(EXPECTED)
    assert set(df.columns) == {"record_book", "task-00-1-check", f"total:{A}", "score", "max_score", "flags"}
    assert (df.loc["19-0401", ["task-00-1-check", "score", "max_score"]] == [3, 3, 3]).all()
    assert df.loc["ivanov", "score"] == 3.0 and df.loc["19-0412", "score"] == 0.0
    assert df.loc["19-0412", "flags"] == f"{A}: missing: no notebook submitted"


def test_grading_is_deterministic_and_skips_what_is_graded(graded):
    c = graded[0]
    first = c.gradebook()
    log: list[str] = []
    c.out = log.append
    again = c.autograde()
    assert {r.status for r in again} == {"up-to-date", "corrupt"}
    regrade = ["19-0401", "19-0402", "19-0405", "19-0410"]
    c.autograde(students=regrade, assignments=[A], force=True)
    assert [line.split(": ", 1)[1].split(" (")[0] for line in log if line.startswith("[")][-len(regrade):] == [
        f"graded {EXPECTED[s][1]:g}/3" for s in regrade]
    pd.testing.assert_frame_equal(c.gradebook(), first)


def test_two_grading_runs_at_once_wait_for_each_other(graded):
    c = graded[0]
    first = c.gradebook()
    cmd = [sys.executable, "-m", "aerophoto.course", "--course", str(c.root), "--notebooks", str(c.notebooks_dir),
           "autograde", "--force", "--student", "19-0401", "--student", "19-0402", "--timeout", str(TIMEOUT)]
    procs = [subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True) for _ in range(2)]
    outs = [p.communicate(timeout=300)[0] for p in procs]
    assert [p.returncode for p in procs] == [0, 0], outs
    assert any("waiting: the course folder is in use" in o for o in outs), outs
    assert all("graded 3/3" in o and "graded 0/3" in o for o in outs), outs
    pd.testing.assert_frame_equal(c.gradebook(), first)


def test_autograde_exits_non_zero_when_a_submission_cannot_be_graded(graded, monkeypatch, capsys):
    from aerophoto.course.grading import Course

    c = graded[0]
    monkeypatch.setattr(Course, "_run", lambda self, *a, **k: {"success": False, "log": "[ERROR] disk full"})
    assert course.main(["--course", str(c.root), "--notebooks", str(c.notebooks_dir), "autograde", "--force",
                        "--student", "19-0402"]) == 1
    out = capsys.readouterr().out
    assert "failed 0/3" in out and "1 submission(s) could not be graded: 19-0402" in out
    monkeypatch.undo()
    (r,) = c.autograde(students=["19-0402"], force=True)
    assert (r.status, r.score) == ("graded", 0.0)


def test_feedback_html_per_student(graded):
    c = graded[0]
    made = c.feedback()
    assert sorted(p.parent.parent.name for p in made) == sorted(s for s in EXPECTED if s not in ("19-0412", "19-0413"))
    html = (c.root / "feedback" / "19-0401" / A / f"{A}.html").read_text(encoding="utf-8")
    assert "3.0" in html and "task-00-1-check" in html
    assert not list((c.root / "feedback").rglob("*.json"))  # the trusted reports stay with the instructor


def test_check_command_exit_codes(graded, capsys):
    c = graded[0]
    good, blank = c.path("submitted", A, "19-0401"), c.path("release", A)
    assert course.main(["check", str(good), "--record-book", "19-0401", "--timeout", str(TIMEOUT)]) == 0
    assert course.main(["check", str(blank), "--record-book", "19-0401", "--timeout", str(TIMEOUT)]) == 1
    out = capsys.readouterr().out
    assert "✓ task-00-1 (3 pt)" in out and "✗ task-00-1 (3 pt) — H_m: no answer yet" in out


def test_cli_works_without_the_venv_on_path(tmp_path, graded):
    """nbgrader runs `alembic` as a subprocess: aerophoto-course must find it from an unactivated venv."""
    exe = Path(sys.executable).parent / "aerophoto-course"
    env = {k: v for k, v in os.environ.items() if k not in ("VIRTUAL_ENV",)}
    env["PATH"] = "/usr/bin:/bin"
    proc = subprocess.run([str(exe), "--course", str(tmp_path / "course"), "--notebooks", str(graded[0].notebooks_dir),
                           "generate"], capture_output=True, text=True, env=env, cwd=tmp_path, timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert f"[1/1] generate {A}: released" in proc.stdout
    assert (tmp_path / "course" / "release" / A / f"{A}.ipynb").exists()


def test_a_resubmission_replaces_the_earlier_copy_and_is_regraded(graded):
    """Runs last: it changes the class (19-0402 hands in a correct notebook instead of a blank one)."""
    c, export = graded[0], graded[1]
    old = c.path("submitted", A, "19-0402").read_bytes()
    new_file = export / "19-0402_00_start_here.ipynb"
    nb = nbformat.read(str(c.path("submitted", A, "19-0402")), as_version=4)
    nbtools.find_cell(nb, "task-00-1-answer")[1].source = _literal_answer(*_elements(variant("19-0402")))
    nbformat.write(nb, str(new_file))
    os.utime(new_file, (1_000_000, 1_000_000))  # an LMS may keep an old modification time
    c.import_submissions(export)
    kept = list((c.root / "replaced" / "19-0402" / A).glob("*.ipynb"))
    assert len(kept) == 1 and kept[0].read_bytes() == old
    (r,) = c.autograde(students=["19-0402"], assignments=[A])
    assert (r.status, r.score, r.flags) == ("graded", 3.0, [])
