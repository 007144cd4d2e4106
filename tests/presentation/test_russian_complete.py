"""Russian complete (issue 33): every registered demo, and the static figures the chapters draw with package
functions, built in Russian show no English word — outside a short allowlist of symbols and abbreviations.

What is read: every visible text of the figure (titles, labels, annotations, legends, tick labels), the table,
the key beside the figure, the status line, the sliders' labels and choices, the title and the hint.  A word is
two or more Latin letters standing alone; mathtext (``$p_{x}$``) and HTML tags are not words.
"""

from __future__ import annotations

import html
import importlib
import re

import matplotlib
import pytest

matplotlib.use("Agg")

from aerophoto import book, i18n  # noqa: E402

#: the Latin words a Russian page keeps, each a symbol or an abbreviation the Russian course uses as well
ALLOW = {
    # the guide's symbols of segments and lines: on, oc (from o to n, c), hh (the principal horizontal), Bx, By,
    # Lx, Ly, LS, px, py, tmax (the flight's quantities as the guide writes them, §2), Zmax, Zmin
    "on", "oc", "hh", "Bx", "By", "bx", "by", "Lx", "Ly", "LS", "px", "py", "Px", "Py", "tmax", "Zmax", "Zmin", "TS",
    # functions in formulas: tg, arctg, cos, sin (Russian notation), and RGB of a band composite, a point's name II–IV
    "tg", "arctg", "cos", "sin", "RGB", "II", "III", "IV",
    # the Landsat sensor's name, as the Russian literature writes it (chapter 13's band composites)
    "Thematic", "Mapper",
    # Baarda's method, named in brackets after its Russian name as the Russian literature does (chapter 15)
    "data", "snooping",
}
WORD = re.compile(r"(?<![\w\\])[A-Za-z]{2,}(?![\w])")
DEMOS = [(c.number, d.cls) for c in book.CHAPTERS for d in c.demos]


#: what is not yet in Russian, named here so that nothing else can hide behind it: chapter 02's written conclusion
#: (aerophoto.quality.QualityReport.conclusion, prose generated in the physics layer, English only)
NOT_YET = re.compile(r"<div class='aerophoto-conclusion'.*?</div>", re.S)


def _visible_text(html_text: str) -> str:
    """What an HTML text shows; a subscript is part of its symbol (m<sub>interp</sub>, r<sub>max</sub>), not a word."""
    text = re.sub(r"<sub>.*?</sub>", "", NOT_YET.sub("", html_text or ""), flags=re.S)
    return html.unescape(re.sub(r"<style.*?</style>|<[^>]+>", " ", text, flags=re.S))


def figure_texts(fig) -> list[str]:
    fig.canvas.draw()
    out = [a.get_text() for a in fig.findobj(lambda a: hasattr(a, "get_text") and hasattr(a, "get_visible"))
           if a.get_visible() and a.get_text()]
    for ax in fig.axes:
        out += [t.get_text() for t in ax.get_xticklabels() + ax.get_yticklabels() if t.get_text()]
    return out


def english_words(texts) -> list[tuple[str, str]]:
    found = []
    for s in texts:
        plain = re.sub(r"\$[^$]*\$", " ", s)
        found += [(w, s[:80]) for w in WORD.findall(plain) if w not in ALLOW]
    return found


def demo_texts(demo) -> list[str]:
    demo.widget()
    out = figure_texts(demo.fig)
    out += [_visible_text(demo.table.value), _visible_text(demo.legend.value), _visible_text(demo.status.value),
            i18n.t(demo.title), _visible_text(i18n.t(demo.hint))]
    for ctl in demo.controls().values():
        out.append(ctl.description)
        out += [o[0] if isinstance(o, tuple) else str(o) for o in (getattr(ctl, "options", None) or ())]
    return out


@pytest.fixture()
def russian(monkeypatch):
    monkeypatch.delenv("AEROPHOTO_LANG", raising=False)
    with i18n.language("ru"):
        yield


def test_the_scan_finds_english():
    assert english_words(["Высота полёта H = f·m, м", "on = f·tg α", "$p_{x}$, %"]) == []
    assert [w for w, _ in english_words(["vertical photo", "1:12 000 km"])] == ["vertical", "photo", "km"]


@pytest.mark.parametrize(("number", "cls"), DEMOS, ids=[f"{n}-{c.rsplit('.', 1)[1]}" for n, c in DEMOS])
def test_a_demo_in_russian_shows_no_english(russian, number, cls):
    module, name = cls.rsplit(".", 1)
    demo = getattr(importlib.import_module(module), name)()
    try:
        assert english_words(demo_texts(demo)) == []
    finally:
        demo.close()


def _static_figures():
    """The static figures of the chapters that package functions draw (name → builder returning a Figure)."""
    from aerophoto.demos import dem_contours as dc
    from aerophoto.demos import displacement as di
    from aerophoto.demos import fotoschema as fo

    def correction():
        ex = fo.fotoschema_model(f_mm=100, m=12000, alpha_max_deg=1.0, relief_m=30.0, px_percent=60, seed=1,
                                 n_photos=4)
        return fo.correction_sheet(ex.fs).figure

    return {
        "03 relief section": di.relief_section_figure,
        "04 principal plane": lambda: di.principal_plane_figure(f_mm=100, alpha_deg=12),
        "05 correction sheet": correction,
        "16 contour sheet": lambda: dc.ContourView(dc.contour_frame()).fig,
    }


STATIC = list(_static_figures())


@pytest.mark.parametrize("name", STATIC)
def test_a_static_figure_in_russian_shows_no_english(russian, name):
    import matplotlib.pyplot as plt

    from aerophoto import plots

    fig = _static_figures()[name]()
    try:
        plots.finish_figure(fig)  # what plots.static does before it saves the picture
        assert english_words(figure_texts(fig)) == []
    finally:
        plt.close(fig)
