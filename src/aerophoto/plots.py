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
import threading

import matplotlib as mpl
import numpy as np

from .tables import _cell_format, html_subscripts, html_table, legend_html, math_subscripts, register_table_display  # noqa: F401 (re-exported)

__all__ = [
    "COLORS",
    "STYLE",
    "use_style",
    "style_context",
    "new_axes",
    "panels",
    "figure",
    "figure_widget",
    "static",
    "StaticFigure",
    "JPEG_QUALITY",
    "JPEG_MIN_SSIM",
    "JPEG_MAX_DE",
    "picture_difference",
    "draw",
    "freeze_layout",
    "scale_figure",
    "natural_size_px",
    "figure_lock",
    "lock_canvas",
    "fast_frames",
    "FRAME_COMPRESS_LEVEL",
    "PHOTO_QUALITY",
    "PREVIEW_QUALITY",
    "PHOTO_SHARE",
    "frame_quality",
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
    "PointLabels",
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


def panels(ax=None, n: int = 2, *, figsize=None, width_ratios=None) -> tuple:
    """Return ``(fig, axes)``: the ``n`` given Axes side by side and their figure, or a new figure of ``n`` panels
    in a row (``width_ratios`` their relative widths) — the two-panel views' ``ax=None``."""
    if ax is not None:
        axes = tuple(ax)
        if len(axes) != n:
            raise ValueError(f"ax holds {len(axes)} Axes; give {n} or None")
        return axes[0].figure, axes
    fig = figure(figsize=figsize)
    kw = {"gridspec_kw": {"width_ratios": list(width_ratios)}} if width_ratios is not None else {}
    return fig, tuple(fig.subplots(1, n, **kw))


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
    """A finished figure as a picture with a text alternative — the book's one way to show a static figure.

    Displays as ``<img alt="…">`` in HTML (JupyterLab, Voilà, nbconvert) and as the picture elsewhere.
    Attributes: ``data`` (the encoded bytes), ``mime`` (``image/png`` or ``image/jpeg``), ``alt`` (str); ``png``
    is ``data`` of a PNG.  A JPEG (:func:`static`'s ``format="jpeg"``, for photos) is shown through its HTML only:
    every front end the book supports renders HTML, and a second copy of the picture in the output would double
    its size.
    """

    def __init__(self, data: bytes, alt: str, mime: str = "image/png"):
        if mime not in ("image/png", "image/jpeg"):
            raise ValueError(f"mime = {mime!r} is not one of ['image/png', 'image/jpeg']")
        self.data = data
        self.alt = alt
        self.mime = mime

    @property
    def png(self) -> bytes | None:
        return self.data if self.mime == "image/png" else None

    def _repr_png_(self):
        return self.png

    def _repr_jpeg_(self):
        return self.data if self.mime == "image/jpeg" else None

    def _repr_html_(self) -> str:
        import base64

        data = base64.b64encode(self.data).decode("ascii")
        return (f"<img src='data:{self.mime};base64,{data}' alt='{_html.escape(self.alt, quote=True)}' "
                "style='max-width:100%'>")

    def _repr_mimebundle_(self, include=None, exclude=None):
        bundle = {"text/html": self._repr_html_(), "text/plain": f"[figure: {self.alt}]"}
        if self.mime == "image/png":
            bundle["image/png"] = self.data
        return bundle


#: JPEG quality of a photo shown by :func:`static` (``format="jpeg"``, no chroma subsampling): the lowest of 50,
#: 55, …, 95 whose pictures of chapter 08's photos keep a structural similarity of at least :data:`JPEG_MIN_SSIM`
#: and a mean colour difference of at most :data:`JPEG_MAX_DE` against the lossless PNG (measured by
#: docs/tools/measure_jpeg_quality.py: 85 gives SSIM 0.974, 90 gives 0.982 and ΔE₀₀ 0.92; the three photos of
#: the chapter then take 1.2 MB of the notebook instead of 5.6 MB as PNG; tests/presentation/test_plots_jpeg.py)
JPEG_QUALITY = 90
#: the least structural similarity (SSIM of the luminance, Wang et al. 2004; scikit-image) a JPEG photo keeps
JPEG_MIN_SSIM = 0.98
#: the largest mean CIEDE2000 colour difference ΔE₀₀ a JPEG photo may show (1 ≈ a just noticeable difference)
JPEG_MAX_DE = 1.0


def picture_difference(ref, got) -> dict:
    """How much two pictures (h, w, 3) uint8 of one shape differ, as an eye would judge it.

    ``ssim``: the structural similarity of their luminance (Wang, Bovik, Sheikh & Simoncelli 2004: Gaussian
    window σ = 1.5 px; scikit-image), 1 for equal pictures; ``dE_mean`` and ``dE_p99``: the mean and 99th
    percentile of the CIEDE2000 colour difference ΔE₀₀ (Sharma, Wu & Dalal 2005), 0 for equal colours and about
    1 for a just noticeable difference.
    """
    from skimage.color import deltaE_ciede2000, rgb2gray, rgb2lab
    from skimage.metrics import structural_similarity

    a = np.asarray(ref)
    b = np.asarray(got)
    if a.shape != b.shape or a.ndim != 3 or a.shape[-1] != 3:
        raise ValueError(f"ref has shape {a.shape} and got {b.shape}; both must be one (h, w, 3) shape")
    a = a.astype(np.float64) / 255.0 if a.dtype == np.uint8 else a.astype(np.float64)
    b = b.astype(np.float64) / 255.0 if b.dtype == np.uint8 else b.astype(np.float64)
    s = structural_similarity(rgb2gray(a), rgb2gray(b), data_range=1.0, gaussian_weights=True, sigma=1.5,
                              use_sample_covariance=False)
    de = deltaE_ciede2000(rgb2lab(a), rgb2lab(b))
    return {"ssim": float(s), "dE_mean": float(de.mean()), "dE_p99": float(np.percentile(de, 99))}


def static(fig, alt: str, *, dpi: int = 100, format: str = "png", quality: int | None = None) -> StaticFigure:
    """Show ``fig`` once as a picture with the alternative text ``alt`` (say what the figure shows); the figure is
    closed.

    Use it for every figure that does not move (a theory sketch, a worked example's plot); live figures are the
    demos' ipympl canvases.  ``format="jpeg"`` suits a photo (a tenth of a PNG's size at a full photo's
    resolution), at ``quality`` (1…95, default :data:`JPEG_QUALITY`); diagrams stay PNG (sharp lines and text).
    """
    import io

    import matplotlib.pyplot as plt

    if not str(alt).strip():
        raise ValueError("alt = '' is empty; describe what the figure shows (read aloud by screen readers)")
    if format not in ("png", "jpeg"):
        raise ValueError(f"format = {format!r} is not one of ['png', 'jpeg']")
    finish_figure(fig)  # the reader's language, the book's number format on the ticks, subscripts set
    buf = io.BytesIO()
    if format == "png":
        fig.savefig(buf, format="png", dpi=dpi)
    else:
        from ._validate import check_int_range

        q = JPEG_QUALITY if quality is None else check_int_range("quality", quality, 1, 95)
        fig.savefig(buf, format="jpeg", dpi=dpi, pil_kwargs={"quality": int(q), "optimize": True, "subsampling": 0})
    plt.close(fig)
    return StaticFigure(buf.getvalue(), str(alt), "image/png" if format == "png" else "image/jpeg")


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
        fig._aerophoto_engine = fig.get_layout_engine()  # scale_figure lays the figure out again with it
        fig.set_layout_engine(PlaceHolderLayoutEngine(adjust_compatible=False, colorbar_gridspec=True))

    fig._aerophoto_freeze = fig.canvas.mpl_connect("draw_event", freeze)


def figure_lock(fig):
    """The figure's re-entrant lock (made once per figure).

    ipykernel 7 may handle a page's widget messages on two threads (JupyterLab sends them through a kernel
    subshell, others arrive on the main shell): ipympl's request to draw can then run while a demo moves artists
    or resizes the figure, and the frame shows a half-made layout.  A live figure is changed and drawn under this
    lock (:func:`lock_canvas`, :class:`aerophoto.widgets.LiveDemo`).
    """
    lock = fig.__dict__.get("_aerophoto_lock")
    if lock is None:
        lock = fig.__dict__.setdefault("_aerophoto_lock", threading.RLock())
    return lock


def lock_canvas(fig) -> None:
    """Draw ``fig``'s canvas and take its frames (ipympl) only under :func:`figure_lock`; idempotent."""
    canvas = fig.canvas
    if getattr(canvas, "_aerophoto_locked", False):
        return
    lock = figure_lock(fig)
    for name in ("draw", "get_diff_image"):
        method = getattr(canvas, name, None)
        if method is None:
            continue

        def locked(*args, _method=method, **kwargs):
            with lock:
                return _method(*args, **kwargs)

        setattr(canvas, name, locked)
    canvas._aerophoto_locked = True


class _Natural:
    """A figure as built: its size (in), logical dpi and the places of its Axes (figure fractions)."""

    def __init__(self, fig):
        self.w_in, self.h_in = (float(v) for v in fig.get_size_inches())
        self.dpi = float(getattr(fig, "_original_dpi", fig.dpi))
        self.boxes = [(ax, ax.get_position(original=True).bounds) for ax in fig.axes]

    @property
    def px(self) -> tuple[float, float]:
        return self.w_in * self.dpi, self.h_in * self.dpi


def _natural(fig) -> _Natural:
    nat = getattr(fig, "_aerophoto_natural", None)
    if nat is None:
        nat = fig._aerophoto_natural = _Natural(fig)
    return nat


def natural_size_px(fig) -> tuple[float, float]:
    """The figure's (width, height) in CSS px as built (its figsize at its dpi), whatever it is drawn at now."""
    return _natural(fig).px


def _stretch(edges: list[tuple[float, float]], k: float) -> dict[float, float]:
    """Figure fractions along one direction → new fractions when everything outside the Axes (margins and gaps:
    tick labels, axis labels, titles) grows by ``k`` and the Axes share what is left (at least 40 % of before)."""
    cuts = sorted({0.0, 1.0, *(min(max(v, 0.0), 1.0) for e in edges for v in e)})
    spans = list(zip(cuts[:-1], cuts[1:]))
    inside = [any(a <= lo + 1e-9 and hi <= b + 1e-9 for a, b in edges) for lo, hi in spans]
    margin = sum(hi - lo for (lo, hi), i in zip(spans, inside) if not i)
    data = 1.0 - margin
    if data <= 0 or margin <= 0:
        return {c: c for c in cuts}
    c = max((1.0 - k * margin) / data, 0.4)
    grow = (1.0 - c * data) / margin  # == k unless the Axes reached their floor
    out, x = {cuts[0]: 0.0}, 0.0
    for (lo, hi), i in zip(spans, inside):
        x += (hi - lo) * (c if i else grow)
        out[hi] = x
    return out


def _lay_out_fixed(nat: _Natural, kx: float, ky: float) -> None:
    """Axes placed by hand (``add_axes``, ``subplots_adjust``): margins and gaps grow with the text, the Axes
    take the rest (:func:`_stretch`), from their places as built."""
    mx = _stretch([(b[0], b[0] + b[2]) for _ax, b in nat.boxes], kx)
    my = _stretch([(b[1], b[1] + b[3]) for _ax, b in nat.boxes], ky)

    def at(m, v):
        return m[min(m, key=lambda c: abs(c - v))]

    for ax, (x, y, w, h) in nat.boxes:
        x0, x1 = at(mx, max(x, 0.0)), at(mx, min(x + w, 1.0))
        y0, y1 = at(my, max(y, 0.0)), at(my, min(y + h, 1.0))
        ax.set_position([x0, y0, x1 - x0, y1 - y0])


def scale_figure(fig, width_px: float, height_px: float, text: float = 1.0) -> bool:
    """Draw ``fig`` at ``width_px`` × ``height_px`` CSS pixels with its text, lines and markers ``text`` times
    their size as built (1: as built); returns True if that changed anything.

    The figure's dpi becomes ``text`` × its dpi as built and its size in inches follows: when ``text`` is the
    zoom (``width_px`` over the natural width) the whole figure is zoomed and keeps its layout; otherwise it is
    laid out again — by its layout engine (constrained, also after :func:`freeze_layout`), or, for Axes placed
    by hand, by growing the margins with the text (:func:`_stretch`).  The device pixel ratio of a HiDPI screen
    is kept (ipympl's canvas draws at it).  Call the figure's draw afterwards.
    """
    nat = _natural(fig)
    w0, h0 = nat.px
    text = float(text)
    if not (width_px > 0 and height_px > 0 and text > 0):
        raise ValueError(f"scale_figure: width_px = {width_px}, height_px = {height_px}, text = {text}; all must be > 0")
    dpi = nat.dpi * text
    w_in, h_in = width_px / dpi, height_px / dpi
    cur_w, cur_h = fig.get_size_inches()
    if abs(getattr(fig, "_original_dpi", fig.dpi) - dpi) < 1e-6 and abs(cur_w - w_in) < 1e-4 and abs(cur_h - h_in) < 1e-4:
        return False
    ratio = float(getattr(fig.canvas, "device_pixel_ratio", 1.0) or 1.0)
    fig._original_dpi = dpi
    if abs(fig.dpi - dpi * ratio) < 1e-6:
        fig.set_size_inches(w_in, h_in, forward=True)
    else:
        fig.set_size_inches(w_in, h_in, forward=False)
        fig.set_dpi(dpi * ratio)  # tells the page (ipympl) the new size in pixels
    kx, ky = text * w0 / width_px, text * h0 / height_px  # text relative to the picture, 1 = zoomed as built
    engine = getattr(fig, "_aerophoto_engine", None) or fig.get_layout_engine()
    from matplotlib.layout_engine import PlaceHolderLayoutEngine

    if engine is not None and not isinstance(engine, PlaceHolderLayoutEngine):
        if getattr(fig, "_aerophoto_engine", None) is not None:  # frozen: lay it out once for the new size
            engine.execute(fig)
    elif nat.boxes:
        _lay_out_fixed(nat, kx, ky)
    _fit_titles(fig)
    fig.stale = True
    return True


def _fit_titles(fig) -> None:
    """Titles wider than the figure (larger text in a narrower figure) are set smaller until they fit; a title
    that fits again at its own size gets it back."""
    texts = [fig._suptitle] if getattr(fig, "_suptitle", None) is not None else []
    for ax in fig.axes:
        texts += [ax.title, ax._left_title, ax._right_title]
    renderer = fig.canvas.get_renderer()
    margin = 6 * fig.dpi / 72
    for text in texts:
        if not text.get_visible() or not text.get_text():
            continue
        # a centred title spreads both ways from its anchor (an axes' centre, often right of the figure's): its
        # room is twice the nearer edge's distance; a left or right title has the figure's width
        room = fig.bbox.width - margin
        if text.get_horizontalalignment() == "center":
            cx = text.get_transform().transform(text.get_position())[0]
            room = 2 * min(cx - fig.bbox.x0, fig.bbox.x1 - cx) - margin
        size = getattr(text, "_aerophoto_size", None)
        if size is None:
            size = text._aerophoto_size = text.get_fontsize()
        text.set_fontsize(size)
        width = text.get_window_extent(renderer).width
        # shrunk in proportion, then again: hinted glyphs are rounded to whole pixels, so a smaller title is a few
        # per cent wider than the proportion says (8.6 pt came out 406 px for 389 px of room)
        for _ in range(4):
            if not width > room > 0 or text.get_fontsize() <= 0.5 * size:
                break
            text.set_fontsize(max(text.get_fontsize() * room / width, 0.5 * size))  # never below half its size
            width = text.get_window_extent(renderer).width


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
#: JPEG quality of a photo demo's frames (:func:`fast_frames` ``photo_quality``): the lowest of 85 / 90 / 95 whose
#: frames differ from the exact pixels by a mean CIEDE2000 ΔE₀₀ ≤ 1 (about one just-noticeable difference) on
#: every demo with :attr:`aerophoto.widgets.LiveDemo.photo_frames`, with chroma kept at full resolution (4:4:4);
#: measured by ``benchmarks/bench_frames.py`` (90 gives 1.07 on the shooting conditions' photo), held by
#: tests/presentation/test_frames.py
PHOTO_QUALITY = 95
#: JPEG quality of a photo demo's *preview* frames (a demo that shows a coarser picture while its slider moves and
#: the full one once it rests: the fotoschema, the transformer): the lowest quality whose preview frames keep a
#: mean ΔE₀₀ ≤ 1 from the exact preview pixels and at most 2 % of pixels above ΔE₀₀ 5 on every such demo
#: (``benchmarks/bench_frames.py``'s ``chosen_preview_quality``); such a frame stands on the screen only while the
#: slider moves — the resting picture follows at :data:`PHOTO_QUALITY` (the fotoschema's preview: 90 gives mean
#: ΔE₀₀ 0.44 with 1.0 % of pixels above 5 and 109 kB against 145 kB at 95; 85 leaves 2.1 % above 5)
PREVIEW_QUALITY = 90
#: a photo demo's frame goes as a JPEG of the whole picture when at least this share of its pixels changed (a moved
#: photo); a smaller change (a line, a label) stays a lossless PNG of the changed pixels.  A changed photo pixel
#: costs the PNG ~3.4 bytes, the whole picture's JPEG at :data:`PHOTO_QUALITY` 0.2–0.7 bytes a pixel, so the JPEG is
#: the smaller frame from 0.06–0.22 of the picture changed (``benchmarks/bench_frames.py``'s ``jpeg_from_share``:
#: the quality demo 0.06, the fotoschema 0.09, the shooting conditions' photo 0.22), and it is 2–3× quicker to
#: encode; a move of a photo demo changes 0.3–0.84 of its pixels (at 0.3 before, the fotoschema's preview went as
#: a 400–500 kB PNG about every other move), a line or a label under 0.05
PHOTO_SHARE = 0.1
#: a PNG diff with fewer changed pixels than this share is compressed run-length (its zeros), else deflated
_RLE_SHARE = 0.3


def _png(rgba: np.ndarray, level: int, *, sparse: bool) -> bytes:
    """A PNG of an RGBA array (h, w, 4): each row unfiltered, zlib at ``level`` (RLE for a ``sparse`` diff).

    The same pixels as PIL's encoder writes, in a half to a third of its time: PIL tries its five row filters
    on every row, which for the transparent-but-for-a-line diff of a blit, or for noisy photo texture, buys
    little; a run-length pass suits a diff whose unchanged pixels are zeros.
    """
    import struct
    import zlib

    h, w, _ = rgba.shape
    rows = np.empty((h, w * 4 + 1), np.uint8)
    rows[:, 0] = 0  # filter type "none"
    rows[:, 1:] = rgba.reshape(h, w * 4)
    z = zlib.compressobj(level, zlib.DEFLATED, 15, 9, zlib.Z_RLE if sparse else zlib.Z_DEFAULT_STRATEGY)
    data = z.compress(rows.tobytes()) + z.flush()

    def chunk(kind: bytes, body: bytes) -> bytes:
        return struct.pack("!I", len(body)) + kind + body + struct.pack("!I", zlib.crc32(kind + body))

    return (b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack("!IIBBBBB", w, h, 8, 6, 0, 0, 0))
            + chunk(b"IDAT", data) + chunk(b"IEND", b""))


