"""G. P. Zhukov's formula (13.1) for the spacing of control points along a radial strip (guide §13 step 1).

    m = 0.25 · k_i · b_ср · (m_ε / ρ′) · √(n³ + 11n + 34)

The scan prints the radicand as n⁰ + 11n + 34; the book reads n³ (the
superscript 3 scanned as 0) — the reasons are in
:data:`aerophoto.guide.ch12.ZHUKOV_READING`, and :func:`bridge_variance_factor`
is the error-propagation argument behind them.  ``reading`` selects the
radicand everywhere: ``"n3"`` (the book), ``"n2"``, ``"n0"`` (as scanned).
"""

from __future__ import annotations

import math

import numpy as np

from .. import _validate as V
from .._validate import check_int_range, check_positive

__all__ = [
    "RHO_ARCMIN",
    "zhukov_radicand",
    "zhukov_error_mm",
    "zhukov_bases_continuous",
    "zhukov_max_bases",
    "bridge_variance_factor",
]

#: ρ′, arc-minutes in a radian (3437.75′)
RHO_ARCMIN = 180.0 * 60.0 / math.pi


@V.checked(n=V.values(1.0))
def zhukov_radicand(n, reading: str = "n3"):
    """The radicand of (13.1): ``"n3"`` n³ + 11n + 34 (the book's reading), ``"n2"`` n² + 11n + 34,
    ``"n0"`` n⁰ + 11n + 34 (as scanned)."""
    n = np.asarray(n, dtype=float)
    if reading == "n3":
        return n**3 + 11.0 * n + 34.0
    if reading == "n2":
        return n**2 + 11.0 * n + 34.0
    if reading == "n0":
        return 1.0 + 11.0 * n + 34.0
    raise ValueError(f"reading = {reading!r}; valid: 'n3' (n³ + 11n + 34), 'n2', 'n0'")


@V.checked(n=V.values(1.0))
def zhukov_error_mm(n, *, k_i: float = 1.0, b_mm: float = 60.0, m_eps_arcmin: float = 4.5, reading: str = "n3"):
    """Zhukov's formula (13.1): RMS error m of an orienting point in the middle of n bases, mm.

        m = 0.25 · k_i · b · (m_ε / ρ′) · √(n³ + 11n + 34)

    Parameters
    ----------
    n : array_like
        Number of photo bases between the outermost control points (n ≥ 1).
    k_i : float
        Transformation (enlargement) coefficient from the photo to the plan
        scale, e.g. m/M = 12000/10000 = 1.2 (guide: k_i).
    b_mm : float
        Mean photo base b_ср, mm (guide: ≈ 60 mm at p_x = 60 %).
    m_eps_arcmin : float
        RMS error of a central direction m_ε, arc-minutes (guide: 4′–5′).
    reading : see :func:`zhukov_radicand`.
    """
    k = check_positive("k_i", k_i)
    b = check_positive("b_mm", b_mm, unit="mm")
    me = check_positive("m_eps_arcmin", m_eps_arcmin, unit="arc-minutes")
    nn = np.asarray(n, dtype=float)
    if np.any(nn < 1):
        raise ValueError(f"n = {float(nn.min()):g} is outside the valid range n ≥ 1 (bases between control points)")
    out = 0.25 * k * b * (me / RHO_ARCMIN) * np.sqrt(zhukov_radicand(nn, reading))
    return float(out) if out.ndim == 0 else out


def zhukov_bases_continuous(m_allowed_mm: float = 0.35, *, k_i: float = 1.0, b_mm: float = 60.0,
                            m_eps_arcmin: float = 4.5, reading: str = "n3") -> float:
    """The real n ≥ 1 at which (13.1) reaches ``m_allowed_mm`` (bisection); 1.0 if already exceeded at n = 1."""
    m_allowed = check_positive("m_allowed_mm", m_allowed_mm, unit="mm")
    f = lambda n: zhukov_error_mm(n, k_i=k_i, b_mm=b_mm, m_eps_arcmin=m_eps_arcmin, reading=reading) - m_allowed  # noqa: E731
    lo, hi = 1.0, 2.0
    if f(lo) > 0:
        return 1.0
    while f(hi) <= 0:
        hi *= 2.0
        if hi > 1e7:
            raise ValueError(f"m_allowed_mm = {m_allowed:g} is never reached (n > 10⁷): check the inputs")
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) <= 0 else (lo, mid)
    return 0.5 * (lo + hi)


def zhukov_max_bases(m_allowed_mm: float = 0.35, *, k_i: float = 1.0, b_mm: float = 60.0, m_eps_arcmin: float = 4.5,
                     reading: str = "n3") -> int:
    """The largest whole number of bases n between control points with (13.1) ≤ ``m_allowed_mm`` (guide §13 step 1).

    Returns 0 when even one base exceeds the allowed error.
    """
    n = zhukov_bases_continuous(m_allowed_mm, k_i=k_i, b_mm=b_mm, m_eps_arcmin=m_eps_arcmin, reading=reading)
    k = int(math.floor(n + 1e-9))
    if k <= 1 and zhukov_error_mm(1, k_i=k_i, b_mm=b_mm, m_eps_arcmin=m_eps_arcmin, reading=reading) > m_allowed_mm:
        return 0
    return k


def bridge_variance_factor(n: int) -> float:
    """Variance at the middle of a chain of n bases held at both ends, per unit azimuth-transfer variance.

    Model: independent azimuth errors ε_1 … ε_n, one per base; the azimuth of
    base j is θ_j = ε_1 + … + ε_j and the lateral offset of point k is
    y_k = b·(θ_1 + … + θ_k); fitting the chain to its end points removes
    (k/n)·y_n.  Returns Var(y_{n/2} − y_n/2) / (b²σ²) computed exactly from
    the coefficients, which equals (n³ + 2n)/48 for even n.
    """
    n = check_int_range("n", n, 1, 100000)
    lo, hi = n // 2, (n + 1) // 2  # the middle point (interpolated between two for odd n)
    tot = 0.0
    for i in range(1, n + 1):
        c_mid = 0.5 * (max(0, lo - i + 1) + max(0, hi - i + 1))
        c_end = n - i + 1
        tot += (c_mid - 0.5 * c_end) ** 2
    return tot

