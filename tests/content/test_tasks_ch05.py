"""Chapter 05's graded tasks (aerophoto.tasks.ch05): the student's own fotoschema, its seams and its mean scale;
the student's sheet (aerophoto.demos.fotoschema); and what guide §6 prints (aerophoto.guide.ch05)."""

import math
import re

import numpy as np
import pytest

from aerophoto import checks, tasks
from aerophoto.course import score
from aerophoto import geometry as g
from aerophoto import mosaic as mo
from aerophoto.labs import ch05 as lab05
from aerophoto.labs import own as _own
from aerophoto.tasks import ch05
from aerophoto.variants import variant, variant_for_index

V3 = variant_for_index(3)
V57 = variant("19-0457")


# --------------------------------------------------------------------------- the student's own fotoschema
def test_the_chapter_registers_its_tasks():
    t1, t2 = tasks.chapter_tasks("05")
    assert (t1.id, t2.id) == ("task-05-1", "task-05-2") and (t1.points, t2.points) == (4, 4)
    assert t1.names == ("dI_mm", "m_rms_mm", "n_cutouts", "seams_ok")
    assert t2.names == ("l_mm", "L_mm", "m_i", "m_mean")
    assert not t1.cross_variant and not t2.cross_variant


@pytest.mark.parametrize("i", [0, 3, 57, 99])
def test_each_student_glues_their_own_strip(i):
    v = variant_for_index(i)
    own = lab05.own_fotoschema(v)
    assert own.fs.camera.f_mm == v.f_mm and own.fs.m_design == v.m and own.fs.scale.M == v.M
    assert own.numbers == (36, 37, 38, 39) and len(own.fs.seams) == 3
    # near-vertical photos, tilts capped at 2° and at f·tg α ≤ 6 mm (the photos stay on the site)
    cap = min(2.0, math.degrees(math.atan(6.0 / v.f_mm)))
    assert max(s.pose.alpha_deg for s in own.strip.shots) <= cap + 1e-9
    # flown at H = f·m above the site's mean height, over the site's true relief (the variants' 30 m)
    assert own.strip.H_m == pytest.approx(g.flying_height_m(v.f_mm, v.m))
    assert own.site.z_max_m - own.site.z_min_m == pytest.approx(v.Zmax_m - v.Zmin_m)
    assert own.point_names == ("36a", "36b", "39a", "39b")


def test_strips_lie_at_places_of_their_own():
    starts = {i: _own.own_strip(variant_for_index(i))[0].start_m for i in range(0, 100, 7)}
    assert len({(round(x), round(y)) for x, y in starts.values()}) == len(starts)
    site = _own.own_strip(V3)[1]
    centre = np.array(site.centre_m)
    s0 = _own.own_strip(variant_for_index(0))[0]  # variant 00 is not the worked example through the centre
    assert np.hypot(*(s0.centres_m[:, :2].mean(axis=0) - centre)) > 300.0
    assert _own.own_strip(V3)[0] is _own.own_strip(variant("20-1103"))[0]  # built once per variant


