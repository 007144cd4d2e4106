"""Timing helpers shared by the benchmark scripts (medians and p95, never asserts)."""

from __future__ import annotations

import platform
import statistics
import time


def summarize(samples_s) -> dict:
    """Median, p95, min, max and count of a list of durations given in seconds, reported in ms."""
    xs = sorted(float(s) * 1000.0 for s in samples_s)
    if not xs:
        return {"n": 0}
    k = max(0, min(len(xs) - 1, int(round(0.95 * (len(xs) - 1)))))
    return {
        "n": len(xs),
        "median_ms": round(statistics.median(xs), 3),
        "p95_ms": round(xs[k], 3),
        "min_ms": round(xs[0], 3),
        "max_ms": round(xs[-1], 3),
    }


def measure(fn, n: int, *, warmup: int = 2, args_for=None) -> dict:
    """Call ``fn`` (or ``fn(*args_for(i))``) n times after a warm-up; return :func:`summarize`."""
    for i in range(warmup):
        fn(*(args_for(i) if args_for else ()))
    samples = []
    for i in range(n):
        a = args_for(i) if args_for else ()
        t0 = time.perf_counter()
        fn(*a)
        samples.append(time.perf_counter() - t0)
    return summarize(samples)


def machine() -> dict:
    import os

    return {"python": platform.python_version(), "cpus": os.cpu_count(), "platform": platform.platform()}
