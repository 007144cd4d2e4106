"""The single-strip fotoschema (guide §6): plane geometry, seams, mean scale, the sheet and its export."""

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aerophoto import geometry as g
from aerophoto import mosaic as mo
from aerophoto import simulate as sim
from aerophoto.terrain import RescaledRelief


# --------------------------------------------------------------------------- plane geometry
@settings(max_examples=40, deadline=None)
@given(th=st.floats(-180, 180), tx=st.floats(-500, 500), ty=st.floats(-500, 500), s=st.floats(0.5, 2.0))
def test_similarity_fit_recovers_a_known_motion(th, tx, ty, s):
    T = mo.Similarity2D.from_angle(th, (tx, ty), s)
    P = np.array([[0.0, 0.0], [100.0, 10.0], [-40.0, 80.0], [25.0, -60.0]])
    fit = mo.fit_similarity(P, T.apply(P), scale=True)
    assert np.allclose(fit.apply(P), T.apply(P), atol=1e-8)
    assert fit.scale == pytest.approx(s)
    rigid = mo.fit_similarity(P, mo.Similarity2D.from_angle(th, (tx, ty)).apply(P))
    assert rigid.scale == pytest.approx(1.0)
    # composition and inverse
    assert np.allclose(T.compose(T.inverse()).apply(P), P, atol=1e-8)
    assert np.allclose(T.inverse().compose(T).matrix(), np.eye(3), atol=1e-9)


def test_rigid_fit_to_two_points_splits_the_misfit_equally():
    # two prints at slightly different scales: a rigid motion cannot make both points coincide
    src = np.array([[0.0, 70.0], [0.0, -70.0]])
    dst = np.array([[5.0, 71.0], [5.0, -71.0]])  # 2 mm longer between a and b
    T = mo.fit_similarity(src, dst)
    r = np.hypot(*(T.apply(src) - dst).T)
    assert r == pytest.approx([1.0, 1.0])  # 1 mm left at each point: shared equally
    assert T.rotation_deg == pytest.approx(0.0, abs=1e-12)


def test_fit_rejects_bad_input():
    with pytest.raises(ValueError, match="at least 2"):
        mo.fit_similarity([[0, 0]], [[1, 1]])
    with pytest.raises(ValueError, match="coincide"):
        mo.fit_similarity([[1, 1], [1, 1]], [[0, 0], [2, 2]])


@pytest.mark.parametrize("shape", mo.CUT_SHAPES)
def test_cut_lines_pass_through_a_and_are_monotone(shape):
    a, b = np.array([30.0, 70.0]), np.array([34.0, -70.0])
    cut = mo.cut_line(a, b, (-95.0, 95.0), shape=shape, amplitude_mm=3.0, period_mm=30.0)
    assert np.all(np.diff(cut[:, 1]) > 0)
    assert cut[0, 1] == -95.0 and cut[-1, 1] == 95.0
    x_at_a = np.interp(a[1], cut[:, 1], cut[:, 0])
    assert x_at_a == pytest.approx(a[0], abs=1e-9)
    straight = a[0] + (a[0] - b[0]) / (a[1] - b[1]) * (cut[:, 1] - a[1])
    dev = cut[:, 0] - straight
    if shape == "straight":
        assert np.allclose(dev, 0.0)
        assert np.interp(b[1], cut[:, 1], cut[:, 0]) == pytest.approx(b[0])
    else:
        assert np.max(np.abs(dev)) == pytest.approx(3.0, abs=0.02)


def test_cut_line_rejects_bad_input():
    with pytest.raises(ValueError, match="shape"):
        mo.cut_line([0, 1], [0, -1], (-5, 5), shape="wavy")
    with pytest.raises(ValueError, match="y_range"):
        mo.cut_line([0, 1], [0, -1], (5, -5))


def test_working_areas_are_counted_from_the_cuts():
    cuts = [np.array([[10.0, -100.0], [10.0, 100.0]]), np.array([[50.0, -100.0], [60.0, 100.0]])]
    idx = mo.assign_working_areas([[0.0, 0.0], [20.0, 0.0], [54.0, -10.0], [56.0, 0.0], [100.0, 0.0]], cuts)
    assert list(idx) == [0, 1, 1, 2, 2]


def test_rms_partial_scales_and_signs():
    # m = √(ΣΔI²/n), guide §6 formula (6.2)
    assert mo.seam_rms([0.3, -0.4]) == pytest.approx(math.sqrt((0.09 + 0.16) / 2))
    assert mo.seam_rms([0.2, -0.2, 0.2, -0.2]) == pytest.approx(0.2)
    with pytest.raises(ValueError, match="dI_mm"):
        mo.seam_rms([])
    # formula (6.1): 1/m_i = l_i/(L_i·M): l = 100 mm on the mosaic, L = 130 mm on the 1:10 000 plan → 1:13 000
    assert mo.partial_scales([100.0, 50.0], [130.0, 60.0], 10000) == pytest.approx([13000.0, 12000.0])
    with pytest.raises(ValueError, match="l_mm"):
        mo.partial_scales([0.0], [1.0])
    assert list(mo.classify_mismatch([-0.3, 0.0, 0.2])) == ["cut-out", "match", "duplicate"]


