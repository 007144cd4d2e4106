"""Plane geometry: 2-D transformations fitted to point pairs, and rays on a sheet.

Layer 1 of the package (beside :mod:`aerophoto.geometry`): pure numpy, no other
aerophoto module but the input checks.  Every chapter that lays prints on a
table, fits a photo to a plan or intersects directions drawn on a template uses
these functions:

=========================  ===========================================  ==============
transformation             x' = T(x)                                    pairs needed
=========================  ===========================================  ==============
:class:`Similarity2D`      s·R(θ)·x + t (rigid when s = 1)              2
:class:`Affine2D`          A·x + t                                      3, not collinear
:class:`Projective2D`      (H·[x, 1]) / (h₃·[x, 1]), 8 parameters       4, no 3 collinear
=========================  ===========================================  ==============

The fits are exact for the minimum number of pairs and least squares beyond
it; each returns the transformation, and :func:`fit` returns a :class:`Fit`
with the residuals (``dst − T(src)``) as well.  A projective transformation
is what maps a photo of flat ground onto the plan (guide §10, §12): the
mutual projective grids and the photo transformer realise it by hand.

Rays: :func:`intersect_rays` (least-squares point of k lines),
:func:`error_triangle` (three lines, guide §13 figure 23) and
:func:`resect_directions` (a direction template's centre and rotation from
known points, guide §7).

Units are whatever the caller uses (mm on photos and sheets, m on the ground);
angles in radians inside, degrees at the public surface where named ``_deg``.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np

from ._validate import check_finite_array, check_int_range, check_points, check_range

__all__ = [
    "Similarity2D",
    "Affine2D",
    "Projective2D",
    "Fit",
    "fit_similarity",
    "fit_affine",
    "fit_projective",
    "fit",
    "intersect_rays",
    "line_intersection",
    "error_triangle",
    "resect_directions",
]


# --------------------------------------------------------------------------- transformations
def _matrix3(name: str, value) -> np.ndarray:
    M = check_finite_array(name, value)
    if M.shape != (3, 3):
        raise ValueError(f"{name} has shape {M.shape}; expected the 3×3 homogeneous matrix")
    return M


@dataclass(frozen=True)
class Similarity2D:
    """A 2-D similarity x' = s·R(θ)·x + t, stored as a = s·cos θ, b = s·sin θ, t = (tx, ty).

    With s = 1 it is a rigid motion — how a contact print can be moved on the
    table (shift and turn, no rescaling).
    """

    a: float = 1.0
    b: float = 0.0
    tx: float = 0.0
    ty: float = 0.0

    def __post_init__(self):
        for name in ("a", "b", "tx", "ty"):
            object.__setattr__(self, name, check_range(name, getattr(self, name)))

    @classmethod
    def from_angle(cls, theta_deg: float = 0.0, t=(0.0, 0.0), scale: float = 1.0) -> "Similarity2D":
        th = math.radians(theta_deg)
        return cls(scale * math.cos(th), scale * math.sin(th), float(t[0]), float(t[1]))

    @property
    def scale(self) -> float:
        return math.hypot(self.a, self.b)

    @property
    def rotation_deg(self) -> float:
        return math.degrees(math.atan2(self.b, self.a))

    def apply(self, xy) -> np.ndarray:
        """Transform points, shape (..., 2) → (..., 2)."""
        p = np.asarray(xy, dtype=float)
        x, y = p[..., 0], p[..., 1]
        return np.stack([self.a * x - self.b * y + self.tx, self.b * x + self.a * y + self.ty], axis=-1)

    __call__ = apply

    def inverse(self) -> "Similarity2D":
        d = self.a * self.a + self.b * self.b
        if d == 0:
            raise ValueError("the similarity has scale 0 and no inverse")
        ia, ib = self.a / d, -self.b / d
        return Similarity2D(ia, ib, -(ia * self.tx - ib * self.ty), -(ib * self.tx + ia * self.ty))

    def compose(self, other: "Similarity2D") -> "Similarity2D":
        """``self ∘ other``: apply ``other`` first, then ``self``."""
        a = self.a * other.a - self.b * other.b
        b = self.b * other.a + self.a * other.b
        t = self.apply([other.tx, other.ty])
        return Similarity2D(a, b, float(t[0]), float(t[1]))

    def matrix(self) -> np.ndarray:
        """The 3×3 homogeneous matrix."""
        return np.array([[self.a, -self.b, self.tx], [self.b, self.a, self.ty], [0.0, 0.0, 1.0]])


@dataclass(frozen=True)
class Affine2D:
    """A 2-D affine transformation x' = A·x + t (6 parameters), stored as its 3×3 matrix."""

    M: np.ndarray = field(default_factory=lambda: np.eye(3))

    def __post_init__(self):
        object.__setattr__(self, "M", _matrix3("M", self.M))

    def apply(self, xy) -> np.ndarray:
        """Transform points, shape (..., 2) → (..., 2)."""
        p = np.asarray(xy, dtype=float)
        return p @ self.M[:2, :2].T + self.M[:2, 2]

    __call__ = apply

    def matrix(self) -> np.ndarray:
        return np.array(self.M, dtype=float)

    def inverse(self) -> "Affine2D":
        if abs(np.linalg.det(self.M[:2, :2])) < 1e-15:
            raise ValueError("the affine transformation is singular (determinant 0) and has no inverse")
        return Affine2D(np.linalg.inv(self.M))


