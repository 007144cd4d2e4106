"""A whole class on the course hub (deploy/jupyterhub), end to end, on 127.0.0.1.

JupyterHub with the course config starts as root; an instructor and four students log in through the log-in
form.  The instructor generates and releases chapter 00 through nbgrader's exchange; ivanova works in
JupyterLab in Debian's chromium (Playwright): Nbgrader → Assignment List → Fetch, types her record-book
number and a correct answer, runs the chapter, saves and submits; petrov (a wrong answer: f·M instead of
f·m) and sidorova (half: only H answered) do the same through their own servers' REST API (nbgrader's
Assignments handlers, the contents API); idler never does anything.  The instructor collects, autogrades with
``aerophoto-course autograde --jobs 2`` (sandboxed, in his server), writes the gradebook and releases
feedback; each student fetches hers.  Checked: the grades, that each student's feedback is hers and names
nobody else, that a student cannot read another's home, the instructor's course (sources with solutions,
gradebook, trusted reports) or the exchange's inbound and feedback listings, cannot open another's server,
has no authoring tools; the idle server and an idle kernel are culled; nothing is left running after the hub
stops.

Needs root, bubblewrap, JupyterHub (deploy/jupyterhub/requirements.txt), the proxy (``npm ci`` in
deploy/jupyterhub), chromium and Playwright: without them a developer gets a skip naming what to install; in
CI (``AEROPHOTO_CI=1``) a missing piece fails.  Wall time is printed (``-s``): 90–160 s on the 2-core
development machine while other work ran on it (about 45 s of it grading in the instructor's server).
"""

from __future__ import annotations

import csv
import html
import importlib.util
import json
import math
import os
import re
import sys
import time
from pathlib import Path

import pytest

pytestmark = [pytest.mark.hub, pytest.mark.slow]

ROOT = Path(__file__).resolve().parents[2]
HUB_DIR = ROOT / "deploy" / "jupyterhub"
IN_CI = os.environ.get("AEROPHOTO_CI") == "1"
A = "00_start_here"
NB = f"{A}/{A}.ipynb"

STUDENTS = {"ivanova": "19-0401", "petrov": "19-0433", "sidorova": "19-0499", "idler": "20-0100"}
CULL_TIMEOUT_S = 45
CULL_EVERY_S = 5
KERNEL_CULL_S = 10


def _load(name: str, path: Path):
    if name in sys.modules:
        return sys.modules[name]
    spec = importlib.util.spec_from_file_location(name, path)
    mod = importlib.util.module_from_spec(spec)
    sys.modules[name] = mod
    spec.loader.exec_module(mod)
    return mod


launch = _load("aerophoto_hub_launch", HUB_DIR / "launch.py")
h = _load("aerophoto_browser_harness", ROOT / "tests" / "browser" / "harness.py")


def _unavailable(why: str):
    if IN_CI:
        pytest.fail(f"the hub test cannot run in CI: {why}. .ci/run must provide it.", pytrace=False)
    pytest.skip(f"the hub test needs {why}")


def _hubclient():
    sys.path.insert(0, str(HUB_DIR))
    try:
        import hubclient
    finally:
        sys.path.remove(str(HUB_DIR))
    return hubclient


# --------------------------------------------------------------------------------------------------- answers
def _elements(record_book):
    from aerophoto.variants import variant

    v = variant(record_book)
    return (v.f_mm / 1000 * v.m, v.f_mm * math.tan(math.radians(v.alpha_deg)),
            -v.f_mm * math.tan(math.radians(v.alpha_deg / 2)))


ANSWER_IVANOVA = ("# ivanova's working: guide §1 and §5\nimport math\nH_m = v.f_mm / 1000 * v.m\n"
                  "on_mm = v.f_mm * math.tan(math.radians(v.alpha_deg))\n"
                  "oc_mm = -v.f_mm * math.tan(math.radians(v.alpha_deg) / 2)")


