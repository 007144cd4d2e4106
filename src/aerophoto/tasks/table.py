"""The grading table: for every task, the values it grades, their tolerances, the methods it accepts and the
slips it rejects — rendered from the tasks' own data into ``docs/grading_table.md`` (``python -m aerophoto.tasks``).

Two parts, kept apart so the table can be checked quickly and proved slowly:

* the **data** of each task — its answers (unit, printed unit, tolerance), its :attr:`~aerophoto.tasks.Task.methods`
  (which reading of an ambiguous source the book adopts), its catalogued slips and its hidden checks — read from
  the code (:func:`render`, instant; tests/content/test_grading_table.py holds the file to it);
* the **measured deviations** over all 100 variants — how far each accepted method and each rounding of the
  answers lies from the reference, and how close each slip comes, in tolerances (:func:`measure`, minutes; kept in
  ``docs/grading_deviations.json`` and proved by the exhaustive grading sweep, which measures them again).

A tolerance is right when every accepted deviation is below 1 and every slip above it.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np

from .rounding import _FLOAT_SLACK, _TOL_REL, width

__all__ = ["DOC", "DEVIATIONS", "HIDDEN", "width", "deviation", "measure_variant", "merge", "combine", "measure",
           "hidden_names",
           "render", "write", "main"]

DOC = "docs/grading_table.md"
DEVIATIONS = "docs/grading_deviations.json"


def deviation(answer, sub, ref) -> float | None:
    """How far ``sub`` lies from ``ref`` in tolerances (the largest over a sequence; None if not comparable)."""
    w = width(answer, ref)
    if w is None:
        return None
    try:
        x, r = np.asarray(sub, dtype=float), np.asarray(ref, dtype=float)
        # the verdict's "≤ tolerance" is inclusive up to FLOAT_SLACK of the values: so is a deviation of 1
        d = np.maximum(np.abs(x - r) - _FLOAT_SLACK * np.maximum(np.abs(x), np.abs(r)), 0.0)
    except (TypeError, ValueError):
        return None
    if d.shape != np.shape(w) and np.ndim(w) != 0:
        return None
    with np.errstate(divide="ignore", invalid="ignore"):
        q = np.where(np.asarray(w) > 0, d / np.asarray(w), np.where(d > 0, np.inf, 0.0))
    return float(np.max(q)) if q.size else 0.0


def _forms(task, v, ref) -> dict:
    from .rounding import four_digits, round_to

    out = {"4 significant digits": {}, "printed unit": {}}
    for a in task.spec:
        if width(a, ref[a.name]) is None:
            continue
        x = np.asarray(ref[a.name], dtype=float)
        out["4 significant digits"][a.name] = four_digits(x, a)
        out["printed unit"][a.name] = round_to(x, a.printed) if a.printed else x
    return out


def measure_variant(task, v) -> dict:
    """The deviations of one task for one variant: ``{answer: {"rounding": …, "methods": {…}, "slips": {…}}}``
    (in tolerances; methods and roundings the largest, slips the smallest)."""
    ref = task.answers(v)
    out = {a.name: {"rounding": {}, "methods": {}, "slips": {}} for a in task.spec if width(a, ref[a.name]) is not None}
    for form, sub in _forms(task, v, ref).items():
        for name, x in sub.items():
            out[name]["rounding"][form] = deviation(task.answer(name), x, ref[name])
    # a method is measured from the nearest value the verdict accepts: the reference, or another reading's
    # value (Task.accepted: 14.1's printed m_D, 16.1's “zr” as 2r, 17.3's transfer), each with its own tolerance
    alternatives = task.accepted(v) or {}
    for m in task.methods:
        if m.submit is None:
            continue
        sub = m.submission(task, v)
        for name in out:
            targets = [ref[name], *(x for x in (alternatives.get(name) or {}).values() if x is not None)]
            ds = [d for d in (deviation(task.answer(name), sub[name], x) for x in targets) if d is not None]
            d = min(ds) if ds else None
            if d is not None and d > 0:
                out[name]["methods"][m.name] = d
    for name, hints in (task.slips(v) or {}).items():
        if name not in out:
            continue
        for hint, value in hints.items():
            d = None if value is None else deviation(task.answer(name), value, ref[name])
            if d is not None and d > 1.0:  # a slip within the tolerance is not told apart: its hint is off there
                out[name]["slips"][hint] = d
    return out


def merge(into: dict, one: dict, variant: int) -> dict:
    """Fold one variant's :func:`measure_variant` into the running extremes ``into`` (changed and returned):
    ``{answer: {"rounding"/"methods": {name: [largest, variant]}, "slips": {hint: [smallest, variant, count]}}}``."""
    for name, parts in one.items():
        slot = into.setdefault(name, {"rounding": {}, "methods": {}, "slips": {}})
        for part in ("rounding", "methods"):
            for k, d in parts[part].items():
                if d is not None and (k not in slot[part] or d > slot[part][k][0]):
                    slot[part][k] = [d, variant]
        for k, d in parts["slips"].items():
            old = slot["slips"].get(k)
            if old is None:
                slot["slips"][k] = [d, variant, 1]
            else:
                old[2] += 1
                if d < old[0]:
                    old[0], old[1] = d, variant
    return into


def combine(a: dict, b: dict) -> dict:
    """Two :func:`merge` results (of disjoint variants) as one (``a`` changed and returned)."""
    for name, parts in b.items():
        slot = a.setdefault(name, {"rounding": {}, "methods": {}, "slips": {}})
        for part in ("rounding", "methods"):
            for k, (d, i) in parts[part].items():
                if k not in slot[part] or d > slot[part][k][0]:
                    slot[part][k] = [d, i]
        for k, (d, i, n) in parts["slips"].items():
            old = slot["slips"].get(k)
            slot["slips"][k] = [d, i, n] if old is None else ([d, i, old[2] + n] if d < old[0] else
                                                               [old[0], old[1], old[2] + n])
    return a


def _measure_part(args) -> dict:
    task_ids, variants = args
    from . import get
    from ..variants import variant_for_index

    out = {}
    for tid in task_ids:
        acc: dict = {}
        for i in variants:
            merge(acc, measure_variant(get(tid), variant_for_index(int(i))), int(i))
        out[tid] = acc
    return out


def measure(variants=range(100), tasks=None, jobs: int = 1) -> dict:
    """:func:`measure_variant` of every task over ``variants``, merged: ``{task id: {answer: …}}`` (``jobs``
    processes share the variants)."""
    from . import all_tasks

    ids = [t.id for t in (tasks if tasks is not None else all_tasks())]
    variants = [int(i) for i in variants]
    parts = [(ids, variants[k::jobs]) for k in range(max(1, int(jobs)))]
    if len(parts) == 1:
        results = [_measure_part(parts[0])]
    else:
        import multiprocessing

        with multiprocessing.get_context("fork").Pool(len(parts)) as pool:
            results = pool.map(_measure_part, parts)
    out: dict = {}
    for r in results:
        for tid, acc in r.items():
            combine(out.setdefault(tid, {}), acc)
    from . import get

    return {tid: {**out[tid], HIDDEN: hidden_names(get(tid))} for tid in ids}


HIDDEN = "(hidden checks)"
"""The key of a task's hidden checks' names in :func:`measure`'s result."""


