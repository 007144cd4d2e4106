"""The note's frame: title page, contents, introduction, the sections in §15's order, conclusion, sources, appendices.

:func:`write_note` turns the checked workbook (:func:`aerophoto.report.build.read_workbook`) into a
:class:`~aerophoto.report.document.Document`: each section is written by its chapter's writer
(:mod:`aerophoto.report.sections`) from the student's own values; the introduction states the task and the
variant's inputs; the conclusion gathers the student's key results; the sources are the guide, the four articles,
the standards and the software the note was made with; the appendices hold the fotoschema sheet at true size
(appendix А, the guide's appendix 1), the list of the guide's graphic materials with the figures that answer
them (Б) and the state of every task in the workbook (В).
"""

from __future__ import annotations

from pathlib import Path

from .document import Document
from .prose import TaskView, Writer

__all__ = ["write_note", "sources"]


def _task_views(statuses, v) -> dict:
    """task id → :class:`TaskView` (inputs read through the chapter writer's extractor, cached)."""
    from .facts import inputs
    from .sections import extractors

    ex = extractors()
    out = {}
    for cs in statuses:
        specs = {t["id"]: t for t in cs.specs}
        for t in cs.tasks:
            spec = specs.get(t.task, {"spec": []})
            inp = inputs(t.task, v, ex[t.task]) if t.attempted and t.task in ex else {}
            out[t.task] = TaskView(t.task, t.title, t.state, dict(t.values), tuple(t.recorded), inp,
                                   dict(t.checks), t.message, tuple(spec["spec"]), dict(t.unreadable))
    return out


def _title_page(opts: dict, rb: str, v, day, lang: str) -> dict:
    ru = lang == "ru"
    group = opts["group"]
    student = (("студент гр. " + group + " ") if group and ru else (f"group {group}, " if group else "")) + \
        (opts["student"] or "________________")
    rows = [["Выполнил:" if ru else "Student:", student],
            ["Зачётная книжка:" if ru else "Record book:", f"№ {rb}, " + ("вариант" if ru else "variant") +
             f" {v.i:02d}"],
            ["Руководитель:" if ru else "Supervisor:", opts["checked_by"] or "________________"],
            ["Работа защищена:" if ru else "Defended:", "«___» ____________ " + str(day.year) + (" г." if ru else "")],
            ["Оценка:" if ru else "Mark:", "________________"]]
    if ru:
        return {"ministry": opts["ministry"], "university_form": DEFAULTS_FORM, "university": opts["university"],
                "department": opts["department"], "work": "Курсовая работа",
                "discipline": "по дисциплине «Фотограмметрия»", "topic_label": "на тему", "topic": opts["topic"],
                "note": "Пояснительная записка", "rows": rows, "place_year": f"{opts['place']} {day.year}"}
    return {"ministry": "Ministry of Science and Higher Education of the Russian Federation",
            "university_form": "", "university": "Penza State University of Architecture and Construction",
            "department": "Department of Land Management and Geodesy", "work": "Course design",
            "discipline": "in photogrammetry", "topic_label": "topic",
            "topic": "Photogrammetric processing of an aerial survey", "note": "Explanatory note", "rows": rows,
            "place_year": f"Penza {day.year}"}


DEFAULTS_FORM = "Федеральное государственное бюджетное образовательное учреждение высшего образования"


