"""Chapter 10 · guide §11 (ground control): the coordinate table of the four known points, checked in its own datum.

§11 closes its resection (обратная засечка) with a table of four known
points I–IV: plane coordinates X, Y and height H, and beside them the
latitude φ and longitude λ.  The section prints no angles and no computed
station — nothing in it follows from anything else — so the audit asks the
one question the table itself raises: **do its X, Y and its φ, λ describe
the same points?**

The leading 5 of Y = 5 3xx xxx names the 6° Gauss–Krüger zone 5 (central
meridian 27° E) of the Pulkovo 1942 datum (Krassowsky ellipsoid): geographic
EPSG:4284, zone 5 EPSG:28405 (false easting 5 500 000 m), as pyproj ships
them (pyproj in the installed book; in the browser, which has no pyproj, the
same Krüger series in numpy, within a millimetre of it).
:func:`coordinate_table` projects the printed φ, λ into that zone
and back, and sets the result beside the printed X, Y as an
:class:`~aerophoto.guide.audit.Audit`; the printed φ, λ are read to 1″, so
the computed X, Y are intervals (φ, λ ± 0.5″: about ±15 m in X, ±9 m in Y).

What the audit finds
--------------------
* None of the eight plane coordinates follows: every point's X lies about
  17.4 km, and its Y about 28.8 km, below the projection of its φ, λ (a
  nearly common shift: spread ±45 m and ±71 m).  Projected back, the
  printed X, Y lie near φ ≈ 54°41′, λ ≈ 24°06′ — 9.9′ south and 26.2′ west of the
  printed φ, λ.  So the X, Y are not Pulkovo 1942 Gauss–Krüger coordinates
  of these φ, λ (no other zone or datum pyproj knows comes nearer); they read
  like a shifted local (conditional) system or invented numbers.
* Even with the common shift removed the relative positions disagree by up
  to 115 m (point III in Y), more than reading φ, λ to 5″ — all the printed
  seconds are multiples of 5 — would explain (±76 m in X, ±47 m in Y).
* OCR: φ of III prints 15′ for 15″; λ of I prints 24°33′ without seconds
  (read as 24°33′00″).

The resection of chapter 10 therefore uses the X, Y (the plane coordinates
a resection works in) and not the φ, λ.
"""

from __future__ import annotations

import math
import re
from functools import lru_cache

import numpy as np
import pandas as pd

from .. import control as c
from .audit import Audit, printed

__all__ = ["SOURCE", "TABLE", "GEOGRAPHIC_CRS", "ZONE_CRS", "ZONE", "parse_dms", "projected", "geographic",
           "coordinate_table", "shift_summary", "known_points", "discrepancies"]

SOURCE = "guide §11"
#: the table as printed (OCR cleaned): point, X, Y, H (m), φ, λ (as printed text)
TABLE = (
    ("I", 6066340.0, 5313900.0, 102.75, "54°51′10″", "24°33′"),
    ("II", 6067000.0, 5313500.0, 108.8, "54°51′30″", "24°32′40″"),
    ("III", 6066540.0, 5312500.0, 110.0, "54°51′15″", "24°31′35″"),
    ("IV", 6065500.0, 5313100.0, 103.75, "54°50′45″", "24°32′20″"),
)
#: Pulkovo 1942 geographic (Krassowsky ellipsoid)
GEOGRAPHIC_CRS = "EPSG:4284"
#: Pulkovo 1942 / Gauss–Krüger zone 5 (central meridian 27° E, false easting 5 500 000 m)
ZONE_CRS = "EPSG:28405"
ZONE = 5

_REASON_X = ("not the Gauss–Krüger X of the printed φ, λ (Pulkovo 1942, zone 5): their projection gives "
             "{c:.0f} m; the printed X is about 17.4 km less, as for every point of the table")
_REASON_Y = ("not the Gauss–Krüger Y of the printed φ, λ (Pulkovo 1942, zone 5): their projection gives "
             "{c:.0f} m; the printed Y is about 28.8 km less, as for every point of the table")
_REASON_PHI = ("the printed X, Y project back to φ = {lat}; the printed φ is {d:.1f}′ further north")
_REASON_LAM = ("the printed X, Y project back to λ = {lon}; the printed λ is {d:.1f}′ further east")


def parse_dms(text: str) -> float:
    """``"54°51′10″"`` → degrees; missing minutes or seconds count as 0 (``"24°33′"``)."""
    nums = [float(x) for x in re.findall(r"\d+(?:[.,]\d+)?", str(text).replace(",", "."))]
    if not nums or len(nums) > 3:
        raise ValueError(f"text = {text!r} is not an angle in degrees, minutes and seconds")
    nums += [0.0] * (3 - len(nums))
    return c.from_dms(*nums)


