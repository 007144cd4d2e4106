"""The browser book (JupyterLite) under test: a static server on 127.0.0.1, a trap for any request that would
leave the machine, and chromium pointed at both.

Used by ``tests/browser/test_lite*.py`` and ``benchmarks/bench_lite.py`` (which loads this file by path next to
``harness.py``), so it depends on Playwright and the standard library only — no pytest.

* :class:`SiteServer` serves a built site (``aerophoto-course lite``) on 127.0.0.1 from a thread of this
  process, as any static host would (``.wasm`` as ``application/wasm``), and counts the requests.
* :class:`EgressTrap` is the browser's proxy: chromium sends every request for a host that is not the loopback
  address there (loopback goes direct), the trap records it and answers 403 — so a request that would leave
  the machine, from the page, a web worker or a service worker, is seen and never sent.
* :func:`launch` starts Debian's chromium with the trap as its proxy; :func:`new_lite_page` opens a fresh
  context (fresh browser storage) that also records every request Playwright sees.
"""

from __future__ import annotations

import contextlib
import functools
import http.server
import json
import socket
import socketserver
import threading
import time
from dataclasses import dataclass, field
from pathlib import Path
from urllib.parse import urlsplit

try:  # imported as tests.browser.lite_harness, or loaded by path beside harness.py (benchmarks)
    from . import harness as h
except ImportError:  # pragma: no cover - the benchmark's way
    import harness as h  # type: ignore[no-redef]

ROOT = h.ROOT
SITE = ROOT / "_site"
MANIFEST = "aerophoto-lite.json"
LOOPBACK = ("127.0.0.1", "localhost", "[::1]", "::1")
#: the browser's own background services: Debian's chromium asks these with nothing but about:blank open,
#: whatever the flags (component updates, sign-in, time, autofill; chromium 150 also www.google.com and
#: android.clients.google.com — seen with about:blank alone, 2026-12-02); the trap refuses them like any other,
#: and the tests fail for any other host
BROWSER_OWN = ("update.googleapis.com", "accounts.google.com", "clients2.google.com", "content-autofill.googleapis.com",
               "optimizationguide-pa.googleapis.com", "redirector.gvt1.com", "edgedl.me.gvt1.com", "www.google.com",
               "android.clients.google.com")
#: quieten what can be quietened of that traffic
QUIET_ARGS = ["--disable-features=AutofillServerCommunication,OptimizationHints,OptimizationGuideModelDownloading,"
              "MediaRouter,Translate", "--no-pings", "--disable-domain-reliability",
              "--disable-client-side-phishing-detection", "--safebrowsing-disable-auto-update", "--disable-default-apps"]
#: the lite note that ``aerophoto.setup`` shows in the browser book (src/aerophoto/book.py)
LITE_NOTE_TEXT = "running in your browser"


def demos_sized() -> bool:
    """Whether the browser book's demos are sized by their page: only with anywidget in the browser's kernel
    (the site carries it, deploy/lite/browser-wheels.txt; were ``aerophoto.lite.NOT_IN_BROWSER`` to leave it out,
    the figures would keep their natural size there)."""
    from aerophoto import lite

    return "anywidget" not in lite.NOT_IN_BROWSER


def site_problem(site: Path = SITE) -> str | None:
    """Why ``site`` is not a built browser book, or None."""
    if not (site / MANIFEST).is_file() or not (site / "jupyter-lite.json").is_file():
        return f"no built site at {site} (build it with `aerophoto-course lite --out {site}`)"
    return None


# --------------------------------------------------------------------------------------------- the server
class _Handler(http.server.SimpleHTTPRequestHandler):
    extensions_map = {**http.server.SimpleHTTPRequestHandler.extensions_map,
                      ".wasm": "application/wasm", ".mjs": "text/javascript", ".js": "text/javascript",
                      ".json": "application/json", ".whl": "application/octet-stream",
                      ".zip": "application/zip", ".ipynb": "application/json"}

    def log_message(self, fmt, *args):  # quiet; the server counts instead
        # log_request's arguments are (request line, status, size); an error's are others: status 0 then
        status = int(args[1]) if len(args) >= 2 and str(args[1]).isdigit() else 0
        self.server.requests.append((self.command, self.path, time.monotonic(), status))

    def end_headers(self):
        # like a plain static host: no caching instructions; the browser's own cache decides
        super().end_headers()


class _Threading(socketserver.ThreadingMixIn, http.server.HTTPServer):
    daemon_threads = True
    allow_reuse_address = True


