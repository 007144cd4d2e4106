"""The stereo chapter's live demos (guide §8): the floating mark on an anaglyph, and base, height and focal length.

* :class:`FloatingMarkDemo` — the overlap of a stereo pair of the virtual site
  as a red–cyan anaglyph (red filter over the left eye), with a floating mark:
  a dark cross in the left photo's channel and one in the right photo's, set
  apart by the x-parallax p of the slider (the drum of a parallax bar,
  параллактометр).  When p equals the parallax of the surface under the mark,
  the two crosses fuse on it: the mark sits on the ground, on a roof, on a tree
  top — and the table reads its height from the parallax equations.
  :class:`AnaglyphView` draws it (also for static figures and the student's own pair).
* :class:`BaseHeightDemo` — air base B, flying height H and focal length f:
  the parallax of a point h above the ground (exact and small-Δp form) and the
  stereo model's vertical exaggeration (B/H against e/d); :class:`BaseHeightView`.

Both open on the guide's example (f = 100 mm, 1:12 000, p_x = 60 %,
:func:`aerophoto.labs.ch07.example_lab`); a student may give another pair
(``FloatingMarkDemo(lab=...)``) — on the student's own pair the demo reads
parallaxes only (``measure_only``), never heights.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import plots
from .. import stereo as st
from ..i18n import t, translate_unit
from ..i18n.numfmt import fmt_number
from ..widgets import LiveDemo, Param

__all__ = ["AREA_SIZE_MM", "areas", "AnaglyphView", "FloatingMarkDemo", "MarkResult", "BaseHeightView",
           "BaseHeightDemo", "BaseHeightResult", "base_height_model", "draw_marks"]

#: the piece of the overlap an area shows (width, height), mm on the photo
AREA_SIZE_MM = (44.0, 30.0)


# =========================================================================== the floating mark
def areas(lab) -> dict:
    """Named places of the pair's overlap to look at: name → centre (x, y) on the left normalised photo, mm."""
    from ..site import get_site

    site = get_site()
    x0, x1, y0, y1 = lab.window_mm
    hw, hh = AREA_SIZE_MM[0] / 2 + 0.5, AREA_SIZE_MM[1] / 2 + 0.5

    def clamp(xy):
        return (float(np.clip(xy[0], x0 + hw, x1 - hw)), float(np.clip(xy[1], y0 + hh, y1 - hh)))

    out = {}
    t = site.objects.table()
    for name, sel in (("village", None), ("chimney and water tower", "chimney"), ("mast", "mast")):
        if sel is None:
            P = np.r_[site.features["village"], site.height(*site.features["village"])]
        else:
            r = t[t["kind"] == sel].iloc[0]
            P = np.array([r["X_m"], r["Y_m"], r["ground_Z_m"]])
        xl, _ = lab.normal_xy(P[None])
        out[name] = clamp(xl[0])
    # a forest edge: the canopy texel next to open ground nearest the middle of the overlap
    objs = site.objects
    c = objs.canopy_dm > 0
    edge = c & ~np.roll(c, 3, axis=1)
    rr, cc = np.nonzero(edge[::2, ::2])
    if len(rr):
        XY = np.column_stack([(cc * 2 + 0.5) * objs.texel_m, (rr * 2 + 0.5) * objs.texel_m])
        P = np.column_stack([XY, site.height(XY[:, 0], XY[:, 1]) + 20.0])
        xl, _ = lab.normal_xy(P)
        ok = (xl[:, 0] > x0 + hw) & (xl[:, 0] < x1 - hw) & (xl[:, 1] > y0 + hh) & (xl[:, 1] < y1 - hh)
        if ok.any():
            mid = np.array([(x0 + x1) / 2, (y0 + y1) / 2])
            k = np.flatnonzero(ok)[np.argmin(np.hypot(*(xl[ok] - mid).T))]
            out["forest edge"] = clamp(xl[k])
    out["the whole overlap"] = ((x0 + x1) / 2, (y0 + y1) / 2)
    return out


