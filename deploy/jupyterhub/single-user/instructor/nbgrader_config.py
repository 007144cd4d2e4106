# nbgrader of the instructor's server on the course hub (JUPYTER_CONFIG_DIR, read-only in the sandbox).
# The course folder is ~/course (aerophoto-course writes its own nbgrader_config.py there on first use);
# `nbgrader release_assignment / collect / release_feedback` and the formgrader work from anywhere.
import os

c = get_config()  # noqa: F821
c.CourseDirectory.course_id = "aerophoto"
c.CourseDirectory.root = os.path.expanduser("~/course")
c.Exchange.root = "/srv/nbgrader/exchange"
c.Exchange.path_includes_course = False
# collect: warn when a submission's owner (uid) is not the student it claims to be (the hub's passwd names
# every user); read the warnings of `nbgrader collect`
c.ExchangeCollect.check_owner = True
# The formgrader's "Autograde" button runs nbgrader in this server: at least run the students' code in the
# grading sandbox (no course folder, no network, nobody's rights).  The trusted scores and the flags come only
# from `aerophoto-course autograde` — grade with that.
c.Autograde.autograde_preprocessors = [
    "aerophoto.course.sandbox_execute.SandboxExecute",
    "nbgrader.preprocessors.IgnorePattern",
    "nbconvert.preprocessors.ClearMetadataPreprocessor",
    "nbgrader.preprocessors.LimitOutput",
    "nbgrader.preprocessors.SaveAutoGrades",
    "nbgrader.preprocessors.AssignLatePenalties",
    "nbgrader.preprocessors.CheckCellMetadata",
]
