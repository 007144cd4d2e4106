"""Live demos sized by their page: the figure follows its container, the lecture pages' projector mode.

A kernel does not know how wide the page is that shows its demo: JupyterLab beside its file browser gives a
notebook some 900 px at 1280×800, a lecture page in Voilà 1 250 px, a 1920×1080 projector 1 900 px.  A small
widget of the demo's layout, :func:`page_sensor` (an `anywidget <https://anywidget.dev>`_ with the page-side
script ``static/page.js``), reports the demo's width, the window's size and where the figure's row starts
(:class:`PageBox`); :func:`chapter_fit` and :func:`lecture_fit` turn that into the figure's size in CSS pixels
and the scale of its text (:class:`Fit`), and :func:`aerophoto.plots.scale_figure` draws the figure so — at the
page's resolution, never a picture stretched by the browser (whose clicks would land beside the point).

*  In a chapter the figure keeps its natural size (its figsize at 100 dpi) where it fits, beside the sliders or
   under them, and shrinks with a narrower column; its text stays at least :data:`MIN_TEXT` of its size.
*  On a lecture page the figure takes the room the screen leaves beside the key and the table and under the
   sliders, growing on a larger screen (the whole picture zoomed, text, lines and markers alike).
*  The projector mode (lecture pages: a toggle beside Reset, remembered in the browser) draws the figure's text,
   lines and markers :data:`PROJECTOR_TEXT` times larger (at least :data:`PROJECTOR_MIN` of the natural size:
   tick labels of 11 pt at ≥ 18 px) within the same room — the axes give way — and the page's CSS sets the
   tables, labels and sliders at ≥ 18 px (:mod:`aerophoto.demos.lecture`).

Without the page script (a static export, a test without a browser) no size is reported and the figure keeps
its natural size.  Sizes are CSS pixels; a scale of 1 is the figure as built.
"""

from __future__ import annotations

from dataclasses import dataclass

__all__ = ["PageBox", "Fit", "chapter_fit", "BESIDE", "lecture_fit", "page_sensor", "TOOLBAR_PX", "COLUMN_PX", "MIN_TEXT",
           "PROJECTOR_TEXT", "PROJECTOR_MIN", "SIDE_PX", "BOTTOM_PX", "PAGE_TOP_PX", "GAP_PX"]

#: the width of ipympl's toolbar beside the canvas (its position "right"), px
TOOLBAR_PX = 40
#: the width of a chapter demo's column of sliders, Reset and table, with its margin, px
COLUMN_PX = 362
#: a chapter's figure goes beside the sliders when it keeps this share of its size there, else under them
BESIDE = 0.7
#: the smallest scale of a chapter figure's text (a narrower figure gives its axes less room instead)
MIN_TEXT = 0.95
#: projector mode: text, lines and markers this much larger than the zoomed figure's ...
PROJECTOR_TEXT = 1.15
#: ... and at least this much larger than the figure as built (11 pt tick labels at 100 dpi × 1.3 = 19.9 px)
PROJECTOR_MIN = 1.3
#: a lecture page's side column (key, status line, table): its share of the width and its bounds, px
SIDE_PX = {False: (0.30, 330, 560), True: (0.36, 420, 720)}
#: room kept under a lecture demo, px
BOTTOM_PX = 24
#: room kept above a lecture demo's figure row besides the demo's own title and band, px: Voilà's top margin
#: (35 px; the page's first demo cannot scroll above it) and the figure widget's frame (8 px) — measured at
#: 1920×1080, where a figure sized without them ran 15 px off the screen's bottom
PAGE_TOP_PX = 44
#: the gap between figure and side column, px
GAP_PX = 12
#: a figure is never drawn smaller than this fraction of its natural size, nor larger than the last
_ZOOM = (0.3, 2.4)


@dataclass(frozen=True)
class PageBox:
    """What the page reports (CSS px): the demo's width, the window's width and height, the top of the
    figure's row measured from the demo's top (0 where the demo has no such row), and the side column's width
    and the height of its content (a lecture page's key, status line and table; 0 without one)."""

    width: int
    view_w: int
    view_h: int
    top: int = 0
    side_w: int = 0
    side_h: int = 0

    @classmethod
    def of(cls, value) -> "PageBox | None":
        """A PageBox from the sensor's ``box`` trait (``[width, view_w, view_h, top, side_w, side_h]``, the last
        two optional); None if nothing was reported."""
        try:
            values = [int(v) for v in value]
        except (TypeError, ValueError):
            return None
        if len(values) not in (4, 6) or min(values[:3]) <= 0:
            return None
        return cls(*values[:3], *(max(0, v) for v in values[3:]))


