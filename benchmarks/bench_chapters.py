"""Run All of every chapter, headless: wall time, the kernel's CPU time and its peak memory, cold and warm cache.

    python benchmarks/run.py chapters                          # every chapter, the teacher's copy, cold then warm
    AEROPHOTO_BENCH_ONLY=07,08 python benchmarks/run.py chapters
    AEROPHOTO_BENCH_BOOK=student python benchmarks/run.py chapters   # the student book (answers blank)

Method: each chapter's notebook runs in a new kernel (nbclient, the test suite's ``test_teachers_copy``
way), cell after cell; the clock runs from the first cell sent to the last reply (the kernel's start is
reported apart).  The *teacher's copy* (:func:`aerophoto.course.teacher_version`: every answer filled, every
check passing) is the default because it runs every cell; the *student* book runs with errors allowed, so the
unanswered checks do not stop it.  Per chapter:

* ``wall_s`` — Run All, seconds (what a student waits on this machine);
* ``kernel_cpu_s`` — the kernel process's user + system CPU time over the run (``/proc/<pid>/stat``): the work
  itself, much less sensitive to other work on a shared machine than the wall time;
* ``peak_rss_gb`` — the kernel's peak resident memory (``VmHWM`` of ``/proc/<pid>/status``), GB;
* ``slowest_cells`` — the five slowest cells, seconds.

Each chapter runs twice with one private cache folder (``AEROPHOTO_CACHE_DIR``, :mod:`aerophoto.cache`): first
*cold* (the folder empty: what the first Run All on a machine costs), then *warm* (what every later Run All
costs).  ``AEROPHOTO_BENCH_CACHE=off`` runs with the cache switched off instead (one run, ``off``).  The load
average is recorded before and after each chapter.  Budget (issue 32): Run All ≤ 15 s and ≤ 0.8 GB.
"""

from __future__ import annotations

import os
import shutil
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
BUDGET_S = 15.0
BUDGET_GB = 0.8


def _proc_cpu_s(pid: int) -> float:
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


def _proc_hwm_gb(pid: int) -> float:
    for line in Path(f"/proc/{pid}/status").read_text().splitlines():
        if line.startswith("VmHWM:"):
            return int(line.split()[1]) / 1e6  # kB → GB
    return float("nan")


def chapter_paths() -> list[Path]:
    """The chapters' notebooks, all or those ``AEROPHOTO_BENCH_ONLY`` names (``07,08`` or ``07_stereoscope``)."""
    only = [c.strip() for c in os.environ.get("AEROPHOTO_BENCH_ONLY", "").split(",") if c.strip()]
    paths = sorted((ROOT / "notebooks").glob("[0-9][0-9]_*.ipynb"))
    return [p for p in paths if not only or p.name[:2] in only or p.stem in only]


def run_notebook(path: Path, *, book: str = "teacher", env: dict | None = None) -> dict:
    """Run one chapter in a new kernel; its wall time, kernel CPU time, peak memory and slowest cells."""
    import nbformat
    from nbclient import NotebookClient

    nb = nbformat.read(str(path), as_version=4)
    if book == "teacher":
        from aerophoto.course import teacher_version

        nb = teacher_version(nb)
    saved = {k: os.environ.get(k) for k in (env or {})}
    os.environ.update(env or {})
    try:
        client = NotebookClient(nb, timeout=1200, kernel_name="python3", allow_errors=(book != "teacher"),
                                resources={"metadata": {"path": str(path.parent)}})
        t_start = time.perf_counter()
        with client.setup_kernel():
            pid = client.km.provisioner.process.pid
            started_s = time.perf_counter() - t_start
            cpu0 = _proc_cpu_s(pid)
            cells = []
            t0 = time.perf_counter()
            for i, cell in enumerate(nb.cells):
                c0 = time.perf_counter()
                client.execute_cell(cell, i)
                cells.append((cell.get("id", str(i)), time.perf_counter() - c0))
            wall = time.perf_counter() - t0
            cpu = _proc_cpu_s(pid) - cpu0
            hwm = _proc_hwm_gb(pid)
    finally:
        for k, v in saved.items():
            if v is None:
                os.environ.pop(k, None)
            else:
                os.environ[k] = v
    errors = [c.get("id") for c in nb.cells if c.cell_type == "code"
              and any(o.get("output_type") == "error" for o in c.get("outputs", []))]
    slow = sorted(cells, key=lambda c: -c[1])[:5]
    return {"wall_s": round(wall, 2), "kernel_cpu_s": round(cpu, 2), "peak_rss_gb": round(hwm, 3),
            "kernel_start_s": round(started_s, 2), "cells_with_errors": len(errors),
            "slowest_cells": {k: round(v, 2) for k, v in slow}}


def run(quick: bool = False) -> dict:
    book = os.environ.get("AEROPHOTO_BENCH_BOOK", "teacher")
    if book not in ("teacher", "student"):
        raise ValueError(f"AEROPHOTO_BENCH_BOOK = {book!r}; valid: teacher, student")
    cache_off = os.environ.get("AEROPHOTO_BENCH_CACHE", "on") == "off"
    paths = chapter_paths()
    out = {"method": __doc__.split("Method: ")[1].split("Each chapter runs")[0].strip().replace("\n", " "),
           "book": book, "budget": {"wall_s": BUDGET_S, "peak_rss_gb": BUDGET_GB}, "chapters": {}}
    for p in paths:
        home = Path(tempfile.mkdtemp(prefix="aerophoto-bench-home-"))
        cache = home / "cache"
        runs = ("off",) if cache_off else ("cold", "warm")
        entry = {"load_before": [round(x, 2) for x in os.getloadavg()]}
        try:
            for kind in runs:
                env = {"AEROPHOTO_HOME": str(home), "AEROPHOTO_CACHE_DIR": str(cache),
                       "AEROPHOTO_CACHE": "0" if kind == "off" else "1"}
                entry[kind] = run_notebook(p, book=book, env=env)
        finally:
            shutil.rmtree(home, ignore_errors=True)
        entry["load_after"] = [round(x, 2) for x in os.getloadavg()]
        last = entry[runs[-1]]
        entry["within_budget"] = last["wall_s"] <= BUDGET_S and last["peak_rss_gb"] <= BUDGET_GB
        out["chapters"][p.stem] = entry
        print(f"# {p.stem}: " + ", ".join(f"{k} {entry[k]['wall_s']} s / cpu {entry[k]['kernel_cpu_s']} s / "
                                          f"{entry[k]['peak_rss_gb']} GB" for k in runs)
              + f" (load {entry['load_before'][0]} → {entry['load_after'][0]})", file=sys.stderr, flush=True)
    return out
