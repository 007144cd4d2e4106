"""Graded tasks of chapter 03 (guide §4): the relief correction of the student's own photo — tables 2, 3, 4.

Every student gets their own photo of the virtual site (:func:`aerophoto.labs.displacement.relief_sheet`):
their variant's f, 1:m, α and λ, six points pricked in two zones (I, 1, 2 on low
ground, II, 3, 4 on high ground) and the same points on a plan at 1:10 000.  The
student **measures** the points' photo coordinates and the bases' plan lengths
with the measuring tool (:mod:`aerophoto.demos.measure`) and does the guide's
§4 on them:

* task 03.1 (:class:`ReliefTable2`): the measurements and table 2 — l_пл, l_сн,
  m_i = l_пл·M/l_сн, the zones' m_част, m_cp and the deviations Δm_i/m_cp;
* task 03.2 (:class:`ReliefTable3`): table 3 — Z_cp, H = m_cp·f, the nadir point
  n, r of each point from n, δh = r·h/H and the number of corrections;
* task 03.3 (:class:`ReliefTable4`): table 4 — the bases between the corrected
  points and the scales again.

Measured values are graded against the truth (the camera model) within the
measuring tolerance (:data:`TOL_XY_MM`); what is computed from them is graded
against the reference computed from error-free measurements within a tolerance
that covers that measuring error, and — hidden — for consistency with the
student's own measurements and columns (each step must follow from the one
before, at the guide's precision).  No task recognises another variant's answers
(``cross_variant = False``): with measuring tolerances a neighbour's scales would
match by accident.

Heights of the points are given (read off the plan's contours, to 0.1 m).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from ..displacement import base_lengths_mm
from ..labs.displacement import RELIEF_BASES, RELIEF_NAMES, relief_sheet
from .base import Answer, Hidden, Method, Task, Withheld
from .rounding import consistency, count_range, numbers as _numbers

__all__ = ["TOL_XY_MM", "TOL_LEN_MM", "TOL_M_I", "TOL_M_PART", "TOL_M_CP", "TOL_DM_PCT", "BASE_LABELS",
           "ZONES", "numbers", "scale_answers", "scale_spec", "scale_hidden", "sheet_answers", "sheet_hidden",
           "corrected_count", "chained_scales", "SHEET_WITHHELD", "sheet_inputs",
           "ReliefTable2", "ReliefTable3", "ReliefTable4", "TASKS"]

#: a coordinate read with the measuring tool (to 0.1 mm) may be this far from the truth, mm
TOL_XY_MM = 0.2
#: a length between two measured points, mm (two readings, each within TOL_XY_MM)
TOL_LEN_MM = 0.45
#: relative tolerances of the scale denominators that cover those measuring errors (bases 20–30 mm long)
TOL_M_I = 0.025
TOL_M_PART = 0.02
TOL_M_CP = 0.015
#: the deviation Δm_i/m_cp of a zone, percentage points
TOL_DM_PCT = 1.5
BASE_LABELS = tuple(f"{a}-{b}" for a, b in RELIEF_BASES)
ZONES = ("I", "II")
#: what a lab sheet knows that its tasks ask for (the student reads the marks with the measuring tools)
SHEET_WITHHELD = ("work", "reference", "photo_xy_mm", "plan_xy_mm", "l_photo_mm", "l_plan_mm", "n_mm", "c_mm",
                  "Z_mean_m", "H_m", "mean_plane_xy_mm", "vertical_xy_mm", "XYZ_m", "pose")


def sheet_inputs(sheet) -> Withheld:
    """A lab sheet (:class:`aerophoto.labs.displacement.LabSheet`) as its tasks give it: the photo, the plan, the
    marks to measure, the heights and the summary — not its solution (:data:`SHEET_WITHHELD`)."""
    return Withheld(sheet, SHEET_WITHHELD, why="it is what your tables compute — measure the marks with the tools")


def numbers(x, n: int):
    """A submitted sequence as a float array of length ``n``, or None if it is not ``n`` finite numbers."""
    return _numbers(x, n)


def _floats(a) -> list:
    return [float(x) for x in np.ravel(a)]


def scale_answers(table, lsn_name: str = "lsn_mm") -> dict:
    """A :class:`~aerophoto.displacement.ScaleTable` as the answers l_сн (``lsn_name``), m_i, m_part, m_cp, dm_pct."""
    return {lsn_name: _floats([b.l_photo_mm for b in table.bases]), "m_i": _floats(table.m_i),
            "m_part": _floats(table.m_part), "m_cp": float(table.m_mean), "dm_pct": _floats(100.0 * table.relative_dm)}


def scale_spec(zones: tuple, bases: tuple, *, lsn_name: str = "lsn_mm", lsn_text: str,
               m_printed: float = 10) -> tuple:
    """The answers of a scale table (2, 4, 5, 7): l_сн, m_i, m_част, m_cp, Δm_i/m_cp.

    ``m_printed`` is the unit the guide prints the scale denominators in (10 in §4's tables 2 and 4, 1 in §5's).
    """
    return (
        Answer(lsn_name, lsn_text, unit="mm", kind="values", tol_abs=TOL_LEN_MM, labels=bases, printed=0.1),
        Answer("m_i", "scale denominators m_i = l_пл·M/l_сн of the bases", kind="values", tol_rel=TOL_M_I,
               labels=bases, printed=m_printed),
        Answer("m_part", f"partial scale denominators m_част of zones {', '.join(zones)}", kind="values",
               tol_rel=TOL_M_PART, labels=tuple(f"zone {z}" for z in zones), printed=m_printed),
        Answer("m_cp", "mean scale denominator m_cp", tol_rel=TOL_M_CP, printed=m_printed),
        Answer("dm_pct", "Δm_i/m_cp of each zone, % (Δm_i = m_част − m_cp, with its sign)", unit="%",
               kind="values", tol_abs=TOL_DM_PCT, labels=tuple(f"zone {z}" for z in zones), printed=0.01),
    )


def _zone_means(values, bases, zones):
    values = np.asarray(values, dtype=float)
    return np.array([np.mean([m for m, (a, _) in zip(values, bases) if a == z]) for z in zones])


def scale_hidden(got: dict, bases: tuple, M: float, *, lsn_name: str = "lsn_mm", l_plan=None,
                 l_plan_truth=None, m_printed: float = 10) -> list:
    """Hidden checks of a scale table: every column follows from the student's own previous column.

    m_i from the student's l_пл (``l_plan``, submitted) or — when the plan lengths are not part of the task —
    from the true plan lengths ``l_plan_truth`` and the student's l_сн, within what a plan reading may be off
    (:data:`TOL_LEN_MM`); m_част, m_cp and Δm/m_cp from the student's own m_i.  Each tolerance is what the
    rounding of the values it uses allows (:func:`aerophoto.tasks.rounding.consistency`; scale denominators
    printed to ``m_printed``).
    """
    nb = len(bases)
    zones = tuple(dict.fromkeys(a for a, _ in bases))
    lsn = numbers(got.get(lsn_name), nb)
    m_i = numbers(got.get("m_i"), nb)
    m_part = numbers(got.get("m_part"), len(zones))
    m_cp = _numbers(got.get("m_cp"))
    if l_plan is not None or l_plan_truth is None:
        first = consistency("m_i from your l_пл and l_сн", got.get("m_i"), m_printed, lambda lp, ls: lp * M / ls,
                            [(l_plan, 0.1), (lsn, 0.1)], n=nb)
    else:
        truth = np.asarray(l_plan_truth, dtype=float)
        extra = None if lsn is None else np.abs(TOL_LEN_MM * M / lsn)
        first = consistency("m_i·l_сн/M gives the plan lengths", got.get("m_i"), m_printed,
                            lambda ls: truth * M / ls, [(lsn, 0.1)], n=nb, extra=0.0 if extra is None else extra)
    return [first,
            consistency("m_част from your m_i", got.get("m_part"), m_printed,
                        lambda mi: _zone_means(mi, bases, zones), [(m_i, m_printed)], n=len(zones)),
            consistency("m_cp from your m_част", got.get("m_cp"), m_printed, lambda mp: float(np.mean(mp)),
                        [(m_part, m_printed)]),
            consistency("Δm/m_cp from your m_част and m_cp", got.get("dm_pct"), 0.01,
                        lambda mp, mc: 100.0 * (mp - mc) / mc, [(m_part, m_printed), (m_cp, m_printed)],
                        n=len(zones))]


def sheet_answers(sheet, table) -> dict:
    """The answers of a lab sheet's first table (tasks 03.1 and 04.2): the points' x, y on the photo (mm), the
    plan lengths l_пл (mm) and the scale columns of ``table`` (:func:`scale_answers`).

    ``sheet`` is an :class:`aerophoto.labs.displacement.LabSheet`; ``table`` its
    :class:`~aerophoto.displacement.ScaleTable` (guide table 2 or 5).
    """
    xy = sheet.photo_xy_mm
    return {"x_mm": _floats(xy[:, 0]), "y_mm": _floats(xy[:, 1]), "lpl_mm": _floats(sheet.l_plan_mm),
            **scale_answers(table)}


def sheet_hidden(got: dict, sheet, names: tuple, bases: tuple, m_printed: float = 10) -> list:
    """Hidden checks of a lab sheet's first table (tasks 03.1 and 04.2): l_сн from the student's own x, y, then
    every scale column from the student's previous one (:func:`scale_hidden`, with their l_пл).

    ``names`` are the sheet's points in the order of ``x_mm``/``y_mm``, ``bases`` its (zone point, point) pairs.
    """
    xy = [numbers(got.get(k), len(names)) for k in ("x_mm", "y_mm")]
    lpl = numbers(got.get("lpl_mm"), len(bases))
    return [consistency("l_сн from your x, y", got.get("lsn_mm"), 0.1,
                        lambda x, y: base_lengths_mm(names, np.column_stack([x, y]), bases),
                        [(xy[0], 0.1), (xy[1], 0.1)], n=len(bases)),
            *scale_hidden(got, bases, sheet.M, l_plan=lpl, m_printed=m_printed)]


# =========================================================================== task 03.1
@dataclass(frozen=True)
class ReliefTable2(Task):
    """Task 03.1: measure the six points on the photo and the four bases on the plan; table 2 (§4 step 3)."""

    id = "task-03-1"
    title = "Table 2 of your photo: the scales before the correction"
    points = 4
    cross_variant = False
    spec = (
        Answer("x_mm", "x of I, 1, 2, II, 3, 4 on your photo, mm (measured)", unit="mm", kind="values",
               tol_abs=TOL_XY_MM, labels=RELIEF_NAMES, printed=0.1),
        Answer("y_mm", "y of I, 1, 2, II, 3, 4 on your photo, mm (measured)", unit="mm", kind="values",
               tol_abs=TOL_XY_MM, labels=RELIEF_NAMES, printed=0.1),
        Answer("lpl_mm", "plan lengths l_пл of I-1, I-2, II-3, II-4, mm (measured on the plan)", unit="mm",
               kind="values", tol_abs=TOL_LEN_MM, labels=BASE_LABELS, printed=0.1),
        *scale_spec(ZONES, BASE_LABELS, lsn_text="photo lengths l_сн of I-1, I-2, II-3, II-4, mm"),
    )

    methods = (Method("readings with the measuring tool, then formulas 5.1, 5.2 column by column",
                      "guide §4 step 3, table 2"),
               Method("each column from the previous one as written (to the printed units)",
                      "the guide's table 2 rounds every column before the next",
                      submit=lambda task, v: chained_scales(task.answers(v), RELIEF_BASES, 10000.0, 10)))

    def inputs(self, v):
        """The student's lab sheet (:class:`aerophoto.labs.displacement.LabSheet`): photo, plan, heights."""
        return sheet_inputs(relief_sheet(int(v.i)))

    def answers(self, v) -> dict:
        sheet = relief_sheet(int(v.i))
        return sheet_answers(sheet, sheet.work().table2)

    def hidden(self, v, got) -> list:
        """l_сн from the student's own coordinates; every scale column from the student's previous one."""
        return sheet_hidden(got, relief_sheet(int(v.i)), RELIEF_NAMES, RELIEF_BASES)


