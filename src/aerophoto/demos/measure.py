"""A measuring tool: read coordinates of pricked points off a picture in millimetres, by clicking.

The guide has students prick points on a photo and on a plan and measure them
with a ruler or a coordinatograph to 0.1 mm (§3–§7, §10–§13).  In the book they
measure on a picture in an ipympl figure: :class:`MeasureTool` shows an image
(a rendered photo, a plan, a fotoschema …) in sheet millimetres with the pricked
points marked, reports the cursor position to 0.1 mm while the mouse moves, and
records a click as the measurement of the selected point (then moves on to the
next point not yet measured).  The toolbar's zoom magnifies the picture (switch
it off again before clicking: clicks made while zooming or panning are ignored).

The measurements are the student's own data: the tool shows them in a table and
as ready-to-paste Python lines (:meth:`MeasureTool.code`), because an answer
cell must hold the numbers themselves — a grader re-running the notebook sees no
clicks.  Everything can be driven from code (``tool.measure("I", 12.3, -4.5)``,
``tool.click(x, y)``), which is how the tests use it.

API (for every chapter that measures)::

    tool = MeasureTool(image, extent_mm, names, marks={name: (x, y)}, title="…",
                       xlabel="x, mm", ylabel="y, mm", decimals=1, contours=None, origin="upper")
    tool                      # displays the widget (figure, point selector, readout, table, code)
    tool.widget(x_name="xpl_mm", y_name="ypl_mm")   # the same, naming the variables of the code lines
    tool.select("II")         # the point the next click measures
    tool.measure("II", x, y)  # record a reading from code (rounded to `decimals`)
    tool.measured             # {name: (x, y) or None}
    tool.xy()                 # (n, 2) array, NaN where not measured
    tool.x_mm(), tool.y_mm()  # lists in the order of `names`, None where not measured
    tool.table()              # DataFrame "x, mm", "y, mm"
    tool.code("x_mm", "y_mm") # "x_mm = [12.3, …]\\ny_mm = […]" (… where not measured)
    tool.load(xs, ys)         # put earlier readings back (e.g. after a restart)
    tool.clear(name=None)     # forget one point or all

:func:`photo_tool` and :func:`plan_tool` build one for a lab sheet of chapters 03–04
(:class:`aerophoto.labs.displacement.LabSheet`): the student's photo with its
fiducial marks, or the plan at 1:M with contours.
"""

from __future__ import annotations

import html
import math

import numpy as np
import pandas as pd
from matplotlib import patheffects

from .. import plots
from ..i18n.numfmt import fmt_scale

__all__ = ["MeasureTool", "photo_tool", "plan_tool"]

_CONTOUR = "#8C510A"  # contour lines (brown, as on a topographic plan)

_HELP = ("Pick a point in the list (or let the tool move on by itself) and click its mark. "
         "Magnify first: the toolbar's □ zooms to a rectangle — click it again to switch zooming off before "
         "you click a point (clicks made while zooming or panning are not recorded); ⌂ shows the whole sheet.")


