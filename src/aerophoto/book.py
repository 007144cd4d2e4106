"""The notebooks' one setup call: style, live figures, installation check, variant.

Every chapter starts with::

    RECORD_BOOK = None          # ← type your record-book number, e.g. "19-0457"
    import aerophoto
    v = aerophoto.setup(RECORD_BOOK)

``setup`` applies the book's plotting style, switches matplotlib to the live
widget backend (ipympl), checks that the installed packages are the ones the
book needs, and returns the student's :class:`~aerophoto.variants.Variant`.

Typing the number once is enough: ``setup`` remembers the last number given
(in ``~/.aerophoto/student.json``, or ``$AEROPHOTO_HOME/student.json``) and
uses it in chapters whose first cell is left at ``None``.  The environment
variable ``AEROPHOTO_RECORD_BOOK`` overrides both (used by tests).  With no
number anywhere, the book shows the guide's own worked example, variant 00.
"""

from __future__ import annotations

import html
import json
import os
import sys
from dataclasses import KW_ONLY, dataclass
from importlib import metadata
from pathlib import Path

from . import __version__
from .plots import register_table_display, use_style
from .tables import LINK_CSS
from .variants import Variant, variant, variant_for_index

__all__ = ["setup", "check_installation", "remembered_record_book", "remember_record_book", "state_dir",
           "remembered_language", "remember_language", "GLOSSARY_PAGE", "glossary_markdown",
           "Demo", "Chapter", "CHAPTERS", "LECTURE_INDEX", "LECTURES_DIR", "chapter", "chapter_table_markdown",
           "lecture_table_markdown", "lecture_page", "lecture_notebook", "sync_generated", "in_browser",
           "BROWSER_NOTE"]

# =========================================================================== the chapter registry
@dataclass(frozen=True)
class Demo:
    """One live demonstration of a chapter (what the lecture index, the browser tests and benchmarks use).

    Attributes
    ----------
    cell : str
        Id of the notebook cell that displays the demo (``demo-…``).
    cls : str
        The LiveDemo class, ``aerophoto.demos.<module>.<Class>``.
    name : str
        Its name in the lecture index ("Camera footprint — o, n, c").
    move : str
        What a lecturer moves, in order.
    sees : str
        What the class sees.
    sliders : tuple of (label, key)
        The headline sliders (their exact labels, "f, mm") and the key that moves
        each by a visible amount in the browser tests (``ArrowRight`` = one step,
        ``PageUp`` = five).
    timed : str
        The slider the browser benchmark times (default: the first headline slider).
    nth : int
        In Voilà (no cell ids): which of the demos carrying these sliders.
    """

    cell: str
    cls: str
    name: str
    move: str
    sees: str
    sliders: tuple = ()
    timed: str = ""
    nth: int = 0

    @property
    def timed_slider(self) -> str:
        return self.timed or self.sliders[0][0]


@dataclass(frozen=True)
class Chapter:
    """One notebook of the book, and the one key to everything of it: the chapter's number ``NN``.

    A maintainer finds chapter ``NN``'s parts from ``NN`` alone: the notebook ``notebooks/NN_slug.ipynb``, the guide's
    tables ``aerophoto.guide.chNN``, the graded tasks
    ``aerophoto.tasks.chNN`` and the lab world ``aerophoto.labs.chNN``.  Only the demos are named by topic (one
    demo module may serve two chapters: :mod:`aerophoto.demos.reduction` is chapters 06 and 12), so the registry
    lists them (:attr:`demo_modules`).  ``python -m aerophoto.book NN`` prints the lot.

    Attributes
    ----------
    number : str
        The notebook's number, ``"03"`` (the guide's §4 → 03, leaving room for later chapters).
    slug : str
        The rest of the file name, ``"relief_displacement"``.
    title, title_ru : str
        The topic in English and the guide's Russian term.
    demos : tuple of :class:`Demo`
        The live demos.
    section : int or None
        The section of the course-design guide the chapter is built from (``4`` for §4), or None.
    article : str or None
        The article it is built from (``"001"``, the seeds' numbering), or None.  Exactly one of ``section``
        and ``article`` is given.
    tables : bool
        Whether the source prints tables the book transcribes (then ``aerophoto.guide.chNN`` holds them);
        False for chapter 00 (guide §1 prints none).
    views : tuple of str
        Demo modules (``aerophoto.demos.<name>``) with static figures or tools the chapter uses besides its
        live demos' modules, e.g. ``("measure",)``.
    """

    number: str
    slug: str
    title: str
    title_ru: str
    demos: tuple = ()
    _: KW_ONLY
    section: int | None = None
    article: str | None = None
    tables: bool = True
    views: tuple = ()

    def __post_init__(self):
        if (self.section is None) == (self.article is None):
            raise ValueError(f"chapter {self.number}: section = {self.section!r}, article = {self.article!r}; "
                             "give exactly one")

    @property
    def name(self) -> str:
        return f"{self.number}_{self.slug}"

    @property
    def notebook(self) -> str:
        return f"{self.name}.ipynb"

    @property
    def source(self) -> str:
        """What the chapter is built from, as the book prints it: ``"guide §4"`` or ``"article 001"``."""
        return f"guide §{self.section}" if self.section is not None else f"article {self.article}"

    @property
    def guide_module(self) -> str | None:
        """The module of the source's printed tables, ``"aerophoto.guide.chNN"``; None if it prints none."""
        return f"aerophoto.guide.ch{self.number}" if self.tables else None

    @property
    def tasks_module(self) -> str:
        """The module of the chapter's graded tasks, ``"aerophoto.tasks.chNN"``."""
        return f"aerophoto.tasks.ch{self.number}"

    @property
    def lab_module(self) -> str | None:
        """The module of the chapter's lab world, ``"aerophoto.labs.chNN"``; None for a chapter whose inputs come
        with its tasks (no lab world of its own: 00, 01, 12, 14, 17)."""
        from . import labs

        return f"aerophoto.labs.ch{self.number}" if f"ch{self.number}" in labs.chapter_modules() else None

    @property
    def demo_modules(self) -> tuple:
        """The demo modules the chapter uses: its live demos' modules, then :attr:`views`, each once."""
        names = [d.cls.rsplit(".", 1)[0] for d in self.demos] + [f"aerophoto.demos.{v}" for v in self.views]
        return tuple(dict.fromkeys(names))

    def key_text(self) -> str:
        """The chapter's key as lines of text: what ``python -m aerophoto.book NN`` prints."""
        rows = [("notebook", f"notebooks/{self.notebook}"), ("source", self.source), ("guide module", self.guide_module or "— (the source prints no tables)"),
                ("tasks module", self.tasks_module), ("lab module", self.lab_module or "— (the inputs come with the tasks)"),
                ("demo modules", ", ".join(self.demo_modules) or "—")]
        head = f"chapter {self.number} · {self.title} ({self.source})"
        return "\n".join([head, *(f"  {k:<13}{v}" for k, v in rows)])