class SiteServer:
    """A built site served on 127.0.0.1 (a free port) from a thread."""

    def __init__(self, site: Path = SITE):
        self.site = Path(site)
        handler = functools.partial(_Handler, directory=str(self.site))
        self.httpd = _Threading(("127.0.0.1", 0), handler)
        self.httpd.requests = []
        self.port = self.httpd.server_address[1]
        self.thread = threading.Thread(target=self.httpd.serve_forever, name="lite-site", daemon=True)

    @property
    def base(self) -> str:
        return f"http://127.0.0.1:{self.port}"

    @property
    def requests(self) -> list:
        return self.httpd.requests

    def lab_url(self, notebook: str, workspace: str | None = None) -> str:
        return f"{self.base}/lab/index.html?path={notebook}"

    def start(self) -> "SiteServer":
        self.thread.start()
        return self

    def shutdown_kernels(self) -> None:
        """Nothing to do: the kernels live in the pages (the desktop servers' interface, for shared code)."""

    def stop(self) -> None:
        self.httpd.shutdown()
        self.httpd.server_close()
        self.thread.join(timeout=10)

    def __enter__(self):
        return self.start()

    def __exit__(self, *exc):
        self.stop()


# --------------------------------------------------------------------------------------------- the trap
class EgressTrap:
    """A proxy that refuses everything and remembers what it was asked for (the first line of each request)."""

    def __init__(self):
        self.sock = socket.socket(socket.AF_INET, socket.SOCK_STREAM)
        self.sock.setsockopt(socket.SOL_SOCKET, socket.SO_REUSEADDR, 1)
        self.sock.bind(("127.0.0.1", 0))
        self.sock.listen(16)
        self.sock.settimeout(0.2)
        self.port = self.sock.getsockname()[1]
        self.attempts: list[str] = []
        #: connections closed before they sent anything (no request: not in ``attempts``)
        self.unused_connections = 0
        self._stop = threading.Event()
        self.thread = threading.Thread(target=self._serve, name="egress-trap", daemon=True)

    def _serve(self) -> None:
        while not self._stop.is_set():
            try:
                conn, _ = self.sock.accept()
            except (TimeoutError, socket.timeout):
                continue
            except OSError:
                return
            with contextlib.closing(conn):
                conn.settimeout(2)
                try:
                    data = conn.recv(4096)
                except OSError:
                    data = b"(no request line)"  # silent for 2 s: counted as a request for an unknown host
                if not data:
                    # closed without a byte: chromium's preconnected socket to its proxy, dropped unused when idle
                    # (seen under CI's load as attempts '' from chapter 16 and the hand-in page) — asks for nothing
                    self.unused_connections += 1
                    continue
                self.attempts.append(data.split(b"\r\n", 1)[0].decode("latin-1"))
                with contextlib.suppress(OSError):
                    conn.sendall(b"HTTP/1.1 403 Forbidden\r\nContent-Length: 0\r\nConnection: close\r\n\r\n")

    def start(self) -> "EgressTrap":
        self.thread.start()
        return self

    def host(self, attempt: str) -> str:
        """The host a request line asked for (``CONNECT host:443 …`` or ``GET http://host/… …``)."""
        parts = attempt.split()
        target = parts[1] if len(parts) > 1 else ""
        if "://" in target:
            return urlsplit(target).hostname or ""
        return target.rsplit(":", 1)[0]

    def from_the_site(self) -> list[str]:
        """The attempts that are not the browser's own background traffic (:data:`BROWSER_OWN`)."""
        return [a for a in self.attempts if self.host(a) not in BROWSER_OWN]

    def stop(self) -> None:
        self._stop.set()
        self.thread.join(timeout=5)
        self.sock.close()


# --------------------------------------------------------------------------------------------- browser
def launch(playwright, trap: EgressTrap, *, headless: bool = True):
    """Debian's chromium with every non-loopback request sent to ``trap`` (chromium never proxies loopback)."""
    path = h.chromium_path()
    if path is None:
        raise RuntimeError(f"chromium is not installed; install it with: {h.INSTALL_HINT}")
    args = [*h.CHROMIUM_ARGS, *QUIET_ARGS, f"--proxy-server=http://127.0.0.1:{trap.port}"]
    return playwright.chromium.launch(executable_path=path, headless=headless, args=args)


def assert_no_egress(trap: "EgressTrap", requests: "RequestLog", where: str) -> None:
    """Fail (AssertionError) when a request left the loopback address or reached the trap for another host."""
    assert not requests.outside(), f"{where}: requests left the loopback address: {requests.outside()[:5]}"
    assert not trap.from_the_site(), f"{where}: requests for other hosts reached the trap: {trap.from_the_site()[:5]}"


