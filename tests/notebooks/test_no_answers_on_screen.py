"""No graded value of the student's own variant is on screen before the student has answered it (issue 12).

Every chapter of the registry (:data:`aerophoto.book.CHAPTERS`) is run headless as the student receives it —
nbgrader's release version (:func:`aerophoto.course.student_version` of :func:`~aerophoto.course.source_version`),
every answer cell left at its template (``H_m = ...``), so every check cell fails with "no answer yet" — for
two sample record books, and everything the notebook shows is searched for the graded values of that variant
(every number of ``aerophoto.tasks.chapter_tasks(nn)[k].answers(v)``):

* the cells' outputs: printed text, errors, ``text/plain``, ``text/html`` (tags, styles and embedded images
  removed; an image's alt text kept), ``text/markdown`` and ``text/latex``;
* the widget states the run leaves (nbclient's ``store_widget_state``): every widget's ``value``,
  ``description``, tooltip and option labels — the demos' tables are HTML widgets;
* the text of every matplotlib figure — titles, axis labels, legends, annotations (not tick labels) — of
  every static figure drawn and every live figure still open at the end.

**When a number on screen counts as a leak** of the graded value x (tolerance t: the Answer's own, else 0.5 %):

1. it is within t of x — typing it in would pass the check.  Numbers are read as they are printed:
   ``11 859``, ``11,859``, ``1.27``, ``−2.6``, ``1.2e+04``;
2. x is not a value the student is given: a graded value within t of one of the variant's inputs
   (f, m, W, L_x, L_y, Z, α, λ, p_x, p_y, M, the frame, i, the record-book digits) or of a number in the task's
   inputs (``task.inputs(v)``: a table, a dataclass, a dict — e.g. chapter 02's measurements) is not searched:
   showing the input is allowed;
3. *distinctive* values — those that need four or more significant digits to land within t (N = 2 706 photos,
   t_max = 0.004675 s, a photo coordinate of 163.27 ± 0.05 mm) — count wherever they appear: nothing else on screen hits
   them by chance, so even a table of every variant's results is caught.  Every other value (H = 11 859 m
   ± 0.5 %, 1.27 km, 60.1 %, 41 strips, a crab limit of 10°) is also printed by chance — in the guide's worked
   example, a step number, another quantity of a demo's table — so it counts only where the number depends on
   the variant: it is shown for variant A in a place (a cell's outputs, the widgets, the figures' texts) that
   does not show it for variant B, whose own value differs.  (A table listing every variant's three-digit
   results would show the same numbers for both and is not caught: the book has none; keep it that way.)
   A value B shares is not searched unless distinctive.  Booleans and choices are not numbers and are not
   searched.

The two variants are ``19-0457`` (i = 57: f = 670 mm, beyond real practice) and ``19-0403`` (i = 03); each is
searched, with the other as the reference of rule 3.  The
kernel is started once for the module and reused for every chapter and both variants (``%reset -f``, a fresh
record book and the checks forgotten between runs): a kernel start with the package's imports costs ~1.5 s and
the virtual site's build ~6 s on this 2-core machine, paid once instead of 32 times.  Measured: all 16
chapters, two variants each, in 140 s (under load from other work 460 s).
"""

from __future__ import annotations

import html
import json
import math
import os
import re
import time
from pathlib import Path

import nbformat
import pytest

from aerophoto import book, tasks
from aerophoto.variants import variant
from conftest import NOTEBOOKS

RECORD_BOOKS = ("19-0457", "19-0403")
"""The two sample variants; each is searched, the other tells variant-dependent numbers apart."""

# --------------------------------------------------------------------------------------------------
# reading numbers off the screen

_NUMBER = re.compile(
    r"(?<![\w.])[-−+]?(?:\d{1,3}(?:[ \u00a0\u2009\u202f,]\d{3})+|\d+)(?:\.\d+)?(?:[eE][-+−]?\d+)?(?![\w])"
    r"|(?<![\w.])[-−+]?\.\d+(?![\w])"
)
_SIMPLE = re.compile(r"(?<![\w.])[-−+]?\d+(?:\.\d+)?(?:[eE][-+−]?\d+)?(?![\w])")
_TAGS = re.compile(r"<(script|style)\b.*?</\1>|<[^>]*>", re.S | re.I)
_ALT = re.compile(r"\balt\s*=\s*(['\"])(.*?)\1", re.S | re.I)
_DATA_URI = re.compile(r"data:[\w/+.-]+;base64,[A-Za-z0-9+/=]+")


