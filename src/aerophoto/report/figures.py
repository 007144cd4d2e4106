"""The note's figures: drawn off-screen for the student's variant, in the note's language, saved as vector PDF.

Every figure comes from the plotting functions the demos and the notebooks use (``ax=None`` views and figure
builders, :mod:`aerophoto.report.figure_draws`), drawn on a figure with its own Agg canvas — never pyplot's
current figure, so a report built from a notebook leaves the notebook's live backend alone — in the book's
style, and saved as PDF: lines, text and shading stay vector; only photos are raster images.  Each
:class:`FigureSpec` says how many photos it holds, and :func:`render` refuses a figure with any other raster
(a DEM or a class map shown as an image is drawn as contours instead), so the note's ``pdfimages`` lists the
photos and nothing else.

:func:`russify` puts a drawn figure into Russian: the i18n catalogue first (:func:`aerophoto.i18n.translate_figure`),
with the book's tick format and subscripts (:func:`aerophoto.plots.finish_figure`), then the report's own table
of the figures' texts the catalogue does not hold (:data:`TEXTS`) and patterns for texts that carry numbers
("1.27 km" → "1,27 км"), numbers in the book's format (:func:`aerophoto.i18n.numfmt.fmt_text`), the demos' own
tick labels too; whatever Latin text is left is listed (:attr:`Drawn.leftover`) so the tests can insist on none.

A figure depends on the variant and on the few values of the student it draws over its base, so it is cached as its
PDF bytes on the student's machine (:mod:`aerophoto.diskcache`); a figure that shows a graded value is drawn only once the
tasks it shows have passed, one that shows what the student works from once the section is attempted
(:attr:`FigureSpec.passed`, :attr:`FigureSpec.attempted`).
"""

from __future__ import annotations

import io
import re
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

from .. import diskcache
from ..i18n import numfmt

__all__ = ["FigureSpec", "Drawn", "render", "russify", "latin_words", "TEXTS", "new_figure", "PDF_META"]

PDF_META = {"CreationDate": None, "Creator": "aerophoto", "Producer": "aerophoto (matplotlib)"}
#: a figure's photos are written at this resolution (the sheet's at 300 dpi, :mod:`aerophoto.report.sheet`)
PHOTO_DPI = 200
#: the figures' format: a change of how they are finished makes every cached figure a miss
FIGURE_FORMAT = 3


@dataclass(frozen=True)
class FigureSpec:
    """One figure of a chapter.

    ``draw(variant, own) -> Figure`` (``own``: the student's values it draws, plain data); ``photos``: how many raster photos it holds (everything else is vector);
    ``attempted``/``passed``: the tasks that must be attempted / have passed before it is drawn;
    ``width``: its width in the note, a fraction of the text width.
    """

    chapter: str
    name: str
    draw: Callable
    photos: int = 0
    attempted: tuple = ()
    passed: tuple = ()
    width: float = 1.0


@dataclass
class Drawn:
    """A rendered figure: its PDF bytes, the photos it holds and any Latin text left after :func:`russify`."""

    pdf: bytes
    photos: int
    leftover: list = field(default_factory=list)


def new_figure(figsize, **kwargs):
    """A Figure with its own Agg canvas (not pyplot's), constrained layout unless told otherwise."""
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    kwargs.setdefault("layout", "constrained")
    fig = Figure(figsize=figsize, **kwargs)
    FigureCanvasAgg(fig)
    return fig


