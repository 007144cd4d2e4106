"""One sandbox recipe: bubblewrap's command line, for a graded kernel and for a hub user's Jupyter server.

:func:`bwrap_argv` turns a :class:`BwrapOptions` and a command into the argv that runs the command in
bubblewrap (Debian package ``bubblewrap``), under ``prlimit``'s limits (:class:`~.limits.Limits`) and, when
run as root, as an unprivileged uid (``setpriv``).  The grader (:class:`~.sandbox.Box`, one per kernel) and
the course hub's spawner (``deploy/jupyterhub/aerophoto_hub.py``) both build their sandboxes here; they
differ only in their options.  The recipe:

* **the files**: ``/usr``, ``/bin``, ``/sbin``, ``/lib*``, ``/etc`` and the book's Python (its prefix, the
  venv, the package's own source folder: :func:`python_roots`) read-only, each under fresh traversable
  parents (a Python under ``/root`` shows nothing else of ``/root``); a fresh ``/proc`` (or the host's, for
  the instructor's server, whose own grading sandboxes need it) and ``/dev``; a size-limited private
  ``/tmp`` (and ``/dev/shm``, and a working folder such as ``/sbx``); then what the options bind, read-only
  or read-write — nothing else of the host;
* **namespaces**: its own IPC, host name and (unless ``own_pids`` is off) processes; no network unless
  ``network``; ``--die-with-parent`` and a new session.  Run by an ordinary user, bubblewrap makes a user
  namespace instead (``--unshare-all``): the same uid inside, no ``setpriv``;
* **limits** (``prlimit``): :meth:`Limits.prlimit_args`;
* **the uid** (run as root): ``setpriv --reuid --regid --clear-groups --no-new-privs`` — nobody (65534) or
  a grading job's own uid (:func:`sandbox_uid`), or the hub user's uid.

Pure: the standard library and :mod:`.limits`; nothing here imports jupyter_client or nbgrader.
"""

from __future__ import annotations

import os
import shutil
import sys
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path

from .limits import GRADING, MB, Limits

__all__ = ["BwrapOptions", "bwrap_argv", "prlimit_argv", "python_roots", "sandbox_uid", "tool", "bwrap_exe",
           "is_root", "NOBODY", "MAX_JOBS", "SYSTEM"]

NOBODY = 65534
MAX_JOBS = 14
"""Parallel grading jobs at most (``autograde --jobs``): one sandbox uid each (see :func:`sandbox_uid`)."""
SYSTEM = ("/usr", "/bin", "/sbin", "/lib", "/lib32", "/lib64", "/libx32", "/etc")
"""The host's system folders every sandbox sees read-only (symbolic links kept as links)."""


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


def is_root() -> bool:
    return os.geteuid() == 0


def tool(name: str) -> str | None:
    """A system tool (``prlimit``, ``setpriv``) from the system's folders only, or None."""
    return shutil.which(name, path="/usr/bin:/bin:/usr/sbin:/sbin")


def bwrap_exe() -> str | None:
    return shutil.which("bwrap") or (shutil.which("bwrap", path="/usr/bin:/bin"))


def python_roots() -> list[Path]:
    """The folders the book's Python needs: the interpreter's prefix, the venv, the package's source."""
    import aerophoto

    here = Path(aerophoto.__file__).resolve().parent.parent  # src/ of an editable install, or site-packages
    roots = []
    for p in (Path(sys.base_prefix), Path(sys.prefix), here):
        p = p.resolve()
        if not any(p == r or r in p.parents for r in roots):
            roots = [r for r in roots if p not in r.parents] + [p]
    return roots


@dataclass(frozen=True)
class BwrapOptions:
    """What one sandbox is, beyond the common recipe (see the module notes).

    limits : the resource limits (``prlimit``) and the sizes of ``/tmp``, the working folder, ``/dev/shm``
    uid, gid : the ids a root-run sandbox drops to (gid None: the uid's number)
    hostname : the sandbox's host name
    network : keep the host's network (a hub server answers the proxy); else only a private loopback
    own_pids : a process namespace of its own (every process gone with the sandbox)
    host_proc : the host's ``/proc`` instead of a fresh one
    etc : (host file, path) bound read-only over the system's files (the hub's ``/etc/passwd``)
    dirs : empty world-writable folders made in ``/tmp`` (``/tmp/mpl``)
    work : a size-limited tmpfs beside ``/tmp`` (the grading kernel's ``/sbx``), or None
    ro_binds, binds : (host path, path inside) bound read-only / read-write, in this order
    chdir : the working folder inside
    env : the whole environment inside (``--clearenv``), or None to keep the caller's
    """

    limits: Limits = GRADING
    uid: int = NOBODY
    gid: int | None = None
    hostname: str = "sandbox"
    network: bool = False
    own_pids: bool = True
    host_proc: bool = False
    etc: tuple = ()
    dirs: tuple = ()
    work: str | None = None
    ro_binds: tuple = ()
    binds: tuple = ()
    chdir: str = "/"
    env: Mapping | None = field(default=None, compare=False)


