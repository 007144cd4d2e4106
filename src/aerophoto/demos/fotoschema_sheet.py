"""The fotoschema's finished sheet (guide §6 and appendix 1): the paper it needs, the drawn sheet with its title
block (ФОТОСХЕМА, the mean scale М 1:m, the year, «Выполнил», «Проверил»), its export to PNG and PDF at true size,
and the student's own sheet from their variant's prints.  Split from :mod:`aerophoto.demos.fotoschema`, which
re-exports every name here."""

from __future__ import annotations

import datetime
import functools
import math
from pathlib import Path

import numpy as np

from .. import mosaic as mo
from .. import plots
from ..i18n import t as _t  # functions here name a local t
from ..i18n.numfmt import fmt_count, fmt_scale, fmt_spec
from .fotoschema import _CUT, _CUT_EDGE, N_PHOTOS, PAPER_MM

__all__ = ["TRIM_MM", "sheet_size_mm", "sheet_paper", "sheet_figure", "export_sheet", "own_prints", "own_sheet_image",
           "own_sheet_figure", "student_sheet", "finished_sheet", "own_numbers"]


def _paper_for(w_mm: float, h_mm: float) -> tuple[str, tuple]:
    for name in ("A4", "A3", "A2", "A1", "A0"):
        pw, ph = PAPER_MM[name]
        if w_mm <= pw and h_mm <= ph:
            return name, (pw, ph)
    raise ValueError(f"a {w_mm:.0f} × {h_mm:.0f} mm sheet does not fit A0; the valid range is up to 1189 × 841 mm")


#: the sheet is trimmed this far outside the working area's upper and lower boundary lines, mm
#: (guide §6 after step 9: 0.5–1.0 cm; step 5 says 1–1.5 cm — the book takes the 1 cm both allow)
TRIM_MM = 10.0
#: the page's margins around the trimmed mosaic, mm: above (title, scale), below (scale bar, year, names), sides
_TOP_MM, _BOTTOM_MM, _SIDE_MM = 48.0, 42.0, 6.0


def sheet_size_mm(fs: mo.Fotoschema, *, working_area: bool = True) -> tuple:
    """(width, height) of the mosaic on the sheet, mm: the prints' extent, trimmed 1 cm outside the working area."""
    x0, x1, y0, y1 = fs.extent_mm
    if working_area:
        lines = fs.working_area_lines()
        y1 = min(y1, float(lines[0][:, 1].max()) + TRIM_MM)
        y0 = max(y0, float(lines[1][:, 1].min()) - TRIM_MM)
    return x1 - x0, y1 - y0


def sheet_paper(fs: mo.Fotoschema, *, working_area: bool = True) -> tuple:
    """The smallest ISO A sheet (landscape) that holds the fotoschema at true size with its marginalia: (name, (w, h) mm)."""
    w, h = sheet_size_mm(fs, working_area=working_area)
    return _paper_for(w + 2 * _SIDE_MM, h + _TOP_MM + _BOTTOM_MM)


