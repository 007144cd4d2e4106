"""Graded tasks of chapter 06 (guide §7): the student's own strip — its error triangles, table 8 and table 9.

Every student triangulates **their own strip** (:func:`aerophoto.tasks._own.own_strip`:
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
   bounded reading error (:func:`aerophoto.tasks._own.read_mm`).

What the student reads (:class:`StripReadings`, all in the Russian geodetic
convention of the guide's table 8 — x north/up, y east/right, directions
clockwise from +x, :mod:`aerophoto.triangulation.geodetic`):

* ``rays`` — at each tie point the three rays of the laid templates (the centre
  on the sheet and the ray's direction): task 06.1, the error triangles;
* ``control`` — the four control points: coordinates X, Y (m) and their
  positions on the free strip (mm): task 06.2, table 8;
* ``points`` — every point on the common tracing (tie points are not
  transferred, guide §13 step 7): task 06.3, table 9.

The reference answers are computed **from those readings**, as the student
computes them; the tests hold them against the truth.  Chapter 12
(:mod:`aerophoto.tasks.ch12`) works on the same strip (tables 12 and 13).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import plane
from .. import triangulation as tri
from .._validate import check_range
from . import _own
from .base import Answer, Hidden, Task

__all__ = ["LabStrip", "StripReadings", "lab_strip", "strip_readings", "free_scale_ratio", "RING", "RING_LABELS",
           "TIE_POINTS", "POINT_ORDER", "CENTRE", "CORRECTION_POINTS", "TOL_COEFF", "SHEET_SIGMA_MM",
           "SHEET_MAX_MM", "tracing_frame", "triangles_from_rays", "coefficients_from_control", "corrections_from_points",
           "ErrorTriangles", "RingCoefficients", "CorrectionsForReduction", "CorrectionsTask", "TASKS"]

#: the four bases of a table-8 ring around the strip, in the order of task 06.2
RING = (("36/1", "39/1"), ("39/1", "39/2"), ("39/2", "36/2"), ("36/2", "36/1"))
RING_LABELS = tuple(f"{a}–{b}" for a, b in RING)
#: the tie points of photos 37 and 38 (a, b in the triple overlap 36-37-38; c, d in 37-38-39)
TIE_POINTS = ("a", "b", "c", "d")
#: the points of the common tracing along the strip (guide table 13's order; tie points are not transferred)
POINT_ORDER = ("36", "36/1", "36/2", "А", "Б", "37", "В", "Г", "38", "Д", "Е", "39/1", "39/2", "39")
#: the centre of the strip for table 9 (guide §13: "one of the middle centres, 37 or 38")
CENTRE = "37"
#: the points whose corrections task 06.3 asks for: every other point of the common tracing
CORRECTION_POINTS = tuple(n for n in POINT_ORDER if n != CENTRE)
#: the coefficient is printed to three decimals: half a unit of the last digit
TOL_COEFF = 0.0005
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
    strip, s = _own._own_strip(i, f_mm, frame_mm, m, px_percent)
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
def _readings(variant) -> StripReadings:
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
    r = _readings(variant)
    return StripReadings(r.rays.copy(), r.control.copy(), r.points.copy(), r.M)


# =========================================================================== the work, from the readings
def triangles_from_rays(rays: pd.DataFrame) -> pd.DataFrame:
    """The error triangle at every tie point from the table of rays: the three sides and the largest, mm.

    Each pair of rays (centre (x, y), direction α clockwise from +x) is
    intersected; the triangle's sides are the distances between the three
    intersections (:func:`aerophoto.plane.error_triangle`, which reads the
    geodetic convention as it is — :mod:`aerophoto.triangulation.geodetic`).
    """
    out = []
    for name in dict.fromkeys(rays.index.get_level_values(0)):
        r = rays.loc[name]
        O = r[["centre x, mm", "centre y, mm"]].to_numpy(dtype=float)
        A = np.radians(r["direction α, °"].to_numpy(dtype=float))
        _V, sides = plane.error_triangle(O, A)
        out.append((name, *sides, float(sides.max())))
    return pd.DataFrame(out, columns=["tie point", "side 1, mm", "side 2, mm", "side 3, mm", "largest, mm"]
                        ).set_index("tie point")


def coefficients_from_control(control: pd.DataFrame, M: float, pairs) -> tri.ReductionCoefficients:
    """Table 8/12 from the control table: l_base from the coordinates (plan mm at 1/M), l_template from the strip."""
    base = control[["X (north), m", "Y (east), m"]].to_numpy(dtype=float) * 1000.0 / float(M)
    strip = control[["x on the strip, mm", "y on the strip, mm"]].to_numpy(dtype=float)
    return tri.reduction_coefficients(list(control.index), base, strip, pairs=pairs)


def corrections_from_points(points: pd.DataFrame, centre: str, k: float, names) -> tuple:
    """(r, v) for the named points: r from the centre on the common tracing, v = r·(k − 1), mm (table 9/13)."""
    xy = points[["x on the strip, mm", "y on the strip, mm"]]
    C = xy.loc[centre].to_numpy(dtype=float)
    P = xy.loc[list(names)].to_numpy(dtype=float)
    r = np.hypot(*(P - C).T)
    return r, r * (float(k) - 1.0)


def _numbers(x, n: int):
    """``x`` as a list of ``n`` finite floats, or None (not answered, wrong length, not numbers)."""
    if x is None or x is Ellipsis or isinstance(x, (str, bytes, dict, bool)):
        return None
    try:
        out = [float(e) for e in (x.tolist() if hasattr(x, "tolist") else x)]
    except (TypeError, ValueError):
        return None
    return out if len(out) == n and all(math.isfinite(e) for e in out) else None


def _verdict_hidden(name: str, got_verdict, deviations, tols, margin: float) -> Hidden:
    """A verdict against the student's own numbers: True if all |d| ≤ tol, False if one exceeds it;
    within ``margin`` of a tolerance either verdict is consistent."""
    d, t = np.abs(np.asarray(deviations, dtype=float)), np.asarray(tols, dtype=float)
    if np.all(d <= t - margin):
        expected = True
    elif np.any(d > t + margin):
        expected = False
    else:
        expected = bool(got_verdict) if isinstance(got_verdict, (bool, np.bool_)) else True
    return Hidden(name, got_verdict, expected, kind="bool")


# =========================================================================== task 06.1
@dataclass(frozen=True)
class ErrorTriangles(Task):
    """Task 06.1: the error triangle at every tie point of the laid strip, and the 0.3 mm check (§7, §13 step 6)."""

    id = "task-06-1"
    title = "The error triangles of your strip"
    points = 3
    spec = (
        Answer("triangle_mm", "largest side of the error triangle at a, b, c, d, mm", unit="mm", kind="values",
               tol_abs=0.01, labels=TIE_POINTS),
        Answer("triangles_ok", "True if every side is within 0.3 mm", kind="bool",
               hint="compare the largest side of every triangle with 0.3 mm (guide §7)."),
    )

    def inputs(self, v) -> StripReadings:
        """The student's readings: ``rays_table()`` is what this task uses."""
        return strip_readings(v)

    def answers(self, v) -> dict:
        t = triangles_from_rays(_readings(v).rays)
        side = [float(t.loc[n, "largest, mm"]) for n in TIE_POINTS]
        return {"triangle_mm": side, "triangles_ok": bool(max(side) <= tri.TRIANGLE_TOL_MM)}

    def hidden(self, v, got) -> list:
        """The verdict must follow from the student's own sides."""
        s = _numbers(got.get("triangle_mm"), len(TIE_POINTS))
        if s is None:
            return [Hidden("triangles_ok from your sides", None, None, kind="bool")]
        return [_verdict_hidden("triangles_ok from your sides", got.get("triangles_ok"), s,
                                [tri.TRIANGLE_TOL_MM] * len(s), 0.01)]


