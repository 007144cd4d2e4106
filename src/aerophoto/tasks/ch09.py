"""Graded tasks of chapter 09 (guide §10): correcting the student's old plan from their new photo.

Each variant has its own piece of farmland (:func:`aerophoto.projective.land_use_scene`
with seed i) and its own new photo of it: the variant's camera f and scale
1:m, tilt α = 3° with the principal vertical at λ, a heading κ and a small
offset of the photo centre drawn from the variant.  The old plan is at
1:10 000 (guide §10).  The student reads (:func:`aerophoto.labs.ch09.plan_correction_lab`):

* the four control points on the photo (x, y mm from the principal point, to
  0.01 mm) and on the plan (x, y mm, to 0.01 mm);
* the photo positions of the changes: the corners of the new farm building 1
  and the vertices of the new road.

The answers are computed from those rounded numbers, as a student computes
them:

* task 09.1 (:class:`GridCell`): in a 4 × 4 grid of central directions, the
  cell of farm building 1's first corner and the plan position a cell-by-cell
  transfer gives it;
* task 09.2 (:class:`NewRoad`): the new road's vertices on the plan by the
  exact projective transformation of the four points, and its length on the
  ground.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np
from .. import projective as pj
from ..labs.ch09 import GRID_N, PlanCorrectionLab, plan_correction_lab
from .base import Answer, Hidden, Method, Task, submitted_number
from .rounding import consistency, source

__all__ = ["GridCell", "NewRoad", "TASKS"]

# =========================================================================== task 09.1
@dataclass(frozen=True)
class GridCell(Task):
    """Task 09.1: the cell of farm building 1's first corner in a 4 × 4 grid, and its transfer to the plan."""

    id = "task-09-1"
    title = "A point carried cell by cell"
    points = 3
    FEATURE = "farm building 1"
    spec = (
        Answer("row", "row of the cell on the photo grid (0 at side 1–2)", kind="count", rounding="exact",
               hint="rows are counted from 0 at side 1–2 towards side 4–3"),
        Answer("col", "column of the cell (0 at side 1–4)", kind="count", rounding="exact",
               hint="columns are counted from 0 at side 1–4 towards side 2–3"),
        Answer("x_mm", "x of the corner on the plan, mm", unit="mm", tol_abs=0.02, printed=0.01),
        Answer("y_mm", "y of the corner on the plan, mm", unit="mm", tol_abs=0.02, printed=0.01),
    )

    tools = ("aerophoto.projective.grid_pair", "aerophoto.projective.locate")
    methods = (Method("grids of central directions, 4 × 4 cells, on the four points; the corner carried cell by cell",
                      "guide §10; chapter 09 (projective.grid_pair, projective.locate)"),)

    def inputs(self, v) -> PlanCorrectionLab:
        return plan_correction_lab(v)

    def _point(self, lab):
        return lab.photo_of(self.FEATURE)[:1]

    def answers(self, v) -> dict:
        lab = plan_correction_lab(v)
        gp = lab.grid_pair(GRID_N, "central")
        p = self._point(lab)
        loc = pj.locate(gp.photo_nodes, p).iloc[0]
        q = gp.transfer(p)[0]
        return {"row": int(loc["row"]), "col": int(loc["col"]), "x_mm": float(q[0]), "y_mm": float(q[1])}

    def slips(self, v) -> dict:
        lab = plan_correction_lab(v)
        p = self._point(lab)
        ex = lab.exact.apply(p)[0]
        pr = lab.grid_pair(GRID_N, "proportional").transfer(p)[0]
        a = self.answers(v)
        exact_hint = ("that is the exact projective position; the task asks for the cell-by-cell transfer on the "
                      "4 × 4 grid — the difference is the grid's own error")
        prop_hint = ("that is the transfer on a grid of proportional division (equal parts); build the grid by "
                     "central directions")
        out = {"x_mm": {exact_hint: float(ex[0]), prop_hint: float(pr[0])},
               "y_mm": {exact_hint: float(ex[1]), prop_hint: float(pr[1])}}
        if a["row"] != a["col"]:
            out["row"] = {"rows and columns are swapped: rows count from side 1–2 towards 4–3": a["col"]}
            out["col"] = {"rows and columns are swapped: columns count from side 1–4 towards 2–3": a["row"]}
        return out

    def hidden(self, v, got) -> list:
        # the submitted plan point must lie in the plan cell the student named (consistency of their own answers)
        lab = plan_correction_lab(v)
        gp = lab.grid_pair(GRID_N, "central")
        x, y = submitted_number(got.get("x_mm")), submitted_number(got.get("y_mm"))
        if x is None or y is None:
            return [Hidden("the plan point lies in the cell (row, col)", None, None, kind="count")]
        loc = pj.locate(gp.plan_nodes, [[x, y]]).iloc[0]
        exp_row, exp_col = int(loc["row"]), int(loc["col"])
        r, c = submitted_number(got.get("row")), submitted_number(got.get("col"))
        if r is not None and c is not None and float(r).is_integer() and float(c).is_integer() \
                and 0 <= r < GRID_N and 0 <= c < GRID_N:
            # a point within the answers' tolerance (0.02 mm) of the named cell's edge is consistent with it
            N = gp.plan_nodes
            r, c = int(r), int(c)
            cell = np.array([N[r, c], N[r, c + 1], N[r + 1, c + 1], N[r + 1, c]])
            sub = pj.locate(np.array([[cell[0], cell[1]], [cell[3], cell[2]]]), [[x, y]]).iloc[0]
            side = min(np.hypot(*(cell[1] - cell[0])), np.hypot(*(cell[3] - cell[0])))
            slack = 0.03 / side
            if -slack <= sub["s"] <= 1 + slack and -slack <= sub["t"] <= 1 + slack:
                exp_row, exp_col = r, c
        return [Hidden("the plan point lies in row `row` of the plan grid", got.get("row"), exp_row, kind="count"),
                Hidden("the plan point lies in column `col` of the plan grid", got.get("col"), exp_col, kind="count")]