_F = ("f, mm", "PageUp")  # focal length: five steps up from the chapter's start
_M = ("m (scale 1:m)", "PageUp")  # scale denominator: five steps up

CHAPTERS = (
    Chapter("00", "start_here", "start here: your variant, central projection",
            "задание; центральная проекция", section=1, tables=False, demos=(
                # the cheapest live figure of the book (one blitted line): also the browser benchmark's floor
                Demo("demo-ray", "aerophoto.demos.ray.RayDemo", "One ray of a vertical photo", "x",
                     "the ray from S turns and its ground point X = x·m slides along the footprint: the scale "
                     "1:m = f:H of a vertical photo", (("x, mm", "ArrowRight"),)),
                Demo("demo-footprint", "aerophoto.demos.footprint.FootprintDemo", "Camera footprint — o, n, c",
                     "α (tilt), then f and m (scale 1:m)",
                     "the footprint turns from a square into a trapezoid; n and c leave o along the principal "
                     "vertical; with the scale fixed, a longer lens flies higher but covers the same ground",
                     (_F, _M, ("α, °", "ArrowRight")), timed="α, °"),
            )),
    Chapter("01", "flight_planning", "planning the aerial survey", "расчёт параметров аэросъёмки", section=2, demos=(
        Demo("demo-flight-plan", "aerophoto.demos.flight_plan.FlightPlanDemo", "Live survey plan", "m, relief h, then f and W",
             "strips and photos multiply as the scale grows or the relief rises; a faster aircraft shortens the "
             "flight and the admissible exposure", (_F, _M, ("px, %", "ArrowRight")), timed="f, mm"),
    )),
    Chapter("02", "photo_quality", "judging the photos' quality", "оценка качества материалов", section=3, demos=(
        Demo("demo-quality", "aerophoto.demos.quality.QualityDemo", "Rough mosaic you can break", "crab φ, α max, ΔH, bend, overlaps",
             "an imperfection past its tolerance turns its print, pair or strip vermillion and changes the verdict",
             (_F, ("α max, °", "ArrowRight"), ("crab φ, °", "ArrowRight")), timed="α max, °"),
    )),
    Chapter("03", "relief_displacement", "relief displacement", "смещение точек за рельеф",
            section=4, views=("measure",), demos=(
        Demo("demo-relief", "aerophoto.demos.displacement.ReliefDemo", "Displacement explorer, relief", "relief ±h, then α and f",
             "arrows radiate from the nadir n — outwards for hills, inwards for the valley; a longer lens at the "
             # relief by PageUp (25 m): with the arrows at a fixed ×2 one 5 m step is a sub-pixel change at f = 150 mm
             "same scale shortens them", (_F, _M, ("α, °", "ArrowRight"), ("relief ±h, m", "PageUp")),
             timed="relief ±h, m"),
    )),
    Chapter("04", "tilt_displacement", "tilt displacement", "смещения за угол наклона",
            section=5, views=("measure",), demos=(
        # m is no headline here: over flat ground the tilt displacement on the photo does not depend on m
        Demo("demo-tilt", "aerophoto.demos.displacement.TiltDemo", "Displacement explorer, tilt", "α, then λ and f",
             "arrows radiate from the isocentre c; points on the isoline stay put; the guide's approximate "
             "formula (orange) parts from the exact displacement (blue) as α grows",
             (_F, ("α, °", "ArrowRight"), ("λ, °", "ArrowRight")), timed="α, °"),
    )),
    Chapter("05", "fotoschema", "the single-strip photo mosaic", "одномаршрутная фотосхема", section=6, demos=(
        Demo("demo-fotoschema", "aerophoto.demos.fotoschema.FotoschemaDemo", "Live single-strip mosaic",
             "relief h, α max, then f and p_x",
             "cut-outs and duplicates appear along the cuts; a longer lens at the same scale shrinks the mismatches",
             (_F, _M, ("α max, °", "ArrowRight")), timed="α max, °"),
    )),
    Chapter("06", "strip_triangulation", "strip phototriangulation and its reduction",
            "фототриангуляционный ряд", section=7, demos=(
                Demo("demo-reduction", "aerophoto.demos.reduction.ReductionDemo", "Reduction explorer",
                     "q (free-strip scale), pricking error, central centre",
                     "k follows 1/q and the reduction arrows grow while the control residuals stay; pricking errors "
                     "grow the error triangles",
                     (_F, ("m (photo 1:m)", "PageUp"), ("α max, °", "ArrowRight")), timed="α max, °"),
            )),
    Chapter("07", "stereoscope", "the stereoscope and the stereo model: parallax, heights, the floating "
            "mark", "линзово-зеркальный стереоскоп; изучение стереомодели",
            section=8, views=("stereo_figures",), demos=(
                Demo("demo-floating-mark", "aerophoto.demos.stereo.FloatingMarkDemo", "The floating mark on an anaglyph",
                     "p (the parallax bar's drum), then x, y onto a roof, then the area",
                     "through red–cyan glasses the two crosses fuse into one mark that rises with p; at the parallax "
                     "of a roof or a tree top it rests on it and the table reads its height",
                     (("p, mm", "PageUp"), ("x, mm", "PageUp")), timed="p, mm"),
                Demo("demo-base-height", "aerophoto.demos.stereo.BaseHeightDemo", "Base, height and focal length",
                     "B, then H and f together",
                     "a longer base or a lower flight gives every height more parallax and a taller model; a longer "
                     "lens at the same scale flattens it",
                     (("B, m", "PageUp"), ("f, mm", "PageUp")), timed="B, m"),
            )),
    Chapter("08", "interpretation", "interpreting aerial photos: conditions, keys, table 10",
            "дешифрирование аэроснимков", section=9, demos=(
                Demo("demo-conditions", "aerophoto.demos.interpretation.ConditionsDemo",
                     "What makes a photo readable", "season, then e (sun elevation) and V (visibility), then θ and t",
                     "snow hides the fields; a low sun lengthens the shadows; haze greys the colours and flattens the "
                     "contrast; wet soil darkens; a long exposure smears the photo along the flight",
                     (("e (sun elevation), °", "PageDown"), ("θ (soil moisture), %", "PageUp")),
                     timed="e (sun elevation), °"),
                Demo("demo-key", "aerophoto.demos.interpretation.KeyDemo", "Table 10 as an interactive key",
                     "table 10 row, then the film",
                     "each row of table 10 shows the place on the site where its key applies: islands and the "
                     "tributary give the flow, tone and crowns tell pine from spruce, curvature a railway from a road",
                     (("table 10 row", "ArrowRight"),), timed="table 10 row"),
                Demo("demo-loupe", "aerophoto.demos.loupe.LoupeDemo", "A magnifier on the photo",
                     "the mark to centre on, then the power, then x and y (or a click on the photo)",
                     "under the glass the marks of table 10 come out: pine's round crowns of one height against "
                     "spruce's small dark ones, a field's rows and tramlines, a road's shoulders and ditches, the "
                     "rails on the ballast",
                     (("power, ×", "ArrowLeft"), ("x (glass centre), mm", "PageUp")),
                     timed="x (glass centre), mm"),
            )),
    Chapter("09", "plan_correction", "correcting a plan by mutual projective grids",
            "корректировка плана методом взаимно-проектных сеток", section=10, demos=(
                Demo("demo-plan-correction", "aerophoto.demos.plan_correction.PlanCorrectionDemo",
                     "Plan correction by mutual projective grids", "α, then n and the grid method, then the spread",
                     "with central directions the carried changes sit on the truth and improve as n grows; with "
                     "proportional division they stay off however fine the grid",
                     (("α, °", "PageUp"), ("n (cells per side)", "ArrowRight"), ("spread of 1–4, %", "PageDown")),
                     timed="n (cells per side)"),
            )),
    Chapter("10", "ground_control", "ground control: design, marking and resection",
            "проект планово-высотной привязки", section=11, demos=(
                Demo("demo-control-design", "aerophoto.demos.control.ControlDesignDemo", "Design of control on a block",
                     "m_ε and the allowed error, then the photo scale",
                     "Zhukov's spacing sets how many bases apart the rows of control go; a smaller scale or poorer "
                     "directions crowd them, down to dense control",
                     (("m_ε, ′", "PageUp"), ("m (photo 1:m)", "PageUp"), ("strips", "ArrowRight")), timed="m_ε, ′"),
                Demo("demo-resection", "aerophoto.demos.control.ResectionDemo", "Resection and the danger circle",
                     "move the station towards the circle through I, II, III",
                     "the cloud of stations resected under angle errors stretches near the danger circle",
                     (("P north, m", "PageUp"), ("P east, m", "PageUp")), timed="P north, m"),
            )),
    Chapter("11", "rectification", "rectifying photos of flat ground", "фототрансформирование", section=12, demos=(
        Demo("demo-transformer", "aerophoto.demos.rectification.TransformerDemo", "The photo transformer, step by step",
             "step, then α and the pricking error",
             "centre, scale, hh, turn, tilt: the misses of the four points fall below 0.4 mm in two cycles",
             (("step", "ArrowRight"), ("α, °", "PageUp")), timed="step"),
    )),
    Chapter("12", "phototriangulation", "phototriangulation: control spacing and reduction",
            "фототриангуляция", section=13, demos=(
                Demo("demo-reduction", "aerophoto.demos.reduction.ReductionDemo", "Reduction explorer (tilted photos)",
                     "α max, q, pricking error",
                     "the same explorer with tilted photos: the reduced strip against the control points",
                     (_F, ("m (photo 1:m)", "PageUp"), ("α max, °", "ArrowRight")), timed="α max, °"),
            )),
    Chapter("13", "soil_mapping", "aerial and space photos in soil mapping: soil reflectance, "
            "soil keys and contour interpretation", "применение аэро- и космических снимков при почвенном "
            "картографировании", section=14, demos=(
                Demo("demo-spectral", "aerophoto.demos.spectral_explorer.SpectralExplorerDemo",
                     "Spectral explorer — soil reflectance and a band composite",
                     "θ (moisture) up, then H (humus), then d (particle size) below 0.4 mm",
                     "wetting darkens every band and deepens the water dips at 1.45 and 1.95 µm; humus darkens "
                     "the red band most and little beyond 5 %; fine particles brighten the soil; the patch "
                     "follows",
                     (("θ (moisture), %", "PageUp"), ("H (humus), %", "PageUp")), timed="θ (moisture), %"),
            )),
    Chapter("14", "triangulation_accuracy", "accuracy of phototriangulation: error accumulation and "
            "control spacing", "точность фототриангуляционных сетей", article="001", views=("bundle_views",), demos=(
                Demo("demo-block-errors", "aerophoto.demos.block_accuracy.BlockErrorDemo",
                     "Block error map — control layout and σ", "n (control spacing), then K strips and σ",
                     "the predicted errors swell between the control rows, faster in height; more strips stiffen "
                     "the block; σ brightens the whole map",
                     (("σ, µm", "PageUp"), ("K, strips", "ArrowRight")), timed="σ, µm"),
            )),
    Chapter("15", "block_adjustment", "bundle block adjustment: locating field points in the "
            "mountains", "блочная фототриангуляция по методу связок", article="002", views=("bundle_views",), demos=(
                Demo("demo-block-adjustment", "aerophoto.demos.block_adjustment_live.BlockAdjustmentDemo",
                     "Bundle block adjustment — control, σ and a blunder", "σ up, then the blunder off and on, "
                     "then the control layout", "the same blunder stands out at a few µm and passes unseen at 30 µm; "
                     "fewer control points swell the ellipses and the check points' errors, most in height",
                     (("σ, µm", "PageUp"), ("blunder, mm", "PageUp")), timed="σ, µm"),
            )),
    Chapter("16", "dem_contours", "contours from a DEM: regular grid, structural lines, Lysenko's "
            "densification accuracy", "рисовка горизонталей по точкам ЦМР", article="000", demos=(
                Demo("demo-contours", "aerophoto.demos.dem_contours.ContourDemo", "Contours from a DEM against the truth",
                     "m_z to 0, then d up to 150 m, then the structural lines on",
                     "with error-free nodes a 30 m grid follows the site's hills to millimetres; coarse grids cut "
                     "the bends and the structural lines win part back; node errors make the contours wriggle",
                     (("d, m", "PageUp"), ("m_z, m", "PageUp")), timed="d, m"),
            )),
    Chapter("17", "map_update_errors", "the error budget of map updating", "анализ плановой точности "
            "при обновлении карт", article="003", demos=(
                Demo("demo-budget", "aerophoto.demos.error_budget.BudgetDemo", "The error budget of map updating",
                     "the DEM stage, then 1:M_c and P, then the map scale",
                     "the instruction's transfer and DEM tolerances dominate; a real DEM brings the map to 0.40 mm, "
                     "the 40 µm transfer rule within 0.4 mm; the photo scale and the scan barely matter",
                     (("1:M_c (photo)", "PageUp"), ("P, µm", "PageUp")), timed="1:M_c (photo)"),
            )),
)
"""Every chapter of the book, in order: the one registry (aerophoto.__init__, the lecture index, the README and
chapter 00's tables, the browser tests and the benchmarks read it)."""

