"""aerophoto.course without running a kernel: the versions of a chapter, LMS exports, flags, the trusted
check on recorded answers, the lock, atomic import, the CLI's refusals.

The end-to-end runs with real nbgrader, its gradebook and the sandbox are in test_grading_e2e.py and
test_grading_hostile.py.
"""

from __future__ import annotations

import copy
import json
import os
import sys
import threading
import time
from pathlib import Path

import nbformat
import pytest

from aerophoto import course, nbtools
from aerophoto.course import Flag, graded_tasks, inspect_submission, parse_record_book, scan_submissions, wire
from aerophoto.course.common import ensure_path, read_roster, template_path, write_atomic
from aerophoto.course.flags import answer_code, code_flags, package_answer_functions, same_code_groups
from aerophoto.course.trusted import grade_executed
from aerophoto.course.versions import source_version, strip_solutions, student_version, teacher_version
from aerophoto.variants import variant, variant_for_index
from conftest import NOTEBOOKS

SOURCE = NOTEBOOKS / "00_start_here.ipynb"
A = "00_start_here"


def read(path):
    return nbformat.read(str(path), as_version=4)


@pytest.fixture(scope="module")
def student_book():
    """Chapter 00 as the student book (stripped here, so the tests hold before and after the notebooks are)."""
    return strip_solutions(read(SOURCE))[0]


@pytest.fixture(scope="module")
def release(student_book):
    return student_version(source_version(student_book))


@pytest.fixture
def book(tmp_path, student_book):
    """A small book: chapter 00 (student book) and a picture beside it."""
    d = tmp_path / "notebooks"
    d.mkdir()
    nbtools.write(copy.deepcopy(student_book), d / f"{A}.ipynb")
    (d / "figures").mkdir()
    (d / "figures" / "frame.png").write_bytes(b"\x89PNG fake")
    return d


def codes(flags):
    return sorted(f.code for f in flags)


def answer(nb):
    return nbtools.find_cell(nb, "task-00-1-answer")[1]


TEMPLATE = ["H_m = ...     # flying height, m", "on_mm = ...   # o to n, mm",
            "oc_mm = ...   # o to c with the guide's sign, mm"]


# ------------------------------------------------------------------------------------ versions


def test_graded_tasks_of_the_reference_chapter(student_book, release):
    assert graded_tasks(student_book) == [course.GradedTask("task-00-1", "task-00-1-answer", "task-00-1-check", 3.0)]
    assert graded_tasks(release) == graded_tasks(student_book)


def test_the_student_book_holds_template_lines_only(student_book):
    assert answer(student_book).source.splitlines() == TEMPLATE
    assert answer(student_book).metadata.nbgrader["solution"] is True
    text = json.dumps(student_book)
    assert "SOLUTION" not in text and "_ref" not in text and "math.tan" not in answer(student_book).source


def test_nbgrader_source_and_teacher_copy_carry_the_packages_reference(student_book):
    src = answer(source_version(student_book)).source.splitlines()
    assert src[:3] == TEMPLATE and src[3] == "### BEGIN SOLUTION" and src[-1] == "### END SOLUTION"
    assert '_ref = _tasks.answers("task-00-1", v)' in src and 'oc_mm = _ref["oc_mm"]' in src
    teacher = answer(teacher_version(student_book)).source
    assert "..." not in teacher and "SOLUTION" not in teacher and 'H_m = _ref["H_m"]' in teacher
    # the same result from a chapter that still carries its old solution block
    old = copy.deepcopy(student_book)
    answer(old).source += "\n### BEGIN SOLUTION\nH_m = 1\non_mm = 2\noc_mm = 3\n### END SOLUTION"
    assert answer(source_version(old)).source == answer(source_version(student_book)).source
    assert answer(teacher_version(old)).source == teacher


def test_release_strips_the_reference_and_keeps_the_check(release, student_book):
    ans = answer(release)
    chk = nbtools.find_cell(release, "task-00-1-check")[1]
    assert ans.source.splitlines()[:3] == TEMPLATE
    assert "SOLUTION" not in ans.source and "_ref" not in ans.source and "NotImplementedError" not in ans.source
    assert chk.source == nbtools.find_cell(student_book, "task-00-1-check")[1].source
    assert chk.source.rstrip().endswith('checks.check_task("task-00-1", v, H_m=H_m, on_mm=on_mm, oc_mm=oc_mm)')
    assert chk.metadata.nbgrader["checksum"] and chk.metadata.nbgrader["locked"]
    assert not nbtools.has_outputs(release)


def test_strip_solutions_is_rerunnable_and_keeps_other_cells(student_book, tmp_path):
    old = copy.deepcopy(student_book)
    answer(old).source += "\n### BEGIN SOLUTION\nimport math\nH_m = v.f_mm / 1000 * v.m\n### END SOLUTION"
    chk = nbtools.find_cell(old, "task-00-1-check")[1]
    chk.source += "\n### BEGIN HIDDEN TESTS\nchecks.check_value('x', 1, 1)\n### END HIDDEN TESTS"
    new, changed = strip_solutions(old)
    assert changed == ["task-00-1-answer", "task-00-1-check"]
    assert answer(new).source.splitlines() == TEMPLATE and "HIDDEN" not in nbtools.find_cell(new, "task-00-1-check")[1].source
    assert [c.source for c in new.cells if c.get("id") not in ("task-00-1-answer", "task-00-1-check")] == [
        c.source for c in old.cells if c.get("id") not in ("task-00-1-answer", "task-00-1-check")]
    assert strip_solutions(new)[1] == []
    # a template line lost by the author comes back from the task's spec
    broken = copy.deepcopy(old)
    answer(broken).source = "### BEGIN SOLUTION\nH_m = 1\n### END SOLUTION"
    assert answer(strip_solutions(broken)[0]).source.splitlines() == TEMPLATE
    # the folder version and the CLI's dry run
    d = tmp_path / "nbs"
    d.mkdir()
    nbtools.write(old, d / f"{A}.ipynb")
    before = (d / f"{A}.ipynb").read_bytes()
    assert course.main(["strip-solutions", str(d), "--dry-run"]) == 0
    assert (d / f"{A}.ipynb").read_bytes() == before
    assert course.main(["strip-solutions", str(d)]) == 0
    assert answer(read(d / f"{A}.ipynb")).source.splitlines() == TEMPLATE
    after = (d / f"{A}.ipynb").read_bytes()
    assert course.main(["strip-solutions", str(d)]) == 0 and (d / f"{A}.ipynb").read_bytes() == after


