"""The graded tasks of chapter 15 (aerophoto.tasks.ch15, labs.ch15): references pass, every variant works, no graded
value in the inputs (the tests that hold chapters 14 and 15 together are in test_tasks_ch14.py)."""

import numpy as np
import pytest

from aerophoto import tasks
from aerophoto.labs import ch15 as lab15
from aerophoto.tasks import ch15
from aerophoto.variants import variant_for_index

VARIANTS = [variant_for_index(i) for i in (0, 1, 17, 58, 99)]
IDS = ("task-15-1", "task-15-2", "task-15-3")


#: a spread of variants (every variant's grading: the exhaustive sweep, test_grading_sweep.py)
SAMPLE = (0, 9, 18, 27, 36, 45, 54, 63, 72, 81, 90, 99)


@pytest.mark.parametrize("which", [pytest.param(SAMPLE, id="sample")])
def test_every_variant_works_for_chapter_15(which):
    for i in which:
        v = variant_for_index(i)
        sv = lab15.student_block(v)
        a2 = ch15.FindBlunders().answers(v)
        assert a2["blunder_point"] == sv.blunder_point, i
        assert a2["bad_control"] == sv.bad_control, i
        a1 = ch15.BlockSize().answers(v)
        assert a1["n_unknowns"] == 6 * sv.meas.n_photos + 3 * sv.meas.n_points
        a3 = ch15.LocateFieldPoint().answers(v)
        fp = ch15.solve_block(sv).field_point(ch15.field_point_id(v))
        assert np.hypot(fp["dX_m"], fp["dY_m"]) < 5 * a3["a_m"] + 0.1


def test_no_graded_value_is_shown_in_the_task_inputs():
    v = VARIANTS[3]
    inp = tasks.inputs("task-15-3", v)
    assert set(inp) == {"point", "block"}
    table = inp["block"].points_table()
    assert "X, m" not in table.columns and "X control, m" in table.columns  # only the control's coordinates
    assert np.isnan(table.loc[inp["point"], "X control, m"])
