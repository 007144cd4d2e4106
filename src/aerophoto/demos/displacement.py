"""The displacement explorer: relief and tilt displacement on one photo (chapters 03 and 04).

The pure part is :func:`aerophoto.displacement.displacement_field`: a grid of
ground points on hilly terrain (:class:`aerophoto.displacement.AnalyticHills`)
photographed exactly through :mod:`aerophoto.geometry`.  :class:`DisplacementView`
draws it on the photo: the relief displacement vectors (from the image the
point would have on the mean object plane to its actual image, radial from
n), the exact tilt displacement vectors (from the image on the equivalent
vertical photo to the image on the tilted one, radial from c) and, beside
them, the guide's approximate δα.  :class:`DisplacementDemo` binds sliders for
f, 1:m, α, λ and the relief amplitude to both; :class:`ReliefDemo` (chapter 03)
and :class:`TiltDemo` (chapter 04) are the same demo with a different emphasis.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from matplotlib.lines import Line2D

from .. import displacement as d
from .. import geometry as g
from .. import plots
from ..widgets import LiveDemo, Param

__all__ = ["DisplacementView", "DisplacementDemo", "ReliefDemo", "TiltDemo", "nice_factor", "legend_html", "SHOW_OPTIONS",
           "relief_section_figure", "principal_plane_figure", "as_png"]

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
    (_C["isocentre"], 1.0, "--", "isoline h_c h_c"),
)


def legend_html() -> str:
    """The view's legend as HTML, shown beside the live figure (cheaper than a legend redrawn each time)."""
    dash = {"-": "solid", ":": "dotted", "--": "dashed"}
    items = "".join(
        f"<div><span style='display:inline-block;width:28px;border-top:{max(2, lw * 1.5):.0f}px "
        f"{dash[ls]} {col};vertical-align:middle;margin-right:6px'></span>{lab}</div>"
        for col, lw, ls, lab in _LEGEND)
    dots = ("<div><span style='color:#8C510A'>●</span> / <span style='color:#01665E'>●</span> "
            "points above / below the mean object plane</div>")
    marks = ("<div><b>+ o</b> principal point, <b style='color:#D55E00'>▲ n</b> nadir point, "
             "<b style='color:#0072B2'>○ c</b> isocentre</div>")
    return f"<div style='font-size:13px;line-height:1.5;margin-bottom:6px'>{items}{dots}{marks}</div>"


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

    field: d.DisplacementField
    show: str
    factor: int


class DisplacementView:
    """The photo with relief (vermillion) and tilt (blue, exact; orange, the guide's formula) vectors.

    ``DisplacementView(ax=None)`` builds the artists once; ``update(field,
    show=..., exaggeration=...)`` moves them (``set_offsets``/``set_UVC``/
    ``set_data``) and returns the exaggeration factor used.
    """

    def __init__(self, field: d.DisplacementField | None = None, ax=None, *, n_points: int | None = None,
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
        self.q_relief = ax.quiver(zeros, zeros, zeros, zeros, color=C["relief"], width=0.006, **kw)
        self.q_tilt = ax.quiver(zeros, zeros, zeros, zeros, color=C["tilt"], width=0.006, **kw)
        self.q_approx = ax.quiver(zeros, zeros, zeros, zeros, color=C["approx"], width=0.0025, **kw)
        self.marks = plots.mark_points(ax, {"o": (0, 0), "n": (0, 0), "c": (0, 0)})
        if legend:
            handles = [Line2D([], [], color=col, lw=lw, ls=ls, label=lab) for col, lw, ls, lab in _LEGEND]
            ax.legend(handles=handles, loc="upper right", fontsize=9, framealpha=0.85)
        if field is not None:
            self.update(field)

    def update(self, field: d.DisplacementField, *, show: str = "both", exaggeration: int = 0) -> int:
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
        for name, pt in (("o", field.o_mm), ("n", field.n_mm), ("c", field.c_mm)):
            marker, label = self.marks[name]
            marker.set_data([pt[0]], [pt[1]])
            label.xy = (pt[0], pt[1])
        what = {"both": "relief and tilt", "relief": "relief", "tilt": "tilt"}[show]
        self.title.set_text(f"Photo, mm — {what} displacement, arrows ×{k}")
        return k


def _params(show: str = "both", alpha: float = 3.0, relief: float = 60.0) -> tuple:
    return (
        Param("f_mm", "f, mm", 70, 500, 10, 100, group="Camera", help="focal length f"),
        Param("m", "m (scale 1:m)", 5000, 30000, 500, 12000, group="Camera",
              help="scale denominator of the photo over the mean plane; H = f·m"),
        Param("alpha_deg", "α, °", 0, 15, 0.25, alpha, group="Orientation", help="tilt of the optical axis"),
        Param("lambda_deg", "λ, °", -180, 180, 5, -60, group="Orientation",
              help="direction of the principal vertical on the photo"),
        Param("relief_m", "relief ±h, m", 0, 200, 5, relief, group="Terrain",
              help="height of the highest hill above (and the valley below) the mean object plane"),
        Param("show", "show", kind="choice", options=SHOW_OPTIONS, default=show, group="View"),
        Param("exaggeration", "arrows", kind="choice", options=EXAGGERATION_OPTIONS, default=0, group="View",
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

    def compute(self, f_mm, m, alpha_deg, lambda_deg, relief_m, show, exaggeration):
        field = d.displacement_field(f_mm, m, alpha_deg, lambda_deg, relief_m, grid_n=9)
        return DemoFrame(field, show, int(exaggeration))

    def render(self, frame: DemoFrame):
        k = self.view.update(frame.field, show=frame.show, exaggeration=frame.factor)
        df = frame.field.table()
        df.loc["arrows drawn lengthened ×"] = ("", float(k))
        self.factor = k
        self.table.value = legend_html() + plots.html_table(df, caption="Displacements on this photo",
                                                            float_format="{:,.2f}")


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
            "orange: the guide's δα = −(r_c²·cos φ/f)·sin α. Points on the isoline h_c h_c do not move.")
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
    t = np.linspace(-math.pi / 2, -math.pi / 2 + math.radians(alpha_deg), 20)
    ax.plot(60 * np.cos(t), H + 60 * np.sin(t), color=C["grey"], lw=1)
    ax.annotate("α", (60 * math.cos(t[10]), H + 60 * math.sin(t[10])), xytext=(3, -14), textcoords="offset points")
    ax.set_title(f"The principal plane W (α = {alpha_deg:g}°, exaggerated)")
    ax.set_aspect("equal")
    ax.set_ylim(-25, H + 20)
    ax.axis("off")
    return fig


def as_png(fig, *, dpi: int = 100):
    """A static figure as a PNG image for a notebook (the figure is closed; nothing stays live)."""
    import io

    import matplotlib.pyplot as plt
    from IPython.display import Image

    buf = io.BytesIO()
    fig.savefig(buf, format="png", dpi=dpi)
    plt.close(fig)
    return Image(data=buf.getvalue(), format="png")
