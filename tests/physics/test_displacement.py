"""Relief and tilt displacement, scales of bases, and the guide's tables 2–7 (guide §4–§5).

The physics (aerophoto.displacement), the demo terrain (aerophoto.terrain), the explorer's exact field
(aerophoto.demos.displacement), the audits of tables 2–7 (aerophoto.guide.ch03, ch04) and the whole procedure
of §4 and §5 on a set of measurements (relief_work, tilt_work).  The lab sheets and graded tasks of chapters
03–04 are tested in tests/content/test_labs_displacement.py, test_tasks_ch03.py and test_tasks_ch04.py."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aerophoto import displacement as d
from aerophoto import geometry as g
from aerophoto.demos.displacement import displacement_field
from aerophoto import guide
from aerophoto.terrain import AnalyticHills

S3 = math.sin(math.radians(3.0))


# --------------------------------------------------------------------------- formula 5.1 and the scales
def test_base_scale_formula_5_1():
    assert d.base_scale(28.0, 18.4) == pytest.approx(28.0 * 10000 / 18.4)  # 15217.39
    assert d.base_scale(35.3, 26.8) == pytest.approx(13171.64, abs=0.01)  # table 5 prints 13172
    assert d.base_scale(10.0, 20.0, M=5000) == pytest.approx(2500.0)
    np.testing.assert_allclose(d.base_scale([28.0, 30.1], [18.4, 19.8]), [15217.391, 15202.020], atol=1e-3)


@pytest.mark.parametrize("kwargs, name", [
    (dict(l_plan_mm=28.0, l_photo_mm=0.0), "l_photo_mm"),
    (dict(l_plan_mm=-1.0, l_photo_mm=18.4), "l_plan_mm"),
    (dict(l_plan_mm=28.0, l_photo_mm=18.4, M=0), "M"),
])
def test_base_scale_rejects_bad_input(kwargs, name):
    with pytest.raises(ValueError, match=name):
        d.base_scale(**kwargs)


def test_partial_scales_of_table_2_from_its_inputs():
    bases = [("I-1", 28.0, 18.4), ("I-2", 30.1, 19.8), ("II-3", 36.0, 24.3), ("II-4", 33.8, 22.9)]
    t = d.partial_scales(bases)
    assert t.zones == ("I", "II")
    m = [28.0e4 / 18.4, 30.1e4 / 19.8, 36.0e4 / 24.3, 33.8e4 / 22.9]
    np.testing.assert_allclose(t.m_i, m)
    np.testing.assert_allclose(t.m_part, [(m[0] + m[1]) / 2, (m[2] + m[3]) / 2])
    assert t.m_mean == pytest.approx((m[0] + m[1] + m[2] + m[3]) / 4)
    # Δm = m_част − m_cp: zone I (smaller scale, larger m) is positive
    assert t.dm[0] == pytest.approx(211.19, abs=0.01) and t.dm[1] == pytest.approx(-211.19, abs=0.01)
    np.testing.assert_allclose(t.ratio_N, [71.02, 71.02], atol=0.01)
    assert t.spread == pytest.approx(211.19 / 14998.51, rel=1e-4)
    # rounded like the guide: 15220, 15200, 14810, 14760; 15210, 14790; 15000
    assert [round(x, -1) for x in t.m_i] == [15220, 15200, 14810, 14760]
    assert [round(x, -1) for x in t.m_part] == [15210, 14790]
    assert round(t.m_mean, -1) == 15000


def test_scale_table_layout_like_the_guide():
    t = d.partial_scales([("I-1", 35.3, 26.8), ("I-2", 36.4, 28.2), ("II-3", 40.6, 32.5), ("II-4", 40.1, 31.9),
                          ("III-5", 29.0, 24.5), ("III-6", 32.1, 27.7)])
    df = t.table()
    assert list(df.index) == ["I-1", "I-2", "II-3", "II-4", "III-5", "III-6"]
    assert list(df.columns) == ["l_пл, mm", "l_сн, mm", "m_i", "m_част", "m_cp", "Δm_i", "Δm_i/m_cp"]
    # zone values on the zone's last row, m_cp on the middle row (as printed in table 5)
    assert np.isnan(df.loc["I-1", "m_част"]) and df.loc["I-2", "m_част"] == pytest.approx(t.m_part[0])
    assert df["m_cp"].notna().sum() == 1 and df.loc["II-3", "m_cp"] == pytest.approx(t.m_mean)
    assert df.loc["III-6", "Δm_i/m_cp"] == d.ratio_text(t.ratio_N[2]) == "1/17"
    assert df.loc["I-1", "Δm_i/m_cp"] == ""


def test_partial_scales_input_checks():
    with pytest.raises(ValueError, match="bases"):
        d.partial_scales([])
    with pytest.raises(ValueError, match="zone_heights_m"):
        d.partial_scales([("I-1", 28.0, 18.4)], zone_heights_m=[1, 2])
    with pytest.raises(ValueError, match="l_photo_mm"):
        d.Base("I-1", 28.0, -3.0)
    assert d.Base("III-5", 29.0, 24.5).zone == "III"


def test_ratio_text():
    assert d.ratio_text(71.02) == "1/71"
    assert d.ratio_text(1482.5) == "1/1500"
    assert d.ratio_text(math.inf) == "0"


# --------------------------------------------------------------------------- relief (formula 4.1)
def test_mean_object_plane_of_the_guide():
    zI = d.zone_height([(141, 138), (141, 141)])
    zII = d.zone_height([(180, 178), (180, 182)])
    assert zI == pytest.approx(140.25) and zII == pytest.approx(180.0)
    assert d.mean_object_plane([zI, zII]) == pytest.approx(160.125)
    with pytest.raises(ValueError, match="base_end_heights_m"):
        d.zone_height([141, 138])
    with pytest.raises(ValueError, match="zone_heights_m"):
        d.mean_object_plane([])


def test_flying_height():
    # H = m_cp·f (guide §4) is geometry.flying_height_m(f_mm, m)
    assert g.flying_height_m(100, 15000) == pytest.approx(1500.0)
    with pytest.raises(ValueError, match="m = 0"):
        g.flying_height_m(100, 0)
    with pytest.raises(ValueError, match="f_mm"):
        g.flying_height_m(-100, 12000)


def test_relief_corrections_table_3():
    r = d.relief_corrections(["I", "1", "2", "II", "3", "4"], [141, 138, 141, 180, 178, 182],
                             [76, 78, 81, 83, 73, 78], H_m=1500.0, Z_mean_m=160.0)
    np.testing.assert_allclose(r.h_m, [-19, -22, -19, 20, 18, 22])
    np.testing.assert_allclose(r.delta_mm, np.array([76 * -19, 78 * -22, 81 * -19, 83 * 20, 73 * 18, 78 * 22]) / 1500)
    # the guide's printed column, to its 0.1 mm
    assert list(np.round(r.delta_mm, 1)) == [-1.0, -1.1, -1.0, 1.1, 0.9, 1.1]
    assert r.n_applied == 6
    assert r.directions == ("away from n",) * 3 + ("towards n",) * 3
    df = r.table()
    assert list(df.columns) == ["Z_i, m", "h, m", "r, mm", "δh, mm", "correction"]


def test_relief_threshold_and_zero_height():
    r = d.relief_corrections(["a", "b", "c"], [100.0, 100.0, 100.2], [80.0, 80.0, 80.0], H_m=1000.0, Z_mean_m=100.0)
    np.testing.assert_array_equal(r.delta_mm[:2], [0.0, 0.0])  # h = 0 → no displacement
    assert r.delta_mm[2] == pytest.approx(0.016)
    assert r.n_applied == 0 and r.directions == ("not applied",) * 3
    # exactly 0.2 mm is not "more than 0.2 mm"
    r2 = d.relief_corrections(["a"], [10.0], [20.0], H_m=1000.0, Z_mean_m=0.0)
    assert r2.delta_mm[0] == pytest.approx(0.2) and not r2.apply[0]


def test_relief_corrections_input_checks():
    with pytest.raises(ValueError, match="r_mm"):
        d.relief_corrections(["a"], [100], [-5], H_m=1000)
    with pytest.raises(ValueError, match="lengths"):
        d.relief_corrections(["a", "b"], [100], [5], H_m=1000)
    with pytest.raises(ValueError, match="H_m"):
        d.relief_corrections(["a"], [100], [5], H_m=0)


def test_relief_vectors_on_a_vertical_photo_are_exactly_r_h_over_H():
    cam = g.Camera(150.0)
    pose = g.Pose.vertical(100.0, -50.0, 1800.0, ground_Z_m=200.0)  # S at 2000 m, mean plane 200 m
    rng = np.random.default_rng(3)
    XY = rng.uniform(-700, 700, size=(40, 2)) + [100.0, -50.0]
    Z = 200.0 + rng.uniform(-150, 250, size=40)
    P = np.column_stack([XY, Z])
    xy, xy0 = d.relief_displacement_vectors(cam, pose, P, Z_mean_m=200.0)
    n = g.nadir_point(cam, pose)
    r = np.hypot(*(xy - n).T)
    delta = g.relief_displacement(r, Z - 200.0, 1800.0)
    np.testing.assert_allclose(np.hypot(*(xy - n).T) - np.hypot(*(xy0 - n).T), delta, atol=1e-9)
    # correcting the actual images by δh (threshold 0) puts them back on the mean plane's images
    np.testing.assert_allclose(d.apply_radial_corrections(xy, n, delta, threshold_mm=0.0), xy0, atol=1e-9)
    # h = 0: no displacement at all
    xy_a, xy_b = d.relief_displacement_vectors(cam, pose, np.column_stack([XY, np.full(40, 200.0)]), 200.0)
    np.testing.assert_allclose(xy_a, xy_b, atol=1e-12)


def test_relief_vectors_on_a_tilted_photo_are_radial_from_the_nadir():
    cam = g.Camera(100.0)
    pose = g.Pose(0, 0, 1200, alpha_deg=6, lambda_deg=-50)
    f = displacement_field(100, 12000, 6, -50, 120)
    v = f.relief_vectors_mm
    w = f.grid_mm - g.nadir_point(cam, pose)
    cross = v[:, 0] * w[:, 1] - v[:, 1] * w[:, 0]
    assert np.max(np.abs(cross)) < 1e-9 * np.max(np.hypot(*w.T)) * 1e3
    assert np.max(np.hypot(*v.T)) > 1.0
    # hills are displaced away from n, the valley towards it
    outward = np.sum(v * w, axis=1)
    assert np.all(np.sign(outward[np.abs(f.h_m) > 5]) == np.sign(f.h_m[np.abs(f.h_m) > 5]))


# --------------------------------------------------------------------------- tilt (guide §5)
def test_isocentre_and_nadir_offsets():
    assert d.isocentre_offset(100, 3) == pytest.approx(-100 * math.tan(math.radians(1.5)))
    assert round(d.isocentre_offset(100, 3), 1) == -2.6  # the guide's −2.6 mm
    assert d.nadir_offset(100, 3) == pytest.approx(-100 * math.tan(math.radians(3)))
    with pytest.raises(ValueError, match="alpha_deg"):
        d.isocentre_offset(100, 95)


def test_tilt_corrections_guide_formula_and_exact():
    t = d.tilt_corrections(["I", "II", "3"], [67.0, 24.6, 9.5], [7, 186, 135], f_mm=100, alpha_deg=3)
    cosp = np.cos(np.radians([7, 186, 135]))
    r = np.array([67.0, 24.6, 9.5])
    np.testing.assert_allclose(t.delta_approx_mm, -(r**2) * cosp / 100 * S3, rtol=1e-12)
    np.testing.assert_allclose(t.delta_exact_mm, -(r**2) * cosp * S3 / (100 - r * cosp * S3), rtol=1e-12)
    assert t.delta_approx_mm[0] == pytest.approx(-2.332, abs=1e-3)
    assert list(t.apply) == [True, True, False]
    assert t.directions == ("away from c", "towards c", "not applied")
    assert t.oc_mm == pytest.approx(-2.6186, abs=1e-4)
    assert list(t.table().columns) == ["r_c, mm", "φ, °", "cos φ", "δα, mm", "δα exact, mm", "correction"]


def test_tilt_corrections_input_checks():
    with pytest.raises(ValueError, match="r_c_mm"):
        d.tilt_corrections(["a"], [-1.0], [0.0])
    with pytest.raises(ValueError, match="f_mm"):
        d.tilt_corrections(["a"], [10.0], [0.0], f_mm=0)
    with pytest.raises(ValueError, match="alpha_deg"):
        d.tilt_corrections(["a"], [10.0], [0.0], alpha_deg=90)
    with pytest.raises(ValueError, match="lengths"):
        d.tilt_corrections(["a", "b"], [10.0], [0.0])


@settings(max_examples=60, deadline=None)
@given(r=st.floats(5, 120), phi=st.floats(0, 360), f=st.floats(70, 500))
def test_exact_tilt_displacement_tends_to_the_guide_formula(r, phi, f):
    errs = []
    for a in (1.0, 0.1, 0.01):
        t = d.tilt_corrections(["p"], [r], [phi], f_mm=f, alpha_deg=a)
        ex, ap = t.delta_exact_mm[0], t.delta_approx_mm[0]
        # the two differ by the factor 1/(1 − r·cos φ·sin α/f) only
        bound = abs(ap) * 2.0 * r * math.sin(math.radians(a)) / f + 1e-15
        assert abs(ex - ap) <= bound
        errs.append(abs(ex - ap))
    assert errs[2] <= errs[1] <= errs[0]
    t0 = d.tilt_corrections(["p"], [r], [phi], f_mm=f, alpha_deg=0.0)
    assert t0.delta_exact_mm[0] == 0.0 and t0.delta_approx_mm[0] == 0.0


@settings(max_examples=40, deadline=None)
@given(r=st.floats(0.5, 120), phi=st.floats(0, 359.9), lam=st.floats(-180, 180), a=st.floats(0, 15))
def test_polar_coordinates_about_c_round_trip(r, phi, lam, a):
    cam = g.Camera(120.0)
    pose = g.Pose(alpha_deg=a, lambda_deg=lam)
    xy = d.point_from_polar(cam, pose, r, phi)
    r2, phi2 = d.polar_about_isocentre(cam, pose, xy)
    assert r2 == pytest.approx(r, abs=1e-9)
    assert ((phi2 - phi + 180) % 360 - 180) == pytest.approx(0.0, abs=1e-7)


def test_tilt_vectors_are_radial_from_c_and_match_the_closed_form():
    f = displacement_field(120, 15000, 8, 30, 0.0)
    v = f.tilt_vectors_mm
    w = f.grid_mm - f.c_mm
    cross = v[:, 0] * w[:, 1] - v[:, 1] * w[:, 0]
    assert np.max(np.abs(cross)) < 1e-8
    cam, pose = f.camera, f.pose
    np.testing.assert_allclose(f.tilt_exact_mm, g.tilt_displacement_exact(cam, pose, f.grid_mm), atol=1e-9)
    np.testing.assert_allclose(f.tilt_approx_mm, g.tilt_displacement_approx(cam, pose, f.grid_mm), atol=1e-12)
    # far side (cos φ > 0) pulled towards c, near side pushed away
    _, phi = d.polar_about_isocentre(cam, pose, f.grid_mm)
    cosp = np.cos(np.radians(phi))
    big = np.abs(cosp) > 0.2
    assert np.all(np.sign(f.tilt_exact_mm[big]) == -np.sign(cosp[big]))
    # correcting the tilted images by the exact δα (threshold 0) gives the vertical photo's images
    back = d.apply_radial_corrections(f.grid_mm, f.c_mm, f.tilt_exact_mm, threshold_mm=0.0)
    np.testing.assert_allclose(back, f.xy_vertical_mm, atol=1e-9)


def test_apply_radial_corrections_direction_and_threshold():
    xy = np.array([[10.0, 0.0], [0.0, 20.0], [-30.0, 0.0]])
    out = d.apply_radial_corrections(xy, [0.0, 0.0], [0.5, -0.3, 0.2])
    np.testing.assert_allclose(out, [[9.5, 0.0], [0.0, 20.3], [-30.0, 0.0]])  # + towards, − away, 0.2 kept
    with pytest.raises(ValueError, match="threshold_mm"):
        d.apply_radial_corrections(xy, [0, 0], [0, 0, 0], threshold_mm=-1)


# --------------------------------------------------------------------------- the field of the demo
def test_field_limiting_cases():
    flat = displacement_field(100, 12000, 4, -60, 0.0)
    np.testing.assert_allclose(flat.relief_vectors_mm, 0.0, atol=1e-12)
    vertical = displacement_field(100, 12000, 0.0, -60, 80.0)
    np.testing.assert_allclose(vertical.tilt_vectors_mm, 0.0, atol=1e-12)
    np.testing.assert_allclose(vertical.n_mm, 0.0, atol=1e-12)
    np.testing.assert_allclose(vertical.c_mm, 0.0, atol=1e-12)
    # on a vertical photo r·h/H (r to the actual image) is the exact relief displacement
    np.testing.assert_allclose(vertical.relief_formula_mm, vertical.relief_exact_mm, atol=1e-9)
    s = vertical.summary()
    assert s["max_tilt_exact_mm"] == 0.0 and s["max_tilt_error_percent"] == 0.0
    assert s["max_relief_error_mm"] < 1e-9 and s["H_m"] == pytest.approx(1200.0)


def test_field_summary_numbers():
    f = displacement_field(100, 12000, 3, -60, 60)
    s = f.summary()
    assert s["on_mm"] == pytest.approx(100 * math.tan(math.radians(3)))
    assert s["oc_mm"] == pytest.approx(-100 * math.tan(math.radians(1.5)))
    # the guide's formula misses the exact tilt displacement by a few per cent at α = 3°
    assert 0.5 < s["max_tilt_error_percent"] < 15
    assert s["max_tilt_exact_mm"] > s["max_tilt_approx_mm"] * 0.9
    assert s["max_relief_exact_mm"] == pytest.approx(np.max(np.abs(f.relief_exact_mm)))
    assert f.table().shape == (11, 2)
    bigger = displacement_field(100, 12000, 10, -60, 60).summary()
    assert bigger["max_tilt_error_percent"] > s["max_tilt_error_percent"]


def test_field_input_checks():
    with pytest.raises(ValueError, match="relief_m"):
        displacement_field(100, 12000, 3, 0, 1200.0)  # as high as the camera
    with pytest.raises(ValueError, match="grid_n"):
        displacement_field(grid_n=1)
    with pytest.raises(ValueError, match="alpha_deg"):
        displacement_field(alpha_deg=-95)


def test_analytic_hills():
    hills = AnalyticHills(relief_m=50.0, half_side_m=900.0, X0_m=100.0, Y0_m=-200.0, Z0_m=150.0)
    t = np.linspace(-1, 1, 201)
    U, V = np.meshgrid(t, t)
    Z = hills.height(100.0 + 900.0 * U, -200.0 + 900.0 * V)
    assert Z.mean() == pytest.approx(150.0, abs=1e-9)  # the mean object plane of the square
    assert np.max(np.abs(Z - 150.0)) == pytest.approx(50.0, rel=1e-9)
    assert hills.z_min_m < Z.min() and hills.z_max_m > Z.max()
    np.testing.assert_array_equal(Z, AnalyticHills(50.0, 900.0, 100.0, -200.0, 150.0).height(
        100.0 + 900.0 * U, -200.0 + 900.0 * V))  # deterministic
    flat = AnalyticHills(relief_m=0.0)
    assert np.all(flat.height(U, V) == 0.0)
    # usable as a DEM by the camera model: photo → terrain → photo round trip
    cam = g.Camera(100.0)
    pose = g.Pose(100.0, -200.0, 1500.0, alpha_deg=3, lambda_deg=20)
    xy = np.array([[10.0, -20.0], [60.0, 55.0], [-70.0, 5.0]])
    P = g.photo_to_dem(cam, pose, xy, hills, tol_m=1e-7)
    np.testing.assert_allclose(P[:, 2], hills.height(P[:, 0], P[:, 1]), atol=1e-5)
    np.testing.assert_allclose(g.ground_to_photo(cam, pose, P), xy, atol=1e-5)
    with pytest.raises(ValueError, match="relief_m"):
        AnalyticHills(relief_m=-1)


# --------------------------------------------------------------------------- the guide's tables 2–7
def _audit(n: int):
    """The audit of the guide's table n: §4 (tables 2–4) or §5 (tables 5–7)."""
    return (guide.ch03 if n <= 4 else guide.ch04).table(n)


