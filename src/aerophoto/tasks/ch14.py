"""Graded tasks of chapter 14 (article 001): error accumulation along a strip and the control spacing.

* task 14.1 (:class:`ControlSpacing1021`): the reconstructed formula (10.21) with the student's survey —
  the plan and height errors in the middle of 10 bases, and the largest whole number of bases between
  plan and between height control points;
* task 14.2 (:class:`AccumulationLaw`): the student's own Monte Carlo of a strip built by the method of
  continuation — the per-link error d of law (10.20), the end error it predicts for 20 links, and how
  much control at both ends gains over control at the start only.

The variant's inputs (:func:`survey_inputs`): the photo scale 1:m and focal length f of guide §1, the
map scale 1:M = 1:10 000, the photo base b = l·(1 − p_x/100) = 72 mm, the parallax error
m_q = 0.010 + 0.002·(i mod 6) mm (the article uses 0.01 and 0.02 mm) and the contour interval
h = 1, 2, 2.5 or 5 m (i mod 4).  For large i the long focal lengths (up to 1090 mm, f/b up to 15) make
heights from a strip poor: the height spacing can come out as 0 bases — control at every base would not
do — which the task accepts as the answer.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass


from .. import accuracy as acc
from .. import geometry as g
from .. import simulate
from .. import site as _site
from .base import Answer, Hidden, Method, Task
from .rounding import allowance, consistency, numbers

__all__ = ["MD_MAP_MM", "OTHER_READING", "N_EXAMPLE", "CONTOURS_M", "SurveyInputs", "survey_inputs", "MC_BASES", "MC_RUNS",
           "student_monte_carlo", "ControlSpacing1021", "AccumulationLaw", "TASKS"]

#: the allowed plan error of densification on the map, mm (article 001: half the 0.6 mm RMS of a contour point)
MD_MAP_MM = 0.3
#: article 001's other reading of m_D (√2·m_X, its printed 0.11 mm): the book adopts the legend's plan error
#: √(m_X² + m_Y²), and accepts this reading too — the article is ambiguous (chapter 14)
OTHER_READING = "article 001's other reading, m_D = √2·m_X"
#: the n of task 14.1's first answers (the article's example uses n = 10)
N_EXAMPLE = 10
#: the contour intervals of the variants, m (i mod 4)
CONTOURS_M = (1.0, 2.0, 2.5, 5.0)


@dataclass(frozen=True)
class SurveyInputs:
    """What task 14.1 gives the student.

    Attributes
    ----------
    i : variant number
    m, M : photo and map scale denominators
    f_mm, b_mm : focal length and photo base, mm
    mq_mm : RMS error of a transverse parallax m_q, mm
    contour_m : contour interval h, m
    """

    i: int
    m: float
    M: float
    f_mm: float
    b_mm: float
    mq_mm: float
    contour_m: float

    def __str__(self) -> str:
        return (f"variant i = {self.i}: 1:m = 1:{self.m:.0f}, 1:M = 1:{self.M:.0f}, f = {self.f_mm:g} mm, "
                f"b = {self.b_mm:g} mm, m_q = {self.mq_mm:.3f} mm, contour interval h = {self.contour_m:g} m, "
                f"allowed plan error {MD_MAP_MM} mm on the map")

    def n_plan_real(self) -> float:
        return acc.plan_bases(self.m, self.M, self.mq_mm, mD_map_mm=MD_MAP_MM)

    def n_height_real(self) -> float:
        return acc.height_bases(self.m, self.mq_mm, contour_interval_m=self.contour_m, f_mm=self.f_mm,
                                b_mm=self.b_mm)


def survey_inputs(v) -> SurveyInputs:
    """Task 14.1's inputs for variant ``v``."""
    i = int(v.i)
    b = float(v.frame_mm) * (1.0 - float(v.px_percent) / 100.0)
    return SurveyInputs(i, float(v.m), float(v.M), float(v.f_mm), b, round(0.010 + 0.002 * (i % 6), 3),
                        CONTOURS_M[i % 4])


def _n_from_coeff(c_photo_mm: float, allowed_photo_mm: float) -> int:
    """The whole n with c·√n³ ≤ allowed (c the error at n = 1)."""
    return acc.whole_bases((allowed_photo_mm / c_photo_mm) ** (2.0 / 3.0))


