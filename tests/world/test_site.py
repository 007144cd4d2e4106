"""The virtual test site: deterministic terrain, texture and a catalogue consistent with the texture."""

import hashlib
import json
import subprocess
import sys

import numpy as np
import pytest

from aerophoto import geometry as g
from aerophoto import site as S
from conftest import ROOT

SMALL = S.SiteParams(width_m=4000, height_m=3000, relief_m=80.0, base_height_m=150.0, seed=7)
ROAD = (S.COVER_CODES["dirt road"], S.COVER_CODES["paved road"])


@pytest.fixture(scope="module")
def small():
    return S.get_site(SMALL)


@pytest.fixture(scope="module")
def default():
    return S.get_site()


def test_deterministic_bit_for_bit(small):
    again = S.build_site(SMALL)  # not from the cache
    assert again is not small
    assert np.array_equal(again.dem, small.dem)
    assert np.array_equal(again.texture, small.texture)
    assert np.array_equal(again.cover, small.cover)
    assert again.catalogue.equals(small.catalogue)
    for k in range(small.n_levels):
        assert np.array_equal(again.texture_level(k), small.texture_level(k))
    other = S.get_site(SMALL, seed=8)
    assert not np.array_equal(other.texture, small.texture)
    assert not np.array_equal(other.dem, small.dem)


def _sha(a) -> str:
    a = np.ascontiguousarray(a)
    return hashlib.sha256(a.tobytes() + str(a.dtype).encode() + str(a.shape).encode()).hexdigest()[:16]


#: the default site as built before build_site was split into named steps (issue 10), and its objects (issue 13):
#: fingerprints that hold on every machine. Exact hashes of the arrays' bytes did not: numpy's exp/sin/cos take
#: other SIMD kernels on a CPU with AVX-512 than on one without, and the last bits of the DEM and the placements
#: built on it differ (the site is the same to 1e-12 m). The fingerprint keeps what a refactoring would change —
#: shape, mean, spread, quantiles and 4 x 8 block means of each array to 1e-9, the share of every value of a
#: whole-number array to 2e-4 of its cells — and lets the last bits go. Integer arrays that no float decides
#: (the cover classes, texture level 6, roads, buildings) keep their exact hashes.
DEFAULT_SITE_SHA = {"cover": "4fd247b649da3e14", "level 6": "21aa6e842145d109", "roads": "6c6f7c3a6318d78f",
                    "buildings": "2e48f5722bd003a3"}
FINGERPRINTS = json.loads((ROOT / "tests" / "data" / "default_site_fingerprint.json").read_text(encoding="utf-8"))
_BLOCKS = (4, 8)


def _block_means(a) -> list:
    a = np.asarray(a, float)
    a = a.reshape(a.shape[0], -1) if a.ndim > 1 else a[:, None]
    rows = np.array_split(np.arange(a.shape[0]), min(_BLOCKS[0], a.shape[0]))
    cols = np.array_split(np.arange(a.shape[1]), min(_BLOCKS[1], a.shape[1]))
    return [[float(a[np.ix_(i, j)].mean()) for j in cols] for i in rows]


def _fingerprint(a) -> dict:
    a = np.asarray(a)
    if a.dtype.kind == "f":
        return {"kind": "float", "shape": list(a.shape), "mean": float(a.mean()), "std": float(a.std()),
                "quantiles": [float(x) for x in np.quantile(a, [0.0, 0.1, 0.5, 0.9, 1.0])], "blocks": _block_means(a)}
    values, counts = np.unique(a, return_counts=True)
    return {"kind": "int", "shape": list(a.shape), "values": [int(v) for v in values],
            "fractions": [float(c / a.size) for c in counts], "blocks": _block_means(a)}


def _differences(got: dict, want: dict) -> list:
    """What differs between two fingerprints beyond the tolerances (empty: the same site)."""
    if (got["kind"], got["shape"]) != (want["kind"], want["shape"]):
        return [f"kind/shape {got['kind']} {got['shape']} != {want['kind']} {want['shape']}"]
    if got["kind"] == "float":
        return [k for k in ("mean", "std", "quantiles", "blocks")
                if not np.allclose(got[k], want[k], rtol=1e-9, atol=1e-9)]
    g, w = dict(zip(got["values"], got["fractions"])), dict(zip(want["values"], want["fractions"]))
    moved = 0.5 * sum(abs(g.get(k, 0.0) - w.get(k, 0.0)) for k in set(g) | set(w))
    out = [f"{moved:.1e} of the cells changed value"] if moved > 2e-4 else []
    return out + (["blocks"] if not np.allclose(got["blocks"], want["blocks"], rtol=0, atol=0.05) else [])


