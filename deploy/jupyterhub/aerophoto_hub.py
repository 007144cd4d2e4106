"""The course hub's spawner: each user's Jupyter server in bubblewrap, as that user's own uid, with their own home.

Used by ``jupyterhub_config.py`` (beside this file); the hub runs as root on the course machine.

Why a spawner of our own.  JupyterHub's ``LocalProcessSpawner`` starts a server with ``setuid`` to a system
account and lets it see the whole machine.  This one starts it through **bubblewrap** with the bind recipe
of the grading sandbox — the package's one recipe, :func:`aerophoto.course.bwrap.bwrap_argv`, with this
server's options — and the limits of :data:`aerophoto.course.limits.HUB_STUDENT` / ``HUB_INSTRUCTOR``:

* the server sees ``/usr``, ``/lib*``, ``/bin``, ``/etc`` and the book's Python (its prefix, the venv, the
  package's source) **read-only**; the book's ``notebooks/`` read-only (for ``aerophoto-course workbook``);
  **its own home** read-write at ``/home/<name>`` (on the host ``<homes>/<name>``, mode 0700, owned by the
  user's uid); nbgrader's **exchange** read-write at ``/srv/nbgrader/exchange``; a private size-limited
  ``/tmp``; nothing else — no other home, no course folder, no hub state;
* it runs as **the user's own uid** (``setpriv``; no capabilities, ``no_new_privs``): uids come from a table
  kept by the hub (``<state>/users.json``, from ``uid_base`` up) so that any authenticator works (LTI and LDAP
  names need no system account); a ``passwd``/``group`` listing them is bound over ``/etc/passwd`` and
  ``/etc/group`` so that tools (and nbgrader's owner check on collect) can name them.  With
  ``system_users = True`` (PAM) the system account's uid and home are used instead;
* students get **their own process namespace** (they see only their own processes; stopping the server ends
  every process it started).  The instructor's server keeps the host's ``/proc`` instead, because grading
  runs ``aerophoto-course autograde`` there and its bubblewrap sandboxes cannot mount ``/proc`` inside a
  sandbox that covers parts of it (a kernel rule for user namespaces);
* **limits** (``prlimit``, :class:`aerophoto.course.limits.Limits`): ``mem_limit`` is each process's address
  space (a runaway array gets a MemoryError; this spawner has no cgroup, so it is per process, not per user),
  processes per uid (``nproc``), open files; ``/tmp`` is a tmpfs of ``tmp_mb``, ``/dev/shm`` one of 64 MB.
  The defaults are the package's (``HUB_STUDENT``, ``HUB_INSTRUCTOR``); ``jupyterhub_config.py`` changes
  the memory only when ``AEROPHOTO_HUB_STUDENT_MEM`` / ``_INSTRUCTOR_MEM`` say so.

The book's Python here lives under ``/root/.pyenv`` (``/root`` is mode 0700), which another uid cannot
reach: inside the sandbox only the Python's own folders are bound, under fresh traversable parents, so
nothing of ``/root`` but the interpreter is visible.  On a server with a system-wide Python the same recipe
applies unchanged.
"""

from __future__ import annotations

import json
import os
import pwd
import re
import signal
import sys
from pathlib import Path

from aerophoto.course.bwrap import BwrapOptions, bwrap_argv
from aerophoto.course.limits import HUB_INSTRUCTOR, HUB_STUDENT, MB, Limits
from jupyterhub.spawner import LocalProcessSpawner
from jupyterhub.utils import random_port
from traitlets import Bool, Integer, Unicode, default

HERE = Path(__file__).resolve().parent
EXCHANGE_MOUNT = "/srv/nbgrader/exchange"
COURSE_ID = "aerophoto"
CONFIG_MOUNT = "/srv/aerophoto/jupyter-config"
NAME_RE = re.compile(r"^[a-z0-9][a-z0-9._@-]{0,63}$")
"""Hub user names the spawner accepts (also the hub's ``Authenticator.username_pattern``): a home folder's
name, an nbgrader student id (no ``+``), a passwd entry."""

