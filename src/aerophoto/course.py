"""The instructor's command line over nbgrader: ``aerophoto-course``.

nbgrader does the grading; this module adds only what the course needs around it:

=====================================  ==============================================================
``aerophoto-course workbook``          the student versions of every chapter into ``workbook/``
                                       (self-study), never overwriting a student's file
``aerophoto-course check NB...``       execute notebooks, print pass/fail per task; exit 1 on a failure
``aerophoto-course generate``          copy ``notebooks/`` into the course's ``source/`` (one assignment
                                       per chapter) and run nbgrader's generate_assignment → ``release/``
``aerophoto-course import FOLDER``     copy an LMS export (``<student_id>_<notebook>.ipynb`` files or
                                       ``<student_id>/`` folders) into ``submitted/``; originals untouched
``aerophoto-course autograde``         nbgrader autograde, every student × chapter, one at a time; a
                                       failure never stops the batch
``aerophoto-course gradebook``         a CSV (pandas): a column per task (grade_id), total, **flags**
``aerophoto-course feedback``          nbgrader's HTML feedback per student
=====================================  ==============================================================

Flags are what nbgrader 0.9.6 is silent about; they are found by reading the submitted and the
autograded notebooks:

* ``answer_error`` — an answer cell raised or timed out (an answer cell running ``while True: pass``
  after a correct definition still gets full marks from nbgrader);
* ``test_cell_deleted`` / ``test_cell_stripped`` — a test cell removed, or its nbgrader metadata
  stripped (nbgrader silently scores it 0); ``test_cell_edited`` — a locked test cell edited (nbgrader
  restored the original before grading, so the score is sound; the attempt is reported);
* ``record_book_mismatch`` / ``variant_mismatch`` — the record-book number declared in the setup cell
  (``RECORD_BOOK``), or the variant the notebook actually ran with, is not the student's;
* ``missing`` / ``corrupt`` / ``not_graded`` — no notebook, a file that is not a valid notebook, or a
  submission nbgrader could not grade.

**Student id and record-book number.**  The student id (the name nbgrader and the LMS export use) is the
record-book number (номер зачётной книжки) unless an optional roster CSV (``course/roster.csv`` or
``--roster``; columns ``student_id,record_book``) maps it to one.  While a submission is graded,
``AEROPHOTO_HOME`` is an empty temporary folder and ``AEROPHOTO_RECORD_BOOK`` is the *student's own*
number (or unset when it is unknown), so neither the grader's remembered number nor another student's
can choose the variant; a notebook whose first cell left ``RECORD_BOOK = None`` is graded for its owner.
"""

from __future__ import annotations

import argparse
import ast
import contextlib
import csv
import hashlib
import json
import logging
import os
import re
import shutil
import sys
import tempfile
import time
from dataclasses import dataclass, field
from pathlib import Path

__all__ = [
    "COURSE_ID",
    "DEFAULT_TIMEOUT_S",
    "GradedTask",
    "Flag",
    "Course",
    "graded_tasks",
    "student_version",
    "release_digest",
    "write_workbook",
    "check_notebook",
    "parse_record_book",
    "inspect_submission",
    "scan_submissions",
    "main",
]

COURSE_ID = "aerophoto"
DEFAULT_TIMEOUT_S = 120
"""Per-cell execution limit (seconds) while grading or checking; nbgrader's own default is 30 s."""

_SID_RE = re.compile(r"^\w[\w.@-]*$")
_COPY_SUFFIX = re.compile(r"\s*\(\d+\)$")  # "00_start_here (1)" as browsers and LMSs rename copies
_LOG = logging.getLogger("aerophoto.course")


# --------------------------------------------------------------------------------------------------
# environment


def _ensure_path() -> None:
    """Put the running Python's bin/ first on PATH (nbgrader runs ``alembic``, kernels run ``python``)."""
    bindir = str(Path(sys.executable).parent)
    parts = os.environ.get("PATH", "").split(os.pathsep)
    if parts[0:1] != [bindir]:
        os.environ["PATH"] = os.pathsep.join([bindir] + [p for p in parts if p and p != bindir])


@contextlib.contextmanager
def _grading_env(record_book: str | None):
    """An empty AEROPHOTO_HOME and the student's own record-book number (or none) for the kernel."""
    saved = {k: os.environ.get(k) for k in ("AEROPHOTO_HOME", "AEROPHOTO_RECORD_BOOK")}
    with tempfile.TemporaryDirectory(prefix="aerophoto-grading-") as home:
        os.environ["AEROPHOTO_HOME"] = home
        if record_book:
            os.environ["AEROPHOTO_RECORD_BOOK"] = str(record_book)
        else:
            os.environ.pop("AEROPHOTO_RECORD_BOOK", None)
        try:
            yield
        finally:
            for k, val in saved.items():
                if val is None:
                    os.environ.pop(k, None)
                else:
                    os.environ[k] = val


@contextlib.contextmanager
def _stderr_to(path: Path):
    """Send file descriptor 2 (this process's and the kernels' it starts) to ``path`` for a while.

    Kernels print start-up chatter ("running over TCP without encryption") and nbgrader's database
    layer prints SQLAlchemy warnings; the instructor's terminal shows progress lines instead, and the
    chatter stays in the course's log file.
    """
    sys.stderr.flush()
    saved = os.dup(2)
    try:
        with open(path, "ab") as fh:
            os.dup2(fh.fileno(), 2)
            try:
                yield
            finally:
                sys.stderr.flush()
                os.dup2(saved, 2)
    finally:
        os.close(saved)


def _need_nbgrader():
    try:
        import nbgrader  # noqa: F401
    except ImportError:
        raise SystemExit(
            "aerophoto-course needs nbgrader: python -m pip install -r environment.txt "
            "(or pip install 'aerophoto[course]')"
        ) from None


def _repo_root() -> Path | None:
    """The repository's top folder when aerophoto runs from a source checkout (editable install)."""
    top = Path(__file__).resolve().parents[2]
    if (top / "notebooks").is_dir() and (top / "pyproject.toml").is_file():
        return top
    return None


def default_notebooks_dir() -> Path:
    """The book's notebooks (the nbgrader source): ``./notebooks`` if present, else the checkout's."""
    here = Path.cwd() / "notebooks"
    if here.is_dir():
        return here
    top = _repo_root()
    return top / "notebooks" if top else here


def default_course_dir() -> Path:
    """``$AEROPHOTO_COURSE`` or ``./course``."""
    return Path(os.environ.get("AEROPHOTO_COURSE") or Path.cwd() / "course")


def chapters(notebooks_dir) -> list[Path]:
    """The chapter notebooks ``NN_*.ipynb`` directly in ``notebooks_dir``, sorted."""
    d = Path(notebooks_dir)
    return sorted(p for p in d.glob("*.ipynb") if re.match(r"^\d\d_", p.name))


