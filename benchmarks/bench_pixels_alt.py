"""Any live demo's own Agg pixels drawn by the browser — a <canvas> fed with raw RGBA boxes — against ipympl.

    python -m pip install --no-deps --target ~/.cache/aerophoto-bench/anywidget-0.11.0 anywidget==0.11.0 psygnal==0.16.1
    python benchmarks/run.py pixels_alt             # 20 moves per demo, host and way
    python benchmarks/run.py pixels_alt --quick     # 10
    AEROPHOTO_PIXELS_ONLY=demo-transformer,demo-fotoschema python benchmarks/run.py pixels_alt   # any demos (cells)

Issue 20: a demo that matplotlib through ipympl cannot bring within 100 ms p95 is compared, on the same demo
and in the same run, with one alternative that draws in the browser.  bench_canvas_alt.py re-implements one
picture (the fotoschema) in JavaScript; this one is **generic** — it works for every LiveDemo unchanged — and
is run on the four image-heavy demos still above 100 ms (``DEMOS``: the rough mosaic of 02, the shooting
conditions and the table-10 key of 08, the contours of 16), each on the slider the browser benchmark times;
``AEROPHOTO_PIXELS_ONLY`` names other demos of tests/browser/chapters.py by their cells (or chapter/cell) instead.

The two ways, per demo:

* **matplotlib** — the chapter's own demo in the chapter's notebook (ipympl: the kernel draws with Agg, blits,
  encodes the changed pixels as a PNG at zlib level 1; the page decodes it and draws it on its canvas);
* **pixels** — a scratch notebook (written at run time into the server's copy of the notebooks, never into
  ``notebooks/``) that switches matplotlib to Agg, builds the same class with its defaults and shows the
  demo's own layout (``demo.widget()``: the same labelled sliders, table, status line and legend, so the same
  observe → on_slider → update → blitted draw runs) with a ~40-line ``anywidget`` canvas in the figure's place.
  After every ``demo.draw`` (the instance's method is wrapped; the delayed full-resolution renders scheduled by
  ``demo.later`` go through it too) the kernel compares Agg's ``buffer_rgba()`` with the previous frame and
  sends only the bounding box of the changed pixels as raw RGBA bytes (one binary traitlet) plus
  [x, y, w, h, W, H, seq] in one sync message (``hold_sync``); JavaScript ``putImageData``s the box onto a
  canvas of the figure's size.  No PNG encoding in the kernel, no decoding in the page, and the picture is
  matplotlib's Agg rendering pixel for pixel.

Latency is measured as in bench_browser.py and bench_canvas_alt.py (``performance.now()`` in the page,
keydown → the requestAnimationFrame after the picture changed; the canvas stamps ``window.__aero.paints``
itself, kind ``alt``).  Moves alternate →/←, 20 per demo, host and way (10 with --quick), each after the
previous move's full picture has painted (and, in JupyterLab, the kernel is idle); JupyterLab and Voilà.
Recorded besides: the bytes the page received per move (all WebSocket frames), a screenshot of each picture
after the last move (``benchmarks/results/pixels_alt_<cell>_<way>_<host>.png``), the two canvases' own pixels
compared (``same_picture``, read with ``toDataURL``), and the load average.  A kernel-side breakdown per demo, in a subprocess with
matplotlib's webagg backend (as ipympl's canvas): ``on_slider`` (compute + blitted Agg draw, inside a running
asyncio loop as in a kernel), ipympl's PNG frame (``get_diff_image`` after ``plots.fast_frames``) with its
size, and the changed box's extraction time and raw size.

Dependency: ``anywidget`` 0.11.0 and ``psygnal`` 0.16.1, **for this benchmark only**, outside the project's
environment, exactly as bench_canvas_alt.py installs and loads them (its module notes); nothing else is added.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from _timing import load_module as _load

ROOT = Path(__file__).resolve().parents[1]
HERE = Path(__file__).resolve().parent

#: (chapter, demo cell) of the demos compared; each is timed on its registry's timed slider
DEMOS = (("02_photo_quality", "demo-quality"), ("08_interpretation", "demo-conditions"),
         ("08_interpretation", "demo-key"), ("16_dem_contours", "demo-contours"))

#: the changed-pixel box of two frames (uint32 arrays h × w), shared by the scratch notebook and the breakdown
BOX_PY = r'''
import numpy as np


def changed_box(cur, prev):
    """(x, y, w, h) of the pixels that differ between two frames; the whole frame when there is no previous
    one of the same size; None when nothing changed."""
    H, W = cur.shape
    if prev is None or prev.shape != cur.shape:
        return 0, 0, W, H
    diff = cur != prev
    rows = np.flatnonzero(diff.any(axis=1))
    if rows.size == 0:
        return None
    cols = np.flatnonzero(diff.any(axis=0))
    return int(cols[0]), int(rows[0]), int(cols[-1] - cols[0] + 1), int(rows[-1] - rows[0] + 1)


def frame_of(fig):
    """The figure's Agg pixels as uint32 (h × w), a view of the renderer's buffer."""
    return np.asarray(fig.canvas.get_renderer().buffer_rgba()).view(np.uint32)[:, :, 0]
'''.lstrip()

#: the canvas's front end (an ES module for anywidget)
PIXELS_JS = r"""
function render({ model, el }) {
  const cv = document.createElement("canvas");
  cv.className = "aerophoto-alt-canvas";
  cv.style.display = "block";
  el.appendChild(cv);
  const ctx = cv.getContext("2d");
  const paint = () => {
    const b = model.get("box"), dv = model.get("pixels");
    if (!b || b.length < 6 || !dv) return;
    const [x, y, w, h, W, H] = b;
    if (cv.width !== W || cv.height !== H) { cv.width = W; cv.height = H; }
    if (w > 0 && h > 0 && dv.byteLength === w * h * 4) {
      ctx.putImageData(new ImageData(new Uint8ClampedArray(dv.buffer, dv.byteOffset, dv.byteLength), w, h), x, y);
    }
    // the pixels are on the canvas: stamp it as the harness stamps ipympl's drawImage (painted at the next frame)
    const t0 = performance.now();
    requestAnimationFrame(() => { const A = window.__aero; if (A) A.paints.push({ kind: "alt", changed: t0, painted: performance.now() }); });
  };
  model.on("change:box", paint);
  model.send({ want: "full" });  // a new view: the whole picture (the state holds only the last changed box)
  return () => model.off("change:box", paint);
}
export default { render };
"""

#: the scratch notebook of the pixels way (format: module, cls)
PIXELS_SETUP = r'''
import matplotlib
matplotlib.use("Agg")   # the figure is never shown by matplotlib: its pixels go to the canvas below
import aerophoto
aerophoto.setup(live=False, quiet=True)   # the book's style, as the chapter's setup applies it
import anywidget, traitlets
{box}

class PixelCanvas(anywidget.AnyWidget):
    """A figure's Agg pixels in the browser: the changed box as raw RGBA bytes plus [x, y, w, h, W, H, seq]."""
    _esm = {esm!r}
    pixels = traitlets.Bytes(b"").tag(sync=True)
    box = traitlets.List([]).tag(sync=True)


