"""The ray of a vertical photo (chapter 00), the browser benchmark's floor: X = x·m, θ = arctan(x/f), one blitted line."""

import math

import numpy as np
import pytest

from aerophoto import i18n
from aerophoto.demos.ray import RAY_FIGSIZE, RayDemo, ray_model

pytestmark = pytest.mark.usefixtures("plot_style")


@pytest.mark.parametrize(("x", "f", "m", "X"), [(40.0, 100.0, 12000.0, 480.0), (-90.0, 100.0, 12000.0, -1080.0),
                                                 (0.0, 150.0, 20000.0, 0.0), (90.0, 1090.0, 21900.0, 1971.0)])
def test_the_ground_point_is_x_times_m_and_the_ray_leaves_the_vertical_at_arctan_x_over_f(x, f, m, X):
    r = ray_model(x, f, m)
    assert r.X_m == pytest.approx(X)
    assert r.H_m == pytest.approx(f / 1000.0 * m)
    assert math.tan(math.radians(r.theta_deg)) == pytest.approx(x / f)
    # the ray from S (0, H) through the ground point: its slope is x/f
    assert (r.X_m - 0.0) / r.H_m == pytest.approx(x / f)


def _buffer(demo):
    return np.asarray(demo.fig.canvas.buffer_rgba())[..., :3].astype(int).copy()


def test_every_move_blits_the_ray_only_and_changes_the_table():
    import matplotlib

    matplotlib.use("Agg")
    demo = RayDemo()
    try:
        assert tuple(demo.fig.get_size_inches()) == RAY_FIGSIZE and demo.fig.dpi == 100
        assert demo.animated == (demo.ray,)
        demo.fig.canvas.draw()
        full = demo.blitter.n_full
        before, table = _buffer(demo), demo.table.value
        demo.set(x_mm=41.0)
        assert demo.blitter.n_blit == 1 and demo.blitter.n_full == full  # a blit, no full draw
        after = _buffer(demo)
        assert demo.table.value != table and "492" in demo.table.value  # X = 41 mm × 12 000 = 492 m
        changed = np.abs(after - before).max(axis=2) > 0
        # only pixels near the old or the new ray: inside the axes, a thin wedge (well under 2 % of the figure)
        bbox = demo.ax.get_window_extent()
        rows, cols = np.nonzero(changed)
        h = after.shape[0]
        assert changed.any() and changed.mean() < 0.02
        assert cols.min() >= bbox.x0 - 1 and cols.max() <= bbox.x1 + 1
        assert (h - rows).min() >= bbox.y0 - 1 and (h - rows).max() <= bbox.y1 + 1
    finally:
        demo.close()


def test_the_demo_speaks_russian():
    i18n.set_language("ru")
    try:
        demo = RayDemo()
        demo.widget()
        assert demo.controls()["x_mm"].description == "x, мм"
        assert demo.ax.get_xlabel() == "X на местности, м" and "Один луч" in demo.table.value
        assert "мм" in demo.ax.get_title()
        demo.close()
    finally:
        i18n.set_language("en")