def test_an_answer_cell_without_a_registered_task_cannot_be_solved(student_book):
    nb = copy.deepcopy(student_book)
    answer(nb).metadata.nbgrader["grade_id"] = "task-00-9-answer"
    with pytest.raises(ValueError, match="task-00-9-answer"):
        source_version(nb)


def test_release_digest_follows_the_cells_only(release):
    other = copy.deepcopy(release)
    other.metadata["anything"] = 1
    assert course.release_digest(other) == course.release_digest(release)
    other.cells[0].source += "!"
    assert course.release_digest(other) != course.release_digest(release)


# ------------------------------------------------------------------------------------ workbook, teacher


def test_workbook_copies_the_student_book_and_never_overwrites(book, tmp_path):
    dest = tmp_path / "workbook"
    lines = []
    (book / "ru").mkdir()
    (book / "ru" / f"{A}.md").write_text("<!-- cell: summary · en: 000000000000 -->\n## Итоги\n", encoding="utf-8")
    (book / "ru" / "notes.md").write_text("a reader's file, not a chapter's Russian text", encoding="utf-8")
    done = course.write_workbook(dest, book, out=lines.append)
    target = dest / f"{A}.ipynb"
    assert done == [("written", target)]
    assert (dest / "figures" / "frame.png").read_bytes() == b"\x89PNG fake"
    # the chapters' Russian sources stay in the book (the Russian notebooks are built from them); other files are copied
    assert not (dest / "ru" / f"{A}.md").exists() and (dest / "ru" / "notes.md").is_file()
    nb = read(target)
    assert "SOLUTION" not in json.dumps(nb) and answer(nb).source.splitlines() == TEMPLATE

    answer(nb).source = answer(nb).source.replace("H_m = ...", "H_m = 1200")
    nbformat.write(nb, str(target))
    mine = target.read_bytes()
    assert course.write_workbook(dest, book, out=lines.append) == [("kept", target)]
    assert target.read_bytes() == mine

    src = read(book / f"{A}.ipynb")
    nbtools.set_cell(src, "summary", "## Summary\n\nA corrected summary.")
    nbtools.write(src, book / f"{A}.ipynb")
    lines.clear()
    (action, beside), = course.write_workbook(dest, book, out=lines.append)
    assert action == "updated-beside" and beside.name.startswith(f"{A}.updated-")
    assert target.read_bytes() == mine
    assert "has changed since" in lines[0] and beside.name in lines[0]
    assert course.write_workbook(dest, book, out=lines.append) == [("updated-beside", beside)]


def test_workbook_never_copies_a_solution_left_in_a_chapter(book, tmp_path):
    nb = read(book / f"{A}.ipynb")
    answer(nb).source += "\n### BEGIN SOLUTION\nH_m = v.f_mm / 1000 * v.m\n### END SOLUTION"
    nbtools.write(nb, book / f"{A}.ipynb")
    course.write_workbook(tmp_path / "wb", book, out=lambda s: None)
    text = (tmp_path / "wb" / f"{A}.ipynb").read_text(encoding="utf-8")
    assert "SOLUTION" not in text and "v.f_mm / 1000" not in text


def test_workbook_cli_from_the_repository_top(tmp_path, monkeypatch, capsys, book):
    monkeypatch.chdir(book.parent)
    assert course.main(["workbook"]) == 0
    assert (book.parent / "workbook" / f"{A}.ipynb").exists()
    assert "1 chapter(s) written" in capsys.readouterr().out


def test_workbook_skips_a_broken_chapter_and_writes_the_others(book, tmp_path, capsys):
    (book / "01_broken.ipynb").write_text('{"cells": [', encoding="utf-8")
    assert course.main(["--notebooks", str(book), "workbook", "--dest", str(tmp_path / "wb")]) == 0
    out = capsys.readouterr().out
    assert "SKIPPED 01_broken.ipynb" in out and "1 chapter(s) written" in out and "1 skipped" in out
    (book / f"{A}.ipynb").unlink()
    assert course.main(["--notebooks", str(book), "workbook", "--dest", str(tmp_path / "wb2")]) == 1


def test_teacher_copy_cli(book, tmp_path, capsys):
    assert course.main(["--notebooks", str(book), "teacher", str(tmp_path / "t")]) == 0
    nb = read(tmp_path / "t" / f"{A}.ipynb")
    assert '_tasks.answers("task-00-1", v)' in answer(nb).source
    assert "not for students" in capsys.readouterr().out


def test_workbook_and_teacher_copies_are_git_ignored():
    ignored = (NOTEBOOKS.parent / ".gitignore").read_text(encoding="utf-8").splitlines()
    assert "/workbook/" in ignored and "/course/source/" in ignored and "/course/teacher/" in ignored


# ------------------------------------------------------------------------------------ LMS exports