# --------------------------------------------------------------------------------------------------
# the graded tasks of a notebook


def _nbg(cell) -> dict:
    return dict(cell.get("metadata", {}).get("nbgrader", {}) or {})


def _is_test(cell) -> bool:
    m = _nbg(cell)
    return bool(m.get("grade")) and not m.get("solution") and cell.get("cell_type") == "code"


def _is_answer(cell) -> bool:
    m = _nbg(cell)
    return bool(m.get("solution")) and cell.get("cell_type") == "code"


def _source(cell) -> str:
    src = cell.get("source", "")
    return "".join(src) if isinstance(src, list) else str(src)


@dataclass(frozen=True)
class GradedTask:
    """One graded task: its answer cell and its autograder test cell (nbgrader grade_ids)."""

    task: str
    answer_id: str | None
    check_id: str
    points: float


def graded_tasks(nb) -> list[GradedTask]:
    """The graded tasks of a notebook, in order: each test cell with the answer cell before it."""
    tasks, answer = [], None
    for cell in nb["cells"]:
        if _is_answer(cell):
            answer = _nbg(cell).get("grade_id")
        elif _is_test(cell):
            gid = str(_nbg(cell).get("grade_id"))
            task = gid[: -len("-check")] if gid.endswith("-check") else gid
            tasks.append(GradedTask(task, answer, gid, float(_nbg(cell).get("points", 0) or 0)))
            answer = None
    return tasks


def _course_config(root: Path | None = None, timeout: int | None = None):
    """The nbgrader Config: the course folder's nbgrader_config.py (or the packaged template)."""
    from traitlets.config.loader import PyFileConfigLoader

    path = (root / "nbgrader_config.py") if root is not None else None
    if path is None or not path.is_file():
        path = _template_path()
    cfg = PyFileConfigLoader(path.name, str(path.parent)).load_config()
    if root is not None:
        cfg.CourseDirectory.root = str(root)
    if "course_id" not in cfg.CourseDirectory:
        cfg.CourseDirectory.course_id = COURSE_ID
    if timeout is not None:
        cfg.ExecutePreprocessor.timeout = int(timeout)
    return cfg


def _template_path() -> Path:
    return Path(__file__).resolve().parent / "course_data" / "nbgrader_config.py"


def student_version(nb, config=None):
    """The student (release) version of a source notebook, made by nbgrader's own preprocessors.

    The same chain as ``nbgrader generate_assignment`` minus the gradebook steps: lock cells, clear
    solutions (the course's code stub), clear outputs, compute checksums, clear hidden tests.
    Returns a new notebook; ``nb`` is not changed.
    """
    import copy

    from nbgrader.preprocessors import (
        CheckCellMetadata,
        ClearHiddenTests,
        ClearMarkScheme,
        ClearOutput,
        ClearSolutions,
        ComputeChecksums,
        LockCells,
    )

    cfg = config if config is not None else _course_config()
    out = copy.deepcopy(nb)
    resources: dict = {}
    for pp_class in (LockCells, ClearSolutions, ClearOutput, CheckCellMetadata, ComputeChecksums,
                     ClearHiddenTests, ClearMarkScheme, ComputeChecksums, CheckCellMetadata):
        out, resources = pp_class(config=cfg).preprocess(out, resources)
    return out


def release_digest(nb) -> str:
    """A short fingerprint of a notebook's cells (type, id, source) — what a student version is made of."""
    h = hashlib.sha256()
    for c in nb["cells"]:
        h.update(json.dumps([c.get("cell_type"), c.get("id"), _source(c)], ensure_ascii=False).encode())
    return h.hexdigest()[:8]


def _write_nb(nb, path: Path) -> None:
    import nbformat

    nbformat.validate(nb)
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(nb, indent=1, ensure_ascii=False, sort_keys=True) + "\n", encoding="utf-8")


def _read_nb(path: Path):
    import nbformat

    return nbformat.read(str(path), as_version=4)


# --------------------------------------------------------------------------------------------------
# workbook: the student versions for self-study


def write_workbook(dest=None, notebooks_dir=None, *, out=print) -> list[tuple[str, Path]]:
    """Write the student version of every chapter into ``dest`` (default ``workbook/`` at the top).

    Never overwrites a file: a chapter already in ``dest`` is left as it is (it may hold the student's
    work).  If the chapter has changed since that copy was written, the new version is written beside
    it as ``NN_name.updated-<digest>.ipynb`` and a message says so.  Other files of ``notebooks/``
    (pictures, data) are copied when absent.  Returns ``[(action, path)]`` with action one of
    ``written``, ``kept``, ``updated-beside`` or ``failed`` (a chapter nbgrader cannot convert: reported,
    the others are still written).
    """
    _need_nbgrader()
    src_dir = Path(notebooks_dir) if notebooks_dir else default_notebooks_dir()
    if not src_dir.is_dir():
        raise SystemExit(f"no notebooks folder at {src_dir}: run from the repository's top folder or pass --notebooks")
    dest = Path(dest) if dest else src_dir.parent / "workbook"
    dest.mkdir(parents=True, exist_ok=True)
    cfg = _course_config()
    done = []
    for path in chapters(src_dir):
        try:
            release = student_version(_read_nb(path), cfg)
        except Exception as exc:  # one broken chapter must not keep the others from the student
            done.append(("failed", path))
            out(f"  SKIPPED {path.name}: no student version can be made ({type(exc).__name__}: {exc}) — "
                "tell your teacher")
            continue
        digest = release_digest(release)
        release.metadata.setdefault("aerophoto", {})["release"] = digest
        target = dest / path.name
        if not target.exists():
            _write_nb(release, target)
            done.append(("written", target))
            out(f"  wrote   {target}")
            continue
        old_digest = None
        try:
            old = json.loads(target.read_text(encoding="utf-8"))
            old_digest = old.get("metadata", {}).get("aerophoto", {}).get("release")
        except (OSError, ValueError):
            old = None
        if old_digest == digest or (old is not None and old_digest is None and release_digest(old) == digest):
            done.append(("kept", target))
            out(f"  kept    {target} (your copy; the chapter has not changed)")
            continue
        beside = dest / f"{path.stem}.updated-{digest}.ipynb"
        if not beside.exists():
            _write_nb(release, beside)
        done.append(("updated-beside", beside))
        out(f"  kept    {target} (your copy) — the chapter has changed since: the new version is {beside}; "
            "copy your answers across")
    for extra in sorted(src_dir.rglob("*")):
        rel = extra.relative_to(src_dir)
        if extra.is_dir() or extra.suffix == ".ipynb" or any(p.startswith(".") for p in rel.parts):
            continue
        if rel.parts[0] in {"__pycache__"}:
            continue
        target = dest / rel
        if not target.exists():
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(extra, target)
    return done


