"""The students' lab sheets of chapters 03–04 (aerophoto.labs.displacement): the guide's layout, the truth.

Every variant 00–99 gets a sheet that keeps the guide's rules (zones, bases of 20–30 mm, points on open ground,
inside the frame), whose reference corrections stay clear of the 0.2 mm threshold, and whose truth is the camera
model: the rendered photo shows each pricked point's ground where its mark is, and the plan shows it at 1:M.
"""

import math

import numpy as np
import pytest

from aerophoto import geometry as g
from aerophoto.site import COVER_CODES, get_site
from aerophoto.labs import displacement as lab
from aerophoto.variants import variant_for_index

VARIANTS = range(100)
OPEN = [COVER_CODES[k] for k in lab.OPEN_GROUND]


def _angle(a, b) -> float:
    c = float(np.dot(a, b) / (np.linalg.norm(a) * np.linalg.norm(b)))
    return math.degrees(math.acos(max(-1.0, min(1.0, c))))


def _common(sheet, v):
    assert sheet.camera.f_mm == v.f_mm
    assert (sheet.pose.alpha_deg, sheet.pose.lambda_deg, sheet.pose.kappa_deg) == (v.alpha_deg, v.lambda_deg, 0.0)
    assert sheet.H_m == pytest.approx(v.f_mm / 1000 * v.m) and sheet.m == pytest.approx(v.m)
    xy = sheet.photo_xy_mm
    np.testing.assert_allclose(xy, g.ground_to_photo(sheet.camera, sheet.pose, sheet.XYZ_m))  # the truth
    assert np.all(np.abs(xy) <= 84.0)
    site = get_site()
    np.testing.assert_allclose(sheet.XYZ_m[:, 2], site.height(sheet.XYZ_m[:, 0], sheet.XYZ_m[:, 1]))  # on the DEM
    assert np.all(np.isin(site.cover_at(sheet.XYZ_m[:, 0], sheet.XYZ_m[:, 1]), OPEN))
    # nothing stands on a point, and nothing standing nearby hides it on the photo
    np.testing.assert_allclose(site.surface_height(sheet.XYZ_m[:, 0], sheet.XYZ_m[:, 1]), sheet.XYZ_m[:, 2],
                               atol=0.05)
    from aerophoto.render import trace

    seen = trace(site, sheet.camera, sheet.pose, xy).XYZ_m
    assert np.max(np.linalg.norm(seen - sheet.XYZ_m, axis=1)) <= 0.5
    lengths = sheet.l_photo_mm
    assert np.all((lengths > 19.0) & (lengths < 31.0))
    np.testing.assert_allclose(sheet.plan_xy_mm, (sheet.XYZ_m[:, :2] - sheet.plan_origin_m) / 10.0)
    assert np.all(sheet.plan_xy_mm > 20.0) and np.all(sheet.plan_xy_mm < sheet.plan_size_mm - 20.0)
    assert np.all(sheet.plan_origin_m % 100.0 == 0.0)
    idx = {n: k for k, n in enumerate(sheet.names)}
    for z in dict.fromkeys(a for a, _ in sheet.bases):  # the two bases of a zone leave its main point ~90° apart
        ends = [b for a, b in sheet.bases if a == z]
        angle = _angle(xy[idx[ends[0]]] - xy[idx[z]], xy[idx[ends[1]]] - xy[idx[z]])
        assert 65.0 <= angle <= 115.0, (sheet, z, angle)


@pytest.mark.parametrize("i", VARIANTS)
def test_relief_sheet_follows_the_guide(i):
    v = variant_for_index(i)
    sheet = lab.relief_sheet(i)
    _common(sheet, v)
    assert sheet.names == ("I", "1", "2", "II", "3", "4")
    w = sheet.work()
    zI, zII = w.table2.zone_heights_m
    assert zII - zI >= 10.0  # zone I on low ground, zone II on high ground (guide §4 step 2)
    n = sheet.n_mm
    rn = np.hypot(*(sheet.photo_xy_mm - n).T)
    assert 36.0 <= rn[0] <= 74.0 and 36.0 <= rn[3] <= 74.0  # the zones 40–70 mm from the nadir point
    assert np.all(np.abs(np.abs(w.table3.delta_mm) - 0.2) >= lab.THRESHOLD_MARGIN_MM)
    # both zones lie near the isoline: their distances along the principal vertical from c differ little
    u = g.principal_vertical(sheet.pose)
    along = (sheet.photo_xy_mm - sheet.c_mm) @ u
    assert abs(along[0]) < 10.0 and abs(along[3]) < 10.0


@pytest.mark.parametrize("i", VARIANTS)
def test_tilt_sheet_follows_the_guide(i):
    v = variant_for_index(i)
    sheet = lab.tilt_sheet(i)
    _common(sheet, v)
    assert sheet.names == ("I", "1", "2", "II", "3", "4", "III", "5", "6")
    u = g.principal_vertical(sheet.pose)
    along = (sheet.photo_xy_mm - sheet.c_mm) @ u
    assert along[0] > 35.0 and abs(along[3]) < 12.0 and along[6] < -35.0  # far side, near c, near side
    w = sheet.work()
    assert np.all(w.table6.r_c_mm >= 12.0)
    off = np.minimum(w.table6.phi_deg, 360.0 - w.table6.phi_deg)
    assert np.all(off >= 7.0)  # no φ near 0°/360°, where a reading could wrap round
    assert np.all(np.abs(np.abs(w.table6.delta_approx_mm) - 0.2) >= lab.THRESHOLD_MARGIN_MM)
    # flat ground: relief moves no point by more than a few hundredths of a millimetre
    P = sheet.XYZ_m.copy()
    P[:, 2] = sheet.Z_mean_m
    relief = np.hypot(*(sheet.photo_xy_mm - g.ground_to_photo(sheet.camera, sheet.pose, P)).T)
    assert np.max(relief) < 0.05