def _files(root: Path, names):
    for name in names:
        (root / name).parent.mkdir(parents=True, exist_ok=True)
        (root / name).write_text("{}")


def test_scan_recognises_flat_files_and_student_folders(tmp_path):
    ex = tmp_path / "export"
    _files(ex, ["19-0401_00_start_here.ipynb", "19-0401_01_flight_planning (1).ipynb", "19-0402/00_start_here.ipynb",
                "ivanov/sub/ivanov_00_start_here.ipynb", "notes.txt", "19-0401_99_unknown.ipynb",
                "bad id!_00_start_here.ipynb", ".ipynb_checkpoints/x_00_start_here-checkpoint.ipynb"])
    scan = scan_submissions(ex, ["00_start_here", "01_flight_planning"])
    assert {k: v.relative_to(ex).as_posix() for k, v in scan.found.items()} == {
        ("19-0401", "00_start_here"): "19-0401_00_start_here.ipynb",
        ("19-0401", "01_flight_planning"): "19-0401_01_flight_planning (1).ipynb",
        ("19-0402", "00_start_here"): "19-0402/00_start_here.ipynb",
        ("ivanov", "00_start_here"): "ivanov/sub/ivanov_00_start_here.ipynb",
    }
    why = {p.name: reason for p, reason in scan.unrecognised}
    assert set(why) == {"notes.txt", "19-0401_99_unknown.ipynb", "bad id!_00_start_here.ipynb"}
    assert "not a notebook" in why["notes.txt"] and "known chapter" in why["19-0401_99_unknown.ipynb"]
    assert "characters" in why["bad id!_00_start_here.ipynb"]


def test_scan_recognises_moodle_folders_and_record_books_in_file_names(tmp_path):
    ex = tmp_path / "export"
    _files(ex, ["Ivan Ivanov_123456_assignsubmission_file_/19-0424_00_start_here.ipynb",
                "Anna Petrova_123457_assignsubmission_file_/00_start_here.ipynb",
                "Oleg Sidorov_123458_assignsubmission_file_/00_start_here.ipynb",
                "group 3/19-0431_00_start_here.ipynb", "group 3/19-0432_00_start_here (1).ipynb",
                "petrov_777_19-0440_00_start_here.ipynb"])
    scan = scan_submissions(ex, ["00_start_here"], roster={"123457": "19-0425"})
    assert sorted(sid for sid, _ in scan.found) == ["123457", "19-0424", "19-0431", "19-0432", "19-0440"]
    (p, why), = scan.unrecognised
    assert "Oleg Sidorov" in why and "roster" in why and "123458" in why


def test_scan_takes_the_newest_of_several_files(tmp_path):
    ex = tmp_path / "export"
    (ex / "19-0401").mkdir(parents=True)
    old, new = ex / "19-0401_00_start_here.ipynb", ex / "19-0401" / "00_start_here.ipynb"
    old.write_text("{}")
    new.write_text("{}")
    os.utime(old, (1_000_000, 1_000_000))
    scan = scan_submissions(ex, ["00_start_here"])
    assert scan.found == {("19-0401", "00_start_here"): new}
    assert scan.duplicates == [(new, [old])]


def test_a_number_claimed_from_two_peoples_folders_is_taken_from_neither(tmp_path):
    ex = tmp_path / "export"
    _files(ex, ["Anna Victim_9001_assignsubmission_file_/19-0530_00_start_here.ipynb",
                "Boris Attacker_9002_assignsubmission_file_/19-0530_00_start_here.ipynb",
                "19-0531_00_start_here.ipynb", "group 1/19-0531_00_start_here.ipynb",
                "Carl Own_9003_assignsubmission_file_/19-0532_00_start_here.ipynb",
                "Dina Other_9004_assignsubmission_file_/19-0533_00_start_here.ipynb",
                "19-0534_00_start_here.ipynb", "19-0534/00_start_here.ipynb"])
    scan = scan_submissions(ex, ["00_start_here"], roster={"9003": "19-0532", "9004": "19-0599"})
    assert sorted(scan.conflicts) == [("19-0530", "00_start_here"), ("19-0531", "00_start_here"),
                                      ("19-0533", "00_start_here")]
    assert len(scan.conflicts[("19-0530", "00_start_here")]) == 2
    (_, _, why), = scan.conflicts[("19-0533", "00_start_here")]  # Dina's folder, the roster says 19-0599
    assert "9004" in why and "19-0533" in why
    # the student's own places (a participant the roster maps to the number, the top and their folder) are fine
    assert sorted(scan.found) == [("19-0532", "00_start_here"), ("19-0534", "00_start_here")]


# ------------------------------------------------------------------------------------ import: atomic, nbformat 3


def _export_of(release, tmp_path, ids):
    ex = tmp_path / "export"
    ex.mkdir()
    for sid in ids:
        nbformat.write(release, str(ex / f"{sid}_{A}.ipynb"))
    return ex


def test_import_is_atomic_per_file(release, book, tmp_path, monkeypatch):
    from aerophoto.course import grading

    c = course.Course(tmp_path / "c", book, out=lambda s: None)
    ex = _export_of(release, tmp_path, ["19-0401", "19-0402", "19-0403"])
    real = grading.write_atomic
    calls = []

    def disk_full(path, data):
        calls.append(path)
        if len(calls) == 2:
            raise OSError(28, "No space left on device")
        real(path, data)

    monkeypatch.setattr(grading, "write_atomic", disk_full)
    scan = c.import_submissions(ex)
    assert [p.name for p, _ in scan.failed] == [f"19-0402_{A}.ipynb"]
    assert not c.path("submitted", A, "19-0402").exists()
    assert c.path("submitted", A, "19-0403").read_bytes() == (ex / f"19-0403_{A}.ipynb").read_bytes()
    assert not [p for p in (c.root / "submitted").rglob("*.tmp")]
    monkeypatch.setattr(grading, "write_atomic", real)
    assert course.main(["--course", str(c.root), "--notebooks", str(book), "import", str(ex)]) == 0


