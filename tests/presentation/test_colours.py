"""Every demo's key stays readable with a colour-vision deficiency (issue "A lecture the back row can read", 6).

Each entry of a demo's key (its legend beside the figure, or the key in its table) is a colour and a shape (a
marker glyph, a line or a line style).  Two entries of the same shape must differ in colour by CIEDE2000
ΔE00 ≥ :data:`MIN_DE` in normal vision and under simulated deuteranopia and protanopia (Machado, Oliveira &
Fernandes 2009, severity 1, applied in linear sRGB); entries of different shapes may be closer in colour.

Why 12: ΔE00 ≈ 2.3 is a just-noticeable difference for large patches side by side; the demos' marks are thin
lines and 6–9 px markers seen from the back of a hall, for which the noticeable difference grows several-fold
with the mark's smallness (Stone, Szafir & Setlur 2014, "An engineering model for color difference as a function
of size"); 12 is about five JNDs of large patches, the level at which Okabe–Ito's vermillion and orange
(ΔE00 12.5 under deuteranopia) just pass and the two blues chapter 14 showed (1.9) fail.
"""

from __future__ import annotations

import importlib
import itertools
import re

import numpy as np
import pytest
from skimage.color import deltaE_ciede2000, rgb2lab

from aerophoto import book

MIN_DE = 12.0
#: Machado et al. 2009, severity 1.0, linear sRGB → simulated linear sRGB
CVD = {
    "deuteranopia": np.array([[0.367322, 0.860646, -0.227968], [0.280085, 0.672501, 0.047413],
                              [-0.011820, 0.042940, 0.968881]]),
    "protanopia": np.array([[0.152286, 1.052583, -0.204868], [0.114503, 0.786281, 0.099216],
                            [-0.003882, -0.048116, 1.051998]]),
}
DEMOS = [(c.number, d.cls) for c in book.CHAPTERS for d in c.demos]


def _linear(c):
    return np.where(c <= 0.04045, c / 12.92, ((c + 0.055) / 1.055) ** 2.4)


def _srgb(c):
    c = np.clip(c, 0.0, 1.0)
    return np.where(c <= 0.0031308, 12.92 * c, 1.055 * c ** (1 / 2.4) - 0.055)


def seen(rgb, vision: str):
    """``rgb`` (sRGB, 0…1) as seen with ``vision`` ("normal", "deuteranopia", "protanopia")."""
    rgb = np.asarray(rgb, float)
    return rgb if vision == "normal" else _srgb(_linear(rgb) @ CVD[vision].T)


def delta_e(a, b) -> float:
    return float(deltaE_ciede2000(rgb2lab(np.asarray(a)[None, None, :]), rgb2lab(np.asarray(b)[None, None, :]))[0, 0])


def _hex(h: str):
    return np.array([int(h[i:i + 2], 16) for i in (1, 3, 5)]) / 255.0


def key_entries(html: str) -> set:
    """(colour, shape) of every entry of a key written as HTML (plots.legend_html and the demos' own keys)."""
    html = re.sub(r"linear-gradient\([^)]*\)", "", html)  # a colour bar is a scale, not entries
    out = set()
    for col, glyph in re.findall(r"color:\s*(#[0-9a-fA-F]{6})[^>]*>\s*([^<\s])", html):
        out.add((col.lower(), glyph))
    for style, col in re.findall(r"border-top:\s*\d+px\s+(\w+)\s+(#[0-9a-fA-F]{6})", html):
        out.add((col.lower(), "line-" + style))
    return out


def test_the_simulation_and_the_distance():
    red, green = _hex("#FF0000"), _hex("#00A000")
    assert delta_e(red, red) == pytest.approx(0.0, abs=1e-9)
    assert delta_e(red, green) > 50  # far apart in normal vision
    assert delta_e(seen(red, "deuteranopia"), seen(green, "deuteranopia")) < delta_e(red, green) / 2  # closer
    assert np.allclose(seen(_hex("#777777"), "protanopia"), _hex("#777777"), atol=0.01)  # greys stay grey
    assert key_entries("<span style='color:#D55E00;font-size:17px'>●</span> x "
                       "<span style='border-top:3px dashed #777777'></span>") == {("#d55e00", "●"),
                                                                                ("#777777", "line-dashed")}


@pytest.mark.parametrize(("number", "cls"), DEMOS, ids=[f"{n}-{c.rsplit('.', 1)[1]}" for n, c in DEMOS])
def test_a_demos_key_is_apart_with_colour_blindness(number, cls):
    import matplotlib

    matplotlib.use("Agg")
    module, name = cls.rsplit(".", 1)
    demo = getattr(importlib.import_module(module), name)()
    try:
        keys = re.findall(r"<div class='aerophoto-legend'.*?</div>\s*</div>|<div class='aerophoto-legend'.*?</div>",
                          demo.table.value, flags=re.S)
        entries = key_entries(demo.legend.value + "".join(keys))
    finally:
        demo.close()
    close = []
    for (ca, sa), (cb, sb) in itertools.combinations(sorted(entries), 2):
        if sa != sb or ca == cb:
            continue  # told apart by shape (or the same series drawn twice)
        for vision in ("normal", "deuteranopia", "protanopia"):
            d = delta_e(seen(_hex(ca), vision), seen(_hex(cb), vision))
            if d < MIN_DE:
                close.append((ca, cb, sa, vision, round(d, 1)))
    assert not close, f"chapter {number} {name}: key entries of one shape too close in colour: {close}"
