"""Sections 5, 6 and 12 of the note: the fotoschema (guide §6, chapter 05), the strip's triangulation (§7, chapter 06)
and phototriangulation with its reduction (§13, chapter 12): tables 8, 9, 12 and 13 in the guide's layout."""

from __future__ import annotations

import math

from .prose import ru_plural as _pl

__all__ = ["write_05", "write_06", "write_12", "EXTRACT"]



def _seams(raw, v) -> dict:
    df = raw.reset_index()
    return {"cut": [str(c) for c in df["cut"]], "point": [int(p) for p in df["point"]]}


def _scale_points(raw, v) -> dict:
    return {"points": [str(p) for p in raw.index]}


def _strip(raw, v) -> dict:
    c = raw.control
    return {"control": {str(k): [float(r["X (north), m"]), float(r["Y (east), m"]), float(r["x on the strip, mm"]),
                                 float(r["y on the strip, mm"])] for k, r in c.iterrows()}, "M": float(raw.M)}


def _zhukov(raw, v) -> dict:
    return {"k_i": float(raw.k_i), "b_mm": float(raw.b_mm), "m_eps": float(raw.m_eps_arcmin)}


EXTRACT = {"task-05-1": _seams, "task-05-2": _scale_points, "task-06-2": _strip, "task-12-2": _strip,
           "task-12-1": _zhukov}


def _labels(t, name) -> list:
    return next((list(a["labels"]) for a in t.spec if a["name"] == name), [])