def _jpeg(rgb: np.ndarray, quality: int) -> bytes:
    from io import BytesIO

    from PIL import Image

    with BytesIO() as buf:
        Image.fromarray(np.ascontiguousarray(rgb)).save(buf, format="jpeg", quality=int(quality), subsampling=0)
        return buf.getvalue()


def _fast_diff_image(canvas, level: int):
    """``FigureCanvasWebAggCore.get_diff_image`` (matplotlib 3.9–3.11), cheaper to encode.

    Same full/diff decision and bookkeeping as matplotlib's; the frame is :func:`_png` at ``level`` (the same
    pixels, faster) — or, when the canvas has a photo quality (``canvas._aerophoto_photo_quality``, set by
    :func:`fast_frames` and :func:`frame_quality`), a JPEG of the whole figure in "full" mode when at least
    :data:`PHOTO_SHARE` of the pixels changed (ipympl's page decodes whatever image it is sent).  Returns the
    bytes, or None when the image is current.
    """
    if not canvas._png_is_old:
        return None
    pixels = np.asarray(canvas.get_renderer().buffer_rgba())
    buff = pixels.view(np.uint32).squeeze(2)
    opaque = bool((pixels[:, :, 3] == 255).all())
    full = canvas._force_full or buff.shape != canvas._last_buff.shape or not opaque
    changed = None if full else buff != canvas._last_buff
    share = 1.0 if changed is None else float(changed.mean())
    canvas._last_buff = buff.copy()
    canvas._force_full = False
    canvas._png_is_old = False
    photo_quality = getattr(canvas, "_aerophoto_photo_quality", None)
    if photo_quality is not None and opaque and share >= PHOTO_SHARE:
        canvas.set_image_mode("full")
        return _jpeg(pixels[:, :, :3], photo_quality)
    if changed is None:
        canvas.set_image_mode("full")
        output = buff
    else:
        canvas.set_image_mode("diff")
        output = np.where(changed, buff, 0)
    return _png(output.view(dtype=np.uint8).reshape((*output.shape, 4)), level, sparse=share < _RLE_SHARE)


