"""Mutual projective grids (взаимно-проектные сетки) on a photo and a plan, and transfer cell by cell (guide §10).

Four control points (трансформационные точки) 1, 2, 3, 4, in order round the
working area, make a quadrilateral on the photo and one on the plan.  Each is
covered by a grid of n × n cells; a detail seen in one photo cell is drawn
into the plan cell with the same number, at the same place inside it
(visually or with a proportional compass).  How the grid is drawn decides
whether the cells really correspond:

``"central"`` — central directions (центральные направления), exact
    The grid lines that join side 1–2 to side 4–3 all pass through the point
    where the other two sides, 1–4 and 2–3, meet (their vanishing point); the
    lines that join 1–4 to 2–3 pass through the meeting point of 1–2 and 4–3.
    Each family is a pencil of lines through one centre.  The construction
    by diagonals (:func:`diagonal_grid`: the diagonals' crossing and the two
    centres halve the quadrilateral, again and again) draws exactly this
    grid.  It is the image of a regular grid under the projective
    transformation of the unit square onto the quadrilateral
    (:func:`projective_grid`), so the photo's and the plan's grids are
    images of each other: cell (j, i) maps onto cell (j, i).  Transferring
    inside a cell by proportion is a bilinear guess of a projective map over
    a small cell: its error falls as 1/n².

``"proportional"`` — proportional division (пропорциональное деление), the guide's steps 3–4
    Every side is divided into n equal parts and the opposite division
    points are joined (:func:`proportional_grid`).  Equal division is not
    preserved by a central projection, so unless the quadrilateral is a
    parallelogram on both sides (no perspective), the nodes of the two
    grids are *not* images of each other.  Transfer cell by cell then
    reproduces the bilinear map of the photo's quadrilateral onto the
    plan's, whatever n is: the error does not fall as the grid is refined.
    It is small when the tilt and the spread of the four points are small.

Conventions
-----------
Corners are given as an array (4, 2) in the order 1, 2, 3, 4 round the
quadrilateral (either sense), in any unit (mm on photo and plan).  Grid
coordinates: u runs along side 1→2 (0 at 1, 1 at 2), v along side 1→4.
A grid is an array ``nodes`` of shape (n + 1, n + 1, 2): ``nodes[j, i]`` is
the node at u = i/n, v = j/n; cell (j, i) has the corners ``nodes[j, i]``,
``nodes[j, i+1]``, ``nodes[j+1, i+1]``, ``nodes[j+1, i]``.  Rows j count from
side 1–2 towards side 4–3, columns i from side 1–4 towards side 2–3.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import _validate as V
from .. import plane
from .._validate import check_int_range, check_points

__all__ = [
    "METHODS",
    "MAX_DIVISIONS",
    "UNIT_SQUARE",
    "check_quadrilateral",
    "unit_square_map",
    "vanishing_points",
    "proportional_grid",
    "projective_grid",
    "diagonal_grid",
    "grid",
    "bilinear",
    "locate",
    "transfer",
    "place",
    "GridPair",
    "grid_pair",
    "transfer_study",
]

#: the ways of drawing the grids: key → description
METHODS = {"central": "central directions (exact projective grids)",
           "proportional": "proportional division (equal parts; the guide's steps 3–4)"}
#: most divisions per side of a grid (work-size guard)
MAX_DIVISIONS = 256
#: the unit square's corners in the order 1, 2, 3, 4 (u along 1→2, v along 1→4)
UNIT_SQUARE = np.array([[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]])


def check_quadrilateral(name: str, corners) -> np.ndarray:
    """Four corners (4, 2) of a convex quadrilateral in order round it, as a float array; else ValueError.

    Rejects repeated corners, three corners on one line, a self-crossing
    (bow-tie) order and a non-convex shape, naming what is wrong.
    """
    V.check_type("name", name, str)
    Q = check_points(name, corners)
    if len(Q) != 4:
        raise ValueError(f"{name} has {len(Q)} point(s); a quadrilateral needs exactly 4 corners in order 1, 2, 3, 4")
    scale = max(float(np.ptp(Q, axis=0).max()), 1e-300)
    for a in range(4):
        for b in range(a + 1, 4):
            if np.hypot(*(Q[a] - Q[b])) <= 1e-9 * scale:
                raise ValueError(f"{name}: corners {a + 1} and {b + 1} coincide; the four corners must be distinct")
    cross = []
    for k in range(4):
        d1 = Q[(k + 1) % 4] - Q[k]
        d2 = Q[(k + 2) % 4] - Q[(k + 1) % 4]
        cross.append(d1[0] * d2[1] - d1[1] * d2[0])
    cross = np.array(cross)
    tiny = 1e-9 * scale * scale
    if np.any(np.abs(cross) <= tiny):
        k = int(np.argmin(np.abs(cross)))
        which = [k % 4 + 1, (k + 1) % 4 + 1, (k + 2) % 4 + 1]
        raise ValueError(f"{name}: corners {which} lie on one line; of four control points no three may be collinear")
    if not (np.all(cross > 0) or np.all(cross < 0)):
        raise ValueError(f"{name}: the corners do not go round a convex quadrilateral in order 1, 2, 3, 4 "
                         "(the sides cross, or one corner lies inside the triangle of the others)")
    return Q


def unit_square_map(corners) -> plane.Projective2D:
    """The projective transformation taking the unit square's corners (u, v) onto ``corners`` 1, 2, 3, 4."""
    Q = check_quadrilateral("corners", corners)
    return plane.fit_projective(UNIT_SQUARE, Q)


