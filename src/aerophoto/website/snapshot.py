"""The web book's static pictures of widgets: what a live demo or a tool looks like at its starting values.

The web book (:mod:`aerophoto.website`) executes every chapter at build time in a kernel whose IPython runs
:func:`install` first (the builder's ``IPYTHONDIR`` profile, ``exec_lines``).  From then on every ipywidgets
widget the chapter displays — a :class:`aerophoto.widgets.LiveDemo`'s layout, a measuring tool — is shown as
plain HTML instead of a widget view that needs a kernel: each ipympl canvas becomes a PNG of its figure (with a text
alternative) and comes first, each control follows as ``label: value`` on one line with the value in the book's
number format (:mod:`aerophoto.i18n.numfmt`), then the HTML widgets' HTML (a demo's hint, legend, status, table);
buttons and a demo's own title (the page's caption names the demo) are dropped.
The chapter's code and its notebooks are not changed: outside that kernel nothing of this runs.

The HTML carries ``data-aerophoto-live="demo"`` on a live demo's picture (its layout has the CSS class
``aerophoto-demo``) and ``data-aerophoto-live="tool"`` on other widgets, so that the builder can add the
"open live" line under it.
"""

from __future__ import annotations

import base64
import html
import io

__all__ = ["install", "widget_html", "figure_png", "MARK"]

_GROUP_HEAD = __import__("re").compile(r"<b>[^<]{0,60}</b>")
#: the attribute the builder looks for (value ``demo`` or ``tool``)
MARK = "data-aerophoto-live"


def figure_png(fig, dpi: int = 100) -> bytes:
    """The figure drawn once more with Agg, as PNG bytes (the figure stays open)."""
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    return buf.getvalue()


def _figure_alt(fig) -> str:
    """A text alternative from the figure's own texts: its suptitle and each Axes' title and axis labels."""
    parts = []
    sup = getattr(fig, "_suptitle", None)
    if sup is not None and sup.get_text().strip():
        parts.append(sup.get_text().strip())
    for ax in fig.axes:
        bits = [ax.get_title().strip(), ax.get_xlabel().strip(), ax.get_ylabel().strip()]
        bits = [b for b in bits if b]
        if bits:
            parts.append(" / ".join(bits))
    return "; ".join(parts) or "figure"


def _number(x, readout_format: str | None = None) -> str:
    """``x`` in the book's number format, with the decimals of a slider's ``readout_format`` (".1f", "d") if given."""
    import re

    from ..i18n.numfmt import fmt_number, fmt_value

    try:
        m = re.fullmatch(r"\.?(\d*)([fd])", readout_format or "")
        if m:
            return fmt_number(x, int(m.group(1) or 0) if m.group(2) == "f" else 0)
        return fmt_value(x)
    except (TypeError, ValueError):
        return html.escape(str(x))


def _control(wd) -> str:
    """A control as ``label: value`` (a range as ``lo – hi``), or '' for one without a value to show."""
    import ipywidgets as w

    label = html.escape(str(getattr(wd, "description", "") or ""))
    if isinstance(wd, (w.Button, w.Textarea, w.Text, w.Password)):
        value = getattr(wd, "value", "")
        return f"<pre class='aerophoto-snapshot-text'>{html.escape(value)}</pre>" if isinstance(wd, w.Textarea) and value else ""
    if isinstance(wd, (w.Dropdown, w.RadioButtons, w.ToggleButtons, w.Select, w.SelectionSlider)):
        value = html.escape(str(wd.label if getattr(wd, "label", None) is not None else wd.value))
    elif isinstance(wd, (w.Checkbox, w.ToggleButton)):
        from ..i18n import t

        value = t("yes") if wd.value else t("no")
    elif isinstance(getattr(wd, "value", None), (tuple, list)):
        value = " – ".join(_number(v, getattr(wd, "readout_format", None)) for v in wd.value)
    elif hasattr(wd, "value"):
        value = _number(wd.value, getattr(wd, "readout_format", None))
    else:
        return ""
    sep = ": " if label else ""
    return f"<span class='aerophoto-snapshot-control'>{label}{sep}<b>{value}</b></span>"


