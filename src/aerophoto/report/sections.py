"""The explanatory note's sections, in the order of the guide's §15, and the book's chapters under each.

§15 ("Требования к оформлению курсовой работы") lists the 13 sections of the explanatory note
(пояснительная записка); they are the guide's §2–§14.  Each section collects the chapters of the book's
registry (:data:`aerophoto.book.CHAPTERS`) whose ``source`` names that § of the guide, so a chapter added
to the registry appears in the report without any change here.  The assignment (guide §1, chapter 00)
comes first; chapters from other sources (the articles) follow the 13 sections.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

__all__ = ["Section", "SECTIONS", "ASSIGNMENT", "chapters_by_section", "guide_sections_of"]


@dataclass(frozen=True)
class Section:
    """One section of the explanatory note: its number in §15's list, the guide's §, headings RU and EN.

    ``formula``: the section's key formula as Typst math and as plain text (shown where the student has
    done the section's work), or empty.
    """

    number: int
    guide: int
    ru: str
    en: str
    formula: tuple = ()


#: guide §1, "Задание на курсовую работу": the variant's inputs and chapter 00
ASSIGNMENT = Section(0, 1, "Задание на курсовую работу", "The assignment: your variant")

#: §15's 13 sections, in its order (headings as §15 prints them)
SECTIONS = (
    Section(1, 2, "Расчет параметров аэрофотосъёмки", "Planning the aerial survey",
            ("H = f m, quad P_x = p_x + 40 h / H, quad B_x = b_x m", "H = f·m,  P_x = p_x + 40·h/H,  B_x = b_x·m")),
    Section(2, 3, "Оценка качества материалов аэрофотосъёмки", "Judging the quality of the photos"),
    Section(3, 4, "Определение смещений точек и поправок за рельеф", "Relief displacement and its corrections",
            ("delta_h = (r h) / H", "δh = r·h/H")),
    Section(4, 5, "Определение смещений точек и поправок за угол наклона аэроснимка",
            "Tilt displacement and its corrections",
            ("delta_alpha = (r_c^2 sin phi sin alpha) / (f - r_c sin phi sin alpha)",
             "δα = r_c²·sin φ·sin α / (f − r_c·sin φ·sin α)")),
    Section(5, 6, "Изготовление одномаршрутной фотосхемы", "Making the single-strip photo mosaic",
            ("1 / m_i = l_i / (L_i M)", "1/m_i = l_i / (L_i·M)  (6.1)")),
    Section(6, 7, "Построение одномаршрутного фототриангуляционного ряда", "Building a strip phototriangulation"),
    Section(7, 8, "Линзово-зеркальный стереоскоп. Изучение стереомодели местности",
            "The mirror stereoscope; studying the stereo model",
            ("Delta h = (H Delta p) / (b + Delta p)", "Δh = H·Δp / (b + Δp)")),
    Section(8, 9, "Дешифрирование аэроснимков", "Interpreting the photos"),
    Section(9, 10, "Корректировка плана части землепользования методом построения взаимно-проектных сеток",
            "Correcting a plan by mutual projective grids"),
    Section(10, 11, "Составление проекта планово-высотной привязки", "Designing the ground control"),
    Section(11, 12, "Фототрансформирование снимков равнинной местности", "Rectifying photos of flat ground"),
    Section(12, 13, "Фототриангуляция", "Phototriangulation"),
    Section(13, 14, "Применение аэро- и космических снимков при почвенном картографировании",
            "Aerial and satellite photos in soil mapping"),
)


def guide_sections_of(chapter) -> tuple:
    """The guide's § numbers a chapter's ``source`` names ("guide §6" → (6,)); () for an article."""
    src = str(getattr(chapter, "source", ""))
    if "guide" not in src:
        return ()
    return tuple(int(n) for n in re.findall(r"§\s*(\d+)", src))


def chapters_by_section(chapters) -> tuple[dict, list]:
    """``({section.guide: [chapter, …]}, [other chapters])`` for the registry's chapters, in registry order.

    A chapter goes under the first § of the guide its source names; the assignment (§1) has key 1.
    """
    known = {ASSIGNMENT.guide} | {s.guide for s in SECTIONS}
    by: dict = {k: [] for k in sorted(known)}
    others = []
    for ch in chapters:
        secs = [g for g in guide_sections_of(ch) if g in known]
        if secs:
            by[secs[0]].append(ch)
        else:
            others.append(ch)
    return by, others
