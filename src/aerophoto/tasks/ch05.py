"""Graded tasks of chapter 05 (guide §6): the quality and the mean scale of the student's own fotoschema.

Each student's fotoschema is built from the virtual site (:func:`fotoschema_of`):
a strip of three photos flown with the variant's camera f, scale 1/m and
forward overlap p_x, tilts up to 2° (less for long-focus cameras, so that
f·tg α stays within 6 mm) drawn from the seed i, over the site with its relief
rescaled to 5 % of the flying height H = f·m — so that every variant, short
or long focus, shows mismatches of comparable size (relief displacement grows
with h/H) — and assembled with :func:`aerophoto.mosaic.assemble`.  What the
student reads from it (:func:`measurements`) is rounded as a technician reads
it: the mismatches ΔI along both cuts and the four bases, to 0.1 mm.

* task 05.1 (:class:`SeamQuality`) — the quality m = √(ΣΔI²/n) (6.2), the
  number of cut-outs and the verdict against the 0.5 mm tolerance (step 8);
* task 05.2 (:class:`MeanScale`) — the partial scales m_i = L_i·M/l_i and their
  mean (6.1, step 7).
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np

from .. import geometry as g
from .. import mosaic as mo
from .. import simulate as sim
from .base import Answer, Hidden, Task, submitted_number

__all__ = ["N_PHOTOS", "RELIEF_FRACTION", "MAX_TILT_DEG", "MAX_TILT_OFFSET_MM", "fotoschema_of", "measurements",
           "answers_of", "SeamQuality", "MeanScale", "TASKS"]

#: photos in the student's strip
N_PHOTOS = 3
#: the site's relief is rescaled to this fraction of the flying height H = f·m
RELIEF_FRACTION = 0.05
#: largest tilt of the student's photos, degrees …
MAX_TILT_DEG = 2.0
#: … and at most this offset f·tg α of the nadir point, mm (long-focus cameras are tilted less)
MAX_TILT_OFFSET_MM = 6.0


def fotoschema_of(variant, *, site=None):
    """The student's fotoschema: ``(fotoschema, ground, H_m)`` for a variant (see the module notes).

    ``site`` is the virtual site (default :func:`aerophoto.site.get_site`);
    ``ground`` is it with the relief rescaled (:class:`aerophoto.terrain.RescaledRelief`).
    """
    from .. import site as site_mod
    from ..terrain import RescaledRelief

    if site is None:
        site = site_mod.get_site()
    H = g.flying_height_m(variant.f_mm, variant.m)
    gr = RescaledRelief(site, RELIEF_FRACTION * H)
    tilt = min(MAX_TILT_DEG, math.degrees(math.atan(MAX_TILT_OFFSET_MM / variant.f_mm)))
    strip = sim.strip_over_site(gr, variant.camera, variant.m, variant.px_percent, N_PHOTOS,
                                imperfections=sim.Imperfections(max_tilt_deg=tilt, seed=int(variant.i)))
    fs = mo.assemble(strip, gr, points_m=mo.catalogue_points(gr), M=variant.M)
    return fs, gr, H


def _read(x) -> list:
    """Values as a technician reads them: to 0.1 mm, as plain floats (no −0.0)."""
    return [float(v) + 0.0 for v in np.round(np.asarray(x, dtype=float), 1)]


def measurements(variant, *, site=None) -> dict:
    """Data "measured" on the student's own fotoschema (:func:`fotoschema_of`), read to 0.1 mm.

    Returns
    -------
    dict with ``dI_mm`` (list of ΔI along both cuts, mm, − cut-out, + duplicate),
    ``l_mm`` and ``L_mm`` (the four bases on the fotoschema and on the 1:M plan,
    mm), ``M``, ``relief_m``, ``H_m``, ``fotoschema`` (the
    :class:`aerophoto.mosaic.Fotoschema`) and ``ground`` (the terrain).
    """
    fs, gr, H = fotoschema_of(variant, site=site)
    return {"dI_mm": _read(fs.dI_mm), "l_mm": _read(fs.scale.l_mm), "L_mm": _read(fs.scale.L_mm),
            "M": float(variant.M), "relief_m": gr.relief_m, "H_m": H, "fotoschema": fs, "ground": gr}


@functools.lru_cache(maxsize=128)
def _read_default(variant) -> tuple:
    """(ΔI, l, L, M) of :func:`measurements` on the default site, cached per variant (the checks ask often)."""
    d = measurements(variant)
    return tuple(d["dI_mm"]), tuple(d["l_mm"]), tuple(d["L_mm"]), d["M"]


def _data(variant) -> dict:
    dI, l, L, M = _read_default(variant)
    return {"dI_mm": list(dI), "l_mm": list(l), "L_mm": list(L), "M": M}


def answers_of(variant, *, site=None) -> dict:
    """The correct answers to both tasks, from the rounded data of :func:`measurements`.

    ``{"m_rms_mm", "n_cutouts", "seams_ok", "m_i" (ndarray of 4), "m_mean"}``.
    """
    d = _data(variant) if site is None else measurements(variant, site=site)
    dI = np.asarray(d["dI_mm"])
    mi = mo.partial_scales(d["l_mm"], d["L_mm"], d["M"])
    return {"m_rms_mm": mo.seam_rms(dI), "n_cutouts": int(np.sum(dI < 0)),
            "seams_ok": bool(dI.min() >= -mo.ALLOWED_CUTOUT_MM), "m_i": mi, "m_mean": float(np.mean(mi))}


@dataclass(frozen=True)
class SeamQuality(Task):
    """Task 05.1: the quality m = √(ΣΔI²/n) of the seams (6.2), the number of cut-outs and the verdict (§6, step 8)."""

    id = "task-05-1"
    title = "The quality of your fotoschema"
    points = 3
    spec = (
        Answer("m_rms_mm", "RMS of the mismatches, mm", unit="mm", tol_abs=0.005),
        Answer("n_cutouts", "number of cut-outs (whole number)", kind="count", rounding="nearest"),
        Answer("seams_ok", "True / False", kind="bool", hint="compare the most negative ΔI with −0.5 mm (guide §6)."),
    )

    def inputs(self, v) -> dict:
        """The readings of the student's fotoschema: ``dI_mm``, ``l_mm``, ``L_mm`` (mm) and ``M``."""
        return _data(v)

    def answers(self, v) -> dict:
        a = answers_of(v)
        return {"m_rms_mm": a["m_rms_mm"], "n_cutouts": a["n_cutouts"], "seams_ok": a["seams_ok"]}

    def slips(self, v) -> dict:
        dI = np.array(_data(v)["dI_mm"])
        return {
            "m_rms_mm": {
                "that is the mean of |ΔI| — formula (6.2) squares, averages, then takes the root.":
                    float(np.mean(np.abs(dI))),
                "divide ΣΔI² by n before taking the root.": float(np.sqrt(np.sum(dI**2))),
                "that is ΣΔI²/n — take the square root.": float(np.mean(dI**2)),
            },
            "n_cutouts": {"you counted the duplicates (+): cut-outs are the negative ΔI.": int(np.sum(dI > 0))},
        }

    def hidden(self, v, got) -> list:
        """The three answers must agree with each other.

        * no cut-out (``n_cutouts`` = 0) cannot fail the 0.5 mm tolerance: ``seams_ok`` is then True;
        * failing seams (``seams_ok`` False) need a |ΔI| > 0.5 mm among the n readings, so
          m = √(ΣΔI²/n) ≥ 0.5/√n.
        """
        out = []
        n_cut = submitted_number(got.get("n_cutouts"))
        ok = got.get("seams_ok")
        if n_cut == 0:
            out.append(Hidden("seams_ok vs n_cutouts (no cut-out cannot fail)", ok, True, kind="bool"))
        if ok is False or (isinstance(ok, np.bool_) and not ok):
            n = len(_data(v)["dI_mm"])
            m = submitted_number(got.get("m_rms_mm"))
            out.append(Hidden("m_rms_mm vs seams_ok (a cut-out > 0.5 mm gives m ≥ 0.5/√n)",
                              None if m is None else bool(m >= mo.ALLOWED_CUTOUT_MM / math.sqrt(n)), True,
                              kind="bool"))
        return out


