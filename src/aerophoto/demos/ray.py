"""One ray of a vertical photo (chapter 00) — and the cheapest live figure the book's stack can show.

A vertical photo over flat ground is a central projection with the scale 1/m = f/H (guide §1–§2): the point
at x on the photo (mm from the principal point o, along the flight) is the ground point X = x·m (m from the
plumb point N), and its ray leaves the vertical at θ = arctan(x/f).  :class:`RayDemo` moves one ray with the
slider x: a cross-section through the projection centre S, the ground and the photo's footprint.

It is also the browser benchmark's **floor** (``benchmarks/bench_browser.py``): one blitted line — the ray —
moved by one slider, in a figure of the demos' size and resolution, with a table beside it.  Nothing a live demo
can do costs less on the same stack (ipympl, ipywidgets, JupyterLab or Voilà, the same machine), so every
demo's latency is reported as a multiple of this one's, measured in the same run.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import pandas as pd

from .. import geometry as g
from .. import plots
from ..i18n import t
from ..i18n.numfmt import fmt_number
from ..widgets import LiveDemo, Param

__all__ = ["RAY_FIGSIZE", "RayResult", "ray_model", "RayDemo"]

#: the figure's size, inches, at the book's 100 dpi: that of the demos' usual two-panel figures (860 × 460 px)
RAY_FIGSIZE = (8.6, 4.6)


@dataclass(frozen=True)
class RayResult:
    """One ray of a vertical photo: photo x (mm), ground X (m), angle from the vertical θ (degrees)."""

    f_mm: float
    m: float
    x_mm: float
    X_m: float
    theta_deg: float

    @property
    def H_m(self) -> float:
        """Flying height above the ground, H = f·m (m)."""
        return g.flying_height_m(self.f_mm, self.m)

    def table(self) -> pd.DataFrame:
        rows = [("x on the photo", "mm", fmt_number(self.x_mm, 0)),
                ("X = x·m on the ground", "m", fmt_number(self.X_m, 0)),
                ("θ = arctan(x/f) from the vertical", "°", fmt_number(self.theta_deg, 1))]
        return pd.DataFrame(rows, columns=["", "unit", "value"]).set_index("")


def ray_model(x_mm: float = 40.0, f_mm: float = 100.0, m: float = 12000.0) -> RayResult:
    """The ray of photo point x (mm, |x| ≤ half the 180 mm frame) of a vertical photo with f (mm) at 1:m."""
    X = x_mm * m / 1000.0
    return RayResult(float(f_mm), float(m), float(x_mm), float(X), math.degrees(math.atan2(x_mm, f_mm)))


class RayDemo(LiveDemo):
    """One ray of a vertical photo moved by the photo coordinate x (see the module notes): the guide's example
    camera, f = 100 mm at 1:12 000 (H = 1 200 m).  Only the ray moves; the rest is a cached picture."""

    params = (Param("x_mm", "x, mm", -90.0, 90.0, 1.0, 40.0, group="Photo point",
                    help="the point on the photo, from o along the flight"),)
    title = "One ray of a vertical photo"
    hint = "Move x: the ray from S turns, its ground point X = x·m slides along the footprint."
    f_mm = 100.0
    m = 12000.0

    def build(self):
        cam = g.Camera(self.f_mm)
        H = g.flying_height_m(self.f_mm, self.m)
        half = cam.half_mm * self.m / 1000.0  # the footprint's half-side on the ground, m
        self.fig, ax = plots.new_axes(None, figsize=RAY_FIGSIZE)
        self.ax = ax
        C = plots.COLORS
        ax.plot([-1.25 * half, 1.25 * half], [0.0, 0.0], color=C["black"], lw=1.5)
        ax.plot([-half, 0.0, half], [0.0, H, 0.0], color=C["grey"], lw=1.0, ls="--", label="footprint's edge rays")
        ax.plot([-half, half], [0.0, 0.0], color=C["footprint"], lw=6, solid_capstyle="butt", label="footprint")
        ax.plot([0.0], [H], "o", color=C["black"], ms=7)
        ax.annotate("S", (0.0, H), xytext=(8, 4), textcoords="offset points", fontsize=12)
        ax.annotate("N", (0.0, 0.0), xytext=(4, -16), textcoords="offset points", fontsize=12)
        (self.ray,) = ax.plot([], [], color=C["vermillion"], lw=2.5, marker="o", markevery=[1], ms=7,
                              label="the ray of x")
        ax.set_xlim(-1.3 * half, 1.3 * half)
        ax.set_ylim(-0.12 * H, 1.12 * H)
        ax.set_xlabel("X on the ground, m")
        ax.set_ylabel("Z above the ground, m")
        ax.set_title(t("f = {f} mm, 1:{m}: H = f·m = {H} m", f=fmt_number(self.f_mm, 0), m=fmt_number(self.m, 0),
                       H=fmt_number(H, 0)))
        ax.legend(loc="upper right", fontsize=9)
        self.animated = (self.ray,)  # one line: the floor of what a move can cost

    def compute(self, x_mm):
        return ray_model(x_mm, self.f_mm, self.m)

    def render(self, r: RayResult):
        self.ray.set_data([0.0, r.X_m], [r.H_m, 0.0])
        self.table.value = plots.html_table(r.table(), caption=t("One ray"))
