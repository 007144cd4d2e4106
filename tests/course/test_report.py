"""The student's course report (issue 17, part 1): read without running, graded by the trusted check, typeset.

A synthetic student's workbook (``aerophoto-course workbook``) has chapter 00 answered with expressions,
chapter 01 with task 01.1 right, 01.2 right from 01.1's answers and 01.3 wrong, chapter 05 answered with
numbers (so the sheet is drawn), one answer that needs package code, and chapter 07 not started.
"""

from __future__ import annotations

import math
import shutil
import subprocess
from pathlib import Path

import pytest

from aerophoto import nbtools, tasks
from aerophoto.course.versions import write_workbook
from aerophoto.report.answers import UNREADABLE, evaluate_cells
from aerophoto.variants import variant

ROOT = Path(__file__).resolve().parents[2]
RB = "19-0457"
V = variant(RB)
DATE = "2026-11-26"

CH00 = ("import math\nH_m = v.f_mm / 1000 * v.m\non_mm = v.f_mm * math.tan(math.radians(v.alpha_deg))\n"
        "oc_mm = -v.f_mm * math.tan(math.radians(v.alpha_deg) / 2)\n")
H_STUDENT = V.f_mm / 1000 * V.m  # 11859 m for variant 57


def literal(x) -> str:
    """A reference value as the literal a student would type."""
    if hasattr(x, "tolist"):
        x = x.tolist()
    if isinstance(x, bool):
        return repr(x)
    if isinstance(x, int):
        return str(x)
    if isinstance(x, float):
        return repr(float(x))
    if isinstance(x, (list, tuple)):
        return "[" + ", ".join(literal(e) for e in x) + "]"
    return repr(x)


def answer_with(task_id: str, values: dict) -> str:
    return "\n".join(f"{k} = {val}" for k, val in values.items()) + "\n"


def fill_reference(nb, task_id: str, v=V) -> None:
    ref = tasks.answers(task_id, v)
    nbtools.set_cell(nb, f"{task_id}-answer", answer_with(task_id, {k: literal(x) for k, x in ref.items()}))


def set_record_book(nb, rb=RB) -> None:
    _, setup = nbtools.find_cell(nb, "setup")
    setup.source = setup.source.replace("RECORD_BOOK = None", f"RECORD_BOOK = {rb!r}")


def _edit(path: Path, fn) -> None:
    nb = nbtools.read(path)
    fn(nb)
    nbtools.write(nb, path)


def make_workbook(dest: Path, *, full: bool = False) -> Path:
    """The synthetic student's workbook; ``full``: every task of every chapter answered right (benchmark)."""
    write_workbook(dest, ROOT / "notebooks", out=lambda s: None)
    books = {p.name[:2]: p for p in dest.glob("[0-9][0-9]_*.ipynb") if ".updated-" not in p.name}
    if full:
        for number, path in books.items():
            def fill(nb, number=number):
                if number == "00":
                    set_record_book(nb)
                if number in tasks.CHAPTER_MODULES:
                    for t in tasks.chapter_tasks(number):
                        fill_reference(nb, t.id)
            _edit(path, fill)
        return dest

    def ch00(nb):
        set_record_book(nb)
        nbtools.set_cell(nb, "task-00-1-answer", CH00)

    def ch01(nb):
        nbtools.set_cell(nb, "task-01-1-answer", (
            "H_m = v.f_mm / 1000 * v.m\nh = v.Zmax_m - v.Zmin_m\nPx_percent = v.px_percent + 40 * h / H_m\n"
            "bx_cm = v.frame_mm / 10 * (100 - Px_percent) / 100\nby_cm = v.frame_mm / 10 * (100 - "
            "v.py_percent) / 100\nBx_km = bx_cm / 100 * v.m / 1000\nBy_km = by_cm / 100 * v.m / 1000\n"))
        nbtools.set_cell(nb, "task-01-2-answer",
                         "K = math.ceil(v.Ly_km / By_km + 1)\nn = math.ceil(v.Lx_km / Bx_km + 1)\nN = n * K\n")
        ref = tasks.answers("task-01-3", V)
        vals = {k: literal(x) for k, x in ref.items()}
        vals["TS_h"] = literal(ref["TS_h"] * 60.0)  # minutes, not hours: the one wrong answer
        nbtools.set_cell(nb, "task-01-3-answer", answer_with("task-01-3", vals))

    def ch02(nb):  # an answer that needs package code: not readable without running
        nbtools.set_cell(nb, "task-02-1-answer",
                         "from aerophoto import flight\nPx_percent = flight.plan(v).Px_percent\n"
                         "dm_percent = 1.5\nn_percent = 2.0\n")

    def ch05(nb):
        fill_reference(nb, "task-05-1")
        fill_reference(nb, "task-05-2")

    def ch06(nb):  # the error triangles
        fill_reference(nb, "task-06-1")

    _edit(books["00"], ch00)
    _edit(books["01"], ch01)
    _edit(books["02"], ch02)
    _edit(books["05"], ch05)
    _edit(books["06"], ch06)
    return dest  # chapter 07 (and the rest) not started


