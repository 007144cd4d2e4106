"""Radial strip phototriangulation and its reduction, done analytically (guide §7, §13).

The guide builds a single-strip radial triangulation (одномаршрутный
фототриангуляционный ряд) with tracing paper: on every photo it pricks a
*working centre* (рабочий центр) near the principal point, *orienting points*
(ориентирующие точки) at the corners of the working area, *tie points*
(связующие точки) in the triple overlap and the *control points* (опознаки);
it draws a *direction template* (восковка направлений) — the rays from the
working centre to every pricked point — and lays the templates one on another.
This module does the same with numbers:

1. :func:`design_points` chooses the points on a simulated strip (from a site
   catalogue when one is given, otherwise exact points on the terrain);
2. :func:`measure_templates` pricks them on every photo through the camera
   model (:func:`aerophoto.geometry.ground_to_photo`) with a seeded pricking
   error and measures the directions from each working centre;
3. :func:`lay_free_strip` lays the templates in an arbitrary scale (свободный
   ряд, §13 step 6): matching working centres and initial directions
   (начальные направления), the scale of every next template from the tie
   points, every point intersected from its rays, the error triangles
   (треугольники погрешностей) at the tie points checked against 0.3 mm;
4. :func:`reduce_strip` reduces the free strip to the plan (редуцирование,
   §7 step 8–9, §13 step 8–9): the reduction coefficients k = l_base/l_template
   per base with their spread (tables 8, 12), the corrections v = r·(k − 1)
   from a central working centre (tables 9, 13), then the rotation and shift
   that lay the corrected control points on the base, and the control
   residuals against 0.4 mm;
5. :func:`build_from_ends` is §7's variant: the first and last templates set
   on the plan by resection (обратная засечка) from their control points, the
   strip built from both ends to the middle, the middle template's two
   solutions and their mean.

Beside them: Zhukov's formula (13.1) for the spacing of control points
(:func:`zhukov_error_mm`, :func:`zhukov_max_bases`) with the reading of its
garbled radicand justified in :data:`ZHUKOV_READING`, and the guide's worked
tables 8 and 9 recomputed from their printed inputs (:func:`guide_table8`,
:func:`guide_table9`) with every printed number that does not follow listed.

Units and frames
----------------
Photo coordinates and template directions are in mm on the photo, angles
counter-clockwise from the photo's +x axis (see :mod:`aerophoto.geometry`).
The free strip lives in its own "template mm" frame (the tracing paper); the
plan (основа) in mm at the plan scale 1/M, with x east and y north; ground in
metres.  Distances between control points in tables are plan mm.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field

import numpy as np
import pandas as pd

from . import geometry as g
from . import plane as _plane
from ._validate import check_int_range, check_positive, check_range

__all__ = [
    "TRIANGLE_TOL_MM",
    "K_SPREAD_TOL",
    "K_SPREAD_TOL_SHORT",
    "SHORT_BASE_MM",
    "CONTROL_TOL_MM",
    "PRICKING_MM",
    "KINDS",
    "StripPoints",
    "Templates",
    "FreeStrip",
    "ReductionCoefficients",
    "ReductionCorrections",
    "Reduction",
    "EndsStrip",
    "design_points",
    "measure_templates",
    "lay_free_strip",
    "reduction_coefficients",
    "reduction_corrections",
    "reduce_strip",
    "build_from_ends",
    "error_triangle",
    "intersect_rays",
    "resect",
    "fit_rigid",
    "fit_similarity",
    "ZHUKOV_READING",
    "zhukov_radicand",
    "zhukov_error_mm",
    "zhukov_max_bases",
    "zhukov_bases_continuous",
    "bridge_variance_factor",
    "RHO_ARCMIN",
    "Discrepancy",
    "GuideCheck",
    "GUIDE_S7_CONTROL",
    "GUIDE_TABLE8",
    "GUIDE_TABLE9",
    "guide_table8",
    "guide_table9",
    "accumulation_study",
]

#: the largest side of an error triangle at a tie point, template mm (guide §7, §13 step 6)
TRIANGLE_TOL_MM = 0.3
#: the largest deviation of a base's reduction coefficient from the mean (guide §7 step 8, §13 step 8)
K_SPREAD_TOL = 0.003
#: … on a short base (guide §13 step 8)
K_SPREAD_TOL_SHORT = 0.006
#: a base shorter than this (plan mm) is "short": there 0.003·l would be below the 0.4 mm the
#: graphical work can hold, so the guide's relaxed 0.006 applies.  0.4 / 0.003 = 133.3 mm.
SHORT_BASE_MM = 0.4 / K_SPREAD_TOL
#: the largest residual of a control point after the reduced strip is laid on the base (guide §13 step 9)
CONTROL_TOL_MM = 0.4
#: the guide's accuracy of identifying and pricking a point on a photo, mm (guide §13 step 2)
PRICKING_MM = 0.1

#: point kinds, with the guide's Russian names
KINDS = {
    "centre": "рабочий центр (working centre)",
    "orienting": "ориентирующая точка (orienting point)",
    "tie": "связующая точка (tie point)",
    "control": "опознак (control point)",
}

_CYR = "АБВГДЕЖЗИКЛМНОПРСТУФХЦЧШЭЮЯ"
_LAT = "abcdefghijklmnopqrstuvwxyz"


# =========================================================================== points
@dataclass(frozen=True)
class StripPoints:
    """The pricked points of a strip with their ground truth.

    Attributes
    ----------
    names : tuple of str, length P
        Labels as in guide §13: working centres by photo number ("36"),
        control points "36/1", orienting points А, Б, В…, tie points a, b, c…
    kinds : tuple of str, length P
        One of :data:`KINDS` for each point.
    XYZ_m : ndarray, shape (P, 3)
        True ground coordinates, metres.
    photo : ndarray of int, shape (P,)
        The photo a point was chosen on (0-based): for a centre its own photo,
        for a tie point the photo whose triple overlap holds it, for an
        orienting or control point the first photo of its overlap pair.
    source : tuple of str, length P
        ``"catalogue"`` (a point of the site's catalogue near the design
        position) or ``"terrain"`` (the exact point where the design
        position's ray meets the terrain).
    photo_numbers : tuple of int, length N
        The photos' numbers used in labels.
    """

    names: tuple
    kinds: tuple
    XYZ_m: np.ndarray
    photo: np.ndarray
    source: tuple
    photo_numbers: tuple

    def __len__(self) -> int:
        return len(self.names)

    def index(self, name: str) -> int:
        """Position of the point called ``name``; ValueError listing the names if absent."""
        try:
            return self.names.index(name)
        except ValueError:
            raise ValueError(f"point = {name!r} is not in the strip; valid points: {', '.join(self.names)}") from None

    def mask(self, kind: str) -> np.ndarray:
        """Boolean mask, shape (P,), of the points of one kind."""
        if kind not in KINDS:
            raise ValueError(f"kind = {kind!r} is not a point kind; valid kinds: {', '.join(KINDS)}")
        return np.array([k == kind for k in self.kinds], dtype=bool)

    @property
    def centre_index(self) -> np.ndarray:
        """Indices, shape (N,), of the working centres in photo order."""
        idx = np.flatnonzero(self.mask("centre"))
        return idx[np.argsort(self.photo[idx])]

    def table(self) -> pd.DataFrame:
        """The point list: kind, photo, ground X, Y, Z (m), source."""
        return pd.DataFrame(
            {
                "kind": list(self.kinds),
                "photo": [self.photo_numbers[i] for i in self.photo],
                "X, m": self.XYZ_m[:, 0],
                "Y, m": self.XYZ_m[:, 1],
                "Z, m": self.XYZ_m[:, 2],
                "source": list(self.source),
            },
            index=pd.Index(list(self.names), name="point"),
        )


def _terrain_of(terrain):
    if terrain is None:
        return g.FlatTerrain(0.0)
    if isinstance(terrain, (int, float)):
        return g.FlatTerrain(float(terrain))
    return terrain


def _photo_to_ground(camera, pose, xy, terrain):
    t = _terrain_of(terrain)
    if isinstance(t, g.FlatTerrain):
        return g.photo_to_plane(camera, pose, xy, t.z_m)
    return g.photo_to_dem(camera, pose, xy, t)


def _catalogue_arrays(catalogue):
    """(names, XYZ (K,3), is_control (K,)) from a site catalogue DataFrame (or None)."""
    if catalogue is None:
        return None
    df = catalogue
    cols = {c.lower(): c for c in df.columns}

    def col(*names):
        for n in names:
            if n.lower() in cols:
                return df[cols[n.lower()]].to_numpy()
        return None

    X = col("X_m", "X")
    Y = col("Y_m", "Y")
    Z = col("Z_m", "Z", "H_m", "H")
    if X is None or Y is None or Z is None:
        raise ValueError(f"catalogue has columns {list(df.columns)}; it needs X, Y, Z (or X_m, Y_m, Z_m) in metres")
    ctl = col("is_control", "control")
    if ctl is None:
        kind = col("kind", "type")
        ctl = np.array([str(k).lower().startswith("control") for k in kind]) if kind is not None else np.zeros(len(df), bool)
    names = col("name", "id", "label")
    if names is None:
        names = np.asarray(df.index)
    XYZ = np.column_stack([X, Y, Z]).astype(float)
    return [str(n) for n in names], XYZ, np.asarray(ctl, dtype=bool)


def design_points(
    camera: g.Camera,
    poses,
    terrain=None,
    *,
    catalogue=None,
    control_layout: str = "overlap",
    tie_from_edge_mm: float = 25.0,
    side_overlap_percent: float = 30.0,
    centre_offset_mm=None,
    search_radius_mm: float = 12.0,
    centre_search_mm: float = 5.0,
    photo_numbers=None,
) -> StripPoints:
    """Choose the working centres, orienting, tie and control points of a strip (guide §13 steps 2–3).

    Design positions (photo mm on the photo they are chosen on; b is the
    photo base between this photo's principal point and the next one's):

    * working centre of photo t: with a catalogue, the catalogue point
      nearest o if it lies within r ≤ f/30 of o (§13 step 3), else the exact
      terrain point at o; ``centre_offset_mm`` (shape (2,) or (N, 2), each
      within f/30) puts it at that photo position instead, ignoring the
      catalogue;
    * orienting points of the pair (t, t+1): the corners of the working area,
      at x = b/2 (mid of the double forward overlap) and y = ±(90 − p_y·180/200)
      mm (mid of the side overlap);
    * tie points of the triple overlap centred on photo t (t = 2 … N − 1):
      x = 0, y = ±(half frame − ``tie_from_edge_mm``) (2–3 cm from the edge);
    * control points: ``"overlap"`` (guide §13, figure 21) — two in the first
      pair's double overlap, nearer the strip start (x = b/4, y = ±(half − 20)
      on photo 1) and two mirrored in the last pair's; ``"ends"`` (guide §7,
      figure 15) — four on each end photo, at x = ±b/2 … the two inner ones
      are in the overlap with the neighbour, the two outer ones only on the
      end photo (enough for a resection, not for a free strip).

    Parameters
    ----------
    camera : Camera
    poses : sequence of Pose, length N ≥ 3
        The strip's true exterior orientations, in flight order.
    terrain : DEM with ``height(X, Y)``, ``z_min_m``, ``z_max_m`` (e.g. the
        site), a number (flat ground at that height) or None (Z = 0).
    catalogue : pandas.DataFrame, optional
        Ground points with X, Y, Z (m) (``X_m``… or ``X``…) and a control
        flag (``control``/``is_control``, or ``kind == "control"``), e.g.
        :attr:`aerophoto.site.Site.catalogue`.  The point nearest each design
        position within ``search_radius_mm`` (photo mm) is used, each at most
        once; a control position prefers the catalogue's control points and
        otherwise takes any catalogue point there (as if surveyed).  Where
        the catalogue has nothing near, the exact terrain point at the design
        position is used (``source`` tells which).  Points keep the guide's
        labels (36/1, А, a, …) either way.
    search_radius_mm : float
        How far from a design position a catalogue point may be, photo mm.
    centre_search_mm : float
        A catalogue point serves as a working centre only within
        min(f/30, centre_search_mm) of o.  The guide's f/30 (§13 step 3) is
        2.3–6.7 mm for its cameras (f = 70–200 mm); for the long lenses of
        high variants (f up to 1090 mm) it would allow centres 20–36 mm from
        o, too far for the neighbouring photos to see them — hence the cap.
    photo_numbers : sequence of int, optional
        Labels of the photos (default 1 … N); guide §13 uses 36 … 39.

    Returns
    -------
    StripPoints
    """
    poses = list(poses)
    N = len(poses)
    if N < 3:
        raise ValueError(f"len(poses) = {N} is outside the valid range 3 ≤ len(poses) (a strip needs a triple overlap)")
    if control_layout not in ("overlap", "ends"):
        raise ValueError(f"control_layout = {control_layout!r}; valid: 'overlap' (guide §13) or 'ends' (guide §7)")
    half = camera.half_mm
    check_range("tie_from_edge_mm", tie_from_edge_mm, 0.0, half, lo_open=True, hi_open=True, unit="mm")
    check_range("side_overlap_percent", side_overlap_percent, 0.0, 100.0, hi_open=True, unit="%")
    check_positive("search_radius_mm", search_radius_mm, unit="mm")
    check_positive("centre_search_mm", centre_search_mm, unit="mm")
    numbers = tuple(int(n) for n in (photo_numbers if photo_numbers is not None else range(1, N + 1)))
    if len(numbers) != N:
        raise ValueError(f"photo_numbers has {len(numbers)} entries; it must have one per photo ({N})")
    terrain = _terrain_of(terrain)
    cat = _catalogue_arrays(catalogue)
    r_max = camera.f_mm / 30.0
    r_centre = min(r_max, float(centre_search_mm))

    # the photo base b_t from photo t to photo t+1, measured on photo t (mm, along the image of the
    # next o); the design geometry uses the plane of the mean height (positions are nominal anyway)
    z_ref = 0.5 * (float(getattr(terrain, "z_min_m", 0.0)) + float(getattr(terrain, "z_max_m", 0.0)))
    O = np.array([g.photo_to_plane(camera, pose, np.zeros(2), z_ref) for pose in poses])
    o_next = np.array([g.ground_to_photo(camera, poses[t], O[t + 1]) for t in range(N - 1)])
    o_prev = {t: g.ground_to_photo(camera, poses[t], O[t - 1]) for t in range(1, N)}

    def along(t, frac, y):
        """Photo point on photo t at fraction ``frac`` of the base towards photo t+1, offset y across."""
        d = o_next[t] / np.hypot(*o_next[t])
        n = np.array([-d[1], d[0]])
        return frac * o_next[t] + y * n

    def along_back(t, frac, y):
        """On photo t at fraction ``frac`` of the base towards photo t−1 (y to the left of the flight)."""
        back = o_prev[t]
        d = -back / np.hypot(*back)  # forward direction
        n = np.array([-d[1], d[0]])
        return frac * back + y * n

    specs = []  # (name, kind, photo, xy, control, exact)
    if centre_offset_mm is None:
        offs = np.zeros((N, 2))
    else:
        offs = np.broadcast_to(np.asarray(centre_offset_mm, dtype=float), (N, 2))
        r = np.hypot(offs[:, 0], offs[:, 1])
        if np.any(r > r_max + 1e-12):
            raise ValueError(
                f"centre_offset_mm puts a working centre {float(r.max()):.2f} mm from o; "
                f"the valid range is r ≤ f/30 = {r_max:.2f} mm (guide §13 step 3)"
            )
    for t in range(N):
        specs.append((str(numbers[t]), "centre", t, offs[t], False, centre_offset_mm is not None))
    y_side = half - side_overlap_percent / 100.0 * camera.frame_mm / 2.0
    y_tie = half - tie_from_edge_mm
    y_ctl = half - 20.0
    letter = 0
    for t in range(N - 1):
        for sgn in (+1, -1):
            lab = _CYR[letter] if letter < len(_CYR) else f"О{letter + 1}"
            letter += 1
            specs.append((lab, "orienting", t, along(t, 0.5, sgn * y_side), False, False))
    tl = 0
    for t in range(1, N - 1):
        for sgn in (+1, -1):
            lab = _LAT[tl] if tl < len(_LAT) else f"t{tl + 1}"
            tl += 1
            specs.append((lab, "tie", t, along(t, 0.0, sgn * y_tie), False, False))
    first, last = numbers[0], numbers[-1]
    ctl = [(f"{first}/1", 0, along(0, 0.25, +y_ctl)), (f"{first}/2", 0, along(0, 0.25, -y_ctl)),
           (f"{last}/1", N - 1, along_back(N - 1, 0.25, +y_ctl)),
           (f"{last}/2", N - 1, along_back(N - 1, 0.25, -y_ctl))]
    if control_layout == "ends":
        ctl = ctl[:2] + [(f"{first}/3", 0, along(0, -0.5, -y_ctl)), (f"{first}/4", 0, along(0, -0.5, +y_ctl))] \
            + ctl[2:] + [(f"{last}/3", N - 1, along_back(N - 1, -0.5, -y_ctl)),
                         (f"{last}/4", N - 1, along_back(N - 1, -0.5, +y_ctl))]
    for lab, t, xy in ctl:
        specs.append((lab, "control", t, xy, True, False))

    # exact terrain points at the design positions: one DEM intersection per photo
    ground = np.zeros((len(specs), 3))
    for t in range(N):
        rows = [j for j, sp in enumerate(specs) if sp[2] == t]
        if rows:
            ground[rows] = _photo_to_ground(camera, poses[t], np.array([specs[j][3] for j in rows]), terrain)

    names, kinds, XYZ, photo, source = [], [], [], [], []
    used = set()
    cat_photo = None
    if cat is not None:
        _cnames, cXYZ, cctl = cat
        cat_photo = []
        for pose in poses:  # catalogue points on each photo (nan behind the camera)
            cz = ((cXYZ - pose.centre) @ g.rotation_matrix(pose))[:, 2]
            xy = np.full((len(cXYZ), 2), np.nan)
            front = cz < 0
            xy[front] = g.ground_to_photo(camera, pose, cXYZ[front])
            cat_photo.append(xy)
    for j, (name, kind, t, xy, control, exact) in enumerate(specs):
        P, src = ground[j], "terrain"
        if cat is not None and not exact:
            xy_c = cat_photo[t]
            dist = np.hypot(xy_c[:, 0] - xy[0], xy_c[:, 1] - xy[1])
            dist[~np.isfinite(dist)] = np.inf
            if used:
                dist[list(used)] = np.inf
            if control:  # a surveyed control point if one is there, else any catalogue point there
                pref = np.where(cctl, dist, np.inf)
                if np.isfinite(pref).any() and pref.min() <= search_radius_mm:
                    dist = pref
            else:
                dist = np.where(cctl, np.inf, dist)
            jj = int(np.argmin(dist))
            near = np.hypot(*xy_c[jj]) <= r_centre if kind == "centre" else dist[jj] <= search_radius_mm
            if np.isfinite(dist[jj]) and near:
                P, src = cXYZ[jj], "catalogue"
                used.add(jj)
        names.append(name)
        kinds.append(kind)
        XYZ.append(np.asarray(P, dtype=float))
        photo.append(t)
        source.append(src)
    # unique names (a catalogue may reuse labels)
    seen = {}
    for i, n in enumerate(names):
        if n in seen:
            seen[n] += 1
            names[i] = f"{n}#{seen[n]}"
        else:
            seen[n] = 0
    return StripPoints(tuple(names), tuple(kinds), np.array(XYZ), np.array(photo, dtype=int), tuple(source), numbers)


# =========================================================================== templates
@dataclass(frozen=True)
class Templates:
    """Direction templates (восковки направлений) measured on the photos (guide §13 step 5).

    Attributes
    ----------
    camera : Camera
    poses : tuple of Pose, length N
    points : StripPoints, P points
    true_xy_mm : ndarray, shape (N, P, 2)
        Exact images of every point on every photo, mm (nan where off the frame).
    xy_mm : ndarray, shape (N, P, 2)
        The pricked positions: the exact images plus the pricking error, mm
        (nan where the point is not pricked on that photo).
    pricked : ndarray of bool, shape (N, P)
        Where a point is pricked: inside the frame by at least ``margin_mm``.
    directions_rad : ndarray, shape (N, P)
        Direction from photo t's own working centre (as pricked) to each
        pricked point, radians counter-clockwise from the photo's +x axis;
        nan where not pricked and for the own centre.
    pricking_mm : float
        RMS position error of one pricking m_p, mm; each coordinate gets a
        normal error with σ = m_p/√2.  A direction over r mm then errs by
        about m_p/r radians (centre and point together): 0.1 mm at 70 mm
        is 4.9′, the m_ε = 4′–5′ of Zhukov's formula (guide §13).
    seed : int
    """

    camera: g.Camera
    poses: tuple
    points: StripPoints
    true_xy_mm: np.ndarray
    xy_mm: np.ndarray
    pricked: np.ndarray
    directions_rad: np.ndarray
    pricking_mm: float
    seed: int

    @property
    def n_photos(self) -> int:
        return len(self.poses)

    def rays(self, t: int):
        """Indices and directions (rad) of the rays drawn on template t (own centre excluded)."""
        d = self.directions_rad[t]
        idx = np.flatnonzero(np.isfinite(d))
        return idx, d[idx]

    def table(self, t: int) -> pd.DataFrame:
        """Template t: each ray's point, kind, direction (degrees) and length on the photo (mm)."""
        idx, d = self.rays(t)
        own = self.points.centre_index[t]
        c = self.xy_mm[t, own]
        r = np.hypot(*(self.xy_mm[t, idx] - c).T)
        return pd.DataFrame(
            {"kind": [self.points.kinds[i] for i in idx], "direction, °": np.degrees(d) % 360.0, "r, mm": r},
            index=pd.Index([self.points.names[i] for i in idx], name=f"template {self.points.photo_numbers[t]}"),
        )