LECTURE_INDEX = "lectures.ipynb"


def chapter(name_or_number: str | int) -> Chapter:
    """A chapter by number (``"03"``, ``"3"`` or ``3``), name (``"03_relief_displacement"``) or notebook file name.

    The chapter carries its key: ``chapter("09").guide_module`` is ``"aerophoto.guide.ch09"``, and so on
    (:class:`Chapter`).
    """
    key = str(name_or_number).removesuffix(".ipynb")
    if key.isdigit() and len(key) <= 2:
        key = f"{int(key):02d}"
    for c in CHAPTERS:
        if key in (c.number, c.name):
            return c
    raise ValueError(f"no chapter {name_or_number!r}; chapters: {[c.name for c in CHAPTERS]}")


def _title(c: Chapter) -> str:
    """The chapter's topic with a capital, in the language in use (:mod:`aerophoto.i18n.chapters`)."""
    from .i18n import t

    title = t(c.title)
    return title[0].upper() + title[1:]


def _source(c: Chapter) -> str:
    """:attr:`Chapter.source` in the language in use: ``"guide §4"``, ``"руководство, §4"``."""
    from .i18n import t

    if c.section is not None:
        return t("guide §{section}", section=c.section)
    return t("article {article}", article=c.article)


#: the generated tables' header rows, per language
_HEADS = {
    "chapters": {"en": "| notebook | source | topic | live demos |",
                 "ru": "| тетрадь | источник | тема | интерактивные демонстрации |"},
    "demos": {"en": "| lecture page | demo | move | what the class sees |",
              "ru": "| лекционная страница | демонстрация | что двигать | что видит аудитория |"},
}
#: the headings of the generated cells (chapter 00's ``chapters``, the lecture index's ``demos``), per language
_HEADINGS = {"chapters": {"en": "## The chapters", "ru": "## Главы"},
             "demos": {"en": "## The demonstrations", "ru": "## Демонстрации"}}


