"""Sections 7–11 and 13 of the note: the stereo model (§8), interpretation (§9), plan correction (§10), ground
control (§11), rectification (§12, table 11) and soil mapping (§14) — chapters 07–11 and 13."""

from __future__ import annotations

import math
import re

from .prose import plain
from .prose import ru_plural as _pl

__all__ = ["write_07", "write_08", "write_09", "write_10", "write_11", "write_13", "EXTRACT", "choice_ru"]

#: the options of the book's choice answers in Russian (an option not listed shows its own Russian in brackets)
_CHOICES_RU = {
    "towards +x (right)": "в сторону +x (вправо)", "towards −x (left)": "в сторону −x (влево)",
    "towards +y (up)": "в сторону +y (вверх)", "towards −y (down)": "в сторону −y (вниз)",
    "detailed": "детальная", "large-scale": "крупномасштабная", "medium-scale": "среднемасштабная",
    "small-scale": "мелкомасштабная", "between classes": "между классами", "blue": "синяя", "green": "зелёная",
    "red": "красная", "nir": "ближняя инфракрасная", "swir1": "средняя инфракрасная (1,55–1,75 мкм)",
    "swir2": "средняя инфракрасная (2,08–2,35 мкм)",
}

#: our own short interpretation keys (after the guide's table 10) for the objects of chapter 08's photos
_KEYS_RU = {
    "river": ("Реки", "Ширина, направление течения", "ширина — по масштабу снимка; течение — по сужающимся вниз по "
              "течению островам и впадающим под острым углом притокам"),
    "lake": ("Озёра", "Форма и размеры", "замкнутый контур берега; размеры — по масштабу снимка"),
    "pond": ("Пруды", "Форма, направление стока", "контур водного зеркала и плотина, по положению которой "
             "определяется сток"),
    "raised bog": ("Болота", "Верховые", "на водоразделе, далеко от водотоков; мхи, пятнистый тон, мелкие озерки"),
    "low bog": ("Болота", "Низинные", "в долине реки, вытянуты лентой; осока, тростник или кустарник"),
    "pine forest": ("Лес", "Сосновый", "ровный серый тон, выпуклые кроны одной высоты"),
    "spruce forest": ("Лес", "Еловый", "пёстрый тон темнее соснового, узкие островерхие кроны"),
    "deciduous forest": ("Лес", "Лиственный", "светлее хвойного, зернистый рисунок с округлыми кронами"),
    "arable land": ("Пашни", "Форма, границы", "прямолинейные границы, ровный тон, бороздчатый рисунок"),
    "meadow with haystacks": ("Низины и луга", "Состояние поверхности", "ровный серый тон, стога сена и редкий "
                              "кустарник"),
    "railway": ("Дороги железные", "Земляное полотно", "постоянная ширина, длинные прямые, кривые большого радиуса"),
    "asphalt road": ("Дороги автомобильные", "Покрытие", "тёмный тон покрытия (асфальт), более извилистая трасса"),
    "gravel road": ("Дороги автомобильные", "Покрытие", "светлый тон покрытия (гравий)"),
}


def choice_ru(value, options=(), lang: str = "ru") -> str:
    """A chosen option as the note prints it: the Russian of one of the task's options, else the student's own text."""
    if not isinstance(value, str):
        return "—"
    if lang != "ru":
        return plain(value)
    if value in _CHOICES_RU:
        return _CHOICES_RU[value]
    m = re.match(r"^[^()]*\(([^()]*[А-Яа-яЁё][^()]*)\)$", value)
    if m and (not options or value in options):
        return m.group(1)
    return f"«{plain(value)}»"


def _english(value) -> str:
    return value.split(" (")[0] if isinstance(value, str) else ""


def _stereo(raw, v) -> dict:
    b1, b2 = raw.photo_bases_mm()
    c = raw.control
    pts = raw.points
    objs = []
    for name in dict.fromkeys(pts["object"]):
        top = pts[(pts["object"] == name) & (pts["point"] == "top")].iloc[0]
        foot = pts[(pts["object"] == name) & (pts["point"] == "foot")].iloc[0]
        objs.append([str(name).split(":")[0], float(top["x left, mm"] - top["x right, mm"]),
                     float(foot["x left, mm"] - foot["x right, mm"])])
    return {"b1": float(b1), "b2": float(b2), "xl": float(c["x left"]), "xr": float(c["x right"]), "ZA": float(c["Z, m"]),
            "B": float(raw.B_record_m), "objects": objs}


