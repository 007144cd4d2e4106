"""Graded tasks of chapter 11 (guide §12): the student's paper deformation and substrate, and a four-point rectification.

* task 11.1 (:class:`Substrate`): the student's own table 11 (:func:`aerophoto.labs.ch11.paper_lab`):
  six lengths on the control grid (5 mm squares: two lines, two other lines and
  two diagonals of the rectangle they span, the numbers of squares drawn from
  the variant) and on the contact print (to 0.1 mm, with a paper deformation
  of the variant, sometimes shrinking, sometimes stretching); f and m from the
  variant, the base at 1:M = 1:10 000.  The student computes
  K_d = [δl]/[l₀] and t = K_d·f·(K_t + 1), K_t = m/M.
* task 11.2 (:class:`FourPointRectification`): the student's photo of the
  virtual site (:func:`aerophoto.labs.ch11.rectification_lab`): variant f, 1:m, α = 3°, λ, a
  heading and a centre drawn from the variant; four control points near the
  corners of the working area and two check points, measured on the photo
  (pricking error σ = 0.03 mm, to 0.01 mm) and on the base (1:10 000, to
  0.01 mm).  The student fits the projective transformation on the four
  points and gives the residuals at the two check points and the 0.4 mm
  verdict.  The site is not flat (30 m of relief): what the residuals show is
  mostly relief displacement, which rectification does not remove.

Answers are computed from the rounded numbers the student reads.  The
chapter's worked example uses the guide's own numbers (f = 108 mm, 1:15 000,
base 1:5000: :func:`aerophoto.labs.ch11.example_rectification_lab`), which no variant has.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .. import plane
from .. import rectify as rf
from ..labs.ch11 import paper_lab, rectification_lab
from .base import Answer, Hidden, Method, Task, Withheld, submitted_number
from .rounding import allowance, consistency, numbers, round_sig, sig_unit, verdict_check

__all__ = ["TOL_K", "TOL_T", "K_DIGITS", "Substrate", "FourPointRectification", "TASKS"]


#: K_d's tolerance: the accepted ways of summing table 11 (the diagonals exact or as shown, over [l₀] or [l_i])
#: differ by up to 2.5 % — K_d itself is a small difference of readings to 0.1 mm, uncertain by far more
TOL_K = 0.03
#: t follows K_d: the same, plus t's own rounding
TOL_T = 0.035
#: the significant digits K_d may be written with (t's hidden check admits that rounding of K_d)
K_DIGITS = 3


@dataclass(frozen=True)
class Substrate(Task):
    """Task 11.1: the mean paper deformation K_d and the substrate thickness t of the student's table 11."""

    id = "task-11-1"
    title = "Your paper's deformation and the substrate"
    points = 3
    spec = (
        Answer("K_d", "mean deformation coefficient [δl]/[l₀] (δl = l₀ − l_i)", tol_rel=TOL_K, printed=1e-08),
        Answer("t_mm", "substrate thickness K_d·f·(K_t + 1), mm, with its sign", unit="mm", tol_rel=TOL_T,
               printed=0.0001),
    )
    methods = (Method("K_d = [δl]/[l₀] with l₀ as table 11 gives it (to 0.01 mm), t = K_d·f·(K_t + 1)",
                      "guide §12 step 2, table 11"),
               Method("the diagonals' l₀ computed exactly, 5 mm·√(a² + b²)", "chapter 11 teaches l₀ = 5 mm·n and "
                      "the diagonals by Pythagoras; the table shows them to 0.01 mm, which moves K_d by up to 2.3 %",
                      submit=lambda task, v: task.other_sums(v, exact=True)),
               Method("[δl] divided by the print's [l_i]", "the same to first order in K_d (they differ by K_d², "
                      "≤ 0.2 % of K_d here)", submit=lambda task, v: task.other_sums(v, over_li=True)),
               Method(f"K_d written to {K_DIGITS} significant digits (−0.00131), t from the unrounded K_d",
                      "K_d is a sum of differences of readings to 0.01 mm: three digits are all it holds",
                      submit=lambda task, v: {"K_d": round_sig(task.answers(v)["K_d"], K_DIGITS)}))

    def other_sums(self, v, *, exact: bool = False, over_li: bool = False) -> dict:
        """K_d (and t from it) with the diagonals' l₀ exact and/or divided by [l_i] (the accepted methods)."""
        lab = paper_lab(v)
        l0 = np.asarray(lab.l0_mm, float) if exact else np.round(lab.l0_mm, 2)
        li = np.asarray(lab.li_mm, float)
        K = float((l0 - li).sum() / (li.sum() if over_li else l0.sum()))
        return {"K_d": K, "t_mm": rf.substrate_thickness_mm(K, lab.f_mm, rf.enlargement(lab.m, lab.M))}

    def inputs(self, v) -> Withheld:
        return Withheld(paper_lab(v), ("deformation",), why="K_d is what task 11.1 asks you to compute")

    def answers(self, v) -> dict:
        lab = paper_lab(v)
        K = lab.deformation.K_d
        return {"K_d": K, "t_mm": rf.substrate_thickness_mm(K, lab.f_mm, rf.enlargement(lab.m, lab.M))}

    def slips(self, v) -> dict:
        lab = paper_lab(v)
        pdf = lab.deformation
        K = pdf.K_d
        Kt = rf.enlargement(lab.m, lab.M)
        t = rf.substrate_thickness_mm(K, lab.f_mm, Kt)
        return {
            "K_d": {"the sign: δl = l₀ − l_i (grid minus print)": -K},
            "t_mm": {"the sign: t has the sign of K_d (the guide's example prints it without)": -t,
                     "K_t = m/M is the enlargement from the photo to the base, not M/m":
                         K * lab.f_mm * (1.0 / Kt + 1.0),
                     "the formula has K_t + 1, not K_t": K * lab.f_mm * Kt},
        }

    def hidden(self, v, got) -> list:
        # t must follow from the student's own K_d: t = K_d·f·(m/M + 1)
        lab = paper_lab(v)
        factor = lab.f_mm * (rf.enlargement(lab.m, lab.M) + 1.0)
        # K_d may be written to three significant digits (−0.00131) and t computed from it or from more digits
        K = numbers(got.get("K_d"))
        return [consistency("t_mm from your own K_d", got.get("t_mm"), 0.0001, lambda K_: K_ * factor,
                            [(K, None if K is None else sig_unit(K, K_DIGITS))])]



