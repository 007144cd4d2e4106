"""The planimetric error budget of map updating at a digital photogrammetric station (article 003).

When a topographic map or plan is updated (обновление карт) from aerial photos at a digital
photogrammetric station (цифровая фотограмметрическая станция, ЦФС), the position of a building
corner on the new map carries the errors of every stage of the work.  Article 003 estimates the RMS
error (средняя квадратическая ошибка, СКО) of each stage on the ground and adds them as independent
errors, root-sum-square (formula 10):

=====================================================  =========  ============================================
stage                                                  symbol     RMS on the ground (the article's rule)
=====================================================  =========  ============================================
control survey (планово-высотная подготовка)            m_пл/в     1.25 · 0.1 mm · M_k   (formula 1)
scanning the negatives (сканирование)                   m_ск       3 µm · M_c            (Deltascan)
phototriangulation (построение сетей фототриангуляции)  m_ф        √2 · 0.84 · M_c · 0.5·P   (7), (8)
the DEM (создание ЦМР)                                  m_ЦМР      1.25 · 0.3 mm · M_k
orthorectification and mosaicking (ортотрансформирование)  m_орт   1.25 · 0.1 mm · M_k
transfer of points between strips (перенос точек)       m_н/м      √([d²]/(2(n−1))) · M_k, d = 0.5 mm, n = 50  (9)
vectorising (векторизация)                              m_вект     0.11 mm · M_k         (table 1, (3)–(6))
=====================================================  =========  ============================================

with 1:M_c the photo scale, 1:M_k the map scale and P the scanning resolution (pixel size).  The
map's requirement is a *mean* error (средняя ошибка) of at most 0.4 mm for buildings; the article
turns mean errors into RMS errors and back with m = 1.25·v (formulas 1 and 5; for normally
distributed errors the factor is √(π/2) = 1.2533).

Three stages are not estimates but tolerances of the instruction turned into RMS errors (the DEM,
orthorectification and the transfer between strips); they dominate the budget.  :func:`budget`
computes it for any photo scale, scanning resolution and map scale; its ``dtm`` argument replaces the
DEM's tolerance by what a DEM of a given height accuracy actually does to an orthophoto
(:func:`dtm_displacement_m`), or by the relief left uncorrected when a photo is rectified onto one
plane (:func:`plane_rectification_m`).

The printed tables 1–5 and their audits: :mod:`aerophoto.guide.ch17`.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from . import _validate as V
from ._validate import check_finite_array, check_int_range, check_positive, check_range

__all__ = ["MEAN_TO_RMS", "TOLERANCE_MEAN_MM", "SCAN_RMS_UM", "TRIANGULATION_K", "SIGMA_PER_PIXEL",
           "CONTROL_MEAN_MM", "DTM_MAX_MM", "ORTHO_MEAN_MM", "TRANSFER_MEAN_MM", "TRANSFER_POINTS",
           "VECTORISING_MAP_MM", "STAGES", "rms_from_mean", "mean_from_rms", "mean_abs_deviation",
           "plan_error", "Vectorising", "vectorising_error", "sigma_um", "triangulation_rms_m",
           "transfer_rms_mm", "transfer_from_mean_mm", "relief_limit_m", "working_area_radii_mm", "dtm_displacement_m",
           "plane_rectification_m", "Stage", "Budget", "budget", "ARTICLE_CASES", "scenarios"]

#: formulas (1) and (5): RMS error m = 1.25 · mean error v
MEAN_TO_RMS = 1.25
#: the map's requirement: mean error of buildings ≤ 0.4 mm on the map (instructions [1; 2])
TOLERANCE_MEAN_MM = 0.4
#: RMS error of the Deltascan scanner, µm on the photo
SCAN_RMS_UM = 3.0
#: formula (7): m_X,Y = 0.84 · M_c · σ
TRIANGULATION_K = 0.84
#: σ = 0.5 · P (refs [6; 7]): the RMS error of an image measurement in pixels
SIGMA_PER_PIXEL = 0.5
#: mean error of the control points on the plan, mm
CONTROL_MEAN_MM = 0.1
#: largest relief distortion the DEM may leave on the plan, mm (instruction [2]); its RMS is 1.25 × this
DTM_MAX_MM = 0.3
#: mean error allowed for orthorectification and mosaicking, mm (0.7 mm misfit − 2 × 0.3 mm relief)
ORTHO_MEAN_MM = 0.1
#: mean discrepancy of common points of adjacent strips, mm on the map (instruction [2])
TRANSFER_MEAN_MM = 0.5
#: number of common points the article assumes in formula (9)
TRANSFER_POINTS = 50
#: the vectorising error on the map, mm (formula 6, from table 1)
VECTORISING_MAP_MM = 0.11

#: the stages of formula (10), in the article's order: (key, symbol, English, Russian)
STAGES = (
    ("control", "m_пл/в", "control survey", "планово-высотная подготовка"),
    ("scanning", "m_ск", "scanning", "сканирование"),
    ("triangulation", "m_ф", "phototriangulation", "фототриангуляция"),
    ("dtm", "m_ЦМР", "DEM", "цифровая модель рельефа"),
    ("ortho", "m_орт", "orthorectification and mosaic", "ортотрансформирование и монтаж"),
    ("transfer", "m_н/м", "transfer between strips", "перенос точек на смежные маршруты"),
    ("vectorising", "m_вект", "vectorising", "векторизация"),
)


@V.checked(v=V.values(0.0))
def rms_from_mean(v):
    """RMS error from a mean error, m = 1.25·v (article 003, formulas 1 and 5); any unit, arrays too."""
    return MEAN_TO_RMS * np.asarray(v, dtype=float) if np.ndim(v) else MEAN_TO_RMS * float(v)


@V.checked(m=V.values(0.0))
def mean_from_rms(m):
    """Mean error from an RMS error, v = m/1.25 (article 003, before table 5)."""
    return np.asarray(m, dtype=float) / MEAN_TO_RMS if np.ndim(m) else float(m) / MEAN_TO_RMS


def mean_abs_deviation(values) -> float:
    """Formula (3): V = Σ|Δᵢ|/n, Δᵢ the deviations of repeated measurements from their mean (same unit)."""
    a = check_finite_array("values", values, ndim=1, min_len=2)
    return float(np.mean(np.abs(a - a.mean())))


@V.checked(v_x=V.values(), v_y=V.values())
def plan_error(v_x, v_y):
    """Formula (4) (and (8) for RMS errors): the planimetric error √(V_X² + V_Y²) from the axes' errors."""
    return np.hypot(v_x, v_y) if np.ndim(v_x) or np.ndim(v_y) else math.hypot(float(v_x), float(v_y))


