"""The settings every nbgrader configuration the project ships makes: student code only in the sandbox, the
trusted scores, what the instructor sees cleaned (:func:`secure_nbgrader`).

The course folder's ``nbgrader_config.py`` (written from ``course_data/nbgrader_config.py``) and the hub's
instructor config (``deploy/jupyterhub/single-user/instructor/nbgrader_config.py``) both call it, and so does
:meth:`aerophoto.course.grading.Course.config`; :func:`is_secure_config` tells whether a loaded config has it.
"""

from __future__ import annotations

__all__ = ["secure_nbgrader", "sandbox_validator", "is_secure_config", "SANITIZE_PREPROCESSORS",
           "AUTOGRADE_PREPROCESSORS", "SOLUTION_PREPROCESSORS", "FEEDBACK_PREPROCESSORS"]

SANITIZE_PREPROCESSORS = ["aerophoto.course.restore.RestoreCells", "nbgrader.preprocessors.ClearOutput",
                          "nbgrader.preprocessors.DeduplicateIds", "nbgrader.preprocessors.OverwriteKernelspec",
                          "nbgrader.preprocessors.OverwriteCells", "nbgrader.preprocessors.CheckCellMetadata"]
AUTOGRADE_PREPROCESSORS = ["aerophoto.course.sandbox_execute.SandboxExecute", "nbgrader.preprocessors.IgnorePattern",
                           "nbconvert.preprocessors.ClearMetadataPreprocessor", "nbgrader.preprocessors.LimitOutput",
                           "nbgrader.preprocessors.SaveAutoGrades", "aerophoto.course.autoscore.TrustedScores",
                           "nbgrader.preprocessors.AssignLatePenalties",
                           "nbgrader.preprocessors.CheckCellMetadata", "aerophoto.course.sanitize.SanitizeNotebook"]
FEEDBACK_PREPROCESSORS = ["aerophoto.course.sanitize.SanitizeNotebook", "nbgrader.preprocessors.GetGrades",
                          "nbconvert.preprocessors.CSSHTMLHeaderPreprocessor"]
SOLUTION_PREPROCESSORS = ["nbgrader.preprocessors.IncludeHeaderFooter", "nbgrader.preprocessors.LockCells",
                          "nbgrader.preprocessors.ClearOutput", "nbgrader.preprocessors.ClearMarkScheme",
                          "aerophoto.course.sandbox_execute.SandboxExecute"]


def secure_nbgrader(c) -> None:
    """The settings every nbgrader configuration the project ships makes (the course folder's, the hub's).

    * ``nbgrader autograde`` and the formgrader's *Autograde* button: the graded cells restored from the
      release first (:mod:`.restore`), the notebook run in the sandbox (:mod:`.execute`), the trusted scores
      written over the kernel's (:mod:`.autoscore`), the autograded notebook cleaned of scripts before it is
      written (:mod:`.sanitize`);
    * the other steps that run a notebook: ``generate_solution`` (its preprocessors, configured) and
      ``validate`` — nbgrader 0.9.6's ``Validator.preprocessors`` is not configurable and its ``Execute`` is
      given its kernel manager as an argument (so ``Execute.kernel_manager_class`` would be ignored): the
      Validator's default list is replaced in the running nbgrader, with the sandboxed Execute;
    * the formgrader's page and the feedback HTML: nbconvert's ``sanitize_html``, and the notebook cleaned
      before feedback is made (nbgrader's templates render markdown uncleaned).
    """
    c.Autograde.sanitize_preprocessors = list(SANITIZE_PREPROCESSORS)
    c.Autograde.autograde_preprocessors = list(AUTOGRADE_PREPROCESSORS)
    c.GenerateSolution.preprocessors = list(SOLUTION_PREPROCESSORS)
    c.HTMLExporter.sanitize_html = True
    c.GenerateFeedback.preprocessors = list(FEEDBACK_PREPROCESSORS)
    sandbox_validator()


def sandbox_validator() -> None:
    """nbgrader's Validator (``nbgrader validate``, the Validate button) runs notebooks in the sandbox."""
    from nbgrader.preprocessors import CheckCellMetadata, ClearOutput
    from nbgrader.validator import Validator

    from .sandbox_execute import SandboxExecute

    Validator.class_traits()["preprocessors"].default_value = [CheckCellMetadata, ClearOutput, SandboxExecute]


def is_secure_config(cfg) -> bool:
    """True when a loaded nbgrader Config runs student code only in the sandbox (see :func:`secure_nbgrader`)."""
    def names(section, key):
        return [p if isinstance(p, str) else getattr(p, "__name__", str(p))
                for p in (cfg[section].get(key, []) if section in cfg else [])]

    auto, sol = names("Autograde", "autograde_preprocessors"), names("GenerateSolution", "preprocessors")
    return all(bool(pre) and any(p.endswith("SandboxExecute") for p in pre)
               and not any(p == "Execute" or p.endswith(".Execute") for p in pre) for pre in (auto, sol))