#: the values whose printed number does not follow from the printed inputs (table, where, quantity; see the
#: REASONS of aerophoto.guide.ch03 and ch04).  Under the one rule of aerophoto.guide.audit (0.6 of a unit of the
#: last printed digit) table 6's cos φ of points 1 and 6 — truncated, not rounded — join the list; the old module
#: allowed a whole unit in that column.
EXPECTED_DISCREPANCIES = {
    (2, "I-2", "m_i"), (2, "I", "Δm_i"), (2, "II", "Δm_i"), (2, "I", "Δm_i/m_cp"), (2, "II", "Δm_i/m_cp"),
    (4, "I-1", "m_i"), (4, "I", "m_част"), (4, "I", "Δm_i"), (4, "II", "Δm_i"), (4, "I", "Δm_i/m_cp"),
    (4, "II", "Δm_i/m_cp"),
    (5, "I-2", "m_i"), (5, "III-6", "m_i"), (5, "I", "m_част"), (5, "III", "m_част"), (5, "—", "m_cp"),
    (5, "I", "Δm_i"), (5, "II", "Δm_i"), (5, "III", "Δm_i"),
    (5, "I", "Δm_i/m_cp"), (5, "II", "Δm_i/m_cp"), (5, "III", "Δm_i/m_cp"),
    (6, "1", "cos φ"), (6, "6", "cos φ"),
    (6, "I", "δα"), (6, "1", "δα"), (6, "2", "δα"), (6, "III", "δα"), (6, "5", "δα"), (6, "6", "δα"),
    (7, "I", "Δm_i"), (7, "II", "Δm_i"), (7, "III", "Δm_i"), (7, "II", "Δm_i/m_cp"), (7, "III-6", "l_сн"),
}