# --------------------------------------------------------------------------------------------------
# check: execute a notebook, pass/fail per task


@dataclass
class TaskOutcome:
    task: str
    passed: bool
    points: float
    message: str = ""
    ename: str = ""     # the exception of a failed check ("WrongAnswer" for a check's verdict)


@dataclass
class CheckResult:
    path: Path
    tasks: list[TaskOutcome] = field(default_factory=list)
    errors: list[tuple[str, str]] = field(default_factory=list)  # (cell id, "Ename: value") outside tests

    @property
    def ok(self) -> bool:
        return all(t.passed for t in self.tasks) and not self.errors


def _error_outputs(cell) -> list[dict]:
    return [o for o in cell.get("outputs", []) if o.get("output_type") == "error"]


def _stderr_text(cell) -> str:
    return "".join(
        "".join(o.get("text", "")) if isinstance(o.get("text"), list) else o.get("text", "")
        for o in cell.get("outputs", [])
        if o.get("output_type") == "stream" and o.get("name") == "stderr"
    )


def _one_line(text: str) -> str:
    text = re.sub(r"\x1b\[[0-9;]*m", "", str(text)).strip()
    return text.splitlines()[0] if text else ""


def _test_outcome(cell) -> tuple[bool, str, str]:
    """nbgrader's rule for an executed test cell: an error or any stderr output scores 0.

    Returns (passed, message, exception name)."""
    errs = _error_outputs(cell)
    if errs:
        e = errs[0]
        msg = _one_line(e.get("evalue", ""))
        ename = str(e.get("ename", ""))
        return False, (msg if ename == "WrongAnswer" and msg else f"{ename}: {msg}".rstrip(": ")), ename
    err = _stderr_text(cell)
    if err.strip():
        return False, "the check printed to stderr (nbgrader scores that 0): " + _one_line(err), "stderr"
    return True, "", ""


def executed_outcomes(nb) -> tuple[list[TaskOutcome], list[tuple[str, str]]]:
    """Per-task pass/fail and the errors outside test cells of an executed notebook."""
    outcomes, errors = [], []
    tests = {t.check_id: t for t in graded_tasks(nb)}
    for cell in nb["cells"]:
        if cell.get("cell_type") != "code":
            continue
        if _is_test(cell):
            gid = _nbg(cell).get("grade_id")
            ok, msg, ename = _test_outcome(cell)
            outcomes.append(TaskOutcome(tests[gid].task, ok, tests[gid].points, msg, ename))
        else:
            for e in _error_outputs(cell):
                errors.append((cell.get("id", "?"), f"{e.get('ename')}: {_one_line(e.get('evalue', ''))}".rstrip(": ")))
    return outcomes, errors


def check_notebook(path, *, timeout: int = DEFAULT_TIMEOUT_S, record_book: str | None = None) -> CheckResult:
    """Execute a copy of a notebook headless and report pass/fail per graded task.

    The notebook file is not changed.  With ``record_book`` the kernel runs with that number and an
    empty ``AEROPHOTO_HOME`` (as in grading); without, with the caller's own environment (the
    student's remembered number).  A cell running longer than ``timeout`` seconds is interrupted and
    counted as an error; the rest of the notebook still runs.
    """
    from nbclient import NotebookClient
    from nbclient.exceptions import DeadKernelError

    path = Path(path)
    nb = _read_nb(path)
    _ensure_path()
    client = NotebookClient(
        nb,
        timeout=timeout,
        interrupt_on_timeout=True,
        error_on_timeout={"ename": "CellTimeoutError", "evalue": f"the cell ran longer than {timeout} s",
                          "traceback": [f"CellTimeoutError: the cell ran longer than {timeout} s"]},
        allow_errors=True,
        kernel_name=nb.metadata.get("kernelspec", {}).get("name", "python3"),
        resources={"metadata": {"path": str(path.parent.resolve())}},
    )
    env = _grading_env(record_book) if record_book else contextlib.nullcontext()
    result = CheckResult(path)
    with env, tempfile.TemporaryDirectory(prefix="aerophoto-check-") as tmp:
        log = Path(tmp) / "kernel.log"
        try:
            with _stderr_to(log):
                client.execute()
        except DeadKernelError as exc:
            tail = log.read_text(encoding="utf-8", errors="replace").strip().splitlines()[-3:] if log.exists() else []
            result.errors.append(("?", f"the kernel died: {exc} {' / '.join(tail)}".strip()))
    tasks, errors = executed_outcomes(nb)
    result.tasks, result.errors = tasks, result.errors + errors
    return result


# --------------------------------------------------------------------------------------------------
# submissions: scanning an LMS export, the record book, flags


def parse_record_book(nb) -> tuple[str, object]:
    """What the setup cell declares: ``("value", "19-0457")``, ``("none", None)``, ``("missing", None)``
    (no setup cell or no ``RECORD_BOOK = ...`` line), or ``("unreadable", reason)``."""
    cells = [c for c in nb["cells"] if c.get("cell_type") == "code"]
    setup = next((c for c in cells if c.get("id") == "setup"), cells[0] if cells else None)
    if setup is None:
        return "missing", None
    src = _source(setup)
    try:
        tree = ast.parse(src)
    except SyntaxError as exc:
        return "unreadable", f"the setup cell is not valid Python ({exc.msg})"
    for node in tree.body:
        if isinstance(node, ast.Assign) and any(isinstance(t, ast.Name) and t.id == "RECORD_BOOK" for t in node.targets):
            if isinstance(node.value, ast.Constant):
                val = node.value.value
                if val is None or (isinstance(val, str) and not val.strip()):
                    return "none", None
                return "value", str(val).strip()
            return "unreadable", "RECORD_BOOK is not a plain number or string"
    return "missing", None


def _digits(text) -> str:
    return re.sub(r"\D", "", str(text or ""))


def _effective_variant(nb) -> int | None:
    """The variant the notebook ran with, from aerophoto.setup's banner in the setup cell's output."""
    for c in nb["cells"]:
        if c.get("cell_type") != "code":
            continue
        for o in c.get("outputs", []):
            data = o.get("data", {}) if isinstance(o.get("data"), dict) else {}
            texts = [data.get("text/html", ""), o.get("text", "")]
            for t in texts:
                t = "".join(t) if isinstance(t, list) else str(t)
                m = re.search(r"variant i = (\d{1,2})\b", t)
                if m:
                    return int(m.group(1))
    return None


