"""Chapter 13 · guide §14 (aerial and space photos in soil mapping): its facts as data.

§14 prints no numeric table to audit.  What it states as facts — the classes of soil maps by scale, the
shape of a soil's reflectance curve and what moves it, the keys a soil interpreter uses and the steps of the
work — is transcribed here once, in English with the guide's Russian terms, and checked against the model of
:mod:`aerophoto.spectral` by the tests.

Transcription notes (OCR garbling cleaned): "хмельном кадастре" is "земельном кадастре" (land cadastre),
"косметических фотоснимков" is "космических" (space photos), "генератизацией" is "генерализацией",
"помненном" is "почвенном", "Диагностику ночи" is "Диагностику почв".

The scale classes leave gaps
----------------------------
The guide lists detailed maps at 1:5000 and larger, large-scale ones at 1:10 000…1:25 000, medium-scale
ones at 1:50 000…1:200 000 and small-scale ones at 1:500 000 and smaller.  Scales between 1:5000 and
1:10 000, between 1:25 000 and 1:50 000 and between 1:200 000 and 1:500 000 belong to no class as printed
(they are not standard scales of the Russian series either); :func:`soil_map_scale_class` answers
``"between classes"`` there and names the neighbours in :func:`scale_class_note`.
"""

from __future__ import annotations

import pandas as pd

from .._validate import check_range
from .._digits import scale as fmt_scale

__all__ = ["SCALE_CLASSES", "BETWEEN", "CLASS_NAMES", "soil_map_scale_class", "scale_class_note", "scale_table",
           "DIRECTIONS", "REFLECTANCE_FACTS", "WATER_DIPS_UM", "HUMUS_LINEAR_UP_TO_PCT", "PARTICLE_BELOW_MM",
           "INDIRECT_KEYS", "DIRECT_KEYS", "TEXTURE_SHOWS", "STEPS", "keys_table", "steps_table"]

#: guide §14, the soil maps by scale: (class, Russian, smallest denominator, largest denominator, use).
#: ``None`` = open: "1:5000 and larger" has no lower bound, "1:500 000 and smaller" no upper bound.
SCALE_CLASSES = (
    ("detailed", "детальные", None, 5000,
     "intensive farming (rice, vineyards, cotton, tea, citrus), anti-erosion measures, irrigation and drainage "
     "networks; soil grading (бонитировка) and land valuation in the land cadastre"),
    ("large-scale", "крупномасштабные", 10000, 25000,
     "the main maps of land management (землеустройство): crop rotations, soil-uniform fields; the land "
     "cadastre"),
    ("medium-scale", "среднемасштабные", 50000, 200000,
     "agro-soil zoning of districts, the direction of their farming"),
    ("small-scale", "мелкомасштабные", 500000, None,
     "maps of regions and republics: strategic tasks such as the specialisation of regions"),
)
#: the answer for a scale the printed classes do not cover
BETWEEN = "between classes"
CLASS_NAMES = tuple(c[0] for c in SCALE_CLASSES) + (BETWEEN,)


def soil_map_scale_class(scale_denominator: float) -> str:
    """The class of a soil map at 1 : ``scale_denominator`` (guide §14), or ``"between classes"`` in a gap.

    Bounds are inclusive as printed ("1:5000 and larger": m ≤ 5000; "1:10 000…1:25 000": 10 000 ≤ m ≤
    25 000; …).  ``scale_denominator`` m: 1 ≤ m ≤ 1e9.
    """
    m = check_range("scale_denominator", scale_denominator, 1.0, 1e9)
    for name, _ru, lo, hi, _use in SCALE_CLASSES:
        if (lo is None or m >= lo) and (hi is None or m <= hi):
            return name
    return BETWEEN


def scale_class_note(scale_denominator: float) -> str:
    """A sentence naming the class of 1:m, or for a gap the two classes it falls between."""
    m = check_range("scale_denominator", scale_denominator, 1.0, 1e9)
    name = soil_map_scale_class(m)
    label = fmt_scale(m)
    if name != BETWEEN:
        ru = dict((c[0], c[1]) for c in SCALE_CLASSES)[name]
        return f"{label}: a {name} soil map ({ru})"
    below = [c for c in SCALE_CLASSES if c[3] is not None and c[3] < m][-1]
    above = [c for c in SCALE_CLASSES if c[2] is not None and c[2] > m][0]
    return (f"{label}: between classes — larger than {below[0]} maps (to {fmt_scale(below[3])}) and smaller than "
            f"{above[0]} ones (from {fmt_scale(above[2])}); the guide's list leaves this gap")


def scale_table() -> pd.DataFrame:
    """The classes as the guide lists them, with the printed range and the gaps between them."""
    rows = []
    for i, (name, ru, lo, hi, use) in enumerate(SCALE_CLASSES):
        rng = (f"{fmt_scale(hi)} and larger" if lo is None else f"{fmt_scale(lo)} and smaller" if hi is None
               else f"{fmt_scale(lo)} … {fmt_scale(hi)}")
        rows.append((name, ru, rng, use))
        if i + 1 < len(SCALE_CLASSES):
            nxt = SCALE_CLASSES[i + 1][2]
            rows.append((BETWEEN, "(не названы)", f"{fmt_scale(hi)} … {fmt_scale(nxt)} (exclusive)",
                         "not listed by the guide"))
    return pd.DataFrame(rows, columns=["class", "Russian", "scales", "used for (guide §14)"])


