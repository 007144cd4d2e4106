"""Chapter 03 · guide §4 (relief displacement): tables 2, 3 and 4 as printed, recomputed and audited.

The worked example of §4 corrects a photo for relief.  Its printed inputs —
the bases' lengths l_пл and l_сн (tables 2 and 4, photoplan 1:M with
M = 10 000), the points' heights Z and distances r from the nadir point
(table 3) — are transcribed here once (:data:`TABLE2`, :data:`TABLE3`,
:data:`TABLE4`).  :func:`table` recomputes each table with
:mod:`aerophoto.displacement` and returns an :class:`~aerophoto.guide.audit.Audit`:
every printed number beside the value that follows from the inputs, by the one
rule of :mod:`aerophoto.guide.audit` (within 0.6 of a unit of the last printed
digit), and the reason wherever a value does not follow.  :func:`discrepancies`
lists them all.

The scale tables of §5 (tables 5 and 7, :mod:`aerophoto.guide.ch04`) have the
layout of tables 2 and 4 and are audited by the same helpers
(:func:`scale_values`, :func:`printed_scale_frame`, :func:`display_frame`).

Printed data are OCR cleaned; the flying height of table 3 is H = m_cp·f with
m_cp from table 2 and the guide's f = 100 mm.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np
import pandas as pd

from .. import displacement as d
from .. import geometry as g
from .._validate import check_range
from .audit import Audit, Printed, discrepancy_frame, printed

__all__ = [
    "SOURCE",
    "TABLE2",
    "TABLE3",
    "TABLE4",
    "TABLE3_BASES",
    "TITLES",
    "REASONS",
    "SIGN_REASON",
    "table",
    "audits",
    "discrepancies",
    "mean_object_plane_of_table3",
    "value",
    "scale_values",
    "ratio_unit",
    "printed_text",
    "computed_text",
    "display_frame",
    "printed_scale_frame",
]

SOURCE = "guide §4"

# --------------------------------------------------------------------------- the printed tables (OCR cleaned)
#: Table 2: bases (name, l_пл mm, l_сн mm) and the printed m_i, zone heights (m), m_част, m_cp, Δm_i, N of 1/N;
#: ``unit`` is the unit of the last printed digit of the scales (they are printed to tens)
TABLE2 = dict(bases=(("I-1", 28.0, 18.4), ("I-2", 30.1, 19.8), ("II-3", 36.0, 24.3), ("II-4", 33.8, 22.9)),
              m_i=(15220, 15220, 14810, 14760), heights=(140, 180), m_part=(15210, 14790), m_mean=15000,
              dm=(-210, +210), N=(72, 70), unit=10)
#: Table 4: as table 2, with the photo lengths corrected for relief
TABLE4 = dict(bases=(("I-1", 28.0, 18.7), ("I-2", 30.1, 20.0), ("II-3", 36.0, 24.0), ("II-4", 33.8, 22.6)),
              m_i=(15010, 15050, 15000, 14950), heights=(140, 180), m_part=(15030, 14980), m_mean=15000,
              dm=(-30, +20), N=(500, 750), unit=10)
#: Table 3: points, heights Z (m), h = Z − Z_cp (m), r from n (mm) and the printed δh (mm)
TABLE3 = dict(names=("I", "1", "2", "II", "3", "4"), Z=(141, 138, 141, 180, 178, 182),
              h=(-19, -22, -19, 20, 18, 22), r=(76, 78, 81, 83, 73, 78), delta=(-1.0, -1.1, -1.0, 1.1, 0.9, 1.1))
#: the bases of tables 2 and 4 join each zone's main point to its two other points
TABLE3_BASES = (("I", "1"), ("I", "2"), ("II", "3"), ("II", "4"))

TITLES = {
    2: "Table 2. Partial and mean scales of the bases",
    3: "Table 3. Corrections for relief",
    4: "Table 4. Partial and mean scales by the corrected points",
}

SIGN_REASON = ("sign reversed: the guide printed m_cp − m_част, but its own definition (§5 step 8: "
               "Δm = m_част − m_cp, the deviation of the partial scale from the mean) gives {c:+.0f}")

#: table → {(where, quantity): why the printed value does not follow}; ``{c}`` is the computed value
REASONS = {
    2: {
        ("I-2", "m_i"): "30.1·10000/19.8 = 15202, not 15220: the value of I-1 was copied down (the printed "
                        "m_част = 15210 was computed with 15202)",
        ("I", "Δm_i"): SIGN_REASON,
        ("II", "Δm_i"): SIGN_REASON,
        ("I", "Δm_i/m_cp"): "divided by m_част instead of m_cp: 15210/210 = 72; m_cp/|Δm| = {c:.1f}, and the "
                            "two zones, with equal |Δm|, must show the same ratio",
        ("II", "Δm_i/m_cp"): "divided by m_част instead of m_cp: 14790/210 = 70; m_cp/|Δm| = {c:.1f}",
    },
    3: {},
    4: {
        ("I-1", "m_i"): "28.0·10000/18.7 = 14973, not 15010 (15010 = 28.0·10000/18.65: the corrected length "
                        "before it was rounded to 18.7)",
        ("I", "m_част"): "carried from the misprinted m_i of I-1: (14973 + 15050)/2 = {c:.0f}",
        ("I", "Δm_i"): "sign reversed (printed m_cp − m_част) and carried from the misprinted m_i of I-1: "
                       "Δm = m_част − m_cp = {c:+.1f}",
        ("II", "Δm_i"): "sign reversed (printed m_cp − m_част) and carried from the misprinted m_i of I-1: "
                        "Δm = {c:+.1f}",
        ("I", "Δm_i/m_cp"): "carried from the misprinted m_i of I-1: m_cp/|Δm| = {c:.0f}; after the relief "
                            "correction the two zones agree to 1/900, not 1/500",
        ("II", "Δm_i/m_cp"): "carried from the misprinted m_i of I-1: m_cp/|Δm| = {c:.0f}",
    },
}


# --------------------------------------------------------------------------- helpers shared with §5
def ratio_unit(N: float) -> float:
    """Unit of the last significant digit of a printed 1/N (72 → 1, 750 → 10, 1400 → 100)."""
    N = int(round(N))
    if N < 100:
        return 1.0
    u = 1
    while N % (u * 10) == 0:
        u *= 10
    return float(u)


#: how the guide prints a quantity, and how its computed value is shown (a digit more): (quantity, printed, computed)
_FORMATS = (
    ("Δm_i/m_cp", "1/{:.0f}", "1/{:.1f}"),
    ("δα", "{:+.1f}", "{:+.2f}"),
    ("δh", "{:+.1f}", "{:+.2f}"),
    ("l_сн", "{:.1f}", "{:.2f}"),
    ("cos φ", "{:+.3f}", "{:+.4f}"),
    ("Δm_i", "{:+.0f}", "{:+.1f}"),
)


def _formats(quantity: str) -> tuple:
    for q, shown_printed, shown_computed in _FORMATS:
        if q == quantity:
            return shown_printed, shown_computed
    if quantity.startswith("m_"):  # the scales m_i, m_част, m_cp
        return "{:.0f}", "{:.1f}"
    return "{:g}", "{:.2f}"


def printed_text(v: float, quantity: str) -> str:
    """A printed value as the guide prints it (``"1/72"``, ``"-210"``, ``"+0.3"``, ``"+0.992"``)."""
    return _formats(quantity)[0].format(v)


def computed_text(v: float, quantity: str, bounds=None) -> str:
    """A computed value with a digit more than printed (an interval as ``"lo … hi"``; 1/N ≥ 1000 as a whole N)."""
    if bounds is not None:
        return f"{bounds[0]:.2f} … {bounds[1]:.2f}"
    if quantity == "Δm_i/m_cp" and v >= 1000:
        return f"1/{v:.0f}"
    return _formats(quantity)[1].format(v)


def value(where: str, quantity: str, printed_value: float, computed: float, unit: float, reasons: dict,
          bounds=None, **fmt) -> Printed:
    """One printed number of a §4–§5 table against the computed one (:func:`aerophoto.guide.audit.printed`).

    ``reasons`` is the table's ``{(where, quantity): template}``; the shown texts
    follow the guide's printing (:func:`printed_text`, :func:`computed_text`).
    """
    return printed(where, quantity, printed_value, computed, unit, reasons=reasons, bounds=bounds,
                   printed_text=printed_text(float(printed_value), quantity),
                   computed_text=computed_text(float(computed), quantity, bounds), **fmt)


def scale_values(t: dict, res: d.ScaleTable, reasons: dict) -> list:
    """The printed m_i, m_част, m_cp, Δm_i and 1/N of a scale table (2, 4, 5, 7) against ``res``."""
    unit = t["unit"]
    out = [value(b.name, "m_i", mp, mc, unit, reasons) for b, mp, mc in zip(res.bases, t["m_i"], res.m_i)]
    out += [value(z, "m_част", mp, mc, unit, reasons) for z, mp, mc in zip(res.zones, t["m_part"], res.m_part)]
    out.append(value("—", "m_cp", t["m_mean"], res.m_mean, unit, reasons))
    out += [value(z, "Δm_i", dp, dc, unit, reasons) for z, dp, dc in zip(res.zones, t["dm"], res.dm)]
    out += [value(z, "Δm_i/m_cp", Np, Nc, ratio_unit(Np), reasons) for z, Np, Nc in zip(res.zones, t["N"], res.ratio_N)]
    return out


def _fmt_cell(v, col: str) -> str:
    if isinstance(v, str):
        return v
    if v is None or (isinstance(v, float) and np.isnan(v)):
        return ""
    if col.startswith("l_"):
        return f"{v:.1f}"
    if col in ("m_i", "m_част", "m_cp"):
        return f"{v:.0f}"
    if col == "Δm_i":
        return f"{v:+.0f}"
    if col.startswith("mean height"):
        return f"{v:.0f}"
    if col in ("Z_i, m", "r, mm"):
        return f"{v:.0f}"
    if col == "h, m":
        return f"{v:+.1f}"
    if col.startswith("δ"):
        return f"{v:+.2f}"
    if col == "cos φ":
        return f"{v:+.3f}"
    if col == "r_c, mm":
        return f"{v:.1f}"
    if col == "φ, °":
        return f"{v:.0f}"
    return f"{v:g}"


def display_frame(df: pd.DataFrame) -> pd.DataFrame:
    """A recomputed table with its numbers as text at the guide's precision (blank where the guide is blank)."""
    out = pd.DataFrame(index=df.index)
    for col in df.columns:
        out[col] = [_fmt_cell(v, col) for v in df[col]]
    return out