@dataclass(frozen=True)
class Flag:
    """Something the instructor must look at; ``code`` is stable, ``message`` explains."""

    code: str
    message: str

    def __str__(self) -> str:
        return f"{self.code}: {self.message}"


def _cells_by_grade_id(nb) -> dict:
    return {str(_nbg(c).get("grade_id")): c for c in nb["cells"] if _nbg(c).get("grade_id")}


def _norm_src(text: str) -> str:
    return "\n".join(line.rstrip() for line in text.strip().splitlines())


def _notebook_problem(path: Path) -> str | None:
    """None for a readable notebook, else what is wrong with the file."""
    try:
        raw = path.read_text(encoding="utf-8")
    except UnicodeDecodeError:
        return "not a notebook: the file is not UTF-8 text"
    except OSError as exc:
        return f"cannot be read: {exc}"
    try:
        data = json.loads(raw)
    except ValueError as exc:
        return f"not valid JSON ({exc.msg} at line {exc.lineno}, column {exc.colno})"
    if not isinstance(data, dict) or "cells" not in data:
        return "not a notebook: valid JSON but no cells"
    try:
        import nbformat

        nb = nbformat.reads(raw, as_version=4)
        nbformat.validate(nb)
    except Exception as exc:  # nbformat raises several kinds
        return f"not a valid notebook ({type(exc).__name__}: {_one_line(str(exc))[:120]})"
    return None


def inspect_submission(release_nb, submitted_path: Path, autograded_path: Path | None,
                       expected_record_book: str | None) -> list[Flag]:
    """The flags of one submitted notebook (see the module docstring); empty when all is well.

    ``release_nb`` is the student version the class received (its test cells without hidden tests);
    ``autograded_path`` is nbgrader's executed copy (None or absent if not graded).
    """
    flags: list[Flag] = []
    if not submitted_path.exists():
        return [Flag("missing", "no notebook submitted")]
    problem = _notebook_problem(submitted_path)
    if problem:
        return [Flag("corrupt", f"{submitted_path.name} is {problem}; scored 0")]
    sub = _read_nb(submitted_path)

    # test and answer cells of the release version: deleted, stripped of metadata, edited
    sub_by_gid = _cells_by_grade_id(sub)
    sub_ids = {c.get("id") for c in sub.cells}
    for cell in release_nb["cells"]:
        m = _nbg(cell)
        gid = m.get("grade_id")
        if not gid or not (_is_test(cell) or _is_answer(cell)):
            continue
        kind = "test" if _is_test(cell) else "answer"
        if gid not in sub_by_gid:
            if cell.get("id") in sub_ids:
                flags.append(Flag(f"{kind}_cell_stripped",
                                  f"{gid}: the cell is there but its nbgrader metadata was removed"
                                  + ("; nbgrader scored it 0" if kind == "test" else "")))
            else:
                flags.append(Flag(f"{kind}_cell_deleted",
                                  f"{gid}: the cell was deleted" + ("; nbgrader scored it 0" if kind == "test" else "")))
        elif kind == "test" and _norm_src(_source(sub_by_gid[gid])) != _norm_src(_source(cell)):
            flags.append(Flag("test_cell_edited", f"{gid}: the locked test cell was edited "
                                                  "(nbgrader restored the original before grading)"))

    # student code reaching into the checks, or re-defining the variant the checks use
    release_sources = {_norm_src(_source(c)) for c in release_nb["cells"] if c.get("cell_type") == "code"}
    for cell in sub.cells:
        if cell.get("cell_type") != "code" or _is_test(cell) or cell.get("id") == "setup":
            continue
        src = _source(cell)
        if _norm_src(src) in release_sources:
            continue
        why = _suspicious(src)
        if why:
            flags.append(Flag("suspicious_code", f"cell {cell.get('id', '?')} {why}"))

    # record-book number
    expected_digits = _digits(expected_record_book)
    kind, value = parse_record_book(sub)
    if kind == "value" and expected_digits and _digits(value) != expected_digits:
        flags.append(Flag("record_book_mismatch",
                          f"RECORD_BOOK = {value!r} in the setup cell, but the student's record book is "
                          f"{expected_record_book!r}"))
    elif kind == "unreadable":
        flags.append(Flag("record_book_unreadable", str(value)))
    elif kind == "missing":
        flags.append(Flag("record_book_unreadable", "the setup cell has no RECORD_BOOK = ... line"))
    if len(expected_digits) < 2:
        flags.append(Flag("record_book_unknown", "no record-book number for this student id (add it to the "
                                                 "roster) — the variant cannot be verified"))

    # the executed copy: errors in answer (and other) cells, the variant actually used
    if autograded_path is None or not autograded_path.exists():
        flags.append(Flag("not_graded", "no autograded notebook (autograde failed or has not run)"))
        return flags
    graded = _read_nb(autograded_path)
    test_ok = {}
    for cell in graded.cells:
        if _is_test(cell):
            test_ok[_nbg(cell).get("grade_id")] = _test_outcome(cell)[0]
    answer_to_test = {t.answer_id: t.check_id for t in graded_tasks(graded) if t.answer_id}
    for cell in graded.cells:
        if cell.get("cell_type") != "code" or _is_test(cell):
            continue
        errs = _error_outputs(cell)
        if not errs:
            continue
        names = ", ".join(dict.fromkeys(str(e.get("ename")) for e in errs))
        if _is_answer(cell):
            gid = _nbg(cell).get("grade_id")
            what = "timed out (cut by the per-cell limit)" if "CellTimeoutError" in names else f"raised {names}"
            passed = test_ok.get(answer_to_test.get(gid))
            tail = "; its test still passed — nbgrader gave the points" if passed else ""
            flags.append(Flag("answer_error", f"{gid}: the answer cell {what}{tail}"))
        else:
            flags.append(Flag("cell_error", f"cell {cell.get('id', '?')} raised {names}"))
    used = _effective_variant(graded)
    if used is not None and len(expected_digits) >= 2 and used != int(expected_digits[-2:]):
        if not any(f.code == "record_book_mismatch" for f in flags):
            flags.append(Flag("variant_mismatch", f"graded as variant {used:02d}, but the student's variant is "
                                                  f"{int(expected_digits[-2:]):02d}"))
    return flags


_SUSPICIOUS = re.compile(r"\b(checks|check_value|check_values|check_count|check_bool|check_choice|task_passed|"
                         r"WrongAnswer|sys\.modules|builtins|__builtins__|NBGRADER_EXECUTION)\b")


