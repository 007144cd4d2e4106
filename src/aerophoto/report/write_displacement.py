"""Sections 3 and 4 of the note: relief displacement (guide §4, chapter 03) and tilt displacement (§5, chapters 00 and 04).

Tables 2–7 of the guide in their own layout: the bases, their plan and photo lengths, the scale denominators of
the bases, the zones and the photo, the deviations (tables 2, 4, 5, 7); the points' heights, distances and
displacements (tables 3 and 6).  Every number is the student's own; the heights Z of the points are what the
student is given.
"""

from __future__ import annotations

import math

from .prose import ru_plural as _pl

__all__ = ["write_03", "write_04", "EXTRACT", "scale_table"]


def _sheet(raw, v) -> dict:
    return {"names": list(raw.names), "bases": [list(b) for b in raw.bases], "Z": [float(z) for z in raw.Z_given_m],
            "M": float(raw.M)}


EXTRACT = {f"task-03-{k}": _sheet for k in (1, 2, 3)} | {f"task-04-{k}": _sheet for k in (2, 3, 4)}


def _ratio(w, dm_pct) -> str:
    """Δm/m_cp as the guide prints it, "1/72" (from the student's own percentage)."""
    if dm_pct is None or abs(dm_pct) < 1e-9:
        return "0"
    return f"1/{w.count(round(100.0 / abs(dm_pct)))}"


def scale_table(w, t, bases, zone_heights, *, label: str, caption_ru: str, caption_en: str, lsn: str = "lsn_mm",
                lpl=None) -> None:
    """The guide's tables 2, 4, 5 and 7: bases, mean heights, l_пл, l_сн, m_i, m_част, m_ср, Δm_i, Δm_i/m_ср."""
    lpl = t.numbers("lpl_mm") if lpl is None else lpl
    ls, mi = t.numbers(lsn), t.numbers("m_i")
    mp, dm = t.numbers("m_part"), t.numbers("dm_pct")
    mcp = t.number("m_cp")
    zones = list(dict.fromkeys(a for a, _ in bases))
    per = len(bases) // max(len(zones), 1)
    heights = zone_heights is not None
    header = [[{"text": w.L("Обозначение базисов", "Bases"), "rowspan": 2}]
              + ([{"text": w.L("Средняя высота базисов, м", "Mean height, m"), "rowspan": 2}] if heights else [])
              + [{"text": w.L("Длина базиса, мм", "Base length, mm"), "colspan": 2},
                 {"text": w.L("Масштабы", "Scales"), "colspan": 3},
                 {"text": w.L("Уклонения масштабов", "Deviations"), "colspan": 2}],
              [{"math": 'l_"пл"'}, {"math": 'l_"сн"'}, {"math": "m_i"}, {"math": 'm_"част"'}, {"math": 'm_"ср"'},
               {"math": "Delta m_i"}, {"math": 'Delta m_i \\/ m_"ср"'}]]
    fmt = lambda xs, k, d: "—" if xs is None or k >= len(xs) else w.n(xs[k], d)  # noqa: E731
    rows = []
    for k, (a, b) in enumerate(bases):
        z = k // per
        row = [f"{a} – {b}"]
        first = k % per == 0
        if first and heights:
            row.append({"text": w.n(zone_heights[z], 0), "rowspan": per})
        row += [fmt(lpl, k, 1), fmt(ls, k, 1), fmt(mi, k, 0)]
        if first:
            row.append({"text": fmt(mp, z, 0), "rowspan": per})
            if k == 0:
                row.append({"text": "—" if mcp is None else w.n(mcp, 0), "rowspan": len(bases)})
            d_abs = None if mp is None or mcp is None or z >= len(mp) else mp[z] - mcp
            row.append({"text": "—" if d_abs is None else w.n(d_abs, 0, plus=True), "rowspan": per})
            row.append({"text": "—" if dm is None or z >= len(dm) else _ratio(w, dm[z]), "rowspan": per})
        rows.append(row)
    n = len(header[0]) - 3 + 7
    widths = [1.3] + ([1.3] if heights else []) + [1, 1, 1.1, 1.1, 1.1, 1, 1.1]
    w.table(caption_ru, caption_en, header, rows, label=label, widths=widths[:n],
            align=["left"] + ["right"] * (n - 1))


