"""The live demos' words in Russian: slider labels, groups, titles, hints, tooltips, choices, buttons, status lines.

Keys are the English strings of the demos' ``Param``\\ s and class attributes (``aerophoto.demos``) and of
:class:`aerophoto.widgets.LiveDemo`; symbols stay as the guide writes them, units go Russian (mm → мм).
"""

from __future__ import annotations

__all__ = ["MESSAGES"]

_LABELS = {
    "1:M_c (photo)": "1:M_с (снимок)",
    "1:M_k (map)": "1:M_к (карта)",
    "A (sun azimuth), °": "A (азимут Солнца), °",
    "B, m": "B, м",
    "DEM stage": "этап ЦМР",
    "H (humus), %": "H (гумус), %",
    "H, m": "H, м",
    "K, strips": "K, маршрутов",
    "Lx, km": "Lx, км",
    "Ly, km": "Ly, км",
    "P east, m": "P к востоку, м",
    "P north, m": "P к северу, м",
    "P, µm": "P, мкм",
    "V (visibility), km": "V (видимость), км",
    "W (ground speed), km/h": "W (путевая скорость), км/ч",
    "W, km/h": "W, км/ч",
    "area": "участок",
    "arrows": "стрелки",
    "bend, %": "изгиб, %",
    "camera": "съёмка",
    "central centre (photo no.)": "центральный центр (№ снимка)",
    "closing paragraph's errors": "ошибки заключительного абзаца",
    "control": "опорные точки",
    "crab ±, °": "непараллельность ±, °",
    "crab φ, °": "непараллельность φ, °",
    "cut": "порез",
    "d (particle size), mm": "d (размер частиц), мм",
    "d, m": "d, м",
    "e (sun elevation), °": "e (высота Солнца), °",
    "f, mm": "f, мм",
    "film": "плёнка",
    "grid drawn by": "построение сеток",
    "h = Zmax − Zmin, m": "h = Zmax − Zmin, м",
    "h, m": "h, м",
    "h, relief, m": "h, рельеф, м",
    "layout": "схема",
    "m (photo 1:m)": "m (снимок 1:m)",
    "m (scale 1:m)": "m (масштаб 1:m)",
    "m allowed, mm": "m допустимая, мм",
    "m_h, m": "m_h, м",
    "m_p (pricking), mm": "m_p (накол), мм",
    "m_z, m": "m_z, м",
    "m_ε, ′": "m_ε, ′",
    "map shows": "на карте",
    "n (cells per side)": "n (ячеек на сторону)",
    "n, bases between control rows": "n, базисов между рядами опоры",
    "p, mm": "p, мм",
    "p_x, %": "p_x, %",
    "p_y, %": "p_y, %",
    "photoplan 1:M": "фотоплан 1:M",
    "photos per strip": "снимков в маршруте",
    "pricking σ, mm": "накол σ, мм",
    "px, %": "px, %",
    "py, %": "py, %",
    "q = free-strip / plan scale": "q = масштаб свободного маршрута / плана",
    "r (clods)": "r (глыбистость)",
    "relief ±h, m": "рельеф ±h, м",
    "season": "сезон",
    "seed": "зерно",
    "sheet": "лист",
    "show": "показать",
    "spread of 1–4, %": "разброс 1–4, %",
    "step": "шаг",
    "strips": "маршруты",
    "structural lines": "структурные линии",
    "t (exposure), ms": "t (выдержка), мс",
    "table 10 row": "строка таблицы 10",
    "view": "вид",
    "x, mm": "x, мм",
    "y, mm": "y, мм",
    "ΔH ±, %": "ΔH ±, %",
    "Δh, m": "Δh, м",
    "α max, °": "α макс, °",
    "α, °": "α, °",
    "θ (moisture), %": "θ (влажность), %",
    "θ (soil moisture), %": "θ (влажность почвы), %",
    "κ, °": "κ, °",
    "λ, °": "λ, °",
    "σ, µm": "σ, мкм",
    "σβ, ″": "σβ, ″",
}

