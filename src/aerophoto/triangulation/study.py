"""Monte Carlo: how the errors of a reduced free strip grow with its length (guide §13; chapter 12).

Vertical photos over flat ground, so every error comes from the pricking;
control points in the first and last overlaps.  Its table is what chapter
12 sets beside Zhukov's formula (13.1) read three ways.
"""

from __future__ import annotations

import numpy as np
import pandas as pd

from .. import _validate as V
from .. import geometry as g
from .._validate import check_int_range, check_percent
from .reduction import reduce_strip
from .strip import PRICKING_MM, design_points, lay_free_strip, measure_templates

__all__ = ["accumulation_study"]


@V.checked(n_bases=V.sequence(V.whole(2, 40), min_len=1), seeds=V.sequence(V.whole(0, 2**32 - 1), min_len=1),
           overlap_percent=V.number(50.0, 95.0, lo_open=True))
def accumulation_study(n_bases=(2, 3, 4, 5, 6, 8), seeds=range(20), *, pricking_mm: float = PRICKING_MM,
                       f_mm: float = 100.0, m: float = 12000.0, M: float = 10000.0, overlap_percent: float = 60.0):
    """Monte Carlo: errors of reduced free strips against the number of bases between the control points.

    Vertical photos over flat ground along +X (so every error comes from the
    pricking), control points in the first and last overlaps (guide §13).

    Returns
    -------
    pandas.DataFrame, one row per n: the RMS error of the orienting points
    and working centres on the plan after reduction (mm), the RMS control
    residual (mm), the RMS largest error-triangle side (template mm), the
    strip's k range — over the seeds.
    """
    cam = g.Camera(f_mm)
    H = g.flying_height_m(f_mm, m)
    overlap = check_percent("overlap_percent", overlap_percent)
    B = (1.0 - overlap / 100.0) * cam.frame_mm / 1000.0 * m
    rows = []
    for n in n_bases:
        n = check_int_range("n_bases", n, 2, 60)
        poses = [g.Pose(i * B, 0.0, H) for i in range(n + 1)]
        pts = design_points(cam, poses, None)
        inner = np.flatnonzero(pts.mask("orienting") | pts.mask("centre"))
        e, c, tri, rng_k = [], [], [], []
        for s in seeds:
            tm = measure_templates(cam, poses, pts, pricking_mm=pricking_mm, seed=int(s))
            fs = lay_free_strip(tm, M=M)
            red = reduce_strip(fs, M=M)
            e.append(np.sqrt(np.mean(red.errors_mm[inner] ** 2)))
            c.append(np.sqrt(np.mean(red.control_residuals_mm**2)))
            tri.append(fs.max_triangle_side_mm)
            rng_k.append(red.coefficients.k_range)
        rows.append((n, float(np.sqrt(np.mean(np.square(e)))), float(np.sqrt(np.mean(np.square(c)))),
                     float(np.sqrt(np.mean(np.square(tri)))), float(np.mean(rng_k))))
    return pd.DataFrame(rows, columns=["n bases", "RMS error of points, mm", "RMS control residual, mm",
                                       "RMS largest triangle side, mm", "mean k range"]).set_index("n bases")
