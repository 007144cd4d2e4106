"""Write notebooks/16_dem_contours.ipynb (chapter 16, article 000) — safe to re-run.

    python docs/tools/build_16_dem_contours.py

The notebook is the student book: answer cells hold the task's template lines only (docs/CONTRIBUTING.md,
"Graded tasks"); `aerophoto-course generate` adds the reference solution for nbgrader's source.

The notebook is rebuilt from the cells below; cells are identified by their ids, so the file a re-run
writes is the same as the one before (outputs are never stored).
"""

from pathlib import Path

from aerophoto.nbtools import code, md, notebook, write

from lab_cells import answer_cell, check_cell  # noqa: E402  (the house's answer and check cells)

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "notebooks" / "16_dem_contours.ipynb"


CELLS = [
    md(r"""
# 16 · Contours from a digital elevation model (article 000)

A land-reclamation project (мелиоративная система) needs a large-scale plan whose relief is shown by
**contours** (горизонтали) at a small **interval** (сечение рельефа): article 000 worked at 1:2000 with
h = 0.5 m and required the contours to be right to 15 cm on average. The contours were not drawn at a
stereo plotter but interpolated between the points of a **digital elevation model** (цифровая модель
рельефа, ЦМР) whose heights came from **height densification** (сгущение высотного обоснования) by
analytical block phototriangulation. Two things therefore decide how good the contours are: how well
the block gives the heights of the DEM's points, and how well the points describe the ground between
them.

**In this chapter you will**

1. read Lysenko's formula for the accuracy of height densification — garbled in the scan — and hold it
   against a block of photos adjusted on the virtual site, where the true heights are known;
2. build a **regular** DEM (регулярная модель, a square grid) and a DEM with **structural lines**
   (структурные линии: thalwegs and watersheds, joined into a triangulated network, TIN) of a 1:2000
   sheet of the site, draw their contours and measure them against the true ground — live;
3. compare what the site shows with what the article found (31 cm for the grid, 12 cm with the
   structural lines);
4. forecast the densification of your own block and check the DEMs of your own sheet.
""", id="title"),
    code("""
RECORD_BOOK = None  # ← type your record-book number in quotes, e.g. "19-0457"
import aerophoto
import math
from aerophoto import dem, guide, plots, tasks
from aerophoto.demos.dem_contours import ContourDemo, ContourView, contour_frame, spacing_study_figure
from aerophoto.site import get_site
v = aerophoto.setup(RECORD_BOOK)
site = get_site()
""", id="setup"),
    md(r"""
## How a DEM becomes contours

A DEM is a set of **nodes** with plan coordinates and heights, and a rule for the height between them.
The article compares two ways of choosing the nodes:

* the **regular model**: nodes at the corners of squares of a fixed step d — 7 mm on its 1:4500 photos,
  about 30 m on the ground. Only the heights need storing, and the height between nodes is linear
  (here: bilinear inside each square, `aerophoto.dem.grid_dem`);
* the **structural model** (нерегулярная модель): the operator puts the points where the ground bends —
  along the **thalwegs** (тальвеги, valley lines where water gathers) and the **watersheds**
  (водоразделы, ridge lines), at peaks and pits — and joins them into triangles whose planes follow the
  ground (a TIN; `aerophoto.dem.structural_lines`, `grid_with_lines`, `structural_dem`).

A contour at height z is the line where the DEM equals z. If the DEM is right, the true ground along
that line is at z as well. So the **height error of a contour** is the true height at a point of the
contour minus z; the book samples it along every contour the DEM gives (weighted by length) and reports
its RMS (`aerophoto.dem.contour_accuracy`).

Two errors add up in it, independently. The **interpolation error** m_interp: a straight line between
nodes cuts across every bend of the ground that falls between them — it grows with the step, roughly as
d². The **errors of the node heights** m_z, from the densification: between the nodes the DEM is a
weighted mean of a few node heights, weights wᵢ summing to 1, so an error of RMS m_z in each node leaves
an error of RMS m_z·√(Σwᵢ²). Averaged over a square of bilinear interpolation Σwᵢ² is (2/3)² = 4/9; over a
triangle it is 1/2. Hence the prediction the demo shows,

$$m_{contour} \approx \sqrt{m_{interp}^2 + k\,m_z^2},\qquad k = 4/9 \text{ (grid)},\ 1/2 \text{ (TIN)}.$$
""", id="theory"),
    md(r"""
### Independent or correlated node errors?

The factor 4/9 assumes that the node errors are **independent** — every node off by its own random amount, so
that a weighted mean of four of them averages part of the error away. That is how the demo and the study below
model them (12 cm of independent noise per node gives $\sqrt{4/9}\cdot 12 = 8$ cm). But the 12 cm of the
article is the error of the **densification** (сгущение): the heights of a stereo model follow from the control
the block triangulation gave it, and an error there tilts or bends the whole model — a **block deformation**
that neighbouring nodes 30 m apart share almost entirely. Correlated errors are not averaged down: for node
errors correlated as $\rho(r) = e^{-r/L}$ the share left between nodes is
$\overline{\sum_i\sum_j w_i w_j \rho_{ij}}$, from 4/9 for $L = 0$ to 1 for $L \gg d$
(`dem.correlated_noise_factor`). For the article's 30 m grid:
""", id="theory-correlated"),
    code("""
import pandas as pd
L_m = [0.0, 30.0, 100.0, 300.0, 1000.0]   # correlation length of the node errors, m
k = [dem.correlated_noise_factor(30.0, L) for L in L_m]
pd.DataFrame({"correlation length L, m": L_m, "share k of m_z² left": k,
              "contour error from m_z = 12 cm, cm": [math.sqrt(x) * 12 for x in k]}
             ).set_index("correlation length L, m").round(3)
""", id="correlated-table"),
    md(r"""
A stereo pair at 1:4500 covers about 800 × 320 m, and a block deformation spans several models, so $L$ is
hundreds of metres: the node errors reach the contours nearly whole, **11–12 cm rather than 8 cm**. The book
takes this correlated reading as the realistic one: the node error that matters is the model's, not a random
pointing error of each node (the stereocomparator's 0.005 mm is ten times smaller). The independent model of
the demo is the optimistic limit; it is kept there because it shows what interpolation can do for the part of
the error that *is* independent — the pointing of each node.
""", id="correlated-argument"),
    md(r"""
## Lysenko's formula for height densification

Before building its DEM, the article forecast the accuracy of the block's heights with a formula of
F. F. Lysenko. The scan prints it as

$$m_z = 0{,}25\,\frac{H}{\rho}\sqrt{\frac{3\,(2ns + mn - zr)}{2mns}}$$

with n photos in the block, m points measured on each photo, s images of each point, r control points,
H the flying height and ρ the photo base (printed "p = 70 mm"). Two terms need reading:

* **"zr" is s·r.** Multiply out: $3(2ns + mn - sr)/(2mns) = (6n + 3\,mn/s - 3r)/(2mn) = u/N$ — the number
  of unknowns of a bundle block adjustment (six exterior-orientation elements per photo, three
  coordinates for each of the mn/s points, less the r known control points) over the number of measured
  image coordinates. The root is the classical mean precision of adjusted observations. With "2r" the
  expression counts nothing; an italic *s* read as *z* is an easy slip of the scan.
* **"0,25" is the measurement error m_p** (средняя квадратическая ошибка измерения), a length on the
  photo: the root and H/ρ are pure numbers, so the leading factor carries m_z's unit. As printed,
  0.25 mm, it gives 1.28 m — fifty times the stereocomparator's 0.005 mm and ten times the article's own
  result. Read as **0.025 mm** (a zero lost) it gives 12.8 cm beside the printed 14 cm and the measured
  12 cm. Which error it is — of one image coordinate, or of a parallax (two coordinates, √2 times
  more) — the simulation below decides: the parallax.

So the book uses $m_z = m_p\,(H/b)\,\sqrt{3(2ns + mn - sr)/(2mns)}$ with m_p = 0.025 mm
(`aerophoto.dem.lysenko_mz_m`; the full argument: `guide.ch16.LYSENKO_READING`). The article's inputs
recomputed, with the printed result audited (article 000):
""", id="theory-lysenko"),
    code("""
guide.ch16.lysenko()
""", id="example-1"),
    md(r"""
What each reading of the two terms gives with the article's inputs (H = 450 m, n = 70, m = 16, r = 38,
s = 3, ρ = 70 mm), in centimetres — only the 0.025 mm row is of the article's order:
""", id="example-2-theory"),
    code("""
guide.ch16.lysenko_readings().round(3)
""", id="example-2"),
    md(r"""
### The formula against a simulated block

`dem.lysenko_study` lays blocks of vertical photos with the article's camera (f = 100 mm, 1:4500,
H = 450 m, b = 70 mm) over the site, puts tie points on the true ground under every photo centre, four
rows per strip, and measures every image coordinate with an error σ = m_p/√2 (so that a parallax has
the error m_p = 0.025 mm). The bundle adjustment — six unknowns per photo, three per point, the control
points held — is linearised at the truth (`dem.block_precision`), which gives the exact covariance of the
densified heights; a seeded Monte Carlo of 20 blocks confirms it. The columns: the block's own n, m, s,
r, the simulated RMS error of the densified heights, and Lysenko's m_z with m_p as the parallax error
and as the error of one coordinate.
""", id="sim-theory"),
    code("""
lysenko = dem.lysenko_study(site)
lysenko.round(3)
""", id="sim-lysenko"),
    md(r"""
**What the simulation says.** For a block of the article's size with its control spread over the block
(r = 40, close to the article's 38), the adjusted heights are within about 5 % of Lysenko's m_z read
with the *parallax* error, and some 35 % worse than the formula with the error of a single coordinate:
m_p is the error of a parallax. The formula counts the control points but does not know where they are:
with the same number on the block's edge only, the middle of the block is half as bad again as it
predicts, and a small block does worse than its count suggests. With the article's inputs the formula
gives 12.8 cm; the article printed 14 cm and measured 12 cm.
""", id="sim-summary"),
    md(r"""
### The article's accuracy figures, audited

The article checked its contours against contours drawn on the same photo plan with the SD-3 plotter
(универсальный прибор СД-3), whose own error, from geodetic check points, it measured at **14 cm**. Two of
its statements do not sit with that:

* **31 cm for the regular DEM.** The article "takes the DEM and the SD-3 as equally accurate", i.e. divides
  the RMS of their differences by √2 — although it has just measured the SD-3 at 14 cm. With independent
  errors the difference's RMS is $31\sqrt2 = 43.8$ cm, and the DEM's own error is
  $\sqrt{43.8^2 - 14^2} = 41.5$ cm: worse than printed, and the conclusion (the grid fails the 15 cm) stands.
* **12 cm for the structural DEM**, the RMS of the DEM − SD-3 differences. For independent errors the RMS of a
  difference is at least that of either term, $\sqrt{m_{DEM}^2 + 14^2} \ge 14$ cm — **12 cm is impossible**.
  Either the 12 cm is again per instrument (differences / √2: 17.0 cm, leaving $\sqrt{17.0^2 - 14^2} = 9.6$ cm
  for the DEM), or the two errors are positively correlated — both drawings rest on the same densified
  models, so they share the block's deformation (the argument above), and their difference hides it.
  Either way the structural DEM's 12 cm is not the error of its contours against the ground.
""", id="sd3-audit"),
    code("""
m_sd3 = 0.14   # the SD-3's RMS error against geodetic points, m
rows = [("regular: 31 cm as 'equally accurate' (diff / √2)", 0.31 * math.sqrt(2), math.sqrt(2 * 0.31**2 - m_sd3**2)),
        ("structural: 12 cm as the RMS of the differences", 0.12, float("nan")),
        ("structural: 12 cm as diff / √2", 0.12 * math.sqrt(2), math.sqrt(2 * 0.12**2 - m_sd3**2))]
pd.DataFrame(rows, columns=["reading", "RMS of DEM − SD-3, m", "DEM's own error (independent), m"]).set_index(
    "reading").round(3)   # nan: no real error fits, a difference cannot be smaller than the SD-3's 14 cm
""", id="sd3-audit-table"),
    md(r"""
## Live: contours of a sheet of the site

One 1 km × 1 km sheet (a 1:2000 trapezoid) in the site's hills. The colour is the DEM's error, DEM − true
height; black lines are the contours drawn from the DEM, dashed grey the true ones. The demo opens on the
article's example: a 30 m grid, h = 0.5 m and node heights with the article's measured densification
error, m_z = 12 cm.

* **d, m** — the grid step; **structural lines** — add points along the thalwegs (green) and watersheds
  (orange, dash-dotted), d/2 apart, and triangulate grid and lines together;
* **m_z, m** — the RMS error of the node heights; **h, m** — the contour interval; **sheet** — hills, a
  valley side or the plain.
""", id="demo-theory"),
    code("""
demo = ContourDemo()
demo
""", id="demo-contours"),
    md(r"""
**Try this.**

* Set m_z = 0: at d = 30 m the contours sit on the dashed ones — the site's hills are broad, and a 30 m
  grid follows them to a few millimetres. The whole 8 cm error of the article's example is the
  densification's (modelled as independent node errors; correlated as a block deformation, 11–12 cm — see
  "Independent or correlated node errors?").
* Keep m_z = 0 and raise d to 150 m: now the straight lines between nodes cut the bends (14 cm); switch
  the structural lines on and the error drops by a tenth — the triangles now bend along the spurs.
* Put m_z back to 0.12 m and switch the lines on at d = 30 m: the error *grows* slightly — a TIN averages
  the node errors less than bilinear squares (1/2 against 4/9 of their variance) and the lines add
  nothing the grid had missed.
* `demo.set(sheet="plain (6–7 km E, 0.2–1.2 km N)", interval_m=0.25)` — on flat ground each node error
  moves a contour far sideways.
""", id="try-this"),
    md(r"""
The demo's opening picture, for the record (the article's example: regular 30 m grid, m_z = 12 cm,
h = 0.5 m):
""", id="figure-theory"),
    code("""
plots.static(ContourView(contour_frame()).fig,
             alt="A 1 km sheet of the site's hills with a regular DEM of 30 m step: the DEM's error as a "
                 "red-blue image of small patches within ±0.2 m, the contours drawn from the DEM every 0.5 m in "
                 "black wriggling around the dashed grey true contours, and the grid nodes as small grey dots.")
""", id="figure-demo"),
    md(r"""
## The grid step, the structural lines and the density

`dem.spacing_study` repeats the demo's evaluation for several steps on the hill sheet, each with the
node errors of 12 cm and without them: the regular grid, the grid with structural lines, and a
**structural model of the same density as the grid** — points on the lines and at characteristic points
d apart, the sheet's edge, and the rest of the grid's point budget filling the largest gaps — which is
the article's comparison (152 grid points against 164 structural points per stereo pair). It takes a
few seconds.
""", id="study-theory"),
    code("""
study = dem.spacing_study(site, dem.Sheet(2000.0, 3000.0), progress=print)
study.round(3)
""", id="study"),
    code("""
plots.static(spacing_study_figure(study),
             alt="RMS of contour heights against the grid step from 20 to 150 m. With node errors of 12 cm "
                 "(solid) both DEMs stay near 8–11 cm up to 100 m, the one with structural lines slightly above "
                 "the grid; at 150 m the grid reaches 17 cm and the lines bring it to 15.5 cm. Without node errors "
                 "(dotted) the error grows roughly as the square of the step, to 14 cm for the grid and 12 cm "
                 "with the lines at 150 m.")
""", id="figure-study"),
    md(r"""
**What the site shows, and what it does not.**

* At the article's 30 m step the interpolation error on the site is about 6 mm; the contours' error is
  the densification's, √(4/9)·12 cm = 8 cm, exactly as predicted for independent node errors — well inside
  the article's 15 cm. Correlated as a block deformation they would leave 11–12 cm, still inside.
* The structural lines pay off only where the step is coarse against the landforms, and modestly: a
  tenth at 150 m, where the triangles then bend along the spurs. With node errors and a fine step they
  even cost a little: a TIN averages the node errors less than bilinear squares.
* At **equal density** the structural model is no better than the grid on this site. The site's relief
  is smooth — broad hills, a valley without banks, no gullies, terraces or embankments — and a regular
  grid is about the best one can do for such ground. The article's 31 cm against 12 cm came from
  ground that breaks: where the slope changes suddenly, a grid node falls on either side of the break and
  the straight line between them misses it, while a point on the break line does not. The article names a
  second cause the site cannot show: grid nodes falling on buildings and trees, whose roofs and crowns are
  not the ground (the site's objects have no height).
""", id="study-summary"),
    md(r"""
## Task 16.1 — how well will your block densify the heights? (graded)

Your block (table below): K strips of n_s photos of your camera and photo scale, 18 cm frame, forward
overlap p_x = 60 %, the article's m = 16 points per photo and s = 3 images per point, r = 3K control
points. (For large variants H is many kilometres: the guide's scheme raises f and m together; the
formula holds at any height.) Compute

* `H_m` — the flying height H = f·m, m;
* `b_mm` — the photo base b = l·(1 − p_x/100), mm;
* `mz_m` — Lysenko's $m_z = m_p\,(H/b)\,\sqrt{3(2ns + mn - sr)/(2mns)}$ with m_p = 0.025 mm, in metres (the
  book reads the scan's "zr" as s·r; read as 2r, the other reading, it is accepted too, with the h that follows);
* `h_m` — the smallest contour interval of the standard series 0.25, 0.5, 1, 2, 2.5, 5, 10, 20, 25, 50, 100 m
  whose requirement your densification meets by itself: the mean error m_z/1.25 at most 0.3·h (the
  article's 15 cm for h = 0.5 m).
""", id="task-16-1"),
    code("""
block = tasks.inputs("task-16-1", v)
block.table()
""", id="task-16-1-data"),
    answer_cell("task-16-1"),
    check_cell("task-16-1"),
    md(r"""
## Task 16.2 — check points of your sheet (graded)

Your sheet is a 1 km square of the site of its own (`aerophoto.labs.ch16.sheet_of(v)` gives its corner);
its regular DEM has the step of the article's 7 mm on *your* photo, d = 0.007·m metres, and node heights
with the article's densification error of 12 cm. The table gives 40 check points: their true
("geodetic") heights `Z_geod_m` and the heights read from the regular DEM (`Z_grid_m`) and from the same
DEM with the structural lines added (`Z_lines_m`). With Δ = Z_DEM − Z_geod compute

* `m_grid_m` and `m_lines_m` — the RMS errors $\sqrt{\sum\Delta^2/n}$ of the two DEMs, m (the true heights are
  known: divide by n);
* `v_lines_m` — the mean error $\sum|\Delta|/n$ of the DEM with structural lines, m;
* `share_pct` — the share of its |Δ| within 15 cm, % (the article counted 70 %).
""", id="task-16-2"),
    code("""
points = tasks.inputs("task-16-2", v)
points
""", id="task-16-2-data"),
    answer_cell("task-16-2"),
    check_cell("task-16-2"),
    md(r"""
**Think about it.** Is your structural DEM better than your grid? For about half of the variants it
is, by a centimetre or two; for the others the ground of the sheet is smooth enough for the grid, and the
TIN's weaker averaging of the node errors shows. Forty check points also have a sampling error of their
own: an RMS from 40 errors is uncertain by about 1/√80 ≈ 11 %.
""", id="task-16-2-note"),
    md(r"""
## Summary

* Lysenko's formula reads $m_z = m_p\,(H/b)\,\sqrt{3(2ns+mn-sr)/(2mns)}$: the root is √(u/N) of a bundle
  block, m_p the error of a measured parallax (0.025 mm; the scan's "0,25" lost a zero). It gives
  12.8 cm for the article's block — the article printed 14 cm — and agrees within about 5 % with a
  simulated block whose control is spread over it; with control on the edge only it is too optimistic.
* Contours from a DEM carry the node errors, reduced by interpolation (4/9 of their variance on a grid,
  1/2 on a TIN) only as far as they are independent — a block deformation shared by neighbouring nodes passes
  whole (11–12 cm, not 8, for the article's 12 cm) — and the interpolation error, which grows with the step.
* The article's 31 cm assumes the DEM and the SD-3 equally accurate although the SD-3 was measured at 14 cm
  (independent errors: 41.5 cm), and its 12 cm RMS of DEM − SD-3 differences is below the SD-3's own 14 cm —
  impossible for independent errors.
* On the site's smooth hills a 30 m grid is as good as its nodes; structural lines help only at coarse
  steps, and at equal density they do not beat the grid — the article's gain needs ground with breaks
  of slope (and grid points on roofs), which the site does not have.

Next: **17 · The error budget of map updating**.
""", id="summary"),
]

if __name__ == "__main__":
    print("wrote", write(notebook(CELLS), OUT))
