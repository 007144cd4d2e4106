"""The sandbox student code runs in (bubblewrap): what it can see, reach and use — proved by running code in it.

CI runs as root and installs bubblewrap (.ci/run): these tests never skip there.
"""

from __future__ import annotations

import json
import os
import signal
import socket
import subprocess
import sys
import time
import uuid
from pathlib import Path

import pytest

from aerophoto.course import sandbox
from aerophoto.course.bwrap import NOBODY
from aerophoto.course.limits import Limits
from aerophoto.course.sandbox import Box, kernel_exit_reason
from conftest import ROOT

PROBE = r"""
import json, os, socket, sys, subprocess
out = {"uid": os.getuid(), "gid": os.getgid(), "cwd": os.getcwd(), "files": sorted(os.listdir("."))}
out["capeff"] = [l.split()[1] for l in open("/proc/self/status") if l.startswith("CapEff")][0]
out["pids"] = len([p for p in os.listdir("/proc") if p.isdigit()])
out["repo_visible"] = os.path.exists(sys.argv[1])
out["secret_visible"] = os.path.exists(sys.argv[2])
out["src_visible"] = os.path.isdir(sys.argv[3])
try:
    socket.create_connection(("127.0.0.1", int(sys.argv[4])), timeout=2).close()
    out["host_port"] = "reached"
except OSError as exc:
    out["host_port"] = type(exc).__name__
try:
    socket.create_connection(("8.8.8.8", 53), timeout=2).close()
    out["internet"] = "reached"
except OSError as exc:
    out["internet"] = type(exc).__name__
for path in ("/usr/evil", "/etc/evil", sys.prefix + "/evil", sys.argv[3] + "/evil"):
    try:
        open(path, "w").write("x")
        out.setdefault("wrote", []).append(path)
    except OSError:
        pass
try:
    open("big", "wb").write(b"x" * (3 * 1024 * 1024))
    out["big_file"] = "written"
except OSError as exc:
    out["big_file"] = exc.errno
try:
    bytearray(2 * 1024**3)
    out["memory"] = "allocated"
except MemoryError:
    out["memory"] = "MemoryError"
n = 0
try:
    kids = []
    for _ in range(200):
        pid = os.fork()
        if pid == 0:
            import time; time.sleep(30); os._exit(0)
        kids.append(pid)
        n += 1
except OSError:
    pass
out["forks"] = n
for pid in kids:
    os.kill(pid, 9)
    os.waitpid(pid, 0)
subprocess.Popen([sys.executable, "-c", "import time; time.sleep(60)", sys.argv[5]], start_new_session=True)
print(json.dumps(out))
"""


@pytest.fixture(scope="module")
def probe_run(tmp_path_factory):
    """Run the probe in a sandbox: (its report, the marker of the detached process it left behind)."""
    assert sandbox.available(), sandbox._probe()
    course = tmp_path_factory.mktemp("course")
    (course / "gradebook.db").write_text("secret")
    srv = socket.socket()
    srv.bind(("127.0.0.1", 0))
    srv.listen()
    port = srv.getsockname()[1]
    marker = f"aerophoto-sandbox-test-{uuid.uuid4().hex}"
    box = Box.create(None, Limits(memory_mb=1024, fsize_mb=2, nproc=40))
    try:
        src = str(Path(sandbox.__file__).resolve().parents[2])
        cmd = box.wrap([sys.executable, "-c", PROBE, str(ROOT / "README.md"), str(course / "gradebook.db"), src,
                        str(port), marker], env={})
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=120, cwd=box.root)
    finally:
        box.remove()
        srv.close()
    assert proc.returncode == 0, proc.stderr
    return json.loads(proc.stdout.strip().splitlines()[-1]), marker, cmd


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


def test_the_sandbox_runs_as_nobody_without_capabilities(probe_run):
    out, _, _ = probe_run
    if os.geteuid() == 0:
        assert (out["uid"], out["gid"]) == (NOBODY, NOBODY)
    assert int(out["capeff"], 16) == 0


def test_the_sandbox_sees_no_repository_and_no_course(probe_run):
    out, _, cmd = probe_run
    assert out["repo_visible"] is False and out["secret_visible"] is False
    assert out["src_visible"] is True  # the package's own source, read-only
    assert out["cwd"] == "/sbx"
    binds = {cmd[i + 2] for i, a in enumerate(cmd) if a in ("--ro-bind", "--bind")}
    assert str(ROOT) not in binds and str(ROOT / "notebooks") not in binds
    assert str(Path(sys.prefix).resolve()) in binds


