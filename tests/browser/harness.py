"""Real-browser harness: JupyterLab and Voilà servers, Debian's chromium, and the demo probes.

Used by the browser tests (``tests/browser/``) and by ``benchmarks/bench_browser.py``
(which loads this file by path), so it depends on Playwright and the standard
library only — no pytest.

* :class:`LabServer` / :class:`VoilaServer` start a server from the running
  Python's environment on 127.0.0.1, a free port and a random token, with
  private config/runtime/data/settings/workspace directories and a private
  ``AEROPHOTO_HOME``; :meth:`Server.stop` shuts it down through its REST API
  (which also stops its kernels), then terminates the whole process group, so
  nothing is left running.
* :func:`launch_chromium` starts Debian's ``/usr/bin/chromium`` through
  Playwright (never ``playwright install``).
* :func:`open_lab_notebook`, :func:`run_all_cells`, :func:`open_voila` bring a
  chapter on screen; :class:`DemoProbe` finds a live demo's sliders, canvas and
  table, moves a slider with the keyboard and reports what changed.
* :data:`INSTRUMENT_JS` timestamps, inside the page, every key press and every
  painted change of a figure (see :func:`latency_of_moves` for the method).
"""

from __future__ import annotations

import contextlib
import io
import json
import os
import secrets
import shutil
import signal
import socket
import subprocess
import sys
import tempfile
import time
import urllib.error
import urllib.request
from dataclasses import dataclass, field
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
NOTEBOOKS = ROOT / "notebooks"
ARTIFACTS = ROOT / "artifacts"

CHROMIUM = os.environ.get("AEROPHOTO_CHROMIUM", "/usr/bin/chromium")
CHROMIUM_ARGS = [
    "--no-sandbox",
    "--disable-gpu",
    "--disable-background-networking",
    "--disable-component-update",
    "--disable-sync",
    "--no-first-run",
    "--disable-quic",
]
INSTALL_HINT = "apt-get install -y chromium"
#: the projector size the demos are laid out for
VIEWPORT = {"width": 1280, "height": 800}

#: generous timeouts (ms): the machine has 2 shared cores
T_SERVER_S = 180
T_PAGE = 120_000
T_RUN = 300_000
T_MOVE = 60_000


def chromium_path() -> str | None:
    """The chromium executable to drive, or None when it is not installed."""
    p = Path(CHROMIUM)
    if p.is_file() and os.access(p, os.X_OK):
        return str(p)
    found = shutil.which("chromium")
    return found


def free_port() -> int:
    with contextlib.closing(socket.socket(socket.AF_INET, socket.SOCK_STREAM)) as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def _bin_python() -> str:
    return sys.executable


