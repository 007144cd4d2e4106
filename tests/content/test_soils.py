"""Chapter 13 (guide §14): the site's soil layer, the soil model's §14 facts, the scale classes, the
segmentation and the graded lab (aerophoto.site.soils, spectral, guide.ch13, soilmap, tasks.ch13)."""

import numpy as np
import pytest

from aerophoto import guide, soilmap, spectral, tasks
from aerophoto.course import score
from aerophoto.site import get_site
from aerophoto.site import soils as so
from aerophoto.labs import ch13 as lab13
from aerophoto.tasks import ch13
from aerophoto.variants import variant_for_index

CHERNOZEM, FOREST, ERODED, ALLUVIAL, GLEY = range(5)


@pytest.fixture(scope="module")
def site():
    return get_site()


@pytest.fixture(scope="module")
def layer(site):
    return so.soil_layer(site)


# --------------------------------------------------------------------------- the layer
def test_layer_is_deterministic_and_does_not_depend_on_the_extent(site, layer):
    ext = (3000.0, 4200.0, 1500.0, 2700.0)
    a = so._build(site, ext, 10.0, 0)
    b = so._build(site, ext, 10.0, 0)
    for name in ("code", "moisture_pct", "humus_pct", "particle_mm"):
        np.testing.assert_array_equal(getattr(a, name), getattr(b, name))
    # the same cells of the whole-site layer (cells aligned on the 10 m grid)
    sub = (slice(150, 270), slice(300, 420))
    np.testing.assert_array_equal(a.code, layer.code[sub])
    np.testing.assert_allclose(a.moisture_pct, layer.moisture_pct[sub], atol=1e-4)
    np.testing.assert_allclose(a.humus_pct, layer.humus_pct[sub], atol=1e-4)


def test_seed_changes_the_variation_not_the_pattern(site):
    ext = (2000.0, 5000.0, 1000.0, 3500.0)
    a = so.soil_layer(site, extent_m=ext, seed=0)
    b = so.soil_layer(site, extent_m=ext, seed=1)
    assert not np.allclose(a.moisture_pct, b.moisture_pct)
    assert np.mean(a.code == b.code) > 0.9  # the classes follow the relief; only borders move


def test_every_class_is_on_the_site_with_its_russian_name(layer):
    shares = layer.shares()
    assert all(shares[k] > 1.0 for k in so.SOIL_CLASSES), shares
    assert abs(sum(shares.values()) - 100.0) < 1e-9
    assert so.SOIL_CLASSES[CHERNOZEM].ru == "чернозём выщелоченный"
    assert all(c.ru and c.name for c in so.SOIL_CLASSES.values())
    t = layer.table()
    assert list(t.index) == list(so.SOIL_NAMES)


def _mean(layer, field, k):
    return float(getattr(layer, field)[layer.code == k].mean())


def test_soils_follow_the_relief(layer):
    # gleyed soils lie in hollows, eroded soils on the steepest ground
    hollow = {k: _mean(layer, "hollow_m", k) for k in so.SOIL_CLASSES}
    assert hollow[GLEY] > 0.6 and hollow[GLEY] == max(hollow.values())
    slope = {k: _mean(layer, "slope_deg", k) for k in so.SOIL_CLASSES}
    assert slope[ERODED] > 1.0 and slope[ERODED] == max(slope.values())
    assert layer.slope_deg[layer.code == ERODED].min() > 0.6
    # wetter in the hollows and the floodplain, driest on the eroded slopes
    th = {k: _mean(layer, "moisture_pct", k) for k in so.SOIL_CLASSES}
    assert th[GLEY] > th[ALLUVIAL] > th[CHERNOZEM] > th[ERODED]
    # thinner humus on the slopes than on the interfluves, and thinner the steeper
    H = {k: _mean(layer, "humus_pct", k) for k in so.SOIL_CLASSES}
    assert H[ERODED] < H[FOREST] < H[CHERNOZEM] < H[GLEY]
    e = layer.code == ERODED
    steep = layer.slope_deg[e] > np.median(layer.slope_deg[e])
    assert layer.humus_pct[e][steep].mean() < layer.humus_pct[e][~steep].mean() - 0.3
    # within one class moisture still rises with hollow depth
    c = layer.code == CHERNOZEM
    assert np.corrcoef(layer.hollow_m[c], layer.moisture_pct[c])[0, 1] > 0.2


