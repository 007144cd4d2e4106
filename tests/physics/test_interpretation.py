"""Chapter 08 (guide §9): the colour site, the shooting conditions, table 10, the interpretation lab."""

from __future__ import annotations

import math

import numpy as np
import pytest

from aerophoto import geometry as g
from aerophoto import interpretation as ip
from aerophoto import spectral as sp
from aerophoto.site import colour, cover
from aerophoto.variants import variant, variant_for_index


@pytest.fixture(scope="module")
def isite():
    return cover.interpretation_site(0)


def _vertical(isite, X, Y, m, **kw):
    return colour.vertical_pose(isite, X, Y, m, **kw)


# ----------------------------------------------------------------------------------------------- the physics
def test_shadow_length_is_h_over_tan_e():
    assert float(ip.shadow_length_m(10.0, 45.0)) == pytest.approx(10.0)
    assert float(ip.shadow_length_m(10.0, 30.0)) == pytest.approx(17.3205, abs=1e-4)
    assert float(ip.shadow_length_m(20.0, 90.0)) == pytest.approx(0.0, abs=1e-12)
    assert ip.shadow_azimuth_deg(150.0) == 330.0
    assert ip.shadow_azimuth_deg(270.0) == 90.0


def test_image_motion_is_W_t_over_m():
    # 360 km/h = 100 m/s, 2 ms, 1:10 000 → 0.2 m on the ground → 0.02 mm on the photo
    assert ip.image_motion_mm(360.0, 2.0, 10000.0) == pytest.approx(0.02)


def test_slope_illumination_lambert():
    assert float(ip.slope_illumination(0.0, 0.0, 40.0, 180.0)) == pytest.approx(1.0)
    # a slope facing the sun, tilted so the rays hit it square: a + (1 − a)/sin e
    e = 30.0
    lit = float(ip.slope_illumination(90.0 - e, 180.0, e, 180.0))
    assert lit == pytest.approx(0.35 + 0.65 / math.sin(math.radians(e)))
    # turned away, steeper than the sun: only the ambient light
    assert float(ip.slope_illumination(70.0, 0.0, e, 180.0)) == pytest.approx(0.35)


def test_motion_blur_keeps_the_mean_and_smears_an_edge():
    img = np.zeros((5, 40), np.float32)
    img[:, 20:] = 1.0
    out = ip.motion_blur(img, 5.0)
    assert out.mean() == pytest.approx(img.mean(), abs=1e-6)
    assert 0.0 < out[2, 19] < 1.0 and 0.0 < out[2, 20] < 1.0
    assert np.array_equal(ip.motion_blur(img, 0.8), img)


@pytest.mark.parametrize("kw, name", [
    (dict(sun_elevation_deg=2.0), "sun_elevation_deg"),
    (dict(visibility_km=0.5), "visibility_km"),
    (dict(season="monsoon"), "season"),
    (dict(moisture_pct=-1), "moisture_pct"),
    (dict(exposure_ms=float("nan")), "exposure_ms"),
])
def test_bad_conditions_name_the_parameter(kw, name):
    with pytest.raises(ValueError, match=name):
        ip.Conditions(**kw)


def test_bad_input_to_the_physics():
    with pytest.raises(ValueError, match="h_m"):
        ip.shadow_length_m(-1.0, 40.0)
    with pytest.raises(ValueError, match="sun_elevation_deg"):
        ip.shadow_length_m(1.0, 0.0)
    with pytest.raises(ValueError, match="band"):
        ip.haze(0.1, "uv", 10.0, 800.0)
    with pytest.raises(ValueError, match="seed"):
        cover.interpretation_site(-1)


