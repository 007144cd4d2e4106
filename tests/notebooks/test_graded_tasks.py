"""The graded-task convention (docs/CONTRIBUTING.md, "Graded tasks") holds in every notebook.

The notebooks in notebooks/ are the *student book*: answer cells hold only their template lines (the task's
spec), no solution anywhere, no hidden tests.  The instructor's nbgrader source and the teacher's copy are
generated from them (aerophoto.course.source_version / teacher_version).  These tests check ids, metadata,
markers, template lines, the checks used, that the generated source makes nbgrader's student version, and
that the book runs for a student who has not answered (every check fails with "no answer yet").
"""

from __future__ import annotations

import ast
import io
import re
import tokenize

import nbformat
import pytest

from aerophoto.course import graded_tasks, source_version, student_version, teacher_version
from conftest import all_notebooks

NOTEBOOKS = all_notebooks()
IDS = [p.stem for p in NOTEBOOKS]
CHAPTERS = [p for p in NOTEBOOKS if re.match(r"^\d\d_", p.name)]

ANSWER_META = {"grade": False, "locked": False, "schema_version": 3, "solution": True, "task": False}
TEST_META = {"grade": True, "locked": True, "schema_version": 3, "solution": False, "task": False}
TEMPLATE = re.compile(r"^([A-Za-z_]\w*)\s*=\s*\.\.\.\s*(#.*)?$")
CHECK_CALL = re.compile(r"\bchecks\.check_task\(")


def read(path):
    return nbformat.read(str(path), as_version=4)


def nbg(cell) -> dict:
    return dict(cell.metadata.get("nbgrader", {}))


def number(path) -> str | None:
    m = re.match(r"^(\d\d)_", path.name)
    return m.group(1) if m else None


def split_answer(src: str):
    """(lines before BEGIN SOLUTION, solution lines, lines after END SOLUTION) or None if unmarked."""
    lines = src.splitlines()
    begins = [i for i, ln in enumerate(lines) if "BEGIN SOLUTION" in ln]
    ends = [i for i, ln in enumerate(lines) if "END SOLUTION" in ln]
    if len(begins) != 1 or len(ends) != 1 or ends[0] < begins[0]:
        return None
    return lines[: begins[0]], lines[begins[0] + 1: ends[0]], lines[ends[0] + 1:]


def template_names(answer_src: str) -> list[str]:
    """The names of the template lines ``name = ...`` of an answer cell (before any solution block)."""
    lines = answer_src.splitlines()
    parts = split_answer(answer_src)
    if parts is not None:
        lines = parts[0]
    return [m.group(1) for ln in lines if (m := TEMPLATE.match(ln.strip()))]


def assigned_names(code: str) -> set[str]:
    names = set()
    for node in ast.walk(ast.parse(code)):
        if isinstance(node, ast.Name) and isinstance(node.ctx, ast.Store):
            names.add(node.id)
    return names


def loaded_names(code: str) -> set[str]:
    return {n.id for n in ast.walk(ast.parse(code)) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}


def displays_a_value(code: str) -> bool:
    """Would IPython show the value of this cell's last statement (nbgrader reads it as partial credit)?"""
    body = ast.parse(code).body
    if not body or not isinstance(body[-1], ast.Expr):
        return False
    last = body[-1].value
    if isinstance(last, ast.Call) and isinstance(last.func, ast.Attribute) and last.func.attr in ("task_passed",
                                                                                                   "check_task"):
        return False  # returns None: nothing is displayed
    # IPython's rule: a trailing ';' (comments after it do not count) silences the value
    skip = {tokenize.COMMENT, tokenize.NL, tokenize.NEWLINE, tokenize.ENDMARKER, tokenize.INDENT, tokenize.DEDENT}
    toks = [t for t in tokenize.generate_tokens(io.StringIO(code).readline) if t.type not in skip]
    return not (toks and toks[-1].string == ";")


