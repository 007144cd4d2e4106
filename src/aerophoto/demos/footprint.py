"""Camera footprint: what a frame camera sees, and where o, n and c fall (chapter 00).

The pure part, :func:`footprint_model`, computes the ground footprint of the
photo and the elements of central projection (guide §5, figure 8) for a camera
and orientation; :class:`FootprintView` draws it (ground plan and photo side by
side); :class:`FootprintDemo` binds sliders for f, 1:m, α, λ and κ to both.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd
from matplotlib.collections import LineCollection

from .. import geometry as g
from .. import plots
from ..widgets import LiveDemo, Param

__all__ = ["FootprintResult", "footprint_model", "FootprintView", "FootprintDemo", "own_footprint"]


@dataclass(frozen=True)
class FootprintResult:
    """The footprint of one photo over flat ground (Z = 0).

    Attributes
    ----------
    camera, pose : the camera and exterior orientation used
    H_m : flying height above the ground, m
    ground_polygon_m : (4, 2) footprint corners X, Y in metres
    vertical_polygon_m : (4, 2) footprint of the equivalent vertical photo, m
    o_ground_m, n_ground_m, c_ground_m : (2,) ground points O, N, C, m
    o_mm, n_mm, c_mm : (2,) photo points o, n, c, mm
    grid_photo_mm : (k, 2, 2) segments of a ground grid as imaged on the photo, mm
    m_near, m_far : scale denominators along the principal vertical at the
        frame's near (nadir-side) and far edges
    """

    camera: g.Camera
    pose: g.Pose
    H_m: float
    ground_polygon_m: np.ndarray
    vertical_polygon_m: np.ndarray
    o_ground_m: np.ndarray
    n_ground_m: np.ndarray
    c_ground_m: np.ndarray
    o_mm: np.ndarray
    n_mm: np.ndarray
    c_mm: np.ndarray
    grid_photo_mm: np.ndarray
    m_near: float
    m_far: float

    @property
    def m(self) -> float:
        """Scale denominator of the equivalent vertical photo, m = H/f."""
        return self.H_m / (self.camera.f_mm / 1000.0)

    @property
    def area_km2(self) -> float:
        return _area(self.ground_polygon_m) / 1e6

    @property
    def vertical_area_km2(self) -> float:
        return _area(self.vertical_polygon_m) / 1e6

    def table(self) -> pd.DataFrame:
        on = float(np.hypot(*self.n_mm))
        oc = -float(np.hypot(*self.c_mm))
        rows = [
            ("Flying height H = f·m", "m", self.H_m),
            ("Photo scale 1/m (vertical)", "1:", self.m),
            ("Nadir distance on = f·tg α", "mm", on),
            ("Isocentre oc = −f·tg(α/2)", "mm", oc),
            ("Scale at the near edge", "1:", self.m_near),
            ("Scale at the far edge", "1:", self.m_far),
            ("Footprint area", "km²", self.area_km2),
            ("… of the vertical photo", "km²", self.vertical_area_km2),
        ]
        return pd.DataFrame(rows, columns=["quantity", "unit", "value"]).set_index("quantity")


#: the table's precision, row by row (the book's number format): H to the metre, on and oc to 0.01 mm, areas 0.01 km²
_PRECISION = {"Flying height H = f·m": 0, "Nadir distance on = f·tg α": 2, "Isocentre oc = −f·tg(α/2)": 2,
              "Footprint area": 2, "… of the vertical photo": 2}


def _area(poly) -> float:
    x, y = poly[:, 0], poly[:, 1]
    return 0.5 * abs(float(np.dot(x, np.roll(y, -1)) - np.dot(y, np.roll(x, -1))))


def _local_scale(camera, pose, xy, direction, step_mm=1.0) -> float:
    a = g.photo_to_plane(camera, pose, xy - direction * step_mm / 2, 0.0)
    b = g.photo_to_plane(camera, pose, xy + direction * step_mm / 2, 0.0)
    return float(np.hypot(*(b - a)[:2]) * 1000.0 / step_mm)


def footprint_model(f_mm=100.0, m=12000.0, alpha_deg=3.0, lambda_deg=-60.0, kappa_deg=0.0,
                    frame_mm=180.0, grid_step_m=None) -> FootprintResult:
    """Footprint and o, n, c of a photo at scale 1:m over flat ground at Z = 0.

    Parameters
    ----------
    f_mm : focal length f, mm
    m : scale denominator of the equivalent vertical photo (guide's m); H = f·m
    alpha_deg, lambda_deg, kappa_deg : tilt α, direction λ of the principal
        vertical on the photo, heading κ (see :mod:`aerophoto.geometry`)
    grid_step_m : spacing of the ground grid drawn on the photo, m
        (default: a tenth of the vertical footprint's side)
    """
    cam = g.Camera(f_mm, frame_mm)
    H = g.flying_height_m(cam.f_mm, m)
    pose = g.Pose(0.0, 0.0, H, alpha_deg, lambda_deg, kappa_deg)
    poly = g.footprint(cam, pose, 0.0)[:, :2]
    vpoly = g.footprint(cam, pose.levelled(), 0.0)[:, :2]
    o, n, c = g.principal_point(cam, pose), g.nadir_point(cam, pose), g.isocentre(cam, pose)
    O, N, C = (g.photo_to_plane(cam, pose, p, 0.0)[:2] for p in (o, n, c))
    # a ground grid over the vertical footprint, imaged on the tilted photo
    side = cam.frame_mm / 1000.0 * m
    step = grid_step_m or side / 10.0
    k = np.arange(-6, 7) * step
    t = np.linspace(-6 * step, 6 * step, 41)
    segs = []
    R = g.rotation_matrix(pose)
    for const in k:
        for line in (np.column_stack([np.full_like(t, const), t]), np.column_stack([t, np.full_like(t, const)])):
            P = np.column_stack([line, np.zeros(len(line))])
            # keep points in front of the camera only
            front = ((P - pose.centre) @ R)[:, 2] < -1e-6
            if front.sum() < 2:
                continue
            xy = g.ground_to_photo(cam, pose, P[front])
            segs.extend(np.stack([xy[:-1], xy[1:]], axis=1))
    segs = np.array(segs) if segs else np.zeros((0, 2, 2))
    u = g.principal_vertical(pose)
    h = cam.half_mm
    m_near = _local_scale(cam, pose, -0.95 * h * u, u)
    m_far = _local_scale(cam, pose, 0.95 * h * u, u)
    return FootprintResult(cam, pose, H, poly, vpoly, O, N, C, o, n, c, segs, m_near, m_far)


class FootprintView:
    """Ground plan (left) and photo (right) of :class:`FootprintResult`; ``update`` moves artists."""

    def __init__(self, result: FootprintResult | None = None, ax=None):
        if ax is None:
            fig = plots.figure(figsize=(8.6, 4.2))
            ax_ground, ax_photo = fig.subplots(1, 2)
        else:
            ax_ground, ax_photo = ax
            fig = ax_ground.figure
        self.fig, self.ax_ground, self.ax_photo = fig, ax_ground, ax_photo
        C = plots.COLORS
        a = ax_ground
        a.set_title("Ground (plan), km")
        a.set_aspect("equal")
        a.set_xlabel("X (east), km")
        a.set_ylabel("Y (north), km")
        # black dashed: the grey it was sat too close to the green grid under deuteranopia (tests/presentation)
        (self.vpoly,) = a.plot([], [], ls="--", color=C["black"], lw=1.5, label="vertical photo")
        (self.poly,) = a.plot([], [], color=C["footprint"], lw=2.5, label="tilted photo")
        (self.N,) = a.plot([], [], "^", color=C["nadir"], ms=9, label="N (plumb point)")
        (self.O,) = a.plot([], [], "+", color=C["photo"], ms=13, mew=2, label="O")
        (self.C,) = a.plot([], [], "o", color=C["isocentre"], ms=9, mfc="none", mew=2, label="C")
        a.legend(loc="upper right", fontsize=9)
        p = ax_photo
        p.set_title("Photo, mm")
        self.grid = LineCollection([], colors=C["green"], linewidths=0.8, alpha=0.8, label="ground grid")
        p.add_collection(self.grid)
        plots.photo_frame(p, g.Camera(), label="frame")
        (self.pv,) = p.plot([], [], color=C["nadir"], lw=1, ls=":", label="principal vertical")
        (self.iso,) = p.plot([], [], color=C["isocentre"], lw=1, ls="--", label="isoline h_c–h_c")
        self.marks = plots.mark_points(p, {"o": (0, 0), "n": (0, 0), "c": (0, 0)})
        p.set_xlim(-100, 100)
        p.set_ylim(-100, 100)
        p.legend(loc="upper right", fontsize=9)
        if result is not None:
            self.update(result)

    def update(self, r: FootprintResult) -> None:
        close = lambda P: np.vstack([P, P[:1]]) / 1000.0  # noqa: E731
        self.poly.set_data(*close(r.ground_polygon_m).T)
        self.vpoly.set_data(*close(r.vertical_polygon_m).T)
        for art, P in ((self.N, r.n_ground_m), (self.O, r.o_ground_m), (self.C, r.c_ground_m)):
            art.set_data([P[0] / 1000.0], [P[1] / 1000.0])
        # the plan is centred on the plumb point N (it stays put while the photo tilts and turns around it) and
        # its half-width is a round value just above the farthest corner: most moves keep the limits, so the
        # axes and their labels stay in the demo's cached background (only a new round value redraws them)
        allp = np.vstack([r.ground_polygon_m, r.vertical_polygon_m]) / 1000.0
        n = np.asarray(r.n_ground_m[:2], dtype=float) / 1000.0
        half = plots.coarse_ceil(float(np.max(np.hypot(*(allp - n).T))) * 1.03)  # any κ, λ: the same frame
        self.ax_ground.set_xlim(n[0] - half, n[0] + half)  # the same limits again: no change (steady_limits)
        self.ax_ground.set_ylim(n[1] - half, n[1] + half)
        self.grid.set_segments(list(r.grid_photo_mm))
        u = g.principal_vertical(r.pose)
        v = np.array([-u[1], u[0]])
        L = r.camera.half_mm * 1.4
        self.pv.set_data([-L * u[0], L * u[0]], [-L * u[1], L * u[1]])
        self.iso.set_data([r.c_mm[0] - L * v[0], r.c_mm[0] + L * v[0]], [r.c_mm[1] - L * v[1], r.c_mm[1] + L * v[1]])
        plots.move_onc(self.marks, r.o_mm, r.n_mm, r.c_mm, u)  # labels fanned out: never overlapping


class FootprintDemo(LiveDemo):
    """Live camera footprint: vary f, scale, tilt, swing and heading.

    It opens on the guide's worked example (variant 00: f = 100 mm, 1:12 000, α = 3°, λ = −60°), never on the
    student's own variant, whose H, on and oc are task 00.1 (:func:`own_footprint` shows those once it passed).
    The sliders cover every variant of the guide's scheme on their steps: f up to 1100 mm by 10
    (f = 100 + 10i ≤ 1090 mm), m up to 50 000 by 100 (m = 12 000 + 100i ≤ 21 900), λ by 1° (λ = −60° + i).
    """

    title = "What the camera sees: footprint, o, n and c"
    hint = ("Tilt the camera (α) and watch the footprint turn into a trapezoid while n and c move "
            "away from o along the principal vertical.")
    params = (
        Param("f_mm", "f, mm", 70, 1100, 10, 100, group="Camera", help="focal length f"),
        Param("m", "m (scale 1:m)", 2000, 50000, 100, 12000, group="Camera", help="photo scale denominator"),
        Param("alpha_deg", "α, °", 0, 20, 0.5, 3, group="Orientation", help="tilt of the optical axis"),
        Param("lambda_deg", "λ, °", -180, 180, 1, -60, group="Orientation",
              help="direction of the principal vertical on the photo"),
        Param("kappa_deg", "κ, °", -180, 180, 5, 0, group="Orientation", help="heading of the photo's x axis"),
    )

    def build(self):
        self.view = FootprintView()
        self.fig = self.view.fig
        # a move redraws the footprints and points over the cached plan (whose frame changes only when the
        # footprint outgrows a round half-width: then the move is a full draw) and the photo's grid and points
        v = self.view
        self.animated = (v.vpoly, v.poly, v.N, v.O, v.C, v.grid)
        plots.steady_limits(v.ax_ground, snap=False)  # the same limits again are no change

    def compute(self, **v):
        return footprint_model(**v)

    def render(self, result):
        self.view.update(result)
        self.table.value = plots.html_table(result.table(), caption="Elements of the photo", precision=_PRECISION)


def own_footprint(variant, passed):
    """The footprint demo on the student's own camera and tilt — once task 00.1 (H, on, oc) has passed.

    ``passed`` is the notebook's ``aerophoto.checks.passed``.  Returns a :class:`FootprintDemo` started at the
    variant's f, m, α and λ (the guide's scheme as it is, f up to 1090 mm), or a
    :class:`~aerophoto.demos.own.Locked` note: the demo's table shows H, on and oc.
    """
    from .own import after

    return after(passed, ["task-00-1"],
                 lambda: FootprintDemo(f_mm=variant.f_mm, m=variant.m, alpha_deg=variant.alpha_deg,
                                       lambda_deg=variant.lambda_deg),
                 "the demo's table shows your H, on and oc.")
