"""The demos' live texts in Russian: titles, notes and labels that carry the current numbers (set on every update).

Keys are the English templates the demos format with ``t(template, **values)``; both languages carry the same
``str.format`` fields.  Also the short words such templates take as values (a layout, a step of the
transformer's sequence, a verdict).
"""

from __future__ import annotations

__all__ = ["MESSAGES"]

_TEMPLATES = {
    "{n} strips, control rows every {every} bases ({layout}), σ = {sigma:g} µm":
        "маршрутов: {n}, шаг рядов опоры (в базисах): {every} ({layout}), σ = {sigma:g} мкм",
    "{n} strip, control rows every {every} bases ({layout}), σ = {sigma:g} µm":
        "маршрутов: {n}, шаг рядов опоры (в базисах): {every} ({layout}), σ = {sigma:g} мкм",
    "Resection: three known points, two angles (scatter ×{k})":
        "Обратная засечка: три известные точки, два угла (разброс ×{k})",
    "h = {h} m: RMS of contour heights {rms} m ({n} nodes)":
        "h = {h} м: СКО высот горизонталей {rms} м (узлов: {n})",
    "colour: DEM − true height, −{lim} m": "цвет: ЦМР − истинная высота, −{lim} м",
    "+{lim} m (red: DEM too high)": "+{lim} м (красный: ЦМР выше истины)",
    "{step}: {name} (cycle {cycle})": "{step}: {name} (цикл {cycle})",
    "Rough mosaic (накидной монтаж): all criteria met": "Накидной монтаж: все критерии выполнены",
    "Rough mosaic (накидной монтаж): checks failed: {n}": "Накидной монтаж: не выполнено проверок: {n}",
    "The principal plane W (α = {a}°, exaggerated)": "Главная плоскость W (α = {a}°, в увеличенном виде)",
    "Correction sheet (корректурный лист): ΔI in mm along each cut · m = {rms} mm, n = {n}":
        "Корректурный лист: ΔI в мм вдоль каждого пореза · m = {rms} мм, n = {n}",
    "Your fotoschema: photos {a}–{b}, f = {f} mm, photos at {scale}":
        "Ваша фотосхема: снимки {a}–{b}, f = {f} мм, снимки в масштабе {scale}",
    "{done} of {total}": "{done} из {total}",
    "{stage} ({share} % of the variance)": "{stage} ({share} % дисперсии)",
    "RMS scatter for σβ = {s}″": "СКО разброса при σβ = {s}″",
    "{blur} mm = {px} px": "{blur} мм = {px} пикс.",
    "Photo, mm — {what} displacement, arrows ×{k}": "Снимок, мм — смещение за {what}, стрелки ×{k}",
    "1:{mk} map, 1:{mc} photos\nv_d = {v:.2f} mm {verdict}": "карта 1:{mk}, снимки 1:{mc}\nv_d = {v:.2f} мм {verdict}",
    "footprint l·m = {s:.2f} km": "охват l·m = {s:.2f} км",
    "drawn route {L:.0f} km (LS {LS:.0f} km)": "построенный маршрут {L:.0f} км (LS {LS:.0f} км)",
    "1 in {st} strips": "каждый {st}-й маршрут",
    "1 in {st} photos": "каждый {st}-й снимок",
    "\n(schematic: {what} drawn)": "\n(схематично: показан {what})",
    "K = {K} strips × n = {n} = N = {N} photos{shown}": "K = {K} маршрутов × n = {n} = N = {N} снимков{shown}",
    "Fotoschema 1:{m} · m = {rms} mm · {verdict}": "Фотосхема 1:{m} · m = {rms} мм · {verdict}",
    "cut {a}/{b}": "порез {a}/{b}",
    "H = f·m = {H} m above the mean ground": "H = f·m = {H} м над средней плоскостью",
    "ΔI from truth: the ground each neighbour shows at a point of the cut, along the strip":
        "ΔI по истине: местность, которую каждый соседний снимок показывает в точке пореза, вдоль маршрута",
    "= {name}, cycle {cycle}": "= {name}, цикл {cycle}",
    "Step {step}: {name} — misses ×{k}, largest {largest} mm":
        "Шаг {step}: {name} — невязки ×{k}, наибольшая {largest} мм",
    "triangles ×{k:g}": "треугольники ×{k:g}",
    "{triangles}; arrows ×{x:g}; k = {k:.4f}": "{triangles}; стрелки ×{x:g}; k = {k:.4f}",
    "Free strip, {n} templates; centre {centre}": "Свободный маршрут, восковок: {n}; центр {centre}",
    "Patch: {bands} as RGB": "Участок: {bands} как RGB",
    "{area}: p = {p} mm": "{area}: p = {p} мм",
}

_WORDS = {
    "rows": "ряды",
    "perimeter": "периметр",
    "relief": "рельеф",
    "tilt": "наклон",
    "≤ 0.4 mm: meets": "≤ 0,4 мм: допуск выполнен",
    "> 0.4 mm: fails": "> 0,4 мм: допуск не выполнен",
    " and ": " и ",
    "seams pass": "порезы в допуске",
    "cut-out > 0.5 mm": "вырез > 0,5 мм",
    # the photo transformer's sequence (aerophoto.rectify)
    "start": "начало",
    "centre": "центрирование",
    "scale": "масштаб",
    "turn": "поворот",
    "tilt the screen": "наклон экрана",
    " — reverse stereo": " — обратный стереоэффект",
    "  (flattened)": "  (уплощена)",
    # the reduction explorer's summary (aerophoto.triangulation: ReductionResult.summary)
    "mean reduction coefficient k": "средний коэффициент редуцирования k",
    "largest |Δk| (spread)": "наибольшее |Δk| (разброс)",
    "bases within tolerance": "базисов в допуске",
    "largest error-triangle side": "наибольшая сторона треугольника погрешностей",
    "largest control residual": "наибольший остаток на опорной точке",
    "RMS error, orienting points and centres": "СКО, ориентирующие точки и центры",
    "largest correction v": "наибольшая поправка v",
    "k = l_base / l_template": "k = l_осн / l_воск",
}

#: English → Russian
MESSAGES = {**_TEMPLATES, **_WORDS}
