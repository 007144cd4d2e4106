"""Graded tasks of chapter 00 (guide §1, §5): the elements of a tilted photo for the student's variant."""

from __future__ import annotations

import math
from dataclasses import dataclass

from .. import geometry as g
from .base import Answer, Hidden, Task

__all__ = ["ElementsOfTiltedPhoto", "TASKS"]


@dataclass(frozen=True)
class ElementsOfTiltedPhoto(Task):
    """Task 00.1: the flying height H = f·m and the nadir and isocentre offsets on = f·tg α, oc = −f·tg(α/2)."""

    id = "task-00-1"
    title = "Flying height and the points n and c of your photo"
    points = 3
    spec = (
        Answer("H_m", "flying height, m", unit="m"),
        Answer("on_mm", "o to n, mm", unit="mm", tol_abs=0.05),
        Answer("oc_mm", "o to c with the guide's sign, mm", unit="mm", tol_abs=0.05),
    )

    def answers(self, v) -> dict:
        return {
            "H_m": g.flying_height_m(v.f_mm, v.m),
            "on_mm": v.f_mm * math.tan(math.radians(v.alpha_deg)),
            "oc_mm": -v.f_mm * math.tan(math.radians(v.alpha_deg) / 2.0),
        }

    def slips(self, v) -> dict:
        return {
            "H_m": {"that is f·M — use the photo scale 1:m, not the photoplan scale 1:M": v.f_mm / 1000.0 * v.M},
            "on_mm": {"that is f·tg(α/2), the isocentre — the nadir point uses the whole α":
                      v.f_mm * math.tan(math.radians(v.alpha_deg) / 2.0)},
            "oc_mm": {"that is on = f·tg α, the nadir point — the isocentre uses α/2":
                      -v.f_mm * math.tan(math.radians(v.alpha_deg))},
        }

    def hidden(self, v, got) -> list:
        # the two elements must agree with each other: on = 2·f·tg(α/2) / (1 − tg²(α/2)), with tg(α/2) = −oc/f
        try:
            t = -float(got["oc_mm"]) / v.f_mm
            on_from_oc = 2.0 * v.f_mm * t / (1.0 - t * t)
        except (TypeError, ValueError, ZeroDivisionError):
            on_from_oc = None
        return [Hidden("on_mm vs oc_mm", got.get("on_mm") if on_from_oc is not None else None, on_from_oc,
                       tol_abs=0.1)]


TASKS = (ElementsOfTiltedPhoto(),)
