"""Radial strip phototriangulation and its reduction (guide §7, §13): aerophoto.triangulation, guide.ch06, guide.ch12."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aerophoto import geometry as g
from aerophoto import plane
from aerophoto import triangulation as T
from aerophoto import guide

CAM = g.Camera(100.0)
M_PHOTO = 12000.0
H = CAM.f_mm / 1000.0 * M_PHOTO
B = 0.4 * CAM.frame_mm / 1000.0 * M_PHOTO  # photo base at p_x = 60 %


def vertical_strip(n_photos=5, *, kappa_deg=0.0, x0=1000.0, y0=500.0):
    a = math.radians(kappa_deg)
    return [g.Pose(x0 + i * B * math.cos(a), y0 + i * B * math.sin(a), H, 0.0, 0.0, kappa_deg) for i in range(n_photos)]


class WavyTerrain:
    """A DEM with ±40 m of relief (for exactness tests that need relief)."""

    z_min_m = -40.0
    z_max_m = 40.0

    def height(self, X, Y):
        return 40.0 * np.sin(np.asarray(X) / 700.0) * np.cos(np.asarray(Y) / 500.0)


# ----------------------------------------------------------------------------- design and templates
def test_design_points_kinds_and_counts():
    poses = vertical_strip(4)
    pts = T.design_points(CAM, poses, None, photo_numbers=[36, 37, 38, 39])
    kinds = np.array(pts.kinds)
    assert (kinds == "centre").sum() == 4
    assert (kinds == "orienting").sum() == 6  # А … Е: two per double overlap (guide §13: A, Б, В, Г, Д, Е)
    assert (kinds == "tie").sum() == 4  # a, b, c, d
    assert [pts.names[i] for i in np.flatnonzero(kinds == "control")] == ["36/1", "36/2", "39/1", "39/2"]
    assert [pts.names[i] for i in np.flatnonzero(kinds == "orienting")] == list("АБВГДЕ")
    tm = T.measure_templates(CAM, poses, pts, pricking_mm=0.0)
    # tie points on three photos, orienting and (overlap layout) control points on two, centres on three or two
    for i in np.flatnonzero(kinds == "tie"):
        assert tm.pricked[:, i].sum() == 3
    for i in np.flatnonzero((kinds == "orienting") | (kinds == "control")):
        assert tm.pricked[:, i].sum() == 2
    assert tm.pricked[:, pts.centre_index].sum(axis=0).tolist() == [2, 3, 3, 2]
    # the tie points are 2–3 cm from the edge of the photo they were chosen on
    for i in np.flatnonzero(kinds == "tie"):
        y = abs(tm.true_xy_mm[pts.photo[i], i, 1])
        assert 20.0 <= CAM.half_mm - y <= 30.0


def test_working_centre_offset_is_limited_to_f_over_30():
    poses = vertical_strip(3)
    T.design_points(CAM, poses, None, centre_offset_mm=(3.3, 0.0))  # 3.3 ≤ 100/30
    with pytest.raises(ValueError, match="f/30"):
        T.design_points(CAM, poses, None, centre_offset_mm=(3.4, 0.0))


def test_template_directions_are_the_photo_directions():
    poses = vertical_strip(3, kappa_deg=20.0)
    pts = T.design_points(CAM, poses, None)
    tm = T.measure_templates(CAM, poses, pts, pricking_mm=0.0)
    own = pts.centre_index[1]
    nxt = pts.centre_index[2]
    # on a vertical photo with κ the photo x axis points along the flight: the next centre lies at 0°
    assert tm.directions_rad[1, nxt] == pytest.approx(0.0, abs=1e-12)
    assert np.isnan(tm.directions_rad[1, own])
    assert tm.table(1).loc[pts.names[pts.centre_index[0]], "direction, °"] == pytest.approx(180.0)


def test_templates_are_deterministic_for_a_seed():
    poses = vertical_strip(5)
    pts = T.design_points(CAM, poses, None)
    a = T.measure_templates(CAM, poses, pts, pricking_mm=0.1, seed=7)
    b = T.measure_templates(CAM, poses, pts, pricking_mm=0.1, seed=7)
    c = T.measure_templates(CAM, poses, pts, pricking_mm=0.1, seed=8)
    np.testing.assert_array_equal(a.directions_rad, b.directions_rad)
    assert not np.allclose(np.nan_to_num(a.directions_rad), np.nan_to_num(c.directions_rad))
    fa, fb = T.lay_free_strip(a), T.lay_free_strip(b)
    np.testing.assert_array_equal(fa.points_mm, fb.points_mm)


def test_pricking_error_has_the_stated_rms():
    poses = vertical_strip(7)
    pts = T.design_points(CAM, poses, None)
    tm = T.measure_templates(CAM, poses, pts, pricking_mm=0.1, seed=3)
    d = (tm.xy_mm - tm.true_xy_mm)[tm.pricked]
    rms = float(np.sqrt(np.mean(np.sum(d * d, axis=1))))
    assert 0.08 < rms < 0.12


# ----------------------------------------------------------------------------- exactness without error
@pytest.mark.parametrize("start", ["first", "last"])
@pytest.mark.parametrize("kappa", [0.0, 35.0])
def test_zero_error_flat_ground_is_a_similarity_of_the_truth(start, kappa):
    poses = vertical_strip(6, kappa_deg=kappa)
    rng = np.random.default_rng(1)
    offs = rng.uniform(-2.0, 2.0, size=(6, 2))  # working centres anywhere within f/30 of o
    pts = T.design_points(CAM, poses, 150.0, centre_offset_mm=offs)
    tm = T.measure_templates(CAM, poses, pts, pricking_mm=0.0)
    fs = T.lay_free_strip(tm, first_base_mm=77.0, start=start)
    s, R, t, res = fs.similarity_to_truth()
    assert np.nanmax(res) * 1000.0 / s < 1e-6  # in template mm
    assert fs.max_triangle_side_mm < 1e-6
    red = T.reduce_strip(fs)
    c = red.coefficients
    assert np.ptp(c.k) < 1e-9 and c.spread < 1e-9 and c.all_ok
    assert red.max_control_residual_mm < 1e-6
    assert np.max(red.errors_mm) < 1e-6


def test_zero_error_with_relief_is_exact_when_centres_are_the_nadir_points():
    # radial triangulation's premise: directions from the nadir point are free of relief displacement
    poses = vertical_strip(5, kappa_deg=-15.0)
    pts = T.design_points(CAM, poses, WavyTerrain(), centre_offset_mm=(0.0, 0.0))
    assert np.ptp(pts.XYZ_m[:, 2]) > 30.0
    tm = T.measure_templates(CAM, poses, pts, pricking_mm=0.0)
    fs = T.lay_free_strip(tm, scale_ratio=0.9)
    assert fs.max_triangle_side_mm < 1e-6
    red = T.reduce_strip(fs)
    assert red.k == pytest.approx(1.0 / 0.9, rel=1e-9)
    assert np.max(red.errors_mm) < 1e-6
    # … and not exact when the centres are off the nadir points by different amounts (relief turns the
    # directions; with one common offset the rays still meet, in points shifted by their height)
    offs = np.random.default_rng(5).uniform(-2.3, 2.3, size=(5, 2))
    pts2 = T.design_points(CAM, poses, WavyTerrain(), centre_offset_mm=offs)
    fs2 = T.lay_free_strip(T.measure_templates(CAM, poses, pts2, pricking_mm=0.0), scale_ratio=0.9)
    assert fs2.max_triangle_side_mm > 1e-4
    assert np.max(T.reduce_strip(fs2).errors_mm) > 1e-3


def test_zero_error_on_the_virtual_site_reproduces_the_truth():
    from aerophoto import simulate, site

    s = site.get_site()
    strip = simulate.strip_over_site(s, CAM, M_PHOTO, 60.0, 5)
    pts = T.design_points(CAM, strip.poses, s, catalogue=s.catalogue, centre_offset_mm=(0.0, 0.0))
    assert "catalogue" in pts.source  # some points are the site's catalogue points
    tm = T.measure_templates(CAM, strip.poses, pts, pricking_mm=0.0)
    fs = T.lay_free_strip(tm, scale_ratio=0.96)
    sc, R, t, res = fs.similarity_to_truth()
    assert np.nanmax(res) < 1e-6  # metres on the ground
    assert fs.max_triangle_side_mm < 1e-6
    red = T.reduce_strip(fs)
    assert np.ptp(red.coefficients.k) < 1e-9
    assert red.max_control_residual_mm < 1e-6


def test_tilt_distorts_the_directions_even_without_pricking_error():
    poses = [p.with_(alpha_deg=2.0, lambda_deg=40.0 * i) for i, p in enumerate(vertical_strip(5))]
    pts = T.design_points(CAM, poses, None)
    fs = T.lay_free_strip(T.measure_templates(CAM, poses, pts, pricking_mm=0.0))
    red = T.reduce_strip(fs)
    assert fs.max_triangle_side_mm > 1e-3
    assert red.max_control_residual_mm > 1e-3


# ----------------------------------------------------------------------------- growth with error and strip length
def _mean_over_seeds(n_photos, pricking, seeds=range(12)):
    poses = vertical_strip(n_photos)
    pts = T.design_points(CAM, poses, None)
    tri, ctl = [], []
    for s in seeds:
        fs = T.lay_free_strip(T.measure_templates(CAM, poses, pts, pricking_mm=pricking, seed=s), method="initial")
        red = T.reduce_strip(fs)
        tri.append(fs.max_triangle_side_mm)
        ctl.append(red.max_control_residual_mm)
    return float(np.mean(tri)), float(np.mean(ctl))


def test_triangles_and_residuals_grow_with_the_pricking_error():
    a = _mean_over_seeds(5, 0.05)
    b = _mean_over_seeds(5, 0.1)
    c = _mean_over_seeds(5, 0.2)
    assert a[0] < b[0] < c[0]
    assert a[1] < b[1] < c[1]
    # both are linear in the error (a small-error theory): doubling the error doubles them
    assert c[0] / b[0] == pytest.approx(2.0, rel=0.05)
    assert c[1] / b[1] == pytest.approx(2.0, rel=0.05)


def test_errors_accumulate_along_the_strip():
    df = T.accumulation_study(n_bases=(2, 4, 6, 8), seeds=range(16))
    e = df["RMS error of points, mm"].to_numpy()
    c = df["RMS control residual, mm"].to_numpy()
    assert np.all(np.diff(e) > 0)
    assert np.all(np.diff(c) > 0)
    assert e[-1] > 2.5 * e[0]  # faster than √n: the azimuth errors carry on from template to template


def test_simulated_accumulation_follows_zhukov_with_n_cubed():
    """The Monte Carlo error of reduced strips against (13.1) read with n³, n² and n⁰."""
    n = np.array([4, 6, 8, 10])
    df = T.accumulation_study(n_bases=tuple(n), seeds=range(16))
    sim = df["RMS error of points, mm"].to_numpy()
    m_eps = T.PRICKING_MM / 72.0 * T.RHO_ARCMIN  # direction error of 0.1 mm over a 72 mm base, arc-minutes
    kw = dict(k_i=M_PHOTO / 10000.0, b_mm=72.0, m_eps_arcmin=m_eps)
    n3 = T.zhukov_error_mm(n, reading="n3", **kw)
    n2 = T.zhukov_error_mm(n, reading="n2", **kw)
    n0 = T.zhukov_error_mm(n, reading="n0", **kw)
    assert np.all(np.abs(sim / n3 - 1.0) < 0.3)
    assert sim[-1] / n2[-1] > 1.8 and sim[-1] / n0[-1] > 2.5
    # the growth from 4 to 10 bases: simulation vs the three readings
    growth = sim[-1] / sim[0]
    assert abs(growth - n3[-1] / n3[0]) < abs(growth - n2[-1] / n2[0]) < abs(growth - n0[-1] / n0[0])


# ----------------------------------------------------------------------------- reduction
def test_reduction_centre_changes_the_corrections_not_the_result():
    poses = vertical_strip(5)
    pts = T.design_points(CAM, poses, None)
    fs = T.lay_free_strip(T.measure_templates(CAM, poses, pts, pricking_mm=0.1, seed=2), scale_ratio=0.95)
    a = T.reduce_strip(fs, centre=2)
    b = T.reduce_strip(fs, centre=0)
    np.testing.assert_allclose(a.plan_mm, b.plan_mm, atol=1e-9)
    np.testing.assert_allclose(a.control_residuals_mm, b.control_residuals_mm, atol=1e-9)
    assert np.max(np.abs(b.corrections.v_mm)) > 1.5 * np.max(np.abs(a.corrections.v_mm))
    assert a.corrections.centre == "3" and a.corrections.v_mm[pts.index("3")] == 0.0


@pytest.mark.parametrize("q", [0.8, 1.25])
def test_corrections_point_away_from_the_centre_when_k_exceeds_one(q):
    poses = vertical_strip(4)
    pts = T.design_points(CAM, poses, None)
    fs = T.lay_free_strip(T.measure_templates(CAM, poses, pts, pricking_mm=0.0), scale_ratio=q)
    red = T.reduce_strip(fs, centre=1)
    k = red.k
    assert k == pytest.approx(1.0 / q)
    C = fs.points_mm[red.centre_index]
    r_before = np.hypot(*(fs.points_mm - C).T)
    r_after = np.hypot(*(red.reduced_mm - C).T)
    np.testing.assert_allclose(r_after - r_before, red.corrections.v_mm, atol=1e-9)  # v = r(k − 1) laid off radially
    assert np.all(np.sign(red.corrections.v_mm[r_before > 0]) == np.sign(k - 1.0))


def test_reduction_coefficients_table_and_tolerances():
    names = ["A", "B", "C"]
    base = np.array([[0.0, 0.0], [200.0, 0.0], [200.0, 100.0]])
    tmpl = base / 1.04
    tmpl[2] += [0.0, 0.5]  # one point off by 0.5 mm on the template
    c = T.reduction_coefficients(names, base, tmpl, pairs="all")
    assert [f"{a}–{b}" for a, b in c.bases] == ["A–B", "A–C", "B–C"]
    np.testing.assert_allclose(c.k, c.l_base_mm / c.l_template_mm)
    assert c.k[0] == pytest.approx(1.04)
    assert c.k_mean == pytest.approx(np.mean(c.k))
    np.testing.assert_allclose(c.dk, c.k - c.k_mean)
    # B–C is 100 mm long: a short base (< 0.4/0.003 = 133 mm) with the relaxed 0.006
    assert T.SHORT_BASE_MM == pytest.approx(133.333, abs=1e-3)
    assert c.short.tolist() == [False, False, True]
    assert c.tol.tolist() == [0.003, 0.003, 0.006]
    assert list(c.table().columns)[:4] == ["l_base (l_осн), mm", "l_template (l_воск), mm", "k", "Δk"]
    ring = T.reduction_coefficients(names, base, tmpl, pairs="perimeter")
    assert [f"{a}–{b}" for a, b in ring.bases] == ["A–B", "B–C", "C–A"]


def test_reduction_tables_follow_the_guide_layout():
    poses = vertical_strip(4)
    pts = T.design_points(CAM, poses, None, photo_numbers=[36, 37, 38, 39])
    red = T.reduce_strip(T.lay_free_strip(T.measure_templates(CAM, poses, pts, seed=1)), centre="37")
    t12 = red.coefficients.table()
    assert list(t12.index) == ["36/1 – 36/2", "36/1 – 39/1", "36/1 – 39/2", "36/2 – 39/1", "36/2 – 39/2",
                               "39/1 – 39/2"]  # the six bases of table 12
    t13 = red.corrections.table()
    assert t13.index.name == "from centre 37" and list(t13.columns) == ["r, mm", "v, mm"]
    np.testing.assert_allclose(t13["v, mm"], t13["r, mm"] * (red.k - 1.0))
    assert red.corrections.table(wide=True).shape == (2, len(pts))  # table 9: one column a point
    full = red.table()
    assert full.loc["36/1", "control ≤ 0.4 mm"] in (True, False)
    assert full.loc["А", "control ≤ 0.4 mm"] is None


# ----------------------------------------------------------------------------- §7: from both ends
def test_build_from_ends_zero_error_is_exact():
    poses = vertical_strip(5)
    pts = T.design_points(CAM, poses, None, control_layout="ends")
    assert sum(k == "control" for k in pts.kinds) == 8  # four on each end photo (guide §7, figure 15)
    es = T.build_from_ends(T.measure_templates(CAM, poses, pts, pricking_mm=0.0))
    assert es.mid == 2
    assert es.mid_discrepancy_mm < 1e-9 and np.max(es.tie_discrepancies_mm) < 1e-9
    assert np.max(es.errors_mm) < 1e-6
    assert len(es.mid_ties) == 2  # the guide's m and n, above and below the middle centre


def test_build_from_ends_with_error_has_two_solutions_for_the_middle():
    poses = vertical_strip(5)
    pts = T.design_points(CAM, poses, None, control_layout="ends")
    es = T.build_from_ends(T.measure_templates(CAM, poses, pts, pricking_mm=0.1, seed=4))
    assert es.mid_discrepancy_mm > 1e-3
    np.testing.assert_allclose(es.centres_mm[es.mid], 0.5 * (es.mid_left_mm + es.mid_right_mm))
    assert 0.0 < np.max(es.errors_mm) < 1.5  # plan mm: a few tenths of a millimetre
    summary = es.summary()
    assert "middle centre 3′ − 3″ (невязка)" in summary.index
    # end templates resected on four control points each
    assert [len(r) for r in es.end_residuals_mm] == [4, 4]


def test_build_from_ends_needs_three_control_points_per_end():
    poses = vertical_strip(5)
    pts = T.design_points(CAM, poses, None, control_layout="overlap")
    with pytest.raises(ValueError, match="at least 3"):
        T.build_from_ends(T.measure_templates(CAM, poses, pts))


# ----------------------------------------------------------------------------- Zhukov (13.1)
def test_zhukov_reading_with_the_guides_inputs():
    kw = dict(k_i=1.0, b_mm=60.0)
    # m_ε = 4′ … 5′ gives 5–6 bases between control points
    assert T.zhukov_bases_continuous(0.35, m_eps_arcmin=4.0, **kw) == pytest.approx(6.66, abs=0.01)
    assert T.zhukov_bases_continuous(0.35, m_eps_arcmin=5.0, **kw) == pytest.approx(5.47, abs=0.01)
    assert T.zhukov_max_bases(0.35, m_eps_arcmin=4.0, **kw) == 6
    assert T.zhukov_max_bases(0.35, m_eps_arcmin=4.5, **kw) == 6
    assert T.zhukov_max_bases(0.35, m_eps_arcmin=5.0, **kw) == 5
    # the value at n = 6, m_ε = 4.5′: 0.25·60·(4.5/3437.75)·√316
    assert T.zhukov_error_mm(6, m_eps_arcmin=4.5, **kw) == pytest.approx(0.25 * 60 * 4.5 / 3437.747 * math.sqrt(316),
                                                                        rel=1e-6)
    assert T.zhukov_error_mm(6, m_eps_arcmin=4.5, **kw) <= 0.35 < T.zhukov_error_mm(7, m_eps_arcmin=4.5, **kw)
    # the other readings give implausibly long strips
    assert T.zhukov_max_bases(0.35, m_eps_arcmin=4.5, reading="n2", **kw) >= 12
    assert T.zhukov_max_bases(0.35, m_eps_arcmin=4.5, reading="n0", **kw) >= 20


def test_zhukov_largest_n_is_largest():
    for me in (3.0, 4.0, 5.0, 6.0):
        for k in (1.0, 1.2, 1.5):
            n = T.zhukov_max_bases(0.35, k_i=k, b_mm=72.0, m_eps_arcmin=me)
            assert T.zhukov_error_mm(n, k_i=k, b_mm=72.0, m_eps_arcmin=me) <= 0.35
            assert T.zhukov_error_mm(n + 1, k_i=k, b_mm=72.0, m_eps_arcmin=me) > 0.35
    assert T.zhukov_max_bases(0.01) == 0


def test_zhukov_coefficient_is_the_chain_held_at_both_ends():
    for n in (2, 4, 6, 10, 20):
        assert T.bridge_variance_factor(n) * 48 == pytest.approx(n**3 + 2 * n)  # no n² term, like n³ + 11n + 34
    assert math.sqrt(3.0 / 48.0) == 0.25  # three direction errors per base → the formula's 0.25
    assert "n³ + 11n + 34" in guide.ch12.ZHUKOV_READING


def test_zhukov_input_checks():
    with pytest.raises(ValueError, match="n = 0"):
        T.zhukov_error_mm(0)
    with pytest.raises(ValueError, match="m_eps_arcmin"):
        T.zhukov_error_mm(3, m_eps_arcmin=0)
    with pytest.raises(ValueError, match="reading"):
        T.zhukov_error_mm(3, reading="n5")


# ----------------------------------------------------------------------------- the guide's tables
def test_table9_corrections_follow_from_r_and_k():
    chk = guide.ch06.table(9)
    v_checks = [c for c in chk.values if c.quantity.startswith("v =")]
    assert len(v_checks) == 12 and all(c.follows for c in v_checks)
    computed = chk.table.loc["v, mm"].to_numpy(dtype=float)
    np.testing.assert_allclose(computed, np.array(guide.ch06.GUIDE_TABLE9["r_mm"]) * 0.037)
    np.testing.assert_allclose(np.round(computed, 1), guide.ch06.GUIDE_TABLE9["v_mm"])
    # what does not follow: the labels (a point twice with two distances) and table 8's template
    bad = {c.where for c in chk.discrepancies}
    assert "table 9, label 498/1" in bad
    assert any("table 9 vs table 8" in w for w in bad)


def test_table8_from_the_coordinates():
    chk = guide.ch06.table(8)
    t = chk.table
    l = t["l_осн from coordinates, mm"].to_numpy()
    np.testing.assert_allclose(l, [196.81, 144.84, 223.15, 129.65], atol=0.01)
    by = {(c.where, c.quantity): c for c in chk.values}
    # rows 1 and 2 are consistent: l_осн rounds to the printed 197 and 145, K to 1.037 and 1.036
    for row in ("496/1 – 498/1", "498/1 – 498/2"):
        assert by[(f"table 8, {row}", "l_осн, mm")].follows
        assert by[(f"table 8, {row}", "K = l_осн/l_воск (printed l_осн)")].follows
    # rows 3 and 4 are not: 223 and 130 mm, and 222/217 = 1.023, 131/126 = 1.040
    for row in ("498/2 – 496/2", "496/2 – 496/1"):
        assert not by[(f"table 8, {row}", "l_осн, mm")].follows
        assert not by[(f"table 8, {row}", "K = l_осн/l_воск (printed l_осн)")].follows
    assert by[("table 8, 498/2 – 496/2", "K = l_осн/l_воск (printed l_осн)")].computed == pytest.approx(1.0230, abs=1e-4)
    # the spread: recomputed it breaks the 0.003 rule either way
    assert not by[("table 8, spread", "largest |ΔK| (printed l_осн) ≤ 0.003?")].follows
    assert not by[("table 8, spread", "largest |ΔK| (l_осн from coordinates) ≤ 0.003?")].follows
    # the printed K themselves do average 1.037
    assert by[("table 8, mean", "mean of the printed K")].follows
    assert len(chk.comparison(only_discrepancies=True)) == len(chk.discrepancies)


def test_guide_tables_7_audits_give_a_reason_exactly_where_a_value_does_not_follow():
    from aerophoto.guide import audit

    for a in (guide.ch06.table8(), guide.ch06.table9()):
        assert a.source == "guide §7" and a.title.startswith(("Table 8.", "Table 9."))
        for p in a.values:
            assert bool(p.reason) == (not p.follows), p
            assert p.reason != audit.GENERIC_REASON
        assert len(a.comparison()) == len(a.discrepancies)
        assert len(a.comparison(only_discrepancies=False)) == len(a.values)
    assert [len(guide.ch06.table8().discrepancies), len(guide.ch06.table9().discrepancies)] == [11, 4]
    assert len(guide.ch06.discrepancies()) == 15 and set(guide.ch06.discrepancies()["table"]) == {"Table 8", "Table 9"}
    with pytest.raises(ValueError, match="number"):
        guide.ch06.table(7)


def test_guide_tables_7_verdicts_are_the_same_under_the_half_unit_rule():
    """The one rule (0.6 of a unit) and the tables' earlier rule (0.5·10⁻ᵈ) agree on every printed value."""
    for a in (guide.ch06.table8(), guide.ch06.table9()):
        for p in a.values:
            lo, hi = p.bounds if p.bounds is not None else (p.computed, p.computed)
            half = lo - 0.5 * p.unit - 1e-9 <= p.printed <= hi + 0.5 * p.unit + 1e-9
            assert half == p.follows, p


