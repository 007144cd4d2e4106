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

__all__ = ["CHAPTERS", "LECTURE_INDEX", "Chapter", "Demo"]

#: the chapters with at least one live demo, in the book's order
CHAPTERS = tuple(c for c in _BOOK if c.demos)
