"""Chapter 06's lab (guide §7, §13): the student's own strip, pricked, laid free, reduced and read.

Every student triangulates **their own strip** (:func:`aerophoto.labs.own.own_strip`:
photos 36 … 39 with their variant's f, 1:m and p_x, at a place of their own
on the virtual site — the same four photos they glue into a fotoschema in
chapter 05).  The work of guide §7 / §13 is done on it (:func:`lab_strip`):

1. the working centres, orienting, tie and control points are pricked on every
   photo with the guide's 0.1 mm (seed: the variant number) and the direction
   templates drawn (:func:`aerophoto.triangulation.measure_templates`);
2. the templates are laid into a free strip at a scale of the variant's own,
   q = 0.92 … 0.969 of the plan's for i < 50 and 1.03 … 1.079 for i ≥ 50 (so
   half the class lays the strip too small, half too large: corrections away
   from and towards the centre), :func:`free_scale_ratio`;
3. the common tracing is "measured": every point of it read to 0.1 mm with a
   bounded reading error (:func:`aerophoto.labs.own.read_mm`), placed on the
   table by :func:`tracing_frame`.

What the student reads (:class:`StripReadings`, all in the Russian geodetic
convention of the guide's table 8 — x north/up, y east/right, directions
clockwise from +x, :mod:`aerophoto.triangulation.geodetic`): the rays at the
tie points, the four control points, every point of the common tracing.
Chapters 06 and 12 grade work on it (:mod:`aerophoto.tasks.ch06`,
:mod:`aerophoto.tasks.ch12`); the reduction demo draws it
(:mod:`aerophoto.demos.reduction`).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import triangulation as tri
from .._validate import check_range
from . import own as _own

__all__ = ["TIE_POINTS", "POINT_ORDER", "CENTRE", "SHEET_SIGMA_MM", "SHEET_MAX_MM", "free_scale_ratio", "LabStrip",
           "lab_strip", "StripReadings", "tracing_frame", "shared_readings", "strip_readings"]

#: the tie points of photos 37 and 38 (a, b in the triple overlap 36-37-38; c, d in 37-38-39)
TIE_POINTS = ("a", "b", "c", "d")
#: the points of the common tracing along the strip (guide table 13's order; tie points are not transferred)
POINT_ORDER = ("36", "36/1", "36/2", "А", "Б", "37", "В", "Г", "38", "Д", "Е", "39/1", "39/2", "39")
#: the centre of the strip for table 9 (guide §13: "one of the middle centres, 37 or 38")
CENTRE = "37"
#: reading a point on the common tracing: σ and bound of the error, mm (then read to 0.1 mm)
SHEET_SIGMA_MM = 0.05
SHEET_MAX_MM = 0.10
_SALT_SHEET, _SALT_FRAME = 6061, 6062


def free_scale_ratio(i: int) -> float:
    """The free strip's scale as a fraction q of the plan's for variant i (k ≈ 1/q).

    0.92 + 0.001·i for i < 50 (k − 1 from +0.087 to +0.032: corrections away
    from the centre), 1.03 + 0.001·(i − 50) for i ≥ 50 (k − 1 from −0.029 to
    −0.073: towards it) — never near 1, where the corrections would vanish.
    """
    i = int(i)
    return 0.92 + 0.001 * i if i < 50 else 1.03 + 0.001 * (i - 50)


# =========================================================================== the lab strip
@dataclass(frozen=True)
class LabStrip:
    """A student's strip, laid free and reduced (the instructor's side: holds the truth and the exact work).

    Attributes
    ----------
    variant : the student's Variant
    strip : aerophoto.simulate.Strip — the student's own photos 36 … 39 (true poses)
    templates : triangulation.Templates — pricked with 0.1 mm, seeded by the variant
    free : triangulation.FreeStrip — laid at the scale :func:`free_scale_ratio`
    reduction : triangulation.Reduction — about centre 37, with all six bases (exact, unrounded)
    params : dict — the inputs (f_mm, m, scale_ratio, pricking_mm, seed, M)
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

    def readings(self) -> "StripReadings":
        """What the student reads on this strip (:func:`strip_readings`)."""
        return strip_readings(self.variant)