def test_exactly_the_listed_cells_do_not_follow():
    flagged = set()
    for n in range(2, 8):
        a = _audit(n)
        assert a.source == ("guide §4" if n <= 4 else "guide §5")
        for p in a.values:
            assert p.tolerance > 0
            if p.follows:
                assert abs(p.printed - p.computed) <= p.tolerance + 1e-9 and p.reason == ""
            else:
                flagged.add((n, p.where, p.quantity))
                assert abs(p.printed - p.computed) > p.tolerance
                assert p.reason and "does not follow from its printed inputs" not in p.reason  # explained
    assert flagged == EXPECTED_DISCREPANCIES
    reasons = {(n, *key) for sec in (guide.ch03, guide.ch04) for n, table in sec.REASONS.items() for key in table}
    assert reasons == EXPECTED_DISCREPANCIES  # every reason written is for a flagged cell
    df4, df5 = guide.ch03.discrepancies(), guide.ch04.discrepancies()
    assert len(df4) + len(df5) == len(EXPECTED_DISCREPANCIES)
    assert set(df4["table"]) == {"Table 2", "Table 4"} and set(df5["table"]) == {"Table 5", "Table 6", "Table 7"}
    assert set(df4.columns) == {"source", "table", "where", "quantity", "printed", "computed", "reason"}


