"""aerophoto.widgets: the LiveDemo base (values, set, reset, bounds) and the Param sliders, on a small demo."""

import numpy as np
import pytest

from aerophoto.widgets import LiveDemo, Param, error_html


class Parabola(LiveDemo):
    """y = s·a·x² on x ∈ [−n, n]: one float, one whole-number and one choice slider."""

    title = "Parabola"
    params = (
        Param("a", "a", 0.0, 2.0, 0.1, 1.0, group="Shape"),
        Param("n", "n", 1, 5, 1, 3, kind="int"),
        Param("sign", "sign", kind="choice", options=(("up", 1), ("down", -1)), default=1),
    )

    def build(self):
        import matplotlib.pyplot as plt

        self.fig, self.ax = plt.subplots()
        (self.line,) = self.ax.plot([], [])

    def compute(self, a, n, sign):
        x = np.linspace(-n, n, 2 * n + 1)
        return x, sign * a * x**2

    def render(self, result):
        x, y = result
        self.line.set_data(x, y)
        self.table.value = f"<b>max y = {y.max() + 0.0:.2f}</b>"


def test_a_demo_opens_on_its_defaults_and_draws_once():
    d = Parabola()
    assert d.values == {"a": 1.0, "n": 3, "sign": 1} and d.start_values == d.values
    assert d.n_updates == 1
    np.testing.assert_allclose(d.line.get_xdata(), [-3, -2, -1, 0, 1, 2, 3])
    np.testing.assert_allclose(d.line.get_ydata(), [9, 4, 1, 0, 1, 4, 9])
    assert d.table.value == "<b>max y = 9.00</b>"


def test_set_moves_the_same_artist_and_reset_returns_to_the_start_values():
    d = Parabola(a=0.5)
    line = d.line
    assert d.set(a=2.0, n=1, sign=-1) is d
    assert d.line is line and d.n_updates == 2
    np.testing.assert_allclose(d.line.get_ydata(), [-2.0, 0.0, -2.0])
    assert d.table.value == "<b>max y = 0.00</b>"
    d.reset()  # back to what it was built with (a = 0.5), not the class defaults
    assert d.values == {"a": 0.5, "n": 3, "sign": 1} and d.n_updates == 3
    np.testing.assert_allclose(d.line.get_ydata(), [4.5, 2.0, 0.5, 0.0, 0.5, 2.0, 4.5])


def test_set_syncs_the_sliders_which_keep_the_params_bounds():
    d = Parabola()
    c = d.controls()
    assert (c["a"].min, c["a"].max, c["a"].step, c["a"].value) == (0.0, 2.0, 0.1, 1.0)
    assert (c["n"].min, c["n"].max, c["n"].value) == (1, 5, 3)
    assert [v for _, v in c["sign"].options] == [1, -1]
    d.set(a=0.3, n=5)
    assert c["a"].value == pytest.approx(0.3) and c["n"].value == 5


@pytest.mark.parametrize("values, match", [
    ({"a": 2.5}, r"a = 2\.5 .*0 ≤ a ≤ 2"),
    ({"a": float("nan")}, "a = nan is not a number"),
    ({"n": 2.5}, "n = 2.5 must be a whole number with 1 ≤ n ≤ 5"),
    ({"sign": 0}, r"sign = 0 is not one of the valid choices \[1, -1\]"),
    ({"b": 1.0}, "'b' is not a parameter of Parabola; valid parameters: a, n, sign"),
], ids=["a above its range", "a not a number", "n not whole", "sign not a choice", "no such parameter"])
def test_values_outside_the_sliders_are_refused_by_name_and_change_nothing(values, match):
    d = Parabola()
    with pytest.raises(ValueError, match=match):
        d.set(**values)
    assert d.values == {"a": 1.0, "n": 3, "sign": 1} and d.n_updates == 1
    with pytest.raises(ValueError, match=match):
        Parabola(**values)


def test_error_html_shows_the_error_escaped():
    html = error_html(ValueError("a < 0 & b > 1"))
    assert "ValueError: a &lt; 0 &amp; b &gt; 1" in html and html.startswith("<span")
