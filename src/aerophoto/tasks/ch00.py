"""Graded tasks of chapter 00 (guide §1, §5): the elements of a tilted photo for the student's variant.

Also the book's variant policy (:func:`scheme_table`): what the guide's scheme gives for i = 00…99 and how
those cameras, aircraft and flying heights compare with real practice.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import pandas as pd

from .. import geometry as g
from .. import variants
from .base import Answer, Method, Task
from .rounding import consistency, numbers
from .._digits import whole

__all__ = ["ElementsOfTiltedPhoto", "TASKS", "SURVEY_LENSES_MM", "RECONNAISSANCE_MAX_MM", "SURVEY_SPEED_KMH",
           "SURVEY_CEILING_KM", "scheme_table"]


@dataclass(frozen=True)
class ElementsOfTiltedPhoto(Task):
    """Task 00.1: the flying height H = f·m and the nadir and isocentre offsets on = f·tg α, oc = −f·tg(α/2)."""

    id = "task-00-1"
    title = "Flying height and the points n and c of your photo"
    points = 3
    spec = (
        Answer("H_m", "flying height, m", unit="m", printed=1),
        Answer("on_mm", "o to n, mm", unit="mm", tol_abs=0.05, printed=0.01),
        Answer("oc_mm", "o to c with the guide's sign, mm", unit="mm", tol_abs=0.05, printed=0.01),
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
        def on_of(oc):
            t = -oc / v.f_mm
            return 2.0 * v.f_mm * t / (1.0 - t * t)

        return [consistency("on_mm from your oc_mm", got.get("on_mm"), 0.01, on_of,
                            [(numbers(got.get("oc_mm")), 0.01)])]

    methods = (Method("H = f·m, on = f·tg α, oc = −f·tg(α/2)", "guide §1 (H) and §5 (the points n and c)"),)


TASKS = (ElementsOfTiltedPhoto(),)


# =========================================================================== the variant policy (chapter 00)
SURVEY_LENSES_MM = (70, 88, 100, 140, 153, 200, 210, 305)
"""Focal lengths of real mapping cameras, mm: the 18×18 cm topographic cameras the guide's §3 names (100, 140,
200 mm; 70 mm wide-angle ones too) and the 23×23 cm survey cameras' lens cones (88 super-wide, 153 wide,
210 normal, 305 mm narrow angle)."""
RECONNAISSANCE_MAX_MM = 610
"""The longest lenses of aerial reconnaissance cameras, about 610 mm (24 in); no mapping camera goes further."""
SURVEY_SPEED_KMH = (180, 550)
"""Speeds survey aircraft fly at, km/h: from the An-2 (≈ 180–200 km/h) through the purpose-built An-30
(≈ 430 km/h) to fast twin turboprops and light jets (≈ 550 km/h)."""
SURVEY_CEILING_KM = 10
"""Survey flights are flown up to about 10 km above the ground; higher only special high-altitude aircraft."""


def _span(lo, hi, fmt="{:g}") -> str:
    return fmt.format(lo) if lo == hi else f"{fmt.format(lo)}–{fmt.format(hi)}"


def _thousands(x) -> str:
    return whole(x)


def _lens_note(f_lo: float, f_hi: float) -> str:
    real = [f for f in SURVEY_LENSES_MM if f_lo <= f <= f_hi]
    longest = max(SURVEY_LENSES_MM)
    if f_hi <= longest:
        return "real mapping lenses" + (f" ({', '.join(f'{f:g}' for f in real)} mm)" if real else "")
    if f_lo <= longest:
        return f"mapping lenses up to {longest} mm; longer only on reconnaissance cameras"
    if f_hi <= RECONNAISSANCE_MAX_MM:
        return f"no mapping lens: long-focus reconnaissance lenses (up to ≈ {RECONNAISSANCE_MAX_MM} mm)"
    if f_lo <= RECONNAISSANCE_MAX_MM:
        return f"reconnaissance lenses up to ≈ {RECONNAISSANCE_MAX_MM} mm, then beyond real practice"
    return "beyond real practice: no lens this long for an 18×18 cm frame"


def _speed_note(w_lo: float, w_hi: float) -> str:
    lo, hi = SURVEY_SPEED_KMH
    if w_hi <= hi:
        return "survey aircraft"
    if w_lo <= hi:
        return f"survey aircraft up to ≈ {hi} km/h, then only jets"
    if w_hi < 1000:
        return "beyond survey aircraft: jet airliners' speeds"
    return "beyond real practice: close to the speed of sound (≈ 1 200 km/h)"


def _height_note(h_lo_km: float, h_hi_km: float) -> str:
    if h_hi_km <= SURVEY_CEILING_KM:
        return "flown by survey aircraft"
    if h_lo_km <= SURVEY_CEILING_KM:
        return f"up to ≈ {SURVEY_CEILING_KM} km flown, higher only by special aircraft"
    if h_hi_km <= 21:
        return "only special high-altitude aircraft"
    return "beyond real practice: above any aircraft's ceiling"


def scheme_table(step: int = 10) -> pd.DataFrame:
    """What the guide's scheme (§1) gives for i = 00…99, in groups of ``step`` variants, beside real practice.

    One row per group (``"00–09"``, …): the inputs f = 100 + 10i mm, 1/m = 1/(12 000 + 100i),
    W = 200 + 10i km/h, the area L_x × L_y = (25 + i) × (30 + i) km; the flying height H = f·m only as a band of
    whole kilometres whose edges are no variant's H (a variant's exact H is task 00.1's answer); and for the lens, the aircraft and the height
    what real practice has (:data:`SURVEY_LENSES_MM`, :data:`RECONNAISSANCE_MAX_MM`, :data:`SURVEY_SPEED_KMH`,
    :data:`SURVEY_CEILING_KM`).  The book computes every variant with the guide's numbers as they are.
    """
    from .._validate import check_int_range

    step = check_int_range("step", step, 1, 100)
    every_H = [variants.variant_for_index(i).H_m / 1000.0 for i in range(100)]
    rows = []
    for start in range(0, 100, step):
        vs = [variants.variant_for_index(i) for i in range(start, min(start + step, 100))]
        a, b = vs[0], vs[-1]
        H = [v.H_m / 1000.0 for v in vs]
        h_lo, h_hi = math.floor(min(H)), math.ceil(max(H))
        # a band's edge never lands on any variant's H (H = 6 000 m for i = 30): it would show that answer
        while any(abs(h_lo - x) <= 0.005 * x for x in every_H):
            h_lo -= 1
        while any(abs(h_hi - x) <= 0.005 * x for x in every_H):
            h_hi += 1
        rows.append({
            "i": _span(f"{a.i:02d}", f"{b.i:02d}", "{}"),
            "f, mm": _span(a.f_mm, b.f_mm),
            "photo scale": f"1:{_thousands(a.m)}" + ("" if a.m == b.m else f"–{_thousands(b.m)}"),
            "W, km/h": _span(a.W_kmh, b.W_kmh),
            "Lx × Ly, km": f"{_span(a.Lx_km, b.Lx_km)} × {_span(a.Ly_km, b.Ly_km)}",
            "H = f·m, km": f"{h_lo}–{h_hi}",
            "the lens": _lens_note(a.f_mm, b.f_mm),
            "the aircraft": _speed_note(a.W_kmh, b.W_kmh),
            "the height": _height_note(min(H), max(H)),
        })
    return pd.DataFrame(rows).set_index("i")
