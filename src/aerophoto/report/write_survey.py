"""Sections 1 and 2 of the note: the survey's parameters (guide §2, chapter 01) and the photos' quality (§3, chapter 02).

Each writer takes the section's :class:`~aerophoto.report.prose.Writer` and the chapter's tasks
(:class:`~aerophoto.report.prose.TaskView` by id) and writes what the student did: the formulas with their own
numbers, the guide's table, the figure and a conclusion drawn from their values.  ``EXTRACT`` reduces a task's
inputs to the plain numbers the note prints (never a reference answer).
"""

from __future__ import annotations

import math

from .prose import ru_plural as _pl

__all__ = ["write_01", "write_02", "EXTRACT"]

#: the guide's shutter speeds, s (§3: from 1/40 to 1/1000, in steps of two: "1/125, 1/250, 1/500")
_SHUTTER = (1 / 40, 1 / 125, 1 / 250, 1 / 500, 1 / 1000)


def _strip_measurements(raw, v) -> dict:
    return {k: float(raw[k]) for k in ("a_mm", "b_mm", "b1_mm", "b2_mm", "L_mm", "l_mm", "crab_deg", "bubble_div",
                                       "f_mm", "H_m")}


EXTRACT = {"task-02-1": _strip_measurements, "task-02-2": _strip_measurements}