def _relief(raw, v) -> dict:
    return {k: float(raw[k]) for k in ("h_m", "H_m", "B_m", "f_mm", "eye_base_mm", "viewing_distance_mm")}


def _photo(raw, v) -> dict:
    return {"m": float(raw.m)}


def _plan(raw, v) -> dict:
    c = raw.control
    ch = raw.changes
    road = ch[ch["feature"] == "new road"]
    return {"control": [[str(k), float(r["x photo, mm"]), float(r["y photo, mm"]), float(r["x plan, mm"]),
                         float(r["y plan, mm"])] for k, r in c.iterrows()],
            "road": [[float(r["x photo, mm"]), float(r["y photo, mm"])] for _, r in road.iterrows()], "M": float(raw.M)}


def _resection(raw, v) -> dict:
    return {"known": [[str(k), float(r["X, m"]), float(r["Y, m"])] for k, r in raw.known.iterrows()],
            "angles": {k: float(a) for k, a in raw.angles_deg.items()}}


def _paper(raw, v) -> dict:
    return {"l0": [float(x) for x in raw.l0_mm], "li": [float(x) for x in raw.li_mm], "f": float(raw.f_mm),
            "m": float(raw.m), "M": float(raw.M)}


def _rect(raw, v) -> dict:
    return {"points": [[str(k), str(r["role"]), float(r["x photo, mm"]), float(r["y photo, mm"]), float(r["x base, mm"]),
                        float(r["y base, mm"])] for k, r in raw.points.iterrows()], "M": float(raw.M)}


def _soil_scales(raw, v) -> dict:
    return {"m": [float(x) for x in raw["scale denominator"]]}


def _pit(raw, v) -> dict:
    return {k: (float(x) if isinstance(x, (int, float)) else str(x)) for k, x in raw.items()}


EXTRACT = {"task-07-1": _stereo, "task-07-2": _stereo, "task-07-3": _relief, "task-08-3": _photo,
           "task-09-1": _plan, "task-09-2": _plan, "task-10-1": _resection, "task-10-2": _resection,
           "task-11-1": _paper, "task-11-2": _rect, "task-13-1": _soil_scales, "task-13-2": _pit}


