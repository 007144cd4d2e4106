"""The chapter registry's texts in Russian: each chapter's topic and each live demo's name.

Keyed, like the rest of the catalogue, by the English text of :data:`aerophoto.book.CHAPTERS` (a chapter's
``title``, a :class:`~aerophoto.book.Demo`'s ``name``), so that a changed English title has no Russian until it is
written here (``tests/presentation/test_prose.py`` fails for it).  :func:`aerophoto.book.chapter_table_markdown`
with ``lang="ru"`` builds chapter 00's Russian table of chapters from them; ``python -m aerophoto.book`` writes it
into ``notebooks/ru/00_start_here.md``.  The topic is the guide's Russian title (``title_ru``) with the chapter's
own subjects after a colon, as the English title has them.
"""

from __future__ import annotations

__all__ = ["TOPICS", "DEMO_NAMES", "MOVES", "SEES", "LECTURES", "SOURCES", "MESSAGES"]

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

#: a live demo's ``Demo.move`` (what the lecturer moves) → Russian
MOVES = {
    'α (tilt), then f and m (scale 1:m)': 'α (наклон), затем f и m (масштаб 1:m)',
    'm, relief h, then f and W': 'm, рельеф h, затем f и W',
    'crab φ, α max, ΔH, bend, overlaps': 'непараллельность φ, α макс, ΔH, изгиб, перекрытия',
    'relief ±h, then α and f': 'рельеф ±h, затем α и f',
    'α, then λ and f': 'α, затем λ и f',
    'relief h, α max, then f and p_x': 'рельеф h, α макс, затем f и p_x',
    'q (free-strip scale), pricking error, central centre':
        'q (масштаб свободного ряда), ошибка накола, центральный центр',
    "p (the parallax bar's drum), then x, y onto a roof, then the area":
        'p (барабан параллактометра), затем x, y на крышу, затем участок',
    'B, then H and f together': 'B, затем H и f вместе',
    'season, then e (sun elevation) and V (visibility), then θ and t':
        'сезон, затем e (высота Солнца) и V (видимость), затем θ и t',
    'table 10 row, then the film': 'строка таблицы 10, затем плёнка',
    'α, then n and the grid method, then the spread': 'α, затем n и способ построения сеток, затем разброс',
    'm_ε and the allowed error, then the photo scale': 'm_ε и допустимая ошибка, затем масштаб снимков',
    'move the station towards the circle through I, II, III': 'вести станцию к окружности через I, II, III',
    'step, then α and the pricking error': 'шаг, затем α и ошибка накола',
    'α max, q, pricking error': 'α макс, q, ошибка накола',
    'θ (moisture) up, then H (humus), then d (particle size) below 0.4 mm':
        'увеличить θ (влажность), затем H (гумус), затем d (размер частиц) ниже 0,4 мм',
    'n (control spacing), then K strips and σ': 'n (расстояние между рядами опоры), затем K маршрутов и σ',
    'σ up, then the blunder off and on, then the control layout':
        'увеличить σ, затем выключить и включить грубую ошибку, затем схема опоры',
    'm_z to 0, then d up to 150 m, then the structural lines on':
        'm_z до 0, затем d до 150 м, затем включить структурные линии',
    'the DEM stage, then 1:M_c and P, then the map scale': 'этап ЦМР, затем 1:M_c и P, затем масштаб карты',
    'the mark to centre on, then the power, then x and y (or a click on the photo)':
        'метка, на которую навести лупу, затем увеличение, затем x и y (или щелчок по снимку)',
}