def test_import_exits_non_zero_when_a_file_cannot_be_written(release, book, tmp_path, monkeypatch, capsys):
    from aerophoto.course import grading

    ex = _export_of(release, tmp_path, ["19-0401"])

    def disk_full(path, data):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(grading, "write_atomic", disk_full)
    assert course.main(["--course", str(tmp_path / "c"), "--notebooks", str(book), "import", str(ex)]) == 1
    assert "FAILED" in capsys.readouterr().out


def test_write_atomic_leaves_the_old_file_or_the_new_one(tmp_path, monkeypatch):
    target = tmp_path / "f.ipynb"
    write_atomic(target, b"old")

    def boom(fd):
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(os, "fsync", boom)
    with pytest.raises(OSError):
        write_atomic(target, b"new")
    assert target.read_bytes() == b"old" and sorted(p.name for p in tmp_path.iterdir()) == ["f.ipynb"]


def test_nbformat_3_is_read_and_converted_on_import(release, book, tmp_path):
    ex = tmp_path / "export"
    ex.mkdir()
    nbformat.write(nbformat.convert(copy.deepcopy(release), 3), str(ex / f"19-0401_{A}.ipynb"), version=3)
    assert course.notebook_problem(ex / f"19-0401_{A}.ipynb") is None
    c = course.Course(tmp_path / "c", book, out=lambda s: None)
    c.import_submissions(ex)
    got = json.loads(c.path("submitted", A, "19-0401").read_text(encoding="utf-8"))
    assert got["nbformat"] == 4 and graded_tasks(read(c.path("submitted", A, "19-0401"))) == graded_tasks(release)


# ------------------------------------------------------------------------------------ the course lock


def test_a_second_run_waits_for_the_lock_or_refuses(tmp_path):
    from aerophoto.course.grading import CourseBusy, course_lock

    order = []
    held = threading.Event()

    def first():
        with course_lock(tmp_path, "autograde"):
            order.append("first in")
            held.set()
            time.sleep(0.6)
            order.append("first out")

    t = threading.Thread(target=first)
    t.start()
    held.wait(5)
    with pytest.raises(CourseBusy, match="in use .*aerophoto-course autograde"):
        with course_lock(tmp_path, "autograde", wait_s=0):
            pass
    said = []
    with course_lock(tmp_path, "gradebook", wait_s=30, out=said.append):
        order.append("second in")
    t.join()
    assert order == ["first in", "first out", "second in"]
    assert said and said[0].startswith("waiting: the course folder is in use")


def test_the_cli_refuses_clearly_when_the_course_is_busy(tmp_path, book, capsys):
    from aerophoto.course.grading import course_lock

    (tmp_path / "c").mkdir()
    with course_lock(tmp_path / "c", "autograde"):
        assert course.main(["--course", str(tmp_path / "c"), "--notebooks", str(book), "--no-wait", "generate"]) == 3
    assert "is in use" in capsys.readouterr().out


# ------------------------------------------------------------------------------------ record book, roster


@pytest.mark.parametrize("source, expected", [
    ('RECORD_BOOK = None  # comment\nimport aerophoto', ("none", None)),
    ('RECORD_BOOK = "19-0457"\n', ("value", "19-0457")),
    ("RECORD_BOOK = 190457\n", ("value", "190457")),
    ('RECORD_BOOK = "  "\n', ("none", None)),
    ("RECORD_BOOK = input()\n", ("unreadable", "RECORD_BOOK is not a plain number or string")),
    ("import aerophoto\n", ("missing", None)),
])
def test_parse_record_book(source, expected):
    nb = nbtools.notebook([nbtools.md("# t", id="title"), nbtools.code(source, id="setup")])
    assert parse_record_book(nb) == expected


def test_roster(tmp_path):
    p = tmp_path / "roster.csv"
    p.write_text("Student_ID,Record_Book,name\nivanov, 20-0115 ,Ivan\n\n", encoding="utf-8")
    assert read_roster(p) == {"ivanov": "20-0115"}
    p.write_text("id,number\n1,2\n", encoding="utf-8")
    with pytest.raises(ValueError, match="expected at least student_id,record_book"):
        read_roster(p)


# ------------------------------------------------------------------------------------ structural flags


def _submission(release, tmp_path, *, record_book=None, edit=None, name="sub.ipynb"):
    nb = copy.deepcopy(release)
    if record_book is not None:
        _, c = nbtools.find_cell(nb, "setup")
        c.source = c.source.replace("RECORD_BOOK = None", f"RECORD_BOOK = {record_book!r}")
    if edit:
        edit(nb)
    path = tmp_path / name
    nbformat.write(nb, str(path))
    return path, nb


def _graded(nb, tmp_path, *, answer_error=None):
    g = copy.deepcopy(nb)
    if answer_error:
        answer(g).outputs = [nbformat.v4.new_output("error", ename=answer_error, evalue="", traceback=[])]
    path = tmp_path / "graded.ipynb"
    nbformat.write(g, str(path))
    return path


def test_a_clean_submission_has_no_flags(release, tmp_path):
    path, nb = _submission(release, tmp_path, record_book="19-0457")
    assert inspect_submission(release, path, _graded(nb, tmp_path), "19-0457") == []
    path, nb = _submission(release, tmp_path)
    assert inspect_submission(release, path, _graded(nb, tmp_path), "19-0457") == []


