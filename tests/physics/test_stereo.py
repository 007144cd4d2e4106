"""Stereo pairs (aerophoto.stereo, guide §8): the parallax equations, the normalised pair, anaglyphs, matching."""

import math
import re
from dataclasses import replace

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as hs

from aerophoto import geometry as g
from aerophoto import stereo as st

CAM = g.Camera(100.0)


def _pair(tilt=(0.0, 0.0), dz=0.0, kappa=(0.0, 0.0)):
    left = g.Pose(1000.0, 2000.0, 1400.0, tilt[0], 30.0, kappa[0])
    right = g.Pose(1864.0, 2012.0, 1400.0 + dz, tilt[1], -110.0, kappa[1])
    return left, right


def _normal(left, right, P):
    R = st.normal_rotation(left, right)
    xl = st.to_normal(CAM, left, R, g.ground_to_photo(CAM, left, P))
    xr = st.to_normal(CAM, right, R, g.ground_to_photo(CAM, right, P))
    return R, xl, xr


# --------------------------------------------------------------------------- the pair's numbers
def test_the_guides_pair():
    p = st.StereoPair.from_plan(100.0, 12000.0, 60.0)
    assert p.H_m == 1200.0 and p.B_m == pytest.approx(864.0) and p.b_mm == pytest.approx(72.0)
    assert p.overlap_percent == pytest.approx(60.0) and p.base_height_ratio == pytest.approx(0.72)
    assert p.m == pytest.approx(12000.0)
    # a 10 m height: b·h/(H − h) = 72·10/1190
    assert p.dp_mm(10.0) == pytest.approx(720.0 / 1190.0)
    assert p.height_precision_m(0.01) == pytest.approx(1200 * 0.01 / 72)
    assert p.vertical_exaggeration() == pytest.approx(0.72 * 250 / 65)
    t = p.table()
    assert t.loc["Photo base b = B·f/H", "value"] == pytest.approx(72.0)
    assert st.photo_base_mm(864.0, 1200.0, 100.0) == pytest.approx(72.0)
    assert st.air_base_m(72.0, 12000.0) == pytest.approx(864.0)
    assert st.base_height_ratio(864.0, 1200.0) == pytest.approx(0.72)
    assert isinstance(st.height_difference_m(0.36, 72.0, 1200.0), float)


def test_parallax_equations_on_a_vertical_pair():
    H, B = 1200.0, 864.0
    left = g.Pose(0.0, 0.0, H)
    right = g.Pose(B, 0.0, H)
    P = np.array([[300.0, 150.0, 0.0], [500.0, -200.0, 25.0], [420.0, 40.0, 64.0]])
    x1, x2 = g.ground_to_photo(CAM, left, P), g.ground_to_photo(CAM, right, P)
    assert np.allclose(st.y_parallax_mm(x1[:, 1], x2[:, 1]), 0.0, atol=1e-12)  # a vertical pair has none
    p = st.x_parallax_mm(x1[:, 0], x2[:, 0])
    assert np.allclose(p, B * 100.0 / (H - P[:, 2]))
    assert np.allclose(p, st.parallax_mm(B, 100.0, H, P[:, 2]))
    M = st.model_point(x1[:, 0], x1[:, 1], p, B, 100.0, H)
    assert np.allclose(M, P, atol=1e-9)  # X = B·x/p, Y = B·y/p, h = H − B·f/p
    M0 = st.model_point(x1[:, 0], x1[:, 1], p, B, 100.0)
    assert np.allclose(M0[:, 2], P[:, 2] - H)


@settings(max_examples=60, deadline=None, derandomize=True)
@given(X=hs.floats(1150.0, 1700.0), Y=hs.floats(1700.0, 2300.0), Z=hs.floats(150.0, 320.0),
       a1=hs.floats(0.0, 3.0), a2=hs.floats(0.0, 3.0), dz=hs.floats(-30.0, 30.0), k1=hs.floats(-5, 5),
       k2=hs.floats(-5, 5))
