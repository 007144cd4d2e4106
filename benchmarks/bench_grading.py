"""Grading speed: nbgrader autograde of chapter 00 for a synthetic class, through aerophoto-course.

Reports the time to autograde one notebook (median, p95 over the class: mostly the kernel's start and
the setup cell), the whole class, generate_assignment, the student workbook of every chapter (a new process, as the
students' first command) and `check` of one notebook.
Runs in a temporary folder; prints nothing (benchmarks/run.py prints the JSON).
"""

from __future__ import annotations

import copy
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _timing import summarize

ROOT = Path(__file__).resolve().parents[1]
A = "00_start_here"


def _class(release, source, n: int):
    """n submissions: alternately correct, blank, wrong units (no infinite loops: they time the limit)."""
    from aerophoto import nbtools

    solution = nbtools.find_cell(source, "task-00-1-answer")[1].source
    subs = {}
    for k in range(n):
        sid = f"19-{k + 1:04d}"
        nb = copy.deepcopy(release)
        setup = nbtools.find_cell(nb, "setup")[1]
        setup.source = setup.source.replace("RECORD_BOOK = None", f'RECORD_BOOK = "{sid}"')
        ans = nbtools.find_cell(nb, "task-00-1-answer")[1]
        if k % 3 == 0:
            ans.source = solution
        elif k % 3 == 2:
            ans.source = solution + "\nH_m = H_m / 1000\n"
        subs[sid] = nb
    return subs


def run(quick: bool = False) -> dict:
    import nbformat

    from aerophoto import course

    n = 3 if quick else 12
    with tempfile.TemporaryDirectory(prefix="aerophoto-bench-grading-") as tmp:
        top = Path(tmp)
        book = top / "notebooks"
        book.mkdir()
        shutil.copy(ROOT / "notebooks" / f"{A}.ipynb", book)
        c = course.Course(top / "course", book, out=lambda s: None)

        t0 = time.perf_counter()
        c.generate()
        t_generate = time.perf_counter() - t0

        release = nbformat.read(str(c.path("release", A)), as_version=4)
        source = nbformat.read(str(book / f"{A}.ipynb"), as_version=4)
        export = top / "export"
        export.mkdir()
        for sid, nb in _class(release, source, n).items():
            nbformat.write(nb, str(export / f"{sid}_{A}.ipynb"))
        t0 = time.perf_counter()
        c.import_submissions(export)
        t_import = time.perf_counter() - t0

        t0 = time.perf_counter()
        results = c.autograde()
        t_class = time.perf_counter() - t0
        per_nb = [r.seconds for r in results if r.status == "graded"]

        t0 = time.perf_counter()
        c.gradebook()
        t_gradebook = time.perf_counter() - t0

        t0 = time.perf_counter()
        c.feedback()
        t_feedback = time.perf_counter() - t0

        # the students' first command, from a cold start (a new Python process, as on a fresh clone)
        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "aerophoto.course", "--notebooks", str(ROOT / "notebooks"),
                        "workbook", "--dest", str(top / "workbook")], check=True, capture_output=True)
        t_workbook = time.perf_counter() - t0
        n_chapters = len(list((top / "workbook").glob("*.ipynb")))

        checks = []
        for _ in range(1 if quick else 3):
            t0 = time.perf_counter()
            course.check_notebook(c.path("submitted", A, "19-0001"), record_book="19-0001")
            checks.append(time.perf_counter() - t0)

    return {
        "notebook": A,
        "students": n,
        "autograde_per_notebook": summarize(per_nb),
        "autograde_class_s": round(t_class, 2),
        "generate_s": round(t_generate, 2),
        "import_s": round(t_import, 3),
        "gradebook_export_s": round(t_gradebook, 3),
        "feedback_class_s": round(t_feedback, 2),
        "workbook_all_chapters_cold_s": round(t_workbook, 2),
        "workbook_chapters": n_chapters,
        "check_one_notebook": summarize(checks),
        "graded": sum(r.status == "graded" for r in results),
    }