# --------------------------------------------------------------------------- servers
class Server:
    """A Jupyter-family server in its own process group, with private directories."""

    kind = "server"

    def __init__(self, root_dir: Path = NOTEBOOKS, *, log_dir: Path | None = None, extra_args=()):
        self.root_dir = Path(root_dir)
        self.extra_args = list(extra_args)
        self.port = free_port()
        self.token = secrets.token_hex(16)
        self.tmp = Path(tempfile.mkdtemp(prefix=f"aerophoto-{self.kind}-"))
        self.home = self.tmp / "aerophoto-home"
        self.home.mkdir()
        self.log_path = (log_dir or self.tmp) / f"{self.kind}-{self.port}.log"
        self.proc: subprocess.Popen | None = None
        self._log = None

    @property
    def base(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    def env(self) -> dict:
        env = dict(os.environ)
        for k in ("MPLBACKEND", "AEROPHOTO_RECORD_BOOK", "JUPYTER_PATH", "JUPYTER_CONFIG_PATH"):
            env.pop(k, None)
        d = self.tmp
        for sub in ("config", "runtime", "data", "settings", "workspaces", "ipython"):
            (d / sub).mkdir(exist_ok=True)
        env.update(
            AEROPHOTO_HOME=str(self.home),
            JUPYTER_CONFIG_DIR=str(d / "config"),
            JUPYTER_RUNTIME_DIR=str(d / "runtime"),
            JUPYTER_DATA_DIR=str(d / "data"),
            JUPYTERLAB_SETTINGS_DIR=str(d / "settings"),
            JUPYTERLAB_WORKSPACES_DIR=str(d / "workspaces"),
            IPYTHONDIR=str(d / "ipython"),
            JUPYTER_PLATFORM_DIRS="1",
            PYTHONUNBUFFERED="1",
        )
        return env

    def command(self) -> list[str]:
        raise NotImplementedError

    def ready_url(self) -> str:
        raise NotImplementedError

    def cwd(self) -> Path:
        return self.root_dir

    def start(self) -> "Server":
        self._log = open(self.log_path, "wb")
        self.proc = subprocess.Popen(self.command(), cwd=self.cwd(), env=self.env(), stdout=self._log,
                                     stderr=subprocess.STDOUT, stdin=subprocess.DEVNULL, start_new_session=True)
        deadline = time.monotonic() + T_SERVER_S
        last = None
        while time.monotonic() < deadline:
            if self.proc.poll() is not None:
                raise RuntimeError(f"{self.kind} exited with {self.proc.returncode} while starting:\n{self.log_tail()}")
            try:
                with urllib.request.urlopen(self.ready_url(), timeout=10) as r:
                    if r.status == 200:
                        return self
            except (urllib.error.URLError, ConnectionError, TimeoutError, OSError) as exc:
                last = exc
            time.sleep(0.25)  # polling a socket that is not listening yet: nothing to await
        self.stop()
        raise RuntimeError(f"{self.kind} did not answer within {T_SERVER_S} s ({last}):\n{self.log_tail()}")

    def kernel_pids(self) -> list[int]:
        """Process ids of the kernels this server runs (ipykernel processes of its group)."""
        import psutil

        if self.proc is None:
            return []
        pids = []
        for p in psutil.Process(self.proc.pid).children(recursive=True):
            try:
                if any("ipykernel" in part for part in p.cmdline()):
                    pids.append(p.pid)
            except psutil.Error:
                continue
        return pids

    def log_text(self) -> str:
        try:
            return self.log_path.read_text(encoding="utf-8", errors="replace")
        except OSError:
            return ""

    def log_tail(self, n: int = 60) -> str:
        return "\n".join(self.log_text().splitlines()[-n:])

    def _graceful(self) -> bool:
        """Ask the server to shut down (and stop its kernels); False when it has no way to be asked."""
        return False

    def stop(self) -> None:
        p = self.proc
        if p is not None and p.poll() is None:
            asked = False
            with contextlib.suppress(Exception):
                asked = self._graceful()
            if asked:  # a server with no shutdown request (Voilà) goes straight to SIGTERM below
                try:
                    p.wait(timeout=30)
                except subprocess.TimeoutExpired:
                    pass
        if p is not None:
            # the whole group: kernels and their children too
            for sig in (signal.SIGTERM, signal.SIGKILL):
                try:
                    os.killpg(p.pid, sig)
                except ProcessLookupError:
                    break
                try:
                    p.wait(timeout=20)
                except subprocess.TimeoutExpired:
                    continue
                # the leader is gone; make sure no member of the group survives
                with contextlib.suppress(ProcessLookupError):
                    os.killpg(p.pid, signal.SIGKILL)
                break
        if self._log is not None:
            self._log.close()
            self._log = None
        self.proc = None

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.stop()
        shutil.rmtree(self.tmp, ignore_errors=True)


class LabServer(Server):
    """JupyterLab on 127.0.0.1 with (a copy of) the notebooks folder as its root.

    By default the root is a fresh copy of ``notebooks/`` in the server's private folder: JupyterLab saves
    the notebooks it has open (autosave, every 120 s), and a test or benchmark that ran long enough wrote a
    notebook with its outputs back into the repository.
    """

    kind = "lab"

    def __init__(self, root_dir: Path | None = None, **kw):
        super().__init__(root_dir or NOTEBOOKS, **kw)
        if root_dir is None:
            copy = self.tmp / "notebooks"
            shutil.copytree(NOTEBOOKS, copy, ignore=shutil.ignore_patterns(".ipynb_checkpoints"))
            self.root_dir = copy

    def env(self) -> dict:
        env = super().env()
        d = self.tmp
        # no "Jupyter news" toast, no network fetches, all cells attached to the DOM
        (d / "config" / "jupyter_server_config.json").write_text(json.dumps({
            "LabApp": {"news_url": None, "expose_app_in_browser": True, "check_for_updates_class":
                       "jupyterlab.handlers.announcements.NeverCheckForUpdate"},
        }), encoding="utf-8")
        settings = {
            "@jupyterlab/apputils-extension/notification.jupyterlab-settings":
                {"fetchNews": "false", "checkForUpdates": False},
            "@jupyterlab/notebook-extension/tracker.jupyterlab-settings": {"windowingMode": "none"},
            "@jupyterlab/extensionmanager-extension/plugin.jupyterlab-settings": {"enabled": False},
        }
        for rel, value in settings.items():
            f = d / "settings" / rel
            f.parent.mkdir(parents=True, exist_ok=True)
            f.write_text(json.dumps(value), encoding="utf-8")
        return env

    def command(self) -> list[str]:
        d = self.tmp
        return [
            _bin_python(), "-m", "jupyterlab", "--no-browser", "--allow-root",
            "--ServerApp.ip=127.0.0.1", f"--ServerApp.port={self.port}", "--ServerApp.port_retries=0",
            f"--IdentityProvider.token={self.token}", f"--ServerApp.root_dir={self.root_dir}",
            f"--LabApp.workspaces_dir={d / 'workspaces'}", f"--LabApp.user_settings_dir={d / 'settings'}",
            "--LabApp.expose_app_in_browser=True", *self.extra_args,
        ]

    def ready_url(self) -> str:
        return f"{self.base}/api/status?token={self.token}"

    def _graceful(self) -> bool:
        req = urllib.request.Request(f"{self.base}/api/shutdown", method="POST",
                                     headers={"Authorization": f"token {self.token}"})
        urllib.request.urlopen(req, timeout=20).close()
        return True

    def _api(self, path: str, method: str = "GET"):
        req = urllib.request.Request(f"{self.base}{path}", method=method,
                                     headers={"Authorization": f"token {self.token}"})
        with urllib.request.urlopen(req, timeout=60) as r:
            body = r.read()
        return json.loads(body) if body else None

    def shutdown_kernels(self) -> None:
        """Shut down every running kernel (after a test, so kernels do not pile up)."""
        for k in self._api("/api/kernels") or []:
            with contextlib.suppress(urllib.error.HTTPError):
                self._api(f"/api/kernels/{k['id']}", method="DELETE")

    def lab_url(self, notebook: str, workspace: str | None = None) -> str:
        ws = workspace or f"t{secrets.token_hex(6)}"
        return f"{self.base}/lab/workspaces/{ws}/tree/{notebook}?reset&token={self.token}"


class StudentLabServer(LabServer):
    """The student's JupyterLab exactly as the README starts it: ``aerophoto-course lab NOTEBOOK -- …``.

    ``root_dir`` is the folder the student works in (it holds ``workbook/``); the server options of
    :class:`LabServer` (address, port, token, private settings) follow the ``--``.
    """

    kind = "student-lab"

    def __init__(self, root_dir: Path, notebook: str = "workbook/00_start_here.ipynb", **kw):
        super().__init__(root_dir, **kw)
        self.notebook = notebook

    def command(self) -> list[str]:
        lab = super().command()
        assert lab[1:3] == ["-m", "jupyterlab"], lab
        return [_bin_python(), "-m", "aerophoto.course", "lab", self.notebook, "--", *lab[3:]]


def lab_chrome(page) -> dict:
    """What JupyterLab offers around the notebook: main menus, notebook toolbar buttons, side-bar tabs (titles)."""
    return page.evaluate("""() => ({
      menus: Array.from(document.querySelectorAll('.lm-MenuBar-itemLabel')).map((e) => e.textContent.trim()),
      toolbar: Array.from(document.querySelectorAll('.jp-NotebookPanel-toolbar [title], .jp-NotebookPanel-toolbar button'))
               .map((e) => ((e.getAttribute('title') || '') + ' ' + e.textContent).trim()).filter((t) => t),
      sidebar: Array.from(document.querySelectorAll('.jp-SideBar .lm-TabBar-tab'))
               .map((e) => e.getAttribute('title') || e.textContent.trim()),
    })""")


class VoilaServer(Server):
    """Voilà serving the notebooks folder, started from the repository's top folder.

    It runs ``voila notebooks/`` from the top folder exactly as the README
    documents, so the repository's ``voila.json`` is the configuration under
    test; only the address, port and token are added here.
    """

    kind = "voila"

    def __init__(self, root_dir: Path = NOTEBOOKS, *, cwd: Path = ROOT, **kw):
        super().__init__(root_dir, **kw)
        self._cwd = Path(cwd)

    def cwd(self) -> Path:
        return self._cwd

    def command(self) -> list[str]:
        return [
            _bin_python(), "-m", "voila", os.path.relpath(self.root_dir, self._cwd), "--no-browser",
            "--Voila.ip=127.0.0.1", f"--port={self.port}", f"--token={self.token}", *self.extra_args,
        ]

    def ready_url(self) -> str:
        return f"{self.base}/voila/tree?token={self.token}"

    def render_url(self, notebook: str) -> str:
        return f"{self.base}/voila/render/{notebook}?token={self.token}"


# --------------------------------------------------------------------------- browser
def launch_chromium(playwright, *, headless: bool = True):
    path = chromium_path()
    if path is None:
        raise RuntimeError(f"chromium is not installed; install it with: {INSTALL_HINT}")
    return playwright.chromium.launch(executable_path=path, headless=headless, args=CHROMIUM_ARGS)


#: In-page instrumentation, installed before any page script runs.
#:
#: * every keydown is timestamped (capture phase, so before the slider sees it);
#: * every drawImage onto a visible ipympl canvas (ipympl copies its offscreen
#:   canvas onto the visible one when a new PNG from the kernel has loaded) and
#:   every <img> that appears and finishes decoding inside a watched output
#:   (the naive inline-PNG version) is a *figure change*; its paint time is the
#:   next requestAnimationFrame callback, i.e. the frame that shows it.
INSTRUMENT_JS = r"""
(() => {
  if (window.__aero) return;
  const A = window.__aero = {keys: [], paints: [], draws: 0, msgs: [], frames: new Set()};
  document.addEventListener('keydown', (e) => { A.keys.push(performance.now()); }, true);
  // every message arriving on a WebSocket (the kernel's channels): its time and size, for the benchmarks'
  // split of a move into kernel + transport, decode, paint (Jupyter's services assign ws.onmessage)
  const wsd = Object.getOwnPropertyDescriptor(WebSocket.prototype, 'onmessage');
  if (wsd && wsd.set && wsd.get) {
    Object.defineProperty(WebSocket.prototype, 'onmessage', {
      configurable: true, enumerable: wsd.enumerable,
      get() { return wsd.get.call(this); },
      set(h) {
        const wrapped = typeof h === 'function' ? function (ev) {
          try { const d = ev.data; A.msgs.push({t: performance.now(), n: (d && (d.byteLength || d.size || d.length)) || 0}); }
          catch (e) { /* never break the page */ }
          return h.call(this, ev);
        } : h;
        wsd.set.call(this, wrapped);
      },
    });
  }
  const markPaint = (kind) => {
    const t0 = performance.now();
    requestAnimationFrame(() => { A.paints.push({kind, changed: t0, painted: performance.now()}); });
  };
  const orig = CanvasRenderingContext2D.prototype.drawImage;
  CanvasRenderingContext2D.prototype.drawImage = function (...args) {
    const r = orig.apply(this, args);
    try {
      const c = this.canvas;
      if (c && c.isConnected && c.closest('.jupyter-matplotlib-canvas-div')) { A.draws++; markPaint('canvas'); }
      // ipympl's offscreen canvas takes each frame from the kernel as an image: remember the frame's width
      else if (c && !c.isConnected && args[0] instanceof HTMLImageElement) { c.__aeroFrameW = args[0].naturalWidth; A.frames.add(c); }
    } catch (e) { /* never break the page */ }
    return r;
  };
  const seen = new WeakSet();
  const watchImg = (img) => {
    if (seen.has(img)) return;
    seen.add(img);
    const done = () => markPaint('img');
    if (img.complete && img.naturalWidth) { img.decode().then(done, done); }
    else { img.addEventListener('load', () => img.decode().then(done, done), {once: true}); }
  };
  new MutationObserver((muts) => {
    for (const m of muts) for (const n of m.addedNodes) {
      if (n.nodeType !== 1) continue;
      const imgs = n.tagName === 'IMG' ? [n] : n.querySelectorAll('img');
      for (const img of imgs) if (img.closest('.aerophoto-naive')) watchImg(img);
    }
  }).observe(document, {childList: true, subtree: true});
})();
"""


@dataclass
class ConsoleLog:
    """Browser console errors and uncaught page errors of one page."""

    errors: list = field(default_factory=list)

    #: messages from third-party code, not ours, that appear in a clean session:
    #: (substring, why it is harmless)
    IGNORED = (
        ("favicon.ico", "a missing icon"),
        ("cdn.jsdelivr.net/npm/@fortawesome", "Voilà's lab template links Font Awesome from a CDN; offline only "
                                              "the icons are missing"),
        ("/voila/api/shutdown/", "Voilà's page-unload beacon carries no XSRF token and gets 403; the kernel of "
                                 "a closed page is culled instead (voila.json)"),
        ("Error setting state: Failed to execute 'drawImage' on 'CanvasRenderingContext2D': The HTMLImageElement "
         "provided is in the 'broken' state", "ipympl's front end, now and then on a busy machine: a frame's image "
         "is drawn before it decoded (known upstream: matplotlib/matplotlib#19116, matplotlib/ipympl#472); the "
         "next frame repaints, and the tests check that the picture did change"),
        ("/api/contents/.aerophoto/all.json", "the browser book (JupyterLite) looks for a static listing of the "
                                              "drive's folder that remembers the record-book number, which lives in "
                                              "browser storage only: a 404 that jupyterlite/jupyterlite#770 calls "
                                              "harmless (no indexed content)"),
        ("/api/contents/Untitled%20Folder/all.json", "the same folder being made: JupyterLite makes a new folder "
                                                     "as \"Untitled Folder\" and renames it"),
    )

    def attach(self, page) -> "ConsoleLog":
        page.on("console", self._on_console)
        page.on("pageerror", lambda exc: self.errors.append(f"pageerror: {exc}"))
        return self

    def _on_console(self, msg) -> None:
        if msg.type == "error":
            loc = msg.location or {}
            self.errors.append(f"console.error: {msg.text} ({loc.get('url', '')}:{loc.get('lineNumber', '')})")

    def relevant(self) -> list[str]:
        return [e for e in self.errors if not any(s in e for s, _why in self.IGNORED)]


def new_page(browser, *, instrument: bool = True):
    """A fresh context and page at the projector size, with the console recorded."""
    ctx = browser.new_context(viewport=VIEWPORT, device_scale_factor=1)
    ctx.set_default_timeout(T_PAGE)
    if instrument:
        ctx.add_init_script(INSTRUMENT_JS)
    page = ctx.new_page()
    log = ConsoleLog().attach(page)
    return page, log


# --------------------------------------------------------------------------- JupyterLab
def open_lab_notebook(page, server: LabServer, notebook: str) -> None:
    """Open ``notebook`` in a fresh workspace and wait until its kernel is ready."""
    page.goto(server.lab_url(notebook), wait_until="domcontentloaded")
    wait_lab_notebook(page, notebook)


def wait_lab_notebook(page, notebook: str, *, timeout: int = T_RUN) -> None:
    """Wait until the page's JupyterLab shows ``notebook`` with its kernel idle (at most ``timeout`` ms); tag its
    cells with their ids."""
    page.wait_for_function(
        """(name) => {
          const app = window.jupyterapp; if (!app || !app.shell) return false;
          const w = app.shell.currentWidget;
          if (!w || !w.context || !w.context.path.endsWith(name) || !w.content) return false;
          const s = w.sessionContext;
          return !!(s && s.session && s.session.kernel && s.session.kernel.status === 'idle'
                    && w.content.widgets.length > 0);
        }""",
        arg=notebook, timeout=timeout, polling=250,
    )
    # tag every cell's node with its stable id so selectors can find a demo cell
    page.evaluate("""() => {
      const nb = window.jupyterapp.shell.currentWidget.content;
      nb.widgets.forEach((c) => { c.node.dataset.aeroCellId = c.model.id; });
    }""")


def run_all_cells(page, *, timeout: int = T_RUN) -> None:
    """Run → Run All Cells, then wait (at most ``timeout`` ms) until every code cell ran and the kernel is idle; a
    timeout says where the run stands (:func:`lab_run_state`)."""
    from playwright.sync_api import TimeoutError as PlaywrightTimeout

    # a kernel that dies is restarted by the server: Run All's cells after it never run, so the wait counts restarts
    page.evaluate("""() => {
      const k = window.jupyterapp.shell.currentWidget.sessionContext.session.kernel;
      window.__aeroRestarts = [];
      k.statusChanged.connect((_, s) => { if (['restarting', 'autorestarting', 'dead'].includes(s))
                                            window.__aeroRestarts.push(s); });
    }""")
    # the command's promise settles when Run All has gone through the notebook (or stopped at a failing cell)
    page.evaluate("() => window.jupyterapp.commands.execute('notebook:run-all-cells')")
    try:
        done = page.wait_for_function(
            """() => {
          const w = window.jupyterapp.shell.currentWidget;
          const k = w.sessionContext.session && w.sessionContext.session.kernel;
          if ((window.__aeroRestarts || []).length) return 'restarted';
          if (!k || k.status !== 'idle') return false;
          // a failing cell stops "run all": done, and the error output is reported by the caller
          if (w.content.node.querySelector('.jp-OutputArea-output[data-mime-type="application/vnd.jupyter.stderr"]'))
            return true;
          return w.content.widgets.every((c) => c.model.type !== 'code'
              || (c.model.executionCount !== null && c.model.executionCount !== undefined
                  && !c.node.querySelector('.jp-InputArea-prompt') ?.textContent.includes('*')));
        }""",
            timeout=timeout, polling=500,
        )
    except PlaywrightTimeout:
        raise AssertionError(f"Run All did not finish in {timeout / 1000:.0f} s: {lab_run_state(page)}") from None
    if done.json_value() == "restarted":
        raise AssertionError(f"the kernel died during Run All ({page.evaluate('window.__aeroRestarts')}): "
                             f"{lab_run_state(page)}")


def lab_run_state(page) -> dict:
    """Where a notebook's Run All stands: the kernel's status, the code cells run, running (*) and waiting, the
    first cell not run (its index and first line), the last output text on the page — for a timeout's message."""
    return page.evaluate("""() => {
      const w = window.jupyterapp.shell.currentWidget;
      const k = w && w.sessionContext.session && w.sessionContext.session.kernel;
      const code = w ? w.content.widgets.filter((c) => c.model.type === 'code') : [];
      const prompt = (c) => (c.node.querySelector('.jp-InputArea-prompt') || {}).textContent || '';
      const run = code.filter((c) => c.model.executionCount !== null && c.model.executionCount !== undefined);
      const busy = code.filter((c) => prompt(c).includes('*'));
      const first = code.findIndex((c) => c.model.executionCount === null || c.model.executionCount === undefined
                                          || prompt(c).includes('*'));
      const outs = Array.from(document.querySelectorAll('.jp-OutputArea-output')).map((o) => o.innerText.trim())
                        .filter((t) => t);
      return {kernel: k ? k.status : null, code_cells: code.length, run: run.length, running: busy.length,
              first_not_done: first < 0 ? null : [first, code[first].model.sharedModel.getSource().split('\\n')[0]],
              last_output: outs.length ? outs[outs.length - 1].slice(0, 300) : null};
    }""")


def lab_kernel_idle(page) -> None:
    page.wait_for_function(
        """() => { const w = window.jupyterapp.shell.currentWidget;
                   const k = w && w.sessionContext.session && w.sessionContext.session.kernel;
                   return !!k && k.status === 'idle'; }""",
        timeout=T_MOVE, polling=100,
    )


def lab_demo_root(page, cell_id: str):
    return page.locator(f'[data-aero-cell-id="{cell_id}"] .aerophoto-demo').first


#: a stderr output (JupyterLab and Voilà draw it in a pink box; an error's traceback has this type too)
STDERR = '.jp-OutputArea-output[data-mime-type="application/vnd.jupyter.stderr"]'


def error_outputs(page, scope=None) -> list[str]:
    """Error outputs, and stderr outputs carrying a traceback, an error or a warning, on the page.

    JupyterLab and Voilà render an error (traceback) with the stderr mime type too.  The rule for
    stderr text is that of tests/notebooks/test_notebooks.py.
    """
    root = scope or page
    texts = [t.strip()[:800] for t in root.locator(STDERR).all_inner_texts()
             if any(word in t for word in ("Traceback", "Error", "Warning", "error", "warning"))]
    # a widget that failed to render shows this text instead of the widget
    for t in root.locator(".jp-OutputArea-output").all_inner_texts():
        if "Error displaying widget" in t or "Error rendering output" in t:
            texts.append(t.strip()[:800])
    return texts


# --------------------------------------------------------------------------- Voilà
def open_voila(page, server: VoilaServer, notebook: str, *, timeout: int = T_RUN) -> None:
    """Load a chapter as a Voilà app and wait until every cell ran and widgets rendered."""
    page.goto(server.render_url(notebook), wait_until="domcontentloaded", timeout=timeout)
    wait_voila_ready(page, timeout=timeout)


def wait_voila_ready(page, *, timeout: int = T_RUN) -> None:
    """Wait until a Voilà page has executed every cell and its loading indicator is gone."""
    # Voilà streams the executed cells behind a spinner (#loading) and, after the
    # last one, removes the spinner and shows #rendered_cells (voila_finish)
    page.wait_for_function(
        """() => {
          if (document.readyState !== 'complete' || document.getElementById('loading')) return false;
          const cells = document.getElementById('rendered_cells');
          return !!cells && cells.style.display !== 'none';
        }""",
        timeout=timeout, polling=250,
    )


# --------------------------------------------------------------------------- demos
def _png_pixels(png: bytes):
    from PIL import Image

    return Image.open(io.BytesIO(png)).convert("RGB")


#: a JupyterLab chapter's notebook (the open one)
LAB_NOTEBOOK = ".jp-NotebookPanel:not(.lm-mod-hidden) .jp-Notebook"


def assert_no_sideways_scroll(page, where: str, scroller: str = "document.scrollingElement") -> None:
    """Fail when ``scroller`` (a JavaScript expression for an element; default the page) scrolls sideways."""
    over = page.evaluate(f"() => {{ const e = {scroller}; return e.scrollWidth - e.clientWidth; }}")
    assert over <= 1, f"{where}: the page scrolls sideways by {over} px"


def assert_demo_in_column(probe, column: dict, where: str) -> None:
    """Fail unless the demo's figure and table are displayed and lie within ``column`` (a bounding box) sideways."""
    for what, box in (("figure", probe.canvas().bounding_box()), ("table", probe.table().bounding_box())):
        assert box is not None, f"{where}: the {what} is not displayed"
        assert box["x"] >= column["x"] - 0.5 and box["x"] + box["width"] <= column["x"] + column["width"] + 0.5, (
            f"{where}: the {what} {box} leaves the notebook's column {column}")


def pixel_change(before: bytes, after: bytes) -> float:
    """Fraction of pixels that differ between two screenshots of the same element."""
    from PIL import ImageChops

    a, b = _png_pixels(before), _png_pixels(after)
    if a.size != b.size:
        return 1.0
    diff = ImageChops.difference(a, b).convert("L").point(lambda v: 255 if v > 8 else 0)
    hist = diff.histogram()
    return hist[255] / float(a.size[0] * a.size[1])


def figure_is_drawn(png: bytes) -> bool:
    """True when a screenshot holds a real figure, not a blank canvas."""
    img = _png_pixels(png).convert("L")
    lo, hi = img.getextrema()
    return hi - lo > 64


class DemoProbe:
    """One live demo on screen: its sliders (by label), canvas, table and status line."""

    def __init__(self, page, root, *, sized: bool = True):
        """``sized``: the demo's figure follows the page's size (its page sensor, :mod:`aerophoto.fit`, reports it;
        False where the kernel has no anywidget: the figure keeps its natural size there)."""
        self.page, self.root, self.sized = page, root, sized

    def wait_rendered(self) -> None:
        self.root.wait_for(state="visible", timeout=T_RUN)
        self.canvas().wait_for(state="visible", timeout=T_RUN)
        self.table().wait_for(state="visible", timeout=T_RUN)
        # the first image from the kernel has been painted on the canvas
        self.page.wait_for_function(
            """(el) => { const c = el.querySelector('.jupyter-matplotlib-canvas-div canvas');
                          return !!c && c.width > 50 && c.height > 50; }""",
            arg=self.root.element_handle(), timeout=T_RUN, polling=250,
        )
        self.page.wait_for_function("() => window.__aero && window.__aero.draws > 0", timeout=T_RUN, polling=250)
        # the demo's top at the top of the screen, as a lecturer would scroll it
        self.root.evaluate("(el) => el.scrollIntoView({block: 'start'})")
        if self.sized:
            self.wait_fitted(0)
        else:
            settle(self.page, 400)

    def fit_count(self) -> int:
        """How many times the kernel has sized this demo's figure for the page (its class ``aerophoto-fit-N``)."""
        return int(self.root.evaluate(
            "(el) => Math.max(0, ...Array.from(el.classList).map((c) => /^aerophoto-fit-(\\d+)$/.exec(c))"
            ".filter((m) => m).map((m) => +m[1]))"))

    def wait_fitted(self, after: int) -> None:
        """Wait until the kernel has sized the figure for the page more than ``after`` times (the page reports
        its size, :mod:`aerophoto.fit`) and a frame of that size has reached the canvas (ipympl blanks a resized
        canvas until its next frame), then until the figure is quiet.  The frame may be one pixel wider than the
        canvas: a figure of 847 px at a fractional dpi renders an 848-px frame (chapter 15's block demo in Voilà) —
        a rounding of matplotlib's, the frame of that size all the same."""
        self.page.wait_for_function(
            """([el, n]) => Array.from(el.classList).some((c) => { const m = /^aerophoto-fit-(\\d+)$/.exec(c);
                                                                   return m && +m[1] > n; })""",
            arg=[self.root.element_handle(), after], timeout=T_RUN, polling=100)
        self.page.wait_for_function(
            """(el) => { const c = el.querySelector('.jupyter-matplotlib-canvas-div canvas');
                         return !!c && [...window.__aero.frames].some((f) => f.width === c.width
                                                                            && Math.abs(f.__aeroFrameW - c.width) <= 1); }""",
            arg=self.root.element_handle(), timeout=T_RUN, polling=100)
        settle(self.page, 400)

    def slider(self, label: str):
        return slider_in(self.page, self.root, label)

    def slider_labels(self) -> list[str]:
        return [t.strip() for t in self.root.locator(".widget-slider .widget-label").all_inner_texts()]

    def readout(self, label: str) -> str:
        return self.slider(label).locator(".widget-readout").inner_text().strip()

    def canvas(self):
        return self.root.locator(".jupyter-matplotlib-canvas-div").first

    def table(self):
        return self.root.locator(".aerophoto-table").first

    def table_text(self) -> str:
        return self.table().inner_text()

    def status_text(self) -> str:
        # the demo's status line (⚠ messages from a failed update) is an HTML widget
        return " ".join(t.strip() for t in self.root.locator(".widget-html").all_inner_texts() if "⚠" in t)

    def canvas_png(self) -> bytes:
        return self.canvas().screenshot()

    def draws(self) -> int:
        return int(self.page.evaluate("() => window.__aero.draws"))

    def press(self, label: str, key: str) -> None:
        handle = self.slider(label).locator(".noUi-handle").first
        handle.focus()
        self.page.keyboard.press(key)

    def move(self, label: str, key: str = "ArrowRight") -> dict:
        """Move one slider with the keyboard; wait until the figure and the table changed.

        Returns the readouts, the table texts and the canvas screenshots before and after.
        """
        table0 = self.table_text()
        value0 = self.readout(label)
        png0 = self.canvas_png()
        draws0 = self.draws()
        self.press(label, key)
        self.page.wait_for_function(
            """([el, v0]) => { const r = el.querySelector('.widget-readout');
                               return !!r && r.textContent.trim() !== v0; }""",
            arg=[self.slider(label).element_handle(), value0], timeout=T_MOVE, polling=50,
        )
        self.page.wait_for_function(
            """([el, t0, d0]) => { const t = el.querySelector('.aerophoto-table');
                                   return !!t && t.innerText !== t0 && window.__aero.draws > d0; }""",
            arg=[self.root.element_handle(), table0, draws0], timeout=T_MOVE, polling=50,
        )
        self.wait_idle()
        return {"value_before": value0, "value_after": self.readout(label), "table_before": table0,
                "table_after": self.table_text(), "png_before": png0, "png_after": self.canvas_png()}

    def settle(self, quiet_ms: int = 300) -> None:
        """Wait until the figure has not been redrawn for ``quiet_ms`` (the update has finished)."""
        settle(self.page, quiet_ms)

    def wait_idle(self, quiet_ms: int = 300) -> None:
        """Wait until the demo has no work scheduled (its status line's ``aerophoto-pending`` note, shown while a
        full-resolution picture waits for the slider to rest, is gone), then until the figure has been quiet for
        ``quiet_ms``; done when no work is scheduled then either, else again (a note that arrived while the
        figure settled: its picture is waited for in the same way)."""
        nothing_pending = "(el) => !el.querySelector('.aerophoto-pending')"
        for _ in range(5):
            self.page.wait_for_function(nothing_pending, arg=self.root.element_handle(), timeout=T_MOVE, polling=50)
            self.settle(quiet_ms)
            if self.root.evaluate(nothing_pending):
                return
        raise AssertionError(f"the demo still had work scheduled after five quiet spells of {quiet_ms} ms")


def settle(page, quiet_ms: int = 300) -> None:
    """Wait until no figure change has been painted for ``quiet_ms`` (an update has finished)."""
    page.evaluate(
        """(quiet) => new Promise((resolve) => {
             let n = window.__aero.paints.length, since = performance.now();
             const tick = () => {
               const m = window.__aero.paints.length;
               if (m !== n) { n = m; since = performance.now(); }
               if (performance.now() - since >= quiet) resolve(true); else setTimeout(tick, 25);
             };
             tick();
           })""",
        quiet_ms,
    )


def slider_in(page, root, label: str):
    """The ipywidgets slider labelled exactly ``label`` inside ``root``."""
    return root.locator(".widget-slider").filter(has=page.locator(f'.widget-label:text-is("{label}")')).first


def time_slider_moves(page, slider, n: int, *, keys=("ArrowRight", "ArrowLeft"), after_move=None) -> dict:
    """Move ``slider`` n times with the keyboard (alternating ``keys``) and time each move in the page.

    Latency of one move = (the requestAnimationFrame that follows the first
    figure change after the key press) − (the keydown event), both read from
    ``performance.now()`` in the page (:data:`INSTRUMENT_JS`).  A figure change
    is ipympl copying a freshly received image onto the visible canvas, or a
    new <img> inside ``.aerophoto-naive`` having decoded.  Between moves the
    figure must have been quiet for 300 ms, so moves never overlap.

    Returns ``{"samples_s": [...], "values": [readouts after each move], "split": [...]}``; ``split`` holds per
    move, in ms from the key press, ``frame_ms`` (the largest WebSocket message between the key press and the
    figure change arrived: the kernel's work and the transport), ``drawn_ms`` (ipympl copied the decoded frame
    onto the canvas) and ``painted_ms`` (the frame that shows it), and ``frame_bytes``.
    """
    handle = slider.locator(".noUi-handle").first
    handle.focus()
    samples, values, splits = [], [], []
    for i in range(n):
        k0 = page.evaluate("() => [window.__aero.keys.length, window.__aero.paints.length]")
        page.keyboard.press(keys[i % len(keys)])
        page.wait_for_function(
            """([k, p]) => { const A = window.__aero; if (A.keys.length <= k) return false;
                             const t = A.keys[k]; return A.paints.slice(p).some((x) => x.changed >= t); }""",
            arg=k0, timeout=T_MOVE,
        )
        settle(page)
        if after_move:
            after_move()
        ms = page.evaluate(
            """([k, p]) => { const A = window.__aero; const t = A.keys[k];
                             return A.paints.slice(p).find((x) => x.changed >= t).painted - t; }""",
            k0,
        )
        samples.append(ms / 1000.0)
        values.append(slider.locator(".widget-readout").inner_text().strip())
        splits.append(page.evaluate(
            """([k, p]) => { const A = window.__aero; const t = A.keys[k];
                             const x = A.paints.slice(p).find((q) => q.changed >= t);
                             const m = (A.msgs || []).filter((q) => q.t >= t && q.t <= x.changed);
                             const big = m.reduce((a, q) => (!a || q.n > a.n ? q : a), null);
                             return {frame_ms: big ? big.t - t : null, frame_bytes: big ? big.n : null,
                                     drawn_ms: x.changed - t, painted_ms: x.painted - t}; }""",
            k0,
        ))
    return {"samples_s": samples, "values": values, "split": splits}


def save_screenshot(page, name: str) -> Path:
    ARTIFACTS.mkdir(exist_ok=True)
    path = ARTIFACTS / f"{name}.png"
    page.screenshot(path=str(path), full_page=False)
    return path


def save_png(data: bytes, name: str) -> Path:
    ARTIFACTS.mkdir(exist_ok=True)
    path = ARTIFACTS / f"{name}.png"
    path.write_bytes(data)
    return path
