"""Chapter 16's physics (aerophoto.dem): Lysenko's formula, the simulated block, DEMs, contours (article 000)."""

import math

import numpy as np
import pytest
from hypothesis import given
from hypothesis import strategies as st

from aerophoto import dem
from aerophoto import guide
from aerophoto.site import get_site

HILLS = dem.Sheet(2000.0, 3000.0)


class Plane:
    """Z = a + b·X + c·Y: linear interpolation must reproduce it exactly."""

    def __init__(self, a=100.0, b=0.01, c=-0.004):
        self.a, self.b, self.c = a, b, c
        self.z_min_m, self.z_max_m = -1e4, 1e4

    def height(self, X, Y):
        return self.a + self.b * np.asarray(X, float) + self.c * np.asarray(Y, float)


class Vee:
    """A V-shaped valley along Y = y0 (or a ridge with sign −1), tilted gently along X."""

    def __init__(self, y0=500.0, sign=1.0):
        self.y0, self.sign = y0, sign
        self.z_min_m, self.z_max_m = -1e4, 1e4

    def height(self, X, Y):
        return 100.0 + self.sign * 0.05 * np.abs(np.asarray(Y, float) - self.y0) - 0.01 * np.asarray(X, float)


@pytest.fixture(scope="module")
def site():
    return get_site()


@pytest.fixture(scope="module")
def hill_lines(site):
    return dem.structural_lines(site, HILLS)


# --------------------------------------------------------------------------- Lysenko's formula
def test_lysenko_with_the_articles_inputs():
    I = guide.ch16.INPUTS
    root = dem.lysenko_ratio(I["n"], I["m"], I["s"], I["r"])
    assert root == pytest.approx(math.sqrt(3 * (2 * 70 * 3 + 16 * 70 - 3 * 38) / (2 * 16 * 70 * 3)))
    assert root == pytest.approx(0.797877, abs=1e-6)
    assert dem.lysenko_mz_m(450, 70, 0.025, 70, 16, 3, 38) == pytest.approx(0.128230, abs=1e-6)
    # as printed, 0.25 mm: ten times the article's figure
    assert dem.lysenko_mz_m(450, 70, 0.25, 70, 16, 3, 38) == pytest.approx(1.2823, abs=1e-4)
    assert dem.bundle_counts(70, 16, 3, 38) == (6 * 70 + 3 * (16 * 70 / 3 - 38), 2 * 16 * 70)


@given(n=st.integers(1, 400), m=st.integers(3, 60), s=st.floats(2.0, 6.0), frac=st.floats(0.0, 0.9))
def test_the_root_is_the_square_root_of_unknowns_over_observations(n, m, s, frac):
    s = min(s, max(n, 2))
    r = int(frac * (m * n / s - 1))
    u, N = dem.bundle_counts(n, m, s, r)
    assert dem.lysenko_ratio(n, m, s, r) ** 2 == pytest.approx(u / N)
    assert dem.lysenko_ratio(n, m, s, r) ** 2 == pytest.approx(3 * (2 * n * s + m * n - s * r) / (2 * m * n * s))
    # more control, fewer unknowns: the adjusted observations are more precise
    if r > 0:
        assert dem.lysenko_ratio(n, m, s, r) < dem.lysenko_ratio(n, m, s, r - 1)


def test_lysenko_rejects_impossible_blocks():
    with pytest.raises(ValueError, match="r = 400"):
        dem.bundle_counts(70, 16, 3, 400)
    with pytest.raises(ValueError, match="s = 1"):
        dem.lysenko_ratio(70, 16, 1, 3)
    with pytest.raises(ValueError, match="H_m = -450"):
        dem.lysenko_mz_m(-450, 70, 0.025, 70, 16, 3, 38)
    with pytest.raises(ValueError, match="mp_mm = nan"):
        dem.lysenko_mz_m(450, 70, float("nan"), 70, 16, 3, 38)
    with pytest.raises(ValueError, match="n = 0"):
        dem.bundle_counts(0, 16, 3, 0)


# --------------------------------------------------------------------------- the simulated block
@pytest.fixture(scope="module")
def article_block(site):
    px = 100 * (1 - 70 / 180)
    return dem.block_layout(site, px_percent=px, control="spread", control_every=3)


