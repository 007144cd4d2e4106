"""A magnifier (лупа) on chapter 08's photo: a chosen spot at 3–6× from the photo's own full-resolution render.

An interpreter reads a contact print with a magnifying glass of 2–6×: the crowns of a stand, the rows and
tramlines of a field, a road's shoulders and ditches, the rails on the ballast only show under it.  The book's
photo (:func:`aerophoto.labs.ch08.lab_photo`) is rendered at 1024 pixels across its 18 cm — about as much as a
screen shows at once — so the magnifier renders the spot it looks at afresh, through the same camera, in the same
light and air (:func:`aerophoto.labs.ch08.photo_window`), at :data:`aerophoto.labs.ch08.LOUPE_PX` pixels across
the field the power allows: what the glass shows is finer than the photo on the screen, as a real glass over a
real print shows finer than the eye alone.

* :func:`loupe_model` — the magnified field: power ×k shows a square of ``FIELD_MM / k`` mm of the photo
  (:data:`FIELD_MM` = 120 mm, the glass's own field at ×1), so ×3 shows 40 mm of the photo, ×6 shows 20 mm.
* :class:`LoupeView` — the whole photo with the glass's field outlined (left) and the field magnified (right),
  with the photo's marks and a 10 m scale bar; ``update`` moves the artists in place.
* :class:`LoupeDemo` — sliders x, y (photo mm), "centre on" a mark, the power and the film; a click on the
  whole photo moves the glass there.  A move shows a quick preview and the full field once the slider rests.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import plots
from ..widgets import LiveDemo, Param

__all__ = ["FIELD_MM", "POWERS", "LoupeResult", "loupe_model", "LoupeView", "LoupeDemo", "PREVIEW_PX"]

#: the glass's field at ×1, mm of the photo (at ×k it shows FIELD_MM / k)
FIELD_MM = 120.0
#: the powers of the magnifier
POWERS = (3, 4, 5, 6)
#: pixels across the field while a slider moves (the full field follows when it rests)
PREVIEW_PX = 160
_FILMS = (("natural colour", "colour film"), ("colour infrared", "colour-infrared film"))
_MARK_COLOURS = {"digit": "#F0E442", "stand": "#56B4E9", "bank": "#D55E00"}


def _mark_colour(name: str) -> str:
    return _MARK_COLOURS["digit" if name.isdigit() else ("stand" if name in "PQ" else "bank")]


@dataclass(frozen=True, eq=False)
class LoupeResult:
    """What the glass shows: the field's picture (n, n, 3) 0…1, its square (photo mm) and its ground scale."""

    image: np.ndarray
    centre_mm: tuple
    side_mm: float
    power: int
    m: float
    pixel_m: float

    @property
    def ground_m(self) -> float:
        """The field's side on the ground, m (side × m)."""
        return self.side_mm * self.m / 1000.0

    def table(self) -> pd.DataFrame:
        from ..i18n.numfmt import fmt_number, fmt_quantity

        x, y = self.centre_mm
        rows = [("power", f"×{self.power}"),
                ("centre of the glass, photo x, y", f"{fmt_number(x, 1)}, {fmt_number(y, 1)} mm"),
                ("field of the glass, on the photo", fmt_quantity(self.side_mm, "mm", 1)),
                ("field of the glass, on the ground", fmt_quantity(self.ground_m, "m", 0)),
                ("one pixel of the glass, on the ground", fmt_quantity(self.pixel_m, "m", 2))]
        return pd.DataFrame(rows, columns=["quantity", "value"]).set_index("quantity")


def _clamp(x_mm: float, y_mm: float, side_mm: float) -> tuple:
    lim = 90.0 - side_mm / 2.0
    return float(np.clip(x_mm, -lim, lim)), float(np.clip(y_mm, -lim, lim))


