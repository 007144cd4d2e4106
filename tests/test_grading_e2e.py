"""End to end with real nbgrader and its sqlite gradebook: a synthetic class hands in chapter 00.

Everything runs in temporary folders.  The class: a correct answer, a blank notebook, wrong units, a
wrong sign, another student's variant (declared and copied), an infinite loop after a correct answer,
an exception, an edited locked test cell, a deleted and a metadata-stripped test cell, a missing and a
corrupted notebook, and a student id that is not a record-book number (roster).
"""

from __future__ import annotations

import copy
import hashlib
import math
import os
import shutil
import subprocess
import sys
from pathlib import Path

import nbformat
import pandas as pd
import pytest

from aerophoto import course, nbtools
from aerophoto.variants import variant, variant_for_index
from conftest import NOTEBOOKS

pytestmark = pytest.mark.slow

A = "00_start_here"
TIMEOUT = 15  # s per cell: the infinite loop is cut after this


def _elements(v):
    return (v.H_m, v.f_mm * math.tan(math.radians(v.alpha_deg)), -v.f_mm * math.tan(math.radians(v.alpha_deg / 2)))


def _literal_answer(h, on, oc):
    return f"H_m = {h!r}\non_mm = {on!r}\noc_mm = {oc!r}\n"


# student id → (what they hand in, expected score, expected flag codes)
EXPECTED = {
    "19-0401": ("correct", 3.0, []),
    "19-0402": ("blank", 0.0, []),
    "19-0403": ("units", 0.0, []),
    "19-0404": ("sign", 0.0, []),
    "19-0405": ("declares another record book", 3.0, ["record_book_mismatch"]),
    "19-0406": ("copies variant 77's numbers", 0.0, []),
    "19-0407": ("infinite loop after a correct answer", 3.0, ["answer_error"]),
    "19-0408": ("exception", 0.0, ["answer_error"]),
    "19-0409": ("edited test cell", 0.0, ["test_cell_edited"]),
    "19-0410": ("deleted test cell", 0.0, ["test_cell_deleted"]),
    "19-0411": ("stripped test cell", 0.0, ["test_cell_stripped"]),
    "19-0412": ("nothing", 0.0, ["missing"]),
    "19-0413": ("corrupted file", 0.0, ["corrupt"]),
    "ivanov": ("correct numbers for variant 15 (roster: 20-0115), RECORD_BOOK left at None", 3.0, []),
}


B = "01_tiny"  # a second, tiny chapter: the class is graded across two assignments
EXPECTED_B = {"19-0401": (2.0, []), "ivanov": (0.0, [])}  # everyone else: 0, missing


def _tiny_chapter(path: Path) -> None:
    md, code = nbtools.md, nbtools.code
    nbtools.write(nbtools.notebook([
        md("# 01 · A tiny chapter", id="title"),
        code("RECORD_BOOK = None\nimport aerophoto\nv = aerophoto.setup(RECORD_BOOK, live=False)", id="setup"),
        md("## Task 01.1\n\nSet `f_mm`, your focal length in mm.", id="task-01-1"),
        nbtools.nbgrader_answer(code("f_mm = ...  # focal length, mm\n### BEGIN SOLUTION\nf_mm = v.f_mm\n"
                                     "### END SOLUTION", id="task-01-1-answer"), "task-01-1-answer"),
        nbtools.nbgrader_tests(code(
            "from aerophoto import checks\n"
            "checks.check_value('f_mm', f_mm, v.f_mm, unit='mm', variant=v, of_variant=lambda w: w.f_mm)\n"
            "### BEGIN HIDDEN TESTS\nchecks.check_value('f_mm hidden', f_mm, 100 + 10 * v.i, quiet=True)\n"
            "### END HIDDEN TESTS\nchecks.task_passed('task-01-1')", id="task-01-1-check"), "task-01-1-check", 2),
    ], title="01 · tiny"), path)


def _digest(path: Path):
    st = path.stat()
    return hashlib.sha256(path.read_bytes()).hexdigest(), st.st_mtime_ns


