"""A class on the course hub (deploy/jupyterhub), measured on this machine: what N students cost.

    python benchmarks/run.py hub                    # N = 10, 20, 30 students (as root; ~20 min)
    python benchmarks/run.py hub --quick            # N = 4
    AEROPHOTO_BENCH_HUB_N=10,30 python benchmarks/run.py hub

For each N, a fresh hub (``deploy/jupyterhub/launch.py``: the course config, bubblewrap spawner, the proxy)
with N students and an instructor:

* **start-up**: all N log in (the log-in form) and ask for their servers at once; per student the seconds
  from the request to a server that answers, and until the whole class is up;
* **opening a chapter**: every student opens chapter 00 at once — N−1 simulated students run its first cells
  (setup, the footprint demo) in a kernel of their server over the kernel websocket; one real student opens
  it in JupyterLab in Debian's chromium (Playwright) and runs it;
* **moving a slider at once**: the simulated students each move the demo's α slider once a second *as a
  browser does* — the slider's new value as a widget message over the kernel websocket; in the kernel the
  demo's own handler (compute, the blitted redraw, the PNG of the changed pixels, as ipympl sends it); the frame
  back over the websocket.  Each simulated student greets the figure's canvas as ipympl's front end does
  (``initialized``: a canvas that never hears it keeps encoding a second, full PNG of every frame for the
  widget's state) and answers its requests for a draw.  Timed: the round trip of each move from the student's
  websocket (the slider's message sent → the frame received), the kernel's own time and CPU time of each move
  (the handler, wrapped in the kernel) and the frame's size.  Meanwhile the real student moves the same slider in
  the browser, timed from the key press to the painted frame with the method of bench_browser.py
  (``performance.now()`` in the page);
* **CPU**: the share of a core the students' servers, their kernels and the hub with its proxy use while the
  class sits idle (chapter open, nobody moving: two windows of :data:`IDLE_S` s, the first just after the last
  student opened the chapter, ``idle_just_opened``, then ``idle``) and while it moves (``cpu_core_share``);
* **memory**: after that, the proportional set size (PSS: shared pages split between their users) of each
  student's server and kernel processes (found by the student's uid), the hub and the proxy, and how much of
  the machine's available memory the class took;
* **grading**: the same N hand in chapter 00 (a third right, a third wrong, a third blank) and the class is
  autograded in the sandbox one at a time and with ``--jobs 2``; the two gradebooks must be identical.

The machine's load average is recorded beside each N: other work on a shared machine inflates every number.
Prints nothing (benchmarks/run.py prints the JSON).
"""

from __future__ import annotations

import asyncio
import copy
import json
import os
import statistics
import sys
import tempfile
import threading
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

from _timing import chapter_opening, hubclient
from _timing import load_module as _load
from _timing import summarize

ROOT = Path(__file__).resolve().parents[1]
HUB = ROOT / "deploy" / "jupyterhub"
A = "00_start_here"
MOVE_PERIOD_S = 1.0
BROWSER_MOVES = 10
#: seconds the class sits idle (chapter open) while its CPU is measured
IDLE_S = 20.0

#: after the chapter's first cells: time every slider move inside the kernel (the demo's own handler, wrapped) and
#: hand the client the ids of the slider's and the canvas' widgets
INSTRUMENT = """
import ast as _ast, json as _json, time as _t
_aero_moves = []
_aero_ctl = demo.controls()["alpha_deg"]
_aero_ctl.unobserve(demo._on_change, names="value")
def _aero_timed(change, _inner=demo._on_change):
    c0, w0 = _t.process_time(), _t.perf_counter()
    _inner(change)
    _aero_moves.append([(_t.perf_counter() - w0) * 1000, (_t.process_time() - c0) * 1000])
_aero_ctl.observe(_aero_timed, names="value")
_aero_ids = _json.dumps({"slider": _aero_ctl.model_id, "canvas": demo.fig.canvas.model_id})
"""

#: what ipympl's front end sends a new figure's canvas (its `send_initialization_message`): a kernel whose canvas
#: never hears "initialized" keeps encoding a second, full PNG of every frame for the widget state
CANVAS_HELLO = ({"type": "set_dpi_ratio", "dpi_ratio": 1}, {"type": "initialized"}, {"type": "send_image_mode"},
                {"type": "refresh"})


