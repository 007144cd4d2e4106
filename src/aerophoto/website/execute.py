"""Executing the chapters for the web book: the guide's example (variant 00), English and Russian, cached.

Each notebook is run top to bottom by nbclient in a kernel of the book's own environment (the one this package is
installed in), as a student who has typed nothing would run it: no record-book number anywhere (``AEROPHOTO_HOME``
is an empty folder of the build, ``AEROPHOTO_RECORD_BOOK`` unset), so :func:`aerophoto.setup` shows variant 00, the
guide's worked example, and every graded task stays unanswered ("no answer yet").  The kernel's IPython first runs
:func:`aerophoto.website.snapshot.install`, so every widget is shown as its static picture.  The Russian book runs
:func:`aerophoto.i18n.prose.russian_notebook`'s notebook with ``AEROPHOTO_LANG=ru``.

An executed notebook is kept in the cache under the SHA-256 of what decides its outputs — the notebook as run,
the language, the package's source files (``src/aerophoto``, every ``.py`` and data file), this module and the
snapshot module — so an unchanged chapter is not run again; any change to the package runs every chapter again
(a change anywhere may change a figure).  Kernels run ``jobs`` at a time (default 2: the project's machines have
2 cores).

The kernels of one build share the book's disk cache of heavy data (:mod:`aerophoto.cache`: the test site, the
guide's stereo pair, chapter 07's height model) in ``<cache>/data`` (``AEROPHOTO_CACHE_DIR``), so the Russian book
reads what the English one computed, and the next build what this one did; an entry read equals the value built
bit for bit, so the pages do not depend on it.
"""

from __future__ import annotations

import copy
import hashlib
import json
import os
import re
import tempfile
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

__all__ = ["package_digest", "execution_key", "execute", "execute_all", "unexpected_errors", "ExecutionError",
           "CELL_TIMEOUT_S"]

#: the per-cell limit of a build execution, s (chapter 16's DEMs take ~30 s on the desktop)
CELL_TIMEOUT_S = 900
#: the kernel's first line (IPython ``exec_lines``): widgets become static pictures
_EXEC_LINES = ["import aerophoto.website.snapshot as _aero_snapshot; _aero_snapshot.install(); del _aero_snapshot"]


class ExecutionError(RuntimeError):
    """A chapter failed to execute (the message names the notebook and the cell)."""


def package_digest() -> str:
    """SHA-256 over the package's source: every file under ``src/aerophoto`` except bytecode, in path order (of
    ``website/`` only the two modules the build kernel runs: this one and :mod:`~aerophoto.website.snapshot`; not
    ``lite.py``, the browser book's build)."""
    import aerophoto

    pkg = Path(aerophoto.__file__).resolve().parent
    h = hashlib.sha256()
    for p in sorted(pkg.rglob("*")):
        rel = p.relative_to(pkg).parts
        if (rel[0] == "website" and rel[-1] not in ("snapshot.py", "execute.py")) or rel == ("lite.py",):
            continue  # the site's page making and the browser book's build do not change what a chapter computes
        if p.is_file() and "__pycache__" not in p.parts and p.suffix not in (".pyc",):
            h.update(p.relative_to(pkg).as_posix().encode())
            h.update(b"\0")
            h.update(p.read_bytes())
    return h.hexdigest()


def execution_key(nb: dict, lang: str, digest: str) -> str:
    """The cache key of one execution (see the module notes)."""
    h = hashlib.sha256()
    h.update(json.dumps(nb, sort_keys=True, ensure_ascii=False).encode("utf-8"))
    h.update(lang.encode())
    h.update(digest.encode())
    return h.hexdigest()[:24]


def _profile(tmp: Path) -> Path:
    """An IPython profile folder whose kernel config runs :data:`_EXEC_LINES` first."""
    ipdir = tmp / "ipython"
    prof = ipdir / "profile_default"
    prof.mkdir(parents=True, exist_ok=True)
    (prof / "ipython_kernel_config.py").write_text(f"c.IPKernelApp.exec_lines = {_EXEC_LINES!r}\n", encoding="utf-8")
    return ipdir