def _output_html(out) -> str:
    """What an Output widget holds, as HTML (images inline, text preformatted)."""
    parts = []
    for o in getattr(out, "outputs", ()):
        data = o.get("data", {}) if isinstance(o, dict) else {}
        if "text/html" in data:
            parts.append(data["text/html"])
        elif "image/png" in data:
            parts.append(f"<img src='data:image/png;base64,{data['image/png']}' alt='figure'>")
        elif "text/plain" in data:
            parts.append(f"<pre>{html.escape(data['text/plain'])}</pre>")
        elif o.get("output_type") == "stream":
            parts.append(f"<pre>{html.escape(o.get('text', ''))}</pre>")
    return "".join(parts)


def _walk(wd, alt, items: list) -> None:
    """Collect a widget tree's parts in order: ``("figure" | "control" | "html", html)``."""
    import ipywidgets as w

    fig = getattr(wd, "figure", None)
    if isinstance(wd, w.DOMWidget) and fig is not None and hasattr(fig, "savefig"):  # an ipympl canvas
        data = base64.b64encode(figure_png(fig)).decode("ascii")
        text = html.escape(alt or _figure_alt(fig), quote=True)
        items.append(("figure", f"<img class='aerophoto-snapshot-figure' src='data:image/png;base64,{data}' "
                                f"alt='{text}'>"))
    elif isinstance(wd, w.Box):
        for c in wd.children:
            _walk(c, alt, items)
    elif isinstance(wd, (w.HTML, w.HTMLMath)):
        value = str(wd.value or "")
        # a demo's title (the page's caption names the demo) and its sliders' group headings ("<b>Camera</b>":
        # the values' line has no groups) are left out
        if value.strip() and "<h3" not in value and not _GROUP_HEAD.fullmatch(value.strip()):
            items.append(("html", value))
    elif isinstance(wd, w.Label):
        items.append(("html", f"<span>{html.escape(str(wd.value))}</span>"))
    elif isinstance(wd, w.Output):
        out = _output_html(wd)
        if out:
            items.append(("figure" if "<img" in out else "html", out))
    elif isinstance(wd, w.DOMWidget):
        text = _control(wd)
        if text:
            items.append(("control", text))


def widget_html(wd, *, alt: str | None = None) -> str:
    """The static HTML of a widget tree (see the module notes): its figures first, then the controls' starting
    values on one line, then its HTML (hint, legend, tables) in order; ``alt`` overrides the figures' text
    alternative."""
    items: list = []
    _walk(wd, alt, items)
    figures = "".join(h for k, h in items if k == "figure")
    controls = [h for k, h in items if k == "control"]
    rest = "".join(h for k, h in items if k == "html")
    line = (f"<div class='aerophoto-snapshot-controls'>{' · '.join(controls)}</div>" if controls else "")
    return figures + line + rest


def _bundle(wd):
    """The mime bundle the display of a widget gets in the build kernel."""
    import ipywidgets as w

    classes = tuple(getattr(wd, "_dom_classes", ()) or ())
    kind = "demo" if "aerophoto-demo" in classes else "tool"
    title = ""
    if kind == "demo":
        for c in getattr(wd, "children", ()):
            if isinstance(c, w.HTML) and "<h3" in str(c.value):
                import re

                title = re.sub(r"<[^>]+>", "", str(c.value)).strip()
                break
    body = widget_html(wd)
    div = (f"<div class='aerophoto-snapshot' {MARK}='{kind}' data-aerophoto-title='{html.escape(title, quote=True)}'>"
           f"{body}</div>")
    return {"text/html": div, "text/plain": f"[{kind}: {title or type(wd).__name__}]"}


def install(ip=None) -> None:
    """Show every ipywidgets widget displayed from now on as its static HTML (in the build kernel only)."""
    if ip is None:
        from IPython import get_ipython

        ip = get_ipython()
    if ip is None:
        return
    import ipywidgets as w

    ip.display_formatter.mimebundle_formatter.for_type(w.Widget, lambda wd, include=None, exclude=None: _bundle(wd))
