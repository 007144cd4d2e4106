"""Start the course hub on this machine: a demonstration, and the hub the tests and the benchmark drive.

    python deploy/jupyterhub/launch.py                 # as root, from the repository's top folder
    python deploy/jupyterhub/launch.py --students 5 --port 8000 --state /tmp/aerophoto-hub-demo

installs what is missing (``pip install -r deploy/jupyterhub/requirements.txt`` into the running Python,
``npm ci`` for the proxy in ``deploy/jupyterhub/``), makes a roster of demo students and an instructor, starts
JupyterHub with ``jupyterhub_config.py`` on http://127.0.0.1:8000 and prints the log-ins.  Ctrl+C stops the
hub, every user's server and kernel; the homes, the exchange and the course folder stay in ``--state``
(``--fresh`` starts from an empty one).

:class:`Hub` is the same start-up for code (tests/course/test_hub.py, benchmarks/bench_hub.py): private state, free
ports, random passwords, an API token for the hub's REST API, and a stop that leaves no process behind.
This file depends on the standard library (and ``psutil``, ``requests``: both come with the book's
environment and JupyterHub) — no pytest.
"""

from __future__ import annotations

import argparse
import contextlib
import csv
import json
import os
import secrets
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
ROOT = HERE.parent.parent
CONFIG = HERE / "jupyterhub_config.py"
CHP = HERE / "node_modules" / ".bin" / "configurable-http-proxy"
T_START_S = 120

DEMO_STUDENTS = [("ivanova", "19-0401"), ("petrov", "19-0457"), ("sidorova", "19-0499"), ("kuznetsov", "20-0112"),
                 ("smirnova", "20-0123"), ("popov", "20-0134"), ("volkova", "20-0145"), ("sokolov", "20-0156")]


def free_port() -> int:
    with contextlib.closing(socket.socket(socket.AF_INET, socket.SOCK_STREAM)) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def missing() -> list[str]:
    """What the hub needs and this machine lacks (empty: ready)."""
    out = []
    if os.geteuid() != 0:
        out.append("root (the hub starts each user's server as that user's uid)")
    for tool in ("bwrap", "setpriv", "prlimit"):
        if shutil.which(tool, path="/usr/bin:/bin:/usr/sbin:/sbin") is None:
            out.append(f"{tool} (apt-get install bubblewrap util-linux)")
    try:
        import jupyterhub  # noqa: F401
        import jupyterhub_idle_culler  # noqa: F401
    except ImportError:
        out.append(f"JupyterHub (python -m pip install -r {HERE.relative_to(ROOT)}/requirements.txt)")
    if not CHP.exists():
        out.append(f"configurable-http-proxy (npm ci --prefix {HERE.relative_to(ROOT)})")
    return out


def install_missing(out=print) -> None:
    """pip install the hub's requirements / npm ci the proxy, when they are missing."""
    try:
        import jupyterhub  # noqa: F401
        import jupyterhub_idle_culler  # noqa: F401
    except ImportError:
        out(f"installing JupyterHub: pip install -r {HERE / 'requirements.txt'}")
        subprocess.run([sys.executable, "-m", "pip", "install", "-q", "-r", str(HERE / "requirements.txt")], check=True)
    if not CHP.exists():
        out(f"installing configurable-http-proxy: npm ci in {HERE}")
        subprocess.run(["npm", "ci", "--no-audit", "--no-fund"], cwd=HERE, check=True)


class HubError(RuntimeError):
    pass


