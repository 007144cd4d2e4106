"""What a course hands back: the gradebook as a table (CSV) and nbgrader's HTML feedback per student."""

from __future__ import annotations

from pathlib import Path

from .common import COURSE_ID, Flag, last_error


def gradebook(course, by: str = "submission"):
    """The grades as a pandas DataFrame (the trusted scores nbgrader's gradebook holds, and the flags).

    ``by="submission"``: a row per student × chapter (chapters that anyone submitted), columns
    ``student_id, record_book, assignment``, one per task (its grade_id), ``score, max_score, flags``.
    ``by="student"``: a row per student, the task columns of every chapter, a ``total:<chapter>`` column per
    chapter, ``score, max_score, flags``.  Missing or unreadable submissions score 0 and carry a flag.
    """
    import pandas as pd
    from nbgrader.api import Gradebook, MissingEntry

    if by not in ("submission", "student"):
        raise ValueError(f"by = {by!r} is not valid; expected 'submission' or 'student'")
    collected = sorted({a for _, a in course.submissions()})
    active = [a for a in collected if course._release_tasks(a)]
    rows = []
    have_db = (course.root / "gradebook.db").exists()
    gb = Gradebook(course.db_url, COURSE_ID) if have_db else None
    try:
        for sid in course.students():
            for a in active:
                tasks = course._release_tasks(a)
                row = {"student_id": sid, "record_book": course.record_book(sid) or "", "assignment": a}
                for t in tasks:
                    row[t.check_id] = 0.0
                flags = course.flags(sid, a)
                bad = {"missing", "corrupt", "not_graded"} & {f.code for f in flags}
                if gb is not None and not bad:
                    try:
                        sub = gb.find_submission(a, sid)
                        for nb in sub.notebooks:
                            for g in nb.grades:
                                if g.name in row:
                                    row[g.name] = float(g.score or 0.0)
                    except MissingEntry:
                        flags.append(Flag("not_graded", "not in nbgrader's gradebook"))
                row["score"] = sum(row[t.check_id] for t in tasks)
                row["max_score"] = sum(t.points for t in tasks)
                row["flags"] = " | ".join(str(f) for f in flags)
                rows.append(row)
    finally:
        if gb is not None:
            gb.close()
    df = pd.DataFrame(rows)
    if df.empty:
        return pd.DataFrame(columns=["student_id", "record_book", "assignment", "score", "max_score", "flags"])
    if by == "submission":
        task_cols = [c for c in df.columns if c not in ("student_id", "record_book", "assignment", "score",
                                                        "max_score", "flags")]
        return df[["student_id", "record_book", "assignment", *task_cols, "score", "max_score", "flags"]]
    out = []
    for sid, g in df.groupby("student_id", sort=True):
        row = {"student_id": sid, "record_book": g["record_book"].iloc[0]}
        for _, r in g.iterrows():
            for c in g.columns:
                if c.startswith("task-") and not pd.isna(r[c]):
                    row[c] = r[c]
            row[f"total:{r['assignment']}"] = r["score"]
        row["score"] = float(g["score"].sum())
        row["max_score"] = float(g["max_score"].sum())
        row["flags"] = " | ".join(f"{r['assignment']}: {r['flags']}" for _, r in g.iterrows() if r["flags"])
        out.append(row)
    return pd.DataFrame(out)


def feedback(course, students=None, assignments=None) -> list[Path]:
    """nbgrader generate_feedback: ``feedback/<student>/<chapter>/<chapter>.html`` per graded chapter.

    No student code runs here (nbgrader renders the autograded notebook with the gradebook's — trusted —
    scores); the HTML is sanitised, so a student's output cannot carry a script to whoever opens it.
    """
    from nbgrader.converters import GenerateFeedback

    with course.lock("feedback"):
        pairs = [(s, a) for s, a in course.submissions(students, assignments)
                 if course.path("autograded", a, s).exists()]
        made = []
        for k, (sid, a) in enumerate(pairs, 1):
            res = course._run(GenerateFeedback, assignment_id=a, student_id=sid, force=True)
            html = course.root / "feedback" / sid / a / f"{a}.html"
            if res.get("success") and html.exists():
                made.append(html)
                course.out(f"[{k}/{len(pairs)}] {sid} · {a}: {html.relative_to(course.root)}")
            else:
                course.out(f"[{k}/{len(pairs)}] {sid} · {a}: FAILED — {last_error(res)}")
        course.out(f"feedback: {len(made)} HTML file(s) in {course.root / 'feedback'}")
        return made