class UidTable:
    """Hub user name → uid, kept in ``<state>/users.json``; also writes the passwd/group files bound into sandboxes.

    A name that is a system account of the host (``root``, ``daemon`` …) is refused: its uid would be wrong.
    """

    def __init__(self, state_dir, uid_base: int = 30000):
        self.dir = Path(state_dir)
        self.path = self.dir / "users.json"
        self.uid_base = int(uid_base)
        self.dir.mkdir(parents=True, exist_ok=True)
        os.chmod(self.dir, 0o700)

    def load(self) -> dict:
        try:
            return json.loads(self.path.read_text(encoding="utf-8"))
        except (OSError, ValueError):
            return {}

    def uid(self, name: str) -> int:
        if not NAME_RE.match(name):
            raise ValueError(f"user name {name!r} is not valid for the course hub; expected {NAME_RE.pattern}")
        table = self.load()
        if name not in table:
            try:
                pwd.getpwnam(name)
                raise ValueError(f"user name {name!r} is a system account of this machine: refused")
            except KeyError:
                pass
            taken = set(table.values()) | {p.pw_uid for p in pwd.getpwall()}
            uid = max([self.uid_base - 1, *[u for u in table.values()]]) + 1
            while uid in taken:
                uid += 1
            table[name] = uid
            tmp = self.path.with_suffix(".tmp")
            tmp.write_text(json.dumps(table, indent=1, sort_keys=True) + "\n", encoding="utf-8")
            os.replace(tmp, self.path)
            self.write_etc()
        return table[name]

    def write_etc(self) -> tuple[Path, Path]:
        """``<state>/etc/passwd`` and ``group``: the host's entries and one per hub user (rewritten in place,
        so a running sandbox that binds them sees users added later)."""
        etc = self.dir / "etc"
        etc.mkdir(exist_ok=True)
        os.chmod(etc, 0o755)
        table = self.load()
        host_p = Path("/etc/passwd").read_text(encoding="utf-8").rstrip("\n").splitlines()
        host_g = Path("/etc/group").read_text(encoding="utf-8").rstrip("\n").splitlines()
        users = [f"{n}:x:{u}:{u}:{n}:/home/{n}:/bin/bash" for n, u in sorted(table.items(), key=lambda kv: kv[1])]
        groups = [f"{n}:x:{u}:" for n, u in sorted(table.items(), key=lambda kv: kv[1])]
        out = []
        for name, lines in (("passwd", host_p + users), ("group", host_g + groups)):
            p = etc / name
            fd = os.open(p, os.O_WRONLY | os.O_CREAT, 0o644)
            with os.fdopen(fd, "w", encoding="utf-8") as fh:
                fh.truncate(0)
                fh.write("\n".join(lines) + "\n")
            os.chmod(p, 0o644)
            out.append(p)
        return out[0], out[1]


def prepare_exchange(exchange_dir, owner_uid: int | None) -> Path:
    """nbgrader's exchange on the host: the root ``1777`` (nbgrader wants ``rwxrwxrwx``; the sticky bit keeps a
    student from renaming the course's folder away), and ``<root>/aerophoto`` made and owned by the instructor
    before any student can take the name."""
    root = Path(exchange_dir)
    root.mkdir(parents=True, exist_ok=True)
    os.chown(root, 0, 0)
    os.chmod(root, 0o1777)
    course = root / COURSE_ID
    if not course.exists():
        course.mkdir()
        os.chmod(course, 0o755)
    if owner_uid is not None and course.stat().st_uid != owner_uid:
        os.chown(course, owner_uid, owner_uid)
    return root


