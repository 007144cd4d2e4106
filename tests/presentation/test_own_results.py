"""Issue 12, chapters 00–02 and the lecture pages: own results only after the task, every variant on the sliders,
the variant policy's table, readable large plans, lecture mode that ignores a remembered number."""

from __future__ import annotations

import json
import math
import os

import numpy as np
import pytest

from aerophoto import book, flight
from aerophoto.demos import own
from aerophoto.demos.flight_plan import OWN_TABLE_TASKS, FlightPlanDemo, own_overlaps, own_plan_table, own_side_allowance
from aerophoto.demos.footprint import FootprintDemo, own_footprint
from aerophoto.demos.quality import QualityDemo, crab_limit_plot
from aerophoto.tasks import ch00
from aerophoto.variants import variant, variant_for_index

V57 = variant("19-0457")
NONE = lambda task: False  # noqa: E731
ALL = lambda task: True  # noqa: E731


# --------------------------------------------------------------------------- own results after the task
def test_locked_notes_name_the_tasks_and_after_calls_only_when_all_passed():
    calls = []
    locked = own.after(lambda t: t == "task-01-1", ["task-01-1", "task-01-2"], lambda: calls.append(1), "why")
    assert isinstance(locked, own.Locked) and calls == []
    assert repr(locked) == "Answer task 01.2 first: why" and "🔒" in locked._repr_html_()
    assert own.after(ALL, ["task-01-1"], lambda: 42) == 42
    assert own.task_label("task-05-2") == "05.2"
    with pytest.raises(ValueError, match="task_id = 'H_m' is not a task id"):
        own.task_label("H_m")


def test_own_plan_table_unlocks_the_rows_of_each_task_as_it_passes():
    p = flight.plan(V57)
    locked = own_plan_table(V57, NONE)
    assert set(OWN_TABLE_TASKS) == set(flight.TABLE_ATTRS) - {"S_km2", "h_m"}
    for attr, value in zip(flight.TABLE_ATTRS, locked["value"]):
        if attr in OWN_TABLE_TASKS:
            assert value == f"answer task {OWN_TABLE_TASKS[attr][5:7]}.{OWN_TABLE_TASKS[attr][8:]} first"
        else:
            assert value == pytest.approx(getattr(p, attr))
    half = own_plan_table(V57, lambda t: t == "task-01-1")
    rows = dict(zip(flight.TABLE_ATTRS, half["value"]))
    assert rows["H_m"] == pytest.approx(11859.0) and rows["Bx_km"] == pytest.approx(p.Bx_km, abs=0.01)
    assert rows["K"] == "answer task 01.2 first" and rows["tau_s"] == "answer task 01.3 first"
    full = own_plan_table(V57, ALL)
    assert list(full["value"]) == list(p.table(rounded=True)["value"])


def test_own_side_allowance_and_overlaps_wait_for_their_tasks():
    assert "01.1 and 01.2" in repr(own_side_allowance(V57, NONE))
    assert "01.2" in repr(own_side_allowance(V57, lambda t: t == "task-01-1"))
    table = own_side_allowance(V57, ALL)
    assert int(table.loc["K"].iloc[0]) == flight.plan(V57).K
    assert isinstance(own_overlaps(V57, NONE), own.Locked)
    ov = own_overlaps(V57, ALL)
    assert ov.loc["lowest ground Z_min", "forward, %"] == pytest.approx(flight.plan(V57).Px_percent, abs=0.01)
    assert ov.loc["highest ground Z_max", "forward, %"] == pytest.approx(60.0, abs=0.01)


def test_own_footprint_opens_on_the_students_camera_only_after_task_00_1():
    assert "00.1" in repr(own_footprint(V57, NONE))
    demo = own_footprint(V57, ALL)
    try:
        assert demo.values["f_mm"] == 670 and demo.values["m"] == 17700
        assert demo.result.H_m == pytest.approx(11859.0)  # the guide's scheme as it is, never clamped
    finally:
        demo.close()