# =========================================================================== task 03.2
@dataclass(frozen=True)
class ReliefTable3(Task):
    """Task 03.2: Z_cp, H = m_cp·f, the nadir point, r from n, δh = r·h/H and the corrections (§4 step 4, table 3)."""

    id = "task-03-2"
    title = "Table 3 of your photo: the relief corrections"
    points = 4
    cross_variant = False
    spec = (
        Answer("Zcp_m", "mean object plane Z_cp, m", unit="m", tol_abs=0.05, printed=0.01),
        Answer("H_m", "flying height H = m_cp·f above it, m", unit="m", tol_rel=0.02, printed=1),
        Answer("xn_mm", "x of the nadir point n, mm", unit="mm", tol_abs=0.05, printed=0.01),
        Answer("yn_mm", "y of the nadir point n, mm", unit="mm", tol_abs=0.05, printed=0.01),
        Answer("r_mm", "distances r of I, 1, 2, II, 3, 4 from n, mm", unit="mm", kind="values", tol_abs=0.3,
               labels=RELIEF_NAMES, printed=0.1),
        Answer("dh_mm", "relief displacements δh = r·h/H of the six points, mm (+ away from n)", unit="mm",
               kind="values", tol_abs=0.01, tol_rel=0.03, labels=RELIEF_NAMES, printed=0.01),
        Answer("n_corr", "number of points corrected (|δh| > 0.2 mm)", integer=True),
    )

    def inputs(self, v):
        return sheet_inputs(relief_sheet(int(v.i)))

    def answers(self, v) -> dict:
        sheet = relief_sheet(int(v.i))
        w = sheet.work()
        t3 = w.table3
        return {"Zcp_m": float(w.Z_mean_m), "H_m": float(w.H_m), "xn_mm": float(w.n_mm[0]),
                "yn_mm": float(w.n_mm[1]), "r_mm": _floats(t3.r_mm), "dh_mm": _floats(t3.delta_mm),
                "n_corr": int(t3.n_applied)}

    def slips(self, v) -> dict:
        sheet = relief_sheet(int(v.i))
        c = sheet.c_mm
        n = sheet.n_mm
        turned = "λ is counted from the photo's +x axis, counter-clockwise — x and y look swapped"
        return {
            "Zcp_m": {"that is the plain mean of the six heights — the guide averages the bases' mean heights "
                      "in each zone, then the two zones": float(np.mean(sheet.Z_given_m))},
            "H_m": {"that is H = f·m with your variant's nominal scale — the guide takes m_cp from your table 2":
                    float(v.f_mm) / 1000.0 * float(v.m)},
            "xn_mm": {"that is the isocentre c (f·tg(α/2)) — the nadir point lies at f·tg α": float(c[0]),
                      turned: float(n[1])},
            "yn_mm": {"that is the isocentre c (f·tg(α/2)) — the nadir point lies at f·tg α": float(c[1]),
                      turned: float(n[0])},
        }

    methods = (Method("Z_cp from the zones' mean heights, H = m_cp·f, n at f·tg α on the negative principal vertical, "
                      "δh = r·h/H (4.1)", "guide §4 step 4, table 3"),)

    def hidden(self, v, got) -> list:
        """δh from the student's own r, H and Z_cp (and the given heights); the count from the student's own δh."""
        Z = relief_sheet(int(v.i)).Z_given_m
        r, dh = numbers(got.get("r_mm"), len(Z)), numbers(got.get("dh_mm"), len(Z))
        H, Zcp = _numbers(got.get("H_m")), _numbers(got.get("Zcp_m"))
        return [consistency("δh from your r, H and Z_cp", got.get("dh_mm"), 0.01,
                            lambda r_, H_, Z_: r_ * (Z - Z_) / H_, [(r, 0.1), (H, 1), (Zcp, 0.01)], n=len(Z)),
                corrected_count("n_corr from your δh", got.get("n_corr"), dh, 0.01, 0.2)]


