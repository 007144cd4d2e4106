"""The versions of a chapter: the student book (``notebooks/``), the nbgrader source and the teacher's copy.

The repository's notebooks are the **student book**: each answer cell holds only its template lines
(``H_m = ...   # flying height, m`` — the names and order of the task's ``spec``), with nbgrader's
``solution: true`` metadata; no solution is stored anywhere in them.  The instructor's versions are made
from it by the package, which computes every reference answer (:func:`aerophoto.tasks.answers`):

* :func:`source_version` — nbgrader's source: each answer cell gets ``### BEGIN SOLUTION``, the
  reference solution (``_ref = tasks.answers("task-NN-k", v)``, one assignment per answer) and
  ``### END SOLUTION`` (``aerophoto-course generate`` writes it into ``course/source/``);
* :func:`teacher_version` — the solved copy for projecting (``aerophoto-course teacher``);
* :func:`strip_solutions` — the maintenance step that turned the old nbgrader source into the student
  book (re-runnable: ``python -m aerophoto.course strip-solutions notebooks/``).

Both generators accept an answer cell that still carries a solution block (they replace it) and one
with template lines only.
"""

from __future__ import annotations

import copy
import json
import re
import shutil
from pathlib import Path

from .common import (chapters, course_config, default_notebooks_dir, is_answer, is_test, nbg, read_nb,
                     release_digest, source, write_nb)

TEMPLATE_LINE = re.compile(r"^([A-Za-z_]\w*)\s*=\s*\.\.\.\s*(#.*)?$")
BEGIN, END = "### BEGIN SOLUTION", "### END SOLUTION"
HIDDEN_BEGIN, HIDDEN_END = "### BEGIN HIDDEN TESTS", "### END HIDDEN TESTS"


def _task_of(cell):
    """The registered task of an answer cell (None when its grade_id names no registered task)."""
    from .. import tasks

    gid = str(nbg(cell).get("grade_id", ""))
    try:
        return tasks.get(gid)
    except ValueError:
        return None


def template_part(src: str) -> list[str]:
    """The lines of an answer cell before its solution block (all of them when it has none)."""
    lines = src.splitlines()
    for i, ln in enumerate(lines):
        if "BEGIN SOLUTION" in ln:
            return lines[:i]
    return lines


def _block_removed(src: str, begin: str, end: str) -> str:
    out, inside = [], False
    for ln in src.splitlines():
        if begin.split("### ")[1] in ln and ln.strip().startswith("###"):
            inside = True
            continue
        if inside and end.split("### ")[1] in ln and ln.strip().startswith("###"):
            inside = False
            continue
        if not inside:
            out.append(ln)
    while out and not out[-1].strip():
        out.pop()
    return "\n".join(out)


def template_names(lines) -> list[str]:
    return [m.group(1) for ln in lines if (m := TEMPLATE_LINE.match(ln.strip()))]


def student_answer_source(cell) -> str:
    """What the student book's answer cell holds: its template lines (the task's spec) and comments only."""
    lines = [ln for ln in template_part(source(cell))
             if not ln.strip() or ln.strip().startswith("#") or TEMPLATE_LINE.match(ln.strip())]
    task = _task_of(cell)
    if task is not None and template_names(lines) != list(task.names):
        return task.template()
    while lines and not lines[-1].strip():
        lines.pop()
    return "\n".join(lines)


def strip_solutions(nb) -> tuple[object, list[str]]:
    """The student book of a notebook: solution blocks (and any hidden-test blocks) removed, outputs cleared.

    Cells are found by id (:mod:`aerophoto.nbtools`); a cell already stripped is left as it is, so the
    step can run any number of times.  Returns ``(new notebook, ids of the cells changed)``.
    """
    from .. import nbtools

    out = copy.deepcopy(nb)
    changed = []
    for cell_id in [c.get("id") for c in out.cells if is_answer(c) or is_test(c)]:
        _, cell = nbtools.find_cell(out, cell_id)
        new = student_answer_source(cell) if is_answer(cell) else _block_removed(source(cell), HIDDEN_BEGIN,
                                                                                 HIDDEN_END)
        if new != source(cell):
            nbtools.set_cell(out, cell_id, new)
            changed.append(cell_id)
    nbtools.strip_outputs(out)
    return out, changed


def strip_solutions_in(folder, *, write: bool = True, out=print) -> dict[str, list[str]]:
    """Strip every chapter notebook of ``folder`` in place (see :func:`strip_solutions`); {file: changed ids}."""
    from .. import nbtools

    done = {}
    for path in sorted(Path(folder).glob("*.ipynb")):
        nb = read_nb(path)
        new, changed = strip_solutions(nb)
        if changed:
            done[path.name] = changed
            if write:
                nbtools.write(new, path)
            out(f"  {'stripped' if write else 'would strip'} {path.name}: {', '.join(changed)}")
    out(f"strip-solutions: {len(done)} notebook(s) {'changed' if write else 'to change'}")
    return done


def reference_lines(task) -> list[str]:
    """The reference solution of a task: computed by the package for the notebook's variant ``v``."""
    lines = ["from aerophoto import tasks as _tasks", f'_ref = _tasks.answers("{task.id}", v)']
    lines += [f'{name} = _ref["{name}"]' for name in task.names]
    return lines


