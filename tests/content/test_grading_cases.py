"""The cases issue 27 names, one test each: what the screen says is what the grader gives, and the hint points
the right way."""

from __future__ import annotations

import math

import numpy as np
import pytest

from aerophoto import checks, stereo, tasks
from aerophoto.labs.ch07 import stereo_lab
from aerophoto.labs.ch09 import plan_correction_lab
from aerophoto.labs.ch10 import resection_lab
from aerophoto.labs.ch11 import paper_lab
from aerophoto.tasks import rounding
from aerophoto.variants import variant_for_index

from .grading_sweep import run


def _both(task_id, i, **changes):
    """(screen ok, screen text, grader score, points) for the reference answers of variant i with ``changes``."""
    v = variant_for_index(i)
    task = tasks.get(task_id)
    o = run(task, v, "case", {**task.answers(v), **changes})
    return o


def _passes(task_id, i, **changes):
    o = _both(task_id, i, **changes)
    assert o.screen_ok and o.full_marks, (o.screen_text, o.grade_text)
    return o


def _fails_with(task_id, i, words, **changes):
    o = _both(task_id, i, **changes)
    assert not o.screen_ok and not o.full_marks, (o.screen_text, o.grade_text)
    assert words in o.screen_text, o.screen_text
    return o


# ------------------------------------------------------------------------------------------------ 07.3
def _small_form(i):
    v = variant_for_index(i)
    lab = stereo_lab(v)
    return float(stereo.parallax_difference_mm(v.Zmax_m - v.Zmin_m, lab.b_flat_mm, lab.H_m, approx=True))


def test_07_3_small_form_is_accepted_where_it_agrees_and_named_where_it_does_not():
    task = tasks.get("task-07-3")
    accepted = [i for i in range(100) if task._small_form(variant_for_index(i))[1]]
    assert 0 < len(accepted) < 100 and 0 not in accepted and 99 in accepted
    # a high variant: the small form agrees with the exact one within the tolerance — both say so
    _passes("task-07-3", 99, dp_relief_mm=_small_form(99))
    _passes("task-07-3", 99, dp_relief_mm=rounding.round_to(_small_form(99), 0.0001))
    # the guide's own example (variant 00): 2.5 % off — named on screen, 0 from the grader
    _fails_with("task-07-3", 0, "small form", dp_relief_mm=_small_form(0))
    # no variant in between: told apart, or within the tolerance even when written to 0.0001 mm
    for i in range(100):
        small, ok = task._small_form(variant_for_index(i))
        dp = task.answers(variant_for_index(i))["dp_relief_mm"]
        assert ok == (abs(small - dp) + rounding.allowance(dp, 0.0001) <= 0.005)
        assert ok or abs(small - dp) > 0.005


def test_07_3_the_base_itself_is_named_not_another_variant():
    v = variant_for_index(62)
    b0 = stereo_lab(v).b_flat_mm
    o = _fails_with("task-07-3", 62, "base b₀", dp_relief_mm=b0)
    assert "variant" not in o.screen_text


# ------------------------------------------------------------------------------------------------ 09.2
def test_09_2_the_road_measured_on_the_photo_is_named_on_screen_and_scores_0():
    for i in (0, 17, 57):
        v = variant_for_index(i)
        lab = plan_correction_lab(v)
        p = lab.photo_of("new road")
        on_photo = float(np.sum(np.hypot(*np.diff(p, axis=0).T))) * float(v.m) / 1000.0
        _fails_with("task-09-2", i, "measured on the photo", road_m=on_photo)


# ------------------------------------------------------------------------------------------------ 10.2
def test_10_2_gamma_written_to_its_stated_precision_keeps_full_marks():
    for i in (1, 4, 57, 93):
        v = variant_for_index(i)
        ch = resection_lab(v).check
        g = rounding.round_to(ch.computed_deg, 0.001)
        _passes("task-10-2", i, gamma_calc_deg=g)                                   # Δγ from the unrounded γ
        _passes("task-10-2", i, gamma_calc_deg=g, dgamma_arcsec=math.remainder(     # Δγ from the written γ
            resection_lab(v).angles_deg["gamma"] - g, 360.0) * 3600.0)


# ------------------------------------------------------------------------------------------------ 11.1
def test_11_1_exact_diagonals_and_a_rounded_K_d_keep_full_marks():
    task = tasks.get("task-11-1")
    for i in range(0, 100, 9):
        v = variant_for_index(i)
        exact = task.other_sums(v, exact=True)
        _passes("task-11-1", i, **exact)
        K = task.answers(v)["K_d"]
        k3 = float(f"{K:.3g}")                     # e.g. −0.00131: three significant digits
        _passes("task-11-1", i, K_d=k3, t_mm=task.answers(v)["t_mm"])
        _fails_with("task-11-1", i, "sign", K_d=-K)
    lab = paper_lab(variant_for_index(0))
    assert not np.allclose(lab.l0_mm, np.round(lab.l0_mm, 2))   # the diagonals are not exact to 0.01 mm


# ------------------------------------------------------------------------------------------------ hints
def test_07_1_stations_from_the_nominal_height_are_named_not_more_digits():
    v = variant_for_index(0)
    lab = stereo_lab(v)
    o = _fails_with("task-07-1", 0, "nominal flying height",
                    ZS_m=float(lab.control["Z, m"]) + lab.f_mm / 1000.0 * float(v.m))
    assert "more digits" not in o.screen_text


