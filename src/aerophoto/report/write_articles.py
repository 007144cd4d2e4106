"""Sections 14–17 of the note: the four articles' chapters (14–17 of the book), written like the guide's sections.

Article 001 (accuracy of phototriangulation networks, formulas (10.20) and (10.21)), article 002 (photo control
of gravimetric points in the high mountains, bundle block adjustment), article 000 (contours from DEM points,
Lysenko's densification accuracy) and article 003 (the planimetric error budget of map updating, tables 1–5).
"""

from __future__ import annotations

import math

from .prose import ru_plural as _pl

__all__ = ["write_14", "write_15", "write_16", "write_17", "EXTRACT"]


def _survey(raw, v) -> dict:
    return {"m": float(raw.m), "M": float(raw.M), "f": float(raw.f_mm), "b": float(raw.b_mm), "mq": float(raw.mq_mm),
            "h": float(raw.contour_m)}


def _mc(raw, v) -> dict:
    return {"n": int(raw.n_bases), "b": float(raw.b_mm), "f": float(raw.f_mm)}


def _block(raw, v) -> dict:
    m = raw.meas
    kinds = [str(k) for k in m.point_kind]
    return {"photos": int(m.n_photos), "points": int(m.n_points), "control": kinds.count("control"),
            "check": kinds.count("check"), "field": kinds.count("field"), "tie": kinds.count("tie"), "m": float(raw.m)}


def _field_point(raw, v) -> dict:
    return {"point": int(raw["point"])}


def _lysenko(raw, v) -> dict:
    return {k: float(getattr(raw, k)) for k in ("f_mm", "m", "frame_mm", "px_percent", "strips", "per_strip", "n",
                                                 "points_per_photo", "images_per_point", "r", "mp_mm")}


def _checks(raw, v) -> dict:
    return {"n": int(len(raw))}


def _corner(raw, v) -> dict:
    return {"X": [float(x) for x in raw["X_m"]], "Y": [float(y) for y in raw["Y_m"]]}


def _case(raw, v) -> dict:
    return {k: float(getattr(raw, k)) for k in ("M_c", "M_k", "f_mm", "frame_mm", "P_um", "relief_m")}


EXTRACT = {"task-14-1": _survey, "task-14-2": _mc, "task-15-1": _block, "task-15-2": _block,
           "task-15-3": _field_point, "task-16-1": _lysenko, "task-16-2": _checks, "task-17-1": _corner,
           "task-17-2": _case, "task-17-3": _case}



