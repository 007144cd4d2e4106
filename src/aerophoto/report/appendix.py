"""The end of the note: the conclusion with the student's key results, the sources, and the appendices."""

from __future__ import annotations

import shutil
from importlib import metadata
from pathlib import Path

__all__ = ["conclusion", "sources_list", "appendices", "SOURCES", "SOFTWARE"]

#: the sources as far as the seeds give their bibliographic data ([1] the guide; [2]–[5] the articles by the
#: book's chapters 16, 14, 15, 17; then the standards)
SOURCES = (
    "Пресняков, В. В. Фотограмметрия. Руководство по курсовому проектированию : учеб. пособие / В. В. Пресняков, "
    "Е. П. Тюкленкова. — Пенза : ПГУАС, 2014. — 88 с.",
    "Опыт рисовки горизонталей на фотоплане по точкам цифровой модели рельефа для проектирования мелиоративных "
    "систем : статья / [авторы в источнике не указаны]. — Поступила в редколлегию 16.05.1980.",
    "Точность фототриангуляционных сетей [Электронный ресурс] : глава учебного пособия по фотограмметрии "
    "(формулы (10.20), (10.21)). — Последнее изменение страницы: 08.03.2017.",
    "Дорожинский, А. Л. Методика аэрофотопривязки пунктов гравиметрической съемки в условиях высокогорья : статья / "
    "А. Л. Дорожинский, О. В. Тумская, Ю. В. Шкурченко, Ю. В. Коваль. — УДК 528.44+528.46+528.74. — Поступила в "
    "редколлегию 14.04.1987.",
    "Михеева, А. А. Анализ плановой точности при обновлении топографических карт (планов) на цифровой "
    "фотограмметрической станции : статья / А. А. Михеева, В. В. Ялтыхов, П. В. Ващеева (Полоцкий государственный "
    "университет). — УДК 528.71. — Поступила 27.11.2014.",
    "Инструкция по фотограмметрическим работам при создании цифровых топографических карт и планов : ГКИНП (ГНТА)"
    "-02-036-02 / Федеральная служба геодезии и картографии России. — М. : ЦНИИГАиК, 2002.",
    "СТП ПГУАС 1.2.1.003-2005. Стандарт предприятия: оформление пояснительных записок курсовых работ (проектов) / "
    "ПГУАС. — Пенза, 2005.",
    "ГОСТ 8.417-2002. Государственная система обеспечения единства измерений. Единицы величин. — М. : "
    "Стандартинформ.",
)

#: the software the note was made with (distribution, what it did)
SOFTWARE = (("aerophoto", "рабочая тетрадь, расчёты, виртуальный полигон, рисунки"),
            ("numpy", "вычисления"), ("scipy", "уравнивание и оптимизация"), ("pandas", "таблицы"),
            ("matplotlib", "рисунки"), ("scikit-image", "обработка изображений"), ("typst", "вёрстка записки"))


def _version(dist: str) -> str:
    try:
        return metadata.version(dist)
    except metadata.PackageNotFoundError:
        return "—"


def sources_list(doc, lang: str) -> None:
    ru = lang == "ru"
    doc.heading(1, "Список использованных источников" if ru else "References", structural=True, newpage=True)
    entries = list(SOURCES)
    for dist, what in SOFTWARE:
        entries.append(f"{dist} {_version(dist)} [Электронный ресурс] : программное обеспечение ({what}). — "
                       "Режим доступа: https://pypi.org/project/" + dist + "/" if ru else
                       f"{dist} {_version(dist)}: software ({what}). https://pypi.org/project/{dist}/")
    doc.items(entries, numbered=True)


