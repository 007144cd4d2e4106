"""Graded tasks of chapters 01 (guide §2) and 02 (guide §3), the side-overlap allowance, and guide §3's table 1."""

import math

import numpy as np
import pandas as pd
import pytest

from aerophoto import checks, flight, tasks
from aerophoto.course import score
from aerophoto import quality as q
from aerophoto import guide
from aerophoto.labs import ch02 as lab02
from aerophoto.tasks import ch01, ch02
from aerophoto.variants import variant_for_index

approx = pytest.approx
IDS = ["task-01-1", "task-01-2", "task-01-3", "task-02-1", "task-02-2"]
SOME_VARIANTS = (0, 7, 42, 57, 99)


# --------------------------------------------------------------------------- registry and reference answers
def test_the_chapters_register_their_tasks():
    assert [t.id for t in tasks.chapter_tasks("01")] == IDS[:3]
    assert [t.id for t in tasks.chapter_tasks("02")] == IDS[3:]
    assert [t.points for t in tasks.chapter_tasks("01")] == [4, 3, 4]
    assert [t.points for t in tasks.chapter_tasks("02")] == [3, 3]
    for tid in IDS:
        t = tasks.get(tid)
        assert set(t.answers(variant_for_index(0))) == set(t.names)


@pytest.mark.parametrize("tid", IDS)
@pytest.mark.parametrize("i", SOME_VARIANTS)
def test_reference_answers_pass_the_trusted_grading(tid, i):
    v = variant_for_index(i)
    grade = score.grade_task(tid, v, tasks.answers(tid, v))
    assert grade.passed, grade.checks
    assert grade.score == grade.points


def test_chapter_01_answers_are_the_plan():
    v = variant_for_index(0)
    p = flight.plan(v)
    assert tasks.answers("task-01-1", v) == {"H_m": 1200.0, "Px_percent": p.Px_percent, "Bx_km": p.Bx_km,
                                             "By_km": p.By_km}
    assert tasks.answers("task-01-2", v) == {"K": 22, "n": 31, "N": 682}
    assert tasks.answers("task-01-3", v)["tau_s"] == approx(15.1632)
    assert tasks.inputs("task-01-1", v) is None                     # the variant itself is the input
    a = ch01.HeightOverlapBases.spec[1]
    assert (a.name, a.tol_abs, a.tol_rel) == ("Px_percent", 0.02, None)
    assert all(x.kind == "count" and x.rounding == "up" for x in ch01.StripsAndPhotos.spec)


def test_chapter_02_data_and_answers():
    # (moved from test_quality: the task data used to be quality.variant_task / variant_task_answers)
    v = variant_for_index(0)
    d = lab02.strip_measurements(v)
    assert d == lab02.strip_measurements(v)  # deterministic
    assert d["b_mm"] == 180.0 and d["f_mm"] == 100.0 and d["H_m"] == 1200.0
    for k in ("a_mm", "b1_mm", "b2_mm", "L_mm", "l_mm"):
        assert d[k] == round(d[k], 1)
    a = ch02.reference_answers(v)
    assert a["Px_percent"] == approx(d["a_mm"] / 180 * 100)
    assert a["dm_percent"] == approx((d["b1_mm"] - d["b2_mm"]) / d["b1_mm"] * 100)
    assert a["n_percent"] == approx(d["l_mm"] / d["L_mm"] * 100)
    assert a["crab_limit_deg"] == 5.0
    assert a["px_ok"] == (a["Px_percent"] >= 56)
    # the variants differ, and the verdicts are not all the same across the class
    answers = [ch02.reference_answers(variant_for_index(i)) for i in range(0, 100, 7)]
    assert len({round(x["Px_percent"], 3) for x in answers}) > 10
    for key in ("px_ok", "dm_ok", "n_ok", "crab_ok"):
        assert {x[key] for x in answers} == {True, False}, key


def test_chapter_02_inputs_are_the_table_the_notebook_shows():
    v = variant_for_index(0)
    meas = tasks.inputs("task-02-1", v)
    assert isinstance(meas, pd.Series) and meas.name == "your measurements"
    assert tuple(meas.index) == lab02.MEASUREMENT_KEYS
    d = lab02.strip_measurements(v)
    assert all(meas[k] == d[k] for k in lab02.MEASUREMENT_KEYS)
    assert meas["a_mm"] == 105.0 and meas["b1_mm"] == 74.4 and meas["bubble_div"] == 0.3
    assert tasks.inputs("task-02-2", v).equals(meas)
    # the notebook's solution works on it as on the old dict
    assert meas["a_mm"] / meas["b_mm"] * 100 == approx(tasks.answers("task-02-1", v)["Px_percent"])


