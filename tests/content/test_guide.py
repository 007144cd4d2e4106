"""aerophoto.guide: the source documents' printed tables and their audits (the one rule of guide.audit; chapter
01's worked example, chapter 02's table 1, every chapter module's audits).  The audits of the other chapters'
tables are tested beside the physics that recomputes them (tests/physics/: test_displacement, test_triangulation,
test_rectify, test_accuracy, test_budget)."""

import numpy as np
from pytest import approx

from aerophoto import flight, guide
from aerophoto import quality as q


# --------------------------------------------------------------------------- chapter 01: the worked example (guide §2)
def _lines_that_differ(audit):
    """The guide's symbols of the printed lines with a factor or result that does not follow."""
    lines = {guide.ch01.line_where(line): line.quantity for line in guide.ch01.LINES}
    return {lines[p.where] for p in audit.discrepancies if p.where in lines}


def test_audit_flags_exactly_the_lines_that_differ():
    a = guide.ch01.worked_example()
    assert len(a.table) == 16
    assert _lines_that_differ(a) == {"Bx", "By", "K", "τ"}
    assert set(a.table.index[~a.table["follows"].astype(bool)]) == {"Bx", "By", "K", "τ"}
    factor = {p.where.split(", ")[1] for p in a.discrepancies if p.quantity.startswith("factor")}
    assert factor == {"Bx", "By", "K", "τ"}
    # the printed result does not follow from the printed factors (the one rule: 0.6 of the last digit)
    arithmetic = set()
    for line in guide.ch01.LINES:
        give = a.table.loc[line.quantity, "printed factors give"]
        if line.count:
            wrong = np.ceil(give - 1e-9) != line.value
        else:
            wrong = abs(give - line.value) > 0.6 * 10.0 ** -line.decimals
        if wrong:
            arithmetic.add(line.quantity)
    assert arithmetic == {"Bx", "By", "K", "τ"}
    results = {p.where.split(", ")[1] for p in a.discrepancies
               if not p.quantity.startswith("factor") and p.where != guide.ch01.ALLOWANCE_WHERE}
    assert results == {"τ"}
    assert all(len(p.reason) > 20 for p in a.discrepancies)
    assert all(p.reason == "" for p in a.values if p.follows)


def test_audit_numbers():
    a = guide.ch01.worked_example()
    t = a.table
    # what the misprinted factors give
    assert t.loc["Bx", "printed factors give"] == approx(0.864)     # 7.2·12000 cm
    assert t.loc["By", "printed factors give"] == approx(1.512)     # 12.6·12000 cm
    assert t.loc["K", "printed factors give"] == approx(30 / 1.51 + 1)   # 20.87 → would be 21
    assert t.loc["τ", "printed factors give"] == approx(15.48)      # 0.86·3600/200
    # the factors that follow from the line before
    assert t.loc["Bx", "factors that follow"] == "7.0, 12000"
    assert t.loc["By", "factors that follow"] == "12.4, 12000"
    assert t.loc["K", "factors that follow"] == "30, 1.49"
    assert t.loc["τ", "factors that follow"] == "0.84, 200"
    # the correct values
    assert t.loc["τ", "computed"] == approx(15.1632)
    assert t.loc["τ", "as printed"] == "15.2"
    assert t.loc["K", "as printed"] == "22" and t.loc["n", "as printed"] == "31"
    assert t.loc["LS", "computed"] == approx(603.8647, abs=1e-4)
    assert t.loc["TS", "computed"] == approx(3.0193, abs=1e-4)
    # each misprinted factor against the value computed one line earlier
    by = {(p.where, p.quantity): p for p in a.values}
    bx = by[("step 5, Bx", "factor bx, cm")]
    assert (bx.printed, bx.computed, bx.unit, bx.follows) == (7.2, approx(7.02), approx(0.1), False)
    assert by[("step 6, K", "factor By, km")].computed == approx(1.4904)
    assert by[("step 12, τ", "τ, s")].printed == 15.4 and not by[("step 12, τ", "τ, s")].follows
    # OCR remarks are notes, not slips
    assert "ч" in t.loc["TS", "note"] and "+ 31" in t.loc["n", "note"]
    assert "ч" in by[("step 10, TS", "TS, h")].note
    assert t.loc["n", "follows"] and t.loc["TS", "follows"]


