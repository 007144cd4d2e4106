"""The chapter registry's texts in Russian: each chapter's topic and each live demo's name.

Keyed, like the rest of the catalogue, by the English text of :data:`aerophoto.book.CHAPTERS` (a chapter's
``title``, a :class:`~aerophoto.book.Demo`'s ``name``), so that a changed English title has no Russian until it is
written here (``tests/presentation/test_prose.py`` fails for it).  :func:`aerophoto.book.chapter_table_markdown`
with ``lang="ru"`` builds chapter 00's Russian table of chapters from them; ``python -m aerophoto.book`` writes it
into ``notebooks/ru/00_start_here.md``.  The topic is the guide's Russian title (``title_ru``) with the chapter's
own subjects after a colon, as the English title has them.
"""

from __future__ import annotations

__all__ = ["TOPICS", "DEMO_NAMES", "SOURCES", "MESSAGES"]

#: a chapter's English title → its Russian topic (the guide's term first)
TOPICS = {
    "start here: your variant, central projection": "с чего начать: задание; центральная проекция",
    "planning the aerial survey": "расчёт параметров аэросъёмки",
    "judging the photos' quality": "оценка качества материалов аэрофотосъёмки",
    "relief displacement": "смещение точек за рельеф",
    "tilt displacement": "смещения за угол наклона",
    "the single-strip photo mosaic": "одномаршрутная фотосхема",
    "strip phototriangulation and its reduction": "фототриангуляционный ряд и его редуцирование",
    "the stereoscope and the stereo model: parallax, heights, the floating mark":
        "линзово-зеркальный стереоскоп; изучение стереомодели: параллакс, высоты, измерительная марка",
    "interpreting aerial photos: conditions, keys, table 10":
        "дешифрирование аэроснимков: условия фотографирования, дешифровочные признаки, таблица 10",
    "correcting a plan by mutual projective grids": "корректировка плана методом взаимно-проектных сеток",
    "ground control: design, marking and resection":
        "проект планово-высотной привязки: проектирование, маркировка, обратная засечка",
    "rectifying photos of flat ground": "фототрансформирование снимков равнинной местности",
    "phototriangulation: control spacing and reduction":
        "фототриангуляция: расстояние между опорными точками и редуцирование",
    "aerial and space photos in soil mapping: soil reflectance, soil keys and contour interpretation":
        "применение аэро- и космических снимков при почвенном картографировании: спектральная яркость почв, "
        "дешифровочные признаки почв, контурное почвенное дешифрирование",
    "accuracy of phototriangulation: error accumulation and control spacing":
        "точность фототриангуляционных сетей: накопление ошибок и густота опорных точек",
    "bundle block adjustment: locating field points in the mountains":
        "блочная фототриангуляция по методу связок: привязка полевых пунктов в горах",
    "contours from a DEM: regular grid, structural lines, Lysenko's densification accuracy":
        "рисовка горизонталей по точкам ЦМР: регулярная сетка, структурные линии, точность сгущения по Лысенко",
    "the error budget of map updating": "анализ плановой точности при обновлении карт: бюджет ошибок",
}

#: a live demo's English name (``Demo.name``) → its Russian name
DEMO_NAMES = {
    "One ray of a vertical photo": "Один луч горизонтального снимка",
    "Camera footprint — o, n, c": "Охват снимка — o, n, c",
    "Live survey plan": "План аэросъёмки в движении",
    "Rough mosaic you can break": "Накидной монтаж, который можно испортить",
    "Displacement explorer, relief": "Смещения точек: рельеф",
    "Displacement explorer, tilt": "Смещения точек: наклон",
    "Live single-strip mosaic": "Одномаршрутная фотосхема в движении",
    "Reduction explorer": "Редуцирование",
    "The floating mark on an anaglyph": "Измерительная марка на анаглифе",
    "Base, height and focal length": "Базис, высота и фокусное расстояние",
    "What makes a photo readable": "Что делает снимок дешифрируемым",
    "Table 10 as an interactive key": "Таблица 10 как интерактивный эталон",
    "A magnifier on the photo": "Лупа на снимке",
    "Plan correction by mutual projective grids": "Корректировка плана по взаимно-проектным сеткам",
    "Design of control on a block": "Проект привязки блока",
    "Resection and the danger circle": "Обратная засечка и опасный круг",
    "The photo transformer, step by step": "Фототрансформатор шаг за шагом",
    "Reduction explorer (tilted photos)": "Редуцирование (наклонные снимки)",
    "Spectral explorer — soil reflectance and a band composite": "Спектры — отражательная способность почвы и синтез зон",
    "Block error map — control layout and σ": "Карта ошибок блока — расположение опоры и σ",
    "Bundle block adjustment — control, σ and a blunder": "Уравнивание блока по методу связок — опора, σ и грубая ошибка",
    "Contours from a DEM against the truth": "Горизонтали по ЦМР против истинной поверхности",
    "The error budget of map updating": "Бюджет ошибок обновления карты",
}

#: how the registry names a source (``Chapter.source``), as templates
SOURCES = {
    "guide §{section}": "руководство, §{section}",
    "article {article}": "статья {article}",
}

#: what this area adds to the catalogue (the other areas' entries win where both have one)
MESSAGES = {**TOPICS, **DEMO_NAMES, **SOURCES}
