"""The sandbox every execution of student code runs in: bubblewrap around the kernel.

A submission's kernel runs inside ``bwrap`` (Debian package ``bubblewrap``):

* **its own view of the files** — ``/usr``, ``/lib*``, ``/bin``, ``/etc`` and the Python that runs the book
  (``sys.base_prefix``, ``sys.prefix``, the package's own source folder), all read-only; a fresh ``/tmp`` and
  a working folder ``/sbx`` (size-limited tmpfs) holding a throw-away copy of the one submission's files.
  The course folder, the gradebook, other submissions, the notebooks and the repository are not there at all.
* **no network** (a network namespace with no interface but its own loopback), its own process, IPC and
  host-name namespaces; ``--die-with-parent`` and the process namespace: every process the student started
  is gone when the kernel ends;
* **nobody's rights**: run as root (CI, a hub's grading account) the kernel drops to uid/gid 65534 with no
  capabilities (``setpriv --no-new-privs``); run by an ordinary user, bubblewrap maps the user into a user
  namespace (``--unshare-all``) instead;
* **resource limits** (:class:`Limits`, set by ``prlimit``): address space, CPU seconds, file size, open files,
  processes (enforced for a non-root uid), the size of ``/sbx`` and ``/tmp``; the instructor's side caps the
  size of one kernel message and the outputs kept per notebook, and the per-cell timeout bounds wall time.

The kernel talks to the instructor's nbclient/nbgrader over jupyter_client's **ipc transport**: unix
sockets in a folder shared with the sandbox (sealed read-only once the kernel has bound them), since the
sandbox has no network to the host.  :class:`SandboxKernelManager` is the jupyter_client kernel manager
that does all this; the course sets it as nbgrader's ``ExecutePreprocessor.kernel_manager_class``.
"""

from __future__ import annotations

import functools
import os
import shutil
import signal
import subprocess
import sys
import tempfile
from dataclasses import asdict, dataclass, replace
from pathlib import Path

__all__ = ["Limits", "SandboxUnavailable", "available", "require", "SandboxKernelManager", "SandboxKernelClient",
           "kernel_exit_reason", "NOBODY", "MAX_JOBS", "sandbox_uid"]

NOBODY = 65534
MAX_JOBS = 14
"""Parallel grading jobs at most (``autograde --jobs``): one sandbox uid each (see :func:`sandbox_uid`)."""
_MB = 1024 * 1024


@dataclass(frozen=True)
class Limits:
    """What one sandboxed kernel may use.

    memory_mb : address space of each process (RLIMIT_AS) — a memory bomb gets a MemoryError
    cpu_s : CPU seconds of each process (RLIMIT_CPU; SIGXCPU ends the kernel, reported as such)
    fsize_mb : the largest file a process may write (RLIMIT_FSIZE)
    nofile : open files per process (RLIMIT_NOFILE)
    nproc : processes and threads of the sandbox's user (RLIMIT_NPROC; a fork bomb stops there)
    tmpfs_mb : size of the working folder ``/sbx`` and of ``/tmp`` (each)
    output_mb : outputs kept per notebook on the instructor's side (more is dropped, flagged)
    message_mb : the largest single message accepted from the kernel (a larger one ends the connection)
    record_kb : the largest answer record a check cell may emit (a larger one is dropped: the task scores 0,
        flagged); the records of a notebook together are kept up to ``output_mb`` beside the other outputs
    notebook_s : wall time the notebook's cells may run in all (beside the per-cell timeout; kernel starts and
        the grader's replays not counted): the cells after it are not run (flagged), and no cell runs past it
    """

    memory_mb: int = 3072
    cpu_s: int = 900
    fsize_mb: int = 64
    nofile: int = 256
    nproc: int = 128
    tmpfs_mb: int = 256
    output_mb: float = 4.0
    message_mb: int = 32
    record_kb: int = 256
    notebook_s: int = 1200

    def replace(self, **kw) -> Limits:
        return replace(self, **kw)

    def as_dict(self) -> dict:
        return asdict(self)


def sandbox_uid(slot: int = 0) -> int:
    """The uid a root-run sandbox drops to, for grading job ``slot`` (0 … MAX_JOBS − 1).

    Slot 0 is nobody (65534).  Parallel jobs need a uid each: RLIMIT_NPROC counts every process of a uid, so
    with one shared uid a fork bomb in one submission would stop the other jobs' kernels from starting, and
    grades would depend on what ran beside them.  Slots 1 … 13 take 65533 down to 65521 — in the range Debian
    policy reserves and never allocates (65000–65533) and above systemd's dynamic users (61184–65519), so no
    account owns them.  (Run by an ordinary user, each sandbox is a user namespace of its own and its process
    count is its own; the slot does not matter.)
    """
    if not isinstance(slot, int) or isinstance(slot, bool) or not 0 <= slot < MAX_JOBS:
        raise ValueError(f"slot = {slot!r} is not valid; expected an integer in 0 … {MAX_JOBS - 1}")
    return NOBODY - slot


