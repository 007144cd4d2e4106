"""Chapter 05 · guide §6 ("Изготовление одномаршрутной фотосхемы"): what the section prints, as data with notes.

§6 prints no worked numeric table — no printed value follows from other
printed values — so it has no :class:`~aerophoto.guide.audit.Audit`.  What it
prints are the rules of the work (distances, tolerances, the sheet), two
formulas and, in the appendix, a sample sheet with its marginalia.  They are
transcribed here once (OCR cleaned; the garbling is said in each note):

* :data:`RULES` — every number of the procedure (steps 2–9) with the place the
  book uses it (e.g. the 0.5 mm cut-out tolerance is
  :data:`aerophoto.mosaic.ALLOWED_CUTOUT_MM`; a test keeps the two equal);
* :data:`FORMULAS` — (6.1) the partial and mean scales and (6.2) the quality
  of the seams, with what the book makes of their second expressions;
* :data:`MARGINALIA` — the appendix's sample sheet ("M 1: 13000", the year,
  made by, checked by) and how :func:`aerophoto.demos.fotoschema.sheet_figure`
  draws each line.

Two things in it can be checked, and :func:`remarks` says what they give:

1. the sheet: step 5 asks for A3 (420 × 297 mm).  The glued strip of n
   contact prints 18 × 18 cm with forward overlap p_x is
   l + (n − 1)·l·(1 − p_x/100) long, plus the trim on both ends
   (:func:`strip_length_mm`); at p_x = 60 % four prints give 396 mm
   (416–426 mm trimmed: at the limit of A3), five give 468 mm, more than A3
   holds (:func:`prints_on_sheet`);
2. the trim: step 5 trims 1–1.5 cm beyond the working areas, the text after
   step 9 0.5–1.0 cm beyond the working-area lines — two different margins
   for the same cut.

The appendix's mean scale "M 1: 13000" cannot be checked: the sample's
photos, plan and bases are not printed.
"""

from __future__ import annotations

from dataclasses import dataclass

import pandas as pd

from .._validate import check_int_range, check_percent, check_positive

__all__ = ["SOURCE", "Rule", "Formula", "Marginal", "RULES", "FORMULAS", "MARGINALIA", "SHEET", "SHEET_MM",
           "FRAME_MM", "rule", "rules_table", "strip_length_mm", "prints_on_sheet", "remarks"]

SOURCE = "guide §6"

#: the sheet step 5 asks for, and its size (ISO 216, landscape), mm
SHEET = "A3"
SHEET_MM = (420.0, 297.0)
#: the contact prints' frame (guide §1: 18 × 18 cm), mm
FRAME_MM = 180.0


@dataclass(frozen=True)
class Rule:
    """One number the procedure of §6 prints.

    Attributes
    ----------
    where : str
        The step ("step 2", "after step 9").
    quantity : str
        What it is, in English.
    value : float, tuple (lo, hi) or str
        As printed, in ``unit`` (a range as a pair; "A3" as text).
    unit : str
    printed_text : str
        The printed words, OCR cleaned (Russian).
    used_by : str
        Where the book uses it ("" if it does not).
    note : str
    """

    where: str
    quantity: str
    value: object
    unit: str
    printed_text: str
    used_by: str = ""
    note: str = ""


@dataclass(frozen=True)
class Formula:
    """A formula of §6 as printed, and what the book makes of it."""

    number: str
    printed_text: str
    meaning: str
    used_by: str
    note: str = ""


@dataclass(frozen=True)
class Marginal:
    """One line of the appendix's sample sheet (the marginalia, зарамочное оформление)."""

    what: str
    printed_text: str
    drawn_as: str
    note: str = ""