@dataclass(frozen=True)
class Vectorising:
    """Table 1: the vectorising error from repeated measurements of one building corner.

    Attributes
    ----------
    n : number of measurements
    V_X_m, V_Y_m : mean errors along X and Y (formula 3), m on the ground
    V_D_m : mean planimetric error (formula 4), m
    m_D_m : RMS planimetric error m_D = 1.25·V_D (formula 5), m
    M_k : map-scale denominator
    """

    n: int
    V_X_m: float
    V_Y_m: float
    V_D_m: float
    m_D_m: float
    M_k: float

    @property
    def m_d_mm(self) -> float:
        """Formula (6): the RMS error on the map, m_d = m_D/M_k, mm."""
        return self.m_D_m / self.M_k * 1000.0

    def table(self) -> pd.DataFrame:
        """Laid out like the article's table 1."""
        return pd.DataFrame({"M_k": [self.M_k], "measurements": [self.n], "V_X, m": [self.V_X_m],
                             "V_Y, m": [self.V_Y_m], "V_D, m": [self.V_D_m], "m_D, m": [self.m_D_m],
                             "m_d, mm": [self.m_d_mm]})


def vectorising_error(X_m, Y_m, M_k: float) -> Vectorising:
    """Table 1 from repeated coordinates X, Y (m, one per measurement) of one point on a 1:M_k orthophoto."""
    X = check_finite_array("X_m", X_m, ndim=1, min_len=2)
    Y = check_finite_array("Y_m", Y_m, ndim=1, min_len=2)
    if len(X) != len(Y):
        raise ValueError(f"X_m has {len(X)} values and Y_m {len(Y)}; they must be equally many")
    Mk = check_range("M_k", M_k, 100.0, 1e7)
    vx, vy = mean_abs_deviation(X), mean_abs_deviation(Y)
    vd = plan_error(vx, vy)
    return Vectorising(len(X), vx, vy, vd, rms_from_mean(vd), Mk)


