"""Flags: what a submission's cells did, read in the instructor's process (never by running them).

Two kinds, both reported in the gradebook's ``flags`` column:

* **structure** (:func:`inspect_submission`): a test or answer cell deleted, stripped of its nbgrader
  metadata or edited; the record-book number in the setup cell; errors while grading;
* **behaviour** (:func:`code_flags`, an AST walk over every cell the student wrote or changed):
  ``exception_hooks`` (``set_custom_exc``, IPython event hooks, ``sys.excepthook``, shell methods),
  ``patched_checks`` (``importlib``, ``sys.modules``, ``reload``, attributes of aerophoto's modules set or
  deleted), ``variant_changed`` (``v`` or ``RECORD_BOOK`` re-assigned, ``globals()``/``vars()``, ``os.environ``
  written, ``setup`` or ``variant_for_index`` called again), ``uses_package_answers`` (an answer cell
  calls a function the graded tasks compute their answers with — the list is read from
  :mod:`aerophoto.tasks`' own code, :func:`package_answer_functions`), ``dynamic_code`` (``exec``, ``eval``,
  ``compile``, ``__import__``, ``getattr``/``setattr`` with a computed name: what obfuscation needs),
  ``system_access`` (processes, sockets, databases, files outside the working folder).

Obfuscated code that hides a name from the AST still has to *do* something: the check cell's record
reports hooks and replaced functions seen in the kernel (:mod:`aerophoto.course.trusted`), and the score
comes from the trusted check in any case, so hiding buys nothing.
"""

from __future__ import annotations

import ast
import functools
import re
from pathlib import Path

from .common import (Flag, cells_by_grade_id, digits, is_answer, is_test, nbg, norm_src, notebook_problem,
                     read_nb, source)

# ----------------------------------------------------------------------------------------------- the record book


def parse_record_book(nb) -> tuple[str, object]:
    """What the setup cell declares: ``("value", "19-0457")``, ``("none", None)``, ``("missing", None)``
    (no setup cell or no ``RECORD_BOOK = ...`` line), or ``("unreadable", reason)``."""
    cells = [c for c in nb["cells"] if c.get("cell_type") == "code"]
    setup = next((c for c in cells if c.get("id") == "setup"), cells[0] if cells else None)
    if setup is None:
        return "missing", None
    try:
        tree = ast.parse(source(setup))
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


# ----------------------------------------------------------------------------------------------- behaviour

_HOOK_NAMES = {"set_custom_exc", "custom_exceptions", "excepthook", "showtraceback", "_showtraceback",
               "showsyntaxerror", "InteractiveShell", "run_cell", "run_cell_async", "run_code", "run_ast_nodes",
               "InteractiveTB", "SyntaxTB", "ast_transformers", "input_transformers_post",
               "input_transformers_cleanup", "post_run_cell", "pre_run_cell", "post_execute", "pre_execute",
               "register_post_execute"}
_DYNAMIC_CALLS = {"exec", "eval", "compile", "__import__", "execfile", "runpy.run_path", "runpy.run_module",
                  "marshal.loads", "pickle.loads", "types.FunctionType", "types.CodeType"}
_SYSTEM_MODULES = {"subprocess", "multiprocessing", "socket", "sqlite3", "ctypes", "signal", "resource", "pty",
                   "threading", "_thread", "http", "urllib", "requests", "asyncio.subprocess", "shutil", "glob"}
_SYSTEM_CALLS = {"os.system", "os.popen", "os.fork", "os.forkpty", "os.kill", "os.killpg", "os.setsid",
                 "os.chdir", "os.remove", "os.unlink", "os.rmdir", "os.rename", "os.replace", "os.listdir",
                 "os.scandir", "os.walk", "os.chmod", "os.symlink", "os.link", "os.makedirs", "os.mkdir",
                 "os.posix_spawn", "os.posix_spawnp", "os.nice", "os.setpgrp", "os.daemon", "os._exit", "os.abort"}
_ENV_WRITERS = {"update", "pop", "popitem", "setdefault", "clear", "__setitem__", "__delitem__"}
_VARIANT_CALLS = {"aerophoto.setup", "aerophoto.book.setup", "aerophoto.variants.variant",
                  "aerophoto.variants.variant_for_index", "aerophoto.book.remember_record_book"}