def lab_strip(variant, *, pricking_mm: float = tri.PRICKING_MM) -> LabStrip:
    """The student's strip (see :class:`LabStrip`), built once per variant and process (arrays shared: read only).

    Parameters
    ----------
    variant : Variant
    pricking_mm : float
        RMS pricking error on the photos, mm, 0 ≤ m_p ≤ 2 (guide §13 step 2: 0.1).
    """
    mp = check_range("pricking_mm", pricking_mm, 0.0, 2.0, unit="mm")
    parts = _lab_parts(int(variant.i), float(variant.f_mm), float(variant.frame_mm), float(variant.m),
                       float(variant.px_percent), float(variant.M), mp)
    return LabStrip(variant, *parts)


@functools.lru_cache(maxsize=128)
def _lab_parts(i: int, f_mm: float, frame_mm: float, m: float, px_percent: float, M: float, pricking_mm: float):
    """(strip, templates, free strip, reduction, params) of the lab strip with these inputs."""
    strip, s = _own.own_strip_of(i, f_mm, frame_mm, m, px_percent)
    cam = strip.camera
    pts = tri.design_points(cam, strip.poses, s, catalogue=s.catalogue, photo_numbers=[sh.number for sh in strip.shots])
    tm = tri.measure_templates(cam, strip.poses, pts, pricking_mm=pricking_mm, seed=i)
    q = free_scale_ratio(i)
    fs = tri.lay_free_strip(tm, scale_ratio=q, M=M)
    red = tri.reduce_strip(fs, M=M, centre=CENTRE)
    params = dict(f_mm=f_mm, m=m, scale_ratio=q, pricking_mm=pricking_mm, seed=i, M=M)
    return strip, tm, fs, red, params


# =========================================================================== what the student reads
@dataclass(frozen=True)
class StripReadings:
    """What a student reads on their strip: plain tables, no computed answers (x north/up, y east/right).

    Attributes
    ----------
    rays : DataFrame, index (tie point, template)
        ``centre x, mm``, ``centre y, mm`` (the template's working centre on the
        laid sheet, to 0.001 mm) and ``direction α, °`` (the ray to the tie point,
        clockwise from +x, to 0.0001°) — given finely enough that the triangles
        computed from them are the laid strip's own (a few hundredths of a mm).
    control : DataFrame, index control point
        ``X (north), m``, ``Y (east), m`` (the catalogue, to 0.1 m) and ``x on
        the strip, mm``, ``y on the strip, mm`` (read on the common tracing, 0.1 mm).
    points : DataFrame, index point (:data:`POINT_ORDER`)
        ``kind`` and ``x on the strip, mm``, ``y on the strip, mm`` (read, 0.1 mm).
    M : the plan's scale denominator (1:M)
    """

    rays: pd.DataFrame
    control: pd.DataFrame
    points: pd.DataFrame
    M: float

    def rays_table(self) -> pd.DataFrame:
        """The rays at the tie points (a copy)."""
        return self.rays.copy()

    def control_table(self) -> pd.DataFrame:
        """The control points: coordinates and positions on the free strip (a copy)."""
        return self.control.copy()

    def points_table(self) -> pd.DataFrame:
        """Every point of the common tracing (a copy)."""
        return self.points.copy()


