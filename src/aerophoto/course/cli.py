"""The ``aerophoto-course`` command line (see ``aerophoto-course --help`` and the README, "For instructors")."""

from __future__ import annotations

import argparse
from pathlib import Path

from ..i18n import t
from .common import DEFAULT_TIMEOUT_S, ensure_path, notebook_problem


def _parser() -> argparse.ArgumentParser:
    ap = argparse.ArgumentParser(
        prog="aerophoto-course",
        description="The aerophoto course over nbgrader: student workbook, teacher's copy, checks, generate, "
                    "import, autograde (sandboxed, trusted scores), gradebook, feedback.")
    ap.add_argument("--course", type=Path, default=None,
                    help="the course folder (default: $AEROPHOTO_COURSE or ./course)")
    ap.add_argument("--notebooks", type=Path, default=None,
                    help="the student book's notebooks (default: ./notebooks)")
    ap.add_argument("--roster", type=Path, default=None,
                    help="CSV student_id,record_book (default: <course>/roster.csv if present)")
    ap.add_argument("--unsafe-no-sandbox", action="store_true",
                    help="run notebooks WITHOUT the sandbox, with your own rights (a developer's escape hatch for "
                         "notebooks you trust; never for submissions)")
    ap.add_argument("--no-wait", action="store_true",
                    help="refuse at once when another aerophoto-course run holds the course folder "
                         "(default: wait for it)")
    sub = ap.add_subparsers(dest="cmd", required=True)

    p = sub.add_parser("workbook", help="copy the student book into workbook/ (self-study)")
    p.add_argument("--dest", type=Path, default=None, help="folder (default: workbook/ beside notebooks/)")

    p = sub.add_parser("lab", help="JupyterLab for the student's workbook, without nbgrader's authoring tools")
    p.add_argument("notebook", nargs="?", type=Path, default=None,
                   help="notebook to open (default: workbook/00_start_here.ipynb)")
    p.add_argument("jupyter_args", nargs=argparse.REMAINDER, help="after --: passed on to JupyterLab")

    p = sub.add_parser("teacher", help="the solved teacher's copy of every chapter (for projecting)")
    p.add_argument("dest", nargs="?", type=Path, default=None, help="folder (default: <course>/teacher)")

    p = sub.add_parser("strip-solutions", help="maintenance: remove solution blocks from the notebooks' answer "
                                               "cells (re-runnable)")
    p.add_argument("folder", nargs="?", type=Path, default=None, help="notebooks folder (default: --notebooks)")
    p.add_argument("--dry-run", action="store_true", help="only say what would change")

    p = sub.add_parser("check", help="run notebooks in the sandbox; pass/fail per task by the trusted check "
                                     "(exit 1 on a failure, 2 when nothing could be verified)")
    p.add_argument("notebook", nargs="+", type=Path)
    p.add_argument("--timeout", type=int, default=DEFAULT_TIMEOUT_S, help="per-cell limit, s (default 120)")
    p.add_argument("--record-book", default=None,
                   help="check for this record-book number (default: the notebook's first cell, else the "
                        "remembered one)")

    p = sub.add_parser("generate", help="nbgrader source (reference solutions) and student versions into <course>")
    p.add_argument("--assignment", action="append", help="only this chapter (repeatable)")

    p = sub.add_parser("import", help="copy an LMS export into <course>/submitted")
    p.add_argument("folder", type=Path)

    p = sub.add_parser("autograde", help="autograde every student and chapter in the sandbox (nbgrader)")
    p.add_argument("--assignment", action="append", help="only this chapter (repeatable)")
    p.add_argument("--student", action="append", help="only this student (repeatable)")
    p.add_argument("--force", action="store_true", help="re-grade submissions already graded")
    p.add_argument("--timeout", type=int, default=None, help="per-cell limit, s (default: the config's, 120)")
    p.add_argument("--jobs", "-j", type=int, default=1,
                   help="grade this many submissions at once, each job in its own process and sandbox uid "
                        "(default 1; up to 14; the grades are the same)")

    p = sub.add_parser("lite", help="build the browser book: a JupyterLite site (Pyodide) of the workbook, the "
                                    "lecture index and the package, offline from pinned, hash-checked inputs")
    p.add_argument("--out", type=Path, default=Path("_site"), help="the site's folder (default: _site)")
    p.add_argument("--cache", type=Path, default=None,
                   help="downloads kept between builds (default: $AEROPHOTO_LITE_CACHE or ~/.cache/aerophoto-lite)")

    p = sub.add_parser("site", help="build the web book: every chapter readable in English and Russian with its "
                                    "figures, formulas and search, the browser book beside it, and the PDFs, offline "
                                    "from pinned inputs")
    p.add_argument("--out", type=Path, default=Path("_book"), help="the site's folder (default: _book)")
    p.add_argument("--cache", type=Path, default=None,
                   help="build tools and executed chapters kept between builds (default: $AEROPHOTO_SITE_CACHE or "
                        "~/.cache/aerophoto-site)")
    p.add_argument("--hub-url", default=None,
                   help="the course hub's address (https://hub.example.edu): adds \"open on the course hub\" to every "
                        "chapter")
    p.add_argument("--lite", type=Path, default=None,
                   help="a browser book already built (aerophoto-course lite --out DIR) to ship instead of building one")
    p.add_argument("--no-pdf", action="store_true", help="leave out the printed books (PDF)")

    p = sub.add_parser("report", help="the student's course report (guide §15, PDF and HTML) and fotoschema sheet "
                                      "from their workbook, read without running it (no course set-up needed)")
    from ..report.cli import add_arguments as _report_arguments

    _report_arguments(p)

    p = sub.add_parser("gradebook", help="export the grades and flags as CSV")
    p.add_argument("--out", type=Path, default=None, help="CSV file (default: <course>/grades.csv)")
    p.add_argument("--by", choices=("submission", "student"), default="submission",
                   help="a row per student × chapter (default) or per student")

    p = sub.add_parser("feedback", help="HTML feedback per student (nbgrader)")
    p.add_argument("--assignment", action="append", help="only this chapter (repeatable)")
    p.add_argument("--student", action="append", help="only this student (repeatable)")
    return _localized(ap)


