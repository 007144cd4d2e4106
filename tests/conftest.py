"""Shared test set-up: a private AEROPHOTO_HOME so tests never read a student's remembered number.

The tests are laid out as the package's layers (foundation/, physics/, world/, content/, presentation/, course/,
notebooks/, browser/).  Each folder is a package (an ``__init__.py``), so pytest puts this folder on ``sys.path``
and ``from conftest import NOTEBOOKS`` reads this file from any of them; an area's own helpers live in its
``conftest.py`` (``from .conftest import …``).  Basenames stay unique over the tree: SPREAD names files by them.
"""

import atexit
import os
import shutil
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
# one disk cache for the whole run (aerophoto.cache: the site, the guide's stereo pair …), shared by the xdist
# workers and the kernels and servers they start: what is the same for everyone is built once per run, as on a
# student's machine.  The first process (pytest's controller) makes it and removes it at the end; the workers
# inherit it.  tests/foundation/test_cache.py holds a read entry equal to the built value, bit for bit.
if not os.environ.get("AEROPHOTO_CACHE_DIR"):
    os.environ["AEROPHOTO_CACHE_DIR"] = tempfile.mkdtemp(prefix="aerophoto-cache-")
    atexit.register(shutil.rmtree, os.environ["AEROPHOTO_CACHE_DIR"], True)


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
          "test_voila.py", "test_lectures.py", "test_own_results.py", "test_displacement_notebooks.py", "test_lite.py"}


def pytest_xdist_make_scheduler(config, log):
    """``--dist loadgroup`` here: every file whole on one worker, except the files in SPREAD (test by test).

    xdist's own loadgroup reads ``xdist_group`` marks by appending the group to each item's node id, which
    pytest 9.2 no longer lets a plugin do (``Item._nodeid`` is gone; xdist 3.8 assigns it to no effect), so
    the marks were silently ignored and a file's module-scoped set-ups were built on both workers.  The
    scheduler below gets the same grouping from the node ids themselves, through xdist's public hook.
    """
    if config.getvalue("dist") != "loadgroup":
        return None
    from xdist.scheduler import LoadGroupScheduling

    class FileGroups(LoadGroupScheduling):
        def _split_scope(self, nodeid: str) -> str:
            if nodeid.rfind("@") > nodeid.rfind("]"):  # an explicit xdist_group, should xdist read them again
                return super()._split_scope(nodeid)
            path = nodeid.split("::", 1)[0]
            return nodeid if Path(path).name in SPREAD else path

    return FileGroups(config, log)


@pytest.fixture(params=["book style", "matplotlib defaults"])
def plot_style(request):
    """Run a figure test under the book's style (as in every notebook: a grid over the data) and under matplotlib's
    defaults (the blitting tests: tests/presentation/test_blit.py, tests/presentation/test_blit_mosaic.py)."""
    from aerophoto import plots

    if request.param == "book style":
        with plots.style_context():
            yield request.param
    else:
        yield request.param
