"""The graded cells of a submission restored from the release before nbgrader reads it (honest slips).

A student who marks a check cell ``grade: false``, strips its nbgrader metadata or copies it below itself
has not changed what is graded — but nbgrader stops on such a notebook ("Inconsistent checksums", "old
version of nbgrader metadata") and the student scores 0 ``not_graded``.  :func:`restore_cells` puts every
locked test cell back as the release has it (source, metadata, in the place of the first cell that carries
its grade_id or its cell id) and removes its copies; an answer cell whose metadata was stripped or changed
gets the release's metadata back (its code is the student's).  :class:`RestoreCells` is the same as an
nbgrader preprocessor, the first of ``Autograde.sanitize_preprocessors`` in every configuration the project
ships; it reads the release's cells from the gradebook, as nbgrader's own ``OverwriteCells`` does.

What was restored is flagged by :func:`aerophoto.course.flags.inspect_submission` (``test_cell_edited``,
``test_cell_stripped``), which compares the submitted file with the release.
"""

from __future__ import annotations

import copy

from nbgrader.preprocessors import NbGraderPreprocessor

from .common import nbg

__all__ = ["restore_cells", "release_cells_from_gradebook", "RestoreCells"]


def _matches(cell, ref) -> bool:
    gid = nbg(ref).get("grade_id")
    return nbg(cell).get("grade_id") == gid or (cell.get("id") is not None and cell.get("id") == ref.get("id"))


def restore_cells(nb, release_cells) -> list[str]:
    """Restore ``nb``'s graded cells (in place) from ``release_cells`` (the release's graded cells, in order).

    A test cell (``grade`` and not ``solution``) is replaced by the release's, outputs cleared; its copies
    (further cells with its grade_id or cell id) are removed.  An answer cell keeps its code and gets the
    release's metadata; further copies lose their nbgrader metadata (they run as ordinary cells).  Returns
    what was done, one line per change.
    """
    done = []
    for ref in release_cells:
        gid = nbg(ref).get("grade_id")
        if not gid:
            continue
        test = bool(nbg(ref).get("grade")) and not nbg(ref).get("solution")
        hits = [i for i, c in enumerate(nb.cells) if _matches(c, ref)]
        if not hits:
            continue
        first, extra = hits[0], hits[1:]
        cell = nb.cells[first]
        if test:
            new = copy.deepcopy(ref)
            new["outputs"], new["execution_count"] = [], None
            if new.get("source") != cell.get("source") or nbg(new) != nbg(cell) or cell.get("cell_type") != "code":
                done.append(f"{gid}: the check cell restored from the release")
            nb.cells[first] = new
            for i in reversed(extra):
                del nb.cells[i]
            if extra:
                done.append(f"{gid}: {len(extra)} copy(ies) of the check cell removed")
        else:
            if nbg(cell) != nbg(ref) or cell.get("cell_type") != ref.get("cell_type"):
                cell["cell_type"] = ref.get("cell_type", "code")
                cell.setdefault("metadata", {})["nbgrader"] = copy.deepcopy(nbg(ref))
                if cell["cell_type"] == "code":
                    cell.setdefault("outputs", [])
                    cell.setdefault("execution_count", None)
                done.append(f"{gid}: the answer cell's nbgrader metadata restored from the release")
            for i in extra:
                nb.cells[i].get("metadata", {}).pop("nbgrader", None)
            if extra:
                done.append(f"{gid}: {len(extra)} copy(ies) of the answer cell kept as ordinary cells")
    return done


def release_cells_from_gradebook(db_url: str, assignment: str, notebook: str) -> list:
    """The release's graded cells of one notebook as nbformat cells, rebuilt from nbgrader's gradebook."""
    from nbformat import NotebookNode
    from nbgrader.api import Gradebook

    cells = []
    with Gradebook(db_url) as gb:
        nb = gb.find_notebook(notebook, assignment)
        solution = {c.name for c in nb.solution_cells}
        points = {c.name: c.max_score for c in nb.grade_cells}
        for sc in nb.source_cells:
            if sc.name not in points and sc.name not in solution:
                continue  # a locked cell that is neither graded nor an answer (nbgrader's own check covers it)
            is_test = sc.name in points and sc.name not in solution
            meta = {"grade": sc.name in points, "grade_id": sc.name, "locked": bool(sc.locked),
                    "schema_version": 3, "solution": sc.name in solution, "task": False}
            if sc.name in points:
                p = points[sc.name]
                meta["points"] = int(p) if float(p).is_integer() else float(p)
            if is_test and sc.checksum:
                meta["checksum"] = sc.checksum
            cell = NotebookNode(cell_type=sc.cell_type, id=sc.name, source=sc.source,
                                metadata=NotebookNode(nbgrader=NotebookNode(meta)))
            if is_test:
                cell["metadata"]["deletable"] = False
                cell["metadata"]["editable"] = False
            if sc.cell_type == "code":
                cell["outputs"], cell["execution_count"] = [], None
            cells.append(cell)
    return cells


class RestoreCells(NbGraderPreprocessor):
    """nbgrader preprocessor: :func:`restore_cells` with the release's cells from the gradebook."""

    def preprocess(self, nb, resources):
        nbr = resources["nbgrader"]
        try:
            ref = release_cells_from_gradebook(nbr["db_url"], nbr["assignment"], nbr["notebook"])
        except Exception as exc:  # no release in the gradebook: nbgrader's own checks will say so
            self.log.warning("RestoreCells: the release's cells could not be read (%s)", exc)
            return nb, resources
        for line in restore_cells(nb, ref):
            self.log.warning("RestoreCells: %s", line)
        return nb, resources
