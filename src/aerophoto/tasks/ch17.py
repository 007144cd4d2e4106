"""Graded tasks of chapter 17 (article 003): the error budget of updating your map.

* task 17.1 (:class:`VectorisingError`): table 1 on the student's own repeated measurements of a
  building corner — V_X, V_Y (formula 3), V_D (4), m_D (5), m_d on the map (6);
* task 17.2 (:class:`TriangulationError`): σ = 0.5·P, formulas (7) and (8), and the scanning error,
  for the student's photos;
* task 17.3 (:class:`UpdateBudget`): the whole budget (formula 10, table 5) of updating the guide's
  1:10 000 map from the student's photos rectified onto the mean plane (no DEM), the relief of the
  student's area left in: total on the ground, mean error on the map, the verdict against 0.4 mm and
  the stage that dominates.

The variant's data
------------------
Photos 1:m with m = 12 000 + 100i and f = 100 + 10i mm on an 18 cm frame (guide §1), the map
1:M = 1:10 000 (guide §1), the relief Z_max − Z_min = 30 m (guide §1), p_x = 60 %, p_y = 30 %.  The
scanning resolution is not in the guide; the book gives variant i the pixel P = 12 + 3·(i mod 10) µm
(12–39 µm, around the article's 16 and 42 µm), :func:`scan_um`.  The corner of task 17.1 is measured
20 times on the 1:10 000 orthophoto with an error of about 0.05–0.09 mm on the map per axis (seed
i), coordinates to the centimetre, :func:`corner_measurements`.  The other stages take the article's
values: control 0.125 mm, orthorectification 0.125 mm, vectorising 0.11 mm on the map, the scanner's
3 µm, and 0.446 mm for the transfer between strips: the instruction's mean discrepancy 0.5 mm made an RMS
by rule (1), then formula (9) (:func:`aerophoto.budget.transfer_from_mean_mm`; the article puts the mean
itself into (9), 0.357 mm, printed 0.35 — a slip hint names that reading).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import budget as bu
from .base import Answer, Hidden, Method, Task
from .rounding import allowance, consistency, numbers, verdict_check

__all__ = ["N_MEASUREMENTS", "scan_um", "corner_measurements", "Case", "case_of", "stage_options",
           "VectorisingError", "TriangulationError", "UpdateBudget", "TASKS"]

N_MEASUREMENTS = 20
#: article 003's own reading of the transfer (formula 9 applied to the mean discrepancy, 0.357 mm): the book turns
#: the mean into an RMS first (rule 1, 0.446 mm) and accepts the article's reading too
TRANSFER_AS_PRINTED = "article 003's own reading: the transfer 0.357 mm"
#: the stage names a student may give as the dominant one (task 17.3)
STAGE_NAMES = tuple(en for _k, _s, en, _ru in bu.STAGES)


def scan_um(v) -> float:
    """The variant's scanning resolution P, µm: 12 + 3·(i mod 10)."""
    return 12.0 + 3.0 * (int(v.i) % 10)


def corner_measurements(v) -> pd.DataFrame:
    """Task 17.1's data: 20 repeated X, Y (m) of one building corner on the variant's 1:M orthophoto."""
    i = int(v.i)
    rng = np.random.default_rng(17_000 + i)
    M = float(v.M)
    s = (0.05 + 0.04 * rng.random(2)) * M / 1000.0  # per-axis RMS, m on the ground
    X0 = 5_400_000.0 + 1000.0 * rng.integers(100, 900) + 0.37
    Y0 = 6_300_000.0 + 1000.0 * rng.integers(100, 900) + 0.81
    X = (X0 + s[0] * rng.standard_normal(N_MEASUREMENTS)).round(2)
    Y = (Y0 + s[1] * rng.standard_normal(N_MEASUREMENTS)).round(2)
    return pd.DataFrame({"X_m": X, "Y_m": Y}, index=pd.Index(np.arange(1, N_MEASUREMENTS + 1), name="measurement"))


