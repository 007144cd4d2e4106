"""Chapter 14 · article 001 (accuracy of phototriangulation networks): the formulas as reconstructed, and its printed numbers.

The article is a textbook section (formula numbers 10.20–10.21, figures 10.7–10.8).
The scan lost both formulas and the accumulation scheme between them; what it
keeps is the prose, the symbols' legend and four worked numbers.  This module
holds the reconstruction (:data:`RECONSTRUCTION`), the printed numbers as data
(:data:`PRINTED`) and :func:`examples`, an :class:`~aerophoto.guide.Audit` of
every printed number against the reconstructed formulas of
:mod:`aerophoto.accuracy`.
"""

from __future__ import annotations

import math

import pandas as pd

from .. import accuracy as acc
from .audit import Audit, printed

__all__ = ["RECONSTRUCTION", "PRINTED", "examples", "discrepancies"]

RECONSTRUCTION = """\
Article 001, formulas (10.20) and (10.21) — lost in the scan — as the book reads them.

(10.20)  m_n = d·√(1² + 2² + … + n²) = d·√(n(n + 1)(2n + 1)/6) ≈ d·√(n³/3)

  How: the article describes the scheme it sums — an error d_j made in link j
  changes the scale of every later base and "persists in all subsequent links",
  so a point of link n carries n·d₁ + (n − 1)·d₂ + … + 1·d_n; with equal
  independent d_j "by the rules of the theory of errors" the RMS is d·√(Σk²).
  The simulation (aerophoto.accuracy.strip_monte_carlo) confirms the shape:
  the free strip's RMS error over its links follows d·√(Σk²) to a few per cent
  and grows as n^1.5 for long strips.

(10.21)  m_X = 0.25·m·m_q·√n³,  m_Y = 0.16·m·m_q·√n³,
         m_Z = 0.25·m·m_q·(f/b)·√n³,  m_D = √(0.25² + 0.16²)·m·m_q·√n³ = 0.297·m·m_q·√n³

  How: the article builds (10.21) from (10.20) by replacing n with n/2, halving,
  and replacing d by the errors of a single model (its formula 8.40, not in the
  article); the legend names m_D, m_Z, m, m_q, f and b.  With the n³/3 form of
  (10.20) the recipe gives ½·√((n/2)³/3) = √(n³/96), so the printed example
  (n = 10, m_q = 0.01 mm, f = b = 70 mm: m_X = m_Z = 0.08 mm, m_D = 0.11 mm,
  m_Y = 0.05 mm) fixes the coefficients 0.25 and 0.16 (m_X: 0.079 mm,
  m_Y: 0.051 mm); f/b goes with the height (the base–height ratio).
  0.25 = √6/√96: a single model's error √6·m_q in X and Z (for f = b).

  m_D — two readings.  The legend calls m_D (with m_Z) the error of the network
  "in plan", i.e. √(m_X² + m_Y²): coefficient 0.297, 0.094 mm in the example.
  The example prints 0.11 mm = √2·m_X (coefficient 0.35), as if Y were as bad
  as X.  The design example decides: with 0.297 the plan spacing is n ≈ 8.6,
  8 bases as printed; with 0.35 it is 7.7 → 7, and the printed 8 would be a
  second slip.  The book adopts the legend's plan error (one slip, the 0.11,
  instead of two); accuracy.COEFF_D_SQRT2 keeps the other reading.  Heights:
  n ≈ 3.0, printed "2–3", in both readings.

Two remarks the simulation supports:
  * the recipe "n → n/2, halve" ignores that the middle's error and the end's
    are correlated; for a strip fitted to both ends the exact variance of the
    middle is (n³ + 2n)/48·d², √2 times the recipe's RMS for long strips — the
    Monte Carlo's middle errors follow the exact law's shape;
  * the printed m_D = 0.11 mm is √2·m_X, not the plan error √(m_X² + m_Y²) =
    0.094 mm of the printed m_X and m_Y that the legend names: a slip that
    treats both plan coordinates as badly as X.
"""

#: article 001's printed numbers (photo-scale mm unless stated)
PRINTED = {
    "example": {"n": 10, "mq_mm": 0.01, "f_mm": 70.0, "b_mm": 70.0, "mX_mm": "0.08", "mZ_mm": "0.08",
                "mD_mm": "0.11", "mY_mm": "0.05"},
    "plan": {"mean_error_map_mm": 0.5, "rms_map_mm": "0.6", "mD_map_mm": "0.3", "m": 20000.0, "M": 10000.0,
             "mq_mm": 0.02, "n": 8},
    "height": {"contour_m": 2.5, "mZ_m": "0.52", "m": 20000.0, "M": 10000.0, "f_mm": 100.0, "b_mm": 100.0,
               "mq_mm": 0.02, "n_range": (2, 3)},
    "block_gain": (1.5, 2.0),
}


def _unit(text: str) -> float:
    t = text.replace(",", ".")
    return 10.0 ** (-len(t.split(".")[1])) if "." in t else 1.0