def _mem_available_mb() -> float:
    for line in Path("/proc/meminfo").read_text().splitlines():
        if line.startswith("MemAvailable:"):
            return int(line.split()[1]) / 1024
    return float("nan")


def _memory(hub) -> dict:
    """PSS (and RSS) of each student's server and kernels, the hub and the proxy, in MB."""
    import psutil

    table = json.loads((hub.state / "users.json").read_text(encoding="utf-8"))
    by_uid = {u: n for n, u in table.items()}
    servers, kernels, per_student = [], [], {}
    for p in psutil.process_iter(["uids", "cmdline"]):
        try:
            uid = p.info["uids"].real if p.info["uids"] else None
            if uid not in by_uid or by_uid[uid] == "teacher":
                continue
            mi = p.memory_full_info()
            cmd = " ".join(p.info["cmdline"] or [])
        except psutil.Error:
            continue
        pss, rss = mi.pss / 2**20, mi.rss / 2**20
        if "jupyterhub-singleuser" in cmd:
            servers.append((pss, rss))
        elif "ipykernel" in cmd:
            kernels.append((pss, rss))
        per_student[by_uid[uid]] = per_student.get(by_uid[uid], 0.0) + pss
    hub_mb = 0.0
    try:
        hp = psutil.Process(hub.proc.pid)
        for p in [hp, *hp.children(recursive=False)]:
            cmd = " ".join(p.cmdline())
            if "jupyterhub" in cmd or "configurable-http-proxy" in cmd or "node" in cmd:
                hub_mb += p.memory_full_info().pss / 2**20
    except psutil.Error:
        pass

    def med(xs, k):
        return round(statistics.median(x[k] for x in xs), 1) if xs else None

    return {"server_pss_mb_median": med(servers, 0), "server_rss_mb_median": med(servers, 1),
            "kernel_pss_mb_median": med(kernels, 0), "kernel_rss_mb_median": med(kernels, 1),
            "per_student_pss_mb_median": round(statistics.median(per_student.values()), 1) if per_student else None,
            "per_student_pss_mb_max": round(max(per_student.values()), 1) if per_student else None,
            "class_pss_mb": round(sum(per_student.values()), 1), "hub_and_proxy_pss_mb": round(hub_mb, 1),
            "servers": len(servers), "kernels": len(kernels)}


def _cpu_s(hub) -> dict:
    """CPU seconds (user + system) so far of the students' servers, their kernels, and the hub with its proxy."""
    import psutil

    table = json.loads((hub.state / "users.json").read_text(encoding="utf-8"))
    uids = {u for n, u in table.items() if n != "teacher"}
    out = {"servers": 0.0, "kernels": 0.0, "hub_and_proxy": 0.0}
    for p in psutil.process_iter(["uids", "cmdline"]):
        try:
            uid = p.info["uids"].real if p.info["uids"] else None
            if uid not in uids:
                continue
            t = p.cpu_times()
            cmd = " ".join(p.info["cmdline"] or [])
        except psutil.Error:
            continue
        key = "kernels" if "ipykernel" in cmd else "servers"
        out[key] += t.user + t.system
    try:
        hp = psutil.Process(hub.proc.pid)
        for p in [hp, *hp.children(recursive=True)]:
            if p.uids().real in uids:
                continue
            t = p.cpu_times()
            out["hub_and_proxy"] += t.user + t.system
    except psutil.Error:
        pass
    return out


def _cpu_rate(a: dict, b: dict, seconds: float, n: int) -> dict:
    """Per part, the share of one core used between two :func:`_cpu_s` snapshots (and per student)."""
    out = {k: round((b[k] - a[k]) / seconds, 3) for k in a}
    out["per_student_core_share"] = round((b["servers"] + b["kernels"] - a["servers"] - a["kernels"]) / seconds / n, 4)
    return out


