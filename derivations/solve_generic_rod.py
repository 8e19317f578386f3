"""Compute, certify and store the generic solution sets of the rod systems ``rod_family(m)`` (m = 2 .. 5).

Re-runnable, NOT a ``derive_*.py`` (monodromy and the trace test are randomized and take minutes):

    python derivations/solve_generic_rod.py --m 2 3 5        # writes cdpr_algebra/data/rod_generic_m{m}.json
    python derivations/solve_generic_rod.py --m 4 --chart 20131   # the witness points on a chart (m = 4 needs it)

The rod system (:mod:`cdpr_algebra.model.rod_equations`) is what a taut set solves when its platform anchors and
centre of mass lie on one line: one root per family of equilibria turning about that line.  No count is known from
the literature, so none is aimed at:

* seed point: random complex (G, u, lam, mu) with u.u = D.D, parameters by minimum-norm Gauss-Newton from a rod of
  unit-size robot (exit points in [-0.6, 0.6]^3, lengths 0.55-1, s in [-1, 1], |D| 0.05-0.2, load 1 along -z) plus
  complex noise (:func:`cdpr_algebra.homotopy.monodromy.seed_instance`);
* monodromy with NO target count, until ``--no-progress`` consecutive loops add nothing; then ``--extra`` more loops
  with every known solution tracked around each must add nothing (recorded);
* the trace test (:func:`cdpr_algebra.homotopy.trace_test.verify_solution_completeness`, the certificate that a
  monodromy solution set is complete) of the set found, in the line's pose coordinates (G, u), which separate the
  solutions (checked by the test; lam and mu follow linearly from the pose and have poles along the test's curve,
  which would multiply its witness points), recorded in the file's ``meta["trace_test"]``; a set whose
  trace test does not pass is NOT stored (exit status 1);
* ``--phc`` (where PHCpack's ``phc`` is installed): an independent count, recorded in the stored file's
  ``meta["phc"]``: PHCpack's blackbox ``phc -b`` on a new random complex instance of the rod system, its regular
  solutions de-duplicated (conditioning-aware, :func:`cdpr_algebra.homotopy.trace_test.distinct_points`), and the
  stored set moved to that instance by a gamma-trick parameter homotopy and matched against them both ways.

Recorded (twenty-fifth session, seed 1; m = 4 from seed 2, whose witness set made the trace pass where seed 1's,
found in affine coordinates, did not): 12, 26, 20 and 8 solutions; PHCpack 12, 26, 20 and 8 (mixed volumes 72, 160,
160, 64), every one matched both ways.  The trace separated weakly for m = 2, 3, 4 at first: the smallest second
difference of a single point (``detection``) was only 7.6, 47 and 12 times the measured trace (below the 1e-8
tolerance), the trace being the rounding noise of double-precision points.  Since the thirty-fifth session a trace
passes only with a separation of at least 100 (``TraceTestOptions.separation``), and ``--retrace EPS`` refines every
point in arbitrary precision before the sums (``polish_condition=0``): m = 2, 3, 4 re-recorded at eps 0.5
(``--retrace 0.5 --m 2 3``; ``--retrace 0.5 --m 4 --seed 2 --chart 20131``), relative traces 1.7e-14, 1.1e-14,
1.6e-14 against detections 1.3e-10, 1.6e-9, 9.6e-9: separations 7.4e3, 1.4e5, 6.0e5 (156, 103, 124 s); m = 5
separates by 4.6e4 as recorded (eps 0.1).  The records keep q0, l and W10, so that the trace can be computed again
(``tests/test_dgp_rod.py``), and the earlier records in ``history``.
"""

from __future__ import annotations

import argparse
import sys
import time
from dataclasses import replace
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from cdpr_algebra.homotopy.monodromy import MonodromyOptions, monodromy_solve, save_instance  # noqa: E402
from cdpr_algebra.homotopy.trace_test import (TraceTestOptions, distinct_points,  # noqa: E402
                                              verify_solution_completeness)
from cdpr_algebra.model.rod_equations import ROD_M, rod_family  # noqa: E402
from certify_generic_dgp import complex_from_record, complex_record  # noqa: E402

DATA = ROOT / "cdpr_algebra" / "data"
POSE_COORDINATES = list(range(6))  # the trace test in (G, u): lam and mu follow linearly and have poles on the curve


def path_for(m: int) -> Path:
    return DATA / f"rod_generic_m{m}.json"


