"""Shared plotting: the book's style, colours and small figure helpers.

Figure builders in the topic modules follow one pattern so that a static
figure and its live version share one function::

    view = SomePlot(ax=None)      # builds artists once; creates a figure if ax is None
    view.update(result)           # changes the artists in place (set_data, set_UVC, ...)

Colours are the Okabe–Ito palette, distinguishable with every common form of
colour blindness, and the style uses projector-sized fonts.
"""

from __future__ import annotations

import contextlib
import html as _html
import re

import matplotlib as mpl
import numpy as np

__all__ = [
    "COLORS",
    "STYLE",
    "use_style",
    "style_context",
    "new_axes",
    "figure",
    "figure_widget",
    "static",
    "StaticFigure",
    "draw",
    "freeze_layout",
    "fast_frames",
    "snapped_limits",
    "coarse_ceil",
    "steady_title",
    "steady_limits",
    "html_table",
    "html_subscripts",
    "math_subscripts",
    "finish_figure",
    "register_table_display",
    "legend_html",
    "mark_points",
    "move_onc",
    "photo_frame",
]

#: Okabe–Ito colours with the meaning each has throughout the book.
COLORS = {
    "black": "#000000",
    "orange": "#E69F00",
    "skyblue": "#56B4E9",
    "green": "#009E73",
    "yellow": "#F0E442",
    "blue": "#0072B2",
    "vermillion": "#D55E00",
    "purple": "#CC79A7",
    "grey": "#777777",
    # meanings
    "photo": "#000000",  # photo frame, principal point o
    "nadir": "#D55E00",  # nadir point n
    "isocentre": "#0072B2",  # isocentre c
    "relief": "#D55E00",  # relief displacement
    "tilt": "#0072B2",  # exact tilt displacement
    "approx": "#E69F00",  # the guide's approximate formula
    "truth": "#009E73",  # ground truth
    "control": "#CC79A7",  # control points (опознаки)
    "footprint": "#56B4E9",
}

#: rcParams of the book: readable on a projector at 1280×800.
STYLE = {
    "figure.figsize": (7.2, 4.6),
    "figure.dpi": 100,
    "savefig.dpi": 150,
    "font.size": 12,
    "axes.titlesize": 13,
    "axes.labelsize": 12,
    "xtick.labelsize": 11,
    "ytick.labelsize": 11,
    "legend.fontsize": 11,
    "lines.linewidth": 2.0,
    "lines.markersize": 7,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "axes.spines.top": False,
    "axes.spines.right": False,
    "axes.prop_cycle": mpl.cycler(
        color=["#0072B2", "#D55E00", "#009E73", "#E69F00", "#CC79A7", "#56B4E9", "#000000"]
    ),
    "image.cmap": "cividis",
    "figure.constrained_layout.use": True,
}


def use_style() -> None:
    """Apply the book's matplotlib style globally (called by :func:`aerophoto.setup`)."""
    mpl.rcParams.update(STYLE)


@contextlib.contextmanager
def style_context():
    """Apply the book's style only inside a ``with`` block."""
    with mpl.rc_context(STYLE):
        yield


def figure(figsize=None, **kwargs):
    """Create a figure without showing it yet, ready to sit inside a widget layout.

    With the ipympl backend the canvas is a widget; its header is hidden and
    its size fixed so the demo layout does not jump.  Returns the Figure.
    """
    import matplotlib.pyplot as plt

    with plt.ioff():
        fig = plt.figure(figsize=figsize, **kwargs)
    canvas = fig.canvas
    for attr, value in (("header_visible", False), ("footer_visible", False), ("resizable", False),
                        ("toolbar_visible", "fade-in-fade-out"), ("toolbar_position", "right")):
        if hasattr(canvas, attr):
            with contextlib.suppress(Exception):
                setattr(canvas, attr, value)
    return fig


def new_axes(ax=None, *, figsize=None, **subplot_kw):
    """Return ``(fig, ax)``: the given axes and its figure, or a new figure with one axes."""
    if ax is not None:
        return ax.figure, ax
    fig = figure(figsize=figsize)
    return fig, fig.add_subplot(1, 1, 1, **subplot_kw)


