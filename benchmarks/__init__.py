"""Benchmark scripts, run by hand from the repository root: ``python -m benchmarks.<name> [--help]`` (or
``python benchmarks/<name>.py``).  Each prints the machine and, for every timed item, the median, min and max
of several runs (:mod:`benchmarks.timing`)."""