_GROUPS = {
    "Accuracy": "Точность",
    "Air": "Атмосфера",
    "Aircraft": "Самолёт",
    "Angles": "Углы",
    "Block": "Блок",
    "Camera": "Камера",
    "Camera and flight": "Камера и полёт",
    "Control": "Опорные точки",
    "DEM": "ЦМР",
    "Errors": "Ошибки",
    "Flight": "Полёт",
    "Floating mark": "Мерная марка",
    "Free strip": "Свободный маршрут",
    "Grids": "Сетки",
    "Ground": "Местность",
    "Image motion": "Сдвиг изображения",
    "Imperfections": "Отклонения",
    "Key": "Эталон",
    "Map": "Карта",
    "Measuring": "Измерение",
    "Mosaic": "Монтаж",
    "New photo": "Новый снимок",
    "Object": "Объект",
    "Orientation": "Ориентирование",
    "Overlaps": "Перекрытия",
    "Photo": "Снимок",
    "Photos": "Снимки",
    "Plan": "План",
    "Reduction": "Редуцирование",
    "Season and moisture": "Сезон и влажность",
    "Sequence": "Последовательность",
    "Soil": "Почва",
    "Station": "Станция",
    "Sun": "Солнце",
    "Surface": "Поверхность",
    "Terrain": "Рельеф",
    "Terrain and area": "Рельеф и участок",
    "View": "Вид",
    "Where": "Где",
}

_TITLES = {
    "Base, height and focal length: parallax and the model's relief":
        "Базис, высота и фокусное расстояние: параллакс и рельеф модели",
    "Contours from a DEM against the true ground (article 000)":
        "Горизонтали по ЦМР против истинной поверхности (статья 000)",
    "Design of control: rows across the strips (guide §11, §13)":
        "Проект планово-высотной подготовки: ряды поперёк маршрутов (пособие §11, §13)",
    "Displacement explorer: relief (from n) and tilt (from c)":
        "Смещения точек: за рельеф (от n) и за наклон (от c)",
    "Is the survey fit for use? The rough mosaic and the checks of guide §3":
        "Годна ли съёмка? Накидной монтаж и проверки пособия §3",
    "Plan correction by mutual projective grids (guide §10)":
        "Исправление плана по взаимно проективным сеткам (пособие §10)",
    "Planning the survey: strips, photos and time (guide §2)":
        "Расчёт аэрофотосъёмки: маршруты, снимки и время (пособие §2)",
    "Relief displacement: radial from the nadir point n":
        "Смещение за рельеф: радиально от точки надира n",
    "Resection (обратная засечка) and the danger circle (guide §11)":
        "Обратная засечка и опасный круг (пособие §11)",
    "Spectral explorer: what moisture, humus and particle size do to a soil's reflectance":
        "Спектры: как влажность, гумус и размер частиц меняют отражательную способность почвы",
    "Table 10 as a key (топографическое дешифрирование)":
        "Таблица 10 как эталон (топографическое дешифрирование)",
    "The error budget of updating a map (article 003)":
        "Бюджет ошибок обновления карты (статья 003)",
    "The floating mark: set it on the ground, then on a roof":
        "Мерная марка: поставьте её на землю, затем на крышу",
    "The photo transformer: matching four points (guide §12)":
        "Фототрансформатор: совмещение четырёх точек (пособие §12)",
    "The reduction explorer: free strip, error triangles, reduction":
        "Редуцирование: свободный маршрут, треугольники погрешностей, редуцирование",
    "The single-strip fotoschema (одномаршрутная фотосхема)":
        "Одномаршрутная фотосхема",
    "Tilt displacement: radial from the isocentre c":
        "Смещение за наклон: радиально от точки нулевых искажений c",
    "What makes a photo readable (дешифрируемость)":
        "Что делает снимок дешифрируемым (дешифрируемость)",
    "What the camera sees: footprint, o, n and c":
        "Что видит камера: охват, o, n и c",
    "Where a block is weakest: predicted errors against the control layout":
        "Где блок слабее всего: ожидаемые ошибки и расположение опорных точек",
}

