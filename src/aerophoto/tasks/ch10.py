"""Graded tasks of chapter 10 (guide §11): the student's own resection and its check angle.

Each variant gets its own station on the virtual site (:func:`aerophoto.labs.ch10.resection_lab`):
a well-defined ground point P that is not yet a control point, and four
known points A, B, C, D of the site's control network round it.  The site's
coordinates are turned into plane coordinates like the guide's §11 table
(X north, Y east, metres, :data:`aerophoto.labs.ch10.GEODETIC_ORIGIN`).  The angles "measured" at
P are the true angles with a theodolite's random error (σ = 5″, rounded to
whole seconds); in every fifth variant (i = 4, 9, 14, …) the angle β₂ was
misread by several minutes — the check must catch it.

* task 10.1 (:class:`Resection`): the station's X, Y from A, B, C and β₁, β₂,
  and the direction angle from P to A;
* task 10.2 (:class:`CheckAngle`): the check angle from C to D computed from
  the station, its discrepancy from the measured one, the tolerance and the
  verdict (:func:`aerophoto.control.check_tolerance_arcsec`, 0.1 mm at 1:10 000).

The answers are computed from the rounded numbers the student reads.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import control as c
from ..labs.ch10 import PLAN_M, resection_lab
from .base import Answer, Hidden, Method, Task, Withheld
from .rounding import allowance, consistency, numbers, round_to, source, verdict_check

__all__ = ["station_inputs", "Resection", "CheckAngle", "TASKS"]

def station_inputs(v) -> Withheld:
    """The student's station as tasks 10.1–10.2 give it: the known points and the angles, not the resection."""
    return Withheld(resection_lab(v), ("resection", "check", "true_station", "blunder_arcsec"),
                    why="it is what tasks 10.1–10.2 ask you to compute")


# =========================================================================== task 10.1
@dataclass(frozen=True)
class Resection(Task):
    """Task 10.1: the station's X, Y by resection from A, B, C and β₁, β₂; the direction angle P → A."""

    id = "task-10-1"
    title = "Your resection"
    points = 4
    spec = (
        Answer("X_m", "X of the station P (north), m", unit="m", tol_abs=0.05, printed=0.01),
        Answer("Y_m", "Y of the station P (east), m", unit="m", tol_abs=0.05, printed=0.01),
        Answer("alpha_PA_deg", "direction angle from P to A, degrees", unit="°", tol_abs=0.002, period=360.0, printed=0.001),
    )

    def inputs(self, v) -> Withheld:
        return station_inputs(v)

    def answers(self, v) -> dict:
        lab = resection_lab(v)
        P = lab.resection.point
        return {"X_m": float(P[0]), "Y_m": float(P[1]), "alpha_PA_deg": c.direction_angle_deg(P, lab.point("A"))}

    def slips(self, v) -> dict:
        lab = resection_lab(v)
        a = lab.angles_deg
        out = {"X_m": {}, "Y_m": {}, "alpha_PA_deg": {}}
        tries = (("the angles were taken counter-clockwise: a theodolite reads them clockwise",
                  (360.0 - a["beta1"], 360.0 - a["beta2"])),
                 ("β₁ and β₂ are swapped: β₁ is measured from A to B, β₂ from B to C", (a["beta2"], a["beta1"])))
        for hint, (b1, b2) in tries:
            try:
                P = c.resect(lab.point("A"), lab.point("B"), lab.point("C"), b1, b2).point
            except ValueError:
                continue
            out["X_m"][hint] = float(P[0])
            out["Y_m"][hint] = float(P[1])
        P = lab.resection.point
        A = lab.point("A")
        out["alpha_PA_deg"]["that is the direction from A to P; the direction angle from P to A is 180° away"] = \
            c.direction_angle_deg(A, P)
        out["alpha_PA_deg"]["atan2 takes (ΔY, ΔX) here: X is north, Y east, and the angle runs clockwise from X"] = \
            float(np.degrees(np.arctan2(A[0] - P[0], A[1] - P[1])) % 360.0)
        return out

    methods = (Method("resection from A, B, C and β₁, β₂; the direction angle P → A by atan2(ΔY, ΔX), clockwise "
                      "from north", "guide §11; chapter 10"),)

    def hidden(self, v, got) -> list:
        # the direction angle must follow from the student's own station: atan2(Y_A − Y_P, X_A − X_P)
        A = resection_lab(v).point("A")
        X, Y = numbers(got.get("X_m")), numbers(got.get("Y_m"))
        a = numbers(got.get("alpha_PA_deg"))
        if X is None or Y is None or a is None or (X, Y) == (float(A[0]), float(A[1])):
            return [Hidden("alpha_PA_deg from your own station", None, None)]
        ref = c.direction_angle_deg([X, Y], A)

        def angle(x, y):  # the direction angle, kept on the side of 0°/360° the student's answer is on
            return ref + math.remainder(c.direction_angle_deg([x, y], A) - ref, 360.0)

        return [consistency("alpha_PA_deg from your own station", ref + math.remainder(a - ref, 360.0), 0.001,
                            angle, [source(self, got, "X_m"), source(self, got, "Y_m")],
                            target_cap=self.answer("alpha_PA_deg").tol_abs)]


