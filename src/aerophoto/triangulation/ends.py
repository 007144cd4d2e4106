"""Building a strip on the plan from both ends towards the middle (guide §7, figures 15–16).

When the first and the last photo each carry three or four control points,
the strip is built at once in the plan's scale: the end templates are set by
resection (обратная засечка, :func:`aerophoto.plane.resect_directions`), the
inner ones are resected in turn from both ends, the middle template gets two
solutions (3′ and 3″) whose mean is the most probable position, and the
adjustment spreads the discrepancy (невязка) over the strip.  Plan mm at 1/M.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import _validate as V
from .. import plane
from .._validate import check_range
from .reduction import _plan_mm
from .strip import Templates, _cross, _intersect_all, _LaidStrip, _u

__all__ = ["EndsStrip", "build_from_ends"]


@dataclass(frozen=True)
class EndsStrip(_LaidStrip):
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


@V.checked(templates=Templates, origin_m=V.optional(V.point(2)))
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
        C[t], th[t], r = plane.resect_directions(D[t, idx], truth[idx])
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
            Cb, tb, _ = plane.resect_directions(D[b, idx], np.array([kn[i] for i in idx]), line=line)
            Cs[b], ths[b] = Cb, tb
            kn[int(cidx[b])] = Cb
            # intersect the points both a and b see that are not known yet (tie points, orienting points)
            for i in range(len(pts)):
                if i in kn or i in own:
                    continue
                if rays_to(a, i) and rays_to(b, i):
                    kn[i] = plane.intersect_rays(np.array([Cs[a], Cb]), np.array([D[a, i] + ths[a], D[b, i] + tb]))
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
        C[t], th[t], _ = plane.resect_directions(D[t, idx], np.array([final_known[i] for i in idx]),
                                                 x0=(C[t][0], C[t][1], th[t]))
    P, nr, tri, sides = _intersect_all(templates, C, th)
    P[cidx] = C
    lone = [i for i in ctl if not np.all(np.isfinite(P[i]))]
    P[lone] = truth[lone]  # control points seen on one photo only: on the plan from their coordinates
    return EndsStrip(templates, Mv, origin, C, th, mid, Cl[mid], Cr[mid], thl[mid], thr[mid], mid_ties, tl, tr,
                     misfit, tuple(end_res), P, truth, sides, tri)


