"""The package's layers: imports point downwards only, and no module grows past ~900 lines.

The layers (docs/CONTRIBUTING.md, "The house"):

1. foundation — ``_validate``, ``_chapters`` (the chapter modules' naming rule), ``_digits`` (whole numbers grouped as the book writes them), ``geometry`` (camera, projection, Terrain), ``plane`` (2-D fits, rays), ``variants``, ``cache`` (the disk cache of the chapters' heavy data), ``diskcache`` (the
   student machine's verified cache)
2. physics — one module or package per topic, pure functions and frozen dataclasses
3. the virtual world — ``terrain``, ``site``, ``simulate``, ``render`` (data only)
4. the course's content — ``guide/`` (printed tables and their audits), ``labs/`` (the students' lab worlds),
   ``tasks/`` (graded tasks: rubrics only)
5. presentation — ``plots``, ``tables``, ``blit``, ``widgets``, ``fit``, ``demos/``, ``i18n``
6. course — ``checks``, ``gradebook``, ``book``, ``glossary_page``, ``course``, ``nbtools``, ``report``, ``lite``, ``website`` (the web book)

A module may import from its own layer or any lower one.  Every import counts, also one inside a function.
Three rules more: ``labs/`` never imports ``tasks/``; nothing under ``demos/`` or ``report/`` imports ``tasks/``;
``report/`` never constructs a live demo (its figures come from the plotting functions the demos use).
"""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

PKG = Path(__file__).resolve().parents[2] / "src" / "aerophoto"

LAYERS = {
    1: ("_validate", "_chapters", "_digits", "geometry", "plane", "variants", "cache", "diskcache"),
    2: ("flight", "quality", "displacement", "mosaic", "triangulation", "stereo", "projective", "control",
        "accuracy", "interpretation", "spectral", "bundle", "dem", "budget", "rectify", "soilmap"),
    3: ("terrain", "site", "simulate", "render"),
    4: ("guide", "labs", "tasks"),
    5: ("plots", "tables", "blit", "widgets", "fit", "demos", "i18n"),
    6: ("checks", "gradebook", "book", "glossary_page", "course", "nbtools", "report", "lite", "website", "__init__", "__main__"),
}
LAYER_OF = {name: layer for layer, names in LAYERS.items() for name in names}
MAX_LINES = 900


def _modules():
    return sorted(p for p in PKG.rglob("*.py") if "__pycache__" not in p.parts and "course_data" not in p.parts)


def _top(path: Path) -> str:
    rel = path.relative_to(PKG).with_suffix("")
    return rel.parts[0]


def _imported(path: Path) -> set[str]:
    """The top-level aerophoto modules that ``path`` imports (absolute or relative, anywhere in the file)."""
    rel = path.relative_to(PKG).with_suffix("")
    package = list(rel.parts[:-1]) if rel.parts[-1] != "__init__" else list(rel.parts[:-1])
    out = set()
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.name.startswith("aerophoto."):
                    out.add(a.name.split(".")[1])
        elif isinstance(node, ast.ImportFrom):
            if node.level == 0:
                mod = node.module or ""
                if mod == "aerophoto":
                    out.update(a.name for a in node.names)
                elif mod.startswith("aerophoto."):
                    out.add(mod.split(".")[1])
                continue
            base = package[: len(package) - (node.level - 1)] if node.level > 1 else package
            if node.level - 1 > len(package):
                continue
            full = base + (node.module.split(".") if node.module else [])
            if full:
                out.add(full[0])
            else:  # "from . import x" at the package's top
                out.update(a.name for a in node.names)
    return out


def test_every_module_has_a_layer():
    unknown = sorted({_top(p) for p in _modules()} - set(LAYER_OF) - {"course_data", "data"})
    assert not unknown, f"modules without a layer in tests/course/test_layers.py (and docs/CONTRIBUTING.md): {unknown}"


