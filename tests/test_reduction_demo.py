"""The reduction explorer (aerophoto.demos.reduction): model, views and the live demo."""

import numpy as np
import pytest

from aerophoto import triangulation as T
from aerophoto.demos import reduction as R


@pytest.fixture(scope="module")
def demo():
    import matplotlib

    matplotlib.use("Agg")
    d = R.ReductionDemo()
    yield d
    d.close()


def test_model_defaults_and_summary():
    r = R.reduction_model()
    assert r.params["n_photos"] == 5 and r.params["centre"] == 3
    assert r.reduction.corrections.centre == str(r.strip.shots[2].number)
    # k ≈ 1/q (the free strip was laid at 0.96 of the plan scale)
    assert r.k == pytest.approx(1 / 0.96, rel=0.01)
    s = r.summary()
    assert s.loc["mean reduction coefficient k", "value"] == pytest.approx(r.k)
    assert 0.0 < s.loc["largest error-triangle side", "value"] < T.TRIANGLE_TOL_MM


def test_model_without_pricking_error_is_nearly_exact_on_the_site():
    # vertical photos: radial directions are almost free of relief displacement (centres near o)
    r = R.reduction_model(pricking_mm=0.0)
    assert r.free.max_triangle_side_mm < 0.02
    assert r.reduction.max_control_residual_mm < 0.05
    noisy = R.reduction_model(pricking_mm=0.3)
    assert noisy.free.max_triangle_side_mm > 5 * r.free.max_triangle_side_mm


def test_model_centre_beyond_the_strip_uses_the_last_with_a_note():
    r = R.reduction_model(centre=7, n_photos=4)
    assert r.params["centre"] == 4 and "beyond" in r.note


def test_model_rejects_bad_input():
    with pytest.raises(ValueError, match="f_mm"):
        R.reduction_model(f_mm=10)
    with pytest.raises(ValueError, match="pricking_mm"):
        R.reduction_model(pricking_mm=-1)


def test_every_slider_extreme_is_valid():
    for p in R.ReductionDemo.params:
        for value in (p.lo, p.hi):
            kw = {p.name: value}
            if p.name == "seed":
                continue
            R.reduction_model(**kw)


def test_demo_updates_artists_in_place(demo):
    demo.reset()
    view = demo.view.strip
    arrows, triangles = view.arrows, view.triangles
    uv0 = np.array(arrows.U, copy=True)
    demo.set(scale_ratio=0.8)
    assert demo.view.strip.arrows is arrows and demo.view.strip.triangles is triangles  # same artists
    assert not np.allclose(np.nan_to_num(arrows.U), np.nan_to_num(uv0))
    assert demo.result.k == pytest.approx(1 / 0.8, rel=0.01)
    assert "Reduction coefficients" in demo.table.value
    n0 = demo.n_updates
    demo.set(pricking_mm=0.3)
    assert demo.n_updates == n0 + 1
    assert len(triangles.get_paths()) == int(np.sum(np.all(np.isfinite(demo.result.free.triangle_sides_mm), axis=1)))
    demo.draw(force=True)
    w, h = demo.fig.get_size_inches() * demo.fig.dpi
    assert w <= 1000 and h <= 600


def test_demo_centre_moves_the_arrows_not_the_result(demo):
    demo.reset()
    res_a = demo.result.reduction.control_residuals_mm.copy()
    v_a = demo.result.reduction.corrections.v_mm.copy()
    demo.set(centre=1)
    np.testing.assert_allclose(demo.result.reduction.control_residuals_mm, res_a, atol=1e-9)
    assert np.max(np.abs(demo.result.reduction.corrections.v_mm)) > 1.5 * np.max(np.abs(v_a))
    ring = demo.view.strip.centre.get_xydata()[0]
    np.testing.assert_allclose(ring, demo.result.free.points_mm[demo.result.reduction.centre_index])


def test_demo_reset_returns_to_defaults(demo):
    demo.set(f_mm=200, m=15000)
    demo.reset()
    assert demo.values == {p.name: p.default for p in R.ReductionDemo.params}
    with pytest.raises(ValueError, match="pricking_mm"):
        demo.set(pricking_mm=5)


def test_coefficient_view_marks_bases_outside_tolerance():
    import matplotlib.colors as mc

    c = T.reduction_coefficients(["A", "B", "C"], [[0, 0], [300, 0], [0, 300]], [[0, 0], [290, 0], [0, 285]])
    view = R.CoefficientView(c)
    colours = [mc.to_hex(fc) for fc in view.points.get_facecolors()]
    bad = mc.to_hex(R.plots.COLORS["vermillion"])
    assert [col == bad for col in colours] == [not ok for ok in c.ok]
    assert not c.all_ok


def test_template_view_draws_the_rays():
    r = R.reduction_model(pricking_mm=0.0)
    v = R.TemplateView(r.templates, 2)
    idx, _ = r.templates.rays(2)
    n_centres = sum(r.free.points.kinds[i] == "centre" for i in idx)
    assert len(v.initial.get_segments()) == n_centres == 2  # the two initial directions
    assert len(v.rays.get_segments()) == len(idx) - n_centres


def test_strip_view_draws_the_ends_strip():
    from aerophoto import geometry as g

    cam = g.Camera(100)
    poses = [g.Pose(i * 864.0, 0, 1200.0) for i in range(5)]
    pts = T.design_points(cam, poses, None, control_layout="ends")
    es = T.build_from_ends(T.measure_templates(cam, poses, pts, seed=1))
    v = R.StripView(es)
    x, y = v.marks["centre"].get_data()
    np.testing.assert_allclose(np.column_stack([x, y]), es.centres_mm)