def _site_fingerprints(site) -> dict:
    o = site.objects
    return {"dem": _fingerprint(site.dem), "texture": _fingerprint(site.texture),
            "catalogue": _fingerprint(site.catalogue.select_dtypes("number").to_numpy(float)),
            "planes": _fingerprint(o.planes), "crowns": _fingerprint(np.c_[o.ell_centre, o.ell_radii]),
            "canopy": _fingerprint(o.canopy_dm), "points": _fingerprint(o.points.select_dtypes("number").to_numpy(float))}


def test_the_named_steps_build_the_same_default_site_as_before(default):
    got = {"cover": _sha(default.cover), "level 6": _sha(default.texture_level(6)),
           "roads": _sha(np.array([r["xy"] for r in default.features["roads"]])),
           "buildings": _sha(default.features["buildings"])}
    assert got == DEFAULT_SITE_SHA
    fps = _site_fingerprints(default)
    bad = {k: _differences(fps[k], FINGERPRINTS[k]) for k in ("dem", "texture", "catalogue")}
    assert not any(bad.values()), bad


def test_the_fingerprint_sees_a_real_change(default):
    # the tolerances let the last bits go, not the site: a 1 mm lift of the DEM or one texel in 1 000 blacked out fails
    want = FINGERPRINTS["dem"]
    assert _differences(_fingerprint(default.dem + 0.001), want)
    t = default.texture.copy()
    t.ravel()[:: 1000] = 0
    assert _differences(_fingerprint(t), FINGERPRINTS["texture"])
    assert not _differences(_fingerprint(default.dem * (1 + 1e-14)), want)


