"""The displacement explorer: relief and tilt displacement on one photo (chapters 03 and 04).

The model is :func:`displacement_field` (:class:`DisplacementField`): a grid of
ground points on hilly terrain (:class:`aerophoto.terrain.AnalyticHills`)
photographed exactly through :mod:`aerophoto.geometry`, with the guide's
formulas from :mod:`aerophoto.displacement` beside the exact values.
:class:`DisplacementView` draws it on the photo: the relief displacement vectors (from the image the
point would have on the mean object plane to its actual image, radial from
n), the exact tilt displacement vectors (from the image on the equivalent
vertical photo to the image on the tilted one, radial from c) and, beside
them, the guide's approximate δα.  :class:`DisplacementDemo` binds sliders for
f, 1:m, α, λ and the relief amplitude to both; :class:`ReliefDemo` (chapter 03)
and :class:`TiltDemo` (chapter 04) are the same demo with a different emphasis.
Every demo opens on the guide's worked example (variant 00: f = 100 mm, 1:12 000,
λ = −60°) — never on a student's own variant — and its sliders cover every
variant of the guide's scheme (f up to 1100 mm, m up to 30 000).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd
from matplotlib.lines import Line2D

from .. import displacement as d
from .. import geometry as g
from .. import plots
from .._validate import check_range
from ..terrain import AnalyticHills
from ..i18n import t
from ..i18n.numfmt import fmt_spec
from ..widgets import LiveDemo, Param

__all__ = ["DisplacementField", "displacement_field", "DisplacementView", "DisplacementDemo", "ReliefDemo",
           "TiltDemo", "nice_factor", "legend_html", "SHOW_OPTIONS", "relief_section_figure",
           "principal_plane_figure"]

#: what the demo draws: (label, value)
SHOW_OPTIONS = (("relief and tilt", "both"), ("relief only", "relief"), ("tilt only", "tilt"))
#: exaggeration of the arrows: (label, factor); 0 = automatic
EXAGGERATION_OPTIONS = (("auto", 0), ("×1", 1), ("×2", 2), ("×5", 5), ("×10", 10), ("×20", 20), ("×50", 50),
                        ("×100", 100), ("×200", 200))
_TARGET_ARROW_MM = 14.0
_C = plots.COLORS
#: the view's legend: colour, line width, style, label
_LEGEND = (
    (_C["relief"], 2.5, "-", "relief δh (radial from n)"),
    (_C["tilt"], 2.5, "-", "tilt δα, exact (radial from c)"),
    (_C["approx"], 1.2, "-", "tilt δα, the guide's formula"),
    (_C["nadir"], 1.0, ":", "principal vertical"),
    (_C["isocentre"], 1.0, "--", "isoline h_c–h_c"),
)


# --------------------------------------------------------------------------- the exact field (the model)
@dataclass(frozen=True)
class DisplacementField:
    """Relief and tilt displacement of a grid of points, computed exactly by projection.

    The grid is regular on the tilted photo: its nodes ``grid_mm`` are the
    images of ground points on the mean object plane Z = 0.  Each ground point
    is then lifted onto the terrain (:class:`aerophoto.terrain.AnalyticHills`).

    Attributes
    ----------
    camera, pose : the camera and orientation (H = Z_S above the mean plane)
    terrain : :class:`aerophoto.terrain.AnalyticHills`
    grid_mm : (N, 2) mean-plane images on the tilted photo, mm
    h_m : (N,) heights of the points above the mean plane, m
    xy_relief_mm : (N, 2) actual images of the terrain points, mm
    relief_formula_mm : (N,) δh = r·h/H with r from n to the actual image, mm
    xy_vertical_mm : (N, 2) images of the mean-plane points on the equivalent
        vertical photo, turned into the tilted photo's plane about the isoline, mm
    tilt_exact_mm : (N,) signed exact tilt displacement along the line from c, mm
    tilt_approx_mm : (N,) the guide's approximate δα at the same points, mm
    o_mm, n_mm, c_mm : (2,) principal point, nadir point, isocentre, mm
    """

    camera: g.Camera
    pose: g.Pose
    terrain: AnalyticHills
    grid_mm: np.ndarray
    h_m: np.ndarray
    xy_relief_mm: np.ndarray
    relief_formula_mm: np.ndarray
    xy_vertical_mm: np.ndarray
    tilt_exact_mm: np.ndarray
    tilt_approx_mm: np.ndarray
    o_mm: np.ndarray
    n_mm: np.ndarray
    c_mm: np.ndarray

    @property
    def H_m(self) -> float:
        """Flying height above the mean object plane, m."""
        return self.pose.Z_m

    @property
    def m(self) -> float:
        """Scale denominator of the equivalent vertical photo over the mean plane, H/f."""
        return self.H_m / (self.camera.f_mm / 1000.0)

    @property
    def relief_vectors_mm(self) -> np.ndarray:
        """(N, 2): from the mean-plane image to the actual image, mm (radial from n)."""
        return self.xy_relief_mm - self.grid_mm

    @property
    def relief_exact_mm(self) -> np.ndarray:
        """(N,) signed exact relief displacement: + away from n, mm."""
        rn1 = np.hypot(*(self.xy_relief_mm - self.n_mm).T)
        rn0 = np.hypot(*(self.grid_mm - self.n_mm).T)
        return rn1 - rn0

    @property
    def tilt_vectors_mm(self) -> np.ndarray:
        """(N, 2): from the (turned) vertical image to the tilted image, mm (radial from c)."""
        return self.grid_mm - self.xy_vertical_mm

    @property
    def tilt_approx_vectors_mm(self) -> np.ndarray:
        """(N, 2): the guide's δα along the line from c, ending at the tilted image, mm."""
        d = self.grid_mm - self.c_mm
        r = np.hypot(d[:, 0], d[:, 1])
        u = np.divide(d, r[:, None], out=np.zeros_like(d), where=r[:, None] > 0)
        return u * self.tilt_approx_mm[:, None]

    def summary(self) -> dict:
        """The numbers the demo's table shows (mm unless stated)."""
        te, ta = self.tilt_exact_mm, self.tilt_approx_mm
        err = np.abs(ta - te)
        max_te = float(np.max(np.abs(te)))
        re, rf = self.relief_exact_mm, self.relief_formula_mm
        return {
            "H_m": self.H_m,
            "m": self.m,
            "on_mm": float(np.hypot(*self.n_mm)),
            "oc_mm": d.isocentre_offset(self.camera.f_mm, self.pose.alpha_deg),
            "max_relief_exact_mm": float(np.max(np.abs(re))),
            "max_relief_formula_mm": float(np.max(np.abs(rf))),
            "max_relief_error_mm": float(np.max(np.abs(rf - re))),
            "n_relief_corrections": int(np.count_nonzero(np.abs(re) > d.THRESHOLD_MM)),
            "max_tilt_exact_mm": max_te,
            "max_tilt_approx_mm": float(np.max(np.abs(ta))),
            "max_tilt_error_mm": float(np.max(err)),
            "max_tilt_error_percent": float(100.0 * np.max(err) / max_te) if max_te > 1e-12 else 0.0,
            "n_tilt_corrections": int(np.count_nonzero(np.abs(te) > d.THRESHOLD_MM)),
        }

    def table(self) -> pd.DataFrame:
        s = self.summary()
        rows = [
            ("Flying height H (above the mean plane)", "m", s["H_m"]),
            ("on = f·tg α", "mm", s["on_mm"]),
            ("oc = −f·tg(α/2)", "mm", s["oc_mm"]),
            ("max |δh| exact", "mm", s["max_relief_exact_mm"]),
            ("max |δh| = r·h/H", "mm", s["max_relief_formula_mm"]),
            ("points with |δh| > 0.2 mm", "", int(s["n_relief_corrections"])),
            ("max |δα| exact", "mm", s["max_tilt_exact_mm"]),
            ("max |δα| guide's formula", "mm", s["max_tilt_approx_mm"]),
            ("max |formula − exact|", "mm", s["max_tilt_error_mm"]),
            ("… relative to max |δα|", "%", s["max_tilt_error_percent"]),
            ("points with |δα| > 0.2 mm", "", int(s["n_tilt_corrections"])),
        ]
        # object dtype: the counts stay whole numbers beside the lengths (shown 71, not 71.00)
        return pd.DataFrame(rows, columns=["quantity", "unit", "value"], dtype=object).set_index("quantity")


