"""Reading a student's answers from their notebooks without running them.

The student's notebook is not trusted, and the report runs in the instructor's (or the student's own)
process: nothing of the workbook is executed, imported or unpickled.  A notebook is read as JSON; the
``RECORD_BOOK = "…"`` line of its setup cell and the source of each task's answer cell
(``task-NN-k-answer``, found by cell id, else by nbgrader grade id) are parsed with :mod:`ast`, and the
assignments are evaluated by a tiny evaluator that knows only

* numbers, strings, ``True``/``False``/``None``, ``...`` (the template's "no answer yet"), lists and tuples;
* arithmetic (``+ - * / // % **``), comparisons, ``and``/``or``/``not``, ``x if c else y``, indexing, list
  comprehensions over lists;
* ``math.<name>`` (functions and constants; not the ones that can take unbounded time), a few ``np.<name>``
  that have a plain-Python meaning (``np.sqrt``, ``np.mean``, ``np.array``…), and the builtins ``abs``,
  ``round``, ``min``, ``max``, ``sum``, ``len``, ``int``, ``float``, ``bool``, ``list``, ``tuple``, ``range``;
* ``v.<attr>`` — the inputs of the student's variant (:class:`aerophoto.variants.Variant`);
* names assigned earlier in the answer cells of the same notebook.

Anything else — a call of package code, an import, a loop, a name from a non-answer cell — makes the
variables it assigns *not readable without running* (:data:`UNREADABLE`), with the reason; for those the
values the task's check cell recorded in the saved notebook are used when there is such a record for the
student's variant (:func:`check_records`, read as untrusted plain data).  Sizes are
bounded (source length, sequence length, exponents), so a hostile cell cannot make the reader run long.
"""

from __future__ import annotations

import ast
import json
import math
import operator
import re
from dataclasses import dataclass, field, fields
from pathlib import Path

__all__ = ["Unreadable", "UNREADABLE", "NotebookAnswers", "read_notebook", "evaluate_cells", "record_book_of",
           "check_records", "RECORDED", "MAX_NOTEBOOK_BYTES"]

#: a notebook file larger than this is not read (MB-sized outputs of a workbook are normal; 50 MB is not)
MAX_NOTEBOOK_BYTES = 50_000_000
_MAX_SOURCE = 20_000        # characters of one answer cell
_MAX_NODES = 5_000          # AST nodes of one answer cell
_MAX_SEQ = 10_000           # elements of a list built by the evaluator
_MAX_ABS_EXP = 1_000        # |exponent| of ** with an integer result
_MAX_STEPS = 200_000        # evaluation steps per notebook
_MAX_INT_BITS = 4_096       # a whole number larger than this is no answer (and repeated squaring must stop)


class Unreadable(Exception):
    """An expression the evaluator does not run; ``str(exc)`` says what it needs."""


class _Unreadable:
    """Marker value of a variable whose value needs running code (see :data:`UNREADABLE`)."""

    __slots__ = ("reason",)

    def __init__(self, reason: str):
        self.reason = reason

    def __repr__(self) -> str:
        return f"<not readable without running: {self.reason}>"


#: the type of a value that is not readable without running (``isinstance(x, UNREADABLE)``)
UNREADABLE = _Unreadable

_MATH_EXCLUDED = {"factorial", "comb", "perm", "prod", "lcm", "gcd", "isqrt", "fsum", "sumprod"}
_MATH = {n: getattr(math, n) for n in dir(math) if not n.startswith("_") and n not in _MATH_EXCLUDED}


def _elementwise(fn):
    def wrapped(x, *rest):
        if isinstance(x, (list, tuple)):
            return [fn(_num(e), *rest) for e in x]
        return fn(_num(x), *rest)
    return wrapped


def _num(x):
    if isinstance(x, bool) or not isinstance(x, (int, float)):
        raise Unreadable(f"{x!r} is not a number")
    return x


def _seq(x) -> list:
    if isinstance(x, (list, tuple)):
        return list(x)
    raise Unreadable("expected a list of numbers")


def _mean(x):
    xs = [_num(e) for e in _seq(x)]
    if not xs:
        raise Unreadable("mean of an empty list")
    return sum(xs) / len(xs)


def _array(x, *args, **kwargs):
    if args or kwargs:
        raise Unreadable("np.array with options")
    return list(_seq(x))


