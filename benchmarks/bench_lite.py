"""The browser book (JupyterLite): build, size, first visit, time to a live demo, slider latency beside the desktop.

    python benchmarks/run.py lite                     # chapters 00, 03, 05, 06, 13; 20 moves per demo
    python benchmarks/run.py lite --quick             # 10 moves
    AEROPHOTO_BENCH_ONLY=00_start_here python benchmarks/run.py lite
    AEROPHOTO_BENCH_ONLY=all python benchmarks/run.py lite      # every chapter with a demo

What is measured (JSON):

* ``build``: ``aerophoto-course lite`` into a fresh folder with its downloads cached (``build_s``; the first
  build on a machine also downloads ~100 MB from npm and PyPI, not timed here), ``site_bytes``, ``pyodide_bytes``.
* ``first_visit``: a fresh browser profile opens chapter 00 from the site served on 127.0.0.1 — the bytes the
  browser fetched until the demo answered (the first-visit cost a student pays), and the same for a second chapter
  in the same profile (the browser's cache serves Pyodide).
* ``to_interactive_s`` per chapter: from the page's navigation to the demo's first painted figure after
  "Run all" (Pyodide's start, the packages' load, the cells), in a fresh profile (nothing cached); the warm
  case is ``first_visit``'s second chapter.
* ``slider_ms``: slider → painted figure (the method of ``bench_browser``: keydown → the frame after ipympl's
  drawImage, in the page's clock) for the demo's timed slider, in the browser book and, in the same run, in the
  desktop JupyterLab (``desktop``).

* ``class`` (``AEROPHOTO_BENCH_LITE_CLASS=10,30``: only this part, for those class sizes): the hub benchmark's
  class (``bench_hub``: N students open chapter 00 and move α at once) on the browser book.  N − 1 students'
  first visits are N − 1 concurrent downloads of what chapter 00's first visit fetched (a process of its own,
  one thread per student, nothing cached); meanwhile one real student in a fresh chromium profile opens
  chapter 00, runs it and moves α, timed as in ``bench_browser``.  The server's part is the CPU of this
  benchmark's process while the class loads (it serves the site from a thread; the downloads run elsewhere) —
  and nothing per move: a move never leaves the student's browser.

Every request that would leave 127.0.0.1 goes to a trap and is counted (``requests_off_machine``; must be 0).
"""

from __future__ import annotations

import os
import tempfile
import time
from pathlib import Path

from _timing import load_module as _load
from _timing import summarize

ROOT = Path(__file__).resolve().parents[1]
DEFAULT = ("00_start_here", "03_relief_displacement", "05_fotoschema", "06_strip_triangulation", "13_soil_mapping")




def _served_bytes(site: Path, requests) -> int:
    """Bytes of the files sent in full (status 200; a 304 "not modified" answer sends none)."""
    total = 0
    for _method, path, _t, status in requests:
        if status != 200:
            continue
        p = site / path.split("?", 1)[0].lstrip("/")
        if p.is_dir():
            p = p / "index.html"
        if p.is_file():
            total += p.stat().st_size
    return total


def _open_demo(h, L, page, server, ch, demo) -> float:
    """Open the chapter, run all, wait for the demo's first painted figure; seconds since navigation."""
    t0 = time.monotonic()
    L.open_notebook(page, server, ch.notebook)
    h.run_all_cells(page)
    root = h.lab_demo_root(page, demo.cell)
    h.DemoProbe(page, root, sized=L.demos_sized()).wait_rendered()
    # wait_rendered ends with a 500 ms quiet period and a scroll: not part of the student's wait
    return time.monotonic() - t0 - 0.5


def _moves(h, page, root, demo, n) -> dict:
    root.scroll_into_view_if_needed()
    h.settle(page, 500)
    slider = h.slider_in(page, root, demo.timed_slider)
    out = h.time_slider_moves(page, slider, n, after_move=lambda: h.lab_kernel_idle(page))
    s = summarize(out["samples_s"])
    s["distinct_values"] = sorted(set(out["values"]))
    return s