# =========================================================================== section 5: chapter 05
def write_05(w, T: dict) -> None:
    v = w.v
    t1, t2 = T.get("task-05-1"), T.get("task-05-2")
    w.par("Одномаршрутная фотосхема смонтирована из рабочих площадей четырёх снимков маршрута: смежные снимки "
          "совмещены по одноимённым контурам и разрезаны по серединам продольных перекрытий. Качество монтажа "
          "проверено по обрезкам — по расхождениям ΔI контуров на порезах, а средний масштаб фотосхемы определён по "
          "четырём базисам между точками начального и конечного снимков, опознанными на фотосхеме и на плане "
          "(пособие, §6, формулы (6.1) и (6.2)).",
          "The single-strip mosaic is glued from the working areas of four photos; the seams are checked by the "
          "mismatches ΔI, the mean scale by four bases (guide §6, formulas 6.1 and 6.2).")
    w.figure("prints", "Контактные отпечатки снимков маршрута варианта", "The strip's prints")
    if w.step(t1, "Качество монтажа", "The seams"):
        dI = t1.numbers("dI_mm")
        cuts, pts = t1.inputs.get("cut", []), t1.inputs.get("point", [])
        if dI and len(dI) == len(cuts):
            groups = list(dict.fromkeys(cuts))
            cols = [[(p, dI[k]) for k, (c, p) in enumerate(zip(cuts, pts)) if c == g] for g in groups]
            depth = max(len(c) for c in cols)
            rows = []
            for r in range(depth):
                row = []
                for col in cols:
                    row += [str(col[r][0]), w.n(col[r][1], 1, plus=True)] if r < len(col) else ["", ""]
                rows.append(row)
            header = [[{"text": w.L(f"Порез {g}", f"Cut {g}"), "colspan": 2} for g in groups],
                      [x for _ in groups for x in (w.L("точка", "point"), {"math": 'Delta I", мм"'})]]
            w.table("Расхождения контуров на порезах фотосхемы (корректурный лист)",
                    "Mismatches along the cuts (the correction sheet)", header, rows, widths=[0.7, 1] * len(groups),
                    align=["center", "right"] * len(groups))
        m, nc = t1.number("m_rms_mm"), t1.number("n_cutouts")
        if m is not None and dI:
            w.par("Знак «минус» означает вырез (контур снимка оказался между порезом и наколом с обрезка), «плюс» — "
                  "дублет. Средняя квадратическая погрешность монтажа:",
                  "Minus is a cut-out, plus a duplicate. The RMS mismatch:")
            w.eq('m = sqrt((sum Delta I^2)/n) = sqrt({s}/{n}) = {m} " мм"', s=w.n(sum(x * x for x in dI), 2),
                 n=w.count(len(dI)), m=w.n(m, 2))
        if nc is not None and dI:
            worst = min(dI)
            w.par(f"Вырезов — {w.count(nc)}, наибольший {w.n(min(worst, 0.0), 1)} мм при допуске −0,5 мм.",
                  f"{int(nc)} cut-outs, the largest {w.n(min(worst, 0.0), 1)} mm (tolerance −0.5 mm).")
        w.check_note(t1)
    w.figure("fotoschema_cuts", "Фотосхема варианта: линии порезов, точки контроля монтажа и точки для определения "
             "среднего масштаба", "Your fotoschema: cuts, check points and the points of the mean scale")
    w.figure("correction", "Корректурный лист фотосхемы: рамки снимков, порезы и точки контроля",
             "The correction sheet: frames, cuts and the check points")
    if w.step(t2, "Средний масштаб фотосхемы", "The mean scale"):
        l, L, mi = (t2.numbers(k, 4) for k in ("l_mm", "L_mm", "m_i"))
        mm = t2.number("m_mean")
        labels = _labels(t2, "l_mm")
        names = t2.inputs.get("points", [])
        pairs = [(names[0], names[2]), (names[1], names[3]), (names[0], names[3]), (names[1], names[2])] \
            if len(names) == 4 else [("", "")] * 4
        if l and L and mi:
            w.eq('1/m_i = l_i/(L_i dot M) arrow m_i = (L_i dot M)/l_i = ({L} dot {M})/{l} = {m}', L=w.n(L[0], 1),
                 M=w.n(v.M, 0), l=w.n(l[0], 1), m=w.n(mi[0], 0))
            rows = [[f"{a} – {b}" if a else str(k + 1), w.n(l[k], 1), w.n(L[k], 1), w.n(mi[k], 0)]
                    for k, (a, b) in enumerate(pairs)]
            w.table("Определение среднего масштаба фотосхемы", "The mean scale of the fotoschema",
                    [[w.L("Базис", "Base"), {"math": 'l_i", мм"'}, {"math": 'L_i", мм"'}, {"math": "m_i"}]], rows,
                    widths=[1.6, 1, 1, 1], align=["center", "right", "right", "right"])
        if mm is not None and mi:
            w.eq('m = (m_1 + m_2 + m_3 + m_4)/4 = {m}, quad "М" 1 : {r}', m=w.n(mm, 0), r=w.n(round(mm / 100) * 100, 0))
        del labels
        w.check_note(t2)
    _conclusion_05(w, t1, t2)


def _conclusion_05(w, t1, t2) -> None:
    parts = []
    m = t1.number("m_rms_mm") if t1 is not None else None
    ok = t1.flag("seams_ok") if t1 is not None else None
    if m is not None:
        parts.append(f"средняя квадратическая погрешность монтажа {w.n(m, 2)} мм" +
                     ("" if ok is None else (", вырезы не превышают 0,5 мм — монтаж удовлетворительный" if ok else
                                             ", есть вырезы больше 0,5 мм — порезы следует переделать")))
    mm = t2.number("m_mean") if t2 is not None else None
    if mm is not None:
        parts.append(f"средний масштаб фотосхемы {w.scale(round(mm / 100) * 100)} (масштаб съёмки {w.scale(w.v.m)}); "
                     "им подписан лист фотосхемы (приложение А)")
    w.conclude(parts)


