"""Graded tasks of chapter 10 (guide §11): the student's own resection and its check angle.

Each variant gets its own station on the virtual site (:func:`resection_lab`):
a well-defined ground point P that is not yet a control point, and four
known points A, B, C, D of the site's control network round it.  The site's
coordinates are turned into plane coordinates like the guide's §11 table
(X north, Y east, metres, :data:`GEODETIC_ORIGIN`).  The angles "measured" at
P are the true angles with a theodolite's random error (σ = 5″, rounded to
whole seconds); in every fifth variant (i = 4, 9, 14, …) the angle β₂ was
misread by several minutes — the check must catch it.

* task 10.1 (:class:`Resection`): the station's X, Y from A, B, C and β₁, β₂,
  and the direction angle from P to A;
* task 10.2 (:class:`CheckAngle`): the check angle from C to D computed from
  the station, its discrepancy from the measured one, the tolerance and the
  verdict (:func:`aerophoto.control.check_tolerance_arcsec`, 0.1 mm at 1:10 000).

The answers are computed from the rounded numbers the student reads.
"""

from __future__ import annotations

import functools
import itertools
import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import control as c
from ..site import get_site
from .base import Answer, Hidden, Task, submitted_number

__all__ = ["GEODETIC_ORIGIN", "SIGMA_ARCSEC", "PLAN_M", "ResectionLab", "resection_lab", "lab_from_points",
           "Resection", "CheckAngle", "TASKS", "blunder_variant"]

#: geodetic X (north) of the site's south edge and Y (east) of its west edge, m — of the size of the guide's table
GEODETIC_ORIGIN = (6_060_000.0, 5_310_000.0)
#: a theodolite's RMS angle error, arc-seconds
SIGMA_ARCSEC = 5.0
#: the plan's scale denominator for the check's tolerance (0.1 mm at 1:10 000 = 1 m)
PLAN_M = 10000.0


def blunder_variant(i: int) -> bool:
    """Every fifth variant (i ≡ 4 mod 5) has a misread β₂ that the check angle must catch."""
    return int(i) % 5 == 4


@dataclass(frozen=True)
class ResectionLab:
    """A resection with its check: the known points, the measured angles and the true station.

    Attributes
    ----------
    known : DataFrame
        A, B, C, D: ``X, m``, ``Y, m`` (geodetic, 0.01 m) and ``site id`` (the catalogue id).
    angles_deg : dict
        ``beta1`` (A → B), ``beta2`` (B → C), ``gamma`` (C → D), measured, degrees (whole seconds).
    true_station : ndarray (2,)
        Where P really is (geodetic X, Y, m) — the instructor's side.
    station_id : int
        The catalogue id of P.
    blunder_arcsec : float
        The misreading added to β₂ (0 for most variants).
    """

    known: pd.DataFrame
    angles_deg: dict
    true_station: np.ndarray
    station_id: int
    blunder_arcsec: float = 0.0

    def point(self, name: str) -> np.ndarray:
        return self.known.loc[name, ["X, m", "Y, m"]].to_numpy(dtype=float)

    def known_table(self) -> pd.DataFrame:
        """What the student reads: the four known points (X north, Y east, m)."""
        return self.known[["X, m", "Y, m"]].copy()

    def angles_table(self) -> pd.DataFrame:
        """What the student reads: the three angles measured at P (clockwise), as degrees-minutes-seconds and degrees."""
        rows = [("β₁", "A → B", self.angles_deg["beta1"]), ("β₂", "B → C", self.angles_deg["beta2"]),
                ("γ (check)", "C → D", self.angles_deg["gamma"])]
        return pd.DataFrame({"from → to": [r[1] for r in rows], "angle": [c.format_dms(r[2]) for r in rows],
                             "angle, °": [round(r[2], 7) for r in rows]},
                            index=pd.Index([r[0] for r in rows], name="angle at P"))

    @functools.cached_property
    def resection(self) -> c.Resection:
        """The station from A, B, C and the measured β₁, β₂."""
        return c.resect(self.point("A"), self.point("B"), self.point("C"), self.angles_deg["beta1"],
                        self.angles_deg["beta2"])

    @functools.cached_property
    def check(self) -> c.ResectionCheck:
        """The check by γ to D (tolerance 0.1 mm at 1:10 000)."""
        return c.check_resection(self.resection, self.point("D"), self.angles_deg["gamma"], M=PLAN_M)


def _round_angle(a_deg: float) -> float:
    return round(a_deg * 3600.0) / 3600.0 % 360.0


