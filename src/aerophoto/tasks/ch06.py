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

from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import plane
from .. import triangulation as tri
from ..labs.ch06 import CENTRE, POINT_ORDER, TIE_POINTS, StripReadings, shared_readings, strip_readings
from .base import Answer, Hidden, Method, Task
from .rounding import allowance, consistency, numbers, round_to, verdict_check

__all__ = ["RING", "RING_LABELS", "CORRECTION_POINTS", "TOL_COEFF", "TOL_MEAN", "TOL_SPREAD", "TOL_V_REL", "triangles_from_rays", "coefficients_from_control",
           "corrections_from_points", "ErrorTriangles", "RingCoefficients", "CorrectionsForReduction",
           "CorrectionsTask", "spread_checks", "rounded_coefficients", "corrections_with_written_k", "TASKS"]

#: the four bases of a table-8 ring around the strip, in the order of task 06.2
RING = (("36/1", "39/1"), ("39/1", "39/2"), ("39/2", "36/2"), ("36/2", "36/1"))
RING_LABELS = tuple(f"{a}–{b}" for a, b in RING)
#: the points whose corrections task 06.3 asks for: every other point of the common tracing
CORRECTION_POINTS = tuple(n for n in POINT_ORDER if n != CENTRE)
#: the coefficient is printed to three decimals: half a unit of the last digit
TOL_COEFF = 0.0005
#: the mean of k written to three decimals, itself written to three decimals (guide table 8): two roundings,
#: and what writing the lengths to 0.01 mm moves k
TOL_MEAN = 0.0011
#: Δk from the written k and the written mean (guide table 12): the same, once more
TOL_SPREAD = 0.0016
#: a correction v = r·(k − 1) with the written k_mean: r·0.0011 on |k − 1| ≥ 0.03, 3.7 % at most
TOL_V_REL = 0.04
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
    out = numbers(x, n)
    return None if out is None else [float(e) for e in out]


def _verdict_hidden(name: str, got_verdict, deviations, tols, allowances) -> Hidden:
    """A verdict against the student's own numbers: True if all |d| ≤ tol, False if one exceeds it; where a
    deviation is within its rounding ``allowances`` of its tolerance, either verdict is consistent."""
    return verdict_check(name, got_verdict, deviations, tols, allowances)


def spread_checks(got: dict, n: int, tol, *, dk_max: bool = False) -> list:
    """Hidden checks of a set of ``n`` reduction coefficients (tables 8, 12): the mean of the student's own k,
    (for table 12) the largest |Δk| from them, and the verdict from their own deviations."""
    ks = numbers(got.get("k_bases"), n)
    out = [consistency("k_mean is the mean of your k_bases", got.get("k_mean"), 0.001, lambda k: float(np.mean(k)),
                       [(ks, 0.001)])]
    if dk_max:
        out.append(consistency("dk_max from your k_bases", got.get("dk_max"), 0.001,
                               lambda k: float(np.max(np.abs(k - np.mean(k)))), [(ks, 0.001)]))
    if ks is None:
        return out + [Hidden("spread_ok from your k_bases", None, None, kind="bool")]
    dev = ks - float(np.mean(ks))
    a = 2.0 * np.asarray(allowance(ks, 0.001), dtype=float)  # k and the mean each as written
    return out + [_verdict_hidden("spread_ok from your k_bases", got.get("spread_ok"), dev, tol, a)]


def rounded_coefficients(task, v) -> dict:
    """Table 8/12 as the guide computes it: every k written to three decimals, the mean of the written k written to
    three decimals, Δk from those (the method of guide §7, table 8)."""
    ref = task.answers(v)
    k = round_to(np.asarray(ref["k_bases"], float), 0.001)
    mean = float(round_to(float(np.mean(k)), 0.001))
    out = {"k_bases": [float(x) for x in k], "k_mean": mean}
    if "dk_max" in ref:
        out["dk_max"] = float(round_to(float(np.max(np.abs(k - mean))), 0.001))
    return out


