"""The student's own strip over the virtual site, and the readings a student makes on it (chapters 05, 06, 12).

Every student flies **their own strip**: four photos 36 … 39 with their
variant's camera f, scale 1:m and forward overlap p_x (guide §1), over the
virtual site (:func:`aerophoto.site.get_site`).  Chapter 05 glues it into a
fotoschema (:mod:`aerophoto.labs.ch05`), chapters 06 and 12 triangulate it
(:mod:`aerophoto.labs.ch06`; graded in :mod:`aerophoto.tasks.ch06`, :mod:`aerophoto.tasks.ch12`).

* **Where.**  The strip is flown along +X (east).  Where it lies on the site
  depends on the variant number i (:func:`strip_position`): the first photo's
  ground point moves along and across the free room of the site by the
  fractional parts of i·0.618… and i·0.755…, so no two neighbouring variants —
  and no student and the guide's worked example (variant 00 through the site's
  centre) — share a strip.
* **Tilts.**  The photos are near-vertical with tilts up to
  :data:`MAX_TILT_DEG` in random directions (seed 1000 + i).  A tilt moves a
  photo's footprint by about H·tg α, which for the long lenses of high variants
  (f up to 1090 mm, H up to 23.9 km) would carry the photos off the
  10 × 5 km site; the tilt is therefore capped so that the nadir point lies
  within :data:`MAX_TILT_OFFSET_MM` of the principal point (f·tg α ≤ 6 mm:
  2° for f ≤ 172 mm, 0.32° for f = 1090 mm).  This mapping is stated in the
  chapters' text.
* **Readings.**  What a student measures with a ruler, a needle and a
  magnifier is the truth (from the camera model) plus a small, bounded,
  seeded error, read to 0.1 mm (:func:`read_mm`).

This is part of the course's content (layer 4): it flies with
:mod:`aerophoto.simulate` over :mod:`aerophoto.site` and never renders.
"""

from __future__ import annotations

import functools
import math

import numpy as np

from .. import geometry as g

__all__ = ["N_PHOTOS", "FIRST_NUMBER", "MAX_TILT_DEG", "MAX_TILT_OFFSET_MM", "SITE_MARGIN_M", "own_tilt_deg",
           "tilt_growth_m", "tilt_that_fits", "strip_position", "own_strip", "own_strip_of", "reading_rng", "read_mm"]

#: photos in the student's strip (guide §3 hands out four contact prints; §13 numbers them 36 … 39)
N_PHOTOS = 4
#: the number of the first photo (guide §13: photos 36, 37, 38, 39)
FIRST_NUMBER = 36
#: largest tilt of the student's photos, degrees (near-vertical photos; guide §3 allows up to 3°) …
MAX_TILT_DEG = 2.0
#: … and at most this offset f·tg α of the nadir point from the principal point, mm
MAX_TILT_OFFSET_MM = 6.0
#: the footprints keep this far inside the site's edges, m
SITE_MARGIN_M = 30.0
#: fractional steps of the strip's position between variants (golden and plastic ratios: well spread)
_STEP_ALONG = 0.6180339887
_STEP_ACROSS = 0.7548776662


def own_tilt_deg(f_mm: float) -> float:
    """The largest tilt of a student's photos for focal length ``f_mm``: min(2°, atan(6 mm / f)), degrees."""
    return min(MAX_TILT_DEG, math.degrees(math.atan(MAX_TILT_OFFSET_MM / float(f_mm))))


def tilt_growth_m(camera: g.Camera, m: float, tilt_deg: float) -> float:
    """How far a photo's footprint can reach beyond the vertical photo's footprint when tilted by ``tilt_deg``, m.

    The frame's corner is seen at β = atan(l/√2 / f) from the axis; tilted by α
    towards it, it reaches H·tg(β + α) instead of H·tg β (H = f·m).  An upper
    bound for any tilt direction.
    """
    H = g.flying_height_m(camera.f_mm, m)
    beta = math.atan(camera.half_mm * math.sqrt(2.0) / camera.f_mm)
    a = math.radians(float(tilt_deg))
    if beta + a >= math.pi / 2:
        return math.inf
    return H * (math.tan(beta + a) - math.tan(beta))


def _room_m(site, camera: g.Camera, m: float, px_percent: float, n_photos: int) -> tuple:
    """Free room (along X, across Y) left by a vertical strip's footprints on the site, m (may be negative)."""
    side = camera.frame_mm / 1000.0 * m
    B = side * (1.0 - px_percent / 100.0)
    x0, x1, y0, y1 = site.extent_m
    return (x1 - x0) - ((n_photos - 1) * B + side), (y1 - y0) - side


