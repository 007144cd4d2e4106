"""aerophoto.control (guide §11): angles, the resection and its danger circle, the check angle, the control design;
aerophoto.guide.ch10: the §11 coordinate table against Pulkovo 1942."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aerophoto import control as c
from aerophoto import triangulation as tri
from aerophoto import guide

I, II, III, IV = (np.array(p) for p in ([6066340.0, 5313900.0], [6067000.0, 5313500.0], [6066540.0, 5312500.0],
                                       [6065500.0, 5313100.0]))


def tienstra(A, B, C, b1, b2):
    """An independent solution (Tienstra's barycentric formula) for a station inside triangle ABC."""
    def ang(p, q, r):  # interior angle at p of triangle pqr
        u, v = q - p, r - p
        return math.acos(np.dot(u, v) / (np.hypot(*u) * np.hypot(*v)))

    a_, b_, c_ = ang(A, B, C), ang(B, C, A), ang(C, A, B)
    # the angles at P subtending BC, CA, AB (P inside: each below 180°, together 360°)
    alpha = math.radians(min(b2, 360.0 - b2))  # between B and C
    gamma = math.radians(min(b1, 360.0 - b1))  # between A and B
    beta = 2 * math.pi - alpha - gamma  # between C and A
    k1 = 1 / (1 / math.tan(a_) - 1 / math.tan(alpha))
    k2 = 1 / (1 / math.tan(b_) - 1 / math.tan(beta))
    k3 = 1 / (1 / math.tan(c_) - 1 / math.tan(gamma))
    return (k1 * A + k2 * B + k3 * C) / (k1 + k2 + k3)


# --------------------------------------------------------------------------- angles
def test_direction_angles_run_clockwise_from_north():
    P = np.zeros(2)
    assert c.direction_angle_deg(P, [1.0, 0.0]) == pytest.approx(0.0)  # north
    assert c.direction_angle_deg(P, [0.0, 1.0]) == pytest.approx(90.0)  # east
    assert c.direction_angle_deg(P, [-1.0, 0.0]) == pytest.approx(180.0)
    assert c.direction_angle_deg(P, [0.0, -1.0]) == pytest.approx(270.0)
    assert c.horizontal_angle_deg(P, [1.0, 0.0], [0.0, -1.0]) == pytest.approx(270.0)
    with pytest.raises(ValueError, match="coincide"):
        c.direction_angle_deg(P, P)


def test_degrees_minutes_seconds():
    assert c.format_dms(54 + 51 / 60 + 10 / 3600) == "54°51′10″"
    assert c.format_dms(24.55) == "24°33′00″"
    assert c.format_dms(10.999999999) == "11°00′00″"  # carried, not 10°59′60″
    assert c.from_dms(24, 33, 0) == pytest.approx(24.55)
    assert c.dms(c.from_dms(54, 50, 45))[:2] == (54, 50)
    assert guide.ch10.parse_dms("54°51′15′") == pytest.approx(c.from_dms(54, 51, 15))  # OCR's ′ for ″
    with pytest.raises(ValueError, match="m = 60"):
        c.from_dms(1, 60, 0)


def test_site_and_geodetic_axes_are_swapped():
    np.testing.assert_array_equal(c.geodetic_from_site([[100.0, 200.0]]), [[200.0, 100.0]])
    np.testing.assert_array_equal(c.site_from_geodetic(c.geodetic_from_site([3.0, 4.0])), [3.0, 4.0])


# --------------------------------------------------------------------------- resection
@pytest.mark.parametrize("P", [[6066600.0, 5313300.0], [6066200.0, 5313000.0], [6065000.0, 5311000.0],
                               [6068000.0, 5315000.0]])
def test_resection_returns_the_true_station(P):
    P = np.array(P)
    r = c.resect(I, II, III, c.horizontal_angle_deg(P, I, II), c.horizontal_angle_deg(P, II, III))
    np.testing.assert_allclose(r.point, P, atol=1e-6)
    assert 0 < r.strength <= 1 and r.metres_per_arcsec > 0


def test_resection_agrees_with_tienstras_formula_inside_the_triangle():
    P = (I + II + III) / 3 + np.array([20.0, -35.0])
    b1, b2 = c.horizontal_angle_deg(P, I, II), c.horizontal_angle_deg(P, II, III)
    np.testing.assert_allclose(c.resect(I, II, III, b1, b2).point, tienstra(I, II, III, b1, b2), atol=1e-6)


@settings(max_examples=40, deadline=None)
@given(x=st.floats(-3000, 3000), y=st.floats(-3000, 3000), seed=st.integers(0, 1000))
def test_resection_round_trip_away_from_the_danger_circle(x, y, seed):
    rng = np.random.default_rng(seed)
    A, B, C = rng.uniform(-2000, 2000, size=(3, 2))
    P = np.array([x, y])
    try:
        centre, R = c.danger_circle(A, B, C)
    except ValueError:
        return  # collinear known points (checked separately)
    if min(np.hypot(*(np.array([A, B, C]) - P).T)) < 50 or abs(np.hypot(*(P - centre)) - R) < 0.05 * R:
        return
    if R > 1e5:
        return
    r = c.resect(A, B, C, c.horizontal_angle_deg(P, A, B), c.horizontal_angle_deg(P, B, C))
    np.testing.assert_allclose(r.point, P, atol=1e-5 * max(1.0, R / 100))


def test_resect_many_is_resect_vectorised():
    P = np.array([[6066600.0, 5313300.0], [6065000.0, 5311000.0]])
    b1 = [c.horizontal_angle_deg(p, I, II) for p in P]
    b2 = [c.horizontal_angle_deg(p, II, III) for p in P]
    np.testing.assert_allclose(c.resect_many(I, II, III, b1, b2), P, atol=1e-6)


def test_the_danger_circle_passes_through_the_three_points_and_refuses_a_station_on_it():
    centre, R = c.danger_circle(I, II, III)
    for p in (I, II, III):
        assert np.hypot(*(p - centre)) == pytest.approx(R)
    P = centre + R * np.array([math.cos(2.0), math.sin(2.0)])
    with pytest.raises(ValueError, match="danger circle"):
        c.resect(I, II, III, c.horizontal_angle_deg(P, I, II), c.horizontal_angle_deg(P, II, III))
    assert np.all(np.isnan(c.resect_many(I, II, III, [c.horizontal_angle_deg(P, I, II)],
                                         [c.horizontal_angle_deg(P, II, III)])))


def test_near_the_danger_circle_the_station_goes_soft():
    centre, R = c.danger_circle(I, II, III)
    u = np.array([math.cos(2.0), math.sin(2.0)])
    shift = []
    for d in (300.0, 30.0, 3.0):
        P = centre + (R + d) * u
        r = c.resect(I, II, III, c.horizontal_angle_deg(P, I, II), c.horizontal_angle_deg(P, II, III))
        np.testing.assert_allclose(r.point, P, atol=1e-3)
        assert r.danger_distance_m == pytest.approx(d, rel=1e-6)
        shift.append(r.metres_per_arcsec)
    assert shift[0] < shift[1] < shift[2]
    assert shift[2] / shift[1] == pytest.approx(10.0, rel=0.2)  # ∝ 1/distance close to the circle


@pytest.mark.parametrize("args, match", [
    ((I, I + [1000.0, 0.0], I + [2000.0, 0.0], 30.0, 40.0), "one line"),
    ((I, II, III, 0.0, 40.0), "beta1_deg = 0"),
    ((I, II, III, 180.0, 40.0), "180"),
    ((I, II, III, 30.0, math.inf), "beta2_deg"),
])
def test_impossible_resections_are_named(args, match):
    with pytest.raises(ValueError, match=match):
        c.resect(*args)


def test_angles_that_no_point_can_see_are_refused():
    P = np.array([6066600.0, 5313300.0])
    b1 = c.horizontal_angle_deg(P, I, II)
    b2 = c.horizontal_angle_deg(P, II, III)
    with pytest.raises(ValueError, match="cannot both be seen"):
        c.resect(I, II, III, (b1 + 180.0) % 360.0, b2)


# --------------------------------------------------------------------------- the check
def test_check_tolerance_is_0_1_mm_at_the_plan_scale_seen_from_the_station():
    assert c.check_tolerance_arcsec(1000.0, 10000.0) == pytest.approx(206.2648, rel=1e-6)
    assert c.check_tolerance_arcsec(2000.0, 10000.0) == pytest.approx(103.1324, rel=1e-6)
    assert c.identification_tolerance_m(10000.0) == pytest.approx(1.0)
    with pytest.raises(ValueError, match="distance_m"):
        c.check_tolerance_arcsec(0.0)


def test_the_check_catches_a_blunder_and_passes_good_angles():
    P = np.array([6066600.0, 5313300.0])
    b1, b2 = c.horizontal_angle_deg(P, I, II), c.horizontal_angle_deg(P, II, III)
    gm = c.horizontal_angle_deg(P, III, IV)
    good = c.check_resection(c.resect(I, II, III, b1, b2), IV, (gm + 3 / 3600) % 360)
    assert good.ok and good.discrepancy_arcsec == pytest.approx(3.0, abs=1e-6)
    assert good.distance_m == pytest.approx(np.hypot(*(IV - P)))
    bad = c.check_resection(c.resect(I, II, III, b1, (b2 + 10 / 60) % 360), IV, gm)
    assert not bad.ok and abs(bad.discrepancy_arcsec) > bad.tolerance_arcsec
    t = good.table()
    assert t.loc["the check holds", "value"] == "yes"


# --------------------------------------------------------------------------- the design
def test_control_rows_every_n_bases_with_both_ends():
    assert c.control_rows(12, 4) == (0, 4, 8, 11)
    assert c.control_rows(9, 4) == (0, 4, 8)
    assert c.control_rows(5, 1) == (0, 1, 2, 3, 4)
    assert c.control_rows(3, 10) == (0, 2)
    with pytest.raises(ValueError, match="spacing_bases"):
        c.control_rows(10, 0)


def test_design_puts_points_in_the_side_overlaps_and_on_the_edges():
    # three strips 1000 m apart along X, photos every 500 m
    C = np.array([[[500.0 * j, 1000.0 * k] for j in range(9)] for k in range(3)])
    d = c.design_control(C, 4)
    assert d.rows == (0, 4, 8) and d.points_m.shape == (3, 4, 2) and d.n_points == 12
    np.testing.assert_allclose(d.points_m[1, :, 0], 2000.0)
    np.testing.assert_allclose(d.points_m[1, :, 1], [-500.0, 500.0, 1500.0, 2500.0])
    dense = c.design_control(C, 1)
    assert dense.dense and dense.n_points == 9 * 4
    one = c.design_control(C[:1], 2, strip_spacing_m=800.0)
    np.testing.assert_allclose(sorted(one.points_m[0, :, 1]), [-400.0, 400.0])
    with pytest.raises(ValueError, match="strip_spacing_m"):
        c.design_control(C[:1], 2)


def test_the_spacing_is_zhukovs():
    kw = dict(k_i=1.2, b_mm=72.0, m_eps_arcmin=4.5)
    n = c.control_spacing_bases(0.35, **kw)
    assert n == tri.zhukov_max_bases(0.35, **kw) == 4
    assert tri.zhukov_error_mm(n, **kw) <= 0.35 < tri.zhukov_error_mm(n + 1, **kw)
    assert c.control_spacing_bases(0.35, k_i=2.0, b_mm=72.0, m_eps_arcmin=4.5) == 1  # dense


def test_marking_rules():
    assert c.MARKING_CIRCLES_MM == (8.0, 10.0) and c.PRICKING_MM == 0.1 and c.IDENTIFICATION_MM == 0.1
    assert c.marking_circles_ground_m(12000.0) == pytest.approx((96.0, 120.0))


# --------------------------------------------------------------------------- the guide's §11 table
def test_the_projection_is_pulkovo_1942_zone_5_and_round_trips():
    XY = guide.ch10.projected(54.85, 24.55)
    assert XY[1] == pytest.approx(5342600, abs=300) and 5_000_000 < XY[1] < 6_000_000  # zone 5 prefix
    np.testing.assert_allclose(guide.ch10.geographic(*XY), [54.85, 24.55], atol=1e-9)
    # on the central meridian 27° E the easting is the false easting 5 500 000 m
    assert guide.ch10.projected(54.0, 27.0)[1] == pytest.approx(5_500_000.0, abs=1e-3)


def test_the_tables_xy_are_not_the_projection_of_its_phi_lambda():
    a = guide.ch10.coordinate_table()
    assert len(a.values) == 16 and len(a.discrepancies) == 16
    assert all(p.reason for p in a.discrepancies)
    s = guide.ch10.shift_summary()
    assert s["mean_dX_m"] == pytest.approx(-17377, abs=5) and s["mean_dY_m"] == pytest.approx(-28758, abs=5)
    assert s["sd_dX_m"] < 60 and s["sd_dY_m"] < 90  # a nearly common shift
    assert 100 < s["max_relative_m"] < 130  # the relative positions disagree too
    assert "17.4 km" in a.values[0].reason and "28.8 km" in a.values[1].reason
    assert any("OCR" in n for n in a.notes)
