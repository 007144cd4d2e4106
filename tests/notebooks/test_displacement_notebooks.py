"""Chapters 03 and 04: the teacher's copy shows the reference tables once the tasks pass (issue 12).

(That the student book shows none of the student's own graded values before they answer is tested for every
chapter by tests/notebooks/test_no_answers_on_screen.py.)

The student book (answer cells unanswered) is run for the record book 19-0457 (variant 57) and for another
student (19-0412, variant 12).  Every graded value of variant 57 — in every rounding a notebook could print it —
is looked for in every output: streams, displayed data and the widgets' state (the demos' tables live there).
A number found for 57 that the other student's run shows as well is not the student's own (the guide's worked
example, the demo at variant 00); any other is a leak.  The teacher's copy, whose tasks pass, shows the reference
tables in the results cell; the student book only asks to answer first.
"""

from __future__ import annotations

import json
import os
import re

import nbformat
import pytest
from nbclient import NotebookClient

from aerophoto import tasks
from aerophoto.variants import variant_for_index
from conftest import NOTEBOOKS

CHAPTERS = [("03_relief_displacement", "03", "task-03-3"), ("04_tilt_displacement", "04", "task-04-4")]


def _run(nb, record_book: str, home) -> nbformat.NotebookNode:
    os.environ["AEROPHOTO_HOME"] = str(home)
    os.environ["AEROPHOTO_RECORD_BOOK"] = record_book
    try:
        NotebookClient(nb, timeout=600, kernel_name="python3", allow_errors=True,
                       resources={"metadata": {"path": str(NOTEBOOKS)}}).execute()
    finally:
        os.environ.pop("AEROPHOTO_RECORD_BOOK", None)
    return nb


def _texts(nb) -> str:
    parts = []
    for c in nb.cells:
        for o in c.get("outputs", []) if c.cell_type == "code" else []:
            if o.get("output_type") == "stream":
                parts.append(o.get("text", ""))
            elif o.get("output_type") == "error":
                parts.append(str(o.get("evalue", "")))
            for k, val in (o.get("data") or {}).items():
                if not k.startswith("image/"):
                    parts.append(val if isinstance(val, str) else json.dumps(val, ensure_ascii=False))
    parts.append(json.dumps(nb.metadata.get("widgets", {}), ensure_ascii=False))
    # pictures travel as base64 (the live figures' frames in the widget state): their letters are not numbers
    return re.sub(r"[A-Za-z0-9+/=]{80,}", " ", "\n".join(parts))


def _renderings(x: float) -> set:
    """How a notebook could print x: 0–3 decimals, with or without thousands separators; at least 3 digits."""
    out = set()
    for dec in range(4):
        plain = f"{abs(x):.{dec}f}"
        if len(plain.replace(".", "").lstrip("0")) < 3:
            continue
        out.add(plain)
        out.add(f"{abs(x):,.{dec}f}")
        out.add(f"{abs(x):,.{dec}f}".replace(",", " "))
    return out


def _pattern(s: str) -> str:
    """s as a number of its own: not a piece of a longer number or of a name (model ids are hex)."""
    return r"(?<![\w.,])" + re.escape(s) + r"(?![\w])"


def _found(s: str, text: str) -> bool:
    return re.search(_pattern(s), text) is not None


def _graded_values(chapter: str, v) -> list:
    out = []
    for task in tasks.chapter_tasks(chapter):
        for name, value in task.answers(v).items():
            values = value if isinstance(value, list) else [value]
            for x in values:
                if isinstance(x, bool) or (isinstance(x, int) and abs(x) < 100):
                    continue  # counts and verdicts cannot be told from any other small number
                out.append((task.id, name, float(x)))
    return out


@pytest.mark.slow
@pytest.mark.parametrize("stem, chapter, last", CHAPTERS, ids=[c[0] for c in CHAPTERS])
def test_the_teachers_copy_shows_the_reference_tables(stem, chapter, last, tmp_path):
    from aerophoto.course import teacher_version

    nb = teacher_version(nbformat.read(str(NOTEBOOKS / f"{stem}.ipynb"), as_version=4))
    _run(nb, "19-0457", tmp_path)
    results = next(c for c in nb.cells if c.get("id") == "results")
    html = "".join(o.get("data", {}).get("text/html", "") for o in results.outputs)
    first = "Table 2" if chapter == "03" else "Table 5"
    assert first in html and "against the geometry" in html
    # and the reference is variant 57's: its m_cp stands in the first table
    m_cp = tasks.answers(f"task-{chapter}-{1 if chapter == '03' else 2}", variant_for_index(57))["m_cp"]
    from aerophoto.i18n.numfmt import numbers_in

    assert round(m_cp) in numbers_in(html)
