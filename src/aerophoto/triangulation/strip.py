"""Laying a free radial strip: its points, its direction templates and the templates laid (guide §7, §13 steps 2–7).

The guide builds a single-strip radial triangulation (одномаршрутный
фототриангуляционный ряд) with tracing paper: on every photo it pricks a
*working centre* (рабочий центр) near the principal point, *orienting points*
(ориентирующие точки) at the corners of the working area, *tie points*
(связующие точки) in the triple overlap and the *control points* (опознаки);
it draws a *direction template* (восковка направлений) — the rays from the
working centre to every pricked point — and lays the templates one on another.

1. :func:`design_points` chooses the points on a simulated strip (from a site
   catalogue when one is given, otherwise exact points on the terrain);
2. :func:`measure_templates` pricks them on every photo through the camera
   model (:func:`aerophoto.geometry.ground_to_photo`) with a seeded pricking
   error and measures the directions from each working centre;
3. :func:`lay_free_strip` lays the templates in an arbitrary scale (свободный
   ряд, §13 step 6): matching working centres and initial directions
   (начальные направления), the scale of every next template from the tie
   points, every point intersected from its rays (:func:`aerophoto.plane.intersect_rays`),
   the error triangles (треугольники погрешностей, :func:`aerophoto.plane.error_triangle`)
   at the tie points checked against 0.3 mm.

Photo coordinates and template directions are in mm on the photo, angles
counter-clockwise from the photo's +x axis; the free strip lives in its own
"template mm" frame (the tracing paper); ground in metres.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import _validate as V
from .. import geometry as g
from .. import plane
from .._validate import check_positive, check_range

__all__ = [
    "TRIANGLE_TOL_MM",
    "PRICKING_MM",
    "KINDS",
    "StripPoints",
    "Templates",
    "FreeStrip",
    "design_points",
    "measure_templates",
    "lay_free_strip",
]

#: the largest side of an error triangle at a tie point, template mm (guide §7, §13 step 6)
TRIANGLE_TOL_MM = 0.3
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



def _photo_to_ground(camera, pose, xy, terrain):
    """Photo points (mm) of ``pose`` → ground X, Y, Z (m) on ``terrain`` (flat: a plane; otherwise the DEM)."""
    t = g.as_terrain(terrain)
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


@V.checked(camera=g.Camera, poses=V.sequence(V.of_type(g.Pose), min_len=2), terrain=V.terrain(none=True))
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
    terrain = g.as_terrain(terrain)
    cat = _catalogue_arrays(catalogue)
    r_max = camera.f_mm / 30.0
    r_centre = min(r_max, float(centre_search_mm))

    o_next, o_prev = _photo_bases(camera, poses, terrain)
    specs = _design_specs(camera, numbers, o_next, o_prev, centre_offset_mm=centre_offset_mm, r_max=r_max,
                          control_layout=control_layout, side_overlap_percent=side_overlap_percent,
                          tie_from_edge_mm=tie_from_edge_mm)

    # a tie point must be seen on three photos: where tilts turn the photos against each other the triple
    # overlap's middle is not at x = 0 of photo t; slide the design position along the strip to the place
    # that keeps it furthest inside all three frames (only where x = 0 would come within 5 mm of an edge)
    for j, (name, kind, t, xy, control, exact) in enumerate(specs):
        if kind == "tie":
            specs[j] = (name, kind, t, _centre_in_overlap(camera, poses, terrain, t, xy, o_next[t]), control, exact)

    # exact terrain points at the design positions: one DEM intersection per photo
    ground = np.zeros((len(specs), 3))
    for t in range(N):
        rows = [j for j, sp in enumerate(specs) if sp[2] == t]
        if rows:
            ground[rows] = _photo_to_ground(camera, poses[t], np.array([specs[j][3] for j in rows]), terrain)

    XYZ, source = _catalogue_or_terrain(camera, poses, cat, specs, ground, search_radius_mm=search_radius_mm,
                                        r_centre=r_centre)
    names = _unique_names([sp[0] for sp in specs])
    kinds = tuple(sp[1] for sp in specs)
    photo = np.array([sp[2] for sp in specs], dtype=int)
    return StripPoints(names, kinds, XYZ, photo, source, numbers)


def _photo_bases(camera: g.Camera, poses: list, terrain) -> tuple:
    """The photo bases of a strip, measured on the photos: ``(o_next, o_prev)``.

    ``o_next[t]`` (shape (N − 1, 2), mm) is the image of photo t+1's principal point on photo t, ``o_prev[t]``
    (a dict for t = 1 … N − 1) that of photo t−1's.  The design geometry uses the plane of the mean height
    (the positions are nominal anyway).
    """
    N = len(poses)
    z_ref = 0.5 * (float(getattr(terrain, "z_min_m", 0.0)) + float(getattr(terrain, "z_max_m", 0.0)))
    O = np.array([g.photo_to_plane(camera, pose, np.zeros(2), z_ref) for pose in poses])
    o_next = np.array([g.ground_to_photo(camera, poses[t], O[t + 1]) for t in range(N - 1)])
    o_prev = {t: g.ground_to_photo(camera, poses[t], O[t - 1]) for t in range(1, N)}
    return o_next, o_prev


def _along(base, frac: float, y: float) -> np.ndarray:
    """Photo point at fraction ``frac`` of the photo ``base`` (mm, towards the next photo), offset ``y`` mm across
    (to the left of the base)."""
    d = base / np.hypot(*base)
    n = np.array([-d[1], d[0]])
    return frac * base + y * n


def _along_back(back, frac: float, y: float) -> np.ndarray:
    """Photo point at fraction ``frac`` of the base ``back`` towards the previous photo (mm), ``y`` mm to the left
    of the flight."""
    d = -back / np.hypot(*back)  # forward direction
    n = np.array([-d[1], d[0]])
    return frac * back + y * n


def _design_specs(camera: g.Camera, numbers: tuple, o_next, o_prev, *, centre_offset_mm, r_max: float,
                  control_layout: str, side_overlap_percent: float, tie_from_edge_mm: float) -> list:
    """The design positions of a strip's points (guide §13 steps 2–3; the layouts in :func:`design_points`).

    Returns a list of ``(name, kind, photo index, xy mm, control, exact)``: working centres, orienting points
    (Cyrillic letters), tie points (Latin letters) and control points (``first/1`` …), in that order.
    """
    N = len(numbers)
    half = camera.half_mm
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
            specs.append((lab, "orienting", t, _along(o_next[t], 0.5, sgn * y_side), False, False))
    tl = 0
    for t in range(1, N - 1):
        for sgn in (+1, -1):
            lab = _LAT[tl] if tl < len(_LAT) else f"t{tl + 1}"
            tl += 1
            specs.append((lab, "tie", t, _along(o_next[t], 0.0, sgn * y_tie), False, False))
    first, last = numbers[0], numbers[-1]
    head, tail = o_next[0], o_prev[N - 1]
    ctl = [(f"{first}/1", 0, _along(head, 0.25, +y_ctl)), (f"{first}/2", 0, _along(head, 0.25, -y_ctl)),
           (f"{last}/1", N - 1, _along_back(tail, 0.25, +y_ctl)),
           (f"{last}/2", N - 1, _along_back(tail, 0.25, -y_ctl))]
    if control_layout == "ends":
        ctl = ctl[:2] + [(f"{first}/3", 0, _along(head, -0.5, -y_ctl)), (f"{first}/4", 0, _along(head, -0.5, +y_ctl))] \
            + ctl[2:] + [(f"{last}/3", N - 1, _along_back(tail, -0.5, -y_ctl)),
                         (f"{last}/4", N - 1, _along_back(tail, -0.5, +y_ctl))]
    for lab, t, xy in ctl:
        specs.append((lab, "control", t, xy, True, False))
    return specs


def _catalogue_or_terrain(camera: g.Camera, poses: list, cat, specs: list, ground, *, search_radius_mm: float,
                          r_centre: float) -> tuple:
    """The ground point of every design position: the nearest usable catalogue point, else the exact terrain point.

    A catalogue point serves if it is imaged on every photo the design point must be seen on, at least
    :data:`_SEEN_MARGIN_MM` inside the frame, and lies within ``search_radius_mm`` of the design position
    (within ``r_centre`` of o for a working centre); each serves once; a control position prefers surveyed
    control points, other positions never take them.  Returns ``(XYZ, source)``: shape (n, 3) metres and
    ``"catalogue"``/``"terrain"`` per point.
    """
    N = len(poses)
    half = camera.half_mm
    XYZ, source = [], []
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
    if cat is not None:  # how far inside each frame every catalogue point is imaged (−inf where it is not)
        cat_margin = [np.where(np.all(np.isfinite(xy), axis=1), half - np.max(np.abs(np.nan_to_num(xy, nan=1e9)),
                                                                               axis=1), -np.inf) for xy in cat_photo]
    for j, (name, kind, t, xy, control, exact) in enumerate(specs):
        P, src = ground[j], "terrain"
        if cat is not None and not exact:
            xy_c = cat_photo[t]
            dist = np.hypot(xy_c[:, 0] - xy[0], xy_c[:, 1] - xy[1])
            dist[~np.isfinite(dist)] = np.inf
            for u in _needed_photos(kind, name, t, N):  # a catalogue point must be seen where the design point is
                dist[cat_margin[u] < _SEEN_MARGIN_MM] = np.inf
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
        XYZ.append(np.asarray(P, dtype=float))
        source.append(src)
    return np.array(XYZ), tuple(source)


def _unique_names(names: list) -> tuple:
    """The names made unique (a catalogue may reuse labels): a repeat of ``n`` becomes ``n#1``, ``n#2``, …"""
    names = list(names)
    seen = {}
    for i, n in enumerate(names):
        if n in seen:
            seen[n] += 1
            names[i] = f"{n}#{seen[n]}"
        else:
            seen[n] = 0
    return tuple(names)