# =========================================================================== tables 8/12 and 9/13
def _coefficients(w, t, pairs_labels, control, M, *, label, caption_ru, caption_en, k_name="k_bases"):
    k = t.numbers(k_name, len(pairs_labels))
    km = t.number("k_mean")
    rows = []
    lb = t.numbers("l_base_mm", len(pairs_labels))
    lt = t.numbers("l_template_mm", len(pairs_labels))
    for j, lab in enumerate(pairs_labels):
        a, b = lab.split("–")
        if lb is None and a in control and b in control:  # lengths from the coordinates (what table 12 starts from)
            (Xa, Ya, xa, ya), (Xb, Yb, xb, yb) = control[a], control[b]
            base = math.hypot(Xa - Xb, Ya - Yb) / M * 1000.0
            strip = math.hypot(xa - xb, ya - yb)
        else:
            base = lb[j] if lb else None
            strip = lt[j] if lt else None
        dk = None if k is None or km is None else k[j] - km
        rows.append([f"{a} – {b}", "—" if base is None else w.n(base, 1), "—" if strip is None else w.n(strip, 1),
                     "—" if k is None else w.n(k[j], 4), "—" if dk is None else w.n(dk, 4, plus=True)])
    w.table(caption_ru, caption_en, [[w.L("Обозначение базисов", "Base"), {"math": 'l_"осн", " мм"'},
                                      {"math": 'l_"воск", " мм"'}, {"math": "k"}, {"math": "Delta k"}]], rows,
            label=label, widths=[1.6, 1, 1, 1, 1], align=["center", "right", "right", "right", "right"])
    return k, km


def _corrections(w, t, *, label, caption_ru, caption_en, centre):
    names = _labels(t, "r_mm")
    r, vv = t.numbers("r_mm", len(names)), t.numbers("v_mm", len(names))
    if not r or not vv:
        return
    half = (len(names) + 1) // 2
    rows = []
    for part in (range(half), range(half, len(names))):
        rows.append([w.L("Точка", "Point")] + [names[k] for k in part] + [""] * (half - len(part)))
        rows.append([{"math": 'r_i", мм"'}] + [w.n(r[k], 1) for k in part] + [""] * (half - len(part)))
        rows.append([{"math": 'v_i", мм"'}] + [w.n(vv[k], 1, plus=True) for k in part] + [""] * (half - len(part)))
    head = [[{"text": w.L(f"Направления из центра {centre} на точки", f"From centre {centre} to the points"),
              "colspan": half + 1}]]
    w.table(caption_ru, caption_en, head, rows, label=label, widths=[1.3] + [1] * half,
            align=["left"] + ["right"] * half, size=9.5)


