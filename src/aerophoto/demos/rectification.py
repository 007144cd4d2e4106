"""The photo transformer live, and a rectified photo against the ground truth (chapter 11, guide §12).

* :func:`transformer_model` / :class:`TransformerDemo` — a tilted photo of the
  flat site is projected onto the screen by a photo transformer; the
  operator's sequence of motions (:func:`aerophoto.rectify.transformer_sequence`:
  centre, scale, find hh, turn, tilt, repeat) brings the images of the
  transformation points onto their places on the base, step by step, until
  every residual is within 0.4 mm.  The "step" slider walks through the
  sequence; the photo itself is resampled onto the screen at every step
  (:func:`aerophoto.projective.warp_photo`).  While a photo slider is being
  dragged the photo is made at a preview resolution.
* :func:`rectified_figure` — a photo rectified on four control points
  (:func:`aerophoto.rectify.rectify_points`) set against the site's truth:
  the residual of every catalogue point, which on hilly ground is the relief
  displacement that rectification leaves.

The worked example uses the guide's §12 numbers: f = 108 mm, photo 1:15 000,
base 1:5000 (K_t = 3).
"""

from __future__ import annotations

import functools
import html
import math
from dataclasses import dataclass

import numpy as np
from matplotlib import patheffects
import pandas as pd

from .. import geometry as g
from .. import plots
from .. import projective as pj
from .. import rectify as rf
from ..i18n import t as _t  # functions here name a local t
from ..i18n.numfmt import fmt_number
from ..widgets import LiveDemo, Param

__all__ = ["EXAMPLE", "TransformerResult", "transformer_model", "TransformerView", "TransformerDemo",
           "rectified_figure", "residual_field"]

_C = plots.COLORS
#: the guide's §12 numbers and where the example photo is taken
EXAMPLE = dict(f_mm=108.0, m=15000.0, M=5000.0, offset_m=(-600.0, 150.0))
#: rendering resolution: while dragging and at rest
PREVIEW_PX, FULL_PX = 160, 320
#: screen raster pixel, mm on the base
SCREEN_PIXEL_MM = 1.5
EXAMPLE_FRAME_MM = 180.0


@functools.lru_cache(maxsize=4)
def _site(flat: bool):
    from ..site import get_site

    return get_site(relief_m=0) if flat else get_site()


def _pose(alpha_deg, lambda_deg, kappa_deg, flat=True):
    site = _site(flat)
    cx, cy = site.centre_m
    H = g.flying_height_m(EXAMPLE["f_mm"], EXAMPLE["m"])
    return g.Pose(cx + EXAMPLE["offset_m"][0], cy + EXAMPLE["offset_m"][1], site.mean_height_m + H, alpha_deg,
                  lambda_deg, kappa_deg)


@functools.lru_cache(maxsize=8)
def _photo(alpha_deg, lambda_deg, kappa_deg, n_px):
    """The example's photo of the flat site, ``n_px`` across: the site's texture resampled through ground → photo.

    Over flat ground a photo is a projective image of the ground, so the
    picture is the texture (at the pyramid level of the photo's ground pixel)
    warped by the homography that :func:`aerophoto.geometry.ground_to_photo`
    fixes on four ground points — exact for the bare ground, and some ten
    times quicker than ray-casting it (:func:`aerophoto.render.render`, which
    the chapter's static figures use, objects with height included).
    Returns a :class:`aerophoto.projective.Raster` in photo mm.
    """
    site = _site(True)
    cam = g.Camera(EXAMPLE["f_mm"])
    pose = _pose(alpha_deg, lambda_deg, kappa_deg, True)
    z = site.base_height_m
    G = g.photo_to_plane(cam, pose, cam.corners_mm(), z)
    to_photo = pj.fit_projective(G[:, :2], cam.corners_mm())
    p = cam.frame_mm / n_px
    level = site.level_for(p * (pose.Z_m - z) / cam.f_mm)
    t = site.texel_m(level)
    tex = site.texture_level(level).astype(np.float32) / np.float32(255.0)
    pixels = np.array([[t, 0.0, 0.5 * t], [0.0, t, 0.5 * t], [0.0, 0.0, 1.0]])  # texture (col, row) → ground X, Y
    h = cam.half_mm
    return pj.warp_raster(tex, pixels, to_photo, (-h, h, -h, h), p, cval=0.5)


