"""The explanatory note's sections, in the order of the guide's §15, and the writer of each.

§15 ("Требования к оформлению курсовой работы") lists the 13 sections of the explanatory note (пояснительная
записка); they are the guide's §2–§14, and the book's chapters 01–13 (chapter 00, the elements of the central
projection, goes with §5).  The four article chapters (14–17) follow as sections 14–17.  :func:`plan` reads the
registry (:data:`aerophoto.book.CHAPTERS`): a chapter with a writer of its own is written by it
(:mod:`aerophoto.report.write_survey` …); a chapter added to the registry without one appears in its section (or
after the articles) with the generic writer, so no chapter is left out.
"""

from __future__ import annotations

import re
from dataclasses import dataclass

__all__ = ["Section", "SECTIONS", "ARTICLES", "guide_sections_of", "plan", "writers", "extractors"]


@dataclass(frozen=True)
class Section:
    """One section of the note: its number, the guide's § (0 for an article) and its heading RU and EN."""

    number: int
    guide: int
    ru: str
    en: str


#: §15's 13 sections, in its order (headings as §15 prints them)
SECTIONS = (
    Section(1, 2, "Расчет параметров аэрофотосъёмки", "Planning the aerial survey"),
    Section(2, 3, "Оценка качества материалов аэрофотосъёмки", "Judging the quality of the photos"),
    Section(3, 4, "Определение смещений точек и поправок за рельеф", "Relief displacement and its corrections"),
    Section(4, 5, "Определение смещений точек и поправок за угол наклона аэроснимка",
            "Tilt displacement and its corrections"),
    Section(5, 6, "Изготовление одномаршрутной фотосхемы", "Making the single-strip photo mosaic"),
    Section(6, 7, "Построение одномаршрутного фототриангуляционного ряда", "Building a strip phototriangulation"),
    Section(7, 8, "Линзово-зеркальный стереоскоп. Изучение стереомодели местности",
            "The mirror stereoscope; studying the stereo model"),
    Section(8, 9, "Дешифрирование аэроснимков", "Interpreting the photos"),
    Section(9, 10, "Корректировка плана части землепользования методом построения взаимно-проектных сеток",
            "Correcting a plan by mutual projective grids"),
    Section(10, 11, "Составление проекта планово-высотной привязки", "Designing the ground control"),
    Section(11, 12, "Фототрансформирование снимков равнинной местности", "Rectifying photos of flat ground"),
    Section(12, 13, "Фототриангуляция", "Phototriangulation"),
    Section(13, 14, "Применение аэро- и космических снимков при почвенном картографировании",
            "Aerial and satellite photos in soil mapping"),
)

#: the articles' chapters as sections 14–17 (article id → number and headings)
ARTICLES = {
    "001": Section(14, 0, "Точность фототриангуляционных сетей", "Accuracy of phototriangulation networks"),
    "002": Section(15, 0, "Аэрофотопривязка пунктов гравиметрической съёмки в высокогорье",
                   "Photo control of gravimetric points in the high mountains"),
    "000": Section(16, 0, "Рисовка горизонталей по точкам цифровой модели рельефа",
                   "Contours from the points of a digital elevation model"),
    "003": Section(17, 0, "Анализ плановой точности при обновлении карт", "Planimetric accuracy of map updating"),
}


def guide_sections_of(chapter) -> tuple:
    """The guide's § numbers a chapter's ``source`` names ("guide §6" → (6,)); () for an article."""
    src = str(getattr(chapter, "source", ""))
    if "guide" not in src:
        return ()
    return tuple(int(n) for n in re.findall(r"§\s*(\d+)", src))


def writers() -> dict:
    """chapter number → the function that writes it (chapter 00 is written inside section 4)."""
    from . import write_articles as A
    from . import write_displacement as D
    from . import write_models as M
    from . import write_strip as S
    from . import write_survey as V

    return {"01": V.write_01, "02": V.write_02, "03": D.write_03, "04": D.write_04, "05": S.write_05,
            "06": S.write_06, "07": M.write_07, "08": M.write_08, "09": M.write_09, "10": M.write_10,
            "11": M.write_11, "12": S.write_12, "13": M.write_13, "14": A.write_14, "15": A.write_15,
            "16": A.write_16, "17": A.write_17}


def extractors() -> dict:
    """task id → the function that reduces its inputs to the numbers the note prints."""
    from . import write_articles, write_displacement, write_models, write_strip, write_survey

    out: dict = {}
    for mod in (write_survey, write_displacement, write_strip, write_models, write_articles):
        out.update(mod.EXTRACT)
    return out


#: chapters written together with another one's section: chapter 00 (o, n, c) goes with §5's writer
COMPANIONS = {"00": "04"}


def plan(chapters) -> list:
    """The note's sections in order: ``[(Section, [chapter, …]), …]`` — §15's 13, then the articles, then any
    registry chapter of neither (under a section of its own)."""
    out = [(s, []) for s in SECTIONS]
    by_guide = {s.guide: k for k, s in enumerate(SECTIONS)}
    extra: list = []
    for ch in chapters:
        if ch.number in COMPANIONS:
            continue
        secs = [g for g in guide_sections_of(ch) if g in by_guide]
        art = getattr(ch, "article", None)
        if secs:
            out[by_guide[secs[0]]][1].append(ch)
        elif art in ARTICLES:
            extra.append((ARTICLES[art], [ch]))
        else:
            extra.append((Section(0, 0, ch.title_ru, ch.title), [ch]))
    extra.sort(key=lambda e: (e[0].number == 0, e[0].number))
    n = len(SECTIONS)
    numbered = []
    for s, chs in extra:
        n += 1
        numbered.append((Section(n, s.guide, s.ru[:1].upper() + s.ru[1:], s.en), chs))
    return out + numbered
