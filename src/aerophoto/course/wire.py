"""The answer record: what a check cell sends from the student's kernel to the instructor's grader.

:func:`aerophoto.checks.check_task` puts the submitted values of its task into the cell's output under
:data:`ANSWERS_MIME`, as plain JSON data (:func:`encode_answers`), before it checks anything — always, so the
saved notebook keeps them (the course report reads them back: :func:`aerophoto.course.trusted.saved_answers`).
While the instructor grades (``AEROPHOTO_GRADING`` set in the sandbox) the grader (:mod:`.trusted`) reads the
record back (:func:`decode_answers`) and scores it outside the student's kernel (:mod:`.score`).

Both ends import this module, so it is pure: the standard library only, nothing else of aerophoto — the
student's kernel loads it without nbgrader or the rest of :mod:`aerophoto.course`.  It also holds the three
small readings of a submitted value that the checks share (:func:`scalar`, :func:`is_bool`,
:func:`as_sequence`).
"""

from __future__ import annotations

import math
from collections.abc import Mapping

__all__ = ["ANSWERS_MIME", "encode_answers", "decode_answers", "scalar", "is_bool", "as_sequence", "MAX_LIST",
           "MAX_STR"]

ANSWERS_MIME = "application/vnd.aerophoto.answers+json"
"""The output a check cell adds (beside a ``text/plain`` line JupyterLab shows): the submitted values."""

MAX_LIST = 2000
"""The longest list or array a record carries as values (a longer one is kept as its repr)."""
MAX_STR = 200
"""The longest string a record carries (longer: its repr, cut)."""


def is_bool(x) -> bool:
    """True and False, also numpy's booleans."""
    t = type(x)
    return isinstance(x, bool) or (t.__module__ == "numpy" and t.__name__ in ("bool", "bool_"))


def scalar(answer):
    """A one-element array or Series → its element; anything else unchanged."""
    size = getattr(answer, "size", None)
    if size == 1 and hasattr(answer, "item") and not isinstance(answer, (int, float)):
        try:
            return answer.item()
        except (TypeError, ValueError):
            return answer
    return answer


def as_sequence(values):
    """A list of the values of a list/tuple/array/Series; None if it is not a sequence."""
    if isinstance(values, (str, bytes, Mapping)) or values is None or values is Ellipsis:
        return None
    if hasattr(values, "tolist") and getattr(values, "ndim", 1) != 1:
        return None
    try:
        return list(values.tolist() if hasattr(values, "tolist") else values)
    except TypeError:
        return None


def _plain(x, depth: int = 0):
    """A submitted value as plain JSON data: numbers, strings, booleans, short lists and dicts."""
    x = scalar(x)
    if x is Ellipsis:
        return {"ellipsis": True}
    if x is None or isinstance(x, str) and len(x) <= MAX_STR:
        return x
    if is_bool(x):
        return bool(x)
    if isinstance(x, int):
        return int(x) if abs(x) < 2**63 else float(x)
    if isinstance(x, float) or type(x).__module__ == "numpy" and hasattr(x, "item") and getattr(x, "size", 0) == 1:
        f = float(x)
        return f if math.isfinite(f) else {"float": str(f)}
    if depth < 2 and isinstance(x, Mapping) and len(x) <= 200:
        return {"dict": [[_plain(k, depth + 1), _plain(v, depth + 1)] for k, v in x.items()]}
    seq = as_sequence(x)
    if depth < 2 and seq is not None and len(seq) <= MAX_LIST:
        return {"list": [_plain(v, depth + 1) for v in seq]}
    return {"repr": repr(x)[:MAX_STR]}


def _unplain(d):
    if isinstance(d, dict):
        if d.get("ellipsis"):
            return Ellipsis
        if "float" in d:
            return float(d["float"])
        if "list" in d:
            return [_unplain(v) for v in d["list"]]
        if "dict" in d:
            return {_unplain(k): _unplain(v) for k, v in d["dict"]}
        if "repr" in d:
            return _Opaque(str(d["repr"]))
        return _Opaque(str(d)[:MAX_STR])
    return d


class _Opaque(str):
    """A submitted value that was not plain data (its repr); every check rejects it as not a number."""

    def __repr__(self):
        return str.__str__(self)


def encode_answers(task_id: str, values: Mapping, variant=None) -> dict:
    """The submitted answers of one task as plain JSON data (what leaves a sandboxed grading run).

    ``variant`` is the kernel's :class:`~aerophoto.variants.Variant` (its index ``i`` is recorded) or None.
    """
    return {"task": str(task_id), "variant": None if variant is None else int(getattr(variant, "i", -1)),
            "values": {str(k): _plain(v) for k, v in values.items()}}


def decode_answers(record: Mapping) -> tuple[str, dict]:
    """(task id, {name: value}) from :func:`encode_answers`'s record; values that were not plain data stay opaque."""
    values = record.get("values") or {}
    if not isinstance(values, Mapping):
        values = {}
    return str(record.get("task", "")), {str(k): _unplain(v) for k, v in values.items()}
