"""The student's strip tables in the Russian geodetic convention: x north, y east, directions clockwise from +x.

The package computes in the mathematical convention of :mod:`aerophoto.geometry`:
ground X east, Y north, angles counter-clockwise from +X; a free strip's sheet
x along its first initial direction, y to the left of it.  The guide's catalogue
of control points (§7: 496/1 at X = 6 067 202, Y = 310 574; table 8) and
Russian survey practice use the geodetic convention instead: **X north (up),
Y east (right)**, and directions (дирекционные углы) measured **clockwise from
+X**.  The tables the student works from in chapters 06 and 12 are in that
convention; this module converts, and nothing else in the package changes.

Swapping the two axes turns one convention into the other.  A distance is the
same in both; a direction becomes α = 90° − θ.  Because then cos α = sin θ and
sin α = cos θ, a ray from (x₀, y₀) at direction α is (x₀ + s·cos α, y₀ + s·sin α)
in the geodetic frame exactly as it is (x₀ + s·cos θ, y₀ + s·sin θ) in the
mathematical one: formulas of intersection and resection read the same in both
conventions, so :func:`aerophoto.plane.intersect_rays` and
:func:`aerophoto.plane.error_triangle` take geodetic (x, y, α) as they are.

Ground coordinates get the offset :data:`GEODETIC_ORIGIN_M` so that they look
like the guide's Gauss–Krüger coordinates (seven digits north, six east); they
are made up — the virtual site is nowhere.
"""

from __future__ import annotations

import numpy as np

from .._validate import check_finite_array

__all__ = ["GEODETIC_ORIGIN_M", "ground_to_geodetic", "geodetic_to_ground", "sheet_to_geodetic",
           "direction_to_geodetic_deg", "geodetic_to_direction_rad"]

#: geodetic X (north) and Y (east), metres, of the virtual site's south-west corner (ground X = Y = 0)
GEODETIC_ORIGIN_M = (6_060_000.0, 310_000.0)


def _xy(name: str, a) -> np.ndarray:
    return check_finite_array(name, a, last=2)


def ground_to_geodetic(XY_m, origin_m=GEODETIC_ORIGIN_M) -> np.ndarray:
    """Ground (X east, Y north), m, shape (..., 2) → geodetic (X north, Y east), m: X = X₀ + Y, Y = Y₀ + X."""
    a = _xy("XY_m", XY_m)
    o = np.asarray(origin_m, dtype=float).reshape(2)
    return np.stack([o[0] + a[..., 1], o[1] + a[..., 0]], axis=-1)


def geodetic_to_ground(XY_geo_m, origin_m=GEODETIC_ORIGIN_M) -> np.ndarray:
    """The inverse of :func:`ground_to_geodetic`: geodetic (X north, Y east) → ground (X east, Y north), m."""
    a = _xy("XY_geo_m", XY_geo_m)
    o = np.asarray(origin_m, dtype=float).reshape(2)
    return np.stack([a[..., 1] - o[1], a[..., 0] - o[0]], axis=-1)


def sheet_to_geodetic(xy_mm) -> np.ndarray:
    """A sheet's mathematical (x, y) → geodetic (x up, y right): the axes swapped, shape (..., 2).

    A free strip laid along the sheet's mathematical +x then runs along the
    geodetic +y (to the right, "east"), its left side up (+x, "north").
    """
    a = _xy("xy_mm", xy_mm)
    return a[..., ::-1].copy()


def direction_to_geodetic_deg(theta_rad) -> np.ndarray:
    """A mathematical direction (radians, counter-clockwise from +x) → geodetic α (degrees, clockwise from +x), 0 ≤ α < 360."""
    t = check_finite_array("theta_rad", theta_rad)
    return np.mod(90.0 - np.degrees(t), 360.0)


def geodetic_to_direction_rad(alpha_deg) -> np.ndarray:
    """The inverse of :func:`direction_to_geodetic_deg` (radians, in (−π, π])."""
    a = check_finite_array("alpha_deg", alpha_deg)
    t = np.radians(90.0 - a)
    out = np.arctan2(np.sin(t), np.cos(t))
    return out if np.ndim(out) else float(out)