def test_flags_for_an_answer_cell_that_raised_or_timed_out(release, tmp_path):
    path, nb = _submission(release, tmp_path, record_book="19-0457")
    (flag,) = inspect_submission(release, path, _graded(nb, tmp_path, answer_error="CellTimeoutError"), "19-0457")
    assert flag.code == "answer_error" and "timed out" in flag.message
    (flag,) = inspect_submission(release, path, _graded(nb, tmp_path, answer_error="ZeroDivisionError"), "19-0457")
    assert "raised ZeroDivisionError" in flag.message


def test_flags_for_deleted_stripped_and_edited_test_cells(release, tmp_path):
    def delete(nb):
        del nb.cells[nbtools.find_cell(nb, "task-00-1-check")[0]]

    def strip(nb):
        del nbtools.find_cell(nb, "task-00-1-check")[1].metadata["nbgrader"]

    def edit(nb):
        nbtools.find_cell(nb, "task-00-1-check")[1].source = "print('all correct')"

    for change, code in ((delete, "test_cell_deleted"), (strip, "test_cell_stripped"), (edit, "test_cell_edited")):
        path, nb = _submission(release, tmp_path, record_book="19-0457", edit=change)
        flags = inspect_submission(release, path, _graded(nb, tmp_path), "19-0457")
        assert codes(flags) == [code], flags
        assert "task-00-1-check" in flags[0].message


def test_flags_for_the_record_book(release, tmp_path):
    path, nb = _submission(release, tmp_path, record_book="19-0477")
    flags = inspect_submission(release, path, _graded(nb, tmp_path), "19-0457")
    assert codes(flags) == ["record_book_mismatch"] and "'19-0477'" in flags[0].message
    path, nb = _submission(release, tmp_path, record_book="190457")
    assert inspect_submission(release, path, _graded(nb, tmp_path), "19-0457") == []
    assert codes(inspect_submission(release, path, _graded(nb, tmp_path), None)) == ["record_book_unknown"]


def test_flags_for_missing_corrupt_and_ungraded(release, tmp_path):
    assert inspect_submission(release, tmp_path / "none.ipynb", None, "19-0457") == [
        Flag("missing", "no notebook submitted")]
    bad = tmp_path / "bad.ipynb"
    bad.write_text('{"cells": [', encoding="utf-8")
    (flag,) = inspect_submission(release, bad, None, "19-0457")
    assert flag.code == "corrupt" and "not valid JSON" in flag.message
    bad.write_text('{"hello": 1}', encoding="utf-8")
    assert "no cells" in inspect_submission(release, bad, None, "19-0457")[0].message
    bad.write_bytes(b"\xff\xfe\x00garbage")
    assert "not UTF-8" in inspect_submission(release, bad, None, "19-0457")[0].message
    path, _ = _submission(release, tmp_path, record_book="19-0457")
    assert codes(inspect_submission(release, path, tmp_path / "absent.ipynb", "19-0457")) == ["not_graded"]


# ------------------------------------------------------------------------------------ behaviour flags (AST)

ALIASES = {"aerophoto": "aerophoto", "checks": "aerophoto.checks"}


@pytest.mark.parametrize("code, expected", [
    ("ip = get_ipython()\nip.set_custom_exc((Exception,), lambda *a, **k: None)", "exception_hooks"),
    ("get_ipython().events.register('post_run_cell', f)", "exception_hooks"),
    ("import sys\nsys.excepthook = print", "exception_hooks"),
    ("import importlib\nc = importlib.import_module('aerophoto.' + 'checks')", "patched_checks"),
    ("checks.check_value = lambda *a, **k: True", "patched_checks"),
    ("import sys\nsys.modules['aerophoto.checks'] = None", "patched_checks"),
    ("from aerophoto import checks\nok = checks.task_passed('task-00-1')", "patched_checks"),
    ("aerophoto.checks.check_task('task-00-1', H_m=1200, v=v)", "patched_checks"),
    ("import os\nos.environ['AEROPHOTO_RECORD_BOOK'] = '19-0400'", "variant_changed"),
    ("from aerophoto.variants import variant_for_index\nglobals().update(v=variant_for_index(0))", "variant_changed"),
    ("v = aerophoto.variants.variant_for_index(0)", "variant_changed"),
    ("aerophoto.setup('19-0400', quiet=True)", "variant_changed"),
    ("from aerophoto import tasks\nH_m = tasks.answers('task-00-1', v)['H_m']", "uses_package_answers"),
    ("from aerophoto import geometry\nH_m = geometry.flying_height_m(v.f_mm, v.m)", "uses_package_answers"),
    ("from aerophoto.site import soils\nk = len(set(soils.soil_layer().classes.ravel()))", "uses_package_answers"),
    ("exec(open('x').read())", "dynamic_code"),
    ("getattr(get_ipython(), 'set_' + 'custom_exc')((Exception,), print)", "dynamic_code"),
    ("import sqlite3\nsqlite3.connect('../../../gradebook.db')", "system_access"),
    ("open('/srv/course/nbgrader_config.py', 'a').write('x')", "system_access"),
    ("import subprocess\nsubprocess.Popen(['sleep', '60'], start_new_session=True)", "system_access"),
    ("import os\nos.fork()", "system_access"),
])
def test_code_flags_catch_each_behaviour(code, expected):
    flags = code_flags(code, where="cell x", answer_cell=True, aliases=ALIASES, known=set())
    assert expected in codes(flags), flags
    assert all(f.message.startswith("cell x: ") for f in flags)


