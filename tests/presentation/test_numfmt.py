"""The book's one number format (aerophoto.i18n.numfmt): decimal mark, grouping, minus, counts, scales."""

import math

import numpy as np
import pytest

from aerophoto.i18n import language
from aerophoto.i18n.numfmt import (DASH, GROUP, MINUS, NBSP, decimals_for, fmt_count, fmt_number, fmt_percent,
                                   fmt_quantity, fmt_scale, fmt_signed, fmt_value)


@pytest.mark.parametrize("x, decimals, ru, en", [
    (11859.2, 0, f"11{GROUP}859", f"11{GROUP}859"),
    (2706, 0, "2706", "2706"),                       # four digits stay whole
    (12043.0, 0, f"12{GROUP}043", f"12{GROUP}043"),
    (1200.0, 2, "1200,00", "1200.00"),               # never "1,200.00"
    (1234567.891, 1, f"1{GROUP}234{GROUP}567,9", f"1{GROUP}234{GROUP}567.9"),
    (-3.25, 1, f"{MINUS}3,2", f"{MINUS}3.2"),        # round half to even, a true minus
    (-0.004, 2, "0,00", "0.00"),                     # no signed zero
    (0.0, 3, "0,000", "0.000"),
])
def test_fixed_decimals(x, decimals, ru, en):
    assert fmt_number(x, decimals, lang="ru") == ru
    assert fmt_number(x, decimals, lang="en") == en


def test_significant_digits_never_scientific():
    assert fmt_number(6004123.4, sig=4, lang="en") == f"6{GROUP}004{GROUP}123"
    assert fmt_number(0.00395604, sig=3, lang="ru") == "0,00396"
    assert fmt_number(0.00395604, lang="en") == "0.003956"   # default: 4 significant digits
    assert "e" not in fmt_number(1.5e-9, lang="en")
    assert decimals_for(123.4, 4) == 1 and decimals_for(0.012, 2) == 3 and decimals_for(98765, 3) == 0


def test_language_in_use_and_missing_values():
    with language("ru"):
        assert fmt_number(0.67, 2) == "0,67"
    with language("en"):
        assert fmt_number(0.67, 2) == "0.67"
    assert fmt_number(None) == DASH and fmt_number(float("nan")) == DASH and fmt_number(np.nan) == DASH
    assert fmt_number(math.inf) == "∞" and fmt_number(-math.inf) == MINUS + "∞"


def test_counts_scales_percent_units():
    assert fmt_count(70.0) == "70" and fmt_count(np.int64(12043)) == f"12{GROUP}043"
    with pytest.raises(ValueError, match="n = 2.5"):
        fmt_count(2.5)
    assert fmt_scale(17700) == f"1:17{GROUP}700" and fmt_scale(10000.4) == f"1:10{GROUP}000"
    with pytest.raises(ValueError, match="m = 0"):
        fmt_scale(0)
    assert fmt_percent(12.34, lang="ru") == f"12,3{NBSP}%"
    assert fmt_quantity(11859.2, "m", 0, lang="ru") == f"11{GROUP}859{NBSP}м"
    assert fmt_quantity(3.0, "°", 1, lang="en") == "3.0°"
    assert fmt_signed(0.12, 2, lang="ru") == "+0,12" and fmt_signed(-0.001, 2, lang="ru") == "0,00"


def test_table_cells():
    assert fmt_value(np.int64(5)) == "5" and fmt_value(12043) == f"12{GROUP}043"
    assert fmt_value(True, lang="ru") == "да" and fmt_value(np.bool_(False), lang="en") == "no"
    assert fmt_value("1a–4a") == "1a–4a" and fmt_value(np.float64("nan")) == DASH
    assert fmt_value(0.1234567, lang="ru") == "0,1235"


@pytest.mark.parametrize("bad", [-1, 1.5, True, "2"])
def test_bad_precision_named(bad):
    with pytest.raises(ValueError, match="decimals"):
        fmt_number(1.0, bad)
    with pytest.raises(ValueError, match="lang"):
        fmt_number(1.0, 1, lang="de")


# ------------------------------------------------------------------ reading numbers back, specs, ticks, tables
from hypothesis import given, settings  # noqa: E402
from hypothesis import strategies as st  # noqa: E402