def test_the_readings_are_the_truth_read_to_a_tenth_of_a_millimetre():
    for v in (variant_for_index(0), V57, variant_for_index(99)):
        own = lab05.own_fotoschema(v)
        t = lab05.seam_readings(v)
        d = own.details
        assert len(t) == d.dI_mm.size == own.fs.dI_mm.size
        for col in ("contour from the cut, mm", "prick from the cut, mm"):
            assert all(x == round(x, 1) and str(x) != "-0.0" for x in t[col])
        assert np.all(np.abs(t["contour from the cut, mm"] - d.contour_from_cut_mm) <= 0.05 + 1e-9)
        assert np.all(np.abs(t["prick from the cut, mm"] - d.prick_from_cut_mm) <= lab05.PRICK_MAX_MM + 0.05 + 1e-9)
        a = lab05.answers_of(v)
        assert np.all(np.abs(np.array(a["dI_mm"]) - d.dI_mm) <= 0.05 + lab05.PRICK_MAX_MM + 0.05 + 1e-9)
        assert a["m_rms_mm"] == pytest.approx(math.sqrt(np.mean(d.dI_mm ** 2)), abs=0.12)
        p = lab05.scale_readings(v)
        truth_sheet, truth_plan = own.fs.scale.sheet_mm, own.plan_xy_mm()
        assert np.all(np.abs(p[["along the strip, mm", "across, mm"]].to_numpy() - truth_sheet) <= 0.15 + 1e-9)
        assert np.all(np.abs(p[["x (north) on the plan, mm", "y (east) on the plan, mm"]].to_numpy() - truth_plan)
                      <= 0.15 + 1e-9)
        # the plan is in the geodetic convention: x north = ground Y, y east = ground X, at 1:M
        G = own.fs.scale.ground_m
        assert np.allclose(truth_plan, np.column_stack([G[:, 1], G[:, 0]]) * 1000.0 / v.M)
        # the bases and scales from the readings are the truth within the reading error
        assert np.allclose(a["l_mm"], own.fs.scale.l_mm, atol=0.3)
        assert np.allclose(a["L_mm"], own.fs.scale.L_mm, atol=0.3)
        assert a["m_mean"] == pytest.approx(own.fs.scale.m, rel=1e-3)
        # the guide's point: the mean scale is near the photos' design scale, nearer the higher the flight
        assert abs(a["m_mean"] / v.m - 1) < 0.02


def test_high_flights_leave_seams_within_the_reading_error():
    # ΔI ≈ b·h/H: 30 m of relief at H = 1200 m (variant 00) against H = 23 871 m (variant 99)
    low, high = lab05.own_fotoschema(variant_for_index(0)), lab05.own_fotoschema(variant_for_index(99))
    assert np.max(np.abs(low.details.dI_mm)) > 0.2
    assert np.max(np.abs(high.details.dI_mm)) < 0.1


def test_inputs_are_the_readings_and_fresh_each_time():
    t = tasks.inputs("task-05-1", V3)
    assert t.equals(lab05.seam_readings(V3))
    assert list(t.columns) == ["y across, mm", "contour from the cut, mm", "prick from the cut, mm"]
    assert list(dict.fromkeys(t.index.get_level_values(0))) == ["36/37", "37/38", "38/39"]
    t.iloc[0, 1] = 99.0  # a student changing the table does not change the task
    assert tasks.inputs("task-05-1", V3).iloc[0, 1] != 99.0
    p = tasks.inputs("task-05-2", V3)
    assert list(p.index) == ["36a", "36b", "39a", "39b"]


def _by_hand(task_id, v):
    """What a student computes from the data cell's table."""
    t = tasks.inputs(task_id, v)
    if task_id == "task-05-1":
        dI = np.round(t["contour from the cut, mm"].to_numpy() - t["prick from the cut, mm"].to_numpy(), 1)
        return {"dI_mm": list(dI), "m_rms_mm": float(np.sqrt(np.mean(dI ** 2))), "n_cutouts": int(np.sum(dI < 0)),
                "seams_ok": bool(dI.min() >= -0.5)}
    S = t[["along the strip, mm", "across, mm"]].to_numpy()
    P = t[["x (north) on the plan, mm", "y (east) on the plan, mm"]].to_numpy()
    pairs = [(0, 2), (1, 3), (0, 3), (1, 2)]
    l = np.array([np.hypot(*(S[j] - S[i])) for i, j in pairs])
    L = np.array([np.hypot(*(P[j] - P[i])) for i, j in pairs])
    m_i = L * 10000 / l
    return {"l_mm": l, "L_mm": L, "m_i": m_i, "m_mean": float(np.mean(m_i))}


