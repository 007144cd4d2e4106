"""What every part of the course tools shares: paths, the nbgrader config, notebook cells, flags."""

from __future__ import annotations

import contextlib
import csv
import hashlib
import json
import logging
import os
import re
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

from .limits import GRADING

COURSE_ID = "aerophoto"
DEFAULT_TIMEOUT_S = GRADING.cell_s
"""Per-cell execution limit (seconds) while grading or checking (:attr:`.limits.Limits.cell_s`); nbgrader's own
default is 30 s."""

SID_RE = re.compile(r"^\w[\w.@-]*$")
_LOG = logging.getLogger("aerophoto.course")


# --------------------------------------------------------------------------------------------------
# environment


def ensure_path() -> None:
    """Put the running Python's bin/ first on PATH (nbgrader runs ``alembic``, kernels run ``python``).

    A virtual environment made with ``--system-site-packages`` imports the base Python's packages, whose scripts
    (``alembic`` among them) live in the base Python's bin/: that one follows, when it is another."""
    first = [str(Path(sys.executable).parent)]
    base = Path(sys.base_prefix) / "bin"
    if Path(sys.prefix) != Path(sys.base_prefix) and base.is_dir():
        first.append(str(base))
    parts = os.environ.get("PATH", "").split(os.pathsep)
    if parts[:len(first)] != first:
        os.environ["PATH"] = os.pathsep.join(first + [p for p in parts if p and p not in first])


@contextlib.contextmanager
def stderr_to(path: Path):
    """Send file descriptor 2 (this process's and the kernels' it starts) to ``path`` for a while.

    Kernels print start-up chatter and nbgrader's database layer prints SQLAlchemy warnings; the
    instructor's terminal shows progress lines instead, and the chatter stays in the course's log file.
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


def need_nbgrader():
    try:
        import nbgrader  # noqa: F401
    except ImportError:
        raise SystemExit(
            "aerophoto-course needs nbgrader: python -m pip install -r environment.txt "
            "(or pip install 'aerophoto[course]')"
        ) from None


def repo_root() -> Path | None:
    """The repository's top folder when aerophoto runs from a source checkout (editable install)."""
    top = Path(__file__).resolve().parents[3]
    if (top / "notebooks").is_dir() and (top / "pyproject.toml").is_file():
        return top
    return None


def default_notebooks_dir() -> Path:
    """The student book's notebooks: ``./notebooks`` if present, else the checkout's (no solutions in it)."""
    here = Path.cwd() / "notebooks"
    if here.is_dir():
        return here
    top = repo_root()
    return top / "notebooks" if top else here


def default_course_dir() -> Path:
    """``$AEROPHOTO_COURSE`` or ``./course``."""
    return Path(os.environ.get("AEROPHOTO_COURSE") or Path.cwd() / "course")


def chapters(notebooks_dir) -> list[Path]:
    """The chapter notebooks ``NN_*.ipynb`` directly in ``notebooks_dir``, sorted."""
    d = Path(notebooks_dir)
    return sorted(p for p in d.glob("*.ipynb") if re.match(r"^\d\d_", p.name))


# --------------------------------------------------------------------------------------------------
# cells


def nbg(cell) -> dict:
    meta = cell.get("metadata", {}) or {}
    m = meta.get("nbgrader", {}) if isinstance(meta, dict) else {}
    return dict(m) if isinstance(m, dict) else {}


def is_test(cell) -> bool:
    m = nbg(cell)
    return bool(m.get("grade")) and not m.get("solution") and cell.get("cell_type") == "code"


def is_answer(cell) -> bool:
    m = nbg(cell)
    return bool(m.get("solution")) and cell.get("cell_type") == "code"


def source(cell) -> str:
    src = cell.get("source", "")
    return "".join(src) if isinstance(src, list) else str(src)


def one_line(text: str) -> str:
    text = re.sub(r"\x1b\[[0-9;]*m", "", str(text)).strip()
    return text.splitlines()[0] if text else ""


def digits(text) -> str:
    return re.sub(r"\D", "", str(text or ""))


def norm_src(text: str) -> str:
    return "\n".join(line.rstrip() for line in text.strip().splitlines())


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
        if is_answer(cell):
            answer = nbg(cell).get("grade_id")
        elif is_test(cell):
            gid = str(nbg(cell).get("grade_id"))
            task = gid[: -len("-check")] if gid.endswith("-check") else gid
            tasks.append(GradedTask(task, answer, gid, float(nbg(cell).get("points", 0) or 0)))
            answer = None
    return tasks


def cells_by_grade_id(nb) -> dict:
    return {str(nbg(c).get("grade_id")): c for c in nb["cells"] if nbg(c).get("grade_id")}


@dataclass(frozen=True)
class Flag:
    """Something the instructor must look at; ``code`` is stable, ``message`` explains."""

    code: str
    message: str

    def __str__(self) -> str:
        return f"{self.code}: {self.message}"


# --------------------------------------------------------------------------------------------------
# the nbgrader configuration


def template_path() -> Path:
    return Path(__file__).resolve().parent.parent / "course_data" / "nbgrader_config.py"