_NP = {
    "sqrt": _elementwise(math.sqrt), "sin": _elementwise(math.sin), "cos": _elementwise(math.cos),
    "tan": _elementwise(math.tan), "arctan": _elementwise(math.atan), "arcsin": _elementwise(math.asin),
    "arccos": _elementwise(math.acos), "arctan2": lambda y, x: math.atan2(_num(y), _num(x)),
    "radians": _elementwise(math.radians), "degrees": _elementwise(math.degrees), "deg2rad": _elementwise(math.radians),
    "rad2deg": _elementwise(math.degrees), "abs": _elementwise(abs), "log10": _elementwise(math.log10),
    "log": _elementwise(math.log), "exp": _elementwise(math.exp), "hypot": lambda a, b: math.hypot(_num(a), _num(b)),
    "ceil": _elementwise(math.ceil), "floor": _elementwise(math.floor), "mean": _mean,
    "sum": lambda x: sum(_num(e) for e in _seq(x)), "array": _array, "asarray": _array,
    "pi": math.pi, "e": math.e,
}


def _range(*args):
    r = range(*[int(_num(a)) for a in args])
    if len(r) > _MAX_SEQ:
        raise Unreadable(f"a range of {len(r)} elements")
    return list(r)


def _round(x, nd=None):
    if isinstance(x, (list, tuple)):
        raise Unreadable("round() of a list")
    return round(_num(x)) if nd is None else round(_num(x), int(_num(nd)))


_BUILTINS = {
    "abs": lambda x: abs(_num(x)), "round": _round, "min": lambda *a: min(*a) if len(a) > 1 else min(_seq(a[0])),
    "max": lambda *a: max(*a) if len(a) > 1 else max(_seq(a[0])), "sum": lambda x: sum(_num(e) for e in _seq(x)),
    "len": lambda x: len(_seq(x)), "int": lambda x: int(_num(x)), "float": lambda x: float(_num(x)),
    "bool": bool, "list": lambda x=(): list(_seq(x)), "tuple": lambda x=(): tuple(_seq(x)), "range": _range,
}

_BINOPS = {ast.Add: operator.add, ast.Sub: operator.sub, ast.Mult: operator.mul, ast.Div: operator.truediv,
           ast.FloorDiv: operator.floordiv, ast.Mod: operator.mod, ast.Pow: operator.pow}
_CMPOPS = {ast.Eq: operator.eq, ast.NotEq: operator.ne, ast.Lt: operator.lt, ast.LtE: operator.le,
           ast.Gt: operator.gt, ast.GtE: operator.ge}


class _Namespace:
    """``v``, ``math``, ``np``: attribute look-ups only from a fixed table."""

    def __init__(self, name: str, attrs: dict):
        self.name, self.attrs = name, attrs

    def get(self, attr: str):
        if attr not in self.attrs:
            raise Unreadable(f"{self.name}.{attr}")
        return self.attrs[attr]


def variant_namespace(v) -> _Namespace:
    """``v.<attr>`` of the student's variant: its fields and the numeric properties (H_m, relief_m)."""
    attrs = {f.name: getattr(v, f.name) for f in fields(v)}
    for prop in ("H_m", "relief_m"):
        attrs[prop] = getattr(v, prop)
    return _Namespace("v", attrs)


