"""The graded tasks of chapter 03 (aerophoto.tasks.ch03): the guide's tables 2–4 on the student's photo; and the tests
that hold chapters 03 and 04 together (one lab of sheets, aerophoto.labs.displacement).

Reference answers pass for every variant; a careful student's readings (the truth with reading errors, rounded
to 0.1 mm) pass too, visible and hidden checks; typical mistakes are named; the hidden checks catch columns that
do not follow from the student's own readings.
"""

import math

import numpy as np
import pytest

from aerophoto import checks, tasks
from aerophoto.course import score
from aerophoto import displacement as d
from aerophoto.tasks import ch03
from aerophoto.labs.displacement import relief_sheet, tilt_sheet
from aerophoto.variants import variant_for_index

from .conftest import _hidden_failed

IDS = ("task-03-1", "task-03-2", "task-03-3")
IDS_03_04 = IDS + ("task-04-1", "task-04-2", "task-04-3", "task-04-4")  # the tests of chapters 03 and 04 together


def test_the_chapters_tasks_are_registered_in_order():
    assert [t.id for t in tasks.chapter_tasks("03")] == ["task-03-1", "task-03-2", "task-03-3"]
    assert [t.id for t in tasks.chapter_tasks("04")] == ["task-04-1", "task-04-2", "task-04-3", "task-04-4"]
    assert [t.points for t in map(tasks.get, IDS_03_04)] == [4, 4, 3, 2, 4, 4, 3]
    # every table task compares lists of the guide's columns; another variant's answers are not looked for
    for tid in IDS_03_04[:3] + IDS_03_04[4:]:
        t = tasks.get(tid)
        assert not t.cross_variant and any(a.kind == "values" for a in t.spec)


def test_the_answers_of_variant_00_are_the_guide_procedure_on_the_true_readings():
    v = variant_for_index(0)
    sheet = relief_sheet(0)
    w = d.relief_work(sheet.names, sheet.photo_xy_mm, sheet.l_plan_mm, sheet.Z_given_m, sheet.bases, f_mm=100.0,
                      n_mm=sheet.n_mm)
    a1, a2, a3 = (tasks.answers(t, v) for t in IDS[:3])
    np.testing.assert_allclose(a1["x_mm"], sheet.photo_xy_mm[:, 0])
    np.testing.assert_allclose(a1["lsn_mm"], d.base_lengths_mm(sheet.names, sheet.photo_xy_mm, sheet.bases))
    np.testing.assert_allclose(a1["m_i"], np.array(a1["lpl_mm"]) * 10000 / np.array(a1["lsn_mm"]))
    np.testing.assert_allclose(a1["m_part"], [np.mean(a1["m_i"][:2]), np.mean(a1["m_i"][2:])])
    assert a1["m_cp"] == pytest.approx(np.mean(a1["m_part"]))
    np.testing.assert_allclose(a1["dm_pct"], 100 * (np.array(a1["m_part"]) / a1["m_cp"] - 1))
    assert a2["H_m"] == pytest.approx(a1["m_cp"] * 0.1) == pytest.approx(w.H_m)
    on = 100 * math.tan(math.radians(3))
    np.testing.assert_allclose([a2["xn_mm"], a2["yn_mm"]], [-on * math.cos(math.radians(-60)),
                                                            -on * math.sin(math.radians(-60))])
    np.testing.assert_allclose(a2["dh_mm"], np.array(a2["r_mm"]) * (sheet.Z_given_m - a2["Zcp_m"]) / a2["H_m"])
    assert a2["n_corr"] == 6  # variant 00: all six points need a correction, as in the guide
    np.testing.assert_allclose(a3["m_i"], w.table4.m_i)
    # the correction brings the zones together: from about 1/150 to about 1/2000
    assert abs(a1["dm_pct"][0]) > 0.5 and abs(a3["dm_pct"][0]) < 0.1