def _coords_table(w, t, names, Z=None) -> None:
    x, y = t.numbers("x_mm"), t.numbers("y_mm")
    if x is None or y is None:
        return
    head = [w.L("Точка", "Point"), {"math": 'x", мм"'}, {"math": 'y", мм"'}] + ([{"math": 'Z", м"'}] if Z else [])
    rows = [[str(nm), w.n(x[k], 1), w.n(y[k], 1)] + ([w.n(Z[k], 1)] if Z else []) for k, nm in enumerate(names)]
    w.table("Координаты наколотых точек на снимке (от главной точки o)" + (" и их высоты" if Z else ""),
            "The pricked points on the photo (from o)" + (" and their heights" if Z else ""), [head], rows,
            widths=[1] + [1] * (len(head) - 1), align=["center"] + ["right"] * (len(head) - 1))


def _base_example(w, t, names, bases, M, lsn="lsn_mm") -> None:
    """The formulas of a table's first base with the student's numbers."""
    x, y = t.numbers("x_mm"), t.numbers("y_mm")
    lpl, ls, mi = t.numbers("lpl_mm"), t.numbers(lsn), t.numbers("m_i")
    a, b = bases[0]
    if x is not None and y is not None and lsn == "lsn_mm" and ls:
        i, j = names.index(a), names.index(b)
        w.eq('l_"сн" = sqrt((x_2 - x_1)^2 + (y_2 - y_1)^2)')
        w.eq('l_"сн" = sqrt(({x2} - {x1})^2 + ({y2} - {y1})^2) = {l} " мм"', numbered=False,
             x1=w.n(x[i], 1), x2=w.n(x[j], 1), y1=w.n(y[i], 1), y2=w.n(y[j], 1), l=w.n(ls[0], 1))
    if lpl and ls and mi:
        w.eq('m_i = (l_"пл" dot M)/l_"сн" = ({lpl} dot {M})/{ls} = {m}', lpl=w.n(lpl[0], 1), M=w.n(M, 0),
             ls=w.n(ls[0], 1), m=w.n(mi[0], 0))
        w.par(f"(для базиса {a} – {b}; остальные базисы — в таблице).", f"(base {a} – {b}; the others in the table).",
              "plain")


def _zone_heights(names, bases, Z) -> tuple:
    """Z of each base's mean, of each zone, and of the mean object plane (guide §4, step 3), from the given Z."""
    Zof = dict(zip(names, Z))
    zones = list(dict.fromkeys(a for a, _ in bases))
    zh = [sum((Zof[a] + Zof[b]) / 2 for a, b in bases if a == z) / sum(1 for a, _ in bases if a == z) for z in zones]
    return zh, sum(zh) / len(zh)