class _Evaluator:
    def __init__(self, env: dict, names: dict):
        self.env = env          # earlier answers: name → value (or an _Unreadable)
        self.names = names      # v, math, np, builtins
        self.steps = 0

    def _tick(self):
        self.steps += 1
        if self.steps > _MAX_STEPS:
            raise Unreadable("too long to evaluate")

    def eval(self, node):  # noqa: C901 - one dispatch over the few node types allowed
        self._tick()
        if isinstance(node, ast.Constant):
            if node.value is Ellipsis or isinstance(node.value, (int, float, str, bool)) or node.value is None:
                if isinstance(node.value, str) and len(node.value) > 1000:
                    raise Unreadable("a very long string")
                return node.value
            raise Unreadable(f"a constant of type {type(node.value).__name__}")
        if isinstance(node, ast.Name):
            if node.id in self.env:
                val = self.env[node.id]
                if isinstance(val, _Unreadable):
                    raise Unreadable(f"{node.id} ({val.reason})")
                return val
            if node.id in self.names:
                return self.names[node.id]
            raise Unreadable(f"the name {node.id!r}, not set in an answer cell above")
        if isinstance(node, (ast.List, ast.Tuple)):
            out = [self.eval(e) for e in node.elts]
            if any(isinstance(e, ast.Starred) for e in node.elts):
                raise Unreadable("a starred expression")
            return out if isinstance(node, ast.List) else tuple(out)
        if isinstance(node, ast.UnaryOp):
            x = self.eval(node.operand)
            if isinstance(node.op, ast.Not):
                return not x
            x = _num(x)
            if isinstance(node.op, ast.USub):
                return -x
            if isinstance(node.op, ast.UAdd):
                return +x
            raise Unreadable("a bitwise operator")
        if isinstance(node, ast.BinOp):
            op = _BINOPS.get(type(node.op))
            if op is None:
                raise Unreadable("a bitwise or matrix operator")
            a, b = self.eval(node.left), self.eval(node.right)
            return self._binop(op, a, b)
        if isinstance(node, ast.BoolOp):
            val = None
            for e in node.values:
                val = self.eval(e)
                if isinstance(node.op, ast.And) and not val:
                    return val
                if isinstance(node.op, ast.Or) and val:
                    return val
            return val
        if isinstance(node, ast.Compare):
            left = self.eval(node.left)
            for op, comp in zip(node.ops, node.comparators):
                fn = _CMPOPS.get(type(op))
                if fn is None:
                    raise Unreadable("'in' or 'is'")
                right = self.eval(comp)
                if not fn(self._cmp_operand(left), self._cmp_operand(right)):
                    return False
                left = right
            return True
        if isinstance(node, ast.IfExp):
            return self.eval(node.body) if self.eval(node.test) else self.eval(node.orelse)
        if isinstance(node, ast.Attribute):
            base = self.eval(node.value)
            if isinstance(base, _Namespace):
                return base.get(node.attr)
            raise Unreadable(f"the attribute .{node.attr}")
        if isinstance(node, ast.Subscript):
            base = self.eval(node.value)
            if not isinstance(base, (list, tuple)):
                raise Unreadable("indexing something that is not a list")
            if isinstance(node.slice, ast.Slice):
                parts = [None if p is None else int(_num(self.eval(p)))
                         for p in (node.slice.lower, node.slice.upper, node.slice.step)]
                if parts[2] == 0:
                    raise Unreadable("a slice with step 0")
                return base[slice(*parts)]
            idx = self.eval(node.slice)
            if isinstance(idx, bool) or not isinstance(idx, int):
                raise Unreadable("an index that is not a whole number")
            try:
                return base[idx]
            except IndexError:
                raise Unreadable("an index out of range") from None
        if isinstance(node, ast.Call):
            fn = self.eval(node.func)
            if not callable(fn) or isinstance(fn, _Namespace):
                raise Unreadable("a call of something that is not a known function")
            if any(isinstance(a, ast.Starred) for a in node.args):
                raise Unreadable("a starred argument")
            args = [self.eval(a) for a in node.args]
            if node.keywords:
                raise Unreadable("a call with keyword arguments")
            try:
                return fn(*args)
            except Unreadable:
                raise
            except (ArithmeticError, ValueError, TypeError) as exc:
                raise Unreadable(f"an error while computing ({type(exc).__name__})") from None
        if isinstance(node, ast.ListComp):
            return self._listcomp(node)
        raise Unreadable(f"a {type(node).__name__} expression")

    @staticmethod
    def _cmp_operand(x):
        if isinstance(x, (int, float, str, bool)) or x is None:
            return x
        raise Unreadable("a comparison of lists")

    def _binop(self, op, a, b):
        if isinstance(a, (list, tuple)) or isinstance(b, (list, tuple)):
            if op is operator.add and isinstance(a, (list, tuple)) and isinstance(b, type(a)):
                if len(a) + len(b) > _MAX_SEQ:
                    raise Unreadable("a list that is too long")
                return a + b
            if op is operator.mul and isinstance(b, int) and not isinstance(b, bool) and isinstance(a, (list, tuple)):
                if len(a) * max(b, 0) > _MAX_SEQ:
                    raise Unreadable("a list that is too long")
                return a * b
            raise Unreadable("arithmetic on a list (write each element, or a list comprehension)")
        if isinstance(a, str) or isinstance(b, str):
            if op is operator.add and isinstance(a, str) and isinstance(b, str) and len(a) + len(b) <= 1000:
                return a + b
            raise Unreadable("arithmetic on text")
        a, b = _num(a), _num(b)
        if op is operator.pow:
            if isinstance(b, int) and abs(b) > _MAX_ABS_EXP and isinstance(a, int) and abs(a) > 1:
                raise Unreadable("a power that is too large")
            if isinstance(a, int) and isinstance(b, int) and b > 0 and abs(a) > 1 and b * math.log2(abs(a)) > 4000:
                raise Unreadable("a power that is too large")
        try:
            out = op(a, b)
        except (ArithmeticError, ValueError) as exc:
            raise Unreadable(f"an error while computing ({type(exc).__name__})") from None
        if isinstance(out, complex):
            raise Unreadable("a complex number")
        if isinstance(out, int) and out.bit_length() > _MAX_INT_BITS:
            raise Unreadable("a whole number that is too large")
        return out

    def _listcomp(self, node: ast.ListComp):
        if len(node.generators) != 1:
            raise Unreadable("a nested list comprehension")
        gen = node.generators[0]
        if gen.is_async or not isinstance(gen.target, (ast.Name, ast.Tuple)):
            raise Unreadable("a list comprehension of this form")
        items = self.eval(gen.iter)
        if not isinstance(items, (list, tuple)):
            raise Unreadable("a list comprehension over something that is not a list")
        if len(items) > _MAX_SEQ:
            raise Unreadable("a list that is too long")
        saved = dict(self.env)
        out = []
        try:
            for item in items:
                self._bind(gen.target, item)
                if all(self.eval(c) for c in gen.ifs):
                    out.append(self.eval(node.elt))
        finally:
            self.env.clear()
            self.env.update(saved)
        return out

    def _bind(self, target, value):
        if isinstance(target, ast.Name):
            self.env[target.id] = value
            return
        if isinstance(target, (ast.Tuple, ast.List)) and all(isinstance(t, ast.Name) for t in target.elts):
            if not isinstance(value, (list, tuple)) or len(value) != len(target.elts):
                raise Unreadable("unpacking into the wrong number of names")
            for t, x in zip(target.elts, value):
                self.env[t.id] = x
            return
        raise Unreadable("an assignment to something other than plain names")


