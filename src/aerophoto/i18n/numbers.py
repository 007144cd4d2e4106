"""One way to write a number on screen, in English and in Russian: :func:`fmt`, :func:`fmt_count`, :func:`fmt_scale`.

The book's rule, the same in both languages except for the decimal marker (SI brochure §5.4.4, ГОСТ 8.417):

* digits are grouped by three with a narrow no-break space (U+202F) — ``12 043``, ``1:12 000`` — never with a
  comma or a dot, so that "1,200" cannot be read as one point two in Russian nor twelve hundred in English; a
  number of four digits before the marker is not split (``1200``, ``4096``);
* the decimal marker is a point in English (``0.25``) and a comma in Russian (``0,25``);
* a negative number has a true minus sign U+2212 (``−3.5``); a value that rounds to zero has no sign
  (never ``−0.00``);
* a count is a whole number (``70``, never ``70.00``);
* a missing value (NaN, None) is an em dash ``—``.

The grouping space does not break at the end of a line (it is a no-break space), so a narrow table column never
splits ``12 043`` in two.

    >>> fmt(12043.2, 0, lang="en"), fmt(-0.004, 2, lang="en"), fmt(0.25, 2, lang="ru")
    ('12\u202f043', '0.00', '0,25')
"""

from __future__ import annotations

import math
import re

__all__ = ["fmt", "fmt_count", "fmt_scale", "fmt_spec", "localise", "MINUS", "GROUP", "DASH"]

#: the minus sign (U+2212), not the hyphen
MINUS = "\u2212"
#: the digit-group separator: narrow no-break space (U+202F)
GROUP = "\u202f"
#: a missing value
DASH = "—"
#: group the digits before the decimal marker from this many digits on (four stay whole: 1200)
GROUP_FROM_DIGITS = 5


def _lang(lang) -> str:
    if lang is None:
        from . import get_language

        return get_language()
    return "ru" if str(lang).lower() == "ru" else "en"


def _missing(x) -> bool:
    if x is None:
        return True
    try:
        return math.isnan(float(x))
    except (TypeError, ValueError):
        return False


def _group(digits: str) -> str:
    if len(digits) < GROUP_FROM_DIGITS:
        return digits
    head = len(digits) % 3 or 3
    return GROUP.join([digits[:head]] + [digits[i:i + 3] for i in range(head, len(digits), 3)])


def _assemble(negative: bool, int_part: str, frac_part: str, lang: str) -> str:
    if negative and set(int_part + frac_part) <= {"0"}:
        negative = False  # −0.00 → 0.00
    dec = "," if lang == "ru" else "."
    out = _group(int_part) + (dec + frac_part if frac_part else "")
    return (MINUS if negative else "") + out


def fmt(x, digits: int | None = None, *, sig: int | None = None, lang: str | None = None, plus: bool = False) -> str:
    """``x`` written by the book's rule (see the module notes).

    Parameters
    ----------
    x : float
        The number.  NaN and None give ``—``; ±inf ``∞``/``−∞``.
    digits : int, optional
        Decimals after the marker (``fmt(3.14159, 2)`` → ``3.14``).
    sig : int, optional
        Significant digits instead (``fmt(0.012345, sig=3)`` → ``0.0123``; ``fmt(12043, sig=3)`` → ``12 000``);
        never an exponent.  With neither, ``digits=2`` for a fraction and ``0`` for a whole number.
    lang : {"en", "ru"}, optional
        Default: the language in use (:func:`aerophoto.i18n.get_language`).
    plus : bool
        Write ``+`` before a positive number (differences, shifts).
    """
    if digits is not None and (not isinstance(digits, (int,)) or isinstance(digits, bool) or not 0 <= digits <= 12):
        raise ValueError(f"digits = {digits!r} is not a whole number of decimals in 0 … 12")
    if sig is not None and (not isinstance(sig, int) or isinstance(sig, bool) or not 1 <= sig <= 15):
        raise ValueError(f"sig = {sig!r} is not a number of significant digits in 1 … 15")
    lang = _lang(lang)
    if _missing(x):
        return DASH
    v = float(x)
    if math.isinf(v):
        return ("" if v > 0 else MINUS) + "∞"
    if digits is None:
        if sig is not None:
            if v == 0:
                digits = max(sig - 1, 0)
            else:
                mag = math.floor(math.log10(abs(v)))
                digits = max(sig - 1 - mag, 0)
                if digits == 0 and mag + 1 > sig:  # round off whole digits too: 12043 (3 sig.) → 12 000
                    q = 10.0 ** (mag + 1 - sig)
                    v = round(v / q) * q
        else:
            digits = 0 if float(v).is_integer() else 2
    s = f"{abs(v):.{digits}f}"
    int_part, _, frac_part = s.partition(".")
    out = _assemble(v < 0, int_part, frac_part, lang)
    if plus and v > 0 and out.strip("0.,") != "":
        out = "+" + out
    return out


