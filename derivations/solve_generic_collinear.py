"""Compute, certify and store the generic solution sets of the taut system for collinear platform anchors.

Re-runnable, NOT a ``derive_*.py`` (monodromy and the trace test are randomized and take minutes):

    python derivations/solve_generic_collinear.py --m 3 4 5     # writes cdpr_algebra/data/collinear_generic_m{m}.json
    python derivations/solve_generic_collinear.py --m 5 --phc   # PHCpack's count recorded next to the stored set

Why.  When the platform anchors of m >= 3 taut cables lie on one line and the centre of mass G does not, the
platform's turn about that line is fixed by gravity alone, and the taut system of m cables
(:func:`cdpr_algebra.model.taut_equations.taut_family`) is a special member of its family: most of the generic
solutions (156, 216, 140 for m = 3, 4, 5) leave to infinity, along complex rotations about the line whose entries
grow without bound (isotropic directions).  A parameter homotopy from the generic set follows them there, and the
endgame cannot always decide them (measured, twenty-sixth session: the beam of ``examples/beam_4cables.toml`` with
G 0.25 below its line, 2, 2 and 7 paths failed "step too small" at |x| ~ 6e5).  The anchors on the line
b'_i = (s_i, 0, 0) (the platform frame turned so that the line is its x axis) are a linear subfamily of the
parameters; its own generic solution set, tracked from a start point inside the subfamily, has only the paths
that stay finite there.

Method (the rod sets' method, :mod:`solve_generic_rod`):

* seed point: random complex (p, R, lam) with R a complex rotation; the parameters by minimum-norm Gauss-Newton
  from :func:`regular_collinear_robot` plus complex noise on the parameters that are free in the subfamily
  (every parameter but the anchors' y and z, which stay 0: ``MonodromyOptions.fixed_parameters``);
* monodromy loops inside the subfamily with NO target count, until ``--no-progress`` consecutive loops add nothing;
  then ``--extra`` more loops with every known solution tracked around each must add nothing (recorded);
* the trace test (:func:`cdpr_algebra.homotopy.trace_test.verify_solution_completeness`) on a curve inside the
  subfamily (``TraceTestOptions.fixed_parameters``), in the 12 pose unknowns, recorded in ``meta["trace_test"]``;
  a set whose trace test does not pass is NOT stored (exit status 1);
* ``--phc`` (where ``phc`` is installed): PHCpack's blackbox ``phc -b`` on a new random complex member of the
  subfamily, its regular solutions with every lam_i nonzero de-duplicated, and the stored set moved there by a
  gamma-trick parameter homotopies (a gamma route stays on the complex line through two members, so inside the
  subfamily; up to 4 routes combined as sets) and matched both ways; recorded in ``meta["phc"]``, earlier runs in
  ``meta["phc_history"]`` (PHCpack's blackbox is randomized).

Recorded (twenty-seventh session): m = 3, 4, 5: 76, 56 and 16 solutions (seeds 1, 2, 1; m = 4 from
:func:`random_collinear_robot`, ``--base random --seed 2``: from the regular robot its set had condition numbers up to
1e10 and a pencil path was lost in every attempt, trace undecided); trace tests passed with |W10| = 724, 620, 224,
relative traces 4.1e-12, 2.2e-12, 6.8e-13 and single-point detections 2.9e-11, 1.1e-7, 5.9e-7 (m = 3 separated
weakly, 6.9 times its trace; re-recorded in the thirty-fifth session with every point refined in arbitrary
precision, ``--retrace 1.0 --m 3``: relative trace 1.5e-15, the same 724 witness points, separation 1.9e4, 51 min).
PHCpack: m = 3, mixed volume 672, 75 and then
76 regular solutions in two runs, all among the stored set moved there; m = 5, mixed volume 128, 16; m = 4
(twenty-eighth session), mixed volume 448, 56 in 116 s, matched both ways.
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
sys.path.insert(0, str(ROOT / "derivations"))

from cdpr_algebra.dgp.collinear_anchors import COLLINEAR_M, collinear_path, fixed_parameters  # noqa: E402
from cdpr_algebra.dgp.solve import fast_family  # noqa: E402
from cdpr_algebra.homotopy.monodromy import MonodromyOptions, monodromy_solve, save_instance  # noqa: E402
from cdpr_algebra.homotopy.trace_test import distinct_points, verify_solution_completeness  # noqa: E402
from cdpr_algebra.model.taut_equations import encode, taut_family  # noqa: E402
from certify_generic_dgp import POSE, _move_stored, trace_options  # noqa: E402
from solve_generic_dgp import complex_rotation  # noqa: E402
from solve_generic_rod import (extra_loop_check, monodromy_arguments, phc_agrees, retrace,  # noqa: E402
                              store_if_certified, trace_record)


def regular_collinear_robot(m: int) -> np.ndarray:
    """Parameters (A_i, rho_i^2, b'_i, g', Q d) of a regular suspended robot of unit size whose platform anchors lie
    on the x axis (s_i evenly spread in [-0.15, 0.15]) and whose centre of mass is 0.05 below it: exit points on a
    circle of radius 0.5 (heights alternating +-0.1), cables of length 0.7, load 1 along -z."""
    th = 2 * np.pi * np.arange(m) / m
    alt = (-1.0) ** np.arange(m)
    A = np.stack([0.5 * np.cos(th), 0.5 * np.sin(th), 0.1 * alt], axis=1)
    b = np.zeros((m, 3))
    b[:, 0] = np.linspace(-0.15, 0.15, m)
    return np.concatenate([A.ravel(), np.full(m, 0.7 ** 2), b.ravel(), [0.0, 0.0, -0.05], [0.0, 0.0, -1.0]])


def random_collinear_robot(m: int, rng) -> np.ndarray:
    """Parameters of a random unit-size robot with its platform anchors on the x axis: exit points in [-0.6, 0.6]^3,
    lengths 0.55-1, s_i in [-0.15, 0.15], G at (0.02, 0.03, -0.08), load 1 along -z (no symmetry: m = 4 from
    :func:`regular_collinear_robot` gave a set with condition numbers up to 1e10 whose trace test was undecided)."""
    A = rng.uniform(-0.6, 0.6, size=(m, 3))
    r2 = rng.uniform(0.55, 1.0, size=m) ** 2
    b = np.zeros((m, 3))
    b[:, 0] = rng.uniform(-0.15, 0.15, size=m)
    return np.concatenate([A.ravel(), r2, b.ravel(), [0.02, 0.03, -0.08], [0.0, 0.0, -1.0]])


def noisy(p: np.ndarray, fixed, rng, noise: float) -> np.ndarray:
    """p plus relative complex noise on the parameters that are free in the subfamily."""
    z = rng.normal(size=p.size) + 1j * rng.normal(size=p.size)
    z[list(fixed)] = 0.0
    return p + noise * (np.abs(p) + 0.1) * z


def solve_generic(m: int, seed: int = 1, no_progress: int = 8, extra: int = 3, noise: float = 0.3,
                  verbose: bool = True, chart: int | None = None, base: str = "regular"):
    fam = fast_family(m)
    fixed = fixed_parameters(m)
    rng = np.random.default_rng(seed)
    x0 = encode(0.3 * (rng.normal(size=3) + 1j * rng.normal(size=3)), complex_rotation(rng),
                rng.normal(size=m) + 1j * rng.normal(size=m))
    t0 = time.perf_counter()
    robot = regular_collinear_robot(m) if base == "regular" else random_collinear_robot(m, rng)
    res = monodromy_solve(fam, seed=seed, x0=x0, p_guess=noisy(robot, fixed, rng, noise),
                          options=MonodromyOptions(max_loops_no_progress=no_progress, max_loops=120,
                                                   fixed_parameters=fixed))
    if verbose:
        print(f"m = {m}: {res.summary_line()}", flush=True)
    check, X, new, distinct = extra_loop_check(fam, res, m, seed, extra, fixed, verbose)
    F, J = fam.evaluate_and_jacobian(X, res.parameters)
    meta = {"m": m, "subfamily": "platform anchors on the x axis: b'_iy = b'_iz = 0 (fixed_parameters)",
            "fixed_parameters": [int(k) for k in fixed], "monodromy": res.to_dict(),
            "check": {"extra_loops": check.loops, "paths_tracked": check.paths_tracked, "new_solutions": new,
                      "seconds": check.seconds},
            "distinct": distinct, "max_residual": float(np.max(np.abs(F))),
            "max_jacobian_condition": float(np.max(np.linalg.cond(J))),
            "max_norm": float(np.max(np.abs(X))), "start_point": {"base": f"{base}_collinear_robot", "noise": noise},
            "scale": "unit-size robot: base centred at the origin, lengths / robot size, load Q d with Q = 1"}
    t1 = time.perf_counter()
    tr = verify_solution_completeness(fam, res.parameters, X, seed=seed,
                                      options=replace(trace_options(), fixed_parameters=fixed), verbose=verbose,
                                      coordinates=POSE, chart=chart)
    meta["trace_test"] = trace_record(tr, len(X), seed, chart, time.perf_counter() - t1)
    meta["seconds"] = time.perf_counter() - t0
    if verbose:
        t = tr.trace
        print(f"m = {m}: trace test {t.status}: |W10| = {len(tr.W10)}, relative {t.relative:.1e}, detection "
              f"{t.detection:.1e} (tol {t.tol:.0e}), {meta['trace_test']['seconds']:.0f} s", flush=True)
    return res.parameters, X, meta


def run_phc(m: int, seed: int = 7, timeout: float = 3600, verbose: bool = True) -> dict:
    """PHCpack's count on a random complex member of the subfamily, matched with the stored set moved there."""
    from cdpr_algebra.homotopy.monodromy import load_instance

    p0, X0, _ = load_instance(collinear_path(m), taut_family(m))
    p = noisy(regular_collinear_robot(m), fixed_parameters(m), np.random.default_rng(seed), 0.3)
    return phc_count_at(m, p0, X0, p, seed, timeout, "collinear_instance", verbose)


