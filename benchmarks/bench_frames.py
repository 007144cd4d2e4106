"""What a live figure's frame costs the kernel to encode, and how far a lossy frame is from the exact picture.

    python benchmarks/run.py frames            # the eight image-heavy demos and the floor, 8 moves each
    python benchmarks/run.py frames --quick    # 3 moves each

Per demo (the registry's demo classes, each on the slider the browser benchmark times, moved →/← in a fresh
Python with matplotlib's web canvas, as ipympl's, inside a running event loop as in a kernel, after two untimed
moves: a demo with a preview sends its preview first), for the frame each move sends (the changed pixels as a
diff, or the whole picture):

* ``on_slider_ms`` — the move itself, served as the slider's callback serves it (``LiveDemo._serve_slider``:
  compute, render, the blitted Agg draw; a table that follows the picture is not in it);
* ``sent`` — the frame the book sends for the move (:func:`aerophoto.plots.fast_frames`: a JPEG at the quality
  the demo chose when at least :data:`aerophoto.plots.PHOTO_SHARE` of a photo demo's picture changed, else the
  PNG of the changed pixels), and
  ``kernel_ms`` = ``on_slider_ms`` + its encoding: the kernel's part of the move, which the browser benchmark
  uses to bound a demo's ratio to the floor (:func:`kernel_per_move`);
* per encoding, ``encode_ms`` (process CPU time), ``kB`` and ``decode_ms`` (PIL, a stand-in for the page's
  decode): matplotlib's own frame (``mpl_png6``: PIL, zlib 6, filtered rows), the book's before this issue
  (``pil_png1``: PIL at zlib 1), the book's now (``png1``: unfiltered rows, zlib 1 — the same pixels) and, for
  the whole picture, JPEG at quality 60 … 95 with full-resolution chroma (4:4:4);
* for the JPEGs, the visual difference from the exact pixels: CIEDE2000 ΔE₀₀ (scikit-image) — its mean, its
  99th percentile and the share of pixels above 5.  ``chosen`` is the lowest quality whose mean ΔE₀₀ ≤ 1 (about
  one just-noticeable difference) on every demo that sends photo frames (``photo_frames``:
:attr:`aerophoto.widgets.LiveDemo.photo_frames`; the contour map, a colour raster under thin lines, stays at
ΔE₀₀ 1.5 even at 95 and keeps lossless frames): :data:`aerophoto.plots.PHOTO_QUALITY` is set from it.
  The moves of a demo with a preview (``preview_frames``: the fotoschema; the transformer's timed slider, its
  step, is drawn whole at once, and its previews are held by tests/presentation/test_frames.py) send their preview;
  ``chosen_preview_quality`` is the lowest quality whose preview frames keep a mean ΔE₀₀ ≤ 1 and at most 2 % of
  pixels above ΔE₀₀ 5 (what tests/presentation/test_frames.py holds every photo frame to) on every such demo:
  :data:`aerophoto.plots.PREVIEW_QUALITY`;
* ``jpeg_from_share`` (photo demos) — the share of changed pixels from which the whole picture's JPEG at 95 is a
  smaller frame than the PNG of the changed pixels (the PNG's bytes scaled to that share):
  :data:`aerophoto.plots.PHOTO_SHARE` lies just above it.

Medians over the moves; the load average before and after.  Nothing is asserted.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DEMOS = ("aerophoto.demos.quality.QualityDemo", "aerophoto.demos.fotoschema.FotoschemaDemo",
         "aerophoto.demos.interpretation.ConditionsDemo", "aerophoto.demos.interpretation.KeyDemo",
         "aerophoto.demos.rectification.TransformerDemo", "aerophoto.demos.dem_contours.ContourDemo",
         "aerophoto.demos.loupe.LoupeDemo", "aerophoto.demos.spectral_explorer.SpectralExplorerDemo",
         "aerophoto.demos.ray.RayDemo")
QUALITIES = (60, 70, 75, 80, 85, 90, 95)

CHILD = r'''
import asyncio, importlib, io, json, statistics, sys, time
import numpy as np
import matplotlib
matplotlib.use("webagg")
from PIL import Image
from aerophoto import book, plots
plots.use_style()
QUALITIES = {qualities}
if QUALITIES:
    from skimage.color import deltaE_ciede2000, rgb2lab

def cpu_ms(fn):
    t = time.process_time(); out = fn(); return (time.process_time() - t) * 1000, out

def pil(arr, **kw):
    buf = io.BytesIO(); Image.fromarray(arr).save(buf, **kw); return buf.getvalue()

def decode_ms(data):
    return cpu_ms(lambda: np.asarray(Image.open(io.BytesIO(data)).convert("RGBA")))[0]

async def one(path, n):
    module, cls = path.rsplit(".", 1)
    Cls = getattr(importlib.import_module(module), cls)
    label = next(d.timed_slider for c in book.CHAPTERS for d in c.demos if d.cls == path)
    p = next(q for q in Cls.params if q.label == label)
    d = Cls(); c = d.fig.canvas
    c.draw_idle = lambda *a, **k: c.draw()
    c.draw()
    up = p.validate(p.default + p.step if p.default + p.step <= p.hi else p.default - p.step)
    for i in range(2):  # warm up (the first moves fill caches); not timed
        d._serve_slider(p.name, {{"new": up if i % 2 == 0 else p.default}})
        await asyncio.sleep(getattr(Cls, "settle_s", 0.0) + 0.35)
    c.draw()
    c.get_diff_image()  # the page has the picture at rest (the canvas' own record of what it last sent)
    last = np.asarray(c.get_renderer().buffer_rgba()).view(np.uint32).squeeze(2).copy()
    rows = []
    for i in range(n):
        # what the slider's callback does (LiveDemo._serve_slider: validate, on_slider, its table after the picture)
        t = time.perf_counter(); d._serve_slider(p.name, {{"new": up if i % 2 == 0 else p.default}})
        slider = (time.perf_counter() - t) * 1000
        px = np.asarray(c.get_renderer().buffer_rgba()).copy()
        buff = px.view(np.uint32).squeeze(2)
        changed = buff != last
        share = float(changed.mean())
        diff = np.where(changed, buff, 0).view(np.uint8).reshape(px.shape)
        last = buff.copy()
        preview = bool(getattr(d.result, "preview", False))
        row = {{"on_slider_ms": slider, "changed_share": share, "preview": preview}}
        # the frame the book sends for this move, made as ipympl asks for it (the canvas' get_diff_image, which
        # plots.fast_frames replaced): its diff, and its JPEG or PNG at the quality LiveDemo chose
        ms, data = cpu_ms(c.get_diff_image)
        row["sent"] = {{"encode_ms": ms, "kB": len(data or b"") / 1000, "decode_ms": decode_ms(data) if data else 0.0}}
        row["kernel_ms"] = slider + ms
        if QUALITIES:
            for name, fn in (("mpl_png6", lambda: pil(diff, format="png")),
                             ("pil_png1", lambda: pil(diff, format="png", compress_level=1)),
                             ("png1", lambda: plots._png(diff, 1, sparse=share < plots._RLE_SHARE))):
                ms, data = cpu_ms(fn)
                row[name] = {{"encode_ms": ms, "kB": len(data) / 1000, "decode_ms": decode_ms(data)}}
            lab = rgb2lab(px[..., :3])
        for q in QUALITIES:
            ms, data = cpu_ms(lambda: plots._jpeg(px[..., :3], q))
            got = np.asarray(Image.open(io.BytesIO(data)).convert("RGB"))
            de = deltaE_ciede2000(lab, rgb2lab(got))
            row[f"jpeg{{q}}"] = {{"encode_ms": ms, "kB": len(data) / 1000, "decode_ms": decode_ms(data),
                                 "dE00_mean": float(de.mean()), "dE00_p99": float(np.percentile(de, 99)),
                                 "share_dE00_above_5": float((de > 5).mean())}}
        rows.append(row)
        await asyncio.sleep(getattr(Cls, "settle_s", 0.0) + 0.35)  # a delayed full picture lands here (not timed)
        c.get_diff_image()  # ... and goes to the page
        last = np.asarray(c.get_renderer().buffer_rgba()).view(np.uint32).squeeze(2).copy()
    d.close()
    med = lambda xs: round(statistics.median(xs), 4)
    out = {{"slider": label, "figure_px": list(c.get_width_height()), "moves": n, "photo_frames": bool(Cls.photo_frames),
           "preview_frames": all(r["preview"] for r in rows),
           "on_slider_ms": med([r["on_slider_ms"] for r in rows]),
           "kernel_ms": med([r["kernel_ms"] for r in rows]),
           "changed_share": med([r["changed_share"] for r in rows])}}
    for k in ("sent", *(("mpl_png6", "pil_png1", "png1") if QUALITIES else ()), *[f"jpeg{{q}}" for q in QUALITIES]):
        out[k] = {{m: med([r[k][m] for r in rows]) for m in rows[0][k]}}
    return out

async def main(jobs):
    out = {{}}
    for path, n in jobs:
        try:
            out[path] = await one(path, n)
        except Exception as exc:  # one demo's failure is reported, the others still measured
            out[path] = {{"error": f"{{type(exc).__name__}}: {{exc}}"}}
    return out

print(json.dumps(asyncio.run(main(json.loads(sys.argv[1])))))
'''


def _child(jobs, qualities) -> dict:
    home = tempfile.mkdtemp(prefix="aerophoto-bench-frames-")
    env = {k: v for k, v in os.environ.items() if k != "MPLBACKEND"}
    env.setdefault("AEROPHOTO_HOME", home)
    r = subprocess.run([sys.executable, "-c", CHILD.format(qualities=tuple(qualities)), json.dumps(jobs)],
                       cwd=ROOT, env=env, capture_output=True, text=True, timeout=3600)
    if r.returncode != 0:
        raise RuntimeError(f"the frames benchmark failed:\n{r.stderr[-3000:]}")
    return json.loads(r.stdout.strip().splitlines()[-1])


def kernel_per_move(classes, n: int = 8) -> dict:
    """The kernel's part of a move of each demo class (dotted path → medians over ``n`` moves of its timed slider):
    ``kernel_ms`` — serving the move as the slider's callback does and encoding the frame the book sends — with
    ``on_slider_ms``, ``sent`` (encode_ms, kB, decode_ms) and ``figure_px``; a demo that fails has ``error``.
    ``benchmarks/bench_browser.py`` bounds each demo's ratio to the floor with it."""
    return _child([[c, n] for c in classes], ())


