"""Shared test set-up: a private AEROPHOTO_HOME so tests never read a student's remembered number."""

import os
import tempfile
from pathlib import Path

import pytest
from hypothesis import settings

# property tests draw the same examples on every machine and every run (no example database)
settings.register_profile("aerophoto", derandomize=True, database=None)
settings.load_profile("aerophoto")

ROOT = Path(__file__).resolve().parents[1]
NOTEBOOKS = ROOT / "notebooks"

# before any test imports aerophoto.book: no remembered record-book number leaks in or out
os.environ["AEROPHOTO_HOME"] = tempfile.mkdtemp(prefix="aerophoto-home-")
os.environ.pop("AEROPHOTO_RECORD_BOOK", None)
os.environ.setdefault("MPLBACKEND", "Agg")


def all_notebooks():
    """The book's notebooks: the chapters and the lecture index (not the template ``_template.ipynb``, not the
    generated lecture pages in ``notebooks/lectures/`` — see :func:`lecture_pages`)."""
    return sorted(p for p in NOTEBOOKS.glob("*.ipynb") if not p.name.startswith("_"))


def lecture_pages():
    """The generated lecture pages (``notebooks/lectures/NN_*.ipynb``): demos only, run by the browser tests."""
    return sorted((NOTEBOOKS / "lectures").glob("*.ipynb"))


@pytest.fixture(autouse=True)
def _close_figures():
    yield
    import matplotlib.pyplot as plt

    plt.close("all")


# ------------------------------------------------------------------------------ parallel runs (pytest-xdist)
#: test files whose tests are spread over the workers one by one: long parametrised runs whose per-worker set-up
#: is cheap (a kernel, a JupyterLab or Voilà server). Every other file runs whole on one worker, so that its
#: module-scoped set-ups (the hostile class, the grading course, the hub, the Monte Carlo studies, the sites) are
#: built once, not once per worker.
SPREAD = {"test_notebooks.py", "test_no_answers_on_screen.py", "test_graded_tasks.py", "test_lab.py",
          "test_voila.py", "test_lectures.py", "test_own_results.py", "test_displacement_notebooks.py"}


@pytest.hookimpl(tryfirst=True)
def pytest_collection_modifyitems(config, items):
    """Group every test of a file on one xdist worker (``--dist loadgroup``), except the files in SPREAD."""
    for item in items:
        name = item.path.name
        if name not in SPREAD and not any(True for _ in item.iter_markers("xdist_group")):
            item.add_marker(pytest.mark.xdist_group(name=str(item.path.relative_to(ROOT))))