@dataclass(frozen=True)
class Case:
    """The student's map-updating case: photo and map scales, camera, scanning, relief."""

    M_c: float
    M_k: float
    f_mm: float
    frame_mm: float
    P_um: float
    relief_m: float
    px_percent: float
    py_percent: float

    def budget(self, transfer_mm: float | None = None) -> bu.Budget:
        """Formula (10) with the mean plane instead of a DEM (task 17.3); ``transfer_mm`` as in :func:`budget`."""
        return bu.budget(self.M_c, self.P_um, self.M_k, f_mm=self.f_mm, frame_mm=self.frame_mm, dtm="plane",
                         relief_m=self.relief_m, px_percent=self.px_percent, py_percent=self.py_percent,
                         transfer_mm=transfer_mm)

    def table(self) -> pd.DataFrame:
        rows = [("photo scale 1:M_c", "", f"1:{self.M_c:.0f}"), ("map scale 1:M_k", "", f"1:{self.M_k:.0f}"),
                ("focal length f", "mm", self.f_mm), ("frame l", "mm", self.frame_mm),
                ("scanning resolution P", "µm", self.P_um), ("relief Z_max − Z_min", "m", self.relief_m),
                ("overlaps p_x, p_y", "%", f"{self.px_percent:g}, {self.py_percent:g}")]
        return pd.DataFrame(rows, columns=["quantity", "unit", "value"]).set_index("quantity")


def case_of(v) -> Case:
    """Tasks 17.2 and 17.3's case for variant ``v``."""
    return Case(float(v.m), float(v.M), float(v.f_mm), float(v.frame_mm), scan_um(v), float(v.Zmax_m - v.Zmin_m),
                float(v.px_percent), float(v.py_percent))


def stage_options() -> tuple:
    """The stage names task 17.3 accepts for ``dominant``."""
    return STAGE_NAMES


@dataclass(frozen=True)
class VectorisingError(Task):
    """Task 17.1: table 1 on the student's 20 measurements of a building corner."""

    id = "task-17-1"
    title = "Your vectorising error (table 1)"
    points = 3
    spec = (
        Answer("VX_m", "mean error V_X = Σ|X − X̄|/n, m", unit="m", tol_abs=0.0005, printed=0.0001),
        Answer("VY_m", "mean error V_Y, m", unit="m", tol_abs=0.0005, printed=0.0001),
        Answer("VD_m", "mean plan error V_D = √(V_X² + V_Y²), m", unit="m", tol_abs=0.0007, printed=0.0001),
        Answer("mD_m", "RMS plan error m_D = 1.25·V_D, m", unit="m", tol_abs=0.001, printed=0.0001),
        Answer("md_mm", "m_d = m_D/M on the map, mm", unit="mm", tol_abs=0.0005, printed=0.0001),
    )

    def inputs(self, v) -> pd.DataFrame:
        return corner_measurements(v)

    def _ref(self, v) -> bu.Vectorising:
        d = corner_measurements(v)
        return bu.vectorising_error(d["X_m"], d["Y_m"], v.M)

    def answers(self, v) -> dict:
        r = self._ref(v)
        return {"VX_m": r.V_X_m, "VY_m": r.V_Y_m, "VD_m": r.V_D_m, "mD_m": r.m_D_m, "md_mm": r.m_d_mm}

    def slips(self, v) -> dict:
        d = corner_measurements(v)
        r = self._ref(v)
        sx = float(np.std(d["X_m"], ddof=1))
        return {
            "VX_m": {"that is the standard deviation; the mean error is the mean of |X − X̄|": sx,
                     "divide the sum of |X − X̄| by n": r.V_X_m * N_MEASUREMENTS},
            "VD_m": {"that is V_X + V_Y; the plan error combines the axes in squares: √(V_X² + V_Y²)": r.V_X_m + r.V_Y_m,
                     "that is √2·V_X; V_D takes both axes, √(V_X² + V_Y²)": math.sqrt(2.0) * r.V_X_m},
            "mD_m": {"m_D = 1.25·V_D (formula 5), not V_D/1.25": r.V_D_m / 1.25},
            "md_mm": {"m_D/M is in metres; the map needs millimetres (×1000)": r.m_D_m / v.M},
        }

    methods = (Method("V = Σ|Δ|/n per axis (3), V_D = √(V_X² + V_Y²) (4), m_D = 1.25·V_D (5), m_d = m_D/M (6)",
                      "article 003, table 1; chapter 17"),)

    def hidden(self, v, got) -> list:
        vx, vy = numbers(got.get("VX_m")), numbers(got.get("VY_m"))
        return [consistency("VD_m from your V_X, V_Y", got.get("VD_m"), 0.0001, math.hypot, [(vx, 0.0001), (vy, 0.0001)]),
                consistency("md_mm from your m_D", got.get("md_mm"), 0.0001, lambda m: m / v.M * 1000.0,
                            [(numbers(got.get("mD_m")), 0.0001)])]