def test_exposure_sunward_slopes_are_eroded_sooner(layer):
    band = (layer.slope_deg > 0.85) & (layer.slope_deg < 1.0) & (layer.code != FOREST) & (layer.code != ALLUVIAL)
    south = band & (np.cos(np.radians(layer.aspect_deg - 180.0)) > 0.7)
    north = band & (np.cos(np.radians(layer.aspect_deg)) > 0.7)
    assert south.sum() > 50 and north.sum() > 50
    assert np.mean(layer.code[south] == ERODED) > np.mean(layer.code[north] == ERODED) + 0.3


def test_floodplain_soils_lie_along_the_river(site, layer):
    river = site.features["river"]
    X, Y = np.meshgrid(layer.X_m, layer.Y_m)
    d = np.abs(Y - np.interp(X, river[:, 0], river[:, 1]))
    assert d[layer.code == ALLUVIAL].max() <= so.FLOODPLAIN_M + 1e-6
    assert np.all(layer.code[d < 50.0] == ALLUVIAL)


def test_flat_site_has_no_eroded_or_gleyed_soils():
    flat = so.soil_layer(get_site(relief_m=0.0), extent_m=(0.0, 10000.0, 0.0, 5000.0), spacing_m=40.0)
    assert not np.any(flat.code == ERODED) and not np.any(flat.code == GLEY)


def test_bad_input_is_named(site):
    with pytest.raises(ValueError, match="spacing_m"):
        so.soil_layer(site, spacing_m=0.1)
    with pytest.raises(ValueError, match=r"extent_m\[1\]"):
        so.soil_layer(site, extent_m=(100.0, 50.0, 0.0, 100.0))
    with pytest.raises(ValueError, match="seed"):
        so.soil_layer(site, seed=-1)
    small = so.soil_layer(site, extent_m=(0.0, 200.0, 0.0, 200.0))
    with pytest.raises(ValueError, match="moisture_shift_pct"):
        small.bands(moisture_shift_pct=99.0)
    with pytest.raises(ValueError, match="band"):
        small.bands(["ultraviolet"])


def test_layer_bands_are_the_model_exactly(layer):
    rows, cols = np.array([10, 200, 300, 450]), np.array([20, 400, 700, 900])
    got = layer.bands()[rows, cols]
    for (r, c), g in zip(zip(rows, cols), got):
        kw = dict(moisture_pct=float(layer.moisture_pct[r, c]), humus_pct=float(layer.humus_pct[r, c]),
                  particle_mm=float(layer.particle_mm[r, c]), parent=so.SOIL_CLASSES[int(layer.code[r, c])].parent)
        np.testing.assert_allclose(g, spectral.soil_bands(**kw), rtol=3e-3)


def test_wetter_layer_is_darker_in_every_band():
    small = so.soil_layer(extent_m=(2000.0, 3000.0, 1500.0, 2500.0))
    dry, wet = small.bands(), small.bands(moisture_shift_pct=10.0)
    assert np.all(wet < dry)


# --------------------------------------------------------------------------- the model against guide §14
def test_wet_soil_is_darker_in_every_band():
    b = np.array([spectral.soil_bands(moisture_pct=t) for t in (0, 10, 20, 30, 40, 50)])
    assert np.all(np.diff(b, axis=0) < 0)


def _dip_depth(theta, at):
    wl = np.array([at - 0.12, at, at + 0.12])
    r = spectral.soil_reflectance(wl, moisture_pct=theta)
    return 1.0 - r[1] / (0.5 * (r[0] + r[2]))


@pytest.mark.parametrize("at", guide.ch13.WATER_DIPS_UM)
def test_water_dips_deepen_with_moisture(at):
    d = [_dip_depth(t, at) for t in (0, 10, 20, 30, 40)]
    assert np.all(np.diff(d) > 0)
    assert d[-1] > 0.05
    # and the dip is a local minimum of the wet curve near the guide's wavelength
    wl = spectral.WAVELENGTHS_UM
    r = spectral.soil_reflectance(moisture_pct=30.0)
    near = (wl > at - 0.1) & (wl < at + 0.1)
    assert abs(wl[near][np.argmin(r[near])] - at) <= 0.03


def test_dry_curve_rises_to_1_6_2_0_then_falls():
    wl = spectral.WAVELENGTHS_UM
    r = spectral.soil_reflectance(moisture_pct=0.0, humus_pct=2.0)
    assert 1.6 <= wl[np.argmax(r)] <= 2.0 + 0.2
    assert r[wl <= 1.3][-1] > r[0] * 2
    assert r[-1] < r.max()