def test_table_3_is_right():
    t = guide.ch03.table(3)
    assert t.discrepancies == ()
    assert t.result.H_m == pytest.approx(guide.ch03.table(2).result.m_mean * 0.1)  # H = m_cp·f ≈ 1500 m
    assert t.result.Z_mean_m == pytest.approx(160.125)
    np.testing.assert_allclose(t.result.delta_mm, [-0.969, -1.151, -1.033, 1.100, 0.870, 1.138], atol=5e-4)
    # with the flight's H = 1200 m (§2) the printed column would not follow
    wrong = d.relief_corrections(t.result.names, t.result.Z_m, t.result.r_mm, 1200.0, 160.125)
    assert abs(wrong.delta_mm[0] - (-1.0)) > 0.1


def test_table_2_and_4_numbers():
    t2 = guide.ch03.table(2).result
    assert t2.m_i[1] == pytest.approx(15202.02, abs=0.01)  # printed 15220
    t4 = guide.ch03.table(4).result
    assert t4.m_i[0] == pytest.approx(14973.26, abs=0.01)  # printed 15010
    assert t4.m_mean == pytest.approx(14994.75, abs=0.01)
    assert t4.ratio_N[0] == pytest.approx(888.4, abs=0.1)
    # the corrected lengths of table 4 do follow from tables 2 and 3 (radial scaling about n)
    lengths = [p for p in guide.ch03.table(4).values if p.quantity == "l_сн"]
    assert len(lengths) == 4 and all(p.follows for p in lengths)


