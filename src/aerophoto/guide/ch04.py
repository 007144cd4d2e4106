"""Chapter 04 · guide §5 (tilt displacement): tables 5, 6 and 7 as printed, recomputed and audited.

The worked example of §5 corrects a photo for tilt.  Its printed inputs — the
bases' lengths l_пл and l_сн (tables 5 and 7, M = 10 000) and the points'
distances r_c from the isocentre and angles φ from the principal vertical
(table 6), with the guide's f = 100 mm and α = 3° — are transcribed here once
(:data:`TABLE5`, :data:`TABLE6`, :data:`TABLE7`).  :func:`table` recomputes
each table with :mod:`aerophoto.displacement` and returns an
:class:`~aerophoto.guide.audit.Audit` (the one rule of
:mod:`aerophoto.guide.audit`: a printed value follows when it lies within 0.6
of a unit of its last printed digit of the computed one);
:func:`discrepancies` lists every value that does not follow, with the reason.

Table 6's δα column does not follow from f = 100 mm and α = 3°;
:func:`table6_fit` finds the reading of the formula's one constant
k = sin α/f that reproduces it (:class:`Table6Fit`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from functools import lru_cache

import numpy as np
import pandas as pd

from .. import displacement as d
from .. import geometry as g
from .._validate import check_range
from .audit import Audit, discrepancy_frame
from .ch03 import SIGN_REASON, display_frame, printed_scale_frame, scale_values, value

__all__ = [
    "SOURCE",
    "TABLE5",
    "TABLE6",
    "TABLE7",
    "TITLES",
    "REASONS",
    "table",
    "audits",
    "discrepancies",
    "Table6Fit",
    "table6_fit",
]

SOURCE = "guide §5"

# --------------------------------------------------------------------------- the printed tables (OCR cleaned)
#: Table 5: bases (name, l_пл mm, l_сн mm) and the printed m_i, m_част, m_cp, Δm_i, N of 1/N (printed to units)
TABLE5 = dict(bases=(("I-1", 35.3, 26.8), ("I-2", 36.4, 28.2), ("II-3", 40.6, 32.5), ("II-4", 40.1, 31.9),
                     ("III-5", 29.0, 24.5), ("III-6", 32.1, 27.7)),
              m_i=(13172, 12880, 12492, 12570, 11837, 11758), m_part=(13026, 12531, 11798), m_mean=12451,
              dm=(-575, -80, +653), N=(23, 157, 18), unit=1)
#: Table 7: as table 5, with the photo lengths corrected for tilt
TABLE7 = dict(bases=(("I-1", 35.3, 27.8), ("I-2", 36.4, 28.9), ("II-3", 40.6, 32.5), ("II-4", 40.1, 31.9),
                     ("III-5", 29.0, 23.4), ("III-6", 32.1, 25.7)),
              m_i=(12698, 12595, 12492, 12570, 12393, 12490), m_part=(12646, 12531, 12442), m_mean=12540,
              dm=(-106, +9, +98), N=(118, 1400, 128), unit=1)
#: Table 6: points, r_c (mm), φ (°, counter-clockwise from the + principal vertical), the printed cos φ and δα (mm)
TABLE6 = dict(names=("I", "1", "2", "II", "3", "4", "III", "5", "6"),
              r_c=(67.0, 43.0, 59.0, 24.6, 9.5, 22.0, 36.4, 43.0, 32.1),
              phi=(7, 9, 343, 186, 135, 264, 196, 172, 195),
              cos=(0.992, 0.987, 0.956, -0.994, -0.707, -0.104, -0.961, -0.990, -0.965),
              delta=(-2.0, -0.8, -1.5, 0.3, 0.0, 0.0, 0.6, 0.8, 0.4))

TITLES = {
    5: "Table 5. Partial and mean scales of the photo (example)",
    6: "Table 6. Corrections of photo points for tilt",
    7: "Table 7. Partial and mean scales by points corrected for tilt",
}

_TRUNCATED = ("cos {phi}° = {c:.4f}, printed truncated to three decimals ({p:.3f}), not rounded ({r:.3f}): more "
              "than 0.6 of a unit from the exact value; the whole column is truncated")

#: table → {(where, quantity): why the printed value does not follow}; ``{c}`` is the computed value
REASONS = {
    5: {
        ("I-2", "m_i"): "36.4·10000/28.2 = 12908, not 12880",
        ("III-6", "m_i"): "32.1·10000/27.7 = 11588, not 11758 (11758 = 32.1·10000/27.3: the photo length was "
                          "probably 27.3 mm, misprinted 27.7)",
        ("I", "m_част"): "carried from the misprinted m_i of I-2: (13172 + 12908)/2 = {c:.0f}",
        ("III", "m_част"): "carried from the misprinted m_i of III-6: (11837 + 11588)/2 = {c:.0f}",
        ("—", "m_cp"): "carried from the two misprinted m_i: the mean of the zones is {c:.0f}",
        ("I", "Δm_i"): "sign reversed (printed m_cp − m_част) and carried from the misprinted m_i: Δm = {c:+.0f}",
        ("II", "Δm_i"): "sign reversed (printed m_cp − m_част) and carried from the misprinted m_cp: Δm = {c:+.0f}",
        ("III", "Δm_i"): "sign reversed (printed m_cp − m_част) and carried from the misprinted m_i: Δm = {c:+.0f}",
        ("I", "Δm_i/m_cp"): "divided by m_част instead of m_cp (13026/575 = 22.7) and carried: m_cp/|Δm| = {c:.1f}",
        ("II", "Δm_i/m_cp"): "divided by m_част instead of m_cp (12531/80 = 157) and carried: m_cp/|Δm| = {c:.0f}",
        ("III", "Δm_i/m_cp"): "divided by m_част instead of m_cp (11798/653 = 18.1) and carried: m_cp/|Δm| = {c:.1f}",
    },
    6: {
        ("1", "cos φ"): _TRUNCATED,
        ("6", "cos φ"): _TRUNCATED,
        ("I", "δα"): "with f = 100 mm and α = 3° the formula gives {c:.2f}; the printed column fits "
                     "sin α/f ≈ 4.5·10⁻⁴ mm⁻¹ (f ≈ 117 mm at α = 3°, or α ≈ 2.57° at f = 100 mm), see table6_fit()",
        ("1", "δα"): "with f = 100 mm and α = 3° the formula gives {c:.2f} (see I)",
        ("2", "δα"): "with f = 100 mm and α = 3° the formula gives {c:.2f} (see I)",
        ("III", "δα"): "with f = 100 mm and α = 3° the formula gives {c:+.2f} (see I)",
        ("5", "δα"): "with f = 100 mm and α = 3° the formula gives {c:+.2f} (see I)",
        ("6", "δα"): "with f = 100 mm and α = 3° the formula gives {c:+.2f} (see I)",
    },
    7: {
        ("I", "Δm_i"): SIGN_REASON,
        ("II", "Δm_i"): SIGN_REASON + "; |Δm| = 8.5 also rounds to 8, not 9",
        ("III", "Δm_i"): SIGN_REASON,
        ("II", "Δm_i/m_cp"): "follows from |Δm| rounded up to 9 (12540/9 = 1393); with |Δm| = 8.46 it is "
                             "1/{c:.0f}, i.e. 1/1500",
        ("III-6", "l_сн"): "cannot follow from table 5: the corrections of III (δα = {a:+.2f}) and 6 ({b:+.2f}) "
                           "change the base by at most {s:.2f} mm, but it shrank from 27.7 to 25.7 mm",
    },
}


# --------------------------------------------------------------------------- tables 5, 6, 7
def _t6_xy() -> np.ndarray:
    """The photo coordinates of table 6's points placed by r_c and φ (f = 100 mm, α = 3°), mm, shape (9, 2)."""
    cam = g.Camera(d.GUIDE_F_MM)
    pose = g.Pose(alpha_deg=d.GUIDE_ALPHA_DEG)
    return d.point_from_polar(cam, pose, TABLE6["r_c"], TABLE6["phi"])


