"""Photos shown as JPEG (plots.static(..., format="jpeg")): a quality chosen by a measured visual difference.

docs/tools/measure_jpeg_quality.py sweeps the qualities on chapter 08's photos; here the book's quality is held to
its two measures on the worked example's photo as the chapter shows it, and the size a photo takes in a notebook.
"""

from __future__ import annotations

import io

import numpy as np
import pytest

from aerophoto import plots


def test_a_photo_as_jpeg_keeps_its_look_at_a_tenth_of_the_size():
    import matplotlib

    matplotlib.use("Agg")
    from PIL import Image

    from aerophoto.demos import interpretation as di
    from aerophoto.labs import ch08

    lab = ch08.example_photo()
    for camera in ("colour film", "colour-infrared film"):
        png = plots.static(di.lab_figure(lab, camera), "the example photo", dpi=di.LAB_DPI)
        jpg = plots.static(di.lab_figure(lab, camera), "the example photo", dpi=di.LAB_DPI, format="jpeg")
        ref = np.asarray(Image.open(io.BytesIO(png.png)).convert("RGB"))
        got = np.asarray(Image.open(io.BytesIO(jpg.data)).convert("RGB"))
        assert ref.shape == got.shape and ref.shape[0] >= 1150  # the photo's 1024 pixels one for one
        d = plots.picture_difference(ref, got)
        assert d["ssim"] >= plots.JPEG_MIN_SSIM and d["dE_mean"] <= plots.JPEG_MAX_DE, d
        assert len(jpg.data) < 0.35 * len(png.data)
        assert len(jpg._repr_html_()) < 600_000  # what the notebook keeps of it (base64), well under the cap
    # a visibly worse quality fails the same measures (they can tell)
    natural = np.asarray(Image.open(io.BytesIO(plots.static(di.lab_figure(lab), "x", dpi=di.LAB_DPI).png)).convert(
        "RGB"))
    worse = plots.static(di.lab_figure(lab), "x", dpi=di.LAB_DPI, format="jpeg", quality=40)
    bad = plots.picture_difference(natural, np.asarray(Image.open(io.BytesIO(worse.data)).convert("RGB")))
    assert bad["ssim"] < plots.JPEG_MIN_SSIM or bad["dE_mean"] > plots.JPEG_MAX_DE


def test_a_jpeg_figure_is_shown_once_with_its_alt_text():
    import matplotlib

    matplotlib.use("Agg")
    fig = plots.figure(figsize=(2, 2))
    fig.add_subplot(1, 1, 1).imshow(np.random.default_rng(0).random((20, 20, 3)))
    out = plots.static(fig, "a noisy <square>", format="jpeg", quality=80)
    bundle = out._repr_mimebundle_()
    assert set(bundle) == {"text/html", "text/plain"}  # no second copy of the picture
    assert "data:image/jpeg;base64," in bundle["text/html"] and "a noisy &lt;square&gt;" in bundle["text/html"]
    assert out.data[:3] == b"\xff\xd8\xff" and out.png is None and out.mime == "image/jpeg"
    with pytest.raises(ValueError, match="format"):
        plots.static(plots.figure(), "x", format="gif")
    with pytest.raises(ValueError, match="quality"):
        plots.static(plots.figure(), "x", format="jpeg", quality=101)
    same = np.zeros((16, 16, 3), np.uint8)
    assert plots.picture_difference(same, same) == {"ssim": 1.0, "dE_mean": 0.0, "dE_p99": 0.0}
