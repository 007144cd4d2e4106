"""The source documents' printed tables, transcribed once, and their audits.

One module per chapter, named by the chapter's number: ``chNN`` holds the
tables of the source of notebook ``NN_*.ipynb`` (``ch03`` for guide §4,
``ch16`` for article 000; the map is :data:`aerophoto.book.CHAPTERS`, each
module's docstring names its section or article).  Each holds the printed
numbers as data — what the scan shows, OCR garbling cleaned and said so — and
functions returning :class:`~aerophoto.guide.audit.Audit` records: the table
recomputed from its own printed inputs, every printed value beside the value
that follows, and the reason wherever one does not.  The rule that decides
"follows" is one for all tables (:data:`~aerophoto.guide.audit.TOLERANCE_UNITS`).

Submodules load on first use; the list of them is the modules ``chNN`` on disk
(:data:`CHAPTER_MODULES`), never kept by hand.
"""

from __future__ import annotations

import functools
import importlib

from .. import _chapters
from .audit import TOLERANCE_UNITS, Audit, Printed, digit_unit, discrepancy_frame, printed, render

__all__ = ["TOLERANCE_UNITS", "Audit", "Printed", "printed", "digit_unit", "render", "discrepancy_frame",
           "CHAPTER_MODULES", "chapter_modules"]


@functools.cache
def chapter_modules() -> tuple:
    """The chapter modules on disk, ``("ch01", …, "ch17")``: the naming rule ``ch`` + the chapter's number
    (:mod:`aerophoto._chapters`).

    Read on first use (importing the package reads nothing); ``CHAPTER_MODULES`` is the same tuple.
    """
    return _chapters.chapter_modules(__path__)


def __getattr__(name: str):
    if name == "CHAPTER_MODULES":
        return chapter_modules()
    if _chapters.CHAPTER_MODULE.fullmatch(name) and name in chapter_modules():
        module = importlib.import_module(f".{name}", __name__)
        globals()[name] = module
        return module
    raise AttributeError(f"module 'aerophoto.guide' has no attribute {name!r}")
