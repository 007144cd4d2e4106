"""The student's explanatory note (aerophoto.report, issue 29): a full workbook, every task answered.

Times ``report.build`` of one full workbook (record book 19-0457, every chapter answered with the package's
values) in five ways, all in this run and on this machine (the load average is reported beside them):

* ``baseline_main_new_process`` — the report as the base commit of this branch builds it (``git merge-base HEAD
  main``, exported to a temporary folder and run from there): today's time, for comparison;
* ``first_build_new_process`` — the new note in a new process with an empty cache: the first build on a
  student's machine (it fills the cache);
* ``cached_build_new_process`` — the same with the cache filled: what ``aerophoto-course report`` costs from then
  on (goal ≤ 20 s);
* ``warm_build`` — a second build in the same process (goal ≤ 10 s);
* ``no_cache_build_new_process`` (not with ``quick``) — the new note with ``cache=False``.

Medians and p95 (``_timing.summarize``); prints nothing (benchmarks/run.py prints the JSON).
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _timing import summarize

ROOT = Path(__file__).resolve().parents[1]
RB = "19-0457"
DATE = "2026-11-26"

_BUILD = ("import sys, json; from aerophoto import report; "
          "r = report.build(sys.argv[1], sys.argv[2], student='Иванова Анна', group='ЗиК 31', "
          f"checked_by='Пресняков В. В.', date={DATE!r}, cache=(sys.argv[3] if sys.argv[3] != '-' else False)); "
          "print(json.dumps({'figures': len(r.figures)}))")
_BASELINE = ("import sys; from aerophoto import report; "
             "report.build(sys.argv[1], sys.argv[2], student='Иванова Анна', checked_by='Пресняков В. В.', "
             f"date={DATE!r})")


def _full_workbook(dest: Path) -> Path:
    """Every chapter's tasks answered with the reference values, typed as numbers (record book 19-0457)."""
    from aerophoto import nbtools, tasks
    from aerophoto.course.versions import write_workbook
    from aerophoto.variants import variant

    v = variant(RB)
    write_workbook(dest, ROOT / "notebooks", out=lambda s: None)

    def lit(x):
        if hasattr(x, "tolist"):
            x = x.tolist()
        if isinstance(x, (list, tuple)):
            return "[" + ", ".join(lit(e) for e in x) + "]"
        return repr(float(x)) if isinstance(x, float) else repr(x)

    for path in sorted(dest.glob("[0-9][0-9]_*.ipynb")):
        number = path.name[:2]
        nb = nbtools.read(path)
        if number == "00":
            _, setup = nbtools.find_cell(nb, "setup")
            setup.source = setup.source.replace("RECORD_BOOK = None", f"RECORD_BOOK = {RB!r}")
        if number in tasks.CHAPTER_MODULES:
            for t in tasks.chapter_tasks(number):
                ref = t.answers(v)
                nbtools.set_cell(nb, f"{t.id}-answer", "\n".join(f"{k} = {lit(x)}" for k, x in ref.items()))
        nbtools.write(nb, path)
    return dest


def _timed(argv, env=None) -> float:
    t0 = time.perf_counter()
    subprocess.run(argv, check=True, capture_output=True, env=env)
    return time.perf_counter() - t0


def _base_source(top: Path) -> Path | None:
    """The base commit's ``src/`` exported into ``top`` (None when git cannot say)."""
    try:
        base = subprocess.run(["git", "-C", str(ROOT), "merge-base", "HEAD", "main"], capture_output=True,
                              text=True, check=True).stdout.strip()
        archive = subprocess.run(["git", "-C", str(ROOT), "archive", base, "src"], capture_output=True, check=True)
    except (OSError, subprocess.CalledProcessError):
        return None
    top.mkdir(parents=True, exist_ok=True)
    subprocess.run(["tar", "-x", "-C", str(top)], input=archive.stdout, check=True)
    return top / "src"


def _load() -> float | None:
    try:
        return round(os.getloadavg()[0], 2)
    except OSError:
        return None


def run(quick: bool = False) -> dict:
    from aerophoto import report

    top = Path(tempfile.mkdtemp(prefix="bench-report-"))
    wb = _full_workbook(top / "workbook")
    n = 1 if quick else 3
    out: dict = {"goal_cached_new_process_ms": 20000.0, "goal_warm_ms": 10000.0, "load_average_1min": {}}
    py = sys.executable
    # today's time: the base commit's report on the same workbook
    base = _base_source(top / "base")
    if base is not None:
        env = dict(os.environ, PYTHONPATH=str(base), PYTHONDONTWRITEBYTECODE="1")
        out["load_average_1min"]["baseline"] = _load()
        out["baseline_main_new_process"] = summarize([_timed([py, "-c", _BASELINE, str(wb), str(top / "b0"), "-"],
                                                             env) for _ in range(1)])
    cache = top / "cache"
    out["load_average_1min"]["first"] = _load()
    out["first_build_new_process"] = summarize([_timed([py, "-c", _BUILD, str(wb), str(top / "f0"), str(cache)])])
    out["load_average_1min"]["cached"] = _load()
    out["cached_build_new_process"] = summarize([_timed([py, "-c", _BUILD, str(wb), str(top / f"c{k}"), str(cache)])
                                                 for k in range(n)])
    report.build(wb, top / "w0", student="Иванова Анна", date=DATE, cache=cache)
    samples = []
    for k in range(n):
        t0 = time.perf_counter()
        r = report.build(wb, top / f"w{k + 1}", student="Иванова Анна", group="ЗиК 31",
                         checked_by="Пресняков В. В.", date=DATE, cache=cache)
        samples.append(time.perf_counter() - t0)
    out["load_average_1min"]["warm"] = _load()
    out["warm_build"] = summarize(samples)
    if not quick:
        out["load_average_1min"]["no_cache"] = _load()
        out["no_cache_build_new_process"] = summarize([_timed([py, "-c", _BUILD, str(wb), str(top / "n0"), "-"])])
    info = subprocess.run(["pdfinfo", str(r.pdf)], capture_output=True, text=True).stdout
    pages = next((line.split()[-1] for line in info.splitlines() if line.startswith("Pages")), "?")
    states = [t.state for ch in r.chapters for t in ch.tasks]
    out["report"] = {"pages": pages, "figures": len(r.figures), "pdf_MB": round(r.pdf.stat().st_size / 1e6, 2),
                     "sheet_paper": r.sheet_paper, "tasks_passed": f"{states.count('passed')}/{len(states)}",
                     "sheet_pdf_MB": round(r.sheet_pdf.stat().st_size / 1e6, 2) if r.sheet_pdf else None,
                     "cache_MB": round(sum(p.stat().st_size for p in cache.rglob("*") if p.is_file()) / 1e6, 1)}
    json.dumps(out)  # plain data
    return out