def _answer_petrov():
    """Wrong: the flying height from the plan's scale 1:M (a slip the check names), n and c right."""
    _, on, oc = _elements(STUDENTS["petrov"])
    return f"H_m = v.f_mm / 1000 * v.M   # petrov\non_mm = {on!r}\noc_mm = {oc!r}\n"


def _answer_sidorova():
    """Half: H answered, on and oc left as the template's `...`."""
    hh, _, _ = _elements(STUDENTS["sidorova"])
    return f"H_m = {hh!r}   # sidorova\non_mm = ...\noc_mm = ...\n"


def _hand_in(user, answer: str) -> None:
    """Fetch chapter 00 with nbgrader's Assignments list, type the record book and the answer, submit."""
    user.assignments("fetch", A)
    nb = user.read(NB)["content"]
    cells = {c.get("id"): c for c in nb["cells"]}
    cells["setup"]["source"] = cells["setup"]["source"].replace("RECORD_BOOK = None",
                                                                f'RECORD_BOOK = "{STUDENTS[user.name]}"')
    assert f'RECORD_BOOK = "{STUDENTS[user.name]}"' in cells["setup"]["source"]
    cells["task-00-1-answer"]["source"] = answer
    user.write_notebook(NB, nb)
    listing = user.assignments("submit", A)
    assert any(x.get("status") == "submitted" for x in listing), listing


# what a student's kernel tries (paths inside the sandbox; the host's state folder is passed in)
PROBE = r"""
import json, os, pwd, sys
state = sys.argv[1] if len(sys.argv) > 1 else {state!r}
res = {{}}
def attempt(label, fn):
    try:
        fn()
        res[label] = "ok"
    except Exception as exc:
        res[label] = type(exc).__name__
attempt("other_home", lambda: os.listdir("/home/{other}"))
attempt("course_source", lambda: open("/home/teacher/course/source/00_start_here/00_start_here.ipynb").read())
attempt("gradebook", lambda: open("/home/teacher/course/gradebook.db", "rb").read())
attempt("trusted_reports", lambda: os.listdir("/home/teacher/course/trusted"))
attempt("host_state", lambda: os.listdir(state))
attempt("host_homes", lambda: os.listdir(os.path.join(state, "home")))
attempt("inbound_listing", lambda: os.listdir("/srv/nbgrader/exchange/aerophoto/inbound"))
attempt("feedback_listing", lambda: os.listdir("/srv/nbgrader/exchange/aerophoto/feedback"))
attempt("write_release", lambda: open("/srv/nbgrader/exchange/aerophoto/outbound/00_start_here/x.ipynb", "w"))
attempt("rename_course", lambda: os.rename("/srv/nbgrader/exchange/aerophoto", "/srv/nbgrader/exchange/mine"))
attempt("write_python", lambda: open(os.path.join(sys.prefix, "x"), "w"))
attempt("repo_tests", lambda: os.listdir({tests!r}))
import resource
res["rlimit_as"] = list(resource.getrlimit(resource.RLIMIT_AS))
res["rlimit_nproc"] = list(resource.getrlimit(resource.RLIMIT_NPROC))
attempt("allocate_4gb", lambda: bytearray(4 * 2**30))
res["homes"] = sorted(os.listdir("/home"))
res["uid"] = os.getuid()
res["user"] = pwd.getpwuid(os.getuid()).pw_name
procs = []
for p in os.listdir("/proc"):
    if p.isdigit():
        uid = [line.split()[1] for line in open(f"/proc/{{p}}/status") if line.startswith("Uid:")][0]
        procs.append([open(f"/proc/{{p}}/comm").read().strip(), int(uid)])
res["processes"] = sorted(procs)
print(json.dumps(res))
"""


# the instructor's commands, run in a kernel of his server as he would in its terminal; every output line is
# printed as it comes (what the server reports as activity to the hub)
SHELL = r"""
import subprocess
for cmd in {cmds!r}:
    p = subprocess.Popen(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    for line in p.stdout:
        print(line, end="", flush=True)
    print(" ".join(cmd), "→", p.wait(), flush=True)
"""