def _suspicious(src: str) -> str:
    """Why a student's code cell deserves a look, or '' (a heuristic; the instructor decides)."""
    import io
    import tokenize

    try:  # names and operators only: a comment or a string saying "checks" is not suspicious
        code = " ".join(t.string for t in tokenize.generate_tokens(io.StringIO(src).readline)
                        if t.type not in (tokenize.COMMENT, tokenize.STRING))
    except (tokenize.TokenError, IndentationError, SyntaxError):
        code = src
    m = _SUSPICIOUS.search(code)
    if m:
        return f"refers to {m.group(1)!r} (the answer checks or the interpreter's internals)"
    try:
        tree = ast.parse(src)
    except SyntaxError:
        return ""
    for node in ast.walk(tree):
        if isinstance(node, ast.Name) and node.id == "v" and isinstance(node.ctx, ast.Store):
            return "assigns v, the variant the checks compute the expected answers from"
    return ""


@dataclass
class Scan:
    """What :func:`scan_submissions` found in an LMS export."""

    found: dict = field(default_factory=dict)          # (student_id, assignment) → Path
    duplicates: list = field(default_factory=list)     # (Path kept, [Paths ignored])
    unrecognised: list = field(default_factory=list)   # (Path, reason)


def scan_submissions(folder, assignments) -> Scan:
    """Recognise the submissions in an LMS export folder.

    Two layouts (mixed freely): ``<student_id>_<notebook>.ipynb`` at the top, or a folder per student,
    ``<student_id>/.../<notebook>.ipynb``.  ``<notebook>`` is a chapter name such as
    ``00_start_here``; a copy suffix `` (1)`` is ignored.  When one student has several files for a
    chapter, the newest (by modification time) is taken and the others are reported.
    """
    folder = Path(folder)
    names = sorted(assignments, key=len, reverse=True)
    candidates: dict = {}
    scan = Scan()
    for p in sorted(folder.rglob("*")):
        rel = p.relative_to(folder)
        if p.is_dir() or any(part.startswith(".") or part == "__MACOSX" for part in rel.parts):
            continue
        if p.suffix != ".ipynb":
            scan.unrecognised.append((p, "not a notebook (.ipynb)"))
            continue
        stem = _COPY_SUFFIX.sub("", p.stem)
        sid = nb_name = None
        if len(rel.parts) == 1:
            for a in names:
                if stem.endswith("_" + a) and len(stem) > len(a) + 1:
                    sid, nb_name = stem[: -len(a) - 1], a
                    break
            if nb_name is None:
                scan.unrecognised.append((p, "name is not <student_id>_<chapter>.ipynb for a known chapter"))
                continue
        else:
            sid = rel.parts[0]
            for a in names:
                if stem == a or stem.endswith("_" + a):
                    nb_name = a
                    break
            if nb_name is None:
                scan.unrecognised.append((p, f"not a known chapter notebook (in the folder of {sid})"))
                continue
        if not _SID_RE.match(sid):
            scan.unrecognised.append((p, f"student id {sid!r} has characters nbgrader cannot use "
                                         "(letters, digits, . _ @ - only)"))
            continue
        candidates.setdefault((sid, nb_name), []).append(p)
    for key, paths in sorted(candidates.items()):
        paths = sorted(paths, key=lambda q: (q.stat().st_mtime, str(q)))
        scan.found[key] = paths[-1]
        if len(paths) > 1:
            scan.duplicates.append((paths[-1], paths[:-1]))
    return scan


# --------------------------------------------------------------------------------------------------
# the course


@dataclass
class GradeResult:
    student: str
    assignment: str
    status: str            # graded, up-to-date, corrupt, missing, failed
    score: float = 0.0
    max_score: float = 0.0
    seconds: float = 0.0
    flags: list = field(default_factory=list)
    error: str = ""