def test_table_5_and_7_numbers():
    t5 = guide.ch04.table(5).result
    assert t5.m_i[1] == pytest.approx(12907.80, abs=0.01)
    assert t5.m_i[5] == pytest.approx(11588.45, abs=0.01)
    assert 32.1e4 / 27.3 == pytest.approx(11758, abs=0.5)  # the printed m_i fits l_сн = 27.3 mm
    t7 = guide.ch04.table(7).result
    assert [round(x) for x in t7.m_i] == [12698, 12595, 12492, 12571, 12393, 12490]
    assert round(t7.m_mean) == 12540
    np.testing.assert_allclose(t7.dm, [106.62, -8.46, -98.16], atol=0.01)


def test_table_6_and_its_best_reading():
    t = guide.ch04.table(6)
    res = t.result
    np.testing.assert_allclose(res.delta_approx_mm, -(np.array(res.r_c_mm) ** 2) * res.cos_phi / 100 * S3)
    assert res.n_applied == 7  # all but 3 and 4
    fit = guide.ch04.table6_fit()
    assert fit.k_lo < fit.k_lsq < fit.k_hi
    assert not (fit.k_lo <= S3 / 100 <= fit.k_hi)  # the stated f = 100 mm, α = 3° does not reproduce it
    lo, hi = fit.f_range_mm
    assert lo < 117 < hi and not (lo <= 100 <= hi) and not (lo <= 120 <= hi)
    alo, ahi = fit.alpha_range_deg
    assert alo < 2.57 < ahi and not (alo <= 2.5 <= ahi)
    cand = fit.candidates
    assert cand.loc["the guide's inputs: f = 100 mm, α = 3°", "matches (of 9)"] == 3
    assert cand.loc["f = 117 mm, α = 3°", "matches (of 9)"] == 9
    assert cand["matches (of 9)"].max() == 9
    # every k in the range reproduces the printed column after rounding
    r = np.array(res.r_c_mm)
    cos_printed = np.array([0.992, 0.987, 0.956, -0.994, -0.707, -0.104, -0.961, -0.990, -0.965])
    printed = np.array([-2.0, -0.8, -1.5, 0.3, 0.0, 0.0, 0.6, 0.8, 0.4])
    for k in np.linspace(fit.k_lo, fit.k_hi, 7)[1:-1]:
        np.testing.assert_allclose(np.round(-k * r**2 * cos_printed, 1), printed, atol=1e-9)