_HINTS = {
    "A longer base B or a lower flight H makes every height give more parallax and the stereo model taller (V); a longer lens at the same scale needs a higher flight and flattens it.":
        "Длиннее базис B или ниже полёт H — каждая высота даёт больший параллакс, и стереомодель выше (V); "
        "более длиннофокусный объектив при том же масштабе требует более высокого полёта и уплощает её.",
    "Black: contours drawn from the DEM; dashed grey: where they should be. Coarsen the grid until the interpolation shows, then switch the structural lines on; raise m_z and watch the contours wriggle.":
        "Чёрные — горизонтали по ЦМР; серые штриховые — где они должны быть. Огрубляйте сетку, пока не проявится "
        "интерполяция, затем включите структурные линии; увеличьте m_z и посмотрите, как горизонтали извиваются.",
    "Blue: the exact displacement (tilted photo vs the vertical one turned about the isoline); orange: the guide's δα = −(r<sub>c</sub>²·cos φ/f)·sin α. Points on the isoline h<sub>c</sub>–h<sub>c</sub> do not move.":
        "Синие — точное смещение (наклонный снимок против горизонтального, повёрнутого вокруг линии неискажённых "
        "масштабов); оранжевые — формула пособия δα = −(r<sub>c</sub>²·cos φ/f)·sin α. Точки на линии h<sub>c</sub>–h<sub>c</sub> не смещаются.",
    "Change the free strip's scale: k follows 1/q and the arrows v = r(k − 1) grow, but the control residuals do not change. Raise the pricking error: the triangles and the spread of k grow. Move the centre: the corrections change, the result does not.":
        "Измените масштаб свободного маршрута: k следует за 1/q и стрелки v = r(k − 1) растут, но остатки на опорных "
        "точках не меняются. Увеличьте ошибку накола: растут треугольники и разброс k. Сместите центр: поправки "
        "меняются, результат — нет.",
    "Change the season, lower the sun, thicken the haze, wet the soil, slow the shutter: watch what you can still tell apart.":
        "Смените сезон, опустите Солнце, сгустите дымку, увлажните почву, удлините выдержку: посмотрите, что ещё "
        "можно различить.",
    "Each blue dot is the station resected from angles with random errors of σβ. Walk the station towards the dashed circle through I, II, III: the cloud stretches, and on the circle the angles no longer fix the station.":
        "Каждая синяя точка — станция, найденная обратной засечкой по углам со случайными ошибками σβ. Ведите "
        "станцию к штриховой окружности через I, II, III: облако вытягивается, а на окружности углы уже не "
        "определяют станцию.",
    "Every arrow runs from where the point would be if it lay on the mean object plane to where it is. Change the relief, then tilt the photo (α) and see the arrows radiate from n, not from o.":
        "Каждая стрелка идёт оттуда, где была бы точка на средней плоскости объекта, туда, где она есть. Измените "
        "рельеф, затем наклоните снимок (α): стрелки расходятся от n, а не от o.",
    "Every bar is one stage's RMS error on the map; the total is their root-sum-square. Find what dominates, then ask what would have to change to bring the mean error under 0.4 mm.":
        "Каждый столбик — СКО одного этапа на карте; итог — корень из суммы квадратов. Найдите главный вклад и "
        "решите, что изменить, чтобы средняя ошибка стала меньше 0,4 мм.",
    "Move 'step' to follow the operator: centre, scale, draw hh through the crossings of corresponding lines, turn it onto the screen's axis, tilt the screen. The arrows (lengthened ×k) are the misses; the sequence repeats until all are within 0.4 mm.":
        "Двигайте «шаг» вслед за оператором: центрирование, масштаб, линия hh через пересечения соответственных "
        "линий, поворот её на ось экрана, наклон экрана. Стрелки (удлинены ×k) — невязки; последовательность "
        "повторяется, пока все не станут меньше 0,4 мм.",
    "Move the control rows apart (n) and watch the errors swell between them — faster in height; add strips and the same control holds a stiffer block.  σ scales every error.":
        "Разведите ряды опорных точек (n): ошибки между ними растут, по высоте быстрее; добавьте маршруты — та же "
        "опора держит более жёсткий блок.  σ масштабирует все ошибки.",
    "Pick a row of table 10: the photo shows the site where that key applies, and what to look at.":
        "Выберите строку таблицы 10: снимок покажет участок, где применим этот признак, и на что смотреть.",
    "Push an imperfection past its tolerance — crab, tilt, height scatter, a bent route, a small overlap — and watch the print, pair or strip turn vermillion and the verdict change.":
        "Выведите отклонение за допуск — непараллельность, наклон, разброс высот, изгиб маршрута, малое перекрытие — "
        "и снимок, пара или маршрут станет красным, а вывод изменится.",
    "Raise the direction error m_ε or lower the allowed error m: Zhukov's spacing shrinks and rows of control crowd together. Switch to dense control to see what phototriangulation saves.":
        "Увеличьте ошибку направления m_ε или уменьшите допустимую ошибку m: расстояние по Жукову сокращается, и "
        "ряды опоры сближаются. Включите плотную опору, чтобы увидеть, что экономит фототриангуляция.",
    "Raise the relief h or lower the scale denominator m and watch the number of strips and photos grow; a faster aircraft shortens the flight but also the longest admissible exposure.":
        "Увеличьте рельеф h или уменьшите знаменатель масштаба m — число маршрутов и снимков растёт; более быстрый "
        "самолёт сокращает полёт, но и наибольшую допустимую выдержку.",
    "Raise the relief or the tilt and watch cut-outs (−, vermillion) and duplicates (+, blue) appear along the cuts; a longer focal length flies higher at the same scale and shrinks the relief mismatches.":
        "Увеличьте рельеф или наклон: вдоль порезов появятся вырезы (−, красные) и дублеты (+, синие); с более "
        "длиннофокусной камерой при том же масштабе летят выше, и несовпадения за рельеф уменьшаются.",
    "Red–cyan glasses, red over the LEFT eye. Move p (the parallax bar's drum) until the two crosses fuse into one mark resting on the surface; then read its height. Larger p lifts the mark.":
        "Красно-голубые очки, красный — на ЛЕВОМ глазу. Вращайте p (барабан параллактического винта), пока два "
        "креста не сольются в одну марку на поверхности; затем прочтите её высоту. Больше p — марка выше.",
    "Relief arrows point away from the nadir n for hills and towards it for the valley; tilt arrows point towards the isocentre c on the far side of the isoline and away from it on the near side. Raise α and watch the guide's formula (orange) part from the exact tilt displacement (blue).":
        "Стрелки за рельеф направлены от надира n на холмах и к нему в долине; стрелки за наклон — к точке нулевых "
        "искажений c по одну сторону линии неискажённых масштабов и от неё по другую. Увеличьте α: формула "
        "пособия (оранжевая) расходится с точным смещением за наклон (синее).",
    "Tilt the camera (α) and watch the footprint turn into a trapezoid while n and c move away from o along the principal vertical.":
        "Наклоните камеру (α): охват превращается в трапецию, а n и c уходят от o вдоль главной вертикали.",
    "Tilt the new photo (α) and compare the two ways of drawing the grids: with central directions the carried changes (vermillion) sit on the truth (green) and get better as n grows; with proportional division they stay off however fine the grid.":
        "Наклоните новый снимок (α) и сравните два способа построения сеток: по центральным направлениям "
        "перенесённые изменения (красные) ложатся на истину (зелёную) и точнее с ростом n; при пропорциональном "
        "делении они остаются в стороне, как ни мельчи сетку.",
    "Wet the soil (θ) and watch the dips at 1.45 and 1.95 µm deepen while every band darkens; add humus (the red band reacts most, and little beyond 5 %); make the particles finer than 0.4 mm.":
        "Увлажните почву (θ): провалы на 1,45 и 1,95 мкм углубляются, а все зоны темнеют; добавьте гумус (сильнее "
        "всего реагирует красная зона, и мало — свыше 5 %); сделайте частицы мельче 0,4 мм.",
}