def tilt_that_fits(site, camera: g.Camera, m: float, px_percent: float, n_photos: int, wanted_deg: float) -> float:
    """The largest tilt ≤ ``wanted_deg`` with which a strip centred on the site keeps its footprints on it, degrees.

    Uses the bound of :func:`tilt_growth_m` against half the free room on each
    side (less :data:`SITE_MARGIN_M`); 0 when even vertical photos leave no room.
    A demo that asks for more shows the reduced value and says why.
    """
    along, across = _room_m(site, camera, m, px_percent, n_photos)
    room = min(along, across) / 2.0 - SITE_MARGIN_M
    if room <= 0:
        return 0.0
    H = g.flying_height_m(camera.f_mm, m)
    beta = math.atan(camera.half_mm * math.sqrt(2.0) / camera.f_mm)
    fit = math.degrees(math.atan(room / H + math.tan(beta)) - beta)
    return float(min(float(wanted_deg), fit))


def strip_position(variant, site) -> tuple:
    """Ground X, Y (m) of the first photo's planned centre for ``variant`` (see the module notes).

    Raises ValueError if the variant's strip cannot fit the site at all.
    """
    cam = variant.camera
    side = cam.frame_mm / 1000.0 * variant.m
    B = side * (1.0 - variant.px_percent / 100.0)
    grow = tilt_growth_m(cam, variant.m, own_tilt_deg(cam.f_mm)) + SITE_MARGIN_M
    along, across = _room_m(site, cam, variant.m, variant.px_percent, N_PHOTOS)
    along -= 2.0 * grow
    across -= 2.0 * grow
    if along < 0 or across < 0:
        raise ValueError(f"variant {variant.i:02d}: a strip of {N_PHOTOS} photos at 1:{variant.m:.0f} does not fit "
                         f"the site {site.extent_m}; the valid range is a site at least "
                         f"{(N_PHOTOS - 1) * B + side + 2 * grow:.0f} × {side + 2 * grow:.0f} m")
    u = (_STEP_ALONG * int(variant.i) + 0.25) % 1.0
    w = (_STEP_ACROSS * int(variant.i) + 0.60) % 1.0
    x0, _x1, y0, _y1 = site.extent_m
    return (x0 + grow + side / 2.0 + u * along, y0 + grow + side / 2.0 + w * across)


@functools.lru_cache(maxsize=128)
def own_strip_of(i: int, f_mm: float, frame_mm: float, m: float, px_percent: float):
    """The own strip of variant ``i`` flown with these f (mm), frame side (mm), 1:m and p_x (%): ``(strip, site)``.

    :func:`own_strip` for a variant's own numbers; a hand-made variant (another f, m or p_x) flies from the
    same place rule.  Cached per process (128 strips); the arrays are shared — read them, do not change them.
    """
    from .. import simulate
    from .. import site as site_mod
    from ..variants import variant_for_index

    s = site_mod.get_site()
    v = variant_for_index(i)
    if (v.f_mm, v.frame_mm, v.m, v.px_percent) != (f_mm, frame_mm, m, px_percent):  # a hand-made variant
        from dataclasses import replace

        v = replace(v, f_mm=f_mm, frame_mm=frame_mm, m=m, px_percent=px_percent)
    start = strip_position(v, s)
    imp = simulate.Imperfections(max_tilt_deg=own_tilt_deg(f_mm), seed=1000 + i)
    strip = simulate.fly_strip(v.camera, m, px_percent, N_PHOTOS, start_m=start, azimuth_deg=0.0,
                               ground_Z_m=s.mean_height_m, imperfections=imp, first_number=FIRST_NUMBER)
    x0, x1, y0, y1 = s.extent_m
    fp = strip.footprints(s.mean_height_m)
    if fp[..., 0].min() < x0 or fp[..., 0].max() > x1 or fp[..., 1].min() < y0 or fp[..., 1].max() > y1:
        raise ValueError(f"variant {i:02d}: the strip's footprints leave the site (a bug in strip_position)")
    return strip, s


def own_strip(variant):
    """The student's own strip: ``(strip, site)`` — four photos 36 … 39 over the virtual site (module notes).

    Built once per variant and process; the strip's arrays are shared — read them, do not change them.
    """
    return own_strip_of(int(variant.i), float(variant.f_mm), float(variant.frame_mm), float(variant.m),
                      float(variant.px_percent))


def reading_rng(variant, salt: int) -> np.random.Generator:
    """The random stream of one kind of reading for a variant (``salt`` tells the kinds apart)."""
    return np.random.default_rng([int(variant.i), int(salt)])


def read_mm(true_mm, rng: np.random.Generator, *, sigma_mm: float, max_mm: float, step_mm: float = 0.1) -> np.ndarray:
    """Readings of true positions or distances: an error N(0, σ) bounded by ±max, then rounded to ``step_mm``.

    So a reading differs from the truth by at most ``max_mm + step_mm/2``.
    Returns floats without −0.0.
    """
    t = np.asarray(true_mm, dtype=float)
    e = np.clip(rng.normal(0.0, sigma_mm, size=t.shape), -max_mm, max_mm)
    k = -math.log10(step_mm)
    if abs(k - round(k)) < 1e-9:  # a power of ten: round to that many decimals (no 4.300000000000001)
        return np.round(t + e, int(round(k))) + 0.0
    return np.round((t + e) / step_mm) * step_mm + 0.0