@dataclass(frozen=True)
class TriangulationError(Task):
    """Task 17.2: σ, m_x,y (7), m_ф = m_D (8) and m_ск for the student's photos and scanning."""

    id = "task-17-2"
    title = "Triangulation and scanning on your photos"
    points = 2
    spec = (
        Answer("sigma_um", "σ = 0.5·P, µm", unit="µm", tol_abs=0.05, printed=0.1),
        Answer("mxy_m", "m_x,y = 0.84·M_c·σ, m", unit="m", printed=0.0001),
        Answer("mphi_m", "m_ф = m_D = √2·m_x,y, m", unit="m", printed=0.0001),
        Answer("msc_m", "scanning m_ск = 3 µm · M_c, m", unit="m", printed=0.0001),
    )

    def inputs(self, v) -> Case:
        return case_of(v)

    def answers(self, v) -> dict:
        c = case_of(v)
        mxy, mD = bu.triangulation_rms_m(c.M_c, c.P_um)
        return {"sigma_um": bu.sigma_um(c.P_um), "mxy_m": mxy, "mphi_m": mD, "msc_m": bu.SCAN_RMS_UM * 1e-6 * c.M_c}

    def slips(self, v) -> dict:
        c = case_of(v)
        mxy, mD = bu.triangulation_rms_m(c.M_c, c.P_um)
        return {"mxy_m": {"σ is 0.5·P, not P": 2 * mxy, "µm to m is ×10⁻⁶": mxy * 1000.0},
                "mphi_m": {"m_D = m_x,y·√2 (formula 8), not ·2": 2 * mxy,
                           "that is m_x,y, one coordinate; the plan error m_D = √2·m_x,y (formula 8)": mxy},
                "msc_m": {"multiply by the photo scale M_c, not the map scale": bu.SCAN_RMS_UM * 1e-6 * c.M_k}}

    methods = (Method("σ = 0.5·P, m_x,y = 0.84·M_c·σ (7), m_ф = √2·m_x,y (8), m_ск = 3 µm·M_c",
                      "article 003; chapter 17"),)

    def hidden(self, v, got) -> list:
        c = case_of(v)
        return [consistency("mxy_m from your σ", got.get("mxy_m"), 0.0001, lambda s: 0.84 * c.M_c * s * 1e-6,
                            [(numbers(got.get("sigma_um")), 0.1)]),
                consistency("mphi_m from your m_x,y", got.get("mphi_m"), 0.0001, lambda m: m * math.sqrt(2.0),
                            [(numbers(got.get("mxy_m")), 0.0001)])]