def fast_frames(fig, level: int = FRAME_COMPRESS_LEVEL, *, photo_quality: int | None = None) -> bool:
    """Send ``fig``'s live frames (ipympl) cheaply encoded; returns whether it applied.

    An ipympl figure reaches the browser as a PNG of the pixels that changed.
    matplotlib compresses it at zlib's default level 6 with PIL's filtered rows; for a figure with a photo in
    it that costs 20–50 ms per frame.  Here the rows go unfiltered at ``level`` (1: a few per cent larger, a
    third of the time; the same pixels).  ``photo_quality`` (1–100, for demos whose frames are mostly photo,
    :attr:`aerophoto.widgets.LiveDemo.photo_frames`): a frame in which at least :data:`PHOTO_SHARE` of the picture
    changed is sent as a JPEG of that quality instead (:func:`frame_quality` changes it, e.g. for a preview) —
    3 ms to encode and a third to a fifth of the bytes, at a mean ΔE₀₀ below one
    just-noticeable difference for :data:`PHOTO_QUALITY`.  Only the frames change: ``savefig``, the inline
    backend and the notebook's saved picture draw the exact figure.  Only this figure's canvas is changed, and
    only when it is matplotlib's web canvas with the method this replaces; otherwise (inline backend, another
    matplotlib) nothing is done.
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
    if photo_quality is not None and not 1 <= int(photo_quality) <= 100:
        raise ValueError(f"photo_quality = {photo_quality} is outside the JPEG qualities 1 … 100")
    # the one place a frame's JPEG quality lives (None: lossless frames); frame_quality changes it (a preview's)
    canvas._aerophoto_photo_quality = None if photo_quality is None else int(photo_quality)
    canvas.get_diff_image = types.MethodType(lambda self: _fast_diff_image(self, level), canvas)
    return True


def frame_quality(fig, quality: int) -> bool:
    """The JPEG quality (1–100) of ``fig``'s photo frames from now on (a figure :func:`fast_frames` set up with a
    ``photo_quality``); returns whether it applied.  :class:`aerophoto.widgets.LiveDemo` sends a preview at
    :data:`PREVIEW_QUALITY` and the resting picture at :data:`PHOTO_QUALITY`.  A frame is encoded when the
    figure is blitted or drawn, from the pixels then on the canvas, so the quality set before a draw is the one
    its frame goes with."""
    canvas = getattr(fig, "canvas", None)
    if canvas is None or getattr(canvas, "_aerophoto_photo_quality", None) is None:
        return False
    quality = int(quality)
    if not 1 <= quality <= 100:
        raise ValueError(f"quality = {quality} is outside the JPEG qualities 1 … 100")
    canvas._aerophoto_photo_quality = quality
    return True


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


class PointLabels:
    """Short labels at data points (photo numbers on a mosaic), drawn as one collection of glyph outlines.

    ``labels = PointLabels(ax)``; ``labels.set(xy, texts, colors)`` moves them: ``xy`` shape (n, 2) in data
    coordinates, ``texts`` n strings, ``colors`` one colour or n.  Each label sits ``offset_pt`` (points, right
    and up) from its point, in bold ``fontsize`` points with a white halo, and scales with the figure's dpi as
    text does (:func:`scale_figure`).  Ten annotations cost ~10 ms a draw on Agg; the two collections
    (``artists``: the halo, then the glyphs) ~0.2 ms — what a slider move of a mosaic pays for its numbers.
    """

    def __init__(self, ax, *, offset_pt=(4.0, 4.0), fontsize: float = 9.0, weight: str = "bold",
                 zorder: float = 6.0, halo_pt: float = 2.4, halo_alpha: float = 0.85):
        from matplotlib.collections import PathCollection
        from matplotlib.font_manager import FontProperties
        from matplotlib.transforms import Affine2D

        self._font = FontProperties(size=fontsize, weight=weight)
        self._offset = (float(offset_pt[0]), float(offset_pt[1]))
        self._paths: dict = {}
        points = Affine2D().scale(1.0 / 72.0) + ax.figure.dpi_scale_trans  # glyphs in points, like text
        common = dict(offsets=np.zeros((0, 2)), offset_transform=ax.transData, transform=points)
        self.halo = PathCollection([], facecolors="white", edgecolors="white", linewidths=halo_pt,
                                   alpha=halo_alpha, zorder=zorder, **common)
        self.glyphs = PathCollection([], facecolors=COLORS["black"], edgecolors="none", zorder=zorder + 0.01,
                                     **common)
        for c in (self.halo, self.glyphs):
            ax.add_collection(c, autolim=False)
        self.artists = (self.halo, self.glyphs)

    def _path(self, text: str):
        p = self._paths.get(text)
        if p is None:
            from matplotlib.textpath import TextPath

            p = self._paths[text] = TextPath(self._offset, text, prop=self._font)
        return p

    def set(self, xy, texts, colors=None) -> None:
        xy = np.asarray(xy, dtype=float).reshape(-1, 2)
        texts = [str(t) for t in texts]
        if len(texts) != len(xy):
            raise ValueError(f"PointLabels.set: {len(texts)} texts for {len(xy)} points; give one text a point")
        paths = [self._path(t) for t in texts]
        for c in self.artists:
            c.set_paths(paths)
            c.set_offsets(xy)
        self.glyphs.set_facecolors(COLORS["black"] if colors is None else colors)
