"""Chapter 11's lab (guide §12): the student's paper deformation table and their photo for rectification.

* :func:`paper_lab` — the student's own table 11: six lengths on the control
  grid (5 mm squares: two lines, two other lines and two diagonals of the
  rectangle they span, the numbers of squares drawn from the variant) and on
  the contact print (mm, to 0.1 mm, with a paper deformation of the variant,
  sometimes shrinking, sometimes stretching); f and m from the variant, the
  base at 1:M = 1:10 000.
* :func:`rectification_lab` — the student's photo of the virtual site: variant
  f, 1:m, α = 3°, λ, a heading and a centre drawn from the variant; four
  control points near the corners of the working area and two check points,
  measured on the photo (pricking error σ = 0.03 mm, to 0.01 mm) and on the
  base (1:10 000, to 0.01 mm).  The site is not flat (30 m of relief).
  :func:`rectification_lab_for` picks the points for any photo (the live demo's);
  :func:`example_rectification_lab` is the guide's own numbers (f = 108 mm,
  1:15 000, base 1:5000), which no variant has.

The graded tasks are :mod:`aerophoto.tasks.ch11`.
"""

from __future__ import annotations

import functools
import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import geometry as g
from .. import rectify as rf
from ..site import get_site

__all__ = ["PLAN_M", "PRICKING_SIGMA_MM", "PaperLab", "paper_lab", "RectificationLab", "rectification_lab_for",
           "rectification_lab", "example_rectification_lab"]

#: the base's scale denominator for the variants (guide §1: 1/M = 1/10 000)
PLAN_M = 10000.0
#: RMS pricking/measuring error of a point on the photo, mm
PRICKING_SIGMA_MM = 0.03


# =========================================================================== task 11.1: table 11
@dataclass(frozen=True)
class PaperLab:
    """The student's table 11: grid lengths, print lengths, and the parameters.

    Attributes
    ----------
    squares : tuple of (along, across)
        The grid squares each length spans.
    l0_mm, li_mm : ndarray (6,)
        Lengths on the grid (exact, 5 mm squares; shown to 0.01 mm) and on the print (0.1 mm).
    f_mm, m, M : float
    """

    squares: tuple
    l0_mm: np.ndarray
    li_mm: np.ndarray
    f_mm: float
    m: float
    M: float

    def table(self) -> pd.DataFrame:
        """What the student reads: l₀ and l_i per line, and the squares."""
        return pd.DataFrame({"squares": [f"{a}" if b == 0 else f"{a} × {b} (diagonal)" for a, b in self.squares],
                             "l₀ on the grid, mm": np.round(self.l0_mm, 2), "l_i on the print, mm": self.li_mm},
                            index=pd.Index([f"l{k + 1}" for k in range(len(self.l0_mm))], name="line"))

    def parameters(self) -> pd.DataFrame:
        return pd.DataFrame({"value": [self.f_mm, f"1:{self.m:.0f}", f"1:{self.M:.0f}"]},
                            index=pd.Index(["f, mm", "photo scale 1:m", "base scale 1:M"], name="parameter"))

    @property
    def deformation(self) -> rf.PaperDeformation:
        return rf.paper_deformation(np.round(self.l0_mm, 2), self.li_mm)


@functools.lru_cache(maxsize=128)
def _paper(i: int, f_mm: float, m: float) -> PaperLab:
    rng = np.random.default_rng([int(i), 12])
    a = int(rng.integers(16, 25))
    b = int(rng.integers(16, 25))
    squares = ((a, 0), (a, 0), (b, 0), (b, 0), (a, b), (a, b))
    l0 = np.array([rf.control_grid_length_mm(p, q) for p, q in squares])
    while True:
        K = float(rng.choice([-1.0, 1.0]) * rng.uniform(0.0006, 0.0018))
        li = np.round(l0 * (1.0 - K) + rng.normal(0.0, 0.08, size=6), 1)
        dl = np.round(l0, 2) - li
        if abs(dl.sum() / np.round(l0, 2).sum()) >= 3e-4:
            break
    return PaperLab(squares, l0, li, float(f_mm), float(m), PLAN_M)


