"""Chapter 17 · article 003 (Mikheeva, Yaltykhov, Vashcheva): the printed numbers of the map-updating error budget, audited.

The article estimates the RMS error of every stage of updating a topographic map at a digital
photogrammetric station, on the ground, and adds them root-sum-square (its formula 10) for two
cases: a 1:10 000 map from 1:15 000 photos scanned at 42 µm, and a 1:2000 plan from 1:10 000 photos
at 16 µm.  Its five tables and the numbers printed in its text are transcribed here once (OCR
cleaned: "V_X , м" etc.; "m_н/м" and "m_n/m" are the same stage) and recomputed from their own printed
inputs with :mod:`aerophoto.budget`:

* :func:`table1` — the vectorising error from repeated measurements (formulas 3–6);
* :func:`table2` — σ = 0.5·P;
* :func:`table3` — phototriangulation, formulas (7) and (8);
* :func:`text_values` — the numbers of the text: the control, DEM and orthorectification RMS errors
  (1.25 × the instruction's tolerances), the transfer error of formula (9), the 40 µm transfer
  tolerance on the ground, and the two errors of the closing paragraph;
* :func:`table4` — every stage on the ground for both cases;
* :func:`table5` — the total (formula 10) on the ground and on the map, RMS and mean.

Every printed value is judged by the one rule of :mod:`aerophoto.guide.audit`.  One does not follow:
the transfer between strips.  The instruction's d = 0.5 mm is a *mean* discrepancy; the article puts it
into formula (9) as if it were the discrepancies themselves (0.5·√(50/98) = 0.357 mm, printed 0.35).
Its own rule (1) makes the mean an RMS first, 1.25·0.5 = 0.625 mm, and (9) then gives 0.446 mm (0.442 =
1.25·0.5/√2 for many points) — :func:`aerophoto.budget.transfer_from_mean_mm`.  The tables carry 0.35
on; with 0.446 mm the 1:2000 plan's m_d is 0.621 mm and v_d = 0.497 mm, further from the 0.4 mm
(:func:`table5` notes the totals).
"""

from __future__ import annotations

import math

import pandas as pd

from .. import budget as b
from .audit import Audit, digit_unit, discrepancy_frame, printed

__all__ = ["SOURCE", "TABLE1", "TABLE2", "TABLE3", "TABLE4", "TABLE5", "TEXT", "REASONS", "NOTES", "table1",
           "table2", "table3", "text_values", "table4", "table5", "audits", "discrepancies"]

SOURCE = "article 003"
SCALES = (10000, 2000)

#: table 1 as printed: M_k, number of measurements, V_X, V_Y, V_D, m_D (m on the ground)
TABLE1 = dict(M_k=2000, n=20, V_X="0.154", V_Y="0.078", V_D="0.173", m_D="0.216", m_d_mm="0.11")
#: table 2 as printed: per map scale M_k → M_c, f (mm), l (cm), P (µm), σ (µm)
TABLE2 = {10000: dict(M_c=15000, f_mm=153, l_cm=23, P_um=42, sigma_um="21"),
          2000: dict(M_c=10000, f_mm=153, l_cm=23, P_um=16, sigma_um="8")}
#: table 3 as printed: per map scale, m_x,y and m_D (m)
TABLE3 = {10000: dict(M_c=15000, m_xy="0.265", m_D="0.374"), 2000: dict(M_c=10000, m_xy="0.067", m_D="0.095")}
#: table 4 as printed: per map scale, every stage's RMS on the ground (m), in the article's column order
TABLE4 = {10000: dict(control="1.25", scanning="0.045", triangulation="0.374", dtm="3.75", ortho="1.25",
                      transfer="3.5", vectorising="1.10"),
          2000: dict(control="0.25", scanning="0.03", triangulation="0.095", dtm="0.75", ortho="0.25",
                     transfer="0.7", vectorising="0.22")}
