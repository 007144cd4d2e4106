"""Graded tasks of chapter 13 (guide §14): soil-map scales, a soil's reflectance, and contour interpretation.

* task 13.1 (:class:`ScaleClasses`): the class of three soil maps made from the student's photos (guide §14's
  classes, with the gaps between them);
* task 13.2 (:class:`PitReflectance`): the reflectance of the soil in the pit (разрез) of the student's patch,
  from the soil model of :mod:`aerophoto.spectral`;
* task 13.3 (:class:`ContourInterpretation`): divide the student's own patch into tone-homogeneous areas
  (k-means of its colour-infrared composite) and compare them with the field survey's soil map.

The variant's data
------------------
The three maps of task 13.1 (:func:`map_scales`): a map at twice the photo's scale denominator (a photo
mosaic reduced twice), a district map ten times smaller than the photos and a regional one forty times
smaller: 1 : 2m, 1 : 10m, 1 : 40m with the student's m = 12 000 + 100i.

The patch of tasks 13.2–13.3 (:func:`aerophoto.labs.ch13.patch_of`): a square 10 cm × 10 cm on the student's photo, i.e.
0.1·m metres on the ground (1.2–2.19 km), in 200 × 200 cells of 0.5 mm on the photo (m/2000 metres), centred
at X = 1200 + 76i m and 300 + 100·(i mod 3) m north of the river's centre line, so every patch holds the
floodplain and the slopes above it.  It is photographed bare (as in spring, before the crops come up: the
guide's direct keys need bare ground) in summer moisture, colour-infrared (NIR, red, green as R, G, B).
The pit is at the patch's cell (50 + i mod 100, 150 − i mod 100) (row, column from the south-west corner).
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import soilmap, spectral
from .. import guide
from ..labs.ch13 import Patch, patch_of
from .base import Answer, Hidden, Method, Task, submitted_number

__all__ = ["MAP_FACTORS", "SEED", "map_scales", "majority_agreement_pct", "ScaleClasses", "PitReflectance",
           "ContourInterpretation", "TASKS"]

#: task 13.1: the maps' scale denominators as multiples of the photo's m
MAP_FACTORS = (2, 10, 40)
#: the k-means seed of task 13.3
SEED = 0


def map_scales(v) -> tuple:
    """Task 13.1's three scale denominators for variant ``v``: 2m, 10m, 40m."""
    return tuple(int(round(f * float(v.m))) for f in MAP_FACTORS)


def majority_agreement_pct(labels, truth) -> float:
    """Label every area with the soil most of its cells have; the share of cells whose label is right, %."""
    t = soilmap.contingency(labels, np.asarray(truth, np.int64))
    return 100.0 * float(t.max(axis=1).sum()) / float(t.sum())


def _pit_keywords(p: Patch) -> dict:
    return {k: p.pit_soil[k] for k in ("moisture_pct", "humus_pct", "particle_mm", "parent")}


# --------------------------------------------------------------------------- the tasks
@dataclass(frozen=True)
class ScaleClasses(Task):
    """Task 13.1: the class of a soil map at 1:2m, 1:10m and 1:40m (guide §14)."""

    id = "task-13-1"
    title = "Which class of soil map?"
    points = 2
    cross_variant = False  # five options: another variant's answer is no sign of a mix-up
    methods = (Method("the denominators 2m, 10m, 40m against guide §14's ranges, gaps included", "guide §14"),)
    spec = tuple(
        Answer(f"class_{f}m", f"class of a soil map at 1 : {f}·m", kind="choice", options=guide.ch13.CLASS_NAMES,
               hint="compare the denominator with the ranges of guide §14 — and mind the gaps between them.")
        for f in MAP_FACTORS
    )

    def inputs(self, v) -> pd.DataFrame:
        return pd.DataFrame({"map": [f"1 : {f}·m" for f in MAP_FACTORS],
                             "scale denominator": list(map_scales(v))}).set_index("map")

    def answers(self, v) -> dict:
        return {f"class_{f}m": guide.ch13.soil_map_scale_class(d) for f, d in zip(MAP_FACTORS, map_scales(v))}

    def hidden(self, v, got) -> list:
        # a smaller map is never of a larger class: the named classes of the three answers do not go back
        # ("between classes" names no class and is skipped; an answer that is no option fails)
        rank = {"detailed": 0, "large-scale": 1, "medium-scale": 2, "small-scale": 3, guide.ch13.BETWEEN: None}
        answers = [got.get(f"class_{f}m") for f in MAP_FACTORS]
        if not all(isinstance(a, str) and a in rank for a in answers):
            ok = None
        else:
            named = [rank[a] for a in answers if rank[a] is not None]
            ok = bool(all(x <= y for x, y in zip(named, named[1:])))
        return [Hidden("the named classes get smaller with the scale", ok, True, kind="bool")]