# =========================================================================== section 7: chapter 07
def write_07(w, T: dict) -> None:
    t1, t2, t3 = T.get("task-07-1"), T.get("task-07-2"), T.get("task-07-3")
    w.par("Стереопара варианта — два смежных снимка с продольным перекрытием около 60 % — рассматривается в "
          "линзово-зеркальный стереоскоп: при прямом стереоэффекте левый снимок виден левым глазом, правый — правым, "
          "и возникает объёмная модель местности; если снимки поменять местами, рельеф кажется обратным. По "
          "измерениям на паре определены базис снимков, продольные параллаксы и по разностям параллаксов — высоты "
          "объектов; оценено, насколько модель кажется вытянутой по высоте (пособие, §8).",
          "The pair is viewed under the mirror stereoscope; its base, parallaxes and the objects' heights are "
          "measured, and the model's vertical exaggeration found (guide §8).")
    w.figure("anaglyph", "Фрагмент перекрытия стереопары варианта в анаглифическом виде (красный фильтр — левый "
             "глаз)", "A piece of the pair's overlap as an anaglyph")
    if w.step(t1, "Базис снимков и высота центров фотографирования", "The base and the stations' height"):
        d = t1.inputs
        b, pA, ZS = t1.number("b_mm"), t1.number("pA_mm"), t1.number("ZS_m")
        if d and b is not None:
            w.eq('b = (b_1 + b_2)/2 = ({b1} + {b2})/2 = {b} " мм"', b1=w.n(d["b1"], 2), b2=w.n(d["b2"], 2),
                 b=w.n(b, 2))
        if d and pA is not None:
            w.eq('p_A = x_"л" - x_"п" = {xl} - ({xr}) = {p} " мм"', xl=w.n(d["xl"], 2), xr=w.n(d["xr"], 2), p=w.n(pA, 2))
        if d and ZS is not None and pA:
            w.eq('Z_S = Z_A + (B f)/p_A = {Z} + ({B} dot {f})/{p} = {ZS} " м"', Z=w.n(d["ZA"], 1), B=w.n(d["B"], 1),
                 f=w.n(w.v.f_mm, 0), p=w.n(pA, 2), ZS=w.n(ZS, 1))
            w.where([("B", "базис фотографирования по навигационной записи, м", "air base, m"),
                     ("Z_A", "высота опорной точки A, м", "height of A, m")])
        w.check_note(t1)
    w.figure("pair_geometry", "Стереопара в разрезе: центры фотографирования S₁ и S₂, точка A на земле и точка C "
             "выше её; продольный параллакс у более высокой точки больше",
             "The pair in section: a higher point has the larger x-parallax")
    if w.step(t2, "Высоты объектов по разностям параллаксов", "Heights from parallax differences"):
        d = t2.inputs
        dp = t2.numbers("dp_mm", 4)
        hs = [t2.number(f"dh{c}_m") for c in "ABCD"]
        if d and dp and all(h is not None for h in hs):
            o = d["objects"]
            H0 = d["B"] * w.v.f_mm / o[0][2]
            w.eq('Delta h = (H dot Delta p)/(p + Delta p), quad H = (B f)/p', numbered=True)
            w.eq('Delta h_A = ({H} dot {dp})/({p} + {dp}) = {h} " м"', numbered=False, H=w.n(H0, 0), dp=w.n(dp[0], 2),
                 p=w.n(o[0][2], 2), h=w.n(hs[0], 1))
            rows = [[o[k][0], w.n(o[k][2], 2), w.n(dp[k], 2), w.n(hs[k], 1)] for k in range(4)]
            w.table("Разности продольных параллаксов и высоты объектов", "Parallax differences and heights",
                    [[w.L("Объект", "Object"), {"math": 'p", мм"'}, {"math": 'Delta p", мм"'},
                      {"math": 'Delta h", м"'}]], rows, widths=[1.2, 1, 1, 1], align=["center", "right", "right", "right"])
            w.par("Здесь p — параллакс основания объекта, Δp — разность параллаксов вершины и основания.",
                  "p is the parallax of the object's foot, Δp that of its top minus its foot.", "plain")
        w.check_note(t2)
    if w.step(t3, "Параллакс рельефа и вертикальный масштаб модели", "The relief's parallax and the vertical exaggeration"):
        d = t3.inputs
        dpr, V = t3.number("dp_relief_mm"), t3.number("V")
        if d and dpr is not None:
            b0 = d["B_m"] * d["f_mm"] / d["H_m"]
            w.eq('b_0 = (B f)/H = ({B} dot {f})/{H} = {b0} " мм"', B=w.n(d["B_m"], 1), f=w.n(d["f_mm"], 0),
                 H=w.n(d["H_m"], 0), b0=w.n(b0, 2))
            w.eq('Delta p = (b_0 h)/(H - h) = ({b0} dot {h})/({H} - {h}) = {dp} " мм"', b0=w.n(b0, 2),
                 h=w.n(d["h_m"], 0), H=w.n(d["H_m"], 0), dp=w.n(dpr, 3))
        if d and V is not None:
            w.eq('V = B/H dot d/b_"гл" = {B}/{H} dot {dv}/{be} = {V}', B=w.n(d["B_m"], 1), H=w.n(d["H_m"], 0),
                 dv=w.n(d["viewing_distance_mm"], 0), be=w.n(d["eye_base_mm"], 0), V=w.n(V, 2))
            w.where([("d", "расстояние наилучшего зрения, мм", "viewing distance, mm"),
                     ('b_"гл"', "глазной базис, мм", "eye base, mm")])
        w.check_note(t3)
    parts = []
    if t2 is not None and t2.attempted and t2.numbers("dp_mm"):
        parts.append(f"разности параллаксов {w.n(min(t2.numbers('dp_mm')), 2)}–{w.n(max(t2.numbers('dp_mm')), 2)} мм "
                     "позволили определить высоты четырёх объектов")
    if t3 is not None and t3.number("V") is not None:
        V = t3.number("V")
        parts.append(f"вертикальный масштаб модели V = {w.n(V, 2)}: рельеф в стереоскопе кажется " +
                     ("сглаженным (в " + w.n(1 / V, 1) + " раза ниже натурного)" if V < 1 else "преувеличенным"))
    w.conclude(parts)