def test_the_sandbox_has_no_network(probe_run):
    out, _, _ = probe_run
    assert out["host_port"] != "reached" and out["internet"] != "reached"


def test_the_sandbox_cannot_write_outside_its_folder(probe_run):
    out, _, _ = probe_run
    assert "wrote" not in out


def test_the_sandbox_limits_file_size_memory_and_processes(probe_run):
    out, _, _ = probe_run
    assert out["big_file"] == 27  # EFBIG: RLIMIT_FSIZE (2 MB)
    assert out["memory"] == "MemoryError"  # RLIMIT_AS (1 GB)
    if os.geteuid() == 0:  # RLIMIT_NPROC binds a non-root uid
        assert out["forks"] < 40
    assert out["pids"] < 10  # its own process namespace


def test_nothing_the_sandbox_started_outlives_it(probe_run):
    _, marker, _ = probe_run
    deadline = time.monotonic() + 5
    while _procs_with(marker) and time.monotonic() < deadline:
        time.sleep(0.1)
    assert _procs_with(marker) == []


def test_a_box_copies_only_the_submissions_folder(tmp_path):
    (tmp_path / "sub").mkdir()
    (tmp_path / "sub" / "a.ipynb").write_text("{}")
    (tmp_path / "sub" / "data").mkdir()
    (tmp_path / "sub" / "data" / "x.csv").write_text("1")
    (tmp_path / "sub" / ".hidden").write_text("no")
    (tmp_path / "sub" / "link").symlink_to(tmp_path / "secret")
    (tmp_path / "secret").write_text("secret")
    box = Box.create(tmp_path / "sub", Limits())
    try:
        assert sorted(box.files) == ["a.ipynb", "data/x.csv"]
        assert all(box.root in p.parents for p in box.files.values())
    finally:
        box.remove()
    assert not box.root.exists()


def test_kernel_exit_reasons():
    lim = Limits(cpu_s=30, fsize_mb=8)
    assert "30 s of CPU time" in kernel_exit_reason(128 + signal.SIGXCPU, lim)
    assert "killed" in kernel_exit_reason(128 + signal.SIGKILL, lim)
    assert "segmentation fault" in kernel_exit_reason(128 + signal.SIGSEGV, lim)
    assert kernel_exit_reason(3, lim) == "the kernel exited (status 3)"
    assert "stopped answering" in kernel_exit_reason(None, lim)


def test_without_bubblewrap_the_grader_refuses(monkeypatch):
    monkeypatch.setattr(sandbox, "_bwrap", lambda: None)
    sandbox._probe.cache_clear()
    try:
        assert not sandbox.available()
        with pytest.raises(sandbox.SandboxUnavailable, match="bubblewrap"):
            sandbox.require()
    finally:
        monkeypatch.undo()
        sandbox._probe.cache_clear()
    assert sandbox.available()


def test_check_refuses_without_a_sandbox(monkeypatch, capsys, tmp_path):
    from aerophoto import course

    monkeypatch.setattr(sandbox, "_bwrap", lambda: None)
    sandbox._probe.cache_clear()
    try:
        nb = tmp_path / "x.ipynb"
        nb.write_text("{}")
        assert course.main(["check", str(nb)]) == 2
        assert "no sandbox for student code" in capsys.readouterr().out
    finally:
        monkeypatch.undo()
        sandbox._probe.cache_clear()


def test_ipc_folder_is_sealed_after_start(tmp_path):
    box = Box.create(None, Limits())
    try:
        box.seal()
        assert (os.stat(box.ipc).st_mode & 0o777) == 0o555
    finally:
        box.remove()