@pytest.mark.parametrize("task_id", ["task-05-1", "task-05-2"])
def test_a_students_own_computation_passes(task_id):
    for v in (variant_for_index(0), V3, V57):
        g_ = score.grade_task(task_id, v, _by_hand(task_id, v))
        assert g_.passed and g_.score == g_.points == 4, g_.checks
        assert any(hidden for *_, hidden in g_.checks)


def test_the_answers_hold_together():
    a = lab05.answers_of(V3)
    t1, t2 = tasks.get("task-05-1"), tasks.get("task-05-2")
    assert t1.answers(V3) == {k: a[k] for k in t1.names} and t2.answers(V3) == {k: a[k] for k in t2.names}
    dI = np.array(a["dI_mm"])
    assert a["m_rms_mm"] == pytest.approx(math.sqrt(np.sum(dI ** 2) / dI.size))
    assert a["n_cutouts"] == int(np.sum(dI < 0)) and a["seams_ok"] == bool(dI.min() >= -0.5)
    assert a["m_i"] == pytest.approx(list(np.array(a["L_mm"]) * 10000 / np.array(a["l_mm"])))
    assert t1.answer("dI_mm").tol_abs == 0.05 and t2.answer("m_i").tol_rel == ch05.TOL_SCALE


def test_typical_slips_are_recognised():
    v = variant_for_index(0)  # mismatches of several tenths: every slip differs from the answer
    ref = _by_hand("task-05-1", v)
    dI = np.array(ref["dI_mm"])
    for hint, value in tasks.get("task-05-1").slips(v)["m_rms_mm"].items():
        with pytest.raises(checks.WrongAnswer, match=re.escape(hint[:20])):
            checks.check_task("task-05-1", v, **{**ref, "m_rms_mm": value})
    if abs(int(np.sum(dI > 0)) - ref["n_cutouts"]) >= 2:  # (one off reads as a rounding slip of a count)
        with pytest.raises(checks.WrongAnswer, match="duplicates"):
            checks.check_task("task-05-1", v, **{**ref, "n_cutouts": int(np.sum(dI > 0))})
    with pytest.raises(checks.WrongAnswer, match="every sign is wrong"):  # prick − contour: the signs reversed
        checks.check_task("task-05-1", v, **{**ref, "dI_mm": list(-dI)})
    ref2 = _by_hand("task-05-2", v)
    with pytest.raises(checks.WrongAnswer, match="not the inverse"):
        checks.check_task("task-05-2", v, **{**ref2, "m_mean": float(np.mean(ref2["l_mm"] * 10000 / ref2["L_mm"]))})
    with pytest.raises(checks.WrongAnswer, match="denominator M"):
        checks.check_task("task-05-2", v, **{**ref2, "m_mean": float(np.mean(ref2["L_mm"] / ref2["l_mm"]))})
    with pytest.raises(checks.WrongAnswer, match="reverse order"):
        checks.check_task("task-05-2", v, **{**ref2, "l_mm": list(ref2["l_mm"])[::-1]})