def phc_count_at(m: int, p0, X0, p, seed: int, timeout: float, name: str, verbose: bool = True) -> dict:
    """PHCpack's blackbox on the taut system of m cables at the complex parameters p (a member of a subfamily), its
    regular solutions with every lam_i nonzero de-duplicated and matched both ways with the stored set X0 (at p0)
    moved to p; the record of ``meta["phc"]``."""
    import sympy as sp

    sys.path.insert(0, str(ROOT / "benchmarks"))
    from bench_homotopy import phc_run  # noqa: E402
    from cdpr_algebra.homotopy.systems import PolynomialSystem

    fam = taut_family(m)
    sub = {v: sp.Float(z.real, 17) + sp.Float(z.imag, 17) * sp.I for v, z in zip(fam.parameters, p)}
    inst = PolynomialSystem([sp.expand(e.xreplace(sub)) for e in fam.equations], fam.variables, (), name)
    res = phc_run(inst, np.zeros(0), timeout=timeout)
    if res is None or res["timeout"]:
        return {"status": "phc not installed" if res is None else "timeout", "seed": seed}
    S = np.asarray(res["solutions"], dtype=complex).reshape(-1, fam.n)
    lam_zero = np.any(np.abs(S[:, 12:]) <= 1e-8 * (1 + np.max(np.abs(S), axis=1))[:, None], axis=1)
    P, _ = distinct_points(fam, p, S[~lam_zero])
    # moved by up to 4 gamma-trick runs combined as sets (certify_generic_dgp._move_stored; measured, m = 5: one
    # run reached 14 of the 16, and arbitrary-precision retries of its lost paths ran for more than half an hour)
    Y, moves = _move_stored(m, p0, X0, p, seed)
    d = np.max(np.abs(Y[:, None, :] - P[None, :, :]), axis=2) if len(Y) and len(P) else np.zeros((len(Y), len(P)))
    close = d <= 1e-6 * (1 + np.max(np.abs(Y), axis=1))[:, None]
    out = {"status": "finished", "seed": seed, "wall_seconds": res["wall"], "mixed_volume": res["paths"],
           "regular": int(len(S)), "regular_some_lam_zero": int(lam_zero.sum()), "phc_distinct": int(len(P)),
           "stored": int(len(X0)), "stored_moved_distinct": int(len(Y)), "moves": moves,
           "stored_matched": int(close.any(axis=1).sum()), "phc_matched": int(close.any(axis=0).sum())}
    if verbose:
        print(f"m = {m}: PHCpack {out['phc_distinct']} distinct regular solutions with every lam_i nonzero (mixed "
              f"volume {out['mixed_volume']}, {res['wall']:.0f} s); stored {len(X0)} moved there: {len(Y)} distinct, "
              f"{out['stored_matched']} match a PHCpack solution, {out['phc_matched']} of PHCpack's matched",
              flush=True)
    return out