# --------------------------------------------------------------------------- homogeneous helpers
def _cross2(a, b) -> float:
    """z-component of the cross product of two 2-D vectors."""
    return float(a[0] * b[1] - a[1] * b[0])


def _h(p) -> np.ndarray:
    p = np.asarray(p, dtype=float)
    return np.concatenate([p, np.ones(p.shape[:-1] + (1,))], axis=-1)


def _join(p, q) -> np.ndarray:
    """The line through two homogeneous points (or the point on two homogeneous lines), scaled to unit length."""
    r = np.cross(p, q)
    n = float(np.linalg.norm(r))
    return r / n if n > 0 else r


def _e(p) -> np.ndarray:
    """A finite homogeneous point back to (x, y)."""
    return p[..., :2] / p[..., 2:3]


def vanishing_points(corners) -> tuple:
    """The centres of the two pencils of grid lines, as homogeneous points (3,).

    Returns ``(V_u, V_v)``: V_u = where lines 1–2 and 4–3 meet (the lines
    v = const pass through it), V_v = where 1–4 and 2–3 meet (the lines
    u = const pass through it).  A third coordinate 0 means the two sides
    are parallel (the centre lies at infinity, in that direction).
    """
    Q = _h(check_quadrilateral("corners", corners))
    Vu = _join(_join(Q[0], Q[1]), _join(Q[3], Q[2]))
    Vv = _join(_join(Q[0], Q[3]), _join(Q[1], Q[2]))
    scale = max(float(np.abs(Q[:, :2]).max()), 1.0)
    out = []
    for V in (Vu, Vv):
        V = V / (np.hypot(V[0], V[1]) or 1.0)
        if abs(V[2]) * scale < 1e-12:
            V[2] = 0.0
        out.append(V)
    return tuple(out)


# --------------------------------------------------------------------------- the grids
@V.checked(corners=V.shape(4, 2), u=V.values(), v=V.values())
def bilinear(corners, u, v) -> np.ndarray:
    """Points at (u, v) of the bilinear map of the unit square onto ``corners`` (4, 2): shape (..., 2).

    B(u, v) = (1−u)(1−v)·P1 + u(1−v)·P2 + u·v·P3 + (1−u)·v·P4; lines u = const
    and v = const are straight — the grid of proportional division.
    """
    V.check_broadcast(u=u, v=v)
    Q = np.asarray(corners, dtype=float)
    u = np.asarray(u, dtype=float)[..., None]
    v = np.asarray(v, dtype=float)[..., None]
    return (1 - u) * (1 - v) * Q[0] + u * (1 - v) * Q[1] + u * v * Q[2] + (1 - u) * v * Q[3]


def _regular(n: int):
    t = np.arange(n + 1) / n
    return np.meshgrid(t, t)  # U[j, i] = i/n, V[j, i] = j/n