def _introduction(doc: Document, w: Writer, rb: str, statuses) -> None:
    v = w.v
    doc.heading(1, w.L("Введение", "Introduction"), structural=True, newpage=True)
    w.par("Курсовая работа выполнена по руководству В. В. Преснякова и Е. П. Тюкленковой [1]: по материалам "
          "аэрофотосъёмки рассчитаны параметры съёмки, оценено качество снимков, определены смещения точек за рельеф "
          "и за наклон снимка, изготовлена одномаршрутная фотосхема, построен и редуцирован фототриангуляционный ряд, "
          "изучена стереомодель, выполнены дешифрирование, корректировка плана, проект привязки, "
          "фототрансформирование, фототриангуляция и почвенное дешифрирование; четыре дополнительных раздела "
          "посвящены точности фототриангуляции, аэрофотопривязке, рисовке горизонталей по цифровой модели рельефа и "
          "точности обновления карт [2–5]. Снимки, планы и стереопары получены в рабочей тетради по виртуальному "
          "испытательному полигону, сфотографированному точной моделью центральной проекции, поэтому каждый "
          "результат можно сравнить с истинным положением точек местности.",
          "The course design follows the guide of Presnyakov and Tyuklenkova [1]; four more sections follow the "
          "articles [2–5]. The photos come from the workbook's virtual test site.")
    w.par(f"Вариант задания i = {v.i:02d} — две последние цифры номера зачётной книжки {rb}. Исходные данные "
          "варианта (пособие, §1):", f"Variant i = {v.i:02d}, the last two digits of record book {rb}. Inputs:")
    i = v.i
    items = [
        [{"text": w.L("скорость самолёта ", "aircraft speed ")},
         {"math": f'W = 200 + 10 dot {i} = "{w.n(v.W_kmh, 0)}" " км/ч"'}],
        [{"text": w.L("размер кадра ", "frame ")}, {"math": f'l times l = "{w.n(v.frame_mm / 10, 0)}" times '
                                                         f'"{w.n(v.frame_mm / 10, 0)}" " см"'}],
        [{"text": w.L("фокусное расстояние ", "focal length ")},
         {"math": f'f = 100 + 10 dot {i} = "{w.n(v.f_mm, 0)}" " мм"'}],
        [{"text": w.L("масштаб аэрофотосъёмки ", "photo scale ")},
         {"math": f'1/m = 1/(12 thin 000 + 100 dot {i}) = "{w.scale(v.m)}"'}],
        [{"text": w.L("масштаб фотоплана ", "photoplan scale ")}, {"math": f'1/M = "{w.scale(v.M)}"'}],
        [{"text": w.L("нормативные перекрытия ", "overlaps ")},
         {"math": f'p_x = "{w.n(v.px_percent, 0)}" " %", quad p_y = "{w.n(v.py_percent, 0)}" " %"'}],
        [{"text": w.L("размеры участка ", "area ")},
         {"math": f'L_x = 25 + {i} = "{w.n(v.Lx_km, 0)}" " км", quad L_y = 30 + {i} = "{w.n(v.Ly_km, 0)}" " км"'}],
        [{"text": w.L("высоты участка ", "heights ")},
         {"math": f'Z_"max" = 200 + {i} = "{w.n(v.Zmax_m, 0)}" " м", quad Z_"min" = 170 + {i} = '
                  f'"{w.n(v.Zmin_m, 0)}" " м"'}],
        [{"text": w.L("угол наклона снимка и угол поворота в его плоскости ", "tilt and swing ")},
         {"math": f'alpha = "{w.n(v.alpha_deg, 0)}"°, quad lambda = -60° + {i}° = "{w.n(v.lambda_deg, 0)}"°'}],
    ]
    doc.items(items)
    done = sum(1 for cs in statuses for t in cs.tasks if t.state == "passed")
    total = sum(len(cs.tasks) for cs in statuses)
    w.par(f"Пояснительная записка содержит 13 разделов, предусмотренных §15 пособия, и разделы 14–17 по статьям. "
          f"Расчёты выполнены в рабочей тетради; из {total} заданий проверку тетради прошли {done}. Таблицы 1–13 "
          "имеют номера таблиц пособия; дополнительные таблицы нумеруются начиная с 14. Лист фотосхемы дан в "
          "приложении А в натуральную величину.",
          f"13 sections after §15 and sections 14–17 on the articles; {done} of {total} tasks pass. Tables 1–13 "
          "keep the guide's numbers; extra tables start at 14.")


