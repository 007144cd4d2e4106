"""Live demos: bounded, labelled, grouped sliders with a Reset, state in an object.

Every live demonstration of the book is a subclass of :class:`LiveDemo`:

* its parameters are declared once as :class:`Param` (name with unit, the
  slider's label with symbol and unit, bounds, step, default, group);
* it builds its figure **once** (:meth:`LiveDemo.build`) and on every change
  recomputes with the pure functions of a topic module (:meth:`compute`) and
  moves the existing artists (:meth:`render`), then draws once;
* its state lives in the object (``demo.values``, ``demo.result``), never in
  notebook globals, so a later cell cannot change what a callback shows;
* it can be driven from code — ``demo.set(f_mm=150, alpha_deg=2)`` — which is
  how tests, benchmarks and browser tests exercise it; ``set`` checks names
  and ranges with the same message as the package's functions;
* sliders observe ``names="value"`` only and are bounded by the parameter's
  range, so a slider can never produce input the model rejects.

A subclass looks like::

    class FootprintDemo(LiveDemo):
        title = "Camera footprint"
        params = (Param("f_mm", "f, mm", 50, 350, 10, 100, group="Camera"), ...)

        def build(self):
            self.fig, self.ax = plots.new_axes()
            (self.line,) = self.ax.plot([], [])

        def compute(self, f_mm, ...):
            return some_module.footprint(...)

        def render(self, result):
            self.line.set_data(result.x, result.y)
            self.table.value = plots.html_table(result.table())
"""

from __future__ import annotations

import contextlib
import math
import os
from dataclasses import dataclass

from ._validate import check_range

__all__ = ["Param", "LiveDemo", "error_html", "pending_html", "running_loop", "PREVIEW_NOTE", "FIGURE_MAX_PX", "TABLE_CSS",
           "table_after_picture", "TABLE_DELAY_S"]


def running_loop():
    """The kernel's running asyncio event loop, or None (a plain script or a test): a demo that paints a quick
    preview schedules its full picture, or its table, there; without a loop it does it at once."""
    import asyncio

    try:
        return asyncio.get_running_loop()
    except RuntimeError:
        return None


#: the widest figure a demo's layout shows whole, px (the right-hand column of :meth:`LiveDemo.widget`; a wider
#: canvas is cut off on the right, in JupyterLab and in Voilà alike)
FIGURE_MAX_PX = 900

#: the status line while a demo's full-resolution picture waits for the slider to rest
PREVIEW_NOTE = "preview — full resolution when the slider rests"


def pending_html(message: str = PREVIEW_NOTE) -> str:
    """A demo's status line while work is scheduled (:meth:`LiveDemo.later`), in the reader's language.

    The span's class ``aerophoto-pending`` marks it: the status clears itself when the work is done, and the
    browser tests wait for it to go before they read a demo's table.
    """
    from .i18n import t

    # one line that never wraps (the status line keeps its height: the table under it does not jump)
    return (f"<span class='aerophoto-pending' style='color:#777777;display:block;white-space:nowrap;"
            f"overflow:hidden;text-overflow:ellipsis'>{t(message)}</span>")


#: seconds a demo's table waits after its picture in a running kernel (:func:`table_after_picture`)
TABLE_DELAY_S = 0.06


def table_after_picture(demo, html, *args) -> None:
    """Set ``demo.table.value = html(*args)`` once the page has had time to paint the new picture.

    A table laid out by the page before the picture's frame arrives delays the picture by tens of ms (more in
    JupyterLab, whose notebook is a long page), so in a running kernel the table follows :data:`TABLE_DELAY_S`
    later (a newer move replaces a pending table); without an event loop (a script, a test) it is set at once.
    """
    def fill():
        demo.table.value = html(*args)

    _after_picture(demo, "_table_pending", fill)