def corrected_count(name: str, n_corr, displacements, printed: float, limit: float) -> Hidden:
    """The count of points to correct must follow from the student's own displacements: any count their rounding
    allows (a displacement within its allowance of ``limit`` may go either way)."""
    if displacements is None:
        return Hidden(name, None, None, kind="count")
    lo, hi = count_range(displacements, printed, limit)
    exact = int(np.count_nonzero(np.abs(displacements) > limit))
    return Hidden(name, n_corr, exact, kind="count", accepted=tuple(range(lo, hi + 1)))


def chained_scales(ref: dict, bases: tuple, M: float, m_printed: float, lsn_name: str = "lsn_mm") -> dict:
    """The scale columns of a sheet computed as the guide's tables do: each from the previous one as written.

    l_пл and l_сн rounded to 0.1 mm, then m_i = l_пл·M/l_сн, m_част, m_cp and Δm/m_cp, each rounded to its printed
    unit before the next (the method of guide tables 2, 4, 5, 7).  ``ref`` holds the reference answers; without
    ``lpl_mm`` (tables 4, 7) the plan lengths follow from the reference m_i and l_сн.
    """
    from .rounding import round_to

    zones = tuple(dict.fromkeys(a for a, _ in bases))
    ls = round_to(np.asarray(ref[lsn_name], float), 0.1)
    lp = np.asarray(ref["lpl_mm"], float) if "lpl_mm" in ref else np.asarray(ref["m_i"], float) * np.asarray(
        ref[lsn_name], float) / M
    lp = round_to(lp, 0.1)
    mi = round_to(lp * M / ls, m_printed)
    mp = round_to(_zone_means(mi, bases, zones), m_printed)
    mc = float(round_to(float(np.mean(mp)), m_printed))
    dm = round_to(100.0 * (mp - mc) / mc, 0.01)
    out = {lsn_name: _floats(ls), "m_i": _floats(mi), "m_part": _floats(mp), "m_cp": mc, "dm_pct": _floats(dm)}
    if "lpl_mm" in ref:
        out["lpl_mm"] = _floats(lp)
    return out


