"""Grading speed: aerophoto-course over nbgrader for a synthetic class of chapter 00, and what the sandbox costs.

Reports the time to autograde one notebook in the sandbox (median, p95 over the class: mostly the kernel's
start and the setup cell; the trusted check is included), the whole class, the same class without the
sandbox (``--unsafe-no-sandbox``, for the overhead), a kernel's start and one trivial cell sandboxed /
unsandboxed / plain nbclient, the trusted check alone, generate_assignment, the student workbook of every
chapter (a new process, as the students' first command) and `check` of one notebook.
Runs in a temporary folder; prints nothing (benchmarks/run.py prints the JSON).
"""

from __future__ import annotations

import copy
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _timing import summarize

ROOT = Path(__file__).resolve().parents[1]
A = "00_start_here"

SOLUTION = ("import math\nH_m = v.f_mm / 1000 * v.m\non_mm = v.f_mm * math.tan(math.radians(v.alpha_deg))\n"
            "oc_mm = -v.f_mm * math.tan(math.radians(v.alpha_deg) / 2)\n")


def _class(release, n: int):
    """n submissions: alternately correct, blank, wrong units (no infinite loops: they time the limit)."""
    from aerophoto import nbtools

    subs = {}
    for k in range(n):
        sid = f"19-{k + 1:04d}"
        nb = copy.deepcopy(release)
        setup = nbtools.find_cell(nb, "setup")[1]
        setup.source = setup.source.replace("RECORD_BOOK = None", f'RECORD_BOOK = "{sid}"')
        ans = nbtools.find_cell(nb, "task-00-1-answer")[1]
        if k % 3 == 0:
            ans.source = f"me = {sid!r}\n" + SOLUTION
        elif k % 3 == 2:
            ans.source = f"me = {sid!r}\n" + SOLUTION + "H_m = H_m / 1000\n"
        subs[sid] = nb
    return subs


def _kernel_start(n: int) -> dict:
    """One trivial cell in a new kernel: sandboxed, unsandboxed (same code path), plain nbclient."""
    from nbclient import NotebookClient

    from aerophoto import nbtools
    from aerophoto.course.sandbox_execute import run_sandboxed

    nb0 = nbtools.notebook([nbtools.code("x = 1", id="setup")])
    out = {}
    for mode in ("sandbox", "no_sandbox", "plain_nbclient"):
        samples = []
        for _ in range(n + 1):
            nb = copy.deepcopy(nb0)
            t0 = time.perf_counter()
            if mode == "plain_nbclient":
                NotebookClient(nb, timeout=60, kernel_name="python3").execute()
            else:
                run_sandboxed(nb, cwd=tempfile.gettempdir(), record_book="19-0457",
                              unsafe_no_sandbox=(mode == "no_sandbox"))
            samples.append(time.perf_counter() - t0)
        out[mode] = summarize(samples[1:])  # the first start warms caches
    return out


def _grade_class(top: Path, book: Path, release, n: int, *, unsafe: bool):
    from aerophoto import course

    c = course.Course(top / ("course-unsafe" if unsafe else "course"), book, out=lambda s: None,
                      unsafe_no_sandbox=unsafe)
    t0 = time.perf_counter()
    c.generate()
    t_generate = time.perf_counter() - t0
    export = top / ("export-unsafe" if unsafe else "export")
    export.mkdir()
    import nbformat

    for sid, nb in _class(release, n).items():
        nbformat.write(nb, str(export / f"{sid}_{A}.ipynb"))
    t0 = time.perf_counter()
    c.import_submissions(export)
    t_import = time.perf_counter() - t0
    t0 = time.perf_counter()
    results = c.autograde()
    t_class = time.perf_counter() - t0
    return c, results, t_class, t_generate, t_import


def run(quick: bool = False) -> dict:
    import nbformat

    from aerophoto import course, nbtools
    from aerophoto.course.trusted import grade_executed
    from aerophoto.course.versions import strip_solutions

    n = 3 if quick else 12
    with tempfile.TemporaryDirectory(prefix="aerophoto-bench-grading-") as tmp:
        top = Path(tmp)
        book = top / "notebooks"
        book.mkdir()
        nbtools.write(strip_solutions(nbtools.read(ROOT / "notebooks" / f"{A}.ipynb"))[0], book / f"{A}.ipynb")
        c0 = course.Course(top / "course", book, out=lambda s: None)
        t0 = time.perf_counter()
        c0.generate()
        t_generate_first = time.perf_counter() - t0
        release = nbformat.read(str(c0.path("release", A)), as_version=4)

        c, results, t_class, t_generate, t_import = _grade_class(top, book, release, n, unsafe=False)
        per_nb = [r.seconds for r in results if r.status == "graded"]
        _, results_u, t_class_u, _, _ = _grade_class(top, book, release, n, unsafe=True)
        per_nb_u = [r.seconds for r in results_u if r.status == "graded"]

        graded = nbformat.read(str(c.path("autograded", A, "19-0001")), as_version=4)
        trusted = []
        for _ in range(20):
            t0 = time.perf_counter()
            grade_executed(graded, "19-0001")
            trusted.append(time.perf_counter() - t0)

        t0 = time.perf_counter()
        c.gradebook()
        t_gradebook = time.perf_counter() - t0

        t0 = time.perf_counter()
        c.feedback()
        t_feedback = time.perf_counter() - t0

        t0 = time.perf_counter()
        subprocess.run([sys.executable, "-m", "aerophoto.course", "--notebooks", str(ROOT / "notebooks"),
                        "workbook", "--dest", str(top / "workbook")], check=True, capture_output=True)
        t_workbook = time.perf_counter() - t0
        n_chapters = len(list((top / "workbook").glob("*.ipynb")))

        checks = []
        for _ in range(1 if quick else 3):
            t0 = time.perf_counter()
            from aerophoto.course.check import check_notebook

            check_notebook(c.path("submitted", A, "19-0001"), record_book="19-0001")
            checks.append(time.perf_counter() - t0)
        starts = _kernel_start(2 if quick else 5)

    med = summarize(per_nb).get("median_ms", 0)
    med_u = summarize(per_nb_u).get("median_ms", 0)
    return {
        "notebook": A,
        "students": n,
        "autograde_per_notebook": summarize(per_nb),
        "autograde_per_notebook_no_sandbox": summarize(per_nb_u),
        "sandbox_overhead_per_notebook_ms": round(med - med_u, 1),
        "autograde_class_s": round(t_class, 2),
        "autograde_class_no_sandbox_s": round(t_class_u, 2),
        "kernel_start_one_cell": starts,
        "trusted_check_per_notebook": summarize(trusted),
        "generate_s": round(t_generate_first, 2),
        "generate_unchanged_s": round(t_generate, 2),
        "import_s": round(t_import, 3),
        "gradebook_export_s": round(t_gradebook, 3),
        "feedback_class_s": round(t_feedback, 2),
        "workbook_all_chapters_cold_s": round(t_workbook, 2),
        "workbook_chapters": n_chapters,
        "check_one_notebook": summarize(checks),
        "graded": sum(r.status == "graded" for r in results),
    }
