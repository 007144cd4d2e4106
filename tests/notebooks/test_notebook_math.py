"""Every notebook's text is clean and its mathematics typesets.

Two defects a reader sees and no other test catches:

* a backslash eaten by a non-raw Python string in a build script turns ``\\varepsilon`` into a vertical tab
  plus "arepsilon", ``\\rho`` into a line break plus "ho", ``\\bar`` into a backspace — so no cell source may hold
  a control character other than a newline or a tab;
* a formula that MathJax cannot typeset shows as raw TeX. The notebooks' ``$…$`` and ``$$…$$`` are parsed with
  matplotlib's mathtext (``MathTextParser("path").parse``), which understands a subset of TeX. Where the book
  uses a MathJax command mathtext lacks, ``MATHJAX_TO_MATHTEXT`` below rewrites it to an equivalent mathtext
  construction first (documented per entry) — a formula is never skipped.
"""

import json
import re
from pathlib import Path

import pytest
from matplotlib.mathtext import MathTextParser

NOTEBOOKS = sorted((Path(__file__).resolve().parents[2] / "notebooks").rglob("*.ipynb"))
NOTEBOOKS = [p for p in NOTEBOOKS if ".ipynb_checkpoints" not in p.parts]

# $$…$$ first, then $…$ (not \$, not part of $$); inline code spans are removed before matching.
MATH = re.compile(r"(?<!\\)\$\$(.+?)\$\$|(?<![\\$])\$(?!\$)(.+?)(?<!\\)\$", re.S)
CODE_SPAN = re.compile(r"`[^`\n]*`")

# MathJax (TeX) → mathtext.  Each entry: (pattern, replacement, why).
MATHJAX_TO_MATHTEXT = [
    (r"\\le(?![a-zA-Z])", r"\\leq", "mathtext spells ≤ only \\leq"),
    (r"\\ge(?![a-zA-Z])", r"\\geq", "mathtext spells ≥ only \\geq"),
    (r"\\(?:big|Big|bigg|Bigg)[lr]?(?![a-zA-Z])", "", "manual delimiter sizes: mathtext has no \\big; size is cosmetic"),
    (r"\\tag\{([^}]*)\}", r"\\qquad(\1)", "an equation number: mathtext has no \\tag"),
    (r"\\boxed\{", "{", "a frame round a result: mathtext has no \\boxed (the content is checked)"),
    (r"\\bmod(?![a-zA-Z])", r"\\ \\mathrm{mod}\\ ", "binary mod: mathtext has no \\bmod"),
    (r"\\tfrac(?![a-zA-Z])", r"\\frac", "text-style fraction: mathtext has only \\frac"),
    (r"\\begin\{pmatrix\}(.*?)\\end\{pmatrix\}",
     lambda m: r"\left(" + m.group(1).replace("&", r"\ ").replace("\\\\", r";\ ") + r"\right)",
     "a matrix: mathtext has no environments; its entries are checked in one bracketed row"),
    # TeX takes a single token as an argument (\frac12, \sqrt2, \mathbf c); mathtext wants braces.
    (r"\\(frac|dfrac)\s*([0-9a-zA-Z])\s*([0-9a-zA-Z])", r"\\frac{\2}{\3}", "\\frac12: braces for one-token arguments"),
    (r"\\(sqrt|mathbf|mathsf|mathrm|mathit)\s*([0-9a-zA-Z])(?![a-zA-Z])", r"\\\1{\2}",
     "\\sqrt2, \\mathbf c: braces for a one-token argument"),
]


def to_mathtext(tex):
    """The formula as mathtext understands it (MATHJAX_TO_MATHTEXT applied in order; newlines → spaces)."""
    out = tex.replace("\n", " ")
    for pattern, repl, _why in MATHJAX_TO_MATHTEXT:
        out = re.sub(pattern, repl, out, flags=re.S)
    return out


def formulas(path):
    """(cell id, formula) for every $…$ / $$…$$ in the notebook's markdown cells."""
    nb = json.loads(path.read_text(encoding="utf-8"))
    for cell in nb["cells"]:
        if cell["cell_type"] != "markdown":
            continue
        text = CODE_SPAN.sub("", "".join(cell["source"]))
        for m in MATH.finditer(text):
            yield cell.get("id"), m.group(1) if m.group(1) is not None else m.group(2)


def test_notebooks_found():
    assert len(NOTEBOOKS) >= 18


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_no_control_characters(path):
    nb = json.loads(path.read_text(encoding="utf-8"))
    bad = []
    for cell in nb["cells"]:
        src = "".join(cell["source"])
        for i, ch in enumerate(src):
            if ord(ch) < 32 and ch not in "\n\t" or ch == "\x7f":
                bad.append((cell.get("id"), hex(ord(ch)), src[max(0, i - 20):i + 20]))
    assert not bad, f"control characters (a backslash eaten by a non-raw string?): {bad}"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_no_doubled_backslash_in_a_formula(path):
    """``\\alpha`` in a formula is a line break and the word "alpha" in MathJax: a backslash escaped twice (a raw
    string written like a plain one); the book's formulas never break lines inside $…$."""
    bad = [(cell_id, tex) for cell_id, tex in formulas(path) if re.search(r"\\\\[A-Za-z]", tex)]
    assert not bad, f"formulas with a doubled backslash before a command: {bad}"


@pytest.mark.parametrize("path", NOTEBOOKS, ids=lambda p: p.stem)
def test_math_typesets(path):
    parser = MathTextParser("path")
    failed = []
    for cell_id, tex in formulas(path):
        try:
            parser.parse("$" + to_mathtext(tex) + "$", dpi=72)
        except ValueError as exc:  # pyparsing's errors are ValueErrors
            failed.append((cell_id, tex, str(exc).splitlines()[-1]))
    assert not failed, f"formulas that do not typeset: {failed}"


def test_substitutions_keep_meaning():
    """The table rewrites notation only; a broken formula still fails after it."""
    parser = MathTextParser("path")
    assert to_mathtext(r"\sqrt2\,m_X \le \tfrac12") == r"\sqrt{2}\,m_X \leq \frac{1}{2}"
    assert to_mathtext(r"\boxed{m = 1} \tag{13.1}") == r"{m = 1} \qquad(13.1)"
    parser.parse("$" + to_mathtext(r"\begin{pmatrix}a & b\\ c & d\end{pmatrix}") + "$")
    for broken in ("m_\x0barepsilon", r"\frac{a}{", r"\varepsilonx"):
        with pytest.raises(ValueError):
            parser.parse("$" + to_mathtext(broken) + "$")


def test_eaten_backslash_is_caught(tmp_path):
    """A cell as the old chapter 12 had it (vertical tab for \\v) fails the control-character check."""
    nb = {"cells": [{"cell_type": "markdown", "id": "x", "source": ["$m_\x0barepsilon$"]}]}
    p = tmp_path / "bad.ipynb"
    p.write_text(json.dumps(nb), encoding="utf-8")
    with pytest.raises(AssertionError):
        test_no_control_characters(p)
