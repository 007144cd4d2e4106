"""aerophoto.course without running nbgrader's grading: the workbook, LMS exports, flags, the CLI.

The end-to-end runs with real nbgrader and its gradebook are in test_grading_e2e.py.
"""

from __future__ import annotations

import copy
import json
import os
import shutil
import sys
from pathlib import Path

import nbformat
import pytest

from aerophoto import course, nbtools
from aerophoto.course import Flag, graded_tasks, inspect_submission, parse_record_book, scan_submissions
from conftest import NOTEBOOKS

SOURCE = NOTEBOOKS / "00_start_here.ipynb"


@pytest.fixture(scope="module")
def release():
    return course.student_version(nbformat.read(str(SOURCE), as_version=4))


@pytest.fixture
def book(tmp_path):
    """A small book: chapter 00 and a picture beside it."""
    d = tmp_path / "notebooks"
    d.mkdir()
    shutil.copy(SOURCE, d)
    (d / "figures").mkdir()
    (d / "figures" / "frame.png").write_bytes(b"\x89PNG fake")
    return d


def codes(flags):
    return sorted(f.code for f in flags)


# ------------------------------------------------------------------------------------ tasks, versions


def test_graded_tasks_of_the_reference_chapter(release):
    src = nbformat.read(str(SOURCE), as_version=4)
    assert graded_tasks(src) == [course.GradedTask("task-00-1", "task-00-1-answer", "task-00-1-check", 3.0)]
    assert graded_tasks(release) == graded_tasks(src)


def test_student_version_strips_solutions_and_hidden_tests(release):
    _, ans = nbtools.find_cell(release, "task-00-1-answer")
    _, chk = nbtools.find_cell(release, "task-00-1-check")
    assert "SOLUTION" not in ans.source and "math.tan" not in ans.source
    assert ans.source.splitlines()[:3] == ["H_m = ...     # flying height, m", "on_mm = ...   # o to n, mm",
                                           "oc_mm = ...   # o to c with the guide's sign, mm"]
    assert "NotImplementedError" not in ans.source  # the course's code stub, not nbgrader's raise
    assert "HIDDEN" not in chk.source and "on_mm vs oc_mm" not in chk.source
    assert chk.source.rstrip().endswith('checks.task_passed("task-00-1")')
    assert chk.metadata.nbgrader["checksum"] and chk.metadata.nbgrader["locked"]
    assert not nbtools.has_outputs(release)


def test_release_digest_follows_the_cells_only(release):
    other = copy.deepcopy(release)
    other.metadata["anything"] = 1
    assert course.release_digest(other) == course.release_digest(release)
    other.cells[0].source += "!"
    assert course.release_digest(other) != course.release_digest(release)


# ------------------------------------------------------------------------------------ workbook


def test_workbook_writes_student_versions_and_never_overwrites(book, tmp_path):
    dest = tmp_path / "workbook"
    lines = []
    done = course.write_workbook(dest, book, out=lines.append)
    target = dest / "00_start_here.ipynb"
    assert done == [("written", target)]
    assert (dest / "figures" / "frame.png").read_bytes() == b"\x89PNG fake"
    nb = nbformat.read(str(target), as_version=4)
    assert "BEGIN SOLUTION" not in json.dumps(nb) and "HIDDEN TESTS" not in json.dumps(nb)

    # the student works in it; a second run keeps it as it is
    _, ans = nbtools.find_cell(nb, "task-00-1-answer")
    ans.source = ans.source.replace("H_m = ...", "H_m = 1200")
    nbformat.write(nb, str(target))
    mine = target.read_bytes()
    assert course.write_workbook(dest, book, out=lines.append) == [("kept", target)]
    assert target.read_bytes() == mine

    # the chapter changes: the new version goes beside the student's copy, which stays untouched
    src = nbformat.read(str(book / "00_start_here.ipynb"), as_version=4)
    nbtools.set_cell(src, "summary", "## Summary\n\nA corrected summary.")
    nbtools.write(src, book / "00_start_here.ipynb")
    lines.clear()
    done = course.write_workbook(dest, book, out=lines.append)
    (action, beside), = done
    assert action == "updated-beside" and beside.name.startswith("00_start_here.updated-")
    assert target.read_bytes() == mine
    assert "has changed since" in lines[0] and beside.name in lines[0]
    assert "A corrected summary." in beside.read_text(encoding="utf-8")
    # idempotent: running again writes nothing new
    assert course.write_workbook(dest, book, out=lines.append) == [("updated-beside", beside)]
    assert sorted(p.name for p in dest.glob("*.ipynb")) == ["00_start_here.ipynb", beside.name]


