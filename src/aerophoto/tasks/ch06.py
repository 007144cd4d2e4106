"""Graded tasks of chapter 06 (guide §7): the student's own strip — its error triangles, table 8 and table 9.

Every student triangulates **their own strip** (:func:`aerophoto.labs.own.own_strip`:
photos 36 … 39 with their variant's f, 1:m and p_x, at a place of their own
on the virtual site — the same four photos they glue into a fotoschema in
chapter 05).  The work of guide §7 / §13 is done on it (:func:`aerophoto.labs.ch06.lab_strip`):

1. the working centres, orienting, tie and control points are pricked on every
   photo with the guide's 0.1 mm (seed: the variant number) and the direction
   templates drawn (:func:`aerophoto.triangulation.measure_templates`);
2. the templates are laid into a free strip at a scale of the variant's own,
   q = 0.92 … 0.969 of the plan's for i < 50 and 1.03 … 1.079 for i ≥ 50 (so
   half the class lays the strip too small, half too large: corrections away
   from and towards the centre), :func:`aerophoto.labs.ch06.free_scale_ratio`;
3. the common tracing is "measured": every point of it read to 0.1 mm with a
   bounded reading error (:func:`aerophoto.labs.own.read_mm`).

What the student reads (:class:`aerophoto.labs.ch06.StripReadings`, all in the Russian geodetic
convention of the guide's table 8 — x north/up, y east/right, directions
clockwise from +x, :mod:`aerophoto.triangulation.geodetic`):

* ``rays`` — at each tie point the three rays of the laid templates (the centre
  on the sheet and the ray's direction): task 06.1, the error triangles;
* ``control`` — the four control points: coordinates X, Y (m) and their
  positions on the free strip (mm): task 06.2, table 8;
* ``points`` — every point on the common tracing (tie points are not
  transferred, guide §13 step 7): task 06.3, table 9.

The reference answers are computed **from those readings**, as the student
computes them; the tests hold them against the truth.  Chapter 12
(:mod:`aerophoto.tasks.ch12`) works on the same strip (tables 12 and 13).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import plane
from .. import triangulation as tri
from ..labs.ch06 import CENTRE, POINT_ORDER, TIE_POINTS, StripReadings, shared_readings, strip_readings
from .base import Answer, Hidden, Task

__all__ = ["RING", "RING_LABELS", "CORRECTION_POINTS", "TOL_COEFF", "triangles_from_rays", "coefficients_from_control",
           "corrections_from_points", "ErrorTriangles", "RingCoefficients", "CorrectionsForReduction",
           "CorrectionsTask", "TASKS"]

#: the four bases of a table-8 ring around the strip, in the order of task 06.2
RING = (("36/1", "39/1"), ("39/1", "39/2"), ("39/2", "36/2"), ("36/2", "36/1"))
RING_LABELS = tuple(f"{a}–{b}" for a, b in RING)
#: the points whose corrections task 06.3 asks for: every other point of the common tracing
CORRECTION_POINTS = tuple(n for n in POINT_ORDER if n != CENTRE)
#: the coefficient is printed to three decimals: half a unit of the last digit
TOL_COEFF = 0.0005
# =========================================================================== the work, from the readings
def triangles_from_rays(rays: pd.DataFrame) -> pd.DataFrame:
    """The error triangle at every tie point from the table of rays: the three sides and the largest, mm.

    Each pair of rays (centre (x, y), direction α clockwise from +x) is
    intersected; the triangle's sides are the distances between the three
    intersections (:func:`aerophoto.plane.error_triangle`, which reads the
    geodetic convention as it is — :mod:`aerophoto.triangulation.geodetic`).
    """
    out = []
    for name in dict.fromkeys(rays.index.get_level_values(0)):
        r = rays.loc[name]
        O = r[["centre x, mm", "centre y, mm"]].to_numpy(dtype=float)
        A = np.radians(r["direction α, °"].to_numpy(dtype=float))
        _V, sides = plane.error_triangle(O, A)
        out.append((name, *sides, float(sides.max())))
    return pd.DataFrame(out, columns=["tie point", "side 1, mm", "side 2, mm", "side 3, mm", "largest, mm"]
                        ).set_index("tie point")


def coefficients_from_control(control: pd.DataFrame, M: float, pairs) -> tri.ReductionCoefficients:
    """Table 8/12 from the control table: l_base from the coordinates (plan mm at 1/M), l_template from the strip."""
    base = control[["X (north), m", "Y (east), m"]].to_numpy(dtype=float) * 1000.0 / float(M)
    strip = control[["x on the strip, mm", "y on the strip, mm"]].to_numpy(dtype=float)
    return tri.reduction_coefficients(list(control.index), base, strip, pairs=pairs)


def corrections_from_points(points: pd.DataFrame, centre: str, k: float, names) -> tuple:
    """(r, v) for the named points: r from the centre on the common tracing, v = r·(k − 1), mm (table 9/13)."""
    xy = points[["x on the strip, mm", "y on the strip, mm"]]
    C = xy.loc[centre].to_numpy(dtype=float)
    P = xy.loc[list(names)].to_numpy(dtype=float)
    r = np.hypot(*(P - C).T)
    return r, r * (float(k) - 1.0)


def _numbers(x, n: int):
    """``x`` as a list of ``n`` finite floats, or None (not answered, wrong length, not numbers)."""
    if x is None or x is Ellipsis or isinstance(x, (str, bytes, dict, bool)):
        return None
    try:
        out = [float(e) for e in (x.tolist() if hasattr(x, "tolist") else x)]
    except (TypeError, ValueError):
        return None
    return out if len(out) == n and all(math.isfinite(e) for e in out) else None


def _verdict_hidden(name: str, got_verdict, deviations, tols, margin: float) -> Hidden:
    """A verdict against the student's own numbers: True if all |d| ≤ tol, False if one exceeds it;
    within ``margin`` of a tolerance either verdict is consistent."""
    d, t = np.abs(np.asarray(deviations, dtype=float)), np.asarray(tols, dtype=float)
    if np.all(d <= t - margin):
        expected = True
    elif np.any(d > t + margin):
        expected = False
    else:
        expected = bool(got_verdict) if isinstance(got_verdict, (bool, np.bool_)) else True
    return Hidden(name, got_verdict, expected, kind="bool")


# =========================================================================== task 06.1
@dataclass(frozen=True)
class ErrorTriangles(Task):
    """Task 06.1: the error triangle at every tie point of the laid strip, and the 0.3 mm check (§7, §13 step 6)."""

    id = "task-06-1"
    title = "The error triangles of your strip"
    points = 3
    spec = (
        Answer("triangle_mm", "largest side of the error triangle at a, b, c, d, mm", unit="mm", kind="values",
               tol_abs=0.01, labels=TIE_POINTS),
        Answer("triangles_ok", "True if every side is within 0.3 mm", kind="bool",
               hint="compare the largest side of every triangle with 0.3 mm (guide §7)."),
    )

    def inputs(self, v) -> StripReadings:
        """The student's readings: ``rays_table()`` is what this task uses."""
        return strip_readings(v)

    def answers(self, v) -> dict:
        t = triangles_from_rays(shared_readings(v).rays)
        side = [float(t.loc[n, "largest, mm"]) for n in TIE_POINTS]
        return {"triangle_mm": side, "triangles_ok": bool(max(side) <= tri.TRIANGLE_TOL_MM)}

    def hidden(self, v, got) -> list:
        """The verdict must follow from the student's own sides."""
        s = _numbers(got.get("triangle_mm"), len(TIE_POINTS))
        if s is None:
            return [Hidden("triangles_ok from your sides", None, None, kind="bool")]
        return [_verdict_hidden("triangles_ok from your sides", got.get("triangles_ok"), s,
                                [tri.TRIANGLE_TOL_MM] * len(s), 0.01)]


