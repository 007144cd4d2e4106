"""Chapter 05's graded tasks (aerophoto.tasks.ch05) and what guide §6 prints (aerophoto.guide.s06)."""

import math
import re

import numpy as np
import pytest

from aerophoto import checks, tasks
from aerophoto import geometry as g
from aerophoto import mosaic as mo
from aerophoto.tasks import ch05
from aerophoto.variants import variant_for_index

V3 = variant_for_index(3)


# --------------------------------------------------------------------------- the student's fotoschema
def test_variant_task_data_and_answers():
    v = V3
    d = ch05.measurements(v)
    assert d["dI_mm"] == ch05.measurements(v)["dI_mm"]  # deterministic
    assert len(d["l_mm"]) == 4 and len(d["L_mm"]) == 4 and d["M"] == 10000.0
    assert d["relief_m"] == pytest.approx(0.05 * v.f_mm / 1000 * v.m)
    assert all(x == round(x, 1) and str(x) != "-0.0" for x in d["dI_mm"])
    a = ch05.answers_of(v)
    dI = np.array(d["dI_mm"])
    assert a["m_rms_mm"] == pytest.approx(math.sqrt(np.sum(dI**2) / len(dI)))
    assert a["n_cutouts"] == int(np.sum(dI < 0))
    assert a["m_mean"] == pytest.approx(np.mean(np.array(d["L_mm"]) * 10000 / np.array(d["l_mm"])))
    # the mean scale is near the design scale of the photos
    assert abs(a["m_mean"] / v.m - 1) < 0.05
    other = ch05.answers_of(variant_for_index(40))
    assert other["m_rms_mm"] != a["m_rms_mm"]


def test_inputs_are_the_readings_and_fresh_each_time():
    got = tasks.inputs("task-05-1", V3)
    d = ch05.measurements(V3)
    assert got == {k: d[k] for k in ("dI_mm", "l_mm", "L_mm", "M")}
    assert tasks.inputs("task-05-2", V3) == got
    got["dI_mm"].append(99.0)  # a student changing the list does not change the task
    assert tasks.inputs("task-05-1", V3)["dI_mm"] == d["dI_mm"]
    # the flying height of the student's strip is H = f·m, the relief 5 % of it
    assert d["H_m"] == g.flying_height_m(V3.f_mm, V3.m) and d["relief_m"] == pytest.approx(0.05 * d["H_m"])
    assert d["fotoschema"].m_design == V3.m and len(d["fotoschema"].poses) == ch05.N_PHOTOS


def _reference(task_id, v):
    """The values the notebook's solution computes from the data cell."""
    d = tasks.inputs(task_id, v)
    dI = np.array(d["dI_mm"])
    if task_id == "task-05-1":
        return {"m_rms_mm": float(np.sqrt(np.sum(dI**2) / dI.size)), "n_cutouts": int(np.sum(dI < 0)),
                "seams_ok": bool(dI.min() >= -0.5)}
    m_i = np.array(d["L_mm"]) * d["M"] / np.array(d["l_mm"])
    return {"m_i": m_i, "m_mean": float(np.mean(m_i))}


@pytest.mark.parametrize("i", [0, 3, 57])
@pytest.mark.parametrize("task_id", ["task-05-1", "task-05-2"])
def test_the_solutions_pass_grading(task_id, i):
    v = variant_for_index(i)
    grade = checks.grade_task(task_id, v, _reference(task_id, v))
    assert grade.passed and grade.score == grade.points == 3, grade.checks


def test_the_answers_are_todays():
    a = ch05.answers_of(V3)
    t1, t2 = tasks.get("task-05-1"), tasks.get("task-05-2")
    assert t1.answers(V3) == {k: a[k] for k in ("m_rms_mm", "n_cutouts", "seams_ok")}
    assert t2.answers(V3) == {"m_i": list(a["m_i"]), "m_mean": a["m_mean"]}
    assert t1.names == ("m_rms_mm", "n_cutouts", "seams_ok") and t2.names == ("m_i", "m_mean")
    assert t1.answer("m_rms_mm").tol_abs == 0.005 and t1.answer("n_cutouts").rounding == "nearest"


def test_typical_slips_are_recognised(capsys):
    v = V3
    slips = tasks.get("task-05-1").slips(v)
    ref = _reference("task-05-1", v)
    dI = np.array(tasks.inputs("task-05-1", v)["dI_mm"])
    for hint, value in slips["m_rms_mm"].items():
        with pytest.raises(checks.WrongAnswer, match=re.escape(hint.split("—")[0].strip()[:20])):
            checks.check_task("task-05-1", v, **{**ref, "m_rms_mm": value})
    assert float(np.mean(np.abs(dI))) in slips["m_rms_mm"].values()
    if int(np.sum(dI > 0)) != ref["n_cutouts"]:
        with pytest.raises(checks.WrongAnswer, match="duplicates"):
            checks.check_task("task-05-1", v, **{**ref, "n_cutouts": int(np.sum(dI > 0))})
    grade = checks.grade_task("task-05-1", v, {**ref, "m_rms_mm": float(np.mean(dI**2))})
    assert not grade.passed and "square root" in grade.first_failure


