"""What a check cell reports about the kernel it runs in, while the instructor grades (kernel side).

:func:`evidence` is called by :func:`aerophoto.checks.check_task` when ``AEROPHOTO_GRADING`` is set and goes
into the answer record (:mod:`.wire`) beside the submitted values.  It is evidence, not proof — the kernel is
the student's — and it is cheap: exception handling and IPython event hooks changed by cell code, the checks
(:mod:`aerophoto.checks`, :mod:`.verdict`, :mod:`.wire`) or the tasks replaced, the ``AEROPHOTO_*``
environment.  The score never depends on it (the trusted check runs in the instructor's process); it names
what a student did.  Kernel side: the standard library only; it imports nothing of aerophoto (it looks at
the modules already loaded).
"""

from __future__ import annotations

import os
import sys

_OURS = ("IPython", "ipykernel", "matplotlib", "matplotlib_inline", "ipympl", "ipywidgets", "comm", "aerophoto",
         "traitlets", "jupyter_client", "debugpy", "zmq", "tornado", "asyncio")
_SHELL_METHODS = ("showtraceback", "_showtraceback", "showsyntaxerror", "run_cell", "run_cell_async",
                  "run_code", "run_ast_nodes", "should_run_async", "transform_cell", "excepthook")
_WATCHED = {
    "aerophoto.checks": ("check_task", "check_value", "check_count", "check_values", "check_bool", "check_choice",
                         "task_passed", "_check_one", "_settle", "_fail", "_pass", "_emit", "_task_values",
                         "WrongAnswer"),
    "aerophoto.course.verdict": ("value_verdict", "count_verdict", "values_verdict", "bool_verdict",
                                 "choice_verdict", "answer_call", "close", "_diagnose", "_paired", "_numbers",
                                 "_whole_set_mistake", "Verdict"),
    "aerophoto.course.wire": ("encode_answers", "scalar", "is_bool", "as_sequence", "_plain"),
}
"""The functions a check cell runs, by module: one replaced by cell code is reported (``patched``)."""


def _module_of(obj) -> str:
    mod = getattr(obj, "__module__", None)
    if mod is None:
        mod = getattr(getattr(obj, "__func__", None), "__module__", None)
    return str(mod or "")


def _ours(obj) -> bool:
    mod = _module_of(obj)
    return bool(mod) and mod != "__main__" and mod.split(".")[0] in _OURS


def _name(obj) -> str:
    return str(getattr(obj, "__qualname__", None) or getattr(obj, "__name__", None) or type(obj).__name__)[:60]


def _patched_functions(module, names, filename) -> list[str]:
    out = []
    for n in names:
        obj = getattr(module, n, None)
        if obj is None:
            out.append(f"{module.__name__}.{n} (deleted)")
            continue
        code = getattr(obj, "__code__", None)
        if code is not None and code.co_filename != filename:
            out.append(f"{module.__name__}.{n}")
        elif code is None and isinstance(obj, type) and obj.__module__ != module.__name__:
            out.append(f"{module.__name__}.{n}")
    return out


def evidence(task=None) -> dict:
    """Plain data about the kernel: hooks, replaced functions, the AEROPHOTO_* environment."""
    ev: dict = {"env": {k: os.environ.get(k) for k in ("AEROPHOTO_RECORD_BOOK", "AEROPHOTO_HOME",
                                                      "AEROPHOTO_GRADING")}}
    try:
        from IPython import get_ipython

        ip = get_ipython()
    except Exception:
        ip = None
    if ip is not None:
        ev["custom_exc"] = [_name(e) for e in (getattr(ip, "custom_exceptions", ()) or ())]
        hooks = []
        for event, callbacks in (getattr(getattr(ip, "events", None), "callbacks", {}) or {}).items():
            hooks += [f"{event}: {_name(cb)}" for cb in callbacks if not _ours(cb)]
        ev["event_hooks"] = hooks
        overrides = [n for n in _SHELL_METHODS if n in vars(ip) and not _ours(vars(ip)[n])]
        for n in _SHELL_METHODS:
            fn = getattr(type(ip), n, None)
            if fn is not None and not _ours(fn):
                overrides.append(f"{type(ip).__name__}.{n}")
        ev["shell_overrides"] = overrides
    hook = sys.excepthook
    ev["excepthook"] = hook is not sys.__excepthook__ and not _ours(hook)
    patched = []
    for name, functions in _WATCHED.items():
        module = sys.modules.get(name)
        if module is not None:
            patched += _patched_functions(module, functions, module.__file__)
    checks = sys.modules.get("aerophoto.checks")
    if checks is not None:
        if getattr(checks, "check_task", None) is not None and checks.check_task.__globals__ is not vars(checks):
            patched.append("aerophoto.checks (module replaced)")
    if task is not None:
        cls = type(task)
        mod = sys.modules.get(cls.__module__)
        fname = getattr(mod, "__file__", None)
        for n in ("answers", "slips", "hidden"):
            fn = getattr(cls, n, None)
            code = getattr(fn, "__code__", None)
            if code is not None and fname and code.co_filename not in (fname, _base_file()):
                patched.append(f"{cls.__module__}.{cls.__name__}.{n}")
        tasks = sys.modules.get("aerophoto.tasks")
        if tasks is not None:
            patched += _patched_functions(tasks, ("get", "answers", "chapter_tasks"), tasks.__file__)
    ev["patched"] = patched
    return ev


def _base_file() -> str:
    base = sys.modules.get("aerophoto.tasks.base")
    return getattr(base, "__file__", "") or ""