# =========================================================================== the evaluator (fast)
def test_evaluator_reads_numbers_math_variant_and_earlier_answers():
    env = evaluate_cells(["import math\nH_m = v.f_mm / 1000 * v.m\nx = [1, 2.5] + [3]\n",
                          "k = math.ceil(H_m / 1000)\nok = H_m > 1000 and not False\ns = sum(x) ** 2\n"
                          "y = [e * 2 for e in x if e > 1]\nz = np.sqrt(16.0)\nw = ...\n"], V)
    assert env["H_m"] == pytest.approx(H_STUDENT)
    assert env["k"] == math.ceil(H_STUDENT / 1000)
    assert env["ok"] is True and env["s"] == 42.25 and env["y"] == [5.0, 6] and env["z"] == 4.0
    assert env["w"] is Ellipsis


def test_each_task_sees_its_own_cell_even_when_a_later_cell_reuses_a_name(tmp_path):
    from aerophoto.report.answers import read_notebook

    nb = nbtools.notebook([nbtools.code('RECORD_BOOK = "19-0457"', id="setup"),
                           nbtools.code("mD_m = 1.0", id="task-17-1-answer"),
                           nbtools.code("x = open('f')", id="task-17-1-data"),
                           nbtools.code("mD_m = 2.0 * mD_m", id="task-17-3-answer")])
    path = nbtools.write(nb, tmp_path / "17_x.ipynb")
    ans = read_notebook(path, ["task-17-1", "task-17-3"])
    assert ans.record_book == RB
    vals = ans.values(V)
    assert vals["task-17-1"]["mD_m"] == 1.0 and vals["task-17-3"]["mD_m"] == 2.0
    assert "x" not in vals["task-17-3"]  # a non-answer cell is never read


@pytest.mark.parametrize("src", [
    "x = flight.plan(v).H_m", "x = __import__('os').system('true')", "x = v.camera", "x = open('/etc/passwd')",
    "x = (1).__class__", "x = [0] * 10**9", "x = 9 ** 9 ** 9", "x = 'a' * 100", "x = eval('1')",
    "for i in range(3):\n    x = i", "x = math.factorial(100000)", "x = lambda: 1",
    "x = 2 ** 4000\n" + "x = x * x\n" * 40, "x = [1]\n" + "x = x + x\n" * 40, "x = math.exp(1e6)",
])
def test_evaluator_never_runs_anything_else(src):
    env = evaluate_cells([src], V)
    assert isinstance(env["x"], UNREADABLE), env["x"]


def test_evaluator_survives_syntax_errors_and_deep_nesting():
    env = evaluate_cells(["x = (", "y = " + "-" * 5000 + "1", "z = " + "(" * 200 + "1" + ")" * 200], V)
    assert isinstance(env["x"], UNREADABLE)
    assert isinstance(env["y"], UNREADABLE) or env["y"] == 1
    assert env["z"] == 1 or isinstance(env["z"], UNREADABLE)


