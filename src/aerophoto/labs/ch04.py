"""Chapter 04 · guide §5: the student's tilt sheet — nine pricked points in three zones, their plan and truth.

The sheet itself is built by :mod:`aerophoto.labs.displacement`, which chapters 03 and 04 share (one camera,
one site, one way of pricking points); this module is chapter 04's door to it, so that the chapter key
(``aerophoto.labs.chNN``) finds the lab from the chapter number alone.
"""

from __future__ import annotations

from .displacement import M_PLAN, PHOTO_PX, TILT_BASES, TILT_NAMES, LabSheet, PlanImage, tilt_sheet

__all__ = ["TILT_NAMES", "TILT_BASES", "PHOTO_PX", "M_PLAN", "LabSheet", "PlanImage", "tilt_sheet", "photo",
           "plan"]


def photo(i: int, n_px: int = PHOTO_PX):
    """Variant ``i``'s tilt photo (:func:`aerophoto.labs.displacement.photo_of` with ``kind="tilt"``)."""
    from .displacement import photo_of

    return photo_of("tilt", i, n_px)


def plan(i: int, px_mm: float = 0.25, contour_step_mm: float = 2.0) -> PlanImage:
    """Variant ``i``'s plan at 1:M of the tilt sheet's points (:func:`~aerophoto.labs.displacement.plan_of`)."""
    from .displacement import plan_of

    return plan_of("tilt", i, px_mm, contour_step_mm)
