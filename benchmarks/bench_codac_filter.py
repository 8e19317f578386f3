"""Our compiled filter operator against Codac 2's contractors in the interval branch and prune (issue 20 item 2):
both engines on seed 000 Tests 1-3, subproblem by subproblem, with the same counts required.

    python -m benchmarks.bench_codac_filter [--tests 1 2 3] [--engines compiled codac] [--save FILE] [--part K/N]
                                            [--taut C1,C2,.. ...]

For every test and engine: wall time, boxes, admissible equilibria and undecided boxes, per m and in all; then,
subproblem by subproblem, whether the two engines found the same admissible equilibria (same count, each
enclosure of one engine meeting one of the other's) with no undecided box.  ``--save`` writes the per-subproblem
records as JSON; ``--part K/N`` runs the subproblems whose index (in the order of ``cdpr dgp``) is K modulo N, so
that the Codac runs of Tests 2-3 (hours) can be spread over processes.  Exit status 1 when the engines disagree anywhere.
Needs ``pip install codac``.  The engines differ only in the filter (``BPOptions.kernels``); the second-order
operator, the Krawczyk proofs and the bisection are the same code.
"""

from __future__ import annotations

import argparse
import json
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path[:0] = [str(ROOT / "benchmarks"), str(ROOT)]

from cdpr_algebra.bp.results import BPOptions  # noqa: E402
from cdpr_algebra.bp.search import interval_dgp  # noqa: E402
from cdpr_algebra.comparison.compare import _match  # noqa: E402
from cdpr_algebra.model.robot import load_robot  # noqa: E402
from cdpr_algebra.model.taut_sets import lengths_and_taut_sets  # noqa: E402
from timing import machine  # noqa: E402


def _run(robot, engine: str, sets=None):
    def progress(sub, done, total):
        print(f"  {engine} [{done}/{total}] taut {list(sub.taut)}: {sub.admissible} admissible, "
              f"{len(sub.undecided)} undecided, {sub.boxes} boxes, {sub.seconds:.2f} s", file=sys.stderr, flush=True)

    t0 = time.perf_counter()
    res = interval_dgp(robot, options=BPOptions(kernels=engine), progress=progress, sets=sets)
    return res, time.perf_counter() - t0


def _same(robot, a, b) -> bool:
    """Same admissible equilibria: equal counts, no undecided box, each enclosure of a meets one of b's (m >= 2);
    m = 1 solutions carry no enclosure (the platform turns about the cable): matched one to one by the
    cross-check's rule (B_i and G, :func:`cdpr_algebra.comparison.compare._match`)."""
    if len(a.undecided) or len(b.undecided) or a.admissible != b.admissible:
        return False
    if len(a.taut) == 1:
        return not any(_match(robot, a.taut, a.solutions, b.solutions))
    return all(any(np.all(s.enclosure_lo <= t.enclosure_hi) and np.all(t.enclosure_lo <= s.enclosure_hi)
                   for t in b.solutions) for s in a.solutions)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tests", nargs="+", type=int, default=[1], choices=[1, 2, 3])
    ap.add_argument("--engines", nargs="+", default=["compiled", "codac"], choices=["compiled", "codac", "numpy"])
    ap.add_argument("--save", help="write the per-subproblem records (JSON)")
    ap.add_argument("--part", default="0/1", help="K/N: only the subproblems whose index is K modulo N")
    ap.add_argument("--taut", nargs="+", metavar="C1,C2,..", help="only these taut sets (cables from 1)")
    args = ap.parse_args(argv)
    print(machine(), flush=True)
    records, ok = {}, True
    for test in args.tests:
        robot = load_robot(ROOT / "examples" / f"seed000_test{test}.toml")
        k, n = (int(v) for v in args.part.split("/"))
        sets = None
        if n > 1:
            sets = [c for i, c in enumerate(lengths_and_taut_sets(robot)[1]) if i % n == k]
        if args.taut:
            sets = [tuple(sorted(int(c) - 1 for c in t.split(","))) for t in args.taut]
        results = {}
        for engine in args.engines:
            res, seconds = _run(robot, engine, sets)
            results[engine] = res
            boxes = sum(s.boxes for s in res.subproblems)
            by_m = {}
            for s in res.subproblems:
                by_m[len(s.taut)] = by_m.get(len(s.taut), 0) + s.admissible
            print(f"Test {test}, {engine}: {seconds:.1f} s, {boxes} boxes, {len(res.undecided)} undecided; "
                  f"admissible by m {dict(sorted(by_m.items(), reverse=True))}", flush=True)
            records[f"test{test}/{engine}"] = {
                "seconds": seconds, "boxes": boxes,
                "subproblems": [{"taut": list(s.taut), "admissible": s.admissible, "undecided": len(s.undecided),
                                 "boxes": s.boxes, "seconds": s.seconds,
                                 "positions": [np.asarray(x.position).tolist() for x in s.solutions]}
                                for s in res.subproblems]}
            if args.save:
                Path(args.save).write_text(json.dumps(records, indent=1))
        names = list(results)
        for e in names[1:]:
            a, b = results[names[0]], results[e]
            differ = [list(x.taut) for x, y in zip(a.subproblems, b.subproblems) if not _same(robot, x, y)]
            ta = sum(s.seconds for s in a.subproblems)
            tb = sum(s.seconds for s in b.subproblems)
            ba = sum(s.boxes for s in a.subproblems)
            bb = sum(s.boxes for s in b.subproblems)
            print(f"Test {test}: {e} / {names[0]}: time x{tb / ta:.1f}, boxes x{bb / ba:.2f}; "
                  + ("same admissible equilibria in every subproblem, no undecided box" if not differ
                     else f"DIFFERENT in {differ}"), flush=True)
            ok &= not differ
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