def test_audit_side_overlap_allowance_shows_both():
    a = guide.ch01.worked_example()
    coeff = {p.quantity: p for p in a.values if p.where == guide.ch01.ALLOWANCE_WHERE}
    fwd = next(p for q, p in coeff.items() if "Px" in q)
    side = next(p for q, p in coeff.items() if "Py" in q)
    assert (fwd.printed, fwd.computed, fwd.follows) == (40, 40, True)
    assert (side.printed, side.computed, side.follows) == (40, 70, False)
    assert "31.75" in side.reason and "12.285" in side.reason and "1.474" in side.reason and "29.23" in side.reason
    assert "31.75" in a.notes[0] and "1.4904" in a.notes[0] and "1.4742" in a.notes[0]


def test_side_allowance_for_variant_00():
    t = guide.ch01.side_allowance_table(flight.guide_example())
    g, e = t.columns[0], t.columns[1]
    assert list(t.index) == ["allowance, %", "Py, %", "by, cm", "By, km", "K"]
    assert t.loc["allowance, %", g] == approx(1.0) and t.loc["allowance, %", e] == approx(1.75)
    assert t.loc["Py, %", g] == approx(31.0) and t.loc["Py, %", e] == approx(31.75)
    assert t.loc["by, cm", g] == approx(12.42) and t.loc["by, cm", e] == approx(12.285)
    assert t.loc["By, km", g] == approx(1.4904) and t.loc["By, km", e] == approx(1.4742)
    assert t.loc["K", g] == 22 and t.loc["K", e] == 22                 # 30/1.4742 + 1 = 21.35 → 22
    assert t.loc["By, km", "difference"] == approx(-0.0162)


# --------------------------------------------------------------------------- guide §3, table 1
def test_guide_table_1_as_printed():
    t = guide.ch02.table_1()
    assert list(t.index) == [542, 543, 544, 545]
    assert list(t.columns) == ["sharpness", "fine detail", "defects"]
    assert t.loc[542, "sharpness"] == "good (хор.)" and t.loc[545, "defects"] == "yes (да)"
    assert not hasattr(q, "guide_table_1")
    assert "no checkable numbers" in " ".join(guide.ch02.__doc__.replace("**", "").split())


# --------------------------------------------------------------------------- the one rule, every chapter's audits
def test_the_one_rule_is_six_tenths_of_the_last_printed_digit():
    assert guide.TOLERANCE_UNITS == 0.6
    assert guide.printed("step 1", "H, m", 1200.0, 1200.59, 1.0).follows
    slip = guide.printed("step 1", "H, m", 1200.0, 1200.61, 1.0, reasons={("step 1", "H, m"): "H = {c:.2f} m"})
    assert not slip.follows and slip.reason == "H = 1200.61 m"
    assert guide.printed("step 2", "H, m", 1200.0, 1201.0, 1.0).reason == guide.audit.GENERIC_REASON
    p = guide.Printed("table 2", "δh, mm", 0.3, 0.2, 0.1)
    assert (p.tolerance, p.follows, p.shown_printed(), p.shown_computed()) == (approx(0.06), False, "0.3", "0.20")


def test_every_chapter_modules_audits_give_a_reason_exactly_where_a_printed_value_does_not_follow():
    with_audits = [name for name in guide.CHAPTER_MODULES if hasattr(getattr(guide, name), "audits")]
    assert with_audits == ["ch03", "ch04", "ch06", "ch16", "ch17"]
    for name in with_audits:
        audits = getattr(guide, name).audits()
        assert audits and all(isinstance(a, guide.Audit) for a in audits), name
        for a in audits:
            assert a.values and len(a.table) > 0, (name, a.title)
            assert a.discrepancies == tuple(p for p in a.values if not p.follows)
            for p in a.values:
                # the flag is the one rule: |printed − computed| ≤ 0.6 of the printed unit (or inside the bounds)
                if p.bounds is None:
                    assert p.follows == (abs(p.printed - p.computed) <= 0.6 * p.unit + 1e-9 * max(1.0, abs(p.computed)))
                assert (p.reason == "") == p.follows, (name, a.title, p.where, p.quantity)
        frame = guide.discrepancy_frame(audits)
        assert len(frame) == sum(len(a.discrepancies) for a in audits), name