# --------------------------------------------------------------------------------------------- simulated students
def _frame(raw):
    """One kernel websocket frame as ``(message, buffers)``: JSON text, or jupyter_server's binary framing of a
    message with buffers (a count, offsets, the JSON, the buffers) — a figure's frame comes that way."""
    import struct

    if isinstance(raw, str):
        return json.loads(raw), []
    n = struct.unpack("!I", raw[:4])[0]
    offsets = list(struct.unpack("!" + "I" * n, raw[4:4 * (n + 1)])) + [len(raw)]
    parts = [raw[offsets[i]:offsets[i + 1]] for i in range(n)]
    return json.loads(parts[0].decode("utf-8")), parts[1:]


async def _next(ws, timeout: float):
    raw = await asyncio.wait_for(ws.read_message(), timeout)
    if raw is None:
        raise RuntimeError("the kernel's websocket closed")
    return _frame(raw)


def _custom(hc, ws, comm_id: str, content: dict) -> None:
    """A widget's custom message, as its front end sends it (ipympl's canvas protocol)."""
    hc.send(ws, "comm_msg", {"comm_id": comm_id, "data": {"method": "custom", "content": content}})


def _canvas_says(msg, canvas: str):
    """What the kernel's canvas sent: "binary" (a frame), "draw" (asks the page for a draw), another type, or None."""
    if msg.get("header", {}).get("msg_type") != "comm_msg" or msg["content"].get("comm_id") != canvas:
        return None
    data = msg["content"].get("data", {})
    try:
        return json.loads(data.get("content", {}).get("data", "{}")).get("type")
    except (TypeError, ValueError, AttributeError):
        return None


async def _execute(hc, ws, code: str, timeout: float = 600, expressions: dict | None = None) -> dict:
    msg_id = hc.send(ws, "execute_request", {"code": code, "silent": False, "store_history": False,
                                             "user_expressions": expressions or {}, "allow_stdin": False,
                                             "stop_on_error": True})
    reply, error, idle = None, None, False
    while reply is None or not idle:  # the reply (shell) and the idle status (iopub) come in either order
        msg, _ = await _next(ws, timeout)
        if msg.get("parent_header", {}).get("msg_id") != msg_id:
            continue
        kind = msg["header"]["msg_type"]
        if kind == "error":
            error = f"{msg['content']['ename']}: {msg['content']['evalue']}"
        elif kind == "execute_reply":
            reply = msg["content"]
        elif kind == "status" and msg["content"]["execution_state"] == "idle" and msg.get("channel") == "iopub":
            idle = True
    if error:
        raise RuntimeError(error)
    return reply


async def _await_frame(hc, ws, canvas: str, timeout: float = 120) -> int:
    """Wait for the canvas' next frame, answering its requests for a draw as the page does; the frame's bytes."""
    while True:
        msg, bufs = await _next(ws, timeout)
        said = _canvas_says(msg, canvas)
        if said == "binary":
            return sum(len(b) for b in bufs)
        if said == "draw":
            _custom(hc, ws, canvas, {"type": "draw"})


async def _student(hc, user, rb: str, go: threading.Event, stop: threading.Event, out: dict) -> None:
    """One student without a browser who moves α once a second *as the browser does*: the slider's new value as
    a widget message, the kernel's frame (a blitted diff) back over the websocket, the canvas greeted and its
    requests for a draw answered as ipympl's front end does."""
    import ast

    kid = await asyncio.to_thread(user.start_kernel)
    ws = await user.connect(kid)
    try:
        t0 = time.perf_counter()
        await _execute(hc, ws, chapter_opening(A, "demo-footprint", rb))
        reply = await _execute(hc, ws, INSTRUMENT, expressions={"ids": "_aero_ids"})
        ids = json.loads(ast.literal_eval(reply["user_expressions"]["ids"]["data"]["text/plain"]))
        for hello in CANVAS_HELLO:
            _custom(hc, ws, ids["canvas"], hello)
        await _await_frame(hc, ws, ids["canvas"])  # the first, full picture
        out["open_s"] = time.perf_counter() - t0
        while not go.is_set():
            await asyncio.sleep(0.05)
        out["moves_s"], out["frame_bytes"] = [], []
        k = 0
        while not stop.is_set() or k < 3:
            t = time.perf_counter()
            hc.send(ws, "comm_msg", {"comm_id": ids["slider"],
                                     "data": {"method": "update", "state": {"value": [3.5, 3.0][k % 2]},
                                              "buffer_paths": []}})
            out["frame_bytes"].append(await _await_frame(hc, ws, ids["canvas"]))
            out["moves_s"].append(time.perf_counter() - t)
            k += 1
            await asyncio.sleep(max(0.0, MOVE_PERIOD_S - (time.perf_counter() - t)))
        reply = await _execute(hc, ws, "", expressions={"m": "_json.dumps(_aero_moves)"})
        moves = json.loads(ast.literal_eval(reply["user_expressions"]["m"]["data"]["text/plain"]))
        out["kernel_ms"] = [w for w, _c in moves]
        out["kernel_cpu_ms"] = [c for _w, c in moves]
    finally:
        ws.close()


