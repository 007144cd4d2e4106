"""Chapter 07 · guide §8 (the lens-mirror stereoscope; studying the stereo model of the ground): the section's terms and steps.

§8 prints no table and no computed numbers: it defines the stereo effect
(стереоскопический эффект, стереоэффект) — direct (прямой) when the left photo
is seen by the left eye and the right by the right, reverse (обратный) when
they are swapped, hollows then looking like hills — and the stereo pair
(стереопара), two neighbouring photos taken from a base that overlap, with
figure 17 (a photo of the work with the stereoscope); then it gives the two
steps of the work: seeing a pair in depth without an instrument, with
conjugate images set at the mean eye base, and checking the stereoscope —
its general state, and the parallelism of its mirrors with a straight line
40 cm long.  They are kept here once, in English with the Russian terms, for
chapter 07 to show; the computations are :mod:`aerophoto.stereo`.

Two points the book adds with numbers (chapter 07): the guide gives no value
for the "mean eye base" (the book takes 65 mm, :data:`aerophoto.stereo.EYE_BASE_MM`),
and its mirror check reads as a diagnosis — two parallel lines mean the
instrument is turned (fixable by turning it), lines at an angle mean a mirror
is not parallel (fixable only by re-seating the mirror).
:func:`aerophoto.demos.stereo_figures.stereoscope_view` reproduces both.

Transcription notes: the scan's "получиться" is read "получится"; nothing
else in §8 is garbled.
"""

from __future__ import annotations

import pandas as pd

__all__ = ["SOURCE", "CHECK_LINE_CM", "TERMS", "STEPS", "CHECKS", "terms_table", "steps_table", "checks_table"]

SOURCE = "guide §8"
#: the straight line drawn for the check of the mirrors, cm (guide §8, step 2)
CHECK_LINE_CM = 40.0

#: the section's terms: English, Russian, what the guide says
TERMS = (
    ("stereo effect", "стереоскопический эффект (стереоэффект)",
     "seeing two flat images as one space image"),
    ("direct stereo effect", "прямой стереоэффект",
     "the left photo seen by the left eye and the right photo by the right eye"),
    ("reverse stereo effect", "обратный стереоэффект",
     "the photos swapped: hollows look like hills and hills like hollows"),
    ("stereo pair", "стереопара",
     "two neighbouring photos taken from a base, overlapping (figure 17)"),
    ("stereo model", "стереомодель",
     "the space image into which the pair fuses"),
    ("lens-mirror stereoscope", "линзово-зеркальный стереоскоп (ЛЗС)",
     "the simplest and most widely used instrument for seeing the stereo model"),
)

#: the steps of the work (guide §8)
STEPS = (
    "Place two conjugate images taken from any base at the distance of the mean eye base; point each eye's "
    "optical axis at the same contour point; the two points must merge into one, sharply seen in the middle — "
    "and with them the pair fuses into one space image, the stereo model.",
    "Check the stereoscope: an outer inspection (lenses and mirrors whole and clean, firmly held) and the check "
    "of the mirrors' setting.",
)

#: the check of the mirrors (guide §8, step 2)
CHECKS = (
    f"Draw a straight line {CHECK_LINE_CM:g} cm long on a sheet and set the stereoscope over it with its base "
    "parallel to the line: the observer must see one line.",
    "If two parallel lines are seen, refine the stereoscope's orientation by turning it until the lines merge.",
    "If they cannot be merged because the lines form an angle, the mirrors are not parallel: loosen each mirror in "
    "turn and tilt it away from the base, and from how the lines move find each mirror's position.",
    "Put strips of paper between the mirror's frame and the base of the instrument to remove the non-parallelism; "
    "tighten the screws and check the condition again.",
)


def terms_table() -> pd.DataFrame:
    """§8's terms: English, Russian and what they mean."""
    return pd.DataFrame(list(TERMS), columns=["term", "Russian", "meaning"]).set_index("term")


def steps_table() -> pd.DataFrame:
    """§8's two steps of the work, numbered."""
    return pd.DataFrame({"step": list(STEPS)}, index=pd.RangeIndex(1, len(STEPS) + 1, name="№"))


def checks_table() -> pd.DataFrame:
    """The check of the stereoscope's mirrors with the 40 cm line, step by step."""
    return pd.DataFrame({"check": list(CHECKS)}, index=pd.RangeIndex(1, len(CHECKS) + 1, name="№"))