def test_workbook_cli_from_the_repository_top(tmp_path, monkeypatch, capsys, book):
    top = book.parent
    monkeypatch.chdir(top)
    assert course.main(["workbook"]) == 0
    assert (top / "workbook" / "00_start_here.ipynb").exists()
    assert "1 chapter(s) written" in capsys.readouterr().out


def test_workbook_skips_a_broken_chapter_and_writes_the_others(book, tmp_path, capsys):
    nb = nbformat.read(str(book / "00_start_here.ipynb"), as_version=4)
    _, chk = nbtools.find_cell(nb, "task-00-1-check")
    chk.source = chk.source.replace("### END HIDDEN TESTS", "")  # an unterminated hidden block
    nbtools.write(nb, book / "01_broken.ipynb")
    assert course.main(["--notebooks", str(book), "workbook", "--dest", str(tmp_path / "wb")]) == 0
    out = capsys.readouterr().out
    assert "SKIPPED 01_broken.ipynb" in out and "1 chapter(s) written" in out and "1 skipped" in out
    assert sorted(p.name for p in (tmp_path / "wb").glob("*.ipynb")) == ["00_start_here.ipynb"]
    (book / "00_start_here.ipynb").unlink()
    assert course.main(["--notebooks", str(book), "workbook", "--dest", str(tmp_path / "wb2")]) == 1


def test_workbook_is_git_ignored():
    ignored = (NOTEBOOKS.parent / ".gitignore").read_text(encoding="utf-8").splitlines()
    assert "/workbook/" in ignored and "/course/source/" in ignored


# ------------------------------------------------------------------------------------ LMS exports


def test_scan_recognises_flat_files_and_student_folders(tmp_path):
    ex = tmp_path / "export"
    (ex / "19-0402").mkdir(parents=True)
    (ex / "ivanov" / "sub").mkdir(parents=True)
    files = {
        "19-0401_00_start_here.ipynb": "{}",
        "19-0401_01_flight_planning (1).ipynb": "{}",
        "19-0402/00_start_here.ipynb": "{}",
        "ivanov/sub/ivanov_00_start_here.ipynb": "{}",
        "notes.txt": "hello",
        "19-0401_99_unknown.ipynb": "{}",
        "bad id!_00_start_here.ipynb": "{}",
        ".ipynb_checkpoints/x_00_start_here-checkpoint.ipynb": "{}",
    }
    for name, text in files.items():
        (ex / name).parent.mkdir(parents=True, exist_ok=True)
        (ex / name).write_text(text)
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


# ------------------------------------------------------------------------------------ record book


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


def test_parse_record_book_syntax_error():
    nb = nbtools.notebook([nbtools.code("RECORD_BOOK = (", id="setup")])
    kind, why = parse_record_book(nb)
    assert kind == "unreadable" and "not valid Python" in why


def test_roster(tmp_path):
    p = tmp_path / "roster.csv"
    p.write_text("Student_ID,Record_Book,name\nivanov, 20-0115 ,Ivan\n\n", encoding="utf-8")
    assert course._read_roster(p) == {"ivanov": "20-0115"}
    p.write_text("id,number\n1,2\n", encoding="utf-8")
    with pytest.raises(ValueError, match="expected at least student_id,record_book"):
        course._read_roster(p)


# ------------------------------------------------------------------------------------ flags


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


def _graded(nb, tmp_path, *, variant=None, answer_error=None, test_error=False):
    """A stand-in for nbgrader's executed copy: the outputs the flags look at."""
    g = copy.deepcopy(nb)
    _, setup = nbtools.find_cell(g, "setup")
    if variant is not None:
        setup.outputs = [nbformat.v4.new_output("display_data", data={
            "text/html": f"<div><b>aerophoto 0.1.0 · variant i = {variant:02d} · record book: x</b></div>",
            "text/plain": "<IPython.core.display.HTML object>"})]
    _, ans = nbtools.find_cell(g, "task-00-1-answer")
    if answer_error:
        ans.outputs = [nbformat.v4.new_output("error", ename=answer_error, evalue="", traceback=[])]
    chk = next((c for c in g.cells if c.get("id") == "task-00-1-check"), None)
    if test_error:
        chk.outputs = [nbformat.v4.new_output("error", ename="WrongAnswer", evalue="H_m: no answer yet", traceback=[])]
    path = tmp_path / "graded.ipynb"
    nbformat.write(g, str(path))
    return path


