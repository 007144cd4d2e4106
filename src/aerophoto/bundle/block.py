"""What a block adjustment works from: the photo measurements, the control, and their a priori weights.

:class:`Measurements` holds one block as arrays: the photos (numbers, strips,
order in the strip), the ground points (ids and kinds) and the image
observations (which photo, which point, x and y in mm, their a priori RMS
error).  Control points (опорные точки, опознаки) also carry measured ground
coordinates with their own a priori RMS errors: they enter the adjustment as
weighted observations of the point's X, Y, Z.  Check points (контрольные точки)
are measured on the photos only; their ground truth is kept outside the
adjustment to judge it.  Field points (here: the gravimetric points, пункты
гравиметрических наблюдений, article 002) are located by the adjustment from
their marks on the photos.

:func:`simulate_measurements` images known ground points on photos of known
orientation (the collinearity equations of :mod:`.collinearity`) and adds
seeded Gaussian errors — the virtual site and a simulated flight provide the
truth (:mod:`aerophoto.labs.ch15` builds the chapter's blocks that way).

Validation (a :class:`ValueError` naming the problem and the valid range):
every array finite and of matching shapes; at least three control points with
X, Y and Z, not on one line; every photo with at least three points that are
also measured on another photo or are control ("a photo with no ties" cannot
be placed); every non-control point on at least two photos; the block
connected (a photo group sharing no point with the rest floats free).
"""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np
import pandas as pd

from .. import _validate as V
from .._validate import check_finite_array, check_positive, check_range
from .collinearity import _project as project
from .collinearity import _rotation_opk as rotation_opk

__all__ = ["KINDS", "MIN_CONTROL", "MIN_TIES_PER_PHOTO", "Measurements", "simulate_measurements"]

#: kinds of ground points
KINDS = ("tie", "control", "check", "field")
#: fewest full (X, Y, Z) control points of a block (a 3-D similarity has 7 parameters: 3 points, not on a line)
MIN_CONTROL = 3
#: fewest tie or control points on one photo (a photo is a 6-parameter resection)
MIN_TIES_PER_PHOTO = 3
#: largest problem accepted (photos, points, observations): a work-size guard
MAX_PHOTOS, MAX_POINTS, MAX_OBS = 5000, 200_000, 2_000_000