def test_zhukov_readings_with_the_guides_inputs():
    t = guide.ch12.zhukov_readings()
    assert list(t.columns) == ["n for m_ε = 4′", "n for m_ε = 4.5′", "n for m_ε = 5′"]
    np.testing.assert_allclose(t.round(2).to_numpy(), [[6.66, 6.01, 5.47], [14.46, 12.22, 10.43],
                                                       [33.38, 25.70, 20.22]])
    assert guide.ch12.GUIDE_ZHUKOV_INPUTS["m_mm"] == 0.35


def test_table8_reproduced_by_reduction_coefficients():
    names = ["496/1", "498/1", "498/2", "496/2"]
    base = np.array([[guide.ch06.GUIDE_S7_CONTROL[n][1], guide.ch06.GUIDE_S7_CONTROL[n][0]] for n in names]) / 10.0  # m → mm at 1:10000
    # a template whose sides are the printed l_воск cannot be checked without its diagonals; use the ratio form
    c = T.reduction_coefficients(names, base, base / 1.037, pairs="perimeter")
    np.testing.assert_allclose(c.k, 1.037)
    np.testing.assert_allclose(np.round(c.l_base_mm[:2]), [197.0, 145.0])


# ----------------------------------------------------------------------------- input checks
def test_input_checks_name_the_parameter():
    poses = vertical_strip(4)
    pts = T.design_points(CAM, poses, None)
    with pytest.raises(ValueError, match="pricking_mm"):
        T.measure_templates(CAM, poses, pts, pricking_mm=-0.1)
    tm = T.measure_templates(CAM, poses, pts)
    with pytest.raises(ValueError, match="first_base_mm"):
        T.lay_free_strip(tm, first_base_mm=0.0)
    with pytest.raises(ValueError, match="start"):
        T.lay_free_strip(tm, start="middle")
    with pytest.raises(ValueError, match="scale_ratio"):
        T.lay_free_strip(tm, scale_ratio=10.0)
    fs = T.lay_free_strip(tm)
    with pytest.raises(ValueError, match="M = 0"):
        T.reduce_strip(fs, M=0)
    with pytest.raises(ValueError, match="centre"):
        T.reduce_strip(fs, centre=9)
    with pytest.raises(ValueError, match="working centre"):
        T.reduce_strip(fs, centre="А")
    with pytest.raises(ValueError, match="len\\(poses\\)"):
        T.design_points(CAM, poses[:2], None)
    with pytest.raises(ValueError, match="control_layout"):
        T.design_points(CAM, poses, None, control_layout="corners")
    with pytest.raises(ValueError, match="r_mm"):
        T.reduction_corrections(["a"], [-1.0], 1.03)


