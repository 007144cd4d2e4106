"""Write notebooks/11_rectification.ipynb (guide §12) from its cells (safe to re-run).

    python docs/tools/build_11_rectification.py
"""

from pathlib import Path

from aerophoto.nbtools import code, md, notebook, write

from lab_cells import answer_cell, check_cell  # noqa: E402  (same folder)

ROOT = Path(__file__).resolve().parents[2]
PATH = ROOT / "notebooks" / "11_rectification.ipynb"

CELLS = [
    md("""
# 11 · Rectifying photos of flat ground (guide §12)

A tilted photo of flat ground is a projective image of the plan: turned, scaled, and squeezed more on one side
than the other. **Rectification** (трансформирование) undoes the tilt and brings the photo to the plan's scale,
so that it can go into a photo plan. The guide does it on a **photo transformer** (фототрансформатор ФТБ),
projecting the negative onto a screen that carries four **transformation points** (трансформационные точки) on a
**base** (основа) and moving the projection until their images fall on them within 0.4 mm.

**In this chapter you will**

1. see the rectification as a projective transformation fixed by four points, and what it cannot do: relief
   displacement survives it;
2. follow the photo transformer's sequence of motions — centre, scale, find the principal horizontal, turn, tilt
   the screen — as it converges;
3. recompute the guide's table 11 (the paper's deformation and the substrate thickness) and find what its printed
   sign hides;
4. rectify your own photo on four points and judge it by its check points.
""", id="title"),
    code("""
RECORD_BOOK = None  # ← type your record-book number in quotes, e.g. "19-0457"
import aerophoto
from aerophoto import guide, labs, plots, rectify, tasks
from aerophoto.demos import rectification as dr
v = aerophoto.setup(RECORD_BOOK)
""", id="setup"),
    md("""
## Rectification is a projective transformation

Flat ground, a central projection: photo and plan are related by the eight-parameter projective transformation of
chapter 09, and four points with no three on a line fix it. A photo transformer realises it optically. Its lens
throws the negative onto a screen; the enlargement $K_t = m/M$ (photo 1:m onto a base 1:M) is set by the distance
from lens to screen, the screen and the cassette tilt, the cassette turns and shifts, and two inversors keep the
image sharp at every setting. Six motions: exactly the freedom a photo of flat ground has once its focal length is
known — a tilt ε in a direction, a turn θ, a scale, a shift.

Analytically: measure the four points on the photo, take their places on the base, and fit
(`rectify.rectify_points(photo, base, check_photo, check_base)`): with four points the fit is exact; points not
used in it — **check points** — show how good it is. The guide's tolerance is **0.4 mm** on the base.

**What rectification cannot do.** It maps one plane onto another. A point above or below the plane of the control
points is displaced on the photo radially from the nadir by $\\delta_h = r\\,h/H$ (chapter 03), and the
transformation carries that displacement onto the base, multiplied by $K_t$. That is why the guide rectifies
photos of **flat** ground (равнинной местности); on hilly ground the photo must be rectified in zones of height,
or orthorectified on a DEM.

## Step 1: the base (основа)

Before any projection the guide's step 1 makes the **base** of the photo plan: stiff white paper glued onto
aluminium (or aircraft plywood, or a plastic that hardly deforms). On it the coordinate grid is drawn, the
transformation points are plotted from their coordinates or from the phototriangulation (chapter 12), and so are
the corners of the map sheets (трапеции). If the transformer is to use each photo's **central point**, its place on
the base is found graphically with a tracing of central directions. For the transformer itself one does not put
the base on the screen but copies of its parts — only the transformation and central points of one photo, on
plastic or stiff paper: the **transformation planchets** (трансформационные планшеты), one per photo. Step 2 (the
substrate, below) prepares the paper; step 3 is the transformer.

## The photo transformer's sequence (guide §12, step 3, figure 20)

Setting up: light on; the negative in the cassette emulsion down, its principal point roughly at the cassette's
centre, pressed flat under its cover glass; the screen horizontal, on it the **substrate** (подложка) of the
computed thickness and over it the planchet, flattened under glass; the lens's diaphragm fully open, so the
image is bright. Then the operator:

1. brings the **central point** of the photo onto its place on the base and turns the planchet to the image;
2. changes the enlargement until the misses at diagonally opposite points are about equal and opposite;
3. draws the **principal horizontal** hh (главная горизонталь): the line through the points where lines joining
   corresponding points of the image and the planchet cross — image and planchet differ by a tilt about this line,
   so corresponding lines meet on it;
4. turns cassette and planchet so that hh lies along the screen's axis of tilt;
5. tilts the screen and adjusts the enlargement until the points coincide;

and repeats until every point is within 0.4 mm. The package does the same, each motion choosing its own settings
by least squares over the points (`aerophoto.rectify.transformer_sequence??`).

**The exposure.** With the points matched, the planchet and the substrate are taken away (the substrate's
thickness now puts the paper where the image has the size the deformed paper needs — step 2); the lens is stopped
down and covered with its orange filter, under which the photo paper is not sensitive; the paper goes onto the
screen under the cover glass; the filter is opened for the exposure, and the developed print is the rectified
photo, ready to be cut along its working area and mounted on the base.
""", id="theory"),
    md("""
## The photo transformer, live

The example photo is the virtual site (flat version) taken with the guide's §12 numbers: $f = 108$ mm, 1:15 000,
base 1:5000, $K_t = 3$, tilted by α = 3°. Magenta triangles are the four transformation points and the central
point on the base; orange dots their images on the screen; the arrows (lengthened ×k) the misses. Move **step**
through the motions; the other sliders change the photo (a quick preview is shown while you drag).
""", id="demo-theory"),
    code("""
demo = dr.TransformerDemo()
demo
""", id="demo-transformer"),
    md("""
**Try this.**

* Step 3 draws hh through the crossings (blue ×) of corresponding lines; step 4 turns the tilt onto it; step 5
  tilts the screen — the misses drop from several millimetres to about one, and the second cycle brings them to
  about a tenth.
* Raise α to 8°: the first cycle leaves two millimetres, the second cleans up. Raise the pricking error σ to
  0.15 mm: the misses stop near 0.4 mm (0.15 mm on the photo is 0.45 mm on the base at $K_t = 3$); at 0.2 mm the
  sequence never gets within the tolerance, however often it is repeated — the points must be pricked again.
* `demo.result.run.table()` lists every step's settings and its largest miss.
""", id="try-this"),
    md("""
## Before the transformer: the paper and the substrate (guide §12, step 2)

Photographic paper changes size when it is developed and dried. To know by how much, a glass **control grid**
(контрольная сетка, squares of 5 mm) is contact-printed on the same paper and lengths $l_1 \\dots l_6$ are measured
on the print to 0.1 mm; on the grid they are $l_0 = 5\\,\\text{mm}\\cdot n$. With $\\delta l = l_0 - l_i$,

$$K_d = \\frac{[\\delta l]}{[l_0]}\\qquad\\text{(positive: the paper shrinks; negative: it stretches).}$$

The transformer compensates it by a **substrate** (подложка) of thickness

$$t = K_d\\,f\\,(K_t + 1),\\qquad K_t = \\frac{m}{M}.$$

Why: the lens throws the image a distance $v = f\\,(K_t + 1)$ (thin-lens law); moving the screen by $t$ changes the
image's size by $t/v$. The substrate lies under the base planchet while the images are matched and is taken away
for the exposure, so the paper sits $t$ further from the lens and its image comes out larger by $t/v = K_d$ — what
a shrinking paper needs. A **negative** $t$ (stretching paper) asks for the opposite: the *paper* must be raised
by $|t|$ at the exposure.

### Table 11, recomputed
""", id="table11-theory"),
    code("""
guide.ch11.table_11()
""", id="example-1"),
    md("""
**What table 11 turns out to contain.** Every length difference, the three sums and $K_d = -0.7/734.8 =
-0.00095264$ follow from the printed lengths. Two things the scan hides: the head of the δl column lost its minus
sign (δl = $l_0 - l_i$, fixed by the printed values), and $l_5 = l_6 = 152.40$ mm are not "5 mm·n" at all but the
diagonals of the 20 × 23-square rectangle whose sides are $l_1, l_2$ (100 mm) and $l_3, l_4$ (115 mm):
$5\\sqrt{20^2 + 23^2} = 152.398$ mm. The substrate is printed as $t = +0.4115$: the product of the printed factors
is $-0.00095264 \\cdot 108 \\cdot 4 = -0.4115$ mm. The magnitude is right; the sign is dropped, and it matters — this
paper stretched, so the 0.41 mm go under the paper at the exposure, not under the planchet.

§12 also lists the plan coordinates of four points; nothing is computed from them in the guide:
""", id="example-1-note"),
    code("""
guide.ch11.plan_points()
""", id="example-2"),
    md("""
Taken round, the four points make a long, narrow quadrilateral (about 830 m by 180–270 m in the list's units),
not the corners of one photo's working area; the numbers 550/551 and 641/644 look like photo numbers of two
neighbouring strips.

## A four-point rectification, worked

The example photo of the virtual site — the real one, with its 30 m of relief — at the guide's numbers. Four
control points near the corners of the working area, two check points (K2 where relief should show most); photo
coordinates with a pricking error of 0.03 mm, base coordinates at 1:5000:
""", id="example-3-theory"),
    code("""
example = labs.ch11.example_rectification_lab()
display(example.table())
example.rectification.table()
""", id="example-3"),
    md("""
The residuals at the control points are zero: four points fix the transformation exactly. The check points are
within 0.4 mm. Over the whole photo, every catalogue point of the site against its true place on the base — first
the flat version of the site, then the real one:
""", id="example-4-theory"),
    code("""
plots.static(dr.rectified_figure(labs.ch11.example_rectification_lab(relief=False), relief=False),
             alt="Left: a photo of the flat version of the virtual site rectified onto the base at 1:5000, with "
                 "arrows at every catalogue point showing its residual enlarged fifty times; the arrows are short "
                 "and point every way (pricking errors only). Right: the left half of the same window is the "
                 "rectified photo, the right half the true map of the site; roads and field edges run straight "
                 "across the seam.")
""", id="figure-flat"),
    code("""
plots.static(dr.rectified_figure(example),
             alt="The same for the real site with 30 m of relief: the residual arrows, enlarged fifty times and "
                 "coloured by height above the control points, now point away from the photo's nadir on high "
                 "ground and towards it in the valley, and are longest far from the centre — relief displacement "
                 "that the rectification keeps.")
""", id="figure-relief"),
    md("""
On flat ground the residuals are what the pricking errors of the four control points leave: about a tenth of a
millimetre, a few tenths at the edges, pointing every way. With relief they line up:
radial from the nadir, outwards on the hills and inwards in the valley, growing with the distance from the centre —
$\\delta_h\\,K_t = r\\,h/H\\cdot K_t$ carried onto the base. Rectification fixes the plane; it cannot fix the height.

## Task 11.1 — your paper and substrate (graded)

Your table 11 is below: six lengths on the control grid (two lines of squares, two other lines and the two
diagonals of the rectangle they span) and on its contact print, and your $f$, $m$ and the base scale 1:10 000.
Compute

* `K_d` — the mean deformation coefficient $[\\delta l]/[l_0]$ with $\\delta l = l_0 - l_i$ (tolerance 3 %: the
  diagonals' $l_0$ as the table shows them or computed exactly, $5\\sqrt{a^2 + b^2}$ mm, and $[l_0]$ or $[l_i]$ in
  the denominator are all accepted — they differ by up to 2.5 %, far less than the 0.1 mm readings make $K_d$
  uncertain);
* `t_mm` — the substrate thickness $K_d\\,f\\,(K_t + 1)$ from your $K_d$, mm, **with its sign** (tolerance 3.5 %).
""", id="task-11-1"),
    code("""
paper = tasks.inputs("task-11-1", v)
display(paper.parameters())
paper.table()
""", id="task-11-1-data"),
    answer_cell("task-11-1"),
    check_cell("task-11-1"),
    md("""
## Task 11.2 — your four-point rectification (graded)

Your photo: your $f$ and 1:m, tilt α = 3° with the principal vertical at your λ, over the virtual site. Four control
points 1–4 and two check points K1, K2 were pricked on it (photo mm) and plotted on the base at 1:10 000 (mm). Fit
the projective transformation photo → base on points 1–4 only (`rectify.rectify_points` or
`aerophoto.projective.fit_projective`) and give

* `d1_mm`, `d2_mm` — the residual lengths $|$base − transformed photo$|$ at K1 and K2, mm on the base
  (tolerance 0.02 mm);
* `rect_ok` — `True` if both are within the guide's 0.4 mm.
""", id="task-11-2"),
    code("""
rect = tasks.inputs("task-11-2", v)
rect.table()
""", id="task-11-2-data"),
    answer_cell("task-11-2"),
    check_cell("task-11-2"),
    md("""
**Think about it.** K2 is the point of your photo where relief should displace most. Is your residual there
larger than at K1? A longer focal length at the same photo scale flies higher and shrinks $r\\,h/H$.

## Summary

* Rectification maps a tilted photo of flat ground onto the plan by a projective transformation; four points fix
  it, check points judge it against 0.4 mm on the base.
* The photo transformer reaches the same result by a sequence of motions — centre, scale, find hh, turn, tilt —
  repeated until the points coincide.
* Relief displacement is not removed: residuals on hilly ground are radial from the nadir and proportional to the
  height above the control points.
* Table 11: δl = $l_0 - l_i$; $l_5, l_6$ are diagonals of the grid; $K_d$ is right; the substrate thickness is
  $-0.4115$ mm, printed without its sign — the paper stretched, so the substrate goes under the paper.

Next: **12 · Phototriangulation**.
""", id="summary"),
]


def main():
    nb = notebook(CELLS, title="11 · Rectifying photos of flat ground")
    write(nb, PATH)
    print("wrote", PATH.relative_to(ROOT))


if __name__ == "__main__":
    main()
