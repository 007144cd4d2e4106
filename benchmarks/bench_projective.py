"""The live demos of chapters 09–11 (guide §10–§12): kernel-side update time per slider change.

For every demo the headline sliders are cycled through their ranges by ``demo.set(...)`` and timed:

* ``compute_render``: ``set`` — the model, moving the artists and refreshing the table (ipympl's
  ``draw_idle`` only schedules a frame, so it is stubbed here);
* ``plus_agg_draw``: the same plus one forced Agg draw of the figure (what the kernel does before sending a
  frame) — the number the book's 100 ms budget is about;
* for the photo transformer, the photo sliders are timed as a drag is served: the preview render
  (``on_slider`` with a preview) — and, separately, the full-resolution update made when the slider rests.

Also: the error of cell-by-cell transfer against the exact map as the grid is refined (the physics'
numbers the chapter quotes), and the cost of one resection and one four-point rectification of a
rendered photo.
"""

from __future__ import annotations

import time

from _timing import summarize


def _cycle(params: dict, n: int):
    names = list(params)
    out = []
    for i in range(n):
        name = names[i % len(names)]
        vals = params[name]
        out.append({name: vals[(i // len(names)) % len(vals)]})
    return out


def _time_demo(demo, changes, *, preview=False):
    canvas = demo.fig.canvas
    canvas.draw_idle = lambda *a, **k: None
    demo.draw(force=True)
    for ch in changes[:3]:
        demo.set(**ch)
        demo.draw(force=True)
    demo.reset()
    demo.draw(force=True)
    kernel, drawn = [], []
    for ch in changes:
        t0 = time.perf_counter()
        if preview:
            demo.values.update(ch)
            demo._preview = True
            try:
                demo.update()
            finally:
                demo._preview = False
        else:
            demo.set(**ch)
        t1 = time.perf_counter()
        demo.draw(force=True)
        t2 = time.perf_counter()
        kernel.append(t1 - t0)
        drawn.append(t2 - t0)
    return {"slider_changes": len(changes), "compute_render": summarize(kernel), "plus_agg_draw": summarize(drawn)}


def run(quick: bool = False) -> dict:
    import matplotlib

    matplotlib.use("Agg")
    from aerophoto import plots

    with plots.style_context():
        return _run(quick)


def _run(quick: bool) -> dict:
    import numpy as np

    from aerophoto import projective as pj
    from aerophoto.demos import control as dc
    from aerophoto.demos import plan_correction as pc
    from aerophoto.demos import rectification as dr

    n = 15 if quick else 45
    out = {}
    d = pc.PlanCorrectionDemo()
    out["plan_correction_demo"] = _time_demo(d, _cycle(
        {"alpha_deg": [5.5, 8.0, 3.0, 12.0, 1.0], "n": [5, 8, 16, 2, 4], "method": ["proportional", "central"],
         "spread_percent": [80.0, 60.0, 95.0, 45.0], "lambda_deg": [-30.0, 40.0, 120.0, -150.0]}, n))
    d.close()
    d = dc.ControlDesignDemo()
    out["control_design_demo"] = _time_demo(d, _cycle(
        {"m_eps_arcmin": [7.0, 3.0, 5.5, 2.0], "m": [14500, 9000, 20000, 26000], "n_strips": [4, 2, 5, 1],
         "n_photos": [16, 8, 20, 12], "scheme": ["dense", "sparse"]}, n))
    d.close()
    d = dc.ResectionDemo()
    out["resection_demo"] = _time_demo(d, _cycle(
        {"north_m": [-100.0, 500.0, -900.0, 1200.0, -270.0], "east_m": [-250.0, 800.0, -820.0, 100.0],
         "sigma_arcsec": [10.0, 2.0, 25.0]}, n))
    d.close()
    d = dr.TransformerDemo()
    out["transformer_demo_step"] = _time_demo(d, _cycle({"step": list(range(1, 11)) + [4, 0, 7, 2]}, n))
    photo = _cycle({"alpha_deg": [3.5, 5.0, 8.0, 1.5, 6.5, 9.5], "lambda_deg": [-40.0, 20.0, 100.0, -140.0],
                    "kappa_deg": [4.0, -10.0, 20.0], "sigma_mm": [0.05, 0.0, 0.1]}, n)
    dr._run.cache_clear()
    dr._photo.cache_clear()
    dr._points.cache_clear()
    out["transformer_demo_photo_preview"] = _time_demo(d, photo, preview=True)
    dr._run.cache_clear()
    dr._photo.cache_clear()
    dr._points.cache_clear()
    out["transformer_demo_photo_full_on_release"] = _time_demo(d, photo)
    d.close()

    # the physics the chapters quote
    r = pc.plan_correction_model(3.0, -60.0, 1, 85.0, "central")
    study = pj.transfer_study(r.pair.photo_corners, r.pair.plan_corners, ns=(1, 2, 4, 8, 16, 32), n_points=300)
    out["transfer_error_vs_n_at_3deg_mm"] = {int(k): {"central": round(float(v["central max, mm"]), 4),
                                                       "proportional": round(float(v["proportional max, mm"]), 4)}
                                              for k, v in study.iterrows()}
    from aerophoto import control as c

    K = dc.guide_points().to_numpy()
    P = K[:3].mean(axis=0) + np.array([-150.0, -300.0])
    b1, b2 = c.horizontal_angle_deg(P, K[0], K[1]), c.horizontal_angle_deg(P, K[1], K[2])
    samples = []
    for _ in range(200 if not quick else 50):
        t0 = time.perf_counter()
        c.resect(K[0], K[1], K[2], b1, b2)
        samples.append(time.perf_counter() - t0)
    out["one_resection"] = summarize(samples)
    from aerophoto.render import render
    from aerophoto.labs import ch11

    lab = ch11.example_rectification_lab(False)
    img = render(dr._site(True), lab.camera, lab.pose, 512).image
    samples = []
    for _ in range(10 if not quick else 3):
        t0 = time.perf_counter()
        pj.warp_photo(img, lab.rectification.transform, (-250, 250, -250, 250), 1.0, frame_mm=180.0)
        samples.append(time.perf_counter() - t0)
    out["rectify_512px_photo_onto_500x500_base"] = summarize(samples)
    out["target"] = "plus_agg_draw p95 ≤ 100 ms for every demo (photo sliders: the preview while dragging)"
    return out