def pixels_widget(demo):
    """``demo`` laid out as usual, a PixelCanvas in its figure's place, fed after every ``demo.draw``."""
    canvas = PixelCanvas()
    state = {{"prev": None, "seq": 0}}

    def send(full=False):
        cur = frame_of(demo.fig)
        box = changed_box(cur, None if full else state["prev"])
        state["prev"] = cur.copy()
        if box is None:
            return
        x, y, w, h = box
        state["seq"] += 1
        with canvas.hold_sync():
            canvas.box = [x, y, w, h, cur.shape[1], cur.shape[0], state["seq"]]
            canvas.pixels = cur[y:y + h, x:x + w].tobytes()

    draw = demo.draw

    def draw_and_send(force=False):
        draw(force=force)
        send()

    demo.draw = draw_and_send
    canvas.on_msg(lambda _w, content, _b: send(full=True) if content.get("want") == "full" else None)
    send(full=True)
    demo.figure_widget = lambda: canvas
    ui = demo.widget()
    ui.add_class("aerophoto-alt")
    return ui

from {module} import {cls}
'''.lstrip()

PIXELS_DEMO = r'''
demo = {cls}()
pixels_widget(demo)
'''.lstrip()

#: the kernel-side breakdown, run in a subprocess (matplotlib's webagg backend, as ipympl's canvas)
BREAKDOWN_PY = r'''
import asyncio, importlib, json, sys, time
import matplotlib
matplotlib.use("webagg")
from aerophoto import plots
plots.use_style()
{box}