@functools.lru_cache(maxsize=None)
def package_answer_functions() -> frozenset:
    """The package's functions the graded tasks compute their answers with (from :mod:`aerophoto.tasks`' code).

    Every call in a ``tasks/chNN.py`` or ``labs/chNN.py`` module of a function of another aerophoto module
    (``flight.plan``, ``geometry.flying_height_m``, ``quality.variant_task_answers``, ...), plus ``aerophoto.tasks``
    and ``aerophoto.labs`` themselves, less the instruments a task's text tells the student to work with
    (``Task.tools``).
    """
    from .. import labs, tasks

    # the rubrics (tasks/chNN.py) and the chapters' lab worlds they build on (labs/chNN.py)
    sources = [(Path(tasks.__file__).parent / f"{mod}.py", "aerophoto.tasks") for mod in tasks.CHAPTER_MODULES.values()]
    sources += [(Path(labs.__file__).parent / f"{mod}.py", "aerophoto.labs") for mod in labs.MODULES
                if mod.startswith("ch")]
    found = {"aerophoto.tasks", "aerophoto.labs"}
    for path, package in sources:
        if not path.is_file():
            continue
        tree = ast.parse(path.read_text(encoding="utf-8"))
        aliases = _aliases(tree, package=package)
        for node in ast.walk(tree):
            if isinstance(node, ast.Call):
                name = _resolve(node.func, aliases)
                if (name and name.startswith("aerophoto.") and not name.startswith(("aerophoto.tasks",
                                                                                     "aerophoto.labs",
                                                                                     "aerophoto._validate",
                                                                                     "aerophoto.variants"))
                        and name.count(".") >= 2):
                    found.add(name)
    taught = {tool for t in tasks.all_tasks() for tool in t.tools}  # the instruments a task tells students to use
    return frozenset(found - taught)


def _aliases(tree, package: str = "") -> dict:
    """name → dotted origin for every import in ``tree`` (relative imports resolved against ``package``)."""
    out = {}
    for node in ast.walk(tree):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.asname:
                    out[a.asname] = a.name
                else:
                    out[a.name.split(".")[0]] = a.name.split(".")[0]
        elif isinstance(node, ast.ImportFrom):
            base = node.module or ""
            if node.level:
                parts = package.split(".")
                parts = parts[: len(parts) - (node.level - 1)] if node.level > 1 else parts
                base = ".".join(parts + ([node.module] if node.module else []))
            for a in node.names:
                out[a.asname or a.name] = f"{base}.{a.name}" if base else a.name
    return out


def _resolve(node, aliases: dict) -> str | None:
    """The dotted name a Name/Attribute chain stands for (``g.flying_height_m`` → ``aerophoto.geometry.…``)."""
    parts = []
    while isinstance(node, ast.Attribute):
        parts.append(node.attr)
        node = node.value
    if isinstance(node, ast.Call):  # get_ipython().set_custom_exc → "get_ipython().set_custom_exc"
        inner = _resolve(node.func, aliases)
        head = f"{inner}()" if inner else "()"
    elif isinstance(node, ast.Name):
        head = aliases.get(node.id, node.id)
    else:
        return None
    return ".".join([head, *reversed(parts)])


def _const_str(node) -> str | None:
    return node.value if isinstance(node, ast.Constant) and isinstance(node.value, str) else None


