"""Chapter 08's covers close up (aerophoto.site.texture, site.crowns): zero-mean marks, exact lines, solid crowns."""

from __future__ import annotations

import math

import numpy as np
import pytest

from aerophoto.site import cover, texture
from aerophoto.site.crowns import Crowns, crown_height


@pytest.fixture(scope="module")
def isite():
    return cover.interpretation_site(0)


# ----------------------------------------------------------------------------------------------- the patterns
def test_pulses_and_stripes_are_zero_mean_and_fade_with_the_footprint():
    u = np.linspace(0.0, 36.0, 72001)[:-1]  # two whole periods of 18 m
    for fp in (0.0, 0.4, 1.5, 3.0):
        p = texture.pulses(u, 18.0, 0.5, fp)
        assert abs(float(p.mean())) < 1e-4, fp
    sharp, blurred = texture.pulses(u, 18.0, 0.5, 0.0), texture.pulses(u, 18.0, 0.5, 1.5)
    assert blurred.max() < 0.5 * sharp.max()  # a blurred line is fainter …
    assert (blurred > 0.1 * blurred.max()).sum() > (sharp > 0.1 * sharp.max()).sum()  # … and wider
    assert not texture.pulses(u, 1.0, 0.4, 2.0).any()  # lines blurred into one another: their mean, 0
    w = np.linspace(0.0, 35.0, 70001)[:-1]  # twenty whole periods of 1.75 m
    s = texture.stripes(w, 1.75, 0.0)
    assert abs(float(s.mean())) < 1e-4 and s.max() == pytest.approx(1.0, abs=1e-6)
    assert texture.stripes(w, 1.75, 0.875).max() == pytest.approx(math.sin(math.pi / 2) / (math.pi / 2), abs=1e-3)
    assert not texture.stripes(w, 1.75, 1.75).any()  # a pixel as wide as a period sees its mean


def test_noise_is_seeded_zero_mean_unit_and_fades_below_the_pixel():
    rng = np.random.default_rng(3)
    X, Y = rng.uniform(0, 1600, 40000), rng.uniform(0, 1600, 40000)
    n = texture.noise(X, Y, 5.0, 11)
    assert abs(float(n.mean())) < 0.05 and float(n.std()) == pytest.approx(1.0, abs=0.08)
    assert np.array_equal(n, texture.noise(X, Y, 5.0, 11))  # seeded
    assert not np.array_equal(n, texture.noise(X, Y, 5.0, 12))
    assert float(texture.noise(X, Y, 5.0, 11, footprint_m=5.0).std()) == pytest.approx(math.exp(-0.5), rel=0.1)
    assert not texture.noise(X, Y, 1.0, 11, footprint_m=4.0).any()
    # streaks: longer along their direction than across it
    along = texture.noise(np.arange(0, 50, 0.5), np.zeros(100), 1.0, 13, along_m=20.0)
    across = texture.noise(np.zeros(100), np.arange(0, 50, 0.5), 1.0, 13, along_m=20.0)
    assert np.abs(np.diff(along)).mean() < 0.3 * np.abs(np.diff(across)).mean()
    gx, gy = texture.wave_gradient(X[:200], Y[:200], 1.0, 5)
    assert np.isfinite(gx).all() and 0.3 < float(np.hypot(gx, gy).mean()) < 3.0


def test_every_cover_keeps_its_mean_tone(isite):
    """The texture varies a cover's tone around its mean: the gain averages 1, the soil's share moves by 0."""
    rng = np.random.default_rng(7)
    n = isite.classes.shape[0]
    checked = 0
    for name in cover.CLASSES:
        code = cover.CLASS_CODES[name]
        rows, cols = np.nonzero(isite.classes == code)
        if len(rows) < 2000:
            continue
        k = rng.integers(0, len(rows), 60000)
        X = cols[k] + rng.uniform(0.0, 1.0, len(k))
        Y = rows[k] + rng.uniform(0.0, 1.0, len(k))
        cls, lines = texture.pixel_classes(isite, X, Y)
        keep = cls == code
        for fp in (0.35, 1.5):
            gain, soil = texture.ground_texture(isite, cls, X, Y, fp, lines)
            assert abs(float(gain[keep].mean()) - 1.0) < 0.02, (name, fp, float(gain[keep].mean()))
            assert abs(float(soil[keep].mean())) < 0.01, (name, fp)
        checked += 1
    assert checked >= 15
    assert n == 1600


# ----------------------------------------------------------------------------------------------- the classes
def test_roads_shoulders_and_ditches_are_drawn_from_the_centre_line(isite):
    line = isite.features["asphalt"]
    k = 150  # a point of the asphalt road's centre line away from the river and the crossings
    a, b = line[k], line[k + 1]
    t = (b - a) / np.hypot(*(b - a))
    nrm = np.array([-t[1], t[0]])
    d = np.arange(0.05, 8.0, 0.1)
    P = a + 0.5 * (b - a) + d[:, None] * nrm
    cls, lines = texture.pixel_classes(isite, P[:, 0], P[:, 1])
    C = cover.CLASS_CODES
    dist, _ = texture.LineIndex(line).query(P[:, 0], P[:, 1], reach_m=10.0)
    w = cover.LINEAR["asphalt road"][1]
    assert np.allclose(dist, d, atol=0.05)
    assert (cls[dist < w - 0.05] == C["asphalt road"]).all()
    assert (cls[(dist > w + 0.05) & (dist < w + 0.95)] == C["dirt road"]).all()  # the shoulder
    assert (cls[(dist > w + 1.05) & (dist < w + 2.95)] == C["ditch"]).all()
    assert C["asphalt road"] not in cls[dist > w + 3.05]
    assert "asphalt road" in lines and len(lines["asphalt road"][0]) > 0


