"""docs/grading_table.md is rendered from the tasks' data and docs/grading_deviations.json: fresh, and complete."""

from __future__ import annotations

import json
from pathlib import Path

from aerophoto import tasks
from aerophoto.tasks import table

ROOT = Path(__file__).resolve().parents[2]


def test_the_grading_table_is_fresh():
    measured = json.loads((ROOT / table.DEVIATIONS).read_text(encoding="utf-8"))
    doc = (ROOT / table.DOC).read_text(encoding="utf-8")
    assert doc == table.render(measured), "run python -m aerophoto.tasks (and --measure when the numbers moved)"


def test_the_table_lists_every_task_its_answers_methods_and_adopted_readings():
    doc = (ROOT / table.DOC).read_text(encoding="utf-8")
    for t in tasks.all_tasks():
        head = f"### Task {t.chapter}.{t.id.split('-')[2]} — "
        assert head in doc, head
        section = doc.split(head, 1)[1].split("\n### ", 1)[0]
        for a in t.spec:
            assert f"| `{a.name}` |" in section, (t.id, a.name)
        for m in t.methods:
            assert m.name.replace("|", "\\|") in section, (t.id, m.name)
    assert doc.count("*the reading the book adopts*") == 3 and doc.count("*the other reading, accepted*") == 3


def test_the_recorded_deviations_cover_every_task_and_number():
    measured = json.loads((ROOT / table.DEVIATIONS).read_text(encoding="utf-8"))
    for t in tasks.all_tasks():
        rec = measured[t.id]
        numbers = [a.name for a in t.spec if a.kind in ("value", "values") and not a.integer]
        assert set(numbers) <= set(rec), (t.id, set(numbers) - set(rec))
        for name in numbers:
            assert {"4 significant digits", "printed unit"} <= set(rec[name]["rounding"]), (t.id, name)