# =========================================================================== task 06.1
@dataclass(frozen=True)
class ErrorTriangles(Task):
    """Task 06.1: the error triangle at every tie point of the laid strip, and the 0.3 mm check (§7, §13 step 6)."""

    id = "task-06-1"
    title = "The error triangles of your strip"
    points = 3
    spec = (
        Answer("triangle_mm", "largest side of the error triangle at a, b, c, d, mm", unit="mm", kind="values",
               tol_abs=0.01, labels=TIE_POINTS, printed=0.001),
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

    methods = (Method("the three rays intersected two by two (forward intersection), the triangle's largest side",
                      "guide §7, §13 step 6"),)

    def hidden(self, v, got) -> list:
        """The verdict must follow from the student's own sides."""
        s = numbers(got.get("triangle_mm"), len(TIE_POINTS))
        if s is None:
            return [Hidden("triangles_ok from your sides", None, None, kind="bool")]
        return [_verdict_hidden("triangles_ok from your sides", got.get("triangles_ok"), s,
                                [tri.TRIANGLE_TOL_MM] * len(s), allowance(s, 0.001))]


# =========================================================================== task 06.2
@dataclass(frozen=True)
class RingCoefficients(Task):
    """Task 06.2: table 8 for the four bases around the strip — l_осн, l_воск, k, the mean, the 0.003 check."""

    id = "task-06-2"
    title = "Reduction coefficients of your strip (table 8)"
    points = 4
    spec = (
        Answer("l_base_mm", "base lengths on the plan l_осн, mm", unit="mm", kind="values", tol_abs=0.05,
               labels=RING_LABELS, printed=0.01),
        Answer("l_template_mm", "the same on the free strip l_воск, mm", unit="mm", kind="values", tol_abs=0.05,
               labels=RING_LABELS, printed=0.01),
        Answer("k_bases", "four reduction coefficients k = l_осн/l_воск", kind="values", tol_abs=TOL_COEFF,
               labels=RING_LABELS, printed=0.001),
        Answer("k_mean", "their mean", tol_abs=TOL_MEAN, printed=0.001),
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

    methods = (Method("l_осн from the coordinates at 1:M, l_воск on the strip, k = l_осн/l_воск, their mean",
                      "guide §7, table 8"),
               Method("k and the mean written to three decimals, as the guide's table 8 prints them",
                      "guide §7, table 8", submit=rounded_coefficients))

    def hidden(self, v, got) -> list:
        """k from the student's own lengths, the mean of their own k, the verdict from their own deviations."""
        n = len(RING)
        lb, lt = numbers(got.get("l_base_mm"), n), numbers(got.get("l_template_mm"), n)
        tol = coefficients_from_control(shared_readings(v).control, float(v.M), RING).tol
        return [consistency("k from your lengths", got.get("k_bases"), 0.001, lambda b, t: b / t,
                            [(lb, 0.01), (lt, 0.01)], n=n),
                *spread_checks(got, n, tol)]


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

    def written_k(self, v) -> float:
        """k_mean as the guide's table writes it: the mean of the k written to three decimals, to three decimals."""
        c = coefficients_from_control(shared_readings(v).control, float(v.M), self.pairs)
        return float(round_to(float(np.mean(round_to(np.asarray(c.k, float), 0.001))), 0.001))

    def hidden(self, v, got) -> list:
        """Every v must be the student's own r times one and the same k − 1: k − 1 fitted to their own r and v,
        each v within what the rounding of r and v moves it."""
        n = len(self.names_)
        r, vv = numbers(got.get("r_mm"), n), numbers(got.get("v_mm"), n)
        if r is None or vv is None or np.any(r <= 0):
            return [Hidden("v_mm = r·(k − 1) with your r and one k", None, None)]

        def one_k(r_, v_):
            return r_ * float(np.sum(v_ * r_) / np.sum(r_ * r_))

        return [consistency("v_mm = r·(k − 1) with your r and one k", got.get("v_mm"), 0.1, one_k,
                            [(r, 0.01), (vv, 0.1)], n=n)]


@dataclass(frozen=True)
class CorrectionsForReduction(CorrectionsTask):
    """Task 06.3: table 9 — r from working centre 37 and v = r·(k − 1) for every other point of the common tracing."""

    id = "task-06-3"
    title = "Corrections for reduction (table 9)"
    points = 3
    spec = (
        Answer("r_mm", "distances from centre 37, in the table's order (37 left out), mm", unit="mm", kind="values",
               tol_abs=0.05, labels=CORRECTION_POINTS, printed=0.01),
        Answer("v_mm", "corrections v = r·(k − 1), same order, mm", unit="mm", kind="values", tol_abs=0.05,
               tol_rel=TOL_V_REL, labels=CORRECTION_POINTS, printed=0.1),
    )
    methods = (Method("r from centre 37 on the common tracing, v = r·(k − 1) with k_mean of table 8",
                      "guide §7, table 9"),
               Method("k_mean as the guide writes it (three decimals, from k written to three decimals)",
                      "guide §7, tables 8–9", submit=lambda task, v: corrections_with_written_k(task, v)))


def corrections_with_written_k(task, v) -> dict:
    """Table 9/13 with the k the guide's table writes (:meth:`CorrectionsTask.written_k`)."""
    r, vv = corrections_from_points(shared_readings(v).points, task.centre, task.written_k(v), task.names_)
    return {"r_mm": [float(x) for x in r], "v_mm": [float(x) for x in vv]}


TASKS = (ErrorTriangles(), RingCoefficients(), CorrectionsForReduction())