class _TransverseMercator:
    """Gauss–Krüger (transverse Mercator) by Krüger's n-series to n⁶ (Karney 2011, J. Geodesy 85, 475–485).

    The browser book's stand-in for pyproj (Pyodide has none); within a zone it
    agrees with PROJ's tmerc (Poder/Engsager, the same series) to well under
    a millimetre.  The defaults are :data:`ZONE_CRS`, EPSG:28405: Krassowsky
    ellipsoid (a = 6 378 245 m, 1/f = 298.3), central meridian λ₀ = 27° E,
    scale k₀ = 1, false easting 5 500 000 m, false northing 0.

    ``transform(x, y)`` works like a pyproj ``Transformer`` with
    ``always_xy=True``: forward (``inverse=False``) λ, φ (degrees) → E, N (m);
    inverse E, N (m) → λ, φ (degrees).  Arrays of any (broadcastable) shape.
    """

    def __init__(self, *, inverse: bool = False, a_m: float = 6378245.0, inv_f: float = 298.3,
                 lon0_deg: float = 27.0, k0: float = 1.0, false_easting_m: float = 5_500_000.0,
                 false_northing_m: float = 0.0):
        f = 1.0 / inv_f
        n = f / (2.0 - f)
        self.inverse = bool(inverse)
        self.e = math.sqrt(f * (2.0 - f))
        self.lon0 = math.radians(lon0_deg)
        self.fe, self.fn = float(false_easting_m), float(false_northing_m)
        # k0·A, A = a/(1 + n)·(1 + n²/4 + n⁴/64 + n⁶/256): the rectifying radius
        self.kA = k0 * a_m / (1.0 + n) * (1.0 + n ** 2 / 4.0 + n ** 4 / 64.0 + n ** 6 / 256.0)
        # α_j (ξ′, η′ → ξ, η) and β_j (ξ, η → ξ′, η′), j = 1…6, to n⁶
        self.alpha = (
            n / 2 - 2 * n**2 / 3 + 5 * n**3 / 16 + 41 * n**4 / 180 - 127 * n**5 / 288 + 7891 * n**6 / 37800,
            13 * n**2 / 48 - 3 * n**3 / 5 + 557 * n**4 / 1440 + 281 * n**5 / 630 - 1983433 * n**6 / 1935360,
            61 * n**3 / 240 - 103 * n**4 / 140 + 15061 * n**5 / 26880 + 167603 * n**6 / 181440,
            49561 * n**4 / 161280 - 179 * n**5 / 168 + 6601661 * n**6 / 7257600,
            34729 * n**5 / 80640 - 3418889 * n**6 / 1995840,
            212378941 * n**6 / 319334400,
        )
        self.beta = (
            n / 2 - 2 * n**2 / 3 + 37 * n**3 / 96 - n**4 / 360 - 81 * n**5 / 512 + 96199 * n**6 / 604800,
            n**2 / 48 + n**3 / 15 - 437 * n**4 / 1440 + 46 * n**5 / 105 - 1118711 * n**6 / 3870720,
            17 * n**3 / 480 - 37 * n**4 / 840 - 209 * n**5 / 4480 + 5569 * n**6 / 90720,
            4397 * n**4 / 161280 - 11 * n**5 / 504 - 830251 * n**6 / 7257600,
            4583 * n**5 / 161280 - 108847 * n**6 / 3991680,
            20648693 * n**6 / 638668800,
        )

    def _tau_prime(self, tau):
        """tan of the conformal latitude χ from τ = tan φ (Karney 2011)."""
        sigma = np.sinh(self.e * np.arctanh(self.e * tau / np.hypot(1.0, tau)))
        return tau * np.hypot(1.0, sigma) - sigma * np.hypot(1.0, tau)

    def _forward(self, lon_deg, lat_deg):
        lam = np.radians(lon_deg) - self.lon0
        tp = self._tau_prime(np.tan(np.radians(lat_deg)))
        xi_p = np.arctan2(tp, np.cos(lam))
        eta_p = np.arcsinh(np.sin(lam) / np.hypot(tp, np.cos(lam)))
        xi, eta = xi_p.copy(), eta_p.copy()
        for j, a in enumerate(self.alpha, start=1):
            xi += a * np.sin(2 * j * xi_p) * np.cosh(2 * j * eta_p)
            eta += a * np.cos(2 * j * xi_p) * np.sinh(2 * j * eta_p)
        return self.fe + self.kA * eta, self.fn + self.kA * xi

    def _inverse(self, E_m, N_m):
        xi = (np.asarray(N_m, float) - self.fn) / self.kA
        eta = (np.asarray(E_m, float) - self.fe) / self.kA
        xi_p, eta_p = xi.copy(), eta.copy()
        for j, b in enumerate(self.beta, start=1):
            xi_p -= b * np.sin(2 * j * xi) * np.cosh(2 * j * eta)
            eta_p -= b * np.cos(2 * j * xi) * np.sinh(2 * j * eta)
        tp = np.sin(xi_p) / np.hypot(np.sinh(eta_p), np.cos(xi_p))  # tan χ
        lam = np.arctan2(np.sinh(eta_p), np.cos(xi_p))
        # τ = tan φ from τ′ = tan χ by Newton's method (Karney 2011); converges in 2–3 steps
        e2 = self.e ** 2
        tau = tp.copy()
        for _ in range(6):
            tpi = self._tau_prime(tau)
            step = (tp - tpi) / np.hypot(1.0, tpi) * (1.0 + (1.0 - e2) * tau ** 2) / ((1.0 - e2) * np.hypot(1.0, tau))
            tau = tau + step
            if np.all(np.abs(step) <= 1e-14 * np.maximum(1.0, np.abs(tau))):
                break
        return np.degrees(lam + self.lon0), np.degrees(np.arctan(tau))

    def transform(self, x, y):
        """(λ, φ) → (E, N), or with ``inverse`` (E, N) → (λ, φ); degrees and metres."""
        x = np.asarray(x, dtype=float)
        y = np.asarray(y, dtype=float)
        with np.errstate(invalid="ignore", divide="ignore"):
            return self._inverse(x, y) if self.inverse else self._forward(x, y)


