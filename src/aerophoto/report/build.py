"""Assemble the student's course report from their workbook (see :mod:`aerophoto.report`)."""

from __future__ import annotations

import datetime as _dt
import re
import shutil
from dataclasses import dataclass, field
from pathlib import Path

from .answers import UNREADABLE, read_notebook
from .document import Document, compile_pdf, write_html
from .sections import ASSIGNMENT, SECTIONS, chapters_by_section

__all__ = ["build", "Report", "TaskStatus", "ChapterStatus", "read_workbook", "DEFAULTS"]

#: the title page's defaults (the guide's university and department; every one can be given to build())
DEFAULTS = {
    "ministry": "Министерство науки и высшего образования Российской Федерации",
    "university": "Пензенский государственный университет архитектуры и строительства",
    "department": "Кафедра «Землеустройство и геодезия»",
    "course": "Фотограмметрия",
    "place": "Пенза",
}

NOT_DONE = "не выполнено (not done)"
#: the folder beside report.pdf with the figures, report.json and the Typst source (rewritten on every build)
BUILD_DIR = "report_files"
_MARKER = ".aerophoto-report"

_STATE_RU = {
    "passed": "выполнено (passed)",
    "failed": "ошибка (the check fails)",
    "partial": "частично (partly answered)",
    "unreadable": "не читается без запуска (not readable without running)",
    "not_started": NOT_DONE,
}


@dataclass(frozen=True)
class TaskStatus:
    """One task of the student's workbook, read without running and checked by the trusted check.

    ``state``: passed, failed, partial, unreadable or not_started.  ``values``: the student's readable
    answers; ``unreadable``: name → what it needs; ``checks``: name → (ok, message) of the visible checks;
    ``message``: the first failing visible check's message.
    """

    task: str
    title: str
    chapter: str
    state: str
    values: dict = field(default_factory=dict)
    unreadable: dict = field(default_factory=dict)
    checks: dict = field(default_factory=dict)
    message: str = ""

    @property
    def attempted(self) -> bool:
        return self.state != "not_started"


@dataclass(frozen=True)
class ChapterStatus:
    """A chapter of the registry in the student's workbook: its notebook (or None) and its tasks' status."""

    chapter: object
    notebook: Path | None
    tasks: tuple = ()
    problem: str = ""

    @property
    def number(self) -> str:
        return self.chapter.number

    @property
    def attempted(self) -> bool:
        return any(t.attempted for t in self.tasks)

    @property
    def state(self) -> str:
        if not self.tasks:
            return "no_tasks"
        if all(t.state == "passed" for t in self.tasks):
            return "done"
        return "in_progress" if self.attempted else "not_done"


@dataclass(frozen=True)
class Report:
    """What :func:`build` wrote: the PDF, the HTML page, the sheet, the build folder, and what it read."""

    pdf: Path | None
    html: Path | None
    sheet_pdf: Path | None
    sheet_png: Path | None
    sheet_paper: str | None
    build_dir: Path
    record_book: str
    variant: object
    chapters: tuple

    def __repr__(self) -> str:
        states = [t.state for ch in self.chapters for t in ch.tasks]
        return (f"Report(record_book={self.record_book!r}, variant={self.variant.i:02d}, pdf={self.pdf}, "
                f"sheet={self.sheet_pdf}, passed={states.count('passed')}/{len(states)})")

    def task(self, task_id: str) -> TaskStatus:
        for ch in self.chapters:
            for t in ch.tasks:
                if t.task == task_id:
                    return t
        raise KeyError(task_id)

    def _repr_html_(self) -> str:  # shown in a notebook cell
        import html

        links = [f'<a href="{html.escape(str(p))}">{html.escape(p.name)}</a>'
                 for p in (self.pdf, self.html, self.sheet_pdf) if p]
        return f"<p>Course report of record book {html.escape(self.record_book)}: {' · '.join(links)}</p>"


