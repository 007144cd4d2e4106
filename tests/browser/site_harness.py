"""The web book under test: one build shared by the test workers, axe-core from the site's npm lock, page probes.

Used by ``tests/browser/test_site.py`` and ``benchmarks/bench_site.py`` (loaded by path beside ``harness.py`` and
``lite_harness.py``), so it depends on Playwright, the standard library and aerophoto only — no pytest.
"""

from __future__ import annotations

import fcntl
import json
import time
from pathlib import Path

try:  # imported as tests.browser.site_harness, or loaded by path (benchmarks)
    from . import lite_harness as L
except ImportError:  # pragma: no cover - the benchmark's way: it loaded lite_harness.py by path first
    import sys

    L = sys.modules["aerophoto_lite_harness"]  # type: ignore[no-redef]

ROOT = L.ROOT


def built_book(dest: Path, lite_site: Path, *, pdf: bool = True, only=None, log=None) -> tuple[Path, float]:
    """Build the web book into ``dest`` once (``aerophoto.website.build``, shipping the browser book ``lite_site``;
    ``pdf``, ``only`` as there), under a file lock so that parallel workers share one build; returns (site, seconds
    this call spent building)."""
    from aerophoto import website

    dest = Path(dest)
    dest.parent.mkdir(parents=True, exist_ok=True)
    with open(dest.parent / (dest.name + ".lock"), "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)
        if (dest / website.MANIFEST).is_file():
            return dest, 0.0
        t0 = time.monotonic()
        website.build(dest, lite_dir=lite_site, pdf=pdf, only=only, out=log or (lambda _text: None))
        return dest, time.monotonic() - t0


def manifest(site: Path) -> dict:
    from aerophoto import website

    return json.loads((Path(site) / website.MANIFEST).read_text(encoding="utf-8"))


def axe_source() -> str:
    """axe-core's ``axe.min.js`` from deploy/site's npm lock (installed into the site's cache by ``npm ci``)."""
    from aerophoto import website
    from aerophoto.website import stack

    node = stack.npm_assets(stack.deploy_dir(ROOT), website.cache_dir(), out=lambda _t: None)
    return (node / "axe-core" / "axe.min.js").read_text(encoding="utf-8")


#: the page's pictures and formulas once it has loaded: every <img> decoded (naturalWidth), its alt text, and
#: MathJax's output (typeset formulas, error nodes, TeX left untypeset)
PAGE_STATE_JS = """async () => {
  const imgs = [...document.querySelectorAll('article img')];
  imgs.forEach((i) => { i.loading = 'eager'; });
  await Promise.all(imgs.map((i) => i.complete ? null : new Promise((r) => { i.onload = i.onerror = r; })));
  if (window.MathJax && MathJax.startup && MathJax.startup.promise) await MathJax.startup.promise;
  const article = document.querySelector('article') || document.body;
  return {
    images: imgs.map((i) => ({src: i.getAttribute('src'), ok: i.complete && i.naturalWidth > 0, alt: i.alt || ''})),
    formulas: document.querySelectorAll('mjx-container').length,
    math_errors: document.querySelectorAll('mjx-merror, [data-mjx-error]').length,
    raw_tex: [...article.querySelectorAll('.math')].filter((m) => !m.querySelector('mjx-container')).length,
    figures: document.querySelectorAll('figure.aerophoto-figure').length,
    title: document.title,
  };
}"""


def run_axe(page, source: str, within: str | None = None) -> list[dict]:
    """axe-core on the page (WCAG 2.x A/AA rules and best practices); returns its violations (id, impact, nodes).

    ``within``: a CSS selector — only that part of the page is checked (a JupyterLab chapter's notebook, not Lab's
    own chrome)."""
    page.add_script_tag(content=source)
    return page.evaluate("""async (within) => {
      const r = await axe.run(within ? {include: [within]} : document, {resultTypes: ['violations']});
      return r.violations.map((v) => ({id: v.id, impact: v.impact, help: v.help,
                                       nodes: v.nodes.slice(0, 3).map((n) => n.target.join(' '))}));
    }""", within)
