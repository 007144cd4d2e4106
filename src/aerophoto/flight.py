"""Planning an aerial survey (guide §2, "Расчёт параметров аэросъёмки").

Given the camera, the photo scale, the normative overlaps, the survey area, the
terrain and the aircraft, the guide computes twelve things in this order
(guide §2, steps 1–12; units as in the guide):

====  ==================================  ==================================  ======
step  quantity                            formula                             unit
====  ==================================  ==================================  ======
1     survey area S                       S = Lx·Ly                           km²
2     flying height H                     H = f·m                             m
3     relief h, overlaps Px, Py           h = Zmax − Zmin, P = p + 40·h/H     m, %
4     working-area sides bx, by           b = l·(100 − P)/100, l = 18 cm      cm
5     photo base Bx, strip spacing By     B = b·m                             km
6     number of strips K                  K = ⌈Ly/By + 1⌉                     —
7     photos per strip n                  n = ⌈Lx/Bx + 1⌉                     —
8     photos in all N                     N = n·K                             —
9     route length LS                     LS = 1.2·S/By                       km
10    flight time TS                      TS = LS/W                           h
11    longest exposure tmax               tmax = δ·M/W, δ = 0.1 mm, W in m/s  s
12    exposure interval τ                 τ = Bx/W                            s
====  ==================================  ==================================  ======

:func:`plan` does the whole calculation and returns a :class:`FlightPlan`
(every quantity, units in the names, and :meth:`FlightPlan.table` laid out like
the guide's numbered steps).  :func:`layout` places the strips and photo
centres over the area for a plan view, with each photo's ground footprint
from :func:`aerophoto.geometry.footprint`.

Rounding (guide §2, steps 6–7)
------------------------------
The guide rounds K and n *up* to whole numbers ("округлить до целого числа в
большую сторону").  Read literally, K = ⌈Ly/By + 1⌉ = ⌈Ly/By⌉ + 1: the ratio
Ly/By is the number of *gaps* between strips needed to span the area, and the
"+ 1" is the fence post — K strips have K − 1 gaps.  So when the ratio is a
whole number exactly (say Ly/By = 20) the area is spanned by exactly 20 gaps
and K = 21: the "+ 1" only, no further rounding.  Ratios within 1e−9
(relative) of a whole number count as that whole number, so that binary
floating point (18/0.9 = 20.000000000000004 in some orders of operation) does
not add a strip.  See :func:`count_up`.

Relief allowance (guide §2, step 3)
-----------------------------------
The guide raises both overlaps by 40·h/H.  The allowance that keeps an
overlap p on the highest ground is (100 − p)·h/H (:func:`exact_allowance_percent`,
:func:`overlaps_at`): the guide's 40 is exact for p_x = 60 %, while for
p_y = 30 % it would be 70.  :func:`plan` follows the guide (the graded tasks
do too); :func:`side_spacing` gives P_y, b_y, B_y and K with either allowance.

The guide's worked example (variant i = 0) is :func:`guide_example`; its
printed lines and their audit are :mod:`aerophoto.guide.ch01`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np
import pandas as pd

from . import geometry as g
from ._validate import check_percent, check_positive, check_range, check_type
from .variants import as_variant

__all__ = [
    "FlightPlan",
    "FlightLayout",
    "plan",
    "count_up",
    "layout",
    "overlaps_at",
    "guide_example",
    "exact_allowance_percent",
    "side_spacing",
    "ROUTE_FACTOR",
    "RELIEF_FACTOR",
    "BLUR_MM",
    "GUIDE_DECIMALS",
    "TABLE_ATTRS",
]

#: the guide's allowance of 20 % for turns and approaches in LS = 1.2·S/By (§2, step 9)
ROUTE_FACTOR = 1.2
#: the coefficient 40 in the relief allowance P = p + 40·h/H (§2, step 3), in %
RELIEF_FACTOR = 40.0
#: the guide's admissible image blur on the photoplan, δ ≤ 0.1 mm (§2, step 11)
BLUR_MM = 0.1

#: decimals the guide prints for each quantity in its worked example (§2)
GUIDE_DECIMALS = {
    "S_km2": 0, "H_m": 0, "h_m": 0, "Px_percent": 1, "Py_percent": 1, "bx_cm": 1, "by_cm": 1,
    "Bx_km": 2, "By_km": 2, "K": 0, "n": 0, "N": 0, "LS_km": 0, "TS_h": 1, "tmax_s": 3, "tau_s": 1,
}

_INPUTS = ("f_mm", "m", "px_percent", "py_percent", "Lx_km", "Ly_km", "Zmax_m", "Zmin_m", "W_kmh", "M",
           "frame_mm", "blur_mm")

#: the guide's worked example (variant i = 0), the inputs printed in §1–§2
_GUIDE_INPUTS = dict(f_mm=100.0, m=12000.0, px_percent=60.0, py_percent=30.0, Lx_km=25.0, Ly_km=30.0,
                     Zmax_m=200.0, Zmin_m=170.0, W_kmh=200.0, M=10000.0, frame_mm=180.0, blur_mm=BLUR_MM)


def count_up(ratio: float) -> int:
    """The guide's count ⌈ratio + 1⌉ for strips K (ratio = Ly/By) and photos n (ratio = Lx/Bx).

    A ratio that is a whole number (within 1e−9 relative, to absorb floating
    point noise) gets the "+ 1" only: ``count_up(20.0) == 21``, while
    ``count_up(20.13) == 22`` (guide §2, steps 6–7; see the module notes).
    """
    r = check_range("ratio", ratio, 0.0, math.inf)
    nearest = round(r)
    if abs(r - nearest) <= 1e-9 * max(1.0, r):
        r = float(nearest)
    return int(math.ceil(r)) + 1


@dataclass(frozen=True)
class FlightPlan:
    """Every quantity of the guide's survey calculation (§2), units in the names.

    Inputs (guide §1)
        f_mm : focal length f, mm · m : photo-scale denominator (1/m) ·
        px_percent, py_percent : normative overlaps p_x, p_y, % ·
        Lx_km, Ly_km : area sides along the parallel (X, the flight direction)
        and the meridian (Y), km · Zmax_m, Zmin_m : highest and lowest ground, m ·
        W_kmh : aircraft ground speed W, km/h · M : photoplan-scale denominator
        (1/M) · frame_mm : frame side l, mm (18 cm = 180 mm) · blur_mm :
        admissible blur δ on the photoplan, mm.

    Results (guide §2, steps 1–12)
        S_km2 (1), H_m (2), h_m, Px_percent, Py_percent (3), bx_cm, by_cm (4),
        Bx_km, By_km (5), K_ratio = Ly/By and K (6), n_ratio = Lx/Bx and n (7),
        N (8), LS_km (9), TS_h (10), W_ms and tmax_s (11), tau_s (12).
    """

    f_mm: float
    m: float
    px_percent: float
    py_percent: float
    Lx_km: float
    Ly_km: float
    Zmax_m: float
    Zmin_m: float
    W_kmh: float
    M: float
    frame_mm: float
    blur_mm: float
    # results
    S_km2: float
    H_m: float
    h_m: float
    Px_percent: float
    Py_percent: float
    bx_cm: float
    by_cm: float
    Bx_km: float
    By_km: float
    K_ratio: float
    K: int
    n_ratio: float
    n: int
    N: int
    LS_km: float
    TS_h: float
    W_ms: float
    tmax_s: float
    tau_s: float

    # ------------------------------------------------------------ derived views
    @property
    def inputs(self) -> dict:
        """The inputs as keyword arguments of :func:`plan`."""
        return {k: getattr(self, k) for k in _INPUTS}

    @property
    def l_cm(self) -> float:
        """Frame side l in cm (the guide's l = 18 cm)."""
        return self.frame_mm / 10.0

    @property
    def Bx_m(self) -> float:
        """Photo base on the ground B_x in metres."""
        return self.Bx_km * 1000.0

    @property
    def By_m(self) -> float:
        """Strip spacing B_y in metres."""
        return self.By_km * 1000.0

    @property
    def footprint_side_km(self) -> float:
        """Ground side of one vertical photo over flat ground, l·m, km."""
        return self.frame_mm / 1e6 * self.m

    @property
    def relief_allowance_percent(self) -> float:
        """The relief allowance 40·h/H added to both overlaps, %."""
        return self.Px_percent - self.px_percent

    def replace(self, **changes) -> "FlightPlan":
        """The plan recomputed with some inputs changed (e.g. ``p.replace(m=15000)``)."""
        return plan(**{**self.inputs, **changes})

    def table(self, *, rounded: bool = False) -> pd.DataFrame:
        """All quantities as the guide's numbered steps (§2).

        Columns: quantity, formula, value, unit; the index is the step number.
        ``rounded=True`` rounds each value to the decimals the guide prints
        (:data:`GUIDE_DECIMALS`).
        """
        rows = _TABLE_ROWS
        out = []
        for step, attr, quantity, formula, unit in rows:
            value = getattr(self, attr)
            if rounded and not isinstance(value, int):
                value = round(float(value), GUIDE_DECIMALS[attr])
            out.append((step, quantity, formula, value, unit))
        df = pd.DataFrame(out, columns=["step", "quantity", "formula", "value", "unit"], dtype=object)
        return df.set_index("step")

    def summary(self) -> dict:
        """The results as a plain dict (name → value), in the guide's order."""
        skip = set(_INPUTS)
        return {f.name: getattr(self, f.name) for f in fields(self) if f.name not in skip}


#: the rows of :meth:`FlightPlan.table`: (step, attribute, quantity, formula, unit)
_TABLE_ROWS = (
    ("1", "S_km2", "Survey area S (площадь участка)", "S = Lx·Ly", "km²"),
    ("2", "H_m", "Flying height H (высота фотографирования)", "H = f·m", "m"),
    ("3", "h_m", "Relief h (разность высот)", "h = Zmax − Zmin", "m"),
    ("3", "Px_percent", "Forward overlap Px (продольное перекрытие)", "Px = px + 40·h/H", "%"),
    ("3", "Py_percent", "Side overlap Py (поперечное перекрытие)", "Py = py + 40·h/H", "%"),
    ("4", "bx_cm", "Working area along the strip bx (рабочая площадь)", "bx = l·(100 − Px)/100", "cm"),
    ("4", "by_cm", "Working area across the strip by", "by = l·(100 − Py)/100", "cm"),
    ("5", "Bx_km", "Photo base Bx (базис фотографирования)", "Bx = bx·m", "km"),
    ("5", "By_km", "Strip spacing By (расстояние между маршрутами)", "By = by·m", "km"),
    ("6", "K", "Strips K (количество маршрутов)", "K = ⌈Ly/By + 1⌉", "—"),
    ("7", "n", "Photos per strip n", "n = ⌈Lx/Bx + 1⌉", "—"),
    ("8", "N", "Photos in all N", "N = n·K", "—"),
    ("9", "LS_km", "Route length LS (длина пути самолёта)", "LS = 1.2·S/By", "km"),
    ("10", "TS_h", "Flight time TS (расчётное время)", "TS = LS/W", "h"),
    ("11", "tmax_s", "Longest exposure tmax (максимальная выдержка)", "tmax = δ·M/W  (W in m/s)", "s"),
    ("12", "tau_s", "Exposure interval τ (интервал фотографирования)", "τ = Bx/W", "s"),
)
TABLE_ATTRS = tuple(r[1] for r in _TABLE_ROWS)


def _checked(name, value, lo=-math.inf, hi=math.inf, *, lo_open=False, hi_open=False, unit="", why=""):
    try:
        return check_range(name, value, lo, hi, lo_open=lo_open, hi_open=hi_open, unit=unit)
    except ValueError as exc:
        if why:
            raise ValueError(f"{exc} — {why}") from None
        raise


def plan(variant=None, *, f_mm=None, m=None, px_percent=None, py_percent=None, Lx_km=None, Ly_km=None,
         Zmax_m=None, Zmin_m=None, W_kmh=None, M=None, frame_mm=None, blur_mm=None) -> FlightPlan:
    """The guide's survey calculation (§2, steps 1–12) for a variant or explicit inputs.

    Parameters
    ----------
    variant : aerophoto.variants.Variant, optional
        The student's variant (guide §1).  Keyword arguments given explicitly
        override its values; without a variant, missing inputs take the
        guide's worked example (variant 00).
    f_mm : focal length f, mm (0 < f ≤ 2000)
    m : photo-scale denominator m (scale 1:m), > 0
    px_percent, py_percent : normative overlaps p_x, p_y in %, 0 ≤ p < 100
    Lx_km, Ly_km : area sides L_x (along the flight lines) and L_y, km, > 0
    Zmax_m, Zmin_m : highest and lowest ground, m; Zmin ≤ Zmax, and the relief
        h = Zmax − Zmin must be below the flying height H
    W_kmh : aircraft ground speed W, km/h, > 0
    M : photoplan-scale denominator M (scale 1:M), > 0
    frame_mm : frame side l, mm (the guide's 18 cm = 180 mm)
    blur_mm : admissible image blur δ on the photoplan, mm (guide: 0.1 mm)

    Returns
    -------
    FlightPlan
        All quantities with units in their names.  K and n are rounded up
        (:func:`count_up`); everything else is kept at full precision.

    Raises
    ------
    ValueError
        Naming the parameter, its value and the valid range — also when the
        overlaps with the relief allowance, Px or Py, reach 100 %.
    """
    given = dict(f_mm=f_mm, m=m, px_percent=px_percent, py_percent=py_percent, Lx_km=Lx_km, Ly_km=Ly_km,
                 Zmax_m=Zmax_m, Zmin_m=Zmin_m, W_kmh=W_kmh, M=M, frame_mm=frame_mm, blur_mm=blur_mm)
    variant = as_variant(variant, "variant")
    values = {}
    for name in _INPUTS:
        if given[name] is not None:
            values[name] = given[name]
        elif variant is not None and hasattr(variant, name):
            values[name] = getattr(variant, name)
        else:
            values[name] = _GUIDE_INPUTS[name]

    f = check_positive("f_mm", values["f_mm"], unit="mm", hi=g.MAX_F_MM)
    m_ = check_positive("m", values["m"])
    px = check_percent("px_percent", values["px_percent"])
    py = check_percent("py_percent", values["py_percent"])
    Lx = check_positive("Lx_km", values["Lx_km"], unit="km")
    Ly = check_positive("Ly_km", values["Ly_km"], unit="km")
    zmax = _checked("Zmax_m", values["Zmax_m"], -1e4, 1e4, unit="m")
    zmin = _checked("Zmin_m", values["Zmin_m"], -1e4, zmax, unit="m",
                    why=f"the lowest ground cannot lie above the highest (Zmax_m = {zmax:g})")
    W = check_positive("W_kmh", values["W_kmh"], unit="km/h")
    M_ = check_positive("M", values["M"])
    frame = check_positive("frame_mm", values["frame_mm"], unit="mm", hi=g.MAX_FRAME_MM)
    blur = check_positive("blur_mm", values["blur_mm"], unit="mm")

    S = Lx * Ly                                          # 1
    H = g.flying_height_m(f, m_)                         # 2
    h = zmax - zmin                                      # 3
    _checked("h_m", h, 0.0, H, hi_open=True, unit="m",
             why=f"the relief h = Zmax − Zmin must be below the flying height H = f·m = {H:g} m")
    allowance = RELIEF_FACTOR * h / H
    Px = _checked("Px_percent", px + allowance, 0.0, 100.0, hi_open=True, unit="%",
                  why=f"Px = px + 40·h/H = {px:g} + {allowance:.3g}; lower px_percent or the relief")
    Py = _checked("Py_percent", py + allowance, 0.0, 100.0, hi_open=True, unit="%",
                  why=f"Py = py + 40·h/H = {py:g} + {allowance:.3g}; lower py_percent or the relief")
    l_cm = frame / 10.0
    bx = l_cm * (100.0 - Px) / 100.0                     # 4, cm
    by = l_cm * (100.0 - Py) / 100.0
    Bx = bx * m_ / 1e5                                   # 5, cm on the ground → km
    By = by * m_ / 1e5
    K_ratio = Ly / By                                    # 6
    K = count_up(K_ratio)
    n_ratio = Lx / Bx                                    # 7
    n = count_up(n_ratio)
    N = n * K                                            # 8
    LS = ROUTE_FACTOR * S / By                           # 9
    TS = LS / W                                          # 10
    W_ms = W / 3.6                                       # 11
    tmax = blur / 1000.0 * M_ / W_ms
    tau = Bx / W * 3600.0                                # 12
    return FlightPlan(f, m_, px, py, Lx, Ly, zmax, zmin, W, M_, frame, blur,
                      S, H, h, Px, Py, bx, by, Bx, By, K_ratio, K, n_ratio, n, N, LS, TS, W_ms, tmax, tau)


def guide_example() -> FlightPlan:
    """The guide's worked example (§2, variant i = 0) computed from its printed inputs."""
    return plan(**_GUIDE_INPUTS)


def exact_allowance_percent(p_percent: float, h_m: float, H_m: float) -> float:
    """The relief allowance that keeps an overlap p on the highest ground: (100 − p)·h/H, in %.

    Photos taken at H above the lowest ground overlap by P there and by
    100 − (100 − P)·H/(H − h) on ground h higher (:func:`overlaps_at`); asking
    for p on the highest ground gives P = p + (100 − p)·h/H.  For the forward
    overlap p_x = 60 % the coefficient 100 − p_x is the guide's 40 (§2, step 3);
    for the side overlap p_y = 30 % it is 70, where the guide keeps 40.

    Parameters
    ----------
    p_percent : normative overlap p, %, 0 ≤ p < 100
    h_m : relief h = Zmax − Zmin, m, 0 ≤ h < H
    H_m : flying height H above the lowest ground, m, > 0
    """
    p = check_percent("p_percent", p_percent)
    H = check_positive("H_m", H_m, unit="m")
    h = _checked("h_m", h_m, 0.0, H, hi_open=True, unit="m", why="the relief must be below the flying height")
    return (100.0 - p) * h / H


def side_spacing(p: FlightPlan, *, exact: bool = False) -> dict:
    """The side overlap and what follows from it for plan ``p``, with the guide's or the exact allowance.

    ``exact=False`` repeats the plan's own steps 3–6 (P_y = p_y + 40·h/H, the
    guide); ``exact=True`` uses (100 − p_y)·h/H (:func:`exact_allowance_percent`),
    which keeps p_y on the highest ground.

    Returns
    -------
    dict with ``allowance_percent``, ``Py_percent`` (%), ``by_cm`` (cm on the
    photo), ``By_km`` (km), ``K_ratio`` (L_y/B_y) and ``K`` (strips, rounded up
    with :func:`count_up`).
    """
    check_type("p", p, FlightPlan)
    if exact:
        allowance = exact_allowance_percent(p.py_percent, p.h_m, p.H_m)
    else:
        allowance = RELIEF_FACTOR * p.h_m / p.H_m
    Py = p.py_percent + allowance
    by = p.l_cm * (100.0 - Py) / 100.0
    By = by * p.m / 1e5
    ratio = p.Ly_km / By
    return {"allowance_percent": allowance, "Py_percent": Py, "by_cm": by, "By_km": By, "K_ratio": ratio,
            "K": count_up(ratio)}


# --------------------------------------------------------------------------- layout
@dataclass(frozen=True)
class FlightLayout:
    """Strips and photo centres of a :class:`FlightPlan` over the area, for a plan view.

    The area is the rectangle 0 ≤ X ≤ Lx, 0 ≤ Y ≤ Ly (km), X along the flight
    lines.  The K strips run along X at spacing By and the n photos of each
    strip lie at spacing Bx; both sets are centred on the area, so the first
    and last strip (photo) lie on or just beyond its edges — the "+ 1" of the
    guide's K and n.  Strips are flown back and forth: strip 0 towards +X,
    strip 1 towards −X, and so on.

    Attributes
    ----------
    plan : the FlightPlan
    strip_y_km : (K,) Y of each flight line, km
    photo_x_km : (n,) X of the photo centres along every strip, km
    footprint_km : (4, 2) ground footprint of one vertical photo relative to
        its centre, km (from :func:`aerophoto.geometry.footprint`, flat ground)
    """

    plan: FlightPlan
    strip_y_km: np.ndarray
    photo_x_km: np.ndarray
    footprint_km: np.ndarray

    @property
    def K(self) -> int:
        return len(self.strip_y_km)

    @property
    def n(self) -> int:
        return len(self.photo_x_km)

    def directions(self) -> np.ndarray:
        """(K,) flight direction of each strip along X: +1 or −1 (back and forth)."""
        return np.where(np.arange(self.K) % 2 == 0, 1.0, -1.0)

    def _select(self, strips, photos):
        ks = np.arange(self.K) if strips is None else np.asarray(strips, dtype=int).ravel()
        js = np.arange(self.n) if photos is None else np.asarray(photos, dtype=int).ravel()
        for name, idx, hi in (("strips", ks, self.K), ("photos", js, self.n)):
            if idx.size and (idx.min() < 0 or idx.max() >= hi):
                raise ValueError(f"{name} = {idx.tolist()[:5]}… is outside the valid range 0 ≤ index ≤ {hi - 1}")
        return ks, js

    def centres_km(self, strips=None, photos=None) -> np.ndarray:
        """(k, 2) photo centres X, Y in km of the chosen strips × photos (default: all N)."""
        ks, js = self._select(strips, photos)
        X, Y = np.meshgrid(self.photo_x_km[js], self.strip_y_km[ks])
        return np.column_stack([X.ravel(), Y.ravel()])

    def footprints_km(self, strips=None, photos=None) -> np.ndarray:
        """(k, 4, 2) ground footprints of the chosen photos (vertical photos, flat ground), km."""
        c = self.centres_km(strips, photos)
        return c[:, None, :] + self.footprint_km[None, :, :]

    def working_areas_km(self, strips=None, photos=None) -> np.ndarray:
        """(k, 4, 2) working areas (рабочая площадь) on the ground: Bx × By rectangles, km."""
        c = self.centres_km(strips, photos)
        hx, hy = self.plan.Bx_km / 2.0, self.plan.By_km / 2.0
        box = np.array([[-hx, -hy], [hx, -hy], [hx, hy], [-hx, hy]])
        return c[:, None, :] + box[None, :, :]

    def route_km(self, turn_points: int = 16) -> np.ndarray:
        """(P, 2) the flight path: the strips back and forth joined by half-circle turns.

        Each strip runs from the first to the last photo centre; each turn is a
        half circle of diameter By outside the area.  km.
        """
        x0, x1 = float(self.photo_x_km[0]), float(self.photo_x_km[-1])
        r = self.plan.By_km / 2.0
        parts = []
        t = np.linspace(0.0, math.pi, int(turn_points))[1:-1]
        for k, y in enumerate(self.strip_y_km):
            fwd = k % 2 == 0
            a, b = (x0, x1) if fwd else (x1, x0)
            parts.append(np.array([[a, y], [b, y]]))
            if k + 1 < self.K:
                yc = y + r
                if fwd:   # turn beyond the east edge, counter-clockwise
                    arc = np.column_stack([b + r * np.sin(t), yc - r * np.cos(t)])
                else:     # beyond the west edge
                    arc = np.column_stack([b - r * np.sin(t), yc - r * np.cos(t)])
                parts.append(arc)
        return np.vstack(parts)

    @property
    def strips_length_km(self) -> float:
        """Total length of the K flight lines from first to last exposure, km."""
        return self.K * (self.n - 1) * self.plan.Bx_km

    @property
    def route_length_km(self) -> float:
        """Length of :meth:`route_km` with exact half circles: strips plus (K − 1)·π·By/2, km."""
        return self.strips_length_km + (self.K - 1) * math.pi * self.plan.By_km / 2.0


def layout(p: FlightPlan) -> FlightLayout:
    """Place the strips and photos of plan ``p`` over its area (see :class:`FlightLayout`)."""
    check_type("p", p, FlightPlan)
    span_y = (p.K - 1) * p.By_km
    span_x = (p.n - 1) * p.Bx_km
    strip_y = (p.Ly_km - span_y) / 2.0 + np.arange(p.K) * p.By_km
    photo_x = (p.Lx_km - span_x) / 2.0 + np.arange(p.n) * p.Bx_km
    cam = g.Camera(p.f_mm, p.frame_mm)
    pose = g.Pose.vertical(0.0, 0.0, p.H_m)
    fp = g.footprint(cam, pose, 0.0)[:, :2] / 1000.0
    return FlightLayout(p, strip_y, photo_x, fp)


def overlaps_at(p: FlightPlan, Z_m: float) -> tuple[float, float]:
    """Forward and side overlap, %, of neighbouring photos of plan ``p`` on ground at height ``Z_m``.

    The camera flies at H = f·m above the *lowest* ground (so the photo scale
    is 1:m on it and larger on higher ground); two neighbouring photos of a
    strip are Bx apart, two neighbouring strips By apart.  The footprints on
    the plane Z = ``Z_m`` come from :func:`aerophoto.geometry.footprint`.
    On the lowest ground the overlaps are Px and Py; higher up the footprints
    shrink by (H − z)/H while the bases stay, so the overlaps fall to
    100 − (100 − P)·H/(H − z) at z = Z − Zmin.  An allowance (100 − p)·h/H
    keeps an overlap at exactly p on the highest ground; with px = 60 % that is
    the guide's 40·h/H, while for py = 30 % the same 40·h/H leaves the side
    overlap slightly below py there (the exact allowance would be 70·h/H).

    Returns ``(forward_percent, side_percent)``.
    """
    check_type("p", p, FlightPlan)
    Z = check_range("Z_m", Z_m, -math.inf, p.Zmin_m + p.H_m, hi_open=True, unit="m")
    cam = g.Camera(p.f_mm, p.frame_mm)
    a = g.footprint(cam, g.Pose.vertical(0.0, 0.0, p.H_m, ground_Z_m=p.Zmin_m), Z)
    b = g.footprint(cam, g.Pose.vertical(p.Bx_m, 0.0, p.H_m, ground_Z_m=p.Zmin_m), Z)
    c = g.footprint(cam, g.Pose.vertical(0.0, p.By_m, p.H_m, ground_Z_m=p.Zmin_m), Z)
    side_x = a[:, 0].max() - a[:, 0].min()
    side_y = a[:, 1].max() - a[:, 1].min()
    forward = (a[:, 0].max() - b[:, 0].min()) / side_x * 100.0
    across = (a[:, 1].max() - c[:, 1].min()) / side_y * 100.0
    return float(forward), float(across)
