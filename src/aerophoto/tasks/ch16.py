"""Graded tasks of chapter 16 (article 000): the densification you can expect, and the contours of your own sheet.

* task 16.1 (:class:`DensificationForecast`): Lysenko's formula for the student's block — H = f·m,
  b = l·(1 − p_x), m_z, and the smallest standard contour interval that m_z allows;
* task 16.2 (:class:`SheetCheckPoints`): the check points of the student's own 1:2000 sheet of the
  virtual site, with the heights of a regular DEM and of the same DEM with structural lines — the
  RMS errors of both, the mean error and the share within 15 cm, as the article judged its DEMs.

The variant's data
------------------
The block of task 16.1 (:func:`aerophoto.labs.ch16.block_of`): K = 4 + (i mod 4) strips of n_s = 8 + (i mod 5) photos of
the student's camera (f = 100 + 10i mm, 1:m with m = 12 000 + 100i, 18 cm frame, p_x = 60 %), the
article's m = 16 points per photo and s = 3 images per point, and r = 3K control points (both ends and
the middle of every strip).  The guide's scheme makes H = f·m grow from 1.2 km (i = 0) to 23.9 km
(i = 99); the formula holds at any height and the interval it allows grows with it — no clamping.

The sheet of task 16.2 (:func:`aerophoto.labs.ch16.sheet_of`): the 1 km × 1 km square with its south-west corner at
X = 100 + 88i m, Y = 2500 + 250·(i mod 7) m on the site (every variant its own, all on the hills
north of the river); the regular grid's step is the article's 7 mm on the student's photo,
d = 0.007·m metres (84–153 m); the node heights carry the article's measured densification error,
12 cm RMS, drawn with the seed 1000 + i; 40 check points spread at random (seed i) over the sheet, none
with an error within 1.5 mm of the 15 cm the task counts against.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import dem
from ..labs.ch16 import N_CHECK, TOL_15_M, Block, block_of, sheet_data
from .base import Answer, Hidden, Method, Task, Withheld, submitted_number
from .rounding import allowance, consistency, either, numbers

__all__ = ["MEAN_RATIO", "OTHER_READING", "DensificationForecast", "SheetCheckPoints", "TASKS"]

#: the article's requirement: mean contour error 15 cm for h = 0.5 m, i.e. 0.3·h
MEAN_RATIO = 0.3
#: article 000's other reading of Lysenko's "zr": 2r (the book reads s·r, an italic s scanned as z)
OTHER_READING = "article 000's other reading of “zr”, 2r"


def _two_r_root(b: Block) -> float:
    """Lysenko's root with "zr" read as 2r."""
    n, m, s, r = b.n, b.points_per_photo, b.images_per_point, b.r
    return math.sqrt(3 * (2 * n * s + m * n - 2 * r) / (2 * m * n * s))


@dataclass(frozen=True)
class DensificationForecast(Task):
    """Task 16.1: H, b, Lysenko's m_z for the student's block, and the contour interval it allows."""

    id = "task-16-1"
    title = "How well will your block densify the heights?"
    points = 3
    spec = (
        Answer("H_m", "flying height H = f·m, m", unit="m", printed=1),
        Answer("b_mm", "photo base b = l·(1 − p_x), mm", unit="mm", printed=0.1),
        Answer("mz_m", "Lysenko's m_z, m", unit="m", printed=0.001),
        # the intervals of the series are at least 0.25 m apart: a tolerance of 0.1 m tells them apart
        Answer("h_m", "smallest standard contour interval h with m_z/1.25 ≤ 0.3·h, m", unit="m", tol_abs=0.1, printed=0.01),
    )

    def inputs(self, v) -> Withheld:
        return Withheld(block_of(v), ("H_m", "b_mm", "mz_m"), why="it is what task 16.1 asks you to compute")

    def answers(self, v) -> dict:
        b = block_of(v)
        return {"H_m": b.H_m, "b_mm": b.b_mm, "mz_m": b.mz_m,
                "h_m": dem.standard_interval(b.mz_m / 1.25, MEAN_RATIO)}

    methods = (Method("m_z = m_p·(H/b)·√(3(2ns + mn − sr)/(2mns)) with m_p = 0.025 mm (“zr” read as s·r); the "
                      "smallest standard h with m_z/1.25 ≤ 0.3·h", "article 000; chapter 16", reading="adopted"),
               Method("“zr” read as 2r, as the scan prints it", "article 000 is ambiguous in the scan; the book "
                      "argues for s·r (the root is then u/N), the other reading is accepted with its h",
                      submit=lambda task, v: task.other_reading(v), reading="other"))

    def other_reading(self, v) -> dict:
        """m_z and h with Lysenko's "zr" read as 2r."""
        b = block_of(v)
        mz = b.mp_mm * b.H_m / b.b_mm * _two_r_root(b)
        return {"mz_m": mz, "h_m": dem.standard_interval(min(mz / 1.25, MEAN_RATIO * dem.STANDARD_INTERVALS_M[-1]),
                                                         MEAN_RATIO)}

    def accepted(self, v) -> dict:
        o, a = self.other_reading(v), self.answers(v)
        return {k: {OTHER_READING: o[k] if o[k] != a[k] else None} for k in o}

    def slips(self, v) -> dict:
        b = block_of(v)
        root = dem.lysenko_ratio(b.n, b.points_per_photo, b.images_per_point, b.r)
        return {
            "H_m": {"f is in millimetres: H = f/1000 · m gives metres": b.f_mm * b.m},
            "b_mm": {"the base is the part of the frame not overlapped: l·(1 − p_x/100)": b.frame_mm},
            "mz_m": {"m_p is 0.025 mm — the printed 0,25 lost a zero (see the reading above)":
                     0.25 * b.H_m / b.b_mm * root,
                     "the whole frame is not the base: b = l·(1 − p_x)": b.mp_mm * b.H_m / b.frame_mm * root},
            "h_m": {"compare the mean error m_z/1.25, not m_z itself, with 0.3·h":
                    dem.standard_interval(min(b.mz_m, 30.0), MEAN_RATIO)},
        }

    def hidden(self, v, got) -> list:
        b = block_of(v)
        roots = (dem.lysenko_ratio(b.n, b.points_per_photo, b.images_per_point, b.r), _two_r_root(b))
        H, base = numbers(got.get("H_m")), numbers(got.get("b_mm"))
        out = [either(*(consistency("mz_m from your H and b", got.get("mz_m"), 0.001,
                                    lambda H_, b_, _r=root: b.mp_mm * H_ / b_ * _r, [(H, 1), (base, 0.1)])
                        for root in roots))]
        mz = numbers(got.get("mz_m"))
        top = MEAN_RATIO * dem.STANDARD_INTERVALS_M[-1]
        if mz is None or not 0 <= mz / 1.25 <= top:
            out.append(Hidden("h_m from your m_z", None, None))
            return out
        a = allowance(mz, 0.001)
        hs = {dem.standard_interval(min(max(x, 0.0), 1.25 * top) / 1.25, MEAN_RATIO) for x in (mz - a, mz, mz + a)}
        h = numbers(got.get("h_m"))
        near = min(hs, key=lambda x: abs(x - h)) if h is not None else dem.standard_interval(mz / 1.25, MEAN_RATIO)
        out.append(Hidden("h_m from your m_z", got.get("h_m"), near, tol_abs=0.1, about="h_m"))
        return out


