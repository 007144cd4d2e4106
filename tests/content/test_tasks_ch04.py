"""The graded tasks of chapter 04 (aerophoto.tasks.ch04): the guide's tables 5–7 on the student's photo: reference
answers for every variant, wrong or missing answers, malformed values in the hidden checks (the tests that hold
chapters 03 and 04 together are in test_tasks_ch03.py)."""

import math
from types import SimpleNamespace

import numpy as np
import pytest

from aerophoto import tasks
from aerophoto.course import score
from aerophoto.tasks import ch03, ch04
from aerophoto.variants import variant_for_index

from .conftest import _hidden_failed

IDS = ("task-04-1", "task-04-2", "task-04-3", "task-04-4")


@pytest.mark.parametrize("task_id", IDS)
def test_the_reference_answers_pass_for_every_variant(task_id):
    task = tasks.get(task_id)
    for i in range(100):
        v = variant_for_index(i)
        right = task.answers(v)
        assert set(right) == set(task.names)
        g = score.grade_task(task_id, v, right)
        assert g.passed and g.score == g.points == task.points, (i, g.checks)
        assert any(hidden for *_, hidden in g.checks)  # every task has a hidden check


@pytest.mark.parametrize("i", [0, 57])
@pytest.mark.parametrize("task_id", IDS)
def test_a_wrong_or_missing_answer_gets_nothing(task_id, i):
    v = variant_for_index(i)
    task = tasks.get(task_id)
    right = task.answers(v)
    first = task.names[0]
    value = right[first]
    bad = [x * 1.5 + 7.0 for x in value] if isinstance(value, list) else value * 1.5 + 7.0
    wrong = score.grade_task(task_id, v, {**right, first: bad})
    assert not wrong.visible_ok and wrong.score == 0.0 and first in wrong.first_failure
    unanswered = score.grade_task(task_id, v, {})
    assert unanswered.score == 0.0 and "no answer yet" in unanswered.first_failure


# --------------------------------------------------------------------------- hidden checks
def test_hidden_checks_reject_malformed_values():
    v = variant_for_index(5)
    right = tasks.answers("task-04-3", v)
    for bad in (None, ..., "x", [1.0] * 8, [math.nan] * 9):
        assert "δα from your r_c and φ" in _hidden_failed("task-04-3", v, {**right, "rc_mm": bad})
    assert ch03.numbers(np.array([1.0, 2.0]), 2).tolist() == [1.0, 2.0]
    assert ch03.numbers(SimpleNamespace(), 2) is None
    assert ch04.TOL_PHI_DEG == 1.0
