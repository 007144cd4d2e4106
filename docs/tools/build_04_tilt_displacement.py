"""Write notebooks/04_tilt_displacement.ipynb (guide §5) from its cells (safe to re-run).

    python docs/tools/build_04_tilt_displacement.py

Cells are identified by id; the notebook is written without outputs.  The answer cells hold the task's
template lines only (the reference lives in aerophoto.tasks.ch04); the check cells are the two-line form.
"""

from pathlib import Path

from aerophoto.nbtools import code, md, notebook, write

from lab_cells import answer_cell, check_cell  # noqa: E402  (same folder)

ROOT = Path(__file__).resolve().parents[2]
PATH = ROOT / "notebooks" / "04_tilt_displacement.ipynb"


CELLS = [
    md("""
# 04 · Tilt displacement (guide §5)

No aerial photo is perfectly vertical: the camera's axis leans from the plumb line by a small **tilt**
$\\alpha$ (угол наклона), up to 3° in a planned survey. The scale of such a photo is no longer the same
everywhere, and points move along lines from one special point of the photo, the **isocentre** $c$
(точка нулевых искажений). This chapter follows the guide's §5: find $c$, compute the **tilt displacement**
(смещение за угол наклона) of pricked points, correct them and compare the photo's scale before and after.

**In this chapter you will**

1. revisit the elements of the central projection — $o$, $n$, $c$, the principal vertical and the isoline —
   and see why tilt displacement is radial from $c$;
2. compare, live, the guide's approximate formula with the exact displacement from the camera model;
3. recompute the guide's tables 5, 6 and 7, and find out which camera the printed table 6 was really
   computed for;
4. locate $c$ on your own photo, measure the pricked points on it and on its plan, and compute the guide's
   tables 5, 6 and 7 for them — the graded tasks.
""", id="title"),
    code("""
RECORD_BOOK = None  # ← type your record-book number in quotes, e.g. "19-0457"
import aerophoto
from aerophoto import guide, plots, tasks
from aerophoto.demos.displacement import TiltDemo, principal_plane_figure
from aerophoto.demos.measure import photo_tool, plan_tool
v = aerophoto.setup(RECORD_BOOK)
""", id="setup"),
    md("""
## Elements of the central projection (guide §5, figure 8)

Through the projection centre $S$ pass two lines that matter: the optical axis, which pierces the photo at
the **principal point** $o$, and the plumb line, which pierces it at the **nadir point** $n$ (точка
надира) and the ground at $N$. The angle between them is the tilt $\\alpha$. The vertical plane through both
is the **principal plane** $W$ (плоскость главного вертикала); it cuts the photo along the **principal
vertical** $vv$ (главная вертикаль). The bisector of the angle $oSn$ pierces the photo at the
**isocentre** $c$. All three points lie on $vv$:

$$on = f\\,\\mathrm{tg}\\,\\alpha,\\qquad oc = -f\\,\\mathrm{tg}\\frac{\\alpha}{2}\\quad(\\text{guide: } -100\\cdot\\mathrm{tg}\\,1.5^\\circ = -2.6\\ \\text{mm}).$$

**The guide's sign convention.** Distances along $vv$ are counted from $o$, positive in the direction away
from the nadir point — towards the far, upper side of the tilted photo, where the ground is farther away and
the scale smaller. Both $n$ and $c$ therefore have negative coordinates. The angle $\\varphi$ of a point is
counted from that positive direction, counter-clockwise, as seen from $c$. The line through $c$ at right
angles to $vv$ is the **isoline** $h_ch_c$ (линия неискажённых масштабов). The figure is drawn by the camera
model, with the tilt exaggerated.
""", id="theory"),
    code("""
plots.static(principal_plane_figure(f_mm=100, alpha_deg=12),
             alt="The principal plane of a tilted photo: the camera S, the photo tilted by α to the ground plane E, "
                 "and on the principal vertical the principal point o, the isocentre c and the nadir point n with "
                 "their ground points O, C and N, joined to S by the optical axis, the bisector of the tilt and the "
                 "plumb line.")
""", id="figure-principal-plane"),
    md("""
## Why the displacement is radial from $c$

Compare the tilted photo with the **equivalent vertical photo** taken from the same $S$, and turn the
vertical one about the isoline $h_ch_c$ into the plane of the tilted one (the two photos share that line,
because $c$ lies on the bisector of the angle between their axes). For flat ground the two images of a point
then lie on one line through $c$: the angle a ground direction makes at $C$ is reproduced unchanged at $c$
on both photos — that is what makes $c$ the point of zero (angular) distortion. Only the distance from $c$
changes. For a point at distance $r_c$ from $c$ and angle $\\varphi$ from the positive principal vertical,
the exact change is

$$\\delta_\\alpha = -\\frac{r_c^2\\cos\\varphi\\,\\sin\\alpha}{f - r_c\\cos\\varphi\\,\\sin\\alpha},$$

and for small $\\alpha$ the guide's approximate formula (§5, step 9):

$$\\delta_\\alpha \\approx -\\frac{r_c^2\\cos\\varphi}{f}\\,\\sin\\alpha .$$

Points on the far side ($\\cos\\varphi > 0$) are pulled **towards** $c$ ($\\delta_\\alpha < 0$, the scale there
is smaller); points on the near side are pushed **away** from $c$ ($\\delta_\\alpha > 0$); points on the
isoline do not move. The **correction** (§5, step 10) undoes it along the line from $c$: away from $c$ for
$\\delta_\\alpha < 0$, towards $c$ for $\\delta_\\alpha > 0$, only when $|\\delta_\\alpha| > 0.2$ mm. The relative
error of the approximate formula is about $r_c\\cos\\varphi\\,\\sin\\alpha/f$ — under 5 % at the frame's edge
for $f = 100$ mm and $\\alpha = 3^\\circ$, but growing with $\\alpha$.
""", id="theory-formula"),
    md(r"""
## The displacement explorer — tilt in front

The same explorer as in chapter 03, with the ground flat and the tilt arrows shown. Blue: the exact
displacement, from the point's image on the (turned) vertical photo to its image on the tilted one; orange:
the guide's formula, drawn along the same line. The table gives the largest of each and the formula's
error. Arrows are lengthened by the factor in the title.

Like every demo of the book it opens on the guide's worked example — $f = 100$ mm, 1:12 000, $\alpha = 3^\circ$,
$\lambda = -60^\circ$ (variant 00) — not on your variant; its $f$ slider reaches 1100 mm, the longest lens of
the guide's scheme.
""", id="demo-theory"),
    code("""
demo = TiltDemo()
demo
""", id="demo-tilt"),
    md("""
**Try this.**

* Turn $\\lambda$: the whole pattern turns with the principal vertical; arrows on the isoline stay zero.
* Raise $\\alpha$ from 3° to 10° and 15°: the blue and orange arrows part on the far side — the table's
  error grows from a few per cent to about 20 %.
* Increase $f$ at a fixed $\\alpha$: every displacement shrinks as $1/f$ (a long-focus camera forgives tilt).
* Add relief (and *show* both): the vermillion relief arrows radiate from $n$, the blue ones from $c$.
""", id="try-this"),
    md("""
## The guide's worked example, recomputed

Inputs as printed: the base lengths $l_{пл}$, $l_{сн}$ with $M = 10\\,000$ (tables 5 and 7), the distances
$r_c$ and angles $\\varphi$ (table 6) with the guide's $f = 100$ mm and $\\alpha = 3^\\circ$. Cells that do not
follow from their inputs are listed beside each table with the reason (same rule as in chapter 03).

### Table 5 — scales before the correction
""", id="example-theory"),
    code("""
guide.ch04.table(5)
""", id="example-1"),
    md("""
Two $m_i$ are misprinted (I-2 and III-6; the latter fits a photo length of 27.3 mm, not the printed 27.7),
and both errors are carried into $m_{част}$, $m_{cp}$ and the deviations. As in chapter 03 the deviations
are printed with the opposite sign, and divided by $m_{част}$.

### Table 6 — the tilt displacements
""", id="example-2-theory"),
    code("""
guide.ch04.table(6)
""", id="example-2"),
    md("""
Six of the nine printed $\\delta_\\alpha$ do not follow from $f = 100$ mm and $\\alpha = 3^\\circ$: the printed
values are all about 15 % smaller. Which camera does the column fit? The formula has a single constant,
$k = \\sin\\alpha/f$, so the package tests readings of it against the printed column:
""", id="example-fit-theory"),
    code("""
fit = guide.ch04.table6_fit()
print(f"least-squares k = {fit.k_lsq:.3e} 1/mm;  every printed value reproduced for "
      f"f = {fit.f_range_mm[0]:.1f}…{fit.f_range_mm[1]:.1f} mm at α = 3°, "
      f"or α = {fit.alpha_range_deg[0]:.2f}…{fit.alpha_range_deg[1]:.2f}° at f = 100 mm")
fit.candidates.round(3)
""", id="example-fit"),
    md("""
So the column was computed for $\\sin\\alpha/f \\approx 4.5\\cdot10^{-4}$ mm⁻¹ — a camera of $f \\approx 117$ mm
at 3°, or a tilt of about 2.6° with $f = 100$ mm — not for the inputs the section states. Measuring $r$ from
$o$ or $n$ instead of $c$ does not explain it, nor does the exact formula (it makes the values larger). In
this book the corrections are computed with $f = 100$ mm and $\\alpha = 3^\\circ$.

### Table 7 — scales after the correction
""", id="example-3-theory"),
    code("""
guide.ch04.table(7)
""", id="example-3"),
    md("""
Table 7's arithmetic is right apart from the signs of $\\Delta m$; but its base III-6 cannot have come from
table 5 and table 6: the two corrections at its ends are 0.67 and 0.52 mm, so the base can change by at most
1.19 mm, yet it shrank by 2.0 mm. The whole list for the chapter:
""", id="example-summary"),
    code("""
guide.ch04.discrepancies()
""", id="example-discrepancies"),
    md("""
## Task 04.1 — the isocentre on your photo (graded)

For **your variant** ($f$, $\\alpha$, and the direction $\\lambda$ of the positive principal vertical, counted
counter-clockwise from the photo's $+x$ axis) compute

* `oc_mm` — $oc = -f\\,\\mathrm{tg}(\\alpha/2)$ with the guide's sign, mm;
* `xc_mm`, `yc_mm` — the photo coordinates of the isocentre $c$, mm (origin at $o$).
""", id="task-04-1"),
    answer_cell("task-04-1"),
    check_cell("task-04-1"),
    md(r"""
## Your photo: the guide's §5 on your own variant

Now the guide's work (§5 steps 5–11) on **your own photo** of the virtual site, taken with your variant's
$f$, scale $1:m$, tilt $\alpha = 3^\circ$ and principal vertical at $\lambda$. It shows the site's flat
plain, so that relief hardly adds to the tilt displacement (the guide works on a photo of flat ground, §5).
Nine points are pricked in **three zones** (зоны) close to the principal vertical, as in the guide's
figure 10: I, 1, 2 on the far side (beyond $c$, where the scale is smaller), II, 3, 4 near the isocentre
and III, 5, 6 on the near side; in each zone two bases of 20–30 mm leave the main point about 90° apart.
The same nine points are pricked on your plan at 1:10 000.

You measure the points, compute the scales of the six bases (table 5), the tilt displacements about the
isocentre $c$ of task 04.1 (table 6), correct the points and compute the scales again (table 7). The book
knows where every point truly is (its camera model took the photo), grades your readings to 0.2 mm and
checks that each column follows from your own readings.

**What your variant means here.** $\delta_\alpha$ shrinks as $1/f$: with the guide's $f = 100$ mm points
60 mm from $c$ move by almost 2 mm; with $f = 1090$ mm ($i = 99$) by less than 0.2 mm, so a long lens
needs few corrections or none — the guide's rule, computed honestly for every variant.
""", id="lab-theory"),
    code("""
sheet = tasks.inputs("task-04-2", v)   # your lab sheet: photo and plan with the pricked points
sheet.summary()
""", id="lab-sheet"),
    md(r"""
### Measuring

As in chapter 03: the first tool shows your photo (coordinates in mm from the principal point $o$, $x$ to the
right, $y$ up), the second your plan (mm from the sheet's lower-left corner, $x$ east, $y$ north). Magnify a
pricked point with the toolbar's zoom (□), switch zooming off, click the centre of the ring; the tool reads
to 0.1 mm and moves on. Copy the lines under each table into the answer cell of task 04.2 — the grader
re-runs your notebook without your clicks. Readings within 0.2 mm of the truth are accepted.
""", id="lab-measure"),
    code("""
photo = photo_tool(sheet)
photo
""", id="lab-photo"),
    code("""
plan = plan_tool(sheet)
plan.widget(x_name="xpl_mm", y_name="ypl_mm")
""", id="lab-plan"),
    md(r"""
## Task 04.2 — table 5 of your photo (graded)

Measure the nine points, then compute the guide's table 5 (§5 steps 6–8, formulas 5.1 and 5.2):

* `x_mm`, `y_mm` — your photo readings of I, 1, 2, II, 3, 4, III, 5, 6, in this order, mm;
* `lpl_mm` — the plan lengths $l_{пл}$ of I-1, I-2, II-3, II-4, III-5, III-6, from your plan readings, mm;
* `lsn_mm` — the photo lengths $l_{сн}$ of the same bases, from `x_mm`, `y_mm`, mm;
* `m_i` — $m_i = l_{пл}\,M/l_{сн}$ for each base, $M = 10\,000$;
* `m_part` — the partial scales $m_{част} = (m_1 + m_2)/2$ of zones I, II, III;
* `m_cp` — the mean scale $m_{cp} = (m_{I\,част} + m_{II\,част} + m_{III\,част})/3$;
* `dm_pct` — $\Delta m_i/m_{cp}$ of each zone in per cent, $\Delta m_i = m_{част} - m_{cp}$ with its sign.

Accepted as in chapter 03: readings 0.2 mm, lengths 0.45 mm, $m_i$ 2.5 %, $m_{част}$ 2 %, $m_{cp}$ 1.5 %,
$\Delta m_i/m_{cp}$ 1.5 percentage points; the grader checks that each column follows from your own readings.
The bases as rows of your readings: `[(0, 1), (0, 2), (3, 4), (3, 5), (6, 7), (6, 8)]`.
""", id="task-04-2"),
    answer_cell("task-04-2"),
    check_cell("task-04-2"),
    md(r"""
## Task 04.3 — table 6: the tilt displacements (graded)

For each of your nine readings compute (§5 step 9):

* `rc_mm` — its distance $r_c$ from the isocentre $c$ (task 04.1), mm;
* `phi_deg` — its angle $\varphi$ seen from $c$, counted **counter-clockwise from the positive principal
  vertical** (the direction $\lambda$), $0 \le \varphi < 360^\circ$: with $d = p - c$,
  $\varphi = \mathrm{atan2}(d_y, d_x) - \lambda$, brought into 0…360°;
* `da_mm` — $\delta_\alpha = -(r_c^2\cos\varphi/f)\,\sin\alpha$, mm;
* `n_corr` — how many of the nine have $|\delta_\alpha| > 0.2$ mm.

Accepted: $r_c$ within 0.3 mm, $\varphi$ within 1°, $\delta_\alpha$ within 0.02 mm or 3 %; hidden,
$\delta_\alpha$ must follow from your own $r_c$ and $\varphi$.
""", id="task-04-3"),
    answer_cell("task-04-3"),
    check_cell("task-04-3"),
    md(r"""
## Task 04.4 — table 7: the scales after the tilt correction (graded)

Correct every point with $|\delta_\alpha| > 0.2$ mm (§5 step 10): move it by $|\delta_\alpha|$ along the line
from $c$ through it — away from $c$ when $\delta_\alpha < 0$, towards $c$ when $\delta_\alpha > 0$:

$$p' = p - \delta_\alpha\,\frac{p - c}{|p - c|}.$$

Then compute table 7 (step 11) from the corrected points and the same plan lengths:

* `lsn_corr_mm` — the photo lengths of the six bases between the corrected points, mm;
* `m_i`, `m_part`, `m_cp`, `dm_pct` — as in task 04.2.
""", id="task-04-4"),
    answer_cell("task-04-4"),
    check_cell("task-04-4"),
    md(r"""
**Think about it.** In your table 5 the far zone I has the largest $m$ (the smallest scale) and the near
zone III the smallest: that is the tilt. After the correction the three partial scales should agree to
within your reading error — on the guide's own photo from 1/23 to about 1/120.

## Your tables beside the reference

Once task 04.4 has passed, the cell below shows the tables of your photo computed from error-free readings,
and — point by point — the guide's $\delta_\alpha$ against the exact displacement (the camera model), and how
far each corrected point still lies from its place on the equivalent vertical photo.
""", id="results-theory"),
    code("""
from IPython.display import HTML
from aerophoto import checks
if checks.passed("task-04-4"):
    from aerophoto.labs.displacement import tilt_sheet  # the reference tables: not part of your inputs
    display(HTML("".join(plots.html_table(t, caption=k) for k, t in tilt_sheet(v.i).reference().items())))
else:
    print("Answer task 04.4 first: then this cell shows the reference tables of your photo.")
""", id="results"),
    md(r"""
## Summary

* On a tilted photo $o$, $n$ ($on = f\,\mathrm{tg}\,\alpha$) and $c$ ($oc = -f\,\mathrm{tg}(\alpha/2)$, the
  guide's sign) lie on the principal vertical; the isoline through $c$ keeps the vertical photo's scale.
* Tilt displacement is **radial from the isocentre $c$**: towards $c$ on the far side, away from it on the
  near side; $\delta_\alpha \approx -(r_c^2\cos\varphi/f)\sin\alpha$, a few per cent short of the exact value
  at 3°, much more at larger tilts.
* Corrections are applied along the line from $c$ when $|\delta_\alpha| > 0.2$ mm; on your own photo they
  brought the three zones' scales together, up to your reading error.
* The guide's table 6 was computed for $\sin\alpha/f \approx 4.5\cdot10^{-4}$ mm⁻¹ ($f \approx 117$ mm at 3°),
  not for its stated $f = 100$ mm; tables 5 and 7 carry two misprinted scales, reversed signs of $\Delta m$
  and a base (III-6) that the corrections cannot explain.
* Relief displaces points radially from $n$ (chapter 03), tilt radially from $c$: on a real photo both act
  at once.

Next: **05 · The single-strip photo mosaic**.
""", id="summary"),
]


def main() -> Path:
    nb = notebook(CELLS, title="04 · Tilt displacement (guide §5)")
    return write(nb, PATH)


if __name__ == "__main__":
    print(main())
