"""Chapters 00–02 for issue 12: demos open on the guide's example, own results only after the task, the variant policy.

    python docs/tools/build_00_02_own_variant.py

Edits notebooks/00_start_here.ipynb, 01_flight_planning.ipynb and 02_photo_quality.ipynb in place, finding every
cell by its id (:mod:`aerophoto.nbtools`), so running it again gives the same notebooks:

* every demo opens on the guide's worked example, variant 00 — never on the student's own variant, whose
  results are the tasks' answers; the sliders cover every variant of the guide's scheme (f up to 1100 mm);
* the student's own results (chapter 00's footprint, chapter 01's plan table, overlaps and side allowance) are
  shown by :func:`aerophoto.demos.own.after` only once the task asking for them has passed (``checks.passed``);
* chapter 00 states the variant policy with :func:`aerophoto.tasks.ch00.scheme_table`;
* chapter 02's crab-limit figure marks no student's camera;
* answer cells carry the reference solution block (``_ref = aerophoto.tasks.answers(...)``).
"""

from __future__ import annotations

from pathlib import Path

from aerophoto import nbtools, tasks
from aerophoto.nbtools import code, md

ROOT = Path(__file__).resolve().parents[2]
NB = ROOT / "notebooks"


def reference_solution(nb, task_id: str) -> None:
    """The answer cell's template lines only (the notebooks are the student book; the teacher's copy is generated)."""
    nbtools.set_cell(nb, f"{task_id}-answer", tasks.get(task_id).template())


def set_or_insert(nb, after_id: str, cell) -> None:
    """Insert ``cell`` after ``after_id``, or if a cell with its id exists, set its source (re-runnable)."""
    try:
        nbtools.find_cell(nb, cell["id"])
    except KeyError:
        nbtools.insert_after(nb, after_id, cell)
        return
    nbtools.set_cell(nb, cell["id"], cell.source)