@pytest.mark.parametrize("code", [
    "import math\nH_m = v.f_mm / 1000 * v.m\non_mm = v.f_mm * math.tan(math.radians(v.alpha_deg))",
    "import numpy as np\nx = np.array([1, 2])\nprint(x.mean())  # my checks of 'globals'",
    "H_m = 11859\non_mm = 35.11\noc_mm = -17.54",
    "from aerophoto import checks\nchecks.report()",
    "open('my_notes.txt', 'w').write('done')",
    # the instruments a task's text tells the student to use (Task.tools), chapter 13's k-means
    "from aerophoto import soilmap\nlabels = soilmap.segment_tones(patch.composite, k, seed=0)",
])
def test_code_flags_leave_honest_work_alone(code):
    assert code_flags(code, where="cell x", answer_cell=True, aliases=ALIASES, known=set()) == []


@pytest.mark.parametrize("limit", [1000, 3000, 20000])
def test_deep_code_is_unreadable_whatever_the_recursion_limit(limit):
    """Importing IPython (jedi) raises the recursion limit to 3 000, where Python itself parses 3 000 nested
    minus signs: the scan measures the depth, so the verdict is the same in every process."""
    import sys

    old = sys.getrecursionlimit()
    sys.setrecursionlimit(limit)
    try:
        deep = code_flags("x = " + "-" * 3000 + "1\n", where="cell x", answer_cell=False, aliases={}, known=set())
        flat = code_flags("x = " + "-1 " * 150 + "\n", where="cell x", answer_cell=False, aliases={}, known=set())
    finally:
        sys.setrecursionlimit(old)
    assert codes(deep) == ["code_unreadable"] and flat == []


def test_the_package_answer_functions_come_from_the_task_registry():
    found = package_answer_functions()
    assert "aerophoto.tasks" in found and "aerophoto.geometry.flying_height_m" in found
    assert not any(name.startswith(("aerophoto.variants", "aerophoto._validate")) for name in found)


def test_release_code_is_not_flagged_and_a_setup_cell_attack_is(release, tmp_path):
    from aerophoto.course.flags import behaviour_flags

    assert behaviour_flags(release, release) == []
    nb = copy.deepcopy(release)
    setup = nbtools.find_cell(nb, "setup")[1]
    setup.source = 'import os\nos.environ["AEROPHOTO_RECORD_BOOK"] = "19-0400"\n' + setup.source
    assert codes(behaviour_flags(release, nb)) == ["variant_changed"]


def test_same_code_is_found_on_normalised_answer_code(release):
    def with_answer(src):
        nb = copy.deepcopy(release)
        answer(nb).source = src
        return answer_code(nb)

    a = with_answer("H_m = v.f_mm/1000*v.m   # mine\non_mm = 35.1\noc_mm = -17.5")
    b = with_answer("# copied\nH_m = v.f_mm / 1000 * v.m\n\non_mm = 35.1\noc_mm = -17.5")
    c = with_answer("H_m = ...\non_mm = ...\noc_mm = ...")
    assert a == b and c == ""
    assert same_code_groups({"x": a, "y": b, "z": c, "w": with_answer("H_m = 1")}) == {"x": ["y"], "y": ["x"]}


# ------------------------------------------------------------------------------------ the trusted check


def _executed(release, values, *, variant_i=57, passed=True, extra=None, evidence=None, records=1):
    """A stand-in for an executed notebook: the check cell's record(s) and nbgrader's pass/fail."""
    nb = copy.deepcopy(release)
    chk = nbtools.find_cell(nb, "task-00-1-check")[1]
    rec = wire.encode_answers("task-00-1", values, variant_for_index(variant_i))
    rec["evidence"] = evidence or {"env": {"AEROPHOTO_RECORD_BOOK": "19-0457", "AEROPHOTO_GRADING": "1",
                                           "AEROPHOTO_HOME": "/sbx/.aerophoto"}}
    outs = [nbformat.v4.new_output("display_data", data={wire.ANSWERS_MIME: rec})] * records
    if not passed:
        outs = outs + [nbformat.v4.new_output("error", ename="WrongAnswer", evalue="H_m: not right", traceback=[])]
    chk.outputs = list(outs) + (extra or [])
    return nb


def _right(v):
    from aerophoto import tasks

    return tasks.answers("task-00-1", v)


def test_trusted_scores_the_values_for_the_students_variant(release):
    v = variant("19-0457")
    (vd,) = grade_executed(_executed(release, _right(v)), "19-0457")
    assert (vd.score, vd.passed, vd.flags) == (3.0, True, [])
    wrong = dict(_right(v), H_m=1.0)
    (vd,) = grade_executed(_executed(release, wrong, passed=False), "19-0457")
    assert (vd.score, vd.passed, vd.flags) == (0.0, False, []) and "H_m" in vd.message


def test_trusted_flags_a_pass_the_values_do_not_earn(release):
    wrong = dict(_right(variant("19-0457")), H_m=1.0)
    (vd,) = grade_executed(_executed(release, wrong, passed=True), "19-0457")
    assert vd.score == 0.0 and codes(vd.flags) == ["tampered"]


def test_trusted_never_uses_the_kernels_variant(release):
    theirs = _right(variant_for_index(0))
    (vd,) = grade_executed(_executed(release, theirs, variant_i=0), "19-0457")
    assert vd.score == 0.0 and codes(vd.flags) == ["variant_mismatch"]  # the kernel's own pass is explained
    assert "variant 00" in next(f.message for f in vd.flags if f.code == "variant_mismatch")