_TOOLTIPS = {
    "1 = a single strip": "1 = один маршрут",
    "RMS error of a central direction": "СКО центрального направления",
    "RMS error of a measured angle": "СКО измеренного угла",
    "RMS error of a measured photo coordinate": "СКО измеренной координаты на снимке",
    "RMS error of pricking a point on a photo (guide: 0.1 mm)": "СКО накола точки на снимке (пособие: 0,1 мм)",
    "RMS error of the pricked points on the photo": "СКО наколотых точек на снимке",
    "RMS height error of the DEM": "СКО высот ЦМР",
    "RMS measurement error of the node heights (densification)": "СКО измерения высот узлов (сгущение)",
    "add points along thalwegs and watersheds and triangulate (TIN)":
        "добавить точки по тальвегам и водоразделам и триангулировать (TIN)",
    "air base: distance between exposures": "базис фотографирования: расстояние между центрами снимков",
    "allowed RMS error of an orienting point on the plan": "допустимая СКО ориентирующей точки на плане",
    "another draw of the pricking errors": "другая выборка ошибок накола",
    "area across the strips": "размер участка поперёк маршрутов",
    "area along the strips": "размер участка вдоль маршрутов",
    "cells per side of the grids": "ячеек на сторону сетки",
    "clockwise from north": "по часовой стрелке от севера",
    "clod roughness: 0 harrowed … 0.15 fresh ploughing": "глыбистость: 0 боронование … 0,15 свежая вспашка",
    "constant crab angle": "постоянный угол непараллельности",
    "contour interval (сечение рельефа)": "сечение рельефа",
    "control rows across the block every n bases": "ряды опорных точек поперёк блока через n базисов",
    "diameter of the particles (aggregates)": "диаметр частиц (агрегатов)",
    "direction of the principal vertical": "направление главной вертикали",
    "direction of the principal vertical on the photo": "направление главной вертикали на снимке",
    "flying height above the ground": "высота полёта над местностью",
    "flying-height scatter, % of H": "разброс высоты полёта, % от H",
    "focal length": "фокусное расстояние",
    "focal length (sets the crab limit)": "фокусное расстояние (задаёт допуск непараллельности)",
    "focal length (the article: 153 mm)": "фокусное расстояние (в статье 153 мм)",
    "focal length f": "фокусное расстояние f",
    "focal length f (the variants reach 1090 mm)": "фокусное расстояние f (в вариантах до 1090 мм)",
    "focal length f; H = f·m (the variants reach 1090 mm)": "фокусное расстояние f; H = f·m (в вариантах до 1090 мм)",
    "form of the cuts (guide figure 12)": "форма порезов (пособие, рисунок 12)",
    "forward overlap": "продольное перекрытие",
    "ground speed": "путевая скорость",
    "heading of the photo": "направление снимка",
    "heading of the photo's x axis": "направление оси x снимка",
    "height difference of the ground (the site's hills rescaled)": "перепад высот местности (холмы участка в масштабе)",
    "height of an object above the ground": "высота объекта над землёй",
    "height of the highest hill above (and the valley below) the mean object plane":
        "высота самого высокого холма над средней плоскостью объекта (и долины под ней)",
    "how far out the four control points lie": "насколько далеко лежат четыре опорные точки",
    "how much the arrows are lengthened so they can be seen; auto keeps the longest ≈ 14 mm":
        "во сколько раз удлинены стрелки, чтобы их было видно; auto — самая длинная ≈ 14 мм",
    "humus content of the topsoil": "содержание гумуса в верхнем слое почвы",
    "interior orientation and σ = 0.884·P": "внутреннее ориентирование и σ = 0,884·P",
    "largest tilt": "наибольший наклон",
    "largest tilt of the photos (each is tilted at random up to this)":
        "наибольший наклон снимков (каждый наклонён случайно не больше этого)",
    "largest tilt of the photos (reduced, with a note, where it would carry them off the site)":
        "наибольший наклон снимков (уменьшается с пометкой, где он вывел бы их за участок)",
    "meteorological visibility: smaller V, thicker haze": "метеорологическая видимость: меньше V — гуще дымка",
    "normative forward overlap": "нормативное продольное перекрытие",
    "normative side overlap": "нормативное поперечное перекрытие",
    "photo scale denominator": "знаменатель масштаба снимка",
    "photo scale denominator (the variants reach 21 900)": "знаменатель масштаба снимка (в вариантах до 21 900)",
    "photo-scale denominator": "знаменатель масштаба снимка",
    "photoplan scale: the blur δ = 0.1 mm is measured on it": "масштаб фотоплана: по нему меряется смаз δ = 0,1 мм",
    "planned forward overlap": "расчётное продольное перекрытие",
    "planned side overlap": "расчётное поперечное перекрытие",
    "random extra crab": "случайная добавочная непараллельность",
    "random stream": "случайная последовательность",
    "random stream of the tilts": "случайная последовательность наклонов",
    "relief of the area": "рельеф участка",
    "relief within a photo, max − min": "рельеф в пределах снимка, макс − мин",
    "sagitta of the route, % of its length": "стрелка прогиба маршрута, % его длины",
    "scale denominator of the photo over the mean plane; H = f·m":
        "знаменатель масштаба снимка для средней плоскости; H = f·m",
    "scanning resolution (pixel size)": "разрешение сканирования (размер пикселя)",
    "step of the regular grid": "шаг регулярной сетки",
    "the mark on the left photo, from the area's centre": "марка на левом снимке, от центра участка",
    "the mark's x-parallax: the drum of the parallax bar": "продольный параллакс марки: барабан параллактического винта",
    "the rows of table 10 that the site shows, in the table's order": "строки таблицы 10, видимые на участке, по порядку таблицы",
    "the rows of table 10 that the site shows, in the table's order, counted from 1":
        "строки таблицы 10, видимые на участке, по порядку таблицы, считая с 1",
    "the station's offset east of the centre of I, II, III": "смещение станции к востоку от центра I, II, III",
    "the station's offset north of the centre of I, II, III": "смещение станции к северу от центра I, II, III",
    "the sun's elevation above the horizon (it matters through the clods' shadows)":
        "высота Солнца над горизонтом (влияет через тени глыб)",
    "the sun's height above the horizon": "высота Солнца над горизонтом",
    "the template's arbitrary scale; k ≈ 1/q": "произвольный масштаб восковки; k ≈ 1/q",
    "the working centre the corrections are measured from (guide §13: 37 or 38)":
        "рабочий центр, от которого считаются поправки (пособие §13: 37 или 38)",
    "tilt of the new photo": "наклон нового снимка",
    "tilt of the optical axis": "наклон оптической оси",
    "tilt of the photo": "наклон снимка",
    "volumetric moisture of the topsoil": "объёмная влажность верхнего слоя почвы",
    "volumetric moisture of the topsoil above the season's": "объёмная влажность верхнего слоя почвы сверх сезонной",
    "which bands are shown as red, green and blue": "какие зоны показаны как красный, зелёный и синий",
    "which motion of the sequence": "какое движение последовательности",
}