def unit_rod_guess(m: int, rng, noise: float = 0.3) -> np.ndarray:
    """Parameters (A_i, rho_i^2, s_i, D.D, Q d) of a rod hung in a unit-size robot, plus complex noise."""
    A = rng.uniform(-0.6, 0.6, size=(m, 3))
    r2 = rng.uniform(0.55, 1.0, size=m) ** 2
    s = rng.uniform(-1.0, 1.0, size=m)
    DD = rng.uniform(0.05, 0.2) ** 2
    p = np.concatenate([A.ravel(), r2, s, [DD], [0.0, 0.0, -1.0]])
    return p + noise * (np.abs(p) + 0.1) * (rng.normal(size=p.size) + 1j * rng.normal(size=p.size))


def seed_point(m: int, rng) -> np.ndarray:
    """A random complex (G, u, lam, mu) with u.u = 0.15^2 (the guess's D.D is then adjusted to it)."""
    u = rng.normal(size=3) + 1j * rng.normal(size=3)
    u *= 0.15 / np.sqrt(u @ u)
    return np.concatenate([0.3 * (rng.normal(size=3) + 1j * rng.normal(size=3)), u,
                           rng.normal(size=m) + 1j * rng.normal(size=m), [rng.normal() + 1j * rng.normal()]])


def solve_generic(m: int, seed: int = 1, no_progress: int = 8, extra: int = 3, verbose: bool = True,
                  chart: int | None = None):
    fam = rod_family(m)
    rng = np.random.default_rng(seed)
    t0 = time.perf_counter()
    res = monodromy_solve(fam, seed=seed, x0=seed_point(m, rng), p_guess=unit_rod_guess(m, rng),
                          options=MonodromyOptions(max_loops_no_progress=no_progress, max_loops=120))
    if verbose:
        print(f"m = {m}: {res.summary_line()}", flush=True)
    check, X, new, distinct = extra_loop_check(fam, res, m, seed, extra, verbose=verbose)
    F, J = fam.evaluate_and_jacobian(X, res.parameters)
    meta = {"m": m, "monodromy": res.to_dict(),
            "check": {"extra_loops": check.loops, "paths_tracked": check.paths_tracked, "new_solutions": new,
                      "seconds": check.seconds},
            "distinct": distinct, "max_residual": float(np.max(np.abs(F))),
            "max_jacobian_condition": float(np.max(np.linalg.cond(J))),
            "scale": "unit-size robot: base centred at the origin, lengths / robot size, load Q d with Q = 1"}
    t1 = time.perf_counter()
    tr = verify_solution_completeness(fam, res.parameters, X, seed=seed, options=TraceTestOptions(),
                                      verbose=verbose, coordinates=POSE_COORDINATES, chart=chart)
    meta["trace_test"] = trace_record(tr, len(X), seed, chart, time.perf_counter() - t1)
    meta["seconds"] = time.perf_counter() - t0
    if verbose:
        print(f"m = {m}: trace test {tr.trace.status} ({len(tr.W10)} witness points, "
              f"{meta['trace_test']['seconds']:.1f} s): {tr.trace.to_dict()}", flush=True)
    return res.parameters, X, meta


def extra_loop_check(fam, res, m: int, seed: int, extra: int, fixed=(), verbose: bool = True, relations=()):
    """``extra`` more monodromy loops from the set of ``res`` with every known solution tracked around each (inside
    the subfamily of ``fixed`` parameters and linear ``relations``): (the run, its solutions, new ones, distinct
    ones)."""
    check = monodromy_solve(fam, parameters=res.parameters, solutions=res.solutions, seed=seed + 1000,
                            options=MonodromyOptions(max_loops_no_progress=extra, initial_loops=extra,
                                                     max_loops=extra, fixed_parameters=tuple(fixed),
                                                     parameter_relations=tuple(relations)))
    new = len(check.solutions) - len(res.solutions)
    X = check.solutions
    distinct = len(distinct_points(fam, res.parameters, X)[0])
    if verbose:
        print(f"m = {m}: check with {check.loops} extra loops ({check.paths_tracked} paths): {new} new; "
              f"{distinct} distinct of {len(X)}", flush=True)
    return check, X, new, distinct