def _t6_distance(a: str, b: str) -> float:
    names = TABLE6["names"]
    xy = _t6_xy()
    return float(np.hypot(*(xy[names.index(a)] - xy[names.index(b)])))


def _table7_lengths() -> list:
    """Corrected lengths of table 7 against table 5 and the corrections of table 6 (|Δl| ≤ |δa| + |δb|)."""
    res6 = table(6).result
    dd = dict(zip(res6.names, np.where(res6.apply, res6.delta_approx_mm, 0.0)))
    out = []
    for (name, _, l_before), (_, _, l_after) in zip(TABLE5["bases"], TABLE7["bases"]):
        a, b = name.split("-")
        s = abs(dd[a]) + abs(dd[b])
        lo, hi = l_before - s, l_before + s
        nearest = min(max(l_after, lo), hi)
        out.append(value(name, "l_сн", l_after, nearest, 0.1, REASONS[7], bounds=(lo, hi), a=dd[a], b=dd[b], s=s))
    return out


def _table6() -> Audit:
    res = d.tilt_corrections(TABLE6["names"], TABLE6["r_c"], TABLE6["phi"], f_mm=d.GUIDE_F_MM,
                             alpha_deg=d.GUIDE_ALPHA_DEG)
    vals = [value(nm, "cos φ", cp, cc, 0.001, REASONS[6], phi=phi, p=cp, r=round(cc, 3))
            for nm, cp, cc, phi in zip(res.names, TABLE6["cos"], res.cos_phi, TABLE6["phi"])]
    vals += [value(nm, "δα", dp, dc, 0.1, REASONS[6])
             for nm, dp, dc in zip(res.names, TABLE6["delta"], res.delta_approx_mm)]
    printed_df = pd.DataFrame({"r_c, mm": [f"{v:.1f}" for v in TABLE6["r_c"]], "φ, °": TABLE6["phi"],
                               "cos φ": [f"{v:+.3f}" for v in TABLE6["cos"]],
                               "δα, mm": [f"{v:+.1f}" if v else "0" for v in TABLE6["delta"]]},
                              index=pd.Index(TABLE6["names"], name="point"))
    fit = table6_fit()
    notes = (
        f"oc = −f·tg(α/2) = {res.oc_mm:.2f} mm for f = 100 mm, α = 3° (guide: −2.6 mm).",
        f"The printed δα fit one constant k = sin α/f: least squares k = {fit.k_lsq:.3e} mm⁻¹; every printed "
        f"value is reproduced (after rounding to 0.1 mm) for {fit.k_lo:.3e} ≤ k ≤ {fit.k_hi:.3e}, i.e. "
        f"f = {fit.f_range_mm[0]:.1f}…{fit.f_range_mm[1]:.1f} mm at α = 3°, or α = "
        f"{fit.alpha_range_deg[0]:.2f}…{fit.alpha_range_deg[1]:.2f}° at f = 100 mm. f = 100 mm, α = 3° gives "
        f"k = {math.sin(math.radians(3)) / 100:.3e}: 6 of 9 values differ.",
        "cos φ agrees with φ everywhere, but is truncated to three decimals, not rounded (cos 9° = 0.9877 is "
        "printed 0.987); for 1 and 6 that is more than rounding (see their rows). φ is counted "
        "counter-clockwise from the positive principal vertical; cos φ cannot tell the sense of rotation, so "
        "δα does not depend on it — only the direction of the move does.",
        "The continuation of this table is headed 'Окончание табл. 3' in the guide: it is the end of table 6.",
        "The points of table 6 are not the ends of table 5's bases: placed by r_c and φ, base II-3 would be "
        f"{_t6_distance('II', '3'):.1f} mm long on the photo (table 5: 32.5 mm) and III-6 "
        f"{_t6_distance('III', '6'):.1f} mm (27.7 mm).",
        "II (|δα| = 0.3 mm > 0.2 mm) is to be corrected, yet bases II-3 and II-4 keep their lengths in "
        "table 7 — possible only if the move is across the bases.",
    )
    return Audit(SOURCE, TITLES[6], display_frame(res.table()), tuple(vals), printed_df, notes, res)