def displacement_field(f_mm: float = 100.0, m: float = 12000.0, alpha_deg: float = 3.0, lambda_deg: float = -60.0,
                       relief_m: float = 60.0, *, grid_n: int = 9, frame_mm: float = 180.0,
                       extent: float = 0.85) -> DisplacementField:
    """Relief and tilt displacement vectors over the analytic hills (chapters 03–04).

    Parameters
    ----------
    f_mm : focal length f, mm
    m : scale denominator of the equivalent vertical photo over the mean plane; H = f·m
    alpha_deg, lambda_deg : tilt α and direction λ of the principal vertical (see
        :mod:`aerophoto.geometry`), degrees; κ = 0
    relief_m : relief amplitude of :class:`aerophoto.terrain.AnalyticHills`, m (0 ≤ relief < H)
    grid_n : points per side of the photo grid
    extent : the grid spans ±extent·(frame/2) on the photo

    The hills are laid out on the vertical photo's footprint (L = frame/2·m),
    so they stay in view at every scale.  Everything is projected with
    :mod:`aerophoto.geometry`: mean-plane ground points under the grid by
    :func:`~aerophoto.geometry.photo_to_plane`, their terrain images by
    :func:`~aerophoto.geometry.ground_to_photo`, the vertical-photo images by
    :func:`~aerophoto.geometry.tilt_displacement_vectors`.
    """
    cam = g.Camera(f_mm, frame_mm)
    m = check_range("m", m, 100.0, 1e6)
    H = g.flying_height_m(cam.f_mm, m)
    relief = check_range("relief_m", relief_m, 0.0, H, hi_open=True, unit="m")
    pose = g.Pose(0.0, 0.0, H, alpha_deg, lambda_deg, 0.0)
    n = int(grid_n)
    if n < 2 or n > 60:
        raise ValueError(f"grid_n = {grid_n} is outside the valid range 2 ≤ grid_n ≤ 60")
    t = np.linspace(-1.0, 1.0, n) * check_range("extent", extent, 0.0, 1.0, lo_open=True) * cam.half_mm
    gx, gy = np.meshgrid(t, t)
    grid = np.column_stack([gx.ravel(), gy.ravel()])
    terrain = AnalyticHills(relief, cam.half_mm / 1000.0 * m)
    P0 = g.photo_to_plane(cam, pose, grid, 0.0)
    h = terrain.height(P0[:, 0], P0[:, 1])
    P = P0.copy()
    P[:, 2] = h
    xy_actual, xy_plane = d.relief_displacement_vectors(cam, pose, P, 0.0)
    n_mm = g.nadir_point(cam, pose)
    c_mm = g.isocentre(cam, pose)
    r_n = np.hypot(*(xy_actual - n_mm).T)
    formula = g.relief_displacement(r_n, h, H)
    xy_t, xy_v = g.tilt_displacement_vectors(cam, pose, P0)
    exact = np.hypot(*(xy_t - c_mm).T) - np.hypot(*(xy_v - c_mm).T)
    approx = g.tilt_displacement_approx(cam, pose, xy_t)
    return DisplacementField(cam, pose, terrain, xy_plane, h, xy_actual, np.asarray(formula), xy_v,
                             exact, np.asarray(approx), g.principal_point(cam, pose), n_mm, c_mm)


