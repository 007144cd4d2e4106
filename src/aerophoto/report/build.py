"""Assemble the student's explanatory note from their workbook (see :mod:`aerophoto.report`).

Reading (:func:`read_workbook`): every chapter's notebook is read as JSON, its answer cells evaluated without
running (:mod:`aerophoto.report.answers`, with the values the check cells recorded where an answer needed package
code), and each task checked by the visible checks (:func:`aerophoto.report.facts.visible_checks`).  Writing
(:func:`build`): the title page, the contents, the introduction, §15's 13 sections and the articles' four, the
conclusion, the sources and the appendices (:mod:`aerophoto.report.frame`), typeset by Typst; the fotoschema sheet
at true size (:mod:`aerophoto.report.sheet`).  On the student's machine the slow parts — the reference worlds
behind the checks, the tasks' data, the figures and the sheet — come from a verified cache
(:mod:`aerophoto.diskcache`), so a second build takes seconds.
"""

from __future__ import annotations

import contextlib
import datetime as _dt
import re
import shutil
from dataclasses import dataclass, field
from pathlib import Path

from .answers import RECORDED, UNREADABLE, read_notebook

__all__ = ["build", "Report", "TaskStatus", "ChapterStatus", "read_workbook", "DEFAULTS", "NOT_DONE"]

#: the title page's defaults (the guide's university and department; every one can be given to build())
DEFAULTS = {
    "ministry": "Министерство науки и высшего образования Российской Федерации",
    "university_form": "Федеральное государственное бюджетное образовательное учреждение высшего образования",
    "university": "«Пензенский государственный университет архитектуры и строительства»",
    "department": "Кафедра «Землеустройство и геодезия»",
    "course": "Фотограмметрия",
    "topic": "Фотограмметрическая обработка материалов аэрофотосъёмки участка землепользования",
    "place": "Пенза",
}

NOT_DONE = "не выполнено"
#: the folder beside report.pdf with the figures, report.json and the Typst source (rewritten on every build)
BUILD_DIR = "report_files"
_MARKER = ".aerophoto-report"


@dataclass(frozen=True)
class TaskStatus:
    """One task of the student's workbook, read without running and checked by the visible checks.

    ``state``: passed, failed, partial, unreadable or not_started.  ``values``: the student's readable answers;
    ``recorded``: names whose value the check cell recorded; ``unreadable``: name → what it needs; ``checks``:
    name → (ok, message); ``message``: the first failing check's message.
    """

    task: str
    title: str
    chapter: str
    state: str
    values: dict = field(default_factory=dict)
    unreadable: dict = field(default_factory=dict)
    checks: dict = field(default_factory=dict)
    message: str = ""
    recorded: tuple = ()

    @property
    def attempted(self) -> bool:
        return self.state != "not_started"


@dataclass(frozen=True)
class ChapterStatus:
    """A chapter of the registry in the student's workbook: its notebook (or None), its tasks and their specs."""

    chapter: object
    notebook: Path | None
    tasks: tuple = ()
    problem: str = ""
    specs: tuple = ()

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
    figures: tuple = ()
    leftover: tuple = ()

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


def _task_status(t: dict, chapter: str, v, env: dict, lang: str) -> TaskStatus:
    from .facts import visible_checks

    names = [a["name"] for a in t["spec"]]
    raw = {n: env.get(n, Ellipsis) for n in names}
    recorded = tuple(n for n in env.get(RECORDED, ()) if n in names)
    unread = {n: x.reason for n, x in raw.items() if isinstance(x, UNREADABLE)}
    values = {n: x for n, x in raw.items() if x is not Ellipsis and not isinstance(x, UNREADABLE)}
    if not values and not unread:
        return TaskStatus(t["id"], t["title"], chapter, "not_started")
    if unread:
        return TaskStatus(t["id"], t["title"], chapter, "unreadable", values, unread,
                          message="; ".join(f"{n}: needs {r}" for n, r in unread.items()), recorded=recorded)
    res = visible_checks(t["id"], v, {n: values.get(n, Ellipsis) for n in names}, lang)["checks"]
    checks = {n: (bool(ok), str(msg)) for n, (ok, msg) in res.items()}
    first = next((msg for ok, msg in checks.values() if not ok), "")
    if len(values) < len(names):
        state = "partial"
    else:
        state = "passed" if all(ok for ok, _ in checks.values()) else "failed"
    return TaskStatus(t["id"], t["title"], chapter, state, values, {}, checks, first, recorded)