# =========================================================================== the conclusion
def _key_results(w, T) -> list:
    """The student's key numbers, section by section (only what they did)."""
    out = []

    def done(tid):  # the task's record when the student attempted it
        x = T.get(tid)
        return x if x is not None and x.attempted else None

    v = w.v
    if done("task-01-1") and done("task-01-1").number("H_m") is not None:
        x = done("task-01-1")
        s = f"высота фотографирования H = {w.n(x.number('H_m'), 0)} м"
        if x.number("Px_percent") is not None:
            s += f", продольное перекрытие с поправкой за рельеф {w.n(x.number('Px_percent'), 1)} %"
        if done("task-01-2") and done("task-01-2").number("N") is not None:
            y = done("task-01-2")
            s += f"; {w.count(y.number('K'))} маршрутов по {w.count(y.number('n'))} снимков, всего {w.count(y.number('N'))}"
        if done("task-01-3") and done("task-01-3").number("TS_h") is not None:
            s += f"; время съёмки {w.n(done('task-01-3').number('TS_h'), 1)} ч"
        out.append(s + " (раздел 1)")
    if done("task-02-2"):
        flags = [done("task-02-2").flag(k) for k in ("px_ok", "dm_ok", "n_ok", "crab_ok", "tilt_ok")]
        if all(f is not None for f in flags):
            out.append("материалы аэрофотосъёмки " + ("удовлетворяют требованиям §3" if all(flags) else
                                                      f"не удовлетворяют требованиям §3 по {flags.count(False)} "
                                                      "показателям") + " (раздел 2)")
    for tid, name, key, sec in (("task-03-2", "за рельеф", "dh_mm", 3), ("task-04-3", "за наклон снимка", "da_mm", 4)):
        x = done(tid)
        if x and x.numbers(key):
            big = max(abs(e) for e in x.numbers(key))
            out.append(f"наибольшее смещение точек {name} {w.n(big, 2)} мм (раздел {sec})")
    if done("task-05-2") and done("task-05-2").number("m_mean") is not None:
        s = f"средний масштаб фотосхемы {w.scale(round(done('task-05-2').number('m_mean') / 100) * 100)}"
        if done("task-05-1") and done("task-05-1").number("m_rms_mm") is not None:
            s += f", погрешность монтажа {w.n(done('task-05-1').number('m_rms_mm'), 2)} мм"
        out.append(s + " (раздел 5)")
    if done("task-06-2") and done("task-06-2").number("k_mean") is not None:
        out.append(f"коэффициент редуцирования ряда {w.n(done('task-06-2').number('k_mean'), 4)} (раздел 6)")
    if done("task-07-2") and done("task-07-2").number("dhD_m") is not None:
        out.append(f"высоты объектов по параллаксам — до {w.n(done('task-07-2').number('dhD_m'), 1)} м (раздел 7)")
    if done("task-10-1") and done("task-10-1").number("X_m") is not None:
        x = done("task-10-1")
        out.append(f"координаты опознака X = {w.n(x.number('X_m'), 2)} м, Y = {w.n(x.number('Y_m'), 2)} м "
                   "(раздел 10)")
    if done("task-11-1") and done("task-11-1").number("t_mm") is not None:
        out.append(f"толщина подложки при трансформировании {w.n(done('task-11-1').number('t_mm'), 2)} мм (раздел 11)")
    if done("task-12-1") and done("task-12-1").number("n_max") is not None:
        out.append(f"опознаки фототриангуляции — через {w.count(done('task-12-1').number('n_max'))} базиса (раздел 12)")
    if done("task-17-3") and isinstance(done("task-17-3").get("vd_mm"), (int, float)):
        out.append(f"средняя ошибка обновлённой карты {w.n(done('task-17-3').get('vd_mm'), 2)} мм (раздел 17)")
    del v
    return out


def conclusion(doc, w, T) -> None:
    doc.heading(1, w.L("Заключение", "Conclusion"), structural=True, newpage=True)
    w.par("В курсовой работе по материалам аэрофотосъёмки участка выполнен полный цикл фотограмметрических работ, "
          "предусмотренный руководством [1]: от расчёта параметров съёмки и оценки качества снимков до "
          "фототрансформирования, фототриангуляции и дешифрирования. Основные результаты варианта:",
          "The work covers the full cycle of the guide [1]. The variant's key results:")
    res = _key_results(w, T)
    if res:
        doc.items([r[0].upper() + r[1:] + ("." if k == len(res) - 1 else ";") for k, r in enumerate(res)])
    not_done = [x.label for x in T.values() if not x.attempted]
    failed = [x.label for x in T.values() if x.state in ("failed", "partial", "unreadable")]
    if not_done:
        w.par(f"Не выполнены задачи {', '.join(not_done)}; соответствующие разделы записки не содержат результатов.",
              f"Not done: {', '.join(not_done)}.")
    if failed:
        w.par(f"Результаты задач {', '.join(failed)} не подтверждены проверкой рабочей тетради и требуют исправления.",
              f"Not confirmed by the workbook's checks: {', '.join(failed)}.")
    w.par("Полученные материалы — фотосхема, откорректированный план, проект привязки, трансформированные снимки и "
          "результаты сгущения опорной сети — пригодны для решения землеустроительных и кадастровых задач в пределах "
          "точности, оценённой в разделах записки.",
          "The products are fit for land-management tasks within the accuracy assessed in the note.")


