"""Speed of the interval certificates (issue 5).  Run by hand:

    python3 benchmarks/bench_certify.py [--runs 5] [--test3]

Prints medians over ``--runs`` runs of:
* the choice of ball arithmetic: one Krawczyk step's work for a root of seed 000 Test 1 (interval F and J over
  the box, and the product C J(X)) in python-flint arb and in mpmath iv;
* ms per root to certify every DGP root of seed 000 Test 1 (the DGP is run once, its time is printed too);
* ms per root to certify the 24 IGP roots of seed 004 Table 3, next to the IGP itself without certificates;
* ``--test3``: the subproblem of seed 000 Test 3 with all 6 cables taut (about 10-20 s) and the certification of
  its admissible roots, as a share of that subproblem's time.
"""

import argparse
import time
from pathlib import Path

import numpy as np
from flint import arb, arb_mat

from cdpr_algebra import load_robot
from cdpr_algebra.certificates.equilibria import certify_dgp_solutions, taut_system, with_certificates
from cdpr_algebra.dgp.solve import dgp, solve_taut_set
from cdpr_algebra.model.taut_equations import encode
from cdpr_algebra.igp.position import igp_position
from timing import median_time  # benchmarks/timing.py (the script folder is on sys.path)

ROOT = Path(__file__).resolve().parent.parent


def backend_comparison(robot, sol, runs):
    """Interval F, J over a box and C J(X) (15 x 15) in arb and in mpmath iv, for one 3-cable root."""
    from mpmath import iv

    cables = [0, 1, 2]
    x0 = encode(sol.position, sol.rotation, sol.tensions[cables] / robot.lengths[cables])
    data = [robot.base[cables].tolist(), robot.platform[cables].tolist(), robot.com.tolist(),
            (robot.load * robot.load_direction).tolist(), (robot.lengths[cables] ** 2).tolist()]
    C = np.linalg.inv(np.array(taut_system(x0.tolist(), *data[:4], data[4])[1], float))
    r = 1e-12

    def with_arb():
        X = [arb(v, r) for v in x0.tolist()]
        F, J = taut_system(X, *data[:4], data[4])
        return arb_mat(C.tolist()) * arb_mat(J)

    def with_iv():
        X = [iv.mpf([v - r, v + r]) for v in x0.tolist()]
        F, J = taut_system(X, *data[:4], data[4])
        return iv.matrix(C.tolist()) * iv.matrix(J)

    return median_time(with_arb, runs), median_time(with_iv, runs)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--runs", type=int, default=5)
    ap.add_argument("--test3", action="store_true")
    args = ap.parse_args()

    robot = load_robot(ROOT / "examples/seed000_test1.toml")
    t = time.perf_counter()
    res = dgp(robot)
    t_dgp = time.perf_counter() - t
    sols = res.solutions
    t_arb, t_iv = backend_comparison(robot, sols[0], args.runs)
    print(f"one Krawczyk step's interval work (F, J over a box and C J(X), 15 unknowns): arb {t_arb * 1e3:.2f} ms, "
          f"mpmath iv {t_iv * 1e3:.1f} ms ({t_iv / t_arb:.0f}x)")
    certs = certify_dgp_solutions(robot, sols)
    assert all(c.certified for c in certs), [c.reason for c in certs]
    t_cert = median_time(lambda: certify_dgp_solutions(robot, sols), args.runs)
    print(f"seed 000 Test 1 DGP: {len(sols)} roots, certification {t_cert / len(sols) * 1e3:.2f} ms per root "
          f"({t_cert * 1e3:.1f} ms in all, {100 * t_cert / t_dgp:.2f} % of the DGP's {t_dgp:.1f} s)")

    robot3 = load_robot(ROOT / "examples/seed004_table3.toml")
    X = [7.0, 9.0, 1.0]
    bare = igp_position(robot3, X, certify=False)
    real = bare.real_solutions
    assert len(real) == 24
    t_igp = median_time(lambda: igp_position(robot3, X, certify=False), args.runs)
    t_c3 = median_time(lambda: with_certificates(robot3, real, "position"), args.runs)
    print(f"seed 004 Table 3 IGP: 24 roots, certification {t_c3 / 24 * 1e3:.2f} ms per root ({t_c3 * 1e3:.1f} ms in "
          f"all; the IGP without certificates takes {t_igp * 1e3:.1f} ms)")

    if args.test3:
        robot6 = load_robot(ROOT / "examples/seed000_test3.toml")
        t = time.perf_counter()
        sub, s6 = solve_taut_set(robot6, robot6.lengths, range(6))
        t_sub = time.perf_counter() - t
        t_c6 = median_time(lambda: certify_dgp_solutions(robot6, s6), args.runs)
        print(f"seed 000 Test 3, 6 taut cables: {len(s6)} admissible roots, certification "
              f"{t_c6 / max(len(s6), 1) * 1e3:.2f} ms per root, {100 * t_c6 / t_sub:.3f} % of the subproblem's "
              f"{t_sub:.1f} s")


if __name__ == "__main__":
    main()
