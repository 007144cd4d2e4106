"""The naming rule of the chapter key: chapter ``NN``'s module in a per-chapter package is ``chNN``.

``aerophoto.guide`` and ``aerophoto.tasks`` (and ``aerophoto.labs``) hold one module per chapter, named by the
notebook's number; their lists of chapter modules are read from the files by this rule, never kept by hand.
The chapters themselves are :data:`aerophoto.book.CHAPTERS` (tests/course/test_chapter_key.py checks the two agree).
"""

from __future__ import annotations

import pkgutil
import re

__all__ = ["CHAPTER_MODULE", "chapter_modules"]

#: the name of a chapter's module: ``ch`` and the chapter's two-digit number
CHAPTER_MODULE = re.compile(r"ch\d\d")


def chapter_modules(path) -> tuple:
    """The chapter modules in a package's ``__path__``, sorted: ``("ch00", "ch01", …)``."""
    return tuple(sorted(m.name for m in pkgutil.iter_modules(path) if CHAPTER_MODULE.fullmatch(m.name)))