def summarize(xs):
    xs = sorted(x * 1000.0 for x in xs)
    k = max(0, min(len(xs) - 1, int(round(0.95 * (len(xs) - 1)))))
    return {{"n": len(xs), "median_ms": round(xs[len(xs) // 2] if len(xs) % 2 else (xs[len(xs) // 2 - 1] + xs[len(xs) // 2]) / 2, 2),
            "p95_ms": round(xs[k], 2)}}


async def one(path, label, n):
    module, cls = path.rsplit(".", 1)
    Cls = getattr(importlib.import_module(module), cls)
    d = Cls(); c = d.fig.canvas; plots.fast_frames(d.fig)
    c.draw_idle = lambda *a, **k: c.draw()  # a move the blitter declines draws in full now (ipympl: on the page's request)
    c.draw(); c._png_is_old = True; c._force_full = True; c.get_diff_image()
    prev = frame_of(d.fig).copy()
    p = next(q for q in Cls.params if q.label == label)
    up = p.default + p.step if p.default + p.step <= p.hi else p.default - p.step
    rest = getattr(Cls, "settle_s", 0.0) + 0.1
    slider, png_t, png_b, box_t, box_b = [], [], [], [], []
    for i in range(n):
        d.values[p.name] = p.validate(up if i % 2 == 0 else p.default)
        t0 = time.perf_counter(); d.on_slider(); t1 = time.perf_counter()
        c._png_is_old = True; png = c.get_diff_image(); t2 = time.perf_counter()
        cur = frame_of(d.fig); b = changed_box(cur, prev)
        raw = b"" if b is None else cur[b[1]:b[1] + b[3], b[0]:b[0] + b[2]].tobytes(); t3 = time.perf_counter()
        prev = cur.copy()
        slider.append(t1 - t0); png_t.append(t2 - t1); png_b.append(len(png or b"")); box_t.append(t3 - t2); box_b.append(len(raw))
        await asyncio.sleep(rest)   # a delayed full picture (d.later) and table (QualityDemo) land here
        c._png_is_old = True; c.get_diff_image(); prev = frame_of(d.fig).copy()
    d.close()
    med = lambda xs: sorted(xs)[len(xs) // 2]
    return {{"moves": n, "figure_px": list(c.get_width_height(physical=True)), "on_slider": summarize(slider),
            "png_encode": summarize(png_t), "png_kB_median": round(med(png_b) / 1000, 1),
            "box_extract": summarize(box_t), "box_raw_kB_median": round(med(box_b) / 1000, 1),
            "blitted_draws": getattr(d.blitter, "n_blit", None), "full_draws": getattr(d.blitter, "n_full", None)}}


jobs = json.loads(sys.argv[1])
print(json.dumps({{path: asyncio.run(one(path, label, n)) for path, label, n in jobs}}))
'''.lstrip()


def _alt_notebook_name(demo) -> str:
    return f"pixels_alt_{demo.cell.removeprefix('demo-')}.ipynb"


def _write_pixels(folder: Path, demo) -> str:
    """Write the pixels way of ``demo`` into ``folder`` (the server's copy of the notebooks); its file name."""
    import nbformat
    from nbformat.v4 import new_code_cell, new_notebook

    module, cls = demo.cls.rsplit(".", 1)
    nb = new_notebook(cells=[
        new_code_cell(PIXELS_SETUP.format(box=BOX_PY, esm=PIXELS_JS, module=module, cls=cls), id="setup"),
        new_code_cell(PIXELS_DEMO.format(cls=cls), id="demo-pixels-alt")])
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    name = _alt_notebook_name(demo)
    nbformat.write(nb, str(folder / name))
    return name


def kernel_breakdown(demos, n: int = 16) -> dict:
    """Per demo (Demo entries of the registry), in a fresh Python: on_slider, PNG frame, raw box (see the notes)."""
    home = tempfile.mkdtemp(prefix="aerophoto-pixels-alt-")
    env = {k: v for k, v in os.environ.items() if k != "MPLBACKEND"}
    env["AEROPHOTO_HOME"] = home
    jobs = [[d.cls, d.timed_slider, n] for d in demos]
    try:
        r = subprocess.run([sys.executable, "-c", BREAKDOWN_PY.format(box=BOX_PY), json.dumps(jobs)], cwd=ROOT,
                           env=env, capture_output=True, text=True, timeout=1800)
    finally:
        shutil.rmtree(home, ignore_errors=True)
    if r.returncode != 0:
        raise RuntimeError(f"the kernel-side breakdown failed:\n{r.stderr[-3000:]}")
    return json.loads(r.stdout.strip().splitlines()[-1])


def _same_picture(a: Path, b: Path) -> dict:
    """The two ways' canvases after the last move, pixel by pixel (their own pixels, not a screenshot)."""
    import numpy as np
    from PIL import Image

    x, y = (np.asarray(Image.open(p).convert("RGBA"), dtype=np.int16) for p in (a, b))
    if x.shape != y.shape:
        return {"sizes_px": [list(x.shape[1::-1]), list(y.shape[1::-1])], "identical": False}
    d = np.abs(x - y).max(axis=2)
    return {"size_px": list(x.shape[1::-1]), "identical": bool((d == 0).all()),
            "pixels_differing": round(float((d > 0).mean()), 6), "max_channel_difference": int(d.max())}


def run(quick: bool = False) -> dict:
    ca = _load("bench_canvas_alt", HERE / "bench_canvas_alt.py")
    ca._anywidget_ready()
    h = _load("aerophoto_browser_harness", ROOT / "tests" / "browser" / "harness.py")
    chapters = _load("aerophoto_browser_chapters", ROOT / "tests" / "browser" / "chapters.py")
    bb = _load("bench_browser", HERE / "bench_browser.py")
    from playwright.sync_api import sync_playwright

    chs = {c.name: c for c in chapters.CHAPTERS}
    only = [c.strip() for c in os.environ.get("AEROPHOTO_PIXELS_ONLY", "").split(",") if c.strip()]
    if only:
        every = [(c, d) for c in chapters.CHAPTERS for d in c.demos if d.cls]
        found = {x: [(c, d) for c, d in every if x in (d.cell, f"{c.name}/{d.cell}")] for x in only}
        unknown = [x for x, hits in found.items() if not hits]
        if unknown:
            valid = ", ".join(f"{c.name}/{d.cell}" for c, d in every)
            raise ValueError(f"AEROPHOTO_PIXELS_ONLY = {','.join(unknown)!r}: no such demo cell; valid: {valid}")
        todo = [found[x][0] for x in only]  # a cell in two chapters: the first, or name it chapter/cell
    else:
        todo = [(chs[name], next(d for d in chs[name].demos if d.cell == cell)) for name, cell in DEMOS]
    n = 10 if quick else 20
    results = HERE / "results"
    out = {"method": __doc__.split("Latency is measured")[1].split("Dependency:")[0].strip().replace("\n", " "),
           "moves": n,
           "dependencies_added": {"anywidget": ca.ANYWIDGET_VERSION, "psygnal": ca.PSYGNAL_VERSION,
                                  "installed_to": str(ca.ANYWIDGET_DIR), "project_environment_changed": False},
           "load_average_start": os.getloadavg(), "demos": {}}
    breakdown = kernel_breakdown([d for _c, d in todo], n=8 if quick else 16)
    for ch, demo in todo:
        out["demos"][f"{ch.name}/{demo.cell}"] = {
            "chapter": ch.name, "cell": demo.cell, "class": demo.cls, "slider": demo.timed_slider,
            "target_p95_ms": bb.target_p95_ms(ch.name), "kernel": breakdown[demo.cls], "jupyterlab": {}, "voila": {}}
    scratch = Path(tempfile.mkdtemp(prefix="aerophoto-pixels-alt-"))

    def write(root_dir):
        return {demo.cell: _write_pixels(root_dir, demo) for _c, demo in todo}

    try:
        with ca._alt_servers(h, write) as (lab, voila, alt_nb), sync_playwright() as pw:
            browser = h.launch_chromium(pw)
            try:
                def alt_root(page):
                    return page.locator(".aerophoto-alt").first

                for ch, demo in todo:
                    entry = out["demos"][f"{ch.name}/{demo.cell}"]
                    rest, label = bb._rest_ms(demo), demo.timed_slider
                    for where, server, is_lab in (("jupyterlab", lab, True), ("voila", voila, False)):
                        if is_lab:
                            def mpl_root(page, cell=demo.cell):
                                return h.lab_demo_root(page, cell)
                        else:
                            def mpl_root(page, demo=demo):
                                return ca._voila_root(page, demo)
                        shots = {way: results / f"pixels_alt_{demo.cell}_{way}_{where}.png"
                                 for way in ("matplotlib", "pixels")}
                        grabs = {way: scratch / f"{demo.cell}_{way}_{where}.png" for way in shots}
                        entry[where]["matplotlib_ipympl"] = ca._measure(
                            h, browser, server, ch.notebook, mpl_root, n, rest, shots["matplotlib"], lab=is_lab,
                            label=label, canvas_to=grabs["matplotlib"])
                        entry[where]["pixels_anywidget"] = ca._measure(
                            h, browser, server, alt_nb[demo.cell], alt_root, n, rest, shots["pixels"], lab=is_lab,
                            label=label, canvas_to=grabs["pixels"])
                        entry[where]["same_picture"] = _same_picture(grabs["matplotlib"], grabs["pixels"])
                        entry[where]["load_average"] = os.getloadavg()
                        print(f"# {ch.name}/{demo.cell} {where}: " + ", ".join(
                            f"{way} {st['median_ms']:.0f}/{st['p95_ms']:.0f} ms {st['kB_received_per_move']} kB"
                            for way, st in entry[where].items() if "median_ms" in st), file=sys.stderr)
            finally:
                browser.close()
    finally:
        shutil.rmtree(scratch, ignore_errors=True)
    out["verdicts"] = [v for key, e in out["demos"].items() for v in ca._verdicts(e, e["target_p95_ms"], demo=key)]
    out["load_average_end"] = os.getloadavg()
    out["finished"] = time.strftime("%Y-%m-%dT%H:%M:%S")
    return out