@dataclass(frozen=True, eq=False)
class Measurements:
    """One block's measurements (see the module notes).

    Attributes
    ----------
    f_mm, frame_mm : float
        Focal length f and frame side l of the camera, mm.
    photo_ids : ndarray (n,) int
        Photo numbers.
    photo_strip, photo_order : ndarray (n,) int
        Strip of each photo (0-based) and its place in the strip's line of flight.
    point_ids : ndarray (P,) int
        Ground-point ids.
    point_kind : ndarray (P,) str
        ``"tie"``, ``"control"``, ``"check"`` or ``"field"`` (:data:`KINDS`).
    obs_photo, obs_point : ndarray (N,) int
        Row index into the photos and the points of each image observation.
    xy_mm : ndarray (N, 2)
        Measured photo coordinates x, y, mm (from the principal point, :mod:`aerophoto.geometry`).
    sigma_mm : ndarray (N,)
        A priori RMS error of each measured coordinate, mm (weight 1/σ²).
    control_XYZ_m : ndarray (P, 3)
        Measured ground coordinates of the control points, m; NaN for other points.
    control_sigma_m : ndarray (P, 3)
        Their a priori RMS errors, m (NaN for other points).
    """

    f_mm: float
    frame_mm: float
    photo_ids: np.ndarray
    photo_strip: np.ndarray
    photo_order: np.ndarray
    point_ids: np.ndarray
    point_kind: np.ndarray
    obs_photo: np.ndarray
    obs_point: np.ndarray
    xy_mm: np.ndarray
    sigma_mm: np.ndarray
    control_XYZ_m: np.ndarray
    control_sigma_m: np.ndarray
    _cache: dict = field(default_factory=dict, repr=False, compare=False)

    def __post_init__(self):
        s = object.__setattr__
        s(self, "f_mm", check_positive("f_mm", self.f_mm, unit="mm", hi=2000.0))
        s(self, "frame_mm", check_positive("frame_mm", self.frame_mm, unit="mm", hi=500.0))
        ints = {}
        for name in ("photo_ids", "photo_strip", "photo_order", "point_ids", "obs_photo", "obs_point"):
            a = check_finite_array(name, getattr(self, name), ndim=1, max_size=MAX_OBS)
            if np.any(a != np.round(a)):
                raise ValueError(f"{name} must hold whole numbers")
            ints[name] = a.astype(np.intp)  # the index type: bincount refuses int64 where intp is int32 (wasm32)
            s(self, name, ints[name])
        n, P, N = len(self.photo_ids), len(self.point_ids), len(self.obs_photo)
        if n > MAX_PHOTOS or P > MAX_POINTS:
            raise ValueError(f"{n} photos and {P} points: the valid range is at most {MAX_PHOTOS} photos and "
                             f"{MAX_POINTS} points")
        for name in ("photo_strip", "photo_order"):
            if len(getattr(self, name)) != n:
                raise ValueError(f"{name} has {len(getattr(self, name))} entries; expected one per photo ({n})")
        if len(np.unique(self.photo_ids)) != n or len(np.unique(self.point_ids)) != P:
            raise ValueError("photo_ids and point_ids must be unique")
        kind = np.asarray(self.point_kind, dtype=object)
        if kind.shape != (P,) or not set(kind) <= set(KINDS):
            raise ValueError(f"point_kind must hold one of {KINDS} per point ({P} points)")
        s(self, "point_kind", kind)
        if len(self.obs_point) != N:
            raise ValueError(f"obs_point has {len(self.obs_point)} entries; obs_photo has {N}")
        if N and (self.obs_photo.min() < 0 or self.obs_photo.max() >= n):
            raise ValueError(f"obs_photo must index the photos: the valid range is 0 ≤ obs_photo < {n}")
        if N and (self.obs_point.min() < 0 or self.obs_point.max() >= P):
            raise ValueError(f"obs_point must index the points: the valid range is 0 ≤ obs_point < {P}")
        s(self, "xy_mm", check_finite_array("xy_mm", self.xy_mm, ndim=2, last=2, max_size=2 * MAX_OBS))
        if len(self.xy_mm) != N:
            raise ValueError(f"xy_mm has {len(self.xy_mm)} rows; expected one per observation ({N})")
        sig = check_finite_array("sigma_mm", self.sigma_mm, ndim=1, max_size=MAX_OBS)
        if len(sig) != N or np.any(sig <= 0) or np.any(sig > 10.0):
            raise ValueError("sigma_mm needs one value per observation with 0 < sigma_mm ≤ 10 (mm)")
        s(self, "sigma_mm", sig)
        c = np.asarray(self.control_XYZ_m, dtype=float)
        cs = np.asarray(self.control_sigma_m, dtype=float)
        if c.shape != (P, 3) or cs.shape != (P, 3):
            raise ValueError(f"control_XYZ_m and control_sigma_m must have shape ({P}, 3)")
        is_c = kind == "control"
        if not np.all(np.isfinite(c[is_c])) or not np.all(np.isfinite(cs[is_c])):
            raise ValueError("every control point needs finite control_XYZ_m and control_sigma_m")
        if np.any(cs[is_c] <= 0) or np.any(cs[is_c] > 1e4):
            raise ValueError("control_sigma_m must lie in 0 < control_sigma_m ≤ 10000 (m)")
        c = c.copy()
        cs = cs.copy()
        c[~is_c] = np.nan
        cs[~is_c] = np.nan
        s(self, "control_XYZ_m", c)
        s(self, "control_sigma_m", cs)
        self._check_geometry()

    # ------------------------------------------------------------------ validation of the block's geometry
    def _check_geometry(self):
        n, P = self.n_photos, self.n_points
        is_c = self.point_kind == "control"
        nc = int(is_c.sum())
        if nc < MIN_CONTROL:
            raise ValueError(f"the block has {nc} control point(s); the valid range is at least {MIN_CONTROL} "
                             "control points with X, Y, Z (not on one line) to fix its position, scale and tilt")
        C = self.control_XYZ_m[is_c]
        d = C - C.mean(axis=0)
        sv = np.linalg.svd(d[:, :2], compute_uv=False)
        if sv[-1] < 1e-3 * max(sv[0], 1e-9):
            raise ValueError(f"the {nc} control points lie on one line in plan; the valid range is at least "
                             f"{MIN_CONTROL} control points not on one line")
        per_point = np.bincount(self.obs_point, minlength=P)
        tied = (per_point >= 2) | is_c
        ties = np.bincount(self.obs_photo[tied[self.obs_point]], minlength=n)
        bad = np.flatnonzero(ties < MIN_TIES_PER_PHOTO)
        if len(bad):
            j = bad[0]
            raise ValueError(f"photo {int(self.photo_ids[j])} has {int(ties[j])} tie point(s) (points also measured "
                             f"on another photo, or control); the valid range is at least {MIN_TIES_PER_PHOTO}")
        lonely = np.flatnonzero((per_point < 2) & ~is_c)
        if len(lonely):
            ids = self.point_ids[lonely[:5]].tolist()
            raise ValueError(f"{len(lonely)} point(s) (ids {ids}…) are measured on fewer than 2 photos; "
                             "the valid range is at least 2 photos for every point that is not control")
        # connectivity: photos joined through shared points
        parent = np.arange(n)

        def root(a):
            while parent[a] != a:
                parent[a] = parent[parent[a]]
                a = parent[a]
            return a

        order = np.argsort(self.obs_point, kind="stable")
        pts, ph = self.obs_point[order], self.obs_photo[order]
        for i in range(1, len(pts)):
            if pts[i] == pts[i - 1]:
                ra, rb = root(ph[i]), root(ph[i - 1])
                if ra != rb:
                    parent[ra] = rb
        roots = {root(j) for j in range(n)}
        if len(roots) > 1:
            raise ValueError(f"the block falls apart into {len(roots)} groups of photos that share no point; "
                             "the valid range is one connected block")

    # ------------------------------------------------------------------ views
    @property
    def n_photos(self) -> int:
        return len(self.photo_ids)

    @property
    def n_points(self) -> int:
        return len(self.point_ids)

    @property
    def n_obs(self) -> int:
        return len(self.obs_photo)

    @property
    def is_control(self) -> np.ndarray:
        return self.point_kind == "control"

    @property
    def n_unknowns(self) -> int:
        """6 elements of exterior orientation per photo + 3 coordinates per ground point."""
        return 6 * self.n_photos + 3 * self.n_points

    @property
    def n_equations(self) -> int:
        """2 per image observation + 3 per control point."""
        return 2 * self.n_obs + 3 * int(self.is_control.sum())

    def index_of_point(self, point_id) -> int:
        k = np.flatnonzero(self.point_ids == int(point_id))
        if not len(k):
            raise ValueError(f"point_id = {point_id!r} is not a point of this block")
        return int(k[0])

    def index_of_photo(self, photo_id) -> int:
        k = np.flatnonzero(self.photo_ids == int(photo_id))
        if not len(k):
            raise ValueError(f"photo_id = {photo_id!r} is not a photo of this block")
        return int(k[0])

    def table(self) -> pd.DataFrame:
        """The observations: photo, point, kind, x, y (mm), σ (mm)."""
        return pd.DataFrame({
            "photo": self.photo_ids[self.obs_photo], "point": self.point_ids[self.obs_point],
            "kind": self.point_kind[self.obs_point], "x, mm": self.xy_mm[:, 0], "y, mm": self.xy_mm[:, 1],
            "σ, mm": self.sigma_mm})

    def summary(self) -> dict:
        """Counts: photos, strips, points of each kind, observations, unknowns, equations, redundancy."""
        out = {"photos": self.n_photos, "strips": int(len(np.unique(self.photo_strip)))}
        for k in KINDS:
            out[f"{k} points"] = int(np.sum(self.point_kind == k))
        out.update({"image observations": self.n_obs, "unknowns": self.n_unknowns,
                    "equations": self.n_equations, "redundancy": self.n_equations - self.n_unknowns})
        return out

    # ------------------------------------------------------------------ editing
    def replace(self, **changes) -> "Measurements":
        """A copy with some arrays changed (validated again)."""
        return replace(self, _cache={}, **changes)

    def without_observations(self, drop) -> "Measurements":
        """A copy without the image observations ``drop`` (indices or a mask); a point left on fewer than two
        photos (and not control) is removed with its last observation."""
        keep = np.ones(self.n_obs, bool)
        keep[np.asarray(drop)] = False
        while True:
            per_point = np.bincount(self.obs_point[keep], minlength=self.n_points)
            weak = (per_point < 2) & ~self.is_control
            more = keep & weak[self.obs_point]
            if not more.any():
                break
            keep &= ~more
        used = np.bincount(self.obs_point[keep], minlength=self.n_points) > 0
        used |= self.is_control
        return self._subset(keep, used)

    def as_tie(self, point_id) -> "Measurements":
        """A copy in which control point ``point_id`` loses its ground coordinates (a rejected control point);
        if it is measured on fewer than two photos it is removed altogether."""
        k = self.index_of_point(point_id)
        if np.sum(self.obs_point == k) < 2:
            keep_pts = np.ones(self.n_points, bool)
            keep_pts[k] = False
            return self._subset(self.obs_point != k, keep_pts)
        kind = self.point_kind.copy()
        kind[k] = "tie"
        return self.replace(point_kind=kind)

    def _subset(self, keep_obs, keep_points) -> "Measurements":
        new_index = np.full(self.n_points, -1)
        new_index[keep_points] = np.arange(int(keep_points.sum()))
        return self.replace(
            point_ids=self.point_ids[keep_points], point_kind=self.point_kind[keep_points],
            obs_photo=self.obs_photo[keep_obs], obs_point=new_index[self.obs_point[keep_obs]],
            xy_mm=self.xy_mm[keep_obs], sigma_mm=self.sigma_mm[keep_obs],
            control_XYZ_m=self.control_XYZ_m[keep_points], control_sigma_m=self.control_sigma_m[keep_points])


