"""Flags: what a submission's cells did, read in the instructor's process (never by running them).

Two kinds, both reported in the gradebook's ``flags`` column:

* **structure** (:func:`inspect_submission`): a test or answer cell deleted, stripped of its nbgrader
  metadata or edited; the record-book number in the setup cell; errors while grading;
* **behaviour** (:func:`code_flags`, an AST walk over every cell the student wrote or changed):
  ``exception_hooks`` (``set_custom_exc``, IPython event hooks, ``sys.excepthook``, shell methods),
  ``patched_checks`` (``importlib``, ``sys.modules``, ``reload``, attributes of aerophoto's modules set or
  deleted), ``variant_changed`` (``RECORD_BOOK`` re-assigned, ``v`` deleted or its attributes set,
  ``globals()``/``vars()``, ``os.environ`` written, ``setup`` or ``variant_for_index`` called again),
  ``variant_shadowed`` (the name ``v`` reused — harmless: the checks keep the setup cell's variant), ``uses_package_answers`` (an answer cell
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

# ----------------------------------------------------------------------------------------------- what they mean
FLAG_MEANINGS = {
    "uses_package_answers": "an answer was computed with a package function that computes the task's answer "
                            "(not one of the tools its text names): the teacher sees the work was not done by hand",
    "variant_changed": "the variant was changed (RECORD_BOOK, the environment, setup or variant_for_index again): "
                       "the grader grades the roster's variant and shows this",
    "variant_shadowed": "a cell reused the name v, the setup cell's variant (e.g. u, v = …): nothing graded changes "
                        "— the checks keep the setup cell's variant — but rename the variable",
    "variant_mismatch": "a check ran for another variant than the student's: graded for the student's own",
    "patched_checks": "the checks or their modules were replaced or imported by hand: the grader ignores the "
                      "kernel's verdict and shows this",
    "exception_hooks": "exception or event hooks were installed: they could hide a failed check",
    "dynamic_code": "code was run from text (exec, eval, a computed attribute name, a magic)",
    "system_access": "files outside the working folder, processes or the network were used",
    "code_unreadable": "a cell could not be analysed (too long or nested too deep)",
    "tampered": "what the check cell saw and what the grader computed disagree: the kernel's word is not taken",
    "no_answer_record": "a check cell left no record of its answers (it did not run, or was stopped): scored 0",
    "unreadable_record": "a check cell's record of the answers could not be read: scored 0",
    "not_graded": "the notebook (or a task) could not be graded",
    "answer_error": "an answer cell raised an error",
    "cell_error": "a cell raised an error",
    "record_book_mismatch": "the setup cell's RECORD_BOOK is not the student's own: graded for the student's",
    "record_book_unreadable": "the setup cell's RECORD_BOOK line is missing or not a plain number",
    "record_book_unknown": "the roster has no record-book number for this student: nothing is graded",
    "test_cell_edited": "a locked check cell was edited or copied: restored from the release before grading",
    "test_cell_stripped": "a check cell lost its grading metadata: restored from the release before grading",
    "test_cell_deleted": "a check cell was deleted: its task scores 0",
    "answer_cell_edited": "an answer cell's grading metadata was changed",
    "answer_cell_stripped": "an answer cell lost its grading metadata",
    "answer_cell_deleted": "an answer cell was deleted",
    "same_code_as": "the answer code is the same as another student's",
    "claimed_twice": "the same record-book number came from two students' folders: neither was imported",
    "missing": "no notebook was handed in",
    "corrupt": "the notebook file cannot be read: scored 0",
    "notebook_time_limit": "the notebook ran longer than its time limit",
}
"""Every flag code, with one line on what it means for the student (``aerophoto-course check`` prints it)."""


def flag_meaning(code: str) -> str:
    """One line on what flag ``code`` means (:data:`FLAG_MEANINGS`); the code itself when unknown."""
    return FLAG_MEANINGS.get(str(code), str(code))


# ----------------------------------------------------------------------------------------------- reading code

MAX_CELL_CHARS = 1_000_000
"""A cell's code longer than this is not analysed (flagged ``code_unreadable``)."""
MAX_NESTING = 200
"""Code whose syntax tree is deeper than this is not analysed (flagged ``code_unreadable``).  Whether Python's own
parser gives up depends on the process's recursion limit, which importing IPython raises (jedi sets 3 000): the
verdict must not depend on what happened to be imported, so the depth is measured, without recursion."""