def test_steps_by_hand_give_the_site_and_keep_their_contracts(small):
    from aerophoto.site import build as B

    b = B.Builder(SMALL)
    river = B.river_line(b)
    X = np.linspace(0.0, SMALL.width_m, 101)  # y0 in 0.36…0.42 of the height, meanders ±(0.09 + 0.03)
    assert np.all((river.y(X) >= 0.24 * SMALL.height_m) & (river.y(X) <= 0.54 * SMALL.height_m))
    dem = B.relief(b, river)
    assert dem.min() == SMALL.base_height_m and dem.max() == pytest.approx(SMALL.base_height_m + SMALL.relief_m)
    systems = B.fields(b, river)
    B.soil_noise(b)
    roads, corners, belts = B.field_network(b, river, systems)
    for p0, p1 in belts:  # belts keep to one side of the river
        assert np.sign(river.side(p0)) == np.sign(river.side(p1))
    forest_tex = B.shelter_belts(b, belts)
    village_c = B.highways(b, river, roads)
    assert sum(r["kind"] == "paved" for r in roads) == 5  # three legs of the main road, two of the second
    band = B.floodplain(b, river)
    B.forest(b, band, village_c, forest_tex)
    B.river_water(b, band)
    B.oxbow_lake(b, river, roads)
    B.paint_roads(b, roads)
    houses = B.village(b, river, village_c, roads)
    trees = B.isolated_trees(b)
    tex = B.texture(b, dem)
    levels = B.pyramid(tex)
    assert [lv.shape for lv in levels[:2]] == [(tex.shape[0] // 2, tex.shape[1] // 2),
                                               (tex.shape[0] // 4, tex.shape[1] // 4)]
    assert np.array_equal(dem, small.dem) and np.array_equal(tex, small.texture)
    assert np.array_equal(b.cv.cover, small.cover) and np.array_equal(trees, small.features["trees"])
    assert len(houses[0]) == len(small.features["buildings"])
    for k, lv in enumerate(levels, start=1):
        assert np.array_equal(lv, small.texture_level(k))


def test_cache_returns_the_same_site(small):
    assert S.get_site(SMALL) is small
    assert S.get_site(width_m=4000, height_m=3000, relief_m=80.0, base_height_m=150.0, seed=7) is small


def test_default_extent_and_guide_heights(default):
    assert default.extent_m == (0.0, 10000.0, 0.0, 5000.0)
    assert default.centre_m == (5000.0, 2500.0)
    assert default.texture.shape == (2500, 5000) and default.texture.dtype == np.uint8
    # guide §1-§2, variant 0: Z_min = 170 m, Z_max = 200 m
    assert default.z_min_m == 170.0 and default.z_max_m == pytest.approx(200.0, abs=1e-12)
    assert 170.0 < default.mean_height_m < 200.0


def test_relief_bounds_and_bilinear_height(small):
    assert small.z_min_m == 150.0 and small.z_max_m == pytest.approx(230.0, abs=1e-12)
    rng = np.random.default_rng(0)
    X = rng.uniform(-200, 4200, 5000)
    Y = rng.uniform(-200, 3200, 5000)
    Z = small.height(X, Y)
    assert Z.shape == (5000,)
    assert np.all((Z >= small.z_min_m - 1e-9) & (Z <= small.z_max_m + 1e-9))
    # nodes, midpoints and the hand formula of bilinear interpolation
    d, s = small.dem, small.dem_spacing_m
    assert small.height(30.0, 50.0) == pytest.approx(d[5, 3])
    assert small.height(35.0, 50.0) == pytest.approx((d[5, 3] + d[5, 4]) / 2)
    tx, ty = 0.3, 0.8
    expect = (d[5, 3] * (1 - tx) + d[5, 4] * tx) * (1 - ty) + (d[6, 3] * (1 - tx) + d[6, 4] * tx) * ty
    assert small.height(30.0 + tx * s, 50.0 + ty * s) == pytest.approx(expect, rel=1e-13)
    # broadcasting, and edge clamping outside the site
    assert small.height(np.array([[1.0], [2.0]]), np.array([3.0, 4.0, 5.0])).shape == (2, 3)
    assert small.height(-500.0, 1000.0) == pytest.approx(small.height(0.0, 1000.0))
    # hills in the north, the plain in the south is much flatter
    north = small.dem[-60:, :]
    south = small.dem[:40, :]
    assert np.ptp(north) > 3 * np.ptp(south)


def test_zero_relief_is_flat_at_base_height():
    flat = S.get_site(SMALL, relief_m=0.0, seed=7)
    assert flat.z_min_m == flat.z_max_m == 150.0
    assert np.all(flat.dem == 150.0)
    assert np.all(flat.height([0.0, 1234.5, 3999.0], [10.0, 2000.0, 2999.9]) == 150.0)
    assert np.all(flat.catalogue["Z_m"] == 150.0)
    assert flat.mean_height_m == 150.0


def test_photo_to_dem_works_with_a_site_directly(small):
    cam = g.Camera(100.0)
    pose = g.Pose(2000.0, 1500.0, 1400.0, alpha_deg=4.0, lambda_deg=30.0, kappa_deg=10.0)
    xy = np.array([[0.0, 0.0], [60.0, -40.0], [-80.0, 85.0]])
    P = g.photo_to_dem(cam, pose, xy, small)
    assert np.allclose(P[:, 2], small.height(P[:, 0], P[:, 1]), atol=1e-3)
    assert np.allclose(g.ground_to_photo(cam, pose, P), xy, atol=1e-6)


def test_catalogue_columns_and_kinds(small, default):
    for s in (small, default):
        cat = s.catalogue
        assert list(cat.columns) == ["id", "kind", "X_m", "Y_m", "Z_m", "control"]
        assert cat["id"].is_unique and cat["id"].min() == 1
        assert set(cat["kind"]) == set(S.KINDS)
        assert cat["control"].dtype == bool
        ctrl = cat[cat["control"]]
        assert len(ctrl) >= 4
        assert set(ctrl["kind"]) <= {"road crossing", "field corner"}
        assert np.allclose(cat["Z_m"], s.height(cat["X_m"], cat["Y_m"]), atol=1e-9)
        assert s.inside(cat["X_m"], cat["Y_m"]).all()
    counts = default.catalogue["kind"].value_counts()
    assert counts["road crossing"] >= 5 and counts["field corner"] >= 30 and counts["tree"] >= 20


def _dist_to_segment(p, a, b):
    d = b - a
    u = np.clip(np.dot(p - a, d) / np.dot(d, d), 0, 1)
    return float(np.hypot(*(p - a - u * d)))


def test_road_crossings_lie_where_roads_cross_in_the_texture(default):
    cat = default.catalogue
    roads = default.features["roads"]
    for _, r in cat[cat["kind"] == "road crossing"].iterrows():
        p = np.array([r["X_m"], r["Y_m"]])
        on = [k for k, rd in enumerate(roads) if _dist_to_segment(p, *rd["xy"]) < 1e-6]
        assert len(on) >= 2  # the intersection of (at least) two road centre lines
        assert default.cover_at(p[0], p[1]) in ROAD
        # 10 m away along each road the texture still shows road
        for k in on[:2]:
            a, b = roads[k]["xy"]
            d = (b - a) / np.hypot(*(b - a))
            for sgn in (-1, 1):
                q = p + sgn * 10 * d
                if default.inside(*q):
                    assert default.cover_at(*q) in ROAD
    # a paved road is darker than the fields beside it
    paved = [rd for rd in roads if rd["kind"] == "paved"][0]["xy"]
    mid = paved.mean(axis=0)
    d = (paved[1] - paved[0]) / np.hypot(*(paved[1] - paved[0]))
    nrm = np.array([-d[1], d[0]])
    assert default.sample(*mid) < 0.45
    assert default.cover_at(*(mid + 30 * nrm)) not in ROAD


def test_other_points_match_their_texture(default):
    cat = default.catalogue
    t = default.params.texture_m
    trees = cat[cat["kind"] == "tree"]
    assert (default.cover_at(trees["X_m"], trees["Y_m"]) == S.COVER_CODES["tree"]).all()
    # a tree is a dark crown: darker than the ground around it (12 m away, off its shadow to the north-east)
    ring = [default.sample(trees["X_m"] + 12 * np.cos(a), trees["Y_m"] + 12 * np.sin(a))
            for a in np.radians([90, 135, 180, 225, 270, 315, 0])]
    assert (default.sample(trees["X_m"], trees["Y_m"]) < np.mean(ring, axis=0) - 0.05).all()
    corners = cat[cat["kind"] == "field corner"]
    cc = default.cover_at(corners["X_m"], corners["Y_m"])
    assert np.isin(cc, [S.COVER_CODES["arable field"], S.COVER_CODES["field boundary"]]).all()
    b = cat[cat["kind"] == "building corner"]
    inward = default.cover_at(b["X_m"] + 1.2 * t, b["Y_m"] + 1.2 * t)
    assert (inward == S.COVER_CODES["building"]).all()
    # every building corner is a corner of a roof in the vector data
    roofs = default.features["buildings"].reshape(-1, 2)
    for x, y in b[["X_m", "Y_m"]].to_numpy():
        assert np.min(np.hypot(roofs[:, 0] - x, roofs[:, 1] - y)) < 1e-9


def test_texture_has_the_land_covers(default):
    share = np.bincount(default.cover.ravel(), minlength=len(S.COVER)) / default.cover.size
    assert share[S.COVER_CODES["arable field"]] > 0.3
    for name in ("forest", "water", "meadow", "dirt road", "paved road", "building", "garden", "sand bank"):
        assert share[S.COVER_CODES[name]] > 0, name
    # water is dark, sand banks and roofs bright
    tex = default.texture
    assert np.median(tex[default.cover == S.COVER_CODES["water"]]) < 60
    assert np.median(tex[default.cover == S.COVER_CODES["building"]]) > 150
    assert np.median(tex[default.cover == S.COVER_CODES["forest"]]) < np.median(tex[default.cover == S.COVER_CODES["arable field"]])


def test_sample_and_pyramid(small):
    t = small.params.texture_m
    r, c = 123, 456
    # at a pixel centre bilinear sampling returns that pixel
    assert small.sample((c + 0.5) * t, (r + 0.5) * t) == pytest.approx(small.texture[r, c] / 255.0, abs=1e-6)
    mid = small.sample((c + 1.0) * t, (r + 0.5) * t)
    assert mid == pytest.approx((int(small.texture[r, c]) + int(small.texture[r, c + 1])) / 510.0, abs=1e-6)
    assert np.isnan(small.sample(-1.0, 10.0))
    assert small.sample(-1.0, 10.0, outside=0.25) == pytest.approx(0.25)
    one = small.texture_level(1)
    blk = small.texture[2 * 10:2 * 10 + 2, 2 * 20:2 * 20 + 2].astype(int)
    assert one[10, 20] == (blk.sum() + 2) // 4
    assert small.texel_m(2) == 4 * t
    assert small.level_for(t * 0.5) == 0 and small.level_for(t * 2.5) == 1 and small.level_for(t * 4) == 2
    with pytest.raises(ValueError, match="level"):
        small.texture_level(99)


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(width_m=500), "width_m"),
        (dict(height_m=2e5), "height_m"),
        (dict(relief_m=-1), "relief_m"),
        (dict(seed=-3), "seed"),
        (dict(texture_m=0.1), "texture_m"),
        (dict(width_m=100000, height_m=100000, texture_m=2), "texture_m"),
        (dict(dem_spacing_m=0), "dem_spacing_m"),
    ],
)
def test_bad_parameters(kwargs, name):
    with pytest.raises(ValueError, match=name):
        S.SiteParams(**kwargs)


