"""The web book: its sizes, how fast its first page reads, and how fast its live chapter comes alive — first visit
and second visit, with the site's cache-first service worker and, in the same run, without it (the baseline:
JupyterLite's own worker, as the browser book was before).

    python benchmarks/run.py site                               # builds the web book into a temporary folder
    AEROPHOTO_BENCH_SITE=_book python benchmarks/run.py site    # measures a site already built
    python benchmarks/run.py site --quick                       # 2 repetitions instead of 3
    AEROPHOTO_BENCH_REPS=1 python benchmarks/run.py site        # one (a loaded machine)

What is measured (JSON), the site served from 127.0.0.1 by a plain static server (no caching headers, as the README's
``python -m http.server``), chromium with every request off the machine trapped:

* ``sizes``: the site and each part (``en``, ``ru``, ``live``, the PDFs, MathJax), the largest chapter page with its
  pictures, and the build's own timings (its manifest).
* ``readable``: a fresh profile opens the front page and chapter 03: time to the first contentful paint and to the
  page's ``load`` event, bytes fetched.
* ``live``: chapter 00's live page, opened from navigation until its demo's first painted figure after Run All
  (Pyodide's start, the packages, the cells: :func:`bench_lite._open_demo`), with the bytes the server sent —
  ``first`` in a fresh profile, ``second`` the same chapter again in the same profile (the browser's cache), and
  ``other_chapter`` chapter 01 after it; for the site as built (``service_worker``) and for the same site with
  JupyterLite's original service worker (``baseline``).  Medians and p95 over the repetitions.
"""

from __future__ import annotations

import os
import shutil
import tempfile
import time
from pathlib import Path

from _timing import load_module as _load
from _timing import summarize

ROOT = Path(__file__).resolve().parents[1]

_PAINT_JS = """() => { const p = performance.getEntriesByType('paint').find((e) => e.name === 'first-contentful-paint');
  const n = performance.getEntriesByType('navigation')[0];
  return {fcp_s: p ? p.startTime / 1000 : null, load_s: n ? n.loadEventEnd / 1000 : null}; }"""