def _default_sigint() -> None:
    """In the hub's process: SIGINT back to its default.  Started from a background job, a process inherits SIGINT
    ignored — and so would the hub's services, which JupyterHub stops with SIGINT (then waits 30 s)."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)


class Hub:
    """JupyterHub with the course config, as a child process group, on 127.0.0.1.

    ``students``: [(hub name, record-book number)]; ``instructors``: hub names.  ``settings`` are extra
    ``AEROPHOTO_HUB_*`` values (without the prefix), e.g. ``{"CULL_TIMEOUT": 30}``.
    """

    def __init__(self, students, instructors=("teacher",), *, state: Path | None = None, port: int | None = None,
                 settings: dict | None = None, log_path: Path | None = None):
        self.students = [(str(n), str(rb)) for n, rb in students]
        self.instructors = list(instructors)
        self._own_state = state is None
        self.state = Path(state) if state else Path(tempfile.mkdtemp(prefix="aerophoto-hub-"))
        self.port = port or free_port()
        self.api_port = free_port()
        self.proxy_api_port = free_port()
        self.student_password = secrets.token_urlsafe(12)
        self.instructor_password = secrets.token_urlsafe(32)
        self.admin_token = secrets.token_hex(32)
        self.settings = dict(settings or {})
        self.log_path = log_path or self.state / "jupyterhub.log"
        self.proc: subprocess.Popen | None = None
        self._log = None

    @property
    def url(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def env(self) -> dict:
        self.state.mkdir(parents=True, exist_ok=True)
        roster = self.state / "roster.csv"
        with open(roster, "w", newline="", encoding="utf-8") as fh:
            w = csv.writer(fh)
            w.writerow(["student_id", "record_book"])
            w.writerows(self.students)
        env = {k: v for k, v in os.environ.items() if not k.startswith(("AEROPHOTO_HUB_", "JUPYTERHUB_", "JPY_"))}
        env.update({
            "AEROPHOTO_HUB_STATE": str(self.state), "AEROPHOTO_HUB_PORT": str(self.port),
            "AEROPHOTO_HUB_API_PORT": str(self.api_port), "AEROPHOTO_HUB_PROXY_API_PORT": str(self.proxy_api_port),
            "AEROPHOTO_HUB_ROSTER": str(roster),
            "AEROPHOTO_HUB_INSTRUCTORS": ",".join(self.instructors),
            "AEROPHOTO_HUB_STUDENT_PASSWORD": self.student_password,
            "AEROPHOTO_HUB_INSTRUCTOR_PASSWORD": self.instructor_password,
            "AEROPHOTO_HUB_ADMIN_TOKEN": self.admin_token,
            "PATH": f"{Path(sys.executable).parent}:{env.get('PATH', '/usr/bin:/bin')}",
            "PYTHONUNBUFFERED": "1",
        })
        env.update({f"AEROPHOTO_HUB_{k}": str(v) for k, v in self.settings.items()})
        return env

    def start(self) -> Hub:
        need = missing()
        if need:
            raise HubError("the course hub cannot start here; missing: " + "; ".join(need))
        self.state.mkdir(parents=True, exist_ok=True)
        self.log_path.parent.mkdir(parents=True, exist_ok=True)
        self._log = open(self.log_path, "ab")
        self.t_start = time.perf_counter()
        self.proc = subprocess.Popen([sys.executable, "-m", "jupyterhub", "-f", str(CONFIG)], cwd=self.state,
                                     env=self.env(), stdout=self._log, stderr=subprocess.STDOUT,
                                     stdin=subprocess.DEVNULL, start_new_session=True, preexec_fn=_default_sigint)
        deadline = time.monotonic() + T_START_S
        last = None
        while time.monotonic() < deadline:
            if self.proc.poll() is not None:
                raise HubError(f"jupyterhub exited with {self.proc.returncode} while starting:\n{self.log_tail()}")
            try:
                if self.api("GET", "/").get("version"):
                    self.seconds_to_start = time.perf_counter() - self.t_start
                    return self
            except Exception as exc:  # not listening yet
                last = exc
            time.sleep(0.25)
        self.stop()
        raise HubError(f"the hub did not answer within {T_START_S} s ({last}):\n{self.log_tail()}")

    # the REST API ------------------------------------------------------------------------------
    def api(self, method: str, path: str, body=None, *, token: str | None = None, ok=(200, 201, 202, 204)):
        import requests

        r = requests.request(method, f"{self.url}/hub/api{path}", json=body, timeout=60,
                             headers={"Authorization": f"token {token or self.admin_token}"})
        if r.status_code not in ok:
            raise HubError(f"{method} /hub/api{path}: {r.status_code} {r.text[:300]}")
        return r.json() if r.content else {}

    def user(self, name: str) -> dict:
        return self.api("GET", f"/users/{name}")

    def server_ready(self, name: str) -> bool:
        s = self.user(name).get("servers", {}).get("")
        return bool(s and s.get("ready"))

    def wait_server(self, name: str, timeout: float = T_START_S) -> float:
        """Wait until ``name``'s server is ready; returns the seconds waited."""
        t0 = time.perf_counter()
        deadline = time.monotonic() + timeout
        while time.monotonic() < deadline:
            u = self.user(name)
            s = u.get("servers", {}).get("")
            if s and s.get("ready"):
                return time.perf_counter() - t0
            if not s and not u.get("pending"):
                raise HubError(f"{name}'s server stopped while starting:\n{self.log_tail()}")
            time.sleep(0.2)
        raise HubError(f"{name}'s server was not ready within {timeout} s:\n{self.log_tail()}")

    def uid(self, name: str) -> int:
        return json.loads((self.state / "users.json").read_text(encoding="utf-8"))[name]

    def home(self, name: str) -> Path:
        return self.state / "home" / name

    def log_text(self) -> str:
        try:
            return self.log_path.read_text(encoding="utf-8", errors="replace")
        except OSError:
            return ""

    def log_tail(self, n: int = 60) -> str:
        return "\n".join(self.log_text().splitlines()[-n:])

    # stopping ----------------------------------------------------------------------------------
    def user_processes(self) -> list:
        """Processes running as any hub user's uid (their servers and kernels)."""
        import psutil

        try:
            uids = set(json.loads((self.state / "users.json").read_text(encoding="utf-8")).values())
        except (OSError, ValueError):
            return []
        procs = []
        for p in psutil.process_iter(["uids", "status"]):
            try:
                # a zombie has ended: only its exit status waits to be collected by its parent
                if p.info["uids"] and p.info["uids"].real in uids and p.info["status"] != psutil.STATUS_ZOMBIE:
                    procs.append(p)
            except psutil.Error:
                continue
        return procs

    def stop(self, remove: bool | None = None) -> None:
        """SIGTERM the hub (it stops every server and the proxy), then make sure nothing of it is left."""
        import psutil

        p = self.proc
        if p is not None and p.poll() is None:
            p.send_signal(signal.SIGTERM)
            try:
                p.wait(timeout=60)
            except subprocess.TimeoutExpired:
                pass
        if p is not None:
            with contextlib.suppress(ProcessLookupError):
                os.killpg(p.pid, signal.SIGKILL)
            with contextlib.suppress(subprocess.TimeoutExpired):
                p.wait(timeout=20)
        left = self.user_processes()
        for q in left:  # a server the hub could not stop: never left running
            with contextlib.suppress(psutil.Error):
                q.kill()
        psutil.wait_procs(left, timeout=15)  # killed is not yet gone: wait until the kernel has ended them
        if self._log is not None:
            self._log.close()
            self._log = None
        self.proc = None
        if remove if remove is not None else self._own_state:
            shutil.rmtree(self.state, ignore_errors=True)

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.stop()


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description="Start the aerophoto course hub on this machine (a demonstration).")
    ap.add_argument("--state", type=Path, default=Path("/tmp/aerophoto-hub-demo"),
                    help="the hub's folder: homes, exchange, database (default /tmp/aerophoto-hub-demo)")
    ap.add_argument("--fresh", action="store_true", help="empty --state first")
    ap.add_argument("--port", type=int, default=8000)
    ap.add_argument("--students", type=int, default=3, help=f"demo students (1–{len(DEMO_STUDENTS)}, default 3)")
    ap.add_argument("--roster", type=Path, default=None, help="CSV student_id,record_book instead of demo students")
    ap.add_argument("--instructor", default="teacher")
    args = ap.parse_args(argv)
    if os.geteuid() != 0:
        print("the course hub runs as root (it starts each user's server as that user's uid): sudo python "
              f"{Path(sys.argv[0])}", file=sys.stderr)
        return 2
    install_missing()
    need = missing()
    if need:
        print("cannot start: missing " + "; ".join(need), file=sys.stderr)
        return 2
    if args.roster:
        with open(args.roster, newline="", encoding="utf-8-sig") as fh:
            students = [(r["student_id"], r["record_book"]) for r in csv.DictReader(fh)]
    else:
        students = DEMO_STUDENTS[: max(1, min(len(DEMO_STUDENTS), args.students))]
    if args.fresh:
        shutil.rmtree(args.state, ignore_errors=True)
    hub = Hub(students, [args.instructor], state=args.state, port=args.port)
    hub.log_path = args.state / "jupyterhub.log"
    print(f"starting the course hub (state: {args.state}, log: {hub.log_path}) …", flush=True)
    hub.start()
    print(f"\n  {hub.url}/hub/login\n")
    print(f"  instructor: {args.instructor:<12} password {hub.instructor_password}")
    print(f"  students:   {', '.join(n for n, _ in students)}  — password {hub.student_password}")
    print("\n  The instructor's Lab has the Nbgrader menu (formgrader, course list) and a terminal for:")
    print("    aerophoto-course generate --assignment 00_start_here && nbgrader release_assignment 00_start_here")
    print("    nbgrader collect 00_start_here && aerophoto-course autograde --jobs 2 && aerophoto-course gradebook")
    print("    aerophoto-course feedback && nbgrader release_feedback 00_start_here")
    print("  Students: Nbgrader → Assignment List → Fetch, answer, Submit; later Fetch Feedback.")
    print("\n  Ctrl+C stops the hub and every server.", flush=True)
    stop = []
    signal.signal(signal.SIGTERM, lambda *a: stop.append(1))
    try:
        while not stop and hub.proc is not None and hub.proc.poll() is None:
            time.sleep(0.5)
    except KeyboardInterrupt:
        pass
    print("stopping …", flush=True)
    hub.stop(remove=False)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