def test_get_site_rejects_unknown_names():
    with pytest.raises(ValueError, match="colour"):
        S.get_site(colour=True)


def test_import_builds_nothing():
    code = (
        "import aerophoto.site as s, aerophoto.render, aerophoto.simulate;"
        "assert s._cached.cache_info().currsize == 0 and s._cached.cache_info().misses == 0;"
        "print('ok')"
    )
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert out.returncode == 0, out.stderr
    assert out.stdout.strip() == "ok"


def test_plot_uses_the_guides_symbols(small):
    from aerophoto.demos.site_views import plot_site

    art = plot_site(small, labels=True)
    ctrl = small.catalogue[small.catalogue["control"]]
    assert art["points"]["control"].get_marker() == "^"
    assert art["points"]["other"].get_marker() == "o"
    assert np.allclose(art["points"]["control"].get_xdata(), ctrl["X_m"])
    assert len(art["points"]["labels"]) == len(ctrl)
    assert art["image"].get_array().shape[1] <= 2000


# --------------------------------------------------------------------------- objects with height
def _objects_sha(o) -> dict:
    return {"planes": _sha(o.planes), "crowns": _sha(np.c_[o.ell_centre, o.ell_radii]), "canopy": _sha(o.canopy_dm),
            "points": hashlib.sha256(o.points.to_csv(float_format="%.12g").encode()).hexdigest()[:16]}


