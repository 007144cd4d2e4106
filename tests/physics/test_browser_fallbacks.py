"""The browser book's stand-ins for scikit-image and pyproj (Pyodide 0.27.7 has neither), against the libraries.

Each of the three functions that use them — :func:`aerophoto.stereo.match_points`
(``skimage.feature.match_template``), :func:`aerophoto.projective.warp_raster`
(``skimage.transform.warp``) and :func:`aerophoto.guide.ch10.projected` /
:func:`~aerophoto.guide.ch10.geographic` (pyproj) — keeps the library when it
imports and falls back to numpy/scipy when it does not.  The fallback is forced
here the way the browser meets it: the library's entries in ``sys.modules`` are
set to None, so its import raises ImportError (``monkeypatch`` restores them).

Measured on the book's inputs (numpy 2.4, scipy 1.17, scikit-image 0.26,
pyproj 3.7 / PROJ 9.5): match_points and the correlations bit-identical (the
fallback repeats scikit-image's float32 arithmetic); warp_raster ≤ 6e-14 for
every order, the same NaN mask to the pixel (no border exception); the
Krüger series within 5e-9 m of PROJ and 5e-14° back.
"""

import math
import subprocess
import sys
import textwrap
import warnings

import numpy as np
import pytest

import pyproj  # environment.txt installs both libraries: the comparison never skips
import skimage.feature  # noqa: F401
import skimage.transform  # noqa: F401

from aerophoto import projective as pj  # noqa: E402
from aerophoto import stereo as st  # noqa: E402
from aerophoto import guide  # noqa: E402
from aerophoto.projective import images  # noqa: E402


def _block(monkeypatch, *names):
    """Make ``import name`` (and of any of its submodules) raise ImportError for the rest of the test."""
    for name in names:
        for mod in [m for m in sys.modules if m == name or m.startswith(name + ".")]:
            monkeypatch.setitem(sys.modules, mod, None)
        monkeypatch.setitem(sys.modules, name, None)


@pytest.fixture(scope="module")
def pair():
    """The chapter 7 example pair, normalised, at 512 pixels (the height model's size; cached by ch07)."""
    from aerophoto.labs import ch07

    lab = ch07.example_lab()
    return lab, ch07.lab_images(lab, 512)


def _d_range(lab, images):
    """The disparity range the chapter's profile searches (demos.stereo_figures.profile)."""
    from aerophoto.site import get_site

    px = images.left.pixel_mm
    site = get_site()
    zlo, zhi = lab.Z_S_m - site.z_min_m + 10.0, lab.Z_S_m - site.surface_z_max_m - 5.0
    dlo = int(math.floor((lab.B_m * lab.f_mm / zlo - lab.p0_mm) / px)) - 2
    dhi = int(math.ceil((lab.B_m * lab.f_mm / max(zhi, 1.0) - lab.p0_mm) / px)) + 2
    return dlo, dhi


# --------------------------------------------------------------------------- stereo: normalised cross-correlation
def test_stereo_ncc_fallback_is_match_template(pair):
    from skimage.feature import match_template

    _, images = pair
    L, R = images.left.image, images.right.image
    assert L.dtype == np.float32
    rng = np.random.default_rng(5)
    cases = [(R[r - 7:r + 8, c - 30:c + 30], L[r - 7:r + 8, c - 7:c + 8]) for r, c in ((60, 60), (200, 150), (225, 38),
                                                                                       (400, 230))]
    cases.append((rng.random((20, 50)), rng.random((9, 11))))  # float64, a template that is not square
    cases.append((np.full((15, 40), 0.5, np.float32), L[100:115, 100:115]))  # a flat strip: 0 everywhere
    cases.append((L[100:115, 50:120], np.zeros((15, 15), np.float32)))  # a flat template: 0 everywhere
    for image, tpl in cases:
        lib = match_template(image, tpl)
        fb = st._ncc(image, tpl, prefer_library=False)
        assert fb.shape == lib.shape and fb.dtype == lib.dtype
        np.testing.assert_allclose(fb, lib, rtol=0, atol=1e-6)
        assert np.array_equal(fb == 0, lib == 0)
    # with the library importable the helper is the library
    image, tpl = cases[1]
    assert np.array_equal(st._ncc(image, tpl), match_template(image, tpl))


