"""Digital elevation models, the contours drawn from them, and the densification that feeds them (article 000).

=================  ==========================================================================
module             what
=================  ==========================================================================
``densification``  Lysenko's formula for the accuracy of height densification by block
                   phototriangulation (:func:`lysenko_mz_m`, read as explained in
                   :data:`aerophoto.guide.ch16.LYSENKO_READING`) and a block simulated on a
                   terrain to hold it against (:func:`block_layout`, :func:`block_precision`)
``surface``        a map sheet (:class:`Sheet`), the regular DEM (:func:`grid_dem`), the
                   structural lines of the relief (:func:`structural_lines`) and the TINs built
                   on them (:func:`grid_with_lines`, :func:`structural_dem`), contours
                   (:func:`contour_lines`) and their accuracy against the true surface
                   (:func:`contour_accuracy`, :func:`evaluate`)
=================  ==========================================================================

The ground is any :class:`aerophoto.geometry.Terrain` — in the book, the virtual site
(:func:`aerophoto.site.get_site`), whose true surface makes every error measurable.
"""

from __future__ import annotations

from . import densification, surface
from .densification import (ARTICLE_BLOCK, PARALLAX_READING, BlockLayout, BlockPrecision, block_layout,
                            block_precision, bundle_counts, lysenko_mz_m, lysenko_ratio, lysenko_study)
from .surface import (NOISE_FACTOR, STANDARD_INTERVALS_M, DEM, ContourAccuracy, Sheet, SheetResult,
                      StructuralLines, contour_accuracy, contour_levels, contour_lines, dem_accuracy, evaluate,
                      correlated_noise_factor, grid_dem, grid_nodes, grid_with_lines, predicted_rms, spacing_study,
                      standard_interval,
                      structural_dem, structural_lines, tin_dem)

__all__ = ["densification", "surface", "ARTICLE_BLOCK", "PARALLAX_READING", "BlockLayout", "BlockPrecision",
           "block_layout", "block_precision", "bundle_counts", "lysenko_mz_m", "lysenko_ratio", "lysenko_study", "NOISE_FACTOR",
           "STANDARD_INTERVALS_M", "DEM", "ContourAccuracy", "Sheet", "SheetResult", "StructuralLines",
           "contour_accuracy", "contour_levels", "contour_lines", "correlated_noise_factor", "dem_accuracy",
           "evaluate", "grid_dem",
           "grid_nodes", "grid_with_lines", "predicted_rms", "spacing_study", "standard_interval", "structural_dem",
           "structural_lines", "tin_dem"]
