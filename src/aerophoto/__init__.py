"""aerophoto — an interactive photogrammetry textbook and lab workbook.

The package does the computing, plotting and widget wiring for the notebooks in
``notebooks/``; the notebooks tell the story.  One module per topic of the
course-design guide (Presnyakov & Tyuklenkova, Penza 2014), in six layers
(imports point downwards only; ``tests/course/test_layers.py`` checks it):

===  ====================  =====================================================
1    foundation            ``geometry`` (camera, central projection, terrain),
                           ``plane`` (2-D fits, rays), ``variants`` (§1)
2    physics               ``flight`` (§2), ``quality`` (§3), ``displacement``
                           (§4–§5), ``mosaic`` (§6), ``triangulation`` (§7, §13),
                           ``stereo`` (§8)
3    the virtual world     ``terrain``, ``site``, ``simulate``, ``render``
4    the course's content  ``guide`` (printed tables and their audits),
                           ``tasks`` (graded tasks per chapter)
5    presentation          ``plots``, ``blit``, ``widgets``, ``demos``, ``i18n``
6    course                ``checks``, ``book`` (setup, chapter registry),
                           ``nbtools``, ``course`` (the instructor's CLI),
                           ``report`` (the student's course report, §15)
===  ====================  =====================================================

Importing aerophoto has no side effects: submodules load on first use, and
nothing changes matplotlib's style until a notebook calls :func:`setup`.
"""

from __future__ import annotations

import importlib

__version__ = "0.1.0"

_SUBMODULES = (
    "cache",
    "geometry",
    "plane",
    "variants",
    "diskcache",
    "flight",
    "site",
    "render",
    "simulate",
    "quality",
    "displacement",
    "mosaic",
    "triangulation",
    "stereo",
    "interpretation",
    "projective",
    "control",
    "rectify",
    "dem",
    "budget",
    "bundle",
    "accuracy",
    "soilmap",
    "spectral",
    "terrain",
    "guide",
    "labs",
    "tasks",
    "plots",
    "tables",
    "blit",
    "widgets",
    "fit",
    "demos",
    "i18n",
    "checks",
    "gradebook",
    "glossary_page",
    "book",
    "nbtools",
    "course",
    "report",
    "lite",
    "website",
)
"""Every public module and subpackage, once (tests/course/test_chapter_key.py checks it against the files on disk)."""

__all__ = ["__version__", "setup", "chapters", *_SUBMODULES]


def setup(*args, **kwargs):
    """Prepare a notebook: style, live-figure backend, installation check, variant.

    See :func:`aerophoto.book.setup`, which this forwards to.
    """
    from .book import setup as _setup

    return _setup(*args, **kwargs)


def chapters() -> tuple:
    """The book's chapters, in order (the one registry, :data:`aerophoto.book.CHAPTERS`)."""
    from .book import CHAPTERS

    return CHAPTERS


def __getattr__(name: str):
    if name in _SUBMODULES:
        module = importlib.import_module(f".{name}", __name__)
        globals()[name] = module
        return module
    raise AttributeError(f"module 'aerophoto' has no attribute {name!r}")


def __dir__():
    return sorted(set(globals()) | set(__all__))