# =========================================================================== reading the workbook
def _chapter_notebook(workbook: Path, ch) -> Path | None:
    """``NN_slug.ipynb`` in the workbook, or ``NN_slug/NN_slug.ipynb`` (a student's folder of nbgrader's
    ``submitted/``), or another ``NN_*.ipynb`` (never an ``.updated-`` copy)."""
    name = f"{ch.number}_{ch.slug}"
    for exact in (workbook / f"{name}.ipynb", workbook / name / f"{name}.ipynb"):
        if exact.is_file():
            return exact
    cands = sorted(p for p in workbook.glob(f"{ch.number}_*.ipynb") if ".updated-" not in p.name)
    return cands[0] if cands else None


def _registry_tasks(number: str) -> tuple[tuple, str]:
    """The chapter's graded tasks and, when they cannot be loaded (a chapter being written), why."""
    from .. import gradebook

    if not gradebook.has_tasks(number):
        return (), ""
    try:
        return tuple(gradebook.chapter_tasks(number)), ""
    except Exception as exc:  # one broken chapter must not keep the student from the rest of the report
        return (), f"the chapter's tasks could not be loaded ({type(exc).__name__})"


def _resolve_record_book(record_book, books: dict) -> str:
    from ..variants import index_from_record_book

    if record_book is not None:
        index_from_record_book(record_book)  # ValueError naming record_book when it has < 2 digits
        return str(record_book).strip()
    found = sorted({rb for rb in books.values() if rb})
    usable = []
    for rb in found:
        try:
            index_from_record_book(rb)
            usable.append(rb)
        except ValueError:
            pass
    if not usable:
        raise ValueError("record_book = None and no notebook of the workbook has RECORD_BOOK set in its first cell; "
                         "type it in chapter 00's first cell or pass record_book (--record-book), e.g. '19-0457'")
    if len(usable) > 1:
        where = ", ".join(f"{name}: {rb}" for name, rb in sorted(books.items()) if rb)
        raise ValueError(f"record_book: the notebooks name different record-book numbers ({where}); "
                         "pass the right one as record_book (--record-book)")
    return usable[0]


def _task_status(t, v, env: dict) -> TaskStatus:
    from ..course.score import grade_task

    raw = {n: env.get(n, Ellipsis) for n in t.names}
    unread = {n: x.reason for n, x in raw.items() if isinstance(x, UNREADABLE)}
    values = {n: x for n, x in raw.items() if x is not Ellipsis and not isinstance(x, UNREADABLE)}
    if not values and not unread:
        return TaskStatus(t.id, t.title, t.chapter, "not_started")
    if unread:
        return TaskStatus(t.id, t.title, t.chapter, "unreadable", values, unread,
                          message="; ".join(f"{n}: needs {r}" for n, r in unread.items()))
    grade = grade_task(t.id, v, {n: values.get(n, Ellipsis) for n in t.names})
    checks = {name: (ok, _clean(msg)) for name, ok, msg, hidden in grade.checks if not hidden}
    visible_ok = grade.visible_ok
    first = next((msg for ok, msg in checks.values() if not ok), "")
    if len(values) < len(t.names):
        state = "partial"
    else:
        state = "passed" if visible_ok else "failed"
    return TaskStatus(t.id, t.title, t.chapter, state, values, {}, checks, first)


def _clean(msg: str) -> str:
    return re.sub(r"\x1b\[[0-9;]*m", "", str(msg or "")).strip()


def read_workbook(workbook_dir, record_book=None, *, chapters=None) -> tuple:
    """Read and check every chapter of a workbook: ``(record_book, variant, (ChapterStatus, …))``.

    Nothing of the workbook is run: see :mod:`aerophoto.report.answers`.  The variant is the one of
    ``record_book`` (default: the notebooks' own ``RECORD_BOOK``, which must agree).
    """
    from ..book import CHAPTERS
    from ..variants import variant

    workbook = _folder("workbook_dir", workbook_dir)
    chapters = tuple(CHAPTERS if chapters is None else chapters)
    read = {}
    for ch in chapters:
        nb = _chapter_notebook(workbook, ch)
        tasks, why = _registry_tasks(ch.number)
        read[ch.number] = (nb, tasks, read_notebook(nb, [t.id for t in tasks]) if nb else None, why)
    books = {r[0].name: r[2].record_book for r in read.values() if r[2] is not None and r[2].record_book}
    rb = _resolve_record_book(record_book, books)
    v = variant(rb)
    out = []
    for ch in chapters:
        nb, tasks, ans, why = read[ch.number]
        if why:
            out.append(ChapterStatus(ch, nb, (), why))
            continue
        if ans is None:
            out.append(ChapterStatus(ch, None, tuple(TaskStatus(t.id, t.title, t.chapter, "not_started")
                                                     for t in tasks), "no notebook in the workbook"))
            continue
        envs = ans.values(v) if not ans.problem else {}
        out.append(ChapterStatus(ch, nb, tuple(_task_status(t, v, envs.get(t.id, {})) for t in tasks), ans.problem))
    return rb, v, tuple(out)