def figure_widget(fig):
    """The widget that shows ``fig``: its ipympl canvas, or an Output holding a static image.

    Outside the widget backend (e.g. ``%matplotlib inline``) a live demo still
    renders once, as a static picture inside an Output widget.
    """
    import ipywidgets as w

    if isinstance(fig.canvas, w.DOMWidget):
        return fig.canvas
    out = w.Output()
    with out:
        from IPython.display import display

        display(fig)
    return out


class StaticFigure:
    """A finished figure as a PNG with a text alternative — the book's one way to show a static figure.

    Displays as ``<img alt="…">`` in HTML (JupyterLab, Voilà, nbconvert) and as
    PNG elsewhere.  Attributes: ``png`` (bytes), ``alt`` (str).
    """

    def __init__(self, png: bytes, alt: str):
        self.png = png
        self.alt = alt

    def _repr_png_(self):
        return self.png

    def _repr_html_(self) -> str:
        import base64

        data = base64.b64encode(self.png).decode("ascii")
        return f"<img src='data:image/png;base64,{data}' alt='{_html.escape(self.alt, quote=True)}' style='max-width:100%'>"

    def _repr_mimebundle_(self, include=None, exclude=None):
        return {"text/html": self._repr_html_(), "image/png": self.png, "text/plain": f"[figure: {self.alt}]"}


def static(fig, alt: str, *, dpi: int = 100) -> StaticFigure:
    """Show ``fig`` once as a PNG with the alternative text ``alt`` (say what the figure shows); the figure is closed.

    Use it for every figure that does not move (a theory sketch, a worked
    example's plot); live figures are the demos' ipympl canvases.
    """
    import io

    import matplotlib.pyplot as plt

    if not str(alt).strip():
        raise ValueError("alt = '' is empty; describe what the figure shows (read aloud by screen readers)")
    finish_figure(fig)  # the reader's language, the book's number format on the ticks, subscripts set
    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    plt.close(fig)
    return StaticFigure(buf.getvalue(), str(alt))


def draw(fig, *, force: bool = False) -> None:
    """Redraw after artists changed: one ``draw_idle`` (or a full draw if ``force``)."""
    if force:
        fig.canvas.draw()
    else:
        fig.canvas.draw_idle()


def freeze_layout(fig) -> None:
    """Keep the layout found at the figure's first draw for every later draw.

    Constrained layout costs a third or more of a redraw; a live demo's axes
    keep their places while the sliders move, so the layout is computed once,
    at the first draw, and then replaced by a do-nothing engine.  Figures
    without a layout engine are left alone.
    """
    from matplotlib.layout_engine import PlaceHolderLayoutEngine

    if fig.get_layout_engine() is None or getattr(fig, "_aerophoto_freeze", None) is not None:
        return

    def freeze(_event):
        fig.canvas.mpl_disconnect(fig._aerophoto_freeze)
        fig.set_layout_engine(PlaceHolderLayoutEngine(adjust_compatible=False, colorbar_gridspec=True))

    fig._aerophoto_freeze = fig.canvas.mpl_connect("draw_event", freeze)


def snapped_limits(lo: float, hi: float, *, steps: int = 40) -> tuple[float, float]:
    """``(lo, hi)`` widened outwards to multiples of a round step (1, 2 or 5 × 10^k, about (hi − lo)/steps).

    Limits that follow the data on every slider move make the axes' ticks and
    labels change with it — the most costly part of a redraw.  Snapped, they
    stay put while the data moves by less than a step (about 2.5 % of the
    span), so the axes can stay in a live demo's cached background; the framing
    differs from the unsnapped one by less than a step on each side.
    """
    import math

    lo, hi = float(lo), float(hi)
    span = hi - lo
    if not (math.isfinite(span) and span > 0):
        return lo, hi
    raw = span / steps
    e = math.floor(math.log10(raw))
    step = next(m * 10.0**e for m in (1.0, 2.0, 5.0, 10.0) if m * 10.0**e >= raw)
    return math.floor(lo / step) * step, math.ceil(hi / step) * step