# =========================================================================== Russian
#: the figures' fixed English texts the i18n catalogue does not hold, and their Russian
TEXTS = {
    "X (along the strips), km": "X (вдоль маршрутов), км", "Y, km": "Y, км", "X, km": "X, км",
    "footprints (first strips)": "контуры снимков (первые маршруты)", "flight path": "линия полёта",
    "survey area Lx × Ly": "участок съёмки Lx × Ly", "photo centres": "центры снимков",
    "detail (right)": "фрагмент (справа)", "Detail: first strips and photos": "Фрагмент: первые маршруты и снимки",
    "footprint l·m": "контур снимка l·m", "working area Bx × By": "рабочая площадь Bx × By",
    "X (east), km": "X (восток), км", "Y (north), km": "Y (север), км", "2 prints": "2 снимка",
    "3 prints": "3 снимка", "4 prints": "4 снимка", "base o–o": "базис o–o", "strip line L": "линия маршрута L",
    "out of tolerance": "вне допуска", "x, mm": "x, мм", "y, mm": "y, мм", "frame": "рамка снимка",
    "photo frame": "рамка снимка", "control points (опознаки)": "опознаки", "ground points": "точки местности",
    "details pricked along the cuts (task 05.1)": "точки контроля монтажа на порезах",
    "points of the mean scale (task 05.2)": "точки для среднего масштаба", "principal points o": "главные точки o",
    "across, mm": "поперёк маршрута, мм", "Y (east), m": "Y (восток), м", "X (north), m": "X (север), м",
    "known points": "исходные пункты", "the station P": "определяемый пункт P",
    "danger circle (опасный круг)": "опасный круг", "resected stations": "решения засечки",
    "Y (east), m − 5 310 000": "Y (восток) − 5 310 000, м", "X (north), m − 6 060 000": "X (север) − 6 060 000, м",
    "along the strip, m": "вдоль маршрута, м", "height, m": "высота, м", "air base B": "базис фотографирования B",
    "A (ground)": "A (на земле)", "C, h above A": "C, выше A на h", "focal length f, mm": "фокусное расстояние f, мм",
    "largest crab φ_max, °": "допустимый угол φ_max, °", "guide §3, item 3.3": "пособие, §3, п. 3.3",
    "book's rule: φ_max = f/20, held outside": "правило книги: φ_max = f/20",
    "the line f/20 continued": "продолжение прямой f/20",
    "beyond real lenses (> 610 mm): the rule applied anyway": "за пределами реальных объективов (> 610 мм)",
    "n, bases between the control points": "n — число базисов между опознаками",
    "RMS error on the plan, mm": "СКП на плане, мм", "simulated free strips, reduced": "моделирование свободных рядов",
    "(13.1) with n³ + 11n + 34": "(13.1) с n³ + 11n + 34", "m = 0.35 mm (guide)": "m = 0,35 мм (пособие)",
    "x on the base, mm": "x на основе, мм", "y on the base, mm": "y на основе, мм",
    "Rectified photo on the base": "Трансформированный снимок на основе",
    "Left half rectified, right half the truth": "Слева снимок, справа план (истина)",
    "h above the control points, m": "h над опознаками, м", "X, km ": "X, км",
    "x from the sheet's corner, m": "x от угла листа, м", "y, m": "y, м",
    "RMS planimetric error on the map, mm": "СКП положения на карте, мм", "left out": "не учтено",
    "n, links (bases)": "n — число звеньев (базисов)", "photo centres ": "центры снимков",
    "unknowns: photos (6 each) | points (3 each)": "неизвестные: снимки (по 6) | точки (по 3)",
    "standard error ellipse": "эллипс средних ошибок", "gravimetric point (true)": "гравиметрический пункт",
    "true error of the adjusted point": "истинная ошибка уравненного пункта",
    "exact middle law √((n³ + 2n)/48)·d′": "точный закон для середины √((n³ + 2n)/48)·d′",
    "article's recipe: (10.20) with n/2, halved, same d": "рецепт статьи: (10.20) с n/2, пополам, то же d",
    "wavelength λ, µm": "длина волны λ, мкм", "reflectance ρ": "КСЯ ρ",
    "… with n² + 11n + 34": "… с n² + 11n + 34", "… with n⁰ + 11n + 34 (as scanned)": "… с n⁰ + 11n + 34 (как в скане)",
    "RMS error in Z, µm at the photo scale": "СКП по Z, мкм в масштабе снимка",
    "TOTAL, formula (10)": "ИТОГО, формула (10)", "interior orientation (m_вн.о.)": "внутреннее ориентирование (m_вн.о.)",
    "Moisture: darker everywhere, dips at 1.45 and 1.95 µm": "Влажность: темнее везде, провалы у 1,45 и 1,95 мкм",
    "Humus: linear to 5 %, then flattening": "Гумус: линейно до 5 %, затем насыщение",
    "Particles: brighter as finer, most below 0.4 mm": "Частицы: мельче — светлее, сильнее всего до 0,4 мм",
    "What is left of the dry brightness": "Доля яркости сухой почвы", "red band": "красная зона",
    "near infrared": "ближняя ИК-зона", "humus H, %": "гумус H, %", "ρ in the band": "ρ в зоне",
    "particle size d, mm": "размер частиц d, мм", "moisture θ, %": "влажность θ, %", "wet / dry, %": "влажная / сухая, %",
    "at 1.25 µm (no dip)": "при 1,25 мкм (без провала)", "λ, µm": "λ, мкм",
}

