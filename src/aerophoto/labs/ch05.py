"""Chapter 05's lab (guide §6): the student's own fotoschema and the readings made on it.

Every student glues **their own strip** (:func:`aerophoto.labs.own.own_strip`:
four photos 36 … 39 with their variant's f, 1:m and p_x, flown over the
virtual site at a place of their own, tilts up to 2° with f·tg α ≤ 6 mm) into a
fotoschema with :func:`aerophoto.mosaic.assemble`, over the site's true relief
(170–200 m: the variant's Z_max − Z_min = 30 m) at the plan scale 1:M.

* :func:`seam_readings` (task 05.1, guide §6 step 8): along every cut, a detail
  pricked through the cut-off strip: its distance from the cut on the glued
  piece (the contour) and of the prick, along the strip, mm (read to 0.1 mm);
* :func:`scale_readings` (task 05.2, step 7): four points near the outer edges
  of the first and last working areas, read on the fotoschema (sheet mm) and on
  the 1:10 000 plan (mm, x north, y east — the Russian geodetic convention; the
  package's ground frame is X east, Y north) to 0.1 mm.

The readings are the truth (the camera model: :func:`aerophoto.mosaic.seam_details`,
:class:`aerophoto.mosaic.ScaleCheck`) plus a bounded, seeded pricking error,
rounded to 0.1 mm (:func:`aerophoto.labs.own.read_mm`).  :func:`answers_of` is
the worked solution from those readings, as the student computes it (ΔI, the
quality m (6.2), the bases l_i, L_i, the partial scales m_i (6.1) and their
mean); the graded tasks (:mod:`aerophoto.tasks.ch05`) and the live demo's sheet
(:mod:`aerophoto.demos.fotoschema`) both take it from here.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import mosaic as mo
from . import own as _own

__all__ = ["INSET_MM", "PRICK_SIGMA_MM", "PRICK_MAX_MM", "POINT_SIGMA_MM", "POINT_MAX_MM", "BASES", "BASE_LABELS",
           "OwnFotoschema", "own_fotoschema", "seam_readings", "scale_readings", "answers_of"]

#: the details pricked through the cut-off strips lie this far into the left piece, along the strip, mm
#: (uniform in the range, seeded: "не отступая далеко от него", guide §6 step 8)
INSET_MM = (2.0, 5.0)
#: pricking through the cut-off strip: σ and bound of the needle's error, mm (then read to 0.1 mm)
PRICK_SIGMA_MM = 0.03
PRICK_MAX_MM = 0.06
#: identifying and reading a point on the fotoschema or the plan: σ and bound, mm (then read to 0.1 mm)
POINT_SIGMA_MM = 0.05
POINT_MAX_MM = 0.10
#: the four bases of step 7, by point: the two along the strip, then the two diagonals
BASES = ((0, 2), (1, 3), (0, 3), (1, 2))
_SALT_SEAMS, _SALT_POINTS, _SALT_DETAILS = 5051, 5052, 5053


@dataclass(frozen=True)
class OwnFotoschema:
    """A student's fotoschema and what the guide's checks read on it (the instructor's side: holds the truth).

    Attributes
    ----------
    variant : the student's Variant
    strip : aerophoto.simulate.Strip — the student's own strip (photos 36 … 39)
    site : the virtual site (the photographed terrain)
    fs : aerophoto.mosaic.Fotoschema — assembled as in guide §6, plan scale 1:M of the variant
    details : aerophoto.mosaic.SeamDetails — the details pricked through the cut-off strips (truth)
    """

    variant: object
    strip: object
    site: object
    fs: mo.Fotoschema
    details: mo.SeamDetails

    @property
    def numbers(self) -> tuple:
        return self.fs.numbers

    @property
    def point_names(self) -> tuple:
        """The four points of the mean scale: 36a, 36b (first photo), 39a, 39b (last photo)."""
        return self.fs.scale.names

    @property
    def base_labels(self) -> tuple:
        n = self.point_names
        return tuple(f"{n[i]}–{n[j]}" for i, j in BASES)

    def plan_xy_mm(self) -> np.ndarray:
        """The four points on the 1:M plan, (4, 2): x north, y east from the plan's south-west corner, mm (truth)."""
        G = self.fs.scale.ground_m
        x0, _x1, y0, _y1 = self.site.extent_m
        M = self.fs.scale.M
        return np.column_stack([(G[:, 1] - y0) * 1000.0 / M, (G[:, 0] - x0) * 1000.0 / M])


@functools.lru_cache(maxsize=128)
def _own_fotoschema(i: int, f_mm: float, frame_mm: float, m: float, px_percent: float, M: float) -> OwnFotoschema:
    from ..variants import variant_for_index

    v = variant_for_index(i)
    strip, site = _own.own_strip(v) if (v.f_mm, v.frame_mm, v.m, v.px_percent) == (f_mm, frame_mm, m, px_percent) \
        else _own.own_strip_of(i, f_mm, frame_mm, m, px_percent)
    fs = mo.assemble(strip, site, points_m=mo.catalogue_points(site), M=M)
    n = int(fs.dI_mm.size)
    inset = np.random.default_rng([i, _SALT_DETAILS]).uniform(*INSET_MM, size=n)  # where the sharp details are
    return OwnFotoschema(v, strip, site, fs, mo.seam_details(fs, site, inset_mm=inset))


def own_fotoschema(variant) -> OwnFotoschema:
    """The student's fotoschema (see :class:`OwnFotoschema`), built once per variant and process."""
    return _own_fotoschema(int(variant.i), float(variant.f_mm), float(variant.frame_mm), float(variant.m),
                           float(variant.px_percent), float(variant.M))


@functools.lru_cache(maxsize=128)
def _seam_readings(variant) -> pd.DataFrame:
    own = own_fotoschema(variant)
    d = own.details
    rng = _own.reading_rng(variant, _SALT_SEAMS)
    contour = _own.read_mm(d.contour_from_cut_mm, rng, sigma_mm=0.0, max_mm=0.0)  # the cut and the contour: read
    prick = _own.read_mm(d.prick_from_cut_mm, rng, sigma_mm=PRICK_SIGMA_MM, max_mm=PRICK_MAX_MM)
    n = own.numbers
    idx = pd.MultiIndex.from_arrays([[f"{n[s]}/{n[s + 1]}" for s in d.seam], d.point.tolist()],
                                    names=["cut", "point"])
    return pd.DataFrame({"y across, mm": np.round(d.contour_mm[:, 1], 0) + 0.0,
                         "contour from the cut, mm": contour, "prick from the cut, mm": prick}, index=idx)


def seam_readings(variant) -> pd.DataFrame:
    """Task 05.1's readings on the student's fotoschema: one row per check point (a fresh copy).

    Index (cut "36/37", point 1, 2, …); columns: ``y across, mm`` (where along
    the cut, to 1 mm), ``contour from the cut, mm`` and ``prick from the cut, mm``
    (along the strip, positive into the left piece, read to 0.1 mm).
    """
    return _seam_readings(variant).copy()


@functools.lru_cache(maxsize=128)
def _scale_readings(variant) -> pd.DataFrame:
    own = own_fotoschema(variant)
    rng = _own.reading_rng(variant, _SALT_POINTS)
    sheet = _own.read_mm(own.fs.scale.sheet_mm, rng, sigma_mm=POINT_SIGMA_MM, max_mm=POINT_MAX_MM)
    plan = _own.read_mm(own.plan_xy_mm(), rng, sigma_mm=POINT_SIGMA_MM, max_mm=POINT_MAX_MM)
    return pd.DataFrame({"along the strip, mm": sheet[:, 0], "across, mm": sheet[:, 1],
                         "x (north) on the plan, mm": plan[:, 0], "y (east) on the plan, mm": plan[:, 1]},
                        index=pd.Index(list(own.point_names), name="point"))


def scale_readings(variant) -> pd.DataFrame:
    """Task 05.2's readings: the four points on the fotoschema (sheet mm) and on the 1:M plan (mm; x north, y east).

    A fresh copy; the bases are :data:`BASES` (first-to-last along the strip, then the diagonals).
    """
    return _scale_readings(variant).copy()


#: the bases' names by position (the points are named after the photos: 36a, 36b, 39a, 39b for the usual strip)
BASE_LABELS = ("base 1 (a–a)", "base 2 (b–b)", "base 3 (a–b)", "base 4 (b–a)")


def _from_seams(t: pd.DataFrame) -> np.ndarray:
    return np.round(t["contour from the cut, mm"].to_numpy() - t["prick from the cut, mm"].to_numpy(), 1) + 0.0


def _from_points(t: pd.DataFrame, M: float):
    S = t[["along the strip, mm", "across, mm"]].to_numpy(dtype=float)
    P = t[["x (north) on the plan, mm", "y (east) on the plan, mm"]].to_numpy(dtype=float)
    l = np.array([math.hypot(*(S[j] - S[i])) for i, j in BASES])
    L = np.array([math.hypot(*(P[j] - P[i])) for i, j in BASES])
    return l, L, mo.partial_scales(l, L, M)


def answers_of(variant) -> dict:
    """The correct answers to both tasks, computed from the student's readings (as the student computes them)."""
    dI = _from_seams(_seam_readings(variant))
    l, L, mi = _from_points(_scale_readings(variant), float(variant.M))
    return {"dI_mm": [float(x) for x in dI], "m_rms_mm": mo.seam_rms(dI), "n_cutouts": int(np.sum(dI < 0)),
            "seams_ok": bool(round(float(dI.min()), 2) >= -mo.ALLOWED_CUTOUT_MM),
            "l_mm": [float(x) for x in l], "L_mm": [float(x) for x in L], "m_i": [float(x) for x in mi],
            "m_mean": float(np.mean(mi))}
