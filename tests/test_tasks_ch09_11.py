"""The graded tasks of chapters 09, 10, 11 (aerophoto.tasks.ch09, ch10, ch11): every variant works, references
pass, slips are named, hidden checks catch answers that pass the visible checks but do not hold together."""

import math

import numpy as np
import pytest

from aerophoto import checks, tasks
from aerophoto.course import score
from aerophoto import control as c
from aerophoto import rectify as rf
from aerophoto.labs import ch09, ch10, ch11
from aerophoto.variants import variant_for_index

IDS = ("task-09-1", "task-09-2", "task-10-1", "task-10-2", "task-11-1", "task-11-2")
ALL = [variant_for_index(i) for i in range(100)]
SOME = [variant_for_index(i) for i in (0, 1, 4, 17, 57, 99)]


def test_the_chapters_register_their_tasks():
    assert [t.id for t in tasks.chapter_tasks("09")] == ["task-09-1", "task-09-2"]
    assert [t.id for t in tasks.chapter_tasks("10")] == ["task-10-1", "task-10-2"]
    assert [t.id for t in tasks.chapter_tasks("11")] == ["task-11-1", "task-11-2"]
    assert tasks.get("task-09-1").names == ("row", "col", "x_mm", "y_mm")
    assert tasks.get("task-10-2").names == ("gamma_calc_deg", "dgamma_arcsec", "tol_arcsec", "check_ok")
    assert tasks.get("task-11-1").names == ("K_d", "t_mm")


@pytest.mark.parametrize("task_id", IDS)
def test_every_variant_has_answers_that_earn_full_marks(task_id):
    for v in ALL:
        g = score.grade_task(task_id, v, tasks.answers(task_id, v))
        assert g.passed and g.score == g.points, (v.i, g.checks)
        assert any(hidden for *_, hidden in g.checks)


@pytest.mark.parametrize("task_id", IDS)
def test_unanswered_and_other_variants_answers_fail(task_id):
    v, w = SOME[1], SOME[3]
    assert score.grade_task(task_id, v, {}).score == 0.0
    g = score.grade_task(task_id, v, tasks.answers(task_id, w))
    assert not g.passed


def test_check_task_prints_the_verdict(capsys):
    v = SOME[0]
    for task_id in IDS:
        checks.check_task(task_id, v, **tasks.answers(task_id, v))
    out = capsys.readouterr().out
    for n in ("09.1", "09.2", "10.1", "10.2", "11.1", "11.2"):
        assert f"Task {n} passed" in out


def _raises(task_id, v, match, **changes):
    with pytest.raises(checks.WrongAnswer, match=match):
        checks.check_task(task_id, v, **{**tasks.answers(task_id, v), **changes})


def _grade(task_id, v, **changes):
    return score.grade_task(task_id, v, {**tasks.answers(task_id, v), **changes})


# --------------------------------------------------------------------------- chapter 09
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
    # road length within the visible 0.5 % but not the sum of the submitted vertices
    b = tasks.answers("task-09-2", v)
    g = _grade("task-09-2", v, road_m=b["road_m"] * 1.004)
    assert g.visible_ok and not g.hidden_ok
    assert "road_m from your own vertices" in g.first_failure


# --------------------------------------------------------------------------- chapter 10
def test_10_the_resection_lab():
    labs = [ch10.resection_lab(v) for v in ALL]
    assert len({lab.station_id for lab in labs}) > 30  # stations spread over the site
    for v, lab in zip(ALL, labs):
        assert lab.check.ok == (not ch10.blunder_variant(v.i))
        if not ch10.blunder_variant(v.i):
            # σ = 5″ angles, rounded to 1″: the station is within what the angle errors allow
            err = np.hypot(*(lab.resection.point - lab.true_station))
            assert err < 4 * ch10.SIGMA_ARCSEC * lab.resection.metres_per_arcsec + 0.02
        assert lab.resection.strength > 0.15
    t = labs[0].angles_table()
    assert list(t.index) == ["β₁", "β₂", "γ (check)"] and t["angle"].str.endswith("″").all()


