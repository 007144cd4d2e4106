"""Input checks shared by every module.

Every public function that takes a physical quantity checks it here, so that a
student who types an impossible value gets one kind of message everywhere:
the parameter's name, the value given and the valid range.
"""

from __future__ import annotations

import math
from numbers import Real

__all__ = ["check_range", "check_positive", "check_percent", "check_int_range", "check_finite_array",
           "check_points"]


def _fmt(x: float) -> str:
    if isinstance(x, float) and math.isinf(x):
        return "∞" if x > 0 else "-∞"
    return f"{x:g}"


def check_range(
    name: str,
    value,
    lo: float = -math.inf,
    hi: float = math.inf,
    *,
    lo_open: bool = False,
    hi_open: bool = False,
    unit: str = "",
) -> float:
    """Return ``float(value)`` if it is finite and lies in the range, else raise ValueError.

    ±inf and NaN are never valid, whatever the range.  The message names the parameter, the value and the valid range, e.g.
    ``f_mm = -5 is outside the valid range 0 < f_mm ≤ 1000 (mm)``.
    """
    try:
        x = float(value)
    except (TypeError, ValueError):
        raise ValueError(
            f"{name} = {value!r} is not a number; expected {_describe(name, lo, hi, lo_open, hi_open, unit)}"
        ) from None
    if math.isnan(x):
        raise ValueError(f"{name} = nan is not a number; expected {_describe(name, lo, hi, lo_open, hi_open, unit)}")
    if math.isinf(x):
        raise ValueError(
            f"{name} = {_fmt(x)} is not a finite number; expected {_describe(name, lo, hi, lo_open, hi_open, unit)}"
        )
    bad_lo = x <= lo if lo_open else x < lo
    bad_hi = x >= hi if hi_open else x > hi
    if bad_lo or bad_hi:
        raise ValueError(
            f"{name} = {_fmt(x)} is outside the valid range {_describe(name, lo, hi, lo_open, hi_open, unit)}"
        )
    return x


def _describe(name, lo, hi, lo_open, hi_open, unit) -> str:
    parts = []
    if lo > -math.inf:
        parts.append(f"{_fmt(lo)} {'<' if lo_open else '≤'} ")
    parts.append(name)
    if hi < math.inf:
        parts.append(f" {'<' if hi_open else '≤'} {_fmt(hi)}")
    text = "".join(parts)
    return f"{text} ({unit})" if unit else text


def check_positive(name: str, value, *, unit: str = "", hi: float = math.inf) -> float:
    """A strictly positive quantity (a length, a focal length, a scale denominator)."""
    return check_range(name, value, 0.0, hi, lo_open=True, unit=unit)


def check_percent(name: str, value, *, lo: float = 0.0, hi: float = 100.0) -> float:
    """An overlap or other percentage; 100 % itself is never valid (no progress)."""
    return check_range(name, value, lo, hi, lo_open=False, hi_open=True, unit="%")


def check_int_range(name: str, value, lo: int, hi: int) -> int:
    """A whole number within [lo, hi] (NaN, ±inf, fractions and non-numbers are rejected by name)."""
    if isinstance(value, bool) or not isinstance(value, (int, Real)):
        raise ValueError(f"{name} = {value!r:.80} must be a whole number with {lo} ≤ {name} ≤ {hi}")
    if not isinstance(value, int) and not math.isfinite(float(value)):
        raise ValueError(f"{name} = {_fmt(float(value)) if not math.isnan(float(value)) else 'nan'} is not a "
                         f"finite number; expected a whole number with {lo} ≤ {name} ≤ {hi}")
    if int(value) != value:
        raise ValueError(f"{name} = {value!r} must be a whole number with {lo} ≤ {name} ≤ {hi}")
    check_range(name, value, lo, hi)
    return int(value)


def check_finite_array(name: str, value, *, ndim: int | None = None, last: int | None = None,
                       min_len: int = 0, max_size: int = 10_000_000):
    """An array of finite numbers, as float ndarray.

    Parameters
    ----------
    ndim : int, optional
        Required number of dimensions.
    last : int, optional
        Required length of the last axis (2 for photo points x, y; 3 for ground points X, Y, Z).
    min_len : int
        Least number of rows (points).
    max_size : int
        Most elements accepted (work-size guard).
    """
    import numpy as np

    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise ValueError(f"{name} = {value!r:.80} is not an array of numbers") from None
    if a.size > max_size:
        raise ValueError(f"{name} has {a.size} elements; the valid range is at most {max_size}")
    if ndim is not None and a.ndim != ndim:
        raise ValueError(f"{name} has {a.ndim} dimension(s), shape {a.shape}; expected {ndim}")
    if last is not None and (a.ndim == 0 or a.shape[-1] != last):
        raise ValueError(f"{name} has shape {a.shape}; expected shape (..., {last})")
    if a.ndim and len(a) < min_len:
        raise ValueError(f"{name} has {len(a)} row(s); the valid range is at least {min_len}")
    if not np.all(np.isfinite(a)):
        bad = a[~np.isfinite(a)].ravel()[0]
        raise ValueError(f"{name} contains {bad}; every value must be a finite number")
    return a


def check_points(name: str, value, *, dim: int = 2, min_points: int = 0):
    """Points as a float array of shape (k, dim) with finite coordinates (a single point → (1, dim))."""
    a = check_finite_array(name, value, last=dim)
    a = a.reshape(-1, dim)
    if len(a) < min_points:
        raise ValueError(f"{name} has {len(a)} point(s); the valid range is at least {min_points}")
    return a