def _to_float(token: str) -> float | None:
    """A number read off the screen by the book's reader (:func:`aerophoto.i18n.numfmt.parse_number`), an English
    grouping comma dropped first ("5,100" is read as 5100 here; the other reading comes from _SIMPLE)."""
    from aerophoto.i18n.numfmt import parse_number

    try:
        x = parse_number(token.replace(",", ""), lang="en")
    except ValueError:
        return None
    return x if math.isfinite(x) else None


_GROUP = re.compile(r"(?<=\d)[\u00a0\u2009\u202f](?=\d{3}(?!\d))")


def numbers_in(text: str) -> set[float]:
    """Every number printed in ``text``: with an ambiguous thousands separator (a plain space, a comma) read both
    ways ("5 100" → 5100, 5, 100); a narrow, thin or no-break space between digit groups is only a group separator
    (the book's :mod:`aerophoto.i18n.numfmt` writes "1:12\u202f300", never two numbers "12" and "300")."""
    out = set()
    for pattern, s in ((_NUMBER, text), (_SIMPLE, _GROUP.sub("", text))):
        for m in pattern.finditer(s):
            x = _to_float(m.group(0))
            if x is not None:
                out.add(x)
    return out


def html_text(s: str) -> str:
    """What an HTML output shows: its text, image alt texts; no tags, styles, scripts or embedded images."""
    alts = " ".join(m.group(2) for m in _ALT.finditer(s))
    s = _DATA_URI.sub(" ", s)
    return html.unescape(_TAGS.sub(" ", s)) + " " + html.unescape(alts)


def output_text(out: dict) -> str:
    """The text one output shows (stream, error message, text/plain, HTML, markdown, LaTeX)."""
    kind = out.get("output_type")
    if kind == "stream":
        return str(out.get("text", ""))
    if kind == "error":
        return f"{out.get('ename', '')}: {out.get('evalue', '')}"
    data = out.get("data", {})
    parts = []
    for mime in ("text/plain", "text/markdown", "text/latex"):
        if mime in data:
            parts.append(str(data[mime]) if not isinstance(data[mime], list) else "".join(data[mime]))
    if "text/html" in data:
        h = data["text/html"]
        parts.append(html_text("".join(h) if isinstance(h, list) else str(h)))
    return "\n".join(parts)


_WIDGET_TEXT_KEYS = ("value", "description", "tooltip", "placeholder", "_options_labels", "readout", "label")
_WIDGET_SKIP = re.compile(r"(Layout|Style)Model$")


def widget_numbers(nb) -> set[float]:
    """Numbers in the widget states the run left: values, descriptions, option labels, HTML tables."""
    state = (nb.metadata.get("widgets", {}).get("application/vnd.jupyter.widget-state+json", {})
             .get("state", {}))
    found: set[float] = set()
    for model in state.values():
        if _WIDGET_SKIP.search(str(model.get("model_name", ""))):
            continue
        st = model.get("state", {})
        for key in _WIDGET_TEXT_KEYS:
            if key not in st:
                continue
            val = st[key]
            vals = val if isinstance(val, list) else [val]
            for x in vals:
                if isinstance(x, bool) or x is None:
                    continue
                if isinstance(x, (int, float)):
                    if math.isfinite(x):
                        found.add(float(x))
                else:
                    found |= numbers_in(html_text(str(x)))
    return found


# --------------------------------------------------------------------------------------------------
# what must not be on screen


def _tolerance(answer, x: float) -> float:
    if answer.kind == "count" or answer.integer:
        return 0.0
    if answer.tol_abs is None and answer.tol_rel is None:
        return 0.005 * abs(x)
    return max(answer.tol_abs or 0.0, (answer.tol_rel or 0.0) * abs(x))


def _digits_needed(x: float, tol: float) -> int:
    """Significant digits of the shortest decimal within ``tol`` of ``x`` (how distinctive the number is)."""
    if x == 0:
        return 1
    for d in range(1, 16):
        if abs(float(f"{x:.{d}g}") - x) <= tol:
            return d
    return 16