# =========================================================================== task 06.2
@dataclass(frozen=True)
class RingCoefficients(Task):
    """Task 06.2: table 8 for the four bases around the strip — l_осн, l_воск, k, the mean, the 0.003 check."""

    id = "task-06-2"
    title = "Reduction coefficients of your strip (table 8)"
    points = 4
    spec = (
        Answer("l_base_mm", "base lengths on the plan l_осн, mm", unit="mm", kind="values", tol_abs=0.05,
               labels=RING_LABELS),
        Answer("l_template_mm", "the same on the free strip l_воск, mm", unit="mm", kind="values", tol_abs=0.05,
               labels=RING_LABELS),
        Answer("k_bases", "four reduction coefficients k = l_осн/l_воск", kind="values", tol_abs=TOL_COEFF,
               labels=RING_LABELS),
        Answer("k_mean", "their mean", tol_abs=TOL_COEFF),
        Answer("spread_ok", "True if every |k − mean| is within its tolerance", kind="bool",
               hint="compare every |k − mean| with 0.003 (0.006 on a base shorter than 133 mm on the plan)."),
    )

    def inputs(self, v) -> StripReadings:
        """The student's readings: ``control_table()`` is what this task uses."""
        return strip_readings(v)

    def answers(self, v) -> dict:
        c = coefficients_from_control(_readings(v).control, float(v.M), RING)
        return {"l_base_mm": [float(x) for x in c.l_base_mm], "l_template_mm": [float(x) for x in c.l_template_mm],
                "k_bases": [float(x) for x in c.k], "k_mean": float(c.k_mean), "spread_ok": bool(c.all_ok)}

    def slips(self, v) -> dict:
        k_mean = self.answers(v)["k_mean"]
        return {"k_mean": {"this is l_воск / l_осн — the coefficient is base over template": 1.0 / k_mean}}

    def hidden(self, v, got) -> list:
        """k from the student's own lengths, the mean of their own k, the verdict from their own deviations."""
        n = len(RING)
        lb, lt, ks = (_numbers(got.get(k), n) for k in ("l_base_mm", "l_template_mm", "k_bases"))
        out = []
        for j, lab in enumerate(RING_LABELS):
            ok = lb is not None and lt is not None and ks is not None and lt[j] > 0
            out.append(Hidden(f"k of {lab} from your lengths", ks[j] if ok else None, lb[j] / lt[j] if ok else None,
                              tol_abs=TOL_COEFF))
        mean = float(np.mean(ks)) if ks is not None else None
        out.append(Hidden("k_mean is the mean of your k_bases", got.get("k_mean") if ks is not None else None, mean,
                          tol_abs=TOL_COEFF))
        if ks is None:
            out.append(Hidden("spread_ok from your k_bases", None, None, kind="bool"))
        else:
            tol = coefficients_from_control(_readings(v).control, float(v.M), RING).tol
            out.append(_verdict_hidden("spread_ok from your k_bases", got.get("spread_ok"), np.array(ks) - mean, tol,
                                       TOL_COEFF))
        return out