def _text(html_doc: str) -> str:
    t = re.sub(r"<(style|script)\b.*?</\1>", " ", html_doc, flags=re.S)
    t = re.sub(r"<[^>]+>", " ", t)
    return html.unescape(re.sub(r"\s+", " ", t))


# --------------------------------------------------------------------------------------------------- browser
def _browser_student(page, hub, password, events):
    """ivanova in JupyterLab: log in, fetch chapter 00, answer, run it, save and submit."""
    page.goto(f"{hub.url}/hub/login?next=%2Fhub%2Fuser-redirect%2Flab", wait_until="domcontentloaded")
    page.fill("#username_input", "ivanova")
    page.fill("#password_input", password)
    page.click("#login_submit")
    page.wait_for_function("() => window.jupyterapp && window.jupyterapp.shell && "
                           "document.querySelector('#jp-MainMenu .lm-MenuBar-item')", timeout=h.T_RUN, polling=250)
    events["lab_open_s"] = time.perf_counter() - events["t0"]
    # the Nbgrader menu holds the Assignment List only (no formgrader, no course list)
    page.locator("#jp-MainMenu .lm-MenuBar-itemLabel", has_text="Nbgrader").click()
    menu = page.locator(".lm-Menu").last
    menu.wait_for(state="visible")
    events["menu"] = sorted(t.strip() for t in menu.locator(".lm-Menu-item:visible .lm-Menu-itemLabel").all_inner_texts()
                            if t.strip())
    menu.locator(".lm-Menu-itemLabel", has_text="Assignment List").click()
    events["create_assignment_panel"] = page.locator("#nbgrader-create_assignemnt").count()
    fetch = page.locator("#released_assignments_list button", has_text="Fetch")
    fetch.wait_for(state="visible", timeout=h.T_RUN)
    events["released_rows"] = page.locator("#released_assignments_list .list_item").all_inner_texts()
    fetch.click()
    page.locator("#fetched_assignments_list button", has_text="Submit").wait_for(state="visible", timeout=h.T_RUN)
    # open the fetched chapter, as the file browser does
    page.evaluate(f"() => window.jupyterapp.commands.execute('docmanager:open', {{path: {NB!r}}})")
    page.wait_for_function(
        """(name) => { const w = window.jupyterapp.shell.currentWidget;
            if (!w || !w.context || !w.context.path.endsWith(name) || !w.content) return false;
            const k = w.sessionContext.session && w.sessionContext.session.kernel;
            return !!k && k.status === 'idle' && w.content.widgets.length > 0; }""",
        arg=f"{A}.ipynb", timeout=h.T_RUN, polling=250)
    page.evaluate("""() => { window.jupyterapp.shell.currentWidget.content.widgets.forEach(
                               (c) => { c.node.dataset.aeroCellId = c.model.id; }); }""")

    def type_into(cell_id, text):
        editor = page.locator(f'[data-aero-cell-id="{cell_id}"] .cm-content').first
        editor.click()
        page.keyboard.press("Control+a")
        page.keyboard.insert_text(text)
        got = page.evaluate("""(id) => window.jupyterapp.shell.currentWidget.content.widgets
                                 .find((c) => c.model.id === id).model.sharedModel.getSource()""", cell_id)
        assert got == text, (cell_id, got)

    setup = page.evaluate("""() => window.jupyterapp.shell.currentWidget.content.widgets
                               .find((c) => c.model.id === 'setup').model.sharedModel.getSource()""")
    type_into("setup", setup.replace("RECORD_BOOK = None", f'RECORD_BOOK = "{STUDENTS["ivanova"]}"'))
    type_into("task-00-1-answer", ANSWER_IVANOVA)
    h.run_all_cells(page)
    events["check_output"] = page.locator('[data-aero-cell-id="task-00-1-check"] .jp-OutputArea-output'
                                          ).all_inner_texts()
    events["errors_on_page"] = h.error_outputs(page)
    page.keyboard.press("Control+s")
    page.wait_for_function("() => !window.jupyterapp.shell.currentWidget.context.model.dirty",
                           timeout=h.T_MOVE, polling=100)
    page.locator(".lm-TabBar-tab", has_text="Assignments").first.click()
    page.locator("#fetched_assignments_list button", has_text="Submit").click()
    page.locator("#submitted_assignments_list button", has_text="Fetch Feedback").wait_for(state="visible",
                                                                                          timeout=h.T_RUN)
    events["submitted_s"] = time.perf_counter() - events["t0"]