def test_chapter_02_tolerances_are_todays():
    tol = {a.name: a.tol_abs for t in tasks.chapter_tasks("02") for a in t.spec if a.kind == "value"}
    assert tol == {"Px_percent": 0.05, "dm_percent": 0.02, "n_percent": 0.02, "crab_limit_deg": 0.05,
                   "alpha_read_deg": 0.01}
    assert [a.name for a in ch02.JudgeStrip.spec if a.kind == "bool"] == ["px_ok", "dm_ok", "n_ok", "crab_ok",
                                                                          "tilt_ok"]


# --------------------------------------------------------------------------- typical slips
def _wrong(tid, v, **change):
    values = {**tasks.answers(tid, v), **change}
    with pytest.raises(checks.WrongAnswer) as e:
        checks.check_task(tid, v, **values)
    return str(e.value)


def test_chapter_01_slips_are_recognised(capsys):
    v = variant_for_index(0)
    p = flight.plan(v)
    flat = p.replace(Zmax_m=p.Zmin_m)
    assert "relief allowance" in _wrong("task-01-1", v, Bx_km=0.864)               # the guide's 7.2·12000
    assert "photoplan scale" in _wrong("task-01-1", v, H_m=p.f_mm / 1000 * p.M)
    assert "normative px" in _wrong("task-01-1", v, Px_percent=60.0)
    assert "rounds" in _wrong("task-01-2", v, K=21)                                 # the guide's 30/1.51 + 1
    assert "without the '+ 1'" in _wrong("task-01-2", v, N=21 * 30)
    assert "factor 1.2" in _wrong("task-01-3", v, LS_km=p.LS_km / 1.2)
    assert "0.86·3600/200" in _wrong("task-01-3", v, tau_s=flat.tau_s)
    assert "photoplan at 1:M" in _wrong("task-01-3", v, tmax_s=p.blur_mm / 1000 * p.m / p.W_ms)
    # another variant's answer is recognised
    w = variant_for_index(10)
    assert "variant 10" in _wrong("task-01-1", v, H_m=flight.plan(w).H_m)
    capsys.readouterr()


def test_chapter_01_slips_are_todays():
    p = flight.guide_example()
    s = ch01.typical_slips(p)
    slips = ch01.HeightOverlapBases().slips(variant_for_index(0))
    assert set(slips) == {"H_m", "Px_percent", "Bx_km", "By_km"} and slips["Bx_km"] == s["Bx_km"]
    assert set(ch01.StripsAndPhotos().slips(variant_for_index(0))) == {"K", "n", "N"}
    assert set(ch01.RouteAndTiming().slips(variant_for_index(0))) == {"LS_km", "TS_h", "tmax_s", "tau_s"}


def test_chapter_02_slips_are_recognised(capsys):
    v = variant_for_index(0)
    d = lab02.strip_measurements(v)
    assert "divides by b1" in _wrong("task-02-1", v, dm_percent=(d["b1_mm"] - d["b2_mm"]) / d["b2_mm"] * 100)
    assert "multiply by 30′" in _wrong("task-02-2", v, alpha_read_deg=d["bubble_div"])
    assert "56 %" in _wrong("task-02-2", v, px_ok=not tasks.answers("task-02-2", v)["px_ok"])
    w = variant_for_index(23)
    assert "variant 23" in _wrong("task-02-1", v, Px_percent=tasks.answers("task-02-1", w)["Px_percent"])
    capsys.readouterr()


# --------------------------------------------------------------------------- hidden checks
def _hidden(grade):
    return {name: ok for name, ok, _, hidden in grade.checks if hidden}


def test_hidden_checks_catch_inconsistent_submissions():
    v = variant_for_index(0)
    p = flight.plan(v)
    # 01.1: Bx within its tolerance, Px within its own, but the two do not belong together
    bad = {**tasks.answers("task-01-1", v), "Px_percent": p.Px_percent + 0.019, "Bx_km": p.Bx_km * 1.0049}
    g = score.grade_task("task-01-1", v, bad)
    assert g.visible_ok and _hidden(g) == {"Bx_km from Px_percent": False} and g.score == 0
    # 01.2: N is not the product of the student's own n and K
    g = score.grade_task("task-01-2", v, {"K": 22, "n": 31, "N": 683})
    assert _hidden(g) == {"N = n·K": False}
    # 01.3: TS is not the student's own LS over W
    bad = {**tasks.answers("task-01-3", v), "LS_km": p.LS_km * 1.004, "TS_h": p.TS_h * 0.996}
    g = score.grade_task("task-01-3", v, bad)
    assert g.visible_ok and _hidden(g) == {"TS_h from LS_km": False}
    # 02.2: a level reading within 0.01° of the right one, but not a whole number of 30′ divisions
    a = tasks.answers("task-02-2", v)
    g = score.grade_task("task-02-2", v, {**a, "alpha_read_deg": a["alpha_read_deg"] + 0.005})
    assert g.visible_ok and _hidden(g) == {"alpha_read_deg (30′ steps)": False} and not g.passed
    # no hidden check repeats a visible one: 02.1 has none (each answer is one formula of the given data)
    assert ch02.MeasureStrip().hidden(v, tasks.answers("task-02-1", v)) == []
    # unanswered values: the hidden check fails, it never raises
    g = score.grade_task("task-01-2", v, {"K": ..., "n": 31, "N": 682})
    assert _hidden(g) == {"N = n·K": False} and g.score == 0


