"""Graded tasks of chapter 15 (article 002): the block bundle adjustment of a mountain survey.

The chapter's blocks are flown over the mountain version of the virtual site
(:data:`aerophoto.labs.ch15.MOUNTAIN_SITE`: 14 km × 11 km, heights 1800–2400 m) with the article's
camera (f = 200 mm, 18 × 18 cm frame).  :func:`aerophoto.labs.ch15.survey_block` builds one: the
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

The worked example (:func:`aerophoto.labs.ch15.example_block`) is the article's experiment made
smaller: four strips of seven photos at 1:15 000.  The student's block
(:func:`aerophoto.labs.ch15.student_block`) is three strips of six photos at the student's scale
1:m (m = 12 000 + 100·i, guide §1: the footprint grows from 2.2 km to 3.9 km
and the site holds the largest), with the student's own random streams.

* task 15.1 (:class:`BlockSize`): the unknowns of the student's block and whether the 1986 package
  (article 002, table 2: at most 1000 unknowns) could have adjusted it;
* task 15.2 (:class:`FindBlunders`): data snooping — the point of the rejected image measurement,
  the rejected control point, and the check-point RMS errors after the adjustment;
* task 15.3 (:class:`LocateFieldPoint`): the adjusted position of the student's gravimetric point
  and the semi-major axis of its standard error ellipse.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from .. import bundle as B
from ..labs.ch15 import SurveyBlock, student_block
from .base import Answer, Hidden, Method, Task, Withheld, submitted_number

__all__ = ["LIMIT_1986", "Solution", "solve_block", "field_point_id", "TaskMeasurements", "block_inputs", "BlockSize",
           "FindBlunders", "LocateFieldPoint", "TASKS"]

#: article 002, table 2: the most unknowns the package could hold in a block
LIMIT_1986 = 1000

@dataclass(frozen=True, eq=False)
class Solution:
    """The reference solution of a block: the three-stage approximations, data snooping, the final adjustment."""

    survey: SurveyBlock
    stages: B.ThreeStage
    snooping: B.Snooping

    @property
    def adjustment(self) -> B.Adjustment:
        return self.snooping.adjustment

    def check_errors_m(self) -> np.ndarray:
        """(k, 3) adjusted − true coordinates of the check points, m."""
        a = self.adjustment
        sel = np.flatnonzero(a.meas.point_kind == "check")
        truth = np.array([self.survey.truth_of(p) for p in a.meas.point_ids[sel]])
        return a.xyz_m[sel] - truth

    def check_rms_m(self) -> dict:
        """RMS errors of the check points: plan √(mean(dX² + dY²)) and height, m."""
        d = self.check_errors_m()
        return {"plan": float(np.sqrt(np.mean(d[:, 0] ** 2 + d[:, 1] ** 2))), "Z": float(np.sqrt(np.mean(d[:, 2] ** 2)))}

    def predicted_check_rms_m(self) -> dict:
        """The a priori estimate of the same RMS from the covariances of the check points, m."""
        a = self.adjustment
        c = a.precision().cov_points[a.meas.point_kind == "check"]
        return {"plan": float(np.sqrt(np.mean(c[:, 0, 0] + c[:, 1, 1]))), "Z": float(np.sqrt(np.mean(c[:, 2, 2])))}

    def check_rms_sampling_m(self) -> dict:
        """The a priori estimate of the check-point RMS with its sampling SD (full covariance), m: {key: (rms, sd)}."""
        a = self.adjustment
        sel = np.flatnonzero(a.meas.point_kind == "check")
        C = B.point_covariance(a.meas, a.eo, a.xyz_m, sel)
        return {"plan": B.rms_expectation(C, (0, 1)), "Z": B.rms_expectation(C, (2,))}

    def field_point(self, point_id) -> dict:
        """The adjusted position of a gravimetric point, its standard error ellipse and its true error."""
        a = self.adjustment
        k = a.meas.index_of_point(point_id)
        cov = a.precision().cov_points[k]
        ax, bx, th = B.error_ellipse(cov[:2, :2])
        X, Y, Z = a.xyz_m[k]
        t = self.survey.truth_of(point_id)
        return {"X_m": float(X), "Y_m": float(Y), "Z_m": float(Z), "a_m": float(ax), "b_m": float(bx),
                "theta_deg": float(th), "sigma_Z_m": float(np.sqrt(cov[2, 2])), "dX_m": float(X - t[0]),
                "dY_m": float(Y - t[1]), "dZ_m": float(Z - t[2])}


@functools.lru_cache(maxsize=8)
def solve_block(survey: SurveyBlock) -> Solution:
    """The reference solution: :func:`aerophoto.bundle.three_stage`, then :func:`aerophoto.bundle.data_snooping`."""
    ts = B.three_stage(survey.meas)
    sn = B.data_snooping(survey.meas, ts.eo0, ts.xyz0_m)
    return Solution(survey, ts, sn)


def _solution(v) -> Solution:
    return solve_block(student_block(v))


#: what the block knows that tasks 15.1–15.2 ask for: its planted blunders
_BLUNDERS = ("blunder_obs", "blunder_mm", "blunder_point", "blunder_photo", "bad_control", "bad_control_dz_m")


@dataclass(frozen=True, eq=False)
class TaskMeasurements(B.Measurements):
    """The block's measurements as tasks 15.1–15.3 give them: the same arrays (every adjustment runs on them),
    without the count of unknowns that task 15.1 asks for (``n_unknowns``, and ``summary()``'s "unknowns" and
    "redundancy")."""

    @property
    def n_unknowns(self) -> int:
        raise AttributeError("'n_unknowns' is not given: it is what task 15.1 asks you to count")

    def summary(self) -> dict:
        """Counts: photos, strips, points of each kind, image observations, equations (no unknowns)."""
        from ..bundle.block import KINDS

        out = {"photos": self.n_photos, "strips": int(len(np.unique(self.photo_strip)))}
        for k in KINDS:
            out[f"{k} points"] = int(np.sum(self.point_kind == k))
        out.update({"image observations": self.n_obs, "equations": self.n_equations})
        return out


@functools.lru_cache(maxsize=8)
def _task_meas(meas: B.Measurements) -> TaskMeasurements:
    from dataclasses import fields

    return TaskMeasurements(**{f.name: getattr(meas, f.name) for f in fields(meas) if f.name != "_cache"})


def block_inputs(v) -> Withheld:
    """The student's block as tasks 15.1–15.3 give it: no planted blunders, no count of unknowns."""
    sv = student_block(v)
    return Withheld(sv, _BLUNDERS, {"meas": _task_meas(sv.meas)},
                    why="the planted blunders are what task 15.2 asks you to find")