def test_importing_has_no_side_effects():
    import importlib
    import sys

    import matplotlib as mpl

    before = dict(mpl.rcParams)
    names = [n for n in sys.modules if n == "aerophoto.triangulation" or n.startswith("aerophoto.triangulation.")]
    saved = {n: sys.modules.pop(n) for n in names}
    try:
        importlib.import_module("aerophoto.triangulation")  # the package and every submodule, afresh
        assert dict(mpl.rcParams) == before
    finally:
        sys.modules.update(saved)  # the other tests keep the classes they were collected with
        import aerophoto

        aerophoto.triangulation = saved["aerophoto.triangulation"]


# --------------------------------------------------------------------------- the student's convention (geodetic)
@settings(max_examples=40, deadline=None)
@given(X=st.floats(-1e4, 1e4), Y=st.floats(-1e4, 1e4), th=st.floats(-3.1, 3.1))
def test_geodetic_round_trips(X, Y, th):
    G = T.ground_to_geodetic([X, Y])
    assert G == pytest.approx([T.GEODETIC_ORIGIN_M[0] + Y, T.GEODETIC_ORIGIN_M[1] + X])  # X north, Y east
    assert T.geodetic_to_ground(G) == pytest.approx([X, Y], abs=1e-6)
    a = T.direction_to_geodetic_deg(th)
    assert 0.0 <= a < 360.0
    assert T.geodetic_to_direction_rad(a) == pytest.approx(th, abs=1e-9)


