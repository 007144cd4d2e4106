"""nbgrader's Execute preprocessor with the kernel in the sandbox, robust to what student code does.

:class:`SandboxExecute` is nbgrader's ``Execute`` with

* the kernel in the sandbox (:class:`~.sandbox_kernel.SandboxKernelManager`, ipc transport);
* a kernel that dies (memory, CPU time, ``os._exit``) or stops answering after a timed-out cell: the cell
  gets an error output with the reason, a new kernel is started, the earlier cells are replayed silently
  (not the failed ones, not the check cells) and grading goes on with the next cell — at most
  ``max_restarts`` times; cells never run get an error output too (nbgrader would give an unexecuted test
  cell full points);
* a cap on the outputs kept per notebook (the rest is dropped and noted) — the answer records of the check
  cells (:data:`.wire.ANSWERS_MIME`) are always kept.

The course sets it as the first of nbgrader's autograde preprocessors (:mod:`.grading`; configurable as
``c.SandboxExecute.*``); :func:`run_sandboxed` runs one notebook with it (``aerophoto-course check``).  What
happened is kept in :data:`EVENTS` (key: student, assignment, notebook) for the flags.  Importing this
module imports nbgrader: only the commands that grade do.
"""

from __future__ import annotations

import copy
import json
import time
from dataclasses import dataclass

from nbclient.client import NotebookClient
from nbclient.exceptions import CellTimeoutError, DeadKernelError
from nbclient.util import run_sync
from nbformat import NotebookNode
from nbgrader.preprocessors import Execute
from traitlets import Any, Bool, Integer, Unicode

from .bwrap import NOBODY
from .common import DEFAULT_TIMEOUT_S, is_test, one_line
from .limits import Limits
from .sandbox import kernel_exit_reason
from .sandbox_kernel import SandboxKernelManager
from .wire import ANSWERS_MIME

__all__ = ["SandboxExecute", "run_sandboxed", "EVENTS", "Event"]

#: (student, assignment, notebook) → list of events of the last sandboxed run
EVENTS: dict = {}


@dataclass
class Event:
    """Something the grader did to keep going: a dead kernel, a cell cut short, outputs dropped."""

    kind: str          # kernel_died, timeout, not_run, output_truncated
    cell: str          # cell id
    message: str

    def as_dict(self) -> dict:
        return {"kind": self.kind, "cell": self.cell, "message": self.message}


def _error_output(ename: str, evalue: str):
    return NotebookNode(output_type="error", ename=ename, evalue=evalue, traceback=[f"{ename}: {evalue}"])