def sheet_figure(fs: mo.Fotoschema, image, extent_mm, *, made_by: str = "", checked_by: str = "",
                 year: int | None = None, place: str = "", english: bool = True, scale_m: float | None = None,
                 working_area: bool = True):
    """The finished fotoschema with its marginalia (зарамочное оформление), guide §6 step 9 and appendix.

    The mosaic is drawn at true size — one sheet millimetre is one millimetre
    of paper — on the smallest ISO A sheet (landscape) that holds it with the
    margins (:func:`sheet_paper`), so the PDF prints at the fotoschema's scale.
    With ``working_area`` (default) the boundary lines of the working area are
    drawn in ink along the middle of the side overlaps and the mosaic is trimmed
    1 cm outside them (guide §6, after step 9).  Above it the title
    "ФОТОСХЕМА" (and "Photo mosaic" if ``english``) and the mean scale
    "М 1:m" rounded to hundreds as in the guide's appendix ("M 1: 13000"); under
    it a scale bar, the year it was made and "Выполнил / made by",
    "Проверил / checked by".  With ``english=False`` every text is Russian (the scale bar in "м", no footer),
    as the guide's sample.

    Parameters
    ----------
    scale_m : the mean scale denominator to sign the sheet with (the one the
        student computed by (6.1)); default: the fotoschema's own, from the
        exact positions of its four points (:attr:`aerophoto.mosaic.ScaleCheck.m`)

    Returns
    -------
    matplotlib.figure.Figure (not attached to pyplot; save it with :func:`export_sheet`);
    ``fig.aerophoto_paper`` is the sheet's name ("A3").
    """
    from matplotlib.figure import Figure
    from matplotlib.backends.backend_agg import FigureCanvasAgg

    x0, x1, _y0, _y1 = fs.extent_mm
    w, h = sheet_size_mm(fs, working_area=working_area)
    if working_area:
        lines = fs.working_area_lines()
        y1 = min(fs.extent_mm[3], float(lines[0][:, 1].max()) + TRIM_MM)
        y0 = y1 - h
    else:
        lines, y0, y1 = None, fs.extent_mm[2], fs.extent_mm[3]
    top, bottom, side = _TOP_MM, _BOTTOM_MM, _SIDE_MM
    name, (pw, ph) = _paper_for(w + 2 * side, h + top + bottom)
    import matplotlib as mpl

    with mpl.rc_context({"figure.constrained_layout.use": False, "figure.autolayout": False}):
        fig = Figure(figsize=(pw / 25.4, ph / 25.4))
    # axes placed by hand, at true size: a do-nothing engine (with None, savefig would restore the
    # rcParams' constrained layout after its first save)
    from matplotlib.layout_engine import PlaceHolderLayoutEngine

    fig.set_layout_engine(PlaceHolderLayoutEngine(adjust_compatible=True, colorbar_gridspec=True))
    FigureCanvasAgg(fig)
    left = (pw - w) / 2.0
    base = bottom + (ph - top - bottom - h) / 2.0
    ax = fig.add_axes((left / pw, base / ph, w / pw, h / ph))
    ax.imshow(image, cmap="gray", vmin=0, vmax=1, origin="lower", extent=extent_mm, interpolation="antialiased")
    if lines is not None:
        for ln in lines:
            ax.plot(ln[:, 0], ln[:, 1], color="black", lw=0.8)
    ax.set_xlim(x0, x1)
    ax.set_ylim(y0, y1)
    ax.set_axis_off()
    ax.set_aspect("auto")
    # a neat line round the mosaic, 0.5 mm outside
    fx = lambda mm: mm / pw  # noqa: E731
    fy = lambda mm: mm / ph  # noqa: E731
    from matplotlib.patches import Rectangle

    fig.add_artist(Rectangle((fx(left - 2), fy(base - 2)), fx(w + 4), fy(h + 4), fill=False, lw=1.2,
                             transform=fig.transFigure))
    yr = datetime.date.today().year if year is None else int(year)
    m_sign = fs.scale.m if scale_m is None else float(scale_m)
    m_rounded = int(round(m_sign / 100.0) * 100)
    m_txt = fmt_count(m_rounded, lang="ru")
    cx = 0.5
    fig.text(cx, fy(ph - 16), "ФОТОСХЕМА", ha="center", va="center", fontsize=26, fontweight="bold")
    if english:
        fig.text(cx, fy(ph - 26), "Photo mosaic (single strip, photos "
                 f"{fs.numbers[0]}–{fs.numbers[-1]})", ha="center", va="center", fontsize=13)
    fig.text(cx, fy(base + h + 8), f"М 1:{m_txt}", ha="center", va="center", fontsize=15, fontweight="bold")
    # scale bar: a round ground length close to a fifth of the mosaic
    ground_len = w / 5.0 * m_sign / 1000.0
    step = 10 ** math.floor(math.log10(ground_len))
    bar_m = max(step, round(ground_len / step) * step)
    bar_mm = bar_m * 1000.0 / m_sign
    by = base - 12.0
    bx = left
    from matplotlib.lines import Line2D

    fig.add_artist(Line2D([fx(bx), fx(bx + bar_mm)], [fy(by), fy(by)], lw=3, color="black",
                          transform=fig.transFigure))
    for t in (0.0, 0.5, 1.0):
        fig.add_artist(Line2D([fx(bx + t * bar_mm)] * 2, [fy(by - 1.5), fy(by + 1.5)], lw=1.2, color="black",
                              transform=fig.transFigure))
    fig.text(fx(bx + bar_mm + 3), fy(by), f"{fmt_count(round(bar_m), lang='ru')} м", va="center", fontsize=10)
    made = f"Фотосхема изготовлена в {yr} г." + (f" ({place})" if place else "")
    fig.text(fx(left), fy(by - 12), made + (f"  ·  made in {yr}" if english else ""), fontsize=11, va="center")
    rx = left + w
    fig.text(fx(rx), fy(by), f"Выполнил{' (made by)' if english else ''}: {made_by or '________________'}",
             fontsize=11, ha="right", va="center")
    fig.text(fx(rx), fy(by - 12), f"Проверил{' (checked by)' if english else ''}: {checked_by or '________________'}",
             fontsize=11, ha="right", va="center")
    if english:  # the guide's sample (appendix) has no such line: the Russian sheet leaves it out
        fig.text(1 - fx(6), fy(5), f"{name}, mosaic drawn at 1:{m_txt}", fontsize=7, ha="right", va="bottom",
                 color="#777777")
    fig.aerophoto_paper = name
    return fig