#: table 5 as printed: per map scale, m_D (m, ground), m_d and v_d (mm, map)
TABLE5 = {10000: dict(m_D="5.55", m_d="0.55", v_d="0.44"), 2000: dict(m_D="1.11", m_d="0.56", v_d="0.45")}
#: the numbers printed in the text (mm on the map unless said)
TEXT = dict(control_mean="0.1", control_rms="0.125", dtm_max="0.3", dtm_rms="0.375", ortho_mean="0.1",
            ortho_rms="0.125", misfit="0.7", transfer_d="0.5", transfer_n=50, transfer_rms="0.35",
            transfer_ground={2000: "0.7", 10000: "3.5"}, tol_um=40, tol_ground={10000: "0.4", 15000: "0.6"},
            interior={15000: "0.394", 10000: "0.100"}, sigma_rms_P="0.884", coarser="1.8")

SYMBOL = {key: sym for key, sym, _en, _ru in b.STAGES}

REASONS = {
    ("formula (9)", "m_н/м, mm"): "d = 0.5 mm is the instruction's mean discrepancy: rule (1) makes it an RMS "
                                  "first, 1.25·0.5 = 0.625 mm, and formula (9) with n = 50 then gives "
                                  "0.625·√(50/98) = {c:.3f} mm (1.25·0.5/√2 = 0.442 for many points). The "
                                  "article puts the mean itself into (9): 0.5·√(50/98) = 0.357, printed 0.35 "
                                  "(d/√2 = 0.354). The tables carry 0.35 on",
}

NOTES = (
    "Formula (2) h_пред = 0.3·f·M_k/r is printed 'in metres', but with f and r in mm and 0.3 mm on the map "
    "the product is in mm: h_пред = 0.3·f·M_k/(1000·r) m (aerophoto.budget.relief_limit_m).",
    "The text says 'as formula (1) shows, the relief distortion must not exceed 0.3 mm'; it is formula (2) "
    "(the instruction's 0.3 mm) that says so.",
    "The DEM row is a tolerance, not an estimate: relief distortions of ±0.3 mm on the two sides of a seam "
    "may misfit by 0.6 mm; 1.25 × 0.3 = 0.375 mm RMS. The orthorectification row takes what is left of the "
    "instruction's 0.7 mm misfit, 0.7 − 0.6 = 0.1 mm mean, 0.125 mm RMS.",
    "The vectorising error was measured at 1:2000 only (table 1) and is assumed to stay 0.11 mm on the "
    "map at 1:10 000 (1.10 m on the ground).",
)


def _val(where, quantity, text, computed, *, reason="", note="") -> object:
    return printed(where, quantity, float(str(text).replace(",", ".")), computed, digit_unit(str(text)),
                   reasons=REASONS, reason=reason, note=note)


def table1() -> Audit:
    """Table 1: V_D = √(V_X² + V_Y²) (4), m_D = 1.25·V_D (5), m_d = m_D/M_k (6) from the printed V_X, V_Y."""
    t = TABLE1
    vx, vy = float(t["V_X"]), float(t["V_Y"])
    vd = b.plan_error(vx, vy)
    mD = b.rms_from_mean(vd)
    md = mD / t["M_k"] * 1000.0
    values = (_val("table 1", "V_D, m", t["V_D"], vd), _val("table 1", "m_D, m", t["m_D"], mD),
              _val("formula (6)", "m_d, mm", t["m_d_mm"], md))
    df = pd.DataFrame({"M_k": [t["M_k"]], "measurements": [t["n"]], "V_X, m": [vx], "V_Y, m": [vy],
                       "V_D, m": [round(vd, 4)], "m_D, m": [round(mD, 4)], "m_d, mm": [round(md, 4)]},
                      index=pd.Index(["1:2000"], name="map"))
    printed_df = pd.DataFrame({"M_k": [t["M_k"]], "measurements": [t["n"]], "V_X, m": [t["V_X"]],
                               "V_Y, m": [t["V_Y"]], "V_D, m": [t["V_D"]], "m_D, m": [t["m_D"]]})
    return Audit(SOURCE, "Table 1. The vectorising error of building corners", df, values, printed_df,
                 notes=("V_X and V_Y are the table's inputs (the repeated measurements are not printed).",))