def sigma_um(P_um: float) -> float:
    """σ = 0.5·P: RMS error of measuring a point on a photo scanned with pixels of P µm, µm."""
    return SIGMA_PER_PIXEL * check_range("P_um", P_um, 1.0, 200.0, unit="µm")


def triangulation_rms_m(M_c: float, P_um: float) -> tuple[float, float]:
    """Formulas (7) and (8): (m_X,Y, m_D) of phototriangulation with GPS and a gyro mount, m on the ground.

    m_X,Y = 0.84 · M_c · σ with σ = 0.5·P; m_D = m_X,Y · √2.

    Parameters
    ----------
    M_c : photo-scale denominator (1:M_c), 500 ≤ M_c ≤ 200 000
    P_um : scanning resolution P (pixel size), µm, 1 ≤ P ≤ 200
    """
    Mc = check_range("M_c", M_c, 500.0, 200_000.0)
    mxy = TRIANGULATION_K * Mc * sigma_um(P_um) * 1e-6
    return mxy, mxy * math.sqrt(2.0)


def transfer_rms_mm(d_mm: float = TRANSFER_MEAN_MM, n: int = TRANSFER_POINTS) -> float:
    """Formula (9) with every discrepancy equal to d: m = √(n·d²/(2(n − 1))) = d·√(n/(2(n−1))), mm.

    The RMS error of transferring a point between adjacent strips from double measurements
    (discrepancies d of n common points).  Article 003: d = 0.5 mm, n = 50 → 0.357 mm (printed 0.35).
    """
    d = check_positive("d_mm", d_mm, unit="mm", hi=100.0)
    n = check_int_range("n", n, 2, 1_000_000)
    return d * math.sqrt(n / (2.0 * (n - 1)))


def transfer_from_mean_mm(d_mean_mm: float = TRANSFER_MEAN_MM, n: int = TRANSFER_POINTS) -> float:
    """The transfer stage's RMS, mm on the map, when d is the instruction's *mean* discrepancy (article 003).

    Formula (9) takes the discrepancies themselves; the instruction gives their mean, 0.5 mm.  The
    article's own rule (1) turns a mean into an RMS first (1.25·d = 0.625 mm), then (9):
    1.25·d·√(n/(2(n − 1))) = 0.446 mm for n = 50 (0.442 = 1.25·0.5/√2 for many points).  Applying (9)
    to the mean itself, as the article does, gives 0.357 mm (printed 0.35): :func:`transfer_rms_mm`.
    """
    return transfer_rms_mm(rms_from_mean(check_positive("d_mean_mm", d_mean_mm, unit="mm", hi=100.0)), n)


def relief_limit_m(f_mm: float, M_k: float, r_mm: float, delta_mm: float = DTM_MAX_MM) -> float:
    """Formula (2): the relief h_пред above the mean plane that displaces a point by δ on the map, m.

    h_пред = δ·f·M_k / r, with δ = 0.3 mm on the map, f and r (the point's distance from the nadir
    point on the photo) in mm.  The article prints it without the unit conversion; with f, r and δ
    in mm the product δ·f·M_k/r is in mm, so the metres are that /1000.
    """
    f = check_positive("f_mm", f_mm, unit="mm", hi=2000.0)
    Mk = check_range("M_k", M_k, 100.0, 1e7)
    r = check_positive("r_mm", r_mm, unit="mm", hi=1000.0)
    dl = check_positive("delta_mm", delta_mm, unit="mm", hi=100.0)
    return dl * f * Mk / r / 1000.0


