"""aerophoto.variants (guide §1): a student's variant from the record-book number, and bad numbers refused by name."""

import dataclasses

import pytest

from aerophoto.variants import Variant, index_from_record_book, variant, variant_for_index


def test_the_variant_is_the_last_two_digits_of_the_record_book_number():
    assert index_from_record_book("19-0457") == 57
    assert index_from_record_book("ЗиК-19-0457") == 57  # non-digits are ignored
    assert index_from_record_book(1203) == 3
    assert index_from_record_book("20-1100") == 0


def test_variant_57_from_its_record_book_number():
    v = variant("19-0457")
    assert isinstance(v, Variant) and v.record_book == "19-0457" and v.i == 57
    # §1: W = 200 + 10 i, f = 100 + 10 i, m = 12 000 + 100 i, L = 25 + i / 30 + i, Z = 200 + i / 170 + i, λ = −60 + i
    assert (v.W_kmh, v.f_mm, v.m, v.M) == (770.0, 670.0, 17700.0, 10000.0)
    assert (v.Lx_km, v.Ly_km, v.Zmax_m, v.Zmin_m) == (82.0, 87.0, 257.0, 227.0)
    assert (v.frame_mm, v.px_percent, v.py_percent, v.alpha_deg, v.lambda_deg) == (180.0, 60.0, 30.0, 3.0, -3.0)
    assert v.H_m == pytest.approx(670.0 * 17700.0 / 1000.0)  # H = f·m = 11 859 m
    assert v.relief_m == 30.0
    assert v.camera.f_mm == 670.0 and v.camera.frame_mm == 180.0


def test_variant_00_is_the_guides_worked_example():
    v = variant_for_index(0)
    assert (v.f_mm, v.m, v.W_kmh, v.Lx_km, v.Ly_km) == (100.0, 12000.0, 200.0, 25.0, 30.0)
    assert v.H_m == pytest.approx(1200.0)
    assert v.record_book == "(variant 00)"
    assert variant("21-1100") == dataclasses.replace(v, record_book="21-1100")


def test_the_variant_table_and_dict():
    v = variant("19-0457")
    t = v.table()
    assert t.shape == (15, 2) and list(t.columns) == ["unit", "value"]
    assert t.loc["Focal length f", "value"] == 670.0
    assert t.loc["Photo scale 1/m", "value"] == 17700.0 and t.loc["Photo scale 1/m", "unit"] == "1:"
    from aerophoto.plots import html_table

    # shown in the book's format: unit "1:" beside 17 700 with a narrow no-break space (numfmt)
    shown = html_table(t, precision=t.attrs["aerophoto"].get("precision"))
    assert "<td class='num'>1:</td><td class='num'>17\u202f700</td>" in shown
    assert t.loc["Frame size", "value"] == "18×18"
    assert v.as_dict()["lambda_deg"] == -3.0 and len(v.as_dict()) == 15


def test_a_variant_cannot_be_changed():
    with pytest.raises(dataclasses.FrozenInstanceError):
        variant_for_index(3).f_mm = 1.0


@pytest.mark.parametrize("bad, match", [
    ("7", r"record_book = '7' has 1 digit\(s\)"),
    ("ab-c", r"record_book = 'ab-c' has 0 digit\(s\)"),
    (None, "record_book = None"),
], ids=["one digit", "no digit", "None"])
def test_a_record_book_number_without_two_digits_is_refused_by_name(bad, match):
    with pytest.raises(ValueError, match=match):
        variant(bad)


@pytest.mark.parametrize("i", [-1, 100, 2.5])
def test_an_index_outside_00_99_is_refused_by_name(i):
    with pytest.raises(ValueError, match=r"i = .*0 ≤ i ≤ 99"):
        variant_for_index(i)
