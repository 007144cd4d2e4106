"""The web book's build tools: Sphinx in an environment of its own, MathJax and axe-core from npm, the PDF printer.

* :func:`sphinx_bin` — ``deploy/site/requirements.txt`` (Sphinx 9.0.4, myst-nb 1.4.0, sphinx-book-theme 1.4.0, every
  file hash-checked, ``--no-deps --only-binary``) in a virtual environment kept in the cache under the
  requirements' digest, made by the same code as the browser book's tools (:func:`aerophoto.lite.tools_venv`).
* :func:`npm_assets` — ``deploy/site/package-lock.json`` (npm ``mathjax`` 3.2.2 and ``axe-core`` 4.14.1; npm checks
  each file's sha512) through ``npm ci`` into the cache; the site serves its own MathJax, never a CDN's.
* :func:`sphinx_build` — ``sphinx-build -b html|singlehtml`` with a clean environment (``SOURCE_DATE_EPOCH`` fixed).
* :func:`print_pdf` — a book's single page printed to PDF by Debian's chromium (Playwright, as the browser tests
  drive it): the page as the site shows it, MathJax typeset, one chapter per printed page run.
"""

from __future__ import annotations

import html
import os
import shutil
import time
from pathlib import Path

from ..lite import LiteBuildError, _run, npm_ci, tools_venv

__all__ = ["deploy_dir", "sphinx_bin", "npm_assets", "sphinx_build", "print_pdf", "copy_mathjax", "SiteBuildError",
           "SOURCE_DATE_EPOCH"]

#: fixed timestamps for the tools that write one (the site's bytes do not depend on when it was built)
SOURCE_DATE_EPOCH = "499162500"


class SiteBuildError(LiteBuildError):
    """The web book could not be built (the message says which step and why)."""


def deploy_dir(root: Path) -> Path:
    """``deploy/site`` of the checkout: the build tools' pins and the npm lock file."""
    d = Path(root) / "deploy" / "site"
    if not (d / "requirements.txt").is_file():
        raise SiteBuildError(f"{d}/requirements.txt is missing: aerophoto-course site builds from a source checkout")
    return d


def sphinx_bin(deploy: Path, cache: Path, out=print) -> Path:
    """The ``bin/`` of the site's build environment (see the module notes)."""
    try:
        return tools_venv(deploy, cache, lambda text: out(text.replace("lite:", "site:", 1)))
    except LiteBuildError as exc:
        raise SiteBuildError(str(exc).replace("deploy/lite", "deploy/site")) from None


def npm_assets(deploy: Path, cache: Path, out=print) -> Path:
    """``node_modules`` of deploy/site's lock (``npm ci``, cached under the lock's digest)."""
    try:
        return npm_ci(deploy, cache, what="site: MathJax and axe-core", out=out) / "node_modules"
    except LiteBuildError as exc:
        raise SiteBuildError(str(exc)) from None


#: the parts of MathJax 3's es5 build the site serves: the TeX-to-SVG component and what it may load later
_MATHJAX_PARTS = ("tex-svg.js", "input/tex/extensions", "a11y", "ui", "sre/sre-node.js")


def copy_mathjax(node_modules: Path, dest: Path) -> None:
    """MathJax's TeX → SVG build (no web fonts needed) into ``dest`` (the site's ``_assets/mathjax``)."""
    es5 = node_modules / "mathjax" / "es5"
    if not (es5 / "tex-svg.js").is_file():
        raise SiteBuildError(f"{es5}/tex-svg.js is missing (npm mathjax 3.2.2)")
    dest.mkdir(parents=True, exist_ok=True)
    for part in _MATHJAX_PARTS:
        src = es5 / part
        if src.is_dir():
            shutil.copytree(src, dest / part, dirs_exist_ok=True)
        elif src.is_file():
            (dest / part).parent.mkdir(parents=True, exist_ok=True)
            shutil.copy2(src, dest / part)
    shutil.copy2(node_modules / "mathjax" / "LICENSE", dest / "LICENSE")


def sphinx_build(bindir: Path, src: Path, dest: Path, *, builder: str = "html", jobs: int = 2, out=print) -> float:
    """``sphinx-build -b builder src dest`` (warnings printed, not fatal); returns its seconds."""
    env = {k: v for k, v in os.environ.items() if not k.startswith(("PYTHON", "JUPYTER"))}
    env.update(SOURCE_DATE_EPOCH=SOURCE_DATE_EPOCH, PYTHONHASHSEED="0", LC_ALL="C.UTF-8",
               PATH=f"{bindir}{os.pathsep}{env.get('PATH', '')}")
    t0 = time.monotonic()
    log = _run([bindir / "sphinx-build", "-b", builder, "-q", "-j", str(jobs), "-d", dest.parent / f".doctrees-{dest.name}",
                src, dest], env=env, what=f"sphinx-build -b {builder} ({src.name})")
    seconds = time.monotonic() - t0
    warnings = [ln for ln in log.splitlines() if "WARNING" in ln]
    out(f"site: sphinx-build -b {builder} {src.name} in {seconds:.0f} s ({len(warnings)} warnings)")
    for ln in warnings[:20]:
        out(f"  {ln}")
    return seconds


def print_pdf(html_file: Path, pdf: Path, *, title: str, out=print) -> float:
    """Print a single-page book (``sphinx-build -b singlehtml``) to ``pdf`` with Debian's chromium; returns seconds."""
    from playwright.sync_api import sync_playwright

    chromium = shutil.which("chromium") or "/usr/bin/chromium"
    if not Path(chromium).exists():
        raise SiteBuildError("chromium is not installed (the PDF is printed by it): apt-get install -y chromium")
    t0 = time.monotonic()
    with sync_playwright() as pw:
        browser = pw.chromium.launch(executable_path=chromium, args=["--no-sandbox", "--disable-gpu"])
        try:
            page = browser.new_page()
            page.route("**/*", lambda route: route.continue_() if route.request.url.startswith("file:")
                       else route.abort())
            page.goto(html_file.resolve().as_uri(), wait_until="load", timeout=300_000)
            page.evaluate("""async () => {
                document.querySelectorAll('img').forEach((i) => { i.loading = 'eager'; });
                await Promise.all([...document.images].map((i) => i.complete ? null
                    : new Promise((r) => { i.onload = i.onerror = r; })));
                if (window.MathJax && MathJax.startup && MathJax.startup.promise) await MathJax.startup.promise;
            }""")
            page.pdf(path=str(pdf), format="A4", print_background=True, display_header_footer=True,
                     header_template="<span></span>",
                     footer_template=f"<div style='font-size:8px;width:100%;text-align:center'>{html.escape(title)} · "
                                     "<span class='pageNumber'></span></div>",
                     margin={"top": "16mm", "bottom": "18mm", "left": "16mm", "right": "16mm"})
        finally:
            browser.close()
    seconds = time.monotonic() - t0
    out(f"site: printed {pdf.name} ({pdf.stat().st_size / 1e6:.1f} MB) in {seconds:.0f} s")
    return seconds
