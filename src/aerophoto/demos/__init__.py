"""The chapters' live demos, one module per topic.

Each module holds a *view* (a figure builder taking ``ax=None`` whose
``update(result)`` moves its artists in place), the pure function that
computes what the view shows, and a :class:`aerophoto.widgets.LiveDemo`
subclass that binds sliders to both.  A static figure in a notebook and the
live demo share the same view.  Submodules load on first use.
"""

from __future__ import annotations

import importlib

_SUBMODULES = (
    "footprint",  # camera footprint with o, n, c (chapter 00)
    "displacement",  # relief and tilt displacement explorer (chapters 03, 04)
    "flight_plan",  # survey plan: strips, photos, footprints, timing (chapter 01)
    "reduction",  # the reduction explorer: free radial strip, error triangles, k, v (chapters 06, 12)
    "quality",  # rough mosaic and the §3 verdicts of a simulated flight (chapter 02)
    "fotoschema",  # the live single-strip fotoschema: seams, RMS, mean scale (chapter 05)
)

__all__ = list(_SUBMODULES)


def __getattr__(name: str):
    if name in _SUBMODULES:
        module = importlib.import_module(f".{name}", __name__)
        globals()[name] = module
        return module
    raise AttributeError(f"module 'aerophoto.demos' has no attribute {name!r}")