def test_objects_are_deterministic_and_leave_the_ground_alone(small, default):
    again = S.build_site(SMALL)
    assert _objects_sha(again.objects) == _objects_sha(small.objects)
    # the painting steps drew exactly what they drew before objects existed (pinned above for the default site)
    assert np.array_equal(again.texture, small.texture) and again.catalogue.equals(small.catalogue)
    o = default.objects
    kinds = o.table()["kind"].value_counts()
    assert kinds["house"] == len(default.features["buildings"])  # a box on every painted roof
    assert kinds["tree"] == len(default.features["trees"])  # a crown on every single tree
    for k in ("chimney", "mast", "water tower", "bridge", "embankment", "garden tree"):
        assert kinds[k] >= 1, k
    h = o.table().groupby("kind")["height_m"]
    assert h.min()["house"] > 2.5 and h.max()["house"] < 9.0
    assert 10.0 <= h.min()["tree"] and h.max()["tree"] <= 20.0
    assert h.max()["mast"] == pytest.approx(64.0) and h.max()["chimney"] == pytest.approx(42.0)
    assert 3.0 < h.max()["embankment"] < 6.0
    assert 0.08 < np.mean(o.canopy_dm > 0) < 0.2 and 14.0 * 0.78 <= o.canopy_max_m <= 24.0
    # the canopy stands exactly on the forest land cover
    assert np.array_equal(o.canopy_dm > 0, default.cover == S.COVER_CODES["forest"])
    bad = {k: _differences(v, FINGERPRINTS[k]) for k, v in _site_fingerprints(default).items()
           if k in ("planes", "crowns", "canopy", "points")}
    assert not any(bad.values()), bad


