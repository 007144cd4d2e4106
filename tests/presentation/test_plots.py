"""Shared plotting helpers: the fast PNG frames of live figures."""

import io

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.backends.backend_webagg_core import FigureCanvasWebAggCore
from matplotlib.figure import Figure
from PIL import Image

from aerophoto import plots


def _web_figure():
    fig = Figure(figsize=(4, 3), dpi=100)
    FigureCanvasWebAggCore(fig)
    ax = fig.add_subplot()
    rng = np.random.default_rng(3)
    img = ax.imshow(rng.random((60, 80)), cmap="gray")  # photo-like noise compresses badly
    (line,) = ax.plot([0, 79], [0, 59], color="C1")
    return fig, img, line


def _frame(fig):
    FigureCanvasAgg.draw(fig.canvas)  # render (the web canvas's own draw also pushes to a browser)
    fig.canvas._png_is_old = True  # as the web canvas's draw sets it
    return fig.canvas.get_diff_image()


def _pixels(png):
    return np.asarray(Image.open(io.BytesIO(png)).convert("RGBA"))


def test_fast_frames_send_the_same_pixels_as_matplotlib():
    fast, img_f, line_f = _web_figure()
    slow, img_s, line_s = _web_figure()
    assert plots.fast_frames(fast) is True
    ratios = []
    for step in range(4):
        if step:  # change a part of the picture: the next frame is a diff
            for img, line in ((img_f, line_f), (img_s, line_s)):
                line.set_ydata([step * 5, 59 - step * 5])
                if step == 2:
                    img.set_data(np.flipud(img.get_array()))
        png_f = _frame(fast)
        png_s = _frame(slow)
        # identical pixels (full frame or diff with transparent unchanged pixels)
        np.testing.assert_array_equal(_pixels(png_f), _pixels(png_s))
        ratios.append(len(png_f) / len(png_s))
    # the first frame is full; later ones are diffs of the same size as matplotlib's
    np.testing.assert_array_equal(fast.canvas._last_buff, slow.canvas._last_buff)
    # nothing new to send: both return None
    assert fast.canvas.get_diff_image() is None and slow.canvas.get_diff_image() is None
    # level 1 trades a little size for speed: never more than 1.5× matplotlib's file
    assert max(ratios) < 1.5


def test_fast_frames_leaves_other_canvases_alone_and_checks_the_level():
    fig = Figure()
    FigureCanvasAgg(fig)
    assert plots.fast_frames(fig) is False
    assert "get_diff_image" not in vars(fig.canvas)
    web, *_ = _web_figure()
    with pytest.raises(ValueError, match="level = 12 .* 0 … 9"):
        plots.fast_frames(web, level=12)


# ----------------------------------------------------------------------- tables in the book's number format
def test_html_table_writes_every_number_in_the_books_format():
    import pandas as pd

    from aerophoto import i18n
    from aerophoto.i18n.numfmt import GROUP, MINUS, numbers_in

    df = pd.DataFrame([("Flying height H = f·m", "m", 1200.0), ("Photo scale 1/m (vertical)", "1:", 12043.4),
                       ("Isocentre oc = −f·tg(α/2)", "mm", -0.0004), ("points with |δh| > 0.2 mm", "", 70),
                       ("forward overlap p_x", "%", -1.8), ("note", "", "-0.00 of 12043.5")],
                      columns=["quantity", "unit", "value"], dtype=object).set_index("quantity")
    precision = {"Flying height H = f·m": 0, "Isocentre oc = −f·tg(α/2)": 2}
    en = plots.html_table(df, precision=precision, float_format="{:.2f}")
    assert ">1200<" in en and f">12{GROUP}043<" in en  # a scale row: whole, grouped from five digits
    assert ">0.00<" in en and "−0.00" not in en and "-0.00" not in en  # no signed zero
    assert ">70<" in en and "70.00" not in en  # a count is whole
    assert f">{MINUS}1.80<" in en  # a true minus
    assert "p<sub>x</sub>" in en  # a symbol's subscript
    assert f"0.00 of 12{GROUP}043.5" in en  # numbers written by Python inside a text
    with i18n.language("ru"):
        ru = plots.html_table(df, precision=precision, float_format="{:.2f}")
    assert ">м<" in ru and f">{MINUS}1,80<" in ru and ">1200<" in ru  # the unit and the decimal comma
    assert 12043.0 in numbers_in(ru, lang="ru") and -1.8 in numbers_in(ru, lang="ru")


def test_subscripts_in_html_and_in_figure_texts():
    assert plots.html_subscripts("p_x, mm") == "p<sub>x</sub>, mm"
    assert plots.html_subscripts("isoline h_c–h_c") == "isoline h<sub>c</sub>–h<sub>c</sub>"
    assert plots.html_subscripts("m_ЦМР") == "m<sub>ЦМР</sub>" and plots.html_subscripts("$λ_{t}$") == "λ<sub>t</sub>"
    assert plots.math_subscripts("λ_t, °") == "$λ_{t}$, °" and plots.math_subscripts("guide_table") == "guide_table"
    assert plots.html_subscripts("a < b & c") == "a &lt; b &amp; c"


def test_the_guides_audits_render_in_the_books_number_format():
    """guide.render with the number format the notebooks get (plots.register_table_display): no 11934.0, no
    hyphen-minus, grouping from five digits; without it the audit renders as before (whole floats whole)."""
    import re

    from aerophoto import guide
    from aerophoto.i18n.numfmt import MINUS, fmt_text

    audit = guide.ch06.table8()
    plain = guide.render(audit)
    shown = guide.render(audit, number=lambda text: fmt_text(text, lang="en"))
    cells = re.findall(r"<td>([^<]*)</td>", shown)
    assert cells and not any(re.fullmatch(r"-?\d+\.0", c) for c in cells)  # a whole number is whole
    assert not any(re.search(r"(?<![\w])-\d", c) for c in cells)  # a true minus
    assert not any(re.search(r"(?<![\d.])\d{5}", c) for c in cells)  # grouped from five digits
    assert MINUS in shown or "-" not in "".join(re.findall(r"<td>([^<]*)</td>", plain))
