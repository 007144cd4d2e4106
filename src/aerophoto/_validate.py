"""Input checks shared by every module.

Every public function that takes a physical quantity checks it here, so that a
student who types an impossible value gets one kind of message everywhere:
the parameter's name, the value given and the valid range.
"""

from __future__ import annotations

import math
from numbers import Real

__all__ = ["check_range", "check_positive", "check_percent", "check_int_range", "check_finite_array",
           "check_points", "check_type", "check_choice", "check_work_size", "check_values", "check_optional",
           "checked", "Spec", "points", "array", "values", "number", "whole", "of_type", "one_of", "terrain",
           "sequence", "names", "optional", "point", "pairs", "has_attrs", "shape", "image", "fill",
           "check_broadcast", "indices", "function"]

#: the most elements a computed grid, profile or sample may have (a step or count asking for more is refused)
MAX_WORK = 20_000_000


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

    if value is None or isinstance(value, (str, bytes)):
        raise TypeError(f"{name} = {value!r:.80} is not an array of numbers; expected numbers (a list or an ndarray)")
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
    if a.ndim > 2:
        raise ValueError(f"{name} has shape {a.shape}; expected ({dim},) for one point or (k, {dim}) for k points")
    a = a.reshape(-1, dim)
    if len(a) < min_points:
        raise ValueError(f"{name} has {len(a)} point(s); the valid range is at least {min_points}")
    return a


def _type_names(types) -> str:
    types = types if isinstance(types, tuple) else (types,)
    return " or ".join(getattr(t, "__name__", str(t)) for t in types)


def check_type(name: str, value, types, *, what: str | None = None, none: bool = False):
    """Return ``value`` if it is an instance of ``types`` (or None when ``none``), else raise TypeError.

    The message names the parameter and the expected type, e.g. ``camera = None is a NoneType; expected a
    Camera``.  ``what`` replaces the type names in the message (``"a Terrain (an object with Z(X, Y))"``).
    """
    if (none and value is None) or isinstance(value, types):
        return value
    expected = what or f"a {_type_names(types)}"
    raise TypeError(f"{name} = {value!r:.60} is a {type(value).__name__}; expected {expected}"
                    + (" or None" if none else ""))


def check_choice(name: str, value, choices):
    """Return ``value`` if it is one of ``choices`` (strings compared exactly), else raise ValueError listing them."""
    try:
        ok = value in choices
    except TypeError:
        ok = False
    if not ok or (isinstance(value, float) and math.isnan(value)):
        raise ValueError(f"{name} = {value!r:.60} is not one of the valid choices: "
                         + ", ".join(repr(c) for c in choices))
    return value


def check_work_size(name: str, value, n: float, *, limit: float = MAX_WORK, what: str = "elements"):
    """Refuse a step or count for which the work (``n`` elements) would exceed ``limit``.

    ``value`` is the parameter the student gave (a step in mm, a count); ``n`` the number of elements it asks
    for.  ValueError names the parameter, its value and the limit.
    """
    if not (n <= limit):  # also NaN
        raise ValueError(f"{name} = {value!r:.40} would need {n:.3g} {what}; the valid range keeps it at most "
                         f"{limit:.3g} (a larger step or a smaller count)")
    return value


def check_values(name: str, value, lo: float = -math.inf, hi: float = math.inf, *, lo_open: bool = False,
                 hi_open: bool = False, unit: str = "", max_size: int = MAX_WORK):
    """A scalar or array of numbers, every one finite and within the range: a float (scalar given) or ndarray.

    The array form of :func:`check_range` for the vectorised formulas (``relief_displacement(r_mm, h_m, H_m)``).
    """
    import numpy as np

    if isinstance(value, (int, float, Real)) and not isinstance(value, bool):
        return check_range(name, value, lo, hi, lo_open=lo_open, hi_open=hi_open, unit=unit)
    a = check_finite_array(name, value, max_size=max_size)
    if a.size:
        bad_lo = a <= lo if lo_open else a < lo
        bad_hi = a >= hi if hi_open else a > hi
        bad = bad_lo | bad_hi
        if bad.any():
            x = float(a[bad].ravel()[0])
            raise ValueError(f"{name} contains {_fmt(x)}, outside the valid range "
                             f"{_describe(name, lo, hi, lo_open, hi_open, unit)}")
    return a if a.ndim else float(a)