@dataclass(frozen=True)
class Fit:
    """A figure's size on the page (CSS px), the scale of its text, lines and markers (1 = as built) and the
    width left for a side column (px; 0 in a chapter)."""

    width_px: int
    height_px: int
    text: float
    side_px: int = 0
    #: a chapter's demo: the figure under the sliders rather than beside them
    stacked: bool = False


def _clamp(x: float, lo: float, hi: float) -> float:
    return max(lo, min(hi, x))


def chapter_fit(box: PageBox, natural_px: tuple[float, float], *, column_px: int = COLUMN_PX,
                toolbar_px: int = TOOLBAR_PX) -> Fit:
    """The figure of a chapter's demo in a column ``box.width`` wide (px).

    ``natural_px`` is the figure's (width, height) as built.  Beside the sliders when it fits there at
    :data:`BESIDE` of its size or more, else under them (``stacked``) at the column's width; never larger than
    built; its text at least :data:`MIN_TEXT` of its size.
    """
    w0, h0 = natural_px
    beside = box.width - column_px - toolbar_px
    stacked = beside < BESIDE * w0
    z = _clamp((box.width - toolbar_px if stacked else beside) / w0, _ZOOM[0], 1.0)
    return Fit(int(round(w0 * z)), int(round(h0 * z)), max(z, MIN_TEXT), stacked=stacked)


def lecture_fit(box: PageBox, natural_px: tuple[float, float], *, projector: bool = False,
                toolbar_px: int = TOOLBAR_PX) -> Fit:
    """The figure of a lecture page's demo: whole on the screen with the side column beside it.

    The side column takes its share of ``box.width`` (:data:`SIDE_PX`); the figure the rest of the width and the
    window's height under the sliders (``box.view_h - box.top``, less :data:`PAGE_TOP_PX` and :data:`BOTTOM_PX`), its aspect kept.  In
    projector mode the side column is wider and the text, lines and markers larger (:data:`PROJECTOR_TEXT`,
    :data:`PROJECTOR_MIN`).
    """
    w0, h0 = natural_px
    share, lo, hi = SIDE_PX[bool(projector)]
    side = int(_clamp(share * box.width, lo, hi))
    room_h = box.view_h - box.top - PAGE_TOP_PX - BOTTOM_PX
    # a side column whose content is taller than the room gets wider (its text wraps less) — by as much as the
    # height it lacks, up to half the width; one that needed it keeps it while its content fills 80 % of the room
    if box.side_w and box.side_h > room_h:
        side = max(side, int(min(box.side_w * box.side_h / room_h * 1.05 + 8, 0.5 * box.width)))
    elif box.side_w > side and box.side_h > 0.8 * room_h:
        side = min(box.side_w, int(0.5 * box.width))
    room_w = box.width - side - GAP_PX - toolbar_px
    z = _clamp(min(room_w / w0, room_h / h0), *_ZOOM)
    text = max(PROJECTOR_MIN, PROJECTOR_TEXT * z) if projector else z
    width, height = int(round(w0 * z)), int(round(h0 * z))
    return Fit(width, height, text, max(side, box.width - width - toolbar_px - GAP_PX))


_SENSOR = None


def _sensor_class():
    """The anywidget class of :func:`page_sensor`, made once (importing this module imports no widget library)."""
    global _SENSOR
    if _SENSOR is None:
        from importlib.resources import files

        import anywidget
        import traitlets

        class PageSensor(anywidget.AnyWidget):
            """Reports the page's size to the kernel and remembers the projector mode (see ``static/page.js``)."""

            _esm = files("aerophoto").joinpath("static", "page.js").read_text(encoding="utf-8")
            #: [demo width, window width, window height, top of the figure's row], CSS px; [] until reported
            box = traitlets.List(traitlets.Int(), default_value=[]).tag(sync=True)
            #: the projector mode, restored from and saved to the browser's localStorage under ``store``
            projector = traitlets.Bool(False).tag(sync=True)
            store = traitlets.Unicode("").tag(sync=True)
            #: the page's language (Voilà: the <html lang> attribute)
            lang = traitlets.Unicode("en").tag(sync=True)

        _SENSOR = PageSensor
    return _SENSOR


def page_sensor(*, store: str = "", projector: bool = False):
    """The page-side helper of one demo layout (an invisible widget; put it first in the demo's box), or None
    where anywidget is not installed (the figures keep their natural size; the browser book has it since the
    site carries its wheel and front end, :mod:`aerophoto.lite`).

    ``store``: the localStorage key the projector mode is remembered under (empty: not remembered).
    Observe its ``box`` (:meth:`PageBox.of`) and ``projector`` traits.
    """
    import ipywidgets as w

    from .i18n import get_language

    try:
        cls = _sensor_class()
    except ImportError:
        return None
    return cls(store=store, projector=bool(projector), lang=get_language(),
               layout=w.Layout(width="100%", height="0px", margin="0", overflow="hidden"))
