"""Whole numbers in the book's format, for every layer: digits grouped by three with U+202F from five digits on.

The one implementation of the grouping rule of :mod:`aerophoto.i18n.numfmt` (which imports it), here in the
foundation so that the physics, the virtual world and the course's content (guide tables, lab summaries, the
quality report's conclusion) write ``1:12 300`` exactly as the presentation layer does — never with a plain
space, which a reader cannot tell from two numbers (12 and 300) and which breaks across a line.  Whole numbers
need no decimal mark, so nothing here depends on the language.

>>> whole(11859.2)
'11\u202f859'
>>> scale(17700)
'1:17\u202f700'
>>> whole(2706)
'2706'
"""

from __future__ import annotations

import math

__all__ = ["GROUP", "MINUS", "group", "whole", "scale"]

#: the thousands separator: a narrow no-break space
GROUP = "\u202f"
#: the minus sign
MINUS = "\u2212"


def group(digits: str) -> str:
    """A string of digits grouped by three from the right with :data:`GROUP`, when it has five digits or more."""
    if len(digits) < 5:
        return digits
    head = len(digits) % 3 or 3
    return GROUP.join([digits[:head]] + [digits[i:i + 3] for i in range(head, len(digits), 3)])


def whole(x) -> str:
    """``x`` rounded to a whole number (half to even), grouped, with a true minus; an error names a non-finite ``x``."""
    v = float(x)
    if not math.isfinite(v):
        raise ValueError(f"x = {x!r} is not a finite number; a whole number prints only a finite one")
    n = round(v)
    return (MINUS if n < 0 else "") + group(str(abs(n)))


def scale(m) -> str:
    """The scale 1/m as ``1:17 700`` (``m``, the scale denominator, to the nearest whole); ``m`` must be > 0."""
    v = float(m)
    if not (math.isfinite(v) and v > 0):
        raise ValueError(f"m = {m!r} is not a scale denominator; expected a finite number > 0")
    return "1:" + whole(v)