def hidden_names(task, i: int = 0) -> list:
    """The names of ``task``'s hidden checks (on the reference answers of variant ``i``)."""
    from ..variants import variant_for_index

    v = variant_for_index(i)
    return [h.name for h in task.hidden(v, task.answers(v))]


# ------------------------------------------------------------------------------------------------ rendering
def _num(x) -> str:
    if x is None:
        return "—"
    if x == 0:
        return "0"
    if not math.isfinite(x):
        return "∞"
    return f"{x:.2g}" if x < 10 else f"{x:.0f}"


def _tolerance(a) -> str:
    if a.kind == "count":
        return f"exact (rounding: {a.rounding})"
    if a.kind in ("bool", "choice"):
        return "exact"
    if a.integer:
        return "exact (a count)"
    parts = []
    if a.tol_abs is not None:
        parts.append(f"{a.tol_abs:g} {a.unit}".strip())
    if a.tol_rel is not None:
        parts.append(f"{100 * a.tol_rel:g} %")
    if not parts:
        parts.append(f"{100 * _TOL_REL:g} % (default)")
    return " or ".join(parts)


def _cell(items: dict, worst: str) -> str:
    if not items:
        return "—"
    return "<br>".join(f"{_md(k)}: {_num(v[0])} (i = {v[1]:02d})" for k, v in sorted(items.items(), key=lambda kv:
                                                                                    (kv[1][0] if worst == "max" else
                                                                                     -kv[1][0])))


def _md(s: str) -> str:
    return str(s).replace("|", "\\|").replace("\n", " ")