def read_workbook(workbook_dir, record_book=None, *, chapters=None, lang: str = "ru") -> tuple:
    """Read and check every chapter of a workbook: ``(record_book, variant, (ChapterStatus, …))``.

    Nothing of the workbook is run (:mod:`aerophoto.report.answers`).  The variant is the one of ``record_book``
    (default: the notebooks' own ``RECORD_BOOK``, which must agree); ``lang`` is the language of the checks'
    messages.
    """
    from ..book import CHAPTERS
    from ..variants import variant
    from .facts import registry

    workbook = _folder("workbook_dir", workbook_dir)
    chapters = tuple(CHAPTERS if chapters is None else chapters)
    reg = registry([ch.number for ch in chapters])
    read = {}
    for ch in chapters:
        nb = _chapter_notebook(workbook, ch)
        tasks = reg[ch.number]["tasks"]
        read[ch.number] = (nb, tasks, read_notebook(nb, [t["id"] for t in tasks]) if nb else None,
                           reg[ch.number]["problem"])
    books = {r[0].name: r[2].record_book for r in read.values() if r[2] is not None and r[2].record_book}
    rb = _resolve_record_book(record_book, books)
    v = variant(rb)
    out = []
    for ch in chapters:
        nb, tasks, ans, why = read[ch.number]
        specs = tuple(tasks)
        if why:
            out.append(ChapterStatus(ch, nb, (), why, specs))
            continue
        if ans is None:
            out.append(ChapterStatus(ch, None, tuple(TaskStatus(t["id"], t["title"], ch.number, "not_started")
                                                     for t in tasks), "no notebook in the workbook", specs))
            continue
        envs = ans.values(v) if not ans.problem else {}
        out.append(ChapterStatus(ch, nb, tuple(_task_status(t, ch.number, v, envs.get(t["id"], {}), lang)
                                               for t in tasks), ans.problem, specs))
    return rb, v, tuple(out)


# =========================================================================== checking the options
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


# =========================================================================== the note
def build(workbook_dir, out_dir=None, *, student: str = "", record_book=None, group: str = "",
          checked_by: str = "", date=None, university: str | None = None, department: str | None = None,
          ministry: str | None = None, place: str | None = None, topic: str | None = None, lang: str = "ru",
          sheet: bool = True, figures: bool = True, formats=("pdf", "html"), cache=True) -> Report:
    """Assemble the student's explanatory note (guide §15) and fotoschema sheet from their workbook.

    Parameters
    ----------
    workbook_dir : the folder of the student's notebooks (``workbook/``); read, never run
    out_dir : where to write (default ``<workbook_dir>/report``): ``report.pdf``, ``report.html``,
        ``fotoschema.pdf`` (the sheet at true size) and ``report_files/`` (the figures, the JSON, the Typst
        source; rewritten on every build)
    student, group, checked_by : the title page and the sheet's marginalia (``checked_by``: the supervisor)
    record_book : the record-book number whose variant is graded (default: the notebooks' RECORD_BOOK)
    date : the note's date (``datetime.date`` or ``"YYYY-MM-DD"``; default today) — fix it for reproducible files
    university, department, ministry, place, topic : the title page (defaults: :data:`DEFAULTS`, the guide's)
    lang : ``"ru"`` (the note the guide asks for) or ``"en"``
    sheet, figures : whether to draw the fotoschema sheet and the sections' figures
    formats : any of ``"pdf"``, ``"html"``
    cache : keep the slow parts in the student's verified cache (True: the default folder,
        :func:`aerophoto.cache.cache_dir`; a path: that folder; False: compute everything)

    Returns a :class:`Report`.  Bad input raises ValueError naming the parameter.
    """
    from .. import diskcache
    from ..i18n import language

    workbook = _folder("workbook_dir", workbook_dir)
    formats = tuple(formats)
    bad = [f for f in formats if f not in ("pdf", "html")]
    if bad or not formats:
        raise ValueError(f"formats = {formats!r}; the valid values are 'pdf' and 'html' (at least one)")
    if lang not in ("ru", "en"):
        raise ValueError(f"lang = {lang!r} is not a language of the note; expected one of ['ru', 'en']")
    day = _date(date)
    opts = {"student": _text("student", student), "group": _text("group", group),
            "checked_by": _text("checked_by", checked_by), "topic": _text("topic", topic) or DEFAULTS["topic"],
            "university": _text("university", university) or DEFAULTS["university"],
            "department": _text("department", department) or DEFAULTS["department"],
            "ministry": _text("ministry", ministry) or DEFAULTS["ministry"],
            "place": _text("place", place) or DEFAULTS["place"]}
    out = Path(out_dir) if out_dir is not None else workbook / "report"
    if out.exists() and not out.is_dir():
        raise ValueError(f"out_dir = {str(out)!r} is a file, not a folder")
    if cache is True:
        opened = diskcache.enabled()
    elif cache:
        opened = diskcache.enabled(Path(cache))
    else:
        opened = contextlib.nullcontext()
    with opened, language(lang):
        rb, v, statuses = read_workbook(workbook, record_book, lang=lang)
        build_dir = _fresh_build_dir(out)
        from .frame import write_note

        doc, info = write_note(statuses, v, rb, opts, day, lang, build_dir, out, figures=figures, sheet=sheet)
        from .document import compile_pdf, write_html

        pdf = html = None
        if "pdf" in formats:
            pdf = compile_pdf(doc, build_dir, out / "report.pdf")
        else:
            (build_dir / "report.json").write_text(doc.as_json() + "\n", encoding="utf-8")
        if "html" in formats:
            html = write_html(doc, out / "report.html", prefix=f"{BUILD_DIR}/")
    return Report(pdf, html, info.get("sheet_pdf"), None, info.get("paper"), build_dir, rb, v, statuses,
                  tuple(info.get("figures", ())), tuple(info.get("leftover", ())))
