"""The camera model: exact projection, o/n/c, tilt and relief displacement."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aerophoto import geometry as g

CAM = g.Camera(100.0, 180.0)


def test_guide_isocentre_example():
    # guide §5, step 3: oc = -f*tg(α/2) = -100*tg(3°/2) = -2.6 mm
    pose = g.Pose(0, 0, 1200, alpha_deg=3, lambda_deg=0)
    c = g.isocentre(CAM, pose)
    assert c[0] == pytest.approx(-100 * math.tan(math.radians(1.5)), rel=1e-12)  # -2.6186
    assert round(c[0], 1) == -2.6
    n = g.nadir_point(CAM, pose)
    assert n[0] == pytest.approx(-100 * math.tan(math.radians(3)), rel=1e-12)  # on = f·tan α = 5.24 mm


def test_nadir_is_image_of_plumb_point():
    pose = g.Pose(500, -300, 1500, alpha_deg=7, lambda_deg=-57, kappa_deg=20)
    plumb = np.array([500, -300, 100.0])
    assert np.allclose(g.ground_to_photo(CAM, pose, plumb), g.nadir_point(CAM, pose), atol=1e-9)


def test_far_side_is_positive_principal_vertical():
    # a point imaged on the + principal vertical lies farther from the plumb point than o's ground point
    pose = g.Pose(0, 0, 1000, alpha_deg=10, lambda_deg=30)
    u = g.principal_vertical(pose)
    Po = g.photo_to_plane(CAM, pose, [0.0, 0.0], 0)
    Pf = g.photo_to_plane(CAM, pose, 50 * u, 0)
    Pn = g.photo_to_plane(CAM, pose, -50 * u, 0)
    # o's ground point lies f·tanα·m... away from the plumb point, in the azimuth of +u
    assert math.hypot(Po[0], Po[1]) == pytest.approx(1000 * math.tan(math.radians(10)))
    assert math.hypot(Pf[0], Pf[1]) > math.hypot(Po[0], Po[1])
    # -50 mm lies beyond the nadir (n is at -17.6 mm): on the other side of the plumb point
    assert np.dot(Pn[:2], Po[:2]) < 0


def test_vertical_photo_scale_and_heading():
    pose = g.Pose.vertical(1000, 2000, 1200, kappa_deg=90)
    xy = g.ground_to_photo(CAM, pose, [[1000, 2000 + 120, 0]])  # 120 m north
    # heading 90°: photo +x points north; scale 1:12000 -> 120 m = 10 mm
    assert np.allclose(xy, [[10.0, 0.0]], atol=1e-9)
    assert g.photo_scale_denominator(CAM, 1200) == pytest.approx(12000)


poses = st.builds(
    g.Pose,
    X_m=st.floats(-5000, 5000),
    Y_m=st.floats(-5000, 5000),
    Z_m=st.floats(600, 5000),
    alpha_deg=st.floats(-15, 15),
    lambda_deg=st.floats(-180, 180),
    kappa_deg=st.floats(-180, 180),
)
cams = st.builds(g.Camera, f_mm=st.floats(50, 350), frame_mm=st.just(180.0))


@settings(max_examples=200, deadline=None)
@given(cams, poses, st.floats(-80, 80), st.floats(-80, 80), st.floats(-200, 300))
def test_round_trip_photo_ground_photo(cam, pose, x, y, z):
    P = g.photo_to_plane(cam, pose, [x, y], z)
    assert P[2] == pytest.approx(z)
    back = g.ground_to_photo(cam, pose, P)
    assert np.allclose(back, [x, y], atol=1e-6)


@settings(max_examples=100, deadline=None)
@given(cams, poses)
def test_alpha_zero_collapses_o_n_c(cam, pose):
    p = pose.with_(alpha_deg=0.0)
    for pt in (g.nadir_point(cam, p), g.isocentre(cam, p)):
        assert np.allclose(pt, 0.0, atol=1e-12)
    xy = np.array([[30.0, -40.0], [-70, 10]])
    assert np.allclose(g.tilt_displacement_exact(cam, p, xy), 0)
    assert np.allclose(g.tilt_displacement_approx(cam, p, xy), 0)


@settings(max_examples=100, deadline=None)
@given(st.floats(0, 100), st.floats(100, 5000))
def test_zero_height_gives_zero_relief_displacement(r, H):
    assert g.relief_displacement(r, 0.0, H) == 0.0


@settings(max_examples=150, deadline=None)
@given(cams, poses.filter(lambda p: abs(p.alpha_deg) > 0.2), st.floats(-70, 70), st.floats(-70, 70))
def test_projected_tilt_displacement_is_radial_from_c_and_matches_closed_form(cam, pose, x, y):
    P = g.photo_to_plane(cam, pose, [x, y], pose.Z_m - 1000)
    xy_t, xy_v = g.tilt_displacement_vectors(cam, pose, P)
    c = g.isocentre(cam, pose)
    d_t, d_v = xy_t - c, xy_v - c
    # radial: the tilted and vertical images lie on one line through c
    cross = d_t[0] * d_v[1] - d_t[1] * d_v[0]
    assert abs(cross) <= 1e-7 * max(1.0, np.hypot(*d_t) ** 2)
    delta = np.hypot(*d_t) - np.hypot(*d_v)
    assert delta == pytest.approx(float(g.tilt_displacement_exact(cam, pose, xy_t)), abs=1e-7)


@pytest.mark.parametrize("alpha", [0.5, 1.0, 2.0, 3.0])
def test_exact_tends_to_approx_as_alpha_shrinks(alpha):
    pose = g.Pose(0, 0, 1000, alpha_deg=alpha, lambda_deg=-60)
    xy = np.array([[60.0, 20.0], [-50, 70], [80, -80]])
    ex = g.tilt_displacement_exact(CAM, pose, xy)
    ap = g.tilt_displacement_approx(CAM, pose, xy)
    # relative error of the approximation is ~ r·cosφ·sinα/f, i.e. proportional to α
    rel = np.max(np.abs(ex - ap) / np.abs(ex))
    assert rel <= 1.2 * 113 * math.sin(math.radians(alpha)) / 100
    if alpha == 0.5:
        assert rel < 0.011


def test_relief_displacement_is_exact_on_a_vertical_photo():
    H = 1500.0
    pose = g.Pose.vertical(0, 0, H)
    top = np.array([400.0, 300.0, 60.0])
    foot = np.array([400.0, 300.0, 0.0])
    r_top = np.hypot(*g.ground_to_photo(CAM, pose, top))
    r_foot = np.hypot(*g.ground_to_photo(CAM, pose, foot))
    assert g.relief_displacement(r_top, 60.0, H) == pytest.approx(r_top - r_foot, rel=1e-12)


def test_photo_to_dem_on_hills():
    class Hills:
        z_min_m, z_max_m = 100.0, 300.0

        def height(self, X, Y):
            return 200 + 100 * np.sin(X / 700.0) * np.cos(Y / 500.0)

    pose = g.Pose(0, 0, 1400, alpha_deg=4, lambda_deg=20)
    xy = np.stack(np.meshgrid(np.linspace(-85, 85, 9), np.linspace(-85, 85, 9)), -1).reshape(-1, 2)
    P = g.photo_to_dem(CAM, pose, xy, Hills())
    assert np.allclose(P[:, 2], Hills().height(P[:, 0], P[:, 1]), atol=1e-3)
    assert np.allclose(g.ground_to_photo(CAM, pose, P), xy, atol=1e-6)


def test_photo_to_dem_on_a_lattice_interpolates_between_exact_cuts():
    """lattice_mm: the rays cut at a lattice's nodes only, the points interpolated — exact at the nodes, its error
    shrinking with the step's square, and the exact answer where a lattice would not save work."""
    class Hills:
        z_min_m, z_max_m = 100.0, 300.0

        def height(self, X, Y):
            return 200 + 100 * np.sin(X / 700.0) * np.cos(Y / 500.0)

    pose = g.Pose(0, 0, 1400, alpha_deg=4, lambda_deg=20)
    rng = np.random.default_rng(5)
    xy = rng.uniform(-85, 85, (20000, 2))  # more points than the 2 mm lattice has nodes (86²)
    exact = g.photo_to_dem(CAM, pose, xy, Hills(), tol_m=1e-7)
    err = {}
    for s in (2.0, 4.0, 8.0):
        approx = g.photo_to_dem(CAM, pose, xy, Hills(), tol_m=1e-7, lattice_mm=s)
        assert approx.shape == exact.shape
        err[s] = np.hypot(*(approx - exact)[:, :2].T).max()
    assert 0 < err[2.0] < err[4.0] < err[8.0] < 5.0  # metres on the ground at 1:14 000
    assert 2.5 < err[8.0] / err[4.0] < 6.0 and 2.5 < err[4.0] / err[2.0] < 6.0  # ~ step²
    # a point on a node is cut exactly (the lattice starts at the points' lower-left corner)
    corner = xy.min(axis=0)
    on_node = np.vstack([corner, corner + 4.0 * np.array([3, 5]), xy])
    got = g.photo_to_dem(CAM, pose, on_node, Hills(), tol_m=1e-7, lattice_mm=4.0)
    assert np.allclose(got[:2], g.photo_to_dem(CAM, pose, on_node[:2], Hills(), tol_m=1e-7), atol=1e-9)
    # the shape follows the input's; a few points (fewer than a lattice's nodes) are cut exactly
    grid = xy[:12].reshape(3, 4, 2)
    assert g.photo_to_dem(CAM, pose, grid, Hills(), lattice_mm=4.0).shape == (3, 4, 3)
    assert np.array_equal(g.photo_to_dem(CAM, pose, grid, Hills(), lattice_mm=4.0),
                          g.photo_to_dem(CAM, pose, grid, Hills()))
    with pytest.raises(ValueError, match="lattice_mm"):
        g.photo_to_dem(CAM, pose, xy, Hills(), lattice_mm=0.0)