def _sizes(site: Path, manifest: dict) -> dict:
    pages = {}
    for lang in manifest["languages"]:
        for p in (site / lang).glob("[0-9][0-9]_*.html"):
            text = p.read_text(encoding="utf-8")
            import re

            pics = sum((p.parent / src).stat().st_size for src in set(re.findall(r'src="(_static/fig/[^"]+)"', text)))
            pages[f"{lang}/{p.name}"] = p.stat().st_size + pics
    biggest = max(pages, key=pages.get)
    return {"site_bytes": manifest["site_bytes"], "parts_bytes": manifest["bytes"],
            "largest_chapter_page": {"page": biggest, "bytes_with_pictures": pages[biggest]},
            "median_chapter_page_bytes_with_pictures": sorted(pages.values())[len(pages) // 2],
            "build": {"build_s": manifest["build_s"], "steps_s": manifest["steps_s"]}}


def _readable(L, browser, server, site: Path, reps: int) -> dict:
    lite_bench = _load("bench_lite", ROOT / "benchmarks" / "bench_lite.py")
    out = {}
    for name in ("en/index.html", "en/03_relief_displacement.html", "ru/03_relief_displacement.html"):
        fcp, load, fetched = [], [], []
        for _ in range(reps):
            page, _log, _req = L.new_lite_page(browser, instrument=False)
            mark = len(server.requests)
            page.goto(f"{server.base}/{name}", wait_until="load")
            t = page.evaluate(_PAINT_JS)
            fcp.append(t["fcp_s"])
            load.append(t["load_s"])
            fetched.append(lite_bench._served_bytes(site, server.requests[mark:]))
            page.context.close()
        out[name] = {"first_contentful_paint": summarize(fcp), "load_event": summarize(load),
                     "bytes_fetched": max(fetched)}
    return out


def _visits(h, L, browser, server, live: Path, chapters, reps: int) -> dict:
    """First visit, second visit, another chapter: seconds to the demo and bytes sent, ``reps`` fresh profiles."""
    lite_bench = _load("bench_lite", ROOT / "benchmarks" / "bench_lite.py")
    first = next(c for c in chapters.CHAPTERS if c.name == "00_start_here")
    other = next(c for c in chapters.CHAPTERS if c.name == "01_flight_planning")
    runs = {"first": [], "second": [], "other_chapter": []}
    failed = []
    fetched = {k: [] for k in runs}
    for _ in range(reps):
        page, _log, _req = L.new_lite_page(browser)
        context = page.context
        for key, ch in (("first", first), ("second", first), ("other_chapter", other)):
            mark = len(server.requests)
            try:
                runs[key].append(lite_bench._open_demo(h, L, page, server, ch, ch.demos[0]))
            except Exception as exc:  # a timeout on a loaded machine: said, and the run goes on
                failed.append(f"{key}: {type(exc).__name__}: {str(exc)[:120]}")
            fetched[key].append(lite_bench._served_bytes(live, server.requests[mark:]))
            page.close()
            page = context.new_page()
        context.close()
    out = {k: {"to_demo": summarize(v), "bytes_fetched_median": sorted(fetched[k])[len(fetched[k]) // 2]}
           for k, v in runs.items()}
    if failed:
        out["failed"] = failed
    return out


def _baseline_copy(live: Path, dest: Path) -> Path:
    """The browser book with JupyterLite's own service worker (the site's cache-first handler taken off)."""
    shutil.copytree(live, dest)
    sw = dest / "service-worker.js"
    text = sw.read_text(encoding="utf-8")
    if "\n/* jupyterlite */\n" in text:
        sw.write_text(text.split("\n/* jupyterlite */\n", 1)[1], encoding="utf-8")
    return dest


def run(quick: bool = False) -> dict:
    h = _load("harness", ROOT / "tests" / "browser" / "harness.py")
    L = _load("aerophoto_lite_harness", ROOT / "tests" / "browser" / "lite_harness.py")
    S = _load("aerophoto_site_harness", ROOT / "tests" / "browser" / "site_harness.py")
    chapters = _load("aerophoto_browser_chapters", ROOT / "tests" / "browser" / "chapters.py")
    from playwright.sync_api import sync_playwright

    from aerophoto import website

    reps = int(os.environ.get("AEROPHOTO_BENCH_REPS") or (2 if quick else 3))
    result = {"repetitions": reps, "load_average_start": [round(x, 2) for x in os.getloadavg()]}
    with tempfile.TemporaryDirectory(prefix="aerophoto-bench-site-") as tmp:
        site = Path(os.environ.get("AEROPHOTO_BENCH_SITE") or Path(tmp) / "book")
        if not (site / website.MANIFEST).is_file():
            t0 = time.monotonic()
            website.build(site, out=lambda _t: None)
            result["build_here_s"] = round(time.monotonic() - t0, 1)
        result["sizes"] = _sizes(site, S.manifest(site))
        baseline = _baseline_copy(site / "live", Path(tmp) / "baseline-live")
        trap = L.EgressTrap().start()
        try:
            with L.SiteServer(site) as server, L.SiteServer(baseline) as base_server, sync_playwright() as pw:
                browser = L.launch(pw, trap)
                try:
                    result["readable"] = _readable(L, browser, server, site, reps)

                    class _Live:  # the browser book inside the site: /live/…
                        base = f"{server.base}/live"
                        requests = server.httpd.requests

                        @staticmethod
                        def lab_url(nb, workspace=None):
                            return f"{server.base}/live/lab/index.html?path={nb}"

                    result["live"] = {
                        "service_worker": _visits(h, L, browser, _Live, site, chapters, reps),
                        "baseline": _visits(h, L, browser, base_server, baseline, chapters, reps),
                    }
                finally:
                    browser.close()
        finally:
            trap.stop()
        result["requests_off_machine"] = trap.from_the_site()
    result["load_average_end"] = [round(x, 2) for x in os.getloadavg()]
    return result
