"""Helpers shared by the content tests (the chapters' task files import them: ``from .conftest import …``)."""

import math

import numpy as np
import pytest

from aerophoto import checks, tasks
from aerophoto.course import score
from aerophoto.tasks import ch06, ch12
from aerophoto.variants import variant_for_index

#: every variant, 00–99
ALL = [variant_for_index(i) for i in range(100)]


def _grade(task_id, v, **changes):
    """The trusted grading of the reference answers of ``task_id`` with ``changes``."""
    return score.grade_task(task_id, v, {**tasks.answers(task_id, v), **changes})


def _raises(task_id, v, match, **changes):
    """check_task on the reference answers with ``changes`` names the slip ``match``."""
    with pytest.raises(checks.WrongAnswer, match=match):
        checks.check_task(task_id, v, **{**tasks.answers(task_id, v), **changes})


def _hidden_failed(task_id, v, got) -> list:
    """The names of the hidden checks that fail for the answers ``got``."""
    g = score.grade_task(task_id, v, got)
    return [name for name, ok, _, hidden in g.checks if hidden and not ok]


# --------------------------------------------------------------------------- chapters 06 and 12: one strip
def _intersect(A, a_deg, B, b_deg):
    """Forward intersection in the geodetic convention, as the task text writes it."""
    ua = np.array([math.cos(math.radians(a_deg)), math.sin(math.radians(a_deg))])
    ub = np.array([math.cos(math.radians(b_deg)), math.sin(math.radians(b_deg))])
    cross = lambda p, q: p[0] * q[1] - p[1] * q[0]  # noqa: E731
    s = cross(B - A, ub) / cross(ua, ub)
    return A + s * ua


def _by_hand(task_id, v):
    """What a student computes by hand from the strip of chapters 06 and 12 (tasks 06.1–06.3, 12.2, 12.3)."""
    r = tasks.inputs(task_id, v)
    if task_id == "task-06-1":
        sides = []
        for name in ("a", "b", "c", "d"):
            t = r.rays_table().loc[name]
            C = t[["centre x, mm", "centre y, mm"]].to_numpy()
            al = t["direction α, °"].to_numpy()
            P = [_intersect(C[i], al[i], C[j], al[j]) for i, j in ((0, 1), (1, 2), (0, 2))]
            sides.append(max(np.hypot(*(P[0] - P[1])), np.hypot(*(P[1] - P[2])), np.hypot(*(P[0] - P[2]))))
        return {"triangle_mm": sides, "triangles_ok": max(sides) <= 0.3}
    c = r.control_table()
    pairs = ch06.RING if task_id in ("task-06-2", "task-06-3") else ch12.TABLE12
    lb = [math.dist(c.loc[a, ["X (north), m", "Y (east), m"]], c.loc[b, ["X (north), m", "Y (east), m"]]) * 1000 / 10000
          for a, b in pairs]
    lt = [math.dist(c.loc[a, ["x on the strip, mm", "y on the strip, mm"]],
                    c.loc[b, ["x on the strip, mm", "y on the strip, mm"]]) for a, b in pairs]
    k = [x / y for x, y in zip(lb, lt)]
    km = sum(k) / len(k)
    ok = all(abs(x - km) <= 0.003 for x in k)  # no base is short (< 133 mm) at these scales
    if task_id == "task-06-2":
        return {"l_base_mm": lb, "l_template_mm": lt, "k_bases": k, "k_mean": km, "spread_ok": ok}
    if task_id == "task-12-2":
        return {"k_bases": k, "k_mean": km, "dk_max": max(abs(x - km) for x in k), "spread_ok": ok}
    p = r.points_table()
    centre = "37" if task_id == "task-06-3" else "38"
    C = p.loc[centre, ["x on the strip, mm", "y on the strip, mm"]]
    names = [n for n in p.index if n != centre]
    rr = [math.dist(p.loc[n, ["x on the strip, mm", "y on the strip, mm"]], C) for n in names]
    return {"r_mm": rr, "v_mm": [x * (round(km, 3) - 1) for x in rr]}  # k rounded as the guide writes it