def test_humus_linear_to_five_percent_then_flatter():
    H = np.linspace(0.0, 5.0, 11)
    red = np.array([spectral.soil_bands(humus_pct=h)[2] for h in H])
    np.testing.assert_allclose(np.diff(red, 2), 0.0, atol=1e-9)  # linear up to 5 %
    slope_low = spectral.soil_bands(humus_pct=3.0)[2] - spectral.soil_bands(humus_pct=2.0)[2]
    slope_high = spectral.soil_bands(humus_pct=11.0)[2] - spectral.soil_bands(humus_pct=10.0)[2]
    assert slope_low < 0 and slope_high < 0
    assert abs(slope_high) < 0.6 * abs(slope_low)
    # the red band is the most sensitive
    rel = 1 - spectral.soil_bands(humus_pct=5.0) / spectral.soil_bands(humus_pct=0.0)
    assert np.argmax(rel) == spectral.BAND_NAMES.index("red")


def test_finer_particles_are_brighter_most_below_0_4_mm():
    d = np.array([0.02, 0.05, 0.1, 0.2, 0.4, 1.0, 2.0])
    red = np.array([spectral.soil_bands(particle_mm=x)[2] for x in d])
    assert np.all(np.diff(red) < 0)
    total = red[0] - red[-1]
    assert (red[0] - red[4]) / total > 0.9


# --------------------------------------------------------------------------- the scale classes
@pytest.mark.parametrize("m, expected", [
    (2000, "detailed"), (5000, "detailed"), (5001, "between classes"), (9999, "between classes"),
    (10000, "large-scale"), (25000, "large-scale"), (25001, "between classes"), (49999, "between classes"),
    (50000, "medium-scale"), (200000, "medium-scale"), (300000, "between classes"),
    (500000, "small-scale"), (1e6, "small-scale"),
])
def test_soil_map_scale_classes_with_the_gaps(m, expected):
    assert guide.ch13.soil_map_scale_class(m) == expected


def test_scale_class_bad_input_and_notes():
    for bad in (0, -5, float("nan"), float("inf")):
        with pytest.raises(ValueError, match="scale_denominator"):
            guide.ch13.soil_map_scale_class(bad)
    assert "between classes" in guide.ch13.scale_class_note(30000) and "25\u202f000" in guide.ch13.scale_class_note(30000)
    assert len(guide.ch13.scale_table()) == 7  # four classes and three gaps
    assert len(guide.ch13.STEPS) == 5 and guide.ch13.HUMUS_LINEAR_UP_TO_PCT == spectral.HUMUS_LINEAR_PCT


# --------------------------------------------------------------------------- segmentation
def test_segment_tones_recovers_three_flat_tones():
    rng = np.random.default_rng(1)
    truth = np.zeros((60, 60), np.int64)
    truth[:, 20:40] = 1
    truth[:, 40:] = 2
    levels = np.array([[0.1, 0.2, 0.1], [0.5, 0.4, 0.3], [0.9, 0.8, 0.7]])
    img = levels[truth] + rng.normal(0, 0.02, (60, 60, 3))
    lab = soilmap.segment_tones(img, 3, seed=0)
    np.testing.assert_array_equal(lab, truth)  # numbered from the darkest
    np.testing.assert_array_equal(lab, soilmap.segment_tones(img, 3, seed=0))
    t = soilmap.contingency(lab, truth)
    np.testing.assert_array_equal(t, np.diag([1200, 1200, 1200]))
    assert ch13.majority_agreement_pct(lab, truth) == 100.0


def test_segmentation_bad_input():
    with pytest.raises(ValueError, match="k = 0"):
        soilmap.segment_tones(np.zeros((4, 4, 3)), 0)
    with pytest.raises(ValueError, match="finite"):
        soilmap.segment_tones(np.full((4, 4), np.nan), 2)
    with pytest.raises(ValueError, match="shape"):
        soilmap.contingency(np.zeros((3, 3), int), np.zeros((4, 4), int))


# --------------------------------------------------------------------------- the lab
V = [variant_for_index(i) for i in (0, 3, 57, 99)]