@pytest.fixture(scope="module")
def graded(tmp_path_factory):
    """The class graded once: (course, export folder, digests of the export, autograde results, log lines)."""
    top = tmp_path_factory.mktemp("e2e")
    book = top / "notebooks"
    book.mkdir()
    shutil.copy(NOTEBOOKS / f"{A}.ipynb", book)
    _tiny_chapter(book / f"{B}.ipynb")
    (top / "course").mkdir()
    (top / "course" / "roster.csv").write_text("student_id,record_book\nivanov,20-0115\n19-0412,19-0412\n",
                                               encoding="utf-8")
    log: list[str] = []
    c = course.Course(top / "course", book, timeout=TIMEOUT, out=log.append)
    assert c.generate() == {A: True, B: True}

    release = nbformat.read(str(c.path("release", A)), as_version=4)
    source = nbformat.read(str(book / f"{A}.ipynb"), as_version=4)
    solution = nbtools.find_cell(source, "task-00-1-answer")[1].source

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
    units = _literal_answer(h / 1000, on, oc)                      # H in km
    h, on, oc = _elements(variant("19-0404"))
    sign = _literal_answer(h, on, -oc)                             # oc without the guide's sign
    copied = _literal_answer(*_elements(variant_for_index(77)))
    ivanov = _literal_answer(*_elements(variant("20-0115")))
    subs = {
        "19-0401_00_start_here.ipynb": hand_in("19-0401", solution),
        "19-0402_00_start_here.ipynb": hand_in(),
        "19-0403/00_start_here.ipynb": hand_in("19-0403", units),
        "19-0404/00_start_here.ipynb": hand_in("19-0404", sign),
        "19-0405_00_start_here.ipynb": hand_in("19-0477", solution),
        "19-0406_00_start_here.ipynb": hand_in("19-0406", copied),
        "19-0407_00_start_here.ipynb": hand_in("19-0407", solution + "\nwhile True:\n    pass\n"),
        "19-0408_00_start_here.ipynb": hand_in("19-0408", "raise ValueError('oops')\n" + solution),
        "19-0409_00_start_here.ipynb": hand_in("19-0409", None, edit),
        "19-0410/00_start_here.ipynb": hand_in("19-0410", solution, delete),
        "19-0411_00_start_here (1).ipynb": hand_in("19-0411", solution, strip),
        "ivanov_00_start_here.ipynb": hand_in(None, ivanov),
    }
    export = top / "lms-export"
    for name, nb in subs.items():
        (export / name).parent.mkdir(parents=True, exist_ok=True)
        nbformat.write(nb, str(export / name))
    tiny = nbformat.read(str(c.path("release", B)), as_version=4)
    good = copy.deepcopy(tiny)
    nbtools.find_cell(good, "task-01-1-answer")[1].source = "f_mm = v.f_mm"
    nbformat.write(good, str(export / f"19-0401_{B}.ipynb"))
    (export / "ivanov").mkdir()
    nbformat.write(tiny, str(export / "ivanov" / f"{B}.ipynb"))
    (export / "19-0413_00_start_here.ipynb").write_text('{"cells": [{"cell_type": "code", "sour', encoding="utf-8")
    (export / "notes.txt").write_text("collected on Monday", encoding="utf-8")
    (export / "19-0401_99_unknown.ipynb").write_text("{}", encoding="utf-8")
    before = {p: _digest(p) for p in export.rglob("*") if p.is_file()}

    scan = c.import_submissions(export)
    results = c.autograde()
    return c, export, before, scan, results, log


def test_generate_strips_solutions_and_hidden_tests(graded):
    c = graded[0]
    release = nbformat.read(str(c.path("release", A)), as_version=4)
    text = "\n".join(cell.source for cell in release.cells)
    assert "BEGIN SOLUTION" not in text and "HIDDEN TESTS" not in text
    assert "math.tan(math.radians(v.alpha_deg))" not in nbtools.find_cell(release, "task-00-1-answer")[1].source
    assert "on_mm vs oc_mm" not in nbtools.find_cell(release, "task-00-1-check")[1].source
    # the self-study workbook is the same student version
    workbook = course.student_version(nbformat.read(str(c.path("source", A)), as_version=4))
    assert [x.source for x in workbook.cells] == [x.source for x in release.cells]
    assert [x.metadata.get("nbgrader") for x in workbook.cells] == [x.metadata.get("nbgrader") for x in release.cells]