@dataclass(frozen=True)
class Projective2D:
    """A 2-D projective transformation (homography), 8 parameters, normalised so that H[2, 2] = 1.

    x' = (h11 x + h12 y + h13) / (h31 x + h32 y + 1),  y' = (h21 x + h22 y + h23) / (h31 x + h32 y + 1).
    """

    H: np.ndarray = field(default_factory=lambda: np.eye(3))

    def __post_init__(self):
        object.__setattr__(self, "H", _matrix3("H", self.H))

    def apply(self, xy) -> np.ndarray:
        """Transform points, shape (..., 2) → (..., 2).  Points on the vanishing line give ±inf."""
        p = np.asarray(xy, dtype=float)
        w = p[..., 0] * self.H[2, 0] + p[..., 1] * self.H[2, 1] + self.H[2, 2]
        x = p[..., 0] * self.H[0, 0] + p[..., 1] * self.H[0, 1] + self.H[0, 2]
        y = p[..., 0] * self.H[1, 0] + p[..., 1] * self.H[1, 1] + self.H[1, 2]
        with np.errstate(divide="ignore", invalid="ignore"):
            return np.stack([x / w, y / w], axis=-1)

    __call__ = apply

    def matrix(self) -> np.ndarray:
        return np.array(self.H, dtype=float)

    def inverse(self) -> "Projective2D":
        if abs(np.linalg.det(self.H)) < 1e-15:
            raise ValueError("the projective transformation is singular and has no inverse")
        Hi = np.linalg.inv(self.H)
        return Projective2D(Hi / Hi[2, 2])


@dataclass(frozen=True)
class Fit:
    """A fitted transformation with its residuals.

    Attributes
    ----------
    transform : Similarity2D, Affine2D or Projective2D
    residuals : ndarray, shape (k, 2)
        ``dst − transform(src)``, in the units of ``dst``.
    """

    transform: object
    residuals: np.ndarray

    @property
    def residual_lengths(self) -> np.ndarray:
        """|residual| per pair, shape (k,)."""
        return np.hypot(self.residuals[:, 0], self.residuals[:, 1])

    @property
    def rms(self) -> float:
        """Root-mean-square residual length (0 for an exact fit)."""
        return float(np.sqrt(np.mean(self.residual_lengths**2)))

    @property
    def max_residual(self) -> float:
        return float(np.max(self.residual_lengths))


def _pairs(src, dst, need: int, what: str):
    P = check_points("src", src)
    Q = check_points("dst", dst)
    if P.shape != Q.shape:
        raise ValueError(f"src has {len(P)} points and dst {len(Q)}; give one dst point per src point")
    if len(P) < need:
        raise ValueError(f"{len(P)} point pair(s) given; {what} needs at least {need}")
    for name, X in (("src", P), ("dst", Q)):
        d = np.hypot(*(X[:, None, :] - X[None, :, :]).transpose(2, 0, 1))
        iu = np.triu_indices(len(X), 1)
        scale = max(float(np.max(np.abs(X))), 1.0)
        if np.any(d[iu] <= 1e-12 * scale):
            i, j = (int(a[np.argmin(d[iu])]) for a in iu)
            raise ValueError(f"{name} points {i} and {j} coincide; every point of a pair set must be distinct")
    return P, Q


def _collinear(X: np.ndarray, tol: float = 1e-9) -> bool:
    c = X - X.mean(axis=0)
    s = np.linalg.svd(c, compute_uv=False)
    return s[-1] <= tol * max(s[0], 1e-300)


