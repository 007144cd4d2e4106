"""Chapter 15's lab (article 002): the mountain site and the survey blocks flown over it.

The chapter's blocks are flown over the mountain version of the virtual site
(:data:`MOUNTAIN_SITE`: 14 km × 11 km, heights 1800–2400 m) with the article's
camera (f = 200 mm, 18 × 18 cm frame).  :func:`survey_block` builds one: the
flight (:func:`aerophoto.simulate.block_over_site`), the tie points at the
standard positions of every photo, sparse control (the site's control points
nearest the block's corners and the middles of its long sides — the article's
"4–5 control points per block of 40–50 photos"), check points (the other
well-defined points of the site's catalogue: road crossings and field
corners), the gravimetric points (single trees of the catalogue: "bushes of
juniper, single stones", marked on the helicopter photo and transferred by
eye, so measured with a larger error) and the planted blunders: one image
measurement moved by a tenth of a millimetre, one control height wrong by
metres (the article's barometric heights "with blunders of 8–12 m").

The worked example (:func:`example_block`) is the article's experiment made
smaller: four strips of seven photos at 1:15 000.  The student's block
(:func:`student_block`) is three strips of six photos at the student's scale
1:m, with the student's own random streams.  The graded tasks and the
reference solution are :mod:`aerophoto.tasks.ch15`; the bundle demo's views
use :data:`MOUNTAIN_SITE`.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
import pandas as pd

from .. import bundle as B
from .. import geometry as g
from .. import simulate
from .. import site as _site

__all__ = ["MOUNTAIN_SITE", "F_MM", "EXAMPLE_M", "PX_PERCENT", "PY_PERCENT", "SIGMA_MM", "FIELD_SIGMA_MM",
           "CONTROL_SIGMA_M", "mountain_site", "SurveyBlock", "survey_block", "example_block", "student_block"]

#: the mountain site: parameters of :func:`aerophoto.site.get_site`
MOUNTAIN_SITE = dict(width_m=14000.0, height_m=11000.0, relief_m=600.0, base_height_m=1800.0, texture_m=5.0, seed=2)
#: the article's camera: f = 200 mm (article 002, the 1985 experiment), 18 × 18 cm frame
F_MM = 200.0
#: the article's photo scale 1:15 000
EXAMPLE_M = 15000.0
#: forward and side overlap of the mountain flights, % (mountain surveys fly a larger forward overlap so that
#: the triple overlap survives on the peaks, where the photo base grows by H/(H − h))
PX_PERCENT, PY_PERCENT = 65.0, 30.0
#: a priori RMS error of a measured photo coordinate, mm
SIGMA_MM = 0.005
#: a priori RMS error of a gravimetric point's mark, transferred by eye from the helicopter photo, mm
FIELD_SIGMA_MM = 0.03
#: a priori RMS errors of the control coordinates X, Y, Z, m
CONTROL_SIGMA_M = (0.5, 0.5, 0.5)


def mountain_site():
    """The mountain version of the virtual site (built once per process, about 3 s)."""
    return _site.get_site(**MOUNTAIN_SITE)


@dataclass(frozen=True, eq=False)
class SurveyBlock:
    """A simulated block of the mountain site with its truth and its planted blunders.

    Attributes
    ----------
    name : str
    m : float — photo scale denominator
    block : :class:`aerophoto.simulate.Block` — the flight (true orientations)
    meas : :class:`aerophoto.bundle.Measurements` — what was measured (blunders included)
    truth_m : (P, 3) true ground coordinates of the points, in the order of ``meas.point_ids``
    eo_true : (n, 6) true exterior orientation
    blunder_obs : index of the image observation moved by ``blunder_mm`` (−1: none)
    blunder_mm : (2,) the move, mm
    bad_control : id of the control point whose height is wrong (−1: none)
    bad_control_dz_m : the height blunder, m
    field_ids : ids of the gravimetric points
    """

    name: str
    m: float
    block: object
    meas: B.Measurements
    truth_m: np.ndarray
    eo_true: np.ndarray
    blunder_obs: int
    blunder_mm: np.ndarray
    bad_control: int
    bad_control_dz_m: float
    field_ids: tuple

    @property
    def blunder_point(self) -> int:
        """Id of the point whose image measurement is the blunder (−1: none)."""
        return -1 if self.blunder_obs < 0 else int(self.meas.point_ids[self.meas.obs_point[self.blunder_obs]])

    @property
    def blunder_photo(self) -> int:
        """Number of the photo carrying the blunder (−1: none)."""
        return -1 if self.blunder_obs < 0 else int(self.meas.photo_ids[self.meas.obs_photo[self.blunder_obs]])

    def truth_of(self, point_id) -> np.ndarray:
        return self.truth_m[self.meas.index_of_point(point_id)]

    def points_table(self) -> pd.DataFrame:
        """The block's points as the student gets them: id, kind, and the control coordinates (m) where given."""
        m = self.meas
        df = pd.DataFrame({"id": m.point_ids, "kind": m.point_kind, "X control, m": m.control_XYZ_m[:, 0],
                           "Y control, m": m.control_XYZ_m[:, 1], "Z control, m": m.control_XYZ_m[:, 2],
                           "photos": np.bincount(m.obs_point, minlength=m.n_points)})
        return df.set_index("id")


