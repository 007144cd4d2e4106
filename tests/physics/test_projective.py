"""aerophoto.projective (guide §10, §12): fits from point pairs, mutual grids, transfer cell by cell, resampling."""

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aerophoto import geometry as g
from aerophoto import plane
from aerophoto import projective as pj

QUAD = np.array([[-60.0, -50.0], [55.0, -45.0], [70.0, 60.0], [-50.0, 52.0]])


def _tilted(alpha=8.0, lam=-60.0, kappa=10.0, f=100.0, H=1200.0):
    """Ground square corners (m) and their images (mm) on a tilted photo, plan at 1:10 000 (mm)."""
    cam = g.Camera(f)
    pose = g.Pose(0.0, 0.0, H, alpha, lam, kappa)
    G = np.array([[-700.0, -650.0], [690.0, -720.0], [720.0, 700.0], [-680.0, 660.0]])
    photo = g.ground_to_photo(cam, pose, np.column_stack([G, np.zeros(4)]))
    return photo, G / 10.0


# --------------------------------------------------------------------------- fits (plane's, re-exported)
def test_the_fits_are_planes_own():
    assert pj.fit_projective is plane.fit_projective and pj.Projective2D is plane.Projective2D


def test_four_points_fix_a_projective_transformation_exactly():
    photo, plan_ = _tilted()
    T = pj.fit_projective(photo, plan_)
    np.testing.assert_allclose(T.apply(photo), plan_, atol=1e-9)


@settings(max_examples=25, deadline=None)
@given(alpha=st.floats(0.0, 12.0), lam=st.floats(-180, 180), kappa=st.floats(-90, 90), k=st.integers(4, 12))
def test_projective_fit_recovers_a_tilted_photo_of_flat_ground(alpha, lam, kappa, k):
    cam = g.Camera(100.0)
    pose = g.Pose(0.0, 0.0, 1200.0, alpha, lam, kappa)
    rng = np.random.default_rng(k)
    G = rng.uniform(-600, 600, size=(k, 2))
    photo = g.ground_to_photo(cam, pose, np.column_stack([G, np.zeros(k)]))
    fit = pj.fit("projective", photo, G)
    assert fit.max_residual < 1e-6
    test = g.ground_to_photo(cam, pose, np.array([[100.0, -50.0, 0.0], [-300.0, 250.0, 0.0]]))
    np.testing.assert_allclose(fit.transform.apply(test), [[100.0, -50.0], [-300.0, 250.0]], atol=1e-5)


@pytest.mark.parametrize("corners, match", [
    ([[0, 0], [1, 0], [1, 1]], "exactly 4"),
    ([[0, 0], [1, 0], [2, 0], [0, 1]], "one line"),
    ([[0, 0], [1, 1], [1, 0], [0, 1]], "convex"),
    ([[0, 0], [0, 0], [1, 1], [0, 1]], "coincide"),
    ([[0, 0], [np.inf, 0], [1, 1], [0, 1]], "finite"),
])
def test_a_quadrilateral_must_be_convex_and_in_order(corners, match):
    with pytest.raises(ValueError, match=match):
        pj.check_quadrilateral("corners", corners)


# --------------------------------------------------------------------------- grids
@pytest.mark.parametrize("levels", [0, 1, 2, 3, 4, 5])
def test_the_draughtsmans_diagonal_construction_gives_the_projective_grid(levels):
    photo, _ = _tilted(alpha=10.0)
    np.testing.assert_allclose(pj.diagonal_grid(photo, levels), pj.projective_grid(photo, 2**levels), atol=1e-9)


def test_grid_lines_of_central_directions_run_to_the_vanishing_points():
    photo, _ = _tilted(alpha=10.0)
    nodes = pj.projective_grid(photo, 6)
    Vu, Vv = pj.vanishing_points(photo)
    assert abs(Vu[2]) > 0 and abs(Vv[2]) > 0
    vu, vv = Vu[:2] / Vu[2], Vv[:2] / Vv[2]
    for i in range(7):  # the line u = i/n through its end nodes passes through V_v
        a, b = nodes[0, i], nodes[-1, i]
        cross = (b - a)[0] * (vv - a)[1] - (b - a)[1] * (vv - a)[0]
        assert abs(cross) / (np.hypot(*(b - a)) * np.hypot(*(vv - a))) < 1e-9
    for j in range(7):
        a, b = nodes[j, 0], nodes[j, -1]
        cross = (b - a)[0] * (vu - a)[1] - (b - a)[1] * (vu - a)[0]
        assert abs(cross) / (np.hypot(*(b - a)) * np.hypot(*(vu - a))) < 1e-9