@lru_cache(maxsize=1)
def _pyproj_transformers():
    from pyproj import Transformer

    fwd = Transformer.from_crs(GEOGRAPHIC_CRS, ZONE_CRS, always_xy=True)
    inv = Transformer.from_crs(ZONE_CRS, GEOGRAPHIC_CRS, always_xy=True)
    return fwd, inv


def _transformers(prefer_library: bool = True):
    """(forward, inverse) with ``.transform(x, y)`` (always_xy): λ, φ → E, N and E, N → λ, φ, zone 5 of Pulkovo 1942.

    pyproj's when it can be imported and ``prefer_library`` (the installed
    book); otherwise (the browser book: Pyodide has no pyproj)
    :class:`_TransverseMercator`, within a millimetre of it.  The import is
    tried on every call (a dictionary look-up once pyproj is loaded), so the
    choice follows the environment of the moment.
    """
    if prefer_library:
        try:
            import pyproj  # noqa: F401
        except ImportError:
            pass
        else:
            return _pyproj_transformers()
    return _TransverseMercator(), _TransverseMercator(inverse=True)


def projected(lat_deg, lon_deg) -> np.ndarray:
    """Gauss–Krüger X (north), Y (east) in zone 5 of Pulkovo 1942 for φ, λ (degrees): shape (…, 2), m."""
    fwd, _ = _transformers()
    E, N = fwd.transform(np.asarray(lon_deg, float), np.asarray(lat_deg, float))
    return np.stack([np.asarray(N, float), np.asarray(E, float)], axis=-1)


def geographic(X_m, Y_m) -> np.ndarray:
    """φ, λ (degrees, Pulkovo 1942) of Gauss–Krüger zone-5 coordinates X (north), Y (east): shape (…, 2)."""
    _, inv = _transformers()
    lon, lat = inv.transform(np.asarray(Y_m, float), np.asarray(X_m, float))
    return np.stack([np.asarray(lat, float), np.asarray(lon, float)], axis=-1)


def _frame() -> pd.DataFrame:
    df = pd.DataFrame(list(TABLE), columns=["point", "X, m", "Y, m", "H, m", "φ", "λ"]).set_index("point")
    df["φ, °"] = [parse_dms(t) for t in df["φ"]]
    df["λ, °"] = [parse_dms(t) for t in df["λ"]]
    return df


def known_points() -> pd.DataFrame:
    """The four points as printed: X, Y, H (m) and φ, λ (text and degrees)."""
    return _frame()


