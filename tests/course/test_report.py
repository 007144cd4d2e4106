"""The student's explanatory note (issue 29): a finished course report in Russian, read without running the workbook.

Two synthetic students (record books 19-0457 and 19-0403, variants 57 and 03) answer every chapter with the
values the package computes, except one wrong answer and one chapter left undone each; one answer of each is
computed with package code and read from the value its check cell recorded in the saved notebook (in an output's
``data`` for one, its ``metadata`` for the other).  Each note is built once per module, with a cache of its own.
The PDF is read back with poppler (pdftotext, pdfimages, pdfinfo, pdftoppm): §15's headings in order, the
student's numbers in Russian typography, no Python names, no scientific notation, the figures counted and vector,
the fotoschema sheet at true size and in Russian.  Page images of the title page, a section and the sheet are
rendered here and kept in ``artifacts/report/`` when a test fails.
"""

from __future__ import annotations

import math
import re
import shutil
import subprocess
from pathlib import Path

import pytest

from aerophoto import diskcache, nbtools, tasks
from aerophoto.course.versions import write_workbook
from aerophoto.course.wire import ANSWERS_MIME, encode_answers
from aerophoto.report.answers import UNREADABLE, evaluate_cells
from aerophoto.variants import variant

ROOT = Path(__file__).resolve().parents[2]
ARTIFACTS = ROOT / "artifacts" / "report"
DATE = "2026-11-26"
NARROW = "\u202f"

#: the two students: record book → (the wrong answer: task, name, what they typed), the chapter left undone,
#: the task answered with package code (read from its check cell's record) and where the record sits
STUDENTS = {
    "19-0457": {"name": "Иванова Анна", "wrong": ("task-01-3", "TS_h", lambda x: x * 60.0), "undone": "07",
                "recorded": ("task-02-1", "data")},
    "19-0403": {"name": "Петров Пётр", "wrong": ("task-05-1", "m_rms_mm", lambda x: x * 3.0), "undone": "13",
                "recorded": ("task-12-1", "metadata")},
}

SECTION_HEADINGS = (
    "Расчет параметров аэрофотосъёмки", "Оценка качества материалов аэрофотосъёмки",
    "Определение смещений точек и поправок за рельеф",
    "Определение смещений точек и поправок за угол наклона аэроснимка", "Изготовление одномаршрутной фотосхемы",
    "Построение одномаршрутного фототриангуляционного ряда",
    "Линзово-зеркальный стереоскоп. Изучение стереомодели местности", "Дешифрирование аэроснимков",
    "Корректировка плана части землепользования методом построения взаимно-проектных сеток",
    "Составление проекта планово-высотной привязки", "Фототрансформирование снимков равнинной местности",
    "Фототриангуляция", "Применение аэро- и космических снимков при почвенном картографировании")


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


def save(nb, path: Path) -> Path:
    """Write a notebook as it was saved, outputs kept (nbtools.write strips them, as the book stores its own)."""
    import json

    path = Path(path)
    path.write_text(json.dumps(nb, indent=1, ensure_ascii=False), encoding="utf-8")
    return path


def _edit(path: Path, fn) -> None:
    nb = nbtools.read(path)
    fn(nb)
    save(nb, path)