@pytest.mark.parametrize("half_window", [7, 9])
def test_stereo_match_points_fallback_on_the_site_pair(pair, monkeypatch, half_window):
    lab, images = pair
    L, R = images.left.image, images.right.image
    dlo, dhi = _d_range(lab, images)
    rows = np.arange(half_window, L.shape[0] - half_window, 7)
    cols = np.arange(half_window, L.shape[1] - half_window, 5)
    rc = np.array([(r, c) for r in rows for c in cols], dtype=float)
    d_lib, p_lib = st.match_points(L, R, rc, half_window=half_window, d_min=dlo, d_max=dhi)
    _block(monkeypatch, "skimage")
    with pytest.raises(ImportError):
        import skimage.feature  # noqa: F401
    d_fb, p_fb = st.match_points(L, R, rc, half_window=half_window, d_min=dlo, d_max=dhi)
    ok = np.isfinite(d_lib)
    assert ok.sum() > 2500  # the overlap is matched over most of the grid
    assert np.array_equal(ok, np.isfinite(d_fb))
    assert np.max(np.abs(d_fb[ok] - d_lib[ok])) <= 1e-4
    assert np.max(np.abs(p_fb[ok] - p_lib[ok])) <= 1e-5


def test_stereo_match_points_fallback_on_the_known_disparity(monkeypatch):
    from scipy.ndimage import gaussian_filter, shift

    rng = np.random.default_rng(3)
    tex = gaussian_filter(rng.random((80, 160)), 1.2)  # as test_stereo: every detail 2.4 px further right
    L = tex[:, 20:140]
    R = shift(tex, (0, 2.4), order=3, mode="nearest")[:, 20:140]
    rc = [[40, 60], [30, 80], [50, 45], [2, 50]]  # the last one's window leaves the image: NaN
    d_lib, p_lib = st.match_points(L, R, rc, half_window=7, d_min=-8, d_max=8)
    _block(monkeypatch, "skimage")
    d_fb, p_fb = st.match_points(L, R, rc, half_window=7, d_min=-8, d_max=8)
    np.testing.assert_allclose(d_fb, d_lib, rtol=0, atol=1e-4)
    np.testing.assert_allclose(p_fb, p_lib, rtol=0, atol=1e-5)
    assert np.isnan(d_fb[3]) and np.allclose(d_fb[:3], -2.4, atol=0.1)


# --------------------------------------------------------------------------- projective: resampling
@pytest.fixture(scope="module")
def rectification(pair):
    """The left photo of the pair and its rectification onto a 1:10 000 base (chapter 11's lab for that photo)."""
    from aerophoto.labs.ch11 import rectification_lab_for

    lab, images = pair
    photo = images.photos[0]
    rect = rectification_lab_for(lab.camera, lab.left.pose, 10000.0, sigma_mm=0.0).rectification
    return photo.image, rect.transform, lab.camera.frame_mm


def _both_warps(monkeypatch, *args, **kw):
    with warnings.catch_warnings():
        warnings.filterwarnings("ignore", message="Bi-quadratic", category=UserWarning)  # scikit-image, order 2
        lib = pj.warp_photo(*args, **kw)
    with monkeypatch.context() as m:
        _block(m, "skimage")
        fb = pj.warp_photo(*args, **kw)
    return lib, fb


