"""Write notebooks/07_stereoscope.ipynb (guide §8) from its cells (safe to re-run).

    python docs/tools/build_07_stereoscope.py

Cells are identified by id; the notebook is written without outputs.
"""

from pathlib import Path

from aerophoto import labs
from aerophoto.nbtools import code, md, notebook, write

from lab_cells import answer_cell, check_cell  # noqa: E402  (same folder)

ROOT = Path(__file__).resolve().parents[2]
PATH = ROOT / "notebooks" / "07_stereoscope.ipynb"


def _bias_table() -> str:
    """The pricked base b against b₀ = B·f/H over the 100 variants, grouped by f (a markdown table, ~90 s)."""
    import pandas as pd

    from aerophoto.variants import variant_for_index

    rows = []
    for i in range(100):
        lab = labs.ch07.stereo_lab(variant_for_index(i))
        rows.append((lab.f_mm, 100.0 * abs(lab.b_mm / lab.b_flat_mm - 1.0)))
    df = pd.DataFrame(rows, columns=["f", "bias"])
    out = ["| f, mm | variants | mean \\|b − b₀\\|, % | largest \\|b − b₀\\|, % |", "|---|---|---|---|"]
    for lo, hi in ((100, 300), (300, 600), (600, 900), (900, 1100)):
        g = df[(df["f"] > lo - (lo == 100)) & (df["f"] <= hi)]["bias"]
        out.append(f"| {lo}–{hi} | {len(g)} | {g.mean():.1f} | {g.max():.1f} |")
    return "\n".join(out)


