"""Every number a notebook prints, cell by cell — to show that a refactoring changed none of them.

    python tests/tools/notebook_numbers.py collect OUT.json [notebooks/*.ipynb]
    python tests/tools/notebook_numbers.py compare BEFORE.json AFTER.json

``collect`` executes each notebook headless (variant 00, a private AEROPHOTO_HOME) and records, per cell id,
the numbers in its text, HTML and stream outputs, and per notebook the numbers in the live demos' HTML widgets
(tables, status lines).  ``compare`` lists the cells whose numbers differ.  Run ``collect`` once on the old
tree (PYTHONPATH=<old>/src) and once on the new.
"""

from __future__ import annotations

import json
import os
import re
import sys
import tempfile
from pathlib import Path

NUM = re.compile(r"[-−+]?\d+(?:[.,]\d+)?(?:e[-+]?\d+)?")
TAG = re.compile(r"<[^>]+>")
NOISE = re.compile(r"(model_id|[0-9a-f]{32}|[0-9a-f-]{36}|\d{4}-\d\d-\d\d|aerophoto \d+\.\d+\.\d+)")


def numbers(text: str) -> list[str]:
    text = NOISE.sub(" ", TAG.sub(" ", text))
    return [n.replace("−", "-") for n in NUM.findall(text)]


def collect(paths, out):
    import nbformat
    from nbclient import NotebookClient

    result = {}
    for p in paths:
        p = Path(p)
        nb = nbformat.read(str(p), as_version=4)
        home = tempfile.mkdtemp(prefix="nbnum-")
        os.environ["AEROPHOTO_HOME"] = home
        os.environ.pop("AEROPHOTO_RECORD_BOOK", None)
        NotebookClient(nb, timeout=900, kernel_name="python3", allow_errors=True,
                       resources={"metadata": {"path": str(p.parent)}}).execute()
        cells = {}
        for c in nb.cells:
            if c.cell_type != "code":
                continue
            nums = []
            for o in c.get("outputs", []):
                if o.get("output_type") == "stream":
                    nums += numbers(o.get("text", ""))
                elif o.get("output_type") == "error":
                    nums += ["ERROR:" + o.get("ename", "")]
                else:
                    data = o.get("data", {})
                    for mime in ("text/html", "text/plain", "text/markdown"):
                        if mime in data:
                            nums += numbers(data[mime] if isinstance(data[mime], str) else "".join(data[mime]))
                            break
            cells[c.get("id")] = nums
        widgets = []
        state = nb.metadata.get("widgets", {}).get("application/vnd.jupyter.widget-state+json", {}).get("state", {})
        for m in state.values():
            st = m.get("state", {})
            if m.get("model_name") in ("HTMLModel", "LabelModel", "HTMLMathModel") and isinstance(st.get("value"), str):
                widgets += numbers(st["value"])
        cells["(widgets)"] = sorted(widgets)
        result[p.name] = cells
        print(p.name, sum(len(v) for v in cells.values()), "numbers", flush=True)
    Path(out).write_text(json.dumps(result, ensure_ascii=False, indent=0), encoding="utf-8")


def compare(before, after) -> int:
    a = json.loads(Path(before).read_text(encoding="utf-8"))
    b = json.loads(Path(after).read_text(encoding="utf-8"))
    bad = 0
    for nb in sorted(set(a) | set(b)):
        ca, cb = a.get(nb, {}), b.get(nb, {})
        for cid in sorted(set(ca) | set(cb), key=str):
            if ca.get(cid) != cb.get(cid):
                bad += 1
                print(f"{nb} [{cid}]:\n  before {ca.get(cid)}\n  after  {cb.get(cid)}")
    total = sum(len(v) for c in a.values() for v in c.values())
    print(f"{bad} cell(s) differ; {total} numbers compared")
    return 1 if bad else 0


if __name__ == "__main__":
    if sys.argv[1] == "collect":
        collect(sys.argv[3:] or sorted(Path("notebooks").glob("[0-9]*.ipynb")), sys.argv[2])
    else:
        sys.exit(compare(sys.argv[2], sys.argv[3]))