def check_optional(name: str, value, check, *args, **kwargs):
    """``None`` passes through (the documented default); anything else goes to ``check(name, value, …)``."""
    return None if value is None else check(name, value, *args, **kwargs)


# ----------------------------------------------------------------------------------------- declarative entry checks
class Spec:
    """A check of one argument for :func:`checked`: ``spec(name, value)`` raises by name or returns."""

    def __init__(self, fn, *args, **kwargs):
        self.fn, self.args, self.kwargs = fn, args, kwargs

    def __call__(self, name, value):
        self.fn(name, value, *self.args, **self.kwargs)


def points(dim: int = 2, *, min_points: int = 0) -> Spec:
    """Points (k, dim) or one point (dim,), finite (``check_points``)."""
    return Spec(check_points, dim=dim, min_points=min_points)


def array(*, ndim: int | None = None, last: int | None = None, min_len: int = 0, max_size: int = MAX_WORK) -> Spec:
    """An array of finite numbers (``check_finite_array``)."""
    return Spec(check_finite_array, ndim=ndim, last=last, min_len=min_len, max_size=max_size)


def values(lo: float = -math.inf, hi: float = math.inf, **kw) -> Spec:
    """A number or an array of numbers, finite and within the range (``check_values``)."""
    return Spec(check_values, lo, hi, **kw)


def number(lo: float = -math.inf, hi: float = math.inf, **kw) -> Spec:
    """One finite number within the range (``check_range``)."""
    return Spec(check_range, lo, hi, **kw)


def whole(lo: int, hi: int) -> Spec:
    """A whole number within [lo, hi] (``check_int_range``)."""
    return Spec(check_int_range, lo, hi)


def of_type(types, *, what: str | None = None, none: bool = False) -> Spec:
    """An instance of ``types`` (``check_type``)."""
    return Spec(check_type, types, what=what, none=none)


def one_of(*choices) -> Spec:
    """One of the given choices (``check_choice``)."""
    return Spec(check_choice, choices)


def _check_terrain(name, value, none=False, number_ok=True):
    if (none and value is None) or (number_ok and isinstance(value, Real) and not isinstance(value, bool)):
        if value is not None:
            check_range(name, value, -1e5, 1e5, unit="m")
        return
    if not callable(getattr(value, "height", None)):
        raise TypeError(f"{name} = {value!r:.60} is a {type(value).__name__}; expected a terrain (an object with "
                        "height(X, Y), z_min_m and z_max_m" + (", a height in metres" if number_ok else "")
                        + (" or None)" if none else ")"))


def terrain(*, none: bool = False, number_ok: bool = True) -> Spec:
    """A terrain (an object with ``height(X, Y)``), a height in metres (``number_ok``) or None (``none``)."""
    return Spec(_check_terrain, none=none, number_ok=number_ok)


def _check_seq(name, value, item, min_len, max_len):
    if value is None or isinstance(value, (str, bytes)) or not hasattr(value, "__len__"):
        raise TypeError(f"{name} = {value!r:.60} is a {type(value).__name__}; expected a sequence")
    if not (min_len <= len(value) <= max_len):
        raise ValueError(f"{name} has {len(value)} item(s); the valid range is {min_len} ≤ len({name}) ≤ {max_len}")
    if item is not None:
        for k, v in enumerate(value):
            item(f"{name}[{k}]", v)


