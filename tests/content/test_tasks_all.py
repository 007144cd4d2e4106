"""What every graded task must do, one test parametrised over all 46 (the chapter files keep what is particular to
a chapter): an unanswered or another variant's submission earns nothing, its data is complete — printed units,
methods, tolerances that admit the printed precision — and its module holds its own code.  The grading sweep
(test_grading_sweep.py) tries the references, every honest form and every slip, on screen and in the grader."""

from __future__ import annotations

import inspect

import numpy as np
import pytest

from aerophoto import checks, tasks
from aerophoto.course import score, verdict
from aerophoto.tasks import rounding, table
from aerophoto.variants import variant_for_index

SAMPLE = (0, 57, 99)
TASKS = tasks.all_tasks()
IDS = [t.id for t in TASKS]


@pytest.mark.parametrize("task_id", IDS)
def test_an_unanswered_task_earns_nothing_and_says_so(task_id):
    v = variant_for_index(57)
    g = score.grade_task(task_id, v, {})
    assert g.score == 0.0 and "no answer yet" in g.first_failure
    with pytest.raises(checks.WrongAnswer, match="no answer yet"):
        checks.check_task(task_id, v)
    checks.reset()


@pytest.mark.parametrize("task_id", IDS)
def test_another_variants_answers_do_not_pass(task_id):
    task = tasks.get(task_id)
    v = variant_for_index(1)
    mine = score.grade_task(task_id, v, task.answers(v))
    others = [score.grade_task(task_id, v, task.answers(variant_for_index(i))) for i in (17, 41, 86, 99)]
    assert mine.score == task.points and any(g.score < task.points for g in others)


@pytest.mark.parametrize("task_id", IDS)
def test_every_number_states_its_printed_unit_and_admits_it(task_id):
    """tolerance ≥ half a printed unit (plus what the chapter's methods need: the sweep proves that part)."""
    task = tasks.get(task_id)
    for a in task.spec:
        if a.kind not in ("value", "values") or a.integer:
            assert a.printed is None, (a.name, "a count, verdict or choice has no printed unit")
            continue
        assert a.printed is not None, a.name
        for i in SAMPLE:
            ref = np.asarray(task.answers(variant_for_index(i))[a.name], dtype=float)
            w = np.asarray(table.width(a, ref))
            # half a printed unit is admitted: the verdict's "≤ tolerance" is inclusive (verdict.FLOAT_SLACK)
            assert np.all(w * (1 + verdict.FLOAT_SLACK) >= 0.5 * a.printed), (a.name, i, float(np.min(w)), a.printed)


@pytest.mark.parametrize("task_id", IDS)
def test_every_task_states_its_methods(task_id):
    task = tasks.get(task_id)
    assert task.methods and task.methods[0].submit is None, "the first method is the reference's"
    assert all(m.name and m.note for m in task.methods)
    readings = [m.reading for m in task.methods if m.reading]
    assert readings in ([], ["adopted", "other"]), readings


def test_the_articles_ambiguous_readings_are_accepted():
    """Issue 30's readings: 14.1 (m_D), 16.1 (“zr”), 17.3 (the transfer) — the other reading is a method."""
    for task_id in ("task-14-1", "task-16-1", "task-17-3"):
        task = tasks.get(task_id)
        other = next(m for m in task.methods if m.reading == "other")
        v = variant_for_index(71)
        g = score.grade_task(task_id, v, other.submission(task, v))
        assert g.passed, (task_id, g.checks)


def test_the_table_uses_the_verdicts_default_tolerance():
    assert table._TOL_REL == verdict.TOL_REL == checks.TOL_REL
    assert rounding._FLOAT_SLACK == verdict.FLOAT_SLACK


@pytest.mark.parametrize("task_id", IDS)
def test_every_tasks_code_lives_in_its_own_module(task_id):
    """The grader's probe trusts a task's answers, slips and hidden checks only from the task's own module."""
    cls = type(tasks.get(task_id))
    for name in ("answers", "slips", "hidden"):
        fn = getattr(cls, name)
        src = inspect.getsourcefile(getattr(fn, "__wrapped__", fn))
        assert src.endswith((f"{cls.__module__.split('.')[-1]}.py", "base.py")), (name, src)


@pytest.mark.parametrize("task_id", IDS)
def test_malformed_answers_never_stop_the_grader(task_id):
    v = variant_for_index(3)
    for junk in (None, "abc", [1, 2], {"a": 1}, float("nan"), True, object()):
        g = score.grade_task(task_id, v, {n: junk for n in tasks.get(task_id).names})
        assert g.score < g.points or tasks.get(task_id).partial


def test_the_rounding_rule_admits_what_a_student_writes():
    for x, printed in ((12000.9, 1), (0.000543404, 1e-8), (61.0, 0.01), (-2.61859, 0.01), (0.0903876, 0.0001)):
        a = rounding.allowance(x, printed)
        for w in (rounding.round_sig(x), rounding.round_to(x, printed), rounding.written(x, printed)):
            assert abs(w - x) <= a * (1 + 1e-12), (x, printed, w, a)
    # the allowance of a derived value is what moving each input by its allowance does to it
    val, tol = rounding.propagated(lambda a, b: a / b, [(300.0, 0.01), (25.0, 0.01)])
    assert val == 12.0 and tol == pytest.approx(12 * (0.05 / 300 + 0.005 / 25), rel=1e-3)
    h = rounding.consistency("q", 12.004, 0.001, lambda a, b: a / b, [(300.0, 0.01), (25.0, 0.01)])
    assert rounding.holds(h) and not rounding.holds(rounding.consistency(
        "q", 12.01, 0.001, lambda a, b: a / b, [(300.0, 0.01), (25.0, 0.01)]))
