"""The graded tasks of chapter 06 (aerophoto.tasks.ch06, labs.ch06): the strip the student reads, the guide's
convention, the references against the truth, a student's own computation, slips, hidden checks; and the tests that
hold chapters 06 and 12 together (one strip for both: their registry, every variant, the printed verdicts)."""

import math

import numpy as np
import pytest

from aerophoto import checks, tasks
from aerophoto.course import score
from aerophoto import triangulation as T
from aerophoto.labs import ch06 as lab06
from aerophoto.tasks import ch06, ch12
from aerophoto.variants import variant, variant_for_index

from .conftest import _by_hand, _grade

VARIANTS = [variant_for_index(i) for i in (0, 1, 2, 17, 57, 99)]
IDS = ("task-06-1", "task-06-2", "task-06-3", "task-12-1", "task-12-2", "task-12-3")  # one strip, both chapters
V57 = variant("19-0457")


def test_the_chapters_register_their_tasks():
    assert [t.id for t in tasks.chapter_tasks("06")] == ["task-06-1", "task-06-2", "task-06-3"]
    assert [t.id for t in tasks.chapter_tasks("12")] == ["task-12-1", "task-12-2", "task-12-3"]
    assert [tasks.get(i).points for i in IDS] == [3, 4, 3, 3, 3, 3]
    assert tasks.get("task-06-1").names == ("triangle_mm", "triangles_ok")
    assert tasks.get("task-06-2").names == ("l_base_mm", "l_template_mm", "k_bases", "k_mean", "spread_ok")
    assert tasks.get("task-06-3").names == tasks.get("task-12-3").names == ("r_mm", "v_mm")
    assert tasks.get("task-12-2").names == ("k_bases", "k_mean", "dk_max", "spread_ok")


# --------------------------------------------------------------------------- what the student reads
def test_the_inputs_are_plain_tables_not_the_answers():
    r = tasks.inputs("task-06-1", V57)
    assert isinstance(r, lab06.StripReadings)
    assert set(vars(r)) == {"rays", "control", "points", "M"}  # no laid strip, no reduction, no coefficients
    for name in ("reduction", "coefficients", "corrections", "free", "templates"):
        assert not hasattr(r, name)
    for task_id in ("task-06-2", "task-06-3", "task-12-2", "task-12-3"):
        assert tasks.inputs(task_id, V57).control.equals(r.control)  # one strip for both chapters
    t = r.control_table()
    t.iloc[0, 0] = 0.0  # a student's change does not reach the task
    assert tasks.inputs("task-06-2", V57).control.iloc[0, 0] != 0.0
    assert list(r.points.index) == list(lab06.POINT_ORDER) and "a" not in r.points.index  # tie points not transferred
    assert list(r.control.index) == ["36/1", "36/2", "39/1", "39/2"]
    assert list(dict.fromkeys(r.rays.index.get_level_values(0))) == list(lab06.TIE_POINTS)
    assert all(len(r.rays.loc[n]) == 3 for n in lab06.TIE_POINTS)


def test_the_tables_are_in_the_geodetic_convention_and_within_the_reading_error():
    for v in (variant_for_index(0), V57, variant_for_index(99)):
        lab, r = lab06.lab_strip(v), lab06.strip_readings(v)
        pts = lab.free.points
        names = list(pts.names)
        # control coordinates: X north = X₀ + ground Y, Y east = Y₀ + ground X, to 0.1 m
        ctl = [names.index(n) for n in r.control.index]
        truth = T.ground_to_geodetic(pts.XYZ_m[ctl, :2])
        assert np.allclose(r.control[["X (north), m", "Y (east), m"]].to_numpy(), truth, atol=0.05 + 1e-9)
        assert np.all(r.control["X (north), m"] > 6.06e6) and np.all(r.control["Y (east), m"] > 3.1e5)
        # the common tracing: the laid strip turned and shifted onto the table, axes swapped, read to 0.1 mm
        phi, R, shift = lab06.tracing_frame(v)
        assert abs(math.degrees(phi)) <= 8.0
        on_table = T.sheet_to_geodetic(lab.free.points_mm[[names.index(n) for n in lab06.POINT_ORDER]] @ R.T + shift)
        read = r.points[["x on the strip, mm", "y on the strip, mm"]].to_numpy()
        assert np.all(np.abs(read - on_table) <= lab06.SHEET_MAX_MM + 0.05 + 1e-9)
        assert np.all(read > 5.0)
        # the strip runs along +y ("east"): 36 … 39 in order
        y = r.points.loc[["36", "37", "38", "39"], "y on the strip, mm"].to_numpy()
        assert np.all(np.diff(y) > 0)
        # the rays reproduce the laid strip's own error triangles (a turn and a shift change no triangle)
        tri_read = ch06.triangles_from_rays(r.rays)["largest, mm"].to_numpy()
        tri_true = lab.free.triangle_sides_mm[[names.index(n) for n in lab06.TIE_POINTS]].max(axis=1)
        assert np.allclose(tri_read, tri_true, atol=0.002)