# --------------------------------------------------------------------------- a careful student
def _readings(sheet, rng, sigma=0.04):
    """A student's readings of a sheet: the truth with clicking errors, read to 0.1 mm (photo and plan)."""
    xy = np.round(sheet.photo_xy_mm + rng.normal(0.0, sigma, sheet.photo_xy_mm.shape), 1)
    plan = np.round(sheet.plan_xy_mm + rng.normal(0.0, sigma, sheet.plan_xy_mm.shape), 1)
    return xy, d.base_lengths_mm(sheet.names, plan, sheet.bases)


def _scale_columns(t, lsn="lsn_mm"):
    return {lsn: [b.l_photo_mm for b in t.bases], "m_i": list(t.m_i), "m_part": list(t.m_part), "m_cp": t.m_mean,
            "dm_pct": list(100 * t.relative_dm)}


def student_answers(v, rng) -> dict:
    """Every answer of chapters 03–04 as a careful student computes them from their own readings."""
    rs, ts = relief_sheet(v.i), tilt_sheet(v.i)
    xy, lpl = _readings(rs, rng)
    w = rs.work(xy, lpl)
    out = {"task-03-1": {"x_mm": list(xy[:, 0]), "y_mm": list(xy[:, 1]), "lpl_mm": list(lpl),
                         **_scale_columns(w.table2)},
           "task-03-2": {"Zcp_m": w.Z_mean_m, "H_m": w.H_m, "xn_mm": w.n_mm[0], "yn_mm": w.n_mm[1],
                         "r_mm": list(w.table3.r_mm), "dh_mm": list(w.table3.delta_mm), "n_corr": w.table3.n_applied},
           "task-03-3": _scale_columns(w.table4, "lsn_corr_mm")}
    xy, lpl = _readings(ts, rng)
    w = ts.work(xy, lpl)
    out["task-04-1"] = tasks.answers("task-04-1", v)
    out["task-04-2"] = {"x_mm": list(xy[:, 0]), "y_mm": list(xy[:, 1]), "lpl_mm": list(lpl), **_scale_columns(w.table5)}
    out["task-04-3"] = {"rc_mm": list(w.table6.r_c_mm), "phi_deg": list(w.table6.phi_deg),
                        "da_mm": list(w.table6.delta_approx_mm), "n_corr": w.table6.n_applied}
    out["task-04-4"] = _scale_columns(w.table7, "lsn_corr_mm")
    return out


@pytest.mark.parametrize("i", [0, 9, 17, 18, 40, 57, 99])
def test_a_careful_students_own_readings_pass_every_task(i):
    v = variant_for_index(i)
    rng = np.random.default_rng(1000 + i)
    for _ in range(4):
        for task_id, got in student_answers(v, rng).items():
            g = score.grade_task(task_id, v, got)
            assert g.passed, (i, task_id, [c for c in g.checks if not c[1]])


def test_readings_beyond_the_tolerance_fail_visibly():
    v = variant_for_index(12)
    got = student_answers(v, np.random.default_rng(3))["task-03-1"]
    got["x_mm"] = [x + (0.3 if k == 2 else 0.0) for k, x in enumerate(got["x_mm"])]
    g = score.grade_task("task-03-1", v, got)
    assert not g.visible_ok and "x_mm" in g.first_failure and "2" in g.first_failure