def record_phc(m: int, seed: int) -> int:
    from cdpr_algebra.homotopy.monodromy import load_instance

    p0, X0, data = load_instance(collinear_path(m), taut_family(m))
    rec = run_phc(m, seed)
    meta = dict(data["meta"])
    if "phc" in meta:  # PHCpack's blackbox is randomized (its gamma): every run is kept, the last one as "phc"
        meta["phc_history"] = meta.get("phc_history", []) + [meta["phc"]]
    save_instance(collinear_path(m), taut_family(m), p0, X0, **{**meta, "phc": rec})
    return 0 if phc_agrees(rec, len(X0)) else 1


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    monodromy_arguments(ap, COLLINEAR_M)
    ap.add_argument("--noise", type=float, default=0.3, help="relative complex noise of the start point")
    ap.add_argument("--base", choices=("regular", "random"), default="regular",
                    help="the start point: regular_collinear_robot or random_collinear_robot, plus noise")
    ap.add_argument("--chart", type=int, default=None, metavar="SEED",
                    help="find the trace test's witness points on a random chart of projective space")
    ap.add_argument("--phc", action="store_true", help="record PHCpack's count next to the stored sets (only)")
    ap.add_argument("--retrace", type=float, default=None, metavar="EPS",
                    help="the trace test of the stored sets again, every point refined in arbitrary precision, the "
                         "pencil tracked to +-EPS (only)")
    args = ap.parse_args(argv)
    if args.phc:
        return max(record_phc(m, 7 + args.seed) for m in args.m)
    if args.retrace is not None:
        return max(retrace(collinear_path(m), taut_family(m), m, args.seed, args.retrace, args.chart, POSE,
                           replace(trace_options(), fixed_parameters=fixed_parameters(m))) for m in args.m)
    status = 0
    for m in args.m:
        params, X, meta = solve_generic(m, seed=args.seed, no_progress=args.no_progress, extra=args.extra,
                                        noise=args.noise, chart=args.chart,
                                        base=args.base)
        print(f"m = {m}: largest solution norm {meta['max_norm']:.1e}", flush=True)
        status = max(status, store_if_certified(collinear_path(m), taut_family(m), params, X, meta))
    return status


if __name__ == "__main__":
    raise SystemExit(main())
