"""The control demos of chapter 10 (aerophoto.demos.control): the control design and the resection with its danger
circle never fail inside their slider ranges; the marking figure."""

import itertools

import numpy as np
import pytest

from aerophoto.demos import control as dc


def test_control_design_demo():
    d = dc.ControlDesignDemo()
    assert d.result.zhukov_n == 4 and d.result.design.n_points == 16 and d.result.dense_points == 48
    d.set(scheme="dense")
    assert d.result.design.dense and d.result.design.n_points == 48
    d.set(m=30000)  # k_i = 3: even one base is too many
    assert d.result.zhukov_n == 0
    d.reset()
    assert d.result.design.n_points == 16
    d.close()


@pytest.mark.parametrize("values", list(itertools.product((2.0, 8.0), (0.2, 0.6), (6000, 30000), (1, 5))))
def test_control_design_never_fails_in_range(values):
    e, m_allowed, m, k = values
    r = dc.control_design_model(e, m_allowed, m, k, 20)
    assert r.design.points_m.shape[1] == k + 1 and np.all(np.isfinite(r.design.points_m))


def test_resection_demo_and_its_danger_circle():
    d = dc.ResectionDemo()
    r0 = d.result
    assert r0.resection is not None and r0.cloud_rms_m < 0.5
    d.set(north_m=-270.0, east_m=-820.0)  # 3 m from the circle through I, II, III
    near = d.result
    assert near.cloud_rms_m > 50 * r0.cloud_rms_m
    assert any(q.startswith("shift of P per 1″") for q in near.table().index)
    d.set(sigma_arcsec=0.0)
    assert d.result.cloud_rms_m < 1e-3
    d.reset()
    d.close()


@pytest.mark.parametrize("north, east", list(itertools.product((-1500.0, 0.0, 1500.0), (-1500.0, 0.0, 1500.0))))
def test_resection_model_never_fails_in_range(north, east):
    r = dc.resection_model(north, east, 30.0)
    assert len(r.table()) >= 6


def test_resection_model_on_the_circle_reports_instead_of_failing():
    K = dc.guide_points().to_numpy()
    centre, R = dc.c.danger_circle(*K[:3])
    P = centre + R * np.array([0.0, -1.0])
    off = P - K[:3].mean(axis=0)
    r = dc.resection_model(off[0], off[1], 5.0)
    assert r.resection is None and "danger circle" in r.error
    assert r.table().loc["resection", "value"].startswith("undetermined")


def test_marking_figure():
    from aerophoto import geometry as g
    from aerophoto.render import render
    from aerophoto.site import get_site

    site = get_site()
    cx, cy = site.centre_m
    photo = render(site, g.Camera(100.0), g.Pose(cx + 700, cy, site.mean_height_m + 1200, 1.0, -60, 0), 128)
    fig = dc.marking_figure(photo)
    assert len(fig.axes) == 2 and len(fig.axes[0].patches) == 2 * int(
        (photo.points()["visible"] & photo.points()["control"]).sum())
