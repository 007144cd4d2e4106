"""Write notebooks/12_phototriangulation.ipynb (guide §13) from its cells (safe to re-run).

    python docs/tools/build_12_phototriangulation.py

Cells are identified by id; the notebook is written without outputs.  The graded work is on the student's own
strip of chapter 06 (aerophoto.tasks.ch12); the live demo opens on the guide's worked example, variant 00.
"""

from pathlib import Path

from aerophoto.nbtools import code, md, notebook, write

from lab_cells import answer_cell, check_cell  # noqa: E402  (same folder)

ROOT = Path(__file__).resolve().parents[2]
PATH = ROOT / "notebooks" / "12_phototriangulation.ipynb"

CELLS = [
    md(r"""
# 12 · Phototriangulation: control spacing and the reduced strip (guide §13)

Chapter 06 built a strip of radial directions and reduced it to the plan. This chapter follows the
guide's §13 — the whole procedure of graphical **phototriangulation** (фототриангуляция), the office
densification of the survey control from the photos — and asks the question that comes first in practice:
**how far apart may the control points be?** The guide answers with G. P. Zhukov's formula (13.1), which
the scan has garbled; we work out what it must say and test it against simulated strips.

**In this chapter you will**

1. read Zhukov's formula for the control spacing, decide its garbled radicand and check it by simulation;
2. go through the nine steps of §13 on a four-photo strip 36–39: templates, the free strip, tables 12 and
   13, and the 0.4 mm check;
3. compute the control spacing for your camera and scale, and tables 12 and 13 of your own strip (graded).
""", id="title"),
    code("""
RECORD_BOOK = None  # ← type your record-book number in quotes, e.g. "19-0457"
import aerophoto
import math
import pandas as pd
from aerophoto import tasks, triangulation
from aerophoto.demos.reduction import (ReductionDemo, TemplateView, StripView, AccumulationView, reduction_model,
                                       own_strip_figure)
from aerophoto import guide
v = aerophoto.setup(RECORD_BOOK)
""", id="setup"),
md(r"""
## Planar phototriangulation

Phototriangulation finds ground coordinates of points from their images. **Spatial** phototriangulation
gives $X, Y, Z$ (analytically, or on stereo instruments); **planar** gives only $X, Y$ (guide §13). The
planar kind can be analytical, analogue or **radial**. The radial kind rests on the fact met in chapter 06:
on a near-vertical photo the directions drawn from the principal point — or a sharp point near it, the
*working centre* — are almost free of the relief and tilt displacements. Drawn graphically, with tracing
paper, it needs no instrument, and it is what the guide's students do: photos with about 60 % forward
overlap (at least 56 %), so that every second photo shares a triple overlap with its neighbours.
""", id="theory"),
    md(r"""
## How far apart may the control points be? Zhukov's formula (13.1)

The guide's step 1 computes the spacing of control points along the strip, in photo bases, "by
G. P. Zhukov's formula". As scanned it reads

$$m = 0.25\,k_i\,b_{ср}\,\frac{m_\varepsilon}{\rho'}\sqrt{n^0 + 11n + 34}, \tag{13.1}$$

with $m$ the RMS error of an orienting point (to be kept at 0.35 mm on the plan), $k_i$ the enlargement
from the photo to the plan ($m/M$), $b_{ср}$ the mean photo base (≈ 60 mm, says the guide, at $p_x = 60\,\%$),
$m_\varepsilon$ the RMS error of a direction (4′–5′), $\rho' = 3437.75'$ and $n$ the number of bases
between the outermost control points. A radicand $n^0 + 11n + 34 = 11n + 35$ makes no sense — then why
write $n^0$? The book reads it as

$$\boxed{m = 0.25\,k_i\,b_{ср}\,\frac{m_\varepsilon}{\rho'}\sqrt{n^3 + 11n + 34}}$$

(the superscript 3 scanned as 0), for three reasons.

**1. How errors travel along a radial strip.** Each template hands the strip's direction on to the next
through its initial directions. Independent direction errors $\varepsilon_j$ therefore *add up*: the
azimuth of base $j$ is $\theta_j = \varepsilon_1 + \dots + \varepsilon_j$, and the sideways position of
point $k$ is $b\,(\theta_1 + \dots + \theta_k)$ — a sum of sums. Fit such a chain to control points at
both ends and the variance left at its middle is, exactly,

$$\sigma^2_{mid} = \frac{n^3 + 2n}{48}\,b^2 \sigma_\theta^2$$

(`triangulation.bridge_variance_factor`): a **cube in $n$ with no $n^2$ term**, the shape of
$n^3 + 11n + 34$. If each base passes on the azimuth with the error of three directions
($\sigma_\theta^2 = 3 m_\varepsilon^2$: back and forward initial directions and the laying), the coefficient
is $\sqrt{3/48} = 0.25$ — the formula's own. The terms $11n + 34$ are the errors that do not accumulate
(intersecting the point itself, the control points). The accuracy article on phototriangulation networks
(G. V. Romanovsky's law of error accumulation) finds the same: each link's error persists in all the
following ones, so the last point's error grows as $\sqrt{\sum k^2} \sim n^{3/2}$, and the middle of a strip
tied at both ends gets half the error of a strip half as long — again $n^{3/2}$. With $n^0$ the error would
grow like $\sqrt{n}$, as if nothing were carried from template to template.

**2. The guide's own numbers.** With $m = 0.35$ mm, $k_i \approx 1$, $b = 60$ mm and $m_\varepsilon = 4'$–$5'$
the reading $n^3$ gives 5–6 bases between control points — the usual spacing for graphical radial
triangulation. The other readings give strips two to five times longer:
""", id="theory-zhukov"),
    code("""
guide.ch12.zhukov_readings().round(2)   # n for m = 0.35 mm, k_i = 1, b = 60 mm: the guide's inputs
""", id="zhukov-readings"),
    md(r"""
**3. A simulation.** The package lays free strips of 2 to 10 bases over flat ground with vertical photos,
pricks every point with the guide's 0.1 mm, reduces them to a 1:10000 plan from two control points at each
end (photo scale 1:12000, so $k_i = 1.2$; base 72 mm) and measures the RMS error of the orienting points
and working centres against the truth, over 20 random draws per length. A pricking error of 0.1 mm at the
ends of a 72 mm direction is an error of $0.1/72$ rad $= 4.8'$ — inside the guide's 4′–5′. The curves are
(13.1) with that $m_\varepsilon$ and the three radicands; none of them is fitted.
""", id="theory-simulation"),
    code("""
study = triangulation.accumulation_study(n_bases=(2, 3, 4, 5, 6, 8, 10), seeds=range(20))
aerophoto.plots.static(AccumulationView(study, k_i=1.2, b_mm=72.0).fig,
                       alt="RMS error of reduced free strips against the number of bases between the control "
                           "points: the simulated points rise with the curve of (13.1) read with n cubed, far above "
                           "the n squared and n to the zero readings; the allowed 0.35 mm is a horizontal line")
""", id="figure-zhukov"),
    code("""
m_eps = triangulation.PRICKING_MM / 72.0 * triangulation.RHO_ARCMIN   # 0.1 mm over a 72 mm direction: 4.77′
sim = study["RMS error of points, mm"]
formula = triangulation.zhukov_error_mm(sim.index.to_numpy(dtype=float), k_i=1.2, b_mm=72.0, m_eps_arcmin=m_eps)
pd.DataFrame({"simulated, mm": sim, "(13.1) with n³, mm": formula,
              "(13.1) against the simulation, %": 100 * (formula / sim - 1)}).round(3)
""", id="zhukov-compare"),
    md(r"""
The simulated errors follow the $n^3$ reading, though not closely: the formula lies **13 %, 30 %, 24 % and 22 %
above** the simulation for 2, 3, 4 and 5 bases (at $n = 4$: 0.357 mm against 0.288 mm) and **5 %, 16 % and 6 %
below** it for 6, 8 and 10 bases — within 30 % everywhere, and with the right growth, while the $n^2$ and $n^0$
readings fall far below the simulation once the strip is longer than three or four bases. The simulation
crosses the 0.35 mm line between 4 and 5 bases (0.288 mm at 4, 0.361 mm at 5), (13.1) at 3.9 bases
(`triangulation.zhukov_bases_continuous`) — a formula for planning is allowed to be a little cautious.

One more remark on the inputs: at $p_x = 60\,\%$ the base of an 18 cm frame is $0.4 \times 180 = 72$ mm, not
the guide's "≈ 60 mm" (that is the base of a 15 cm frame, or of an 18 cm frame at $p_x \approx 67\,\%$).
""", id="zhukov-notes"),
    md(r"""
## The procedure of §13 on a strip 36–39

The guide's steps, as the package does them on a simulated strip of four photos (f = 100 mm, 1:12000, plan
1:10000):

1. the control spacing (above);
2. four control points are transferred onto the photos — at the middle of the forward and side overlaps of
   the first and last pair (36/1, 36/2, 39/1, 39/2);
3. working centres 36–39 within $f/30$ of the principal points; **orienting points** А–Е at the corners of
   the working areas; **tie points** a–d in the triple overlaps, 2–3 cm from the edges;
4. – 5. every pricked point is transferred onto a template, and the rays are drawn from the working centre;
   the rays to the neighbouring centres are the **initial directions** (figure 22 shows template 38);
""", id="theory-procedure"),
    code("""
example = reduction_model(n_photos=4, first_number=36, seed=100, scale_ratio=0.95, centre=2)
aerophoto.plots.static(TemplateView(example.templates, 2).fig,
                       alt="The direction template of photo 38: rays from its working centre to every point pricked "
                           "on it, the rays to centres 37 and 39 drawn thick and orange as the initial directions")
""", id="figure-template-38"),
    md(r"""
6. the templates are laid on one sheet starting from 36 (or 39): 37 with its centre on the initial direction
   36–37 — shifted along it to choose the free strip's scale, here 0.95 of the plan's — then 38 so that its
   centre lies on the direction 37–38 and its rays pass through the tie points a and b found from 36 and 37,
   and so on. At every tie point three rays meet; the **error triangle** they form must have sides
   ≤ 0.3 mm;
7. centres, orienting and control points are transferred onto the common sheet (tie points are not);
""", id="theory-procedure-2"),
    code("""
example.free.table().round(3)
""", id="example-triangles"),
    md(r"""
The triangles here are small: each template after the second was turned and slid until its rays passed
as near as possible through the tie points *and* its initial direction matched — the guide's "achieving
the coincidence of the centres with the initial directions and with the directions through a and b" — so
only the disagreement left over by that best fit shows. Laid strictly by the initial direction alone
(`triangulation.lay_free_strip(..., method="initial")`), the same templates give triangles several times
larger; the 0.3 mm tolerance is meant for that rougher, purely graphical laying.
""", id="example-triangles-notes"),
    md(r"""
8. the control points are plotted on the base (основа) from their coordinates; the distances between them
   are measured on the base, $l_{осн}$, and on the sheet, $l_{воск}$, and every base gets its **reduction
   coefficient** $k_{ред} = l_{осн}/l_{воск}$ (table 12); their spread may be 0.003, or 0.006 on short bases
   (the book: shorter than 133 mm, where 0.003·l would be less than the 0.4 mm graphical precision).
   One of the middle centres, 37 or 38, is the centre of the strip; every point's distance $r_i$ from it
   is measured and its correction $v_i = r_i\,(k_{ред} - 1)$ laid off along the ray — away from the
   centre if positive, towards it if negative (table 13);
""", id="theory-procedure-3"),
    code("""
example.reduction.coefficients.table().round(4)
""", id="example-table12"),
    code("""
example.reduction.corrections.table().round(2)
""", id="example-table13"),
    md(r"""
9. the corrected sheet is laid on the base so that the corrected control points fall on the plotted ones
   (a turn and a shift); they may miss by at most 0.4 mm; then every point is transferred onto the base.
   The figure is the laid strip with its error triangles, the correction arrows and the base's control
   points carried back onto the sheet; the table gives each point's position on the plan and its error
   against the truth the simulation knows.
""", id="theory-procedure-4"),
    code("""
aerophoto.plots.static(StripView(example.free, example.reduction).fig,
                       alt="The free strip 36 to 39 with its rays, the error triangles enlarged, the correction "
                           "arrows from centre 37 and the control points of the base carried into the strip's frame")
""", id="figure-strip"),
    code("""
example.reduction.table().round(3)
""", id="example-final"),
    md(r"""
**Printed vs computed (§13).** The section's tables 12 and 13 are blank forms (no numbers to check). The
scan's slips, all in labels and symbols:

* formula (13.1): the radicand "$n^0 + 11n + 34$" — read $n^3 + 11n + 34$ (above);
* the mean base "$b_{ср} \approx 60$ mm at $p_x = 60\,\%$" — 72 mm for the 18 cm frame of guide §1;
* "ρ_x = 60 %" is the forward overlap $p_x$;
* the reduction formulas are numbered (12.2) and (12.3) inside §13 (read 13.2, 13.3);
* the orienting points "A, B, B, C, D, E" are the Cyrillic А, Б, В, Г, Д, Е;
* table 12's row "33/1 – 39/2" is 36/1 – 39/2 (there is no point 33/1; the six rows are the six pairs of
  36/1, 36/2, 39/1, 39/2);
* table 13 lists 39/2 twice ("39/1 39/2", "39/2").
""", id="example-notes"),
    md(r"""
### Live: the reduction explorer

The same explorer as in chapter 06 (four photos 36–39, opening on the guide's worked example, variant 00), here
with tilted photos: the guide's method assumes near-vertical ones. With the pricking error at 0, a tilt of 3°
bends the directions from the working centres by the tilt displacement: error triangles appear even with perfect
pricking — but only about 0.01 mm — and the reduced strip misses its control points by about 0.05 mm instead of
nothing. Both stay far inside the 0.3 and 0.4 mm tolerances: near-vertical photos are what the method needs.
Then move the central centre: the corrections change, the result does not.
""", id="theory-demo"),
    code("""
demo = ReductionDemo(max_tilt_deg=1.0)   # variant 00 (f = 100 mm, 1:12 000), photos tilted up to 1°
demo
""", id="demo-reduction"),
    md(r"""
## Task 12.1 — the control spacing for your camera (graded)

Use (13.1) read with $n^3 + 11n + 34$ and **your** inputs:

* $m = 0.35$ mm, the allowed RMS error of an orienting point on the plan;
* $k_i = m_{photo}/M$ — your photo scale denominator over the plan's, $M = 10000$;
* $b_{ср} = l\,(100 - p_x)/100$ with $l = 180$ mm and your $p_x$;
* $m_\varepsilon = 4' + 0.5'\cdot(i \bmod 3)$, $i$ your variant number (so 4′, 4.5′ or 5′); $\rho' = 3437.75'$.

Set

* `m3_mm` — the predicted error $m$ for a strip of $n = 3$ bases (the four photos of §13), mm (tolerance 0.5 %);
* `n_max` — the largest whole number of bases for which $m \le 0.35$ mm (0 if even one base exceeds it).
""", id="task-12-1"),
    code("""
given = tasks.inputs("task-12-1", v)   # your inputs to (13.1)
print(given)
""", id="task-12-1-inputs"),
    answer_cell("task-12-1"),
    check_cell("task-12-1"),
    md(r"""
## Your strip (the same as in chapter 06)

Tables 12 and 13 are worked on **your** strip of chapter 06: your photos 36–39, pricked, laid free at a scale
of your own and measured on the common tracing to 0.1 mm — the same readings. The control points are in the
Russian geodetic convention (X north, Y east, m), the strip's sheet with $x$ up and $y$ to the right along the
strip (chapter 06, "Your strip").
""", id="lab-theory"),
    code("""
aerophoto.plots.static(own_strip_figure(v), alt="Your templates laid into the free strip: the rays of every template, "
                                                "the working centres, orienting, tie and control points, drawn with "
                                                "x up and y to the right along the strip")
""", id="lab-strip"),
    md(r"""
## Task 12.2 — table 12: does your strip pass the reduction check? (graded)

Compute the reduction coefficient $k = l_{осн}/l_{воск}$ of **all six** bases between your four control points,
in the order of table 12: 36/1–36/2, 36/1–39/1, 36/1–39/2, 36/2–39/1, 36/2–39/2, 39/1–39/2 ($l_{осн}$ from the
coordinates at 1:10 000, $l_{воск}$ on the free strip), their mean $\bar k$ and each base's deviation
$\Delta k = k - \bar k$. A base passes when $|\Delta k| \le 0.003$, or $\le 0.006$ if it is short — shorter than
133 mm **on the base** (the book's definition, chapter 06). Set

* `k_bases` — the six coefficients, in that order;
* `k_mean` — their mean;
* `dk_max` — the largest $|\Delta k|$;
* `spread_ok` — `True` if every base passes, else `False`.

Tolerance: 0.0005 for the coefficients, 0.0011 for their mean and 0.0016 for `dk_max` (table 12's way: every
value written to three decimals, the mean and Δk from the written ones).
""", id="task-12-2"),
    code("""
readings = tasks.inputs("task-12-2", v)   # your strip's readings (chapter 06)
readings.control_table()
""", id="task-12-2-data"),
    answer_cell("task-12-2"),
    check_cell("task-12-2"),
    md(r"""
## Task 12.3 — table 13: the corrections from centre 38 (graded)

Chapter 06 took working centre 37; take the other middle centre, **38**, as the centre of the strip, and the
six-base mean $\bar k$ of task 12.2. For every other point of the common tracing (the table below without 38, in
its order) measure its distance $r_i$ from 38 and compute $v_i = r_i(\bar k - 1)$ — away from the centre if
positive, towards it if negative (formula 12.3 of the guide, table 13). Set

* `r_mm` — the distances from 38, mm (13 values);
* `v_mm` — the corrections, mm, in the same order.

Tolerances: 0.05 mm for $r$; for $v$ 0.05 mm or 4 % (a $\bar k$ written as table 12 writes it passes).
""", id="task-12-3"),
    code("""
readings.points_table()   # every point of your common tracing
""", id="task-12-3-data"),
    answer_cell("task-12-3"),
    check_cell("task-12-3"),
    md(r"""
## Summary

* Planar radial phototriangulation keeps only directions from the working centres; its errors accumulate
  from template to template, so the error in the middle of a strip held at both ends grows like $n^{3/2}$.
* Zhukov's formula (13.1), read $m = 0.25\,k_i\,b\,(m_\varepsilon/\rho')\sqrt{n^3 + 11n + 34}$, has exactly
  that growth and the coefficient of three direction errors per base; with the guide's inputs it allows
  control points every 5–6 bases, and simulated strips follow it within 30 % (closest for long strips).
* §13's nine steps: control spacing → pricking the four kinds of points → templates → the free strip with
  error triangles ≤ 0.3 mm → reduction coefficients (spread ≤ 0.003 / 0.006) → corrections
  $v = r(k - 1)$ from a middle centre → laying on the base with control residuals ≤ 0.4 mm.
* The reduction is a similarity transformation; the free strip's scale and the choice of the centre do not
  change the result, only the size of the corrections.
""", id="summary"),
]


def main() -> None:
    write(notebook(CELLS), PATH)
    print(f"wrote {PATH.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
