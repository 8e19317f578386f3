"""Shared timing helper of the benchmark scripts."""

import statistics
import time


def median_time(fn, runs: int, warmup: bool = True) -> float:
    """Median wall time (s) of ``runs`` calls of ``fn`` (after one warm-up call)."""
    if warmup:
        fn()
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return statistics.median(times)
