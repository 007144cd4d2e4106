"""Projective transformations of the plane: mutual grids, plan correction and resampling (guide §10, §12).

A photo of flat ground and its plan are related by a projective
transformation (проективное преобразование) of the plane: eight parameters,
fixed by four point pairs of which no three lie on a line.  The fits
themselves — similarity, affine and projective, exact for the minimum number
of pairs and least squares beyond, each with residuals — are
:mod:`aerophoto.plane`'s (layer 1) and are re-exported here:
:func:`fit_similarity`, :func:`fit_affine`, :func:`fit_projective`, :func:`fit`
(→ :class:`Fit` with ``residuals``, ``rms``, ``max_residual``).  This package
adds what the guide does with them, one module per concern:

=========  ===================================================================  ==========
module     what                                                                 guide
=========  ===================================================================  ==========
``grids``  mutual projective grids from four points — by central directions     §10
           (exact: :func:`projective_grid`, :func:`diagonal_grid`) and by
           proportional division (:func:`proportional_grid`); transfer cell by
           cell (:func:`transfer`, :class:`GridPair`) and its error against the
           exact map as the grid is refined (:func:`transfer_study`)
``images`` resampling whole photos through a transformation (scikit-image's     §10, §12
           warp): :func:`warp_photo` → :class:`Raster`
``scene``  an old land-use plan and the changed ground of a new photo           §10
           (:func:`land_use_scene`)
=========  ===================================================================  ==========

Units: whatever the caller uses (mm on photos and plans, m on the ground).
The photo → plan direction is the one of the guide: points measured on the
new photo are carried onto the plan.
"""

from __future__ import annotations

from ..plane import Affine2D, Fit, Projective2D, Similarity2D, fit, fit_affine, fit_projective, fit_similarity
from . import grids, images, scene
from .grids import *  # noqa: F403 — each submodule's explicit __all__
from .images import *  # noqa: F403
from .scene import *  # noqa: F403

#: the public API: the plane fits (re-exported), every submodule's ``__all__`` and the submodules
__all__ = ["Similarity2D", "Affine2D", "Projective2D", "Fit", "fit_similarity", "fit_affine", "fit_projective", "fit",
           *grids.__all__, *images.__all__, *scene.__all__, "grids", "images", "scene"]