def test_bad_input_names_the_parameter(tmp_path):
    from aerophoto import report

    with pytest.raises(ValueError, match="workbook_dir"):
        report.build(tmp_path / "nowhere")
    with pytest.raises(ValueError, match="date"):
        report.build(tmp_path, date="26.11.2026")
    with pytest.raises(ValueError, match="record_book"):
        report.build(tmp_path)  # no notebook names a record book
    with pytest.raises(ValueError, match="formats"):
        report.build(tmp_path, formats=("docx",))
    wb = tmp_path / "wb"
    wb.mkdir()
    shutil.copy(ROOT / "notebooks" / "00_start_here.ipynb", wb)
    _edit(wb / "00_start_here.ipynb", set_record_book)
    (tmp_path / "out" / "report_files").mkdir(parents=True)  # not the report's own: never deleted
    (tmp_path / "out" / "report_files" / "keep.txt").write_text("mine")
    with pytest.raises(ValueError, match="out_dir"):
        report.build(wb, tmp_path / "out", date=DATE, formats=("html",), sheet=False)
    assert (tmp_path / "out" / "report_files" / "keep.txt").read_text() == "mine"


# =========================================================================== the report (slow: renders photos)
@pytest.fixture(scope="module")
def built(tmp_path_factory):
    from aerophoto import report

    top = tmp_path_factory.mktemp("report")
    wb = make_workbook(top / "workbook")
    r = report.build(wb, top / "out", student="Иванова Анна", group="ЗиК 31", checked_by="Пресняков В. В.",
                     date=DATE)
    text = subprocess.run(["pdftotext", "-layout", str(r.pdf), "-"], capture_output=True, text=True,
                          check=True).stdout
    return r, text, top


@pytest.mark.slow
def test_report_reads_the_students_work(built):
    r, _, _ = built
    assert r.record_book == RB and r.variant.i == 57
    assert r.task("task-00-1").state == "passed"
    assert r.task("task-01-1").state == "passed"
    assert r.task("task-01-2").state == "passed"  # computed from the student's own 01.1 answers
    assert r.task("task-01-3").state == "failed"
    assert r.task("task-02-1").state == "unreadable"
    assert "flight" in r.task("task-02-1").unreadable["Px_percent"]
    assert r.task("task-05-2").state == "passed"
    assert r.task("task-06-1").state == "passed"
    assert {p.name for p in (r.build_dir / "figures").glob("*.png")} >= {
        "ch05_prints.png", "ch05_fotoschema.png", "ch06_site.png", "ch06_strip.png", "fotoschema.png"}
    assert all(not t.attempted for t in next(c for c in r.chapters if c.number == "07").tasks)


@pytest.mark.slow
def test_pdf_text_has_the_students_values_cyrillic_and_not_done(built):
    r, text, _ = built
    flat = " ".join(text.split())
    assert "КУРСОВАЯ РАБОТА" in flat and "Иванова Анна" in flat and RB in flat
    assert "Пояснительная записка" in flat
    assert "Расчет параметров аэрофотосъёмки" in flat
    assert "Линзово-зеркальный стереоскоп" in flat
    assert f"{H_STUDENT:.6g}" in flat                         # 11859, the student's H
    wrong = tasks.answers("task-01-3", V)["TS_h"] * 60.0
    assert f"{wrong:.6g}" in flat                             # their wrong value is theirs to see
    assert "не выполнено" in flat
    assert "не читается без запуска" in flat
    ch07 = flat[flat.rindex("Линзово-зеркальный стереоскоп. Изучение"):]  # the body, not the contents
    ch07 = ch07[:ch07.index("Дешифрирование аэроснимков")]
    assert "не выполнено" in ch07
    assert "Рисунок 4" in flat and "Таблица 12" in flat  # numbered figures and tables


@pytest.mark.slow
def test_no_reference_value_of_a_task_not_done(built):
    r, text, _ = built
    flat = " ".join(text.split())
    html = r.html.read_text(encoding="utf-8")
    for tid in ("task-07-1", "task-07-2", "task-03-2", "task-01-3"):
        ref = tasks.answers(tid, V)
        for name, x in ref.items():
            if tid == "task-01-3" and name != "TS_h":
                continue  # the student answered these right: their values may equal the reference
            xs = x if isinstance(x, (list, tuple)) else [x]
            for e in xs:
                if isinstance(e, bool) or not isinstance(e, (int, float)) or abs(e) < 10 or float(e).is_integer():
                    continue
                for form in (f"{e:.6g}", f"{e:.2f}"):
                    assert form not in flat, (tid, name, form)
                    assert form not in html, (tid, name, form)


