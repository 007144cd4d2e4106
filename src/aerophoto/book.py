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

import json
import os
from dataclasses import dataclass
from importlib import metadata
from pathlib import Path

from . import __version__
from .plots import use_style
from .variants import Variant, variant, variant_for_index

__all__ = ["setup", "check_installation", "remembered_record_book", "remember_record_book", "state_dir",
           "Demo", "Chapter", "CHAPTERS", "LECTURE_INDEX", "chapter", "chapter_table_markdown",
           "lecture_table_markdown", "sync_generated"]

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
    """One notebook of the book.

    Attributes
    ----------
    number : str
        The notebook's number, ``"03"`` (the guide's §4 → 03, leaving room for later chapters).
    slug : str
        The rest of the file name, ``"relief_displacement"``.
    source : str
        What it is built from: ``"guide §4"``, ``"article 001"``.
    title, title_ru : str
        The topic in English and the guide's Russian term.
    demos : tuple of :class:`Demo`
    """

    number: str
    slug: str
    source: str
    title: str
    title_ru: str
    demos: tuple = ()

    @property
    def name(self) -> str:
        return f"{self.number}_{self.slug}"

    @property
    def notebook(self) -> str:
        return f"{self.name}.ipynb"


_F = ("f, mm", "PageUp")  # focal length: five steps up from the chapter's start
_M = ("m (scale 1:m)", "PageUp")  # scale denominator: five steps up

CHAPTERS = (
    Chapter("00", "start_here", "guide §1", "start here: your variant, central projection",
            "задание; центральная проекция", (
                Demo("demo-footprint", "aerophoto.demos.footprint.FootprintDemo", "Camera footprint — o, n, c",
                     "α (tilt), then f and m (scale 1:m)",
                     "the footprint turns from a square into a trapezoid; n and c leave o along the principal "
                     "vertical; with the scale fixed, a longer lens flies higher but covers the same ground",
                     (_F, _M, ("α, °", "ArrowRight")), timed="α, °"),
            )),
    Chapter("01", "flight_planning", "guide §2", "planning the aerial survey", "расчёт параметров аэросъёмки", (
        Demo("demo-flight-plan", "aerophoto.demos.flight_plan.FlightPlanDemo", "Live survey plan", "m, relief h, then f and W",
             "strips and photos multiply as the scale grows or the relief rises; a faster aircraft shortens the "
             "flight and the admissible exposure", (_F, _M, ("px, %", "ArrowRight")), timed="f, mm"),
    )),
    Chapter("02", "photo_quality", "guide §3", "judging the photos' quality", "оценка качества материалов", (
        Demo("demo-quality", "aerophoto.demos.quality.QualityDemo", "Rough mosaic you can break", "crab φ, α max, ΔH, bend, overlaps",
             "an imperfection past its tolerance turns its print, pair or strip vermillion and changes the verdict",
             (_F, ("α max, °", "ArrowRight"), ("crab φ, °", "ArrowRight")), timed="α max, °"),
    )),
    Chapter("03", "relief_displacement", "guide §4", "relief displacement", "смещение точек за рельеф", (
        Demo("demo-relief", "aerophoto.demos.displacement.ReliefDemo", "Displacement explorer, relief", "relief ±h, then α and f",
             "arrows radiate from the nadir n — outwards for hills, inwards for the valley; a longer lens at the "
             "same scale shortens them", (_F, _M, ("α, °", "ArrowRight"), ("relief ±h, m", "ArrowRight")),
             timed="relief ±h, m"),
    )),
    Chapter("04", "tilt_displacement", "guide §5", "tilt displacement", "смещения за угол наклона", (
        # m is no headline here: over flat ground the tilt displacement on the photo does not depend on m
        Demo("demo-tilt", "aerophoto.demos.displacement.TiltDemo", "Displacement explorer, tilt", "α, then λ and f",
             "arrows radiate from the isocentre c; points on the isoline stay put; the guide's approximate "
             "formula (orange) parts from the exact displacement (blue) as α grows",
             (_F, ("α, °", "ArrowRight"), ("λ, °", "ArrowRight")), timed="α, °"),
    )),
    Chapter("05", "fotoschema", "guide §6", "the single-strip photo mosaic", "одномаршрутная фотосхема", (
        Demo("demo-fotoschema", "aerophoto.demos.fotoschema.FotoschemaDemo", "Live single-strip mosaic",
             "relief h, α max, then f and p_x",
             "cut-outs and duplicates appear along the cuts; a longer lens at the same scale shrinks the mismatches",
             (_F, _M, ("α max, °", "ArrowRight")), timed="α max, °"),
    )),
    Chapter("06", "strip_triangulation", "guide §7", "strip phototriangulation and its reduction",
            "фототриангуляционный ряд", (
                Demo("demo-reduction", "aerophoto.demos.reduction.ReductionDemo", "Reduction explorer",
                     "q (free-strip scale), pricking error, central centre",
                     "k follows 1/q and the reduction arrows grow while the control residuals stay; pricking errors "
                     "grow the error triangles",
                     (_F, ("m (photo 1:m)", "PageUp"), ("α max, °", "ArrowRight")), timed="α max, °"),
            )),
    Chapter("12", "phototriangulation", "guide §13", "phototriangulation: control spacing and reduction",
            "фототриангуляция", (
                Demo("demo-reduction", "aerophoto.demos.reduction.ReductionDemo", "Reduction explorer (tilted photos)",
                     "α max, q, pricking error",
                     "the same explorer with tilted photos: the reduced strip against the control points",
                     (_F, ("m (photo 1:m)", "PageUp"), ("α max, °", "ArrowRight")), timed="α max, °"),
            )),
)
"""Every chapter of the book, in order: the one registry (aerophoto.__init__, the lecture index, the README and
chapter 00's tables, the browser tests and the benchmarks read it)."""