@dataclass(frozen=True)
class SheetCheckPoints(Task):
    """Task 16.2: RMS errors of the regular and the structural-line DEM at the sheet's check points."""

    id = "task-16-2"
    title = "Check points of your sheet"
    points = 3
    cross_variant = False  # each variant's table is its own; no other variant's numbers to recognise
    spec = (
        Answer("m_grid_m", "RMS error of the regular DEM at the check points, m", unit="m", tol_abs=0.0005, printed=0.0001),
        Answer("m_lines_m", "RMS error of the DEM with structural lines, m", unit="m", tol_abs=0.0005, printed=0.0001),
        Answer("v_lines_m", "mean error Σ|Δ|/n of the DEM with structural lines, m", unit="m", tol_abs=0.0005, printed=0.0001),
        Answer("share_pct", "share of its errors within 15 cm, %", unit="%", tol_abs=0.01, printed=0.01),
    )

    tools = ("aerophoto.labs.ch16.sheet_of",)
    methods = (Method("Δ = Z_DEM − Z_geod at the 40 points: RMS √(ΣΔ²/n), mean Σ|Δ|/n, the share of |Δ| ≤ 0.15 m",
                      "article 000; chapter 16, task 16.2"),)

    def inputs(self, v) -> pd.DataFrame:
        return sheet_data(v).points.copy()

    def answers(self, v) -> dict:
        d = sheet_data(v)
        eg, el = d.errors("grid"), d.errors("lines")
        return {"m_grid_m": float(np.sqrt(np.mean(eg**2))), "m_lines_m": float(np.sqrt(np.mean(el**2))),
                "v_lines_m": float(np.mean(np.abs(el))),
                "share_pct": float(100.0 * np.count_nonzero(np.abs(el) <= TOL_15_M) / len(el))}

    def slips(self, v) -> dict:
        d = sheet_data(v)
        eg, el = d.errors("grid"), d.errors("lines")
        n = len(el)
        return {
            "m_grid_m": {"that is the mean error Σ|Δ|/n; the RMS error is √(ΣΔ²/n)": float(np.mean(np.abs(eg))),
                         "divide ΣΔ² by n, not n − 1 (the true heights are known)":
                         float(np.sqrt(np.sum(eg**2) / (n - 1)))},
            "m_lines_m": {"that is the mean error Σ|Δ|/n; the RMS error is √(ΣΔ²/n)": float(np.mean(np.abs(el))),
                          "divide ΣΔ² by n, not n − 1 (the true heights are known)":
                          float(np.sqrt(np.sum(el**2) / (n - 1)))},
            "v_lines_m": {"the mean error takes |Δ|: with signs the errors cancel": float(abs(np.mean(el)))},
            "share_pct": {"count |Δ| ≤ 0.15 m, of the DEM with structural lines": float(
                100.0 * np.count_nonzero(np.abs(eg) <= TOL_15_M) / n)},
        }

    def hidden(self, v, got) -> list:
        # the share is a whole number of the 40 points; the mean error can never exceed the RMS error
        share = submitted_number(got.get("share_pct"))
        k = None if share is None else share * N_CHECK / 100.0
        out = [Hidden("share_pct is a count of the 40 points", k, round(k) if k is not None else None,
                      tol_abs=1e-6)]
        mv, mr = submitted_number(got.get("v_lines_m")), submitted_number(got.get("m_lines_m"))
        ratio = None if mv is None or mr is None or mr <= 0 else mv / mr
        out.append(Hidden("v_lines_m / m_lines_m between 0.5 and 1", ratio, 0.75, tol_abs=0.25))
        return out


TASKS = (DensificationForecast(), SheetCheckPoints())
