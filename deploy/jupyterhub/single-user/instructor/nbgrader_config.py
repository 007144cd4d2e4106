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
# The formgrader's buttons run nbgrader in this server: student code only in the grading sandbox (no course
# folder, no network, nobody's rights), every notebook shown cleaned of scripts (formgrader and feedback) —
# the same settings as the course folder's own nbgrader_config.py (aerophoto.course.nbconfig.secure_nbgrader).
# The trusted scores are written by either; the flags and the report come from `aerophoto-course autograde`.
from aerophoto.course.nbconfig import secure_nbgrader  # noqa: E402

secure_nbgrader(c)