def loupe_model(i: int, x_mm: float = 0.0, y_mm: float = 0.0, power: int = 4, camera: str = "colour film",
                n_px: int | None = None) -> LoupeResult:
    """The glass over variant ``i``'s photo (or the worked example's) at photo (x, y) mm, power ×``power``.

    The field (``FIELD_MM / power`` mm square) is kept inside the frame: a centre nearer the edge is moved in.
    ``n_px`` pixels across the field (default :data:`aerophoto.labs.ch08.LOUPE_PX`).
    """
    from .. import spectral as sp
    from ..labs import ch08

    if int(power) not in POWERS:
        raise ValueError(f"power = {power!r} is not one of the magnifier's powers {list(POWERS)}")
    if camera not in sp.CAMERAS:
        raise ValueError(f"camera = {camera!r} is not one of {list(sp.CAMERAS)}")
    side = FIELD_MM / int(power)
    x, y = _clamp(x_mm, y_mm, side)
    cp = ch08.photo_window(int(i), x, y, side, n_px or ch08.LOUPE_PX)
    su = ch08.setup_for(int(i))
    return LoupeResult(image=cp.composite(camera), centre_mm=(x, y), side_mm=side, power=int(power), m=su.m,
                       pixel_m=cp.geometry.footprint_m)


class LoupeView:
    """The whole photo with the glass's field (left), the field magnified (right); ``update`` moves them in place.

    ``lab`` is the :class:`aerophoto.labs.ch08.LabPhoto` (its picture and marks).  The right panel's axes run
    0…1 across the field (fixed, so a move redraws only the picture); its marks and the 10 m bar follow the field.
    """

    def __init__(self, lab, result: LoupeResult | None = None, ax=None, camera: str = "colour film"):
        from matplotlib.patches import Rectangle

        fig, (ax_all, ax_glass) = plots.panels(ax, 2, figsize=(8.8, 5.0), width_ratios=(1.0, 1.45))
        self.fig, self.ax_all, self.ax_glass, self.lab = fig, ax_all, ax_glass, lab
        self.marks = lab.marks
        self._camera = camera
        self.im_all = ax_all.imshow(lab.composite(camera)[::2, ::2], extent=lab.extent_mm, interpolation="antialiased")
        for name, row in lab.marks.iterrows():
            ax_all.plot([row["x, mm"]], [row["y, mm"]], "o", ms=3, mfc="none", mec=_mark_colour(name), mew=1.0)
        ax_all.set_xlim(-90, 90)
        ax_all.set_ylim(-90, 90)
        ax_all.set_xlabel("x, mm")
        ax_all.set_ylabel("y, mm")
        ax_all.set_title("the photo: click to move the glass")
        self.field = Rectangle((-10, -10), 20, 20, fill=False, ec="white", lw=1.5)
        ax_all.add_patch(self.field)
        self.im_glass = ax_glass.imshow(np.zeros((8, 8, 3), np.float32), extent=(0, 1, 0, 1),
                                        interpolation="antialiased")
        ax_glass.set_xlim(0, 1)
        ax_glass.set_ylim(0, 1)
        ax_glass.set_xticks([])
        ax_glass.set_yticks([])
        ax_glass.set_title("under the magnifier (лупа)")
        self.ring = ax_glass.scatter(np.zeros(len(self.marks)), np.zeros(len(self.marks)), s=160, facecolors="none",
                                     edgecolors=[_mark_colour(nm) for nm in self.marks.index], linewidths=1.8)
        self.labels = [ax_glass.text(0, 0, nm, color=_mark_colour(nm), fontsize=13, fontweight="bold",
                                     visible=False) for nm in self.marks.index]
        self.bar, = ax_glass.plot([0.05, 0.15], [0.05, 0.05], color="white", lw=3, solid_capstyle="butt")
        self.bar_text = ax_glass.text(0.05, 0.075, "", color="white", fontsize=12)
        self._bar_m = None
        if result is not None:
            self.update(result)

    def set_camera(self, camera: str) -> None:
        """Show the whole photo in another film (the left panel)."""
        if camera != self._camera:
            self._camera = camera
            self.im_all.set_data(self.lab.composite(camera)[::2, ::2])

    def update(self, r: LoupeResult) -> None:
        self.im_glass.set_data(r.image)
        x, y = r.centre_mm
        s = r.side_mm
        self.field.set_xy((x - s / 2.0, y - s / 2.0))
        self.field.set_width(s)
        self.field.set_height(s)
        u = (self.marks["x, mm"].to_numpy() - (x - s / 2.0)) / s
        v = (self.marks["y, mm"].to_numpy() - (y - s / 2.0)) / s
        inside = (u > 0.0) & (u < 1.0) & (v > 0.0) & (v < 1.0)
        self.ring.set_offsets(np.column_stack([np.where(inside, u, -1.0), np.where(inside, v, -1.0)]))
        for lab, uu, vv, ok in zip(self.labels, u, v, inside):
            lab.set_position((uu + 0.02, vv + 0.02))
            lab.set_visible(bool(ok))
        bar_m = next(b for b in (100.0, 50.0, 20.0, 10.0, 5.0) if b <= 0.25 * r.ground_m)
        self.bar.set_data([0.05, 0.05 + bar_m / r.ground_m], [0.05, 0.05])
        if bar_m != self._bar_m:
            from ..i18n.numfmt import fmt_quantity

            self._bar_m = bar_m
            self.bar_text.set_text(fmt_quantity(bar_m, "m", 0))


