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
import re
from numbers import Real

from .._digits import GROUP, MINUS  # the thousands separator (U+202F) and the minus sign (U+2212)
from .._digits import group as _group  # the grouping rule, in the foundation for every layer
from .._digits import scale as _scale

__all__ = ["GROUP", "MINUS", "NBSP", "DASH", "NUMBER", "decimal_mark", "decimals_for", "fmt_number", "fmt_count",
           "fmt_scale", "fmt_percent", "fmt_quantity", "fmt_signed", "fmt_value", "fmt_spec", "fmt_text",
           "parse_number", "numbers_in", "TickFormatter", "localise_ticks"]

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
    _lang(lang)  # checks it: a scale is written the same in both languages
    return _scale(v)  # aerophoto._digits.scale: the one rule (and its error naming m)


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


_SPEC = re.compile(r"^\{?:?(?P<plus>\+)?,?(?:\.(?P<prec>\d+))?(?P<kind>[fgd%]?)\}?$")


def fmt_spec(x, spec: str = "{:.4g}", *, lang=None) -> str:
    """``x`` in the book's format with the precision of a ``str.format`` spec: ``"{:.2f}"`` (2 decimals),
    ``"{:.3g}"`` (3 significant digits, trailing zeros dropped as ``g`` does, never an exponent), ``"{:d}"`` (a
    count), ``"{:.1%}"`` (a percentage), ``"{:+.2f}"`` (a sign always).  A grouping comma in the spec is ignored
    (grouping is the book's rule).  A spec it does not know is a ValueError naming it."""
    m = _SPEC.match(str(spec).strip())
    if m is None:
        raise ValueError(f"spec = {spec!r} is not a number format of the book (e.g. '{{:.2f}}', '{{:.3g}}')")
    prec = None if m.group("prec") is None else int(m.group("prec"))
    kind, plus = m.group("kind") or "g", bool(m.group("plus"))
    v = _finite(x)
    if v is None:
        return DASH
    if kind == "d":
        return fmt_count(round(v), lang=lang)
    if kind == "%":
        return fmt_percent(v * 100, 6 if prec is None else prec, lang=lang, plus=plus)
    if kind == "f":
        return fmt_number(v, 6 if prec is None else prec, lang=lang, plus=plus)
    if math.isinf(v):
        return fmt_number(v, lang=lang)
    sig = max(1, 6 if prec is None else prec)
    decimals = decimals_for(v, sig)
    text = fmt_number(round(v, decimals), decimals, lang=lang, plus=plus)
    mark = decimal_mark(lang)
    return text.rstrip("0").rstrip(mark) if mark in text else text


#: a number as the book writes it, or as Python does (``12 043``, ``−3,5``, ``1200.00``, ``-0.25``, ``1:17 700``'s
#: 17 700); the separators of both languages are read by :func:`parse_number`
NUMBER = (r"(?<![\w.,])[-−+]?(?:\d{1,3}(?:[\u202f\u00a0\u2009 ]\d{3})+|\d+)(?:[.,]\d+)?(?![\w]|[.,]\d)")
_NUMBER_RE = re.compile(NUMBER)
_PY_NUMBER = re.compile(r"(?<![\w.,\u202f\u00a0\u2009])(?P<sign>-)?(?P<int>\d+)(?:\.(?P<frac>\d+))?"
                        r"(?![\w]|[.,]\d|\u202f\d)")


def parse_number(text, *, lang=None) -> float:
    """A number written by this module back into a float: ``"12 043"`` → 12043.0, ``"−3,25"`` → −3.25 (``lang``'s
    decimal mark: a comma in Russian; in English a comma is no mark and a point is), ``"—"`` → NaN, ``"1:17 700"``
    → 17700.0 (the scale's denominator), ``"12,3 %"`` → 12.3.  The tests read every number off a page or a table
    with it.  Text that is no number is a ValueError naming it."""
    s = str(text).strip()
    if s == DASH:
        return math.nan
    core = s[2:] if s.startswith("1:") else s
    core = core.rstrip("%°′″ \u00a0")
    core = core.replace(MINUS, "-")
    for sep in (GROUP, NBSP, "\u2009", " "):
        core = core.replace(sep, "")
    if "," in core:
        if _lang(lang) == "ru" or "." in core:
            core = core.replace(",", "." if "." not in core else "")
        else:
            raise ValueError(f"text = {text!r} has a decimal comma; in English the book writes a point")
    try:
        return float(core)
    except ValueError:
        raise ValueError(f"text = {text!r} is not a number in the book's format") from None