def fmt_count(n, *, lang: str | None = None) -> str:
    """A count (photos, strips, nodes): a whole number, grouped (``1225``, ``12 043``); NaN → ``—``."""
    if _missing(n):
        return DASH
    v = float(n)
    if not math.isfinite(v):
        raise ValueError(f"n = {n!r} is not a finite count")
    return fmt(round(v), 0, lang=lang)


def fmt_scale(m, *, lang: str | None = None) -> str:
    """A scale 1:m with its denominator grouped: ``1:12 000`` (in both languages)."""
    return "1:" + fmt_count(m, lang=lang)


_SPEC = re.compile(r"^\{?:?(?P<plus>\+)?(?P<group>,)?(?:\.(?P<prec>\d+))?(?P<kind>[fgdn%]?)\}?$")


def fmt_spec(x, spec: str = "{:.4g}", *, lang: str | None = None) -> str:
    """``x`` written by the book's rule with the precision of a ``str.format`` spec (``"{:.2f}"``, ``"{:,.3g}"``,
    ``".1f"``, ``"{:d}"``): ``f`` → decimals, ``g`` → significant digits (no exponent), ``d`` → a count.

    The grouping comma of a spec is ignored: grouping is the book's rule.  A spec it does not know raises
    ValueError naming it.
    """
    m = _SPEC.match(spec.strip())
    if m is None:
        raise ValueError(f"spec = {spec!r} is not a number format this book writes (e.g. '{{:.2f}}', '{{:.3g}}')")
    prec = m.group("prec")
    kind = m.group("kind") or ("g" if prec is not None else "")
    plus = bool(m.group("plus"))
    if kind == "d":
        return fmt_count(x, lang=lang)
    if kind == "f":
        return fmt(x, int(prec) if prec is not None else 6, lang=lang, plus=plus)
    if kind == "%":
        return fmt(None if _missing(x) else float(x) * 100, int(prec) if prec is not None else 6, lang=lang) + " %"
    if kind in ("g", "n"):
        p = int(prec) if prec is not None else 6
        if _missing(x):
            return DASH
        v = float(x)
        if v == 0:
            return "0"
        # like "g": at most p significant digits, trailing zeros dropped
        mag = math.floor(math.log10(abs(v)))
        decimals = max(p - 1 - mag, 0)
        # a whole number longer than p digits keeps its digits (12 043, not 1.204e+04 nor 12 040)
        out = fmt(round(v, decimals), decimals, lang=lang, plus=plus)
        dec = "," if _lang(lang) == "ru" else "."
        if dec in out:
            out = out.rstrip("0").rstrip(dec)
        return out
    return fmt(x, lang=lang, plus=plus)


# a cell that is a number as Python writes it: -12043.5, 1,200.00, 11934.0, 12 043 (not 1a–4a, §6.1, 2.5e-05)
_NUMBER = re.compile(r"^(?P<scale>1:)?(?P<sign>[-−])?(?P<int>\d{1,3}(?:[, \u202f\u2009]\d{3})+|\d+)(?:\.(?P<frac>\d+))?(?P<suffix>\s?[%°″‰])?$")


def localise(text: str, *, lang: str | None = None) -> str:
    """A table cell that is a plain number, rewritten by the book's rule (``-0.00`` → ``0.00``, ``1,200.00`` →
    ``1200.00``, ``12043`` → ``12 043``, hyphen → minus, the decimal comma in Russian); any other text unchanged.

    A scale ``1:12000`` → ``1:12 000``; a sign after the number stays (``-1.80 %`` → ``−1.80 %``).  Only a whole cell is a number: ``1a–4a``, ``(6.1)`` and text with words stay as they are.
    """
    if not isinstance(text, str) or not text:
        return text
    m = _NUMBER.match(text.strip())
    if m is None:
        return text
    int_part = re.sub(r"[, \u202f\u2009]", "", m.group("int"))
    if len(int_part) > 1 and int_part.startswith("0"):
        return text  # 007: a code, not a number
    return ((m.group("scale") or "") + _assemble(bool(m.group("sign")), int_part, m.group("frac") or "", _lang(lang))
            + (m.group("suffix") or ""))
