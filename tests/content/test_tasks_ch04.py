"""The graded tasks of chapter 04 (aerophoto.tasks.ch04): the guide's tables 5–7 on the student's photo: reference
answers for every variant, wrong or missing answers, malformed values in the hidden checks (the tests that hold
chapters 03 and 04 together are in test_tasks_ch03.py)."""

import math
from types import SimpleNamespace

import numpy as np

from aerophoto import tasks
from aerophoto.tasks import ch03, ch04
from aerophoto.variants import variant_for_index

from .conftest import _hidden_failed

IDS = ("task-04-1", "task-04-2", "task-04-3", "task-04-4")


# --------------------------------------------------------------------------- hidden checks
def test_hidden_checks_reject_malformed_values():
    v = variant_for_index(5)
    right = tasks.answers("task-04-3", v)
    for bad in (None, ..., "x", [1.0] * 8, [math.nan] * 9):
        assert "δα from your r_c and φ" in _hidden_failed("task-04-3", v, {**right, "rc_mm": bad})
    assert ch03.numbers(np.array([1.0, 2.0]), 2).tolist() == [1.0, 2.0]
    assert ch03.numbers(SimpleNamespace(), 2) is None
    assert ch04.TOL_PHI_DEG == 1.0
