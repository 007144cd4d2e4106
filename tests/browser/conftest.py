"""Fixtures of the browser tests: chromium through Playwright, JupyterLab and Voilà servers, screenshots.

* Without chromium a developer gets a skip that names the install command; in CI
  (``AEROPHOTO_CI=1``, set by ``.ci/run``) a missing chromium or Playwright fails.
* Screenshots of every demo before and after each slider move go to
  ``artifacts/`` (git-ignored) when a test fails, or always with
  ``AEROPHOTO_SCREENSHOTS=1``.
* The Playwright driver, the browser and the servers live for one test module and
  are shut down after it (servers through their REST API, then their whole
  process group), so no kernel or server outlives the tests.
"""

from __future__ import annotations

import os
import re

import pytest

from . import harness as h

IN_CI = os.environ.get("AEROPHOTO_CI") == "1"
WANT_SCREENSHOTS = os.environ.get("AEROPHOTO_SCREENSHOTS", "") not in ("", "0")


def _unavailable(why: str):
    if IN_CI:
        pytest.fail(f"browser tests cannot run in CI: {why}. .ci/run must install it "
                    f"({h.INSTALL_HINT}; Playwright comes from environment.txt).", pytrace=False)
    pytest.skip(f"browser tests need Debian's chromium and Playwright: {why}; install with `{h.INSTALL_HINT}` "
                "(and `python -m pip install -r environment.txt`), never `playwright install`")


@pytest.fixture(scope="module")
def browser():
    try:
        from playwright.sync_api import sync_playwright
    except ImportError:
        _unavailable("Playwright for Python is not installed")
    if h.chromium_path() is None:
        _unavailable(f"{h.CHROMIUM} not found")
    pw = sync_playwright().start()
    try:
        b = h.launch_chromium(pw)
        try:
            yield b
        finally:
            b.close()
    finally:
        pw.stop()


def _stopped(server) -> None:
    """Stop a server and check that nothing of its process group survived."""
    pid = server.proc.pid if server.proc else None
    server.__exit__(None, None, None)
    if pid is not None:
        try:
            os.killpg(pid, 0)
        except ProcessLookupError:
            return
        raise AssertionError(f"processes of the {server.kind} server (group {pid}) are still running")


@pytest.fixture(scope="module")
def lab_server(browser):
    server = h.LabServer().start()
    yield server
    _stopped(server)


@pytest.fixture
def lab(lab_server):
    """The module's JupyterLab; the kernels a test started are shut down after it."""
    yield lab_server
    lab_server.shutdown_kernels()


@pytest.fixture(scope="module")
def voila(browser):
    server = h.VoilaServer().start()
    yield server
    _stopped(server)


@pytest.hookimpl(wrapper=True, tryfirst=True)
def pytest_runtest_makereport(item, call):
    rep = yield
    setattr(item, f"rep_{rep.when}", rep)
    return rep


class Tab:
    """One browser page of a test, its console log and the screenshots taken on it.

    At the end of the test the screenshots (and, on failure, the viewport as it
    was) are written to artifacts/ when the test failed or AEROPHOTO_SCREENSHOTS=1.
    """

    def __init__(self, browser, test_name: str):
        self.prefix = re.sub(r"[^A-Za-z0-9_.-]+", "_", test_name).strip("_")
        self.page, self.log = h.new_page(browser)
        self.items: list[tuple[str, bytes]] = []

    def add(self, name: str, png: bytes) -> None:
        self.items.append((name, png))

    def finish(self, failed: bool) -> None:
        paths = []
        if failed or WANT_SCREENSHOTS:
            for name, png in self.items:
                paths.append(h.save_png(png, f"{self.prefix}__{name}"))
            if failed:
                try:
                    paths.append(h.save_screenshot(self.page, f"{self.prefix}__at-failure"))
                except Exception:  # the page may have crashed
                    pass
        if paths:
            print(f"\nscreenshots in {h.ARTIFACTS}: {', '.join(p.name for p in paths)}")
        self.page.context.close()


@pytest.fixture
def tab(browser, request):
    t = Tab(browser, request.node.name)
    yield t
    rep = getattr(request.node, "rep_call", None)
    t.finish(failed=rep is not None and rep.failed)