#: a catalogue point replaces a design point only if it is imaged at least this far inside every frame
#: the design point must be seen on (the templates prick points 3 mm inside the frame)
_SEEN_MARGIN_MM = 4.0


def _needed_photos(kind: str, name: str, t: int, N: int) -> list:
    """The photos a point of this kind, chosen on photo t, must be seen on (0-based)."""
    if kind in ("tie", "centre"):
        return [u for u in (t - 1, t, t + 1) if 0 <= u < N]
    if kind == "orienting":
        return [t, t + 1]
    if name.endswith(("/1", "/2")):  # a control point in the overlap of the end pair
        return [t, t + 1] if t == 0 else [t - 1, t]
    return [t]


def _centre_in_overlap(camera, poses, terrain, t, xy, towards_next, *, keep_mm: float = 5.0, reach_mm: float = 18.0):
    """A tie point's design position on photo t, slid along the strip to stay inside photos t − 1, t, t + 1."""
    d = np.asarray(towards_next, dtype=float)
    d = d / np.hypot(*d)
    shifts = np.linspace(-reach_mm, reach_mm, 37)
    cand = np.asarray(xy, dtype=float) + shifts[:, None] * d
    G = _photo_to_ground(camera, poses[t], cand, terrain)
    margin = camera.half_mm - np.max(np.abs(cand), axis=1)
    for u in (t - 1, t + 1):
        margin = np.minimum(margin, camera.half_mm - np.max(np.abs(g.ground_to_photo(camera, poses[u], G)), axis=1))
    mid = len(shifts) // 2
    if margin[mid] >= keep_mm:
        return np.asarray(xy, dtype=float)
    return cand[int(np.argmax(margin))]


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