def chapter_table_markdown(*, prefix: str = "", lang: str = "en") -> str:
    """The chapter table of the README (``prefix="notebooks/"``) and of chapter 00 (generated; a test keeps both current).

    ``lang="ru"``: the Russian table of chapter 00's Russian text (``notebooks/ru/00_start_here.md``), its topics,
    demo names and sources from the catalogue (:mod:`aerophoto.i18n.chapters`; a text without Russian stays English).
    """
    from .i18n import language, t

    lines = [_HEADS["chapters"][lang], "|---|---|---|---|"]
    with language(lang):
        for c in CHAPTERS:
            demos = "; ".join(t(d.name) for d in c.demos) or "—"
            topic = f"{c.title} ({c.title_ru})" if lang == "en" else t(c.title)
            lines.append(f"| [`{c.name}`]({prefix}{c.notebook}) | {_source(c)} | {topic} | {demos} |")
    return "\n".join(lines)


def lecture_table_markdown(*, lang: str = "en") -> str:
    """The lecture index's table of demos (generated; a test keeps ``notebooks/lectures.ipynb`` current).

    Each chapter links its lecture page (``lectures/NN_slug.ipynb``: the demos only, the guide's example) and,
    beside it, the whole chapter.  ``lang="ru"``: the Russian table of ``notebooks/ru/lectures.md``.
    """
    from .i18n import language, t

    lines = [_HEADS["demos"][lang], "|---|---|---|---|"]
    with language(lang):
        for c in CHAPTERS:
            for d in c.demos:
                lines.append(f"| [{c.number} · {_title(c)} ({_source(c)})]({lecture_page(c)}) "
                             f"<br>([{t('whole chapter')}]({c.notebook})) | {t(d.name)} | {t(d.move)} | {t(d.sees)} |")
    return "\n".join(lines)


