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
    "ray",  # one ray of a vertical photo (chapter 00): the cheapest live figure, the browser benchmark's floor
    "footprint",  # camera footprint with o, n, c (chapter 00)
    "displacement",  # relief and tilt displacement explorer (chapters 03, 04)
    "flight_plan",  # survey plan: strips, photos, footprints, timing (chapter 01)
    "reduction",  # the reduction explorer: free radial strip, error triangles, k, v (chapters 06, 12)
    "quality",  # rough mosaic and the §3 verdicts of a simulated flight (chapter 02)
    "fotoschema",  # the live single-strip fotoschema: seams, RMS, mean scale (chapter 05)
    "fotoschema_sheet",  # the fotoschema's finished sheet and the student's own (chapter 05, the report)
    "plan_correction",  # mutual projective grids: a new photo's changes carried onto the old plan (chapter 09)
    "control",  # control design on a block and the resection with its danger circle (chapter 10)
    "rectification",  # the photo transformer's sequence converging on the base (chapter 11)
    "bundle_views",  # static figures of chapters 14, 15: block layout, sparsity, error ellipses, accumulation
    "block_accuracy",  # the error map of a block against its control layout and measuring error (chapter 14)
    "block_adjustment_live",  # the bundle block adjustment of article 002: control, σ and a blunder (chapter 15)
    "dem_contours",  # contours from a DEM of the site against the true ground (chapter 16)
    "error_budget",  # the live error budget of map updating (chapter 17)
    "interpretation",  # what makes a photo readable; table 10 as an interactive key (chapter 08)
    "loupe",  # a magnifier on chapter 08's photo: a chosen spot at 3–6× from its full-resolution render
    "stereo",  # the floating mark over a stereo pair's anaglyph; base, height and focal length (chapter 07)
    "stereo_figures",  # the stereoscope and its check, parallax profile, height model, prints at true size (07)
    "site_views",  # views of the virtual world: the site as a map, a rendered photo (PhotoView)
    "spectral_explorer",  # soil reflectance under a camera's bands and a patch's composite (chapter 13)
    "measure",  # the measuring tool: readings of pricked points on a photo or plan by clicking (chapters 03, 04)
    "own",  # the student's own results, shown once the task asking for them has passed
    "lecture",  # a demo laid out on one projector screen for the lecture pages (every chapter with demos)
)
"""Every demo module, once: the one list (tests/course/test_chapter_key.py checks it against the files on disk; which
chapter uses which is :attr:`aerophoto.book.Chapter.demo_modules`)."""

__all__ = list(_SUBMODULES)


def __getattr__(name: str):
    if name in _SUBMODULES:
        module = importlib.import_module(f".{name}", __name__)
        globals()[name] = module
        return module
    raise AttributeError(f"module 'aerophoto.demos' has no attribute {name!r}")