@lru_cache(maxsize=1)
def coordinate_table() -> Audit:
    """The §11 table with the printed X, Y beside the projection of the printed φ, λ and the reverse."""
    df = _frame()
    half = 0.5 / 3600.0
    values, rows = [], []
    for name, r in df.iterrows():
        lat, lon = r["φ, °"], r["λ, °"]
        XY = projected(lat, lon)
        corners = projected(np.array([lat - half, lat - half, lat + half, lat + half]),
                            np.array([lon - half, lon + half, lon - half, lon + half]))
        lo, hi = corners.min(axis=0), corners.max(axis=0)
        back = geographic(r["X, m"], r["Y, m"])
        values.append(printed(name, "X, m", r["X, m"], XY[0], 1.0, bounds=(lo[0], hi[0]), reason=_REASON_X,
                              computed_text=f"{lo[0]:.0f} … {hi[0]:.0f}"))
        values.append(printed(name, "Y, m", r["Y, m"], XY[1], 1.0, bounds=(lo[1], hi[1]), reason=_REASON_Y,
                              computed_text=f"{lo[1]:.0f} … {hi[1]:.0f}"))
        lat_t, lon_t = c.format_dms(back[0]), c.format_dms(back[1])
        values.append(printed(name, "φ, ″", lat * 3600.0, back[0] * 3600.0, 1.0,
                              reason=_REASON_PHI.format(lat=lat_t, d=(lat - back[0]) * 60.0), printed_text=r["φ"], computed_text=lat_t,
                              note="printed 15′ for 15″ (OCR)" if name == "III" else ""))
        values.append(printed(name, "λ, ″", lon * 3600.0, back[1] * 3600.0, 1.0,
                              reason=_REASON_LAM.format(lon=lon_t, d=(lon - back[1]) * 60.0), printed_text=r["λ"], computed_text=lon_t,
                              note="printed without seconds: read 24°33′00″" if name == "I" else ""))
        rows.append((name, r["X, m"], r["Y, m"], r["H, m"], r["φ"], r["λ"], round(XY[0]), round(XY[1]),
                     round(r["X, m"] - XY[0]), round(r["Y, m"] - XY[1]), lat_t, lon_t))
    table = pd.DataFrame(rows, columns=["point", "X, m", "Y, m", "H, m", "φ", "λ", "X from φ, λ, m",
                                        "Y from φ, λ, m", "ΔX, m", "ΔY, m", "φ from X, Y", "λ from X, Y"]
                         ).set_index("point")
    s = shift_summary()
    notes = (
        f"Datum and zone: Pulkovo 1942 ({GEOGRAPHIC_CRS}), Gauss–Krüger zone {ZONE} ({ZONE_CRS}, central meridian "
        "27° E, false easting 5 500 000 m), as the leading 5 of Y names it; projected with pyproj.",
        f"The printed X, Y are not the projection of the printed φ, λ: all four points are shifted by nearly the "
        f"same amount, ΔX = {s['mean_dX_m']:.0f} m (±{s['sd_dX_m']:.0f}), ΔY = {s['mean_dY_m']:.0f} m "
        f"(±{s['sd_dY_m']:.0f}) — a shifted local system or invented numbers, not Pulkovo 1942 Gauss–Krüger.",
        f"With the common shift removed the points still disagree by up to {s['max_relative_m']:.0f} m, more than "
        "reading φ, λ to 5″ explains (±76 m in X, ±47 m in Y); the printed seconds are all multiples of 5.",
        "OCR: φ of III printed 54°51′15′ (read 15″); λ of I printed 24°33′ (read 24°33′00″).",
        "The resection uses the plane X, Y: a resection works in plane coordinates, and they are the ones the "
        "field work would give.",
    )
    return Audit(SOURCE, "Coordinates of the known points (§11)", table, tuple(values),
                 printed_table=df[["X, m", "Y, m", "H, m", "φ", "λ"]], notes=notes, result=s)


@lru_cache(maxsize=1)
def shift_summary() -> dict:
    """The printed X, Y minus the projection of the printed φ, λ: mean and spread, and what is left after it.

    Keys: ``mean_dX_m``, ``mean_dY_m``, ``sd_dX_m``, ``sd_dY_m`` (population SD),
    ``residuals_m`` (4, 2) after removing the mean shift, ``max_relative_m``
    (the largest of their lengths), and ``mean_dlat_min``, ``mean_dlon_min``: the printed φ, λ minus those of the
    printed X, Y projected back, arcminutes (mean of the four; positive: the printed value is north / east).
    """
    df = _frame()
    XY = projected(df["φ, °"].to_numpy(), df["λ, °"].to_numpy())
    d = df[["X, m", "Y, m"]].to_numpy() - XY
    res = d - d.mean(axis=0)
    back = np.array([geographic(X, Y) for X, Y in df[["X, m", "Y, m"]].to_numpy()])
    dlat = (df["φ, °"].to_numpy() - back[:, 0]) * 60.0
    dlon = (df["λ, °"].to_numpy() - back[:, 1]) * 60.0
    return {"mean_dlat_min": float(dlat.mean()), "mean_dlon_min": float(dlon.mean()),
            "mean_dX_m": float(d[:, 0].mean()), "mean_dY_m": float(d[:, 1].mean()),
            "sd_dX_m": float(d[:, 0].std()), "sd_dY_m": float(d[:, 1].std()), "residuals_m": res,
            "max_relative_m": float(np.max(np.hypot(*res.T)))}


def discrepancies() -> pd.DataFrame:
    """Every printed value of §11 that does not agree with the others."""
    from .audit import discrepancy_frame

    return discrepancy_frame([coordinate_table()])
