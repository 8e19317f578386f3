"""Wall time of the interval branch-and-prune DGP (issue 8, seed 000's method) on seed 000 Tests 1-3.

    python -m benchmarks.bench_interval_bp [--repeat 3] [--test2] [--test3] [--max-m M] [--subproblem C1 C2 ..]

Test 1 (all 7 subproblems, m <= 3): the median of ``--repeat`` runs against the target <= 25 s (the published
single-core time of the C++ code, seed 000 Sec. 5.1).  ``--test2`` / ``--test3``: one run of all 63 subproblems
(m <= 6) of Tests 2 / 3 against the published 187 s / 702 s (single core), with the seconds and boxes per m, the
slowest subproblems, and the admissible counts per m against the paper's and against our homotopy DGP
(``cdpr dgp``): Test 2 published 2, 11, 12, 9 with 6, 5, 4, 3 taut cables,
homotopy 2, 11, 14, 7 (the same 34 in all, same counts subproblem by subproblem as the interval solver); Test 3
published 17 *stable* (3, 1, 7, 4, 2 with 6..2 taut), homotopy 16 admissible (3, 0, 7, 4, 2: the paper's 5-cable
row is its 6-cable row 3 with tau_4 = 0.004, over-length with 5 taut cables).  ``--max-m`` limits the subproblems.
Progress goes to stderr.  The first run on a machine also compiles the numba kernels (about 20 s; cached after).
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "benchmarks"), str(ROOT)]

from cdpr_algebra.bp.search import interval_dgp, solve_taut_set_interval  # noqa: E402
from cdpr_algebra.model.robot import load_robot  # noqa: E402
from timing import machine, spread  # noqa: E402

# name: (published seconds, published counts by m, homotopy admissible counts by m)
PUBLISHED = {"seed000_test1": (25.0, {3: 6, 2: 0, 1: 0}, {3: 6, 2: 0, 1: 0}),
             "seed000_test2": (187.0, {6: 2, 5: 11, 4: 12, 3: 9}, {6: 2, 5: 11, 4: 14, 3: 7}),
             "seed000_test3": (702.0, {6: 3, 5: 1, 4: 7, 3: 4, 2: 2}, {6: 3, 5: 0, 4: 7, 3: 4, 2: 2})}


def _progress(sub, done, total):
    print(f"  [{done}/{total}] taut {list(sub.taut)}: {sub.admissible} admissible, {len(sub.undecided)} undecided, "
          f"{sub.boxes} boxes, {sub.seconds:.2f} s{' (' + sub.skipped + ')' if sub.skipped else ''}",
          file=sys.stderr, flush=True)


def run(path, repeat: int, max_m: int, verbose: bool):
    robot = load_robot(path)
    published, counts, homotopy = PUBLISHED.get(robot.name, (None, {}, {}))
    times, res = [], None
    for _ in range(repeat):
        t0 = time.perf_counter()
        res = interval_dgp(robot, max_m=max_m, progress=_progress if verbose else None)
        times.append(time.perf_counter() - t0)
    by_m = {m: len(res.by_m(m)) for m in range(6, 0, -1) if any(len(s.taut) == m for s in res.subproblems)}
    boxes = sum(s.boxes for s in res.subproblems)
    med = statistics.median(times)
    line = (f"{robot.name}: {spread(times)}; "
            f"{len(res.subproblems)} subproblems, {boxes} boxes; admissible by m: "
            f"{', '.join(f'm={m}: {c}' for m, c in by_m.items())}; undecided boxes: {len(res.undecided)}")
    if published is not None:
        line += f"; published {published:g} s (single core)"
        if counts:
            line += f", published counts {counts}" + (" (stable)" if robot.name == "seed000_test3" else "")
        if homotopy:
            line += f", homotopy DGP {homotopy}"
    print(line, flush=True)
    print("  by m (last run): " + "; ".join(
        f"m={m}: {sum(s.seconds for s in res.subproblems if len(s.taut) == m):.1f} s, "
        f"{sum(s.boxes for s in res.subproblems if len(s.taut) == m)} boxes"
        for m in sorted({len(s.taut) for s in res.subproblems})), flush=True)
    slow = sorted(res.subproblems, key=lambda s: -s.seconds)[:8]
    print("  slowest: " + ", ".join(f"{list(s.taut)} {s.seconds:.1f} s ({s.boxes} boxes)" for s in slow), flush=True)
    return med


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--test2", action="store_true", help="also Test 2 (minutes)")
    ap.add_argument("--test3", action="store_true", help="also Test 3 (minutes)")
    ap.add_argument("--max-m", type=int, default=6)
    ap.add_argument("--subproblem", nargs="+", type=int, metavar="C",
                    help="time one subproblem of Test 1 (cable numbers from 1) instead")
    ap.add_argument("--verbose", action="store_true", help="per-subproblem progress on stderr")
    args = ap.parse_args(argv)
    print(machine())
    if args.subproblem:
        robot = load_robot(ROOT / "examples" / "seed000_test1.toml")
        times = []
        for _ in range(args.repeat):
            sub = solve_taut_set_interval(robot, robot.lengths, [c - 1 for c in args.subproblem])
            times.append(sub.seconds)
        print(f"taut {args.subproblem}: {spread(times)}, {sub.admissible} admissible, "
              f"{len(sub.undecided)} undecided, {sub.boxes} boxes")
        return
    med = run(ROOT / "examples" / "seed000_test1.toml", args.repeat, min(args.max_m, 3), args.verbose)
    print(f"Test 1 target <= 25 s: {'met' if med <= 25 else 'NOT met'} ({med:.1f} s)")
    if args.test2:
        run(ROOT / "examples" / "seed000_test2.toml", 1, args.max_m, True)
    if args.test3:
        run(ROOT / "examples" / "seed000_test3.toml", 1, args.max_m, True)


if __name__ == "__main__":
    main()