def _too_deep(tree) -> bool:
    """Whether ``tree`` is nested more than :data:`MAX_NESTING` levels (walked iteratively)."""
    stack = [(tree, 1)]
    while stack:
        node, depth = stack.pop()
        if depth > MAX_NESTING:
            return True
        stack.extend((child, depth + 1) for child in ast.iter_child_nodes(node))
    return False


def parse_code(src: str):
    """``(tree, None)`` for a cell's code, or ``(None, why)``: never raises.

    IPython's own syntax (``!cmd``, ``%magic``, ``%%cell magic``) is first turned into the Python IPython runs
    (``get_ipython().system(...)``), so what it does is seen.  Code nested too deep to parse (RecursionError),
    too long or otherwise unreadable is reported, not raised: one notebook never stops the scan of a class.
    """
    if not isinstance(src, str):
        return None, "the cell's source is not text"
    if len(src) > MAX_CELL_CHARS:
        return None, f"the cell holds {len(src):,} characters (more than {MAX_CELL_CHARS:,} are not analysed)"
    text = src
    try:
        if any(line.lstrip().startswith(("!", "%")) for line in src.splitlines()) or "?" in src:
            from IPython.core.inputtransformer2 import TransformerManager

            text = TransformerManager().transform_cell(src)
    except Exception:  # IPython's transformer failed: parse the text as it is
        text = src
    try:
        tree = ast.parse(text)
        if _too_deep(tree):
            return None, f"the code is nested more than {MAX_NESTING} levels deep"
        return tree, None
    except SyntaxError as exc:
        return None, f"not valid Python ({exc.msg})"
    except (RecursionError, MemoryError) as exc:
        return None, f"the code is nested too deep to read ({type(exc).__name__})"
    except (ValueError, TypeError) as exc:  # NUL bytes and the like
        return None, f"the code cannot be read ({type(exc).__name__})"


def _dump(node) -> str | None:
    """``ast.dump`` of a statement, None when it is nested too deep to dump."""
    try:
        return ast.dump(node)
    except (RecursionError, MemoryError):
        return None


# ----------------------------------------------------------------------------------------------- the record book


def parse_record_book(nb) -> tuple[str, object]:
    """What the setup cell declares: ``("value", "19-0457")``, ``("none", None)``, ``("missing", None)``
    (no setup cell or no ``RECORD_BOOK = ...`` line), or ``("unreadable", reason)``."""
    cells = [c for c in nb["cells"] if c.get("cell_type") == "code"]
    setup = next((c for c in cells if c.get("id") == "setup"), cells[0] if cells else None)
    if setup is None:
        return "missing", None
    tree, why = parse_code(source(setup))
    if tree is None:
        return "unreadable", f"the setup cell: {why}"
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
_GRADER_MODULES = {"json", "math", "cmath", "numbers", "numpy", "IPython", "ipykernel", "traitlets", "zmq",
                   "jupyter_client", "decimal", "fractions", "operator", "functools", "types", "inspect", "os",
                   "contextlib", "dataclasses", "collections", "copy", "re"}
_HARMLESS_MAGICS = {"time", "timeit", "matplotlib", "precision", "who", "whos", "pwd", "pprint", "xmode",
                    "pinfo", "pinfo2", "psearch", "pdoc", "pdef", "psource"}
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
    return frozenset(found - package_tools())


ALWAYS_TOOLS = ("aerophoto.tasks.inputs", "aerophoto.gradebook.task_inputs")
"""What every task's data cell calls: a task's inputs never carry its answers (tests/content/test_task_inputs.py)."""


@functools.lru_cache(maxsize=None)
def package_tools() -> frozenset:
    """The package's names a task's text tells the student to work with (every task's ``Task.tools``, and
    :data:`ALWAYS_TOOLS`): never flagged, nor anything under them (``aerophoto.tasks.inputs`` is a tool though
    ``aerophoto.tasks`` is not)."""
    from .. import tasks

    return frozenset(tool for t in tasks.all_tasks() for tool in t.tools) | frozenset(ALWAYS_TOOLS)