# =========================================================================== chapter 14: article 001
def write_14(w, T: dict) -> None:
    t1, t2 = T.get("task-14-1"), T.get("task-14-2")
    w.par("Ошибки построения фототриангуляционной сети накапливаются от звена к звену: при одинаковой ошибке d "
          "каждого звена средняя квадратическая ошибка точки последнего звена свободного ряда растёт как "
          "d·√(Σk²) (формула (10.20) источника [3]). После внешнего ориентирования по опорным точкам на концах ряда "
          "наибольшая ошибка — в его середине; по ней (формула (10.21)) рассчитывается, через сколько базисов "
          "фотографирования нужны плановые и высотные опознаки для заданных масштабов и сечения рельефа.",
          "Errors accumulate along a strip as d·√(Σk²) (10.20); with control at both ends the middle is worst, and "
          "(10.21) gives the control spacing for the survey's scales and contour interval [3].")
    if w.step(t1, "Расстояние между опорными точками по формуле (10.21)", "Control spacing by (10.21)"):
        d = t1.inputs
        mD, mZ, npl, nh = (t1.number(k) for k in ("mD_mm", "mZ_m", "n_plan", "n_height"))
        if d and mD is not None:
            w.eq('m_D = sqrt(0","25^2 + 0","16^2) thin m_q sqrt(n^3), quad m_Z = 0","25 thin m_q f/b sqrt(n^3)')
            w.eq('m_D = {c} dot {mq} dot sqrt({n}^3) = {mD} " мм"', numbered=False, c=w.n(math.hypot(0.25, 0.16), 3),
                 mq=w.n(d["mq"], 3), n="10", mD=w.n(mD, 3))
        if d and mZ is not None:
            w.eq('m_Z = 0","25 dot {mq} dot {f}/{b} dot sqrt({n}^3) dot {m} = {mZ} " м"', numbered=False,
                 mq=w.n(d["mq"], 3), f=w.n(d["f"], 0), b=w.n(d["b"], 0), n="10", m=w.n(d["m"] / 1000, 1),
                 mZ=w.n(mZ, 2))
            w.par("(ошибка по высоте переведена из масштаба снимка в метры на местности множителем m/1000).",
                  "(the height error scaled from the photo to metres on the ground by m/1000).", "plain")
            w.where([("m_q", "средняя квадратическая ошибка измерения поперечного параллакса, мм",
                      "RMS error of a transverse parallax, mm"),
                     ("n", "число базисов фотографирования между опознаками (здесь 10)", "bases (here 10)")])
            w.par("Коэффициент плановой ошибки принят по легенде формулы (ошибка в плане $sqrt(m_X^2 + m_Y^2)$); "
                  "напечатанный в источнике пример $m_D$ = 0,11 мм соответствует иному прочтению, $sqrt(2) m_X$.",
                  "The plan coefficient follows the legend (√(m_X² + m_Y²)); the printed 0.11 mm reads √2·m_X.",
                  "note")
        if npl is not None and nh is not None and d:
            w.par(f"Допустимая ошибка планового сгущения — 0,3 мм в масштабе карты ({w.n(0.3 * d['M'] / d['m'], 3)} мм в "
                  f"масштабе снимка), высотного — половина средней квадратической ошибки высот карты при сечении "
                  f"{w.n(d['h'], 1)} м. Отсюда плановые опознаки нужны не реже чем через {w.count(npl)} "
                  f"{_pl(npl, 'базис', 'базиса', 'базисов')}, высотные — через {w.count(nh)}" +
                  (" (то есть на каждом базисе: даже один базис даёт ошибку больше допустимой)." if nh == 0 else "."),
                  f"Plan control every {int(npl)} bases, height control every {int(nh)}.")
        w.check_note(t1)
    if w.step(t2, "Закон накопления ошибок по моделированию", "The accumulation law from the simulation"):
        dd, m20, gain = (t2.number(k) for k in ("d_mm", "m20_mm", "gain"))
        if dd is not None and m20 is not None:
            w.par("По результатам моделирования свободного ряда подобрана ошибка звена d закона (10.20); по ней "
                  "предсказана ошибка в конце ряда из 20 звеньев:",
                  "The per-link error d fitted to the simulated free strip predicts the error after 20 links:")
            w.eq('m_20 = d sqrt(sum_(k=1)^20 k^2) = {d} dot sqrt({s}) = {m} " мм"', d=w.n(dd, 4), s="2870",
                 m=w.n(m20, 3))
        if gain is not None:
            w.par(f"Закрепление ряда опорными точками на обоих концах уменьшает наибольшую ошибку в {w.n(gain, 1)} "
                  "раза по сравнению с концом свободного ряда той же длины (12 базисов).",
                  f"Control at both ends cuts the largest error {w.n(gain, 1)} times (12 bases).")
        w.check_note(t2)
    w.figure("accumulation", "Накопление ошибок высот вдоль ряда: моделирование свободного ряда и ряда, закреплённого "
             "на концах, и законы источника", "Height errors along the strip: simulation and the article's laws")
    if t1 is not None and t1.number("n_plan") is not None:
        w.conclusion(f"Для съёмки варианта плановые опознаки размещаются через {w.count(t1.number('n_plan'))} "
                     f"{_pl(t1.number('n_plan'), 'базис', 'базиса', 'базисов')}" +
                     (", высотные — на каждом базисе." if t1.number("n_height") == 0 else
                      f", высотные — через {w.count(t1.number('n_height') or 0)}."),
                     "Control spacing found.")