def make_workbook(dest: Path, rb: str) -> Path:
    """A full workbook for ``rb`` with STUDENTS[rb]'s wrong answer, undone chapter and recorded answer."""
    plan = STUDENTS[rb]
    v = variant(rb)
    write_workbook(dest, ROOT / "notebooks", out=lambda s: None)
    books = {p.name[:2]: p for p in dest.glob("[0-9][0-9]_*.ipynb") if ".updated-" not in p.name}
    for number, path in books.items():
        def fill(nb, number=number):
            if number == "00":
                _, setup = nbtools.find_cell(nb, "setup")
                setup.source = setup.source.replace("RECORD_BOOK = None", f"RECORD_BOOK = {rb!r}")
            if number not in tasks.CHAPTER_MODULES or number == plan["undone"]:
                return
            for t in tasks.chapter_tasks(number):
                ref = dict(tasks.answers(t.id, v))
                if t.id == plan["wrong"][0]:
                    ref[plan["wrong"][1]] = plan["wrong"][2](ref[plan["wrong"][1]])
                if t.id == plan["recorded"][0]:  # computed with package code; the saved output holds the record
                    src = "from aerophoto import tasks as _t\n" + "\n".join(
                        f"{k} = _t.answers({t.id!r}, v)[{k!r}]" for k in ref)
                    nbtools.set_cell(nb, f"{t.id}-answer", src)
                    _, check = nbtools.find_cell(nb, f"{t.id}-check")
                    rec = encode_answers(t.id, ref, v)
                    out = ({"output_type": "display_data", "data": {ANSWERS_MIME: rec}, "metadata": {}}
                           if plan["recorded"][1] == "data" else
                           {"output_type": "display_data", "data": {"text/plain": "✓"},
                            "metadata": {ANSWERS_MIME: rec}})
                    check["outputs"] = [out]
                    check["execution_count"] = 1
                    continue
                nbtools.set_cell(nb, f"{t.id}-answer", "\n".join(f"{k} = {literal(x)}" for k, x in ref.items()))
        _edit(path, fill)
    return dest


def pdf_text(path: Path, *args) -> str:
    return subprocess.run(["pdftotext", *args, str(path), "-"], capture_output=True, text=True, check=True).stdout


def flat(text: str) -> str:
    """One line, the mathematical italic letters of formulas read as plain letters (𝐻 → H), spaces kept as they are."""
    import unicodedata

    text = "".join(unicodedata.normalize("NFKC", c) if 0x1D400 <= ord(c) <= 0x1D7FF else c for c in text)
    text = re.sub(r"\u00ad\s*", "", text)  # a word hyphenated at a line's end
    return re.sub(r"[ \t\n\r\f\u2009]+", " ", text)


def keep_on_failure(pages: dict, name: str) -> None:
    """Copy the rendered page images to artifacts/report/ (called when an assertion about them fails)."""
    ARTIFACTS.mkdir(parents=True, exist_ok=True)
    for label, p in pages.items():
        shutil.copy(p, ARTIFACTS / f"{name}_{label}.png")


@pytest.fixture(scope="module")
def notes(tmp_path_factory):
    """Both students' notes, built once: {rb: (Report, pdf text, html text, folder)} (the second without figures
    and sheet, whose tests the first covers: it keeps the module's time down)."""
    from aerophoto import report

    out = {}
    for rb, plan in STUDENTS.items():
        top = tmp_path_factory.mktemp(f"report-{rb}")
        wb = make_workbook(top / "workbook", rb)
        full = rb == "19-0457"  # the second student's note without figures and sheet: the text's tests only
        r = report.build(wb, top / "out", student=plan["name"], group="ЗиК 31", checked_by="Пресняков В. В.",
                         date=DATE, cache=top / "cache", figures=full, sheet=full)
        out[rb] = (r, pdf_text(r.pdf), r.html.read_text(encoding="utf-8"), top)
    return out


# =========================================================================== the evaluator and the records (fast)
def test_evaluator_reads_numbers_math_variant_and_earlier_answers():
    V = variant("19-0457")
    env = evaluate_cells(["import math\nH_m = v.f_mm / 1000 * v.m\nx = [1, 2.5] + [3]\n",
                          "k = math.ceil(H_m / 1000)\nok = H_m > 1000 and not False\ns = sum(x) ** 2\n"
                          "y = [e * 2 for e in x if e > 1]\nz = np.sqrt(16.0)\nw = ...\n"], V)
    assert env["H_m"] == pytest.approx(11859.0)
    assert env["k"] == 12 and env["ok"] is True and env["s"] == 42.25 and env["y"] == [5.0, 6] and env["z"] == 4.0
    assert env["w"] is Ellipsis


@pytest.mark.parametrize("src", [
    "x = flight.plan(v).H_m", "x = __import__('os').system('true')", "x = v.camera", "x = open('/etc/passwd')",
    "x = (1).__class__", "x = [0] * 10**9", "x = 9 ** 9 ** 9", "x = 'a' * 100", "x = eval('1')",
    "for i in range(3):\n    x = i", "x = math.factorial(100000)", "x = lambda: 1",
    "x = 2 ** 4000\n" + "x = x * x\n" * 40, "x = [1]\n" + "x = x + x\n" * 40, "x = math.exp(1e6)",
])
def test_evaluator_never_runs_anything_else(src):
    env = evaluate_cells([src], variant("19-0457"))
    assert isinstance(env["x"], UNREADABLE), env["x"]


