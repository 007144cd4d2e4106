"""The book's HTML tables and text marks: :func:`html_table` (every number by :mod:`aerophoto.i18n.numfmt`),
symbols' subscripts in HTML and in mathtext, legends as HTML beside a live figure, and the notebook's display of
the package's tables.  :mod:`aerophoto.plots` re-exports all of it (``plots.html_table``)."""

from __future__ import annotations

import html as _html
import re

import numpy as np

__all__ = ["html_subscripts", "math_subscripts", "html_table", "register_table_display", "legend_html", "LINK_CSS"]

#: links in the chapters' text underlined, not told apart by colour alone (WCAG 1.4.1; axe-core's link-in-text-block
#: found JupyterLab's and Voilà's plain blue links on the lecture index): written by the setup cell of every page
#: (:func:`aerophoto.setup`)
LINK_CSS = ("<style>.jp-RenderedHTMLCommon a:not(.jp-InternalAnchorLink):not(.anchor-link) "
            "{text-decoration: underline; text-underline-offset: 0.15em;}</style>")


#: a symbol with a subscript in a label: p_x, m_z, λ_t, h_c, m_ЦМР, h_{max} (not words joined by underscores)
_SUBSCRIPT = re.compile(r"(?<![\w\\$])([A-Za-zα-ωΑ-ΩΔ])_(\{[^}]{1,10}\}|[A-Za-z0-9α-ωА-Яа-яЁё.]{1,8}?)"
                        r"(?=[\s,;:()/·=+−–\-²³′″]|$)")
#: mathtext written by :func:`math_subscripts` (read back by :func:`html_subscripts`)
_MATH_SUB = re.compile(r"\$([A-Za-zα-ωΑ-ΩΔ])_\{([^}]{1,10})\}\$")


def html_subscripts(text: str) -> str:
    """Escape ``text`` for HTML with its symbols' subscripts as subscripts: ``p_x, mm`` → ``p<sub>x</sub>, mm``
    (also ``$p_{x}$`` from :func:`math_subscripts`)."""
    out = _MATH_SUB.sub(lambda m: f"{m.group(1)}_{{{m.group(2)}}}", str(text))
    out = _html.escape(out)
    return _SUBSCRIPT.sub(lambda m: f"{m.group(1)}<sub>{m.group(2).strip('{}')}</sub>", out)


def math_subscripts(text):
    """A figure text with its symbols' subscripts in mathtext: ``p_x, mm`` → ``$p_{x}$, mm`` (matplotlib sets the
    subscript); a text already holding ``$`` and anything that is not a str are returned unchanged."""
    if not isinstance(text, str) or "$" in text or "_" not in text:
        return text
    return _SUBSCRIPT.sub(lambda m: f"${m.group(1)}_{{{m.group(2).strip('{}')}}}$", text)


def _cell_format(spec, v, lang):
    """One real number of a table by its column's or row's ``spec``: decimals (int), ``"count"``, ``"scale"``, a
    ``str.format`` spec (``"{:.3g}"``) or a callable."""
    from .i18n.numfmt import fmt_count, fmt_number, fmt_spec

    if callable(spec):
        return spec(v)
    if isinstance(spec, bool):
        raise ValueError(f"precision = {spec!r} is not a precision; expected decimals, 'count', 'scale' or a spec")
    if isinstance(spec, int):
        return fmt_number(v, spec, lang=lang)
    if spec == "count":
        return fmt_count(round(float(v)), lang=lang)
    if spec == "scale":
        return fmt_number(round(float(v)), 0, lang=lang)
    return fmt_spec(v, spec, lang=lang)


