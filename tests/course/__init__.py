"""Layer 6, the course: checks, grading (course/, sandbox, hub), report, book, the layers and the chapter key."""
