"""Reading an LMS export: which file is whose submission of which chapter.

Layouts, mixed freely (``<chapter>`` is a chapter name such as ``00_start_here``; a copy suffix `` (1)`` is
ignored):

* ``<student_id>_<chapter>.ipynb`` at the top; a student id that carries a record-book number among other
  words (``ivanov_12345_19-0424_00_start_here.ipynb``, as some LMSs prefix files) is that number;
* a folder per student: ``<student_id>/…/<chapter>.ipynb``;
* any folder holding files named ``<record-book number>_<chapter>.ipynb`` — each file is filed under the
  number in its own name, so two students' files in one folder are both kept;
* Moodle's per-participant folders ``<Full Name>_<participant no.>_assignsubmission_file_/`` — the file's own
  record-book number wins; a bare ``<chapter>.ipynb`` there is filed under the participant number or name
  only if the roster lists it (a participant number is not a record-book number).

**A number claimed twice.**  Several files for one student and chapter from the student's own places (the
top folder, where files are named by student id; a folder named after the student; a Moodle participant the
roster maps to the student) are versions of one submission — the newest is taken and the others reported.
Files for one student and chapter from places of *different* people (two Moodle participants, a group folder
and the student's own) are two people claiming one record-book number — which one is the student's cannot be
told from the export, so neither is taken: all go to ``Scan.conflicts`` (the course keeps them aside in
``conflicts/`` and flags the student ``claimed_twice``).  So does a file in a Moodle participant folder whose
participant the roster maps to another student than the number in the file's name.
"""

from __future__ import annotations

import re
from dataclasses import dataclass, field
from pathlib import Path

from .common import SID_RE

_COPY_SUFFIX = re.compile(r"\s*\(\d+\)$")  # "00_start_here (1)" as browsers and LMSs rename copies
RECORD_BOOK_RE = re.compile(r"(?<![\d])(\d{2}-\d{3,6})(?![\d])")
_MOODLE = re.compile(r"^(?P<name>.+?)_(?P<pid>\d+)_assign(?:submission|feedback)_\w+?_?$")


@dataclass
class Scan:
    """What :func:`scan_submissions` found in an LMS export."""

    found: dict = field(default_factory=dict)          # (student_id, assignment) → Path
    duplicates: list = field(default_factory=list)     # (Path kept, [Paths ignored])
    unrecognised: list = field(default_factory=list)   # (Path, reason)
    failed: list = field(default_factory=list)         # (Path, why): could not be written (import)
    conflicts: dict = field(default_factory=dict)      # (student_id, assignment) → [(Path, owner, why)]: kept aside


def _looks_like_record_book(text: str) -> bool:
    return bool(RECORD_BOOK_RE.fullmatch(text)) or bool(re.fullmatch(r"\d{4,10}", text))


def _from_prefix(prefix: str) -> str:
    """A student id from a file-name prefix: the one record-book number in it, if it has one among words."""
    found = RECORD_BOOK_RE.findall(prefix)
    if len(found) == 1 and found[0] != prefix:
        return found[0]
    return prefix


def _chapter_of(stem: str, names) -> tuple[str | None, str | None]:
    """(prefix, chapter) of a file stem ``<prefix>_<chapter>`` or ``<chapter>`` (prefix None)."""
    for a in names:
        if stem == a:
            return None, a
        if stem.endswith("_" + a) and len(stem) > len(a) + 1:
            return stem[: -len(a) - 1], a
    return None, None


