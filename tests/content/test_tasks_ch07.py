"""Chapter 07's graded tasks (aerophoto.tasks.ch07): the student's own stereo pair, for every variant."""

import math

import numpy as np
import pytest

from aerophoto import checks, tasks
from aerophoto.course import score
from aerophoto import stereo as st
from aerophoto.labs import ch07
from aerophoto.variants import variant_for_index

V3 = variant_for_index(3)
IDS = ("task-07-1", "task-07-2", "task-07-3")


def _reference(task_id, v):
    """What the notebook's student computes from the data cells (the task texts' formulas)."""
    lab = tasks.inputs("task-07-1", v)
    b1 = math.hypot(*lab.base_table().iloc[0])
    b2 = math.hypot(*lab.base_table().iloc[1])
    b = (b1 + b2) / 2
    if task_id == "task-07-1":
        c = lab.control_table().iloc[0]
        pA = c["x left, mm"] - c["x right, mm"]
        return {"b_mm": b, "pA_mm": pA, "ZS_m": c["Z, m"] + lab.B_record_m * v.f_mm / pA}
    if task_id == "task-07-2":
        t = lab.objects_table()
        out, dps = {}, []
        for name, key in zip(ch07.OBJECT_LABELS, ("dhA_m", "dhB_m", "dhC_m", "dhD_m")):
            top, foot = t.loc[(name, "top")], t.loc[(name, "foot")]
            pf = foot["x left, mm"] - foot["x right, mm"]
            dp = (top["x left, mm"] - top["x right, mm"]) - pf
            H = lab.B_record_m * v.f_mm / pf
            dps.append(dp)
            out[key] = H * dp / (pf + dp)
        return {"dp_mm": dps, **out}
    d = tasks.inputs("task-07-3", v)
    h, H = d["h_m"], v.f_mm / 1000 * v.m
    b0 = d["B_m"] * d["f_mm"] / H  # the base of the normalised pair, not the pricked principal points' b
    return {"dp_relief_mm": b0 * h / (H - h), "V": (b0 / v.f_mm) / (d["eye_base_mm"] / d["viewing_distance_mm"])}


@pytest.mark.parametrize("i", range(100))
def test_every_variant_has_its_pair_and_its_answers_pass(i):
    v = variant_for_index(i)
    lab = ch07.stereo_lab(v)
    assert lab.camera.f_mm == v.f_mm and lab.m == v.m
    assert lab.left.pose.Z_m == lab.right.pose.Z_m  # both stations at one height
    assert len(lab.objects_table()) == 8 and list(lab.truth().index) == list(ch07.OBJECT_LABELS)
    # measured values carry the reading error: round to 0.01 mm, the y-parallax no more than noise
    t = lab.objects_table()
    assert np.all(np.abs(t["y left, mm"] - t["y right, mm"]) <= 0.06)
    for task_id in IDS:  # a student's own computation from the tables (the sweep tries the reference and roundings)
        grade = score.grade_task(task_id, v, _reference(task_id, v))
        assert grade.passed and grade.score == grade.points, (i, task_id, grade.checks)
    # the heights measured agree with the truth within the reading error (4 σ of Δh, plus rounding)
    par = lab.parallaxes().join(lab.truth())
    sigma_dp = math.hypot(2 * ch07.SIGMA_READ_MM, 0.005) * math.sqrt(2)
    sig_h = par["H over the foot, m"] * sigma_dp / par["p foot, mm"]
    assert np.all(np.abs(par["Δh, m"] - par["true Δh, m"]) <= 4 * sig_h + 0.1), par


def test_the_truth_is_the_objects():
    from aerophoto.site import get_site

    lab = ch07.stereo_lab(V3)
    pts = get_site().object_points
    top = lab.points[lab.points["point"] == "top"]
    for (_, r), kind in zip(top.iterrows(), ("roof corner", "tree top", "chimney top", "mast top")):
        P = pts[pts["kind"] == kind][["X_m", "Y_m", "Z_m"]].to_numpy()
        assert np.min(np.linalg.norm(P - r[["X, m", "Y, m", "Z, m"]].to_numpy(float), axis=1)) < 1e-9
    truth = lab.truth()["true Δh, m"]
    assert 2.5 < truth.iloc[0] < 9 and 8 < truth.iloc[1] < 21 and truth.iloc[2] == pytest.approx(42, abs=0.6)
    assert truth.iloc[3] == pytest.approx(64, abs=0.6)
    # the normalised coordinates are the geometry's, plus the reading noise
    xl, xr = lab.normal_xy(top[["X, m", "Y, m", "Z, m"]].to_numpy(float))
    assert np.all(np.abs(top["x left, mm"].to_numpy() - xl[:, 0]) < 0.04)