def _env(tmp: Path, lang: str, data_cache: Path | None) -> dict:
    env = {k: v for k, v in os.environ.items() if not k.startswith("AEROPHOTO_")}
    home = tmp / "home"
    home.mkdir(parents=True, exist_ok=True)
    env.update(AEROPHOTO_HOME=str(home), AEROPHOTO_LANG=lang, IPYTHONDIR=str(_profile(tmp)),
               MPLBACKEND="module://ipympl.backend_nbagg", PYTHONHASHSEED="0", AEROPHOTO_WEBSITE="1")
    if data_cache is not None:
        env["AEROPHOTO_CACHE_DIR"] = str(data_cache)
    return env


def execute(nb: dict, lang: str, *, cwd: Path, name: str = "notebook", timeout: int = CELL_TIMEOUT_S,
            data_cache: Path | None = None) -> dict:
    """Run ``nb`` (not changed) in a fresh kernel and return the executed copy; raises :class:`ExecutionError`.
    ``data_cache``: the folder of the book's heavy-data cache the kernel uses (None: its own empty home's)."""
    import nbformat
    from nbclient import NotebookClient
    from nbclient.exceptions import CellExecutionError

    run = nbformat.from_dict(copy.deepcopy(nb))
    with tempfile.TemporaryDirectory(prefix="aerophoto-site-run-") as tmp:
        client = NotebookClient(run, timeout=timeout, kernel_name="python3", allow_errors=True,
                                store_widget_state=False, record_timing=False,
                                resources={"metadata": {"path": str(cwd)}})
        try:
            client.execute(env=_env(Path(tmp), lang, data_cache))
        except CellExecutionError as exc:
            raise ExecutionError(f"{name} ({lang}) failed to execute: {str(exc)[:2000]}") from None
    out = json.loads(nbformat.writes(run))
    out.get("metadata", {}).pop("widgets", None)
    failed = unexpected_errors(out)
    if failed:
        raise ExecutionError(f"{name} ({lang}) failed to execute: " + "; ".join(failed))
    return out


def unexpected_errors(nb: dict) -> list[str]:
    """The cells that raised, other than a graded task's check cell (``task-NN-k-check``), which raises by design
    while its task is unanswered (nbgrader reads that as "failed"): ``["cell id: ename: evalue", …]``."""
    bad = []
    for c in nb.get("cells", []):
        cid = str(c.get("id", ""))
        for o in c.get("outputs", []):
            if o.get("output_type") == "error" and not re.fullmatch(r"task-\d\d-\d+-check", cid):
                bad.append(f"{cid}: {o.get('ename')}: {str(o.get('evalue'))[:300]}")
    return bad


def execute_all(jobs_in: list, *, cache: Path, cwd: Path, jobs: int = 2, out=print) -> list[dict]:
    """Execute ``[(name, lang, notebook dict)]``, each from the cache when it holds it; returns the executed
    notebooks in the same order.  Prints one line per notebook run (with its seconds)."""
    digest = package_digest()
    data = Path(cache) / "data"
    data.mkdir(mode=0o700, parents=True, exist_ok=True)  # aerophoto.cache reads no folder others may write
    cache = Path(cache) / "executed"
    cache.mkdir(parents=True, exist_ok=True)

    def one(item):
        name, lang, nb = item
        key = execution_key(nb, lang, digest)
        path = cache / f"{name}.{lang}.{key}.ipynb"
        if path.is_file():
            return json.loads(path.read_text(encoding="utf-8")), False
        t0 = time.monotonic()
        done = execute(nb, lang, cwd=cwd, name=name, data_cache=data)
        tmp = path.with_suffix(".tmp")
        tmp.write_text(json.dumps(done, ensure_ascii=False), encoding="utf-8")
        tmp.replace(path)
        for old in cache.glob(f"{name}.{lang}.*.ipynb"):  # older executions of this chapter: never used again
            if old != path:
                old.unlink(missing_ok=True)
        out(f"site: executed {name} ({lang}) in {time.monotonic() - t0:.0f} s")
        return done, True

    with ThreadPoolExecutor(max_workers=max(1, jobs)) as pool:
        results = list(pool.map(one, jobs_in))
    ran = sum(r[1] for r in results)
    out(f"site: {ran} notebook(s) executed, {len(results) - ran} from the cache")
    return [r[0] for r in results]
