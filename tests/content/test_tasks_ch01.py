"""The graded tasks of chapter 01 (aerophoto.tasks.ch01): the flight plan's answers, slips, the side-overlap allowance;
and the tests that hold chapters 01 and 02 together (their registry, hidden checks, no NaN answers)."""

import math

import numpy as np
import pytest

from aerophoto import checks, flight, tasks
from aerophoto.course import score
from aerophoto import guide
from aerophoto.tasks import ch01, ch02
from aerophoto.variants import variant_for_index

approx = pytest.approx
IDS = ["task-01-1", "task-01-2", "task-01-3"]
IDS_01_02 = IDS + ["task-02-1", "task-02-2"]  # the tests of chapters 01 and 02 together
SOME_VARIANTS = (0, 7, 42, 57, 99)


# --------------------------------------------------------------------------- registry and reference answers
def test_the_chapters_register_their_tasks():
    assert [t.id for t in tasks.chapter_tasks("01")] == IDS_01_02[:3]
    assert [t.id for t in tasks.chapter_tasks("02")] == IDS_01_02[3:]
    assert [t.points for t in tasks.chapter_tasks("01")] == [4, 3, 4]
    assert [t.points for t in tasks.chapter_tasks("02")] == [3, 3]
    for tid in IDS_01_02:
        t = tasks.get(tid)
        assert set(t.answers(variant_for_index(0))) == set(t.names)


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
    assert [(x.kind, x.rounding) for x in ch01.StripsAndPhotos.spec] == [("count", "up"), ("count", "up"),
                                                                          ("count", "exact")]  # N = n·K


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
    assert "30/1.51 + 1" in _wrong("task-01-2", v, K=21)                           # the guide's slip, named
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
        for tid in IDS_01_02:
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


def test_survey_tasks_have_no_nan_answers():
    for i in SOME_VARIANTS:
        v = variant_for_index(i)
        for tid in IDS_01_02:
            for name, value in tasks.answers(tid, v).items():
                assert isinstance(value, (bool, np.bool_)) or math.isfinite(float(value)), (tid, name)