# =========================================================================== section 1: chapter 01
def write_01(w, T: dict) -> None:
    v = w.v
    t1, t2, t3 = T.get("task-01-1"), T.get("task-01-2"), T.get("task-01-3")
    w.par("В разделе по исходным данным варианта рассчитываются параметры аэрофотосъёмки участка: высота "
          "фотографирования, продольное и поперечное перекрытия с поправкой за рельеф, базис фотографирования и "
          "расстояние между маршрутами, число маршрутов и снимков, длина маршрутов и время съёмки, допустимая "
          "выдержка и интервал фотографирования (пособие, §2). От них зависят объём лётных работ и пригодность "
          "снимков для фотограмметрической обработки.",
          "This section computes the survey's parameters from the variant's inputs: flying height, forward and side "
          "overlaps with the relief allowance, photo base and strip spacing, the numbers of strips and photos, the "
          "route length and flying time, the longest exposure and the interval between exposures (guide §2).")
    S = v.Lx_km * v.Ly_km
    if w.step(t1, "Высота фотографирования и перекрытия", "Flying height and overlaps"):
        H, Px = t1.number("H_m"), t1.number("Px_percent")
        w.par("Площадь участка съёмки равна произведению его размеров по параллели и меридиану:",
              "The area is the product of its sides along the parallel and the meridian:")
        w.eq('S = L_x dot L_y = {Lx} dot {Ly} = {S} " км"^2', Lx=w.n(v.Lx_km, 0), Ly=w.n(v.Ly_km, 0), S=w.n(S, 0))
        w.par("Высота фотографирования над средней плоскостью участка определяется фокусным расстоянием камеры и "
              "знаменателем масштаба съёмки:", "The flying height follows from the focal length and the scale:")
        if H is not None:
            w.eq('H = f dot m = {f} dot {m} = {H} " м"', f=w.n(v.f_mm / 1000, 3), m=w.n(v.m, 0), H=w.n(H, 0))
            w.where([("f", "фокусное расстояние аэрофотоаппарата, м", "focal length, m"),
                     ("m", "знаменатель масштаба аэрофотосъёмки", "scale denominator")])
        h = v.Zmax_m - v.Zmin_m
        w.par("Чтобы перекрытия не стали меньше нормативных на возвышенных частях участка, к ним прибавляется "
              "поправка за рельеф 40·h/H, где h — разность высот на участке:",
              "The overlaps get the relief allowance 40·h/H so that they stay normative on the highest ground:")
        w.eq('h = Z_"max" - Z_"min" = {a} - {b} = {h} " м"', a=w.n(v.Zmax_m, 0), b=w.n(v.Zmin_m, 0), h=w.n(h, 0))
        if H is not None and Px is not None:
            Py = v.py_percent + 40 * h / H
            w.eq('P_x = p_x + 40 h/H = {px} + 40 dot {h}/{H} = {Px} " %"', px=w.n(v.px_percent, 0), h=w.n(h, 0),
                 H=w.n(H, 0), Px=w.n(Px, 1))
            w.eq('P_y = p_y + 40 h/H = {py} + 40 dot {h}/{H} = {Py} " %"', py=w.n(v.py_percent, 0), h=w.n(h, 0),
                 H=w.n(H, 0), Py=w.n(Py, 1))
            bx = v.frame_mm / 10 * (100 - Px) / 100
            by = v.frame_mm / 10 * (100 - Py) / 100
            w.par("Стороны рабочей площади снимка и их проекции на местность — базис фотографирования и расстояние "
                  "между маршрутами:", "The working area's sides on the photo and on the ground:")
            w.eq('b_x = l(100 - P_x)/100 = {l} dot ({c} - {Px})/100 = {bx} " см"', l=w.n(v.frame_mm / 10, 0),
                 c="100", Px=w.n(Px, 1), bx=w.n(bx, 2))
            w.eq('b_y = l(100 - P_y)/100 = {l} dot ({c} - {Py})/100 = {by} " см"', l=w.n(v.frame_mm / 10, 0),
                 c="100", Py=w.n(Py, 1), by=w.n(by, 2))
        Bx, By = t1.number("Bx_km"), t1.number("By_km")
        if Bx is not None and By is not None and Px is not None:
            w.eq('B_x = b_x dot m = {bx} " см" dot {m} = {Bx} " км"', bx=w.n(bx, 2), m=w.n(v.m, 0), Bx=w.n(Bx, 3))
            w.eq('B_y = b_y dot m = {by} " см" dot {m} = {By} " км"', by=w.n(by, 2), m=w.n(v.m, 0), By=w.n(By, 3))
        w.check_note(t1)
    if w.step(t2, "Число маршрутов и снимков", "Strips and photos"):
        K, n, N = t2.number("K"), t2.number("n"), t2.number("N")
        By = t1.number("By_km") if t1 is not None else None
        Bx = t1.number("Bx_km") if t1 is not None else None
        w.par("Число маршрутов и число снимков в маршруте округляются в большую сторону, чтобы участок был покрыт "
              "полностью:", "Strips and photos per strip are rounded up so that the whole area is covered:")
        if K is not None and By:
            w.eq('K = L_y/B_y + 1 = {Ly}/{By} + 1 = {Kr} arrow K = {K}', Ly=w.n(v.Ly_km, 0), By=w.n(By, 3),
                 Kr=w.n(v.Ly_km / By + 1, 2), K=w.count(K))
        if n is not None and Bx:
            w.eq('n = L_x/B_x + 1 = {Lx}/{Bx} + 1 = {nr} arrow n = {n}', Lx=w.n(v.Lx_km, 0), Bx=w.n(Bx, 3),
                 nr=w.n(v.Lx_km / Bx + 1, 2), n=w.count(n))
        if N is not None and K is not None and n is not None:
            w.eq('N = n dot K = {n} dot {K} = {N}', n=w.count(n), K=w.count(K), N=w.count(N))
        w.check_note(t2)
    if w.step(t3, "Длина маршрутов, время съёмки, выдержка и интервал", "Route, time, exposure and interval"):
        LS, TS, tmax, tau = (t3.number(k) for k in ("LS_km", "TS_h", "tmax_s", "tau_s"))
        By = t1.number("By_km") if t1 is not None else None
        Bx = t1.number("Bx_km") if t1 is not None else None
        w.par("Длина пути самолёта включает заходы на маршруты (множитель 1,2), время съёмки — частное от деления "
              "пути на скорость; допустимая выдержка ограничена смазом изображения δ ≤ 0,1 мм на фотоплане, "
              "интервал фотографирования — время пролёта базиса:",
              "The route includes the turns (factor 1.2); the exposure is limited by a blur of 0.1 mm on the "
              "photoplan; the interval is the time to fly one base:")
        if LS is not None and By:
            w.eq('L_S = 1","2 S/B_y = 1","2 dot {S}/{By} = {LS} " км"', S=w.n(S, 0), By=w.n(By, 3), LS=w.n(LS, 0))
        if TS is not None and LS is not None:
            w.eq('T_S = L_S/W = {LS}/{W} = {TS} " ч"', LS=w.n(LS, 0), W=w.n(v.W_kmh, 0), TS=w.n(TS, 2))
        if tmax is not None:
            w.eq('t_"max" = (delta M)/W = ({d} " м" dot {M})/({Wms} " м/с") = {t} " с"', d=w.n(0.0001, 4),
                 M=w.n(v.M, 0), Wms=w.n(v.W_kmh / 3.6, 1), t=w.n(tmax, sig=2))
        if tau is not None and Bx:
            w.eq('tau = B_x/W = ({Bx} dot {c})/{W} = {tau} " с"', Bx=w.n(Bx, 3), c="3600", W=w.n(v.W_kmh, 0),
                 tau=w.n(tau, 1))
        w.check_note(t3)
    w.figure("flight_plan", f"Схема аэрофотосъёмки участка {w.n(v.Lx_km, 0)} × {w.n(v.Ly_km, 0)} км: маршруты, "
             "центры и контуры снимков; справа — фрагмент с рабочими площадями",
             f"The survey plan of the {w.n(v.Lx_km, 0)} × {w.n(v.Ly_km, 0)} km area: strips, photo centres and "
             "footprints; right: a corner with the working areas")
    _conclusion_01(w, t1, t2, t3, S)


