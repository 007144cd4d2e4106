"""What one sandbox may use: the resource limits of a grading kernel and of a hub user's server, in one place.

:class:`Limits` is the one record of them.  :data:`GRADING` is what a submission's kernel gets
(:mod:`.sandbox`, :mod:`.sandbox_kernel`, :mod:`.sandbox_execute`; the course's ``c.SandboxExecute.limits``
overrides it field by field); :data:`HUB_STUDENT` and :data:`HUB_INSTRUCTOR` are what each user's Jupyter
server on the course hub gets (``deploy/jupyterhub/aerophoto_hub.py``; ``AEROPHOTO_HUB_STUDENT_MEM`` and
``AEROPHOTO_HUB_INSTRUCTOR_MEM`` override the memory).  :mod:`.bwrap` turns them into ``prlimit``'s and
bubblewrap's arguments.  A field that is ``None`` is not limited.

Pure: the standard library only (the hub's configuration imports it).
"""

from __future__ import annotations

from dataclasses import asdict, dataclass, replace

__all__ = ["Limits", "GRADING", "HUB_STUDENT", "HUB_INSTRUCTOR", "MB"]

MB = 1024 * 1024


@dataclass(frozen=True)
class Limits:
    """What one sandbox may use (``None``: not limited).

    memory_mb : address space of each process (RLIMIT_AS) — a memory bomb gets a MemoryError
    cpu_s : CPU seconds of each process (RLIMIT_CPU; SIGXCPU ends the kernel, reported as such)
    fsize_mb : the largest file a process may write (RLIMIT_FSIZE)
    nofile : open files per process (RLIMIT_NOFILE)
    nproc : processes and threads of the sandbox's user (RLIMIT_NPROC; a fork bomb stops there)
    tmpfs_mb : size of ``/tmp`` and of the grading kernel's working folder ``/sbx`` (each)
    shm_mb : size of a private ``/dev/shm`` (None: none is mounted)
    output_mb : outputs kept per notebook on the instructor's side (more is dropped, flagged)
    message_mb : the largest single message accepted from the kernel (a larger one ends the connection)
    cell_s : the default wall time of one cell, s (``aerophoto-course --timeout``'s default,
        :data:`~.common.DEFAULT_TIMEOUT_S`); the time a run uses is nbclient's ``timeout`` (``--timeout``,
        ``c.ExecutePreprocessor.timeout`` in the course's config)
    """

    memory_mb: int | None = 3072
    cpu_s: int | None = 900
    fsize_mb: int | None = 64
    nofile: int | None = 256
    nproc: int | None = 128
    tmpfs_mb: int = 256
    shm_mb: int | None = None
    output_mb: float = 4.0
    message_mb: int = 32
    cell_s: int = 120

    def replace(self, **kw) -> Limits:
        return replace(self, **kw)

    def as_dict(self) -> dict:
        return asdict(self)

    @classmethod
    def of(cls, value) -> Limits:
        """``value`` as Limits: a Limits as it is, a dict (a config's ``limits = {...}``) over :data:`GRADING`,
        anything else (None, unset) :data:`GRADING`."""
        if isinstance(value, Limits):
            return value
        if isinstance(value, dict):
            return cls(**value)
        return GRADING

    def prlimit_args(self) -> list[str]:
        """``prlimit``'s options for these limits (without the program's name), ending in ``--``."""
        out = []
        if self.memory_mb is not None:
            out.append(f"--as={int(self.memory_mb * MB)}")
        if self.cpu_s is not None:
            out.append(f"--cpu={self.cpu_s}:{self.cpu_s + 5}")  # soft: SIGXCPU, then 5 s to SIGKILL
        if self.fsize_mb is not None:
            out.append(f"--fsize={int(self.fsize_mb * MB)}")
        if self.nofile is not None:
            out.append(f"--nofile={self.nofile}")
        if self.nproc is not None:
            out.append(f"--nproc={self.nproc}")
        return out + ["--core=0", "--"]


GRADING = Limits()
"""A submission's kernel while it is graded (``aerophoto-course check``/``autograde``)."""

HUB_STUDENT = Limits(memory_mb=3072, cpu_s=None, fsize_mb=None, nofile=4096, nproc=512, tmpfs_mb=512, shm_mb=64)
"""A student's Jupyter server on the course hub: no CPU-time or file-size limit (a session lasts hours),
more processes and files than one graded kernel; memory per process (the spawner has no cgroup)."""

HUB_INSTRUCTOR = HUB_STUDENT.replace(memory_mb=4096)
"""The instructor's server: room for grading (≥ :data:`GRADING`'s memory, which its sandboxes get)."""