def trace_record(tr, count: int, seed: int, chart, seconds: float) -> dict:
    """The record of a trace test ``tr`` of ``count`` stored solutions, kept in the file's ``meta["trace_test"]``:
    with q0, l and W10, so that the trace can be computed again (:func:`retrace`, the tests)."""
    return {"status": tr.trace.status, "count": int(count), "seed": seed,
            "coordinates": [int(c) for c in tr.coordinates], "chart": chart, "W10_count": int(len(tr.W10)),
            "q0": complex_record(tr.q0), "l": complex_record(tr.l), "W10": complex_record(tr.W10),
            "trace": tr.trace.to_dict(), "witnesses": tr.witnesses, "seconds": seconds}


def run_phc(m: int, seed: int = 7, timeout: float = 3600, verbose: bool = True) -> dict:
    """PHCpack's count on a random complex instance, matched with the stored set moved there (module doc)."""
    import sympy as sp

    sys.path.insert(0, str(ROOT / "benchmarks"))
    from bench_homotopy import phc_run  # noqa: E402
    from cdpr_algebra.homotopy.endgame import SolveOptions
    from cdpr_algebra.homotopy.monodromy import load_instance
    from cdpr_algebra.homotopy.solve import solve_parameter_homotopy
    from cdpr_algebra.homotopy.systems import PolynomialSystem

    fam = rod_family(m)
    p0, X0, _ = load_instance(path_for(m), fam)
    p = unit_rod_guess(m, np.random.default_rng(seed))
    sub = {v: sp.Float(z.real, 17) + sp.Float(z.imag, 17) * sp.I for v, z in zip(fam.parameters, p)}
    inst = PolynomialSystem([sp.expand(e.xreplace(sub)) for e in fam.equations], fam.variables, (), "rod_instance")
    res = phc_run(inst, np.zeros(0), timeout=timeout)
    if res is None or res["timeout"]:
        return {"status": "phc not installed" if res is None else "timeout", "seed": seed}
    P, _ = distinct_points(fam, p, res["solutions"])
    moved = solve_parameter_homotopy(fam, p0, X0, p, seed=seed, gamma=True, options=SolveOptions())
    Y, _ = distinct_points(fam, p, np.array([x.x for x in moved.solutions if not x.singular]).reshape(-1, fam.n))
    d = np.max(np.abs(Y[:, None, :] - P[None, :, :]), axis=2) if len(Y) and len(P) else np.zeros((len(Y), len(P)))
    close = d <= 1e-6 * (1 + np.max(np.abs(Y), axis=1))[:, None]
    out = {"status": "finished", "seed": seed, "wall_seconds": res["wall"], "mixed_volume": res["paths"],
           "regular": int(len(res["solutions"])), "phc_distinct": int(len(P)), "stored": int(len(X0)),
           "stored_moved_distinct": int(len(Y)), "stored_matched": int(close.any(axis=1).sum()),
           "phc_matched": int(close.any(axis=0).sum())}
    if verbose:
        print(f"m = {m}: PHCpack {out['phc_distinct']} distinct regular solutions (mixed volume "
              f"{out['mixed_volume']}, {res['wall']:.0f} s); stored {len(X0)} moved there: {len(Y)} distinct, "
              f"{out['stored_matched']} match a PHCpack solution, {out['phc_matched']} of PHCpack's matched",
              flush=True)
    return out


def retrace(path, fam, m: int, seed: int, eps: float, chart: int | None = None, coordinates=POSE_COORDINATES,
            options: TraceTestOptions | None = None, verbose: bool = True) -> int:
    """The trace test of the stored set of ``path`` (system ``fam``) again, every point refined in arbitrary
    precision before the sums (``polish_condition=0``: the trace's rounding noise drops to ~1e-15, so it separates
    from a single point's second difference) and the pencil tracked to +-eps (a larger eps gives every point a
    larger second difference); W10 is the recorded one when the record holds it (same seed, q0, l), else found
    again (``chart``; ``options`` the test's other settings).  Recorded in ``meta["trace_test"]`` when it passes
    (the previous record kept in its ``history``); exit status 0 when it passed."""
    from cdpr_algebra.homotopy.monodromy import load_instance
    from cdpr_algebra.homotopy.trace_test import TraceTestResult, compute_trace

    p0, X0, data = load_instance(path, fam)
    old = dict(data["meta"]["trace_test"])
    o = replace(options or TraceTestOptions(), eps=eps, polish_condition=0.0)
    t0 = time.perf_counter()
    if "W10" in old and old["seed"] == seed:
        q0, l = complex_from_record(old["q0"]), complex_from_record(old["l"])
        W10 = complex_from_record(old["W10"]).reshape(old["W10_count"], fam.n + 1)
        t = compute_trace(fam, p0, q0, l, X0, W10, o, seed=seed, coordinates=old["coordinates"])
        tr = TraceTestResult(trace=t, q0=q0, l=l, W10=W10, witnesses=old["witnesses"], seed=seed, seconds=0.0,
                             coordinates=np.asarray(old["coordinates"]))
        chart = old.get("chart")
    else:
        tr = verify_solution_completeness(fam, p0, X0, seed=seed, options=o, verbose=verbose,
                                          coordinates=coordinates, chart=chart)
    rec = trace_record(tr, len(X0), seed, chart, time.perf_counter() - t0)
    t = tr.trace
    print(f"m = {m}: trace test with eps = {eps}, every point refined: {t.status}, relative {t.relative:.1e}, "
          f"detection {t.detection:.1e} (separation {t.separation:.1e}; tol {t.tol:.0e}), {len(tr.W10)} witness "
          f"points, {rec['seconds']:.0f} s {t.reason}", flush=True)
    if t.status != "passed":
        return 1
    history = old.pop("history", []) + [{k: old[k] for k in ("status", "seed", "W10_count", "seconds")}
                                        | {"relative": old["trace"]["relative"], "detection": old["trace"]["detection"],
                                           "eps": old["trace"].get("eps")}]
    save_instance(path, fam, p0, X0, **{**data["meta"], "trace_test": {**rec, "history": history}})
    return 0