@V.checked(f_mm=V.number(0.0, 2000.0, lo_open=True), frame_mm=V.number(0.0, 500.0, lo_open=True),
           eo_true=V.array(ndim=2, last=6, min_len=1), photo_ids=V.indices(), photo_strip=V.indices(),
           photo_order=V.indices(), XYZ_true_m=V.points(3, min_points=1), point_ids=V.indices(),
           point_kind=V.sequence(min_len=1), seed=V.whole(0, 2**32 - 1))
def simulate_measurements(f_mm: float, frame_mm: float, eo_true, photo_ids, photo_strip, photo_order,
                          XYZ_true_m, point_ids, point_kind, *, sigma_mm: float = 0.005,
                          sigma_kind_mm: dict | None = None, control_sigma_m=(0.1, 0.1, 0.1),
                          margin_mm: float = 5.0, seed: int = 0, drop_single: bool = True) -> Measurements:
    """Image known ground points on photos of known orientation, with seeded Gaussian measurement errors.

    Parameters
    ----------
    f_mm, frame_mm : the camera (mm)
    eo_true : (n, 6) true exterior orientation (X, Y, Z m; ω, φ, κ rad) — :func:`.collinearity.eo_from_poses`
    photo_ids, photo_strip, photo_order : (n,) photo numbers, strips, order in the strip
    XYZ_true_m : (P, 3) true ground coordinates, m
    point_ids, point_kind : (P,) ids and kinds (:data:`KINDS`)
    sigma_mm : RMS error of a measured photo coordinate, mm (0 ≤ σ ≤ 1; 0 gives exact measurements)
    sigma_kind_mm : optional {kind: σ} overriding ``sigma_mm`` for a kind (e.g. ``{"field": 0.03}``: marks
        transferred by eye from the helicopter photo)
    control_sigma_m : (σ_X, σ_Y, σ_Z) of the control coordinates, m (the errors are drawn and added)
    margin_mm : a point is measured where it falls at least this far inside the frame, mm
    seed : the random stream
    drop_single : drop points (not control) imaged on fewer than two photos

    The a priori σ stored with each observation is the σ used to draw its error
    (a zero σ is stored as 1 µm so that the weights stay finite).
    """
    eo = check_finite_array("eo_true", eo_true, ndim=2, last=6)
    P = check_finite_array("XYZ_true_m", XYZ_true_m, ndim=2, last=3)
    sig = check_range("sigma_mm", sigma_mm, 0.0, 1.0, unit="mm")
    margin = check_range("margin_mm", margin_mm, -50.0, frame_mm / 2.0, unit="mm")
    csig = np.broadcast_to(np.asarray(control_sigma_m, dtype=float), (3,))
    for v in csig:
        check_range("control_sigma_m", v, 0.0, 1e4, unit="m")
    kinds = np.asarray(point_kind, dtype=object)
    rng = np.random.default_rng(seed)
    half = frame_mm / 2.0 - margin
    rows_ph, rows_pt, rows_xy = [], [], []
    for j in range(len(eo)):
        xy = project(np.repeat(eo[j:j + 1], len(P), axis=0), P, f_mm)
        R = rotation_opk(*eo[j, 3:])
        cz = (P - eo[j, :3]) @ R[:, 2]
        ok = (cz < 0) & np.all(np.abs(xy) <= half, axis=1)
        k = np.flatnonzero(ok)
        rows_ph.append(np.full(len(k), j))
        rows_pt.append(k)
        rows_xy.append(xy[k])
    ph = np.concatenate(rows_ph)
    pt = np.concatenate(rows_pt)
    xy = np.concatenate(rows_xy)
    s = np.full(len(ph), sig)
    for kind, value in (sigma_kind_mm or {}).items():
        if kind not in KINDS:
            raise ValueError(f"sigma_kind_mm has kind {kind!r}; valid kinds: {KINDS}")
        s[kinds[pt] == kind] = check_range(f"sigma_kind_mm[{kind!r}]", value, 0.0, 1.0, unit="mm")
    order = np.lexsort((ph, pt))  # by point, then photo
    ph, pt, xy, s = ph[order], pt[order], xy[order], s[order]
    xy = xy + rng.standard_normal(xy.shape) * s[:, None]
    is_c = kinds == "control"
    ctrl = np.full(P.shape, np.nan)
    ctrl[is_c] = P[is_c] + rng.standard_normal((int(is_c.sum()), 3)) * csig
    csg = np.full(P.shape, np.nan)
    csg[is_c] = np.maximum(csig, 1e-4)
    keep_pt = np.ones(len(P), bool)
    if drop_single:
        per = np.bincount(pt, minlength=len(P))
        keep_pt = (per >= 2) | (is_c & (per >= 1))
    new = np.full(len(P), -1)
    new[keep_pt] = np.arange(int(keep_pt.sum()))
    keep_obs = keep_pt[pt]
    return Measurements(
        f_mm=f_mm, frame_mm=frame_mm, photo_ids=np.asarray(photo_ids), photo_strip=np.asarray(photo_strip),
        photo_order=np.asarray(photo_order), point_ids=np.asarray(point_ids)[keep_pt], point_kind=kinds[keep_pt],
        obs_photo=ph[keep_obs], obs_point=new[pt[keep_obs]], xy_mm=xy[keep_obs],
        sigma_mm=np.maximum(s[keep_obs], 1e-3), control_XYZ_m=ctrl[keep_pt], control_sigma_m=csg[keep_pt])