# --------------------------------------------------------------------------- the view and the demo
def legend_html() -> str:
    """The view's legend as HTML, shown beside the live figure (cheaper than a legend redrawn each time)."""
    dash = {"-": "solid", ":": "dotted", "--": "dashed"}
    items = "".join(
        f"<div><span style='display:inline-block;width:28px;border-top:{max(2, lw * 1.5):.0f}px "
        f"{dash[ls]} {col};vertical-align:middle;margin-right:6px'></span>{plots.html_subscripts(t(lab))}</div>"
        for col, lw, ls, lab in _LEGEND)
    dots = ("<div><span style='color:#8C510A'>●</span> / <span style='color:#01665E'>●</span> "
            f"{t('points above / below the mean object plane')}</div>")
    marks = (f"<div><b>+ o</b> {t('principal point')}, <b style='color:#D55E00'>▲ n</b> {t('nadir point')}, "
             f"<b style='color:#0072B2'>○ c</b> {t('isocentre')}</div>")
    return f"<div class='aerophoto-legend' style='font-size:13px;line-height:1.5;margin-bottom:6px'>{items}{dots}{marks}</div>"


def nice_factor(max_length_mm: float, target_mm: float = _TARGET_ARROW_MM) -> int:
    """The largest of 1, 2, 5, 10, 20, 50, … (at most 1000) that keeps the longest arrow ≤ target.

    Arrows of a few tenths of a millimetre are invisible on a 180 mm frame; the
    demo multiplies them by this factor and says so.  Returns 1 for no arrows.
    """
    L = float(max_length_mm)
    if not np.isfinite(L) or L <= 1e-9:
        return 1
    raw = target_mm / L
    best = 1
    for k in (1, 2, 5, 10, 20, 50, 100, 200, 500, 1000):
        if k <= raw:
            best = k
    return best


