"""A live figure's frames to the browser: the book's PNG writer keeps every pixel; a photo demo's JPEG frames stay
within one just-noticeable difference of the exact picture (the measured criterion of plots.PHOTO_QUALITY)."""

import io

import numpy as np
import pytest
from matplotlib.backends.backend_agg import FigureCanvasAgg
from matplotlib.backends.backend_webagg_core import FigureCanvasWebAggCore
from matplotlib.figure import Figure
from PIL import Image

from aerophoto import plots

pytestmark = pytest.mark.usefixtures("plot_style")

PHOTO_DEMOS = [("quality", "QualityDemo", {"max_tilt_deg": 2.5}), ("fotoschema", "FotoschemaDemo", {"alpha_max_deg": 1.0}),
               ("interpretation", "ConditionsDemo", {"sun_elevation_deg": 20.0}),
               ("interpretation", "KeyDemo", {"row": 3}), ("rectification", "TransformerDemo", {"step": 3}),
               ("loupe", "LoupeDemo", {"x_mm": 20.0}), ("spectral_explorer", "SpectralExplorerDemo", {"moisture_pct": 30})]


@pytest.mark.parametrize("sparse", [False, True])
@pytest.mark.parametrize("level", [0, 1, 6])
def test_the_png_writer_keeps_every_pixel(level, sparse):
    rng = np.random.default_rng(level)
    a = rng.integers(0, 256, (37, 53, 4), dtype=np.uint8)
    if sparse:  # a blit's diff: transparent zeros but for a few pixels
        a[rng.random((37, 53)) < 0.97] = 0
    png = plots._png(a, level, sparse=sparse)
    back = Image.open(io.BytesIO(png))
    assert back.format == "PNG" and back.mode == "RGBA" and back.size == (53, 37)
    np.testing.assert_array_equal(np.asarray(back), a)


def _web_figure():
    fig = Figure(figsize=(4, 3), dpi=100, layout="none")  # a live demo's layout is frozen at its first draw
    FigureCanvasWebAggCore(fig)
    ax = fig.add_subplot()
    img = ax.imshow(np.random.default_rng(3).random((60, 80)), cmap="gray")
    (line,) = ax.plot([0, 79], [0, 59], color="C1")
    ax.set_xlim(-0.5, 79.5)  # fixed: a moved line changes only its own pixels
    ax.set_ylim(59.5, -0.5)
    return fig, img, line


def _frame(fig):
    FigureCanvasAgg.draw(fig.canvas)
    fig.canvas._png_is_old = True
    modes = []
    fig.canvas.set_image_mode = modes.append
    return fig.canvas.get_diff_image(), modes[-1]


def test_photo_frames_go_as_jpeg_only_when_most_of_the_picture_changed():
    fig, img, line = _web_figure()
    assert plots.fast_frames(fig, photo_quality=plots.PHOTO_QUALITY)
    first, mode = _frame(fig)
    assert first[:2] == b"\xff\xd8" and mode == "full"  # the first frame: the whole picture, as JPEG
    line.set_ydata([5, 54])  # a line moves: a few pixels, a lossless diff
    small, mode = _frame(fig)
    assert small[:4] == b"\x89PNG" and mode == "diff"
    img.set_data(np.flipud(img.get_array()))  # the photo changes: a JPEG of the whole picture
    big, mode = _frame(fig)
    assert big[:2] == b"\xff\xd8" and mode == "full"
    exact = np.asarray(fig.canvas.get_renderer().buffer_rgba())[..., :3]
    assert np.array_equal(fig.canvas._last_buff, np.asarray(fig.canvas.get_renderer().buffer_rgba()).view(np.uint32).squeeze(2))
    sent = np.asarray(Image.open(io.BytesIO(big)).convert("RGB")).astype(int)
    assert np.abs(sent - exact).mean() < 2.0  # lossy, but close
    with pytest.raises(ValueError, match="photo_quality = 0"):
        plots.fast_frames(_web_figure()[0], photo_quality=0)


def test_only_photo_demos_send_jpeg_frames():
    from aerophoto import book
    from aerophoto.widgets import LiveDemo

    photo = {f"aerophoto.demos.{m}.{c}" for m, c, _ in PHOTO_DEMOS}
    import importlib

    for ch in book.CHAPTERS:
        for d in ch.demos:
            module, cls = d.cls.rsplit(".", 1)
            klass = getattr(importlib.import_module(module), cls)
            assert issubclass(klass, LiveDemo)
            assert klass.photo_frames == (d.cls in photo), d.cls


def _demo(module, cls):
    import importlib

    import matplotlib

    matplotlib.use("Agg")
    return getattr(importlib.import_module(f"aerophoto.demos.{module}"), cls)()