@dataclass(frozen=True)
class PitReflectance(Task):
    """Task 13.2: the pit soil's red reflectance, its brightness at 1.45 µm against the dried soil, the band
    moisture darkens most."""

    id = "task-13-2"
    title = "Reading the pit's reflectance curve"
    points = 2
    cross_variant = False
    tools = ("aerophoto.spectral.soil_reflectance", "aerophoto.spectral.soil_bands", "aerophoto.spectral.BAND_NAMES")
    methods = (Method("spectral.soil_bands and spectral.soil_reflectance with the pit's keywords, and with θ = 0",
                      "guide §14; chapter 13, task 13.2"),)
    spec = (
        Answer("rho_red", "the pit soil's reflectance in the red band (0.63–0.69 µm), 0…1", tol_abs=0.002, printed=0.001),
        Answer("wet_dry_145_pct", "its reflectance at 1.45 µm as a share of the same soil dried (θ = 0), %",
               unit="%", tol_abs=0.3, printed=0.1),
        Answer("band", "the band that keeps the smallest share of its dry brightness", kind="choice",
               options=spectral.BAND_NAMES,
               hint="compare wet/dry band by band: where does water itself absorb most?"),
    )

    def inputs(self, v) -> dict:
        return dict(patch_of(v).pit_soil)

    def answers(self, v) -> dict:
        kw = _pit_keywords(patch_of(v))
        wet = spectral.soil_bands(**kw)
        dry = spectral.soil_bands(**{**kw, "moisture_pct": 0.0})
        r145 = spectral.soil_reflectance([1.45], **kw)[0] / spectral.soil_reflectance(
            [1.45], **{**kw, "moisture_pct": 0.0})[0]
        return {"rho_red": float(wet[spectral.BAND_NAMES.index("red")]), "wet_dry_145_pct": 100.0 * float(r145),
                "band": spectral.BAND_NAMES[int(np.argmin(wet / dry))]}

    def slips(self, v) -> dict:
        kw = _pit_keywords(patch_of(v))
        dry = spectral.soil_bands(**{**kw, "moisture_pct": 0.0})
        r145_wet = spectral.soil_reflectance([1.45], **kw)[0]
        r145_dry = spectral.soil_reflectance([1.45], **{**kw, "moisture_pct": 0.0})[0]
        return {"rho_red": {"that is the dried soil: keep the pit's own moisture θ":
                            float(dry[spectral.BAND_NAMES.index("red")])},
                "wet_dry_145_pct": {"that is the darkening; the task asks for the share that is left":
                                    100.0 * (1.0 - r145_wet / r145_dry)}}

    def hidden(self, v, got) -> list:
        # wet soil is darker: the share left at 1.45 µm is below 100 %
        x = submitted_number(got.get("wet_dry_145_pct"))
        return [Hidden("wet is darker than dry at 1.45 µm", None if x is None else bool(0 < x < 100), True,
                       kind="bool")]


@dataclass(frozen=True)
class ContourInterpretation(Task):
    """Task 13.3: k-means areas of the patch's composite against the survey's soil map."""

    id = "task-13-3"
    title = "Contour interpretation of your patch"
    points = 3
    cross_variant = False  # each patch is its own
    tools = ("aerophoto.soilmap.segment_tones", "aerophoto.soilmap.contingency")
    methods = (Method("k from the survey map, soilmap.segment_tones(composite, k, seed=0), each area labelled with its "
                      "majority soil in soilmap.contingency", "guide §14; chapter 13, task 13.3"),)
    spec = (
        Answer("k", "number of soil classes on the survey map of your patch", kind="count", rounding="exact",
               hint="count the classes present on the map: np.unique(patch.soil_map); a class of a few cells counts"),
        Answer("agreement_pct", "share of cells whose area's majority soil is their own soil, %", unit="%",
               tol_abs=0.05, printed=0.01),
    )

    def inputs(self, v) -> Patch:
        return patch_of(v)

    def answers(self, v) -> dict:
        p = patch_of(v)
        k = int(len(np.unique(p.soil_map)))
        return {"k": k, "agreement_pct": majority_agreement_pct(_areas(v), p.soil_map)}

    def slips(self, v) -> dict:
        p = patch_of(v)
        t = soilmap.contingency(_areas(v), p.soil_map.astype(np.int64))
        diag = 100.0 * float(np.trace(t[:, :min(t.shape)])) / float(t.sum())
        return {"k": {"count the classes present on the map (np.unique), not all classes of the legend":
                      len(p.legend())},
                "agreement_pct": {"the area numbers are not soil codes: give each area the soil most of its "
                                  "cells have": diag}}

    def hidden(self, v, got) -> list:
        # labelling by the majority can never do worse than calling everything the commonest soil
        p = patch_of(v)
        floor = 100.0 * float(np.bincount(p.soil_map.ravel()).max()) / p.soil_map.size
        x = submitted_number(got.get("agreement_pct"))
        return [Hidden("agreement at least the commonest soil's share", None if x is None else bool(
            floor - 0.05 <= x <= 100.0), True, kind="bool")]


def _areas(v) -> np.ndarray:
    """The k-means areas of the variant's patch (task 13.3; the one k-means run its answers and slips share)."""
    return _areas_of(int(v.i))


@functools.lru_cache(maxsize=2)
def _areas_of(i: int) -> np.ndarray:
    from ..variants import variant_for_index

    p = patch_of(variant_for_index(i))
    labels = soilmap.segment_tones(p.composite, int(len(np.unique(p.soil_map))), seed=SEED)
    labels.setflags(write=False)
    return labels


TASKS = (ScaleClasses(), PitReflectance(), ContourInterpretation())