def test_trusted_scores_0_without_a_record_and_says_why(release):
    nb = copy.deepcopy(release)
    nbtools.find_cell(nb, "task-00-1-check")[1].outputs = [nbformat.v4.new_output("stream", name="stdout",
                                                                                   text="✓ Task 00.1 passed\n")]
    (vd,) = grade_executed(nb, "19-0457")
    assert vd.score == 0.0 and codes(vd.flags) == ["no_answer_record", "tampered"]
    (vd,) = grade_executed(_executed(release, _right(variant("19-0457")), records=2), "19-0457")
    assert codes(vd.flags) == ["tampered"] and "2 answer records" in vd.flags[0].message
    (vd,) = grade_executed(_executed(release, _right(variant("19-0457"))), None)
    assert vd.score == 0.0 and "no record-book number" in vd.message


def test_trusted_reports_what_the_check_saw_in_the_kernel(release):
    ev = {"env": {"AEROPHOTO_RECORD_BOOK": "19-0400", "AEROPHOTO_GRADING": "1", "AEROPHOTO_HOME": "/sbx/.aerophoto"},
          "custom_exc": ["Exception"], "event_hooks": ["post_run_cell: _clear"], "shell_overrides": [],
          "excepthook": False, "patched": ["aerophoto.checks.check_value"]}
    (vd,) = grade_executed(_executed(release, _right(variant("19-0457")), evidence=ev), "19-0457")
    assert vd.score == 3.0
    assert codes(vd.flags) == ["exception_hooks", "patched_checks", "variant_changed"]
    assert "19-0400" in next(f.message for f in vd.flags if f.code == "variant_changed")


def test_executed_outcomes_follow_nbgraders_scoring_rule(release):
    nb = copy.deepcopy(release)
    _, chk = nbtools.find_cell(nb, "task-00-1-check")
    chk.outputs = [nbformat.v4.new_output("stream", name="stdout", text="✓ H_m: correct\n")]
    tasks, errors = course.executed_outcomes(nb)
    assert [(t.task, t.passed) for t in tasks] == [("task-00-1", True)] and errors == []
    chk.outputs.append(nbformat.v4.new_output("stream", name="stderr", text="RuntimeWarning: overflow\n"))
    (t,), _ = course.executed_outcomes(nb)
    assert not t.passed and "stderr" in t.message and t.ename == "stderr"
    chk.outputs = [nbformat.v4.new_output("error", ename="WrongAnswer", evalue="\x1b[31mH_m: sign\x1b[0m",
                                          traceback=[])]
    _, setup = nbtools.find_cell(nb, "setup")
    setup.outputs = [nbformat.v4.new_output("error", ename="ValueError", evalue="record_book = 'x'", traceback=[])]
    (t,), errors = course.executed_outcomes(nb)
    assert (t.passed, t.message, t.ename) == (False, "H_m: sign", "WrongAnswer")
    assert errors == [("setup", "ValueError: record_book = 'x'")]


# ------------------------------------------------------------------------------------ check: nothing unverified


def test_check_cli_reports_missing_and_corrupt_files(tmp_path, capsys):
    bad = tmp_path / "bad.ipynb"
    bad.write_text("not json", encoding="utf-8")
    assert course.main(["check", str(tmp_path / "absent.ipynb"), str(bad)]) == 2
    out = capsys.readouterr().out
    assert "no such notebook" in out and "not valid JSON" in out


def test_check_never_reports_what_it_did_not_verify(release, tmp_path, capsys):
    empty = tmp_path / "empty.ipynb"
    nbformat.write(nbtools.notebook([nbtools.code("RECORD_BOOK = None", id="setup")]), str(empty))
    other = tmp_path / "other_kernel.ipynb"
    nb = copy.deepcopy(release)
    nb.metadata["kernelspec"] = {"name": "no-such-kernel", "display_name": "x", "language": "python"}
    nbformat.write(nb, str(other))
    anonymous = tmp_path / "anonymous.ipynb"
    nbformat.write(release, str(anonymous))
    os.environ.pop("AEROPHOTO_RECORD_BOOK", None)
    assert course.main(["check", str(empty)]) == 2
    assert course.main(["check", str(other), "--record-book", "19-0457"]) == 2
    assert course.main(["check", str(anonymous)]) == 2
    out = capsys.readouterr().out
    assert "no graded tasks" in out and "0 of 0" not in out
    assert "'no-such-kernel', which is not installed" in out
    assert "no record-book number" in out


# ------------------------------------------------------------------------------------ set-up


def test_ensure_path_puts_this_python_first(monkeypatch):
    monkeypatch.setenv("PATH", "/usr/bin:/bin")
    ensure_path()
    parts = os.environ["PATH"].split(os.pathsep)
    # a venv's base Python's bin/ follows (a --system-site-packages venv runs the base's alembic)
    base = [str(Path(sys.base_prefix) / "bin")] if sys.prefix != sys.base_prefix else []
    assert parts == [str(Path(sys.executable).parent), *base, "/usr/bin", "/bin"]
    ensure_path()
    assert os.environ["PATH"].split(os.pathsep) == parts


def test_course_folder_gets_the_config_template_once(tmp_path, book):
    c = course.Course(tmp_path / "c", book, out=lambda s: None)
    cfg_file = tmp_path / "c" / "nbgrader_config.py"
    assert cfg_file.read_text(encoding="utf-8") == template_path().read_text(encoding="utf-8")
    cfg = c.config()
    assert cfg.ExecutePreprocessor.timeout == 120 and cfg.ExecutePreprocessor.interrupt_on_timeout is True
    assert cfg.CourseDirectory.root == str(tmp_path / "c") and cfg.CourseDirectory.course_id == "aerophoto"
    assert cfg.Autograde.autograde_preprocessors[0].__name__ == "SandboxExecute"
    assert cfg.HTMLExporter.sanitize_html is True
    cfg_file.write_text(cfg_file.read_text(encoding="utf-8").replace("timeout = 120", "timeout = 45")
                        + '\nc.SandboxExecute.limits = {"memory_mb": 500}\n')
    course.Course(tmp_path / "c", book, out=lambda s: None)  # never overwrites the instructor's edits
    again = course.Course(tmp_path / "c", book, out=lambda s: None)
    assert again.config().ExecutePreprocessor.timeout == 45 and again.limits.memory_mb == 500
    assert course.Course(tmp_path / "c", book, timeout=7, out=lambda s: None).config().ExecutePreprocessor.timeout == 7
    assert c.assignments() == [A]
    assert c.record_book("19-0457") == "19-0457" and c.record_book("ivanov") is None