# ----------------------------------------------------------------------------------------------- the site
def test_site_has_table_10_objects(isite):
    f = isite.features
    tab = isite.class_table()
    for name in ("deep water", "shallow water", "sand bank", "pine forest", "spruce forest", "deciduous forest",
                 "raised bog", "low bog", "railway", "asphalt road", "gravel road", "ditch", "dam", "haystack",
                 "ploughed field", "mown meadow", "wet meadow", "shrub"):
        assert tab.loc[cover.CLASS_CODES[name], "share, %"] > 0, name
    # islands narrow downstream: the tail is east (downstream) of the head
    for isl in f["islands"]:
        assert isl["tail_m"][0] > isl["head_m"][0]
    # shallows below the islands' tails
    tail = f["islands"][1]["tail_m"]
    near = isite.class_at(tail[0] + np.arange(0, 40, 2.0), np.full(20, tail[1]))
    assert (np.isin(near, [cover.CLASS_CODES["shallow water"], cover.CLASS_CODES["sand bank"]])).sum() >= 5
    # the tributary enters at an acute angle, pointing downstream (east)
    t = f["tributary"]
    d = t[-1] - t[-2]
    angle = math.degrees(math.atan2(-d[1], d[0]))
    assert d[0] > 0 and 20 < angle < 50
    # canopies: spruce uneven and pointed, pine even (the canopy at the class map's texel centres)
    rows, cols = np.indices(isite.classes.shape)
    can = isite.site.objects.canopy_at(cols + 0.5, rows + 0.5)
    pine = can[isite.classes == cover.CLASS_CODES["pine forest"]]
    spruce = can[isite.classes == cover.CLASS_CODES["spruce forest"]]
    assert np.percentile(pine[pine > 0], 90) - np.percentile(pine[pine > 0], 50) < 3.0
    assert np.std(spruce[spruce > 0]) > 2 * np.std(pine[pine > 0])


def test_site_is_deterministic():
    a = cover.build_interpretation_site(0)
    b = cover.interpretation_site(0)
    assert np.array_equal(a.classes, b.classes) and np.array_equal(a.under_roads, b.under_roads)
    assert np.array_equal(a.site.objects.canopy_dm, b.site.objects.canopy_dm)
    assert np.array_equal(a.crowns.index, b.crowns.index) and np.array_equal(a.crowns.tone, b.crowns.tone)
    assert np.array_equal(a.site.objects.planes, b.site.objects.planes)


# ----------------------------------------------------------------------------------------------- rendering
@pytest.fixture(scope="module")
def flat_photo(isite):
    """Sun overhead, no objects, no air, no blur: every class's pixels show its reflectance (× grain)."""
    cond = ip.Conditions(sun_elevation_deg=90.0, visibility_km=None, speed_kmh=0.0)
    return colour.render_colour(isite, g.Camera(), _vertical(isite, 800, 800, 8500), 512, cond, objects=False,
                                relief_shading=False)


def test_each_class_renders_its_reflectance(flat_photo):
    from scipy.ndimage import binary_erosion

    cls = flat_photo.classes
    geom = flat_photo.geometry
    fixed, soil_share = colour.class_band_table("summer")
    checked = 0
    for name in cover.CLASSES:
        code = cover.CLASS_CODES[name]
        mask = binary_erosion(cls == code, iterations=2)
        if mask.sum() < 60:
            continue
        expected = np.tile(fixed[code], (int(mask.sum()), 1)).astype(float)
        if soil_share[code] > 0:
            sb = sp.soil_band_table().bands(geom.moisture_pct[mask], geom.humus_pct[mask], 0.1, sp.PARENTS["loam"])
            expected += soil_share[code] * sb
            # and the band table is the model: the mean texel's soil equals soil_bands of the curve
            h, th = float(geom.humus_pct[mask].mean()), float(geom.moisture_pct[mask].mean())
            np.testing.assert_allclose(sp.soil_band_table().bands(th, h, 0.1, 0.34),
                                       sp.soil_bands(humus_pct=h, moisture_pct=th), rtol=0.01)
        got = flat_photo.bands[mask].mean(axis=0)
        np.testing.assert_allclose(got, expected.mean(axis=0), rtol=0.03, atol=0.002, err_msg=name)
        checked += 1
    assert checked >= 14
    # and the spectra are distinct where table 10 says so: spruce darker than pine, pine than deciduous (NIR)
    nir = sp.BAND_NAMES.index("nir")
    assert fixed[cover.CLASS_CODES["spruce forest"], nir] < fixed[cover.CLASS_CODES["pine forest"], nir] \
        < fixed[cover.CLASS_CODES["deciduous forest"], nir]
    red = sp.BAND_NAMES.index("red")
    assert fixed[cover.CLASS_CODES["asphalt road"], red] < fixed[cover.CLASS_CODES["gravel road"], red]


