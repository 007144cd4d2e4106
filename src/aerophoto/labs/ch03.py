"""Chapter 03 · guide §4: the student's relief sheet — six pricked points in two zones, their plan and truth.

The sheet itself is built by :mod:`aerophoto.labs.displacement`, which chapters 03 and 04 share (one camera,
one site, one way of pricking points); this module is chapter 03's door to it, so that the chapter key
(``aerophoto.labs.chNN``) finds the lab from the chapter number alone.
"""

from __future__ import annotations

from .displacement import M_PLAN, PHOTO_PX, RELIEF_BASES, RELIEF_NAMES, LabSheet, PlanImage, relief_sheet

__all__ = ["RELIEF_NAMES", "RELIEF_BASES", "PHOTO_PX", "M_PLAN", "LabSheet", "PlanImage", "relief_sheet", "photo",
           "plan"]


def photo(i: int, n_px: int = PHOTO_PX):
    """Variant ``i``'s relief photo (:func:`aerophoto.labs.displacement.photo_of` with ``kind="relief"``)."""
    from .displacement import photo_of

    return photo_of("relief", i, n_px)


def plan(i: int, px_mm: float = 0.25, contour_step_mm: float = 2.0) -> PlanImage:
    """Variant ``i``'s plan at 1:M of the relief sheet's points (:func:`~aerophoto.labs.displacement.plan_of`)."""
    from .displacement import plan_of

    return plan_of("relief", i, px_mm, contour_step_mm)