# =========================================================================== formatting
def fmt(x) -> str:
    """A student's value as text: up to 6 significant digits, lists joined with "; "."""
    if isinstance(x, bool):
        return "да (True)" if x else "нет (False)"
    if isinstance(x, int):
        return str(x)
    if isinstance(x, float):
        return f"{x:.6g}"
    if isinstance(x, (list, tuple)):
        items = [fmt(e) for e in x[:60]]
        return "; ".join(items) + (" …" if len(x) > 60 else "")
    if x is None:
        return "None"
    s = str(x)
    return s if len(s) <= 200 else s[:200] + "…"


def _folder(name: str, path) -> Path:
    if path is None or str(path).strip() == "":
        raise ValueError(f"{name} = {path!r}: give the folder")
    p = Path(path)
    if not p.is_dir():
        raise ValueError(f"{name} = {str(p)!r} is not a folder")
    return p


def _date(date) -> _dt.date:
    if date is None:
        return _dt.date.today()
    if isinstance(date, _dt.datetime):
        return date.date()
    if isinstance(date, _dt.date):
        return date
    try:
        return _dt.date.fromisoformat(str(date))
    except ValueError:
        raise ValueError(f"date = {date!r} is not a date; expected the form YYYY-MM-DD, e.g. '2026-12-15'") from None


def _text(name: str, value, limit: int = 200) -> str:
    if value is None:
        return ""
    if not isinstance(value, str):
        raise ValueError(f"{name} = {value!r} must be text")
    s = re.sub(r"[\x00-\x1f\x7f]", " ", value).strip()
    if len(s) > limit:
        raise ValueError(f"{name} is {len(s)} characters long; the valid range is up to {limit}")
    return s


# =========================================================================== the document
def _title_page(opts: dict, rb: str, v, date: _dt.date) -> dict:
    rows = [["Выполнил (student)", opts["student"] or "________________"]]
    if opts["group"]:
        rows.append(["Группа (group)", opts["group"]])
    rows += [["Зачётная книжка (record book)", rb], ["Вариант (variant)", f"{v.i:02d}"],
             ["Проверил (checked by)", opts["checked_by"] or "________________"],
             ["Дата (date)", date.isoformat()]]
    return {
        "ministry": opts["ministry"], "university": opts["university"], "department": opts["department"],
        "work_ru": "КУРСОВАЯ РАБОТА", "discipline_ru": f"по дисциплине «{opts['course']}»",
        "note_ru": "Пояснительная записка", "work_en": f"Course design in {opts['course_en']}: explanatory note",
        "rows": rows, "place": f"{opts['place']} {date.year}",
        "generated": "Составлено из рабочей тетради студента пакетом aerophoto "
                     "(assembled from the student's own workbook)",
    }


def _inputs_table(doc: Document, t, v) -> None:
    """The task's inputs when they are a small table (what the student works from; never an answer)."""
    import pandas as pd

    from .. import gradebook

    try:
        inp = gradebook.task_inputs(t.task, v)
    except Exception:  # an input the package cannot give is left out, never guessed
        return
    if isinstance(inp, pd.Series):
        inp = inp.to_frame()
    if not isinstance(inp, pd.DataFrame) or inp.empty or len(inp) > 40 or inp.shape[1] > 7:
        return
    df = inp.reset_index() if inp.index.name or not isinstance(inp.index, pd.RangeIndex) else inp
    rows = [[fmt(x.item() if hasattr(x, "item") else x) for x in r] for r in df.itertuples(index=False)]
    aligns = ["right" if pd.api.types.is_numeric_dtype(df[c]) else "left" for c in df.columns]
    doc.table(f"Задача {_label(t.task)}: исходные данные (inputs)", [str(c) for c in df.columns], rows,
              align=aligns)


