"""Chapter 17's physics (aerophoto.budget) and the audits of articles 003 and 000 (aerophoto.guide.ch17, ch16)."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from aerophoto import budget as bu
from aerophoto import guide


# --------------------------------------------------------------------------- the formulas
def test_mean_and_rms_errors():
    assert bu.rms_from_mean(0.1) == pytest.approx(0.125)
    assert bu.mean_from_rms(0.5558) == pytest.approx(0.44464)
    np.testing.assert_allclose(bu.rms_from_mean([0.3, 0.4]), [0.375, 0.5])
    # 1.25 is the article's rounding of √(π/2)
    assert abs(bu.MEAN_TO_RMS - math.sqrt(math.pi / 2)) < 0.004


@given(st.floats(0.0, 1e4))
def test_mean_rms_round_trip(v):
    assert bu.mean_from_rms(bu.rms_from_mean(v)) == pytest.approx(v)


def test_mean_abs_deviation_and_plan_error_by_hand():
    assert bu.mean_abs_deviation([1.0, 2.0, 3.0, 6.0]) == pytest.approx((2 + 1 + 0 + 3) / 4)
    assert bu.plan_error(0.154, 0.078) == pytest.approx(0.17263, abs=1e-5)
    assert bu.plan_error(3.0, 4.0) == 5.0
    with pytest.raises(ValueError, match="values"):
        bu.mean_abs_deviation([1.0])


def test_vectorising_error_is_table1():
    rng = np.random.default_rng(0)
    X = 100 + 0.2 * rng.standard_normal(20)
    Y = 50 + 0.1 * rng.standard_normal(20)
    r = bu.vectorising_error(X, Y, 2000)
    assert r.V_X_m == pytest.approx(np.mean(np.abs(X - X.mean())))
    assert r.V_D_m == pytest.approx(math.hypot(r.V_X_m, r.V_Y_m))
    assert r.m_D_m == pytest.approx(1.25 * r.V_D_m)
    assert r.m_d_mm == pytest.approx(r.m_D_m / 2000 * 1000)
    assert list(r.table().columns)[:3] == ["M_k", "measurements", "V_X, m"]
    with pytest.raises(ValueError, match="equally many"):
        bu.vectorising_error(X, Y[:5], 2000)


def test_triangulation_and_scanning_are_tables_2_and_3():
    assert bu.sigma_um(42) == 21 and bu.sigma_um(16) == 8
    mxy, mD = bu.triangulation_rms_m(15000, 42)
    assert mxy == pytest.approx(0.2646) and mD == pytest.approx(0.37420, abs=1e-5)
    mxy, mD = bu.triangulation_rms_m(10000, 16)
    assert mxy == pytest.approx(0.0672) and mD == pytest.approx(0.0672 * math.sqrt(2))
    with pytest.raises(ValueError, match="P_um = 0"):
        bu.triangulation_rms_m(10000, 0)
    with pytest.raises(ValueError, match="M_c = ∞"):
        bu.triangulation_rms_m(float("inf"), 16)


@given(d=st.floats(0.01, 5.0), n=st.integers(2, 100_000))
def test_transfer_formula_9(d, n):
    m = bu.transfer_rms_mm(d, n)
    assert m == pytest.approx(math.sqrt(n * d * d / (2 * (n - 1))))
    assert m >= d / math.sqrt(2) - 1e-12  # the large-n limit from above


def test_transfer_of_the_article():
    assert bu.transfer_rms_mm() == pytest.approx(0.357143, abs=1e-6)  # (9) on the mean d itself, as printed
    assert bu.transfer_rms_mm(0.5, 10**6) == pytest.approx(0.5 / math.sqrt(2), abs=1e-6)
    # d = 0.5 mm is a mean discrepancy: rule (1) first (0.625 mm RMS), then (9)
    assert bu.transfer_from_mean_mm() == pytest.approx(0.625 * math.sqrt(50 / 98), abs=1e-9)
    assert round(bu.transfer_from_mean_mm(), 3) == 0.446
    assert bu.transfer_from_mean_mm(0.5, 10**6) == pytest.approx(1.25 * 0.5 / math.sqrt(2), abs=1e-6)  # 0.442
    with pytest.raises(ValueError, match="d_mean_mm"):
        bu.transfer_from_mean_mm(-0.5)


def test_relief_limit_and_displacements():
    r_max, r_rms = bu.working_area_radii_mm(230, 60, 30)
    assert r_max == pytest.approx(math.hypot(92, 161) / 2)
    assert r_rms == pytest.approx(math.sqrt((92**2 + 161**2) / 12))
    # formula (2): 0.3 mm at 1:2000 with f = 153 mm at r = 92.7 mm → about 1 m of relief
    h = bu.relief_limit_m(153, 2000, r_max)
    assert h == pytest.approx(0.3 * 153 * 2000 / r_max / 1000)
    # that relief, at that radius, displaces the point by 0.3 mm on the map: δ = r·h/f on the ground
    assert bu.dtm_displacement_m(h, 153, r_max) / 2000 * 1000 == pytest.approx(0.3)
    assert bu.plane_rectification_m(30, 153, r_rms) == pytest.approx(r_rms / 153 * 30 / math.sqrt(12))
    assert bu.dtm_displacement_m(0.0, 153, r_rms) == 0.0
    with pytest.raises(ValueError, match="r_mm = -1"):
        bu.relief_limit_m(153, 2000, -1)


# --------------------------------------------------------------------------- the budget
def test_the_budget_reproduces_the_articles_consistent_numbers():
    """With the article's printed 0.35 mm for the transfer, the budget gives tables 4 and 5 to the printed digit."""
    for case, Mk in zip(bu.ARTICLE_CASES, (10000, 2000)):
        B = bu.budget(**case, transfer_mm=0.35)
        for s in B.stages:
            printed = float(guide.ch17.TABLE4[Mk][s.key])
            unit = 10 ** -len(guide.ch17.TABLE4[Mk][s.key].split(".")[1])
            assert abs(s.rms_m - printed) <= 0.6 * unit, (Mk, s.key, s.rms_m, printed)
        P = guide.ch17.TABLE5[Mk]
        assert abs(B.total_m - float(P["m_D"])) <= 0.006
        assert abs(B.map_rms_mm - float(P["m_d"])) <= 0.006
        assert abs(B.map_mean_mm - float(P["v_d"])) <= 0.006
        assert not B.meets_tolerance and B.dominant.key == "dtm"
    # the book's default, rule (1) then formula (9) (0.446 mm), keeps the verdict, further from 0.4 mm
    for case in bu.ARTICLE_CASES:
        B = bu.budget(**case)
        assert B.stage("transfer").rms_m == pytest.approx(0.446429 * case["M_k"] / 1000, rel=1e-5)
        assert 0.49 < B.map_mean_mm < 0.50 and not B.meets_tolerance
        assert B.dominant.key == "transfer"
    B = bu.budget(**bu.ARTICLE_CASES[1])
    assert round(B.map_rms_mm, 3) == 0.621 and round(B.map_mean_mm, 3) == 0.497
    # with the large-n value 1.25·0.5/√2 = 0.442 mm: m_d = 0.618, v_d = 0.494 mm
    B = bu.budget(**bu.ARTICLE_CASES[1], transfer_mm=1.25 * 0.5 / math.sqrt(2))
    assert round(B.map_rms_mm, 3) == 0.618 and round(B.map_mean_mm, 3) == 0.494