def _conclusion_01(w, t1, t2, t3, S) -> None:
    done = [t for t in (t1, t2, t3) if t is not None and t.attempted]
    if not done:
        return
    v = w.v
    parts_ru, parts_en = [], []
    H = t1.number("H_m") if t1 is not None else None
    if H is not None:
        parts_ru.append(f"съёмка участка площадью {w.n(S, 0)} км² камерой с f = {w.n(v.f_mm, 0)} мм в масштабе "
                        f"{w.scale(v.m)} выполняется с высоты {w.n(H, 0)} м")
        parts_en.append(f"the {w.n(S, 0)} km² area is photographed with f = {w.n(v.f_mm, 0)} mm at {w.scale(v.m)} "
                        f"from {w.n(H, 0)} m")
    if t2 is not None and t2.number("N") is not None and t2.number("K") is not None:
        K, n, N = (int(t2.number(k) or 0) for k in ("K", "n", "N"))
        parts_ru.append(f"потребуется {w.count(K)} {_pl(K, 'маршрут', 'маршрута', 'маршрутов')} по {w.count(n)} "
                        f"{_pl(n, 'снимку', 'снимка', 'снимков')}, всего {w.count(N)} "
                        f"{_pl(N, 'аэронегатив', 'аэронегатива', 'аэронегативов')}")
        parts_en.append(f"{K} strips of {n} photos, {N} negatives in all")
    if t3 is not None and t3.number("TS_h") is not None:
        parts_ru.append(f"расчётное время съёмки {w.n(t3.number('TS_h'), 1)} ч")
        parts_en.append(f"{w.n(t3.number('TS_h'), 1)} h of flying")
    tmax = t3.number("tmax_s") if t3 is not None else None
    shutter = ""
    if tmax is not None and tmax > 0:
        ok = [s for s in _SHUTTER if s <= tmax]
        shutter = (f" Выдержка не должна превышать {w.n(tmax, sig=2)} с; из ряда выдержек затвора подходит "
                   f"1/{round(1 / ok[0])} с и короче." if ok else
                   f" Допустимая выдержка {w.n(tmax, sig=2)} с короче 1/1000 с — нужна камера с компенсацией сдвига "
                   "изображения.")
    ru = "; ".join(parts_ru) + "." + shutter
    w.conclusion(ru[0].upper() + ru[1:], "; ".join(parts_en) + ".")