def is_package_answer(name: str) -> bool:
    """Whether the dotted ``name`` is (under) a function the graded tasks compute their answers with and not
    (under) a tool a task's text names (:func:`package_answer_functions`, :func:`package_tools`)."""
    def under(prefixes):
        return any(name == a or name.startswith(a + ".") for a in prefixes)

    return under(package_answer_functions()) and not under(package_tools())


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
    """Behaviour flags of one cell's code (statements in ``known``, the release's own, are skipped).

    ``answer_cell`` is kept for callers; every cell a student wrote is scanned alike.  Code that cannot be
    read (nested too deep, too long) is flagged ``code_unreadable``; plain syntax errors are not (the kernel
    reports them when the cell runs).
    """
    tree, why = parse_code(src)
    if tree is None:
        if why and not why.startswith("not valid Python"):
            return [Flag("code_unreadable", f"{where}: {why}; the cell was not analysed")]
        return []
    try:
        aliases = {**aliases, **_aliases(tree)}
        _assigned_aliases(tree, aliases)
        return _code_flags(tree, where=where, aliases=aliases, known=known, setup_cell=setup_cell)
    except (RecursionError, MemoryError) as exc:
        return [Flag("code_unreadable", f"{where}: the code is nested too deep to analyse ({type(exc).__name__})")]