def _student(task_id, v):
    """What a student computes from the task's inputs, independently of the task code."""
    d = tasks.inputs(task_id, v)
    if task_id == "task-13-1":
        out = {}
        for f, m in zip(ch13.MAP_FACTORS, d["scale denominator"]):
            out[f"class_{f}m"] = ("detailed" if m <= 5000 else "large-scale" if 10000 <= m <= 25000 else
                                  "medium-scale" if 50000 <= m <= 200000 else "small-scale" if m >= 500000
                                  else "between classes")
        return out
    if task_id == "task-13-2":
        kw = {k: d[k] for k in ("moisture_pct", "humus_pct", "particle_mm", "parent")}
        wl = spectral.WAVELENGTHS_UM
        wet = spectral.soil_reflectance(None, **kw)
        dry = spectral.soil_reflectance(None, **{**kw, "moisture_pct": 0.0})
        red = (wl >= 0.63 - 1e-9) & (wl <= 0.69 + 1e-9)
        i145 = int(np.argmin(np.abs(wl - 1.45)))
        ratios = [spectral.soil_bands(**kw)[j] / spectral.soil_bands(**{**kw, "moisture_pct": 0.0})[j]
                  for j in range(6)]
        return {"rho_red": wet[red].mean(), "wet_dry_145_pct": 100 * wet[i145] / dry[i145],
                "band": spectral.BAND_NAMES[int(np.argmin(ratios))]}
    k = len(np.unique(d.soil_map))
    lab = soilmap.segment_tones(d.composite, k, seed=0)
    agree = 0
    for a in range(k):
        agree += np.bincount(d.soil_map[lab == a]).max() if np.any(lab == a) else 0
    return {"k": k, "agreement_pct": 100 * agree / d.soil_map.size}


@pytest.mark.parametrize("task_id", ["task-13-1", "task-13-2", "task-13-3"])
def test_lab_grades_a_correct_submission_full(task_id):
    for v in V:
        g = score.grade_task(task_id, v, _student(task_id, v))
        assert g.score == g.points, (v.i, g.checks)


def test_lab_grades_wrong_submissions_zero():
    v = V[2]
    good = _student("task-13-1", v)
    g = score.grade_task("task-13-1", v, {**good, "class_2m": "large-scale"})  # ignoring the gap
    assert g.score == 0
    good = _student("task-13-2", v)
    g = score.grade_task("task-13-2", v, {**good, "band": "swir1"})
    assert g.score == 0
    g = score.grade_task("task-13-2", v, {**good, "wet_dry_145_pct": 100 - good["wet_dry_145_pct"]})
    assert g.score == 0
    good = _student("task-13-3", v)
    g = score.grade_task("task-13-3", v, {**good, "agreement_pct": good["agreement_pct"] - 1.0})
    assert g.score == 0
    g = score.grade_task("task-13-3", v, {**good, "k": len(so.SOIL_CLASSES) + 1})
    assert g.score == 0


def test_lab_answers_depend_on_the_variant_and_inputs_hold_no_key():
    a = [tasks.answers("task-13-3", v)["agreement_pct"] for v in V]
    assert len(set(np.round(a, 2))) == len(V)
    c = {tuple(tasks.answers("task-13-1", v).values()) for v in (variant_for_index(i) for i in range(100))}
    assert len(c) >= 3
    p = tasks.inputs("task-13-3", V[0])
    assert not hasattr(p, "labels") and p.composite.shape == (200, 200, 3)
    assert "rho_red" not in tasks.inputs("task-13-2", V[0])


# --------------------------------------------------------------------------- the demo
def test_explorer_opens_on_variant_00_and_moves_its_artists_in_place():
    import matplotlib

    matplotlib.use("Agg")
    from aerophoto.demos.spectral_explorer import REFERENCE, SpectralExplorerDemo, demo_patch

    demo = SpectralExplorerDemo()
    assert demo.values["moisture_pct"] == REFERENCE["moisture_pct"]
    p00 = lab13.patch_of(variant_for_index(0))
    assert demo_patch().extent_m == p00.extent_m
    demo.set(roughness=0.0)  # no clods: the task's own photo of variant 00's patch
    np.testing.assert_allclose(demo.result.composite, p00.composite, atol=1e-6)
    demo.reset()
    curve, img = demo.view.curve, demo.view.img
    before_curve = np.array(curve.get_ydata())
    before_img = np.array(img.get_array())
    demo.set(moisture_pct=40)
    assert demo.view.curve is curve and demo.view.img is img
    assert np.all(np.array(curve.get_ydata()) < before_curve)  # wetter: darker at every wavelength
    assert np.array(img.get_array()).mean() < before_img.mean()
    segs = demo.view.levels.get_segments()
    assert len(segs) == 3  # the camera's three bands
    demo.set(camera="Thematic Mapper 5-4-3", humus_pct=0, particle_mm=0.02)
    assert demo.view.spans["swir1"].get_alpha() > demo.view.spans["blue"].get_alpha()
    demo.reset()
    np.testing.assert_allclose(np.array(curve.get_ydata()), before_curve)
    labels = {p.label for p in demo.params}
    from aerophoto import book

    ch = next(c for c in book.CHAPTERS if c.number == "13")
    assert {lab for d in ch.demos for lab, _ in d.sliders} <= labels
    for p in demo.params:  # every slider's ends are valid input
        if p.kind != "choice":
            demo.set(**{p.name: p.lo})
            demo.set(**{p.name: p.hi})
    with pytest.raises(ValueError, match="moisture_pct"):
        demo.set(moisture_pct=80)
    demo.close()


