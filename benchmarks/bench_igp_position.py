"""Speed of the IGP with assigned position (seed 004 Sec. 4, Table 3).  Run by hand:

    python3 -m benchmarks.bench_igp_position [--runs 200]

Prints the machine, then median / min / max over ``--runs`` calls of:
* ``igp_position`` on seed 004 Table 3 (x = [7, 9, 1]): everything, including ``make_solutions`` (lengths,
  tensions, residual, H_r class, batched over the 24 solutions);
* ``solve_euler_parameters``: the numeric core alone (quartic coefficients, dialytic eigenproblem, clusters,
  e0 = 0 branch, Newton polish, verification, deduplication) returning the 24 Euler parameter vectors;
* ``make_solutions`` for the 24 solutions at once (its share of the full call);
* the exact determinant det S(e3) (20 x 20 form) for Table 3.
"""

import argparse
import sys
from pathlib import Path

sys.path[:0] = [str(Path(__file__).resolve().parent), str(Path(__file__).resolve().parents[1])]

import numpy as np  # noqa: E402

from cdpr_algebra import load_robot  # noqa: E402
from cdpr_algebra.igp.position import dialytic_determinant, igp_position, solve_euler_parameters
from cdpr_algebra.model.pose import matrix_from_euler_parameters
from cdpr_algebra.igp.results import make_solutions
from timing import machine, run_times, spread  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
X = [7.0, 9.0, 1.0]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=200)
    args = ap.parse_args()
    robot = load_robot(ROOT / "examples/seed004_table3.toml")
    res = igp_position(robot, X)
    assert len(res.real_solutions) == 24, res.message
    full = run_times(lambda: igp_position(robot, X), args.runs)
    core = run_times(lambda: solve_euler_parameters(robot, X), args.runs)
    eps = [np.real(s.euler_parameters) for s in res.solutions]
    Rs = [matrix_from_euler_parameters(e) for e in eps]
    batch = run_times(lambda: make_solutions(robot, [X] * len(eps), Rs, eps), args.runs)
    exact = run_times(lambda: dialytic_determinant(robot, X, "20"), max(3, args.runs // 20))
    print(machine())
    print("IGP assigned position, Carricato 2013 Table 3, 24 real solutions")
    print(f"  igp_position (all 24 solutions, complete):          {spread(full, 'ms', 1e3)}")
    print(f"  numeric core solve_euler_parameters:                {spread(core, 'ms', 1e3)}")
    print(f"  make_solutions, the 24 solutions batched:           {spread(batch, 'ms', 1e3)}")
    print(f"  exact det S(e3), 20 x 20 form:                      {spread(exact, 'ms', 1e3)}")


if __name__ == "__main__":
    main()