class SandboxExecute(Execute):
    """nbgrader's Execute with the kernel in the sandbox (see the module notes)."""

    record_book = Unicode(None, allow_none=True).tag(config=True)
    unsafe_no_sandbox = Bool(False).tag(config=True)
    grading = Bool(True).tag(config=True)
    limits = Any(None).tag(config=True)
    uid = Integer(NOBODY).tag(config=True)  # run as root: the uid the kernel drops to (one per grading job)
    max_restarts = Integer(2).tag(config=True)
    startup_timeout = Integer(120).tag(config=True)
    shutdown_kernel = Unicode("immediate").tag(config=True)

    @property
    def the_limits(self) -> Limits:
        return Limits.of(self.limits)

    def create_kernel_manager(self):
        self.km = SandboxKernelManager(config=self.config, record_book=self.record_book,
                                       limits=self.the_limits, unsafe_no_sandbox=self.unsafe_no_sandbox,
                                       grading=self.grading, uid=self.uid, parent=None)
        self._km_ref = self.km
        return self.km

    async def async_start_new_kernel_client(self):
        kc = await super().async_start_new_kernel_client()
        self.km.seal()  # the kernel has bound its sockets: nothing more is written into the shared folder
        return kc

    start_new_kernel_client = run_sync(async_start_new_kernel_client)

    async def _async_handle_timeout(self, timeout, cell=None):
        self._timed_out = True
        return await super()._async_handle_timeout(timeout, cell)

    # outputs ------------------------------------------------------------------------------------
    def output(self, outs, msg, display_id, cell_index):
        content = msg.get("content", {})
        data = content.get("data") if isinstance(content, dict) else None
        is_record = isinstance(data, dict) and ANSWERS_MIME in data
        size = len(json.dumps(content, default=str)) if isinstance(content, dict) else 0
        limit = self.the_limits.output_mb * 1024 * 1024
        if not is_record and self._output_bytes + size > limit:
            self._dropped += size
            if cell_index not in self._truncated:
                self._truncated.add(cell_index)
                cell = self.nb.cells[cell_index]
                note = (f"[the grader kept the first {self.the_limits.output_mb:g} MB of this notebook's "
                        "output; the rest was dropped]")
                outs.append(NotebookNode(output_type="stream", name="stdout", text=note + "\n"))
                self._event("output_truncated", cell, f"more than {self.the_limits.output_mb:g} MB of output")
            return None
        self._output_bytes += size
        return super().output(outs, msg, display_id, cell_index)

    # the run ------------------------------------------------------------------------------------
    def _event(self, kind, cell, message):
        self.events.append(Event(kind, str(cell.get("id", "?")), message))

    def _reason(self, exc) -> str:
        km = getattr(self, "_km_ref", None)
        status = None
        if km is not None:
            try:
                status = km.exit_status()
            except Exception:
                status = getattr(km, "last_exit_status", None)
        if getattr(self, "_timed_out", False):
            return (f"the cell ran past the time limit ({self.timeout} s) and did not stop when interrupted; "
                    "the kernel was ended")
        if isinstance(exc, CellTimeoutError) and "IOPub" in str(exc):
            return (f"the cell's output could not be received (one message over "
                    f"{self.the_limits.message_mb} MB, or the kernel stopped answering); the kernel was ended")
        if isinstance(exc, CellTimeoutError) or (status is None and "Timeout" in type(exc).__name__):
            return (f"the cell ran past the time limit ({self.timeout} s) and did not stop when interrupted; "
                    "the kernel was ended")
        if isinstance(exc, DeadKernelError) or status is not None:
            return kernel_exit_reason(status, self.the_limits)
        return f"the kernel stopped answering ({type(exc).__name__}: {one_line(str(exc))[:120]})"

    def _replay(self, upto: int, skip: set) -> None:
        """Run cells[:upto] again in a new kernel, outputs discarded (not the failed ones, not the checks)."""
        for i in range(upto):
            cell = self.nb.cells[i]
            if cell.get("cell_type") != "code" or i in skip or is_test(cell):
                continue
            original = self.nb.cells[i]
            try:
                self.execute_cell(copy.deepcopy(cell), i, store_history=False)
            finally:
                self.nb.cells[i] = original

    def _kernel_died(self, exc, index: int) -> None:
        """The kernel died or stopped answering in cell ``index``: the cell gets an error output saying why."""
        self.km, self.kc = None, None
        reason = self._reason(exc)
        cell = self.nb.cells[index]
        if cell.get("cell_type") == "code":
            cell.setdefault("outputs", []).append(_error_output("KernelDied", reason))
        self._event("kernel_died", cell, reason)

    def _not_run(self, start: int, restarts: int) -> None:
        """Too many restarts: every code cell from ``start`` on gets an error output (never full points)."""
        cells = self.nb.cells
        for j in range(start, len(cells)):
            if cells[j].get("cell_type") == "code" and cells[j].get("source", "").strip():
                cells[j].setdefault("outputs", []).append(
                    _error_output("NotRun", f"not run: the kernel died {restarts} times"))
                if is_test(cells[j]):
                    self._event("not_run", cells[j], "the kernel died too often before this cell")

    def preprocess(self, nb, resources=None, km=None):
        NotebookClient.__init__(self, nb, km)
        self.reset_execution_trackers()
        self._check_assign_resources(resources)
        self.events, self._output_bytes, self._dropped, self._truncated = [], 0, 0, set()
        t0 = time.perf_counter()
        cells = self.nb.cells
        start, failed, restarts, ran_any = 0, set(), 0, False
        while start < len(cells):
            index = start
            try:
                with self.setup_kernel():
                    info = self.wait_for_reply(self.kc.kernel_info())
                    if info and "language_info" in info["content"]:
                        self.nb.metadata["language_info"] = info["content"]["language_info"]
                    if start:
                        self._replay(start, failed)
                    for index in range(start, len(cells)):
                        self._timed_out = False
                        self.preprocess_cell(cells[index], resources, index)
                        ran_any = True
                        cell = cells[index]
                        if any(o.get("ename") == "CellTimeoutError" for o in cell.get("outputs", [])
                               if o.get("output_type") == "error"):
                            self._event("timeout", cell, f"cut at the per-cell limit ({self.timeout} s)")
                start = len(cells)
            except Exception as exc:  # a dead or unresponsive kernel: note it, go on with a new one
                if not ran_any and index == start == 0 and not isinstance(exc, (DeadKernelError,
                                                                                CellTimeoutError)):
                    raise  # the sandbox itself did not start: that is the grader's failure, not the student's
                self._kernel_died(exc, index)
                failed.add(index)
                restarts += 1
                start = index + 1
                if restarts > self.max_restarts:
                    self._not_run(start, restarts)
                    break
        self.set_widgets_metadata()
        self.seconds = time.perf_counter() - t0
        key = _key(resources)
        if key is not None:
            EVENTS[key] = [e.as_dict() for e in self.events]
        return self.nb, self.resources


def _key(resources):
    nbr = (resources or {}).get("nbgrader") or {}
    if not nbr.get("student"):
        return None
    return (str(nbr.get("student")), str(nbr.get("assignment")), str(nbr.get("notebook")))


def run_sandboxed(nb, *, cwd, timeout: int = DEFAULT_TIMEOUT_S, record_book: str | None = None,
                  limits: Limits | None = None, unsafe_no_sandbox: bool = False, grading: bool = True,
                  resources: dict | None = None):
    """Execute ``nb`` (in place) in the sandbox; returns the preprocessor (``.events``, ``.seconds``)."""
    ex = SandboxExecute(timeout=timeout, interrupt_on_timeout=True, allow_errors=True, record_book=record_book,
                        limits=Limits.of(limits), unsafe_no_sandbox=unsafe_no_sandbox, grading=grading,
                        error_on_timeout={"ename": "CellTimeoutError",
                                          "evalue": f"the cell ran longer than {timeout} s",
                                          "traceback": [f"CellTimeoutError: the cell ran longer than {timeout} s"]})
    res = dict(resources or {})
    res.setdefault("metadata", {})["path"] = str(cwd)
    ex.preprocess(nb, res)
    return ex
