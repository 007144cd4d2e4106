"""The graded tasks of chapters 06 and 12 (aerophoto.tasks.ch06, ch12): references pass, slips are named,
hidden checks catch answers that pass the visible checks but do not hold together."""

import math

import numpy as np
import pytest

from aerophoto import checks, tasks
from aerophoto import triangulation as T
from aerophoto.tasks import ch06, ch12
from aerophoto.variants import variant_for_index

VARIANTS = [variant_for_index(i) for i in (0, 1, 2, 17, 57, 99)]
IDS = ("task-06-1", "task-06-2", "task-12-1", "task-12-2")


def test_the_chapters_register_their_tasks():
    assert [t.id for t in tasks.chapter_tasks("06")] == ["task-06-1", "task-06-2"]
    assert [t.id for t in tasks.chapter_tasks("12")] == ["task-12-1", "task-12-2"]
    assert [t.points for t in (tasks.get(i) for i in IDS)] == [4, 3, 3, 3]
    assert tasks.get("task-06-1").names == ("k_bases", "k_mean")
    assert tasks.get("task-12-2").names == ("dk_max", "spread_ok")


@pytest.mark.parametrize("task_id", IDS)
@pytest.mark.parametrize("v", VARIANTS, ids=lambda v: f"v{v.i:02d}")
def test_reference_answers_earn_full_marks(task_id, v):
    g = checks.grade_task(task_id, v, tasks.answers(task_id, v))
    assert g.passed and g.score == g.points, g.checks
    assert any(hidden for *_, hidden in g.checks)  # every task has a hidden check


@pytest.mark.parametrize("task_id", IDS)
def test_unanswered_and_other_variant_answers_fail(task_id):
    v, w = VARIANTS[1], VARIANTS[3]
    assert checks.grade_task(task_id, v, {}).score == 0.0
    g = checks.grade_task(task_id, v, tasks.answers(task_id, w))
    if task_id == "task-12-2":  # a verdict may coincide; the deviation may not
        assert not g.passed or tasks.answers(task_id, v)["dk_max"] == pytest.approx(
            tasks.answers(task_id, w)["dk_max"], abs=0.0005)
    else:
        assert not g.passed and g.score == 0.0


def test_the_lab_strip_tables_are_what_the_answers_use():
    v = VARIANTS[2]
    lab = tasks.inputs("task-06-1", v)
    assert isinstance(lab, ch06.LabStrip) and lab.centre == "37" and lab.M == v.M
    t = lab.control_table()
    assert list(t.index) == ["36/1", "36/2", "39/1", "39/2"]
    assert lab.ring() == list(ch06.RING)
    # the reference k_bases from the rounded table by hand
    k = [math.hypot(*(t.loc[a, ["X, m", "Y, m"]] - t.loc[b, ["X, m", "Y, m"]])) * 1000 / v.M
         / math.hypot(*(t.loc[a, ["x strip, mm", "y strip, mm"]] - t.loc[b, ["x strip, mm", "y strip, mm"]]))
         for a, b in ch06.RING]
    np.testing.assert_allclose(tasks.answers("task-06-1", v)["k_bases"], k, rtol=1e-12)
    # the free strip's scale q = 0.90 + 0.002·i makes k ≈ 1/q
    assert tasks.answers("task-06-1", v)["k_mean"] == pytest.approx(1 / (0.90 + 0.002 * v.i), rel=0.01)
    assert tasks.inputs("task-12-2", v).control_table().equals(t)  # chapter 12 uses the same strip


def test_wrong_answers_get_the_slip_hint():
    v = VARIANTS[1]
    a = tasks.answers("task-06-1", v)
    with pytest.raises(checks.WrongAnswer, match="base over template"):
        checks.check_task("task-06-1", v, k_bases=a["k_bases"], k_mean=1 / a["k_mean"])
    with pytest.raises(checks.WrongAnswer, match="reverse order"):
        checks.check_task("task-06-1", v, k_bases=a["k_bases"][::-1], k_mean=a["k_mean"])
    kw = ch12.zhukov_inputs(v).zhukov_kwargs()
    n_max = tasks.answers("task-12-1", v)["n_max"]
    with pytest.raises(checks.WrongAnswer, match="as scanned"):
        checks.check_task("task-12-1", v, m3_mm=T.zhukov_error_mm(3, reading="n0", **kw), n_max=n_max)
    with pytest.raises(checks.WrongAnswer, match="k_i is the enlargement"):
        checks.check_task("task-12-1", v, m3_mm=T.zhukov_error_mm(3, **{**kw, "k_i": 1.0}), n_max=n_max)
    c = tasks.get("task-12-2").inputs(v).coefficients("all")
    with pytest.raises(checks.WrongAnswer, match="max k − min k"):
        checks.check_task("task-12-2", v, dk_max=c.k_range, spread_ok=c.all_ok)
    with pytest.raises(checks.WrongAnswer, match="spread_ok"):
        checks.check_task("task-12-2", v, dk_max=c.spread, spread_ok=not c.all_ok)


