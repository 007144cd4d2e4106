"""Inputs never carry graded answers (issue 27): for every task and a few variants, no graded number of the task
is found anywhere in what ``tasks.inputs`` gives — its attributes, properties, tables, summaries, arrays.

The walk goes through what a student can reach without calling a package function with arguments: attributes
and properties, mappings, sequences, arrays, DataFrames, and the object's own argument-free reporting methods
(``table()``, ``summary()``, ``*_table()``).  A number counts as found when it equals a graded answer exactly
(whole numbers) or to nine significant digits.
"""

from __future__ import annotations

import dataclasses
import math
from numbers import Number

import numpy as np
import pandas as pd
import pytest

from aerophoto import tasks
from aerophoto.tasks.base import Withheld
from aerophoto.variants import variant_for_index

VARIANTS = (0, 41, 86)
#: answers that are identifiers: a point's id is one of the block's ids by definition (the task is to find which)
IDENTIFIERS = {("task-15-2", "blunder_point"), ("task-15-2", "bad_control")}
_METHODS = ("table", "summary", "parameters", "to_frame")
_MAX_ARRAY = 200_000


def _is_method_to_call(name: str) -> bool:
    return name in _METHODS or name.endswith("_table")


def numbers_in(obj, depth: int = 0, seen=None) -> list[float]:
    """Every number reachable in ``obj`` (see the module notes)."""
    seen = set() if seen is None else seen
    if depth > 4 or id(obj) in seen:
        return []
    if isinstance(obj, (bool, np.bool_)) or obj is None or isinstance(obj, (str, bytes)):
        return []
    if isinstance(obj, Number) or isinstance(obj, np.generic):
        try:
            x = float(obj)
        except (TypeError, ValueError):
            return []
        return [x] if math.isfinite(x) else []
    seen.add(id(obj))
    if isinstance(obj, pd.DataFrame):
        out = []
        for col in obj.columns:
            out += numbers_in(list(obj[col]), depth + 1, seen)
        return out + numbers_in(list(obj.index), depth + 1, seen)
    if isinstance(obj, pd.Series):
        return numbers_in(list(obj), depth + 1, seen) + numbers_in(list(obj.index), depth + 1, seen)
    if isinstance(obj, np.ndarray):
        if obj.dtype.kind in "fiu" and obj.size <= _MAX_ARRAY:
            a = obj.astype(float).ravel()
            return [float(x) for x in a[np.isfinite(a)]]
        return []
    if isinstance(obj, dict):
        out = []
        for k, val in obj.items():
            out += numbers_in(k, depth + 1, seen) + numbers_in(val, depth + 1, seen)
        return out
    if isinstance(obj, (list, tuple, set, frozenset)):
        out = []
        for e in list(obj)[:_MAX_ARRAY]:
            out += numbers_in(e, depth + 1, seen)
        return out
    if type(obj).__module__.split(".")[0] not in ("aerophoto",) and not isinstance(obj, Withheld):
        return []
    out = []
    names = [f.name for f in dataclasses.fields(obj)] if dataclasses.is_dataclass(obj) else []
    names += [n for n in dir(obj) if not n.startswith("_")]
    for name in dict.fromkeys(names):
        if name.startswith("_"):
            continue
        try:
            val = getattr(obj, name)
        except Exception:  # a withheld attribute, or a property that needs more than the object
            continue
        if callable(val) and not isinstance(val, (np.ndarray, pd.DataFrame)):
            if not _is_method_to_call(name):
                continue
            try:
                val = val()
            except Exception:
                continue
        out += numbers_in(val, depth + 1, seen)
    return out


def graded_numbers(task, v) -> dict:
    """name → the distinctive numbers among the task's graded answers (not 0, ±1 or tiny whole numbers)."""
    out = {}
    for a in task.spec:
        if a.kind in ("bool", "choice"):
            continue
        x = task.answers(v)[a.name]
        vals = [float(e) for e in np.ravel(np.asarray(x, dtype=float))]
        keep = [e for e in vals if math.isfinite(e) and not (e.is_integer() and abs(e) < 10)]
        if keep:
            out[a.name] = keep
    return out


def _found(value: float, pool: np.ndarray) -> bool:
    if value.is_integer():
        return bool(np.any(pool == value))
    return bool(np.any(np.isclose(pool, value, rtol=1e-9, atol=0.0)))


@pytest.mark.parametrize("task_id", [t.id for t in tasks.all_tasks()])
def test_the_inputs_carry_no_graded_answer(task_id):
    task = tasks.get(task_id)
    found = []
    for i in VARIANTS:
        v = variant_for_index(i)
        pool = np.array(numbers_in(tasks.inputs(task_id, v)), dtype=float)
        if pool.size == 0:
            continue
        for name, values in graded_numbers(task, v).items():
            if (task_id, name) in IDENTIFIERS:
                continue
            hits = [x for x in values if _found(x, pool)]
            if hits:
                found.append((i, name, hits[:3]))
    assert not found, f"{task_id}: graded answers in its inputs: {found}"


def test_chapter_15s_block_hides_its_blunders_and_its_unknowns():
    v = variant_for_index(57)
    block = tasks.inputs("task-15-2", v)
    for name in ("bad_control", "blunder_point", "blunder_obs", "blunder_photo"):
        with pytest.raises(AttributeError, match="not given"):
            getattr(block, name)
    assert "unknowns" not in block.meas.summary() and "redundancy" not in block.meas.summary()
    with pytest.raises(AttributeError, match="15.1"):
        block.meas.n_unknowns
    # the measurements still adjust: the task's own tools run on them and find what the reference finds
    from aerophoto import bundle

    stages = bundle.three_stage(block.meas)
    rejected = bundle.data_snooping(block.meas, stages.eo0, stages.xyz0_m).rejected
    a = tasks.answers("task-15-2", v)
    assert int(rejected[rejected["kind"] == "image"]["point"].iloc[0]) == a["blunder_point"]
    assert int(rejected[rejected["kind"] == "control"]["point"].iloc[0]) == a["bad_control"]
    assert tasks.inputs("task-15-3", v)["block"].meas.n_photos == 18