def working_area_radii_mm(frame_mm: float = 230.0, px_percent: float = 60.0,
                          py_percent: float = 30.0) -> tuple[float, float]:
    """(r_max, r_rms) of a photo's working area b_x × b_y about its centre, mm.

    The working area (рабочая площадь) is the part of the photo the orthophoto takes from it:
    b_x = l(1 − p_x) by b_y = l(1 − p_y).  r_max is its half-diagonal (formula 2's r), r_rms the RMS
    distance of its points from the centre, √((b_x² + b_y²)/12).
    """
    l = check_positive("frame_mm", frame_mm, unit="mm", hi=500.0)
    px = check_range("px_percent", px_percent, 0.0, 100.0, hi_open=True, unit="%")
    py = check_range("py_percent", py_percent, 0.0, 100.0, hi_open=True, unit="%")
    bx, by = l * (1 - px / 100.0), l * (1 - py / 100.0)
    return math.hypot(bx, by) / 2.0, math.sqrt((bx * bx + by * by) / 12.0)


def dtm_displacement_m(m_h_m: float, f_mm: float, r_mm: float) -> float:
    """Plan error an orthophoto gets from a DEM height error m_h, on the ground: (r/f)·m_h, m.

    A height error Δh displaces a point at distance r from the nadir point by r·Δh/H on the photo,
    i.e. by r·Δh/f on the ground (H = f·M_c).
    """
    mh = check_range("m_h_m", m_h_m, 0.0, 1e4, unit="m")
    f = check_positive("f_mm", f_mm, unit="mm", hi=2000.0)
    r = check_range("r_mm", r_mm, 0.0, 1000.0, unit="mm")
    return r / f * mh


def plane_rectification_m(relief_m: float, f_mm: float, r_mm: float) -> float:
    """RMS plan error left by rectifying onto the mean plane ground of relief Δh (heights uniform in ±Δh/2), m.

    (r/f)·Δh/√12 — the DEM replaced by one plane.
    """
    dh = check_range("relief_m", relief_m, 0.0, 1e4, unit="m")
    return dtm_displacement_m(dh / math.sqrt(12.0), f_mm, r_mm)


@dataclass(frozen=True)
class Stage:
    """One stage of the budget: its RMS planimetric error on the ground and where it comes from."""

    key: str
    symbol: str
    name: str
    name_ru: str
    rms_m: float
    rule: str


@dataclass(frozen=True)
class Budget:
    """The error budget of one map (formula 10 and table 5).

    Attributes
    ----------
    stages : tuple of :class:`Stage`
    M_k : map-scale denominator
    M_c : photo-scale denominator
    """

    stages: tuple
    M_k: float
    M_c: float

    @property
    def total_m(self) -> float:
        """Formula (10): m_D = √Σ mᵢ², m on the ground."""
        return float(math.sqrt(sum(s.rms_m**2 for s in self.stages)))

    @property
    def map_rms_mm(self) -> float:
        """m_d = m_D/M_k on the map, mm (table 5)."""
        return self.total_m / self.M_k * 1000.0

    @property
    def map_mean_mm(self) -> float:
        """v_d = m_d/1.25 on the map, mm (table 5)."""
        return mean_from_rms(self.map_rms_mm)

    @property
    def meets_tolerance(self) -> bool:
        """v_d ≤ 0.4 mm: the map meets the instruction's requirement for buildings."""
        return self.map_mean_mm <= TOLERANCE_MEAN_MM + 1e-12

    @property
    def dominant(self) -> Stage:
        """The stage with the largest error."""
        return max(self.stages, key=lambda s: s.rms_m)

    def stage(self, key: str) -> Stage:
        for s in self.stages:
            if s.key == key:
                return s
        raise KeyError(f"no stage {key!r}; stages: {[s.key for s in self.stages]}")

    def shares(self) -> dict:
        """Each stage's share of the total variance Σmᵢ², key → fraction."""
        tot = sum(s.rms_m**2 for s in self.stages)
        return {s.key: (s.rms_m**2 / tot if tot > 0 else 0.0) for s in self.stages}

    def table(self) -> pd.DataFrame:
        """The stages as the rows of table 4 (ground and map), their variance shares, and the totals of table 5."""
        sh = self.shares()
        rows = [(f"{s.name} ({s.name_ru})", s.symbol, s.rms_m, s.rms_m / self.M_k * 1000.0, 100.0 * sh[s.key], s.rule)
                for s in self.stages]
        rows.append(("total, formula (10)", "m_D", self.total_m, self.map_rms_mm, 100.0, "√Σ mᵢ²"))
        df = pd.DataFrame(rows, columns=["stage", "symbol", "RMS on the ground, m", "RMS on the map, mm",
                                         "share of variance, %", "rule"])
        return df.set_index("stage")


