"""Chapter 06 · guide §7 (single-strip phototriangulation): tables 8 and 9, transcribed once and audited.

Table 8 gives the reduction coefficients K = l_осн/l_воск of the four bases
around a free strip, from four control points with coordinates (X north,
Y east — the Russian geodetic convention — metres) plotted at 1:10000;
table 9 the corrections v = r·(k − 1) of twelve points with k = 1.037.

:func:`table` (``table(8)``, ``table(9)``) recomputes them from their own printed
inputs (with :mod:`aerophoto.triangulation`) and return
:class:`~aerophoto.guide.audit.Audit` records: every printed number beside
the number that follows, under the one rule of :mod:`aerophoto.guide.audit`
(within 0.6 of a unit of the last printed digit).  Under the earlier rule of
this table (half a unit, 0.5·10⁻ᵈ) every verdict is the same: no printed
value of tables 8 and 9 lies between 0.5 and 0.6 of a unit from its
computed value.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from .. import triangulation as tri
from .._validate import check_positive, check_range
from .audit import Audit, discrepancy_frame, printed

__all__ = ["SOURCE", "GUIDE_S7_CONTROL", "GUIDE_TABLE8", "GUIDE_TABLE8_MEAN", "GUIDE_TABLE9", "table", "table8", "table9",
           "audits", "discrepancies"]

SOURCE = "guide §7"

#: guide §7: the control points (X north, Y east in the Russian geodetic convention), metres
GUIDE_S7_CONTROL = {
    "496/1": (6067202.0, 310574.0),
    "496/2": (6065910.0, 310466.0),
    "498/1": (6066967.0, 312528.0),
    "498/2": (6065525.0, 312664.0),
}

#: guide §7, table 8 as printed: (from, to, l_осн mm, l_воск mm, K, ΔK)
GUIDE_TABLE8 = (
    ("496/1", "498/1", 197.0, 190.0, 1.037, 0.000),
    ("498/1", "498/2", 145.0, 140.0, 1.036, -0.001),
    ("498/2", "496/2", 222.0, 217.0, 1.037, 0.000),
    ("496/2", "496/1", 131.0, 126.0, 1.038, +0.001),
)
#: guide §7: "R составляет 1,037"
GUIDE_TABLE8_MEAN = 1.037

#: guide §7, table 9 as printed: k and, per column, the (garbled) label, r (mm) and v (mm)
GUIDE_TABLE9 = {
    "k": 1.037,
    "labels": ("496", "498", "7/967", "496/1", "7/867", "498/1", "7/267", "497/1", "7/967", "496/1", "7/867", "498/1"),
    "r_mm": (54, 72, 26, 40, 61, 76, 65, 35, 96, 40, 133, 96),
    "v_mm": (2.0, 2.7, 1.0, 1.5, 2.3, 2.8, 2.4, 1.3, 3.6, 1.5, 4.9, 3.6),
}

# the units of the printed digits: lengths to 1 mm, coefficients to 0.001, corrections to 0.1 mm
_UNIT_MM = 1.0
_UNIT_K = 0.001
_UNIT_V = 0.1


def _printed_table8() -> pd.DataFrame:
    return pd.DataFrame([(f"{a} – {b}", lo, lv, k, dk) for a, b, lo, lv, k, dk in GUIDE_TABLE8],
                        columns=["base", "l_осн, mm", "l_воск, mm", "K", "ΔK"]).set_index("base")


def table8(M: float = 10000.0) -> Audit:
    """Table 8 (guide §7) recomputed from its inputs: the control coordinates at 1:M and the printed l_воск.

    Checks every printed l_осн against the coordinates, every K against
    l_осн/l_воск with the printed l_осн, the mean, the ΔK column and the
    guide's 0.003 rule on the spread (recomputed from the printed lengths
    and from the coordinates).

    Parameters
    ----------
    M : float
        The plan's scale denominator 1/M (guide: 10000).

    Returns
    -------
    Audit
        ``table``: per base the distance L from the coordinates (m), l_осн
        from the coordinates and as printed (mm), the printed l_воск, k from
        both l_осн, the printed K and ΔK, and Δk from the coordinates.
    """
    Mv = check_positive("M", M)
    values, rows = [], []
    k_printed_l, k_coord = [], []
    for a, b, l_osn, l_vosk, K, dK in GUIDE_TABLE8:
        pa, pb = np.array(GUIDE_S7_CONTROL[a]), np.array(GUIDE_S7_CONTROL[b])
        L_m = float(np.hypot(*(pb - pa)))
        l_c = L_m * 1000.0 / Mv
        where = f"table 8, {a} – {b}"
        values.append(printed(
            where, "l_осн, mm", l_osn, l_c, _UNIT_MM,
            note=f"L = {L_m:.1f} m from the coordinates → {l_c:.2f} mm at 1:{Mv:.0f}",
            reason=f"the control coordinates put {a} and {b} {L_m:.1f} m apart: {l_c:.1f} mm at 1:{Mv:.0f}, "
                   f"not the printed {l_osn:g} mm"))
        kp = l_osn / l_vosk
        kc = l_c / l_vosk
        values.append(printed(
            where, "K = l_осн/l_воск (printed l_осн)", K, kp, _UNIT_K,
            note=f"{l_osn:g} / {l_vosk:g} = {kp:.4f}",
            reason=f"{l_osn:g} / {l_vosk:g} = {kp:.4f}: the printed K does not follow even from the printed "
                   f"lengths (from the coordinates {l_c:.1f} / {l_vosk:g} = {kc:.4f})"))
        k_printed_l.append(kp)
        k_coord.append(kc)
        rows.append((f"{a} – {b}", L_m, l_c, l_osn, l_vosk, kc, kp, K, dK))
    kp_arr, kc_arr = np.array(k_printed_l), np.array(k_coord)
    K_printed = np.array([r[4] for r in GUIDE_TABLE8])
    values.append(printed("table 8, mean", "mean of the printed K", GUIDE_TABLE8_MEAN, float(K_printed.mean()),
                          _UNIT_K, note="the printed K do average 1.037"))
    values.append(printed(
        "table 8, mean", "mean K = l_осн/l_воск (printed l_осн)", GUIDE_TABLE8_MEAN, float(kp_arr.mean()), _UNIT_K,
        note="mean of the recomputed coefficients",
        reason=f"the coefficients recomputed from the printed lengths average {kp_arr.mean():.4f}; the printed "
               "R = 1.037 averages the printed K of rows 3 and 4, which do not follow"))
    dk_p = kp_arr - kp_arr.mean()
    for (a, b, *_r, dK), d in zip(GUIDE_TABLE8, dk_p):
        values.append(printed(
            f"table 8, {a} – {b}", "ΔK (printed l_осн)", dK, float(d), _UNIT_K, note="K − mean K",
            reason=f"K − mean K from the printed lengths is {d:+.4f}: the printed ΔK are those of the printed K, "
                   "and the K of rows 3 and 4 do not follow"))
    spread_p = float(np.max(np.abs(dk_p)))
    spread_c = float(np.max(np.abs(kc_arr - kc_arr.mean())))
    largest_printed = max(abs(r[5]) for r in GUIDE_TABLE8)
    values.append(printed(
        "table 8, spread", "largest |ΔK| (printed l_осн) ≤ 0.003?", largest_printed, spread_p, _UNIT_K,
        note="the printed ΔK stay within 0.003; recomputed they do not",
        reason=f"the printed ΔK stay within 0.003; recomputed from the printed lengths the largest |ΔK| is "
               f"{spread_p:.4f} > 0.003: the strip breaks the guide's own rule"))
    values.append(printed(
        "table 8, spread", "largest |ΔK| (l_осн from coordinates) ≤ 0.003?", largest_printed, spread_c, _UNIT_K,
        note="with the distances from the coordinates",
        reason=f"with the distances from the coordinates the largest |Δk| is {spread_c:.4f} > 0.003: the strip "
               "breaks the guide's own rule"))
    df = pd.DataFrame(rows, columns=["base", "L from coordinates, m", "l_осн from coordinates, mm", "l_осн printed, mm",
                                     "l_воск printed, mm", "k (l_осн from coordinates)", "k (printed l_осн)",
                                     "K printed", "ΔK printed"]).set_index("base")
    df["Δk (from coordinates)"] = kc_arr - kc_arr.mean()
    notes = (
        f"mean k from the coordinates: {kc_arr.mean():.4f}; from the printed l_осн: {kp_arr.mean():.4f}; printed R = 1.037",
        "the guide's rows are the four sides of the quadrilateral 496/1 → 498/1 → 498/2 → 496/2 → 496/1",
    )
    return Audit(SOURCE, "Table 8. Reduction coefficients", df, tuple(values), _printed_table8(), notes)


def table9() -> Audit:
    """Table 9 (guide §7) recomputed: v = r·(k − 1) with the printed r and k = 1.037.

    Also checks the printed distances against table 8's template: a point
    cannot be nearer the centre than allows the distance between two control
    points on the template (triangle inequality r_a + r_b ≥ l_воск(a, b)),
    and one point cannot have two distances from one centre.

    Returns
    -------
    Audit
        ``table``: one column a point (r, v computed, v printed, mm);
        ``result``: the :class:`~aerophoto.triangulation.ReductionCorrections`.
    """
    k = GUIDE_TABLE9["k"]
    labels, r, v = GUIDE_TABLE9["labels"], np.array(GUIDE_TABLE9["r_mm"], float), np.array(GUIDE_TABLE9["v_mm"], float)
    corr = tri.reduction_corrections([f"{j + 1}: {lab}" for j, lab in enumerate(labels)], r, k, centre="(not named)")
    values = []
    for j, (lab, rr, vp, vc) in enumerate(zip(labels, r, v, corr.v_mm)):
        values.append(printed(f"table 9, column {j + 1} ({lab})", "v = r·(k − 1), mm", vp, float(vc), _UNIT_V,
                              note=f"{rr:g} × {k - 1:.3f} = {vc:.3f}",
                              reason=f"{rr:g} × {k - 1:.3f} = {vc:.3f} mm"))
    # consistency with table 8: 496/1 and 498/1 are 190 mm apart on the template
    l_vosk = {frozenset((a, b)): lv for a, b, _lo, lv, _k, _d in GUIDE_TABLE8}
    by_label = {}
    for lab, rr in zip(labels, r):
        by_label.setdefault(lab, []).append(float(rr))
    for (a, b), lv in ((tuple(sorted(p)), lv) for p, lv in l_vosk.items()):
        if a in by_label and b in by_label:
            best = max(by_label[a]) + max(by_label[b])
            values.append(printed(
                f"table 9 vs table 8, {a} and {b}", "r_a + r_b ≥ l_воск(a, b)?", lv, best, _UNIT_MM,
                bounds=(0.0, best), computed_text=f"≤ {best:g}",
                note=f"largest printed r_a + r_b = {best:g} mm against l_воск = {lv:g} mm",
                reason=f"{a} and {b} are {lv:g} mm apart on the template of table 8, but no centre can be "
                       f"{max(by_label[a]):g} mm from one and {max(by_label[b]):g} mm from the other "
                       f"(r_a + r_b = {best:g} mm < {lv:g} mm): the distances were not measured on that strip"))
    for lab, rs in by_label.items():
        if len(rs) > 1 and len(set(rs)) > 1:
            values.append(printed(
                f"table 9, label {lab}", "one point, one distance?", rs[0], rs[1], _UNIT_MM, computed_text=f"{rs[1]:g}",
                note=f"the label appears {len(rs)} times with r = {', '.join(f'{x:g}' for x in rs)} mm",
                reason=f"the label appears {len(rs)} times with r = {', '.join(f'{x:g}' for x in rs)} mm: one "
                       "point has one distance from one centre (the labels are garbled in the scan)"))
    df = corr.table(wide=True)
    df.loc["v printed, mm"] = v
    notes = (
        "every printed v is r·(k − 1) rounded to 0.1 mm",
        "the point labels are garbled in the scan (7/967, 7/867 … repeat); 496/1 appears twice and 498/1 twice with "
        "different r, and no centre can be 40 mm from 496/1 and at most 96 mm from 498/1 when the two are 190 mm apart "
        "on the template (table 8)",
    )
    printed_df = pd.DataFrame({"label": labels, "r, mm": GUIDE_TABLE9["r_mm"], "v, mm": GUIDE_TABLE9["v_mm"]},
                              index=pd.RangeIndex(1, len(labels) + 1, name="column"))
    return Audit(SOURCE, "Table 9. Corrections for reduction", df, tuple(values), printed_df, notes, result=corr)


def table(number: int) -> Audit:
    """The guide's table ``number`` (8 or 9) of §7, recomputed from its printed inputs and audited."""
    n = int(check_range("number", number, 8, 9))
    return table8() if n == 8 else table9()


def audits() -> tuple:
    """The audits of tables 8 and 9, in order."""
    return (table8(), table9())


def discrepancies() -> pd.DataFrame:
    """Every printed number of tables 8 and 9 that does not follow from its inputs, with the reason.

    One row per value: source, table, where, quantity, printed, computed, reason
    (:func:`aerophoto.guide.audit.discrepancy_frame`).
    """
    return discrepancy_frame(audits())
