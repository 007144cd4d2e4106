"""The book's one way to write numbers (aerophoto.i18n.numbers): grouping, minus, decimal marker, counts."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from aerophoto import plots
from aerophoto.i18n import language
from aerophoto.i18n.numbers import GROUP, MINUS, fmt, fmt_count, fmt_scale, fmt_spec, localise

NB = GROUP  # narrow no-break space


@pytest.mark.parametrize("x, digits, en, ru", [
    (12043.2, 0, f"12{NB}043", f"12{NB}043"),
    (1200.0, 2, "1200.00", "1200,00"),          # four digits are not split
    (123456.789, 1, f"123{NB}456.8", f"123{NB}456,8"),
    (-3.5, 1, f"{MINUS}3.5", f"{MINUS}3,5"),
    (-0.004, 2, "0.00", "0,00"),                # never −0.00
    (0.25, 2, "0.25", "0,25"),
    (-1234567.0, 0, f"{MINUS}1{NB}234{NB}567", f"{MINUS}1{NB}234{NB}567"),
])
def test_fmt_both_languages(x, digits, en, ru):
    assert fmt(x, digits, lang="en") == en
    assert fmt(x, digits, lang="ru") == ru


def test_significant_digits_and_specs():
    assert fmt(0.012345, sig=3, lang="en") == "0.0123"
    assert fmt(12043, sig=3, lang="en") == f"12{NB}000"
    assert fmt_spec(11934.0, "{:.4g}", lang="en") == f"11{NB}934"   # no exponent, no lost digit
    assert fmt_spec(1.5, "{:,.3g}", lang="ru") == "1,5"
    assert fmt_spec(2.0, "{:.3g}", lang="en") == "2"
    assert fmt_spec(-0.0001, "{:.2f}", lang="en") == "0.00"
    assert fmt_spec(-2.25, ".1f", lang="en") == f"{MINUS}2.2"
    assert fmt_spec(70.0, "{:d}", lang="en") == "70"
    with pytest.raises(ValueError, match="spec"):
        fmt_spec(1.0, "{:>8s}")


def test_counts_scales_missing():
    assert fmt_count(70.0, lang="en") == "70"
    assert fmt_count(np.int64(1225), lang="en") == "1225"
    assert fmt_count(12043, lang="ru") == f"12{NB}043"
    assert fmt_scale(12000, lang="en") == f"1:12{NB}000"
    assert fmt(float("nan")) == "—" and fmt_count(None) == "—"
    assert fmt(-math.inf, 1) == f"{MINUS}∞"
    with pytest.raises(ValueError, match="digits"):
        fmt(1.0, -1)


def test_language_in_use_is_the_default():
    with language("ru"):
        assert fmt(0.5, 1) == "0,5"
    with language("en"):
        assert fmt(0.5, 1) == "0.5"


@pytest.mark.parametrize("cell, en, ru", [
    ("12043", f"12{NB}043", f"12{NB}043"),
    ("12 043", f"12{NB}043", f"12{NB}043"),
    ("-0.00", "0.00", "0,00"),
    ("1,200.00", "1200.00", "1200,00"),
    ("11934.0", f"11{NB}934.0", f"11{NB}934,0"),
    ("1:12000", f"1:12{NB}000", f"1:12{NB}000"),
    ("-2.5", f"{MINUS}2.5", f"{MINUS}2,5"),
    ("1a–4a", "1a–4a", "1a–4a"),              # labels stay
    ("(6.1)", "(6.1)", "(6.1)"),              # formula numbers stay
    ("2.5e-05", "2.5e-05", "2.5e-05"),
    ("-", "-", "-"),
    ("-1.80 %", f"{MINUS}1.80 %", f"{MINUS}1,80 %"),
    ("2.5°", "2.5°", "2,5°"),
])
def test_localise_whole_cells_only(cell, en, ru):
    assert localise(cell, lang="en") == en
    assert localise(cell, lang="ru") == ru


def test_html_table_one_format():
    df = pd.DataFrame({"n photos": [70, 1225], "p_x, %": [-0.001, 60.5], "m": ["12043", "-0.00"]})
    html = plots.html_table(df, float_format="{:.2f}")
    assert ">70<" in html and ">1225<" in html and "70.00" not in html          # counts stay whole
    assert ">0.00<" in html and "−0.00" not in html and "-0.00" not in html      # no signed zero
    assert f">12{NB}043<" in html
    assert "p<sub>x</sub>, %" in html                                           # a real subscript
    assert "<th scope='row'>1</th>" in html and "<th scope='row'>0</th>" not in html  # rows from 1
    assert "<th scope='col'>" in html and "<th></th>" not in html               # no empty header
    with language("ru"):
        assert ">60,50<" in plots.html_table(df, float_format="{:.2f}")


def test_math_subscripts():
    assert plots.math_subscripts("p_x, mm") == "$p_{x}$, mm"
    assert plots.math_subscripts("λ_t, °") == "$λ_{t}$, °"
    assert plots.math_subscripts("m_z = 0.5 m") == "$m_{z}$ = 0.5 m"
    assert plots.math_subscripts("$p_x$") == "$p_x$"                     # mathtext already
    assert plots.math_subscripts("guide_table") == "guide_table"         # not a symbol


def test_o_n_c_labels_never_overlap():
    """Chapter 03/00: the o, n, c labels stay apart at every tilt (they overlapped from α ≈ 2.5°)."""
    import matplotlib

    matplotlib.use("Agg")
    from aerophoto.demos.displacement import ReliefDemo

    demo = ReliefDemo()
    try:
        for alpha in (0.0, 1.0, 2.5, 4.0, 10.0):
            demo.set(alpha_deg=alpha)
            demo.fig.canvas.draw()
            r = demo.fig.canvas.get_renderer()
            boxes = {k: demo.view.marks[k][1].get_window_extent(r) for k in ("o", "n", "c")}
            for a, b in (("o", "n"), ("o", "c"), ("n", "c")):
                assert not boxes[a].overlaps(boxes[b]), (alpha, a, b, boxes[a], boxes[b])
    finally:
        demo.close()
