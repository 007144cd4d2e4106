"""One audit type for every printed table of the source documents.

The guide is an OCR'd scan with arithmetic slips.  The book reproduces each of
its tables from the table's own printed inputs and sets every printed number
beside the number that follows from them.  One record per printed number,
:class:`Printed`, and one record per table, :class:`Audit`; one function,
:func:`render`, shows an audit in a notebook.

The rule (the same for every table)
-----------------------------------
A printed value *follows* from its inputs when it lies within
``TOLERANCE_UNITS`` = 0.6 of a unit of its last printed digit of the computed
value: half a unit for its own rounding, and a tenth more for the hand
rounding of intermediate values that the guide's authors did between lines
(e.g. a height printed to 1 m, then used).  A whole number (a count of strips,
photos, points) has a unit of 1 and must therefore be exact.  Interval checks
(a corrected length that must lie between the limits two corrections allow)
follow when the printed value lies within the interval widened by the same
tolerance.

A value that does not follow carries the reason — a sentence saying what
went wrong (a copied cell, a misprinted factor, a reversed sign) and what the
right value is.  The tests require a specific reason for every value that
does not follow and none for a value that does.
"""

from __future__ import annotations

import html
import math
from dataclasses import dataclass, field, replace

import pandas as pd

__all__ = ["TOLERANCE_UNITS", "GENERIC_REASON", "Printed", "Audit", "FullTextFrame", "printed", "digit_unit", "render",
           "discrepancy_frame"]

TOLERANCE_UNITS = 0.6
"""How far, in units of its last printed digit, a printed value may sit from the computed one and still follow."""

GENERIC_REASON = "does not follow from its printed inputs"


def digit_unit(text_or_decimals) -> float:
    """The unit of the last printed digit: ``"7.0"`` → 0.1, ``"15220"`` → 1, ``2`` (decimals) → 0.01.

    For an integer number of decimals the unit is 10⁻ᵈ; for a printed string
    the decimals are counted after the decimal point (comma or dot).
    """
    if isinstance(text_or_decimals, str):
        t = text_or_decimals.strip().replace(",", ".")
        d = len(t.split(".", 1)[1]) if "." in t else 0
        return 10.0 ** (-d)
    return 10.0 ** (-int(text_or_decimals))


@dataclass(frozen=True)
class Printed:
    """One printed number of a source table against the value its own inputs give.

    Attributes
    ----------
    where : str
        Where it is printed: ``"table 2, I-2"``, ``"step 5"``, ``"table 8, 498/2 – 496/2"``.
    quantity : str
        What it is, with the guide's symbol and unit where useful: ``"m_i"``, ``"Bx, km"``.
    printed : float
        The value as printed (a ratio 1/N is stored as N).
    computed : float
        The value that follows from the table's printed inputs, at full
        precision (for an interval check: the admissible value nearest to the
        printed one).
    unit : float
        The unit of the printed value's last digit (0.1 for "7.0"; 1 for counts).
    reason : str
        Why the printed value does not follow; empty when it follows.
    note : str
        A remark that does not make the value wrong (OCR garbling, units).
    bounds : (lo, hi) or None
        For interval checks: the range the inputs allow.
    printed_text, computed_text : str
        How to show the two values (``"1/72"``, ``"1/71.2"``); by default the
        printed value with its decimals and the computed one with a digit more.
    """

    where: str
    quantity: str
    printed: float
    computed: float
    unit: float
    reason: str = ""
    note: str = ""
    bounds: tuple | None = None
    printed_text: str = ""
    computed_text: str = ""

    @property
    def tolerance(self) -> float:
        """Largest |printed − computed| explained by rounding: ``TOLERANCE_UNITS`` × unit."""
        return TOLERANCE_UNITS * self.unit

    @property
    def follows(self) -> bool:
        """The printed value follows from its inputs (the one rule of this module)."""
        eps = 1e-9 * max(1.0, abs(self.computed))
        if self.bounds is not None:
            lo, hi = self.bounds
            return lo - self.tolerance - eps <= self.printed <= hi + self.tolerance + eps
        return abs(self.printed - self.computed) <= self.tolerance + eps

    @property
    def decimals(self) -> int:
        return max(0, int(round(-math.log10(self.unit)))) if self.unit < 1 else 0

    def shown_printed(self) -> str:
        return self.printed_text or f"{self.printed:.{self.decimals}f}"

    def shown_computed(self) -> str:
        if self.computed_text:
            return self.computed_text
        if self.bounds is not None:
            return f"{self.bounds[0]:.{self.decimals + 1}f} … {self.bounds[1]:.{self.decimals + 1}f}"
        return f"{self.computed:.{self.decimals + 1}f}"


def printed(where: str, quantity: str, value: float, computed: float, unit: float, *, reasons=None,
            reason: str = "", note: str = "", bounds=None, printed_text: str = "", computed_text: str = "",
            **fmt) -> Printed:
    """Build a :class:`Printed`, attaching the reason only when the value does not follow.

    Parameters
    ----------
    reasons : dict, optional
        ``{(where, quantity): template}``: the reasons known for this table; a
        template may use ``{c}`` (the computed value) and the keywords ``fmt``.
    reason : str
        The reason for this value directly (instead of ``reasons``).
    """
    p = Printed(where, quantity, float(value), float(computed), float(unit), "", note, bounds, printed_text,
                computed_text)
    if p.follows:
        return p
    template = reason or (reasons or {}).get((where, quantity), GENERIC_REASON)
    text = template.format(c=computed, **fmt) if "{" in template else template
    return replace(p, reason=text)