@V.checked(camera=g.Camera, poses=V.sequence(V.of_type(g.Pose), min_len=2), points=StripPoints,
           seed=V.whole(0, 2**32 - 1))
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



# =========================================================================== rays on the sheet
def _u(a):
    """Unit vectors, shape (..., 2), at the angles ``a`` (radians)."""
    a = np.asarray(a, dtype=float)
    return np.stack([np.cos(a), np.sin(a)], axis=-1)


def _cross(a, b):
    """The z component of the cross product of 2-D vectors (last axis)."""
    return a[..., 0] * b[..., 1] - a[..., 1] * b[..., 0]


# =========================================================================== free strip
def _largest_side(sides_mm) -> float:
    """The largest finite error-triangle side, mm (0 when there is none)."""
    s = np.asarray(sides_mm, dtype=float)
    return float(np.nanmax(s)) if np.any(np.isfinite(s)) else 0.0


class _LaidStrip:
    """What every strip laid from templates offers: :class:`FreeStrip` and :class:`~.ends.EndsStrip`.

    Needs the attributes ``templates``, ``centres_mm`` (N, 2), ``theta_rad`` (N,),
    ``points_mm`` (P, 2) and ``triangle_sides_mm`` (P, 3).
    """

    @property
    def points(self) -> StripPoints:
        """The strip's points (those of its templates)."""
        return self.templates.points

    @property
    def max_triangle_side_mm(self) -> float:
        """The largest side of an error triangle at the points with three rays, mm (0 when there is none)."""
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


@dataclass(frozen=True)
class FreeStrip(_LaidStrip):
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
        S = plane.fit_similarity(self.points_mm[ok], self.points.XYZ_m[ok, :2], scale=True)
        T = S.matrix()
        s, R, t = S.scale, T[:2, :2] / S.scale, T[:2, 2]
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
            pts[i] = plane.intersect_rays(O, A)
        except ValueError:
            continue
        if len(ts) == 3:
            tri[i], sides[i] = plane.error_triangle(O, A)
    return pts, nr, tri, sides


@V.checked(templates=Templates)
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
            T = plane.intersect_rays(C[[ta, tb]], np.array([D[ta, i] + th[ta], D[tb, i] + th[tb]]))
            w = _u(D[tc, i] + th[tc])
            a_.append(_cross(w, T - C[tb]))
            c_.append(_cross(w, uf))
        a_, c_ = np.array(a_), np.array(c_)
        s = float(np.dot(a_, c_) / np.dot(c_, c_))
        C[tc] = C[tb] + s * uf
        if method == "compromise":
            # the guide's "добиваясь совмещения": centre on the initial direction, the initial
            # direction back through the previous centre and the rays through the tie points, together
            Ts = [plane.intersect_rays(C[[ta, tb]], np.array([D[ta, i] + th[ta], D[tb, i] + th[tb]])) for i in ties]
            idx = [centres_idx[tb]] + ties
            K = np.vstack([C[tb]] + Ts)
            C[tc], th[tc], r = plane.resect_directions(D[tc, idx], K, line=(C[tb], fwd),
                                                       x0=(C[tc][0], C[tc][1], th[tc]))
            residuals.append(r)
        else:
            residuals.append(a_ - s * c_)
    pts, nr, tri, sides = _intersect_all(templates, C, th)
    pts[centres_idx] = C
    return FreeStrip(templates, C, th, pts, nr, tri, sides, tuple(residuals), float(first_base_mm), start)


