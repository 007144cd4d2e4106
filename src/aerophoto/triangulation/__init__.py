"""Radial strip phototriangulation and its reduction, done analytically (guide §7, §13).

The guide builds a single-strip radial triangulation (одномаршрутный
фототриангуляционный ряд) with tracing paper: direction templates
(восковки направлений) from working centres near the principal points, laid
one on another into a free strip, reduced to the plan on a few control points
(опознаки).  This package does the same with numbers, one module per concern:

=============  =================================================================  ==========
module         what                                                               guide
=============  =================================================================  ==========
``strip``      the points (:func:`design_points`), the templates                  §13 st. 2–7
               (:func:`measure_templates`), the free strip (:func:`lay_free_strip`)
``reduction``  reduction coefficients k = l_base/l_template and their spread,     §7 st. 8–9,
               corrections v = r·(k − 1), the strip laid on the base              §13 st. 8–9
               (:func:`reduce_strip`)
``ends``       building on the plan from both ends to the middle                  §7, fig. 16
               (:func:`build_from_ends`)
``zhukov``     Zhukov's formula (13.1) for the control spacing, its readings,     §13 st. 1
               and the variance of a chain held at both ends
``study``      Monte Carlo: the reduced strip's error against its length          §13
``geodetic``   the student's tables in the Russian convention: X north, Y east,   §7 table 8
               directions clockwise from +X
=============  =================================================================  ==========

The 2-D ray geometry (intersections, error triangles, resection) and the
similarity fits are :mod:`aerophoto.plane`'s; the guide's printed tables 8
and 9 and their audits are :mod:`aerophoto.guide.ch06`, the reading of
formula (13.1) :data:`aerophoto.guide.ch12.ZHUKOV_READING`.

Units and frames
----------------
Photo coordinates and template directions are in mm on the photo, angles
counter-clockwise from the photo's +x axis (see :mod:`aerophoto.geometry`).
The free strip lives in its own "template mm" frame (the tracing paper); the
plan (основа) in mm at the plan scale 1/M, with x east and y north; ground in
metres.  Distances between control points in tables are plan mm.  This is the
package's internal (mathematical) convention; the tables a student works from
use the geodetic one (X north, Y east, directions clockwise from +X), converted
by :mod:`~aerophoto.triangulation.geodetic` — distances and every formula of the
reduction are the same in both.
"""

from __future__ import annotations

from . import ends, geodetic, reduction, strip, study, zhukov
from .ends import *  # noqa: F403 — each submodule's explicit __all__
from .geodetic import *  # noqa: F403
from .reduction import *  # noqa: F403
from .strip import *  # noqa: F403
from .study import *  # noqa: F403
from .zhukov import *  # noqa: F403

#: the public API: every submodule's ``__all__`` (strip, reduction, ends, zhukov, study, geodetic) and the submodules
__all__ = [*strip.__all__, *reduction.__all__, *ends.__all__, *zhukov.__all__, *study.__all__, *geodetic.__all__,
           "strip", "reduction", "ends", "zhukov", "study", "geodetic"]
