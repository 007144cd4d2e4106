"""Chapter 01 · guide §2 ("Расчёт параметров аэросъёмки"): the worked example of the survey calculation, and its audit.

The guide works the twelve steps of the survey calculation for the inputs of
variant i = 0 (f = 100 mm, 1:12 000, p_x = 60 %, p_y = 30 %, L_x = 25 km,
L_y = 30 km, Z_max = 200 m, Z_min = 170 m, W = 200 km/h, 1:M = 1:10 000), one
printed line per quantity.  :data:`LINES` holds those sixteen lines as printed
(OCR cleaned, the garbling said in each line's note): the line's text, the
factors it prints with the quantity each should equal, the printed result and
the line's formula.

:func:`worked_example` recomputes the example with :func:`aerophoto.flight.plan`
and returns an :class:`~aerophoto.guide.audit.Audit`.  Each printed line gives
one :class:`~aerophoto.guide.audit.Printed` per printed factor (e.g. step 5's
factor 7.2 cm against b_x = 7.02 cm computed one line earlier) and one for its
printed result (against the value that follows from the example's inputs),
all judged by the one rule of :mod:`aerophoto.guide.audit` (0.6 of a unit of
the last printed digit; counts exact).  Four lines print factors that do not
follow — steps 5 (twice), 6 and 12 use the working-area sides for the
normative overlaps without the relief allowance — and step 12's result does
not follow either.

One inconsistency is not an arithmetic slip: step 3 raises *both* overlaps by
40·h/H.  The coefficient 40 = 100 − p_x keeps the forward overlap p_x = 60 % on
the highest ground; the side overlap p_y = 30 % would need 100 − p_y = 70
(:func:`aerophoto.flight.exact_allowance_percent`).  The audit records the
coefficient of each overlap as a printed value (``where = "step 3, relief
allowance"``) and says in its notes what the exact allowance changes (P_y,
b_y, B_y, K); :func:`side_allowance_table` sets both side by side for any plan.
The book and its graded tasks keep the guide's 40.
"""

from __future__ import annotations

from dataclasses import dataclass

import pandas as pd

from .. import flight
from .audit import Audit, digit_unit, printed

__all__ = ["Line", "LINES", "FACTOR_LABELS", "ALLOWANCE_WHERE", "worked_example", "side_allowance_table", "line_where"]

#: how the audit names each factor's quantity: plan attribute → symbol, unit
FACTOR_LABELS = {
    "Lx_km": "Lx, km", "Ly_km": "Ly, km", "f_m": "f, m", "m": "m", "Zmax_m": "Zmax, m", "Zmin_m": "Zmin, m",
    "px_percent": "px, %", "py_percent": "py, %", "h_m": "h, m", "H_m": "H, m", "l_cm": "l, cm",
    "Px_percent": "Px, %", "Py_percent": "Py, %", "bx_cm": "bx, cm", "by_cm": "by, cm", "Bx_km": "Bx, km",
    "By_km": "By, km", "n": "n", "K": "K", "S_km2": "S, km²", "LS_km": "LS, km", "W_kmh": "W, km/h",
    "blur_m": "δ, m", "M": "M", "W_ms": "W, m/s",
}


@dataclass(frozen=True)
class Line:
    """One printed line of the guide's §2 example (variant 00).

    Attributes
    ----------
    step : str
        The guide's step number ("1" … "12"; steps 3–5 have several lines).
    attr : str
        The :class:`~aerophoto.flight.FlightPlan` attribute of the line's result.
    quantity : str
        The guide's symbol ("Bx", "τ").
    text : str
        The line as printed, OCR cleaned.
    factors : tuple of (printed value, plan attribute, printed decimals)
        The numbers the line multiplies or divides, each with the quantity
        (computed one line earlier, or an input) it should equal.
    value : float
        The printed result.
    unit : str
        Its unit ("—" for counts).
    formula : callable
        The line's formula on its factors (for "what the printed factors give").
    count : bool
        The result is a count, rounded up (guide §2, steps 6–7).
    note : str
        OCR garbling and unit remarks that do not make the line wrong.
    reasons : dict
        ``{attr: reason}`` for a factor, ``{"result": reason}`` for the
        result, used where that value does not follow.
    """

    step: str
    attr: str
    quantity: str
    text: str
    factors: tuple
    value: float
    unit: str
    formula: object
    count: bool = False
    note: str = ""
    reasons: tuple = ()

    @property
    def reason_map(self) -> dict:
        return dict(self.reasons)

    @property
    def decimals(self) -> int:
        """Decimals the guide prints for the result (:data:`aerophoto.flight.GUIDE_DECIMALS`)."""
        return 0 if self.count else int(flight.GUIDE_DECIMALS[self.attr])