def _label(task_id: str) -> str:
    p = task_id.split("-")
    return f"{p[1]}.{p[2]}" if len(p) >= 3 else task_id


def _task_block(doc: Document, t: TaskStatus, v) -> None:
    from .. import gradebook

    task = gradebook.task(t.task)
    doc.heading(3, f"Задача {_label(t.task)}", t.title)
    if not t.attempted:
        doc.par(NOT_DONE, "missing")
        return
    _inputs_table(doc, t, v)
    rows = []
    for a in task.spec:
        if a.name in t.values:
            val = fmt(t.values[a.name])
        elif a.name in t.unreadable:
            val = "не читается без запуска (not readable without running)"
        else:
            val = "нет ответа (no answer yet)"
        ok = t.checks.get(a.name)
        mark = "—" if ok is None else ("✓" if ok[0] else "✗")
        rows.append([a.name, a.text, a.unit, val, mark])
    doc.table(f"Задача {_label(t.task)}: ваши ответы (your answers) — {_STATE_RU[t.state]}",
              ["Величина (quantity)", "Что это (what)", "Ед. (unit)", "Ваше значение (your value)",
               "Проверка (check)"], rows, align=["left", "left", "left", "right", "left"], widths=[14, 30, 7, 26, 9])
    if t.state == "passed":
        doc.par(f"✓ Задача {_label(t.task)} проверена (passed the check).", "ok")
    elif t.state == "unreadable":
        for name, why in t.unreadable.items():
            doc.par(f"{name}: не читается без запуска — нужен {why} (not readable without running; write the "
                    "value or an expression of numbers, math.* and v.*)", "bad")
    elif t.message:
        doc.par(f"✗ {t.message}", "bad")


def _chapter_block(doc: Document, cs: ChapterStatus, v, build_dir: Path, figures: bool) -> None:
    from .figures import CHAPTER_FIGURES

    ch = cs.chapter
    doc.heading(2, f"Глава {ch.number}: {ch.title_ru}", ch.title)
    if not cs.tasks:
        if cs.problem:
            doc.par(f"{NOT_DONE} — {cs.problem}", "missing")
        else:
            doc.par("В этой главе нет оцениваемых задач (no graded tasks in this chapter).", "note")
        return
    if not cs.attempted:
        why = " — нет файла в рабочей тетради (no notebook in the workbook)" if cs.notebook is None else ""
        doc.par(NOT_DONE + why, "missing")
        for t in cs.tasks:
            doc.par(f"Задача {_label(t.task)} — {t.title}: {NOT_DONE}", "note")
        return
    doc.par(f"Тетрадь (notebook): {cs.notebook.name}. Задачи выполнены (tasks passed): "
            f"{sum(t.state == 'passed' for t in cs.tasks)} из {len(cs.tasks)}.", "note")
    if figures and ch.number in CHAPTER_FIGURES:
        folder = build_dir / "figures"
        folder.mkdir(exist_ok=True)
        try:
            drawn = CHAPTER_FIGURES[ch.number](v, folder)
        except Exception as exc:  # a figure that cannot be drawn must not cost the student the report
            drawn = []
            doc.par(f"Рисунки главы не построены (the chapter's figures could not be drawn: {type(exc).__name__}).",
                    "note")
        for src, caption, width in drawn:
            doc.figure(src, caption, width)
    for t in cs.tasks:
        _task_block(doc, t, v)


def _section(doc: Document, sec, chapters, statuses: dict, v, build_dir: Path, figures: bool) -> None:
    num = f"{sec.number}." if sec.number else ""
    doc.heading(1, sec.ru, sec.en, num)
    if not chapters:
        doc.par(NOT_DONE + " — в книге пока нет главы к этому разделу (the book has no chapter for this "
                "section yet)", "missing")
        return
    if sec.formula and any(statuses[c.number].attempted for c in chapters):
        doc.math(*sec.formula)
    for ch in chapters:
        _chapter_block(doc, statuses[ch.number], v, build_dir, figures)


