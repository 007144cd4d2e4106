"""Every demo's series stay apart for the common colour-vision deficiencies (issue 33).

A *series* is a labelled artist of a demo's figure (what its key names: a line, a marker kind, a set of arrows).
Two series that the demo tells apart by colour alone (CIEDE2000 ≥ 5 to normal vision, and shapes that do not tell
them apart: :func:`apart_by_shape`) must stay at least :data:`MIN_DELTA_E` apart as seen with deuteranopia and
with protanopia (Machado et al. 2009 at full severity, :mod:`.cvd`).

The threshold: a ΔE00 of about 1 is just noticeable between two large patches side by side, but marks as small
as a demo's (a 1.5 px line, a 7 pt marker, on a projector) need several times more (Szafir & Stone's size model
of colour difference); the issue's observed failure — chapter 05's orange cut lines against its vermilion dots,
which a deuteranope could not tell apart — is ΔE00 12.5 under deuteranopia.  15 fails that pair with a margin,
and holds for most of the Okabe–Ito palette (its closest pairs, orange–yellow 11.6 and blue–purple 12.2, must
then differ in shape too).
"""

from __future__ import annotations

import importlib
import itertools

import matplotlib
import pytest

matplotlib.use("Agg")

from matplotlib.collections import Collection, LineCollection, PathCollection  # noqa: E402
from matplotlib.colors import to_hex  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402
from matplotlib.quiver import Quiver  # noqa: E402

from aerophoto import book  # noqa: E402

from .cvd import delta_e  # noqa: E402

MIN_DELTA_E = 15.0
#: to normal vision, colours this close are one colour (a demo that does not mean them to differ)
SAME_COLOUR = 5.0
DEFICIENCIES = ("deuteranopia", "protanopia")
DEMOS = sorted({d.cls for c in book.CHAPTERS for d in c.demos})


def _dash(ls) -> str:
    return {"-": "solid", "--": "dashed", ":": "dotted", "-.": "dashdot"}.get(ls, str(ls))


def _first_colour(values):
    import numpy as np

    c = np.atleast_2d(values) if values is not None and len(values) else None
    if c is None or c.shape[-1] not in (3, 4):
        return None
    visible = [row for row in c if len(row) == 3 or row[3] > 0]
    return to_hex(visible[0]) if visible else None


def series(fig) -> list[tuple[str, tuple, str]]:
    """(label, shape, colour) of every labelled artist of ``fig`` (colour-mapped artists are fields, not series);
    the shape's last entry is the artist's Axes (series are compared where they are drawn together)."""
    out = []
    for k, ax in enumerate(fig.axes):
        for art in [*ax.lines, *ax.collections]:
            label = art.get_label() or ""
            if not label or label.startswith("_"):
                continue
            if isinstance(art, Line2D):
                marker = art.get_marker()
                if marker not in (None, "None", "", " ") and art.get_linestyle() in ("None", "none", "", " "):
                    face = art.get_markerfacecolor()
                    colour = art.get_markeredgecolor() if face in ("none", "None") else face
                    shape = ("marker", str(marker), face in ("none", "None"))
                else:
                    colour, shape = art.get_color(), ("line", _dash(art.get_linestyle()))
                out.append((label, (*shape, k), to_hex(colour)))
            elif isinstance(art, Collection):
                if art.get_array() is not None and not isinstance(art, Quiver):
                    continue
                if isinstance(art, Quiver):
                    shape, colour = ("arrow",), _first_colour(art.get_facecolor())
                elif isinstance(art, LineCollection):
                    styles = art.get_linestyle()
                    dashed = "solid" if not styles or styles[0][1] is None else f"dashed{tuple(styles[0][1])}"
                    shape, colour = ("line", dashed), _first_colour(art.get_edgecolor())
                elif isinstance(art, PathCollection):
                    shape = ("marker", "scatter")
                    colour = _first_colour(art.get_facecolor()) or _first_colour(art.get_edgecolor())
                else:
                    shape, colour = ("patch",), _first_colour(art.get_facecolor())
                if colour is not None:
                    out.append((label, (*shape, k), colour))
    return out


def apart_by_shape(a: tuple, b: tuple) -> bool:
    """Whether two series' shapes tell them apart without colour: markers of different glyphs (or one open, one
    filled), lines of different dash patterns, arrows against anything else.  A line and a marker are *not*: a short
    cut line and a dot of nearly one colour merge on a photo (chapter 05's cuts and cut-outs did)."""
    if a[-1] != b[-1]:
        return True  # drawn in different axes: not side by side
    if (a[0] == "arrow") != (b[0] == "arrow"):
        return True
    if {a[0], b[0]} == {"patch", "line"}:  # a filled area against a dashed outline: apart; a solid one: not
        line = a if a[0] == "line" else b
        return line[1] != "solid"
    return a[0] == b[0] and a[0] in ("marker", "line") and a != b


def clashes(items) -> list[str]:
    """Pairs told apart by colour only that merge for a deficiency: 'label colour / label colour: ΔE kind'."""
    bad = []
    for (la, sa, ca), (lb, sb, cb) in itertools.combinations(items, 2):
        if apart_by_shape(sa, sb) or delta_e(ca, cb) < SAME_COLOUR:
            continue
        for kind in DEFICIENCIES:
            d = delta_e(ca, cb, kind)
            if d < MIN_DELTA_E:
                bad.append(f"{la!r} {ca} / {lb!r} {cb}: ΔE00 {d:.1f} with {kind}")
    return bad


def test_the_measure_tells_the_known_failure_and_the_fixes():
    """The observed failure (orange vs vermilion) fails the threshold; black vs Okabe–Ito orange passes."""
    from aerophoto.plots import COLORS as C

    assert delta_e(C["orange"], C["vermillion"], "deuteranopia") < MIN_DELTA_E
    assert delta_e(C["black"], C["orange"], "deuteranopia") > 3 * MIN_DELTA_E
    assert delta_e(C["blue"], C["orange"], "protanopia") > MIN_DELTA_E
    assert delta_e("#ff0000", "#00ff00", "normal") > 80  # red and green: far apart to normal vision …
    assert delta_e("#d00000", "#7a8000", "deuteranopia") < 10  # … a dull red and an olive merge for a deuteranope
    items = [("a", ("line", "solid", 0), C["orange"]), ("b", ("line", "solid", 0), C["vermillion"]),
             ("c", ("marker", "o", False, 0), C["vermillion"]), ("d", ("line", "solid", 1), C["vermillion"])]
    assert len(clashes(items)) == 2 and "'a'" in clashes(items)[0]  # line/line and line/dot; dot vs line 'a'
    shaped = [("a", ("marker", "o", False, 0), C["blue"]), ("b", ("marker", "^", False, 0), C["purple"])]
    assert clashes(shaped) == []  # a triangle and a dot: told apart by shape


@pytest.mark.parametrize("path", DEMOS, ids=[p.rsplit(".", 1)[1] for p in DEMOS])
def test_a_demos_series_stay_apart_with_colour_blindness(path):
    module, name = path.rsplit(".", 1)
    demo = getattr(importlib.import_module(module), name)()
    try:
        items = series(demo.fig)
        assert clashes(items) == [], items
    finally:
        demo.close()