def proportional_grid(corners, n: int) -> np.ndarray:
    """The grid of proportional division: every side in n equal parts, opposite points joined; (n+1, n+1, 2)."""
    Q = check_quadrilateral("corners", corners)
    n = check_int_range("n", n, 1, MAX_DIVISIONS)
    U, V = _regular(n)
    return bilinear(Q, U, V)


def projective_grid(corners, n: int) -> np.ndarray:
    """The grid of central directions: the image of a regular n × n grid under the unit square's projective map.

    Its lines u = i/n all pass through the vanishing point V_v, the lines
    v = j/n through V_u (:func:`vanishing_points`).  Shape (n+1, n+1, 2).
    """
    Q = check_quadrilateral("corners", corners)
    n = check_int_range("n", n, 1, MAX_DIVISIONS)
    U, V = _regular(n)
    T = plane.fit_projective(UNIT_SQUARE, Q)
    out = T.apply(np.stack([U, V], axis=-1))
    out[0, 0], out[0, -1], out[-1, -1], out[-1, 0] = Q  # exact corners
    return out


def diagonal_grid(corners, levels: int) -> np.ndarray:
    """The grid of central directions drawn as a draughtsman would: by diagonals, halving again and again.

    Each quadrilateral is split in four by two lines through the crossing O
    of its diagonals: one through O and V_v (the meeting point of sides 1–4
    and 2–3; for parallel sides, parallel to them), one through O and V_u.
    ``levels`` halvings give n = 2**levels cells per side.  Only ruler
    constructions (lines through two points, crossings of two lines) are
    used; the nodes equal :func:`projective_grid` (n = 2**levels) to
    rounding.  Shape (n+1, n+1, 2).
    """
    Q = check_quadrilateral("corners", corners)
    levels = check_int_range("levels", levels, 0, 8)
    n = 2**levels
    H = np.full((n + 1, n + 1, 3), np.nan)
    H[0, 0], H[0, n], H[n, n], H[n, 0] = _h(Q)

    def split(j0, i0, size):
        if size == 1:
            return
        A, B, C, D = H[j0, i0], H[j0, i0 + size], H[j0 + size, i0 + size], H[j0 + size, i0]
        O = _join(_join(A, C), _join(B, D))
        Vu = _join(_join(A, B), _join(D, C))
        Vv = _join(_join(A, D), _join(B, C))
        lu = _join(O, Vv)  # the line u = mid, through the centre of the pencil of u-lines
        lv = _join(O, Vu)
        h = size // 2
        H[j0, i0 + h] = _join(lu, _join(A, B))
        H[j0 + size, i0 + h] = _join(lu, _join(D, C))
        H[j0 + h, i0] = _join(lv, _join(A, D))
        H[j0 + h, i0 + size] = _join(lv, _join(B, C))
        H[j0 + h, i0 + h] = O
        for dj in (0, h):
            for di in (0, h):
                split(j0 + dj, i0 + di, h)

    split(0, 0, n)
    return _e(H)


def grid(corners, n: int, method: str = "central") -> np.ndarray:
    """The n × n grid over ``corners`` by ``method`` (:data:`METHODS`): nodes (n+1, n+1, 2)."""
    if method == "central":
        return projective_grid(corners, n)
    if method == "proportional":
        return proportional_grid(corners, n)
    raise ValueError(f"method = {method!r} is not valid; expected one of {sorted(METHODS)}")


# --------------------------------------------------------------------------- locating and transferring
def _cells(nodes):
    """Corners of every cell, shape (n·n, 4, 2), in the order (j, i) row-major."""
    P1 = nodes[:-1, :-1]
    P2 = nodes[:-1, 1:]
    P3 = nodes[1:, 1:]
    P4 = nodes[1:, :-1]
    return np.stack([P1, P2, P3, P4], axis=-2).reshape(-1, 4, 2)