# --------------------------------------------------------------------------- demos: the guide's example, every variant
@pytest.mark.parametrize("cls", [FootprintDemo, FlightPlanDemo, QualityDemo])
def test_demos_open_on_the_guides_example(cls):
    demo = cls()
    try:
        assert demo.values["f_mm"] == 100
        if "m" in demo.values and cls is not QualityDemo:
            assert demo.values["m"] == 12000
    finally:
        demo.close()


@pytest.mark.parametrize("i", [0, 57, 99])
def test_every_variant_of_the_scheme_fits_the_sliders(i):
    v = variant_for_index(i)
    for cls, wanted in ((FootprintDemo, dict(f_mm=v.f_mm, m=v.m, alpha_deg=v.alpha_deg, lambda_deg=v.lambda_deg)),
                        (FlightPlanDemo, dict(f_mm=v.f_mm, m=v.m, W_kmh=v.W_kmh, Lx_km=v.Lx_km, Ly_km=v.Ly_km)),
                        (QualityDemo, dict(f_mm=v.f_mm))):
        params = {p.name: p for p in cls.params}
        for name, x in wanted.items():
            p = params[name]
            assert p.lo <= x <= p.hi, f"{cls.__name__}.{name} = {x} outside {p.lo}…{p.hi}"
            assert abs((x - p.lo) / p.step - round((x - p.lo) / p.step)) < 1e-9, f"{name} = {x} not on a step"


def test_flight_overview_of_a_large_plan_is_a_readable_schematic():
    demo = FlightPlanDemo()
    try:
        assert demo.view.shown == 682 and "schematic" not in demo.view.ax_plan.get_title()
        demo.set(f_mm=670, m=17700, W_kmh=770, Lx_km=82, Ly_km=87)   # variant 57: 41 strips × 66 photos
        p = demo.result.plan
        assert (p.K, p.n) == (41, 66)
        title = demo.view.ax_plan.get_title()
        assert "schematic: 1 in 3 strips and 1 in 3 photos drawn" in title and "N = 2706 photos" in title  # 4 digits: no group
        ys = np.unique(np.asarray(demo.view.centres.get_offsets())[:, 1])
        assert len(ys) <= 25 and np.min(np.diff(ys)) >= 2 * p.By_km   # the drawn strips stay apart
        # the drawn strips still fly both ways (an odd step): arrows east and west
        assert len(demo.view.arrows_e.get_xdata()) and len(demo.view.arrows_w.get_xdata())
        assert ys[0] == pytest.approx(demo.result.strip_y_km[0]) and ys[-1] == pytest.approx(demo.result.strip_y_km[-1])
        demo.draw(force=True)
    finally:
        demo.close()


def test_crab_limit_figure_marks_no_students_camera_and_reaches_every_lens():
    ax = crab_limit_plot()
    labels = [t.get_text() for t in ax.get_legend().get_texts()]
    assert not [t for t in labels if "camera" in t] and any("610" in t for t in labels)
    assert ax.get_xlim()[1] >= 1090
    ax2 = crab_limit_plot(f_mm=670)
    assert any("670" in t.get_text() for t in ax2.get_legend().get_texts())


