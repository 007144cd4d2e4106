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
from .base import Answer, Hidden, Task, submitted_number

__all__ = ["TOL_XY_MM", "TOL_LEN_MM", "TOL_M_I", "TOL_M_PART", "TOL_M_CP", "TOL_DM_PCT", "BASE_LABELS",
           "ZONES", "numbers", "scale_answers", "scale_spec", "scale_hidden", "sheet_answers", "sheet_hidden",
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


def numbers(x, n: int):
    """A submitted sequence as a float array of length ``n``, or None if it is not ``n`` finite numbers."""
    if x is None or x is Ellipsis or isinstance(x, (str, bytes, dict, bool)):
        return None
    try:
        out = np.array([float(e) for e in (x.tolist() if hasattr(x, "tolist") else x)], dtype=float)
    except (TypeError, ValueError):
        return None
    if len(out) != n or not np.all(np.isfinite(out)):
        return None
    return out


def _floats(a) -> list:
    return [float(x) for x in np.ravel(a)]


def scale_answers(table, lsn_name: str = "lsn_mm") -> dict:
    """A :class:`~aerophoto.displacement.ScaleTable` as the answers l_сн (``lsn_name``), m_i, m_part, m_cp, dm_pct."""
    return {lsn_name: _floats([b.l_photo_mm for b in table.bases]), "m_i": _floats(table.m_i),
            "m_part": _floats(table.m_part), "m_cp": float(table.m_mean), "dm_pct": _floats(100.0 * table.relative_dm)}


def scale_spec(zones: tuple, bases: tuple, *, lsn_name: str = "lsn_mm", lsn_text: str) -> tuple:
    """The answers of a scale table (2, 4, 5, 7): l_сн, m_i, m_част, m_cp, Δm_i/m_cp."""
    return (
        Answer(lsn_name, lsn_text, unit="mm", kind="values", tol_abs=TOL_LEN_MM, labels=bases),
        Answer("m_i", "scale denominators m_i = l_пл·M/l_сн of the bases", kind="values", tol_rel=TOL_M_I,
               labels=bases),
        Answer("m_part", f"partial scale denominators m_част of zones {', '.join(zones)}", kind="values",
               tol_rel=TOL_M_PART, labels=tuple(f"zone {z}" for z in zones)),
        Answer("m_cp", "mean scale denominator m_cp", tol_rel=TOL_M_CP),
        Answer("dm_pct", "Δm_i/m_cp of each zone, % (Δm_i = m_част − m_cp, with its sign)", unit="%",
               kind="values", tol_abs=TOL_DM_PCT, labels=tuple(f"zone {z}" for z in zones)),
    )


def _dev(a, b) -> float:
    return float(np.max(np.abs(np.asarray(a, dtype=float) - np.asarray(b, dtype=float))))


def scale_hidden(got: dict, bases: tuple, M: float, *, lsn_name: str = "lsn_mm", l_plan=None,
                 l_plan_truth=None) -> list:
    """Hidden checks of a scale table: every column follows from the student's own previous column.

    m_i from the student's l_пл (``l_plan``, submitted) or — when the plan lengths are not part of the task —
    the student's m_i·l_сн/M against the true plan lengths within the measuring tolerance; m_част, m_cp and
    Δm/m_cp from the student's own m_i.
    """
    nb = len(bases)
    zones = tuple(dict.fromkeys(a for a, _ in bases))
    lsn = numbers(got.get(lsn_name), nb)
    m_i = numbers(got.get("m_i"), nb)
    m_part = numbers(got.get("m_part"), len(zones))
    m_cp = submitted_number(got.get("m_cp"))
    dm = numbers(got.get("dm_pct"), len(zones))
    out = []
    if l_plan is not None:
        ok = lsn is not None and m_i is not None and np.all(lsn > 0) and np.all(l_plan > 0)
        rel = _dev(m_i / (l_plan * M / lsn), 1.0) if ok else None
        out.append(Hidden("m_i from your l_пл and l_сн", rel, 0.0, tol_abs=0.002))
    else:
        ok = lsn is not None and m_i is not None
        dev = _dev(m_i * lsn / M, l_plan_truth) if ok else None
        out.append(Hidden("m_i·l_сн/M gives the plan lengths", dev, 0.0, tol_abs=TOL_LEN_MM))
    if m_i is not None and m_part is not None:
        own = np.array([np.mean([m for m, (a, _) in zip(m_i, bases) if a == z]) for z in zones])
        out.append(Hidden("m_част from your m_i", _dev(m_part / own, 1.0), 0.0, tol_abs=0.001))
    else:
        out.append(Hidden("m_част from your m_i", None, 0.0))
    ok = m_part is not None and m_cp is not None and m_cp > 0
    out.append(Hidden("m_cp from your m_част", abs(m_cp / float(np.mean(m_part)) - 1.0) if ok else None, 0.0,
                      tol_abs=0.001))
    ok = ok and dm is not None
    out.append(Hidden("Δm/m_cp from your m_част and m_cp", _dev(dm, 100.0 * (m_part - m_cp) / m_cp) if ok else None,
                      0.0, tol_abs=0.02))
    return out


def sheet_answers(sheet, table) -> dict:
    """The answers of a lab sheet's first table (tasks 03.1 and 04.2): the points' x, y on the photo (mm), the
    plan lengths l_пл (mm) and the scale columns of ``table`` (:func:`scale_answers`).

    ``sheet`` is an :class:`aerophoto.labs.displacement.LabSheet`; ``table`` its
    :class:`~aerophoto.displacement.ScaleTable` (guide table 2 or 5).
    """
    xy = sheet.photo_xy_mm
    return {"x_mm": _floats(xy[:, 0]), "y_mm": _floats(xy[:, 1]), "lpl_mm": _floats(sheet.l_plan_mm),
            **scale_answers(table)}


def sheet_hidden(got: dict, sheet, names: tuple, bases: tuple) -> list:
    """Hidden checks of a lab sheet's first table (tasks 03.1 and 04.2): l_сн from the student's own x, y (within
    0.06 mm), then every scale column from the student's previous one (:func:`scale_hidden`, with their l_пл).

    ``names`` are the sheet's points in the order of ``x_mm``/``y_mm``, ``bases`` its (zone point, point) pairs.
    """
    xy = [numbers(got.get(k), len(names)) for k in ("x_mm", "y_mm")]
    lsn = numbers(got.get("lsn_mm"), len(bases))
    dev = None
    if xy[0] is not None and xy[1] is not None and lsn is not None:
        dev = _dev(lsn, base_lengths_mm(names, np.column_stack(xy), bases))
    lpl = numbers(got.get("lpl_mm"), len(bases))
    return [Hidden("l_сн from your x, y", dev, 0.0, tol_abs=0.06), *scale_hidden(got, bases, sheet.M, l_plan=lpl)]


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
               tol_abs=TOL_XY_MM, labels=RELIEF_NAMES),
        Answer("y_mm", "y of I, 1, 2, II, 3, 4 on your photo, mm (measured)", unit="mm", kind="values",
               tol_abs=TOL_XY_MM, labels=RELIEF_NAMES),
        Answer("lpl_mm", "plan lengths l_пл of I-1, I-2, II-3, II-4, mm (measured on the plan)", unit="mm",
               kind="values", tol_abs=TOL_LEN_MM, labels=BASE_LABELS),
        *scale_spec(ZONES, BASE_LABELS, lsn_text="photo lengths l_сн of I-1, I-2, II-3, II-4, mm"),
    )

    def inputs(self, v):
        """The student's lab sheet (:class:`aerophoto.labs.displacement.LabSheet`): photo, plan, heights."""
        return relief_sheet(int(v.i))

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
        Answer("Zcp_m", "mean object plane Z_cp, m", unit="m", tol_abs=0.05),
        Answer("H_m", "flying height H = m_cp·f above it, m", unit="m", tol_rel=0.02),
        Answer("xn_mm", "x of the nadir point n, mm", unit="mm", tol_abs=0.05),
        Answer("yn_mm", "y of the nadir point n, mm", unit="mm", tol_abs=0.05),
        Answer("r_mm", "distances r of I, 1, 2, II, 3, 4 from n, mm", unit="mm", kind="values", tol_abs=0.3,
               labels=RELIEF_NAMES),
        Answer("dh_mm", "relief displacements δh = r·h/H of the six points, mm (+ away from n)", unit="mm",
               kind="values", tol_abs=0.01, tol_rel=0.03, labels=RELIEF_NAMES),
        Answer("n_corr", "number of points corrected (|δh| > 0.2 mm)", integer=True),
    )

    def inputs(self, v):
        return relief_sheet(int(v.i))

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

    def hidden(self, v, got) -> list:
        """δh from the student's own r, H and Z_cp (and the given heights); the count from the student's own δh."""
        Z = relief_sheet(int(v.i)).Z_given_m
        r = numbers(got.get("r_mm"), len(Z))
        dh = numbers(got.get("dh_mm"), len(Z))
        H, Zcp = submitted_number(got.get("H_m")), submitted_number(got.get("Zcp_m"))
        dev = None
        if r is not None and dh is not None and H and Zcp is not None:
            dev = _dev(dh, r * (Z - Zcp) / H)
        count = None if dh is None else int(np.count_nonzero(np.abs(dh) > 0.2))
        return [Hidden("δh from your r, H and Z_cp", dev, 0.0, tol_abs=0.006),
                Hidden("n_corr from your δh", got.get("n_corr") if count is not None else None, count, kind="count")]


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
        return relief_sheet(int(v.i))

    def answers(self, v) -> dict:
        return scale_answers(relief_sheet(int(v.i)).work().table4, "lsn_corr_mm")

    def hidden(self, v, got) -> list:
        sheet = relief_sheet(int(v.i))
        return scale_hidden(got, RELIEF_BASES, sheet.M, lsn_name="lsn_corr_mm", l_plan_truth=sheet.l_plan_mm)


TASKS = (ReliefTable2(), ReliefTable3(), ReliefTable4())