def test_a_timed_out_cells_interrupt_never_lands_in_the_next_cell(tmp_path):
    """A cell busy in C code past its limit: the grader waits until the kernel has ended it and answered the
    interrupt before it sends the next cell (there a check cell that records nothing would score 0)."""
    import nbformat

    from aerophoto.course.sandbox_execute import SandboxExecute

    nb = nbformat.v4.new_notebook(cells=[
        # the interpreter lock held for 6 s: the kernel's control thread turns the interrupt into SIGINT after
        nbformat.v4.new_code_cell("import ctypes\nctypes.PyDLL(None).sleep(6)\n"),
        nbformat.v4.new_code_cell("import time\ntime.sleep(1.5)\nx = 41 + 1\n"),
        nbformat.v4.new_code_cell("print('x =', x)\n")])
    ex = SandboxExecute(timeout=3, iopub_timeout=1, interrupt_on_timeout=True, allow_errors=True,
                        interrupt_grace_s=20, limits=Limits(),
                        error_on_timeout={"ename": "CellTimeoutError", "evalue": "over 3 s", "traceback": []})
    ex.preprocess(nb, {"metadata": {"path": str(tmp_path)}})
    errors = [[o.get("ename") for o in c.outputs if o.get("output_type") == "error"] for c in nb.cells]
    assert "CellTimeoutError" in errors[0] and errors[1:] == [[], []], errors
    assert nb.cells[2].outputs[0]["text"] == "x = 42\n"
    assert [e.kind for e in ex.events] == ["timeout"]
    # a cell that ignores the interrupt: its kernel is ended after the grace; the next cell runs in a new one
    nb = nbformat.v4.new_notebook(cells=[
        nbformat.v4.new_code_cell("y = 7\n"),
        nbformat.v4.new_code_cell("import signal\nsignal.signal(signal.SIGINT, signal.SIG_IGN)\nwhile True:\n"
                                  "    pass\n"),
        nbformat.v4.new_code_cell("print('y =', y)\n")])
    ex.interrupt_grace_s = 2
    ex.preprocess(nb, {"metadata": {"path": str(tmp_path)}})
    assert [e.kind for e in ex.events] == ["kernel_died"]
    assert "did not stop when interrupted" in ex.events[0].message
    assert nb.cells[2].outputs[0]["text"] == "y = 7\n"


def test_one_recipe_for_the_grader_and_the_hub():
    from aerophoto.course.bwrap import BwrapOptions, bwrap_argv, is_root
    from aerophoto.course.limits import GRADING, HUB_INSTRUCTOR, HUB_STUDENT

    # the limits: one record, the hub's and the grader's differing only where they should
    assert GRADING == Limits() and HUB_INSTRUCTOR.memory_mb > HUB_STUDENT.memory_mb >= GRADING.memory_mb
    assert HUB_STUDENT.prlimit_args() == ["--as=3221225472", "--nofile=4096", "--nproc=512", "--core=0", "--"]
    assert "--cpu=900:905" in GRADING.prlimit_args() and "--fsize=67108864" in GRADING.prlimit_args()
    hub = BwrapOptions(limits=HUB_STUDENT, uid=30001, gid=30002, hostname="aerophoto", network=True,
                       ro_binds=(("/srv/book/notebooks", "/srv/book/notebooks"),),
                       binds=(("/srv/home/a", "/home/a"), ("/srv/x", "/srv/nbgrader/exchange")), chdir="/home/a")
    argv = bwrap_argv(hub, ["jupyterhub-singleuser"])
    assert argv[-1] == "jupyterhub-singleuser" and "--clearenv" not in argv
    assert argv[argv.index("--chdir") + 1] == "/home/a"
    # read-only before read-write, each under fresh parents; /dev/shm and /tmp sized by the limits
    assert argv.index("/srv/book/notebooks") < argv.index("/srv/home/a") < argv.index("/srv/x")
    assert argv[argv.index("/home/a") - 2] == "--bind" and "/home" in argv
    assert argv[argv.index("/dev/shm") - 3: argv.index("/dev/shm")] == ["--size", str(64 * 1024 * 1024), "--tmpfs"]
    assert "--as=3221225472" in argv and "--cpu=900:905" not in argv
    if is_root():
        assert "--unshare-net" not in argv and "--unshare-pid" in argv
        assert "--reuid=30001" in argv and "--regid=30002" in argv
    grading = bwrap_argv(BwrapOptions(env={"HOME": "/sbx"}, work="/sbx", chdir="/sbx"), ["python"])
    assert grading[grading.index("--clearenv") + 1: grading.index("--clearenv") + 4] == ["--setenv", "HOME", "/sbx"]
    assert "/dev/shm" not in grading and "--cpu=900:905" in grading
    if is_root():
        assert "--unshare-net" in grading and f"--reuid={NOBODY}" in grading