RULES = (
    Rule("step 2", "distance of the tie points a, b from the upper and lower edges", (15.0, 25.0), "mm",
         "на расстоянии 1,5–2,5 см от верхнего и нижнего краев снимков",
         "aerophoto.mosaic.choose_tie_points(margin_mm=(15.0, 25.0))",
         "the tie points are taken on high ground, to avoid cut-outs"),
    Rule("step 4", "least distance of a cut from important linear features (roads, rivers)", 1.0, "mm",
         "порез не должен проходить ближе чем на 1 мм от важных линейных контуров", "",
         "a rule for the technician's choice of the cut; the book's cuts are straight lines through a and b"),
    Rule("step 5", "the sheet the working areas are glued onto", SHEET, "",
         "наклеивают на лист плотной бумаги формата А3", "aerophoto.demos.fotoschema.sheet_figure (smallest ISO A sheet)",
         "OCR: 'АЗ' for А3.  A3 holds at most four prints at p_x = 60 % (see strip_length_mm); the book takes the "
         "smallest sheet that holds the strip"),
    Rule("step 5", "trim beyond the borders of the working area", (10.0, 15.0), "mm",
         "Отступив 1–1,5 см от границ рабочей площади, обрезают лишние части аэроснимков",
         "aerophoto.demos.fotoschema.sheet_figure (10 mm at the sides)",
         "after step 9 the guide trims 0.5–1.0 cm beyond the working-area lines instead"),
    Rule("steps 5, 8", "largest cut-out (вырез) allowed on a seam", 0.5, "mm",
         "вырезы не будут превышать 0,5 мм; допускается вырез до -0,5 мм", "aerophoto.mosaic.ALLOWED_CUTOUT_MM",
         "ΔI read to 0.01 mm is compared with −0.5 mm (aerophoto.mosaic.Fotoschema.ok)"),
    Rule("step 7", "points identified for the mean scale (two at each end of the strip)", 4, "",
         "опознают по две точки на фотосхеме и топографическом плане (всего по 4 точки)",
         "aerophoto.mosaic.mean_scale"),
    Rule("step 7", "bases l_i, L_i measured to", 0.1, "mm", "с точностью 0,1 мм",
         "aerophoto.labs.ch05 (the student's readings, rounded to 0.1 mm)",
         "the guide numbers the bases I = 1, 2, 3, 4 (OCR: 'I=1, 2, 3, 4' for i)"),
    Rule("step 8", "spacing of the pricks along a cut", (20.0, 30.0), "mm", "через 2-3см",
         "aerophoto.mosaic.CHECK_SPACING_MM (25 mm)", "OCR: 'четные точки' for чёткие (sharp) points"),
    Rule("after step 9", "trim beyond the working-area lines", (5.0, 10.0), "mm",
         "отступают от каждой линии с внешней стороны на 0,5-1,0 см", "",
         "differs from step 5's 1–1.5 cm for the same trimming"),
)

FORMULAS = (
    Formula("6.1", "1/m_i = l_i/(L_i·M),  1/m = l_сн/(l_пл·M)",
            "partial scale of the fotoschema along base i: l_i on the fotoschema, L_i on the 1:M plan; the mean "
            "scale 1/m is signed on the sheet",
            "aerophoto.mosaic.partial_scales (m_i = L_i·M/l_i, through aerophoto.displacement.base_scale)",
            "the second expression is the base scale of §5 (5.1) in the photo's (сн) and plan's (пл, OCR 'ILT') "
            "lengths; the book takes the mean of the denominators m_i, as §4 averages them"),
    Formula("6.2", "m = √(Σ(ΔI)²/n);  m_i = √((l_обр − l_сн)²/n) → 0",
            "quality of the fotoschema: the RMS of the mismatches ΔI along the cuts, n the number of pricks",
            "aerophoto.mosaic.seam_rms",
            "the second expression (lengths on the cut-off strips, обр, against the photo, сн; OCR 'oбp', 'ch') "
            "is printed without an explanation; the book uses only the first"),
)

MARGINALIA = (
    Marginal("title", "ФОТОСХЕМА (пример)", "ФОТОСХЕМА above the mosaic (and 'Photo mosaic' in English)",
             "'(пример)' marks the appendix's sheet as a sample"),
    Marginal("mean scale", "M 1: 13000", "'М 1:m' under the title, m the mean scale rounded to hundreds "
             "(aerophoto.mosaic.ScaleCheck.m_rounded)",
             "the appendix writes the fotoschema's mean scale with the letter M, which the guide uses elsewhere "
             "for the plan's scale (1:M = 1:10 000); it cannot be checked: the sample's bases are not printed"),
    Marginal("year", "Фотосхема изготовлена в 2014 г.", "'Фотосхема изготовлена в <year> г.' at the bottom left"),
    Marginal("made by", "Выполнил: ст. гр. … (the student and the group)", "'Выполнил (made by): <name>'"),
    Marginal("checked by", "Проверил: … (the teacher)", "'Проверил (checked by): <name>'"),
)


def rule(where: str, quantity_starts: str) -> Rule:
    """The rule printed at ``where`` whose quantity starts with ``quantity_starts`` (KeyError if none)."""
    for r in RULES:
        if r.where == where and r.quantity.startswith(quantity_starts):
            return r
    raise KeyError(f"guide §6 prints no rule {quantity_starts!r} at {where!r}")


