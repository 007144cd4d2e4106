"""Chapter 16 · article 000 (contours on a 1:2000 photoplan from DEM points): Lysenko's formula as printed, its reading, the audit.

The article prints one formula — F. F. Lysenko's prediction of the accuracy of height densification
by analytical block phototriangulation — with its inputs and result (m_z = 14 cm), and reports
accuracies measured in the field (12 cm for the densification, 31 cm for contours from the regular
DEM, 12 cm from the structural one, 14 cm for contours drawn on the SD-3 plotter).  Only the formula's
result can be recomputed; the measured figures are the article's findings.

:data:`LYSENKO_READING` says how the book reads the garbled formula, :func:`lysenko_readings` shows
what each reading gives with the article's inputs, and :func:`lysenko` is the audit.  The formula
itself is :func:`aerophoto.dem.lysenko_mz_m`; the simulation it is held against is
:func:`aerophoto.dem.block_precision`.
"""

from __future__ import annotations

import math

import pandas as pd

from .. import dem
from .audit import Audit, discrepancy_frame, printed

__all__ = ["SOURCE", "LYSENKO_PRINTED", "LYSENKO_READING", "INPUTS", "FINDINGS", "lysenko_readings", "lysenko",
           "audits", "discrepancies"]

SOURCE = "article 000"

#: the formula as the scan prints it
LYSENKO_PRINTED = "m_z = 0,25 · (H/ρ) · √( 3(2ns + mn − zr) / (2mns) )"

#: the article's inputs ("принимая в расчёт фактические данные") and the grid step it quotes
INPUTS = dict(H_m=450.0, n=70, m=16, r=38, s=3, b_mm=70.0, scale=4500.0, f_mm=100.0, grid_step_photo_mm=7.0,
              grid_step_ground_m="30", mz_printed_cm="14")

#: what the article measured, cm (RMS unless said) — findings, not computations
FINDINGS = dict(densification_cm=12.0, sd3_cm=14.0, grid_contours_cm=31.0, structural_contours_cm=12.0,
                required_mean_cm=15.0, interval_m=0.5, share_within_15cm_percent=70.0,
                grid_points_per_pair=152, structural_points_per_pair=164, stereocomparator_mm=0.005)

LYSENKO_READING = """\
Article 000 prints Lysenko's formula as  m_z = 0,25 · (H/ρ) · √(3(2ns + mn − zr)/(2mns)),
n photos in the block, m points on each photo, r control points, s images of each point, H the
flying height, ρ (printed p = 70 mm) the photo base.  The book reads it as

    m_z = m_p · (H/b) · √( 3(2ns + mn − s·r) / (2mns) ),   m_p = 0.025 mm,

and says so wherever it is used.  Why:

1. "zr" is s·r.  Multiply out: 3(2ns + mn − sr)/(2mns) = (6n + 3·mn/s − 3r)/(2mn) = u/N, where
   u = 6n + 3(mn/s − r) is the number of unknowns of a bundle block adjustment (six elements of
   exterior orientation per photo, three coordinates for each of the mn/s points, less the r control
   points) and N = 2mn the number of measured image coordinates.  √(u/N) is the classical mean
   precision of adjusted observations (the trace of the hat matrix is u).  With "2r" the expression
   counts nothing.  An italic s read as z is an easy OCR slip; the numbers hardly care (√ = 0.798 with
   s·r, 0.808 with 2r).
2. The factor "0,25" is the measurement-error term, a length on the photo.  The root and H/ρ are pure
   numbers, so whatever stands in front gives m_z its unit.  Printed as 0.25 mm it would make
   m_z = 1.28 m — fifty times the stereocomparator's stated error of 0.005 mm, and ten times the
   article's prediction and its measured 12 cm.  Read as 0.025 mm (a zero lost in the scan) it gives
   m_z = 12.8 cm, beside the printed 14 cm and the measured 12 cm; 0.025 mm is five times the
   instrument's error, the usual size of the total error of a point in analytical triangulation
   (identification, transfer between photos, film and lens distortions on top of the measurement).
3. Which error is m_p: of one image coordinate σ, or of a parallax, the difference of two
   coordinates (√2·σ)?  The simulation decides (aerophoto.dem.block_precision): a block of the
   article's size (70 photos, control spread over it) adjusted with image coordinates measured with
   σ each gives height errors within a few per cent of the formula with m_p = √2·σ, and a third above
   it with m_p = σ.  So m_p is the RMS error of a measured parallax — the article's comparator measured
   "coordinates and parallaxes" with 0.005 mm.
4. What the formula cannot know: where the control points are.  It counts r, not their layout; with
   the same r on the block's edge only, the simulated errors are half as large again as it predicts.

With m_p = 0.025 mm the printed result 14 cm does not follow (12.8 cm): 14 cm would need
m_p = 0.0273 mm, or the minus before s·r read as a plus.
"""