# =========================================================================== the appendices
_GRAPHICS = (("Фотосхема", [("05", "fotoschema_cuts")], True),
             ("Калька с корректировочными данными", [("05", "correction")], False),
             ("Калька с дешифровочными данными", [("08", "interpretation_photo")], False),
             ("Калька с вариантами корректировки участка плана землепользования", [("09", "grids")], False),
             ("Калька с аппроксимирующими элементами по выбранному варианту", [], False),
             ("Калька проекта привязки аэроснимков", [("10", "control_design"), ("10", "resection")], False),
             ("Калька направлений и план с трансформированными точками", [("11", "rectified")], False),
             ("Восковка направлений (4 шт.) и общая восковка", [("06", "free_strip"), ("12", "free_strip")], False))


def appendices(doc, w, T, statuses, opts, day, lang, build_dir: Path, out: Path, drawn: dict, want_sheet: bool):
    from .sheet import made_by_text, sheet_pdf

    ru = lang == "ru"
    info: dict = {}
    doc.heading(1, "Приложение А. Фотосхема" if ru else "Appendix A. The fotoschema", structural=True, newpage=True)
    t = T.get("task-05-2")
    m = t.number("m_mean") if t is not None else None
    if not want_sheet:
        w.par("Лист фотосхемы не строился.", "The sheet was not drawn.", "note")
    elif m is None or not 1000 <= m <= 1e6:
        w.par("Лист фотосхемы подписывается средним масштабом из задачи 05.2; задача не выполнена — лист не построен.",
              "The sheet carries the mean scale of task 05.2, which is not done.", "missing")
    else:
        figs = Path(build_dir) / "figures"
        figs.mkdir(exist_ok=True)
        s = sheet_pdf(w.v, m, figs / "fotoschema.pdf", made_by=made_by_text(opts["student"], opts["group"]),
                      checked_by=opts["checked_by"], year=day.year)
        info["sheet_pdf"] = Path(shutil.copy2(s["pdf"], out / "fotoschema.pdf"))
        info["paper"] = s["paper"]
        wmm, hmm = s["size_mm"]
        w.par(f"Фотосхема маршрута снимков 36–39, подписанная средним масштабом М {w.scale(round(m / 100) * 100)}, "
              f"дана на следующей странице на листе формата {s['paper']} ({w.n(wmm, 0)} × {w.n(hmm, 0)} мм) в "
              "натуральную величину; печатать в масштабе 100 %." + ("" if t.passed else
                                                                  " Задача 05.2 не прошла проверку тетради."),
              f"The sheet follows on an {s['paper']} page at true size; print at 100 %.")
        doc.page("figures/fotoschema.pdf", wmm, hmm)
    doc.heading(1, "Приложение Б. Графические материалы" if ru else "Appendix B. The graphic materials",
                structural=True, newpage=True)
    w.par("Графические материалы, перечисленные в задании на курсовую работу (пособие, §1), и рисунки записки, "
          "которые их содержат:", "The graphic materials of the assignment and the figures that hold them:")
    rows = []
    for k, (name, where, sheet) in enumerate(_GRAPHICS, start=1):
        nums = [n for key in where for n in drawn.get(key, [])]
        cell = ", ".join(f"рис. {n}" for n in nums) if nums else "—"
        if sheet and info.get("sheet_pdf"):
            cell = "приложение А" + (f"; {cell}" if nums else "")
        rows.append([str(k), name, cell])
    w.table("Графические материалы курсовой работы", "The graphic materials",
            [[w.L("№", "No."), w.L("Материал", "Material"), w.L("Где в записке", "Where")]], rows,
            widths=[0.5, 5, 2.2], align=["center", "left", "left"])
    doc.heading(1, "Приложение В. Проверка заданий в рабочей тетради" if ru else "Appendix C. The workbook's checks",
                structural=True, newpage=True)
    state_ru = {"passed": "проверка пройдена", "failed": "ошибка", "partial": "частично",
                "unreadable": "не читается без запуска", "not_started": "не выполнено"}
    rows = [[x.label, state_ru[x.state]] for x in T.values()]
    w.table("Состояние заданий рабочей тетради", "The tasks' state",
            [[w.L("Задача", "Task"), w.L("Состояние", "State")]], rows, widths=[1, 3], align=["center", "left"])
    return info