# =========================================================================== lecture pages
LECTURES_DIR = "lectures"
"""The lecture pages' folder inside ``notebooks/``: one generated page per chapter with demos."""


def lecture_page(c: Chapter) -> str:
    """The lecture page of chapter ``c``, relative to ``notebooks/``: ``"lectures/01_flight_planning.ipynb"``."""
    return f"{LECTURES_DIR}/{c.notebook}"


_GENERATED_NOTE = ("<!-- generated from aerophoto.book.CHAPTERS and the chapter's setup and demo cells by "
                   "`python -m aerophoto.book`; do not edit -->")


def _lecture_setup(source: str, where: str) -> str:
    """A chapter's setup cell for its lecture page: always the guide's example, never a student's number."""
    lines = [ln for ln in source.splitlines() if not ln.strip().startswith("RECORD_BOOK")]
    text = "\n".join(lines)
    if "aerophoto.setup(RECORD_BOOK)" not in text:
        raise ValueError(f"{where}: the setup cell does not call aerophoto.setup(RECORD_BOOK); the lecture page "
                         "cannot force the guide's example")
    text = text.replace("aerophoto.setup(RECORD_BOOK)", "aerophoto.setup(lecture=True)   # the guide's example, variant 00")
    return text + "\nfrom aerophoto.demos.lecture import lecture_view"


def _lecture_demo(source: str, c: Chapter, d: Demo, where: str) -> str:
    """A chapter's demo cell for its lecture page: the same demo, shown by :func:`~aerophoto.demos.lecture.lecture_view`."""
    import ast

    body = source.rstrip().splitlines()
    try:
        last = ast.parse(source).body[-1]
    except (SyntaxError, IndexError) as exc:
        raise ValueError(f"{where}: the demo cell cannot be read ({exc})") from None
    if not (isinstance(last, ast.Expr) and isinstance(last.value, ast.Name) and last.lineno == len(body)):
        raise ValueError(f"{where}: the demo cell must end with the demo's name on a line of its own (e.g. `demo`)")
    name = last.value.id
    title = f"{c.number} · {c.title[0].upper() + c.title[1:]} ({c.source})"
    subtitle = f"{d.name} · the guide's example (variant 00)"
    screen = ", full_screen=True" if len(c.demos) > 1 else ""   # several demos: each fills a screen
    return "\n".join([*body[:-1], f"lecture_view({name}, {title!r}, {subtitle!r}{screen})"])


def lecture_notebook(c: Chapter, root=None):
    """The lecture page of chapter ``c``, built from its notebook: its demos only, each at the top of a screen.

    Cells: ``setup`` (the chapter's setup cell forcing the guide's example, ``aerophoto.setup(lecture=True)``),
    then for each demo its cell (same id, shown by :func:`aerophoto.demos.lecture.lecture_view`: title, sliders,
    figure and table on one 1280×800 screen) and a note ``<demo cell>-notes`` with what to move and what the
    class sees (from :data:`CHAPTERS`), and last ``links`` (back to the lecture index, the whole chapter).  No
    task, no check cell, no student's variant.
    """
    from . import nbtools

    root = Path(root) if root is not None else Path(__file__).resolve().parents[2]
    src = nbtools.read(root / "notebooks" / c.notebook)
    cells = {cell.get("id"): cell for cell in src.cells}
    where = c.notebook
    if "setup" not in cells:
        raise ValueError(f"{where} has no setup cell")
    out = [nbtools.code(_lecture_setup(cells["setup"].source, where), id="setup")]
    for d in c.demos:
        if d.cell not in cells:
            raise ValueError(f"{where} has no cell {d.cell!r} (aerophoto.book.CHAPTERS names it)")
        out.append(nbtools.code(_lecture_demo(cells[d.cell].source, c, d, f"{where} [{d.cell}]"), id=d.cell))
        out.append(nbtools.md(_lecture_texts(c)[f"{d.cell}-notes"], id=f"{d.cell}-notes"))
    out.append(nbtools.md(_lecture_texts(c)["links"], id="links"))
    return nbtools.notebook(out, title=f"{c.number} · {c.title[0].upper() + c.title[1:]} — lecture")