def test_10_slips_are_named():
    v = SOME[0]
    lab = ch10.resection_lab(v)
    s = tasks.get("task-10-1").slips(v)
    hint = next(h for h in s["X_m"] if "swapped" in h)
    _raises("task-10-1", v, "swapped", X_m=s["X_m"][hint], Y_m=s["Y_m"][hint])
    ch = lab.check
    _raises("task-10-2", v, "sign", dgamma_arcsec=-ch.discrepancy_arcsec)
    _raises("task-10-2", v, "not to C", tol_arcsec=tasks.get("task-10-2").slips(v)["tol_arcsec"][
        "the tolerance uses the distance to the check point D, not to C"])


def test_10_hidden_checks_tie_the_answers_together():
    v = SOME[1]
    a = tasks.answers("task-10-1", v)
    # the direction angle from a station 4 cm off, within the visible 0.05 m: consistent — passes
    lab = ch10.resection_lab(v)
    X, Y = a["X_m"] + 0.04, a["Y_m"]
    g = _grade("task-10-1", v, X_m=X, alpha_PA_deg=c.direction_angle_deg([X, Y], lab.point("A")))
    assert g.passed
    # an angle within its visible tolerance that does not follow from the submitted station
    g = _grade("task-10-1", v, X_m=X, alpha_PA_deg=(a["alpha_PA_deg"] - 0.0019) % 360)
    assert g.visible_ok is False or not g.hidden_ok
    b = tasks.answers("task-10-2", v)
    g = _grade("task-10-2", v, dgamma_arcsec=b["dgamma_arcsec"] + 3.0)
    assert g.visible_ok and not g.hidden_ok and "gamma_calc_deg" in g.first_failure
    w = next(x for x in ALL if ch10.blunder_variant(x.i))
    bw = tasks.answers("task-10-2", w)
    assert bw["check_ok"] is False
    g = _grade("task-10-2", w, check_ok=True)
    assert not g.passed


# --------------------------------------------------------------------------- chapter 11
def test_11_the_paper_lab():
    signs = {np.sign(ch11.paper_lab(v).deformation.K_d) for v in ALL}
    assert signs == {-1.0, 1.0}  # some papers shrink, some stretch
    lab = ch11.paper_lab(SOME[0])
    assert lab.table().shape == (6, 3)
    a = tasks.answers("task-11-1", SOME[0])
    assert a["t_mm"] == pytest.approx(a["K_d"] * SOME[0].f_mm * (SOME[0].m / 10000 + 1))


def test_11_slips_are_named():
    v = SOME[1]
    a = tasks.answers("task-11-1", v)
    _raises("task-11-1", v, "sign", K_d=-a["K_d"], t_mm=-a["t_mm"])
    _raises("task-11-1", v, "sign", t_mm=-a["t_mm"])
    _raises("task-11-1", v, "K_t \\+ 1", t_mm=a["K_d"] * v.f_mm * v.m / 10000)
    lab = ch11.rectification_lab(v)
    d = lab.rectification.check_lengths_mm
    _raises("task-11-2", v, "photo mm", d1_mm=float(d[0]) / (v.m / 10000))


def test_11_hidden_checks_tie_the_answers_together():
    v = SOME[2]
    a = tasks.answers("task-11-1", v)
    g = _grade("task-11-1", v, t_mm=a["t_mm"] * 1.004)
    assert g.visible_ok and not g.hidden_ok
    b = tasks.answers("task-11-2", v)
    g = _grade("task-11-2", v, rect_ok=not b["rect_ok"])
    assert not g.passed


def test_11_the_residuals_are_relief_displacement():
    # the same photos over the flat site: the residuals shrink to the pricking error's share
    v = SOME[0]
    lab = ch11.rectification_lab(v)
    flat = ch11.rectification_lab_for(lab.camera, lab.pose, lab.M, site=__import__(
        "aerophoto.site", fromlist=["get_site"]).get_site(relief_m=0), seed=0, sigma_mm=0.0)
    assert flat.rectification.check_lengths_mm.max() < 0.02
    assert lab.rectification.check_lengths_mm.max() > 0.05
    assert rf.TOLERANCE_MM == 0.4


def test_the_examples_are_no_variants():
    # the chapters' worked examples use the guide's numbers, which no variant has
    ex = ch11.example_rectification_lab()
    assert ex.camera.f_mm == 108.0 and ex.M == 5000.0
    assert all(v.f_mm != 108.0 for v in ALL)
    assert ch09.EXAMPLE_SEED not in range(100)
    assert math.isclose(ch10.PLAN_M, 10000.0)