@lru_cache(maxsize=None)
def table(number: int) -> Audit:
    """The guide's table ``number`` (5, 6 or 7) recomputed from its printed inputs and audited.

    Inputs taken as printed: the lengths l_пл and l_сн (tables 5 and 7;
    M = 10 000) and the distances r_c and angles φ (table 6, with the guide's
    f = 100 mm and α = 3°).  Everything else is computed at full precision
    and compared with the printed number.  Table 7's corrected lengths are
    also checked against tables 5 and 6: a base can change by at most the sum
    of the corrections applied at its two ends.

    Returns an :class:`~aerophoto.guide.audit.Audit` (``result``: a
    :class:`~aerophoto.displacement.ScaleTable` or
    :class:`~aerophoto.displacement.TiltCorrections`).  Computed once and
    cached: treat it as read-only.
    """
    number = int(check_range("number", number, 5, 7))
    if number == 6:
        return _table6()
    t = TABLE5 if number == 5 else TABLE7
    res = d.partial_scales(t["bases"], d.GUIDE_M_PLAN)
    vals = scale_values(t, res, REASONS[number])
    if number == 7:
        vals += _table7_lengths()
        notes = ("The ratio column is Δm/m_cp here (12540/106 = 118), unlike tables 2 and 5.",
                 "Bases II-3 and II-4 are copied from table 5 although II was to be corrected (δα = +0.3 mm).")
    else:
        notes = ("The ratio column is Δm/m_част in the print (13026/575 = 22.7, 12531/80 = 157, 11798/653 = 18.1).",)
    return Audit(SOURCE, TITLES[number], display_frame(res.table()), tuple(vals), printed_scale_frame(t), notes,
                 res)


def audits() -> tuple:
    """The audits of tables 5, 6 and 7, in order."""
    return tuple(table(n) for n in (5, 6, 7))


def discrepancies() -> pd.DataFrame:
    """Every printed number of tables 5–7 that does not follow from its inputs, with the reason.

    One row per value: source, table, where, quantity, printed, computed, reason
    (:func:`aerophoto.guide.audit.discrepancy_frame`).
    """
    return discrepancy_frame(audits())


