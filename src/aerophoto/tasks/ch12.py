"""Graded tasks of chapter 12 (guide §13): the control spacing by Zhukov's formula, and the reduction check of the strip.

Task 12.1 uses formula (13.1) read with n³ + 11n + 34
(:mod:`aerophoto.triangulation.zhukov`) with the student's own inputs; the
direction error m_ε of a variant is defined once here, :func:`m_eps_arcmin`.
Task 12.2 uses the lab strip of chapter 06 (:func:`aerophoto.tasks.ch06.lab_strip`)
with all six bases of table 12.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .. import triangulation as tri
from .base import Answer, Hidden, Task
from .ch06 import TOL_COEFF, LabStrip, lab_strip

__all__ = ["M_ALLOWED_MM", "N_BASES", "m_eps_arcmin", "ZhukovInputs", "zhukov_inputs", "ControlSpacing",
           "SpreadCheck", "TASKS"]

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
        Answer("m3_mm", "predicted RMS error of an orienting point for n = 3 bases, mm", unit="mm"),
        Answer("n_max", "largest whole number of bases with m ≤ 0.35 mm", kind="count", rounding="down"),
    )

    def inputs(self, v) -> ZhukovInputs:
        return zhukov_inputs(v)

    def answers(self, v) -> dict:
        kw = zhukov_inputs(v).zhukov_kwargs()
        return {"m3_mm": tri.zhukov_error_mm(N_BASES, **kw), "n_max": tri.zhukov_max_bases(M_ALLOWED_MM, **kw)}

    def slips(self, v) -> dict:
        kw = zhukov_inputs(v).zhukov_kwargs()
        return {"m3_mm": {
            "this is the radicand as scanned (n⁰): read it n³ + 11n + 34": tri.zhukov_error_mm(N_BASES, reading="n0", **kw),
            "this is with n² — the radicand is n³ + 11n + 34": tri.zhukov_error_mm(N_BASES, reading="n2", **kw),
            "k_i is the enlargement m/M, not 1": tri.zhukov_error_mm(N_BASES, **{**kw, "k_i": 1.0}),
        }}

    def hidden(self, v, got) -> list:
        # n_max must follow from the student's own m(3): (13.1) grows as √(n³ + 11n + 34).  Where m(3) is
        # within its tolerance (0.5 %) of a boundary, every whole number that tolerance allows is consistent.
        # Both answers are fixed by the inputs, so a pair that passes the visible checks passes this one too.
        try:
            m3 = float(got.get("m3_mm"))
        except (TypeError, ValueError):
            m3 = float("nan")
        if not (math.isfinite(m3) and m3 > 0):
            return [Hidden("n_max follows from m3_mm", None, None, kind="count")]
        tol = ControlSpacing.spec[0].tol_rel or TOL_REL
        allowed = set(range(_n_max(m3 / (1.0 - tol)), _n_max(m3 / (1.0 + tol)) + 1))
        n_got = got.get("n_max")
        try:
            n_val = float(n_got)
        except (TypeError, ValueError):
            n_val = None
        expected = n_val if n_val in allowed else _n_max(m3)
        return [Hidden("n_max follows from m3_mm", n_got, expected, kind="count")]


# =========================================================================== task 12.2
@dataclass(frozen=True)
class SpreadCheck(Task):
    """Task 12.2: the largest deviation |Δk| over the six bases of table 12, and the 0.003/0.006 verdict."""

    id = "task-12-2"
    title = "Does your strip pass the reduction check? (table 12)"
    points = 3
    spec = (
        Answer("dk_max", "largest |Δk| over the six bases", tol_abs=TOL_COEFF),
        Answer("spread_ok", "True if every base is within its tolerance", kind="bool",
               hint="compare every |Δk| with 0.003, or with 0.006 on a base shorter than 133 mm on the base"),
    )

    def inputs(self, v) -> LabStrip:
        """The student's lab strip of chapter 06: ``control_table()`` is what the student reads."""
        return lab_strip(v)

    def answers(self, v) -> dict:
        c = lab_strip(v).coefficients("all")
        return {"dk_max": float(c.spread), "spread_ok": bool(c.all_ok)}

    def slips(self, v) -> dict:
        c = lab_strip(v).coefficients("all")
        return {"dk_max": {"this is max k − min k; the guide's spread is the deviation from the mean": float(c.k_range)}}

    def hidden(self, v, got) -> list:
        # the verdict must agree with the student's own largest deviation: well within 0.003 every base passes,
        # well beyond 0.006 no tolerance holds; in between (and within dk_max's tolerance of 0.003 or 0.006)
        # it depends on the bases' lengths, and the verdict of the student's strip is expected
        try:
            dk = abs(float(got.get("dk_max")))
        except (TypeError, ValueError):
            dk = float("nan")
        if not math.isfinite(dk):
            return [Hidden("spread_ok agrees with dk_max", None, None, kind="bool")]
        if dk < tri.K_SPREAD_TOL - TOL_COEFF:
            expected = True
        elif dk > tri.K_SPREAD_TOL_SHORT + TOL_COEFF:
            expected = False
        else:
            expected = bool(lab_strip(v).coefficients("all").all_ok)
        return [Hidden("spread_ok agrees with dk_max", got.get("spread_ok"), expected, kind="bool")]


TASKS = (ControlSpacing(), SpreadCheck())