def _browser_feedback(page, events):
    page.locator(".lm-TabBar-tab", has_text="Assignments").first.click()
    button = page.locator("#submitted_assignments_list button", has_text="Fetch Feedback")
    button.wait_for(state="visible", timeout=h.T_RUN)
    button.click()
    page.locator("#submitted_assignments_list", has_text="view feedback").wait_for(state="visible", timeout=h.T_RUN)
    events["feedback_row"] = page.locator("#submitted_assignments_list").inner_text()


# --------------------------------------------------------------------------------------------------- the class
@pytest.fixture(scope="module")
def hub():
    need = launch.missing()
    if need:
        _unavailable("; ".join(need))
    try:
        import playwright.sync_api  # noqa: F401
    except ImportError:
        _unavailable("Playwright for Python (environment.txt)")
    if h.chromium_path() is None:
        _unavailable(f"Debian's chromium ({h.INSTALL_HINT})")
    hub = launch.Hub(sorted(STUDENTS.items()), ["teacher"], settings={
        "CULL_TIMEOUT": CULL_TIMEOUT_S, "CULL_EVERY": CULL_EVERY_S, "KERNEL_CULL": KERNEL_CULL_S,
        "ACTIVITY_INTERVAL": 5,
        # Playwright reads the Lab's state through window.jupyterapp (as tests/browser do)
        "SINGLEUSER_ARGS": "--LabApp.expose_app_in_browser=True",
    })
    hub.start()
    try:
        yield hub
    finally:
        hub.stop(remove=False)
        left = hub.user_processes()
        log_tail = hub.log_tail(80)
        import shutil

        shutil.rmtree(hub.state, ignore_errors=True)
        assert not left, f"processes of hub users left after the hub stopped: {left}\n{log_tail}"


@pytest.fixture(scope="module")
def course_run(hub):
    """The whole term of chapter 00 through the hub; returns what each step showed (see the module notes)."""
    try:
        return _course_run(hub)
    except BaseException:
        print(f"\n--- the hub's log (last lines) ---\n{hub.log_tail(150)}")
        raise


