"""The displacement explorer (chapters 03–04): drivable, updates artists in place, rejects bad values."""

import itertools

import numpy as np
import pytest

from aerophoto import displacement as d
from aerophoto.demos.displacement import (DisplacementDemo, DisplacementView, ReliefDemo, TiltDemo,
                                          displacement_field, legend_html, nice_factor)


def _uv(q):
    return np.array(q.U, dtype=float).copy(), np.array(q.V, dtype=float).copy()


def test_demo_is_drivable_and_moves_its_arrows():
    demo = DisplacementDemo()
    fig = demo.fig
    u0, v0 = _uv(demo.view.q_tilt)
    off0 = np.array(demo.view.q_tilt.get_offsets()).copy()
    n0 = demo.n_updates
    demo.set(f_mm=150, alpha_deg=2)
    assert demo.values["f_mm"] == 150 and demo.values["alpha_deg"] == 2
    assert demo.n_updates == n0 + 1
    assert demo.fig is fig  # the figure is never re-created
    u1, v1 = _uv(demo.view.q_tilt)
    assert not np.allclose(u0, u1) or not np.allclose(v0, v1)
    assert not np.allclose(off0, demo.view.q_tilt.get_offsets())
    # the drawn arrows are the model's exact tilt vectors times the factor used
    field = demo.result.field
    k = demo.factor
    np.testing.assert_allclose(demo.view.q_tilt.U, k * field.tilt_vectors_mm[:, 0])
    np.testing.assert_allclose(demo.view.q_tilt.V, k * field.tilt_vectors_mm[:, 1])
    np.testing.assert_allclose(demo.view.q_tilt.get_offsets(), field.grid_mm - k * field.tilt_vectors_mm)
    np.testing.assert_allclose(demo.view.q_tilt.XY, demo.view.q_tilt.get_offsets())
    np.testing.assert_allclose(demo.view.q_relief.U, k * field.relief_vectors_mm[:, 0])
    np.testing.assert_allclose(demo.view.q_relief.get_offsets(), field.grid_mm)
    # o, n, c markers moved to the new camera's points
    n_marker = demo.view.marks["n"][0]
    np.testing.assert_allclose([n_marker.get_xdata()[0], n_marker.get_ydata()[0]], field.n_mm)
    np.testing.assert_allclose(field.n_mm, d.nadir_offset(150, 2) * np.array([np.cos(np.radians(-60)),
                                                                               np.sin(np.radians(-60))]))
    demo.close()


def test_relief_slider_changes_relief_arrows_and_dot_colours():
    demo = DisplacementDemo(relief_m=0)
    np.testing.assert_allclose(demo.view.q_relief.U, 0.0, atol=1e-12)
    demo.set(relief_m=150, exaggeration=10)
    assert demo.factor == 10
    field = demo.result.field
    np.testing.assert_allclose(demo.view.q_relief.U, 10 * field.relief_vectors_mm[:, 0])
    assert np.max(np.abs(demo.view.q_relief.U)) > 1.0
    np.testing.assert_allclose(demo.view.pts.get_array(), field.h_m)
    assert demo.view.pts.get_clim() == (-150.0, 150.0)
    demo.close()


def test_show_option_hides_and_shows_vectors():
    demo = DisplacementDemo(show="relief")
    assert demo.view.q_relief.get_visible() and not demo.view.q_tilt.get_visible()
    assert not demo.view.q_approx.get_visible()
    demo.set(show="tilt")
    assert not demo.view.q_relief.get_visible() and demo.view.q_tilt.get_visible()
    demo.set(show="both")
    assert demo.view.q_relief.get_visible() and demo.view.q_approx.get_visible()
    assert "relief and tilt" in demo.view.title.get_text()
    demo.close()


