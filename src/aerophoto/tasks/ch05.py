"""Graded tasks of chapter 05 (guide §6): the student's own fotoschema — its seams and its mean scale.

Every student glues **their own strip** (:func:`aerophoto.labs.own.own_strip`:
four photos 36 … 39 with their variant's f, 1:m and p_x, flown over the
virtual site at a place of their own, tilts up to 2° with f·tg α ≤ 6 mm) into a
fotoschema with :func:`aerophoto.mosaic.assemble`, over the site's true relief
(170–200 m: the variant's Z_max − Z_min = 30 m).  The student then does the
guide's two checks on it from readings made on the sheet:

* task 05.1 (:class:`SeamQuality`, step 8) — along every cut, a detail pricked
  through the cut-off strip: its distance from the cut on the glued piece (the
  contour) and of the prick, along the strip, read to 0.1 mm.  The student
  forms ΔI = contour − prick with the guide's signs (− cut-out, + duplicate),
  the quality m = √(ΣΔI²/n) (6.2), counts the cut-outs and judges the seams
  against the 0.5 mm tolerance;
* task 05.2 (:class:`MeanScale`, step 7) — four points near the outer edges of
  the first and last working areas, their coordinates read on the fotoschema
  and on the 1:10 000 plan to 0.1 mm; the student measures the four bases l_i
  and L_i, the partial scales m_i = L_i·M/l_i and their mean (6.1).

The readings are the truth (the camera model: :func:`aerophoto.mosaic.seam_details`,
:class:`aerophoto.mosaic.ScaleCheck`) plus a bounded, seeded pricking error,
rounded to 0.1 mm (:func:`aerophoto.labs.own.read_mm`); the reference answers
are computed **from the readings**, as the student computes them, and the tests
hold them against the truth.  Plan coordinates follow the Russian geodetic
convention — x north, y east (the package's ground frame is X east, Y north).

A long lens flies high: the relief displacement r·h/H that makes the seams
mismatch shrinks with H = f·m (up to ≈ b·h/H = 72 mm·30 m/1200 m = 1.8 mm for
variant 00, 0.09 mm for variant 99) — the student of a high variant finds seams
within the reading error.  That is the honest result, not a defect.

Another variant's answers are not looked for (``cross_variant = False``): each
student's readings are their own, and recognising another's would assemble all
100 fotoschemas on every wrong answer.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import mosaic as mo
from ..labs.ch05 import BASE_LABELS, answers_of, scale_readings, seam_readings
from .base import Answer, Hidden, Method, Task
from .rounding import consistency, numbers

__all__ = ["TOL_SCALE", "DESIGN_SCALE", "SeamQuality", "MeanScale", "TASKS"]

#: slip hint of task 05.2: the photos' design scale typed instead of the fotoschema's own
DESIGN_SCALE = "that is your photos' design scale 1:m; the fotoschema's scale comes from your bases: m_i = L_i·M/l_i"
#: tolerance of the scales (relative): l and L rounded to 0.1 mm before dividing change m_i by up to 0.035 %
TOL_SCALE = 0.0005


def _numbers(x, n: int | None = None):
    """``x`` as a list of finite floats (of length ``n`` if given), or None."""
    if n is None:
        n = len(x) if hasattr(x, "__len__") and not isinstance(x, (str, bytes, dict)) else -1
    out = numbers(x, n) if n > 0 else None
    return None if out is None else [float(e) for e in out]


# =========================================================================== task 05.1
@dataclass(frozen=True)
class SeamQuality(Task):
    """Task 05.1: ΔI on every check point, the quality m = √(ΣΔI²/n) (6.2), the cut-outs and the verdict (§6 step 8)."""

    id = "task-05-1"
    title = "The seams of your fotoschema"
    points = 4
    cross_variant = False
    spec = (
        Answer("dI_mm", "ΔI at every check point, in the table's order, mm", unit="mm", kind="values", tol_abs=0.05, printed=0.1),
        Answer("m_rms_mm", "RMS of the mismatches m, mm", unit="mm", tol_abs=0.005, printed=0.001),
        Answer("n_cutouts", "number of cut-outs (whole number)", kind="count", rounding="exact"),
        Answer("seams_ok", "True / False", kind="bool", hint="compare the most negative ΔI with −0.5 mm (guide §6)."),
    )

    def inputs(self, v) -> pd.DataFrame:
        """The readings along the cuts of the student's fotoschema (:func:`aerophoto.labs.ch05.seam_readings`)."""
        return seam_readings(v)

    def answers(self, v) -> dict:
        a = answers_of(v)
        return {k: a[k] for k in self.names}

    def slips(self, v) -> dict:
        dI = np.array(answers_of(v)["dI_mm"])
        return {
            "m_rms_mm": {
                "that is the mean of |ΔI| — formula (6.2) squares, averages, then takes the root.":
                    float(np.mean(np.abs(dI))),
                "divide ΣΔI² by n before taking the root.": float(np.sqrt(np.sum(dI**2))),
                "that is ΣΔI²/n — take the square root.": float(np.mean(dI**2)),
            },
            "n_cutouts": {"you counted the duplicates (+): cut-outs are the negative ΔI.": int(np.sum(dI > 0))},
        }

    methods = (Method("ΔI = contour − prick with the guide's signs, m = √(ΣΔI²/n) (6.2), cut-outs the negative ΔI",
                      "guide §6 step 8"),)

    def hidden(self, v, got) -> list:
        """m, the count and the verdict must follow from the student's own ΔI (readings to 0.1 mm: exact
        multiples, so the count and the verdict are read from ΔI rounded to 0.01 mm)."""
        dI = _numbers(got.get("dI_mm"))
        if dI is None:
            return [Hidden("m_rms_mm from your ΔI", None, None), Hidden("n_cutouts from your ΔI", None, None,
                                                                         kind="count"),
                    Hidden("seams_ok from your ΔI", None, None, kind="bool")]
        d = np.round(np.array(dI), 2)
        return [consistency("m_rms_mm from your ΔI", got.get("m_rms_mm"), 0.001,
                            lambda x: float(np.sqrt(np.mean(x**2))), [(np.array(dI), 0.1)]),
                Hidden("n_cutouts from your ΔI", got.get("n_cutouts"), int(np.sum(d < 0)), kind="count"),
                Hidden("seams_ok from your ΔI", got.get("seams_ok"), bool(d.min() >= -mo.ALLOWED_CUTOUT_MM),
                       kind="bool")]


