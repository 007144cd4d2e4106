"""The hostile class: students who attack the grader, beside honest ones, graded by aerophoto-course.

Every attack of issue 11 is a submission of chapter 00 (one task, 3 points).  Asserted:

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
TIMEOUT = 6
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
        "19-0516": (WRONG + "from aerophoto import checks\nchecks.check_value = lambda *a, **k: True\n", None, None,
                    0.0, {"patched_checks", "tampered"}),
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
    c = course.Course(top / "course", book, timeout=TIMEOUT, out=lambda s: None,
                      limits=Limits(memory_mb=1024, nproc=64, output_mb=1.0, message_mb=8, cpu_s=120))
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
        nbformat.write(nb, str(export / f"{sid}_{A}.ipynb"))
    c.import_submissions(export)
    before = _course_files(c.root)
    t0 = time.perf_counter()
    results = c.autograde()
    seconds = time.perf_counter() - t0
    time.sleep(0.5)
    return c, plan, results, before, seconds


def test_every_submission_was_graded(hostile):
    c, plan, results, _, seconds = hostile
    assert sorted(r.student for r in results) == sorted(plan)
    assert {r.status for r in results} == {"graded"}, [(r.student, r.status, r.error) for r in results]
    print(f"hostile class: {len(results)} submissions in {seconds:.0f} s")


def test_honest_students_get_the_right_grade(hostile):
    c, plan, results, _, _ = hostile
    got = {r.student: (r.score, {f.code for f in r.flags}) for r in results}
    for sid in ("19-0501", "19-0502", "19-0503"):
        assert got[sid] == (plan[sid][3], set()), sid


@pytest.mark.parametrize("sid", sorted(attacks(Path("/course"))))
def test_each_attack_scores_what_its_answers_deserve_and_is_flagged(hostile, sid):
    c, plan, results, _, _ = hostile
    r = next(r for r in results if r.student == sid)
    _, _, _, score, expected = plan[sid]
    got = {f.code for f in r.flags}
    assert r.score == score, (sid, r.score, [str(f) for f in r.flags])
    assert expected <= got, (sid, sorted(got), [str(f) for f in r.flags])
    assert got - expected <= ORDINARY | {"system_access", "dynamic_code"}, (sid, sorted(got - expected))


def test_nothing_outside_the_sandbox_changed(hostile):
    c, _, _, before, _ = hostile
    assert _course_files(c.root) == before
    assert not PWNED.exists()
    # nbgrader_config.py is read by every later command: still the template
    assert "pathlib" not in (c.root / "nbgrader_config.py").read_text(encoding="utf-8")


def test_the_gradebook_holds_exactly_the_trusted_scores(hostile):
    c, plan, _, _, _ = hostile
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
    c, _, results, _, _ = hostile
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
