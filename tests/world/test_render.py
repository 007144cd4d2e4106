"""Rendered photos are exact central projections of the site's DEM and texture — and of the objects standing on it."""

from dataclasses import replace

import numpy as np
import pytest

from aerophoto import geometry as g
from aerophoto import render as R
from aerophoto import simulate as sim
from aerophoto import site as S

CAM = g.Camera(100.0, 180.0)


@pytest.fixture(scope="module")
def hilly():
    # strong relief so that a wrong intersection would show as a displacement of many pixels
    return S.get_site(width_m=4000, height_m=3000, relief_m=400.0, base_height_m=100.0, seed=5)


@pytest.fixture(scope="module")
def flat():
    return S.get_site(width_m=4000, height_m=3000, relief_m=0.0, base_height_m=120.0, seed=5)


POSES = [
    g.Pose(2000.0, 1500.0, 1300.0),
    g.Pose(1900.0, 1550.0, 1250.0, alpha_deg=5.0, lambda_deg=-60.0, kappa_deg=25.0),
    g.Pose(2100.0, 1450.0, 1350.0, alpha_deg=2.0, lambda_deg=150.0, kappa_deg=-100.0),
]


def test_pixel_convention(hilly):
    ph = R.render(hilly, CAM, POSES[0], 64, fiducials=False)
    p = ph.pixel_mm
    assert p == pytest.approx(180.0 / 64)
    assert np.allclose(ph.pixel_to_mm([0, 0]), [-90 + p / 2, 90 - p / 2])  # row 0 at the top (+y)
    assert np.allclose(ph.pixel_to_mm([63, 63]), [90 - p / 2, -90 + p / 2])
    assert np.allclose(ph.mm_to_pixel([0.0, 0.0]), [31.5, 31.5])  # o between the four middle pixels
    assert np.allclose(ph.mm_to_pixel([-90.0, 90.0]), [-0.5, -0.5])  # the frame corner is a pixel corner
    rc = np.random.default_rng(0).uniform(-0.5, 63.5, (50, 2))
    assert np.allclose(ph.mm_to_pixel(ph.pixel_to_mm(rc)), rc)
    grid = ph.pixel_centres_mm()
    assert grid.shape == (64, 64, 2)
    assert np.allclose(grid[5, 7], ph.pixel_to_mm([5, 7]))
    assert ph.extent_mm == (-90.0, 90.0, -90.0, 90.0)


@pytest.mark.parametrize("k", range(len(POSES)))
def test_every_pixel_is_the_ray_dem_intersection_and_samples_the_texture(hilly, k):
    pose = POSES[k]
    ph = R.render(hilly, CAM, pose, 192, vignetting=0.0, fiducials=False, keep_ground=True, objects=False)
    G = ph.ground_m.reshape(-1, 3)
    assert ph.valid.all()
    # on the DEM ...
    assert np.max(np.abs(G[:, 2] - hilly.height(G[:, 0], G[:, 1]))) <= 1e-3
    assert ph.dem_residual_m <= 1e-3
    # ... and on the ray through the pixel centre
    assert np.allclose(g.ground_to_photo(CAM, pose, G), ph.pixel_centres_mm().reshape(-1, 2), atol=1e-6)
    # the same ground point as the reference (bracketed) solver of geometry.photo_to_dem
    sel = np.random.default_rng(k).choice(len(G), 300, replace=False)
    ref = g.photo_to_dem(CAM, pose, ph.pixel_centres_mm().reshape(-1, 2)[sel], hilly, tol_m=1e-5)
    assert np.allclose(G[sel], ref, atol=0.02)
    # the pixel's value is the texture sampled at that ground point
    tex = hilly.sample(G[:, 0], G[:, 1], ph.level).reshape(ph.shape)
    assert np.allclose(ph.image, tex, atol=1e-6)
    assert ph.image.dtype == np.float32 and ph.image.shape == (192, 192)


def test_tight_tolerance(hilly):
    ph = R.render(hilly, CAM, POSES[1], 96, tol_m=1e-6, keep_ground=True, objects=False)
    G = ph.ground_m.reshape(-1, 3)
    assert np.max(np.abs(G[:, 2] - hilly.height(G[:, 0], G[:, 1]))) <= 1e-6
    assert ph.dem_evaluations >= 2


