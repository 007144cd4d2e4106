"""Every registry demo built in Russian shows no English word: figure texts, legends, keys, tables, status.

Symbols stay as they are (f, m, p_x, RGB, roman numerals of control points); words are caught by the pattern
below, outside mathtext ($…$) and a short allowlist of symbols and abbreviations.  The one part not yet in
Russian is listed in NOT_YET with the reason; the test fails when it grows and when it is fixed (then remove it).
"""

from __future__ import annotations

import html
import importlib
import re

import pytest

from aerophoto import book, i18n

WORD = re.compile(r"\b[A-Za-z]{3,}\b")
ROMAN = re.compile(r"^[IVX]+$")
#: symbols and abbreviations that are the same in both languages (subscripts of symbols, the colour model)
ALLOW = {"max", "min", "tmax", "RGB", "TM", "Bx", "By", "Lx", "Ly", "LS", "TS",
         "data", "snooping"}  # Baarda's "data snooping", named in brackets after the Russian term (chapter 15)
#: what is still English, by chapter, and why (remove the entry once it is translated)
NOT_YET = {
    "02": ("the written conclusion of the quality report is English prose composed by aerophoto.quality (layer 2), "
           "which cannot use the catalogue; its sentences need templates there", 4),
}
DEMOS = [(c.number, d.cls) for c in book.CHAPTERS for d in c.demos]


def _english(text: str) -> list[str]:
    text = re.sub(r"\$[^$]*\$", "", text)
    return [w for w in WORD.findall(text) if w not in ALLOW and not ROMAN.match(w)]


def _shown_texts(demo) -> list[str]:
    out = []
    for a in demo.fig.findobj(lambda a: hasattr(a, "get_text") and type(a).__name__ != "Figure"):
        if a.get_visible() and a.get_text():
            out.append(a.get_text())
    for name in ("table", "legend", "status"):
        s = re.sub(r"<style.*?</style>", "", getattr(demo, name).value, flags=re.S)
        s = re.sub(r"<sub>[^<]*</sub>", "", s)  # a symbol's subscript (m_interp, r_max) is part of the symbol
        out += [html.unescape(x).strip() for x in re.split(r"<[^>]+>", s) if x.strip()]
    return out


@pytest.fixture(autouse=True)
def _russian(monkeypatch):
    monkeypatch.delenv("AEROPHOTO_LANG", raising=False)
    i18n.set_language("ru")
    yield
    i18n.set_language(None)


@pytest.mark.parametrize(("number", "cls"), DEMOS, ids=[f"{n}-{c.rsplit('.', 1)[1]}" for n, c in DEMOS])
def test_a_demo_in_russian_shows_no_english_word(number, cls):
    import matplotlib

    matplotlib.use("Agg")
    module, name = cls.rsplit(".", 1)
    demo = getattr(importlib.import_module(module), name)()
    try:
        demo.widget()
        english = sorted({t for t in _shown_texts(demo) if _english(t)})
    finally:
        demo.close()
    if number in NOT_YET:
        why, n = NOT_YET[number]
        assert 0 < len(english) <= n, f"chapter {number}: {english} (known: {why})"
    else:
        assert not english, f"chapter {number} {name} in Russian shows English: {english}"


def test_units_and_numbers_in_russian():
    """Chapter 00's table in Russian: the unit м, the decimal comma, a true minus, 12 000 grouped, 1200 not."""
    from aerophoto.demos.footprint import FootprintDemo

    demo = FootprintDemo()
    try:
        table = demo.table.value
    finally:
        demo.close()
    assert "<td class='num'>м</td>" in table and "<td class='num'>m</td>" not in table
    assert ">1200<" in table and ">12\u202f000<" in table      # H = f·m = 1200 m; the scale 1:12 000
    assert ">5,24<" in table and ">−2,62<" in table             # on and oc, mm: decimal comma, minus sign
    assert "1,200" not in table and "1200.0" not in table
