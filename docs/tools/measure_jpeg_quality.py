"""Measure which JPEG quality chapter 08's photos need: structural similarity (SSIM) and size against the PNG.

    python docs/tools/measure_jpeg_quality.py [dpi]

Renders the worked example's photo and two students' photos (natural colour and colour infrared) as the chapter
shows them (:func:`aerophoto.demos.interpretation.lab_figure`), encodes each as PNG (the reference, lossless) and
as JPEG at qualities 50…95, and prints, per quality, the smallest SSIM over the photos (scikit-image's
``structural_similarity`` of the luminance, Wang et al. 2004), the largest mean and 99th-percentile CIEDE2000
difference and the total size of the chapter's three photos
as a notebook stores them (base64).  The book's :data:`aerophoto.plots.JPEG_QUALITY` is the lowest quality whose
SSIM is at least :data:`aerophoto.plots.JPEG_MIN_SSIM` and whose mean CIEDE2000 difference is at most
:data:`aerophoto.plots.JPEG_MAX_DE`; tests/presentation/test_plots_jpeg.py checks that it meets both.
"""

from __future__ import annotations

import io
import json
import sys


def pictures(dpi: int):
    import matplotlib

    matplotlib.use("Agg")
    from aerophoto.demos import interpretation as di
    from aerophoto.labs import ch08

    labs = [ch08.example_photo(), ch08._lab_photo(57), ch08._lab_photo(3)]
    out = []
    for lab in labs:
        for camera in ("colour film", "colour-infrared film"):
            fig = di.lab_figure(lab, camera)
            buf = io.BytesIO()
            fig.savefig(buf, format="png", dpi=dpi)
            import matplotlib.pyplot as plt

            plt.close(fig)
            out.append(buf.getvalue())
    return out


def jpeg(picture, quality: int) -> bytes:
    """The picture (h, w, 3) uint8 as the book encodes a photo: JPEG, no chroma subsampling (the marks' colours and
    the labels keep their edges), optimised Huffman tables."""
    from PIL import Image

    buf = io.BytesIO()
    Image.fromarray(picture).save(buf, format="JPEG", quality=int(quality), optimize=True, subsampling=0)
    return buf.getvalue()


def sweep(pngs, qualities=range(50, 96, 5)) -> tuple:
    import numpy as np
    from PIL import Image

    from aerophoto import plots

    refs = [np.asarray(Image.open(io.BytesIO(p)).convert("RGB")) for p in pngs]
    rows = []
    for q in qualities:
        d, size = [], 0
        for k, ref in enumerate(refs):
            data = jpeg(ref, q)
            got = np.asarray(Image.open(io.BytesIO(data)).convert("RGB"))
            d.append(plots.picture_difference(ref, got))
            if k in (0, 2, 3):  # the chapter shows the example (natural colour) and one student's two photos
                size += len(data)
        rows.append({"quality": int(q), "ssim_min": round(min(x["ssim"] for x in d), 4),
                     "dE_mean_max": round(max(x["dE_mean"] for x in d), 3),
                     "dE_p99_max": round(max(x["dE_p99"] for x in d), 2),
                     "three_photos_kb_base64": round(size * 4 / 3 / 1024)})
    png_kb = round(sum(len(pngs[k]) for k in (0, 2, 3)) * 4 / 3 / 1024)
    return rows, png_kb


if __name__ == "__main__":
    from aerophoto import plots

    dpi = int(sys.argv[1]) if len(sys.argv) > 1 else 150
    rows, png_kb = sweep(pictures(dpi))
    ok = [r["quality"] for r in rows if r["ssim_min"] >= plots.JPEG_MIN_SSIM and r["dE_mean_max"] <= plots.JPEG_MAX_DE]
    print(json.dumps({"dpi": dpi, "png_three_photos_kb_base64": png_kb, "sweep": rows,
                      "lowest_quality_meeting_both": min(ok) if ok else None, "min_ssim": plots.JPEG_MIN_SSIM,
                      "max_mean_dE": plots.JPEG_MAX_DE, "book_quality": plots.JPEG_QUALITY}, indent=1))