def _simulated_class(hc, users, rbs, go, stop, results, done) -> None:
    async def main():
        await asyncio.gather(*[_student(hc, u, rbs[u.name], go, stop, results[u.name]) for u in users],
                             return_exceptions=False)

    try:
        asyncio.run(main())
    except BaseException as exc:  # reported by the caller
        results["_error"] = f"{type(exc).__name__}: {exc}"
    finally:
        done.set()


# --------------------------------------------------------------------------------------------- the browser student
def _browser_student(h, hub, user, password, browser, go, sim_opened) -> dict:
    """Log in, open chapter 00 in JupyterLab, run it; when the class moves, time the α slider."""
    page, log = h.new_page(browser)
    out = {}
    try:
        t0 = time.perf_counter()
        page.goto(f"{hub.url}/hub/login?next=%2Fhub%2Fuser-redirect%2Flab%2Ftree%2F{A}.ipynb",
                  wait_until="domcontentloaded")
        page.fill("#username_input", user)
        page.fill("#password_input", password)
        page.click("#login_submit")
        page.wait_for_function(
            """(name) => { const app = window.jupyterapp; if (!app || !app.shell) return false;
                const w = app.shell.currentWidget;
                if (!w || !w.context || !w.context.path.endsWith(name) || !w.content) return false;
                const k = w.sessionContext.session && w.sessionContext.session.kernel;
                return !!k && k.status === 'idle' && w.content.widgets.length > 0; }""",
            arg=f"{A}.ipynb", timeout=h.T_RUN * 3, polling=250)
        page.evaluate("""() => { window.jupyterapp.shell.currentWidget.content.widgets.forEach(
                                   (c) => { c.node.dataset.aeroCellId = c.model.id; }); }""")
        h.run_all_cells(page)
        out["open_s"] = time.perf_counter() - t0
        root = h.lab_demo_root(page, "demo-footprint")
        root.wait_for(state="visible", timeout=h.T_RUN)
        root.scroll_into_view_if_needed()
        h.settle(page, 500)
        sim_opened.wait(timeout=1800)
        go.set()
        slider = h.slider_in(page, root, "α, °")
        res = h.time_slider_moves(page, slider, BROWSER_MOVES, after_move=lambda: h.lab_kernel_idle(page))
        out["slider_to_paint"] = summarize(res["samples_s"])
        out["values"] = sorted(set(res["values"]))
        out["console_errors"] = log.relevant()
    finally:
        page.context.close()
    return out