# =========================================================================== task 14.1
@dataclass(frozen=True)
class ControlSpacing1021(Task):
    """Task 14.1: formula (10.21) for the student's survey — errors for 10 bases and the control spacing."""

    id = "task-14-1"
    title = "Control spacing for your survey by formula (10.21)"
    points = 4
    spec = (
        Answer("mD_mm", "plan error m_D in the middle of 10 bases, mm at the photo scale", unit="mm", printed=0.0001),
        Answer("mZ_m", "height error m_Z in the middle of 10 bases, m on the ground", unit="m", printed=0.01),
        Answer("n_plan", "largest whole number of bases between plan control points", kind="count",
               rounding="down"),
        Answer("n_height", "largest whole number of bases between height control points", kind="count",
               rounding="down"),
    )

    def inputs(self, v) -> SurveyInputs:
        return survey_inputs(v)

    def answers(self, v) -> dict:
        s = survey_inputs(v)
        e = acc.strip_errors_mm(N_EXAMPLE, s.mq_mm, f_mm=s.f_mm, b_mm=s.b_mm)
        return {"mD_mm": e["D"], "mZ_m": e["Z"] * s.m / 1000.0, "n_plan": acc.whole_bases(s.n_plan_real()),
                "n_height": acc.whole_bases(s.n_height_real())}

    methods = (Method("m_D = √(m_X² + m_Y²) = 0.297·m_q·√n³ (the article's legend: the plan error), m_Z with f/b; "
                      "n from the allowed errors", "article 001, (10.21); chapter 14", reading="adopted"),
               Method("m_D = √2·m_X = 0.35·m_q·√n³ (the article's printed 0.11 mm)", "article 001 is ambiguous: "
                      "its example prints 0.11 = √2·m_X; the n_plan that follows is accepted with it",
                      submit=lambda task, v: task.other_reading(v), reading="other"))

    def other_reading(self, v) -> dict:
        """m_D and n_plan under the other reading of m_D (√2·m_X, coefficient 0.35)."""
        s = survey_inputs(v)
        c = acc.COEFF_D_SQRT2 * s.mq_mm
        return {"mD_mm": c * math.sqrt(N_EXAMPLE**3), "n_plan": _n_from_coeff(c, MD_MAP_MM * s.M / s.m)}

    def accepted(self, v) -> dict:
        o = self.other_reading(v)
        return {"mD_mm": {OTHER_READING: o["mD_mm"]}, "n_plan": {OTHER_READING: o["n_plan"]}}

    def reals(self, v) -> dict:
        s = survey_inputs(v)
        return {"n_plan": s.n_plan_real(), "n_height": s.n_height_real()}

    def slips(self, v) -> dict:
        s = survey_inputs(v)
        e = acc.strip_errors_mm(N_EXAMPLE, s.mq_mm, f_mm=s.f_mm, b_mm=s.b_mm)
        mz_allowed_photo = acc.allowed_height_error_m(s.contour_m) / s.m * 1000.0
        cz = acc.COEFF_10_21["Z"] * s.mq_mm * s.f_mm / s.b_mm
        cD = acc.COEFF_10_21["D"] * s.mq_mm
        return {
            "mD_mm": {"the law grows as √n³, not as √n": cD * math.sqrt(N_EXAMPLE),
                      "this is m_X alone; the plan error m_D = √(m_X² + m_Y²)": acc.COEFF_10_21["X"] * s.mq_mm
                      * math.sqrt(N_EXAMPLE**3)},
            "mZ_m": {"this is m_Z at the photo scale in mm; the task asks for metres on the ground": e["Z"],
                     "m_Z carries the factor f/b": e["Z"] * s.b_mm / s.f_mm * s.m / 1000.0},
            "n_plan": {"the allowed 0.3 mm is on the map: at the photo scale it is 0.3·M/m":
                       _n_from_coeff(cD, MD_MAP_MM)},
            "n_height": {"the allowed height error is the RMS: 1.25 × the mean error h/3, halved":
                         _n_from_coeff(cz, 0.5 * s.contour_m / 3.0 / s.m * 1000.0),
                         "densification gets half of the map's RMS height error": _n_from_coeff(cz, 2 * mz_allowed_photo)},
        }

    def hidden(self, v, got) -> list:
        # the spacing must follow from the student's own errors for 10 bases (both grow as √n³): every whole
        # number the rounding of those errors allows is consistent
        s = survey_inputs(v)
        out = []
        for err, n_name, allowed_photo in (("mD_mm", "n_plan", MD_MAP_MM * s.M / s.m),
                                           ("mZ_m", "n_height", acc.allowed_height_error_m(s.contour_m))):
            x = numbers(got.get(err))
            if x is None or x <= 0:
                out.append(Hidden(f"{n_name} follows from {err}", None, None, kind="count"))
                continue
            a = allowance(x, self.answer(err).printed)
            ns = {_n_from_coeff(y / math.sqrt(N_EXAMPLE**3), allowed_photo) for y in (x - a, x, x + a) if y > 0}
            out.append(Hidden(f"{n_name} follows from {err}", got.get(n_name),
                              _n_from_coeff(x / math.sqrt(N_EXAMPLE**3), allowed_photo), kind="count",
                              accepted=tuple(range(min(ns), max(ns) + 1))))
        return out


