"""``aerophoto-course autograde --jobs N``: a class graded in parallel gets the same grades as one at a time.

A class's grading is what a hub's instructor waits for; ``--jobs`` runs that many submissions at once, each
job in a worker process with a sandbox uid of its own (run as root: nobody for the first job, 65533, 65532 …
for the others — RLIMIT_NPROC counts per uid, so one student's fork bomb cannot starve another's kernel).
"""

from __future__ import annotations

import copy
import json
import os

import nbformat
import pytest

from aerophoto import course, nbtools
from aerophoto.course.bwrap import MAX_JOBS, NOBODY, sandbox_uid
from aerophoto.course.limits import Limits
from aerophoto.course.sandbox import Box
from aerophoto.course.versions import strip_solutions
from conftest import NOTEBOOKS

A = "00_start_here"
SOLUTION = ("import math\nH_m = v.f_mm / 1000 * v.m\non_mm = v.f_mm * math.tan(math.radians(v.alpha_deg))\n"
            "oc_mm = -v.f_mm * math.tan(math.radians(v.alpha_deg) / 2)\n")
UID = "import os\nprint('uid', os.getuid())\n"
CLASS = {  # student id → (answer cell, expected score); each prints the uid its kernel runs as
    "19-0601": (UID + "me = 1\n" + SOLUTION, 3.0),
    "19-0602": (UID + "me = 2\n" + SOLUTION + "H_m = H_m / 1000   # km: a units slip\n", 0.0),
    "19-0603": (UID + "me = 3\n" + SOLUTION, 3.0),
    "19-0604": (UID + "me = 4\n" + SOLUTION, 3.0),
}


def test_sandbox_uid_per_job():
    assert sandbox_uid(0) == NOBODY == 65534
    assert [sandbox_uid(k) for k in range(1, MAX_JOBS)] == list(range(65533, 65533 - MAX_JOBS + 1, -1))
    assert min(sandbox_uid(k) for k in range(MAX_JOBS)) == 65521  # in Debian's never-allocated 65000–65533
    for bad in (-1, MAX_JOBS, 1.0, True, "1"):
        with pytest.raises(ValueError, match="slot"):
            sandbox_uid(bad)
    box = Box.create(None, Limits())
    try:
        cmd = box.wrap(["python"], env={}, uid=sandbox_uid(3))
    finally:
        box.remove()
    if os.geteuid() == 0:
        assert "--reuid=65531" in cmd and "--regid=65531" in cmd
    else:  # an ordinary user: a user namespace of its own per sandbox, the uid does not change
        assert not any(a.startswith("--reuid") for a in cmd)


@pytest.mark.slow
def test_jobs_grade_like_one_at_a_time(tmp_path):
    book = tmp_path / "notebooks"
    book.mkdir()
    nbtools.write(strip_solutions(nbtools.read(NOTEBOOKS / f"{A}.ipynb"))[0], book / f"{A}.ipynb")
    c = course.Course(tmp_path / "course", book, out=lambda s: None)
    assert c.generate() == {A: True}
    release = nbformat.read(str(c.path("release", A)), as_version=4)
    export = tmp_path / "export"
    export.mkdir()
    for sid, (answer, _) in CLASS.items():
        nb = copy.deepcopy(release)
        setup = nbtools.find_cell(nb, "setup")[1]
        setup.source = setup.source.replace("RECORD_BOOK = None", f'RECORD_BOOK = "{sid}"')
        nbtools.find_cell(nb, "task-00-1-answer")[1].source = answer
        nbformat.write(nb, str(export / f"{sid}_{A}.ipynb"))
    c.import_submissions(export)

    def graded():
        csv_text = c.gradebook().to_csv(index=False)
        reports = {}
        for sid in CLASS:
            rep = json.loads(c.report_path(A, sid).read_text(encoding="utf-8"))
            reports[sid] = [(v["task"], v["score"], v["passed"], v["message"], v["flags"]) for v in rep["verdicts"]]
        return csv_text, reports

    serial = c.autograde()
    csv1, reports1 = graded()
    log: list[str] = []
    c.out = log.append
    parallel = c.autograde(force=True, jobs=2)
    csv2, reports2 = graded()

    assert [(r.student, r.status, r.score) for r in serial] == [(sid, "graded", exp) for sid, (_, exp) in CLASS.items()]
    assert [(r.student, r.status, r.score, sorted(f.code for f in r.flags)) for r in parallel] == [
        (r.student, r.status, r.score, sorted(f.code for f in r.flags)) for r in serial]
    assert csv2 == csv1 and reports2 == reports1
    assert "autograde: 4 submission(s) in 2 parallel jobs" in log
    assert sum(line.startswith("[") and "/4] " in line for line in log) == 4
    # each job ran its kernels as a uid of its own (both jobs graded at least one: each takes one at its start)
    uids = set()
    for sid in CLASS:
        nb = nbformat.read(str(c.path("autograded", A, sid)), as_version=4)
        out = "".join(o.get("text", "") for o in nbtools.find_cell(nb, "task-00-1-answer")[1].outputs)
        uids.add(int(out.split("uid", 1)[1].split()[0]))
    if os.geteuid() == 0:
        assert uids == {NOBODY, NOBODY - 1}
    else:
        assert uids == {os.getuid()}
    with pytest.raises(ValueError, match="jobs"):
        c.autograde(jobs=MAX_JOBS + 1)