class Course:
    """An nbgrader course folder for the book: ``source/``, ``release/``, ``submitted/``, ...

    Parameters
    ----------
    root : path
        The course folder (created with its nbgrader_config.py on first use).
    notebooks_dir : path, optional
        The book's notebooks, the nbgrader source (default: :func:`default_notebooks_dir`).
    roster : path, optional
        CSV with columns ``student_id,record_book`` (default ``<root>/roster.csv`` if present).
    timeout : int, optional
        Per-cell execution limit in seconds (default: the config file's, 120 s).
    out : callable
        Where progress lines go (``print``).
    """

    def __init__(self, root=None, notebooks_dir=None, *, roster=None, timeout=None, out=print):
        _need_nbgrader()
        _ensure_path()
        self.root = Path(root or default_course_dir()).resolve()
        self.notebooks_dir = Path(notebooks_dir) if notebooks_dir else default_notebooks_dir()
        self.timeout = timeout
        self.out = out
        self.root.mkdir(parents=True, exist_ok=True)
        cfg_file = self.root / "nbgrader_config.py"
        if not cfg_file.exists():
            shutil.copyfile(_template_path(), cfg_file)
        if roster is not None and not Path(roster).is_file():
            raise SystemExit(f"--roster {roster}: no such file (a CSV with columns student_id,record_book)")
        roster = Path(roster) if roster else self.root / "roster.csv"
        self.roster = _read_roster(roster) if roster.exists() else {}
        self._log = _course_logger(self.root)

    # paths -------------------------------------------------------------------------------------
    def path(self, step: str, assignment: str, student: str | None = None) -> Path:
        base = self.root / step
        return (base / student / assignment if student else base / assignment) / f"{assignment}.ipynb"

    @property
    def db_url(self) -> str:
        return f"sqlite:///{self.root / 'gradebook.db'}"

    def config(self):
        return _course_config(self.root, self.timeout)

    def coursedir(self, **attrs):
        from nbgrader.coursedir import CourseDirectory

        cd = CourseDirectory(config=self.config())
        for k, val in attrs.items():
            setattr(cd, k, val)
        return cd

    def assignments(self) -> list[str]:
        """The chapters, one assignment each (from notebooks/, else from source/)."""
        names = [p.stem for p in chapters(self.notebooks_dir)] if self.notebooks_dir.is_dir() else []
        if not names and (self.root / "source").is_dir():
            names = sorted(d.name for d in (self.root / "source").iterdir() if (d / f"{d.name}.ipynb").exists())
        return names

    def record_book(self, student: str) -> str | None:
        """The student's record-book number: the roster's, else the student id if it has ≥ 2 digits."""
        if student in self.roster:
            return self.roster[student]
        return student if len(_digits(student)) >= 2 else None

    def students(self) -> list[str]:
        """Everyone known: the roster, the submitted folders and the gradebook."""
        ids = set(self.roster)
        sub = self.root / "submitted"
        if sub.is_dir():
            ids |= {d.name for d in sub.iterdir() if d.is_dir() and not d.name.startswith(".")}
        if (self.root / "gradebook.db").exists():
            from nbgrader.api import Gradebook

            with Gradebook(self.db_url, COURSE_ID) as gb:
                ids |= {s.id for s in gb.students}
        return sorted(ids)

    def _run(self, converter_class, **attrs) -> dict:
        import warnings

        from nbgrader.utils import capture_log

        cd = self.coursedir(**{k: v for k, v in attrs.items() if k in ("assignment_id", "student_id")})
        app = converter_class(coursedir=cd, config=self.config(), log=self._log)
        for k, val in attrs.items():
            if k not in ("assignment_id", "student_id"):
                setattr(app, k, val)
        logfile = self.root / "aerophoto-course.log"
        handler = logging.FileHandler(logfile, encoding="utf-8")
        handler.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(message)s"))
        self._log.addHandler(handler)
        try:
            with warnings.catch_warnings(), _stderr_to(logfile):
                warnings.simplefilter("ignore")  # SQLAlchemy's SAWarnings from inside nbgrader
                return capture_log(app)
        finally:
            self._log.removeHandler(handler)
            handler.close()

    # generate ----------------------------------------------------------------------------------
    def sync_sources(self) -> list[str]:
        """Copy each chapter into ``source/<chapter>/<chapter>.ipynb`` (only when it changed)."""
        changed = []
        for nb_path in chapters(self.notebooks_dir):
            target = self.path("source", nb_path.stem)
            if target.exists() and target.read_bytes() == nb_path.read_bytes():
                continue
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(nb_path, target)
            changed.append(nb_path.stem)
        return changed

    def generate(self, assignments=None) -> dict[str, bool]:
        """nbgrader generate_assignment for every chapter (or the given ones) → ``release/``."""
        from nbgrader.converters import GenerateAssignment

        self.sync_sources()
        names = list(assignments or self.assignments())
        ok = {}
        for k, a in enumerate(names, 1):
            t0 = time.perf_counter()
            res = self._run(GenerateAssignment, assignment_id=a, force=True, create_assignment=True)
            ok[a] = bool(res.get("success"))
            status = "released" if ok[a] else "FAILED: " + _last_error(res)
            self.out(f"[{k}/{len(names)}] generate {a}: {status} ({time.perf_counter() - t0:.1f} s)")
        return ok

    def _in_gradebook(self, assignment: str) -> bool:
        if not (self.root / "gradebook.db").exists():
            return False
        from nbgrader.api import Gradebook, MissingEntry

        with Gradebook(self.db_url, COURSE_ID) as gb:
            try:
                gb.find_assignment(assignment)
                return True
            except MissingEntry:
                return False

    # import ------------------------------------------------------------------------------------
    def import_submissions(self, folder) -> Scan:
        """Copy an LMS export into ``submitted/<student>/<chapter>/<chapter>.ipynb``.

        The export is only read.  A submission that replaces a different earlier one is kept: the
        earlier file moves to ``replaced/<student>/<chapter>/``.  Files that are not valid notebooks
        are copied too (the gradebook flags them); unrecognised files are reported.
        """
        folder = Path(folder)
        if not folder.is_dir():
            raise SystemExit(f"import: {folder} is not a folder")
        scan = scan_submissions(folder, self.assignments())
        counts = {"new": 0, "updated": 0, "unchanged": 0}
        for n, ((sid, a), src) in enumerate(sorted(scan.found.items()), 1):
            dest = self.path("submitted", a, sid)
            if dest.exists() and dest.read_bytes() == src.read_bytes():
                counts["unchanged"] += 1
                continue
            if dest.exists():
                stamp = time.strftime("%Y%m%dT%H%M%S", time.localtime(dest.stat().st_mtime))
                keep = self.root / "replaced" / sid / a / f"{a}.{stamp}.ipynb"
                keep.parent.mkdir(parents=True, exist_ok=True)
                shutil.move(str(dest), keep)
                counts["updated"] += 1
            else:
                counts["new"] += 1
            dest.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(src, dest)  # modified now: newer than any earlier grading of this student
            problem = _notebook_problem(dest)
            note = f" — WARNING: {problem} (copied; it will be flagged)" if problem else ""
            self.out(f"[{n}/{len(scan.found)}] {sid} · {a} ← {src.relative_to(folder)}{note}")
        for kept, others in scan.duplicates:
            self.out(f"several files for one submission: took {kept.relative_to(folder)} (newest), ignored "
                     + ", ".join(str(o.relative_to(folder)) for o in others))
        for p, why in scan.unrecognised:
            self.out(f"unrecognised: {p.relative_to(folder)} — {why}")
        self.out(f"import: {counts['new']} new, {counts['updated']} updated, {counts['unchanged']} unchanged, "
                 f"{len(scan.unrecognised)} unrecognised file(s)")
        return scan

    # autograde ---------------------------------------------------------------------------------
    def submissions(self, students=None, assignments=None) -> list[tuple[str, str]]:
        """(student, assignment) pairs present in ``submitted/``."""
        known = set(self.assignments())
        pairs = []
        sub = self.root / "submitted"
        if not sub.is_dir():
            return pairs
        for sdir in sorted(d for d in sub.iterdir() if d.is_dir() and not d.name.startswith(".")):
            if students and sdir.name not in students:
                continue
            for adir in sorted(d for d in sdir.iterdir() if d.is_dir()):
                if adir.name in known and (not assignments or adir.name in assignments):
                    pairs.append((sdir.name, adir.name))
        return pairs

    def autograde(self, students=None, assignments=None, *, force: bool = False) -> list[GradeResult]:
        """nbgrader autograde for every submitted (student, chapter), one at a time.

        Each runs with an empty ``AEROPHOTO_HOME`` and the student's own record-book number; a file
        that is not a notebook is not given to nbgrader; an error never stops the batch.  A submission
        already graded and not changed since is skipped unless ``force``.
        """
        from nbgrader.converters import Autograde

        pairs = self.submissions(students, assignments)
        needed = sorted({a for _, a in pairs})
        missing = [a for a in needed if not self._in_gradebook(a) or not self.path("release", a).exists()]
        if missing:
            self.out(f"autograde: generating {', '.join(missing)} first")
            self.generate(missing)
        results = []
        t_all = time.perf_counter()
        for k, (sid, a) in enumerate(pairs, 1):
            prefix = f"[{k}/{len(pairs)}] {sid} · {a}:"
            sub_path, graded_path = self.path("submitted", a, sid), self.path("autograded", a, sid)
            r = GradeResult(sid, a, "graded")
            if not sub_path.exists():
                r.status = "missing"
            elif (problem := _notebook_problem(sub_path)) is not None:
                r.status, r.error = "corrupt", problem
            elif (not force and graded_path.exists() and self.path("source", a).exists()
                  and graded_path.stat().st_mtime >= sub_path.stat().st_mtime
                  and graded_path.stat().st_mtime >= self.path("source", a).stat().st_mtime):
                r.status = "up-to-date"
            else:
                t0 = time.perf_counter()
                try:
                    with _grading_env(self.record_book(sid)):
                        res = self._run(Autograde, assignment_id=a, student_id=sid, force=True, create_student=True)
                    if not res.get("success"):
                        r.status, r.error = "failed", _last_error(res)
                except Exception as exc:  # never stop the batch
                    r.status, r.error = "failed", f"{type(exc).__name__}: {exc}"
                r.seconds = time.perf_counter() - t0
            r.score, r.max_score = self._score(a, sid) if r.status in ("graded", "up-to-date") else (0.0, self._max(a))
            r.flags = self.flags(sid, a)
            results.append(r)
            note = f" — {r.error}" if r.error else ""
            fl = f" [{len(r.flags)} flag(s): {', '.join(sorted({f.code for f in r.flags}))}]" if r.flags else ""
            self.out(f"{prefix} {r.status} {r.score:g}/{r.max_score:g} ({r.seconds:.1f} s){fl}{note}")
        n_fail = sum(r.status in ("failed", "corrupt") for r in results)
        self.out(f"autograde: {len(results)} submission(s) in {time.perf_counter() - t_all:.0f} s, "
                 f"{n_fail} could not be graded, {sum(bool(r.flags) for r in results)} flagged")
        return results

    def _score(self, assignment: str, student: str) -> tuple[float, float]:
        from nbgrader.api import Gradebook, MissingEntry

        with Gradebook(self.db_url, COURSE_ID) as gb:
            try:
                s = gb.find_submission(assignment, student)
                return float(s.score), float(s.max_score)
            except MissingEntry:
                return 0.0, self._max(assignment)

    def _max(self, assignment: str) -> float:
        return sum(t.points for t in self._release_tasks(assignment))

    def _release_tasks(self, assignment: str) -> list[GradedTask]:
        p = self.path("release", assignment)
        return graded_tasks(_read_nb(p)) if p.exists() else []

    def flags(self, student: str, assignment: str) -> list[Flag]:
        """The flags of one student's chapter (see the module docstring)."""
        release = self.path("release", assignment)
        if not release.exists():
            return [Flag("not_generated", f"{assignment} has no student version: run aerophoto-course generate")]
        return inspect_submission(_read_nb(release), self.path("submitted", assignment, student),
                                  self.path("autograded", assignment, student), self.record_book(student))

    # gradebook ---------------------------------------------------------------------------------
    def gradebook(self, by: str = "submission"):
        """The grades as a pandas DataFrame.

        ``by="submission"``: a row per student × chapter (chapters that anyone submitted), columns
        ``student_id, record_book, assignment``, one per task (its grade_id), ``score, max_score,
        flags``.  ``by="student"``: a row per student, the task columns of every chapter, a
        ``total:<chapter>`` column per chapter, ``score, max_score, flags``.  Missing or unreadable
        submissions score 0 and carry a flag.
        """
        import pandas as pd
        from nbgrader.api import Gradebook, MissingEntry

        if by not in ("submission", "student"):
            raise ValueError(f"by = {by!r} is not valid; expected 'submission' or 'student'")
        collected = sorted({a for _, a in self.submissions()})
        active = [a for a in collected if self._release_tasks(a)]
        rows = []
        have_db = (self.root / "gradebook.db").exists()
        gb = Gradebook(self.db_url, COURSE_ID) if have_db else None
        try:
            for sid in self.students():
                for a in active:
                    tasks = self._release_tasks(a)
                    row = {"student_id": sid, "record_book": self.record_book(sid) or "", "assignment": a}
                    for t in tasks:
                        row[t.check_id] = 0.0
                    flags = self.flags(sid, a)
                    bad = {"missing", "corrupt", "not_graded"} & {f.code for f in flags}
                    if gb is not None and not bad:
                        try:
                            sub = gb.find_submission(a, sid)
                            for nb in sub.notebooks:
                                for g in nb.grades:
                                    if g.name in row:
                                        row[g.name] = float(g.score or 0.0)
                        except MissingEntry:
                            flags.append(Flag("not_graded", "not in nbgrader's gradebook"))
                    row["score"] = sum(row[t.check_id] for t in tasks)
                    row["max_score"] = sum(t.points for t in tasks)
                    row["flags"] = " | ".join(str(f) for f in flags)
                    rows.append(row)
        finally:
            if gb is not None:
                gb.close()
        df = pd.DataFrame(rows)
        if df.empty:
            return pd.DataFrame(columns=["student_id", "record_book", "assignment", "score", "max_score", "flags"])
        if by == "submission":
            task_cols = [c for c in df.columns if c not in ("student_id", "record_book", "assignment", "score",
                                                            "max_score", "flags")]
            return df[["student_id", "record_book", "assignment", *task_cols, "score", "max_score", "flags"]]
        out = []
        for sid, g in df.groupby("student_id", sort=True):
            row = {"student_id": sid, "record_book": g["record_book"].iloc[0]}
            for _, r in g.iterrows():
                for c in g.columns:
                    if c.startswith("task-") and not pd.isna(r[c]):
                        row[c] = r[c]
                row[f"total:{r['assignment']}"] = r["score"]
            row["score"] = float(g["score"].sum())
            row["max_score"] = float(g["max_score"].sum())
            row["flags"] = " | ".join(f"{r['assignment']}: {r['flags']}" for _, r in g.iterrows() if r["flags"])
            out.append(row)
        return pd.DataFrame(out)

    # feedback ----------------------------------------------------------------------------------
    def feedback(self, students=None, assignments=None) -> list[Path]:
        """nbgrader generate_feedback: ``feedback/<student>/<chapter>/<chapter>.html`` per graded chapter."""
        from nbgrader.converters import GenerateFeedback

        pairs = [(s, a) for s, a in self.submissions(students, assignments) if self.path("autograded", a, s).exists()]
        made = []
        for k, (sid, a) in enumerate(pairs, 1):
            res = self._run(GenerateFeedback, assignment_id=a, student_id=sid, force=True)
            html = self.root / "feedback" / sid / a / f"{a}.html"
            if res.get("success") and html.exists():
                made.append(html)
                self.out(f"[{k}/{len(pairs)}] {sid} · {a}: {html.relative_to(self.root)}")
            else:
                self.out(f"[{k}/{len(pairs)}] {sid} · {a}: FAILED — {_last_error(res)}")
        self.out(f"feedback: {len(made)} HTML file(s) in {self.root / 'feedback'}")
        return made