def test_guide_table_objects():
    from aerophoto.guide import render

    for n in range(2, 8):
        t = _audit(n)
        assert t.title.startswith(f"Table {n}.")
        html = t._repr_html_()
        assert html == render(t) and "recomputed by aerophoto" in html
        assert len(t.printed_table) == len(t.result.table())
        assert t.table.shape == t.result.table().shape  # the recomputed table at the guide's precision
        assert all(isinstance(x, str) for x in t.table.to_numpy().ravel())
        comp = t.comparison(only_discrepancies=False)
        assert len(comp) == len(t.values)
    assert guide.ch03.audits() == tuple(guide.ch03.table(n) for n in (2, 3, 4))
    assert guide.ch04.audits() == tuple(guide.ch04.table(n) for n in (5, 6, 7))
    assert "Окончание табл. 3" in " ".join(guide.ch04.table(6).notes)
    for section, bad in ((guide.ch03, 5), (guide.ch03, 1), (guide.ch04, 4), (guide.ch04, 8)):
        with pytest.raises(ValueError, match="number"):
            section.table(bad)


def test_guide_texts_as_printed():
    # printed values shown as the guide prints them, computed ones with a digit more
    p = next(p for p in guide.ch03.table(2).values if (p.where, p.quantity) == ("I", "Δm_i"))
    assert (p.shown_printed(), p.shown_computed()) == ("-210", "+211.2")
    p = next(p for p in guide.ch03.table(2).values if (p.where, p.quantity) == ("I", "Δm_i/m_cp"))
    assert (p.shown_printed(), p.shown_computed()) == ("1/72", "1/71.0")
    p = next(p for p in guide.ch04.table(7).values if (p.where, p.quantity) == ("III-6", "l_сн"))
    assert p.bounds is not None and p.shown_computed() == "26.51 … 28.89"
    assert guide.ch03.ratio_unit(72) == 1.0 and guide.ch03.ratio_unit(750) == 10.0 and guide.ch03.ratio_unit(1400) == 100.0


