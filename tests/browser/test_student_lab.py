"""The student's JupyterLab (``aerophoto-course lab``) has no nbgrader authoring tools; the instructor's keeps them.

The README's student command writes the workbook and starts ``aerophoto-course lab``; nbgrader, installed into
the same environment for the instructor, adds a *Nbgrader* menu, a *Validate* button, a *Create Assignment*
side panel and server extensions that log "No nbgrader_config.py file found" in a folder that is not a course.
Both Labs here open the same workbook in the same kind of folder; only the command differs.
"""

from __future__ import annotations

import shutil
import tempfile
from pathlib import Path

import pytest

from . import harness as h
from .demo_checks import assert_clean

pytestmark = [pytest.mark.browser, pytest.mark.timeout(900)]

START = "workbook/00_start_here.ipynb"
#: what nbgrader's extensions put into JupyterLab (as the instructor's Lab shows them)
NBGRADER_MENU = "Nbgrader"
NBGRADER_BUTTON = "Validate"
NBGRADER_PANEL = "Create Assignment"
WARNING = "No nbgrader_config.py file found"


@pytest.fixture(scope="module")
def student_folder():
    """A folder with a fresh workbook in it, written by the README's command (``aerophoto-course workbook``)."""
    import subprocess
    import sys

    d = Path(tempfile.mkdtemp(prefix="aerophoto-student-"))
    try:
        done = subprocess.run([sys.executable, "-m", "aerophoto.course", "--notebooks", str(h.NOTEBOOKS),
                               "workbook", "--dest", str(d / "workbook")], capture_output=True, text=True,
                              timeout=300)
        assert done.returncode == 0, done.stdout + done.stderr
        assert (d / START).is_file(), done.stdout
        yield d
    finally:
        shutil.rmtree(d, ignore_errors=True)


def test_the_students_lab_has_no_nbgrader_tools_and_no_config_warning(browser, student_folder, tab):
    server = h.StudentLabServer(student_folder, START).start()
    try:
        page = tab.page
        h.open_lab_notebook(page, server, START)
        page.locator(".jp-NotebookPanel-toolbar").first.wait_for(state="visible", timeout=h.T_PAGE)
        page.locator(".lm-MenuBar-itemLabel", has_text="Help").first.wait_for(state="visible", timeout=h.T_PAGE)
        tab.add("student-lab", page.screenshot())
        chrome = h.lab_chrome(page)
        assert "Kernel" in chrome["menus"] and chrome["toolbar"], chrome  # a working Lab, fully drawn
        assert NBGRADER_MENU not in chrome["menus"], chrome["menus"]
        assert not [t for t in chrome["toolbar"] if NBGRADER_BUTTON in t], chrome["toolbar"]
        assert not [t for t in chrome["sidebar"] if NBGRADER_PANEL in t], chrome["sidebar"]
        disabled = page.evaluate("() => JSON.parse(document.getElementById('jupyter-config-data').textContent)"
                                 ".disabledExtensions")
        assert "@jupyter/nbgrader" in disabled, disabled
        # the workbook runs: its setup cell (the first code cell) gives the guide's example, no number typed
        page.evaluate("""() => { const nb = window.jupyterapp.shell.currentWidget.content;
                                 nb.activeCellIndex = nb.widgets.findIndex((c) => c.model.type === 'code');
                                 return window.jupyterapp.commands.execute('notebook:run-cell'); }""")
        page.locator(".jp-OutputArea-output", has_text="variant i = 00").first.wait_for(state="visible",
                                                                                         timeout=h.T_RUN)
        log = server.log_text()
        assert WARNING not in log, [ln for ln in log.splitlines() if "nbgrader" in ln.lower()]
        assert "nbgrader.server_extensions" not in log, [ln for ln in log.splitlines() if "nbgrader" in ln]
        assert_clean(tab, "the student's Lab")
    finally:
        server.__exit__(None, None, None)


def test_the_instructors_lab_keeps_nbgrader(browser, student_folder, tab):
    """Plain ``jupyter lab`` in the same folder: nbgrader's menu, Validate and Create Assignment are there."""
    server = h.LabServer(student_folder).start()
    try:
        page = tab.page
        h.open_lab_notebook(page, server, START)
        page.locator(".lm-MenuBar-itemLabel", has_text=NBGRADER_MENU).first.wait_for(state="visible",
                                                                                      timeout=h.T_PAGE)
        chrome = h.lab_chrome(page)
        tab.add("instructor-lab", page.screenshot())
        assert NBGRADER_MENU in chrome["menus"], chrome["menus"]
        assert [t for t in chrome["toolbar"] if NBGRADER_BUTTON in t], chrome["toolbar"]
        assert [t for t in chrome["sidebar"] if NBGRADER_PANEL in t], chrome["sidebar"]
        assert "nbgrader.server_extensions.formgrader" in server.log_text()
    finally:
        server.__exit__(None, None, None)