@contextlib.contextmanager
def trapped_chromium(site: Path):
    """``(server, trap, browser)``: ``site`` served on 127.0.0.1, and chromium whose every non-loopback request goes
    to the trap; everything is stopped on leaving."""
    from playwright.sync_api import sync_playwright

    trap = EgressTrap().start()
    server = SiteServer(site).start()
    pw = sync_playwright().start()
    browser = launch(pw, trap)
    try:
        yield server, trap, browser
    finally:
        browser.close()
        pw.stop()
        server.stop()
        trap.stop()


@dataclass
class RequestLog:
    """Every request Playwright sees in a context (pages, workers): URL, and whether it left the loopback."""

    urls: list = field(default_factory=list)

    def attach(self, context) -> "RequestLog":
        context.on("request", lambda req: self.urls.append(req.url))
        return self

    def outside(self) -> list[str]:
        out = []
        for url in self.urls:
            parts = urlsplit(url)
            if parts.scheme in ("data", "blob", "about", "chrome-extension"):
                continue
            if parts.hostname not in LOOPBACK:
                out.append(url)
        return out


def new_lite_page(browser, *, instrument: bool = True):
    """A fresh context (empty browser storage) at the projector size; returns (page, console log, request log)."""
    page, log = h.new_page(browser, instrument=instrument)
    requests = RequestLog().attach(page.context)
    return page, log, requests


def open_notebook(page, site: SiteServer, notebook: str) -> float:
    """Open ``notebook`` in the site's JupyterLab, wait until its kernel is idle; returns the seconds it took."""
    t0 = time.monotonic()
    h.open_lab_notebook(page, site, notebook)
    return time.monotonic() - t0


def run_each_cell(page) -> list:
    """Run the code cells one at a time, top to bottom, going on past a failing cell (a student answering as they
    go, or "run all" without its stop on error); returns ``[(cell id, ename, evalue)]`` of the cells that failed.

    Each cell's execution finishes (the kernel idle) before the next starts, so a failing check cell cancels
    nothing queued behind it.
    """
    page.evaluate("""() => { const k = window.jupyterapp.shell.currentWidget.sessionContext.session.kernel;
        window.__aeroCellErrors = [];
        k.anyMessage.connect((_, a) => { const m = a.msg;
          if (m.header.msg_type === 'execute_reply' && m.content.status !== 'ok')
            window.__aeroCellErrors.push([String(m.content.ename), String(m.content.evalue || '').slice(0, 300)]); });
    }""")
    n = page.evaluate("() => window.jupyterapp.shell.currentWidget.content.widgets.length")
    failed = []
    for i in range(n):
        cell = page.evaluate("""async (i) => { const app = window.jupyterapp; const nb = app.shell.currentWidget.content;
            const c = nb.widgets[i]; if (c.model.type !== 'code') return null;
            nb.activeCellIndex = i; const before = window.__aeroCellErrors.length;
            await app.commands.execute('notebook:run-cell');
            const e = window.__aeroCellErrors.slice(before); return [c.model.id, e]; }""", i)
        if cell is None:
            continue
        h.lab_kernel_idle(page)
        cid, errors = cell
        failed.extend((cid, ename, evalue) for ename, evalue in errors)
    return failed


def save_notebook(page) -> None:
    """File ▸ Save: into the browser's storage (IndexedDB)."""
    page.evaluate("() => window.jupyterapp.commands.execute('docmanager:save')")
    page.wait_for_function(
        "() => { const w = window.jupyterapp.shell.currentWidget; return !!w && !w.context.model.dirty; }",
        timeout=h.T_MOVE, polling=100)


def built_site(dest: Path, *, log=None) -> tuple[Path, float]:
    """Build the site into ``dest`` once (``aerophoto-course lite``), under a file lock so that parallel test
    workers share one build; returns (site, seconds this call spent building, 0 if another had built it)."""
    import fcntl

    from aerophoto import lite

    dest = Path(dest)
    dest.parent.mkdir(parents=True, exist_ok=True)
    with open(dest.parent / (dest.name + ".lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if site_problem(dest) is None:
            return dest, 0.0
        t0 = time.monotonic()
        lite.build(dest, out=log or (lambda _text: None))
        return dest, time.monotonic() - t0


def manifest(site: Path = SITE) -> dict:
    return json.loads((Path(site) / MANIFEST).read_text(encoding="utf-8"))