def export_sheet(fig, folder, stem: str = "fotoschema", *, overwrite: bool = False, dpi: int = 150) -> dict:
    """Write the sheet as ``<folder>/<stem>.png`` and ``<folder>/<stem>.pdf``.

    Existing files are never replaced silently: with ``overwrite=False`` (the
    default) an existing file raises FileExistsError naming it.  The folder is
    created if needed.  Returns ``{"png": Path, "pdf": Path}``.
    """
    folder = Path(folder)
    if not stem or any(c in stem for c in "/\\"):
        raise ValueError(f"stem = {stem!r} must be a plain file name without folders")
    dpi = int(dpi)
    if not 50 <= dpi <= 600:
        raise ValueError(f"dpi = {dpi} is outside the valid range 50 ≤ dpi ≤ 600")
    paths = {"png": folder / f"{stem}.png", "pdf": folder / f"{stem}.pdf"}
    if not overwrite:
        for p in paths.values():
            if p.exists():
                raise FileExistsError(f"{p} exists; choose another stem or pass overwrite=True to replace it")
    folder.mkdir(parents=True, exist_ok=True)
    fig.savefig(paths["png"], dpi=dpi, format="png")
    fig.savefig(paths["pdf"], format="pdf")
    return paths


# =========================================================================== the student's own fotoschema
@functools.lru_cache(maxsize=2)
def _own_prints(i: int, f_mm: float, frame_mm: float, m: float, px_percent: float, n_px: int) -> tuple:
    from .. import render
    from ..labs.own import own_strip_of

    strip, site = own_strip_of(i, f_mm, frame_mm, m, px_percent)
    return tuple(render.render_strip(site, strip, n_px))


def own_prints(variant, n_px: int = 1024) -> tuple:
    """The student's four prints (:func:`aerophoto.render.render_strip` of their own strip), cached per variant.

    ``n_px`` × ``n_px`` pixels each (1024: 0.18 mm a pixel on the 18 cm frame).
    """
    from .._validate import check_int_range

    n = check_int_range("n_px", n_px, 64, 4096)
    return _own_prints(int(variant.i), float(variant.f_mm), float(variant.frame_mm), float(variant.m),
                       float(variant.px_percent), n)