def _assigned_aliases(tree, aliases: dict) -> dict:
    """Add the names bound to a module, a function or an attribute chain by plain assignment (``_a = aerophoto``,
    ``t = aerophoto.tasks``, ``f = getattr(aerophoto, "tasks")``), in order, to ``aliases`` (changed in place)."""
    for node in ast.walk(tree):
        if isinstance(node, (ast.Assign, ast.AnnAssign, ast.NamedExpr)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            value = node.value
            if value is None:
                continue
            origin = None
            if isinstance(value, (ast.Name, ast.Attribute)):
                origin = _resolve(value, aliases)
            elif isinstance(value, ast.Call) and _resolve(value.func, aliases) == "getattr" and \
                    len(value.args) >= 2 and _const_str(value.args[1]) is not None:
                base = _resolve(value.args[0], aliases)
                origin = f"{base}.{_const_str(value.args[1])}" if base else None
            imported = {str(val).split(".")[0] for val in aliases.values()}
            if not origin or origin.split(".")[0] not in imported:
                continue  # a local value (x = y, h = v.f_mm): not an alias of anything imported
            for t in targets:
                for leaf in ([t] if not isinstance(t, (ast.Tuple, ast.List)) else []):
                    if isinstance(leaf, ast.Name) and leaf.id != origin:
                        aliases[leaf.id] = origin
    return aliases


def _code_flags(tree, *, where: str, aliases: dict, known: set, setup_cell: bool) -> list[Flag]:
    hits: dict[str, list[str]] = {}

    def hit(code, why, node):
        hits.setdefault(code, [])
        text = f"{why} (line {getattr(node, 'lineno', '?')})"
        if text not in hits[code]:
            hits[code].append(text)

    for stmt in tree.body:
        if _dump(stmt) in known:
            continue
        if setup_cell and isinstance(stmt, ast.Assign) and isinstance(stmt.value, ast.Constant) and \
                [getattr(t, "id", None) for t in stmt.targets] == ["RECORD_BOOK"]:
            continue  # the one line a student types in the setup cell
        inner = {id(n.value) for n in ast.walk(stmt) if isinstance(n, ast.Attribute)}  # a.b of a.b.c: not alone
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
                if id(node) not in inner and is_package_answer(name):
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
                if fn in ("get_ipython().system", "get_ipython().getoutput", "get_ipython().system_piped",
                          "get_ipython().system_raw"):
                    hit("system_access", "runs a shell command (!cmd)", node)
                if fn in ("get_ipython().run_line_magic", "get_ipython().run_cell_magic"):
                    magic = _const_str(node.args[0]) if node.args else None
                    if magic not in _HARMLESS_MAGICS:
                        hit("dynamic_code", f"uses the magic %{magic or '?'}", node)
                if fn in ("get_ipython().run_cell", "get_ipython().ex", "get_ipython().ev"):
                    hit("dynamic_code", f"calls {fn}()", node)
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
                        if isinstance(leaf, ast.Name) and leaf.id == "v" and isinstance(leaf.ctx, ast.Store):
                            # the checks use the setup cell's variant whatever v holds (aerophoto.checks): a
                            # reused name changes nothing graded, but the student should rename it
                            hit("variant_shadowed", "assigns v", node)
                        elif isinstance(leaf, ast.Name) and leaf.id in ("v", "RECORD_BOOK") and \
                                isinstance(leaf.ctx, (ast.Store, ast.Del)):
                            hit("variant_changed", f"{'deletes' if isinstance(leaf.ctx, ast.Del) else 'assigns'} "
                                                   f"{leaf.id}", node)
                        if isinstance(leaf, ast.Attribute) and isinstance(leaf.ctx, (ast.Store, ast.Del)):
                            base = _resolve(leaf.value, aliases) or ""
                            if base.split(".")[0] in ("aerophoto", "checks", "tasks", "builtins", "__builtins__",
                                                      "sys") or base.startswith("get_ipython()"):
                                hit("patched_checks", f"sets {base}.{leaf.attr}", node)
                            elif base.split(".")[0] in _GRADER_MODULES:
                                # the modules the check relies on (json writes the answer record, math and
                                # numpy compare the values): replacing their functions forges the record
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
        tree, _ = parse_code(src)
        if tree is not None:
            known |= {d for d in map(_dump, tree.body) if d is not None}
    aliases: dict = {}
    for c in list(release_nb["cells"]) + list(sub["cells"]):
        if c.get("cell_type") == "code":
            tree, _ = parse_code(source(c))
            if tree is not None:
                try:
                    aliases.update(_aliases(tree))
                    _assigned_aliases(tree, aliases)  # a name bound in one cell is used in the next
                except (RecursionError, MemoryError):
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
        tree, _ = parse_code(src)
        try:
            if tree is None:
                raise SyntaxError
            body = [s for s in tree.body
                    if not (isinstance(s, ast.Assign) and isinstance(s.value, ast.Constant) and s.value.value is ...)]
            parts.append("\n".join(ast.unparse(s) for s in body))
        except (SyntaxError, RecursionError, MemoryError, ValueError):
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
    restored = " (restored from the release before grading: graded as the release has it)"
    for cell in release_nb["cells"]:
        gid = nbg(cell).get("grade_id")
        if not gid or not (is_test(cell) or is_answer(cell)):
            continue
        kind = "test" if is_test(cell) else "answer"
        same = [c for c in sub.cells if nbg(c).get("grade_id") == gid or
                (cell.get("id") is not None and c.get("id") == cell.get("id"))]
        if gid not in sub_by_gid:
            if cell.get("id") in sub_ids:
                flags.append(Flag(f"{kind}_cell_stripped",
                                  f"{gid}: the cell is there but its nbgrader metadata was removed{restored}"))
            else:
                flags.append(Flag(f"{kind}_cell_deleted",
                                  f"{gid}: the cell was deleted" + ("; it scores 0" if kind == "test" else "")))
            continue
        if kind == "test" and len(same) > 1:
            flags.append(Flag("test_cell_edited", f"{gid}: the locked test cell is there {len(same)} times (copied); "
                                                  f"the copies were removed{restored}"))
        mine = same[0]
        if kind == "test" and norm_src(source(mine)) != norm_src(source(cell)):
            flags.append(Flag("test_cell_edited", f"{gid}: the locked test cell was edited{restored}"))
        keys = ("grade", "solution", "locked", "points", "grade_id")
        changed = [k for k in keys if nbg(mine).get(k) != nbg(cell).get(k)] if nbg(mine) else []
        if changed:
            flags.append(Flag(f"{kind}_cell_edited",
                              f"{gid}: the cell's nbgrader metadata was changed ({', '.join(changed)}){restored}"))

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
