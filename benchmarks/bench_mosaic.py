"""Speed of the fotoschema (chapter 05): prints, assembly, gluing and the live demo (median and p95).

    python benchmarks/run.py mosaic
    python benchmarks/run.py mosaic --quick

Measured (never asserted):

* ``render_print_<n>`` — rendering one print of the strip with :func:`aerophoto.render.render`
  (n × n pixels);
* ``assemble`` — :func:`aerophoto.mosaic.assemble` of a five-photo strip (tie points, motions, cuts,
  mismatches along the cuts, mean scale);
* ``glue_preview`` / ``glue_full`` — :func:`aerophoto.mosaic.sheet_raster` at the demo's preview
  (1 px/mm) and full (2.5 px/mm) resolutions, sampling the ground directly;
* ``glue_prints_5px`` — gluing five rendered 1024-px prints at 5 px/mm (the finished sheet);
* ``demo_update_preview`` — one slider event of :class:`aerophoto.demos.fotoschema.FotoschemaDemo` at
  preview resolution, with the relief stepping through 20 values: fly, assemble, glue, move the
  artists, refresh the tables and draw the figure once (under the Agg backend ``draw_idle`` draws at
  once, so this is everything the kernel does for a slider event; ipympl then only sends the image);
* ``demo_update_full`` — the same at full resolution (what follows when the slider rests);
* ``quality_demo_update`` — one slider event of the chapter 02 rough-mosaic demo, for comparison.

Target: a preview update ≤ 250 ms at p95.
"""

from __future__ import annotations


from _timing import measure, summarize

TARGET_PREVIEW_P95_MS = 250.0


def run(quick: bool = False) -> dict:
    import matplotlib

    matplotlib.use("Agg", force=True)
    from aerophoto import geometry as g
    from aerophoto import mosaic as mo
    from aerophoto import plots
    from aerophoto import render as R
    from aerophoto import simulate as sim
    from aerophoto.demos.fotoschema import FotoschemaDemo, default_ground

    plots.use_style()
    out = {"target_preview_p95_ms": TARGET_PREVIEW_P95_MS}
    gr = default_ground(60.0)
    cam = g.Camera(100.0)
    strip = sim.strip_over_site(gr, cam, 12000, 60, 5, imperfections=sim.Imperfections(max_tilt_deg=2, seed=1))
    pts = mo.catalogue_points(gr)

    for n, reps in ((512, 20), (1024, 8)):
        k = max(3, reps // 4) if quick else reps
        out[f"render_print_{n}"] = measure(lambda s, n=n: R.render_shot(gr, s, n), k, warmup=1,
                                           args_for=lambda i: (strip.shots[i % len(strip.shots)],))
    k = 5 if quick else 30
    out["assemble"] = measure(lambda: mo.assemble(strip, gr, points_m=pts), k)
    fs = mo.assemble(strip, gr, points_m=pts)
    out["glue_preview"] = measure(lambda: mo.sheet_raster(fs, gr, FotoschemaDemo.preview_px_per_mm), k)
    out["glue_full"] = measure(lambda: mo.sheet_raster(fs, gr, FotoschemaDemo.full_px_per_mm), max(3, k // 3))
    prints = R.render_strip(gr, strip, 1024)
    out["glue_prints_5px"] = measure(lambda: mo.sheet_raster(fs, gr, 5.0, photos=prints), max(3, k // 5))

    # the live demo: slider events at preview resolution
    demo = FotoschemaDemo()
    reliefs = [20.0 + 5.0 * (i % 20) for i in range(200)]
    n = 10 if quick else 40
    out["demo_update_preview"] = measure(lambda r: demo.set(preview=True, relief_m=r), n, warmup=2,
                                         args_for=lambda i: (reliefs[i],))
    out["demo_update_full"] = measure(lambda r: demo.set(relief_m=r), max(3, n // 4), warmup=1,
                                      args_for=lambda i: (reliefs[i + 100],))
    # stages of one preview update, as the model reports them
    stages = {"fly": [], "assemble": [], "glue": []}
    for i in range(5 if quick else 20):
        demo.set(preview=True, relief_m=reliefs[i + 150])
        for key in stages:
            stages[key].append(demo.result.timings_s[key])
    out["demo_preview_stages"] = {key: summarize(v) for key, v in stages.items()}
    p95 = out["demo_update_preview"]["p95_ms"]
    out["preview_p95_within_target"] = bool(p95 <= TARGET_PREVIEW_P95_MS)
    demo.close()

    from aerophoto.demos.quality import QualityDemo

    qd = QualityDemo()
    crabs = [-6.0 + 0.5 * (i % 24) for i in range(100)]
    out["quality_demo_update"] = measure(lambda c: qd.set(crab_deg=c), 8 if quick else 30, warmup=2,
                                         args_for=lambda i: (crabs[i],))
    qd.close()
    return out
