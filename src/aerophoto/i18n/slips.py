"""The graded tasks' mistake hints in Russian: what a typical slip gives (``Task.slips``) and the verdict hints.

Keys are the English hints of :mod:`aerophoto.tasks` (``slips(v)`` keys, ``Answer.hint``); the checks
(:mod:`aerophoto.checks`) translate a hint when they show it.  A hint never states the answer.
"""

from __future__ import annotations

__all__ = ["MESSAGES"]

_SLIPS = {
    "(10.20) grows as √(n(n + 1)(2n + 1)/6), not as n": "(10.20) растёт как √(n(n + 1)(2n + 1)/6), а не как n",
    "0.1 mm at the plan's scale 1:10 000 is 1 m on the ground, not 0.1 m":
        "0,1 мм в масштабе плана 1:10 000 — это 1 м на местности, а не 0,1 м",
    "B/H is b/f with both in mm": "B/H — это b/f, обе величины в мм",
    "H must be the flying height over the foot, B·f/p_foot — not Z_S or f·m":
        "H — высота полёта над основанием, B·f/p_осн, а не Z_S и не f·m",
    "K and n rounded down — the guide rounds both up": "K и n округлены вниз — пособие округляет оба вверх",
    "K and n rounded to the nearest — the guide rounds both up":
        "K и n округлены до ближайшего — пособие округляет оба вверх",
    "K and n without the '+ 1'": "K и n без «+ 1»",
    "K_d divides by the grid's lengths [l₀], not the print's [l_i]":
        "K_d делится на длины сетки [l₀], а не отпечатка [l_i]",
    "K_t = m/M is the enlargement from the photo to the base, not M/m":
        "K_t = m/M — увеличение со снимка на основу, а не M/m",
    "V is (B/H) divided by (e/d), not the other way round": "V — это (B/H), делённое на (e/d), а не наоборот",
    "a photo has six elements of exterior orientation, not three":
        "у снимка шесть элементов внешнего ориентирования, а не три",
    "atan2 takes (ΔY, ΔX) here: X is north, Y east, and the angle runs clockwise from X":
        "здесь atan2 берёт (ΔY, ΔX): X — на север, Y — на восток, угол идёт по часовой стрелке от X",
    "base mix-up: with the mean photo base b and H = f·m the formula is only approximate — use the foot's own parallax p and H = B·f/p":
        "путаница с базисом: со средним базисом b и H = f·m формула лишь приближённая — возьмите собственный "
        "параллакс основания p и H = B·f/p",
    "c lies on the principal vertical, turned by λ from the x axis":
        "c лежит на главной вертикали, повёрнутой на λ от оси x",
    "compare the mean error m_z/1.25, not m_z itself, with 0.3·h":
        "с 0,3·h сравнивается средняя ошибка m_z/1,25, а не сама m_z",
    "count the classes present on the map (np.unique), not all classes of the legend":
        "считайте классы, которые есть на карте (np.unique), а не все классы легенды",
    "count the links beyond the controlled model: the point of photo k has come through k − 1 of them":
        "считайте звенья за пределами опорной модели: точка снимка k прошла через k − 1 из них",
    "count |Δ| ≤ 0.15 m, of the DEM with structural lines": "считайте |Δ| ≤ 0,15 м для ЦМР со структурными линиями",
    "densification gets half of the map's RMS height error": "на сгущение приходится половина СКО высот карты",
    "divide the sum of |X − X̄| by n": "разделите сумму |X − X̄| на n",
    "divide ΣΔI² by n before taking the root.": "разделите ΣΔI² на n, прежде чем извлекать корень.",
    "divide ΣΔ² by n, not n − 1 (the true heights are known)":
        "делите ΣΔ² на n, а не на n − 1 (истинные высоты известны)",
    "divided by Bx — the route length is S/By (strips × strip length)":
        "поделено на Bx — длина маршрутов равна S/By (маршруты × длина маршрута)",
    "f is in millimetres: H = f/1000 · m gives metres": "f в миллиметрах: H = f/1000 · m даёт метры",
    "formula (10) takes all seven stages": "формула (10) учитывает все семь этапов",
    "heights spread uniformly over Δh have an RMS of Δh/√12 about the mean plane":
        "высоты, равномерно распределённые в пределах Δh, имеют СКО Δh/√12 относительно средней плоскости",
    "independent errors add as squares (formula 10), not linearly":
        "независимые ошибки складываются квадратично (формула 10), а не линейно",
    "k_i is the enlargement m/M, not 1": "k_i — увеличение m/M, а не 1",
    "m_D = 1.25·V_D (formula 5), not V_D/1.25": "m_D = 1,25·V_D (формула 5), а не V_D/1,25",
    "m_D = m_x,y·√2 (formula 8), not ·2": "m_D = m_x,y·√2 (формула 8), а не ·2",
    "m_D/M is in metres; the map needs millimetres (×1000)": "m_D/M в метрах; для карты нужны миллиметры (×1000)",
    "m_Z carries the factor f/b": "в m_Z входит множитель f/b",
    "m_p is 0.025 mm — the printed 0,25 lost a zero (see the reading above)":
        "m_p = 0,025 мм — в напечатанном 0,25 потерян ноль (см. пояснение выше)",
    "multiply by the photo scale M_c, not the map scale": "умножайте на масштаб снимка M_с, а не карты",
    "multiply by the plan's scale denominator M = 10 000 (6.1).":
        "умножьте на знаменатель масштаба плана M = 10 000 (6.1).",
    "only the x-coordinates: b is the whole distance from o to the transferred point":
        "не только абсциссы: b — полное расстояние от o до перенесённой точки",
    "read the level to a whole division (round the offset first).":
        "отсчитывайте уровень до целого деления (сначала округлите смещение).",
    "rounded to the nearest whole number — the guide rounds K up":
        "округлено до ближайшего целого — пособие округляет K вверх",
    "rounded to the nearest whole number — the guide rounds n up":
        "округлено до ближайшего целого — пособие округляет n вверх",
    "rows and columns are swapped: columns count from side 1–4 towards 2–3":
        "строки и столбцы перепутаны: столбцы считаются от стороны 1–4 к 2–3",
    "rows and columns are swapped: rows count from side 1–2 towards 4–3":
        "строки и столбцы перепутаны: строки считаются от стороны 1–2 к 4–3",
    "that is Bx, the photo base — By uses the side overlap Py":
        "это Bx, базис фотографирования — для By нужно поперечное перекрытие Py",
    "that is By, the strip spacing — Bx uses the forward overlap Px":
        "это By, расстояние между маршрутами — для Bx нужно продольное перекрытие Px",
    "that is H = f·m with your variant's nominal scale — the guide takes m_cp from your table 2":
        "это H = f·m с номинальным масштабом вашего варианта — пособие берёт m_ср из вашей таблицы 2",
    "that is an affine fit: four points fix a projective (8-parameter) transformation":
        "это аффинное приближение: четыре точки задают проективное (8-параметрическое) преобразование",
    "that is f·M — use the photo scale 1:m, not the photoplan scale 1:M":
        "это f·M — берите масштаб снимка 1:m, а не фотоплана 1:M",
    "that is f·tg(α/2), the isocentre — the nadir point uses the whole α":
        "это f·tg(α/2), точка нулевых искажений — для точки надира нужен весь угол α",
    "that is in minutes — τ is asked in seconds": "это в минутах — τ требуется в секундах",
    "that is in photo mm: the residuals are measured on the base":
        "это в мм снимка: остатки измеряются на основе",
    "that is measured on the photo at 1:m — a tilted photo has no single scale; measure on the corrected plan":
        "это измерено на снимке в 1:m — у наклонного снимка нет единого масштаба; измеряйте на исправленном плане",
    "that is on = f·tg α, the nadir point — the isocentre uses α/2":
        "это on = f·tg α, точка надира — для точки нулевых искажений нужен α/2",
    "that is the RMS error m_d; the mean error is m_d/1.25": "это СКО m_d; средняя ошибка равна m_d/1,25",
    "that is the angle from D to C; the check angle runs clockwise from C to D":
        "это угол от D к C; контрольный угол отсчитывается по часовой стрелке от C к D",
    "that is the darkening; the task asks for the share that is left":
        "это потемнение; задание спрашивает об оставшейся доле",
    "that is the direction from A to P; the direction angle from P to A is 180° away":
        "это направление от A к P; дирекционный угол от P к A отличается на 180°",
    "that is the dried soil: keep the pit's own moisture θ": "это высушенная почва: сохраните собственную влажность разреза θ",
    "that is the exact projective position; the task asks for the cell-by-cell transfer on the 4 × 4 grid — the difference is the grid's own error":
        "это точное проективное положение; задание спрашивает о переносе по клеткам сетки 4 × 4 — разница и есть "
        "собственная ошибка сетки",
    "that is the flying height over A, B·f/p; add A's own height Z_A":
        "это высота полёта над A, B·f/p; прибавьте собственную высоту A, Z_A",
    "that is the isocentre c (f·tg(α/2)) — the nadir point lies at f·tg α":
        "это точка нулевых искажений c (f·tg(α/2)) — точка надира лежит на f·tg α",
    "that is the length on the plan in mm — multiply by M/1000 for metres":
        "это длина на плане в мм — умножьте на M/1000, чтобы получить метры",
    "that is the mean error Σ|Δ|/n; the RMS error is √(ΣΔ²/n)": "это средняя ошибка Σ|Δ|/n; СКО равна √(ΣΔ²/n)",
    "that is the mean of |ΔI| — formula (6.2) squares, averages, then takes the root.":
        "это среднее |ΔI| — формула (6.2) возводит в квадрат, усредняет, затем извлекает корень.",
    "that is the nadir point's distance f·tg α — the isocentre uses α/2":
        "это расстояние до точки надира f·tg α — для точки нулевых искажений нужен α/2",
    "that is the normative px — add the relief allowance 40·h/H":
        "это нормативное px — добавьте поправку за рельеф 40·h/H",
    "that is the overlap itself (l·Px/100·m) — the base is the part that does not overlap":
        "это само перекрытие (l·Px/100·m) — базис — это неперекрытая часть",
    "that is the overlap itself (l·Py/100·m) — the spacing is the part that does not overlap":
        "это само перекрытие (l·Py/100·m) — расстояние между маршрутами — это неперекрытая часть",
    "that is the plain mean of the six heights — the guide averages the bases' mean heights in each zone, then the two zones":
        "это простое среднее шести высот — пособие усредняет средние высоты базисов в каждой зоне, затем две зоны",
    "that is the planned base l·(100 − p_x)/100 of §2 — measure b on your photos":
        "это расчётный базис l·(100 − p_x)/100 из §2 — измерьте b на своих снимках",
    "that is the small form b·h/H; the exact one is b·h/(H − h)":
        "это упрощённая формула b·h/H; точная — b·h/(H − h)",
    "that is the small-Δp form H·Δp/p; the exact formula has p + Δp in the denominator":
        "это формула для малых Δp, H·Δp/p; в точной в знаменателе p + Δp",
    "that is the standard deviation; the mean error is the mean of |X − X̄|":
        "это стандартное отклонение; средняя ошибка — среднее из |X − X̄|",
    "that is the straight distance between the road's ends; add up its segments":
        "это прямое расстояние между концами дороги; сложите её отрезки",
    "that is the tilt in divisions — multiply by 30′ = 0.5°.": "это наклон в делениях — умножьте на 30′ = 0,5°.",
    "that is the transfer on a grid of proportional division (equal parts); build the grid by central directions":
        "это перенос по сетке пропорционального деления (равные части); стройте сетку по центральным направлениям",
    "that is the whole frame on the ground (l·m), not the working area bx·m":
        "это весь кадр на местности (l·m), а не рабочая площадь bx·m",
    "that is the whole frame on the ground (l·m), not the working area by·m":
        "это весь кадр на местности (l·m), а не рабочая площадь by·m",
    "that is what you get without the relief allowance 40·h/H (as in the guide's misprinted 7.2 and 12.6 cm)":
        "так получается без поправки за рельеф 40·h/H (как в опечатках пособия 7,2 и 12,6 см)",
    "that is what you get without the relief allowance 40·h/H (as in the guide's misprinted 7.2 and 12.6 cm); like the guide's '0.86·3600/200'":
        "так получается без поправки за рельеф 40·h/H (как в опечатках пособия 7,2 и 12,6 см); как «0,86·3600/200» "
        "в пособии",
    "that is what you get without the relief allowance 40·h/H (as in the guide's misprinted 7.2 and 12.6 cm); like the guide's '30/1.51 + 1'":
        "так получается без поправки за рельеф 40·h/H (как в опечатках пособия 7,2 и 12,6 см); как «30/1,51 + 1» "
        "в пособии",
    "that is ΣΔI²/n — take the square root.": "это ΣΔI²/n — извлеките квадратный корень.",
    "that uses By — the interval is the photo base Bx over W": "здесь взят By — интервал равен базису Bx, делённому на W",
    "that uses Lx/Bx — strips are counted across the area: Ly/By":
        "здесь взято Lx/Bx — маршруты считаются поперёк участка: Ly/By",
    "that uses Ly/By — photos are counted along a strip: Lx/Bx":
        "здесь взято Ly/By — снимки считаются вдоль маршрута: Lx/Bx",
    "that uses the photo scale m — the blur δ is on the photoplan at 1:M":
        "здесь взят масштаб снимка m — смаз δ оценивается на фотоплане в 1:M",
    "the air base B is in metres on the ground; Δp and p are on the photo — B does not go in the denominator":
        "базис фотографирования B — в метрах на местности; Δp и p — на снимке; B не входит в знаменатель",
    "the allowed 0.3 mm is on the map: at the photo scale it is 0.3·M/m":
        "допустимые 0,3 мм — на карте; в масштабе снимка это 0,3·M/m",
    "the allowed height error is the RMS: 1.25 × the mean error h/3, halved":
        "допустимая ошибка высот — СКО: 1,25 × средняя ошибка h/3, пополам",
    "the angles were taken counter-clockwise: a theodolite reads them clockwise":
        "углы взяты против часовой стрелки, а теодолит отсчитывает их по часовой",
    "the area numbers are not soil codes: give each area the soil most of its cells have":
        "номера контуров — не коды почв: присвойте каждому контуру почву большинства его ячеек",
    "the base is the part of the frame not overlapped: l·(1 − p_x/100)":
        "базис — неперекрытая часть кадра: l·(1 − p_x/100)",
    "the book reads “zr” as s·r, not 2r": "в книге «zr» читается как s·r, а не 2r",
    "the control points are unknowns as well (their coordinates are observed, with weights)":
        "опорные точки тоже неизвестные (их координаты измерены, с весами)",
    "the formula has K_t + 1, not K_t": "в формуле K_t + 1, а не K_t",
    "the law grows as √n³, not as √n": "закон растёт как √n³, а не как √n",
    "the mean error takes |Δ|: with signs the errors cancel": "средняя ошибка берёт |Δ|: со знаками ошибки взаимно гасятся",
    "the partial scale is m_i = L_i·M/l_i — the plan's base times M over the fotoschema's, not the inverse.":
        "частный масштаб m_i = L_i·M/l_i — базис на плане, умноженный на M, делённый на базис на фотосхеме, а не "
        "наоборот.",
    "the photo base is the mean of both photos' bases, b = (b₁ + b₂)/2":
        "базис на снимке — среднее из базисов обоих снимков, b = (b₁ + b₂)/2",
    "the photo distance is in mm: multiply by m and divide by 1000 for metres":
        "расстояние на снимке в мм: умножьте на m и разделите на 1000, чтобы получить метры",
    "the relief allowance uses h = Zmax − Zmin, not Zmax": "в поправке за рельеф h = Zmax − Zmin, а не Zmax",
    "the relief's parallax difference uses the photo base b in mm, not B in m":
        "в разности параллаксов за рельеф — базис на снимке b в мм, а не B в м",
    "the sign: t has the sign of K_d (the guide's example prints it without)":
        "знак: t имеет знак K_d (в примере пособия он напечатан без знака)",
    "the sign: the x-parallax is p = x_left − x_right": "знак: продольный параллакс p = x_лев − x_прав",
    "the sign: Δγ = measured − computed": "знак: Δγ = измеренное − вычисленное",
    "the sign: δl = l₀ − l_i (grid minus print)": "знак: δl = l₀ − l_i (сетка минус отпечаток)",
    "the tie points are unknowns too: 3 coordinates each": "связующие точки тоже неизвестные: по 3 координаты",
    "the tolerance uses the distance to the check point D, not to C":
        "в допуске — расстояние до контрольной точки D, а не до C",
    "the whole frame is not the base: b = l·(1 − p_x)": "весь кадр — не базис: b = l·(1 − p_x)",
    "this is l_воск / l_осн — the coefficient is base over template":
        "это l_воск / l_осн — коэффициент равен основе, делённой на восковку",
    "the transfer stage here is formula (9) applied to the mean discrepancy 0.5 mm (0.357 mm, the article's slip); "
    "rule (1) first turns the mean into an RMS, 1.25·0.5 mm (chapter 17)":
        "этап переноса здесь — формула (9), применённая к средней невязке 0,5 мм (0,357 мм, ошибка статьи); "
        "правило (1) сначала переводит среднюю ошибку в СКО, 1,25·0,5 мм (глава 17)",
    "that uses b from the pricked principal points, which the photos' tilts shift by 1–3 %; the parallaxes of the "
    "normalised pair go with its base b₀ = B·f/H (chapter 07)":
        "здесь взят базис b по наколотым главным точкам, который наклоны снимков сдвигают на 1–3 %; параллаксы "
        "нормализованной пары идут с её базисом b₀ = B·f/H (глава 07)",
    "that is the scale of your variant's flight (the 1:m of the banner); this photo has its own scale, lab.m, "
    "printed with the photo — use that one":
        "это масштаб съёмки вашего варианта (1:m из заголовка); у этого снимка свой масштаб, lab.m, напечатанный "
        "вместе со снимком, — возьмите его",
    "this is m_X alone; the plan error m_D = √(m_X² + m_Y²)": "это одна m_X; ошибка в плане m_D = √(m_X² + m_Y²)",
    "this is the other reading of m_D, √2·m_X (the article's printed 0.11 mm); this task takes m_D as the plan "
    "error √(m_X² + m_Y²), as the article's legend names it (chapter 14)":
        "это другое прочтение m_D, √2·m_X (напечатанные в статье 0,11 мм); в этой задаче m_D — ошибка в плане "
        "√(m_X² + m_Y²), как её называет экспликация статьи (глава 14)",
    "this is m_Z at the photo scale in mm; the task asks for metres on the ground":
        "это m_Z в масштабе снимка в мм; задание требует метры на местности",
    "this is max k − min k; the guide's spread is the deviation from the mean":
        "это max k − min k; разброс в пособии — отклонение от среднего",
    "this is the X (along-strip) column; the task asks for heights Z":
        "это столбец X (вдоль маршрута); задание требует высоты Z",
    "this is the predicted (a priori) error; the task asks for the true errors of the check points":
        "это ожидаемая (априорная) ошибка; задание требует истинные ошибки контрольных точек",
    "this is the radicand as scanned (n⁰): read it n³ + 11n + 34":
        "это подкоренное выражение в отсканированном виде (n⁰): читайте n³ + 11n + 34",
    "this is the semi-minor axis: the task asks for the major one": "это малая полуось; задание требует большую",
    "this is with n² — the radicand is n³ + 11n + 34": "это с n² — подкоренное выражение n³ + 11n + 34",
    "this is with the blunders still in: reject them first (data snooping)":
        "это с неотбракованными грубыми ошибками: сначала отбракуйте их (data snooping)",
    "this is √(σX² + σY²), the plan RMS, not the ellipse's semi-major axis":
        "это √(σX² + σY²), СКО в плане, а не большая полуось эллипса",
    "use A's own parallax p_A in B·f/p, not the photo base b":
        "используйте собственный параллакс точки A, p_A, в B·f/p, а не базис на снимке b",
    "use the RMS radius r_rms of the working area, not its half-diagonal":
        "используйте средний квадратический радиус рабочей площади r_rms, а не её полудиагональ",
    "use the photo's scale 1:m — the ground distance is the photo distance times m":
        "используйте масштаб снимка 1:m — расстояние на местности равно расстоянию на снимке, умноженному на m",
    "without the factor 1.2 for turns and approaches": "без коэффициента 1,2 на развороты и заходы",
    "without the factor 1.2 in LS": "без коэффициента 1,2 в LS",
    "you counted the duplicates (+): cut-outs are the negative ΔI.":
        "вы посчитали дублеты (+): вырезы — это отрицательные ΔI.",
    "you divided by b2 — formula (3.4) divides by b1.": "вы разделили на b2 — формула (3.4) делит на b1.",
    "µm to m is ×10⁻⁶": "из мкм в м — это ×10⁻⁶",
    "β₁ and β₂ are swapped: β₁ is measured from A to B, β₂ from B to C":
        "β₁ и β₂ перепутаны: β₁ измеряется от A к B, β₂ — от B к C",
    "λ is counted from the photo's +x axis, counter-clockwise — x and y look swapped":
        "λ отсчитывается от оси +x снимка против часовой стрелки — похоже, x и y перепутаны",
    "σ is 0.5·P, not P": "σ равно 0,5·P, а не P",
}