# =========================================================================== 00
def chapter_00() -> None:
    path = NB / "00_start_here.ipynb"
    nb = nbtools.read(path)
    nbtools.set_cell(nb, "title", """
# 00 · Start here: how this book works

*aerophoto* is a photogrammetry workbook for land-management and cadastre students. It follows the
course design (курсовая работа) of the Penza guide by Presnyakov & Tyuklenkova (2014), one notebook per
section of the guide, and replaces the contact prints, scissors and glue of the original with a
virtual test site photographed by an exact camera model.

**In this chapter you will**

1. run the setup cell and get *your own variant* from your record-book number (guide §1), and see what it
   means in real practice;
2. meet the elements of a central projection (центральная проекция): the projection centre $S$, the
   principal point $o$, the nadir point $n$ and the isocentre $c$;
3. move sliders and watch a tilted camera's footprint change;
4. solve a first small task and check it.
""")
    nbtools.set_cell(nb, "setup", """
RECORD_BOOK = None  # ← type your record-book number in quotes, e.g. "19-0457"
import aerophoto
from aerophoto.demos.footprint import FootprintDemo, footprint_model, FootprintView, own_footprint
v = aerophoto.setup(RECORD_BOOK)
""")
    nbtools.set_cell(nb, "how-to-read", """
## How to read this book

Every chapter has the same shape: **goals → theory → a live demonstration → the guide's worked example,
recomputed → your variant → a check → a summary.** The notebooks stay short because the computing lives
in the installed package `aerophoto`. When you want to see how a number was obtained, put two question
marks after a name and run the cell — for example `aerophoto.geometry.isocentre??` or
`FootprintDemo??` shows the source.

* Move a slider: the figure and the table beside it update in place. Every demo opens on **the guide's
  worked example (variant 00)**, and **Reset** returns there. A demo never opens on your own variant: its
  table would show the very results your tasks ask for. Set your own values with the sliders if you like.
* Every demo can also be driven from code, e.g. `demo.set(alpha_deg=10)`; that is handy when you need an
  exact value.
* Lecturers: [the lecture index](lectures.ipynb) lists every live demo and opens each chapter's lecture
  page — its demos only, without code (`voila notebooks/`).
* Your answers go in the cells marked *answer*; the cell under each one checks it and tells you what kind
  of mistake it sees (units, sign, rounding, wrong variant) without giving the answer away. Your own
  results (your plan, your camera's footprint) appear below a task once you have answered it.

The chapters of the book are listed below; notebook numbers follow the guide's sections (§2 → 01, §3 → 02, …), leaving room for later chapters.
""")
    set_or_insert(nb, "variant-table", md("""
## Large variants: what the guide's scheme gives, and the book's policy

The guide's scheme is linear in $i$, and for large $i$ it leaves real practice behind. The table groups the
hundred variants by tens: the inputs as the scheme gives them, the flying height $H = f\\,m$ only as a band of
whole kilometres (your own $H$ is task 00.1), and how the lens, the aircraft and the height compare with
real ones.
""", id="variant-policy"))
    set_or_insert(nb, "variant-policy", code("""
from aerophoto.tasks import ch00
ch00.scheme_table()
""", id="variant-scheme"))
    set_or_insert(nb, "variant-scheme", md("""
**Real practice.** Mapping cameras with the guide's 18×18 cm frame carried lenses of about 70–200 mm (the
guide's §3 names 100, 140 and 200 mm); the 23×23 cm survey cameras have lens cones of 88, 153, 210 and
305 mm. Longer lenses, up to about 610 mm (24 in), exist only on reconnaissance cameras; nothing longer is
made for a mapping frame. Survey aircraft fly at about 180–550 km/h — the An-2 (Ан-2) at about 200 km/h,
the purpose-built survey aircraft An-30 (Ан-30) at about 430 km/h — and survey flights stay below about
10 km. Above 20 km or so only high-altitude reconnaissance aircraft have flown.

**The book's policy.** The book uses the guide's scheme as it is, for every $i$ = 00–99, and never clamps a
value: $f = 100 + 10i$ mm (up to 1 090 mm), $1/m = 1/(12\\,000 + 100i)$ (down to 1:21 900),
$W = 200 + 10i$ km/h (up to 1 190 km/h), $L_x = 25 + i$ and $L_y = 30 + i$ km. Every formula of the course
holds for these numbers, so your tasks are computed and checked with them even where your variant is
"beyond real practice" — the table says where. The demos' sliders cover the whole range (f up to 1 100 mm,
W up to 1 200 km/h), and figures stay readable for the largest plans: chapter 01's overview of a plan with
dozens of strips becomes a schematic (every s-th strip and photo, as its title says).
""", id="variant-policy-notes"))
    set_or_insert(nb, "try-this", md("""
### One ray

On a vertical photo (горизонтальный снимок) over flat ground every point keeps the same scale,
$1/m = f/H$ (guide §2): the point $x$ from the principal point $o$ on the photo is the ground point
$X = x\\,m$ from the plumb point $N$ (40 mm on the photo is 480 m on the ground at 1:12 000), and its ray
leaves the vertical through $S$ at $\\theta = \\arctan(x/f)$. Move $x$ below: only the ray moves — the guide's camera, $f$ = 100 mm at 1:12 000,
flies at $H = f\\,m$ = 1200 m, and its 180 mm frame covers 2160 m of ground.
""", id="theory-ray"))
    set_or_insert(nb, "theory-ray", code("""
from aerophoto.demos.ray import RayDemo
ray = RayDemo()   # the guide's camera, variant 00: f = 100 mm, 1:12 000
ray
""", id="demo-ray"))
    nbtools.set_cell(nb, "demo-footprint", """
demo = FootprintDemo()   # the guide's worked example, variant 00: f = 100 mm, 1:12 000, α = 3°, λ = −60°
demo
""")
    reference_solution(nb, "task-00-1")
    set_or_insert(nb, "task-00-1-check", md("""
## Your own camera (after task 00.1)

Once task 00.1 has passed, the cell below opens the same demo on **your** camera and tilt — $f$, $1:m$,
$\\alpha$ and $\\lambda$ of your variant, the guide's numbers as they are, even where they leave real
practice. Its table then shows your $H$, $on$ and $oc$; until the task passes it says what to answer first.
""", id="own-footprint-text"))
    set_or_insert(nb, "own-footprint-text", code("""
from aerophoto import checks
own_footprint(v, checks.passed)
""", id="own-footprint"))
    nbtools.write(nb, path)