def test_round_trip_parallax_to_ground(X, Y, Z, a1, a2, dz, k1, k2):
    """Projected into both photos of any (tilted) pair, normalised: no y-parallax, and X, Y, Z come back."""
    left, right = _pair((a1, a2), dz, (k1, k2))
    P = np.array([[X, Y, Z]])
    R, xl, xr = _normal(left, right, P)
    assert abs(xl[0, 1] - xr[0, 1]) < 1e-9
    p = xl[:, 0] - xr[:, 0]
    assert p[0] > 0
    B = float(np.linalg.norm(right.centre - left.centre))
    M = st.model_point(xl[:, 0], xl[:, 1], p, B, CAM.f_mm)
    assert np.allclose(left.centre + M @ R.T, P, atol=1e-6)
    # the photo → normal → photo mapping is the identity
    back = st.from_normal(CAM, left, R, st.to_normal(CAM, left, R, [[12.0, -30.0]]))
    assert np.allclose(back, [[12.0, -30.0]], atol=1e-9)


@settings(max_examples=60, deadline=None, derandomize=True)
@given(h1=hs.floats(-50.0, 100.0), dh=hs.floats(-40.0, 300.0), H=hs.floats(500.0, 25000.0),
       B=hs.floats(100.0, 3000.0))
def test_height_difference_against_exact_projection(h1, dh, H, B):
    """Δh = H·Δp/(p + Δp) is exact with H over the lower point and p its parallax; the small form approaches it."""
    f = 150.0
    p1 = st.parallax_mm(B, f, H, h1)
    p2 = st.parallax_mm(B, f, H, h1 + dh)
    assert st.height_difference_m(p2 - p1, p1, H - h1) == pytest.approx(dh, abs=1e-7 * H)
    assert st.parallax_difference_mm(dh, p1, H - h1) == pytest.approx(p2 - p1, rel=1e-9, abs=1e-12)
    approx = st.height_difference_m(p2 - p1, p1, H - h1, approx=True)
    # the small form errs by the factor (p + Δp)/p
    assert approx == pytest.approx(dh * p2 / p1, rel=1e-9, abs=1e-9)


def test_limiting_cases():
    assert st.height_difference_m(0.0, 72.0, 1200.0) == 0.0
    assert st.parallax_mm(864.0, 100.0, 1200.0, 0.0) == pytest.approx(72.0)  # the ground's parallax is b
    # tiny Δp: exact → small form
    for dp in (1e-1, 1e-3, 1e-5):
        e = st.height_difference_m(dp, 72.0, 1200.0)
        a = st.height_difference_m(dp, 72.0, 1200.0, approx=True)
        assert abs(a / e - 1.0) == pytest.approx(dp / 72.0, rel=1e-6)
    # a point of known height gives the flying height, and a known flying height the air base
    p = st.parallax_mm(864.0, 100.0, 1200.0, 30.0)
    assert st.flying_height_from_point(864.0, 100.0, p, 200.0) == pytest.approx(200.0 + 1170.0)
    assert st.air_base_from_point(p, 100.0, 1170.0) == pytest.approx(864.0)
    # vertical exaggeration: proportional to B/H, 1 when B/H = e/d
    assert st.vertical_exaggeration(65.0, 250.0) == pytest.approx(1.0)
    assert st.vertical_exaggeration(1728.0, 1200.0) == pytest.approx(2 * st.vertical_exaggeration(864.0, 1200.0))