def _read_roster(path: Path) -> dict[str, str]:
    """``student_id → record_book`` from a CSV with those two columns (other columns ignored)."""
    with open(path, newline="", encoding="utf-8-sig") as fh:
        reader = csv.DictReader(fh)
        cols = {c.strip().lower(): c for c in (reader.fieldnames or [])}
        if "student_id" not in cols or "record_book" not in cols:
            raise ValueError(f"roster {path}: columns = {reader.fieldnames}; expected at least student_id,record_book")
        return {row[cols["student_id"]].strip(): row[cols["record_book"]].strip()
                for row in reader if row.get(cols["student_id"], "").strip()}


def _course_logger(root: Path) -> logging.Logger:
    """nbgrader's logger for this course: not shown in the terminal (see :meth:`Course._run`)."""
    log = logging.getLogger(f"aerophoto.course.nbgrader.{hashlib.sha1(str(root).encode()).hexdigest()[:8]}")
    log.propagate = False
    log.setLevel(logging.INFO)
    return log


def _last_error(res: dict) -> str:
    text = (res.get("log") or "") + "\n" + (res.get("error") or "")
    lines = [ln.strip() for ln in text.splitlines() if ln.strip()]
    errs = [ln for ln in lines if ln.startswith("[ERROR]")]
    pick = errs[0] if errs else (lines[-1] if lines else "unknown error")
    return pick.removeprefix("[ERROR]").strip()[:300]