def test_import_copies_and_leaves_the_export_untouched(graded):
    c, export, before, scan, _, log = graded
    assert {p: _digest(p) for p in export.rglob("*") if p.is_file()} == before
    assert set(scan.found) == {(sid, A) for sid in set(EXPECTED) - {"19-0412"}} | {(sid, B) for sid in EXPECTED_B}
    for (sid, a), src in scan.found.items():
        assert c.path("submitted", a, sid).read_bytes() == src.read_bytes()
    assert sorted(p.name for p, _ in scan.unrecognised) == ["19-0401_99_unknown.ipynb", "notes.txt"]
    assert any("unrecognised: notes.txt" in line for line in log)
    assert any("19-0413 · 00_start_here" in line and "not valid JSON" in line for line in log)
    # importing again changes nothing
    again: list[str] = []
    c.out = again.append
    try:
        c.import_submissions(export)
    finally:
        c.out = log.append
    assert again[-1].startswith("import: 0 new, 0 updated, 15 unchanged")


def test_autograde_batch_runs_through_with_progress(graded):
    _, _, _, _, results, log = graded
    assert [(r.student, r.assignment) for r in results] == sorted(
        [(s, A) for s in EXPECTED if s != "19-0412"] + [(s, B) for s in EXPECTED_B])
    status = {(r.student, r.assignment): r.status for r in results}
    assert status.pop(("19-0413", A)) == "corrupt"
    assert set(status.values()) == {"graded"}
    progress = [line for line in log if line.startswith("[") and "/15] " in line and "←" not in line]
    assert len(progress) == 15
    assert progress[0].startswith("[1/15] 19-0401 · 00_start_here: graded 3/3 (")
    assert progress[1].startswith("[2/15] 19-0401 · 01_tiny: graded 2/2 (")
    assert "[6/15] 19-0405 · 00_start_here: graded 3/3" in progress[5] and "record_book_mismatch" in progress[5]
    assert log[-1].startswith("autograde: 15 submission(s)")


def test_gradebook_has_every_student_with_score_and_flags(graded, tmp_path):
    c = graded[0]
    out = tmp_path / "grades.csv"
    assert course.main(["--course", str(c.root), "--notebooks", str(c.notebooks_dir),
                        "gradebook", "--out", str(out)]) == 0
    df = pd.read_csv(out, dtype={"student_id": str, "record_book": str, "flags": str}).fillna(
        {"flags": "", "record_book": ""})
    assert list(df.columns) == ["student_id", "record_book", "assignment", "task-00-1-check", "task-01-1-check",
                                "score", "max_score", "flags"]
    assert sorted(df["student_id"]) == sorted(list(EXPECTED) * 2)
    got = {(r.student_id, r.assignment): (float(r.score), sorted({f.split(":")[0] for f in r.flags.split(" | ") if f}))
           for r in df.itertuples()}
    want = {(sid, A): (score, flags) for sid, (_, score, flags) in EXPECTED.items()}
    want |= {(sid, B): EXPECTED_B.get(sid, (0.0, ["missing"])) for sid in EXPECTED}
    assert got == want
    a, b = df[df["assignment"] == A], df[df["assignment"] == B]
    assert (a["max_score"] == 3.0).all() and (a["task-00-1-check"] == a["score"]).all()
    assert (b["max_score"] == 2.0).all() and (b["task-01-1-check"] == b["score"]).all()
    assert a["task-01-1-check"].isna().all() and b["task-00-1-check"].isna().all()  # not that chapter's task
    a = a.set_index("student_id")
    assert a.loc["ivanov", "record_book"] == "20-0115"
    flags = a["flags"]
    assert "timed out" in flags["19-0407"] and "its test still passed" in flags["19-0407"]
    assert "raised ValueError" in flags["19-0408"]
    assert "'19-0477'" in flags["19-0405"]


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
    assert set(df.columns) == {"record_book", "task-00-1-check", "task-01-1-check", f"total:{A}", f"total:{B}",
                               "score", "max_score", "flags"}
    assert (df.loc["19-0401", ["task-00-1-check", "task-01-1-check", "score", "max_score"]] == [3, 2, 5, 5]).all()
    assert df.loc["ivanov", "score"] == 3.0 and df.loc["19-0412", "score"] == 0.0
    assert df.loc["19-0412", "flags"] == f"{A}: missing: no notebook submitted | {B}: missing: no notebook submitted"