# =========================================================================== task 06.3
@dataclass(frozen=True)
class CorrectionsTask(Task):
    """Base of tasks 06.3 and 12.3: distances r from a central working centre and corrections v = r·(k − 1)."""

    centre = CENTRE
    names_ = CORRECTION_POINTS
    pairs = RING

    def inputs(self, v) -> StripReadings:
        """The student's readings: ``points_table()`` is what this task uses."""
        return strip_readings(v)

    def _k(self, v) -> float:
        return coefficients_from_control(_readings(v).control, float(v.M), self.pairs).k_mean

    def answers(self, v) -> dict:
        r, vv = corrections_from_points(_readings(v).points, self.centre, self._k(v), self.names_)
        return {"r_mm": [float(x) for x in r], "v_mm": [float(x) for x in vv]}

    def slips(self, v) -> dict:
        return {}

    def hidden(self, v, got) -> list:
        """Every v must be the student's own r times one and the same k − 1 (within the 0.1 mm the guide prints)."""
        n = len(self.names_)
        r, vv = _numbers(got.get("r_mm"), n), _numbers(got.get("v_mm"), n)
        if r is None or vv is None:
            return [Hidden("v_mm proportional to your r_mm", None, None)]
        r, vv = np.array(r), np.array(vv)
        far = r > 30.0
        if not np.any(far) or np.any(r < 0):
            return [Hidden("v_mm proportional to your r_mm", None, None)]
        k1 = float(np.median(vv[far] / r[far]))
        return [Hidden(f"v_mm at {name} = r·(k − 1) with your r and one k", float(vv[j]), float(k1 * r[j]),
                       tol_abs=0.06) for j, name in enumerate(self.names_)]


@dataclass(frozen=True)
class CorrectionsForReduction(CorrectionsTask):
    """Task 06.3: table 9 — r from working centre 37 and v = r·(k − 1) for every other point of the common tracing."""

    id = "task-06-3"
    title = "Corrections for reduction (table 9)"
    points = 3
    spec = (
        Answer("r_mm", "distances from centre 37, in the table's order (37 left out), mm", unit="mm", kind="values",
               tol_abs=0.05, labels=CORRECTION_POINTS),
        Answer("v_mm", "corrections v = r·(k − 1), same order, mm", unit="mm", kind="values", tol_abs=0.05,
               tol_rel=0.02, labels=CORRECTION_POINTS),
    )


TASKS = (ErrorTriangles(), RingCoefficients(), CorrectionsForReduction())
