"""The course folder and the grading workflow over nbgrader: generate, import, autograde, gradebook, feedback.

nbgrader is the engine for the workflow and the gradebook; what is added around it:

* the student book is the repository's ``notebooks/``; ``generate`` writes nbgrader's source from it with
  reference solutions computed by the package (:func:`~.versions.source_version`);
* every submission runs in the sandbox (:mod:`.sandbox`, :class:`~.sandbox_execute.SandboxExecute`), and the score
  written into nbgrader's gradebook is the trusted one (:mod:`.trusted`);
* a lock on the course folder (:func:`course_lock`): a second grading run waits (or refuses) instead of
  corrupting the first; ``import`` writes each file atomically;
* flags (:mod:`.flags`, :mod:`.trusted`, the sandbox's events) in the gradebook CSV.
"""

from __future__ import annotations

import contextlib
import fcntl
import hashlib
import json
import logging
import os
import shutil
import time
from dataclasses import dataclass, field
from pathlib import Path

from .common import (COURSE_ID, Flag, GradedTask, chapters, course_config, default_course_dir,
                     default_notebooks_dir, digits, ensure_path, graded_tasks, last_error, nb_bytes,
                     nbformat_major, need_nbgrader, notebook_problem, read_nb, read_roster, stderr_to,
                     template_path, write_atomic)
from .bwrap import MAX_JOBS, NOBODY, sandbox_uid
from .limits import Limits


class CourseBusy(RuntimeError):
    """Another aerophoto-course run holds the course folder."""