def rules_table() -> pd.DataFrame:
    """:data:`RULES` as a table: where, quantity, value, unit, used by, note."""

    def shown(v):
        if isinstance(v, tuple):
            return f"{v[0]:g}–{v[1]:g}"
        return f"{v:g}" if isinstance(v, float) else str(v)

    return pd.DataFrame(
        {"where": [r.where for r in RULES], "quantity": [r.quantity for r in RULES],
         "value": [shown(r.value) for r in RULES], "unit": [r.unit for r in RULES],
         "used by": [r.used_by for r in RULES], "note": [r.note for r in RULES]},
        columns=["where", "quantity", "value", "unit", "used by", "note"],
    )


def strip_length_mm(n_photos: int, px_percent: float = 60.0, *, frame_mm: float = FRAME_MM,
                    trim_mm: float = 0.0) -> float:
    """Length of a glued single-strip fotoschema on the sheet, mm.

        L = l + (n − 1)·l·(1 − p_x/100) + 2·trim

    The first and the last print keep their outer parts, every cut lies in
    the middle of an overlap, so the working areas add up to one frame plus
    n − 1 photo bases b = l·(1 − p_x/100) (guide §2).  Contact prints of an
    untilted strip over flat ground; ``trim_mm`` is what is left beyond the
    working areas on each end (step 5: 10–15 mm).

    Parameters
    ----------
    n_photos : int, 1 ≤ n ≤ 1000
    px_percent : float, forward overlap p_x, 0 ≤ p_x < 100 %
    frame_mm : float, frame side l, mm (> 0)
    trim_mm : float, ≥ 0, mm
    """
    n = check_int_range("n_photos", n_photos, 1, 1000)
    px = check_percent("px_percent", px_percent)
    l = check_positive("frame_mm", frame_mm, unit="mm", hi=1000.0)
    if trim_mm != 0.0:
        trim_mm = check_positive("trim_mm", trim_mm, unit="mm", hi=1000.0)
    return l + (n - 1) * l * (1.0 - px / 100.0) + 2.0 * float(trim_mm)


def prints_on_sheet(sheet_mm=SHEET_MM, px_percent: float = 60.0, *, frame_mm: float = FRAME_MM,
                    trim_mm: float = 0.0) -> int:
    """The most prints whose glued strip (:func:`strip_length_mm`) fits the sheet's long side (0 if not even one)."""
    long_side = max(float(s) for s in sheet_mm)
    n = 0
    while n < 1000 and strip_length_mm(n + 1, px_percent, frame_mm=frame_mm, trim_mm=trim_mm) <= long_side:
        n += 1
    return n


def remarks() -> tuple:
    """What can be checked in §6, as sentences: the A3 sheet against the strip, and the two trims."""
    w, _ = SHEET_MM
    four = strip_length_mm(4, 60.0)
    lo, hi = rule("step 5", "trim").value
    four_lo, four_hi = strip_length_mm(4, 60.0, trim_mm=lo), strip_length_mm(4, 60.0, trim_mm=hi)
    five = strip_length_mm(5, 60.0)
    n_untrimmed = prints_on_sheet(SHEET_MM, 60.0)
    n_trimmed = prints_on_sheet(SHEET_MM, 60.0, trim_mm=hi)
    t9 = rule("after step 9", "trim").value
    return (
        f"Step 5 asks for an {SHEET} sheet ({w:g} mm long).  The working areas of n contact prints "
        f"({FRAME_MM:g} mm) at p_x = 60 % are {FRAME_MM:g} + (n − 1)·{FRAME_MM * 0.4:g} mm long: four prints "
        f"{four:g} mm ({four_lo:g}–{four_hi:g} mm with the trim of {lo / 10:g}–{hi / 10:g} cm), five prints "
        f"{five:g} mm.  {SHEET} holds {n_untrimmed} prints, {n_trimmed} with the {hi / 10:g} cm trim; a longer "
        "strip needs a larger sheet (the book takes the smallest ISO sheet that holds it).",
        f"Step 5 trims {lo / 10:g}–{hi / 10:g} cm beyond the working areas; the text after step 9 trims "
        f"{t9[0] / 10:g}–{t9[1] / 10:g} cm beyond the working-area lines — two margins for the same cut.",
        "The appendix signs the sample with 'M 1: 13000' — the letter M, which the guide uses for the plan's "
        "scale, for the fotoschema's mean scale; the value cannot be checked (the sample's bases are not printed).",
    )
