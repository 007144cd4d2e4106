"""The graded tasks of chapter 12 (aerophoto.tasks.ch12): a student's own computation, Zhukov's m_ε defined once,
the hidden checks (the tests that hold chapters 06 and 12 together are in test_tasks_ch06.py)."""

import math

import pytest

from aerophoto import tasks
from aerophoto.course import score
from aerophoto import triangulation as T
from aerophoto.tasks import ch12
from aerophoto.variants import variant_for_index

from .conftest import _by_hand

VARIANTS = [variant_for_index(i) for i in (0, 1, 2, 17, 57, 99)]


@pytest.mark.parametrize("task_id", ["task-12-2", "task-12-3"])
def test_a_students_own_computation_passes(task_id):
    for v in VARIANTS:
        g = score.grade_task(task_id, v, _by_hand(task_id, v))
        assert g.passed, (v.i, g.checks)


def test_hidden_12_1_n_max_follows_from_m3():
    for v in VARIANTS:
        task = tasks.get("task-12-1")
        a = task.answers(v)
        (h,) = task.hidden(v, a)
        assert h.answer == h.expected == a["n_max"]
        (h,) = task.hidden(v, {**a, "n_max": a["n_max"] + 1})
        assert h.expected == a["n_max"] != h.answer
    (h,) = tasks.get("task-12-1").hidden(VARIANTS[0], {"m3_mm": ..., "n_max": 5})
    assert h.answer is None


def test_hidden_12_1_accepts_both_whole_numbers_at_a_boundary():
    m3 = 0.35 * 1.002 * math.sqrt(T.zhukov_radicand(3) / T.zhukov_radicand(6))
    task = tasks.get("task-12-1")
    v = VARIANTS[0]
    for n in (5, 6):
        (h,) = task.hidden(v, {"m3_mm": m3, "n_max": n})
        assert score.hidden_ok(h)[0], n
    (h,) = task.hidden(v, {"m3_mm": m3, "n_max": 4})
    assert h.expected == 5 and not score.hidden_ok(h)[0]


def test_hidden_12_2_mean_deviation_and_verdict_follow_from_the_students_k():
    task = tasks.get("task-12-2")
    v = VARIANTS[1]
    a = task.answers(v)
    hs = task.hidden(v, a)
    assert all(score.hidden_ok(h)[0] for h in hs)
    # a largest deviation that no rounding of the student's own k gives
    hs = task.hidden(v, {**a, "dk_max": a["dk_max"] + 0.003})
    assert not score.hidden_ok(hs[1])[0]
    flat = [a["k_mean"]] * 6
    hs = task.hidden(v, {"k_bases": flat, "k_mean": a["k_mean"], "dk_max": 0.0, "spread_ok": False})
    assert [score.hidden_ok(h)[0] for h in hs] == [True, True, False]
    hs = task.hidden(v, {"k_bases": "six", "k_mean": 1.0, "dk_max": 0.0, "spread_ok": True})
    assert all(h.answer is None for h in hs)


def test_m_eps_is_defined_once_and_shown_in_the_inputs():
    assert [ch12.m_eps_arcmin(variant_for_index(i)) for i in range(6)] == [4.0, 4.5, 5.0, 4.0, 4.5, 5.0]
    given = tasks.inputs("task-12-1", VARIANTS[0])
    assert str(given) == "variant i = 0: m = 1:12000, M = 1:10000, p_x = 60 %, frame 180 mm, m_ε = 4′"
    assert given.k_i == pytest.approx(1.2) and given.b_mm == pytest.approx(72.0)
    kw = given.zhukov_kwargs()
    assert tasks.answers("task-12-1", VARIANTS[0]) == {"m3_mm": T.zhukov_error_mm(3, **kw),
                                                       "n_max": T.zhukov_max_bases(0.35, **kw)}