def test_inputs_and_answers_are_deterministic_and_differ_between_variants():
    a = tasks.answers("task-07-2", V3)
    assert a == tasks.answers("task-07-2", variant_for_index(3))
    b = tasks.answers("task-07-2", variant_for_index(40))
    assert a["dhD_m"] != b["dhD_m"]
    d = tasks.inputs("task-07-3", V3)
    assert d == {"h_m": 30.0, "H_m": V3.f_mm / 1000 * V3.m, "B_m": ch07.stereo_lab(V3).B_record_m, "f_mm": V3.f_mm,
                 "eye_base_mm": 65.0, "viewing_distance_mm": 250.0}


@pytest.mark.parametrize("task_id, name, hint", [
    ("task-07-1", "b_mm", "planned base"),
    ("task-07-1", "pA_mm", "the sign: the x-parallax"),
    ("task-07-1", "ZS_m", "add A's own height"),
    ("task-07-1", "ZS_m", "not the photo base"),
    ("task-07-2", "dhD_m", "base mix-up"),
    ("task-07-2", "dhD_m", "small-Δp form"),
    ("task-07-2", "dhD_m", "air base B is in metres"),
    ("task-07-3", "dp_relief_mm", "small form"),
    ("task-07-3", "V", "not the other way round"),
    ("task-07-3", "dp_relief_mm", "pricked principal points"),
])
def test_typical_slips_are_named(task_id, name, hint):
    v = V3
    ref = _reference(task_id, v)
    slips = tasks.get(task_id).slips(v)
    if name == "pA_mm":
        wrong = -ref["pA_mm"]
    else:
        wrong = next(val for h, val in slips[name].items() if hint in h and val is not None)
    got = dict(ref)
    got[name] = wrong
    checks.reset()
    with pytest.raises(checks.WrongAnswer, match=hint.split("'")[0][:20]):
        checks.check_task(task_id, v, **got)


def test_unit_mix_ups_are_named():
    v = V3
    ref = _reference("task-07-2", v)
    got = dict(ref, dhC_m=ref["dhC_m"] * 1000)  # f in mm where metres belong
    with pytest.raises(checks.WrongAnswer, match="factor of 1000"):
        checks.check_task("task-07-2", v, **got)
    got = dict(ref, dp_mm=[-x for x in ref["dp_mm"]])
    with pytest.raises(checks.WrongAnswer, match="sign"):
        checks.check_task("task-07-2", v, **got)


def test_hidden_checks_catch_inconsistent_answers():
    v = V3
    ref = _reference("task-07-1", v)
    # Z_S that the submitted parallax of A does not give (written to four digits, 1777 m, it would: that passes)
    assert not score.grade_task("task-07-1", v, dict(ref, ZS_m=ref["ZS_m"] + 3.0)).hidden_ok
    assert score.grade_task("task-07-1", v, dict(ref, ZS_m=float(f"{ref['ZS_m']:.4g}"))).passed
    ref2 = _reference("task-07-2", v)
    bad2 = dict(ref2, dhB_m=ref2["dhB_m"] + 0.5)   # a height that does not follow from its own Δp
    g2 = score.grade_task("task-07-2", v, bad2)
    assert not g2.hidden_ok and "dhB_m from your own Δp" in [n for n, ok, _, h in g2.checks if h and not ok]
    ref3 = _reference("task-07-3", v)
    bad3 = dict(ref3, V=ref3["V"] * 1.004)
    g3 = score.grade_task("task-07-3", v, bad3)
    assert g3.visible_ok and not g3.hidden_ok


def test_large_variants_are_computed_honestly():
    """Variant 99 (f = 1090 mm, 1:21 900): B/H ≈ 0.07, a house gives hundredths of a millimetre of parallax."""
    v = variant_for_index(99)
    lab = ch07.stereo_lab(v)
    assert lab.H_m == pytest.approx(1090 / 1000 * 21900)
    a = tasks.answers("task-07-3", v)
    assert a["V"] < 0.3
    assert st.parallax_difference_mm(5.0, lab.b_mm, lab.H_m) < 0.02
