"""What the note needs from the package for a variant — the registry, the tasks' inputs, the visible checks — cached.

Each of these is slow the first time in a process (the reference sites and photos of the chapters are rebuilt
to grade an answer or to list a task's data) and cheap to keep: plain JSON.  With the student's cache open
(:func:`aerophoto.diskcache.enabled`, which :func:`aerophoto.report.build` does) they are kept on the student's
machine, signed and verified before use, keyed by the code's fingerprint, the variant and — for a verdict —
the student's values; without it they are computed every time.  The instructor's grading never opens the
cache (:mod:`aerophoto.diskcache`).

* :func:`registry` — the chapters' tasks as plain data (id, title, points, the answers' names, units, kinds,
  options), read through :mod:`aerophoto.gradebook`;
* :func:`inputs` — what the student works from in a task, reduced to plain data by the chapter's writer;
* :func:`visible_checks` — the verdicts of the visible checks the student's notebook runs
  (:mod:`aerophoto.course.verdict`), without the cross-variant search (a wrong answer is wrong; the note does
  not need to know whose it is) and without the hidden checks, which stay hidden.
"""

from __future__ import annotations

import contextlib
import json
import math
import re
from dataclasses import fields

from .. import diskcache

__all__ = ["variant_key", "plain", "registry", "inputs", "visible_checks", "values_key"]


def variant_key(v) -> dict:
    """The variant's fields as plain data (the cache key of everything computed for it)."""
    return {f.name: plain(getattr(v, f.name)) for f in fields(v)}


def plain(x):
    """``x`` as plain JSON data: numpy scalars and arrays as numbers and lists, tuples as lists, NaN/inf as None."""
    if x is None or isinstance(x, (bool, str)):
        return x
    if hasattr(x, "tolist") and not isinstance(x, (int, float)):
        return plain(x.tolist())
    if isinstance(x, int):
        return int(x)
    if isinstance(x, float):
        return float(x) if math.isfinite(x) else None
    if isinstance(x, dict):
        return {str(k): plain(e) for k, e in x.items()}
    if isinstance(x, (list, tuple)):
        return [plain(e) for e in x]
    try:
        f = float(x)
    except (TypeError, ValueError):
        return str(x)
    return f if math.isfinite(f) else None


def _cached(namespace: str, key: dict, build):
    cache = diskcache.active()
    if cache is None:
        return build()
    return cache.json(namespace, key, build)


# =========================================================================== the registry
def _spec_of(task) -> dict:
    return {"id": task.id, "title": task.title, "points": float(task.points),
            "spec": [{"name": a.name, "unit": a.unit, "kind": a.kind, "options": list(a.options),
                      "labels": list(a.labels)} for a in task.spec]}


def registry(numbers) -> dict:
    """chapter number → ``{"tasks": [task as plain data, …], "problem": why it could not be loaded or ""}``."""
    numbers = [str(n) for n in numbers]

    def build():
        from .. import gradebook

        out = {}
        for n in numbers:
            if not gradebook.has_tasks(n):
                out[n] = {"tasks": [], "problem": ""}
                continue
            try:
                out[n] = {"tasks": [_spec_of(t) for t in gradebook.chapter_tasks(n)], "problem": ""}
            except Exception as exc:  # one broken chapter must not cost the student the rest of the note
                out[n] = {"tasks": [], "problem": f"the chapter's tasks could not be loaded ({type(exc).__name__})"}
        return out
    return _cached("registry", {"chapters": numbers}, build)


# =========================================================================== inputs
def inputs(task_id: str, v, extract) -> dict:
    """``extract(raw inputs, variant)`` of the task's inputs (:func:`aerophoto.gradebook.task_inputs`), cached.

    ``extract`` (the chapter writer's) reduces the task's data to plain numbers and lists — what the note
    prints from it; it must never include a reference answer.  An input the package cannot give is {}.
    """
    def build():
        from .. import gradebook

        try:
            raw = gradebook.task_inputs(task_id, v)
            return plain(extract(raw, v))
        except Exception:  # an input the package cannot give is left out, never guessed
            return {}
    return _cached("inputs", {"task": task_id, "variant": variant_key(v), "extract": extract.__qualname__}, build)


# =========================================================================== the visible checks
def values_key(values: dict) -> str:
    """The student's values as canonical text (a missing answer as null)."""
    return json.dumps({k: (None if x is Ellipsis else plain(x)) for k, x in sorted(values.items())},
                      sort_keys=True, separators=(",", ":"), ensure_ascii=True)


class _NoCrossVariant:
    """The task as the visible checks see it, without the search through the other variants' answers."""

    cross_variant = False

    def __init__(self, task):
        self._task = task

    def __getattr__(self, name):
        return getattr(self._task, name)


def _clean(msg) -> str:
    return re.sub(r"\x1b\[[0-9;]*m", "", str(msg or "")).strip()


def visible_checks(task_id: str, v, values: dict, lang: str) -> dict:
    """``{"checks": {name: [ok, message]}}`` of the visible checks on the student's values (message in ``lang``)."""
    def build():
        from .. import gradebook
        from ..course.verdict import VERDICTS, answer_call
        from ..i18n import language

        task = gradebook.task(task_id)
        got = {n: values.get(n, Ellipsis) for n in task.names}
        proxy = _NoCrossVariant(task)

        def verdicts(names, expected, slips) -> dict:
            out = {}
            for a in task.spec:
                if a.name not in names:
                    continue
                try:
                    kind, args, kw = answer_call(proxy, a, got[a.name], expected[a.name], slips, v)
                    verdict = VERDICTS[kind](*args, **kw)
                    text = "" if verdict.ok else _clean(verdict.text)
                    if text.startswith(a.name + ": "):  # the note names the quantity itself, never the variable
                        text = text[len(a.name) + 2:]
                    out[a.name] = [bool(verdict.ok), text]
                except Exception as exc:  # a malformed answer must never stop the note
                    out[a.name] = [False, f"({type(exc).__name__})"]
            return out

        with language(lang), contextlib.redirect_stdout(None):
            expected = task.answers(v)
            out = verdicts(task.names, expected, {})
            wrong = [n for n, (ok, _) in out.items() if not ok]
            if wrong:  # the typical mistakes (some cost a whole adjustment) only to say what went wrong
                out.update(verdicts(wrong, expected, task.slips(v)))
        return {"checks": out}
    key = {"task": task_id, "variant": variant_key(v), "values": values_key(values), "lang": lang}
    return _cached("checks", key, build)
