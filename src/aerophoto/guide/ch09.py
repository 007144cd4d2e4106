"""Chapter 09 · guide §10 (plan correction by mutual projective grids): the section's inputs and steps, as data.

§10 prints no table and no numbers to audit: it lists the materials (a
1:10 000 topographic map, a photo of the new survey, tracing paper), the
ways of carrying changes onto an old plan, and the four steps of graphical
transformation (графическое трансформирование) by mutual projective grids
(взаимно-проектные сетки), with figure 18.  They are kept here once, in
English with the Russian terms, for chapter 09 to show; the computations
are :mod:`aerophoto.projective`.

The one technical point the audit of the steps raises (chapter 09 shows it
with numbers): step 3 builds each grid by *equal* division of the
quadrilateral's sides — proportional division (пропорциональное деление).
Equal parts on the plan are not equal parts on a tilted photo, so those two
grids are not images of each other and transfer cell by cell keeps an error
however fine the grid; the grids of central directions (центральные
направления), which §10 names as the alternative, are exactly projective.
"""

from __future__ import annotations

import pandas as pd

__all__ = ["SOURCE", "PLAN_SCALE_M", "INPUTS", "METHODS", "GRID_METHODS", "STEPS", "methods_table", "steps_table"]

SOURCE = "guide §10"
#: the scale of the plan to be corrected, 1:M (guide §10: "часть топокарты М 1:10000")
PLAN_SCALE_M = 10000.0
#: the materials of §10
INPUTS = ("a part of a 1:10 000 topographic map (часть топокарты М 1:10000)",
          "a photo of the new survey (аэроснимок новой съёмки)",
          "tracing paper (калька)")
#: the simplified ways of carrying changes onto the plan (guide §10), English (Russian)
METHODS = (
    ("linear measurements, intersections, alignments", "линейные промеры и засечки, створы"),
    ("phototriangulation intersections", "фототриангуляционные засечки"),
    ("graphical transformation", "графическое трансформирование"),
    ("grapho-mechanical transformation", "графо-механическое"),
    ("optico-graphical transformation", "оптико-графическое"),
    ("with a stereoscope", "при помощи стереоскопа"),
    ("inserting the photo brought to the plan's scale", "врезка приведённого к заданному масштабу аэроснимка"),
)
#: the ways of drawing mutual projective grids named in step 1: key of aerophoto.projective.METHODS or None
GRID_METHODS = (
    ("similar figures", "подобных фигур", None),
    ("proportional division", "пропорционального деления", "proportional"),
    ("central directions", "центральных направлений", "central"),
)
#: the steps of graphical transformation (guide §10)
STEPS = (
    "Within the working area of the photo and on the plan, build mutual projective grids by one of the ways of "
    "step 1 (figure 18); four control (transformation) points are chosen at the corners of the working area.",
    "Transfer the control points and the principal point c.",
    "Measure the sides of the quadrilateral, divide the longest into parts and the others into as many; join the "
    "points on opposite sides: the grid.",
    "On the plan join the corresponding points: the corresponding figure.  Carry the changes onto the plan cell "
    "by cell, by eye or with a proportional compass.",
)


def methods_table() -> pd.DataFrame:
    """§10's list of ways to carry changes onto a plan (English, Russian)."""
    return pd.DataFrame(list(METHODS), columns=["method", "Russian"], index=pd.RangeIndex(1, len(METHODS) + 1))


def steps_table() -> pd.DataFrame:
    """§10's steps of graphical transformation, numbered."""
    return pd.DataFrame({"step": list(STEPS)}, index=pd.RangeIndex(1, len(STEPS) + 1, name="№"))