def test_another_variants_answer_is_recognised():
    other = ch05.answers_of(variant_for_index(40))
    ref = _reference("task-05-2", V3)
    with pytest.raises(checks.WrongAnswer, match="variant"):
        checks.check_task("task-05-2", V3, m_i=ref["m_i"], m_mean=other["m_mean"])


def test_hidden_checks_catch_inconsistent_answers():
    v = V3
    t1, t2 = tasks.get("task-05-1"), tasks.get("task-05-2")
    ref2 = _reference("task-05-2", v)
    # the mean scale must be the mean of the student's own partial scales
    (h,) = t2.hidden(v, ref2)
    assert checks._hidden_ok(h)[0]
    bad_mi = np.array(ref2["m_i"]) * np.array([1.0, 1.0, 1.0, 1.04])
    (h,) = t2.hidden(v, {"m_i": bad_mi, "m_mean": ref2["m_mean"]})
    assert not checks._hidden_ok(h)[0]
    (h,) = t2.hidden(v, {"m_i": ..., "m_mean": ref2["m_mean"]})
    assert not checks._hidden_ok(h)[0]
    # no cut-out cannot fail the seams; failing seams need a large enough RMS
    hs = t1.hidden(v, {"m_rms_mm": 0.2, "n_cutouts": 0, "seams_ok": False})
    assert [checks._hidden_ok(h)[0] for h in hs] == [False, True]
    hs = t1.hidden(v, {"m_rms_mm": 0.01, "n_cutouts": 3, "seams_ok": False})
    assert [checks._hidden_ok(h)[0] for h in hs] == [False]
    assert t1.hidden(v, {"m_rms_mm": 0.2, "n_cutouts": 3, "seams_ok": True}) == []
    # the instructor's grade fails a consistent-looking but inconsistent submission
    grade = checks.grade_task("task-05-2", v, {"m_i": bad_mi, "m_mean": ref2["m_mean"]})
    assert not grade.passed and not grade.hidden_ok


def test_malformed_answers_never_stop_the_grader():
    for values in ({}, {"m_i": "twelve thousand", "m_mean": None}, {"m_i": [1, 2], "m_mean": float("nan")}):
        grade = checks.grade_task("task-05-2", V3, values)
        assert grade.score == 0 and not grade.passed
    grade = checks.grade_task("task-05-1", V3, {"m_rms_mm": "x", "n_cutouts": 0, "seams_ok": "yes"})
    assert grade.score == 0


def test_photo_axis_towards():
    assert g.photo_axis_towards([71.8, -2.1]) == (0, 1.0)
    assert g.photo_axis_towards([3.0, -70.0]) == (1, -1.0)
    assert g.photo_axis_towards(np.array([-5.0, 0.0])) == (0, -1.0)


# --------------------------------------------------------------------------- guide §6
def test_the_book_uses_the_guides_printed_rules():
    import inspect

    from aerophoto.guide import s06

    assert s06.rule("steps 5, 8", "largest cut-out").value == mo.ALLOWED_CUTOUT_MM == 0.5
    lo, hi = s06.rule("step 8", "spacing").value
    assert lo <= mo.CHECK_SPACING_MM <= hi
    margin = inspect.signature(mo.choose_tie_points).parameters["margin_mm"].default
    assert tuple(margin) == s06.rule("step 2", "distance of the tie points").value
    assert s06.rule("step 7", "bases").value == 0.1
    assert s06.rule("step 5", "the sheet").value == s06.SHEET == "A3"
    with pytest.raises(KeyError, match="step 9"):
        s06.rule("step 9", "anything")
    t = s06.rules_table()
    assert len(t) == len(s06.RULES) and list(t.columns)[:4] == ["where", "quantity", "value", "unit"]
    assert [f.number for f in s06.FORMULAS] == ["6.1", "6.2"]
    assert any("13000" in m.printed_text for m in s06.MARGINALIA)


def test_four_prints_at_60_percent_just_fill_a3():
    from aerophoto.guide import s06

    assert s06.strip_length_mm(4, 60) == pytest.approx(180 + 3 * 72)  # 396 mm
    assert s06.strip_length_mm(5, 60) == pytest.approx(468.0)
    assert s06.strip_length_mm(4, 60, trim_mm=15) == pytest.approx(426.0)
    assert s06.prints_on_sheet() == 4
    assert s06.prints_on_sheet(trim_mm=15) == 3  # with the guide's 1.5 cm trim A3 holds three
    assert s06.prints_on_sheet((594.0, 420.0)) == 6  # A2
    text = " ".join(s06.remarks())
    assert "396" in text and "468" in text and "0.5–1" in text and "13000" in text
    with pytest.raises(ValueError, match="px_percent"):
        s06.strip_length_mm(4, 100)
    with pytest.raises(ValueError, match="n_photos"):
        s06.strip_length_mm(0)


def test_the_fotoschema_of_four_prints_matches_the_strip_length():
    # the sheet of the book's worked example (four untilted prints over flat ground) is as long as §6 says
    from aerophoto import simulate as sim
    from aerophoto.guide import s06

    fs = mo.assemble(sim.fly_strip(g.Camera(100), 12000, 60, 4))
    x0, x1, _, _ = fs.extent_mm
    assert x1 - x0 == pytest.approx(s06.strip_length_mm(4, 60), abs=1e-6)
    assert len(fs.scale.names) == len(fs.scale.l_mm) == s06.rule("step 7", "points").value == 4
