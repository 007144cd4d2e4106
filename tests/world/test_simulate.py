"""Simulated flights: ideal strips follow the plan exactly, imperfections stay within their maxima."""

import math

import numpy as np
import pytest

from aerophoto import geometry as g
from aerophoto import simulate as sim
from aerophoto import site as site_mod
from aerophoto.variants import variant_for_index

CAM = g.Camera(100.0, 180.0)
IMP = sim.Imperfections(max_tilt_deg=3, crab_deg=2, max_crab_jitter_deg=1.5, max_height_percent=3,
                        curvature_percent=2, max_base_percent=5, seed=11)


def _overlap_percent(fp_a, fp_b, direction):
    """Overlap of two footprints along ``direction``, % of the footprint length (vertical photos)."""
    pa = fp_a[:, :2] @ direction
    pb = fp_b[:, :2] @ direction
    inter = min(pa.max(), pb.max()) - max(pa.min(), pb.min())
    return inter / (pa.max() - pa.min()) * 100.0


def test_guide_base_and_strip_spacing():
    # guide §2, steps 4-5 (variant 0): b_x = 18(100-61)/100 = 7.02 cm, B_x = b_x·m = 0.84 km;
    # b_y = 18(100-31)/100 = 12.42 cm, B_y = 1.49 km
    assert sim.photo_base_m(CAM, 12000, 61.0) == pytest.approx(842.4)
    assert sim.strip_spacing_m(CAM, 12000, 31.0) == pytest.approx(1490.4)
    assert round(sim.photo_base_m(CAM, 12000, 61.0) / 1000, 2) == 0.84
    assert round(sim.strip_spacing_m(CAM, 12000, 31.0) / 1000, 2) == 1.49


@pytest.mark.parametrize("az", [0.0, 30.0, -120.0])
def test_ideal_strip_is_vertical_with_exact_base_and_overlap(az):
    st = sim.fly_strip(CAM, 12000, 60, 6, start_m=(1000.0, -500.0), azimuth_deg=az, ground_Z_m=170.0)
    assert st.H_m == pytest.approx(1200.0) and st.B_m == pytest.approx(864.0)
    assert len(st) == 6 and [s.number for s in st] == [1, 2, 3, 4, 5, 6]
    for s in st:
        assert s.pose == s.nominal
        assert s.pose.alpha_deg == 0.0 and s.pose.kappa_deg == az
        assert s.pose.Z_m == pytest.approx(1370.0)
        assert s.H_m == pytest.approx(1200.0) and s.m == pytest.approx(12000.0)
    c = st.centres_m
    steps = np.diff(c[:, :2], axis=0)
    assert np.allclose(np.hypot(steps[:, 0], steps[:, 1]), 864.0, atol=1e-9)
    assert np.allclose(steps / 864.0, st.direction, atol=1e-12)
    assert np.allclose(c[0, :2], [1000.0, -500.0])
    fp = st.footprints()
    for a, b in zip(fp[:-1], fp[1:]):
        assert _overlap_percent(a, b, st.direction) == pytest.approx(60.0, abs=1e-9)
    t = st.table()
    assert list(t.index) == [1, 2, 3, 4, 5, 6]
    assert np.allclose(t[["dX_m", "dY_m", "crab_deg", "dH_percent"]].to_numpy(), 0.0)


def test_ideal_block_side_overlap():
    bl = sim.fly_block(CAM, 12000, 60, 30, 4, 3, ground_Z_m=0.0)
    assert bl.By_m == pytest.approx(0.18 * 12000 * 0.7)
    assert [s.number for s in bl.shots] == list(range(1, 13))
    fp = bl.footprints()
    left = np.array([0.0, 1.0])
    for k in range(2):  # photo 0 of strip k and of strip k+1, side by side
        assert _overlap_percent(fp[4 * k], fp[4 * (k + 1)], left) == pytest.approx(30.0, abs=1e-9)
    right = sim.fly_block(CAM, 12000, 60, 30, 4, 2, side="right")
    assert right[1][0].pose.Y_m == pytest.approx(-bl.By_m)