# --------------------------------------------------------------------------------------------- one class size
def _one_class(n: int, launch, hc, h, browser) -> dict:
    students = [(f"s{k:03d}", f"19-{1000 + k:04d}"[-7:]) for k in range(1, n + 1)]
    rbs = dict(students)
    load0 = os.getloadavg()
    mem0 = _mem_available_mb()
    hub = launch.Hub(students, ["teacher"], settings={"CULL_TIMEOUT": 36000, "KERNEL_CULL": 36000,
                                                     "START_TIMEOUT": 900,
                                                     "SINGLEUSER_ARGS": "--LabApp.expose_app_in_browser=True"})
    result: dict = {"students": n, "loadavg_before": [round(x, 2) for x in load0]}
    hub.start()
    try:
        result["hub_start_s"] = round(hub.seconds_to_start, 2)
        with ThreadPoolExecutor(8) as pool:
            users = list(pool.map(lambda s: hc.HubUser(hub.url, s[0], hub.password(s[0])).login(), students))
        t0 = time.perf_counter()
        for u in users:
            u.request_server()
        ready: dict = {}
        while len(ready) < n and time.perf_counter() - t0 < 1200:
            for u in hub.api("GET", "/users"):
                if u["name"] in rbs and u["name"] not in ready and u.get("servers", {}).get("", {}).get("ready"):
                    ready[u["name"]] = time.perf_counter() - t0
            time.sleep(0.25)
        if len(ready) < n:
            raise RuntimeError(f"only {len(ready)} of {n} servers started:\n{hub.log_tail(40)}")
        result["server_start"] = summarize(ready.values())
        result["class_up_s"] = round(max(ready.values()), 2)
        result["server_start_per_student_s"] = round(max(ready.values()) / n, 2)
        # the chapter in the browser student's home (her workbook copy)
        b_user = users[0]
        nb = json.loads((ROOT / "notebooks" / f"{A}.ipynb").read_text(encoding="utf-8"))
        for c in nb["cells"]:
            if c.get("id") == "setup":
                c["source"] = "".join(c["source"]).replace("RECORD_BOOK = None", f'RECORD_BOOK = "{rbs[b_user.name]}"')
        b_user.write_notebook(f"{A}.ipynb", nb)
        sims = users[1:]
        go, stop, done, opened = threading.Event(), threading.Event(), threading.Event(), threading.Event()
        sim = {u.name: {} for u in sims}
        thread = threading.Thread(target=_simulated_class, args=(hc, sims, rbs, go, stop, sim, done), daemon=True)
        thread.start()

        cpu: dict = {}

        def all_opened():
            while not done.is_set():
                if all("open_s" in sim[u.name] for u in sims):
                    # the class idle (chapter open, nobody moving): what it costs the machine anyway — in two
                    # windows: the first holds the tail of the class's start (the last kernels' first full draws),
                    # the second is what an idle class costs for as long as it sits
                    for window in ("idle_just_opened", "idle"):
                        c0, t0 = _cpu_s(hub), time.perf_counter()
                        time.sleep(IDLE_S)
                        cpu[window] = _cpu_rate(c0, _cpu_s(hub), time.perf_counter() - t0, n)
                    cpu["moving_from"] = (_cpu_s(hub), time.perf_counter())
                    opened.set()
                    return
                time.sleep(0.2)

        watcher = threading.Thread(target=all_opened, daemon=True)
        watcher.start()
        try:
            result["browser"] = _browser_student(h, hub, b_user.name, hub.password(b_user.name), browser, go, opened)
        finally:
            if "moving_from" in cpu:
                c0, t0 = cpu.pop("moving_from")
                cpu["moving"] = _cpu_rate(c0, _cpu_s(hub), time.perf_counter() - t0, n)
            stop.set()
            done.wait(timeout=600)
        if "_error" in sim:
            raise RuntimeError(f"a simulated student failed: {sim['_error']}")
        result["open_chapter"] = summarize([s["open_s"] for s in sim.values()] + [result["browser"]["open_s"]])
        moves = [x for s in sim.values() for x in s.get("moves_s", [])]
        kernel = [x / 1000 for s in sim.values() for x in s.get("kernel_ms", [])]
        kernel_cpu = [x / 1000 for s in sim.values() for x in s.get("kernel_cpu_ms", [])]
        result["kernel_round_trip_of_a_move"] = summarize(moves)
        result["kernel_work_of_a_move"] = summarize(kernel)
        result["kernel_cpu_of_a_move"] = summarize(kernel_cpu)
        result["frame_kb_of_a_move"] = round(statistics.median(
            [b / 1000 for s in sim.values() for b in s.get("frame_bytes", [])] or [float("nan")]), 1)
        result["cpu_core_share"] = cpu
        result["moves_per_s_offered"] = round(len(sims) / MOVE_PERIOD_S, 1)
        result["memory"] = _memory(hub)
        result["memory"]["machine_available_mb_before"] = round(mem0)
        result["memory"]["machine_available_mb_with_class"] = round(_mem_available_mb())
        result["loadavg_after"] = [round(x, 2) for x in os.getloadavg()]
    finally:
        hub.stop()
    result["grading"] = _grading(students)
    return result


