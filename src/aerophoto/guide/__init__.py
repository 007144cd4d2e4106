"""The source documents' printed tables, transcribed once, and their audits.

One module per section of the course-design guide (``s02`` for §2, ``s04``
for §4, …) and per article (``a000`` … ``a003``).  Each holds the printed
numbers as data — what the scan shows, OCR garbling cleaned and said so — and
functions returning :class:`~aerophoto.guide.audit.Audit` records: the table
recomputed from its own printed inputs, every printed value beside the value
that follows, and the reason wherever one does not.  The rule that decides
"follows" is one for all tables (:data:`~aerophoto.guide.audit.TOLERANCE_UNITS`).

Submodules load on first use.
"""

from __future__ import annotations

import importlib

from .audit import TOLERANCE_UNITS, Audit, Printed, digit_unit, discrepancy_frame, printed, render

_SUBMODULES = ("s02", "s03", "s04", "s05", "s06", "s07", "s08", "s09", "s10", "s11", "s12", "s13", "s14", "a000", "a001", "a002", "a003")

__all__ = ["TOLERANCE_UNITS", "Audit", "Printed", "printed", "digit_unit", "render", "discrepancy_frame",
           *_SUBMODULES]


def __getattr__(name: str):
    if name in _SUBMODULES:
        module = importlib.import_module(f".{name}", __name__)
        globals()[name] = module
        return module
    raise AttributeError(f"module 'aerophoto.guide' has no attribute {name!r}")