def test_an_explicit_roster_must_exist(tmp_path, book):
    with pytest.raises(SystemExit, match="no such file"):
        course.Course(tmp_path / "c", book, roster=tmp_path / "absent.csv", out=lambda s: None)


def test_package_data_lists_the_config_template():
    text = (NOTEBOOKS.parent / "pyproject.toml").read_text(encoding="utf-8")
    assert '"course_data/*"' in text and 'aerophoto-course = "aerophoto.course:main"' in text
    assert template_path().is_file()


def test_the_course_package_imports_lazily():
    import subprocess

    code = "import sys, aerophoto.course; print(sorted(m for m in sys.modules if m.startswith(('nbgrader', 'jupyter_client'))))"
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True).stdout
    assert out.strip() == "[]"



# ------------------------------------------------------------------------------------ check: the teacher's flags
def test_check_prints_the_flags_the_teacher_will_see_with_what_they_mean(tmp_path):
    from aerophoto.course.check import print_check, release_for
    from aerophoto.course.common import Flag
    from aerophoto.course.flags import FLAG_MEANINGS
    from aerophoto.course.outcomes import CheckResult, TaskOutcome

    res = CheckResult(tmp_path / "09_plan_correction.ipynb",
                      tasks=[TaskOutcome("task-09-1", True, 3.0, "", "", 3.0)],
                      flags=[Flag("variant_shadowed", "cell task-09-1-answer: assigns v (line 2)"),
                             Flag("uses_package_answers", "cell task-09-2-answer: uses aerophoto.labs.ch09 (line 1)")])
    lines = []
    print_check(res, lines.append)
    text = "\n".join(lines)
    assert "the teacher will see these flags" in text
    assert "! variant_shadowed: cell task-09-1-answer: assigns v (line 2)" in text
    assert f"variant_shadowed — {FLAG_MEANINGS['variant_shadowed']}" in text
    assert f"uses_package_answers — {FLAG_MEANINGS['uses_package_answers']}" in text
    # the book's own copy of a chapter is found by its number, wherever the student's copy lives
    rel = release_for(tmp_path / "09_plan_correction.ipynb", NOTEBOOKS)
    assert rel is not None and any(c.get("id") == "task-09-1-check" for c in rel["cells"])
    assert release_for(tmp_path / "notes.ipynb", NOTEBOOKS) is None


def test_every_flag_code_the_course_raises_has_a_meaning():
    import re

    from aerophoto.course import flags

    src = "".join(p.read_text(encoding="utf-8") for p in (Path(flags.__file__).parent).glob("*.py"))
    codes_used = set(re.findall(r'Flag\("([a-z_]+)"', src)) | set(re.findall(r'hit\("([a-z_]+)"', src))
    codes_used |= {f"{k}_cell_{s}" for k in ("test", "answer") for s in ("stripped", "deleted", "edited")}
    codes_used -= {"flags_failed", "not_generated"}  # the instructor's own failures, not a student's
    assert codes_used <= set(flags.FLAG_MEANINGS), codes_used - set(flags.FLAG_MEANINGS)


def test_reusing_the_name_v_is_flagged_as_harmless_not_as_a_changed_variant():
    flags_ = code_flags("u, v = 0.25, 0.75\nx_mm = u", where="cell x", answer_cell=True, aliases=ALIASES, known=set())
    assert codes(flags_) == ["variant_shadowed"]
    assert "variant_changed" in codes(code_flags("del v", where="cell x", answer_cell=True, aliases=ALIASES,
                                                 known=set()))


def test_a_saved_notebook_keeps_the_values_its_check_cells_recorded(release):
    """The course report reads answers that needed package code from the saved notebook (issue 29's interface)."""
    from aerophoto.course.trusted import answer_records, saved_answers

    v = variant("19-0457")
    values = dict(_right(v), on_mm=[1.0, 2.0])   # any plain data survives: here a (wrong) list
    nb = copy.deepcopy(release)
    rec = wire.encode_answers("task-00-1", values, v)
    out = nbformat.v4.new_output("display_data", data={"text/plain": "Task 00.1 — checking H_m, on_mm, oc_mm",
                                                       wire.ANSWERS_MIME: rec})
    nbtools.find_cell(nb, "task-00-1-check")[1].outputs = [out]
    assert answer_records(nb) == {"task-00-1-check": [rec]}
    saved = saved_answers(json.loads(nbformat.writes(nb)))   # read back from the file's JSON
    assert set(saved) == {"task-00-1"} and saved["task-00-1"]["H_m"] == pytest.approx(values["H_m"])
    assert saved["task-00-1"]["on_mm"] == [1.0, 2.0]
    nbtools.find_cell(nb, "task-00-1-check")[1].outputs = [nbformat.v4.new_output(
        "display_data", data={"text/plain": "x", wire.ANSWERS_MIME: {"task": 5, "values": "nonsense"}})]
    assert saved_answers(nb) == {}   # a record that does not name its own cell's task is not read
    assert saved_answers({"cells": "broken"}) == {}