def test_haze_lowers_contrast_monotonically(isite):
    geom = colour.colour_geometry(isite, g.Camera(), _vertical(isite, 800, 800, 8500), 256)
    cs = []
    for V in (None, 60.0, 20.0, 8.0, 3.0, 1.0):
        cp = colour.colour_photo(geom, ip.Conditions(visibility_km=V, speed_kmh=0.0))
        cs.append(ip.contrast(cp.band("green"), geom.photo.valid))
    assert all(a > b for a, b in zip(cs, cs[1:])), cs
    assert cs[-1] < 0.5 * cs[0]


def test_snow_hides_the_fields(isite):
    geom = colour.colour_geometry(isite, g.Camera(), _vertical(isite, 1320, 300, 4000), 256, objects=False,
                                  relief_shading=False)
    fields = [cover.CLASS_CODES[c] for c in ("ploughed field", "crop", "stubble")]

    def class_means(season):
        cp = colour.colour_photo(geom, ip.Conditions(season=season, visibility_km=None, speed_kmh=0.0))
        red = cp.band("red")
        return np.array([red[geom.classes == c].mean() for c in fields])

    summer, winter = class_means("summer"), class_means("winter")
    assert summer.max() - summer.min() > 0.05  # the fields differ in summer …
    assert winter.max() - winter.min() < 0.01  # … and are one snow field in winter
    assert winter.min() > 0.8


def test_shadows_point_away_from_the_sun_with_length_h_over_tan_e(isite):
    x, y, h, r = isite.features["haystacks"][0]
    c = h / 2.0
    for A, e in ((150.0, 35.0), (240.0, 50.0)):
        geom = colour.colour_geometry(isite, g.Camera(), _vertical(isite, x, y, 150), 512, sun_elevation_deg=e,
                                      sun_azimuth_deg=A)
        P = geom.photo.ground_m[geom.shadow & (geom.photo.surface == 0)]
        d = P[:, :2] - [x, y]
        az = np.degrees(np.arctan2(d[:, 0], d[:, 1])) % 360
        mean_az = math.degrees(math.atan2(d[:, 0].mean(), d[:, 1].mean())) % 360
        assert abs((mean_az - ip.shadow_azimuth_deg(A) + 180) % 360 - 180) < 3.0
        # the shadow's tip: the spheroid's farthest shadow point, c·k + sqrt(r² + c²k²) with k = 1/tan e …
        k = 1.0 / math.tan(math.radians(e))
        tip = c * k + math.hypot(r, c * k)
        along = np.hypot(d[:, 0], d[:, 1])[abs((az - ip.shadow_azimuth_deg(A) + 180) % 360 - 180) < 10]
        assert along.max() == pytest.approx(tip, abs=0.4)
        # … which is the shadow of the top point, h/tan e, plus what the round shape adds (< r)
        assert 0 < tip - float(ip.shadow_length_m(h, e)) < r


def test_winter_and_season_change_colour_not_geometry(isite):
    geom = colour.colour_geometry(isite, g.Camera(), _vertical(isite, 800, 800, 8500), 128)
    s = colour.colour_photo(geom, ip.Conditions())
    w = colour.colour_photo(geom, ip.Conditions(season="winter"))
    assert s.bands.shape == w.bands.shape == (128, 128, 6)
    assert w.band("green").mean() > 2 * s.band("green").mean()


