"""The fotoschema preview drawn in the browser — a <canvas> widget fed with arrays — against matplotlib + ipympl.

    python -m pip install --no-deps --target ~/.cache/aerophoto-bench/anywidget-0.11.0 anywidget==0.11.0 psygnal==0.16.1
    python benchmarks/run.py canvas_alt             # 20 moves per host and way
    python benchmarks/run.py canvas_alt --quick     # 10

Issue 20 asks, for a demo that matplotlib through ipympl cannot bring within its target, for one alternative
that draws in the browser, measured on the same demo in the same run: its latency, its picture and the
dependencies it adds.  This benchmark does that for the fotoschema preview of chapter 05.

The two ways, same model, same slider (``α max, °``, 0–5 by 0.25, the chapter's headline slider), same
resolutions (the preview glued at 1 px/mm while the slider moves, 2.5 px/mm 0.35 s after it rests):

* **matplotlib** — chapter 05's own ``FotoschemaDemo`` in the chapter's notebook (ipympl: the kernel draws
  with Agg, blits, and sends the changed pixels as a PNG);
* **canvas** — a ~150-line ``anywidget`` widget (written into a scratch notebook at run time, never into
  ``notebooks/``): the kernel runs the same ``fotoschema_model`` and sends the sheet raster as 8-bit grey
  bytes (one binary buffer, ~75 kB for the preview) plus the overlay as JSON (frame outlines, cuts, check
  points with ΔI, tie and principal points, title, the ΔI chart's stems, in sheet mm); JavaScript puts the
  raster on an offscreen canvas, scales it onto the visible one (``drawImage``, smoothed) and strokes the
  overlay with the 2-D context — no PNG encoding in the kernel, no decoding in the page.

Latency is measured exactly as in bench_browser.py (``performance.now()`` in the page, keydown → the
requestAnimationFrame after the picture changed): ipympl's ``drawImage`` onto its canvas is stamped by the
harness's instrumentation; the canvas widget stamps itself the same way (its drawing done → the next animation
frame, pushed onto the same ``window.__aero.paints``).  Moves alternate →/←, 20 per host and way, each after
the previous move's full-resolution picture has painted; JupyterLab and Voilà.  Also recorded: the bytes the
page received from the kernel per move (all WebSocket frames), and a screenshot of each picture after the
last move (``benchmarks/results/canvas_alt_<way>_<host>.png``).

Dependencies: ``anywidget`` 0.11.0 (pure Python plus a prebuilt JupyterLab extension of ~550 kB of
JavaScript) and its import-time dependency ``psygnal`` 0.16.1 (an event library, compiled wheels); the rest it
needs (ipywidgets, typing-extensions) is here already.  They are installed **for this benchmark only**, outside the project's environment, by the command above (or into
``$AEROPHOTO_ANYWIDGET_DIR``); the benchmark adds that folder to the servers' kernels' PYTHONPATH and copies
the extension into the servers' private data folder, so neither the .venv nor environment.txt changes.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import sys
import time
from pathlib import Path

from _timing import load_module as _load
from _timing import summarize

ROOT = Path(__file__).resolve().parents[1]
HERE = Path(__file__).resolve().parent
ANYWIDGET_VERSION = "0.11.0"
PSYGNAL_VERSION = "0.16.1"
ANYWIDGET_DIR = Path(os.environ.get("AEROPHOTO_ANYWIDGET_DIR",
                                    Path.home() / ".cache" / "aerophoto-bench" / f"anywidget-{ANYWIDGET_VERSION}"))
CHAPTER = "05_fotoschema"
LABEL = "α max, °"
ALT_NOTEBOOK = "canvas_alt_fotoschema.ipynb"

#: the canvas widget's front end (an ES module for anywidget)
CANVAS_JS = r"""
const W = 880, H = 560, PX = 100 / 72;  // the matplotlib figure's size in pixels; points → pixels at 100 dpi
const C = {sky: "#56B4E9", orange: "#E69F00", green: "#009E73", black: "#000000", grey: "#999999",
           cutout: "#D55E00", duplicate: "#0072B2"};

