"""Chapter 09's lab (guide §10): the student's piece of farmland, their new photo of it and the old plan.

Each variant has its own piece of farmland (:func:`aerophoto.projective.land_use_scene`
with seed i) and its own new photo of it: the variant's camera f and scale
1:m, tilt α = 3° with the principal vertical at λ, a heading κ and a small
offset of the photo centre drawn from the variant.  The old plan is at
1:10 000 (guide §10).  The student reads (:func:`plan_correction_lab`):

* the four control points on the photo (x, y mm from the principal point, to
  0.01 mm) and on the plan (x, y mm, to 0.01 mm);
* the photo positions of the changes: the corners of the new farm building 1
  and the vertices of the new road.

:func:`lab_for` builds the same for any seed and photo (the worked example:
:data:`EXAMPLE_SEED`).  The graded tasks are :mod:`aerophoto.tasks.ch09`.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import geometry as g
from .. import projective as pj

__all__ = ["PLAN_M", "GRID_N", "SCENE_SIZE_M", "SPREAD", "EXAMPLE_SEED", "PlanCorrectionLab", "lab_for",
           "plan_correction_lab"]

#: the plan's scale denominator (guide §10: a 1:10 000 map)
PLAN_M = 10000.0
#: cells per side of task 09.1's grid
GRID_N = 4
#: side of the variant's square of farmland, m
SCENE_SIZE_M = 1600.0
#: how far out the four control points lie (fraction of the half-side)
SPREAD = 0.85
#: the scene of the chapter's worked example and live demo (no variant's: variants use seeds 0…99)
EXAMPLE_SEED = 2014


@dataclass(frozen=True)
class PlanCorrectionLab:
    """The student's plan-correction data (or the worked example's).

    Attributes
    ----------
    scene : :class:`aerophoto.projective.LandUseScene`
    camera : Camera
    pose : Pose
        The new photo's exterior orientation over flat ground at Z = 0.
    M : float
        The plan's scale denominator.
    control : DataFrame
        The four control points: ``x photo, mm``, ``y photo, mm``, ``x plan, mm``, ``y plan, mm`` (rounded to
        0.01 mm), index "1"…"4".
    changes : DataFrame
        Photo positions of the new features' vertices: ``feature``, ``vertex``, ``x photo, mm``, ``y photo, mm``
        (0.01 mm); index like "farm building 1/1".
    """

    scene: pj.LandUseScene
    camera: g.Camera
    pose: g.Pose
    M: float
    control: pd.DataFrame
    changes: pd.DataFrame

    # -- what the student reads
    def control_table(self) -> pd.DataFrame:
        return self.control.copy()

    def changes_table(self) -> pd.DataFrame:
        return self.changes.copy()

    @property
    def photo_corners(self) -> np.ndarray:
        return self.control[["x photo, mm", "y photo, mm"]].to_numpy(dtype=float)

    @property
    def plan_corners(self) -> np.ndarray:
        return self.control[["x plan, mm", "y plan, mm"]].to_numpy(dtype=float)

    def photo_of(self, feature: str) -> np.ndarray:
        """Photo positions (k, 2) mm of a feature's vertices, as the table gives them."""
        df = self.changes[self.changes["feature"] == feature]
        if not len(df):
            raise ValueError(f"no changed feature {feature!r}; features: {sorted(set(self.changes['feature']))}")
        return df[["x photo, mm", "y photo, mm"]].to_numpy(dtype=float)

    def truth_plan_of(self, feature: str) -> np.ndarray:
        """Where the feature's vertices belong on the plan (the ground truth), plan mm."""
        return self.scene.feature(feature).xy_m * 1000.0 / self.M

    # -- the computations (the instructor's side)
    def grid_pair(self, n: int = GRID_N, method: str = "central") -> pj.GridPair:
        return pj.grid_pair(self.photo_corners, self.plan_corners, n, method)

    @functools.cached_property
    def exact(self) -> pj.Projective2D:
        """The projective transformation photo → plan fixed by the four rounded control points."""
        return pj.fit_projective(self.photo_corners, self.plan_corners)


def _round(a, decimals=2):
    return np.round(np.asarray(a, dtype=float), decimals)


def lab_for(seed: int, f_mm: float, m: float, alpha_deg: float, lambda_deg: float, kappa_deg: float,
            offset_m=(0.0, 0.0), *, M: float = PLAN_M, spread: float = SPREAD,
            size_m: float = SCENE_SIZE_M) -> PlanCorrectionLab:
    """A plan-correction lab for any scene seed and photo (the demo and the worked example use it too)."""
    scene = pj.land_use_scene(seed, size_m)
    cam = g.Camera(f_mm)
    H = g.flying_height_m(f_mm, m)
    pose = g.Pose(float(offset_m[0]), float(offset_m[1]), H, alpha_deg, lambda_deg, kappa_deg)
    cp = scene.control_points(spread)
    G = np.column_stack([cp[["X_m", "Y_m"]].to_numpy(), np.zeros(len(cp))])
    ph = _round(g.ground_to_photo(cam, pose, G))
    pl = _round(cp[["X_m", "Y_m"]].to_numpy() * 1000.0 / M)
    control = pd.DataFrame({"ground point": cp["point"].to_numpy(), "x photo, mm": ph[:, 0], "y photo, mm": ph[:, 1],
                            "x plan, mm": pl[:, 0], "y plan, mm": pl[:, 1]}, index=pd.Index(cp["name"], name="control"))
    V = scene.change_vertices()
    xy = _round(g.ground_to_photo(cam, pose, np.column_stack([V[["X_m", "Y_m"]].to_numpy(), np.zeros(len(V))])))
    changes = pd.DataFrame({"feature": V["feature"].to_numpy(), "vertex": V["vertex"].to_numpy(),
                            "x photo, mm": xy[:, 0], "y photo, mm": xy[:, 1]},
                           index=pd.Index([f"{a}/{b}" for a, b in zip(V["feature"], V["vertex"])], name="point"))
    return PlanCorrectionLab(scene, cam, pose, float(M), control, changes)


@functools.lru_cache(maxsize=128)
def _lab(i: int, f_mm: float, m: float, alpha_deg: float, lambda_deg: float) -> PlanCorrectionLab:
    rng = np.random.default_rng([int(i), 9])
    kappa = float(rng.uniform(-20.0, 20.0))
    offset = rng.uniform(-60.0, 60.0, size=2)
    return lab_for(int(i), f_mm, m, alpha_deg, lambda_deg, kappa, offset)


def plan_correction_lab(v) -> PlanCorrectionLab:
    """The student's lab for variant ``v`` (its i, f, m, α, λ; the scene's seed is i)."""
    return _lab(int(v.i), float(v.f_mm), float(v.m), float(v.alpha_deg), float(v.lambda_deg))