def lab_from_points(P, A, B, C, D, *, rng=None, sigma_arcsec: float = SIGMA_ARCSEC, blunder_arcsec: float = 0.0,
                    ids=(0, 0, 0, 0, 0)) -> ResectionLab:
    """A resection lab from a true station and four known points (geodetic X, Y, m), angles with noise."""
    P, A, B, C, D = (np.asarray(p, dtype=float).reshape(2) for p in (P, A, B, C, D))
    true = {"beta1": c.horizontal_angle_deg(P, A, B), "beta2": c.horizontal_angle_deg(P, B, C),
            "gamma": c.horizontal_angle_deg(P, C, D)}
    noise = rng.normal(0.0, sigma_arcsec, size=3) if rng is not None else np.zeros(3)
    meas = {k: _round_angle(val + e / 3600.0) for (k, val), e in zip(true.items(), noise)}
    meas["beta2"] = _round_angle(meas["beta2"] + blunder_arcsec / 3600.0)
    known = pd.DataFrame({"X, m": [round(p[0], 2) for p in (A, B, C, D)],
                          "Y, m": [round(p[1], 2) for p in (A, B, C, D)], "site id": list(ids[1:])},
                         index=pd.Index(["A", "B", "C", "D"], name="point"))
    return ResectionLab(known, meas, P, int(ids[0]), float(blunder_arcsec))


def _geodetic(df) -> np.ndarray:
    X0, Y0 = GEODETIC_ORIGIN
    return np.column_stack([X0 + df["Y_m"].to_numpy(float), Y0 + df["X_m"].to_numpy(float)])


@functools.lru_cache(maxsize=1)
def _network():
    cat = get_site().catalogue
    net = cat[cat["control"]]
    stations = cat[(~cat["control"]) & cat["kind"].isin(["road crossing", "field corner"])]
    return (net["id"].to_numpy(), _geodetic(net), stations["id"].to_numpy(), _geodetic(stations))


def _choose(P, N, ids):
    """The best A, B, C, D among the nearest network points: a firm resection and well-spread directions."""
    d = np.hypot(*(N - P).T)
    near = [k for k in np.argsort(d) if 400.0 <= d[k] <= 3500.0][:8]
    best = None
    for combo in itertools.combinations(near, 4):
        az = {k: c.direction_angle_deg(P, N[k]) for k in combo}
        order = sorted(combo, key=lambda k: az[k])  # clockwise from north
        for shift in range(4):
            seq = order[shift:] + order[:shift]
            A, B, C, D = (N[k] for k in seq)
            b1, b2 = c.horizontal_angle_deg(P, A, B), c.horizontal_angle_deg(P, B, C)
            g = c.horizontal_angle_deg(P, C, D)
            if min(b1, b2, g) < 25.0 or b1 + b2 > 300.0:
                continue
            try:
                r = c.resect(A, B, C, b1, b2)
            except ValueError:
                continue
            score = r.strength * min(b1, b2, g) / 90.0
            if best is None or score > best[0]:
                best = (score, seq)
    return best


@functools.lru_cache(maxsize=128)
def _lab(i: int) -> ResectionLab:
    net_ids, N, st_ids, S = _network()
    rng = np.random.default_rng([int(i), 11])
    order = rng.permutation(len(S))
    for k in order:
        best = _choose(S[k], N, net_ids)
        if best is not None and best[0] > 0.15:
            seq = best[1]
            break
    else:  # pragma: no cover - the site always has a usable station
        raise RuntimeError("no station on the site has four usable known points")
    P = S[k]
    A, B, C, D = (N[j] for j in seq)
    ids = (int(st_ids[k]), *(int(net_ids[j]) for j in seq))
    if not blunder_variant(i):
        return lab_from_points(P, A, B, C, D, rng=rng, ids=ids)
    blunder = float(rng.choice([-1.0, 1.0]) * rng.integers(4, 9) * 60.0)
    for _ in range(20):  # a misreading large enough for the check to see
        lab = lab_from_points(P, A, B, C, D, rng=np.random.default_rng([int(i), 11, 1]), blunder_arcsec=blunder,
                              ids=ids)
        if not lab.check.ok:
            return lab
        blunder *= 1.5
    return lab  # pragma: no cover


def resection_lab(v) -> ResectionLab:
    """The student's resection for variant ``v`` (its i only)."""
    return _lab(int(v.i))