def test_hidden_checks_catch_inconsistent_answers():
    v = V3
    ref1 = _by_hand("task-05-1", v)
    # an RMS, a count or a verdict that does not follow from the student's own ΔI
    for bad in ({"m_rms_mm": ref1["m_rms_mm"] + 0.1}, {"n_cutouts": ref1["n_cutouts"] + 1},
                {"seams_ok": not ref1["seams_ok"]}):
        hs = tasks.get("task-05-1").hidden(v, {**ref1, **bad})
        assert not all(score.hidden_ok(h)[0] for h in hs), bad
    # a ΔI of 0.0 written −0.04 (within the visible 0.05 mm) with the true count: every visible check passes, but
    # the count does not follow from the student's own ΔI — and the screen says so, as the grader does
    d = list(ref1["dI_mm"])
    k = d.index(0.0)
    d[k] = -0.04
    g_ = score.grade_task("task-05-1", v, {**ref1, "dI_mm": d})
    assert g_.visible_ok and not g_.hidden_ok and g_.score == 0
    assert "n_cutouts from your ΔI" in g_.first_failure
    with pytest.raises(checks.WrongAnswer, match="n_cutouts from your ΔI"):
        checks.check_task("task-05-1", v, **{**ref1, "dI_mm": d})
    # the mean scale: m_i must come from the student's own l and L, m from their own m_i
    ref2 = _by_hand("task-05-2", v)
    hs = tasks.get("task-05-2").hidden(v, {**ref2, "m_i": ...})
    assert not any(score.hidden_ok(h)[0] for h in hs)
    far = {**ref2, "l_mm": list(np.array(ref2["l_mm"]) * 1.01)}   # bases changed afterwards, m_i left as they were
    assert "m_i from your l and L" in [n for n, ok, _, hid in score.grade_task("task-05-2", v, far).checks
                                       if hid and not ok]
    # rounding m_i to whole numbers, or l and L to four digits, is consistent
    assert score.grade_task("task-05-2", v, {**ref2, "m_i": list(np.round(ref2["m_i"]))}).passed
    assert score.grade_task("task-05-2", v, {**ref2, "l_mm": [float(f"{x:.4g}") for x in ref2["l_mm"]]}).passed


def test_the_design_scale_typed_for_every_m_i_is_named_where_it_is_told_apart():
    # for variant 57 the photos' scale 1:17 700 lies within 0.05 % of two partial scales — there it is the answer
    # within the tolerance; on the others it is named, on screen as in the grader
    ref = _by_hand("task-05-2", V57)
    g_ = score.grade_task("task-05-2", V57, {**ref, "m_i": [V57.m] * 4, "m_mean": V57.m})
    assert not g_.passed and "design scale" in g_.first_failure
    with pytest.raises(checks.WrongAnswer, match="design scale"):
        checks.check_task("task-05-2", V57, **{**ref, "m_i": [V57.m] * 4, "m_mean": V57.m})


def test_photo_axis_towards():
    assert g.photo_axis_towards([71.8, -2.1]) == (0, 1.0)
    assert g.photo_axis_towards([3.0, -70.0]) == (1, -1.0)
    assert g.photo_axis_towards(np.array([-5.0, 0.0])) == (0, -1.0)


# --------------------------------------------------------------------------- the student's sheet
def test_the_measuring_figure_shows_the_work_not_the_answers():
    from aerophoto.demos.fotoschema import own_sheet_figure

    fig = own_sheet_figure(V57)
    ax = fig.axes[0]
    texts = [t.get_text() for t in ax.texts] + [ax.get_title()]
    assert {"36a", "36b", "39a", "39b", "cut 36/37"} <= set(texts)
    from aerophoto.i18n.numfmt import numbers_in

    assert 17700 in numbers_in(ax.get_title())  # the design scale: an input (1:17 700, the book's format)
    a = lab05.answers_of(V57)
    shown = " ".join(texts)
    assert f"{a['m_mean']:.0f}" not in shown and "ΔI" not in shown and "m =" not in shown