def test_12_1_the_guides_example_base_is_named_not_another_variant():
    from aerophoto import triangulation as tri
    from aerophoto.tasks.ch12 import N_BASES, zhukov_inputs

    for i in (2, 5, 40):
        v = variant_for_index(i)
        kw = zhukov_inputs(v).zhukov_kwargs()
        o = _fails_with("task-12-1", i, "example base b = 60 mm", m3_mm=tri.zhukov_error_mm(N_BASES, **{**kw,
                                                                                                     "b_mm": 60.0}))
        assert "variant" not in o.screen_text


def test_11_2_a_residual_scaled_again_is_named():
    task = tasks.get("task-11-2")
    v = variant_for_index(6)
    d1 = task.answers(v)["d1_mm"]
    kt = float(v.m) / 10000.0
    o = _both("task-11-2", 6, d1_mm=d1 * kt)
    if not o.screen_ok:
        assert "variant" not in o.screen_text and "K_t" in o.screen_text, o.screen_text


def test_14_2_the_large_n_form_gets_its_own_hint():
    v = variant_for_index(3)
    d = tasks.answers("task-14-2", v)["d_mm"]
    o = _fails_with("task-14-2", 3, "large-n form", m20_mm=d * math.sqrt(20**3 / 3))
    assert "more digits" not in o.screen_text


def test_09_1_swapped_row_and_column_are_named_not_a_rounding():
    for i in range(100):
        a = tasks.answers("task-09-1", variant_for_index(i))
        if a["row"] != a["col"]:
            o = _fails_with("task-09-1", i, "swapped", row=a["col"], col=a["row"])
            assert "rounds" not in o.screen_text
            return
    pytest.fail("no variant with row ≠ col")


def test_13_3_one_class_too_few_is_a_miscount_not_a_rounding():
    v = variant_for_index(0)
    k = tasks.answers("task-13-3", v)["k"]
    o = _fails_with("task-13-3", 0, "np.unique", k=k - 1)
    assert "rounds" not in o.screen_text


def test_per_coordinate_plan_errors_are_named():
    v = variant_for_index(57)
    rms = tasks.answers("task-15-2", v)["rms_plan_m"]
    _fails_with("task-15-2", 57, "per coordinate", rms_plan_m=rms / math.sqrt(2))
    mxy = tasks.answers("task-17-2", v)["mxy_m"]
    _fails_with("task-17-2", 57, "one coordinate", mphi_m=mxy)


def test_15_2_a_photo_or_an_index_instead_of_the_point_id_is_named():
    v = variant_for_index(57)
    s = tasks.get("task-15-2").slips(v)["blunder_point"]
    photo = next(x for h, x in s.items() if "photo" in h)
    o = _fails_with("task-15-2", 57, "point's id", blunder_point=photo)
    assert "count" not in o.screen_text.split("blunder_point:")[1]


def test_14_1_the_other_reading_of_the_article_is_accepted_with_its_spacing():
    task = tasks.get("task-14-1")
    v = variant_for_index(71)
    other = task.other_reading(v)
    assert (task.answers(v)["n_plan"], other["n_plan"]) == (8, 7)
    o = _passes("task-14-1", 71, **other)
    assert "other reading" in o.screen_text
    # mixing the readings is caught: the spacing does not follow from the error
    _fails_with("task-14-1", 71, "do not agree", mD_mm=other["mD_mm"])


# ------------------------------------------------------------------------------------------------ the variant
def test_09_u_v_in_an_answer_cell_does_not_change_the_variant(monkeypatch, capsys):
    monkeypatch.setenv("AEROPHOTO_RECORD_BOOK", "19-0457")
    v = variant_for_index(57, "19-0457")
    a = tasks.answers("task-09-1", v)
    u, v_clobbered = np.float64(0.25), np.float64(0.75)   # what `u, v = …` leaves in v
    checks.check_task("task-09-1", v_clobbered, **a)
    out = capsys.readouterr().out
    assert "✓ Task 09.1 passed" in out and "reused the name v" in out and "57" in out
    with pytest.raises(checks.WrongAnswer):
        checks.check_task("task-09-1", v_clobbered, **tasks.answers("task-09-1", variant_for_index(12)))
    checks.reset()
    del u


def test_the_record_is_left_in_the_output_always(monkeypatch):
    from IPython.core.interactiveshell import InteractiveShell

    from aerophoto.course import wire

    shown = []
    monkeypatch.delenv("AEROPHOTO_GRADING", raising=False)
    monkeypatch.setattr("IPython.get_ipython", lambda: InteractiveShell.instance())
    monkeypatch.setattr("IPython.display.display", lambda obj, **kw: shown.append((obj, kw)))
    v = variant_for_index(5)
    a = tasks.answers("task-00-1", v)
    checks.check_task("task-00-1", v, **a)
    (bundle, kw), = shown
    assert kw == {"raw": True} and set(bundle) == {"text/plain", wire.ANSWERS_MIME}
    assert "Task 00.1" in bundle["text/plain"] and "H_m" in bundle["text/plain"]
    rec = bundle[wire.ANSWERS_MIME]
    assert rec["task"] == "task-00-1" and rec["variant"] == 5 and "evidence" not in rec
    assert wire.decode_answers(rec)[1]["H_m"] == pytest.approx(a["H_m"])
    checks.reset()