#: a coarse ladder of round values (× 10^k): limits and frames that follow the data only in these steps
COARSE_STEPS = (1.0, 1.25, 1.6, 2.0, 2.5, 3.2, 4.0, 5.0, 6.4, 8.0)


def coarse_ceil(x: float) -> float:
    """The first of 1, 1.25, 1.6, 2, 2.5, 3.2, 4, 5, 6.4, 8 (× 10^k) at least as large as ``x`` (x ≤ 0 → 1e-6).

    A live demo whose frame or axis limit is this of what it must hold keeps
    the same frame — and so its cached axes, ticks and labels — over most
    slider moves: the value changes only when the data crosses a step of
    about 25 %, and the frame is never more than 1.28 × what the data needs.
    """
    import math

    v = max(float(x), 1e-6)
    k = math.floor(math.log10(v))
    return next(h * 10.0**e for e in (k, k + 1) for h in COARSE_STEPS if h * 10.0**e >= v * (1 - 1e-12))


def steady_title(ax) -> None:
    """Make ``ax.set_title(label)`` do nothing when ``label`` is the title already (and no style is passed).

    ``set_title`` marks the axes changed even for the same text, which would
    make a live demo that re-sets its title on every move redraw in full.
    """
    original = ax.set_title

    def set_title(label, fontdict=None, loc=None, pad=None, *, y=None, **kwargs):
        same_size = set(kwargs) <= {"fontsize"} and (
            "fontsize" not in kwargs or _same_fontsize(ax.title, kwargs["fontsize"]))
        if (fontdict is None and loc in (None, "center") and pad is None and y is None and same_size
                and str(label) == ax.get_title()):
            return ax.title
        return original(label, fontdict, loc, pad, y=y, **kwargs)

    ax.set_title = set_title


def _same_fontsize(text, size) -> bool:
    try:
        return float(size) == float(text.get_fontsize())
    except (TypeError, ValueError):  # "large" etc.: cannot tell, treat as a change
        return False


def steady_limits(ax, *, snap: bool = True) -> None:
    """Make ``ax.set_xlim(lo, hi)`` / ``set_ylim`` round the limits outwards (``snap``, :func:`snapped_limits`)
    and do nothing when they are the current limits already.

    A live demo whose view sets its limits from the data on every move keeps
    its axes (ticks, labels) — and so its cached background — while the data
    moves by less than a rounding step.  Calls with other arguments (one bound,
    ``auto=None`` from autoscaling, ``xmin=``) pass through unchanged.
    """
    for name, get, auto_on in (("set_xlim", ax.get_xlim, ax.get_autoscalex_on),
                               ("set_ylim", ax.get_ylim, ax.get_autoscaley_on)):
        original = getattr(ax, name)

        def steady(left=None, right=None, *, emit=True, auto=False, _original=original, _get=get,
                   _auto_on=auto_on, **kwargs):
            if right is None and np.iterable(left) and len(left) == 2:
                left, right = left
            simple = not kwargs and auto is False and left is not None and right is not None
            if not simple:
                return _original(left, right, emit=emit, auto=auto, **kwargs)
            lo, hi = (snapped_limits(left, right) if snap and left < right else (float(left), float(right)))
            if not _auto_on() and tuple(map(float, _get())) == (lo, hi):
                return lo, hi
            return _original(lo, hi, emit=emit, auto=auto)

        setattr(ax, name, steady)


#: zlib level of the PNG frames a live figure sends to the browser (matplotlib uses the default, 6)
FRAME_COMPRESS_LEVEL = 1


