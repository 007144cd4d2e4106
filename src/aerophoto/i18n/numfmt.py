"""One number format for the whole book: demos, tables, checks, the report.

The rules (the same in both languages, except the decimal mark):

* the decimal mark of the language: a comma in Russian (``0,67``), a point in English (``0.67``);
* digits grouped by three with a narrow no-break space (U+202F) from five digits of the whole part on
  (``12 043``, ``1 200 000``), never with a comma; a four-digit number stays whole (``2706``), as the
  Russian standard (ГОСТ 8.417) and the SI brochure write it;
* a true minus sign (U+2212, ``−3,2``), and never a signed zero: a value that rounds to zero prints ``0,00``;
* a count is a whole number (``70``, not ``70.00``); a scale is ``1:10 000``;
* the precision is the value's own: ``decimals`` digits after the mark, or ``sig`` significant digits
  (never scientific notation: ``sig=4`` gives ``6 004 123`` for a coordinate, not ``6.004e+06``);
* a missing value (None, NaN) prints an em dash.

Every function takes ``lang`` (``"en"``/``"ru"``; default: the language in use, :func:`aerophoto.i18n.get_language`)
and returns a ``str``.  Nothing here reads a locale of the machine: the same value prints the same on every
machine.

>>> fmt_number(11859.2, 0, lang="ru")
'11\u202f859'
>>> fmt_number(-0.004, 2, lang="ru")
'0,00'
>>> fmt_scale(17700)
'1:17\u202f700'
"""

from __future__ import annotations

import math
from numbers import Real

__all__ = ["GROUP", "MINUS", "NBSP", "DASH", "decimal_mark", "decimals_for", "fmt_number", "fmt_count",
           "fmt_scale", "fmt_percent", "fmt_quantity", "fmt_signed", "fmt_value"]

#: the thousands separator: a narrow no-break space
GROUP = "\u202f"
#: the minus sign
MINUS = "\u2212"
#: a no-break space (between a number and its unit)
NBSP = "\u00a0"
#: what a missing value prints as
DASH = "—"


def _lang(lang) -> str:
    if lang is None:
        from . import get_language

        return get_language()
    key = str(lang).strip().lower()
    if key not in ("en", "ru"):
        raise ValueError(f"lang = {lang!r} is not a language of the book; expected one of ['en', 'ru']")
    return key


def decimal_mark(lang=None) -> str:
    """``","`` in Russian, ``"."`` in English."""
    return "," if _lang(lang) == "ru" else "."


def _finite(x):
    """``x`` as a float, or None when it is missing (None, NaN, not a number)."""
    if x is None or isinstance(x, bool):
        return None
    if getattr(x, "size", 1) == 1 and hasattr(x, "item"):
        x = x.item()
    if not isinstance(x, Real):
        try:
            x = float(x)
        except (TypeError, ValueError):
            return None
    x = float(x)
    return None if math.isnan(x) else x


def decimals_for(x, sig: int) -> int:
    """The digits after the decimal mark that give ``x`` ``sig`` significant digits (0 for large numbers)."""
    if isinstance(sig, bool) or not isinstance(sig, int) or sig < 1:
        raise ValueError(f"sig = {sig!r} is not valid; expected a whole number ≥ 1")
    x = _finite(x)
    if x is None or x == 0 or math.isinf(x):
        return max(sig - 1, 0)
    return max(0, sig - 1 - math.floor(math.log10(abs(x))))


def _group(whole: str) -> str:
    if len(whole) < 5:
        return whole
    head = len(whole) % 3 or 3
    parts = [whole[:head]] + [whole[i:i + 3] for i in range(head, len(whole), 3)]
    return GROUP.join(parts)


