"""Write notebooks/09_plan_correction.ipynb (guide §10) from its cells (safe to re-run).

    python docs/tools/build_09_plan_correction.py

Cells are identified by id; the notebook is written without outputs.
"""

from pathlib import Path

from aerophoto.demos.plan_correction import grid_node_misses
from aerophoto.nbtools import code, md, notebook, write

from lab_cells import answer_cell, check_cell  # noqa: E402  (same folder)

ROOT = Path(__file__).resolve().parents[2]
PATH = ROOT / "notebooks" / "09_plan_correction.ipynb"

#: the grids figure's largest node misses, mm: the same numbers its titles print (grid_node_misses)
MISS = grid_node_misses(alpha_deg=10.0, n=4)
MISS_C, MISS_P = f"{MISS['central']:.2f}", f"{MISS['proportional']:.2f}"


CELLS = [
    md("""
# 09 · Correcting a plan from a new photo (guide §10)

A land-use plan ages: fields are re-cut, farms and roads are built, houses disappear. Instead of surveying the
whole plan again, the changes can be read off a new aerial photo and drawn onto the old plan — **plan
correction** (корректировка плана). The photo is tilted and its scale varies across it, so the changes cannot
simply be traced; the guide's §10 carries them over with **mutual projective grids** (взаимно-проектные сетки):
a grid on the photo and a grid on the plan whose cells correspond, built on four **control points**
(опорные, трансформационные точки) that both show.

**In this chapter you will**

1. see why a photo of flat ground and its plan are related by a **projective transformation**
   (проективное преобразование) fixed by four points, and what that means for a grid;
2. compare the three ways of drawing the grids the guide names — **similar figures** (подобные фигуры),
   **proportional division** (пропорциональное деление) and **central directions** (центральные направления) —
   and find that only the last gives cells that truly correspond;
3. move the sliders of the plan-correction explorer: tilt, grid density, the spread of the four points;
4. carry the changes of your own new photo onto your own old plan, and check them.
""", id="title"),
    code("""
RECORD_BOOK = None  # ← type your record-book number in quotes, e.g. "19-0457"
import aerophoto
from aerophoto import guide, labs, plots, projective, tasks
from aerophoto.demos import plan_correction as pc
v = aerophoto.setup(RECORD_BOOK)
""", id="setup"),
    md("""
## Why four points are enough

Over flat ground the photo is a central projection of one plane (the ground) onto another (the photo), and so is
its inverse. Every such mapping between two planes is a projective transformation with eight parameters:

$$x' = \\frac{a_1 x + a_2 y + a_3}{c_1 x + c_2 y + 1},\\qquad y' = \\frac{b_1 x + b_2 y + b_3}{c_1 x + c_2 y + 1}.$$

Each control point seen on both gives two equations, so **four points fix it**, provided no three of them lie on
one line (three collinear points carry no more than two would about the perspective). When $c_1 = c_2 = 0$ the
mapping is affine: parallel lines stay parallel. A vertical photo of flat ground is even simpler, a similarity
(one scale, a turn, a shift). A tilt brings in $c_1, c_2$: lines that are parallel on the ground meet on the
photo at a **vanishing point**, and equal steps on the ground become unequal on the photo.

The package fits all three kinds from point pairs, exactly for the minimum number of points and by least squares
beyond it: `projective.fit("projective", photo_xy, plan_xy)` returns the transformation with its residuals
(`aerophoto.plane.fit_projective??` shows the code).

**The guide's work (§10).** Four control points are chosen at the corners of the photo's working area and found
on the plan (a 1:10 000 map). On both, the quadrilateral of the four points is covered by a grid with the same
number of cells; then every change seen on the photo is drawn into the same cell of the plan grid at the same
place inside the cell — by eye or with a proportional compass (пропорциональный циркуль). It works only if the
two grids are images of each other under the projective transformation.
""", id="theory"),
    code("""
guide.ch09.steps_table()
""", id="theory-steps"),
    md("""
## Two ways to draw the grid

**Proportional division.** Divide every side of the quadrilateral into $n$ equal parts and join the points on
opposite sides (the guide's step 3, on the photo and on the plan alike). Equal parts are *not* preserved by a
central projection: the image of the plan's middle is not the middle of the photo's side. So the photo's grid and
the plan's grid are not images of each other; their nodes miss by an amount that depends on the tilt and on how
far apart the four points are — **but not on $n$**.

**Central directions.** All the grid lines of one family pass through one point: the point where the two
opposite sides of the quadrilateral meet (the vanishing point of that direction; at infinity when the sides are
parallel). Drawn like this — or, with a ruler only, by halving the quadrilateral again and again with its
diagonals (`projective.diagonal_grid`) — the grid is exactly the projective image of a regular grid, and the
photo's cell $(j, i)$ maps exactly onto the plan's cell $(j, i)$. What is left is the guess *inside* a cell:
the compass places a point by proportion, which treats the small cell as if it had no perspective. That error
falls as $1/n^2$.

The figure shows both on the example's new photo, tilted by 10° to make the difference visible. In each panel the
plan's grid is drawn by the same method as the photo's, and the green circles are the exact images of the plan
grid's nodes on the photo. With central directions every node sits on its circle (largest miss {MISS_C} mm); with
equal parts the nodes miss their circles by up to {MISS_P} mm. (Compared with the images of the plan's
*equal-part* grid, even the exact central grid would seem to miss: the two methods do not give the same grid, and
what matters is that photo and plan are drawn alike.)
""".format(MISS_C=MISS_C, MISS_P=MISS_P), id="grids-theory"),
    code("""
plots.static(pc.grids_figure(alpha_deg=10.0, n=4),
             alt="Two panels with the same quadrilateral of four control points on a photo tilted by 10 degrees. "
                 "Left: a 4 by 4 grid drawn by central directions; its grid lines converge to the points where "
                 "opposite sides meet, and every node sits on a green circle, the exact image of the node of the "
                 "plan's grid drawn the same way (largest miss {MISS_C} mm). Right: the grid of proportional "
                 "division (equal parts of each side, on photo and plan); its nodes miss the green circles by up "
                 "to {MISS_P} mm.")
""".replace("{MISS_C}", MISS_C).replace("{MISS_P}", MISS_P), id="figure-grids"),
    md("""
How the error of the transfer depends on the grid's density, for three tilts (the example's four points; every
point inside their quadrilateral):
""", id="study-theory"),
    code("""
plots.static(pc.transfer_study_figure(),
             alt="Log-log plot of the largest transfer error on the plan against the number of cells per side n "
                 "from 1 to 32, for tilts 1, 3 and 8 degrees. The solid lines of central directions fall with a "
                 "slope of minus two (halving the cells quarters the error) to hundredths of a millimetre; the "
                 "dashed lines of proportional division stay flat at the error of a single cell, about 0.4 mm "
                 "at 1 degree, 1.2 mm at 3 degrees and 3 mm at 8 degrees.")
""", id="figure-study"),
    md("""
At the guide's tilt of 3° and a 1:10 000 plan, proportional division leaves errors of more than a millimetre on
the plan (1.2 mm here) — twelve metres on the ground, more than a plan may carry (article 001 puts the mean error
of a clear contour point at 0.5 mm). With central directions a 4 × 4 grid is already within a tenth of a
millimetre inside the four points, and 8 × 8 within a few hundredths.

### The third way: similar figures

The guide's step 1 names three ways of building the mutual grids (взаимно-проектные сетки): **similar figures**,
proportional division and central directions (guide §10). In the method of **similar figures** (способ подобных
фигур) the figure of the control points is cut into triangles — here the quadrilateral by its diagonal into two —
and a change is carried into the matching triangle on the plan so that it keeps its place relative to the
triangle's corners (with a proportional compass, or by eye): each triangle is treated as *similar* to its image, an
affine map. That is exact for a vertical photo of flat ground and wrong for a tilted one, because a central
projection does not keep ratios along a line — the same fault as equal parts, at the scale of the whole figure.
`pc.three_methods_study` carries 625 points inside the example's quadrilateral all three ways:
""", id="similar-theory"),
    code("""
pc.three_methods_study().round(3)
""", id="similar-study"),
    md("""
Similar figures err about as much as proportional division — 1.1 mm at 3° against 0.08 mm for a 4 × 4 grid of
central directions — and for the same reason: both assume that the photo keeps proportions. With more control
points the triangles shrink and so does the error; with four, only central directions are exact.

## The plan-correction explorer

The example's piece of farmland, now: black lines on the new photo (left). The old plan (right) shows it as it was.
In vermillion, the changes — a farm of three long buildings, its road, and a field boundary that was moved; on the
plan, where the grids carry them; in dashed green, where they really are.

* **α, λ** tilt the new photo; **n** sets the cells per side; **grid drawn by** switches between the two
  constructions; **spread of 1–4** moves the control points in towards the centre.
* The table gives the errors of the carried changes on the plan (and on the ground), the largest miss of a grid
  node, and the grid's own transfer error inside the four points.
""", id="demo-theory"),
    code("""
demo = pc.PlanCorrectionDemo()
demo
""", id="demo-plan-correction"),
    md("""
**Try this.**

* Switch to *proportional division* and raise $n$: the carried changes stay where they were; the error is in the
  nodes, not in the cells' size. Set α = 0: the two constructions agree, because a vertical photo of flat ground is
  a similarity of the plan.
* Back on *central directions*, lower the **spread** of the control points to 40 %: changes outside the
  quadrilateral are carried by extending its edge cells, and their error grows fast. The guide puts the four
  points at the corners of the working area for this reason.
* `demo.set(alpha_deg=12, n=16)` — steep tilt, fine grid: the grid is still right, inside the four points.
""", id="try-this"),
    md("""
## The guide's worked example

§10 prints no table — only the materials, the list of ways to carry changes onto a plan and the steps above.
The ways it lists:
""", id="example-theory"),
    code("""
guide.ch09.methods_table()
""", id="example-1"),
    md("""
So the worked example is the explorer's scene at the guide's numbers: a photo at 1:12 000 with $f = 100$ mm,
tilted by 3°, and the plan at 1:10 000. Its four control points on the photo and the plan, to 0.01 mm:
""", id="example-2-theory"),
    code("""
example = labs.ch09.lab_for(pc.EXAMPLE_SEED, 100.0, 12000.0, 3.0, -60.0, 10.0)
example.control_table()
""", id="example-2"),
    md("""
Carried cell by cell on a 4 × 4 grid of central directions and, for comparison, by proportional division,
against the truth (plan mm):
""", id="example-3-theory"),
    code("""
import numpy as np
import pandas as pd

photo_xy = example.photo_of("farm building 1")
truth = example.truth_plan_of("farm building 1")
central = example.grid_pair(4, "central").transfer(photo_xy)
proportional = example.grid_pair(4, "proportional").transfer(photo_xy)
pd.DataFrame({"x photo, mm": photo_xy[:, 0], "y photo, mm": photo_xy[:, 1],
              "x plan (truth), mm": truth[:, 0], "y plan (truth), mm": truth[:, 1],
              "miss, central, mm": np.hypot(*(central - truth).T),
              "miss, proportional, mm": np.hypot(*(proportional - truth).T)},
             index=pd.Index([1, 2, 3, 4], name="corner of farm building 1")).round(3)
""", id="example-3"),
    md("""
The central-direction grid puts the corners within a few hundredths of a millimetre (what is left is the
0.01 mm rounding of the points and the cell's own guess); proportional division misses by about a millimetre —
ten metres on the ground — although its grid looks just as neat.

## Task 09.1 — a point carried cell by cell (graded)

Your new photo and your old plan are in the tables below: the four control points 1–4 (photo mm from the
principal point; plan mm at 1:10 000) and the photo positions of the changes. Build the grids of **central
directions** with **4 × 4 cells** on your four points (`projective.grid_pair(photo, plan, 4, "central")`
builds both; `projective.locate` finds a point's cell). For the **first corner of farm building 1**
(`farm building 1/1` in the changes table) give

* `row`, `col` — the cell that contains it on the photo grid: rows are counted from 0 at side 1–2 towards
  side 4–3, columns from 0 at side 1–4 towards side 2–3;
* `x_mm`, `y_mm` — where the cell-by-cell transfer puts it on the plan, mm (tolerance 0.02 mm).
""", id="task-09-1"),
    code("""
lab = tasks.inputs("task-09-1", v)
display(lab.control_table())
lab.changes_table()
""", id="task-09-1-data"),
    answer_cell("task-09-1"),
    check_cell("task-09-1"),
    md("""
## Task 09.2 — the new road on the old plan (graded)

Carry the vertices of the **new road** (`new road/1` … `new road/4` in your changes table) onto the plan with
the projective transformation fixed by your four control points — the limit of an ever finer grid of central
directions (`projective.fit_projective(photo, plan)`) — and give

* `xr_mm`, `yr_mm` — the plan x and y of the road's vertices, in the table's order, mm (tolerance 0.1 mm);
* `road_m` — the road's length on the ground, m: the sum of its segments on the plan times $M/1000$
  (tolerance 0.2 %; it must follow from your own vertices).
""", id="task-09-2"),
    answer_cell("task-09-2"),
    check_cell("task-09-2"),
    md("""
**Think about it.** Measure the same road on the photo and multiply by your $m$: the answer is off by up to about
a per cent, because a tilted photo has no single scale — its $1:m$ is the scale of the equivalent vertical photo.
The corrected plan has one scale everywhere.

## Summary

* A photo of flat ground and its plan are related by a projective transformation; four control points, no three
  on a line, fix it.
* Grids of **central directions** (lines through the vanishing points, or halving by diagonals) are images of
  each other: cell-by-cell transfer converges to the exact map as $1/n^2$.
* Grids of **proportional division** (equal parts of the sides), which the guide's step 3 describes, are not:
  their error depends on the tilt and the spread of the points, not on the density — above a millimetre on a
  1:10 000 plan at the guide's 3°. The third way the guide names, **similar figures** (triangles carried as if
  similar), errs as much: 1.1 mm at 3°.
* Changes outside the four points are extrapolated and quickly lose accuracy: put the points at the corners of
  the working area.

Next: **10 · Ground control**.
""", id="summary"),
]


def main():
    nb = notebook(CELLS, title="09 · Correcting a plan from a new photo")
    write(nb, PATH)
    print("wrote", PATH.relative_to(ROOT))


if __name__ == "__main__":
    main()
