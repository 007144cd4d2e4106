"""aerophoto — an interactive photogrammetry textbook and lab workbook.

The package does the computing, plotting and widget wiring for the notebooks in
``notebooks/``; the notebooks tell the story.  One module per topic of the
course-design guide (Presnyakov & Tyuklenkova, Penza 2014):

=================  ==========================================================
``geometry``       the frame camera and exact central projection (§4–§5)
``variants``       the student's variant from the record-book number (§1)
``flight``         aerial-survey planning (§2)
``site``           the virtual test site: terrain, texture, ground points
``render``         exact photographs of the virtual site
``simulate``       simulated flights (strips, blocks) with imperfections
``quality``        photo-quality assessment of a flight (§3)
``displacement``   relief and tilt displacement, corrected scales (§4–§5)
``mosaic``         the single-strip fotoschema (§6)
``triangulation``  radial strip phototriangulation and reduction (§7, §13)
``plots``          figure builders shared by the chapters (``ax=None``)
``widgets``        the live-demo base: bounded, labelled sliders with a Reset
``demos``          the chapters' live demos and their figure builders
``checks``         answer checks for the lab tasks
``book``           the notebooks' one setup call
``nbtools``        notebook maintenance: build, find cells by id, strip outputs
``course``         the instructor's command line over nbgrader
=================  ==========================================================

Importing aerophoto has no side effects: submodules load on first use, and
nothing changes matplotlib's style until a notebook calls :func:`setup`.
"""

from __future__ import annotations

import importlib

__version__ = "0.1.0"

_SUBMODULES = (
    "geometry",
    "variants",
    "flight",
    "site",
    "render",
    "simulate",
    "quality",
    "displacement",
    "mosaic",
    "triangulation",
    "plots",
    "widgets",
    "demos",
    "checks",
    "book",
    "nbtools",
    "course",
)

__all__ = ["__version__", "setup", *_SUBMODULES]


def setup(*args, **kwargs):
    """Prepare a notebook: style, live-figure backend, installation check, variant.

    See :func:`aerophoto.book.setup`, which this forwards to.
    """
    from .book import setup as _setup

    return _setup(*args, **kwargs)


def __getattr__(name: str):
    if name in _SUBMODULES:
        module = importlib.import_module(f".{name}", __name__)
        globals()[name] = module
        return module
    raise AttributeError(f"module 'aerophoto' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(__all__))