def test_greyscale_photos_of_the_main_site_are_unchanged():
    """The colour site is separate: rendering it leaves the book's site and its photos as they were."""
    from aerophoto.render import render
    from aerophoto.site import get_site

    site = get_site()
    pose = g.Pose(5000.0, 2500.0, 1385.0)
    before = render(site, g.Camera(), pose, 64).image.copy()
    cover.interpretation_site(0)
    after = render(site, g.Camera(), pose, 64).image
    assert np.array_equal(before, after)


# ----------------------------------------------------------------------------------------------- guide §9
def test_table_10_transcribed():
    from aerophoto import guide

    tab = guide.ch08.table_10()
    assert len(tab) == 20
    assert tab["признаки"].str.contains("острым углом").any()
    assert len(guide.ch08.CONDITIONS) == 8
    objs = {r[5] for r in guide.ch08.TABLE_10 if r[5]}
    from aerophoto.demos.interpretation import KEY_VIEWS, N_KEY_ROWS

    assert objs <= set(KEY_VIEWS)
    assert N_KEY_ROWS == sum(1 for r in guide.ch08.TABLE_10 if r[5])


# ----------------------------------------------------------------------------------------------- the lab
V = variant("19-0457")


def test_lab_inputs_hold_no_answer_key():
    from aerophoto.labs import ch08
    from aerophoto.tasks.ch08 import NameObjects

    lab = NameObjects().inputs(V)
    assert set(vars(lab)) == {"bands", "pixel_mm", "m", "marks", "options"}
    assert list(lab.marks.index) == ["1", "2", "3", "4", "5", "6", "P", "Q", "A", "B"]
    key = NameObjects().answers(V)
    assert all(name in ch08.OBJECT_NAMES for name in key.values())
    # nothing of the key in the inputs' text
    text = lab.marks.to_string() + repr(lab).replace(repr(lab.options), "")
    for name in ch08.OBJECT_NAMES:
        assert name not in text


def test_lab_grades_correct_full_and_swapped_labels_partly():
    from aerophoto import tasks
    from aerophoto.course import score

    t = tasks.get("task-08-1")
    key = t.answers(V)
    full = score.grade_task("task-08-1", V, key)
    assert full.score == t.points == 3
    swapped = dict(key, obj1=key["obj2"], obj2=key["obj1"])
    assert key["obj1"] != key["obj2"]
    part = score.grade_task("task-08-1", V, swapped)
    assert part.score == pytest.approx(3 * 4 / 6)
    assert [ok for _, ok, _, _ in part.checks] == [False, False, True, True, True, True]
    # flow and spruce: one of two right → half the points
    t2 = tasks.get("task-08-2")
    k2 = t2.answers(V)
    assert score.grade_task("task-08-2", V, k2).score == 2
    wrong = dict(k2, spruce="Q" if k2["spruce"] == "P" else "P")
    assert score.grade_task("task-08-2", V, wrong).score == pytest.approx(1.0)


def test_width_by_the_scale_passes_and_a_slip_does_not():
    from aerophoto.course import score
    from aerophoto.labs import ch08

    for i in range(0, 60, 7):
        v = variant_for_index(i)
        lab = ch08.lab_photo(v) if i == 0 else None
        tr = ch08.truth(i)
        su = ch08.setup_for(i)
        ab_mm = math.hypot(*(np.array(tr["A"]) - np.array(tr["B"])))
        w = ab_mm * su.m / 1000.0
        g_ = score.grade_task("task-08-3", v, {"width_m": w})
        assert g_.score == 1, (i, w, tr["width_m"])
        if lab is not None:  # from the marks as the student reads them
            A, B = lab.marks.loc["A"].to_numpy(), lab.marks.loc["B"].to_numpy()
            assert score.grade_task("task-08-3", v, {"width_m": math.hypot(*(A - B)) * lab.m / 1000}).score == 1
    assert score.grade_task("task-08-3", V, {"width_m": ch08.truth(V.i)["width_m"] * 1.2}).score == 0