def line_where(line: Line) -> str:
    """The ``where`` of every printed value of ``line``: ``"step 5, Bx"``."""
    return f"step {line.step}, {line.quantity}"


#: the sixteen printed lines of guide §2's example, as printed (OCR cleaned)
LINES = (
    Line("1", "S_km2", "S", "S = 25·30 = 750 km²", ((25, "Lx_km", 0), (30, "Ly_km", 0)), 750, "km²",
         lambda a, b: a * b,
         note="The scan prints the multiplication dot as a decimal point: '25.30 = 750'."),
    Line("2", "H_m", "H", "H = 0.100·12000 = 1200 m", ((0.100, "f_m", 3), (12000, "m", 0)), 1200, "m",
         lambda a, b: a * b, note="f is entered in metres (0.100 m) so that H comes out in metres."),
    Line("3", "h_m", "h", "h = 200 − 170 = 30 m", ((200, "Zmax_m", 0), (170, "Zmin_m", 0)), 30, "m",
         lambda a, b: a - b),
    Line("3", "Px_percent", "Px", "Px = 60 + 40(30/1200) = 61.0 %",
         ((60, "px_percent", 0), (30, "h_m", 0), (1200, "H_m", 0)), 61.0, "%", lambda p, h, H: p + 40 * h / H),
    Line("3", "Py_percent", "Py", "Py = 30 + 40(30/1200) = 31.0 %",
         ((30, "py_percent", 0), (30, "h_m", 0), (1200, "H_m", 0)), 31.0, "%", lambda p, h, H: p + 40 * h / H),
    Line("4", "bx_cm", "bx", "bx = 18(100 − 61.0)/100 = 7.0 cm", ((18, "l_cm", 0), (61.0, "Px_percent", 1)), 7.0,
         "cm", lambda l, P: l * (100 - P) / 100,
         note="The scan prints the symbol as 'b_r'; the exact value is 7.02 cm."),
    Line("4", "by_cm", "by", "by = 18(100 − 31.0)/100 = 12.4 cm", ((18, "l_cm", 0), (31.0, "Py_percent", 1)), 12.4,
         "cm", lambda l, P: l * (100 - P) / 100,
         note="The scan prints the symbol as 'b_ν'; the exact value is 12.42 cm."),
    Line("5", "Bx_km", "Bx", "Bx = 7.2·12000 = 0.84 km", ((7.2, "bx_cm", 1), (12000, "m", 0)), 0.84, "km",
         lambda b, m: b * m / 1e5,
         note="cm × m gives cm on the ground; the line converts 84 000 cm to 0.84 km silently.",
         reasons=(("bx_cm", "The factor 7.2 cm is 18·(100 − 60)/100, the working-area side for the normative "
                            "px = 60 % without the relief allowance of step 3; the printed 0.84 km does follow "
                            "from bx = 7.0 cm (7.02·12000 cm = 0.842 km), whereas 7.2·12000 cm would be 0.864 km."),)),
    Line("5", "By_km", "By", "By = 12.6·12000 = 1.49 km", ((12.6, "by_cm", 1), (12000, "m", 0)), 1.49, "km",
         lambda b, m: b * m / 1e5,
         reasons=(("by_cm", "The factor 12.6 cm is 18·(100 − 30)/100, the side for the normative py = 30 % without "
                            "the relief allowance; the printed 1.49 km follows from by = 12.4 cm "
                            "(12.42·12000 cm = 1.490 km), whereas 12.6·12000 cm would be 1.512 km."),)),
    Line("6", "K", "K", "K = 30/1.51 + 1 = 22", ((30, "Ly_km", 0), (1.51, "By_km", 2)), 22, "—",
         lambda L, B: L / B + 1, count=True,
         reasons=(("By_km", "The divisor 1.51 km is 12.6·12000 cm, the misprinted factor of step 5, not the "
                            "By = 1.49 km computed there; 30/1.51 + 1 = 20.87 would round up to 21, while the "
                            "correct 30/1.490 + 1 = 21.13 rounds up to the printed 22."),)),
    Line("7", "n", "n", "n = 25/0.84 + 1 = 31", ((25, "Lx_km", 0), (0.84, "Bx_km", 2)), 31, "—",
         lambda L, B: L / B + 1, count=True,
         note="The scan reads '= 31' as '+ 31': 'n = 25/0.84 + 1 + 31'; 25/0.842 + 1 = 30.68, rounded up 31."),
    Line("8", "N", "N", "N = 31·22 = 682", ((31, "n", 0), (22, "K", 0)), 682, "—", lambda a, b: a * b),
    Line("9", "LS_km", "LS", "LS = (1.2·750)/1.49 = 604 km", ((750, "S_km2", 0), (1.49, "By_km", 2)), 604, "km",
         lambda S, B: 1.2 * S / B, note="The scan prints '1.2·750' as '1.2.750'; exactly 603.9 km."),
    Line("10", "TS_h", "TS", "TS = 604/200 = 3.0 h", ((604, "LS_km", 0), (200, "W_kmh", 0)), 3.0, "h",
         lambda L, W: L / W,
         note="The scan reads the unit '(ч)' (hours) as '(4)': 'TS = 604/200 = 3.0 (4)'; exactly 3.02 h."),
    Line("11", "tmax_s", "tmax", "tmax = (0.0001·10000)/55.6 = 0.018 s",
         ((0.0001, "blur_m", 4), (10000, "M", 0), (55.6, "W_ms", 1)), 0.018, "s", lambda d, M, W: d * M / W,
         note="δ = 0.1 mm is entered in metres and W = 200 km/h as 55.6 m/s, so tmax comes out in seconds."),
    Line("12", "tau_s", "τ", "τ = 0.86·3600/200 = 15.4 s", ((0.86, "Bx_km", 2), (200, "W_kmh", 0)), 15.4, "s",
         lambda B, W: B * 3600 / W,
         reasons=(("Bx_km", "The base 0.86 km is 7.2·12000 cm from the misprinted factor of step 5, not "
                            "Bx = 0.84 km."),
                  ("result", "Even 0.86·3600/200 = 15.48 s would round to 15.5 s, not 15.4 s; "
                             "the correct τ = 0.842·3600/200 = 15.2 s."))),
)