# --------------------------------------------------------------------------- hidden checks
@pytest.mark.parametrize("i", [0, 30, 99])
def test_hidden_checks_catch_columns_that_do_not_follow_from_the_students_readings(i):
    v = variant_for_index(i)
    own = student_answers(v, np.random.default_rng(i))
    # 03.1: the nominal m copied into every scale column
    copied = {**own["task-03-1"], "m_i": [v.m] * 4, "m_part": [v.m] * 2, "m_cp": v.m, "dm_pct": [0.0, 0.0]}
    if max(abs(m / v.m - 1) for m in own["task-03-1"]["m_i"]) > 0.01:  # beyond what rounding l_сн to 0.1 mm allows
        assert "m_i from your l_пл and l_сн" in _hidden_failed("task-03-1", v, copied)
    # 03.1: readings changed afterwards (point 1 moved 0.5 mm along base I-1) but l_сн left as it was
    t2 = own["task-03-1"]
    x, y = np.array(t2["x_mm"]), np.array(t2["y_mm"])
    u = np.array([x[1] - x[0], y[1] - y[0]]) / t2["lsn_mm"][0]
    moved = {**t2, "x_mm": list(x + [0, 0.5 * u[0], 0, 0, 0, 0]), "y_mm": list(y + [0, 0.5 * u[1], 0, 0, 0, 0])}
    assert _hidden_failed("task-03-1", v, moved) == ["l_сн from your x, y"]
    # 03.1: Δm with the guide's printed sign (m_cp − m_част)
    flipped = {**own["task-03-1"], "dm_pct": [-x for x in own["task-03-1"]["dm_pct"]]}
    if 2 * max(abs(x) for x in own["task-03-1"]["dm_pct"]) > 0.15:  # beyond what rounding m_част, m_cp allows
        assert _hidden_failed("task-03-1", v, flipped) == ["Δm/m_cp from your m_част and m_cp"]
    # 03.2: δh computed with the nominal H = f·m while H_m says m_cp·f
    t3 = own["task-03-2"]
    nominal = np.array(t3["r_mm"]) * (relief_sheet(i).Z_given_m - t3["Zcp_m"]) / (v.f_mm / 1000 * v.m)
    if np.max(np.abs(nominal - t3["dh_mm"])) > 0.015:
        assert _hidden_failed("task-03-2", v, {**t3, "dh_mm": list(nominal)}) == ["δh from your r, H and Z_cp"]
    # 03.2: a count that does not follow from the student's own δh
    assert _hidden_failed("task-03-2", v, {**t3, "n_corr": 7})[-1:] == ["n_corr from your δh"]  # of six points
    # 03.3 and 04.4: a partial scale that is not the mean of the zone's m_i
    t4 = own["task-03-3"]
    assert "m_част from your m_i" in _hidden_failed("task-03-3", v, {**t4, "m_part": [t4["m_part"][0] * 1.005,
                                                                                        t4["m_part"][1]]})
    t7 = own["task-04-4"]
    scaled = {**t7, "m_i": [m * 1.004 for m in t7["m_i"]]}  # m_i that do not give the plan lengths back
    if max(abs(m * l / 10000 * 0.004) for m, l in zip(t7["m_i"], t7["lsn_corr_mm"])) > ch03.TOL_LEN_MM + 0.05:
        assert "m_i·l_сн/M gives the plan lengths" in _hidden_failed("task-04-4", v, scaled)
    # 04.3: δα computed with φ from the photo's x axis while phi_deg is right
    t6 = own["task-04-3"]
    wrong_phi = np.array(t6["phi_deg"]) + v.lambda_deg
    da = -np.array(t6["rc_mm"]) ** 2 * np.cos(np.radians(wrong_phi)) / v.f_mm * math.sin(math.radians(3))
    if np.max(np.abs(da - t6["da_mm"])) > 0.02:
        assert "δα from your r_c and φ" in _hidden_failed("task-04-3", v, {**t6, "da_mm": list(da)})
    # 04.1: c not at the distance |oc| from o
    assert _hidden_failed("task-04-1", v, {**own["task-04-1"], "xc_mm": 0.0, "yc_mm": 0.0}) == [
        "|oc| from your xc_mm, yc_mm"]
    # a non-number never passes a hidden check
    assert "l_сн from your x, y" in _hidden_failed("task-03-1", v, {**own["task-03-1"], "x_mm": "seventy"})