function render({ model, el }) {
  const cv = document.createElement("canvas");
  cv.width = W; cv.height = H; cv.className = "aerophoto-alt-canvas";
  el.appendChild(cv);
  const ctx = cv.getContext("2d");
  const off = document.createElement("canvas");
  const octx = off.getContext("2d");

  const line = (pts, X, Y) => { ctx.beginPath(); pts.forEach((p, i) => (i ? ctx.lineTo : ctx.moveTo).call(ctx, X(p[0]), Y(p[1]))); };
  const text = (s, x, y, { size = 12, align = "center", base = "middle", color = "#000", bold = false } = {}) => {
    ctx.font = `${bold ? "bold " : ""}${size}px DejaVu Sans, sans-serif`;
    ctx.textAlign = align; ctx.textBaseline = base; ctx.fillStyle = color; ctx.fillText(s, x, y);
  };

  const draw = () => {
    const ov = model.get("overlay"), shape = model.get("shape"), dv = model.get("image");
    if (!ov || !ov.lim || !dv || !shape || shape.length !== 2) return;
    const [h, w] = shape;
    const src = new Uint8Array(dv.buffer, dv.byteOffset, dv.byteLength);
    if (off.width !== w || off.height !== h) { off.width = w; off.height = h; }
    const im = octx.createImageData(w, h), d = im.data;
    for (let i = 0, j = 0; i < src.length; i++, j += 4) { const v = src[i]; d[j] = v; d[j + 1] = v; d[j + 2] = v; d[j + 3] = 255; }
    octx.putImageData(im, 0, 0);

    ctx.setTransform(1, 0, 0, 1, 0, 0);
    ctx.fillStyle = "#ffffff"; ctx.fillRect(0, 0, W, H);
    // ---- the sheet, aspect equal, in the upper box
    const [x0, x1, y0, y1] = ov.lim, box = { l: 78, t: 28, w: 790, h: 322 };
    const s = Math.min(box.w / (x1 - x0), box.h / (y1 - y0));
    const L = box.l + (box.w - (x1 - x0) * s) / 2, T = box.t + (box.h - (y1 - y0) * s) / 2;
    const X = (x) => L + (x - x0) * s, Y = (y) => T + (y1 - y) * s;
    ctx.save(); ctx.beginPath(); ctx.rect(L, T, (x1 - x0) * s, (y1 - y0) * s); ctx.clip();
    const [e0, e1, f0, f1] = ov.extent;
    ctx.imageSmoothingEnabled = true;
    ctx.drawImage(off, X(e0), Y(f1), (e1 - e0) * s, (f1 - f0) * s);
    ctx.lineWidth = 0.8 * PX; ctx.strokeStyle = C.sky; ctx.globalAlpha = 0.9;
    for (const fr of ov.frames) { line(fr, X, Y); ctx.closePath(); ctx.stroke(); }
    ctx.globalAlpha = 1; ctx.lineWidth = 1.8 * PX; ctx.strokeStyle = C.orange;
    for (const c of ov.cuts) { line(c, X, Y); ctx.stroke(); }
    for (const [px, py, size, cut, bad] of ov.points) {
      ctx.beginPath(); ctx.arc(X(px), Y(py), Math.sqrt(size) / 2 * PX, 0, 2 * Math.PI);
      ctx.fillStyle = cut ? C.cutout : C.duplicate; ctx.fill();
      ctx.lineWidth = (bad ? 2.0 : 0.8) * PX; ctx.strokeStyle = bad ? "#000" : "#fff"; ctx.stroke();
    }
    ctx.lineWidth = 1.8 * PX; ctx.strokeStyle = C.green;
    for (const [tx, ty] of ov.ties) {
      const a = X(tx), b = Y(ty), r = 3 * PX;
      ctx.beginPath(); ctx.moveTo(a - r, b - r); ctx.lineTo(a + r, b + r); ctx.moveTo(a - r, b + r); ctx.lineTo(a + r, b - r); ctx.stroke();
    }
    ctx.strokeStyle = C.black;
    ov.o.forEach(([ox, oy], k) => {
      const a = X(ox), b = Y(oy), r = 5 * PX;
      ctx.beginPath(); ctx.moveTo(a - r, b); ctx.lineTo(a + r, b); ctx.moveTo(a, b - r); ctx.lineTo(a, b + r); ctx.stroke();
      ctx.fillStyle = "rgba(255,255,255,0.7)"; ctx.fillRect(a + 4 * PX, b + 5 * PX, 10 * PX, 14 * PX);
      text(String(ov.numbers[k]), a + 9 * PX, b + 12 * PX, { size: 13, bold: true });
    });
    ctx.restore();
    // axes: left and bottom spines, ticks every 50 mm (x) and 25 mm (y)
    ctx.strokeStyle = "#000"; ctx.lineWidth = 1;
    ctx.beginPath(); ctx.moveTo(L, T); ctx.lineTo(L, Y(y0)); ctx.lineTo(X(x1), Y(y0)); ctx.stroke();
    for (let t = Math.ceil(x0 / 50) * 50; t <= x1; t += 50) {
      ctx.beginPath(); ctx.moveTo(X(t), Y(y0)); ctx.lineTo(X(t), Y(y0) + 4); ctx.stroke(); text(String(t), X(t), Y(y0) + 12);
    }
    for (let t = Math.ceil(y0 / 25) * 25; t <= y1; t += 25) {
      ctx.beginPath(); ctx.moveTo(L, Y(t)); ctx.lineTo(L - 4, Y(t)); ctx.stroke(); text(String(t), L - 7, Y(t), { align: "right" });
    }
    text("along the strip, sheet mm", (L + X(x1)) / 2, Y(y0) + 30, { size: 13 });
    ctx.save(); ctx.translate(L - 48, (T + Y(y0)) / 2); ctx.rotate(-Math.PI / 2); text("across, mm", 0, 0, { size: 13 }); ctx.restore();
    text(ov.title, W / 2, 12, { size: 15 });
    // ---- ΔI along the cuts
    const c = { l: 78, t: 408, w: 730, h: 120 }, [u0, u1] = ov.dx, lim = ov.dlim;
    const U = (x) => c.l + (x - u0) / (u1 - u0) * c.w, V = (y) => c.t + (lim - y) / (2 * lim) * c.h;
    ctx.lineWidth = 1; ctx.strokeStyle = C.grey;
    ctx.beginPath(); ctx.moveTo(c.l, V(0)); ctx.lineTo(c.l + c.w, V(0)); ctx.stroke();
    ctx.setLineDash([1, 3]);
    for (const sx of ov.seps) { ctx.beginPath(); ctx.moveTo(U(sx), c.t); ctx.lineTo(U(sx), c.t + c.h); ctx.stroke(); }
    ctx.setLineDash([5, 3]); ctx.strokeStyle = C.cutout; ctx.lineWidth = 1.2 * PX;
    ctx.beginPath(); ctx.moveTo(c.l, V(-0.5)); ctx.lineTo(c.l + c.w, V(-0.5)); ctx.stroke(); ctx.setLineDash([]);
    text(" −0.5 mm", c.l + c.w, V(-0.5), { size: 12, align: "left", color: C.cutout });
    ov.stems.forEach(([x, y, cut]) => {
      ctx.strokeStyle = ctx.fillStyle = cut ? C.cutout : C.duplicate; ctx.lineWidth = 2.2 * PX;
      ctx.beginPath(); ctx.moveTo(U(x), V(0)); ctx.lineTo(U(x), V(y)); ctx.stroke();
      ctx.beginPath(); ctx.arc(U(x), V(y), 3 * PX, 0, 2 * Math.PI); ctx.fill();
    });
    ctx.strokeStyle = "#000"; ctx.lineWidth = 1;
    ctx.beginPath(); ctx.moveTo(c.l, c.t); ctx.lineTo(c.l, c.t + c.h); ctx.lineTo(c.l + c.w, c.t + c.h); ctx.stroke();
    for (const t of [-lim, -lim / 2, 0, lim / 2, lim]) text(t.toFixed(2), c.l - 6, V(t), { align: "right" });
    ov.ticks.forEach((t, k) => text(ov.labels[k], U(t), c.t + c.h + 12, { size: 13 }));
    ctx.save(); ctx.translate(c.l - 50, c.t + c.h / 2); ctx.rotate(-Math.PI / 2); text("ΔI, mm", 0, 0, { size: 13 }); ctx.restore();
    // the picture is on the canvas: stamp it as the harness stamps ipympl's drawImage (painted at the next frame)
    const t0 = performance.now();
    requestAnimationFrame(() => { const A = window.__aero; if (A) A.paints.push({ kind: "alt", changed: t0, painted: performance.now() }); });
  };
  model.on("change:overlay", draw);
  draw();
}
export default { render };
"""

#: the scratch notebook of the canvas way (two cells: the widget, then the demo)
ALT_SETUP = r'''
import asyncio, sys
import matplotlib
matplotlib.use("Agg")   # no matplotlib figure is shown here
import numpy as np
import ipywidgets as w
import anywidget, traitlets
from aerophoto import mosaic as mo
from aerophoto.i18n import t as _t
from aerophoto.demos.fotoschema import FotoschemaDemo, fotoschema_model, _nice_up, _sheet_limits


class SheetCanvas(anywidget.AnyWidget):
    """The fotoschema drawn in the browser: the raster as 8-bit grey bytes, the overlay as JSON."""
    _esm = {esm!r}
    image = traitlets.Bytes(b"").tag(sync=True)
    shape = traitlets.List([]).tag(sync=True)
    overlay = traitlets.Dict({{}}).tag(sync=True)


def overlay(r, seq):
    fs = r.fs
    dI = fs.dI_mm
    pts = np.vstack([s.points_mm for s in fs.seams])
    size = 12.0 + 260.0 * np.minimum(np.abs(dI), 1.5)
    bad = np.round(dI, 2) < -mo.ALLOWED_CUTOUT_MM
    ties = np.vstack([T.apply(s.ties.photo_a_mm) for s, T in zip(fs.seams, fs.to_sheet[:-1])])
    xs, ticks, labels, seps, x = [], [], [], [], 0.0
    for k, s in enumerate(fs.seams):
        n = len(s.dI_mm)
        xs += list(x + np.arange(1, n + 1))
        ticks.append(x + (n + 1) / 2.0)
        labels.append(_t("cut {{a}}/{{b}}", a=s.numbers[0], b=s.numbers[1]))
        x += n + 1.5
        if k < len(fs.seams) - 1:
            seps.append(x - 0.25)
    res = _t("preview") if r.preview else _t("full resolution")
    title = _t("Fotoschema 1:{{m}} · m = {{rms:.2f}} mm · {{verdict}} · {{res}}", m=f"{{fs.scale.m:,.0f}}".replace(",", " "),
               rms=fs.rms_mm, verdict=_t("seams pass") if fs.ok else _t("cut-out > 0.5 mm"), res=res)
    return {{
        "seq": seq, "lim": list(_sheet_limits(fs.extent_mm)), "extent": [float(v) for v in r.extent_mm],
        "frames": [f.tolist() for f in fs.frames_mm()], "cuts": [s.cut_mm.tolist() for s in fs.seams],
        "points": [[float(p[0]), float(p[1]), float(z), bool(d < 0), bool(b)] for p, z, d, b in zip(pts, size, dI, bad)],
        "ties": ties.tolist(), "o": fs.principal_points_mm().tolist(), "numbers": [int(n) for n in fs.numbers],
        "title": title, "stems": [[float(a), float(b), bool(b < 0)] for a, b in zip(xs, dI)],
        "dx": [0.0, max(x - 0.5, 1.0)], "dlim": _nice_up(max(0.7, float(np.max(np.abs(dI))) * 1.15)),
        "ticks": ticks, "labels": labels, "seps": seps,
    }}
'''.lstrip()

ALT_DEMO = r'''
values = {k: p.default for k, p in ((p.name, p) for p in FotoschemaDemo.params)}
canvas = SheetCanvas()
slider = w.FloatSlider(value=values["alpha_max_deg"], min=0.0, max=5.0, step=0.25, readout_format=".1f",
                       description="α max, °", continuous_update=True, style={"description_width": "initial"})
state = {"seq": 0, "pending": None}


def show(preview):
    px = FotoschemaDemo.preview_px_per_mm if preview else FotoschemaDemo.full_px_per_mm
    r = fotoschema_model(values["f_mm"], values["m"], values["alpha_max_deg"], values["relief_m"],
                         values["px_percent"], values["cut_shape"], values["seed"], px_per_mm=px, preview=preview)
    grey = np.clip((r.image * 256.0).astype(np.int32), 0, 255).astype(np.uint8)[::-1]  # row 0 at the top
    state["seq"] += 1
    with canvas.hold_sync():
        canvas.shape = list(grey.shape)
        canvas.image = grey.tobytes()
        canvas.overlay = overlay(r, state["seq"])


def on_change(change):
    values["alpha_max_deg"] = float(change["new"])
    if state["pending"] is not None:
        state["pending"].cancel()
    show(True)   # the preview now, the full picture once the slider rests (as FotoschemaDemo.settle_s)
    state["pending"] = asyncio.get_running_loop().call_later(FotoschemaDemo.settle_s, show, False)


slider.observe(on_change, names="value")
show(False)
ui = w.VBox([slider, canvas])
ui.add_class("aerophoto-alt")
ui
'''.lstrip()




def _anywidget_ready() -> None:
    if not (ANYWIDGET_DIR / "anywidget" / "__init__.py").exists():
        raise RuntimeError(
            f"anywidget {ANYWIDGET_VERSION} is not in {ANYWIDGET_DIR}; install it for this benchmark only with:\n"
            f"  python -m pip install --no-deps --target {ANYWIDGET_DIR} anywidget=={ANYWIDGET_VERSION} "
            f"psygnal=={PSYGNAL_VERSION}")


def _write_alt(folder: Path) -> None:
    import nbformat
    from nbformat.v4 import new_code_cell, new_notebook

    nb = new_notebook(cells=[new_code_cell(ALT_SETUP.format(esm=CANVAS_JS), id="setup"),
                             new_code_cell(ALT_DEMO, id="demo-canvas-alt")])
    nb.metadata["kernelspec"] = {"name": "python3", "display_name": "Python 3", "language": "python"}
    nbformat.write(nb, str(folder / ALT_NOTEBOOK))


def _with_anywidget(server):
    """Give a server (not started yet) the anywidget front end in its private data folder."""
    dest = server.tmp / "data" / "labextensions" / "anywidget"
    dest.parent.mkdir(parents=True, exist_ok=True)
    shutil.copytree(ANYWIDGET_DIR / "share" / "jupyter" / "labextensions" / "anywidget", dest, dirs_exist_ok=True)
    return server


def _bytes_counter(page) -> list:
    sizes: list = []

    def on_ws(ws):
        ws.on("framereceived", lambda payload: sizes.append(len(payload)))

    page.on("websocket", on_ws)
    return sizes


def _measure(h, browser, server, notebook, root_of, n, rest_ms, shot: Path, *, lab: bool, label: str = LABEL,
             canvas_to: Path | None = None) -> dict:
    """Time ``n`` moves of the slider ``label`` inside ``root_of(page)``; bytes received per move, a screenshot
    (and, with ``canvas_to``, the picture's own canvas pixels as a PNG there)."""
    page, log = h.new_page(browser)
    try:
        sizes = _bytes_counter(page)
        if lab:
            h.open_lab_notebook(page, server, notebook)
            h.run_all_cells(page)
        else:
            h.open_voila(page, server, notebook)
        root = root_of(page)
        root.wait_for(state="visible", timeout=h.T_RUN)
        root.scroll_into_view_if_needed()
        h.settle(page, 1000)
        slider = h.slider_in(page, root, label)

        def after_move():
            h.settle(page, rest_ms)
            if lab:
                h.lab_kernel_idle(page)

        before = sum(sizes)
        out = h.time_slider_moves(page, slider, n, after_move=after_move)
        received = sum(sizes) - before
        pic = root.locator("canvas.aerophoto-alt-canvas, .jupyter-matplotlib-canvas-div").first
        shot.parent.mkdir(exist_ok=True)
        pic.screenshot(path=str(shot))
        if canvas_to is not None:
            import base64

            url = pic.evaluate("(el) => (el.tagName === 'CANVAS' ? el : el.querySelector('canvas')).toDataURL('image/png')")
            canvas_to.write_bytes(base64.b64decode(url.split(",", 1)[1]))
        s = summarize(out["samples_s"])
        s["distinct_values"] = sorted(set(out["values"]))
        s["kB_received_per_move"] = round(received / n / 1000.0, 1)  # preview and full picture, all messages
        s["screenshot"] = str(shot.relative_to(ROOT))
        if log.relevant():
            s["console_errors"] = log.relevant()
        return s
    finally:
        page.context.close()
        if lab:
            server.shutdown_kernels()


@contextlib.contextmanager
def _kernels_see_anywidget():
    """While servers are started inside: their kernels find anywidget (PYTHONPATH), the project's .venv untouched."""
    old_pp = os.environ.get("PYTHONPATH")
    os.environ["PYTHONPATH"] = os.pathsep.join([str(ANYWIDGET_DIR)] + ([old_pp] if old_pp else []))
    try:
        yield
    finally:
        if old_pp is None:
            os.environ.pop("PYTHONPATH", None)
        else:
            os.environ["PYTHONPATH"] = old_pp


def _voila_root(page, demo):
    """A chapter demo's root on a Voilà page (no cell ids there): the ``demo.nth`` demo with its sliders."""
    loc = page.locator(".aerophoto-demo")
    for label, _k in demo.sliders:
        loc = loc.filter(has=page.locator(f'.widget-label:text-is("{label}")'))
    return loc.nth(demo.nth)


def _verdicts(entry: dict, target_ms: float, **tag) -> list:
    """One row per host and way of a measured ``entry`` ({host: {way: stats}}): median, p95, whether the p95 is
    within ``target_ms``, kB per move; ``tag`` (e.g. the demo) is added to every row."""
    return [{**tag, "where": where, "way": way, "median_ms": st["median_ms"], "p95_ms": st["p95_ms"],
             "meets_target": st["p95_ms"] <= target_ms, "kB_received_per_move": st["kB_received_per_move"]}
            for where in ("jupyterlab", "voila") for way, st in entry[where].items()
            if isinstance(st, dict) and "median_ms" in st]


@contextlib.contextmanager
def _alt_servers(h, write):
    """A JupyterLab and a Voilà server on one scratch folder, both with anywidget's front end and kernels that see
    it; ``write(root_dir)`` puts the scratch notebooks there first.  Yields ``(lab, voila, what write returned)``;
    on a failure prints the servers' logs; always stops the servers and removes their folders."""
    servers, made = [], []
    try:
        lab = _with_anywidget(h.LabServer())
        made.append(lab)
        written = write(lab.root_dir)
        voila = _with_anywidget(h.VoilaServer(lab.root_dir))
        made.append(voila)
        with _kernels_see_anywidget():
            for s in (lab, voila):
                s.start()
                servers.append(s)
        yield lab, voila, written
    except Exception:
        for s in servers:
            print(f"--- {s.kind} server log ({s.root_dir}):\n{s.log_tail(40)}", file=sys.stderr)
        raise
    finally:
        for s in servers:
            s.stop()
        for s in made:
            shutil.rmtree(s.tmp, ignore_errors=True)


def run(quick: bool = False) -> dict:
    _anywidget_ready()
    h = _load("aerophoto_browser_harness", ROOT / "tests" / "browser" / "harness.py")
    chapters = _load("aerophoto_browser_chapters", ROOT / "tests" / "browser" / "chapters.py")
    bb = _load("bench_browser", HERE / "bench_browser.py")
    from playwright.sync_api import sync_playwright

    ch = next(c for c in chapters.CHAPTERS if c.name == CHAPTER)
    demo = ch.demos[0]
    n = 10 if quick else 20
    rest = bb._rest_ms(demo)
    results = HERE / "results"
    out = {"method": __doc__.split("Latency is measured")[1].split("Dependency:")[0].strip().replace("\n", " "),
           "moves": n, "demo": f"{CHAPTER}/{demo.cell} [{LABEL}]", "target_p95_ms": bb.target_p95_ms(CHAPTER),
           "dependencies_added": {"anywidget": ANYWIDGET_VERSION, "psygnal": PSYGNAL_VERSION,
                                  "installed_to": str(ANYWIDGET_DIR),
                                  "project_environment_changed": False},
           "jupyterlab": {}, "voila": {}}
    with _alt_servers(h, _write_alt) as (lab, voila, _written), sync_playwright() as pw:
        browser = h.launch_chromium(pw)
        try:
            def alt_root(page):
                return page.locator(".aerophoto-alt").first

            def voila_root(page):
                return _voila_root(page, demo)

            for where, server, is_lab in (("jupyterlab", lab, True), ("voila", voila, False)):
                mpl_root = (lambda page: h.lab_demo_root(page, demo.cell)) if is_lab else voila_root
                out[where]["matplotlib_ipympl"] = _measure(
                    h, browser, server, ch.notebook, mpl_root, n, rest,
                    results / f"canvas_alt_matplotlib_{where}.png", lab=is_lab)
                out[where]["canvas_anywidget"] = _measure(
                    h, browser, server, ALT_NOTEBOOK, alt_root, n, rest,
                    results / f"canvas_alt_canvas_{where}.png", lab=is_lab)
                out[where]["load_average"] = os.getloadavg()
        finally:
            browser.close()
    out["verdicts"] = _verdicts(out, out["target_p95_ms"])
    out["finished"] = time.strftime("%Y-%m-%dT%H:%M:%S")
    return out
