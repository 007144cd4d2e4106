"""Chapter 16's lab (article 000): the student's block for Lysenko's formula and their own 1 km sheet of the site.

* :func:`block_of` (task 16.1): K = 4 + (i mod 4) strips of n_s = 8 + (i mod 5) photos of the student's camera
  (f = 100 + 10i mm, 1:m with m = 12 000 + 100i, 18 cm frame, p_x = 60 %), the article's m = 16 points per
  photo and s = 3 images per point, and r = 3K control points (both ends and the middle of every strip).
* :func:`sheet_of` / :func:`sheet_data` (task 16.2): the 1 km × 1 km square with its south-west corner at
  X = 100 + 88i m, Y = 2500 + 250·(i mod 7) m on the site; the regular grid's step is the article's 7 mm on
  the student's photo, d = 0.007·m metres (84–153 m); the node heights carry the article's measured
  densification error, 12 cm RMS, drawn with the seed 1000 + i; 40 check points spread at random (seed i)
  over the sheet, none with an error within 1.5 mm of the 15 cm the task counts against.

The graded tasks are :mod:`aerophoto.tasks.ch16`.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import dem
from .. import geometry as g

__all__ = ["MP_MM", "POINTS_PER_PHOTO", "IMAGES_PER_POINT", "MZ_SHEET_M", "N_CHECK", "TOL_15_M", "Block", "block_of",
           "sheet_of", "SheetData", "sheet_data"]

#: the measurement-error term of Lysenko's formula, mm (the article's "0,25" read as 0.025 mm)
MP_MM = 0.025
POINTS_PER_PHOTO = 16
IMAGES_PER_POINT = 3
#: the node heights' error of task 16.2: the article's measured densification, m
MZ_SHEET_M = 0.12
N_CHECK = 40
#: the article's 15 cm
TOL_15_M = 0.15


@dataclass(frozen=True)
class Block:
    """The student's block for Lysenko's formula (task 16.1).

    Attributes
    ----------
    f_mm, m : the camera's focal length (mm) and the photo scale denominator
    frame_mm, px_percent : frame side l (mm) and forward overlap p_x (%)
    strips, per_strip : K and n_s
    n, points_per_photo, images_per_point, r : Lysenko's n, m, s, r
    mp_mm : the measurement-error term m_p, mm
    """

    f_mm: float
    m: float
    frame_mm: float
    px_percent: float
    strips: int
    per_strip: int
    n: int
    points_per_photo: int
    images_per_point: int
    r: int
    mp_mm: float

    @property
    def H_m(self) -> float:
        """H = f·m, m."""
        return g.flying_height_m(self.f_mm, self.m)

    @property
    def b_mm(self) -> float:
        """b = l·(1 − p_x/100), mm."""
        return self.frame_mm * (1.0 - self.px_percent / 100.0)

    @property
    def mz_m(self) -> float:
        """Lysenko's m_z, m."""
        return dem.lysenko_mz_m(self.H_m, self.b_mm, self.mp_mm, self.n, self.points_per_photo,
                                self.images_per_point, self.r)

    def table(self) -> pd.DataFrame:
        rows = [("focal length f", "mm", self.f_mm), ("photo scale 1:m", "", f"1:{self.m:.0f}"),
                ("frame l", "mm", self.frame_mm), ("forward overlap p_x", "%", self.px_percent),
                ("strips K × photos per strip", "", f"{self.strips} × {self.per_strip}"),
                ("photos in the block n", "", self.n), ("points per photo m", "", self.points_per_photo),
                ("images per point s", "", self.images_per_point), ("control points r", "", self.r),
                ("measurement-error term m_p", "mm", self.mp_mm)]
        return pd.DataFrame(rows, columns=["quantity", "unit", "value"]).set_index("quantity")


def block_of(v) -> Block:
    """Task 16.1's block for variant ``v`` (see the module notes)."""
    i = int(v.i)
    K, ns = 4 + i % 4, 8 + i % 5
    return Block(float(v.f_mm), float(v.m), float(v.frame_mm), float(v.px_percent), K, ns, K * ns,
                 POINTS_PER_PHOTO, IMAGES_PER_POINT, 3 * K, MP_MM)


def sheet_of(v) -> dem.Sheet:
    """The student's 1 km sheet of the site (see the module notes)."""
    i = int(v.i)
    return dem.Sheet(100.0 + 88.0 * i, 2500.0 + 250.0 * (i % 7), 1000.0)


@dataclass(frozen=True, eq=False)
class SheetData:
    """Task 16.2's data: the sheet, its DEMs and the check points (the reference solution's side).

    Attributes
    ----------
    sheet : :class:`aerophoto.dem.Sheet`
    spacing_m : the regular grid's step d, m
    grid, lines_dem : the regular DEM and the same with structural lines (:class:`aerophoto.dem.DEM`)
    points : DataFrame — X_m, Y_m, Z_geod_m (true), Z_grid_m, Z_lines_m (heights read from the DEMs)
    """

    sheet: dem.Sheet
    spacing_m: float
    grid: dem.DEM
    lines_dem: dem.DEM
    points: pd.DataFrame

    def errors(self, which: str) -> np.ndarray:
        col = {"grid": "Z_grid_m", "lines": "Z_lines_m"}[which]
        return (self.points[col] - self.points["Z_geod_m"]).to_numpy()


@functools.lru_cache(maxsize=8)
def _sheet_data(i: int, f_mm: float, m: float) -> SheetData:
    from ..site import get_site

    site = get_site()
    sheet = dem.Sheet(100.0 + 88.0 * i, 2500.0 + 250.0 * (i % 7), 1000.0)
    d = 0.007 * m
    lines = dem.structural_lines(site, sheet)
    grid = dem.grid_dem(site, sheet, d, mz_m=MZ_SHEET_M, seed=1000 + i)
    with_lines = dem.grid_with_lines(site, sheet, d, lines, mz_m=MZ_SHEET_M, seed=1000 + i)
    rng = np.random.default_rng(i)
    k = 3 * N_CHECK
    P = np.column_stack([sheet.X0_m + 20.0 + 960.0 * rng.random(k), sheet.Y0_m + 20.0 + 960.0 * rng.random(k)]).round(1)
    Zt = np.asarray(site.height(P[:, 0], P[:, 1]), dtype=float).round(3)
    Zg = grid.height(P[:, 0], P[:, 1]).round(3)
    Zl = with_lines.height(P[:, 0], P[:, 1]).round(3)
    # no error within a millimetre of the 15 cm the task counts against (no ties to round either way)
    clear = (np.abs(np.abs(Zl - Zt) - TOL_15_M) > 0.0015) & (np.abs(np.abs(Zg - Zt) - TOL_15_M) > 0.0015)
    use = np.flatnonzero(clear)[:N_CHECK]
    pts = pd.DataFrame({"X_m": P[use, 0], "Y_m": P[use, 1], "Z_geod_m": Zt[use], "Z_grid_m": Zg[use],
                        "Z_lines_m": Zl[use]}, index=pd.Index(np.arange(1, N_CHECK + 1), name="point"))
    return SheetData(sheet, d, grid, with_lines, pts)


def sheet_data(v) -> SheetData:
    """Task 16.2's data for variant ``v`` (cached)."""
    return _sheet_data(int(v.i), float(v.f_mm), float(v.m))