# --------------------------------------------------------------------------- table 6: which reading fits
@dataclass(frozen=True)
class Table6Fit:
    """Which reading of the guide's table 6 reproduces its printed δα column.

    The guide's formula is δα = −k·r_c²·cos φ with k = sin α/f.  Every printed
    δα (rounded to 0.1 mm) is reproduced exactly for k_lo ≤ k ≤ k_hi.

    Attributes
    ----------
    k_lsq : float
        Least-squares k over the nine points, mm⁻¹.
    k_lo, k_hi : float
        The range of k that reproduces every printed value after rounding, mm⁻¹.
    f_range_mm : (float, float)
        The f that does so with α = 3°.
    alpha_range_deg : (float, float)
        The α that does so with f = 100 mm.
    f_best_mm, alpha_best_deg : float
        The least-squares f (α = 3°) and α (f = 100 mm).
    candidates : pandas.DataFrame
        Readings tested, with how many of the nine printed values each
        reproduces and the residuals (printed − computed).
    """

    k_lsq: float
    k_lo: float
    k_hi: float
    f_range_mm: tuple
    alpha_range_deg: tuple
    f_best_mm: float
    alpha_best_deg: float
    candidates: pd.DataFrame = field(repr=False)


@lru_cache(maxsize=1)
def table6_fit() -> Table6Fit:
    """Test readings of the guide's table 6 against its printed δα column (see :class:`Table6Fit`)."""
    names = TABLE6["names"]
    r = np.array(TABLE6["r_c"])
    cos_p = np.array(TABLE6["cos"])
    phi = np.array(TABLE6["phi"], dtype=float)
    printed = np.array(TABLE6["delta"])
    x = -(r**2) * cos_p  # δα = k·x
    k_lsq = float(x @ printed / (x @ x))
    lo, hi = 0.0, math.inf
    for xi, p in zip(x, printed):
        a, b = sorted(((p - 0.05) / xi, (p + 0.05) / xi))
        lo, hi = max(lo, a), min(hi, b)
    s3 = math.sin(math.radians(3.0))

    def rows():
        def approx(f, a):
            return d.tilt_corrections(names, r, phi, f_mm=f, alpha_deg=a).delta_approx_mm

        def exact(f, a):
            return d.tilt_corrections(names, r, phi, f_mm=f, alpha_deg=a).delta_exact_mm

        a_best = math.degrees(math.asin(k_lsq * 100.0))
        f_best = s3 / k_lsq
        yield "the guide's inputs: f = 100 mm, α = 3°", 100.0, 3.0, approx(100, 3)
        yield "the exact formula, f = 100 mm, α = 3°", 100.0, 3.0, exact(100, 3)
        yield "f = 100 mm, α = 2.5°", 100.0, 2.5, approx(100, 2.5)
        yield "f = 120 mm (variant 02), α = 3°", 120.0, 3.0, approx(120, 3)
        yield "f = 117 mm, α = 3°", 117.0, 3.0, approx(117, 3)
        yield f"least squares: f = {f_best:.1f} mm, α = 3°", f_best, 3.0, approx(f_best, 3)
        yield f"least squares: f = 100 mm, α = {a_best:.2f}°", 100.0, a_best, approx(100, a_best)
        # r and φ measured from o or from n instead of c (the same points, f = 100 mm, α = 3°)
        cam, pose = g.Camera(100.0), g.Pose(alpha_deg=3.0)
        xy = d.point_from_polar(cam, pose, r, phi)
        for label, centre in (("o", g.principal_point(cam, pose)), ("n", g.nadir_point(cam, pose))):
            dxy = xy - centre
            r2 = np.sum(dxy**2, axis=1)
            cosp = dxy[:, 0] / np.sqrt(r2)
            yield (f"r and φ measured from {label} instead of c, f = 100 mm, α = 3°", 100.0, 3.0,
                   -r2 * cosp / 100.0 * s3)

    out = []
    for label, f, a, dl in rows():
        res = printed - dl
        matched = int(np.count_nonzero(np.abs(printed - np.round(dl + 1e-12, 1)) < 1e-9))
        out.append({"reading": label, "f, mm": f, "α, °": a, "10⁴·sin α/f, 1/mm": 1e4 * math.sin(math.radians(a)) / f,
                    "matches (of 9)": matched, "max |residual|, mm": float(np.max(np.abs(res))),
                    "rms residual, mm": float(np.sqrt(np.mean(res**2)))})
    cand = pd.DataFrame(out).set_index("reading")
    return Table6Fit(k_lsq, lo, hi, (s3 / hi, s3 / lo),
                     (math.degrees(math.asin(lo * 100)), math.degrees(math.asin(hi * 100))),
                     s3 / k_lsq, math.degrees(math.asin(k_lsq * 100)), cand)
