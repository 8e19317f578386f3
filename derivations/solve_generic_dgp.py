"""Compute and store the generic solution sets of the DGP families ``taut_family(m)`` (m = 2 .. 6).

Re-runnable, NOT a ``derive_*.py`` (monodromy is randomized and takes minutes, so it is not part of
tests/test_derivations.py):

    python derivations/solve_generic_dgp.py --m 2 3          # writes cdpr_algebra/data/dgp_generic_m{m}.json
    python derivations/solve_generic_dgp.py --rebase --m 3   # moves the stored set to a better start point
    python derivations/solve_generic_dgp.py --m 4 --near-regular 0.3   # monodromy directly near regular_robot

Method (see :mod:`cdpr_algebra.homotopy.monodromy`):

* seed point x0 = encode(p, R, lam) with R a random *complex* rotation (from a complex quaternion q,
  q.q = 1), so x0 satisfies the parameter-free rotation equations; the parameters are then found by
  minimum-norm Gauss-Newton from ``p_guess``, a robot of unit size (the scale :mod:`cdpr_algebra.dgp.solve`
  normalizes every robot to: base centred at the origin, lengths divided by the robot size, load 1)
  with the load along -z, plus complex noise, so parameter homotopies to real robots are short;
* monodromy loops until the published generic count (24, 156, 216, 140, 40 for m = 2 .. 6) is reached;
* check: ``--extra`` more loops (every known solution tracked around each) must find nothing new,
  and every stored solution must be nonsingular (Jacobian condition number reported).

``--rebase`` moves a stored set, by a gamma-trick parameter homotopy, to a new generic point close to the
robots the DGP meets (:func:`regular_robot`, a regular suspended robot of unit size, plus complex noise), keeping
the candidate (of ``--candidates``) whose solutions are all reached, distinct and nonsingular with the smallest
worst Jacobian condition number.  Parameter homotopies from a start point near real robots are much shorter
(seed 000 Test 1, 3 taut cables: median steps per path 119 -> about 45).

The JSON file (``save_instance``) records the system hash and format version, and in ``meta``: the
monodromy statistics (loops, paths, seconds, seed), the extra-loop check and the maximum residual.
"""

from __future__ import annotations

import argparse
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))

from cdpr_algebra.dgp.solve import fast_family  # noqa: E402
from cdpr_algebra.model.taut_equations import encode, taut_family  # noqa: E402
from cdpr_algebra.homotopy.monodromy import MonodromyOptions, monodromy_solve, save_instance  # noqa: E402

PUBLISHED = {2: 24, 3: 156, 4: 216, 5: 140, 6: 40}
DATA = ROOT / "cdpr_algebra" / "data"


def path_for(m: int) -> Path:
    return DATA / f"dgp_generic_m{m}.json"


def complex_rotation(rng) -> np.ndarray:
    q = rng.normal(size=4) + 1j * rng.normal(size=4)
    q = q / np.sqrt(q @ q)  # complex "unit" quaternion: q.q = 1 (no conjugation)
    a, b, c, d = q
    return np.array([[a * a + b * b - c * c - d * d, 2 * (b * c - a * d), 2 * (b * d + a * c)],
                     [2 * (b * c + a * d), a * a - b * b + c * c - d * d, 2 * (c * d - a * b)],
                     [2 * (b * d - a * c), 2 * (c * d + a * b), a * a - b * b - c * c + d * d]])


def unit_robot_guess(m: int, rng, noise: float = 0.3) -> np.ndarray:
    """Parameters of a unit-size robot (A_i, rho_i^2, b'_i, g', Q d) plus complex noise."""
    A = rng.uniform(-0.6, 0.6, size=(m, 3))
    r2 = rng.uniform(0.3, 1.0, size=m) ** 2
    b = rng.uniform(-0.15, 0.15, size=(m, 3))
    g = rng.uniform(-0.1, 0.1, size=3)
    f = np.array([0.0, 0.0, -1.0])
    p = np.concatenate([A.ravel(), r2, b.ravel(), g, f])
    return p + noise * (np.abs(p) + 0.1) * (rng.normal(size=p.size) + 1j * rng.normal(size=p.size))