def html_table(df, *, caption: str = "", float_format: str = "{:.4g}", precision=None, notes=None,
               highlight=None, fold: bool | str = False) -> str:
    """Render a DataFrame as compact, projector-friendly HTML for an HTML widget, in the book's number format.

    Numbers follow :mod:`aerophoto.i18n.numfmt` (the reader's decimal mark, ``12 043``, a true minus, never
    ``−0.00``): a whole-number cell (an int, or a float in an integer column) is a count; a real number takes
    ``precision`` — a dict from a column's or a row's label to decimals (``2``), ``"count"``, ``"scale"`` or a
    ``str.format`` spec (a row's label wins over its column's), or one int for every real cell — else
    ``float_format`` (``"{:.4g}"``: 4 significant digits).  A row whose ``unit`` is ``"1:"`` is a scale
    (``1:12 000``).  Text is translated, a number written in it by Python rewritten (``-0.00`` → ``0.00``), and
    symbols' subscripts set (``p_x`` → p<sub>x</sub>); a ``unit`` column's units are the reader's (m → м).
    ``highlight`` is an optional boolean DataFrame/array of the same shape: True cells are shaded (e.g. a
    tolerance exceeded).  ``notes`` is a list of strings printed under the table.  ``fold`` (a secondary
    table): ``True`` folds the table under its caption (a ``<details>`` the reader opens; a demo's page keeps it
    open or closed across updates), ``"open"`` shows it unfolded.

    Column headers are ``<th scope="col">``, row labels ``<th scope="row">``; the corner cell is an empty
    ``<td>`` when the index has no name, and a table whose columns have no names has no header row; cells of
    numbers (a digit and no word of four letters or more: "12 043", "1a–4a", "−0.48 mm") carry the class ``num``
    and never break across lines (:data:`aerophoto.widgets.TABLE_CSS`).
    """
    import pandas as pd

    from .i18n import get_language, translate_unit, translate_units_in
    from .i18n import translate as _tr  # the reader's language (aerophoto.i18n); English unchanged
    from .i18n.numfmt import fmt_count, fmt_text, fmt_value

    lang = get_language()
    rules = precision if isinstance(precision, dict) else {}
    every = precision if isinstance(precision, int) and not isinstance(precision, bool) else None
    cols = [str(c) for c in df.columns]
    unit_col = next((j for j, c in enumerate(cols) if c.strip().lower() in ("unit", "units")), None)
    int_col = [pd.api.types.is_integer_dtype(df.iloc[:, j]) for j in range(df.shape[1])]

    def fmt(v, row, j):
        if isinstance(v, str):
            # a unit column's units are the tasks' (m → м; a lone "m" elsewhere may be a point's name)
            shown = translate_unit(v) if j == unit_col and translate_unit(v) != v else _tr(v)
            return html_subscripts(translate_units_in(fmt_text(shown, lang=lang)))
        if v is None or isinstance(v, (bool, np.bool_)):
            return _html.escape(fmt_value(v, lang=lang))
        if isinstance(v, (int, np.integer)):
            return fmt_count(v, lang=lang)
        if isinstance(v, (float, np.floating)):
            if np.isnan(v):
                return "—"
            spec = rules.get(row, rules.get(cols[j], every))
            if spec is None and unit_col is not None and str(df.iat[ri, unit_col]) == "1:":
                spec = "scale"
            if spec is None and int_col[j] and float(v).is_integer():
                spec = "count"
            return _html.escape(_cell_format(float_format if spec is None else spec, v, lang))
        return html_subscripts(translate_units_in(fmt_text(_tr(str(v)), lang=lang)))

    def num(text: str) -> str:
        return " class='num'" if _NUMBER_LIKE.search(text) and not _WORD.search(text) else ""

    hl = None if highlight is None else np.asarray(highlight, dtype=bool)
    head = "".join(f"<th scope='col'>{html_subscripts(_tr(c))}</th>" for c in cols)
    index_name = html_subscripts(_tr(str(df.index.name or "")))
    corner = f"<th scope='col'>{index_name}</th>" if index_name else "<td></td>"
    rows = []
    for ri in range(len(df)):
        label = str(df.index[ri])
        cells = []
        for j in range(df.shape[1]):
            style = ' style="background:#F0E442"' if hl is not None and hl[ri, j] else ""
            text = fmt(df.iat[ri, j], label, j)
            cells.append(f"<td{num(text)}{style}>{text}</td>")
        shown = html_subscripts(fmt_text(_tr(label), lang=lang))
        rows.append(f"<tr><th scope='row'{num(shown)}>{shown}</th>{''.join(cells)}</tr>")
    title = html_subscripts(_tr(caption)) if caption else ""
    cap = (f"<caption style='caption-side:top;font-weight:bold;text-align:left'>{title}</caption>"
           if caption and not fold else "")
    foot = ""
    if notes:
        foot = "<ul style='margin:4px 0 0 16px;padding:0'>" + "".join(
            f"<li>{html_subscripts(translate_units_in(fmt_text(_tr(n), lang=lang)))}</li>" for n in notes) + "</ul>"
    # a table whose columns have no names has no header row (no empty header cells)
    thead = f"<thead><tr>{corner}{head}</tr></thead>" if index_name or any(cols) else ""
    table = (f"<table style='border-collapse:collapse' border='1' cellpadding='3'>"
             f"{cap}{thead}<tbody>{''.join(rows)}</tbody></table>{foot}")
    if fold:
        key = _html.escape(str(caption or "table"), quote=True)
        table = (f"<details data-fold='{key}'{' open' if fold == 'open' else ''}><summary>{title or '…'}</summary>"
                 f"{table}</details>")
    return f"<div class='aerophoto-table' style='font-size:15px'>{table}</div>"