_MARK_OPTIONS = (("— (use x, y)", "free"), *((f"mark {k}", k) for k in ("1", "2", "3", "4", "5", "6")),
                 ("stand P", "P"), ("stand Q", "Q"), ("bank point A", "A"), ("bank point B", "B"))


class LoupeDemo(LiveDemo):
    """A magnifier on the chapter's photo: the student's own (``LoupeDemo(v)``) or the worked example's."""

    photo_frames = True  # a move changes the photo: its frames go as JPEG (plots.fast_frames; issue 32)
    title = "A magnifier on the photo (лупа)"
    hint = ("Put the glass on a mark or click on the photo; at ×5–×6 you see the crowns of a stand, the rows and "
            "wheel tracks of a field, a road's shoulders and ditches, the rails.")
    params = (
        Param("x_mm", "x (glass centre), mm", -80, 80, 1, 0, group="Where the glass is",
              help="photo x of the glass's centre"),
        Param("y_mm", "y (glass centre), mm", -80, 80, 1, 0, group="Where the glass is",
              help="photo y of the glass's centre"),
        Param("mark", "centre on", default="free", kind="choice", options=_MARK_OPTIONS, group="Where the glass is",
              help="put the glass over one of the photo's marks"),
        Param("power", "power, ×", 3, 6, 1, 5, kind="int", group="Glass", help="how many times larger than the print"),
        Param("camera", "film", default="colour film", kind="choice", options=_FILMS, group="Glass"),
    )

    def __init__(self, v=None, **values):
        from ..labs import ch08

        self.i = ch08.EXAMPLE_I if v is None else int(getattr(v, "i", v))
        self.lab = ch08._lab_photo(self.i)
        self._click = None
        super().__init__(**values)

    def build(self):
        self.view = LoupeView(self.lab)
        self.fig = self.view.fig
        v = self.view
        self.animated = (v.field, v.im_glass)  # a move: the field's outline over the photo, the glass's picture
        self._click = self.fig.canvas.mpl_connect("button_press_event", self._on_press)

    def _on_press(self, event) -> None:
        if event.inaxes is not self.view.ax_all or event.xdata is None:
            return
        x = float(np.clip(event.xdata, -80, 80))
        y = float(np.clip(event.ydata, -80, 80))
        try:
            self.set(x_mm=round(x), y_mm=round(y), mark="free")
        except Exception as exc:  # never let a callback die silently
            from ..widgets import error_html

            self.status.value = error_html(exc)

    def _where(self, v) -> tuple:
        if v["mark"] != "free":
            row = self.lab.marks.loc[v["mark"]]
            return float(row["x, mm"]), float(row["y, mm"])
        return float(v["x_mm"]), float(v["y_mm"])

    def compute(self, **v):
        x, y = self._where(v)
        return loupe_model(self.i, x, y, v["power"], v["camera"], PREVIEW_PX if self._preview else None)

    def render(self, result):
        self.view.set_camera(self.values["camera"])
        self.view.update(result)
        self.table.value = plots.html_table(result.table(), caption="The magnifier")

    def on_slider(self) -> str:
        return self.preview_then_full(0.25, note="the glass: full detail when the slider rests")
