"""Graded tasks of chapter 02 (guide §3): measuring and judging the student's own strip.

:func:`strip_measurements` flies a strip of five photos with the variant's
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
import pandas as pd

from .. import geometry as g
from .. import quality as q
from .. import simulate as sim
from .base import Answer, Hidden, Task, submitted_number

__all__ = ["MEASUREMENT_KEYS", "strip_measurements", "reference_answers", "measurement_table", "MeasureStrip",
           "JudgeStrip", "TASKS"]

#: the measurements the student is given, in the order shown
MEASUREMENT_KEYS = ("a_mm", "b_mm", "b1_mm", "b2_mm", "L_mm", "l_mm", "crab_deg", "bubble_div", "f_mm", "H_m")


def strip_measurements(variant) -> dict:
    """Measurements "taken on the rough mosaic" of the student's own strip (chapter 02's graded tasks).

    A strip of five photos is flown with the variant's camera, scale and
    overlap (:func:`aerophoto.simulate.variant_strip`, flat ground at the
    mean of Z_min and Z_max) with imperfections drawn from the seed i (the
    variant number): tilts up to 3.5°, a crab of up to ±12°, a flying-height
    scatter of ±4 %, a route bend of up to ±3 % and a ±8 % base jitter, so
    that some variants pass a criterion and others fail it.  The returned
    values are what a technician reads: lengths to 0.1 mm with a ruler,
    the crab angle to 0.5° with a protractor, the level bubble's offset to
    0.1 of a division.

    Returns
    -------
    dict with
        ``a_mm`` (overlap width of photos 1–2), ``b_mm`` (frame side, 180),
        ``b1_mm``, ``b2_mm`` (bases of photos 2–3 on photo 2 and on photo 3),
        ``L_mm``, ``l_mm`` (strip line and the deviation of the middle photo),
        ``crab_deg`` (measured on photo 2), ``bubble_div`` (offset of the
        level's bubble on photo 3, divisions of 30′), ``f_mm``, ``H_m``,
        ``numbers`` (photo numbers 1–5).
    """
    i = int(variant.i)
    rng = np.random.default_rng([2014, i])
    # tilts shift the principal points by about f·tan α on the photo: long-focus cameras fly stabilised
    tilt = min(3.5, math.degrees(math.atan(6.0 / variant.f_mm)))
    imp = sim.Imperfections(max_tilt_deg=tilt, crab_deg=float(rng.uniform(-12.0, 12.0)), max_crab_jitter_deg=1.0,
                            max_height_percent=4.0, curvature_percent=float(rng.uniform(-3.0, 3.0)),
                            max_base_percent=8.0, seed=i)
    st = sim.variant_strip(variant, 5, imperfections=imp)
    cam = st.camera
    dem = g.FlatTerrain(st.ground_Z_m)
    s = st.shots
    a = q.measure_overlap(cam, s[0].pose, s[1].pose, dem)
    b1, b2 = q.measure_base(cam, s[1].pose, s[2].pose, dem)
    stt = q.measure_straightness(cam, [x.pose for x in s], dem, st.m)
    crab = q.measure_crab_deg(cam, s[1].pose, s[2].pose, dem)
    r1 = lambda x: float(np.round(x, 1))  # noqa: E731  (a ruler reads 0.1 mm)
    return {
        "a_mm": r1(a), "b_mm": cam.frame_mm, "b1_mm": r1(b1), "b2_mm": r1(b2),
        "L_mm": r1(stt["L_mm"]), "l_mm": r1(stt["l_mm"][2]),
        "crab_deg": float(np.round(crab * 2.0) / 2.0),
        "bubble_div": float(np.round(abs(s[2].pose.alpha_deg) / (q.LEVEL_DIVISION_ARCMIN / 60.0), 1)),
        "f_mm": cam.f_mm, "H_m": st.H_m, "numbers": tuple(x.number for x in s),
    }


def measurement_table(variant) -> pd.Series:
    """The measurements the student works from, as shown in the notebook: a Series named "your measurements"."""
    d = strip_measurements(variant)
    return pd.Series({k: d[k] for k in MEASUREMENT_KEYS}, name="your measurements")


def reference_answers(variant) -> dict:
    """The correct answers to chapter 02's graded tasks, computed from :func:`strip_measurements` with the formulas."""
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
        """The measurements on the student's strip (:func:`measurement_table`)."""
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
        Answer("Px_percent", "forward overlap of photos 1–2, %", unit="%", tol_abs=0.05),
        Answer("dm_percent", "scale difference of photos 2–3, % (signed)", unit="%", tol_abs=0.02),
        Answer("n_percent", "straightness of the strip, %", unit="%", tol_abs=0.02),
    )

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
        Answer("crab_limit_deg", "largest crab for your f, degrees", unit="°", tol_abs=0.05),
        Answer("alpha_read_deg", "tilt read on the level, degrees", unit="°", tol_abs=0.01),
        Answer("px_ok", "True / False", kind="bool", hint="compare P_x with the 56 % rejection threshold (guide §3)."),
        Answer("dm_ok", kind="bool", hint="compare |Δm/m| with 3 %."),
        Answer("n_ok", kind="bool", hint="compare n with 2 % (H > 750 m) or 3 %."),
        Answer("crab_ok", kind="bool", hint="compare |φ| with the limit for your f."),
        Answer("tilt_ok", kind="bool", hint="compare the level reading with 3°."),
    )

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