@pytest.mark.parametrize("path", _modules(), ids=lambda p: str(p.relative_to(PKG)))
def test_imports_point_downwards(path):
    here = _top(path)
    if here not in LAYER_OF:
        pytest.fail(f"{path.relative_to(PKG)} has no layer")
    upward = sorted(m for m in _imported(path) if m in LAYER_OF and LAYER_OF[m] > LAYER_OF[here])
    assert not upward, (f"{path.relative_to(PKG)} (layer {LAYER_OF[here]}) imports "
                        f"{[(m, LAYER_OF[m]) for m in upward]} from a higher layer")


@pytest.mark.parametrize("path", _modules(), ids=lambda p: str(p.relative_to(PKG)))
def test_no_module_is_too_big(path):
    n = sum(1 for _ in path.open(encoding="utf-8"))
    assert n <= MAX_LINES, f"{path.relative_to(PKG)} has {n} lines; split it by concern (≤ {MAX_LINES})"


#: (packages whose modules must not import these top-level modules, why)
FORBIDDEN = (
    (("labs",), "tasks", "the rubrics build on the lab worlds, never the other way round"),
    (("demos", "report"), "tasks", "presentation and the report never reach into the rubrics: a demo takes what it "
                                   "needs from labs/, the report reads the registry through aerophoto.gradebook"),
)


@pytest.mark.parametrize("path", _modules(), ids=lambda p: str(p.relative_to(PKG)))
def test_no_forbidden_imports(path):
    here = _top(path)
    for packages, target, why in FORBIDDEN:
        if here in packages:
            assert target not in _imported(path), f"{path.relative_to(PKG)} imports {target}: {why}"


def _constructed_demos(path: Path) -> list:
    """Names ending in ``Demo`` that ``path`` calls (constructs), anywhere in the file."""
    out = []
    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Call):
            f = node.func
            name = f.id if isinstance(f, ast.Name) else f.attr if isinstance(f, ast.Attribute) else ""
            if name.endswith("Demo"):
                out.append(name)
    return out


@pytest.mark.parametrize("path", sorted((PKG / "report").glob("*.py")), ids=lambda p: p.name)
def test_the_report_draws_no_live_demo(path):
    made = _constructed_demos(path)
    assert not made, f"report/{path.name} constructs {made}: draw with the demos' plotting functions (ax=None)"


def test_the_layer_test_sees_relative_and_lazy_imports():
    # a probe of the reader itself: known imports of known modules
    assert "geometry" in _imported(PKG / "flight.py")
    assert "tasks" in _imported(PKG / "checks.py")  # imported inside a function
    assert "labs" in _imported(PKG / "tasks" / "ch06.py")
    assert "labs" in _imported(PKG / "demos" / "fotoschema.py")  # inside functions
    assert "FootprintDemo" in _constructed_demos(PKG / "demos" / "footprint.py")  # the probe sees a construction


# ------------------------------------------------------------------ the answer's road: notebook → gradebook
COURSE = PKG / "course"
KERNEL_SIDE = {"wire", "verdict", "probe", "score"}
"""The parts of aerophoto.course the student's kernel loads (through aerophoto.checks)."""


def _imported_modules(path: Path) -> set[str]:
    """The aerophoto modules ``path`` imports, dotted below ``aerophoto`` (``"course.wire"``, ``"checks"``);
    ``from P import name`` counts as ``P.name`` when that is a module of the package, else as ``P``."""
    rel = path.relative_to(PKG).with_suffix("")
    package = list(rel.parts[:-1])
    out = set()

    def add(parts: list[str], names=()):
        base = ".".join(parts)
        subs = [f"{base}.{n}" if base else n for n in names]
        found = [s for s in subs if (PKG / s.replace(".", "/")).with_suffix(".py").exists()
                 or (PKG / s.replace(".", "/")).is_dir()]
        out.update(found or ([base] if base else []))

    for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
        if isinstance(node, ast.Import):
            for a in node.names:
                if a.name.startswith("aerophoto."):
                    out.add(a.name[len("aerophoto."):])
        elif isinstance(node, ast.ImportFrom):
            names = [a.name for a in node.names]
            if node.level == 0:
                mod = node.module or ""
                if mod == "aerophoto" or mod.startswith("aerophoto."):
                    add(mod.split(".")[1:], names)
                continue
            if node.level - 1 > len(package):
                continue
            base = package[: len(package) - (node.level - 1)]
            add(base + (node.module.split(".") if node.module else []), names)
    return out