_OPTIONS = {
    "0.25 m": "0,25 м", "0.5 m": "0,5 м", "1 m": "1 м", "2 m": "2 м",
    "DEM of accuracy m_h": "ЦМР точности m_h",
    "Thematic Mapper 5-4-3": "Thematic Mapper 5-4-3",
    "Thematic Mapper 7-4-2": "Thematic Mapper 7-4-2",
    "auto": "авто",
    "autumn (осень)": "осень",
    "central directions": "центральные направления",
    "chimney and water tower": "труба и водонапорная башня",
    "colour film": "цветная плёнка",
    "colour infrared": "спектрозональный",
    "colour-infrared film": "спектрозональная плёнка",
    "curved": "криволинейный",
    "dense (every base)": "плотная (каждый базис)",
    "direct (left photo to the left eye)": "прямой (левый снимок — левому глазу)",
    "forest edge": "опушка леса",
    "height error": "ошибка по высоте",
    "hills (2–3 km E, 3–4 km N)": "холмы (2–3 км В, 3–4 км С)",
    "in": "включены",
    "instruction's tolerance (article)": "допуск инструкции (статья)",
    "left out": "не учитываются",
    "mast": "мачта",
    "natural colour": "естественные цвета",
    "no DEM: mean plane, relief Δh": "без ЦМР: средняя плоскость, рельеф Δh",
    "off": "выкл.",
    "on": "вкл.",
    "perimeter only": "только по периметру",
    "plain (6–7 km E, 0.2–1.2 km N)": "равнина (6–7 км В, 0,2–1,2 км С)",
    "plan error": "ошибка в плане",
    "proportional division": "пропорциональное деление",
    "relief and tilt": "рельеф и наклон",
    "relief only": "только рельеф",
    "reverse (photos swapped)": "обратный (снимки переставлены)",
    "rows across every strip": "ряды поперёк каждого маршрута",
    "sparse (Zhukov)": "разреженная (по Жукову)",
    "spring, leaf-off (весна)": "весна, без листвы",
    "straight": "прямолинейный",
    "summer (лето)": "лето",
    "the whole overlap": "всё перекрытие",
    "tilt only": "только наклон",
    "valley side (4–5 km E, 1.5–2.5 km N)": "склон долины (4–5 км В, 1,5–2,5 км С)",
    "village": "посёлок",
    "winter, snow (зима)": "зима, снег",
    "zigzag": "зигзаг",
}

