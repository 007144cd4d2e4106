"""Ground control live: the design of control on a block, and the resection with its danger circle (chapter 10).

* :class:`ControlDesignDemo` — a simulated block (:func:`aerophoto.simulate.fly_block`)
  with rows of control across its strips every n bases, n from Zhukov's
  formula (13.1) and the accuracy goal (:func:`aerophoto.control.control_spacing_bases`),
  against dense control (every base);
* :class:`ResectionDemo` — the four known points of the guide's §11 table, a
  station you move, its resection from three of them under random angle
  errors (a cloud of solutions, :func:`aerophoto.control.resect_many`) and the
  danger circle through the three, where the cloud blows up;
* :func:`marking_figure` — control points on a rendered photo, ringed by the
  8 and 10 mm circles of guide §11 step 2.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd
from matplotlib.collections import LineCollection

from .. import control as c
from .. import geometry as g
from .. import plots
from ..i18n import t as _t  # functions here name a local t
from ..i18n.numfmt import fmt_number, fmt_spec
from ..widgets import LiveDemo, Param

__all__ = ["ControlDesignResult", "control_design_model", "ControlDesignView", "ControlDesignDemo",
           "ResectionResult", "resection_model", "ResectionView", "ResectionDemo", "marking_figure", "exaggeration",
           "guide_points"]

_C = plots.COLORS


# =========================================================================== the design of control
@dataclass(frozen=True)
class ControlDesignResult:
    """A block and its control design.

    Attributes
    ----------
    footprints_km : ndarray (N, 4, 2) — the photos' ground footprints, km
    centres_km : ndarray (K, n, 2) — photo centres, km
    design : :class:`aerophoto.control.ControlDesign` (positions in m)
    dense_points : int — how many points dense control (every base) would need
    zhukov_n : int — Zhukov's largest spacing, bases (0 when even one base is too many)
    m_at_n_mm : float — the error (13.1) predicts at that spacing, mm
    params : dict — the inputs
    """

    footprints_km: np.ndarray
    centres_km: np.ndarray
    design: c.ControlDesign
    dense_points: int
    zhukov_n: int
    m_at_n_mm: float
    params: dict

    def table(self) -> pd.DataFrame:
        p = self.params
        k_i = p["m"] / p["M"]
        rows = [
            ("enlargement k_i = m/M", "", f"{k_i:.2f}"),
            ("Zhukov's spacing (13.1), n³ reading", "bases", f"{self.zhukov_n}" if self.zhukov_n else "< 1"),
            ("error predicted at that spacing", "mm", f"{self.m_at_n_mm:.3f}" if self.zhukov_n else "—"),
            ("spacing used", "bases", f"{self.design.spacing_bases}" + (" (dense)" if self.design.dense else "")),
            ("rows of control across the strips", "", f"{len(self.design.rows)}"),
            ("control points, this design", "", f"{self.design.n_points}"),
            ("control points, dense (every base)", "", f"{self.dense_points}"),
            ("identification 0.1 mm at 1:M", "m", f"{c.identification_tolerance_m(p['M']):.1f}"),
            ("marking circles 8 / 10 mm", "m on the ground",
             " / ".join(f"{d:.0f}" for d in c.marking_circles_ground_m(p["m"]))),
        ]
        return pd.DataFrame(rows, columns=["quantity", "unit", "value"]).set_index("quantity")


def control_design_model(m_eps_arcmin: float = 4.5, m_allowed_mm: float = 0.35, m: float = 12000.0,
                         n_strips: int = 3, n_photos: int = 12, scheme: str = "sparse", *, f_mm: float = 100.0,
                         M: float = 10000.0, px_percent: float = 60.0, py_percent: float = 30.0
                         ) -> ControlDesignResult:
    """A block of ``n_strips`` × ``n_photos`` photos at 1:m and its control ("sparse": Zhukov's spacing; "dense")."""
    from ..simulate import fly_block

    if scheme not in ("sparse", "dense"):
        raise ValueError(f"scheme = {scheme!r} is not valid; expected 'sparse' or 'dense'")
    cam = g.Camera(f_mm)
    block = fly_block(cam, m, px_percent, py_percent, int(n_photos), int(n_strips))
    centres = np.array([[s.pose.centre[:2] for s in st] for st in block.strips])
    b_mm = cam.frame_mm * (100.0 - px_percent) / 100.0
    from ..triangulation import zhukov as zk

    n_z = zk.zhukov_max_bases(m_allowed_mm, k_i=m / M, b_mm=b_mm, m_eps_arcmin=m_eps_arcmin)
    m_n = zk.zhukov_error_mm(max(n_z, 1), k_i=m / M, b_mm=b_mm, m_eps_arcmin=m_eps_arcmin)
    spacing = max(n_z, 1) if scheme == "sparse" else 1
    design = c.design_control(centres, spacing, strip_spacing_m=block.By_m)
    dense = c.design_control(centres, 1, strip_spacing_m=block.By_m).n_points
    fps = block.footprints(0.0)[:, :, :2] / 1000.0
    return ControlDesignResult(fps, centres / 1000.0, design, dense, int(n_z), float(m_n),
                               dict(m_eps_arcmin=m_eps_arcmin, m_allowed_mm=m_allowed_mm, m=m, n_strips=n_strips,
                                    n_photos=n_photos, scheme=scheme, f_mm=f_mm, M=M))


class ControlDesignView:
    """The block's footprints, photo centres, rows and control points on the ground; ``update`` moves them."""

    def __init__(self, ax=None):
        self.fig, self.ax = plots.new_axes(ax, figsize=(8.6, 4.8))
        a = self.ax
        a.set_aspect("equal")
        a.set_xlabel("X (east), km")
        a.set_ylabel("Y (north), km")
        a.set_title("Design of control on the block")
        self.footprints = LineCollection([], colors=_C["footprint"], linewidths=0.8, alpha=0.7)
        self.rows = LineCollection([], colors=_C["control"], linewidths=1.2, linestyles="--")
        a.add_collection(self.footprints)
        a.add_collection(self.rows)
        (self.centres,) = a.plot([], [], ".", color=_C["black"], ms=4, label="photo centres")
        (self.points,) = a.plot([], [], "^", mfc="none", mec=_C["control"], mew=2.0, ms=10,
                                label="control points (опознаки)")
        a.grid(False)

    def update(self, r: ControlDesignResult) -> None:
        self.footprints.set_segments([np.vstack([f, f[:1]]) for f in r.footprints_km])
        C = r.centres_km.reshape(-1, 2)
        self.centres.set_data(C[:, 0], C[:, 1])
        P = r.design.points_m / 1000.0
        self.points.set_data(P[..., 0].ravel(), P[..., 1].ravel())
        self.rows.set_segments([row for row in P])
        allp = np.vstack([r.footprints_km.reshape(-1, 2), P.reshape(-1, 2)])
        lo, hi = allp.min(axis=0), allp.max(axis=0)
        pad = 0.05 * float(max(hi - lo))
        self.ax.set_xlim(lo[0] - pad, hi[0] + pad)
        self.ax.set_ylim(lo[1] - pad, hi[1] + pad)


class ControlDesignDemo(LiveDemo):
    """Rows of control across the strips: Zhukov's spacing against dense control."""

    title = "Design of control: rows across the strips (guide §11, §13)"
    hint = ("Raise the direction error m_ε or lower the allowed error m: Zhukov's spacing shrinks and rows of "
            "control crowd together. Switch to dense control to see what phototriangulation saves.")
    params = (
        Param("m_eps_arcmin", "m_ε, ′", 2.0, 8.0, 0.5, 4.5, group="Accuracy", help="RMS error of a central direction"),
        Param("m_allowed_mm", "m allowed, mm", 0.2, 0.6, 0.05, 0.35, group="Accuracy",
              help="allowed RMS error of an orienting point on the plan"),
        Param("m", "m (photo 1:m)", 6000, 30000, 500, 12000, group="Block", help="photo scale denominator"),
        Param("n_strips", "strips", 1, 5, 1, 3, kind="int", group="Block"),
        Param("n_photos", "photos per strip", 4, 20, 1, 12, kind="int", group="Block"),
        Param("scheme", "control", default="sparse", kind="choice", group="Block",
              options=(("sparse (Zhukov)", "sparse"), ("dense (every base)", "dense"))),
    )

    def build(self):
        self.view = ControlDesignView()
        self.fig = self.view.fig
        v = self.view
        # the accuracy sliders and the scheme move only the rows and points over the cached axes; the photo scale
        # scales the whole block, so its limits change: the two axes are animated too (an animated axis' new
        # limits are no change of the rest).  The frame keeps its shape then (every length ∝ m); a block of another
        # shape (strips, photos) reshapes the equal-aspect box: render marks the axes changed, a full draw
        self.animated = (v.ax.xaxis, v.ax.yaxis, v.footprints, v.rows, v.centres, v.points)
        plots.steady_limits(v.ax, snap=False)  # the same limits again are no change

    def compute(self, **v):
        return control_design_model(**v)

    def render(self, result):
        ax = self.view.ax
        before = _data_ratio(ax)
        self.view.update(result)
        if not math.isclose(_data_ratio(ax), before, rel_tol=1e-9):
            ax.stale = True  # the equal-aspect box takes another shape: not a move the cached background can take
        self.table.value = plots.html_table(result.table(), caption="The design")


def _data_ratio(ax) -> float:
    (x0, x1), (y0, y1) = ax.get_xlim(), ax.get_ylim()
    return float((y1 - y0) / (x1 - x0))


# =========================================================================== the resection
def guide_points() -> pd.DataFrame:
    """The four known points of the guide's §11 table: X (north), Y (east), m; index I…IV."""
    from .. import guide

    return guide.ch10.known_points()[["X, m", "Y, m"]]


@dataclass(frozen=True)
class ResectionResult:
    """One state of the resection demo.

    Attributes
    ----------
    known : ndarray (4, 2) — I, II, III (used) and IV (check), X, Y, m
    station : ndarray (2,) — where the station really is
    cloud : ndarray (k, 2) — stations resected from angles with random errors (NaN where undetermined)
    resection : :class:`aerophoto.control.Resection` or None — from the error-free angles (None on the circle)
    error : str — why there is no resection ("" otherwise)
    check : :class:`aerophoto.control.ResectionCheck` or None — one draw's check by the angle III → IV
    danger_centre, danger_radius_m
    sigma_arcsec : float
    """

    known: np.ndarray
    station: np.ndarray
    cloud: np.ndarray
    resection: c.Resection | None
    error: str
    check: c.ResectionCheck | None
    danger_centre: np.ndarray
    danger_radius_m: float
    sigma_arcsec: float

    @property
    def cloud_rms_m(self) -> float:
        ok = np.all(np.isfinite(self.cloud), axis=1)
        if not ok.any():
            return float("inf")
        d = self.cloud[ok] - self.station
        return float(np.sqrt(np.mean(np.sum(d * d, axis=1))))

    def table(self) -> pd.DataFrame:
        P, K = self.station, self.known
        b1 = c.horizontal_angle_deg(P, K[0], K[1])
        b2 = c.horizontal_angle_deg(P, K[1], K[2])
        gm = c.horizontal_angle_deg(P, K[2], K[3])
        dist = abs(float(np.hypot(*(P - self.danger_centre))) - self.danger_radius_m)
        rows = [("β₁ (I → II)", "", c.format_dms(b1)), ("β₂ (II → III)", "", c.format_dms(b2)),
                ("γ check (III → IV)", "", c.format_dms(gm)),
                ("distance from the danger circle", "m", f"{dist:.0f}")]
        if self.resection is not None:
            rows.append(("shift of P per 1″ of angle error", "m", f"{self.resection.metres_per_arcsec:.4f}"))
        else:
            rows.append(("resection", "", "undetermined: on the danger circle"))
        rows.append((_t("RMS scatter for σβ = {s}″", s=fmt_spec(self.sigma_arcsec, "{:g}")), "m",
                     fmt_number(self.cloud_rms_m, 2)))
        if self.check is not None:
            rows.append(("check, one draw: |Δγ| / tolerance", "″",
                         f"{abs(self.check.discrepancy_arcsec):.0f} / {self.check.tolerance_arcsec:.0f}"))
        return pd.DataFrame(rows, columns=["quantity", "unit", "value"]).set_index("quantity")


def resection_model(north_m: float = -150.0, east_m: float = -300.0, sigma_arcsec: float = 5.0, *,
                    n_draws: int = 300, seed: int = 0, M: float = 10000.0) -> ResectionResult:
    """The station at (north_m, east_m) from the centre of the guide's points I–III, resected under angle errors.

    Parameters
    ----------
    north_m, east_m : the station's offset from the centroid of I, II, III, m
    sigma_arcsec : RMS error of a measured angle, ″ (0 ≤ σ ≤ 60)
    n_draws : angle-error draws in the cloud (1…5000)
    """
    K = guide_points().to_numpy(dtype=float)
    sig = float(sigma_arcsec)
    P = K[:3].mean(axis=0) + np.array([north_m, east_m], dtype=float)
    centre, radius = c.danger_circle(K[0], K[1], K[2])
    if np.min(np.hypot(*(K - P).T)) < 1.0:
        P = P + np.array([1.5, 1.5])  # not on a known point itself
    b1 = c.horizontal_angle_deg(P, K[0], K[1])
    b2 = c.horizontal_angle_deg(P, K[1], K[2])
    gm = c.horizontal_angle_deg(P, K[2], K[3])
    rng = np.random.default_rng([int(seed), 10])
    e = rng.normal(0.0, 1.0, size=(int(n_draws), 3)) * sig / 3600.0
    cloud = c.resect_many(K[0], K[1], K[2], (b1 + e[:, 0]) % 360.0, (b2 + e[:, 1]) % 360.0)
    try:
        res = c.resect(K[0], K[1], K[2], b1, b2)
        err = ""
    except ValueError as exc:
        res, err = None, str(exc)
    chk = None
    try:
        r1 = c.resect(K[0], K[1], K[2], (b1 + e[0, 0]) % 360.0, (b2 + e[0, 1]) % 360.0)
        chk = c.check_resection(r1, K[3], (gm + e[0, 2]) % 360.0, M=M)
    except ValueError:
        pass
    return ResectionResult(K, P, cloud, res, err, chk, centre, radius, sig)


def exaggeration(rms_m: float, target_m: float = 40.0) -> int:
    """The largest of 1, 2, 5, 10, … 1000 that keeps a scatter of ``rms_m`` within about ``target_m`` on the plot."""
    if not math.isfinite(rms_m) or rms_m <= 0:
        return 1
    best = 1
    for k in (1, 2, 5, 10, 20, 50, 100, 200, 500, 1000):
        if k * rms_m <= target_m:
            best = k
    return best


class ResectionView:
    """Known points, the danger circle, the station with its rays and the cloud of resected stations."""

    def __init__(self, ax=None):
        self.fig, self.ax = plots.new_axes(ax, figsize=(7.0, 5.6))
        a = self.ax
        a.set_aspect("equal")
        a.set_xlabel("Y (east), m − 5 310 000")
        a.set_ylabel("X (north), m − 6 060 000")
        a.set_title("Resection: three known points, two angles")
        t = np.linspace(0, 2 * np.pi, 241)
        self._circle_t = np.column_stack([np.cos(t), np.sin(t)])
        (self.circle,) = a.plot([], [], "--", color=_C["vermillion"], lw=1.5, label="danger circle (опасный круг)")
        self.rays = LineCollection([], colors=_C["grey"], linewidths=0.9)
        self.check_ray = LineCollection([], colors=_C["green"], linewidths=1.2, linestyles=":")
        a.add_collection(self.rays)
        a.add_collection(self.check_ray)
        (self.cloud,) = a.plot([], [], ".", color=_C["blue"], ms=2.5, alpha=0.6, label="resected stations")
        (self.known,) = a.plot([], [], "^", mfc="none", mec=_C["control"], mew=2.2, ms=11, label="known points")
        (self.station,) = a.plot([], [], "+", color=_C["black"], ms=14, mew=2.2, label="the station P")
        self.labels = [a.annotate(n, (0, 0), xytext=(7, 5), textcoords="offset points", color=_C["control"],
                                  fontweight="bold") for n in ("I", "II", "III", "IV")]
        a.grid(True, alpha=0.3)
        self.origin = np.array([6_060_000.0, 5_310_000.0])
        self._fixed = None  # (known points, circle) in plot coordinates, as last set
        self._frame = None  # (centre, least half-width) of the square frame around them

    def _xy(self, P):
        """Geodetic (X north, Y east) → plot (east, north) relative to the origin."""
        P = np.asarray(P, float) - self.origin
        return P[..., ::-1]

    def update(self, r: ResectionResult) -> None:
        K = self._xy(r.known)
        circ = self._xy(r.danger_centre + r.danger_radius_m * self._circle_t)
        if self._fixed is None or not (np.array_equal(self._fixed[0], K) and np.array_equal(self._fixed[1], circ)):
            # the known points and their circle: set only when they change, so that a move of the station
            # leaves them (and the frame around them) in a live demo's cached background
            self._fixed = (K, circ)
            lo, hi = np.vstack([K, circ]).min(axis=0), np.vstack([K, circ]).max(axis=0)
            self._frame = ((lo + hi) / 2, 0.55 * float(max(hi - lo)))  # the frame's centre and least half-width
            self.known.set_data(K[:, 0], K[:, 1])
            for t, p in zip(self.labels, K):
                t.xy = (p[0], p[1])
            self.circle.set_data(circ[:, 0], circ[:, 1])
        P = self._xy(r.station)
        self.station.set_data([P[0]], [P[1]])
        self.rays.set_segments([np.array([P, k]) for k in K[:3]])
        self.check_ray.set_segments([np.array([P, K[3]])])
        cl = r.cloud[np.all(np.isfinite(r.cloud), axis=1)]
        k = exaggeration(r.cloud_rms_m)
        cl = self._xy(r.station + k * (cl - r.station)) if len(cl) else np.zeros((0, 2))
        self.cloud.set_data(cl[:, 0], cl[:, 1])
        # set_text, not set_title: set_title restyles the axes' other titles too, which is a change of the axes
        self.ax.title.set_text(_t("Resection: three known points, two angles (scatter ×{k})", k=k))
        # a square frame centred on the known points and their circle, its half-width a round value
        # (plots.coarse_ceil) just beyond them and the station: it changes only when the station walks out of it
        mid, least = self._frame
        half = plots.coarse_ceil(max(least, 1.08 * float(np.max(np.abs(P - mid))) + 60.0))
        self.ax.set_xlim(mid[0] - half, mid[0] + half)
        self.ax.set_ylim(mid[1] - half, mid[1] + half)


class ResectionDemo(LiveDemo):
    """Move the station and watch its resection go soft near the danger circle."""

    title = "Resection (обратная засечка) and the danger circle (guide §11)"
    hint = ("Each blue dot is the station resected from angles with random errors of σβ. Walk the station towards "
            "the dashed circle through I, II, III: the cloud stretches, and on the circle the angles no longer "
            "fix the station.")
    params = (
        Param("north_m", "P north, m", -1500.0, 1500.0, 10.0, -150.0, group="Station",
              help="the station's offset north of the centre of I, II, III"),
        Param("east_m", "P east, m", -1500.0, 1500.0, 10.0, -300.0, group="Station",
              help="the station's offset east of the centre of I, II, III"),
        Param("sigma_arcsec", "σβ, ″", 0.0, 30.0, 1.0, 5.0, group="Angles", help="RMS error of a measured angle"),
    )

    def build(self):
        self.view = ResectionView()
        self.fig = self.view.fig
        v = self.view
        # the station, its rays, the cloud and the title (its ×k) move over the cached axes, known points and
        # danger circle; the frame is a round square (ResectionView.update), so a move that keeps it keeps the
        # axes' ticks and labels; one that changes it (the station walked out) is a full draw
        self.animated = (v.rays, v.check_ray, v.cloud, v.station, v.ax.title)
        plots.steady_limits(v.ax, snap=False)  # the same limits again are no change

    def compute(self, **v):
        return resection_model(**v)

    def render(self, result):
        self.view.update(result)
        self.table.value = plots.html_table(result.table(), caption="The resection")


# =========================================================================== marking
def marking_figure(photo, *, zoom_mm: float = 7.0):
    """A rendered photo with its visible control points ringed by 8 and 10 mm circles, and one enlarged.

    ``photo`` is a :class:`aerophoto.render.Photo`.  Left: the whole photo (mm);
    right: ±``zoom_mm`` around the first control point, with the 0.1 mm
    pricking tolerance drawn to scale.
    """
    from matplotlib.patches import Circle

    fig = plots.figure(figsize=(9.6, 4.8))
    ax, zx = fig.subplots(1, 2)
    pts = photo.points()
    pts = pts[pts["visible"] & pts["control"]]
    for a in (ax, zx):
        a.imshow(photo.image, cmap="gray", vmin=0, vmax=1, extent=photo.extent_mm, interpolation="antialiased")
        a.set_aspect("equal")
        a.grid(False)
        a.set_xlabel("x, mm")
        a.set_ylabel("y, mm")
        for _, p in pts.iterrows():
            for d in c.MARKING_CIRCLES_MM:
                a.add_patch(Circle((p["x_mm"], p["y_mm"]), d / 2, fill=False, color="#E8112D", lw=1.4))
    for _, p in pts.iterrows():
        ax.annotate(str(p["id"]), (p["x_mm"], p["y_mm"]), xytext=(7, 7), textcoords="offset points",
                    color="#E8112D", fontweight="bold", fontsize=10)
    h = photo.camera.half_mm
    ax.set_xlim(-h, h)
    ax.set_ylim(-h, h)
    ax.set_title("Control points ringed by 8 and 10 mm circles")
    if len(pts):
        p = pts.iloc[0]
        x, y = p["x_mm"], p["y_mm"]
        zx.set_xlim(x - zoom_mm, x + zoom_mm)
        zx.set_ylim(y - zoom_mm, y + zoom_mm)
        zx.add_patch(Circle((x, y), c.PRICKING_MM, fill=True, color="#E8112D"))
        zx.set_title(f"point {p['id']} enlarged; red dot: 0.1 mm")
    return fig