def _move_quiver(q, xy, uv) -> None:
    """Move a Quiver's tails and set its vectors (its offsets and XY are kept in step)."""
    q.set_offsets(xy)
    q.XY = xy  # Quiver keeps its own copy of the tails for drawing
    q.X, q.Y = xy[:, 0], xy[:, 1]
    q.set_UVC(uv[:, 0], uv[:, 1])


@dataclass(frozen=True)
class DemoFrame:
    """What the demo shows: the field, which vectors, and the exaggeration used."""

    field: DisplacementField
    show: str
    factor: int


class DisplacementView:
    """The photo with relief (vermillion) and tilt (blue, exact; orange, the guide's formula) vectors.

    ``DisplacementView(ax=None)`` builds the artists once; ``update(field,
    show=..., exaggeration=...)`` moves them (``set_offsets``/``set_UVC``/
    ``set_data``) and returns the exaggeration factor used.
    """

    def __init__(self, field: DisplacementField | None = None, ax=None, *, n_points: int | None = None,
                 legend: bool = True):
        if ax is None:
            # a fixed layout (no layout engine runs on each redraw) and few text artists: the redraw is
            # most of a live update's cost
            fig = plots.figure(figsize=(6.0, 5.9), layout="none")
            ax = fig.add_axes([0.125, 0.085, 0.85, 0.85])
        else:
            fig = ax.figure
        self.fig, self.ax = fig, ax
        C = plots.COLORS
        ax.set_xlim(-100, 100)
        ax.set_ylim(-100, 100)
        ticks = [-90, -45, 0, 45, 90]
        ax.set_xticks(ticks)
        ax.set_yticks(ticks)
        ax.grid(False)
        ax.set_aspect("equal", adjustable="box")
        plots.photo_frame(ax, g.Camera(), label="frame")
        self.title = ax.set_title("")
        (self.pv,) = ax.plot([], [], color=C["nadir"], lw=1, ls=":")
        (self.iso,) = ax.plot([], [], color=C["isocentre"], lw=1, ls="--")
        n = n_points or (len(field.grid_mm) if field is not None else 81)
        zeros = np.zeros(n)
        # dots: the points' images on the mean plane, coloured by height (brown above, green below)
        self.pts = ax.scatter(zeros, zeros, c=zeros, s=16, cmap="BrBG_r", vmin=-1, vmax=1, zorder=3,
                              edgecolors="none")
        kw = dict(angles="xy", scale_units="xy", scale=1.0, zorder=4)
        # arrows thick enough for the back row at the fixed ×2 (a relief step of 5 m must show on a projector)
        self.q_relief = ax.quiver(zeros, zeros, zeros, zeros, color=C["relief"], width=0.009, **kw)
        self.q_tilt = ax.quiver(zeros, zeros, zeros, zeros, color=C["tilt"], width=0.009, **kw)
        self.q_approx = ax.quiver(zeros, zeros, zeros, zeros, color=C["approx"], width=0.0025, **kw)
        self.marks = plots.mark_points(ax, {"o": (0, 0), "n": (0, 0), "c": (0, 0)})
        if legend:
            handles = [Line2D([], [], color=col, lw=lw, ls=ls, label=lab) for col, lw, ls, lab in _LEGEND]
            ax.legend(handles=handles, loc="upper right", fontsize=9, framealpha=0.85)
        if field is not None:
            self.update(field)

    def update(self, field: DisplacementField, *, show: str = "both", exaggeration: int = 0) -> int:
        """Move the artists to ``field``; ``exaggeration`` 0 = automatic.  Returns the factor used."""
        if show not in ("both", "relief", "tilt"):
            raise ValueError(f"show = {show!r} is not one of the valid choices ['both', 'relief', 'tilt']")
        grid = field.grid_mm
        rv = field.relief_vectors_mm
        tv = field.tilt_vectors_mm
        av = field.tilt_approx_vectors_mm
        lengths = []
        if show in ("both", "relief"):
            lengths.append(np.max(np.hypot(rv[:, 0], rv[:, 1])))
        if show in ("both", "tilt"):
            lengths.append(np.max(np.hypot(tv[:, 0], tv[:, 1])))
        k = int(exaggeration) if exaggeration else nice_factor(max(lengths))
        _move_quiver(self.q_relief, grid, k * rv)
        _move_quiver(self.q_tilt, grid - k * tv, k * tv)
        _move_quiver(self.q_approx, grid - k * av, k * av)
        self.q_relief.set_visible(show != "tilt")
        self.q_tilt.set_visible(show != "relief")
        self.q_approx.set_visible(show != "relief")
        self.pts.set_offsets(grid)
        self.pts.set_array(field.h_m)
        amp = max(field.terrain.relief_m, 1e-6)
        self.pts.set_clim(-amp, amp)
        u = g.principal_vertical(field.pose)
        v = np.array([-u[1], u[0]])
        L = 130.0
        self.pv.set_data([-L * u[0], L * u[0]], [-L * u[1], L * u[1]])
        c = field.c_mm
        self.iso.set_data([c[0] - L * v[0], c[0] + L * v[0]], [c[1] - L * v[1], c[1] + L * v[1]])
        plots.move_onc(self.marks, field.o_mm, field.n_mm, field.c_mm, u)  # labels fanned out: never overlapping
        what = {"both": "relief and tilt", "relief": "relief", "tilt": "tilt"}[show]
        self.title.set_text(t("Photo, mm — {what} displacement, arrows ×{k}", what=t(what), k=k))
        return k