@functools.lru_cache(maxsize=16)
def _points(alpha_deg, lambda_deg, kappa_deg, sigma_mm, flat=True):
    """The four transformation points and the central point: photo mm (with pricking error) and base mm."""
    from ..labs.ch11 import rectification_lab_for

    cam = g.Camera(EXAMPLE["f_mm"])
    pose = _pose(alpha_deg, lambda_deg, kappa_deg, flat)
    site = _site(flat)
    lab = rectification_lab_for(cam, pose, EXAMPLE["M"], site=site, seed=2014, sigma_mm=0.0)
    ctrl = lab.points[lab.points["role"] == "control"]
    cat = site.catalogue
    well = cat[cat["kind"].isin(["road crossing", "field corner", "building corner"])]
    P = well[["X_m", "Y_m", "Z_m"]].to_numpy(float)
    xy = g.ground_to_photo(cam, pose, P)
    k = int(np.argmin(np.hypot(*xy.T)))
    photo = np.vstack([ctrl[["x photo, mm", "y photo, mm"]].to_numpy(float), xy[k]])
    base = np.vstack([ctrl[["x base, mm", "y base, mm"]].to_numpy(float), (P[k, :2] - lab.origin_m) * 1000.0 / lab.M])
    rng = np.random.default_rng([2014, 15])
    photo = photo + rng.normal(0.0, 1.0, size=photo.shape) * float(sigma_mm)
    return photo, base, lab.origin_m


def _state_matrix(state: rf.TransformerState, f_mm: float) -> np.ndarray:
    """3×3 homogeneous matrix photo mm → screen (base) mm of a transformer state."""
    R = g.rotation_matrix(g.Pose(alpha_deg=state.eps_deg, lambda_deg=state.tilt_dir_deg))
    H_lev = np.diag([-f_mm, -f_mm, 1.0]) @ R @ np.diag([1.0, 1.0, -f_mm])
    th = math.radians(state.theta_deg)
    S = np.array([[state.scale * math.cos(th), -state.scale * math.sin(th), state.tx_mm],
                  [state.scale * math.sin(th), state.scale * math.cos(th), state.ty_mm], [0.0, 0.0, 1.0]])
    return S @ H_lev


@dataclass(frozen=True)
class TransformerResult:
    """One step of the photo transformer's sequence, with the photo on the screen.

    Attributes
    ----------
    run : :class:`aerophoto.rectify.TransformerRun`
    step : int
        The step shown (clipped to the run's length).
    photo_mm, base_mm : ndarray (5, 2) — points 1–4 and the central point on the photo and on the base
    screen : :class:`aerophoto.projective.Raster` — the photo as projected at this step
    preview : bool
    frame_mm : (x_min, x_max, y_min, y_max) — the piece of the screen shown (the raster covers it to a pixel)
    """

    run: rf.TransformerRun
    step: int
    photo_mm: np.ndarray
    base_mm: np.ndarray
    screen: pj.Raster
    preview: bool
    frame_mm: tuple | None = None

    @property
    def current(self) -> rf.TransformerStep:
        return self.run.steps[self.step]

    def table(self) -> pd.DataFrame:
        s = self.current
        st = s.state
        first = self.run.within_tolerance_step
        conv = self.run.converged_step
        rows = [("motion", "", _t("{step}: {name} (cycle {cycle})", step=self.step, name=_t(s.name), cycle=s.cycle)),
                ("what the operator does", "", rf.STEP_NAMES[s.name]),
                ("screen tilt ε", "°", fmt_number(st.eps_deg, 3)),
                ("tilt direction λ_t", "°", fmt_number(st.tilt_dir_deg % 360, 1)),
                ("cassette turn θ", "°", fmt_number(st.theta_deg, 2)),
                ("enlargement s", "", fmt_number(st.scale, 4))]
        names = ("1", "2", "3", "4", "centre")
        rows += [(f"residual at {n}", "mm", fmt_number(d, 2)) for n, d in zip(names, s.lengths_mm)]
        rows.append(("largest residual vs 0.4 mm", "", fmt_number(s.max_residual_mm, 2) + " — "
                     + _t("within" if s.max_residual_mm <= rf.TOLERANCE_MM else "not yet")))
        rows.append(("every point within 0.4 mm from step", "", "—" if first is None else f"{first}"))
        rows.append(("first full cycle within 0.4 mm ends at step", "", "—" if conv is None else f"{conv}"))
        return pd.DataFrame(rows, columns=["quantity", "unit", "value"]).set_index("quantity")