def _lecture_texts(c: Chapter, lang: str = "en") -> dict:
    """The Markdown cells of chapter ``c``'s lecture page by id (``<demo cell>-notes``, ``links``) in ``lang``;
    in Russian they are the page's translation, ``notebooks/lectures/ru/NN_slug.md`` (written by :func:`sync_generated`)."""
    from .i18n import language, t

    with language(lang):
        out = {f"{d.cell}-notes": t("**{name}.** Move: {move}. The class sees: {sees}.", name=t(d.name), move=t(d.move),
                                    sees=t(d.sees)) for d in c.demos}
        out["links"] = _GENERATED_NOTE + "\n" + t(
            "[← every lecture page](../{index}) · [the whole chapter {number}, with the theory and the tasks](../{notebook})"
            " · {source} · the demos open on the guide's worked example (variant 00); **Reset** returns there.",
            index=LECTURE_INDEX, number=c.number, notebook=c.notebook, source=_source(c))
    return out


# =========================================================================== the glossary page
# aerophoto.glossary_page (the page and its Russian text); its names stay importable from here
from .glossary_page import GLOSSARY_PAGE, glossary_markdown, glossary_notebook, glossary_texts  # noqa: E402


def _notebook_text(nb) -> str:
    import json

    from . import nbtools

    nbtools.strip_outputs(nb)
    return json.dumps(nb, indent=1, ensure_ascii=False, sort_keys=True) + "\n"


#: where the generated tables live: (file relative to the repository, how to find the place, generator)
_README_MARK = ("<!-- BEGIN chapters (generated from aerophoto.book.CHAPTERS: python -m aerophoto.book) -->",
                "<!-- END chapters -->")


def _table_cell(cell: str, lang: str = "en") -> str:
    """The source of a generated table's cell (chapter 00's ``chapters``, the lecture index's ``demos``)."""
    table = chapter_table_markdown(lang=lang) if cell == "chapters" else lecture_table_markdown(lang=lang)
    return _HEADINGS[cell][lang] + "\n\n" + table


def _generated(root: Path) -> list[tuple[Path, str, str, object]]:
    """[(file, kind, place, content)]: kind "markdown-section" (between markers), "cell" (a notebook cell by
    id), "translation" (a generated cell's block in a Russian text: content (English, Russian)), "translation-file"
    (a generated page's whole Russian text, a lecture page's or the glossary's: content (English, Russian) cell texts
    by id), "page" (the glossary) or "notebook" (a whole generated notebook: a lecture page)."""
    out = [
        (root / "README.md", "markdown-section", "chapters", chapter_table_markdown(prefix="notebooks/")),
        (root / "notebooks" / LECTURE_INDEX, "cell", "demos", _table_cell("demos")),
        (root / "notebooks" / CHAPTERS[0].notebook, "cell", "chapters", _table_cell("chapters")),
        (root / "notebooks" / "ru" / f"{CHAPTERS[0].name}.md", "translation", "chapters",
         (_table_cell("chapters"), _table_cell("chapters", "ru"))),
        (root / "notebooks" / "ru" / LECTURE_INDEX.replace(".ipynb", ".md"), "translation", "demos",
         (_table_cell("demos"), _table_cell("demos", "ru"))),
    ]
    for c in CHAPTERS:
        if c.demos:
            out.append((root / "notebooks" / lecture_page(c), "notebook", "lecture page", c))
            out.append((root / "notebooks" / LECTURES_DIR / "ru" / f"{c.name}.md", "translation-file", "lecture page",
                        (_lecture_texts(c), _lecture_texts(c, "ru"))))
    out.append((root / "notebooks" / GLOSSARY_PAGE, "page", "glossary", glossary_notebook()))
    out.append((root / "notebooks" / "ru" / "glossary.md", "translation-file", "glossary",
                (glossary_texts("en"), glossary_texts("ru"))))
    return out