def fit_similarity(src, dst, *, scale: bool = False) -> Similarity2D:
    """Least-squares 2-D motion taking ``src`` points onto ``dst`` (Umeyama's method).

    Parameters
    ----------
    src, dst : array_like, shape (k, 2), k ≥ 2
        Corresponding points (e.g. the same detail on two prints), any unit.
    scale : bool
        False (default): a rigid motion, rotation + shift, as when a print is
        laid on its neighbour; True: a similarity with a free scale.

    Returns
    -------
    Similarity2D minimising Σ|T(src) − dst|².  For a rigid fit to two points
    the leftover misfit is shared equally between them.
    """
    P = check_points("src", src)
    Q = check_points("dst", dst)
    if P.shape != Q.shape:
        raise ValueError(f"src has shape {P.shape} and dst {Q.shape}; they must match, shape (k, 2)")
    if len(P) < 2:
        raise ValueError(f"{len(P)} point pair(s) given; the valid range is at least 2 pairs")
    mp, mq = P.mean(axis=0), Q.mean(axis=0)
    p, q = P - mp, Q - mq
    sxx = float(np.sum(p * p))
    if sxx == 0:
        raise ValueError("the source points coincide; at least two distinct points are needed")
    # for 2-D the optimal rotation comes from the complex cross-correlation
    c = float(np.sum(p[:, 0] * q[:, 0] + p[:, 1] * q[:, 1]))
    s_ = float(np.sum(p[:, 0] * q[:, 1] - p[:, 1] * q[:, 0]))
    th = math.atan2(s_, c)
    k = math.hypot(c, s_) / sxx if scale else 1.0
    a, b = k * math.cos(th), k * math.sin(th)
    t = mq - np.array([a * mp[0] - b * mp[1], b * mp[0] + a * mp[1]])
    return Similarity2D(a, b, float(t[0]), float(t[1]))


def fit_affine(src, dst) -> Affine2D:
    """Least-squares affine transformation taking ``src`` onto ``dst`` (k ≥ 3 pairs, not all collinear)."""
    P, Q = _pairs(src, dst, 3, "an affine transformation (6 parameters)")
    if _collinear(P) or _collinear(Q):
        raise ValueError("the points lie on one line; an affine transformation needs three points not on a line")
    A = np.column_stack([P, np.ones(len(P))])
    sol, *_ = np.linalg.lstsq(A, Q, rcond=None)
    M = np.eye(3)
    M[:2, :] = sol.T
    return Affine2D(M)


def _normaliser(X: np.ndarray) -> np.ndarray:
    """Hartley's normalisation: centroid to the origin, mean distance √2."""
    c = X.mean(axis=0)
    d = float(np.mean(np.hypot(*(X - c).T)))
    s = math.sqrt(2.0) / d
    return np.array([[s, 0.0, -s * c[0]], [0.0, s, -s * c[1]], [0.0, 0.0, 1.0]])


def fit_projective(src, dst) -> Projective2D:
    """Projective transformation taking ``src`` onto ``dst``: exact for 4 pairs, least squares (DLT) beyond.

    Parameters
    ----------
    src, dst : array_like, shape (k, 2), k ≥ 4
        Corresponding points; no three of the first four — and not all of
        them — on one line (guide §10, §12: four control points spread over
        the photo).

    Raises ValueError naming the problem for fewer than four pairs, repeated
    points, three collinear points among four, or a degenerate solution.
    """
    P, Q = _pairs(src, dst, 4, "a projective transformation (8 parameters)")
    for name, X in (("src", P), ("dst", Q)):
        if _collinear(X):
            raise ValueError(f"the {name} points lie on one line; a projective transformation needs four points, "
                             "no three of them on a line")
        if len(X) == 4:
            for drop in range(4):
                tri = np.delete(X, drop, axis=0)
                if _collinear(tri):
                    which = [i for i in range(4) if i != drop]
                    raise ValueError(f"{name} points {which} lie on one line; of four points no three may be collinear")
    Tp, Tq = _normaliser(P), _normaliser(Q)
    ph = np.column_stack([P, np.ones(len(P))]) @ Tp.T
    qh = np.column_stack([Q, np.ones(len(Q))]) @ Tq.T
    rows = []
    for (x, y, _), (u, v, _) in zip(ph, qh):
        rows.append([-x, -y, -1, 0, 0, 0, u * x, u * y, u])
        rows.append([0, 0, 0, -x, -y, -1, v * x, v * y, v])
    _, s, vt = np.linalg.svd(np.asarray(rows, dtype=float))
    Hn = vt[-1].reshape(3, 3)
    H = np.linalg.inv(Tq) @ Hn @ Tp
    if abs(H[2, 2]) < 1e-15 or not np.all(np.isfinite(H)):
        raise ValueError("the point pairs do not determine a projective transformation (degenerate configuration)")
    return Projective2D(H / H[2, 2])


