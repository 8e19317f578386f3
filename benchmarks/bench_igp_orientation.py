"""Speed of the IGP with assigned orientation (seed 004 Sec. 3).  Run by hand:

    python3 benchmarks/bench_igp_orientation.py [--repeat 7]

Prints the median of ``--repeat`` runs of: one call of ``igp_orientation`` on seed 004 Table 1 (closed form,
Newton polish, tensions, H_r class), the exact-rational mode on Table 1, and the vectorized closed form
``igp_orientation_batch`` over 100,000 random orientations (target <= 1 s).
"""

import argparse
from pathlib import Path

import numpy as np
import sympy as sp
from scipy.spatial.transform import Rotation

from cdpr_algebra import load_robot
from cdpr_algebra.igp.orientation import exact_solution, igp_orientation, igp_orientation_batch
from timing import median_time  # benchmarks/timing.py (the script folder is on sys.path)

ROOT = Path(__file__).resolve().parent.parent


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=7)
    ap.add_argument("--n", type=int, default=100_000)
    args = ap.parse_args()
    robot = load_robot(ROOT / "examples/seed004_table1.toml")
    igp_orientation(robot, np.eye(3))  # warm up imports
    single = median_time(lambda: [igp_orientation(robot, np.eye(3)) for _ in range(100)], args.repeat) / 100
    exact = median_time(lambda: exact_solution(robot, sp.eye(3)), max(3, args.repeat // 2))
    Rs = Rotation.random(args.n, random_state=1).as_matrix()
    batch = median_time(lambda: igp_orientation_batch(robot, Rs), args.repeat)
    _, ok = igp_orientation_batch(robot, Rs)
    print(f"IGP assigned orientation, seed 004 Table 1 (median of {args.repeat} runs)")
    print(f"  single call (numeric, polished, H_r):     {single * 1e3:8.3f} ms")
    print(f"  exact rational mode:                      {exact * 1e3:8.1f} ms")
    print(f"  batch of {args.n} orientations:          {batch:8.3f} s  ({args.n / batch:,.0f} poses/s; "
          f"{ok.sum()} generic, {(~ok).sum()} left to the scalar solver)")


if __name__ == "__main__":
    main()
