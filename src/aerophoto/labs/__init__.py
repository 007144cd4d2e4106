"""The students' lab worlds: what each student photographs, pricks, reads and measures — never the grading.

Every graded chapter hands the student a world of their own, built from their
variant: a strip over the virtual site, a stereo pair, a photo to rectify, a
survey block.  Those worlds live here, one module per chapter, so that the
rubrics (:mod:`aerophoto.tasks`), the live demos (:mod:`aerophoto.demos`) and
the report (:mod:`aerophoto.report`) all take them from one place.  This is
the course's content (layer 4, beside :mod:`aerophoto.guide`): it imports the
physics and the virtual world, never :mod:`aerophoto.tasks` (which imports it).

=======  ==================================  ====================================================================
chapter  module                              what the student gets
=======  ==================================  ====================================================================
02       :mod:`aerophoto.labs.ch02`          five photos' measurements on the rough mosaic (guide §3)
03       :mod:`aerophoto.labs.ch03`          the relief sheet: six pricked points, photo, plan (§4)
04       :mod:`aerophoto.labs.ch04`          the tilt sheet: nine pricked points, photo, plan (§5)
03, 04   :mod:`aerophoto.labs.displacement`  what the two sheets share: how they are built (§4, §5)
05       :mod:`aerophoto.labs.ch05`          the own fotoschema, seam and scale readings, the worked answers (§6)
05–06    :mod:`aerophoto.labs.own`           the own strip 36 … 39 over the site, tilts that fit, readings
06, 12   :mod:`aerophoto.labs.ch06`          the strip's templates, free strip, reduction and readings (§7, §13)
07       :mod:`aerophoto.labs.ch07`          the stereo pair, its measurements, images, height model (§8)
08       :mod:`aerophoto.labs.ch08`          the interpretation photo, its marks and truth (§9)
09       :mod:`aerophoto.labs.ch09`          the farmland scene, new photo and old plan (§10)
10       :mod:`aerophoto.labs.ch10`          the resection station and its measured angles (§11)
11       :mod:`aerophoto.labs.ch11`          table 11 of paper deformation; the photo to rectify (§12)
13       :mod:`aerophoto.labs.ch13`          the bare-soil patch, its composite and soil map (§14)
15       :mod:`aerophoto.labs.ch15`          the mountain site and the survey blocks (article 002)
16       :mod:`aerophoto.labs.ch16`          the block for Lysenko's formula; the own 1 km sheet, its DEMs (000)
=======  ==================================  ====================================================================

Chapters 00, 01, 14 and 17 give their inputs with their tasks (:mod:`aerophoto.tasks`): numbers drawn from
the variant (and chapter 14's Monte Carlo strip).  Everything is
deterministic (seeded by the variant number) and cached per process where it is costly; shared arrays are
read only.  Submodules load on first use::

    from aerophoto import labs
    labs.ch06.lab_strip(v)
"""

from __future__ import annotations

import functools
import importlib

from .. import _chapters

__all__ = ["SHARED", "MODULES", "chapter_modules"]

#: the lab modules that serve more than one chapter (the chapter modules ``chNN`` are found by their name)
SHARED = ("own", "displacement")


@functools.cache
def chapter_modules() -> tuple:
    """The chapter lab modules on disk, ``("ch02", "ch03", …)``, by the naming rule (:mod:`aerophoto._chapters`)."""
    return _chapters.chapter_modules(__path__)


def __getattr__(name: str):
    if name == "MODULES":  # every lab module: the shared ones, then the chapters'
        return SHARED + chapter_modules()
    if name in SHARED or (_chapters.CHAPTER_MODULE.fullmatch(name) and name in chapter_modules()):
        module = importlib.import_module(f".{name}", __name__)
        globals()[name] = module
        return module
    raise AttributeError(f"module 'aerophoto.labs' has no attribute {name!r}")
