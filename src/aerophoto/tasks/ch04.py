"""Graded tasks of chapter 04 (guide §5): the isocentre and the tilt displacement on the student's photo.

The photo has the variant's f, tilt α and direction λ of the positive
principal vertical (counter-clockwise from the photo's +x axis).

* task 04.1 (:class:`Isocentre`): oc = −f·tg(α/2) with the guide's sign and
  the photo coordinates of the isocentre c;
* task 04.2 (:class:`TiltOfPoint`): the point A at :data:`TILT_LAB_POINT_MM`:
  its r_c and φ about c and its δα = −(r_c²·cos φ/f)·sin α;
* task 04.3 (:class:`Table6OnYourPhoto`): the guide's nine table-6 points
  (r_c, φ as printed, :data:`aerophoto.guide.s05.TABLE6`) with the variant's f
  and α: δα of point I and the number of corrections.

:func:`tilt_lab` computes the reference solution (:class:`TiltLab`) with
:mod:`aerophoto.displacement` and :mod:`aerophoto.geometry`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import displacement as d
from .. import geometry as g
from ..guide.s05 import TABLE6
from .base import Answer, Hidden, Task, submitted_number

__all__ = ["TILT_LAB_POINT_MM", "TiltLab", "tilt_lab", "table6_points", "Isocentre", "TiltOfPoint",
           "Table6OnYourPhoto", "TASKS"]

#: the point A of task 04.2: photo coordinates x, y from o, mm
TILT_LAB_POINT_MM = (70.0, -15.0)


@dataclass(frozen=True)
class TiltLab:
    """The reference solution of the tilt tasks for one variant (the instructor's side).

    Attributes
    ----------
    f_mm, alpha_deg, lambda_deg : float
        The variant's camera and tilt.
    oc_mm : float
        oc = −f·tg(α/2) with the guide's sign, mm.
    c_mm : ndarray, shape (2,)
        Photo coordinates of the isocentre c, mm.
    point_mm : ndarray, shape (2,)
        The task's point A, mm.
    r_c_mm, phi_deg : float
        Polar coordinates of A about c (φ counter-clockwise from the + principal vertical, 0 ≤ φ < 360).
    delta_mm, delta_exact_mm : float
        δα of A, the guide's formula and exact, mm.
    table6 : :class:`aerophoto.displacement.TiltCorrections`
        The guide's nine table-6 points with the variant's f and α.
    """

    f_mm: float
    alpha_deg: float
    lambda_deg: float
    oc_mm: float
    c_mm: np.ndarray
    point_mm: np.ndarray
    r_c_mm: float
    phi_deg: float
    delta_mm: float
    delta_exact_mm: float
    table6: d.TiltCorrections

    # typical mistakes, for the checks' hints
    @property
    def r_from_o_mm(self) -> float:
        """The distance of A from o instead of c, mm."""
        return float(np.hypot(*self.point_mm))

    @property
    def phi_from_x_deg(self) -> float:
        """The angle of A about c counted from the photo's x axis instead of the principal vertical, degrees."""
        d_ = self.point_mm - self.c_mm
        return float(np.degrees(np.arctan2(d_[1], d_[0])) % 360.0)

    @property
    def delta_from_o_mm(self) -> float:
        """δα with r and φ measured from o instead of c, mm."""
        u = g.principal_vertical(g.Pose(alpha_deg=self.alpha_deg, lambda_deg=self.lambda_deg))
        r = self.r_from_o_mm
        cosp = float(self.point_mm @ u) / r
        return -(r**2) * cosp / self.f_mm * math.sin(math.radians(self.alpha_deg))

    @property
    def delta_phi_from_x_mm(self) -> float:
        """δα with φ counted from the photo's x axis, mm."""
        return -(self.r_c_mm**2) * math.cos(math.radians(self.phi_from_x_deg)) / self.f_mm * math.sin(
            math.radians(self.alpha_deg))


def tilt_lab(v) -> TiltLab:
    """The reference solution for variant ``v`` (any object with ``f_mm``, ``alpha_deg``, ``lambda_deg``)."""
    cam = g.Camera(v.f_mm)
    pose = g.Pose(alpha_deg=v.alpha_deg, lambda_deg=v.lambda_deg)
    c = g.isocentre(cam, pose)
    A = np.array(TILT_LAB_POINT_MM, dtype=float)
    r, phi = d.polar_about_isocentre(cam, pose, A)
    approx = float(g.tilt_displacement_approx(cam, pose, A))
    exact = float(g.tilt_displacement_exact(cam, pose, A))
    t6 = d.tilt_corrections(TABLE6["names"], TABLE6["r_c"], TABLE6["phi"], f_mm=v.f_mm, alpha_deg=v.alpha_deg)
    return TiltLab(cam.f_mm, pose.alpha_deg, pose.lambda_deg, d.isocentre_offset(cam.f_mm, pose.alpha_deg), c, A,
                   float(r), float(phi), approx, exact, t6)


def table6_points() -> pd.DataFrame:
    """The guide's table 6 inputs as printed: ``r_c, mm`` and ``φ, °`` of its nine points (task 04.3)."""
    return pd.DataFrame({"r_c, mm": [float(x) for x in TABLE6["r_c"]], "φ, °": list(TABLE6["phi"])},
                        index=pd.Index(TABLE6["names"], name="point"))


@dataclass(frozen=True)
class Isocentre(Task):
    """Task 04.1: oc = −f·tg(α/2) with the guide's sign, and the photo coordinates of the isocentre c."""

    id = "task-04-1"
    title = "The isocentre on your photo"
    points = 3
    spec = (
        Answer("oc_mm", "o to c along the principal vertical, guide's sign, mm", unit="mm", tol_abs=0.05),
        Answer("xc_mm", "x of the isocentre c, mm", unit="mm", tol_abs=0.05),
        Answer("yc_mm", "y of the isocentre c, mm", unit="mm", tol_abs=0.05),
    )

    def answers(self, v) -> dict:
        lab = tilt_lab(v)
        return {"oc_mm": lab.oc_mm, "xc_mm": float(lab.c_mm[0]), "yc_mm": float(lab.c_mm[1])}

    def slips(self, v) -> dict:
        lab = tilt_lab(v)
        on = d.nadir_offset(v.f_mm, v.alpha_deg)
        turned = "c lies on the principal vertical, turned by λ from the x axis"
        return {
            "oc_mm": {"that is on = f·tg α, the nadir point — the isocentre uses α/2": on,
                      "that is the nadir point's distance f·tg α — the isocentre uses α/2": -on},
            "xc_mm": {turned: lab.oc_mm},
            "yc_mm": {turned: 0.0},
        }

    def hidden(self, v, got) -> list:
        # c lies at the distance |oc| from o
        xc, yc = submitted_number(got.get("xc_mm")), submitted_number(got.get("yc_mm"))
        dist = None if xc is None or yc is None else math.hypot(xc, yc)
        return [Hidden("|oc| from xc, yc", dist, abs(tilt_lab(v).oc_mm), tol_abs=0.05)]


@dataclass(frozen=True)
class TiltOfPoint(Task):
    """Task 04.2: r_c and φ of the point A about the isocentre, and its tilt displacement δα."""

    id = "task-04-2"
    title = "The tilt displacement of a point"
    points = 4
    spec = (
        Answer("rcA_mm", "distance from c, mm", unit="mm", tol_abs=0.05),
        Answer("phiA_deg", "angle from the + principal vertical, counter-clockwise, 0–360°", unit="°", tol_abs=0.5,
               period=360.0),
        Answer("dA_mm", "tilt displacement, mm", unit="mm", tol_abs=0.01),
    )

    def inputs(self, v) -> dict:
        """The point A: ``{"x_mm": 70.0, "y_mm": -15.0}`` (the same on every photo)."""
        return {"x_mm": TILT_LAB_POINT_MM[0], "y_mm": TILT_LAB_POINT_MM[1]}

    def answers(self, v) -> dict:
        lab = tilt_lab(v)
        return {"rcA_mm": lab.r_c_mm, "phiA_deg": lab.phi_deg, "dA_mm": lab.delta_mm}

    def slips(self, v) -> dict:
        lab = tilt_lab(v)
        return {
            "rcA_mm": {"that is the distance from o — tilt displacement is measured from the isocentre c":
                       lab.r_from_o_mm},
            "phiA_deg": {"φ is counted from the principal vertical (direction λ), not from the x axis":
                         lab.phi_from_x_deg,
                         "φ is counted counter-clockwise, not clockwise": (360 - lab.phi_deg) % 360},
            "dA_mm": {"r_c and φ must be measured from the isocentre c, not from o": lab.delta_from_o_mm,
                      "φ is counted from the principal vertical, not from the x axis": lab.delta_phi_from_x_mm},
        }

    def hidden(self, v, got) -> list:
        # the student's δα must follow from the student's own r_c and φ
        r, phi = submitted_number(got.get("rcA_mm")), submitted_number(got.get("phiA_deg"))
        expected = None
        if r is not None and phi is not None:
            expected = -(r**2) * math.cos(math.radians(phi)) / v.f_mm * math.sin(math.radians(v.alpha_deg))
        return [Hidden("dA_mm (from your r_c, φ)", got.get("dA_mm") if expected is not None else None, expected,
                       tol_abs=0.01)]


@dataclass(frozen=True)
class Table6OnYourPhoto(Task):
    """Task 04.3: the guide's nine table-6 points with the variant's f and α: δα of point I, number of corrections."""

    id = "task-04-3"
    title = "Which points of table 6 need a correction on your photo?"
    points = 3
    spec = (
        Answer("dI_mm", "tilt displacement of point I, mm", unit="mm", tol_abs=0.01),
        Answer("n_corr", "number of points corrected", integer=True),
    )

    def inputs(self, v) -> pd.DataFrame:
        return table6_points()

    def answers(self, v) -> dict:
        t6 = tilt_lab(v).table6
        return {"dI_mm": float(t6.delta_approx_mm[0]), "n_corr": t6.n_applied}

    @staticmethod
    def _guide_dI() -> float:
        """δα of point I with the guide's f = 100 mm and α = 3°, mm."""
        return float(d.tilt_corrections(TABLE6["names"][:1], TABLE6["r_c"][:1], TABLE6["phi"][:1], f_mm=d.GUIDE_F_MM,
                                        alpha_deg=d.GUIDE_ALPHA_DEG).delta_approx_mm[0])

    def slips(self, v) -> dict:
        other_f = v.f_mm != d.GUIDE_F_MM
        return {"dI_mm": {"that is the guide's printed value — compute with your own f":
                          TABLE6["delta"][0] if other_f else None,
                          "you used the guide's f = 100 mm, not your variant's f":
                          self._guide_dI() if other_f else None}}

    def hidden(self, v, got) -> list:
        # δα scales as sin α/f: brought to the guide's f = 100 mm and α = 3° it must give the guide's point I
        dI, sin_a = submitted_number(got.get("dI_mm")), math.sin(math.radians(v.alpha_deg))
        scaled = None if dI is None or sin_a == 0 else dI * v.f_mm / d.GUIDE_F_MM * math.sin(
            math.radians(d.GUIDE_ALPHA_DEG)) / sin_a
        return [Hidden("dI_mm (scales as sin α/f)", scaled, self._guide_dI(), tol_abs=0.02)]


TASKS = (Isocentre(), TiltOfPoint(), Table6OnYourPhoto())
