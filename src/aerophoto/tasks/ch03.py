"""Graded tasks of chapter 03 (guide §4): the mean object plane and the relief displacement on the student's photo.

The student's photo carries the six points of the guide's table 3 (I, 1, 2 on
low ground, II, 3, 4 on high ground), placed on the photo about as far from
the centre as the guide's r, with the guide's heights raised by the variant
number i metres (:data:`RELIEF_LAB_POINTS`, :func:`relief_points`).  The photo
has the variant's f, scale 1:m and tilt α, λ; the flying height above the
mean object plane is taken as H = f·m.

* task 03.1 (:class:`MeanObjectPlane`): Z_cp and H;
* task 03.2 (:class:`ReliefDisplacement`): r of point 1 from the nadir point
  n, its δh = r·h/H, and how many of the six points are corrected.

:func:`relief_lab` computes the reference solution (:class:`ReliefLab`) with
:mod:`aerophoto.displacement`.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import displacement as d
from .. import geometry as g
from ..guide.s04 import TABLE3_BASES
from .base import Answer, Hidden, Task, submitted_number

__all__ = ["RELIEF_LAB_POINTS", "ReliefPoints", "relief_points", "ReliefLab", "relief_lab", "MeanObjectPlane",
           "ReliefDisplacement", "TASKS"]

#: The six pricked points of the relief lab: the guide's table 3 points, placed on the photo
#: (name, x mm, y mm from the principal point o) about as far from the centre as the guide's r,
#: with the guide's heights Z, m (the student's variant adds i metres to every height).
RELIEF_LAB_POINTS = (
    ("I", -52.0, 55.0, 141.0),
    ("1", -70.0, 35.0, 138.0),
    ("2", -40.0, 70.0, 141.0),
    ("II", 60.0, -57.0, 180.0),
    ("3", 45.0, -57.0, 178.0),
    ("4", 70.0, -38.0, 182.0),
)


@dataclass(frozen=True)
class ReliefPoints:
    """The six points of the relief lab for one variant: what tasks 03.1 and 03.2 work from.

    Attributes
    ----------
    names : tuple of str
        ``("I", "1", "2", "II", "3", "4")``.
    xy_mm : ndarray, shape (6, 2)
        Photo coordinates from the principal point o, mm.
    Z_m : ndarray, shape (6,)
        Heights, m: the guide's table 3 heights + i.
    """

    names: tuple
    xy_mm: np.ndarray
    Z_m: np.ndarray

    @property
    def Z_mean_m(self) -> float:
        """The mean object plane Z_cp, m (guide §4 step 3: each zone the mean of its bases' mean heights).

        Task 03.1 asks for it; task 03.2 works from it.
        """
        Z = dict(zip(self.names, self.Z_m))
        zones = [d.zone_height([(Z[a], Z[b]) for a, b in TABLE3_BASES if a == z]) for z in ("I", "II")]
        return d.mean_object_plane(zones)

    def table(self) -> pd.DataFrame:
        """The points' photo coordinates and heights: columns ``x, mm``, ``y, mm``, ``Z, m``, one row per point."""
        return pd.DataFrame({"x, mm": self.xy_mm[:, 0], "y, mm": self.xy_mm[:, 1], "Z, m": self.Z_m},
                            index=pd.Index(self.names, name="point"))


def relief_points(v) -> ReliefPoints:
    """The relief lab's points for variant ``v`` (any object with ``i``): heights raised by i metres."""
    names = tuple(p[0] for p in RELIEF_LAB_POINTS)
    xy = np.array([[p[1], p[2]] for p in RELIEF_LAB_POINTS])
    Z = np.array([p[3] for p in RELIEF_LAB_POINTS]) + float(v.i)
    return ReliefPoints(names, xy, Z)


@dataclass(frozen=True)
class ReliefLab:
    """The reference solution of the relief tasks for one variant (the instructor's side).

    Attributes
    ----------
    points : :class:`ReliefPoints`
    H_m : float
        Flying height above the mean plane, H = f·m, m.
    n_mm : ndarray, shape (2,)
        The nadir point of the variant's tilted photo, mm.
    result : :class:`aerophoto.displacement.ReliefCorrections`
        δh of the six points with r measured from n.
    r_from_o_mm : ndarray, shape (6,)
        Distances from o — the usual mistake.
    """

    points: ReliefPoints
    H_m: float
    n_mm: np.ndarray
    result: d.ReliefCorrections
    r_from_o_mm: np.ndarray

    @property
    def Z_mean_m(self) -> float:
        """The mean object plane Z_cp, m."""
        return self.result.Z_mean_m

    def delta_from_o_mm(self) -> np.ndarray:
        """δh with r measured from o instead of n (a typical mistake), mm."""
        return self.r_from_o_mm * self.result.h_m / self.H_m

    def delta_absolute_h_mm(self) -> np.ndarray:
        """δh with h taken as the absolute height Z instead of Z − Z_cp (a typical mistake), mm."""
        return self.result.r_mm * self.points.Z_m / self.H_m


def relief_lab(v) -> ReliefLab:
    """The reference solution for variant ``v`` (with ``i``, ``f_mm``, ``m``, ``alpha_deg``, ``lambda_deg``)."""
    pts = relief_points(v)
    H = g.flying_height_m(v.f_mm, v.m)
    cam = g.Camera(v.f_mm)
    pose = g.Pose(alpha_deg=v.alpha_deg, lambda_deg=v.lambda_deg)
    n = g.nadir_point(cam, pose)
    r = np.hypot(*(pts.xy_mm - n).T)
    res = d.relief_corrections(pts.names, pts.Z_m, r, H, pts.Z_mean_m)
    return ReliefLab(pts, H, n, res, np.hypot(*pts.xy_mm.T))


@dataclass(frozen=True)
class MeanObjectPlane(Task):
    """Task 03.1: the mean object plane Z_cp of the six points and the flying height H = f·m above it."""

    id = "task-03-1"
    title = "The mean object plane of your photo"
    points = 2
    spec = (
        Answer("Zcp_m", "mean object plane, m", unit="m", tol_abs=0.2),
        Answer("H_m", "flying height above it, m", unit="m"),
    )

    def inputs(self, v) -> ReliefPoints:
        return relief_points(v)

    def answers(self, v) -> dict:
        return {"Zcp_m": relief_points(v).Z_mean_m, "H_m": g.flying_height_m(v.f_mm, v.m)}

    def slips(self, v) -> dict:
        z = relief_points(v).Z_mean_m
        return {"Zcp_m": {"you left out your variant's i metres — the heights in the table include it":
                          z - v.i if v.i else None}}

    def hidden(self, v, got) -> list:
        # the plane lies between the zones: the mean of the two zones' point heights (not weighted by bases)
        Z = relief_points(v).Z_m
        return [Hidden("Zcp_m (between the zones)", got.get("Zcp_m"), (Z[:3].mean() + Z[3:].mean()) / 2, tol_abs=0.5)]


@dataclass(frozen=True)
class ReliefDisplacement(Task):
    """Task 03.2: r of point 1 from the nadir point n, its relief displacement δh = r·h/H, the number of corrections."""

    id = "task-03-2"
    title = "Relief displacement and corrections"
    points = 4
    spec = (
        Answer("r1_mm", "distance from n to point 1, mm", unit="mm", tol_abs=0.05),
        Answer("dh1_mm", "relief displacement of point 1, mm (negative: towards n)", unit="mm", tol_abs=0.01),
        Answer("n_corr", "number of points corrected", integer=True),
    )

    def inputs(self, v) -> ReliefPoints:
        return relief_points(v)

    def answers(self, v) -> dict:
        res = relief_lab(v).result
        return {"r1_mm": float(res.r_mm[1]), "dh1_mm": float(res.delta_mm[1]), "n_corr": res.n_applied}

    def slips(self, v) -> dict:
        lab = relief_lab(v)
        return {
            "r1_mm": {"that is the distance from o — relief displacement is measured from the nadir point n":
                      float(lab.r_from_o_mm[1])},
            "dh1_mm": {"r must be measured from the nadir point n, not from o": float(lab.delta_from_o_mm()[1]),
                       "h is the height above the mean object plane, Z − Z_cp, not the height Z itself":
                       float(lab.delta_absolute_h_mm()[1])},
        }

    def hidden(self, v, got) -> list:
        # the student's δh must follow from the student's own r: δh = r·h/H
        res = relief_lab(v).result
        r1 = submitted_number(got.get("r1_mm"))
        expected = None if r1 is None else r1 * res.h_m[1] / res.H_m
        return [Hidden("dh1_mm (from your r1)", got.get("dh1_mm") if expected is not None else None, expected,
                       tol_abs=0.01)]


TASKS = (MeanObjectPlane(), ReliefDisplacement())
