"""The magnifier on chapter 08's photo (aerophoto.demos.loupe): where it looks, how much, in place, by name."""

from __future__ import annotations

import numpy as np
import pytest

from aerophoto.demos import loupe

pytestmark = pytest.mark.usefixtures("plot_style")


@pytest.fixture()
def demo():
    import matplotlib

    matplotlib.use("Agg")
    d = loupe.LoupeDemo()  # the worked example's photo
    yield d
    d.close()


def test_the_glass_shows_its_field_at_its_power(demo):
    im = demo.view.im_glass
    demo.set(mark="free", x_mm=10, y_mm=-20, power=4)
    r = demo.result
    assert r.centre_mm == (10.0, -20.0) and r.side_mm == pytest.approx(loupe.FIELD_MM / 4)
    assert r.image.shape == (400, 400, 3) and demo.view.im_glass is im  # the same artist, new data
    assert r.ground_m == pytest.approx(r.side_mm * r.m / 1000.0)
    assert r.pixel_m == pytest.approx(r.side_mm / 400 * r.m / 1000.0, rel=0.02)
    x0, y0 = demo.view.field.get_xy()
    assert (x0, y0) == pytest.approx((10 - r.side_mm / 2, -20 - r.side_mm / 2))
    demo.set(power=6)
    assert demo.result.side_mm == pytest.approx(20.0) and demo.view.field.get_width() == pytest.approx(20.0)
    assert "×6" in demo.table.value and "20.0 mm" in demo.table.value


def test_centre_on_a_mark_and_near_the_edge(demo):
    row = demo.lab.marks.loc["P"]
    demo.set(mark="P", power=5)
    assert demo.result.centre_mm == pytest.approx((row["x, mm"], row["y, mm"]), abs=1e-9) or \
        abs(row["x, mm"]) > 90 - 12 or abs(row["y, mm"]) > 90 - 12
    # the mark's ring sits at the field's centre
    u, v = demo.view.ring.get_offsets()[list(demo.lab.marks.index).index("P")]
    assert (u, v) == pytest.approx((0.5, 0.5), abs=0.15)
    demo.set(mark="free", x_mm=80, y_mm=-80, power=3)  # a field of 40 mm cannot centre at 80: moved in
    assert demo.result.centre_mm == (70.0, -70.0)


def test_a_click_moves_the_glass(demo):
    class Event:
        inaxes = demo.view.ax_all
        xdata, ydata = -33.4, 41.6

    demo._on_press(Event())
    assert demo.values["x_mm"] == -33 and demo.values["y_mm"] == 42 and demo.values["mark"] == "free"
    Event.inaxes = demo.view.ax_glass
    demo._on_press(Event())  # a click on the glass itself does nothing
    assert demo.values["x_mm"] == -33


def test_the_glass_is_finer_than_the_photo_and_shows_the_same_place(demo):
    from aerophoto.labs import ch08

    demo.set(mark="free", x_mm=0, y_mm=0, power=3, camera="colour film")
    r = demo.result
    lab = demo.lab
    n = int(round(r.side_mm / lab.pixel_mm))
    c0 = int(round((r.centre_mm[0] - r.side_mm / 2 + 90.0) / lab.pixel_mm))
    r0 = int(round((90.0 - r.centre_mm[1] - r.side_mm / 2) / lab.pixel_mm))
    photo = lab.composite("colour film")[r0:r0 + n, c0:c0 + n]
    from skimage.transform import resize

    small = resize(r.image, photo.shape, anti_aliasing=True)
    assert np.corrcoef(small.ravel(), photo.ravel())[0, 1] > 0.85
    assert r.pixel_m < 0.6 * lab.pixel_mm * r.m / 1000.0  # ×3: 0.1 mm pixels against the photo's 0.18 mm
    assert ch08.LOUPE_PX == r.image.shape[0]


def test_bad_input_is_refused_by_name():
    with pytest.raises(ValueError, match="power"):
        loupe.loupe_model(2014, power=10)
    with pytest.raises(ValueError, match="camera"):
        loupe.loupe_model(2014, camera="x-ray")
    d = loupe.LoupeDemo.__new__(loupe.LoupeDemo)
    with pytest.raises(ValueError, match="mark"):
        loupe.LoupeDemo.params[2].validate("Z")
    assert d is not None


def test_a_students_glass_is_their_own_photo():
    from aerophoto.labs import ch08
    from aerophoto.variants import variant_for_index

    v = variant_for_index(57)
    d = loupe.LoupeDemo(v)
    try:
        assert d.i == 57 and d.lab is ch08._lab_photo(57)
        assert list(d.lab.marks.index) == ["1", "2", "3", "4", "5", "6", "P", "Q", "A", "B"]
    finally:
        d.close()