def run(quick: bool = False) -> dict:
    n = 3 if quick else 8
    load0 = [round(x, 2) for x in os.getloadavg()]
    demos = _child([[d, n] for d in DEMOS], QUALITIES)
    photo = [v for v in demos.values() if v["photo_frames"]]
    for v in photo:  # the changed share from which the whole picture's JPEG is the smaller frame (plots.PHOTO_SHARE)
        per_px = v["png1"]["kB"] / max(v["changed_share"], 1e-9)  # the PNG's kB per unit share changed
        v["jpeg_from_share"] = round(v[f"jpeg{max(QUALITIES)}"]["kB"] / per_px, 3) if v["changed_share"] > 0.02 else None
    ok = [q for q in QUALITIES if all(v[f"jpeg{q}"]["dE00_mean"] <= 1.0 for v in photo)]
    preview = [v for v in photo if v["preview_frames"]]
    ok_preview = [q for q in QUALITIES if all(v[f"jpeg{q}"]["dE00_mean"] <= 1.0
                                              and v[f"jpeg{q}"]["share_dE00_above_5"] <= 0.02 for v in preview)]
    return {"method": __doc__.split("Per demo")[1].split("Medians")[0].strip().replace("\n", " "), "demos": demos,
            "chosen_quality": ok[0] if ok else None,
            "chosen_preview_quality": ok_preview[0] if ok_preview else None, "load_before": load0,
            "load_after": [round(x, 2) for x in os.getloadavg()]}
