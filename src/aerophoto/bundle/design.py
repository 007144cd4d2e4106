"""Where the tie points of a block go: the standard (Gruber) positions on every photo.

Analytical aerotriangulation measures tie points (связующие точки) at standard
places of each photo: near its principal point and straight above and below
it, ±d from the photo's x axis (von Gruber's six points of a stereopair are
these three on each photo).  A point near a principal point of a strip with
60 % forward overlap is seen on three consecutive photos (the triple overlap
that carries the scale from model to model), and a point at ±d with d in the
side overlap is seen from the neighbouring strip too (it ties the strips).
Halfway points (x = b/2) make the block denser.

:func:`standard_points` finds the ground points under those photo positions by
intersecting the rays with the terrain (:func:`aerophoto.geometry.photo_to_dem`).
"""

from __future__ import annotations

import numpy as np

from .. import _validate as V
from .. import geometry as g
from .._validate import check_range

__all__ = ["standard_points"]


@V.checked(camera=g.Camera, poses=V.sequence(V.of_type(g.Pose), min_len=2), terrain=V.terrain(none=True))
def standard_points(camera: g.Camera, poses, terrain, *, d_mm: float | None = None, halfway_mm: float | None = None,
                    ) -> np.ndarray:
    """Ground points (k, 3), m, under the standard tie-point positions of every photo.

    Parameters
    ----------
    camera : the frame camera
    poses : sequence of :class:`aerophoto.geometry.Pose` (the true orientation: the points are chosen
        where they image at the standard places)
    terrain : a :class:`aerophoto.geometry.Terrain` (e.g. the virtual site)
    d_mm : distance of the upper and lower points from the photo's x axis, mm (default 0.4·frame:
        72 mm on the 18 cm frame; 0 < d < frame/2)
    halfway_mm : also put points at x = ``halfway_mm`` (e.g. half the photo base) in the three rows
        (None: none)
    """
    half = camera.half_mm
    d = 0.4 * camera.frame_mm if d_mm is None else check_range("d_mm", d_mm, 0.0, half, lo_open=True, unit="mm")
    xs = [0.0]
    if halfway_mm is not None:
        xs.append(check_range("halfway_mm", halfway_mm, -half, half, unit="mm"))
    xy = np.array([[x, y] for x in xs for y in (-d, 0.0, d)])
    T = g.as_terrain(terrain)
    out = [g.photo_to_dem(camera, p, xy, T) for p in poses]
    return np.concatenate(out, axis=0) if out else np.zeros((0, 3))