class SandboxUnavailable(RuntimeError):
    """bubblewrap is missing or cannot create a sandbox on this machine."""


def _is_root() -> bool:
    return os.geteuid() == 0


def _bwrap() -> str | None:
    return shutil.which("bwrap") or (shutil.which("bwrap", path="/usr/bin:/bin"))


HOW_TO_INSTALL = ("install bubblewrap (Debian/Ubuntu: sudo apt-get install bubblewrap; Fedora: dnf install "
                  "bubblewrap); as an ordinary user it needs unprivileged user namespaces "
                  "(sysctl kernel.unprivileged_userns_clone=1 on older Debian kernels)")


@functools.lru_cache(maxsize=None)
def _probe() -> str | None:
    """None when a sandbox can be made here, else why not (cached: bwrap is run once per process)."""
    exe = _bwrap()
    if exe is None:
        return "bubblewrap (bwrap) is not installed"
    for tool in ("prlimit",) + (("setpriv",) if _is_root() else ()):
        if _tool(tool) is None:
            return f"{tool} (util-linux) is not installed"
    box = Box.create(None, Limits())
    try:
        cmd = box.wrap([sys.executable, "-c", "import os; print(os.getuid())"], env={})
        proc = subprocess.run(cmd, capture_output=True, text=True, timeout=60, cwd=box.root)
    except (OSError, subprocess.TimeoutExpired) as exc:
        return f"bwrap could not start ({exc})"
    finally:
        box.remove()
    if proc.returncode != 0:
        return f"bwrap could not start a sandbox: {proc.stderr.strip()[:300] or proc.returncode}"
    if _is_root() and proc.stdout.strip() != str(NOBODY):
        return f"the sandbox did not drop root's rights (uid {proc.stdout.strip()!r})"
    return None


def available() -> bool:
    """True when student code can be sandboxed on this machine."""
    return _probe() is None


def require() -> None:
    """Raise :class:`SandboxUnavailable` with what to do, unless a sandbox can be made."""
    why = _probe()
    if why is not None:
        raise SandboxUnavailable(
            f"no sandbox for student code: {why}. The grader never runs a submission with your own rights; "
            f"{HOW_TO_INSTALL}. (A developer may pass --unsafe-no-sandbox for notebooks they trust.)")


def _tool(name: str) -> str | None:
    return shutil.which(name, path="/usr/bin:/bin:/usr/sbin:/sbin")


# --------------------------------------------------------------------------------------------------
# the file system the kernel sees


def _package_parent() -> str | None:
    """The folder holding the running ``aerophoto`` package, unless it is the Python's own site-packages."""
    import aerophoto

    here = Path(aerophoto.__file__).resolve().parent.parent
    return None if here.name in ("site-packages", "dist-packages") else str(here)


def _python_roots() -> list[Path]:
    """The folders the book's Python needs: the interpreter's prefix, the venv, the package's source."""
    import aerophoto

    here = Path(aerophoto.__file__).resolve().parent.parent  # src/ of an editable install, or site-packages
    roots = []
    for p in (Path(sys.base_prefix), Path(sys.prefix), here):
        p = p.resolve()
        if not any(p == r or r in p.parents for r in roots):
            roots = [r for r in roots if p not in r.parents] + [p]
    return roots


_SYSTEM = ("/usr", "/bin", "/sbin", "/lib", "/lib32", "/lib64", "/libx32", "/etc")


def _font_cache() -> Path | None:
    """matplotlib's font list of this machine (copied in, so a kernel does not rebuild it: ~1 s)."""
    try:
        import matplotlib

        caches = sorted(Path(matplotlib.get_cachedir()).glob("fontlist-v*.json"))
    except Exception:
        return None
    return caches[-1] if caches else None


