"""``aerophoto-course check``: run a notebook in the sandbox and report each task as the grader would.

A task is reported passed only when the trusted check (:mod:`.trusted`, in this process, on the values the
check cell recorded) passes it — never on the kernel's word — so an exception hook that hides a failing
check, a replaced check function or a swapped variant cannot make ``check`` say "passed".  Nothing is
verified, and the exit status is 2, for a notebook with no graded task, a kernel name that is not installed
or no record-book number.

The flags the teacher will see are printed too, one line each on what they mean: the grader's (from the
records) and the behaviour flags of the student's own cells (:func:`aerophoto.course.flags.behaviour_flags`,
read against the book's own copy of the chapter, :func:`release_for`).
"""

from __future__ import annotations

from pathlib import Path

from .common import DEFAULT_TIMEOUT_S, digits, graded_tasks, read_nb
from .limits import Limits
from .outcomes import CheckResult, TaskOutcome, executed_outcomes


def resolve_record_book(nb, record_book=None) -> tuple[str | None, str]:
    """(number, where it came from): the one given, the notebook's first cell, or the remembered one."""
    from .flags import parse_record_book

    if record_book:
        return str(record_book), "--record-book"
    kind, value = parse_record_book(nb)
    if kind == "value":
        return str(value), "the notebook's first cell"
    from ..book import remembered_record_book

    saved = remembered_record_book()
    return (saved, "remembered") if saved else (None, "")


def release_for(path, notebooks_dir=None):
    """The book's own copy of the chapter of ``path`` (``NN_*.ipynb`` with the same number), or None."""
    import re

    from .common import chapters, default_notebooks_dir

    m = re.match(r"^(\d\d)_", Path(path).name)
    if not m:
        return None
    folder = Path(notebooks_dir) if notebooks_dir is not None else default_notebooks_dir()
    same = [p for p in chapters(folder) if p.name.startswith(m.group(1) + "_")] if folder.is_dir() else []
    if not same:
        return None
    try:
        return read_nb(same[0])
    except Exception:  # the book's copy cannot be read: no behaviour flags, said in the output
        return None


def _installed_kernels() -> set:
    try:
        from jupyter_client.kernelspec import KernelSpecManager

        return set(KernelSpecManager().find_kernel_specs()) | {"python3"}
    except Exception:
        return {"python3"}


def check_notebook(path, *, timeout: int = DEFAULT_TIMEOUT_S, record_book: str | None = None,
                   limits: Limits | None = None, unsafe_no_sandbox: bool = False) -> CheckResult:
    """Execute a copy of a notebook in the sandbox and grade each task with the trusted check.

    The file is not changed.  The kernel runs with the record-book number given, else the one in the
    notebook's first cell, else the remembered one, and an empty ``AEROPHOTO_HOME``.  A cell running
    longer than ``timeout`` seconds is interrupted and counted as an error; the rest still runs.
    """
    from .trusted import grade_executed

    path = Path(path)
    result = CheckResult(path)
    nb = read_nb(path)
    kernel = (nb.metadata.get("kernelspec") or {}).get("name") or "python3"
    if kernel not in _installed_kernels():
        result.problem = (f"the notebook asks for the kernel {kernel!r}, which is not installed here; the book's "
                          "notebooks run on 'python3' — nothing was run")
        return result
    tasks = graded_tasks(nb)
    if not tasks:
        result.problem = "no graded tasks in this notebook (no nbgrader check cells): nothing to verify"
        return result
    rb, _ = resolve_record_book(nb, record_book)
    if rb is None or len(digits(rb)) < 2:
        result.problem = ("no record-book number: type it in the first cell (RECORD_BOOK = \"19-0457\") or pass "
                          "--record-book — without it the answers cannot be verified")
        return result
    from .sandbox_execute import run_sandboxed

    ex = run_sandboxed(nb, cwd=path.parent.resolve(), timeout=timeout, record_book=rb, limits=limits,
                       unsafe_no_sandbox=unsafe_no_sandbox)
    outcomes = {o.task: o for o in executed_outcomes(nb)[0]}
    _, errors = executed_outcomes(nb)
    for vd in grade_executed(nb, rb, tasks=tasks):
        oc = outcomes.get(vd.task)
        message = vd.message or (oc.message if oc is not None else "")
        flagged = [f for f in vd.flags if f.code in ("tampered", "no_answer_record", "variant_mismatch")]
        if flagged and vd.passed is False and oc is not None and oc.passed:
            message = f"{message} — the notebook's own check said passed, the grader's did not ({flagged[0].code})"
        ename = oc.ename if oc is not None and not vd.passed else ""
        result.tasks.append(TaskOutcome(vd.task, vd.passed, vd.points, message.strip(" —"), ename, vd.score))
        result.flags += vd.flags
    result.errors = errors
    for e in ex.events:
        if e.kind in ("kernel_died", "output_truncated"):
            result.errors.append((e.cell, e.message))
    release = release_for(path)
    if release is not None:
        from .flags import behaviour_flags

        try:
            result.flags += behaviour_flags(release, read_nb(path))
        except Exception as exc:  # the scan never stops the check
            result.flags.append(_flag("code_unreadable", f"the notebook's cells could not be scanned "
                                                         f"({type(exc).__name__})"))
    return result


def _flag(code, message):
    from .common import Flag

    return Flag(code, message)


def print_check(result: CheckResult, out=print) -> None:
    from ..i18n import t as _t  # the loop below names its task t

    out(f"{result.path}:")
    if result.problem:
        out(f"  ✗ {result.problem}")
        return
    for t in result.tasks:
        out(_t("  {mark} {task} ({points:g} pt)", mark="✓" if t.passed else "✗", task=t.task, points=t.points)
            + ("" if t.passed else f" — {t.message}"))
    for cid, err in result.errors:
        out(_t("  ✗ cell {cell}: {error}", cell=cid, error=err))
    if result.flags:
        from .flags import flag_meaning

        out(_t("  the teacher will see these flags:"))
        for f in result.flags:
            out(f"  ! {f}")
        for code in dict.fromkeys(f.code for f in result.flags):
            out(_t("    {code} — {meaning}", code=code, meaning=_t(flag_meaning(code))))
    n = sum(t.passed for t in result.tasks)
    out(_t("  {n} of {total} task(s) passed", n=n, total=len(result.tasks))
        + (_t("; {n} cell error(s)", n=len(result.errors)) if result.errors else ""))