_WIDGETS = {
    # aerophoto.widgets.LiveDemo
    "Reset": "Сброс",
    "Back to the starting values": "Вернуть начальные значения",
    # aerophoto.demos.lecture.lecture_view: the projector mode
    "Projector": "Проектор",
    "Larger text, lines and markers for the back row (remembered)":
        "Крупнее текст, линии и маркеры для задних рядов (запоминается)",
    # aerophoto.widgets.pending_html: the status line while the full picture waits for the slider to rest
    "preview — full resolution when the slider rests": "предпросмотр — полное разрешение, когда ползунок остановится",
    "preview (10 m raster) — full resolution when the slider rests":
        "предпросмотр (растр 10 м) — полное разрешение, когда ползунок остановится",
}

#: English → Russian
MESSAGES = {**_LABELS, **_GROUPS, **_TITLES, **_HINTS, **_TOOLTIPS, **_OPTIONS, **_WIDGETS}


# aerophoto.demos.block_adjustment_live (chapter 15): sliders, table, figure
_BLOCK_ADJUSTMENT = {
    "Bundle block adjustment: control, σ and a blunder": "Уравнивание блока по методу связок: опора, σ и грубая ошибка",
    "Switch the blunder on and off, then raise σ: the same 0.1 mm blunder stands out at a few µm and hides in the "
    "noise at 30 µm. Take the control down to three corners: the ellipses and the check points' errors swell, most "
    "in height.":
        "Включите и выключите грубую ошибку, затем увеличьте σ: та же ошибка 0,1 мм хорошо видна при нескольких мкм "
        "и теряется в шуме при 30 мкм. Оставьте опору только в трёх углах: эллипсы и ошибки контрольных точек "
        "растут, больше всего по высоте.",
    "control layout": "схема опоры",
    "control points kept; the others become check points": "оставленные опорные точки; остальные становятся контрольными",
    "corners, sides and centre (9)": "углы, стороны и центр (9)",
    "corners and sides (8)": "углы и стороны (8)",
    "four corners (4)": "четыре угла (4)",
    "three corners (3)": "три угла (3)",
    "RMS error of a photo coordinate; the gravimetric marks 6σ, the control 0.1 m per µm":
        "СКО координаты на снимке; гравиметрические метки 6σ, опора 0,1 м на мкм",
    "blunder": "грубая ошибка",
    "Blunder": "Грубая ошибка",
    "one image measurement moved on the photo": "одно измерение на снимке смещено",
    "blunder, mm": "грубая ошибка, мм",
    "length of the image blunder on the photo": "величина грубой ошибки на снимке",
    "data snooping": "поиск грубых ошибок (data snooping)",
    "largest |w| (critical 4.0)": "наибольший |w| (критический 4,0)",
    "|w| of the blundered observation": "|w| измерения с грубой ошибкой",
    "check points, plan RMS (true)": "контрольные точки, СКО в плане (истинная)",
    "… predicted by the covariances": "… предвычисленная по ковариациям",
    "check points, height RMS (true)": "контрольные точки, СКО по высоте (истинная)",
    "gravimetric points, largest semi-axis a": "гравиметрические пункты, наибольшая полуось a",
    "the largest |w| is the planted blunder: rejected": "наибольший |w| — у заложенной грубой ошибки: отбракована",
    "the largest |w| is a good observation: a false alarm": "наибольший |w| — у верного измерения: ложная тревога",
    "no |w| above the critical value: the blunder passes unseen":
        "нет |w| выше критического: грубая ошибка проходит незамеченной",
    "no |w| above the critical value: no blunder found": "нет |w| выше критического: грубых ошибок не найдено",
    "The adjusted block": "Уравненный блок",
    "adjusting the block for the new control layout…": "уравнивание блока для новой схемы опоры…",
    "photo centres": "центры снимков",
    "tie points": "связующие точки",
    "check points": "контрольные точки",
    "gravimetric points": "гравиметрические пункты",
    "standard ellipse × 400": "стандартный эллипс × 400",
    "flagged": "отбраковано",
    "true error × 400": "истинная ошибка × 400",
    "Data snooping: standardised residuals": "Поиск грубых ошибок: нормированные поправки",
    "observations, sorted by |w|": "измерения, по возрастанию |w|",
    "image observations": "измерения на снимках",
    "control coordinates": "координаты опорных точек",
    "the blunder": "грубая ошибка",
    "critical |w| = 4": "критический |w| = 4",
}
MESSAGES = {**MESSAGES, **_BLOCK_ADJUSTMENT}

