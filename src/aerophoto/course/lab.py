"""The student's JupyterLab: ``aerophoto-course lab`` — the workbook without nbgrader's authoring tools.

nbgrader installs itself into the environment for everyone: its JupyterLab extension (``@jupyter/nbgrader``:
the *Nbgrader* menu, *Create Assignment*, *Validate*, the formgrader) and its four Jupyter server extensions,
which log "No nbgrader_config.py file found" in every folder that is not a course.  A student needs none of it.
``aerophoto-course lab`` starts JupyterLab for this launch only without them:

* the server extensions are switched off on the command line,
  ``--ServerApp.jpserver_extensions={"nbgrader.server_extensions.formgrader": False, …}`` (the command line wins
  over every ``jupyter_server_config.d/nbgrader.json``);
* the lab extension is disabled through JupyterLab's page config — ``labconfig/page_config.json`` with
  ``{"disabledExtensions": {"@jupyter/nbgrader": true}}``, the file ``jupyter labextension disable`` writes —
  in a folder of its own (``<AEROPHOTO_HOME>/student-lab``) put first on ``JUPYTER_CONFIG_PATH`` for this
  process only.

Nothing is changed for anyone else: the instructor's ``jupyter lab`` (e.g. in the course folder, for the
formgrader) keeps every nbgrader tool.  The command replaces itself with JupyterLab (``os.execve``), so Ctrl+C
and the terminal behave as with ``jupyter lab``.
"""

from __future__ import annotations

import json
import os
import sys
from pathlib import Path

__all__ = ["NBGRADER_SERVER_EXTENSIONS", "NBGRADER_LAB_EXTENSION", "student_config_dir", "student_lab_command",
           "student_lab_env", "default_notebook", "main"]

NBGRADER_SERVER_EXTENSIONS = (
    "nbgrader.server_extensions.formgrader",
    "nbgrader.server_extensions.validate_assignment",
    "nbgrader.server_extensions.assignment_list",
    "nbgrader.server_extensions.course_list",
)
"""nbgrader's Jupyter server extensions (its ``jupyter_server_config.d/nbgrader.json``), all off for a student."""
NBGRADER_LAB_EXTENSION = "@jupyter/nbgrader"
"""nbgrader's JupyterLab extension: the Nbgrader menu, Create Assignment, Validate, formgrader, assignment list."""


def student_config_dir(home: Path | None = None) -> Path:
    """Write (each launch) and return the config folder of the student's Lab: ``labconfig/page_config.json``."""
    from ..book import state_dir

    d = Path(home) if home is not None else state_dir() / "student-lab"
    page = d / "labconfig" / "page_config.json"
    page.parent.mkdir(parents=True, exist_ok=True)
    page.write_text(json.dumps({"disabledExtensions": {NBGRADER_LAB_EXTENSION: True}}, indent=1) + "\n",
                    encoding="utf-8")
    return d


def student_lab_env(config_dir: Path, base: dict | None = None) -> dict:
    """The environment of the student's Lab: ``config_dir`` first on ``JUPYTER_CONFIG_PATH``."""
    env = dict(os.environ if base is None else base)
    rest = env.get("JUPYTER_CONFIG_PATH", "")
    env["JUPYTER_CONFIG_PATH"] = os.pathsep.join([str(config_dir), *([rest] if rest else [])])
    return env


def student_lab_command(notebook=None, extra=()) -> list[str]:
    """``python -m jupyterlab [notebook] --ServerApp.jpserver_extensions={nbgrader's: False} [extra…]``."""
    off = {name: False for name in NBGRADER_SERVER_EXTENSIONS}
    cmd = [sys.executable, "-m", "jupyterlab"]
    if notebook is not None:
        cmd.append(str(notebook))
    return [*cmd, f"--ServerApp.jpserver_extensions={off!r}", *extra]


def default_notebook(workbook: Path | None = None) -> Path:
    """The student's start page: ``workbook/00_start_here.ipynb`` beside ``notebooks/``."""
    from .common import default_notebooks_dir

    wb = Path(workbook) if workbook is not None else default_notebooks_dir().parent / "workbook"
    return wb / "00_start_here.ipynb"


def main(notebook=None, extra=(), *, out=print, exec_=True) -> int:
    """Start the student's JupyterLab on ``notebook`` (default: the workbook's start page).

    ``extra`` are passed on to JupyterLab (``--no-browser``, ``--port 8890``, …).  With ``exec_`` the process
    becomes JupyterLab (never returns); otherwise JupyterLab runs as a child and its exit status is returned.
    """
    nb = Path(notebook) if notebook is not None else default_notebook()
    if not nb.exists():
        out(f"aerophoto-course lab: {nb} does not exist — write your workbook first: aerophoto-course workbook")
        return 2
    env = student_lab_env(student_config_dir())
    cmd = student_lab_command(nb, extra)
    out(f"JupyterLab for the workbook (no nbgrader authoring tools): {nb}")
    if exec_:
        os.execve(sys.executable, cmd, env)
    import subprocess

    return subprocess.call(cmd, env=env)