def transformer_model(step: int = 0, alpha_deg: float = 3.0, lambda_deg: float = -60.0, kappa_deg: float = 8.0,
                      sigma_mm: float = 0.03, *, preview: bool = False) -> TransformerResult:
    """The photo transformer's sequence for the example photo, shown at ``step`` (guide §12 step 3).

    Parameters
    ----------
    step : which motion to show, 0 = where the operator starts
    alpha_deg, lambda_deg, kappa_deg : the photo's tilt, principal-vertical direction and heading, °
    sigma_mm : pricking error of the points on the photo, mm
    preview : render the photo at the preview resolution
    """
    a, lam, kap, sig = float(alpha_deg), float(lambda_deg), float(kappa_deg), float(sigma_mm)
    run, photo, base = _run(a, lam, kap, sig)
    k = int(min(max(int(step), 0), len(run.steps) - 1))
    img = _photo(a, lam, kap, PREVIEW_PX if preview else FULL_PX)
    M = _state_matrix(run.steps[k].state, EXAMPLE["f_mm"])
    lo, hi = base.min(axis=0), base.max(axis=0)
    pad = 0.25 * float(max(hi - lo))
    ext = (lo[0] - pad, hi[0] + pad, lo[1] - pad, hi[1] + pad)
    px = SCREEN_PIXEL_MM * (2.0 if preview else 1.0)
    screen = pj.warp_photo(img.image, M, ext, px, frame_mm=EXAMPLE_FRAME_MM, cval=1.0)
    return TransformerResult(run, k, photo, base, screen, bool(preview), ext)


@functools.lru_cache(maxsize=32)
def _run(a, lam, kap, sig):
    photo, base, _ = _points(a, lam, kap, sig)
    f = EXAMPLE["f_mm"]
    Kt = EXAMPLE["m"] / EXAMPLE["M"]
    # where the operator starts: screen level, cassette not turned, the enlargement from the scales,
    # the principal point on the central point's place
    start = rf.TransformerState(0.0, 0.0, 0.0, Kt, float(base[4, 0] - Kt * photo[4, 0]),
                                float(base[4, 1] - Kt * photo[4, 1]))
    run = rf.transformer_sequence(photo, base, f, centre_index=4, start=start, cycles=4)
    return run, photo, base


class TransformerView:
    """The screen: the projected photo, the base's points, the images' misses (arrows ×k) and hh."""

    def __init__(self, ax=None):
        self.fig, self.ax = plots.new_axes(ax, figsize=(7.4, 6.0))
        a = self.ax
        a.set_aspect("equal")
        a.set_xlabel("x on the base, mm")
        a.set_ylabel("y on the base, mm")
        a.grid(False)
        self.image = a.imshow(np.ones((2, 2)), cmap="gray", vmin=0, vmax=1, extent=(0, 1, 0, 1),
                              interpolation="antialiased")
        # black: blue sat too close to the pink base triangles with protanopia (tests/presentation/test_colours)
        (self.hh,) = a.plot([], [], "-.", color=_C["black"], lw=1.6, label="principal horizontal hh")
        (self.hh_pts,) = a.plot([], [], "x", color=_C["black"], ms=7, mew=1.6, label="crossings of corresponding lines")
        # a black outline under the pink triangles: they stay visible on the grey photo with any colour vision
        (self.base,) = a.plot([], [], "^", mfc="none", mec=_C["control"], mew=2.4, ms=12,
                              label="points on the base planchet",
                              path_effects=[patheffects.withStroke(linewidth=4.6, foreground="black")])
        (self.images,) = a.plot([], [], "o", color=_C["orange"], ms=7, label="their images on the screen",
                                markeredgecolor="black", markeredgewidth=0.8)
        self.arrows = a.quiver(np.zeros(5), np.zeros(5), np.zeros(5), np.zeros(5), angles="xy", scale_units="xy",
                               scale=1.0, color=_C["vermillion"], width=0.006, zorder=5, label="misses (lengthened ×k)")
        a.legend(loc="upper right")  # the key (a live demo shows it beside the figure: LiveDemo.legend_beside)

    def update(self, r: TransformerResult) -> None:
        s = r.current
        self.image.set_data(r.screen.image)
        self.image.set_extent(r.screen.extent)
        # the piece of the screen asked for (the preview's coarser raster ends up to a pixel further out)
        x0, x1, y0, y1 = r.frame_mm if r.frame_mm is not None else r.screen.extent
        self.ax.set_xlim(x0, x1)
        self.ax.set_ylim(y0, y1)
        self.base.set_data(r.base_mm[:, 0], r.base_mm[:, 1])
        self.images.set_data(s.images_mm[:, 0], s.images_mm[:, 1])
        L = float(np.max(s.lengths_mm))
        span = x1 - x0
        k = 1
        for kk in (1, 2, 5, 10, 20, 50, 100, 200, 500):
            if kk * L <= 0.12 * span:
                k = kk
        self.arrows.set_offsets(s.images_mm)
        self.arrows.set_UVC(k * s.residuals_mm[:, 0], k * s.residuals_mm[:, 1])
        if s.hh is not None:
            p, d = s.hh
            t = np.array([-2.0, 2.0]) * span
            self.hh.set_data(p[0] + t * d[0], p[1] + t * d[1])
            pts = s.hh_points if s.hh_points is not None else np.zeros((0, 2))
            self.hh_pts.set_data(pts[:, 0], pts[:, 1])
        else:
            self.hh.set_data([], [])
            self.hh_pts.set_data([], [])
        # set_text, not set_title: set_title restyles the axes' other titles too, which is a change of the axes
        self.ax.title.set_text(_t("Step {step}: {name} — misses ×{k}, largest {largest} mm", step=r.step,
                                  name=_t(s.name), k=k, largest=fmt_number(s.max_residual_mm, 2)))