def _cross(arm: int):
    """Offsets (dr, dc) and values of a dark cross with a light rim."""
    k = np.arange(-arm, arm + 1)
    rim = k[np.abs(k) > 1]
    dr = np.r_[np.zeros_like(k), k, np.ones_like(rim), -np.ones_like(rim), rim, rim]
    dc = np.r_[k, np.zeros_like(k), rim, rim, np.ones_like(rim), -np.ones_like(rim)]
    val = np.r_[np.zeros(2 * len(k)), np.ones(4 * len(rim))]
    return dr, dc, val.astype(np.float32)


def draw_marks(rgb, marks, *, arm: int = 6) -> np.ndarray:
    """Burn crosses into single channels of an anaglyph (in place): ``marks`` = [(row, col, channels)].

    A cross drawn into the red channel only is seen by the left eye only
    (through its red filter); one in green and blue by the right eye only.
    Each cross is dark with a light rim, visible on bright and dark ground.
    """
    rows, cols = rgb.shape[:2]
    dr, dc, val = _cross(arm)
    for r, c, ch in marks:
        y = int(round(r)) + dr
        x = int(round(c)) + dc
        ok = (y >= 0) & (y < rows) & (x >= 0) & (x < cols)
        for k in ch:
            rgb[y[ok], x[ok], k] = val[ok]
    return rgb


@dataclass(frozen=True, eq=False)
class MarkResult:
    """What the floating-mark demo shows for one setting."""

    rgb: np.ndarray
    extent_mm: tuple
    area: str
    x_mm: float
    y_mm: float
    p_mm: float
    reverse: bool
    table: pd.DataFrame


class AnaglyphView:
    """An anaglyph in left-photo millimetres (``imshow`` of an RGB array); ``update(rgb, extent)`` swaps it in place."""

    def __init__(self, ax=None, *, title: str = ""):
        self.fig, self.ax = plots.new_axes(ax, figsize=(6.2, 4.6))
        self.image = self.ax.imshow(np.full((2, 2, 3), 0.5, np.float32), extent=(0, 1, 0, 1),
                                    interpolation="nearest")
        self.ax.set_xlabel("x on the left photo, mm")
        self.ax.set_ylabel("y, mm")
        self.ax.grid(False)
        self.ax.set_aspect("equal")
        if title:
            self.ax.set_title(title)

    def update(self, rgb, extent_mm) -> None:
        self.image.set_data(rgb)
        self.image.set_extent(extent_mm)
        self.ax.set_xlim(extent_mm[0], extent_mm[1])
        self.ax.set_ylim(extent_mm[2], extent_mm[3])


#: the table's row with the mark's height
MARK_Z = "mark's height Z = Z_S − B·f/p"
#: the areas the guide's example pair offers (another pair may lack one, e.g. a forest edge)
EXAMPLE_AREAS = ("village", "chimney and water tower", "mast", "forest edge", "the whole overlap")


def _mark_params(area_names, default_area, p0) -> tuple:
    lo, hi = math.floor((p0 - 3.0) * 10) / 10, math.ceil((p0 + 6.0) * 10) / 10
    return (
        Param("area", "area", kind="choice", options=tuple(area_names), default=default_area, group="Where"),
        Param("x_mm", "x, mm", -20.0, 20.0, 0.1, 0.0, group="Floating mark",
              help="the mark on the left photo, from the area's centre"),
        Param("y_mm", "y, mm", -14.0, 14.0, 0.1, 0.0, group="Floating mark"),
        Param("p_mm", "p, mm", lo, hi, 0.01, round(p0, 2), group="Floating mark",
              help="the mark's x-parallax: the drum of the parallax bar"),
        Param("view", "view", kind="choice", default="direct", group="Where",
              options=(("direct (left photo to the left eye)", "direct"), ("reverse (photos swapped)", "reverse"))),
    )


