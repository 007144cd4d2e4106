"""What the instructor is shown of a submission is cleaned (aerophoto.course.sanitize), and honest slips in the
check cells are undone before nbgrader reads a notebook (aerophoto.course.restore).  Fast unit tests; the hostile
class (tests/test_grading_hostile.py) runs the same through nbgrader and a browser."""

from __future__ import annotations

import copy

import nbformat
from nbformat.v4 import new_code_cell, new_markdown_cell, new_notebook, new_output, new_raw_cell

from aerophoto.course.wire import ANSWERS_MIME
from aerophoto.course.restore import restore_cells
from aerophoto.course.sanitize import _md2html, clean_html, is_clean, sanitize_notebook

ATTACKS = ['<script>alert(1)</script>', '<img src=x onerror=alert(2)>', '[a](javascript:alert(3))',
           '<a href="JaVaScRiPt:alert(4)">a</a>', '<img src="http://evil.example/p.png">', '<form><input></form>',
           '<svg onload=alert(5)>', '<iframe src="http://evil.example"></iframe>', '<a href="java&#x09;script:x">t</a>',
           '<style>*{background:url(http://evil.example)}</style>', '<object data=x></object>', '<!-- c -->',
           '<div style="background:url(http://evil.example)">s</div>', '<math><mi xlink:href="javascript:x">m</mi></math>']


def test_markdown_renders_clean_as_nbgrader_renders_it_and_keeps_the_text():
    for a in ATTACKS:
        nb = new_notebook(cells=[new_markdown_cell(f"**Note** {a} end")])
        sanitize_notebook(nb)
        rendered = _md2html(nb.cells[0].source)  # what nbgrader's formgrade and feedback templates do
        assert is_clean(rendered), (a, rendered)
        assert "Note" in rendered and "end" in rendered
        low = rendered.lower()
        assert "javascript" not in low.replace("java&#x09;script", "") and "evil.example" not in low.split(">", 1)[0]


def test_outputs_keep_text_and_images_and_the_answer_record_only():
    png = "iVBORw0KGgo="
    cell = new_code_cell("x", outputs=[
        new_output("display_data", data={"text/html": '<b>ok</b><img src=x onerror=alert(1)>', "text/plain": "ok"}),
        new_output("display_data", data={"application/javascript": "alert(2)"}),
        new_output("display_data", data={"image/svg+xml": "<svg onload=alert(3)/>", "image/png": png}),
        new_output("display_data", data={ANSWERS_MIME: {"task": "task-00-1", "values": {}}}),
    ])
    nb = new_notebook(cells=[cell, new_raw_cell("<script>alert(4)</script>", metadata={"raw_mimetype": "text/html"})])
    nb.metadata["widgets"] = {"application/vnd.jupyter.widget-state+json": {}}
    sanitize_notebook(nb)
    outs = nb.cells[0].outputs
    assert outs[0].data["text/html"] == "<b>ok</b><img>" and outs[0].data["text/plain"] == "ok"
    assert list(outs[1].data) == ["text/plain"] and "not shown" in outs[1].data["text/plain"]
    assert sorted(outs[2].data) == ["image/png", "text/plain"]  # the SVG dropped, said in text
    assert outs[3].data[ANSWERS_MIME] == {"task": "task-00-1", "values": {}}
    assert "<script>" not in nb.cells[1].source and "raw_mimetype" not in nb.cells[1].metadata
    assert "widgets" not in nb.metadata
    nbformat.validate(nb)


def test_clean_html_allows_data_images_and_web_links_only():
    assert clean_html('<a href="https://example.org">x</a>') == '<a href="https://example.org">x</a>'
    assert clean_html('<img src="data:image/png;base64,AAAA">') == '<img src="data:image/png;base64,AAAA">'
    assert clean_html('<img src="data:text/html;base64,AAAA">') == "<img>"


def _release():
    check = new_code_cell("checks.check_task('task-00-1', v)", id="task-00-1-check", metadata={"nbgrader": {
        "grade": True, "grade_id": "task-00-1-check", "locked": True, "points": 3, "schema_version": 3,
        "solution": False, "task": False}})
    answer = new_code_cell("H_m = ...", id="task-00-1-answer", metadata={"nbgrader": {
        "grade": False, "grade_id": "task-00-1-answer", "locked": False, "schema_version": 3, "solution": True,
        "task": False}})
    return new_notebook(cells=[new_markdown_cell("t", id="t"), answer, check])


def test_check_cells_are_restored_by_grade_id_and_copies_removed():
    rel = _release()
    ref = [c for c in rel.cells if c.get("metadata", {}).get("nbgrader")]
    # grade: false
    nb = copy.deepcopy(rel)
    nb.cells[2].metadata.nbgrader["grade"] = False
    assert restore_cells(nb, ref) and nb.cells[2].metadata.nbgrader == rel.cells[2].metadata.nbgrader
    # copied below itself, the original's metadata stripped
    nb = copy.deepcopy(rel)
    pasted = copy.deepcopy(nb.cells[2])
    pasted["id"] = "pasted"
    del nb.cells[2].metadata["nbgrader"]
    nb.cells.append(pasted)
    done = restore_cells(nb, ref)
    assert [c.id for c in nb.cells] == ["t", "task-00-1-answer", "task-00-1-check"] and any("copy" in d for d in done)
    # the answer cell keeps the student's code, gets its metadata back
    nb = copy.deepcopy(rel)
    nb.cells[1].source = "H_m = 5"
    del nb.cells[1].metadata["nbgrader"]
    restore_cells(nb, ref)
    assert nb.cells[1].source == "H_m = 5" and nb.cells[1].metadata.nbgrader["solution"] is True
    # an untouched notebook is left as it is
    nb = copy.deepcopy(rel)
    assert restore_cells(nb, ref) == [] and nb == rel