def examples() -> Audit:
    """Every printed number of article 001 against the reconstructed (10.20)–(10.21)."""
    ex, pl, ht = PRINTED["example"], PRINTED["plan"], PRINTED["height"]
    e = acc.strip_errors_mm(ex["n"], ex["mq_mm"], f_mm=ex["f_mm"], b_mm=ex["b_mm"])
    vals = []
    dxy = math.hypot(float(ex["mX_mm"]), float(ex["mY_mm"]))
    for key, q in (("X", "mX_mm"), ("Z", "mZ_mm"), ("D", "mD_mm"), ("Y", "mY_mm")):
        vals.append(printed("example (n = 10, m_q = 0.01 mm, f = b = 70 mm)", f"m_{key}, mm", float(ex[q]), e[key],
                            _unit(ex[q]), reason=(
                                f"m_D is the plan error (the legend): √(m_X² + m_Y²) = {e['D']:.3f} mm "
                                f"(of the printed 0.08 and 0.05: {dxy:.3f} mm); the printed 0.11 mm is √2·m_X, as "
                                "if Y were as bad as X — the one slip of this reading (the other reading, "
                                "m_D = √2·m_X, keeps the 0.11 but then contradicts the printed n = 8)")))
    rms = pl["mean_error_map_mm"] * 1.25
    vals.append(printed("plan tolerance", "RMS error of a contour point on the map, mm", float(pl["rms_map_mm"]), rms,
                        0.1))
    vals.append(printed("plan tolerance", "allowed m_D of densification (half of it), mm", float(pl["mD_map_mm"]),
                        0.5 * float(pl["rms_map_mm"]), 0.1))
    n_plan = acc.plan_bases(pl["m"], pl["M"], pl["mq_mm"], mD_map_mm=float(pl["mD_map_mm"]))
    n_whole = acc.whole_bases(n_plan)
    n_sqrt2 = n_plan * (acc.COEFF_10_21["D"] / acc.COEFF_D_SQRT2) ** (2.0 / 3.0)
    vals.append(printed("plan example (m = 20 000, M = 10 000, m_q = 0.02 mm)", "bases between plan control n",
                        pl["n"], n_whole, 1.0, computed_text=f"{n_whole} (n = {n_plan:.2f})",
                        note=f"the other reading m_D = √2·m_X gives n = {n_sqrt2:.2f} → {acc.whole_bases(n_sqrt2)}, "
                             "not the printed 8"))
    mz = acc.allowed_height_error_m(ht["contour_m"])
    vals.append(printed("height tolerance (h = 2.5 m)", "allowed m_Z = 0.5 × h/3 × 1.25, m", float(ht["mZ_m"]), mz,
                        0.01))
    n_h = acc.height_bases(ht["m"], ht["mq_mm"], contour_interval_m=ht["contour_m"], f_mm=ht["f_mm"],
                           b_mm=ht["b_mm"])
    lo, hi = ht["n_range"]
    vals.append(printed("height example (m = 20 000, f = b = 100 mm, m_q = 0.02 mm)",
                        "bases between height control (the printed range's upper end)", float(hi),
                        acc.whole_bases(n_h), 1.0, printed_text=f"{lo}–{hi}",
                        computed_text=f"{acc.whole_bases(n_h)} (n = {n_h:.2f})"))
    table = pd.DataFrame([
        ("(10.21) m_X, n = 10", "mm (photo)", e["X"]), ("(10.21) m_Y, n = 10", "mm (photo)", e["Y"]),
        ("(10.21) m_Z, n = 10", "mm (photo)", e["Z"]), ("(10.21) m_D, n = 10", "mm (photo)", e["D"]),
        ("allowed m_D on the map", "mm", 0.5 * 1.25 * pl["mean_error_map_mm"]),
        ("n for the plan (real)", "bases", n_plan), ("n for the plan (whole, ≤ 0.3 mm)", "bases", n_whole),
        ("n for the plan, other reading m_D = √2·m_X (real)", "bases", n_sqrt2),
        ("allowed m_Z (h = 2.5 m)", "m", mz), ("n for heights (real)", "bases", n_h),
    ], columns=["quantity", "unit", "value"]).set_index("quantity")
    notes = ("The formulas are the book's reconstruction (aerophoto.guide.ch14.RECONSTRUCTION): the scan lost them.",
             "The coefficients of (10.21) are fixed by the first example, so its m_X, m_Y, m_Z follow by "
             "construction; the two design examples are independent checks of the reconstruction.",
             "m_D is read as the legend names it, the plan error √(m_X² + m_Y²) (coefficient 0.297): the design "
             "example's n = 8 then follows and the example's m_D = 0.11 mm (= √2·m_X) is the one slip. Read as "
             "√2·m_X (0.35) the 0.11 follows but n = 7.7 → 7 contradicts the printed 8: two slips instead of one.")
    return Audit("article 001", "Worked numbers of article 001. Error accumulation and control spacing", table,
                 tuple(vals), notes=notes)


def discrepancies() -> pd.DataFrame:
    """Every printed number of article 001 that does not follow, with the reason."""
    from .audit import discrepancy_frame

    return discrepancy_frame([examples()])
