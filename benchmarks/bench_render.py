"""Speed of the virtual site and of exact rendering (median and p95, never asserted).

Target: a 512×512 photo in ≤ 60 ms; building the default site in ≤ ~2 s.
Besides whole renders the benchmark times the parts of one 512×512 render
(the exact coarse intersection, one full-resolution DEM evaluation, the
texture sampling) so the report can say what bounds the speed.

The objects with height (issue 13): ``render_512`` ray-casts them (the default),
``render_512_bare`` does not (``objects=False``: the old renderer), and
``render_512_sun`` adds cast shadows; ``objects_cost_ratio_512`` is the ratio of
the medians.  ``render_512_forest`` is the slowest case, a photo over the most
forest; ``build_objects_step`` times the objects step alone.
"""

from __future__ import annotations

import time

import numpy as np
from _timing import measure, summarize


def run(quick: bool = False) -> dict:
    from scipy.ndimage import map_coordinates

    from aerophoto import geometry as g
    from aerophoto import render as R
    from aerophoto import simulate as sim
    from aerophoto import site as S

    out = {}
    # --- building the default site (uncached)
    samples = []
    for _ in range(1 if quick else 3):
        t0 = time.perf_counter()
        site = S.build_site(S.SiteParams())
        samples.append(time.perf_counter() - t0)
    out["build_site_default_10x5km_2m"] = summarize(samples)
    site = S.get_site()

    cam = g.Camera(100.0)
    strip = sim.strip_over_site(site, cam, 12000, 60, 7,
                                imperfections=sim.Imperfections(max_tilt_deg=3, crab_deg=2, max_height_percent=3,
                                                                curvature_percent=1, seed=1))
    poses = strip.poses
    for n, reps in ((256, 40), (512, 40), (1024, 10)):
        k = max(4, reps // 5) if quick else reps
        out[f"render_{n}"] = measure(lambda p, n=n: R.render(site, cam, p, n), k, warmup=2,
                                     args_for=lambda i: (poses[i % len(poses)],))
    k = 6 if quick else 30
    out["render_512_bare"] = measure(lambda p: R.render(site, cam, p, 512, objects=False), k, warmup=2,
                                     args_for=lambda i: (poses[i % len(poses)],))
    out["render_512_sun"] = measure(lambda p: R.render(site, cam, p, 512, sun=R.Sun(225.0, 40.0)), k, warmup=1,
                                    args_for=lambda i: (poses[i % len(poses)],))
    out["objects_cost_ratio_512"] = round(out["render_512"]["median_ms"] / out["render_512_bare"]["median_ms"], 2)
    # the photo over the most forest the default site has (its north-west)
    forest_pose = g.Pose(2600.0, 3300.0, site.mean_height_m + 1200.0)
    out["render_512_forest"] = measure(lambda: R.render(site, cam, forest_pose, 512), k, warmup=1)
    out["render_512_forest_bare"] = measure(lambda: R.render(site, cam, forest_pose, 512, objects=False), k, warmup=1)
    out["render_1536_stereo_pair_photo_sun"] = measure(
        lambda: R.render(site, cam, poses[3], 1536, sun=R.Sun(225.0, 40.0)), 2 if quick else 4, warmup=1)
    out["build_objects_step"] = _objects_step(quick)
    ph = R.render(site, cam, poses[3], 512, keep_ground=True)
    out["render_512_dem_evaluations"] = ph.dem_evaluations
    out["render_512_dem_residual_m"] = ph.dem_residual_m

    # --- parts of one 512×512 render
    n = 512
    k = 10 if quick else 40
    grid = R._pixel_grid_mm(cam.frame_mm, n)
    idx, A = R._coarse_plan(n, R.COARSE_STEP)
    coarse_xy = grid[np.ix_(idx, idx)]
    out["part_coarse_exact_intersection_65x65"] = measure(
        lambda: g.photo_to_dem(cam, poses[3], coarse_xy, site, tol_m=1e-4), k)
    G = ph.ground_m.reshape(-1, 3)
    s = site.dem_spacing_m
    coords = np.stack([G[:, 1] / s, G[:, 0] / s])
    out["part_one_dem_evaluation_512"] = measure(lambda: map_coordinates(site.dem, coords, order=1, mode="nearest"), k)
    t = site.texel_m(ph.level)
    tcoords = np.stack([G[:, 1] / t - 0.5, G[:, 0] / t - 0.5])
    tex = site.texture_level(ph.level)
    out["part_texture_sampling_512"] = measure(
        lambda: map_coordinates(tex, tcoords, order=1, mode="nearest", output=np.float32), k)
    cv = R._camera_vectors(cam.f_mm, cam.frame_mm, n)
    Rm = g.rotation_matrix(poses[3])
    out["part_ray_directions_512"] = measure(lambda: (cv @ Rm[2], cv @ Rm[0], cv @ Rm[1]), k)
    return out


def _objects_step(quick: bool) -> dict:
    """The objects step of the default site's build alone (the painting steps run once, untimed)."""
    from aerophoto.site import SiteParams
    from aerophoto.site import build as B
    from aerophoto.site.objects import build_objects

    P = SiteParams()
    samples = []
    for _ in range(1 if quick else 3):
        b = B.Builder(P)
        river = B.river_line(b)
        dem = B.relief(b, river)
        systems = B.fields(b, river)
        B.soil_noise(b)
        roads, corners, belts = B.field_network(b, river, systems)
        forest_tex = B.shelter_belts(b, belts)
        village_c = B.highways(b, river, roads)
        band = B.floodplain(b, river)
        B.forest(b, band, village_c, forest_tex)
        B.river_water(b, band)
        B.oxbow_lake(b, river, roads)
        B.paint_roads(b, roads)
        B.village(b, river, village_c, roads)
        B.isolated_trees(b)
        tex = B.texture(b, dem)
        t0 = time.perf_counter()
        build_objects(b, dem, river, roads, village_c, tex, b.cv.cover, first_id=220)
        samples.append(time.perf_counter() - t0)
    return summarize(samples)