def table2() -> Audit:
    """Table 2: the survey parameters of the two cases and σ = 0.5·P."""
    rows, values = {}, []
    for Mk in SCALES:
        t = TABLE2[Mk]
        s = b.sigma_um(t["P_um"])
        values.append(_val(f"table 2, 1:{Mk}", "σ, µm", t["sigma_um"], s))
        rows[f"1:{Mk}"] = {"M_c": t["M_c"], "f, mm": t["f_mm"], "l, cm": t["l_cm"], "P, µm": t["P_um"], "σ, µm": s}
    df = pd.DataFrame(rows).T
    df.index.name = "map 1:M_k"
    return Audit(SOURCE, "Table 2. Survey parameters and scanning resolution", df, tuple(values))


def table3() -> Audit:
    """Table 3: m_x,y = 0.84·M_c·σ (7), m_D = √2·m_x,y (8) from table 2's M_c and P."""
    rows, values = {}, []
    for Mk in SCALES:
        t = TABLE3[Mk]
        mxy, mD = b.triangulation_rms_m(TABLE2[Mk]["M_c"], TABLE2[Mk]["P_um"])
        values += [_val(f"table 3, 1:{Mk}", "m_x,y, m", t["m_xy"], mxy),
                   _val(f"table 3, 1:{Mk}", "m_D, m", t["m_D"], mD)]
        rows[f"1:{t['M_c']} → 1:{Mk}"] = {"m_x,y, m": round(mxy, 4), "m_D, m": round(mD, 4)}
    df = pd.DataFrame(rows).T
    df.index.name = "photo → map"
    return Audit(SOURCE, "Table 3. Phototriangulation with GPS and a gyro mount", df, tuple(values))


def text_values() -> Audit:
    """The numbers printed in the article's text, each against the rule it states."""
    T = TEXT
    v = [
        _val("formula (1)", "m_пл/в, mm", T["control_rms"], b.rms_from_mean(float(T["control_mean"]))),
        _val("DEM", "m_ЦМР, mm", T["dtm_rms"], b.rms_from_mean(float(T["dtm_max"]))),
        _val("orthorectification", "mean error, mm", T["ortho_mean"], float(T["misfit"]) - 2 * float(T["dtm_max"])),
        _val("orthorectification", "m_орт, mm", T["ortho_rms"], b.rms_from_mean(float(T["ortho_mean"]))),
        _val("formula (9)", "m_н/м, mm", T["transfer_rms"],
             b.transfer_from_mean_mm(float(T["transfer_d"]), T["transfer_n"])),
    ]
    for Mk in (2000, 10000):
        v.append(_val(f"transfer, 1:{Mk}", "m_н/м on the ground, m", T["transfer_ground"][Mk],
                      float(T["transfer_rms"]) * Mk / 1000.0,
                      note="from the printed 0.35 mm; rule (1) and (9), 0.446 mm, give {:.3f} m".format(
                          b.transfer_from_mean_mm() * Mk / 1000.0)))
    for Mc in (10000, 15000):
        v.append(_val(f"40 µm tolerance, 1:{Mc}", "on the ground, m", T["tol_ground"][Mc], T["tol_um"] * 1e-6 * Mc))
    for Mk, Mc in ((10000, 15000), (2000, 10000)):
        v.append(_val(f"interior orientation, 1:{Mc}", "m_вн.о., m", T["interior"][Mc],
                      0.625 * TABLE2[Mk]["P_um"] * 1e-6 * Mc))
    v.append(_val("closing paragraph", "σ = 1.25·0.5P·√2, in P", T["sigma_rms_P"], 1.25 * 0.5 * math.sqrt(2)))
    v.append(_val("closing paragraph", "0.884P / 0.5P", T["coarser"], 1.25 * 0.5 * math.sqrt(2) / 0.5))
    df = pd.DataFrame([(p.where, p.quantity, p.shown_printed(), p.computed) for p in v],
                      columns=["where", "quantity", "printed", "computed"]).set_index("where")
    return Audit(SOURCE, "The numbers in the text", df, tuple(v), notes=NOTES)