# =========================================================================== task 06.2
@dataclass(frozen=True)
class RingCoefficients(Task):
    """Task 06.2: table 8 for the four bases around the strip — l_осн, l_воск, k, the mean, the 0.003 check."""

    id = "task-06-2"
    title = "Reduction coefficients of your strip (table 8)"
    points = 4
    spec = (
        Answer("l_base_mm", "base lengths on the plan l_осн, mm", unit="mm", kind="values", tol_abs=0.05,
               labels=RING_LABELS),
        Answer("l_template_mm", "the same on the free strip l_воск, mm", unit="mm", kind="values", tol_abs=0.05,
               labels=RING_LABELS),
        Answer("k_bases", "four reduction coefficients k = l_осн/l_воск", kind="values", tol_abs=TOL_COEFF,
               labels=RING_LABELS),
        Answer("k_mean", "their mean", tol_abs=TOL_COEFF),
        Answer("spread_ok", "True if every |k − mean| is within its tolerance", kind="bool",
               hint="compare every |k − mean| with 0.003 (0.006 on a base shorter than 133 mm on the plan)."),
    )

    def inputs(self, v) -> StripReadings:
        """The student's readings: ``control_table()`` is what this task uses."""
        return strip_readings(v)

    def answers(self, v) -> dict:
        c = coefficients_from_control(shared_readings(v).control, float(v.M), RING)
        return {"l_base_mm": [float(x) for x in c.l_base_mm], "l_template_mm": [float(x) for x in c.l_template_mm],
                "k_bases": [float(x) for x in c.k], "k_mean": float(c.k_mean), "spread_ok": bool(c.all_ok)}

    def slips(self, v) -> dict:
        k_mean = self.answers(v)["k_mean"]
        return {"k_mean": {"this is l_воск / l_осн — the coefficient is base over template": 1.0 / k_mean}}

    def hidden(self, v, got) -> list:
        """k from the student's own lengths, the mean of their own k, the verdict from their own deviations."""
        n = len(RING)
        lb, lt, ks = (_numbers(got.get(k), n) for k in ("l_base_mm", "l_template_mm", "k_bases"))
        out = []
        for j, lab in enumerate(RING_LABELS):
            ok = lb is not None and lt is not None and ks is not None and lt[j] > 0
            out.append(Hidden(f"k of {lab} from your lengths", ks[j] if ok else None, lb[j] / lt[j] if ok else None,
                              tol_abs=TOL_COEFF))
        mean = float(np.mean(ks)) if ks is not None else None
        out.append(Hidden("k_mean is the mean of your k_bases", got.get("k_mean") if ks is not None else None, mean,
                          tol_abs=TOL_COEFF))
        if ks is None:
            out.append(Hidden("spread_ok from your k_bases", None, None, kind="bool"))
        else:
            tol = coefficients_from_control(shared_readings(v).control, float(v.M), RING).tol
            out.append(_verdict_hidden("spread_ok from your k_bases", got.get("spread_ok"), np.array(ks) - mean, tol,
                                       TOL_COEFF))
        return out


