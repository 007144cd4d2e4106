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
* ``demo_update_preview_largest`` — the same at the largest variant's camera and scale (f = 1090 mm,
  1:21 900), the demo's four photos;
* ``quality_demo_update`` — one slider event of the chapter 02 rough-mosaic demo, for comparison;
* the student's own fotoschema (chapter 05's tasks), for the largest variant 99 (and variant 00 beside it):
  ``own_fotoschema`` (fly, assemble, the details along the cuts — uncached), ``own_readings_all_variants``
  (both tasks' reference answers for all 100 variants, uncached: what the grader builds),
  ``own_prints_1024`` (rendering the four prints), ``own_glue_5px`` (gluing them at 5 px/mm),
  ``own_sheet_export`` (the A3 sheet figure written as PNG at 150 dpi and PDF) and the sheet's size
  (``own_sheet_size``: pixels, paper, megabytes of the raster and the files).

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

    d2 = FotoschemaDemo(f_mm=1090, m=21900)
    out["demo_update_preview_largest"] = measure(lambda r: d2.set(preview=True, relief_m=r), max(3, n // 4),
                                                 warmup=1, args_for=lambda i: (reliefs[i + 50],))
    d2.close()
    out.update(_own_sheet(quick))

    qd = QualityDemo()
    crabs = [-6.0 + 0.5 * (i % 24) for i in range(100)]
    out["quality_demo_update"] = measure(lambda c: qd.set(crab_deg=c), 8 if quick else 30, warmup=2,
                                         args_for=lambda i: (crabs[i],))
    qd.close()
    return out


def _own_sheet(quick: bool) -> dict:
    """The student's own fotoschema and its finished sheet, for the largest variant (99) and the first (00)."""
    import tempfile
    import time
    from pathlib import Path

    from aerophoto import mosaic as mo
    from aerophoto.demos import fotoschema as F
    from aerophoto.labs import ch05
    from aerophoto.labs import own as _own
    from aerophoto.variants import variant_for_index

    out = {}
    v99, v00 = variant_for_index(99), variant_for_index(0)

    def uncached_fotoschema(v):
        ch05._own_fotoschema.cache_clear()
        _own.own_strip_of.cache_clear()
        return ch05.own_fotoschema(v)

    out["own_fotoschema_v99"] = measure(lambda: uncached_fotoschema(v99), 2 if quick else 5, warmup=1)
    out["own_fotoschema_v00"] = measure(lambda: uncached_fotoschema(v00), 2 if quick else 5, warmup=1)

    def all_readings():
        ch05._own_fotoschema.cache_clear()
        _own.own_strip_of.cache_clear()
        ch05._seam_readings.cache_clear()
        ch05._scale_readings.cache_clear()
        for i in range(100):
            ch05.answers_of(variant_for_index(i))

    out["own_readings_all_variants"] = measure(all_readings, 1, warmup=0)
    own = ch05.own_fotoschema(v99)
    F._own_prints.cache_clear()
    out["own_prints_1024_v99"] = measure(lambda: (F._own_prints.cache_clear(), F.own_prints(v99)), 1 if quick else 3,
                                         warmup=0)
    prints = list(F.own_prints(v99))
    out["own_glue_5px_v99"] = measure(lambda: mo.sheet_raster(own.fs, own.site, 5.0, photos=prints),
                                      2 if quick else 5, warmup=1)
    folder = Path(tempfile.mkdtemp(prefix="bench-sheet-"))
    k = iter(range(1000))
    t0 = time.perf_counter()
    fig = F.student_sheet(v99, "Benchmark B.")
    build_s = time.perf_counter() - t0
    out["own_sheet_export_v99"] = measure(lambda: F.export_sheet(fig, folder, f"sheet{next(k)}"), 1 if quick else 3,
                                          warmup=0)
    image, _extent = F.own_sheet_image(v99)
    files = F.export_sheet(fig, folder, "final")
    out["own_sheet_size"] = {
        "raster_px": list(image.shape), "raster_MB": round(image.nbytes / 1e6, 1), "paper": fig.aerophoto_paper,
        "sheet_mm": [round(x, 1) for x in F.sheet_size_mm(own.fs)], "figure_build_ms": round(build_s * 1000, 1),
        "png_MB": round(files["png"].stat().st_size / 1e6, 2), "pdf_MB": round(files["pdf"].stat().st_size / 1e6, 2),
    }
    return out