def _targets(stmt) -> list[str]:
    """Every plain name a statement stores into (whatever its kind)."""
    return sorted({n.id for n in ast.walk(stmt) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Store)})


def evaluate_cells(sources, variant, *, snapshots: list | None = None) -> dict:
    """Evaluate answer-cell sources in order; returns ``{name: value}`` (values may be :data:`UNREADABLE`).

    ``sources`` is a list of strings (the notebook's answer cells, in notebook order); ``variant`` the
    student's :class:`~aerophoto.variants.Variant` (for ``v.<attr>``).  Never runs anything else.
    With ``snapshots`` (a list), a copy of the variables after each cell is appended to it — what the
    check cell under that answer cell sees, even when a later cell reuses a name.
    """
    env: dict = {}
    names = {"v": variant_namespace(variant), "math": _Namespace("math", _MATH),
             "np": _Namespace("np", _NP), "numpy": _Namespace("numpy", _NP), **_BUILTINS,
             "True": True, "False": False, "None": None}
    ev = _Evaluator(env, names)
    for src in sources:
        src = str(src)
        _one_cell(ev, src)
        if snapshots is not None:
            snapshots.append(dict(env))
    return env


def _one_cell(ev: _Evaluator, src: str) -> None:
    env = ev.env
    if len(src) > _MAX_SOURCE:
        for name in set(re.findall(r"^\s*([A-Za-z_]\w*)\s*=", src, re.M)):
            env[name] = _Unreadable("the answer cell is too long to read")
        return
    try:
        tree = ast.parse(src, mode="exec")
    except (SyntaxError, ValueError, RecursionError, MemoryError) as exc:
        why = "an expression nested too deeply" if isinstance(exc, (RecursionError, MemoryError)) else \
            f"a syntax error in the answer cell (line {getattr(exc, 'lineno', '?')})"
        for name in set(re.findall(r"^\s*([A-Za-z_]\w*)\s*=", src, re.M)):
            env[name] = _Unreadable(why)
        return
    if sum(1 for _ in ast.walk(tree)) > _MAX_NODES:
        for stmt in tree.body:
            for name in _targets(stmt):
                env[name] = _Unreadable("the answer cell is too long to read")
        return
    for stmt in tree.body:
        _statement(ev, stmt)