LECTURE_INDEX = "lectures.ipynb"


def chapter(name_or_number: str) -> Chapter:
    """A chapter by number (``"03"``), name (``"03_relief_displacement"``) or notebook file name."""
    key = str(name_or_number).removesuffix(".ipynb")
    for c in CHAPTERS:
        if key in (c.number, c.name):
            return c
    raise ValueError(f"no chapter {name_or_number!r}; chapters: {[c.name for c in CHAPTERS]}")


def _title(c: Chapter) -> str:
    return c.title[0].upper() + c.title[1:]


def chapter_table_markdown(*, prefix: str = "") -> str:
    """The chapter table of the README (``prefix="notebooks/"``) and of chapter 00 (generated; a test keeps both current)."""
    lines = ["| notebook | source | topic | live demos |", "|---|---|---|---|"]
    for c in CHAPTERS:
        demos = "; ".join(d.name for d in c.demos) or "—"
        lines.append(f"| [`{c.name}`]({prefix}{c.notebook}) | {c.source} | {c.title} ({c.title_ru}) | {demos} |")
    return "\n".join(lines)


def lecture_table_markdown() -> str:
    """The lecture index's table of demos (generated; a test keeps ``notebooks/lectures.ipynb`` current)."""
    lines = ["| chapter | demo | move | what the class sees |", "|---|---|---|---|"]
    for c in CHAPTERS:
        for d in c.demos:
            lines.append(f"| [{c.number} · {_title(c)} ({c.source})]({c.notebook}) | {d.name} | {d.move} | {d.sees} |")
    return "\n".join(lines)


#: where the generated tables live: (file relative to the repository, how to find the place, generator)
_README_MARK = ("<!-- BEGIN chapters (generated from aerophoto.book.CHAPTERS: python -m aerophoto.book) -->",
                "<!-- END chapters -->")


def _generated(root: Path) -> list[tuple[Path, str, str, object]]:
    """[(file, kind, place, text)]: kind "markdown-section" (between markers) or "cell" (a notebook cell by id)."""
    return [
        (root / "README.md", "markdown-section", "chapters", chapter_table_markdown(prefix="notebooks/")),
        (root / "notebooks" / LECTURE_INDEX, "cell", "demos",
         "## The demonstrations\n\n" + lecture_table_markdown()),
        (root / "notebooks" / CHAPTERS[0].notebook, "cell", "chapters",
         "## The chapters\n\n" + chapter_table_markdown()),
    ]