class FloatingMarkDemo(LiveDemo):
    """The floating mark over the anaglyph of a stereo pair (see the module notes).

    Parameters
    ----------
    lab : :class:`aerophoto.labs.ch07.StereoLab` or None
        The pair; None is the guide's example.
    n_px : int or None
        The photos' pixels a side; None: :data:`aerophoto.labs.ch07.PAIR_PX` (1536: 0.15 mm pixels, 1.8 m on the
        ground at 1:12 000), the pair the chapter's figures and prints use — one rendering for both.
    measure_only : bool
        Show the mark's coordinates and parallax only (for the student's own pair: no heights).
    """

    #: the guide's example pair's sliders (each pair sets its own when built)
    params = _mark_params(EXAMPLE_AREAS, "village", 72.5)
    title = "The floating mark: set it on the ground, then on a roof"
    hint = ("Red–cyan glasses, red over the LEFT eye. Move p (the parallax bar's drum) until the two crosses "
            "fuse into one mark resting on the surface; then read its height. Larger p lifts the mark.")

    def __init__(self, lab=None, n_px: int | None = None, *, measure_only: bool = False, **values):
        from ..labs import ch07

        self.lab = ch07.example_lab() if lab is None else lab
        self.images = ch07.lab_images(self.lab, ch07.PAIR_PX if n_px is None else n_px)
        self.measure_only = bool(measure_only)
        self.areas = areas(self.lab)
        default_area = "village" if "village" in self.areas else next(iter(self.areas))
        self.params = _mark_params(self.areas, default_area, self.lab.p0_mm)  # this pair's areas and parallaxes
        super().__init__(**values)

    def build(self):
        self.view = AnaglyphView()
        self.fig = self.view.fig
        # the reading beside the mark (both eyes see it): the drum's p, and on the example the mark's height
        self.reading = self.view.ax.annotate("", (0, 0), xytext=(12, 10), textcoords="offset points", fontsize=12,
                                             color="white", fontweight="bold",
                                             bbox=dict(boxstyle="round,pad=0.25", fc="black", ec="none", alpha=0.75))
        # a move within an area swaps the anaglyph (the marks are burnt into its channels), the reading and the
        # title: only they are redrawn over the cached axes; another area (new limits) is a full draw
        self.animated = (self.view.image, self.reading, self.view.ax.title)
        plots.steady_limits(self.view.ax, snap=False)  # the same limits again are no change

    def _crop(self, area):
        L, R = self.images.left, self.images.right
        if area == "the whole overlap":
            k = 4
            a = L.image[::k, ::k]
            b = R.image[::k, ::k]
            ex = L.extent_mm
            return a, b, (ex[0], ex[0] + a.shape[1] * L.pixel_mm * k, ex[3] - a.shape[0] * L.pixel_mm * k, ex[3]), k
        cx, cy = self.areas[area]
        w, h = AREA_SIZE_MM
        rc0 = np.floor(L.mm_to_pixel(np.array([cx - w / 2, cy + h / 2])) + 0.5).astype(int)
        nr, nc = int(round(h / L.pixel_mm)), int(round(w / L.pixel_mm))
        r0 = int(np.clip(rc0[0], 0, L.image.shape[0] - nr))
        c0 = int(np.clip(rc0[1], 0, L.image.shape[1] - nc))
        a = L.image[r0:r0 + nr, c0:c0 + nc]
        b = R.image[r0:r0 + nr, c0:c0 + nc]
        left_mm = L.x0_mm + c0 * L.pixel_mm
        top_mm = L.y_top_mm - r0 * L.pixel_mm
        return a, b, (left_mm, left_mm + nc * L.pixel_mm, top_mm - nr * L.pixel_mm, top_mm), 1

    def _base(self, area):
        """The area's anaglyph without marks (cached per area)."""
        cache = self.__dict__.setdefault("_bases", {})
        if area not in cache:
            a, b, ext, k = self._crop(area)
            cache[area] = (st.anaglyph(a, b), ext, k)
        return cache[area]

    def compute(self, area, x_mm, y_mm, p_mm, view):
        lab = self.lab
        base, ext, k = self._base(area)
        cx, cy = self.areas[area]
        x, y = cx + x_mm, cy + y_mm
        rgb = base.copy()
        pix = self.images.left.pixel_mm * k
        col_l = (x - ext[0]) / pix - 0.5
        col_r = (x - p_mm + lab.p0_mm - ext[0]) / pix - 0.5
        row = (ext[3] - y) / pix - 0.5
        draw_marks(rgb, [(row, col_l, (0,)), (row, col_r, (1, 2))])
        reverse = view == "reverse"
        if reverse:  # the left eye gets the right photo (and its mark): the reverse stereo effect
            red = rgb[..., 0].copy()
            rgb[..., 0] = rgb[..., 1]
            rgb[..., 1] = red
            rgb[..., 2] = red
        return MarkResult(rgb, ext, area, x, y, p_mm, reverse, self._table(x, y, p_mm))

    def _table(self, x, y, p) -> pd.DataFrame:
        lab = self.lab
        rows = [("mark on the left photo x, y", "mm", f"{x:.2f}, {y:.2f}"),
                ("its parallax p (the drum)", "mm", f"{p:.2f}"),
                ("Δp from the mean ground p₀", "mm", f"{p - lab.p0_mm + 0.0:+.2f}".replace("-0.00", "+0.00"))]
        if not self.measure_only:
            from ..site import get_site

            site = get_site()
            P = lab.model_to_ground(np.array([x, y]), p)
            ground = float(site.height(P[0], P[1]))
            surface = float(site.surface_height(P[0], P[1]))
            rows += [(MARK_Z, "m", f"{P[2]:.1f}"),
                     ("bare ground there (DEM)", "m", f"{ground:.1f}"),
                     ("top of the surface there (truth)", "m", f"{surface:.1f}"),
                     ("mark above the surface", "m", f"{P[2] - surface:+.1f}")]
        return pd.DataFrame(rows, columns=["", "unit", "value"]).set_index("")

    def render(self, r: MarkResult):
        self.view.update(r.rgb, r.extent_mm)
        # set_text, not set_title: set_title restyles the axes' other titles too, which is a change of the axes
        self.view.ax.title.set_text(t("{area}: p = {p} mm", area=t(r.area), p=fmt_number(r.p_mm, 2))
                                    + (t(" — reverse stereo") if r.reverse else ""))
        text = f"p {fmt_number(r.p_mm, 2)} {t('mm')}"
        if not self.measure_only:
            text += f"\nZ {fmt_number(float(r.table.loc[MARK_Z, 'value']), 1)} {translate_unit('m')}"
        self.reading.xy = (r.x_mm, r.y_mm)
        self.reading.set_text(text)
        self.table.value = plots.html_table(r.table, caption="Floating mark")