def _pick_nearest(cands_xy, targets_xy):
    chosen = []
    for t in targets_xy:
        d = np.hypot(*(cands_xy - t).T)
        for k in np.argsort(d):
            if k not in chosen:
                chosen.append(int(k))
                break
    return chosen


def survey_block(m: float, n_strips: int, n_photos: int, *, seed: int, name: str = "", n_field: int = 8,
                 sigma_mm: float = SIGMA_MM, blunder_size_mm: float = 0.1, control_dz_m: float = 10.0,
                 tilt_deg: float = 1.5) -> SurveyBlock:
    """A simulated block of the mountain site (see the module notes), deterministic for ``seed``.

    Parameters
    ----------
    m : photo scale denominator (the camera is the article's, f = 200 mm)
    n_strips, n_photos : strips and photos per strip
    seed : the flight's imperfections, the measuring errors and the blunders' places
    n_field : gravimetric points
    sigma_mm : RMS error of a measured photo coordinate, mm
    blunder_size_mm : length of the image blunder, mm (0: none)
    control_dz_m : height blunder of one control point, m (0: none)
    tilt_deg : largest photo tilt, degrees
    """
    st = mountain_site()
    cam = g.Camera(F_MM)
    imp = simulate.Imperfections(max_tilt_deg=tilt_deg, max_crab_jitter_deg=2.0, max_height_percent=2.0,
                                 max_base_percent=3.0, seed=int(seed))
    bl = simulate.block_over_site(st, cam, m, PX_PERCENT, PY_PERCENT, n_photos, n_strips, imperfections=imp)
    shots = bl.shots
    poses = [s.pose for s in shots]
    eo = B.eo_from_poses(poses)
    b_mm = bl.B_m / (bl.H_m / F_MM)
    ties = B.standard_points(cam, poses, st, halfway_mm=b_mm / 2.0)
    cen = bl.centres_m[:, :2]
    lo, hi = cen.min(axis=0), cen.max(axis=0)
    cat = st.catalogue
    xy = cat[["X_m", "Y_m"]].to_numpy()
    pad = 0.25 * cam.frame_mm / 1000.0 * m  # well inside the block's footprint
    inside = np.all((xy > lo - pad) & (xy < hi + pad), axis=1)
    wd = cat["kind"].isin(["road crossing", "field corner"]).to_numpy()
    # sparse control: the well-defined points nearest the corners, the middles of the sides and the centre
    mid = (lo + hi) / 2.0
    a0, a1 = lo - 0.5 * pad, hi + 0.5 * pad
    corners = np.array([[a0[0], a0[1]], [a1[0], a0[1]], [a1[0], a1[1]], [a0[0], a1[1]], [mid[0], a0[1]],
                        [mid[0], a1[1]], [a0[0], mid[1]], [a1[0], mid[1]], [mid[0], mid[1]]])
    cand = np.flatnonzero(inside & wd)
    ctrl = cand[_pick_nearest(xy[cand], corners)]
    check = np.setdiff1d(cand, ctrl)
    rng = np.random.default_rng([int(seed), 15])
    trees = np.flatnonzero(inside & (cat["kind"] == "tree").to_numpy())
    field = rng.choice(trees, size=min(n_field, len(trees)), replace=False) if len(trees) else np.zeros(0, int)
    XYZ_cat = cat[["X_m", "Y_m", "Z_m"]].to_numpy()
    P = np.vstack([ties, XYZ_cat[ctrl], XYZ_cat[check], XYZ_cat[field]])
    kinds = np.array(["tie"] * len(ties) + ["control"] * len(ctrl) + ["check"] * len(check) + ["field"] * len(field),
                     dtype=object)
    ids = np.concatenate([np.arange(1, len(ties) + 1), 1000 + cat["id"].to_numpy()[ctrl],
                          1000 + cat["id"].to_numpy()[check], 1000 + cat["id"].to_numpy()[field]])
    meas = B.simulate_measurements(F_MM, cam.frame_mm, eo, [s.number for s in shots], [s.strip for s in shots],
                                   [s.index for s in shots], P, ids, kinds, sigma_mm=sigma_mm,
                                   sigma_kind_mm={"field": FIELD_SIGMA_MM}, control_sigma_m=CONTROL_SIGMA_M,
                                   margin_mm=3.0, seed=int(seed) + 7)
    truth = P[[int(np.flatnonzero(ids == p)[0]) for p in meas.point_ids]]
    # the blunders: placed where the block can see them (an image measurement with redundancy numbers of at
    # least 0.4, a control height with at least 0.25 — the best one if none has — at the true values, so that
    # the blunder shows a standardised residual of 10 or more)
    pr = B.precision(meas, eo, truth)
    xy_m = meas.xy_mm.copy()
    blunder_obs, move = -1, np.zeros(2)
    if blunder_size_mm > 0:
        per = np.bincount(meas.obs_point, minlength=meas.n_points)
        ok = np.flatnonzero(np.isin(meas.point_kind[meas.obs_point], ["tie", "check"]) & (per[meas.obs_point] >= 3)
                            & (pr.redundancy_img.min(axis=1) >= 0.4))
        blunder_obs = int(rng.choice(ok))
        ang = rng.uniform(0.0, 2.0 * np.pi)
        move = blunder_size_mm * np.array([np.cos(ang), np.sin(ang)])
        xy_m[blunder_obs] += move
    ctrl_m = meas.control_XYZ_m.copy()
    bad = -1
    if control_dz_m:
        ci = np.flatnonzero(meas.is_control)
        rz = pr.redundancy_ctrl[ci, 2]
        good = ci[rz >= 0.25]
        k = int(rng.choice(good)) if len(good) else int(ci[np.argmax(rz)])
        ctrl_m[k, 2] += control_dz_m * (1.0 if rng.random() < 0.5 else -1.0)
        bad = int(meas.point_ids[k])
    meas = meas.replace(xy_mm=xy_m, control_XYZ_m=ctrl_m)
    field_ids = tuple(int(p) for p, k in zip(meas.point_ids, meas.point_kind) if k == "field")
    return SurveyBlock(name, float(m), bl, meas, truth, eo, blunder_obs, move, bad,
                       float(control_dz_m if bad >= 0 else 0.0), field_ids)


@functools.lru_cache(maxsize=2)
def example_block() -> SurveyBlock:
    """The worked example: 4 strips × 7 photos at 1:15 000 (the article's scale and camera), seed 2002."""
    return survey_block(EXAMPLE_M, 4, 7, seed=2002, name="example (article 002 setting)")


def _student_m(v) -> float:
    return float(v.m)


@functools.lru_cache(maxsize=8)
def _student_block(i: int, m: float) -> SurveyBlock:
    return survey_block(m, 3, 6, seed=15_000 + i, name=f"variant {i:02d}",
                        blunder_size_mm=0.08 + 0.0005 * i, control_dz_m=10.0 + 0.05 * i)


def student_block(v) -> SurveyBlock:
    """The student's block: 3 strips × 6 photos at the variant's scale 1:m, the variant's own seeds."""
    return _student_block(int(v.i), _student_m(v))
