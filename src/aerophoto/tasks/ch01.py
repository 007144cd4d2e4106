"""Graded tasks of chapter 01 (guide §2): the survey plan of the student's variant.

The variant itself is the input (``inputs(v)`` is None); the reference
answers are :func:`aerophoto.flight.plan` (v), with the guide's relief
allowance 40·h/H for both overlaps (guide §2, step 3 — the exact side-overlap
allowance of :mod:`aerophoto.guide.ch01` is shown in the chapter, not graded).
:func:`typical_slips` gives the values that typical mistakes produce — among
them the guide's own misprinted factors of step 5 (7.2 and 12.6 cm: the
relief allowance left out).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

from .. import flight
from .base import Answer, Hidden, Method, Task, submitted_number
from .rounding import consistency, numbers

__all__ = ["typical_slips", "HeightOverlapBases", "StripsAndPhotos", "RouteAndTiming", "TASKS"]


def typical_slips(p: flight.FlightPlan) -> dict:
    """Values that typical mistakes give for plan ``p``: quantity → {hint: wrong value}.

    Factor-of-1000/3600/3.6 unit slips are recognised by the checks
    themselves.  The guide's own misprinted factors (7.2 and 12.6 cm, step 5)
    are the working-area sides for the normative overlaps, i.e. the relief
    allowance left out, so the "no relief allowance" entries also catch the
    guide's slip.
    """
    flat = p.replace(Zmax_m=p.Zmin_m)   # the same plan without the relief allowance
    no_relief = "that is what you get without the relief allowance 40·h/H (as in the guide's misprinted 7.2 and 12.6 cm)"
    frame_km = p.footprint_side_km
    slips = {
        "H_m": {"that is f·M — use the photo scale 1:m, not the photoplan scale 1:M": p.f_mm / 1000 * p.M},
        "Px_percent": {"that is the normative px — add the relief allowance 40·h/H": p.px_percent,
                       "the relief allowance uses h = Zmax − Zmin, not Zmax": p.px_percent + 40 * p.Zmax_m / p.H_m},
        "Py_percent": {"that is the normative py — add the relief allowance 40·h/H": p.py_percent,
                       "the relief allowance uses h = Zmax − Zmin, not Zmax": p.py_percent + 40 * p.Zmax_m / p.H_m},
        "Bx_km": {no_relief: flat.Bx_km,
                  "that is the whole frame on the ground (l·m), not the working area bx·m": frame_km,
                  "that is the overlap itself (l·Px/100·m) — the base is the part that does not overlap":
                      p.l_cm * p.Px_percent / 100 * p.m / 1e5,
                  "that is By, the strip spacing — Bx uses the forward overlap Px": p.By_km},
        "By_km": {no_relief: flat.By_km,
                  "that is the whole frame on the ground (l·m), not the working area by·m": frame_km,
                  "that is the overlap itself (l·Py/100·m) — the spacing is the part that does not overlap":
                      p.l_cm * p.Py_percent / 100 * p.m / 1e5,
                  "that is Bx, the photo base — By uses the side overlap Py": p.Bx_km},
        "K": {f"{no_relief}; like the guide's '30/1.51 + 1'": flat.K,
              "rounded to the nearest whole number — the guide rounds K up": round(p.K_ratio + 1),
              "that uses Lx/Bx — strips are counted across the area: Ly/By": p.n},
        "n": {no_relief: flat.n,
              "rounded to the nearest whole number — the guide rounds n up": round(p.n_ratio + 1),
              "that uses Ly/By — photos are counted along a strip: Lx/Bx": p.K},
        "N": {"K and n without the '+ 1'": math.ceil(p.K_ratio) * math.ceil(p.n_ratio),
              "K and n rounded down — the guide rounds both up": (math.floor(p.K_ratio) + 1) * (math.floor(p.n_ratio) + 1),
              "K and n rounded to the nearest — the guide rounds both up": round(p.K_ratio + 1) * round(p.n_ratio + 1),
              no_relief: flat.N},
        "LS_km": {"without the factor 1.2 for turns and approaches": p.LS_km / flight.ROUTE_FACTOR,
                  "divided by Bx — the route length is S/By (strips × strip length)":
                      flight.ROUTE_FACTOR * p.S_km2 / p.Bx_km,
                  no_relief: flat.LS_km},
        "TS_h": {"without the factor 1.2 in LS": p.TS_h / flight.ROUTE_FACTOR, no_relief: flat.TS_h},
        "tau_s": {f"{no_relief}; like the guide's '0.86·3600/200'": flat.tau_s,
                  "that uses By — the interval is the photo base Bx over W": p.By_km / p.W_kmh * 3600,
                  "that is in minutes — τ is asked in seconds": p.tau_s / 60},
        "tmax_s": {"that uses the photo scale m — the blur δ is on the photoplan at 1:M": p.blur_mm / 1000 * p.m / p.W_ms},
    }
    return slips


class _PlanTask(Task):
    """A task whose answers are attributes of the variant's :func:`aerophoto.flight.plan`."""

    def answers(self, v) -> dict:
        p = flight.plan(v)
        return {name: getattr(p, name) for name in self.names}

    def slips(self, v) -> dict:
        s = typical_slips(flight.plan(v))
        return {name: s[name] for name in self.names if name in s}