def test_flow_follows_the_photo_swing():
    from aerophoto.labs import ch08

    seen = {}
    for i in range(40):
        su = ch08.setup_for(i)
        seen.setdefault(round(su.kappa_deg) % 360, set()).add(ch08.truth(i)["flow"])
    # κ = 0: east is +x on the photo; κ = 90°: +x points north, so the river (east) flows towards −y
    assert seen[0] == {"towards +x (right)"}
    assert seen[90] == {"towards −y (down)"}
    assert seen[180] == {"towards −x (left)"}
    assert seen[270] == {"towards +y (up)"}


def test_illumination_is_the_renderers(isite):
    """Relit per sun from one render: the same light the renderer gives its white-textured site, pixel by pixel."""
    from aerophoto.render import Sun, render

    pose = _vertical(isite, 620, 1250, 3000)
    for A, e in ((150.0, 45.0), (250.0, 20.0)):
        geom = colour.colour_geometry(isite, g.Camera(), pose, 160, sun_elevation_deg=e, sun_azimuth_deg=A,
                                      relief_shading=False)
        ref = render(isite.site, g.Camera(), pose, 160, vignetting=0.0, fiducials=False, level=0, background=0.0,
                     sun=Sun(A, e))
        np.testing.assert_allclose(geom.illumination, ref.image, atol=1e-5)
        assert np.array_equal(geom.shadow, ref.shadow)
        assert geom.shadow.mean() > 0.05


# ----------------------------------------------------------------------------------------------- the demos
def test_conditions_demo_updates_in_place_and_resets():
    from aerophoto.demos.interpretation import ConditionsDemo

    demo = ConditionsDemo()
    im = demo.view.im_nat
    summer = np.asarray(im.get_array()).copy()
    c0 = demo.result.contrast
    demo.set(season="winter")
    assert demo.view.im_nat is im  # the same artist, new data
    assert np.asarray(im.get_array()).mean() > summer.mean() + 0.2  # snow
    demo.set(season="summer", visibility_km=2)
    assert demo.result.contrast < c0
    demo.set(sun_elevation_deg=20)
    assert demo.result.shadow_m == pytest.approx(20 / math.tan(math.radians(20)))
    demo.reset()
    assert np.array_equal(np.asarray(im.get_array()), summer)
    assert demo.values["season"] == "summer" and demo.values["sun_elevation_deg"] == 45
    with pytest.raises(ValueError, match="visibility_km"):
        demo.set(visibility_km=500)
    labels = {p.label for p in demo.params}
    from aerophoto import book

    ch = next(c for c in book.CHAPTERS if c.number == "08")
    import importlib

    for d in ch.demos:  # every demo of the chapter, wherever it lives (the loupe has its own module)
        mod, cls = d.cls.rsplit(".", 1)
        demo_cls = getattr(importlib.import_module(mod if mod.startswith("aerophoto") else f"aerophoto.demos.{mod}"), cls)
        assert {label for label, _ in d.sliders} <= {p.label for p in demo_cls.params}
    assert "V (visibility), km" in labels


def test_key_demo_shows_each_row():
    from aerophoto.demos.interpretation import KeyDemo

    demo = KeyDemo()
    first = np.asarray(demo.view.im.get_array()).copy()
    assert "Длина" in demo.table.value
    demo.set(row=12)  # spruce (the slider counts table 10's rows from 1)
    assert "Еловый" in demo.table.value
    assert not np.array_equal(first, np.asarray(demo.view.im.get_array()))
    with pytest.raises(ValueError, match="row"):
        demo.set(row=99)


# ----------------------------------------------------------------------------------------------- properties
from hypothesis import given  # noqa: E402
from hypothesis import strategies as st  # noqa: E402


@given(h=st.floats(0.0, 100.0), e1=st.floats(5.0, 89.0), de=st.floats(0.5, 40.0))
def test_shadows_shorten_as_the_sun_rises(h, e1, de):
    e2 = min(e1 + de, 90.0)
    assert float(ip.shadow_length_m(h, e2)) <= float(ip.shadow_length_m(h, e1)) + 1e-9
    assert float(ip.shadow_length_m(h, e1)) == pytest.approx(h / math.tan(math.radians(e1)))