def task_cells(nb):
    """[(answer_index, answer_cell, test_index or None, test_cell or None)] for every answer cell."""
    out = []
    for i, c in enumerate(nb.cells):
        if nbg(c).get("solution"):
            nxt = nb.cells[i + 1] if i + 1 < len(nb.cells) else None
            is_test = nxt is not None and nbg(nxt).get("grade") and not nbg(nxt).get("solution")
            out.append((i, c, i + 1 if is_test else None, nxt if is_test else None))
    return out


# --------------------------------------------------------------------------------------------------


def test_there_are_graded_tasks():
    assert any(graded_tasks(read(p)) for p in NOTEBOOKS)
    assert [t.check_id for t in graded_tasks(read(next(p for p in NOTEBOOKS if p.stem == "00_start_here")))] == [
        "task-00-1-check"]


def lint_unique(named_notebooks) -> list[str]:
    """Duplicate grade_ids across the book ([(name, nb)]); the gradebook has one column per grade_id."""
    seen: dict[str, str] = {}
    dupes = []
    for name, nb in named_notebooks:
        for c in nb.cells:
            gid = nbg(c).get("grade_id")
            if gid is None:
                continue
            if gid in seen:
                dupes.append(f"{gid} in {seen[gid]} and {name}")
            seen[gid] = name
    return dupes


def test_grade_ids_are_unique_across_the_book():
    dupes = lint_unique([(p.name, read(p)) for p in NOTEBOOKS])
    assert not dupes, f"duplicate nbgrader grade_ids (the gradebook has one column per grade_id): {dupes}"


def lint_setup(nb, path) -> list[str]:
    code = [c for c in nb.cells if c.cell_type == "code"]
    if not code or code[0].get("id") != "setup":
        return ["the first code cell must have id 'setup'"]
    setup = code[0]
    problems = []
    if "nbgrader" in setup.metadata:
        problems.append("the setup cell must not be an nbgrader cell (students type their number in it)")
    try:
        tree = ast.parse(setup.source)
    except SyntaxError as exc:
        return problems + [f"the setup cell is not valid Python ({exc.msg})"]
    decl = [n for n in tree.body if isinstance(n, ast.Assign)
            and any(isinstance(t, ast.Name) and t.id == "RECORD_BOOK" for t in n.targets)]
    if not decl:
        problems.append("the setup cell must declare RECORD_BOOK = None")
    elif not (isinstance(decl[0].value, ast.Constant) and decl[0].value.value is None):
        problems.append("the book ships with RECORD_BOOK = None (each student types their own number)")
    if not re.search(r"\bv\s*=\s*aerophoto\.setup\(RECORD_BOOK\)", setup.source):
        problems.append("the setup cell must call v = aerophoto.setup(RECORD_BOOK)")
    return problems


@pytest.mark.parametrize("path", CHAPTERS, ids=[p.stem for p in CHAPTERS])
def test_setup_cell_declares_record_book_and_is_not_graded(path):
    problems = lint_setup(read(path), path)
    assert not problems, f"{path.name}: " + "; ".join(problems)


def lint_metadata(nb, path) -> list[str]:
    nn = number(path)
    problems = []
    for c in nb.cells:
        m = nbg(c)
        if not m:
            continue
        gid = m.get("grade_id", "")
        base = {k: m.get(k) for k in ANSWER_META}
        if m.get("solution"):
            if base != ANSWER_META or "points" in m:
                problems.append(f"{gid}: answer-cell metadata {m} != {ANSWER_META} + grade_id")
            if not re.fullmatch(rf"task-{nn}-\d+-answer", gid or ""):
                problems.append(f"{gid!r}: an answer cell's grade_id is task-{nn}-k-answer")
        elif m.get("grade"):
            if base != TEST_META:
                problems.append(f"{gid}: test-cell metadata {m} != {TEST_META} + grade_id + points")
            if not re.fullmatch(rf"task-{nn}-\d+-check", gid or ""):
                problems.append(f"{gid!r}: a test cell's grade_id is task-{nn}-k-check")
            pts = m.get("points")
            if not isinstance(pts, (int, float)) or isinstance(pts, bool) or not pts > 0:
                problems.append(f"{gid}: points = {pts!r}; a test cell is worth a positive number of points")
        else:
            problems.append(f"{c.get('id')}: nbgrader cell that is neither an answer nor an autograded test "
                            f"(the book has no manually graded or task cells): {m}")
        if c.cell_type != "code":
            problems.append(f"{gid}: graded cells are code cells")
        if gid and c.get("id") != gid:
            problems.append(f"{gid}: the cell id must equal the grade_id (it is {c.get('id')!r})")
    return problems


