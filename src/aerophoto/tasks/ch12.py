"""Graded tasks of chapter 12 (guide §13): the control spacing by Zhukov's formula, and the reduction check of the strip.

Task 12.1 uses formula (13.1) read with n³ + 11n + 34
(:mod:`aerophoto.triangulation.zhukov`) with the student's own inputs; the
direction error m_ε of a variant is defined once here, :func:`m_eps_arcmin`.
Tasks 12.2 and 12.3 use the student's own strip of chapter 06
(:func:`aerophoto.labs.ch06.strip_readings`: the same four photos 36 … 39, the
same readings): table 12 with all six bases between the four control points,
and table 13 — the corrections from the other middle centre, 38, with the
six-base mean.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import triangulation as tri
from .base import Answer, Hidden, Method, Task
from ..labs.ch06 import POINT_ORDER, StripReadings, shared_readings, strip_readings
from .ch06 import (TOL_COEFF, TOL_MEAN, TOL_SPREAD, TOL_V_REL, CorrectionsTask, coefficients_from_control, corrections_with_written_k,
                   rounded_coefficients, spread_checks)
from .rounding import allowance, numbers

__all__ = ["M_ALLOWED_MM", "N_BASES", "m_eps_arcmin", "ZhukovInputs", "zhukov_inputs", "ControlSpacing",
           "TABLE12", "TABLE12_LABELS", "CENTRE_13", "CORRECTION_POINTS_13", "SpreadCheck", "Table13", "TASKS"]

#: the allowed RMS error m of an orienting point on the plan, mm (guide §13 step 1)
M_ALLOWED_MM = 0.35
#: the n of task 12.1's first answer: the three bases of the four photos 36–39
N_BASES = 3
#: the default relative tolerance of a derived value (0.5 %), as in :mod:`aerophoto.checks`
TOL_REL = 0.005


def m_eps_arcmin(v) -> float:
    """The RMS direction error m_ε of variant ``v``, arc-minutes: 4′ + 0.5′·(i mod 3) — 4′, 4.5′ or 5′ (guide: 4′–5′)."""
    return 4.0 + 0.5 * (int(v.i) % 3)


@dataclass(frozen=True)
class ZhukovInputs:
    """What task 12.1 gives the student: the variant's numbers that enter (13.1).

    Attributes
    ----------
    i : int
        The variant number.
    m, M : float
        Photo and plan scale denominators (1:m, 1:M).
    px_percent : float
        Forward overlap p_x, %.
    frame_mm : float
        Frame side l, mm.
    m_eps_arcmin : float
        RMS direction error m_ε, arc-minutes (:func:`m_eps_arcmin`).
    """

    i: int
    m: float
    M: float
    px_percent: float
    frame_mm: float
    m_eps_arcmin: float

    @property
    def k_i(self) -> float:
        """The enlargement k_i = m/M from the photo to the plan."""
        return self.m / self.M

    @property
    def b_mm(self) -> float:
        """The mean photo base b_ср = l·(100 − p_x)/100, mm."""
        return self.frame_mm * (100.0 - self.px_percent) / 100.0

    def zhukov_kwargs(self) -> dict:
        """Keyword arguments of :func:`aerophoto.triangulation.zhukov_error_mm` for these inputs."""
        return dict(k_i=self.k_i, b_mm=self.b_mm, m_eps_arcmin=self.m_eps_arcmin)

    def __str__(self) -> str:
        return (f"variant i = {self.i}: m = 1:{self.m:.0f}, M = 1:{self.M:.0f}, p_x = {self.px_percent:g} %, "
                f"frame {self.frame_mm:g} mm, m_ε = {self.m_eps_arcmin:g}′")


def zhukov_inputs(v) -> ZhukovInputs:
    """Task 12.1's inputs for variant ``v``."""
    return ZhukovInputs(int(v.i), float(v.m), float(v.M), float(v.px_percent), float(v.frame_mm), m_eps_arcmin(v))