@dataclass
class Box:
    """The host side of one sandbox: a private temporary folder with the ipc sockets and the files' copy."""

    root: Path
    limits: Limits
    files: dict  # name inside /sbx → host path of its copy

    @classmethod
    def create(cls, src_dir, limits: Limits, *, max_files: int = 200, max_bytes: int = 64 * _MB) -> Box:
        root = Path(tempfile.mkdtemp(prefix="aerophoto-sandbox-"))
        os.chmod(root, 0o711)
        (root / "ipc").mkdir()
        os.chmod(root / "ipc", 0o777)
        copies = root / "files"
        copies.mkdir()
        files: dict = {}
        total = 0
        if src_dir is not None and Path(src_dir).is_dir():
            for p in sorted(Path(src_dir).rglob("*")):
                rel = p.relative_to(src_dir)
                if (p.is_symlink() or not p.is_file() or any(part.startswith(".") for part in rel.parts)
                        or len(files) >= max_files):
                    continue
                size = p.stat().st_size
                if total + size > max_bytes:
                    continue
                total += size
                dest = copies / rel
                dest.parent.mkdir(parents=True, exist_ok=True)
                shutil.copyfile(p, dest)
                os.chmod(dest, 0o644)
                files[rel.as_posix()] = dest
        for d in [copies, *[p for p in copies.rglob("*") if p.is_dir()]]:
            os.chmod(d, 0o755)
        return cls(root, limits, files)

    @property
    def ipc(self) -> Path:
        return self.root / "ipc"

    def seal(self) -> None:
        """After the kernel has bound its sockets: nothing more can be written into the shared folder."""
        try:
            os.chmod(self.ipc, 0o555)
        except OSError:
            pass

    def remove(self) -> None:
        try:
            os.chmod(self.ipc, 0o755)
        except OSError:
            pass
        shutil.rmtree(self.root, ignore_errors=True)

    def kernel_env(self, extra: dict) -> dict:
        env = {
            "HOME": "/sbx",
            "PATH": f"{Path(sys.executable).parent}:/usr/bin:/bin",
            "LANG": "C.UTF-8",
            "TMPDIR": "/tmp",
            "MPLCONFIGDIR": "/tmp/mpl",
            "PYTHONDONTWRITEBYTECODE": "1",
            "PYDEVD_DISABLE_FILE_VALIDATION": "1",
            "OPENBLAS_NUM_THREADS": "1",
            "OMP_NUM_THREADS": "1",
            "MKL_NUM_THREADS": "1",
            "AEROPHOTO_HOME": "/sbx/.aerophoto",
        }
        src = _package_parent()
        if src is not None:  # the aerophoto this grader runs (a checkout on PYTHONPATH too; bound read-only)
            env["PYTHONPATH"] = src
        env.update({k: str(v) for k, v in extra.items() if v is not None})
        return env

    def limit_args(self) -> list[str]:
        lim = self.limits
        return [_tool("prlimit") or "prlimit", f"--as={lim.memory_mb * _MB}", f"--cpu={lim.cpu_s}:{lim.cpu_s + 5}",
                f"--fsize={lim.fsize_mb * _MB}", f"--nofile={lim.nofile}", f"--nproc={lim.nproc}", "--core=0", "--"]

    def wrap(self, cmd: list[str], *, env: dict, uid: int = NOBODY) -> list[str]:
        """``cmd`` (the kernel's command line) inside bubblewrap, with the limits, as ``uid`` (run as root:
        nobody by default; see :func:`sandbox_uid`)."""
        lim = self.limits
        args = [_bwrap() or "bwrap"]
        if _is_root():
            args += ["--unshare-ipc", "--unshare-pid", "--unshare-net", "--unshare-uts"]
        else:  # an ordinary user: a user namespace too (the same uid inside)
            args += ["--unshare-all"]
        args += ["--die-with-parent", "--new-session", "--hostname", "sandbox"]
        made: set[str] = set()

        def ancestors(path: Path):
            for parent in reversed(path.parents):
                s = str(parent)
                if s == "/" or s in made or any(s == m or s.startswith(m + "/") for m in _SYSTEM):
                    continue
                made.add(s)
                args.extend(["--perms", "0755", "--dir", s])

        for top in _SYSTEM:
            p = Path(top)
            if p.is_symlink():
                args += ["--symlink", os.readlink(p), top]
            elif p.is_dir():
                args += ["--ro-bind", top, top]
        # the fresh /tmp first: a Python environment that lives under /tmp (a clone checked out there) is bound
        # on top of it below, not hidden by it
        size = str(lim.tmpfs_mb * _MB)
        args += ["--proc", "/proc", "--dev", "/dev",
                 "--perms", "1777", "--size", size, "--tmpfs", "/tmp",
                 "--perms", "1777", "--dir", "/tmp/mpl",
                 "--perms", "1777", "--size", size, "--tmpfs", "/sbx"]
        made.update({"/tmp", "/tmp/mpl", "/sbx"})
        for root in _python_roots():
            if any(str(root) == m or str(root).startswith(m + "/") for m in _SYSTEM):
                continue
            ancestors(root)
            args += ["--ro-bind", str(root), str(root)]
            made.add(str(root))
        fonts = _font_cache()
        if fonts is not None:
            args += ["--ro-bind", str(fonts), f"/tmp/mpl/{fonts.name}"]
        for name, host in sorted(self.files.items()):
            args += ["--ro-bind", str(host), f"/sbx/{name}"]
        ancestors(self.ipc / "x")
        args += ["--bind", str(self.ipc), str(self.ipc), "--chdir", "/sbx", "--clearenv"]
        for k, v in sorted(self.kernel_env(env).items()):
            args += ["--setenv", k, v]
        args += ["--", *self.limit_args()]
        if _is_root():
            args += [_tool("setpriv") or "setpriv", f"--reuid={int(uid)}", f"--regid={int(uid)}", "--clear-groups",
                     "--no-new-privs"]
        return args + list(cmd)