def _numbers(value) -> list[float]:
    """The numbers of one answer (a number, or each entry of a sequence); booleans and text are not numbers."""
    if isinstance(value, bool) or value is None or isinstance(value, str):
        return []
    if hasattr(value, "tolist"):
        value = value.tolist()
    if isinstance(value, (list, tuple)):
        return [y for v in value for y in _numbers(v)]
    try:
        x = float(value)
    except (TypeError, ValueError):
        return []
    return [x] if math.isfinite(x) else []


_MAX_INPUT_NUMBERS = 100_000


def _given(obj, depth: int = 0) -> set[float]:
    """The numbers inside a task's inputs: a number, a table, an array, a dict, a dataclass, a sequence, text."""
    import dataclasses

    import numpy as np

    if obj is None or isinstance(obj, bool) or depth > 4:
        return set()
    if isinstance(obj, (int, float, np.integer, np.floating)):
        return set(_numbers(obj))
    if isinstance(obj, str):
        return numbers_in(obj)
    if hasattr(obj, "to_numpy"):  # pandas
        out = set()
        for col in (obj.to_frame() if hasattr(obj, "to_frame") else obj).to_numpy().ravel()[:_MAX_INPUT_NUMBERS]:
            out |= _given(col, depth + 1)
        return out
    if isinstance(obj, np.ndarray):
        flat = obj.ravel()[:_MAX_INPUT_NUMBERS]
        return {float(x) for x in flat if np.issubdtype(flat.dtype, np.number) and np.isfinite(x)}
    if isinstance(obj, dict):
        return set().union(set(), *(_given(x, depth + 1) for x in obj.values()))
    if dataclasses.is_dataclass(obj):
        return set().union(numbers_in(str(obj)[:20000]),
                           *(_given(getattr(obj, f.name), depth + 1) for f in dataclasses.fields(obj)))
    if isinstance(obj, (list, tuple)):
        return set().union(set(), *(_given(x, depth + 1) for x in obj[:_MAX_INPUT_NUMBERS]))
    # a lab object (a stereo pair, a sheet): its repr and the tables it hands the student as attributes (chapter 07's
    # measured tops and feet, `lab.points`); a withheld name raises and is not given
    # (tables only, by attribute — a lazy one too, chapter 07's `points` — never a method, and never one named as a
    # solution: truth, reference, answer, solution)
    out = numbers_in(str(obj)[:20000])
    for name in dir(obj):
        if name.startswith("_") or any(w in name for w in ("truth", "reference", "answer", "solution")):
            continue
        if callable(getattr(type(obj), name, None)):
            continue
        try:
            value = getattr(obj, name)  # a withheld name raises: not given
        except Exception:
            continue
        if hasattr(value, "to_numpy") and hasattr(value, "columns"):
            out |= _given(value, depth + 1)
        elif isinstance(value, (int, float, np.integer, np.floating)) and not isinstance(value, bool):
            out |= set(_numbers(value))  # a number it hands over (chapter 16's block: 10 photos per strip)
    return out


def _input_numbers(v, chapter_tasks) -> set[float]:
    """The numbers the student is given: the variant's inputs and every task's inputs."""
    given = {float(x) for x in v.as_dict().values() if isinstance(x, (int, float)) and not isinstance(x, bool)}
    given |= numbers_in(v.record_book)
    for t in chapter_tasks:
        given |= _given(t.inputs(v))
    return given


def graded_values(chapter_tasks, v) -> list[dict]:
    """Every graded number of variant ``v``: task, answer name, value, tolerance, distinctive or common, given."""
    given = _input_numbers(v, chapter_tasks)
    rows = []
    for t in chapter_tasks:
        answers = t.answers(v)
        for a in t.spec:
            if a.kind in ("bool", "choice"):
                continue
            for k, x in enumerate(_numbers(answers[a.name])):
                tol = _tolerance(a, x)
                digits = _digits_needed(x, tol)
                rows.append({"task": t.id, "name": a.name, "k": k, "x": x, "tol": tol, "digits": digits,
                             "distinctive": digits >= 4,
                             "given": any(abs(x - g) <= tol for g in given)})
    return rows