def field_point_id(v) -> int:
    """The gravimetric point of task 15.3 for variant ``v``: the variant picks one of the block's."""
    ids = student_block(v).field_ids
    return int(ids[int(v.i) % len(ids)])


# =========================================================================== task 15.1
@dataclass(frozen=True)
class BlockSize(Task):
    """Task 15.1: the unknowns of the student's block and the verdict against the 1986 package's limit."""

    id = "task-15-1"
    title = "How big is your block? (article 002, table 2)"
    points = 2
    cross_variant = False
    spec = (
        Answer("n_unknowns", "unknowns of the bundle adjustment: 6 per photo + 3 per ground point", kind="count",
               rounding="exact"),
        Answer("fits_1986", "True if the 1986 package (at most 1000 unknowns) could adjust it", kind="bool",
               hint="compare your number of unknowns with the limit in table 2"),
    )

    methods = (Method("6 elements of exterior orientation per photo + 3 coordinates per ground point (tie, control, "
                      "check and gravimetric), against table 2's 1000", "article 002, table 2; chapter 15"),)

    def inputs(self, v) -> Withheld:
        return block_inputs(v)

    def answers(self, v) -> dict:
        n = student_block(v).meas.n_unknowns
        return {"n_unknowns": n, "fits_1986": bool(n <= LIMIT_1986)}

    def slips(self, v) -> dict:
        m = student_block(v).meas
        return {"n_unknowns": {
            "the tie points are unknowns too: 3 coordinates each": 6 * m.n_photos,
            "the control points are unknowns as well (their coordinates are observed, with weights)":
                6 * m.n_photos + 3 * int(np.sum(~m.is_control)),
            "a photo has six elements of exterior orientation, not three": 3 * m.n_photos + 3 * m.n_points,
        }}

    def hidden(self, v, got) -> list:
        n = submitted_number(got.get("n_unknowns"))
        expected = None if n is None else bool(n <= LIMIT_1986)
        return [Hidden("fits_1986 agrees with n_unknowns", got.get("fits_1986") if n is not None else None,
                       expected, kind="bool")]


