"""What a live figure's frame costs the kernel to encode, and how far a lossy frame is from the exact picture.

    python benchmarks/run.py frames            # the six image-heavy demos and the floor, 8 moves each
    python benchmarks/run.py frames --quick    # 3 moves each

Per demo (the registry's demo classes, each on the slider the browser benchmark times, moved →/← in a fresh
Python with matplotlib's web canvas, as ipympl's, inside a running event loop as in a kernel: a demo with a
preview sends its preview first), for the frame each move sends (the changed pixels as a diff, or
the whole picture when most of it changed):

* ``on_slider_ms`` — the move itself (compute, render, the blitted Agg draw);
* per encoding, ``encode_ms`` (process CPU time), ``kB`` and ``decode_ms`` (PIL, a stand-in for the page's
  decode): matplotlib's own frame (``mpl_png6``: PIL, zlib 6, filtered rows), the book's before this issue
  (``pil_png1``: PIL at zlib 1), the book's now (``png1``: unfiltered rows, zlib 1 — the same pixels) and, for
  the whole picture, JPEG at quality 85 / 90 / 95 with full-resolution chroma (4:4:4);
* for the JPEGs, the visual difference from the exact pixels: CIEDE2000 ΔE₀₀ (scikit-image) — its mean, its
  99th percentile and the share of pixels above 5.  ``chosen`` is the lowest quality whose mean ΔE₀₀ ≤ 1 (about
  one just-noticeable difference) on every demo that sends photo frames (``photo_frames``:
:attr:`aerophoto.widgets.LiveDemo.photo_frames`; the contour map, a colour raster under thin lines, stays at
ΔE₀₀ 1.5 even at 95 and keeps lossless frames): :data:`aerophoto.plots.PHOTO_QUALITY` is set from it.

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
         "aerophoto.demos.ray.RayDemo")
QUALITIES = (85, 90, 95)

CHILD = r'''
import asyncio, importlib, io, json, statistics, sys, time
import numpy as np
import matplotlib
matplotlib.use("webagg")
from PIL import Image
from skimage.color import deltaE_ciede2000, rgb2lab
from aerophoto import book, plots
plots.use_style()
QUALITIES = {qualities}

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
    last = np.asarray(c.get_renderer().buffer_rgba()).view(np.uint32).squeeze(2).copy()
    up = p.validate(p.default + p.step if p.default + p.step <= p.hi else p.default - p.step)
    rows = []
    for i in range(n):
        d.values[p.name] = up if i % 2 == 0 else p.default
        t = time.perf_counter(); d.on_slider(); slider = (time.perf_counter() - t) * 1000
        px = np.asarray(c.get_renderer().buffer_rgba()).copy()
        buff = px.view(np.uint32).squeeze(2)
        changed = buff != last
        share = float(changed.mean())
        diff = np.where(changed, buff, 0).view(np.uint8).reshape(px.shape)
        last = buff.copy()
        row = {{"on_slider_ms": slider, "changed_share": share}}
        for name, fn in (("mpl_png6", lambda: pil(diff, format="png")),
                         ("pil_png1", lambda: pil(diff, format="png", compress_level=1)),
                         ("png1", lambda: plots._png(diff, 1, sparse=share < plots.PHOTO_SHARE))):
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
        await asyncio.sleep(getattr(Cls, "settle_s", 0.0) + 0.1)  # a delayed full picture lands here (not timed)
        last = np.asarray(c.get_renderer().buffer_rgba()).view(np.uint32).squeeze(2).copy()
    d.close()
    med = lambda xs: round(statistics.median(xs), 2)
    out = {{"slider": label, "figure_px": list(c.get_width_height()), "moves": n, "photo_frames": bool(Cls.photo_frames),
           "on_slider_ms": med([r["on_slider_ms"] for r in rows]),
           "changed_share": med([r["changed_share"] for r in rows])}}
    for k in ("mpl_png6", "pil_png1", "png1", *[f"jpeg{{q}}" for q in QUALITIES]):
        out[k] = {{m: med([r[k][m] for r in rows]) for m in rows[0][k]}}
    return out

jobs = json.loads(sys.argv[1])
print(json.dumps({{path: asyncio.run(one(path, n)) for path, n in jobs}}))
'''


def run(quick: bool = False) -> dict:
    n = 3 if quick else 8
    home = tempfile.mkdtemp(prefix="aerophoto-bench-frames-")
    env = {k: v for k, v in os.environ.items() if k != "MPLBACKEND"}
    env.setdefault("AEROPHOTO_HOME", home)
    load0 = [round(x, 2) for x in os.getloadavg()]
    r = subprocess.run([sys.executable, "-c", CHILD.format(qualities=QUALITIES), json.dumps([[d, n] for d in DEMOS])],
                       cwd=ROOT, env=env, capture_output=True, text=True, timeout=3600)
    if r.returncode != 0:
        raise RuntimeError(f"the frames benchmark failed:\n{r.stderr[-3000:]}")
    demos = json.loads(r.stdout.strip().splitlines()[-1])
    photo = [v for v in demos.values() if v["photo_frames"]]
    ok = [q for q in QUALITIES if all(v[f"jpeg{q}"]["dE00_mean"] <= 1.0 for v in photo)]
    return {"method": __doc__.split("Per demo")[1].split("Medians")[0].strip().replace("\n", " "), "demos": demos,
            "chosen_quality": ok[0] if ok else None, "load_before": load0,
            "load_after": [round(x, 2) for x in os.getloadavg()]}