class FullTextFrame(pd.DataFrame):
    """A DataFrame that shows its text cells in full (a reason is a sentence; pandas would cut it at 50 characters)."""

    @property
    def _constructor(self):
        return FullTextFrame

    def _repr_html_(self):
        with pd.option_context("display.max_colwidth", None):
            return super()._repr_html_()

    def __repr__(self):
        with pd.option_context("display.max_colwidth", None):
            return super().__repr__()


@dataclass(frozen=True)
class Audit:
    """A source table recomputed from its printed inputs, with every printed number checked.

    Attributes
    ----------
    source : str
        The document and section: ``"guide §4"``, ``"article 003"``.
    title : str
        The table's title, e.g. ``"Table 2. Partial and mean scales of the bases"``.
    table : pandas.DataFrame
        The recomputed table, laid out like the printed one.
    values : tuple of :class:`Printed`
        Every printed number that can be computed from the inputs.
    printed_table : pandas.DataFrame or None
        The table as printed (OCR cleaned), for reference.
    notes : tuple of str
        Remarks on the table that are not single numbers.
    result : object
        The package's computed result behind ``table`` (e.g. a ScaleTable), for further use.
    """

    source: str
    title: str
    table: pd.DataFrame
    values: tuple = ()
    printed_table: pd.DataFrame | None = None
    notes: tuple = ()
    result: object = field(default=None, repr=False, compare=False)

    @property
    def discrepancies(self) -> tuple:
        """The printed values that do not follow from their inputs."""
        return tuple(p for p in self.values if not p.follows)

    def comparison(self, *, only_discrepancies: bool = True) -> pd.DataFrame:
        """Printed vs computed, one row per value: where, quantity, printed, computed, verdict, reason."""
        rows = [p for p in self.values if not (only_discrepancies and p.follows)]
        return FullTextFrame(
            {"where": [p.where for p in rows], "quantity": [p.quantity for p in rows],
             "printed": [p.shown_printed() for p in rows], "computed": [p.shown_computed() for p in rows],
             "verdict": ["follows" if p.follows else "does not follow" for p in rows],
             "reason": [p.reason for p in rows]},
            columns=["where", "quantity", "printed", "computed", "verdict", "reason"],
        )

    def _repr_html_(self) -> str:
        return render(self)


def discrepancy_frame(audits) -> pd.DataFrame:
    """Every value that does not follow, over several audits: source, table, where, quantity, printed, computed, reason."""
    rows = []
    for a in audits:
        for p in a.discrepancies:
            rows.append({"source": a.source, "table": a.title.split(".")[0], "where": p.where,
                         "quantity": p.quantity, "printed": p.shown_printed(), "computed": p.shown_computed(),
                         "reason": p.reason})
    return FullTextFrame(rows, columns=["source", "table", "where", "quantity", "printed", "computed", "reason"])


def _html_frame(df: pd.DataFrame, caption: str, number=None) -> str:
    """A small HTML table (no presentation-layer import: the guide layer renders its own audits).

    ``number`` (text → text) writes a cell's numbers in the reader's format (:func:`render`); a whole float is
    shown as a whole number (``11934``, not ``11934.0``)."""
    number = number or str
    head = "".join(f"<th>{html.escape(str(c))}</th>" for c in [df.index.name or ""] + list(df.columns))
    body = []
    for idx, row in df.iterrows():
        cells = "".join(f"<td>{html.escape('' if _blank(v) else number(_text(v)))}</td>" for v in row)
        body.append(f"<tr><th>{html.escape(number(str(idx)))}</th>{cells}</tr>")
    cap = f"<caption style='caption-side:top;text-align:left;font-weight:bold'>{html.escape(caption)}</caption>"
    return (f"<table class='aerophoto-audit' style='border-collapse:collapse;font-size:13px'>{cap}"
            f"<thead><tr>{head}</tr></thead><tbody>{''.join(body)}</tbody></table>")


def _text(v) -> str:
    """A cell as text: a whole float as a whole number, any other float with 4 significant digits (no exponent
    for the table's magnitudes), text as it is."""
    if isinstance(v, float) and math.isfinite(v):
        if v.is_integer():
            return str(int(v))
        digits = max(0, 3 - math.floor(math.log10(abs(v))))
        return f"{v:.{digits}f}".rstrip("0").rstrip(".")
    return str(v)


def _blank(v) -> bool:
    return v is None or (isinstance(v, float) and math.isnan(v))


def render(audit: Audit, number=None) -> str:
    """An audit as HTML: the recomputed table left; printed vs computed (the values that do not follow) right.

    ``number`` (text → text) rewrites the numbers of every cell and note in the book's format; the notebooks get
    :mod:`aerophoto.i18n.numfmt`'s (:func:`aerophoto.plots.register_table_display`), without it they stay as
    written."""
    left = _html_frame(audit.table, f"{audit.title} — recomputed by aerophoto ({audit.source})", number)
    disc = audit.comparison()
    if len(disc):
        right = _html_frame(disc.drop(columns=["verdict"]).set_index("where"),
                            "Printed vs computed: the values that do not follow", number)
    else:
        right = "<p><b>Printed vs computed:</b> every printed number follows from its inputs.</p>"
    notes = "".join(f"<li>{html.escape((number or str)(n))}</li>" for n in audit.notes)
    notes_html = f"<ul style='margin:4px 0 0 16px;padding:0;font-size:13px'>{notes}</ul>" if notes else ""
    return ("<div class='aerophoto-guide-table' style='display:flex;flex-wrap:wrap;gap:16px;align-items:flex-start'>"
            "<style>.aerophoto-audit td,.aerophoto-audit th{text-align:left;padding:2px 6px;"
            "border-bottom:1px solid #ddd}</style>"
            f"<div>{left}</div><div style='flex:1 1 420px;max-width:620px'>{right}{notes_html}</div></div>")