def _params(show: str = "both", alpha: float = 3.0, relief: float = 60.0) -> tuple:
    return (
        # the ranges cover every variant of the guide's scheme (f = 100 + 10i ≤ 1090 mm, m = 12000 + 100i ≤ 21 900);
        # the defaults are the guide's worked example, variant 00 (f = 100 mm, 1:12 000, λ = −60°)
        Param("f_mm", "f, mm", 70, 1100, 10, 100, group="Camera", help="focal length f"),
        Param("m", "m (scale 1:m)", 5000, 30000, 500, 12000, group="Camera",
              help="scale denominator of the photo over the mean plane; H = f·m"),
        Param("alpha_deg", "α, °", 0, 15, 0.25, alpha, group="Orientation", help="tilt of the optical axis"),
        Param("lambda_deg", "λ, °", -180, 180, 5, -60, group="Orientation",
              help="direction of the principal vertical on the photo"),
        Param("relief_m", "relief ±h, m", 0, 200, 5, relief, group="Terrain",
              help="height of the highest hill above (and the valley below) the mean object plane"),
        Param("show", "show", kind="choice", options=SHOW_OPTIONS, default=show, group="View"),
        # a fixed ×2 (the automatic factor at the guide's example), not auto: doubling the relief doubles every
        # arrow on screen, as the chapters say (auto would halve the factor instead); "auto" stays a choice
        Param("exaggeration", "arrows", kind="choice", options=EXAGGERATION_OPTIONS, default=2, group="View",
              help="how much the arrows are lengthened so they can be seen; auto keeps the longest ≈ 14 mm"),
    )


class DisplacementDemo(LiveDemo):
    """Live relief and tilt displacement: vary f, scale, tilt, swing and relief."""

    title = "Displacement explorer: relief (from n) and tilt (from c)"
    hint = ("Relief arrows point away from the nadir n for hills and towards it for the valley; tilt arrows point "
            "towards the isocentre c on the far side of the isoline and away from it on the near side. "
            "Raise α and watch the guide's formula (orange) part from the exact tilt displacement (blue).")
    params = _params()

    def build(self):
        self.view = DisplacementView(n_points=81, legend=False)
        self.fig = self.view.fig
        # a move redraws the lines, dots, arrows, marks and the title (its arrows ×k) over the cached photo frame
        self.animated = (self.view.pv, self.view.title)

    def compute(self, f_mm, m, alpha_deg, lambda_deg, relief_m, show, exaggeration):
        field = displacement_field(f_mm, m, alpha_deg, lambda_deg, relief_m, grid_n=9)
        return DemoFrame(field, show, int(exaggeration))

    def render(self, frame: DemoFrame):
        k = self.view.update(frame.field, show=frame.show, exaggeration=frame.factor)
        df = frame.field.table()
        df.loc["arrows drawn lengthened ×"] = ("", int(k))
        self.factor = k
        self.table.value = legend_html() + plots.html_table(df, caption="Displacements on this photo", precision=2)


