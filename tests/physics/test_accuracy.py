"""Error accumulation along a strip and block precision (aerophoto.accuracy), article 001's audit, the block demo."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from aerophoto import accuracy as acc
from aerophoto import geometry as g
from aerophoto import guide, triangulation
from aerophoto.bundle import relative_orientation


# ----------------------------------------------------------------------------------------------- the laws
@given(n=st.integers(0, 300))
def test_squares_sum_is_the_sum_of_squares(n):
    assert acc.squares_sum(n) == pytest.approx(sum(k * k for k in range(1, n + 1)))


def test_free_strip_factor_and_its_n3_approximation():
    assert acc.free_strip_factor(10) == pytest.approx(math.sqrt(385))
    assert acc.free_strip_factor(10, approx=True) == pytest.approx(math.sqrt(1000 / 3))
    big = np.array([100.0, 1000.0])
    np.testing.assert_allclose(acc.free_strip_factor(big) / acc.free_strip_factor(big, approx=True), 1.0, atol=0.02)


def test_middle_factors():
    # the article's recipe: (10.20) with n/2, halved
    assert acc.middle_factor_article(10) == pytest.approx(0.5 * math.sqrt(55))
    assert acc.middle_factor_article(10, approx=True) == pytest.approx(math.sqrt(1000 / 96))
    for n in (2, 4, 10, 16, 40):
        exact = acc.middle_factor_exact(n)
        assert exact == pytest.approx(math.sqrt((n**3 + 2 * n) / 48))
        assert exact == pytest.approx(math.sqrt(triangulation.bridge_variance_factor(n)))
    assert acc.middle_factor_exact(400) / acc.middle_factor_article(400) == pytest.approx(math.sqrt(2), rel=0.01)
    assert acc.middle_factor_exact(10, k=10) == 0.0 and acc.middle_factor_exact(10, k=0) == 0.0


def test_the_reconstructed_1021_reproduces_the_article():
    e = acc.strip_errors_mm(10, 0.01, f_mm=70, b_mm=70)
    assert round(e["X"], 2) == 0.08 and round(e["Z"], 2) == 0.08
    assert round(e["Y"], 2) == 0.05
    # m_D is the plan error (the legend): √(m_X² + m_Y²) = 0.094 mm; the printed 0.11 is √2·m_X (the other reading)
    assert e["D"] == pytest.approx(math.hypot(e["X"], e["Y"])) and round(e["D"], 3) == 0.094
    assert round(acc.COEFF_D_SQRT2 * 0.01 * 10**1.5, 2) == 0.11
    assert acc.strip_errors_mm(10, 0.01, f_mm=140, b_mm=70)["Z"] == pytest.approx(2 * e["Z"])
    # the design examples: n ≈ 8.6 → 8 as printed (the other reading: 7.7 → 7) and n ≈ 3.0 ("2–3")
    assert acc.plan_bases(20000, 10000, 0.02) == pytest.approx(8.61, abs=0.01)
    assert (0.15 / (0.2968 * 0.02)) ** (2 / 3) == pytest.approx(acc.plan_bases(20000, 10000, 0.02), abs=0.01)
    assert acc.whole_bases(acc.plan_bases(20000, 10000, 0.02)) == 8
    assert acc.whole_bases((0.15 / (acc.COEFF_D_SQRT2 * 0.02)) ** (2 / 3)) == 7
    assert acc.allowed_height_error_m(2.5) == pytest.approx(0.5208, abs=1e-4)
    assert acc.height_bases(20000, 0.02, contour_interval_m=2.5, f_mm=100, b_mm=100) == pytest.approx(3.00, abs=0.01)


@given(mq=st.floats(0.001, 0.1), m=st.floats(5000, 50000))
def test_plan_spacing_round_trip(mq, m):
    n = acc.plan_bases(m, 10000, mq)
    assert acc.strip_errors_mm(n, mq)["D"] * m / 10000 == pytest.approx(0.3, rel=1e-9)


def test_bad_input_is_a_clear_error():
    with pytest.raises(ValueError, match="mq_mm"):
        acc.strip_errors_mm(10, -0.01)
    with pytest.raises(ValueError, match="n = "):
        acc.strip_errors_mm(0, 0.01)
    with pytest.raises(ValueError, match="contour_interval_m"):
        acc.allowed_height_error_m(float("nan"))
    with pytest.raises(ValueError, match="every"):
        acc.control_rows(13, 0)
    assert list(acc.control_rows(13, 4)) == [0, 4, 8, 12]
    assert list(acc.control_rows(13, 5)) == [0, 5, 10, 12]


# ----------------------------------------------------------------------------------------------- Monte Carlo
@pytest.fixture(scope="module")
def mc():
    cam = g.Camera(70.0)
    poses = [g.Pose(i * 420.0, 0.0, 420.0) for i in range(17)]  # f = b = 70 mm at 1:6000 over flat ground
    return acc.strip_monte_carlo(cam, poses, 0.0, sigma_mm=0.01 / math.sqrt(2), n_runs=400, seed=1)


def test_batched_relative_orientation_agrees_with_the_single_one():
    cam = g.Camera(100.0)
    left, right = g.Pose(0, 0, 1000, 1.0, 20, 1.0), g.Pose(400, 10, 1005, 0.5, 100, -2.0)
    X, Y = np.meshgrid([0.0, 200.0, 400.0], [-400.0, 0.0, 400.0])
    P = np.column_stack([X.ravel(), Y.ravel(), np.zeros(9)])
    rng = np.random.default_rng(0)
    xl = g.ground_to_photo(cam, left, P) + rng.normal(0, 0.005, (9, 2))
    xr = g.ground_to_photo(cam, right, P) + rng.normal(0, 0.005, (9, 2))
    Rl = g.rotation_matrix(left)
    single = relative_orientation(xl, xr, 100.0, Rl, reject_k=0)
    Rr, u, q = acc._relative_orientation_b(Rl[None], xl[None], xr[None], 100.0)
    np.testing.assert_allclose(Rr[0], single.R_right, atol=1e-10)
    np.testing.assert_allclose(u[0], single.base_dir, atol=1e-10)
    np.testing.assert_allclose(q[0], single.q_mm, atol=1e-10)


def test_noise_free_strip_has_no_error():
    cam = g.Camera(70.0)
    poses = [g.Pose(i * 420.0, 0.0, 420.0) for i in range(7)]
    mc0 = acc.strip_monte_carlo(cam, poses, 0.0, sigma_mm=1e-9, n_runs=2, seed=0)
    assert np.abs(mc0.free_m).max() < 1e-6 and np.abs(mc0.mid_m).max() < 1e-6


def test_free_strip_follows_law_1020(mc):
    n = mc.free_links()[1:]
    for c in range(3):
        r = mc.rms_free_mm()[1:, c]
        d, _ = acc.fit_accumulation(n, r, acc.free_strip_factor)
        ratio = r / (d * acc.free_strip_factor(n))
        assert np.all((ratio[2:] > 0.85) & (ratio[2:] < 1.15)), (c, ratio)  # within 15 % from 3 links on
        assert 0.7 * mc.mq_mm < d < 1.6 * mc.mq_mm
        # the growth of the long strips: the law's own local slope (≈ 1.43 over 6…15 links), within sampling
        slope = np.polyfit(np.log(n[n >= 6]), np.log(r[n >= 6]), 1)[0]
        assert 1.3 < slope < 1.55


def test_middle_follows_the_exact_law_better_than_the_recipe(mc):
    L = mc.mid_n[1:]
    mid = mc.rms_mid_mm()[1:, 2]
    exact = mid / np.array([acc.middle_factor_exact(int(k)) for k in L])
    recipe = mid / acc.middle_factor_article(L)
    spread = lambda x: x.max() / x.min()  # noqa: E731
    assert spread(exact) < 1.15
    assert spread(recipe) > spread(exact) + 0.1
    # control at both ends is far better than at the start only
    assert mc.rms_free_mm()[-1, 2] / mc.rms_mid_mm()[-1, 2] > 3.0


def test_strip_monte_carlo_bad_input():
    cam = g.Camera(70.0)
    with pytest.raises(ValueError, match="at least 3"):
        acc.strip_monte_carlo(cam, [g.Pose(0, 0, 420)] * 2, 0.0)
    with pytest.raises(ValueError, match="sigma_mm"):
        acc.strip_monte_carlo(cam, [g.Pose(i * 420.0, 0, 420) for i in range(4)], 0.0, sigma_mm=0.0)
    with pytest.raises(ValueError, match="share"):  # 20 % forward overlap: no six common points
        acc.strip_monte_carlo(cam, [g.Pose(i * 860.0, 0, 420) for i in range(4)], 0.0)


# ----------------------------------------------------------------------------------------------- blocks
@pytest.fixture(scope="module")
def block3():
    from aerophoto.demos import block_accuracy

    return block_accuracy.block_geometry(3)


def test_block_precision_scales_with_sigma_and_a_block_beats_a_strip(block3):
    from aerophoto.demos import block_accuracy

    a = block_accuracy.block_map(3, 4, "rows", 7.0).precision
    b = block_accuracy.block_map(3, 4, "rows", 14.0).precision
    np.testing.assert_allclose(b.sigma_plan_m, 2 * a.sigma_plan_m, rtol=1e-12)
    for every in (4, 6):
        s1 = block_accuracy.block_map(1, every, "rows", 7.0).precision
        s4 = block_accuracy.block_map(4, every, "rows", 7.0).precision
        r = acc.block_vs_strip(s1, s4)
        assert 1.5 <= r["plan"] <= 2.2 and 1.5 <= r["height"] <= 2.2  # the article: 1.5–2 times
    # sparser control, larger errors — faster in height
    s2 = block_accuracy.block_map(1, 2, "rows", 7.0).precision.summary()
    s12 = block_accuracy.block_map(1, 12, "rows", 7.0).precision.summary()
    assert s12["height RMS, m"] / s2["height RMS, m"] > s12["plan RMS, m"] / s2["plan RMS, m"] > 2.0


def test_block_monte_carlo_agrees_with_the_covariance(block3):
    from aerophoto import site

    cam, poses, strip, order, pts = block3
    r = acc.block_monte_carlo(cam, poses, strip, order, site.get_site(), every=6, sigma_mm=0.007, n_runs=12, seed=3,
                              points_m=pts)
    assert r["plan RMS, m"] == pytest.approx(r["plan RMS predicted, m"], rel=0.2)
    assert r["height RMS, m"] == pytest.approx(r["height RMS predicted, m"], rel=0.2)


def test_block_precision_bad_input(block3):
    from aerophoto import site

    cam, poses, strip, order, pts = block3
    with pytest.raises(ValueError, match="layout"):
        acc.block_precision(cam, poses, strip, order, site.get_site(), layout="diagonal")
    with pytest.raises(ValueError, match="points_m has shape"):
        acc.block_precision(cam, poses, strip, order, site.get_site(), points_m=pts[:-1])


# ----------------------------------------------------------------------------------------------- article 001's audit
def test_article_001_audit_names_the_one_number_that_does_not_follow():
    a = guide.ch14.examples()
    bad = a.discrepancies
    assert len(bad) == 1
    assert {p.quantity for p in bad} == {"m_D, mm"}  # 0.11 printed, 0.094 by the legend's plan error
    assert bad[0].printed == 0.11 and bad[0].computed == pytest.approx(0.0939, abs=1e-4)
    n = next(p for p in a.values if p.quantity == "bases between plan control n")
    assert n.follows and n.printed == 8 and "7" in n.note
    assert all(p.reason for p in bad)
    assert all(not p.reason for p in a.values if p.follows)
    assert "n³" in guide.ch14.RECONSTRUCTION and "(10.21)" in guide.ch14.RECONSTRUCTION
    assert len(guide.ch14.discrepancies()) == 1


# ----------------------------------------------------------------------------------------------- the live demo
def test_block_error_demo_moves_its_artists_and_opens_on_the_article_example():
    from aerophoto.demos.block_accuracy import BlockErrorDemo

    d = BlockErrorDemo()
    assert d.values["sigma_um"] == 7 and d.values["every"] == 4  # m_q = 0.01 mm → σ = 7 µm
    before = d.view.pts.get_array().copy()
    d.set(sigma_um=14)
    np.testing.assert_allclose(d.view.pts.get_array(), 2 * before, rtol=1e-9)
    n0 = len(d.view.pts.get_offsets())
    d.set(n_strips=1)
    assert len(d.view.pts.get_offsets()) < n0
    d.set(every=12, quantity="height")
    assert "every 12 bases" in d.view.ax_map.get_title()
    assert "height" in d.table.value
    with pytest.raises(ValueError, match="sigma_um"):
        d.set(sigma_um=100)
    d.reset()
    assert d.values["sigma_um"] == 7
    d.draw(force=True)
    d.close()
