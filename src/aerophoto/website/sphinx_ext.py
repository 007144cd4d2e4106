"""The web book's Sphinx extension: the bar at the top of every page (run live, course hub, the other language, PDF).

Copied into each book's Sphinx source folder by :mod:`aerophoto.website.project` and loaded there by Sphinx in the
site's own build environment (deploy/site/requirements.txt), which does not have aerophoto: this file imports only
Sphinx and the standard library.  Its settings are the ``aerophoto_site`` configuration value (a dict written into
conf.py):

``live``          page name → the browser book's URL for it, relative to the site's root
``live_default``  the URL for a page without its own (the book's start)
``hub``           page name → the course hub's URL (absolute), for the chapters; {} when no hub is configured
``other``         the other language's folder ("ru" in the English book)
``other_name``    its name in itself ("Русский")
``pdf``           the book's PDF, relative to the site's root; empty when the site is built without the PDFs
``words``         the bar's texts in this book's language
"""

from __future__ import annotations

import html

__all__ = ["setup"]


def _bar(cfg: dict, pagename: str) -> str:
    up = "../" * (pagename.count("/") + 1)  # from the page to the site's root (the book is one folder down)
    words = cfg["words"]
    live = cfg["live"].get(pagename, cfg["live_default"])
    run_text = words["run"] if pagename in cfg["live"] else words["run_book"]
    items = [f'<a class="aerophoto-launch" href="{html.escape(up + live, quote=True)}">▶ {html.escape(run_text)}</a>']
    hub = cfg["hub"].get(pagename)
    if hub:
        items.append(f'<a class="aerophoto-hub" href="{html.escape(hub, quote=True)}">{html.escape(words["hub"])}</a>')
    if cfg.get("pdf"):
        items.append(f'<a class="aerophoto-pdf" href="{html.escape(up + cfg["pdf"], quote=True)}">'
                     f'{html.escape(words["pdf"])}</a>')
    other = f"{up}{cfg['other']}/{pagename}.html"
    items.append(f'<a class="aerophoto-lang" href="{html.escape(other, quote=True)}" hreflang="{cfg["other"]}" '
                 f'lang="{cfg["other"]}">{html.escape(cfg["other_name"])}</a>')
    return f'<nav class="aerophoto-bar" aria-label="{html.escape(words["bar"], quote=True)}">{"".join(items)}</nav>'


def _page(app, pagename, templatename, context, doctree):
    if app.builder.name != "html" or "body" not in context:
        return
    context["body"] = _bar(app.config.aerophoto_site, pagename) + context["body"]


def setup(app):
    app.add_config_value("aerophoto_site", {}, "html")
    app.connect("html-page-context", _page, priority=900)
    return {"parallel_read_safe": True, "parallel_write_safe": True}