class AerophotoSpawner(LocalProcessSpawner):
    """Each user's server in bubblewrap as their own uid, with their own home (see the module notes)."""

    state_dir = Unicode("/srv/aerophoto-hub", config=True, help="the hub's state: users.json, etc/")
    homes_dir = Unicode("", config=True, help="host folder holding a home per user (default <state>/home)")
    exchange_dir = Unicode("", config=True, help="host folder of nbgrader's exchange (default <state>/exchange)")
    book_dir = Unicode(str(HERE.parent.parent), config=True,
                       help="the book's repository: its notebooks/ and pyproject.toml are bound read-only")
    config_root = Unicode(str(HERE / "single-user"), config=True,
                          help="folder with the Jupyter config of each role: student/ and instructor/")
    instructor_group = Unicode("instructors", config=True)
    instructor_mem_limit = Unicode(f"{HUB_INSTRUCTOR.memory_mb}M", config=True,
                                   help="address space per process of an instructor (≥ the grading sandbox's)")
    uid_base = Integer(30000, config=True, help="first uid the table gives out")
    system_users = Bool(False, config=True, help="use the system account's uid and home (PAM) instead of the table")
    nproc = Integer(HUB_STUDENT.nproc, config=True, help="processes and threads per uid (RLIMIT_NPROC)")
    nofile = Integer(HUB_STUDENT.nofile, config=True, help="open files per process")
    tmp_mb = Integer(HUB_STUDENT.tmpfs_mb, config=True, help="size of the private /tmp, MB")

    @default("homes_dir")
    def _homes(self):
        return str(Path(self.state_dir) / "home")

    @default("exchange_dir")
    def _exchange(self):
        return str(Path(self.state_dir) / "exchange")

    # identity ---------------------------------------------------------------------------------
    @property
    def is_instructor(self) -> bool:
        return any(g.name == self.instructor_group for g in self.user.groups)

    @property
    def role(self) -> str:
        return "instructor" if self.is_instructor else "student"

    def account(self) -> tuple[int, int, Path]:
        """(uid, gid, host home folder) of this user."""
        name = self.user.name
        if self.system_users:
            pw = pwd.getpwnam(name)
            return pw.pw_uid, pw.pw_gid, Path(pw.pw_dir)
        uid = UidTable(self.state_dir, self.uid_base).uid(name)
        return uid, uid, Path(self.homes_dir) / name

    def make_preexec_fn(self, name):
        return None  # bubblewrap runs as root and drops to the user's uid itself (setpriv)

    def user_env(self, env):
        name = self.user.name
        home = f"/home/{name}"
        env.update(USER=name, LOGNAME=name, HOME=home, SHELL="/bin/bash")
        return env

    def get_env(self):
        env = super().get_env()
        env.update({
            "PATH": f"{Path(sys.executable).parent}:/usr/local/bin:/usr/bin:/bin",
            "LANG": env.get("LANG") or "C.UTF-8",
            "JUPYTER_CONFIG_DIR": CONFIG_MOUNT,  # read-only: the course's settings, not overridable by a user
            "JUPYTERLAB_SETTINGS_DIR": f"/home/{self.user.name}/.jupyter/lab/user-settings",
            "JUPYTERLAB_WORKSPACES_DIR": f"/home/{self.user.name}/.jupyter/lab/workspaces",
            "TMPDIR": "/tmp",
            "MALLOC_ARENA_MAX": "2",       # glibc's per-thread arenas otherwise reserve address space by the GB
            "OPENBLAS_NUM_THREADS": "1",   # 2 cores shared by a class: no BLAS thread pools per kernel
            "OMP_NUM_THREADS": "1",
            "MKL_NUM_THREADS": "1",
            "PYDEVD_DISABLE_FILE_VALIDATION": "1",
            "MEM_LIMIT": str(self.mem_bytes()),
        })
        for k in ("PYTHONPATH", "VIRTUAL_ENV", "LD_LIBRARY_PATH"):
            env.pop(k, None)
        return env

    def mem_bytes(self) -> int:
        if self.is_instructor:
            from jupyterhub.traitlets import ByteSpecification

            return int(ByteSpecification().validate(self, self.instructor_mem_limit))
        return int(self.mem_limit or HUB_STUDENT.memory_mb * MB)

    def limits(self) -> Limits:
        """This user's limits: the package's for the role, with this spawner's memory, processes, files, /tmp."""
        base = HUB_INSTRUCTOR if self.is_instructor else HUB_STUDENT
        return base.replace(memory_mb=self.mem_bytes() / MB, nproc=self.nproc, nofile=self.nofile,
                            tmpfs_mb=self.tmp_mb)

    # the sandbox ------------------------------------------------------------------------------
    def prepare_home(self, uid: int, gid: int, home: Path) -> None:
        home.parent.mkdir(parents=True, exist_ok=True)
        os.chmod(home.parent, 0o711)  # the homes' folder: no listing of who is in the course
        if not home.exists():
            home.mkdir(mode=0o700)
            os.chown(home, uid, gid)
        st = home.stat()
        if st.st_uid != uid:
            raise RuntimeError(f"{home} belongs to uid {st.st_uid}, not to {self.user.name} (uid {uid})")
        os.chmod(home, 0o700)

    def bwrap_options(self, uid: int, gid: int, home: Path) -> BwrapOptions:
        """This user's sandbox (see the module notes): the package's recipe with a home, the exchange, the book."""
        name = self.user.name
        etc = ()
        if not self.system_users:
            passwd, group = UidTable(self.state_dir, self.uid_base).write_etc()
            etc = ((str(passwd), "/etc/passwd"), (str(group), "/etc/group"))
        book = Path(self.book_dir)
        ro = [(str(book / rel), str(book / rel)) for rel in ("notebooks", "pyproject.toml") if (book / rel).exists()]
        ro.append((str(Path(self.config_root) / self.role), CONFIG_MOUNT))
        return BwrapOptions(limits=self.limits(), uid=uid, gid=gid, hostname="aerophoto", network=True,
                            own_pids=not self.is_instructor, host_proc=self.is_instructor, etc=etc,
                            ro_binds=tuple(ro),
                            binds=((str(home), f"/home/{name}"), (str(self.exchange_dir), EXCHANGE_MOUNT)),
                            chdir=f"/home/{name}")

    def bwrap_args(self, uid: int, gid: int, home: Path) -> list[str]:
        """The command line up to the server's own: bubblewrap, prlimit, setpriv (:func:`bwrap_argv`)."""
        return bwrap_argv(self.bwrap_options(uid, gid, home), [])

    async def start(self):
        if os.geteuid() != 0:
            raise RuntimeError("the course hub runs as root: it starts each user's server as that user's uid")
        uid, gid, home = self.account()
        self.prepare_home(uid, gid, home)
        if self.is_instructor:
            prepare_exchange(self.exchange_dir, uid)
        if self.port == 0:
            self.port = random_port()
        env = self.get_env()
        cmd = self.bwrap_args(uid, gid, home) + list(self.cmd) + list(self.get_args())
        self.log.info("Spawning %s (%s, uid %d) in bubblewrap", self.user.name, self.role, uid)
        from subprocess import Popen

        self.proc = Popen(cmd, env=env, start_new_session=True, cwd="/", **self.popen_kwargs)
        self.pid = self.proc.pid
        return (self.ip or "127.0.0.1", self.port)

    # stopping ---------------------------------------------------------------------------------
    def _server_process(self):
        """The server inside the sandbox (the first descendant that is not bubblewrap), or None."""
        import psutil

        try:
            for p in psutil.Process(self.pid).children(recursive=True):
                try:
                    if os.path.basename(p.exe()) != "bwrap":
                        return p
                except psutil.Error:
                    continue
        except psutil.Error:
            return None
        return None

    async def _signal(self, sig):
        """SIGINT/SIGTERM go to the server itself (it shuts its kernels down; the sandbox then ends); SIGKILL
        kills the sandbox and everything in it.  bubblewrap does not forward signals."""
        import psutil

        if sig == 0 or not self.pid:
            return await super()._signal(sig)
        if sig in (signal.SIGINT, signal.SIGTERM):
            server = self._server_process()
            if server is not None:
                try:
                    server.send_signal(signal.SIGTERM)
                    return True
                except psutil.Error:
                    pass
            return await super()._signal(signal.SIGTERM)
        try:
            tree = psutil.Process(self.pid).children(recursive=True)
        except psutil.Error:
            tree = []
        for p in reversed(tree):
            try:
                p.kill()
            except psutil.Error:
                pass
        return await super()._signal(sig)