def test_the_block_layout_counts(article_block):
    lay = article_block
    c = lay.counts()
    assert c["n"] == 70 and lay.strips == 7 and lay.per_strip == 10
    assert lay.b_mm == pytest.approx(70.0) and lay.H_m == pytest.approx(450.0)
    assert c["m"] == pytest.approx(16.0)  # four rows × three columns of own strip + the neighbours' edge rows
    assert 3.0 <= c["s"] <= 6.0 and c["r"] >= 30
    assert np.all(lay.visible.sum(axis=1) >= 2)
    # the control points of a spread layout include the block's four corners
    P = lay.points_m[lay.control]
    for fx in (np.min, np.max):
        for fy in (np.min, np.max):
            assert np.any((P[:, 0] == fx(lay.points_m[:, 0])) & (P[:, 1] == fy(lay.points_m[:, 1])))


def test_lysenko_against_the_simulated_block(article_block):
    """The stated tolerance: for a block of the article's size with control spread over it, Lysenko's m_z with
    m_p = √2·σ (the parallax error) is within 10 % of the simulated RMS error of the densified heights."""
    sigma = 0.025 / math.sqrt(2)
    bp = dem.block_precision(article_block, sigma, trials=20, seed=1)
    ratio = bp.rms_Z_m / bp.lysenko_m()
    assert 0.9 <= ratio <= 1.1, ratio
    # read with the error of one coordinate the formula is a third too optimistic
    assert bp.rms_Z_m / bp.lysenko_m(1.0) > 1.25
    # the Monte Carlo confirms the covariance (≈ 6000 height errors: a few per cent)
    assert bp.mc_rms_Z_m == pytest.approx(bp.rms_Z_m, rel=0.06)
    # heights are worse than plan positions (the base-to-height ratio)
    assert bp.rms_Z_m > bp.rms_XY_m
    assert bp.single_pair_m == pytest.approx(450 / 70 * 0.025 / 1000 * 1000, rel=1e-9)


def test_lysenko_does_not_know_where_the_control_is(site):
    px = 100 * (1 - 70 / 180)
    edge = dem.block_precision(dem.block_layout(site, px_percent=px, control="perimeter", control_every=2),
                               0.01, trials=2)
    assert edge.layout.r == pytest.approx(36, abs=4)
    assert edge.rms_Z_m / edge.lysenko_m() > 1.3


def test_block_errors_scale_with_sigma_and_repeat_with_the_seed(site):
    lay = dem.block_layout(site, strips=2, per_strip=4, control_every=2)
    a = dem.block_precision(lay, 0.005, trials=5, seed=3)
    b = dem.block_precision(lay, 0.010, trials=5, seed=3)
    np.testing.assert_allclose(b.sd_Z_m, 2 * a.sd_Z_m)
    np.testing.assert_allclose(b.mc_Z_m, 2 * a.mc_Z_m)
    np.testing.assert_array_equal(dem.block_precision(lay, 0.005, trials=5, seed=3).mc_Z_m, a.mc_Z_m)
    assert list(a.table().index)[-1].startswith("Lysenko")


def test_block_rejects_bad_layouts(site):
    with pytest.raises(ValueError, match="photos is outside"):
        dem.block_layout(site, strips=20, per_strip=10)
    with pytest.raises(ValueError, match="control point"):
        dem.block_layout(site, strips=2, per_strip=3, control="perimeter", control_every=20)
    with pytest.raises(ValueError, match="control"):
        dem.block_layout(site, control="middle")
    with pytest.raises(ValueError, match="sigma_mm"):
        dem.block_precision(dem.block_layout(site, strips=1, per_strip=3), 0.0)


# --------------------------------------------------------------------------- DEMs and contours
def test_linear_dems_reproduce_a_plane_and_its_contours():
    ground = Plane()
    sheet = dem.Sheet(0.0, 0.0, 1000.0)
    for model in (dem.grid_dem(ground, sheet, 70.0),
                  dem.tin_dem(ground, [[0, 0], [1000, 0], [0, 1000], [1000, 1000], [400, 300], [700, 800]])):
        res = dem.evaluate(ground, sheet, model, 0.5, cell_m=10.0)
        assert res.accuracy.rms_m < 1e-9 and res.raster_rms_m < 1e-9
        assert res.accuracy.n_lines > 10
    # the contours of a plane are straight: every vertex of the 105 m contour satisfies the plane's equation
    x, y = sheet.raster(10.0)
    Z = ground.height(*np.meshgrid(x, y))
    lines = dem.contour_lines(x, y, Z, [105.0])
    (z, P), = lines
    np.testing.assert_allclose(ground.height(P[:, 0], P[:, 1]), 105.0, atol=1e-9)