_VERDICT_HINTS = {
    "compare P_x with the 56 % rejection threshold (guide §3).": "сравните P_x с порогом браковки 56 % (пособие §3).",
    "compare both residuals with the guide's 0.4 mm": "сравните оба остатка с 0,4 мм пособия",
    "compare every |k − mean| with 0.003 (0.006 on a base shorter than 133 mm on the plan).":
        "сравните каждое |k − среднее| с 0,003 (0,006 для базиса короче 133 мм на плане).",
    "compare every |Δk| with 0.003, or with 0.006 on a base shorter than 133 mm on the base":
        "сравните каждое |Δk| с 0,003 или с 0,006 для базиса короче 133 мм на основе",
    "compare its tone, texture, shape and surroundings with table 10's keys.":
        "сравните его тон, текстуру, форму и окружение с признаками таблицы 10.",
    "compare n with 2 % (H > 750 m) or 3 %.": "сравните n с 2 % (H > 750 м) или 3 %.",
    "compare the denominator with the ranges of guide §14 — and mind the gaps between them.":
        "сравните знаменатель с диапазонами пособия §14 — и учтите промежутки между ними.",
    "compare the largest side of every triangle with 0.3 mm (guide §7).":
        "сравните наибольшую сторону каждого треугольника с 0,3 мм (пособие §7).",
    "compare the level reading with 3°.": "сравните отсчёт по уровню с 3°.",
    "compare the mean error on the map v_d with 0.4 mm.": "сравните среднюю ошибку на карте v_d с 0,4 мм.",
    "compare the most negative ΔI with −0.5 mm (guide §6).": "сравните наименьшее (отрицательное) ΔI с −0,5 мм (пособие §6).",
    "compare the seven stages' errors on the ground; the relief stage replaces the DEM.":
        "сравните ошибки семи этапов на местности; этап рельефа заменяет ЦМР.",
    "compare the stands' tone, its evenness, and the crowns' shape and shadows.":
        "сравните тон насаждений, его равномерность, форму крон и тени.",
    "compare wet/dry band by band: where does water itself absorb most?":
        "сравните влажную/сухую по зонам: где сильнее всего поглощает сама вода?",
    "compare your number of unknowns with the limit in table 2": "сравните своё число неизвестных с пределом в таблице 2",
    "compare |Δm/m| with 3 %.": "сравните |Δm/m| с 3 %.",
    "compare |Δγ| with the tolerance ρ″·(0.1 mm · M)/S_PD": "сравните |Δγ| с допуском ρ″·(0,1 мм · M)/S_PD",
    "compare |φ| with the limit for your f.": "сравните |φ| с допуском для вашего f.",
    "look at the islands' ends and at how the tributary meets the river.":
        "посмотрите на концы островов и на то, как приток впадает в реку.",
}