def _computed_table4(Mk: int) -> dict:
    """Table 4's row for map 1:M_k from its stated rules and the printed inputs (table 3, 0.35 mm, 0.11 mm)."""
    Mc = TABLE2[Mk]["M_c"]
    g = Mk / 1000.0
    return {"control": float(TEXT["control_rms"]) * g, "scanning": b.SCAN_RMS_UM * 1e-6 * Mc,
            "triangulation": float(TABLE3[Mk]["m_D"]), "dtm": float(TEXT["dtm_rms"]) * g,
            "ortho": float(TEXT["ortho_rms"]) * g, "transfer": float(TEXT["transfer_rms"]) * g,
            "vectorising": float(TABLE1["m_d_mm"]) * g}


def table4() -> Audit:
    """Table 4: every stage's RMS on the ground — map-scale errors × M_k, the scanner's 3 µm × M_c."""
    rows, values = {}, []
    for Mk in SCALES:
        c = _computed_table4(Mk)
        rows[f"1:{Mk}"] = {f"{SYMBOL[k]}, m": c[k] for k in c}
        values += [_val(f"table 4, 1:{Mk}", f"{SYMBOL[k]}, m", TABLE4[Mk][k], c[k]) for k in c]
    df = pd.DataFrame(rows).T
    df.index.name = "map 1:M_k"
    printed_df = pd.DataFrame({f"1:{Mk}": {f"{SYMBOL[k]}, m": TABLE4[Mk][k] for k in TABLE4[Mk]} for Mk in SCALES}).T
    return Audit(SOURCE, "Table 4. The stages' RMS errors on the ground", df, tuple(values), printed_df)


def table5() -> Audit:
    """Table 5: m_D = √Σmᵢ² (10) from table 4's printed values; m_d = m_D/M_k; v_d = m_d/1.25."""
    rows, values, notes = {}, [], []
    for Mk in SCALES:
        mD = math.sqrt(sum(float(x) ** 2 for x in TABLE4[Mk].values()))
        md = mD / Mk * 1000.0
        vd = b.mean_from_rms(md)
        P = TABLE5[Mk]
        values += [_val(f"table 5, 1:{Mk}", "m_D, m", P["m_D"], mD), _val(f"table 5, 1:{Mk}", "m_d, mm", P["m_d"], md),
                   _val(f"table 5, 1:{Mk}", "v_d, mm", P["v_d"], vd,
                        note="0.56/1.25 = 0.448: computed from the rounded m_d" if Mk == 2000 else "")]
        rows[f"1:{Mk}"] = {"m_D, m (ground)": round(mD, 4), "m_d, mm (map)": round(md, 4),
                           "v_d, mm (map)": round(vd, 4),
                           "v_d ≤ 0.4 mm": vd <= b.TOLERANCE_MEAN_MM}
        full = b.budget(**{k: v for k, v in b.ARTICLE_CASES[SCALES.index(Mk)].items()})
        notes.append(f"1:{Mk} with the transfer by rule (1) and formula (9), {b.transfer_from_mean_mm():.3f} mm "
                     f"instead of 0.35: m_D = {full.total_m:.2f} m, m_d = {full.map_rms_mm:.3f} mm, "
                     f"v_d = {full.map_mean_mm:.3f} mm — the same verdict, further from 0.4 mm.")
    df = pd.DataFrame(rows).T
    df.index.name = "map 1:M_k"
    return Audit(SOURCE, "Table 5. The total error, formula (10)", df, tuple(values), notes=tuple(notes))


def audits() -> tuple:
    """Every audit of article 003, in the article's order."""
    return (table1(), table2(), table3(), text_values(), table4(), table5())


def discrepancies() -> pd.DataFrame:
    """Every printed number of article 003 that does not follow from its inputs, with the reason."""
    return discrepancy_frame(audits())