#: the two directions of soil interpretation (почвенное дешифрирование), guide §14
DIRECTIONS = (
    ("soil mapping", "почвенно-картографическое", "the types of soils and their boundaries, for special maps"),
    ("soil research", "почвенно-исследовательское",
     "dynamic processes in the soil cover (erosion, salinisation, waterlogging, advancing sands: repeated "
     "surveys; floods, ripeness for sowing, moisture, temperature: prompt surveys)"),
)

#: where liquid water absorbs: the dips of a wet soil's curve, µm (guide §14)
WATER_DIPS_UM = (1.45, 1.95)
#: the integral brightness is linear in humus and iron oxides up to this content, %, then parabolic (guide §14)
HUMUS_LINEAR_UP_TO_PCT = 5.0
#: brightness rises exponentially as particles get finer, most noticeably below this diameter, mm (guide §14)
PARTICLE_BELOW_MM = 0.4

#: guide §14's statements about soil reflectance (r_λ), each with what the model does
REFLECTANCE_FACTS = (
    ("shape", "a dry soil brightens smoothly from 0.4 µm to 1.6…2.0 µm, then dims gently to 2.5 µm",
     "dry_shape S(λ)"),
    ("moisture", "a wet soil's curve dips where water absorbs, with maxima (of absorption) at 1.45 and 1.95 µm; "
                 "moisture changes the brightness strongly; visible and near-infrared photos together show "
                 "the moisture", "moisture_factor"),
    ("humus", "the integral brightness falls linearly with humus and iron oxides up to 5 %, then along a "
              "parabola; the red zone is the most sensitive", "humus_g, humus_sensitivity"),
    ("clods", "coarser clods darken the surface: shaded area, anisotropic reflection, multiple reflection",
     "clod_factor"),
    ("particles", "brightness rises exponentially as the particles get finer, most below 0.4 mm",
     "particle_factor"),
)

#: the indirect keys (косвенные признаки): soil-forming factors seen on the photo (guide §14)
INDIRECT_KEYS = (
    ("relief", "рельеф", "steepness and exposure of slopes, hollows and rises on flat ground; seen best in "
                         "the stereo model; micro-relief shows by tone (gleying in micro-hollows, poorer soils on "
                         "micro-rises)"),
    ("vegetation", "растительность", "hides the soil yet indicates it; trees are read most easily, of the "
                                     "grasses only natural ones are reliable indicators"),
    ("parent rock", "почвообразующие породы", "rarely exposed: judged mainly by the relief, on stereo photo "
                                              "mosaics"),
    ("human activity", "хозяйственная деятельность", "which land use goes with which soils; irrigation, "
                                                     "drainage, anti-erosion works"),
)
#: the direct keys (прямые признаки), usable on bare or sparsely covered ground (guide §14)
DIRECT_KEYS = (
    ("tone (colour)", "тон (цвет)", "depends on the band and on the soil's spectral brightness; two fields of "
                                    "the same soil differ if their moisture or roughness differ, and with their "
                                    "place relative to the photo's centre and the sun; colour and false-colour "
                                    "(spectrozonal) photos carry more"),
    ("texture", "текстура", "shows tillage, complexes of small soil patches, erosion, salt, animals; helps "
                            "recognise landscapes rather than soils"),
    ("size and shape of contours", "размеры и форма контуров", "follow the relief; not reliable keys"),
)
TEXTURE_SHOWS = ("tillage traces (ploughing, harrowing)", "the parts of complex soils", "erosion",
                 "salt on the surface", "the work of animals (marmots, moles)")

#: the steps of soil interpretation (guide §14): (English, Russian, what is done)
STEPS = (
    ("preparation", "подготовительный", "collect and study soil maps, profile descriptions and analyses; "
                                        "bring the soil names to the current classification; relate the "
                                        "photos to the maps to find the keys and their reliability"),
    ("preliminary office interpretation", "предварительное камеральное дешифрирование",
     "divide the image into areas homogeneous in tone (colour), texture and soil-forming factors (contour "
     "soil interpretation); name the soils where the keys allow; sure contours solid, doubtful dashed; plan "
     "routes, key areas and soil pits"),
    ("field survey", "полевое обследование", "routes through every doubtful area; a pit in every new or "
                                             "re-characterised contour; each soil type checked at least three "
                                             "times; key areas study all soil-factor links"),
    ("office processing and final interpretation", "камеральная обработка и окончательное дешифрирование",
     "analyse the samples, complete the diagnosis, refine the contours, prepare reference samples (эталоны)"),
    ("transfer to the base map", "перенесение на топографическую основу",
     "onto a topographic or base land map at the given scale; if there is none, a simplified topographic "
     "interpretation is made alongside"),
)


def keys_table() -> pd.DataFrame:
    """The direct and indirect keys of soil interpretation (guide §14)."""
    rows = [("indirect", *k) for k in INDIRECT_KEYS] + [("direct", *k) for k in DIRECT_KEYS]
    return pd.DataFrame(rows, columns=["kind", "key", "Russian", "what it tells (guide §14)"])


def steps_table() -> pd.DataFrame:
    """The five steps of soil interpretation (guide §14)."""
    return pd.DataFrame([(i + 1, *s) for i, s in enumerate(STEPS)],
                        columns=["step", "stage", "Russian", "what is done"]).set_index("step")