def sequence(item: Spec | None = None, *, min_len: int = 0, max_len: int = 10**6) -> Spec:
    """A sequence (list, tuple, array) of ``min_len``… items, each passing ``item``."""
    return Spec(_check_seq, item, min_len, max_len)


def _check_names(name, value, min_len):
    if value is None or isinstance(value, (str, bytes)) or not hasattr(value, "__len__"):
        raise TypeError(f"{name} = {value!r:.60} is a {type(value).__name__}; expected a sequence of point names")
    for k, v in enumerate(value):
        if not isinstance(v, (str, int)) or isinstance(v, bool):
            raise TypeError(f"{name}[{k}] = {v!r:.40} is a {type(v).__name__}; expected a point name (str)")
    if len(value) < min_len:
        raise ValueError(f"{name} has {len(value)} name(s); the valid range is at least {min_len}")


def names(*, min_len: int = 0) -> Spec:
    """A sequence of point names (strings or whole numbers)."""
    return Spec(_check_names, min_len)


def optional(spec) -> Spec:
    """``spec``, or None."""
    spec = spec if isinstance(spec, Spec) else of_type(spec)
    return Spec(lambda name, value: None if value is None else spec(name, value))


def checked(**specs):
    """Decorator: check the named arguments of a public function at its entry, before any work.

    ``specs`` maps parameter names to a :class:`Spec` (``points(2)``, ``values(0)``, …) or a class (a
    ``check_type``).  Only arguments actually passed are checked (defaults are valid by construction), with
    one dictionary look-up per argument: cheap enough for every public entry.  The signature is kept
    (``inspect.signature`` follows ``__wrapped__``).
    """
    import functools
    import inspect

    specs = {k: (v if isinstance(v, Spec) else of_type(v)) for k, v in specs.items()}

    def deco(fn):
        params = list(inspect.signature(fn).parameters.values())
        unknown = set(specs) - {p.name for p in params}
        if unknown:
            raise TypeError(f"checked: {fn.__qualname__} has no parameter(s) {sorted(unknown)}")
        positional = [p.name for p in params if p.kind in (p.POSITIONAL_ONLY, p.POSITIONAL_OR_KEYWORD)]

        @functools.wraps(fn)
        def wrapper(*args, **kwargs):
            for name, value in zip(positional, args):
                spec = specs.get(name)
                if spec is not None:
                    spec(name, value)
            for name, value in kwargs.items():
                spec = specs.get(name)
                if spec is not None:
                    spec(name, value)
            return fn(*args, **kwargs)

        return wrapper

    return deco


def _check_point(name, value, dim):
    a = check_finite_array(name, value)
    if a.size != dim:
        raise ValueError(f"{name} has shape {a.shape}; expected one point of {dim} coordinates")


def point(dim: int = 2) -> Spec:
    """Exactly one point: ``dim`` finite coordinates."""
    return Spec(_check_point, dim)


def _check_pairs(name, value, min_len=1):
    if value is None or isinstance(value, (str, bytes)) or not hasattr(value, "__len__"):
        raise TypeError(f"{name} = {value!r:.60} is a {type(value).__name__}; "
                        "expected a sequence of (name, name) pairs")
    for k, pr in enumerate(value):
        if isinstance(pr, (str, bytes)) or not hasattr(pr, "__len__") or len(pr) != 2 \
                or not all(isinstance(x, (str, int)) and not isinstance(x, bool) for x in pr):
            raise ValueError(f"{name}[{k}] = {pr!r:.40} is not a pair of point names (name, name)")
    if len(value) < min_len:
        raise ValueError(f"{name} has {len(value)} pair(s); the valid range is at least {min_len}")


def pairs(*, min_len: int = 1) -> Spec:
    """A sequence of at least ``min_len`` (name, name) pairs (bases between named points)."""
    return Spec(_check_pairs, min_len)


def _check_attrs(name, value, attrs, what):
    if not all(hasattr(value, a) for a in attrs):
        raise TypeError(f"{name} = {value!r:.60} is a {type(value).__name__}; expected {what}")