ALLOWANCE_WHERE = "step 3, relief allowance"


def _value(p: flight.FlightPlan, attr: str) -> float:
    extra = {"f_m": p.f_mm / 1000.0, "l_cm": p.l_cm, "blur_m": p.blur_mm / 1000.0}
    return extra[attr] if attr in extra else getattr(p, attr)


def _fmt(x: float, decimals: int) -> str:
    return f"{x:.{decimals}f}"


def _allowance_values(p: flight.FlightPlan) -> tuple:
    """The coefficient of h/H in step 3's two overlaps: printed 40, and the exact 100 − p."""
    guide, exact = flight.side_spacing(p), flight.side_spacing(p, exact=True)
    hi = p.Zmin_m + p.h_m
    side_high = flight.overlaps_at(p, hi)[1]
    reason = (f"40 = 100 − px is exact for the forward overlap (px = {p.px_percent:g} %); the side overlap uses it "
              f"too, where keeping py = {p.py_percent:g} % on the highest ground needs 100 − py = "
              f"{100 - p.py_percent:g}: Py = {p.py_percent:g} + {100 - p.py_percent:g}·{p.h_m:g}/{p.H_m:g} = "
              f"{exact['Py_percent']:.2f} % instead of {guide['Py_percent']:.1f} %, by = {exact['by_cm']:.3f} instead "
              f"of {guide['by_cm']:.2f} cm, By = {exact['By_km']:.3f} instead of {guide['By_km']:.3f} km, "
              + (f"K = {guide['K']} either way" if exact['K'] == guide['K'] else
                 f"K = {exact['K']} instead of {guide['K']}")
              + f" ({p.Ly_km:g}/{exact['By_km']:.3f} + 1 = {exact['K_ratio'] + 1:.2f}). With 40 the side overlap on "
              f"the highest ground (Z = {hi:g} m) is {side_high:.2f} %, below py.")
    return (
        printed(ALLOWANCE_WHERE, "coefficient of h/H in Px (exact: 100 − px)", 40, 100 - p.px_percent, 1,
                note="The guide's 40 keeps px on the highest ground."),
        printed(ALLOWANCE_WHERE, "coefficient of h/H in Py (exact: 100 − py)", 40, 100 - p.py_percent, 1,
                reason=reason, note="The book and the graded tasks keep the guide's 40."),
    )