def fmt_number(x, decimals: int | None = None, *, sig: int | None = None, lang=None, group: bool = True,
               plus: bool = False) -> str:
    """``x`` in the book's format, with ``decimals`` digits after the mark or ``sig`` significant digits.

    Neither given: 4 significant digits, at most 6 decimals (a general-purpose default for tables).
    ``group=False`` keeps the whole part ungrouped (a record-book or a photo number); ``plus`` writes ``+``
    before a positive value (corrections, deviations).
    """
    lang = _lang(lang)
    v = _finite(x)
    if v is None:
        return DASH
    if math.isinf(v):
        return ("" if v > 0 else MINUS) + "∞"
    if decimals is None:
        decimals = min(decimals_for(v, sig or 4), 6)
    elif isinstance(decimals, bool) or not isinstance(decimals, int) or decimals < 0:
        raise ValueError(f"decimals = {decimals!r} is not valid; expected a whole number ≥ 0")
    text = f"{abs(v):.{decimals}f}"
    negative = v < 0 and any(c not in "0." for c in text)  # no −0,00
    whole, _, frac = text.partition(".")
    whole = _group(whole) if group else whole
    body = whole + (decimal_mark(lang) + frac if frac else "")
    if negative:
        return MINUS + body
    if plus and v > 0 and any(c not in "0." for c in text):
        return "+" + body
    return body


def fmt_signed(x, decimals: int | None = None, *, sig: int | None = None, lang=None) -> str:
    """A value with its sign always written (``+0,12``, ``−0,05``, ``0,00``)."""
    return fmt_number(x, decimals, sig=sig, lang=lang, plus=True)


def fmt_count(n, *, lang=None) -> str:
    """A count as a whole number (``70``; ``12 043``); a value that is not whole is an error naming ``n``."""
    v = _finite(n)
    if v is None:
        return DASH
    if not float(v).is_integer():
        raise ValueError(f"n = {n!r} is not a whole number; a count prints as one")
    return fmt_number(v, 0, lang=lang)


def fmt_scale(m, *, lang=None) -> str:
    """The scale 1/m as ``1:17 700`` (m, the scale denominator, to the nearest whole)."""
    v = _finite(m)
    if v is None:
        return DASH
    if not v > 0 or math.isinf(v):
        raise ValueError(f"m = {m!r} is not a scale denominator; expected a finite number > 0")
    return "1:" + fmt_number(round(v), 0, lang=lang)


def fmt_percent(x, decimals: int = 1, *, lang=None, plus: bool = False) -> str:
    """A percentage, ``12,3 %`` (a no-break space before the sign, as both languages' standards write it)."""
    return fmt_number(x, decimals, lang=lang, plus=plus) + NBSP + "%"


def fmt_quantity(x, unit: str, decimals: int | None = None, *, sig: int | None = None, lang=None) -> str:
    """A value with its unit, ``11 859 м`` (the unit in the language: :func:`aerophoto.i18n.translate_unit`)."""
    from . import language, translate_unit

    lang = _lang(lang)
    with language(lang):
        u = translate_unit(unit)
    number = fmt_number(x, decimals, sig=sig, lang=lang)
    if not u:
        return number
    if u in ("°", "′", "″"):
        return number + u
    return number + NBSP + u


def fmt_value(x, *, decimals: int | None = None, sig: int | None = None, lang=None) -> str:
    """Anything a table cell may hold: a whole number (int, or a float that is whole and large) prints whole,
    a real number by :func:`fmt_number`, a bool as yes/no in the language, text unchanged, None/NaN as a dash."""
    lang = _lang(lang)
    if x is None:
        return DASH
    if isinstance(x, bool) or type(x).__name__ in ("bool_", "bool"):
        yes, no = ("да", "нет") if lang == "ru" else ("yes", "no")
        return yes if bool(x) else no
    if isinstance(x, str):
        return x
    if isinstance(x, Real) and not isinstance(x, float) and float(x).is_integer():
        return fmt_number(x, 0, lang=lang)
    v = _finite(x)
    if v is None:
        return DASH if isinstance(x, Real) or hasattr(x, "dtype") else str(x)
    if hasattr(x, "dtype") and getattr(x.dtype, "kind", "") in "iu":
        return fmt_number(v, 0, lang=lang)
    return fmt_number(v, decimals, sig=sig, lang=lang)
