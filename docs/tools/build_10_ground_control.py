"""Write notebooks/10_ground_control.ipynb (guide §11) from its cells (safe to re-run).

    python docs/tools/build_10_ground_control.py
"""

from pathlib import Path

from aerophoto.guide import ch10 as s11
from aerophoto.nbtools import code, md, notebook, write

from lab_cells import answer_cell, check_cell  # noqa: E402  (same folder)

ROOT = Path(__file__).resolve().parents[2]
PATH = ROOT / "notebooks" / "10_ground_control.ipynb"

#: §11's shift, computed (guide.ch10.shift_summary): the text prints these, never typed-in numbers
_S = s11.shift_summary()
SHIFT = {"dX_km": f"{abs(_S['mean_dX_m']) / 1000:.1f}", "dY_km": f"{abs(_S['mean_dY_m']) / 1000:.1f}",
         "dlat_min": f"{_S['mean_dlat_min']:.1f}", "dlon_min": f"{_S['mean_dlon_min']:.1f}",
         "rel_m": f"{_S['max_relative_m']:.0f}"}


def _shift(text: str) -> str:
    """Fill <dX_km>, <dY_km>, <dlat_min>, <dlon_min>, <rel_m> with the computed shift."""
    for k, val in SHIFT.items():
        text = text.replace(f"<{k}>", val)
    return text