def test_proportional_division_divides_every_side_equally():
    nodes = pj.proportional_grid(QUAD, 5)
    for side in (nodes[0, :], nodes[-1, :], nodes[:, 0], nodes[:, -1]):
        steps = np.hypot(*np.diff(side, axis=0).T)
        np.testing.assert_allclose(steps, steps[0], rtol=1e-12)


def test_on_a_parallelogram_both_constructions_agree_and_the_centres_are_at_infinity():
    para = np.array([[0.0, 0.0], [100.0, 10.0], [130.0, 90.0], [30.0, 80.0]])
    np.testing.assert_allclose(pj.proportional_grid(para, 4), pj.projective_grid(para, 4), atol=1e-9)
    Vu, Vv = pj.vanishing_points(para)
    assert Vu[2] == 0.0 and Vv[2] == 0.0


def test_central_grids_correspond_node_for_node_and_proportional_ones_do_not():
    photo, plan_ = _tilted(alpha=8.0)
    central = pj.grid_pair(photo, plan_, 8, "central")
    prop = pj.grid_pair(photo, plan_, 8, "proportional")
    assert central.node_error().max() < 1e-8
    assert prop.node_error().max() > 0.5  # millimetres on the plan at 8° of tilt


def test_transfer_error_of_central_grids_falls_as_one_over_n_squared():
    photo, plan_ = _tilted(alpha=6.0)
    study = pj.transfer_study(photo, plan_, ns=(2, 4, 8, 16, 32), n_points=300)
    c = study["central max, mm"].to_numpy()
    assert np.all(np.diff(c) < 0)
    np.testing.assert_allclose(c[1:] / c[:-1], 0.25, atol=0.04)
    assert c[-1] < 0.01
    # proportional division: the same error whatever n (the bilinear map of one quadrilateral onto the other)
    p = study["proportional max, mm"].to_numpy()
    np.testing.assert_allclose(p, p[0], rtol=1e-9)
    assert p[0] > 1.0


def test_a_vertical_photo_has_no_grid_error():
    photo, plan_ = _tilted(alpha=0.0)
    study = pj.transfer_study(photo, plan_, ns=(1, 4), n_points=100)
    assert study.to_numpy().max() < 1e-9


def test_locate_finds_the_cell_and_transfer_round_trips():
    photo, plan_ = _tilted(alpha=5.0)
    pair = pj.grid_pair(photo, plan_, 4)
    # the centre of cell (1, 2) of the photo grid
    N = pair.photo_nodes
    centre = (N[1, 2] + N[1, 3] + N[2, 3] + N[2, 2]) / 4
    loc = pj.locate(N, [centre]).iloc[0]
    assert (loc["row"], loc["col"]) == (1, 2) and loc["inside"]
    pts = pj.unit_square_map(photo).apply(np.random.default_rng(5).uniform(0, 1, size=(20, 2)))
    there = pair.transfer(pts)
    back = pj.transfer(pair.plan_nodes, pair.photo_nodes, there)
    np.testing.assert_allclose(back, pts, atol=1e-8)
    # nodes go to nodes exactly
    np.testing.assert_allclose(pair.transfer(N.reshape(-1, 2)), pair.plan_nodes.reshape(-1, 2), atol=1e-9)


def test_points_outside_the_four_are_extrapolated_and_flagged():
    photo, plan_ = _tilted(alpha=3.0)
    loc = pj.locate(pj.projective_grid(photo, 4), [[0.0, 0.0], [200.0, 0.0]])
    assert loc["inside"].tolist() == [True, False]


def test_grid_pair_refuses_a_mirrored_plan():
    photo, plan_ = _tilted()
    with pytest.raises(ValueError, match="opposite senses"):
        pj.grid_pair(photo, plan_[::-1], 4)