# =========================================================================== chapter 15: article 002
def write_15(w, T: dict) -> None:
    t1, t2, t3 = T.get("task-15-1"), T.get("task-15-2"), T.get("task-15-3")
    w.par("Пункты гравиметрической съёмки в высокогорье трудно опознать по карте, а барометрическое нивелирование "
          "ненадёжно; источник [4] определяет их координаты по аэроснимкам уравниванием блока по методу связок. "
          "Для блока снимков варианта подсчитано число неизвестных уравнивания, найдены промахи измерений, оценена "
          "точность по контрольным точкам и определено положение гравиметрического пункта с эллипсом ошибок.",
          "Gravimetric points in the mountains are located by bundle block adjustment [4]: the block's size, its "
          "blunders, its accuracy and your point.")
    w.figure("block", "Блок снимков варианта: центры снимков, опорные, контрольные, связующие и определяемые точки",
             "Your block: photo centres, control, check, tie and field points")
    d = next((t.inputs for t in (t1, t2) if t is not None and t.inputs), {})
    if w.step(t1, "Размер блока", "The block's size"):
        n, fits = t1.number("n_unknowns"), t1.flag("fits_1986")
        if d and n is not None:
            w.eq('N = 6 n_"сн" + 3 n_"т" = 6 dot {p} + 3 dot {q} = {N}', p=w.count(d["photos"]), q=w.count(d["points"]),
                 N=w.count(n))
            w.par(f"Точек: опорных {w.count(d['control'])}, контрольных {w.count(d['check'])}, связующих "
                  f"{w.count(d['tie'])}, определяемых {w.count(d['field'])}. Программа 1986 г. (таблица 2 источника) "
                  "уравнивала не более 1000 неизвестных: блок " + ("укладывается в это ограничение." if fits else
                                                                  "в него не укладывается."),
                  f"{d['points']} points; the 1986 package {'could' if fits else 'could not'} adjust it.")
        w.check_note(t1)
    if w.step(t2, "Промахи и точность блока", "Blunders and accuracy"):
        bp, bc, rp, rz = (t2.number(k) for k in ("blunder_point", "bad_control", "rms_plan_m", "rms_Z_m"))
        if None not in (bp, bc, rp, rz):
            w.par(f"Поиск грубых ошибок по нормированным поправкам отбраковал измерение изображения точки {w.count(bp)} и опорную точку "
                  f"{w.count(bc)}. После повторного уравнивания средние квадратические ошибки по контрольным точкам: "
                  f"в плане {w.n(rp, 2)} м, по высоте {w.n(rz, 2)} м.",
                  f"Rejected: image of point {int(bp)}, control point {int(bc)}; RMS {w.n(rp, 2)} m plan, "
                  f"{w.n(rz, 2)} m height.")
        w.check_note(t2)
    if w.step(t3, "Положение гравиметрического пункта", "The gravimetric point"):
        X, Y, Z, a = (t3.number(k) for k in ("X_m", "Y_m", "Z_m", "a_m"))
        pid = t3.inputs.get("point")
        if None not in (X, Y, Z, a):
            w.par(f"Уравненные координаты пункта {w.count(pid) if pid else ''}: X = {w.n(X, 2)} м, Y = {w.n(Y, 2)} м, "
                  f"Z = {w.n(Z, 2)} м; большая полуось эллипса средних ошибок {w.n(a, 2)} м.",
                  f"X = {w.n(X, 2)}, Y = {w.n(Y, 2)}, Z = {w.n(Z, 2)} m; a = {w.n(a, 2)} m.")
        w.check_note(t3)
    if t2 is not None and t2.number("rms_Z_m") is not None:
        rz = t2.number("rms_Z_m")
        w.conclusion(f"Ошибка высот {w.n(rz, 2)} м соответствует {w.n(rz * 0.197, 2)} мГал при вертикальном градиенте "
                     "Буге 0,197 мГал/м — много меньше сечения изоаномал 2 мГал съёмки масштаба 1:200 000; "
                     "аэрофотопривязка заменяет барометрическое нивелирование.",
                     f"{w.n(rz, 2)} m is {w.n(rz * 0.197, 2)} mGal, far below the 2 mGal interval.")