def test_partial_scales_are_the_base_scales_of_guide_5_1():
    # one formula m = L·M/l: the fotoschema's (mosaic, plan) order is displacement.base_scale's (plan, photo)
    from aerophoto import displacement

    l, L = np.array([348.2, 333.4, 358.5, 362.2]), np.array([415.5, 405.0, 432.6, 435.4])
    assert np.array_equal(mo.partial_scales(l, L, 10000), displacement.base_scale(L, l, 10000))
    with pytest.raises(ValueError, match="L_mm"):
        mo.partial_scales([1.0, 2.0], [1.0, -2.0])
    with pytest.raises(ValueError, match="match"):
        mo.partial_scales([1.0, 2.0], [1.0])


# --------------------------------------------------------------------------- the fotoschema of a strip
@pytest.mark.parametrize("f_mm, m", [(100.0, 12000.0), (140.0, 12500.0), (200.0, 9000.0)])
def test_flat_ground_and_vertical_photos_give_a_clean_mosaic_at_scale_f_over_H(f_mm, m):
    cam = g.Camera(f_mm)
    strip = sim.fly_strip(cam, m, 60, 5, ground_Z_m=150.0)
    fs = mo.assemble(strip, g.FlatTerrain(150.0))
    assert fs.dI_mm.size >= 4 * 5
    assert np.max(np.abs(fs.dI_mm)) <= 0.05
    H = f_mm / 1000 * m
    assert fs.scale.m == pytest.approx(H / (f_mm / 1000), rel=0.005)  # 1/m = f/H
    assert np.allclose(fs.scale.m_i, m, rtol=1e-9)
    assert fs.ok and fs.rms_mm <= 0.05
    # the principal points lie along +x one photo base apart
    o = fs.principal_points_mm()
    assert np.allclose(o[:, 1], 0.0, atol=1e-9)
    assert np.allclose(np.diff(o[:, 0]), 180 * 0.4, atol=1e-9)


def test_a_print_moved_along_the_strip_makes_a_duplicate_and_back_a_cut_out():
    cam = g.Camera(100)
    strip = sim.fly_strip(cam, 12000, 60, 2)
    fs = mo.assemble(strip)
    s = fs.seams[0]
    flat = g.FlatTerrain(0.0)
    for shift, expected in ((+1.0, +1.0), (-0.5, -0.5)):
        moved = mo.Similarity2D(1, 0, shift, 0).compose(fs.to_sheet[1])  # right print moved by `shift` mm
        dI, _, _ = mo.seam_mismatches(cam, fs.poses[0], fs.poses[1], fs.to_sheet[0], moved, s.points_mm, flat,
                                      fs.strip_direction, fs.m_design)
        assert dI == pytest.approx(np.full(len(dI), expected), abs=1e-9)
    assert list(mo.classify_mismatch([1.0, -0.5])) == ["duplicate", "cut-out"]


class Valley:
    """A valley along the strip (axis Y = 0): ground rising to a plateau 120 m up at |Y| ≥ 800 m."""

    z_min_m, z_max_m = 0.0, 120.0

    def height(self, X, Y):
        Y = np.asarray(Y, float)
        return 120.0 * np.minimum(1.0, (Y / 800.0) ** 2) + 0.0 * np.asarray(X, float)


def test_matching_on_high_ground_leaves_duplicates_not_cut_outs():
    # guide §6, step 2: tie points on high ground avoid cut-outs; lower ground along the cut is duplicated
    cam = g.Camera(100)
    strip = sim.fly_strip(cam, 12000, 60, 4, ground_Z_m=40.0)
    fs = mo.assemble(strip, Valley())
    for s in fs.seams:
        assert s.ties.ground_m[:, 2].min() > 60.0  # both ties found high up the valley sides
    assert fs.dI_mm.min() > -0.01
    assert fs.dI_mm.max() > 0.3
    # the same valley matched on its floor instead (ties forced low) gives cut-outs
    low = mo.assemble(strip, Valley(), tie_margin_mm=(80.0, 85.0))
    assert low.dI_mm.min() < -0.3


def _relief_ground(relief_m):
    from aerophoto import site

    return RescaledRelief(site.get_site(), relief_m)