_NEW_SLIPS = {  # issue 27: hints of the slips the grading table catalogues
    "that uses the nominal flying height H = f·m; the stations' height comes from A's own parallax: Z_S = Z_A + B·f/p_A":
        "здесь взята номинальная высота полёта H = f·m; высота центров проекции следует из собственного параллакса "
        "A: Z_S = Z_A + B·f/p_A",
    "that is the nominal flying height f·m itself; the stations' height is Z_S = Z_A + B·f/p_A":
        "это сама номинальная высота полёта f·m; высота центров проекции Z_S = Z_A + B·f/p_A",
    "that is the small form b₀·h/H; with your H the exact b₀·h/(H − h) differs by more than the tolerance":
        "это упрощённая формула b₀·h/H; при вашем H точная b₀·h/(H − h) отличается больше допуска",
    "the residuals are already on the base: do not multiply them by K_t again":
        "остаточные расхождения уже на основе: не умножайте их ещё раз на K_t",
    "that is the guide's example base b = 60 mm; your b = l·(100 − p_x)/100 with your p_x":
        "это базис примера пособия b = 60 мм; ваш b = l·(100 − p_x)/100 с вашим p_x",
    "that is the large-n form d·√(n³/3); (10.20) sums the squares exactly: d·√(n(n + 1)(2n + 1)/6)":
        "это форма для больших n, d·√(n³/3); (10.20) суммирует квадраты точно: d·√(n(n + 1)(2n + 1)/6)",
    "that is the photo the rejected measurement is on; the task asks for the point's id":
        "это снимок, на котором отбраковано измерение; задание спрашивает номер точки",
    "that is the index of the observation (its row); the task asks for the point's id":
        "это порядковый номер измерения (его строка); задание спрашивает номер точки",
    "that is the point's index in meas.point_ids; the task asks for the id itself":
        "это позиция точки в meas.point_ids; задание спрашивает сам номер точки",
    "that is the rejected control point; blunder_point is the point of the rejected image measurement":
        "это отбракованная опорная точка; blunder_point — точка отбракованного измерения на снимке",
    "that is the point of the rejected image measurement; bad_control is the rejected control point":
        "это точка отбракованного измерения на снимке; bad_control — отбракованная опорная точка",
    "that is the RMS per coordinate, √(mean(dX² + dY²)/2); the plan error combines both: √(mean(dX² + dY²))":
        "это СКО на одну координату, √(mean(dX² + dY²)/2); ошибка в плане объединяет обе: √(mean(dX² + dY²))",
    "that is V_X + V_Y; the plan error combines the axes in squares: √(V_X² + V_Y²)":
        "это V_X + V_Y; ошибка в плане складывает оси квадратично: √(V_X² + V_Y²)",
    "that is √2·V_X; V_D takes both axes, √(V_X² + V_Y²)": "это √2·V_X; V_D берёт обе оси, √(V_X² + V_Y²)",
    "that is m_x,y, one coordinate; the plan error m_D = √2·m_x,y (formula 8)":
        "это m_x,y, одна координата; ошибка в плане m_D = √2·m_x,y (формула 8)",
    "rows are counted from 0 at side 1–2 towards side 4–3": "ряды считаются от 0 у стороны 1–2 к стороне 4–3",
    "columns are counted from 0 at side 1–4 towards side 2–3": "столбцы считаются от 0 у стороны 1–4 к стороне 2–3",
    "count the classes present on the map: np.unique(patch.soil_map); a class of a few cells counts":
        "сосчитайте классы, которые есть на карте: np.unique(patch.soil_map); класс из нескольких ячеек тоже считается",
    "give the id of the rejected image measurement's point, from the rejected table's 'point' column (not a count, not a photo)":
        "укажите номер точки отбракованного измерения на снимке из столбца 'point' таблицы отбраковки (не количество, "
        "не снимок)",
    "give the id of the rejected control point, from the rejected table's 'point' column":
        "укажите номер отбракованной опорной точки из столбца 'point' таблицы отбраковки",
}