def _marker_site(site, points_xy):
    """The site with a uniform texture and a bright 3×3-texel marker centred on each given texel centre."""
    t = site.params.texture_m
    tex = np.full_like(site.texture, 60)
    for x, y in points_xy:
        c, r = int(x // t), int(y // t)
        tex[r - 1:r + 2, c - 1:c + 2] = 255
    return replace(site, texture=tex, _levels=[])


@pytest.mark.parametrize("k", range(len(POSES)))
def test_rendered_marker_lies_on_the_geometric_projection(hilly, k):
    pose = POSES[k]
    t = hilly.params.texture_m
    cat = hilly.catalogue
    # catalogue points well inside the photo, snapped to the centre of their texel
    xy = cat[["X_m", "Y_m"]].to_numpy()
    xy = (np.floor(xy / t) + 0.5) * t
    P = np.column_stack([xy, hilly.height(xy[:, 0], xy[:, 1])])
    ph0 = R.render(hilly, CAM, pose, 32, fiducials=False)
    pr = ph0.project(P)
    inner = np.all(np.abs(pr) < 70.0, axis=1)
    far = [0]
    for i in np.flatnonzero(inner):  # keep markers at least 20 mm apart
        if all(np.hypot(*(pr[i] - pr[j])) > 20.0 for j in far[1:]):
            far.append(i)
    chosen = np.array(far[1:9])
    assert len(chosen) >= 4
    marked = _marker_site(hilly, xy[chosen])
    n = 1024  # 0.18 mm pixels: about 2.5 m on the ground, close to the 2 m texels
    ph = R.render(marked, CAM, pose, n, vignetting=0.0, fiducials=False, level=0, objects=False)
    img = ph.image - 60.0 / 255.0
    H = pose.Z_m - hilly.mean_height_m
    for i in chosen:
        r, c = ph.mm_to_pixel(pr[i])
        r0, c0 = int(round(r)), int(round(c))
        win = img[r0 - 6:r0 + 7, c0 - 6:c0 + 7]
        assert win.max() > 0.5  # the marker is there
        rr, cc = np.mgrid[r0 - 6:r0 + 7, c0 - 6:c0 + 7]
        w = np.clip(win, 0, None)
        centroid = np.array([np.sum(w * rr), np.sum(w * cc)]) / np.sum(w)
        assert np.hypot(*(centroid - [r, c])) < 0.5  # within half a pixel (the requirement is 1 pixel)
        # and the test can tell: ignoring the relief would put it several pixels away
        flat_xy = g.ground_to_photo(CAM, pose, [P[i, 0], P[i, 1], hilly.mean_height_m])
        if abs(P[i, 2] - hilly.mean_height_m) / H * np.hypot(*pr[i]) > 6 * ph.pixel_mm:
            assert np.hypot(*(ph.mm_to_pixel(flat_xy) - centroid)) > 3.0


def test_catalogue_points_round_trip(hilly):
    pose = POSES[1]
    ph = R.render(hilly, CAM, pose, 64)
    pts = ph.points()
    assert {"x_mm", "y_mm", "row", "col", "visible"} <= set(pts.columns)
    vis = pts[pts["visible"]]
    assert len(vis) >= 10
    back = g.photo_to_dem(CAM, pose, vis[["x_mm", "y_mm"]].to_numpy(), hilly, tol_m=1e-6)
    assert np.allclose(back, vis[["X_m", "Y_m", "Z_m"]].to_numpy(), atol=1e-3)
    outside = pts[~np.all(np.abs(pts[["x_mm", "y_mm"]].to_numpy()) <= 90.0, axis=1)]
    assert len(outside) > 0 and not outside["visible"].any()
    assert np.allclose(ph.mm_to_pixel(vis[["x_mm", "y_mm"]].to_numpy()), vis[["row", "col"]].to_numpy())


def test_vertical_photo_of_flat_ground_has_scale_f_over_H(flat):
    pose = g.Pose.vertical(2000.0, 1500.0, 1200.0, ground_Z_m=120.0, kappa_deg=30.0)
    ph = R.render(flat, CAM, pose, 128, keep_ground=True, objects=False)
    G = ph.ground_m
    assert np.allclose(G[..., 2], 120.0)
    ref = g.photo_to_plane(CAM, pose, ph.pixel_centres_mm(), 120.0)
    assert np.allclose(G, ref, atol=1e-9)
    step = np.hypot(*(G[0, 1, :2] - G[0, 0, :2]))
    assert step == pytest.approx(ph.pixel_mm * 12000 / 1000)  # p·m, in metres
    assert ph.dem_evaluations == 1 and ph.dem_residual_m < 1e-9


def test_deterministic(hilly):
    a = R.render(hilly, CAM, POSES[2], 200)
    b = R.render(hilly, CAM, POSES[2], 200)
    assert np.array_equal(a.image, b.image)


def test_fiducials_and_vignetting(hilly):
    pose = POSES[0]
    n = 256
    plain = R.render(hilly, CAM, pose, n, vignetting=0.0, fiducials=False)
    vig = R.render(hilly, CAM, pose, n, vignetting=0.3, fiducials=False)
    fall = vig.light_falloff()
    assert np.allclose(vig.image, plain.image * fall, atol=1e-6)
    assert fall[n // 2, n // 2] == pytest.approx(1.0, abs=1e-3)
    assert fall[0, 0] == pytest.approx(0.7, abs=0.01)  # 1 − v at the corners
    fid = R.render(hilly, CAM, pose, n, vignetting=0.0, fiducials=True)
    changed = fid.image != plain.image
    # only near the middles of the four sides, and there black (wedge) or white (axis line)
    rows, cols = np.nonzero(changed)
    near_side = (np.minimum.reduce([rows, cols, n - 1 - rows, n - 1 - cols]) <= 0.04 * n + 1)
    near_mid = (np.abs(rows - n / 2) <= 0.02 * n + 1) | (np.abs(cols - n / 2) <= 0.02 * n + 1)
    assert changed.sum() > 40 and np.all(near_side & near_mid)
    assert set(np.unique(fid.image[changed])) <= {0.0, 1.0}
    for r, c in ((n // 2 - 3, 1), (n // 2 - 3, n - 2), (1, n // 2 - 3), (n - 2, n // 2 - 3)):
        assert fid.image[r, c] == 0.0


def test_off_site_pixels_get_the_background(hilly):
    pose = g.Pose(200.0, 1500.0, 1500.0)  # the west part of the photo looks beyond the site
    ph = R.render(hilly, CAM, pose, 128, background=0.25, fiducials=False, vignetting=0.0)
    assert not ph.valid.all() and ph.valid.any()
    assert np.all(ph.image[~ph.valid] == 0.25)
    assert not ph.valid[:, :10].any() and ph.valid[:, -10:].all()


def test_render_shots_of_a_strip(hilly):
    st = sim.strip_over_site(hilly, CAM, 6000, 60, 3, imperfections=sim.Imperfections(max_tilt_deg=2, seed=1))
    photos = R.render_strip(hilly, st, 48)
    assert [p.number for p in photos] == [1, 2, 3]
    assert all(p.pose == s.pose for p, s in zip(photos, st))
    # consecutive photos overlap: the ground under photo 2's principal point appears on photo 1
    P = g.photo_to_dem(CAM, st[1].pose, [0.0, 0.0], hilly)
    xy = photos[0].project(P)
    # about the base B = l·m·(1 − p_x/100) at the local scale f/(Z_S − Z), forward (+x: κ = 0, flying along +X)
    assert abs(xy[0]) < 90
    assert xy[0] == pytest.approx(st.B_m * CAM.f_mm / (st[0].pose.Z_m - P[2]), rel=0.1)


@pytest.mark.parametrize(
    "kwargs, name",
    [
        (dict(n_px=8), "n_px"),
        (dict(vignetting=1.0), "vignetting"),
        (dict(background=2.0), "background"),
        (dict(tol_m=0.0), "tol_m"),
        (dict(level=99), "level"),
        (dict(pose=g.Pose(2000.0, 1500.0, 200.0)), "Z_m"),
        (dict(pose=g.Pose(2000.0, 1500.0, 1500.0, alpha_deg=50.0)), "alpha_deg"),
        (dict(camera=None), "camera"),
    ],
)
def test_bad_input(hilly, kwargs, name):
    args = dict(camera=CAM, pose=POSES[0], n_px=32)
    args.update(kwargs)
    with pytest.raises(TypeError if name == "camera" else ValueError, match=name):  # a wrong object: TypeError
        R.render(hilly, args.pop("camera"), args.pop("pose"), **args)


def test_photo_view_updates_in_place(hilly):
    a = R.render(hilly, CAM, POSES[0], 64, number=7)
    b = R.render(hilly, CAM, POSES[1], 64)
    from aerophoto.demos.site_views import show_photo

    view = show_photo(a, labels=True)
    assert view.ax.get_title() == "photo 7"
    img_artist = view.image
    xa = view.other.get_xdata().copy()
    assert np.array_equal(img_artist.get_array(), a.image)
    view.update(b)
    assert view.image is img_artist and np.array_equal(img_artist.get_array(), b.image)
    vis = b.points()
    vis = vis[vis["visible"] & ~vis["control"]]
    assert np.allclose(view.other.get_xdata(), vis["x_mm"]) and not np.array_equal(xa, view.other.get_xdata())
    assert a.value_at([[0.0, 0.0]]).shape == (1,)


# --------------------------------------------------------------------------- objects with height
def test_every_pixel_shows_the_first_surface_on_its_ray(hilly):
    pose = POSES[1]
    ph = R.render(hilly, CAM, pose, 192, keep_ground=True)
    assert ph.objects and ph.surface.shape == (192, 192) and ph.object_id.dtype == np.int32
    G = ph.ground_m.reshape(-1, 3)
    sf = ph.surface.ravel()
    # on the ray through the pixel centre …
    assert np.allclose(g.ground_to_photo(CAM, pose, G), ph.pixel_centres_mm().reshape(-1, 2), atol=1e-6)
    # … never below the ground, on the DEM where the ground shows
    dem = hilly.height(G[:, 0], G[:, 1])
    assert np.all(G[:, 2] >= dem - 1e-3)
    assert np.allclose(G[sf == 0, 2], dem[sf == 0], atol=1e-3)
    assert set(np.unique(sf)) >= {0, 1, 3, 4}  # ground, roofs, crowns, canopy
    # roofs and crowns seen are the top of the surface there (the DSM); the ground too, except under a crown
    dsm = hilly.surface_height(G[:, 0], G[:, 1])
    assert np.allclose(G[sf == 1, 2], dsm[sf == 1], atol=1e-3)
    crown = sf == 3  # mostly their tops; an oblique ray may meet a crown's side below its top
    assert np.all(G[crown, 2] <= dsm[crown] + 1e-3) and np.mean(np.abs(G[crown, 2] - dsm[crown]) < 1e-3) > 0.8
    under = (sf == 0) & (dsm > G[:, 2] + 1e-3)
    objs = hilly.objects
    Gu = G[under]
    k, i = objs.candidates_at(Gu[:, 0], Gu[:, 1])
    # no house or structure standing on the ground covers such a point (or it is at a wall's foot); the water
    # tower's tank overhangs the ground, like a crown …
    poly = (k < objs.n_polyhedra) & (objs.bbox[k, 4] <= Gu[i, 2] + 0.1)
    from aerophoto.site.objects import hit_ellipsoids, hit_polyhedra

    def covered(dx, dy):
        S_up = np.column_stack([Gu[i[poly], 0] + dx, Gu[i[poly], 1] + dy, np.full(poly.sum(), 1e4)])
        return np.isfinite(hit_polyhedra(objs.planes, k[poly], S_up, [0.0, 0.0, -1.0])[0])

    inside = covered(0.0, 0.0)
    wall = np.zeros_like(inside)
    for dx, dy in ((0.05, 0), (-0.05, 0), (0, 0.05), (0, -0.05)):
        wall |= ~covered(dx, dy)
    assert np.all(~inside | wall)
    e = k[~poly] - objs.n_polyhedra  # … a crown does: the ground is seen obliquely under it …
    S_e = np.column_stack([Gu[i[~poly], :2], np.full((~poly).sum(), 1e4)])
    crowned = np.unique(i[~poly][np.isfinite(hit_ellipsoids(objs.ell_centre[e], objs.ell_radii[e], S_e,
                                                            [0.0, 0.0, -1.0])[0])])
    rest = np.setdiff1d(np.arange(under.sum()), crowned)
    edge = np.zeros(len(rest), bool)  # … or the ray meets a forest column's wall at its very foot (the march
    for dx, dy in ((0.3, 0), (-0.3, 0), (0, 0.3), (0, -0.3)):  # places wall hits to step/2⁵ ≈ 0.2 m)
        edge |= hilly.objects.canopy_at(Gu[rest, 0] + dx, Gu[rest, 1] + dy) == 0
    assert edge.all()
    # the canopy: mostly its tops (walls at the forest's edges are below the top of their column)
    can = sf == 4
    assert np.mean(np.abs(G[can, 2] - dsm[can]) < 0.1) > 0.5
    assert np.all(G[can, 2] > dem[can])
    # the same as trace() finds for those pixel centres
    sel = np.random.default_rng(0).choice(len(G), 400, replace=False)
    t = R.trace(hilly, CAM, pose, ph.pixel_centres_mm().reshape(-1, 2)[sel])
    assert np.allclose(t.XYZ_m, G[sel], atol=0.05) and np.array_equal(t.surface, sf[sel])


def test_a_tall_object_leans_by_r_h_over_H():
    """The mast on a vertical photo: its image runs from the foot's image to the top's, radially, r·h/H long."""
    site = S.get_site()
    t = site.objects.table()
    k = int(t.index[t["kind"] == "mast"][0])
    X, Y, z0, top = t.loc[k, ["X_m", "Y_m", "ground_Z_m", "top_Z_m"]]
    H = 1200.0
    pose = g.Pose(X - 600.0, Y - 350.0, z0 + H)  # the mast some 60 mm from the nadir point
    n = 1024
    ph = R.render(site, CAM, pose, n, fiducials=False)
    foot, tip = ph.project([[X, Y, z0], [X, Y, top]])
    r_foot, r_tip = np.hypot(*foot), np.hypot(*tip)
    # geometry: radial from n (= o on a vertical photo), δh = r·h/H with r at the top's image
    assert foot[0] * tip[1] - foot[1] * tip[0] == pytest.approx(0.0, abs=1e-9)
    assert r_tip - r_foot == pytest.approx(r_tip * (top - z0) / H, rel=1e-9)
    # the rendered mast: its pixels reach from the foot's image out to the top's, within a pixel
    rc = np.argwhere(ph.object_id == k)
    assert len(rc) > 10
    xy = ph.pixel_to_mm(rc)
    u = tip / r_tip
    along = xy @ u
    p = ph.pixel_mm
    assert abs(along.max() - r_tip) < 1.5 * p and abs(along.min() - r_foot) < 1.5 * p
    assert np.abs(xy @ np.array([-u[1], u[0]])).max() < 2.0 * p  # a thin radial line
    lean = along.max() - along.min()
    assert abs(lean - r_tip * (top - z0) / H) < 2.0 * p


def test_a_roof_corner_projects_where_geometry_says():
    """A house's roof: the pixels showing it are the pixel centres inside its projected outline (to a pixel)."""
    from matplotlib.path import Path

    site = S.get_site()
    pts = site.object_points
    roofs = pts[pts["kind"] == "roof corner"]
    objs = site.objects
    # a flat-roofed house (four roof corners at one height, no ridge)
    k = next(int(o) for o, grp in roofs.groupby("object") if len(grp) == 4
             and (pts[(pts["object"] == o) & (pts["kind"] == "ridge end")]).empty)
    corners = roofs[roofs["object"] == k][["X_m", "Y_m", "Z_m"]].to_numpy()
    c = corners.mean(axis=0)
    pose = g.Pose(c[0], c[1], site.mean_height_m + 400.0)  # the house under the camera: the roof hides nothing
    n = 2048
    ph = R.render(site, CAM, pose, n, fiducials=False)
    xy = ph.project(corners)
    order = np.argsort(np.arctan2(*(xy - xy.mean(axis=0)).T[::-1]))
    outline = Path(xy[order])
    cen = ph.pixel_centres_mm().reshape(-1, 2)
    r0, c0 = np.floor(ph.mm_to_pixel(xy).min(axis=0)).astype(int) - 3
    r1, c1 = np.ceil(ph.mm_to_pixel(xy).max(axis=0)).astype(int) + 3
    rr, cc = np.mgrid[r0:r1, c0:c1]
    inside = outline.contains_points(cen[(rr * n + cc).ravel()]).reshape(rr.shape)
    roof = (ph.object_id[r0:r1, c0:c1] == k) & (ph.surface[r0:r1, c0:c1] == 1)
    differ = inside != roof
    # where they differ, the pixel centre is within a pixel of the outline
    p = ph.pixel_mm
    d = np.array([min(_seg_dist(q, xy[order][j], xy[order][(j + 1) % 4]) for j in range(4))
                  for q in cen[(rr * n + cc).ravel()][differ.ravel()]])
    assert inside.sum() > 50 and np.all(d < p)


def _seg_dist(q, a, b):
    d = b - a
    u = np.clip(np.dot(q - a, d) / np.dot(d, d), 0, 1)
    return float(np.hypot(*(q - a - u * d)))


def test_objects_hide_what_stands_behind_and_under_them():
    site = S.get_site()
    cat = site.all_points
    trees = cat[cat["kind"] == "tree"].iloc[:5]
    for _, t in trees.iterrows():
        pose = g.Pose(t["X_m"], t["Y_m"], site.mean_height_m + 1200.0)  # the tree under the camera
        with_objects = R.render(site, CAM, pose, 32).points(cat).set_index("id")
        bare = R.render(site, CAM, pose, 32, objects=False).points(cat).set_index("id")
        assert bare.loc[t["id"], "visible"] and not with_objects.loc[t["id"], "visible"]  # the crown hides its foot
        top = cat[(cat["kind"] == "tree top") & (np.hypot(cat["X_m"] - t["X_m"], cat["Y_m"] - t["Y_m"]) < 1e-6)]
        assert with_objects.loc[int(top["id"].iloc[0]), "visible"]  # and its top is seen


def test_sun_and_shadows():
    site = S.get_site()
    t = site.objects.table()
    k = int(t.index[t["kind"] == "mast"][0])
    X, Y, z0, top = t.loc[k, ["X_m", "Y_m", "ground_Z_m", "top_Z_m"]]
    pose = g.Pose(X, Y, z0 + 800.0)
    sun = R.Sun(azimuth_deg=225.0, elevation_deg=35.0)
    ph = R.render(site, CAM, pose, 1024, sun=sun, keep_ground=True, fiducials=False, vignetting=0.0)
    assert ph.sun == sun and ph.shadow.dtype == bool and ph.shadow.any()
    plain = R.render(site, CAM, pose, 1024, keep_ground=True, fiducials=False, vignetting=0.0)
    assert plain.shadow is None and plain.sun is None
    # the shadow darkens what it falls on to the ambient share of the light
    gr = (ph.surface == 0) & ph.shadow
    assert np.allclose(ph.image[gr], plain.image[gr] * R.AMBIENT, atol=1e-5)
    # the mast's shadow: on the ground to the north-east, as long as h / tg(elevation)
    G = ph.ground_m
    near = ph.shadow & (ph.surface == 0) & (np.hypot(G[..., 0] - X, G[..., 1] - Y) < 120.0)
    d = G[near][:, :2] - [X, Y]
    assert np.all(d @ [1.0, 1.0] > -3.0)  # away from the sun (north-east)
    length = np.max(np.hypot(*d.T))
    assert length == pytest.approx(sun.shadow_length_m(top - z0), abs=2.0)
    assert sun.shadow_azimuth_deg == 45.0 and np.allclose(sun.direction, [-0.5792, -0.5792, 0.5736], atol=1e-4)
    for bad, name in ((dict(azimuth_deg=360.0), "azimuth_deg"), (dict(elevation_deg=0.0), "elevation_deg")):
        with pytest.raises(ValueError, match=name):
            R.Sun(**bad)
    with pytest.raises(ValueError, match="sun"):
        R.render(site, CAM, pose, 32, sun=(225, 35))


def test_a_site_without_objects_renders_bare_ground(hilly):
    from aerophoto.terrain import RescaledRelief

    rr = RescaledRelief(hilly, 100.0)
    ph = R.render(rr, CAM, POSES[0], 48)
    assert not ph.objects and ph.surface is None and ph.object_id is None
    bare = R.render(hilly, CAM, POSES[0], 48, objects=False)
    assert not bare.objects and bare.surface is None


# ----------------------------------------------------------------------------------------------- windows
def test_a_window_is_the_frames_own_pixels_when_its_grid_matches(hilly):
    """A window whose pixels fall on the frame's is the same photo there: same rays, ground, surfaces, shadows."""
    site = S.get_site(width_m=4000, height_m=3000, relief_m=120.0, base_height_m=100.0, seed=5)
    pose = POSES[1]
    sun = R.Sun(200.0, 40.0)
    full = R.render(site, CAM, pose, 256, sun=sun, keep_ground=True, fiducials=False, keep_normals=True)
    p = 180.0 / 256
    r0, c0, n = 40, 150, 48
    x0, y0 = -90.0 + c0 * p, 90.0 - r0 * p
    win = R.render(site, CAM, pose, n, sun=sun, keep_ground=True, fiducials=False, keep_normals=True,
                   window_mm=(x0 + n * p / 2, y0 - n * p / 2, n * p))
    part = (slice(r0, r0 + n), slice(c0, c0 + n))
    assert win.pixel_mm == pytest.approx(p)
    assert np.allclose(win.pixel_centres_mm(), full.pixel_centres_mm()[part])
    assert np.allclose(win.ground_m, full.ground_m[part], atol=2e-3)
    assert np.allclose(win.image, full.image[part], atol=1e-4)
    assert np.array_equal(win.surface, full.surface[part]) and np.array_equal(win.shadow, full.shadow[part])
    assert np.allclose(win.normal, full.normal[part], atol=1e-6)
    # its own pixel convention: extent, mm ↔ pixel
    left, right, bottom, top = win.extent_mm
    assert (right - left, top - bottom) == pytest.approx((n * p, n * p))
    assert np.allclose(win.pixel_to_mm([0, 0]), full.pixel_to_mm([r0, c0]))
    assert np.allclose(win.mm_to_pixel(win.pixel_to_mm([[3.0, 7.5]])), [[3.0, 7.5]])
    # a finer window: the same ground, four pixels to one
    fine = R.render(site, CAM, pose, 4 * n, sun=sun, keep_ground=True, fiducials=False,
                    window_mm=(x0 + n * p / 2, y0 - n * p / 2, n * p))
    assert fine.pixel_mm == pytest.approx(p / 4)
    assert np.allclose(g.ground_to_photo(CAM, pose, fine.ground_m.reshape(-1, 3)),
                       fine.pixel_centres_mm().reshape(-1, 2), atol=1e-5)
    block = fine.image.reshape(n, 4, n, 4).mean(axis=(1, 3))
    assert np.corrcoef(block.ravel(), full.image[part].ravel())[0, 1] > 0.95


def test_a_window_must_lie_in_the_frame(hilly):
    for window, name in (((0.0, 0.0, 0.1), "side"), ((85.0, 0.0, 20.0), "x"), ((0.0, -95.0, 10.0), "y"),
                         ((0.0, 0.0), "window_mm"), ((np.nan, 0.0, 10.0), "window_mm"), ("abc", "window_mm")):
        with pytest.raises(ValueError, match=name):
            R.render(hilly, CAM, POSES[0], 16, window_mm=window)
    # the fiducial marks show where a window holds them
    top = R.render(hilly, CAM, POSES[0], 64, window_mm=(0.0, 82.0, 16.0))
    assert (top.image == 0.0).mean() > 0.02
    assert "window 16 mm" in repr(top)