from aerophoto.i18n.numfmt import fmt_spec, fmt_text, localise_ticks, numbers_in, parse_number  # noqa: E402


@settings(max_examples=300, deadline=None)
@given(st.floats(min_value=-1e9, max_value=1e9, allow_nan=False), st.integers(0, 4), st.sampled_from(["en", "ru"]))
def test_parse_number_reads_back_what_fmt_number_writes(x, decimals, lang):
    text = fmt_number(x, decimals, lang=lang)
    assert parse_number(text, lang=lang) == pytest.approx(round(x, decimals), abs=10.0 ** -decimals)
    assert numbers_in(f"h = {text} m", lang=lang) == [parse_number(text, lang=lang)]


def test_parse_number_and_numbers_in():
    assert parse_number(f"12{GROUP}043") == 12043.0 and parse_number(f"{MINUS}3,25", lang="ru") == -3.25
    assert parse_number(f"1:17{GROUP}700") == 17700.0 and parse_number(f"12,3{NBSP}%", lang="ru") == 12.3
    assert math.isnan(parse_number(DASH))
    with pytest.raises(ValueError, match="decimal comma"):
        parse_number("3,25", lang="en")
    with pytest.raises(ValueError, match="abc"):
        parse_number("abc")
    assert numbers_in(f"h = 0,5 м: СКО 0,123 м (узлов: 1{GROUP}225)", lang="ru") == [0.5, 0.123, 1225.0]
    assert numbers_in(f"misses ×2, largest {MINUS}0.25 mm (1, 2)", lang="en") == [2.0, -0.25, 1.0, 2.0]


def test_fmt_spec_follows_the_python_spec_in_the_books_format():
    assert fmt_spec(12043.2, "{:.4g}") == f"12{GROUP}043"  # never 1.204e+04
    assert fmt_spec(0.0123456, "{:.3g}") == "0.0123" and fmt_spec(2.50, "{:.3g}") == "2.5"
    assert fmt_spec(1200.0, "{:,.2f}", lang="ru") == "1200,00" and fmt_spec(-0.001, "{:.2f}") == "0.00"
    assert fmt_spec(0.123, "{:+.2f}") == "+0.12" and fmt_spec(7.0, "{:d}") == "7"
    assert fmt_spec(0.1234, "{:.1%}", lang="ru") == f"12,3{NBSP}%"
    with pytest.raises(ValueError, match="spec"):
        fmt_spec(1.0, "{:>10}")


def test_fmt_text_rewrites_numbers_written_by_python():
    assert fmt_text("-0.00 and 12043.5 and -1.80 %", lang="ru") == f"0,00 and 12{GROUP}043,5 and {MINUS}1,80 %"
    # codes, names and numbers already in the book's format stay as they are
    for keep in ("19-0457", "1a–4a", "p_x2", "007", f"12{GROUP}043", "0,25"):
        assert fmt_text(keep, lang="ru") == keep


def test_tick_labels_in_the_books_format():
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots()
    ax.plot([-12000, 15000], [-0.5, 1.5])
    ax.set_yscale("linear")
    assert localise_ticks(fig, lang="ru") == 2 and localise_ticks(fig, lang="ru") == 0  # once is enough
    fig.canvas.draw()
    xs = [t.get_text() for t in ax.get_xticklabels()]
    ys = [t.get_text() for t in ax.get_yticklabels()]
    plt.close(fig)
    assert f"{MINUS}10{GROUP}000" in xs and "5000" in xs
    assert f"{MINUS}0,50" in ys and "1,00" in ys


def test_no_module_groups_thousands_by_hand():
    """Every grouped number goes through numfmt: a hand-made ``f"{x:,.0f}".replace(",", " ")`` writes a plain space,
    which the reader cannot tell from two numbers ("1:12 300" — 12 and 300) and which breaks across a line."""
    import re
    from pathlib import Path

    import aerophoto

    src = Path(aerophoto.__file__).parent
    pattern = re.compile(r""":,[^}]*\}[^\n]*\.replace\(",", " "\)|\.replace\(",", " "\)""")
    offenders = [f"{p.relative_to(src)}:{i}" for p in sorted(src.rglob("*.py"))
                 for i, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1) if pattern.search(line)]
    assert not offenders, offenders
