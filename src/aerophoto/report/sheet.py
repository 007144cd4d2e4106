"""The student's fotoschema sheet (guide §6, appendix 1): true size, Russian, vector marginalia, photos at 300 dpi.

The mosaic is glued from the working areas of the student's four photos by
:func:`aerophoto.mosaic.sheet_raster` at :data:`PX_PER_MM` pixels per sheet millimetre (≥ 300 dpi at true size,
each pixel read from the site exactly where that photo's ray meets the ground), and laid out with its
marginalia by :func:`aerophoto.demos.fotoschema.sheet_figure` in Russian only, as the guide's sample: the title
ФОТОСХЕМА, the mean scale "М 1:m" (the student's own, task 05.2, rounded to hundreds), the scale bar, the year,
"Выполнил: ст. гр. … name" and "Проверил: …" — no record-book number (the sample has none).  Lines and text stay
vector in the PDF; the glued photos are its one raster image, written at their own resolution.

The glued raster depends on the variant only and takes a while to build: it is kept in the student's cache
(:mod:`aerophoto.diskcache`) as an 8-bit image, and so is the finished PDF for the same marginalia.
"""

from __future__ import annotations

import io
import json
from pathlib import Path

import numpy as np

from .. import diskcache

__all__ = ["PX_PER_MM", "sheet_pdf", "made_by_text"]

#: the glued photos' resolution, pixels per sheet mm (12 px/mm = 305 dpi at 100 %)
PX_PER_MM = 12.0


def made_by_text(student: str, group: str) -> str:
    """The sample's "ст. гр. ЗиК 31 Ваксман С.В." from the student's group and name."""
    return " ".join(x for x in ((f"ст. гр. {group}" if group else ""), student) if x)


def _raster(v) -> tuple:
    from .. import mosaic as mo
    from ..labs.ch05 import own_fotoschema
    from .facts import variant_key

    def build():
        own = own_fotoschema(v)
        image, extent = mo.sheet_raster(own.fs, own.site, PX_PER_MM)
        return {"image": np.round(np.clip(image, 0.0, 1.0) * 255.0).astype(np.uint8),
                "extent": np.asarray(extent, dtype=float)}

    cache = diskcache.active()
    key = {"variant": variant_key(v), "px_per_mm": PX_PER_MM}
    z = cache.arrays("sheet-raster", key, build) if cache is not None else build()
    return z["image"], tuple(float(e) for e in z["extent"])


def _render(v, m_mean: float, made_by: str, checked_by: str, year: int) -> tuple[bytes, str]:
    import matplotlib.pyplot as plt

    from ..demos.fotoschema import sheet_figure
    from ..labs.ch05 import own_fotoschema
    from .figures import PDF_META

    image, extent = _raster(v)
    fig = sheet_figure(own_fotoschema(v).fs, image.astype(np.float32) / 255.0, extent, made_by=made_by,
                       checked_by=checked_by, year=year, english=False, scale_m=float(m_mean))
    try:
        for ax in fig.axes:
            for im in ax.images:
                im.set_interpolation("none")  # embedded at its own pixels (≥ 300 dpi), not resampled
        buf = io.BytesIO()
        fig.savefig(buf, format="pdf", metadata=PDF_META)
        return buf.getvalue(), fig.aerophoto_paper
    finally:
        plt.close(fig)


def sheet_pdf(v, m_mean: float, path: Path, *, made_by: str, checked_by: str, year: int) -> dict:
    """Write the sheet to ``path``; returns ``{"pdf": path, "paper": "A3", "size_mm": (w, h)}``."""
    from ..demos.fotoschema import PAPER_MM
    from .facts import variant_key

    cache = diskcache.active()
    key = {"variant": variant_key(v), "m": float(m_mean), "made_by": made_by, "checked_by": checked_by,
           "year": int(year), "px_per_mm": PX_PER_MM}
    data = meta = None
    if cache is not None:
        meta = cache.get_bytes("sheet-meta", key)
        data = cache.get_bytes("sheet", key) if meta is not None else None
    if data is None:
        data, paper = _render(v, m_mean, made_by, checked_by, year)
        if cache is not None:
            cache.put_bytes("sheet", key, data)
            cache.put_bytes("sheet-meta", key, json.dumps({"paper": paper}).encode("utf-8"))
    else:
        paper = json.loads(meta.decode("utf-8"))["paper"]
    path = Path(path)
    path.write_bytes(data)
    return {"pdf": path, "paper": paper, "size_mm": PAPER_MM[paper]}