def test_check_records_fill_only_what_the_evaluator_cannot_read(tmp_path):
    from aerophoto.report.answers import RECORDED, read_notebook

    V = variant("19-0457")
    rec = encode_answers("task-17-1", {"mD_m": 1.5, "VX_m": 0.25}, V)
    other = encode_answers("task-17-1", {"mD_m": 9.9}, variant("19-0403"))
    hostile = {"task": "task-17-1", "variant": 57, "values": {"VY_m": {"__class__": "x"}, "md_mm": "$#eval()$" * 99}}
    check = nbtools.code("checks.check_task(...)", id="task-17-1-check")
    check["metadata"]["nbgrader"] = {"grade": True, "grade_id": "task-17-1-check", "points": 3, "solution": False}
    check["outputs"] = [{"output_type": "display_data", "data": {ANSWERS_MIME: hostile}, "metadata": {}},
                        {"output_type": "display_data", "data": {}, "metadata": {ANSWERS_MIME: rec}}]
    nb = nbtools.notebook([nbtools.code('RECORD_BOOK = "19-0457"', id="setup"),
                           nbtools.code("VX_m = 0.5\nmD_m = flight.x(v)\nVY_m = flight.y(v)", id="task-17-1-answer"),
                           check])
    ans = read_notebook(save(nb, tmp_path / "17_x.ipynb"), ["task-17-1"])
    env = ans.values(V)["task-17-1"]
    assert env["VX_m"] == 0.5                     # typed: the typed value, never the record's
    assert env["mD_m"] == 1.5                     # package code: the check cell's record
    assert isinstance(env["VY_m"], UNREADABLE)    # not in the last record, and no plain value anywhere
    assert env[RECORDED] == ("mD_m",)
    check["outputs"] = [{"output_type": "display_data", "data": {ANSWERS_MIME: other}, "metadata": {}}]
    ans = read_notebook(save(nb, tmp_path / "17_y.ipynb"), ["task-17-1"])
    assert isinstance(ans.values(V)["task-17-1"]["mD_m"], UNREADABLE)  # another variant's record is not used


def test_bad_input_names_the_parameter(tmp_path):
    from aerophoto import report

    with pytest.raises(ValueError, match="workbook_dir"):
        report.build(tmp_path / "nowhere")
    with pytest.raises(ValueError, match="date"):
        report.build(tmp_path, date="26.11.2026")
    with pytest.raises(ValueError, match="record_book"):
        report.build(tmp_path, cache=False)
    with pytest.raises(ValueError, match="formats"):
        report.build(tmp_path, formats=("docx",))
    with pytest.raises(ValueError, match="lang"):
        report.build(tmp_path, lang="de")
    wb = tmp_path / "wb"
    wb.mkdir()
    shutil.copy(ROOT / "notebooks" / "00_start_here.ipynb", wb)
    _edit(wb / "00_start_here.ipynb", lambda nb: nbtools.find_cell(nb, "setup")[1].__setitem__(
        "source", nbtools.find_cell(nb, "setup")[1].source.replace("RECORD_BOOK = None", "RECORD_BOOK = '19-0457'")))
    (tmp_path / "out" / "report_files").mkdir(parents=True)  # not the report's own: never deleted
    (tmp_path / "out" / "report_files" / "keep.txt").write_text("mine")
    with pytest.raises(ValueError, match="out_dir"):
        report.build(wb, tmp_path / "out", date=DATE, formats=("html",), sheet=False, cache=False)
    assert (tmp_path / "out" / "report_files" / "keep.txt").read_text() == "mine"