# =========================================================================== section 8: chapter 08
def write_08(w, T: dict) -> None:
    t1, t2, t3 = T.get("task-08-1", ), T.get("task-08-2"), T.get("task-08-3")
    w.par("Дешифрирование — распознавание объектов местности по их изображению на снимке. Объекты опознаются по "
          "прямым признакам (форма, размер, тон, структура изображения, тень) и косвенным (положение в рельефе, "
          "связь с другими объектами); на дешифрируемость влияют время года и дня, влажность, дымка, наклон снимка и "
          "выдержка. На цветном снимке варианта опознаны шесть пронумерованных объектов, определены направление "
          "течения реки и порода леса, по масштабу снимка измерена ширина реки (пособие, §9, таблица 10).",
          "Interpretation by direct and indirect keys: six numbered objects, the river's flow, the spruce stand and "
          "the river's width on your photo (guide §9, table 10).")
    w.figure("interpretation_photo", "Снимок варианта с пронумерованными объектами 1–6, участками леса P и Q и "
             "створом A–B на реке", "Your photo with the objects 1–6, the stands P and Q and the line A–B")
    if w.step(t1, "Опознавание объектов", "The objects"):
        opts = next((a["options"] for a in t1.spec if a["name"] == "obj1"), [])
        rows = []
        for k in range(1, 7):
            val = t1.get(f"obj{k}")
            key = _KEYS_RU.get(_english(val))
            rows.append([str(k), choice_ru(val, opts, w.lang), key[1] if key else "—", key[2] if key else "—"])
        w.table("Топографическое дешифрирование аэрофотоснимка варианта (по признакам таблицы 10 пособия)",
                "Interpretation of your photo (keys after table 10)",
                [[w.L("№", "No."), w.L("Объект", "Object"), w.L("Определяемые элементы", "Element"),
                  w.L("Способ и признаки дешифрирования", "Keys")]], rows, label="10", widths=[0.5, 2, 1.8, 4.5],
                align=["center", "left", "left", "left"], size=10)
        w.check_note(t1)
    if w.step(t2, "Направление течения и порода леса", "The flow and the stands"):
        flow, sp = t2.get("flow"), t2.get("spruce")
        opts = next((a["options"] for a in t2.spec if a["name"] == "flow"), [])
        w.par(f"Течение реки направлено {choice_ru(flow, opts, w.lang)}: острова сужаются вниз по течению, приток "
              f"впадает под острым углом. Еловый лес — участок {choice_ru(sp, ('P', 'Q'), 'en')}: его тон пёстрый и "
              "темнее, кроны узкие, островерхие.",
              f"The river flows {plain(flow)}; the spruce stand is {plain(sp)}.")
        w.check_note(t2)
    if w.step(t3, "Ширина реки", "The river's width"):
        W = t3.number("width_m")
        m = t3.inputs.get("m")
        if W is not None and m:
            w.par(f"Расстояние A–B между урезами воды измерено на снимке и переведено в метры по собственному масштабу "
                  f"снимка 1:{w.n(m, 0)} (он отличается от масштаба съёмки варианта):",
                  f"A–B measured on the photo and scaled by the photo's own 1:{w.n(m, 0)}:")
            w.eq('L = l dot m = {l} " мм" dot {m} = {W} " м"', l=w.n(W / m * 1000, 2), m=w.n(m, 0), W=w.n(W, 1))
        w.check_note(t3)
    if t1 is not None and t1.attempted:
        ok = sum(1 for k in range(1, 7) if t1.checks.get(f"obj{k}", (False,))[0])
        w.conclusion(f"По прямым и косвенным признакам опознано {ok} из 6 объектов" +
                     (f"; ширина реки по масштабу снимка — {w.n(t3.number('width_m'), 1)} м"
                      if t3 is not None and t3.number("width_m") is not None else "") + ".",
                     f"{ok} of 6 objects identified.")