# the ray of a vertical photo (chapter 00; the browser benchmark's floor, aerophoto.demos.ray)
_RAY = {
    "x, mm": "x, мм",
    "Photo point": "Точка снимка",
    "the point on the photo, from o along the flight": "точка на снимке, от o вдоль маршрута",
    "One ray of a vertical photo": "Один луч горизонтального снимка",
    "Move x: the ray from S turns, its ground point X = x·m slides along the footprint.":
        "Двигайте x: луч из S поворачивается, его точка на местности X = x·m скользит по границам снимка.",
    "f = {f} mm, 1:{m}: H = f·m = {H} m": "f = {f} мм, 1:{m}: H = f·m = {H} м",
    "footprint's edge rays": "лучи на края снимка",
    "footprint": "покрытие снимка",
    "the ray of x": "луч точки x",
    "X on the ground, m": "X на местности, м",
    "Z above the ground, m": "Z над местностью, м",
    "One ray": "Один луч",
    "x on the photo": "x на снимке",
    "X = x·m on the ground": "X = x·m на местности",
    "θ = arctan(x/f) from the vertical": "θ = arctg(x/f) от отвесной линии",
}
MESSAGES = {**MESSAGES, **{k: v for k, v in _RAY.items() if k not in MESSAGES}}
# aerophoto.demos.loupe and the table-10 key's close-ups (chapter 08)
_LOUPE = {
    "A magnifier on the photo (лупа)": "Лупа на снимке",
    "Put the glass on a mark or click on the photo; at ×5–×6 you see the crowns of a stand, the rows and wheel "
    "tracks of a field, a road's shoulders and ditches, the rails.":
        "Наведите лупу на метку или щёлкните по снимку; при ×5–×6 видны кроны деревьев, рядки и колеи на поле, "
        "обочины и кюветы дороги, рельсы.",
    "x (glass centre), mm": "x (центр лупы), мм",
    "y (glass centre), mm": "y (центр лупы), мм",
    "centre on": "навести на",
    "power, ×": "увеличение, ×",
    "Where the glass is": "Где лупа",
    "Glass": "Лупа",
    "photo x of the glass's centre": "координата x центра лупы на снимке",
    "photo y of the glass's centre": "координата y центра лупы на снимке",
    "put the glass over one of the photo's marks": "навести лупу на одну из меток снимка",
    "how many times larger than the print": "во сколько раз крупнее отпечатка",
    "— (use x, y)": "— (по x, y)",
    "mark 1": "метка 1", "mark 2": "метка 2", "mark 3": "метка 3", "mark 4": "метка 4", "mark 5": "метка 5",
    "mark 6": "метка 6",
    "stand P": "насаждение P", "stand Q": "насаждение Q",
    "bank point A": "точка берега A", "bank point B": "точка берега B",
    "the glass: full detail when the slider rests": "лупа: все подробности, когда ползунок остановится",
    "the close-up: full detail when the slider rests": "участок: все подробности, когда ползунок остановится",
}
MESSAGES = {**MESSAGES, **_LOUPE}

# a variant without a record-book number shows as "(variant NN)" in the variant's table (aerophoto.variants)
MESSAGES = {**MESSAGES, **{f"(variant {i:02d})": f"(вариант {i:02d})" for i in range(100)}}