def _localized(ap: argparse.ArgumentParser) -> argparse.ArgumentParser:
    """The parser's description and help texts in the user's language (:mod:`aerophoto.i18n`; English: as written)."""
    from ..i18n import get_language, translate

    if get_language() == "en":
        return ap

    def walk(p):
        p.description = translate(p.description)
        for a in p._actions:
            if a.help and a.help is not argparse.SUPPRESS:
                a.help = translate(a.help)
            if isinstance(a, argparse._SubParsersAction):
                for ca in a._choices_actions:
                    ca.help = translate(ca.help)
                for sp in a.choices.values():
                    walk(sp)

    walk(ap)
    return ap


def main(argv=None) -> int:
    """``aerophoto-course`` — see ``aerophoto-course --help`` and README, "For instructors"."""
    from .grading import CourseBusy
    from .sandbox import SandboxUnavailable

    args = _parser().parse_args(argv)
    ensure_path()

    def out(text):
        print(text, flush=True)

    try:
        return _dispatch(args, out)
    except SandboxUnavailable as exc:
        out(t("aerophoto-course {cmd}: {error}", cmd=args.cmd, error=exc))
        return 2
    except CourseBusy as exc:
        out(t("aerophoto-course {cmd}: {error}", cmd=args.cmd, error=exc))
        return 3