def _course_run(hub):
    from playwright.sync_api import sync_playwright

    hc = _hubclient()
    t0 = time.perf_counter()
    ev: dict = {"t0": t0, "phases": {}}

    def phase(name):
        ev["phases"][name] = round(time.perf_counter() - t0, 1)

    teacher = hc.HubUser(hub.url, "teacher", hub.instructor_password).login()
    users = {n: hc.HubUser(hub.url, n, hub.password(n)).login() for n in ("petrov", "sidorova", "idler")}
    ev["student_as_teacher"] = _login_status(hub.url, "teacher", hub.password("petrov"))
    ev["student_as_student"] = _login_status(hub.url, "sidorova", hub.password("petrov"))
    teacher.request_server()
    for u in users.values():
        u.request_server()
    phase("logged in, servers requested")
    pw = sync_playwright().start()
    browser = h.launch_chromium(pw)
    page, console = h.new_page(browser)
    try:
        teacher.start_server()
        out = teacher.run(SHELL.format(cmds=[["aerophoto-course", "generate", "--assignment", A],
                                             ["nbgrader", "release_assignment", A]]))
        ev["release"] = out
        phase("generated and released")
        ev["t0"] = time.perf_counter()
        _browser_student(page, hub, hub.password("ivanova"), ev)
        phase("ivanova submitted in the browser")
        for name, answer in (("petrov", _answer_petrov()), ("sidorova", _answer_sidorova())):
            users[name].start_server()
            _hand_in(users[name], answer)
        phase("petrov and sidorova submitted")
        # an idle kernel that no tab holds: her server culls it after KERNEL_CULL_S (its log line is checked below).
        # Watched here, while her server surely runs: asking for her kernels keeps the server active for the hub's
        # culler but is no activity of the kernel (under CI's load the server used to be culled with the kernel
        # still in it, before its own culler had said anything: no log line, the test failed)
        kid = ev["idle_kernel"] = users["sidorova"].start_kernel()
        t_kernel = time.monotonic()
        while kid in users["sidorova"].kernels() and time.monotonic() - t_kernel < KERNEL_CULL_S + 120:
            time.sleep(1)
        ev["idle_kernel_alive_s"] = round(time.monotonic() - t_kernel, 1)
        ev["idle_kernel_left"] = kid in users["sidorova"].kernels()
        phase("sidorova's idle kernel culled")
        teacher.start_server()  # idle while the class worked: the culler may have stopped it (his files stay)
        out = teacher.run(SHELL.format(cmds=[["nbgrader", "collect", A],
                                             ["aerophoto-course", "autograde", "--jobs", "2"],
                                             ["aerophoto-course", "gradebook"], ["aerophoto-course", "feedback"],
                                             ["nbgrader", "release_feedback", A]]))
        ev["grading"] = out
        phase("collected, graded, feedback released")
        _browser_feedback(page, ev)
        ev["feedback"] = {}
        ivanova = hc.HubUser(hub.url, "ivanova", hub.password("ivanova")).login()
        for name, user in (("ivanova", ivanova), ("petrov", users["petrov"]), ("sidorova", users["sidorova"])):
            user.start_server()  # a server culled while the class was graded starts again
            if name != "ivanova":
                user.assignments("fetch_feedback", A)
            stamps = user.listing(f"{A}/feedback")
            ev["feedback"][name] = {"stamps": stamps, "home": user.listing(""),
                                    "html": user.read(f"{A}/feedback/{stamps[0]}/{A}.html")["content"]
                                    if stamps else ""}
        phase("feedback fetched")
        # the culler stops a server idle for CULL_TIMEOUT_S: on a loaded machine the feedback round can take that
        # long, so petrov's server is (re)started right before it is used (his files stay either way)
        users["petrov"].start_server()
        ev["probe"] = json.loads(users["petrov"].run(PROBE.format(
            state=str(hub.state), other="sidorova", tests=str(ROOT / "tests")))["stdout"])
        for u in (teacher, users["sidorova"], users["petrov"]):
            u.start_server()
        ev["http"] = _http_checks(hub, teacher, users)
        phase("isolation probed")
        ev["console_errors"] = console.relevant()
    finally:
        page.context.close()
        browser.close()
        pw.stop()
    # culling: idler's server (never used) and sidorova's kernel (no tab)
    deadline = time.monotonic() + CULL_TIMEOUT_S + 4 * CULL_EVERY_S + 30
    while time.monotonic() < deadline and hub.server_ready("idler"):
        time.sleep(1)
    ev["idler_running"] = hub.server_ready("idler")
    phase("culling observed")
    ev["grades"] = list(csv.DictReader(open(hub.home("teacher") / "course" / "grades.csv", encoding="utf-8")))
    ev["homes"] = {p.name: (p.stat().st_uid, oct(p.stat().st_mode & 0o777)) for p in (hub.state / "home").iterdir()}
    ev["log"] = hub.log_text()
    ev["wall_s"] = round(time.perf_counter() - t0, 1)
    print(f"\nhub test: {ev['wall_s']} s; phases (s since start): {ev['phases']}")
    return ev