def _after_picture(demo, slot: str, fill) -> None:
    """Call ``fill()`` :data:`TABLE_DELAY_S` from now in a running kernel (at once without an event loop).

    ``slot`` names the attribute of ``demo`` that holds the pending call: a newer call for the same slot
    fills the newest content but keeps the pending call's time (a stream of moves faster than the delay would
    otherwise hold the table back until the slider stops: the figure saying 196 nodes, the table 1 225), and
    :func:`_drop_after_picture` drops it.  The demos' tables and status lines use it.
    """
    loop = running_loop()
    if loop is None:
        _drop_after_picture(demo, slot)
        fill()
        return
    setattr(demo, slot + "_fill", fill)
    pending = getattr(demo, slot, None)
    if pending is not None and not pending.cancelled():
        return

    def run():
        setattr(demo, slot, None)
        getattr(demo, slot + "_fill")()

    setattr(demo, slot, loop.call_later(TABLE_DELAY_S, run))


def _drop_after_picture(demo, slot: str) -> None:
    """Drop the call :func:`_after_picture` holds in ``demo``'s ``slot``, if any."""
    pending = getattr(demo, slot, None)
    if pending is not None:
        pending.cancel()
    setattr(demo, slot, None)


class _HeldTable:
    """Stands in for a demo's table widget while a slider move renders: keeps the value instead of sending it."""

    def __init__(self, value: str):
        self.value = value


def _same_value(a, b, param) -> bool:
    """True when two values of ``param`` are the same setting (floats within a millionth of its step)."""
    if param.kind == "choice" or isinstance(a, str) or isinstance(b, str) or b is None:
        return a == b
    return abs(float(a) - float(b)) <= 1e-6 * max(abs(float(param.step or 1.0)), 1e-12)


def error_html(exc: BaseException) -> str:
    """A one-line, visible error message for a demo's status line (a callback never fails silently)."""
    import html

    return f"<span style='color:#D55E00'>⚠ {type(exc).__name__}: {html.escape(str(exc))}</span>"


@dataclass(frozen=True)
class Param:
    """One slider of a live demo.

    Parameters
    ----------
    name : str
        Keyword of :meth:`LiveDemo.set` and :meth:`LiveDemo.compute`, with its
        unit in the name (``f_mm``, ``alpha_deg``).
    label : str
        Slider label: the guide's symbol and the unit, e.g. ``"f, mm"``.
    lo, hi : float
        Inclusive bounds; the slider cannot leave them.
    step : float
        Slider step (also the keyboard step).
    default : float
        Value at start and after Reset.
    group : str
        Heading of the slider group ("Camera", "Flight", "Terrain", ...).
    kind : {"float", "int", "choice"}
        ``choice`` shows a dropdown of ``options`` (value = the option itself).
    options : tuple
        For ``kind="choice"``: ``(label, value)`` pairs or plain values.
    help : str
        Tooltip shown on hover.
    continuous : bool
        Update while dragging (True) or only on release (False).
    fmt : str
        Readout format of the slider, e.g. ``".1f"``.
    """

    name: str
    label: str
    lo: float = 0.0
    hi: float = 1.0
    step: float = 0.1
    default: float = 0.0
    group: str = ""
    kind: str = "float"
    options: tuple = ()
    help: str = ""
    continuous: bool = True
    fmt: str = ""

    def validate(self, value):
        if self.kind == "choice":
            values = [o[1] if isinstance(o, tuple) else o for o in self.options]
            if value not in values:
                raise ValueError(f"{self.name} = {value!r} is not one of the valid choices {values}")
            return value
        x = check_range(self.name, value, self.lo, self.hi)
        if self.kind == "int":
            if x != int(x):
                raise ValueError(f"{self.name} = {value!r} must be a whole number with {self.lo:g} ≤ {self.name} ≤ {self.hi:g}")
            return int(x)
        return x

    def make_widget(self):
        import ipywidgets as w

        from .i18n import t, translate_options

        style = {"description_width": "initial"}
        layout = w.Layout(width="340px")
        if self.kind == "choice":
            wid = w.Dropdown(options=translate_options(self.options), value=self.default, description=self.label,
                             style=style, layout=layout)
        elif self.kind == "int":
            wid = w.IntSlider(value=int(self.default), min=int(self.lo), max=int(self.hi), step=int(self.step),
                              description=self.label, continuous_update=self.continuous, style=style, layout=layout)
        else:
            fmt = self.fmt or _auto_format(self.step)
            wid = w.FloatSlider(value=self.default, min=self.lo, max=self.hi, step=self.step, readout_format=fmt,
                                description=self.label, continuous_update=self.continuous, style=style, layout=layout)
        wid.description = t(self.label)  # the reader's language (aerophoto.i18n); English: unchanged
        if self.help:
            wid.tooltip = t(self.help)
        return wid