def course_config(root: Path | None = None, timeout: int | None = None):
    """The nbgrader Config: the course folder's nbgrader_config.py (or the packaged template)."""
    from traitlets.config.loader import PyFileConfigLoader

    path = (root / "nbgrader_config.py") if root is not None else None
    if path is None or not path.is_file():
        path = template_path()
    cfg = PyFileConfigLoader(path.name, str(path.parent)).load_config()
    if root is not None:
        cfg.CourseDirectory.root = str(root)
    if "course_id" not in cfg.CourseDirectory:
        cfg.CourseDirectory.course_id = COURSE_ID
    if timeout is not None:
        cfg.ExecutePreprocessor.timeout = int(timeout)
    return cfg


# --------------------------------------------------------------------------------------------------
# notebook files


def write_atomic(path: Path, data: bytes) -> None:
    """Write ``data`` to ``path`` through a temporary file in the same folder and a rename: all or nothing."""
    path = Path(path)
    path.parent.mkdir(parents=True, exist_ok=True)
    fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=path.parent)
    try:
        with os.fdopen(fd, "wb") as fh:
            fh.write(data)
            fh.flush()
            os.fsync(fh.fileno())
        os.replace(tmp, path)
    except BaseException:
        with contextlib.suppress(OSError):
            os.unlink(tmp)
        raise


def nb_bytes(nb) -> bytes:
    import nbformat

    nbformat.validate(nb)
    return (json.dumps(nb, indent=1, ensure_ascii=False, sort_keys=True) + "\n").encode("utf-8")


def write_nb(nb, path: Path) -> None:
    write_atomic(Path(path), nb_bytes(nb))


def read_nb(path: Path):
    import nbformat

    return nbformat.read(str(path), as_version=4)


MAX_NOTEBOOK_MB = 64
"""The largest submitted notebook read at all (MB); a larger file is reported corrupt, never parsed."""


def notebook_problem(path: Path) -> str | None:
    """None for a readable notebook (nbformat 4, or 3 which is converted), else what is wrong with the file.

    Never raises: a file too large (:data:`MAX_NOTEBOOK_MB`), binary, not JSON, JSON nested too deep to
    read, or not a valid notebook is a problem, reported in words.
    """
    try:
        size = Path(path).stat().st_size
        if size > MAX_NOTEBOOK_MB * 1024 * 1024:
            return f"too large ({size / 1024 / 1024:.0f} MB; a notebook is read up to {MAX_NOTEBOOK_MB} MB)"
        raw = Path(path).read_text(encoding="utf-8")
    except UnicodeDecodeError:
        return "not a notebook: the file is not UTF-8 text"
    except OSError as exc:
        return f"cannot be read: {exc}"
    if "\x00" in raw:
        return "not a notebook: the file holds binary data (NUL bytes)"
    try:
        data = json.loads(raw)
    except ValueError as exc:
        return f"not valid JSON ({getattr(exc, 'msg', exc)} at line {getattr(exc, 'lineno', '?')}, " \
               f"column {getattr(exc, 'colno', '?')})"
    except RecursionError:
        return "not a notebook: its JSON is nested too deep to read"
    except MemoryError:
        return "not a notebook: too large to read"
    if not isinstance(data, dict) or ("cells" not in data and "worksheets" not in data):
        return "not a notebook: valid JSON but no cells"
    try:
        import nbformat

        nb = nbformat.reads(raw, as_version=4)
        nbformat.validate(nb)
    except Exception as exc:  # nbformat raises several kinds (RecursionError too)
        return f"not a valid notebook ({type(exc).__name__}: {one_line(str(exc))[:120]})"
    return None


def nbformat_major(path: Path) -> int | None:
    try:
        return int(json.loads(Path(path).read_text(encoding="utf-8")).get("nbformat"))
    except (OSError, ValueError, TypeError, AttributeError, RecursionError, MemoryError):
        return None


def release_digest(nb) -> str:
    """A short fingerprint of a notebook's cells (type, id, source) — what a student version is made of."""
    h = hashlib.sha256()
    for c in nb["cells"]:
        h.update(json.dumps([c.get("cell_type"), c.get("id"), source(c)], ensure_ascii=False).encode())
    return h.hexdigest()[:8]


def read_roster(path: Path) -> dict[str, str]:
    """``student_id → record_book`` from a CSV with those two columns (other columns ignored)."""
    with open(path, newline="", encoding="utf-8-sig") as fh:
        reader = csv.DictReader(fh)
        cols = {c.strip().lower(): c for c in (reader.fieldnames or [])}
        if "student_id" not in cols or "record_book" not in cols:
            raise ValueError(f"roster {path}: columns = {reader.fieldnames}; expected at least student_id,record_book")
        return {row[cols["student_id"]].strip(): row[cols["record_book"]].strip()
                for row in reader if row.get(cols["student_id"], "").strip()}


def last_error(res: dict) -> str:
    text = (res.get("log") or "") + "\n" + (res.get("error") or "")
    lines = [ln.strip() for ln in text.splitlines() if ln.strip()]
    errs = [ln for ln in lines if ln.startswith("[ERROR]")]
    pick = errs[0] if errs else (lines[-1] if lines else "unknown error")
    return pick.removeprefix("[ERROR]").strip()[:300]