def test_class_edges_run_between_texels_without_steps(isite):
    """At a texel's centre the class is the map's; between centres one of the four around it, by the larger
    bilinear weight — a boundary at 45° is a straight line, not a staircase."""
    rows, cols = np.mgrid[200:260, 140:200]
    at = texture._interp_class(isite.classes, cols + 0.5, rows + 0.5, 1.0)
    assert np.array_equal(at, isite.classes[200:260, 140:200])
    cmap = np.zeros((8, 8), np.uint8)
    cmap[np.add.outer(np.arange(8), np.arange(8)) >= 8] = 1  # a diagonal edge of texels
    x = np.linspace(0.5, 7.5, 281)
    X, Y = np.meshgrid(x, x)
    c = texture._interp_class(cmap, X, Y, 1.0)
    edge = np.array([x[np.argmax(row > 0)] if row.any() else np.nan for row in c])
    ok = np.isfinite(edge) & (x > 1.5) & (x < 6.5)
    slope = np.polyfit(x[ok], edge[ok], 1)[0]
    assert slope == pytest.approx(-1.0, abs=0.05)
    assert np.std(edge[ok] - np.polyval(np.polyfit(x[ok], edge[ok], 1), x[ok])) < 0.15  # steps would be 0.29


# ----------------------------------------------------------------------------------------------- the crowns
def _crowns():
    c = Crowns(x_m=np.array([10.0, 30.0]), y_m=np.array([10.0, 10.0]), r_m=np.array([2.0, 2.5]),
               top_m=np.array([20.0, 22.0]), shape=np.array([0, 1]), cls=np.array([12, 11], np.uint8),
               tone=np.ones(2, np.float32))
    return c.with_rasters(80, 0.5)


def test_a_crowns_normal_is_its_shapes_slope():
    crowns, canopy = _crowns()
    assert 215 <= canopy.max() <= 220 and canopy[20, 20] > 150  # decimetres: the dome's top; the cone's
    k, h, q = crowns.lookup(np.array([11.2, 31.0, 50.0]), np.array([10.0, 10.0, 30.0]))
    assert list(k) == [0, 1, -1] and not np.isfinite(h[2])
    assert h[0] == pytest.approx(crown_height(np.int64(0), 20.0, 0.6))
    n = crowns.normal_at(np.array([11.2, 31.0]), np.array([10.0, 10.0]))
    tilt = np.degrees(np.arccos(n[:, 2]))
    assert tilt[0] == pytest.approx(math.degrees(math.atan(0.75 * 20 / 2.0)), abs=1.5)  # the cone's steep side
    assert tilt[1] == pytest.approx(math.degrees(math.atan(6.0 * 1.0 / 2.5 ** 2)), abs=4.0)  # the dome's top
    assert n[0, 0] > 0 and n[1, 0] > 0  # both face away from their axes (east of them)
    # the flank below the surface leans out; the depth into the canopy is measured from the surface
    side = crowns.normal_at(np.array([11.2]), np.array([10.0]), np.array([5.0]))
    assert side[0, 2] < 0.5 and side[0, 0] > 0.8
    assert crowns.surface_depth(np.array([11.2]), np.array([10.0]), np.array([5.0]))[0] == pytest.approx(
        float(h[0]) - 5.0)


def test_the_sites_crowns_make_the_canopy(isite):
    objs = isite.site.objects
    cr = isite.crowns
    assert objs.crowns is cr and cr.index.shape == objs.canopy_dm.shape
    rng = np.random.default_rng(1)
    k = rng.integers(0, len(cr), 300)
    X, Y = cr.x_m[k] + 0.1, cr.y_m[k] + 0.1
    idx, h, _ = cr.lookup(X, Y)
    seen = idx >= 0
    assert seen.mean() > 0.9
    diff = np.abs(objs.canopy_at(X[seen], Y[seen]) - h[seen])  # the raster's columns against the surface
    # a column of the raster spans its crown's slope over one texel: at most the steepest shape's slope (2·top/R)
    # across a texel's diagonal (measured: the largest difference is 0.18 of that bound, the median 8 cm)
    i = idx[seen]
    bound = 2.0 * cr.top_m[i] / cr.r_m[i] * objs.texel_m * np.sqrt(2.0)
    assert np.median(diff) < 0.3 and (diff <= bound).all()
    codes = {cover.CLASS_CODES[n] for n in ("pine forest", "spruce forest", "deciduous forest", "shrub")}
    assert set(np.unique(cr.cls)) <= codes
    for name in ("pine forest", "spruce forest"):
        t = cr.tone[cr.cls == cover.CLASS_CODES[name]]
        assert abs(float(t.mean()) - 1.0) < 0.01
    assert cr.tone[cr.cls == cover.CLASS_CODES["spruce forest"]].std() > \
        2 * cr.tone[cr.cls == cover.CLASS_CODES["pine forest"]].std()  # spruce mottled, pine even (table 10)


def test_the_village_stands_clear_of_the_lab_marks(isite):
    """The village's houses and gardens, and the meadow's bushes, keep off every point a lab mark may take."""
    from aerophoto.labs import ch08

    v = isite.features["village"]
    assert len(v["houses"]) >= 20 and len(v["gardens"]) >= 10
    marks = [p for pts in ch08._candidates(isite).values() for p in pts]
    C = cover.CLASS_CODES
    village = {C["garden"], C["slate roof"], C["red iron roof"]}
    for x, y in marks:
        assert int(isite.class_at(x, y)) not in village
    roofs = np.isin(isite.classes, [C["slate roof"], C["red iron roof"]])
    assert roofs.sum() > 1000
    assert len(isite.features["object_class"]) == len(isite.site.objects)
