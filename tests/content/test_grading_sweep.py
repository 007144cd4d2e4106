"""One verdict (issue 27): every task × variants × honest forms, on screen and in the grader.

For each task and variant the sweep (:mod:`.grading_sweep`) hands in the reference answers, the answers rounded to
four significant digits and to their printed units, and every accepted method of the task's table (and that
method rounded), and asserts: the check cell's verdict is the grader's (``aerophoto.checks.check_task`` ✓ exactly
when ``aerophoto.course.score.grade_task`` gives full marks) and every honest form earns full marks.  Every
catalogued slip the variant tells apart fails both, and the screen names it.  It also measures the deviations
the grading table states (:func:`aerophoto.tasks.table.measure_variant`) and holds ``docs/grading_deviations.json``
to them.

The README's command runs every task on :data:`SAMPLE`; ``-m exhaustive`` (CI's second step) runs all 100
variants in :data:`PARTS` parts, each caching the references of its variants for the run.
"""

from __future__ import annotations

import json
import math
from pathlib import Path

import pytest

from aerophoto import tasks
from aerophoto.tasks import table
from aerophoto.variants import variant_for_index

from .grading_sweep import cached_references, summary, sweep_one

ROOT = Path(__file__).resolve().parents[2]
SAMPLE = (0, 57, 99)
PARTS = 4
TASK_IDS = [t.id for t in tasks.all_tasks()]


def _problems(outcomes) -> list[str]:
    return [f"{o.task} v{o.variant:02d} [{o.form}]: {p}" for o in outcomes if (p := o.problem())]


@pytest.mark.parametrize("task_id", TASK_IDS)
def test_the_screen_and_the_grader_agree_on_a_sample(task_id):
    task = tasks.get(task_id)
    outcomes = []
    with cached_references():
        for i in SAMPLE:
            outcomes += sweep_one(task, variant_for_index(i))
    assert not _problems(outcomes), _problems(outcomes)[:10]
    s = summary(outcomes)
    assert s["split"] == 0 and s["honest marked down"] == 0
    # the forms were really tried: the reference, two roundings and every accepted method, per variant
    forms = {o.form for o in outcomes if o.honest}
    assert {"reference", "4 digits", "printed"} <= forms
    assert all(any(f.startswith(f"method: {m.name}") for f in forms) for m in task.methods if m.submit)


def _deviations() -> dict:
    return json.loads((ROOT / table.DEVIATIONS).read_text(encoding="utf-8"))


def _check_measured(recorded: dict, part: dict, variants) -> list[str]:
    """The JSON's extremes must bound this part's measurements, and equal them where they occur in this part."""
    bad = []
    for tid, answers in part.items():
        rec = recorded.get(tid, {})
        for name, kinds in answers.items():
            r = rec.get(name, {})
            for kind in ("rounding", "methods"):
                for k, (d, i) in kinds[kind].items():
                    top = r.get(kind, {}).get(k)
                    if top is None or d > top[0] * 1.02 + 1e-9:
                        bad.append(f"{tid} {name} {kind} {k!r}: {d:.3g} at i={i} above the recorded {top}")
                    elif top[1] in variants and not math.isclose(d, top[0], rel_tol=0.02, abs_tol=1e-9) and i == top[1]:
                        bad.append(f"{tid} {name} {kind} {k!r}: {d:.3g} at i={i}, recorded {top}")
            for k, (d, i, _n) in kinds["slips"].items():
                low = r.get("slips", {}).get(k)
                if low is None or d < low[0] / 1.02 - 1e-9:
                    bad.append(f"{tid} {name} slip {k[:50]!r}: {d:.3g} at i={i} below the recorded {low}")
    return bad


@pytest.mark.slow
@pytest.mark.exhaustive
@pytest.mark.parametrize("part", range(PARTS))
def test_the_sweep_over_every_task_and_variant(part):
    variants = list(range(part, 100, PARTS))
    outcomes, measured = [], {}
    with cached_references():
        for i in variants:
            v = variant_for_index(i)
            for task in tasks.all_tasks():
                outcomes += sweep_one(task, v)
                table.merge(measured.setdefault(task.id, {}), table.measure_variant(task, v), i)
    problems = _problems(outcomes)
    assert not problems, f"{len(problems)} problems: {problems[:20]}"
    s = summary(outcomes)
    assert s["submissions"] > 2000 and s["split"] == 0, s
    assert not _check_measured(_deviations(), measured, set(variants)), _check_measured(_deviations(), measured,
                                                                                         set(variants))[:20]


def test_every_recorded_accepted_deviation_is_below_one_tolerance_and_every_slip_above():
    """The table's claim, on the recorded measurements (the exhaustive sweep proves the record)."""
    rec = _deviations()
    assert set(rec) == set(TASK_IDS)
    for tid, answers in rec.items():
        for name, kinds in answers.items():
            if name == table.HIDDEN:
                continue
            for kind in ("rounding", "methods"):
                for k, (d, i) in kinds[kind].items():
                    assert d <= 1.0, (tid, name, k, d, i)
            for k, (d, i, n) in kinds["slips"].items():
                assert d > 1.0, (tid, name, k, d, i)
