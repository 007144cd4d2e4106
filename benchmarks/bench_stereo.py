"""The stereo chapter (07): the floating mark and the base–height explorer, the pair, the height model.

* ``floating_mark_*`` — :class:`aerophoto.demos.stereo.FloatingMarkDemo` driven through slider changes (p, x, y,
  now and then the area): ``compute_render_only`` is ``demo.set(...)`` (the kernel's work before a frame),
  ``live_set_plus_agg_draw`` adds the one forced Agg draw (with ipympl ``draw_idle`` only schedules it; it is
  stubbed here so the draw is counted once).  Target: p95 ≤ 100 ms kernel side.
* ``base_height_*`` — :class:`aerophoto.demos.stereo.BaseHeightDemo` the same way.
* ``lab_*`` — building a student's pair and its measurements (all 100 variants), rendering and normalising a pair
  at 1536 px (the anaglyph's), and the correlation height model at 512 px.
"""

from __future__ import annotations

import time

from _timing import measure, time_demo_moves


def _drive(demo, changes):
    moves = time_demo_moves(demo, changes)
    return {"slider_changes": len(changes), **moves, "target": "p95 ≤ 100 ms (kernel side)"}


def run(quick: bool = False) -> dict:
    import matplotlib

    matplotlib.use("Agg")
    from aerophoto import plots
    from aerophoto.demos import stereo as ds
    from aerophoto.site import get_site
    from aerophoto.labs import ch07
    from aerophoto.variants import variant_for_index

    out = {}
    with plots.style_context():
        t0 = time.perf_counter()
        get_site()
        out["site_build_s"] = round(time.perf_counter() - t0, 2)
        t0 = time.perf_counter()
        lab = ch07.example_lab()
        out["lab_example_s"] = round(time.perf_counter() - t0, 2)
        t0 = time.perf_counter()
        ch07.lab_images(lab, 1536)
        out["lab_images_1536_s"] = round(time.perf_counter() - t0, 2)
        t0 = time.perf_counter()
        ch07.height_model(lab)
        out["height_model_512_s"] = round(time.perf_counter() - t0, 2)
        t0 = time.perf_counter()
        for i in range(100 if not quick else 10):
            ch07.stereo_lab(variant_for_index(i))
        out["labs_of_the_variants_s"] = round(time.perf_counter() - t0, 2)

        n = 20 if quick else 60
        mark = ds.FloatingMarkDemo(lab=lab)
        p0 = round(lab.p0_mm, 2)
        changes = []
        for i in range(n):
            k = i % 6
            if k in (0, 1, 2):
                changes.append({"p_mm": round(p0 + 0.07 * ((i * 7) % 40) - 0.5, 2)})
            elif k == 3:
                changes.append({"x_mm": round(-15 + (i * 3.7) % 30, 1)})
            elif k == 4:
                changes.append({"y_mm": round(-10 + (i * 2.3) % 20, 1)})
            else:
                changes.append({"area": list(mark.areas)[(i // 6) % len(mark.areas)]})
        for ch in changes[:6]:  # warm-up: every area's anaglyph once
            mark.set(**ch)
        for a in mark.areas:
            mark.set(area=a)
        mark.reset()
        out["floating_mark"] = _drive(mark, changes)
        w, h = mark.fig.canvas.get_width_height()
        out["floating_mark"]["figure_px"] = [w, h]
        mark.close()

        base = ds.BaseHeightDemo()
        bch = []
        for i in range(n):
            k = i % 3
            bch.append({"B_m": 200 + (i * 97) % 2500} if k == 0 else {"H_m": 500 + (i * 613) % 20000} if k == 1
                       else {"f_mm": 70 + (i * 37) % 1000})
        out["base_height"] = _drive(base, bch)
        base.close()
        out["t_build_floating_mark_demo"] = measure(lambda: ds.FloatingMarkDemo(lab=lab).close(), 2, warmup=1)
    return out