# =========================================================================== section 6: chapter 06
def write_06(w, T: dict) -> None:
    t1, t2, t3 = T.get("task-06-1"), T.get("task-06-2"), T.get("task-06-3")
    w.par("Одномаршрутный фототриангуляционный ряд построен графически по восковкам направлений четырёх снимков "
          "(36–39): из рабочих центров проведены направления на связующие, ориентирующие и опорные точки, восковки "
          "уложены по начальным направлениям, а в пересечении направлений на связующие точки оценены треугольники "
          "погрешностей. Построенный в произвольном масштабе свободный ряд приведён к масштабу плана по опознакам: "
          "вычислены коэффициенты редуцирования и поправки в расстояния до точек (пособие, §7, таблицы 8 и 9).",
          "The strip is built from direction templates; the error triangles are judged, the free strip is reduced "
          "to the plan by the control points (guide §7, tables 8 and 9).")
    w.figure("strip_site", "Маршрут снимков 36–39 над участком и наколотые на снимках точки",
             "Photos 36–39 over the site and the pricked points")
    if w.step(t1, "Треугольники погрешностей", "Error triangles"):
        s = t1.numbers("triangle_mm", 4)
        if s:
            names = _labels(t1, "triangle_mm")
            w.table("Наибольшие стороны треугольников погрешностей на связующих точках",
                    "Largest sides of the error triangles",
                    [[w.L("Связующая точка", "Tie point")] + names], [[w.L("сторона, мм", "side, mm")] +
                                                                      [w.n(x, 2) for x in s]],
                    widths=[2] + [1] * len(names), align=["left"] + ["right"] * len(names))
            w.par(f"Наибольшая сторона {w.n(max(s), 2)} мм " + ("не превышает" if max(s) <= 0.3 else "превышает") +
                  " допустимых 0,3 мм.", f"The largest side is {w.n(max(s), 2)} mm (tolerance 0.3 mm).")
        w.check_note(t1)
    w.figure("free_strip", "Восковки направлений, уложенные в свободный ряд: направления, рабочие центры и точки",
             "The templates laid into the free strip")
    if w.step(t2, "Коэффициенты редуцирования", "Reduction coefficients"):
        lb = t2.numbers("l_base_mm")
        if lb:
            w.eq('k = l_"осн"/l_"воск" = {a}/{b} = {k}', a=w.n(lb[0], 1), b=w.n(t2.numbers("l_template_mm")[0], 1),
                 k=w.n(t2.numbers("k_bases")[0], 4))
        k, km = _coefficients(w, t2, _labels(t2, "k_bases"), t2.inputs.get("control", {}), t2.inputs.get("M", 1e4),
                              label="8", caption_ru="Вычисление коэффициента редуцирования",
                              caption_en="Reduction coefficients")
        if km is not None:
            w.par(f"Средний коэффициент редуцирования k = {w.n(km, 4)}; колебания коэффициентов не должны превышать "
                  "0,003.", f"The mean coefficient is {w.n(km, 4)}; the spread must stay within 0.003.")
        w.check_note(t2)
    if w.step(t3, "Поправки за редуцирование", "Corrections for the reduction"):
        r, vv = t3.numbers("r_mm"), t3.numbers("v_mm")
        km = t2.number("k_mean") if t2 is not None else None
        if r and vv and km is not None:
            w.eq('v = r(k - 1) = {r} dot ({k} - 1) = {v} " мм"', r=w.n(r[0], 1), k=w.n(km, 4), v=w.n(vv[0], 1))
            w.par("При k < 1 поправки отрицательны, и точки смещаются к центру ряда; при k > 1 — от центра.",
                  "With k < 1 the points move towards the centre, with k > 1 away from it.")
        _corrections(w, t3, label="9", caption_ru="Поправки за редуцирование", caption_en="Corrections", centre="37")
        w.check_note(t3)
    _conclusion_strip(w, t1, t2, 0.003)


def _conclusion_strip(w, t1, t2, tol) -> None:
    parts = []
    s = t1.numbers("triangle_mm") if t1 is not None else None
    if s:
        parts.append(f"треугольники погрешностей не больше {w.n(max(s), 2)} мм" +
                     (" — в допуске 0,3 мм" if max(s) <= 0.3 else " — больше допуска 0,3 мм, ряд надо перестроить"))
    k, km = (t2.numbers("k_bases"), t2.number("k_mean")) if t2 is not None else (None, None)
    ok = t2.flag("spread_ok") if t2 is not None else None
    if k and km is not None:
        dk = max(abs(x - km) for x in k)
        parts.append(f"средний коэффициент редуцирования {w.n(km, 4)}, наибольшее отклонение от него {w.n(dk, 4)}" +
                     ("" if ok is None else (" — в допуске" if ok else
                                             f" — больше допуска {w.n(tol, 3)}: следует проверить опознаки и "
                                             "укладку восковок")))
    w.conclude(parts)


