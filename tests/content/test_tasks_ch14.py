"""The graded tasks of chapter 14 (aerophoto.tasks.ch14): references pass, every variant works, the worked example;
and the tests that hold chapters 14 and 15 together (their registry, named slips, hidden checks)."""

import math

import pytest

from aerophoto import accuracy as acc
from aerophoto import checks, tasks
from aerophoto.labs import ch15 as lab15
from aerophoto.tasks import ch14, ch15
from aerophoto.variants import variant_for_index

from .conftest import _grade

VARIANTS = [variant_for_index(i) for i in (0, 1, 17, 58, 99)]
IDS = ("task-14-1", "task-14-2")


def test_the_chapters_register_their_tasks():
    assert [t.id for t in tasks.chapter_tasks("14")] == ["task-14-1", "task-14-2"]
    assert [t.id for t in tasks.chapter_tasks("15")] == ["task-15-1", "task-15-2", "task-15-3"]
    assert tasks.get("task-14-1").names == ("mD_mm", "mZ_m", "n_plan", "n_height")
    assert tasks.get("task-15-2").names == ("blunder_point", "bad_control", "rms_plan_m", "rms_Z_m")


def test_task_14_1_example_inputs_and_answers():
    v = VARIANTS[0]
    s = tasks.inputs("task-14-1", v)
    assert (s.m, s.M, s.f_mm, s.b_mm, s.mq_mm, s.contour_m) == (12000, 10000, 100, 72, 0.01, 1.0)
    a = tasks.answers("task-14-1", v)
    assert a["mD_mm"] == pytest.approx(math.hypot(0.25, 0.16) * 0.01 * 1000**0.5)  # the plan error (legend)
    assert a["mZ_m"] == pytest.approx(0.25 * 0.01 * 100 / 72 * 1000**0.5 * 12)
    assert a["n_plan"] == 19 and a["n_height"] == 2  # 19.2 (the other reading, m_D = √2·m_X: 17.2)
    assert tasks.answers("task-14-1", variant_for_index(71))["n_plan"] == 8  # 8.88 (other reading: 7.96 → 7)


def test_task_14_1_accepts_the_other_reading_of_m_D_with_its_own_spacing():
    v = VARIANTS[0]
    other = 0.35 * 0.01 * 1000**0.5
    g = _grade("task-14-1", v, mD_mm=other, n_plan=17)
    assert g.passed and "other reading" in g.lines[0]
    g = _grade("task-14-1", v, mD_mm=other)      # the other reading's m_D with the adopted reading's spacing
    assert g.visible_ok and not g.hidden_ok and "n_plan follows from mD_mm" in g.first_failure


#: a spread of variants (every variant's grading: the exhaustive sweep, test_grading_sweep.py)
SAMPLE = (0, 9, 18, 27, 36, 45, 54, 63, 72, 81, 90, 99)


@pytest.mark.parametrize("which", [pytest.param(SAMPLE, id="sample")])
def test_every_variant_works_for_chapter_14(which):
    seen = set()
    for i in which:
        v = variant_for_index(i)
        a = tasks.answers("task-14-1", v)
        assert a["n_plan"] >= 1 and a["n_height"] >= 0 and a["mD_mm"] > 0
        b = ch14.AccumulationLaw().answers(v)
        assert 0.7 * ch14.survey_inputs(v).mq_mm < b["d_mm"] < 1.8 * ch14.survey_inputs(v).mq_mm
        assert 2.5 < b["gain"] < 7.0
        seen.add(a["n_height"])
    assert 0 in seen  # the long lenses of large i: heights from a strip need control at every base or more


def test_slips_are_named():
    v = VARIANTS[1]
    a = tasks.answers("task-14-1", v)
    s = ch14.survey_inputs(v)
    with pytest.raises(checks.WrongAnswer, match="√n³"):
        checks.check_task("task-14-1", v, **{**a, "mD_mm": math.hypot(0.25, 0.16) * s.mq_mm * 10**0.5})
    with pytest.raises(checks.WrongAnswer, match="metres on the ground"):
        checks.check_task("task-14-1", v, **{**a, "mZ_m": acc.strip_errors_mm(10, s.mq_mm, f_mm=s.f_mm,
                                                                             b_mm=s.b_mm)["Z"]})
    b = tasks.answers("task-14-2", v)
    with pytest.raises(checks.WrongAnswer, match="not as n"):
        checks.check_task("task-14-2", v, **{**b, "m20_mm": b["d_mm"] * 20})
    c = tasks.answers("task-15-1", v)
    m = lab15.student_block(v).meas
    with pytest.raises(checks.WrongAnswer, match="tie points are unknowns"):
        checks.check_task("task-15-1", v, **{**c, "n_unknowns": 6 * m.n_photos})
    d = tasks.answers("task-15-3", v)
    fp = ch15.solve_block(lab15.student_block(v)).field_point(ch15.field_point_id(v))
    with pytest.raises(checks.WrongAnswer, match="semi-minor"):
        checks.check_task("task-15-3", v, **{**d, "a_m": fp["b_m"]})
    e = tasks.answers("task-15-2", v)
    slip = ch15.FindBlunders().slips(v)["rms_Z_m"]
    hint = next(h for h in slip if "blunders still in" in h)
    if abs(slip[hint] - e["rms_Z_m"]) > 0.05 * e["rms_Z_m"]:
        with pytest.raises(checks.WrongAnswer, match="blunders still in"):
            checks.check_task("task-15-2", v, **{**e, "rms_Z_m": slip[hint]})


def test_hidden_checks_catch_inconsistent_answers():
    v = VARIANTS[2]
    a = tasks.answers("task-14-1", v)
    g = _grade("task-14-1", v, n_plan=a["n_plan"] + 3)
    assert not g.hidden_ok
    b = tasks.answers("task-14-2", v)
    g = _grade("task-14-2", v, m20_mm=b["m20_mm"] * 1.03)  # visible tolerance is 1 %: fails both
    assert not g.passed
    g = _grade("task-15-1", v, fits_1986=not tasks.answers("task-15-1", v)["fits_1986"])
    assert not g.hidden_ok
    c = tasks.answers("task-15-3", v)
    g = _grade("task-15-3", v, X_m=c["X_m"] + 40.0)
    assert not g.passed and not g.hidden_ok