def _grading(students) -> dict:
    """The class hands in chapter 00; autograde one at a time and with --jobs 2 (identical gradebooks)."""
    import nbformat

    from aerophoto import course, nbtools
    from aerophoto.course.versions import strip_solutions

    sol = ("import math\nH_m = v.f_mm / 1000 * v.m\non_mm = v.f_mm * math.tan(math.radians(v.alpha_deg))\n"
           "oc_mm = -v.f_mm * math.tan(math.radians(v.alpha_deg) / 2)\n")
    with tempfile.TemporaryDirectory(prefix="aerophoto-bench-hub-grading-") as tmp:
        top = Path(tmp)
        book = top / "notebooks"
        book.mkdir()
        nbtools.write(strip_solutions(nbtools.read(ROOT / "notebooks" / f"{A}.ipynb"))[0], book / f"{A}.ipynb")
        (top / "course").mkdir()
        with open(top / "course" / "roster.csv", "w", encoding="utf-8") as fh:
            fh.write("student_id,record_book\n" + "".join(f"{s},{rb}\n" for s, rb in students))
        c = course.Course(top / "course", book, out=lambda s: None)
        c.generate()
        release = nbformat.read(str(c.path("release", A)), as_version=4)
        export = top / "export"
        export.mkdir()
        for k, (sid, rb) in enumerate(students):
            nb = copy.deepcopy(release)
            setup = nbtools.find_cell(nb, "setup")[1]
            setup.source = setup.source.replace("RECORD_BOOK = None", f'RECORD_BOOK = "{rb}"')
            ans = nbtools.find_cell(nb, "task-00-1-answer")[1]
            if k % 3 == 0:
                ans.source = f"me = {sid!r}\n" + sol
            elif k % 3 == 1:
                ans.source = f"me = {sid!r}\n" + sol + "H_m = H_m / 1000\n"
            nbformat.write(nb, str(export / f"{sid}_{A}.ipynb"))
        c.import_submissions(export)
        out = {}
        t0 = time.perf_counter()
        r1 = c.autograde()
        out["serial_s"] = round(time.perf_counter() - t0, 1)
        g1 = c.gradebook().to_csv(index=False)
        t0 = time.perf_counter()
        r2 = c.autograde(force=True, jobs=2)
        out["jobs2_s"] = round(time.perf_counter() - t0, 1)
        g2 = c.gradebook().to_csv(index=False)
        out["speed_up"] = round(out["serial_s"] / out["jobs2_s"], 2)
        out["per_notebook_serial"] = summarize([r.seconds for r in r1])
        out["identical_gradebooks"] = g1 == g2
        out["failed"] = sum(r.status == "failed" for r in r1 + r2)
        out["scores"] = sorted({r.score for r in r1})
    return out


def run(quick: bool = False) -> dict:
    launch = _load("aerophoto_hub_launch", HUB / "launch.py")
    h = _load("aerophoto_browser_harness", ROOT / "tests" / "browser" / "harness.py")
    hc = hubclient()
    need = launch.missing()
    if need:
        return {"skipped": "the course hub cannot start here: " + "; ".join(need)}
    sizes = [4] if quick else [10, 20, 30]
    if os.environ.get("AEROPHOTO_BENCH_HUB_N"):
        sizes = [int(x) for x in os.environ["AEROPHOTO_BENCH_HUB_N"].split(",") if x.strip()]
    from playwright.sync_api import sync_playwright

    out = {"method": __doc__.split("For each N,")[1].split("The machine's")[0].strip().replace("\n", " "),
           "move_period_s": MOVE_PERIOD_S, "browser_moves": BROWSER_MOVES, "cpus": os.cpu_count(),
           "memory_total_mb": round(int(Path("/proc/meminfo").read_text().split()[1]) / 1024), "classes": {}}
    with sync_playwright() as pw:
        browser = h.launch_chromium(pw)
        try:
            for n in sizes:
                out["classes"][str(n)] = _one_class(n, launch, hc, h, browser)
        finally:
            browser.close()
    return out


if __name__ == "__main__":
    print(json.dumps(run(quick="--quick" in sys.argv), indent=2, ensure_ascii=False))