def measure_templates(
    camera: g.Camera,
    poses,
    points: StripPoints,
    *,
    pricking_mm: float = PRICKING_MM,
    seed: int = 0,
    margin_mm: float = 3.0,
) -> Templates:
    """Prick every point on every photo and measure the template directions (guide §13 steps 2–5).

    Each point is projected through each true pose with
    :func:`aerophoto.geometry.ground_to_photo`; where its image falls inside
    the frame by at least ``margin_mm`` it is pricked with an independent
    normal error (σ = pricking_mm/√2 per coordinate, seeded).  Working
    centres are pricked on their own photo and transferred to the
    neighbours with the same error.

    Parameters
    ----------
    pricking_mm : float
        RMS pricking error m_p on the photo, mm, 0 ≤ m_p ≤ 2 (guide: 0.1 mm).
    seed : int
        Seed of the pricking errors: the same seed gives the same templates.
    """
    poses = tuple(poses)
    mp = check_range("pricking_mm", pricking_mm, 0.0, 2.0, unit="mm")
    check_range("margin_mm", margin_mm, 0.0, camera.half_mm, hi_open=True, unit="mm")
    N, P = len(poses), len(points)
    true_xy = np.full((N, P, 2), np.nan)
    for t, pose in enumerate(poses):
        cam_z = ((points.XYZ_m - pose.centre) @ g.rotation_matrix(pose))[:, 2]
        front = cam_z < 0
        if np.any(front):
            true_xy[t, front] = g.ground_to_photo(camera, pose, points.XYZ_m[front])
    lim = camera.half_mm - margin_mm
    pricked = np.all(np.abs(true_xy) <= lim, axis=-1)
    rng = np.random.default_rng(int(seed))
    noise = rng.normal(0.0, mp / math.sqrt(2.0), size=(N, P, 2))
    xy = np.where(pricked[..., None], true_xy + noise, np.nan)
    centres = points.centre_index
    if len(centres) != N:
        raise ValueError(f"points has {len(centres)} working centres; it needs one per photo ({N})")
    directions = np.full((N, P), np.nan)
    for t in range(N):
        own = centres[t]
        if not pricked[t, own]:
            raise ValueError(f"the working centre {points.names[own]} falls outside its own photo {points.photo_numbers[t]}")
        d = xy[t] - xy[t, own]
        ang = np.arctan2(d[:, 1], d[:, 0])
        ang[~pricked[t]] = np.nan
        ang[own] = np.nan
        directions[t] = ang
    return Templates(camera, poses, points, true_xy, xy, pricked, directions, mp, int(seed))