def _under_system(path: str) -> bool:
    return any(path == m or path.startswith(m + "/") for m in SYSTEM)


def _namespaces(opts: BwrapOptions) -> list[str]:
    if not is_root():  # an ordinary user: a user namespace too (the same uid inside)
        return ["--unshare-all"] + (["--share-net"] if opts.network else [])
    args = ["--unshare-ipc"]
    if opts.own_pids:
        args.append("--unshare-pid")
    if not opts.network:
        args.append("--unshare-net")
    return args + ["--unshare-uts"]


def _tmpfs(path: str, mb: int) -> list[str]:
    return ["--perms", "1777", "--size", str(int(mb * MB)), "--tmpfs", path]


def _mounts(opts: BwrapOptions) -> list[str]:
    """The file system inside: system, /proc, /dev, the private folders, the Python, the binds."""
    args: list[str] = []
    made: set[str] = set()

    def ancestors(path: Path):  # fresh traversable parents of a mount point (not the host's)
        for parent in reversed(path.parents):
            s = str(parent)
            if s == "/" or s in made or _under_system(s):
                continue
            made.add(s)
            args.extend(["--perms", "0755", "--dir", s])

    for top in SYSTEM:
        p = Path(top)
        if p.is_symlink():
            args += ["--symlink", os.readlink(p), top]
        elif p.is_dir():
            args += ["--ro-bind", top, top]
    for host, inside in opts.etc:
        args += ["--ro-bind", str(host), str(inside)]
    # /proc, /dev and a fresh /tmp before the Python and the binds: a Python environment (or a book) that
    # lives under /tmp is bound on top of the tmpfs, not hidden by it
    args += ["--bind", "/proc", "/proc"] if opts.host_proc else ["--proc", "/proc"]
    args += ["--dev", "/dev"]
    if opts.limits.shm_mb:
        args += _tmpfs("/dev/shm", opts.limits.shm_mb)
    args += _tmpfs("/tmp", opts.limits.tmpfs_mb)
    made.update({"/proc", "/dev", "/tmp"})
    for d in opts.dirs:
        args += ["--perms", "1777", "--dir", str(d)]
        made.add(str(d))
    if opts.work:
        args += _tmpfs(opts.work, opts.limits.tmpfs_mb)
        made.add(opts.work)
    for root in python_roots():
        if _under_system(str(root)):
            continue
        ancestors(root)
        args += ["--ro-bind", str(root), str(root)]
        made.add(str(root))
    for flag, pairs in (("--ro-bind", opts.ro_binds), ("--bind", opts.binds)):
        for host, inside in pairs:
            ancestors(Path(inside))
            args += [flag, str(host), str(inside)]
    return args


def prlimit_argv(limits: Limits) -> list[str]:
    """``prlimit`` with ``limits``, ending in ``--`` (the command follows)."""
    return [tool("prlimit") or "prlimit", *limits.prlimit_args()]


def bwrap_argv(opts: BwrapOptions, cmd) -> list[str]:
    """``cmd`` inside bubblewrap with ``opts`` (see the module notes): the whole argv to start."""
    args = [bwrap_exe() or "bwrap", *_namespaces(opts), "--die-with-parent", "--new-session",
            "--hostname", opts.hostname]
    args += _mounts(opts)
    args += ["--chdir", opts.chdir]
    if opts.env is not None:
        args.append("--clearenv")
        for k, v in sorted(opts.env.items()):
            args += ["--setenv", k, str(v)]
    args += ["--", *prlimit_argv(opts.limits)]
    if is_root():
        gid = opts.uid if opts.gid is None else opts.gid
        args += [tool("setpriv") or "setpriv", f"--reuid={int(opts.uid)}", f"--regid={int(gid)}", "--clear-groups",
                 "--no-new-privs", "--"]
    return args + list(cmd)