# =========================================================================== section 9: chapter 09
def write_09(w, T: dict) -> None:
    t1, t2 = T.get("task-09-1"), T.get("task-09-2")
    w.par("Изменения ситуации, выявленные на новом снимке, переносятся на устаревший план графически: в "
          "четырёхугольнике, образованном четырьмя опорными точками, на снимке и на плане строятся взаимно-проектные "
          "сетки, и контуры переносятся по клеткам сеток — каждая точка занимает в клетке плана то же положение, что "
          "и в клетке снимка (пособие, §10).", "Changes are carried from the new photo to the old plan cell by cell "
          "by mutual projective grids on four control points (guide §10).")
    d = next((t.inputs for t in (t1, t2) if t is not None and t.inputs), {})
    if not any(t is not None and t.attempted for t in (t1, t2)):
        w.not_done(t1)
        w.not_done(t2)
        return
    if d:
        rows = [[r[0], w.n(r[1], 2), w.n(r[2], 2), w.n(r[3], 2), w.n(r[4], 2)] for r in d["control"]]
        w.table("Опорные (трансформационные) точки на снимке и на плане", "The four control points",
                [[{"text": w.L("Точка", "Point"), "rowspan": 2}, {"text": w.L("Снимок, мм", "Photo, mm"), "colspan": 2},
                  {"text": w.L("План, мм", "Plan, mm"), "colspan": 2}], ["x", "y", "x", "y"]], rows,
                widths=[1, 1, 1, 1, 1], align=["center"] + ["right"] * 4)
    if w.step(t1, "Перенос точки по клеткам сетки", "A point carried cell by cell"):
        r, c, x, y = (t1.number(k) for k in ("row", "col", "x_mm", "y_mm"))
        if None not in (r, c, x, y):
            w.par(f"Первый угол хозяйственной постройки 1 попадает в клетку сетки 4 × 4 на снимке в ряду {w.count(r)} и "
                  f"колонке {w.count(c)} (счёт от нуля от сторон 1–2 и 1–4). Перенесённый в ту же клетку плана, он "
                  f"получает координаты x = {w.n(x, 2)} мм, y = {w.n(y, 2)} мм.",
                  f"The corner lies in row {int(r)}, column {int(c)}; on the plan x = {w.n(x, 2)} mm, y = {w.n(y, 2)} mm.")
        w.check_note(t1)
    if w.step(t2, "Нанесение новой дороги", "The new road"):
        xr, yr, L = t2.numbers("xr_mm"), t2.numbers("yr_mm"), t2.number("road_m")
        road = d.get("road", []) if d else []
        if xr and yr and len(xr) == len(road):
            rows = [[str(k + 1), w.n(road[k][0], 2), w.n(road[k][1], 2), w.n(xr[k], 2), w.n(yr[k], 2)]
                    for k in range(len(xr))]
            w.table("Вершины новой дороги на снимке и на плане", "The new road's vertices",
                    [[{"text": w.L("Вершина", "Vertex"), "rowspan": 2},
                      {"text": w.L("Снимок, мм", "Photo, mm"), "colspan": 2},
                      {"text": w.L("План, мм", "Plan, mm"), "colspan": 2}], ["x", "y", "x", "y"]], rows,
                    widths=[1, 1, 1, 1, 1], align=["center"] + ["right"] * 4)
            seg = sum(math.hypot(xr[k + 1] - xr[k], yr[k + 1] - yr[k]) for k in range(len(xr) - 1))
            if L is not None:
                w.eq('L = sum l_k dot M = {s} " мм" dot {M} = {L} " м"', s=w.n(seg, 2), M=w.n(d.get("M", 1e4), 0),
                     L=w.n(L, 0))
        w.check_note(t2)
    w.figure("grids", "Взаимно-проектные сетки на новом снимке (слева) и на устаревшем плане (справа), опорные точки "
             "1–4 и перенесённые изменения", "The mutual grids on the photo and the plan, and the carried changes")
    if t2 is not None and t2.number("road_m") is not None:
        w.conclusion(f"Новая дорога длиной {w.n(t2.number('road_m'), 0)} м нанесена на план по клеткам сетки; план "
                     "части землепользования откорректирован.", "The new road is carried onto the plan.")