_NEW_SLIPS["that is your photos' design scale 1:m; the fotoschema's scale comes from your bases: m_i = L_i·M/l_i"] = (
    "это расчётный масштаб снимков 1:m; масштаб фотосхемы следует из ваших базисов: m_i = L_i·M/l_i")

_QUANTITIES = {  # Task.quantities: the chapter's other quantities a wrong answer may be
    "the base b₀ = B·f/H of your pair, mm": "базис b₀ = B·f/H вашей пары, мм",
    "B/H = b₀/f (not yet divided by e/d)": "B/H = b₀/f (ещё не делённое на e/d)",
    "the relief h = Z_max − Z_min, m": "перепад рельефа h = Z_max − Z_min, м",
}

_READINGS = {  # Task.accepted: the other readings of the articles, accepted
    "article 001's other reading, m_D = √2·m_X": "другое прочтение статьи 001, m_D = √2·m_X",
    "article 000's other reading of “zr”, 2r": "другое прочтение «zr» в статье 000, 2r",
    "article 003's own reading: the transfer 0.357 mm": "прочтение самой статьи 003: перенос 0,357 мм",
}

_HIDDEN = {  # the hidden checks' names, shown when the student's answers do not agree with each other
    "on_mm from your oc_mm": "on_mm по вашему oc_mm",
    "Bx_km from Px_percent": "Bx_km по Px_percent",
    "N = n·K": "N = n·K",
    "TS_h from LS_km": "TS_h по LS_km",
    "alpha_read_deg (30′ steps)": "alpha_read_deg (шаг 30′)",
    "l_сн from your x, y": "l_сн по вашим x, y",
    "m_i from your l_пл and l_сн": "m_i по вашим l_пл и l_сн",
    "m_част from your m_i": "m_част по вашим m_i",
    "m_cp from your m_част": "m_cp по вашим m_част",
    "Δm/m_cp from your m_част and m_cp": "Δm/m_cp по вашим m_част и m_cp",
    "δh from your r, H and Z_cp": "δh по вашим r, H и Z_cp",
    "n_corr from your δh": "n_corr по вашим δh",
    "m_i·l_сн/M gives the plan lengths": "m_i·l_сн/M даёт длины на плане",
    "|oc| from your xc_mm, yc_mm": "|oc| по вашим xc_mm, yc_mm",
    "δα from your r_c and φ": "δα по вашим r_c и φ",
    "n_corr from your δα": "n_corr по вашим δα",
    "m_rms_mm from your ΔI": "m_rms_mm по вашим ΔI",
    "n_cutouts from your ΔI": "n_cutouts по вашим ΔI",
    "seams_ok from your ΔI": "seams_ok по вашим ΔI",
    "m_i from your l and L": "m_i по вашим l и L",
    "m_mean (mean of your m_i)": "m_mean (среднее ваших m_i)",
    "triangles_ok from your sides": "triangles_ok по вашим сторонам",
    "k from your lengths": "k по вашим длинам",
    "k_mean is the mean of your k_bases": "k_mean — среднее ваших k_bases",
    "spread_ok from your k_bases": "spread_ok по вашим k_bases",
    "dk_max from your k_bases": "dk_max по вашим k_bases",
    "v_mm = r·(k − 1) with your r and one k": "v_mm = r·(k − 1) по вашим r и одному k",
    "ZS_m from your own pA_mm": "ZS_m по вашему pA_mm",
    "dhA_m from your own Δp": "dhA_m по вашему Δp",
    "dhB_m from your own Δp": "dhB_m по вашему Δp",
    "dhC_m from your own Δp": "dhC_m по вашему Δp",
    "dhD_m from your own Δp": "dhD_m по вашему Δp",
    "dp_relief_mm and V from one base": "dp_relief_mm и V по одному базису",
    "the plan point lies in row `row` of the plan grid": "точка плана лежит в ряду `row` сетки плана",
    "the plan point lies in column `col` of the plan grid": "точка плана лежит в столбце `col` сетки плана",
    "road_m from your own vertices": "road_m по вашим вершинам",
    "alpha_PA_deg from your own station": "alpha_PA_deg по вашей станции",
    "dgamma_arcsec from your own gamma_calc_deg": "dgamma_arcsec по вашему gamma_calc_deg",
    "check_ok from your own dgamma_arcsec and tol_arcsec": "check_ok по вашим dgamma_arcsec и tol_arcsec",
    "t_mm from your own K_d": "t_mm по вашему K_d",
    "rect_ok from your own d1_mm, d2_mm": "rect_ok по вашим d1_mm, d2_mm",
    "n_max follows from m3_mm": "n_max следует из m3_mm",
    "the named classes get smaller with the scale": "названные классы мельчают вместе с масштабом",
    "wet is darker than dry at 1.45 µm": "влажная почва темнее сухой на 1,45 мкм",
    "agreement at least the commonest soil's share": "совпадение не меньше доли самой частой почвы",
    "n_plan follows from mD_mm": "n_plan следует из mD_mm",
    "n_height follows from mZ_m": "n_height следует из mZ_m",
    "m20_mm follows from d_mm": "m20_mm следует из d_mm",
    "fits_1986 agrees with n_unknowns": "fits_1986 согласуется с n_unknowns",
    "rms_plan_m is of the size the block's precision allows": "rms_plan_m такой величины, какую допускает точность блока",
    "rms_Z_m is of the size the block's precision allows": "rms_Z_m такой величины, какую допускает точность блока",
    "the point lies where the ground truth is": "точка лежит там, где она на самом деле",
    "mz_m from your H and b": "mz_m по вашим H и b",
    "h_m from your m_z": "h_m по вашему m_z",
    "share_pct is a count of the 40 points": "share_pct — доля из 40 точек",
    "v_lines_m / m_lines_m between 0.5 and 1": "v_lines_m / m_lines_m между 0,5 и 1",
    "VD_m from your V_X, V_Y": "VD_m по вашим V_X, V_Y",
    "md_mm from your m_D": "md_mm по вашему m_D",
    "mxy_m from your σ": "mxy_m по вашему σ",
    "mphi_m from your m_x,y": "mphi_m по вашему m_x,y",
    "vd_mm from your m_D": "vd_mm по вашему m_D",
    "ok from your v_d": "ok по вашему v_d",
    "hidden checks": "скрытые проверки",
}

#: English → Russian
MESSAGES = {**_SLIPS, **_VERDICT_HINTS, **_NEW_SLIPS, **_QUANTITIES, **_READINGS, **_HIDDEN}
