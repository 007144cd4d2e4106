"""Write notebooks/06_strip_triangulation.ipynb (guide §7) from its cells (safe to re-run).

    python docs/tools/build_06_strip_triangulation.py

Cells are identified by id; the notebook is written without outputs.  The graded work is on the student's own
strip (aerophoto.tasks.ch06); the live demo opens on the guide's worked example, variant 00.
"""

from pathlib import Path

from aerophoto.nbtools import code, md, notebook, write

from lab_cells import answer_cell, check_cell  # noqa: E402  (same folder)

ROOT = Path(__file__).resolve().parents[2]
PATH = ROOT / "notebooks" / "06_strip_triangulation.ipynb"

CELLS = [
    md("""
# 06 · Building a single-strip phototriangulation (guide §7)

A photo plan needs four known points on every photo, but surveying them all on the ground is slow and
expensive. **Phototriangulation** (фототриангуляция) finds most of them in the office: a few control points
(опознаки) surveyed at the ends of a strip, and the photos themselves carry their positions across the
strip. This chapter follows the guide's §7 — the *single-strip phototriangulation* (одномаршрутный
фототриангуляционный ряд) built with direction templates on tracing paper — and does every step with
numbers on a simulated strip, where the truth is known.

**In this chapter you will**

1. see why directions from a point near the principal point survive tilt and relief;
2. prick working centres, orienting, tie and control points and draw the direction templates;
3. build a strip on the plan from both ends to the middle (guide §7, figures 15–16);
4. lay a *free* strip in an arbitrary scale and reduce it to the plan (tables 8 and 9) with a live demo;
5. recompute the guide's tables 8 and 9 and find which printed numbers do not follow;
6. check the error triangles of **your own** strip and compute its table 8 and table 9 (graded).
""", id="title"),
    code("""
RECORD_BOOK = None  # ← type your record-book number in quotes, e.g. "19-0457"
import aerophoto
from aerophoto import geometry, simulate, site, tasks, triangulation
from aerophoto.demos.reduction import (ReductionDemo, TemplateView, StripView, EndsView, SiteStripView,
                                       own_site_figure, own_templates_figure, own_strip_figure)
from aerophoto import guide
v = aerophoto.setup(RECORD_BOOK)
""", id="setup"),
    md("""
## Why radial directions

On a vertical photo of flat ground the picture is a true, reduced copy of the ground: every angle is
kept. Two things spoil it. **Relief** shifts each point along the line from the nadir point $n$,
by $\\delta_h = r\\,h/H$ (chapter 03); **tilt** shifts it along the line from the isocentre $c$ (chapter 04).
Both displacements are *radial*: they move a point along the ray through $n$ or $c$, not across it. So the
**direction** from $n$ (or $c$) to any point is free of the relief displacement (or the tilt
displacement), and on a near-vertical photo $o$, $n$ and $c$ are only a few millimetres apart
($on = f\\,\\mathrm{tg}\\,\\alpha$). Radial triangulation (радиальная фототриангуляция) uses exactly this:
from one point near the principal point it keeps only **directions**, never distances.

That point is the photo's **working centre** (рабочий центр): a sharp contour point within
$r \\le f/30$ of the principal point (guide §13 step 3), so that the directions from it are "almost"
radial. On each photo one also pricks (накалывает):

| point | Russian | where (guide §13 step 3) | purpose |
|---|---|---|---|
| working centre | рабочий центр | within $f/30$ of $o$; transferred to both neighbours | vertex of the directions; its neighbours give the **initial directions** (начальные направления) |
| orienting point | ориентирующая точка | corners of the working area: middle of the double forward and side overlaps | the points the strip delivers for rectifying each photo |
| tie point | связующая точка | triple overlap, 2–3 cm from the upper and lower edge | three directions meet there: they carry the scale from photo to photo |
| control point | опознак | surveyed; at the ends of the strip | tie the strip to the plan |

A **direction template** (восковка направлений) is a sheet of tracing paper laid on the photo with the
rays drawn from the working centre to every pricked point. The figure below shows the points of a
five-photo strip like the guide's example (f = 70 mm, 1:12000; guide §7, figure 15) over the book's
virtual site, and then two of its templates.
""", id="theory"),
    code("""
terrain = site.get_site()
strip7 = simulate.strip_over_site(terrain, geometry.Camera(70), 12000, 60, 5)
points7 = triangulation.design_points(strip7.camera, strip7.poses, terrain, catalogue=terrain.catalogue,
                                      control_layout="ends")
aerophoto.plots.static(SiteStripView(strip7, points7, site=terrain).fig,
                       alt="Five photo footprints of a strip over the virtual site, with the pricked points: a working "
                           "centre near each principal point, orienting points at the corners of the working areas, "
                           "tie points in the triple overlaps and four control points on each end photo")
""", id="figure-points"),
    code("""
templates7 = triangulation.measure_templates(strip7.camera, strip7.poses, points7, pricking_mm=0.1, seed=7)
fig = aerophoto.plots.figure(figsize=(10.5, 4.6))
axes = fig.subplots(1, 2)
TemplateView(templates7, 1, ax=axes[0]); TemplateView(templates7, 2, ax=axes[1], legend=False)
aerophoto.plots.static(fig, alt="The direction templates of photos 2 and 3: rays from each working centre to every "
                                "point pricked on the photo, the two rays to the neighbouring centres drawn thick and "
                                "orange as the initial directions")
""", id="figure-templates"),
    md("""
The thick **orange** rays are the **initial directions** to the neighbouring working centres; the grey ones go
to every other pricked point. The points were taken from the site's catalogue where it has a well-defined point
at the designed place (a road crossing, a field corner), elsewhere at the designed place itself
(`points7.table()` lists which); each was pricked on every photo with an error of 0.1 mm — the accuracy the
guide expects of pricking (guide §13 step 2) — so the directions are slightly wrong, as on real paper.
""", id="figure-notes"),
    md("""
## Building on the plan from both ends (guide §7)

When the first and the last photo each have three or four control points, the strip can be built at once
in the plan's scale (guide §7, figure 16):

1. the first and last templates are set on the plan by **resection** (обратная засечка): turned and slid
   until their rays pass through their control points;
2. working inwards, the second and the second-to-last templates are resected on what is already known:
   the previous centre, the control points they see and the **initial direction** — the next centre must
   lie on the ray drawn towards it;
3. the middle template is reached from both sides and gets **two solutions**, $3'$ from the left and $3''$
   from the right, each with its own pair of tie points above and below it ($m', n'$ and $m'', n''$). The
   most probable positions are the midpoints of the discrepancies (невязки);
4. the strip is adjusted: the middle template is centred on $3$; its upper and lower rays may miss $m$ and
   $n$ by at most 0.3 mm; the neighbours are re-laid so their rays go through the tie points, and every
   **error triangle** (треугольник погрешностей) at a tie point — three rays that should meet in a point —
   must have sides ≤ 0.3 mm.

The package does each step as a small least-squares problem (`plane.resect_directions`,
`plane.intersect_rays`); beside the plan below the middle centre's two solutions are shown enlarged.
""", id="theory-ends"),
    code("""
ends = triangulation.build_from_ends(templates7, M=10000)
aerophoto.plots.static(EndsView(ends).fig, alt="The strip built on the plan from both ends: the rays of every template, "
                                              "the points and their error triangles enlarged; beside it the middle "
                                              "centre from the left, from the right, their mean and the truth, enlarged")
""", id="figure-ends"),
    code("""
ends.summary().round(3)
""", id="table-ends"),
    md("""
The two solutions of the middle centre differ by a few tenths of a millimetre on the plan: each carries
the errors accumulated from its own end, and neither is the truth (the green star). The guide takes the
midpoint as the most probable position; the tie points $m$, $n$ are treated the same way. The largest error of a
point on the plan is the accuracy of the densification; compare it with the 0.4 mm the guide allows when a
strip is laid on the plan (§13 step 9).
""", id="ends-notes"),
    md("""
## The free strip and its reduction (guide §7 steps 7–9)

In production the strip is more often laid **free** (свободный ряд): templates are laid one on another in
an arbitrary scale, without the plan, and only afterwards brought to the plan with a few control points.
The first template goes down anywhere; the next one goes with its working centre on the initial direction
from the first, its own initial direction back along it, at any distance — that distance sets the strip's
scale. Every further template goes with its centre on the previous initial direction and slides along it
until its rays pass through the tie points found from the two templates before — three rays per tie point,
an error triangle if they do not meet.

**Reduction** (редуцирование) brings the free strip to the plan's scale and orientation:

1. plot the control points on the base (основа) from their coordinates and measure, for each pair
   (a *base*), the distance on the base $l_{осн}$ and on the free strip $l_{воск}$; the **reduction
   coefficient** of the base is
   $$k = \\frac{l_{осн}}{l_{воск}},$$
   and the coefficients of all bases may differ from their mean by at most 0.003 (guide §7, table 8; 0.006
   for short bases, §13);
2. take one working centre as the centre of the whole strip; for every point measure its distance $r$ from
   it and lay off the **correction**
   $$v = r\\,(k - 1)$$
   along the ray from the centre — away from it when $v > 0$ ($k > 1$, the strip was laid too small),
   towards it when $v < 0$ (guide §7, table 9);
3. lay the corrected sheet on the base so that the corrected control points fall on their plotted
   positions (a turn and a shift, no more scaling) and transfer every point.

Step 2 is a *scaling about the centre*; step 3 a *rotation and shift*. Together they are the similarity
transformation that takes the free strip onto the plan. Where the centre is does not matter for the
result — scaling about another point differs only by a shift, which step 3 absorbs — it only changes how
long the corrections are; a middle centre keeps them short.

**A short base.** The guide relaxes 0.003 to 0.006 "for short bases" without saying what short is. The book
takes a base as short when $0.003\\,l_{осн}$ would be less than the 0.4 mm the graphical work can hold at
all: $l_{осн} < 0.4/0.003 = 133$ mm (`triangulation.SHORT_BASE_MM`). On such a base a spread of 0.003
means a length error below what the graphical work can hold, so the relaxed 0.006 applies.
""", id="theory-reduction"),
    md("""
### Live: the reduction explorer

A strip of four photos, 36 to 39 as in guide §13, opening on the guide's worked example (variant 00:
$f$ = 100 mm, 1:12 000). Sliders: the camera ($f$ up to 1100 mm, the photo scale $1:m$ up to 1:22 000 — every
variant of the course — and the largest tilt), the free strip's arbitrary scale $q$ as a fraction of the plan's,
the pricking error $m_p$, the central working centre and the random draw. The strip is drawn on the left in the
free strip's own millimetres: template rays (grey), error triangles (vermillion, enlarged by the factor in the
corner), the correction vectors $v$ (purple, exaggerated), and — as open orange triangles — where the base's
control points fall when carried back into the free strip's frame. On the right, every base's $k$ with the mean
and the tolerance band (green inside, red outside). Where a tilt would carry the photos off the 10 × 5 km site
(at the largest $H = f\\,m$), the demo flies the largest tilt that keeps them on it and says so under the table.
""", id="theory-demo"),
    code("""
demo = ReductionDemo()   # the guide's worked example, variant 00: f = 100 mm, 1:12 000
demo
""", id="demo-reduction"),
    md("""
**Try this.**

* Move $q$ from 0.96 to 0.8: $k$ follows $1/q$ (1.04 → 1.25) and the arrows grow fivefold, but the control
  residuals in the table do not change — the scale of the free strip is arbitrary.
* Set the pricking error to 0: with vertical photos the triangles vanish (relief barely turns directions taken
  near the nadir) and the coefficients agree. Raise it to 0.3 mm: the triangles triple and the spread of $k$
  leaves the 0.003 band.
* Add a tilt of 2–3° with the pricking error at 0: now the directions from the working centres are bent by the
  tilt, and triangles appear even without pricking error — a few thousandths of a millimetre, far below the
  0.3 mm: near-vertical photos are what the method needs, and what it gets.
* Choose centre 36 instead of 37: the largest correction grows by half (7 → 10 mm), the result does not change.
* Change $f$ at a fixed scale, from 100 to 1000 mm: nothing changes — radial directions do not care about the
  flying height, which is why the method works over hilly ground.

From code: `demo.set(scale_ratio=0.85, pricking_mm=0.2)`, `demo.reset()`.
""", id="try-this"),
    md("""
## The guide's worked example: table 8 (guide §7)

The guide's input: four control points with coordinates (X north, Y east, metres — the Russian geodetic
convention), a plan at 1:10000 and a free strip on which the four distances between them were measured:

| control point | X, m | Y, m |
|---|---|---|
| 496/1 | 6067202 | 310574 |
| 496/2 | 6065910 | 310466 |
| 498/1 | 6066967 | 312528 |
| 498/2 | 6065525 | 312664 |

The package recomputes the table from these inputs: the base lengths from the coordinates, and the
coefficients both from the printed $l_{осн}$ and from the recomputed one.
""", id="example-theory"),
    code("""
t8 = guide.ch06.table(8)   # the audit: recomputed table, every printed number checked
t8.table.round(4)
""", id="example-table8"),
    code("""
t8.comparison(only_discrepancies=False).set_index("where")   # every printed number of table 8
""", id="example-table8-check"),
    md("""
**Printed vs computed (table 8).**

* **Rows 1 and 2 are right**: 496/1–498/1 is 1968.1 m apart, 196.8 mm at 1:10000 (printed 197), and
  $197/190 = 1.0368$ (printed 1.037); 498/1–498/2 is 144.8 mm (printed 145), $145/140 = 1.0357$
  (printed 1.036).
* **Row 3 does not follow.** 498/2–496/2 is 2231.5 m apart: $l_{осн} = 223.1$ mm, not the printed 222;
  and the printed $K = 1.037$ is not $222/217 = 1.023$ (nor $223.1/217 = 1.028$).
* **Row 4 does not follow.** 496/2–496/1 is 1296.5 m apart: 129.7 mm, not 131; and $131/126 = 1.040$,
  not the printed 1.038.
* **The mean and the spread.** The printed $K$ average 1.037 and their printed deviations ΔK stay within
  ±0.001, but only because rows 3 and 4 are wrong. From the printed lengths the coefficients range from
  1.023 to 1.040 (the largest deviation from their mean, 1.034, is 0.011); from the coordinates, from 1.028
  to 1.036 (largest deviation 0.004). Either way the **0.003 rule is broken** and, by the guide's own rule,
  the strip would have to be laid again.
""", id="example-table8-notes"),
    md("""
## The guide's worked example: table 9 (guide §7)

Table 9 lists, for twelve points, the distance $r$ from the chosen centre and the correction $v = r\\,(k - 1)$
with $k = 1.037$.
""", id="example-theory-9"),
    code("""
t9 = guide.ch06.table(9)
t9.table.round(3)
""", id="example-table9"),
    code("""
t9.comparison().set_index("where")   # the printed numbers of table 9 that do not follow
""", id="example-table9-check"),
    md("""
**Printed vs computed (table 9).** Every printed $v$ is $r \\times 0.037$ rounded to 0.1 mm — the arithmetic
is right. What does not hold together are the point labels, garbled in the scan ("7/967", "7/867", "7/267"
repeat): 496/1 appears twice (both at 40 mm) and 498/1 twice with two different distances (76 and 96 mm),
which one point cannot have from one centre. Worse, on the free strip of table 8 the points 496/1 and
498/1 are 190 mm apart, so no centre can be 40 mm from the first and at most 96 mm from the second
($40 + 96 < 190$). The table's distances were therefore not measured on the strip of table 8; they
illustrate the formula only.
""", id="example-table9-notes"),
    md("""
## Your strip

Now the guide's work on **your** strip: the four photos 36–39 you glued into a fotoschema in chapter 05 —
**your** camera ($f$ = 100 + 10·i mm), **your** scale (1:(12 000 + 100·i)), $p_x$ = 60 %, at a place of the
virtual site of your own, near-vertical (tilts up to 2°, less for long lenses: $f\\,\\mathrm{tg}\\,\\alpha \\le$
6 mm so that the photos stay on the site). On every photo the working centre, the orienting points А–Е, the
tie points a–d and the control points 36/1, 36/2, 39/1, 39/2 were pricked with the guide's 0.1 mm, the
templates drawn, and the templates laid into a free strip at a scale of your own — between 0.92 and 0.97 of
the plan's or between 1.03 and 1.08, depending on your variant — exactly as the demo does. Then the common
tracing was measured to 0.1 mm.

**Coordinates.** Your tables use the **Russian geodetic convention**, as the guide's table 8 does: $X$ north
and $Y$ east for the control points (metres, in the style of the guide's catalogue), and on the sheet of the
strip $x$ up and $y$ to the right along the strip, directions $\\alpha$ measured **clockwise from +x**. (The
package computes internally with $X$ east, $Y$ north and angles counter-clockwise, `aerophoto.geometry`; the
swap of axes changes no distance, and `triangulation.geodetic` converts.) A ray from $(x_0, y_0)$ in the
direction $\\alpha$ is $(x_0 + s\\cos\\alpha,\\ y_0 + s\\sin\\alpha)$.

For large variants the strip is long: at 1:21 900 it spans some 8.7 km, 87 cm at 1:10 000 — more than the
guide's 25 × 40 cm tracing paper holds. The numbers work all the same (the guide's scheme taken honestly).
""", id="lab-theory"),
    code("""
aerophoto.plots.static(own_site_figure(v), alt="Your four photo footprints over the virtual site with the points "
                                               "pricked on them: working centres 36–39, orienting points А–Е, tie points "
                                               "a–d and the control points 36/1, 36/2, 39/1, 39/2")
""", id="lab-site"),
    code("""
aerophoto.plots.static(own_templates_figure(v), alt="Your four direction templates 36 to 39: rays from each working "
                                                     "centre to every point pricked on the photo, the initial "
                                                     "directions to the neighbouring centres in orange")
""", id="lab-templates"),
    code("""
aerophoto.plots.static(own_strip_figure(v), alt="Your templates laid into the free strip: the rays of every template, "
                                                "the working centres, orienting, tie and control points, drawn with "
                                                "x up and y to the right along the strip")
""", id="lab-strip"),
    md("""
## Task 06.1 — the error triangles of your strip (graded)

At each tie point a, b, c, d three rays of your laid templates meet — from the template of the photo the tie point
was chosen on and from its two neighbours. The table gives each ray as laid on the sheet: the template's working
centre $(x, y)$ in mm and the ray's direction $\\alpha$ in degrees, clockwise from +x. For every tie point
intersect the three rays two by two and measure the sides of the **error triangle** the three intersections form.

(Two rays $P = A + s\\,u_A$ and $P = B + t\\,u_B$ with $u = (\\cos\\alpha, \\sin\\alpha)$ meet at
$s = \\dfrac{(B - A) \\times u_B}{u_A \\times u_B}$, where $a \\times b = a_x b_y - a_y b_x$. Geodesists know it as
the forward intersection, прямая засечка.)

Set

* `triangle_mm` — the largest side of the error triangle at a, b, c and d, mm (a list of four, in that order);
* `triangles_ok` — `True` if every side is within the guide's 0.3 mm, else `False`.

Tolerance: 0.01 mm.
""", id="task-06-1"),
    code("""
readings = tasks.inputs("task-06-1", v)   # your strip's readings (the same for tasks 06.1–06.3)
readings.rays_table()
""", id="task-06-1-data"),
    answer_cell("task-06-1"),
    check_cell("task-06-1"),
    md("""
## Task 06.2 — the reduction coefficients of your strip (table 8, graded)

The control points' coordinates (X north, Y east, m) give their places on the base at 1:10 000; their positions
on your free strip were measured on the common tracing. As in table 8, take the four bases around the strip
**in this order**: 36/1–39/1, 39/1–39/2, 39/2–36/2, 36/2–36/1. Set

* `l_base_mm` — the four lengths on the base $l_{осн}$, from the coordinates, in mm at 1:10 000;
* `l_template_mm` — the same four on the free strip $l_{воск}$, mm;
* `k_bases` — the four reduction coefficients $k = l_{осн}/l_{воск}$;
* `k_mean` — their mean;
* `spread_ok` — `True` if every $|k - \\bar k|$ is within 0.003 (0.006 on a base shorter than 133 mm on the base),
  else `False`.

Tolerances: 0.05 mm for the lengths, 0.0005 for the coefficients (the guide prints them to three decimals), 0.0011
for the mean (the mean of the written coefficients, written to three decimals, as table 8 does).
""", id="task-06-2"),
    code("""
readings.control_table()   # your control points: coordinates and positions on the free strip
""", id="task-06-2-data"),
    answer_cell("task-06-2"),
    check_cell("task-06-2"),
    md("""
## Task 06.3 — the corrections for reduction (table 9, graded)

Take working centre **37** as the centre of your strip and your `k_mean` of task 06.2. For every other point of
the common tracing (the table below, without 37, **in its order**; tie points are not transferred to the common
tracing) measure its distance $r$ from 37 and compute the correction $v = r\\,(k - 1)$ — positive: laid off away
from the centre, negative: towards it. Set

* `r_mm` — the distances from 37, mm (13 values);
* `v_mm` — the corrections, mm, in the same order.

Tolerances: 0.05 mm for $r$; for $v$ 0.05 mm or 4 % (so $k$ as the guide's table writes it — the mean of the
coefficients written to three decimals, itself written to three decimals — passes).
""", id="task-06-3"),
    code("""
readings.points_table()   # every point of your common tracing, in the order of the guide's table 13
""", id="task-06-3-data"),
    answer_cell("task-06-3"),
    check_cell("task-06-3"),
    md("""
## Summary

* Radial triangulation keeps only **directions** from a working centre within $f/30$ of the principal
  point: relief and tilt move points along rays from $n$ and $c$, so those directions are nearly exact.
* Working centres, orienting points (corners of the working area), tie points (triple overlap, 2–3 cm from
  the edge) and control points are pricked on every photo they appear on; a direction template is drawn for
  each photo; the rays to the neighbouring centres are the initial directions.
* With control on the first and last photos the strip is built on the plan from both ends (resection),
  the middle template gets two solutions, the mean is taken, and error triangles must stay within 0.3 mm.
* A free strip is reduced with $k = l_{осн}/l_{воск}$ (spread ≤ 0.003, or 0.006 on bases shorter than
  133 mm) and the corrections $v = r\\,(k-1)$ from a central working centre, then turned and shifted onto
  the control points of the base.
* The guide's table 8 is inconsistent in its rows 3 and 4 and, recomputed, breaks its own 0.003 rule;
  table 9's arithmetic is right but its distances cannot come from the strip of table 8.

Continued in **12 · Phototriangulation** — how far apart the control points may be (Zhukov's formula) and the
whole procedure of guide §13 on your strip (tables 12 and 13).
""", id="summary"),
]


def main() -> None:
    write(notebook(CELLS), PATH)
    print(f"wrote {PATH.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
