"""The graded tasks of chapter 10 (aerophoto.tasks.ch10, labs.ch10): the resection lab, every variant, slips, hidden
checks (the tests that hold chapters 09–11 together are in test_tasks_ch09.py)."""

import numpy as np

from aerophoto import tasks
from aerophoto import control as c
from aerophoto.labs import ch10
from aerophoto.variants import variant_for_index

from .conftest import ALL, _grade, _raises

IDS = ("task-10-1", "task-10-2")
SOME = [variant_for_index(i) for i in (0, 1, 4, 17, 57, 99)]


def test_10_the_resection_lab():
    labs = [ch10.resection_lab(v) for v in ALL]
    assert len({lab.station_id for lab in labs}) > 30  # stations spread over the site
    for v, lab in zip(ALL, labs):
        assert lab.check.ok == (not ch10.blunder_variant(v.i))
        if not ch10.blunder_variant(v.i):
            # σ = 5″ angles, rounded to 1″: the station is within what the angle errors allow
            err = np.hypot(*(lab.resection.point - lab.true_station))
            assert err < 4 * ch10.SIGMA_ARCSEC * lab.resection.metres_per_arcsec + 0.02
        assert lab.resection.strength > 0.15
    t = labs[0].angles_table()
    assert list(t.index) == ["β₁", "β₂", "γ (check)"] and t["angle"].str.endswith("″").all()


def test_10_slips_are_named():
    v = SOME[0]
    lab = ch10.resection_lab(v)
    s = tasks.get("task-10-1").slips(v)
    hint = next(h for h in s["X_m"] if "swapped" in h)
    _raises("task-10-1", v, "swapped", X_m=s["X_m"][hint], Y_m=s["Y_m"][hint])
    ch = lab.check
    _raises("task-10-2", v, "sign", dgamma_arcsec=-ch.discrepancy_arcsec)
    _raises("task-10-2", v, "not to C", tol_arcsec=tasks.get("task-10-2").slips(v)["tol_arcsec"][
        "the tolerance uses the distance to the check point D, not to C"])


def test_10_hidden_checks_tie_the_answers_together():
    v = SOME[1]
    a = tasks.answers("task-10-1", v)
    # the direction angle from a station 4 cm off, within the visible 0.05 m: consistent — passes
    lab = ch10.resection_lab(v)
    X, Y = a["X_m"] + 0.04, a["Y_m"]
    g = _grade("task-10-1", v, X_m=X, alpha_PA_deg=c.direction_angle_deg([X, Y], lab.point("A")))
    assert g.passed
    # an angle within its visible tolerance that does not follow from the submitted station
    g = _grade("task-10-1", v, X_m=X, alpha_PA_deg=(a["alpha_PA_deg"] - 0.0019) % 360)
    assert g.visible_ok is False or not g.hidden_ok
    b = tasks.answers("task-10-2", v)
    g = _grade("task-10-2", v, dgamma_arcsec=b["dgamma_arcsec"] + 3.0)
    assert g.visible_ok and not g.hidden_ok and "gamma_calc_deg" in g.first_failure
    w = next(x for x in ALL if ch10.blunder_variant(x.i))
    bw = tasks.answers("task-10-2", w)
    assert bw["check_ok"] is False
    g = _grade("task-10-2", w, check_ok=True)
    assert not g.passed
