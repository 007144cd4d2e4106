"""The tests that execute the book's notebooks (headless kernels; slow)."""