# =========================================================================== task 06.3
@dataclass(frozen=True)
class CorrectionsTask(Task):
    """Base of tasks 06.3 and 12.3: distances r from a central working centre and corrections v = r·(k − 1)."""

    centre = CENTRE
    names_ = CORRECTION_POINTS
    pairs = RING

    def inputs(self, v) -> StripReadings:
        """The student's readings: ``points_table()`` is what this task uses."""
        return strip_readings(v)

    def _k(self, v) -> float:
        return coefficients_from_control(shared_readings(v).control, float(v.M), self.pairs).k_mean

    def answers(self, v) -> dict:
        r, vv = corrections_from_points(shared_readings(v).points, self.centre, self._k(v), self.names_)
        return {"r_mm": [float(x) for x in r], "v_mm": [float(x) for x in vv]}

    def slips(self, v) -> dict:
        return {}

    def hidden(self, v, got) -> list:
        """Every v must be the student's own r times one and the same k − 1 (within the 0.1 mm the guide prints)."""
        n = len(self.names_)
        r, vv = _numbers(got.get("r_mm"), n), _numbers(got.get("v_mm"), n)
        if r is None or vv is None:
            return [Hidden("v_mm proportional to your r_mm", None, None)]
        r, vv = np.array(r), np.array(vv)
        far = r > 30.0
        if not np.any(far) or np.any(r < 0):
            return [Hidden("v_mm proportional to your r_mm", None, None)]
        k1 = float(np.median(vv[far] / r[far]))
        return [Hidden(f"v_mm at {name} = r·(k − 1) with your r and one k", float(vv[j]), float(k1 * r[j]),
                       tol_abs=0.06) for j, name in enumerate(self.names_)]


@dataclass(frozen=True)
class CorrectionsForReduction(CorrectionsTask):
    """Task 06.3: table 9 — r from working centre 37 and v = r·(k − 1) for every other point of the common tracing."""

    id = "task-06-3"
    title = "Corrections for reduction (table 9)"
    points = 3
    spec = (
        Answer("r_mm", "distances from centre 37, in the table's order (37 left out), mm", unit="mm", kind="values",
               tol_abs=0.05, labels=CORRECTION_POINTS),
        Answer("v_mm", "corrections v = r·(k − 1), same order, mm", unit="mm", kind="values", tol_abs=0.05,
               tol_rel=0.02, labels=CORRECTION_POINTS),
    )


TASKS = (ErrorTriangles(), RingCoefficients(), CorrectionsForReduction())