def test_contour_levels_are_multiples_of_the_interval():
    np.testing.assert_allclose(dem.contour_levels(170.2, 172.0, 0.5), [170.5, 171.0, 171.5, 172.0])
    np.testing.assert_allclose(dem.contour_levels(-1.0, 1.0, 1.0), [-1.0, 0.0, 1.0])
    assert len(dem.contour_levels(0.1, 0.4, 0.5)) == 0
    with pytest.raises(ValueError, match="interval_m"):
        dem.contour_levels(0, 10, 0)
    with pytest.raises(ValueError, match="contours"):
        dem.contour_levels(0, 1e4, 0.01)


def test_node_errors_are_averaged_by_the_interpolation():
    """On flat ground the DEM's error is the node errors interpolated: 4/9 (grid) and 1/2 (TIN) of their variance."""
    flat = Plane(100.0, 0.0, 0.0)
    sheet = dem.Sheet(0.0, 0.0, 1000.0)
    grid = dem.grid_dem(flat, sheet, 10.0, mz_m=0.2, seed=4)
    r = dem.evaluate(flat, sheet, grid, 0.5, cell_m=2.5)
    assert r.raster_rms_m == pytest.approx(0.2 * math.sqrt(4 / 9), rel=0.04)
    assert r.interp_rms_m == pytest.approx(0.0, abs=1e-12)
    tin = dem.tin_dem(flat, grid.nodes_m[:, :2], mz_m=0.2, seed=4)
    r = dem.evaluate(flat, sheet, tin, 0.5, cell_m=2.5)
    assert r.raster_rms_m == pytest.approx(0.2 * math.sqrt(0.5), rel=0.04)
    assert dem.predicted_rms(0.0, 0.2, "tin") == pytest.approx(0.2 * math.sqrt(0.5))
    assert dem.predicted_rms(0.03, 0.0, "grid") == pytest.approx(0.03)
    with pytest.raises(ValueError, match="kind"):
        dem.predicted_rms(0.0, 0.1, "spline")


def test_the_prediction_holds_on_the_site(site):
    for d in (30.0, 100.0):
        r = dem.evaluate(site, HILLS, dem.grid_dem(site, HILLS, d, mz_m=0.12), 0.5)
        assert r.accuracy.rms_m == pytest.approx(r.predicted_m, rel=0.12)
        assert r.raster_rms_m == pytest.approx(r.predicted_m, rel=0.1)
    # the article's example: a 30 m grid follows the site's hills to millimetres; the contours carry the nodes' errors
    r = dem.evaluate(site, HILLS, dem.grid_dem(site, HILLS, 30.0, mz_m=0.12), 0.5)
    assert r.interp_rms_m < 0.01
    assert 0.07 < r.accuracy.rms_m < 0.09


def test_contour_rms_decreases_with_structural_lines(site, hill_lines):
    """Adding the structural lines to a coarse grid lowers the RMS of the contour heights: with error-free
    nodes (the interpolation error the lines address) at 100 and 150 m, and with the article's 12 cm node
    errors at 150 m, where interpolation dominates; the article's 30 m grid on the site's smooth hills leaves
    them nothing to add."""
    cases = ((100.0, 0.0), (150.0, 0.0), (150.0, 0.12))
    for d, mz in cases:
        grid = dem.evaluate(site, HILLS, dem.grid_dem(site, HILLS, d, mz_m=mz), 0.5)
        lines = dem.evaluate(site, HILLS, dem.grid_with_lines(site, HILLS, d, hill_lines, mz_m=mz), 0.5)
        assert lines.accuracy.rms_m < grid.accuracy.rms_m, (d, mz)
        assert lines.interp_rms_m < grid.interp_rms_m
    g150 = dem.evaluate(site, HILLS, dem.grid_dem(site, HILLS, 150.0), 0.5).accuracy.rms_m
    l150 = dem.evaluate(site, HILLS, dem.grid_with_lines(site, HILLS, 150.0, hill_lines), 0.5).accuracy.rms_m
    assert l150 < 0.95 * g150
    g30 = dem.evaluate(site, HILLS, dem.grid_dem(site, HILLS, 30.0), 0.5).accuracy.rms_m
    l30 = dem.evaluate(site, HILLS, dem.grid_with_lines(site, HILLS, 30.0, hill_lines), 0.5).accuracy.rms_m
    assert abs(l30 - g30) < 0.002