def _task_section(task, measured: dict | None) -> list[str]:
    kind = "partial credit" if task.partial else "all or nothing"
    lines = [f"### {task.id.replace('task-', 'Task ').replace('-', '.', 1).replace('-', '.')} — {_md(task.title)}",
             "", f"{task.points} points, {kind}.", ""]
    lines.append("**Methods** (the first is the reference's):")
    lines.append("")
    for m in task.methods:
        tag = {"adopted": " — *the reading the book adopts*", "other": " — *the other reading, accepted*"}.get(
            m.reading, "")
        lines.append(f"* {_md(m.name)}{tag}" + (f" — {_md(m.note)}" if m.note else ""))
    lines.append("")
    lines += ["| answer | unit | printed | tolerance | roundings and accepted methods, largest deviation | "
              "catalogued slips, smallest deviation |", "|---|---|---|---|---|---|"]
    mt = (measured or {}).get(task.id, {})
    for a in task.spec:
        m = mt.get(a.name)
        if m is None:
            accepted, slips = ("—", "—") if a.kind in ("value", "values") and not a.integer else ("exact", "exact")
        else:
            accepted = _cell({**m.get("rounding", {}), **m.get("methods", {})}, "max")
            slips = "<br>".join(f"{_md(k)}: {_num(v[0])} (i = {v[1]:02d}; in {v[2]} variants)"
                                for k, v in sorted(m.get("slips", {}).items(), key=lambda kv: kv[1][0])) or "—"
        printed = "—" if a.printed is None else f"{a.printed:g}"
        lines.append(f"| `{a.name}` | {_md(a.unit) or '—'} | {printed} | {_md(_tolerance(a))} | {accepted} | {slips} |")
    names = mt.get(HIDDEN) or ()
    if names:
        lines += ["", "**Hidden checks** (each against the student's own answers, its tolerance propagated from "
                  "the rounding of the values it uses): " + "; ".join(_md(n) for n in names) + "."]
    return lines + [""]


def render(measured: dict | None = None) -> str:
    """The text of ``docs/grading_table.md`` for every task, with ``measured`` deviations (:func:`measure`)."""
    from . import all_tasks

    head = [
        "# The grading table",
        "",
        "<!-- generated by `python -m aerophoto.tasks` from aerophoto.tasks (the tasks' data) and "
        f"{DEVIATIONS} (`python -m aerophoto.tasks --measure`); do not edit -->",
        "",
        "Every graded task of the book: what it grades, the tolerance of each value, the methods the chapter "
        "teaches and accepts, and the slips it rejects. *Printed* is the unit of the last digit the task expects "
        "written (the guide's, or finer where the task's text asks for more digits). Deviations are measured over "
        "all 100 variants **in tolerances** (a method from the nearest accepted value: the reference or another "
        "reading's): the largest of every rounding and accepted method must stay below 1, "
        "the smallest of every slip above it (where a slip is not told apart for a variant, its hint is off there "
        "and the count of variants says so). *i* is the variant where the extreme occurs. The on-screen check and "
        "the instructor's grader run the same scorer (`aerophoto.course.score.grade_task`), so a value accepted "
        "here is accepted in both; the exhaustive grading sweep (`tests/content/test_grading_sweep.py`) proves "
        "it on every task, variant and form.",
        "",
    ]
    body = []
    chapter = None
    for t in all_tasks():
        if t.chapter != chapter:
            chapter = t.chapter
            body += [f"## Chapter {chapter}", ""]
        body += _task_section(t, measured)
    return "\n".join(head + body).rstrip() + "\n"


def _root() -> Path:
    return Path(__file__).resolve().parents[3]


def write(root=None, *, measured: dict | None = None) -> Path:
    """Write ``docs/grading_table.md`` (reading ``docs/grading_deviations.json`` unless ``measured`` is given)."""
    root = Path(root) if root is not None else _root()
    if measured is None:
        path = root / DEVIATIONS
        measured = json.loads(path.read_text(encoding="utf-8")) if path.is_file() else None
    out = root / DOC
    out.write_text(render(measured), encoding="utf-8")
    return out


def main(argv=None) -> int:
    """``python -m aerophoto.tasks``: rewrite docs/grading_table.md; ``--measure [--jobs N]``: measure the deviations
    over all 100 variants first (minutes; N processes, 2 by default), writing docs/grading_deviations.json."""
    import sys

    args = sys.argv[1:] if argv is None else list(argv)
    root = _root()
    if "--measure" in args:
        jobs = int(args[args.index("--jobs") + 1]) if "--jobs" in args else 2
        measured = measure(jobs=jobs)
        (root / DEVIATIONS).write_text(json.dumps(measured, ensure_ascii=False, indent=1, sort_keys=True) + "\n",
                                       encoding="utf-8")
        print("wrote", DEVIATIONS)
    print("wrote", write(root).relative_to(root))
    return 0