@pytest.mark.slow
def test_first_page_renders(built):
    r, _, top = built
    subprocess.run(["pdftoppm", "-r", "40", "-png", "-f", "1", "-l", "1", str(r.pdf), str(top / "page")], check=True,
                   capture_output=True)
    pngs = list(top.glob("page*.png"))
    assert pngs and pngs[0].stat().st_size > 2000


@pytest.mark.slow
def test_sheet_is_on_the_a_size_it_claims(built):
    from aerophoto.demos.fotoschema import PAPER_MM

    r, text, _ = built
    assert r.sheet_pdf and r.sheet_pdf.is_file()
    info = subprocess.run(["pdfinfo", str(r.sheet_pdf)], capture_output=True, text=True, check=True).stdout
    size = next(line for line in info.splitlines() if line.startswith("Page size"))
    w_pt, h_pt = (float(x) for x in size.split(":")[1].split("pts")[0].split("x"))
    w_mm, h_mm = PAPER_MM[r.sheet_paper]
    assert w_pt * 25.4 / 72 == pytest.approx(w_mm, abs=1.0) and h_pt * 25.4 / 72 == pytest.approx(h_mm, abs=1.0)
    sheet_text = " ".join(subprocess.run(["pdftotext", str(r.sheet_pdf), "-"], capture_output=True, text=True,
                                         check=True).stdout.split())
    m_student = tasks.answers("task-05-2", V)["m_mean"]  # the student typed the right value
    m_txt = f"{int(round(m_student / 100) * 100):,}".replace(",", " ")
    assert "ФОТОСХЕМА" in sheet_text and m_txt in sheet_text and "Иванова Анна" in sheet_text
    assert "Пресняков" in sheet_text and "2026" in sheet_text
    assert r.sheet_paper in " ".join(text.split())


@pytest.mark.slow
def test_same_files_for_the_same_workbook_and_date(built, tmp_path):
    from aerophoto import report

    r, _, top = built
    r2 = report.build(top / "workbook", tmp_path / "again", student="Иванова Анна", group="ЗиК 31",
                      checked_by="Пресняков В. В.", date=DATE)
    assert r2.pdf.read_bytes() == r.pdf.read_bytes()
    assert r2.sheet_pdf.read_bytes() == r.sheet_pdf.read_bytes()


@pytest.mark.slow
def test_cli_report_without_a_course(built, tmp_path):
    from aerophoto.course.cli import main

    _, _, top = built
    wb = tmp_path / "wb"
    shutil.copytree(top / "workbook", wb)
    lines = []
    import contextlib
    import io

    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        rc = main(["report", str(wb), "--out", str(tmp_path / "o"), "--student", "Иванова Анна", "--date", DATE,
                   "--no-sheet", "--html-only"])
    lines = buf.getvalue()
    assert rc == 0, lines
    assert (tmp_path / "o" / "report.html").is_file() and "19-0457" in lines
    with contextlib.redirect_stdout(io.StringIO()) as bad:
        assert main(["report", str(wb), "--date", "tomorrow"]) == 2
    assert "date" in bad.getvalue()


def test_empty_chapter_section_is_marked_not_done(tmp_path):
    """A chapter with no notebook in the workbook, and the 13 sections in §15's order."""
    from aerophoto.report.sections import SECTIONS

    assert [s.guide for s in SECTIONS] == list(range(2, 15)) and len(SECTIONS) == 13
    wb = tmp_path / "wb"
    wb.mkdir()
    src = ROOT / "notebooks" / "00_start_here.ipynb"
    shutil.copy(src, wb / src.name)
    _edit(wb / src.name, set_record_book)
    from aerophoto import report

    r = report.build(wb, tmp_path / "o", date=DATE, formats=("html",), sheet=False, figures=False)
    html = r.html.read_text(encoding="utf-8")
    assert "нет файла в рабочей тетради" in html and "не выполнено" in html
    assert html.index("Расчет параметров") < html.index("Фототриангуляция") < html.index("почвенном картографировании")
