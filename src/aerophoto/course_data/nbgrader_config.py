# nbgrader configuration of the aerophoto course.
#
# Written into the course folder by `aerophoto-course` the first time it runs there; edit it freely,
# `aerophoto-course` never overwrites it and reads it on every run (its command-line options win).
# The same file drives plain `nbgrader ...` commands and the formgrader when run from this folder.
#
# Course layout (nbgrader's standard one; one assignment per chapter, named after the notebook):
#
#   course/
#     nbgrader_config.py          this file
#     roster.csv                  optional: student_id,record_book (see README, "For instructors")
#     source/00_start_here/00_start_here.ipynb      written by `aerophoto-course generate` from notebooks/ (the
#                                                   student book) with reference solutions computed by the package
#     release/00_start_here/00_start_here.ipynb     student version (solutions removed)
#     submitted/<student_id>/00_start_here/00_start_here.ipynb    from `aerophoto-course import`
#     autograded/<student_id>/00_start_here/...     executed and scored
#     feedback/<student_id>/00_start_here/00_start_here.html
#     trusted/<student_id>/00_start_here.json       the trusted check's report per submission (never released)
#     teacher/                    `aerophoto-course teacher`: the solved copy for projecting
#     gradebook.db                nbgrader's sqlite gradebook
#     grades.csv                  `aerophoto-course gradebook`

c = get_config()  # noqa: F821  (provided by nbgrader's config loader)

c.CourseDirectory.course_id = "aerophoto"

# Every nbgrader command run from this folder — and the formgrader's Autograde and Generate Feedback buttons —
# runs students' code only in the grading sandbox and shows their notebooks cleaned of scripts
# (aerophoto.course.nbconfig.secure_nbgrader: Autograde's preprocessors, Execute's kernel manager,
# HTMLExporter.sanitize_html, GenerateFeedback's preprocessors).  Without aerophoto importable here nbgrader
# refuses to start rather than run a submission unsandboxed.  Keep this line.
from aerophoto.course.nbconfig import secure_nbgrader  # noqa: E402

secure_nbgrader(c)

# Each cell of a submission may run this long (seconds) before the kernel is interrupted and the cell
# recorded as failed (CellTimeoutError); the rest of the notebook still runs.  nbgrader's default is 30 s;
# the book's heaviest cells (rendering the virtual site) take a few seconds on a slow machine.
c.ExecutePreprocessor.timeout = 120
c.ExecutePreprocessor.interrupt_on_timeout = True

# Every submission runs in a sandbox (bubblewrap; see README, "For instructors").  Its resource limits, per
# kernel (all optional; these are the defaults):
# c.SandboxExecute.limits = {"memory_mb": 3072, "cpu_s": 900, "fsize_mb": 64, "nofile": 256, "nproc": 128,
#                            "tmpfs_mb": 256, "output_mb": 4.0, "message_mb": 32}
# A kernel that dies (memory, CPU time) is restarted and the rest of the notebook graded; at most:
# c.SandboxExecute.max_restarts = 2

# What replaces the solution in the student version.  nbgrader's default stub,
# `raise NotImplementedError()`, would stay below the template lines (`H_m = ...`) the student fills,
# so a correct answer cell would still raise.  The template lines already make an unanswered task
# fail its check with "no answer yet".
c.ClearSolutions.code_stub = {"python": "# ↑ replace each ... with your value (your working may go here)"}

# A whole class on JupyterHub: uncomment and point every user's nbgrader at one exchange folder,
# then use nbgrader's release_assignment / collect (see README, "For instructors").
# c.Exchange.root = "/srv/nbgrader/exchange"
