"""Write notebooks/03_relief_displacement.ipynb (guide §4) from its cells (safe to re-run).

    python docs/tools/build_03_relief_displacement.py

Cells are identified by id; the notebook is written without outputs.  The answer cells hold the task's
template lines only (the reference lives in aerophoto.tasks.ch03); the check cells are the two-line form.
"""

from pathlib import Path

from aerophoto.nbtools import code, md, notebook, write

from lab_cells import answer_cell, check_cell  # noqa: E402  (same folder)

ROOT = Path(__file__).resolve().parents[2]
PATH = ROOT / "notebooks" / "03_relief_displacement.ipynb"


CELLS = [
    md("""
# 03 · Relief displacement (guide §4)

Real ground is not a plane. A hill top is closer to the camera than the valley floor, so on the photo it
lands farther from the centre than it would if it lay at the valley's height. This chapter measures that
effect — the **relief displacement** (смещение точки за рельеф) — and corrects for it, the way the guide's
§4 does with pricked points, a photoplan and a ruler.

**In this chapter you will**

1. see why the guide works against a **mean object plane** (средняя предметная плоскость) and why the
   displacement is **radial from the nadir point** $n$;
2. move the sliders of the displacement explorer and watch hills push points away from $n$ and the valley
   pull them in;
3. recompute the guide's tables 2, 3 and 4 with the package, with a note beside every printed number that
   does not follow from its inputs;
4. measure the pricked points on **your own photo** and plan, and compute the guide's tables 2, 3 and 4 for
   them — the graded tasks.
""", id="title"),
    code("""
RECORD_BOOK = None  # ← type your record-book number in quotes, e.g. "19-0457"
import aerophoto
from aerophoto import guide, plots, tasks
from aerophoto.demos.displacement import ReliefDemo, relief_section_figure
from aerophoto.demos.measure import photo_tool, plan_tool
v = aerophoto.setup(RECORD_BOOK)
""", id="setup"),
    md("""
## The mean object plane

A plan (план) shows every ground point where a plumb line drops it onto a horizontal plane: the
orthogonal projection. A photo is a central projection through $S$, and for a central projection the
height of the reference plane matters. Put the plane low (at sea level, $E_0$) and every point is above it
and displaced outwards; put it at the middle height of the ground the photo shows and the displacements are
as small as they can be and of both signs, so the ends of a line partly compensate each other (guide §4,
figure 6). That middle plane is the **mean object plane** $E$. The guide finds its height from two zones of
pricked points, one on high ground and one low: each zone's height is the mean of its bases' mean heights,

$$Z_{I\\,cp} = \\frac{Z_{I\\text{-}1} + Z_{I\\text{-}2}}{2},\\qquad Z_{II\\,cp} = \\frac{Z_{II\\text{-}3} + Z_{II\\text{-}4}}{2},
\\qquad Z_{cp} = \\frac{Z_{I\\,cp} + Z_{II\\,cp}}{2},$$

and a point's **excess** over the plane is $h_i = Z_i - Z_{cp}$ (negative below it).
""", id="theory"),
    md("""
## Why $\\delta_h = r\\,h/H$ and why it points from $n$

Take a vertical photo from height $H$ above the plane $E$ (the figure below is drawn by the camera model).
A point $A$ at height $h$ has its foot $A'$ on $E$; the ray $SA$ meets $E$ at $A_0$. On the photo, $a$ is
the image of $A$, $a'$ the image $A$ would have if it lay on $E$. If $A'$ is at the ground distance $R$ from the plumb point $N$,
similar triangles put the images at $r = f R/(H-h)$ and $r' = f R/H$ from $n$, so

$$\\delta_h = a'a = r - r' = \\frac{r\\,h}{H}\\qquad\\text{(guide formula 4.1)},$$

with $r$ the distance of the image $a$ from the nadir point $n$ (mm) and $H = m_{cp}\\,f$ (m). On a vertical
photo this is exact. On a tilted photo the formula still holds to first order, and the **direction** is
exact: a plumb line on the ground is imaged as a line through $n$ (verticals converge to the nadir), so
$A$ and $A'$ always image on one radius from $n$. Hills ($h>0$) move away from $n$, the valley towards it.

**The correction** (guide §4, step 5) is the opposite move along the radius from $n$: towards $n$ when
$\\delta_h > 0$, away from $n$ when $\\delta_h < 0$ — and only when $|\\delta_h| > 0.2$ mm, the accuracy of
pricking and measuring by hand.

**Scales of bases** (formula 5.1). The photo's scale along a base (базис) between two pricked points is
measured against the photoplan of scale $1/M$ ($M = 10\\,000$):

$$m_i = \\frac{l_{пл}\\,M}{l_{сн}},\\qquad m_{част} = \\frac{m_1 + m_2}{2},\\qquad m_{cp} = \\overline{m_{част}},\\qquad
\\Delta m_i = m_{част} - m_{cp}.$$

Relief makes the high zone's scale larger (smaller $m$) than the low zone's; after the correction the
partial scales should agree much better.
""", id="theory-formula"),
    code("""
plots.static(relief_section_figure(),
             alt="Cross-section through a vertical photo: the camera S above the mean object plane E, a point A "
                 "at height h above E with its foot A′, and the point A₀ where the ray from S through A meets E. "
                 "On the photo the images a of A and a′ of A′ lie on one radius from the nadir point n, here at o; "
                 "the segment a′a is the relief displacement δh = r·h/H.")
""", id="figure-section"),
    md("""
## The displacement explorer

A 9 × 9 grid of ground points over four hills and a valley, photographed exactly. Each vermillion arrow
runs from where a point *would* be imaged if it lay on the mean plane to where it *is* imaged. The dots are
coloured by height. Arrows are lengthened by the factor shown in the title so that a few tenths of a
millimetre become visible (choose a fixed factor under *View*). Tilt arrows are hidden here; chapter 04 is
about them (*show* brings them back).

The explorer opens on the guide's worked example — a vertical photo with $f = 100$ mm at 1:12 000
(variant 00) — whatever your own variant is. Its sliders reach every camera of the guide's variant scheme,
$f$ up to 1100 mm and $m$ up to 30 000: set your own values if you like.
""", id="demo-theory"),
    code("""
demo = ReliefDemo()
demo
""", id="demo-relief"),
    md("""
**Try this.**

* Set the relief to 0: every arrow vanishes. Double it: every arrow doubles — $\\delta_h$ is proportional
  to $h$.
* Halve the scale denominator $m$ (fly lower) with $f$ fixed: the arrows double — $\\delta_h \\propto 1/H$.
* Raise $\\alpha$ to 10°: $n$ leaves $o$ along the principal vertical and the arrows now radiate from $n$.
  The table compares the exact displacement with $r\\,h/H$ (with $r$ from $n$).
* `demo.set(relief_m=150, exaggeration=1)` shows the arrows at true size.
* Take the longest lens of the guide's scheme, $f$ = 1090 mm, at 1:21 900 with ±30 m of relief
  (`demo.set(f_mm=1090, m=21900, relief_m=30)`): $H$ is almost 24 km and no arrow reaches 0.2 mm — a long
  lens flown high hardly sees gentle relief.
""", id="try-this"),
    md("""
## The guide's worked example, recomputed

The guide's §4 example is the package's input: the bases' lengths $l_{пл}$, $l_{сн}$ (tables 2 and 4) and
the points' heights $Z$ and distances $r$ (table 3). Everything else is computed at full precision and set
beside the printed number. A printed number "follows" if it is within 0.6 of a unit of its last printed
digit of the computed one (half a unit for its own rounding, a little more for the guide's rounding of
intermediate values). Cells that do not follow are listed, with the reason, to the right of each table.

### Table 2 — partial and mean scales before the correction
""", id="example-theory"),
    code("""
guide.ch03.table(2)
""", id="example-1"),
    md("""
Two things recur in all four scale tables of §4–§5: the guide prints $\\Delta m$ with the opposite sign to
its own definition ($m_{cp} - m_{част}$ instead of $m_{част} - m_{cp}$), and in table 2 it divides by the
zone's $m_{част}$ rather than by $m_{cp}$ — which is why two zones with the same $|\\Delta m|$ get different
ratios, 1/72 and 1/70.

### Table 3 — the relief corrections
""", id="example-2-theory"),
    code("""
guide.ch03.table(3)
""", id="example-2"),
    md("""
Table 3 is right: its $h$ follow from $Z$ and $Z_{cp}$, and its $\\delta_h$ from $r$, $h$ and
$H = m_{cp}\\,f = 15\\,000 \\times 0.1\\ \\text{m} = 1500$ m, with $m_{cp}$ from table 2 and the guide's
$f = 100$ mm. All six corrections exceed 0.2 mm and are applied.

### Table 4 — the scales after the correction
""", id="example-3-theory"),
    code("""
guide.ch03.table(4)
""", id="example-3"),
    md("""
The corrected photo lengths of table 4 do follow from tables 2 and 3 (the package checks each against the
range the two corrections allow). The one slip, $m_{I-1} = 15\\,010$ instead of 14 973, spoils the zone's
partial scale and the deviations: corrected properly, both zones agree to about 1/890, not 1/500 and 1/750.
The whole list for the chapter:
""", id="example-summary"),
    code("""
guide.ch03.discrepancies()
""", id="example-discrepancies"),
    md(r"""
## Your photo: the guide's §4 on your own variant

The guide's lab is done on a real photo: prick points, measure them, compute three tables. You do the same
on **your own photo** of the book's virtual site (полигон), taken with your variant's camera: focal length
$f$, scale $1:m$, tilt $\alpha = 3^\circ$ with the principal vertical at $\lambda$ (counter-clockwise from
the photo's $+x$ axis). Six points are pricked already, in two **zones** (зоны) as the guide asks (step 2):
I, 1, 2 on low ground and II, 3, 4 on high ground, each zone's main point joined to the other two by a
**base** (базис) of 20–30 mm. The same six points are pricked on your **plan** at 1:10 000 (фотоплан с
горизонталями), whose contours give their heights (step 3).

The book photographed the points with its camera model, so it knows where each one truly is: it grades
your readings to 0.2 mm, checks that every column of your tables follows from your own readings, and —
once you have finished — shows how close the guide's corrections come to the exact ones.

**What your variant means here.** The photo is taken from $H = f\,m$ above the mean plane of the points.
The site's ground lies between 170 and 200 m (the guide's $Z_{min}$ and $Z_{max}$ of variant 00), so the
two zones differ by 15–25 m. In the guide's scheme a larger $i$ means a longer lens flown higher: for
$i = 99$, $f = 1090$ mm and $H \approx 24$ km — far beyond any mapping camera (survey lenses are
88–305 mm; chapter 00 states the book's policy). The book computes with your numbers all the same. Once
$H$ exceeds about 4 km (variants from about 18 on) no point moves by more than the guide's 0.2 mm: nothing
needs correcting and your table 4 repeats table 2. That is the right result, and the reason a photo taken
from high above gentle ground needs no relief correction.
""", id="lab-theory"),
    code("""
sheet = tasks.inputs("task-03-1", v)   # your lab sheet: photo, plan and heights of the pricked points
sheet.summary()
""", id="lab-sheet"),
    md(r"""
The heights $Z$ of the six points, read off the plan's contours (to 0.1 m); the bases are I-1, I-2, II-3
and II-4, from each zone's main point:
""", id="lab-heights-theory"),
    code("""
sheet.heights()
""", id="lab-heights"),
    md(r"""
### Measuring

1. The first tool below shows your photo with the six pricked points (yellow rings). Photo coordinates are
   millimetres from the principal point $o$, where the lines joining opposite fiducial marks (координатные
   метки) cross: $x$ to the right, $y$ up.
2. Magnify a point with the toolbar's zoom (□) until its ring is large, switch zooming off (click □ again)
   and click the centre of the ring. The tool records the reading to 0.1 mm (a red ×) and moves on to the
   next point; home (⌂) shows the whole photo again. A wrong click: choose the point in the list and click
   again.
3. When all six are measured, copy the two lines under the table (`x_mm = [...]`, `y_mm = [...]`) into
   the answer cell of task 03.1. The grader re-runs your notebook without your clicks: the numbers
   themselves must stand in the answer cell. (After a restart, `photo.load(x_mm, y_mm)` shows them again.)
4. Do the same on the plan, the second tool. Its lines read `xpl_mm = [...]`, `ypl_mm = [...]`: plan
   millimetres from the sheet's lower-left corner, $x$ east, $y$ north. From them you compute the plan
   lengths $l_{пл}$ of the bases.

Readings within 0.2 mm of the truth are accepted; careful clicks on a magnified ring are within 0.05 mm.
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
## Task 03.1 — table 2 of your photo (graded)

Measure the points, then compute the guide's table 2 (§4 step 3, formulas 5.1 and 5.2):

* `x_mm`, `y_mm` — your photo readings of I, 1, 2, II, 3, 4, in this order, mm;
* `lpl_mm` — the plan lengths $l_{пл}$ of the bases I-1, I-2, II-3, II-4, from your plan readings, mm;
* `lsn_mm` — the photo lengths $l_{сн}$ of the same bases, from `x_mm`, `y_mm`, mm;
* `m_i` — the scale denominator along each base, $m_i = l_{пл}\,M/l_{сн}$ with $M = 10\,000$;
* `m_part` — the **partial scale** (частный масштаб) of each zone, $m_{част} = (m_1 + m_2)/2$: zone I from
  I-1 and I-2, zone II from II-3 and II-4;
* `m_cp` — the **mean scale** (средний масштаб) $m_{cp}$, the mean of the two $m_{част}$;
* `dm_pct` — each zone's deviation $\Delta m_i/m_{cp}$ in per cent, with $\Delta m_i = m_{част} - m_{cp}$
  and its sign (the guide prints it as 1/N, and with the sign reversed — see table 2 above).

Give lists in the order above. Accepted: readings within 0.2 mm, lengths within 0.45 mm, $m_i$ within
2.5 %, $m_{част}$ 2 %, $m_{cp}$ 1.5 % and $\Delta m_i/m_{cp}$ 1.5 percentage points of the values from
error-free readings — what a reading error can do. The grader also checks that each column follows from
your own previous one.

A start for the answer cell (paste your own lines first):

```python
import numpy as np
x_mm = [...]; y_mm = [...]            # from the photo tool
xpl_mm = [...]; ypl_mm = [...]        # from the plan tool
P, Q = np.column_stack([x_mm, y_mm]), np.column_stack([xpl_mm, ypl_mm])
bases = [(0, 1), (0, 2), (3, 4), (3, 5)]          # I-1, I-2, II-3, II-4 as rows of P and Q
lsn_mm = [float(np.hypot(*(P[a] - P[b]))) for a, b in bases]
```
""", id="task-03-1"),
    answer_cell("task-03-1"),
    check_cell("task-03-1"),
    md(r"""
## Task 03.2 — table 3: the relief corrections (graded)

With the heights above and your table 2, compute the guide's table 3 (§4 step 4, formula 4.1):

* `Zcp_m` — the **mean object plane** $Z_{cp}$: the mean height of each base, $Z_{I\text{-}1} = (Z_I + Z_1)/2$,
  …; each zone's height, $Z_{I\,cp} = (Z_{I\text{-}1} + Z_{I\text{-}2})/2$, …; then
  $Z_{cp} = (Z_{I\,cp} + Z_{II\,cp})/2$, m;
* `H_m` — the flying height above it, $H = m_{cp}\,f$ with **your** $m_{cp}$ of task 03.1 and $f$ in metres;
* `xn_mm`, `yn_mm` — the **nadir point** $n$ (step 1): at $on = f\,\mathrm{tg}\,\alpha$ from $o$ on the
  **negative** side of the principal vertical, i.e. in the direction $\lambda + 180^\circ$, mm;
* `r_mm` — the distance $r$ of each point's reading from $n$ (not from $o$), mm;
* `dh_mm` — $\delta_h = r\,h/H$ with $h = Z - Z_{cp}$, mm: positive for points above the plane (displaced
  away from $n$);
* `n_corr` — how many of the six have $|\delta_h| > 0.2$ mm.

Accepted: $Z_{cp}$ within 0.05 m, $H$ within 2 %, $n$ within 0.05 mm, $r$ within 0.3 mm, $\delta_h$ within
0.01 mm or 3 %; hidden, $\delta_h$ must follow from your own $r$, $H$ and $Z_{cp}$.
""", id="task-03-2"),
    answer_cell("task-03-2"),
    check_cell("task-03-2"),
    md(r"""
## Task 03.3 — table 4: the scales after the correction (graded)

Correct every point with $|\delta_h| > 0.2$ mm (guide §4 step 5): move it by $|\delta_h|$ along the line
from $n$ through it — towards $n$ when $\delta_h > 0$, away from $n$ when $\delta_h < 0$. In coordinates,
with $p$ the reading and $n$ the nadir point,

$$p' = p - \delta_h\,\frac{p - n}{|p - n|}.$$

Points with a smaller $|\delta_h|$ stay where they are. Then compute table 4 (step 6) from the corrected
points and the same plan lengths:

* `lsn_corr_mm` — the photo lengths of I-1, I-2, II-3, II-4 between the corrected points, mm;
* `m_i`, `m_part`, `m_cp`, `dm_pct` — as in task 03.1.

If none of your points needed a correction, table 4 is table 2 again — that is the right answer.
""", id="task-03-3"),
    answer_cell("task-03-3"),
    check_cell("task-03-3"),
    md(r"""
**Think about it.** Compare the deviations $\Delta m_i/m_{cp}$ of your tables 2 and 4. On the guide's photo
the correction brings the zones from 1/71 to about 1/890. On yours the correction removes what relief did,
but not your reading error: 0.1 mm on a 25 mm base is already 0.4 % of the scale. And compare your
`n_corr` with your neighbours': the higher the flight $H = f\,m$, the smaller the same relief's
displacement.

## Your tables beside the reference

Once task 03.3 has passed, the cell below shows the tables of your photo computed from error-free readings,
and — point by point — how the formula $\delta_h = r\,h/H$ compares with the exact displacement the camera
model gives, and how far each corrected point still lies from where it would be imaged if it stood on the
mean object plane. The differences between these tables and yours are your reading errors.
""", id="results-theory"),
    code("""
from IPython.display import HTML
from aerophoto import checks
if checks.passed("task-03-3"):
    from aerophoto.labs.displacement import relief_sheet  # the reference tables: not part of your inputs
    display(HTML("".join(plots.html_table(t, caption=k) for k, t in relief_sheet(v.i).reference().items())))
else:
    print("Answer task 03.3 first: then this cell shows the reference tables of your photo.")
""", id="results"),
    md(r"""
## Summary

* Heights are counted from the **mean object plane** $Z_{cp}$, which keeps the displacements small and of
  both signs.
* Relief displacement $\delta_h = r\,h/H$ is **radial from the nadir point $n$**: hills outwards, the
  valley inwards; the correction moves the point back along the radius, if $|\delta_h| > 0.2$ mm.
* The guide's table 3 is right; tables 2 and 4 contain a copied and a misprinted $m_i$, the deviations
  $\Delta m$ are printed with the opposite sign, and table 2's ratios are divided by $m_{част}$.
  After the correction the partial scales of its high and low zones agree to about 1/890.
* On your own photo you measured the pricked points, built tables 2, 3 and 4 and saw what the correction
  can and cannot do: it removes the relief's share of the scale difference, not the reading error — and
  above $H \approx 4$ km the site's 30 m of relief needs no correction at all.

Next: **04 · Tilt displacement**.
""", id="summary"),
]


def main() -> Path:
    nb = notebook(CELLS, title="03 · Relief displacement (guide §4)")
    return write(nb, PATH)


if __name__ == "__main__":
    print(main())
