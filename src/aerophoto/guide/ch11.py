"""Chapter 11 · guide §12 (rectification of photos of flat ground): table 11 and the list of plan coordinates, audited.

Table 11 ("Определение среднего коэффициента деформации фотобумаги и
толщины подложки") gives six lengths l₁…l₆ on the glass control grid (l₀)
and on its contact print (l_i), their differences δl, the sums, and — in the
text beside it — K_d = [δl]/[l₀] = −0.7/734.8 = −0.00095264 and the substrate
thickness t = K_d·f·(K_t + 1) = −0.00095264·108·(3 + 1) = 0.4115 with
m = 15 000, M = 5000, f = 108.  :func:`table_11` recomputes all of it with
:mod:`aerophoto.rectify`.

What the audit finds
--------------------
* δl, the three sums and K_d follow from the printed lengths.
* The OCR drops the operator of δl ("δl = l_i^0 l_i"); the printed values
  (−0.5 for 100 vs 100.5, +0.2 for 152.40 vs 152.2) fix it as δl = l₀ − l_i.
* l₀ = 152.40 mm is not a multiple of the 5 mm square, as the text's rule
  "5 mm·n" would want: it is the diagonal of a rectangle of 20 × 23 squares,
  5·√(20² + 23²) = 152.398 mm, across the lines l₁, l₂ (20 squares, 100 mm)
  and l₃, l₄ (23 squares, 115 mm).
* The substrate thickness is printed +0.4115: the product of the printed
  factors is −0.4115.  The magnitude is right; the sign is dropped — and with
  it the direction: K_d < 0 means the paper stretched, so the image must be
  projected smaller, i.e. the paper (not the planchet) lifted by 0.41 mm
  (see :mod:`aerophoto.rectify`, "Sign of t").
* The column head "l₀, м" reads metres; the lengths are millimetres.

The list of plan coordinates (:data:`PLAN_POINTS`, points 550, 551, 641,
644) has nothing computed from it; :func:`plan_points` returns it with the
distances between the points for reference.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from .. import rectify as r
from .audit import Audit, printed

__all__ = ["SOURCE", "TABLE_11", "TABLE_11_INPUTS", "PLAN_POINTS", "GRID_SQUARES", "REASONS", "table_11",
           "plan_points", "discrepancies"]

SOURCE = "guide §12"

#: table 11 as printed: (line, l₀ mm, l_i mm, δl mm printed); sums printed (Σl₀, Σl_i, Σδl)
TABLE_11 = dict(
    lines=(("l1", 100.0, 100.5, -0.5), ("l2", 100.0, 100.0, 0.0), ("l3", 115.0, 115.0, 0.0),
           ("l4", 115.0, 115.3, -0.3), ("l5", 152.40, 152.5, -0.1), ("l6", 152.40, 152.2, +0.2)),
    sums=(734.8, 735.5, -0.7),
    K_d="-0.00095264",
    t="0.4115",
)
#: the known parameters printed beside table 11: photo 1:m, plan 1:M, f (mm)
TABLE_11_INPUTS = dict(m=15000.0, M=5000.0, f_mm=108.0, K_t_printed=3.0)
#: the squares each grid length spans (along, across): 100 = 5·20, 115 = 5·23, 152.40 = 5·√(20² + 23²)
GRID_SQUARES = {"l1": (20, 0), "l2": (20, 0), "l3": (23, 0), "l4": (23, 0), "l5": (20, 23), "l6": (20, 23)}
#: §12's "список плановых координат": point, X, Y (as printed; units not stated — metres of a local system)
PLAN_POINTS = (("550", 6474.1, 746.6), ("551", 6448.4, 930.0), ("641", 5636.2, 920.5), ("644", 5634.4, 1188.8))

REASONS = {
    ("formula", "t, mm"): ("the sign is dropped: K_d·f·(K_t + 1) = −0.00095264·108·4 = {c:.4f}. The magnitude is "
                           "right; the sign says which way: the paper stretched (K_d < 0), so the image must be "
                           "projected smaller — the paper, not the planchet, raised by 0.41 mm"),
}


def table_11() -> Audit:
    """Table 11 recomputed from its printed lengths and parameters, every printed number checked."""
    t = TABLE_11
    names = [ln[0] for ln in t["lines"]]
    l0 = np.array([ln[1] for ln in t["lines"]])
    li = np.array([ln[2] for ln in t["lines"]])
    pd_ = r.paper_deformation(l0, li)
    inp = TABLE_11_INPUTS
    K_t = r.enlargement(inp["m"], inp["M"])
    thick = r.substrate_thickness_mm(pd_.K_d, inp["f_mm"], K_t)
    values = []
    for (name, l0p, _lip, dlp), dl in zip(t["lines"], pd_.dl_mm):
        values.append(printed(name, "δl, mm", dlp, dl, 0.1, reasons=REASONS))
        n1, n2 = GRID_SQUARES[name]
        values.append(printed(name, "l₀ = 5 mm·n, mm", l0p, r.control_grid_length_mm(n1, n2), 0.01 if n2 else 1.0,
                              reasons=REASONS,
                              note="the diagonal of 20 × 23 squares" if n2 else ""))
    for q, p, c in zip(("Σl₀, mm", "Σl_i, mm", "Σδl, mm"), t["sums"], (pd_.sum_l0_mm, pd_.sum_li_mm, pd_.sum_dl_mm)):
        values.append(printed("Σ", q, p, c, 0.1, reasons=REASONS))
    values.append(printed("formula", "K_d", float(t["K_d"]), pd_.K_d, 1e-8, reasons=REASONS,
                          printed_text=t["K_d"], computed_text=f"{pd_.K_d:.9f}"))
    values.append(printed("formula", "K_t = m/M", inp["K_t_printed"], K_t, 1.0, reasons=REASONS))
    values.append(printed("formula", "t, mm", float(t["t"]), thick, 1e-4, reasons=REASONS, printed_text=t["t"],
                          computed_text=f"{thick:.5f}"))
    table = pd_.table(names)
    table["squares (along × across)"] = [f"{a}" if b == 0 else f"{a} × {b} (diagonal)"
                                         for a, b in (GRID_SQUARES[n] for n in names)] + [""]
    notes = (
        "δl = l₀ − l_i: the scan drops the minus sign of the table's head (δl = l_i^0 l_i); the printed values fix it.",
        "l₅, l₆ = 152.40 mm are not 5 mm·n but diagonals: 5·√(20² + 23²) = 152.398 mm across the 100 × 115 mm "
        "rectangle of l₁…l₄.",
        f"K_d = {pd_.K_d:.8f} < 0: the print is larger than the grid — the paper stretched.",
        f"K_t = m/M = {inp['m']:.0f}/{inp['M']:.0f} = {K_t:g}; projection distance f·(K_t + 1) = "
        f"{r.projection_distance_mm(inp['f_mm'], K_t):.0f} mm.",
        f"t = {thick:.4f} mm: a substrate of {abs(thick):.2f} mm — under the paper at exposure (the sign), not under "
        "the planchet. The guide prints +0.4115.",
        "The column head 'l₀, м' should read mm.",
    )
    return Audit(SOURCE, "Table 11. The mean deformation coefficient of the photo paper and the substrate thickness",
                 table, tuple(values), printed_table=_printed_frame(), notes=notes, result=(pd_, thick))


def _printed_frame() -> pd.DataFrame:
    t = TABLE_11
    df = pd.DataFrame([(ln[1], ln[2], ln[3]) for ln in t["lines"]], columns=["l₀", "l_i", "δl"],
                      index=pd.Index([ln[0] for ln in t["lines"]], name="line"))
    df.loc["Σ"] = t["sums"]
    return df


def plan_points() -> pd.DataFrame:
    """§12's list of plan coordinates (points 550, 551, 641, 644) with the sides of their quadrilateral.

    Nothing in the guide is computed from it.  Taken round the quadrilateral
    (550, 551, 644, 641: north-west, north-east, south-east, south-west with
    X north, Y east) its sides show the shape: long and narrow, about 830 m
    north–south by 180–270 m east–west.  Column ``side`` names the side from
    each point to the next one round, ``length`` its length (the list's units).
    """
    df = pd.DataFrame(list(PLAN_POINTS), columns=["point", "X", "Y"]).set_index("point")
    order = ["550", "551", "644", "641"]
    P = df.loc[order, ["X", "Y"]].to_numpy()
    nxt = np.roll(P, -1, axis=0)
    sides = {a: (f"{a}–{b}", round(math.hypot(*(q - p)), 1))
             for a, b, p, q in zip(order, np.roll(order, -1), P, nxt)}
    df["side"] = [sides[k][0] for k in df.index]
    df["length"] = [sides[k][1] for k in df.index]
    return df


def discrepancies() -> pd.DataFrame:
    """Every printed value of §12 that does not follow from its inputs."""
    from .audit import discrepancy_frame

    return discrepancy_frame([table_11()])
