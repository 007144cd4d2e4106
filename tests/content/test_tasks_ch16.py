"""The graded tasks of chapter 16 (aerophoto.tasks.ch16, labs.ch16): every variant, slips; and the tests that hold
chapters 16 and 17 together (the variants' data, the hidden checks, malformed answers, the book's physics)."""

import math
import re

import numpy as np
import pytest

from aerophoto import budget as bu
from aerophoto import checks, dem, tasks
from aerophoto.course import score
from aerophoto.labs import ch16 as lab16
from aerophoto.tasks import ch17
from aerophoto.variants import variant_for_index

from .conftest import ALL

V3 = variant_for_index(3)
IDS = ["task-16-1", "task-16-2"]
IDS_16_17 = IDS + ["task-17-1", "task-17-2", "task-17-3"]  # the tests of both chapters


def _reference(task_id, v):
    """What a student computes from the task's data cell, independently of the package's task code."""
    d = tasks.inputs(task_id, v)
    if task_id == "task-16-1":
        H = d.f_mm / 1000 * d.m
        b = d.frame_mm * (1 - d.px_percent / 100)
        n, m, s, r = d.n, d.points_per_photo, d.images_per_point, d.r
        mz = 0.025 * H / b * math.sqrt(3 * (2 * n * s + m * n - s * r) / (2 * m * n * s))
        h = next(h for h in (0.25, 0.5, 1, 2, 2.5, 5, 10, 20, 25, 50, 100) if mz / 1.25 <= 0.3 * h)
        return {"H_m": H, "b_mm": b, "mz_m": mz, "h_m": h}
    if task_id == "task-16-2":
        eg = (d["Z_grid_m"] - d["Z_geod_m"]).to_numpy()
        el = (d["Z_lines_m"] - d["Z_geod_m"]).to_numpy()
        return {"m_grid_m": np.sqrt(np.mean(eg**2)), "m_lines_m": np.sqrt(np.mean(el**2)),
                "v_lines_m": np.mean(np.abs(el)), "share_pct": 100 * np.mean(np.abs(el) <= 0.15)}
    raise ValueError(f"task_id = {task_id!r}: chapter 16's tasks are task-16-1 and task-16-2")


@pytest.mark.parametrize("task_id", IDS)
def test_every_variant_has_answers_and_an_independent_solution_passes(task_id):
    for v in ALL:
        ref = _reference(task_id, v)
        grade = score.grade_task(task_id, v, ref)
        assert grade.passed and grade.score == grade.points, (v.i, grade.checks)
        ans = tasks.answers(task_id, v)
        assert set(ans) == set(tasks.get(task_id).names)
        for k, x in ans.items():
            assert isinstance(x, (bool, str)) or math.isfinite(x), (v.i, k, x)


def test_the_variants_data_are_their_own_and_deterministic():
    assert lab16.sheet_of(V3) == dem.Sheet(100 + 88 * 3, 2500 + 250 * 3, 1000)
    sheets = {(lab16.sheet_of(v).X0_m, lab16.sheet_of(v).Y0_m) for v in ALL}
    assert len(sheets) == 100
    for v in (ALL[0], ALL[99]):
        s = lab16.sheet_of(v)
        assert 0 <= s.X0_m and s.X0_m + s.size_m <= 10000 and 0 <= s.Y0_m and s.Y0_m + s.size_m <= 5000
    d3 = lab16.sheet_data(V3)
    assert d3.spacing_m == pytest.approx(0.007 * V3.m) and len(d3.points) == lab16.N_CHECK
    assert d3.grid.mz_m == lab16.MZ_SHEET_M
    assert tasks.inputs("task-16-2", V3).equals(tasks.inputs("task-16-2", V3))
    b = lab16.block_of(V3)
    assert (b.strips, b.per_strip, b.n, b.r) == (7, 11, 77, 21)
    c1, c2 = ch17.corner_measurements(V3), ch17.corner_measurements(V3)
    assert c1.equals(c2) and len(c1) == 20
    assert not c1.equals(ch17.corner_measurements(ALL[4]))
    assert [ch17.scan_um(v) for v in ALL[:3]] == [12.0, 15.0, 18.0] and ch17.scan_um(ALL[19]) == 39.0