def lint_pairing(nb, path) -> list[str]:
    ids = [c.get("id") for c in nb.cells]
    problems = []
    for i, ans, _, test in task_cells(nb):
        task = nbg(ans)["grade_id"].removesuffix("-answer")
        if test is None:
            problems.append(f"{task}: the cell after the answer cell must be its test cell")
        elif nbg(test).get("grade_id") != f"{task}-check":
            problems.append(f"{task}: the test cell after it is {nbg(test).get('grade_id')!r}, not {task}-check")
        if task not in ids[:i] or nb.cells[ids.index(task)].cell_type != "markdown":
            problems.append(f"{task}: a markdown cell with id {task!r} (the task text) must come before the answer")
    tests = [c for c in nb.cells if nbg(c).get("grade") and not nbg(c).get("solution")]
    paired = {nbg(t).get("grade_id") for _, _, _, t in task_cells(nb) if t is not None}
    for t in tests:
        if nbg(t).get("grade_id") not in paired:
            problems.append(f"{nbg(t).get('grade_id')}: a test cell without an answer cell just before it")
    return problems


def lint_answers(nb, path) -> list[str]:
    """The student book's answer cell: template lines (``name = ...  # text``) and comments, nothing else."""
    problems = []
    for _, ans, _, _ in task_cells(nb):
        gid = nbg(ans)["grade_id"]
        if "SOLUTION" in ans.source:
            problems.append(f"{gid}: solution markers in the student book — run "
                            "`aerophoto-course strip-solutions notebooks/`; the reference lives in aerophoto.tasks")
        names = template_names(ans.source)
        if not names:
            problems.append(f"{gid}: no template line `name = ...`")
        stray = [ln for ln in ans.source.splitlines()
                 if ln.strip() and not ln.strip().startswith("#") and not TEMPLATE.match(ln.strip())]
        if stray:
            problems.append(f"{gid}: only template lines and comments in an answer cell (no solution code): {stray}")
    return problems


def _check_task_call(code: str):
    """The one ``checks.check_task(...)`` call of a check cell: (task id, positional names, {kw: value name}) or None."""
    calls = [n for n in ast.walk(ast.parse(code)) if isinstance(n, ast.Call) and isinstance(n.func, ast.Attribute)
             and n.func.attr == "check_task"]
    if len(calls) != 1:
        return None
    call = calls[0]
    tid = call.args[0].value if call.args and isinstance(call.args[0], ast.Constant) else None
    pos = [a.id if isinstance(a, ast.Name) else None for a in call.args[1:]]
    kws = {k.arg: (k.value.id if isinstance(k.value, ast.Name) else None) for k in call.keywords}
    return tid, pos, kws


def lint_tests(nb, path) -> list[str]:
    """A check cell is ``from aerophoto import checks`` and one ``checks.check_task("task-NN-k", v, name=name, …)``."""
    from aerophoto import tasks

    problems = []
    for _, ans, _, test in task_cells(nb):
        if test is None:
            continue
        gid = nbg(test)["grade_id"]
        task = gid.removesuffix("-check")
        try:
            tree = ast.parse(test.source)
        except SyntaxError as exc:
            problems.append(f"{gid}: not valid Python ({exc.msg})")
            continue
        if "HIDDEN TESTS" in test.source:
            problems.append(f"{gid}: hidden tests live in aerophoto.tasks (Task.hidden), run by the instructor's "
                            "grader — not in the notebook")
        if not re.search(r"from aerophoto import checks", test.source):
            problems.append(f"{gid}: import the checks in the cell: `from aerophoto import checks`")
        call = _check_task_call(test.source)
        if call is None:
            problems.append(f"{gid}: the cell must call checks.check_task(\"{task}\", v, name=name, ...) exactly once")
            continue
        tid, pos, kws = call
        if tid != task:
            problems.append(f"{gid}: check_task names {tid!r}; this cell checks {task!r}")
        if pos != ["v"]:
            problems.append(f"{gid}: check_task's second argument is the student's variant v")
        names = template_names(ans.source)
        if set(kws) != set(names) or any(kws[k] != k for k in kws):
            problems.append(f"{gid}: pass every answer as itself, name=name: {names} (got {kws})")
        try:
            spec = list(tasks.get(task).names)
        except ValueError as exc:
            problems.append(f"{gid}: {exc}")
        else:
            if names != spec:
                problems.append(f"{gid}: the answer cell's template names {names} differ from the task's "
                                f"answers {spec} (aerophoto.tasks)")
        if len(tree.body) != 2 or not isinstance(tree.body[-1], ast.Expr):
            problems.append(f"{gid}: the check cell is the import and the check_task call, nothing else")
        if displays_a_value(test.source):
            problems.append(f"{gid}: the cell ends with an expression whose value is displayed (nbgrader reads "
                            "it as partial credit)")
    return problems