def paper_lab(v) -> PaperLab:
    """The student's table 11 for variant ``v`` (i, f, m)."""
    return _paper(int(v.i), float(v.f_mm), float(v.m))

# =========================================================================== task 11.2: four-point rectification
@dataclass(frozen=True)
class RectificationLab:
    """A photo of the site with four control points and two check points, measured on the photo and the base.

    Attributes
    ----------
    camera, pose : the photo's camera and true exterior orientation
    M : float
        The base's scale denominator.
    origin_m : ndarray (2,)
        The ground point (site X, Y) at the base's origin.
    points : DataFrame
        index "1"…"4" (control) and "K1", "K2" (check): ``role``, ``site id``, ``x photo, mm``,
        ``y photo, mm`` (measured, 0.01 mm), ``x base, mm``, ``y base, mm`` (0.01 mm), ``Z, m`` (the point's height).
    """

    camera: g.Camera
    pose: g.Pose
    M: float
    origin_m: np.ndarray
    points: pd.DataFrame

    def table(self) -> pd.DataFrame:
        """What the student reads: every point's role and its photo and base coordinates."""
        return self.points[["role", "x photo, mm", "y photo, mm", "x base, mm", "y base, mm"]].copy()

    def _xy(self, role, which):
        df = self.points[self.points["role"] == role]
        return df[[f"x {which}, mm", f"y {which}, mm"]].to_numpy(dtype=float)

    @functools.cached_property
    def rectification(self) -> rf.Rectification:
        """The projective fit on the four control points with the residuals at the check points."""
        return rf.rectify_points(self._xy("control", "photo"), self._xy("control", "base"),
                                 self._xy("check", "photo"), self._xy("check", "base"))

    def base_to_ground(self, xy_base_mm) -> np.ndarray:
        """Base mm → site X, Y, m."""
        return np.asarray(xy_base_mm, float) * self.M / 1000.0 + self.origin_m

    @property
    def mean_height_m(self) -> float:
        return float(self.points["Z, m"].mean())


def rectification_lab_for(camera: g.Camera, pose: g.Pose, M: float, *, site=None, seed: int = 0,
                          sigma_mm: float = PRICKING_SIGMA_MM, margin_mm: float = 12.0) -> RectificationLab:
    """Pick four control points near the corners of the photo's working area and two check points inside it.

    Control points are the site's well-defined points (road crossings, field
    corners, building corners, single trees — "separate bushes" serve as
    control points too, article 001) farthest out in each quadrant of the photo,
    at least ``margin_mm`` from its edge (guide §13: not nearer than 1 cm to
    the edges); the check points (of any kind, not control points) are K1,
    the point nearest to the middle of the working area's lower half, and K2,
    the point where relief displaces most: the largest |Z − mean Z of the
    control points| · r among the points at least 20 mm from every control point.  Photo coordinates carry a pricking error of σ = ``sigma_mm``
    (seeded) and are rounded to 0.01 mm; base coordinates are exact, rounded
    to 0.01 mm.
    """
    site = get_site() if site is None else site
    cat = site.catalogue
    P = cat[["X_m", "Y_m", "Z_m"]].to_numpy(dtype=float)
    xy = g.ground_to_photo(camera, pose, P)
    lim = camera.half_mm - margin_mm
    inside = np.all(np.abs(xy) <= lim, axis=1)
    well = cat["kind"].isin(["road crossing", "field corner", "building corner", "tree"]).to_numpy()
    chosen = []
    for sx, sy in ((-1, -1), (1, -1), (1, 1), (-1, 1)):
        q = inside & well & (np.sign(xy[:, 0]) == sx) & (np.sign(xy[:, 1]) == sy)
        if not q.any():
            raise ValueError("the photo has a quadrant without a well-defined site point; move the photo")
        k = np.flatnonzero(q)
        score = (xy[k, 0] * sx + xy[k, 1] * sy) - 0.6 * np.abs(np.abs(xy[k, 0]) - np.abs(xy[k, 1]))
        chosen.append(int(k[np.argmax(score)]))
    used = set(chosen)
    k = np.array([j for j in np.flatnonzero(inside) if j not in used])
    j1 = int(k[np.argmin(np.hypot(*(xy[k] - np.array([0.0, -0.45 * lim])).T))])
    k = k[k != j1]
    # the second check point: where relief shows most — the largest |Z − Z_control|·r — at least 20 mm from
    # every control point (right beside one, the fit forces the residual small)
    far = np.min(np.hypot(*(xy[k][:, None, :] - xy[chosen][None, :, :]).transpose(2, 0, 1)), axis=1) >= 20.0
    k = k[far] if far.any() else k
    zc = P[chosen, 2].mean()
    j2 = int(k[np.argmax(np.abs(P[k, 2] - zc) * np.hypot(*xy[k].T))])
    checks_ = [j1, j2]
    idx = chosen + checks_
    rng = np.random.default_rng([int(seed), 13])
    meas = np.round(xy[idx] + rng.normal(0.0, sigma_mm, size=(len(idx), 2)), 2)
    origin = np.round(np.array([pose.X_m, pose.Y_m]), -2)
    base = np.round((P[idx, :2] - origin) * 1000.0 / M, 2)
    pts = pd.DataFrame({"role": ["control"] * 4 + ["check"] * 2, "site id": cat["id"].to_numpy()[idx],
                        "x photo, mm": meas[:, 0], "y photo, mm": meas[:, 1], "x base, mm": base[:, 0],
                        "y base, mm": base[:, 1], "Z, m": P[idx, 2]},
                       index=pd.Index(["1", "2", "3", "4", "K1", "K2"], name="point"))
    return RectificationLab(camera, pose, float(M), origin, pts)


