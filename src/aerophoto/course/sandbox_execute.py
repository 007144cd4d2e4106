"""nbgrader's Execute preprocessor with the kernel in the sandbox, robust to what student code does.

:class:`SandboxExecute` is nbgrader's ``Execute`` with

* the kernel in the sandbox (:class:`~.sandbox_kernel.SandboxKernelManager`, ipc transport);
* a timed-out cell is interrupted and the next cell waits until the kernel has answered the interrupt and
  ended the cell (``interrupt_grace_s``), so the interrupt cannot land in the next cell (a check cell);
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
from queue import Empty

from nbclient.client import NotebookClient
from nbclient.exceptions import CellTimeoutError, DeadKernelError
from nbclient.util import run_sync
from nbformat import NotebookNode
from nbgrader.preprocessors import Execute
from traitlets import Any, Bool, Float, Integer, Unicode

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

    kind: str          # kernel_died, timeout, not_run, output_truncated, notebook_timeout
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
    # seconds a timed-out cell has to stop once interrupted before its kernel is ended (None: its limit, 5–30 s)
    interrupt_grace_s = Float(None, allow_none=True).tag(config=True)
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

    async def _async_poll_for_reply(self, msg_id, cell, timeout, task_poll_output_msg, task_poll_kernel_alive):
        self._waiting_for = msg_id
        return await super()._async_poll_for_reply(msg_id, cell, timeout, task_poll_output_msg,
                                                   task_poll_kernel_alive)

    async def _async_handle_timeout(self, timeout, cell=None):
        self._timed_out = True
        reply = await super()._async_handle_timeout(timeout, cell)  # the interrupt is sent
        # nbclient would go on with the next cell at once, while the kernel may still be in this one: its
        # interrupt (the control thread's SIGINT, sent once it gets the interpreter lock) would then stop
        # the next cell — a check cell that records nothing.  Go on only when the kernel has answered both
        # the interrupt and this cell; a kernel that does not within the grace is ended (a new one replays
        # the earlier cells).
        grace = self.interrupt_grace_s if self.interrupt_grace_s is not None else _grace_s(timeout)
        t0 = time.monotonic()
        if not (await self.km.wait_interrupted(grace)
                and await self._wait_for_reply(self._waiting_for, grace - (time.monotonic() - t0))):
            raise CellTimeoutError.error_from_timeout_and_cell(
                "the cell did not stop when interrupted", timeout, cell)
        return reply

    async def _wait_for_reply(self, msg_id, timeout: float) -> bool:
        """True once the kernel's execute reply to ``msg_id`` has come on the shell channel."""
        deadline = time.monotonic() + timeout
        while (left := deadline - time.monotonic()) > 0:
            try:
                msg = await self.kc.shell_channel.get_msg(timeout=left)
            except Empty:
                return False
            if msg.get("parent_header", {}).get("msg_id") == msg_id:
                return True
        return False

    # outputs ------------------------------------------------------------------------------------
    def _over_cap(self, content, cell_index) -> bool:
        """Count one output against the caps; True when it is to be dropped.  Everything the kernel emits counts:
        an answer record may be at most ``record_kb`` and the records of a notebook ``output_mb`` together,
        beside the other outputs' ``output_mb``."""
        data = content.get("data") if isinstance(content, dict) else None
        is_record = isinstance(data, dict) and ANSWERS_MIME in data
        try:
            size = len(json.dumps(content, default=str)) if isinstance(content, dict) else 0
        except (ValueError, RecursionError):
            size = 1 << 40
        lim = self.the_limits
        limit = lim.output_mb * 1024 * 1024
        cell = self.nb.cells[cell_index]
        if is_record:
            if size > lim.record_kb * 1024 or self._record_bytes + size > limit:
                self._dropped += size
                self._event("output_truncated", cell, f"an answer record of {size / 1024:.0f} KB (the limit is "
                                                      f"{lim.record_kb} KB) was dropped")
                return True
            self._record_bytes += size
            return False
        if self._output_bytes + size > limit:
            self._dropped += size
            if cell_index not in self._truncated:
                self._truncated.add(cell_index)
                self._truncation_note.append(cell_index)
                self._event("output_truncated", cell, f"more than {lim.output_mb:g} MB of output")
            return True
        self._output_bytes += size
        return False

    def output(self, outs, msg, display_id, cell_index):
        if self._over_cap(msg.get("content", {}), cell_index):
            if self._truncation_note and self._truncation_note[-1] == cell_index:
                self._truncation_note.pop()
                note = (f"[the grader kept the first {self.the_limits.output_mb:g} MB of this notebook's "
                        "output; the rest was dropped]")
                outs.append(NotebookNode(output_type="stream", name="stdout", text=note + "\n"))
            return None
        return super().output(outs, msg, display_id, cell_index)

    def _update_display_id(self, display_id, msg):
        # an update of an earlier display replaces its data: counted against the same cap
        index = getattr(self, "_cell_index", 0) or 0
        if self._over_cap(msg.get("content", {}), min(index, len(self.nb.cells) - 1)):
            return None
        return super()._update_display_id(display_id, msg)

    async def async_execute_cell(self, cell, cell_index, execution_count=None, store_history=True):
        self._cell_index = cell_index
        return await super().async_execute_cell(cell, cell_index, execution_count, store_history)

    execute_cell = run_sync(async_execute_cell)

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

    def _notebook_time_up(self, budget: float) -> None:
        """Every code cell not run yet gets an error output; the first one an event (the flag)."""
        said = False
        for cell in self.nb.cells:
            if cell.get("cell_type") != "code" or not str(cell.get("source", "")).strip():
                continue
            if cell.get("execution_count") is None and not cell.get("outputs"):
                cell.setdefault("outputs", []).append(_error_output(
                    "NotRun", f"not run: the notebook used up its time limit ({budget:g} s)"))
                if not said:
                    self._event("notebook_timeout", cell, f"the notebook ran past its time limit ({budget:g} s); "
                                                          "this cell and the ones after it were not run")
                    said = True

    def _default_record_book(self, resources) -> None:
        """Run by plain nbgrader (the formgrader's button): the student's number from the course's roster."""
        if self.record_book:
            return
        student = str(((resources or {}).get("nbgrader") or {}).get("student") or "")
        if not student:
            return
        from pathlib import Path

        from .common import digits, read_roster

        root = self.config.CourseDirectory.get("root") if "CourseDirectory" in self.config else None
        roster = Path(str(root or ".")) / "roster.csv"
        try:
            found = read_roster(roster).get(student) if roster.is_file() else None
        except (OSError, ValueError):
            found = None
        self.record_book = found or (student if len(digits(student)) >= 2 else None)

    def preprocess(self, nb, resources=None, km=None):
        self._default_record_book(resources)
        NotebookClient.__init__(self, nb, km)
        self.reset_execution_trackers()
        self._check_assign_resources(resources)
        self.events, self._output_bytes, self._dropped, self._truncated = [], 0, 0, set()
        self._record_bytes, self._truncation_note = 0, []
        t0 = time.perf_counter()
        cell_timeout = self.timeout
        # the notebook's limit counts the time its cells run (not kernel starts, not the grader's replays)
        budget, spent = float(self.the_limits.notebook_s), [0.0]
        cells = self.nb.cells
        start, failed, restarts, ran_any, start_failures = 0, set(), 0, False, 0
        while start < len(cells) and spent[0] < budget:
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
                        left = budget - spent[0]
                        if left <= 0:
                            break
                        # no cell runs past the notebook's own limit
                        self.timeout = max(1, min(int(cell_timeout or left), int(left) + 1)) \
                            if cell_timeout else max(1, int(left) + 1)
                        t_cell = time.perf_counter()
                        try:
                            self.preprocess_cell(cells[index], resources, index)
                        finally:
                            spent[0] += time.perf_counter() - t_cell
                        ran_any = True
                        cell = cells[index]
                        if any(o.get("ename") == "CellTimeoutError" for o in cell.get("outputs", [])
                               if o.get("output_type") == "error"):
                            self._event("timeout", cell, f"cut at the per-cell limit ({self.timeout} s)")
                start = len(cells)
            except Exception as exc:  # a dead or unresponsive kernel: note it, go on with a new one
                if not ran_any and index == start == 0 and not isinstance(exc, (DeadKernelError,
                                                                                CellTimeoutError)):
                    # the sandbox itself did not start — no student code has run yet: once more (a loaded
                    # machine), then it is the grader's failure, not the student's
                    self.km, self.kc = None, None
                    start_failures += 1
                    if start_failures > 1:
                        raise
                    time.sleep(1.0)
                    continue
                self._kernel_died(exc, index)
                failed.add(index)
                restarts += 1
                start = index + 1
                if restarts > self.max_restarts:
                    self._not_run(start, restarts)
                    break
        self.timeout = cell_timeout
        if spent[0] >= budget:
            self._notebook_time_up(budget)
        self.set_widgets_metadata()
        self.seconds = time.perf_counter() - t0
        key = _key(resources)
        if key is not None:
            EVENTS[key] = [e.as_dict() for e in self.events]
        return self.nb, self.resources


def _grace_s(timeout) -> float:
    """Seconds a timed-out cell gets to stop once interrupted: as long as its limit, 5–30 s."""
    return float(min(30, max(5, int(timeout or 0))))


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