def record_phc(m: int, seed: int) -> int:
    from cdpr_algebra.homotopy.monodromy import load_instance

    p0, X0, data = load_instance(path_for(m), rod_family(m))
    rec = run_phc(m, seed)
    save_instance(path_for(m), rod_family(m), p0, X0, **{**data["meta"], "phc": rec})
    return 0 if phc_agrees(rec, len(X0)) else 1


def phc_agrees(rec: dict, count: int) -> bool:
    """Whether a PHCpack record (``run_phc``) found exactly the ``count`` stored solutions, matched both ways."""
    return rec.get("status") == "finished" and rec["phc_distinct"] == rec["stored_matched"] == rec["phc_matched"] \
        == rec["stored_moved_distinct"] == count


def monodromy_arguments(ap, ms) -> None:
    """The options every generic-set script shares: ``--m`` (choices ``ms``), ``--seed``, ``--no-progress``,
    ``--extra``."""
    ap.add_argument("--m", type=int, nargs="+", default=list(ms), choices=ms)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--no-progress", type=int, default=8, help="monodromy loops in a row that add nothing")
    ap.add_argument("--extra", type=int, default=3, help="extra monodromy loops that must find nothing new")


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    monodromy_arguments(ap, ROD_M)
    ap.add_argument("--chart", type=int, default=None, metavar="SEED",
                    help="find the trace test's witness points on a random chart of projective space (points of "
                         "very large norm are ordinary there)")
    ap.add_argument("--phc", action="store_true", help="record PHCpack's count next to the stored sets (only)")
    ap.add_argument("--retrace", type=float, default=None, metavar="EPS",
                    help="the trace test of the stored sets again, every point refined in arbitrary precision, the "
                         "pencil tracked to +-EPS (only)")
    args = ap.parse_args(argv)
    status = 0
    if args.phc:
        return max(record_phc(m, 7 + args.seed) for m in args.m)
    if args.retrace is not None:
        return max(retrace(path_for(m), rod_family(m), m, args.seed, args.retrace, args.chart) for m in args.m)
    for m in args.m:
        params, X, meta = solve_generic(m, seed=args.seed, no_progress=args.no_progress, extra=args.extra,
                                        chart=args.chart)
        status = max(status, store_if_certified(path_for(m), rod_family(m), params, X, meta))
    return status


def store_if_certified(path, system, params, X, meta) -> int:
    """Store the set (``save_instance``) when the extra loops found nothing new, its points are distinct and its
    trace test passed; print the verdict; exit status 0 when stored."""
    ok = (meta["check"]["new_solutions"] == 0 and meta["distinct"] == len(X)
          and meta["trace_test"]["status"] == "passed")
    print(f"m = {meta['m']}: {len(X)} solutions, residual {meta['max_residual']:.1e}, max cond "
          f"{meta['max_jacobian_condition']:.1e}, {meta['seconds']:.1f} s: {'stored' if ok else 'NOT stored'}",
          flush=True)
    if ok:
        save_instance(path, system, params, X, **meta)
    return 0 if ok else 1


if __name__ == "__main__":
    raise SystemExit(main())