def test_reference_answers_hold_against_the_truth():
    for v in VARIANTS:
        lab = lab06.lab_strip(v)
        red = lab.reduction  # exact, unrounded, in the package's own frame
        a2, a12 = tasks.answers("task-06-2", v), tasks.answers("task-12-2", v)
        exact = T.reduction_coefficients([red.strip.points.names[i] for i in red.control],
                                         red.truth_plan_mm[red.control], red.strip.points_mm[red.control],
                                         pairs=ch06.RING)
        assert np.allclose(a2["l_base_mm"], exact.l_base_mm, atol=0.02)  # coordinates read to 0.1 m = 0.01 mm
        assert np.allclose(a2["l_template_mm"], exact.l_template_mm, atol=0.25)  # two points read to 0.1 mm
        assert np.allclose(a2["k_bases"], exact.k, atol=0.002)
        assert a12["k_mean"] == pytest.approx(red.k, abs=0.001)
        assert a2["k_mean"] == pytest.approx(1 / lab06.free_scale_ratio(v.i), abs=0.01)  # k ≈ 1/q
        a3 = tasks.answers("task-06-3", v)
        r_true = red.corrections.r_mm[[red.strip.points.names.index(n) for n in ch06.CORRECTION_POINTS]]
        assert np.allclose(a3["r_mm"], r_true, atol=0.25)
        assert np.allclose(a3["v_mm"], np.array(a3["r_mm"]) * (a2["k_mean"] - 1))


def test_half_the_class_lays_the_strip_too_small_and_half_too_large():
    q = [lab06.free_scale_ratio(i) for i in range(100)]
    k1 = [1 / x - 1 for x in q]
    assert min(abs(x) for x in k1) > 0.02  # corrections never vanish
    assert sum(x > 0 for x in k1) == 50 and sum(x < 0 for x in k1) == 50
    v_pos = tasks.answers("task-06-3", variant_for_index(10))["v_mm"]
    v_neg = tasks.answers("task-06-3", variant_for_index(60))["v_mm"]
    assert min(v_pos) > 0 and max(v_neg) < 0  # away from the centre, and towards it


@pytest.mark.parametrize("task_id", ["task-06-1", "task-06-2", "task-06-3"])
def test_a_students_own_computation_passes(task_id):
    for v in VARIANTS:
        g = score.grade_task(task_id, v, _by_hand(task_id, v))
        assert g.passed, (v.i, g.checks)


def test_wrong_answers_get_the_slip_hint():
    v = VARIANTS[1]
    a = tasks.answers("task-06-2", v)
    with pytest.raises(checks.WrongAnswer, match="base over template"):
        checks.check_task("task-06-2", v, **{**a, "k_mean": 1 / a["k_mean"]})
    with pytest.raises(checks.WrongAnswer, match="reverse order"):
        checks.check_task("task-06-2", v, **{**a, "k_bases": a["k_bases"][::-1]})
    a3 = tasks.answers("task-06-3", v)
    with pytest.raises(checks.WrongAnswer, match="sign"):  # r(1 − k): laid off the wrong way
        checks.check_task("task-06-3", v, **{**a3, "v_mm": [-x for x in a3["v_mm"]]})
    kw = ch12.zhukov_inputs(v).zhukov_kwargs()
    n_max = tasks.answers("task-12-1", v)["n_max"]
    with pytest.raises(checks.WrongAnswer, match="as scanned"):
        checks.check_task("task-12-1", v, m3_mm=T.zhukov_error_mm(3, reading="n0", **kw), n_max=n_max)
    with pytest.raises(checks.WrongAnswer, match="k_i is the enlargement"):
        checks.check_task("task-12-1", v, m3_mm=T.zhukov_error_mm(3, **{**kw, "k_i": 1.0}), n_max=n_max)
    a12 = tasks.answers("task-12-2", v)
    k = np.array(a12["k_bases"])
    with pytest.raises(checks.WrongAnswer, match="max k − min k"):
        checks.check_task("task-12-2", v, **{**a12, "dk_max": float(k.max() - k.min())})
    with pytest.raises(checks.WrongAnswer, match="spread_ok"):
        checks.check_task("task-12-2", v, **{**a12, "spread_ok": not a12["spread_ok"]})