def budget(M_c: float = 10_000.0, P_um: float = 16.0, M_k: float = 2000.0, *, f_mm: float = 153.0,
           frame_mm: float = 230.0, dtm: str = "instruction", m_h_m: float = 1.0, relief_m: float = 0.0,
           px_percent: float = 60.0, py_percent: float = 30.0, transfer_mm: float | None = None,
           extra_stages: bool = False) -> Budget:
    """The planimetric error budget of updating a 1:M_k map from 1:M_c photos scanned at P µm (article 003).

    Parameters
    ----------
    M_c : photo-scale denominator (500 ≤ M_c ≤ 200 000); the article: 15 000 and 10 000
    P_um : scanning resolution P, µm (1 ≤ P ≤ 200); the article: 42 and 16
    M_k : map-scale denominator (100 ≤ M_k ≤ 10⁶); the article: 10 000 and 2000
    f_mm, frame_mm : the camera (the article: 153 mm, 23 cm) — for the DEM stage and h_пред
    dtm : the DEM stage:
        ``"instruction"`` — the article's 1.25 × 0.3 mm on the map;
        ``"dem"`` — a DEM of height RMS ``m_h_m``: (r_rms/f)·m_h on the ground;
        ``"plane"`` — no DEM, rectification onto the mean plane of ground with relief ``relief_m``:
        (r_rms/f)·Δh/√12
    m_h_m : the DEM's height RMS, m (0 ≤ m_h ≤ 10⁴)
    relief_m : the relief within a photo, max − min height, m (0 ≤ Δh ≤ 10⁴)
    px_percent, py_percent : overlaps, % — the working area for r_rms
    transfer_mm : the transfer stage's RMS on the map, mm; default :func:`transfer_from_mean_mm`, 0.446 mm
        (rule (1) then formula (9); the article applies (9) to the mean discrepancy: 0.357, printed 0.35)
    extra_stages : add the two errors the article names last but leaves out of formula (10): interior
        orientation, 0.625·P·M_c, and the larger image-measurement error σ = 0.884·P in triangulation

    Returns
    -------
    :class:`Budget`
    """
    Mc = check_range("M_c", M_c, 500.0, 200_000.0)
    Mk = check_range("M_k", M_k, 100.0, 1e6)
    P = check_range("P_um", P_um, 1.0, 200.0, unit="µm")
    check_positive("f_mm", f_mm, unit="mm", hi=2000.0)  # checked whichever DEM stage uses them
    check_range("m_h_m", m_h_m, 0.0, 1e4, unit="m")
    check_range("relief_m", relief_m, 0.0, 1e4, unit="m")
    if dtm not in ("instruction", "dem", "plane"):
        raise ValueError(f"dtm = {dtm!r} is not one of the valid choices ['instruction', 'dem', 'plane']")
    _, r_rms = working_area_radii_mm(frame_mm, px_percent, py_percent)
    t_mm = transfer_from_mean_mm() if transfer_mm is None else check_range("transfer_mm", transfer_mm, 0.0, 100.0, unit="mm")
    on_ground = Mk / 1000.0  # map mm → ground m
    _, m_phi = triangulation_rms_m(Mc, P)
    rule_phi = "√2·0.84·M_c·0.5P"
    if extra_stages:
        m_phi *= 0.884 / SIGMA_PER_PIXEL
        rule_phi = "√2·0.84·M_c·0.884P"
    if dtm == "instruction":
        m_dtm, rule_dtm = rms_from_mean(DTM_MAX_MM) * on_ground, "1.25·0.3 mm·M_k"
    elif dtm == "dem":
        m_dtm, rule_dtm = dtm_displacement_m(m_h_m, f_mm, r_rms), "(r_rms/f)·m_h"
    else:
        m_dtm, rule_dtm = plane_rectification_m(relief_m, f_mm, r_rms), "(r_rms/f)·Δh/√12"
    values = {
        "control": (rms_from_mean(CONTROL_MEAN_MM) * on_ground, "1.25·0.1 mm·M_k"),
        "scanning": (SCAN_RMS_UM * 1e-6 * Mc, "3 µm·M_c"),
        "triangulation": (m_phi, rule_phi),
        "dtm": (m_dtm, rule_dtm),
        "ortho": (rms_from_mean(ORTHO_MEAN_MM) * on_ground, "1.25·0.1 mm·M_k"),
        "transfer": (t_mm * on_ground, "rule (1), formula (9)·M_k"),
        "vectorising": (VECTORISING_MAP_MM * on_ground, "0.11 mm·M_k"),
    }
    stages = [Stage(k, sym, en, ru, float(values[k][0]), values[k][1]) for k, sym, en, ru in STAGES]
    if extra_stages:
        stages.append(Stage("interior", "m_вн.о.", "interior orientation", "внутреннее ориентирование",
                            0.625 * P * 1e-6 * Mc, "0.625·P·M_c"))
    return Budget(tuple(stages), Mk, Mc)