# =========================================================================== chapter 16: article 000
def write_16(w, T: dict) -> None:
    t1, t2 = T.get("task-16-1"), T.get("task-16-2")
    w.par("Горизонтали крупномасштабного фотоплана для проектирования мелиоративных систем можно рисовать "
          "интерполированием по точкам цифровой модели рельефа, построенной блочной фототриангуляцией (источник "
          "[2]). Точность сгущения высот оценивается по формуле Лысенко; точность модели с регулярной сеткой и модели "
          "со структурными линиями сравнивается по контрольным точкам листа.",
          "Contours interpolated from a DEM densified by block triangulation: Lysenko's accuracy, and a regular "
          "grid against structural lines at the check points [2].")
    if w.step(t1, "Точность сгущения высот", "The densification's accuracy"):
        d = t1.inputs
        H, b, mz, h = (t1.number(k) for k in ("H_m", "b_mm", "mz_m", "h_m"))
        if H is not None:
            w.eq('H = f dot m = {f} dot {m} = {H} " м"', f=w.n(w.v.f_mm / 1000, 3), m=w.n(w.v.m, 0), H=w.n(H, 0))
        if b is not None and d:
            w.eq('b = l (1 - p_x/100) = {l} dot (1 - {p}/100) = {b} " мм"', l=w.n(d["frame_mm"], 0),
                 p=w.n(d["px_percent"], 0), b=w.n(b, 1))
        if mz is not None and d:
            w.par(f"Блок: {w.count(d['strips'])} маршрутов по {w.count(d['per_strip'])} снимков (n = {w.count(d['n'])}), "
                  f"{w.count(d['points_per_photo'])} точек на снимке, каждая на {w.count(d['images_per_point'])} "
                  f"снимках, {w.count(d['r'])} опорных точек; по формуле Лысенко $m_z$ = {w.n(mz, 2)} м.",
                  f"Lysenko's m_z = {w.n(mz, 2)} m for the block.")
        if h is not None and mz is not None:
            w.par(f"Наименьшее стандартное сечение рельефа, при котором $m_z$/1,25 ≤ 0,3·h: h = {w.n(h, 1)} м.",
                  f"The smallest standard contour interval: {w.n(h, 1)} m.")
        w.check_note(t1)
    if w.step(t2, "Точность цифровой модели по контрольным точкам", "The DEM at the check points"):
        mg, ml, vl, sh = (t2.number(k) for k in ("m_grid_m", "m_lines_m", "v_lines_m", "share_pct"))
        n = t2.inputs.get("n", 40)
        if None not in (mg, ml, vl, sh):
            rows = [[w.L("регулярная сетка", "regular grid"), w.n(mg, 3), "—", "—"],
                    [w.L("сетка и структурные линии", "grid and structural lines"), w.n(ml, 3), w.n(vl, 3),
                     w.n(sh, 1)]]
            w.table(f"Ошибки цифровых моделей рельефа по {n} контрольным точкам листа",
                    f"DEM errors at {n} check points",
                    [[w.L("Модель", "DEM"), w.L("СКП m, м", "RMS m, m"), w.L("средняя ошибка, м", "mean error, m"),
                      w.L("ошибок ≤ 15 см, %", "errors ≤ 15 cm, %")]], rows, widths=[3, 1, 1.2, 1.2],
                    align=["left", "right", "right", "right"])
        w.check_note(t2)
    w.figure("dem_contours", "Горизонтали листа варианта по цифровой модели со структурными линиями (синие) и "
             "истинные горизонтали (серые)", "Your sheet's contours from the DEM against the true ones")
    if t2 is not None and t2.number("v_lines_m") is not None:
        v = t2.number("v_lines_m")
        w.conclusion(f"Средняя ошибка модели со структурными линиями {w.n(v * 100, 0)} см " +
                     ("не превышает" if v <= 0.15 else "превышает") + " допустимых источником 15 см.",
                     f"The mean error is {w.n(v * 100, 0)} cm (15 cm allowed).")


