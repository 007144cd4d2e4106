"""Write notebooks/05_fotoschema.ipynb (guide §6) from its cells (safe to re-run).

    python docs/tools/build_05_fotoschema.py

Cells are identified by id; the notebook is written without outputs.  The graded work is on the student's own
fotoschema (aerophoto.tasks.ch05); the live demo opens on the guide's worked example, variant 00.
"""

from pathlib import Path

from aerophoto.nbtools import code, md, notebook, write

from lab_cells import answer_cell, check_cell  # noqa: E402  (same folder)

ROOT = Path(__file__).resolve().parents[2]
PATH = ROOT / "notebooks" / "05_fotoschema.ipynb"

CELLS = [
    md("""
# 05 · The single-strip photo mosaic (guide §6)

A single photo covers a few square kilometres; a farm, a village or a stretch of road usually needs
several. The quickest way to get one continuous picture of them is to cut the prints of a strip along
the middle of their overlaps and glue the central parts side by side: a **photo mosaic** (фотосхема).
It can be made the day after the flight with a scalpel, a ruler and glue, and land-management offices
use it for field inspections, draft projects, soil and vegetation surveys and for checking land use.
It is not a map, though, and this chapter shows exactly how far from one it is.

**In this chapter you will**

1. learn how a fotoschema differs from a photoplan and how it is assembled: working areas, tie points,
   cuts (guide §6, steps 1–5);
2. assemble one live from the virtual site and watch cut-outs and duplicates appear along the cuts as you
   change the focal length, the scale, the tilt, the relief and the overlap;
3. measure its quality by the mismatches ΔI and their RMS $m$, and its mean scale from four bases
   (guide §6, steps 7–8), on the guide's worked example;
4. glue **your own** fotoschema from your own four photos, check its seams and measure its mean scale
   (two graded tasks);
5. sign your sheet with the guide's marginalia and print it at true size (PDF and PNG).
""", id="title"),
    code("""
RECORD_BOOK = None  # ← type your record-book number in quotes, e.g. "19-0457"
import aerophoto
import numpy as np
from aerophoto import tasks
from aerophoto.demos.fotoschema import (FotoschemaDemo, FotoschemaView, fotoschema_model, correction_sheet,
                                        sheet_figure, own_sheet_figure, finished_sheet)
v = aerophoto.setup(RECORD_BOOK)
""", id="setup"),
    md("""
## Fotoschema and photoplan

Both are made of the central parts of aerial photos. A **photoplan** (фотоплан) is made of photos that
have first been *rectified* (трансформированы; chapter 11, guide §12): brought to one exact scale and freed
from tilt displacement, so it is a plan and can be measured like one. A **fotoschema** is made of the photos
as they are — contact prints, or prints enlarged or brought roughly to one scale. Inside each glued piece
it has the geometry of that photo (its tilt and relief displacements, its own scale); across a cut, small
distances can be wrong by the mismatch of the two pieces. Over longer distances the errors of the pieces
partly cancel, so lengths and areas measured across the whole sheet are better than those measured
across one cut.

The central part of a print that ends up on the sheet is its **working area** (рабочая площадь): it
reaches half way into the overlap with each neighbour, so that every piece of ground appears once. The
guide describes two ways of assembling a strip — by corresponding points and by initial directions — and
we follow the first (guide §6, steps 1–5):

1. lay the first print on the second so that the same detail coincides (by flicking, способ мельканий)
   and note the middle of their double overlap;
2. near that middle, 1.5–2.5 cm from the upper and the lower edge, pick two sharp points $a$ and $b$ seen
   on both prints — **on high ground**, to avoid cut-outs (see below) — and prick them;
3. lay a ruler through $a$ and $b$ and cut both prints with one stroke of the scalpel;
4. go on along the strip the same way, cutting each pair together;
5. glue the working areas in order onto a sheet (the guide asks for A3), matching the detail, and trim
   the sheet 1–1.5 cm beyond the working areas.

The cut may be straight, zigzag or curved (figure 12 of the guide), and the guide gives rules for where
it goes: it should not cross linear features (roads, rivers) at an acute angle, should not run through
buildings and other small detail, should keep at least 1 mm from important linear features, and is best
laid along ground of the same tone on both prints, so that it does not show.

The book does the same on simulated photos. The tie points are the highest ground in the two windows
the guide prescribes; the right print is laid on the left one by the **rigid motion** (a shift and a
turn — contact prints cannot be stretched) that brings $a$ and $b$ together as closely as possible; the
leftover misfit is shared equally between the two points, as the guide asks.
""", id="theory"),
    md("""
## Cut-outs, duplicates and the quality of the seams (guide §6, step 8)

Along a cut, the two prints rarely fit exactly. The left print shows ground up to the cut; the right one
continues from the cut. If the ground the right print shows at the cut lies *further along* the strip
than what the left print shows there, the ground in between is on neither working area: a **cut-out**
(вырез), given a minus sign. If it lies *behind*, that ground appears on both sides of the cut: a
**duplicate** (дублет), plus sign. Cut-outs are worse — small detail near the cut is simply lost — and
the guide allows them only up to 0.5 mm.

Where do they come from? A point $h$ metres above the height at which the prints were matched is
displaced on each photo by $\\delta_h = r\\,h/H$ away from that photo's nadir (chapter 03). At a cut half
way between two principal points, the two photos displace it in *opposite* directions along the strip,
so the two prints disagree by about $b\\,h/H$ there ($b$ the photo base, ≈ 7 cm). Matching on high ground
makes the other points of the cut lower ($h < 0$): they come out as duplicates, not cut-outs. Tilt adds
its own, smaller disagreement, and prints of different scale cannot be made to fit everywhere by a
shift and a turn.

**How the mismatches are measured.** The technician keeps the cut-off strips (обрезки). At a cut, the strip
cut off the *right* print is laid back where it was — over the left print's glued piece — so that its detail
matches the right print's piece across the cut. Every 2–3 cm along the cut a sharp detail close to the cut is
pricked through the strip with a needle. With the strip lifted, the prick sits where the *right* print shows
the detail; the detail itself, the **contour**, is where the *left* print shows it. Their offset along the
strip is the mismatch $\\Delta I$, and the guide gives its sign by their order: **minus** (a cut-out) when
the contour lies *between the cut and the prick*, **plus** (a duplicate) when the prick lies *between the
contour and the cut*. With both distances measured from the cut along the strip (positive into the left
piece),

$$\\Delta I = d_{contour} - d_{prick}.$$

The values are written on the **correction sheet** (корректурный лист, guide figure 13), and the quality of
the fotoschema is their RMS,

$$m = \\sqrt{\\frac{\\sum \\Delta I^2}{n}} \\qquad (6.2),$$

with $n$ the number of pricks. In the book the truth comes from the camera model: the ground each of the two
photos shows at a point of the cut, or the ground point of a detail and where each print places it.

*A note on the source.* Formula (6.2) is printed together with a second expression,
$m_i = \\sqrt{(l_{обр} - l_{сн})^2/n} \\to 0$, that the scan leaves without explanation (it seems to compare
lengths on the cut-off strips and on the photos); the book uses only the first.

## The mean scale (guide §6, step 7)

A fotoschema has no single exact scale, so it is signed with its **mean scale**. Two points are
identified near the outer edge of the first working area and two near the outer edge of the last one,
both on the fotoschema and on the 1:M topographic plan ($M$ = 10 000). Between them four bases are
measured to 0.1 mm — the two along the strip and the two diagonals — $l_i$ on the fotoschema and $L_i$ on
the plan. Each gives a partial scale, and their mean is the scale written on the sheet:

$$\\frac{1}{m_i} = \\frac{l_i}{L_i\\,M}\\ \\Rightarrow\\ m_i = \\frac{L_i\\,M}{l_i}, \\qquad m = \\frac{1}{4}\\sum m_i \\qquad (6.1).$$

The book takes the four points from the site's catalogue of well-defined points (road crossings, field
corners) nearest to those spots.
""", id="theory-seams"),
    md("""
## Live: assemble a fotoschema

The demo flies a strip of four photos — the guide's four prints — over the virtual site, assembles it as
described above and glues the working areas onto the sheet. It opens on the guide's worked example, variant 00
($f$ = 100 mm, 1:12 000). On the sheet: the print outlines (light blue), the cuts (orange), the tie points
$a$, $b$ (green ×), the principal points (+) and, at every check point, a disc whose size is $|\\Delta I|$ —
vermillion for cut-outs, blue for duplicates, black-rimmed beyond the tolerance. Below, the mismatches of each
cut against the −0.5 mm line. The tables give $m$, the mean scale and the partial scales.

The sliders reach every variant of the course (guide §1: $f = 100 + 10i$ up to 1090 mm, $m = 12\\,000 + 100i$ up
to 21 900). At the largest scales a tilt would carry the photos off the 10 × 5 km site (a photo tilted by α
moves its footprint by about $H\\,\\mathrm{tg}\\,\\alpha$, 1.3 km at $H$ = 24 km and 3°); the demo then flies
the largest tilt that keeps them on it and says so above the table.

While you drag a slider the sheet is glued at a coarse *preview* resolution; when the slider rests for a
third of a second it is glued again at full resolution (the title says which one you see).
""", id="demo-theory"),
    code("""
demo = FotoschemaDemo()   # the guide's worked example, variant 00: f = 100 mm, 1:12 000
demo
""", id="demo-fotoschema"),
    md("""
**Try this.**

* Set the relief $h$ to 0 and the tilt to 0: every disc vanishes, $m$ drops to zero and the mean scale is
  exactly the photos' scale. A fotoschema of flat ground from vertical photos is a perfect plan.
* Raise the relief to 150 m: the discs grow. Where a cut runs over ground lower than its tie points they
  are blue duplicates; where it climbs over a hill higher than the tie points, vermillion cut-outs — the
  guide's advice to tie on high ground helps only as far as the tie points really are the highest ground
  along the cut.
* Keep the relief and raise $f$ from 100 to 1000 mm. The scale stays the same, but the aircraft flies ten
  times higher and the relief displacements, $r\\,h/H$, shrink with it: long-focus cameras make better
  fotoschemas of hilly ground.
* With the relief at 0, raise the tilt to 5°: the mismatches stay small (a shift and a turn absorb most of
  the tilt displacement along a cut), but the partial scales spread — tilt shows in the *scale* of the
  fotoschema more than in its seams.
* Try the zigzag and curved cuts: the mismatches change from point to point because the cut samples
  different ground.
""", id="try-this"),
    md("""
## A worked example: the quality of a fotoschema

The guide prints no numbers for this section, so here is a fotoschema of our own: four photos (like the
four prints of the guide's assignment), the guide's camera of variant 00 ($f$ = 100 mm, 1:12 000,
$p_x$ = 60 %), tilts up to 1°, flown through the middle of the virtual site, whose relief of 30 m (170–200 m)
is exactly that of the guide's variants ($Z_{max} - Z_{min}$ = 30 m for every $i$).
""", id="example-theory"),
    code("""
ex = fotoschema_model(f_mm=100, m=12000, alpha_max_deg=1.0, relief_m=30.0, px_percent=60, seed=1, n_photos=4)
fs = ex.fs
view = FotoschemaView(ex)
aerophoto.plots.static(view.fig, alt="The fotoschema of four photos (f = 100 mm, 1:12 000, tilts up to 1°, relief 30 m): "
                       "the glued sheet with the print outlines, the cuts, the tie points and a disc at every check "
                       "point (vermillion cut-outs, blue duplicates); below it the mismatches ΔI of each cut against "
                       "the −0.5 mm tolerance.")
""", id="example-1"),
    md("""
The correction sheet: every check point with its $\\Delta I$ in mm.
""", id="example-2-text"),
    code("""
ax = correction_sheet(fs)
aerophoto.plots.static(ax.figure, alt="The correction sheet (корректурный лист) of the same fotoschema: the frames, "
                       "the cuts and, beside every check point, its mismatch ΔI in mm with its sign.")
""", id="example-2"),
    md("""
The same values as a table, and the RMS by formula (6.2) computed by hand beside the package's value:
""", id="example-3-text"),
    code("""
dI = fs.dI_mm
n = dI.size
m_hand = np.sqrt(np.sum(dI**2) / n)
print(f"n = {n} pricks, ΣΔI² = {np.sum(dI**2):.3f} mm², m = √(ΣΔI²/n) = {m_hand:.3f} mm   (package: {fs.rms_mm:.3f} mm)")
print(f"largest cut-out {dI.min():+.2f} mm → {'within' if fs.ok else 'beyond'} the 0.5 mm tolerance")
fs.seams_table()
""", id="example-3"),
    md("""
And the mean scale from the four bases (6.1). The points are catalogue points of the site; their plan
positions are their true coordinates drawn at 1:10 000.
""", id="example-4-text"),
    code("""
sc = fs.scale
m_i = sc.L_mm * sc.M / sc.l_mm
print("partial scales m_i = L_i·M/l_i:", np.round(m_i).astype(int), " mean m =", round(float(m_i.mean())),
      f" (package {sc.m:.0f}; design 1:{fs.m_design:.0f}; signed on the sheet as 1:{sc.m_rounded})")
sc.table()
""", id="example-4"),
    md("""
The mean scale differs from the photos' design scale 1:12 000 because the design refers to the mean
height of the *whole site*, while these four points lie on whatever ground the ends of the strip happen to
cover, and because the tilts change the scale across each photo.

## The finished sheet (guide §6, step 9 and the appendix)

After the check the boundary of the working area is drawn on the fotoschema: on the first and the last photo
two points on the middle of the side overlap with the neighbouring strips ($l/2 - p_y l/200$ = 63 mm from the
principal point for the 18 cm frame at $p_y$ = 30 %) are joined by straight lines in ink, and the sheet is
trimmed 0.5–1 cm outside them (the book: 1 cm). The guide's appendix shows the finished sheet: the title
**ФОТОСХЕМА** above, the mean scale "М 1:13000" under it (the appendix writes the fotoschema's mean scale with
the letter M, which elsewhere in the guide denotes the plan's scale), and at the bottom the year it was made,
who made it and who checked it. The book draws the sheet **at true size** on the smallest ISO A sheet that
holds it — for four photos that is A3, as the guide asks — so the PDF prints at the fotoschema's scale. The
prints glued here are rendered photos, with the light fall-off towards their corners and their fiducial marks,
so the cuts show as the tone changes of a real fotoschema. Here is the worked example's sheet:
""", id="sheet-theory"),
    code("""
prints = fotoschema_model(f_mm=100, m=12000, alpha_max_deg=1.0, relief_m=30.0, px_percent=60, seed=1, n_photos=4,
                          px_per_mm=5.0, prints="render")
example_sheet = sheet_figure(prints.fs, prints.image, prints.extent_mm, made_by="", checked_by="")
aerophoto.plots.static(example_sheet, dpi=50,
                       alt=f"The worked example's finished fotoschema on an {example_sheet.aerophoto_paper} sheet: the "
                           "four glued prints trimmed 1 cm outside the working-area lines, the title ФОТОСХЕМА, the mean "
                           "scale, a scale bar, the year and blank lines for who made and who checked it")
""", id="sheet-example"),
    md("""
## Your fotoschema

Now the guide's work on **your** photos. Your strip is four photos, 36 to 39, taken with **your** camera
($f$ = 100 + 10·i mm) at **your** scale (1:(12 000 + 100·i)) with $p_x$ = 60 %, over the virtual site at a place
of its own (it depends on your variant number $i$), glued exactly as above. The same four photos are the strip
you triangulate in chapters 06 and 12.

Two things about the flight, so that every variant 00–99 flies the guide's scheme honestly:

* the photos are near-vertical, tilted by up to 2° in random directions — except that a tilt moves a photo's
  footprint by about $H\\,\\mathrm{tg}\\,\\alpha$, and at $H$ = 24 km (variant 99) 2° would move it 830 m, off
  the 10 × 5 km site. So the tilt is capped where the nadir point would lie more than 6 mm from the principal
  point ($f\\,\\mathrm{tg}\\,\\alpha \\le$ 6 mm): 2° up to $f$ = 172 mm, 0.32° at 1090 mm;
* the ground is the site's true relief, 170–200 m: the 30 m of every variant. The mismatches scale with
  $b\\,h/H$, so they depend on your **flying height**: up to about 72 mm · 30 m / 1200 m = 1.8 mm for
  variant 00, 0.09 mm for variant 99 ($H$ = 23.9 km). A long-focus variant finds seams within the reading
  error — that is the honest result, and the point of the "Try this" above.

The figure shows your sheet as you work on it: the cuts, the details pricked along them through the cut-off
strips (numbered as in the readings of task 05.1) and the four points 36a, 36b, 39a, 39b of the mean scale
(task 05.2). No mismatch and no scale is shown: those you compute.
""", id="own-theory"),
    code("""
aerophoto.plots.static(own_sheet_figure(v),
                       alt="Your fotoschema of photos 36 to 39: the glued prints, the three cuts, the numbered details "
                           "pricked along each cut and the four points 36a, 36b, 39a, 39b of the mean scale")
""", id="own-figure"),
    md("""
## Task 05.1 — the seams of your fotoschema (graded)

Along each of your three cuts the cut-off strip of the right print was laid back and a detail close to the cut
pricked through it every 2.5 cm (the yellow circles of the figure). The table gives, for every check point: where
along the cut it is (across the strip, to 1 mm), and — measured **along the strip from the cut, positive into the
left piece**, to 0.1 mm — the distance to the **contour** (the detail on the glued left piece) and to the
**prick** (where the cut-off strip of the right print put it). Set

* `dI_mm` — the mismatch $\\Delta I$ at every check point, in the table's order, mm, with the guide's sign:
  **−** (cut-out) where the contour lies between the cut and the prick, **+** (duplicate) where the prick lies
  between the contour and the cut;
* `m_rms_mm` — the quality $m = \\sqrt{\\sum\\Delta I^2/n}$ of your fotoschema (6.2), mm;
* `n_cutouts` — how many check points are cut-outs;
* `seams_ok` — `True` if no cut-out exceeds the guide's 0.5 mm, else `False`.

Tolerances: 0.05 mm for $\\Delta I$ (half the 0.1 mm of the readings), 0.005 mm for $m$.
""", id="task-05-1"),
    code("""
seams = tasks.inputs("task-05-1", v)   # your readings along the cuts
seams
""", id="task-05-1-data"),
    answer_cell("task-05-1"),
    check_cell("task-05-1"),
    md("""
## Task 05.2 — the mean scale of your fotoschema (graded)

Near the outer edges of your first and last working areas four points were identified on the fotoschema and on
the 1:10 000 plan: 36a, 36b (photo 36) and 39a, 39b (photo 39), the squares of the figure. The table gives their
positions read to 0.1 mm — on the fotoschema along and across the strip, on the plan $x$ north and $y$ east
(the Russian geodetic convention, which the book uses for every plan you work on). Take the four bases **in this
order**: 1 = 36a–39a, 2 = 36b–39b (along the strip), 3 = 36a–39b, 4 = 36b–39a (the diagonals). Set

* `l_mm` — the four bases on the fotoschema $l_i$, mm;
* `L_mm` — the same bases on the plan $L_i$, mm;
* `m_i` — the four partial scale denominators $m_i = L_i M / l_i$ with $M$ = 10 000;
* `m_mean` — the mean scale denominator $m$ of your fotoschema (6.1).

Tolerances: 0.05 mm for the bases, 0.1 % for the scales.
""", id="task-05-2"),
    code("""
points = tasks.inputs("task-05-2", v)   # your four points on the fotoschema and on the plan
points
""", id="task-05-2-data"),
    answer_cell("task-05-2"),
    check_cell("task-05-2"),
    md("""
## Your finished sheet

Once task 05.2 has passed, the cell below signs your fotoschema with the mean scale you computed (rounded to
hundreds, as the appendix does), the year, your name and your record book, and writes it at true size as PDF and
PNG (A3 for every variant). Type your name (it is not graded). The files go to a fresh temporary folder; to keep
them, give `finished_sheet` a `folder=` of your own — it never overwrites an existing file. Put a copy in your
report: the guide lists the fotoschema first among the graphic products to hand in (guide §1).
""", id="own-sheet-text"),
    code("""
STUDENT_NAME = ""          # ← your name for the sheet, e.g. "Ivanova A."
from aerophoto import checks
finished_sheet(v, STUDENT_NAME, answered=checks.passed("task-05-2"))
""", id="own-sheet"),
    md("""
## Summary

* A fotoschema is glued from the working areas of unrectified prints; a photoplan from rectified ones.
* Neighbours are laid together on two tie points on high ground near the middle of the overlap, and cut
  through them; relief ($\\approx b\\,h/H$), tilt and scale differences leave mismatches along the cuts.
* Cut-out (вырез, −: the contour between the cut and the prick): ground lost between the pieces, allowed up to
  0.5 mm; duplicate (дублет, +): ground shown twice. Quality $m = \\sqrt{\\sum\\Delta I^2/n}$ (6.2).
* Mean scale from four bases: $m_i = L_i M / l_i$, $m$ their mean (6.1); it is written on the sheet with the
  title, the year and the names (the appendix), and the sheet is trimmed 1 cm outside the working area.
* Longer lenses (higher flights at the same scale) and flat ground make better fotoschemas: the variants of
  the course go from mismatches near 1 mm (i = 00) to below the reading error (i = 99).

Next: **06 · Strip phototriangulation** — how to give a strip of photos a real scale and position.
""", id="summary"),
]


def main() -> None:
    write(notebook(CELLS), PATH)
    print(f"wrote {PATH.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