def _login_status(url, name, password) -> int:
    import requests

    s = requests.Session()
    s.get(f"{url}/hub/login", timeout=60)
    r = s.post(f"{url}/hub/login", data={"username": name, "password": password, "_xsrf": s.cookies.get("_xsrf", "")},
               allow_redirects=False, timeout=60)
    return r.status_code


def _http_checks(hub, teacher, users) -> dict:
    import requests

    petrov = users["petrov"]

    def status(user, url):
        return requests.get(url, headers=user.headers, timeout=60, allow_redirects=False).status_code

    return {
        "petrov→sidorova's files": status(petrov, f"{hub.url}/user/sidorova/api/contents"),
        "petrov→teacher's files": status(petrov, f"{hub.url}/user/teacher/api/contents"),
        "petrov→own formgrader": status(petrov, f"{hub.url}/user/petrov/formgrader/manage_assignments"),
        "petrov→own course list": status(petrov, f"{hub.url}/user/petrov/formgrader/api/courses"),
        "petrov→user list": status(petrov, f"{hub.url}/hub/api/users"),
        "teacher→formgrader": status(teacher, f"{hub.url}/user/teacher/formgrader/manage_assignments"),
        "teacher→user list": status(teacher, f"{hub.url}/hub/api/users"),
        "teacher→petrov's files": status(teacher, f"{hub.url}/user/petrov/api/contents"),
    }


# --------------------------------------------------------------------------------------------------- checks
def test_instructor_releases_and_grades_through_the_exchange(course_run):
    rel, grading = course_run["release"], course_run["grading"]
    assert rel["error"] is None and grading["error"] is None, (rel, grading)
    assert "aerophoto-course generate --assignment 00_start_here → 0" in rel["stdout"], rel["stdout"]
    assert "nbgrader release_assignment 00_start_here → 0" in rel["stdout"], rel["stdout"]
    out = grading["stdout"]
    for cmd in ("nbgrader collect 00_start_here", "aerophoto-course autograde --jobs 2", "aerophoto-course gradebook",
                "aerophoto-course feedback", "nbgrader release_feedback 00_start_here"):
        assert f"{cmd} → 0" in out, out
    for name in ("ivanova", "petrov", "sidorova"):
        assert f"Collecting submission: {name} 00_start_here" in out
    assert "idler" not in out.split("aerophoto-course autograde")[0]  # nothing to collect from idler
    assert "3 submission(s) in 2 parallel jobs" in out
    assert "cheating attempt" not in out  # every submission is owned by the student it names


def test_grades_are_the_trusted_ones(course_run):
    rows = {r["student_id"]: r for r in course_run["grades"]}
    assert set(rows) == set(STUDENTS)  # the roster (the hub's) is the course's: idler has a row too
    assert {n: float(rows[n]["score"]) for n in ("ivanova", "petrov", "sidorova")} == {
        "ivanova": 3.0, "petrov": 0.0, "sidorova": 0.0}
    assert all(float(rows[n]["max_score"]) == 3.0 for n in rows)
    assert {n: rows[n]["record_book"] for n in rows} == STUDENTS
    assert rows["idler"]["flags"].startswith("missing")
    for n in ("ivanova", "petrov", "sidorova"):
        assert rows[n]["flags"] == "", (n, rows[n]["flags"])


def test_the_browser_student_works_in_jupyterlab(course_run):
    ev = course_run
    assert ev["menu"] == ["Assignment List"], ev["menu"]  # no formgrader, no course list
    assert ev["create_assignment_panel"] == 0
    assert any(A in row for row in ev["released_rows"]), ev["released_rows"]
    check = "\n".join(ev["check_output"])
    assert "✓ Task 00.1 passed" in check, check
    assert ev["errors_on_page"] == [] and ev["console_errors"] == [], (ev["errors_on_page"], ev["console_errors"])
    assert "view feedback" in ev["feedback_row"]