def _inverse_bilinear(C, xy, iterations: int = 12):
    """(s, t) of points ``xy`` (k, 2) in every cell ``C`` (c, 4, 2) by Newton's method: shapes (k, c)."""
    P = xy[:, None, :]
    P1, P2, P3, P4 = (C[None, :, k, :] for k in range(4))
    s = np.full(P.shape[:2], 0.5)
    t = np.full(P.shape[:2], 0.5)
    a = P2 - P1
    b = P4 - P1
    c = P1 - P2 + P3 - P4
    for _ in range(iterations):
        F = P1 + s[..., None] * a + t[..., None] * b + (s * t)[..., None] * c - P
        Js = a + t[..., None] * c
        Jt = b + s[..., None] * c
        det = Js[..., 0] * Jt[..., 1] - Js[..., 1] * Jt[..., 0]
        det = np.where(np.abs(det) < 1e-300, 1e-300, det)
        ds = (F[..., 0] * Jt[..., 1] - F[..., 1] * Jt[..., 0]) / det
        dt = (Js[..., 0] * F[..., 1] - Js[..., 1] * F[..., 0]) / det
        s = s - ds
        t = t - dt
        if float(np.max(np.abs(ds)) + np.max(np.abs(dt))) < 1e-13:
            break
    return s, t


@V.checked(xy=V.points(2, min_points=1))
def locate(nodes, xy) -> pd.DataFrame:
    """Which cell of a grid each point lies in, and where inside it.

    Parameters
    ----------
    nodes : array (n+1, n+1, 2)
        A grid (:func:`grid`).
    xy : array_like (k, 2)
        Points in the grid's units.

    Returns
    -------
    DataFrame with, per point: ``row`` j and ``col`` i of the cell (0-based,
    rows from side 1–2, columns from side 1–4), ``s`` and ``t`` (its place in
    the cell: 0…1 along the cell's side 1→2 and 1→4) and ``inside`` (False
    for a point outside the grid: it is placed by extending the nearest
    edge cell).
    """
    N = check_finite_array_nodes(nodes)
    P = check_points("xy", xy)
    n = N.shape[0] - 1
    C = _cells(N)
    s, t = _inverse_bilinear(C, P)
    # distance of (s, t) from the unit square: 0 inside the cell
    ds = np.maximum(0.0, np.maximum(-s, s - 1.0))
    dt = np.maximum(0.0, np.maximum(-t, t - 1.0))
    out_of = np.hypot(ds, dt)
    out_of = np.where(np.isfinite(out_of), out_of, np.inf)
    k = np.argmin(out_of, axis=1)
    idx = np.arange(len(P))
    row, col = np.divmod(k, n)
    return pd.DataFrame({"row": row.astype(int), "col": col.astype(int), "s": s[idx, k], "t": t[idx, k],
                         "inside": out_of[idx, k] <= 1e-9})


def check_finite_array_nodes(nodes, name: str = "nodes") -> np.ndarray:
    """A grid's nodes as a float array (n+1, n+1, 2) with n ≥ 1; else ValueError naming ``name``."""
    from .._validate import check_finite_array

    N = check_finite_array(name, nodes, ndim=3, last=2)
    if N.shape[0] != N.shape[1] or N.shape[0] < 2:
        raise ValueError(f"{name} has shape {N.shape}; a grid has shape (n+1, n+1, 2) with n ≥ 1")
    return N


@V.checked(xy=V.points(2, min_points=1))
def transfer(nodes_from, nodes_to, xy) -> np.ndarray:
    """Carry points cell by cell from one grid to the other (guide §10 step 4): shape (k, 2).

    Each point goes into the cell with the same (row, col), at the same
    proportional place (s, t) inside it — what a proportional compass does.
    """
    A = check_finite_array_nodes(nodes_from, "nodes_from")
    B = check_finite_array_nodes(nodes_to, "nodes_to")
    if A.shape != B.shape:
        raise ValueError(f"the grids have shapes {A.shape} and {B.shape}; cells correspond only on grids of one size")
    return place(B, locate(A, xy))


@V.checked(loc=pd.DataFrame)
def place(nodes, loc: pd.DataFrame) -> np.ndarray:
    """Points at the cells and in-cell places ``loc`` (from :func:`locate` on another grid) of a grid: (k, 2)."""
    B = check_finite_array_nodes(nodes)
    j, i = loc["row"].to_numpy(), loc["col"].to_numpy()
    if len(j) and (j.max() >= B.shape[0] - 1 or i.max() >= B.shape[1] - 1):
        raise ValueError(f"loc names a cell beyond the grid's {B.shape[0] - 1} × {B.shape[1] - 1} cells")
    s, t = loc["s"].to_numpy()[:, None], loc["t"].to_numpy()[:, None]
    return ((1 - s) * (1 - t) * B[j, i] + s * (1 - t) * B[j, i + 1] + s * t * B[j + 1, i + 1]
            + (1 - s) * t * B[j + 1, i])