def _summary(doc: Document, statuses) -> None:
    doc.heading(1, "Сводка выполнения", "Summary of the work")
    names = {"done": "выполнено (done)", "in_progress": "частично (in progress)", "not_done": NOT_DONE,
             "no_tasks": "нет задач (no graded tasks)"}
    rows = []
    for cs in statuses:
        if not cs.tasks:
            continue
        passed = sum(t.state == "passed" for t in cs.tasks)
        rows.append([cs.number, cs.chapter.title_ru, f"{passed} / {len(cs.tasks)}", names[cs.state]])
    doc.table("Задачи по главам (tasks passed, chapter by chapter)",
              ["Глава (chapter)", "Тема (topic)", "Задачи (passed)", "Состояние (state)"], rows,
              align=["left", "left", "right", "left"], widths=[9, 40, 10, 20])


def build(workbook_dir, out_dir=None, *, student: str = "", record_book=None, group: str = "",
          checked_by: str = "", date=None, university: str | None = None, department: str | None = None,
          ministry: str | None = None, place: str | None = None, sheet: bool = True, figures: bool = True,
          formats=("pdf", "html")) -> Report:
    """Assemble the student's course report (guide §15) and fotoschema sheet from their workbook.

    Parameters
    ----------
    workbook_dir : the folder of the student's notebooks (``workbook/``); read, never run
    out_dir : where to write (default ``<workbook_dir>/report``): ``report.pdf``, ``report.html``,
        ``fotoschema.pdf`` (the sheet at true size) and ``report_files/`` (the figures, the JSON, the Typst
        source; rewritten on every build)
    student, group, checked_by : names for the title page and the sheet's marginalia
    record_book : the record-book number whose variant is graded (default: the notebooks' RECORD_BOOK)
    date : the report's date (``datetime.date`` or ``"YYYY-MM-DD"``; default today) — fix it for
        reproducible files
    university, department, ministry, place : the title page (defaults: :data:`DEFAULTS`, the guide's)
    sheet, figures : whether to draw the fotoschema sheet and the chapters' figures
    formats : any of ``"pdf"``, ``"html"``

    Returns a :class:`Report`.  Bad input raises ValueError naming the parameter.
    """
    workbook = _folder("workbook_dir", workbook_dir)
    formats = tuple(formats)
    bad = [f for f in formats if f not in ("pdf", "html")]
    if bad or not formats:
        raise ValueError(f"formats = {formats!r}; the valid values are 'pdf' and 'html' (at least one)")
    day = _date(date)
    opts = {"student": _text("student", student), "group": _text("group", group),
            "checked_by": _text("checked_by", checked_by),
            "university": _text("university", university) or DEFAULTS["university"],
            "department": _text("department", department) or DEFAULTS["department"],
            "ministry": _text("ministry", ministry) or DEFAULTS["ministry"],
            "place": _text("place", place) or DEFAULTS["place"],
            "course": DEFAULTS["course"], "course_en": "photogrammetry"}
    out = Path(out_dir) if out_dir is not None else workbook / "report"
    if out.exists() and not out.is_dir():
        raise ValueError(f"out_dir = {str(out)!r} is a file, not a folder")
    rb, v, statuses = read_workbook(workbook, record_book)
    build_dir = _fresh_build_dir(out)
    by_number = {cs.number: cs for cs in statuses}

    doc = Document(_title_page(opts, rb, v, day),
                   {"title": f"Курсовая работа по фотограмметрии — {opts['student'] or rb}",
                    "author": opts["student"] or rb, "date": [day.year, day.month, day.day]})
    by_section, others = chapters_by_section([cs.chapter for cs in statuses])
    # the assignment: the variant's inputs (the student's own data) and chapter 00
    doc.heading(1, ASSIGNMENT.ru, ASSIGNMENT.en)
    doc.par(f"Вариант {v.i:02d} — последние две цифры номера зачётной книжки {rb} (guide §1: the variant is the "
            "last two digits of the record-book number).")
    vt = v.table()
    doc.table("Исходные данные варианта (the inputs of your variant, guide §1)",
              ["Величина (quantity)", "Ед.", "Значение"],
              [[str(q), str(r["unit"]), fmt(r["value"].item() if hasattr(r["value"], "item") else r["value"])]
               for q, r in vt.iterrows()], align=["left", "left", "right"], widths=[40, 6, 14])
    for ch in by_section.get(ASSIGNMENT.guide, []):
        _chapter_block(doc, by_number[ch.number], v, build_dir, figures)
    for sec in SECTIONS:
        _section(doc, sec, by_section.get(sec.guide, []), by_number, v, build_dir, figures)
    if others:
        doc.heading(1, "Дополнительные главы", "Further chapters (articles)")
        for ch in others:
            _chapter_block(doc, by_number[ch.number], v, build_dir, figures)
    _summary(doc, statuses)

    # the graphic material: the fotoschema sheet (guide §15, appendix 1)
    sheet_info = _sheet(doc, by_number.get("05"), v, out, build_dir, opts, day, sheet)

    pdf = html = None
    if "pdf" in formats:
        pdf = compile_pdf(doc, build_dir, out / "report.pdf")
    else:
        (build_dir / "report.json").write_text(doc.as_json() + "\n", encoding="utf-8")
    if "html" in formats:
        html = write_html(doc, out / "report.html", prefix=f"{BUILD_DIR}/")
    return Report(pdf, html, sheet_info.get("pdf"), sheet_info.get("png"), sheet_info.get("paper"), build_dir, rb,
                  v, statuses)


