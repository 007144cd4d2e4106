"""Timing helpers shared by the benchmark scripts (medians and p95, never asserts)."""

from __future__ import annotations

import importlib.util
import platform
import statistics
import sys
import time


def summarize(samples_s) -> dict:
    """Median, p95, min, max and count of a list of durations given in seconds, reported in ms."""
    xs = sorted(float(s) * 1000.0 for s in samples_s)
    if not xs:
        return {"n": 0}
    k = max(0, min(len(xs) - 1, int(round(0.95 * (len(xs) - 1)))))
    return {
        "n": len(xs),
        "median_ms": round(statistics.median(xs), 3),
        "p95_ms": round(xs[k], 3),
        "min_ms": round(xs[0], 3),
        "max_ms": round(xs[-1], 3),
    }


def measure(fn, n: int, *, warmup: int = 2, args_for=None) -> dict:
    """Call ``fn`` (or ``fn(*args_for(i))``) n times after a warm-up; return :func:`summarize`."""
    for i in range(warmup):
        fn(*(args_for(i) if args_for else ()))
    samples = []
    for i in range(n):
        a = args_for(i) if args_for else ()
        t0 = time.perf_counter()
        fn(*a)
        samples.append(time.perf_counter() - t0)
    return summarize(samples)


def in_book_style(fn, *args):
    """``fn(*args)`` on matplotlib's Agg backend in the book's plotting style (what a benchmark of a figure needs)."""
    import matplotlib

    matplotlib.use("Agg")
    from aerophoto import plots

    with plots.style_context():
        return fn(*args)


def time_demo_moves(demo, changes, *, by=None) -> dict:
    """Drive a LiveDemo through ``changes`` (dicts for ``demo.set``) and time each move, in ms.

    Per move: ``compute_render_only`` (``set``: the model and the artists moved in place),
    ``live_set_plus_agg_draw`` (plus a full Agg draw, what a redraw costs the kernel), ``live_cpu_time`` (the
    process's CPU time of the two, less sensitive to a busy machine) and ``live_plus_png_encode`` (plus the PNG
    frame ipympl would send).  Returns those summaries and ``figure_px``; the demo stays open.  With ``by`` (a
    function of a change giving a group name), also ``compute_render_only_by``: the first summary per group.
    ipympl's ``draw_idle`` only schedules a draw; it is stubbed so that the forced draw is counted once.
    """
    import io

    import numpy as np
    from PIL import Image

    canvas = demo.fig.canvas
    canvas.draw_idle = lambda *a, **k: None
    demo.draw(force=True)
    kernel, live, live_png, cpu = [], [], [], []
    for ch in changes:
        c0 = time.process_time()
        t0 = time.perf_counter()
        demo.set(**ch)
        t1 = time.perf_counter()
        demo.draw(force=True)
        t2 = time.perf_counter()
        cpu.append(time.process_time() - c0)
        buf = io.BytesIO()
        Image.fromarray(np.asarray(canvas.buffer_rgba())).save(buf, format="png")
        t3 = time.perf_counter()
        kernel.append(t1 - t0)
        live.append(t2 - t0)
        live_png.append(t3 - t0)
    out = {"figure_px": list(canvas.get_width_height()), "compute_render_only": summarize(kernel),
           "live_set_plus_agg_draw": summarize(live), "live_cpu_time": summarize(cpu),
           "live_plus_png_encode": summarize(live_png)}
    if by is not None:
        groups: dict = {}
        for ch, k in zip(changes, kernel):
            groups.setdefault(by(ch), []).append(k)
        out["compute_render_only_by"] = {g: summarize(ks) for g, ks in groups.items()}
    return out


def machine() -> dict:
    import os

    return {"python": platform.python_version(), "cpus": os.cpu_count(), "platform": platform.platform()}


def load_module(name: str, path):
    """The module in the file ``path`` (the browser test harness, another benchmark), loaded once under ``name``
    (benchmarks load their helpers by path: no sys.path edits)."""
    if name in sys.modules:
        return sys.modules[name]
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod
    spec.loader.exec_module(mod)
    return mod


def chapter_opening(notebook: str, demo_cell: str, record_book: str | None = None) -> str:
    """The code a student runs to open a chapter up to one demo: its setup cell (with ``record_book`` typed in,
    if given) and the demo's cell, then the demo displayed — read from ``notebooks/<notebook>.ipynb``."""
    import json
    from pathlib import Path

    path = Path(__file__).resolve().parents[1] / "notebooks" / f"{notebook}.ipynb"
    cells = {c.get("id"): "".join(c["source"]) for c in json.loads(path.read_text(encoding="utf-8"))["cells"]}
    setup = cells["setup"]
    if record_book is not None:
        setup = setup.replace("RECORD_BOOK = None", f'RECORD_BOOK = "{record_book}"')
    return setup + "\n" + cells[demo_cell] + "\nfrom IPython.display import display\ndisplay(demo)\n"


def hubclient():
    """deploy/jupyterhub/hubclient.py (the course hub's kernel-protocol client, as the hub tests use it), loaded by
    path once."""
    from pathlib import Path

    return load_module("hubclient", Path(__file__).resolve().parents[1] / "deploy" / "jupyterhub" / "hubclient.py")