# =========================================================================== the cache
def test_cache_is_off_by_default_and_verified_before_use(tmp_path, monkeypatch):
    monkeypatch.delenv("AEROPHOTO_CACHE", raising=False)
    monkeypatch.delenv("AEROPHOTO_GRADING", raising=False)
    assert diskcache.active() is None
    with diskcache.enabled(tmp_path / "c") as c:
        assert diskcache.active() is c
        assert c.json("t", {"a": 1}, lambda: {"x": [1, 2]}) == {"x": [1, 2]}
        assert c.json("t", {"a": 1}, lambda: pytest.fail("rebuilt")) == {"x": [1, 2]}
        assert (tmp_path / "c" / "key").stat().st_mode & 0o777 == 0o600
        data = next((tmp_path / "c").rglob("*.data"))
        data.write_bytes(b'{"x": [6, 6, 6]}')  # planted: the signature no longer holds
        assert c.json("t", {"a": 1}, lambda: {"x": [1, 2]}) == {"x": [1, 2]}
        assert c.stats["rejected"] == 1
        arr = c.arrays("t", {"b": 2}, lambda: {"z": __import__("numpy").arange(3)})
        assert arr["z"].tolist() == [0, 1, 2]
    assert diskcache.active() is None
    with diskcache.enabled(tmp_path / "other") as c2:  # another key: nothing of the first folder's entries
        assert c2.get_bytes("t", {"a": 1}) is None
    monkeypatch.setenv("AEROPHOTO_GRADING", "1")  # never in a grading kernel
    with diskcache.enabled(tmp_path / "c") as c3:
        assert c3 is None and diskcache.active() is None


def test_the_instructors_grading_never_opens_the_cache():
    import ast

    for path in (ROOT / "src" / "aerophoto" / "course").rglob("*.py"):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            names = [a.name for a in node.names] if isinstance(node, (ast.Import, ast.ImportFrom)) else []
            mod = getattr(node, "module", "") or ""
            assert "diskcache" not in mod and "diskcache" not in names, path


# =========================================================================== the notes (slow: two full workbooks)
@pytest.mark.slow
def test_the_students_work_is_read_and_checked(notes):
    for rb, plan in STUDENTS.items():
        r = notes[rb][0]
        states = {t.task: t.state for ch in r.chapters for t in ch.tasks}
        assert states[plan["wrong"][0]] == "failed", rb
        assert all(s == "not_started" for t, s in states.items() if t.split("-")[1] == plan["undone"]), rb
        assert states[plan["recorded"][0]] == "passed", rb   # read from the check cell's record
        assert r.task(plan["recorded"][0]).recorded
        others = {t: s for t, s in states.items() if t != plan["wrong"][0] and t.split("-")[1] != plan["undone"]}
        assert set(others.values()) == {"passed"}, {t: s for t, s in others.items() if s != "passed"}


@pytest.mark.slow
def test_the_note_is_in_the_guides_order(notes):
    for rb, (r, text, _, _) in notes.items():
        body = flat(text)
        body = body[body.index("ВВЕДЕНИЕ", body.index("ВВЕДЕНИЕ") + 1):]  # after the contents
        pos = [body.index("ВВЕДЕНИЕ")]
        for k, h in enumerate(SECTION_HEADINGS, start=1):
            pos.append(body.index(f"{k} {h}", pos[-1]))
        for h in ("ЗАКЛЮЧЕНИЕ", "СПИСОК ИСПОЛЬЗОВАННЫХ ИСТОЧНИКОВ", "ПРИЛОЖЕНИЕ А. ФОТОСХЕМА"):
            pos.append(body.index(h, pos[-1]))
        assert pos == sorted(pos)
        for article in ("14 Точность фототриангуляционных сетей", "15 Аэрофотопривязка",
                        "16 Рисовка горизонталей", "17 Анализ плановой точности"):
            assert article in body
        for source in ("Пресняков, В. В. Фотограмметрия. Руководство по курсовому проектированию",
                       "Дорожинский, А. Л.", "Михеева, А. А.", "Опыт рисовки горизонталей", "ГКИНП",
                       "СТП ПГУАС 1.2.1.003-2005", "typst"):
            assert source in body, source
        title = flat(text.split("\f")[0])
        for part in ("МИНИСТЕРСТВО НАУКИ И ВЫСШЕГО ОБРАЗОВАНИЯ", "Пензенский государственный университет",
                     "Кафедра «Землеустройство и геодезия»", "КУРСОВАЯ РАБОТА", "по дисциплине «Фотограмметрия»",
                     "на тему", "ПОЯСНИТЕЛЬНАЯ ЗАПИСКА", f"№ {rb}, вариант {variant(rb).i:02d}", "гр. ЗиК 31",
                     STUDENTS[rb]["name"], "Руководитель: Пресняков В. В.", "Пенза 2026"):
            assert part in title, part