@pytest.mark.parametrize("cval", [np.nan, 1.0])
@pytest.mark.parametrize("order", [0, 1, 2, 3, 4, 5])
def test_projective_warp_fallback_on_a_rendered_photo(rectification, monkeypatch, order, cval):
    """Equal to rounding and the same NaN mask to the pixel, the photo's edge inside the output (no border excepted).

    With cval NaN scikit-image's orders 2, 4, 5 give an all-NaN raster (scipy's spline prefilter spreads the
    NaN of "grid-constant" over the image); the fallback does the same.
    """
    image, T, frame_mm = rectification
    h = frame_mm / 2
    c = np.array([[-h, -h, 1.0], [h, -h, 1.0], [h, h, 1.0], [-h, h, 1.0]]) @ pj.as_matrix(T).T
    corners = c[:, :2] / c[:, 2:]  # the photo's corners on the base, mm
    lo, hi = corners.min(axis=0) - 10.0, corners.max(axis=0) + 10.0  # the whole photo and a margin off it
    lib, fb = _both_warps(monkeypatch, image, T, (lo[0], hi[0], lo[1], hi[1]), 0.9, frame_mm=frame_mm, order=order,
                          cval=cval)
    assert fb.extent == lib.extent and fb.pixel == lib.pixel and fb.image.shape == lib.image.shape
    assert np.array_equal(np.isnan(fb.image), np.isnan(lib.image))
    ok = np.isfinite(lib.image)
    if np.isnan(cval) and order in (0, 1, 3):
        assert ok.mean() > 0.2 and (~ok).mean() > 0.05  # the photo and its surroundings are both in the raster
    assert np.max(np.abs(fb.image[ok] - lib.image[ok]), initial=0.0) <= 1e-6


def test_projective_warp_fallback_on_the_tests_cases(monkeypatch):
    from aerophoto import plane

    rng = np.random.default_rng(0)
    img = rng.uniform(0, 1, size=(64, 64))
    lib, fb = _both_warps(monkeypatch, img, np.eye(3), (-90, 90, -90, 90), 180.0 / 64)
    np.testing.assert_allclose(fb.image, img, atol=1e-9)
    np.testing.assert_allclose(fb.image, lib.image, rtol=0, atol=1e-12)
    half = np.zeros((90, 90))
    half[:, 45:] = 1.0
    S = plane.Similarity2D.from_angle(0.0, (0.0, 0.0), scale=2.0)
    for cval in (np.nan, 0.5):
        lib, fb = _both_warps(monkeypatch, half, S, (-300, 300, -300, 300), 2.0, cval=cval)
        np.testing.assert_allclose(fb.image, lib.image, rtol=0, atol=1e-12)  # NaN at the same places
        v = fb.value_at(np.array([[-100.0, 0.0], [100.0, 0.0]]))
        assert v[0] == pytest.approx(0.0) and v[1] == pytest.approx(1.0)
    # the helper itself: the library when it imports, a raster of the requested shape either way
    inv = np.array([[1.1, 0.1, -3.0], [-0.05, 0.9, 2.0], [1e-4, -2e-4, 1.0]])
    a = images._warp(img, inv, (70, 80), order=1, cval=0.25)
    b = images._warp(img, inv, (70, 80), order=1, cval=0.25, prefer_library=False)
    assert a.shape == b.shape == (70, 80)
    np.testing.assert_allclose(b, a, rtol=0, atol=1e-12)


# --------------------------------------------------------------------------- guide §11: Gauss–Krüger zone 5
def test_s11_transformers_are_chosen_at_each_call(monkeypatch):
    fwd, inv = guide.ch10._transformers()
    assert isinstance(fwd, pyproj.Transformer) and isinstance(inv, pyproj.Transformer)
    with monkeypatch.context() as m:
        _block(m, "pyproj")
        fwd, inv = guide.ch10._transformers()
        assert isinstance(fwd, guide.ch10._TransverseMercator) and isinstance(inv, guide.ch10._TransverseMercator)
    assert isinstance(guide.ch10._transformers()[0], pyproj.Transformer)  # pyproj again once it imports
    assert isinstance(guide.ch10._transformers(prefer_library=False)[0], guide.ch10._TransverseMercator)