def find_leaks(values_a: list[dict], values_b: list[dict], seen_a: dict, seen_b: dict) -> list[str]:
    """The graded values of variant A on screen, by the rule of the module notes.

    ``seen_a``/``seen_b`` map a place (a cell id, ``"widgets"``, ``"figures"``) to the numbers shown there
    for variants A and B.  Returns one line per leak: the value, where, and the number shown.
    """
    b_by_key = {(r["task"], r["name"], r["k"]): r for r in values_b}
    leaks = []
    for r in values_a:
        if r["given"]:
            continue
        x, tol = r["x"], r["tol"]
        rb = b_by_key.get((r["task"], r["name"], r["k"]))
        if not r["distinctive"] and (rb is None or abs(rb["x"] - x) <= max(tol, rb["tol"])):
            continue  # B has the same value: nothing tells it from chance
        for place, nums in seen_a.items():
            hits = sorted(y for y in nums if abs(y - x) <= tol)
            if not r["distinctive"]:
                hits = [y for y in hits if y not in seen_b.get(place, set())]
            if hits:
                leaks.append(f"{r['task']} {r['name']} = {x:.6g} (±{tol:.3g}) shown in [{place}] as {hits[0]:g}")
    return leaks


# --------------------------------------------------------------------------------------------------
# running a chapter as the student receives it

_PREAMBLE = """\
%reset -f
import os, sys, json
os.environ["AEROPHOTO_RECORD_BOOK"] = {record_book!r}
os.chdir({cwd!r})
import matplotlib
import matplotlib.pyplot as _plt
_plt.close("all")
from aerophoto import checks as _checks
_checks.reset()
_mod = sys.modules.setdefault("_aero_screen", type(sys)("_aero_screen"))
if not hasattr(_mod, "texts"):
    import matplotlib.figure, matplotlib.text
    _mod.texts = []
    def _figure_texts(fig):
        ticks = set()
        for ax in fig.axes:
            for axis in (ax.xaxis, ax.yaxis):
                ticks.update(id(t) for t in axis.get_ticklabels(which="both"))
                ticks.add(id(axis.get_offset_text()))
        return [t.get_text() for t in fig.findobj(matplotlib.text.Text)
                if id(t) not in ticks and t.get_visible() and t.get_text()]
    _mod.figure_texts = _figure_texts
    # the hook looks itself up in sys.modules at every draw: `%reset -f` and the `del` below clear the
    # notebook's globals, so it must not refer to any of them
    def draw(self, renderer, _draw=matplotlib.figure.Figure.draw):
        _hook = sys.modules["_aero_screen"]
        _hook.texts.extend(_hook.figure_texts(self))
        return _draw(self, renderer)
    matplotlib.figure.Figure.draw = draw
_mod.texts.clear()
del _mod, _plt, _checks
"""

_POSTAMBLE = """\
import sys as _sys, json as _json, matplotlib.pyplot as _plt
_m = _sys.modules["_aero_screen"]
for _n in _plt.get_fignums():
    _m.texts.extend(_m.figure_texts(_plt.figure(_n)))
print("AERO-FIGURE-TEXTS " + _json.dumps(sorted(set(_m.texts)), ensure_ascii=False))
"""


def release_version(path: Path):
    """The chapter as nbgrader releases it to the student: answer cells at their templates."""
    from aerophoto import course

    nb = nbformat.read(str(path), as_version=4)
    return course.student_version(course.source_version(nb))


def run_as_student(km, path: Path, record_book: str):
    """Execute the release version of ``path`` for ``record_book`` in the shared kernel; returns the notebook."""
    from nbclient import NotebookClient

    nb = release_version(path)
    pre = nbformat.v4.new_code_cell(_PREAMBLE.format(record_book=record_book, cwd=str(path.parent)))
    post = nbformat.v4.new_code_cell(_POSTAMBLE)
    pre["id"], post["id"] = "aero-preamble", "aero-postamble"
    nb.cells = [pre, *nb.cells, post]
    client = NotebookClient(nb, km=km, timeout=600, allow_errors=True, store_widget_state=True,
                            resources={"metadata": {"path": str(path.parent)}})
    try:
        client.execute(cleanup_kc=False)
    finally:
        if client.kc is not None:
            client.kc.stop_channels()
    return nb


