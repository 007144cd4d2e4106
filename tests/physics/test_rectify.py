"""aerophoto.rectify (guide §12): table 11, four-point rectification of rendered photos, the photo transformer;
aerophoto.guide.ch11: table 11 audited."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aerophoto import geometry as g
from aerophoto import projective as pj
from aerophoto import rectify as rf
from aerophoto import guide


# --------------------------------------------------------------------------- table 11
def test_table_11_numbers():
    l0 = [100, 100, 115, 115, 152.40, 152.40]
    li = [100.5, 100, 115, 115.3, 152.5, 152.2]
    d = rf.paper_deformation(l0, li)
    np.testing.assert_allclose(d.dl_mm, [-0.5, 0.0, 0.0, -0.3, -0.1, 0.2], atol=1e-12)
    assert d.sum_l0_mm == pytest.approx(734.8) and d.sum_li_mm == pytest.approx(735.5)
    assert d.K_d == pytest.approx(-0.7 / 734.8) == pytest.approx(-0.00095264, abs=5e-9)
    K_t = rf.enlargement(15000, 5000)
    assert K_t == 3.0
    assert rf.projection_distance_mm(108, K_t) == pytest.approx(432.0)
    assert rf.substrate_thickness_mm(d.K_d, 108, K_t) == pytest.approx(-0.41154, abs=5e-6)
    assert list(d.table().index) == ["l1", "l2", "l3", "l4", "l5", "l6", "Σ"]


def test_the_diagonals_of_the_grid():
    assert rf.control_grid_length_mm(20) == 100.0
    assert rf.control_grid_length_mm(20, 23) == pytest.approx(152.398, abs=5e-4)
    with pytest.raises(ValueError, match="at least one square"):
        rf.control_grid_length_mm(0, 0)


def test_the_substrate_has_the_sign_of_k_d():
    shrink = rf.paper_deformation([100.0, 100.0], [99.9, 99.9])
    assert shrink.K_d > 0 and rf.substrate_thickness_mm(shrink.K_d, 100, 1.2) > 0
    stretch = rf.paper_deformation([100.0, 100.0], [100.1, 100.1])
    assert stretch.K_d < 0 and rf.substrate_thickness_mm(stretch.K_d, 100, 1.2) < 0


def test_the_substrate_compensates_the_deformation():
    # moving the screen by t changes the projected size by t / (f (K_t + 1)) = K_d (thin lens, object fixed)
    f, K_t, K_d = 108.0, 3.0, 0.0012
    u = f * (K_t + 1) / K_t  # object distance for the enlargement K_t
    v = 1 / (1 / f - 1 / u)
    t = rf.substrate_thickness_mm(K_d, f, K_t)
    assert v == pytest.approx(f * (K_t + 1))
    assert ((v + t) / u) / (v / u) - 1 == pytest.approx(K_d)


@pytest.mark.parametrize("l0, li, match", [
    ([100.0], [100.0, 100.0], "one print length"),
    ([0.5], [0.5], "1 ≤ length"),
    ([100.0], [np.nan], "finite"),
])
def test_bad_lengths_are_named(l0, li, match):
    with pytest.raises(ValueError, match=match):
        rf.paper_deformation(l0, li)


def test_the_audit_of_table_11():
    a = guide.ch11.table_11()
    bad = a.discrepancies
    assert [(p.where, p.quantity) for p in bad] == [("formula", "t, mm")]
    assert bad[0].printed == pytest.approx(0.4115) and bad[0].computed == pytest.approx(-0.41154, abs=1e-5)
    assert "sign" in bad[0].reason
    follows = {(p.where, p.quantity) for p in a.values if p.follows}
    assert ("formula", "K_d") in follows and ("l5", "l₀ = 5 mm·n, mm") in follows and ("Σ", "Σδl, mm") in follows
    assert any("diagonal" in n for n in a.notes)


def test_the_list_of_plan_coordinates():
    df = guide.ch11.plan_points()
    assert list(df.index) == ["550", "551", "641", "644"]
    assert df.loc["550", "length"] == pytest.approx(185.2, abs=0.05)
    assert df["length"].max() == pytest.approx(855.8, abs=0.05)


# --------------------------------------------------------------------------- four-point rectification
def _photo_points(alpha=3.0, lam=-60.0, kappa=8.0, f=108.0, m=15000.0, M=5000.0, Z=0.0):
    cam = g.Camera(f)
    H = f / 1000 * m
    pose = g.Pose(0.0, 0.0, Z + H, alpha, lam, kappa)
    G = np.array([[-900, -800, 0], [850, -900, 0], [900, 850, 0], [-800, 900, 0], [100, -200, 0], [-300, 400, 0.0]])
    G[:, 2] += Z
    return cam, pose, g.ground_to_photo(cam, pose, G), G[:, :2] * 1000 / M


def test_four_points_rectify_flat_ground_exactly():
    _, _, photo, base = _photo_points()
    r = rf.rectify_points(photo[:4], base[:4], photo[4:], base[4:])
    assert r.control_lengths_mm.max() < 1e-9 and r.check_lengths_mm.max() < 1e-7 and r.ok
    t = r.table()
    assert list(t["role"]) == ["control"] * 4 + ["check"] * 2 and t["≤ 0.4 mm"].all()


def test_pricking_errors_show_at_the_check_points():
    _, _, photo, base = _photo_points()
    rng = np.random.default_rng(2)
    noisy = photo + rng.normal(0, 0.05, size=photo.shape)
    r = rf.rectify_points(noisy[:4], base[:4], noisy[4:], base[4:])
    assert r.control_lengths_mm.max() < 1e-9  # four points: still an exact fit
    assert 0.01 < r.check_lengths_mm.max() < 0.6  # 0.05 mm on the photo is 0.15 mm on the base at K_t = 3


def test_relief_survives_rectification():
    cam, pose, photo, base = _photo_points()
    # a check point 30 m above the plane of the control points: δh = r·h/H on the photo, times K_t on the base
    P = np.array([[100.0, -200.0, 30.0]])
    xy = g.ground_to_photo(cam, pose, P)
    r = rf.rectify_points(photo[:4], base[:4], xy, P[:, :2] * 1000 / 5000)
    n = g.nadir_point(cam, pose)
    dh = np.hypot(*(xy[0] - n)) * 30.0 / (108 / 1000 * 15000)
    assert r.check_lengths_mm[0] == pytest.approx(dh * 3.0, rel=0.1)


def test_a_rendered_photo_of_flat_ground_rectifies_onto_the_truth_within_a_pixel():
    from skimage.registration import phase_cross_correlation

    from aerophoto.render import render
    from aerophoto.site import get_site
    from aerophoto.labs.ch11 import rectification_lab_for

    site = get_site(relief_m=0)
    cam = g.Camera(108.0)
    cx, cy = site.centre_m
    pose = g.Pose(cx - 600, cy + 150, site.base_height_m + 1620.0, 3.0, -60.0, 8.0)
    lab = rectification_lab_for(cam, pose, 5000.0, site=site, sigma_mm=0.0)
    r = lab.rectification
    # control and check points: on flat ground the base positions follow to the 0.01 mm rounding
    assert r.max_residual_mm < 0.02
    photo = render(site, cam, pose, 512, vignetting=0.0, fiducials=False)
    px = 1.0  # mm on the base (5 m of ground)
    ext = (-150.0, 150.0, -150.0, 150.0)
    rect = pj.warp_photo(photo.image, r.transform, ext, px, frame_mm=cam.frame_mm)
    XY = lab.base_to_ground(rect.pixel_centres())
    truth = site.sample(XY[..., 0], XY[..., 1], level=site.level_for(px * 5.0))
    ok = np.isfinite(rect.image) & np.isfinite(truth)
    assert ok.mean() > 0.95
    a = np.where(ok, rect.image, 0.0)
    b = np.where(ok, truth, 0.0)
    corr = np.corrcoef(a[ok], b[ok])[0, 1]
    assert corr > 0.95
    shift, _, _ = phase_cross_correlation(b, a, upsample_factor=10)
    assert np.hypot(*shift) < 1.0  # within a pixel of the truth


# --------------------------------------------------------------------------- the photo transformer
def test_the_true_state_maps_the_photo_onto_the_plan():
    cam, pose, photo, base = _photo_points(alpha=6.0, lam=30.0, kappa=-12.0)
    st_ = rf.true_state(cam, pose, 5000.0)
    np.testing.assert_allclose(rf.screen_image(st_, photo, cam.f_mm), base, atol=1e-9)
    assert st_.scale == pytest.approx(3.0)


def test_principal_horizontal_of_a_pure_tilt_is_near_its_axis():
    # image = plan levelled by a tilt: corresponding lines meet near the axis of the tilt
    f = 100.0
    st_ = rf.TransformerState(eps_deg=5.0, tilt_dir_deg=40.0)
    plan_ = np.array([[-60.0, -50.0], [55.0, -45.0], [70.0, 60.0], [-50.0, 52.0], [5.0, 3.0]])
    image = rf.screen_image(st_, plan_, f)
    p, d, pts = rf.principal_horizontal(image, plan_)
    # the line runs (nearly — the guide's "приближение") perpendicular to the tilt's direction (40°): within 4°
    assert abs(d @ np.array([math.cos(math.radians(40)), math.sin(math.radians(40))])) < math.sin(math.radians(4))
    assert len(pts) >= 4


@settings(max_examples=12, deadline=None)
@given(alpha=st.floats(0.5, 8.0), lam=st.floats(-180, 180), kappa=st.floats(-25, 25))
def test_the_sequence_converges_within_0_4_mm(alpha, lam, kappa):
    cam, pose, photo, base = _photo_points(alpha, lam, kappa)
    pts, bp = photo[[0, 1, 2, 3, 4]], base[[0, 1, 2, 3, 4]]
    run = rf.transformer_sequence(pts, bp, cam.f_mm, centre_index=4, cycles=4)
    k = run.converged_step
    assert k is not None and k <= 15
    s = run.steps[k]
    assert s.max_residual_mm <= 0.4
    assert [x.name for x in run.steps[:6]] == ["start", "centre", "scale", "hh", "turn", "tilt"]
    # the settings found are the photo's: tilt α (the sign goes with the direction), enlargement m/M
    tilt = np.array([math.cos(math.radians(s.state.tilt_dir_deg)), math.sin(math.radians(s.state.tilt_dir_deg))])
    true = np.array([math.cos(math.radians(lam)), math.sin(math.radians(lam))])
    assert s.state.eps_deg * (tilt @ true) == pytest.approx(alpha, abs=0.3)
    assert s.state.scale == pytest.approx(3.0, rel=0.01)


def test_the_sequence_validates_its_input():
    with pytest.raises(ValueError, match="at least 4"):
        rf.transformer_sequence(np.zeros((3, 2)), np.zeros((3, 2)), 100.0)
    with pytest.raises(ValueError, match="cycles"):
        rf.transformer_sequence(np.eye(4, 2), np.eye(4, 2), 100.0, cycles=0)