# =========================================================================== section 3: chapter 03
def write_03(w, T: dict) -> None:
    v = w.v
    t1, t2, t3 = T.get("task-03-1"), T.get("task-03-2"), T.get("task-03-3")
    w.par("Из-за рельефа точки, лежащие выше или ниже средней предметной плоскости, изображаются на снимке "
          "смещёнными по радиусам от точки надира, и масштаб снимка в разных его частях различен. В разделе на "
          "снимке варианта выбраны две зоны — на возвышенности (I, 1, 2) и в низине (II, 3, 4), по базисам зон "
          "определены частные и средний масштабы, вычислены смещения точек за рельеф $delta_h = r h \\/ H$ и, где они больше "
          "0,2 мм, введены поправки, после чего масштабы определены вновь (пособие, §4, таблицы 2–4).",
          "Relief shifts the images radially from the nadir point; two zones, on high and low ground, give partial "
          "scales before and after the correction δh = r·h/H (guide §4, tables 2–4).")
    d = next((t.inputs for t in (t1, t2, t3) if t is not None and t.inputs), {})
    if not any(t is not None and t.attempted for t in (t1, t2, t3)) or not d:
        for t in (t1, t2, t3):
            if t is not None:
                w.not_done(t)
        return
    names, bases, Z, M = d["names"], [tuple(b) for b in d["bases"]], d["Z"], d["M"]
    zh, zcp = _zone_heights(names, bases, Z)
    if w.step(t1, "Частные и средний масштабы до введения поправок", "Scales before the correction"):
        _coords_table(w, t1, names, Z)
        w.par("Длины базисов на снимке вычислены по координатам точек, длины на плане измерены; знаменатель "
              "масштаба по каждому базису:", "Photo lengths from the coordinates, plan lengths measured:")
        _base_example(w, t1, names, bases, M)
        scale_table(w, t1, bases, zh, label="2", caption_ru="Определение частных и среднего масштабов базисов",
                    caption_en="Partial and mean scales of the bases")
        w.check_note(t1)
    if w.step(t2, "Смещения точек за рельеф", "Relief displacements"):
        Zs, H, xn, yn = t2.number("Zcp_m"), t2.number("H_m"), t2.number("xn_mm"), t2.number("yn_mm")
        r, dh = t2.numbers("r_mm", len(names)), t2.numbers("dh_mm", len(names))
        mcp = t1.number("m_cp") if t1 is not None else None
        w.par("Высота средней предметной плоскости — среднее из средних высот зон:",
              "The mean object plane is the mean of the zones' heights:")
        if Zs is not None:
            w.eq('Z_"ср" = (Z_"Iср" + Z_"IIср")/2 = ({a} + {b})/2 = {Z} " м"', a=w.n(zh[0], 2), b=w.n(zh[-1], 2),
                 Z=w.n(Zs, 2))
        if H is not None and mcp is not None:
            w.eq('H = m_"ср" dot f = {m} dot {f} = {H} " м"', m=w.n(mcp, 0), f=w.n(v.f_mm / 1000, 3), H=w.n(H, 0))
        if xn is not None and yn is not None:
            w.par(f"Точка надира n наколота по элементам ориентирования снимка: x = {w.n(xn, 2)} мм, "
                  f"y = {w.n(yn, 2)} мм от главной точки; расстояния r измерены от неё.",
                  f"The nadir point n is at x = {w.n(xn, 2)} mm, y = {w.n(yn, 2)} mm; r is measured from it.")
        if r and dh and H and Zs is not None:
            h0 = Z[0] - Zs
            w.eq('delta_h = (r dot h)/H = ({r} dot ({h}))/{H} = {d} " мм"', r=w.n(r[0], 1), h=w.n(h0, 1), H=w.n(H, 0),
                 d=w.n(dh[0], 2))
            w.where([("h = Z_i - Z_\"ср\"", "превышение точки над средней плоскостью, м", "height above the plane, m"),
                     ("r", "расстояние от точки надира до точки, мм", "distance from n, mm")])
            rows = [[nm, w.n(Z[k], 1), w.n(Z[k] - Zs, 1, plus=True), w.n(r[k], 1), w.n(dh[k], 2, plus=True)]
                    for k, nm in enumerate(names)]
            w.table("Определение поправок за влияние рельефа местности", "Relief corrections",
                    [[w.L("Обозначение точек базиса", "Point"), {"math": 'Z_i", м"'}, {"math": 'h", м"'},
                      {"math": 'r", мм"'}, {"math": 'delta_h", мм"'}]], rows, label="3", widths=[2, 1, 1, 1, 1],
                    align=["center", "right", "right", "right", "right"])
        nc = t2.number("n_corr")
        if nc is not None and nc == 0:
            w.par("Все смещения меньше 0,2 мм: поправки за рельеф не вводятся, и длины базисов по исправленным точкам "
                  "(таблица 4) остаются прежними.", "Every displacement is below 0.2 mm: no corrections.")
        elif nc is not None:
            w.par(f"Поправки больше 0,2 мм вводятся по направлению к точке надира при положительном смещении и от неё "
                  f"при отрицательном; их число — {w.count(nc)}.",
                  f"Corrections above 0.2 mm are applied towards n (positive) or away from it; {int(nc)} in all.")
        w.check_note(t2)
    if w.step(t3, "Масштабы по исправленным точкам", "Scales after the correction"):
        lpl = t1.numbers("lpl_mm") if t1 is not None else None
        scale_table(w, t3, bases, zh, label="4", caption_ru="Определение частных и среднего масштабов базисов по "
                    "исправленным точкам", caption_en="Scales of the bases between the corrected points",
                    lsn="lsn_corr_mm", lpl=lpl)
        w.check_note(t3)
    own = {}
    if t1 is not None and t2 is not None and t1.numbers("x_mm") and t1.numbers("y_mm") and t2.numbers("dh_mm"):
        own = {"xy": [list(p) for p in zip(t1.numbers("x_mm"), t1.numbers("y_mm"))],
               "centre": [t2.number("xn_mm"), t2.number("yn_mm")], "d": t2.numbers("dh_mm")}
    w.figure("relief_points", "Снимок варианта: точки зон I и II, точка надира n, направления на точки и смещения "
             "за рельеф (стрелки в увеличенном масштабе)", "Your photo: the zones' points, the nadir point and the "
             "relief displacements (arrows enlarged)", own=own)
    _conclusion_03(w, t1, t2, t3)