def code_flags(src: str, *, where: str, answer_cell: bool, aliases: dict, known: set,
               setup_cell: bool = False) -> list[Flag]:
    """Behaviour flags of one cell's code (statements in ``known``, the release's own, are skipped)."""
    try:
        tree = ast.parse(src)
    except SyntaxError:
        return []
    aliases = {**aliases, **_aliases(tree)}
    answers = package_answer_functions()
    hits: dict[str, list[str]] = {}

    def hit(code, why, node):
        hits.setdefault(code, [])
        text = f"{why} (line {getattr(node, 'lineno', '?')})"
        if text not in hits[code]:
            hits[code].append(text)

    for stmt in tree.body:
        if ast.dump(stmt) in known:
            continue
        if setup_cell and isinstance(stmt, ast.Assign) and isinstance(stmt.value, ast.Constant) and \
                [getattr(t, "id", None) for t in stmt.targets] == ["RECORD_BOOK"]:
            continue  # the one line a student types in the setup cell
        for node in ast.walk(stmt):
            if isinstance(node, (ast.Import, ast.ImportFrom)):
                mods = [a.name for a in node.names] if isinstance(node, ast.Import) else [node.module or ""]
                for m in mods:
                    top = m.split(".")[0]
                    if top in ("importlib", "imp"):
                        hit("patched_checks", f"imports {m}", node)
                    if m in _SYSTEM_MODULES or top in _SYSTEM_MODULES:
                        hit("system_access", f"imports {m}", node)
                    if top == "builtins":
                        hit("patched_checks", "imports builtins", node)
                if isinstance(node, ast.ImportFrom) and (node.module or "") == "os":
                    for a in node.names:
                        if f"os.{a.name}" in _SYSTEM_CALLS or a.name in ("environ", "putenv", "unsetenv"):
                            hit("system_access" if f"os.{a.name}" in _SYSTEM_CALLS else "variant_changed",
                                f"imports os.{a.name}", node)
            name = _resolve(node, aliases) if isinstance(node, (ast.Name, ast.Attribute)) else None
            if isinstance(node, ast.Attribute) and node.attr in _HOOK_NAMES:
                hit("exception_hooks", f"uses .{node.attr}", node)
            if isinstance(node, ast.Attribute) and node.attr == "register" and "events" in (name or ""):
                hit("exception_hooks", "registers an IPython event hook", node)
            if isinstance(node, ast.Name) and node.id in _HOOK_NAMES:
                hit("exception_hooks", f"uses {node.id}", node)
            if isinstance(node, ast.Constant) and isinstance(node.value, str) and node.value in _HOOK_NAMES:
                hit("exception_hooks", f"names {node.value!r}", node)
            if name:
                if name.startswith("sys.modules") or name in ("reload", "importlib.reload") or name.startswith(
                        ("importlib.", "builtins.", "__builtins__")):
                    hit("patched_checks", f"uses {name}", node)
                if name == "sys.excepthook":
                    hit("exception_hooks", "uses sys.excepthook", node)
                if answer_cell and any(name == a or name.startswith(a + ".") for a in answers):
                    hit("uses_package_answers", f"uses {name}", node)
            if isinstance(node, ast.Call):
                fn = _resolve(node.func, aliases) or ""
                if fn in _DYNAMIC_CALLS or fn.split(".")[-1] in ("exec", "eval", "compile", "__import__"):
                    hit("dynamic_code", f"calls {fn}()", node)
                if fn in ("getattr", "setattr", "delattr", "hasattr") and len(node.args) >= 2 and \
                        _const_str(node.args[1]) is None:
                    hit("dynamic_code", f"{fn}() with a computed name", node)
                if fn in ("setattr", "delattr") and node.args:
                    target = _resolve(node.args[0], aliases) or ""
                    if target.startswith(("aerophoto", "checks", "tasks")) or target.split(".")[0] in (
                            "checks", "tasks", "aerophoto", "sys", "builtins", "IPython"):
                        hit("patched_checks", f"{fn}() on {target}", node)
                if fn in ("globals", "vars", "locals"):
                    hit("variant_changed", f"calls {fn}()", node)
                leaf_fn = fn.split(".")[-1]
                if fn.split(".")[0] in ("aerophoto", "checks") and "checks" in fn.split(".")[:2] and (
                        leaf_fn in ("task_passed", "grade_task", "check_task") or leaf_fn.startswith("check_")):
                    # the check cells are the release's own (skipped above): a student's own call of a check
                    # can only serve to probe or fake a pass
                    hit("patched_checks", f"calls {fn}() in their own code", node)
                if fn in _SYSTEM_CALLS or fn.startswith(("os.exec", "os.spawn", "subprocess.", "socket.",
                                                         "sqlite3.", "multiprocessing.", "ctypes.", "shutil.")):
                    hit("system_access", f"calls {fn}()", node)
                if fn in ("os.putenv", "os.unsetenv") or (fn.startswith("os.environ.") and
                                                          fn.split(".")[-1] in _ENV_WRITERS):
                    hit("variant_changed", f"calls {fn}()", node)
                if fn in _VARIANT_CALLS or fn.endswith((".variant_for_index", ".remember_record_book")) or \
                        fn == "variant_for_index":
                    hit("variant_changed", f"calls {fn}()", node)
                if fn in ("open", "io.open", "pathlib.Path", "Path", "os.open") and node.args:
                    p = _const_str(node.args[0]) or ""
                    if p.startswith(("/", "~")) or ".." in p:
                        hit("system_access", f"opens {p!r}", node)
            if isinstance(node, (ast.Assign, ast.AugAssign, ast.AnnAssign, ast.Delete)):
                targets = node.targets if isinstance(node, (ast.Assign, ast.Delete)) else [node.target]
                for t in targets:
                    for leaf in ast.walk(t):
                        if isinstance(leaf, ast.Name) and leaf.id in ("v", "RECORD_BOOK") and \
                                isinstance(leaf.ctx, (ast.Store, ast.Del)):
                            hit("variant_changed", f"assigns {leaf.id}", node)
                        if isinstance(leaf, ast.Attribute) and isinstance(leaf.ctx, (ast.Store, ast.Del)):
                            base = _resolve(leaf.value, aliases) or ""
                            if base.split(".")[0] in ("aerophoto", "checks", "tasks", "builtins", "__builtins__",
                                                      "sys") or base.startswith("get_ipython()"):
                                hit("patched_checks", f"sets {base}.{leaf.attr}", node)
                            if base == "v" or base.startswith("v."):
                                hit("variant_changed", f"sets v.{leaf.attr}", node)
                        if isinstance(leaf, ast.Subscript) and isinstance(leaf.ctx, (ast.Store, ast.Del)):
                            base = _resolve(leaf.value, aliases) or ""
                            if base in ("os.environ", "environ"):
                                hit("variant_changed", "writes os.environ", node)
                            if base.startswith("sys.modules"):
                                hit("patched_checks", "writes sys.modules", node)
            if isinstance(node, ast.Global) and "v" in node.names:
                hit("variant_changed", "declares global v", node)
    return [Flag(code, f"{where}: " + "; ".join(whys[:4]) + (" …" if len(whys) > 4 else ""))
            for code, whys in hits.items()]