# =========================================================================== task 10.2
@dataclass(frozen=True)
class CheckAngle(Task):
    """Task 10.2: the check angle C → D from the station, its discrepancy, the tolerance and the verdict."""

    id = "task-10-2"
    title = "The check angle"
    points = 4
    spec = (
        Answer("gamma_calc_deg", "check angle C → D computed from your station, degrees", unit="°", tol_abs=0.001,
               period=360.0, printed=0.001),
        Answer("dgamma_arcsec", "measured minus computed, arc-seconds", unit="″", tol_abs=4.0, printed=0.1),
        Answer("tol_arcsec", "tolerance of the check angle, arc-seconds", printed=0.1),
        Answer("check_ok", "True if the check holds", kind="bool",
               hint="compare |Δγ| with the tolerance ρ″·(0.1 mm · M)/S_PD"),
    )

    def inputs(self, v) -> Withheld:
        return station_inputs(v)

    def answers(self, v) -> dict:
        ch = resection_lab(v).check
        return {"gamma_calc_deg": ch.computed_deg, "dgamma_arcsec": ch.discrepancy_arcsec,
                "tol_arcsec": ch.tolerance_arcsec, "check_ok": bool(ch.ok)}

    def slips(self, v) -> dict:
        lab = resection_lab(v)
        ch = lab.check
        S_C = float(np.hypot(*(lab.point("C") - lab.resection.point)))
        return {
            "gamma_calc_deg": {"that is the angle from D to C; the check angle runs clockwise from C to D":
                               (360.0 - ch.computed_deg) % 360.0},
            "dgamma_arcsec": {"the sign: Δγ = measured − computed": -ch.discrepancy_arcsec},
            "tol_arcsec": {"the tolerance uses the distance to the check point D, not to C":
                           c.check_tolerance_arcsec(S_C, PLAN_M),
                           "0.1 mm at the plan's scale 1:10 000 is 1 m on the ground, not 0.1 m":
                           ch.tolerance_arcsec / 10.0},
        }

    methods = (Method("γ from the directions P → C and P → D of the station, Δγ = measured − computed, "
                      "tolerance ρ″·(0.1 mm · M)/S_PD", "guide §11; chapter 10"),
               Method("γ written to its stated 0.001°, Δγ from the written γ", "the task states γ to 0.001°",
                      submit=lambda task, v: task.written_gamma(v)))

    def written_gamma(self, v) -> dict:
        """γ as written to 0.001°, and Δγ from it (the tolerance and the verdict as before)."""
        lab = resection_lab(v)
        g = float(round_to(lab.check.computed_deg, 0.001))
        return {"gamma_calc_deg": g, "dgamma_arcsec": math.remainder(lab.angles_deg["gamma"] - g, 360.0) * 3600.0}

    def hidden(self, v, got) -> list:
        # Δγ must follow from the student's own computed angle, and the verdict from their own Δγ and tolerance
        lab = resection_lab(v)
        g, dg, tol = numbers(got.get("gamma_calc_deg")), numbers(got.get("dgamma_arcsec")), numbers(got.get("tol_arcsec"))
        out = [consistency("dgamma_arcsec from your own gamma_calc_deg", got.get("dgamma_arcsec"), 0.1,
                           lambda x: math.remainder(lab.angles_deg["gamma"] - x, 360.0) * 3600.0,
                           [(g, 0.001, self.answer("gamma_calc_deg").tol_abs)],
                           target_cap=self.answer("dgamma_arcsec").tol_abs)]
        if dg is None or tol is None:
            out.append(Hidden("check_ok from your own dgamma_arcsec and tol_arcsec", None, None, kind="bool"))
        else:
            out.append(verdict_check("check_ok from your own dgamma_arcsec and tol_arcsec", got.get("check_ok"), [dg],
                                     [tol], [allowance(dg, 0.1, 4.0) + allowance(tol, 0.1, 0.005 * abs(tol))]))
        return out


TASKS = (Resection(), CheckAngle())