def numbers_in(text, *, lang=None) -> list:
    """Every number in ``text`` (a title, a table's text, a page), in order, as floats (:func:`parse_number`)."""
    lang = _lang(lang)
    out = []
    for m in _NUMBER_RE.finditer(str(text)):
        token = m.group(0)
        if lang == "en" and "," in token:  # "1,2" in English: two numbers in a list
            out += [parse_number(p, lang=lang) for p in token.split(",") if p.strip("+-−")]
        else:
            out.append(parse_number(token, lang=lang))
    return out


def fmt_text(text, *, lang=None) -> str:
    """Numbers inside a text, as Python writes them, rewritten in the book's format: ``"-0.00"`` → ``"0.00"``,
    ``"12043.5"`` → ``"12 043.5"``, ``"-1.80 %"`` → ``"−1,80 %"`` in Russian.  Each keeps its own decimals; a
    number already grouped, a code with a leading zero (``007``) and a number glued to a word (``p_x2``, ``1a``)
    are left as they are.  For a table cell or a label that carries numbers from elsewhere (a catalogue, a task)."""
    if not isinstance(text, str) or not any(c.isdigit() for c in text):
        return text
    lang = _lang(lang)

    def one(m):
        whole, frac = m.group("int"), m.group("frac")
        if len(whole) > 1 and whole.startswith("0"):
            return m.group(0)
        value = float(("-" if m.group("sign") else "") + whole + ("." + frac if frac else ""))
        return fmt_number(value, len(frac or ""), lang=lang)

    return _PY_NUMBER.sub(one, text)


def _tick_text(text: str, lang: str) -> str:
    """A tick label matplotlib wrote (``"−1.5"``, ``"12000"``, ``"$\\mathdefault{10^{3}}$"``) in the book's format."""
    if "$" in text or not text:
        return text
    return fmt_text(text.replace(MINUS, "-"), lang=lang)


def TickFormatter(lang=None):  # noqa: N802 - a class factory: matplotlib is imported only when it is used
    """A matplotlib tick formatter writing the book's format: matplotlib's own choice of ticks and decimals
    (:class:`matplotlib.ticker.ScalarFormatter`), with ``lang``'s decimal mark, a true minus and the narrow-space
    grouping from five digits (``12 000``).  ``lang`` fixed at construction (default: the language in use)."""
    from matplotlib.ticker import ScalarFormatter

    lang = _lang(lang)

    class _BookFormatter(ScalarFormatter):
        _aerophoto_numfmt = lang

        def __call__(self, x, pos=None):
            return _tick_text(super().__call__(x, pos), lang)

        def get_offset(self):
            return _tick_text(super().get_offset(), lang)

        def format_data_short(self, value):
            return _tick_text(super().format_data_short(value), lang)

    return _BookFormatter(useOffset=False)


def localise_ticks(fig, *, lang=None) -> int:
    """Give every plain numeric axis of ``fig`` (a ScalarFormatter's, linear) the book's tick format
    (:func:`TickFormatter`); log axes, dates, fixed and custom labels are left alone.  Returns how many changed.
    The live demos and :func:`aerophoto.plots.static` call it once on a built figure."""
    from matplotlib.ticker import ScalarFormatter

    if fig is None:
        return 0
    lang = _lang(lang)
    changed = 0
    for ax in getattr(fig, "axes", ()):
        for axis in (getattr(ax, "xaxis", None), getattr(ax, "yaxis", None)):
            if axis is None or axis.get_scale() != "linear":
                continue
            f = axis.get_major_formatter()
            if type(f) is ScalarFormatter or (getattr(f, "_aerophoto_numfmt", None) not in (None, lang)):
                axis.set_major_formatter(TickFormatter(lang))
                changed += 1
    return changed