def _spread(t) -> float | None:
    dm = t.numbers("dm_pct") if t is not None else None
    return None if not dm else max(abs(x) for x in dm)


def _conclusion_03(w, t1, t2, t3) -> None:
    dh = t2.numbers("dh_mm") if t2 is not None else None
    parts = []
    if dh:
        big = max(abs(x) for x in dh)
        n = sum(abs(x) > 0.2 for x in dh)
        parts.append(f"наибольшее смещение за рельеф {w.n(big, 2)} мм; " +
                     (f"поправки введены в {n} {_pl(n, 'точку', 'точки', 'точек')}" if n else
                      "все смещения меньше 0,2 мм, поправки не вводились"))
    a, b = _spread(t1), _spread(t3)
    if a is not None:
        parts.append(f"уклонения частных масштабов от среднего до поправок — до {w.n(a, 2)} %" +
                     (f", после — до {w.n(b, 2)} %" if b is not None else ""))
    w.conclude(parts)



# =========================================================================== section 4: chapters 00 and 04
def write_04(w, T: dict) -> None:
    v = w.v
    t0, t1, t2, t3, t4 = (T.get(k) for k in ("task-00-1", "task-04-1", "task-04-2", "task-04-3", "task-04-4"))
    w.par("Наклон снимка искажает масштаб: изображение по одну сторону от линии неискажённых масштабов $h_c h_c$, "
          "проходящей через точку нулевых искажений c, растянуто, по другую — сжато. В разделе найдены главная точка "
          "o, точка надира n и точка нулевых искажений c снимка варианта, по трём зонам вблизи главной вертикали "
          "определены масштабы, вычислены смещения точек за наклон $delta_alpha = -(r_c^2 cos phi \\/ f) sin alpha$ и по исправленным "
          "точкам масштабы определены вновь (пособие, §5, таблицы 5–7).",
          "A tilt stretches the photo on one side of the isoline and compresses it on the other: the points o, n, "
          "c, the zones' scales, the tilt displacements and the scales after the correction (guide §5, tables 5–7).")
    if w.step(t0, "Элементы центральной проекции снимка", "The elements of the central projection"):
        on, oc = t0.number("on_mm"), t0.number("oc_mm")
        f, a = v.f_mm, v.alpha_deg
        w.par(f"Для снимка с углом наклона α = {w.n(a, 0)}° главная точка o, точка надира n и точка нулевых "
              "искажений c лежат на главной вертикали; их расстояния от главной точки:",
              f"With a tilt of α = {w.n(a, 0)}° the points o, n and c lie on the principal vertical:")
        if on is not None:
            w.eq('o n = f dot "tg" alpha = {f} dot "tg" {a}° = {on} " мм"', f=w.n(f, 0), a=w.n(a, 0), on=w.n(on, 2))
        if oc is not None:
            w.eq('o c = -f dot "tg"(alpha/2) = -{f} dot "tg" {a2}° = {oc} " мм"', f=w.n(f, 0), a2=w.n(a / 2, 1),
                 oc=w.n(oc, 2))
        w.check_note(t0)
    d = next((t.inputs for t in (t2, t3, t4) if t is not None and t.inputs), {})
    if t1 is not None and t1.attempted:
        xc, yc, oc = t1.number("xc_mm"), t1.number("yc_mm"), t1.number("oc_mm")
        if xc is not None and yc is not None:
            w.par(f"Главная вертикаль снимка повёрнута на угол λ = {w.n(v.lambda_deg, 0)}°; точка c отложена от главной "
                  f"точки на {w.n(abs(oc or math.hypot(xc, yc)), 2)} мм и имеет координаты $x_c$ = {w.n(xc, 2)} мм, "
                  f"$y_c$ = {w.n(yc, 2)} мм.", f"The swing is λ = {w.n(v.lambda_deg, 0)}°; c is at x = {w.n(xc, 2)} mm, "
                  f"y = {w.n(yc, 2)} mm.")
        w.check_note(t1)
    elif t1 is not None:
        w.not_done(t1)
    if not d:
        for t in (t2, t3, t4):
            if t is not None and not t.attempted:
                w.not_done(t)
        return
    names, bases, M = d["names"], [tuple(b) for b in d["bases"]], d["M"]
    if w.step(t2, "Частные и средний масштабы наклонного снимка", "Scales of the tilted photo"):
        _coords_table(w, t2, names)
        _base_example(w, t2, names, bases, M)
        scale_table(w, t2, bases, None, label="5", caption_ru="Результаты измерений и вычислений знаменателей частных и "
                    "среднего масштабов аэроснимка", caption_en="Partial and mean scales of the photo")
        w.check_note(t2)
    if w.step(t3, "Смещения точек за угол наклона", "Tilt displacements"):
        rc, phi, da = (t3.numbers(k, len(names)) for k in ("rc_mm", "phi_deg", "da_mm"))
        if rc and phi and da:
            w.eq('delta_alpha = -(r_c^2 cos phi)/f dot sin alpha = -({r}^2 dot {c})/{f} dot sin {a}° = {d} " мм"',
                 r=w.n(rc[0], 1), c=w.n(math.cos(math.radians(phi[0])), 3), f=w.n(v.f_mm, 0), a=w.n(v.alpha_deg, 0),
                 d=w.n(da[0], 2))
            w.where([("r_c", "расстояние от точки нулевых искажений до точки, мм", "distance from c, mm"),
                     ("phi", "угол от положительного направления главной вертикали, против часовой стрелки",
                      "angle from the + principal vertical, counter-clockwise")])
            rows = [[nm, w.n(rc[k], 1), w.n(phi[k], 0), w.n(math.cos(math.radians(phi[k])), 3, plus=True),
                     w.n(da[k], 2, plus=True)] for k, nm in enumerate(names)]
            w.table("Определение поправок в точки снимка за угол его наклона", "Tilt corrections",
                    [[w.L("Обозначение точек базиса", "Point"), {"math": "r_c"}, {"math": "phi°"},
                      {"math": "cos phi"}, {"math": "delta_alpha"}], ["1", "2", "3", "4", "5"]], rows, label="6",
                    widths=[2, 1, 1, 1, 1], align=["center", "right", "right", "right", "right"])
        nc = t3.number("n_corr")
        if nc is not None:
            w.par(f"Поправки больше 0,2 мм ({w.count(nc)}) вводятся по направлениям из точки c: отрицательные — от "
                  "точки c, положительные — к ней.", f"{int(nc)} corrections above 0.2 mm, along the lines from c.")
        w.check_note(t3)
    if w.step(t4, "Масштабы по исправленным точкам", "Scales after the tilt correction"):
        lpl = t2.numbers("lpl_mm") if t2 is not None else None
        scale_table(w, t4, bases, None, label="7", caption_ru="Определение частных и среднего масштабов аэроснимка по "
                    "точкам, положение которых исправлено за угол его наклона",
                    caption_en="Scales after the tilt correction", lsn="lsn_corr_mm", lpl=lpl)
        w.check_note(t4)
    own = {}
    if t1 is not None and t2 is not None and t3 is not None and t2.numbers("x_mm") and t3.numbers("da_mm") \
            and t1.number("xc_mm") is not None:
        own = {"xy": [list(p) for p in zip(t2.numbers("x_mm"), t2.numbers("y_mm"))],
               "centre": [t1.number("xc_mm"), t1.number("yc_mm")], "d": t3.numbers("da_mm")}
    w.figure("tilt_points", "Снимок варианта: главная точка o, точка нулевых искажений c, главная вертикаль и линия "
             "$h_c h_c$, точки зон I–III и их смещения за наклон (стрелки в увеличенном масштабе)",
             "Your photo: o, c, the principal vertical, the zones' points and their tilt displacements", own=own)
    _conclusion_04(w, t3, t2, t4)


def _conclusion_04(w, t3, t2, t4) -> None:
    da = t3.numbers("da_mm") if t3 is not None else None
    parts = []
    if da:
        n = sum(abs(x) > 0.2 for x in da)
        parts.append(f"смещения за наклон достигают {w.n(max(abs(x) for x in da), 2)} мм, поправки введены в {n} "
                     f"{_pl(n, 'точку', 'точки', 'точек')}")
    a, b = _spread(t2), _spread(t4)
    if a is not None:
        parts.append(f"наибольшее уклонение частного масштаба от среднего до исправления {w.n(a, 2)} %" +
                     (f", после — {w.n(b, 2)} %" + (": исправление выровняло масштаб снимка" if b < a else "")
                      if b is not None else ""))
    w.conclude(parts)