# =========================================================================== base, height, focal length
@dataclass(frozen=True, eq=False)
class BaseHeightResult:
    pair: st.StereoPair
    h_m: float
    h_axis: np.ndarray
    dp_exact: np.ndarray
    dp_small: np.ndarray
    V: float
    table: pd.DataFrame


def base_height_model(f_mm=100.0, H_m=1200.0, B_m=864.0, h_m=20.0, eye_base_mm=st.EYE_BASE_MM,
                      viewing_distance_mm=st.VIEWING_DISTANCE_MM) -> BaseHeightResult:
    """Parallax differences of heights 0…100 m and the vertical exaggeration of a pair (f, H, B); the object h."""
    pair = st.StereoPair(f_mm, B_m, H_m)
    top = min(100.0, 0.9 * H_m)
    hs = np.linspace(0.0, top, 101)
    dp = st.parallax_difference_mm(hs, pair.b_mm, H_m)
    small = st.parallax_difference_mm(hs, pair.b_mm, H_m, approx=True)
    h = min(float(h_m), top)
    V = pair.vertical_exaggeration(eye_base_mm, viewing_distance_mm)
    overlap = pair.overlap_percent
    rows = [("photo base b = B·f/H", "mm", pair.b_mm),
            ("forward overlap p_x", "%", overlap if overlap > 0 else float("nan")),
            ("B/H", "", pair.base_height_ratio),
            ("parallax of the ground p = b", "mm", pair.b_mm),
            (f"Δp of h = {h:g} m, b·h/(H − h)", "mm", float(st.parallax_difference_mm(h, pair.b_mm, H_m))),
            ("… small form b·h/H", "mm", float(st.parallax_difference_mm(h, pair.b_mm, H_m, approx=True))),
            ("height error of σ_p = 0.01 mm, H·σ_p/b", "m", pair.height_precision_m(0.01)),
            ("vertical exaggeration V = (B/H)/(e/d)", "×", V)]
    table = pd.DataFrame(rows, columns=["quantity", "unit", "value"]).set_index("quantity")
    return BaseHeightResult(pair, h, hs, np.asarray(dp), np.asarray(small), V, table)


#: a gabled house 10 m wide, walls 6 m, ridge 9 m (the model shows it V times taller)
_HOUSE_X = np.array([-5.0, -5.0, 0.0, 5.0, 5.0])
_HOUSE_Z = np.array([0.0, 6.0, 9.0, 6.0, 0.0])