def printed_scale_frame(t: dict) -> pd.DataFrame:
    """A scale table (2, 4, 5, 7) as printed, laid out like :meth:`aerophoto.displacement.ScaleTable.table`."""
    bases = t["bases"]
    zones = list(dict.fromkeys(b[0].split("-")[0] for b in bases))
    df = pd.DataFrame(index=pd.Index([b[0] for b in bases], name="base"))
    if "heights" in t:
        df["mean height of bases, m"] = ""
    df["l_пл, mm"] = [f"{b[1]:.1f}" for b in bases]
    df["l_сн, mm"] = [f"{b[2]:.1f}" for b in bases]
    df["m_i"] = [str(v) for v in t["m_i"]]
    df["m_част"] = ""
    df["m_cp"] = ""
    df["Δm_i"] = ""
    df["Δm_i/m_cp"] = ""
    for k, z in enumerate(zones):
        last = max(i for i, b in enumerate(bases) if b[0].split("-")[0] == z)
        df.iloc[last, df.columns.get_loc("m_част")] = str(t["m_part"][k])
        df.iloc[last, df.columns.get_loc("Δm_i")] = f"{t['dm'][k]:+d}"
        df.iloc[last, df.columns.get_loc("Δm_i/m_cp")] = f"1/{t['N'][k]}"
        if "heights" in t:
            df.iloc[last, df.columns.get_loc("mean height of bases, m")] = str(t["heights"][k])
    mid_zone = zones[len(zones) // 2]
    first = min(i for i, b in enumerate(bases) if b[0].split("-")[0] == mid_zone)
    df.iloc[first, df.columns.get_loc("m_cp")] = str(t["m_mean"])
    return df


# --------------------------------------------------------------------------- tables 2, 3, 4
@lru_cache(maxsize=1)
def mean_object_plane_of_table3() -> tuple:
    """(zone heights Z_Icp, Z_IIcp; Z_cp), m, from table 3's heights (guide §4 step 3).

    Each zone: the mean of its two bases' mean heights (:func:`aerophoto.displacement.zone_height`);
    Z_cp: the mean of the zones (:func:`aerophoto.displacement.mean_object_plane`).
    """
    Z = dict(zip(TABLE3["names"], TABLE3["Z"]))
    zones: dict = {}
    for a, b in TABLE3_BASES:
        zones.setdefault(a, []).append((Z[a], Z[b]))
    z_heights = tuple(d.zone_height(v) for v in zones.values())
    return z_heights, d.mean_object_plane(z_heights)


def _table4_lengths() -> list:
    """Corrected lengths of table 4 against table 2's lengths and table 3's δh (homothety about n)."""
    res3 = table(3).result
    h = dict(zip(res3.names, res3.h_m))
    r = dict(zip(res3.names, res3.r_mm))
    out = []
    for (name, _, l_before), (_, _, l_after), (a, b) in zip(TABLE2["bases"], TABLE4["bases"], TABLE3_BASES):
        hbar = (h[a] + h[b]) / 2.0
        pred = l_before * (1.0 - hbar / res3.H_m)
        # ends at different heights: the move is not a pure scaling; bound the difference
        spread = abs(h[a] - h[b]) / (2.0 * res3.H_m) * (r[a] + r[b])
        lo, hi = pred - spread, pred + spread
        nearest = min(max(l_after, lo), hi)
        out.append(value(name, "l_сн", l_after, nearest, 0.1, REASONS[4], bounds=(lo, hi)))
    return out


@lru_cache(maxsize=None)
def table(number: int) -> Audit:
    """The guide's table ``number`` (2, 3 or 4) recomputed from its printed inputs and audited.

    Inputs taken as printed: the lengths l_пл and l_сн (tables 2 and 4;
    M = 10 000) and the heights Z and distances r (table 3).  Everything else
    is computed at full precision and compared with the printed number; the
    flying height of table 3 is H = m_cp·f with m_cp from table 2 and
    f = 100 mm.  Table 4's corrected lengths are also checked against tables
    2 and 3: a corrected length must be one the two corrections can produce.

    Returns an :class:`~aerophoto.guide.audit.Audit` whose ``table`` is the
    recomputed table at the guide's precision (text), ``result`` the package's
    :class:`~aerophoto.displacement.ScaleTable` or
    :class:`~aerophoto.displacement.ReliefCorrections`, ``printed_table`` the
    table as printed.  Computed once and cached: treat it as read-only.
    """
    number = int(check_range("number", number, 2, 4))
    z_heights, Zcp = mean_object_plane_of_table3()
    if number == 3:
        m_cp = table(2).result.m_mean
        H = g.flying_height_m(d.GUIDE_F_MM, m_cp)
        res = d.relief_corrections(TABLE3["names"], TABLE3["Z"], TABLE3["r"], H, Zcp)
        vals = [value(nm, "h", hp, hc, 1.0, REASONS[3]) for nm, hp, hc in zip(res.names, TABLE3["h"], res.h_m)]
        vals += [value(nm, "δh", dp, dc, 0.1, REASONS[3])
                 for nm, dp, dc in zip(res.names, TABLE3["delta"], res.delta_mm)]
        printed_df = pd.DataFrame({"Z_i, m": TABLE3["Z"], "h, m": [f"{v:+d}" for v in TABLE3["h"]],
                                   "r, mm": TABLE3["r"], "δh, mm": [f"{v:+.1f}" for v in TABLE3["delta"]]},
                                  index=pd.Index(TABLE3["names"], name="point"))
        notes = (
            f"Mean object plane: Z_Icp = {z_heights[0]:.2f} m, Z_IIcp = {z_heights[1]:.2f} m, "
            f"Z_cp = {Zcp:.3f} m (each zone: the mean of its two bases' mean heights).",
            f"H = m_cp·f = {m_cp:.1f} × 0.100 m = {H:.1f} m, with m_cp from table 2 and "
            "f = 100 mm — not the §2 flight's H = 1200 m (with 1200 m every δh would be 25 % larger, "
            "e.g. −1.2 mm for I).",
            "All six |δh| exceed 0.2 mm, so all six points are corrected: zone I (below the plane) away from n, "
            "zone II (above it) towards n.",
        )
        return Audit(SOURCE, TITLES[3], display_frame(res.table()), tuple(vals), printed_df, notes, res)
    t = TABLE2 if number == 2 else TABLE4
    res = d.partial_scales(t["bases"], d.GUIDE_M_PLAN, zone_heights_m=z_heights)
    vals = [value(z, "mean height", hp, hc, 1.0, REASONS[number])
            for z, hp, hc in zip(res.zones, t["heights"], z_heights)]
    vals += scale_values(t, res, REASONS[number])
    if number == 2:
        notes = (
            "The ratio column is Δm/m_част in the print (15210/210 = 72, 14790/210 = 70); the guide's "
            "heading asks for Δm/m_cp, which is the same for both zones here.",
            "Step 3 of §4 says the partial scales come from formula (4.1); it means m = l_пл·M/l_сн, "
            "numbered (5.1) in §5 — (4.1) is the relief formula.",
        )
    else:
        vals += _table4_lengths()
        notes = (
            "The corrected photo lengths l_сн follow from table 2 and table 3: moving both ends of a "
            "base radially by δh shrinks or stretches it by the factor (1 − h/H) about n, so "
            "l' ≈ l·(1 − h̄/H) — 18.4 → 18.65, 19.8 → 20.05, 24.3 → 23.99, 22.9 → 22.58 mm.",
            "m_i of II-4: 33.8·10000/22.6 = 14955.8, printed 14950 (rounded down; within rounding).",
        )
    return Audit(SOURCE, TITLES[number], display_frame(res.table()), tuple(vals), printed_scale_frame(t), notes,
                 res)


def audits() -> tuple:
    """The audits of tables 2, 3 and 4, in order."""
    return tuple(table(n) for n in (2, 3, 4))


def discrepancies() -> pd.DataFrame:
    """Every printed number of tables 2–4 that does not follow from its inputs, with the reason.

    One row per value: source, table, where, quantity, printed, computed, reason
    (:func:`aerophoto.guide.audit.discrepancy_frame`).
    """
    return discrepancy_frame(audits())