def regular_robot(m: int) -> np.ndarray:
    """Parameters (A_i, rho_i^2, b'_i, g', Q d) of a regular suspended robot of unit size: exit points on a circle
    of radius 0.5 (heights alternating +-0.1), platform anchors on a circle of radius 0.12, cables of length 0.7,
    G slightly below the platform frame, load 1 along -z."""
    th = 2 * np.pi * np.arange(m) / m
    alt = (-1.0) ** np.arange(m)
    A = np.stack([0.5 * np.cos(th), 0.5 * np.sin(th), 0.1 * alt], axis=1)
    b = np.stack([0.12 * np.cos(th + 0.3), 0.12 * np.sin(th + 0.3), 0.03 * alt], axis=1)
    r2 = np.full(m, 0.7 ** 2)
    return np.concatenate([A.ravel(), r2, b.ravel(), [0.0, 0.0, -0.05], [0.0, 0.0, -1.0]])


def rebase(m: int, seed: int = 1, candidates: int = 4, noise: float = 0.1, verbose: bool = True):
    """Move the stored generic set of ``m`` to the best of ``candidates`` points regular_robot(m) + complex noise."""
    from cdpr_algebra.homotopy.clusters import duplicate_groups
    from cdpr_algebra.homotopy.endgame import SolveOptions
    from cdpr_algebra.homotopy.monodromy import load_instance
    from cdpr_algebra.homotopy.solve import solve_parameter_homotopy

    fam = fast_family(m)
    p_old, X_old, data = load_instance(path_for(m), taut_family(m))
    rng = np.random.default_rng(seed)
    base = regular_robot(m)
    best = None
    t0 = time.perf_counter()
    for k in range(candidates):
        pstar = base + noise * (np.abs(base) + 0.1) * (rng.normal(size=base.size) + 1j * rng.normal(size=base.size))
        res = solve_parameter_homotopy(fam, p_old, X_old, pstar, seed=seed + k, gamma=True,
                                       options=SolveOptions(retry_mpmath=False))
        X = np.array([p.endpoint for p in res.track.paths if p.status == "success"]).reshape(-1, fam.n)
        ok = len(X) == len(X_old) and not duplicate_groups(X, 1e-8)
        cond = float(np.max(np.linalg.cond(fam.evaluate_and_jacobian(X, pstar)[1]))) if len(X) else np.inf
        if verbose:
            print(f"m = {m}: candidate {k}: {len(X)} of {len(X_old)} reached, distinct: {ok}, max cond {cond:.1e}",
                  flush=True)
        if ok and (best is None or cond < best[2]):
            best = (pstar, X, cond, k)
    if best is None:
        return None
    pstar, X, cond, k = best
    resid = float(np.max(np.abs(taut_family(m).evaluate(X, pstar))))
    meta = dict(data["meta"])
    meta.update({"rebased": {"from_meta_seconds": data["meta"].get("seconds"), "seed": seed, "candidate": k,
                             "candidates": candidates, "noise": noise, "base": "regular_robot",
                             "seconds": time.perf_counter() - t0},
                 "max_residual": resid, "max_jacobian_condition": cond})
    return pstar, X, meta