# =========================================================================== task 03.3
@dataclass(frozen=True)
class ReliefTable4(Task):
    """Task 03.3: the bases between the corrected points and the scales again (§4 steps 5–6, table 4)."""

    id = "task-03-3"
    title = "Table 4 of your photo: the scales after the correction"
    points = 3
    cross_variant = False
    spec = scale_spec(ZONES, BASE_LABELS, lsn_name="lsn_corr_mm",
                      lsn_text="photo lengths l_сн of I-1, I-2, II-3, II-4 between the corrected points, mm")

    def inputs(self, v):
        return sheet_inputs(relief_sheet(int(v.i)))

    methods = (Method("each point with |δh| > 0.2 mm moved by δh along the ray from n, then table 2's formulas",
                      "guide §4 steps 5–6, table 4"),
               Method("each column from the previous one as written (to the printed units)",
                      "the guide's table 4 rounds every column before the next",
                      submit=lambda task, v: chained_scales(task.answers(v), RELIEF_BASES, 10000.0, 10,
                                                            "lsn_corr_mm")))

    def answers(self, v) -> dict:
        return scale_answers(relief_sheet(int(v.i)).work().table4, "lsn_corr_mm")

    def hidden(self, v, got) -> list:
        sheet = relief_sheet(int(v.i))
        return scale_hidden(got, RELIEF_BASES, sheet.M, lsn_name="lsn_corr_mm", l_plan_truth=sheet.l_plan_mm)


TASKS = (ReliefTable2(), ReliefTable3(), ReliefTable4())
