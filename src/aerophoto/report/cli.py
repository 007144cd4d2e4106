"""``aerophoto-course report``: the subcommand's arguments and its run (wired in :mod:`aerophoto.course.cli`)."""

from __future__ import annotations

import argparse
from pathlib import Path

__all__ = ["add_arguments", "run"]


def add_arguments(p: argparse.ArgumentParser) -> None:
    p.add_argument("workbook", nargs="?", type=Path, default=Path("workbook"),
                   help="the folder of your notebooks (default: workbook/)")
    p.add_argument("--out", type=Path, default=None, help="where to write (default: <workbook>/report)")
    p.add_argument("--student", default="", help="your name, for the title page and the sheet (\"Иванов И. И.\")")
    p.add_argument("--group", default="", help="your group (\"ЗиК 31\")")
    p.add_argument("--record-book", default=None,
                   help="the record-book number (default: RECORD_BOOK in the notebooks' first cell)")
    p.add_argument("--checked-by", default="", help="the supervisor who checks it (the title page, the sheet's «Проверил»)")
    p.add_argument("--topic", default=None, help="the title page's topic (default: the course's)")
    p.add_argument("--lang", default="ru", choices=("ru", "en"), help="the note's language (default: ru)")
    p.add_argument("--no-cache", action="store_true",
                   help="compute everything afresh (default: keep the slow parts in your own verified cache)")
    p.add_argument("--date", default=None, help="the report's date, YYYY-MM-DD (default: today)")
    p.add_argument("--university", default=None, help="the title page's university (default: the guide's, PGUAS)")
    p.add_argument("--department", default=None, help="the title page's department")
    p.add_argument("--place", default=None, help="the city on the title page (default: Пенза)")
    p.add_argument("--no-sheet", action="store_true", help="do not draw the fotoschema sheet")
    p.add_argument("--html-only", action="store_true", help="write only the HTML page (no Typst needed)")


def run(args, out=print) -> int:
    """Build the report; 0 when written, 2 on bad input (the message names the parameter)."""
    from .build import build

    try:
        r = build(args.workbook, args.out, student=args.student, group=args.group, record_book=args.record_book,
                  checked_by=args.checked_by, date=args.date, university=args.university,
                  department=args.department, place=args.place, topic=args.topic, lang=args.lang,
                  cache=not args.no_cache, sheet=not args.no_sheet,
                  formats=("html",) if args.html_only else ("pdf", "html"))
    except (ValueError, RuntimeError) as exc:
        out(f"aerophoto-course report: {exc}")
        return 2
    states = [t.state for ch in r.chapters for t in ch.tasks]
    out(f"report for record book {r.record_book} (variant {r.variant.i:02d}): "
        f"{states.count('passed')} of {len(states)} task(s) passed, {states.count('failed')} failing, "
        f"{states.count('unreadable')} not readable without running, {states.count('not_started')} not done")
    for p in (r.pdf, r.html):
        if p:
            out(f"  wrote {p}")
    if r.sheet_pdf:
        out(f"  wrote {r.sheet_pdf} ({r.sheet_paper}, true size: print at 100 %)")
    else:
        out("  no fotoschema sheet: answer task 05.2 (the mean scale it is signed with) first")
    return 0