# =========================================================================== section 2: chapter 02
def write_02(w, T: dict) -> None:
    t1, t2 = T.get("task-02-1"), T.get("task-02-2")
    w.par("Фотограмметрическое качество материалов оценивается на накидном монтаже маршрута из пяти снимков: "
          "продольное перекрытие, разномасштабность смежных снимков, прямолинейность маршрута, отклонение сторон "
          "снимка от направления маршрута и углы наклона снимков сравниваются с допусками пособия (§3). "
          "Фотографическое качество (резкость, проработка деталей, дефекты) для снимков виртуального полигона не "
          "оценивалось: они получены расчётом без фотохимической обработки.",
          "The photogrammetric quality is judged on the rough mosaic of a strip of five photos: forward overlap, "
          "scale difference, straightness, crab and tilt against the tolerances of guide §3.")
    src = t1 if t1 is not None and t1.inputs else t2
    d = src.inputs if src is not None else {}
    if not (t1 and t1.attempted) and not (t2 and t2.attempted):
        for t in (t1, t2):
            if t is not None:
                w.not_done(t)
        return
    if d:
        rows = [["a", w.L("ширина продольного перекрытия снимков 1–2", "overlap of photos 1–2"), w.n(d["a_mm"], 1)],
                ["b", w.L("сторона снимка", "frame side"), w.n(d["b_mm"], 1)],
                [{"math": "b_1"}, w.L("базис снимков 2–3 на снимке 2", "base 2–3 on photo 2"), w.n(d["b1_mm"], 1)],
                [{"math": "b_2"}, w.L("тот же базис на снимке 3", "the same base on photo 3"), w.n(d["b2_mm"], 1)],
                ["L", w.L("расстояние между главными точками крайних снимков", "first to last principal point"),
                 w.n(d["L_mm"], 1)],
                ["l", w.L("уклонение главной точки среднего снимка от прямой L", "deviation of the middle photo"),
                 w.n(d["l_mm"], 1)]]
        w.table("Измерения на накидном монтаже маршрута, мм", "Measurements on the rough mosaic, mm",
                [[w.L("Обозначение", "Symbol"), w.L("Что измерено", "What"), w.L("Значение, мм", "Value, mm")]],
                rows, widths=[1.2, 5, 1.6], align=["center", "left", "right"])
    if w.step(t1, "Перекрытие, разномасштабность и прямолинейность", "Overlap, scale difference and straightness"):
        Px, dm, n = (t1.number(k) for k in ("Px_percent", "dm_percent", "n_percent"))
        if Px is not None and d:
            w.eq('P_x = a/b dot 100 " %" = {a}/{b} dot 100 = {Px} " %"', a=w.n(d["a_mm"], 1), b=w.n(d["b_mm"], 0),
                 Px=w.n(Px, 1))
        if dm is not None and d:
            w.eq('(Delta m)/m = (b_1 - b_2)/b_1 dot 100 " %" = ({b1} - {b2})/{b1} dot 100 = {dm} " %"',
                 b1=w.n(d["b1_mm"], 1), b2=w.n(d["b2_mm"], 1), dm=w.n(dm, 2))
        if n is not None and d:
            w.eq('n = l/L dot 100 " %" = {l}/{L} dot 100 = {n} " %"', l=w.n(d["l_mm"], 1), L=w.n(d["L_mm"], 1),
                 n=w.n(n, 2))
        w.check_note(t1)
    if w.step(t2, "Отклонение от направления маршрута и наклон снимков", "Crab and tilt"):
        lim, alpha = t2.number("crab_limit_deg"), t2.number("alpha_read_deg")
        if d:
            w.par(f"Угол отклонения базиса от направления маршрута, измеренный транспортиром на снимке 2, φ = "
                  f"{w.n(d['crab_deg'], 1)}°; допуск для f = {w.n(d['f_mm'], 0)} мм — {w.n(lim, 0) if lim is not None else '—'}° "
                  f"(пособие даёт 5°, 7° и 10° для f = 100, 140 и 200 мм, для более длиннофокусных камер принят "
                  "наибольший допуск). Пузырёк круглого уровня на снимке 3 смещён на "
                  f"{w.n(d['bubble_div'], 1)} деления; при цене деления 30′ и отсчёте до целого деления угол наклона "
                  f"α = {w.n(alpha, 1) if alpha is not None else '—'}°.",
                  f"The crab measured on photo 2 is {w.n(d['crab_deg'], 1)}°, the limit for f = {w.n(d['f_mm'], 0)} mm "
                  f"is {w.n(lim, 0) if lim is not None else '—'}°; the level reads α = "
                  f"{w.n(alpha, 1) if alpha is not None else '—'}°.")
        w.check_note(t2)
    _table_1(w, t1, t2, d)
    w.figure("rough_mosaic", "Накидной монтаж маршрута: контуры снимков, главные точки, базисы и линия маршрута "
             "(элементы вне допуска выделены)", "The rough mosaic of the strip: frames, principal points, bases, "
             "strip line (out of tolerance highlighted)")
    w.figure("crab_limit", f"Допустимое отклонение от направления маршрута в зависимости от фокусного расстояния; "
             f"ромбом отмечена камера варианта, f = {w.n(w.v.f_mm, 0)} мм",
             f"The crab limit against the focal length; the variant's camera, f = {w.n(w.v.f_mm, 0)} mm, marked")
    _conclusion_02(w, t1, t2)