def _fresh_build_dir(out: Path) -> Path:
    """``<out>/report_files``, emptied — only when this command wrote it (its marker file is there)."""
    out.mkdir(parents=True, exist_ok=True)
    build_dir = out / BUILD_DIR
    if build_dir.exists():
        if not (build_dir / _MARKER).is_file():
            raise ValueError(f"out_dir = {str(out)!r} holds a folder {BUILD_DIR}/ that the report did not write; "
                             "choose another out_dir")
        shutil.rmtree(build_dir)
    build_dir.mkdir()
    (build_dir / _MARKER).write_text("written by aerophoto.report; rewritten on every build\n", encoding="utf-8")
    return build_dir


def _sheet(doc: Document, cs, v, out: Path, build_dir: Path, opts: dict, day: _dt.date, want: bool) -> dict:
    doc.pagebreak()
    doc.heading(1, "Приложение 1. Фотосхема", "Appendix 1: the fotoschema sheet")
    task = None if cs is None else next((t for t in cs.tasks if t.task == "task-05-2"), None)
    m_mean = None if task is None else task.values.get("m_mean")
    usable = isinstance(m_mean, (int, float)) and not isinstance(m_mean, bool) and 1000 <= float(m_mean) <= 1e6
    if not want:
        doc.par("Лист фотосхемы не строился (the sheet was not drawn: sheet=False).", "note")
        return {}
    if task is None or not usable:
        doc.par(NOT_DONE + " — фотосхема подписывается средним масштабом из задачи 05.2; ответьте на неё "
                "(the sheet is signed with the mean scale of task 05.2: answer it first)", "missing")
        return {}
    figs = build_dir / "figures"
    figs.mkdir(exist_ok=True)
    info = _sheet_files(v, float(m_mean), figs, opts, day)
    pdf = Path(shutil.copy2(info["pdf"], out / "fotoschema.pdf"))
    w, h = info["size_mm"]
    m_txt = f"{int(round(float(m_mean) / 100.0) * 100):,}".replace(",", " ")
    state = "" if task.state == "passed" else \
        " Внимание: задача 05.2 не прошла проверку (task 05.2 does not pass its check)."
    doc.par(f"Фотосхема вашего маршрута подписана вашим средним масштабом М 1:{m_txt}; лист формата {info['paper']} "
            f"({w:g} × {h:g} мм) в натуральную величину — файл fotoschema.pdf (print it at 100 %, the sheet is at "
            f"true size).{state}")
    doc.figure("figures/fotoschema.png", f"Фотосхема (уменьшено), лист {info['paper']} (the sheet, reduced)", 1.0)
    return {"pdf": pdf, "png": info["png"], "paper": info["paper"]}


def _sheet_files(v, m_mean: float, folder: Path, opts: dict, day: _dt.date) -> dict:
    from .figures import sheet_files

    made_by = opts["student"] + (f", ст. гр. {opts['group']}" if opts["group"] else "")
    return sheet_files(v, m_mean, folder, made_by=made_by, checked_by=opts["checked_by"], year=day.year)