# =========================================================================== plane geometry
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
    C = np.asarray(origins, dtype=float).reshape(-1, 2)
    u = _u(angles_rad).reshape(-1, 2)
    if len(C) < 2:
        raise ValueError(f"{len(C)} ray(s) given; an intersection needs at least 2")
    Nmat = np.eye(2)[None] - u[:, :, None] * u[:, None, :]
    A = Nmat.sum(axis=0)
    b = np.einsum("kij,kj->i", Nmat, C)
    if abs(np.linalg.det(A)) < 1e-12:
        raise ValueError("the rays are parallel: the point cannot be intersected")
    return np.linalg.solve(A, b)


def _line_intersection(Ca, ua, Cb, ub):
    den = _cross(ua, ub)
    if abs(den) < 1e-15:
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
    C = np.asarray(origins, dtype=float).reshape(3, 2)
    u = _u(angles_rad).reshape(3, 2)
    v01 = _line_intersection(C[0], u[0], C[1], u[1])
    v12 = _line_intersection(C[1], u[1], C[2], u[2])
    v02 = _line_intersection(C[0], u[0], C[2], u[2])
    V = np.array([v01, v12, v02])
    sides = np.array([np.hypot(*(v01 - v12)), np.hypot(*(v12 - v02)), np.hypot(*(v02 - v01))])
    return V, sides


