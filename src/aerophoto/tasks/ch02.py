"""Graded tasks of chapter 02 (guide §3): measuring and judging the student's own strip.

:func:`aerophoto.labs.ch02.strip_measurements` flies a strip of five photos with the variant's
camera, scale and overlap (:func:`aerophoto.simulate.variant_strip`) with
imperfections drawn from the variant number, and reads on it what a
technician reads on the rough mosaic.  The tasks' input is that table
(:meth:`MeasureStrip.inputs`, a Series the notebook shows and the answer cells
index as ``meas["a_mm"]``); the reference answers follow from it with the
formulas of :mod:`aerophoto.quality` (:func:`reference_answers`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .. import quality as q
from ..labs.ch02 import measurement_table, strip_measurements
from .base import Answer, Hidden, Method, Task, submitted_number

__all__ = ["reference_answers", "MeasureStrip", "JudgeStrip", "TASKS"]


def reference_answers(variant) -> dict:
    """The correct answers to chapter 02's graded tasks, computed from :func:`aerophoto.labs.ch02.strip_measurements` with the formulas."""
    d = strip_measurements(variant)
    Px = q.overlap_percent(d["a_mm"], d["b_mm"])
    dm = q.scale_difference_percent(d["b1_mm"], d["b2_mm"])
    n = q.straightness_percent(d["l_mm"], d["L_mm"])
    lim = q.crab_limit_deg(d["f_mm"])
    alpha = float(np.floor(d["bubble_div"] + 0.5)) * q.LEVEL_DIVISION_ARCMIN / 60.0
    return {
        "Px_percent": Px, "dm_percent": dm, "n_percent": n, "crab_limit_deg": lim, "alpha_read_deg": alpha,
        "px_ok": Px >= q.PX_MIN_PERCENT, "dm_ok": abs(dm) <= q.SCALE_DIFF_MAX_PERCENT,
        "n_ok": n <= q.straightness_limit_percent(d["H_m"]), "crab_ok": abs(d["crab_deg"]) <= lim,
        "tilt_ok": alpha <= q.TILT_MAX_DEG,
    }


class _StripTask(Task):
    def inputs(self, v) -> pd.Series:
        """The measurements on the student's strip (:func:`aerophoto.labs.ch02.measurement_table`)."""
        return measurement_table(v)

    def answers(self, v) -> dict:
        a = reference_answers(v)
        return {name: a[name] for name in self.names}


@dataclass(frozen=True)
class MeasureStrip(_StripTask):
    """Task 02.1: P_x = a/b·100 (3.1), Δm/m = (b1 − b2)/b1·100 (3.4) and n = l/L·100 (3.3) of the student's strip.

    No hidden checks: each answer is one formula of the given measurements, so
    a second check of it would only repeat the visible one (the old notebook's
    hidden checks did exactly that and were dropped).
    """

    id = "task-02-1"
    title = "Measure your strip"
    points = 3
    spec = (
        Answer("Px_percent", "forward overlap of photos 1–2, %", unit="%", tol_abs=0.05, printed=0.01),
        Answer("dm_percent", "scale difference of photos 2–3, % (signed)", unit="%", tol_abs=0.02, printed=0.01),
        Answer("n_percent", "straightness of the strip, %", unit="%", tol_abs=0.02, printed=0.01),
    )

    methods = (Method("P_x = a/b·100 (3.1), Δm/m = (b₁ − b₂)/b₁·100 (3.4), n = l/L·100 (3.3)",
                      "guide §3, from the technician's readings"),)

    def slips(self, v) -> dict:
        d = strip_measurements(v)
        return {"dm_percent": {"you divided by b2 — formula (3.4) divides by b1.":
                               (d["b1_mm"] - d["b2_mm"]) / d["b2_mm"] * 100}}


@dataclass(frozen=True)
class JudgeStrip(_StripTask):
    """Task 02.2: the crab limit for the student's f, the level reading, and the five verdicts of guide §3.

    ``cross_variant`` is off: a crab limit (5°–10°) or a level reading (a
    multiple of 30′) is shared by many variants, so "this is another
    variant's answer" would mislead (the old check cell did not look for
    other variants' level readings either).
    """

    id = "task-02-2"
    title = "Judge your strip"
    points = 3
    cross_variant = False
    spec = (
        Answer("crab_limit_deg", "largest crab for your f, degrees", unit="°", tol_abs=0.05, printed=0.1),
        Answer("alpha_read_deg", "tilt read on the level, degrees", unit="°", tol_abs=0.05, printed=0.1),
        Answer("px_ok", "True / False", kind="bool", hint="compare P_x with the 56 % rejection threshold (guide §3)."),
        Answer("dm_ok", kind="bool", hint="compare |Δm/m| with 3 %."),
        Answer("n_ok", kind="bool", hint="compare n with 2 % (H > 750 m) or 3 %."),
        Answer("crab_ok", kind="bool", hint="compare |φ| with the limit for your f."),
        Answer("tilt_ok", kind="bool", hint="compare the level reading with 3°."),
    )

    methods = (Method("the book's crab rule for f, the level read to whole divisions of 30′, the five norms of §3",
                      "guide §3"),)

    def slips(self, v) -> dict:
        d = strip_measurements(v)
        return {"alpha_read_deg": {"that is the tilt in divisions — multiply by 30′ = 0.5°.": d["bubble_div"],
                                   "read the level to a whole division (round the offset first).":
                                       d["bubble_div"] * 0.5}}

    def hidden(self, v, got) -> list:
        # the level is read in whole divisions of 30′: the reading is a multiple of 0.5°
        alpha = submitted_number(got.get("alpha_read_deg"))
        twice = None if alpha is None or not math.isfinite(alpha * 2.0) else alpha * 2.0
        return [Hidden("alpha_read_deg (30′ steps)", twice, None if twice is None else float(round(twice)),
                       tol_abs=1e-9)]


TASKS = (MeasureStrip(), JudgeStrip())