def test_another_variants_answers_are_recognised():
    v, w = VARIANTS[1], VARIANTS[3]
    a = tasks.answers("task-06-2", v)
    with pytest.raises(checks.WrongAnswer, match=f"variant {w.i:02d}"):
        checks.check_task("task-06-2", v, **{**a, "k_bases": tasks.answers("task-06-2", w)["k_bases"]})
    for task_id in IDS:
        g = score.grade_task(task_id, v, tasks.answers(task_id, w))
        assert not g.passed and g.score == 0.0, task_id


def test_check_task_passes_the_reference_and_prints_the_verdict(capsys):
    v = VARIANTS[0]
    for task_id in IDS:
        checks.check_task(task_id, v, **tasks.answers(task_id, v))
    out = capsys.readouterr().out
    for n in ("06.1", "06.2", "06.3", "12.1", "12.2", "12.3"):
        assert f"Task {n} passed" in out


def test_hidden_06_1_verdict_follows_from_the_students_sides():
    task = tasks.get("task-06-1")
    v = VARIANTS[1]
    (h,) = task.hidden(v, {"triangle_mm": [0.05, 0.06, 0.04, 0.05], "triangles_ok": False})
    assert h.expected is True and not score.hidden_ok(h)[0]
    (h,) = task.hidden(v, {"triangle_mm": [0.05, 0.36, 0.04, 0.05], "triangles_ok": True})
    assert h.expected is False and not score.hidden_ok(h)[0]
    for side in (0.2999, 0.3003):  # within its rounding of the limit: either verdict
        for ok in (True, False):
            (h,) = task.hidden(v, {"triangle_mm": [0.05, side, 0.04, 0.05], "triangles_ok": ok})
            assert score.hidden_ok(h)[0]
    (h,) = task.hidden(v, {"triangle_mm": "small", "triangles_ok": True})
    assert h.answer is None


def test_hidden_06_2_k_from_the_students_own_lengths_and_mean():
    v = VARIANTS[1]
    a = tasks.answers("task-06-2", v)
    # a coefficient that no rounding of the student's own lengths gives (the lengths written to 0.01 mm move k by
    # about 0.0001, four significant digits of them by up to 0.0003: that is consistent)
    ks = list(a["k_bases"])
    ks[0] += 0.003
    g = _grade("task-06-2", v, k_bases=ks)
    assert "k from your lengths" in [n for n, ok, _, h in g.checks if h and not ok]
    assert _grade("task-06-2", v, l_base_mm=[float(f"{x:.4g}") for x in a["l_base_mm"]]).passed
    # every coefficient and the mean nudged together: consistent and within tolerance
    assert _grade("task-06-2", v, k_bases=[k + 0.0003 for k in a["k_bases"]], k_mean=a["k_mean"] + 0.0003).passed


def test_hidden_06_3_corrections_must_be_proportional_to_r():
    v = VARIANTS[1]
    a = tasks.answers("task-06-3", v)
    bad = list(a["v_mm"])
    j = int(np.argmax(np.abs(bad)))  # the largest correction, moved by just under its 2 % visible tolerance
    bad[j] += 0.019 * bad[j]
    g = _grade("task-06-3", v, v_mm=bad)
    assert g.visible_ok and not g.hidden_ok
    assert "v_mm = r·(k − 1) with your r and one k" in g.first_failure
    # k rounded to three decimals, as the guide writes 1.037: consistent and accepted
    r = np.array(a["r_mm"])
    k3 = round(tasks.answers("task-06-2", v)["k_mean"], 3)
    assert _grade("task-06-3", v, v_mm=list(r * (k3 - 1))).passed
    assert tasks.get("task-06-3").hidden(v, {"r_mm": ..., "v_mm": a["v_mm"]})[0].answer is None


def test_the_tasks_are_seeded_by_the_variant():
    a = [tasks.answers("task-06-2", v)["k_mean"] for v in VARIANTS]
    assert len(set(a)) == len(a)
    assert tasks.answers("task-06-3", VARIANTS[2]) == tasks.answers("task-06-3", VARIANTS[2])
    assert tasks.inputs("task-06-1", V57).rays.equals(tasks.inputs("task-06-1", variant("21-1157")).rays)