def test_s11_fallback_on_the_guides_points(monkeypatch):
    df = guide.ch10.known_points()
    lat, lon = df["φ, °"].to_numpy(), df["λ, °"].to_numpy()
    X, Y = df["X, m"].to_numpy(), df["Y, m"].to_numpy()
    XY_lib, back_lib = guide.ch10.projected(lat, lon), guide.ch10.geographic(X, Y)
    one_lib = guide.ch10.projected(lat[0], lon[0])
    table_lib = guide.ch10.coordinate_table().table
    with monkeypatch.context() as m:
        _block(m, "pyproj")
        XY_fb, back_fb = guide.ch10.projected(lat, lon), guide.ch10.geographic(X, Y)
        one_fb = guide.ch10.projected(lat[0], lon[0])
        table_fb = guide.ch10.coordinate_table.__wrapped__().table  # uncached: computed with the fallback
        summary_fb = guide.ch10.shift_summary.__wrapped__()
    assert XY_fb.shape == XY_lib.shape == (4, 2) and one_fb.shape == one_lib.shape == (2,)
    assert np.max(np.abs(XY_fb - XY_lib)) < 1e-3  # m
    assert np.max(np.abs(one_fb - one_lib)) < 1e-3
    assert np.max(np.abs(back_fb - back_lib)) < 1e-9  # degrees
    assert table_fb.equals(table_lib)  # the audit's table, rounded to metres and seconds, is the same
    summary_lib = guide.ch10.shift_summary()
    for key in ("mean_dX_m", "mean_dY_m", "sd_dX_m", "sd_dY_m", "max_relative_m"):
        assert summary_fb[key] == pytest.approx(summary_lib[key], abs=1e-3)


def test_s11_fallback_over_the_zone(monkeypatch):
    # the zone's 6° strip (24…30° E) and half a degree beyond, from the equator to 84° N, and the south too
    lon, lat = np.meshgrid(np.linspace(23.5, 30.5, 29), np.r_[np.linspace(-80.0, 84.0, 83), 54.85])
    XY_lib = guide.ch10.projected(lat, lon)
    back_lib = guide.ch10.geographic(XY_lib[..., 0], XY_lib[..., 1])
    with monkeypatch.context() as m:
        _block(m, "pyproj")
        XY_fb = guide.ch10.projected(lat, lon)
        back_fb = guide.ch10.geographic(XY_lib[..., 0], XY_lib[..., 1])
        round_trip = guide.ch10.geographic(XY_fb[..., 0], XY_fb[..., 1])
    assert np.max(np.abs(XY_fb - XY_lib)) < 1e-3  # m
    assert np.max(np.abs(back_fb - back_lib)) < 1e-9  # degrees
    assert np.max(np.abs(round_trip - np.stack([lat, lon], axis=-1))) < 1e-9
    # the zone's own numbers: the central meridian at Y = 5 500 000 m, the equator at X = 0
    tm = guide.ch10._TransverseMercator()
    E, N = tm.transform(27.0, 0.0)
    assert float(E) == pytest.approx(5_500_000.0, abs=1e-9) and float(N) == pytest.approx(0.0, abs=1e-9)


# --------------------------------------------------------------------------- the browser's situation
def test_stereo_projective_s11_run_in_a_process_without_skimage_and_pyproj():
    """Import aerophoto with scikit-image and pyproj unimportable from the start (as in Pyodide) and use all three."""
    code = textwrap.dedent("""
        import sys
        for name in ("skimage", "pyproj"):
            sys.modules[name] = None
        import numpy as np
        from aerophoto import projective as pj, stereo as st
        from aerophoto import guide
        rng = np.random.default_rng(1)
        L = rng.random((40, 80)).astype(np.float32)
        d, peak = st.match_points(L, np.roll(L, -3, axis=1), [[20, 40]], half_window=5, d_min=0, d_max=8)
        assert abs(d[0] - 3) < 0.05 and peak[0] > 0.999, (d, peak)
        out = pj.warp_photo(L[:, :40].astype(float), np.eye(3), (-90, 90, -90, 90), 4.5)
        assert np.allclose(out.image, L[:, :40]), "identity warp"
        assert abs(guide.ch10.projected(54.0, 27.0)[1] - 5_500_000.0) < 1e-3
        assert isinstance(guide.ch10._transformers()[0], guide.ch10._TransverseMercator)
        assert "skimage.feature" not in sys.modules and "pyproj.transformer" not in sys.modules
        print("ok")
    """)
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert run.returncode == 0, run.stderr[-2000:]
    assert run.stdout.strip().endswith("ok")