#: a table cell of a number: a digit, and no word of four letters or more (kept on one line)
_NUMBER_LIKE = re.compile(r"\d")
_WORD = re.compile(r"[^\W\d_]{4,}")


def register_table_display() -> bool:
    """Show the package's tables in a notebook in the book's format: a DataFrame marked
    ``df.attrs["aerophoto"]`` (``Variant.table()``) through :func:`html_table`, a guide's audit
    (:class:`aerophoto.guide.Audit`) with its numbers by :mod:`aerophoto.i18n.numfmt`; every other DataFrame as
    pandas shows it.  :func:`aerophoto.setup` calls it; returns False outside IPython."""
    try:
        from IPython import get_ipython
    except ImportError:  # pragma: no cover - IPython is a dependency of ipywidgets
        return False
    shell = get_ipython()
    if shell is None:
        return False
    import pandas as pd

    from .guide.audit import Audit, render

    def frame_html(df):
        meta = df.attrs.get("aerophoto") if hasattr(df, "attrs") else None
        if not isinstance(meta, dict):
            return df._repr_html_()
        return html_table(df, caption=meta.get("caption", ""), precision=meta.get("precision"))

    def audit_html(audit):
        from .i18n.numfmt import fmt_text

        return render(audit, number=lambda text: fmt_text(text, lang="en"))

    html = shell.display_formatter.formatters["text/html"]
    html.for_type(pd.DataFrame, frame_html)
    html.for_type(Audit, audit_html)
    return True


_MARKER_GLYPH = {"o": "●", "s": "■", "^": "▲", "v": "▼", "D": "◆", "+": "+", "x": "×", "*": "★", ".": "•"}


def legend_html(ax, *, remove: bool = True) -> str:
    """The legend(s) of an axes or of a whole figure as a small HTML block (swatch + label per entry).

    Live demos show their legend beside the figure instead of inside it: a
    legend is redrawn on every update and costs a large share of the draw.
    With ``remove`` the axes' own legend is taken off the figure.
    """
    from matplotlib.colors import to_hex
    from matplotlib.lines import Line2D

    from matplotlib.figure import Figure

    if isinstance(ax, Figure):
        legends = [a.get_legend() for a in ax.axes] + list(ax.legends)
    else:
        legends = [ax.get_legend()]
    entries = []
    for leg in legends:
        if leg is None:
            continue
        entries += list(zip(leg.legend_handles, [t.get_text() for t in leg.get_texts()]))
        if remove:
            leg.remove()
    items = []
    for h, label in entries:
        if h is None:
            continue
        glyph, colour, style = "▬", "#000000", ""
        try:
            if isinstance(h, Line2D):
                colour = to_hex(h.get_color())
                marker = h.get_marker()
                if marker not in (None, "None", "", " ") and h.get_linestyle() in ("None", "none", "", " "):
                    glyph = _MARKER_GLYPH.get(marker, "●")
                    if h.get_markerfacecolor() in ("none", "None"):
                        glyph = {"●": "○", "■": "□", "▲": "△", "▼": "▽", "◆": "◇"}.get(glyph, glyph)
                        colour = to_hex(h.get_markeredgecolor())  # an open marker shows its edge's colour
                    else:
                        colour = to_hex(h.get_markerfacecolor())
                elif h.get_linestyle() in ("--", "dashed", ":", "dotted", "-.", "dashdot"):
                    glyph = "┅" if h.get_linestyle() in (":", "dotted") else "╍"
            else:
                for getter in ("get_edgecolor", "get_facecolor", "get_color"):
                    c = getattr(h, getter, lambda: None)()
                    c = np.atleast_2d(c) if c is not None else np.zeros((0, 4))
                    if len(c) and np.asarray(c).shape[-1] in (3, 4) and np.asarray(c)[0][-1] > 0:
                        colour = to_hex(np.asarray(c)[0])
                        break
                glyph = "■"
        except (TypeError, ValueError):
            pass
        items.append(f"<span style='white-space:nowrap;margin-right:12px'><span style='color:{colour};{style}"
                     f"font-size:17px'>{glyph}</span> {html_subscripts(label)}</span> ")
    if not items:
        return ""
    return f"<div class='aerophoto-legend' style='font-size:14px;line-height:1.6;margin:4px 0'>{''.join(items)}</div>"