CELLS = [
    md("""
# 10 · Ground control (guide §11)

Photogrammetry measures shapes; ground coordinates come from a few points whose coordinates are known. Finding
such points on the photos and fixing them on the ground is **ground control** (привязка аэроснимков); the points
are **control points** (опорные точки, опознаки). This chapter plans them on a block of photos — where, how many,
how they are marked — and determines one of them in the field by **resection** (обратная засечка), checked by a
third angle.

**In this chapter you will**

1. design the control of a simulated block: rows of points across the strips, spaced by Zhukov's formula for the
   accuracy wanted, against control on every model;
2. see how a control point is marked on the photo (0.1 mm, the 8 and 10 mm circles);
3. resect a station from three known points and two angles, and find the **danger circle** (опасный круг) where
   the method fails;
4. check the guide's table of known points against its own latitudes and longitudes (Pulkovo 1942, pyproj);
5. resect your own station on the virtual site and check it with the third angle.
""", id="title"),
    code("""
RECORD_BOOK = None  # ← type your record-book number in quotes, e.g. "19-0457"
import aerophoto
from aerophoto import control, guide, plots, tasks
from aerophoto.demos import control as dc
v = aerophoto.setup(RECORD_BOOK)
""", id="setup"),
    md("""
## What ground control is for

A single photo is rectified on control points (chapter 11); a stereo model is levelled and scaled on them.
Control with all three coordinates is **planimetric-and-height** control (планово-высотная привязка); with X, Y
only, **planimetric** (плановая); with the height only, **height** control (высотная). When every photo or every
stereo pair gets its own points, the control is **dense** (сплошная); when only some do and phototriangulation
carries the coordinates on between them, it is **sparse** (разреженная).

The work, in the guide's order: prepare the photos and a print of the overview mosaic (накидной монтаж) with the
state network's points copied onto it; **design** the control on that print; reconnoitre and fix the points in
the field; measure; compute the catalogue of coordinates; hand over a file (техническое дело) per map sheet.

### The design

Sparse control is laid out in **rows across the strips** (рядами поперёк маршрутов). A row sits in the triple
forward overlap round one photo of every strip, with a point in the middle of each side overlap — shared by two
strips — and one on each outer edge of the block, so that every strip has two points in every row. How many bases
may separate two rows follows from the accuracy wanted: Zhukov's formula (13.1), read with $n^3$ (chapter 12),

$$m = 0.25\\,k_i\\,b\\,\\frac{m_\\varepsilon}{\\rho'}\\sqrt{n^3 + 11n + 34},$$

gives the error $m$ of a point in the middle of $n$ bases of radial triangulation; the largest $n$ with
$m \\le 0.35$ mm is the spacing. A smaller photo scale (larger $k_i = m/M$) or poorer directions
($m_\\varepsilon$) pull the rows together; below one base, the control must be dense.
(`aerophoto.control.design_control??`, `aerophoto.control.control_spacing_bases??`)
""", id="theory"),
    md("""
## Designing the control of a block

A block of parallel strips with $p_x = 60$ %, $p_y = 30$ %, $f = 100$ mm (the guide's variant 00) and its control:
triangles are control points, dashed lines the rows. Compare the number of points with dense control (every base).
""", id="demo-theory"),
    code("""
design = dc.ControlDesignDemo()
design
""", id="demo-control-design"),
    md("""
**Try this.** Raise $m$ (photo 1:m) to 20 000: $k_i = 2$ and only one base keeps $m \\le 0.35$ mm — every
photo gets its row of control, as dense control would. Set $m_\\varepsilon$ to 2′: the rows spread to eight bases apart.

### Marking (guide §11, steps 1–2)

A control point must be identified on the ground within **0.1 mm at the plan's scale** (1 m at 1:10 000) and
pricked on the photo within **0.1 mm**; on the photo it is ringed by two red concentric circles **8 and 10 mm**
across and numbered; on the ground it is fixed by a stake 0.3–0.5 m long in a ditched triangle with sides of
1.2–1.5 m. Below: a photo of the virtual site at 1:12 000 with its control points marked the guide's way (at this
scale the circles span about 100 m of ground).
""", id="marking-theory"),
    code("""
from aerophoto import geometry, render, site
_site = site.get_site()
_cx, _cy = _site.centre_m
_photo = render.render(_site, geometry.Camera(100.0),
                       geometry.Pose(_cx + 700.0, _cy, _site.mean_height_m + 1200.0, 1.0, -60.0, 0.0), 512)
plots.static(dc.marking_figure(_photo),
             alt="A photo of the virtual site at 1:12 000 with its control points ringed by two red concentric "
                 "circles of 8 and 10 mm diameter and numbered; beside it one control point enlarged, with a red "
                 "dot of 0.1 mm radius showing how small the pricking tolerance is.")
""", id="figure-marking"),
    md("""
## Resection: three known points, two angles (the Snellius–Pothenot problem)

At the station $P$ to be determined, a theodolite sights three points $A$, $B$, $C$ of known coordinates and
measures two horizontal angles: $\\beta_1$ from $A$ to $B$ and $\\beta_2$ from $B$ to $C$ (clockwise, as the
instrument reads). Every point from which the segment $AB$ is seen under the angle $\\beta_1$ lies on one arc of a
circle through $A$ and $B$; likewise for $BC$ and $\\beta_2$. Both circles pass through $B$; their second meeting
point is $P$.

**One way to compute it.** Put the origin at $B$ and write points as complex numbers $z = X + iY$ (X north,
Y east, so that an argument is a direction angle (дирекционный угол), clockwise from north). Under the inversion
$w = 1/(z - z_B)$ a circle through $B$ becomes a straight line, so the two conditions become two *linear*
equations in $w$:

$$\\operatorname{Im}\\big[(a\\,w - 1)\\,e^{i\\beta_1}\\big] = 0,\\qquad \\operatorname{Im}\\big[(c\\,w - 1)\\,e^{-i\\beta_2}\\big] = 0,
\\qquad a = z_A - z_B,\\; c = z_C - z_B,$$

and $z_P = z_B + 1/w$. (Tienstra's or Collins' formulas give the same point.)

**The danger circle.** If $P$ lies on the circle through $A$, $B$, $C$, both angle circles *are* that circle: the
two lines in $w$ coincide and $P$ can be anywhere on it. Near it the lines cross at a grazing angle and small angle
errors move $P$ far. A station should keep well away from the circle through its three known points; the package
refuses a station on it (`aerophoto.control.resect??`).

**The check** (guide §11). A third angle $\\gamma$ is measured from one of the three points to a fourth known
point $D$. From the computed $P$ the same angle is computed; the two must agree. The guide gives no tolerance; the
book holds the check to the guide's own accuracy of a control point, 0.1 mm at the plan's scale ($e$ = 1 m at
1:10 000): seen from $P$ at the distance $S_{PD}$, a shift $e$ across the line of sight turns it by

$$\\Delta\\gamma_{доп} = \\rho''\\,\\frac{e}{S_{PD}},\\qquad \\rho'' = 206\\,265''.$$

## The resection explorer

The four known points are those of the guide's §11 table (I, II, III for the resection, IV for the check). Move
the station; each blue dot is the station resected from angles with random errors of σβ (the cloud is enlarged by
the factor in the title).
""", id="resection-theory"),
    code("""
res_demo = dc.ResectionDemo()
res_demo
""", id="demo-resection"),
    md("""
**Try this.** Walk the station onto the dashed circle (for example `res_demo.set(north_m=-270, east_m=-820)`, 3 m from it):
the shift per arc-second grows by orders of magnitude and the cloud stretches along the circle. Stations well
inside the triangle of the points, or well outside the circle, are firm.

## The guide's table of known points, checked

§11 ends with the coordinates of the four points: plane X, Y and height H, and beside them latitude φ and longitude
λ. Nothing in it is computed from anything else, but X, Y and φ, λ must describe the same points. The leading 5 of
Y names zone 5 of the Gauss–Krüger projection (central meridian 27° E) of the **Pulkovo 1942** datum — EPSG:4284
for φ, λ and EPSG:28405 for X, Y in the EPSG registry that pyproj ships. Projecting the printed φ, λ (read to 1″:
the computed X, Y are ranges):
""", id="example-theory"),
    code("""
guide.ch10.coordinate_table()
""", id="example-1"),
    md(_shift("""
**What the table turns out to contain.** The X, Y are *not* the Gauss–Krüger coordinates of the printed φ, λ:
every point is off by nearly the same amount, about <dX_km> km in X and <dY_km> km in Y, and projected back the X, Y
fall <dlat_min>′ south and <dlon_min>′ west of the printed latitudes and longitudes (the mean of the four points).
A common shift is what a local (conditional) coordinate system or invented numbers would give. Even with the shift removed the four points disagree by up to
about <rel_m> m, more than reading φ, λ to 5″ (all the printed seconds are multiples of 5) would explain. So the table's
plane coordinates and its geographic coordinates come from two different sources. A resection works in plane
coordinates: below we use X, Y.

### A resection on the guide's points

The guide prints no measured angles. Take the explorer's starting station and compute what a theodolite there
would read, then resect it back and check it:
"""), id="example-2-theory"),
    code("""
import numpy as np

K = dc.guide_points().to_numpy()
P_true = K[:3].mean(axis=0) + np.array([-150.0, -300.0])
b1 = control.horizontal_angle_deg(P_true, K[0], K[1])
b2 = control.horizontal_angle_deg(P_true, K[1], K[2])
g = control.horizontal_angle_deg(P_true, K[2], K[3])
example = control.resect(K[0], K[1], K[2], b1, b2)
print("β1 =", control.format_dms(b1), "  β2 =", control.format_dms(b2), "  γ (III → IV) =", control.format_dms(g))
example.table()
""", id="example-2"),
    code("""
control.check_resection(example, K[3], g, M=10000).table()
""", id="example-3"),
    md(r"""
**How loose is the check?** Here the tolerance is 210″ — three and a half minutes of arc, for angles a theodolite
reads to a few seconds. Which blunder (грубая ошибка) would it catch? Put a blunder of 30″ to 10′ into one of the
two measured angles, resect again and compute the check:
""", id="check-blunder-theory"),
    code("""
import pandas as pd

rows = []
for which in ("β1", "β2"):
    for blunder_s in (30.0, 60.0, 120.0, 300.0, 600.0):
        d = blunder_s / 3600.0
        bad = control.resect(K[0], K[1], K[2], b1 + d * (which == "β1"), b2 + d * (which == "β2"))
        chk = control.check_resection(bad, K[3], g, M=10000)
        rows.append((which, blunder_s, np.hypot(*(bad.point - P_true)), chk.discrepancy_arcsec, not chk.ok))
pd.DataFrame(rows, columns=["angle", "blunder, ″", "station moved, m", "Δγ, ″", "caught"]).set_index(
    ["angle", "blunder, ″"]).round(1)
""", id="check-blunder"),
    md(r"""
A blunder in β₁ shows in γ about 1.5 times enlarged, one in β₂ only 0.64 times (γ is measured from C, on β₂'s
side of the figure, and shares its geometry). So the check catches a blunder in β₁ from about 2.3′ and one in β₂
only from about 5.5′: a misread minute on the circle, the commonest blunder of all, passes unseen. That is the
price of tying the tolerance to the plan rather than to the instrument: every blunder that passes moves the
station by less than about 1 m — 0.1 mm at 1:10 000, the accuracy the plan asks for — so it does no harm *to the
plan*. A check meant to catch blunders would be set from the angles' own precision: with an RMS of 15″ per angle,
Δγ has an RMS of $15''\sqrt{1 + 1.5^2 + 0.64^2} = 29''$, three times that is 86″, and blunders from about 1′ in β₁ and
2.2′ in β₂ would be caught — two to three times finer. The book keeps the plan's tolerance, as its purpose is the
plan, and the task asks for it; it is worth knowing what it lets through.
""", id="check-blunder-notes"),
    md("""
## Task 10.1 — your resection (graded)

Your station P is a field corner or road crossing of the virtual site; A, B, C, D are points of the site's control
network. Their plane coordinates (X north, Y east, m — the site placed like the guide's table) and the angles
measured at P (clockwise, to whole seconds) are below. Compute

* `X_m`, `Y_m` — the station's coordinates from A, B, C and β₁, β₂, m (tolerance 0.05 m);
* `alpha_PA_deg` — the direction angle (дирекционный угол) from P to A, degrees, clockwise from north
  (tolerance 0.002°).
""", id="task-10-1"),
    code("""
lab = tasks.inputs("task-10-1", v)
display(lab.known_table())
lab.angles_table()
""", id="task-10-1-data"),
    answer_cell("task-10-1"),
    check_cell("task-10-1"),
    md("""
## Task 10.2 — the check angle (graded)

With your station from task 10.1, compute the check angle from C to D and compare it with the measured γ:

* `gamma_calc_deg` — the angle C → D at P computed from the coordinates, degrees (tolerance 0.001°);
* `dgamma_arcsec` — measured minus computed, arc-seconds (tolerance 4″);
* `tol_arcsec` — its tolerance $\\rho''\\,e/S_{PD}$ with $e$ = 0.1 mm at 1:10 000 = 1 m, arc-seconds;
* `check_ok` — `True` if $|\\Delta\\gamma|$ is within the tolerance.

If the check fails, one of the measured angles is wrong: the station must be measured again.
""", id="task-10-2"),
    answer_cell("task-10-2"),
    check_cell("task-10-2"),
    md(_shift("""
## Summary

* Sparse control is laid in rows across the strips, the rows as many bases apart as Zhukov's formula allows for
  the accuracy wanted; dense control gives every model its points and costs several times more of them.
* A control point is identified within 0.1 mm at the plan's scale and ringed on the photo by 8 and 10 mm circles.
* A resection from three known points and two angles is the second meeting point of two circles; on the circle
  through the three points (the danger circle) it is undetermined, near it weak. A third angle to a fourth point
  checks it.
* The guide's §11 table: its X, Y are not the Pulkovo 1942 Gauss–Krüger coordinates of its φ, λ — all four are
  shifted by about <dX_km> km and <dY_km> km, and even the relative positions disagree by up to <rel_m> m.

Next: **11 · Rectification**.
"""), id="summary"),
]


def main():
    nb = notebook(CELLS, title="10 · Ground control")
    write(nb, PATH)
    print("wrote", PATH.relative_to(ROOT))


if __name__ == "__main__":
    main()