class MeasureTool:
    """Measure the coordinates of named points on a picture by clicking (see the module notes).

    Parameters
    ----------
    image : array_like, shape (rows, cols)
        Brightness 0…1 (grey) — row 0 at the top with ``origin="upper"``.
    extent_mm : (left, right, bottom, top)
        Where the image lies in sheet millimetres.
    names : sequence of str
        The points to measure, in the order of the answers.
    marks : dict name → (x, y), optional
        The pricked marks to draw (a small ring with a dot at the prick and the name beside it).
    title, xlabel, ylabel : str
    decimals : int
        Readings are rounded to this many decimals of a millimetre (1: to 0.1 mm, as the guide measures).
    contours : (x, y, Z, levels), optional
        Contour lines to draw over the picture (plan mm and heights in m).
    origin : str
        ``"upper"`` (row 0 at the top, as photos and plans here) or ``"lower"``.
    figsize : (w, h) inches
    """

    def __init__(self, image, extent_mm, names, *, marks=None, title: str = "", xlabel: str = "x, mm",
                 ylabel: str = "y, mm", decimals: int = 1, contours=None, origin: str = "upper",
                 figsize=(6.4, 6.4)):
        names = tuple(str(n) for n in names)
        if not names or len(set(names)) != len(names):
            raise ValueError(f"names = {names!r} must be one or more distinct point names")
        ext = tuple(float(e) for e in extent_mm)
        if len(ext) != 4 or not all(math.isfinite(e) for e in ext) or ext[0] >= ext[1] or ext[2] >= ext[3]:
            raise ValueError(f"extent_mm = {extent_mm!r} must be (left, right, bottom, top) with left < right, "
                             "bottom < top (mm)")
        if origin not in ("upper", "lower"):
            raise ValueError(f"origin = {origin!r} is not one of the valid choices ['upper', 'lower']")
        if int(decimals) != decimals or not 0 <= int(decimals) <= 3:
            raise ValueError(f"decimals = {decimals!r} is outside the valid range 0 ≤ decimals ≤ 3")
        self.names = names
        self.extent_mm = ext
        self.decimals = int(decimals)
        self.measured: dict = {n: None for n in names}
        self.current = names[0]
        self.n_clicks = 0
        self._widgets = None
        self._code_names = ("x_mm", "y_mm")
        self._build(np.asarray(image), ext, marks or {}, title, xlabel, ylabel, contours, origin, figsize)

    # ------------------------------------------------------------------ the figure
    def _build(self, image, ext, marks, title, xlabel, ylabel, contours, origin, figsize):
        C = plots.COLORS
        self.fig = plots.figure(figsize=figsize)
        ax = self.fig.add_subplot(1, 1, 1)
        self.ax = ax
        ax.imshow(image, cmap="gray", vmin=0.0, vmax=1.0, extent=ext, origin=origin, interpolation="antialiased")
        if contours is not None:
            cx, cy, Z, levels = contours
            cs = ax.contour(cx, cy, Z, levels=levels, colors=[_CONTOUR], linewidths=0.6, alpha=0.8)
            major = [lv for lv in cs.levels if abs(lv / 10.0 - round(lv / 10.0)) < 1e-9]
            if major:
                ax.clabel(cs, levels=major, fmt="%.0f", fontsize=8, inline=True)
        self.marks = {}
        halo = [patheffects.withStroke(linewidth=2.5, foreground="black")]
        for n, (x, y) in marks.items():
            ring = ax.plot([x], [y], linestyle="none", marker="o", ms=11, mfc="none", mec=C["yellow"], mew=1.6,
                           zorder=5, path_effects=halo)[0]
            dot = ax.plot([x], [y], linestyle="none", marker=".", ms=2.5, color=C["yellow"], zorder=6)[0]
            label = ax.annotate(str(n), (x, y), xytext=(7, 7), textcoords="offset points", color=C["yellow"],
                                fontsize=12, fontweight="bold", zorder=6, path_effects=halo)
            self.marks[str(n)] = (ring, dot, label)
        (self.readings,) = ax.plot([], [], linestyle="none", marker="x", ms=8, mew=1.6, color=C["relief"],
                                   zorder=7, label="your readings")
        ax.set_xlim(ext[0], ext[1])
        ax.set_ylim(ext[2], ext[3])
        ax.set_aspect("equal")
        ax.grid(False)
        ax.set_xlabel(xlabel)
        ax.set_ylabel(ylabel)
        if title:
            ax.set_title(title)
        plots.freeze_layout(self.fig)  # lay out once, at the first draw: a click then redraws without layout work
        plots.fast_frames(self.fig)
        self._cids = (self.fig.canvas.mpl_connect("button_press_event", self._on_press),
                      self.fig.canvas.mpl_connect("motion_notify_event", self._on_move))

    # ------------------------------------------------------------------ measuring
    def _round(self, v: float) -> float:
        return round(float(v), self.decimals) + 0.0

    def select(self, name: str) -> "MeasureTool":
        """Make ``name`` the point the next click measures."""
        name = str(name)
        if name not in self.measured:
            raise ValueError(f"name = {name!r} is not one of the points {list(self.names)}")
        self.current = name
        if self._widgets is not None and self._widgets["point"].value != name:
            self._widgets["point"].value = name
        return self

    def measure(self, name: str, x_mm: float, y_mm: float) -> "MeasureTool":
        """Record a reading of point ``name`` (rounded to ``decimals``); returns the tool."""
        name = str(name)
        if name not in self.measured:
            raise ValueError(f"name = {name!r} is not one of the points {list(self.names)}")
        x, y = float(x_mm), float(y_mm)
        if not (math.isfinite(x) and math.isfinite(y)):
            raise ValueError(f"x_mm, y_mm = {x_mm!r}, {y_mm!r} must be finite numbers (mm)")
        self.measured[name] = (self._round(x), self._round(y))
        self._refresh()
        return self

    def click(self, x_mm: float, y_mm: float) -> str:
        """A click at (x, y): measures the selected point and selects the next unmeasured one; returns its name."""
        name = self.current
        self.measure(name, x_mm, y_mm)
        self.n_clicks += 1
        following = [n for n in self.names[self.names.index(name) + 1:] + self.names if self.measured[n] is None]
        if following:
            self.select(following[0])
        return name

    def clear(self, name: str | None = None) -> "MeasureTool":
        """Forget the reading of ``name`` (of every point when None)."""
        for n in (self.names if name is None else (str(name),)):
            if n not in self.measured:
                raise ValueError(f"name = {n!r} is not one of the points {list(self.names)}")
            self.measured[n] = None
        self._refresh()
        return self

    def load(self, x_mm, y_mm) -> "MeasureTool":
        """Put readings back, e.g. the lists of an answer cell after the kernel restarted (None = not measured)."""
        xs, ys = list(x_mm), list(y_mm)
        if len(xs) != len(self.names) or len(ys) != len(self.names):
            raise ValueError(f"x_mm and y_mm need {len(self.names)} values each, one per point {list(self.names)}")
        for n, x, y in zip(self.names, xs, ys):
            if x is None or y is None or x is Ellipsis or y is Ellipsis:
                self.measured[n] = None
            else:
                self.measured[n] = (self._round(x), self._round(y))
        self._refresh()
        return self

    # ------------------------------------------------------------------ results
    def xy(self) -> np.ndarray:
        """The readings, shape (n, 2) mm, NaN where a point is not measured yet."""
        return np.array([self.measured[n] if self.measured[n] is not None else (np.nan, np.nan) for n in self.names],
                        dtype=float)

    def x_mm(self) -> list:
        """x of every point in the order of ``names`` (None where not measured)."""
        return [None if self.measured[n] is None else self.measured[n][0] for n in self.names]

    def y_mm(self) -> list:
        """y of every point in the order of ``names`` (None where not measured)."""
        return [None if self.measured[n] is None else self.measured[n][1] for n in self.names]

    @property
    def complete(self) -> bool:
        """Every point measured."""
        return all(v is not None for v in self.measured.values())

    def table(self) -> pd.DataFrame:
        """The readings: columns ``x, mm`` and ``y, mm``, one row per point (NaN where not measured)."""
        xy = self.xy()
        return pd.DataFrame({"x, mm": xy[:, 0], "y, mm": xy[:, 1]}, index=pd.Index(self.names, name="point"))

    def code(self, x_name: str = "x_mm", y_name: str = "y_mm") -> str:
        """The readings as two Python lines to paste into an answer cell (``...`` where not measured)."""
        fmt = f"{{:.{self.decimals}f}}"

        def line(name, vals):
            return f"{name} = [" + ", ".join("..." if v is None else fmt.format(v) for v in vals) + "]"

        return line(x_name, self.x_mm()) + "\n" + line(y_name, self.y_mm())

    # ------------------------------------------------------------------ events
    def _toolbar_busy(self) -> bool:
        canvas = self.fig.canvas
        tb = getattr(canvas, "toolbar", None) or getattr(getattr(canvas, "manager", None), "toolbar", None)
        return bool(str(getattr(tb, "mode", "") or ""))

    def _on_press(self, event) -> None:
        if event.inaxes is not self.ax or event.button != 1 or event.xdata is None or self._toolbar_busy():
            return
        try:
            self.click(event.xdata, event.ydata)
        except Exception as exc:  # a callback never fails silently
            if self._widgets is not None:
                from ..widgets import error_html

                self._widgets["status"].value = error_html(exc)

    def _on_move(self, event) -> None:
        if self._widgets is None:
            return
        if event.inaxes is self.ax and event.xdata is not None:
            f = f"{{:.{self.decimals}f}}"
            self._widgets["readout"].value = (f"<b>cursor</b>: x = {f.format(event.xdata)} mm, "
                                              f"y = {f.format(event.ydata)} mm")

    # ------------------------------------------------------------------ display
    def _refresh(self) -> None:
        xy = self.xy()
        ok = ~np.isnan(xy[:, 0])
        self.readings.set_data(xy[ok, 0], xy[ok, 1])
        plots.draw(self.fig)
        if self._widgets is None:
            return
        w = self._widgets
        w["table"].value = self.table_html()
        w["code"].value = self.code(*self._code_names)
        done = sum(v is not None for v in self.measured.values())
        w["status"].value = (f"{done} of {len(self.names)} points measured" +
                             (" — copy the lines below into the answer cell." if self.complete else ""))

    def table_html(self) -> str:
        """The readings as an HTML table (— where not measured)."""
        return plots.html_table(self.table(), caption="Your readings",
                                float_format=f"{{:.{self.decimals}f}}").replace("font-size:15px", "font-size:13px")

    def widget(self, *, x_name: str | None = None, y_name: str | None = None):
        """The tool: the figure on the left; point selector, cursor readout, readings and code on the right.

        ``x_name``, ``y_name`` name the variables of the paste-able lines (default ``x_mm``, ``y_mm``; they stay
        as first given).
        """
        import ipywidgets as w

        if x_name is not None or y_name is not None:
            self._code_names = (x_name or self._code_names[0], y_name or self._code_names[1])
        if self._widgets is not None:
            self._refresh()
            return self._widgets["layout"]
        point = w.Dropdown(options=list(self.names), value=self.current, description="point",
                           layout=w.Layout(width="200px"))
        point.observe(lambda ch: self.select(ch["new"]), names="value")
        clear_one = w.Button(description="Clear point", layout=w.Layout(width="110px"))
        clear_one.on_click(lambda _b: self.clear(self.current))
        clear_all = w.Button(description="Clear all", layout=w.Layout(width="110px"))
        clear_all.on_click(lambda _b: self.clear())
        code = w.Textarea(value="", layout=w.Layout(width="330px", height="64px"))
        readout, status, table = w.HTML(), w.HTML(), w.HTML()
        side = [point, w.HBox([clear_one, clear_all]), readout, status, code, table,
                w.HTML(f"<div style='font-size:12px;line-height:1.35;max-width:330px;color:#444'>"
                       f"{html.escape(_HELP)}</div>")]
        self._widgets = {"point": point, "readout": readout, "status": status, "table": table, "code": code}
        right = w.VBox(side, layout=w.Layout(width="350px", margin="0 0 0 12px"))
        layout = w.HBox([plots.figure_widget(self.fig), right], layout=w.Layout(align_items="flex-start"))
        self._widgets["layout"] = layout
        self._widgets["readout"].value = "<b>cursor</b>: move the mouse over the picture"
        self._refresh()
        return layout

    def _ipython_display_(self):
        from IPython.display import display

        display(self.widget())

    def close(self) -> None:
        """Close the figure and the widgets."""
        import matplotlib.pyplot as plt

        for cid in self._cids:
            self.fig.canvas.mpl_disconnect(cid)
        plt.close(self.fig)
        if self._widgets is not None:
            self._widgets["layout"].close()