def lint_registry(nb, path) -> list[str]:
    """Every task of the chapter's module in aerophoto.tasks has its cells in the notebook, and no other."""
    from aerophoto import tasks

    nn = number(path)
    in_nb = [nbg(a)["grade_id"].removesuffix("-answer") for _, a, _, _ in task_cells(nb)]
    if nn not in tasks.CHAPTER_MODULES:
        return [f"graded cells {in_nb} but no module aerophoto.tasks for chapter {nn}"] if in_nb else []
    registered = [t.id for t in tasks.chapter_tasks(nn)]
    return [] if in_nb == registered else [f"the notebook's tasks {in_nb} differ from aerophoto.tasks: {registered}"]


def lint_markers(nb, path) -> list[str]:
    problems = []
    for c in nb.cells:
        m = nbg(c)
        text = c.source
        if ("BEGIN SOLUTION" in text or "END SOLUTION" in text) and not m.get("solution"):
            problems.append(f"{c.get('id')}: the text 'BEGIN/END SOLUTION' outside an answer cell breaks nbgrader")
        if "HIDDEN TESTS" in text and not (m.get("grade") and not m.get("solution")):
            problems.append(f"{c.get('id')}: the text 'HIDDEN TESTS' outside a test cell breaks nbgrader")
    return problems


def lint_downstream(nb, path) -> list[str]:
    """In the student version a task's variables are `...` until answered: later cells must not use them."""
    problems = []
    for i, ans, _, _ in task_cells(nb):
        names = set(template_names(ans.source))
        redefined: set[str] = set()
        for c in nb.cells[i + 1:]:
            if c.cell_type != "code" or nbg(c):
                continue
            try:
                used = loaded_names(c.source) & (names - redefined)
                redefined |= assigned_names(c.source)
            except SyntaxError:
                continue
            if used:
                problems.append(f"cell {c.get('id')} uses {sorted(used)} from {nbg(ans)['grade_id']}")
    return problems


def lint_release(nb, path) -> list[str]:
    """The generated nbgrader source makes nbgrader's student version: template lines kept, no reference."""
    try:
        source = source_version(nb)
        teacher_version(nb)
        release = student_version(source)  # nbgrader's own preprocessors; they raise on broken markers
    except Exception as exc:
        return [f"the nbgrader source or its student version cannot be made: {type(exc).__name__}: {exc}"]
    if [c.get("id") for c in release.cells] != [c.get("id") for c in nb.cells]:
        return ["the student version lost or reordered cells"]
    by_id = {c.get("id"): c for c in release.cells}
    src_by_id = {c.get("id"): c for c in source.cells}
    problems = []
    for _, ans, _, test in task_cells(nb):
        r_ans, s_ans = by_id[ans.get("id")], src_by_id[ans.get("id")]
        parts = split_answer(s_ans.source)
        if parts is None or not set(template_names(ans.source)) <= assigned_names("\n".join(parts[1])):
            problems.append(f"{ans.get('id')}: the generated source has no reference solution setting every answer")
        if "SOLUTION" in r_ans.source or "_ref" in r_ans.source:
            problems.append(f"{ans.get('id')}: the reference solution leaked into the student version")
        if template_names(ans.source) != template_names(r_ans.source):
            problems.append(f"{ans.get('id')}: the template lines must survive into the student version")
        if test is not None and by_id[test.get("id")].source != test.source:
            problems.append(f"{test.get('id')}: the student version changed the check cell")
    return problems


