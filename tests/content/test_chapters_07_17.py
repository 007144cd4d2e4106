"""Chapters 07–17 read against their sources: the numbers the text states follow from the computation."""

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

NB = Path(__file__).resolve().parents[2] / "notebooks"


def _cell(stem, cell_id):
    nb = json.loads((NB / f"{stem}.ipynb").read_text(encoding="utf-8"))
    return next("".join(c["source"]) for c in nb["cells"] if c.get("id") == cell_id)


# ---- chapter 10: the §11 table's shift is printed as computed ------------------------------------------------

def test_ch10_shift_text_follows_the_projection():
    from aerophoto.guide import ch10 as s11
    s = s11.shift_summary()
    assert s["mean_dlon_min"] == pytest.approx(26.2, abs=0.05)
    assert s["mean_dlat_min"] == pytest.approx(9.9, abs=0.05)
    text = _cell("10_ground_control", "example-2-theory")
    m = re.search(r"fall ([\d.]+)′ south and ([\d.]+)′ west", text)
    assert m and (float(m.group(1)), float(m.group(2))) == (round(s["mean_dlat_min"], 1), round(s["mean_dlon_min"], 1))
    assert "27′" not in text


# ---- chapter 11: table 11 without float noise; the transformer says when it first met 0.4 mm ----------------

def test_ch11_table_11_prints_clean_differences():
    from aerophoto import guide
    t = guide.ch11.table_11().table
    col = t["δl = l₀ − l_i, mm"]
    assert list(col) == [-0.5, 0.0, 0.0, -0.3, -0.1, 0.2, -0.7]
    assert "99999" not in guide.ch11.table_11()._repr_html_()


def test_ch11_transformer_reports_first_step_within_tolerance():
    from aerophoto import rectify as rf
    from aerophoto.demos import rectification as dr
    r = dr.transformer_model(0)
    run = r.run
    first = run.within_tolerance_step
    assert first == 6 and run.converged_step == 10
    assert all(s.max_residual_mm <= rf.TOLERANCE_MM for s in run.steps[first:])
    assert run.steps[first - 1].max_residual_mm > rf.TOLERANCE_MM
    table = r.table()["value"]
    assert table["every point within 0.4 mm from step"] == "6"
    assert table["first full cycle within 0.4 mm ends at step"] == "10"


# ---- chapter 16: correlated node errors are not averaged down ------------------------------------------------

def test_ch16_correlated_node_errors():
    from aerophoto import dem
    assert dem.correlated_noise_factor(30.0, 0.0) == pytest.approx(4 / 9, rel=1e-3)  # independent: the 8 cm
    assert dem.correlated_noise_factor(30.0, 1e7) == pytest.approx(1.0, abs=1e-5)    # fully shared: all 12 cm
    ks = [dem.correlated_noise_factor(30.0, L) for L in (10.0, 30.0, 100.0, 300.0)]
    assert all(a < b for a, b in zip(ks, ks[1:]))
    assert 11.0 < math.sqrt(dem.correlated_noise_factor(30.0, 300.0)) * 12 < 12.0
    with pytest.raises(ValueError, match="corr_length_m"):
        dem.correlated_noise_factor(30.0, -1.0)


def test_ch16_sd3_audit_numbers():
    text = _cell("16_dem_contours", "sd3-audit")
    assert f"{31 * math.sqrt(2):.1f}" in text and f"{math.sqrt(2 * 31**2 - 14**2):.1f}" in text
    assert f"{12 * math.sqrt(2):.1f}" in text and f"{math.sqrt(2 * 12**2 - 14**2):.1f}" in text


# ---- chapter 08: task 08.3 names the banner's scale; chapter 07: task 07.3 on the unbiased base ----------------

def test_ch08_width_with_the_flight_scale_gets_its_hint():
    from aerophoto import checks, tasks
    from aerophoto.variants import variant_for_index
    v = variant_for_index(17)
    lab = tasks.inputs("task-08-3", v)
    w = tasks.answers("task-08-3", v)["width_m"]
    assert abs(v.m / lab.m - 1) > 0.2  # the flight's 1:m and the photo's own scale differ
    g = checks.grade_task("task-08-3", v, {"width_m": w * v.m / lab.m})
    assert not g.passed and "scale of your variant's flight" in g.checks[0][2]
    text = _cell("08_interpretation", "task-08-3")
    assert "lab.m" in text and "not the 1:m of your variant" in text


def test_ch07_task_3_uses_the_base_of_the_normalised_pair():
    from aerophoto import stereo as st
    from aerophoto import tasks
    from aerophoto.labs import ch07
    from aerophoto.variants import variant_for_index
    v = variant_for_index(63)  # f = 730 mm: the pricked base is 2.9 % long
    lab = ch07.stereo_lab(v)
    assert lab.b_mm / lab.b_flat_mm - 1 == pytest.approx(0.029, abs=0.001)
    assert lab.b_flat_mm == pytest.approx(lab.B_record_m * v.f_mm / lab.H_m)
    a = tasks.answers("task-07-3", v)
    h = v.Zmax_m - v.Zmin_m
    assert a["dp_relief_mm"] == pytest.approx(lab.b_flat_mm * h / (lab.H_m - h))
    assert a["V"] == pytest.approx(float(st.vertical_exaggeration(lab.b_flat_mm, v.f_mm, 65.0, 250.0)))


# ---- chapter 09: the third way of §10, similar figures -------------------------------------------------------

def test_ch09_similar_figures():
    from aerophoto.demos import plan_correction as pc
    P = np.array([[-60.0, -40.0], [30.0, -40.0], [60.0, 55.0], [-40.0, 58.0]])
    M = np.array([[1.1, 0.2], [-0.1, 0.9]])
    Q = P @ M.T + [5.0, -3.0]  # an affine pair: similar figures are exact
    xy = np.array([[0.0, 0.0], [20.0, 10.0], [-30.0, 30.0]])
    np.testing.assert_allclose(pc.similar_figures_transfer(P, Q, xy), xy @ M.T + [5.0, -3.0], atol=1e-9)
    study = pc.three_methods_study((3.0,))
    sim, prop, cen = study.iloc[0]
    assert 0.8 < sim < 1.5 and abs(sim / prop - 1) < 0.15 and cen < 0.1