# =========================================================================== task 09.2
@dataclass(frozen=True)
class NewRoad(Task):
    """Task 09.2: the new road's vertices on the plan (exact projective transfer) and its length on the ground."""

    id = "task-09-2"
    title = "The new road on the old plan"
    points = 3
    FEATURE = "new road"
    spec = (
        Answer("xr_mm", "x of the road's vertices on the plan, mm (in the table's order)", unit="mm", kind="values",
               tol_abs=0.1, printed=0.01),
        Answer("yr_mm", "y of the road's vertices on the plan, mm", unit="mm", kind="values", tol_abs=0.1, printed=0.01),
        Answer("road_m", "length of the new road on the ground, m", unit="m", tol_rel=0.002, printed=0.1),
    )

    tools = ("aerophoto.projective.fit_projective",)
    methods = (Method("the projective transformation of the four points (projective.fit_projective), the road's "
                      "segments summed on the plan times M/1000", "guide §10; chapter 09"),)

    def inputs(self, v) -> PlanCorrectionLab:
        return plan_correction_lab(v)

    def answers(self, v) -> dict:
        lab = plan_correction_lab(v)
        q = lab.exact.apply(lab.photo_of(self.FEATURE))
        length = float(np.sum(np.hypot(*np.diff(q, axis=0).T))) * lab.M / 1000.0
        return {"xr_mm": [float(a) for a in q[:, 0]], "yr_mm": [float(a) for a in q[:, 1]], "road_m": length}

    def slips(self, v) -> dict:
        lab = plan_correction_lab(v)
        q = lab.exact.apply(lab.photo_of(self.FEATURE))
        L = float(np.sum(np.hypot(*np.diff(q, axis=0).T)))
        p = lab.photo_of(self.FEATURE)
        Lp = float(np.sum(np.hypot(*np.diff(p, axis=0).T)))
        return {"road_m": {"that is the length on the plan in mm — multiply by M/1000 for metres": L,
                           "that is the straight distance between the road's ends; add up its segments":
                           float(np.hypot(*(q[-1] - q[0]))) * lab.M / 1000.0,
                           "that is measured on the photo at 1:m — a tilted photo has no single scale; measure on "
                           "the corrected plan": Lp * float(v.m) / 1000.0}}

    def hidden(self, v, got) -> list:
        # the length must follow from the student's own vertices: Σ|segment| · M/1000
        lab = plan_correction_lab(v)
        n = len(lab.photo_of(self.FEATURE))
        return [consistency("road_m from your own vertices", got.get("road_m"), 0.1,
                            lambda x, y: float(np.sum(np.hypot(np.diff(x), np.diff(y)))) * lab.M / 1000.0,
                            [source(self, got, "xr_mm", n), source(self, got, "yr_mm", n)], about="road_m")]


TASKS = (GridCell(), NewRoad())