def test_forced_draw_changes_pixels():
    demo = DisplacementDemo(relief_m=0, alpha_deg=0)
    demo.draw(force=True)
    before = np.asarray(demo.fig.canvas.buffer_rgba()).copy()
    demo.set(alpha_deg=8, relief_m=150)
    demo.draw(force=True)
    after = np.asarray(demo.fig.canvas.buffer_rgba())
    assert before.shape == after.shape
    assert np.count_nonzero(np.any(before != after, axis=-1)) > 500
    w, h = demo.fig.canvas.get_width_height()
    assert w <= 1000 and h <= 600
    demo.close()


@pytest.mark.parametrize("values, name", [
    (dict(alpha_deg=40), "alpha_deg"),
    (dict(f_mm=-1), "f_mm"),
    (dict(m=100), "m"),
    (dict(relief_m=500), "relief_m"),
    (dict(lambda_deg=float("nan")), "lambda_deg"),
    (dict(show="everything"), "show"),
    (dict(exaggeration=3), "exaggeration"),
    (dict(kappa_deg=10), "kappa_deg"),
])
def test_bad_values_raise_value_error_naming_the_parameter(values, name):
    demo = DisplacementDemo()
    before = dict(demo.values)
    with pytest.raises(ValueError, match=name):
        demo.set(**values)
    assert demo.values == before
    demo.close()


def test_every_corner_of_the_slider_box_computes():
    demo = DisplacementDemo()
    p = demo._params
    corners = itertools.product(*[(p[k].lo, p[k].hi) for k in ("f_mm", "m", "alpha_deg", "lambda_deg", "relief_m")])
    for f, m, a, lam, relief in corners:
        frame = demo.compute(f_mm=f, m=m, alpha_deg=a, lambda_deg=lam, relief_m=relief, show="both", exaggeration=0)
        s = frame.field.summary()
        assert all(np.isfinite(v) for v in s.values())
    demo.close()


def test_reset_and_presets():
    r = ReliefDemo()
    assert r.values["show"] == "relief" and r.values["alpha_deg"] == 0 and r.values["relief_m"] == 80
    t = TiltDemo()
    assert t.values["show"] == "tilt" and t.values["relief_m"] == 0
    np.testing.assert_allclose(t.view.q_relief.U, 0.0, atol=1e-12)
    t.set(alpha_deg=10, f_mm=200)
    t.reset()
    assert t.values == {p.name: p.default for p in t.params}
    r.close()
    t.close()


def test_table_and_widget():
    demo = DisplacementDemo()
    html = demo.table.value
    assert "max |δα| exact" in html and "arrows drawn lengthened" in html and "isocentre" in html
    s = demo.result.field.summary()
    from aerophoto.i18n.numfmt import fmt_number, numbers_in

    assert fmt_number(s["H_m"], 2) in html  # the book's number format, at the table's precision
    assert s["H_m"] in numbers_in(html)
    w = demo.widget()
    assert set(demo.controls()) == {p.name for p in demo.params}
    assert w is demo.widget()
    # moving a slider widget drives the demo like set()
    demo.controls()["alpha_deg"].value = 5.0
    assert demo.values["alpha_deg"] == 5.0 and demo.result.field.pose.alpha_deg == 5.0
    demo.set(lambda_deg=30)
    assert demo.controls()["lambda_deg"].value == 30
    assert "principal vertical" in legend_html()
    demo.close()


def test_a_slider_move_sends_its_table_after_the_picture_and_reset_wins():
    """In a kernel (a running event loop) a slider's table follows the picture TABLE_DELAY_S later; Reset's table
    is set at once and a table still pending from the move does not overwrite it."""
    import asyncio

    from aerophoto.widgets import TABLE_DELAY_S

    async def drive():
        demo = DisplacementDemo()
        start = demo.table.value
        draws = demo.n_updates
        demo.controls()["alpha_deg"].value = 5.0
        seen = [demo.n_updates == draws + 1, demo.table.value == start]  # the picture moved, the table not yet
        await asyncio.sleep(TABLE_DELAY_S + 0.1)
        moved = demo.table.value
        seen.append(moved != start and "max |δα| exact" in moved)
        demo.controls()["alpha_deg"].value = 7.0  # a move, then Reset before its table was sent
        demo._on_reset()
        seen.append(demo.table.value == start)
        await asyncio.sleep(TABLE_DELAY_S + 0.1)
        seen.append(demo.table.value == start)
        demo.close()
        return seen

    assert asyncio.run(drive()) == [True, True, True, True, True]