@given(Mc=st.floats(500, 200_000), P=st.floats(1, 200), Mk=st.floats(100, 1e6), mh=st.floats(0, 100))
def test_the_total_is_the_root_sum_square(Mc, P, Mk, mh):
    B = bu.budget(Mc, P, Mk, dtm="dem", m_h_m=mh)
    assert B.total_m == pytest.approx(math.sqrt(sum(s.rms_m**2 for s in B.stages)))
    assert B.total_m >= B.dominant.rms_m - 1e-12
    assert sum(B.shares().values()) == pytest.approx(1.0)
    assert B.map_mean_mm == pytest.approx(B.total_m / Mk * 1000 / 1.25)
    assert B.meets_tolerance == (B.map_mean_mm <= 0.4 + 1e-12)


def test_the_map_defined_stages_do_not_depend_on_the_map_scale():
    a, b = bu.budget(10000, 16, 2000), bu.budget(10000, 16, 10000)
    for key in ("control", "dtm", "ortho", "transfer", "vectorising"):
        assert a.stage(key).rms_m / 2000 == pytest.approx(b.stage(key).rms_m / 10000)
    for key in ("scanning", "triangulation"):
        assert a.stage(key).rms_m == pytest.approx(b.stage(key).rms_m)


def test_the_dem_stage_options_and_the_closing_paragraph():
    inst = bu.budget(10000, 16, 2000)
    dem = bu.budget(10000, 16, 2000, dtm="dem", m_h_m=0.5)
    plane = bu.budget(10000, 16, 2000, dtm="plane", relief_m=0.0)
    _, r_rms = bu.working_area_radii_mm()
    assert dem.stage("dtm").rms_m == pytest.approx(r_rms / 153 * 0.5)
    assert plane.stage("dtm").rms_m == 0.0
    # with the transfer at 0.446 mm a DEM good to 0.5 m alone just misses: v_d = 0.402 mm
    assert not dem.meets_tolerance and round(dem.map_mean_mm, 3) == 0.402 and dem.dominant.key == "transfer"
    assert bu.budget(10000, 16, 2000, dtm="dem", m_h_m=0.5, transfer_mm=bu.transfer_rms_mm()).meets_tolerance
    extra = bu.budget(10000, 16, 2000, extra_stages=True)
    assert extra.stage("interior").rms_m == pytest.approx(0.100, abs=1e-9)
    assert extra.stage("triangulation").rms_m == pytest.approx(inst.stage("triangulation").rms_m * 0.884 / 0.5)
    assert extra.total_m > inst.total_m
    with pytest.raises(ValueError, match="dtm = 'lidar'"):
        bu.budget(dtm="lidar")
    with pytest.raises(KeyError, match="interior"):
        inst.stage("interior")
    t = inst.table()
    assert t.index[-1] == "total, formula (10)" and t["share of variance, %"].iloc[:-1].sum() == pytest.approx(100)