# =========================================================================== task 15.2
@dataclass(frozen=True)
class FindBlunders(Task):
    """Task 15.2: data snooping on the student's block — the blunders, and the check-point RMS after it."""

    id = "task-15-2"
    title = "Find the blunders and judge the block by its check points"
    points = 4
    cross_variant = False
    tools = ("aerophoto.bundle.three_stage", "aerophoto.bundle.data_snooping")
    methods = (Method("bundle.three_stage, then bundle.data_snooping; the check points' errors against "
                      "block.truth_of", "article 002; chapter 15, task 15.2"),)
    spec = (
        Answer("blunder_point", "id of the point whose image measurement is rejected", kind="count",
               rounding="exact", hint="give the id of the rejected image measurement's point, from the rejected "
                                      "table's 'point' column (not a count, not a photo)"),
        Answer("bad_control", "id of the control point that is rejected", kind="count", rounding="exact",
               hint="give the id of the rejected control point, from the rejected table's 'point' column"),
        Answer("rms_plan_m", "RMS plan error of the check points after the adjustment, m", unit="m", tol_rel=0.02, printed=0.001),
        Answer("rms_Z_m", "RMS height error of the check points after the adjustment, m", unit="m", tol_rel=0.02, printed=0.001),
    )

    def inputs(self, v) -> Withheld:
        return block_inputs(v)

    def answers(self, v) -> dict:
        sol = _solution(v)
        rej = sol.snooping.rejected
        img = rej[rej["kind"] == "image"]
        ctl = rej[rej["kind"] == "control"]
        r = sol.check_rms_m()
        return {"blunder_point": int(img["point"].iloc[0]) if len(img) else -1,
                "bad_control": int(ctl["point"].iloc[0]) if len(ctl) else -1,
                "rms_plan_m": r["plan"], "rms_Z_m": r["Z"]}

    def slips(self, v) -> dict:
        sv = student_block(v)
        # the check-point RMS with the blunders left in (no snooping)
        ts = B.three_stage(sv.meas)
        adj = B.adjust(sv.meas, ts.eo0, ts.xyz0_m)
        sel = np.flatnonzero(adj.meas.point_kind == "check")
        d = adj.xyz_m[sel] - np.array([sv.truth_of(p) for p in adj.meas.point_ids[sel]])
        sol = _solution(v)
        pr = sol.predicted_check_rms_m()
        r = sol.check_rms_m()
        meas = sv.meas
        ids = {"that is the photo the rejected measurement is on; the task asks for the point's id":
               sv.blunder_photo,
               "that is the index of the observation (its row); the task asks for the point's id": sv.blunder_obs,
               "that is the point's index in meas.point_ids; the task asks for the id itself":
               int(meas.obs_point[sv.blunder_obs]) if sv.blunder_obs >= 0 else None,
               "that is the rejected control point; blunder_point is the point of the rejected image measurement":
               sv.bad_control}
        ctl = {"that is the point of the rejected image measurement; bad_control is the rejected control point":
               sv.blunder_point,
               "that is the point's index in meas.point_ids; the task asks for the id itself":
               meas.index_of_point(sv.bad_control) if sv.bad_control >= 0 else None}
        return {
            "blunder_point": ids, "bad_control": ctl,
            "rms_plan_m": {"this is with the blunders still in: reject them first (data snooping)":
                           float(np.sqrt(np.mean(d[:, 0] ** 2 + d[:, 1] ** 2))),
                           "that is the RMS per coordinate, √(mean(dX² + dY²)/2); the plan error combines both: "
                           "√(mean(dX² + dY²))": r["plan"] / np.sqrt(2.0),
                           "this is the predicted (a priori) error; the task asks for the true errors of the check "
                           "points": pr["plan"]},
            "rms_Z_m": {"this is with the blunders still in: reject them first (data snooping)":
                        float(np.sqrt(np.mean(d[:, 2] ** 2))),
                        "this is the predicted (a priori) error; the task asks for the true errors of the check "
                        "points": pr["Z"]},
        }

    def hidden(self, v, got) -> list:
        # a second quantity: the rejected image measurement's photo must be one the point is measured on —
        # and the check-point errors must be plausible for the block (within 3× the prediction)
        sol = _solution(v)
        pr = sol.predicted_check_rms_m()
        out = []
        for name, key in (("rms_plan_m", "plan"), ("rms_Z_m", "Z")):
            x = submitted_number(got.get(name))
            ok = None if x is None else bool(0.3 * pr[key] <= x <= 3.0 * pr[key])
            out.append(Hidden(f"{name} is of the size the block's precision allows", ok if x is not None else None,
                              True, kind="bool"))
        return out