def _fast_diff_image(canvas, level: int):
    """``FigureCanvasWebAggCore.get_diff_image`` (matplotlib 3.9–3.11) with the PNG compressed at ``level``.

    Same frames, same full/diff decision and bookkeeping; only the zlib
    level differs.  Returns the PNG bytes, or None when the image is current.
    """
    from io import BytesIO

    from PIL import Image

    if not canvas._png_is_old:
        return None
    pixels = np.asarray(canvas.get_renderer().buffer_rgba())
    buff = pixels.view(np.uint32).squeeze(2)
    if canvas._force_full or buff.shape != canvas._last_buff.shape or (pixels[:, :, 3] != 255).any():
        canvas.set_image_mode("full")
        output = buff
    else:
        canvas.set_image_mode("diff")
        output = np.where(buff != canvas._last_buff, buff, 0)
    canvas._last_buff = buff.copy()
    canvas._force_full = False
    canvas._png_is_old = False
    data = output.view(dtype=np.uint8).reshape((*output.shape, 4))
    with BytesIO() as png:
        Image.fromarray(data).save(png, format="png", compress_level=level)
        return png.getvalue()


def fast_frames(fig, level: int = FRAME_COMPRESS_LEVEL) -> bool:
    """Send ``fig``'s live frames (ipympl) as quickly compressed PNGs; returns whether it applied.

    An ipympl figure reaches the browser as a PNG of the pixels that changed.
    matplotlib compresses it at zlib's default level 6; for a figure with a
    photo in it that costs about 50 ms per frame (an 880×560 sheet), level 1
    about 20 ms for a file some 10 % larger — on a local connection the
    cheaper encoding wins.  Only this figure's canvas is changed, and only
    when it is matplotlib's web canvas with the method this replaces;
    otherwise (inline backend, another matplotlib) nothing is done.
    """
    import types

    from matplotlib.backends.backend_webagg_core import FigureCanvasWebAggCore

    canvas = fig.canvas
    if not isinstance(canvas, FigureCanvasWebAggCore):
        return False
    if type(canvas).get_diff_image is not FigureCanvasWebAggCore.get_diff_image:
        return False
    if not all(hasattr(canvas, a) for a in ("_png_is_old", "_force_full", "_last_buff")):
        return False
    level = int(level)
    if not 0 <= level <= 9:
        raise ValueError(f"level = {level} is outside the zlib compression levels 0 … 9")
    canvas.get_diff_image = types.MethodType(lambda self: _fast_diff_image(self, level), canvas)
    return True


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


def finish_figure(fig) -> None:
    """What every figure of the book gets once it is built: its fixed texts in the reader's language
    (:func:`aerophoto.i18n.translate_figure`), tick labels in the book's number format
    (:func:`aerophoto.i18n.numfmt.localise_ticks`) and symbols' subscripts set (:func:`math_subscripts`).
    :class:`aerophoto.widgets.LiveDemo` and :func:`static` call it; calling it twice changes nothing more."""
    from .i18n import translate_figure
    from .i18n.numfmt import localise_ticks

    if fig is None:
        return
    translate_figure(fig)
    localise_ticks(fig)
    for art in fig.findobj(lambda a: hasattr(a, "get_text") and hasattr(a, "set_text")):
        s = art.get_text()
        new = math_subscripts(s)
        if new != s:
            art.set_text(new)


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
               highlight=None) -> str:
    """Render a DataFrame as compact, projector-friendly HTML for an HTML widget, in the book's number format.

    Numbers follow :mod:`aerophoto.i18n.numfmt` (the reader's decimal mark, ``12 043``, a true minus, never
    ``−0.00``): a whole-number cell (an int, or a float in an integer column) is a count; a real number takes
    ``precision`` — a dict from a column's or a row's label to decimals (``2``), ``"count"``, ``"scale"`` or a
    ``str.format`` spec (a row's label wins over its column's), or one int for every real cell — else
    ``float_format`` (``"{:.4g}"``: 4 significant digits).  A row whose ``unit`` is ``"1:"`` is a scale
    (``1:12 000``).  Text is translated, a number written in it by Python rewritten (``-0.00`` → ``0.00``), and
    symbols' subscripts set (``p_x`` → p<sub>x</sub>); a ``unit`` column's units are the reader's (m → м).
    ``highlight`` is an optional boolean DataFrame/array of the same shape: True cells are shaded (e.g. a
    tolerance exceeded).  ``notes`` is a list of strings printed under the table.
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

    hl = None if highlight is None else np.asarray(highlight, dtype=bool)
    head = "".join(f"<th>{html_subscripts(_tr(c))}</th>" for c in cols)
    index_name = html_subscripts(_tr(str(df.index.name or "")))
    rows = []
    for ri in range(len(df)):
        label = str(df.index[ri])
        cells = []
        for j in range(df.shape[1]):
            style = ' style="background:#F0E442"' if hl is not None and hl[ri, j] else ""
            cells.append(f"<td{style}>{fmt(df.iat[ri, j], label, j)}</td>")
        rows.append(f"<tr><th>{html_subscripts(fmt_text(_tr(label), lang=lang))}</th>{''.join(cells)}</tr>")
    cap = (f"<caption style='caption-side:top;font-weight:bold;text-align:left'>{html_subscripts(_tr(caption))}"
           "</caption>") if caption else ""
    foot = ""
    if notes:
        foot = "<ul style='margin:4px 0 0 16px;padding:0'>" + "".join(
            f"<li>{html_subscripts(translate_units_in(fmt_text(_tr(n), lang=lang)))}</li>" for n in notes) + "</ul>"
    return (
        "<div class='aerophoto-table' style='font-size:15px'>"
        "<table style='border-collapse:collapse' border='1' cellpadding='3'>"
        f"{cap}<thead><tr><th>{index_name}</th>{head}</tr></thead><tbody>{''.join(rows)}</tbody></table>{foot}</div>"
    )


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


def photo_frame(ax, camera, *, color=None, label="photo frame", lw=1.5):
    """Draw the camera's frame (photo coordinates, mm) on ``ax``; returns the Line2D."""
    c = camera.corners_mm()
    c = np.vstack([c, c[:1]])
    (line,) = ax.plot(c[:, 0], c[:, 1], color=color or COLORS["photo"], lw=lw, label=label)
    ax.set_aspect("equal")
    ax.set_xlabel("x, mm")
    ax.set_ylabel("y, mm")
    return line


