"""Graded tasks of chapter 06 (guide §7): the student's own free strip, its reduction coefficients and corrections.

Both tasks work from the same lab strip, :func:`lab_strip`: four photos
36 … 39 of the student's variant over the virtual site, pricked, laid free in
a variant-dependent scale.  The student reads two tables — the control points
(ground X, Y to 0.1 m; free-strip x, y to 0.01 mm) and every point on the
free strip — and the expected answers are computed from those rounded
numbers, as a student computes them.  Chapter 12 (:mod:`aerophoto.tasks.ch12`)
uses the same strip.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import triangulation as tri
from .._validate import check_range
from .base import Answer, Hidden, Task

__all__ = ["LabStrip", "lab_strip", "RING", "RING_LABELS", "CORRECTION_POINTS", "RingCoefficients",
           "CorrectionsForReduction", "TASKS"]

#: the four bases of a table-8 ring around the strip, in the order of task 06.1
RING = (("36/1", "39/1"), ("39/1", "39/2"), ("39/2", "36/2"), ("36/2", "36/1"))
RING_LABELS = tuple(f"{a}–{b}" for a, b in RING)
#: the points whose corrections task 06.2 asks for (А and В are Cyrillic, as in the guide)
CORRECTION_POINTS = ("36/1", "А", "В", "38", "39/2")
#: the coefficient is printed to three decimals: half a unit of the last digit
TOL_COEFF = 0.0005


# =========================================================================== the lab strip
@dataclass(frozen=True)
class LabStrip:
    """A student's free strip for the graded tasks of chapters 06 and 12 (guide §7, §13).

    Four photos 36 … 39 of the student's variant (f, 1:m, p_x = 60 %) over the
    virtual site, pricked with 0.1 mm, laid in a variant-dependent arbitrary
    scale and reduced about working centre 37.  The tables give what the
    student reads: ground coordinates of the control points (to 0.1 m) and the
    positions of every point on the free strip (to 0.01 mm).  The expected
    answers are computed **from those rounded numbers**, as a student would.

    Attributes
    ----------
    variant : the student's Variant
    strip : aerophoto.simulate.Strip
        The simulated flight (true poses).
    templates : triangulation.Templates
    free : triangulation.FreeStrip
    reduction : triangulation.Reduction
        The unrounded computation (about centre 37).
    params : dict
        The inputs (f_mm, m, scale_ratio, pricking_mm, centre, max_tilt_deg, n_photos, seed, M).
    """

    variant: object
    strip: object
    templates: tri.Templates
    free: tri.FreeStrip
    reduction: tri.Reduction
    params: dict

    @property
    def M(self) -> float:
        """The plan scale denominator 1/M."""
        return self.reduction.M

    @property
    def centre(self) -> str:
        """The central working centre (37)."""
        return self.reduction.corrections.centre

    def control_table(self) -> pd.DataFrame:
        """Control points: ground X, Y (m, to 0.1 m) and free-strip x, y (mm, to 0.01 mm)."""
        red = self.reduction
        pts = red.strip.points
        idx = red.control
        return pd.DataFrame(
            {"X, m": np.round(pts.XYZ_m[idx, 0], 1), "Y, m": np.round(pts.XYZ_m[idx, 1], 1),
             "x strip, mm": np.round(red.strip.points_mm[idx, 0], 2),
             "y strip, mm": np.round(red.strip.points_mm[idx, 1], 2)},
            index=pd.Index([pts.names[i] for i in idx], name="control point"))

    def points_table(self) -> pd.DataFrame:
        """Every point on the free strip (mm, to 0.01 mm) with its kind."""
        fs = self.free
        return pd.DataFrame({"kind": list(fs.points.kinds), "x strip, mm": np.round(fs.points_mm[:, 0], 2),
                             "y strip, mm": np.round(fs.points_mm[:, 1], 2)},
                            index=pd.Index(list(fs.points.names), name="point"))

    def ring(self) -> list:
        """The four bases of a table-8 ring: 36/1 – 39/1 – 39/2 – 36/2 – 36/1."""
        c = list(self.control_table().index)
        a1, a2, b1, b2 = c[0], c[1], c[2], c[3]
        return [(a1, b1), (b1, b2), (b2, a2), (a2, a1)]

    def coefficients(self, pairs="all") -> tri.ReductionCoefficients:
        """Table 8/12 from the rounded tables: ``pairs="all"`` (six bases) or ``"ring"`` (four, like table 8)."""
        t = self.control_table()
        base = t[["X, m", "Y, m"]].to_numpy() * 1000.0 / self.M
        strip = t[["x strip, mm", "y strip, mm"]].to_numpy()
        return tri.reduction_coefficients(list(t.index), base, strip, pairs=self.ring() if pairs == "ring" else pairs)

    def corrections(self, names, k: float | None = None) -> np.ndarray:
        """v = r·(k − 1) (mm) for the named points, r from the rounded strip positions to the centre;
        k defaults to the mean over the six bases."""
        t = self.points_table()
        kk = self.coefficients().k_mean if k is None else k
        C = t.loc[self.centre, ["x strip, mm", "y strip, mm"]].to_numpy(dtype=float)
        P = t.loc[list(names), ["x strip, mm", "y strip, mm"]].to_numpy(dtype=float)
        return np.hypot(*(P - C).T) * (kk - 1.0)


def lab_strip(variant, *, pricking_mm: float = 0.1) -> LabStrip:
    """The student's free strip (see :class:`LabStrip`): seeded by the variant number i.

    The free strip's scale is q = 0.90 + 0.002·i of the plan scale (so the
    reduction coefficient, near 1/q, differs between variants).  The strip of
    a variant is built once per process (the grader asks for every variant's
    answers to recognise another variant's); its arrays are shared — read them,
    do not change them in place.

    Parameters
    ----------
    variant : Variant
        The student's variant (f, frame, 1:m, p_x, 1:M and the number i).
    pricking_mm : float
        RMS pricking error on the photos, mm, 0 ≤ m_p ≤ 2 (guide: 0.1).
    """
    mp = check_range("pricking_mm", pricking_mm, 0.0, 2.0, unit="mm")
    parts = _lab_parts(int(variant.i), float(variant.f_mm), float(variant.frame_mm), float(variant.m),
                       float(variant.px_percent), float(variant.M), mp)
    return LabStrip(variant, *parts)


@functools.lru_cache(maxsize=128)
def _lab_parts(i: int, f_mm: float, frame_mm: float, m: float, px_percent: float, M: float, pricking_mm: float):
    """(strip, templates, free strip, reduction, params) of the lab strip with these inputs."""
    from .. import geometry as g
    from .. import simulate
    from .. import site as site_mod

    s = site_mod.get_site()
    strip = simulate.strip_over_site(s, g.Camera(f_mm, frame_mm), m, px_percent, 4, first_number=36)
    cam = strip.camera
    pts = tri.design_points(cam, strip.poses, s, catalogue=s.catalogue, photo_numbers=[sh.number for sh in strip.shots])
    tm = tri.measure_templates(cam, strip.poses, pts, pricking_mm=pricking_mm, seed=i)
    q = 0.90 + 0.002 * i
    fs = tri.lay_free_strip(tm, scale_ratio=q, M=M)
    red = tri.reduce_strip(fs, M=M, centre=1)
    params = dict(f_mm=f_mm, m=m, scale_ratio=q, pricking_mm=pricking_mm, centre=2, max_tilt_deg=0.0, n_photos=4,
                  seed=i, M=M)
    return strip, tm, fs, red, params


def _numbers(x, n: int):
    """``x`` as a list of ``n`` finite floats, or None (not answered, wrong length, not numbers)."""
    if x is None or x is Ellipsis or isinstance(x, (str, bytes, dict)):
        return None
    try:
        out = [float(e) for e in (x.tolist() if hasattr(x, "tolist") else x)]
    except (TypeError, ValueError):
        return None
    return out if len(out) == n and all(math.isfinite(e) for e in out) else None


# =========================================================================== task 06.1
@dataclass(frozen=True)
class RingCoefficients(Task):
    """Task 06.1: the reduction coefficients k = l_осн/l_воск of the four bases around the strip and their mean (table 8)."""

    id = "task-06-1"
    title = "Reduction coefficients of your strip (table 8)"
    points = 4
    spec = (
        Answer("k_bases", "four reduction coefficients, in the order of the task", kind="values", tol_abs=TOL_COEFF,
               labels=RING_LABELS),
        Answer("k_mean", "their mean", tol_abs=TOL_COEFF),
    )

    def inputs(self, v) -> LabStrip:
        """The student's lab strip: ``control_table()`` and ``points_table()`` are what the student reads."""
        return lab_strip(v)

    def answers(self, v) -> dict:
        c = lab_strip(v).coefficients("ring")
        return {"k_bases": [float(k) for k in c.k], "k_mean": float(c.k_mean)}

    def slips(self, v) -> dict:
        k_mean = lab_strip(v).coefficients("ring").k_mean
        return {"k_mean": {"this is l_воск / l_осн — the coefficient is base over template": 1.0 / k_mean}}

    def hidden(self, v, got) -> list:
        # the student's own mean must be the mean of the student's own coefficients
        ks = _numbers(got.get("k_bases"), len(RING))
        return [Hidden("k_mean is the mean of k_bases", got.get("k_mean") if ks is not None else None,
                       float(np.mean(ks)) if ks is not None else None, tol_abs=1e-6)]


# =========================================================================== task 06.2
@dataclass(frozen=True)
class CorrectionsForReduction(Task):
    """Task 06.2: the corrections v = r·(k − 1) from working centre 37 for five points (table 9)."""

    id = "task-06-2"
    title = "Corrections for reduction (table 9)"
    points = 3
    spec = (
        Answer("v_mm", "corrections for 36/1, А, В, 38, 39/2, mm", unit="mm", kind="values", tol_abs=0.1,
               labels=CORRECTION_POINTS),
    )

    def inputs(self, v) -> LabStrip:
        """The student's lab strip (the same as task 06.1's)."""
        return lab_strip(v)

    def answers(self, v) -> dict:
        lab = lab_strip(v)
        v_mm = lab.corrections(CORRECTION_POINTS, k=lab.coefficients("ring").k_mean)
        return {"v_mm": [float(x) for x in v_mm]}

    def hidden(self, v, got) -> list:
        # the corrections are proportional to the distances: v/r is the same k − 1 for every point
        lab = lab_strip(v)
        r = lab.corrections(CORRECTION_POINTS, k=2.0)  # r·(2 − 1): the distances from 37, mm
        k1 = lab.coefficients("ring").k_mean - 1.0
        vs = _numbers(got.get("v_mm"), len(CORRECTION_POINTS))
        return [Hidden(f"v_mm / r at {name}", vs[j] / r[j] if vs is not None else None, k1, tol_abs=0.001)
                for j, name in enumerate(CORRECTION_POINTS)]


TASKS = (RingCoefficients(), CorrectionsForReduction())