def test_the_structural_model_has_the_grids_density(site, hill_lines):
    for d in (30.0, 100.0):
        grid = dem.grid_dem(site, HILLS, d)
        s = dem.structural_dem(site, HILLS, d, hill_lines)
        assert s.n_nodes == grid.n_nodes
        assert set(np.unique(s.kinds)) <= {"line", "boundary", "grid"} and "line" in s.kinds
        for corner in ((2000, 3000), (3000, 4000)):
            assert np.any(np.all(np.isclose(s.nodes_m[:, :2], corner), axis=1))


def test_structural_lines_follow_a_valley_and_a_ridge():
    sheet = dem.Sheet(0.0, 0.0, 1000.0)
    v = dem.structural_lines(Vee(500.0, 1.0), sheet, min_curvature_per_m=1e-4)
    assert len(v.valley_xy) > 20
    near = np.abs(v.valley_xy[:, 1] - 500.0) <= 10.0
    assert near.mean() > 0.9  # the thalweg runs along Y = 500
    r = dem.structural_lines(Vee(300.0, -1.0), sheet, min_curvature_per_m=1e-4)
    assert np.mean(np.abs(r.ridge_xy[:, 1] - 300.0) <= 10.0) > 0.9
    P = v.points(50.0)
    d = np.hypot(*(P[:, None, :] - P[None, :, :]).transpose(2, 0, 1))
    assert np.all(d[np.triu_indices(len(P), 1)] >= 50.0 - 1e-9)


def test_dems_are_deterministic_and_grid_errors_survive_the_lines(site, hill_lines):
    a = dem.grid_dem(site, HILLS, 50.0, mz_m=0.1, seed=7)
    b = dem.grid_dem(site, HILLS, 50.0, mz_m=0.1, seed=7)
    c = dem.grid_dem(site, HILLS, 50.0, mz_m=0.1, seed=8)
    np.testing.assert_array_equal(a.nodes_m, b.nodes_m)
    assert not np.array_equal(a.nodes_m, c.nodes_m)
    wl = dem.grid_with_lines(site, HILLS, 50.0, hill_lines, mz_m=0.1, seed=7)
    np.testing.assert_array_equal(wl.nodes_m[: a.n_nodes], a.nodes_m)
    e = a.nodes_m[:, 2] - a.true_Z_m
    assert np.std(e) == pytest.approx(0.1, rel=0.15)


def test_check_point_errors_and_intervals(site):
    grid = dem.grid_dem(site, HILLS, 30.0)
    P = np.array([[2000.0, 3000.0], [2030.0, 3060.0], [2515.0, 3500.0]])
    err = dem.dem_accuracy(site, grid, P)
    np.testing.assert_allclose(err[:2], 0.0, atol=1e-9)  # on the nodes
    assert abs(err[2]) < 0.05
    assert dem.standard_interval(0.096) == 0.5
    assert dem.standard_interval(0.07) == 0.25
    assert dem.standard_interval(0.15) == 0.5
    assert dem.standard_interval(0.151) == 1.0
    assert dem.standard_interval(5.3) == 20.0
    with pytest.raises(ValueError, match="mean_error_m"):
        dem.standard_interval(40.0)


def test_bad_sheets_and_steps_are_clear_errors(site):
    with pytest.raises(ValueError, match="size_m = 10"):
        dem.Sheet(0, 0, 10)
    with pytest.raises(ValueError, match="spacing_m = 0.5"):
        dem.grid_dem(site, HILLS, 0.5)
    with pytest.raises(ValueError, match="one line"):
        dem.tin_dem(site, [[0, 0], [1, 1], [2, 2]])
    with pytest.raises(ValueError, match="cover the sheet"):
        dem.evaluate(site, HILLS, dem.tin_dem(site, [[2100, 3100], [2900, 3100], [2500, 3900]]), 0.5, cell_m=20.0)