@functools.lru_cache(maxsize=4)
def _own_sheet_image(variant, px_per_mm: float) -> tuple:
    from ..labs.ch05 import own_fotoschema

    own = own_fotoschema(variant)
    return mo.sheet_raster(own.fs, own.site, px_per_mm, photos=list(own_prints(variant)))


def own_sheet_image(variant, px_per_mm: float = 5.0) -> tuple:
    """The student's fotoschema glued from their rendered prints: ``(image, extent_mm)`` (:func:`aerophoto.mosaic.sheet_raster`).

    At 5 px/mm the sheet of four prints is about 2000 × 900 pixels (0.6 s to glue, after 1–2.5 s to render
    the prints); cached per variant.
    """
    from .._validate import check_range

    r = check_range("px_per_mm", px_per_mm, 0.5, 10.0, unit="px/mm")
    return _own_sheet_image(variant, float(r))


def own_sheet_figure(variant, ax=None, *, px_per_mm: float = 5.0):
    """The student's fotoschema for measuring: prints, cuts, numbered check points, the four points of the scale.

    Shows what the student works **from** — where the cuts run, where the
    details were pricked along them (numbered as in the readings of task 05.1),
    and the points 36a … 39b of the mean scale (task 05.2) — and nothing they
    must compute: no mismatch ΔI and no scale.  Returns the Figure.
    """
    from ..labs.ch05 import own_fotoschema

    own = own_fotoschema(variant)
    fs = own.fs
    image, extent = own_sheet_image(variant, px_per_mm)
    fig, ax = plots.new_axes(ax, figsize=(11.0, 5.6))
    C = plots.COLORS
    ax.imshow(image, cmap="gray", vmin=0, vmax=1, origin="lower", extent=extent, interpolation="antialiased")
    ax.set_aspect("equal")
    ax.grid(False)
    for s in fs.seams:
        ax.plot(s.cut_mm[:, 0], s.cut_mm[:, 1], color=_CUT, lw=1.6, path_effects=_CUT_EDGE)
    d = own.details
    ax.plot(d.contour_mm[:, 0], d.contour_mm[:, 1], linestyle="none", marker="o", ms=5, mfc="none", mew=1.4,
            color=C["yellow"], label="details pricked along the cuts (task 05.1)")
    for p, k in zip(d.contour_mm, d.point):
        ax.annotate(str(k), p, xytext=(-3, 0), textcoords="offset points", ha="right", va="center", fontsize=8,
                    color="black", bbox=dict(boxstyle="round,pad=0.1", fc="white", ec="none", alpha=0.75))
    for s in fs.seams:
        top = s.cut_mm[np.argmax(s.cut_mm[:, 1])]
        ax.annotate(f"cut {s.numbers[0]}/{s.numbers[1]}", top, xytext=(0, 4), textcoords="offset points",
                    ha="center", va="bottom", fontsize=10, color=C["orange"], fontweight="bold")
    P = fs.scale.sheet_mm
    ax.plot(P[:, 0], P[:, 1], linestyle="none", marker="s", ms=9, mfc="none", mew=2.0, color=C["skyblue"],
            label="points of the mean scale (task 05.2)")
    for name, p in zip(fs.scale.names, P):
        ax.annotate(name, p, xytext=(6, 6), textcoords="offset points", fontsize=11, fontweight="bold",
                    color="black", bbox=dict(boxstyle="round,pad=0.15", fc="white", ec=C["skyblue"], alpha=0.85))
    o = fs.principal_points_mm()
    ax.plot(o[:, 0], o[:, 1], "+", color=C["vermillion"], ms=11, mew=2.0, label="principal points o")
    for n, p in zip(fs.numbers, o):
        ax.annotate(str(n), p, xytext=(5, -14), textcoords="offset points", fontsize=11, fontweight="bold",
                    color=C["vermillion"])
    x0, x1, y0, y1 = fs.extent_mm
    ax.set_xlim(x0 - 2, x1 + 2)
    ax.set_ylim(y0 - 2, y1 + 10)
    ax.set_xlabel("along the strip, mm (from the principal point of photo %d)" % fs.numbers[0])
    ax.set_ylabel("across, mm")
    ax.set_title(_t("Your fotoschema: photos {a}–{b}, f = {f} mm, photos at {scale}", a=fs.numbers[0],
                    b=fs.numbers[-1], f=fmt_spec(fs.camera.f_mm, "{:g}"), scale=fmt_scale(fs.m_design)))
    ax.legend(loc="upper center", bbox_to_anchor=(0.5, -0.12), ncol=3, fontsize=9, frameon=False)
    return fig