def _statement(ev: _Evaluator, stmt) -> None:
    env = ev.env
    try:
        if isinstance(stmt, ast.Assign):
            value = ev.eval(stmt.value)
            for t in stmt.targets:
                ev._bind(t, value)
        elif isinstance(stmt, ast.AnnAssign) and stmt.value is not None and isinstance(stmt.target, ast.Name):
            env[stmt.target.id] = ev.eval(stmt.value)
        elif isinstance(stmt, ast.AugAssign) and isinstance(stmt.target, ast.Name):
            op = _BINOPS.get(type(stmt.op))
            if op is None:
                raise Unreadable("a bitwise operator")
            env[stmt.target.id] = ev._binop(op, ev.eval(ast.Name(stmt.target.id, ast.Load())), ev.eval(stmt.value))
        elif isinstance(stmt, (ast.Expr, ast.Pass)):
            return  # a bare expression (a value shown in the notebook) assigns nothing
        else:
            raise Unreadable(f"a {type(stmt).__name__} statement")
    except Unreadable as exc:
        for name in _targets(stmt):
            env[name] = _Unreadable(str(exc))
    except RecursionError:
        for name in _targets(stmt):
            env[name] = _Unreadable("an expression nested too deeply")


# =========================================================================== notebooks
def _cells(nb) -> list:
    cells = nb.get("cells") if isinstance(nb, dict) else None
    return [c for c in cells if isinstance(c, dict)] if isinstance(cells, list) else []


def _source(cell) -> str:
    src = cell.get("source", "")
    if isinstance(src, list):
        return "".join(s for s in src if isinstance(s, str))
    return src if isinstance(src, str) else ""


def _grade_id(cell) -> str:
    meta = cell.get("metadata")
    nbg = meta.get("nbgrader") if isinstance(meta, dict) else None
    gid = nbg.get("grade_id") if isinstance(nbg, dict) else None
    return gid if isinstance(gid, str) else ""


def record_book_of(nb) -> str | None:
    """The ``RECORD_BOOK = "…"`` of a notebook's setup cell (id ``setup``, else the first code cell), or None."""
    cells = _cells(nb)
    setup = next((c for c in cells if c.get("id") == "setup"), None)
    if setup is None:
        setup = next((c for c in cells if c.get("cell_type") == "code"), None)
    if setup is None:
        return None
    try:
        tree = ast.parse(_source(setup))
    except (SyntaxError, ValueError, RecursionError, MemoryError):
        return None
    for stmt in tree.body:
        if (isinstance(stmt, ast.Assign) and len(stmt.targets) == 1 and isinstance(stmt.targets[0], ast.Name)
                and stmt.targets[0].id == "RECORD_BOOK" and isinstance(stmt.value, ast.Constant)):
            val = stmt.value.value
            if isinstance(val, (str, int)) and not isinstance(val, bool) and str(val).strip():
                return str(val).strip()[:64]
    return None


@dataclass
class NotebookAnswers:
    """What one notebook says, read without running it.

    ``answer_cells``: task id → the answer cell's source (tasks whose cell was found);
    ``records``: task id → ``(variant index, {name: value})``, the values its check cell recorded in the saved
    notebook (:func:`check_records`); ``record_book``: the setup cell's number (or None); ``problem``: why the
    file could not be read.
    """

    path: Path
    record_book: str | None = None
    answer_cells: dict = field(default_factory=dict)
    order: list = field(default_factory=list)
    records: dict = field(default_factory=dict)
    problem: str = ""

    def values(self, variant) -> dict:
        """task id → the variables right after its answer cell, evaluated for ``variant`` (:func:`evaluate_cells`).

        A variable the evaluator cannot read (an answer computed with package code) takes the value the task's
        check cell recorded when the notebook was run, if that record is for this variant; such names are
        listed under the key ``RECORDED`` of the task's variables.
        """
        snaps: list = []
        evaluate_cells([self.answer_cells[t] for t in self.order], variant, snapshots=snaps)
        out = dict(zip(self.order, snaps))
        for task, env in out.items():
            rec = self.records.get(task)
            if rec is None or rec[0] != int(variant.i):
                continue
            taken = [n for n, x in env.items() if isinstance(x, _Unreadable) and n in rec[1]]
            for n in taken:
                env[n] = rec[1][n]
            if taken:
                env[RECORDED] = tuple(sorted(taken))
        return out


#: the key under which :meth:`NotebookAnswers.values` lists the names taken from a check cell's record
RECORDED = "__recorded__"
_MAX_RECORD_LIST = 2000


