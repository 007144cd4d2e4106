"""Write notebooks/15_block_adjustment.ipynb (chapter 15, article 002) — safe to re-run.

    python docs/tools/build_15_block_adjustment.py

The notebook is rebuilt from the cells below; cells are identified by their ids, so the file a re-run
writes is the same as the one before (outputs are never stored).
"""

from pathlib import Path

from aerophoto import tasks
from aerophoto.nbtools import code, md, nbgrader_answer, nbgrader_tests, notebook, write

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "notebooks" / "15_block_adjustment.ipynb"


from lab_cells import answer_cell, check_cell  # noqa: E402  (docs/tools/lab_cells.py: the shared task cells)


CELLS = [
    md(r"""
# 15 · Bundle block adjustment: locating field points in the mountains (article 002)

In the high mountains of the Pamirs and the Tien Shan a gravimetric survey needs the plan position and
height of every **gravimetric point** (пункт гравиметрических наблюдений, ПГН) — and neither a map nor
barometric levelling gives them reliably there. Article 002 (1987) proposes to locate them from photos:
while the crew reads the gravimeters, the point is marked on the ground and photographed from the
helicopter; in the office the mark is transferred to the **archive aerial photos** of the area, and all
points are computed together by **block phototriangulation** (блочная фототриангуляция) adjusted by the
**bundle method** (метод связок).

**In this chapter you will**

1. write down the **collinearity equations** (уравнения коллинеарности) of a whole block — the exterior
   orientation of every photo and the ground coordinates of every point as unknowns — and see why the
   problem, thousands of unknowns large, is sparse;
2. adjust a simulated block of the mountain site by the article's **three-stage procedure** (strip
   models → joined strips → the block), with a priori weights, control and check points;
3. hunt the planted **blunders** (грубые ошибки) by data snooping and by a robust loss;
4. locate the gravimetric points with their **error ellipses** (эллипсы ошибок) against the truth;
5. set the article's 1986 package limits (table 2) and its technology (table 1) beside what the same work
   costs today;
6. adjust your own block and locate your own gravimetric point.
""", id="title"),
    code("""
RECORD_BOOK = None  # ← type your record-book number in quotes, e.g. "19-0457"
import aerophoto
import math
import numpy as np
import pandas as pd
from aerophoto import bundle, guide, plots, tasks
from aerophoto.demos import bundle_views
from aerophoto.labs import ch15 as lab15
from aerophoto.tasks import ch15
v = aerophoto.setup(RECORD_BOOK)
""", id="setup"),
    md(r"""
## The method of the article (tables 1 and 2)

The article's technology (its table 1) splits the work between a gravimetric party, a survey party and a
computing centre. The office part is what this chapter does with numbers: the points marked from the
helicopter (the СШ-45 camera: f = 20 mm, 24 × 36 mm frame, flown 100–150 m above the point, i.e. photos
at about 1:5000–1:7500) are **re-identified** (переопознаны) on the archive photos at 1:15 000 with
f = 200 mm, measured with the other points on a stereocomparator, and computed by the block program.
The column *here* names the part of the package that does each computational step.
""", id="theory-article"),
    code("""
guide.ch15.technology()
""", id="table-technology"),
    md(r"""
## The collinearity equations of a block

A photo point $(x, y)$, the projection centre $S$ and the ground point $P$ lie on one line. With the
rotation $R$ of the photo (camera → ground) and $\mathbf c = R^{\mathsf T}(P - S)$,

$$x = -f\,\frac{c_1}{c_3},\qquad y = -f\,\frac{c_2}{c_3}.$$

This is the camera model of every chapter (`aerophoto.geometry.ground_to_photo`). In a block the
**unknowns** are, for each of the $n$ photos, its six **elements of exterior orientation** (элементы
внешнего ориентирования) $X_S, Y_S, Z_S$ and the angles $\omega$ (tilt across the flight), $\varphi$
(tilt along it), $\kappa$ (swing), and for each of the $P$ ground points its $X, Y, Z$: $6n + 3P$ in all
— the number table 2 of the article limits to 1000. Every measured coordinate gives one equation,
weighted by $1/\sigma^2$ with its a priori RMS error $\sigma$; every **control point** (опорная точка,
опознак) gives three more, its surveyed $X, Y, Z$ with their own $\sigma$. **Check points**
(контрольные точки) are measured on the photos only: their surveyed coordinates stay out of the
adjustment and judge it afterwards.

The least-squares solution minimises $\sum (v/\sigma)^2$. Each equation involves one photo and one point,
so of the Jacobian's millions of cells only nine per row are not zero. In the normal equations the
points can be eliminated point by point (each is a 3 × 3 block), leaving the **reduced system** of the
photos, $S = U - W V^{-1} W^{\mathsf T}$, only $6n \times 6n$ — the trick by which the 1980s packages
fitted a block into 250 KB, and by which `aerophoto.bundle.adjust` solves it today
(`aerophoto.bundle.solve??`). The same blocks give the covariance of every unknown.
""", id="theory-collinearity"),
    md(r"""
## The worked example: a block of the mountain site

The article's 1985 block had five strips, 64 photos at 1:15 000 with f = 200 mm, and 20 gravimetric
points. Ours is smaller — four strips of seven photos, the same camera and scale — over the mountain
version of the virtual site (heights 1800–2400 m). Tie points sit at the standard positions of each
photo; nine well-defined points of the site's catalogue are the **sparse control** (at the corners, the
middles of the sides and the centre), the other road crossings and field corners are **check points**,
and single trees are the **gravimetric points** (the article chose them next to "bushes of juniper,
single stones"). Photo coordinates are measured with σ = 5 µm, the gravimetric marks — transferred by
eye from the helicopter photo — with 30 µm, the control with 0.5 m. Two blunders are planted: one image
measurement is moved by 0.1 mm and one control height is wrong by 10 m (the article found barometric
heights wrong by 8–12 m).
""", id="example-theory"),
    code("""
ex = lab15.example_block()
pd.Series(ex.meas.summary(), name="example block")
""", id="example-summary"),
    code("""
plots.static(bundle_views.block_figure(ex),
             alt="Map of the mountain site's heights with the 28 photo footprints of the example block in four "
                 "strips, the tie points at the standard positions, the check points, nine control triangles and "
                 "eight gravimetric stars.")
""", id="figure-block"),
    code("""
plots.static(bundle_views.sparsity_figure(ex.meas),
             alt="Left: the non-zero pattern of the Jacobian, equations down, unknowns across, photos left of a "
                 "red line and points right of it; each row has nine entries. Right: the pattern of the reduced "
                 "system of the photo unknowns, a band of blocks between neighbouring photos.")
""", id="figure-sparsity"),
    md(r"""
## Stage 1 and 2: strip models and joined strips

Before the bundle the article builds **each strip on its own** in an arbitrary scale and orientation: the
first photo fixes the strip's frame, each next photo is oriented to the previous one by dependent
**relative orientation** (взаимное ориентирование: five elements from the transverse parallaxes $q$ of the
points the pair shares) and brought to the previous model's scale through the points of their triple
overlap — the method of continuation of chapter 14. Then the strips are **joined** by a 3-D similarity
on the points of the side overlaps, and the whole block is put on its control by one more similarity.
This gives approximate values of all the unknowns, and each stage screens its data: a pair's point whose
$q$ is far above the pair's own RMS, a control point far off the similarity. A similarity cannot bend,
though: the control residuals below mix the block's deformation with any blunder, so only gross errors
show here (`aerophoto.bundle.three_stage??`).
""", id="stages-theory"),
    code("""
sol = ch15.solve_block(ex)
st = sol.stages
print(f"stage 1: {len(st.rms_q_mm)} relative orientations, RMS transverse parallax "
      f"{st.rms_q_mm.min() * 1000:.1f}–{st.rms_q_mm.max() * 1000:.1f} µm; observations rejected: {len(st.rejected_obs)}")
print("stage 2: strips joined to the first"); display(st.joins.round(4))
print("stage 3: the block on its control (residuals of the similarity, m)"); st.control.round(2)
""", id="stages-run"),
    md(r"""
## Stage 3: the bundle adjustment and data snooping

From these approximations the bundle adjustment converges in a few iterations. After it every
observation has a **redundancy number** $r_i = 1 - h_{ii}$ (how much of its own error it can show in its
residual; $\sum r_i$ is the number of degrees of freedom), and Baarda's **standardised residual**
$w_i = v_i / (\sigma_i\sqrt{r_i})$ is normally distributed for a good observation. **Data snooping**
rejects the largest $|w|$ above a critical value (4.0 here, so that a block of a thousand observations
rejects no good one by chance), adjusts again, and repeats (`aerophoto.bundle.data_snooping??`).
""", id="snooping-theory"),
    code("""
sn = sol.snooping
print(f"rounds: {sn.rounds}; σ̂₀ after = {sn.adjustment.sigma0:.3f}; degrees of freedom {sn.adjustment.dof}")
print(f"planted: image blunder on point {ex.blunder_point} (photo {ex.blunder_photo}), "
      f"control {ex.bad_control} off by {ex.bad_control_dz_m:+.0f} m in height")
sn.rejected.round(2)
""", id="snooping-run"),
    md(r"""
A robust loss does the same job without removing anything: the Huber loss weighs an observation
normally up to $k\sigma$ and beyond it only linearly, so a blunder pulls far less and shows a larger
residual. With plain least squares the wrong control height drags its point 5 m off and the image blunder
hides half of itself in the other unknowns; the robust adjustment keeps both nearer the truth. It is a
safety net, not a verdict — the blundered observations are still in, only down-weighted:
""", id="robust-theory"),
    code("""
plain = bundle.adjust(ex.meas, st.eo0, st.xyz0_m)
robust = bundle.adjust(ex.meas, st.eo0, st.xyz0_m, loss="huber", f_scale=2.0)
rows = []
for name, a in (("least squares, blunders in", plain), ("Huber loss (k = 2σ), blunders in", robust)):
    k = a.meas.index_of_point(ex.bad_control)
    rows.append((name, a.xyz_m[k, 2] - ex.truth_of(ex.bad_control)[2],
                 np.hypot(*a.v_img_mm[ex.blunder_obs]) * 1000))
pd.DataFrame([r[1:] for r in rows], index=[r[0] for r in rows],
             columns=["bad control: adjusted Z − true Z, m", "residual of the 100 µm image blunder, µm"]).round(2)
""", id="robust-run"),
    md(r"""
## How good is the block? Check points against the a priori estimate

The covariance of the adjusted points predicts their errors before any check. The check points test the
prediction: the RMS of their true errors should agree with it within its **sampling error**. That error
is larger than "one over the square root of the number of points" suggests: the check points share the
block's datum — the control's own errors shift and tilt the whole block — so their errors are correlated.
The full covariance of all check points gives the spread honestly: $E\,[\sum d^2] = \mathrm{tr}\,C$ and
$\mathrm{Var}\,[\sum d^2] = 2\,\mathrm{tr}\,C^2$ (`aerophoto.bundle.rms_expectation`).
""", id="check-theory"),
    code("""
r, p = sol.check_rms_m(), sol.check_rms_sampling_m()
n_chk = int(np.sum(sn.adjustment.meas.point_kind == "check"))
pd.DataFrame({"check points, true RMS, m": [r["plan"], r["Z"]], "a priori estimate, m": [p["plan"][0], p["Z"][0]],
              "± its sampling SD, m": [p["plan"][1], p["Z"][1]],
              "difference in SDs": [(r["plan"] - p["plan"][0]) / p["plan"][1], (r["Z"] - p["Z"][0]) / p["Z"][1]]},
             index=[f"plan ({n_chk} points)", "height"]).round(3)
""", id="check-run"),
    md(r"""
With well-identified control this block locates points to a few decimetres — about 0.02 mm at the photo
scale in plan. The article's check points in 1985 showed $m_x = m_y = 15$ m and $m_z = 2.5$ m: 1 mm at the
photo scale, fifty times more. Its authors blame the identification of the state geodetic points on the
archive photos; their third group (plan from a 1:25 000 map, heights from barometric levelling: 37, 62
and 5.5 m) is the map's own accuracy. The audit of the experiment's numbers:
""", id="experiment-theory"),
    code("""
guide.ch15.experiment()
""", id="example-experiment"),
    md(r"""
### Is 2.5 m good enough for the gravity map?

The article ends by declaring the method fit for a gravimetric survey at 1:200 000 with isoanomalies
(изоаномалы) every 2 mGal, but never ties that to its errors. A point's height enters the anomaly through the
vertical gradient of gravity. Which gradient? A survey of mountains maps the **Bouguer anomaly** (аномалия Буге),
in which the station's height is corrected twice: the free-air gradient, 0.3086 mGal per metre, and the attraction
of the rock slab under the station, $2\pi G\rho = 0.0419\,\rho$ mGal/m with ρ in g/cm³ — 0.1119 mGal/m for the
usual 2.67 g/cm³. An error in the height therefore moves the Bouguer anomaly by $0.3086 - 0.1119 = 0.197$ mGal/m,
about 0.2 mGal per metre. The free-air gradient alone would be the right one only for a free-air anomaly, which is
not what a mountain gravity map shows; it is the upper bound. The plan error matters through the change of normal
gravity with latitude, at most $0.81\sin 2\varphi$ mGal/km — hundredths of a milligal for 15 m:
""", id="gravity-theory"),
    code("""
free_air = 0.3086               # mGal/m, the normal vertical gradient of gravity
slab = 0.0419 * 2.67            # mGal/m, 2πGρ of the Bouguer slab, ρ = 2.67 g/cm³
bouguer = free_air - slab       # mGal/m: what a height error does to the Bouguer anomaly
latitude = 0.81 * math.sin(math.radians(2 * 39.0)) / 1000   # mGal/m north–south at 39° N (the Pamirs)
rows = [(f"groups 1–2: m_z = 2.5 m, m_x = m_y = 15 m", 2.5, 15.0), ("group 3: m_z = 5.5 m, m_y = 62 m", 5.5, 62.0)]
pd.DataFrame([(name, mz * bouguer, mz * free_air, mxy * latitude, mz * bouguer / 2.0)
              for name, mz, mxy in rows],
             columns=["", "Bouguer, mGal", "free-air, mGal", "from the plan error, mGal",
                      "Bouguer / 2 mGal interval"]).set_index("").round(3)
""", id="gravity-table"),
    md(r"""
So the heights of the first two groups put about **0.5 mGal** into the Bouguer anomalies (0.77 mGal if one
takes the free-air gradient), a quarter of the 2 mGal interval; the plan errors add nothing worth counting.
That is what makes the article's claim hold: an anomaly is off by more than a quarter of the interval in only
about one point in three, inside the third of an interval that topographic instructions allow a contour's height
(article 001, chapter 14) — measured by the same yardstick, the isoanomalies are fit for the map. The third group's 5.5 m gives 1.1 mGal, more than half an interval: fit for the map only where the
anomaly field is steep, not as a rule. The block adjusted above, with its decimetre heights, puts hundredths of a
milligal into the anomalies — far below what the gravimeters themselves read.
""", id="gravity-notes"),
    md(r"""
## The gravimetric points and their error ellipses

A located point's plan covariance $\begin{pmatrix}\sigma_X^2 & \sigma_{XY}\\ \sigma_{XY} & \sigma_Y^2\end{pmatrix}$
defines its **standard error ellipse**: semi-axes $a \ge b$ the square roots of the eigenvalues, the major
axis at $\theta = \tfrac12\,\mathrm{atan2}(2\sigma_{XY}, \sigma_X^2 - \sigma_Y^2)$ from $+X$
(`aerophoto.bundle.error_ellipse`). The true point falls inside its standard ellipse about 39 % of the
time, inside 2.45 times it 95 % of the time. The gravimetric points are measured six times worse than the
tie points, so their ellipses are the largest in the block:
""", id="ellipse-theory"),
    code("""
fp = pd.DataFrame([{"id": p, **sol.field_point(p)} for p in ex.field_ids]).set_index("id")
fp[["X_m", "Y_m", "Z_m", "a_m", "b_m", "theta_deg", "sigma_Z_m", "dX_m", "dY_m", "dZ_m"]].round(2)
""", id="ellipse-table"),
    code("""
plots.static(bundle_views.ellipse_figure(sol),
             alt="The example block's gravimetric points as stars with their standard error ellipses in blue and "
                 "the true error of each adjusted point as a red arrow, both magnified 600 times; most arrows end "
                 "near or inside their ellipse.")
""", id="figure-ellipses"),
    md(r"""
## Live: control, measuring error and a blunder

A smaller block of the same mountains (3 strips × 4 photos at 1:15 000, f = 200 mm), adjusted by the bundle method
as above — linearised at the truth, so that every move is one solution of the same normal equations
(`aerophoto.demos.block_adjustment_live??`). Choose which of the nine control points stay control (the rest
become check points), the measuring error σ of a photo coordinate, and whether one image measurement carries a
blunder, and how large. σ scales all the a priori errors together (the gravimetric marks 6σ, the control 0.1 m per
µm), so the shapes of the ellipses stay and their sizes follow σ. Left: the block, the gravimetric points' standard
ellipses and the check points' true errors, both ×400; the point of the observation data snooping rejects is
ringed. Right: every observation's |w|, sorted, against the critical 4.0.

**Try this.** At σ = 5 µm the 0.1 mm blunder has |w| ≈ 12 and is rejected. Raise σ: its |w| falls as 1/σ — 6.6 at
10 µm, 4.3 at 20 µm — and at 30 µm it passes unseen, while the check points' errors grow in proportion. Switch the
blunder off: no |w| reaches 4. Take the control down to three corners: the height errors and the ellipses grow
several times — nothing holds the block's bending.
""", id="demo-adjustment-theory"),
    code("""
from aerophoto.demos.block_adjustment_live import BlockAdjustmentDemo
adjustment_demo = BlockAdjustmentDemo()
adjustment_demo
""", id="demo-block-adjustment"),
    md(r"""
## The 1986 package and the same work today (table 2)

The article's Fortran-IV package ran in 120–250 KB of memory; its table 2 lists what it could hold. Some
limits follow from others — the smallest block's 54 unknowns are 3 photos × 6 + 12 points × 3 — and the
audit checks them. The largest values cannot all be reached at once: 1000 unknowns is the one that binds.
""", id="limits-theory"),
    code("""
guide.ch15.package_limits()
""", id="example-limits"),
    code("""
import time
t0 = time.perf_counter()
again = bundle.adjust(sn.adjustment.meas, sn.adjustment.eo, sn.adjustment.xyz_m)
t_adj = time.perf_counter() - t0
print(f"the example block: {ex.meas.n_unknowns} unknowns (> 1000: too big for the 1986 package); "
      f"adjusted here in {t_adj * 1000:.0f} ms ({again.n_iterations} iterations from the final values)")
""", id="cost-today"),
    md(r"""
`benchmarks/bench_bundle.py` measures the adjustment of blocks of 20, 100 and 400 photos (up to 9500
unknowns) on a 2-core machine: the time grows from about 0.05 s to a few seconds, the memory to about
150 MB — the reduced system of 400 photos alone is a 2400 × 2400 matrix, 46 MB, two hundred times the
1986 computer's whole memory.

## Task 15.1 — how big is your block? (graded)

Your block: three strips of six photos at **your** scale 1:m with the article's camera (f = 200 mm), over
the mountain site, with your own tie, control, check and gravimetric points (and your own planted
blunders). `block.meas.summary()` counts the photos and points. Compute

* `n_unknowns` — the unknowns of its bundle adjustment;
* `fits_1986` — True if the article's package (table 2: at most 1000 unknowns) could have adjusted it.
""", id="task-15-1"),
    code("""
block = tasks.inputs("task-15-1", v)
pd.Series({k: val for k, val in block.meas.summary().items() if k in ("photos", "strips", "tie points",
           "control points", "check points", "field points", "image observations")}, name=block.name)
""", id="task-15-1-data"),
    answer_cell("task-15-1"),
    check_cell("task-15-1"),
    md(r"""
## Task 15.2 — find the blunders and judge your block (graded)

Your measurements (`block.meas`) contain one blundered image measurement and one control point with a
wrong height. Get approximations with `bundle.three_stage(block.meas)`, run
`bundle.data_snooping(block.meas, stages.eo0, stages.xyz0_m)` and give

* `blunder_point` — the id of the point whose image measurement is rejected;
* `bad_control` — the id of the rejected control point;
* `rms_plan_m`, `rms_Z_m` — after the adjustment, the RMS plan error $\sqrt{\overline{dX^2 + dY^2}}$ and
  the RMS height error of the **check points**, m. Their true coordinates:
  `block.truth_of(point_id)`; the adjusted ones are in the final adjustment's `xyz_m`, in the order of
  its `meas.point_ids` (within 2 %).
""", id="task-15-2"),
    answer_cell("task-15-2"),
    check_cell("task-15-2"),
    md(r"""
## Task 15.3 — locate your gravimetric point (graded)

`tasks.inputs("task-15-3", v)["point"]` is the id of your gravimetric point. From the final adjustment of
task 15.2 give its adjusted `X_m`, `Y_m`, `Z_m` (to 5 cm) and the semi-major axis `a_m` of its standard
error ellipse (within 2 %: `adjustment.precision().cov_points` and `bundle.error_ellipse`).
""", id="task-15-3"),
    code("""
point = tasks.inputs("task-15-3", v)["point"]
print("your gravimetric point:", point)
""", id="task-15-3-data"),
    answer_cell("task-15-3"),
    check_cell("task-15-3"),
    md(r"""
## Summary

* A bundle block adjustment solves the collinearity equations of all photos at once: 6 unknowns per
  photo, 3 per point, weighted by their a priori errors; the points are eliminated point by point and
  only the photos' reduced system is solved — why a 1986 package could fit 1000 unknowns into 250 KB.
* The article's three stages (strip models, joined strips, the block on its control) give approximate
  values and screen gross errors; data snooping on the standardised residuals $w = v/(\sigma\sqrt r)$
  then finds the rest — here a 0.1 mm image blunder and a 10 m control height.
* The covariance predicts the check points' errors before they are checked; the simulation agrees.
* Table 2's minima follow from one another (54 = 3·6 + 12·3); its maxima cannot hold together, the
  1000 unknowns bind. The article's 15 m check-point errors are an identification problem, not a
  limit of the method.
* For the gravity map the heights matter: at the Bouguer gradient 0.197 mGal/m (free air 0.3086 less the slab's
  0.112) the article's m_z = 2.5 m is 0.5 mGal, a quarter of its 2 mGal isoanomaly interval (0.77 mGal with the
  free-air gradient); the plan errors are negligible.

Next: **16 · Contours from a DEM** (article 000).
""", id="summary"),
]

if __name__ == "__main__":
    out = write(notebook(CELLS), OUT)
    print("wrote", out)
