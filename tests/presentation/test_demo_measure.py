"""The measuring tool (aerophoto.demos.measure): readings by click or from code, their table and paste-able lines."""

from types import SimpleNamespace

import numpy as np
import pytest

from aerophoto.demos.measure import MeasureTool, photo_tool, plan_tool
from aerophoto.labs.displacement import relief_sheet, tilt_sheet

NAMES = ("I", "1", "2")


def _tool(**kw):
    img = np.linspace(0, 1, 40 * 40).reshape(40, 40)
    return MeasureTool(img, (-20, 20, -20, 20), NAMES, marks={"I": (0.0, 0.0), "1": (5.0, 5.0)}, **kw)


def _event(tool, x, y, *, button=1, inside=True):
    return SimpleNamespace(inaxes=tool.ax if inside else None, button=button, xdata=x, ydata=y)


def test_clicks_measure_the_selected_point_and_move_on():
    tool = _tool()
    assert tool.current == "I" and not tool.complete
    tool._on_press(_event(tool, 0.04, -0.06))
    assert tool.measured["I"] == (0.0, -0.1) and tool.current == "1" and tool.n_clicks == 1
    tool._on_press(_event(tool, 5.123, 4.96))
    tool._on_press(_event(tool, -7.25, 3.0))
    assert tool.complete and tool.x_mm() == [0.0, 5.1, -7.2] and tool.y_mm() == [-0.1, 5.0, 3.0]
    np.testing.assert_allclose(tool.readings.get_xdata(), [0.0, 5.1, -7.2])  # the red crosses are drawn there
    # a second round: select a point, click again
    tool.select("1")._on_press(_event(tool, 5.0, 5.0))
    assert tool.measured["1"] == (5.0, 5.0)
    tool.close()


def test_clicks_that_are_not_readings_are_ignored():
    tool = _tool()
    tool._on_press(_event(tool, 1.0, 1.0, button=3))
    tool._on_press(_event(tool, 1.0, 1.0, inside=False))
    tool._on_press(_event(tool, None, None))
    tool._toolbar_busy = lambda: True  # zooming or panning
    tool._on_press(_event(tool, 1.0, 1.0))
    assert tool.n_clicks == 0 and all(v is None for v in tool.measured.values())
    tool.close()


def test_code_table_load_and_clear():
    tool = _tool()
    assert tool.code() == "x_mm = [..., ..., ...]\ny_mm = [..., ..., ...]"
    tool.measure("2", 1.26, -3.04)
    assert tool.code("xpl_mm", "ypl_mm") == "xpl_mm = [..., ..., 1.3]\nypl_mm = [..., ..., -3.0]"
    t = tool.table()
    assert list(t.columns) == ["x, mm", "y, mm"] and list(t.index) == list(NAMES)
    assert np.isnan(t.loc["I", "x, mm"]) and t.loc["2", "y, mm"] == -3.0
    assert np.isnan(tool.xy()[0]).all() and tool.xy()[2].tolist() == [1.3, -3.0]
    tool.load([1.0, 2.0, None], [3.0, 4.0, None])
    assert tool.measured == {"I": (1.0, 3.0), "1": (2.0, 4.0), "2": None}
    exec(tool.code(), ns := {})  # the lines paste into an answer cell as they are
    assert ns["x_mm"] == [1.0, 2.0, ...]
    tool.clear("I")
    assert tool.measured["I"] is None and tool.measured["1"] == (2.0, 4.0)
    tool.clear()
    assert all(v is None for v in tool.measured.values())
    fine = _tool(decimals=2).measure("I", 1.234, 5.678)
    assert fine.measured["I"] == (1.23, 5.68) and "1.23" in fine.code()
    tool.close()
    fine.close()


def test_the_widget_shows_readout_table_and_code():
    tool = _tool()
    layout = tool.widget(x_name="xpl_mm", y_name="ypl_mm")
    assert tool.widget() is layout
    w = tool._widgets
    tool._on_move(_event(tool, 3.14159, -2.5))
    assert "x = 3.1 mm" in w["readout"].value and "y = -2.5 mm" in w["readout"].value
    tool._on_press(_event(tool, 1.0, 2.0))
    assert "1 of 3 points measured" in w["status"].value and w["point"].value == "1"
    assert w["code"].value.startswith("xpl_mm = [1.0, ..., ...]")
    assert "Your readings" in w["table"].value and "2.0" in w["table"].value
    w["point"].value = "2"  # choosing in the list selects the point
    assert tool.current == "2"
    tool.measure("I", 0, 0).measure("1", 0, 0).measure("2", 0, 0)
    assert "copy the lines" in w["status"].value
    tool.close()


@pytest.mark.parametrize("kwargs, name", [
    (dict(names=()), "names"),
    (dict(names=("a", "a")), "names"),
    (dict(extent_mm=(1, 0, 0, 1)), "extent_mm"),
    (dict(extent_mm=(0, 1, 0)), "extent_mm"),
    (dict(decimals=5), "decimals"),
    (dict(origin="middle"), "origin"),
])
def test_bad_arguments_raise_value_error(kwargs, name):
    args = {"image": np.zeros((4, 4)), "extent_mm": (0, 1, 0, 1), "names": ("a",), **kwargs}
    with pytest.raises(ValueError, match=name):
        MeasureTool(**args)


def test_bad_readings_raise_value_error():
    tool = _tool()
    with pytest.raises(ValueError, match="name"):
        tool.measure("IV", 0, 0)
    with pytest.raises(ValueError, match="x_mm"):
        tool.measure("I", float("nan"), 0)
    with pytest.raises(ValueError, match="name"):
        tool.select("IV")
    with pytest.raises(ValueError, match="3 values"):
        tool.load([1.0], [2.0])
    tool.close()


@pytest.mark.parametrize("sheet", [relief_sheet(0), tilt_sheet(99)], ids=["relief-00", "tilt-99"])
def test_tools_on_a_lab_sheet_mark_the_true_points(sheet):
    photo = photo_tool(sheet)
    assert photo.names == sheet.names and photo.extent_mm == (-90.0, 90.0, -90.0, 90.0)
    for name, (x, y) in sheet.marks("photo").items():
        ring = photo.marks[name][0]
        assert (ring.get_xdata()[0], ring.get_ydata()[0]) == (x, y)
    image = photo.ax.images[0].get_array()
    assert image.shape == (1024, 1024)
    plan = plan_tool(sheet)
    assert plan.extent_mm == (0.0, float(sheet.plan_size_mm[0]), 0.0, float(sheet.plan_size_mm[1]))
    np.testing.assert_allclose([plan.marks[n][0].get_xdata()[0] for n in sheet.names], sheet.plan_xy_mm[:, 0])
    assert plan.ax.collections  # the contours
    assert "1:10\u202f000" in plan.ax.get_title()  # the book's number format (aerophoto.i18n.numfmt)
    photo.close()
    plan.close()