@pytest.mark.parametrize("call, name", [
    (lambda: st.model_point(1.0, 2.0, 0.0, 864.0, 100.0), "p_mm = 0"),
    (lambda: st.model_point(1.0, 2.0, -3.0, 864.0, 100.0), "p_mm = -3"),
    (lambda: st.height_difference_m(-80.0, 72.0, 1200.0), "b_mm \\+ dp_mm = -8"),
    (lambda: st.parallax_difference_mm(1200.0, 72.0, 1200.0), "dh_m = 1200"),
    (lambda: st.parallax_mm(864.0, 100.0, 1200.0, 1300.0), "h_m = 1300"),
    (lambda: st.photo_base_mm(-1.0, 1200.0, 100.0), "B_m = -1"),
    (lambda: st.photo_base_mm(864.0, 1200.0, float("nan")), "f_mm"),
    (lambda: st.height_difference_m(0.3, 72.0, float("inf")), "H_m"),
    (lambda: st.height_difference_m(0.3, 0.0, 1200.0), "b_mm = 0"),
    (lambda: st.flying_height_from_point(864.0, 100.0, 0.0), "p_mm = 0"),
    (lambda: st.vertical_exaggeration(864.0, 1200.0, eye_base_mm=0.0), "eye_base_mm"),
    (lambda: st.StereoPair(100.0, 0.0, 1200.0), "B_m"),
    (lambda: st.StereoPair.from_plan(100.0, 12000.0, 100.0), "px_percent"),
    (lambda: st.normal_rotation(g.Pose(0, 0, 1000), g.Pose(0, 0, 1000)), "base B > 0"),
    (lambda: st.normalise_image(np.zeros((8, 8)), CAM, g.Pose(), np.eye(3), (1, 0, 0, 1), 0.1), "window_mm"),
    (lambda: st.normalise_image(np.zeros((8, 8)), CAM, g.Pose(), np.eye(3), (0, 1, 0, 1), 0.0), "pixel_mm"),
    (lambda: st.anaglyph(np.zeros((4, 4)), np.zeros((4, 5))), "same shape"),
    (lambda: st.side_by_side(np.zeros((4, 8)), np.zeros((4, 8)), 5), "separation_px = 5"),
    (lambda: st.dense_parallax(np.zeros((20, 20)), np.zeros((20, 20)), d_min=3, d_max=3), "d_max"),
    (lambda: st.match_points(np.zeros((20, 20)), np.zeros((20, 20)), [[5, 5]], d_min=4, d_max=2), "d_max = 2"),
])
def test_bad_input_names_the_value(call, name):
    with pytest.raises(ValueError, match=name):
        call()


# --------------------------------------------------------------------------- pictures
def test_anaglyph_channels_and_reverse():
    rng = np.random.default_rng(1)
    L, R = rng.random((30, 40)).astype(np.float32), rng.random((30, 40)).astype(np.float32)
    L[3, 4] = np.nan
    a = st.anaglyph(L, R)
    assert a.shape == (30, 40, 3) and a.dtype == np.float32
    ok = np.isfinite(L)
    assert np.array_equal(a[..., 0][ok], L[ok]) and a[3, 4, 0] == 0.5  # red: the left photo; NaN: background
    assert np.array_equal(a[..., 1], R) and np.array_equal(a[..., 2], R)  # green and blue: the right photo
    b = st.anaglyph(R, L)  # swapped: the reverse stereo effect
    assert np.array_equal(b[..., 0], R)
    sbs = st.side_by_side(L, R, 55)
    assert sbs.shape == (30, 95) and np.array_equal(sbs[:, 55:], R) and np.all(sbs[:, 40:55] == 1.0)


def test_matching_finds_a_known_disparity():
    rng = np.random.default_rng(3)
    from scipy.ndimage import gaussian_filter, shift

    tex = gaussian_filter(rng.random((80, 160)), 1.2)
    L = tex[:, 20:140]
    R = shift(tex, (0, 2.4), order=3, mode="nearest")[:, 20:140]  # every detail 2.4 px further right:
    # col_left − col_right = −2.4
    d, peak = st.match_points(L, R, [[40, 60], [30, 80], [50, 45]], half_window=7, d_min=-8, d_max=8)
    assert np.allclose(d, -2.4, atol=0.1) and np.all(peak > 0.9)
    dense = st.dense_parallax(L, R, half_window=7, d_min=-8, d_max=8)
    inner = dense.d_px[15:-15, 20:-20]
    assert np.nanmedian(np.abs(inner + 2.4)) < 0.1
    assert dense.reliable()[15:-15, 20:-20].mean() > 0.9  # a unique clear peak, consistent both ways