def kernel_exit_reason(status: int | None, limits: Limits | None = None) -> str:
    """Why a sandboxed kernel ended, from bwrap's exit status (128 + signal when killed by a signal)."""
    if status is None:
        return "the kernel stopped answering"
    lim = limits or Limits()
    sig = status - 128 if status > 128 else (-status if status < 0 else None)
    if sig == signal.SIGXCPU:
        return f"the kernel used its {lim.cpu_s} s of CPU time (limit) and was stopped"
    if sig == signal.SIGKILL:
        return "the kernel was killed (out of memory, or the grader's time limit)"
    if sig == signal.SIGSEGV:
        return "the kernel crashed (segmentation fault)"
    if sig == signal.SIGXFSZ:
        return f"the kernel wrote a file larger than {lim.fsize_mb} MB (limit)"
    if sig is not None and sig > 0:
        try:
            name = signal.Signals(sig).name
        except ValueError:
            name = f"signal {sig}"
        return f"the kernel was ended by {name}"
    return f"the kernel exited (status {status})"


# --------------------------------------------------------------------------------------------------
# jupyter_client: the kernel manager and client


def _kernel_classes():
    """Built lazily: jupyter_client is imported only by the commands that run kernels."""
    import zmq
    from jupyter_client.asynchronous import AsyncKernelClient
    from jupyter_client.manager import AsyncKernelManager
    from traitlets import Any, Bool, Dict, Integer, Unicode

    class SandboxKernelClient(AsyncKernelClient):
        """A kernel client that refuses messages larger than ``max_message_bytes`` (zmq MAXMSGSIZE)."""

        max_message_bytes = Integer(32 * _MB).tag(config=True)

        def _create_connected_socket(self, channel, identity=None):
            from jupyter_client.connect import channel_socket_types

            url = self._make_url(channel)
            sock = self.context.socket(channel_socket_types[channel])
            sock.linger = 1000
            sock.setsockopt(zmq.MAXMSGSIZE, int(self.max_message_bytes))
            if identity:
                sock.identity = identity
            if self.curve_publickey is not None:
                sock.curve_secretkey = self.curve_secretkey
                sock.curve_publickey = self.curve_publickey
                sock.curve_serverkey = self.curve_publickey
            sock.connect(url)
            return sock

    class SandboxKernelManager(AsyncKernelManager):
        """The book's Python kernel inside bubblewrap (see the module notes), over the ipc transport.

        Configurable (nbgrader config or keyword arguments): ``record_book`` (the student's number, the
        kernel's ``AEROPHOTO_RECORD_BOOK``), ``limits`` (:class:`Limits`), ``grading`` (sets
        ``AEROPHOTO_GRADING=1``: check cells emit the submitted values), ``uid`` (run as root: the uid the
        kernel drops to, :func:`sandbox_uid`), ``unsafe_no_sandbox`` (a developer's escape hatch: no
        bubblewrap, the caller's rights — never the default).
        """

        record_book = Unicode(None, allow_none=True).tag(config=True)
        uid = Integer(NOBODY).tag(config=True)
        grading = Bool(True).tag(config=True)
        unsafe_no_sandbox = Bool(False).tag(config=True)
        limits = Any(None).tag(config=True)
        extra_env = Dict().tag(config=True)

        def __init__(self, **kw):
            kw["kernel_name"] = "python3"  # never a kernel the notebook names: the book's own Python
            super().__init__(**kw)
            self.client_class = "aerophoto.course.sandbox.SandboxKernelClient"
            self.box = None
            self.last_exit_status = None

        @property
        def the_limits(self) -> Limits:
            lim = self.limits
            if isinstance(lim, dict):
                return Limits(**lim)
            return lim if isinstance(lim, Limits) else Limits()

        def _grading_env(self) -> dict:
            env = {"AEROPHOTO_RECORD_BOOK": self.record_book or None,
                   "AEROPHOTO_GRADING": "1" if self.grading else None}
            env.update(self.extra_env)
            return env

        async def _async_pre_start_kernel(self, **kw):
            if not self.unsafe_no_sandbox:
                require()
            src = kw.pop("cwd", None)
            kw.pop("env", None)
            if self.box is not None:
                self.box.remove()
            self.box = Box.create(src, self.the_limits)
            if self.unsafe_no_sandbox:
                work = self.box.root / "work"
                shutil.copytree(self.box.root / "files", work)
                env = {k: v for k, v in os.environ.items() if not k.startswith("AEROPHOTO_")}
                env.update(self.box.kernel_env(self._grading_env()))
                env.update({"HOME": str(work), "AEROPHOTO_HOME": str(work / ".aerophoto"), "TMPDIR": str(work),
                            "MPLCONFIGDIR": os.environ.get("MPLCONFIGDIR", "") or str(Path.home() / ".config"
                                                                                         / "matplotlib")})
                kw["cwd"], kw["env"] = str(work), env
            else:
                self.transport = "ipc"
                self.ip = str(self.box.ipc / "k")
                self.connection_file = str(self.box.ipc / "kernel.json")
                kw["cwd"] = str(self.box.root)
                kw["env"] = {"PATH": "/usr/bin:/bin", "LANG": "C.UTF-8"}
            # the kernel's own stdout/stderr (start-up chatter, C-level writes): a log in the box, whose size
            # RLIMIT_FSIZE bounds; never the instructor's terminal
            self._log_fh = open(self.box.root / "kernel.log", "ab")
            kw["stdout"] = kw["stderr"] = self._log_fh
            return await super()._async_pre_start_kernel(**kw)

        def write_connection_file(self, **kw):
            super().write_connection_file(**kw)
            if not self.unsafe_no_sandbox and os.path.exists(self.connection_file):
                os.chmod(self.connection_file, 0o644)  # readable by the sandbox's nobody; its folder is private

        def format_kernel_cmd(self, extra_arguments=None):
            cmd = super().format_kernel_cmd(extra_arguments)
            if self.unsafe_no_sandbox:
                return (self.box.limit_args() if _tool("prlimit") else []) + cmd
            return self.box.wrap(cmd, env=self._grading_env(), uid=self.uid)

        def client(self, **kw):
            kc = super().client(**kw)
            kc.max_message_bytes = int(self.the_limits.message_mb * _MB)
            return kc

        def seal(self) -> None:
            if self.box is not None and not self.unsafe_no_sandbox:
                self.box.seal()

        async def _async_interrupt_kernel(self):
            # the sandbox is its own session: a signal to the launcher's process group does not reach the
            # kernel, so interrupt by message (ipykernel sends itself SIGINT)
            if not self.has_kernel:
                raise RuntimeError("Cannot interrupt kernel. No kernel is running!")
            msg = self.session.msg("interrupt_request", content={})
            self._connect_control_socket()
            self.session.send(self._control_socket, msg)

        interrupt_kernel = _async_interrupt_kernel

        def exit_status(self) -> int | None:
            proc = getattr(self.provisioner, "process", None) if self.provisioner is not None else None
            if proc is not None:
                code = proc.poll()
                if code is not None:
                    self.last_exit_status = code
            return self.last_exit_status

        async def _async_cleanup_resources(self, restart: bool = False):
            self.exit_status()
            try:
                await super()._async_cleanup_resources(restart)
            finally:
                fh = getattr(self, "_log_fh", None)
                if fh is not None:
                    fh.close()
                    self._log_fh = None
                if self.box is not None:
                    self.box.remove()
                    self.box = None

        cleanup_resources = _async_cleanup_resources

    return SandboxKernelClient, SandboxKernelManager


def __getattr__(name: str):
    if name in ("SandboxKernelClient", "SandboxKernelManager"):
        client, manager = _kernel_classes()
        globals().update(SandboxKernelClient=client, SandboxKernelManager=manager)
        return globals()[name]
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