class ReliefDemo(DisplacementDemo):
    """The explorer with relief in front (chapter 03): vertical photo, tilt arrows hidden."""

    title = "Relief displacement: radial from the nadir point n"
    hint = ("Every arrow runs from where the point would be if it lay on the mean object plane to where it is. "
            "Change the relief, then tilt the photo (α) and see the arrows radiate from n, not from o.")
    params = _params(show="relief", alpha=0.0, relief=80.0)


class TiltDemo(DisplacementDemo):
    """The explorer with tilt in front (chapter 04): flat ground, relief arrows hidden."""

    title = "Tilt displacement: radial from the isocentre c"
    hint = ("Blue: the exact displacement (tilted photo vs the vertical one turned about the isoline); "
            "orange: the guide's δα = −(r<sub>c</sub>²·cos φ/f)·sin α. Points on the isoline h<sub>c</sub>–h<sub>c</sub> do not move.")
    params = _params(show="tilt", alpha=3.0, relief=0.0)


# --------------------------------------------------------------------------- static section figures
def _section_point(camera, pose, x_mm):
    """Where a photo point on the principal vertical (λ = κ = 0) lies in the principal plane (X, Z)."""
    R = g.rotation_matrix(pose)
    p = pose.centre + R @ np.array([x_mm, 0.0, -camera.f_mm])
    return p[0], p[2]


def relief_section_figure(ax=None, *, H=300.0, f_mm=100.0, X_m=150.0, h_m=70.0):
    """A vertical cross-section showing why δh = r·h/H (guide §4, figure 6), drawn from the camera model.

    A vertical photo from S at height ``H`` over the mean object plane E; a point A at height h above E,
    its foot A′ on E and the point A₀ where the ray SA meets E.  On the photo, a is A's image and a′ the
    image A would have if it lay on E: the displacement a′a = δh is along the radius from n (= o here).
    Units are schematic (the photo is drawn at distance f = ``f_mm`` below S on the same scale).
    Returns the Figure.
    """
    fig, ax = plots.new_axes(ax, figsize=(7.0, 4.2))
    C = plots.COLORS
    cam = g.Camera(f_mm)
    pose = g.Pose(0.0, 0.0, H, 0.0, 0.0, 0.0)
    A = np.array([X_m, 0.0, h_m])
    Af = np.array([X_m, 0.0, 0.0])
    a = g.ground_to_photo(cam, pose, A)
    a0 = g.ground_to_photo(cam, pose, Af)
    A0 = g.photo_to_plane(cam, pose, a, 0.0)
    zp = H - f_mm  # the positive photo, drawn f below S
    ax.plot([-60, 260], [0, 0], color=C["green"], lw=2)
    ax.text(-58, 6, "E (mean object plane)", ha="left", color=C["green"])
    ax.plot([-cam.half_mm, cam.half_mm], [zp, zp], color=C["photo"], lw=2.5)
    ax.text(-cam.half_mm, zp + 6, "photo P", color=C["photo"])
    ax.plot([0], [H], "ko")
    ax.annotate("S", (0, H), xytext=(6, 4), textcoords="offset points")
    ax.plot([0, 0], [H, 0], color=C["nadir"], lw=1, ls=":")
    ax.annotate("n = o", (0, zp), xytext=(-40, -18), textcoords="offset points", color=C["nadir"])
    ax.annotate("N", (0, 0), xytext=(-5, -18), textcoords="offset points", color=C["nadir"])
    ax.plot([X_m, X_m], [0, h_m], color=C["relief"], lw=3)
    ax.plot([0, A0[0]], [H, 0], color=C["relief"], lw=1)
    ax.plot([0, X_m], [H, 0], color=C["grey"], lw=1, ls="--")
    for P, name, off in ((A, "A (height h)", (6, 2)), (Af, "A′", (4, -16)), (A0, "A₀", (4, -16))):
        ax.plot([P[0]], [P[2]], "o", color=C["relief"], ms=5)
        ax.annotate(name, (P[0], P[2]), xytext=off, textcoords="offset points")
    ax.plot([a[0], a0[0]], [zp, zp], color=C["relief"], lw=4)
    ax.annotate("a", (a[0], zp), xytext=(2, 6), textcoords="offset points", color=C["relief"])
    ax.annotate("a′", (a0[0], zp), xytext=(-14, 6), textcoords="offset points", color=C["relief"])
    ax.annotate("", xy=(-cam.half_mm, 0), xytext=(-cam.half_mm, H),
                arrowprops=dict(arrowstyle="<->", color=C["grey"]))
    ax.text(-cam.half_mm + 4, H / 2, "H", color=C["grey"])
    ax.set_title("Relief displacement on a vertical photo: a′a = δh = r·h/H")
    ax.set_aspect("equal")
    ax.set_xlim(-100, 270)
    ax.set_ylim(-25, H + 20)
    ax.axis("off")
    return fig