def behaviour_flags(release_nb, sub) -> list[Flag]:
    """:func:`code_flags` for every code cell of a submission that is not a locked test cell."""
    release_code = [source(c) for c in release_nb["cells"] if c.get("cell_type") == "code"]
    known = set()
    for src in release_code:
        try:
            known |= {ast.dump(s) for s in ast.parse(src).body}
        except SyntaxError:
            pass
    aliases: dict = {}
    for c in list(release_nb["cells"]) + list(sub["cells"]):
        if c.get("cell_type") == "code":
            try:
                aliases.update(_aliases(ast.parse(source(c))))
            except SyntaxError:
                pass
    code_cells = [c for c in sub["cells"] if c.get("cell_type") == "code"]
    setup = next((c for c in code_cells if c.get("id") == "setup"), code_cells[0] if code_cells else None)
    flags = []
    for cell in sub["cells"]:
        if cell.get("cell_type") != "code" or is_test(cell):
            continue
        where = f"cell {cell.get('id', '?')}"
        flags += code_flags(source(cell), where=where, answer_cell=is_answer(cell), aliases=aliases, known=known,
                            setup_cell=cell is setup)
    return flags


# ----------------------------------------------------------------------------------------------- same code


def answer_code(nb) -> str:
    """The code of a notebook's answer cells, normalised (comments, layout and template lines dropped)."""
    parts = []
    for cell in nb["cells"]:
        if not is_answer(cell):
            continue
        src = source(cell)
        try:
            body = [s for s in ast.parse(src).body
                    if not (isinstance(s, ast.Assign) and isinstance(s.value, ast.Constant) and s.value.value is ...)]
            parts.append("\n".join(ast.unparse(s) for s in body))
        except SyntaxError:
            parts.append(" ".join(src.split()))
    return "\n#--\n".join(parts)


def same_code_groups(named: dict, min_chars: int = 40) -> dict:
    """{id: [other ids with identical normalised answer code]} for submissions with a non-trivial answer."""
    by_code: dict = {}
    for sid, code in named.items():
        if len(re.sub(r"\s|#--", "", code)) >= min_chars:
            by_code.setdefault(code, []).append(sid)
    out = {}
    for ids in by_code.values():
        if len(ids) > 1:
            for sid in ids:
                out[sid] = sorted(i for i in ids if i != sid)
    return out