# =========================================================================== chapter 17: article 003
def write_17(w, T: dict) -> None:
    t1, t2, t3 = T.get("task-17-1"), T.get("task-17-2"), T.get("task-17-3")
    w.par("При обновлении карты на цифровой фотограмметрической станции положение точки искажается ошибками всех "
          "этапов: привязки, сканирования, фототриангуляции, цифровой модели рельефа, ортотрансформирования и "
          "монтажа, переноса между маршрутами и векторизации. Источник [5] складывает их как независимые "
          "(формула (10)) и сравнивает итог с требованием инструкции — средняя ошибка контура не более 0,4 мм в "
          "масштабе карты.", "The error budget of map updating: seven stages added as independent errors (10) "
          "against the 0.4 mm mean error allowed [5].")
    if w.step(t1, "Ошибка векторизации", "The vectorising error"):
        d = t1.inputs
        VX, VY, VD, mD, md = (t1.number(k) for k in ("VX_m", "VY_m", "VD_m", "mD_m", "md_mm"))
        if d and d.get("X"):
            X, Y = d["X"], d["Y"]
            half = (len(X) + 1) // 2
            rows = []
            for k in range(half):
                row = [str(k + 1), w.n(X[k], 2), w.n(Y[k], 2)]
                j = k + half
                row += [str(j + 1), w.n(X[j], 2), w.n(Y[j], 2)] if j < len(X) else ["", "", ""]
                rows.append(row)
            w.table("Результаты векторизации угла здания (20 измерений)", "The 20 measurements of a building corner",
                    [[w.L("№", "No."), {"math": 'X", м"'}, {"math": 'Y", м"'}] * 2], rows,
                    widths=[0.5, 1.6, 1.6] * 2, align=["center", "right", "right"] * 2, size=9.5)
        if None not in (VX, VY, VD):
            w.eq('V_D = sqrt(V_X^2 + V_Y^2) = sqrt({a}^2 + {b}^2) = {c} " м"', a=w.n(VX, 3), b=w.n(VY, 3), c=w.n(VD, 3))
            w.where([("V_X = sum |X - macron(X)|/n", "средняя ошибка по оси X", "mean error in X")])
        if mD is not None and VD is not None:
            w.eq('m_D = 1","25 V_D = 1","25 dot {v} = {m} " м"', v=w.n(VD, 3), m=w.n(mD, 3))
        if md is not None and mD is not None:
            w.eq('m_d = m_D/M = {m} " м"/{M} = {d} " мм"', m=w.n(mD, 3), M=w.n(w.v.M, 0), d=w.n(md, 3))
        w.check_note(t1)
    if w.step(t2, "Фототриангуляция и сканирование", "Triangulation and scanning"):
        d = t2.inputs
        s, mxy, mphi, msc = (t2.number(k) for k in ("sigma_um", "mxy_m", "mphi_m", "msc_m"))
        if d and s is not None:
            w.eq('sigma = 0","5 P = 0","5 dot {P} = {s} " мкм"', P=w.n(d["P_um"], 0), s=w.n(s, 1))
        if d and mxy is not None and s is not None:
            w.eq('m_(x,y) = 0","84 M_c sigma = 0","84 dot {M} dot {s} " мкм" = {m} " м"', M=w.n(d["M_c"], 0),
                 s=w.n(s, 1), m=w.n(mxy, 3))
        if mphi is not None and mxy is not None:
            w.eq('m_phi = sqrt(2) m_(x,y) = {a} dot {b} = {c} " м"', a=w.n(math.sqrt(2), 3), b=w.n(mxy, 3), c=w.n(mphi, 3))
        if d and msc is not None:
            w.eq('m_"ск" = 3 " мкм" dot M_c = {m} " м"', m=w.n(msc, 3))
        w.check_note(t2)
    if w.step(t3, "Сводная оценка точности обновления", "The budget"):
        mrel, mD, vd, ok, dom = (t3.get(k) for k in ("mrel_m", "mD_m", "vd_mm", "ok", "dominant"))
        if isinstance(mD, (int, float)) and isinstance(vd, (int, float)):
            w.eq('v_d = m_D/(1","25 M) = {m} " м"/(1","25 dot {M}) = {v} " мм"', m=w.n(mD, 2), M=w.n(w.v.M, 0),
                 v=w.n(vd, 3))
            w.par(f"Без цифровой модели рельефа ортотрансформирование ведётся на среднюю плоскость, и рельеф участка "
                  f"даёт ошибку {w.n(mrel, 2) if isinstance(mrel, (int, float)) else '—'} м; итоговая ошибка по "
                  f"формуле (10) $m_D$ = {w.n(mD, 2)} м. Наибольший вклад — этап «{_stage_ru(dom, w.lang)}».",
                  f"The total is {w.n(mD, 2)} m; the largest stage is {_stage_ru(dom, 'en')}.")
        w.check_note(t3)
    w.figure("budget", "Средние квадратические ошибки этапов обновления в масштабе карты и их сумма",
             "The stages' errors on the map and their total")
    if t3 is not None and isinstance(t3.get("vd_mm"), (int, float)):
        vd = t3.get("vd_mm")
        w.conclusion(f"Средняя ошибка положения контура на обновлённой карте {w.n(vd, 2)} мм " +
                     ("не превышает допустимых 0,4 мм: технология обеспечивает точность карты."
                      if vd <= 0.4 else "превышает допустимые 0,4 мм: нужна цифровая модель рельефа или более "
                                        "крупный масштаб съёмки."), f"v_d = {w.n(vd, 2)} mm.")


def _stage_ru(name, lang) -> str:
    from .. import budget as bu

    if not isinstance(name, str):
        return "—"
    from .prose import plain

    if lang != "ru":
        return plain(name)
    for _k, _sym, en, ru in bu.STAGES:
        if name == en:
            return ru
    return plain(name)