def _residual_lengths(lab, transform) -> np.ndarray:
    df = lab.points[lab.points["role"] == "check"]
    P = df[["x photo, mm", "y photo, mm"]].to_numpy(float)
    Q = df[["x base, mm", "y base, mm"]].to_numpy(float)
    return np.hypot(*(Q - transform.apply(P)).T)


@dataclass(frozen=True)
class FourPointRectification(Task):
    """Task 11.2: the residuals at the two check points after a four-point projective fit, and the 0.4 mm verdict."""

    id = "task-11-2"
    title = "Your four-point rectification"
    points = 3
    spec = (
        Answer("d1_mm", "residual length at check point K1, mm on the base", unit="mm", tol_abs=0.02, printed=0.01),
        Answer("d2_mm", "residual length at check point K2, mm on the base", unit="mm", tol_abs=0.02, printed=0.01),
        Answer("rect_ok", "True if both are within 0.4 mm", kind="bool",
               hint="compare both residuals with the guide's 0.4 mm"),
    )

    def inputs(self, v) -> Withheld:
        return Withheld(rectification_lab(v), ("rectification",), why="the fit is what task 11.2 asks you to make")

    def answers(self, v) -> dict:
        r = rectification_lab(v).rectification
        d = r.check_lengths_mm
        return {"d1_mm": float(d[0]), "d2_mm": float(d[1]), "rect_ok": bool(np.all(d <= rf.TOLERANCE_MM))}

    def slips(self, v) -> dict:
        lab = rectification_lab(v)
        ctrl = lab.points[lab.points["role"] == "control"]
        P = ctrl[["x photo, mm", "y photo, mm"]].to_numpy(float)
        Q = ctrl[["x base, mm", "y base, mm"]].to_numpy(float)
        aff = _residual_lengths(lab, plane.fit_affine(P, Q))
        d = lab.rectification.check_lengths_mm
        Kt = rf.enlargement(float(v.m), lab.M)
        out = {}
        for k, name in enumerate(("d1_mm", "d2_mm")):
            out[name] = {"that is an affine fit: four points fix a projective (8-parameter) transformation": float(aff[k]),
                         "that is in photo mm: the residuals are measured on the base": float(d[k] / Kt),
                         "the residuals are already on the base: do not multiply them by K_t again": float(d[k] * Kt)}
        return out

    tools = ("aerophoto.rectify.rectify_points", "aerophoto.projective.fit_projective")
    methods = (Method("the projective transformation photo → base fitted on points 1–4, the residual lengths at "
                      "K1, K2 on the base", "guide §12; chapter 11 (rectify.rectify_points or "
                      "projective.fit_projective)"),)

    def hidden(self, v, got) -> list:
        # the verdict must follow from the student's own residuals
        d1, d2 = submitted_number(got.get("d1_mm")), submitted_number(got.get("d2_mm"))
        if d1 is None or d2 is None:
            return [Hidden("rect_ok from your own d1_mm, d2_mm", None, None, kind="bool")]
        d = [abs(d1), abs(d2)]
        return [verdict_check("rect_ok from your own d1_mm, d2_mm", got.get("rect_ok"), d, [rf.TOLERANCE_MM] * 2,
                              allowance(d, 0.01))]


TASKS = (Substrate(), FourPointRectification())