def _plain_value(x):
    """A recorded value if it is plain data the report can show (a number, a bool, short text, a list of
    those), else None.  Records are untrusted: nothing else is kept."""
    if isinstance(x, bool):
        return x
    if isinstance(x, int):
        return x if x.bit_length() <= 64 else None
    if isinstance(x, float):
        return x if math.isfinite(x) else None
    if isinstance(x, str):
        return x if len(x) <= 200 else None
    if isinstance(x, list) and len(x) <= _MAX_RECORD_LIST:
        items = [_plain_value(e) for e in x]
        return items if all(e is not None and not isinstance(e, list) for e in items) else None
    return None


def check_records(nb, task_ids) -> dict:
    """task id → ``(variant index, {name: value})`` of the last answer record each task's check cell left in the
    saved notebook (:func:`aerophoto.course.trusted.answer_records`), read as untrusted data.

    A record is taken from an output's ``data`` or its ``metadata`` under :data:`aerophoto.course.wire.ANSWERS_MIME`;
    only plain values are kept (:func:`_plain_value`), and a record of another task is ignored.
    """
    from ..course.trusted import answer_records
    from ..course.wire import ANSWERS_MIME, decode_answers

    wanted = {f"{t}-check": t for t in task_ids}
    clean = []
    for cell in _cells(nb):
        gid = _grade_id(cell)
        outputs = cell.get("outputs")
        if gid not in wanted or not isinstance(outputs, list):
            continue
        outs = []
        for o in outputs:
            if not isinstance(o, dict):
                continue
            data, meta = o.get("data"), o.get("metadata")
            rec = data.get(ANSWERS_MIME) if isinstance(data, dict) else None
            if rec is None and isinstance(meta, dict):
                rec = meta.get(ANSWERS_MIME)
            if isinstance(rec, (dict, str)) and (not isinstance(rec, str) or len(rec) <= 300_000):
                outs.append({"data": {ANSWERS_MIME: rec}})
        meta = cell.get("metadata") if isinstance(cell.get("metadata"), dict) else {}
        clean.append({"cell_type": "code", "metadata": {"nbgrader": dict(meta.get("nbgrader") or {})},
                      "outputs": outs, "source": ""})
    try:
        found = answer_records({"cells": clean})
    except (TypeError, ValueError, AttributeError, KeyError, RecursionError):
        return {}
    out = {}
    for gid, recs in found.items():
        task = wanted.get(gid)
        if task is None or not recs:
            continue
        try:
            rec_task, values = decode_answers(recs[-1])
            variant = int(recs[-1].get("variant"))
        except (TypeError, ValueError, AttributeError):
            continue
        if rec_task != task:
            continue
        kept = {str(k): _plain_value(x) for k, x in values.items() if isinstance(k, str) and k.isidentifier()}
        out[task] = (variant, {k: x for k, x in kept.items() if x is not None})
    return out


def read_notebook(path, task_ids) -> NotebookAnswers:
    """Read a notebook's setup number and the answer cells of ``task_ids`` (JSON only; nothing runs)."""
    path = Path(path)
    out = NotebookAnswers(path)
    try:
        size = path.stat().st_size
        if size > MAX_NOTEBOOK_BYTES:
            out.problem = f"the file is {size / 1e6:.0f} MB, larger than {MAX_NOTEBOOK_BYTES / 1e6:.0f} MB"
            return out
        nb = json.loads(path.read_text(encoding="utf-8"))
    except (OSError, UnicodeDecodeError, ValueError, RecursionError) as exc:
        out.problem = f"not a readable notebook ({type(exc).__name__})"
        return out
    if not isinstance(nb, dict):
        out.problem = "not a notebook"
        return out
    out.record_book = record_book_of(nb)
    wanted = {f"{t}-answer": t for t in task_ids}
    found: dict = {}
    for k, cell in enumerate(_cells(nb)):
        if cell.get("cell_type") != "code":
            continue
        key = cell.get("id") if cell.get("id") in wanted else _grade_id(cell)
        if key in wanted and wanted[key] not in found:
            found[wanted[key]] = (k, _source(cell))
    out.order = [t for t, _ in sorted(found.items(), key=lambda kv: kv[1][0])]
    out.answer_cells = {t: src for t, (_, src) in found.items()}
    out.records = check_records(nb, task_ids)
    return out
