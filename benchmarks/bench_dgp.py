"""Wall time of the complete DGP (every set of taut cables) on seed 000 Test 1 (target <= 1 s) and, when the
generic sets for m = 4 .. 6 are stored, Test 3 (63 subproblems, target <= 10 s on 2 cores).

    python benchmarks/bench_dgp.py [--repeat 3] [--jobs N] [--no-test3]

The first run of each robot also builds and compiles the families (reported separately as "first run");
the median is over the following runs.  Peak memory (ru_maxrss of this process: subproblems run in threads) is printed.
"""

from __future__ import annotations

import argparse
import resource
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from cdpr_algebra.dgp import available_m, dgp  # noqa: E402
from cdpr_algebra.robot import load_robot  # noqa: E402


def bench(path, repeat, jobs):
    robot = load_robot(path)
    t0 = time.perf_counter()
    res = dgp(robot, jobs=jobs)
    first = time.perf_counter() - t0
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        res = dgp(robot, jobs=jobs)
        times.append(time.perf_counter() - t0)
    counts = {m: len(res.by_m(m)) for m in range(1, 7)}
    skipped = sum(1 for s in res.subproblems if s.skipped)
    failed = sum(s.failed_paths for s in res.subproblems)
    paths = sum(s.paths for s in res.subproblems)
    print(f"{robot.name}: first run {first:.2f} s, median of {repeat}: {statistics.median(times):.2f} s "
          f"(jobs={jobs}); {len(res.solutions)} admissible ({', '.join(f'm={m}: {c}' for m, c in counts.items() if c)}), "
          f"{len(res.stable)} stable; {len(res.subproblems)} subproblems ({skipped} skipped), {paths} paths, "
          f"{failed} failed", flush=True)


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--jobs", type=int, default=None)
    ap.add_argument("--no-test3", action="store_true", help="Test 1 only")
    args = ap.parse_args(argv)
    print(f"stored generic sets: m = {available_m()}")
    bench(ROOT / "examples" / "seed000_test1.toml", args.repeat, args.jobs)
    if args.no_test3:
        print("Test 3: not run (--no-test3)")
    elif {4, 5, 6} <= set(available_m()):
        bench(ROOT / "examples" / "seed000_test3.toml", args.repeat, args.jobs)
    else:
        print("Test 3: skipped (generic sets for m = 4, 5, 6 not all stored)")
    self_kb = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss
    print(f"peak memory: {self_kb / 1024:.0f} MiB")


if __name__ == "__main__":
    main()