# =========================================================================== section 10: chapter 10
def write_10(w, T: dict) -> None:
    from ..control import format_dms

    t1, t2 = T.get("task-10-1"), T.get("task-10-2")
    w.par("Проект планово-высотной привязки размещает опорные точки (опознаки) на снимках так, чтобы каждая "
          "находилась на наибольшем числе снимков и надёжно опознавалась; при разреженной привязке опознаки "
          "располагают рядами поперёк маршрутов. Координаты опознака определены обратной засечкой по трём исходным "
          "пунктам A, B, C и двум измеренным углам; для контроля измерен третий угол на пункт D (пособие, §11).",
          "The control design, and the control point's resection from A, B, C with a check angle to D (guide §11).")
    w.figure("control_design", "Проект привязки блока снимков варианта: контуры снимков, центры и ряды опознаков "
             "поперёк маршрутов", "The control design of a block at your scale")
    d = next((t.inputs for t in (t1, t2) if t is not None and t.inputs), {})
    if not any(t is not None and t.attempted for t in (t1, t2)):
        w.not_done(t1)
        w.not_done(t2)
        return
    if d:
        rows = [[k, w.n(X, 2), w.n(Y, 2)] for k, X, Y in d["known"]]
        w.table("Координаты исходных пунктов", "The known points",
                [[w.L("Пункт", "Point"), {"math": 'X", м"'}, {"math": 'Y", м"'}]], rows, widths=[1, 2, 2],
                align=["center", "right", "right"])
        a = d["angles"]
        w.par(f"Измеренные углы: β₁ (A → B) = {format_dms(a['beta1'])}, β₂ (B → C) = {format_dms(a['beta2'])}, "
              f"контрольный γ (C → D) = {format_dms(a['gamma'])}.",
              f"Measured: β₁ = {format_dms(a['beta1'])}, β₂ = {format_dms(a['beta2'])}, γ = {format_dms(a['gamma'])}.")
    if w.step(t1, "Обратная засечка", "The resection"):
        X, Y, aPA = (t1.number(k) for k in ("X_m", "Y_m", "alpha_PA_deg"))
        if X is not None and Y is not None:
            w.par(f"Координаты определяемого пункта P: X = {w.n(X, 2)} м, Y = {w.n(Y, 2)} м" +
                  (f"; дирекционный угол направления P → A α = {format_dms(aPA % 360)}." if aPA is not None else "."),
                  f"P: X = {w.n(X, 2)} m, Y = {w.n(Y, 2)} m.")
        w.check_note(t1)
    own = {"station": [t1.number("X_m"), t1.number("Y_m")]} if t1 is not None and t1.number("X_m") is not None else {}
    w.figure("resection", "Обратная засечка: исходные пункты A–D, опасный круг через A, B, C и определяемый пункт P",
             "The resection: the known points, the danger circle and the station", own=own)
    if w.step(t2, "Контроль по третьему углу", "The check angle"):
        g, dg, tol, ok = (t2.get(k) for k in ("gamma_calc_deg", "dgamma_arcsec", "tol_arcsec", "check_ok"))
        if isinstance(g, (int, float)) and isinstance(dg, (int, float)) and d:
            w.eq('Delta gamma = gamma_"изм" - gamma_"выч" = {dg}″', dg=w.n(dg, 1))
            w.par(f"Вычисленный по координатам угол γ = {format_dms(g % 360)}; расхождение {w.n(dg, 1)}″ при допуске "
                  f"{w.n(tol, 0) if isinstance(tol, (int, float)) else '—'}″ — контроль " +
                  ("выполнен." if ok else "не выполнен: в измерениях промах, засечку следует повторить."),
                  f"Δγ = {w.n(dg, 1)}″, tolerance {tol}″.")
        w.check_note(t2)
    if t2 is not None and isinstance(t2.get("check_ok"), bool):
        w.conclusion("Положение опознака определено обратной засечкой; " +
                     ("контрольный угол подтвердил результат." if t2.get("check_ok") else
                      "контрольный угол выявил промах — результат засечки не принимается."),
                     "The resection " + ("holds." if t2.get("check_ok") else "fails its check."))


