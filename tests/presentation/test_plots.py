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