CELLS = [
    md("""
# 07 · The stereoscope and the stereo model (guide §8)

Two neighbouring photos of a strip show the same ground from two places. Looked at so that each eye sees one of
them, they fuse into one picture in depth: hills stand up, houses and trees rise from the ground. This is how a
photogrammetrist reads relief from photos — and, with a measuring mark, how heights are measured on them.

**In this chapter you will**

1. learn what a **stereo pair** (стереопара) is, why it gives a **stereo effect** (стереоэффект), direct or
   reverse, and what **x-parallax** (продольный параллакс) measures;
2. see how the **lens-mirror stereoscope** (линзово-зеркальный стереоскоп) works and check its mirrors the
   guide's way;
3. look at a pair of the virtual site in depth — now the site has houses, trees, forest, a chimney and a mast —
   through red–cyan glasses, and set a **floating mark** (измерительная марка) on the ground and on a roof to
   read heights;
4. see how base, flying height and focal length change the parallaxes and the relief of the model;
5. let a computer find parallaxes by correlation and compare its height model with the truth;
6. measure heights on **your own** pair and check them.
""", id="title"),
    code("""
RECORD_BOOK = None  # ← type your record-book number in quotes, e.g. "19-0457"
import aerophoto
from aerophoto import checks, guide, labs, plots, stereo, tasks
from aerophoto.demos import stereo as ds
from aerophoto.demos import stereo_figures as sf
v = aerophoto.setup(RECORD_BOOK)
""", id="setup"),
    md("""
## Two photos, one space image

Each eye sees the world from a slightly different place; the brain fuses the two views and reads depth from their
small differences. Two photos taken from the two ends of a **base** (базис фотографирования) give the eyes just
such views of the ground — only from places hundreds of metres apart. Seen left photo by the left eye and right
photo by the right eye, they fuse into a **stereo model** (стереомодель): the **direct stereo effect** (прямой
стереоэффект). Swap them and the model turns inside out — valleys rise, hills sink: the **reverse stereo effect**
(обратный стереоэффект). Two neighbouring photos of a strip that overlap are a **stereo pair** (guide §8; with
p_x = 60 %, every ground point in the middle of a strip is on two photos).

### x-parallax

Put the pair side by side with both x axes along the flight. A ground point has the coordinate $x_1$ on the left
photo and $x_2$ on the right; their difference is its **x-parallax**

$$p = x_1 - x_2 .$$

Over flat ground every point has the same parallax, the **photo base** $b = B\\,f/H$: the air base $B$ (m) between
the exposures, seen from the flying height $H$ with the focal length $f$. A point higher by $h$ is nearer to the
cameras, so it moves more between the two photos: $p = B f/(H - h)$. That difference is what the eyes see as depth,
and what a **parallax bar** (параллактометр) measures.

On a pair turned to a common orientation with x along the base — **normalised**, or **epipolar**, photos — the
rows are epipolar lines: a point has the same $y$ on both photos, and the **parallax equations** give its place
from the left photo's coordinates and its parallax (x, y, p, f in mm; B in m):

$$X = \\frac{B\\,x}{p},\\qquad Y = \\frac{B\\,y}{p},\\qquad h = H - \\frac{B\\,f}{p}.$$

Two points whose parallaxes differ by $\\Delta p$ differ in height by

$$\\Delta h = \\frac{H\\,\\Delta p}{p + \\Delta p}\\;\\approx\\; \\frac{H\\,\\Delta p}{b},$$

with $H$ the flying height above the lower point and $p$ its parallax (close to $b$); the small form is good while
$\\Delta p \\ll b$. Conversely, a height $h$ shows as $\\Delta p = b\\,h/(H - h)$. A point of known height gives the
flying height from its parallax, $H = B f/p$, or the air base, $B = p H / f$. What is left across the base,
the **y-parallax** $q = y_1 - y_2$ (поперечный параллакс), is zero for a correctly oriented pair: it is the check
of the orientation, and the eyes cannot fuse a pair with much of it.

**Vertical exaggeration.** The cameras saw the ground from $H$ with the base $B$; the eyes see the model from the
viewing distance $d$ (about 250 mm) with the eye base $e$ (about 65 mm). Heights therefore look

$$V = \\frac{B/H}{e/d}$$

times larger than horizontal distances — about 2.8 for the guide's pair ($B/H = 0.72$). It is a geometric guide:
how deep a model looks also depends on the observer.
""", id="theory"),
    code("""
guide.ch07.terms_table()
""", id="theory-terms"),
    code("""
plots.static(sf.pair_geometry_figure(),
             alt="Cross-section of a stereo pair: two stations S1 and S2 at the same height, an air base apart, and "
                 "the two photo planes below them. Rays from both stations go to a ground point A and to a point C "
                 "on a tower, higher than A. On the photos the images c1 and c2 of the higher point lie farther apart "
                 "than a1 and a2: its x-parallax is larger.")
""", id="figure-pair"),
    md("""
## The lens-mirror stereoscope

Conjugate points of two photos laid side by side are farther apart than the eyes, and each eye would see both
photos. The stereoscope (guide §8, figure 17) separates the views: under each eye a lens and a small mirror, and
further out a large mirror, send each eye's line of sight down to its own photo. The photos lie about the
instrument's base apart (for a common stereoscope about 25 cm), and the lenses let the eyes relax as if looking far
away. Without an instrument, the guide's first step places two conjugate images at the **mean eye base** apart
and asks the eyes to look "through" the paper until the two images of one point merge.
""", id="theory-stereoscope"),
    code("""
plots.static(sf.stereoscope_figure(),
             alt="Section through a lens-mirror stereoscope: two eyes 65 mm apart at the top, a lens under each, small "
                 "mirrors at 45 degrees sending each line of sight outwards to a large mirror, which sends it down to "
                 "its photo; the two photos lie about 250 mm apart on the table.")
""", id="figure-stereoscope"),
    code("""
guide.ch07.steps_table()
""", id="example-steps"),
    md("""
### Checking the stereoscope

Besides looking the instrument over (lenses and mirrors whole, clean and firm), §8 checks that the mirrors are
parallel in pairs with a straight line 40 cm long: with the instrument's base along the line, the observer must
see **one** line.
""", id="checks-theory"),
    code("""
guide.ch07.checks_table()
""", id="example-checks"),
    md("""
Why it works: each eye looks at its own part of the line, one base apart. If the instrument is turned by a small
angle from the line, the two parts are no longer at one height in the two views: two **parallel** lines, which
turning the instrument brings together. If a pair of mirrors is rolled about the line of sight, that eye's view
turns by twice the roll: the two lines cross at an **angle**, and no turning can merge them — the mirror has to
be re-seated (the guide's strips of paper under its frame). The figure computes both cases
(`sf.stereoscope_view??`):
""", id="checks-why"),
    code("""
plots.static(sf.mirror_check_figure(turn_deg=1.5, mirror_roll_deg=1.0),
             alt="Three small views of the 40 cm check line as the two eyes see it. Left: both lines coincide, one "
                 "line. Middle: the stereoscope turned by 1.5 degrees, two parallel lines about 6 mm apart. Right: "
                 "one mirror pair rolled by 1 degree, the two lines cross at an angle of 2 degrees.")
""", id="figure-mirrors"),
    md("""
## A site with heights

Until now the virtual site was painted on its terrain. For stereo it has what a real site has: **houses**
(boxes on their roofs' footprints, gabled or flat), **single trees** and **garden trees** (crowns), the **forest
canopy** (14–24 m over the forest land cover), a **chimney** (42 m), a **water tower** (24 m), a **radio mast**
(64 m), and the paved road on an **embankment** and a **bridge** across the river's floodplain. The renderer casts
every ray against them, so on the photos they lean away from the nadir point by $\\delta_h = r\\,h/H$ (chapter 03)
and hide what stands behind them. The bare ground stays the site's DEM; roof corners and tree tops are surveyed
points (`site.all_points`). The objects, by kind:
""", id="site-theory"),
    code("""
from aerophoto.site import get_site
site = get_site()
table = site.objects.table()
table.groupby("kind")["height_m"].agg(["count", "min", "max"]).round(1).rename(
    columns={"count": "objects", "min": "lowest, m", "max": "highest, m"})
""", id="site-objects"),
    md("""
## The floating mark

The guide's pair: $f = 100$ mm, 1:12 000, $p_x = 60$ % — normalised and shown as a **red–cyan anaglyph**: the left
photo in the red channel, the right in green and blue. Put on red–cyan glasses **with the red filter over the left
eye**; each eye then sees only its photo, and the overlap stands up in depth.

The mark is two small crosses, one in each photo's channel, $p$ apart: the setting of a parallax bar's drum. At
one $p$ the eyes fuse them into a single mark floating in the model; raise $p$ and it rises, lower it and it sinks.
When it just touches the surface — the ground, a roof, a tree top — its parallax is that point's parallax, and the
table turns it into a height with the parallax equations. (Beside it, for this example, the truth of the site.)
""", id="demo-theory"),
    code("""
mark = ds.FloatingMarkDemo()
mark
""", id="demo-floating-mark"),
    md("""
**Try this.**

* With the mark on the road in the village, find the $p$ at which it rests on the asphalt. Then move it onto a
  roof ($x$, $y$) and raise $p$ until it sits on the roof: the height difference is the house's height, 3–8 m.
* Choose *mast* and climb the 64 m mast: about 4 mm of parallax. The mast leans on the photo, away from the nadir.
* Switch to *reverse*: the village sinks into the ground — the reverse stereo effect.
* `mark.set(area="forest edge", p_mm=73.6)` puts the mark at the level of the canopy.
""", id="try-this"),
    md("""
## Base, height and focal length

The parallax a height gives, $\\Delta p = b\\,h/(H - h)$ with $b = B f/H$, and the relief of the model, $V$, depend
on the pair's geometry. The explorer starts on the guide's pair ($H = 1200$ m, $B = 864$ m, $f = 100$ mm).
""", id="demo-base-theory"),
    code("""
base = ds.BaseHeightDemo()
base
""", id="demo-base-height"),
    md("""
**Try this.** Double $B$: every parallax difference doubles and the model looks twice as tall. Keep the scale (raise
$f$ and $H$ together, e.g. `base.set(f_mm=200, H_m=2400)`): $b$ stays 72 mm, but $\\Delta p$ of the same height halves
and $V$ halves — long lenses flatten the model. Set the guide's variant 99, `base.set(f_mm=1090, H_m=23871,
B_m=1577)`: $V$ = 0.25, a house of 6 m gives 0.02 mm of parallax — beyond what a parallax bar reads. The book's
variants go that far honestly (chapter 00); real mapping cameras stop near 305 mm.
""", id="try-this-base"),
    md("""
## The guide's pair, worked

§8 prints no table to recompute: its work is looking. So the worked example is the pair above, measured the way the
tasks below will ask you to: the principal points transferred to the neighbour photo give the photo base, and
the normalised pair — the pair turned onto its base — removes the y-parallax that the small tilts of a real flight
leave:
""", id="example-theory"),
    code("""
import numpy as np
import pandas as pd

lab = labs.ch07.example_lab()
b1, b2 = lab.photo_bases_mm()
from aerophoto import geometry as g

P = site.catalogue[["X_m", "Y_m", "Z_m"]].to_numpy()  # the site's surveyed points seen on both photos
xy1 = g.ground_to_photo(lab.camera, lab.left.pose, P)
xy2 = g.ground_to_photo(lab.camera, lab.right.pose, P)
seen = np.all(np.abs(xy1) < 88, axis=1) & np.all(np.abs(xy2) < 88, axis=1)
n1, n2 = lab.normal_xy(P[seen])
pd.DataFrame({"value": [lab.camera.f_mm, lab.m, lab.B_m, b1, b2, lab.left.pose.alpha_deg, lab.right.pose.alpha_deg,
                        seen.sum(), np.abs(xy1[seen, 1] - xy2[seen, 1]).max(), np.abs(n1[:, 1] - n2[:, 1]).max()]},
             index=["f, mm", "m (1:m)", "air base B, m", "photo base b₁, mm", "photo base b₂, mm", "tilt α₁, °",
                    "tilt α₂, °", "points seen on both photos", "largest y-parallax, original photos, mm",
                    "… on the normalised photos, mm"]).round(4)
""", id="example-pair"),
    md(r"""
**Two photo bases.** The base pricked from the principal points, $b = (b_1 + b_2)/2$, and the base of the
normalised pair, $b_0 = B\,f/H$ — the parallax of a point on the mean plane, what the parallax bar measures against —
are not the same on tilted photos. A tilt α moves the principal point away from the nadir by about $f\,\mathrm{tg}\,\alpha$
(chapter 04), so each pricked base carries the two photos' tilts: with the half-degree tilts of this pair
$b$ is 73.85 mm against $b_0$ = 72.68 mm, 1.6 % long. The bias grows with $f$: at $f$ = 730 mm (variant 63) half a
degree is 6.4 mm on the photo, and one variant's pricked base comes out about 3 % long; over the hundred variants
the two differ by 4.4 % on average and by up to 22 % for the longest lenses (the table, computed when the book
is built: the variants grouped by focal length, so that no one's own answer shows). Heights and exaggerations built on $b$
inherit that error; built on $b_0$ they do not. So task 07.1 asks for $b$ (it is what a student measures with a
ruler on the prints, and the task checks the measuring), and task 07.3, which computes what a height does to the
parallaxes, uses $b_0 = B\,f/H$ from the navigation record's $B$.

""" + _bias_table() + """
""", id="base-bias"),
    md("""
The photos, tilted by about half a degree and turned by a degree of crab, show y-parallaxes up to about a
millimetre — too much to fuse comfortably; after normalisation none is left (to rounding). The anaglyph above was made from the normalised photos. The same piece of
the overlap, direct and reversed:
""", id="example-anaglyph-theory"),
    code("""
images = labs.ch07.lab_images(lab)
fig = plots.figure(figsize=(10.5, 4.2))
ax1, ax2 = fig.subplots(1, 2)
centre = mark.areas["village"]
sf.anaglyph_figure(images, centre_mm=centre, size_mm=(40, 28), ax=ax1)
sf.anaglyph_figure(images, centre_mm=centre, size_mm=(40, 28), reverse=True, ax=ax2)
plots.static(fig, alt="Two red-cyan anaglyphs of the village on the guide's pair. Left: direct, the red channel "
                      "holds the left photo; houses and trees show red and cyan fringes that the glasses turn into "
                      "height. Right: the same with the photos swapped, the reverse stereo effect.")
""", id="example-anaglyph"),
    md("""
**A pair to print.** For a real stereoscope, or for free viewing without one, print the pair at **true size**:
`sf.stereo_print` writes a PDF (or PNG) whose page is exactly as large as needed, the two pieces with their conjugate
points 65 mm apart (free viewing) or 250 mm apart (the stereoscope — measure yours between the centres of the large
mirrors and pass `mode="stereoscope"` after setting `aerophoto.stereo.STEREOSCOPE_BASE_MM`). Print at 100 %; the
50 mm bar must measure 50 mm.
""", id="example-print-theory"),
    code("""
import tempfile
from pathlib import Path

folder = Path(tempfile.mkdtemp(prefix="stereo-"))
for mode in ("free viewing", "stereoscope", "anaglyph"):
    f = sf.stereo_print(images, folder / f"guide_pair_{mode.replace(' ', '_')}.pdf", mode=mode, centre_mm=centre)
    print(f"{mode:13s} →", f)
""", id="example-print"),
    md("""
## Parallaxes by correlation

A computer finds conjugate points by **correlation** (корреляция изображений): a small window of the left photo is
slid along the same row of the right photo — the epipolar line — and the shift where the normalised
cross-correlation is highest is the point's parallax (`stereo.match_points`, scikit-image's `match_template`). Along
one line through the village:
""", id="profile-theory"),
    code("""
y_line = mark.areas["village"][1]
plots.static(sf.profile_figure(lab, images, y_line),
             alt="Top: a strip of the anaglyph along one epipolar line through the village. Bottom: heights along "
                 "that line; the green truth line follows the gentle ground and jumps up at each house and tree; "
                 "the blue dots from the matched parallaxes follow it on the fields and the road and miss or blur "
                 "the narrow houses, where the red crosses mark weak matches.")
""", id="profile"),
    md("""
Done for every pixel (`stereo.dense_parallax`: the same correlation for all shifts at once), the parallaxes become
a coarse **height model** of the overlap. A match is kept only when it is clear: a high correlation (≥ 0.8), no
second peak close to it (a margin of 0.2), some texture, and the right photo matched back lands on the same pixel
(the left–right check). Here on the pair rendered at 512 pixels (0.35 mm, 4.2 m on the ground):
""", id="height-model-theory"),
    code("""
hm = labs.ch07.height_model(lab)
plots.static(sf.height_model_figure(hm),
             alt="Three maps of the overlap. Left: heights from correlation where the match was reliable, patchy. "
                 "Middle: the true heights, the gentle hills with the forest and the village standing up. Right: "
                 "the error; white within 2 m over most matched fields and roads, orange and blue spots at houses, "
                 "forest edges and some striped fields.")
""", id="height-model"),
    code("""
hm.table().round(1)
""", id="height-model-table"),
    md("""
**Where correlation fails, and why.**

* **Uniform fields** (fallow, smooth grass): nothing to correlate; the match is rejected (low texture, flat peak).
* **Repetitive texture**: the furrows of a ploughed field repeat every few pixels, so the correlation has many
  equal peaks — the wrong one is often a little higher. The uniqueness and left–right checks reject most; the rest
  are the gross errors of the table.
* **Occlusion** (закрытые участки): what the left photo sees beside a house or at a forest edge is hidden on the
  right photo; there is nothing to match.
* **Shadows**: dark and flat, like uniform fields.
* **Steep objects**: a window straddling a roof and the ground mixes two parallaxes; narrow houses, masts and
  single trees blur or vanish, and the forest's canopy is smoothed.

On the fields that are textured and seen by both photos the reliable matches agree with the truth to a couple of
metres (RMS) — about the height that one tenth of a pixel of parallax means at this scale.
""", id="failures"),
    md("""
## Task 07.1 — the base of your pair (graded)

Your pair is flown with your variant's $f$ and $1:m$, $p_x = 60$ %, over the middle of the site, with the small
tilts of a real flight. Below: the principal point of each photo as pricked on the other (mm, from that photo's
principal point), a control point A of known height on the normalised pair, and the air base $B$ of the
navigation record. Compute

* `b_mm` — the photo base, the mean of $b_1 = |o_1 o_2'|$ on the left photo and $b_2 = |o_2 o_1'|$ on the right, mm;
* `pA_mm` — the x-parallax of A, $p_A = x_{left} - x_{right}$, mm (tolerance 0.005 mm);
* `ZS_m` — the height of the projection centres from A: $Z_S = Z_A + B f / p_A$, m (tolerance 0.5 m).

Your pair's anaglyph, and prints of it for the stereoscope, are under the tables.
""", id="task-07-1"),
    code("""
lab = tasks.inputs("task-07-1", v)
display(lab.base_table())
display(lab.control_table())
print(f"air base of the navigation record: B = {lab.B_record_m:.1f} m; focal length f = {lab.camera.f_mm:g} mm")
""", id="task-07-1-data"),
    code("""
own = labs.ch07.lab_images(lab)
plots.static(sf.anaglyph_figure(own, size_mm=(70, 50), title="your pair: red filter over the left eye"),
             alt="A red-cyan anaglyph of the middle of your own stereo pair of the virtual site.")
""", id="task-07-1-pair"),
    code("""
own_folder = Path(tempfile.mkdtemp(prefix="my-stereo-"))
print("for your stereoscope:", sf.stereo_print(own, own_folder / "my_pair_stereoscope.pdf", mode="stereoscope"))
print("for free viewing:    ", sf.stereo_print(own, own_folder / "my_pair_free_viewing.pdf", mode="free viewing"))
own_mark = ds.FloatingMarkDemo(lab=lab, measure_only=True)  # measure on your pair: it reads parallaxes only
own_mark
""", id="task-07-1-mark"),
    answer_cell("task-07-1"),
    check_cell("task-07-1"),
    md("""
## Task 07.2 — heights of four objects (graded)

On your normalised pair (the parallax bar's setting) four objects were measured: **A** a roof corner, **B** the top
of a single tree, **C** the top of the chimney and **D** the top of the mast — each with a ground point beside it
(its *foot*). For each object compute the parallaxes $p_{foot}$, $p_{top}$, the difference
$\\Delta p = p_{top} - p_{foot}$, the flying height over the foot $H = B f / p_{foot}$ (B of the record), and its
height

$$\\Delta h = \\frac{H\\,\\Delta p}{p_{foot} + \\Delta p}.$$

* `dp_mm` — the four $\\Delta p$, in the order A, B, C, D, mm (tolerance 0.005 mm);
* `dhA_m`, `dhB_m`, `dhC_m`, `dhD_m` — the four heights, m (tolerance 0.05 m).
""", id="task-07-2"),
    code("""
lab.objects_table()
""", id="task-07-2-data"),
    answer_cell("task-07-2"),
    check_cell("task-07-2"),
    code("""
if checks.passed("task-07-2"):
    own_lab = labs.ch07.stereo_lab(v)   # the pair itself (its results are not part of your inputs)
    display(own_lab.parallaxes()[["Δh, m"]].join(own_lab.truth()).round(2))
else:
    print("Answer task 07.2 first: then your heights appear here beside the site's truth.")
""", id="task-07-2-truth"),
    md("""
**Think about it.** Your readings carry an error of about 0.01 mm in $p$; a height error of $H\\,\\sigma_p/b$
follows (0.17 m at 1:12 000 with $f$ = 100 mm). Compare your heights with the truth above: at a larger $H$ the same
reading error costs metres — and a house of 4 m may not show at all.
""", id="task-07-2-note"),
    md("""
## Task 07.3 — what a height does to your parallaxes (graded)

The site's relief is $h = Z_{max} - Z_{min}$ (your variant: 30 m). With the base of your normalised pair
$b_0 = B\\,f/H$ — the navigation record's air base $B$ and $H = f\\cdot m$, both in the table below; not the $b$ of the
pricked principal points from task 07.1, which your photos' tilts shift ("Two photo bases" above) — compute

* `dp_relief_mm` — the parallax difference of $h$: $\\Delta p = b_0\\,h/(H - h)$, mm, to four decimals
  (tolerance 0.005 mm; the small form $b_0\\,h/H$ is accepted where your $H$ makes it agree with the exact one
  within the tolerance, and named where it does not);
* `V` — the vertical exaggeration of your stereo model viewed at $d$ = 250 mm with the eye base $e$ = 65 mm:
  $V = (B/H)/(e/d)$, with $B/H = b_0/f$.
""", id="task-07-3"),
    code("""
tasks.inputs("task-07-3", v)
""", id="task-07-3-data"),
    answer_cell("task-07-3"),
    check_cell("task-07-3"),
    md("""
## Summary

* A stereo pair seen left-to-left and right-to-right gives the direct stereo effect; swapped, the reverse one.
* Height is x-parallax: $p = x_1 - x_2 = B f/(H - h)$; two points differ in height by
  $\\Delta h = H\\,\\Delta p/(p + \\Delta p) \\approx H\\,\\Delta p/b$; y-parallax checks the orientation.
* The stereoscope sends each eye to its photo; its mirrors are checked with a 40 cm line — two parallel lines mean
  a turn, lines at an angle a mirror out of true.
* A floating mark at the parallax of a surface rests on it: that is how heights are measured in the model.
* $V = (B/H)/(e/d)$: a long base or a short lens deepens the model; long lenses flatten it.
* Correlation finds parallaxes automatically where the ground is textured and seen twice; it fails on uniform or
  repetitive fields, in shadows, and where one photo cannot see.

Next: **08 · Interpretation** — reading what the photos show.
""", id="summary"),
]


def main():
    nb = notebook(CELLS, title="07 · The stereoscope and the stereo model")
    write(nb, PATH)
    print("wrote", PATH.relative_to(ROOT))


if __name__ == "__main__":
    main()