def scan_submissions(folder, assignments, roster: dict | None = None) -> Scan:
    """Recognise the submissions in an LMS export folder (see the module notes).

    When one student has several files for a chapter, the newest (by modification time) is taken and
    the others are reported.
    """
    folder = Path(folder)
    names = sorted(assignments, key=len, reverse=True)
    roster = roster or {}
    candidates: dict = {}
    scan = Scan()
    for p in sorted(folder.rglob("*")):
        rel = p.relative_to(folder)
        if p.is_dir() or any(part.startswith(".") or part == "__MACOSX" for part in rel.parts):
            continue
        if p.suffix != ".ipynb":
            scan.unrecognised.append((p, "not a notebook (.ipynb)"))
            continue
        stem = _COPY_SUFFIX.sub("", p.stem)
        prefix, nb_name = _chapter_of(stem, names)
        if nb_name is None:
            where = "" if len(rel.parts) == 1 else f" (in the folder {rel.parts[0]})"
            scan.unrecognised.append((p, f"name is not <student_id>_<chapter>.ipynb for a known chapter{where}"))
            continue
        sid, owner, claimed_by = None, "(the export's top folder)" if len(rel.parts) == 1 else rel.parts[0], None
        if len(rel.parts) == 1:
            if prefix is None:
                scan.unrecognised.append((p, "a chapter without a student id: name it <student_id>_<chapter>.ipynb"))
                continue
            sid = _from_prefix(prefix)
        else:
            top = rel.parts[0]
            moodle = _MOODLE.match(top)
            if moodle:  # whom the roster says this participant is (None: not listed)
                pid, person = moodle.group("pid"), moodle.group("name")
                claimed_by = next((k for k in (pid, person, person.replace(" ", "_")) if k in roster), None)
            if prefix is not None and (_looks_like_record_book(_from_prefix(prefix)) or prefix in roster
                                       or prefix == top):
                sid = _from_prefix(prefix)
            elif moodle:
                pid, person = moodle.group("pid"), moodle.group("name")
                sid = next((k for k in (pid, person, person.replace(" ", "_")) if k in roster), None)
                if sid is None:
                    scan.unrecognised.append((p, f"Moodle folder of {person} (participant {pid}): the file name "
                                                 "has no record-book number and the roster does not list "
                                                 "the participant — rename it <record book>_<chapter>.ipynb "
                                                 "or add the participant to the roster"))
                    continue
            elif SID_RE.match(top):
                sid = top
            else:
                found = RECORD_BOOK_RE.findall(top)
                if len(found) == 1:
                    sid = found[0]
                else:
                    scan.unrecognised.append((p, f"the folder name {top!r} is not a student id and holds no "
                                                 "record-book number"))
                    continue
        if not SID_RE.match(sid):
            scan.unrecognised.append((p, f"student id {sid!r} has characters nbgrader cannot use "
                                         "(letters, digits, . _ @ - only)"))
            continue
        if claimed_by is not None and claimed_by != sid and roster.get(claimed_by) != sid and \
                _digits(roster.get(claimed_by)) != _digits(sid):
            scan.conflicts.setdefault((sid, nb_name), []).append(
                (p, owner, f"in the folder of {claimed_by} (roster), but named for {sid}"))
            continue
        if len(rel.parts) == 1 or rel.parts[0] == sid or claimed_by == sid or (
                claimed_by is not None and _digits(roster.get(claimed_by)) == _digits(sid)):
            owner = sid  # the student's own place: the top folder (files named by id), their folder, their participant
        candidates.setdefault((sid, nb_name), []).append((p, owner))
    for key, found in sorted(candidates.items()):
        owners = sorted({o for _, o in found})
        if len(owners) > 1 or key in scan.conflicts:
            places = sorted(set(owners) | {o for _, o, _ in scan.conflicts.get(key, [])})
            for p, o in found:
                scan.conflicts.setdefault(key, []).append(
                    (p, o, f"{key[0]} · {key[1]} is claimed from {len(places)} folders: {', '.join(places)}"))
            continue
        paths = sorted((p for p, _ in found), key=lambda q: (_mtime(q), str(q)))
        scan.found[key] = paths[-1]
        if len(paths) > 1:
            scan.duplicates.append((paths[-1], paths[:-1]))
    return scan


def _mtime(p: Path) -> float:
    try:
        return p.stat().st_mtime
    except OSError:
        return 0.0


def _digits(text) -> str:
    return re.sub(r"\D", "", str(text or ""))