def _n_max(m3_mm: float) -> int:
    """The largest whole n with m(n) ≤ 0.35 mm when m(3) = ``m3_mm``: (13.1) scales as √(n³ + 11n + 34)."""
    r3 = tri.zhukov_radicand(N_BASES)
    n = 0
    while m3_mm * math.sqrt(tri.zhukov_radicand(n + 1) / r3) <= M_ALLOWED_MM and n < 10000:
        n += 1
    return n


# =========================================================================== task 12.1
@dataclass(frozen=True)
class ControlSpacing(Task):
    """Task 12.1: the error (13.1) predicts for three bases and the largest control spacing with m ≤ 0.35 mm."""

    id = "task-12-1"
    title = "The control spacing for your camera (formula 13.1)"
    points = 3
    spec = (
        Answer("m3_mm", "predicted RMS error of an orienting point for n = 3 bases, mm", unit="mm", printed=0.001),
        Answer("n_max", "largest whole number of bases with m ≤ 0.35 mm", kind="count", rounding="down"),
    )

    def inputs(self, v) -> ZhukovInputs:
        return zhukov_inputs(v)

    def answers(self, v) -> dict:
        kw = zhukov_inputs(v).zhukov_kwargs()
        return {"m3_mm": tri.zhukov_error_mm(N_BASES, **kw), "n_max": tri.zhukov_max_bases(M_ALLOWED_MM, **kw)}

    methods = (Method("(13.1) read with n³ + 11n + 34, k_i = m/M, b = l·(100 − p_x)/100; n_max the largest whole n "
                      "with m(n) ≤ 0.35 mm", "guide §13 step 1; chapter 12"),)

    def slips(self, v) -> dict:
        kw = zhukov_inputs(v).zhukov_kwargs()
        return {"m3_mm": {
            "this is the radicand as scanned (n⁰): read it n³ + 11n + 34": tri.zhukov_error_mm(N_BASES, reading="n0", **kw),
            "this is with n² — the radicand is n³ + 11n + 34": tri.zhukov_error_mm(N_BASES, reading="n2", **kw),
            "k_i is the enlargement m/M, not 1": tri.zhukov_error_mm(N_BASES, **{**kw, "k_i": 1.0}),
            "that is the guide's example base b = 60 mm; your b = l·(100 − p_x)/100 with your p_x":
                tri.zhukov_error_mm(N_BASES, **{**kw, "b_mm": 60.0}) if abs(kw["b_mm"] - 60.0) > 0.5 else None,
        }}

    def reals(self, v) -> dict:
        """The real n at which (13.1) reaches 0.35 mm: n³ + 11n + 34 = r(3)·(0.35/m(3))²."""
        m3 = self.answers(v)["m3_mm"]
        R = tri.zhukov_radicand(N_BASES) * (M_ALLOWED_MM / m3) ** 2
        roots = [r.real for r in np.roots([1.0, 0.0, 11.0, 34.0 - R]) if abs(r.imag) < 1e-9 and r.real > -1]
        return {"n_max": max(roots)} if roots else {}

    def hidden(self, v, got) -> list:
        # n_max must follow from the student's own m(3): (13.1) grows as √(n³ + 11n + 34).  Where m(3) is within
        # its rounding allowance of a boundary, every whole number that allowance reaches is consistent.
        m3 = numbers(got.get("m3_mm"))
        if m3 is None or m3 <= 0:
            return [Hidden("n_max follows from m3_mm", None, None, kind="count")]
        a = allowance(m3, self.spec[0].printed)
        allowed = tuple(range(_n_max(m3 + a), _n_max(max(m3 - a, 1e-12)) + 1))
        return [Hidden("n_max follows from m3_mm", got.get("n_max"), _n_max(m3), kind="count", accepted=allowed)]


# =========================================================================== task 12.2
#: the six bases of table 12, in its order (the scan's "33/1 – 39/2" is 36/1 – 39/2)
TABLE12 = (("36/1", "36/2"), ("36/1", "39/1"), ("36/1", "39/2"), ("36/2", "39/1"), ("36/2", "39/2"), ("39/1", "39/2"))
TABLE12_LABELS = tuple(f"{a}–{b}" for a, b in TABLE12)
#: the centre of the strip for table 13 (chapter 06 took 37; "37 or 38", guide §13 step 8)
CENTRE_13 = "38"
CORRECTION_POINTS_13 = tuple(n for n in POINT_ORDER if n != CENTRE_13)


