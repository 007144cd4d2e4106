"""Graded tasks of chapter 04 (guide §5): the tilt correction of the student's own photo — tables 5, 6, 7.

Every student gets their own photo of the plain of the virtual site
(:func:`aerophoto.labs.displacement.tilt_sheet`): their variant's f, 1:m,
tilt α and the direction λ of the positive principal vertical (counter-clockwise
from the photo's +x axis), nine points pricked in three zones along the principal
vertical (I, 1, 2 on the far side; II, 3, 4 near the isocentre; III, 5, 6 on the
near side) and the same points on a plan at 1:10 000.

* task 04.1 (:class:`Isocentre`): oc = −f·tg(α/2) with the guide's sign and the
  photo coordinates of the isocentre c;
* task 04.2 (:class:`TiltTable5`): the measurements and table 5 — l_пл, l_сн,
  m_i, m_част, m_cp and Δm_i/m_cp;
* task 04.3 (:class:`TiltTable6`): table 6 — r_c and φ of each point about c (φ
  counter-clockwise from the positive principal vertical), δα = −(r_c²·cos φ/f)·sin α
  and the number of corrections;
* task 04.4 (:class:`TiltTable7`): table 7 — the bases between the corrected
  points and the scales again.

Grading as in chapter 03 (:mod:`aerophoto.tasks.ch03`): measured values against
the truth within :data:`~aerophoto.tasks.ch03.TOL_XY_MM`, computed columns against
the reference with tolerances that cover the measuring error, and — hidden — each
column against the student's own previous one.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import displacement as d
from .. import geometry as g
from ..labs.displacement import TILT_BASES, TILT_NAMES, tilt_sheet
from .base import Answer, Method, Task
from .ch03 import (TOL_LEN_MM, TOL_XY_MM, chained_scales, corrected_count, numbers, scale_answers, scale_hidden, scale_spec,
                   sheet_answers, sheet_hidden, sheet_inputs)
from .rounding import consistency, numbers as number

__all__ = ["BASE_LABELS", "ZONES", "TOL_PHI_DEG", "Isocentre", "TiltTable5", "TiltTable6", "TiltTable7", "TASKS"]

BASE_LABELS = tuple(f"{a}-{b}" for a, b in TILT_BASES)
ZONES = ("I", "II", "III")
#: an angle φ about c from measured coordinates (points at least 12 mm from c), degrees
TOL_PHI_DEG = 1.0


def _floats(a) -> list:
    return [float(x) for x in np.ravel(a)]


# =========================================================================== task 04.1
@dataclass(frozen=True)
class Isocentre(Task):
    """Task 04.1: oc = −f·tg(α/2) with the guide's sign, and the photo coordinates of the isocentre c."""

    id = "task-04-1"
    title = "The isocentre on your photo"
    points = 2
    spec = (
        Answer("oc_mm", "o to c along the principal vertical, guide's sign, mm", unit="mm", tol_abs=0.05, printed=0.01),
        Answer("xc_mm", "x of the isocentre c, mm", unit="mm", tol_abs=0.05, printed=0.01),
        Answer("yc_mm", "y of the isocentre c, mm", unit="mm", tol_abs=0.05, printed=0.01),
    )

    def answers(self, v) -> dict:
        cam = g.Camera(v.f_mm)
        c = g.isocentre(cam, g.Pose(alpha_deg=v.alpha_deg, lambda_deg=v.lambda_deg))
        return {"oc_mm": d.isocentre_offset(v.f_mm, v.alpha_deg), "xc_mm": float(c[0]), "yc_mm": float(c[1])}

    def slips(self, v) -> dict:
        oc = d.isocentre_offset(v.f_mm, v.alpha_deg)
        on = d.nadir_offset(v.f_mm, v.alpha_deg)
        turned = "c lies on the principal vertical, turned by λ from the x axis"
        return {
            "oc_mm": {"that is on = f·tg α, the nadir point — the isocentre uses α/2": on,
                      "that is the nadir point's distance f·tg α — the isocentre uses α/2": -on},
            "xc_mm": {turned: oc},
            "yc_mm": {turned: 0.0},
        }

    methods = (Method("oc = −f·tg(α/2); c at |oc| from o along the principal vertical (direction λ)",
                      "guide §5 step 1"),)

    def hidden(self, v, got) -> list:
        """c lies at the distance |oc| from o (the student's own oc)."""
        oc = number(got.get("oc_mm"))
        return [consistency("|oc| from your xc_mm, yc_mm", None if oc is None else abs(oc), 0.01, math.hypot,
                            [(number(got.get("xc_mm")), 0.01), (number(got.get("yc_mm")), 0.01)])]


