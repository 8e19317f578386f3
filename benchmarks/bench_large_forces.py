"""Robustness of the DGP on robots built around a known equilibrium with internal forces K times the load
(issue 15; the construction of ``tests/large_forces.py``, a nearly singular wrench matrix).

    python -m benchmarks.bench_large_forces [--m 3 4 5 6] [--K 1e1 1e2 1e3 1e4 1e5] [--seeds 300 301 302 303]
                                            [--extended-precision]

For every (m, K, seed) the taut set of all m cables is solved (``dgp.solve.solve_taut_set``, certificates on) and
counted as

* **found**: the equilibrium is returned (pose within 1e-6 of the robot's size, tensions to 1e-6 relative), either
  as constructed, as the root of the system actually solved, whose parameters are rounded to doubles, or as the
  root of the robot's own system, which the certificates prove (60-digit Newton from the constructed point: with
  condition numbers ~1e11 the three differ by ~1e-6 .. 1e-5 in the tensions), and of
  these how many carry a certificate (existence, uniqueness, tension signs and slack cables proven);
* **flagged**: not returned, and the subproblem says it is incomplete (failed paths or uncertified endpoints);
* **missed**: not returned although the subproblem says complete.  For these the equilibrium is confirmed to be
  a root of the normalized system the homotopy solved: Newton's method in 60 digits from the constructed point
  (``converges`` when its updates fall below 1e-40 quadratically); a missed root is a broken promise.

``--extended-precision`` solves with ``dgp.solve.default_options(extended=True)`` (``cdpr dgp --extended-precision``).
Prints the counts, each missed case with its outcomes, and the seconds.  Robot-independent figures, not a timing.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path


ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))


def main(argv=None):
    from cdpr_algebra.dgp.solve import default_options, solve_taut_set
    from large_forces import equilibrium_hits, large_force_robot

    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--m", type=int, nargs="+", default=[3, 4, 5, 6])
    ap.add_argument("--K", type=float, nargs="+", default=[1e1, 1e2, 1e3, 1e4, 1e5])
    ap.add_argument("--seeds", type=int, nargs="+", default=[300, 301, 302, 303])
    ap.add_argument("--extended-precision", action="store_true", help="Newton residuals in double-double where "
                    "double precision stalls")
    a = ap.parse_args(argv)
    options = default_options(extended=a.extended_precision)
    t0 = time.perf_counter()
    counts = {"found": 0, "flagged": 0, "missed": 0}
    certified = 0
    missed = []
    for m in a.m:
        for K in a.K:
            for seed in a.seeds:
                robot, p, R, tau = large_force_robot(m, K, seed + 10 * m)
                cables = tuple(range(m))
                sub, sols = solve_taut_set(robot, robot.lengths, cables, options=options)
                hits, root = equilibrium_hits(sols, robot, cables, p, R, tau)
                found = bool(hits)
                certified += any(s.certificate is not None and s.certificate.certified for s in hits)
                kind = "found" if found else ("flagged" if not sub.complete else "missed")
                counts[kind] += 1
                if kind == "missed":
                    missed.append((m, K, seed, dict(sub.outcomes), root is not None))
    n = sum(counts.values())
    mode = ", extended precision" if a.extended_precision else ""
    print(f"{n} robots (m = {a.m}, K = {a.K}, seeds {a.seeds}{mode}): {counts['found']} found ({certified} certified), "
          f"{counts['flagged']} flagged "
          f"incomplete, {counts['missed']} missed while complete; {time.perf_counter() - t0:.1f} s")
    for m, K, seed, outcomes, root in missed:
        print(f"  missed: m = {m}, K = {K:g}, seed {seed}: outcomes {outcomes}; the equilibrium is "
              + ("a root (60-digit Newton converges)" if root else "not confirmed by 60-digit Newton"))


if __name__ == "__main__":
    main()
