"""Every chapter's teacher's copy executes headless with no error and no warning; all are stored without outputs.

The repository's notebooks are the student book (answer cells hold template lines only); the teacher's copy
(:func:`aerophoto.course.teacher_version`, the package's reference solution in each answer cell) is built here
and run, so every check cell must pass.
"""

import json
import os

import nbformat
import pytest
from nbclient import NotebookClient

from conftest import all_notebooks, lecture_pages

NOTEBOOKS = all_notebooks()
IDS = [p.stem for p in NOTEBOOKS]
STORED = NOTEBOOKS + lecture_pages()  # the lecture pages are executed by tests/browser/test_lectures.py
STORED_IDS = IDS + [f"lectures/{p.stem}" for p in lecture_pages()]


def test_there_are_notebooks():
    names = {p.stem for p in NOTEBOOKS}
    assert "00_start_here" in names


@pytest.mark.parametrize("path", STORED, ids=STORED_IDS)
def test_notebook_is_stored_without_outputs(path):
    nb = json.loads(path.read_text(encoding="utf-8"))
    dirty = [c.get("id") for c in nb["cells"] if c["cell_type"] == "code" and (c.get("outputs") or c.get("execution_count"))]
    assert not dirty, f"{path.name}: cells with outputs {dirty}; clear outputs before committing"


@pytest.mark.parametrize("path", STORED, ids=STORED_IDS)
def test_notebook_cells_have_stable_ids(path):
    nb = nbformat.read(str(path), as_version=4)
    ids = [c.get("id") for c in nb.cells]
    assert len(ids) == len(set(ids)), f"{path.name}: duplicate cell ids"
    assert "setup" in ids, f"{path.name}: the first code cell must have id 'setup'"
    first_code = next(c for c in nb.cells if c.cell_type == "code")
    assert first_code.get("id") == "setup", f"{path.name}: the setup cell must be the first code cell"


def _problem_outputs(nb):
    """Error outputs, and stderr text that carries a warning or a traceback."""
    problems = []
    for cell in nb.cells:
        if cell.cell_type != "code":
            continue
        for out in cell.get("outputs", []):
            if out.get("output_type") == "error":
                problems.append((cell.get("id"), f"{out.get('ename')}: {out.get('evalue')}"))
            elif out.get("output_type") == "stream" and out.get("name") == "stderr":
                text = out.get("text", "")
                if "Warning" in text or "Traceback" in text or "Error" in text:
                    problems.append((cell.get("id"), text.strip()[:500]))
    return problems


@pytest.mark.slow
@pytest.mark.parametrize("path", NOTEBOOKS, ids=IDS)
def test_teachers_copy_executes_without_error_or_warning(path, tmp_path):
    from aerophoto.course import teacher_version

    nb = teacher_version(nbformat.read(str(path), as_version=4))
    env_home = tmp_path / "home"
    env_home.mkdir()
    os.environ["AEROPHOTO_HOME"] = str(env_home)
    client = NotebookClient(
        nb,
        timeout=600,
        kernel_name="python3",
        resources={"metadata": {"path": str(path.parent)}},
        allow_errors=False,
    )
    client.execute()
    problems = _problem_outputs(nb)
    assert not problems, f"{path.name}: {problems}"
    checks = [c for c in nb.cells if c.get("metadata", {}).get("nbgrader", {}).get("grade")]
    passed = ["passed" in "".join(o.get("text", "") for o in c.get("outputs", [])) for c in checks]
    assert all(passed), f"{path.name}: a check of the teacher's copy did not pass"