# =========================================================================== task 05.2
@dataclass(frozen=True)
class MeanScale(Task):
    """Task 05.2: the four bases on the fotoschema and the plan, the partial scales and the mean scale (6.1, §6 step 7)."""

    id = "task-05-2"
    title = "The mean scale of your fotoschema"
    points = 4
    cross_variant = False
    spec = (
        Answer("l_mm", "the four bases on the fotoschema l_i, mm", unit="mm", kind="values", tol_abs=0.05,
               labels=BASE_LABELS, printed=0.01),
        Answer("L_mm", "the same bases on the plan L_i, mm", unit="mm", kind="values", tol_abs=0.05,
               labels=BASE_LABELS, printed=0.01),
        Answer("m_i", "four partial scale denominators m_i = L_i·M/l_i", kind="values", tol_rel=TOL_SCALE,
               labels=BASE_LABELS, printed=1),
        Answer("m_mean", "mean scale denominator m", unit="(scale denominator)", tol_rel=TOL_SCALE, printed=1),
    )

    def inputs(self, v) -> pd.DataFrame:
        """The four points read on the student's fotoschema and plan (:func:`aerophoto.labs.ch05.scale_readings`)."""
        return scale_readings(v)

    def answers(self, v) -> dict:
        a = answers_of(v)
        return {k: a[k] for k in self.names}

    def slips(self, v) -> dict:
        a = answers_of(v)
        l, L, M = np.array(a["l_mm"]), np.array(a["L_mm"]), float(v.M)
        return {"m_mean": {
            "the partial scale is m_i = L_i·M/l_i — the plan's base times M over the fotoschema's, not the inverse.":
                float(np.mean(l * M / L)),
            "multiply by the plan's scale denominator M = 10 000 (6.1).": float(np.mean(L / l)),
            DESIGN_SCALE: float(v.m),
        }, "m_i": {DESIGN_SCALE: [float(v.m)] * 4}}

    methods = (Method("l_i and L_i from the readings, m_i = L_i·M/l_i, their mean (6.1)", "guide §6 step 7"),)

    def hidden(self, v, got) -> list:
        """Each m_i must follow from the student's own l_i and L_i, and m from their own m_i."""
        l, L = numbers(got.get("l_mm"), 4), numbers(got.get("L_mm"), 4)
        mi = numbers(got.get("m_i"), 4)
        M = float(v.M)
        return [consistency("m_i from your l and L", got.get("m_i"), 1, lambda l_, L_: L_ * M / l_,
                            [(l, 0.01), (L, 0.01)], n=4),
                consistency("m_mean (mean of your m_i)", got.get("m_mean"), 1, lambda m_: float(np.mean(m_)),
                            [(mi, 1)])]


TASKS = (SeamQuality(), MeanScale())