def test_a_clean_submission_has_no_flags(release, tmp_path):
    path, nb = _submission(release, tmp_path, record_book="19-0457")
    assert inspect_submission(release, path, _graded(nb, tmp_path, variant=57), "19-0457") == []
    # RECORD_BOOK left at None is graded with the student's own number: no flag
    path, nb = _submission(release, tmp_path)
    assert inspect_submission(release, path, _graded(nb, tmp_path, variant=57), "19-0457") == []


def test_flags_for_an_answer_cell_that_timed_out_but_passed(release, tmp_path):
    path, nb = _submission(release, tmp_path, record_book="19-0457")
    flags = inspect_submission(release, path, _graded(nb, tmp_path, variant=57, answer_error="CellTimeoutError"),
                               "19-0457")
    assert codes(flags) == ["answer_error"]
    assert "timed out" in flags[0].message and "its test still passed" in flags[0].message
    flags = inspect_submission(release, path, _graded(nb, tmp_path, variant=57, answer_error="ZeroDivisionError",
                                                      test_error=True), "19-0457")
    assert codes(flags) == ["answer_error"] and "raised ZeroDivisionError" in flags[0].message
    assert "still passed" not in flags[0].message


def test_flags_for_deleted_stripped_and_edited_test_cells(release, tmp_path):
    def delete(nb):
        del nb.cells[nbtools.find_cell(nb, "task-00-1-check")[0]]

    def strip(nb):
        del nbtools.find_cell(nb, "task-00-1-check")[1].metadata["nbgrader"]

    def edit(nb):
        nbtools.find_cell(nb, "task-00-1-check")[1].source = "print('all correct')"

    for change, code in ((delete, "test_cell_deleted"), (strip, "test_cell_stripped"), (edit, "test_cell_edited")):
        path, nb = _submission(release, tmp_path, record_book="19-0457", edit=change)
        flags = inspect_submission(release, path, _graded(nb, tmp_path, variant=57), "19-0457")
        assert codes(flags) == [code], flags
        assert "task-00-1-check" in flags[0].message


def test_whitespace_changes_to_a_test_cell_are_not_edits(release, tmp_path):
    def touch(nb):
        c = nbtools.find_cell(nb, "task-00-1-check")[1]
        c.source = "\n" + c.source.replace("\n", "  \n") + "\n\n"

    path, nb = _submission(release, tmp_path, record_book="19-0457", edit=touch)
    assert inspect_submission(release, path, _graded(nb, tmp_path, variant=57), "19-0457") == []


def test_flags_for_the_record_book(release, tmp_path):
    path, nb = _submission(release, tmp_path, record_book="19-0477")
    flags = inspect_submission(release, path, _graded(nb, tmp_path, variant=77), "19-0457")
    assert codes(flags) == ["record_book_mismatch"] and "'19-0477'" in flags[0].message
    # the same digits written differently are the same number
    path, nb = _submission(release, tmp_path, record_book="190457")
    assert inspect_submission(release, path, _graded(nb, tmp_path, variant=57), "19-0457") == []
    # None in the cell, but the notebook ran with another variant (e.g. setup() called by hand)
    path, nb = _submission(release, tmp_path)
    flags = inspect_submission(release, path, _graded(nb, tmp_path, variant=12), "19-0457")
    assert codes(flags) == ["variant_mismatch"] and "variant 12" in flags[0].message
    # a student id with no record-book digits and no roster entry
    flags = inspect_submission(release, path, _graded(nb, tmp_path, variant=0), None)
    assert codes(flags) == ["record_book_unknown"]


def test_flags_for_code_reaching_into_the_checks(release, tmp_path):
    def patch(nb):
        nbtools.insert_after(nb, "task-00-1-answer", nbtools.code(
            "from aerophoto import checks\nchecks.check_value = lambda *a, **k: True", id="mine"))

    def variant_swap(nb):
        c = nbtools.find_cell(nb, "task-00-1-answer")[1]
        c.source = "v = aerophoto.variants.variant_for_index(0)\n" + c.source

    def harmless(nb):
        nbtools.insert_after(nb, "task-00-1-answer", nbtools.code("# my checks of H\nx = 'checks'", id="mine"))

    for change, word in ((patch, "'checks'"), (variant_swap, "assigns v")):
        path, nb = _submission(release, tmp_path, record_book="19-0457", edit=change)
        flags = inspect_submission(release, path, _graded(nb, tmp_path, variant=57), "19-0457")
        assert codes(flags) == ["suspicious_code"] and word in flags[0].message
    path, nb = _submission(release, tmp_path, record_book="19-0457", edit=harmless)
    assert inspect_submission(release, path, _graded(nb, tmp_path, variant=57), "19-0457") == []


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


# ------------------------------------------------------------------------------------ outcomes, CLI


