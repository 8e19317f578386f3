"""Wall times of the cable-configuration analysis of Merlet's 8-cable robot (seed 002).

    python -m benchmarks.bench_cc [--repeat 3] [--no-paths] [--no-second]

* Sec. IV-B.1 table: valid CCs at (0,1,2) and (1,0,2) and every radius of every CC (8 CCs, 56 cubics, 48 distinct),
  certified; target <= 5 s (published: 8 min 26 s).  "cold" includes the one-time generic solve of the cubic
  distance family (cleared before each run), "warm" reuses it.
* Sec. IV-D uncertainty check: CC [3,4,5,6,7,8] at (0,1,2), +-5 mm on A and rho, +-1 mm on B; target <= 30 s
  (published: 9 min 58 s).
* Second criterion (interval exclusion, radius 0.03) for the 8 CCs; Sec. IV-C arc and planar circle (single runs).
"""

from __future__ import annotations

import argparse
import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "benchmarks"), str(ROOT)]

import numpy as np  # noqa: E402

from cdpr_algebra.cc import cubic_distances  # noqa: E402
from cdpr_algebra.cc.radii import cc_radii_many  # noqa: E402
from cdpr_algebra.cc.configurations import valid_configurations  # noqa: E402
from cdpr_algebra.model.robot import load_robot  # noqa: E402
from timing import machine, spread  # noqa: E402

POSES = [(0.0, 1.0, 2.0), (1.0, 0.0, 2.0)]


def table(robot, cold: bool):
    if cold:
        cubic_distances._GENERIC.clear()
    reqs = [(p, c.cables) for p in POSES for c in valid_configurations(robot, p, sizes=[6])]
    return cc_radii_many(robot, reqs, certify=True)


def timed(fn, repeat):
    """(median wall time, wall times, result, median CPU time of this process): on a shared machine the CPU time
    is the better estimate of the unloaded wall time (the code is single-threaded)."""
    times, cpus, out = [], [], None
    for _ in range(repeat):
        t, c = time.perf_counter(), time.process_time()
        out = fn()
        times.append(time.perf_counter() - t)
        cpus.append(time.process_time() - c)
    return statistics.median(times), times, out, statistics.median(cpus)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--no-paths", action="store_true")
    ap.add_argument("--no-second", action="store_true")
    args = ap.parse_args()
    robot = load_robot(ROOT / "examples" / "seed002_8cables.toml")
    print(machine())

    med, times, res, cpu = timed(lambda: table(robot, cold=True), args.repeat)
    print(f"Sec. IV-B.1 table, cold (generic solve included): {spread(times)} (CPU {cpu:.2f} s)")
    med, times, res, cpu = timed(lambda: table(robot, cold=False), args.repeat)
    print(f"Sec. IV-B.1 table, warm: {spread(times)} (CPU {cpu:.2f} s)")
    for r in res:
        print(f"  {[c + 1 for c in r.cables]} at {r.position.tolist()}: r_min {r.rmin:.12g} "
              f"({'singular' if r.limiting == 'singular' else r.limiting + 1}), certified {r.certified}, "
              f"failed paths {r.failed_paths}")

    from cdpr_algebra.cc.uncertainty import uncertainty_check

    med, times, u, cpu = timed(lambda: uncertainty_check(robot, POSES[0], (2, 3, 4, 5, 6, 7), None, 0.005, 0.001,
                                                         0.005), args.repeat)
    print(f"Sec. IV-D uncertainty, CC [3..8] at (0,1,2), 5/1/5 mm: {spread(times)} (CPU {cpu:.2f} s): robust {u.robust}, {u.boxes} boxes, tension bounds "
          f"{np.round(u.tension_bounds, 4).tolist()}")

    if not args.no_second:
        from cdpr_algebra.cc.safety import exclusion_proof

        t = time.perf_counter()
        out = []
        for p in POSES:
            for c in valid_configurations(robot, p, sizes=[6]):
                ok, boxes, _ = exclusion_proof(robot, p, c.cables, radius=0.03)
                out.append((c.numbers, ok, boxes))
        print(f"second criterion (interval exclusion, R = 0.03), 8 CCs: {time.perf_counter() - t:.2f} s (one run): {out}")

    if not args.no_paths:
        from cdpr_algebra.cc.paths import parse_path, path_radii

        for exprs, rng in ((["cos(t)", "sin(t)", "2"], (0, np.pi / 2)),
                           (["1 + 0.4*cos(t)", "0.4*sin(t)", "2"], (0, 2 * np.pi))):
            t = time.perf_counter()
            pr = path_radii(robot, parse_path(exprs, [rng]), (2, 3, 4, 5, 6, 7))
            print(f"Sec. IV-C {exprs} over {rng}: index {pr.index:.15g} ({pr.where.get('source')}), "
                  f"{time.perf_counter() - t:.2f} s (one run)")


if __name__ == "__main__":
    main()