@dataclass(frozen=True)
class HeightOverlapBases(_PlanTask):
    """Task 01.1: H = f·m, P_x = p_x + 40·h/H, B_x = b_x·m and B_y = b_y·m (guide §2, steps 2–5)."""

    id = "task-01-1"
    title = "Height, overlap and bases"
    points = 4
    spec = (
        Answer("H_m", "flying height H = f·m, m", unit="m", printed=1),
        Answer("Px_percent", "forward overlap with the relief allowance, %", unit="%", tol_abs=0.02, printed=0.01),
        Answer("Bx_km", "photo base on the ground, km", unit="km", printed=0.001),
        Answer("By_km", "distance between strips, km", unit="km", printed=0.001),
    )

    methods = (Method("H = f·m, P_x = p_x + 40·h/H, B_x = l·(100 − P_x)/100·m, B_y likewise",
                      "guide §2 steps 2–5 at full precision (b_x, b_y not rounded to 0.1 cm, as the task says)"),)

    def hidden(self, v, got) -> list:
        # the base must follow from the student's own overlap: Bx = l·(100 − Px)/100 · m
        return [consistency("Bx_km from Px_percent", got.get("Bx_km"), 0.001,
                            lambda Px: v.frame_mm / 10 * (100 - Px) / 100 * v.m / 1e5,
                            [(numbers(got.get("Px_percent")), 0.01)])]


@dataclass(frozen=True)
class StripsAndPhotos(_PlanTask):
    """Task 01.2: K = ⌈L_y/B_y + 1⌉, n = ⌈L_x/B_x + 1⌉ and N = n·K (guide §2, steps 6–8)."""

    id = "task-01-2"
    title = "Strips and photos"
    points = 3
    spec = (
        Answer("K", "strips (whole number)", kind="count", rounding="up"),
        Answer("n", "photos per strip (whole number)", kind="count", rounding="up"),
        Answer("N", "photos in all (whole number)", kind="count", rounding="exact"),
    )

    methods = (Method("K = ⌈L_y/B_y + 1⌉, n = ⌈L_x/B_x + 1⌉, N = n·K", "guide §2 steps 6–8, from full-precision bases"),)

    def reals(self, v) -> dict:
        p = flight.plan(v)
        return {"K": p.K_ratio + 1, "n": p.n_ratio + 1}

    def hidden(self, v, got) -> list:
        # N is the product of the student's own counts
        n, K = submitted_number(got.get("n")), submitted_number(got.get("K"))
        nK = None if n is None or K is None else n * K
        return [Hidden("N = n·K", got.get("N") if nK is not None else None, nK, kind="count")]


@dataclass(frozen=True)
class RouteAndTiming(_PlanTask):
    """Task 01.3: L_S = 1.2·S/B_y, T_S = L_S/W, t_max = δ·M/W and τ = B_x/W (guide §2, steps 9–12)."""

    id = "task-01-3"
    title = "Route, time, exposure and interval"
    points = 4
    spec = (
        Answer("LS_km", "route length, km", unit="km", printed=1),
        Answer("TS_h", "flight time, h", unit="h", printed=0.01),
        Answer("tmax_s", "longest admissible exposure, s", unit="s", printed=1e-05),
        Answer("tau_s", "interval between exposures, s", unit="s", printed=0.01),
    )

    methods = (Method("L_S = 1.2·S/B_y, T_S = L_S/W, t_max = δ·M/W, τ = B_x/W", "guide §2 steps 9–12"),)

    def hidden(self, v, got) -> list:
        # the flight time follows from the student's own route length
        return [consistency("TS_h from LS_km", got.get("TS_h"), 0.01, lambda LS: LS / v.W_kmh,
                            [(numbers(got.get("LS_km")), 1)])]


TASKS = (HeightOverlapBases(), StripsAndPhotos(), RouteAndTiming())
