"""Chapter 02's lab (guide §3): the student's own strip of five photos and what a technician reads on it.

:func:`strip_measurements` flies a strip of five photos with the variant's
camera f, scale 1:m and forward overlap p_x (:func:`aerophoto.simulate.variant_strip`)
with imperfections drawn from the variant number, and reads on it what a
technician reads on the rough mosaic: lengths in mm (to 0.1 mm), the crab
angle in degrees (to 0.5°), the level bubble's offset in divisions of 30′.
:func:`measurement_table` is that table as the notebook shows it.  The graded
tasks built on it are :mod:`aerophoto.tasks.ch02`.
"""

from __future__ import annotations

import math

import numpy as np
import pandas as pd

from .. import geometry as g
from .. import quality as q
from .. import simulate as sim

__all__ = ["MEASUREMENT_KEYS", "lab_strip", "strip_measurements", "measurement_table"]

#: the measurements the student is given, in the order shown
MEASUREMENT_KEYS = ("a_mm", "b_mm", "b1_mm", "b2_mm", "L_mm", "l_mm", "crab_deg", "bubble_div", "f_mm", "H_m")


def lab_strip(variant):
    """The student's strip of five photos (:class:`aerophoto.simulate.Strip`, flat ground at the mean of Z_min and
    Z_max) with the imperfections drawn from the variant number i — what :func:`strip_measurements` measures."""
    i = int(variant.i)
    rng = np.random.default_rng([2014, i])
    # tilts shift the principal points by about f·tan α on the photo: long-focus cameras fly stabilised
    tilt = min(3.5, math.degrees(math.atan(6.0 / variant.f_mm)))
    imp = sim.Imperfections(max_tilt_deg=tilt, crab_deg=float(rng.uniform(-12.0, 12.0)), max_crab_jitter_deg=1.0,
                            max_height_percent=4.0, curvature_percent=float(rng.uniform(-3.0, 3.0)),
                            max_base_percent=8.0, seed=i)
    return sim.variant_strip(variant, 5, imperfections=imp)


def strip_measurements(variant) -> dict:
    """Measurements "taken on the rough mosaic" of the student's own strip (chapter 02's graded tasks).

    A strip of five photos is flown with the variant's camera, scale and
    overlap (:func:`aerophoto.simulate.variant_strip`, flat ground at the
    mean of Z_min and Z_max) with imperfections drawn from the seed i (the
    variant number): tilts up to 3.5°, a crab of up to ±12°, a flying-height
    scatter of ±4 %, a route bend of up to ±3 % and a ±8 % base jitter, so
    that some variants pass a criterion and others fail it.  The returned
    values are what a technician reads: lengths to 0.1 mm with a ruler,
    the crab angle to 0.5° with a protractor, the level bubble's offset to
    0.1 of a division.

    Returns
    -------
    dict with
        ``a_mm`` (overlap width of photos 1–2), ``b_mm`` (frame side, 180),
        ``b1_mm``, ``b2_mm`` (bases of photos 2–3 on photo 2 and on photo 3),
        ``L_mm``, ``l_mm`` (strip line and the deviation of the middle photo),
        ``crab_deg`` (measured on photo 2), ``bubble_div`` (offset of the
        level's bubble on photo 3, divisions of 30′), ``f_mm``, ``H_m``,
        ``numbers`` (photo numbers 1–5).
    """
    st = lab_strip(variant)
    cam = st.camera
    dem = g.FlatTerrain(st.ground_Z_m)
    s = st.shots
    a = q.measure_overlap(cam, s[0].pose, s[1].pose, dem)
    b1, b2 = q.measure_base(cam, s[1].pose, s[2].pose, dem)
    stt = q.measure_straightness(cam, [x.pose for x in s], dem, st.m)
    crab = q.measure_crab_deg(cam, s[1].pose, s[2].pose, dem)
    r1 = lambda x: float(np.round(x, 1))  # noqa: E731  (a ruler reads 0.1 mm)
    return {
        "a_mm": r1(a), "b_mm": cam.frame_mm, "b1_mm": r1(b1), "b2_mm": r1(b2),
        "L_mm": r1(stt["L_mm"]), "l_mm": r1(stt["l_mm"][2]),
        "crab_deg": float(np.round(crab * 2.0) / 2.0),
        "bubble_div": float(np.round(abs(s[2].pose.alpha_deg) / (q.LEVEL_DIVISION_ARCMIN / 60.0), 1)),
        "f_mm": cam.f_mm, "H_m": st.H_m, "numbers": tuple(x.number for x in s),
    }


def measurement_table(variant) -> pd.Series:
    """The measurements the student works from, as shown in the notebook: a Series named "your measurements"."""
    d = strip_measurements(variant)
    return pd.Series({k: d[k] for k in MEASUREMENT_KEYS}, name="your measurements")