@given(L=st.floats(0.0, 30.0), seed=st.integers(0, 1000))
def test_motion_blur_keeps_the_mean(L, seed):
    img = np.random.default_rng(seed).random((4, 64))
    out = ip.motion_blur(img, L)
    # edges replicated: the mean moves by at most the edge pixels' share
    assert abs(out.mean() - img.mean()) < 0.5 * L / 64 + 1e-9
    assert out.min() >= img.min() - 1e-12 and out.max() <= img.max() + 1e-12


@given(rho=st.floats(0.0, 1.0), V1=st.floats(1.0, 99.0), dV=st.floats(0.5, 50.0))
def test_haze_pulls_every_reflectance_towards_the_air(rho, V1, dV):
    V2 = min(V1 + dV, 100.0)
    thick = float(ip.haze(rho, "green", V1, 2000.0))
    thin = float(ip.haze(rho, "green", V2, 2000.0))
    # the apparent contrast against black: thicker haze, less of the ground's own signal
    dark_thick = float(ip.haze(0.0, "green", V1, 2000.0))
    dark_thin = float(ip.haze(0.0, "green", V2, 2000.0))
    assert thick - dark_thick <= thin - dark_thin + 1e-12


def test_tilt_condition_tilts_the_camera(isite):
    pose = _vertical(isite, 800, 800, 8500)
    flat = colour.render_colour(isite, g.Camera(), pose, 64, ip.Conditions(speed_kmh=0.0))
    tilted = colour.render_colour(isite, g.Camera(), pose, 64, ip.Conditions(alpha_deg=5.0, speed_kmh=0.0))
    assert flat.photo.pose.alpha_deg == 0.0 and tilted.photo.pose.alpha_deg == 5.0
    assert not np.array_equal(flat.bands, tilted.bands)


# ----------------------------------------------------------------------------------------------- the marks on the photo
def _window(isite, X, Y, side_mm, n, m=8300.0, **cond):
    pose = _vertical(isite, X, Y, m)
    return colour.render_colour(isite, g.Camera(), pose, n, ip.Conditions(speed_kmh=0.0, **cond),
                                window_mm=(0.0, 0.0, side_mm))


def test_pine_is_even_and_spruce_mottled_and_darker_under_a_glass(isite):
    """Table 10: pine an even grey tone, spruce mottled and darker — on a 1:8 300 photo seen at ×6 (0.1 mm pixels).

    The tone's evenness is that of the stand, at the scale of groups of trees (blocks of 20 pixels, 17 m): the
    crowns and gaps of both are finer texture."""
    nir = sp.BAND_NAMES.index("nir")
    stats = {}
    for name, (X, Y) in (("pine", (160.0, 1320.0)), ("spruce", (670.0, 1360.0))):
        b = _window(isite, X, Y, 20.0, 200).bands[..., nir]
        blocks = b.reshape(10, 20, 10, 20).mean(axis=(1, 3))
        stats[name] = (float(b.mean()), float(blocks.std() / blocks.mean()), float(b.std() / b.mean()))
    assert stats["spruce"][0] < 0.85 * stats["pine"][0]
    assert stats["spruce"][1] > 1.2 * stats["pine"][1]
    assert stats["pine"][2] > 0.15 and stats["spruce"][2] > 0.15  # crowns and gaps: texture, not a flat tone


