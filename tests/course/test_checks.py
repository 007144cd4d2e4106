"""aerophoto.checks: pass/fail with the right hint, never the expected value in the message."""

import math

import numpy as np
import pandas as pd
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from aerophoto import checks
from aerophoto.checks import WrongAnswer
from aerophoto.variants import variant, variant_for_index


@pytest.fixture(autouse=True)
def _fresh():
    checks.reset()
    yield
    checks.reset()


def fails(fn, *args, **kwargs) -> str:
    with pytest.raises(WrongAnswer) as info:
        fn(*args, **kwargs)
    return str(info.value)


# ---------------------------------------------------------------------------------------- check_value


def test_check_value_accepts_within_default_half_percent(capsys):
    assert checks.check_value("H_m", 1204.0, 1200.0, unit="m") is True
    assert "✓ H_m: correct" in capsys.readouterr().out
    msg = fails(checks.check_value, "H_m", 1207.0, 1200.0, unit="m")
    assert "close, but outside the tolerance" in msg


def test_check_value_keeps_its_signature_and_positional_use():
    # other chapters call it positionally as (name, answer, expected) with keywords after
    assert checks.check_value("x", 2.0, 2.0, tol_abs=None, tol_rel=None, unit="", integer=False,
                              of_variant=None, variant=None, alternatives=None, quiet=True) is True


@pytest.mark.parametrize("answer, hint", [
    (1.2, "a factor of 1/1000 — kilometres vs metres"),   # H in km instead of m
    (1_200_000.0, "a factor of 1000 — metres vs kilometres"),
    (-1200.0, "sign is wrong"),
    (12_000.0, "centimetres vs millimetres"),
])
def test_check_value_diagnoses_units_and_sign(answer, hint):
    msg = fails(checks.check_value, "H_m", answer, 1200.0, unit="m")
    assert hint in msg
    assert "1200" not in msg  # the expected value is never printed


def test_check_value_counts_exact_with_rounding_hint():
    assert "rounds this count up" in fails(checks.check_value, "K", 5, 6, integer=True)
    assert "off by one" in fails(checks.check_value, "K", 7, 6, integer=True)
    assert "not a whole number" in fails(checks.check_value, "K", 5.5, 6, integer=True)
    assert checks.check_value("K", 6, 6, integer=True, quiet=True)
    assert checks.check_value("K", np.int64(6), 6, integer=True, quiet=True)


def test_check_value_recognises_another_variant():
    v = variant("19-0457")
    other = variant_for_index(12)
    msg = fails(checks.check_value, "H_m", other.H_m, v.H_m, variant=v, of_variant=lambda w: w.H_m)
    assert "variant 12" in msg and "(57)" in msg
    assert f"{v.H_m:g}" not in msg


def test_check_value_alternatives_give_their_hint():
    msg = fails(checks.check_value, "Px", 61.0, 62.5, alternatives={"forgot the relief allowance": 61.0})
    assert msg.endswith("forgot the relief allowance")


@pytest.mark.parametrize("answer, words", [
    (None, "no answer yet"),
    (..., "no answer yet"),
    ("twelve", "is not a number"),
    (float("nan"), "nan"),
    (float("inf"), "infinite"),
    (True, "yes/no verdict"),
    ([1.0, 2.0], "single value"),
    (np.array([1.0, 2.0]), "single value"),
])
def test_check_value_bad_answers_say_what_is_wrong(answer, words):
    assert words in fails(checks.check_value, "H_m", answer, 1200.0, unit="m")


def test_check_value_takes_one_element_arrays_and_series_without_warnings():
    import warnings

    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert checks.check_value("x", np.array([2.0]), 2.0, quiet=True)
        assert checks.check_value("x", pd.Series([2.0]), 2.0, quiet=True)
        assert checks.check_value("x", np.float32(2.0), 2.0, quiet=True)


def test_wrong_answer_renders_as_one_red_line():
    with pytest.raises(WrongAnswer) as info:
        checks.check_value("H_m", 1.2, 1200.0)
    lines = info.value._render_traceback_()
    assert len(lines) == 1 and lines[0].startswith("\x1b[31m✗ H_m:")
    assert isinstance(info.value, AssertionError)  # nbgrader marks the test cell failed


@settings(max_examples=60, deadline=None)
@given(expected=st.floats(0.01, 1e6), rel=st.floats(-0.0049, 0.0049))
def test_check_value_accepts_anything_within_tolerance(expected, rel):
    assert checks.check_value("q", expected * (1 + rel), expected, quiet=True)


@settings(max_examples=60, deadline=None)
@given(expected=st.floats(0.01, 1e6), rel=st.floats(0.0051, 10.0))
def test_check_value_rejects_anything_outside_tolerance(expected, rel):
    with pytest.raises(WrongAnswer) as info:
        checks.check_value("q", expected * (1 + rel), expected, quiet=True)
    assert f"{expected}" not in str(info.value)


# ---------------------------------------------------------------------------------------- check_count


def test_check_count_rounding_rules():
    assert checks.check_count("K", 6, 6, quiet=True)
    assert "one too few" in fails(checks.check_count, "K", 5, 6) and "rounds this count up" in fails(
        checks.check_count, "K", 5, 6)
    assert "one too many" in fails(checks.check_count, "n", 8, 7, rounding="down")
    assert "nearest" in fails(checks.check_count, "n", 7.4, 7, rounding="nearest")
    assert "sign is wrong" in fails(checks.check_count, "K", -6, 6)
    assert "no answer yet" in fails(checks.check_count, "K", ..., 6)
    with pytest.raises(ValueError, match="rounding = 'sideways'"):
        checks.check_count("K", 6, 6, rounding="sideways")