# every rule on every notebook

RULES = {
    "answer-or-test-cells-with-the-book-metadata": lint_metadata,
    "answer-cell-followed-by-its-test-cell-with-task-text": lint_pairing,
    "answer-cells-hold-template-lines-only": lint_answers,
    "tests-call-check-task-of-the-registered-task": lint_tests,
    "tasks-match-the-registry": lint_registry,
    "markers-only-in-their-cells": lint_markers,
    "later-cells-independent-of-the-answers": lint_downstream,
    "generated-source-and-student-version": lint_release,
}


@pytest.mark.parametrize("rule", RULES)
@pytest.mark.parametrize("path", NOTEBOOKS, ids=IDS)
def test_notebook_follows_the_grading_rule(path, rule):
    problems = RULES[rule](read(path), path)
    assert not problems, f"{path.name} breaks {rule}: " + "; ".join(problems)


# the rules themselves: each catches the mistake it is for


def _broken(mutate):
    from aerophoto import nbtools

    path = next(p for p in NOTEBOOKS if p.stem == "00_start_here")
    nb = read(path)
    mutate(nb, nbtools)
    return nb, path


def _set(nb, nbtools, cell_id, fn):
    _, c = nbtools.find_cell(nb, cell_id)
    fn(c)


@pytest.mark.parametrize("lint, mutate, expect", [
    (lint_metadata, lambda nb, t: _set(nb, t, "task-00-1-check", lambda c: c.metadata.nbgrader.update(points=0)),
     "positive number of points"),
    (lint_metadata, lambda nb, t: _set(nb, t, "task-00-1-answer",
                                       lambda c: c.metadata.nbgrader.update(grade_id="task-01-1-answer")),
     "grade_id is task-00-k-answer"),
    (lint_metadata, lambda nb, t: _set(nb, t, "task-00-1-check", lambda c: c.metadata.nbgrader.update(locked=False)),
     "test-cell metadata"),
    (lint_pairing, lambda nb, t: t.insert_after(nb, "task-00-1-answer", t.md("hint", id="hint")),
     "must be its test cell"),
    (lint_pairing, lambda nb, t: nb.cells.pop(t.find_cell(nb, "task-00-1")[0]), "the task text"),
    (lint_answers, lambda nb, t: _set(nb, t, "task-00-1-answer", lambda c: setattr(
        c, "source", c.source + "\n### BEGIN SOLUTION\nH_m = v.f_mm / 1000 * v.m\n### END SOLUTION")),
     "solution markers in the student book"),
    (lint_answers, lambda nb, t: _set(nb, t, "task-00-1-answer",
                                      lambda c: setattr(c, "source", "import math\n" + c.source)),
     "only template lines and comments"),
    (lint_answers, lambda nb, t: _set(nb, t, "task-00-1-answer", lambda c: setattr(c, "source", "# nothing")),
     "no template line"),
    (lint_tests, lambda nb, t: _set(nb, t, "task-00-1-answer",
                                    lambda c: setattr(c, "source", c.source.replace("oc_mm = ...", "oc = ..."))),
     "differ from the task's answers"),
    (lint_tests, lambda nb, t: _set(nb, t, "task-00-1-check", lambda c: setattr(
        c, "source", c.source + "\n### BEGIN HIDDEN TESTS\nchecks.check_value('x', 1, 1)\n### END HIDDEN TESTS")),
     "hidden tests live in aerophoto.tasks"),
    (lint_tests, lambda nb, t: _set(nb, t, "task-00-1-check", lambda c: setattr(
        c, "source", c.source + "\n1 + 1")), "ends with an expression whose value is displayed"),
    (lint_tests, lambda nb, t: _set(nb, t, "task-00-1-check", lambda c: setattr(
        c, "source", c.source.replace("oc_mm=oc_mm", "oc_mm=0"))), "pass every answer as itself"),
    (lint_tests, lambda nb, t: _set(nb, t, "task-00-1-check", lambda c: setattr(
        c, "source", c.source.replace('"task-00-1"', '"task-00-2"'))), "check_task names 'task-00-2'"),
    (lint_registry, lambda nb, t: _set(nb, t, "task-00-1-answer", lambda c: c.metadata.nbgrader.update(
        grade_id="task-00-9-answer")), "differ from aerophoto.tasks"),
    (lint_markers, lambda nb, t: _set(nb, t, "summary", lambda c: setattr(c, "source", "see ### BEGIN SOLUTION")),
     "outside an answer cell"),
    (lint_downstream, lambda nb, t: t.insert_after(nb, "task-00-1-check", t.code("print(2 * H_m)", id="later")),
     "cell later uses ['H_m']"),
    (lint_release, lambda nb, t: _set(nb, t, "task-00-1-answer", lambda c: c.metadata.nbgrader.update(
        grade_id="task-00-9-answer")), "cannot be made"),
    (lint_setup, lambda nb, t: _set(nb, t, "setup", lambda c: setattr(
        c, "source", c.source.replace("RECORD_BOOK = None", 'RECORD_BOOK = "19-0457"'))), "ships with RECORD_BOOK = None"),
    (lint_setup, lambda nb, t: _set(nb, t, "setup", lambda c: c.metadata.update(nbgrader={"grade": False})),
     "must not be an nbgrader cell"),
])
def test_each_rule_catches_its_mistake(lint, mutate, expect):
    nb, path = _broken(mutate)
    problems = lint(nb, path)
    assert any(expect in p for p in problems), problems