@dataclass(frozen=True)
class MeanScale(Task):
    """Task 05.2: the partial scales m_i = L_i·M/l_i of four bases and the mean scale (6.1, §6 step 7)."""

    id = "task-05-2"
    title = "The mean scale of your fotoschema"
    points = 3
    spec = (
        Answer("m_i", "four partial scale denominators", kind="values",
               labels=("base 1", "base 2", "base 3", "base 4")),
        Answer("m_mean", "mean scale denominator", unit="(scale denominator)"),
    )

    def inputs(self, v) -> dict:
        """The readings of the student's fotoschema: ``dI_mm``, ``l_mm``, ``L_mm`` (mm) and ``M``."""
        return _data(v)

    def answers(self, v) -> dict:
        a = answers_of(v)
        return {"m_i": list(a["m_i"]), "m_mean": a["m_mean"]}

    def hidden(self, v, got) -> list:
        """The mean scale is the mean of the student's own partial scales (6.1)."""
        try:
            mi = np.asarray(got.get("m_i"), dtype=float).ravel()
            mean = float(np.mean(mi)) if mi.size and np.all(np.isfinite(mi)) else None
        except (TypeError, ValueError):
            mean = None
        return [Hidden("m_mean (mean of your m_i)", got.get("m_mean") if mean is not None else None, mean)]


TASKS = (SeamQuality(), MeanScale())