def test_alternate_strips_fly_back_over_the_same_columns():
    bl = sim.fly_block(CAM, 10000, 60, 30, 5, 2, alternate=True)
    a = bl[0].centres_m[:, 0]
    b = bl[1].centres_m[:, 0]
    assert np.allclose(a, b[::-1])
    assert bl[1][0].pose.kappa_deg == pytest.approx(180.0)


def test_block_strip_zero_equals_single_strip():
    st = sim.fly_strip(CAM, 12000, 60, 5, imperfections=IMP)
    bl = sim.fly_block(CAM, 12000, 60, 30, 5, 3, imperfections=IMP)
    assert [s.pose for s in bl[0]] == [s.pose for s in st]
    # the other strips have their own random streams
    assert bl[1][0].pose.alpha_deg != st[0].pose.alpha_deg


@pytest.mark.parametrize("seed", range(8))
def test_imperfections_stay_within_their_maxima(seed):
    imp = sim.Imperfections(max_tilt_deg=3, crab_deg=-4, max_crab_jitter_deg=1, max_height_percent=3,
                            curvature_percent=0, max_base_percent=4, seed=seed)
    st = sim.fly_strip(CAM, 15000, 60, 12, ground_Z_m=100.0, imperfections=imp)
    t = st.table()
    assert t["alpha_deg"].between(0, 3).all()
    assert t["lambda_deg"].between(-180, 180).all()
    assert (t["crab_deg"] + 4).abs().max() <= 1.0 + 1e-12
    assert t["dH_percent"].abs().max() <= 3.0 + 1e-9
    assert t["dX_m"].abs().max() <= 0.04 * st.B_m + 1e-9
    assert t["dY_m"].abs().max() <= 1e-9  # no curvature: no lateral offset
    # the random draws really are spread over their ranges, not stuck at zero
    assert t["alpha_deg"].max() > 1.0 and t["dH_percent"].abs().max() > 1.0


def test_curvature_is_the_guides_straightness():
    # guide §3.2: n = l/L·100 %, l the deviation of a middle photo's centre from the chord
    for c in (2.0, -1.5):
        st = sim.fly_strip(CAM, 12000, 60, 9, imperfections=sim.Imperfections(curvature_percent=c))
        xy = st.centres_m[:, :2]
        chord = xy[-1] - xy[0]
        L = float(np.hypot(*chord))
        dev = ((xy - xy[0]) @ np.array([-chord[1], chord[0]])) / L  # signed, + to the left
        assert L == pytest.approx(st.length_m)
        assert dev[4] / L * 100 == pytest.approx(c, rel=1e-12)
        assert np.max(np.abs(dev)) / L * 100 == pytest.approx(abs(c), rel=1e-12)
        # the photo x axis follows the arc's tangent: κ turns from +slope to −slope
        kap = np.array([s.pose.kappa_deg for s in st])
        assert kap[0] == pytest.approx(math.degrees(math.atan(4 * c / 100)))
        assert kap[-1] == pytest.approx(-kap[0])


def test_seeds_are_reproducible_and_maxima_only_scale():
    a = sim.fly_strip(CAM, 12000, 60, 7, imperfections=IMP).table()
    b = sim.fly_strip(CAM, 12000, 60, 7, imperfections=IMP).table()
    assert a.equals(b)
    c = sim.fly_strip(CAM, 12000, 60, 7, imperfections=sim.Imperfections(**{**IMP.__dict__, "seed": 12})).table()
    assert not np.allclose(a["alpha_deg"], c["alpha_deg"])
    doubled = sim.Imperfections(**{**IMP.__dict__, "max_tilt_deg": 6.0})
    d = sim.fly_strip(CAM, 12000, 60, 7, imperfections=doubled).table()
    assert np.allclose(d["alpha_deg"], 2 * a["alpha_deg"])
    assert np.allclose(d["Z_m"], a["Z_m"]) and np.allclose(d["lambda_deg"], a["lambda_deg"])


