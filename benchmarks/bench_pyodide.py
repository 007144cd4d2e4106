"""Run All of every chapter in the browser book's Python (Pyodide, WebAssembly) without a browser: node.

    python benchmarks/run.py pyodide                              # every chapter (~6 min)
    AEROPHOTO_BENCH_ONLY=16,08 python benchmarks/run.py pyodide

Why: the browser book's kernel is CPython compiled to WebAssembly, and some numpy operations cost there what
they never cost on the desktop — numpy's matrix product runs without BLAS (chapter 16's block simulation took
90 s in it against 0.1 s here, until it went to scipy's sparse and LAPACK routines).  A browser run mixes that
with the page, the kernel's start and the widgets; this one times only the chapters' own Python, cell by cell,
so a cell that is slow only in WebAssembly shows up by name.

Method: the browser book is built (``aerophoto-course lite``, its downloads cached) into a temporary folder;
for each chapter a new ``node`` process loads that site's own Pyodide (``static/pyodide/``), loads the book's
packages from it (the kernel's preload: :data:`aerophoto.lite.PRELOAD`), and runs the teacher's copy of the
chapter (:func:`aerophoto.course.teacher_version`: every answer filled, every cell runs) cell by cell with
matplotlib's Agg backend (no widget front end: a demo's figure is built and drawn, not sent).  IPython magics
are skipped.  Per chapter: ``pyodide_start_s`` (loadPyodide), ``packages_s`` (loadPackage of the preload),
``run_s`` (the cells), ``slowest_cells``, ``cells_with_errors`` and node's peak resident memory
(``peak_rss_gb``, ``process.resourceUsage().maxRSS``); the load average before and after.  The desktop's Run
All of the same chapters is ``bench_chapters``.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

from _timing import load_module as _load

ROOT = Path(__file__).resolve().parents[1]
MARK = "AEROPHOTO_PYODIDE_RESULT "

_RUNNER = """
import { loadPyodide } from "%(pyodide)s/pyodide.mjs";
import fs from "fs";
const t0 = performance.now();
const py = await loadPyodide({ indexURL: "%(pyodide)s/", env: { HOME: "/home/pyodide", MPLBACKEND: "agg" } });
const t1 = performance.now();
await py.loadPackage(%(packages)s, { messageCallback: () => {} });
const t2 = performance.now();
py.FS.mkdirTree("/work");
py.FS.writeFile("/work/chapter.ipynb", fs.readFileSync(process.argv[2]));
py.setStdout({ batched: () => {} });
py.setStderr({ batched: () => {} });
const cells = await py.runPythonAsync(`
import json, os, time
os.chdir("/work")
nb = json.load(open("/work/chapter.ipynb"))
from IPython.display import display  # a notebook's built-in
g = {"__name__": "__main__", "display": display}
times, errors = [], []
for c in nb["cells"]:
    if c["cell_type"] != "code":
        continue
    src = "".join(c["source"])
    src = "\\\\n".join(l for l in src.splitlines() if not l.lstrip().startswith(("%%", "!")))
    t = time.perf_counter()
    try:
        exec(compile(src, c.get("id", "?"), "exec"), g)
    except Exception as e:
        errors.append([c.get("id"), type(e).__name__ + ": " + str(e)[:200]])
    times.append([c.get("id"), time.perf_counter() - t])
json.dumps({"cells": times, "errors": errors})
`);
const r = JSON.parse(cells);
r.pyodide_start_s = (t1 - t0) / 1000;
r.packages_s = (t2 - t1) / 1000;
r.peak_rss_gb = process.resourceUsage().maxRSS / 1e6;
console.log("%(mark)s" + JSON.stringify(r));
"""


def run_chapter(node: str, runner: Path, notebook: Path, timeout_s: float = 1200.0) -> dict:
    """One chapter in a new node process (see the module notes); its times, errors and peak memory."""
    p = subprocess.run([node, str(runner), str(notebook)], capture_output=True, text=True, timeout=timeout_s)
    line = next((x for x in p.stdout.splitlines() if x.startswith(MARK)), None)
    if line is None:
        raise RuntimeError(f"{notebook.name}: node exited {p.returncode} without a result: {p.stderr[-2000:]}")
    r = json.loads(line[len(MARK):])
    cells = sorted(r["cells"], key=lambda c: -c[1])
    return {"pyodide_start_s": round(r["pyodide_start_s"], 2), "packages_s": round(r["packages_s"], 2),
            "run_s": round(sum(t for _c, t in r["cells"]), 2), "peak_rss_gb": round(r["peak_rss_gb"], 3),
            "cells_with_errors": len(r["errors"]), "errors": r["errors"][:5],
            "slowest_cells": {c: round(t, 2) for c, t in cells[:5]}}


def run(quick: bool = False) -> dict:
    import nbformat

    from aerophoto import lite
    from aerophoto.course import teacher_version

    node = shutil.which("node")
    if node is None:
        raise RuntimeError("bench_pyodide needs node (Debian: apt-get install nodejs)")
    paths = _load("bench_chapters", ROOT / "benchmarks" / "bench_chapters.py").chapter_paths()
    out = {"method": __doc__.split("Method: ")[1].strip().replace("\n", " "), "chapters": {}}
    with tempfile.TemporaryDirectory(prefix="aerophoto-bench-pyodide-") as tmp:
        site = Path(tmp) / "site"
        m = lite.build(site, out=lambda _t: None)
        out["versions"] = {k: m["versions"][k] for k in ("pyodide", "python")}
        runner = Path(tmp) / "run.mjs"
        runner.write_text(_RUNNER % {"pyodide": (site / "static" / "pyodide").as_posix(),
                                     "packages": json.dumps(list(lite.PRELOAD)), "mark": MARK}, encoding="utf-8")
        for p in paths:
            nb = teacher_version(nbformat.read(str(p), as_version=4))
            copy = Path(tmp) / p.name
            nbformat.write(nb, str(copy))
            entry = {"load_before": [round(x, 2) for x in os.getloadavg()]}
            entry.update(run_chapter(node, runner, copy))
            entry["load_after"] = [round(x, 2) for x in os.getloadavg()]
            out["chapters"][p.stem] = entry
            top = next(iter(entry["slowest_cells"].items()), ("-", 0))
            print(f"# {p.stem}: start {entry['pyodide_start_s']} s, packages {entry['packages_s']} s, cells "
                  f"{entry['run_s']} s (slowest {top[0]} {top[1]} s), {entry['peak_rss_gb']} GB, "
                  f"{entry['cells_with_errors']} errors (load {entry['load_before'][0]} → {entry['load_after'][0]})",
                  file=sys.stderr, flush=True)
    return out