@pytest.mark.slow
def test_the_students_numbers_are_in_russian_typography(notes):
    r, text, html, _ = notes["19-0457"]
    # the book's formatter wrote a narrow no-break space into the note (the PDF's text layer reads it as a space)
    source = (r.build_dir / "report.json").read_text(encoding="utf-8")
    assert f"17{NARROW}700" in source and f"11{NARROW}859" in source and "17700" not in source
    body = flat(text).replace(NARROW, " ")
    assert "H = f ⋅ m = 0,670 ⋅ 17 700 = 11 859 м" in body
    assert "N = n ⋅ K = 66 ⋅ 41 = 2706" in body                     # four digits stay whole
    assert "= 1,271 км" in body
    for value in ("1,271", "2,227", "3844", "0,0047", "53,2", "1,36", "17 703", "0,9601"):
        assert value in body, value
        assert value.replace(",", ".") not in body or "," not in value, value
    assert "М 1:17 700" in flat(pdf_text(r.sheet_pdf, "-raw")).replace(NARROW, " ")
    wrong = tasks.answers("task-01-3", variant("19-0457"))["TS_h"] * 60.0
    assert f"{wrong:.2f}".replace(".", ",") in body                  # their own wrong value, theirs to see
    assert "не подтверждает результат задачи 01.3" in body
    r3, text3, _, _ = notes["19-0403"]
    assert "H = f ⋅ m = 0,130 ⋅ 12 300 = 1599 м" in flat(text3).replace(NARROW, " ")
    for t in (text, text3, html):
        assert not re.search(r"\d[eE][+-]\d", t)                     # no scientific notation anywhere
    # 17.1's coordinates in full, grouped: nothing of the data is lost
    X = tasks.inputs("task-17-1", variant("19-0457"))["X_m"].iloc[0]
    whole, frac = f"{X:.2f}".split(".")
    assert f"{whole[:1]} {whole[1:4]} {whole[4:]},{frac}" in body
    assert f"{whole[:1]}{NARROW}{whole[1:4]}{NARROW}{whole[4:]},{frac}" in source
    assert "−" in body                                               # a true minus


@pytest.mark.slow
def test_no_python_names_and_no_english_glosses(notes):
    names = {a.name for n in tasks.CHAPTER_MODULES for t in tasks.chapter_tasks(n) for a in t.spec}
    names = {n for n in names if "_" in n}
    for rb, (r, text, html, _) in notes.items():
        body = flat(text)
        for n in names:
            assert not re.search(rf"\b{re.escape(n)}\b", body), (rb, n)
        assert "(not done)" not in body and "passed the check" not in body and "your value" not in body
        assert r.leftover == ()                                      # every figure text in Russian


def where_a_task_writes(body: str, chapter: str) -> str:
    """The parts of a note where a task's values would show: its chapter's section (from its heading in the text,
    not in the contents, to the next section's) and everything from the conclusion on (the key numbers, the
    appendices).  Another section's given tables may hold the same digits by chance (chapter 04's plan length
    41,8 mm beside 07.2's dh_C = 41,78 m for variant 57)."""
    k = int(chapter) - 1
    start = body.rfind(f"{chapter.lstrip('0')} {SECTION_HEADINGS[k][:20]}")
    assert start >= 0, chapter
    nxt = body.rfind(f"{k + 2} {SECTION_HEADINGS[k + 1][:20]}") if k + 1 < len(SECTION_HEADINGS) else -1
    end = max(body.rfind("ЗАКЛЮЧЕНИЕ"), body.rfind("Заключение"))  # the PDF's heading, the HTML's (CSS upper case)
    assert end > start, chapter
    return body[start:nxt if nxt > start else end] + " " + body[end:]