#: patterns for texts with numbers: (regex, replacement) applied after TEXTS
_PATTERNS = [
    (re.compile(r"(?<![\w.])(\d[\d\u202f]*(?:[.,]\d+)?)\s?(mm|km|m|cm|s|h|µm)\b"), None),  # a number and its unit
    (re.compile(r"\bphoto (\d+)\b"), r"снимок \1"), (re.compile(r"\bphotos (\d+)[–-](\d+)\b"), r"снимки \1–\2"),
    (re.compile(r"\bcut (\d+)/(\d+)\b"), r"порез \1/\2"), (re.compile(r"\bstrip (\d+)\b"), r"маршрут \1"),
    (re.compile(r"\bcamera f = "), "камера f = "),
    (re.compile(r"\(from the principal point of (photo|снимок) (\d+)\)"), r"(от главной точки снимка \2)"),
    (re.compile(r"\balong the strip\b"), "вдоль маршрута"), (re.compile(r"\(east\)"), "(восток)"),
    (re.compile(r"\(north\)"), "(север)"), (re.compile(r"\b([xy]) on the strip\b"), r"\1 на общей восковке"),
    (re.compile(r"\bphoto footprints\b"), "контуры снимков"), (re.compile(r"\bworking centres\b"), "рабочие центры"),
    (re.compile(r"\borienting points\b"), "ориентирующие точки"), (re.compile(r"\btie points\b"), "связующие точки"),
    (re.compile(r"\bcontrol points\b"), "опознаки"),
    (re.compile(r"\bfree strip, simulated \(slope ([^)]*)\)"), r"свободный ряд, моделирование (наклон \1)"),
    (re.compile(r"\bboth ends held, middle \(slope ([^)]*)\)"), r"закреплены оба конца, середина (наклон \1)"),
    (re.compile(r"^tie \((\d+)\)$"), r"связующие (\1)"), (re.compile(r"^check \((\d+)\)$"), r"контрольные (\1)"),
    (re.compile(r"^control \((\d+)\)$"), r"опорные (\1)"), (re.compile(r"^field \((\d+)\)$"), r"определяемые (\1)"),
    (re.compile(r"^at ([\d.,]+)\s?(µm|мкм)$"), r"при \1 мкм"),
    # "english name (русское название)": the Russian alone
    (re.compile(r"^[A-Za-z][A-Za-z ,'/-]*\(([^()]*[А-Яа-яЁё][^()]*)\)$"), r"\1"),
    (re.compile(r", (mm|km|m|cm|µm|s|h)\b"), None),
]
_UNITS_RU = {"mm": "мм", "km": "км", "m": "м", "cm": "см", "s": "с", "h": "ч", "µm": "мкм"}
#: Latin tokens that are symbols, not words (the guide's letters, functions, the site's names)
_SYMBOLS = {"px", "py", "Px", "Py", "Bx", "By", "Lx", "Ly", "LS", "TS", "tg", "sin", "cos", "max", "min", "mm",
            "RMS", "II", "III", "IV", "VI", "VII", "VIII", "IX", "XI", "XII"}
_MATH = re.compile(r"\$[^$]*\$")
_STAGES: dict = {}


def _numbers(text: str, lang: str) -> str:
    """Numbers in a figure's text in the book's format (:func:`aerophoto.i18n.numfmt.fmt_text`), mathtext left alone."""
    parts = re.split(r"(\$[^$]*\$)", text)
    return "".join(p if p.startswith("$") else numfmt.fmt_text(p, lang=lang) for p in parts)


def _stage_texts() -> dict:
    """The error budget's stage labels ("scanning (m_ск)") in Russian, from :data:`aerophoto.budget.STAGES`."""
    from .. import budget as bu

    return {f"{en} ({sym})": f"{ru} ({sym})" for _k, sym, en, ru in bu.STAGES}


def _translate(text: str) -> str:
    if not _STAGES:
        _STAGES.update(_stage_texts())
    s = TEXTS.get(text, TEXTS.get(text.strip(), _STAGES.get(text, text)))
    if s != text:
        return s
    s = _PATTERNS[0][0].sub(lambda m: f"{m.group(1)}\u00a0{_UNITS_RU[m.group(2)]}", s)
    for pat, rep in _PATTERNS[1:]:
        s = pat.sub(rep if rep is not None else (lambda m: ", " + _UNITS_RU[m.group(1)]), s)
    return s


def latin_words(text: str) -> list:
    """The Latin words of a text that are not symbols (mathtext ``$…$`` left out)."""
    bare = _MATH.sub(" ", str(text))
    return [w for w in re.findall(r"[A-Za-z]{2,}", bare) if w not in _SYMBOLS]


