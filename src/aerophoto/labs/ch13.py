"""Chapter 13's lab (guide §14): the student's patch of bare soil, its colour-infrared composite and soil map.

The patch of tasks 13.2–13.3 (:func:`patch_of`): a square 10 cm × 10 cm on the student's photo, i.e.
0.1·m metres on the ground (1.2–2.19 km), in 200 × 200 cells of 0.5 mm on the photo (m/2000 metres), centred
at X = 1200 + 76i m and 300 + 100·(i mod 3) m north of the river's centre line, so every patch holds the
floodplain and the slopes above it.  It is photographed bare (as in spring, before the crops come up: the
guide's direct keys need bare ground) in summer moisture, colour-infrared (NIR, red, green as R, G, B).
The pit is at the patch's cell (50 + i mod 100, 150 − i mod 100) (row, column from the south-west corner).
The spectral explorer demo opens on variant 00's patch; the graded tasks are :mod:`aerophoto.tasks.ch13`.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np
import pandas as pd

__all__ = ["CAMERA", "PATCH_CELLS", "Patch", "patch_of"]

#: the composite of task 13.3
CAMERA = "colour-infrared film"
#: cells along each side of the patch
PATCH_CELLS = 200
@dataclass(frozen=True, eq=False)
class Patch:
    """The student's patch: its place, the bare soil's composite and the field survey's soil map.

    Attributes
    ----------
    extent_m : (X0, X1, Y0, Y1) on the site, m
    spacing_m : cell size on the ground, m (0.5 mm on the photo)
    composite : (200, 200, 3) float32, the colour-infrared composite (NIR, red, green), 0…1
    soil_map : (200, 200) uint8, the soil class of each cell (:data:`aerophoto.site.soils.SOIL_CLASSES`)
    pit : (row, column) of the soil pit
    pit_soil : the pit's topsoil: ``moisture_pct``, ``humus_pct``, ``particle_mm``, ``parent`` (keywords of
        :func:`aerophoto.spectral.soil_reflectance`) and ``soil`` (its class)
    """

    extent_m: tuple
    spacing_m: float
    composite: np.ndarray
    soil_map: np.ndarray
    pit: tuple
    pit_soil: dict

    def legend(self) -> pd.DataFrame:
        """The soil classes of the survey map (names only; the areas are the student's to find)."""
        from ..site.soils import SOIL_CLASSES

        return pd.DataFrame([(k, c.name, c.ru) for k, c in SOIL_CLASSES.items()],
                            columns=["code", "soil", "почва"]).set_index("code")


@functools.lru_cache(maxsize=4)
def _patch(i: int, m: float) -> Patch:
    from ..site import get_site
    from ..site.soils import soil_layer

    site = get_site()
    side = 0.1 * m
    Xc = 1200.0 + 76.0 * i
    river = site.features["river"]
    Yc = float(np.interp(Xc, river[:, 0], river[:, 1])) + 300.0 + 100.0 * (i % 3)
    ext = (Xc - side / 2, Xc + side / 2, Yc - side / 2, Yc + side / 2)
    layer = soil_layer(site, extent_m=ext, spacing_m=side / PATCH_CELLS)
    comp = layer.composite(CAMERA)
    comp.flags.writeable = False
    r, c = 50 + i % 100, 150 - i % 100
    code = int(layer.code[r, c])
    pit = {"moisture_pct": round(float(layer.moisture_pct[r, c]), 1),
           "humus_pct": round(float(layer.humus_pct[r, c]), 1),
           "particle_mm": round(float(layer.particle_mm[r, c]), 2),
           "parent": layer.classes[code].parent, "soil": layer.classes[code].name}
    return Patch(ext, side / PATCH_CELLS, comp, layer.code, (r, c), pit)


def patch_of(v) -> Patch:
    """Tasks 13.2–13.3's patch for variant ``v`` (cached)."""
    return _patch(int(v.i), float(v.m))
