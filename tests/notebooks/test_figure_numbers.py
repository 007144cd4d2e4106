"""A number a figure states (title, alt text, the text beside it) comes from one computed variable.

Chapter 09's grids figure once titled its left panel "largest node miss 1.36 mm" while the text and the alt text
said every node sits on its circle: the title compared the central grid with the images of the plan's *equal-part*
grid.  Now ``plan_correction.grid_node_misses`` is the one source: the titles print it, the build script writes it
into the text and the alt text, and this test reads all three back.
"""

import json
import re
from pathlib import Path

import matplotlib
import pytest

matplotlib.use("Agg")

from aerophoto.demos import plan_correction as pc  # noqa: E402

NB09 = Path(__file__).resolve().parents[2] / "notebooks" / "09_plan_correction.ipynb"
NUM = r"(\d+\.\d+) mm"


def _cell(nb, cell_id):
    return next("".join(c["source"]) for c in nb["cells"] if c.get("id") == cell_id)


@pytest.fixture(scope="module")
def titles():
    import matplotlib.pyplot as plt
    fig = pc.grids_figure(alpha_deg=10.0, n=4)
    out = [ax.get_title() for ax in fig.axes[:2]]
    plt.close(fig)
    return out


def test_titles_print_the_misses(titles):
    miss = pc.grid_node_misses(alpha_deg=10.0, n=4)
    from aerophoto.i18n.numfmt import parse_number

    got = [parse_number(re.search(r"largest node miss " + NUM, t).group(1)) for t in titles]
    assert got == [round(miss["central"], 2), round(miss["proportional"], 2)]


def test_the_claims_are_true():
    """Central directions are exact (photo and plan drawn alike); equal parts are not, by millimetres at 10°."""
    miss = pc.grid_node_misses(alpha_deg=10.0, n=4)
    assert miss["central"] < 1e-6
    assert 2.0 < miss["proportional"] < 6.0
    # the equal-part miss does not shrink with n (the chapter's claim "but not on n")
    assert pc.grid_node_misses(alpha_deg=10.0, n=8)["proportional"] == pytest.approx(miss["proportional"], rel=0.3)


def test_text_and_alt_say_what_the_titles_say(titles):
    nb = json.loads(NB09.read_text(encoding="utf-8"))
    in_titles = [re.search(NUM, t).group(1) for t in titles]
    text = _cell(nb, "grids-theory")
    alt = _cell(nb, "figure-grids")
    for where in (text, alt):
        assert re.findall(NUM, where) == in_titles, where
    assert "several millimetres" not in alt
