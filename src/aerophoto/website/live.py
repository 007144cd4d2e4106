"""What the browser book (:mod:`aerophoto.lite`) carries for the web book: the Russian chapters, the lecture pages
as apps, and a browser cache that works on any static host.

* :func:`russian_contents` — beside the workbook, ``ru/NN_slug.ipynb``: the same student book with the Russian
  prose of ``notebooks/ru/NN_slug.md`` and ``aerophoto.setup(..., lang="ru")``
  (:func:`aerophoto.i18n.prose.russian_notebook`; an untranslated cell stays English), the glossary
  (``ru/glossary.ipynb``), the lecture index and the lecture pages in Russian (``ru/lectures.ipynb``, ``ru/lectures/``).
* :func:`lecture_apps` — the lecture pages' code cells collapsed (``jupyter.source_hidden``), so that a lecture page
  opened in the site's single-document view (``notebooks/index.html?path=lectures/…``) shows its demos, not code.
* :func:`cache_service_worker` — JupyterLite's service worker (``service-worker.js``) fetches every file again on
  every visit (without ``enableCache``), and a plain static host sends no caching headers, so a second visit
  fetched the whole 69 MB again.  The site's service worker answers first, cache-first, for the files of this
  build that never change while the build stays — Pyodide and its wheels (``static/pyodide/``), the front end's
  bundles (``build/``) and extensions (``extensions/``) — from a Cache Storage named after the build (a new build,
  a new name; the old cache is deleted when the new worker takes over).  Everything else (the contents, the
  settings, the drive) goes to JupyterLite's own handler as before.
"""

from __future__ import annotations

import hashlib
import json
from pathlib import Path

__all__ = ["russian_contents", "lecture_apps", "cache_service_worker", "CACHED", "SW_MARK"]

#: the folders of the browser book served cache-first (paths relative to the site's root)
CACHED = ("static/pyodide/", "build/", "extensions/")
#: the first line of the patched service worker (its presence tells the patch is applied)
SW_MARK = "/* aerophoto: cache-first for this build's immutable files */"


def _read(path: Path) -> dict:
    return json.loads(path.read_text(encoding="utf-8"))


def _write(path: Path, nb: dict) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(nb, ensure_ascii=False, indent=1) + "\n", encoding="utf-8")


def russian_contents(contents: Path, notebooks: Path, out=print) -> list[str]:
    """Write the Russian chapters and lecture pages under ``contents/ru`` (see the module notes); returns their
    names relative to ``contents``."""
    from .. import book
    from ..i18n import prose

    names = []
    for ch in book.CHAPTERS:
        src = Path(contents) / ch.notebook
        blocks = prose.read_translations(prose.translation_path(Path(notebooks) / ch.notebook))
        nb, _untranslated = prose.russian_notebook(_read(src), blocks)
        _write(Path(contents) / "ru" / ch.notebook, nb)
        names.append(f"ru/{ch.notebook}")
    pages = [Path(contents) / book.GLOSSARY_PAGE, Path(contents) / book.LECTURE_INDEX]
    for page in [*pages, *sorted((Path(contents) / book.LECTURES_DIR).glob("*.ipynb"))]:
        rel = page.relative_to(contents)
        blocks = prose.read_translations(prose.translation_path(Path(notebooks) / rel))  # ru/glossary.md, ru/lectures.md…
        nb, _u = prose.russian_notebook(_read(page), blocks)
        _write(Path(contents) / "ru" / rel, nb)
        names.append(f"ru/{rel.as_posix()}")
    out(f"lite: contents: {len(names)} Russian notebooks and lecture pages under ru/")
    return names


def lecture_apps(contents: Path) -> int:
    """Collapse the code cells of every lecture page under ``contents`` (both languages); returns how many pages."""
    from .. import book

    n = 0
    for page in sorted(Path(contents).rglob(f"{book.LECTURES_DIR}/*.ipynb")):
        nb = _read(page)
        for c in nb.get("cells", []):
            if c.get("cell_type") == "code":
                c.setdefault("metadata", {}).setdefault("jupyter", {})["source_hidden"] = True
        _write(page, nb)
        n += 1
    return n


def _build_key(site: Path) -> str:
    """A digest of the cached folders' file names and sizes (a new build of other files gets a new cache)."""
    h = hashlib.sha256()
    for part in CACHED:
        for p in sorted((site / part).rglob("*")):
            if p.is_file():
                h.update(f"{p.relative_to(site).as_posix()}\0{p.stat().st_size}\0".encode())
                if p.suffix in (".js", ".json"):
                    h.update(hashlib.sha256(p.read_bytes()).digest())
    return h.hexdigest()[:16]


def _worker_js(key: str) -> str:
    prefixes = json.dumps(list(CACHED))
    return f"""{SW_MARK}
const AERO_CACHE = "aerophoto-{key}";
const AERO_ROOT = new URL("./", self.location.href).pathname;
const AERO_PREFIXES = {prefixes}.map((p) => AERO_ROOT + p);
self.addEventListener("fetch", (event) => {{
  const request = event.request;
  const url = new URL(request.url);
  if (request.method !== "GET" || url.origin !== self.location.origin || request.headers.has("range")
      || !AERO_PREFIXES.some((p) => url.pathname.startsWith(p))) return;
  event.stopImmediatePropagation();
  event.respondWith((async () => {{
    const cache = await caches.open(AERO_CACHE);
    const hit = await cache.match(request);
    if (hit) return hit;
    const response = await fetch(request);
    if (response.status === 200 && response.type === "basic") event.waitUntil(cache.put(request, response.clone()));
    return response;
  }})());
}});
self.addEventListener("activate", (event) => {{
  event.waitUntil(caches.keys().then((keys) => Promise.all(
    keys.filter((k) => k.startsWith("aerophoto-") && k !== AERO_CACHE).map((k) => caches.delete(k)))));
}});
"""


def cache_service_worker(site: Path) -> dict:
    """Put the site's cache-first handler in front of JupyterLite's service worker (see the module notes); returns
    ``{"file": …, "cache": …, "cached": […]}`` for the manifest.  Idempotent."""
    from ..lite import LiteBuildError

    sw = Path(site) / "service-worker.js"
    if not sw.is_file():
        raise LiteBuildError("the browser book has no service-worker.js (jupyterlite-core 0.6.4 writes one)")
    text = sw.read_text(encoding="utf-8")
    if text.startswith(SW_MARK):
        text = text.split("\n/* jupyterlite */\n", 1)[1]
    if 'addEventListener("fetch"' not in text:
        raise LiteBuildError("service-worker.js has no fetch handler: is it jupyterlite-core 0.6.4's?")
    key = _build_key(Path(site))
    sw.write_text(_worker_js(key) + "\n/* jupyterlite */\n" + text, encoding="utf-8")
    return {"file": "service-worker.js", "cache": f"aerophoto-{key}", "cached": list(CACHED)}