def test_student_sheet_is_signed_with_the_computed_scale_on_a3(tmp_path, capsys):
    from aerophoto.demos.fotoschema import PAPER_MM, finished_sheet, sheet_paper, student_sheet

    fig = student_sheet(V57, "Ivanova A.", year=2025)
    assert fig.aerophoto_paper == "A3"
    texts = " ".join(t.get_text() for t in fig.texts)
    from aerophoto.i18n.numfmt import fmt_count

    m_txt = fmt_count(int(round(lab05.answers_of(V57)['m_mean'] / 100) * 100), lang="ru")
    assert f"М 1:{m_txt}" in texts and "Ivanova A., record book 19-0457" in texts and "2025" in texts
    assert "ФОТОСХЕМА" in texts and "Проверил" in texts
    # every variant's sheet fits A3 at true size, the largest variant too
    for i in (0, 17, 77, 99):
        assert sheet_paper(lab05.own_fotoschema(variant_for_index(i)).fs)[0] == "A3"
    assert PAPER_MM["A3"] == (420.0, 297.0)
    # in the notebook: not before task 05.2 has passed
    assert finished_sheet(V57, "Ivanova A.", answered=False) is None
    assert "Answer task 05.2 first" in capsys.readouterr().out
    shown = finished_sheet(V57, "Ivanova A.", answered=True, folder=tmp_path)
    assert shown is not None and "A3" in shown.alt
    assert (tmp_path / "fotoschema_19-0457.pdf").read_bytes().startswith(b"%PDF-")
    assert (tmp_path / "fotoschema_19-0457.png").read_bytes()[:4] == b"\x89PNG"
    with pytest.raises(FileExistsError):
        finished_sheet(V57, "Ivanova A.", answered=True, folder=tmp_path)


# --------------------------------------------------------------------------- guide §6
def test_the_book_uses_the_guides_printed_rules():
    import inspect

    from aerophoto import guide

    assert guide.ch05.rule("steps 5, 8", "largest cut-out").value == mo.ALLOWED_CUTOUT_MM == 0.5
    lo, hi = guide.ch05.rule("step 8", "spacing").value
    assert lo <= mo.CHECK_SPACING_MM <= hi
    margin = inspect.signature(mo.choose_tie_points).parameters["margin_mm"].default
    assert tuple(margin) == guide.ch05.rule("step 2", "distance of the tie points").value
    assert guide.ch05.rule("step 7", "bases").value == 0.1
    assert guide.ch05.rule("step 5", "the sheet").value == guide.ch05.SHEET == "A3"
    with pytest.raises(KeyError, match="step 9"):
        guide.ch05.rule("step 9", "anything")
    t = guide.ch05.rules_table()
    assert len(t) == len(guide.ch05.RULES) and list(t.columns)[:4] == ["where", "quantity", "value", "unit"]
    assert [f.number for f in guide.ch05.FORMULAS] == ["6.1", "6.2"]
    assert any("13000" in m.printed_text for m in guide.ch05.MARGINALIA)


def test_four_prints_at_60_percent_just_fill_a3():
    from aerophoto import guide

    assert guide.ch05.strip_length_mm(4, 60) == pytest.approx(180 + 3 * 72)  # 396 mm
    assert guide.ch05.strip_length_mm(5, 60) == pytest.approx(468.0)
    assert guide.ch05.strip_length_mm(4, 60, trim_mm=15) == pytest.approx(426.0)
    assert guide.ch05.prints_on_sheet() == 4
    assert guide.ch05.prints_on_sheet(trim_mm=15) == 3  # with the guide's 1.5 cm trim A3 holds three
    assert guide.ch05.prints_on_sheet((594.0, 420.0)) == 6  # A2
    text = " ".join(guide.ch05.remarks())
    assert "396" in text and "468" in text and "0.5–1" in text and "13000" in text
    with pytest.raises(ValueError, match="px_percent"):
        guide.ch05.strip_length_mm(4, 100)
    with pytest.raises(ValueError, match="n_photos"):
        guide.ch05.strip_length_mm(0)


def test_the_fotoschema_of_four_prints_matches_the_strip_length():
    # the sheet of the book's worked example (four untilted prints over flat ground) is as long as §6 says
    from aerophoto import simulate as sim
    from aerophoto import guide

    fs = mo.assemble(sim.fly_strip(g.Camera(100), 12000, 60, 4))
    x0, x1, _, _ = fs.extent_mm
    assert x1 - x0 == pytest.approx(guide.ch05.strip_length_mm(4, 60), abs=1e-6)
    assert len(fs.scale.names) == len(fs.scale.l_mm) == guide.ch05.rule("step 7", "points").value == 4