#: the demos' tables, wherever they are shown: numbers never break across lines, a folded table's summary
#: looks like a caption, a table fills its column (it does not jump in width as its texts change), links in
#: prose are underlined (not told apart by colour alone)
TABLE_CSS = """
.aerophoto-table table { max-width: 100%; }
.aerophoto-table .num { white-space: nowrap; }
.aerophoto-table tbody th { text-align: left; font-weight: normal; }
.aerophoto-table details > summary { font-weight: bold; cursor: pointer; margin: 4px 0 2px 0; }
.aerophoto-side .aerophoto-table table { width: 100%; }
.jp-RenderedHTMLCommon a, .jp-RenderedMarkdown a, .widget-html-content a { text-decoration: underline; }
"""

#: projector-sized text for the demos' labels, readouts and hints (Lab and Voilà)
_DEMO_CSS = """<style>
.aerophoto-demo .widget-label, .aerophoto-demo .widget-readout, .aerophoto-demo .widget-html-content,
.aerophoto-demo .widget-button, .aerophoto-demo select { font-size: 15px; }
.aerophoto-demo .aerophoto-hint { font-size: 15px; margin-bottom: 4px; max-width: 1200px; }
.aerophoto-demo .widget-slider .slider-container { min-width: 120px; }
.aerophoto-demo .aerophoto-slider-note .widget-html-content { color: #333333; font-style: italic; line-height: 1.3; }
""" + TABLE_CSS + "</style>"


#: the chapter layout's grid (:meth:`LiveDemo.widget`): the column of sliders and the table left of the figure,
#: or (stacked) the sliders across the top, the figure and the table under them
_GRID = {
    False: {"grid_template_columns": "350px minmax(0, auto)", "grid_template_rows": "auto 1fr",
            "grid_template_areas": '"controls figure" "table figure"', "grid_gap": "0px 12px",
            "justify_content": "flex-start", "align_items": "flex-start"},
    True: {"grid_template_columns": "minmax(0, 100%)", "grid_template_rows": "auto auto auto",
           "grid_template_areas": '"controls" "figure" "table"', "grid_gap": "4px 0px",
           "justify_content": "flex-start", "align_items": "flex-start"},
}


def _auto_format(step: float) -> str:
    if step >= 1 and float(step).is_integer():
        return ".0f"
    decimals = max(0, min(4, -int(math.floor(math.log10(step)))))
    return f".{decimals}f"


