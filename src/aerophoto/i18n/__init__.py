"""Every user-facing string in English and Russian: one catalogue, keyed by the English text.

The book is written in English with the Russian terms beside them; what the
student *operates* — the live demos' sliders, groups, titles and tables, the
figures' labels, the check messages and the instructor's command line — speaks
either language::

    import aerophoto
    v = aerophoto.setup(RECORD_BOOK, lang="ru")     # remembered for later chapters

    from aerophoto.i18n import t
    t("f, mm")                                       # "f, мм" in Russian, "f, mm" in English
    t("{name}: correct", name="H_m")                 # placeholders: str.format

The English text itself is the message's id, so English output is the code's
own string, byte for byte, and a string without a Russian entry falls back to
it.  The catalogue is split by area (:mod:`.demos`, :mod:`.figures`,
:mod:`.live`, :mod:`.checks`, :mod:`.slips`, :mod:`.cli`, :mod:`.chapters`); :mod:`.glossary` holds the key
terms EN ↔ RU with the guide's sections (the glossary page is generated from
it).

Which language: ``$AEROPHOTO_LANG`` (``en`` or ``ru``; tests and servers) wins,
else the last :func:`set_language` (``aerophoto.setup(..., lang=...)`` calls it,
and with no ``lang`` applies the one remembered in ``student.json``), else
English.  Importing reads no file and changes nothing.
"""

from __future__ import annotations

import os
import string

__all__ = ["LANGUAGES", "DEFAULT", "t", "_", "set_language", "get_language", "language", "catalogue",
           "translate", "translate_unit", "translate_units_in", "translate_options", "translate_figure", "placeholders", "has"]

#: the languages of the book
LANGUAGES = ("en", "ru")
#: the language when nothing else is said
DEFAULT = "en"
_ENV = "AEROPHOTO_LANG"
_current: str | None = None
_catalogue: dict | None = None


def _valid(lang) -> str:
    key = str(lang).strip().lower()
    if key not in LANGUAGES:
        raise ValueError(f"lang = {lang!r} is not a language of the book; expected one of {list(LANGUAGES)}")
    return key


def get_language() -> str:
    """The language in use: ``$AEROPHOTO_LANG``, else the one set last, else English."""
    env = os.environ.get(_ENV, "").strip().lower()
    if env in LANGUAGES:
        return env
    return _current or DEFAULT


def set_language(lang) -> str:
    """Switch the language of this process (``"en"`` or ``"ru"``); returns it.  ``None`` returns to the default."""
    global _current
    _current = None if lang is None else _valid(lang)
    return get_language()


class language:  # noqa: N801 - used as a context manager, reads like a function
    """``with language("ru"): ...`` — a language for a block (tests), the previous one restored after it."""

    def __init__(self, lang):
        self.lang = _valid(lang)

    def __enter__(self):
        global _current
        self._saved, self._env = _current, os.environ.pop(_ENV, None)
        _current = self.lang
        return self.lang

    def __exit__(self, *exc):
        global _current
        _current = self._saved
        if self._env is not None:
            os.environ[_ENV] = self._env
        return False


def catalogue() -> dict:
    """English → Russian, every area merged (built on first use)."""
    global _catalogue
    if _catalogue is None:
        from . import chapters, checks, cli, demos, figures, live, slips

        merged: dict = {}
        for part in (chapters.MESSAGES, demos.MESSAGES, figures.MESSAGES, live.MESSAGES, checks.MESSAGES, slips.MESSAGES, cli.MESSAGES):
            merged.update(part)
        _catalogue = merged
    return _catalogue


def has(text: str) -> bool:
    """Whether ``text`` has a Russian entry."""
    return text in catalogue()


def translate(text, lang: str | None = None):
    """``text`` in ``lang`` (default: the language in use); anything not in the catalogue comes back unchanged."""
    lang = lang or get_language()
    if lang == "en" or not isinstance(text, str) or not text:
        return text
    return catalogue().get(text, text)


class _BookFormatter(string.Formatter):
    """``str.format`` with the book's number format for a real number under a plain ``f``, ``g`` or ``%`` spec
    (``{v:.2f}`` → ``0,25`` in Russian, ``−3.5``, never ``−0.00``, ``12 043``: :func:`.numfmt.fmt_spec`); any
    other field (text, a count without a spec, ``{i:02d}``, a width) as Python formats it."""

    _PLAIN = None

    def format_field(self, value, format_spec):
        import re
        from numbers import Real

        if _BookFormatter._PLAIN is None:
            _BookFormatter._PLAIN = re.compile(r"^\+?(?:\.\d+)?[fg%]$")
        if (format_spec and isinstance(value, Real) and not isinstance(value, bool)
                and _BookFormatter._PLAIN.match(format_spec)):
            from .numfmt import fmt_spec

            return fmt_spec(value, "{:" + format_spec + "}")
        return super().format_field(value, format_spec)