def tracing_frame(variant) -> tuple:
    """Where the student's common tracing lies on the table: ``(φ rad, R (2, 2), shift (2,) mm)``.

    The laid strip's own frame (:class:`aerophoto.triangulation.FreeStrip`:
    the first centre at the origin, the first initial direction along +x) is
    turned by φ (−8° … 8°, seeded) and shifted so that every point lies at
    positive coordinates some 2–5 cm from the edges: P_table = R·P + shift (the
    package's mathematical frame; :func:`aerophoto.triangulation.sheet_to_geodetic`
    then gives the student's x up, y right).  A tracing is never measured from
    its first centre along its first direction, and that would make every distance
    from 36 a plain coordinate of the table.
    """
    fs = lab_strip(variant).free
    rng = np.random.default_rng([int(variant.i), _SALT_FRAME])
    phi = math.radians(rng.uniform(-8.0, 8.0))
    R = np.array([[math.cos(phi), -math.sin(phi)], [math.sin(phi), math.cos(phi)]])
    P = fs.points_mm[np.all(np.isfinite(fs.points_mm), axis=1)] @ R.T
    shift = np.array([30.0 - P[:, 0].min() + rng.uniform(0.0, 15.0), 20.0 - P[:, 1].min() + rng.uniform(0.0, 15.0)])
    return phi, R, shift


@functools.lru_cache(maxsize=128)
def shared_readings(variant) -> StripReadings:
    lab = lab_strip(variant)
    fs, pts = lab.free, lab.free.points
    names = list(pts.names)
    # the rays at the tie points, as laid, in the geodetic convention of the sheet
    phi, R, shift = tracing_frame(variant)

    def on_sheet(xy):  # the laid strip's frame → the tracing on the table, geodetic (x up, y right)
        return tri.sheet_to_geodetic(np.asarray(xy, dtype=float) @ R.T + shift)

    rows, idx = [], []
    for name in TIE_POINTS:
        i = names.index(name)
        for t in range(fs.templates.n_photos):
            d = fs.templates.directions_rad[t, i]
            if not np.isfinite(d):
                continue
            c = on_sheet(fs.centres_mm[t])
            rows.append((round(float(c[0]), 3) + 0.0, round(float(c[1]), 3) + 0.0,
                         round(float(tri.direction_to_geodetic_deg(d + fs.theta_rad[t] + phi)), 4) % 360.0 + 0.0))
            idx.append((name, str(pts.photo_numbers[t])))
    rays = pd.DataFrame(rows, columns=["centre x, mm", "centre y, mm", "direction α, °"],
                        index=pd.MultiIndex.from_tuples(idx, names=["tie point", "template"]))
    # every point of the common tracing, read to 0.1 mm
    order = [names.index(n) for n in POINT_ORDER]
    xy = on_sheet(fs.points_mm[order])
    read = _own.read_mm(xy, _own.reading_rng(variant, _SALT_SHEET), sigma_mm=SHEET_SIGMA_MM, max_mm=SHEET_MAX_MM)
    points = pd.DataFrame({"kind": [pts.kinds[i] for i in order], "x on the strip, mm": read[:, 0],
                           "y on the strip, mm": read[:, 1]}, index=pd.Index(list(POINT_ORDER), name="point"))
    ctl = [n for n in POINT_ORDER if pts.kinds[names.index(n)] == "control"]
    ctl = sorted(ctl)  # 36/1, 36/2, 39/1, 39/2
    XY = np.round(tri.ground_to_geodetic(pts.XYZ_m[[names.index(n) for n in ctl], :2]), 1) + 0.0
    control = pd.DataFrame({"X (north), m": XY[:, 0], "Y (east), m": XY[:, 1],
                            "x on the strip, mm": points.loc[ctl, "x on the strip, mm"].to_numpy(),
                            "y on the strip, mm": points.loc[ctl, "y on the strip, mm"].to_numpy()},
                           index=pd.Index(ctl, name="control point"))
    return StripReadings(rays, control, points, float(variant.M))


def strip_readings(variant) -> StripReadings:
    """The student's readings on their strip (:class:`StripReadings`), fresh copies of the tables."""
    r = shared_readings(variant)
    return StripReadings(r.rays.copy(), r.control.copy(), r.points.copy(), r.M)