class LiveDemo:
    """Base class of every live demo (see the module notes for the pattern).

    Subclasses set ``params`` and ``title`` and implement :meth:`build`,
    :meth:`compute` and :meth:`render`.  Construct with keyword values to start
    somewhere other than the defaults: ``Demo(f_mm=150)``.

    Attributes
    ----------
    values : dict
        Current parameter values, name → value.
    result : object
        What :meth:`compute` returned for ``values``.
    fig : matplotlib.figure.Figure
        The figure, built once.
    table : ipywidgets.HTML
        A table beside the figure; :meth:`render` sets its ``value``.
    n_updates : int
        How many times the demo has recomputed (for tests and benchmarks).
    """

    title: str = ""
    params: tuple = ()
    #: a short sentence under the title: what to try
    hint: str = ""
    #: lay the figure out once, at its first draw, and keep that layout (redraws get much cheaper)
    fixed_layout: bool = True
    #: show the figure's legends as HTML under it instead of drawing them on every update
    legend_beside: bool = True
    #: the demo's picture is mostly a photo that a move changes whole (a moved mosaic, a rendered photo, a
    #: map): its frames to the browser go as JPEG of :data:`aerophoto.plots.PHOTO_QUALITY` (see
    #: :func:`aerophoto.plots.fast_frames`), a preview (a result whose ``preview`` is True) at
    #: :data:`aerophoto.plots.PREVIEW_QUALITY`; the figure itself, savefig and the saved notebook stay exact
    photo_frames: bool = False
    #: parameters whose slider shows a note under it (what the value means, e.g. the motion a step is): the
    #: demo sets ``self.notes[name].value`` (HTML) in :meth:`render`
    noted: tuple = ()
    #: the artists a move changes (lines, markers, whole Axes whose limits move), set in :meth:`build`;
    #: when given, a move redraws only these over a cached picture of the rest (:class:`blit.Blitter`)
    animated: tuple = ()
    #: the handle of the work scheduled by :meth:`later` (None: nothing scheduled)
    _later = None
    #: True while a slider move is served (its table then follows the picture, :meth:`show`)
    _from_slider = False
    #: the handle of a status line waiting to follow the picture (:meth:`_status_after_picture`)
    _status_pending = None

    def __init__(self, **values):
        import ipywidgets as w

        from .plots import finish_figure

        self._params = {p.name: p for p in self.params}
        self.values = {p.name: p.default for p in self.params}
        for p in self.params:  # defaults must themselves be valid
            p.validate(p.default)
        self.values.update(self._checked(values))
        self.table = w.HTML()
        # a fixed height for the one-line status: a note that comes and goes never moves the table under it
        self.status = w.HTML(layout=w.Layout(min_height="24px"))
        #: the notes under the sliders of :attr:`noted`, name → HTML widget
        self.notes = {name: w.HTML(layout=w.Layout(margin="-4px 0 2px 0")) for name in self.noted}
        for note in self.notes.values():
            note.add_class("aerophoto-slider-note")
        self.n_updates = 0
        self._controls = {}
        self._syncing = False
        self._layout = None
        #: the box the figure and its key sit in (sized by fit_to), the last size the page reported, the rule
        #: that turns it into the figure's size (aerophoto.fit: chapter_fit; lecture_view sets lecture_fit)
        self._figure_box = None
        self._root = None
        self._fits = 0
        self._page_box = None
        self._fit_rule = None
        self.build()
        finish_figure(self.fig)  # texts in the reader's language, ticks in the book's number format, subscripts
        from .plots import fast_frames, freeze_layout, legend_html, lock_canvas

        #: the figure's legends, moved beside it as HTML (a legend redrawn on every update is costly)
        self.legend = w.HTML(legend_html(self.fig) if self.legend_beside else "")
        if self.fixed_layout:
            freeze_layout(self.fig)
        from .plots import PHOTO_QUALITY

        # cheaper frames to the browser (ipympl only): unfiltered PNG rows; a photo demo's moved photo as JPEG
        fast_frames(self.fig, photo_quality=PHOTO_QUALITY if self.photo_frames else None)
        if getattr(self, "fig", None) is not None:
            lock_canvas(self.fig)  # drawn under the figure's lock (widget messages may come on two threads)
        #: draws only ``animated`` on a move (None: every move draws the whole figure)
        self.blitter = None
        if self.animated and getattr(self, "fig", None) is not None and os.environ.get("AEROPHOTO_BLIT", "1") != "0":
            from .blit import Blitter

            self.blitter = Blitter(self.fig, self.animated)
        #: where Reset returns: the values the demo was built with (e.g. the student's variant)
        self.start_values = dict(self.values)
        self.update()

    # ----------------------------------------------------------- to override
    def build(self) -> None:
        """Create ``self.fig`` and its artists once."""
        raise NotImplementedError

    def compute(self, **values):
        """Return the model result for the parameter values (pure; no drawing)."""
        raise NotImplementedError

    def render(self, result) -> None:
        """Move the existing artists and refresh ``self.table`` for ``result``."""
        raise NotImplementedError

    # ----------------------------------------------------------- driving
    def _checked(self, values: dict) -> dict:
        out = {}
        for name, value in values.items():
            if name not in self._params:
                valid = ", ".join(self._params)
                raise ValueError(f"{name!r} is not a parameter of {type(self).__name__}; valid parameters: {valid}")
            out[name] = self._params[name].validate(value)
        return out

    def set(self, **values):
        """Change parameters from code, as if the sliders were moved; returns self.

        Always at full resolution and final: work a slider move scheduled (:meth:`later`) is dropped.
        """
        checked = self._checked(values)
        with self._locked():
            self.values.update(checked)
            self._sync_controls(checked)
            self.cancel_later()
            self.update()
        return self

    def _locked(self):
        """The figure's lock (:func:`aerophoto.plots.figure_lock`): every change of the demo from a callback or
        from code, and every draw, holds it."""
        if getattr(self, "fig", None) is None:
            return contextlib.nullcontext()
        from .plots import figure_lock

        return figure_lock(self.fig)

    def reset(self):
        """Back to where the demo started (the values it was built with, else the defaults)."""
        return self.set(**self.start_values)

    def later(self, delay_s: float, fn) -> bool:
        """Run ``fn()`` once, ``delay_s`` seconds from now, on the kernel's event loop; returns True if scheduled.

        Whatever was scheduled before is dropped (a newer slider move supersedes
        an older one's full picture); :meth:`set`, Reset and :meth:`close` drop it
        too.  ``fn`` may schedule the next piece of work itself.  When the work
        is done the status line's :func:`pending_html` note is cleared; a failure
        is shown there instead.  Without a running loop (a script, a test)
        ``fn`` runs at once and False is returned.
        """
        self._drop_later()
        loop = running_loop()
        if loop is None:
            fn()
            return False

        def run():
            self._later = None
            try:
                with self._locked():
                    fn()
            except Exception as exc:  # never let a callback die silently
                self._drop_status_later()
                self.status.value = error_html(exc)
                return
            if self._later is None and "aerophoto-pending" in self.status.value:
                self._status_after_picture("")

        self._later = loop.call_soon(run) if delay_s <= 0 else loop.call_later(delay_s, run)
        return True

    #: True while :meth:`preview_then_full` computes the quick preview (``compute`` reads it)
    _preview = False

    def preview_then_full(self, delay_s: float, note: str = PREVIEW_NOTE) -> str:
        """What a heavy demo's slider move does: a preview now (``compute`` sees ``self._preview`` True), the full
        resolution once the slider has rested ``delay_s`` seconds (:meth:`later`); without an event loop (a script,
        a test) the full resolution at once.  Returns the status line (:func:`pending_html` of ``note``, or "").
        A pending note of the previous move stays up (a move while dragging sends no status of its own)."""
        self._drop_later()
        if running_loop() is None:
            self.update()
            return ""
        self._preview = True
        try:
            self.update()
        finally:
            self._preview = False
        self.later(delay_s, self.update)
        return pending_html(note)

    def _drop_later(self) -> None:
        if self._later is not None:
            self._later.cancel()
            self._later = None
        self._drop_status_later()

    def _drop_status_later(self) -> None:
        _drop_after_picture(self, "_status_pending")

    def _status_after_picture(self, value: str) -> None:
        """Set the status line to ``value`` once the page has had time to paint the picture just drawn.

        The status is HTML: a note laid out by the page right after a picture's frame arrives holds that frame's
        decoding back (some 10–20 ms in JupyterLab), so in a running kernel it follows :data:`TABLE_DELAY_S`
        later, like the table; a :func:`pending_html` note whose work is done by then is not shown at all.
        Without an event loop, or when the line is already ``value``, it is set at once.
        """
        if value == self.status.value:
            self._drop_status_later()
            return

        def fill():
            if "aerophoto-pending" in value and self._later is None:
                return  # the work it announces has been done already
            self.status.value = value

        _after_picture(self, "_status_pending", fill)

    def _drop_table_later(self) -> None:
        _drop_after_picture(self, "_table_pending")

    def cancel_later(self) -> None:
        """Drop the work scheduled by :meth:`later`, if any, and its note on the status line."""
        self._drop_later()
        if "aerophoto-pending" in self.status.value:
            self.status.value = ""

    def update(self) -> None:
        """Recompute with the current values, move the artists, draw once."""
        self.show(self.compute(**self.values))

    def show(self, result) -> None:
        """Show a computed ``result``: keep it as ``self.result``, move the artists, draw once.

        On a slider move the table that :meth:`render` sets is sent after the picture
        (:func:`table_after_picture`), so the page paints the figure first.
        """
        self.result = result
        if self.photo_frames:  # a preview (result.preview) goes to the browser as a lighter JPEG
            from .plots import PHOTO_QUALITY, PREVIEW_QUALITY, frame_quality

            frame_quality(self.fig, PREVIEW_QUALITY if getattr(result, "preview", False) else PHOTO_QUALITY)
        if not self._from_slider:
            self._drop_table_later()  # a table a slider move left pending is older than this one
            self.render(result)
            self.n_updates += 1
            self.draw()
            return
        table = self.table
        held = self.table = _HeldTable(table.value)
        try:
            self.render(result)
        finally:
            self.table = table
        self.n_updates += 1
        self.draw()
        if held.value != table.value:
            table_after_picture(self, str, held.value)

    def draw(self, force: bool = False) -> None:
        """Redraw the figure (``force=True`` renders the whole figure now, e.g. in tests and benchmarks).

        With ``animated`` artists a move redraws only those over the cached
        rest of the figure and blits it; a full draw happens instead whenever
        anything else changed (limits, ticks, titles) or the size did.
        """
        from .plots import draw

        if getattr(self, "fig", None) is None:
            return
        if not force and self.blitter is not None and self.blitter.update():
            return
        draw(self.fig, force=force)

    # ----------------------------------------------------------- widgets
    def _sync_controls(self, values: dict) -> None:
        if not self._controls:
            return
        self._syncing = True
        try:
            for name, value in values.items():
                ctl = self._controls.get(name)
                if ctl is not None and ctl.value != value:
                    ctl.value = value
        finally:
            self._syncing = False

    def on_slider(self) -> str:
        """What a slider move does once ``values`` holds the new value.

        By default one full :meth:`update`.  Heavy demos override it (e.g. a
        preview now, full resolution when the slider rests).  Returns a status
        line (HTML) to show under the sliders, or ``""``.
        """
        self.update()
        return ""

    def _on_change(self, change) -> None:
        if self._syncing:
            return
        name = change["owner"]._aerophoto_name
        with self._locked():
            self._serve_slider(name, change)

    def _serve_slider(self, name: str, change) -> None:
        from .i18n import t

        self._from_slider = True
        try:
            value = self._params[name].validate(change["new"])
            if _same_value(value, self.values.get(name), self._params[name]):
                return  # the page sent back the value the demo shows (e.g. after Reset): nothing to redraw
            self.values[name] = value
            self._status_after_picture(t(self.on_slider()))
        except Exception as exc:  # never let a callback die silently
            self._drop_status_later()
            self.status.value = error_html(exc)
        finally:
            self._from_slider = False

    def _on_reset(self) -> None:
        try:
            self.reset()  # set() holds the figure's lock
        except Exception as exc:  # never let a callback die silently
            self.status.value = error_html(exc)

    def controls(self) -> dict:
        """The slider widgets, name → widget (created on first call)."""
        if not self._controls:
            for p in self.params:
                ctl = p.make_widget()
                ctl.value = self.values[p.name]
                ctl._aerophoto_name = p.name
                ctl.observe(self._on_change, names="value")
                self._controls[p.name] = ctl
        return self._controls

    def figure_widget(self):
        from .plots import figure_widget

        return figure_widget(self.fig)

    def widget(self):
        """The whole demo, laid out for its page (sized by it, :mod:`aerophoto.fit`).

        Title and hint on top; on the left a column with the grouped sliders,
        Reset, the status line and the table; on the right the figure.  In a
        column too narrow for the figure beside the sliders (JupyterLab beside
        its file browser) the sliders' groups go side by side across the top,
        the figure under them, the table under the figure.
        """
        if self._layout is not None:
            return self._layout
        import ipywidgets as w

        from .i18n import t

        ctls = self.controls()
        groups: dict[str, list] = {}
        for p in self.params:
            groups.setdefault(p.group, []).append(ctls[p.name])
            if p.name in self.notes:
                groups[p.group].append(self.notes[p.name])
        column = []
        for g, items in groups.items():
            head = [w.HTML(f"<b>{t(g)}</b>")] if g else []
            column.append(w.VBox(head + items, layout=w.Layout(margin="0 16px 6px 0")))
        reset = w.Button(description=t("Reset"), icon="undo", tooltip=t("Back to the starting values"),
                         layout=w.Layout(width="110px"))
        reset.on_click(lambda _b: self._on_reset())
        self.reset_button = reset
        controls = w.VBox([*column, w.VBox([reset, self.status], layout=w.Layout(margin="0 16px 0 0"))],
                          layout=w.Layout(grid_area="controls", align_items="flex-start"))
        table = w.VBox([self.table], layout=w.Layout(grid_area="table", min_width="0"))
        figure = w.VBox([self.figure_widget(), self.legend], layout=w.Layout(grid_area="figure", min_width="0"))
        self._figure_box = figure
        self._grid = w.GridBox([controls, figure, table], layout=w.Layout(**_GRID[False]))
        self._grid._aerophoto_parts = (controls, table)
        parts = [w.HTML(_DEMO_CSS), *filter(None, [self.page_sensor()])]
        if self.title:
            parts.append(w.HTML(f"<h3 style='margin:4px 0'>{t(self.title)}</h3>"))
        if self.hint:
            parts.append(w.HTML(f"<div class='aerophoto-hint'>{t(self.hint)}</div>"))
        parts.append(self._grid)
        self._layout = self._root = w.VBox(parts, layout=w.Layout(max_width="1300px"))
        self._layout.add_class("aerophoto-demo")
        return self._layout

    def _stack(self, stacked: bool) -> None:
        """The chapter layout side by side (False) or stacked (True): see :meth:`widget`."""
        grid = getattr(self, "_grid", None)
        if grid is None or getattr(grid, "_aerophoto_stacked", False) == stacked:
            return
        controls, table = grid._aerophoto_parts
        for key, value in _GRID[stacked].items():
            setattr(grid.layout, key, value)
        controls.layout.flex_flow = "row wrap" if stacked else "column nowrap"
        grid._aerophoto_stacked = stacked

    # ----------------------------------------------------------- the page's size
    def page_sensor(self, *, store: str = "", projector: bool = False):
        """A new page sensor (:func:`aerophoto.fit.page_sensor`) whose reports size this demo's figure (None
        without anywidget)."""
        from .fit import page_sensor

        sensor = page_sensor(store=store, projector=projector)
        if sensor is not None:
            sensor.observe(self._on_page_box, names="box")
        return sensor

    def _on_page_box(self, change) -> None:
        from .fit import PageBox

        box = PageBox.of(change["new"])
        if box is None:
            return
        self._page_box = box
        try:
            self.refit()
        except Exception as exc:  # never let a callback die silently
            self.status.value = error_html(exc)

    def refit(self) -> None:
        """Size the figure for the page's last reported box (nothing before the page reported one)."""
        if self._page_box is None or getattr(self, "fig", None) is None:
            return
        from .fit import chapter_fit
        from .plots import natural_size_px

        rule = self._fit_rule or chapter_fit
        with self._locked():
            self.fit_to(rule(self._page_box, natural_size_px(self.fig)))

    def fit_to(self, fit) -> None:
        """Draw the figure at ``fit`` (:class:`aerophoto.fit.Fit`: its size in CSS px, the scale of its text)."""
        from .fit import TOOLBAR_PX
        from .plots import scale_figure

        self._stack(fit.stacked)
        if self._figure_box is not None:
            self._figure_box.layout.width = f"{fit.width_px + TOOLBAR_PX}px"
        if scale_figure(self.fig, fit.width_px, fit.height_px, fit.text):
            self.draw(force=False)
        if self._root is not None:  # the page's size has reached the figure: aerophoto-fit-N for the N-th (tests)
            self._fits += 1
            self._root.remove_class(f"aerophoto-fit-{self._fits - 1}")
            self._root.add_class(f"aerophoto-fit-{self._fits}")

    def _ipython_display_(self):
        from IPython.display import display

        display(self.widget())

    def close(self) -> None:
        """Close the figure and widgets (frees the kernel side)."""
        import matplotlib.pyplot as plt

        self.cancel_later()
        self._drop_table_later()
        self._drop_status_later()
        with contextlib.suppress(Exception):
            plt.close(self.fig)
        if self._layout is not None:
            self._layout.close()