def test_rescaled_relief_keeps_shape_and_bounds():
    gr = _relief_ground(90.0)
    s = gr.site
    assert gr.z_min_m == pytest.approx(s.z_min_m)
    assert gr.z_max_m == pytest.approx(s.z_min_m + 90.0)
    X = np.array([100.0, 2500.0, 7000.0])
    Y = np.array([300.0, 2500.0, 4000.0])
    k = 90.0 / (s.z_max_m - s.z_min_m)
    assert np.allclose(gr.height(X, Y) - s.z_min_m, k * (s.height(X, Y) - s.z_min_m))
    assert gr.dem.max() == pytest.approx(gr.z_max_m)
    assert np.allclose(gr.points_m()[:, :2], s.catalogue[["X_m", "Y_m"]].to_numpy())
    with pytest.raises(ValueError, match="relief_m"):
        RescaledRelief(s, -1.0)


def _fotoschema(relief_m=30.0, tilt=0.0, seed=1, f_mm=100.0):
    gr = _relief_ground(relief_m)
    strip = sim.strip_over_site(gr, g.Camera(f_mm), 12000, 60, 5,
                                imperfections=sim.Imperfections(max_tilt_deg=tilt, seed=seed))
    return mo.assemble(strip, gr, points_m=mo.catalogue_points(gr)), gr


def test_mismatches_grow_with_relief():
    rms = [_fotoschema(relief_m=h)[0].rms_mm for h in (0.0, 25.0, 50.0, 100.0, 150.0)]
    assert rms[0] <= 0.05
    assert all(b > a for a, b in zip(rms, rms[1:])), rms
    assert rms[-1] > 0.3


def test_mismatches_grow_with_tilt():
    rms = [_fotoschema(relief_m=0.0, tilt=t)[0].rms_mm for t in (0.0, 1.0, 2.0, 4.0)]
    assert all(b > a for a, b in zip(rms, rms[1:])), rms
    assert rms[0] <= 0.05


def test_longer_focal_length_shrinks_relief_mismatches():
    # same scale, higher flight: relief displacement r·h/H shrinks
    a = _fotoschema(relief_m=100.0, f_mm=100.0)[0].rms_mm
    b = _fotoschema(relief_m=100.0, f_mm=300.0)[0].rms_mm
    assert b < a / 2


def test_mean_scale_uses_catalogue_points_in_the_end_working_areas():
    fs, gr = _fotoschema(relief_m=30.0, tilt=1.0)
    sc = fs.scale
    cat = gr.points_m()
    for P in sc.ground_m:  # every scale point is a catalogue point
        assert np.min(np.linalg.norm(cat - P, axis=1)) < 1e-6
    idx = fs.photo_index(sc.sheet_mm)
    assert list(idx) == [0, 0, 4, 4]
    assert sc.l_mm == pytest.approx(np.hypot(*(sc.sheet_mm[[2, 3, 3, 2]] - sc.sheet_mm[[0, 1, 0, 1]]).T))
    assert sc.m_i == pytest.approx(sc.L_mm * 10000 / sc.l_mm)
    assert abs(sc.m / 12000 - 1) < 0.02  # tilted photos over gentle relief: close to the design scale
    assert sc.m_rounded % 100 == 0
    t = sc.table()
    assert len(t) == 4 and list(t.columns)[:3] == ["l on mosaic, mm", "L on plan, mm", "m_i = L·M/l"]


def test_fotoschema_is_deterministic():
    a, _ = _fotoschema(relief_m=80.0, tilt=2.0, seed=4)
    b, _ = _fotoschema(relief_m=80.0, tilt=2.0, seed=4)
    assert np.array_equal(a.dI_mm, b.dI_mm)
    assert a.table().equals(b.table())
    assert a.scale.m == b.scale.m
    c, _ = _fotoschema(relief_m=80.0, tilt=2.0, seed=5)
    assert not np.array_equal(a.dI_mm, c.dI_mm)


def test_tables_and_verdict():
    fs, _ = _fotoschema(relief_m=150.0)
    t = fs.table()
    assert len(t) == fs.dI_mm.size
    assert set(t["kind"]) <= {"cut-out (вырез)", "duplicate (дублет)", "match"}
    st_ = fs.seams_table()
    assert list(st_.index)[-1] == "all"
    assert st_.loc["all", "m, mm"] == pytest.approx(round(fs.rms_mm, 2))
    assert fs.ok == (round(fs.dI_mm.min(), 2) >= -0.5)


def test_assemble_rejects_bad_input():
    cam = g.Camera(100)
    with pytest.raises(ValueError, match="at least 2"):
        mo.assemble(sim.fly_strip(cam, 12000, 60, 1))
    with pytest.raises(ValueError, match="cut_shape"):
        mo.assemble(sim.fly_strip(cam, 12000, 60, 3), cut_shape="wavy")