# ----------------------------------------------------------------------------------------------- structure


def inspect_submission(release_nb, submitted_path: Path, autograded_path: Path | None,
                       expected_record_book: str | None) -> list[Flag]:
    """The structural and behaviour flags of one submitted notebook; empty when all is well.

    ``release_nb`` is the student version the class received; ``autograded_path`` is nbgrader's executed
    copy (None or absent if not graded).  The trusted check's flags come from :mod:`.trusted`.
    """
    flags: list[Flag] = []
    if not submitted_path.exists():
        return [Flag("missing", "no notebook submitted")]
    problem = notebook_problem(submitted_path)
    if problem:
        return [Flag("corrupt", f"{submitted_path.name} is {problem}; scored 0")]
    sub = read_nb(submitted_path)

    sub_by_gid = cells_by_grade_id(sub)
    sub_ids = {c.get("id") for c in sub.cells}
    for cell in release_nb["cells"]:
        gid = nbg(cell).get("grade_id")
        if not gid or not (is_test(cell) or is_answer(cell)):
            continue
        kind = "test" if is_test(cell) else "answer"
        if gid not in sub_by_gid:
            if cell.get("id") in sub_ids:
                flags.append(Flag(f"{kind}_cell_stripped",
                                  f"{gid}: the cell is there but its nbgrader metadata was removed"
                                  + ("; it scores 0" if kind == "test" else "")))
            else:
                flags.append(Flag(f"{kind}_cell_deleted",
                                  f"{gid}: the cell was deleted" + ("; it scores 0" if kind == "test" else "")))
        elif kind == "test" and norm_src(source(sub_by_gid[gid])) != norm_src(source(cell)):
            flags.append(Flag("test_cell_edited", f"{gid}: the locked test cell was edited "
                                                  "(nbgrader restored the original before grading)"))

    flags += behaviour_flags(release_nb, sub)

    expected_digits = digits(expected_record_book)
    kind, value = parse_record_book(sub)
    if kind == "value" and expected_digits and digits(value) != expected_digits:
        flags.append(Flag("record_book_mismatch",
                          f"RECORD_BOOK = {value!r} in the setup cell, but the student's record book is "
                          f"{expected_record_book!r} (graded for the student's)"))
    elif kind == "unreadable":
        flags.append(Flag("record_book_unreadable", str(value)))
    elif kind == "missing":
        flags.append(Flag("record_book_unreadable", "the setup cell has no RECORD_BOOK = ... line"))
    if len(expected_digits) < 2:
        flags.append(Flag("record_book_unknown", "no record-book number for this student id (add it to the "
                                                 "roster): the variant is unknown, nothing is graded"))

    if autograded_path is None or not autograded_path.exists():
        flags.append(Flag("not_graded", "no autograded notebook (autograde failed or has not run)"))
        return flags
    from .outcomes import error_outputs, test_outcome
    from .common import graded_tasks

    graded = read_nb(autograded_path)
    test_ok = {nbg(c).get("grade_id"): test_outcome(c)[0] for c in graded.cells if is_test(c)}
    answer_to_test = {t.answer_id: t.check_id for t in graded_tasks(graded) if t.answer_id}
    for cell in graded.cells:
        if cell.get("cell_type") != "code" or is_test(cell):
            continue
        errs = [e for e in error_outputs(cell) if e.get("ename") not in ("KernelDied", "NotRun")]
        if not errs:
            continue
        names = ", ".join(dict.fromkeys(str(e.get("ename")) for e in errs))
        if is_answer(cell):
            gid = nbg(cell).get("grade_id")
            what = "timed out (cut by the per-cell limit)" if "CellTimeoutError" in names else f"raised {names}"
            passed = test_ok.get(answer_to_test.get(gid))
            tail = "; its check still passed" if passed else ""
            flags.append(Flag("answer_error", f"{gid}: the answer cell {what}{tail}"))
        else:
            flags.append(Flag("cell_error", f"cell {cell.get('id', '?')} raised {names}"))
    return flags
