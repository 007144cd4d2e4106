"""Chapters 07–17 read against their sources: the numbers the text states follow from the computation."""

import json
import math
import re
from pathlib import Path

import numpy as np
import pytest

NB = Path(__file__).resolve().parents[1] / "notebooks"


def _cell(stem, cell_id):
    nb = json.loads((NB / f"{stem}.ipynb").read_text(encoding="utf-8"))
    return next("".join(c["source"]) for c in nb["cells"] if c.get("id") == cell_id)


# ---- chapter 10: the §11 table's shift is printed as computed ------------------------------------------------

def test_ch10_shift_text_follows_the_projection():
    from aerophoto.guide import s11
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
    t = guide.s12.table_11().table
    col = t["δl = l₀ − l_i, mm"]
    assert list(col) == [-0.5, 0.0, 0.0, -0.3, -0.1, 0.2, -0.7]
    assert "99999" not in guide.s12.table_11()._repr_html_()


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