def _custom_ticks(axis, lang: str) -> None:
    """A tick formatter the book's :func:`~aerophoto.i18n.numfmt.localise_ticks` leaves alone (a function of the
    demo's own, fixed labels) wrapped so that its words are translated and its numbers in the book's format."""
    from matplotlib.ticker import FuncFormatter, ScalarFormatter

    fmt = axis.get_major_formatter()
    if getattr(fmt, "_aerophoto_numfmt", None) or getattr(fmt, "_aerophoto_report", False) \
            or type(fmt) is ScalarFormatter or axis.get_scale() != "linear":
        return

    def func(x, pos=None, _inner=fmt):
        text = _inner(x, pos)
        return _numbers(_translate(text) if lang == "ru" else text, lang)
    wrapped = FuncFormatter(func)
    wrapped._aerophoto_report = True
    if hasattr(fmt, "set_locs"):
        wrapped.set_locs = fmt.set_locs  # a formatter that needs its tick positions before formatting
    axis.set_major_formatter(wrapped)


def russify(fig, lang: str) -> list:
    """Finish the drawn ``fig`` in ``lang`` (:func:`aerophoto.plots.finish_figure`: the catalogue's texts, the
    book's tick format, subscripts), then the report's own texts; returns the texts with Latin words left (Russian)."""
    from ..i18n import language, translate_figure
    from ..plots import finish_figure

    texts = lambda: fig.findobj(lambda a: hasattr(a, "get_text") and hasattr(a, "set_text"))  # noqa: E731
    with language(lang):
        translate_figure(fig)  # the catalogue first, on the demos' own English texts
        if lang == "ru":
            for art in texts():
                s = art.get_text()
                if s and _translate(s) != s:
                    art.set_text(_translate(s))
        finish_figure(fig)  # then ticks in the book's format and subscripts
    left = []
    for art in texts():
        s = art.get_text()
        if not s:
            continue
        new = _numbers(s, lang)
        if new != s:
            art.set_text(new)
        if lang == "ru" and latin_words(new) and art.get_visible():
            left.append(new)
    for ax in fig.axes:
        for axis in (ax.xaxis, ax.yaxis):
            _custom_ticks(axis, lang)
    return left


# =========================================================================== rendering
def _raster_count(fig) -> int:
    from matplotlib.image import AxesImage, FigureImage

    return sum(1 for a in fig.findobj(lambda a: isinstance(a, (AxesImage, FigureImage))) if a.get_visible())


def _draw(spec: FigureSpec, v, lang: str, own: dict) -> Drawn:
    import matplotlib.pyplot as plt

    from ..plots import style_context

    with style_context():
        fig = spec.draw(v, own)
        try:
            leftover = russify(fig, lang)
            n = _raster_count(fig)
            if n != spec.photos:
                raise RuntimeError(f"figure {spec.chapter}/{spec.name} holds {n} raster images; it declares "
                                   f"{spec.photos} photos (everything else must be vector)")
            buf = io.BytesIO()
            fig.savefig(buf, format="pdf", metadata=PDF_META, dpi=PHOTO_DPI, bbox_inches="tight", pad_inches=0.04)
        finally:
            plt.close(fig)
    return Drawn(buf.getvalue(), spec.photos, leftover)


def render(spec: FigureSpec, v, lang: str, folder: Path, own: dict | None = None) -> tuple[Path, Drawn]:
    """Draw ``spec`` for variant ``v`` in ``lang`` into ``folder`` (from the student's cache when it holds it).

    ``own``: the student's values the figure shows (plain data; part of the cache key).
    """
    from .facts import plain, variant_key

    own = plain(dict(own or {}))
    cache = diskcache.active()
    key = {"chapter": spec.chapter, "name": spec.name, "variant": variant_key(v), "lang": lang, "own": own,
           "dpi": PHOTO_DPI, "format": FIGURE_FORMAT}
    drawn = None
    if cache is not None:
        meta = cache.get_bytes("figure-meta", key)
        pdf = cache.get_bytes("figure", key) if meta is not None else None
        if pdf is not None:
            import json

            m = json.loads(meta.decode("utf-8"))
            drawn = Drawn(pdf, int(m["photos"]), list(m["leftover"]))
    if drawn is None:
        drawn = _draw(spec, v, lang, own)
        if cache is not None:
            import json

            cache.put_bytes("figure", key, drawn.pdf)
            cache.put_bytes("figure-meta", key, json.dumps({"photos": drawn.photos,
                                                            "leftover": drawn.leftover}).encode("utf-8"))
    path = Path(folder) / f"ch{spec.chapter}_{spec.name}.pdf"
    path.write_bytes(drawn.pdf)
    return path, drawn