# =========================================================================== section 11: chapter 11
def write_11(w, T: dict) -> None:
    t1, t2 = T.get("task-11-1"), T.get("task-11-2")
    w.par("Снимки равнинной местности трансформируются на фототрансформаторе: по четырём трансформационным точкам "
          "изображение приводится к масштабу плана и освобождается от искажений за наклон. До этого по контактному "
          "отпечатку контрольной сетки определяется деформация фотобумаги и рассчитывается толщина подложки, "
          "компенсирующая её (пособие, §12, таблица 11).",
          "Paper deformation and the substrate (table 11), and a four-point rectification (guide §12).")
    if w.step(t1, "Деформация фотобумаги и толщина подложки", "Paper deformation and the substrate"):
        d = t1.inputs
        Kd, t = t1.number("K_d"), t1.number("t_mm")
        if d:
            l0, li = d["l0"], d["li"]
            rows = [[{"math": f"l_{k + 1}"}, w.n(l0[k], 2), w.n(li[k], 2), w.n(l0[k] - li[k], 2, plus=True)]
                    for k in range(len(l0))]
            rows.append([w.L("Сумма", "Sum"), w.n(sum(l0), 2), w.n(sum(li), 2), w.n(sum(l0) - sum(li), 2, plus=True)])
            rows[0].append({"text": f"m = {w.n(d['m'], 0)}\nM = {w.n(d['M'], 0)}\nf = {w.n(d['f'], 0)}",
                            "rowspan": len(rows)})
            w.table("Определение среднего коэффициента деформации фотобумаги и толщины подложки",
                    "Paper deformation and the substrate thickness",
                    [[w.L("Обозначения", "Line"), {"math": 'l_0", мм"'}, {"math": 'l_i", мм"'},
                      {"math": 'delta l = l_0 - l_i'}, w.L("Известные параметры", "Given")]], rows, label="11",
                    widths=[1, 1, 1, 1.2, 1.4], align=["center", "right", "right", "right", "left"])
            if Kd is not None:
                w.eq('K_d = [delta l]/[l_0] = {s}/{l} = {K}', s=w.n(sum(l0) - sum(li), 2), l=w.n(sum(l0), 2),
                     K=w.n(Kd, sig=3))
            if t is not None and Kd is not None:
                Kt = d["m"] / d["M"]
                w.eq('t = K_d dot f dot (K_t + 1) = {K} dot {f} dot ({Kt} + 1) = {t} " мм"', K=w.n(Kd, sig=3),
                     f=w.n(d["f"], 0), Kt=w.n(Kt, 2), t=w.n(t, 2))
                w.where([("K_t = m/M", "коэффициент увеличения снимков", "enlargement"),
                         ("f", "фокусное расстояние, мм", "focal length, mm")])
                w.par("В примере пособия t = −0,00095264·108·(3 + 1) напечатано как 0,4115: знак минус коэффициента "
                      "деформации потерян, должно быть −0,4115 мм; знак толщины здесь сохранён.",
                      "The guide prints t = 0.4115 for −0.00095264·108·4: the minus is lost (−0.4115 mm).", "note")
        w.check_note(t1)
    if w.step(t2, "Трансформирование по четырём точкам", "Four-point rectification"):
        d = t2.inputs
        d1, d2, ok = t2.number("d1_mm"), t2.number("d2_mm"), t2.flag("rect_ok")
        if d:
            rows = [[p[0], w.L("трансформационная" if p[1] == "control" else "контрольная",
                               "control" if p[1] == "control" else "check")] + [w.n(x, 2) for x in p[2:]]
                    for p in d["points"]]
            w.table("Трансформационные и контрольные точки на снимке и на основе", "Control and check points",
                    [[{"text": w.L("Точка", "Point"), "rowspan": 2}, {"text": w.L("Назначение", "Role"), "rowspan": 2},
                      {"text": w.L("Снимок, мм", "Photo, mm"), "colspan": 2},
                      {"text": w.L("Основа, мм", "Base, mm"), "colspan": 2}], ["x", "y", "x", "y"]], rows,
                    widths=[0.8, 2, 1, 1, 1, 1], align=["center", "left"] + ["right"] * 4)
        if d1 is not None and d2 is not None:
            w.par(f"После совмещения четырёх трансформационных точек контрольные точки K1 и K2 отстоят от своих "
                  f"положений на основе на {w.n(d1, 2)} и {w.n(d2, 2)} мм при допуске 0,4 мм.",
                  f"The check points miss by {w.n(d1, 2)} and {w.n(d2, 2)} mm (tolerance 0.4 mm).")
        w.check_note(t2)
    w.figure("rectified", "Снимок варианта, трансформированный по четырём точкам на основу (слева), и тот же участок "
             "с правой половиной плана (справа): контуры продолжаются через шов", "The rectified photo and the plan")
    parts = []
    if t1 is not None and t1.number("t_mm") is not None:
        parts.append(f"толщина подложки {w.n(t1.number('t_mm'), 2)} мм")
    if t2 is not None and t2.flag("rect_ok") is not None:
        parts.append("трансформирование " + ("выполнено в допуске 0,4 мм" if t2.flag("rect_ok") else
                                             "не укладывается в допуск 0,4 мм и должно быть повторено"))
    w.conclude(parts)