# --------------------------------------------------------------------------- the sheet raster
def test_sheet_raster_of_flat_ground_shows_the_ground_pattern_seamlessly():
    cam = g.Camera(100)
    strip = sim.fly_strip(cam, 12000, 60, 3)
    fs = mo.assemble(strip)
    img, ext = mo.sheet_raster(fs, None, 1.0)
    assert img.shape == (int(math.ceil(ext[3] - ext[2])), int(math.ceil(ext[1] - ext[0])))
    # each pixel equals the ground pattern at the pixel's true ground point (flat, vertical: sheet = scaled ground)
    ys, xs = np.mgrid[0:img.shape[0], 0:img.shape[1]]
    P = np.column_stack([ext[0] + xs.ravel() + 0.5, ext[2] + ys.ravel() + 0.5])
    G = g.photo_to_plane(cam, strip[0].pose, fs.to_sheet[0].inverse().apply(P), 0.0)
    inside = np.abs(P[:, 1]) < 85
    same = np.isclose(img.ravel()[inside], mo._pattern(G[inside, 0], G[inside, 1]))
    assert same.mean() > 0.995  # (a few pixels on pattern edges differ by rounding)
    with pytest.raises(ValueError, match="px_per_mm"):
        mo.sheet_raster(fs, None, 0.0)


def test_sheet_raster_from_rendered_prints_matches_direct_sampling():
    from aerophoto import render

    fs, gr = _fotoschema(relief_m=30.0)
    strip = sim.strip_over_site(gr, g.Camera(100), 12000, 60, 5, imperfections=sim.Imperfections(seed=1))
    prints = render.render_strip(gr, strip, 256, vignetting=0.0, fiducials=False)
    a, _ = mo.sheet_raster(fs, gr, 0.5, photos=prints)
    b, _ = mo.sheet_raster(fs, gr, 0.5)
    both = (a < 1.0) & (b < 1.0)
    assert both.mean() > 0.7
    assert np.median(np.abs(a[both] - b[both])) < 0.05
    with pytest.raises(ValueError, match="photos"):
        mo.sheet_raster(fs, gr, 0.5, photos=prints[:2])


