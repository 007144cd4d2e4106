"""The bundle block adjustment (aerophoto.bundle): collinearity, the adjustment, precision, blunders, bad input."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aerophoto import bundle as B
from aerophoto import geometry as g
from aerophoto import simulate, terrain

# ----------------------------------------------------------------------------------------------- collinearity


@settings(max_examples=40)
@given(alpha=st.floats(0, 20), lam=st.floats(-180, 180), kap=st.floats(-180, 180),
       x=st.floats(-800, 800), y=st.floats(-800, 800), z=st.floats(-300, 300))
def test_collinearity_is_the_geometry_camera_model(alpha, lam, kap, x, y, z):
    cam = g.Camera(150.0)
    pose = g.Pose(100.0, -50.0, 2500.0, alpha, lam, kap)
    eo = B.eo_from_pose(pose)
    np.testing.assert_allclose(B.rotation_opk(*eo[3:]), g.rotation_matrix(pose), atol=1e-12)
    P = np.array([[x + 100.0, y - 50.0, z]])
    np.testing.assert_allclose(B.project(eo[None], P, 150.0), g.ground_to_photo(cam, pose, P), atol=1e-9)


@settings(max_examples=40)
@given(o=st.floats(-1.2, 1.2), p=st.floats(-1.2, 1.2), k=st.floats(-3.1, 3.1))
def test_opk_round_trip(o, p, k):
    np.testing.assert_allclose(B.opk_from_matrix(B.rotation_opk(o, p, k)), [o, p, k], atol=1e-9)


def test_jacobian_matches_finite_differences():
    rng = np.random.default_rng(3)
    eo = np.column_stack([rng.uniform(-100, 100, (5, 2)), rng.uniform(2800, 3200, 5), rng.uniform(-0.05, 0.05, (5, 2)),
                          rng.uniform(-3, 3, 5)])
    P = np.column_stack([rng.uniform(-900, 900, (5, 2)), rng.uniform(-200, 200, 5)])
    xy, d_eo, d_pt = B.project_jacobian(eo, P, 200.0)
    for j in range(6):
        h = 1e-3 if j < 3 else 1e-7
        e2 = eo.copy()
        e2[:, j] += h
        e1 = eo.copy()
        e1[:, j] -= h
        num = (B.project(e2, P, 200.0) - B.project(e1, P, 200.0)) / (2 * h)
        np.testing.assert_allclose(d_eo[:, :, j], num, rtol=1e-5, atol=1e-7)
    for j in range(3):
        P2 = P.copy()
        P2[:, j] += 1e-3
        P1 = P.copy()
        P1[:, j] -= 1e-3
        np.testing.assert_allclose(d_pt[:, :, j], (B.project(eo, P2, 200.0) - B.project(eo, P1, 200.0)) / 2e-3,
                                   rtol=1e-6, atol=1e-9)


# ----------------------------------------------------------------------------------------------- a test block

def make_block(*, sigma_mm=0.0, control_sigma=0.05, seed=0, n_strips=3, n_photos=6, control="corners", relief=300.0):
    """A small block over analytic hills: tie points at the standard positions, control, check points."""
    cam = g.Camera(150.0)
    imp = simulate.Imperfections(max_tilt_deg=1.5, max_crab_jitter_deg=2, max_height_percent=1, max_base_percent=3,
                                 seed=seed)
    bl = simulate.fly_block(cam, 10000.0, 65.0, 30.0, n_photos, n_strips, imperfections=imp, ground_Z_m=500.0)
    poses = [s.pose for s in bl.shots]
    cen = bl.centres_m
    T = terrain.AnalyticHills(relief_m=relief, half_side_m=6000.0, X0_m=cen[:, 0].mean(), Y0_m=cen[:, 1].mean(),
                              Z0_m=500.0)
    ties = B.standard_points(cam, poses, T, halfway_mm=0.5 * bl.B_m / (bl.H_m / 150.0))
    lo, hi = cen[:, :2].min(0) - [0.0, 400.0], cen[:, :2].max(0) + [0.0, 400.0]
    rng = np.random.default_rng(seed + 100)
    if control == "corners":
        ctrl_xy = np.array([[lo[0], lo[1]], [hi[0], lo[1]], [hi[0], hi[1]], [lo[0], hi[1]],
                            [(lo[0] + hi[0]) / 2, lo[1]], [(lo[0] + hi[0]) / 2, hi[1]]])
    else:
        ctrl_xy = np.asarray(control, dtype=float)
    chk_xy = rng.uniform(lo + 300.0, hi - 300.0, (40, 2))
    extra = np.vstack([ctrl_xy, chk_xy])
    extra = np.column_stack([extra, T.height(extra[:, 0], extra[:, 1])])
    P = np.vstack([ties, extra])
    kinds = np.array(["tie"] * len(ties) + ["control"] * len(ctrl_xy) + ["check"] * len(chk_xy), dtype=object)
    ids = np.arange(1, len(P) + 1)
    eo = B.eo_from_poses(poses)
    meas = B.simulate_measurements(150.0, 180.0, eo, [s.number for s in bl.shots], [s.strip for s in bl.shots],
                                   [s.index for s in bl.shots], P, ids, kinds, sigma_mm=sigma_mm,
                                   control_sigma_m=control_sigma, seed=seed)
    truth = P[np.searchsorted(ids, meas.point_ids)]
    return meas, eo, truth


def test_noise_free_block_gives_exact_truth_from_the_three_stages():
    meas, eo, truth = make_block(sigma_mm=0.0, control_sigma=0.0)
    ts = B.three_stage(meas)
    assert np.abs(ts.xyz0_m - truth).max() < 0.5  # the stages alone are already close
    adj = B.adjust(meas, ts.eo0, ts.xyz0_m)
    np.testing.assert_allclose(adj.xyz_m, truth, atol=1e-4)
    np.testing.assert_allclose(adj.eo[:, :3], eo[:, :3], atol=1e-4)
    np.testing.assert_allclose(adj.eo[:, 3:], eo[:, 3:], atol=1e-8)
    assert np.abs(adj.v_img_mm).max() < 1e-6


def test_both_solvers_reach_the_same_minimum():
    meas, eo, truth = make_block(sigma_mm=0.005, control_sigma=0.2, seed=4)
    ts = B.three_stage(meas)
    a = B.adjust(meas, ts.eo0, ts.xyz0_m, method="schur")
    b = B.adjust(meas, ts.eo0, ts.xyz0_m, method="scipy")
    np.testing.assert_allclose(a.xyz_m, b.xyz_m, atol=2e-3)
    assert a.sigma0 == pytest.approx(b.sigma0, rel=1e-4)


def test_redundancy_numbers_sum_to_the_degrees_of_freedom():
    meas, eo, truth = make_block(sigma_mm=0.005, control_sigma=0.2, seed=5)
    adj = B.adjust(meas, eo, truth)
    pr = adj.precision()
    total = pr.redundancy_img.sum() + np.nansum(pr.redundancy_ctrl)
    assert total == pytest.approx(adj.dof, rel=1e-8)
    assert adj.dof == meas.n_equations - meas.n_unknowns
    assert np.all((pr.redundancy_img > 0) & (pr.redundancy_img < 1))
    # the per-point blocks agree with the full covariance
    sel = np.flatnonzero(meas.point_kind == "check")[:4]
    C = B.point_covariance(meas, adj.eo, adj.xyz_m, sel)
    for k, i in enumerate(sel):
        np.testing.assert_allclose(C[3 * k:3 * k + 3, 3 * k:3 * k + 3], pr.cov_points[i], rtol=1e-8, atol=1e-12)


@pytest.mark.parametrize("seed", [11, 12, 13])
def test_check_point_rms_matches_the_a_priori_estimate_within_its_sampling_error(seed):
    meas, eo, truth = make_block(sigma_mm=0.006, control_sigma=0.3, seed=seed)
    ts = B.three_stage(meas)
    adj = B.adjust(meas, ts.eo0, ts.xyz0_m)
    assert adj.sigma0 == pytest.approx(1.0, abs=0.15)
    sel = np.flatnonzero(meas.point_kind == "check")
    d = adj.xyz_m[sel] - truth[sel]
    C = B.point_covariance(meas, adj.eo, adj.xyz_m, sel)
    for comps, err in (((0, 1), np.sqrt(np.mean(d[:, 0] ** 2 + d[:, 1] ** 2))), ((2,), np.sqrt(np.mean(d[:, 2] ** 2)))):
        rms, sd = B.rms_expectation(C, comps)
        assert abs(err - rms) <= 3.0 * sd, (comps, err, rms, sd)
        assert sd < 0.5 * rms


def test_rms_expectation_of_independent_errors_is_the_textbook_one():
    k = 50
    C = np.eye(3 * k) * 4.0  # σ = 2 in every coordinate, independent
    rms, sd = B.rms_expectation(C, (0, 1))
    assert rms == pytest.approx(math.sqrt(8.0))
    assert sd == pytest.approx(rms / math.sqrt(2 * 2 * k), rel=1e-9)  # relative SD 1/√(2·(2k))


def test_planted_blunders_are_found_by_data_snooping():
    meas, eo, truth = make_block(sigma_mm=0.005, control_sigma=0.3, seed=21)
    xy = meas.xy_mm.copy()
    per = np.bincount(meas.obs_point)
    i_bad = int(np.flatnonzero((meas.point_kind[meas.obs_point] == "tie") & (per[meas.obs_point] >= 3))[7])
    xy[i_bad] += [0.06, -0.05]
    ctrl = meas.control_XYZ_m.copy()
    c_bad = int(np.flatnonzero(meas.is_control)[1])
    ctrl[c_bad, 2] += 8.0
    bad = meas.replace(xy_mm=xy, control_XYZ_m=ctrl)
    ts = B.three_stage(bad)
    sn = B.data_snooping(bad, ts.eo0, ts.xyz0_m)
    rej = sn.rejected
    assert set(rej["kind"]) == {"image", "control"} and len(rej) == 2
    assert int(rej[rej.kind == "image"]["point"].iloc[0]) == int(meas.point_ids[meas.obs_point[i_bad]])
    assert int(rej[rej.kind == "image"]["photo"].iloc[0]) == int(meas.photo_ids[meas.obs_photo[i_bad]])
    assert int(rej[rej.kind == "control"]["point"].iloc[0]) == int(meas.point_ids[c_bad])
    assert sn.adjustment.sigma0 == pytest.approx(1.0, abs=0.15)
    # without the blunders nothing is rejected
    clean = B.data_snooping(meas, ts.eo0, ts.xyz0_m)
    assert clean.rejected.empty


def test_a_robust_loss_limits_a_blunder():
    meas, eo, truth = make_block(sigma_mm=0.005, control_sigma=0.3, seed=22)
    ctrl = meas.control_XYZ_m.copy()
    c_bad = int(np.flatnonzero(meas.is_control)[0])
    ctrl[c_bad, 2] += 10.0
    bad = meas.replace(control_XYZ_m=ctrl)
    ls = B.adjust(bad, eo, truth)
    hub = B.adjust(bad, eo, truth, loss="huber", f_scale=2.0)
    e_ls = abs(ls.xyz_m[c_bad, 2] - truth[c_bad, 2])
    e_hub = abs(hub.xyz_m[c_bad, 2] - truth[c_bad, 2])
    assert e_ls > 2.0 and e_hub < 0.5 * e_ls


def test_error_ellipse_of_a_known_covariance():
    a, b, th = B.error_ellipse(np.array([[4.0, 0.0], [0.0, 1.0]]))
    assert (a, b, th) == (pytest.approx(2.0), pytest.approx(1.0), pytest.approx(0.0))
    R = np.array([[math.cos(0.5), -math.sin(0.5)], [math.sin(0.5), math.cos(0.5)]])
    a, b, th = B.error_ellipse(R @ np.diag([9.0, 0.25]) @ R.T)
    assert (a, b, th) == (pytest.approx(3.0), pytest.approx(0.5), pytest.approx(math.degrees(0.5)))
    a95, _, _ = B.error_ellipse(np.diag([1.0, 1.0]), p=0.95)
    assert a95 == pytest.approx(math.sqrt(-2 * math.log(0.05)))


def test_similarity_fit_recovers_a_known_transform():
    rng = np.random.default_rng(1)
    A = rng.normal(size=(10, 3)) * 100
    R = B.rotation_opk(0.2, -0.1, 1.3)
    Bp = 2.5 * A @ R.T + [10.0, -20.0, 5.0]
    fit = B.similarity_fit(A, Bp)
    assert fit.s == pytest.approx(2.5)
    np.testing.assert_allclose(fit.R, R, atol=1e-12)
    np.testing.assert_allclose(fit.t, [10.0, -20.0, 5.0], atol=1e-9)
    with pytest.raises(ValueError, match="one line"):
        B.similarity_fit(np.outer(np.arange(4), [1.0, 2.0, 3.0]), np.outer(np.arange(4), [1.0, 2.0, 3.0]))


def test_relative_orientation_recovers_the_pair_and_screens_a_blunder():
    cam = g.Camera(150.0)
    left = g.Pose(0.0, 0.0, 1500.0, 1.0, 30.0, 2.0)
    right = g.Pose(600.0, 20.0, 1510.0, 1.5, -60.0, -1.0)
    rng = np.random.default_rng(2)
    X, Y = np.meshgrid([0.0, 200.0, 400.0, 600.0], [-600.0, 0.0, 600.0])
    P = np.column_stack([X.ravel(), Y.ravel(), rng.uniform(-50, 50, 12)])
    xl, xr = g.ground_to_photo(cam, left, P), g.ground_to_photo(cam, right, P)
    Rl = g.rotation_matrix(left)
    ro = B.relative_orientation(xl, xr, 150.0, Rl)
    np.testing.assert_allclose(ro.R_right, g.rotation_matrix(right), atol=1e-9)
    b = right.centre - left.centre
    np.testing.assert_allclose(ro.base_dir, b / np.linalg.norm(b), atol=1e-9)
    assert ro.rms_q_mm < 1e-9
    xr2 = xr.copy()
    xr2[5, 1] += 0.08  # an inner point: the columns at the overlap's ends hide much of a blunder (low redundancy)
    ro2 = B.relative_orientation(xl, xr2, 150.0, Rl)
    assert not ro2.used[5] and ro2.used.sum() == 11
    assert ro2.q_mm[5] == pytest.approx(0.08, abs=0.005)
    with pytest.raises(ValueError, match="at least 6"):
        B.relative_orientation(xl[:5], xr[:5], 150.0)


# ----------------------------------------------------------------------------------------------- bad input


def test_too_few_control_points_is_a_clear_error():
    with pytest.raises(ValueError, match=r"has 1 control point\(s\); the valid range is at least 3"):
        make_block(control=[[0.0, 0.0]])
    meas, eo, truth = make_block(sigma_mm=0.0)
    kinds = meas.point_kind.copy()
    ci = np.flatnonzero(kinds == "control")
    kinds[ci[2:]] = "tie"
    with pytest.raises(ValueError, match="2 control point"):
        meas.replace(point_kind=kinds)


def test_collinear_control_is_a_clear_error():
    meas, eo, truth = make_block(sigma_mm=0.0)
    c = meas.control_XYZ_m.copy()
    ci = np.flatnonzero(meas.is_control)
    c[ci, 1] = 1000.0  # all on one line Y = 1000
    c[ci, 0] = np.arange(len(ci)) * 500.0
    with pytest.raises(ValueError, match="one line"):
        meas.replace(control_XYZ_m=c)


def test_a_photo_with_no_ties_is_a_clear_error():
    meas, eo, truth = make_block(sigma_mm=0.0)
    j = 4
    drop = np.flatnonzero(meas.obs_photo == j)
    keep = np.ones(meas.n_obs, bool)
    keep[drop] = False
    with pytest.raises(ValueError, match=rf"photo {int(meas.photo_ids[j])} has 0 tie point"):
        meas.replace(obs_photo=meas.obs_photo[keep], obs_point=meas.obs_point[keep], xy_mm=meas.xy_mm[keep],
                     sigma_mm=meas.sigma_mm[keep])


def test_a_point_on_one_photo_and_bad_arrays_are_clear_errors():
    meas, eo, truth = make_block(sigma_mm=0.0)
    i = int(np.flatnonzero(meas.point_kind[meas.obs_point] == "tie")[0])
    k = meas.obs_point[i]
    others = np.flatnonzero((meas.obs_point == k) & (np.arange(meas.n_obs) != i))
    keep = np.ones(meas.n_obs, bool)
    keep[others] = False
    with pytest.raises(ValueError, match="fewer than 2 photos"):
        meas.replace(obs_photo=meas.obs_photo[keep], obs_point=meas.obs_point[keep], xy_mm=meas.xy_mm[keep],
                     sigma_mm=meas.sigma_mm[keep])
    xy = meas.xy_mm.copy()
    xy[0, 0] = np.nan
    with pytest.raises(ValueError, match="xy_mm contains nan"):
        meas.replace(xy_mm=xy)
    with pytest.raises(ValueError, match="sigma_mm"):
        meas.replace(sigma_mm=-meas.sigma_mm)
    with pytest.raises(ValueError, match="eo0 has shape"):
        B.adjust(meas, eo[:-1], truth)
    with pytest.raises(ValueError, match="method"):
        B.adjust(meas, eo, truth, method="magic")
    with pytest.raises(ValueError, match="needs method='scipy'"):
        B.adjust(meas, eo, truth, loss="cauchy")


def test_a_block_that_falls_apart_is_a_clear_error():
    m1, eo1, t1 = make_block(sigma_mm=0.0, n_strips=1, n_photos=4, seed=1)
    # two copies of one strip side by side share no point
    n, P = m1.n_photos, m1.n_points
    with pytest.raises(ValueError, match="falls apart into 2 groups"):
        B.Measurements(
            f_mm=m1.f_mm, frame_mm=m1.frame_mm, photo_ids=np.r_[m1.photo_ids, m1.photo_ids + 100],
            photo_strip=np.r_[m1.photo_strip, m1.photo_strip + 1], photo_order=np.r_[m1.photo_order, m1.photo_order],
            point_ids=np.r_[m1.point_ids, m1.point_ids + 10000], point_kind=np.r_[m1.point_kind, m1.point_kind],
            obs_photo=np.r_[m1.obs_photo, m1.obs_photo + n], obs_point=np.r_[m1.obs_point, m1.obs_point + P],
            xy_mm=np.vstack([m1.xy_mm, m1.xy_mm]), sigma_mm=np.r_[m1.sigma_mm, m1.sigma_mm],
            control_XYZ_m=np.vstack([m1.control_XYZ_m, m1.control_XYZ_m]),
            control_sigma_m=np.vstack([m1.control_sigma_m, m1.control_sigma_m]))


def test_summary_counts_unknowns_and_equations():
    meas, eo, truth = make_block()
    s = meas.summary()
    assert s["unknowns"] == 6 * meas.n_photos + 3 * meas.n_points
    assert s["equations"] == 2 * meas.n_obs + 3 * int(meas.is_control.sum())
    assert s["redundancy"] == s["equations"] - s["unknowns"]
    assert s["photos"] == 18 and s["strips"] == 3