# --------------------------------------------------------------------------- the whole procedure (relief_work, tilt_work)
def test_base_lengths():
    names = ("I", "1", "2")
    xy = [[0.0, 0.0], [3.0, 4.0], [-6.0, 8.0]]
    np.testing.assert_allclose(d.base_lengths_mm(names, xy, [("I", "1"), ("I", "2"), ("1", "2")]),
                               [5.0, 10.0, math.hypot(9.0, 4.0)])
    with pytest.raises(ValueError, match="names"):
        d.base_lengths_mm(names, xy, [("I", "7")])
    with pytest.raises(ValueError, match="xy_mm"):
        d.base_lengths_mm(names, xy[:2], [("I", "1")])
    with pytest.raises(ValueError, match="finite"):
        d.base_lengths_mm(names, [[0, 0], [1, np.nan], [2, 2]], [("I", "1")])


NAMES6 = ("I", "1", "2", "II", "3", "4")
BASES6 = (("I", "1"), ("I", "2"), ("II", "3"), ("II", "4"))
GROUND6 = np.array([[-500.0, -300.0], [-760.0, -250.0], [-480.0, -560.0], [520.0, 350.0], [780.0, 300.0],
                    [540.0, 610.0]])


def _vertical_lab(Z, *, f=100.0, H=1200.0):
    """Six ground points photographed vertically from H above their mean plane: images, plan lengths (1:10 000)."""
    XY = GROUND6
    Z = np.asarray(Z, dtype=float)
    Zm = d.mean_object_plane([d.zone_height([(Z[0], Z[1]), (Z[0], Z[2])]), d.zone_height([(Z[3], Z[4]), (Z[3], Z[5])])])
    cam, pose = g.Camera(f), g.Pose(0.0, 0.0, Zm + H)
    xy = g.ground_to_photo(cam, pose, np.column_stack([XY, Z]))
    l_plan = d.base_lengths_mm(NAMES6, XY / 10.0, BASES6)  # ground m → plan mm at 1:10 000
    return cam, pose, xy, l_plan, Zm


def test_relief_work_on_flat_ground_changes_nothing():
    cam, pose, xy, l_plan, Zm = _vertical_lab([180.0] * 6)
    w = d.relief_work(NAMES6, xy, l_plan, [180.0] * 6, BASES6, f_mm=100.0, n_mm=[0.0, 0.0])
    np.testing.assert_allclose(w.table2.m_i, 12000.0, rtol=1e-12)  # H/f exactly, every base
    assert w.H_m == pytest.approx(1200.0) and w.Z_mean_m == 180.0
    np.testing.assert_allclose(w.table3.delta_mm, 0.0)
    assert w.table3.n_applied == 0
    np.testing.assert_allclose(w.corrected_xy_mm, xy)
    np.testing.assert_allclose(w.table4.m_i, w.table2.m_i)


def test_relief_work_step_by_step_on_a_vertical_photo():
    Z = [171.0, 170.0, 172.0, 195.0, 197.0, 193.0]
    cam, pose, xy, l_plan, Zm = _vertical_lab(Z)
    w = d.relief_work(NAMES6, xy, l_plan, Z, BASES6, f_mm=100.0, n_mm=[0.0, 0.0])
    # table 2: l_сн from the points, m_i = l_пл·M/l_сн, the high zone II has the larger scale (smaller m)
    lsn = d.base_lengths_mm(NAMES6, xy, BASES6)
    np.testing.assert_allclose([b.l_photo_mm for b in w.table2.bases], lsn)
    np.testing.assert_allclose(w.table2.m_i, l_plan * 10000.0 / lsn)
    assert w.table2.m_part[0] > w.table2.m_part[1] and w.table2.zone_heights_m == pytest.approx((171.0, 195.0))
    # table 3: H = m_cp·f, h = Z − Z_cp, δh = r·h/H with r from n
    assert w.Z_mean_m == pytest.approx(Zm) == pytest.approx(183.0)  # zone I: (2·171 + 170 + 172)/4
    assert w.H_m == pytest.approx(w.table2.m_mean * 0.1)
    r = np.hypot(*xy.T)
    np.testing.assert_allclose(w.table3.delta_mm, r * (np.array(Z) - Zm) / w.H_m)
    # step 5: each point moved back along its radius by δh (all |δh| > 0.2 mm here)
    assert w.table3.n_applied == 6
    np.testing.assert_allclose(np.hypot(*w.corrected_xy_mm.T), r - w.table3.delta_mm)
    # with H = m_cp·f (not quite the true H) the corrected points come within a few hundredths of a millimetre
    # of where they would be imaged on the mean plane, and the zones' scales agree ten times better
    on_plane = g.ground_to_photo(cam, pose, np.column_stack([GROUND6, np.full(6, Zm)]))
    assert np.max(np.hypot(*(w.corrected_xy_mm - on_plane).T)) < 0.03
    assert abs(w.table4.dm[0]) < 0.1 * abs(w.table2.dm[0])


