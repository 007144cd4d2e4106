"""The graded tasks of chapter 11 (aerophoto.tasks.ch11, labs.ch11): the paper and rectification labs, every variant,
slips, hidden checks (the tests that hold chapters 09–11 together are in test_tasks_ch09.py)."""

import numpy as np
import pytest

from aerophoto import tasks
from aerophoto import rectify as rf
from aerophoto.labs import ch11
from aerophoto.variants import variant_for_index

from .conftest import ALL, _grade, _raises

IDS = ("task-11-1", "task-11-2")
SOME = [variant_for_index(i) for i in (0, 1, 4, 17, 57, 99)]


def test_11_the_paper_lab():
    signs = {np.sign(ch11.paper_lab(v).deformation.K_d) for v in ALL}
    assert signs == {-1.0, 1.0}  # some papers shrink, some stretch
    lab = ch11.paper_lab(SOME[0])
    assert lab.table().shape == (6, 3)
    a = tasks.answers("task-11-1", SOME[0])
    assert a["t_mm"] == pytest.approx(a["K_d"] * SOME[0].f_mm * (SOME[0].m / 10000 + 1))


def test_11_slips_are_named():
    v = SOME[1]
    a = tasks.answers("task-11-1", v)
    _raises("task-11-1", v, "sign", K_d=-a["K_d"], t_mm=-a["t_mm"])
    _raises("task-11-1", v, "sign", t_mm=-a["t_mm"])
    _raises("task-11-1", v, "K_t \\+ 1", t_mm=a["K_d"] * v.f_mm * v.m / 10000)
    lab = ch11.rectification_lab(v)
    d = lab.rectification.check_lengths_mm
    _raises("task-11-2", v, "photo mm", d1_mm=float(d[0]) / (v.m / 10000))


def test_11_hidden_checks_tie_the_answers_together():
    v = SOME[2]
    a = tasks.answers("task-11-1", v)
    g = _grade("task-11-1", v, t_mm=a["t_mm"] * 1.004)
    assert g.visible_ok and not g.hidden_ok
    b = tasks.answers("task-11-2", v)
    g = _grade("task-11-2", v, rect_ok=not b["rect_ok"])
    assert not g.passed


def test_11_the_residuals_are_relief_displacement():
    # the same photos over the flat site: the residuals shrink to the pricking error's share
    v = SOME[0]
    lab = ch11.rectification_lab(v)
    flat = ch11.rectification_lab_for(lab.camera, lab.pose, lab.M, site=__import__(
        "aerophoto.site", fromlist=["get_site"]).get_site(relief_m=0), seed=0, sigma_mm=0.0)
    assert flat.rectification.check_lengths_mm.max() < 0.02
    assert lab.rectification.check_lengths_mm.max() > 0.05
    assert rf.TOLERANCE_MM == 0.4
