"""Which chapters have live demos, and which sliders the browser tests move: read from the book's registry.

The one registry is :data:`aerophoto.book.CHAPTERS`: each chapter's demos name their cell (``demo-…``), their
LiveDemo class and their headline sliders — the exact slider labels (``"f, mm"``, ``"α, °"``) with the key that
moves them by a visible amount (``ArrowRight``/``ArrowLeft`` = one step, ``PageUp``/``PageDown`` = five steps).
``tests/browser/test_registry.py`` fails while a notebook with a ``demo-`` cell is missing there or from the
lecture index.
"""

from __future__ import annotations

from aerophoto.book import CHAPTERS as _BOOK
from aerophoto.book import LECTURE_INDEX, Chapter, Demo

import pytest

__all__ = ["CHAPTERS", "LECTURE_INDEX", "Chapter", "Demo", "CORE", "CORE_VOILA", "core_params"]

#: the chapters with at least one live demo, in the book's order
CHAPTERS = tuple(c for c in _BOOK if c.demos)

#: the chapters whose whole notebook runs in JupyterLab in the README's test command: the simplest (00) and the
#: heaviest demo (05, the fotoschema); in Voilà, whole, chapter 00 (:data:`CORE_VOILA`: chapter 05's demo runs in
#: Voilà on its lecture page in that command, test_lectures.py's ``SAMPLE``). Every other whole-notebook run in
#: JupyterLab and Voilà, and every other lecture page, is ``exhaustive`` (a step of .ci/run of its own), so every
#: chapter still runs whole in both hosts, and on its lecture page, in CI.
CORE = ("00", "05")
CORE_VOILA = ("00",)


def core_params(chapters=CHAPTERS, core=CORE):
    """``chapters`` as pytest params, those outside ``core`` marked ``exhaustive``."""
    return [pytest.param(c, id=c.name, marks=() if c.number in core else pytest.mark.exhaustive) for c in chapters]