@pytest.mark.slow
def test_no_reference_value_of_a_task_not_done(notes):
    for rb, plan in STUDENTS.items():
        r, text, html, _ = notes[rb]
        body = flat(text)
        v = variant(rb)
        section = plan["undone"]
        scanned = [where_a_task_writes(body, section),
                   where_a_task_writes(flat(re.sub(r"<[^>]+>", " ", html)), section)]
        for t in tasks.chapter_tasks(section):
            assert f"Задача {t.id.split('-')[1]}.{t.id.split('-')[2]} не выполнена" in body
            for name, x in tasks.answers(t.id, v).items():
                for e in (x if isinstance(x, (list, tuple)) else [x]):
                    if isinstance(e, bool) or not isinstance(e, (int, float)) or abs(e) < 10 or float(e).is_integer():
                        continue
                    for form in (f"{e:.1f}", f"{e:.2f}"):
                        number = re.compile(r"(?<![\d,])" + re.escape(form.replace(".", ",")) + r"(?![\d])")
                        assert not any(number.search(part) for part in scanned), (rb, t.id, name, form)


@pytest.mark.slow
def test_every_done_sections_figures_are_there_and_vector(notes):
    from aerophoto.report.figure_draws import FIGURES

    for rb in ("19-0457",):
        plan = STUDENTS[rb]
        r, text, _, _ = notes[rb]
        drawn = set(r.figures)
        for ch, specs in FIGURES.items():
            if ch == plan["undone"]:
                assert not any(c == ch for c, _ in drawn), ch
                continue
            wrong = plan["wrong"][0]
            for s in specs:
                if wrong in s.passed:
                    assert (ch, s.name) not in drawn  # it would show the graded value the student got wrong
                else:
                    assert (ch, s.name) in drawn, (rb, ch, s.name)
        n_caption = len(re.findall(r"Рисунок \d+ –", flat(text)))
        assert n_caption == len(drawn)
        listing = subprocess.run(["pdfimages", "-list", str(r.pdf)], capture_output=True, text=True,
                                 check=True).stdout.splitlines()[2:]
        images = [ln.split() for ln in listing if ln.split()[2] == "image"]
        photos = sum(s.photos for ch, specs in FIGURES.items() for s in specs if (ch, s.name) in drawn)
        assert len(images) == photos + (1 if r.sheet_pdf else 0), listing


@pytest.mark.slow
def test_the_fotoschema_sheet_is_true_size_russian_and_sharp(notes):
    from aerophoto.demos.fotoschema import PAPER_MM, sheet_size_mm
    from aerophoto.labs.ch05 import own_fotoschema
    from aerophoto.report.figures import latin_words

    r, text, _, top = notes["19-0457"]
    info = subprocess.run(["pdfinfo", str(r.sheet_pdf)], capture_output=True, text=True, check=True).stdout
    w_pt, h_pt = (float(x) for x in re.search(r"Page size:\s+([\d.]+) x ([\d.]+)", info).groups())
    w_mm, h_mm = PAPER_MM[r.sheet_paper]
    assert (w_pt * 25.4 / 72, h_pt * 25.4 / 72) == (pytest.approx(w_mm, abs=0.5), pytest.approx(h_mm, abs=0.5))
    # the note carries the same sheet on a page of its own size
    sizes = subprocess.run(["pdfinfo", "-f", "1", "-l", "200", str(r.pdf)], capture_output=True, text=True,
                           check=True).stdout
    assert f"{w_pt:.2f} x {h_pt:.2f}" in sizes.replace(" pts", "")
    # true scale: the glued photos span the mosaic's own size in mm, at ≥ 300 dpi
    listing = subprocess.run(["pdfimages", "-list", str(r.sheet_pdf)], capture_output=True, text=True,
                             check=True).stdout.splitlines()[2:]
    assert len(listing) == 1, listing
    cols = listing[0].split()
    px, xppi = int(cols[3]), float(cols[12])
    assert xppi >= 300
    mosaic_w, _ = sheet_size_mm(own_fotoschema(variant("19-0457")).fs)
    assert px / xppi * 25.4 == pytest.approx(mosaic_w, abs=1.0)
    sheet = flat(pdf_text(r.sheet_pdf))
    assert latin_words(sheet) == [], latin_words(sheet)
    for part in ("ФОТОСХЕМА", "Фотосхема изготовлена в 2026 г.", "Выполнил: ст. гр. ЗиК 31 Иванова Анна",
                 "Проверил: Пресняков В. В."):
        assert part in sheet
    assert "19-0457" not in sheet                                   # the guide's sample has no record book