class TransformerDemo(LiveDemo):
    """Walk through the photo transformer's motions until the points fall within 0.4 mm."""

    photo_frames = True  # a move changes the photo: its frames go as JPEG (plots.fast_frames; issue 32)
    title = "The photo transformer: matching four points (guide §12)"
    hint = ("Move 'step' to follow the operator: centre, scale, draw hh through the crossings of corresponding "
            "lines, turn it onto the screen's axis, tilt the screen. The arrows (lengthened ×k) are the misses; "
            "the sequence repeats until all are within 0.4 mm.")
    params = (
        Param("step", "step", 0, 20, 1, 0, kind="int", group="Sequence", help="which motion of the sequence"),
        Param("alpha_deg", "α, °", 0.0, 10.0, 0.5, 3.0, group="Photo", help="tilt of the photo"),
        Param("lambda_deg", "λ, °", -180.0, 180.0, 10.0, -60.0, group="Photo",
              help="direction of the principal vertical"),
        Param("kappa_deg", "κ, °", -30.0, 30.0, 2.0, 8.0, group="Photo", help="heading of the photo"),
        Param("sigma_mm", "pricking σ, mm", 0.0, 0.2, 0.01, 0.03, group="Photo",
              help="RMS error of the pricked points on the photo"),
    )
    noted = ("step",)  # the motion a step is, under the slider

    def build(self):
        self.view = TransformerView()
        self.fig = self.view.fig
        v = self.view
        # a step re-projects the photo and moves the images, the misses, hh and the title over the cached axes (the
        # screen's limits are the base's, the same at every step); the photo's sliders move the base's frame a
        # little: its limits are rounded outwards (a step ≈ 2.5 % of the span) so that they mostly stay
        self.animated = (v.image, v.hh, v.hh_pts, v.base, v.images, v.arrows, v.ax.title)
        plots.steady_limits(v.ax)

    def compute(self, **v):
        return transformer_model(**v, preview=self._preview)

    def render(self, result):
        self.view.update(result)
        self._shown = dict(self.values)
        self.table.value = plots.html_table(result.table(), caption="The screen")
        s = result.current
        self.notes["step"].value = html.escape(_t("= {name}, cycle {cycle}", name=_t(s.name), cycle=s.cycle))

    def on_slider(self) -> str:
        """Photo sliders: a preview render at once, the full resolution when the slider rests.  The step slider is
        discrete and cheap: every step is drawn at full resolution at once (no blurred frame, no status line)."""
        shown = getattr(self, "_shown", {})
        if {k for k, v in self.values.items() if shown.get(k) != v} <= {"step"}:
            self.cancel_later()
            self.update()
            return ""
        return self.preview_then_full(0.25)