# --------------------------------------------------------------------------------------------------
# command line


def _print_check(result: CheckResult, out=print) -> None:
    out(f"{result.path}:")
    if not result.tasks:
        out("  (no graded tasks)")
    for t in result.tasks:
        out(f"  {'✓' if t.passed else '✗'} {t.task} ({t.points:g} pt)" + ("" if t.passed else f" — {t.message}"))
    for cid, err in result.errors:
        out(f"  ✗ cell {cid}: {err}")
    n = sum(t.passed for t in result.tasks)
    out(f"  {n} of {len(result.tasks)} task(s) passed" + (f"; {len(result.errors)} cell error(s)" if result.errors else ""))


def main(argv=None) -> int:
    """``aerophoto-course`` — see ``aerophoto-course --help`` and README, "For instructors"."""
    ap = argparse.ArgumentParser(
        prog="aerophoto-course",
        description="The aerophoto course over nbgrader: student workbook, checks, generate, import, "
                    "autograde, gradebook, feedback.")
    ap.add_argument("--course", type=Path, default=None,
                    help="the course folder (default: $AEROPHOTO_COURSE or ./course)")
    ap.add_argument("--notebooks", type=Path, default=None,
                    help="the book's notebooks, the nbgrader source (default: ./notebooks)")
    ap.add_argument("--roster", type=Path, default=None,
                    help="CSV student_id,record_book (default: <course>/roster.csv if present)")
    sub = ap.add_subparsers(dest="cmd", required=True)

    p = sub.add_parser("workbook", help="write the student versions of all chapters (self-study)")
    p.add_argument("--dest", type=Path, default=None, help="folder (default: workbook/ beside notebooks/)")

    p = sub.add_parser("check", help="execute notebooks and report pass/fail per task (exit 1 on a failure)")
    p.add_argument("notebook", nargs="+", type=Path)
    p.add_argument("--timeout", type=int, default=DEFAULT_TIMEOUT_S, help="per-cell limit, s (default 120)")
    p.add_argument("--record-book", default=None,
                   help="run as this record-book number, with an empty AEROPHOTO_HOME (as in grading)")

    p = sub.add_parser("generate", help="student versions of all chapters into <course>/release (nbgrader)")
    p.add_argument("--assignment", action="append", help="only this chapter (repeatable)")

    p = sub.add_parser("import", help="copy an LMS export into <course>/submitted")
    p.add_argument("folder", type=Path)

    p = sub.add_parser("autograde", help="autograde every student and chapter (nbgrader)")
    p.add_argument("--assignment", action="append", help="only this chapter (repeatable)")
    p.add_argument("--student", action="append", help="only this student (repeatable)")
    p.add_argument("--force", action="store_true", help="re-grade submissions already graded")
    p.add_argument("--timeout", type=int, default=None, help="per-cell limit, s (default: the config's, 120)")

    p = sub.add_parser("gradebook", help="export the grades and flags as CSV")
    p.add_argument("--out", type=Path, default=None, help="CSV file (default: <course>/grades.csv)")
    p.add_argument("--by", choices=("submission", "student"), default="submission",
                   help="a row per student × chapter (default) or per student")

    p = sub.add_parser("feedback", help="HTML feedback per student (nbgrader)")
    p.add_argument("--assignment", action="append", help="only this chapter (repeatable)")
    p.add_argument("--student", action="append", help="only this student (repeatable)")

    args = ap.parse_args(argv)
    _ensure_path()

    def out(text):
        print(text, flush=True)

    if args.cmd == "workbook":
        done = write_workbook(args.dest, args.notebooks, out=out)
        n_new = sum(a == "written" for a, _ in done)
        n_failed = sum(a == "failed" for a, _ in done)
        out(f"workbook: {n_new} chapter(s) written, {len(done) - n_new - n_failed} kept as they were"
            + (f", {n_failed} skipped" if n_failed else ""))
        return 1 if done and n_failed == len(done) else 0
    if args.cmd == "check":
        status = 0
        for nb_path in args.notebook:
            if not nb_path.is_file():
                out(f"{nb_path}: no such notebook")
                status = max(status, 2)
                continue
            problem = _notebook_problem(nb_path)
            if problem:
                out(f"{nb_path}: {problem}")
                status = max(status, 2)
                continue
            res = check_notebook(nb_path, timeout=args.timeout, record_book=args.record_book)
            _print_check(res, out)
            if not res.ok:
                status = max(status, 1)
        return status

    course = Course(args.course, args.notebooks, roster=args.roster,
                    timeout=getattr(args, "timeout", None), out=out)
    if args.cmd == "generate":
        ok = course.generate(args.assignment)
        return 0 if all(ok.values()) else 1
    if args.cmd == "import":
        course.import_submissions(args.folder)
        return 0
    if args.cmd == "autograde":
        results = course.autograde(args.student, args.assignment, force=args.force)
        if not results:
            out(f"autograde: no submissions in {course.root / 'submitted'} — run aerophoto-course import first")
            return 1
        return 0
    if args.cmd == "gradebook":
        df = course.gradebook(by=args.by)
        dest = args.out or course.root / "grades.csv"
        dest.parent.mkdir(parents=True, exist_ok=True)
        df.to_csv(dest, index=False)
        out(f"gradebook: {len(df)} row(s), {int((df['flags'] != '').sum()) if len(df) else 0} flagged → {dest}")
        return 0
    if args.cmd == "feedback":
        course.feedback(args.student, args.assignment)
        return 0
    return 2  # pragma: no cover


if __name__ == "__main__":  # pragma: no cover
    raise SystemExit(main())
