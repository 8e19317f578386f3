"""Speed of the interval certificates (issue 5).  Run by hand:

    python3 -m benchmarks.bench_certify [--runs 5] [--test3]

Prints the machine, then median / min / max over ``--runs`` runs of:
* the choice of ball arithmetic: one Krawczyk step's work for a root of seed 000 Test 1 (interval F and J over
  the box, and the product C J(X)) in python-flint arb and in mpmath iv;
* ms per root to certify every DGP root of seed 000 Test 1 (the DGP is run once, its time is printed too);
* ms per root to certify the 24 IGP roots of seed 004 Table 3, next to the IGP itself without certificates;
* ``--test3``: the subproblem of seed 000 Test 3 with all 6 cables taut (about 10-20 s) and the certification of
  its admissible roots, as a share of that subproblem's time.
"""

import argparse
import statistics
import time
import sys
from pathlib import Path

sys.path[:0] = [str(Path(__file__).resolve().parent), str(Path(__file__).resolve().parents[1])]

import numpy as np  # noqa: E402
from flint import arb, arb_mat  # noqa: E402

from cdpr_algebra import load_robot  # noqa: E402
from cdpr_algebra.certificates.equilibria import certify_dgp_solutions, taut_system, with_certificates  # noqa: E402
from cdpr_algebra.dgp.solve import dgp, solve_taut_set  # noqa: E402
from cdpr_algebra.model.taut_equations import encode  # noqa: E402
from cdpr_algebra.igp.position import igp_position  # noqa: E402
from timing import machine, median_time, run_times, spread  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]


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
    print(machine())

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
    times = run_times(lambda: certify_dgp_solutions(robot, sols), args.runs)
    t_cert = statistics.median(times)
    print(f"Berti et al. 2016 Test 1 DGP: {len(sols)} roots, certification {t_cert / len(sols) * 1e3:.2f} ms per root "
          f"({spread(times, 'ms', 1e3)} in all, {100 * t_cert / t_dgp:.2f} % of the DGP's {t_dgp:.1f} s)")

    robot3 = load_robot(ROOT / "examples/seed004_table3.toml")
    X = [7.0, 9.0, 1.0]
    bare = igp_position(robot3, X, certify=False)
    real = bare.real_solutions
    assert len(real) == 24
    t_igp = run_times(lambda: igp_position(robot3, X, certify=False), args.runs)
    t_c3 = run_times(lambda: with_certificates(robot3, real, "position"), args.runs)
    print(f"Carricato 2013 Table 3 IGP: 24 roots, certification {statistics.median(t_c3) / 24 * 1e3:.2f} ms per root "
          f"({spread(t_c3, 'ms', 1e3)} in all; the IGP without certificates: {spread(t_igp, 'ms', 1e3)})")

    if args.test3:
        robot6 = load_robot(ROOT / "examples/seed000_test3.toml")
        t = time.perf_counter()
        sub, s6 = solve_taut_set(robot6, robot6.lengths, range(6))
        t_sub = time.perf_counter() - t
        times6 = run_times(lambda: certify_dgp_solutions(robot6, s6), args.runs)
        t_c6 = statistics.median(times6)
        print(f"Berti et al. 2016 Test 3, 6 taut cables ({spread(times6)}): {len(s6)} admissible roots, certification "
              f"{t_c6 / max(len(s6), 1) * 1e3:.2f} ms per root, {100 * t_c6 / t_sub:.3f} % of the subproblem's "
              f"{t_sub:.1f} s")


if __name__ == "__main__":
    main()