# ---------------------------------------------------------------------------------------- check_values


def test_check_values_all_right(capsys):
    assert checks.check_values("d_mm", [1.0, -2.0, 3.0], np.array([1.0, -2.0, 3.0]), tol_abs=0.05)
    assert "all 3 values correct" in capsys.readouterr().out
    assert checks.check_values("d_mm", pd.Series([1.0, 2.0]), (1.0, 2.0), quiet=True)


@pytest.mark.parametrize("answers, hint", [
    ([3.0, 2.0, 1.0], "reverse order"),
    ([-1.0, -2.0, -3.0], "every sign is wrong"),
    ([1000.0, 2000.0, 3000.0], "factor of 1000"),
    ([2.0, 1.0, 3.0], "not in the order"),
    ([1.0, 2.0, 3.5], "1 of 3 values are not right: point 3"),
    ([1.0, -2.0, 3.0], "the sign of point 2 is wrong"),
    ([1.0, 2.0], "2 values given, the task asks for 3"),
    ("1, 2, 3", "give a list of 3 values"),
    ([1.0, None, 3.0], "no value yet for point 2"),
    ([1.0, "x", 3.0], "point 2 = 'x' is not a number"),
])
def test_check_values_diagnoses_the_whole_set(answers, hint):
    msg = fails(checks.check_values, "d_mm", answers, [1.0, 2.0, 3.0], tol_abs=0.05,
                labels=["point 1", "point 2", "point 3"])
    assert hint in msg


def test_check_values_dict_and_variants():
    assert checks.check_values("r", {"a": 1.0, "b": 2.0}, {"a": 1.0, "b": 2.0}, quiet=True)
    assert "no value for b" in fails(checks.check_values, "r", {"a": 1.0}, {"a": 1.0, "b": 2.0})
    assert "unexpected entries c" in fails(checks.check_values, "r", {"a": 1.0, "b": 2.0, "c": 3},
                                           {"a": 1.0, "b": 2.0})
    v = variant("19-0457")

    def of(w):
        return [w.f_mm, w.m]

    msg = fails(checks.check_values, "fm", of(variant_for_index(3)), of(v), variant=v, of_variant=of)
    assert "variant 03" in msg


def test_check_values_integer_and_bad_expected():
    assert checks.check_values("N", [3, 4], [3, 4], integer=True, quiet=True)
    fails(checks.check_values, "N", [3, 4.0001], [3, 4], integer=True)
    with pytest.raises(ValueError, match="expected = 5"):
        checks.check_values("N", [1], 5)
    with pytest.raises(ValueError, match="labels has 1 entries"):
        checks.check_values("N", [1, 2], [1, 2], labels=["a"])


# ---------------------------------------------------------------------------------------- verdicts, choices


def test_check_bool():
    assert checks.check_bool("ok", True, True, quiet=True)
    assert checks.check_bool("ok", np.bool_(False), False, quiet=True)
    assert "56 %" in fails(checks.check_bool, "ok", True, False, hint="compare P_x with the guide's 56 % minimum")
    assert "write True or False" in fails(checks.check_bool, "ok", "yes", True)
    assert "no answer yet" in fails(checks.check_bool, "ok", ..., True)


def test_check_choice():
    opts = ["direct", "reverse", "zero"]
    assert checks.check_choice("effect", "  Reverse ", "reverse", opts, quiet=True)
    assert "not one of the options" in fails(checks.check_choice, "effect", "inverse", "reverse", opts)
    assert "not this one" in fails(checks.check_choice, "effect", "direct", "reverse", opts)
    with pytest.raises(ValueError, match="not one of the options"):
        checks.check_choice("effect", "direct", "upside-down", opts)


# ---------------------------------------------------------------------------------------- session summary


def test_task_passed_and_report(capsys):
    checks.check_value("H_m", 1200.0, 1200.0)
    assert checks.task_passed("task-00-1") is None
    with pytest.raises(WrongAnswer):
        checks.check_value("K", 5, 6, integer=True)
    capsys.readouterr()
    text = checks.report()
    printed = capsys.readouterr().out
    assert printed.strip() == text.strip()
    assert "✓ Task 00.1 passed (1 check(s))" in text
    assert "✗ K — K: one too few" in text
    assert "1 of 2 checks passed; 1 task(s) passed completely" in text
    assert set(checks.results()) == {"H_m", "K"} and not checks.results()["K"].passed
    assert list(checks.task_results()) == ["task-00-1"]


def test_report_shows_once_in_a_notebook():
    text = checks.report()
    assert "No answers checked yet" in text
    assert hasattr(text, "_ipython_display_")  # IPython shows nothing more: the text was printed


def test_checks_write_nothing_to_stderr(capsys):
    checks.check_value("a", 1.0, 1.0)
    checks.check_values("b", [1.0], [1.0])
    checks.check_bool("c", True, True)
    checks.check_count("d", 2, 2)
    checks.task_passed("task-99-1")
    with pytest.raises(WrongAnswer):
        checks.check_value("e", 2.0, 1.0)
    assert capsys.readouterr().err == ""  # nbgrader scores a test cell that writes to stderr 0


def test_tolerance_constants_match_the_docstring():
    doc = checks.__doc__
    # each constant is the value the module's documentation promises
    assert f"``rel={checks.TOL_REL:g}`` ({checks.TOL_REL * 100:g} %)" in doc
    assert f"``tol_abs={checks.TOL_PHOTO_MM:g}`` mm" in doc and f"``tol_abs={checks.TOL_COEFF:g}``" in doc
    # photo distances are printed to 0.1 mm: the tolerance is half the last printed digit
    assert "printed to 0.1 mm" in doc and math.isclose(checks.TOL_PHOTO_MM * 2, 0.1)
