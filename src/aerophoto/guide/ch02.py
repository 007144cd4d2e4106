"""Chapter 02 · guide §3 ("Оценка качества материалов аэросъёмки"): table 1, the visual control of the photos.

Table 1 records, for four photos of the guide's example (nos. 542–545), the
photographic quality judged by eye: sharpness (резкость), the rendering of
fine detail (проработка деталей) and defects (дефекты).  It has **no
checkable numbers** — the photo numbers are labels and every other cell is a
verdict — so there is nothing to audit and no :class:`~aerophoto.guide.audit.Audit`:
:func:`table_1` returns the table as printed.

The section's numbers are tolerances (overlaps ≥ 56 % and ≥ 20 %,
straightness ≤ 2 %, crab ≤ 5°/7°/10°, tilt ≤ 3°, scale difference 2–3 %,
flying height ≤ 3 %), not results computed from inputs; they live in
:mod:`aerophoto.quality` as its constants.  The guide's worked example has no
calculation for this section (chapter 02 checks a simulated flight instead).
"""

from __future__ import annotations

import pandas as pd

__all__ = ["TABLE_1", "table_1"]

#: table 1 as printed: photo number, sharpness, fine detail, defects (English, Russian in brackets)
TABLE_1 = (
    (542, "good (хор.)", "good (хор.)", "no (нет)"),
    (543, "fair (удовл.)", "fair (удовл.)", "yes (да)"),
    (544, "fair (удовл.)", "fair (удовл.)", "yes (да)"),
    (545, "fair (удовл.)", "fair (удовл.)", "yes (да)"),
)


def table_1() -> pd.DataFrame:
    """The guide's table 1 (§3) as printed: visual control of four photos (no computation in it).

    Index ``photo`` (the photo's number); columns ``sharpness``,
    ``fine detail``, ``defects``.
    """
    return pd.DataFrame(list(TABLE_1), columns=["photo", "sharpness", "fine detail", "defects"]).set_index("photo")
