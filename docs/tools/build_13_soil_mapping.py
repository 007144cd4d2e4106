"""Write notebooks/13_soil_mapping.ipynb (chapter 13, guide §14) — safe to re-run.

    python docs/tools/build_13_soil_mapping.py

The notebook is the student book: answer cells hold the task's template lines only (docs/CONTRIBUTING.md,
"Graded tasks"); `aerophoto-course generate` adds the reference solution for nbgrader's source.

The notebook is rebuilt from the cells below; cells are identified by their ids, so the file a re-run
writes is the same as the one before (outputs are never stored).
"""

from pathlib import Path

from aerophoto import spectral
from aerophoto.nbtools import code, md, notebook, write

from lab_cells import answer_cell, check_cell  # noqa: E402  (the house's answer and check cells)

ROOT = Path(__file__).resolve().parents[2]
OUT = ROOT / "notebooks" / "13_soil_mapping.ipynb"

SOURCES_MD = "\n".join(f"{k}. {s}" for k, s in enumerate(spectral.SOURCES, 1))

CELLS = [
    md(r"""
# 13 · Aerial and space photos in soil mapping (guide §14)

A soil map (почвенная карта) tells a land manager which crop rotation a field can carry, where erosion
must be stopped and how much a hectare is worth. Photos make such maps cheaper and better — but a photo
shows only the very top of the soil, and usually through a cover of plants. Guide §14 explains what the
photographed brightness of a soil depends on, which **keys** (дешифровочные признаки) let an interpreter
read soils all the same, and how the work is organised.

**In this chapter you will**

1. learn the classes of soil maps by scale — and notice that the guide's list has gaps;
2. see, live, how **moisture** (влажность), **humus** (гумус) and **particle size** (размер частиц) change
   a soil's reflectance curve and its tone in a camera's bands;
3. reproduce the guide's statements about soil reflectance from a documented model;
4. meet the site's soil cover, laid out by the guide's **indirect keys** — slope, exposure, hollows,
   vegetation, the floodplain;
5. classify maps by scale, read a soil pit's curve, and do the first step of soil interpretation — the
   division into tone-homogeneous areas (контурное почвенное дешифрирование) — on your own patch of the
   site, and compare it with the field survey.
""", id="title"),
    code("""
RECORD_BOOK = None  # ← type your record-book number in quotes, e.g. "19-0457"
import aerophoto
import numpy as np
from aerophoto import guide, plots, soilmap, spectral, tasks
from aerophoto.demos.spectral_explorer import SpectralExplorerDemo, overlay_figure, plot_patch, plot_soil_facts, plot_soil_map
from aerophoto.site.soils import SOIL_CLASSES, soil_layer
v = aerophoto.setup(RECORD_BOOK)
""", id="setup"),
    md(r"""
## Soil interpretation and soil maps

Reading soils from photos (**soil interpretation**, почвенное дешифрирование) has two aims (guide §14):

* **soil mapping** (почвенно-картографическое): the types of soils and the boundaries between them, for
  special maps;
* **soil research** (почвенно-исследовательское): processes in the soil cover. Slow ones — erosion,
  salinisation, waterlogging, advancing sands — are followed on repeated surveys; fast or accidental ones —
  soil washed away in a flood, a field drying to ripeness for sowing, its moisture and temperature — on
  prompt ones.

Soil maps are classed by their scale. Land management (землеустройство) works mostly with large-scale
maps; intensive farming, anti-erosion, irrigation and drainage projects need detailed ones; medium-scale
maps serve the zoning of districts, small-scale ones the strategy of regions. Look at the ranges: the
guide says nothing about maps between 1:5000 and 1:10 000, between 1:25 000 and 1:50 000, or between
1:200 000 and 1:500 000. The book answers **"between classes"** there
(`guide.ch13.soil_map_scale_class`).
""", id="theory"),
    code("""
guide.ch13.scale_table()
""", id="theory-scales"),
    md(r"""
### What a soil's brightness depends on

A photo in the optical range records only the **upper horizon** (верхний горизонт) of the soil profile,
and most of the season the soil is hidden under plants — so soil interpretation is mostly **indirect**
(косвенное). Where the soil is bare, its tone depends on its **spectral reflectance** ρ(λ) (коэффициент
спектральной яркости, КСЯ). Guide §14 states:

* a **dry soil's curve** rises smoothly from 0.4 µm to 1.6–2.0 µm and falls gently towards 2.5 µm; its
  level is set by the mineral base, humus, iron oxides, water and the surface;
* a **wet soil** has dips where water absorbs sunlight, deepest at **1.45 µm and 1.95 µm**, and moisture
  changes the brightness strongly; visible and near-infrared photos together show the moisture;
* the integral brightness falls **linearly with humus** (and iron oxides) **up to 5 %**, then along a
  parabola; the **red** zone reacts most;
* **clods** (макроструктура) darken the surface: shadows, directional reflection, light trapped between
  them;
* the finer the **particles** (микроструктура), the brighter the soil — exponentially, most of all **below
  0.4 mm**.

The book's model (`aerophoto.spectral.soil_reflectance`) reproduces each statement with a factor taken from
the soil-physics literature; the sources are listed in the summary. The bands are those of the Landsat
Thematic Mapper (blue, green, red, near infrared, and two short-wave infrared bands at 1.6 and 2.2 µm) —
chosen, like every remote-sensing band, **between** the water-absorption dips.
""", id="theory-reflectance"),
    md(r"""
## Live: the spectral explorer

Left: the reflectance curve of a topsoil (black), the same soil dried (dashed), the bands of the chosen
camera (shaded) with the soil's value in each (red bars). Right: a patch of the site — the guide's example,
variant 00's patch — photographed bare in the camera's bands. The sliders set a leached chernozem's topsoil;
every other soil of the patch changes with it (wetter, more humus, finer), keeping its own differences.

* **θ (moisture), %** — volumetric moisture; **H (humus), %**; **d (particle size), mm**;
* **r (clods)** — clod roughness (0 harrowed … 0.15 fresh ploughing), and **e (sun elevation), °**: the
  clods' shadows grow as the sun sinks;
* **camera** — colour film, colour-infrared (spectrozonal, спектрозональная) film, or two Thematic Mapper
  composites.
""", id="demo-theory"),
    code("""
demo = SpectralExplorerDemo()
demo
""", id="demo-spectral"),
    md(r"""
**Try this.**

* Dry the soil (θ = 0), then wet it step by step: every band darkens, the dips at 1.45 and 1.95 µm deepen,
  and the short-wave infrared band at 2.2 µm loses the most.
* Set θ back to 18 % and move the humus from 0 to 15 %: the red bar falls fastest, and beyond 5 % each
  further per cent does less.
* Move d from 2 mm down to 0.02 mm: nothing happens until about 0.4 mm, then the soil brightens quickly.
* Set r = 0.15 and lower the sun to 10°: the same field turns darker — two fields of one soil can differ in
  tone, as the guide warns.
* `demo.set(camera="Thematic Mapper 5-4-3")` — which composite separates the floodplain from the chernozem
  best?
""", id="try-this"),
    md(r"""
## The guide's statements reproduced

§14 prints no table to recompute; its numbers are statements about curves (its figure 25 is missing from
the scan). The model, drawn against each of them — moisture curves of a loam with 3 % humus; the red and
near-infrared band values against humus and against particle size; and how much of the dry brightness
survives at 1.45 and 1.93 µm (water's strongest absorption in the model's data is at 1.93 µm — the guide's
"1.95" is the rounded position of the dip) and at 1.25 µm, where water hardly absorbs:
""", id="example-1-theory"),
    code("""
plots.static(plot_soil_facts(),
             alt="Four panels of the soil model. Top left: reflectance curves of a loam for moisture 0, 10, 20, "
                 "30 and 40 %: each wetter curve lies lower everywhere, with dips deepening at 1.45 and 1.95 µm. "
                 "Top right: red and near-infrared reflectance falling straight with humus up to 5 %, then "
                 "curving flat towards 15 %. Bottom left: red reflectance falling steeply as particles grow "
                 "from 0.02 to 0.4 mm and flat beyond. Bottom right: the share of dry brightness left falls with "
                 "moisture, fastest at 1.93 µm, then 1.45 µm, slowest at 1.25 µm.")
""", id="example-1"),
    md(r"""
## The site's soil cover and the indirect keys

The guide's **indirect keys** (косвенные признаки) are the soil-forming factors a photo shows: the
**relief** (рельеф: the steepness and **exposure** of slopes, hollows and rises), the **vegetation**
(растительность), the **parent rock** (почвообразующие породы, judged mostly by the relief) and **human
activity** (хозяйственная деятельность). The **direct keys** (прямые признаки) — tone (colour), texture,
size and shape of the contours — work only on bare ground, and even there tone alone misleads. The site's
soils are laid out by exactly these keys (`aerophoto.site.soils`): forest → grey forest soil, slopes over
about 1° (less where they face the sun) → eroded soil, closed hollows → gleyed soil, the floodplain →
alluvial meadow soil, the rest → leached chernozem.
""", id="soils-theory"),
    code("""
site_soils = soil_layer()
plots.static(plot_soil_map(site_soils),
             alt="Map of the 10 × 5 km site's soils: leached chernozem over most of it, grey forest soil in "
                 "the forests and on the high northern hills, orange bands of eroded soil on the slopes, a "
                 "light-blue strip of alluvial meadow soil along the river with dark-blue spots of gleyed soil "
                 "in hollows.")
""", id="soils-map"),
    md(r"""
The keys at work, class by class: the share of the site, the mean moisture, humus and particle size of the
topsoil, and the relief under it (`slope_deg`, and `hollow_m`: how far the ground lies below its
surroundings — positive in a hollow):
""", id="soils-keys-theory"),
    code("""
keys = site_soils.table().drop(columns="where")
keys["slope, °"] = [float(site_soils.slope_deg[site_soils.code == k].mean()) for k in SOIL_CLASSES]
keys["hollow, m"] = [float(site_soils.hollow_m[site_soils.code == k].mean()) for k in SOIL_CLASSES]
keys.round(2)
""", id="soils-keys"),
    md(r"""
The keys as the guide lists them, and the five steps of soil interpretation. The step this chapter
practises is the second one: the office interpreter first divides the image into areas homogeneous in
tone, texture and soil-forming factors, and only then names the soils — in the office where the keys
allow, otherwise in the field, checking each soil type at least three times.

The guide's office work is done on **contact prints** (контактные отпечатки), interpreting **every other photo** of
a strip (дешифрирование через снимок: with 60 % overlap the even, or the odd, photos cover the ground between them);
on **photo mosaics** (фотосхемы, chapter 05) where the landscape as a whole decides which soils to expect — the
landscape approach — and on **stereo mosaics** (стереофотосхемы) where the relief matters most. The finished
contours go onto the topographic or base land map at the map's scale, by computer or with projection instruments
that bring the photos to that scale.
""", id="keys-theory"),
    code("""
guide.ch13.keys_table()
""", id="keys"),
    code("""
guide.ch13.steps_table()
""", id="steps"),
    md(r"""
## Task 13.1 — which class of soil map? (graded)

Your photos are at 1:m (your variant). Three soil maps are made with them: one at **1 : 2m** (a photo mosaic
reduced twice), a district map at **1 : 10m** and a regional one at **1 : 40m** (their denominators are
in the table). Name the class of each as guide §14 does — one of `"detailed"`, `"large-scale"`,
`"medium-scale"`, `"small-scale"`, or `"between classes"` where the guide's ranges leave a gap. Type the
words yourself (as text in quotes).
""", id="task-13-1"),
    code("""
tasks.inputs("task-13-1", v)
""", id="task-13-1-data"),
    answer_cell("task-13-1"),
    check_cell("task-13-1"),
    md(r"""
## Task 13.2 — reading the pit's curve (graded)

A soil pit (почвенный разрез) was dug in your patch (the cross on the maps of task 13.3); its topsoil is in
the dictionary below. With `spectral.soil_reflectance(wavelengths, **pit)` (the keywords `moisture_pct`,
`humus_pct`, `particle_mm`, `parent`) and `spectral.soil_bands(**pit)` (the six band values, in the order
`spectral.BAND_NAMES`) find

* `rho_red` — the pit soil's reflectance in the red band (0.63–0.69 µm), to ±0.002;
* `wet_dry_145_pct` — its reflectance at 1.45 µm as a percentage of the same soil dried (θ = 0), to
  ±0.3 %;
* `band` — the name (from `spectral.BAND_NAMES`) of the band that keeps the smallest share of its dry
  brightness.

Leave the key `soil` out of the keywords: it names the class, not a model input.
""", id="task-13-2"),
    code("""
pit = tasks.inputs("task-13-2", v)
pit
""", id="task-13-2-data"),
    answer_cell("task-13-2"),
    check_cell("task-13-2"),
    md(r"""
## Task 13.3 — contour interpretation of your patch (graded)

Your patch is a 10 cm × 10 cm square of your photo, 0.1·m metres on the ground, in 200 × 200 cells. It
lies across the river's floodplain and the slopes above it, and it was photographed **bare** (in spring,
before the crops came up) on colour-infrared film: `patch.composite` is a (200, 200, 3) array of the
near-infrared, red and green bands as red, green and blue. The field survey's soil map is
`patch.soil_map` (class codes as in `SOIL_CLASSES`).

1. `k` — how many soil classes does the survey map of your patch hold?
2. Divide the composite into k tone-homogeneous areas: `labels = soilmap.segment_tones(patch.composite, k,
   seed=0)` (k-means clustering of the pixels' band values; the areas are numbered from the darkest).
3. Compare with the survey: `soilmap.contingency(labels, patch.soil_map)` counts, for each area (row), the
   cells of each soil (column). Give every area the soil that most of its cells have, and find
   `agreement_pct` — the share of all cells whose area's soil is their own soil, %, to ±0.05 %.
""", id="task-13-3"),
    code("""
patch = tasks.inputs("task-13-3", v)
plots.static(plot_patch(patch),
             alt="Your patch: left the colour-infrared composite of the bare soil in shades of brown, right the "
                 "field survey's soil map in the colours of the soil classes, with the soil pit marked by a "
                 "cross on both.")
""", id="task-13-3-data"),
    answer_cell("task-13-3"),
    check_cell("task-13-3"),
    md(r"""
**Think about it.** Which soils did the areas confuse? Look at the rows of your contingency table. On most
patches a grey forest soil and the wetter but finer alluvial soil share one tone (moisture darkens what fine
silt brightens), the gleyed soil of a hollow hides among the dark chernozem (humus and water darken alike),
and the chernozem itself splits into two areas where its moisture varies. That is why the guide calls tone
alone an unreliable key, adds the indirect keys — the floodplain, the hollows, the forest — and sends the
interpreter to the field, with routes through every doubtful contour.
""", id="task-13-3-note"),
    md(r"""
## Space and scanner images, and the overlay technique (guide §14)

**Space photos** (космические фотоснимки) change the balance of the keys. Against them: a coarser **resolution**
(разрешение) takes away the shape, size and texture of the plants that are the best indicator of a soil, and the
much smaller ratio of base to height, with the coarser image, blunts the **stereo** view — a height is read from a
parallax as $\Delta h = H\,\Delta p/b$ on the photo, so at the same $\Delta p$ a pair with a ten times smaller $b/H$
hides relief ten times higher, and the micro-relief that points to soils (hollows, low ridges) is lost. For them: one
image covers a large region under the same light and season, so brightness can be compared from one end to the
other; seen from that height the vegetation masks the ground less, and the image's own blur generalises the
brightness into areas of soils that differ in reflectance. **Scanner images** (сканерные изображения) resolve even
less than photos (television frames likewise), but a photometric scanner measures the brightness in its band more
selectively and more exactly than film: with the band chosen well (chapter 13's spectral explorer), reading soils
from brightness becomes more reliable.

**The overlay technique** (the Delft training centre's method, for complex soil cover or a beginner): instead of
drawing the soil contours at once, put two or three **transparent sheets** over the photo and on each outline, in
its own colour, the areas of one group of keys — say, tone on the first, relief elements (hollows, slopes, the
floodplain) on the second, vegetation or land use on the third. Laid together, the sheets cut the photo into areas
with different *combinations* of direct and indirect keys; those combined areas are the candidate soil contours
(контурное почвенное дешифрирование) — the same idea as task 13.3's tone areas, with the indirect keys as more
layers. Sure contours are then drawn in solid lines, doubtful ones dashed, and the field routes go through the
dashed ones.

The figure does it on a 1.6 km square of the site's bare soil (not a task's patch). Sheet 1 holds four tone areas
of the colour-infrared photo (k-means, as in task 13.3, on the photo smoothed over 20 m, since an interpreter
outlines areas, not specks); sheet 2 the relief read from the stereo model — level ground, slopes steeper than 1°,
closed hollows; sheet 3 the vegetation and land use — arable land, forest, meadow, water. Laid together, the
sheets cut the square into pieces of one combination of keys (`aerophoto.soilmap.overlay`). A piece is drawn
**solid** where its combination is the usual one within its tone area (at least 70 % of that area has it: the keys
agree) and **dashed** where it is not — the tone says one thing, the relief or the cover another. Compare the
contours with the field survey's soil map under them: the solid ones follow soil boundaries the tone alone misses
(the slopes, the floodplain's edge), and most dashed ones lie where two soils meet.
""", id="space-overlay"),
    code("""
plots.static(overlay_figure(),
             alt="Six panels of one square of bare soil. The colour-infrared photo in browns; sheet 1 with orange "
                 "outlines of four tone areas; sheet 2 with blue outlines of level ground, slopes and hollows; "
                 "sheet 3 with green outlines of arable land, forest, meadow and water along the river; the three "
                 "sheets laid together over the photo; and the field survey's soil map in the soil classes' colours "
                 "with the combined contours in black, solid where the keys agree and dashed where they do not.")
""", id="space-overlay-figure"),
    md(r"""
## Summary

* Soil maps are **detailed** (1:5000 and larger), **large-scale** (1:10 000–1:25 000), **medium-scale**
  (1:50 000–1:200 000) or **small-scale** (1:500 000 and smaller); the guide leaves the scales between these
  ranges unnamed.
* A bare soil's reflectance rises from the visible to 1.6–2.0 µm; **moisture** darkens it everywhere and
  digs the water dips at 1.45 and 1.95 µm; **humus** darkens it linearly to about 5 %, then less, most in
  the red; **finer particles** (below 0.4 mm) and smoother surfaces brighten it.
* Because moisture, humus, clods and the sun all move the tone, soils are read mostly by **indirect keys** —
  relief, vegetation, parent rock, land use — and the office interpretation begins by dividing the image into
  tone-homogeneous areas, which the field survey then names and checks.

**Sources of the spectral model** (`aerophoto.spectral.SOURCES`):

""" + SOURCES_MD + r"""

Next: **14 · Accuracy of phototriangulation**.
""", id="summary"),
]

if __name__ == "__main__":
    print("wrote", write(notebook(CELLS), OUT))
