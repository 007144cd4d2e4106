"""The sandbox every execution of student code runs in: bubblewrap around the kernel (the host's side).

A submission's kernel runs inside ``bwrap`` (Debian package ``bubblewrap``), by the recipe of :mod:`.bwrap`
(the one the course hub's servers use too):

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
* **resource limits** (:class:`~.limits.Limits`, set by ``prlimit``): address space, CPU seconds, file size,
  open files, processes (enforced for a non-root uid), the size of ``/sbx`` and ``/tmp``; the instructor's
  side caps the size of one kernel message and the outputs kept per notebook, and the per-cell timeout
  bounds wall time.

Here: whether a sandbox can be made (:func:`available`, :func:`require`), the host side of one sandbox
(:class:`Box`: its private folder, the files' copy, the kernel's environment and command line) and why a
kernel ended (:func:`kernel_exit_reason`).  The kernel talks to the instructor's nbclient/nbgrader over
jupyter_client's **ipc transport**: unix sockets in a folder shared with the sandbox (sealed read-only once
the kernel has bound them), since the sandbox has no network to the host.  The jupyter_client kernel manager
is :class:`~.sandbox_kernel.SandboxKernelManager`; nbgrader's preprocessor that uses it is
:class:`~.sandbox_execute.SandboxExecute`.
"""

from __future__ import annotations

import functools
import os
import shutil
import signal
import subprocess
import sys
import tempfile
from dataclasses import dataclass
from pathlib import Path

from .bwrap import NOBODY, BwrapOptions, bwrap_argv, bwrap_exe, is_root, prlimit_argv, tool
from .limits import GRADING, MB, Limits

__all__ = ["SandboxUnavailable", "available", "require", "Box", "kernel_exit_reason", "HOW_TO_INSTALL"]


class SandboxUnavailable(RuntimeError):
    """bubblewrap is missing or cannot create a sandbox on this machine."""


_is_root = is_root
_bwrap = bwrap_exe  # looked up by name at call time (a test stands in a missing bubblewrap)
_tool = tool


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
    box = Box.create(None, GRADING)
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


# --------------------------------------------------------------------------------------------------
# the host side of one sandbox


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
    def create(cls, src_dir, limits: Limits, *, max_files: int = 200, max_bytes: int = 64 * MB) -> Box:
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
        env.update({k: str(v) for k, v in extra.items() if v is not None})
        return env

    def limit_args(self) -> list[str]:
        """``prlimit`` with this sandbox's limits (for a run without bubblewrap)."""
        return prlimit_argv(self.limits)

    def wrap(self, cmd: list[str], *, env: dict, uid: int = NOBODY) -> list[str]:
        """``cmd`` (the kernel's command line) inside bubblewrap, with the limits, as ``uid`` (run as root:
        nobody by default; see :func:`~.bwrap.sandbox_uid`)."""
        fonts = _font_cache()
        ro = [(str(fonts), f"/tmp/mpl/{fonts.name}")] if fonts is not None else []
        ro += [(str(host), f"/sbx/{name}") for name, host in sorted(self.files.items())]
        opts = BwrapOptions(limits=self.limits, uid=uid, hostname="sandbox", dirs=("/tmp/mpl",), work="/sbx",
                            ro_binds=tuple(ro), binds=((str(self.ipc), str(self.ipc)),), chdir="/sbx",
                            env=self.kernel_env(env))
        return bwrap_argv(opts, cmd)


def kernel_exit_reason(status: int | None, limits: Limits | None = None) -> str:
    """Why a sandboxed kernel ended, from bwrap's exit status (128 + signal when killed by a signal)."""
    if status is None:
        return "the kernel stopped answering"
    lim = limits or GRADING
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