def test_a_crop_shows_its_tramlines_every_18_m(isite):
    """Across a crop field under the glass, the soil of the wheel tracks repeats at the tramlines' 18 m."""
    cp = _window(isite, 1264.0, 150.0, 24.0, 320)  # the crop south of the pond, its rows along y (north)
    red = cp.band("red")
    inside = cp.classes == cover.CLASS_CODES["crop"]
    full = inside.mean(axis=0) > 0.9
    runs = np.split(np.arange(len(full)), np.flatnonzero(np.diff(full.astype(int))) + 1)
    cols = max((r for r in runs if full[r[0]]), key=len)  # the widest stretch of columns all in the crop
    profile = np.array([red[inside[:, c], c].mean() for c in cols])
    step = float(np.mean(np.diff(cp.photo.ground_m[0, cols, 0])))
    a = profile - profile.mean()
    acf = np.correlate(a, a, "full")[len(a) - 1:] / (a @ a)
    lags = np.arange(len(acf)) * step
    near = (lags > 10.0) & (lags < 26.0)
    best = lags[near][np.argmax(acf[near])]
    assert abs(best - 18.0) < 1.5 and acf[near].max() > 0.3


def test_houses_cast_shadows_and_their_roof_slopes_take_the_light_differently(isite):
    cp = _window(isite, 480.0, 400.0, 30.0, 300, sun_elevation_deg=35.0, sun_azimuth_deg=150.0)
    geo = cp.geometry
    roof = geo.photo.surface == 1
    assert roof.sum() > 200
    from scipy.ndimage import binary_dilation

    near_roof = binary_dilation(roof, iterations=6) & ~roof
    assert geo.shadow[near_roof].mean() > 0.1  # shadows beside the houses …
    assert geo.shadow[geo.photo.surface == 0].mean() < geo.shadow[near_roof].mean() / 3  # … not everywhere
    lit = geo.illumination[roof]
    assert np.percentile(lit, 90) - np.percentile(lit, 10) > 0.3  # the sunny slope and the shaded one


def test_the_magnifier_shows_what_the_photo_shows_finer():
    from aerophoto.labs import ch08

    i = 57
    lab = ch08._lab_photo(i)
    x, y, side = -20.0, 30.0, 180.0 / 1024 * 64
    win = ch08.photo_window(i, x, y, side, 256)
    r0 = int(round((90.0 - (y + side / 2)) / lab.pixel_mm))
    c0 = int(round((x - side / 2 + 90.0) / lab.pixel_mm))
    part = lab.bands[r0:r0 + 64, c0:c0 + 64]
    block = win.bands.reshape(64, 4, 64, 4, 6).mean(axis=(1, 3))
    assert np.allclose(win.photo.extent_mm, (x - side / 2, x + side / 2, y - side / 2, y + side / 2))
    assert abs(float(block.mean()) / float(part.mean()) - 1.0) < 0.03
    assert np.corrcoef(block.ravel(), part.ravel())[0, 1] > 0.9
    assert float(win.bands.std()) > float(part.std())  # finer: more detail than the photo's pixels hold
    with pytest.raises(ValueError, match="x_mm"):
        ch08.photo_window(i, 85.0, 0.0, 20.0)
    with pytest.raises(ValueError, match="side_mm"):
        ch08.photo_window(i, 0.0, 0.0, 0.2)


def test_the_key_shows_a_preview_first_and_the_full_close_up_when_it_rests():
    from aerophoto.demos.interpretation import KEY_PREVIEW_PX, KEY_PX, KeyDemo, key_model

    r = key_model(10, n_px=KEY_PREVIEW_PX)  # pine: 180 mm × 1 200 of the ground, on a 1:8 000 photo
    assert r.image.shape == (KEY_PREVIEW_PX, KEY_PREVIEW_PX, 3) and r.ground_m == pytest.approx(1200 * 0.18)
    assert "Сосновый" in r.row[2]
    demo = KeyDemo()
    demo._preview = True
    demo.values["row"] = 3
    preview = demo.compute(**demo.values)
    demo._preview = False
    assert preview.image.shape[0] == KEY_PREVIEW_PX and (3, "colour film") not in demo._seen
    demo.set(row=3)  # from code: always the full close-up, and kept
    assert demo.result.image.shape[0] == KEY_PX and (3, "colour film") in demo._seen
    assert "current" in {row[5] for row in __import__("aerophoto").guide.ch08.TABLE_10}
    demo.close()