def has_attrs(*attrs: str, what: str) -> Spec:
    """An object with the given attributes (a duck-typed package object from a higher layer), e.g. a Strip."""
    return Spec(_check_attrs, attrs, what)


def _check_shape(name, value, shape, stacked=False):
    a = check_finite_array(name, value)
    if (a.shape[a.ndim - len(shape):] != shape or a.ndim < len(shape)) if stacked else a.shape != shape:
        want = f"(..., {', '.join(map(str, shape))})" if stacked else str(shape)
        raise ValueError(f"{name} has shape {a.shape}; expected {want}")


def shape(*dims: int, stacked: bool = False) -> Spec:
    """A finite array of exactly this shape (a 3×3 rotation, a 4-number window); with ``stacked`` any number of
    leading axes before it (a stack of 2×2 covariances, ``(..., 2, 2)``)."""
    return Spec(_check_shape, tuple(dims), stacked)


def _check_image(name, value, ndim, nan_ok):
    import numpy as np

    if value is None or isinstance(value, (str, bytes)):
        raise TypeError(f"{name} = {value!r:.60} is not an image; expected a 2-D array of grey values")
    try:
        a = np.asarray(value, dtype=float)
    except (TypeError, ValueError):
        raise TypeError(f"{name} = {value!r:.60} is not an image; expected a 2-D array of grey values") from None
    if a.ndim not in ndim or a.size == 0 or a.size > MAX_WORK * 4:
        raise ValueError(f"{name} has shape {a.shape}; expected a non-empty image with {' or '.join(map(str, ndim))} "
                         "dimensions")
    bad = np.isinf(a) if nan_ok else ~np.isfinite(a)
    if bad.any():
        raise ValueError(f"{name} contains {a[bad].ravel()[0]}; grey values must be finite"
                         + (" (NaN marks no data)" if nan_ok else ""))


def image(*ndim: int, nan_ok: bool = True) -> Spec:
    """An image: a non-empty array of 2 (or the given) dimensions; NaN marks no data when ``nan_ok``, ±inf never."""
    return Spec(_check_image, ndim or (2,), nan_ok)


def _check_fill(name, value):
    if not (isinstance(value, Real) and not isinstance(value, bool) and (math.isnan(value) or math.isfinite(value))):
        raise (TypeError if not isinstance(value, Real) else ValueError)(
            f"{name} = {value!r:.40} is not a fill value; expected a finite number or NaN (no data)")


def fill() -> Spec:
    """A fill value for pixels with no data: a finite number or NaN (never ±inf)."""
    return Spec(_check_fill)


def check_broadcast(**arrays):
    """Refuse arrays whose shapes do not broadcast together, naming them (instead of numpy's message)."""
    import numpy as np

    shapes = {k: np.shape(v) for k, v in arrays.items()}
    try:
        np.broadcast_shapes(*shapes.values())
    except ValueError:
        raise ValueError("the shapes of " + ", ".join(f"{k} {s}" for k, s in shapes.items())
                         + " do not match (one value per point)") from None


def _check_indices(name, value, min_len, ndim):
    import numpy as np

    a = check_finite_array(name, value, ndim=ndim, min_len=min_len).ravel()
    if a.size and (np.any(a < 0) or np.any(a != np.round(a))):
        bad = a[(a < 0) | (a != np.round(a))][0]
        raise ValueError(f"{name} contains {bad:g}; every entry must be a whole number ≥ 0 (an index)")


def indices(*, min_len: int = 1, ndim: int | None = 1) -> Spec:
    """An array (1-D unless ``ndim``) of whole numbers ≥ 0 (photo, strip or point indices)."""
    return Spec(_check_indices, min_len, ndim)


def function(what: str = "a function") -> Spec:
    """A callable."""
    return Spec(lambda name, value: None if callable(value) else check_type(name, value, (), what=what))