# =========================================================================== 01
def chapter_01() -> None:
    path = NB / "01_flight_planning.ipynb"
    nb = nbtools.read(path)
    _, cell = nbtools.find_cell(nb, "theory-overlaps")
    text = cell.source
    old = ("confirms both statements for your variant (footprints of neighbouring photos projected onto the\n"
           "lowest and the highest ground with `aerophoto.geometry.footprint`):")
    new = ("confirms both statements for the guide's example, variant 00 (footprints of neighbouring photos\n"
           "projected onto the lowest and the highest ground with `aerophoto.geometry.footprint`; the same check "
           "for\nyour own plan is at the end of the chapter, once task 01.1 has passed):")
    if old in text:
        nbtools.set_cell(nb, "theory-overlaps", text.replace(old, new))
    elif new not in text:
        raise SystemExit("01 [theory-overlaps]: the sentence to change is not there; update this script")
    nbtools.set_cell(nb, "theory-overlap-check", """
p00 = flight.guide_example()   # variant 00: f = 100 mm, 1:12 000, h = 30 m
for name, Z in (("lowest ground Z_min", p00.Zmin_m), ("highest ground Z_max", p00.Zmax_m)):
    fwd, side = flight.overlaps_at(p00, Z)
    print(f"{name:22s}  forward {fwd:6.2f} %   side {side:6.2f} %")
""")
    nbtools.set_cell(nb, "theory-demo", """
## Live demo: the plan of the area

The demo opens on **the guide's worked example** (variant 00). Left: the whole area $L_x \\times L_y$
(black) with the flight path flown back and forth (blue; the orange arrows show the direction of each
strip), every photo centre (dots) and the footprints of the first two strips. Right: a detail of the
lower-left corner — the footprints of the first photos (blue, darker where they overlap), their working
areas $B_x \\times B_y$ (green, dashed), which tile the area without gaps or overlaps, and the base $B_x$
and strip spacing $B_y$. The table beside the figure repeats all twelve steps of the guide.

The sliders cover every variant of the course (f up to 1 100 mm, 1:m up to 1:30 000, W up to 1 200 km/h,
areas up to 150 km). You may set your own variant's values — the table then shows your plan, which is
what the three tasks below ask you to compute, so it is better to do them first. A large plan (dozens of
strips) is drawn as a schematic: every s-th strip and photo, as the title says, so the strips stay apart.
""")
    nbtools.set_cell(nb, "demo-flight-plan", """
demo = FlightPlanDemo()   # the guide's worked example, variant 00
demo
""")
    for k in (1, 2, 3):
        reference_solution(nb, f"task-01-{k}")
    nbtools.set_cell(nb, "variant-theory", """
## Your variant's full table

The complete calculation for your variant, step by step as in the guide — the table that goes into your
report (пояснительная записка). Each result appears once the task that asks for it has passed in this
session (run the check cells above); until then its row says which task to answer first. It is computed
directly with the package from your exact inputs; the guide's rounding is applied only for display
(`flight.plan(v).table()` keeps full precision).
""")
    nbtools.set_cell(nb, "variant-table", """
from aerophoto import checks
from aerophoto.demos.flight_plan import own_plan_table, own_side_allowance, own_overlaps
own_plan_table(v, checks.passed)
""")
    nbtools.set_cell(nb, "variant-side-allowance", """
own_side_allowance(v, checks.passed)
""")
    set_or_insert(nb, "variant-side-allowance", md("""
**The overlaps of your plan on the ground**, measured with the camera model as for the guide's example
above: exactly $P_x$ forward on the lowest ground, and on the highest ground $p_x$ = 60 % forward but a
little less than $p_y$ sideways (the guide's $40\\,h/H$).
""", id="variant-overlaps-text"))
    set_or_insert(nb, "variant-overlaps-text", code("""
own_overlaps(v, checks.passed)
""", id="variant-overlaps"))
    nbtools.write(nb, path)


# =========================================================================== 02
def chapter_02() -> None:
    path = NB / "02_photo_quality.ipynb"
    nb = nbtools.read(path)
    _, cell = nbtools.find_cell(nb, "theory-criteria")
    text = cell.source
    old = ("200 mm — no more latitude than the guide grants its longest camera.")
    new = ("200 mm — no more latitude than the guide grants its longest camera, for every lens of the guide's scheme up\n"
           "to 1 090 mm, including those beyond the longest real lenses (≈ 610 mm).")
    if old in text:
        nbtools.set_cell(nb, "theory-criteria", text.replace(old, new))
    elif new not in text:
        raise SystemExit("02 [theory-criteria]: the sentence to change is not there; update this script")
    nbtools.set_cell(nb, "crab-limit-plot", """
ax = crab_limit_plot()
aerophoto.plots.static(ax.figure, alt="The largest allowed crab angle against the focal length from 50 to 1100 mm: "
                       "the guide's three values (5° at 100 mm, 7° at 140 mm, 10° at 200 mm) on the line f/20, held "
                       "at 5° below 100 mm and 10° above 200 mm; lenses beyond 610 mm, longer than any real one, "
                       "shaded")
""")
    _, cell = nbtools.find_cell(nb, "demo-theory")
    text = cell.source
    old = "The demo flies two strips of five photos"
    new = "The demo opens on the guide's camera ($f$ = 100 mm, variant 00) and flies two strips of five photos"
    if old in text and new not in text:
        nbtools.set_cell(nb, "demo-theory", text.replace(old, new, 1))
    nbtools.set_cell(nb, "demo-quality", """
demo = QualityDemo()   # the guide's camera, f = 100 mm (variant 00)
demo
""")
    for k in (1, 2):
        reference_solution(nb, f"task-02-{k}")
    nbtools.write(nb, path)


if __name__ == "__main__":
    chapter_00()
    chapter_01()
    chapter_02()
    print("chapters 00–02 written")
