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
    d = R.ReductionDemo
    for p in d.params:
        for value in (p.lo, p.hi):
            if p.name == "seed":
                continue
            kw = {p.name: value - d.first_number + 1} if p.name == "centre" else {p.name: value}
            R.reduction_model(n_photos=d.n_photos, first_number=d.first_number, **kw)
    # the corner of the largest variants: f = 1100 mm, 1:22 000, the largest tilt
    r = R.reduction_model(f_mm=1100, m=22000, max_tilt_deg=3, n_photos=4, first_number=36)
    assert np.isfinite(r.k) and "reduced from 3°" in r.note
    assert max(s.pose.alpha_deg for s in r.strip.shots) <= r.strip.imperfections.max_tilt_deg < 3


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
    demo.set(centre=36)
    np.testing.assert_allclose(demo.result.reduction.control_residuals_mm, res_a, atol=1e-9)
    assert np.max(np.abs(demo.result.reduction.corrections.v_mm)) > 1.4 * np.max(np.abs(v_a))  # by half: 7 → 10 mm
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


def test_demo_opens_on_variant_00_with_four_photos_and_reaches_every_variant(demo):
    from aerophoto.variants import variant_for_index

    demo.reset()
    p = {q.name: q for q in R.ReductionDemo.params}
    v0 = variant_for_index(0)
    assert (demo.values["f_mm"], demo.values["m"]) == (v0.f_mm, v0.m)
    assert [s.number for s in demo.result.strip.shots] == [36, 37, 38, 39]
    assert demo.result.reduction.corrections.centre == "37" and demo.result.note == ""
    for i in (0, 57, 99):  # every variant's camera and scale is a slider position: nothing clamped
        v = variant_for_index(i)
        for name in ("f_mm", "m"):
            q, x = p[name], getattr(v, name)
            assert q.lo <= x <= q.hi and abs((x - q.lo) / q.step - round((x - q.lo) / q.step)) < 1e-9
    demo.set(f_mm=1090, m=21900, max_tilt_deg=3)
    assert "reduced from 3°" in demo.table.value
    demo.reset()


def test_template_view_draws_the_initial_directions_orange():
    import matplotlib.colors as mc

    r = R.reduction_model(pricking_mm=0.0)
    v = R.TemplateView(r.templates, 1)
    assert mc.to_hex(v.initial.get_colors()[0]) == mc.to_hex(R.plots.COLORS["orange"])
    assert "orange" in v.initial.get_label()


def test_ends_view_puts_the_enlarged_middle_beside_the_strip():
    from aerophoto import geometry as g

    cam = g.Camera(100)
    poses = [g.Pose(i * 864.0, 0, 1200.0) for i in range(5)]
    es = T.build_from_ends(T.measure_templates(cam, poses, T.design_points(cam, poses, None, control_layout="ends"),
                                               seed=1))
    v = R.EndsView(es)
    assert len(v.fig.axes) == 2 and v.inset is v.fig.axes[1]  # a panel of its own, not an inset over empty plan
    x = np.concatenate([line.get_xdata() for line in v.marks.values()])
    x0, x1 = v.ax.get_xlim()
    assert (x.max() - x.min()) / (x1 - x0) > 0.7  # the strip fills its axes
    assert v.inset.get_xlim()[1] - v.inset.get_xlim()[0] < 2.0  # the middle centre, enlarged


def test_own_strip_figures_show_the_work_not_the_answers():
    from aerophoto.labs import ch06
    from aerophoto.variants import variant

    v = variant("19-0457")
    fig = R.own_strip_figure(v)
    ax = fig.axes[0]
    assert ax.get_xlabel() == "y on the strip, mm" and ax.get_ylabel() == "x on the strip, mm"
    texts = [t.get_text() for t in ax.texts if t.get_visible()]
    assert {"36", "37", "38", "39", "36/1", "39/2"} <= set(texts)
    assert not any(c.get_paths() for c in ax.collections if c.get_label() == "error triangles")
    assert all("k =" not in t and "×" not in t for t in texts)  # no coefficient, no enlarged triangles
    # drawn where the tables measure: the centres at their (x, y) of the points table
    r = ch06.strip_readings(v)
    cx, cy = ax.lines[0].get_data()  # the working centres (the first kind drawn)
    assert np.allclose(np.column_stack([cy, cx]), r.points.loc[["36", "37", "38", "39"],
                                                               ["x on the strip, mm", "y on the strip, mm"]], atol=0.2)
    assert len(R.own_templates_figure(v).axes) == 4
    site_ax = R.own_site_figure(v).axes[0]
    assert site_ax.get_xlabel() == "Y (east), m" and site_ax.get_ylabel() == "X (north), m"