def seen_on_screen(nb) -> dict[str, set[float]]:
    """Place → numbers shown there: each code cell's outputs, the widgets, the figures' texts."""
    seen: dict[str, set[float]] = {}
    figure_texts: list[str] = []
    for cell in nb.cells:
        if cell.cell_type != "code":
            continue
        if cell.get("id") == "aero-postamble":
            for out in cell.get("outputs", []):
                text = out.get("text", "") if out.get("output_type") == "stream" else ""
                for line in text.splitlines():
                    if line.startswith("AERO-FIGURE-TEXTS "):
                        figure_texts = json.loads(line.split(" ", 1)[1])
            continue
        if cell.get("id") == "aero-preamble":
            continue
        nums = set()
        for out in cell.get("outputs", []):
            nums |= numbers_in(output_text(out))
        seen[str(cell.get("id"))] = nums
    seen["widgets"] = widget_numbers(nb)
    seen["figures"] = set().union(*(numbers_in(t) for t in figure_texts)) if figure_texts else set()
    return seen


# --------------------------------------------------------------------------------------------------
# the rule itself, on made-up screens (fast)


class _A:
    def __init__(self, name, kind="value", tol_abs=None, tol_rel=None, integer=False):
        self.name, self.kind, self.tol_abs, self.tol_rel, self.integer = name, kind, tol_abs, tol_rel, integer


class _T:
    def __init__(self, tid, spec, answers, inputs=None):
        self.id, self.spec, self._answers, self._inputs = tid, spec, answers, inputs

    def answers(self, v):
        return self._answers

    def inputs(self, v):
        return self._inputs


def test_numbers_are_read_as_printed():
    assert numbers_in("H = 11 859 m, on = −35.1 mm") >= {11859.0, -35.1}
    assert 11859.0 in numbers_in("<td>11,859</td>")
    assert 12000.0 in numbers_in("1:12\u202f000") and 1.2e4 in numbers_in("1.2e+04")
    assert 12.0 not in numbers_in("1/m = 1:12\u202f300") and {5.0, 100.0} <= numbers_in("5 100")
    assert numbers_in(html_text("<img src='data:image/png;base64,AAAA1234' alt='limit 7.5°'>")) == {7.5}
    assert numbers_in(html_text("<style>.x{width:340px}</style><b>60.07</b> %")) == {60.07}


def test_the_rule_finds_leaks_and_spares_inputs_and_chance():
    v = variant("19-0457")  # f = 670 mm, m = 17 700
    spec = (_A("H_m"), _A("K", kind="count"), _A("N", kind="count"), _A("crab_limit_deg", tol_abs=0.05),
            _A("f_again"), _A("x_mm", tol_abs=0.05))
    t_a = _T("task-99-1", spec, {"H_m": 11859.0, "K": 41, "N": 2706, "crab_limit_deg": 10.0, "f_again": 670.0,
                                 "x_mm": 163.27})
    t_b = _T("task-99-1", spec, {"H_m": 1599.0, "K": 22, "N": 782, "crab_limit_deg": 10.0, "f_again": 130.0,
                                 "x_mm": 12.5})
    va, vb = graded_values([t_a], v), graded_values([t_b], variant("19-0403"))
    by = {r["name"]: r for r in va}
    assert by["N"]["distinctive"] and by["x_mm"]["distinctive"]
    assert not by["H_m"]["distinctive"] and not by["K"]["distinctive"]
    assert by["f_again"]["given"] and not by["H_m"]["given"]
    # H in a demo's table (B's run shows its own H there), K in a figure title (B shows its own K), N in a
    # sentence both variants print, a photo coordinate in a table of every variant's values, the input f, the
    # crab limit both share in prose: four leaks
    seen_a = {"demo": {11860.0, 670.0}, "figures": {41.0, 2.0}, "text": {10.0, 3.0, 2706.0},
              "table": {163.3, 12.5}}
    seen_b = {"demo": {1599.0, 130.0}, "figures": {22.0, 2.0}, "text": {10.0, 3.0, 2706.0}, "table": {163.3, 12.5}}
    leaks = find_leaks(va, vb, seen_a, seen_b)
    assert {s.split(" = ")[0].split()[-1] + s[s.index("["):s.index("]") + 1] for s in leaks} == {
        "H_m[demo]", "K[figures]", "N[text]", "x_mm[table]"}, leaks
    # chance: the same 41 and the same rounded H in places both variants show (a step number, an example)
    assert find_leaks(va, vb, {"figures": {41.0}, "demo": {11900.0}}, {"figures": {41.0}, "demo": {11900.0}}) == []
    # off by more than the tolerance: not a leak
    assert find_leaks(va, vb, {"demo": {11980.0, 2705.0, 163.2}}, {"demo": set()}) == []