# =========================================================================== task 15.3
@dataclass(frozen=True)
class LocateFieldPoint(Task):
    """Task 15.3: the adjusted position of the student's gravimetric point and its standard error ellipse."""

    id = "task-15-3"
    title = "Locate your gravimetric point"
    points = 3
    cross_variant = False
    spec = (
        Answer("X_m", "adjusted X of the gravimetric point, m", unit="m", tol_abs=0.05, printed=0.01),
        Answer("Y_m", "adjusted Y, m", unit="m", tol_abs=0.05, printed=0.01),
        Answer("Z_m", "adjusted Z, m", unit="m", tol_abs=0.05, printed=0.01),
        Answer("a_m", "semi-major axis of its standard error ellipse, m", unit="m", tol_rel=0.02, printed=0.001),
    )

    tools = ("aerophoto.bundle.error_ellipse",)
    methods = (Method("the final adjustment's xyz_m of the point; the ellipse of its 2 × 2 plan covariance "
                      "(bundle.error_ellipse)", "article 002; chapter 15, task 15.3"),)

    def inputs(self, v) -> dict:
        return {"point": field_point_id(v), "block": block_inputs(v)}

    def answers(self, v) -> dict:
        fp = _solution(v).field_point(field_point_id(v))
        return {k: fp[k] for k in ("X_m", "Y_m", "Z_m", "a_m")}

    def slips(self, v) -> dict:
        fp = _solution(v).field_point(field_point_id(v))
        return {"a_m": {"this is the semi-minor axis: the task asks for the major one": fp["b_m"],
                        "this is √(σX² + σY²), the plan RMS, not the ellipse's semi-major axis":
                            float(np.hypot(fp["a_m"], fp["b_m"]))}}

    def hidden(self, v, got) -> list:
        # the truth, never shown: the submitted point must lie within 5 semi-major axes of the true point
        sv = student_block(v)
        t = sv.truth_of(field_point_id(v))
        fp = _solution(v).field_point(field_point_id(v))
        X, Y = submitted_number(got.get("X_m")), submitted_number(got.get("Y_m"))
        ok = None if X is None or Y is None else bool(np.hypot(X - t[0], Y - t[1]) <= 5.0 * fp["a_m"] + 0.1)
        return [Hidden("the point lies where the ground truth is", ok, True, kind="bool")]


TASKS = (BlockSize(), FindBlunders(), LocateFieldPoint())