def test_rotation_matrix_is_remembered_read_only():
    pose = g.Pose(0, 0, 1400, alpha_deg=4, lambda_deg=20, kappa_deg=7)
    R = g.rotation_matrix(pose)
    assert R is g.rotation_matrix(g.Pose(5, 5, 900, alpha_deg=4, lambda_deg=20, kappa_deg=7))  # angles only
    assert np.allclose(R @ R.T, np.eye(3), atol=1e-12)
    with pytest.raises(ValueError, match="read-only"):
        R[0, 0] = 2.0


def test_footprint_of_vertical_photo_is_square():
    pose = g.Pose.vertical(0, 0, 1200)
    fp = g.footprint(CAM, pose, 0)
    assert np.allclose(np.abs(fp[:, :2]), 1080.0)  # 90 mm × 12000


@pytest.mark.parametrize(
    "make, name",
    [
        (lambda: g.Camera(f_mm=0), "f_mm"),
        (lambda: g.Camera(f_mm=-100), "f_mm"),
        (lambda: g.Camera(frame_mm=0), "frame_mm"),
        (lambda: g.Pose(alpha_deg=90), "alpha_deg"),
        (lambda: g.Pose(alpha_deg=-95), "alpha_deg"),
        (lambda: g.Pose.vertical(0, 0, 0), "H_m"),
        (lambda: g.Pose(Z_m=100).flying_height(150), "Z_m"),
        (lambda: g.photo_to_plane(CAM, g.Pose(Z_m=100), [0, 0], 120), "Z_m"),
        (lambda: g.relief_displacement(50, 10, -5), "H_m"),
        (lambda: g.relief_displacement(50, 1500, 1000), "h_m"),
    ],
)
def test_bad_input_names_parameter_value_and_range(make, name):
    with pytest.raises(ValueError) as e:
        make()
    msg = str(e.value)
    assert name in msg and "range" in msg
