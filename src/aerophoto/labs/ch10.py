"""Chapter 10's lab (guide §11): the student's resection station and the angles measured at it.

Each variant gets its own station on the virtual site (:func:`resection_lab`):
a well-defined ground point P that is not yet a control point, and four
known points A, B, C, D of the site's control network round it.  The site's
coordinates are turned into plane coordinates like the guide's §11 table
(X north, Y east, metres, :data:`GEODETIC_ORIGIN`).  The angles "measured" at
P are the true angles with a theodolite's random error (σ = 5″, rounded to
whole seconds); in every fifth variant (i = 4, 9, 14, …, :func:`blunder_variant`)
the angle β₂ was misread by several minutes.  :func:`lab_from_points` builds
the same from any five points.  The graded tasks are :mod:`aerophoto.tasks.ch10`.
"""

from __future__ import annotations

import functools
import itertools
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import control as c
from ..site import get_site

__all__ = ["GEODETIC_ORIGIN", "SIGMA_ARCSEC", "PLAN_M", "blunder_variant", "ResectionLab", "lab_from_points",
           "resection_lab"]

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