def move_onc(marks: dict, o, n, c, u, *, offset_pt: float = 14.0) -> None:
    """Move the o, n, c marks of :func:`mark_points` to the photo points ``o``, ``n``, ``c`` (mm) with their labels
    fanned out so that they never overlap, at any tilt: the three lie on the principal vertical (unit direction
    ``u``, from o towards n), so o's label goes behind o, n's beyond n and c's across the line (α = 0: all three
    coincide, and the labels still stand apart)."""
    o, n, c = (np.asarray(p, float) for p in (o, n, c))
    d = n - o
    ahead = d / np.hypot(*d) if np.hypot(*d) > 1e-9 else np.asarray(u, float) / max(np.hypot(*u), 1e-12)
    across = np.array([-ahead[1], ahead[0]])
    for name, pt, way in (("o", o, -ahead), ("n", n, ahead), ("c", c, across)):
        marker, label = marks[name]
        marker.set_data([pt[0]], [pt[1]])
        label.xy = (pt[0], pt[1])
        label.set_horizontalalignment("center")
        label.set_verticalalignment("center")
        label.xyann = (float(offset_pt * way[0]), float(offset_pt * way[1]))


def mark_points(ax, points: dict, *, size=9):
    """Mark named points, e.g. ``{"o": (0, 0), "n": (...), "c": (...)}``, on ``ax``.

    Returns a dict name → (Line2D marker, Text label) so callers can move them
    with ``marker.set_data`` and ``label.set_position`` on update.
    """
    style = {
        "o": dict(marker="+", color=COLORS["photo"], ms=size + 4, mew=2),
        "n": dict(marker="^", color=COLORS["nadir"], ms=size),
        "c": dict(marker="o", color=COLORS["isocentre"], ms=size, mfc="none", mew=2),
    }
    out = {}
    for name, (x, y) in points.items():
        st = style.get(name, dict(marker="o", color=COLORS["black"], ms=size))
        (m,) = ax.plot([x], [y], linestyle="none", **st, zorder=5)
        t = ax.annotate(name, (x, y), xytext=(6, 6), textcoords="offset points", color=st["color"],
                        fontsize=12, fontweight="bold", zorder=6)
        out[name] = (m, t)
    return out
