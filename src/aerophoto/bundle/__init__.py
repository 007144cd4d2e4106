"""Bundle block adjustment (блочная фототриангуляция по методу связок): article 002, chapters 14 and 15.

One module per concern:

================  ===========================================================================
module            what
================  ===========================================================================
``collinearity``  the collinearity equations vectorised over a block, their derivatives, and
                  the (X, Y, Z, ω, φ, κ) exterior orientation converted from a geometry Pose
``block``         :class:`Measurements` — photos, points (tie, control, check, field), image
                  observations with a priori σ, control coordinates with σ; validation;
                  :func:`simulate_measurements` from a known truth
``design``        :func:`standard_points`: tie points at the standard (Gruber) positions
``stages``        article 002's three stages: relative orientation and strip models (the
                  method of continuation), joined strips, the block on its control
                  (:func:`three_stage`), 3-D similarity fits
``solve``         :func:`adjust` (the reduced normal equations, or scipy's least_squares with
                  the sparse Jacobian), :func:`precision` (covariances, redundancy numbers),
                  :func:`data_snooping`, :func:`error_ellipse`, :func:`point_covariance`
================  ===========================================================================

Units: ground coordinates in metres (X east, Y north, Z up), photo coordinates in mm from the
principal point (as :mod:`aerophoto.geometry`), angles in radians inside the adjustment.
"""

from __future__ import annotations

from . import block, collinearity, design, solve, stages
from .block import *  # noqa: F403
from .collinearity import *  # noqa: F403
from .design import *  # noqa: F403
from .solve import *  # noqa: F403
from .stages import *  # noqa: F403

__all__ = [*block.__all__, *collinearity.__all__, *design.__all__, *solve.__all__, *stages.__all__,
           "block", "collinearity", "design", "solve", "stages"]