def _made_by(variant, name: str) -> str:
    name = str(name or "").strip()
    rb = getattr(variant, "record_book", "")
    rb = "" if not rb or str(rb).startswith("(") else f"record book {rb}"
    return ", ".join(x for x in (name, rb) if x)


def student_sheet(variant, made_by: str = "", *, checked_by: str = "", year: int | None = None,
                  scale_m: float | None = None, px_per_mm: float = 5.0):
    """The finished fotoschema of a variant with the appendix's marginalia (for the student's report).

    The student's own strip glued from their prints (:func:`own_sheet_image`),
    trimmed to the working area, at true size on the A sheet that holds it
    (A3 for every variant), titled, signed "М 1:m" with the mean scale rounded
    to hundreds, the year, "made by" ``made_by`` and the variant's record
    book, "checked by" ``checked_by``.

    Parameters
    ----------
    variant : the student's Variant (its record book goes on the sheet)
    made_by : the student's name
    scale_m : the mean scale to sign with; default the reference value of task 05.2 (6.1 from the
        student's readings, :func:`aerophoto.labs.ch05.answers_of`) — the instructor's and the report's side
    """
    from ..labs.ch05 import answers_of, own_fotoschema

    own = own_fotoschema(variant)
    image, extent = own_sheet_image(variant, px_per_mm)
    m_sign = answers_of(variant)["m_mean"] if scale_m is None else float(scale_m)
    return sheet_figure(own.fs, image, extent, made_by=_made_by(variant, made_by), checked_by=checked_by,
                        year=year, scale_m=m_sign)


def finished_sheet(variant, made_by: str = "", *, answered: bool, checked_by: str = "", folder=None,
                   preview_dpi: int = 60):
    """Show and write the student's finished sheet — once task 05.2 (the mean scale it is signed with) is answered.

    ``answered`` is the notebook's ``checks.passed("task-05-2")``.  Without it
    a line says what to do first (the sheet carries the mean scale, a graded
    value).  With it the sheet (:func:`student_sheet`) is written as PNG and
    PDF at true size into ``folder`` (default: a fresh temporary folder; an
    existing file is never overwritten) and shown.  Returns the shown figure
    (:class:`aerophoto.plots.StaticFigure`) or None.
    """
    import tempfile

    if not answered:
        print("Answer task 05.2 first: the sheet is signed with the mean scale you compute there.")
        return None
    fig = student_sheet(variant, made_by, checked_by=checked_by)
    rb = "".join(c for c in str(getattr(variant, "record_book", "")) if c.isalnum() or c in "-_") or f"v{variant.i:02d}"
    files = export_sheet(fig, folder if folder is not None else tempfile.mkdtemp(prefix="fotoschema-"),
                         f"fotoschema_{rb}")
    print(f"{fig.aerophoto_paper} sheet at true size written to:", *files.values(), sep="\n  ")
    return plots.static(fig, alt=f"Your finished fotoschema on an {fig.aerophoto_paper} sheet: the glued prints "
                                 f"{own_numbers(variant)} trimmed to the working area, titled ФОТОСХЕМА, signed with "
                                 "its mean scale, the year, and who made and who checked it", dpi=preview_dpi)


def own_numbers(variant) -> str:
    """The photo numbers of the student's strip as text ("36–39")."""
    from ..labs.own import FIRST_NUMBER, N_PHOTOS

    return f"{FIRST_NUMBER}–{FIRST_NUMBER + N_PHOTOS - 1}"