# =========================================================================== rectified photo against the truth
def residual_field(lab, *, relief: bool = True) -> pd.DataFrame:
    """Where every visible catalogue point lands after rectification on the lab's four points, against the truth.

    ``lab`` is a :class:`aerophoto.labs.ch11.RectificationLab`.  Returns one
    row per point with ``x base, mm``, ``y base, mm`` (truth), ``dx, mm``,
    ``dy, mm`` (rectified − truth) and ``h, m`` (height above the control points' mean).
    """
    site = _site(not relief)
    cat = site.catalogue
    P = cat[["X_m", "Y_m", "Z_m"]].to_numpy(float)
    xy = g.ground_to_photo(lab.camera, lab.pose, P)
    inside = np.all(np.abs(xy) <= lab.camera.half_mm - 2.0, axis=1)
    T = lab.rectification.transform
    truth = (P[:, :2] - lab.origin_m) * 1000.0 / lab.M
    got = T.apply(xy)
    zc = lab.points[lab.points["role"] == "control"]["Z, m"].mean()
    df = pd.DataFrame({"id": cat["id"].to_numpy(), "x base, mm": truth[:, 0], "y base, mm": truth[:, 1],
                       "dx, mm": got[:, 0] - truth[:, 0], "dy, mm": got[:, 1] - truth[:, 1],
                       "h, m": P[:, 2] - zc})
    return df[inside].reset_index(drop=True)


def rectified_figure(lab, *, relief: bool = True, n_px: int = 512, pixel_mm: float = 1.0, arrows_x: float = 50.0):
    """A photo rectified on the lab's four points, half of it replaced by the truth, with every point's residual.

    Left: the rectified photo (:func:`aerophoto.projective.warp_photo`) on the
    base; right: the same window of the site's true texture (the plan) — a
    feature that continues straight across the seam is in place.  Arrows
    (×``arrows_x``) show each catalogue point's residual, coloured by its
    height above the control points.
    """
    from ..render import render

    site = _site(not relief)
    photo = render(site, lab.camera, lab.pose, n_px, vignetting=0.1, fiducials=False)
    T = lab.rectification.transform
    base = lab.points[["x base, mm", "y base, mm"]].to_numpy(float)
    lo, hi = base.min(axis=0), base.max(axis=0)
    pad = 0.15 * float(max(hi - lo))
    ext = (lo[0] - pad, hi[0] + pad, lo[1] - pad, hi[1] + pad)
    rect = pj.warp_photo(photo.image, T, ext, pixel_mm, frame_mm=lab.camera.frame_mm)
    XY = lab.base_to_ground(rect.pixel_centres())
    truth = site.sample(XY[..., 0], XY[..., 1], level=site.level_for(pixel_mm * lab.M / 1000.0))
    mixed = rect.image.copy()
    half = mixed.shape[1] // 2
    mixed[:, half:] = truth[:, half:] * (1.0 - 0.1)
    fig = plots.figure(figsize=(9.8, 5.0))
    ax1, ax2 = fig.subplots(1, 2)
    for a, img, title in ((ax1, rect.image, "Rectified photo on the base"),
                          (ax2, mixed, "Left half rectified, right half the truth")):
        a.imshow(img, cmap="gray", vmin=0, vmax=1, extent=rect.extent, interpolation="antialiased")
        a.set_aspect("equal")
        a.grid(False)
        a.set_title(title)
        a.set_xlabel("x on the base, mm")
        ctrl = lab.points[lab.points["role"] == "control"]
        a.plot(ctrl["x base, mm"], ctrl["y base, mm"], "^", mfc="none", mec=_C["control"], mew=2.2, ms=11)
    ax1.set_ylabel("y on the base, mm")
    ax2.axvline(rect.extent[0] + half * rect.pixel, color=_C["yellow"], lw=1.5)
    rf_ = residual_field(lab, relief=relief)
    x0, x1, y0, y1 = rect.extent
    rf_ = rf_[rf_["x base, mm"].between(x0, x1) & rf_["y base, mm"].between(y0, y1)]
    q = ax1.quiver(rf_["x base, mm"], rf_["y base, mm"], arrows_x * rf_["dx, mm"], arrows_x * rf_["dy, mm"],
                   rf_["h, m"], angles="xy", scale_units="xy", scale=1.0, cmap="BrBG_r", width=0.006,
                   edgecolor="k", linewidth=0.4)
    fig.colorbar(q, ax=ax1, shrink=0.7, label="h above the control points, m")
    ax1.set_xlim(rect.extent[0], rect.extent[1])
    ax1.set_ylim(rect.extent[2], rect.extent[3])
    fig.suptitle(f"residuals ×{arrows_x:g}: largest {np.hypot(rf_['dx, mm'], rf_['dy, mm']).max():.2f} mm")
    return fig
