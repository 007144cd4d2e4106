"""An old land-use plan and the state of the ground years later: the data of a plan correction (guide §10).

A seeded, synthetic piece of farmland, square, ``size_m`` on a side, in local
ground coordinates (metres, X east, Y north, origin at the square's centre,
flat ground):

* a field system turned by a few degrees: field boundaries (межи) in two
  directions, some of them field roads;
* a village of small buildings by one road crossing, and a stream;

and what changed between the survey of the old plan and the new photo
(изменения ситуации):

* a new farm complex (three long buildings) in a field,
* a new road joining it to the road network,
* one field boundary moved (the old line is gone, a new one drawn),
* one village building pulled down.

Each :class:`Feature` carries a ``status``: ``"kept"`` (on both dates),
``"gone"`` (on the old plan only) or ``"new"`` (on the new photo only).  The
crossings of boundaries and roads are the well-defined ground points
(контурные точки) from which four control points are picked
(:meth:`LandUseScene.control_points`).  The generator is deterministic for a
seed; it knows nothing of cameras — :mod:`aerophoto.geometry` images it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .._validate import check_int_range, check_range

__all__ = ["Feature", "LandUseScene", "land_use_scene", "KINDS", "STATUSES"]

KINDS = ("field boundary", "road", "building", "stream")
STATUSES = ("kept", "gone", "new")


@dataclass(frozen=True)
class Feature:
    """One line feature of the scene.

    Attributes
    ----------
    name : str
        E.g. ``"road 2"``, ``"farm building 1"``.
    kind : str
        One of :data:`KINDS`.
    xy_m : ndarray (k, 2)
        Vertices in ground metres (X east, Y north, origin at the centre).
    closed : bool
        A polygon (buildings) rather than a line.
    status : str
        ``"kept"``, ``"gone"`` (old plan only) or ``"new"`` (new photo only).
    """

    name: str
    kind: str
    xy_m: np.ndarray
    closed: bool
    status: str

    def outline_m(self) -> np.ndarray:
        """The vertices, the first repeated at the end for a closed feature (for drawing)."""
        return np.vstack([self.xy_m, self.xy_m[:1]]) if self.closed else self.xy_m


@dataclass(frozen=True, eq=False)
class LandUseScene:
    """The old plan and the new state of a square of farmland (see the module notes).

    Attributes
    ----------
    size_m : float
        Side of the square, metres.
    seed : int
    rotation_deg : float
        Turn of the field system from the X axis, degrees.
    features : tuple of :class:`Feature`
    points : DataFrame
        Well-defined ground points: ``name``, ``X_m``, ``Y_m`` (crossings of
        boundaries and roads that exist on both dates).
    """

    size_m: float
    seed: int
    rotation_deg: float
    features: tuple
    points: pd.DataFrame

    def old(self) -> tuple:
        """The features of the old plan (kept and gone)."""
        return tuple(f for f in self.features if f.status in ("kept", "gone"))

    def new(self) -> tuple:
        """The features on the ground when the new photo was taken (kept and new)."""
        return tuple(f for f in self.features if f.status in ("kept", "new"))

    def changes(self) -> tuple:
        """The new features: what has to be carried from the photo onto the plan."""
        return tuple(f for f in self.features if f.status == "new")

    def feature(self, name: str) -> Feature:
        for f in self.features:
            if f.name == name:
                return f
        raise ValueError(f"no feature {name!r}; features: {[f.name for f in self.features]}")

    def control_points(self, spread: float = 0.85) -> pd.DataFrame:
        """Four control points 1–4 near the corners of the square's central part, counter-clockwise from south-west.

        ``spread`` (0.3…1) is the half-width of the part they span, as a
        fraction of the half-side: each control point is the well-defined
        point nearest to (±spread, ±spread)·size/2.  Returns a DataFrame with
        ``name`` ("1"…"4"), ``point`` (the ground point's name), ``X_m``, ``Y_m``.
        """
        sp = check_range("spread", spread, 0.3, 1.0)
        h = self.size_m / 2.0 * sp
        targets = np.array([[-h, -h], [h, -h], [h, h], [-h, h]])
        P = self.points[["X_m", "Y_m"]].to_numpy()
        rows, used = [], set()
        for k, t in enumerate(targets):
            d = np.hypot(*(P - t).T)
            for idx in np.argsort(d):
                if int(idx) not in used:
                    used.add(int(idx))
                    break
            rows.append((str(k + 1), self.points["name"].iloc[idx], P[idx, 0], P[idx, 1]))
        return pd.DataFrame(rows, columns=["name", "point", "X_m", "Y_m"])

    def change_vertices(self) -> pd.DataFrame:
        """Every vertex of the new features: ``feature``, ``vertex`` (1, 2, …), ``X_m``, ``Y_m``."""
        rows = [(f.name, k + 1, x, y) for f in self.changes() for k, (x, y) in enumerate(f.xy_m)]
        return pd.DataFrame(rows, columns=["feature", "vertex", "X_m", "Y_m"])


# --------------------------------------------------------------------------- the generator
def _clip(p0, d, half):
    """The part of the line p0 + s·d inside the square |X|, |Y| ≤ half: (2, 2) or None (Liang–Barsky)."""
    lo, hi = -np.inf, np.inf
    for k in range(2):
        if abs(d[k]) < 1e-12:
            if abs(p0[k]) > half:
                return None
            continue
        a = (-half - p0[k]) / d[k]
        b = (half - p0[k]) / d[k]
        lo, hi = max(lo, min(a, b)), min(hi, max(a, b))
    if hi - lo <= 1e-9:
        return None
    return np.array([p0 + lo * d, p0 + hi * d])


def _rect(c, a, b, ang):
    du = np.array([math.cos(ang), math.sin(ang)])
    dv = np.array([-math.sin(ang), math.cos(ang)])
    return np.array([c - a * du - b * dv, c + a * du - b * dv, c + a * du + b * dv, c - a * du + b * dv])


def land_use_scene(seed: int = 0, size_m: float = 1600.0) -> LandUseScene:
    """Generate the scene for ``seed`` (deterministic): a square of ``size_m`` metres (400 ≤ size ≤ 20 000)."""
    seed = check_int_range("seed", seed, 0, 2**32 - 1)
    S = check_range("size_m", size_m, 400.0, 20000.0, unit="m")
    rng = np.random.default_rng([seed, 10])
    half = S / 2.0
    rot = float(rng.choice([-1.0, 1.0]) * rng.uniform(6.0, 24.0))
    th = math.radians(rot)
    ea = np.array([math.cos(th), math.sin(th)])  # field axis a
    eb = np.array([-math.sin(th), math.cos(th)])  # field axis b
    span = half * 1.5
    step = S / 6.0

    def positions():
        out, x = [], -span + rng.uniform(0.2, 0.8) * step
        while x < span:
            out.append(x)
            x += step * rng.uniform(0.75, 1.3)
        return np.array(out)

    pa, pb = positions(), positions()  # boundary lines a = const (along eb) and b = const (along ea)
    feats = []
    road_a = int(np.argmin(np.abs(pa - rng.uniform(-0.3, 0.3) * half)))
    road_b = int(np.argmin(np.abs(pb - rng.uniform(-0.3, 0.3) * half)))
    inner_a = [k for k in range(len(pa)) if abs(pa[k]) < 0.55 * half and k != road_a]
    moved = int(rng.choice(inner_a)) if inner_a else None
    shift = float(rng.choice([-1.0, 1.0]) * rng.uniform(0.25, 0.4) * step)
    lines_a, lines_b = [], []
    for k, a in enumerate(pa):
        seg = _clip(a * ea, eb, half)
        if seg is None:
            continue
        kind = "road" if k == road_a else "field boundary"
        if k == moved:
            feats.append(Feature(f"boundary {len(feats) + 1} (old)", kind, seg, False, "gone"))
            new_seg = _clip((a + shift) * ea, eb, half)
            if new_seg is not None:
                feats.append(Feature(f"boundary {len(feats) + 1} (moved)", kind, new_seg, False, "new"))
            continue
        feats.append(Feature(f"{kind} {len(feats) + 1}", kind, seg, False, "kept"))
        lines_a.append((a, kind))
    for k, b in enumerate(pb):
        seg = _clip(b * eb, ea, half)
        if seg is None:
            continue
        kind = "road" if k == road_b else "field boundary"
        feats.append(Feature(f"{kind} {len(feats) + 1}", kind, seg, False, "kept"))
        lines_b.append((b, kind))
    # well-defined points: crossings of kept lines, inside the square
    pts = []
    for a, ka in lines_a:
        for b, kb in lines_b:
            p = a * ea + b * eb
            if np.all(np.abs(p) < half - 5.0):
                kind = "road crossing" if (ka == "road" and kb == "road") else (
                    "road and boundary" if "road" in (ka, kb) else "field corner")
                pts.append((f"{kind} {len(pts) + 1}", p[0], p[1]))
    points = pd.DataFrame(pts, columns=["name", "X_m", "Y_m"])
    # the village by the road crossing, kept buildings and one pulled down
    cross = pa[road_a] * ea + pb[road_b] * eb
    n_b = int(rng.integers(7, 11))
    demolished = int(rng.integers(0, n_b))
    for k in range(n_b):
        side = rng.choice([-1.0, 1.0], size=2)
        c = cross + side[0] * rng.uniform(25, 0.5 * step) * ea + side[1] * rng.uniform(25, 0.5 * step) * eb
        r = _rect(c, rng.uniform(6, 12), rng.uniform(5, 9), th + rng.normal(0, 0.03))
        feats.append(Feature(f"village building {k + 1}", "building", r, True, "gone" if k == demolished else "kept"))
    # the stream: a smooth curve across the square
    t = np.linspace(-1.0, 1.0, 25)
    amp = rng.uniform(0.08, 0.16) * S
    ph = rng.uniform(0, 2 * math.pi)
    off = rng.uniform(-0.25, 0.25) * half
    sx = t * half * 1.02
    sy = off + amp * np.sin(2.2 * t + ph) * (1.0 - 0.3 * t**2)
    stream = np.column_stack([sx, sy])
    if rng.random() < 0.5:
        stream = stream[:, ::-1]
    stream = np.clip(stream, -half, half)
    feats.append(Feature("stream", "stream", stream, False, "kept"))
    # the changes: a farm complex in a quarter away from the village, its road
    quad = -np.sign(cross + 1e-9)
    farm = quad * rng.uniform(0.3, 0.45, size=2) * half
    fa = th + (math.pi / 2 if rng.random() < 0.5 else 0.0)
    du = np.array([math.cos(fa), math.sin(fa)])
    dv = np.array([-math.sin(fa), math.cos(fa)])
    L, W, gap = rng.uniform(45, 70), rng.uniform(10, 16), rng.uniform(14, 22)
    for k in range(3):
        c = farm + (k - 1) * (2 * W + gap) * dv
        feats.append(Feature(f"farm building {k + 1}", "building", _rect(c, L, W, fa), True, "new"))
    # the new road: from the farm's entrance to the nearest point of the nearest kept road, with one bend
    entrance = farm - (L + 20.0) * du
    best = None
    for f in feats:
        if f.kind == "road" and f.status == "kept":
            a0, a1 = f.xy_m
            d = a1 - a0
            s = np.clip(np.dot(entrance - a0, d) / np.dot(d, d), 0.02, 0.98)
            q = a0 + s * d
            dist = float(np.hypot(*(q - entrance)))
            if best is None or dist < best[0]:
                best = (dist, q)
    q = best[1] if best is not None else np.zeros(2)
    bend = entrance + 0.5 * (q - entrance) + rng.uniform(-0.15, 0.15) * np.array([-(q - entrance)[1],
                                                                                   (q - entrance)[0]])
    feats.append(Feature("new road", "road", np.array([farm - (L + 3.0) * du, entrance, bend, q]), False, "new"))
    return LandUseScene(S, seed, rot, tuple(feats), points)