def _course_parts(path: Path) -> set[str]:
    return {m.split(".")[1] for m in _imported_modules(path) if m.startswith("course.")}


def test_the_import_reader_sees_submodules():
    assert "course.wire" in _imported_modules(PKG / "checks.py")
    assert "course.outcomes" in _imported_modules(COURSE / "trusted.py")


def test_the_answer_road_runs_downhill():
    # nothing of the grader imports the student-facing checks …
    climbing = sorted(p.name for p in COURSE.glob("*.py") if "checks" in _imported_modules(p))
    assert not climbing, f"course modules that import aerophoto.checks: {climbing}"
    # … and checks uses only the kernel-side parts of course
    assert _course_parts(PKG / "checks.py") <= KERNEL_SIDE, _course_parts(PKG / "checks.py")
    # the answer record and the kernel probe: the standard library only
    for name in ("wire", "probe"):
        assert _imported_modules(COURSE / f"{name}.py") == set(), name
    assert _imported_modules(COURSE / "verdict.py") <= {"i18n", "variants", "course.wire"}
    # the trusted side: records in (wire), scores out (score → verdict, tasks)
    assert {"wire", "score"} <= _course_parts(COURSE / "trusted.py")
    assert _imported_modules(COURSE / "score.py") <= {"tasks", "i18n", "course.verdict", "course.wire"}


def test_checks_and_course_have_no_import_cycle():
    mods = {"checks": PKG / "checks.py"} | {f"course.{p.stem}": p for p in COURSE.glob("*.py")}
    graph = {m: {i for i in _imported_modules(p) if i in mods and i != m} for m, p in mods.items()}
    done, path = set(), []

    def visit(m):
        if m in path:
            pytest.fail(f"import cycle: {' → '.join(path[path.index(m):] + [m])}")
        if m in done:
            return
        path.append(m)
        for n in sorted(graph[m]):
            visit(n)
        path.pop()
        done.add(m)

    for m in sorted(graph):
        visit(m)


def test_no_course_module_builds_its_classes_on_attribute_access():
    # nbgrader's way: the preprocessor and the kernel manager are top-level classes of their modules
    lazy = sorted(p.name for p in COURSE.glob("*.py") if p.name != "__init__.py" and any(
        isinstance(n, ast.FunctionDef) and n.name == "__getattr__" for n in ast.parse(p.read_text("utf-8")).body))
    assert not lazy, f"module __getattr__ in {lazy}"


def test_the_students_kernel_loads_the_answer_record_alone():
    import subprocess
    import sys

    code = ("import sys, {mod}; print(sorted(m for m in sys.modules if m.startswith(('aerophoto', 'nbgrader', "
            "'jupyter_client', 'nbclient', 'zmq'))))")

    def loaded(mod):
        out = subprocess.run([sys.executable, "-c", code.format(mod=mod)], capture_output=True, text=True,
                             check=True).stdout
        return set(ast.literal_eval(out.strip()))

    assert loaded("aerophoto.course.wire") == {"aerophoto", "aerophoto.course", "aerophoto.course.wire"}
    with_checks = loaded("aerophoto.checks")
    assert not {m for m in with_checks if not m.startswith("aerophoto")}, with_checks
    assert {m.split(".")[2] for m in with_checks if m.startswith("aerophoto.course.")} <= KERNEL_SIDE