@dataclass(frozen=True)
class SpreadCheck(Task):
    """Task 12.2: table 12 — k of all six bases, their mean, the largest |Δk| and the 0.003/0.006 verdict."""

    id = "task-12-2"
    title = "Table 12: does your strip pass the reduction check?"
    points = 3
    spec = (
        Answer("k_bases", "six reduction coefficients, in table 12's order", kind="values", tol_abs=TOL_COEFF,
               labels=TABLE12_LABELS, printed=0.001),
        Answer("k_mean", "their mean", tol_abs=TOL_MEAN, printed=0.001),
        Answer("dk_max", "largest |Δk| = |k − mean| over the six bases", tol_abs=TOL_SPREAD, printed=0.001),
        Answer("spread_ok", "True if every base is within its tolerance", kind="bool",
               hint="compare every |Δk| with 0.003, or with 0.006 on a base shorter than 133 mm on the base"),
    )

    def inputs(self, v) -> StripReadings:
        """The student's readings of chapter 06's strip: ``control_table()`` is what this task uses."""
        return strip_readings(v)

    def _coefficients(self, v):
        return coefficients_from_control(shared_readings(v).control, float(v.M), TABLE12)

    def answers(self, v) -> dict:
        c = self._coefficients(v)
        return {"k_bases": [float(x) for x in c.k], "k_mean": float(c.k_mean), "dk_max": float(c.spread),
                "spread_ok": bool(c.all_ok)}

    def slips(self, v) -> dict:
        c = self._coefficients(v)
        return {"dk_max": {"this is max k − min k; the guide's spread is the deviation from the mean": float(c.k_range)},
                "k_mean": {"this is l_воск / l_осн — the coefficient is base over template": 1.0 / c.k_mean}}

    methods = (Method("k of all six bases, their mean, the largest |Δk| against 0.003 (0.006 under 133 mm)",
                      "guide §13, table 12"),
               Method("k and the mean written to three decimals, as the guide's table 12 prints them",
                      "guide §13, table 12", submit=rounded_coefficients))

    def hidden(self, v, got) -> list:
        """The mean, the largest deviation and the verdict must follow from the student's own six k."""
        return spread_checks(got, len(TABLE12), self._coefficients(v).tol, dk_max=True)


# =========================================================================== task 12.3
@dataclass(frozen=True)
class Table13(CorrectionsTask):
    """Task 12.3: table 13 — r from working centre 38 and v = r·(k − 1) with the six-base mean of table 12."""

    id = "task-12-3"
    title = "Table 13: corrections from centre 38"
    points = 3
    centre = CENTRE_13
    names_ = CORRECTION_POINTS_13
    pairs = TABLE12
    spec = (
        Answer("r_mm", "distances from centre 38, in the table's order (38 left out), mm", unit="mm", kind="values",
               tol_abs=0.05, labels=CORRECTION_POINTS_13, printed=0.01),
        Answer("v_mm", "corrections v = r·(k − 1) with k of table 12, same order, mm", unit="mm", kind="values",
               tol_abs=0.05, tol_rel=TOL_V_REL, labels=CORRECTION_POINTS_13, printed=0.1),
    )
    methods = (Method("r from centre 38 on the common tracing, v = r·(k − 1) with the six-base mean of table 12",
                      "guide §13, table 13"),
               Method("k_mean as the guide writes it (three decimals, from k written to three decimals)",
                      "guide §13, tables 12–13", submit=lambda task, v: corrections_with_written_k(task, v)))

    # defined here, not only inherited from chapter 06's class: the grader's probe trusts a task's answers, slips
    # and hidden checks only when their code lives in the task's own module (aerophoto.course.probe)
    def answers(self, v) -> dict:
        return CorrectionsTask.answers(self, v)

    def slips(self, v) -> dict:
        return CorrectionsTask.slips(self, v)

    def hidden(self, v, got) -> list:
        return CorrectionsTask.hidden(self, v, got)


TASKS = (ControlSpacing(), SpreadCheck(), Table13())