def test_points_read_their_cells(layer):
    X = layer.X_m[[5, 500, 999]]
    Y = layer.Y_m[[7, 250, 499]]
    got = layer.at(X + 3.0, Y - 4.0)  # inside the cells
    np.testing.assert_array_equal(got["code"], layer.code[[7, 250, 499], [5, 500, 999]])
    np.testing.assert_array_equal(got["humus_pct"], layer.humus_pct[[7, 250, 499], [5, 500, 999]])
    np.testing.assert_array_equal(layer.class_at(X, Y), got["code"])
    assert layer.class_at(-5.0, 100.0) == 255
    b = spectral.soil_band_table().bands(got["moisture_pct"], got["humus_pct"], got["particle_mm"],
                                         got["parent_peak"])
    np.testing.assert_allclose(b, layer.bands()[[7, 250, 499], [5, 500, 999]], rtol=1e-6)


# ----------------------------------------------------------------------------------------------- the overlay technique
def test_overlay_cuts_the_image_into_pieces_of_one_combination_of_keys():
    tone = np.array([[0, 0, 0, 1, 1, 1],
                     [0, 0, 0, 1, 1, 1],
                     [0, 0, 0, 1, 1, 1]])
    relief = np.array([[0, 0, 1, 1, 1, 1],
                       [0, 0, 0, 1, 1, 1],
                       [0, 0, 0, 1, 1, 0]])
    pieces, sure = soilmap.overlay([tone, relief])
    # the combinations (0,0), (0,1), (1,1), (1,0): four pieces, numbered in the order of their first cells
    assert pieces.tolist() == [[0, 0, 1, 2, 2, 2],
                               [0, 0, 0, 2, 2, 2],
                               [0, 0, 0, 2, 2, 3]]
    # within tone 0, (0,0) holds 8 of 9 cells: sure; (0,1) one cell: doubtful; likewise in tone 1
    assert sure.tolist() == [True, False, True, False]
    # one combination in two separate places is two pieces
    p2, _ = soilmap.overlay([np.array([[0, 1, 0]])])
    assert p2.tolist() == [[0, 1, 2]]
    with pytest.raises(ValueError, match="sheets"):
        soilmap.overlay([tone, relief[:, :4]])
    with pytest.raises(ValueError, match="sheets"):
        soilmap.overlay([tone.astype(float)])
    with pytest.raises(ValueError, match="sure_share"):
        soilmap.overlay([tone], sure_share=0.2)


def test_the_key_sheets_follow_the_relief_and_the_cover(site, layer):
    part = so.soil_layer(site, extent_m=(2000.0, 3600.0, 2300.0, 3900.0), spacing_m=20.0)
    small = so.key_sheets(part, site)
    assert small["relief"].shape == part.shape == small["cover"].shape
    sheets = so.key_sheets(layer, site)  # the whole site
    assert (sheets["relief"][layer.slope_deg > so.ERODED_SLOPE_DEG] >= 1).all()
    assert set(np.unique(sheets["relief"])) == {0, 1, 2} and set(np.unique(sheets["cover"])) == {0, 1, 2, 3}
    # the soils the keys point to (guide §14): gley in the hollows (alluvial where the floodplain takes them),
    # grey forest soil under the forest, eroded soil on slopes in the fields
    hollow = sheets["relief"] == 2
    assert np.isin(layer.code[hollow], [GLEY, ALLUVIAL]).mean() > 0.8  # the map's hollow edge is noisy
    forest = (sheets["cover"] == 1) & ~hollow  # (a hollow's gley takes precedence over the forest's soil)
    assert (layer.code[forest] == FOREST).mean() > 0.8
    slope_field = (sheets["relief"] == 1) & (sheets["cover"] == 0)
    assert (layer.code[slope_field] == ERODED).mean() > 0.6
    with pytest.raises(TypeError, match="layer"):
        so.key_sheets("abc", site)