def _solved(nb, *, teacher: bool):
    out = copy.deepcopy(nb)
    missing = []
    for cell in out.cells:
        if not is_answer(cell):
            continue
        task = _task_of(cell)
        if task is None:
            missing.append(str(nbg(cell).get("grade_id")))
            continue
        template = student_answer_source(cell).splitlines()
        if teacher:
            cell.source = "\n".join(["# reference solution (teacher's copy), computed by aerophoto.tasks for v",
                                     *reference_lines(task)])
        else:
            cell.source = "\n".join([*template, BEGIN, *reference_lines(task), END])
        cell.outputs, cell.execution_count = [], None
    for cell in out.cells:
        if is_test(cell):
            cell.source = _block_removed(source(cell), HIDDEN_BEGIN, HIDDEN_END)
    if missing:
        raise ValueError(f"answer cells without a registered task in aerophoto.tasks: {missing}")
    return out


def source_version(nb):
    """nbgrader's source version of a student-book chapter (reference solutions between the markers)."""
    return _solved(nb, teacher=False)


def teacher_version(nb):
    """The solved teacher's copy of a chapter (for projecting): each answer cell computes the reference."""
    return _solved(nb, teacher=True)


def student_version(nb, config=None):
    """The release version of an nbgrader source notebook, made by nbgrader's own preprocessors.

    The same chain as ``nbgrader generate_assignment`` minus the gradebook steps: lock cells, clear
    solutions (the course's code stub), clear outputs, compute checksums, clear hidden tests.
    Returns a new notebook; ``nb`` is not changed.
    """
    from nbgrader.preprocessors import (
        CheckCellMetadata,
        ClearHiddenTests,
        ClearMarkScheme,
        ClearOutput,
        ClearSolutions,
        ComputeChecksums,
        LockCells,
    )

    cfg = config if config is not None else course_config()
    out = copy.deepcopy(nb)
    resources: dict = {}
    for pp_class in (LockCells, ClearSolutions, ClearOutput, CheckCellMetadata, ComputeChecksums,
                     ClearHiddenTests, ClearMarkScheme, ComputeChecksums, CheckCellMetadata):
        out, resources = pp_class(config=cfg).preprocess(out, resources)
    return out


def _is_translation_source(path: Path) -> bool:
    """A chapter's Russian text (``ru/NN_name.md`` beside ``NN_name.ipynb``, :func:`aerophoto.i18n.prose.translation_path`):
    the book's source, read where the book is built — never a file of a student's or a teacher's copy."""
    return path.suffix == ".md" and path.parent.name == "ru" and (path.parent.parent / f"{path.stem}.ipynb").is_file()


def _copy_extras(src_dir: Path, dest: Path) -> None:
    for extra in sorted(src_dir.rglob("*")):
        rel = extra.relative_to(src_dir)
        if extra.is_dir() or extra.suffix == ".ipynb" or any(p.startswith(".") for p in rel.parts):
            continue
        if rel.parts[0] in {"__pycache__"} or _is_translation_source(extra):
            continue
        target = dest / rel
        if not target.exists():
            target.parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(extra, target)


def write_workbook(dest=None, notebooks_dir=None, *, out=print) -> list[tuple[str, Path]]:
    """Copy the student book into ``dest`` (default ``workbook/`` at the top), for self-study.

    Never overwrites a file: a chapter already in ``dest`` is left as it is (it may hold the student's
    work).  If the chapter has changed since that copy was written, the new version is written beside
    it as ``NN_name.updated-<digest>.ipynb`` and a message says so.  Other files of ``notebooks/``
    (pictures, data) are copied when absent.  Returns ``[(action, path)]`` with action one of
    ``written``, ``kept``, ``updated-beside`` or ``failed`` (a chapter that cannot be read: reported,
    the others are still written).  Any solution block left in a chapter is removed on the way.
    """
    src_dir = Path(notebooks_dir) if notebooks_dir else default_notebooks_dir()
    if not src_dir.is_dir():
        raise SystemExit(f"no notebooks folder at {src_dir}: run from the repository's top folder or pass --notebooks")
    dest = Path(dest) if dest else src_dir.parent / "workbook"
    dest.mkdir(parents=True, exist_ok=True)
    done = []
    for path in chapters(src_dir):
        try:
            book, _ = strip_solutions(read_nb(path))
        except Exception as exc:  # one broken chapter must not keep the others from the student
            done.append(("failed", path))
            out(f"  SKIPPED {path.name}: it cannot be read ({type(exc).__name__}: {exc}) — tell your teacher")
            continue
        digest = release_digest(book)
        book.metadata.setdefault("aerophoto", {})["release"] = digest
        target = dest / path.name
        if not target.exists():
            write_nb(book, target)
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
            write_nb(book, beside)
        done.append(("updated-beside", beside))
        out(f"  kept    {target} (your copy) — the chapter has changed since: the new version is {beside}; "
            "copy your answers across")
    _copy_extras(src_dir, dest)
    return done


def write_teacher(dest, notebooks_dir=None, *, out=print) -> list[Path]:
    """The teacher's copy of every chapter into ``dest`` (overwritten: it is generated)."""
    src_dir = Path(notebooks_dir) if notebooks_dir else default_notebooks_dir()
    if not src_dir.is_dir():
        raise SystemExit(f"no notebooks folder at {src_dir}: run from the repository's top folder or pass --notebooks")
    dest = Path(dest)
    made = []
    for path in chapters(src_dir):
        try:
            nb = teacher_version(read_nb(path))
        except Exception as exc:
            out(f"  SKIPPED {path.name}: {type(exc).__name__}: {exc}")
            continue
        write_nb(nb, dest / path.name)
        made.append(dest / path.name)
        out(f"  wrote   {dest / path.name}")
    _copy_extras(src_dir, dest)
    out(f"teacher: {len(made)} chapter(s) with reference solutions in {dest} — not for students")
    return made