# =========================================================================== task 04.2
@dataclass(frozen=True)
class TiltTable5(Task):
    """Task 04.2: measure the nine points on the photo and the six bases on the plan; table 5 (§5 steps 6–8)."""

    id = "task-04-2"
    title = "Table 5 of your photo: the scales of the tilted photo"
    points = 4
    cross_variant = False
    spec = (
        Answer("x_mm", "x of I, 1, 2, II, 3, 4, III, 5, 6 on your photo, mm (measured)", unit="mm", kind="values",
               tol_abs=TOL_XY_MM, labels=TILT_NAMES, printed=0.1),
        Answer("y_mm", "y of the nine points on your photo, mm (measured)", unit="mm", kind="values",
               tol_abs=TOL_XY_MM, labels=TILT_NAMES, printed=0.1),
        Answer("lpl_mm", "plan lengths l_пл of I-1, I-2, II-3, II-4, III-5, III-6, mm (measured on the plan)",
               unit="mm", kind="values", tol_abs=TOL_LEN_MM, labels=BASE_LABELS, printed=0.1),
        *scale_spec(ZONES, BASE_LABELS, lsn_text="photo lengths l_сн of the six bases, mm", m_printed=1),
    )

    def inputs(self, v):
        """The student's lab sheet (:class:`aerophoto.labs.displacement.LabSheet`): photo and plan."""
        return sheet_inputs(tilt_sheet(int(v.i)))

    def answers(self, v) -> dict:
        sheet = tilt_sheet(int(v.i))
        return sheet_answers(sheet, sheet.work().table5)

    methods = (Method("readings with the measuring tool, then formulas 5.1, 5.2 column by column",
                      "guide §5 steps 6–8, table 5"),
               Method("each column from the previous one as written (to the printed units)",
                      "the guide's table 5 rounds every column before the next",
                      submit=lambda task, v: chained_scales(task.answers(v), TILT_BASES, 10000.0, 1)))

    def hidden(self, v, got) -> list:
        """l_сн from the student's own coordinates; every scale column from the student's previous one."""
        return sheet_hidden(got, tilt_sheet(int(v.i)), TILT_NAMES, TILT_BASES, m_printed=1)


# =========================================================================== task 04.3
@dataclass(frozen=True)
class TiltTable6(Task):
    """Task 04.3: r_c and φ about the isocentre, δα = −(r_c²·cos φ/f)·sin α, the corrections (§5 step 9, table 6)."""

    id = "task-04-3"
    title = "Table 6 of your photo: the tilt displacements"
    points = 4
    cross_variant = False
    spec = (
        Answer("rc_mm", "distances r_c of the nine points from c, mm", unit="mm", kind="values", tol_abs=0.3,
               labels=TILT_NAMES, printed=0.1),
        Answer("phi_deg", "angles φ from the + principal vertical, counter-clockwise, 0 ≤ φ < 360°", unit="°",
               kind="values", tol_abs=TOL_PHI_DEG, labels=TILT_NAMES, printed=0.1),
        Answer("da_mm", "tilt displacements δα of the nine points, mm", unit="mm", kind="values", tol_abs=0.02,
               tol_rel=0.03, labels=TILT_NAMES, printed=0.01),
        Answer("n_corr", "number of points corrected (|δα| > 0.2 mm)", integer=True),
    )

    def inputs(self, v):
        return sheet_inputs(tilt_sheet(int(v.i)))

    def answers(self, v) -> dict:
        t6 = tilt_sheet(int(v.i)).work().table6
        return {"rc_mm": _floats(t6.r_c_mm), "phi_deg": _floats(t6.phi_deg), "da_mm": _floats(t6.delta_approx_mm),
                "n_corr": int(t6.n_applied)}

    methods = (Method("r_c and φ about c, δα = −(r_c²·cos φ/f)·sin α", "guide §5 step 9, table 6"),)

    def hidden(self, v, got) -> list:
        """δα from the student's own r_c and φ; the count from the student's own δα."""
        n = len(TILT_NAMES)
        r, phi, da = (numbers(got.get(k), n) for k in ("rc_mm", "phi_deg", "da_mm"))
        sin_a = math.sin(math.radians(v.alpha_deg))
        return [consistency("δα from your r_c and φ", got.get("da_mm"), 0.01,
                            lambda r_, p_: -(r_**2) * np.cos(np.radians(p_)) / v.f_mm * sin_a,
                            [(r, 0.1), (phi, 0.1)], n=n),
                corrected_count("n_corr from your δα", got.get("n_corr"), da, 0.01, 0.2)]


# =========================================================================== task 04.4
@dataclass(frozen=True)
class TiltTable7(Task):
    """Task 04.4: the bases between the points corrected for tilt and the scales again (§5 steps 10–11, table 7)."""

    id = "task-04-4"
    title = "Table 7 of your photo: the scales after the tilt correction"
    points = 3
    cross_variant = False
    spec = scale_spec(ZONES, BASE_LABELS, lsn_name="lsn_corr_mm",
                      lsn_text="photo lengths l_сн of the six bases between the corrected points, mm", m_printed=1)

    def inputs(self, v):
        return sheet_inputs(tilt_sheet(int(v.i)))

    def answers(self, v) -> dict:
        return scale_answers(tilt_sheet(int(v.i)).work().table7, "lsn_corr_mm")

    methods = (Method("each point with |δα| > 0.2 mm moved by δα along the ray from c, then table 5's formulas",
                      "guide §5 steps 10–11, table 7"),
               Method("each column from the previous one as written (to the printed units)",
                      "the guide's table 7 rounds every column before the next",
                      submit=lambda task, v: chained_scales(task.answers(v), TILT_BASES, 10000.0, 1, "lsn_corr_mm")))

    def hidden(self, v, got) -> list:
        sheet = tilt_sheet(int(v.i))
        return scale_hidden(got, TILT_BASES, sheet.M, lsn_name="lsn_corr_mm", l_plan_truth=sheet.l_plan_mm,
                            m_printed=1)


TASKS = (Isocentre(), TiltTable5(), TiltTable6(), TiltTable7())
