"""The graded tasks of chapter 09 (aerophoto.tasks.ch09, labs.ch09): every variant works, references pass, slips are
named, hidden checks catch answers that pass the visible checks but do not hold together; and the tests that hold
chapters 09, 10 and 11 together (their registry, the printed verdicts, the worked examples)."""

import math

import numpy as np

from aerophoto import checks, tasks
from aerophoto.labs import ch09, ch10, ch11
from aerophoto.variants import variant_for_index

from .conftest import ALL, _grade, _raises

IDS = ("task-09-1", "task-09-2")
IDS_09_11 = IDS + ("task-10-1", "task-10-2", "task-11-1", "task-11-2")  # the tests of chapters 09–11 together
SOME = [variant_for_index(i) for i in (0, 1, 4, 17, 57, 99)]


def test_the_chapters_register_their_tasks():
    assert [t.id for t in tasks.chapter_tasks("09")] == ["task-09-1", "task-09-2"]
    assert [t.id for t in tasks.chapter_tasks("10")] == ["task-10-1", "task-10-2"]
    assert [t.id for t in tasks.chapter_tasks("11")] == ["task-11-1", "task-11-2"]
    assert tasks.get("task-09-1").names == ("row", "col", "x_mm", "y_mm")
    assert tasks.get("task-10-2").names == ("gamma_calc_deg", "dgamma_arcsec", "tol_arcsec", "check_ok")
    assert tasks.get("task-11-1").names == ("K_d", "t_mm")


def test_check_task_prints_the_verdict(capsys):
    v = SOME[0]
    for task_id in IDS_09_11:
        checks.check_task(task_id, v, **tasks.answers(task_id, v))
    out = capsys.readouterr().out
    for n in ("09.1", "09.2", "10.1", "10.2", "11.1", "11.2"):
        assert f"Task {n} passed" in out


def test_09_the_lab_is_the_students_own():
    a, b = ch09.plan_correction_lab(SOME[0]), ch09.plan_correction_lab(SOME[1])
    assert not a.control_table().equals(b.control_table())
    t = a.control_table()
    assert list(t.index) == ["1", "2", "3", "4"]
    assert np.all(np.round(t[["x photo, mm", "y photo, mm"]].to_numpy(), 2) == t[["x photo, mm", "y photo, mm"]])
    # the changes on the photo carried by the exact map land on the truth within the 0.01 mm rounding, × m/M
    p = a.photo_of("new road")
    assert np.max(np.hypot(*(a.exact.apply(p) - a.truth_plan_of("new road")).T)) < 0.05


def test_09_slips_are_named():
    v = SOME[1]
    lab = ch09.plan_correction_lab(v)
    p = lab.photo_of("farm building 1")[:1]
    prop = lab.grid_pair(4, "proportional").transfer(p)[0]
    _raises("task-09-1", v, "proportional division", x_mm=float(prop[0]), y_mm=float(prop[1]))
    a = tasks.answers("task-09-2", v)
    _raises("task-09-2", v, "multiply by M/1000", road_m=a["road_m"] * 1000 / lab.M)
    q = np.column_stack([a["xr_mm"], a["yr_mm"]])
    _raises("task-09-2", v, "add up its segments", road_m=float(np.hypot(*(q[-1] - q[0]))) * lab.M / 1000)


def test_09_hidden_checks_tie_the_answers_together():
    v = SOME[2]
    a = tasks.answers("task-09-1", v)
    # a point in the right place but the wrong cell named: visible checks fail on row; the hidden ones too
    g = _grade("task-09-1", v, row=(a["row"] + 1) % 4)
    assert not g.hidden_ok
    # road length within the visible 0.2 % but not the sum of the submitted vertices
    b = tasks.answers("task-09-2", v)
    g = _grade("task-09-2", v, road_m=b["road_m"] * 1.0018)
    assert g.visible_ok and not g.hidden_ok
    assert "road_m from your own vertices" in g.first_failure


def test_the_examples_are_no_variants():
    # the chapters' worked examples use the guide's numbers, which no variant has
    ex = ch11.example_rectification_lab()
    assert ex.camera.f_mm == 108.0 and ex.M == 5000.0
    assert all(v.f_mm != 108.0 for v in ALL)
    assert ch09.EXAMPLE_SEED not in range(100)
    assert math.isclose(ch10.PLAN_M, 10000.0)