@functools.lru_cache(maxsize=128)
def _rect(i: int, f_mm: float, m: float, alpha_deg: float, lambda_deg: float) -> RectificationLab:
    site = get_site()
    rng = np.random.default_rng([int(i), 14])
    cx, cy = site.centre_m
    cam = g.Camera(f_mm)
    H = g.flying_height_m(f_mm, m)
    foot = cam.half_mm * m / 1000.0
    room_x = max(0.0, site.params.width_m / 2 - 1.15 * foot * math.sqrt(2))
    room_y = max(0.0, site.params.height_m / 2 - 1.15 * foot * math.sqrt(2))
    for _ in range(200):  # a photo with a usable point in every quadrant
        X = cx + rng.uniform(-1, 1) * min(room_x, 2500.0)
        Y = cy + rng.uniform(-1, 1) * min(room_y, 1200.0)
        pose = g.Pose(X, Y, site.mean_height_m + H, alpha_deg, lambda_deg, float(rng.uniform(-15.0, 15.0)))
        try:
            lab = rectification_lab_for(cam, pose, PLAN_M, site=site, seed=int(i))
        except ValueError:
            continue
        if _firm(lab):
            return lab
    raise RuntimeError(f"no photo position for variant {i} has control points in every quadrant")  # pragma: no cover


def _firm(lab) -> bool:
    """The control quadrilateral spans the photo: every side at least 60 % of the working area's side."""
    P = lab.points[lab.points["role"] == "control"][["x photo, mm", "y photo, mm"]].to_numpy(float)
    sides = np.hypot(*(np.roll(P, -1, axis=0) - P).T)
    return bool(sides.min() >= 0.6 * (2 * (lab.camera.half_mm - 12.0)))


def rectification_lab(v) -> RectificationLab:
    """The student's photo and points for variant ``v`` (i, f, m, α, λ)."""
    return _rect(int(v.i), float(v.f_mm), float(v.m), float(v.alpha_deg), float(v.lambda_deg))


@functools.lru_cache(maxsize=2)
def example_rectification_lab(relief: bool = True) -> RectificationLab:
    """The chapter's worked example: the guide's §12 numbers (f = 108 mm, 1:15 000, base 1:5000), α = 3°.

    ``relief=False`` photographs the flat version of the site (relief 0).
    """
    site = get_site() if relief else get_site(relief_m=0)
    cam = g.Camera(108.0)
    H = g.flying_height_m(108.0, 15000.0)
    cx, cy = site.centre_m
    pose = g.Pose(cx - 600.0, cy + 150.0, site.mean_height_m + H, 3.0, -60.0, 8.0)
    return rectification_lab_for(cam, pose, 5000.0, site=site, seed=2014)