def sync_generated(root=None, *, write: bool = False) -> list[str]:
    """Check (or with ``write=True`` rewrite) what is generated from :data:`CHAPTERS`; returns the stale places.

    README.md's chapter table (between the ``BEGIN chapters``/``END chapters`` markers), the lecture index's
    ``demos`` cell, chapter 00's ``chapters`` cell, their Russian blocks (``notebooks/ru/``), the lecture pages' Russian
    text (``notebooks/lectures/ru/NN_slug.md``) and the lecture pages ``notebooks/lectures/NN_slug.ipynb``
    (:func:`lecture_notebook`, one per chapter with demos; a page without its chapter is stale and removed).
    Safe to re-run: cells are found by id.
    """
    from . import nbtools
    from .i18n import prose

    root = Path(root) if root is not None else Path(__file__).resolve().parents[2]
    stale = []
    pages = set()
    for path, kind, place, content in _generated(root):
        if kind == "markdown-section":
            doc = path.read_text(encoding="utf-8")
            begin, end = _README_MARK
            if begin not in doc or end not in doc:
                raise ValueError(f"{path.name} has no generated-table markers {begin!r} … {end!r}")
            head, rest = doc.split(begin, 1)
            _, tail = rest.split(end, 1)
            new = f"{head}{begin}\n{content}\n{end}{tail}"
            if new != doc:
                stale.append(f"{path.name} [{place}]")
                if write:
                    path.write_text(new, encoding="utf-8")
        elif kind == "notebook":
            pages.add(path)
            text = _notebook_text(lecture_notebook(content, root))
            old = path.read_text(encoding="utf-8") if path.is_file() else None
            if old != text:
                stale.append(f"{path.relative_to(root / 'notebooks')} [{place}]")
                if write:
                    path.parent.mkdir(parents=True, exist_ok=True)
                    nbtools.write(lecture_notebook(content, root), path)
        elif kind == "translation":  # a generated cell's block in a chapter's Russian text
            if prose.sync_block(path, place, *content, write=write):
                stale.append(f"{path.relative_to(root / 'notebooks')} [{place}]")
        elif kind == "translation-file":  # a generated page's whole Russian text (lecture page, glossary)
            pages.add(path)
            en, ru = content
            blocks = [prose.Block(cell, prose.cell_key(en[cell]), ru[cell]) for cell in en]
            if prose.sync_file(path, blocks, write=write):
                stale.append(f"{path.relative_to(root / 'notebooks')} [{place}, Russian]")
        elif kind == "page":  # a whole generated page (the glossary)
            text = _notebook_text(content)
            old = path.read_text(encoding="utf-8") if path.is_file() else None
            if old != text:
                stale.append(f"{path.name} [{place}]")
                if write:
                    nbtools.write(content, path)
        else:
            nb = nbtools.read(path)
            _, cell = nbtools.find_cell(nb, place)
            if cell.source != content:
                stale.append(f"{path.name} [{place}]")
                if write:
                    nbtools.set_cell(nb, place, content)
                    nbtools.write(nb, path)
    lectures = root / "notebooks" / LECTURES_DIR
    for extra in sorted([*lectures.glob("*.ipynb"), *(lectures / "ru").glob("*.md")]):
        if extra not in pages:
            stale.append(f"{extra.relative_to(root / 'notebooks')} [no such chapter with demos]")
            if write:
                extra.unlink()
    return stale


REQUIRED = {  # distribution: (minimum major.minor, why)
    "numpy": ((2, 0), "computing"),
    "matplotlib": ((3, 8), "figures"),   # 3.8: the browser book (JupyterLite, Pyodide 0.27) has 3.8.4
    "ipywidgets": ((8, 1), "sliders"),
    "ipympl": ((0, 9), "live figures"),
    "pandas": ((2, 2), "tables"),
}


def state_dir() -> Path:
    """Where aerophoto keeps the remembered record-book number (and language).

    ``$AEROPHOTO_HOME``, else ``~/.aerophoto``; in the browser book, ``/drive/.aerophoto`` — the site's file
    drive, kept in the browser's storage (the home folder there is in memory, gone at the next page load).
    """
    if os.environ.get("AEROPHOTO_HOME"):
        return Path(os.environ["AEROPHOTO_HOME"])
    if in_browser() and Path("/drive").is_dir():
        return Path("/drive") / ".aerophoto"
    return Path.home() / ".aerophoto"


def remembered_record_book() -> str | None:
    """The record-book number from the environment or the last ``setup`` call, or None."""
    env = os.environ.get("AEROPHOTO_RECORD_BOOK")
    if env:
        return env
    path = state_dir() / "student.json"
    try:
        return json.loads(path.read_text(encoding="utf-8")).get("record_book") or None
    except (OSError, ValueError):
        return None