def sync_generated(root=None, *, write: bool = False) -> list[str]:
    """Check (or with ``write=True`` rewrite) the tables generated from :data:`CHAPTERS`; returns the stale places.

    README.md's chapter table (between the ``BEGIN chapters``/``END chapters`` markers), the lecture index's
    ``demos`` cell and chapter 00's ``chapters`` cell.  Safe to re-run: cells are found by id.
    """
    from . import nbtools

    root = Path(root) if root is not None else Path(__file__).resolve().parents[2]
    stale = []
    for path, kind, place, text in _generated(root):
        if kind == "markdown-section":
            doc = path.read_text(encoding="utf-8")
            begin, end = _README_MARK
            if begin not in doc or end not in doc:
                raise ValueError(f"{path.name} has no generated-table markers {begin!r} … {end!r}")
            head, rest = doc.split(begin, 1)
            _, tail = rest.split(end, 1)
            new = f"{head}{begin}\n{text}\n{end}{tail}"
            if new != doc:
                stale.append(f"{path.name} [{place}]")
                if write:
                    path.write_text(new, encoding="utf-8")
        else:
            nb = nbtools.read(path)
            _, cell = nbtools.find_cell(nb, place)
            if cell.source != text:
                stale.append(f"{path.name} [{place}]")
                if write:
                    nbtools.set_cell(nb, place, text)
                    nbtools.write(nb, path)
    return stale


REQUIRED = {  # distribution: (minimum major.minor, why)
    "numpy": ((2, 0), "computing"),
    "matplotlib": ((3, 9), "figures"),
    "ipywidgets": ((8, 1), "sliders"),
    "ipympl": ((0, 9), "live figures"),
    "pandas": ((2, 2), "tables"),
}


def state_dir() -> Path:
    """Where aerophoto keeps the remembered record-book number."""
    return Path(os.environ.get("AEROPHOTO_HOME") or Path.home() / ".aerophoto")


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


def remember_record_book(record_book: str) -> None:
    """Save the number so later chapters can leave their first cell at None."""
    d = state_dir()
    try:
        d.mkdir(parents=True, exist_ok=True)
        (d / "student.json").write_text(json.dumps({"record_book": str(record_book)}), encoding="utf-8")
    except OSError:
        pass  # a read-only home must not stop the book


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


def _in_ipython():
    try:
        from IPython import get_ipython
    except ImportError:
        return None
    return get_ipython()


def setup(record_book=None, *, live: bool = True, quiet: bool = False) -> Variant:
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
    """
    use_style()
    problems = check_installation()
    if problems:
        raise RuntimeError("aerophoto cannot run in this environment:\n- " + "\n- ".join(problems))
    ip = _in_ipython()
    if live and ip is not None:
        ip.run_line_magic("matplotlib", "widget")
    note = ""
    if record_book is not None and str(record_book).strip():
        v = variant(record_book)
        remember_record_book(str(record_book).strip())
    else:
        saved = remembered_record_book()
        if saved:
            v = variant(saved)
            note = f"(remembered from an earlier chapter: {saved})"
        else:
            v = variant_for_index(0, "not given — the guide's worked example")
            note = "Type your record-book number in the first cell to get your own variant."
    if not quiet:
        _banner(v, note, ip)
    return v


def _banner(v: Variant, note: str, ip) -> None:
    text = (
        f"aerophoto {__version__} · variant i = {v.i:02d} · record book: {v.record_book} {note}\n"
        f"f = {v.f_mm:g} mm, 1/m = 1:{v.m:.0f}, W = {v.W_kmh:g} km/h, α = {v.alpha_deg:g}°, λ = {v.lambda_deg:g}°. "
        "The code behind every figure is in the package: add ?? to a name to read it, "
        "e.g. aerophoto.geometry.ground_to_photo??"
    )
    if ip is None:
        print(text)
        return
    from IPython.display import HTML, display

    line1, line2 = text.split("\n")
    display(HTML(f"<div style='border-left:4px solid #0072B2;padding:4px 8px'><b>{line1}</b><br>{line2}</div>"))


if __name__ == "__main__":  # python -m aerophoto.book: rewrite the generated chapter tables
    for place in sync_generated(write=True) or ["(all current)"]:
        print("updated", place)
