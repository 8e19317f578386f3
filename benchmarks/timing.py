"""Shared timing helpers of the benchmark scripts: repeated wall-clock runs summarized as median / min / max,
and a line describing the machine."""

import os
import platform
import statistics
import sys
import time


def run_times(fn, runs: int, warmup: bool = True) -> list:
    """Wall times (s) of ``runs`` calls of ``fn`` (after one warm-up call)."""
    if warmup:
        fn()
    times = []
    for _ in range(runs):
        t = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t)
    return times


def median_time(fn, runs: int, warmup: bool = True) -> float:
    """Median wall time (s) of ``runs`` calls of ``fn`` (after one warm-up call)."""
    return statistics.median(run_times(fn, runs, warmup))


def spread(times, unit: str = "s", scale: float = 1.0, digits: int = 3) -> str:
    """'median X unit (min .., max .., N runs)' of a list of times in seconds."""
    v = [t * scale for t in times]
    return (f"median {statistics.median(v):.{digits}g} {unit} (min {min(v):.{digits}g}, max {max(v):.{digits}g}, "
            f"{len(v)} runs)")


def machine() -> str:
    """One line: CPU model, cores, Python and numpy versions, the date."""
    cpu = platform.processor() or platform.machine()
    try:
        with open("/proc/cpuinfo", encoding="ascii", errors="replace") as f:
            for line in f:
                if line.startswith("model name"):
                    cpu = line.split(":", 1)[1].strip()
                    break
    except OSError:
        pass
    import numpy as np

    return (f"machine: {cpu}, {os.cpu_count()} cores, Python {sys.version.split()[0]}, numpy {np.__version__}, "
            f"{time.strftime('%Y-%m-%d %H:%M')}")