#: the article's two cases (table 2): map scale, photo scale, f, frame, scanning resolution
ARTICLE_CASES = (
    dict(M_k=10_000.0, M_c=15_000.0, f_mm=153.0, frame_mm=230.0, P_um=42.0),
    dict(M_k=2000.0, M_c=10_000.0, f_mm=153.0, frame_mm=230.0, P_um=16.0),
)


@V.checked(m_h_m=V.number(0.0, 1e3))
def scenarios(M_c: float = 10_000.0, P_um: float = 16.0, M_k: float = 2000.0, *, f_mm: float = 153.0,
              frame_mm: float = 230.0, m_h_m: float = 0.5) -> pd.DataFrame:
    """What would change the verdict: the article's budget and four variations of it, one row each.

    * the article's stages (the transfer by rule (1) and formula (9), 0.446 mm);
    * the DEM's tolerance replaced by a DEM of height RMS ``m_h_m`` ((r_rms/f)·m_h);
    * the transfer between strips by the instruction's rule for digital work, 40 µm on the photo;
    * both;
    * the article's stages plus the closing paragraph's two errors (interior orientation, σ = 0.884·P).

    Columns: m_D (m, ground), m_d and v_d (mm, map), whether v_d ≤ 0.4 mm, and the dominant stage.
    """
    kw = dict(f_mm=f_mm, frame_mm=frame_mm)
    t40 = 40.0e-3 * check_range("M_c", M_c, 500.0, 200_000.0) / check_range("M_k", M_k, 100.0, 1e6)
    cases = (
        ("the article's budget", budget(M_c, P_um, M_k, **kw)),
        (f"a DEM of m_h = {m_h_m:g} m instead of the tolerance", budget(M_c, P_um, M_k, dtm="dem", m_h_m=m_h_m, **kw)),
        ("transfer at 40 µm on the photo", budget(M_c, P_um, M_k, transfer_mm=t40, **kw)),
        ("both", budget(M_c, P_um, M_k, dtm="dem", m_h_m=m_h_m, transfer_mm=t40, **kw)),
        ("with the closing paragraph's errors", budget(M_c, P_um, M_k, extra_stages=True, **kw)),
    )
    rows = [{"case": name, "m_D, m": B.total_m, "m_d, mm": B.map_rms_mm, "v_d, mm": B.map_mean_mm,
             "v_d ≤ 0.4 mm": bool(B.meets_tolerance), "largest stage": B.dominant.name} for name, B in cases]
    return pd.DataFrame(rows).set_index("case")