# --------------------------------------------------------------------------- what the student sees
def test_the_check_cells_name_the_mistakes(capsys):
    v = variant_for_index(3)
    a2 = tasks.answers("task-03-2", v)
    sheet = relief_sheet(3)
    with pytest.raises(checks.WrongAnswer, match="plain mean"):
        checks.check_task("task-03-2", v, **{**a2, "Zcp_m": float(np.mean(sheet.Z_given_m))})
    with pytest.raises(checks.WrongAnswer, match="isocentre"):
        checks.check_task("task-03-2", v, **{**a2, "xn_mm": float(sheet.c_mm[0])})
    with pytest.raises(checks.WrongAnswer, match="sign"):
        checks.check_task("task-03-2", v, **{**a2, "xn_mm": -a2["xn_mm"]})
    with pytest.raises(checks.WrongAnswer, match="every sign is wrong"):
        checks.check_task("task-03-2", v, **{**a2, "dh_mm": [-x for x in a2["dh_mm"]]})
    r_from_o = list(np.hypot(*sheet.photo_xy_mm.T))
    with pytest.raises(checks.WrongAnswer, match=r"r_mm: \d of 6 values are not right: .*1, 2"):
        checks.check_task("task-03-2", v, **{**a2, "r_mm": r_from_o})
    a1 = tasks.answers("task-03-1", v)
    with pytest.raises(checks.WrongAnswer, match="factor of 1/10"):
        checks.check_task("task-03-1", v, **{**a1, "m_i": [m / 10 for m in a1["m_i"]]})  # M = 1000, not 10 000
    with pytest.raises(checks.WrongAnswer, match="reverse order"):
        checks.check_task("task-03-1", v, **{**a1, "x_mm": a1["x_mm"][::-1]})
    w = variant_for_index(40)
    right = tasks.answers("task-04-1", v)
    with pytest.raises(checks.WrongAnswer, match="variant 40"):
        checks.check_task("task-04-1", v, **{**right, "oc_mm": tasks.answers("task-04-1", w)["oc_mm"]})
    with pytest.raises(checks.WrongAnswer, match="α/2"):
        checks.check_task("task-04-1", v, **{**right, "oc_mm": -v.f_mm * math.tan(math.radians(v.alpha_deg))})
    a6 = tasks.answers("task-04-3", v)
    with pytest.raises(checks.WrongAnswer, match="every sign is wrong"):
        checks.check_task("task-04-3", v, **{**a6, "da_mm": [-x for x in a6["da_mm"]]})
    with pytest.raises(checks.WrongAnswer, match="phi_deg"):  # counted clockwise
        checks.check_task("task-04-3", v, **{**a6, "phi_deg": [360 - p for p in a6["phi_deg"]]})
    checks.check_task("task-03-2", v, **a2)
    assert "✓ Task 03.2 passed" in capsys.readouterr().out
    assert checks.passed("task-03-2")


def test_inputs_are_the_students_lab_sheets():
    """Each task's inputs are a read-only view of the student's sheet without its solution (issue 27: the
    inputs never carry a graded answer): the same sheet for the three tasks of chapter 03 and of 04.2/04.4."""
    v = variant_for_index(12)
    s1 = tasks.inputs("task-03-1", v)
    views = [s1, tasks.inputs("task-03-2", v), tasks.inputs("task-03-3", v)]
    assert all(type(s) is ch03.Withheld and s._obj is relief_sheet(12) for s in views)  # noqa: SLF001
    assert s1.kind == "relief" and s1.names == ("I", "1", "2", "II", "3", "4")
    assert tasks.inputs("task-04-1", v) is None  # the variant itself
    s2 = tasks.inputs("task-04-2", v)
    assert s2._obj is tasks.inputs("task-04-4", v)._obj is tilt_sheet(12)  # noqa: SLF001
    assert s2.kind == "tilt" and len(s2.names) == 9
    # the sheet's solution is not given, and the view is read-only
    for name in ch03.SHEET_WITHHELD:
        with pytest.raises(AttributeError, match="is not given"):
            getattr(s1, name)
    with pytest.raises(AttributeError, match="read-only"):
        s1.kind = "tilt"
    # what a notebook shows of a sheet has no coordinates and no results
    assert repr(s1) == f"LabSheet(…, inputs of the task: {', '.join(sorted(ch03.SHEET_WITHHELD))} withheld)"
    assert list(s1.heights().columns) == ["Z, m"]
    text = s1.summary().to_string()
    assert "1:13\u202f200" in text and "220" in text and "-48" in text


def test_the_task_templates_and_checks_read_the_same_names():
    for task_id in IDS_03_04:
        task = tasks.get(task_id)
        lines = task.template().splitlines()
        assert [ln.split(" = ")[0] for ln in lines] == list(task.names)