_FITTERS = {"similarity": lambda s, d: fit_similarity(s, d, scale=True),
            "rigid": lambda s, d: fit_similarity(s, d, scale=False),
            "affine": fit_affine, "projective": fit_projective}


def fit(kind: str, src, dst) -> Fit:
    """Fit a transformation of ``kind`` ("rigid", "similarity", "affine", "projective") and return it with residuals."""
    if kind not in _FITTERS:
        raise ValueError(f"kind = {kind!r} is not valid; expected one of {sorted(_FITTERS)}")
    T = _FITTERS[kind](src, dst)
    P = check_points("src", src)
    Q = check_points("dst", dst)
    return Fit(T, Q - T.apply(P))


# --------------------------------------------------------------------------- rays on a sheet
def _u(a):
    a = np.asarray(a, dtype=float)
    return np.stack([np.cos(a), np.sin(a)], axis=-1)


def _cross(a, b):
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


def intersect_rays(origins, angles_rad) -> np.ndarray:
    """The point nearest (least squares) to two or more lines, each through an origin at an angle.

    Parameters
    ----------
    origins : array_like, shape (k, 2)
    angles_rad : array_like, shape (k,)

    Returns
    -------
    ndarray, shape (2,)
        Minimises the sum of squared perpendicular distances; for two rays it
        is their intersection.  ValueError if the lines are (nearly) parallel.
    """
    C = check_points("origins", origins)
    a = check_finite_array("angles_rad", angles_rad).reshape(-1)
    u = _u(a).reshape(-1, 2)
    if len(C) < 2:
        raise ValueError(f"origins has {len(C)} ray(s); an intersection needs at least 2")
    if len(u) != len(C):
        raise ValueError(f"origins has {len(C)} points but angles_rad {len(u)} angles; give one angle per origin")
    Nmat = np.eye(2)[None] - u[:, :, None] * u[:, None, :]
    A = Nmat.sum(axis=0)
    b = np.einsum("kij,kj->i", Nmat, C)
    if abs(np.linalg.det(A)) < 1e-12:
        raise ValueError("the rays are parallel: the point cannot be intersected")
    return np.linalg.solve(A, b)


def line_intersection(Ca, ua, Cb, ub) -> np.ndarray:
    """Intersection, shape (2,), of the lines Ca + s·ua and Cb + t·ub (each argument a 2-vector).

    ValueError for parallel lines (no intersection) or a zero direction.
    """
    Ca, ua, Cb, ub = (check_points(n, v).reshape(-1) for n, v in (("Ca", Ca), ("ua", ua), ("Cb", Cb), ("ub", ub)))
    for n, v in (("Ca", Ca), ("ua", ua), ("Cb", Cb), ("ub", ub)):
        if v.shape != (2,):
            raise ValueError(f"{n} has {len(v) // 2} points; expected one 2-vector (x, y)")
    for n, v in (("ua", ua), ("ub", ub)):
        if not v.any():
            raise ValueError(f"{n} = (0, 0) is not a direction; expected a non-zero vector")
    p = _line_intersection(Ca, ua, Cb, ub)
    if not np.isfinite(p).all():
        raise ValueError("the lines are parallel (ua ∥ ub): they have no intersection")
    return p


def _line_intersection(Ca, ua, Cb, ub) -> np.ndarray:
    den = _cross(ua, ub)
    if abs(den) < 1e-15 * max(1.0, float(np.abs(ua).max() * np.abs(ub).max())):
        return np.array([np.nan, np.nan])
    s = _cross(Cb - Ca, ub) / den
    return Ca + s * ua


def error_triangle(origins, angles_rad):
    """The error triangle (треугольник погрешностей) of three rays (guide §13, figure 23).

    Returns
    -------
    vertices : ndarray, shape (3, 2)
        Intersections of rays (0, 1), (1, 2) and (0, 2).
    sides : ndarray, shape (3,)
        The triangle's sides: on ray 1 (between its intersections with 0
        and 2), on ray 2, on ray 0 — all zero when the three meet in a point.
    """
    C = check_points("origins", origins)
    if len(C) != 3:
        raise ValueError(f"{len(C)} origins given; an error triangle needs exactly 3 rays")
    a = check_finite_array("angles_rad", angles_rad).reshape(-1)
    if a.shape != (3,):
        raise ValueError(f"angles_rad has {a.size} value(s); an error triangle needs exactly 3 directions")
    u = _u(a).reshape(3, 2)
    v01 = _line_intersection(C[0], u[0], C[1], u[1])
    v12 = _line_intersection(C[1], u[1], C[2], u[2])
    v02 = _line_intersection(C[0], u[0], C[2], u[2])
    V = np.array([v01, v12, v02])
    if not np.isfinite(V).all():
        raise ValueError("two of the rays are parallel (angles_rad): they do not form a triangle")
    sides = np.array([np.hypot(*(v01 - v12)), np.hypot(*(v12 - v02)), np.hypot(*(v02 - v01))])
    return V, sides