def test_executed_outcomes_follow_nbgraders_scoring_rule(release):
    nb = copy.deepcopy(release)
    _, chk = nbtools.find_cell(nb, "task-00-1-check")
    chk.outputs = [nbformat.v4.new_output("stream", name="stdout", text="✓ H_m: correct\n")]
    tasks, errors = course.executed_outcomes(nb)
    assert [(t.task, t.passed) for t in tasks] == [("task-00-1", True)] and errors == []
    chk.outputs.append(nbformat.v4.new_output("stream", name="stderr", text="RuntimeWarning: overflow\n"))
    (t,), _ = course.executed_outcomes(nb)
    assert not t.passed and "stderr" in t.message and t.ename == "stderr"  # nbgrader scores it 0
    chk.outputs = [nbformat.v4.new_output("error", ename="WrongAnswer", evalue="\x1b[31mH_m: sign\x1b[0m",
                                          traceback=[])]
    _, setup = nbtools.find_cell(nb, "setup")
    setup.outputs = [nbformat.v4.new_output("error", ename="ValueError", evalue="record_book = 'x'", traceback=[])]
    (t,), errors = course.executed_outcomes(nb)
    assert (t.passed, t.message, t.ename) == (False, "H_m: sign", "WrongAnswer")
    assert errors == [("setup", "ValueError: record_book = 'x'")]


def test_check_cli_reports_missing_and_corrupt_files(tmp_path, capsys):
    bad = tmp_path / "bad.ipynb"
    bad.write_text("not json", encoding="utf-8")
    assert course.main(["check", str(tmp_path / "absent.ipynb"), str(bad)]) == 2
    out = capsys.readouterr().out
    assert "no such notebook" in out and "not valid JSON" in out


def test_ensure_path_puts_this_python_first(monkeypatch):
    monkeypatch.setenv("PATH", "/usr/bin:/bin")
    course._ensure_path()
    parts = os.environ["PATH"].split(os.pathsep)
    assert parts[0] == str(Path(sys.executable).parent) and parts[1:] == ["/usr/bin", "/bin"]
    course._ensure_path()
    assert os.environ["PATH"].split(os.pathsep).count(str(Path(sys.executable).parent)) == 1


def test_grading_env_isolates_and_restores(monkeypatch, tmp_path):
    monkeypatch.setenv("AEROPHOTO_HOME", str(tmp_path))
    monkeypatch.setenv("AEROPHOTO_RECORD_BOOK", "grader-99")
    with course._grading_env("19-0457"):
        home = Path(os.environ["AEROPHOTO_HOME"])
        assert home != tmp_path and home.is_dir() and not any(home.iterdir())
        assert os.environ["AEROPHOTO_RECORD_BOOK"] == "19-0457"
    with course._grading_env(None):
        assert "AEROPHOTO_RECORD_BOOK" not in os.environ
    assert os.environ["AEROPHOTO_HOME"] == str(tmp_path) and os.environ["AEROPHOTO_RECORD_BOOK"] == "grader-99"


def test_course_folder_gets_the_config_template_once(tmp_path, book):
    c = course.Course(tmp_path / "c", book, out=lambda s: None)
    cfg_file = tmp_path / "c" / "nbgrader_config.py"
    assert cfg_file.read_text(encoding="utf-8") == course._template_path().read_text(encoding="utf-8")
    cfg = c.config()
    assert cfg.ExecutePreprocessor.timeout == 120 and cfg.ExecutePreprocessor.interrupt_on_timeout is True
    assert cfg.CourseDirectory.root == str(tmp_path / "c") and cfg.CourseDirectory.course_id == "aerophoto"
    cfg_file.write_text(cfg_file.read_text(encoding="utf-8").replace("timeout = 120", "timeout = 45"))
    course.Course(tmp_path / "c", book, out=lambda s: None)  # never overwrites the instructor's edits
    assert course.Course(tmp_path / "c", book, out=lambda s: None).config().ExecutePreprocessor.timeout == 45
    assert course.Course(tmp_path / "c", book, timeout=7, out=lambda s: None).config().ExecutePreprocessor.timeout == 7
    assert c.assignments() == ["00_start_here"]
    assert c.record_book("19-0457") == "19-0457" and c.record_book("ivanov") is None


def test_an_explicit_roster_must_exist(tmp_path, book):
    with pytest.raises(SystemExit, match="no such file"):
        course.Course(tmp_path / "c", book, roster=tmp_path / "absent.csv", out=lambda s: None)


def test_package_data_lists_the_config_template():
    text = (NOTEBOOKS.parent / "pyproject.toml").read_text(encoding="utf-8")
    assert '"course_data/*"' in text
    assert course._template_path().is_file()