@contextlib.contextmanager
def course_lock(root: Path, what: str, *, wait_s: float = 3600.0, out=print):
    """Hold the course folder's lock (``.aerophoto-course.lock``, an advisory flock) while ``what`` runs.

    A second run waits up to ``wait_s`` seconds (saying so once), then raises :class:`CourseBusy`;
    ``wait_s = 0`` refuses at once.
    """
    path = Path(root) / ".aerophoto-course.lock"
    try:
        fh = open(path, "a+", encoding="utf-8")
    except OSError as exc:
        raise CourseBusy(f"cannot lock the course folder {root}: {exc}") from None
    try:
        try:
            fcntl.flock(fh, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            fh.seek(0)
            holder = fh.read().strip() or "another run"
            if wait_s <= 0:
                raise CourseBusy(f"the course folder {root} is in use ({holder}); try again when it has finished")
            out(f"waiting: the course folder is in use ({holder}) …")
            deadline = time.monotonic() + wait_s
            while True:
                time.sleep(0.2)
                try:
                    fcntl.flock(fh, fcntl.LOCK_EX | fcntl.LOCK_NB)
                    break
                except BlockingIOError:
                    if time.monotonic() > deadline:
                        raise CourseBusy(f"the course folder {root} was still in use after {wait_s:g} s "
                                         f"({holder})") from None
        fh.seek(0)
        fh.truncate()
        fh.write(f"aerophoto-course {what}, pid {os.getpid()}, since {time.strftime('%H:%M:%S')}\n")
        fh.flush()
        yield
    finally:
        with contextlib.suppress(OSError):
            fcntl.flock(fh, fcntl.LOCK_UN)
        fh.close()


@dataclass
class GradeResult:
    student: str
    assignment: str
    status: str            # graded, up-to-date, corrupt, missing, failed
    score: float = 0.0
    max_score: float = 0.0
    seconds: float = 0.0
    flags: list = field(default_factory=list)
    error: str = ""


def _course_logger(root: Path) -> logging.Logger:
    """nbgrader's logger for this course: not shown in the terminal (see :meth:`Course._run`)."""
    log = logging.getLogger(f"aerophoto.course.nbgrader.{hashlib.sha1(str(root).encode()).hexdigest()[:8]}")
    log.propagate = False
    log.setLevel(logging.INFO)
    return log


class Course:
    """An nbgrader course folder for the book: ``source/``, ``release/``, ``submitted/``, ...

    Parameters
    ----------
    root : path
        The course folder (created with its nbgrader_config.py on first use).
    notebooks_dir : path, optional
        The student book's notebooks (default: :func:`default_notebooks_dir`).
    roster : path, optional
        CSV with columns ``student_id,record_book`` (default ``<root>/roster.csv`` if present).
    timeout : int, optional
        Per-cell execution limit in seconds (default: the config file's, 120 s).
    limits : Limits, optional
        The sandbox's resource limits (default :class:`~.sandbox.Limits`).
    unsafe_no_sandbox : bool
        Run submissions without the sandbox — for a developer's own notebooks only; never the default.
    wait_s : float
        How long a command waits for another run holding the course folder (0: refuse at once).
    out : callable
        Where progress lines go (``print``).
    """

    def __init__(self, root=None, notebooks_dir=None, *, roster=None, timeout=None, limits: Limits | None = None,
                 unsafe_no_sandbox: bool = False, wait_s: float = 3600.0, out=print):
        need_nbgrader()
        ensure_path()
        self.root = Path(root or default_course_dir()).resolve()
        self.notebooks_dir = Path(notebooks_dir) if notebooks_dir else default_notebooks_dir()
        self.timeout = timeout
        self._limits = limits
        self.unsafe_no_sandbox = bool(unsafe_no_sandbox)
        self.wait_s = wait_s
        self.out = out
        self.root.mkdir(parents=True, exist_ok=True)
        cfg_file = self.root / "nbgrader_config.py"
        if not cfg_file.exists():
            shutil.copyfile(template_path(), cfg_file)
        if roster is not None and not Path(roster).is_file():
            raise SystemExit(f"--roster {roster}: no such file (a CSV with columns student_id,record_book)")
        roster = Path(roster) if roster else self.root / "roster.csv"
        self.roster = read_roster(roster) if roster.exists() else {}
        self._roster_path = roster if roster.exists() else None
        self.sandbox_uid = NOBODY  # run as root: the uid the kernels drop to (one per parallel grading job)
        self._log = _course_logger(self.root)
        self._same_code: dict = {}

    # paths -------------------------------------------------------------------------------------
    def path(self, step: str, assignment: str, student: str | None = None) -> Path:
        base = self.root / step
        return (base / student / assignment if student else base / assignment) / f"{assignment}.ipynb"

    def report_path(self, assignment: str, student: str) -> Path:
        """The trusted grading's report of one submission (course-private: never released)."""
        return self.root / "trusted" / student / f"{assignment}.json"

    @property
    def db_url(self) -> str:
        # parallel grading jobs (autograde --jobs) write into one sqlite file: wait for its lock (up to 60 s)
        # instead of sqlite's default 5 s
        return f"sqlite:///{self.root / 'gradebook.db'}?timeout=60"

    @property
    def limits(self) -> Limits:
        """The sandbox's limits: the ones given, else the course config's ``c.SandboxExecute.limits``, else the defaults."""
        if self._limits is not None:
            return self._limits
        cfg = course_config(self.root)
        lim = cfg.SandboxExecute.get("limits") if "SandboxExecute" in cfg else None
        return Limits.of(lim)

    def lock(self, what: str):
        return course_lock(self.root, what, wait_s=self.wait_s, out=self.out)

    def config(self, record_book: str | None = None):
        from nbconvert.preprocessors import ClearMetadataPreprocessor
        from nbgrader.preprocessors import (AssignLatePenalties, CheckCellMetadata, IgnorePattern, LimitOutput,
                                            SaveAutoGrades)

        from .sandbox_execute import SandboxExecute

        cfg = course_config(self.root, self.timeout)
        cfg.Autograde.autograde_preprocessors = [SandboxExecute, IgnorePattern,
                                                 ClearMetadataPreprocessor, LimitOutput, SaveAutoGrades,
                                                 AssignLatePenalties, CheckCellMetadata]
        if self._limits is not None or "limits" not in cfg.SandboxExecute:
            cfg.SandboxExecute.limits = self.limits.as_dict()
        cfg.SandboxExecute.record_book = record_book
        cfg.SandboxExecute.unsafe_no_sandbox = self.unsafe_no_sandbox
        cfg.SandboxExecute.uid = int(self.sandbox_uid)
        cfg.CourseDirectory.db_url = self.db_url
        cfg.HTMLExporter.sanitize_html = True  # feedback shows a student's outputs: no script from them
        return cfg

    def coursedir(self, **attrs):
        from nbgrader.coursedir import CourseDirectory

        cd = CourseDirectory(config=self.config())
        for k, val in attrs.items():
            setattr(cd, k, val)
        return cd

    def assignments(self) -> list[str]:
        """The chapters, one assignment each (from notebooks/, else from source/)."""
        names = [p.stem for p in chapters(self.notebooks_dir)] if self.notebooks_dir.is_dir() else []
        if not names and (self.root / "source").is_dir():
            names = sorted(d.name for d in (self.root / "source").iterdir() if (d / f"{d.name}.ipynb").exists())
        return names

    def record_book(self, student: str) -> str | None:
        """The student's record-book number: the roster's, else the student id if it has ≥ 2 digits."""
        if student in self.roster:
            return self.roster[student]
        return student if len(digits(student)) >= 2 else None

    def students(self) -> list[str]:
        """Everyone known: the roster, the submitted folders and the gradebook."""
        ids = set(self.roster)
        sub = self.root / "submitted"
        if sub.is_dir():
            ids |= {d.name for d in sub.iterdir() if d.is_dir() and not d.name.startswith(".")}
        if (self.root / "gradebook.db").exists():
            from nbgrader.api import Gradebook

            with Gradebook(self.db_url, COURSE_ID) as gb:
                ids |= {s.id for s in gb.students}
        return sorted(ids)

    def _run(self, converter_class, record_book: str | None = None, **attrs) -> dict:
        import warnings

        from nbgrader.utils import capture_log

        cfg = self.config(record_book)
        cd = self.coursedir(**{k: v for k, v in attrs.items() if k in ("assignment_id", "student_id")})
        app = converter_class(coursedir=cd, config=cfg, log=self._log)
        for k, val in attrs.items():
            if k not in ("assignment_id", "student_id"):
                setattr(app, k, val)
        logfile = self.root / "aerophoto-course.log"
        handler = logging.FileHandler(logfile, encoding="utf-8")
        handler.setFormatter(logging.Formatter("%(asctime)s %(levelname)s %(message)s"))
        self._log.addHandler(handler)
        try:
            with warnings.catch_warnings(), stderr_to(logfile):
                warnings.simplefilter("ignore")  # SQLAlchemy's SAWarnings from inside nbgrader
                return capture_log(app)
        finally:
            self._log.removeHandler(handler)
            handler.close()

    # generate ----------------------------------------------------------------------------------
    def sync_sources(self) -> list[str]:
        """nbgrader's source of each chapter (reference solutions added) into ``source/<chapter>/``, if changed."""
        from .versions import source_version

        changed = []
        for nb_path in chapters(self.notebooks_dir):
            data = nb_bytes(source_version(read_nb(nb_path)))
            target = self.path("source", nb_path.stem)
            if target.exists() and target.read_bytes() == data:
                continue
            write_atomic(target, data)
            for extra in nb_path.parent.glob(f"{nb_path.stem}_files/*"):
                if extra.is_file():
                    shutil.copy2(extra, target.parent / extra.name)
            changed.append(nb_path.stem)
        return changed

    def generate(self, assignments=None) -> dict[str, bool]:
        """nbgrader generate_assignment for every chapter (or the given ones) → ``release/``."""
        with self.lock("generate"):
            return self._generate(assignments)

    def _generate(self, assignments=None) -> dict[str, bool]:
        from nbgrader.converters import GenerateAssignment

        try:
            self.sync_sources()
        except ValueError as exc:
            self.out(f"generate: {exc}")
            return {a: False for a in (assignments or self.assignments())}
        names = list(assignments or self.assignments())
        ok = {}
        for k, a in enumerate(names, 1):
            t0 = time.perf_counter()
            res = self._run(GenerateAssignment, assignment_id=a, force=True, create_assignment=True)
            ok[a] = bool(res.get("success"))
            status = "released" if ok[a] else "FAILED: " + last_error(res)
            self.out(f"[{k}/{len(names)}] generate {a}: {status} ({time.perf_counter() - t0:.1f} s)")
        return ok

    def _in_gradebook(self, assignment: str) -> bool:
        if not (self.root / "gradebook.db").exists():
            return False
        from nbgrader.api import Gradebook, MissingEntry

        with Gradebook(self.db_url, COURSE_ID) as gb:
            try:
                gb.find_assignment(assignment)
                return True
            except MissingEntry:
                return False

    # import ------------------------------------------------------------------------------------
    def import_submissions(self, folder):
        """Copy an LMS export into ``submitted/<student>/<chapter>/<chapter>.ipynb`` (see :mod:`.lms`).

        The export is only read.  Each file is written atomically (a temporary file, then a rename), so a
        full disk leaves the earlier copy, never a truncated one; nbformat 3 is converted to 4.  A
        submission that replaces a different earlier one is kept: the earlier file is copied to
        ``replaced/<student>/<chapter>/``.  Returns the :class:`~.lms.Scan`; ``scan.failed`` lists the files
        that could not be written.
        """
        from .lms import scan_submissions

        folder = Path(folder)
        if not folder.is_dir():
            raise SystemExit(f"import: {folder} is not a folder")
        with self.lock("import"):
            scan = scan_submissions(folder, self.assignments(), self.roster)
            counts = {"new": 0, "updated": 0, "unchanged": 0}
            for n, ((sid, a), src) in enumerate(sorted(scan.found.items()), 1):
                dest = self.path("submitted", a, sid)
                try:
                    data = src.read_bytes()
                    note = ""
                    if nbformat_major(src) == 3 and notebook_problem(src) is None:
                        converted = read_nb(src)
                        for i, cell in enumerate(converted.cells):  # the same ids on every import
                            cell["id"] = str(cell.get("metadata", {}).get("nbgrader", {}).get("grade_id")
                                             or f"cell-{i}")
                        data, note = nb_bytes(converted), " (nbformat 3, converted to 4)"
                    if dest.exists() and dest.read_bytes() == data:
                        counts["unchanged"] += 1
                        continue
                    if dest.exists():
                        stamp = time.strftime("%Y%m%dT%H%M%S", time.localtime(dest.stat().st_mtime))
                        write_atomic(self.root / "replaced" / sid / a / f"{a}.{stamp}.ipynb", dest.read_bytes())
                        counts["updated"] += 1
                    else:
                        counts["new"] += 1
                    write_atomic(dest, data)  # modified now: newer than any earlier grading of this student
                except OSError as exc:
                    scan.failed.append((src, str(exc)))
                    self.out(f"[{n}/{len(scan.found)}] {sid} · {a} ← {src.relative_to(folder)} — FAILED: {exc} "
                             "(nothing written for it)")
                    continue
                problem = notebook_problem(dest)
                note += f" — WARNING: {problem} (copied; it will be flagged)" if problem else ""
                self.out(f"[{n}/{len(scan.found)}] {sid} · {a} ← {src.relative_to(folder)}{note}")
            for kept, others in scan.duplicates:
                self.out(f"several files for one submission: took {kept.relative_to(folder)} (newest), ignored "
                         + ", ".join(str(o.relative_to(folder)) for o in others))
            for p, why in scan.unrecognised:
                self.out(f"unrecognised: {p.relative_to(folder)} — {why}")
            self.out(f"import: {counts['new']} new, {counts['updated']} updated, {counts['unchanged']} unchanged, "
                     f"{len(scan.unrecognised)} unrecognised file(s)"
                     + (f", {len(scan.failed)} FAILED" if scan.failed else ""))
            return scan

    # autograde ---------------------------------------------------------------------------------
    def submissions(self, students=None, assignments=None) -> list[tuple[str, str]]:
        """(student, assignment) pairs present in ``submitted/``."""
        known = set(self.assignments())
        pairs = []
        sub = self.root / "submitted"
        if not sub.is_dir():
            return pairs
        for sdir in sorted(d for d in sub.iterdir() if d.is_dir() and not d.name.startswith(".")):
            if students and sdir.name not in students:
                continue
            for adir in sorted(d for d in sdir.iterdir() if d.is_dir()):
                if adir.name in known and (not assignments or adir.name in assignments):
                    pairs.append((sdir.name, adir.name))
        return pairs

    def autograde(self, students=None, assignments=None, *, force: bool = False, jobs: int = 1) -> list[GradeResult]:
        """Grade every submitted (student, chapter) in the sandbox; trusted scores.

        A file that is not a notebook is not given to nbgrader; an error never stops the batch; a
        submission already graded and not changed since is skipped unless ``force``.  ``jobs`` > 1 grades
        that many submissions at once, each job in a worker process of its own with a sandbox uid of its own
        (:func:`~.sandbox.sandbox_uid`); the grades are the same as one at a time (each submission is graded
        on its own, for its student's variant), and the results come back in the same order.
        """
        if not isinstance(jobs, int) or isinstance(jobs, bool) or not 1 <= jobs <= MAX_JOBS:
            raise ValueError(f"jobs = {jobs!r} is not valid; expected an integer in 1 … {MAX_JOBS}")
        if not self.unsafe_no_sandbox:
            from .sandbox import require

            require()
        with self.lock("autograde"):
            return self._autograde(students, assignments, force=force, jobs=jobs)

    def _needs_grading(self, sid: str, a: str, force: bool) -> GradeResult | None:
        """The result of a submission that is not to be graded now (missing, corrupt, up to date), else None."""
        sub_path, graded_path = self.path("submitted", a, sid), self.path("autograded", a, sid)
        report = self.report_path(a, sid)
        if not sub_path.exists():
            return GradeResult(sid, a, "missing")
        if (problem := notebook_problem(sub_path)) is not None:
            return GradeResult(sid, a, "corrupt", error=problem)
        if (not force and graded_path.exists() and report.exists() and self.path("source", a).exists()
                and graded_path.stat().st_mtime >= sub_path.stat().st_mtime
                and report.stat().st_mtime >= graded_path.stat().st_mtime
                and graded_path.stat().st_mtime >= self.path("source", a).stat().st_mtime):
            return GradeResult(sid, a, "up-to-date")
        return None

    def _grade_one(self, sid: str, a: str) -> GradeResult:
        """nbgrader autograde of one submission in the sandbox, then the trusted check (the caller holds the lock)."""
        from nbgrader.converters import Autograde

        r = GradeResult(sid, a, "graded")
        t0 = time.perf_counter()
        try:
            with contextlib.suppress(FileNotFoundError):
                self.report_path(a, sid).unlink()
            res = self._run(Autograde, record_book=self.record_book(sid), assignment_id=a, student_id=sid,
                            force=True, create_student=True)
            if not res.get("success"):
                r.status, r.error = "failed", last_error(res)
            else:
                self._trusted(sid, a)
        except Exception as exc:  # never stop the batch
            r.status, r.error = "failed", f"{type(exc).__name__}: {exc}"
        r.seconds = time.perf_counter() - t0
        return r

    def _finish(self, r: GradeResult) -> GradeResult:
        """Score and flags of a result, read from the gradebook and the reports (in the lock holder's process)."""
        if r.status in ("graded", "up-to-date"):
            r.score, r.max_score = self._score(r.assignment, r.student)
        else:
            r.score, r.max_score = 0.0, self._max(r.assignment)
        r.flags = self.flags(r.student, r.assignment)
        return r

    def _say(self, k: int, n: int, r: GradeResult) -> None:
        note = f" — {r.error}" if r.error else ""
        fl = f" [{len(r.flags)} flag(s): {', '.join(sorted({f.code for f in r.flags}))}]" if r.flags else ""
        self.out(f"[{k}/{n}] {r.student} · {r.assignment}: {r.status} {r.score:g}/{r.max_score:g} "
                 f"({r.seconds:.1f} s){fl}{note}")

    def _autograde(self, students, assignments, *, force: bool, jobs: int = 1) -> list[GradeResult]:
        pairs = self.submissions(students, assignments)
        needed = sorted({a for _, a in pairs})
        missing = [a for a in needed if not self._in_gradebook(a) or not self.path("release", a).exists()]
        if missing:
            self.out(f"autograde: generating {', '.join(missing)} first")
            self._generate(missing)
        t_all = time.perf_counter()
        self._same_code.clear()
        done: dict = {}
        todo = []
        for sid, a in pairs:
            r = self._needs_grading(sid, a, force)
            if r is None:
                todo.append((sid, a))
            else:
                done[(sid, a)] = r
        n_jobs = max(1, min(jobs, len(todo)))
        if n_jobs == 1:
            for k, (sid, a) in enumerate(pairs, 1):
                r = done.get((sid, a)) or self._grade_one(sid, a)
                done[(sid, a)] = self._finish(r)
                self._say(k, len(pairs), done[(sid, a)])
        else:
            k = 0
            for sid, a in pairs:  # the ones not graded now, first
                if (sid, a) in done:
                    k += 1
                    self._say(k, len(pairs), self._finish(done[(sid, a)]))
            self.out(f"autograde: {len(todo)} submission(s) in {n_jobs} parallel jobs")
            for r in _parallel(self, todo, n_jobs):
                k += 1
                done[(r.student, r.assignment)] = self._finish(r)
                self._say(k, len(pairs), r)
        results = [done[p] for p in pairs]
        n_fail = sum(r.status == "failed" for r in results)
        self.out(f"autograde: {len(results)} submission(s) in {time.perf_counter() - t_all:.0f} s, "
                 f"{n_fail} could not be graded, {sum(bool(r.flags) for r in results)} flagged")
        return results

    def _trusted(self, sid: str, a: str) -> list:
        """The trusted check of one autograded submission: scores into the gradebook, a report beside."""
        from .sandbox_execute import EVENTS
        from .trusted import grade_executed, write_scores

        rb = self.record_book(sid)
        graded = read_nb(self.path("autograded", a, sid))
        verdicts = grade_executed(graded, rb, tasks=self._release_tasks(a))
        write_scores(self.db_url, a, sid, a, verdicts)
        events = EVENTS.pop((sid, a, a), [])
        report = {"student": sid, "assignment": a, "record_book": rb, "graded_at": time.time(),
                  "sandbox": "none (--unsafe-no-sandbox)" if self.unsafe_no_sandbox else "bubblewrap",
                  "limits": self.limits.as_dict(), "events": events, "verdicts": [v.as_dict() for v in verdicts]}
        write_atomic(self.report_path(a, sid), (json.dumps(report, indent=1) + "\n").encode("utf-8"))
        return verdicts

    def _score(self, assignment: str, student: str) -> tuple[float, float]:
        from nbgrader.api import Gradebook, MissingEntry

        with Gradebook(self.db_url, COURSE_ID) as gb:
            try:
                s = gb.find_submission(assignment, student)
                return float(s.score), float(s.max_score)
            except MissingEntry:
                return 0.0, self._max(assignment)

    def _max(self, assignment: str) -> float:
        return sum(t.points for t in self._release_tasks(assignment))

    def _release_tasks(self, assignment: str) -> list[GradedTask]:
        p = self.path("release", assignment)
        return graded_tasks(read_nb(p)) if p.exists() else []

    def same_code(self, assignment: str) -> dict:
        """{student: [others with identical answer code]} among the submissions of a chapter (cached per run)."""
        if assignment not in self._same_code:
            from .flags import answer_code, same_code_groups

            codes = {}
            for sid, a in self.submissions(assignments=[assignment]):
                p = self.path("submitted", a, sid)
                if p.exists() and notebook_problem(p) is None:
                    codes[sid] = answer_code(read_nb(p))
            self._same_code[assignment] = same_code_groups(codes)
        return self._same_code[assignment]

    def flags(self, student: str, assignment: str) -> list[Flag]:
        """The flags of one student's chapter: structure, behaviour, the trusted check, the sandbox's events."""
        from .flags import inspect_submission

        release = self.path("release", assignment)
        if not release.exists():
            return [Flag("not_generated", f"{assignment} has no student version: run aerophoto-course generate")]
        sub = self.path("submitted", assignment, student)
        flags = inspect_submission(read_nb(release), sub, self.path("autograded", assignment, student),
                                   self.record_book(student))
        if sub.exists() and not {"missing", "corrupt"} & {f.code for f in flags}:
            others = self.same_code(assignment).get(student)
            if others:
                flags.append(Flag("same_code_as", f"{', '.join(others)}: identical answer code"))
        report = self.report_path(assignment, student)
        if report.exists() and not {"missing", "corrupt", "not_graded"} & {f.code for f in flags}:
            try:
                data = json.loads(report.read_text(encoding="utf-8"))
            except (OSError, ValueError):
                data = {}
            for e in data.get("events", []):
                if e.get("kind") in ("kernel_died", "output_truncated", "not_run"):
                    code = "output_truncated" if e["kind"] == "output_truncated" else "kernel_died"
                    flags.append(Flag(code, f"cell {e.get('cell')}: {e.get('message')}"))
            for vd in data.get("verdicts", []):
                flags += [Flag(c, m) for c, m in vd.get("flags", [])]
        elif sub.exists() and not {"missing", "corrupt", "not_graded"} & {f.code for f in flags}:
            flags.append(Flag("not_graded", "no trusted grade: run aerophoto-course autograde"))
        seen, out = set(), []
        for f in flags:
            if (f.code, f.message) not in seen:
                seen.add((f.code, f.message))
                out.append(f)
        return out

    # gradebook, feedback -----------------------------------------------------------------------
    def gradebook(self, by: str = "submission"):
        """The grades and flags as a pandas DataFrame (see :func:`.reports.gradebook`)."""
        from .reports import gradebook

        with self.lock("gradebook"):
            return gradebook(self, by)

    def feedback(self, students=None, assignments=None) -> list[Path]:
        """nbgrader's HTML feedback per student (see :func:`.reports.feedback`)."""
        from .reports import feedback

        return feedback(self, students, assignments)


# --------------------------------------------------------------------------------------------------
# parallel grading: autograde --jobs N


def _worker_spec(course: Course) -> dict:
    return {"root": str(course.root), "notebooks_dir": str(course.notebooks_dir),
            "roster": str(course._roster_path) if course._roster_path else None, "timeout": course.timeout,
            "limits": course._limits.as_dict() if course._limits is not None else None,
            "unsafe_no_sandbox": course.unsafe_no_sandbox}


def _worker(spec: dict, slot: int, tasks, results) -> None:
    """One grading job (a process of its own): grade the (student, chapter) pairs from ``tasks`` until None.

    Runs without the course lock: the process that started it holds it for the whole run.  Its kernels drop
    to the slot's uid (run as root), so its process limit is its own.
    """
    import dataclasses

    try:
        course = Course(spec["root"], spec["notebooks_dir"], roster=spec["roster"], timeout=spec["timeout"],
                        limits=Limits(**spec["limits"]) if spec["limits"] else None,
                        unsafe_no_sandbox=spec["unsafe_no_sandbox"], out=lambda s: None)
        course.sandbox_uid = sandbox_uid(slot)
    except BaseException as exc:  # report the failure for every pair this job takes
        course, why = None, f"the grading job could not start ({type(exc).__name__}: {exc})"
    while True:
        item = tasks.get()
        if item is None:
            return
        sid, a = item
        if course is None:
            r = GradeResult(sid, a, "failed", error=why)
        else:
            try:
                r = course._grade_one(sid, a)
            except BaseException as exc:
                r = GradeResult(sid, a, "failed", error=f"{type(exc).__name__}: {exc}")
        results.put(dataclasses.asdict(r))


def _parallel(course: Course, pairs: list, jobs: int):
    """Grade ``pairs`` in ``jobs`` worker processes; yields each :class:`GradeResult` as it is done.

    Workers are fresh interpreters (``spawn``: nothing of this process's threads, kernels or open gradebook
    is inherited); a pair goes to whichever job is free.  A worker that dies fails its pair, never the batch.
    """
    import multiprocessing as mp
    import queue as queue_mod

    ctx = mp.get_context("spawn")
    tasks, results = ctx.Queue(), ctx.Queue()
    for p in pairs:
        tasks.put(p)
    for _ in range(jobs):
        tasks.put(None)
    spec = _worker_spec(course)
    procs = [ctx.Process(target=_worker, args=(spec, slot, tasks, results), daemon=True,
                         name=f"aerophoto-grader-{slot}") for slot in range(jobs)]
    for proc in procs:
        proc.start()
    left = {tuple(p) for p in pairs}
    try:
        while left:
            try:
                d = results.get(timeout=5)
            except queue_mod.Empty:
                if any(proc.is_alive() for proc in procs):
                    continue
                for sid, a in sorted(left):  # every worker is gone: what is left could not be graded
                    yield GradeResult(sid, a, "failed", error="the grading job ended before grading it")
                return
            left.discard((d["student"], d["assignment"]))
            yield GradeResult(**{k: v for k, v in d.items() if k != "flags"})
    finally:
        for proc in procs:
            proc.join(timeout=30)
            if proc.is_alive():
                proc.kill()
                proc.join(timeout=10)