def _state() -> dict:
    """What ``student.json`` holds (``record_book``, ``lang``), or {}."""
    try:
        data = json.loads((state_dir() / "student.json").read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return {}
    return data if isinstance(data, dict) else {}


def _save_state(**fields) -> None:
    d = state_dir()
    try:
        d.mkdir(parents=True, exist_ok=True)
        (d / "student.json").write_text(json.dumps({**_state(), **fields}), encoding="utf-8")
    except OSError:
        pass  # a read-only home must not stop the book


def remember_record_book(record_book: str) -> None:
    """Save the number so later chapters can leave their first cell at None."""
    _save_state(record_book=str(record_book))


def remembered_language() -> str | None:
    """The language of the last ``setup(..., lang=...)`` (``"en"``/``"ru"``), or None (``$AEROPHOTO_LANG`` still wins)."""
    lang = _state().get("lang")
    return lang if lang in ("en", "ru") else None


def remember_language(lang: str) -> None:
    """Save the language so later chapters speak it without being told."""
    _save_state(lang=str(lang))


def _version_tuple(text: str) -> tuple:
    parts = []
    for p in text.split(".")[:2]:
        digits = "".join(ch for ch in p if ch.isdigit())
        parts.append(int(digits or 0))
    return tuple(parts)


def check_installation() -> list[str]:
    """Return a list of problems with the installed packages (empty when all is well)."""
    problems = []
    for dist, (minimum, why) in REQUIRED.items():
        try:
            have = metadata.version(dist)
        except metadata.PackageNotFoundError:
            problems.append(f"{dist} is not installed (needed for {why}); run: python -m pip install -r environment.txt")
            continue
        if _version_tuple(have) < minimum:
            problems.append(f"{dist} {have} is too old (need ≥ {'.'.join(map(str, minimum))} for {why})")
    return problems


def in_browser() -> bool:
    """True in the browser book (JupyterLite: Python compiled to WebAssembly by Pyodide, ``aerophoto-course lite``)."""
    return sys.platform == "emscripten"


#: what the browser book cannot do, said under the banner of every chapter that runs there (English; the
#: Russian text is in aerophoto.i18n)
BROWSER_NOTE = (
    "You are running in your browser (JupyterLite): nothing is installed and nothing leaves this computer. "
    "File ▸ Save keeps your answers in this browser's storage (another browser, a private window or clearing "
    "the site's data starts afresh); to hand in, File ▸ Download gives the .ipynb to upload. Grading "
    "(nbgrader, aerophoto-course) runs only in the installed book; image matching, resampling and the "
    "Gauss–Krüger conversions use the package's own numpy/scipy versions of scikit-image and pyproj here "
    "(the same numbers, slower)."
)


def _in_ipython():
    try:
        from IPython import get_ipython
    except ImportError:
        return None
    return get_ipython()


def setup(record_book=None, *, live: bool = True, quiet: bool = False, lecture: bool = False,
          lang: str | None = None) -> Variant:
    """Prepare a chapter and return the student's variant.

    Parameters
    ----------
    record_book : str or int or None
        The student's record-book number (номер зачётной книжки); the variant
        is its last two digits (guide §1).  None: use the remembered number,
        else the guide's worked example (variant 00).
    live : bool
        Switch to the ipympl widget backend (``%matplotlib widget``) so demos
        update in place.  Set False for static figures.
    quiet : bool
        Do not display the banner.
    lecture : bool
        A lecture page (``notebooks/lectures/``): always the guide's worked
        example, variant 00 — whatever number is remembered on the machine or
        set in ``AEROPHOTO_RECORD_BOOK`` — nothing remembered, no banner.
        ``record_book`` must then be None.
    lang : {"en", "ru"} or None
        The language of the demos' sliders, tables and figures, the check
        messages and this banner (:mod:`aerophoto.i18n`); remembered like the
        number (not on a lecture page).  None: the remembered one, else English.
        ``$AEROPHOTO_LANG`` overrides both.
    """
    from .i18n import set_language, t

    if lang is not None:
        set_language(lang)  # checks it: "en" or "ru"
        if not lecture:
            remember_language(str(lang).strip().lower())
    else:
        saved = remembered_language()
        if saved:
            set_language(saved)
    use_style()
    register_table_display()  # the package's tables and the guide's audits in the book's number format
    problems = check_installation()
    if problems:
        raise RuntimeError("aerophoto cannot run in this environment:\n- " + "\n- ".join(problems))
    if lecture and record_book is not None:
        raise ValueError(f"record_book = {record_book!r} with lecture=True: a lecture page always shows the guide's "
                         "worked example (variant 00); leave record_book at None")
    ip = _in_ipython()
    if live and ip is not None:
        try:
            ip.run_line_magic("matplotlib", "widget")
        except NotImplementedError:  # a shell with no event loop (a plain InteractiveShell): figures stay static
            pass
    if lecture:
        if ip is not None and not quiet:
            from IPython.display import HTML, display

            display(HTML(LINK_CSS))
        return variant_for_index(0, "lecture — the guide's worked example")
    note = ""
    if record_book is not None and str(record_book).strip():
        v = variant(record_book)
        remember_record_book(str(record_book).strip())
    else:
        saved = remembered_record_book()
        if saved:
            v = variant(saved)
            note = t("(remembered from an earlier chapter: {saved})", saved=saved)
        else:
            v = variant_for_index(0, "not given — the guide's worked example")
            note = t("Type your record-book number in the first cell to get your own variant.")
    if not quiet:
        _banner(v, note, ip)
    return v


def _banner(v: Variant, note: str, ip) -> None:
    from .i18n import t

    text = (
        t("aerophoto {version} · variant i = {i:02d} · record book: {record_book} {note}", version=__version__, i=v.i,
          record_book=v.record_book, note=note) + "\n"
        + t("f = {f:g} mm, 1/m = 1:{m:.0f}, W = {W:g} km/h, α = {alpha:g}°, λ = {lam:g}°. "
            "The code behind every figure is in the package: add ?? to a name to read it, "
            "e.g. aerophoto.geometry.ground_to_photo??", f=v.f_mm, m=v.m, W=v.W_kmh, alpha=v.alpha_deg,
            lam=v.lambda_deg)
    )
    if ip is None:
        print(text)
        return
    from IPython.display import HTML, display

    line1, line2 = text.split("\n")
    extra = ""
    if in_browser():
        extra = f"<br><span class='aerophoto-browser-note'>{html.escape(t(BROWSER_NOTE))}</span>"
    display(HTML(f"{LINK_CSS}<div style='border-left:4px solid #0072B2;padding:4px 8px'><b>{line1}</b><br>{line2}{extra}"
                 "</div>"))


def main(argv=None) -> int:
    """``python -m aerophoto.book``: rewrite the generated chapter tables; ``python -m aerophoto.book 09``: print
    chapter 09's key (its notebook, source, guide, tasks, lab and demo modules)."""
    args = sys.argv[1:] if argv is None else list(argv)
    if args:
        for a in args:
            print(chapter(a).key_text())
        return 0
    for place in sync_generated(write=True) or ["(all current)"]:
        print("updated", place)
    return 0


if __name__ == "__main__":
    sys.exit(main())