# =========================================================================== section 13: chapter 13
def write_13(w, T: dict) -> None:
    t1, t2, t3 = T.get("task-13-1"), T.get("task-13-2"), T.get("task-13-3")
    w.par("Почвенное дешифрирование определяет по снимкам типы почв и границы их контуров. Отражательная "
          "способность почвы тем ниже, чем выше её влажность и гумусированность и крупнее частицы; вода даёт полосы "
          "поглощения около 1,45 и 1,95 мкм. Для участка варианта определён класс почвенных карт по масштабу, "
          "прочитана кривая отражения почвы шурфа и выделены почвенные контуры по синтезированному снимку "
          "(пособие, §14).", "Soil keys from reflectance, the classes of soil maps and the contours of your patch "
          "(guide §14).")
    if w.step(t1, "Классы почвенных карт", "Classes of soil maps"):
        ms = t1.inputs.get("m", [])
        opts = next((a["options"] for a in t1.spec if a["name"] == "class_2m"), [])
        if len(ms) == 3:
            rows = [[w.scale(m), choice_ru(t1.get(k), opts, w.lang)] for m, k in
                    zip(ms, ("class_2m", "class_10m", "class_40m"))]
            w.table("Классы почвенных карт для масштабов, кратных масштабу съёмки", "Classes of soil maps",
                    [[w.L("Масштаб карты", "Map scale"), w.L("Класс карты", "Class")]], rows, widths=[1, 2],
                    align=["right", "left"])
            w.par("Детальные карты — 1:5000 и крупнее, крупномасштабные — 1:10 000…1:25 000, среднемасштабные — "
                  "1:50 000…1:200 000, мелкомасштабные — 1:500 000 и мельче.",
                  "Detailed ≤ 1:5000, large 1:10 000–1:25 000, medium 1:50 000–1:200 000, small ≥ 1:500 000.", "note")
        w.check_note(t1)
    if w.step(t2, "Отражательная способность почвы шурфа", "The pit soil's reflectance"):
        d = t2.inputs
        rho, share, band = t2.number("rho_red"), t2.number("wet_dry_145_pct"), t2.get("band")
        opts = next((a["options"] for a in t2.spec if a["name"] == "band"), [])
        if d:
            w.par(f"Почва шурфа: влажность {w.n(d.get('moisture_pct', 0), 1)} %, гумус {w.n(d.get('humus_pct', 0), 1)} %, "
                  f"размер частиц {w.n(d.get('particle_mm', 0), 2)} мм.", "The pit's soil.")
        if rho is not None and share is not None:
            w.par(f"Коэффициент спектральной яркости в красной зоне (0,63–0,69 мкм) ρ = {w.n(rho, 3)}; на 1,45 мкм "
                  f"влажная почва сохраняет {w.n(share, 1)} % яркости сухой. Сильнее всего влажность гасит "
                  f"{choice_ru(band, opts, w.lang)} зону.", f"ρ_red = {w.n(rho, 3)}; {w.n(share, 1)} % at 1.45 µm.")
        w.check_note(t2)
    w.figure("soil_facts", "Отражательная способность почв по модели книги: влияние влажности, гумуса, размера "
             "частиц и глубина полос поглощения воды", "Soil reflectance: moisture, humus, particle size, water dips")
    if w.step(t3, "Почвенные контуры участка", "The soil contours of your patch"):
        k, agr = t3.number("k"), t3.number("agreement_pct")
        if k is not None and agr is not None:
            w.par(f"Синтезированный снимок участка разделён по тону на {w.count(k)} "
                  f"{_pl(k, 'класс', 'класса', 'классов')} — по числу почв на карте полевого обследования; доля клеток, "
                  f"где преобладающая почва выделенного контура совпадает с почвой клетки, — {w.n(agr, 1)} %.",
                  f"{int(k)} classes; agreement {w.n(agr, 1)} %.")
        w.check_note(t3)
    w.figure("soil_contours", "Участок варианта: синтезированный снимок открытой почвы (слева) и почвенные контуры "
             "по данным полевого обследования (справа)", "Your patch: the composite and the soil contours")
    if t3 is not None and t3.number("agreement_pct") is not None:
        agr = t3.number("agreement_pct")
        w.conclusion(f"Выделение почвенных контуров по тону снимка совпадает с полевой картой на {w.n(agr, 1)} % "
                     "площади" + ("; для крупномасштабного картографирования контуры требуют полевой проверки."
                                  if agr < 90 else "."), f"{w.n(agr, 1)} % agreement.")