#: a live demo's ``Demo.sees`` (what the class sees) → Russian
SEES = {
    'the ray from S turns and its ground point X = x·m slides along the footprint: the scale 1:m = f:H of a vertical '
    'photo':
        'луч из S поворачивается, и его точка на местности X = x·m скользит по охвату снимка: масштаб горизонтального'
        ' снимка 1:m = f:H',
    'the footprint turns from a square into a trapezoid; n and c leave o along the principal vertical; with the scale'
    ' fixed, a longer lens flies higher but covers the same ground':
        'охват превращается из квадрата в трапецию; n и c уходят от o вдоль главной вертикали; при неизменном '
        'масштабе длиннофокусный объектив летит выше, но охватывает ту же местность',
    'strips and photos multiply as the scale grows or the relief rises; a faster aircraft shortens the flight and the'
    ' admissible exposure':
        'маршрутов и снимков становится больше, когда масштаб крупнее или рельеф выше; более быстрый самолёт '
        'сокращает полёт и допустимую выдержку',
    'an imperfection past its tolerance turns its print, pair or strip vermillion and changes the verdict':
        'отклонение за пределами допуска окрашивает свой отпечаток, пару или маршрут в красный и меняет вывод',
    'arrows radiate from the nadir n — outwards for hills, inwards for the valley; a longer lens at the same scale '
    'shortens them':
        'стрелки расходятся от точки надира n — наружу на холмах, внутрь в долине; длиннофокусный объектив при том же'
        ' масштабе их укорачивает',
    "arrows radiate from the isocentre c; points on the isoline stay put; the guide's approximate formula (orange) "
    'parts from the exact displacement (blue) as α grows':
        'стрелки расходятся от точки нулевых искажений c; точки на линии неискажённых масштабов остаются на месте; '
        'приближённая формула руководства (оранжевая) расходится с точным смещением (синим) по мере роста α',
    'cut-outs and duplicates appear along the cuts; a longer lens at the same scale shrinks the mismatches':
        'вдоль порезов появляются вырезы и дублеты; длиннофокусный объектив при том же масштабе уменьшает расхождения',
    'k follows 1/q and the reduction arrows grow while the control residuals stay; pricking errors grow the error '
    'triangles':
        'k следует за 1/q, и стрелки редуцирования растут, а расхождения на опорных точках остаются; ошибки накола '
        'увеличивают треугольники погрешностей',
    'through red–cyan glasses the two crosses fuse into one mark that rises with p; at the parallax of a roof or a '
    'tree top it rests on it and the table reads its height':
        'в красно-голубых очках два крестика сливаются в одну марку, которая поднимается с ростом p; при параллаксе '
        'крыши или вершины дерева она ложится на неё, и таблица показывает её высоту',
    'a longer base or a lower flight gives every height more parallax and a taller model; a longer lens at the same '
    'scale flattens it':
        'более длинный базис или более низкий полёт дают каждой высоте больший параллакс и более высокую модель; '
        'длиннофокусный объектив при том же масштабе её уплощает',
    'snow hides the fields; a low sun lengthens the shadows; haze greys the colours and flattens the contrast; wet '
    'soil darkens; a long exposure smears the photo along the flight':
        'снег скрывает поля; низкое Солнце удлиняет тени; дымка обесцвечивает краски и снижает контраст; влажная '
        'почва темнеет; длинная выдержка смазывает снимок вдоль полёта',
    'each row of table 10 shows the place on the site where its key applies: islands and the tributary give the flow,'
    ' tone and crowns tell pine from spruce, curvature a railway from a road':
        'каждая строка таблицы 10 показывает место на полигоне, где применим её признак: острова и приток дают '
        'направление течения, тон и кроны отличают сосну от ели, кривизна — железную дорогу от автомобильной',
    'with central directions the carried changes sit on the truth and improve as n grows; with proportional division '
    'they stay off however fine the grid':
        'при центральных направлениях перенесённые изменения ложатся на истину и уточняются с ростом n; при '
        'пропорциональном делении они остаются в стороне, как ни мельчи сетку',
    "Zhukov's spacing sets how many bases apart the rows of control go; a smaller scale or poorer directions crowd "
    'them, down to dense control':
        'расстояние по Жукову определяет, через сколько базисов идут ряды опорных точек; более мелкий масштаб или '
        'менее точные направления сближают их вплоть до сплошной привязки',
    'the cloud of stations resected under angle errors stretches near the danger circle':
        'облако станций, найденных обратной засечкой при ошибках углов, вытягивается вблизи опасного круга',
    'centre, scale, hh, turn, tilt: the misses of the four points fall below 0.4 mm in two cycles':
        'центрирование, масштаб, hh, поворот, наклон: расхождения четырёх точек за два цикла становятся меньше 0,4 мм',
    'the same explorer with tilted photos: the reduced strip against the control points':
        'тот же исследователь с наклонными снимками: редуцированный ряд против опорных точек',
    'wetting darkens every band and deepens the water dips at 1.45 and 1.95 µm; humus darkens the red band most and '
    'little beyond 5 %; fine particles brighten the soil; the patch follows':
        'увлажнение затемняет все зоны и углубляет провалы поглощения водой на 1,45 и 1,95 мкм; гумус сильнее всего '
        'затемняет красную зону и мало — свыше 5 %; мелкие частицы осветляют почву; участок следует за этим',
    'the predicted errors swell between the control rows, faster in height; more strips stiffen the block; σ '
    'brightens the whole map':
        'ожидаемые ошибки растут между рядами опорных точек, по высоте быстрее; больше маршрутов — жёстче блок; σ '
        'делает светлее всю карту',
    'the same blunder stands out at a few µm and passes unseen at 30 µm; fewer control points swell the ellipses and '
    "the check points' errors, most in height":
        'та же грубая ошибка хорошо видна при нескольких мкм и проходит незамеченной при 30 мкм; меньше опорных точек'
        ' — больше эллипсы и ошибки контрольных точек, сильнее всего по высоте',
    "with error-free nodes a 30 m grid follows the site's hills to millimetres; coarse grids cut the bends and the "
    'structural lines win part back; node errors make the contours wriggle':
        'при безошибочных узлах сетка 30 м повторяет холмы полигона до миллиметров; грубые сетки срезают перегибы, и '
        'структурные линии отчасти возвращают точность; ошибки узлов заставляют горизонтали извиваться',
    "the instruction's transfer and DEM tolerances dominate; a real DEM brings the map to 0.40 mm, the 40 µm transfer"
    ' rule within 0.4 mm; the photo scale and the scan barely matter':
        'преобладают допуски инструкции на перенос и на ЦМР; настоящая ЦМР доводит карту до 0,40 мм, правило переноса'
        ' 40 мкм — до пределов 0,4 мм; масштаб снимков и сканирование почти не влияют',
    "under the glass the marks of table 10 come out: pine's round crowns of one height against spruce's small dark "
    "ones, a field's rows and tramlines, a road's shoulders and ditches, the rails on the ballast":
        'под лупой проступают признаки таблицы 10: круглые кроны сосны одной высоты рядом с маленькими тёмными '
        'кронами ели, рядки и технологическая колея на поле, обочины и кюветы дороги, рельсы на балласте',
}

#: the lecture index's and the lecture pages' words
LECTURES = {
    "whole chapter": "вся глава",
    "**{name}.** Move: {move}. The class sees: {sees}.": "**{name}.** Что двигать: {move}. Что видит аудитория: {sees}.",
    "[← every lecture page](../{index}) · [the whole chapter {number}, with the theory and the tasks](../{notebook})"
    " · {source} · the demos open on the guide's worked example (variant 00); **Reset** returns there.":
        "[← все лекционные страницы](../{index}) · [вся глава {number} — с теорией и заданиями](../{notebook})"
        " · {source} · демонстрации открываются на примере из руководства (вариант 00); **Сброс** возвращает к нему.",
}

#: how the registry names a source (``Chapter.source``), as templates
SOURCES = {
    "guide §{section}": "руководство, §{section}",
    "article {article}": "статья {article}",
}

#: what this area adds to the catalogue (the other areas' entries win where both have one)
MESSAGES = {**TOPICS, **DEMO_NAMES, **MOVES, **SEES, **LECTURES, **SOURCES}