def test_a_slider_that_sends_back_the_shown_value_redraws_nothing():
    """The page may send a slider's value back (after Reset, or with float noise): no preview, no draw."""
    demo = DisplacementDemo()
    ctl = demo.controls()["alpha_deg"]
    n0 = demo.n_updates
    ctl.value = demo.values["alpha_deg"] + 1e-12  # the same setting, as a float round trip gives it
    assert demo.n_updates == n0
    ctl.value = demo.values["alpha_deg"] + ctl.step  # a real move
    assert demo.n_updates == n0 + 1
    demo.close()


def test_nice_factor():
    assert nice_factor(0.0) == 1
    assert nice_factor(6.5) == 2
    assert nice_factor(0.3) == 20
    assert nice_factor(1e-4) == 1000
    assert nice_factor(50.0) == 1
    assert nice_factor(float("nan")) == 1


def test_static_view_on_given_axes():
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    field = displacement_field(100, 12000, 3, -60, 60)
    view = DisplacementView(field, ax=ax)
    assert view.fig is fig and ax.get_legend() is not None
    k = view.update(field, show="tilt", exaggeration=5)
    assert k == 5 and not view.q_relief.get_visible()
    with pytest.raises(ValueError, match="show"):
        view.update(field, show="nothing")


def test_static_section_figures():
    from aerophoto import plots
    from aerophoto.demos.displacement import principal_plane_figure, relief_section_figure

    fig = principal_plane_figure(f_mm=100, alpha_deg=12)
    texts = {t.get_text() for t in fig.axes[0].texts}
    assert {"o", "n", "c", "O", "N", "C", "S"} <= texts
    img = plots.static(relief_section_figure(), alt="a vertical cross-section")
    assert img.png[:8] == b"\x89PNG\r\n\x1a\n"


# --------------------------------------------------------------------------- the variant policy (issue 12)
def test_the_demos_open_on_the_guides_example_and_reach_every_variant():
    from aerophoto.variants import variant_for_index

    r, t = ReliefDemo(), TiltDemo()
    # variant 00, the guide's worked example: f = 100 mm, 1:12 000, λ = −60° (the relief demo starts vertical)
    assert (t.values["f_mm"], t.values["m"], t.values["alpha_deg"], t.values["lambda_deg"]) == (100, 12000, 3.0, -60)
    assert (r.values["f_mm"], r.values["m"], r.values["lambda_deg"]) == (100, 12000, -60)
    for demo in (r, t):
        p = demo._params
        for i in range(100):
            v = variant_for_index(i)
            assert p["f_mm"].lo <= v.f_mm <= p["f_mm"].hi and p["m"].lo <= v.m <= p["m"].hi
            assert p["lambda_deg"].lo <= v.lambda_deg <= p["lambda_deg"].hi
        assert p["f_mm"].hi >= 1100 and p["m"].hi >= 22000
    # the largest variant is shown as it is: H = f·m = 1.09 m × 21 900 = 23 871 m, nothing clamped
    t.set(f_mm=1090, m=21900)
    assert t.result.field.summary()["H_m"] == pytest.approx(23871.0)
    r.close()
    t.close()


@pytest.mark.parametrize("notebook, cell, cls", [("03_relief_displacement.ipynb", "demo-relief", "ReliefDemo"),
                                                 ("04_tilt_displacement.ipynb", "demo-tilt", "TiltDemo")])
def test_the_notebooks_build_their_demo_without_the_students_variant(notebook, cell, cls):
    from conftest import NOTEBOOKS

    from aerophoto import nbtools

    src = nbtools.find_cell(nbtools.read(NOTEBOOKS / notebook), cell)[1].source
    assert src.splitlines()[0] == f"demo = {cls}()" and "v." not in src