def _dispatch(args, out) -> int:
    from .versions import strip_solutions_in, write_teacher, write_workbook

    if args.cmd == "lab":
        from .lab import main as lab

        nb, rest = args.notebook, [a for a in args.jupyter_args if a != "--"]
        if nb is not None and str(nb).startswith("-"):  # `lab -- --no-browser`: no notebook given
            nb, rest = None, [str(nb), *rest]
        return lab(nb, rest, out=out)
    if args.cmd == "workbook":
        done = write_workbook(args.dest, args.notebooks, out=out)
        n_new = sum(a == "written" for a, _ in done)
        n_failed = sum(a == "failed" for a, _ in done)
        out(t("workbook: {n_new} chapter(s) written, {n_kept} kept as they were", n_new=n_new,
              n_kept=len(done) - n_new - n_failed) + (t(", {n_failed} skipped", n_failed=n_failed) if n_failed else ""))
        return 1 if done and n_failed == len(done) else 0
    if args.cmd == "strip-solutions":
        from .common import default_notebooks_dir

        folder = args.folder or args.notebooks or default_notebooks_dir()
        strip_solutions_in(folder, write=not args.dry_run, out=out)
        return 0
    if args.cmd == "teacher":
        from .common import default_course_dir

        dest = args.dest or (args.course or default_course_dir()) / "teacher"
        return 0 if write_teacher(dest, args.notebooks, out=out) else 1
    if args.cmd == "check":
        return _check(args, out)
    if args.cmd == "report":
        from ..report.cli import run as report

        return report(args, out)
    if args.cmd == "lite":
        from ..lite import main as lite

        return lite(args.out, cache=args.cache, notebooks=args.notebooks, out=out)

    if args.cmd == "site":
        from ..website import main as site

        return site(args.out, cache=args.cache, hub_url=args.hub_url, lite_dir=args.lite, pdf=not args.no_pdf, out=out)

    from .grading import Course

    course = Course(args.course, args.notebooks, roster=args.roster, timeout=getattr(args, "timeout", None),
                    unsafe_no_sandbox=args.unsafe_no_sandbox, wait_s=0 if args.no_wait else 3600.0, out=out)
    if args.cmd == "generate":
        ok = course.generate(args.assignment)
        return 0 if ok and all(ok.values()) else 1
    if args.cmd == "import":
        scan = course.import_submissions(args.folder)
        return 1 if scan.failed else 0
    if args.cmd == "autograde":
        from .bwrap import MAX_JOBS

        if not 1 <= args.jobs <= MAX_JOBS:
            out(t("autograde: --jobs {jobs} is not valid; expected 1 … {max_jobs}", jobs=args.jobs, max_jobs=MAX_JOBS))
            return 2
        results = course.autograde(args.student, args.assignment, force=args.force, jobs=args.jobs)
        if not results:
            out(t("autograde: no submissions in {folder} — run aerophoto-course import first",
                  folder=course.root / "submitted"))
            return 1
        failed = [r for r in results if r.status == "failed"]
        if failed:
            which = ", ".join(f"{r.student} · {r.assignment}" for r in failed[:10]) + (" …" if len(failed) > 10 else "")
            out(t("autograde: {n} submission(s) could not be graded: {which} (see {log})", n=len(failed), which=which,
                  log=course.root / "aerophoto-course.log"))
            return 1
        return 0
    if args.cmd == "gradebook":
        df = course.gradebook(by=args.by)
        dest = args.out or course.root / "grades.csv"
        dest.parent.mkdir(parents=True, exist_ok=True)
        df.to_csv(dest, index=False)
        out(t("gradebook: {rows} row(s), {flagged} flagged → {dest}", rows=len(df),
              flagged=int((df["flags"] != "").sum()) if len(df) else 0, dest=dest))
        return 0
    if args.cmd == "feedback":
        course.feedback(args.student, args.assignment)
        return 0
    return 2  # pragma: no cover


def _check(args, out) -> int:
    from .check import check_notebook, print_check
    from .sandbox import require

    if not args.unsafe_no_sandbox:
        require()
    status = 0
    for nb_path in args.notebook:
        if not nb_path.is_file():
            out(t("{path}: no such notebook", path=nb_path))
            status = max(status, 2)
            continue
        problem = notebook_problem(nb_path)
        if problem:
            out(t("{path}: {problem}", path=nb_path, problem=problem))
            status = max(status, 2)
            continue
        try:
            res = check_notebook(nb_path, timeout=args.timeout, record_book=args.record_book,
                                 unsafe_no_sandbox=args.unsafe_no_sandbox)
        except Exception as exc:  # the sandbox or the kernel could not start: nothing verified
            out(t("{path}: could not be run ({error})", path=nb_path, error=f"{type(exc).__name__}: {exc}"))
            status = max(status, 2)
            continue
        print_check(res, out)
        if res.problem:
            status = max(status, 2)
        elif not res.ok:
            status = max(status, 1)
    return status