def test_check_task_passes_the_reference_and_prints_the_verdict(capsys):
    v = VARIANTS[0]
    for task_id in IDS:
        checks.check_task(task_id, v, **tasks.answers(task_id, v))
    out = capsys.readouterr().out
    for n in ("06.1", "06.2", "12.1", "12.2"):
        assert f"Task {n} passed" in out


def _grade(task_id, v, **changes):
    return checks.grade_task(task_id, v, {**tasks.answers(task_id, v), **changes})


def test_hidden_06_1_k_mean_must_be_the_mean_of_k_bases():
    v = VARIANTS[1]
    a = tasks.answers("task-06-1", v)
    g = _grade("task-06-1", v, k_mean=a["k_mean"] + 0.0003)  # within the visible 0.0005, not the mean
    assert g.visible_ok and not g.hidden_ok and g.score == 0.0
    assert "k_mean is the mean of k_bases" in g.first_failure
    # every coefficient nudged by the same 0.0003 and the mean with them: consistent, and within tolerance
    g = _grade("task-06-1", v, k_bases=[k + 0.0003 for k in a["k_bases"]], k_mean=a["k_mean"] + 0.0003)
    assert g.passed


def test_hidden_06_2_corrections_must_be_proportional_to_r():
    v = VARIANTS[1]
    a = tasks.answers("task-06-2", v)["v_mm"]
    lab = ch06.lab_strip(v)
    r = lab.corrections(ch06.CORRECTION_POINTS, k=2.0)
    near = int(np.argmin(r))  # the point nearest 37: 0.08 mm there is a large change of v/r
    bad = list(a)
    bad[near] += 0.08
    g = _grade("task-06-2", v, v_mm=bad)
    assert g.visible_ok and not g.hidden_ok
    assert f"v_mm / r at {ch06.CORRECTION_POINTS[near]}" in g.first_failure
    # with the wrong k for every point (the mean of all six bases instead of the ring's) v/r is off for all
    k6 = lab.coefficients("all").k_mean
    k4 = lab.coefficients("ring").k_mean
    if abs(k6 - k4) > 0.0012:
        assert not _grade("task-06-2", v, v_mm=list(r * (k6 - 1))).hidden_ok


def test_hidden_12_1_n_max_follows_from_m3():
    for v in VARIANTS:
        task = tasks.get("task-12-1")
        a = task.answers(v)
        (h,) = task.hidden(v, a)
        assert h.answer == h.expected == a["n_max"]
        # a pair that does not hold together: n_max one more than m(3) allows
        (h,) = task.hidden(v, {**a, "n_max": a["n_max"] + 1})
        assert h.expected == a["n_max"] != h.answer
    (h,) = tasks.get("task-12-1").hidden(VARIANTS[0], {"m3_mm": ..., "n_max": 5})
    assert h.answer is None


def test_hidden_12_1_accepts_both_whole_numbers_at_a_boundary():
    # m(3) such that m(n = 6) is 0.2 % above 0.35 mm: within the 0.5 % tolerance n = 5 and n = 6 are both consistent
    m3 = 0.35 * 1.002 * math.sqrt(T.zhukov_radicand(3) / T.zhukov_radicand(6))
    task = tasks.get("task-12-1")
    v = VARIANTS[0]
    for n in (5, 6):
        (h,) = task.hidden(v, {"m3_mm": m3, "n_max": n})
        assert h.answer == h.expected
    (h,) = task.hidden(v, {"m3_mm": m3, "n_max": 4})
    assert h.expected == 5


def test_hidden_12_2_verdict_must_agree_with_dk_max():
    task = tasks.get("task-12-2")
    v = VARIANTS[1]
    (h,) = task.hidden(v, {"dk_max": 0.001, "spread_ok": False})
    assert h.expected is True and h.answer is False
    (h,) = task.hidden(v, {"dk_max": 0.009, "spread_ok": True})
    assert h.expected is False
    (h,) = task.hidden(v, {"dk_max": "a lot", "spread_ok": True})
    assert h.answer is None


def test_m_eps_is_defined_once_and_shown_in_the_inputs():
    assert [ch12.m_eps_arcmin(variant_for_index(i)) for i in range(6)] == [4.0, 4.5, 5.0, 4.0, 4.5, 5.0]
    given = tasks.inputs("task-12-1", VARIANTS[0])
    assert str(given) == "variant i = 0: m = 1:12000, M = 1:10000, p_x = 60 %, frame 180 mm, m_ε = 4′"
    assert given.k_i == pytest.approx(1.2) and given.b_mm == pytest.approx(72.0)
    kw = given.zhukov_kwargs()
    assert tasks.answers("task-12-1", VARIANTS[0]) == {"m3_mm": T.zhukov_error_mm(3, **kw),
                                                       "n_max": T.zhukov_max_bases(0.35, **kw)}


def test_the_tasks_are_seeded_by_the_variant():
    a = [tasks.answers("task-06-1", v)["k_mean"] for v in VARIANTS]
    assert len(set(a)) == len(a)  # every variant its own strip
    assert tasks.answers("task-06-2", VARIANTS[2]) == tasks.answers("task-06-2", VARIANTS[2])  # and the same every time
