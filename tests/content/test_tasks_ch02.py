"""The graded tasks of chapter 02 (aerophoto.tasks.ch02, labs.ch02): the strip's data and answers, the inputs the
notebook shows, today's tolerances, slips (the tests that hold chapters 01 and 02 together are in test_tasks_ch01.py)."""

import pandas as pd
import pytest

from aerophoto import checks, tasks
from aerophoto.labs import ch02 as lab02
from aerophoto.tasks import ch02
from aerophoto.variants import variant_for_index

approx = pytest.approx
IDS = ["task-02-1", "task-02-2"]
SOME_VARIANTS = (0, 7, 42, 57, 99)


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
                   "alpha_read_deg": 0.05}  # half a printed unit of 0.1° (issue 27); its hidden check keeps 30′ steps
    assert [a.name for a in ch02.JudgeStrip.spec if a.kind == "bool"] == ["px_ok", "dm_ok", "n_ok", "crab_ok",
                                                                          "tilt_ok"]


# --------------------------------------------------------------------------- typical slips
def _wrong(tid, v, **change):
    values = {**tasks.answers(tid, v), **change}
    with pytest.raises(checks.WrongAnswer) as e:
        checks.check_task(tid, v, **values)
    return str(e.value)


def test_chapter_02_slips_are_recognised(capsys):
    v = variant_for_index(0)
    d = lab02.strip_measurements(v)
    assert "divides by b1" in _wrong("task-02-1", v, dm_percent=(d["b1_mm"] - d["b2_mm"]) / d["b2_mm"] * 100)
    assert "multiply by 30′" in _wrong("task-02-2", v, alpha_read_deg=d["bubble_div"])
    assert "56 %" in _wrong("task-02-2", v, px_ok=not tasks.answers("task-02-2", v)["px_ok"])
    w = variant_for_index(23)
    assert "variant 23" in _wrong("task-02-1", v, Px_percent=tasks.answers("task-02-1", w)["Px_percent"])
    capsys.readouterr()