def test_what_if_scenarios():
    s = bu.scenarios(10000, 16, 2000)
    assert list(s.index)[0] == "the article's budget"
    # with the transfer at 0.446 mm a DEM of 0.5 m alone just misses (0.402 mm); the 40 µm transfer rule passes
    assert list(s["v_d ≤ 0.4 mm"]) == [False, False, True, True, False]
    assert s["v_d, mm"].iloc[3] < s["v_d, mm"].iloc[1] < s["v_d, mm"].iloc[0]


# --------------------------------------------------------------------------- the audits of article 003
def test_article_003_has_exactly_one_inconsistent_number():
    audits = guide.ch17.audits()
    assert [a.title.split(".")[0] for a in audits] == ["Table 1", "Table 2", "Table 3", "The numbers in the text",
                                                        "Table 4", "Table 5"]
    bad = [p for a in audits for p in a.values if not p.follows]
    assert len(bad) == 1
    (p,) = bad
    assert p.where == "formula (9)" and p.printed == 0.35 and p.computed == pytest.approx(0.446429, abs=1e-6)
    assert "0.357" in p.reason and "rule (1)" in p.reason and "0.442" in p.reason
    assert all(p.reason == "" for a in audits for p in a.values if p.follows)
    d = guide.ch17.discrepancies()
    assert len(d) == 1 and d.iloc[0]["source"] == "article 003"
    # every printed value of tables 4 and 5 is checked
    assert len(guide.ch17.table4().values) == 14 and len(guide.ch17.table5().values) == 6
    assert any("0.446" in n and "0.497" in n for n in guide.ch17.table5().notes)
    assert "1000" in guide.ch17.NOTES[0] and "formula (2)" in guide.ch17.NOTES[1]


# --------------------------------------------------------------------------- the audit of article 000
def test_article_000_lysenko_reading_and_audit():
    a = guide.ch16.lysenko()
    (mz, step) = a.values
    assert not mz.follows and mz.printed == 14.0 and mz.computed == pytest.approx(12.823, abs=1e-3)
    assert "12.8 cm" in mz.reason and "0.0273" in mz.reason
    assert step.follows and step.computed == pytest.approx(31.5)
    r = guide.ch16.lysenko_readings()
    assert r.loc[("s·r (the book)", "0.025 mm (the book)"), "m_z, cm"] == pytest.approx(12.823, abs=1e-3)
    assert r.loc[("2r", "0.025 mm (the book)"), "m_z, cm"] == pytest.approx(12.993, abs=1e-3)
    assert r.loc[("s·r (the book)", "0.25 mm (as printed)"), "m_z, cm"] == pytest.approx(128.23, abs=1e-2)
    # 14 cm would need m_p = 0.0273 mm under the book's reading
    assert 0.14 / (450 / 70 * r.loc[("s·r (the book)", "0.025 mm (the book)"), "root"]) == pytest.approx(
        0.0273, abs=1e-4)
    assert "s·r" in guide.ch16.LYSENKO_READING and "0.025 mm" in guide.ch16.LYSENKO_READING
    assert len(guide.ch16.discrepancies()) == 1
