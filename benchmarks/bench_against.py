"""Interleaved before/after timing of the complete DGP against an earlier git revision, on this machine.

    python -m benchmarks.bench_against REV [--tests test1,test3] [--rounds 5] [--repeat 3] [--jobs N]

Why.  Timings on the shared 2-core machines drift by 5 % within the hour and differ by 20-40 % between
machines (thirteenth session: the same code ran seed 000 Test 3 in 4.2 s one day and 5.8-6.4 s the next), so a
figure measured in an earlier session is no baseline.  This script checks REV out into a temporary git worktree
and alternates, ``--rounds`` times, one process per tree (the order swapped every round: A B, B A, ...), each
timing ``--repeat`` runs of ``dgp`` after one warm-up run in that process (the warm-up also compiles REV's numba
kernels into its worktree the first time).  Printed: per tree the median and minimum over all timed runs, the
ratio of the medians, and the admissible count of each tree (a check that both solved the same problem).

It imports whichever module layout REV has (``cdpr_algebra.dgp.solve`` and ``cdpr_algebra.model.robot`` since
issue 16, ``cdpr_algebra.dgp`` and ``cdpr_algebra.robot`` before), so it reaches back to the revisions before issue 15
(for example b8c763d, the last commit before it).  The worktree is removed at the end.
"""

from __future__ import annotations

import argparse
import json
import os
import statistics
import subprocess
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

# run in a tree's own directory: times `repeat` DGP runs (after a warm-up) and prints one JSON line
CHILD = r"""
import importlib, json, sys, time
try:
    from cdpr_algebra.model.robot import load_robot
    dgp = importlib.import_module("cdpr_algebra.dgp.solve").dgp
except ImportError:
    from cdpr_algebra.robot import load_robot
    dgp = importlib.import_module("cdpr_algebra.dgp").dgp
robot = load_robot(sys.argv[1])
repeat = int(sys.argv[2])
jobs = None if sys.argv[3] == "None" else int(sys.argv[3])
res = dgp(robot, jobs=jobs)
times = []
for _ in range(repeat):
    t0 = time.perf_counter()
    res = dgp(robot, jobs=jobs)
    times.append(time.perf_counter() - t0)
print(json.dumps({"times": times, "admissible": len(res.solutions)}))
"""


def run_tree(tree: Path, example: Path, repeat: int, jobs) -> dict:
    """One process in ``tree``: its JSON line (times, admissible count)."""
    env = {**os.environ, "PYTHONPATH": str(tree)}
    out = subprocess.run([sys.executable, "-c", CHILD, str(example), str(repeat), str(jobs)], cwd=tree, env=env,
                         capture_output=True, text=True, check=True)
    return json.loads(out.stdout.strip().splitlines()[-1])


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("rev", help="the git revision to compare with (e.g. b8c763d, HEAD~3)")
    ap.add_argument("--tests", default="test3", help="comma-separated: test1, test2, test3")
    ap.add_argument("--rounds", type=int, default=5)
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--jobs", type=int, default=None)
    args = ap.parse_args(argv)
    sys.path.insert(0, str(ROOT / "benchmarks"))
    from timing import machine

    print(machine())
    rev = subprocess.run(["git", "rev-parse", "--short", args.rev], cwd=ROOT, capture_output=True, text=True,
                         check=True).stdout.strip()
    head = subprocess.run(["git", "describe", "--always", "--dirty"], cwd=ROOT, capture_output=True, text=True,
                          check=True).stdout.strip()
    with tempfile.TemporaryDirectory(prefix="cdpr_against_") as tmp:
        old = Path(tmp) / rev
        subprocess.run(["git", "worktree", "add", "--detach", "-q", str(old), rev], cwd=ROOT, check=True)
        try:
            trees = {f"{rev} (REV)": old, f"{head} (this tree)": ROOT}
            for test in args.tests.split(","):
                example = ROOT / "examples" / f"seed000_{test.strip()}.toml"
                acc = {k: [] for k in trees}
                adm = {k: set() for k in trees}
                for r in range(args.rounds):
                    order = list(trees) if r % 2 == 0 else list(trees)[::-1]
                    for k in order:
                        res = run_tree(trees[k], example, args.repeat, args.jobs)
                        acc[k] += res["times"]
                        adm[k].add(res["admissible"])
                        print(f"  {test} round {r + 1} {k}: " + " ".join(f"{t:.2f}" for t in res["times"]), flush=True)
                med = {k: statistics.median(v) for k, v in acc.items()}
                for k, v in acc.items():
                    print(f"{test} {k}: median {med[k]:.2f} s, min {min(v):.2f} s ({len(v)} runs, "
                          f"jobs={args.jobs}); admissible {sorted(adm[k])}")
                a, b = list(trees)
                print(f"{test}: this tree / REV = {med[b] / med[a]:.2f} (medians)", flush=True)
        finally:
            subprocess.run(["git", "worktree", "remove", "--force", str(old)], cwd=ROOT, check=False)


if __name__ == "__main__":
    main()
