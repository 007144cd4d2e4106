"""Write notebooks/_template.ipynb, the notebook every new chapter starts from (safe to re-run).

    python docs/tools/make_template.py

The template is not part of the book (names starting with "_" are skipped by the workbook, the grader, the
lecture index and the notebook tests); tests/test_template.py checks that it keeps the chapter shape of
docs/CONTRIBUTING.md ("Adding a chapter").
"""

from pathlib import Path

from aerophoto.nbtools import code, md, nbgrader_answer, nbgrader_tests, notebook, write

ROOT = Path(__file__).resolve().parents[2]

CELLS = [
    md("""
# NN · Title of the chapter (guide §S)

One paragraph: what the student will be able to do after this chapter, in plain words, with the key term and its
Russian name beside it — e.g. the **mean object plane** (средняя предметная плоскость).

**In this chapter you will**

1. …
2. move the sliders of the live demo and watch …;
3. recompute the guide's table T with the package, with a note beside every printed number that does not follow;
4. do the guide's work on your own variant and check it.
""", id="title"),
    code("""
RECORD_BOOK = None  # ← type your record-book number in quotes, e.g. "19-0457"
import aerophoto
from aerophoto import plots          # and the chapter's modules, e.g. from aerophoto import guide, tasks
v = aerophoto.setup(RECORD_BOOK)
""", id="setup"),
    md("""
## Theory

Our own explanation (never the guide's sentences), the formulas with the guide's numbers, e.g.
$\\delta_h = r\\,h/H$ (guide §4, formula 4.1), and where the code lives: `aerophoto.<module>.<function>??`.
""", id="theory"),
    code("""
# a static figure: built by a function of the package (ax=None), shown once with a text alternative
# plots.static(aerophoto.demos.<topic>.<figure>(), alt="what the figure shows")
""", id="figure-theory"),
    md("""
## The live demo

What each slider does and what to watch. The demo opens on the guide's worked example (variant 00), never on
the student's graded values.
""", id="demo-theory"),
    code("""
# demo = aerophoto.demos.<topic>.<Name>Demo()     # a LiveDemo; register it in aerophoto.book.CHAPTERS
# demo
""", id="demo-name"),
    md("""
## The guide's worked example, recomputed

Every printed table is an `aerophoto.guide.sNN` audit: the table recomputed from its own printed inputs and
every printed value beside the value that follows (one rule: within 0.6 of a unit of the last printed digit).
""", id="example-theory"),
    code("""
# aerophoto.guide.<sNN>.table(T)        # an Audit: shows the recomputed table and the discrepancies
""", id="example-1"),
    md("""
## Task NN.1 — … (graded)

What to compute, the variables and their units, the sign convention, the tolerance when it is not the default.
""", id="task-NN-1"),
    code("""
# tasks.inputs("task-NN-1", v)          # the student's own data (their photo, their table)
""", id="task-NN-1-data"),
    nbgrader_answer(code("""
x_m = ...   # what it is, unit
""", id="task-NN-1-answer"), "task-NN-1-answer"),
    nbgrader_tests(code("""
from aerophoto import checks
checks.check_task("task-NN-1", v, x_m=x_m)
""", id="task-NN-1-check"), "task-NN-1-check", 1),
    md("""
## Summary

Three to five bullets: what was learnt, what the guide got wrong and what is right. Next: **NN+1 · …**.
""", id="summary"),
]

if __name__ == "__main__":
    out = write(notebook(CELLS), ROOT / "notebooks" / "_template.ipynb")
    print("wrote", out)