def test_sheets_are_deterministic_and_cached():
    a = lab.relief_sheet(7)
    assert lab.relief_sheet(7) is a
    b = lab._build("relief", 7)
    np.testing.assert_array_equal(a.XYZ_m, b.XYZ_m)
    assert a.pose == b.pose
    assert lab.sheet_for("tilt", variant_for_index(7)) is lab.tilt_sheet(7)
    with pytest.raises(ValueError, match="kind"):
        lab.sheet_for("scale", variant_for_index(7))
    with pytest.raises(ValueError, match="i"):
        lab.relief_sheet(100)


def test_sheets_differ_between_students():
    places = {tuple(np.round(lab.relief_sheet(i).XYZ_m[0, :2])) for i in range(0, 100, 5)}
    assert len(places) >= 15


def test_the_corrections_count_falls_with_the_flying_height():
    counts = [lab.relief_sheet(i).work().table3.n_applied for i in range(100)]
    assert counts[0] == 6 and counts[99] == 0
    assert all(c == 0 for c in counts[20:])  # above H ≈ 4 km the site's 30 m of relief needs no correction
    tilt = [lab.tilt_sheet(i).work().table6.n_applied for i in range(100)]
    assert tilt[0] >= 6 and sum(tilt[:20]) > sum(tilt[80:])


@pytest.mark.parametrize("kind, i", [("relief", 0), ("tilt", 99)])
def test_the_rendered_photo_shows_each_point_under_its_mark(kind, i):
    """Truth by geometry and picture by the renderer agree: the ground seen at a mark's pixel is the point."""
    from aerophoto import render

    sheet = lab.sheet_for(kind, variant_for_index(i))
    photo = render.render(get_site(), sheet.camera, sheet.pose, n_px=512, keep_ground=True)
    rc = np.round(photo.mm_to_pixel(sheet.photo_xy_mm)).astype(int)
    ground = photo.ground_m[rc[:, 0], rc[:, 1]]
    pixel_ground_m = photo.pixel_mm * sheet.m / 1000.0
    assert np.max(np.hypot(*(ground[:, :2] - sheet.XYZ_m[:, :2]).T)) < pixel_ground_m
    assert sheet.photo().image.shape == (lab.PHOTO_PX, lab.PHOTO_PX)


def test_the_plan_is_the_site_seen_from_above_at_1_to_M():
    sheet = lab.relief_sheet(3)
    plan = sheet.plan()
    site = get_site()
    W, H = sheet.plan_size_mm
    assert plan.extent_mm == (0.0, W, 0.0, H)
    rows, cols = plan.image.shape
    px = W / cols
    assert px == pytest.approx(0.25, rel=0.01)
    for (x, y), (X, Y, _) in zip(sheet.plan_xy_mm, sheet.XYZ_m):
        r, c = int((H - y) / px), int(x / px)
        Xc = sheet.plan_origin_m[0] + (c + 0.5) * px * 10
        Yc = sheet.plan_origin_m[1] + (H - (r + 0.5) * px) * 10
        assert plan.image[r, c] == pytest.approx(float(site.sample(Xc, Yc, site.level_for(2.5))), abs=1e-6)
        assert math.hypot(Xc - X, Yc - Y) < 2.0
    k = np.argmin(np.abs(plan.contour_x_mm - sheet.plan_xy_mm[0, 0]))
    assert plan.contour_Z_m.shape == (len(plan.contour_y_mm), len(plan.contour_x_mm))
    assert np.all((plan.contour_Z_m[:, k] >= site.z_min_m) & (plan.contour_Z_m[:, k] <= site.z_max_m))


def test_the_reference_compares_the_formulas_with_the_geometry():
    ref = lab.relief_sheet(0).reference()
    assert list(ref) == ["Table 2", "Table 3", "Table 4", "against the geometry"]
    check = ref["against the geometry"]
    assert (check["formula − exact, mm"].abs() < 0.01).all()  # δh = r·h/H is nearly exact at 3°
    assert (check["corrected point off by, mm"] < 0.01).all()
    ref = lab.tilt_sheet(0).reference()
    assert list(ref) == ["Table 5", "Table 6", "Table 7", "against the geometry"]
    check = ref["against the geometry"]
    # the guide's δα is a few per cent short of the exact value; the corrections come within 0.1 mm
    assert (check["formula − exact, mm"].abs() <= 0.05 * check["δα exact, mm"].abs() + 0.002).all()
    assert (check["corrected point off by, mm"] < 0.1).all()
    assert "1/" in ref["Table 7"]["Δm_i/m_cp"].str.cat()


def test_marks_and_errors():
    sheet = lab.tilt_sheet(4)
    assert list(sheet.marks("plan")) == list(sheet.names)
    with pytest.raises(ValueError, match="where"):
        sheet.marks("map")
    assert sheet.bases_frame().index.tolist() == ["I-1", "I-2", "II-3", "II-4", "III-5", "III-6"]