def test_ideal_imperfections_ignore_the_seed():
    a = sim.fly_strip(CAM, 12000, 60, 4, imperfections=sim.Imperfections(seed=5))
    b = sim.fly_strip(CAM, 12000, 60, 4)
    assert [s.pose for s in a] == [s.pose for s in b]
    assert sim.Imperfections().is_ideal and not IMP.is_ideal


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(px_percent=100), "px_percent"),
        (dict(px_percent=-1), "px_percent"),
        (dict(m=0), "m"),
        (dict(n_photos=0), "n_photos"),
        (dict(n_photos=2.5), "n_photos"),
        (dict(azimuth_deg=400), "azimuth_deg"),
        (dict(start_m=(1, 2, 3)), "start_m"),
    ],
)
def test_bad_strip_input(kwargs, name):
    args = dict(camera=CAM, m=12000, px_percent=60, n_photos=4)
    args.update(kwargs)
    with pytest.raises(ValueError, match=name):
        sim.fly_strip(**args)


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(max_tilt_deg=-1), "max_tilt_deg"),
        (dict(max_tilt_deg=31), "max_tilt_deg"),
        (dict(crab_deg=50), "crab_deg"),
        (dict(max_height_percent=-2), "max_height_percent"),
        (dict(curvature_percent=60), "curvature_percent"),
        (dict(max_base_percent=50), "max_base_percent"),
        (dict(seed=-1), "seed"),
        (dict(seed=1.5), "seed"),
    ],
)
def test_bad_imperfections(kwargs, name):
    with pytest.raises(ValueError, match=name):
        sim.Imperfections(**kwargs)


def test_bad_block_input():
    with pytest.raises(ValueError, match="py_percent"):
        sim.fly_block(CAM, 12000, 60, 100, 4, 2)
    with pytest.raises(ValueError, match="n_strips"):
        sim.fly_block(CAM, 12000, 60, 30, 4, 0)
    with pytest.raises(ValueError, match="side"):
        sim.fly_block(CAM, 12000, 60, 30, 4, 2, side="up")
    with pytest.raises(TypeError, match="camera"):  # a wrong object is a TypeError naming the parameter
        sim.fly_strip("f=100", 12000, 60, 4)


def test_variant_with_long_focal_length_needs_no_site():
    v = variant_for_index(99)  # f = 1090 mm, 1/m = 1/21900
    st = sim.variant_strip(v, 4, imperfections=IMP)
    assert st.H_m == pytest.approx(1.09 * 21900)
    assert st.ground_Z_m == pytest.approx((v.Zmin_m + v.Zmax_m) / 2)
    assert st.B_m == pytest.approx(0.18 * 21900 * 0.4)
    bl = sim.variant_block(v, 3, 2)
    assert bl.By_m == pytest.approx(0.18 * 21900 * 0.7)
    st61 = sim.variant_strip(variant_for_index(0), 3, px_percent=61.0)
    assert st61.B_m == pytest.approx(842.4)


@pytest.fixture(scope="module")
def small_site():
    return site_mod.get_site(width_m=6000, height_m=3600, seed=3)


def test_strip_over_site_is_centred_at_mean_height(small_site):
    st = sim.strip_over_site(small_site, CAM, 10000, 60, 4)
    c = st.centres_m
    assert np.allclose(c[:, :2].mean(axis=0), small_site.centre_m)
    assert np.allclose(c[:, 2], small_site.mean_height_m + 1000.0)
    with pytest.raises(ValueError, match="do not fit the site"):
        sim.strip_over_site(small_site, CAM, 12000, 60, 8)
    bl = sim.block_over_site(small_site, CAM, 5000, 60, 30, 4, 3, imperfections=IMP)
    assert np.allclose(bl.footprints()[..., :2].reshape(-1, 2).mean(axis=0), small_site.centre_m, atol=300)


@pytest.mark.parametrize("imp", [None, IMP, sim.Imperfections(max_tilt_deg=8, crab_deg=-10, curvature_percent=-5,
                                                              max_height_percent=10, max_base_percent=20, seed=1)])
def test_required_site_size_holds_the_flight(imp):
    # the size is computed without the site; a site of that size must hold the centred flight
    w, h = sim.required_site_size(CAM, 6000, 60, 5, n_strips=2, py_percent=30, imperfections=imp)
    assert w % 100 == 0 and h % 100 == 0
    assert w >= 4 * 0.18 * 6000 * 0.4 + 0.18 * 6000
    s = site_mod.get_site(width_m=w, height_m=h, texture_m=4.0, relief_m=0.0)
    bl = sim.block_over_site(s, CAM, 6000, 60, 30, 5, 2, imperfections=imp)
    assert len(bl.shots) == 10