# --------------------------------------------------------------------------- the lab sheets of chapters 03–04
def photo_tool(sheet, **kwargs) -> MeasureTool:
    """A tool on the student's photo of a lab sheet: the rendered photo in photo mm with the pricked points.

    ``sheet`` is a :class:`aerophoto.labs.displacement.LabSheet` (anything with ``photo()``,
    ``marks("photo")`` and ``names``).  The principal point o is the crossing of the fiducial marks' axes.
    """
    photo = sheet.photo()
    kwargs.setdefault("title", "Your photo (x, y from o, mm)")
    tool = MeasureTool(photo.image, photo.extent_mm, sheet.names, marks=sheet.marks("photo"), **kwargs)
    h = photo.camera.half_mm
    tool.ax.plot([-h, h], [0, 0], color=plots.COLORS["grey"], lw=0.5, alpha=0.6, zorder=2)
    tool.ax.plot([0, 0], [-h, h], color=plots.COLORS["grey"], lw=0.5, alpha=0.6, zorder=2)
    return tool


def plan_tool(sheet, *, contour_interval_m: float = 2.0, **kwargs) -> MeasureTool:
    """A tool on the plan of a lab sheet at 1:M: the ground seen from above, contours, the pricked points.

    Plan coordinates in mm from the sheet's lower-left corner, x east, y north.
    """
    plan = sheet.plan()
    Z = plan.contour_Z_m
    step = float(contour_interval_m)
    levels = np.arange(math.floor(Z.min() / step) * step, Z.max() + step, step)
    kwargs.setdefault("title", f"Your plan at {fmt_scale(sheet.M)} with contours every {step:g} m")
    return MeasureTool(plan.image, plan.extent_mm, sheet.names, marks=sheet.marks("plan"),
                       contours=(plan.contour_x_mm, plan.contour_y_mm, Z, levels), xlabel="plan x (east), mm",
                       ylabel="plan y (north), mm", **kwargs)