# --------------------------------------------------------------------------- the pair of the site
@pytest.fixture(scope="module")
def lab():
    from aerophoto.labs import ch07

    return ch07.example_lab()


def test_normalised_pair_of_the_site_has_no_y_parallax(lab):
    from aerophoto.site import get_site

    P = get_site().catalogue[["X_m", "Y_m", "Z_m"]].to_numpy()
    x1 = g.ground_to_photo(lab.camera, lab.left.pose, P)
    x2 = g.ground_to_photo(lab.camera, lab.right.pose, P)
    both = np.all(np.abs(x1) < 88, axis=1) & np.all(np.abs(x2) < 88, axis=1)
    assert both.sum() > 20
    raw_q = np.abs(x1[both, 1] - x2[both, 1]).max()
    assert raw_q > 0.05  # the flight's tilts and crab leave y-parallax on the photos themselves …
    xl, xr = lab.normal_xy(P[both])
    assert np.abs(xl[:, 1] - xr[:, 1]).max() < 1e-9  # … and none on the normalised pair
    p = xl[:, 0] - xr[:, 0]
    assert np.allclose(lab.model_to_ground(xl, p), P[both], atol=1e-6)


def test_anaglyph_alignment_on_rendered_markers(lab):
    """Bright markers on known points: same row on both normalised images, the columns apart by (p − p₀)/pixel."""
    from aerophoto import render as R
    from aerophoto.site import get_site

    site = get_site()
    t = site.params.texture_m
    cat = site.catalogue
    P = cat[["X_m", "Y_m"]].to_numpy()
    P = (np.floor(P / t) + 0.5) * t
    P3 = np.column_stack([P, site.height(P[:, 0], P[:, 1])])
    xl, xr = lab.normal_xy(P3)
    w = lab.window_mm
    inside = (xl[:, 0] > w[0] + 8) & (xl[:, 0] < w[1] - 8) & (xl[:, 1] > w[2] + 8) & (xl[:, 1] < w[3] - 8)
    chosen = []
    for i in np.flatnonzero(inside):
        if all(np.hypot(*(xl[i] - xl[j])) > 15 for j in chosen):
            chosen.append(i)
    chosen = chosen[:8]
    assert len(chosen) >= 4
    tex = np.full_like(site.texture, 60)
    for x, y in P[chosen]:
        c, r = int(x // t), int(y // t)
        tex[r - 1:r + 2, c - 1:c + 2] = 255
    marked = replace(site, texture=tex, _levels=[])
    n = 1024
    photos = [R.render_shot(marked, s, n, vignetting=0.0, fiducials=False, level=0, objects=False)
              for s in (lab.left, lab.right)]
    px = CAM.frame_mm / n
    L = st.normalise_image(photos[0].image, lab.camera, lab.left.pose, lab.R_n, w, px)
    Rn = st.normalise_image(photos[1].image, lab.camera, lab.right.pose, lab.R_n,
                            (w[0] - lab.p0_mm, w[1] - lab.p0_mm, w[2], w[3]), px)
    ana = st.anaglyph(L.image, Rn.image)
    for i in chosen:
        rc = L.mm_to_pixel(xl[i])
        r0, c0 = int(round(rc[0])), int(round(rc[1]))
        d_expected = (xl[i, 0] - xr[i, 0] - lab.p0_mm) / px  # the marker's disparity on the anaglyph, px
        cents = []
        for ch, c_guess in ((0, c0), (1, c0 - d_expected)):
            cg = int(round(c_guess))
            win = ana[r0 - 8:r0 + 9, cg - 8:cg + 9, ch] - 60 / 255
            rr, cc = np.mgrid[r0 - 8:r0 + 9, cg - 8:cg + 9]
            wgt = np.clip(win, 0, None)
            assert wgt.max() > 0.5
            cents.append((np.sum(wgt * rr) / wgt.sum(), np.sum(wgt * cc) / wgt.sum()))
        (rl, cl), (rr_, cr) = cents
        assert abs(rl - rr_) < 0.3  # zero vertical parallax after the epipolar alignment
        assert abs((cl - cr) - d_expected) < 0.5  # the horizontal disparity of a known point
        assert np.hypot(rl - rc[0], cl - rc[1]) < 0.5  # and the left marker where geometry puts it


def test_height_model_on_textured_ground(lab):
    """The correlation height model agrees with the truth to RMS ≤ 2.5 m where the ground is textured and seen twice."""
    from aerophoto.labs import ch07

    hm = ch07.height_model(lab)
    tg = hm.textured_ground & hm.reliable
    assert tg.sum() > 0.15 * hm.textured_ground.sum()  # a good share of the fields is matched reliably
    assert hm.rms_m(hm.textured_ground) <= 2.5
    assert np.mean(np.abs(hm.error_m[tg]) > 5.0) < 0.03  # few gross errors (repetitive furrows)
    t = hm.table()
    assert list(t.index[:5]) == list(ch07.HM_CLASSES)
    assert t["share, %"].iloc[:5].sum() == pytest.approx(100.0)
    # the reliability tests throw out much more of the forest than of the roads
    assert t.loc["forest canopy", "matched, %"] < t.loc["roads, sand banks", "matched, %"]


# --------------------------------------------------------------------------- the demos
def test_floating_mark_marks_one_channel_each_and_reads_heights(lab):
    import matplotlib

    matplotlib.use("Agg")
    from aerophoto.demos import stereo as ds
    from aerophoto.site import get_site

    d = ds.FloatingMarkDemo(lab=lab)
    base, ext, k = d._base("village")
    r = d.set(p_mm=round(lab.p0_mm + 2.0, 2)).result  # the two crosses 2 mm (17 pixels) apart
    changed = np.any(r.rgb != base, axis=2)
    red_only = changed & (r.rgb[..., 1] == base[..., 1])
    cyan_only = changed & (r.rgb[..., 0] == base[..., 0])
    assert red_only.sum() > 10 and cyan_only.sum() > 10 and not np.any(changed & ~red_only & ~cyan_only)
    # a roof corner: put the mark on its left image and set its parallax — the mark rests on the roof
    pts = get_site().object_points
    corner = pts[pts["kind"] == "roof corner"][["X_m", "Y_m", "Z_m"]].to_numpy()
    xl, xr = lab.normal_xy(corner)
    cx, cy = d.areas["village"]
    near = np.flatnonzero((np.abs(xl[:, 0] - cx) < 18) & (np.abs(xl[:, 1] - cy) < 12))
    j = near[0]
    p = round(float(xl[j, 0] - xr[j, 0]), 2)
    d.set(area="village", x_mm=round(xl[j, 0] - cx, 1), y_mm=round(xl[j, 1] - cy, 1), p_mm=p)
    Z = float(d.result.table.loc["mark's height Z = Z_S − B·f/p", "value"])
    P = lab.model_to_ground(np.array([cx + round(xl[j, 0] - cx, 1), cy + round(xl[j, 1] - cy, 1)]), p)
    assert Z == pytest.approx(P[2], abs=0.05)
    assert abs(P[2] - corner[j, 2]) < 0.4  # 0.1 mm and 0.01 mm of rounding: a few decimetres at most
    z1 = float(d.set(p_mm=p + 0.5).result.table.loc["mark's height Z = Z_S − B·f/p", "value"])
    assert z1 > Z + 5  # a larger parallax lifts the mark
    direct = d.result.rgb
    d.set(view="reverse")  # the left eye now gets the right photo (and its cross), the right eye the left one
    assert np.array_equal(d.result.rgb[..., 0], direct[..., 1]) and np.array_equal(d.result.rgb[..., 1], direct[..., 0])
    mo = ds.FloatingMarkDemo(lab=lab, measure_only=True)
    assert not any("height" in s for s in mo.result.table.index)  # on the student's own pair: readings only
    d.close()
    mo.close()


def test_base_height_demo():
    import matplotlib

    matplotlib.use("Agg")
    from aerophoto.demos import stereo as ds

    d = ds.BaseHeightDemo()
    t0 = d.result.table
    assert t0.loc["photo base b = B·f/H", "value"] == pytest.approx(72.0)
    dp0 = t0.loc["Δp of h = 20 m, b·h/(H − h)", "value"]
    d.set(B_m=1728)
    assert d.result.table.loc["Δp of h = 20 m, b·h/(H − h)", "value"] == pytest.approx(2 * dp0)
    assert d.result.V == pytest.approx(2 * 2.769, rel=1e-3)
    d.set(B_m=3000, H_m=300, f_mm=1100)  # the photos no longer overlap: said, no error
    assert "do not overlap" in d.table.value and not d.status.value
    d.close()


def test_stereoscope_check_geometry():
    from aerophoto.demos.stereo_figures import stereoscope_view

    L, R = stereoscope_view(0.0, 0.0)
    assert np.allclose(L, R)  # set right: one line
    L, R = stereoscope_view(1.5, 0.0, base_mm=250.0)
    dl, dr = L[1] - L[0], R[1] - R[0]
    assert abs(dl[0] * dr[1] - dl[1] * dr[0]) < 1e-9  # parallel …
    assert abs(np.mean(L[:, 1]) - np.mean(R[:, 1])) == pytest.approx(250 * math.sin(math.radians(1.5)))  # … apart
    L, R = stereoscope_view(0.0, 1.0)
    ang = math.degrees(math.atan2(*(R[1] - R[0])[::-1]) - math.atan2(*(L[1] - L[0])[::-1]))
    assert ang == pytest.approx(2.0)  # a rolled mirror turns its eye's line by twice the roll
    with pytest.raises(ValueError, match="turn_deg"):
        stereoscope_view(60.0)


def test_prints_at_true_size(lab, tmp_path):
    from PIL import Image

    from aerophoto.demos import stereo_figures as sf
    from aerophoto.labs import ch07

    im = ch07.lab_images(lab, 512)
    f = sf.stereo_print(im, tmp_path / "free.pdf", mode="free viewing", size_mm=(55.0, 40.0))
    box = re.search(rb"/MediaBox \[\s*([\d.]+) ([\d.]+) ([\d.]+) ([\d.]+)", f.read_bytes())
    w_pt, h_pt = float(box.group(3)), float(box.group(4))
    wmm = round(55.0 / im.left.pixel_mm) * im.left.pixel_mm
    hmm = round(40.0 / im.left.pixel_mm) * im.left.pixel_mm
    assert w_pt / 72 * 25.4 == pytest.approx(st.EYE_BASE_MM + wmm + 20.0, abs=0.05)  # 65 mm + a piece + margins
    assert h_pt / 72 * 25.4 == pytest.approx(hmm + 28.0, abs=0.05)
    png = sf.stereo_print(im, tmp_path / "scope.png", mode="stereoscope", size_mm=(100.0, 50.0), dpi=200)
    wpx, hpx = Image.open(png).size
    ex = im.left.extent_mm
    w_piece = round(min(100.0, ex[1] - ex[0]) / im.left.pixel_mm) * im.left.pixel_mm  # capped by the overlap
    w_exp = (st.STEREOSCOPE_BASE_MM + w_piece + 20.0) / 25.4 * 200
    assert abs(wpx - w_exp) <= 1.0
    with pytest.raises(ValueError, match="mode"):
        sf.stereo_print(im, tmp_path / "x.pdf", mode="cross-eyed")
    with pytest.raises(ValueError, match="path"):
        sf.stereo_print(im, tmp_path / "x.jpg")


def test_guide_s08():
    from aerophoto import guide

    assert guide.ch07.CHECK_LINE_CM == 40.0
    assert len(guide.ch07.steps_table()) == 2 and len(guide.ch07.checks_table()) == 4
    assert "обратный стереоэффект" in guide.ch07.terms_table()["Russian"].tolist()