_DOWNLOADERS = r"""
import json, sys, time, urllib.request
from concurrent.futures import ThreadPoolExecutor
base, n, paths = sys.argv[1], int(sys.argv[2]), json.loads(sys.stdin.read())
def student(_k):
    got = 0
    for p in paths:
        with urllib.request.urlopen(base + p, timeout=600) as r:
            got += len(r.read())
    return got
t0 = time.perf_counter()
with ThreadPoolExecutor(max(n, 1)) as pool:
    sizes = list(pool.map(student, range(n)))
print(json.dumps({"bytes": sum(sizes), "seconds": time.perf_counter() - t0}))
"""


def _lite_class(h, L, browser, server, first, paths, n_students: int, moves: int) -> dict:
    """N students on the browser book: N − 1 first visits downloaded at once, one real student moving α."""
    import json
    import subprocess
    import sys

    load0 = [round(x, 2) for x in os.getloadavg()]
    cpu0, t0 = time.process_time(), time.perf_counter()
    dl = subprocess.Popen([sys.executable, "-c", _DOWNLOADERS, server.base, str(n_students - 1)],
                          stdin=subprocess.PIPE, stdout=subprocess.PIPE, text=True)
    dl.stdin.write(json.dumps(paths))
    dl.stdin.close()
    page, log, _req = L.new_lite_page(browser)
    try:
        to_demo = _open_demo(h, L, page, server, first, first.demos[0])
        out_dl = json.loads(dl.stdout.read().strip().splitlines()[-1])
        dl.wait(timeout=600)
        loaded_s = time.perf_counter() - t0
        cpu_serving = time.process_time() - cpu0
        demo = next(d for d in first.demos if d.cell == "demo-footprint")
        root = h.lab_demo_root(page, demo.cell)
        root.scroll_into_view_if_needed()
        h.settle(page, 500)
        res = h.time_slider_moves(page, h.slider_in(page, root, "α, °"), moves,
                                  after_move=lambda: h.lab_kernel_idle(page))
    finally:
        page.context.close()
        if dl.poll() is None:
            dl.kill()
    return {"students": n_students, "loadavg_before": load0, "loadavg_after": [round(x, 2) for x in os.getloadavg()],
            "real_student_to_demo_s": round(to_demo, 1), "class_loaded_s": round(loaded_s, 1),
            "others_download_s": round(out_dl["seconds"], 1), "bytes_served_gb": round(out_dl["bytes"] / 1e9, 2),
            "server_cpu_s_while_loading": round(cpu_serving, 1),
            "server_cpu_s_per_student": round(cpu_serving / n_students, 2),
            "slider_to_paint": summarize(res["samples_s"]), "server_work_per_move": 0,
            "console_errors": log.relevant()}


