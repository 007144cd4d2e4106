"""Chapter 16: the contour demo's update (kernel side) and the simulations behind the chapter.

* ``live_set_plus_agg_draw``: ``demo.set(...)`` (build the DEM, interpolate it on the 5 m raster of the 1 km
  sheet, trace its contours, sample the truth along them, move the artists, refresh the table) and one forced
  Agg draw — what the kernel does for one slider move (``draw_idle`` is stubbed: ipympl only schedules there).
  The changes cycle the grid step (20–200 m), the structural lines, m_z, h and the three sheets (their per-sheet
  data cached after a first visit, as in a lecture).
* ``live_plus_png_encode``: the same plus encoding the frame as PNG, as ipympl does before sending it.
* ``live_cpu_time``: the process CPU time of set + draw — the work itself, less sensitive to other processes
  on a shared machine than the wall-clock figures.
* ``preview_set_plus_agg_draw`` / ``preview_cpu_time``: the same changes as a drag renders them, on the
  10 m preview raster (full resolution follows when the slider rests).
* ``block_precision_s``: the linearised bundle adjustment of the article-size block (70 photos) with 20 Monte
  Carlo trials; ``spacing_study_s``: the chapter's study of five grid steps; ``structural_lines_s``: tracing
  the lines of one sheet.
"""

from __future__ import annotations

import time

from _timing import in_book_style, summarize, time_demo_moves


def _cycle(n: int, sheets) -> list:
    steps = [30, 60, 100, 150, 200, 20, 50, 120, 80, 40]
    mzs = [0.12, 0.0, 0.3, 0.05, 0.2]
    hs = [0.5, 0.25, 1.0, 2.0]
    out = []
    for i in range(n):
        k = i % 6
        if k in (0, 3):
            out.append({"spacing_m": steps[(i // 3) % len(steps)]})
        elif k == 1:
            out.append({"structural": "on" if (i // 6) % 2 == 0 else "off"})
        elif k == 2:
            out.append({"mz_m": mzs[(i // 6) % len(mzs)]})
        elif k == 4:
            out.append({"interval_m": hs[(i // 6) % len(hs)]})
        else:
            out.append({"sheet": sheets[(i // 6) % len(sheets)]})
    return out


def run(quick: bool = False) -> dict:
    return in_book_style(_run, quick)


def _run(quick: bool) -> dict:

    from aerophoto import dem
    from aerophoto.demos.dem_contours import SHEETS, ContourDemo
    from aerophoto.site import get_site

    site = get_site()
    labels = [lab for lab, _ in SHEETS]
    n = 24 if quick else 72
    changes = _cycle(n, labels)
    t0 = time.perf_counter()
    demo = ContourDemo()
    first_s = time.perf_counter() - t0
    canvas = demo.fig.canvas
    canvas.draw_idle = lambda *a, **k: None
    for lab in labels:  # visit every sheet once, in full and in preview (its truth, contours, lines are cached)
        demo.set(sheet=lab, structural="on")
        demo._preview = True
        demo.update()
        demo._preview = False
    demo.reset()
    demo.draw(force=True)
    moves = time_demo_moves(demo, changes)
    # what a drag does: the same changes on the preview raster (10 m), as ContourDemo.on_slider renders them
    preview, preview_cpu = [], []
    for ch in changes:
        demo.values.update(demo._checked(ch))
        c0 = time.process_time()
        t0 = time.perf_counter()
        demo._preview = True
        try:
            demo.update()
        finally:
            demo._preview = False
        demo.draw(force=True)
        preview.append(time.perf_counter() - t0)
        preview_cpu.append(time.process_time() - c0)
    demo.close()

    sheet = dem.Sheet(2000.0, 3000.0)
    t0 = time.perf_counter()
    dem.structural_lines(site, sheet)
    lines_s = time.perf_counter() - t0
    t0 = time.perf_counter()
    lay = dem.block_layout(site, px_percent=100 * (1 - 70 / 180))
    dem.block_precision(lay, 0.025 / 2**0.5, trials=20)
    block_s = time.perf_counter() - t0
    t0 = time.perf_counter()
    if not quick:
        dem.spacing_study(site, sheet)
    study_s = time.perf_counter() - t0
    return {
        "slider_changes": n,
        "first_build_s": round(first_s, 3),
        **moves,
        "preview_set_plus_agg_draw": summarize(preview),
        "preview_cpu_time": summarize(preview_cpu),
        "structural_lines_s": round(lines_s, 3),
        "block_precision_s": round(block_s, 3),
        "spacing_study_s": round(study_s, 3) if not quick else None,
        "target": "p95 ≤ 100 ms for preview_set_plus_agg_draw (while dragging) and live_set_plus_agg_draw",
    }