def _generic(w: Writer, T: dict) -> None:
    """A chapter without a writer of its own: each task's values in a plain table."""
    for tid, t in T.items():
        w.sub(t.title, t.title)
        if not t.attempted:
            w.not_done(t)
            continue
        rows = []
        for k, a in enumerate(t.spec, start=1):
            x = t.get(a["name"])
            if isinstance(x, (list, tuple)):
                val = "; ".join(w.n(e) if isinstance(e, (int, float)) else str(e) for e in x)
            elif isinstance(x, bool):
                val = w.yes(x)
            elif isinstance(x, (int, float)):
                val = w.n(x)
            else:
                val = "—" if x is None else str(x)
            rows.append([str(k), w.unit(a["unit"]), val])
        w.table(f"Результаты задачи {t.label}", f"Results of task {t.label}",
                [[w.L("Ответ", "Answer"), w.L("Ед.", "Unit"), w.L("Значение", "Value")]], rows, widths=[1, 1, 4],
                align=["center", "center", "left"])
        w.check_note(t)


def _section(doc, sec, chapters, views, lang, v, figs, writers) -> None:
    doc.heading(1, sec.ru if lang == "ru" else sec.en, num=str(sec.number), newpage=True)
    w = Writer(doc, lang, v, str(sec.number), figures=None)
    if not chapters:
        w.par("Раздел не выполнен: в рабочей тетради нет главы к этому разделу.",
              "Not done: the workbook has no chapter for this section.", "missing")
        return
    for ch in chapters:
        nums = [ch.number] + [k for k, of in _companions().items() if of == ch.number]
        T = {tid: t for tid, t in views.items() if tid.split("-")[1] in nums}
        w.figures = lambda name, own, _ch=ch.number: figs(_ch, name, own)
        if not any(t.attempted for t in T.values()):
            w.par("Раздел не выполнен: задачи главы в рабочей тетради не решены.",
                  "Not done: the chapter's tasks are not answered.", "missing")
            for t in T.values():
                w.not_done(t)
            continue
        writers.get(ch.number, _generic)(w, T)


def _companions() -> dict:
    from .sections import COMPANIONS

    return COMPANIONS


def write_note(statuses, v, rb, opts, day, lang, build_dir: Path, out: Path, *, figures=True, sheet=True):
    """The note as a :class:`Document`, and ``{"sheet_pdf", "paper", "figures", "leftover"}``."""
    from .appendix import appendices, conclusion, sources_list
    from .figure_draws import specs_for
    from .figures import render
    from .sections import plan, writers

    doc = Document(_title_page(opts, rb, v, day, lang),
                   {"title": ("Курсовая работа по фотограмметрии — " if lang == "ru" else "Course design — ")
                    + (opts["student"] or rb), "author": opts["student"] or rb, "date": [day.year, day.month, day.day],
                    "lang": lang, "contents": "СОДЕРЖАНИЕ" if lang == "ru" else "CONTENTS",
                    "table_word": "Таблица" if lang == "ru" else "Table",
                    "figure_word": "Рисунок" if lang == "ru" else "Figure"})
    doc.outline()
    views = _task_views(statuses, v)
    fig_dir = Path(build_dir) / "figures"
    fig_dir.mkdir(exist_ok=True)
    drawn: dict = {}
    leftover: list = []

    def figs(chapter, name, own):
        spec = specs_for(chapter).get(name)
        if spec is None or not figures:
            return []
        if any(not (views.get(t) and views[t].attempted) for t in spec.attempted + spec.passed):
            return []
        if any(not views[t].passed for t in spec.passed):
            return []
        try:
            path, d = render(spec, v, lang, fig_dir, own)
        except Exception as exc:  # a figure that cannot be drawn must not cost the student the note
            doc.par(("Рисунок не построен: " if lang == "ru" else "The figure could not be drawn: ")
                    + type(exc).__name__, "note")
            return []
        leftover.extend(d.leftover)
        drawn.setdefault((chapter, name), []).append(doc.n_figures + 1)
        return [(f"figures/{path.name}", spec.width)]

    w0 = Writer(doc, lang, v, "0")
    _introduction(doc, w0, rb, statuses)
    wr = writers()
    for sec, chapters in plan([cs.chapter for cs in statuses]):
        _section(doc, sec, chapters, views, lang, v, figs, wr)
    conclusion(doc, w0, views)
    sources_list(doc, lang)
    info = appendices(doc, w0, views, statuses, opts, day, lang, build_dir, out, drawn, sheet)
    info["figures"] = sorted(drawn)
    info["leftover"] = leftover
    return doc, info


def sources() -> list:
    from .appendix import SOURCES

    return list(SOURCES)