# --------------------------------------------------------------------------- chapter 00's variant policy
def test_scheme_table_covers_every_variant_and_flags_what_is_beyond_real_practice():
    t = ch00.scheme_table()
    assert list(t.index) == [f"{a:02d}–{a + 9:02d}" for a in range(0, 100, 10)]
    assert t.loc["00–09", "f, mm"] == "100–190" and t.loc["90–99", "f, mm"] == "1000–1090"
    assert t.loc["90–99", "photo scale"] == "1:21\u202f000–21\u202f900" and t.loc["90–99", "W, km/h"] == "1100–1190"
    assert "real mapping lenses" in t.loc["00–09", "the lens"]
    assert t.loc["60–69", "the lens"].startswith("beyond real practice")
    assert t.loc["00–09", "the aircraft"] == "survey aircraft"
    assert t.loc["90–99", "the aircraft"].startswith("beyond real practice")
    assert t.loc["90–99", "the height"].startswith("beyond real practice")
    # the heights are bands of whole kilometres that contain every H of the group and show no variant's H
    shown = {float(x) for band in t["H = f·m, km"] for x in band.split("–")}
    for i in range(100):
        v = variant_for_index(i)
        lo, hi = (float(x) for x in t.iloc[i // 10]["H = f·m, km"].split("–"))
        assert lo <= v.H_m / 1000 <= hi
        assert not [s for s in shown if abs(s * 1000 - v.H_m) <= 0.005 * v.H_m], (i, v.H_m)
    with pytest.raises(ValueError, match="step"):
        ch00.scheme_table(step=0)


# --------------------------------------------------------------------------- lecture mode
def test_setup_for_a_lecture_ignores_every_students_number(tmp_path, monkeypatch):
    monkeypatch.setenv("AEROPHOTO_HOME", str(tmp_path))
    (tmp_path / "student.json").write_text(json.dumps({"record_book": "19-0457"}), encoding="utf-8")
    monkeypatch.setenv("AEROPHOTO_RECORD_BOOK", "19-0412")
    assert book.setup(live=False, quiet=True).i == 12
    v = book.setup(live=False, lecture=True)
    assert v.i == 0 and v.f_mm == 100
    assert json.loads((tmp_path / "student.json").read_text(encoding="utf-8"))["record_book"] == "19-0457"
    with pytest.raises(ValueError, match="lecture=True"):
        book.setup("19-0457", lecture=True)


def test_lecture_pages_are_built_from_the_chapters_demo_cells():
    c = book.chapter("01")
    nb = book.lecture_notebook(c)
    ids = [cell.get("id") for cell in nb.cells]
    assert ids == ["setup", "demo-flight-plan", "demo-flight-plan-notes", "links"]
    setup, demo = nb.cells[0].source, nb.cells[1].source
    assert "aerophoto.setup(lecture=True)" in setup and "RECORD_BOOK" not in setup
    assert demo.splitlines()[-1].startswith("lecture_view(demo, '01 · Planning the aerial survey (guide §2)'")
    assert book.lecture_page(c) == "lectures/01_flight_planning.ipynb"
    assert f"]({book.lecture_page(c)})" in book.lecture_table_markdown()


def test_a_demo_cell_that_does_not_end_with_the_demo_cannot_make_a_lecture_page():
    c = book.chapter("01")
    d = c.demos[0]
    with pytest.raises(ValueError, match="must end with the demo's name"):
        book._lecture_demo("demo = FlightPlanDemo()\ndemo.widget()", c, d, "x")
    with pytest.raises(ValueError, match="does not call aerophoto.setup"):
        book._lecture_setup("import aerophoto\nv = aerophoto.setup()", "x")


def test_lecture_view_lays_the_demo_out_for_one_screen():
    from aerophoto.demos.lecture import MAX_PER_COLUMN, lecture_view

    demo = QualityDemo()
    try:
        import ipywidgets as w

        view = lecture_view(demo, "02 · Quality", "Rough mosaic", full_screen=True)
        sensor, top, band, main = view.children   # the page sensor first (aerophoto.fit)
        assert "aerophoto-demo" in view._dom_classes and view.layout.min_height == "max(780px, 100vh)"
        assert "aerophoto-main" in main._dom_classes and "aerophoto-band" in band._dom_classes
        cols = band.children
        # a column holds at most MAX_PER_COLUMN + 1 rows: a heading and its sliders, or small groups together
        assert all(len(col.children) <= MAX_PER_COLUMN + 1 for col in cols)
        sliders = [c for col in cols for c in col.children if not isinstance(c, w.HTML)]
        assert len(sliders) == len(QualityDemo.params)
        assert demo.table in main.children[1].children and demo.legend in main.children[1].children
        demo.set(f_mm=200)
        assert top.children[1].description == "Projector"
        top.children[2].click()   # Reset, at the right of the title line
        assert demo.values["f_mm"] == 100
    finally:
        demo.close()