def _slip_cases():
    for task_id in IDS:
        for i in (0, 3, 57):
            yield task_id, i


@pytest.mark.parametrize("task_id,i", list(_slip_cases()))
def test_typical_slips_are_recognised(task_id, i):
    v = ALL[i]
    ref = tasks.answers(task_id, v)
    t = tasks.get(task_id)
    n_checked = 0
    for name, slips in t.slips(v).items():
        a = t.answer(name)
        for hint, value in slips.items():
            if value is None:
                continue
            tol = a.tol_abs or 0.005 * abs(ref[name])
            if a.kind == "value" and math.isclose(value, ref[name], rel_tol=0, abs_tol=tol):
                continue  # this slip gives the right value for this variant
            with pytest.raises(checks.WrongAnswer, match=re.escape(hint[:25])):
                checks.check_task(task_id, v, **{**ref, name: value})
            n_checked += 1
    assert n_checked >= 2


def test_hidden_checks_catch_inconsistent_answers():
    v = V3
    ok = lambda hs: [score.hidden_ok(h)[0] for h in hs]  # noqa: E731
    t = tasks.get("task-16-1")
    ref = tasks.answers("task-16-1", v)
    assert ok(t.hidden(v, ref)) == [True, True]
    assert ok(t.hidden(v, {**ref, "mz_m": ref["mz_m"] * 1.02})) == [False, True]
    assert ok(t.hidden(v, {**ref, "h_m": 5.0})) == [True, False]
    assert ok(t.hidden(v, {**ref, "H_m": ...})) == [False, True]
    t = tasks.get("task-16-2")
    ref = tasks.answers("task-16-2", v)
    assert ok(t.hidden(v, ref)) == [True, True]
    # within the visible tolerance, but not a count of the 40 points
    grade = score.grade_task("task-16-2", v, {**ref, "share_pct": ref["share_pct"] + 0.009})
    assert grade.visible_ok and not grade.hidden_ok
    assert ok(t.hidden(v, {**ref, "v_lines_m": 2 * ref["m_lines_m"]})) == [True, False]
    t = tasks.get("task-17-1")
    ref = tasks.answers("task-17-1", v)
    assert ok(t.hidden(v, ref)) == [True, True]
    assert ok(t.hidden(v, {**ref, "VX_m": ref["VX_m"] + 0.01})) == [False, True]
    assert ok(t.hidden(v, {**ref, "mD_m": ref["mD_m"] * 1.1})) == [True, False]
    t = tasks.get("task-17-2")
    ref = tasks.answers("task-17-2", v)
    assert ok(t.hidden(v, ref)) == [True, True]
    assert ok(t.hidden(v, {**ref, "sigma_um": 2 * ref["sigma_um"]})) == [False, True]
    t = tasks.get("task-17-3")
    ref = tasks.answers("task-17-3", v)
    assert ok(t.hidden(v, ref)) == [True, True]
    assert ok(t.hidden(v, {**ref, "ok": not ref["ok"]})) == [True, False]
    assert ok(t.hidden(v, {**ref, "mD_m": None})) == [False, True]


def test_malformed_answers_never_stop_the_grader():
    for task_id in IDS_16_17:
        names = tasks.get(task_id).names
        for values in ({}, {n: "x" for n in names}, {n: float("nan") for n in names}):
            grade = score.grade_task(task_id, V3, values)
            assert grade.score == 0 and not grade.passed


def test_the_reference_uses_the_books_physics():
    v = V3
    b = lab16.block_of(v)
    assert tasks.answers("task-16-1", v)["mz_m"] == pytest.approx(
        dem.lysenko_mz_m(b.H_m, b.b_mm, 0.025, b.n, 16, 3, b.r))
    c = ch17.case_of(v)
    assert tasks.answers("task-17-3", v)["mD_m"] == pytest.approx(c.budget().total_m)
    assert c.budget().stage("transfer").rms_m == pytest.approx(bu.transfer_from_mean_mm() * 10)