def test_grid_sizes_are_bounded():
    with pytest.raises(ValueError, match="n = 0"):
        pj.projective_grid(QUAD, 0)
    with pytest.raises(ValueError, match="method"):
        pj.grid(QUAD, 4, "similar figures")


# --------------------------------------------------------------------------- resampling
def test_warp_photo_with_the_identity_reproduces_the_photo():
    rng = np.random.default_rng(0)
    img = rng.uniform(0, 1, size=(64, 64))
    h = 90.0
    p = 180.0 / 64
    out = pj.warp_photo(img, np.eye(3), (-h, h, -h, h), p)
    assert out.image.shape == (64, 64)
    np.testing.assert_allclose(out.image, img, atol=1e-9)
    # pixel centres and value_at follow the render convention
    np.testing.assert_allclose(out.pixel_centres()[0, 0], [-h + p / 2, h - p / 2])
    np.testing.assert_allclose(out.value_at(out.pixel_centres()[3, 5]), img[3, 5], atol=1e-9)


def test_warp_photo_scales_and_leaves_nan_off_the_photo():
    img = np.zeros((90, 90))
    img[:, 45:] = 1.0  # right half bright: x > 0 on the photo
    S = plane.Similarity2D.from_angle(0.0, (0.0, 0.0), scale=2.0)  # photo mm → plane, twice as large
    out = pj.warp_photo(img, S, (-300, 300, -300, 300), 2.0)
    v = out.value_at(np.array([[-100.0, 0.0], [100.0, 0.0], [250.0, 0.0]]))
    assert v[0] == pytest.approx(0.0) and v[1] == pytest.approx(1.0) and np.isnan(v[2])


def test_warp_photo_validates_its_input():
    with pytest.raises(ValueError, match="square"):
        pj.warp_photo(np.zeros((4, 5)), np.eye(3), (0, 1, 0, 1), 0.1)
    with pytest.raises(ValueError, match="singular"):
        pj.warp_photo(np.zeros((4, 4)), np.zeros((3, 3)), (0, 1, 0, 1), 0.1)
    with pytest.raises(ValueError, match="at most"):
        pj.warp_photo(np.zeros((4, 4)), np.eye(3), (0, 1e6, 0, 1e6), 0.1)
    with pytest.raises(ValueError, match="x_max > x_min"):
        pj.warp_photo(np.zeros((4, 4)), np.eye(3), (1, 0, 0, 1), 0.1)


# --------------------------------------------------------------------------- the scene of §10
def test_the_scene_is_deterministic_and_its_changes_are_new():
    a, b = pj.land_use_scene(7), pj.land_use_scene(7)
    assert [f.name for f in a.features] == [f.name for f in b.features]
    for fa, fb in zip(a.features, b.features):
        np.testing.assert_array_equal(fa.xy_m, fb.xy_m)
    assert pj.land_use_scene(8).rotation_deg != a.rotation_deg
    names = [f.name for f in a.changes()]
    assert {"farm building 1", "farm building 2", "farm building 3", "new road"} <= set(names)
    assert any("moved" in n for n in names)
    assert all(f.status == "new" for f in a.changes())
    assert any(f.status == "gone" for f in a.old()) and not any(f.status == "gone" for f in a.new())
    assert np.all(np.abs(np.vstack([f.xy_m for f in a.features])) <= a.size_m / 2 + 1e-6)


@pytest.mark.parametrize("seed", [0, 1, 17, 99, 2014])
def test_the_control_points_span_a_convex_quadrilateral(seed):
    sc = pj.land_use_scene(seed)
    cp = sc.control_points(0.85)[["X_m", "Y_m"]].to_numpy()
    pj.check_quadrilateral("cp", cp)
    assert np.min(np.abs(cp)) > 0.4 * sc.size_m / 2


def test_scene_input_is_checked():
    with pytest.raises(ValueError, match="size_m"):
        pj.land_use_scene(0, 100.0)
    with pytest.raises(ValueError, match="spread"):
        pj.land_use_scene(0).control_points(0.1)


def test_the_guides_section_10_as_data():
    from aerophoto import guide

    assert guide.ch09.methods_table().shape == (7, 2) and len(guide.ch09.steps_table()) == 4
    assert guide.ch09.PLAN_SCALE_M == 10000.0
    assert {k for _, _, k in guide.ch09.GRID_METHODS if k} == set(pj.METHODS)
