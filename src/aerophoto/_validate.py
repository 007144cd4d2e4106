"""Input checks shared by every module.

Every public function that takes a physical quantity checks it here, so that a
student who types an impossible value gets one kind of message everywhere:
the parameter's name, the value given and the valid range.
"""

from __future__ import annotations

import math
from numbers import Real

__all__ = ["check_range", "check_positive", "check_percent", "check_int_range"]


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
    """Return ``float(value)`` if it lies in the range, else raise ValueError.

    The message names the parameter, the value and the valid range, e.g.
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
    """A whole number within [lo, hi]."""
    if isinstance(value, bool) or not isinstance(value, (int, Real)) or int(value) != value:
        raise ValueError(f"{name} = {value!r} must be a whole number with {lo} ≤ {name} ≤ {hi}")
    check_range(name, value, lo, hi)
    return int(value)