def side_allowance_table(p: flight.FlightPlan) -> pd.DataFrame:
    """P_y, b_y, B_y and K of plan ``p`` with the guide's allowance 40·h/H beside the exact (100 − p_y)·h/H.

    Rows: ``Py, %``, ``by, cm``, ``By, km``, ``K``; columns ``guide: 40·h/H``,
    ``exact: (100 − py)·h/H`` and ``difference`` (exact − guide).  The guide's
    column is what :func:`aerophoto.flight.plan` computes (and the graded tasks
    ask for); the exact one keeps p_y on the highest ground.
    """
    guide, exact = flight.side_spacing(p), flight.side_spacing(p, exact=True)
    rows = [("allowance, %", "allowance_percent", 3), ("Py, %", "Py_percent", 2), ("by, cm", "by_cm", 3),
            ("By, km", "By_km", 4), ("K", "K", 0)]
    out = []
    for label, key, d in rows:
        a, b = guide[key], exact[key]
        if key == "K":
            out.append((label, int(a), int(b), int(b - a)))
        else:
            out.append((label, round(float(a), d), round(float(b), d), round(float(b - a), d)))
    df = pd.DataFrame(out, columns=["quantity", "guide: 40·h/H", f"exact: (100 − py)·h/H = {100 - p.py_percent:g}·h/H",
                                    "difference"], dtype=object)
    return df.set_index("quantity")


def worked_example() -> Audit:
    """The guide's §2 example recomputed, with every printed factor and result checked.

    Returns
    -------
    Audit
        ``table`` — one row per printed line (index: the guide's symbol):
        step, the line as printed, the factors that follow (the quantities
        they should equal, at the precision the guide prints them), what the
        printed factors give, the computed value (full precision) and as
        printed, the unit, whether every value of the line follows, and the
        OCR note.  ``values`` — for each line its printed factors
        (``quantity = "factor bx, cm"``) and its result (``"Bx, km"``), each a
        :class:`~aerophoto.guide.audit.Printed` with ``where = "step 5, Bx"``
        (:func:`line_where`); then the coefficient of h/H of the two overlaps
        (``where = "step 3, relief allowance"``).  ``printed_table`` — the
        lines as printed.  ``notes`` — the side-overlap allowance, guide vs
        exact.  ``result`` — the :class:`~aerophoto.flight.FlightPlan`.
    """
    p = flight.guide_example()
    values, rows, printed_rows = [], [], []
    for line in LINES:
        where = line_where(line)
        reasons = line.reason_map
        line_values = []
        for value, attr, d in line.factors:
            line_values.append(printed(where, f"factor {FACTOR_LABELS[attr]}", value, float(_value(p, attr)),
                                       digit_unit(d), reason=reasons.get(attr, "")))
        computed = _value(p, line.attr)
        unit_label = "" if line.unit == "—" else f", {line.unit}"
        line_values.append(printed(where, f"{line.quantity}{unit_label}", line.value, float(computed),
                                   1.0 if line.count else digit_unit(line.decimals),
                                   reason=reasons.get("result", ""), note=line.note))
        values += line_values
        give = float(line.formula(*[f for f, _, _ in line.factors]))
        as_printed = computed if line.count else round(float(computed), line.decimals)
        rows.append({
            "quantity": line.quantity, "step": line.step, "printed": line.text,
            "factors that follow": ", ".join(_fmt(round(float(_value(p, a)), d), d) for _, a, d in line.factors),
            "printed factors give": give, "computed": float(computed),
            "as printed": str(as_printed) if line.count else _fmt(as_printed, line.decimals),
            "unit": line.unit, "follows": all(v.follows for v in line_values), "note": line.note,
        })
        printed_rows.append({"quantity": line.quantity, "step": line.step, "printed": line.text,
                             "value": line.value, "unit": line.unit})
    values += list(_allowance_values(p))
    guide, exact = flight.side_spacing(p), flight.side_spacing(p, exact=True)
    notes = (
        "Side-overlap allowance (step 3): the guide's 40·h/H gives "
        f"Py = {guide['Py_percent']:.2f} %, by = {guide['by_cm']:.3f} cm, By = {guide['By_km']:.4f} km, "
        f"K = {guide['K']}; the exact (100 − py)·h/H = {100 - p.py_percent:g}·h/H gives "
        f"Py = {exact['Py_percent']:.2f} %, by = {exact['by_cm']:.3f} cm, By = {exact['By_km']:.4f} km, "
        f"K = {exact['K']}. The book and its graded tasks follow the guide (40).",
    )
    table = pd.DataFrame(rows).set_index("quantity")
    return Audit("guide §2", "Worked example. The survey parameters of variant 00", table, tuple(values),
                 pd.DataFrame(printed_rows).set_index("quantity"), notes, p)