# --------------------------------------------------------------------------- a pair of grids
@dataclass(frozen=True)
class GridPair:
    """Grids on the photo and on the plan built from the same four control points (guide §10 steps 1–4).

    Attributes
    ----------
    photo_corners, plan_corners : ndarray (4, 2)
        The control points 1–4 on the photo (mm) and on the plan (mm).
    n : int
        Cells per side.
    method : str
        ``"central"`` or ``"proportional"`` (:data:`METHODS`).
    photo_nodes, plan_nodes : ndarray (n+1, n+1, 2)
        The two grids.
    exact : :class:`aerophoto.plane.Projective2D`
        The projective transformation photo → plan fixed by the four points.
    """

    photo_corners: np.ndarray
    plan_corners: np.ndarray
    n: int
    method: str
    photo_nodes: np.ndarray
    plan_nodes: np.ndarray
    exact: plane.Projective2D

    def transfer(self, xy_photo_mm) -> np.ndarray:
        """Photo points → plan, cell by cell (the guide's way); (k, 2) plan mm."""
        return transfer(self.photo_nodes, self.plan_nodes, xy_photo_mm)

    def exact_transfer(self, xy_photo_mm) -> np.ndarray:
        """Photo points → plan by the exact projective transformation; (k, 2) plan mm."""
        return self.exact.apply(check_points("xy_photo_mm", xy_photo_mm))

    def transfer_error(self, xy_photo_mm) -> np.ndarray:
        """Cell-by-cell minus exact, (k, 2) plan mm."""
        return self.transfer(xy_photo_mm) - self.exact_transfer(xy_photo_mm)

    def node_error(self) -> np.ndarray:
        """|plan node − exact image of the photo node|, (n+1, n+1), mm: 0 for central directions."""
        return np.hypot(*np.moveaxis(self.exact.apply(self.photo_nodes) - self.plan_nodes, -1, 0))


def grid_pair(photo_corners, plan_corners, n: int, method: str = "central") -> GridPair:
    """Build the two grids of ``method`` with n cells per side on the photo's and the plan's four points."""
    P = check_quadrilateral("photo_corners", photo_corners)
    Q = check_quadrilateral("plan_corners", plan_corners)
    cp = _cross2(P[1] - P[0], P[3] - P[0])
    cq = _cross2(Q[1] - Q[0], Q[3] - Q[0])
    if np.sign(cp) != np.sign(cq):
        raise ValueError("photo_corners and plan_corners go round in opposite senses; a photo (positive) and its "
                         "plan have the same orientation — check the order of the points or a mirrored axis")
    return GridPair(P, Q, check_int_range("n", n, 1, MAX_DIVISIONS), method, grid(P, n, method), grid(Q, n, method),
                    plane.fit_projective(P, Q))


@V.checked(ns=V.sequence(V.whole(1, 64), min_len=1))
def transfer_study(photo_corners, plan_corners, ns=(1, 2, 4, 8, 16, 32), *, n_points: int = 400,
                   seed: int = 0) -> pd.DataFrame:
    """The error of cell-by-cell transfer against the exact projective map, as the grid is refined.

    Random points inside the photo quadrilateral (uniform in its unit-square
    coordinates, seeded) are transferred with both methods for each n.

    Returns
    -------
    DataFrame indexed by n with columns ``central max, mm``, ``central RMS, mm``,
    ``proportional max, mm``, ``proportional RMS, mm`` (plan mm).
    """
    n_points = check_int_range("n_points", n_points, 1, 100000)
    rng = np.random.default_rng(check_int_range("seed", seed, 0, 2**32 - 1))
    uv = rng.uniform(0.0, 1.0, size=(n_points, 2))
    P = check_quadrilateral("photo_corners", photo_corners)
    xy = unit_square_map(P).apply(uv)
    rows = []
    for n in ns:
        row = {"n": int(n)}
        for method in ("central", "proportional"):
            e = np.hypot(*grid_pair(P, plan_corners, n, method).transfer_error(xy).T)
            row[f"{method} max, mm"] = float(e.max())
            row[f"{method} RMS, mm"] = float(np.sqrt(np.mean(e**2)))
        rows.append(row)
    return pd.DataFrame(rows).set_index("n")