def test_each_student_gets_her_own_feedback_and_nobody_elses(course_run):
    fb = course_run["feedback"]
    expected = {"ivanova": "Score: 3.0 / 3.0", "petrov": "Score: 0.0 / 3.0", "sidorova": "Score: 0.0 / 3.0"}
    for name, want in expected.items():
        assert len(fb[name]["stamps"]) == 1, fb[name]
        text = _text(fb[name]["html"])
        assert want in text, (name, text[:500])
        assert STUDENTS[name] in text  # her record book: her own notebook
        for other, rb in STUDENTS.items():
            if other != name:
                assert rb not in text and other not in text.replace(name, ""), (name, other)
        assert "BEGIN SOLUTION" not in fb[name]["html"] and "_tasks.answers" not in fb[name]["html"]
    assert "f·M" in _text(fb["petrov"]["html"]) or "1:M" in _text(fb["petrov"]["html"])  # the slip is named
    assert "no answer yet" in _text(fb["sidorova"]["html"])


def test_a_student_cannot_reach_other_homes_the_course_or_the_hidden_material(course_run):
    p = course_run["probe"]
    for what in ("other_home", "course_source", "gradebook", "trusted_reports", "host_state", "host_homes",
                 "repo_tests"):
        assert p[what] == "FileNotFoundError", (what, p[what])  # not even there: only her own home is mounted
    for what in ("inbound_listing", "feedback_listing", "write_release", "rename_course"):
        assert p[what] == "PermissionError", (what, p[what])
    assert p["write_python"] in ("OSError", "PermissionError"), p["write_python"]  # read-only
    assert p["homes"] == ["petrov"] and p["user"] == "petrov" and p["uid"] >= 30000
    # the memory limit of her processes (the spawner's mem_limit, 3 GB): a 4 GB array is refused
    assert p["rlimit_as"] == [3 * 2**30, 3 * 2**30] and p["allocate_4gb"] == "MemoryError", p
    assert p["rlimit_nproc"] == [512, 512]
    # her own process namespace: her server and kernel (and bubblewrap's init, root inside it) — not the hub,
    # the proxy or anyone else's processes
    assert {uid for _, uid in p["processes"]} <= {0, p["uid"]}, p["processes"]
    assert [c for c, uid in p["processes"] if uid == 0] == ["bwrap"], p["processes"]
    assert "node" not in {c for c, _ in p["processes"]} and len(p["processes"]) <= 6, p["processes"]
    # on the host too: each home is its owner's alone
    homes = course_run["homes"]
    assert len({uid for uid, _ in homes.values()}) == len(homes)
    assert {mode for _, mode in homes.values()} == {"0o700"}


def test_roles_over_http(course_run):
    assert course_run["http"] == {
        "petrov→sidorova's files": 403,
        "petrov→teacher's files": 403,
        "petrov→own formgrader": 404,
        "petrov→own course list": 404,
        "petrov→user list": 403,
        "teacher→formgrader": 200,
        "teacher→user list": 200,
        # the default log-in (a password per user) makes no one the hub's admin: the instructor role sees the class
        # and stops/starts its servers, but opens no student's files (jupyterhub_config.py)
        "teacher→petrov's files": 403,
    }
    assert course_run["student_as_teacher"] == 403  # a student's password does not open the instructor's account
    assert course_run["student_as_student"] == 403  # ... nor another student's

def test_idle_servers_and_kernels_are_culled(course_run):
    assert course_run["idler_running"] is False
    assert "Culling server idler" in course_run["log"] or "culling server idler" in course_run["log"].lower()
    kid = course_run["idle_kernel"]
    assert course_run["idle_kernel_left"] is False, (
        f"an idle kernel with no tab still ran {course_run['idle_kernel_alive_s']} s after it started "
        f"(cull after {KERNEL_CULL_S} s)")
    assert course_run["idle_kernel_alive_s"] >= KERNEL_CULL_S, course_run["idle_kernel_alive_s"]  # idle, then culled
    culled = [line for line in course_run["log"].splitlines() if "Culling" in line and kid in line]
    assert culled and "inactivity" in culled[0], culled