_FORMATTER = _BookFormatter()


def t(key: str, /, **fmt) -> str:
    """The message ``key`` (its English text) in the language in use, formatted with ``fmt`` (``str.format``; a
    real number under an ``f``/``g``/``%`` spec in the book's number format, :mod:`.numfmt`)."""
    text = translate(key)
    return _FORMATTER.format(text, **fmt) if fmt else text


_ = t


def translate_unit(unit: str) -> str:
    """A task's unit (``"mm"``, ``"km"``) in the language in use; unknown units unchanged."""
    if get_language() == "en" or not unit:
        return unit
    from .checks import UNITS

    return UNITS.get(unit, unit)


#: units that follow a number in a text written by code (a table cell from a physics module, a figure text)
_UNIT_AFTER_NUMBER = None
#: the units this rewrites beyond the tasks' own (:data:`aerophoto.i18n.checks.UNITS`)
_MORE_UNITS = {"cm": "см", "km²": "км²", "km/h": "км/ч", "px": "пикс.", "m/s": "м/с"}


def translate_units_in(text):
    """A text's units that follow a number in the language in use: ``"f = 100 mm"`` → ``"f = 100 мм"``,
    ``"0.5 m"`` → ``"0.5 м"`` in Russian (a unit only after a number and a space: a lone "m" is a symbol).  English
    and anything not a str come back unchanged."""
    global _UNIT_AFTER_NUMBER
    if get_language() == "en" or not isinstance(text, str) or not any(c.isdigit() for c in text):
        return text
    import re

    from .checks import UNITS

    units = {**{k: v for k, v in UNITS.items() if k.isalpha() or k == "µm"}, **_MORE_UNITS}
    if _UNIT_AFTER_NUMBER is None:
        names = sorted(units, key=len, reverse=True)
        _UNIT_AFTER_NUMBER = re.compile(r"(?<=\d)([ \u00a0])(" + "|".join(re.escape(u) for u in names) +
                                        r")(?![\w²/])")
    return _UNIT_AFTER_NUMBER.sub(lambda m: m.group(1) + units[m.group(2)], text)


def translate_options(options) -> list:
    """A dropdown's options with translated labels: ``(label, value)`` pairs, or plain values (kept as values)."""
    if get_language() == "en":
        return list(options)
    out = []
    for o in options:
        if isinstance(o, tuple):
            out.append((translate(o[0]), o[1]))
        elif isinstance(o, str) and has(o):
            out.append((translate(o), o))
        else:
            out.append(o)
    return out


def translate_figure(fig) -> int:
    """Translate a figure's fixed texts in place (titles, axis labels, legends, annotations, fixed tick labels).

    Called once after a live demo builds its figure; a no-op in English.  Returns how many texts changed.
    """
    if fig is None or get_language() == "en":
        return 0
    changed = 0
    for art in fig.findobj(lambda a: hasattr(a, "get_text") and hasattr(a, "set_text")):
        s = art.get_text()
        new = translate(s)
        if new != s:
            art.set_text(new)
            changed += 1
    for ax in getattr(fig, "axes", ()):
        for axis in (getattr(ax, "xaxis", None), getattr(ax, "yaxis", None)):
            fmt = axis.get_major_formatter() if axis is not None else None
            seq = getattr(fmt, "seq", None)
            if isinstance(seq, (list, tuple)) and any(isinstance(s, str) and has(s) for s in seq):
                fmt.seq = [translate(s) for s in seq]
                changed += 1
            elif callable(getattr(fmt, "func", None)) and not getattr(fmt.func, "_aerophoto_i18n", False):
                # fixed tick labels (``set_yticks(y, labels)``: a FuncFormatter over the list) that are words
                if any(has(lab.get_text()) for lab in axis.get_ticklabels()):
                    def func(x, pos=None, _inner=fmt.func):
                        return translate(_inner(x, pos))

                    func._aerophoto_i18n = True
                    fmt.func = func
                    changed += 1
    return changed


def placeholders(text: str) -> list:
    """The ``str.format`` fields of ``text`` (name, conversion, spec), in order — the same in both languages."""
    return sorted((name, conv or "", spec or "") for _, name, spec, conv in string.Formatter().parse(text)
                  if name is not None)
