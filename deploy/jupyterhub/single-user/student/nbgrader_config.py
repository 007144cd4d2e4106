# nbgrader of a student's server on the course hub (JUPYTER_CONFIG_DIR, read-only in the sandbox).
# The Assignments list (Nbgrader → Assignment List) fetches from and submits to the shared exchange.
c = get_config()  # noqa: F821
c.CourseDirectory.course_id = "aerophoto"
c.Exchange.root = "/srv/nbgrader/exchange"   # bound read-write into every user's sandbox
c.Exchange.path_includes_course = False      # fetched chapters land in ~/<chapter>/
