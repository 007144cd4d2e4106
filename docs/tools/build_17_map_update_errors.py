"""Write notebooks/17_map_update_errors.ipynb (chapter 17, article 003) — safe to re-run.

    python docs/tools/build_17_map_update_errors.py

The notebook is the student book: answer cells hold the task's template lines only (docs/CONTRIBUTING.md,
"Graded tasks"); `aerophoto-course generate` adds the reference solution for nbgrader's source.
"""

from pathlib import Path

from aerophoto.nbtools import code, md, notebook, write

from lab_cells import answer_cell, check_cell  # noqa: E402  (the house's answer and check cells)

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "notebooks" / "17_map_update_errors.ipynb"


CELLS = [
    md(r"""
# 17 · The error budget of updating a map (article 003)

When a topographic map is **updated** (обновление карт) at a **digital photogrammetric station**
(цифровая фотограмметрическая станция, ЦФС), a building corner reaches the new map through a chain of
work: control points, scanning, phototriangulation, a DEM, orthorectification, mosaicking, vectorising.
Each link adds its own error. Article 003 lists the links, gives each an RMS error, adds them up and
asks whether the result meets the instruction: a **mean error** (средняя ошибка) of at most 0.4 mm on the
map for buildings. Its answer is "not quite" — 0.44–0.45 mm; with its own rule for mean errors applied to
the transfer between strips, 0.50 mm.

**In this chapter you will**

1. see how independent errors add (root-sum-square) and how the article turns mean errors into RMS
   errors and back;
2. recompute the article's tables 1–5 and every number of its text, with a note where a printed number
   does not follow;
3. move the sliders of a live budget — photo scale, scanning resolution, map scale, the DEM, the relief —
   and watch which stage dominates and whether the 0.4 mm is met;
4. measure your own vectorising error and work out the budget of updating your map from your photos.
""", id="title"),
    code("""
RECORD_BOOK = None  # ← type your record-book number in quotes, e.g. "19-0457"
import aerophoto
import math
from aerophoto import budget, guide, plots, tasks
from aerophoto.demos.error_budget import BudgetDemo, budget_figure
v = aerophoto.setup(RECORD_BOOK)
""", id="setup"),
    md(r"""
## Adding errors

Errors of stages that do not depend on each other add as the squares of their RMS errors (средние
квадратические ошибки, СКО) — the article's formula (10):

$$m_D = \sqrt{m_{пл/в}^2 + m_{ск}^2 + m_ф^2 + m_{ЦМР}^2 + m_{орт}^2 + m_{н/м}^2 + m_{вект}^2}.$$

The largest terms decide the sum: a stage half as large as the largest adds only an eighth to the total.
Everything is first brought to the same footing — metres on the ground: an error on the map is
multiplied by the map's scale denominator M_k, an error on the photo by the photo's M_c.

Instructions state tolerances as **mean errors** v (the mean of |error|), photogrammetry works with RMS
errors m. For normally distributed errors m = √(π/2)·v ≈ 1.2533·v; the article rounds it to
**m = 1.25·v** (formulas 1 and 5) and uses it both ways (`budget.rms_from_mean`, `budget.mean_from_rms`).
The map's 0.4 mm mean error is therefore an RMS error of 0.5 mm.
""", id="theory"),
    md(r"""
## The stages, one by one (article 003)

| stage | Russian | the article's RMS error | where from |
|---|---|---|---|
| control survey | планово-высотная подготовка, m_пл/в | 1.25 · 0.1 mm on the map | instruction: control points to 0.1 mm (mean) |
| scanning | сканирование, m_ск | 3 µm on the photo | the Deltascan scanner |
| phototriangulation | построение сетей фототриангуляции, m_ф | $m_{x,y} = 0.84\,M_c\,\sigma$ (7), $m_D = \sqrt2\,m_{x,y}$ (8), σ = 0.5·P | GPS and a gyro-stabilised mount; P the scanning pixel |
| DEM | создание ЦМР, m_ЦМР | 1.25 · 0.3 mm on the map | the instruction's largest relief distortion, 0.3 mm |
| orthorectification and mosaic | ортотрансформирование и монтаж, m_орт | 1.25 · 0.1 mm | what is left of the 0.7 mm allowed misfit at a seam after 2 × 0.3 mm of relief |
| transfer between strips | перенос точек на смежные маршруты, m_н/м | $\sqrt{[d^2]/(2(n-1))}$ (9), d = 0.5 mm (a mean), n = 50 | double measurements of common points |
| vectorising | векторизация, m_вект | 0.11 mm on the map | the authors' experiment, table 1 |

Three rows are not estimates but **tolerances** of the instruction turned into RMS errors: the DEM,
orthorectification and the transfer between strips. They are also the three largest. The relief limit
behind the DEM row is formula (2), $h_{пред} = 0.3\,f\,M_k/r$ — the height above the mean plane that
displaces a point at r mm from the nadir by 0.3 mm on the map (`budget.relief_limit_m`; with f and r in
mm the product is in millimetres, so divide by 1000 for metres).
""", id="theory-stages"),
    md(r"""
## The article's tables, recomputed

Each table below is recomputed from its own printed inputs by `aerophoto.budget`; every printed number is
set beside the value that follows (one rule for the whole book: within 0.6 of a unit of its last
printed digit). A number that does not follow is listed to the right of its table, with the reason.

### Table 1 — the vectorising error (formulas 3–6)

Two corners of a building on a 1:2000 orthophoto were measured 20 times; V_X, V_Y are the mean absolute
deviations from the mean (3), $V_D = \sqrt{V_X^2 + V_Y^2}$ (4), $m_D = 1.25\,V_D$ (5), and on the map
$m_d = m_D/M_k$ (6).
""", id="example-theory"),
    code("""
guide.ch17.table1()
""", id="example-1"),
    md(r"""
### Tables 2 and 3 — scanning and phototriangulation
""", id="example-2-theory"),
    code("""
guide.ch17.table2()
""", id="example-2"),
    code("""
guide.ch17.table3()
""", id="example-3"),
    md(r"""
### The numbers in the text

The control, DEM and orthorectification errors, formula (9) for the transfer between strips, the
instruction's other transfer rule (40 µm on the photo), and the two errors of the closing paragraph
(interior orientation 0.625·P·M_c; an image-measurement error σ = 1.25·0.5P·√2 = 0.884·P instead of
0.5·P).
""", id="example-4-theory"),
    code("""
guide.ch17.text_values()
""", id="example-4"),
    md(r"""
**One slip, and its fix.** The instruction's d = 0.5 mm is the **mean** discrepancy of the common points
(средние расхождения). Formula (9), the RMS from double measurements, takes the discrepancies themselves,
$[d^2] = \sum d_i^2$; the article puts the mean in as if every discrepancy were exactly 0.5 mm and gets
$0.5\sqrt{50/98} = 0.357$ mm (printed 0.35, the many-points value d/√2 = 0.354). Its own rule (1) turns a mean
error into an RMS first: the discrepancies have an RMS of 1.25·0.5 = 0.625 mm, and (9) then gives
$0.625\sqrt{50/98} = 0.446$ mm (for many points $1.25\cdot0.5/\sqrt2 = 0.442$ mm). The tables carry 0.35 on; the
book's budget uses 0.446 mm (`budget.transfer_from_mean_mm`) — for the 1:2000 plan $m_d = 0.621$ mm and
$v_d = 0.497$ mm (0.618 and 0.494 with 0.442), against the article's 0.56 and 0.45. The verdict stands, further
from the 0.4 mm.

### Tables 4 and 5 — the stages on the ground and the total
""", id="example-4-summary"),
    code("""
guide.ch17.table4()
""", id="example-5"),
    code("""
guide.ch17.table5()
""", id="example-6"),
    md(r"""
Table 5 follows from table 4. Its 1:2000 mean error, 0.45 mm, was divided from the rounded
m_d = 0.56 mm (0.56/1.25 = 0.448); from the unrounded 0.5558 mm it is 0.4447 — still within the rounding
rule. With the transfer at 0.446 mm the totals grow to 0.62 mm RMS, 0.50 mm mean (notes under the table);
the verdict stands.
All the discrepancies of article 003:
""", id="example-summary"),
    code("""
guide.ch17.discrepancies()
""", id="example-discrepancies"),
    md(r"""
## The live budget

Each bar is one stage's RMS error on the map, in mm; the bottom bar is their root-sum-square, green when
the mean error v_d = m_d/1.25 is within 0.4 mm (the dashed line is the equivalent RMS, 0.5 mm). The
largest stage is vermillion. The demo opens on the article's 1:2000 case (1:10 000 photos, f = 153 mm,
23 cm frame, P = 16 µm).

* **Photos**: the photo scale 1:M_c, the scanning pixel P, the focal length f;
* **Map**: the map scale 1:M_k; the closing paragraph's two errors in or left out;
* **Ground**: the DEM stage — the instruction's tolerance (the article), a DEM of height accuracy m_h
  (an error Δh displaces a point r mm from the nadir by r·Δh/f on the ground; r is the RMS distance of
  the photo's working area, 53.5 mm for a 23 cm frame at 60 %/30 % overlap), or no DEM at all — the photo
  rectified onto its mean plane, the relief Δh left in (heights spread evenly over Δh have an RMS of
  Δh/√12 about that plane).
""", id="demo-theory"),
    code("""
demo = BudgetDemo()
demo
""", id="demo-budget"),
    md(r"""
**Try this.**

* Move the map scale from 1:2000 to 1:10 000: almost nothing changes — five of the seven stages are
  defined on the map and scale with it. Only scanning and triangulation, fixed on the photo, shrink.
* Choose "DEM of accuracy m_h": the article's DEM row is a DEM with a height error of about 2.1 m at
  1:2000 (0.375 mm × 2000 × 153/53.5). A DEM good to 0.5 m drops the mean error to 0.40 mm — just over
  the tolerance, because the transfer between strips, already the largest stage, stays.
* Choose "no DEM" and raise Δh: by the article's formula (2) a plane is enough while the relief stays
  within about ±1 m at 1:2000 and ±5 m at 1:10 000 (h_пред in the table).
* A coarser scan (P = 42 µm) and smaller photos (1:15 000) matter little at 1:2000: the mean error goes
  from 0.45 to 0.47 mm, and triangulation stays a minor stage.
""", id="try-this"),
    md(r"""
What would bring the article's maps within 0.4 mm? `budget.scenarios` replaces the tolerances one at a
time by what the work can actually do — a DEM good to 0.5 m, the transfer between strips at the
instruction's 40 µm on the photo — and adds the two errors the article named last but left out:
""", id="scenarios-theory"),
    code("""
budget.scenarios(10_000, 16, 2000).round(2)
""", id="scenarios"),
    code("""
plots.static(budget_figure(budget.budget(10_000, 16, 2000)),
             alt="Bars of the seven stages' RMS errors on a 1:2000 map from 1:10 000 photos: the DEM (0.375 mm) "
                 "and the transfer between strips (0.446 mm) are the longest, control and orthorectification "
                 "0.125 mm, vectorising 0.11 mm, triangulation and scanning below 0.05 mm; the total, 0.62 mm, "
                 "passes the dashed 0.5 mm RMS tolerance line.")
""", id="figure-budget"),
    md(r"""
**Reading the budget.** The article concludes that either the intermediate stages must become more
accurate or the map's tolerance must change. The budget says which stages: the two largest are the
instruction's tolerances for the transfer between strips and for the DEM. Replace the transfer by what a
digital station actually achieves (40 µm on the photo) and the map passes; a real DEM alone brings it to
0.40 mm, just over; both together leave a wide margin. The photo scale and the scanning resolution — the
things one pays for — hardly matter at these scales.
""", id="scenarios-summary"),
    md(r"""
### Two more readings of the article's budget

Formula (10) adds the seven stages as independent errors. Two of its entries can be read another way:

* **The transfer between strips is counted twice.** Carrying tie points onto the photos of the next strip
  is part of building the block: in a block adjustment (chapter 15) the tie points' errors *are* the
  triangulation's errors, and the instruction's 0.5 mm discrepancy is a check on the adjusted block, not an
  extra step after it. Counted as a stage of its own it enters the total a second time. Left out (as part of
  m_ф), the plan's total falls to 0.43 mm RMS, a mean error of 0.35 mm: the map passes. Against that, the
  article's m_ф comes from the image-measurement error σ = 0.5·P alone, which leaves out identifying the
  same point on two strips; so the book keeps the stage, as the article does, and shows the total without it.
* **The orthorectification allowance is subtracted linearly.** Of the 0.7 mm misfit allowed at a seam the
  article gives 0.6 mm to the relief (0.3 mm with opposite signs on the two sides) and keeps 0.7 − 0.6 =
  0.1 mm (mean) for orthorectification. Added in squares, as (10) adds everything else, the allowance would be
  $\sqrt{0.7^2 - 0.6^2} = 0.36$ mm mean, 0.45 mm RMS, and the plan's mean error 0.61 mm. The book keeps the
  linear split: the 0.6 mm is a worst case of two relief displacements of known, opposite signs — systematic,
  not a random error — and a worst case adds linearly; the square-root reading would allow the
  orthorectification four times more than the article does.
""", id="readings-theory"),
    code("""
import pandas as pd

def _totals(B, ortho_rms_mm=None):
    # formula (10), optionally with another orthorectification RMS on the map (mm): (m_d, v_d) on the map, mm
    sq = sum(s.rms_m**2 for s in B.stages)
    if ortho_rms_mm is not None:
        sq += (ortho_rms_mm * B.M_k / 1000) ** 2 - B.stage("ortho").rms_m ** 2
    m_d = math.sqrt(sq) / B.M_k * 1000
    return m_d, m_d / 1.25

ortho_sq = 1.25 * math.sqrt(0.7**2 - 0.6**2)   # RMS of the allowance taken in squares, mm
cases = {"the book (transfer 0.446 mm, ortho 0.125 mm)": _totals(budget.budget(10_000, 16, 2000)),
         "the article (transfer 0.357 mm)": _totals(budget.budget(10_000, 16, 2000,
                                                                  transfer_mm=budget.transfer_rms_mm())),
         "transfer counted once, in triangulation": _totals(budget.budget(10_000, 16, 2000, transfer_mm=0.0)),
         "ortho allowance in squares (0.45 mm RMS)": _totals(budget.budget(10_000, 16, 2000), ortho_sq)}
pd.DataFrame(cases, index=["m_d, mm", "v_d, mm"]).T.assign(**{"v_d ≤ 0.4 mm": lambda d: d["v_d, mm"] <= 0.4}).round(3)
""", id="readings-table"),
    md(r"""
## Task 17.1 — your vectorising error (graded)

You measured one corner of a building 20 times on the 1:10 000 orthophoto of your update (table below,
coordinates in metres). As in the article's table 1, compute

* `VX_m`, `VY_m` — the mean errors $V = \sum|\Delta_i|/n$ with Δᵢ the deviations from the mean, m (3);
* `VD_m` — the mean plan error $V_D = \sqrt{V_X^2 + V_Y^2}$, m (4);
* `mD_m` — the RMS plan error $m_D = 1.25\,V_D$, m (5);
* `md_mm` — on the map, $m_d = m_D/M$ with M = 10 000, in mm (6).
""", id="task-17-1"),
    code("""
corner = tasks.inputs("task-17-1", v)
corner
""", id="task-17-1-data"),
    answer_cell("task-17-1"),
    check_cell("task-17-1"),
    md(r"""
## Task 17.2 — triangulation and scanning on your photos (graded)

Your photos (1:m and f of your variant) were scanned with the pixel P of your variant (the guide has no
scanning; the book gives variant i the pixel P = 12 + 3·(i mod 10) µm — see the table). Compute

* `sigma_um` — σ = 0.5·P, µm;
* `mxy_m` — formula (7), $m_{x,y} = 0.84\,M_c\,\sigma$, m on the ground;
* `mphi_m` — formula (8), the triangulation stage $m_ф = m_D = \sqrt2\,m_{x,y}$, m;
* `msc_m` — the scanning stage, the scanner's 3 µm on the photo, m on the ground.
""", id="task-17-2"),
    code("""
case = tasks.inputs("task-17-2", v)
case.table()
""", id="task-17-2-data"),
    answer_cell("task-17-2"),
    check_cell("task-17-2"),
    md(r"""
## Task 17.3 — the error budget of your update (graded)

You update the guide's 1:10 000 map (1/M, guide §1) from your photos, and — to save the DEM — you rectify
each photo onto its mean plane. The whole relief of your area, Z_max − Z_min, stays in the photos. Take
the other stages as the article does: control and orthorectification 1.25·0.1 mm, vectorising 0.11 mm on
the map, the transfer between strips 0.446 mm (rule (1), then formula 9: see "One slip, and its fix"),
scanning and triangulation from task 17.2 (the article's own transfer, 0.357 mm, is accepted too, with the total,
mean error, verdict and dominant stage that follow from it). Compute

* `mrel_m` — the relief stage, in place of the DEM: $(r_{rms}/f)\cdot\Delta h/\sqrt{12}$ on the ground, m, with
  $r_{rms} = \sqrt{(b_x^2 + b_y^2)/12}$ the RMS distance of the working area $b_x = l(1-p_x)$ by $b_y = l(1-p_y)$
  from its centre (18 cm frame, 60 % and 30 %);
* `mD_m` — the total, formula (10), m on the ground;
* `vd_mm` — the mean error on the map $v_d = m_D/M/1.25$, mm;
* `ok` — `True` if v_d ≤ 0.4 mm;
* `dominant` — the name of the largest stage, one of `budget.STAGES`' English names:
  "control survey", "scanning", "phototriangulation", "DEM" (here: the relief), "orthorectification and
  mosaic", "transfer between strips", "vectorising".
""", id="task-17-3"),
    code("""
tasks.inputs("task-17-3", v).table()
""", id="task-17-3-data"),
    answer_cell("task-17-3"),
    check_cell("task-17-3"),
    md(r"""
**Think about it.** A long-focus camera (large f) sees the ground more steeply, so the relief displaces
its images less: compare your relief stage with a neighbour's whose variant number is far from yours.
""", id="task-17-3-note"),
    md(r"""
## Summary

* Independent errors add as squares: formula (10). Mean and RMS errors differ by 1.25 (√(π/2)).
* Article 003's tables follow from their inputs, but for one number: the transfer between strips. The
  instruction's 0.5 mm is a mean discrepancy; rule (1) makes it 0.625 mm RMS and formula (9) then gives
  0.446 mm (the article: 0.357, printed 0.35). The 1:2000 total becomes 0.62 mm RMS, 0.50 mm mean: the
  0.4 mm tolerance is missed more clearly.
* Two more choices of the article are open: the transfer is also part of the triangulation's error and is
  counted twice (without it the plan passes, 0.35 mm), and the orthorectification allowance 0.7 − 0.6 is
  subtracted linearly where formula (10) works in squares ($\sqrt{0.7^2 - 0.6^2} = 0.36$ mm: 0.61 mm).
* The budget is dominated by two tolerances of the instruction — the transfer between strips (0.446 mm) and
  the DEM (0.375 mm, a DEM 2 m off in height at 1:2000) — not by what the digital station does; the 40 µm
  digital transfer rule alone brings the map within 0.4 mm.
* Without a DEM the relief takes over: (r/f)·Δh, so long lenses and flat ground forgive rectification onto
  a plane; formula (2) says how much relief a plane can take.

Back to **00 · Start here** for the book's other chapters.
""", id="summary"),
]

if __name__ == "__main__":
    print("wrote", write(notebook(CELLS), OUT))