# =========================================================================== task 14.2
#: bases of the student's Monte Carlo strip, and runs
MC_BASES = 12
MC_RUNS = 150
#: the article's geometry for the Monte Carlo: f = b = 70 mm at 1:8000 over the default site
MC_F_MM, MC_M = 70.0, 8000.0


@functools.lru_cache(maxsize=4)
def _mc(i: int, mq_mm: float) -> acc.StripMonteCarlo:
    st = _site.get_site()
    cam = g.Camera(MC_F_MM)
    px = 100.0 * (1.0 - MC_F_MM / cam.frame_mm)  # b = f = 70 mm
    strip = simulate.strip_over_site(st, cam, MC_M, px, MC_BASES + 1,
                                     imperfections=simulate.Imperfections(max_tilt_deg=0.5, seed=i))
    return acc.strip_monte_carlo(cam, strip.poses, st, sigma_mm=mq_mm / math.sqrt(2.0), n_runs=MC_RUNS, seed=1400 + i)


def student_monte_carlo(v) -> acc.StripMonteCarlo:
    """The student's Monte Carlo: 150 strips of 12 bases (f = b = 70 mm, 1:8000) with the variant's m_q."""
    return _mc(int(v.i), survey_inputs(v).mq_mm)


def _law_fit(mc: acc.StripMonteCarlo) -> tuple:
    n = mc.free_links()[1:]
    r = mc.rms_free_mm()[1:, 2]
    return acc.fit_accumulation(n, r, acc.free_strip_factor)


@dataclass(frozen=True)
class AccumulationLaw(Task):
    """Task 14.2: law (10.20) fitted to the student's Monte Carlo — d, its prediction for 20 links, the gain."""

    id = "task-14-2"
    title = "Read the accumulation law off your simulation"
    points = 3
    cross_variant = False
    spec = (
        Answer("d_mm", "per-link height error d of law (10.20) fitted to the free strip, mm at the photo scale",
               unit="mm", tol_rel=0.01, printed=0.0001),
        Answer("m20_mm", "height error (10.20) predicts at the end of a free strip of 20 links, mm", unit="mm",
               tol_rel=0.01, printed=0.001),
        Answer("gain", "free-strip end error / middle error with control at both ends, 12 bases", tol_rel=0.01, printed=0.01),
    )

    def inputs(self, v) -> acc.StripMonteCarlo:
        return student_monte_carlo(v)

    def answers(self, v) -> dict:
        mc = student_monte_carlo(v)
        d, _ = _law_fit(mc)
        free_end = mc.rms_free_mm()[MC_BASES - 1, 2]
        mid = mc.rms_mid_mm()[list(mc.mid_n).index(MC_BASES), 2]
        return {"d_mm": d, "m20_mm": d * acc.free_strip_factor(20), "gain": float(free_end / mid)}

    tools = ("aerophoto.accuracy.fit_accumulation",)
    methods = (Method("least squares through the origin of m = d·√(n(n+1)(2n+1)/6) to the Z column, n = 1 … 11 "
                      "(acc.fit_accumulation); (10.20) at n = 20; the gain from the two columns",
                      "article 001, (10.20); chapter 14, task 14.2"),)

    def slips(self, v) -> dict:
        mc = student_monte_carlo(v)
        d, _ = _law_fit(mc)
        n = mc.free_links()[1:]
        r = mc.rms_free_mm()[1:, 2]
        d_k = acc.fit_accumulation(n + 1, r, acc.free_strip_factor)[0]
        return {"d_mm": {"count the links beyond the controlled model: the point of photo k has come through "
                         "k − 1 of them": d_k,
                         "this is the X (along-strip) column; the task asks for heights Z":
                             acc.fit_accumulation(n, mc.rms_free_mm()[1:, 0], acc.free_strip_factor)[0]},
                "m20_mm": {"(10.20) grows as √(n(n + 1)(2n + 1)/6), not as n": d * 20.0,
                           "that is the large-n form d·√(n³/3); (10.20) sums the squares exactly: "
                           "d·√(n(n + 1)(2n + 1)/6)": d * math.sqrt(20.0**3 / 3.0)}}

    def hidden(self, v, got) -> list:
        return [consistency("m20_mm follows from d_mm", got.get("m20_mm"), 0.001,
                            lambda d: d * acc.free_strip_factor(20), [(numbers(got.get("d_mm")), 0.0001)])]


TASKS = (ControlSpacing1021(), AccumulationLaw())