def test_sheet_raster_in_bands_fills_the_same_image_a_band_at_a_time():
    fs, gr = _fotoschema(relief_m=30.0)
    whole, ext = mo.sheet_raster(fs, gr, 1.0)
    steps = list(mo.sheet_raster_bands(fs, gr, 1.0, band_px=3_000))
    ny, nx = whole.shape
    rows = [done for _img, _ext, done in steps]
    assert rows == sorted(rows) and rows[-1] == ny and len(steps) == math.ceil(ny / (3_000 // nx))
    img = steps[-1][0]
    assert all(s[0] is img for s in steps) and steps[-1][1] == ext  # one array, filled in place
    assert np.abs(img - whole).max() < 1e-3
    # a band of one row when band_px is below a row's width; nonsense is refused by name
    assert sum(1 for _ in mo.sheet_raster_bands(fs, gr, 0.2, band_px=1)) == \
        int(math.ceil((fs.extent_mm[3] - fs.extent_mm[2]) * 0.2))
    with pytest.raises(ValueError, match="band_px = 0"):
        next(mo.sheet_raster_bands(fs, gr, 1.0, band_px=0))



def test_a_preview_glued_on_a_lattice_puts_every_ground_point_within_a_fraction_of_a_pixel():
    """lattice_px (the fotoschema's preview): rays cut every few pixels and interpolated between.  On the slider's
    steepest setting (200 m of relief, 5° of tilt, f = 70 mm at 1:12 000) every sheet pixel's ground point lies
    within 0.15 px of its exact cut at the demo's step of 6 px, and the glued picture is the exact one but for a
    few pixels on the texture's sharpest edges."""
    from aerophoto.demos.fotoschema import PREVIEW_LATTICE_PX

    fs, gr = _fotoschema(relief_m=200.0, tilt=5.0, f_mm=70.0)
    r = 1.0  # the preview's px/mm
    xs = np.arange(-85.0, 85.0, 1.0 / r) + 0.5 / r  # a photo's pixel centres, mm (sheet ≈ photo scale)
    xy = np.stack(np.meshgrid(xs, xs), -1).reshape(-1, 2)
    dem = g.as_terrain(gr)
    worst = {}
    for step in (3, PREVIEW_LATTICE_PX, 12):
        e = []
        for pose in fs.poses:
            a = g.photo_to_dem(fs.camera, pose, xy, dem, lattice_mm=step / r)
            b = g.photo_to_dem(fs.camera, pose, xy, dem)
            e.append(np.hypot(*(a - b)[:, :2].T).max() / (fs.m_design / 1000.0) * r)  # ground m → sheet px
        worst[step] = max(e)
    assert worst[3] < worst[PREVIEW_LATTICE_PX] < 0.15 < worst[12], worst
    exact, ext = mo.sheet_raster(fs, gr, r)
    quick, ext2 = mo.sheet_raster(fs, gr, r, lattice_px=PREVIEW_LATTICE_PX)
    assert ext2 == ext and quick.shape == exact.shape
    d = np.abs(quick - exact)
    assert 0 < d.max() and np.mean(d > 0.02) < 0.01  # the same picture: under 1 % of pixels off by 2 % of grey
    with pytest.raises(ValueError, match="lattice_px"):
        mo.sheet_raster(fs, gr, r, lattice_px=1)


def test_sheet_raster_gives_each_pixel_to_its_working_area_and_photo():
    """The raster finds a row's cut positions once (not once a pixel): the same photo for every pixel as
    Fotoschema.photo_index at the pixel's centre, and background outside that photo's frame."""
    from aerophoto.demos.fotoschema import fotoschema_model

    class Flat:  # a "print" that reads its own index everywhere
        def __init__(self, i):
            self.i = i

        def value_at(self, xy):
            return np.full(len(xy), float(self.i))

    for shape in ("straight", "zigzag"):
        fs = fotoschema_model(alpha_max_deg=3.0, relief_m=120.0, cut_shape=shape, px_per_mm=0.1).fs
        img, (x0, x1, y0, y1) = mo.sheet_raster(fs, None, 0.7, photos=[Flat(i) for i in range(len(fs.poses))],
                                                background=-1.0)
        ny, nx = img.shape
        X, Y = np.meshgrid(x0 + (np.arange(nx) + 0.5) / 0.7, y0 + (np.arange(ny) + 0.5) / 0.7)
        P = np.stack([X, Y], axis=-1)
        want = fs.photo_index(P).astype(float)
        on_photo = np.stack([T.inverse().apply(P) for T in fs.to_sheet])  # (photo, ny, nx, 2), photo mm
        own = np.take_along_axis(on_photo, want.astype(int)[None, ..., None], 0)[0]
        want[np.any(np.abs(own) > fs.camera.half_mm, axis=-1)] = -1.0
        assert np.array_equal(img, want.astype(np.float32)), shape
        assert set(np.unique(img)) == {-1.0, *map(float, range(len(fs.poses)))}


# --------------------------------------------------------------------------- the live demo and the sheet
def test_demo_renders_full_resolution_from_code_and_preview_on_request():
    from aerophoto.demos.fotoschema import FotoschemaDemo

    d = FotoschemaDemo()
    assert not d.result.preview and d.result.px_per_mm == d.full_px_per_mm
    full_shape = d.result.image.shape
    d.set(preview=True, relief_m=80.0, alpha_max_deg=2.0)
    assert d.result.preview and d.result.px_per_mm == d.preview_px_per_mm
    assert d.result.image.shape[1] < full_shape[1] / 2
    # the artists follow the result
    fs = d.result.fs
    assert d.view.points.get_offsets().shape == (fs.dI_mm.size, 2)
    assert np.allclose(d.view.tops.get_offsets()[:, 1], fs.dI_mm)
    preview_title = d.view.title.get_text()
    assert d.view.image.get_array().shape == d.result.image.shape
    d.set(relief_m=80.0)
    # the resolution is never in the title (issue 33: calm while sliding): the same title for both pictures
    assert not d.result.preview and d.view.title.get_text() == preview_title
    assert "preview" not in preview_title and "resolution" not in preview_title
    assert "Mismatches by cut" in d.table.value
    with pytest.raises(ValueError, match="relief_m"):
        d.set(relief_m=500)
    # the whole widget: grouped sliders (and the cut dropdown) with a Reset
    w = d.widget()
    ctl = d.controls()
    assert set(ctl) == {p.name for p in d.params}
    assert ctl["relief_m"].max == 200 and ctl["cut_shape"].value == "straight"
    assert w is d.widget()
    d.reset()
    assert d.values["relief_m"] == 30 and not d.result.preview
    d.close()


def test_demo_sliders_preview_while_moving_and_render_full_when_still():
    import asyncio

    from aerophoto.demos.fotoschema import FotoschemaDemo, fotoschema_model
    from aerophoto.widgets import TABLE_DELAY_S

    d = FotoschemaDemo()
    d.settle_s = 0.15  # longer than the status line's delay (TABLE_DELAY_S), as the demo's own 0.35 s
    ctl = d.controls()
    seen = []

    async def until_full(timeout_s=20.0):
        t0 = asyncio.get_running_loop().time()
        while d.result.preview or d._later is not None:
            assert asyncio.get_running_loop().time() - t0 < timeout_s, "the full render never came"
            await asyncio.sleep(0.01)

    async def drive():
        ctl["relief_m"].value = 60.0
        seen.append(d.result.preview)
        ctl["relief_m"].value = 65.0  # a second event restarts the settle timer
        seen.append(d.result.preview)
        seen.append(d._later is not None)
        await asyncio.sleep(TABLE_DELAY_S + 0.02)  # the status line follows the picture
        seen.append("aerophoto-pending" in d.status.value)  # and says a full picture is coming
        await until_full()
        seen.append(d.result.preview)
        seen.append(d._later is None)
        await asyncio.sleep(TABLE_DELAY_S + 0.02)  # the status line follows the picture
        seen.append(d.status.value)  # and clears when it came

    n0 = d.n_updates
    asyncio.run(drive())
    assert seen == [True, True, True, True, False, True, ""]
    assert d.n_updates - n0 == 3  # two previews, one full render
    assert d.values["relief_m"] == 65.0
    # the banded full render is the full-resolution model, pixel for pixel (to the ray tolerance)
    ref = fotoschema_model(**{k: d.values[k] for k in ("f_mm", "m", "alpha_max_deg", "relief_m", "px_percent",
                                                       "cut_shape", "seed")}, px_per_mm=d.full_px_per_mm)
    assert d.result.image.shape == ref.image.shape and d.result.extent_mm == ref.extent_mm
    assert np.abs(d.result.image - ref.image).max() < 1e-3

    # a slider moved while the full render is being glued: the rest is dropped, the move is served at once
    d.band_px = 5_000  # many small bands

    async def interrupt():
        ctl["relief_m"].value = 70.0
        while d._later is None or isinstance(d._later, asyncio.TimerHandle):
            await asyncio.sleep(0.001)  # until the settle timer has fired and the glueing has begun
        await asyncio.sleep(0)  # a band or two more
        assert d.result.preview and d._later is not None  # still glueing
        n = d.n_updates
        ctl["relief_m"].value = 75.0
        seen2.append((d.n_updates - n, d.result.preview, d.values["relief_m"]))
        await until_full()
        seen2.append((d.n_updates - n, d.result.preview))

    seen2 = []
    asyncio.run(interrupt())
    assert seen2 == [(1, True, 75.0), (2, False)]  # one preview for 75, then one full render (70's was dropped)

    # Reset while the full render is pending: the reset values at full resolution, final, nothing left to run
    async def reset_while_pending():
        ctl["relief_m"].value = 80.0
        assert d._later is not None and d.result.preview
        d._on_reset()  # what the Reset button does
        after = (d._later, d.result.preview, d.values["relief_m"], d.status.value, d.n_updates)
        await asyncio.sleep(3 * d.settle_s)
        return after, d.n_updates

    (later, preview, relief, status, n), n_end = asyncio.run(reset_while_pending())
    assert (later, preview, relief, status) == (None, False, 30.0, "")
    assert n_end == n  # the dropped full render did not run after the reset
    # without an event loop (a plain script) a slider event renders in full at once
    ctl["px_percent"].value = 65
    assert not d.result.preview and d.values["px_percent"] == 65
    d.close()


@pytest.mark.parametrize("values", [
    dict(f_mm=70, m=16000, px_percent=56, alpha_max_deg=5, relief_m=200, seed=20),
    dict(f_mm=350, m=8000, px_percent=80, alpha_max_deg=5, relief_m=0, seed=0, cut_shape="zigzag"),
    dict(f_mm=70, m=16000, px_percent=56, alpha_max_deg=5, relief_m=200, seed=7, cut_shape="curved"),
    dict(f_mm=1100, m=22000, px_percent=56, alpha_max_deg=0, relief_m=200, seed=3),
    dict(f_mm=70, m=22000, px_percent=80, alpha_max_deg=5, relief_m=0, seed=9),
])
def test_demo_slider_extremes_work(values):
    from aerophoto.demos.fotoschema import FotoschemaDemo

    d = FotoschemaDemo()
    d.set(preview=True, **values)
    assert d.result.fs.dI_mm.size > 0 and np.isfinite(d.result.fs.scale.m)
    assert len(d.result.fs.poses) == 4  # the guide's four prints, at every scale
    d.close()


def test_demo_opens_on_variant_00_and_reaches_every_variant():
    from aerophoto.demos.fotoschema import FotoschemaDemo
    from aerophoto.variants import variant_for_index

    p = {q.name: q for q in FotoschemaDemo.params}
    v0, v99 = variant_for_index(0), variant_for_index(99)
    assert (p["f_mm"].default, p["m"].default) == (v0.f_mm, v0.m)
    for v in (v0, variant_for_index(57), v99):  # every variant's f and m is a slider position: nothing clamped
        for name in ("f_mm", "m"):
            q, x = p[name], getattr(v, name)
            assert q.lo <= x <= q.hi and abs((x - q.lo) / q.step - round((x - q.lo) / q.step)) < 1e-9


def test_demo_says_when_it_flies_a_smaller_tilt_than_asked():
    from aerophoto.demos.fotoschema import FotoschemaDemo

    d = FotoschemaDemo()
    assert d.result.note == "" and d.result.alpha_max_deg == 1.0
    d.set(preview=True, f_mm=1100, m=22000, alpha_max_deg=5)
    assert 0.5 < d.result.alpha_max_deg < 1.5  # H = 24.2 km: about 1.1° keeps the four photos on the site
    assert "reduced from 5°" in d.result.note and "reduced from 5°" in d.table.value
    assert max(s.pose.alpha_deg for s in d.result.strip.shots) <= d.result.alpha_max_deg + 1e-9
    d.close()


def test_demo_flies_a_smaller_tilt_when_neighbours_would_share_no_tie_strip():
    """f = 1100 mm at 1:8 000 and p_x = 80 %: the base is 288 m and a 5° tilt carries a photo ~770 m, so two
    neighbours can share no strip for tie points (the assembly refused it and the demo showed an error); the
    demo now flies a smaller tilt, a quarter degree at a time, and says so."""
    from aerophoto.demos.fotoschema import fotoschema_model
    from aerophoto import mosaic as mo

    values = dict(f_mm=1100, m=8000, px_percent=80, seed=13, relief_m=45, cut_shape="straight")
    r = fotoschema_model(alpha_max_deg=5.0, **values)
    assert r.alpha_max_deg == 4.5 and "reduced from 5° to 4.50°" in r.note and "tie points" in r.note
    assert r.fs.dI_mm.size > 0
    # the tilt asked for really leaves no common strip (the reduction is needed), the reduced one does
    from aerophoto import simulate as sim
    from aerophoto import geometry as g

    strip = sim.strip_over_site(r.ground, g.Camera(1100), 8000, 80, len(r.strip.shots),
                                imperfections=sim.Imperfections(max_tilt_deg=4.75, seed=13))
    with pytest.raises(ValueError, match="do not overlap enough"):
        mo.assemble(strip, r.ground, cut_shape="straight", points_m=mo.catalogue_points(r.ground))


def test_correction_sheet_writes_every_mismatch():
    from aerophoto.demos.fotoschema import correction_sheet

    fs, _ = _fotoschema(relief_m=120.0)
    ax = correction_sheet(fs)
    texts = [t.get_text() for t in ax.texts]
    from aerophoto.i18n.numfmt import fmt_number, fmt_signed, numbers_in

    for d in fs.dI_mm:
        assert fmt_signed(d, 2) in texts  # the book's format: +0.12, −0.25 (a true minus)
    assert f"m = {fmt_number(fs.rms_mm, 2)} mm" in ax.get_title()
    assert round(fs.rms_mm, 2) in numbers_in(ax.get_title())


def test_finished_sheet_exports_valid_png_and_pdf(tmp_path):
    import re

    from PIL import Image

    from aerophoto.demos.fotoschema import PAPER_MM, export_sheet, sheet_figure

    from aerophoto.demos.fotoschema import TRIM_MM, sheet_size_mm

    fs, gr = _fotoschema(relief_m=30.0)
    img, ext = mo.sheet_raster(fs, gr, 1.0)
    fig = sheet_figure(fs, img, ext, made_by="Student S.", checked_by="Teacher T.", year=2025)
    texts = " ".join(t.get_text() for t in fig.texts)
    assert "ФОТОСХЕМА" in texts and "Photo mosaic" in texts
    from aerophoto.i18n.numfmt import fmt_count

    assert f"М 1:{fmt_count(fs.scale.m_rounded, lang='ru')}" in texts  # the book's format: 1:12 000, narrow space
    assert "2025" in texts and "Student S." in texts and "Teacher T." in texts
    paper = fig.aerophoto_paper
    w_mm, h_mm = PAPER_MM[paper]
    paths = export_sheet(fig, tmp_path / "out", "sheet", dpi=60)
    png = paths["png"].read_bytes()
    assert png[:8] == b"\x89PNG\r\n\x1a\n"
    with Image.open(paths["png"]) as im:
        im.load()
        assert im.size == (round(w_mm / 25.4 * 60), round(h_mm / 25.4 * 60))
    pdf = paths["pdf"].read_bytes()
    assert pdf.startswith(b"%PDF-") and pdf.rstrip().endswith(b"%%EOF")
    box = re.search(rb"/MediaBox \[\s*0 0 ([\d.]+) ([\d.]+)\s*\]", pdf)
    assert box and float(box.group(1)) == pytest.approx(w_mm / 25.4 * 72, abs=0.5)
    # the mosaic is drawn at true size: its axes span the sheet's millimetres on the paper, trimmed 1 cm outside
    # the working-area lines (63 mm from o across the strip at p_y = 30 %), which are drawn in ink
    ax = fig.axes[0]
    x0, x1, y0, y1 = fs.extent_mm
    w, h = sheet_size_mm(fs)
    assert (w, h) == (pytest.approx(x1 - x0), pytest.approx(2 * (63.0 + TRIM_MM), abs=0.5))
    assert ax.get_position().width * w_mm == pytest.approx(w, rel=1e-6)
    assert ax.get_position().height * h_mm == pytest.approx(h, rel=1e-6)
    assert ax.get_ylim()[1] - ax.get_ylim()[0] == pytest.approx(h)
    inked = [ln.get_ydata() for ln in ax.lines]
    assert len(inked) == 2 and all(np.all(np.abs(np.abs(y) - 63.0) < 1.0) for y in inked)
    # signed with the scale the student computed, when given
    fig2 = sheet_figure(fs, img, ext, scale_m=12345.0)
    assert "М 1:12\u202f300" in " ".join(t.get_text() for t in fig2.texts)
    # never overwrite silently
    with pytest.raises(FileExistsError, match="sheet.png"):
        export_sheet(fig, tmp_path / "out", "sheet")
    before = paths["png"].stat().st_mtime_ns
    export_sheet(fig, tmp_path / "out", "sheet", overwrite=True, dpi=60)
    assert paths["png"].stat().st_mtime_ns >= before
    with pytest.raises(ValueError, match="stem"):
        export_sheet(fig, tmp_path, "../evil")



# --------------------------------------------------------------------------- what the student measures
def test_working_area_lines_run_along_the_middle_of_the_side_overlaps():
    fs = mo.assemble(sim.fly_strip(g.Camera(100), 12000, 60, 4))
    up, low = fs.working_area_lines()
    assert np.allclose(up[:, 1], 63.0) and np.allclose(low[:, 1], -63.0)  # 90 − 30 %·180/2
    assert up[0, 0] == pytest.approx(fs.extent_mm[0]) and up[1, 0] == pytest.approx(fs.extent_mm[1])
    assert np.allclose(fs.working_area_lines(20.0)[:, :, 1], [[72.0, 72.0], [-72.0, -72.0]])
    with pytest.raises(ValueError, match="py_percent"):
        fs.working_area_lines(100.0)


def test_seam_details_give_the_guides_signs():
    # a right print moved along the strip by +1 mm puts the prick 1 mm nearer the cut than the contour:
    # ΔI = contour − prick = +1, a duplicate; moved back by 0.5 mm, the contour lies between cut and prick: −0.5
    import dataclasses

    fs = mo.assemble(sim.fly_strip(g.Camera(100), 12000, 60, 2))
    for shift, expected in ((+1.0, +1.0), (-0.5, -0.5)):
        moved = mo.Similarity2D(1, 0, shift, 0).compose(fs.to_sheet[1])
        d = mo.seam_details(dataclasses.replace(fs, to_sheet=(fs.to_sheet[0], moved)), g.FlatTerrain(0.0),
                            inset_mm=3.0)
        assert d.dI_mm == pytest.approx(np.full(len(d.dI_mm), expected), abs=1e-9)
        assert d.contour_from_cut_mm == pytest.approx(np.full(len(d.dI_mm), 3.0), abs=1e-9)
        assert np.all((d.prick_from_cut_mm < d.contour_from_cut_mm) == (expected > 0))
        assert list(d.seam) == [0] * len(d.dI_mm) and list(d.point) == list(range(1, len(d.dI_mm) + 1))


def test_seam_details_agree_with_the_mismatch_at_the_cut():
    # vertical photos over a valley along the strip: a detail 3 mm from the cut lies at the cut's height, so the
    # prick's offset is the mismatch the cut itself shows (duplicates up the valley sides, guide §6 step 2)
    strip = sim.fly_strip(g.Camera(100), 12000, 60, 4, ground_Z_m=40.0)
    fs = mo.assemble(strip, Valley())
    d = mo.seam_details(fs, Valley(), inset_mm=3.0)
    assert d.dI_mm.shape == fs.dI_mm.shape and fs.dI_mm.max() > 0.3
    # (the cut's ΔI converts ground metres with the design scale 1:m; the detail's is sheet mm, at the local
    # scale of ground up to 120 m above the mean: they agree to that few per cent)
    assert np.all(np.abs(d.dI_mm - fs.dI_mm) <= 0.01 + 0.05 * np.abs(fs.dI_mm))
    # the details lie on the left piece, the pricks where the right print shows the same ground point
    for k, (s_, A, B, G) in enumerate(zip(d.seam, d.contour_mm, d.prick_mm, d.ground_m)):
        assert fs.photo_index(A) == s_
        back = fs.to_sheet[s_ + 1].inverse().apply(B)
        assert np.allclose(g.ground_to_photo(fs.camera, fs.poses[s_ + 1], G), back, atol=1e-6)
    inset = np.linspace(2.0, 5.0, fs.dI_mm.size)
    assert np.allclose(mo.seam_details(fs, Valley(), inset_mm=inset).contour_from_cut_mm, inset, atol=1e-6)
    with pytest.raises(ValueError, match="inset_mm"):
        mo.seam_details(fs, Valley(), inset_mm=[1.0, 2.0])
    with pytest.raises(ValueError, match="inset_mm"):
        mo.seam_details(fs, Valley(), inset_mm=0.0)