# =========================================================================== task 10.1
@dataclass(frozen=True)
class Resection(Task):
    """Task 10.1: the station's X, Y by resection from A, B, C and β₁, β₂; the direction angle P → A."""

    id = "task-10-1"
    title = "Your resection"
    points = 4
    spec = (
        Answer("X_m", "X of the station P (north), m", unit="m", tol_abs=0.05),
        Answer("Y_m", "Y of the station P (east), m", unit="m", tol_abs=0.05),
        Answer("alpha_PA_deg", "direction angle from P to A, degrees", unit="°", tol_abs=0.002, period=360.0),
    )

    def inputs(self, v) -> ResectionLab:
        return resection_lab(v)

    def answers(self, v) -> dict:
        lab = resection_lab(v)
        P = lab.resection.point
        return {"X_m": float(P[0]), "Y_m": float(P[1]), "alpha_PA_deg": c.direction_angle_deg(P, lab.point("A"))}

    def slips(self, v) -> dict:
        lab = resection_lab(v)
        a = lab.angles_deg
        out = {"X_m": {}, "Y_m": {}, "alpha_PA_deg": {}}
        tries = (("the angles were taken counter-clockwise: a theodolite reads them clockwise",
                  (360.0 - a["beta1"], 360.0 - a["beta2"])),
                 ("β₁ and β₂ are swapped: β₁ is measured from A to B, β₂ from B to C", (a["beta2"], a["beta1"])))
        for hint, (b1, b2) in tries:
            try:
                P = c.resect(lab.point("A"), lab.point("B"), lab.point("C"), b1, b2).point
            except ValueError:
                continue
            out["X_m"][hint] = float(P[0])
            out["Y_m"][hint] = float(P[1])
        P = lab.resection.point
        A = lab.point("A")
        out["alpha_PA_deg"]["that is the direction from A to P; the direction angle from P to A is 180° away"] = \
            c.direction_angle_deg(A, P)
        out["alpha_PA_deg"]["atan2 takes (ΔY, ΔX) here: X is north, Y east, and the angle runs clockwise from X"] = \
            float(np.degrees(np.arctan2(A[0] - P[0], A[1] - P[1])) % 360.0)
        return out

    def hidden(self, v, got) -> list:
        # the direction angle must follow from the student's own station: atan2(Y_A − Y_P, X_A − X_P)
        lab = resection_lab(v)
        X, Y = submitted_number(got.get("X_m")), submitted_number(got.get("Y_m"))
        a = submitted_number(got.get("alpha_PA_deg"))
        if X is None or Y is None or a is None:
            return [Hidden("alpha_PA_deg from your own station", None, None)]
        A = lab.point("A")
        try:
            exp = c.direction_angle_deg([X, Y], A)
        except ValueError:
            return [Hidden("alpha_PA_deg from your own station", None, None)]
        diff = math.remainder(a - exp, 360.0)
        return [Hidden("alpha_PA_deg from your own station", exp + diff, exp, tol_abs=0.002)]


# =========================================================================== task 10.2
@dataclass(frozen=True)
class CheckAngle(Task):
    """Task 10.2: the check angle C → D from the station, its discrepancy, the tolerance and the verdict."""

    id = "task-10-2"
    title = "The check angle"
    points = 4
    spec = (
        Answer("gamma_calc_deg", "check angle C → D computed from your station, degrees", unit="°", tol_abs=0.001,
               period=360.0),
        Answer("dgamma_arcsec", "measured minus computed, arc-seconds", unit="″", tol_abs=4.0),
        Answer("tol_arcsec", "tolerance of the check angle, arc-seconds"),
        Answer("check_ok", "True if the check holds", kind="bool",
               hint="compare |Δγ| with the tolerance ρ″·(0.1 mm · M)/S_PD"),
    )

    def inputs(self, v) -> ResectionLab:
        return resection_lab(v)

    def answers(self, v) -> dict:
        ch = resection_lab(v).check
        return {"gamma_calc_deg": ch.computed_deg, "dgamma_arcsec": ch.discrepancy_arcsec,
                "tol_arcsec": ch.tolerance_arcsec, "check_ok": bool(ch.ok)}

    def slips(self, v) -> dict:
        lab = resection_lab(v)
        ch = lab.check
        S_C = float(np.hypot(*(lab.point("C") - lab.resection.point)))
        return {
            "gamma_calc_deg": {"that is the angle from D to C; the check angle runs clockwise from C to D":
                               (360.0 - ch.computed_deg) % 360.0},
            "dgamma_arcsec": {"the sign: Δγ = measured − computed": -ch.discrepancy_arcsec},
            "tol_arcsec": {"the tolerance uses the distance to the check point D, not to C":
                           c.check_tolerance_arcsec(S_C, PLAN_M),
                           "0.1 mm at the plan's scale 1:10 000 is 1 m on the ground, not 0.1 m":
                           ch.tolerance_arcsec / 10.0},
        }

    def hidden(self, v, got) -> list:
        # Δγ must follow from the student's own computed angle, and the verdict from their own Δγ and tolerance
        lab = resection_lab(v)
        g = submitted_number(got.get("gamma_calc_deg"))
        dg = submitted_number(got.get("dgamma_arcsec"))
        tol = submitted_number(got.get("tol_arcsec"))
        out = []
        if g is None or dg is None:
            out.append(Hidden("dgamma_arcsec from your own gamma_calc_deg", None, None))
        else:
            exp = math.remainder(lab.angles_deg["gamma"] - g, 360.0) * 3600.0
            out.append(Hidden("dgamma_arcsec from your own gamma_calc_deg", dg, exp, tol_abs=1.0))
        if dg is None or tol is None:
            out.append(Hidden("check_ok from your own dgamma_arcsec and tol_arcsec", None, None, kind="bool"))
        else:
            out.append(Hidden("check_ok from your own dgamma_arcsec and tol_arcsec", got.get("check_ok"),
                              abs(dg) <= tol, kind="bool"))
        return out


TASKS = (Resection(), CheckAngle())