@dataclass(frozen=True)
class UpdateBudget(Task):
    """Task 17.3: the budget of updating the 1:10 000 map from the student's photos, no DEM."""

    id = "task-17-3"
    title = "The error budget of your update"
    points = 4
    spec = (
        Answer("mrel_m", "relief stage (r_rms/f)·Δh/√12 on the ground, m", unit="m", printed=0.001),
        Answer("mD_m", "total m_D, formula (10), m", unit="m", printed=0.001),
        Answer("vd_mm", "mean error v_d = m_D/M/1.25 on the map, mm", unit="mm", printed=0.001),
        Answer("ok", "True if v_d ≤ 0.4 mm", kind="bool",
               hint="compare the mean error on the map v_d with 0.4 mm."),
        Answer("dominant", "the stage with the largest error", kind="choice", options=STAGE_NAMES,
               hint="compare the seven stages' errors on the ground; the relief stage replaces the DEM."),
    )

    def inputs(self, v) -> Case:
        return case_of(v)

    def answers(self, v) -> dict:
        B = case_of(v).budget()
        return {"mrel_m": B.stage("dtm").rms_m, "mD_m": B.total_m, "vd_mm": B.map_mean_mm,
                "ok": bool(B.meets_tolerance), "dominant": B.dominant.name}

    def slips(self, v) -> dict:
        c = case_of(v)
        B = c.budget()
        r_max, r_rms = bu.working_area_radii_mm(c.frame_mm, c.px_percent, c.py_percent)
        sq = {s.key: s.rms_m**2 for s in B.stages}
        linear = sum(s.rms_m for s in B.stages)
        return {
            "mrel_m": {"use the RMS radius r_rms of the working area, not its half-diagonal":
                       bu.plane_rectification_m(c.relief_m, c.f_mm, r_max),
                       "heights spread uniformly over Δh have an RMS of Δh/√12 about the mean plane":
                       bu.dtm_displacement_m(c.relief_m, c.f_mm, r_rms)},
            "mD_m": {"independent errors add as squares (formula 10), not linearly": linear,
                     "formula (10) takes all seven stages": math.sqrt(sum(sq.values()) - sq["dtm"])},
            "vd_mm": {"that is the RMS error m_d; the mean error is m_d/1.25": B.map_rms_mm},
        }

    methods = (Method("the relief stage (r_rms/f)·Δh/√12 for the DEM, the other six as the article gives them, the "
                      "transfer 0.446 mm (rule (1), then formula 9); formula (10); v_d = m_D/M/1.25",
                      "article 003, formula (10), table 5; chapter 17", reading="adopted"),
               Method("the transfer as the article computes it: formula (9) on the mean discrepancy, 0.357 mm",
                      "article 003's own reading (chapter 17, \"One slip, and its fix\"): accepted, with the "
                      "total, the mean error, the verdict and the dominant stage that follow",
                      submit=lambda task, v: task.article_reading(v), reading="other"))

    def article_reading(self, v) -> dict:
        """The budget with the article's transfer (formula 9 on the mean discrepancy)."""
        art = case_of(v).budget(transfer_mm=bu.transfer_rms_mm())
        return {"mD_m": art.total_m, "vd_mm": art.map_mean_mm, "ok": bool(art.meets_tolerance),
                "dominant": art.dominant.name}

    def accepted(self, v) -> dict:
        o, a = self.article_reading(v), self.answers(v)
        return {k: {TRANSFER_AS_PRINTED: o[k] if o[k] != a[k] else None} for k in o}

    def hidden(self, v, got) -> list:
        vd = numbers(got.get("vd_mm"))
        out = [consistency("vd_mm from your m_D", got.get("vd_mm"), 0.001, lambda m: m / v.M * 1000.0 / 1.25,
                           [(numbers(got.get("mD_m")), 0.001)])]
        if vd is None:
            out.append(Hidden("ok from your v_d", None, None, kind="bool"))
        else:
            out.append(verdict_check("ok from your v_d", got.get("ok"), [vd], [bu.TOLERANCE_MEAN_MM],
                                     [allowance(vd, 0.001)]))
        return out


TASKS = (VectorisingError(), TriangulationError(), UpdateBudget())
