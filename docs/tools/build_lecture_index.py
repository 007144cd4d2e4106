"""The lecture index's own text (notebooks/lectures.ipynb), around its generated table (safe to re-run).

    python docs/tools/build_lecture_index.py && python -m aerophoto.book

The table of demos (cell ``demos``) and the lecture pages ``notebooks/lectures/NN_slug.ipynb`` are generated
from :data:`aerophoto.book.CHAPTERS` by ``python -m aerophoto.book``; this script writes the other cells.
"""

from __future__ import annotations

from pathlib import Path

from aerophoto import nbtools

ROOT = Path(__file__).resolve().parents[2]
PATH = ROOT / "notebooks" / "lectures.ipynb"

CELLS = {
    "title": """
# Lecture mode: the live demonstrations

This page lists every live demonstration of the book, for showing in class. Each chapter has a **lecture
page**: its demos only — no theory, no tasks, no code, no check output — each laid out for one 1280×800
projector screen, its sliders on top and its table beside the figure. Every demo opens on **the guide's
worked example (variant 00)**, whatever record-book number is remembered on the machine, and **Reset**
returns there.
""",
    "setup": """
import aerophoto
v = aerophoto.setup(lecture=True)   # the guide's example, variant 00: no student's number is read or shown
""",
    "voila": """
## Show the demos without code (Voilà)

From the repository's top folder run

```bash
voila notebooks/
```

and open <http://localhost:8866/voila/render/lectures.ipynb> (this page): each link in the first column
opens that chapter's lecture page as an app. One page alone:
`voila notebooks/lectures/03_relief_displacement.ipynb`. The settings live in `voila.json` in the top folder
(kernels of closed tabs are shut down after 10 idle minutes; Jupyter extensions that do not belong in an app
are not loaded). Stop the server with Ctrl+C.

The pages are generated from the chapters (their setup and demo cells) by `python -m aerophoto.book`; a test
keeps them current. The whole chapter, with theory, worked example and tasks, is linked beside each page.
""",
}


def main() -> None:
    nb = nbtools.read(PATH)
    for cell_id, text in CELLS.items():
        nbtools.set_cell(nb, cell_id, text)
    nbtools.write(nb, PATH)
    print(f"wrote {PATH.relative_to(ROOT)}")


if __name__ == "__main__":
    main()
