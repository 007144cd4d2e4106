"""The graded tasks of chapters 03 and 04 (aerophoto.tasks.ch03, ch04): answers, grading, hidden checks."""

import math

import numpy as np
import pytest

from aerophoto import checks, tasks
from aerophoto.guide import s05
from aerophoto.tasks import ch03, ch04
from aerophoto.variants import variant_for_index

IDS = ("task-03-1", "task-03-2", "task-04-1", "task-04-2", "task-04-3")

#: the answers of variant 00 (the guide's example: f = 100 mm, 1:12000, α = 3°, λ = −60°), as the chapter's
#: checks computed them before the tasks moved to aerophoto.tasks
VARIANT_00 = {
    "task-03-1": {"Zcp_m": 160.125, "H_m": 1200.0},
    "task-03-2": {"r1_mm": 73.94529072772127, "dh1_mm": -1.3633662977923608, "n_corr": 6},
    "task-04-1": {"oc_mm": -2.618592156918693, "xc_mm": -1.30929608, "yc_mm": 2.26776733},
    "task-04-2": {"rcA_mm": 73.37023576198902, "phiA_deg": 46.387678871349486, "dA_mm": -1.9433346954394755},
    "task-04-3": {"dI_mm": -2.3318492945473595, "n_corr": 7},
}
#: and of variant 57 (f = 670 mm, 1:17700, λ = −3°)
VARIANT_57 = {
    "task-03-1": {"Zcp_m": 217.125, "H_m": 11859.0},
    "task-03-2": {"r1_mm": 48.16832073528778, "dh1_mm": -0.08986627002852199, "n_corr": 1},
    "task-04-1": {"oc_mm": -17.544567451355245, "xc_mm": -17.52052323, "yc_mm": 0.91821171},
    "task-04-2": {"rcA_mm": 88.95634575951632, "phiA_deg": 352.6917383288912, "dA_mm": -0.613107543623736},
    "task-04-3": {"dI_mm": -0.34803720814139694, "n_corr": 2},
}


def test_the_chapters_tasks_are_registered_in_order():
    assert [t.id for t in tasks.chapter_tasks("03")] == ["task-03-1", "task-03-2"]
    assert [t.id for t in tasks.chapter_tasks("04")] == ["task-04-1", "task-04-2", "task-04-3"]
    assert [t.points for t in map(tasks.get, IDS)] == [2, 4, 3, 4, 3]  # as the notebooks' check cells score them


@pytest.mark.parametrize("i, expected", [(0, VARIANT_00), (57, VARIANT_57)])
@pytest.mark.parametrize("task_id", IDS)
def test_answers_are_the_values_the_old_checks_expected(task_id, i, expected):
    got = tasks.answers(task_id, variant_for_index(i))
    assert set(got) == set(tasks.get(task_id).names)
    for name, value in expected[task_id].items():
        assert got[name] == pytest.approx(value, abs=1e-7), name


@pytest.mark.parametrize("i", [0, 23, 57, 99])
@pytest.mark.parametrize("task_id", IDS)
def test_the_reference_answers_get_full_marks_and_a_wrong_one_none(task_id, i):
    v = variant_for_index(i)
    task = tasks.get(task_id)
    right = task.answers(v)
    g = checks.grade_task(task_id, v, right)
    assert g.passed and g.score == g.points == task.points, g.checks
    assert any(hidden for *_, hidden in g.checks)  # every task has a hidden check
    first = task.names[0]
    wrong = checks.grade_task(task_id, v, {**right, first: right[first] * 1.5 + 7.0})
    assert not wrong.visible_ok and wrong.score == 0.0 and first in wrong.first_failure
    unanswered = checks.grade_task(task_id, v, {})
    assert unanswered.score == 0.0 and "no answer yet" in unanswered.first_failure


@pytest.mark.parametrize("i", [0, 23])
def test_hidden_checks_catch_inconsistent_answers(i):
    v = variant_for_index(i)

    def hidden_failed(task_id, **changed):
        right = tasks.answers(task_id, v)
        g = checks.grade_task(task_id, v, {**right, **changed})
        return [name for name, ok, _, hidden in g.checks if hidden and not ok]

    # 03.1: a mean plane far from between the zones
    zcp = tasks.answers("task-03-1", v)["Zcp_m"]
    assert hidden_failed("task-03-1", Zcp_m=zcp + 3.0) == ["Zcp_m (between the zones)"]
    # 03.2: δh that does not follow from the student's own r (r from o, δh from n)
    lab = ch03.relief_lab(v)
    assert hidden_failed("task-03-2", r1_mm=lab.r_from_o_mm[1]) == ["dh1_mm (from your r1)"]
    # 04.1: c not at the distance |oc| from o
    assert hidden_failed("task-04-1", xc_mm=0.0, yc_mm=0.0) == ["|oc| from xc, yc"]
    # 04.2: δα that does not follow from the student's own r_c and φ
    tl = ch04.tilt_lab(v)
    assert hidden_failed("task-04-2", phiA_deg=tl.phi_from_x_deg) == ["dA_mm (from your r_c, φ)"]
    # 04.3: δα of I not in proportion to sin α/f
    assert hidden_failed("task-04-3", dI_mm=-2.0) == ["dI_mm (scales as sin α/f)"]
    # a non-number never passes a hidden check
    assert hidden_failed("task-03-2", r1_mm="seventy") == ["dh1_mm (from your r1)"]


def test_hidden_checks_hold_for_every_variant():
    for i in range(100):
        v = variant_for_index(i)
        for task_id in IDS:
            task = tasks.get(task_id)
            for h in task.hidden(v, task.answers(v)):
                assert checks._hidden_ok(h)[0], (task_id, i, h)


def test_the_check_cells_recognise_another_variant_and_the_slips(capsys):
    v, w = variant_for_index(3), variant_for_index(40)
    right = tasks.answers("task-04-1", v)
    with pytest.raises(checks.WrongAnswer, match="variant 40"):
        checks.check_task("task-04-1", v, **{**right, "oc_mm": tasks.answers("task-04-1", w)["oc_mm"]})
    with pytest.raises(checks.WrongAnswer, match="α/2"):
        checks.check_task("task-04-1", v, **{**right, "oc_mm": -v.f_mm * math.tan(math.radians(v.alpha_deg))})
    z = tasks.answers("task-03-1", v)
    with pytest.raises(checks.WrongAnswer, match="i metres"):
        checks.check_task("task-03-1", v, Zcp_m=z["Zcp_m"] - v.i, H_m=z["H_m"])
    checks.check_task("task-03-1", v, **z)
    assert "✓ Task 03.1 passed" in capsys.readouterr().out


def test_inputs():
    v = variant_for_index(12)
    pts = tasks.inputs("task-03-1", v)
    assert pts.names == ("I", "1", "2", "II", "3", "4")
    np.testing.assert_allclose(pts.Z_m, np.array([141, 138, 141, 180, 178, 182]) + 12)
    np.testing.assert_allclose(pts.xy_mm, [p[1:3] for p in ch03.RELIEF_LAB_POINTS])
    assert tasks.inputs("task-04-1", v) is None  # the variant itself
    assert tasks.inputs("task-04-2", v) == {"x_mm": 70.0, "y_mm": -15.0}
    t6 = tasks.inputs("task-04-3", v)
    assert list(t6.columns) == ["r_c, mm", "φ, °"] and list(t6.index) == list(s05.TABLE6["names"])
    np.testing.assert_allclose(t6["r_c, mm"], s05.TABLE6["r_c"])
    np.testing.assert_allclose(t6["φ, °"], s05.TABLE6["phi"])
