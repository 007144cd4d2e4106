"""Chapter 12 · guide §13 (phototriangulation): formula (13.1) as printed, its reading, and the guide's inputs to it.

§13's tables 12 and 13 are blank forms (no printed numbers to audit).  What
the section prints is Zhukov's formula (13.1) for the spacing of control
points — with a garbled radicand — and the inputs to use with it.  This
module holds both: :data:`ZHUKOV_READING` (why the book reads the radicand
n³ + 11n + 34), :data:`GUIDE_ZHUKOV_INPUTS` (m, k_i, b_ср, m_ε as printed)
and :func:`zhukov_readings` (the spacing the guide's inputs give under each
reading).  The formula itself is :mod:`aerophoto.triangulation.zhukov`.
"""

from __future__ import annotations

import pandas as pd

from ..triangulation import zhukov as _zhukov

__all__ = ["ZHUKOV_READING", "GUIDE_ZHUKOV_INPUTS", "READINGS", "zhukov_readings"]

ZHUKOV_READING = """\
Guide §13, formula (13.1), as scanned:  m = 0.25·k_i·b_ср·(m_ε/ρ′)·√(n⁰ + 11n + 34).
A radicand n⁰ + 11n + 34 = 11n + 35 cannot be meant, and the book reads it as

    m = 0.25 · k_i · b_ср · (m_ε / ρ′) · √(n³ + 11n + 34)

(the superscript 3 scanned as 0).  Why:

1. Error propagation.  In a radial strip every template carries the strip's
   azimuth on to the next through its initial directions, so independent
   direction errors add up as a random walk of the azimuth, and the lateral
   position — the sum of the azimuths times the base — as a walk of a walk.
   With both ends held by control points (the strip fitted to them), the
   variance at the middle of n bases is exactly (n³ + 2n)/48 per unit
   azimuth-transfer variance (see
   :func:`aerophoto.triangulation.zhukov.bridge_variance_factor`): a cubic
   with no n² term, like n³ + 11n + 34.  A transfer error of √3·m_ε per base
   (the back and forward initial directions and the laying) gives
   √(3/48) = 0.25, the formula's own coefficient.  The terms 11n + 34 are
   the errors that do not accumulate (intersection and pricking of the point
   itself, control points).  Romanovsky's accumulation law in the accuracy
   article (seed 001, formula 10.20, with "replace n by n/2 and halve" for
   the middle of a strip tied at both ends) likewise grows as n^(3/2).
   A radicand 11n + 35 would make the error grow like √n only — as if the
   errors did not carry from template to template.
2. The guide's own inputs: m = 0.35 mm, k_i ≈ 1, b ≈ 60 mm, m_ε = 4′–5′
   give n ≈ 5.5–6.6, i.e. control points every 5–6 bases — the usual
   spacing for graphical radial triangulation.  With n² the same inputs
   would give 10–14 bases, with n⁰ 20–33 bases, both far beyond what a
   graphical strip holds (our simulation,
   :func:`aerophoto.triangulation.study.accumulation_study`, shows the
   reduced strip's errors pass 0.35 mm within a few bases at 0.1 mm
   pricking).
"""

#: guide §13 step 1, the inputs of (13.1) as printed: the allowed RMS error m of an orienting point on the
#: plan (mm), the enlargement k_i ≈ 1, the mean photo base b_ср ≈ 60 mm ("at p_x = 60 %"; 72 mm for the
#: 18 cm frame of guide §1) and the RMS direction error m_ε = 4′–5′ (arc-minutes, with the middle value)
GUIDE_ZHUKOV_INPUTS = {"m_mm": 0.35, "k_i": 1.0, "b_mm": 60.0, "m_eps_arcmin": (4.0, 4.5, 5.0)}

#: the three readings of the radicand: key for :func:`aerophoto.triangulation.zhukov_error_mm` and label
READINGS = (("n3", "n³ + 11n + 34 (the book)"), ("n2", "n² + 11n + 34"), ("n0", "n⁰ + 11n + 34 (scan)"))


def zhukov_readings(m_allowed_mm: float | None = None, *, k_i: float | None = None, b_mm: float | None = None,
                    m_eps_arcmin=None) -> pd.DataFrame:
    """The number of bases n at which (13.1) reaches the allowed error, for each reading and each m_ε.

    Defaults are the guide's inputs (:data:`GUIDE_ZHUKOV_INPUTS`).  One row
    per reading of the radicand (:data:`READINGS`), one column per m_ε
    ("n for m_ε = 4′"); the values are real n
    (:func:`aerophoto.triangulation.zhukov_bases_continuous`), not rounded.
    """
    gi = GUIDE_ZHUKOV_INPUTS
    m = gi["m_mm"] if m_allowed_mm is None else m_allowed_mm
    k = gi["k_i"] if k_i is None else k_i
    b = gi["b_mm"] if b_mm is None else b_mm
    eps = tuple(gi["m_eps_arcmin"] if m_eps_arcmin is None else m_eps_arcmin)
    rows = [[label] + [_zhukov.zhukov_bases_continuous(m, k_i=k, b_mm=b, m_eps_arcmin=me, reading=reading)
                       for me in eps]
            for reading, label in READINGS]
    return pd.DataFrame(rows, columns=["radicand"] + [f"n for m_ε = {me:g}′" for me in eps]).set_index("radicand")
