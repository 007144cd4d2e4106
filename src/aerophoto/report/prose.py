"""The writers' toolkit: how a section of the note says what the student did, in Russian (or English).

A :class:`Writer` writes one section into the :class:`~aerophoto.report.document.Document`: subsection
headings numbered "2.1", paragraphs in the note's language, formulas with the student's numbers substituted
and numbered "(2.1)", the guide's tables, figures, a "task not done" notice and the conclusion.  Every number
goes through the book's one formatter, :mod:`aerophoto.i18n.numfmt` (decimal comma in Russian, narrow
no-break space from five digits, a true minus); no Python name of an answer ever reaches the page.

The writers read a task as a :class:`TaskView`: its state, the student's own values (typed in the answer cell
or recorded by its check cell), what the student works from (``inputs``, plain data) and the verdict of the
visible checks.  A value the student has not given is None; a task not attempted is written as "not done"
with no number (:meth:`Writer.not_done`).
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

from ..i18n import numfmt
from .document import Document, formula

__all__ = ["TaskView", "Writer", "ru_plural", "plain", "symbol"]


@dataclass(frozen=True)
class TaskView:
    """One task as the writers see it.

    ``state``: passed, failed, partial, unreadable or not_started; ``values``: the student's readable answers
    (name → value); ``recorded``: names taken from the check cell's record; ``inputs``: what the student works
    from (plain data, see the chapter's writer); ``checks``: name → (ok, message) of the visible checks;
    ``spec``: the task's answers as plain dicts (name, unit, kind, options).
    """

    id: str
    title: str
    state: str
    values: dict = field(default_factory=dict)
    recorded: tuple = ()
    inputs: dict = field(default_factory=dict)
    checks: dict = field(default_factory=dict)
    message: str = ""
    spec: tuple = ()
    unreadable: dict = field(default_factory=dict)

    @property
    def attempted(self) -> bool:
        return self.state != "not_started"

    @property
    def passed(self) -> bool:
        return self.state == "passed"

    @property
    def label(self) -> str:
        p = self.id.split("-")
        return f"{p[1]}.{p[2]}" if len(p) >= 3 else self.id

    def get(self, name: str):
        """The student's value of ``name`` (None when not given or not readable)."""
        x = self.values.get(name)
        return None if x is Ellipsis else x

    def number(self, name: str) -> float | None:
        """The student's value as a finite float, or None."""
        x = self.get(name)
        if isinstance(x, bool) or not isinstance(x, (int, float)):
            return None
        return float(x) if math.isfinite(x) else None

    def numbers(self, name: str, n: int | None = None) -> list | None:
        """The student's list of numbers (of length ``n`` if given), or None."""
        x = self.get(name)
        if not isinstance(x, (list, tuple)) or (n is not None and len(x) != n):
            return None
        out = []
        for e in x:
            if isinstance(e, bool) or not isinstance(e, (int, float)) or not math.isfinite(e):
                return None
            out.append(float(e))
        return out

    def flag(self, name: str) -> bool | None:
        x = self.get(name)
        return x if isinstance(x, bool) else None


_UNIT_SUFFIX = re.compile(r"_(mm|km|m|s|h|deg|percent|pct|arcsec|um|cm)$")
_GREEK = {"alpha": "alpha", "phi": "phi", "tau": "tau", "sigma": "sigma", "gamma": "gamma", "rho": "rho",
          "lambda": "lambda", "kappa": "kappa", "beta": "beta"}


_SPECIAL = {"da": 'delta_alpha', "dh": "delta_h", "m_rms": "m", "dm": "Delta m", "rc": "r_c", "K_d": "K_d"}


def symbol(name: str) -> str | None:
    """A task's answer variable as a symbol to print (Typst math, never the Python name): ``TS_h`` → $T_"S"$,
    ``Px_percent`` → $P_"x"$, ``dgamma_arcsec`` → $Delta gamma$; the subscript always a quoted string.  None when
    the name makes no clean symbol (a subscript that is a word): the caller names the answer by its place instead."""
    base = _UNIT_SUFFIX.sub("", str(name))
    if base in _SPECIAL:
        return _SPECIAL[base]
    delta = ""
    if len(base) > 1 and base[0] == "d" and (base[1].isupper() or base[1:].split("_")[0] in _GREEK or
                                             base[1:2] in ("a", "h", "p", "k", "m")):
        delta, base = "Delta ", base[1:]
    head, _, tail = base.partition("_")
    for word, g in _GREEK.items():
        if head.startswith(word):
            head, tail = g, (head[len(word):] + tail)
            break
    else:
        head, tail = (head[:1], head[1:] + tail) if len(head) > 1 else (head, tail)
    if not re.fullmatch(r"[A-Za-z]+", head):
        head = '"' + re.sub(r"[^0-9A-Za-z]", "", head) + '"'
    tail = re.sub(r"[^0-9A-Za-z]", "", tail)
    if tail and not (len(tail) <= 2 and (tail.isalpha() or tail.isdigit()) or tail in ("max", "min")
                     or tail.isdigit()):
        return None  # a word (rms, corr, red…) or letters and digits: not a symbol of the guide
    return delta + head + (f'_"{tail}"' if tail else "")


def plain(text) -> str:
    """Text from the student (a chosen option, a name) made safe inside a paragraph: no ``$`` opens a formula."""
    return str(text).replace("$", "\uff04")


def _segments(text: str) -> list:
    """``"a $x_c$ b"`` → text and math segments."""
    parts = text.split("$")
    if len(parts) % 2 == 0:  # an unmatched $: all text
        return [{"text": text}]
    return [{"math": p} if k % 2 else {"text": p} for k, p in enumerate(parts) if p]


def ru_plural(n: int, one: str, few: str, many: str) -> str:
    """The Russian noun form after the count ``n`` (1 снимок, 2 снимка, 5 снимков)."""
    n = abs(int(n))
    if n % 10 == 1 and n % 100 != 11:
        return one
    if 2 <= n % 10 <= 4 and not 12 <= n % 100 <= 14:
        return few
    return many


class Writer:
    """Writes one section (``number`` "2") of the note; ``lang`` is "ru" or "en"."""

    def __init__(self, doc: Document, lang: str, variant, number: str, *, figures=None):
        self.doc, self.lang, self.v, self.number = doc, lang, variant, str(number)
        self.figures = figures          # callable (name) -> [(src, caption_default, width)] or []
        self._sub = 0
        self._eq = 0
        self.drawn: list = []

    # ---- language and numbers
    def L(self, ru: str, en: str) -> str:
        return ru if self.lang == "ru" else en

    def n(self, x, decimals: int | None = None, *, sig: int | None = None, plus: bool = False) -> str:
        """A number in the book's format (:func:`aerophoto.i18n.numfmt.fmt_number`)."""
        return numfmt.fmt_number(x, decimals, sig=sig, lang=self.lang, plus=plus)

    def count(self, x) -> str:
        return numfmt.fmt_count(int(round(float(x))), lang=self.lang)

    def scale(self, m) -> str:
        return numfmt.fmt_scale(m, lang=self.lang)

    def pct(self, x, decimals: int = 1) -> str:
        return numfmt.fmt_percent(x, decimals, lang=self.lang)

    def q(self, x, unit: str, decimals: int | None = None, *, sig: int | None = None) -> str:
        """A value with its unit ("11 859 м")."""
        number = self.n(x, decimals, sig=sig)
        u = self.unit(unit)
        if not u:
            return number
        return number + (u if u in ("°", "′", "″") else numfmt.NBSP + u)

    def unit(self, unit: str) -> str:
        if self.lang == "en":
            return unit
        return {"m": "м", "mm": "мм", "km": "км", "km2": "км²", "s": "с", "h": "ч", "km/h": "км/ч", "cm": "см",
                "µm": "мкм", "%": "%", "°": "°", "″": "″", "′": "′", "m/s": "м/с", "mGal": "мГал"}.get(unit, unit)

    def yes(self, ok: bool) -> str:
        return self.L("да", "yes") if ok else self.L("нет", "no")

    # ---- structure
    def sub(self, ru: str, en: str) -> str:
        """A numbered subsection "2.3 …" (level 2)."""
        self._sub += 1
        num = f"{self.number}.{self._sub}"
        self.doc.heading(2, self.L(ru, en), num=num)
        return num

    def step(self, t: TaskView | None, ru: str, en: str) -> bool:
        """A subsection for task ``t``; True when the student did it (else its "not done" notice is written)."""
        self.sub(ru, en)
        if t is None or not t.attempted or t.state == "unreadable":
            self.not_done(t)
            return False
        return True

    def par(self, ru, en=None, style: str = "normal") -> None:
        """A paragraph in the note's language: ``ru``/``en`` strings, or lists of segments (see Document.par).

        In a string, ``$…$`` is inline mathematics (the writer's own symbols: ``$x_c$``); text that comes from the
        student goes through :func:`plain` first, so it can never open a formula.
        """
        text = ru if (self.lang == "ru" or en is None) else en
        self.doc.par(_segments(text) if isinstance(text, str) else text, style)

    def where(self, pairs) -> None:
        """"где f — …; m — …" under a formula: ``pairs`` of (Typst math symbol, ru, en)."""
        segs = [{"text": self.L("где ", "where ")}]
        for k, (sym, ru, en) in enumerate(pairs):
            if k:
                segs.append({"text": "; "})
            segs += [{"math": sym}, {"text": " — " + self.L(ru, en)}]
        segs.append({"text": "."})
        self.doc.par(segs, "plain")

    def eq(self, template: str, *, numbered: bool = True, **numbers) -> str:
        """A displayed formula with the student's numbers (``{name}`` → formatted strings); returns its number."""
        num = ""
        if numbered:
            self._eq += 1
            num = f"{self.number}.{self._eq}"
        self.doc.math(formula(template, **numbers), num=num)
        return num

    def table(self, caption_ru: str, caption_en: str, header, rows, **kw) -> str:
        return self.doc.table(self.L(caption_ru, caption_en), header, rows, **kw)

    def figure(self, name: str, caption_ru: str, caption_en: str, width: float | None = None, *,
               own: dict | None = None) -> list:
        """The section's figure ``name`` (drawn by :mod:`aerophoto.report.figures` for the student's variant);
        ``own``: the student's values it draws over its base (plain data)."""
        if self.figures is None:
            return []
        nums = []
        for src, w in self.figures(name, own or {}):
            nums.append(self.doc.figure(src, self.L(caption_ru, caption_en), width if width is not None else w))
            self.drawn.append(name)
        return nums

    # ---- states
    def not_done(self, t: TaskView | None) -> None:
        """The notice of a task the student has not done: no number, never a reference value (None: nothing)."""
        if t is None:
            return
        if t.state == "unreadable":
            names = len(t.unreadable)
            self.par(f"Задача {t.label} не может быть прочитана без запуска тетради: ответ вычислен кодом пакета "
                     f"({names} {ru_plural(names, 'величина', 'величины', 'величин')}), а проверочная ячейка не "
                     "сохранила вывод. Впишите значения числами или выполните проверочную ячейку и сохраните "
                     "тетрадь.",
                     f"Task {t.label} cannot be read without running the notebook: its answer is computed with "
                     "package code and its check cell kept no output. Type the values as numbers, or run the check "
                     "cell and save the notebook.", "missing")
            return
        self.par(f"Задача {t.label} не выполнена.", f"Task {t.label} is not done.", "missing")

    def check_note(self, t: TaskView) -> None:
        """For a task whose visible check fails: what the check says (never the expected value)."""
        if t.state in ("passed", "unreadable") or not t.attempted:
            return
        if t.state == "partial":
            self.par(f"Задача {t.label} выполнена не полностью: не все величины указаны в рабочей тетради.",
                     f"Task {t.label} is only partly answered.", "bad")
            return
        bad = [(n, m) for n, (ok, m) in t.checks.items() if not ok]
        segs = [{"text": self.L(f"Проверка рабочей тетради не подтверждает результат задачи {t.label}",
                                f"The workbook's check does not confirm task {t.label}")}]
        order = [a["name"] for a in t.spec]
        for k, (name, msg) in enumerate(bad[:3]):
            sym = symbol(name)
            what = {"math": sym} if sym else {"text": self.L(f"ответ {order.index(name) + 1 if name in order else k + 1}",
                                                              f"answer {order.index(name) + 1 if name in order else k + 1}")}
            segs += [{"text": ": " if k == 0 else "; "}, what]
            if msg.strip():
                segs.append({"text": " — " + plain(msg.strip().rstrip("."))})
        segs.append({"text": "."})
        self.par(segs, None, "bad")

    def recorded_note(self, t: TaskView) -> None:
        if t.recorded:
            self.par("Значения, вычисленные в тетради кодом пакета, взяты из сохранённого вывода проверочной ячейки.",
                     "Values computed in the notebook with package code are taken from the check cell's saved output.",
                     "note")

    def conclude(self, parts: list) -> None:
        """The conclusion from its clauses (Russian; the English note has them as they are): "A; b; c."."""
        if parts:
            text = "; ".join(parts) + "."
            self.conclusion(text[0].upper() + text[1:], text)

    def conclusion(self, ru: str, en: str) -> None:
        """The section's conclusion paragraph ("Вывод. …")."""
        self.doc.par([{"text": self.L("Вывод. ", "Conclusion. "), "b": True}] + _segments(self.L(ru, en)))