def _table_1(w, t1, t2, d) -> None:
    """Table 1 of the guide, for the photogrammetric indicators the student measured and judged."""
    if d is None or not d:
        return
    rows = []
    yes = lambda ok: w.L("удовл.", "yes") if ok else w.L("брак", "no")  # noqa: E731
    H = d.get("H_m", 0.0)
    items = [("Px_percent", "px_ok", w.L("Продольное перекрытие P_x, %", "Forward overlap P_x, %"), "≥ 56", 1),
             ("dm_percent", "dm_ok", w.L("Разномасштабность Δm/m, %", "Scale difference Δm/m, %"), "≤ 3", 2),
             ("n_percent", "n_ok", w.L("Непрямолинейность n, %", "Straightness n, %"), "≤ 2" if H > 750 else "≤ 3", 2),
             ("crab_deg", "crab_ok", w.L("Отклонение от маршрута φ, °", "Crab φ, °"), None, 1),
             ("alpha_read_deg", "tilt_ok", w.L("Угол наклона α, °", "Tilt α, °"), "≤ 3", 1)]
    for key, flag, label, tol, dec in items:
        if key == "crab_deg":
            val = d.get("crab_deg")
            lim = t2.number("crab_limit_deg") if t2 is not None else None
            tol = f"≤ {w.n(lim, 0)}" if lim is not None else "—"
        else:
            src = t1 if key in ("Px_percent", "dm_percent", "n_percent") else t2
            val = src.number(key) if src is not None else None
        verdict = t2.flag(flag) if t2 is not None else None
        rows.append([label, "—" if val is None else w.n(val, dec), tol,
                     "—" if verdict is None else yes(verdict)])
    w.table("Оценка качества материалов аэрофотосъёмки (фотограмметрические показатели маршрута)",
            "Quality of the photos (photogrammetric indicators of the strip)",
            [[w.L("Показатель", "Indicator"), w.L("Значение", "Value"), w.L("Допуск", "Tolerance"),
              w.L("Оценка", "Verdict")]], rows, label="1", widths=[4, 1.4, 1.4, 1.4],
            align=["left", "right", "center", "center"])


def _conclusion_02(w, t1, t2) -> None:
    if t2 is None or not t2.attempted:
        if t1 is not None and t1.attempted and t1.number("Px_percent") is not None:
            Px = t1.number("Px_percent")
            w.conclusion(f"Продольное перекрытие {w.n(Px, 1)} % " + ("не ниже" if Px >= 56 else "ниже") +
                         " предельных 56 %; остальные показатели не оценены (задача 02.2 не выполнена).",
                         f"The forward overlap is {w.n(Px, 1)} %; the rest is not judged (task 02.2 not done).")
        return
    names = {"px_ok": ("продольному перекрытию", "the forward overlap"),
             "dm_ok": ("разномасштабности", "the scale difference"), "n_ok": ("прямолинейности", "straightness"),
             "crab_ok": ("отклонению от маршрута", "the crab"), "tilt_ok": ("углу наклона", "the tilt")}
    bad = [k for k in names if t2.flag(k) is False]
    good = [k for k in names if t2.flag(k) is True]
    if not bad and good:
        w.conclusion("Все фотограмметрические показатели маршрута в пределах допусков §3: материалы пригодны для "
                     "землеустроительных работ.", "Every indicator is within tolerance: the photos are fit for use.")
    elif bad:
        ru = ", ".join(names[k][0] for k in bad)
        en = ", ".join(names[k][1] for k in bad)
        extra = (" Снимки 1–2 бракуются: требуется повторный залёт с большим продольным перекрытием."
                 if "px_ok" in bad else "")
        w.conclusion(f"Материалы не удовлетворяют требованиям §3 по {ru}; по остальным показателям маршрут в "
                     f"пределах допусков.{extra}", f"The strip fails on {en}; the rest is within tolerance.")