def test_surface_height_is_the_top_of_everything(default):
    o = default.objects
    rng = np.random.default_rng(2)
    X, Y = rng.uniform(0, 10000, 20000), rng.uniform(0, 5000, 20000)
    Z, Zs = default.height(X, Y), default.surface_height(X, Y)
    assert np.all(Zs >= Z) and Zs.shape == X.shape
    bare = Zs == Z
    assert bare.mean() > 0.8  # most of the site is open ground
    # the forest: ground + canopy of the texel
    f = o.canopy_at(X, Y) > 0
    k, i = o.candidates_at(X, Y)
    free = f & ~np.isin(np.arange(len(X)), i)
    assert np.allclose(Zs[free], Z[free] + o.canopy_at(X[free], Y[free]))
    # the tops: each object point lies on the surface, nothing above it (a tree top is its crown's apex)
    pts = default.object_points
    P = pts[["X_m", "Y_m", "Z_m"]].to_numpy()
    top = pts["kind"].isin(["tree top", "chimney top", "mast top", "tower top", "ridge end"]).to_numpy()
    # (a ridge end sits on the gable wall's edge: look 1 cm inside, towards the house's centre)
    c = o.centre_m[pts["object"].to_numpy()]
    d = c - P[:, :2]
    n = np.hypot(*d.T)
    Q = P[:, :2] + np.where(n[:, None] > 0.01, d / np.maximum(n, 1e-9)[:, None] * 0.01, 0.0)
    assert np.allclose(default.surface_height(Q[top, 0], Q[top, 1]), P[top, 2], atol=0.01)
    # a flat roof's inside is at its eaves; the ground beside a house is bare
    assert default.surface_z_max_m == pytest.approx(o.z_max_m)
    fc = default.catalogue[default.catalogue["kind"] == "field corner"][["X_m", "Y_m"]].to_numpy()
    assert np.array_equal(default.height(fc[:, 0], fc[:, 1]), default.surface_height(fc[:, 0], fc[:, 1]))


def test_object_points_are_appended_after_the_catalogue(default):
    cat, obj, allp = default.catalogue, default.object_points, default.all_points
    assert list(obj.columns) == ["id", "kind", "X_m", "Y_m", "Z_m", "control", "object", "ground_Z_m", "height_m"]
    assert obj["id"].min() == cat["id"].max() + 1 and obj["id"].is_unique and not obj["control"].any()
    assert list(dict.fromkeys(obj["kind"])) == [k for k in S.POINT_KINDS if k in set(obj["kind"])]
    assert np.allclose(obj["ground_Z_m"], default.height(obj["X_m"], obj["Y_m"]))
    assert np.allclose(obj["height_m"], obj["Z_m"] - obj["ground_Z_m"]) and (obj["height_m"] > 2.5).all()
    counts = obj["kind"].value_counts()
    assert counts["roof corner"] == 4 * len(default.features["buildings"])
    assert counts["tree top"] == len(default.features["trees"]) and counts["mast top"] == 1
    # every roof corner is a corner of its painted roof, raised to the eaves
    roofs = default.features["buildings"].reshape(-1, 2)
    rc = obj[obj["kind"] == "roof corner"][["X_m", "Y_m"]].to_numpy()
    assert max(np.min(np.hypot(*(roofs - p).T)) for p in rc) < 1e-6
    # all points: the catalogue's rows unchanged and first, the object points after them
    assert allp.iloc[:len(cat)][list(cat.columns)].equals(cat)
    assert (allp.iloc[:len(cat)]["object"] == -1).all() and (allp.iloc[:len(cat)]["height_m"] == 0).all()
    assert list(allp["id"]) == list(cat["id"]) + list(obj["id"])


def test_objects_step_by_hand(small):
    from aerophoto.site import build as B
    from aerophoto.site.objects import build_objects

    b = B.Builder(SMALL)
    river = B.river_line(b)
    dem = B.relief(b, river)
    systems = B.fields(b, river)
    B.soil_noise(b)
    roads, corners, belts = B.field_network(b, river, systems)
    forest_tex = B.shelter_belts(b, belts)
    village_c = B.highways(b, river, roads)
    band = B.floodplain(b, river)
    B.forest(b, band, village_c, forest_tex)
    B.river_water(b, band)
    B.oxbow_lake(b, river, roads)
    B.paint_roads(b, roads)
    houses = B.village(b, river, village_c, roads)
    trees = B.isolated_trees(b)
    # the painting steps leave what the objects need on the builder
    assert b.houses[0] is houses[0] and len(b.house_roof_tone) == len(houses[0])
    assert np.array_equal(b.tree_crowns[0], trees) and len(b.garden_crowns[1]) == len(b.garden_crowns[0])
    tex = B.texture(b, dem)
    o = build_objects(b, dem, river, roads, village_c, tex, b.cv.cover, first_id=1000)
    assert _objects_sha(o) == {**_objects_sha(small.objects), "points": _objects_sha(o)["points"]}
    assert o.points["id"].min() == 1000