def test_relief_work_with_the_true_flying_height_restores_the_mean_plane_image():
    Z = [171.0, 170.0, 172.0, 195.0, 197.0, 193.0]
    cam, pose, xy, l_plan, Zm = _vertical_lab(Z)
    r = np.hypot(*xy.T)
    delta = d.relief_corrections(NAMES6, Z, r, 1200.0, Zm).delta_mm  # the true H above the mean plane
    corrected = d.apply_radial_corrections(xy, [0.0, 0.0], delta)
    on_plane = g.ground_to_photo(cam, pose, np.column_stack([GROUND6, np.full(6, Zm)]))
    np.testing.assert_allclose(corrected, on_plane, atol=1e-9)  # exact on a vertical photo


def test_relief_work_input_checks():
    Z = [171.0, 170.0, 172.0, 195.0, 197.0, 193.0]
    cam, pose, xy, l_plan, Zm = _vertical_lab(Z)
    with pytest.raises(ValueError, match="Z_m"):
        d.relief_work(NAMES6, xy, l_plan, Z[:5], BASES6, f_mm=100.0, n_mm=[0, 0])
    with pytest.raises(ValueError, match="l_plan_mm"):
        d.relief_work(NAMES6, xy, l_plan[:3], Z, BASES6, f_mm=100.0, n_mm=[0, 0])
    with pytest.raises(ValueError, match="f_mm"):
        d.relief_work(NAMES6, xy, l_plan, Z, BASES6, f_mm=0.0, n_mm=[0, 0])


NAMES9 = ("I", "1", "2", "II", "3", "4", "III", "5", "6")
BASES9 = (("I", "1"), ("I", "2"), ("II", "3"), ("II", "4"), ("III", "5"), ("III", "6"))


def _tilted_lab(lam=-60.0, alpha=3.0, f=100.0, H=1200.0):
    cam, pose = g.Camera(f), g.Pose(0.0, 0.0, H, alpha, lam, 0.0)
    u = g.principal_vertical(pose)
    w = np.array([-u[1], u[0]])
    c = g.isocentre(cam, pose)
    pattern = [(50, 5), (30, -12), (58, 22), (0, 18), (-20, 30), (8, 40), (-45, -5), (-60, 12), (-38, -27)]
    xy = np.array([c + a * u + b * w for a, b in pattern])
    XY = g.photo_to_plane(cam, pose, xy, 0.0)[:, :2]
    return cam, pose, xy, d.base_lengths_mm(NAMES9, XY / 10.0, BASES9), XY


@pytest.mark.parametrize("lam", [-60.0, 0.0, 39.0, 150.0])
def test_tilt_work_step_by_step(lam):
    cam, pose, xy, l_plan, XY = _tilted_lab(lam)
    w = d.tilt_work(NAMES9, xy, l_plan, BASES9, f_mm=100.0, alpha_deg=3.0, lambda_deg=lam)
    np.testing.assert_allclose(w.c_mm, g.isocentre(cam, pose))
    r, phi = d.polar_about_isocentre(cam, pose, xy)
    np.testing.assert_allclose(w.table6.r_c_mm, r)
    np.testing.assert_allclose(w.table6.phi_deg, phi)
    np.testing.assert_allclose(w.table6.delta_approx_mm, -(r**2) * np.cos(np.radians(phi)) / 100.0 * S3)
    # the far zone I has the smallest scale (largest m) before the correction, the near zone III the largest
    assert w.table5.m_part[0] > w.table5.m_part[1] > w.table5.m_part[2]
    # after it the zones agree within the approximate formula's error, much better than before
    assert w.table7.spread < 0.2 * w.table5.spread
    np.testing.assert_allclose(w.table7.m_part, 12000.0, rtol=0.004)
    # corrected points lie near their images on the equivalent vertical photo (turned about the isoline)
    vertical = g.tilt_displacement_vectors(cam, pose, np.column_stack([XY, np.zeros(9)]))[1]
    before = np.hypot(*(xy - vertical).T)
    after = np.hypot(*(w.corrected_xy_mm - vertical).T)
    moved = w.table6.apply
    assert np.all(after[moved] < 0.1 * before[moved] + 1e-9)


def test_tilt_work_without_tilt_changes_nothing():
    cam, pose, xy, l_plan, XY = _tilted_lab(alpha=0.0)
    w = d.tilt_work(NAMES9, xy, l_plan, BASES9, f_mm=100.0, alpha_deg=0.0, lambda_deg=-60.0)
    np.testing.assert_allclose(w.table6.delta_approx_mm, 0.0, atol=1e-12)
    np.testing.assert_allclose(w.table5.m_i, 12000.0, rtol=1e-9)
    np.testing.assert_allclose(w.table7.m_i, w.table5.m_i)
