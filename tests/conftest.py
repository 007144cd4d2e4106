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