def test_the_rules_pass_the_reference_chapter_and_catch_duplicates():
    path = next(p for p in NOTEBOOKS if p.stem == "00_start_here")
    nb = read(path)
    for lint in (lint_setup, lint_metadata, lint_pairing, lint_answers, lint_tests, lint_registry, lint_markers,
                 lint_downstream, lint_release):
        assert lint(nb, path) == [], lint.__name__
    assert lint_unique([("a", nb), ("b", read(path))]) == [
        "task-00-1-answer in a and b", "task-00-1-check in a and b"]


# --------------------------------------------------------------------------------------------------

GRADED = [p for p in NOTEBOOKS if graded_tasks(read(p))]
#: chapters whose student book runs in the sandbox in the README's test command; the others are ``exhaustive``
#: (their own step of .ci/run). Every chapter's unanswered run is also checked for clean failures, outside the
#: sandbox, by tests/notebooks/test_no_answers_on_screen.py.
SANDBOXED_CORE = ("00_", "05_")


@pytest.mark.slow
@pytest.mark.parametrize("path", [pytest.param(p, id=p.stem, marks=() if p.name.startswith(SANDBOXED_CORE)
                                               else pytest.mark.exhaustive) for p in GRADED])
def test_student_book_runs_and_every_unanswered_check_fails_cleanly(path, tmp_path):
    """A student who has not answered sees one red ✗ line per task (e.g. "no answer yet"), no other error.

    Run as the grader runs it: in the sandbox, each task judged by the trusted check."""
    from aerophoto.course import check_notebook

    release = read(path)
    target = tmp_path / path.name
    nbformat.write(release, str(target))
    for extra in path.parent.iterdir():  # pictures or data the chapter reads beside it
        if extra.is_file() and extra.suffix != ".ipynb":
            (tmp_path / extra.name).write_bytes(extra.read_bytes())
    result = check_notebook(target, record_book="19-0457", timeout=300)
    assert not result.errors, f"{path.name}: errors outside the check cells: {result.errors}"
    assert [t.task for t in result.tasks] == [t.task for t in graded_tasks(release)]
    wrong = [(t.task, t.message) for t in result.tasks if t.passed or t.ename != "WrongAnswer"]
    assert not wrong, f"{path.name}: an unanswered task must fail with a check's message, not an error: {wrong}"