def test_hidden_checks_pass_the_reference_answers():
    for i in SOME_VARIANTS:
        v = variant_for_index(i)
        for tid in IDS:
            hidden = tasks.get(tid).hidden(v, tasks.answers(tid, v))
            assert all(score.hidden_ok(h)[0] for h in hidden), (tid, i)


# --------------------------------------------------------------------------- the side-overlap allowance (guide §2)
def test_exact_allowance_keeps_the_overlap_on_the_highest_ground():
    assert flight.exact_allowance_percent(60, 30, 1200) == approx(1.0)     # the guide's 40·h/H
    assert flight.exact_allowance_percent(30, 30, 1200) == approx(1.75)    # 70·h/H, where the guide keeps 40
    with pytest.raises(ValueError, match="h_m = 1300"):
        flight.exact_allowance_percent(30, 1300, 1200)
    for i in SOME_VARIANTS:
        p = flight.plan(variant_for_index(i))
        exact = flight.side_spacing(p, exact=True)
        side_on_top = 100 - (100 - exact["Py_percent"]) * p.H_m / (p.H_m - p.h_m)
        assert side_on_top == approx(p.py_percent)
        guide = flight.side_spacing(p)
        assert (guide["Py_percent"], guide["by_cm"], guide["By_km"], guide["K"]) == (p.Py_percent, p.by_cm, p.By_km,
                                                                                    p.K)


def test_side_allowance_for_variant_00():
    t = guide.ch01.side_allowance_table(flight.guide_example())
    g, e = t.columns[0], t.columns[1]
    assert list(t.index) == ["allowance, %", "Py, %", "by, cm", "By, km", "K"]
    assert t.loc["allowance, %", g] == approx(1.0) and t.loc["allowance, %", e] == approx(1.75)
    assert t.loc["Py, %", g] == approx(31.0) and t.loc["Py, %", e] == approx(31.75)
    assert t.loc["by, cm", g] == approx(12.42) and t.loc["by, cm", e] == approx(12.285)
    assert t.loc["By, km", g] == approx(1.4904) and t.loc["By, km", e] == approx(1.4742)
    assert t.loc["K", g] == 22 and t.loc["K", e] == 22                 # 30/1.4742 + 1 = 21.35 → 22
    assert t.loc["By, km", "difference"] == approx(-0.0162)


def test_the_graded_answers_keep_the_guides_40():
    for i in SOME_VARIANTS:
        v = variant_for_index(i)
        p = flight.plan(v)
        assert tasks.answers("task-01-1", v)["By_km"] == p.By_km == flight.side_spacing(p)["By_km"]
        assert tasks.answers("task-01-2", v)["K"] == flight.side_spacing(p)["K"]


def test_exact_allowance_changes_some_variants_strip_count():
    changed = [i for i in range(100) if flight.side_spacing(flight.plan(variant_for_index(i)), exact=True)["K"]
               != flight.plan(variant_for_index(i)).K]
    # the effect is small (B_y about 1 % shorter): K changes for a minority of the class
    assert 0 <= len(changed) < 50


# --------------------------------------------------------------------------- guide §3, table 1
def test_guide_table_1_as_printed():
    t = guide.ch02.table_1()
    assert list(t.index) == [542, 543, 544, 545]
    assert list(t.columns) == ["sharpness", "fine detail", "defects"]
    assert t.loc[542, "sharpness"] == "good (хор.)" and t.loc[545, "defects"] == "yes (да)"
    assert not hasattr(q, "guide_table_1")
    assert "no checkable numbers" in " ".join(guide.ch02.__doc__.replace("**", "").split())


def test_survey_tasks_have_no_nan_answers():
    for i in SOME_VARIANTS:
        v = variant_for_index(i)
        for tid in IDS:
            for name, value in tasks.answers(tid, v).items():
                assert isinstance(value, (bool, np.bool_)) or math.isfinite(float(value)), (tid, name)
