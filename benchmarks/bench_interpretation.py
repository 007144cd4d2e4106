"""The interpretation chapter (08): colour photos against greyscale ones, and the conditions demo.

* ``photo_512`` — a 512² photo of the interpretation site with the sun (shadows): ``greyscale`` is
  :func:`aerophoto.render.render` of its site (the renderer every chapter uses); ``colour`` is
  :func:`aerophoto.site.colour.render_colour` (the same render with the ground kept, plus the six bands, haze and
  blur), both geometry caches cleared each time; ``colour_new_sun`` a new sun over a cached render (the shadows
  and shading only); ``colour_recolour_only`` recolours a cached geometry (what every
  slider but the sun's costs).  Goal: colour ≤ ~2× greyscale.
* ``conditions_demo`` — :class:`aerophoto.demos.interpretation.ConditionsDemo` driven through slider changes
  (``compute_render_only`` = ``demo.set``; ``live_set_plus_agg_draw`` adds one forced Agg draw), all sliders
  mixed, and split into the sun's sliders (a new render of the patch's shadows; cached per sun position) and the
  others (recolour only).  Goal: p95 ≤ 150 ms kernel side.
* ``key_demo`` — :class:`aerophoto.demos.interpretation.KeyDemo` stepping through the rows (each a new close-up).
* ``key_first_view`` — each row of the key seen for the first time, as a student's slider move meets it (the
  renders' caches cleared, so nothing of that row is rendered yet): ``preview`` is the book's path (the quick
  :data:`~aerophoto.demos.interpretation.KEY_PREVIEW_PX` close-up at once, the slider move's
  ``preview_then_full``) plus the canvas update; ``baseline_full`` is the same first view at full resolution
  (:data:`~aerophoto.demos.interpretation.KEY_PX`, what every first view cost before, and what follows the
  preview once the slider rests), interleaved row by row so both see the same load.  Goal: preview ≤ 300 ms.
* ``lab`` — the answer keys of all 100 variants, and one student's photo (1024², six bands).
"""

from __future__ import annotations

import time

from _timing import measure, time_demo_moves


def _drive(demo, changes):
    moves = time_demo_moves(demo, changes, by=lambda ch: "sun" if next(iter(ch)).startswith("sun_") else "other")
    by = moves.pop("compute_render_only_by")
    return {"slider_changes": len(changes), **moves, "sun_sliders_kernel": by.get("sun", {"n": 0}),
            "other_sliders_kernel": by.get("other", {"n": 0}), "target": "p95 ≤ 150 ms (kernel side)"}


def _key_first_views(di, colour, quick: bool) -> dict:
    """See the module notes (``key_first_view``)."""
    import os

    from _timing import summarize

    demo = di.KeyDemo()
    demo.fig.canvas.draw_idle = lambda *a, **k: None
    demo.draw(force=True)
    load = [os.getloadavg()[0]]
    preview, full = [], []
    rows = list(range(2, di.N_KEY_ROWS + 1)) * (1 if quick else 2)  # the slider counts rows from 1
    for r in rows:
        for path, out in (("preview", preview), ("full", full)):
            colour._base.cache_clear()
            colour._geometry.cache_clear()
            demo._seen.clear()
            demo.values["row"] = 1
            t0 = time.perf_counter()
            demo.values["row"] = r
            demo._preview = path == "preview"
            try:
                demo.update()
            finally:
                demo._preview = False
            demo.draw()
            out.append(time.perf_counter() - t0)
    load.append(os.getloadavg()[0])
    demo.close()
    return {"rows": len(rows), "preview": summarize(preview), "baseline_full": summarize(full),
            "preview_px": di.KEY_PREVIEW_PX, "full_px": di.KEY_PX, "load_1min_before_after": load,
            "target": "preview ≤ 300 ms (kernel side)"}


def run(quick: bool = False) -> dict:
    import matplotlib

    matplotlib.use("Agg")
    from aerophoto import geometry as g
    from aerophoto import interpretation as ip
    from aerophoto import plots
    from aerophoto.demos import interpretation as di
    from aerophoto.render import Sun, render
    from aerophoto.site import colour, cover
    from aerophoto.labs import ch08
    from aerophoto.variants import variant_for_index

    out = {}
    t0 = time.perf_counter()
    isite = cover.build_interpretation_site(0)
    out["site_build_s"] = round(time.perf_counter() - t0, 2)
    isite = cover.interpretation_site(0)
    cam = g.Camera()
    pose = colour.vertical_pose(isite, 800.0, 800.0, 8500.0)
    cond = ip.Conditions()
    n = 5 if quick else 15
    grey = measure(lambda: render(isite.site, cam, pose, 512, sun=Sun(cond.sun_azimuth_deg, cond.sun_elevation_deg)),
                   n, warmup=1)

    def colour_fresh():
        colour._geometry.cache_clear()
        colour._base.cache_clear()
        colour.render_colour(isite, cam, pose, 512, cond)

    col = measure(colour_fresh, n, warmup=1)
    suns = iter(range(10, 90))

    def new_sun():
        colour.colour_geometry(isite, cam, pose, 512, sun_elevation_deg=next(suns))

    sun = measure(new_sun, min(n, 30), warmup=1)
    geom = colour.colour_geometry(isite, cam, pose, 512)
    recol = measure(lambda: colour.colour_photo(geom, cond), n, warmup=1)
    out["photo_512"] = {"greyscale": grey, "colour": col, "colour_new_sun": sun, "colour_recolour_only": recol,
                        "colour_over_greyscale_median": round(col["median_ms"] / grey["median_ms"], 2),
                        "target": "colour ≤ ~2× greyscale"}

    with plots.style_context():
        demo = di.ConditionsDemo()
        m = 24 if quick else 72
        seasons = ("summer", "autumn", "spring", "winter")
        changes = []
        for i in range(m):
            k = i % 8
            changes.append(
                {"visibility_km": 2 + (i * 7) % 58} if k in (0, 4) else
                {"season": seasons[(i // 8) % 4]} if k == 1 else
                {"moisture_pct": (i * 6) % 30} if k == 2 else
                {"exposure_ms": 0.5 + (i * 1.5) % 19} if k == 3 else
                {"speed_kmh": 100 + (i * 60) % 400} if k == 5 else
                {"sun_elevation_deg": 10 + 5 * ((i * 3) % 15)} if k == 6 else
                {"sun_azimuth_deg": 90 + 15 * ((i * 5) % 13)})
        out["conditions_demo"] = _drive(demo, changes)
        w, h = demo.fig.canvas.get_width_height()
        out["conditions_demo"]["figure_px"] = [w, h]
        key = di.KeyDemo()
        out["key_demo"] = _drive(key, [{"row": 1 + r % di.N_KEY_ROWS} for r in range(1, (6 if quick else 18) + 1)])
        out["key_first_view"] = _key_first_views(di, colour, quick)

    t0 = time.perf_counter()
    for i in range(100 if not quick else 10):
        ch08.truth(i)
    out["lab_answer_keys_100_s"] = round(time.perf_counter() - t0, 2)
    t0 = time.perf_counter()
    ch08.lab_photo(variant_for_index(57))
    out["lab_photo_1024_s"] = round(time.perf_counter() - t0, 2)
    return out


if __name__ == "__main__":
    import json

    print(json.dumps(run(), indent=2))
