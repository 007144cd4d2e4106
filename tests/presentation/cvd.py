"""Simulated colour-vision deficiency and colour distance, for the colour tests and the screenshots.

Simulation: Machado, Oliveira & Fernandes (2009), "A physiologically-based model for simulation of color vision
deficiency", IEEE TVCG 15(6) — the matrices for severity 1.0 (dichromacy) from the authors' table, applied to
linear sRGB.  Distance: CIEDE2000 (``skimage.color.deltaE_ciede2000``) in CIELAB (``skimage.color.rgb2lab``).
"""

from __future__ import annotations

import numpy as np
from matplotlib.colors import to_rgb
from skimage.color import deltaE_ciede2000, rgb2lab

#: Machado 2009, severity 1.0, linear RGB → linear RGB
MACHADO = {
    "protanopia": np.array([[0.152286, 1.052583, -0.204868],
                            [0.114503, 0.786281, 0.099216],
                            [-0.003882, -0.048116, 1.051998]]),
    "deuteranopia": np.array([[0.367322, 0.860646, -0.227968],
                              [0.280085, 0.672501, 0.047413],
                              [-0.011820, 0.042940, 0.968881]]),
}


def _to_linear(c):
    c = np.asarray(c, float)
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def _to_srgb(c):
    c = np.clip(c, 0.0, 1.0)
    return np.where(c <= 0.0031308, 12.92 * c, 1.055 * c ** (1 / 2.4) - 0.055)


def simulate(rgb, kind: str) -> np.ndarray:
    """sRGB values in 0…1 (any shape ending in 3) as seen with ``kind`` ("normal", "protanopia", "deuteranopia")."""
    rgb = np.asarray(rgb, float)
    if kind == "normal":
        return rgb
    return _to_srgb(_to_linear(rgb) @ MACHADO[kind].T)


def simulate_png(png: bytes, kind: str = "deuteranopia") -> bytes:
    """A screenshot (PNG bytes) as seen with ``kind``."""
    import io

    from PIL import Image

    img = Image.open(io.BytesIO(png)).convert("RGB")
    arr = np.asarray(img, dtype=float) / 255.0
    out = (simulate(arr, kind) * 255.0 + 0.5).astype(np.uint8)
    buf = io.BytesIO()
    Image.fromarray(out).save(buf, format="png")
    return buf.getvalue()


def delta_e(c1, c2, kind: str = "normal") -> float:
    """CIEDE2000 distance between two matplotlib colours as seen with ``kind``."""
    a = simulate(np.array(to_rgb(c1)), kind).reshape(1, 1, 3)
    b = simulate(np.array(to_rgb(c2)), kind).reshape(1, 1, 3)
    return float(deltaE_ciede2000(rgb2lab(a), rgb2lab(b))[0, 0])