def test_grading_is_deterministic_and_skips_what_is_graded(graded):
    c = graded[0]
    first = c.gradebook()
    log: list[str] = []
    c.out = log.append  # the last test to use the course's progress lines
    again = c.autograde()  # nothing changed: nothing is re-run
    assert {r.status for r in again} == {"up-to-date", "corrupt"}
    regrade = [s for s in EXPECTED if s not in ("19-0407", "19-0412", "19-0413")]
    c.autograde(students=regrade, assignments=[A], force=True)
    assert [line.split(": ", 1)[1].split(" (")[0] for line in log if line.startswith("[")][-len(regrade):] == [
        f"graded {EXPECTED[s][1]:g}/3" for s in sorted(regrade)]
    pd.testing.assert_frame_equal(c.gradebook(), first)


def test_feedback_html_per_student(graded):
    c = graded[0]
    made = c.feedback()
    assert sorted((p.parent.parent.name, p.parent.name) for p in made) == sorted(
        [(s, A) for s in EXPECTED if s not in ("19-0412", "19-0413")] + [(s, B) for s in EXPECTED_B])
    html = (c.root / "feedback" / "19-0401" / A / f"{A}.html").read_text(encoding="utf-8")
    assert "3.0" in html and "task-00-1-check" in html


def test_check_command_exit_codes(graded, tmp_path, capsys):
    c = graded[0]
    good, blank = c.path("submitted", A, "19-0401"), c.path("release", A)
    assert course.main(["check", str(good), "--record-book", "19-0401", "--timeout", str(TIMEOUT)]) == 0
    assert course.main(["check", str(blank), "--record-book", "19-0401", "--timeout", str(TIMEOUT)]) == 1
    out = capsys.readouterr().out
    assert "✓ task-00-1 (3 pt)" in out and "✗ task-00-1 (3 pt) — H_m: no answer yet" in out


def test_cli_works_without_the_venv_on_path(tmp_path):
    """nbgrader runs `alembic` as a subprocess: aerophoto-course must find it from an unactivated venv."""
    book = tmp_path / "notebooks"
    book.mkdir()
    shutil.copy(NOTEBOOKS / f"{A}.ipynb", book)
    exe = Path(sys.executable).parent / "aerophoto-course"
    env = {k: v for k, v in os.environ.items() if k not in ("VIRTUAL_ENV",)}
    env["PATH"] = "/usr/bin:/bin"
    proc = subprocess.run([str(exe), "--course", str(tmp_path / "course"), "--notebooks", str(book), "generate"],
                          capture_output=True, text=True, env=env, cwd=tmp_path, timeout=300)
    assert proc.returncode == 0, proc.stdout + proc.stderr
    assert f"[1/1] generate {A}: released" in proc.stdout
    assert (tmp_path / "course" / "release" / A / f"{A}.ipynb").exists()
    assert (tmp_path / "course" / "gradebook.db").exists()


def test_a_resubmission_replaces_the_earlier_copy_and_is_regraded(graded):
    """Runs last: it changes the class (19-0402 hands in a correct notebook instead of a blank one)."""
    c, export = graded[0], graded[1]
    old = c.path("submitted", A, "19-0402").read_bytes()
    new_file = export / "19-0402_00_start_here.ipynb"
    new_file.write_bytes(c.path("submitted", A, "19-0401").read_bytes().replace(b"19-0401", b"19-0402"))
    os.utime(new_file, (1_000_000, 1_000_000))  # an LMS may keep an old modification time
    c.import_submissions(export)
    kept = list((c.root / "replaced" / "19-0402" / A).glob("*.ipynb"))
    assert len(kept) == 1 and kept[0].read_bytes() == old
    (r,) = c.autograde(students=["19-0402"], assignments=[A])
    assert (r.status, r.score, r.flags) == ("graded", 3.0, [])
