"""Chapter 13: the spectral explorer's update (kernel side), the soil layer and the lab's segmentation.

* ``compute_render_only``: ``demo.set(...)`` — the soil curve and its dried twin on 211 wavelengths, the
  six band values, the patch's three bands for 200 × 200 cells from the tabulated model, the composite, the
  artists moved and the table refreshed — with ``draw_idle`` stubbed (ipympl only schedules there).
* ``live_set_plus_agg_draw``: the same and one forced Agg draw — what the kernel does for one slider move.
* ``live_cpu_time``: the process CPU time of set + draw (less sensitive to other processes on a shared machine).
* ``live_plus_png_encode``: the same plus encoding the frame as PNG, as ipympl does before sending it.
  The changes cycle θ, H, d, the clods, the sun and (every tenth) the camera.
* ``soil_layer_site_s``: the soil layer of the whole 10 × 5 km site at 10 m (uncached);
  ``patch_s``: one student's patch (layer and composite, uncached); ``segment_s``: k-means of a patch (k = 5).
"""

from __future__ import annotations

import time

from _timing import in_book_style, time_demo_moves


def _cycle(n: int, cameras) -> list:
    th = [5, 30, 45, 12, 0, 25, 40, 18]
    hum = [0, 3, 5, 10, 15, 7.5, 1]
    d = [0.02, 0.1, 0.3, 0.6, 2.0, 1.0]
    out = []
    for i in range(n):
        k = i % 10
        if k in (0, 3, 6):
            out.append({"moisture_pct": th[(i // 3) % len(th)]})
        elif k in (1, 4):
            out.append({"humus_pct": hum[(i // 2) % len(hum)]})
        elif k in (2, 7):
            out.append({"particle_mm": d[(i // 2) % len(d)]})
        elif k == 5:
            out.append({"sun_elevation_deg": [10, 30, 60, 90][(i // 10) % 4]})
        elif k == 8:
            out.append({"roughness": [0.0, 0.1, 0.15, 0.05][(i // 10) % 4]})
        else:
            out.append({"camera": cameras[(i // 10) % len(cameras)]})
    return out


def run(quick: bool = False) -> dict:
    return in_book_style(_run, quick)


def _run(quick: bool) -> dict:

    from aerophoto import soilmap, spectral
    from aerophoto.demos.spectral_explorer import SpectralExplorerDemo
    from aerophoto.site import get_site
    from aerophoto.site import soils
    from aerophoto.labs import ch13
    from aerophoto.variants import variant_for_index

    site = get_site()
    n = 30 if quick else 100
    changes = _cycle(n, list(spectral.CAMERAS))
    t0 = time.perf_counter()
    demo = SpectralExplorerDemo()
    first_s = time.perf_counter() - t0
    canvas = demo.fig.canvas
    canvas.draw_idle = lambda *a, **k: None
    for cam in spectral.CAMERAS:  # every camera's white point once (cached, as after a first visit)
        demo.set(camera=cam)
    demo.reset()
    demo.draw(force=True)
    moves = time_demo_moves(demo, changes)
    demo.close()

    t0 = time.perf_counter()
    soils._build(site, (0.0, site.params.width_m, 0.0, site.params.height_m), 10.0, 0)
    layer_s = time.perf_counter() - t0
    v = variant_for_index(57)
    ch13._patch.cache_clear()
    t0 = time.perf_counter()
    p = ch13.patch_of(v)
    patch_s = time.perf_counter() - t0
    t0 = time.perf_counter()
    soilmap.segment_tones(p.composite, 5, seed=0)
    seg_s = time.perf_counter() - t0
    return {
        "slider_changes": n,
        "first_build_s": round(first_s, 3),
        **moves,
        "soil_layer_site_s": round(layer_s, 3),
        "patch_s": round(patch_s, 3),
        "segment_s": round(seg_s, 3),
        "target": "p95 ≤ 150 ms for live_set_plus_agg_draw (issue 14)",
    }


if __name__ == "__main__":
    import json

    print(json.dumps(run(), indent=2, ensure_ascii=False))
