"""The report's figures and the student's fotoschema sheet, drawn off-screen (Agg) into the build folder.

Every figure is a :class:`matplotlib.figure.Figure` with its own Agg canvas — never pyplot, so building a
report from a notebook leaves the notebook's live backend alone — drawn in the book's style and saved
without time stamps (PNG without "Software", PDF without "CreationDate"), so the same workbook gives the
same files on every machine.

:data:`CHAPTER_FIGURES` maps a chapter number to the function that draws that chapter's figures of the
student's own photos; a chapter shows them only when the student has worked on it, and they show what the
student works *from* (their prints, their sheet for measuring), never an answer.
"""

from __future__ import annotations

from pathlib import Path

__all__ = ["CHAPTER_FIGURES", "save_png", "save_pdf", "chapter05_figures", "chapter06_figures", "sheet_files"]

_PNG_META = {"Software": None}
_PDF_META = {"CreationDate": None, "Creator": "aerophoto", "Producer": "aerophoto (matplotlib)"}


def _figure(figsize):
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure

    fig = Figure(figsize=figsize)
    FigureCanvasAgg(fig)
    return fig


def save_png(fig, path: Path, dpi: int = 110) -> Path:
    path = Path(path)
    fig.savefig(path, dpi=dpi, format="png", metadata=_PNG_META)
    return path


def save_pdf(fig, path: Path) -> Path:
    path = Path(path)
    fig.savefig(path, format="pdf", metadata=_PDF_META)
    return path


def chapter05_figures(v, folder: Path) -> list:
    """Chapter 05 (guide §6): the student's four prints, and their fotoschema as they measure on it.

    Returns ``[(path relative to the build folder, caption, width), …]``.
    """
    from ..demos import fotoschema as F
    from ..plots import style_context

    folder = Path(folder)
    out = []
    with style_context():
        photos = F.own_prints(v)
        fig = _figure((10.0, 3.0))
        axes = fig.subplots(1, len(photos))
        for ax, ph, k in zip(axes, photos, range(len(photos))):
            ax.imshow(ph.image, cmap="gray", vmin=0, vmax=1, interpolation="antialiased")
            ax.set_axis_off()
            number = ph.number if ph.number is not None else k + 1
            ax.set_title(f"снимок {number}", fontsize=11)
        save_png(fig, folder / "ch05_prints.png", dpi=100)
        out.append(("figures/ch05_prints.png",
                    f"Ваши аэроснимки {F.own_numbers(v)}, f = {v.f_mm:g} мм, 1:{v.m:,.0f} (your prints)"
                    .replace(",", " "), 1.0))
        fig = _figure((11.0, 5.6))
        ax = fig.add_subplot()
        F.own_sheet_figure(v, ax=ax)
        save_png(fig, folder / "ch05_fotoschema.png", dpi=100)
        out.append(("figures/ch05_fotoschema.png",
                    "Ваша фотосхема: порезы, точки контроля монтажа и точки масштаба "
                    "(your mosaic: cuts, check points, the four points of the mean scale)", 1.0))
    return out


def chapter06_figures(v, folder: Path) -> list:
    """Chapter 06 (guide §7): the student's strip over the site and their templates laid into the free strip.

    What the student measures from (guide figures 21, 23–24), without the error triangles, the coefficients
    or the corrections — those are their answers, in the chapter's tables.
    """
    from ..demos.reduction import own_site_figure, own_strip_figure
    from ..plots import style_context

    folder = Path(folder)
    out = []
    with style_context():
        fig = _figure((10.0, 5.0))
        own_site_figure(v, ax=fig.add_subplot())
        save_png(fig, folder / "ch06_site.png", dpi=100)
        out.append(("figures/ch06_site.png", "Ваш маршрут 36–39 над участком, наколотые точки (your strip over the "
                                              "site, the pricked points; guide fig. 21)", 0.9))
        fig = _figure((11.0, 5.0))
        own_strip_figure(v, ax=fig.add_subplot())
        save_png(fig, folder / "ch06_strip.png", dpi=100)
        out.append(("figures/ch06_strip.png", "Ваши шаблоны в свободном ряду: направления, центры, точки "
                                               "(your templates laid into the free strip; guide figs. 23–24)", 1.0))
    return out


#: chapter number → ``fn(variant, folder) -> [(src, caption, width)]``; chapters not listed have no figures
CHAPTER_FIGURES = {"05": chapter05_figures, "06": chapter06_figures}


def sheet_files(v, m_mean: float, folder: Path, *, made_by: str, checked_by: str, year: int,
                stem: str = "fotoschema") -> dict:
    """The student's fotoschema sheet at true size (guide §6 and appendix) as PDF, and a PNG preview.

    Signed with the student's own mean scale ``m_mean`` (task 05.2).  Returns ``{"pdf", "png", "paper",
    "size_mm"}``.
    """
    from ..demos import fotoschema as F

    fig = F.student_sheet(v, made_by, checked_by=checked_by, year=year, scale_m=float(m_mean))
    folder = Path(folder)
    pdf = save_pdf(fig, folder / f"{stem}.pdf")
    png = save_png(fig, folder / f"{stem}.png", dpi=60)
    paper = fig.aerophoto_paper
    return {"pdf": pdf, "png": png, "paper": paper, "size_mm": F.PAPER_MM[paper]}