# =========================================================================== section 12: chapter 12
def write_12(w, T: dict) -> None:
    t1, t2, t3 = T.get("task-12-1"), T.get("task-12-2"), T.get("task-12-3")
    w.par("Плановая фототриангуляция сгущает опорную сеть по снимкам. Расстояние между опорными точками вдоль "
          "маршрута, выраженное числом базисов фотографирования, рассчитано по формуле Г. П. Жукова (13.1) для "
          "камеры и масштабов варианта; затем ряд из четырёх снимков редуцирован по шести базисам между опознаками "
          "(таблица 12) и вычислены поправки в расстояния от рабочего центра 38 (таблица 13) (пособие, §13).",
          "Zhukov's formula gives the control spacing; the strip is reduced on six bases (table 12) and corrected "
          "from centre 38 (table 13) (guide §13).")
    if w.step(t1, "Расстояние между опорными точками", "The control spacing"):
        m3, nmax = t1.number("m3_mm"), t1.number("n_max")
        z = t1.inputs
        if m3 is not None and z:
            w.eq('m = 0","25 k_i b_"ср" m_epsilon/rho′ sqrt(n^3 + 11 n + 34)')
            w.eq('m = 0","25 dot {k} dot {b} dot {e}/{rho} dot sqrt({n3} + 11 dot 3 + 34) = {m} " мм"',
                 numbered=False, k=w.n(z["k_i"], 2), b=w.n(z["b_mm"], 0), e=w.n(z["m_eps"], 1), rho=w.n(3438, 0),
                 n3=w.n(27, 0), m=w.n(m3, 3))
            w.where([("k_i = m/M", "коэффициент трансформирования (увеличения)", "enlargement"),
                     ("b_\"ср\"", "средняя длина базиса на снимке, мм", "mean photo base, mm"),
                     ("m_epsilon", "средняя квадратическая погрешность направления, угл. мин", "direction error, ′"),
                     ("n", "число базисов между опознаками (здесь n = 3)", "bases between the control points")])
            w.par("Радикал n³ + 11n + 34 принят в чтении книги: в скане пособия показатель степени при первом члене "
                  "искажён (напечатано «n⁰»); при n⁰ формула не растёт с n и не может ограничивать расстояние.",
                  "The radicand is read as n³ + 11n + 34: the scan prints a garbled exponent (n⁰).", "note")
        if nmax is not None:
            w.par(f"Наибольшее целое число базисов, при котором m ≤ 0,35 мм: n = {w.count(nmax)}.",
                  f"The largest whole n with m ≤ 0.35 mm: {int(nmax)}.")
        w.check_note(t1)
    w.figure("zhukov", "Погрешность ориентирующей точки в зависимости от числа базисов между опознаками: формула "
             "(13.1) и моделирование свободных рядов для камеры варианта",
             "The orienting point's error against the number of bases: (13.1) and simulated strips")
    if w.step(t2, "Коэффициент редуцирования", "The reduction coefficient"):
        labels = _labels(t2, "k_bases")
        k, km = _coefficients(w, t2, labels, t2.inputs.get("control", {}), t2.inputs.get("M", 1e4), label="12",
                              caption_ru="Вычисление коэффициента редуцирования",
                              caption_en="The reduction coefficient")
        dk = t2.number("dk_max")
        if km is not None:
            w.par(f"Средний k_ред = {w.n(km, 4)}" + (f", наибольшее |Δk| = {w.n(dk, 4)}" if dk is not None else "") +
                  "; колебания не должны превышать 0,003, для коротких базисов — 0,006.",
                  f"The mean k is {w.n(km, 4)}; tolerance 0.003 (0.006 for short bases).")
        w.check_note(t2)
    w.figure("free_strip", "Общая восковка направлений ряда снимков 36–39", "The common tracing of photos 36–39")
    if w.step(t3, "Поправки в расстояния до точек", "Corrections of the distances"):
        _corrections(w, t3, label="13", caption_ru="Вычисление поправок в расстояния до точек",
                     caption_en="Corrections of the distances", centre="38")
        w.par("Поправки откладываются на общей восковке от центра 38 при положительных значениях и к центру при "
              "отрицательных; после наложения на основу опознаки должны совпасть с точностью 0,4 мм.",
              "The corrections are laid off from centre 38 (positive) or towards it (negative).")
        w.check_note(t3)
    parts = []
    if t1 is not None and t1.number("n_max") is not None:
        n = int(t1.number("n_max"))
        parts.append(f"для камеры f = {w.n(w.v.f_mm, 0)} мм и масштаба {w.scale(w.v.m)} опознаки нужны не реже чем "
                     f"через {w.count(n)} {_pl(n, 'базис', 'базиса', 'базисов')}")
    if t2 is not None and t2.flag("spread_ok") is not None:
        parts.append("колебания коэффициентов редуцирования " + ("в допуске" if t2.flag("spread_ok") else
                                                                 "превышают допуск — редуцирование следует повторить"))
    w.conclude(parts)