def resect(angles_rad, known_xy, *, line=None, x0=None, iterations: int = 20):
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

    Returns
    -------
    C : ndarray (2,), theta_rad : float, residuals_mm : ndarray (k,) (signed
    perpendicular distances of the known points from their rays; the line's
    residual is appended last when ``line`` is given).
    """
    phi = np.asarray(angles_rad, dtype=float).ravel()
    K = np.asarray(known_xy, dtype=float).reshape(-1, 2)
    k = len(phi)
    if len(K) != k:
        raise ValueError(f"{k} directions but {len(K)} known points; give one known point per direction")
    n_obs = k + (1 if line is not None else 0)
    if n_obs < 3:
        raise ValueError(f"{n_obs} observations; a resection needs at least 3 (centre and rotation are 3 unknowns)")
    if x0 is None:
        if k < 3:
            raise ValueError(f"{k} known points; the starting values need at least 3 (or give x0)")
        # linear solution in (cos θ, sin θ, A, B): c(s_j Kx − c_j Ky) + s(c_j Kx + s_j Ky) − s_j A − c_j B = 0
        cj, sj = np.cos(phi), np.sin(phi)
        A = np.column_stack([sj * K[:, 0] - cj * K[:, 1], cj * K[:, 0] + sj * K[:, 1], -sj, -cj])
        _, _, vt = np.linalg.svd(A)
        c, s, a, b = vt[-1]
        nrm = math.hypot(c, s)
        c, s, a, b = c / nrm, s / nrm, a / nrm, b / nrm
        x = np.array([c * a + s * b, s * a - c * b, math.atan2(s, c)])
    else:
        x = np.asarray(x0, dtype=float).copy()
    for _ in range(iterations):
        psi = phi + x[2]
        u = _u(psi)
        d = K - x[:2]
        r = _cross(u, d)
        J = np.column_stack([u[:, 1], -u[:, 0], -np.sum(u * d, axis=1)])
        if line is not None:
            L0, la = np.asarray(line[0], dtype=float), float(line[1])
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
        L0, la = np.asarray(line[0], dtype=float), float(line[1])
        r = np.append(r, _cross(np.array([math.cos(la), math.sin(la)]), x[:2] - L0))
    return x[:2].copy(), float(x[2]), r


def fit_rigid(src, dst):
    """Best-fit rotation + translation (no scale) taking ``src`` points onto ``dst``.

    Parameters
    ----------
    src, dst : array_like, shape (k, 2), k ≥ 2

    Returns
    -------
    R : ndarray (2, 2), t : ndarray (2,) — ``dst ≈ src @ R.T + t`` in the
    least-squares sense (:func:`aerophoto.plane.fit_similarity`, reflections excluded).
    """
    T = _plane.fit_similarity(src, dst).matrix()
    return T[:2, :2], T[:2, 2]


def fit_similarity(src, dst):
    """Best-fit similarity (scale, rotation, translation): ``dst ≈ s · src @ R.T + t``; returns (s, R, t).

    The matrix form of :func:`aerophoto.plane.fit_similarity` with a free scale.
    """
    S = _plane.fit_similarity(src, dst, scale=True)
    T = S.matrix()
    return S.scale, T[:2, :2] / S.scale, T[:2, 2]


# =========================================================================== free strip
def _largest_side(sides_mm) -> float:
    """The largest finite error-triangle side, mm (0 when there is none)."""
    s = np.asarray(sides_mm, dtype=float)
    return float(np.nanmax(s)) if np.any(np.isfinite(s)) else 0.0


@dataclass(frozen=True)
class FreeStrip:
    """A free strip (свободный ряд): the templates laid in an arbitrary scale (guide §13 step 6–7).

    Attributes
    ----------
    templates : Templates
    centres_mm : ndarray, shape (N, 2)
        Working centres on the sheet, template mm.
    theta_rad : ndarray, shape (N,)
        Rotation of each template on the sheet (its photo +x axis), radians.
    points_mm : ndarray, shape (P, 2)
        Every point on the sheet: centres where laid, the others intersected
        from all their rays (least squares); nan if fewer than two rays.
    n_rays : ndarray of int, shape (P,)
    triangle_mm : ndarray, shape (P, 3, 2)
        Error-triangle vertices at points with exactly three rays (nan elsewhere).
    triangle_sides_mm : ndarray, shape (P, 3)
    scale_residuals_mm : tuple of ndarray
        For each template laid from tie points: the perpendicular distances
        of the tie points from its rays after its scale was fixed.
    first_base_mm : float
        The laid length of the first base (the free strip's arbitrary scale).
    start : str
        ``"first"`` or ``"last"``: the template laying started from.
    """

    templates: Templates
    centres_mm: np.ndarray
    theta_rad: np.ndarray
    points_mm: np.ndarray
    n_rays: np.ndarray
    triangle_mm: np.ndarray
    triangle_sides_mm: np.ndarray
    scale_residuals_mm: tuple
    first_base_mm: float
    start: str

    @property
    def points(self) -> StripPoints:
        return self.templates.points

    @property
    def max_triangle_side_mm(self) -> float:
        return _largest_side(self.triangle_sides_mm)

    def ray_segments(self, extend: float = 1.15) -> np.ndarray:
        """Segments, shape (k, 2, 2), of every template ray from its centre to (a bit past) its point."""
        segs = []
        for t in range(self.templates.n_photos):
            idx, d = self.templates.rays(t)
            C = self.centres_mm[t]
            for i, a in zip(idx, d):
                P = self.points_mm[i]
                if not np.all(np.isfinite(P)):
                    continue
                L = float(np.hypot(*(P - C))) * extend
                segs.append([C, C + L * _u(a + self.theta_rad[t])])
        return np.array(segs) if segs else np.zeros((0, 2, 2))

    def table(self) -> pd.DataFrame:
        """Error triangles at the points intersected from three rays: sides and the 0.3 mm check."""
        idx = np.flatnonzero(np.all(np.isfinite(self.triangle_sides_mm), axis=1))
        s = self.triangle_sides_mm[idx]
        return pd.DataFrame(
            {
                "kind": [self.points.kinds[i] for i in idx],
                "side 1, mm": s[:, 0],
                "side 2, mm": s[:, 1],
                "side 3, mm": s[:, 2],
                "largest, mm": s.max(axis=1) if len(idx) else [],
                f"≤ {TRIANGLE_TOL_MM} mm": s.max(axis=1) <= TRIANGLE_TOL_MM if len(idx) else [],
            },
            index=pd.Index([self.points.names[i] for i in idx], name="point"),
        )

    def similarity_to_truth(self):
        """Best similarity from this strip to the ground truth (plan X, Y in m): (scale m/mm, R, t, residuals m)."""
        ok = np.all(np.isfinite(self.points_mm), axis=1)
        s, R, t = fit_similarity(self.points_mm[ok], self.points.XYZ_m[ok, :2])
        res = np.full(len(self.points_mm), np.nan)
        res[ok] = np.hypot(*((s * self.points_mm[ok] @ R.T + t) - self.points.XYZ_m[ok, :2]).T)
        return s, R, t, res


def _intersect_all(tmpl: Templates, centres, theta):
    P = len(tmpl.points)
    pts = np.full((P, 2), np.nan)
    nr = np.zeros(P, dtype=int)
    tri = np.full((P, 3, 2), np.nan)
    sides = np.full((P, 3), np.nan)
    own = set(tmpl.points.centre_index.tolist())
    for i in range(P):
        if i in own:
            continue
        ts = [t for t in range(tmpl.n_photos) if np.isfinite(tmpl.directions_rad[t, i]) and np.all(np.isfinite(centres[t]))]
        nr[i] = len(ts)
        if len(ts) < 2:
            continue
        O = centres[ts]
        A = tmpl.directions_rad[ts, i] + theta[ts]
        try:
            pts[i] = intersect_rays(O, A)
        except ValueError:
            continue
        if len(ts) == 3:
            tri[i], sides[i] = error_triangle(O, A)
    return pts, nr, tri, sides


def lay_free_strip(
    templates: Templates,
    *,
    first_base_mm: float | None = None,
    scale_ratio: float = 1.0,
    M: float = 10000.0,
    start: str = "first",
    method: str = "compromise",
) -> FreeStrip:
    """Lay the templates into a free strip in an arbitrary scale (guide §13 step 6).

    The first template goes down with its initial direction to the second
    along the sheet's +x.  The second is laid with its centre on that initial
    direction, its own initial direction back along it, at the chosen
    distance ``first_base_mm`` (the strip's arbitrary scale).  Every further
    template t goes with its centre on the initial direction from t − 1 and
    its initial direction back onto it (the rotation), and slides along that
    line until its rays to the tie points of the triple overlap t−2, t−1, t
    pass through their intersections from t − 2 and t − 1 (least squares
    over the tie points: the scale transfer).  Then every point is
    intersected from all its rays; at the tie points the three rays form an
    error triangle.

    Parameters
    ----------
    templates : Templates
    first_base_mm : float, optional
        Laid length of the first base, mm (0 < l ≤ 2000).  By default the true
        first base at the plan scale 1/M times ``scale_ratio``.
    scale_ratio : float
        The free strip's scale as a fraction of the plan scale (0.2 … 5); the
        reduction coefficient then comes out near 1/scale_ratio.  Used only
        when ``first_base_mm`` is not given.
    M : float
        Plan scale denominator (guide: 1/M = 1/10000).
    start : {"first", "last"}
        Lay from the first template (36 in §13) or from the last (39).
    method : {"compromise", "initial"}
        ``"initial"``: the rotation strictly from the initial direction and
        only the position along it from the tie points.  ``"compromise"``
        (default, the guide's "добиваясь совмещения рабочих центров с
        начальными направлениями и направлениями через связующие точки"):
        starting there, the centre and rotation are adjusted together so that
        the back initial direction passes through the previous centre, the
        centre lies on the previous initial direction and the rays pass
        through the tie points, all in the least-squares sense.
    """
    if method not in ("compromise", "initial"):
        raise ValueError(f"method = {method!r}; valid: 'compromise' or 'initial'")
    if start not in ("first", "last"):
        raise ValueError(f"start = {start!r}; valid: 'first' or 'last' (guide §13 step 6)")
    N = templates.n_photos
    if N < 3:
        raise ValueError(f"{N} templates; a strip needs at least 3")
    centres_idx = templates.points.centre_index
    order = list(range(N)) if start == "first" else list(range(N - 1, -1, -1))
    if first_base_mm is None:
        q = check_range("scale_ratio", scale_ratio, 0.2, 5.0, unit="free-strip scale / plan scale")
        Mv = check_positive("M", M)
        a, b = templates.points.XYZ_m[centres_idx[order[0]], :2], templates.points.XYZ_m[centres_idx[order[1]], :2]
        first_base_mm = float(np.hypot(*(b - a))) * 1000.0 / Mv * q
    else:
        first_base_mm = check_positive("first_base_mm", first_base_mm, unit="mm", hi=2000.0)
    D = templates.directions_rad
    C = np.full((N, 2), np.nan)
    th = np.full(N, np.nan)
    residuals = []
    t0, t1 = order[0], order[1]
    th[t0] = -D[t0, centres_idx[t1]]  # the initial direction 0 → 1 along +x
    C[t0] = 0.0
    fwd = D[t0, centres_idx[t1]] + th[t0]
    C[t1] = C[t0] + first_base_mm * _u(fwd)
    th[t1] = fwd + math.pi - D[t1, centres_idx[t0]]
    for k in range(2, N):
        ta, tb, tc = order[k - 2], order[k - 1], order[k]
        if not np.isfinite(D[tb, centres_idx[tc]]) or not np.isfinite(D[tc, centres_idx[tb]]):
            raise ValueError(f"the working centres of photos {tb + 1} and {tc + 1} are not pricked on each other: "
                             "the initial direction is missing (overlap too small?)")
        fwd = D[tb, centres_idx[tc]] + th[tb]
        th[tc] = fwd + math.pi - D[tc, centres_idx[tb]]
        uf = _u(fwd)
        own = set(centres_idx.tolist())
        ties = [i for i in range(len(templates.points)) if i not in own
                and np.isfinite(D[ta, i]) and np.isfinite(D[tb, i]) and np.isfinite(D[tc, i])]
        if not ties:
            raise ValueError(f"no tie point in the triple overlap of photos {ta + 1}, {tb + 1}, {tc + 1}: "
                             "the next template's scale cannot be transferred")
        a_, c_ = [], []
        for i in ties:
            T = intersect_rays(C[[ta, tb]], np.array([D[ta, i] + th[ta], D[tb, i] + th[tb]]))
            w = _u(D[tc, i] + th[tc])
            a_.append(_cross(w, T - C[tb]))
            c_.append(_cross(w, uf))
        a_, c_ = np.array(a_), np.array(c_)
        s = float(np.dot(a_, c_) / np.dot(c_, c_))
        C[tc] = C[tb] + s * uf
        if method == "compromise":
            # the guide's "добиваясь совмещения": centre on the initial direction, the initial
            # direction back through the previous centre and the rays through the tie points, together
            Ts = [intersect_rays(C[[ta, tb]], np.array([D[ta, i] + th[ta], D[tb, i] + th[tb]])) for i in ties]
            idx = [centres_idx[tb]] + ties
            K = np.vstack([C[tb]] + Ts)
            C[tc], th[tc], r = resect(D[tc, idx], K, line=(C[tb], fwd), x0=(C[tc][0], C[tc][1], th[tc]))
            residuals.append(r)
        else:
            residuals.append(a_ - s * c_)
    pts, nr, tri, sides = _intersect_all(templates, C, th)
    pts[centres_idx] = C
    return FreeStrip(templates, C, th, pts, nr, tri, sides, tuple(residuals), float(first_base_mm), start)


# =========================================================================== reduction
def _plan_mm(XY_m, M, origin_m):
    return (np.asarray(XY_m, dtype=float) - origin_m) * 1000.0 / M


@dataclass(frozen=True)
class ReductionCoefficients:
    """Reduction coefficients per base (guide §7 table 8, §13 table 12).

    Attributes
    ----------
    bases : tuple of (str, str)
        The control-point pairs.
    l_base_mm : ndarray (B,)
        Distance on the base (основа), plan mm at 1/M, from the coordinates.
    l_template_mm : ndarray (B,)
        Distance on the free strip (общая восковка), template mm.
    k : ndarray (B,)
        k = l_base / l_template (guide's R in §7, k_ред in §13).
    k_mean : float
        Mean coefficient (the guide's "R составляет …", "средний k_ред").
    dk : ndarray (B,)
        Δk = k − k_mean (table 8's ΔK).
    short : ndarray of bool (B,)
        l_base < ``short_base_mm`` (see :data:`SHORT_BASE_MM`).
    tol : ndarray (B,)
        0.003, or 0.006 on a short base.
    """

    bases: tuple
    l_base_mm: np.ndarray
    l_template_mm: np.ndarray
    k: np.ndarray
    k_mean: float
    dk: np.ndarray
    short: np.ndarray
    tol: np.ndarray
    short_base_mm: float

    @property
    def ok(self) -> np.ndarray:
        """Per base: |Δk| within its tolerance."""
        return np.abs(self.dk) <= self.tol + 1e-12

    @property
    def spread(self) -> float:
        """The largest |Δk| (the guide's "колебания")."""
        return float(np.max(np.abs(self.dk)))

    @property
    def k_range(self) -> float:
        """max k − min k."""
        return float(np.max(self.k) - np.min(self.k))

    @property
    def all_ok(self) -> bool:
        return bool(np.all(self.ok))

    def table(self) -> pd.DataFrame:
        """Laid out like tables 8 and 12: base, l_осн, l_воск, k, Δk, tolerance, ok."""
        return pd.DataFrame(
            {
                "l_base (l_осн), mm": self.l_base_mm,
                "l_template (l_воск), mm": self.l_template_mm,
                "k": self.k,
                "Δk": self.dk,
                "short base": self.short,
                "tolerance": self.tol,
                "within": self.ok,
            },
            index=pd.Index([f"{a} – {b}" for a, b in self.bases], name="base"),
        )


def reduction_coefficients(names, base_mm, template_mm, *, pairs="all", short_base_mm: float = SHORT_BASE_MM,
                           tol: float = K_SPREAD_TOL, tol_short: float = K_SPREAD_TOL_SHORT) -> ReductionCoefficients:
    """Reduction coefficients k = l_base / l_template over pairs of control points (guide §7, §13 step 8).

    Parameters
    ----------
    names : sequence of str, length C
    base_mm : array_like, shape (C, 2)
        Control points on the base (plan mm).
    template_mm : array_like, shape (C, 2)
        The same points on the free strip (template mm).
    pairs : "all", "perimeter" or a sequence of (i, j) / (name, name)
        "all" — every pair, like table 12; "perimeter" — the closed ring
        0–1–…–(C−1)–0 in the given order, like table 8.
    """
    names = [str(n) for n in names]
    B = np.asarray(base_mm, dtype=float).reshape(-1, 2)
    T = np.asarray(template_mm, dtype=float).reshape(-1, 2)
    C = len(names)
    if C < 2 or len(B) != C or len(T) != C:
        raise ValueError(f"reduction needs at least 2 control points with base and template positions; got {C}, {len(B)}, {len(T)}")
    if isinstance(pairs, str):
        if pairs == "all":
            pr = [(i, j) for i in range(C) for j in range(i + 1, C)]
        elif pairs == "perimeter":
            pr = [(i, (i + 1) % C) for i in range(C)] if C > 2 else [(0, 1)]
        else:
            raise ValueError(f"pairs = {pairs!r}; valid: 'all', 'perimeter' or a list of pairs")
    else:
        pr = []
        for a, b in pairs:
            ia = names.index(a) if isinstance(a, str) else int(a)
            ib = names.index(b) if isinstance(b, str) else int(b)
            pr.append((ia, ib))
    lb = np.array([np.hypot(*(B[j] - B[i])) for i, j in pr])
    lt = np.array([np.hypot(*(T[j] - T[i])) for i, j in pr])
    if np.any(lt <= 0):
        raise ValueError("two control points coincide on the template: a base of zero length")
    k = lb / lt
    km = float(np.mean(k))
    short = lb < short_base_mm
    return ReductionCoefficients(tuple((names[i], names[j]) for i, j in pr), lb, lt, k, km, k - km, short,
                                 np.where(short, tol_short, tol), float(short_base_mm))


@dataclass(frozen=True)
class ReductionCorrections:
    """Corrections for reduction v = r·(k − 1) (guide §7 table 9, §13 table 13, formula 12.3).

    Attributes
    ----------
    names : tuple of str, length P
    centre : str
        The working centre taken as the centre of the whole strip (полюс).
    k : float
    r_mm : ndarray (P,)
        Distance from the centre to each point on the free strip, mm.
    v_mm : ndarray (P,)
        v = r·(k − 1): laid off away from the centre when positive, towards it when negative.
    """

    names: tuple
    centre: str
    k: float
    r_mm: np.ndarray
    v_mm: np.ndarray

    def table(self, wide: bool = False) -> pd.DataFrame:
        """Table 13's layout (one row a point); ``wide=True`` gives table 9's (one column a point)."""
        df = pd.DataFrame({"r, mm": self.r_mm, "v, mm": self.v_mm},
                          index=pd.Index(list(self.names), name=f"from centre {self.centre}"))
        return df.T if wide else df


def reduction_corrections(names, r_mm, k: float, centre: str = "") -> ReductionCorrections:
    """v = r·(k − 1) for given distances r (mm) and coefficient k (guide formula 12.3)."""
    kk = check_range("k", k, 0.0, 100.0, lo_open=True)
    r = np.asarray(r_mm, dtype=float)
    if np.any(r < 0):
        raise ValueError(f"r_mm has a negative value {float(r.min()):g}; the valid range is r_mm ≥ 0 (a distance)")
    return ReductionCorrections(tuple(str(n) for n in names), str(centre), kk, r, r * (kk - 1.0))


@dataclass(frozen=True)
class Reduction:
    """A free strip reduced to the plan (guide §13 steps 8–9).

    Attributes
    ----------
    strip : FreeStrip
    M : float
        Plan scale denominator.
    origin_m : ndarray (2,)
        Ground X, Y of the plan's origin (plan mm = (ground − origin)·1000/M).
    control : ndarray of int
        Indices of the control points used.
    coefficients : ReductionCoefficients
    corrections : ReductionCorrections
    centre_index : int
        Point index of the chosen central working centre.
    reduced_mm : ndarray (P, 2)
        Points moved by their corrections (still in the free strip's frame).
    rotation_deg : float, translation_mm : ndarray (2,)
        The rigid motion laying the corrected control points on the base.
    plan_mm : ndarray (P, 2)
        Every point on the plan after reduction, mm.
    truth_plan_mm : ndarray (P, 2)
        True positions on the plan, mm.
    """

    strip: FreeStrip
    M: float
    origin_m: np.ndarray
    control: np.ndarray
    coefficients: ReductionCoefficients
    corrections: ReductionCorrections
    centre_index: int
    reduced_mm: np.ndarray
    rotation_deg: float
    translation_mm: np.ndarray
    plan_mm: np.ndarray
    truth_plan_mm: np.ndarray

    @property
    def k(self) -> float:
        return self.coefficients.k_mean

    @property
    def base_control_mm(self) -> np.ndarray:
        """The control points on the base, plan mm, shape (C, 2)."""
        return self.truth_plan_mm[self.control]

    @property
    def control_residuals_mm(self) -> np.ndarray:
        """Length of (reduced control point on the plan − base), mm, shape (C,)."""
        return np.hypot(*(self.plan_mm[self.control] - self.base_control_mm).T)

    @property
    def errors_mm(self) -> np.ndarray:
        """Length of (reduced position − truth) for every point on the plan, mm, shape (P,)."""
        return np.hypot(*(self.plan_mm - self.truth_plan_mm).T)

    @property
    def max_control_residual_mm(self) -> float:
        return float(np.max(self.control_residuals_mm))

    @property
    def control_ok(self) -> bool:
        return bool(self.max_control_residual_mm <= CONTROL_TOL_MM)

    def to_strip_frame(self, plan_mm) -> np.ndarray:
        """Plan mm → the free strip's frame (undoing the rigid motion and the scaling about the centre)."""
        a = math.radians(self.rotation_deg)
        R = np.array([[math.cos(a), -math.sin(a)], [math.sin(a), math.cos(a)]])
        red = (np.asarray(plan_mm, dtype=float) - self.translation_mm) @ R
        C = self.strip.points_mm[self.centre_index]
        return C + (red - C) / self.k

    def table(self) -> pd.DataFrame:
        """Every point after reduction: r, v, plan x, y, error against the truth; control residuals checked."""
        pts = self.strip.points
        ctl = set(self.control.tolist())
        err = self.errors_mm
        return pd.DataFrame(
            {
                "kind": list(pts.kinds),
                "r, mm": self.corrections.r_mm,
                "v, mm": self.corrections.v_mm,
                "x plan, mm": self.plan_mm[:, 0],
                "y plan, mm": self.plan_mm[:, 1],
                "error, mm": err,
                f"control ≤ {CONTROL_TOL_MM} mm": [bool(err[i] <= CONTROL_TOL_MM) if i in ctl else None for i in range(len(pts))],
            },
            index=pd.Index(list(pts.names), name="point"),
        )


def reduce_strip(
    strip: FreeStrip,
    *,
    M: float = 10000.0,
    centre=None,
    pairs="all",
    control=None,
    origin_m=None,
    short_base_mm: float = SHORT_BASE_MM,
) -> Reduction:
    """Reduce a free strip to the plan scale and lay it on the base (guide §13 steps 8–9).

    1. the control points are plotted on the base from their coordinates
       (plan mm at 1/M); the distances between them on the base and on the
       free strip give k = l_base/l_template per base and the mean k
       (table 12), with the spread checked (≤ 0.003; ≤ 0.006 for short bases);
    2. one working centre is the centre of the whole strip (default: the
       middle one, "37 or 38"); from it every point's distance r and its
       correction v = r·(k − 1) (table 13) — positive v moves the point away
       from the centre, negative towards it: the points are scaled by k
       about the centre;
    3. the corrected strip is laid on the base by matching the corrected
       control points: the best rotation and shift (least squares; no further
       scaling), and the control residuals are checked against 0.4 mm.

    Where the centre is does not change the residuals — scaling about another
    point differs by a shift, which step 3 absorbs; it only changes the
    corrections one has to lay off (smallest about a middle centre).

    Parameters
    ----------
    strip : FreeStrip
    M : float
        Plan scale denominator (1/M; guide 1/10000), 100 ≤ M ≤ 1e6.
    centre : int or str, optional
        The central working centre: template index (0-based) or its name.
    pairs : see :func:`reduction_coefficients`.
    control : sequence of str, optional
        Names of the control points to use (default: all intersected ones).
    origin_m : (2,), optional
        Ground X, Y of the plan origin (default: the first control point
        rounded down to 100 m).
    """
    Mv = check_range("M", M, 100.0, 1e6, unit="plan scale denominator")
    pts = strip.points
    N = strip.templates.n_photos
    cidx = pts.centre_index
    if centre is None:
        ci = int(cidx[(N - 1) // 2])
    elif isinstance(centre, str):
        ci = pts.index(centre)
        if pts.kinds[ci] != "centre":
            raise ValueError(f"centre = {centre!r} is a {pts.kinds[ci]}; the reduction centre must be a working centre")
    else:
        t = check_int_range("centre", centre, 0, N - 1)
        ci = int(cidx[t])
    ok = np.all(np.isfinite(strip.points_mm), axis=1)
    if control is None:
        ctl = np.array([i for i in np.flatnonzero(pts.mask("control")) if ok[i]], dtype=int)
    else:
        ctl = np.array([pts.index(n) for n in control], dtype=int)
        bad = [pts.names[i] for i in ctl if not ok[i]]
        if bad:
            raise ValueError(f"control points {bad} are not intersected on the free strip (fewer than two rays)")
    if len(ctl) < 2:
        raise ValueError(f"{len(ctl)} control point(s) on the free strip; the reduction needs at least 2")
    XY = pts.XYZ_m[:, :2]
    if origin_m is None:
        origin = np.floor(XY[ctl[0]] / 100.0) * 100.0
    else:
        origin = np.asarray(origin_m, dtype=float).reshape(2)
    truth_plan = _plan_mm(XY, Mv, origin)
    coef = reduction_coefficients([pts.names[i] for i in ctl], truth_plan[ctl], strip.points_mm[ctl], pairs=pairs,
                                  short_base_mm=short_base_mm)
    k = coef.k_mean
    Cc = strip.points_mm[ci]
    r = np.hypot(*(strip.points_mm - Cc).T)
    corr = ReductionCorrections(pts.names, pts.names[ci], k, r, r * (k - 1.0))
    reduced = Cc + k * (strip.points_mm - Cc)
    R, t = fit_rigid(reduced[ctl], truth_plan[ctl])
    plan = reduced @ R.T + t
    rot = math.degrees(math.atan2(R[1, 0], R[0, 0]))
    return Reduction(strip, Mv, origin, ctl, coef, corr, ci, reduced, rot, t, plan, truth_plan)


# =========================================================================== §7: from both ends
@dataclass(frozen=True)
class EndsStrip:
    """A strip built on the plan from both ends towards the middle (guide §7, figure 16).

    Attributes
    ----------
    templates : Templates
    M : float
    origin_m : ndarray (2,)
    centres_mm : ndarray (N, 2), theta_rad : ndarray (N,)
        Final (adjusted) positions and rotations of the templates on the plan.
    mid : int
        Index of the middle template (the one with two solutions).
    mid_left_mm, mid_right_mm : ndarray (2,)
        Its two solutions 3′ (from the left) and 3″ (from the right).
    mid_theta_left_rad, mid_theta_right_rad : float
    mid_ties : ndarray of int
        Tie points around the middle centre (the guide's m and n).
    ties_left_mm, ties_right_mm : ndarray (k, 2)
        Those tie points from the left and from the right.
    mid_ray_misfit_mm : ndarray (k,)
        After the middle template is centred on 3 (the midpoint), the
        distances of its rays from m and n (guide: ≤ 0.3 mm).
    end_residuals_mm : tuple of ndarray
        Resection residuals of the first and last templates on their control points.
    points_mm : ndarray (P, 2)
        Every point on the plan, mm (centres as laid; others intersected).
    truth_plan_mm : ndarray (P, 2)
    triangle_sides_mm : ndarray (P, 3)
    triangle_mm : ndarray (P, 3, 2)
        Error-triangle vertices at the points with three rays (nan elsewhere).
    """

    templates: Templates
    M: float
    origin_m: np.ndarray
    centres_mm: np.ndarray
    theta_rad: np.ndarray
    mid: int
    mid_left_mm: np.ndarray
    mid_right_mm: np.ndarray
    mid_theta_left_rad: float
    mid_theta_right_rad: float
    mid_ties: np.ndarray
    ties_left_mm: np.ndarray
    ties_right_mm: np.ndarray
    mid_ray_misfit_mm: np.ndarray
    end_residuals_mm: tuple
    points_mm: np.ndarray
    truth_plan_mm: np.ndarray
    triangle_sides_mm: np.ndarray
    triangle_mm: np.ndarray

    @property
    def points(self) -> StripPoints:
        return self.templates.points

    @property
    def max_triangle_side_mm(self) -> float:
        return _largest_side(self.triangle_sides_mm)

    @property
    def mid_discrepancy_mm(self) -> float:
        """|3′ − 3″|: the discrepancy (невязка) of the middle centre, mm."""
        return float(np.hypot(*(self.mid_left_mm - self.mid_right_mm)))

    @property
    def tie_discrepancies_mm(self) -> np.ndarray:
        """|m′ − m″|, |n′ − n″|, mm."""
        return np.hypot(*(self.ties_left_mm - self.ties_right_mm).T)

    @property
    def errors_mm(self) -> np.ndarray:
        """|position on the plan − truth| for every point, mm."""
        return np.hypot(*(self.points_mm - self.truth_plan_mm).T)

    def table(self) -> pd.DataFrame:
        """Every point: plan position, error against truth, largest error-triangle side."""
        pts = self.templates.points
        s = self.triangle_sides_mm
        big = np.where(np.any(np.isfinite(s), axis=1), np.nanmax(np.where(np.isfinite(s), s, -1.0), axis=1), np.nan)
        return pd.DataFrame(
            {"kind": list(pts.kinds), "x plan, mm": self.points_mm[:, 0], "y plan, mm": self.points_mm[:, 1],
             "error, mm": self.errors_mm, "largest triangle side, mm": big},
            index=pd.Index(list(pts.names), name="point"),
        )

    def summary(self) -> pd.DataFrame:
        """The middle template's two solutions and the adjustment (guide §7)."""
        rows = [("middle centre 3′ − 3″ (невязка)", "mm", self.mid_discrepancy_mm)]
        names = self.templates.points.names
        for i, d in zip(self.mid_ties, self.tie_discrepancies_mm):
            rows.append((f"tie point {names[i]}: left − right", "mm", float(d)))
        for i, d in zip(self.mid_ties, self.mid_ray_misfit_mm):
            rows.append((f"middle template's ray misses {names[i]} by", "mm", float(abs(d))))
        rows.append(("largest error-triangle side", "mm", float(np.nanmax(self.triangle_sides_mm))
                     if np.any(np.isfinite(self.triangle_sides_mm)) else 0.0))
        rows.append(("largest error of a point on the plan", "mm", float(np.max(self.errors_mm))))
        return pd.DataFrame(rows, columns=["quantity", "unit", "value"]).set_index("quantity")


def _circmean(a, b):
    return math.atan2(math.sin(a) + math.sin(b), math.cos(a) + math.cos(b))


def build_from_ends(templates: Templates, *, M: float = 10000.0, origin_m=None) -> EndsStrip:
    """Build the strip on the plan from both ends to the middle (guide §7, figures 15–16).

    1. The first and last templates are set on the plan by resection from
       their control points (at least three each; ``control_layout="ends"``
       gives four);
    2. going inwards, each next template is resected from the known points
       its rays reach — the previous centre, control points already on the
       plan and the tie points intersected so far — with its centre on the
       previous template's initial direction;
    3. the middle template is solved twice, from the left (3′) and from the
       right (3″), each with its pair of tie points (m′, n′ and m″, n″); the
       most probable positions are the midpoints of the discrepancies;
    4. adjustment: the middle template is centred on 3 and turned to the mean
       of its two rotations (its rays should miss m and n by ≤ 0.3 mm); its
       neighbours are resected again on both sides' centres and tie points;
       every point is intersected from all its rays and the error triangles
       are measured.

    Returns
    -------
    EndsStrip (plan mm at 1/M).
    """
    Mv = check_range("M", M, 100.0, 1e6, unit="plan scale denominator")
    pts = templates.points
    N = templates.n_photos
    if N < 3:
        raise ValueError(f"{N} templates; building from both ends needs at least 3")
    D = templates.directions_rad
    cidx = pts.centre_index
    own = set(cidx.tolist())
    ctl = np.flatnonzero(pts.mask("control"))
    XY = pts.XYZ_m[:, :2]
    origin = np.floor(XY[ctl[0]] / 100.0) * 100.0 if origin_m is None else np.asarray(origin_m, float).reshape(2)
    truth = _plan_mm(XY, Mv, origin)
    known = {int(i): truth[i] for i in ctl}  # control points are on the plan from their coordinates

    C = np.full((N, 2), np.nan)
    th = np.full(N, np.nan)
    end_res = []
    for t in (0, N - 1):
        idx = [i for i in ctl if np.isfinite(D[t, i])]
        if len(idx) < 3:
            raise ValueError(f"photo {pts.photo_numbers[t]} has {len(idx)} control point(s); a resection needs at least 3 "
                             "(use design_points(..., control_layout='ends'), guide §7)")
        C[t], th[t], r = resect(D[t, idx], truth[idx])
        end_res.append(r)

    def rays_to(t, i):
        return np.isfinite(D[t, i])

    def solve_side(seq, kn):
        """Resect templates in ``seq`` (inwards) using and extending the dict of known points ``kn``."""
        Cs, ths = {seq[0]: C[seq[0]]}, {seq[0]: th[seq[0]]}
        kn = dict(kn)
        kn[int(cidx[seq[0]])] = C[seq[0]]
        for a, b in zip(seq[:-1], seq[1:]):
            idx = [i for i in kn if rays_to(b, i)]
            line = (Cs[a], D[a, cidx[b]] + ths[a]) if rays_to(a, cidx[b]) else None
            if len(idx) < 3:
                raise ValueError(f"template {pts.photo_numbers[b]} reaches {len(idx)} known point(s); need at least 3")
            Cb, tb, _ = resect(D[b, idx], np.array([kn[i] for i in idx]), line=line)
            Cs[b], ths[b] = Cb, tb
            kn[int(cidx[b])] = Cb
            # intersect the points both a and b see that are not known yet (tie points, orienting points)
            for i in range(len(pts)):
                if i in kn or i in own:
                    continue
                if rays_to(a, i) and rays_to(b, i):
                    kn[i] = intersect_rays(np.array([Cs[a], Cb]), np.array([D[a, i] + ths[a], D[b, i] + tb]))
        return Cs, ths, kn

    mid = N // 2
    left_seq = list(range(0, mid + 1))
    right_seq = list(range(N - 1, mid - 1, -1))
    Cl, thl, knl = solve_side(left_seq, known)
    Cr, thr, knr = solve_side(right_seq, known)
    for t in left_seq[:-1]:
        C[t], th[t] = Cl[t], thl[t]
    for t in right_seq[:-1]:
        C[t], th[t] = Cr[t], thr[t]
    # the middle template: two solutions, the midpoint
    C[mid] = 0.5 * (Cl[mid] + Cr[mid])
    th[mid] = _circmean(thl[mid], thr[mid])
    # its tie points m, n: the triple overlap centred on the middle photo
    mid_ties = np.array([i for i in range(len(pts)) if pts.kinds[i] == "tie" and pts.photo[i] == mid
                         and i in knl and i in knr], dtype=int)
    if len(mid_ties) == 0:  # an even strip: ties of the overlap next to the middle
        mid_ties = np.array([i for i in range(len(pts)) if pts.kinds[i] == "tie" and i in knl and i in knr
                             and rays_to(mid, i)], dtype=int)
    tl = np.array([knl[i] for i in mid_ties]).reshape(-1, 2)
    tr = np.array([knr[i] for i in mid_ties]).reshape(-1, 2)
    tmid = 0.5 * (tl + tr)
    misfit = np.array([_cross(_u(D[mid, i] + th[mid]), tmid[j] - C[mid]) for j, i in enumerate(mid_ties)])
    # adjustment of the other inner templates: resect again on every known point on both sides
    final_known = dict(known)
    for i in set(knl) | set(knr):
        if i in knl and i in knr:
            final_known[i] = 0.5 * (np.asarray(knl[i]) + np.asarray(knr[i]))
        else:
            final_known[i] = knl[i] if i in knl else knr[i]
    for j, i in enumerate(mid_ties):
        final_known[int(i)] = tmid[j]
    final_known[int(cidx[mid])] = C[mid]
    for t in range(1, N - 1):
        if t == mid:
            continue
        idx = [i for i in final_known if rays_to(t, i) and i != int(cidx[t])]
        C[t], th[t], _ = resect(D[t, idx], np.array([final_known[i] for i in idx]), x0=(C[t][0], C[t][1], th[t]))
    P, nr, tri, sides = _intersect_all(templates, C, th)
    P[cidx] = C
    lone = [i for i in ctl if not np.all(np.isfinite(P[i]))]
    P[lone] = truth[lone]  # control points seen on one photo only: on the plan from their coordinates
    return EndsStrip(templates, Mv, origin, C, th, mid, Cl[mid], Cr[mid], thl[mid], thr[mid], mid_ties, tl, tr,
                     misfit, tuple(end_res), P, truth, sides, tri)


# =========================================================================== Zhukov (13.1)
ZHUKOV_READING = """\
Guide §13, formula (13.1), as scanned:  m = 0.25·k_i·b_ср·(m_ε/ρ′)·√(n⁰ + 11n + 34).
A radicand n⁰ + 11n + 34 = 11n + 35 cannot be meant, and the book reads it as

    m = 0.25 · k_i · b_ср · (m_ε / ρ′) · √(n³ + 11n + 34)

(the superscript 3 scanned as 0).  Why:

1. Error propagation.  In a radial strip every template carries the strip's
   azimuth on to the next through its initial directions, so independent
   direction errors add up as a random walk of the azimuth, and the lateral
   position — the sum of the azimuths times the base — as a walk of a walk.
   With both ends held by control points (the strip fitted to them), the
   variance at the middle of n bases is exactly (n³ + 2n)/48 per unit
   azimuth-transfer variance (see :func:`bridge_variance_factor`): a cubic
   with no n² term, like n³ + 11n + 34.  A transfer error of √3·m_ε per base
   (the back and forward initial directions and the laying) gives
   √(3/48) = 0.25, the formula's own coefficient.  The terms 11n + 34 are
   the errors that do not accumulate (intersection and pricking of the point
   itself, control points).  Romanovsky's accumulation law in the accuracy
   article (seed 001, formula 10.20, with "replace n by n/2 and halve" for
   the middle of a strip tied at both ends) likewise grows as n^(3/2).
   A radicand 11n + 35 would make the error grow like √n only — as if the
   errors did not carry from template to template.
2. The guide's own inputs: m = 0.35 mm, k_i ≈ 1, b ≈ 60 mm, m_ε = 4′–5′
   give n ≈ 5.5–6.6, i.e. control points every 5–6 bases — the usual
   spacing for graphical radial triangulation.  With n² the same inputs
   would give 10–14 bases, with n⁰ 20–33 bases, both far beyond what a
   graphical strip holds (our simulation, :func:`accumulation_study`, shows
   the reduced strip's errors pass 0.35 mm within a few bases at 0.1 mm
   pricking).
"""


def zhukov_radicand(n, reading: str = "n3"):
    """The radicand of (13.1): ``"n3"`` n³ + 11n + 34 (the book's reading), ``"n2"`` n² + 11n + 34,
    ``"n0"`` n⁰ + 11n + 34 (as scanned)."""
    n = np.asarray(n, dtype=float)
    if reading == "n3":
        return n**3 + 11.0 * n + 34.0
    if reading == "n2":
        return n**2 + 11.0 * n + 34.0
    if reading == "n0":
        return 1.0 + 11.0 * n + 34.0
    raise ValueError(f"reading = {reading!r}; valid: 'n3' (n³ + 11n + 34), 'n2', 'n0'")


RHO_ARCMIN = 180.0 * 60.0 / math.pi  # ρ′ = 3437.75′


def zhukov_error_mm(n, *, k_i: float = 1.0, b_mm: float = 60.0, m_eps_arcmin: float = 4.5, reading: str = "n3"):
    """Zhukov's formula (13.1): RMS error m of an orienting point in the middle of n bases, mm.

        m = 0.25 · k_i · b · (m_ε / ρ′) · √(n³ + 11n + 34)

    Parameters
    ----------
    n : array_like
        Number of photo bases between the outermost control points (n ≥ 1).
    k_i : float
        Transformation (enlargement) coefficient from the photo to the plan
        scale, e.g. m/M = 12000/10000 = 1.2 (guide: k_i).
    b_mm : float
        Mean photo base b_ср, mm (guide: ≈ 60 mm at p_x = 60 %).
    m_eps_arcmin : float
        RMS error of a central direction m_ε, arc-minutes (guide: 4′–5′).
    reading : see :func:`zhukov_radicand`.
    """
    k = check_positive("k_i", k_i)
    b = check_positive("b_mm", b_mm, unit="mm")
    me = check_positive("m_eps_arcmin", m_eps_arcmin, unit="arc-minutes")
    nn = np.asarray(n, dtype=float)
    if np.any(nn < 1):
        raise ValueError(f"n = {float(nn.min()):g} is outside the valid range n ≥ 1 (bases between control points)")
    out = 0.25 * k * b * (me / RHO_ARCMIN) * np.sqrt(zhukov_radicand(nn, reading))
    return float(out) if out.ndim == 0 else out


def zhukov_bases_continuous(m_allowed_mm: float = 0.35, *, k_i: float = 1.0, b_mm: float = 60.0,
                            m_eps_arcmin: float = 4.5, reading: str = "n3") -> float:
    """The real n ≥ 1 at which (13.1) reaches ``m_allowed_mm`` (bisection); 1.0 if already exceeded at n = 1."""
    m_allowed = check_positive("m_allowed_mm", m_allowed_mm, unit="mm")
    f = lambda n: zhukov_error_mm(n, k_i=k_i, b_mm=b_mm, m_eps_arcmin=m_eps_arcmin, reading=reading) - m_allowed  # noqa: E731
    lo, hi = 1.0, 2.0
    if f(lo) > 0:
        return 1.0
    while f(hi) <= 0:
        hi *= 2.0
        if hi > 1e7:
            raise ValueError("the allowed error is never reached: check the inputs")
    for _ in range(100):
        mid = 0.5 * (lo + hi)
        lo, hi = (mid, hi) if f(mid) <= 0 else (lo, mid)
    return 0.5 * (lo + hi)


def zhukov_max_bases(m_allowed_mm: float = 0.35, *, k_i: float = 1.0, b_mm: float = 60.0, m_eps_arcmin: float = 4.5,
                     reading: str = "n3") -> int:
    """The largest whole number of bases n between control points with (13.1) ≤ ``m_allowed_mm`` (guide §13 step 1).

    Returns 0 when even one base exceeds the allowed error.
    """
    n = zhukov_bases_continuous(m_allowed_mm, k_i=k_i, b_mm=b_mm, m_eps_arcmin=m_eps_arcmin, reading=reading)
    k = int(math.floor(n + 1e-9))
    if k <= 1 and zhukov_error_mm(1, k_i=k_i, b_mm=b_mm, m_eps_arcmin=m_eps_arcmin, reading=reading) > m_allowed_mm:
        return 0
    return k


def bridge_variance_factor(n: int) -> float:
    """Variance at the middle of a chain of n bases held at both ends, per unit azimuth-transfer variance.

    Model: independent azimuth errors ε_1 … ε_n, one per base; the azimuth of
    base j is θ_j = ε_1 + … + ε_j and the lateral offset of point k is
    y_k = b·(θ_1 + … + θ_k); fitting the chain to its end points removes
    (k/n)·y_n.  Returns Var(y_{n/2} − y_n/2) / (b²σ²) computed exactly from
    the coefficients, which equals (n³ + 2n)/48 for even n.
    """
    n = check_int_range("n", n, 1, 100000)
    lo, hi = n // 2, (n + 1) // 2  # the middle point (interpolated between two for odd n)
    tot = 0.0
    for i in range(1, n + 1):
        c_mid = 0.5 * (max(0, lo - i + 1) + max(0, hi - i + 1))
        c_end = n - i + 1
        tot += (c_mid - 0.5 * c_end) ** 2
    return tot


# =========================================================================== guide's tables
#: guide §7: the control points (X north, Y east in the Russian geodetic convention), metres
GUIDE_S7_CONTROL = {
    "496/1": (6067202.0, 310574.0),
    "496/2": (6065910.0, 310466.0),
    "498/1": (6066967.0, 312528.0),
    "498/2": (6065525.0, 312664.0),
}

#: guide §7, table 8 as printed: (from, to, l_осн mm, l_воск mm, K, ΔK)
GUIDE_TABLE8 = (
    ("496/1", "498/1", 197.0, 190.0, 1.037, 0.000),
    ("498/1", "498/2", 145.0, 140.0, 1.036, -0.001),
    ("498/2", "496/2", 222.0, 217.0, 1.037, 0.000),
    ("496/2", "496/1", 131.0, 126.0, 1.038, +0.001),
)
#: guide §7: "R составляет 1,037"
GUIDE_TABLE8_MEAN = 1.037

#: guide §7, table 9 as printed: k and, per column, the (garbled) label, r (mm) and v (mm)
GUIDE_TABLE9 = {
    "k": 1.037,
    "labels": ("496", "498", "7/967", "496/1", "7/867", "498/1", "7/267", "497/1", "7/967", "496/1", "7/867", "498/1"),
    "r_mm": (54, 72, 26, 40, 61, 76, 65, 35, 96, 40, 133, 96),
    "v_mm": (2.0, 2.7, 1.0, 1.5, 2.3, 2.8, 2.4, 1.3, 3.6, 1.5, 4.9, 3.6),
}


@dataclass(frozen=True)
class Discrepancy:
    """One printed number of the guide against the number its own inputs give."""

    where: str
    quantity: str
    printed: float
    computed: float
    agrees: bool
    note: str


@dataclass(frozen=True)
class GuideCheck:
    """A guide table recomputed from its printed inputs, with printed vs computed for every number."""

    title: str
    computed: pd.DataFrame
    checks: tuple = field(default_factory=tuple)
    notes: tuple = field(default_factory=tuple)

    @property
    def discrepancies(self) -> tuple:
        """The checks whose printed number does not follow from its inputs."""
        return tuple(c for c in self.checks if not c.agrees)

    def table(self) -> pd.DataFrame:
        """The recomputed table (laid out like the guide's)."""
        return self.computed

    def comparison(self, only_discrepancies: bool = False) -> pd.DataFrame:
        """Printed vs computed, one row per number checked."""
        rows = [c for c in self.checks if not (only_discrepancies and c.agrees)]
        return pd.DataFrame(
            {"quantity": [c.quantity for c in rows], "printed": [c.printed for c in rows],
             "computed": [c.computed for c in rows], "agrees": [c.agrees for c in rows], "note": [c.note for c in rows]},
            index=pd.Index([c.where for c in rows], name="where"),
        )


def _agree(printed: float, computed: float, decimals: int) -> bool:
    """The printed value is the computed one rounded to the printed decimals (half a unit of the last digit)."""
    return abs(printed - computed) <= 0.5 * 10.0 ** (-decimals) + 1e-9


def guide_table8(M: float = 10000.0) -> GuideCheck:
    """Table 8 (guide §7) recomputed from its inputs: the control coordinates at 1:10000 and the printed l_воск.

    Checks every printed l_осн against the coordinates, every K against
    l_осн/l_воск (both with the printed and with the computed l_осн), the
    mean, the ΔK column and the 0.003 rule.
    """
    Mv = check_positive("M", M)
    checks, rows = [], []
    k_printed_l, k_coord = [], []
    for a, b, l_osn, l_vosk, K, dK in GUIDE_TABLE8:
        pa, pb = np.array(GUIDE_S7_CONTROL[a]), np.array(GUIDE_S7_CONTROL[b])
        L_m = float(np.hypot(*(pb - pa)))
        l_c = L_m * 1000.0 / Mv
        where = f"table 8, {a} – {b}"
        checks.append(Discrepancy(where, "l_осн, mm", l_osn, round(l_c, 2), _agree(l_osn, l_c, 0),
                                  f"L = {L_m:.1f} m from the coordinates → {l_c:.2f} mm at 1:{Mv:.0f}"))
        kp = l_osn / l_vosk
        kc = l_c / l_vosk
        checks.append(Discrepancy(where, "K = l_осн/l_воск (printed l_осн)", K, round(kp, 4), _agree(K, kp, 3),
                                  f"{l_osn:g} / {l_vosk:g} = {kp:.4f}"))
        k_printed_l.append(kp)
        k_coord.append(kc)
        rows.append((f"{a} – {b}", L_m, l_c, l_osn, l_vosk, kc, kp, K, dK))
    kp_arr, kc_arr = np.array(k_printed_l), np.array(k_coord)
    K_printed = np.array([r[4] for r in GUIDE_TABLE8])
    checks.append(Discrepancy("table 8, mean", "mean of the printed K", GUIDE_TABLE8_MEAN, round(float(K_printed.mean()), 4),
                              _agree(GUIDE_TABLE8_MEAN, K_printed.mean(), 3), "the printed K do average 1.037"))
    checks.append(Discrepancy("table 8, mean", "mean K = l_осн/l_воск (printed l_осн)", GUIDE_TABLE8_MEAN,
                              round(float(kp_arr.mean()), 4), _agree(GUIDE_TABLE8_MEAN, kp_arr.mean(), 3),
                              "mean of the recomputed coefficients"))
    dk_p = kp_arr - kp_arr.mean()
    for (a, b, *_r, dK), d in zip(GUIDE_TABLE8, dk_p):
        checks.append(Discrepancy(f"table 8, {a} – {b}", "ΔK (printed l_осн)", dK, round(float(d), 4), _agree(dK, d, 3),
                                  "K − mean K"))
    spread_p = float(np.max(np.abs(dk_p)))
    spread_c = float(np.max(np.abs(kc_arr - kc_arr.mean())))
    checks.append(Discrepancy("table 8, spread", "largest |ΔK| (printed l_осн) ≤ 0.003?", max(abs(r[5]) for r in GUIDE_TABLE8),
                              round(spread_p, 4), spread_p <= K_SPREAD_TOL,
                              "the printed ΔK stay within 0.003; recomputed they do not"))
    checks.append(Discrepancy("table 8, spread", "largest |ΔK| (l_осн from coordinates) ≤ 0.003?",
                              max(abs(r[5]) for r in GUIDE_TABLE8), round(spread_c, 4), spread_c <= K_SPREAD_TOL,
                              "with the distances from the coordinates"))
    df = pd.DataFrame(rows, columns=["base", "L from coordinates, m", "l_осн from coordinates, mm", "l_осн printed, mm",
                                     "l_воск printed, mm", "k (l_осн from coordinates)", "k (printed l_осн)",
                                     "K printed", "ΔK printed"]).set_index("base")
    df["Δk (from coordinates)"] = kc_arr - kc_arr.mean()
    notes = (
        f"mean k from the coordinates: {kc_arr.mean():.4f}; from the printed l_осн: {kp_arr.mean():.4f}; printed R = 1.037",
        "the guide's rows are the four sides of the quadrilateral 496/1 → 498/1 → 498/2 → 496/2 → 496/1",
    )
    return GuideCheck("Guide §7, table 8: reduction coefficients", df, tuple(checks), notes)


def guide_table9() -> GuideCheck:
    """Table 9 (guide §7) recomputed: v = r·(k − 1) with the printed r and k = 1.037.

    Also checks the printed distances against table 8's template: a point
    cannot be nearer the centre than allows the distance between two control
    points on the template (triangle inequality r_a + r_b ≥ l_воск(a, b)).
    """
    k = GUIDE_TABLE9["k"]
    labels, r, v = GUIDE_TABLE9["labels"], np.array(GUIDE_TABLE9["r_mm"], float), np.array(GUIDE_TABLE9["v_mm"], float)
    corr = reduction_corrections([f"{j + 1}: {lab}" for j, lab in enumerate(labels)], r, k, centre="(not named)")
    checks = []
    for j, (lab, rr, vp, vc) in enumerate(zip(labels, r, v, corr.v_mm)):
        checks.append(Discrepancy(f"table 9, column {j + 1} ({lab})", "v = r·(k − 1), mm", vp, round(float(vc), 3),
                                  _agree(vp, vc, 1), f"{rr:g} × {k - 1:.3f} = {vc:.3f}"))
    # consistency with table 8: 496/1 and 498/1 are 190 mm apart on the template
    l_vosk = {frozenset((a, b)): lv for a, b, _lo, lv, _k, _d in GUIDE_TABLE8}
    by_label = {}
    for lab, rr in zip(labels, r):
        by_label.setdefault(lab, []).append(rr)
    for (a, b), lv in ((tuple(sorted(p)), l) for p, l in l_vosk.items()):
        if a in by_label and b in by_label:
            best = max(by_label[a]) + max(by_label[b])
            checks.append(Discrepancy(f"table 9 vs table 8, {a} and {b}", "r_a + r_b ≥ l_воск(a, b)?", lv, best,
                                      best >= lv, f"largest printed r_a + r_b = {best:g} mm against l_воск = {lv:g} mm"))
    for lab, rs in by_label.items():
        if len(rs) > 1 and len(set(rs)) > 1:
            checks.append(Discrepancy(f"table 9, label {lab}", "one point, one distance?", rs[0], rs[1], False,
                                      f"the label appears {len(rs)} times with r = {', '.join(f'{x:g}' for x in rs)} mm"))
    df = corr.table(wide=True)
    df.loc["v printed, mm"] = v
    notes = (
        "every printed v is r·(k − 1) rounded to 0.1 mm",
        "the point labels are garbled in the scan (7/967, 7/867 … repeat); 496/1 appears twice and 498/1 twice with "
        "different r, and no centre can be 40 mm from 496/1 and at most 96 mm from 498/1 when the two are 190 mm apart "
        "on the template (table 8)",
    )
    return GuideCheck("Guide §7, table 9: corrections for reduction", df, tuple(checks), notes)


# =========================================================================== accumulation
def accumulation_study(n_bases=(2, 3, 4, 5, 6, 8), seeds=range(20), *, pricking_mm: float = PRICKING_MM,
                       f_mm: float = 100.0, m: float = 12000.0, M: float = 10000.0, overlap_percent: float = 60.0):
    """Monte Carlo: errors of reduced free strips against the number of bases between the control points.

    Vertical photos over flat ground along +X (so every error comes from the
    pricking), control points in the first and last overlaps (guide §13).

    Returns
    -------
    pandas.DataFrame, one row per n: the RMS error of the orienting points
    and working centres on the plan after reduction (mm), the RMS control
    residual (mm), the RMS largest error-triangle side (template mm), the
    strip's k range — over the seeds.
    """
    cam = g.Camera(f_mm)
    H = f_mm / 1000.0 * m
    B = (1.0 - overlap_percent / 100.0) * cam.frame_mm / 1000.0 * m
    rows = []
    for n in n_bases:
        n = check_int_range("n_bases", n, 2, 60)
        poses = [g.Pose(i * B, 0.0, H) for i in range(n + 1)]
        pts = design_points(cam, poses, None)
        inner = np.flatnonzero(pts.mask("orienting") | pts.mask("centre"))
        e, c, tri, rng_k = [], [], [], []
        for s in seeds:
            tm = measure_templates(cam, poses, pts, pricking_mm=pricking_mm, seed=int(s))
            fs = lay_free_strip(tm, M=M)
            red = reduce_strip(fs, M=M)
            e.append(np.sqrt(np.mean(red.errors_mm[inner] ** 2)))
            c.append(np.sqrt(np.mean(red.control_residuals_mm**2)))
            tri.append(fs.max_triangle_side_mm)
            rng_k.append(red.coefficients.k_range)
        rows.append((n, float(np.sqrt(np.mean(np.square(e)))), float(np.sqrt(np.mean(np.square(c)))),
                     float(np.sqrt(np.mean(np.square(tri)))), float(np.mean(rng_k))))
    return pd.DataFrame(rows, columns=["n bases", "RMS error of points, mm", "RMS control residual, mm",
                                       "RMS largest triangle side, mm", "mean k range"]).set_index("n bases")