def solve_generic(m: int, seed: int = 1, extra: int = 2, verbose: bool = True, near_regular: float | None = None):
    fam = fast_family(m)  # same equations as taut_family(m), faster vectorized evaluators
    rng = np.random.default_rng(seed)
    R = complex_rotation(rng)
    p = 0.3 * (rng.normal(size=3) + 1j * rng.normal(size=3))
    lam = rng.normal(size=m) + 1j * rng.normal(size=m)
    x0 = encode(p, R, lam)
    if near_regular is None:
        guess = unit_robot_guess(m, rng)
    else:  # the start point of --rebase, reached directly by monodromy
        base = regular_robot(m)
        guess = base + near_regular * (np.abs(base) + 0.1) * (rng.normal(size=base.size) + 1j * rng.normal(size=base.size))
    t0 = time.perf_counter()
    res = monodromy_solve(fam, seed=seed, x0=x0, p_guess=guess,
                          options=MonodromyOptions(target_solutions_count=PUBLISHED[m], max_loops=60))
    if verbose:
        print(f"m = {m}: {res.summary_line()}", flush=True)
    check = monodromy_solve(fam, parameters=res.parameters, solutions=res.solutions, seed=seed + 1000,
                            options=MonodromyOptions(max_loops_no_progress=extra, initial_loops=extra,
                                                     max_loops=extra))
    new = len(check.solutions) - len(res.solutions)
    if verbose:
        print(f"m = {m}: check with {check.loops} extra loops ({check.paths_tracked} paths): {new} new", flush=True)
    X = check.solutions
    F = taut_family(m).evaluate(X, res.parameters)
    resid = float(np.max(np.abs(F)))
    _, J, _ = fam.evaluate_all(X, res.parameters)
    cond = float(np.max(np.linalg.cond(J)))
    meta = {"m": m, "published_count": PUBLISHED[m], "monodromy": res.to_dict(),
            "check": {"extra_loops": check.loops, "paths_tracked": check.paths_tracked, "new_solutions": new,
                      "seconds": check.seconds},
            "max_residual": resid, "max_jacobian_condition": cond, "seconds": time.perf_counter() - t0,
            "scale": "unit-size robot: base centred at the origin, lengths / robot size, load Q d with Q = 1"}
    return res.parameters, X, meta


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--m", type=int, nargs="+", default=[2, 3], choices=sorted(PUBLISHED))
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--extra", type=int, default=2, help="extra monodromy loops that must find nothing new")
    ap.add_argument("--rebase", action="store_true", help="move the stored sets to a better start point")
    ap.add_argument("--near-regular", type=float, default=None, metavar="NOISE",
                    help="monodromy at a point near regular_robot(m) (relative complex noise NOISE)")
    ap.add_argument("--candidates", type=int, default=4)
    ap.add_argument("--noise", type=float, default=0.1, help="relative complex noise of the rebase candidates")
    args = ap.parse_args(argv)
    status = 0
    for m in args.m:
        if args.rebase:
            out = rebase(m, seed=args.seed, candidates=args.candidates, noise=args.noise)
            if out is None:
                print(f"m = {m}: no candidate kept every solution: NOT stored", flush=True)
                status = 1
                continue
            params, X, meta = out
            print(f"m = {m}: rebased, {len(X)} solutions, residual {meta['max_residual']:.1e}, max cond "
                  f"{meta['max_jacobian_condition']:.1e}: stored", flush=True)
            save_instance(path_for(m), taut_family(m), params, X, **meta)
            continue
        params, X, meta = solve_generic(m, seed=args.seed, extra=args.extra, near_regular=args.near_regular)
        if args.near_regular is not None:
            meta["start_point"] = {"base": "regular_robot", "noise": args.near_regular}
        ok = len(X) == PUBLISHED[m] and meta["check"]["new_solutions"] == 0
        print(f"m = {m}: {len(X)} solutions (published {PUBLISHED[m]}), residual {meta['max_residual']:.1e}, "
              f"max cond {meta['max_jacobian_condition']:.1e}, {meta['seconds']:.1f} s: "
              f"{'stored' if ok else 'NOT stored'}", flush=True)
        if ok:
            save_instance(path_for(m), taut_family(m), params, X, **meta)
        else:
            status = 1
    return status


if __name__ == "__main__":
    raise SystemExit(main())