# --------------------------------------------------------------------------------------------------
# every chapter


@pytest.fixture(scope="module")
def kernel(tmp_path_factory):
    """One kernel for every chapter and variant of this module (a private AEROPHOTO_HOME, no MPLBACKEND)."""
    from jupyter_client.manager import KernelManager

    env = dict(os.environ)
    env.pop("MPLBACKEND", None)
    env["AEROPHOTO_HOME"] = str(tmp_path_factory.mktemp("home"))
    km = KernelManager(kernel_name="python3")
    km.start_kernel(env=env)
    try:
        yield km
    finally:
        km.shutdown_kernel(now=True)


def _chapter_ids():
    return [c.name for c in book.CHAPTERS]


@pytest.mark.slow
@pytest.mark.parametrize("name", _chapter_ids())
def test_no_graded_value_is_on_screen_before_it_is_answered(name, kernel):
    chapter = book.chapter(name)
    path = NOTEBOOKS / chapter.notebook
    assert path.is_file(), f"{chapter.notebook} is registered in aerophoto.book.CHAPTERS but missing"
    nb_src = nbformat.read(str(path), as_version=4)
    answer_cells = [c for c in nb_src.cells if c.get("metadata", {}).get("nbgrader", {}).get("solution")]
    try:
        chapter_tasks = tasks.chapter_tasks(chapter.number)
    except ValueError:
        chapter_tasks = ()
    if not chapter_tasks:
        assert not answer_cells, f"{chapter.notebook} has answer cells but no graded tasks in aerophoto.tasks"
        return
    va, vb = (variant(rb) for rb in RECORD_BOOKS)
    values_a, values_b = graded_values(chapter_tasks, va), graded_values(chapter_tasks, vb)
    assert any(not r["given"] for r in values_a), f"{name}: no graded number to look for"
    t0 = time.perf_counter()
    nb_a = run_as_student(kernel, path, RECORD_BOOKS[0])
    nb_b = run_as_student(kernel, path, RECORD_BOOKS[1])
    elapsed = time.perf_counter() - t0
    # the runs were the student's: every check cell says "no answer", none passed
    checks_out = [output_text(o) for c in nb_a.cells
                  if c.get("metadata", {}).get("nbgrader", {}).get("grade") for o in c.get("outputs", [])]
    assert checks_out and not any("passed" in t for t in checks_out), f"{name}: a check passed without an answer"
    # and they failed cleanly: a check cell fails with WrongAnswer ("no answer yet"); no other cell raises
    for run in (nb_a, nb_b):
        for c in run.cells:
            for o in c.get("outputs", []):
                if o.get("output_type") != "error":
                    continue
                is_check = bool(c.get("metadata", {}).get("nbgrader", {}).get("grade"))
                assert is_check and o.get("ename") == "WrongAnswer", (
                    f"{name}: cell {c.get('id')} raised {o.get('ename')}: {o.get('evalue')}"[:600])
    seen_a, seen_b = seen_on_screen(nb_a), seen_on_screen(nb_b)
    leaks = [f"variant {va.i:02d}: {s}" for s in find_leaks(values_a, values_b, seen_a, seen_b)]
    leaks += [f"variant {vb.i:02d}: {s}" for s in find_leaks(values_b, values_a, seen_b, seen_a)]
    print(f"{name}: two variants in {elapsed:.1f} s; {len(values_a) + len(values_b)} graded numbers searched")
    assert not leaks, f"{chapter.notebook}: graded values on screen before they are answered:\n" + "\n".join(leaks)