def resect_directions(angles_rad, known_xy, *, line=None, x0=None, iterations: int = 20):
    """Resection (обратная засечка) of a direction template: its centre and rotation.

    Finds the centre C and rotation θ that make the template's rays (angle
    φ_j + θ from C) pass as near as possible (least squares of perpendicular
    distances) through the known points K_j — guide §7: the first and last
    templates on their control points, the inner ones on tie points, a
    centre and the initial direction.

    Parameters
    ----------
    angles_rad : array_like, shape (k,)
        Directions φ_j measured on the template, radians.
    known_xy : array_like, shape (k, 2)
        The points those rays must pass through (plan or strip mm).
    line : tuple (point (2,), angle_rad), optional
        An initial direction (начальное направление) drawn on the sheet: C
        must also lie on this line (one more observation).
    x0 : (Cx, Cy, θ), optional
        Starting values; by default a linear solution (needs k ≥ 3).
    iterations : int, 1 ≤ iterations ≤ 200
        Most Gauss–Newton steps.

    Returns
    -------
    C : ndarray (2,), theta_rad : float, residuals_mm : ndarray (k,) (signed
    perpendicular distances of the known points from their rays; the line's
    residual is appended last when ``line`` is given).
    """
    phi = check_finite_array("angles_rad", angles_rad).ravel()
    K = check_points("known_xy", known_xy)
    iterations = check_int_range("iterations", iterations, 1, 200)
    k = len(phi)
    if len(K) != k:
        raise ValueError(f"angles_rad has {k} directions but known_xy {len(K)} points; "
                         "give one known point per direction")
    n_obs = k + (1 if line is not None else 0)
    if n_obs < 3:
        raise ValueError(f"{n_obs} observations; a resection needs at least 3 (centre and rotation are 3 unknowns)")
    if line is not None:
        L0 = check_points("line point", line[0]).reshape(2)
        la = float(line[1])
        if not math.isfinite(la):
            raise ValueError(f"line angle = {la} is not a finite number")
    if x0 is None:
        if k < 3:
            raise ValueError(f"{k} known points; the starting values need at least 3 (or give x0)")
        # linear solution in (cos θ, sin θ, A, B): c(s_j Kx − c_j Ky) + s(c_j Kx + s_j Ky) − s_j A − c_j B = 0
        cj, sj = np.cos(phi), np.sin(phi)
        A = np.column_stack([sj * K[:, 0] - cj * K[:, 1], cj * K[:, 0] + sj * K[:, 1], -sj, -cj])
        _, _, vt = np.linalg.svd(A)
        c, s, a, b = vt[-1]
        nrm = math.hypot(c, s)
        if nrm == 0:
            raise ValueError("the known points do not determine the template's rotation (degenerate configuration)")
        c, s, a, b = c / nrm, s / nrm, a / nrm, b / nrm
        x = np.array([c * a + s * b, s * a - c * b, math.atan2(s, c)])
    else:
        x = np.asarray(x0, dtype=float).reshape(3).copy()
        if not np.all(np.isfinite(x)):
            raise ValueError("x0 contains a value that is not finite")
    for _ in range(iterations):
        psi = phi + x[2]
        u = _u(psi)
        d = K - x[:2]
        r = _cross(u, d)
        J = np.column_stack([u[:, 1], -u[:, 0], -np.sum(u * d, axis=1)])
        if line is not None:
            w = np.array([math.cos(la), math.sin(la)])
            r = np.append(r, _cross(w, x[:2] - L0))
            J = np.vstack([J, [-w[1], w[0], 0.0]])
        dx, *_ = np.linalg.lstsq(J, -r, rcond=None)
        x = x + dx
        if np.max(np.abs(dx)) < 1e-12:
            break
    psi = phi + x[2]
    u = _u(psi)
    if np.sum(np.sum(u * (K - x[:2]), axis=1)) < 0:  # lines, not rays: turn the template to face its points
        x[2] += math.pi
        psi = phi + x[2]
        u = _u(psi)
    x[2] = math.remainder(x[2], 2.0 * math.pi)
    r = _cross(u, K - x[:2])
    if line is not None:
        r = np.append(r, _cross(np.array([math.cos(la), math.sin(la)]), x[:2] - L0))
    return x[:2].copy(), float(x[2]), r