def test_geodetic_directions_read_the_same_formulas():
    # a ray from the sheet's centre at θ (math) reaches the same point as the swapped ray at α = 90° − θ (geodetic)
    C = np.array([12.0, -3.0])
    for th in np.radians([0.0, 30.0, 90.0, 200.0, -45.0]):
        P = C + 50.0 * np.array([math.cos(th), math.sin(th)])
        a = math.radians(float(T.direction_to_geodetic_deg(th)))
        Cg, Pg = T.sheet_to_geodetic(C), T.sheet_to_geodetic(P)
        assert Cg + 50.0 * np.array([math.cos(a), math.sin(a)]) == pytest.approx(Pg)
    # so an error triangle is the same in both conventions
    O = np.array([[0.0, 0.0], [70.0, 1.0], [141.0, -2.0]])
    A = np.radians([40.0, 91.0, 139.5])
    _, sides = plane.error_triangle(O, A)
    _, sides_g = plane.error_triangle(T.sheet_to_geodetic(O), np.radians(T.direction_to_geodetic_deg(A)))
    assert sides_g == pytest.approx(sides)
    with pytest.raises(ValueError, match="XY_m"):
        T.ground_to_geodetic([1.0, 2.0, 3.0])
    with pytest.raises(ValueError, match="theta_rad"):
        T.direction_to_geodetic_deg(float("nan"))


def test_tie_points_are_seen_on_all_three_photos_of_every_students_strip():
    # tilted photos turn against each other: a tie point at x = 0 of its photo, or a catalogue point near it,
    # may leave a neighbour's frame; the design slides it along the strip and the catalogue must be seen there
    from aerophoto.labs import ch06
    from aerophoto.variants import variant_for_index

    for i in range(100):
        fs = ch06.lab_strip(variant_for_index(i)).free
        pts = fs.points
        for k, kind in enumerate(pts.kinds):
            if kind == "tie":
                assert fs.n_rays[k] == 3, (i, pts.names[k])
            else:
                assert np.all(np.isfinite(fs.points_mm[k])), (i, pts.names[k])
