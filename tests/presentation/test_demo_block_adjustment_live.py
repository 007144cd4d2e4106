"""The live bundle block adjustment of chapter 15 (aerophoto.demos.block_adjustment_live)."""

import math

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")

from aerophoto import bundle as B  # noqa: E402
from aerophoto.demos import block_adjustment_live as bl  # noqa: E402


@pytest.fixture()
def demo():
    return bl.BlockAdjustmentDemo()


def test_the_linearised_adjustment_is_the_bundle_adjustment():
    """One Gauss–Newton step from the truth = the package's iterated adjustment of the same measurements, up to the
    linearisation (about 2 mm on errors of up to 1.4 m)."""
    sv = bl._block()
    m = sv.meas
    M = bl.block_model("nine")
    z_img, z_ctrl, k_bl, direction = bl._noise_and_blunder()
    s = 5.0
    xy = B.project(sv.eo_true[m.obs_photo], sv.truth_m[m.obs_point], m.f_mm)
    xy = xy + (z_img * M.sigma1[:2 * M.n_img] * s).reshape(-1, 2)
    ctrl = m.control_XYZ_m.copy()
    ctrl[M.ctrl_points] = sv.truth_m[M.ctrl_points] + z_ctrl[M.ctrl_points] * bl._CONTROL_M_PER_UM * s
    sig = np.where(M.kind[m.obs_point] == "field", 6.0, 1.0) * 1e-3 * s
    meas = m.replace(xy_mm=xy, control_XYZ_m=ctrl, sigma_mm=sig,
                     control_sigma_m=np.full_like(m.control_sigma_m, bl._CONTROL_M_PER_UM * s))
    adj = B.adjust(meas, sv.eo_true, sv.truth_m)
    live = bl.adjust_live("nine", s, 0.0)
    got = live.xyz_err_m[M.kind != "unused"]
    ref = (adj.xyz_m - sv.truth_m)[M.kind != "unused"]
    assert np.max(np.abs(got - ref)) < 0.01
    assert np.max(np.abs(got - ref)) < 0.01 * np.max(np.abs(ref))
    assert np.max(np.abs(ref)) > 0.3  # errors of decimetres: the comparison is not trivially small


def test_sigma_scales_errors_and_the_blunder_fades(demo):
    demo.set(layout="nine", blunder="off", sigma_um=5.0)
    a = demo.result
    demo.set(sigma_um=10.0)
    b = demo.result
    assert b.check_rms_m["plan"] == pytest.approx(2 * a.check_rms_m["plan"], rel=1e-9)
    assert b.field_axes_m[:, 0] == pytest.approx(2 * a.field_axes_m[:, 0], rel=1e-9)
    assert a.flagged == -1 and "no blunder found" in a.verdict
    # the blunder's |w| falls as 1/σ: found at 5 µm, unseen at 30 µm
    demo.set(blunder="on", blunder_mm=0.1, sigma_um=5.0)
    w5 = demo.result.w[demo.result.blunder_row]
    assert demo.result.flagged == demo.result.blunder_row and w5 > 8
    demo.set(sigma_um=30.0)
    assert demo.result.flagged == -1 and "passes unseen" in demo.result.verdict
    assert demo.result.w[demo.result.blunder_row] < 4.0


def test_fewer_control_points_weaken_the_block(demo):
    demo.set(layout="nine", blunder="off", sigma_um=5.0)
    nine = demo.result.predicted_rms_m
    demo.set(layout="three")
    three = demo.result.predicted_rms_m
    assert three["Z"] > 2 * nine["Z"] and three["plan"] > nine["plan"]
    assert int(np.sum(demo.result.kind == "control")) == 3


def test_moves_update_artists_in_place_and_reset(demo):
    view = demo.view
    ell, arrows = view.ellipses, view.arrows
    demo.set(layout="nine", sigma_um=5.0, blunder="on")
    x5 = np.array(view.ellipses.get_xdata(), float)
    demo.set(sigma_um=20.0)
    assert view.ellipses is ell and view.arrows is arrows
    x20 = np.array(view.ellipses.get_xdata(), float)
    assert np.nanmax(np.abs(x20 - np.nanmean(x20))) > np.nanmax(np.abs(x5 - np.nanmean(x5)))
    assert len(view.flag.get_xdata()) == 1  # the blunder is still found at 20 µm and ringed
    demo.reset()
    assert demo.values == {"layout": "nine", "sigma_um": 5.0, "blunder": "on", "blunder_mm": 0.1}
    assert "planted blunder" in demo.result.table().loc["data snooping", "value"]


def test_sliders_are_bounded_and_named(demo):
    with pytest.raises(ValueError, match="sigma_um"):
        demo.set(sigma_um=0.5)
    with pytest.raises(ValueError, match="layout"):
        demo.set(layout="everywhere")
    with pytest.raises(ValueError, match="sigma_um"):
        bl.adjust_live("nine", math.inf)