def run(quick: bool = False) -> dict:
    h = _load("harness", ROOT / "tests" / "browser" / "harness.py")
    L = _load("aerophoto_lite_harness", ROOT / "tests" / "browser" / "lite_harness.py")
    chapters = _load("aerophoto_browser_chapters", ROOT / "tests" / "browser" / "chapters.py")
    from playwright.sync_api import sync_playwright

    from aerophoto import lite

    n = 10 if quick else 20
    only = os.environ.get("AEROPHOTO_BENCH_ONLY", "")
    names = [c.name for c in chapters.CHAPTERS]
    wanted = names if only == "all" else [c.strip() for c in only.split(",") if c.strip()] or list(DEFAULT)
    unknown = [c for c in wanted if c not in names]
    if unknown:
        raise ValueError(f"AEROPHOTO_BENCH_ONLY = {only!r}: no chapter with a demo named {unknown}; valid: "
                         f"{', '.join(names)} or 'all'")

    class_sizes = [int(x) for x in os.environ.get("AEROPHOTO_BENCH_LITE_CLASS", "").split(",") if x.strip()]
    result = {"moves_per_demo": n, "chapters": {}}
    with tempfile.TemporaryDirectory(prefix="aerophoto-bench-lite-") as tmp:
        site = Path(tmp) / "site"
        lite.build(site, out=lambda _t: None)  # warms the download cache if it is cold
        t0 = time.monotonic()
        m = lite.build(site, out=lambda _t: None)
        result["build"] = {"build_s": round(time.monotonic() - t0, 1), "site_bytes": m["site_bytes"],
                           "pyodide_bytes": m["pyodide_bytes"], "binaries": len(m["binaries"]),
                           "versions": {k: m["versions"][k] for k in ("pyodide", "python", "jupyterlite-core",
                                                                      "jupyterlite-pyodide-kernel")}}
        trap = L.EgressTrap().start()
        desktop = h.LabServer().start()
        try:
            with L.SiteServer(site) as server, sync_playwright() as pw:
                browser = L.launch(pw, trap)
                desk_browser = h.launch_chromium(pw)
                try:
                    # first visit: a fresh profile, chapter 00, then a second chapter in the same profile
                    first = next(c for c in chapters.CHAPTERS if c.name == "00_start_here")
                    second = next(c for c in chapters.CHAPTERS if c.name == "01_flight_planning")
                    page, _log, _req = L.new_lite_page(browser)
                    mark = len(server.requests)
                    cold = _open_demo(h, L, page, server, first, first.demos[0])
                    fetched = _served_bytes(site, server.requests[mark:])
                    first_mark_end = len(server.requests)
                    mark = len(server.requests)
                    warm = _open_demo(h, L, page, server, second, second.demos[0])
                    result["first_visit"] = {
                        "chapter_00_bytes_fetched": fetched, "chapter_00_to_demo_s": round(cold, 1),
                        "then_chapter_01_bytes_fetched": _served_bytes(site, server.requests[mark:]),
                        "then_chapter_01_to_demo_s": round(warm, 1)}
                    page.context.close()
                    if class_sizes:
                        paths = [p for _m, p, _t, status in server.requests[:first_mark_end] if status == 200]
                        result["class"] = {str(k): _lite_class(h, L, browser, server, first, paths, k, n)
                                           for k in class_sizes}
                        wanted = []  # the class alone

                    for ch in chapters.CHAPTERS:
                        if ch.name not in wanted:
                            continue
                        for demo in ch.demos:
                            key = f"{ch.name}/{demo.cell} [{demo.timed_slider}]"
                            page, log, _req = L.new_lite_page(browser)
                            try:
                                to_demo = _open_demo(h, L, page, server, ch, demo)
                                lite_ms = _moves(h, page, h.lab_demo_root(page, demo.cell), demo, n)
                                errors = log.relevant()
                            finally:
                                page.context.close()
                            dpage, dlog = h.new_page(desk_browser)
                            try:
                                h.open_lab_notebook(dpage, desktop, ch.notebook)
                                h.run_all_cells(dpage)
                                droot = h.lab_demo_root(dpage, demo.cell)
                                h.DemoProbe(dpage, droot).wait_rendered()
                                desk_ms = _moves(h, dpage, droot, demo, n)
                            finally:
                                dpage.context.close()
                                desktop.shutdown_kernels()
                            result["chapters"][key] = {"to_interactive_s": round(to_demo, 1),
                                                       "slider_ms": lite_ms, "desktop_slider_ms": desk_ms}
                            if errors:
                                result["chapters"][key]["console_errors"] = errors
                finally:
                    desk_browser.close()
                    browser.close()
        finally:
            desktop.stop()
            trap.stop()
        result["requests_off_machine"] = trap.from_the_site()
    result["load_average"] = [round(x, 2) for x in os.getloadavg()]
    return result
