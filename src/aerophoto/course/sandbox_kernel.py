"""The jupyter_client side of the sandbox: the kernel manager that starts the book's kernel in bubblewrap.

:class:`SandboxKernelManager` starts the kernel inside the sandbox of a :class:`~.sandbox.Box` (bubblewrap,
:mod:`.bwrap`'s recipe, :class:`~.limits.Limits`), over jupyter_client's ipc transport, and tells why a
kernel ended; :class:`SandboxKernelClient` refuses messages larger than the limit.  nbgrader's preprocessor
(:class:`~.sandbox_execute.SandboxExecute`) uses it; so does ``aerophoto-course check``.  Importing this
module imports jupyter_client and zmq: only the commands that run kernels do.
"""

from __future__ import annotations

import os
import shutil
import time
from pathlib import Path

import zmq
from jupyter_client.asynchronous import AsyncKernelClient
from jupyter_client.connect import channel_socket_types
from jupyter_client.manager import AsyncKernelManager
from traitlets import Any, Bool, Dict, Integer, Unicode

from .bwrap import NOBODY, tool
from .limits import GRADING, MB, Limits
from .sandbox import Box, require

__all__ = ["SandboxKernelClient", "SandboxKernelManager"]


class SandboxKernelClient(AsyncKernelClient):
    """A kernel client that refuses messages larger than ``max_message_bytes`` (zmq MAXMSGSIZE)."""

    max_message_bytes = Integer(GRADING.message_mb * MB).tag(config=True)

    def _create_connected_socket(self, channel, identity=None):
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
    kernel's ``AEROPHOTO_RECORD_BOOK``), ``limits`` (:class:`~.limits.Limits`), ``grading`` (sets
    ``AEROPHOTO_GRADING=1``: check cells emit the submitted values), ``uid`` (run as root: the uid the
    kernel drops to, :func:`~.bwrap.sandbox_uid`), ``unsafe_no_sandbox`` (a developer's escape hatch: no
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
        self.client_class = "aerophoto.course.sandbox_kernel.SandboxKernelClient"
        self.box = None
        self.last_exit_status = None

    @property
    def the_limits(self) -> Limits:
        return Limits.of(self.limits)

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
            return (self.box.limit_args() if tool("prlimit") else []) + cmd
        return self.box.wrap(cmd, env=self._grading_env(), uid=self.uid)

    def client(self, **kw):
        kc = super().client(**kw)
        kc.max_message_bytes = int(self.the_limits.message_mb * MB)
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
        self._interrupt_id = msg["header"]["msg_id"]

    interrupt_kernel = _async_interrupt_kernel

    async def wait_interrupted(self, timeout: float) -> bool:
        """True once the kernel has answered the last interrupt (it has sent itself SIGINT), within ``timeout`` s.

        The kernel's control thread turns the request into the signal only when it gets the interpreter
        lock: a cell busy in C code holds it, and the signal can then land in a later cell.
        """
        want, sock = getattr(self, "_interrupt_id", None), self._control_socket
        if want is None or sock is None:
            return False
        deadline = time.monotonic() + max(0.0, float(timeout))
        while (left := deadline - time.monotonic()) > 0:
            if not await sock.poll(int(left * 1000) + 1):
                return False
            frames = await sock.recv_multipart()
            _, frames = self.session.feed_identities(frames)
            msg = self.session.deserialize(frames, content=False)
            if msg.get("parent_header", {}).get("msg_id") == want:
                return True
        return False

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