def principal_plane_figure(ax=None, *, f_mm=100.0, alpha_deg=12.0, H=300.0):
    """The principal plane W of a tilted photo (guide §5, figure 8), drawn from the camera model.

    Shows S, the positive photo P tilted by α, the ground plane E, the principal point o, the nadir
    point n and the isocentre c on the principal vertical, and their ground points O, N, C: the
    optical axis SoO, the plumb line SnN and the bisector ScC of the angle oSn.  The tilt is
    exaggerated for legibility and the units are schematic.  Returns the Figure.
    """
    fig, ax = plots.new_axes(ax, figsize=(7.0, 4.6))
    C = plots.COLORS
    cam = g.Camera(f_mm)
    pose = g.Pose(0.0, 0.0, H, alpha_deg, 0.0, 0.0)
    xs = {"o": 0.0, "n": float(g.nadir_point(cam, pose)[0]), "c": float(g.isocentre(cam, pose)[0])}
    ends = [_section_point(cam, pose, x) for x in (-cam.half_mm, cam.half_mm)]
    ax.plot(*zip(*ends), color=C["photo"], lw=2.5)
    ax.annotate("v", ends[0], xytext=(-12, -4), textcoords="offset points")
    ax.annotate("v  principal vertical\n(+ away from n)", ends[1], xytext=(4, -10),
                textcoords="offset points", fontsize=10)
    ground = g.photo_to_plane(cam, pose, np.array([[xs["n"], 0.0], [0.0, 0.0], [xs["c"], 0.0]]), 0.0)
    X = ground[:, 0]
    ax.plot([min(X) - 60, max(X) + 80], [0, 0], color=C["green"], lw=2)
    ax.text(max(X) + 78, 6, "E", color=C["green"], ha="right")
    ax.plot([0], [H], "ko")
    ax.annotate("S", (0, H), xytext=(-14, 4), textcoords="offset points")
    colours = {"n": C["nadir"], "o": C["photo"], "c": C["isocentre"]}
    for (name, x), Xg in zip((("n", xs["n"]), ("o", 0.0), ("c", xs["c"])), X):
        px, pz = _section_point(cam, pose, x)
        ax.plot([0, Xg], [H, 0], color=colours[name], lw=1.2, ls="-" if name != "c" else "--")
        ax.plot([px], [pz], "o", color=colours[name], ms=6)
        off = {"n": (-14, 5), "c": (-4, -20), "o": (5, 5)}[name]
        ax.annotate(name, (px, pz), xytext=off, textcoords="offset points", color=colours[name], fontweight="bold")
        ax.plot([Xg], [0], "o", color=colours[name], ms=6)
        ax.annotate(name.upper(), (Xg, 0), xytext=(-5, -16), textcoords="offset points", color=colours[name])
    # the tilt α between the plumb line SN and the optical axis SO
    arc = np.linspace(-math.pi / 2, -math.pi / 2 + math.radians(alpha_deg), 20)
    ax.plot(60 * np.cos(arc), H + 60 * np.sin(arc), color=C["grey"], lw=1)
    ax.annotate("α", (60 * math.cos(arc[10]), H + 60 * math.sin(arc[10])), xytext=(3, -14), textcoords="offset points")
    ax.set_title(t("The principal plane W (α = {a}°, exaggerated)", a=fmt_spec(alpha_deg, "{:g}")))
    ax.set_aspect("equal")
    ax.set_ylim(-25, H + 20)
    ax.axis("off")
    return fig