@pytest.mark.slow
def test_pages_render_title_section_and_sheet(notes):
    from PIL import Image

    r, text, _, top = notes["19-0457"]
    n_sheet = next(k for k, page in enumerate(text.split("\f"), start=1) if "Фотосхема изготовлена" in page)
    n_section = next(k for k, page in enumerate(text.split("\f"), start=1) if "Таблица 2 –" in page)
    pages = {}
    for label, n, dpi in (("title", 1, 60), ("section", n_section, 60), ("sheet", n_sheet, 25)):
        stem = top / f"page_{label}"
        subprocess.run(["pdftoppm", "-r", str(dpi), "-png", "-singlefile", "-f", str(n), "-l", str(n), str(r.pdf),
                        str(stem)], check=True, capture_output=True)
        pages[label] = stem.with_suffix(".png")
    try:
        for label, p in pages.items():
            with Image.open(p) as im:
                grey = im.convert("L")
                hist = grey.histogram()
                dark = sum(hist[:128]) / (grey.size[0] * grey.size[1])
                assert 0.003 < dark < 0.6, (label, dark)           # text or photos on it, not a blank page
                if label == "sheet":
                    assert grey.size[0] > grey.size[1]              # the A3 sheet lies landscape
    except AssertionError:
        keep_on_failure(pages, "19-0457")
        raise


@pytest.mark.slow
def test_same_files_for_the_same_workbook_and_date(notes, tmp_path):
    from aerophoto import report

    r, _, _, top = notes["19-0457"]
    r2 = report.build(top / "workbook", tmp_path / "again", student="Иванова Анна", group="ЗиК 31",
                      checked_by="Пресняков В. В.", date=DATE, cache=top / "cache")
    assert r2.pdf.read_bytes() == r.pdf.read_bytes()
    assert r2.sheet_pdf.read_bytes() == r.sheet_pdf.read_bytes()


@pytest.mark.slow
def test_english_note_and_the_cli(notes, tmp_path):
    from aerophoto.course.cli import main
    import contextlib
    import io

    _, _, _, top = notes["19-0457"]
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        rc = main(["report", str(top / "workbook"), "--out", str(tmp_path / "o"), "--student", "Ivanova A.",
                   "--date", DATE, "--lang", "en", "--no-sheet", "--html-only", "--no-cache"])
    assert rc == 0, buf.getvalue()
    html = (tmp_path / "o" / "report.html").read_text(encoding="utf-8")
    assert "Planning the aerial survey" in html and "Explanatory note" in html and "19-0457" in buf.getvalue()
    with contextlib.redirect_stdout(io.StringIO()) as bad:
        assert main(["report", str(top / "workbook"), "--date", "tomorrow"]) == 2
    assert "date" in bad.getvalue()


def test_a_workbook_of_one_chapter_marks_every_other_section_not_done(tmp_path):
    from aerophoto import report
    from aerophoto.report.sections import SECTIONS

    assert [s.guide for s in SECTIONS] == list(range(2, 15)) and len(SECTIONS) == 13
    wb = tmp_path / "wb"
    wb.mkdir()
    src = ROOT / "notebooks" / "00_start_here.ipynb"
    shutil.copy(src, wb / src.name)
    def answer(nb):
        _, setup = nbtools.find_cell(nb, "setup")
        setup.source = setup.source.replace("RECORD_BOOK = None", "RECORD_BOOK = '19-0457'")
        nbtools.set_cell(nb, "task-00-1-answer", "from aerophoto import flight\nH_m = flight.plan(v).H_m\n"
                                                 "on_mm = 35.11\noc_mm = -17.54\n")

    _edit(wb / src.name, answer)
    r = report.build(wb, tmp_path / "o", date=DATE, formats=("html",), sheet=False, figures=False, cache=False)
    html = r.html.read_text(encoding="utf-8")
    assert r.task("task-00-1").state == "unreadable"
    assert "Задача 00.1 не может быть прочитана без запуска тетради" in html and "H_m" not in html
    assert html.count("Раздел не выполнен") >= 12
    assert html.index("Расчет параметров") < html.index("Фототриангуляция") < html.index("почвенном картографировании")
    assert math.isfinite(r.variant.f_mm)