def lysenko_readings() -> pd.DataFrame:
    """m_z (cm) from the article's inputs under each reading of the two garbled terms."""
    I = INPUTS
    terms = {"s·r (the book)": I["s"] * I["r"], "2r": 2 * I["r"], "r": I["r"], "none": 0}
    rows = []
    for label, zr in terms.items():
        root = math.sqrt(3 * (2 * I["n"] * I["s"] + I["m"] * I["n"] - zr) / (2 * I["m"] * I["n"] * I["s"]))
        for mp_label, mp in (("0.25 mm (as printed)", 0.25), ("0.025 mm (the book)", 0.025),
                             ("0.005 mm (the comparator)", FINDINGS["stereocomparator_mm"])):
            rows.append({"“zr” read as": label, "m_p": mp_label, "root": root,
                         "m_z, cm": 100.0 * mp * I["H_m"] / I["b_mm"] * root})
    return pd.DataFrame(rows).set_index(["“zr” read as", "m_p"])


def lysenko() -> Audit:
    """The article's m_z = 14 cm against Lysenko's formula as read (module notes), and the grid step."""
    I = INPUTS
    mz = dem.lysenko_mz_m(I["H_m"], I["b_mm"], dem.ARTICLE_BLOCK["mp_mm"], I["n"], I["m"], I["s"], I["r"])
    u, N = dem.bundle_counts(I["n"], I["m"], I["s"], I["r"])
    values = (
        printed("Lysenko's formula", "m_z, cm", float(I["mz_printed_cm"]), 100.0 * mz, 1.0,
                reason="the formula as read (s·r, m_p = 0.025 mm) gives {c:.1f} cm; 14 cm would need "
                       "m_p = 0.0273 mm (the reading 2r gives 13.0 cm, neither reaches 13.4). The measured "
                       "12 cm agrees better with the formula than the printed prediction does"),
        printed("grid of the regular DEM", "step on the ground, m", float(I["grid_step_ground_m"]),
                I["grid_step_photo_mm"] * I["scale"] / 1000.0, 10.0,
                note="printed as 'about 30 m', a round figure (unit 10 m): 7 mm × 4500 = 31.5 m"),
    )
    table = pd.DataFrame([("H", "m", I["H_m"]), ("b (the article's ρ)", "mm", I["b_mm"]), ("n", "", I["n"]),
                          ("m", "", I["m"]), ("s", "", I["s"]), ("r", "", I["r"]), ("u = 6n + 3(mn/s − r)", "", u),
                          ("N = 2mn", "", N), ("√(u/N)", "", math.sqrt(u / N)),
                          ("m_p", "mm", dem.ARTICLE_BLOCK["mp_mm"]), ("m_z", "cm", 100.0 * mz)],
                         columns=["quantity", "unit", "value"]).set_index("quantity")
    notes = (
        "Formula as printed: " + LYSENKO_PRINTED + "; read as m_z = m_p·(H/b)·√(3(2ns + mn − s·r)/(2mns)), "
        "m_p = 0.025 mm (see guide.ch16.LYSENKO_READING).",
        "Measured in the article: densification 12 cm RMS (predicted 14 cm); for a normal error of RMS 12 cm, "
        "79 % of the errors lie within 15 cm — the article counted 70 % for its structural DEM's contours.",
        "The article's requirement for h = 0.5 m is a mean error of 15 cm (0.3·h); 12 cm RMS is a mean error "
        "of 12/1.25 = 9.6 cm.",
    )
    return Audit(SOURCE, "Lysenko's formula with the article's inputs", table, values, notes=notes)


def audits() -> tuple:
    return (lysenko(),)


def discrepancies() -> pd.DataFrame:
    """Every printed number of article 000 that does not follow from its inputs, with the reason."""
    return discrepancy_frame(audits())