class BaseHeightView:
    """Left: Δp against the height h (exact and small-Δp form); right: a house as the stereo model shows it (×V)."""

    def __init__(self, ax=None):
        if ax is None:
            fig = plots.figure(figsize=(8.0, 4.0))
            a1, a2 = fig.subplots(1, 2)
        else:
            a1, a2 = ax
            fig = a1.figure
        self.fig, self.ax_dp, self.ax_model = fig, a1, a2
        C = plots.COLORS
        (self.exact,) = a1.plot([], [], color=C["blue"], label="Δp = b·h/(H − h)")
        (self.small,) = a1.plot([], [], color=C["orange"], ls="--", label="small form b·h/H")
        # black: a vermilion dot on the orange dashed curve merged with deuteranopia (tests/presentation/test_colours)
        (self.point,) = a1.plot([], [], "o", color=C["black"], ms=9, label="the object")
        a1.set_xlabel("height h above the ground, m")
        a1.set_ylabel("parallax difference Δp, mm")
        a1.set_title("Parallax grows with height")
        a1.legend(loc="upper left", fontsize=10)
        (self.true,) = a2.plot([], [], color=C["grey"], ls="--", lw=1.5, label="the house")
        (self.seen,) = a2.plot([], [], color=C["blue"], lw=2.5, label="as the model shows it")
        a2.set_title("Vertical exaggeration")
        a2.set_xlabel("m")
        a2.set_aspect("equal")
        a2.set_xlim(-15, 15)
        a2.set_ylim(0, 32)
        a2.legend(loc="upper right", fontsize=10)
        self.label = a2.text(0.03, 0.95, "", transform=a2.transAxes, va="top", fontsize=12)
        self.true.set_data(_HOUSE_X, _HOUSE_Z)  # the house itself does not change: drawn once

    def update(self, r: BaseHeightResult) -> None:
        self.exact.set_data(r.h_axis, r.dp_exact)
        self.small.set_data(r.h_axis, r.dp_small)
        self.point.set_data([r.h_m], [float(st.parallax_difference_mm(r.h_m, r.pair.b_mm, r.pair.H_m))])
        self.ax_dp.set_xlim(0, r.h_axis[-1])
        self.ax_dp.set_ylim(0, max(float(r.dp_exact[-1]) * 1.05, 1e-3))
        self.seen.set_data(_HOUSE_X, np.minimum(_HOUSE_Z * r.V, 31.5))
        self.label.set_text(f"V = {r.V:.2f}" + (t("  (flattened)") if r.V < 1 else ""))


class BaseHeightDemo(LiveDemo):
    """Air base, flying height and focal length against parallax and vertical exaggeration."""

    title = "Base, height and focal length: parallax and the model's relief"
    hint = ("A longer base B or a lower flight H makes every height give more parallax and the stereo model "
            "taller (V); a longer lens at the same scale needs a higher flight and flattens it.")
    params = (
        Param("f_mm", "f, mm", 70, 1100, 10, 100, group="Camera and flight", help="focal length"),
        Param("H_m", "H, m", 300, 25000, 50, 1200, group="Camera and flight", help="flying height above the ground"),
        Param("B_m", "B, m", 50, 3000, 10, 864, group="Camera and flight", help="air base: distance between exposures"),
        Param("h_m", "h, m", 1, 100, 1, 20, group="Object", help="height of an object above the ground"),
    )

    def build(self):
        self.view = BaseHeightView()
        self.fig = self.view.fig
        v = self.view
        # a move redraws the curves, the object, the house as seen and V over the cached axes; the Δp axis follows
        # the curve, so it (an animated axis: its new limits are no change of the rest) is redrawn with them
        self.animated = (v.ax_dp.yaxis, v.exact, v.small, v.point, v.seen, v.label)
        plots.steady_limits(v.ax_dp, snap=False)  # the same limits again are no change

    def compute(self, f_mm, H_m, B_m, h_m):
        return base_height_model(f_mm, H_m, B_m, h_m)

    def render(self, r: BaseHeightResult):
        self.view.update(r)
        notes = [] if r.pair.overlap_percent > 0 else ["b is longer than the frame: the photos do not overlap"]
        self.table.value = plots.html_table(r.table, caption="The pair", float_format="{:,.3g}", notes=notes)
