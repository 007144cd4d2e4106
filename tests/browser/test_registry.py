"""The browser tests and the lecture index know every chapter that has a live demo (no browser needed)."""

from __future__ import annotations

import json
import re
import sys
from pathlib import Path

import nbformat

from . import harness as h
from .chapters import CHAPTERS, LECTURE_INDEX


def _demo_cells(path: Path) -> list[str]:
    nb = nbformat.read(str(path), as_version=4)
    return [c.get("id", "") for c in nb.cells if c.cell_type == "code" and str(c.get("id", "")).startswith("demo-")]


def _chapters_with_demos() -> dict[str, list[str]]:
    out = {}
    for p in sorted(h.NOTEBOOKS.glob("[0-9]*.ipynb")):  # the book's chapters (not _template)
        cells = _demo_cells(p)
        if cells:
            out[p.name] = cells
    return out


def test_every_demo_cell_is_exercised_in_the_browser():
    found = _chapters_with_demos()
    listed = {c.notebook: [d.cell for d in c.demos] for c in CHAPTERS}
    missing = {nb: cells for nb, cells in found.items() if sorted(cells) != sorted(listed.get(nb, []))}
    assert not missing, (f"demo cells not (or not exactly) listed in tests/browser/chapters.py: {missing}; "
                         f"listed there: {listed}")
    gone = [nb for nb in listed if nb not in found]
    assert not gone, f"tests/browser/chapters.py lists chapters without demo cells: {gone}"


def test_each_listed_demo_names_the_class_its_cell_builds():
    for chapter in CHAPTERS:
        nb = nbformat.read(str(h.NOTEBOOKS / chapter.notebook), as_version=4)
        cells = {c.get("id"): c.source for c in nb.cells}
        for demo in chapter.demos:
            cls = demo.cls.rsplit(".", 1)[-1]
            assert cls and re.search(rf"\b{cls}\b", cells[demo.cell]), (
                f"{chapter.notebook} [{demo.cell}] does not build {demo.cls!r}; fix tests/browser/chapters.py")
            assert demo.timed_slider in [label for label, _key in demo.sliders]


def test_lecture_index_links_every_chapter_with_a_demo_and_its_lecture_page():
    from aerophoto.book import LECTURES_DIR

    index = h.NOTEBOOKS / LECTURE_INDEX
    nb = nbformat.read(str(index), as_version=4)
    text = "\n".join(c.source for c in nb.cells if c.cell_type == "markdown")
    missing = [name for name in _chapters_with_demos() if f"]({name})" not in text]
    assert not missing, f"{LECTURE_INDEX} has no link to {missing}"
    missing = [name for name in _chapters_with_demos()
               if f"]({LECTURES_DIR}/{name})" not in text or not (h.NOTEBOOKS / LECTURES_DIR / name).is_file()]
    assert not missing, f"{LECTURE_INDEX} links no lecture page (or it is missing) for {missing}"


def test_lecture_pages_hold_the_chapters_demo_cells_and_no_task():
    from aerophoto.book import lecture_page

    for chapter in CHAPTERS:
        nb = nbformat.read(str(h.NOTEBOOKS / lecture_page(chapter)), as_version=4)
        ids = [c.get("id") for c in nb.cells]
        assert [i for i in ids if i.startswith("demo-") and not i.endswith("-notes")] == [d.cell for d in chapter.demos]
        code = "\n".join(c.source for c in nb.cells if c.cell_type == "code")
        assert "aerophoto.setup(lecture=True)" in code and "RECORD_BOOK" not in code
        assert "check_task" not in code and "nbgrader" not in json.dumps(nb.cells)


def test_voila_config_denies_the_extensions_it_cannot_load_and_culls_kernels():
    cfg = json.loads((h.ROOT / "voila.json").read_text(encoding="utf-8"))
    installed = set()
    for base in (Path(sys.prefix) / "share" / "jupyter" / "labextensions",):
        for pkg in base.glob("**/package.json"):
            if "node_modules" in pkg.parts or "static" in pkg.parts:
                continue
            installed.add(json.loads(pkg.read_text(encoding="utf-8"))["name"])
    deny = set(cfg["VoilaConfiguration"]["extension_denylist"])
    # Lab-only extensions that log load errors in a Voilà page when present
    for name in ("@jupyter/nbgrader", "@jupyter-notebook/lab-extension"):
        if name in installed:
            assert name in deny, f"voila.json must deny-list {name}"
    # the widgets and live figures must stay
    assert not deny & {"@jupyter-widgets/jupyterlab-manager", "jupyter-matplotlib"}
    km = cfg["MappingKernelManager"]
    assert km["cull_idle_timeout"] > 0 and km["cull_interval"] > 0
    assert km.get("cull_connected", False) is False, "an open lecture tab must keep its kernel"


# --------------------------------------------------------------------------- the student's Lab (no browser)
def test_the_readmes_first_command_opens_the_workbook_in_the_students_lab():
    from aerophoto.course import lab

    readme = (h.ROOT / "README.md").read_text(encoding="utf-8")
    first = next(ln for ln in readme.splitlines() if ln.startswith("python -m pip install"))
    assert first.endswith("&& aerophoto-course workbook && aerophoto-course lab"), first
    assert lab.default_notebook() == h.ROOT / "workbook" / "00_start_here.ipynb"


def test_the_students_lab_switches_off_every_nbgrader_extension_installed(tmp_path):
    import ast
    import sys

    from aerophoto.course import lab

    installed = set()
    for d in (Path(sys.prefix) / "etc" / "jupyter" / "jupyter_server_config.d",):
        for f in d.glob("*.json"):
            exts = json.loads(f.read_text(encoding="utf-8")).get("ServerApp", {}).get("jpserver_extensions", {})
            installed |= {name for name in exts if name.startswith("nbgrader")}
    assert installed and installed <= set(lab.NBGRADER_SERVER_EXTENSIONS), installed
    cmd = lab.student_lab_command("workbook/00_start_here.ipynb", ["--no-browser"])
    assert cmd[1:4] == ["-m", "jupyterlab", "workbook/00_start_here.ipynb"] and cmd[-1] == "--no-browser"
    off = ast.literal_eval(next(a for a in cmd if a.startswith("--ServerApp.jpserver_extensions=")).split("=", 1)[1])
    assert off == {name: False for name in lab.NBGRADER_SERVER_EXTENSIONS}
    d = lab.student_config_dir(tmp_path / "cfg")
    page = json.loads((d / "labconfig" / "page_config.json").read_text(encoding="utf-8"))
    assert page == {"disabledExtensions": {"@jupyter/nbgrader": True}}
    env = lab.student_lab_env(d, {"JUPYTER_CONFIG_PATH": "/elsewhere"})
    assert env["JUPYTER_CONFIG_PATH"].split(":") == [str(d), "/elsewhere"]


def test_the_lab_command_line(tmp_path, capsys):
    from aerophoto.course.cli import main

    assert main(["lab", str(tmp_path / "missing.ipynb")]) == 2
    assert "aerophoto-course workbook" in capsys.readouterr().out