def _assert_within_one_jnd(cls, exact, quality):
    """The JPEG of ``exact`` (h, w, 3) at ``quality`` against the exact pixels (CIEDE2000): mean ΔE00 ≤ 1 (about
    one just-noticeable difference), at most 2 % of the pixels above 5."""
    from skimage.color import deltaE_ciede2000, rgb2lab

    sent = np.asarray(Image.open(io.BytesIO(plots._jpeg(exact, quality))).convert("RGB"))
    de = deltaE_ciede2000(rgb2lab(exact), rgb2lab(sent))
    assert de.mean() <= 1.0, f"{cls} at {quality}: mean ΔE00 {de.mean():.2f}"
    assert (de > 5).mean() <= 0.02, f"{cls} at {quality}: {(de > 5).mean():.2%} of the pixels above ΔE00 5"


@pytest.mark.parametrize(("module", "cls", "move"), PHOTO_DEMOS, ids=[c for _, c, _ in PHOTO_DEMOS])
def test_a_photo_demos_jpeg_frame_is_within_one_just_noticeable_difference(module, cls, move):
    """CIEDE2000 between the exact picture and its frame at PHOTO_QUALITY: mean ≤ 1, few pixels above 5."""
    demo = _demo(module, cls)
    try:
        demo.set(**move)
        demo.draw(force=True)
        exact = np.asarray(demo.fig.canvas.buffer_rgba())[..., :3].copy()
    finally:
        demo.close()
    _assert_within_one_jnd(cls, exact, plots.PHOTO_QUALITY)


def test_a_frame_goes_at_the_quality_set_before_it():
    """plots.frame_quality: the next photo frame is the JPEG of the canvas' pixels at that quality, byte for byte."""
    fig, img, line = _web_figure()
    assert plots.fast_frames(fig, photo_quality=plots.PHOTO_QUALITY)
    for q in (plots.PREVIEW_QUALITY, plots.PHOTO_QUALITY):
        assert plots.frame_quality(fig, q)
        img.set_data(np.flipud(img.get_array()))
        frame, mode = _frame(fig)
        exact = np.asarray(fig.canvas.get_renderer().buffer_rgba())[..., :3]
        assert mode == "full" and frame == plots._jpeg(exact, q)
    assert len(plots._jpeg(exact, plots.PREVIEW_QUALITY)) < len(plots._jpeg(exact, plots.PHOTO_QUALITY))
    with pytest.raises(ValueError, match="quality = 101"):
        plots.frame_quality(fig, 101)
    assert not plots.frame_quality(_web_figure()[0], 50)  # no photo frames set up: nothing to change
    lossless, _, _ = _web_figure()
    assert plots.fast_frames(lossless) and not plots.frame_quality(lossless, 50)


# the demos that show a preview while a slider moves (result.preview), with a move of a slider that previews
PREVIEW_DEMOS = [("fotoschema", "FotoschemaDemo", ("alpha_max_deg", 1.25)),  # off the defaults: a move
                 ("rectification", "TransformerDemo", ("alpha_deg", 4.0))]


@pytest.mark.parametrize(("module", "cls", "move"), PREVIEW_DEMOS, ids=[c for _, c, _ in PREVIEW_DEMOS])
def test_a_preview_goes_at_the_preview_quality_and_the_resting_picture_at_the_photo_quality(module, cls, move):
    """LiveDemo.show chooses the quality of the frames to come from the result it shows; a preview's JPEG stays
    within one just-noticeable difference of the exact preview (mean ΔE00 ≤ 1, ≤ 2 % of pixels above 5, as a
    resting photo frame)."""
    import asyncio

    name, value = move
    demo = _demo(module, cls)
    try:
        assert demo.photo_frames
        canvas = demo.fig.canvas
        canvas._aerophoto_photo_quality = plots.PHOTO_QUALITY  # as plots.fast_frames sets it on ipympl's canvas

        async def slider_move():  # in a running loop, as in a kernel: the slider's callback shows a preview
            demo._serve_slider(name, {"new": value})
            demo.cancel_later()  # the full picture it scheduled is drawn below, by set()

        asyncio.run(slider_move())
        assert demo.result.preview and canvas._aerophoto_photo_quality == plots.PREVIEW_QUALITY
        demo.draw(force=True)
        exact = np.asarray(canvas.buffer_rgba())[..., :3].copy()
        demo.set(**{name: value})  # the resting picture
        assert not demo.result.preview and canvas._aerophoto_photo_quality == plots.PHOTO_QUALITY
    finally:
        demo.close()
    _assert_within_one_jnd(cls, exact, plots.PREVIEW_QUALITY)
