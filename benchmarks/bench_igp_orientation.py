"""Speed of the IGP with assigned orientation (seed 004 Sec. 3).  Run by hand:

    python3 -m benchmarks.bench_igp_orientation [--repeat 7]

Prints the machine, then median / min / max of ``--repeat`` runs of: one call of ``igp_orientation`` on seed 004 Table 1 (closed form,
Newton polish, tensions, H_r class), the exact-rational mode on Table 1, and the vectorized closed form
``igp_orientation_batch`` over 100,000 random orientations (target <= 1 s).
"""

import argparse
import statistics
import sys
from pathlib import Path

sys.path[:0] = [str(Path(__file__).resolve().parent), str(Path(__file__).resolve().parents[1])]

import numpy as np  # noqa: E402
import sympy as sp  # noqa: E402
from scipy.spatial.transform import Rotation  # noqa: E402

from cdpr_algebra import load_robot  # noqa: E402
from cdpr_algebra.igp.orientation import exact_solution, igp_orientation, igp_orientation_batch  # noqa: E402
from timing import machine, run_times, spread  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--n", type=int, default=100_000)
    args = ap.parse_args()
    robot = load_robot(ROOT / "examples/seed004_table1.toml")
    igp_orientation(robot, np.eye(3))  # warm up imports
    single = [t / 100 for t in run_times(lambda: [igp_orientation(robot, np.eye(3)) for _ in range(100)], args.repeat)]
    exact = run_times(lambda: exact_solution(robot, sp.eye(3)), max(3, args.repeat // 2))
    Rs = Rotation.random(args.n, random_state=1).as_matrix()
    batch = run_times(lambda: igp_orientation_batch(robot, Rs), args.repeat)
    _, ok = igp_orientation_batch(robot, Rs)
    print(machine())
    print("IGP assigned orientation, Carricato 2013 Table 1")
    print(f"  single call (numeric, polished, H_r):     {spread(single, 'ms', 1e3)}")
    print(f"  exact rational mode:                      {spread(exact, 'ms', 1e3)}")
    print(f"  batch of {args.n} orientations:          {spread(batch)}  "
          f"({args.n / statistics.median(batch):,.0f} poses/s; {ok.sum()} generic, {(~ok).sum()} left to the scalar "
          f"solver)")


if __name__ == "__main__":
    main()
