"""Write notebooks/08_interpretation.ipynb (guide §9) from its cells (safe to re-run).

    python docs/tools/build_08_interpretation.py

Cells are identified by id; the notebook is written without outputs.
"""

from pathlib import Path

from aerophoto.nbtools import code, md, notebook, write

from lab_cells import answer_cell, check_cell  # noqa: E402  (same folder)

ROOT = Path(__file__).resolve().parents[2]
PATH = ROOT / "notebooks" / "08_interpretation.ipynb"

CELLS = [
    md("""
# 08 · Interpreting aerial photos (guide §9)

A photo is only useful once somebody has said what is on it. **Interpretation** (дешифрирование) is finding the
objects a photo shows, recognising them, and reading off their number and qualities — what a river is, which way
it flows, whether a wood is pine or spruce, how wide a road is. How well a photo lends itself to that is its
**interpretability** (дешифрируемость): it depends on the conditions the photo was taken in and on the physics of
the image.

**In this chapter you will**

1. meet the conditions of photographing that make a photo readable or not (guide §9), and watch each of them act
   on a colour photo of a new part of the virtual world, made for this chapter;
2. learn the **direct keys** (прямые дешифровочные признаки: shape, size, tone, shadow) and the **indirect** ones
   (косвенные), and see why colour and the near infrared help;
3. walk through the guide's **table 10** of topographic keys (топографическое дешифрирование), each row shown on
   the site where it applies;
4. look at the photo as an interpreter does — its tone, texture, pattern, shadows, shapes and sizes — at its full
   resolution and under a **magnifier** (лупа);
5. interpret **your own** photo: name six numbered objects, find the river's flow, tell pine from spruce, and
   measure the river's width by the photo's scale.
""", id="title"),
    code("""
RECORD_BOOK = None  # ← type your record-book number in quotes, e.g. "19-0457"
import aerophoto
from aerophoto import checks, guide, interpretation, labs, plots, spectral, tasks
from aerophoto.demos import interpretation as di, loupe
v = aerophoto.setup(RECORD_BOOK)
""", id="setup"),
    md("""
## What a photo shows, and what helps reading it

The guide's list of the **conditions of photographing** (условия фотографирования) that matter most is short and
practical: the season, the time of day, the moisture of the ground, the landscape's own contrast, haze, the tilt
of the camera, the exposure time and the aircraft's speed, and steep slopes. Summer photos taken in the hours
before noon are usually the most complete; snow, autumn's uniform colours, wet soil, smoke and a smeared image all
take detail away.
""", id="theory"),
    code("""
guide.ch08.conditions_table()
""", id="theory-conditions"),
    md("""
### How the book models them

Every condition acts on the photo through physics, not by hand-painted effects (`aerophoto.interpretation`):

* **Season** changes the spectra of the land covers: each class of the site is a linear mixture of typical spectra
  (grass, crowns, soil, water, snow …), and the mixture changes with the season — snow on open ground in winter,
  bare branches in spring, dull vegetation and wetter soil in autumn.
* **Sun**: objects cast shadows of length $L = h/\\tan e$ away from the sun (azimuth $A + 180°$); a slope is lit in
  proportion to the cosine of the sun's angle of incidence (Lambert's law), so steep slopes turned away darken.
* **Moisture** darkens soil at every wavelength and most in the short-wave infrared, where water absorbs (the soil
  model of chapter 13).
* **Haze**: the air below the aircraft scatters light into the camera and dims the ground's own light; every
  contrast shrinks, more in blue than in the infrared. The book takes the aerosol from the meteorological
  visibility $V$ (Koschmieder's law) and treats it as a scattering layer.
* **Image motion**: while the shutter is open the aircraft moves $W t$ over the ground, which is
  $\\delta = W t / m$ on a photo of scale $1:m$ — the same quantity that chapter 01 limits to 0.1 mm.
* **Tilt** changes the scale across the photo; the book's exact camera renders it.
""", id="theory-model"),
    code("""
interpretation.conditions_table()
""", id="theory-model-table"),
    md("""
### Tone and colour: reflectance in bands

The **tone** (тон изображения) of an object is its brightness in the band the film or sensor records. Underneath it
is the object's **reflectance** (коэффициент спектральной яркости, КСЯ): the share of the light it sends back, at
each wavelength. Green plants reflect little red light but a lot of near infrared; water absorbs the infrared
almost completely; asphalt is dark everywhere, gravel light. A **natural-colour** film records blue, green and red;
a **colour-infrared** (spectrozonal, спектрозональный) film records green, red and near infrared and shows them as
blue, green and red — vegetation turns red, water black, and conifers separate from broadleaf trees more clearly
than to the eye.
""", id="theory-tone"),
    code("""
plots.static(di.spectra_figure(),
             alt="Line chart of reflectance against wavelength for nine land-cover classes of the site, with the six "
                 "bands shaded. Water is low everywhere and falls to almost zero in the infrared; grass and the "
                 "three forests are low in the visible and high in the near infrared, deciduous highest, spruce "
                 "lowest; the raised bog lies between; asphalt is flat and dark; gravel rises gently and is "
                 "brighter than asphalt in every band.")
""", id="figure-spectra"),
    md("""
## Live: what makes a photo readable

Below is one patch of the chapter's site: the river with an island, a tributary joining it, a spruce wood, two
fields, and the floodplain meadow with haystacks, at 1:4 000, in natural colour and colour infrared. Change the conditions and
watch what you can still tell apart. The table gives the photo's RMS contrast, the shadow of a 20 m tree and the
image motion.
""", id="demo-theory"),
    code("""
conditions = di.ConditionsDemo()
conditions
""", id="demo-conditions"),
    md("""
**Try this.** (1) Winter: the fields, the meadow and the river vanish under one white — only the forests and the
roads' lines stay. (2) Lower the sun to 15°: the spruce crowns throw long shadows and the wood turns darker; the
haystacks' shadows stretch away from the sun. (3) Visibility 3 km: every colour greys and the RMS contrast drops.
(4) Wet the soil (θ): the ploughed field darkens and its furrows fade. (5) An exposure of 20 ms at 500 km/h
smears the photo by more than a pixel along the flight (the photo's x).
""", id="try-this"),
    md("""
## Direct and indirect keys

Objects are recognised by their **direct keys** (прямые признаки) — shape, size, tone and shadow — and, where those
are not enough, by **indirect keys** (косвенные): the links between objects. A bog is told partly by where it lies
(on a watershed, or along a valley floor), a pond by the dam on its stream, a meadow by its haystacks. The guide
calls the objects that point to something unseen **indicators** (индикаторы).
""", id="theory-keys"),
    code("""
guide.ch08.keys_table()
""", id="theory-keys-table"),
    md(r"""
### What the keys look like on a photo

The direct keys are read off the photo's image, and a practised interpreter names six things in it (guide §9's
shape, size, tone and shadow, with the two that come from many objects together):

* **tone** (тон) or colour — how bright an object is in the film's bands: water dark, gravel light, conifers darker
  than broadleaf trees;
* **texture** (текстура, зернистость) — the fine grain of small things too small to see one by one: the crowns of a
  stand, the clods of a ploughed field, grass tufts;
* **pattern** (рисунок) — a regular arrangement: the rows and **tramlines** (технологическая колея, the wheel tracks
  a sprayer drives in every 18 m or so) of a crop, the furrows of a ploughed field, a mown meadow's strips, the
  streaks of a current;
* **shadow** (тень) — the height and the shape in height: a haystack's round shadow, a house's sharp one, long thin
  shadows of spruce;
* **shape** (форма) and **size** (размер) — a field's straight edges, a road's even width with shoulders (обочины)
  and ditches (кюветы), a house's gabled roof whose two slopes take the light differently.

What shows depends on the scale: a key is seen only if it is larger than what the photo resolves. The table below
puts a few sizes on the worked example's photo (1:m of the example; one pixel of the 1024 across the 18 cm frame
is 0.18 mm): a road shows everywhere, tramlines and a house clearly, single crowns as a few pixels — so that pine
and spruce are told by their stands' tone and grain rather than crown by crown — and the rails only under a glass.
""", id="theory-marks"),
    code("""
di.detail_table(labs.ch08.example_setup().m)
""", id="theory-marks-table"),
    md(r"""
## How interpretation is organised (guide §9)

**By content** (по содержанию) the guide divides interpretation into two kinds. **Topographic** interpretation
(топографическое) finds every element of the landscape a topographic map shows and puts it into the map's symbols;
at small scales, for geographic maps and for dividing a region into types of terrain, it becomes **landscape**
interpretation (ландшафтное). **Special** interpretation (специальное, тематическое or **branch**, отраслевое) serves
one trade: geological, geomorphological, soil (chapter 13), hydrological, meteorological, military — or, for land
management, the farmland and the boundaries of land holdings; it usually shows the topographic elements as well, in
a simplified form.

**By method** (методы) the work is done in the **field** (полевой: on the ground with the photo in hand), from the
air (**aerovisual**, аэровизуальный: looking down from a slow aircraft or helicopter), in the **office**
(камеральный: from the photos alone, with keys and reference samples), or **combined** (комбинированный: office
work checked and completed in the field — the usual way). Within any method the **ways** (способы) of reading are
**visual** (by eye and stereoscope), **measuring** (масштабный: sizes and heights from the scale and the
parallaxes, as in task 08.3 and chapter 07) or both.

**The general order of work:** study the area on topographic maps and small-scale photos; fly reconnaissance
routes and observe from the air; survey sample areas on the ground to make **reference samples** (эталоны
дешифрирования); then interpret in the office, going back to the field for more samples where needed. The office
work itself runs: look through the strip of photos; view the stereo pairs under a stereoscope for the relief; analyse
the terrain; interpret and compare with the samples. Where the area is split among photos, the results are
**matched across the boundaries** of neighbouring working areas (сводка): the same object must get the same class
and the same characteristics on both sides, nothing may be lost at the seam, and an object added by measurement is
checked from two or three points that are sure on both photos.

**§9's three steps for the relief.** The guide's exercise starts from the relief: (1) study how the **tone**
depends on the **steepness and exposure of the slopes**; (2) find the links between the relief and the objects that
betray it — streams, gullies; (3) with both, look at the pair under the stereoscope. Step 1 is the Lambert law of
the conditions demo above: a slope facing the sun is brighter than level ground, one turned away darker, and the
steeper the slope the larger the difference — so on one photo the same grass can take any tone from dark to light.
""", id="theory-organisation"),
    code("""
import numpy as np
slope = np.linspace(0.0, 45.0, 46)
fig, ax = plots.new_axes(None, figsize=(7.5, 4.0))
for aspect, name in ((180.0, "facing the sun (south)"), (90.0, "east"), (270.0, "west"), (0.0, "turned away (north)")):
    ax.plot(slope, interpretation.slope_illumination(slope, aspect, 40.0, 180.0), label=name)
ax.set_xlabel("slope steepness, °")
ax.set_ylabel("brightness / level ground")
ax.set_title("Tone of a slope, sun 40° high in the south")
ax.legend()
plots.static(fig, alt="Brightness of a slope relative to level ground against its steepness from 0 to 45 degrees, "
                      "sun 40 degrees high in the south. South-facing slopes brighten to about 1.36 times level ground "
                      "at 45 degrees, east and west slopes (one curve) darken slowly to about 0.8, north-facing "
                      "slopes darken fast and reach the shadow level, about 0.35, at 40 degrees.")
""", id="figure-slope-tone"),
    md("""
## Table 10: the keys of topographic interpretation

The guide's table 10 (guide §9) lists, for rivers, lakes, ponds, bogs, forest, lowlands and meadows, arable land,
railways and roads, what to determine and by which key. Here it is as printed, with our English beside it.
""", id="example-theory"),
    code("""
guide.ch08.table_10()
""", id="example-table-10"),
    md("""
**Notes on the table.** The guide places the **shallows on the downstream side of islands**: true of the bars that
trail behind an island where the two currents meet again, but an island's head often gathers a bar too — so use it
together with the island's shape, which narrows downstream. A river's own width is no key to its flow (rivers
usually widen downstream; on the site it does). The scan's "технологии ческое" in §9's classification of
interpretation by content is read *топографическое*.

### Each key on the site

Move the row slider: the picture shows the place on the site where that row's key applies — a square of a 1:8 000
photo taken over that spot, seen through a magnifier (the bar gives the ground distance) — and the table says what
to look at. Compare the three forests at the same magnification: pine even and grey with round, convex crowns of one
height; spruce darker and mottled, with small pointed crowns, deep gaps and thin shadows; deciduous lighter, with
broad, lumpy crowns. Compare the railway's long straights and wide curve with the asphalt road's tight bends, and
look at the current below an island: streaks along the flow and foam where the two arms meet (table 10's speed of
flow). A row seen for the first time shows a quick, coarser picture at once and the full one as soon as the slider
rests. Table 10's row on the height and steepness of banks is the one the site does not show: its banks are low and
gentle, without the shadows the key reads.
""", id="example-key-theory"),
    code("""
key = di.KeyDemo()
key
""", id="demo-key"),
    md("""
### A worked example

A photo taken like yours (a different crop and conditions; nobody's variant), with its numbered marks, stands P
and Q, and the river's flow read with table 10's keys.
""", id="example-1-theory"),
    code("""
example = labs.ch08.example_photo()
plots.static(di.lab_figure(example), dpi=di.LAB_DPI, format="jpeg",
             alt="A colour aerial photo of the interpretation site, at its full resolution: fields with rows and "
                 "tramlines, forest stands, a village with red and grey roofs along a gravel road, the river with "
                 "two islands, a lake and a raised bog; six yellow numbered marks, two blue marks P and Q on two "
                 "forest stands, and two red marks A and B on opposite banks of the river.")
""", id="example-1"),
    code("""
labs.ch08.example_key()
""", id="example-1-key"),
    md("""
## Task 08.1 — name the numbered objects (graded)

Your photo is below: your own crop of the site, at your own scale, turned by your own swing κ, in your own light and
air. Six objects are numbered. Name each of them with one of the names of `labs.ch08.OBJECT_NAMES` (copy the
text exactly, e.g. `obj1 = "lake (озеро)"`):

* `obj1` … `obj6` — the names of objects 1 to 6.

Each name is graded on its own (half a point for each right one).

**Seeing the photo larger.** The photo below is drawn at its full resolution: 1024 pixels across the 18 cm frame,
one pixel 0.18 mm on the photo, about 1.5 m on the ground. Two ways to look closer:

* the **magnifier** below the photos (лупа): it shows any spot at ×3 to ×6, rendered afresh from the photo itself —
  the same camera, light and air — so that it shows finer detail than the screen's picture, as a glass over a print
  does: crowns, rows, wheel tracks, rails. Put it on a mark with *centre on*, or click on the photo;
* the browser: right-click the photo → *Open image in new tab* and zoom there, or zoom the page (Ctrl and +). This
  only enlarges the 1024 pixels: it helps the eye, but shows nothing the pixels do not hold.

The colour-infrared copy helps to tell water (black), forest (dark red) and fields apart.
""", id="task-08-1"),
    code("""
lab = tasks.inputs("task-08-1", v)
print(lab)
print("the names to choose from:")
for name in labs.ch08.OBJECT_NAMES:
    print("   ", repr(name))
""", id="task-08-1-data"),
    code("""
plots.static(di.lab_figure(lab), dpi=di.LAB_DPI, format="jpeg",
             alt="Your colour aerial photo of the interpretation site at its full resolution, with six numbered "
                 "yellow marks, two blue marks P and Q on two forest stands, and red marks A and B on the two banks "
                 "of the river.")
""", id="task-08-1-photo"),
    code("""
plots.static(di.lab_figure(lab, "colour-infrared film"), dpi=di.LAB_DPI, format="jpeg",
             alt="The same photo as colour infrared: vegetation red, forest dark red, water black, bare fields "
                 "grey-brown, with the same marks.")
""", id="task-08-1-cir"),
    md("""
### The magnifier (лупа)

Put the glass on each mark in turn (*centre on*), or click on the photo at the left; raise the power to ×5–×6 for
the stands P and Q. Read what the glass shows with table 10 and the six keys above: how bright, how grainy, what
pattern, what shadows, what shape and size. The table beside it gives the glass's field on the photo and on the
ground, and what one of its pixels covers on the ground.
""", id="demo-loupe-theory"),
    code("""
glass = loupe.LoupeDemo(v)
glass
""", id="demo-loupe"),
    answer_cell("task-08-1"),
    check_cell("task-08-1"),
    md("""
## Task 08.2 — which way does the river flow, and which wood is spruce? (graded)

On your photo:

* `flow` — the direction the river flows **on the photo**, one of `labs.ch08.FLOW_OPTIONS`
  (`"towards +x (right)"`, `"towards −x (left)"`, `"towards +y (up)"`, `"towards −y (down)"`); use the islands'
  shape and the tributary (table 10);
* `spruce` — which of the two stands marked P and Q is spruce: `"P"` or `"Q"` (the other is pine).
""", id="task-08-2"),
    answer_cell("task-08-2"),
    check_cell("task-08-2"),
    md("""
## Task 08.3 — the river's width by the scale (graded)

Marks A and B stand on the two banks of the river, across its flow. Their photo coordinates, read on your photo, are
in the table below (mm). The scale to use is **this photo's own**, `lab.m`, printed above the table (between
1:8 000 and 1:9 500) — not the 1:m of your variant in the banner at the top, which is the scale of the course's
flight (chapters 01–07), a different photo. Compute

* `width_m` — the river's width on the ground, $|AB| \\cdot m$, in metres (tolerance 5 %: the scale of a tilted
  photo of uneven ground is not quite $1:m$ everywhere).
""", id="task-08-3"),
    code("""
print(f"this photo's scale: 1:{lab.m:.0f}")
lab.marks_table().loc[["A", "B"]]
""", id="task-08-3-data"),
    answer_cell("task-08-3"),
    check_cell("task-08-3"),
    md("""
## Summary

* Interpretability depends on the conditions of photographing (guide §9): summer photos taken before noon, in
  clear air, of dry ground, with a short exposure are the most readable; snow, haze, wet soil and image motion
  ($\\delta = W t/m$) take detail away, and the sun's height sets the shadows ($L = h/\\tan e$).
* Objects are told by direct keys (shape, size, tone, shadow) and indirect ones (their links to other objects);
  on the photo they show as tone, texture, pattern, shadow, shape and size, each only where it is larger than what
  the photo resolves — a magnifier (лупа) brings out the finer ones.
* Table 10: shallow water is light and deep water dark; islands narrow downstream and tributaries meet a river at an
  acute angle pointing downstream; a pond is widest at its dam; raised bogs lie on watersheds, low bogs along
  valleys; pine is even and grey, spruce darker and mottled with pointed crowns, deciduous lighter; railways have
  long straights and wide curves, roads tight bends and ditches; asphalt is dark, gravel light.

**Sources of the spectral model** (`aerophoto.spectral.SOURCES`): the typical spectra of the USGS, ECOSTRESS and
ASTER spectral libraries, urban materials after Herold et al. (2004), mosses and bogs after Bubier et al. (1997),
snow after Wiscombe and Warren (1980), linear mixtures after Adams et al. (1986), soil after Stoner and
Baumgardner (1981), Bowers and Hanks (1965) and Lobell and Asner (2002), water absorption after Hale and Querry
(1973) and Kou et al. (1993), haze after Koschmieder (1924), Ångström (1929), Hansen and Travis (1974) and Bohren
(1987). The full list:
""", id="summary"),
    code("""
for source in spectral.SOURCES:
    print("•", source)
""", id="summary-sources"),
    md("""
Next: **09 · Plan correction**; the soil application of these spectra is chapter **13 · Soil mapping**.
""", id="summary-next"),
]


def main():
    nb = notebook(CELLS, title="08 · Interpreting aerial photos")
    write(nb, PATH)
    print("wrote", PATH.relative_to(ROOT))


if __name__ == "__main__":
    main()
