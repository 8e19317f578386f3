"""Compute, certify and store the generic solution set of the 4-cable taut system for two parallelograms.

Re-runnable, NOT a ``derive_*.py`` (monodromy and the trace test are randomized and take minutes):

    python derivations/solve_generic_parallelogram.py            # writes cdpr_algebra/data/parallelogram_generic_m4.json
    python derivations/solve_generic_parallelogram.py --kind off_centre   # parallelogram_offcentre_generic_m4.json

``--kind off_centre`` (G not at the centre of the platform anchors' parallelogram, g' free): the same method and
relations without g' = 0 (:mod:`cdpr_algebra.dgp.parallelogram`); the seed point's G is (0.03, -0.02, -0.15) plus
the noise.  ``--kind squares`` (two squares, G off their centre): the seed point's squares are those of
:func:`square_robot`.  ``--kind squares_axis`` (G on the plate's axis): its seed root is moved from the squares set
(:func:`seed_from_squares`); its trace test did not decide (README), so no set is stored.  Their records are in the
files' ``meta``.  The rest of this text is about the centred kind.

Why.  When the four exit points A_1 .. A_4 of a taut set are a parallelogram (A_1 + A_3 = A_2 + A_4) and the four
platform anchors are a parallelogram centred on the centre of mass (b'_1 + b'_3 = b'_2 + b'_4 = 2 g'), in the
same order, the taut system of four cables (:func:`cdpr_algebra.model.taut_equations.taut_family`) is a special
member of its family: of its 216 generic solutions, only 152 stay finite (measured, thirty-fifth session: a
rectangular frame with a flat plate whose G is at its centre, G lowered by eps = 0.2, 0.01, 0.001: 184, 182, 160
regular roots, the largest growing like a negative power of eps).  The most common suspended robot is such a robot
(a rectangular frame's four top corners, a flat rectangular platform with G at its centre), and a parameter
homotopy from the generic set leaves 40 of its paths failed there (``examples/symmetric_4cables.toml`` with G at the
plate's centre).  In the normalized problem (:func:`cdpr_algebra.dgp.normalization.normalized_problem`: base centred
at the exit points' centroid, platform frame at its anchors' centroid) the subfamily is linear: A_1 + A_3 = 0,
A_2 + A_4 = 0, b'_1 + b'_3 = 0, b'_2 + b'_4 = 0 and g' = 0 (:func:`parallelogram_relations`); its own generic solution
set has only the paths that stay finite there (:mod:`cdpr_algebra.dgp.parallelogram`, which defines the subfamily).

Method (the collinear anchors' method, :mod:`solve_generic_collinear`, with the subfamily given by linear relations:
``MonodromyOptions.parameter_relations``):

* seed point: random complex (p, R, lam) with R a complex rotation; the parameters by minimum-norm Gauss-Newton
  inside the subfamily from :func:`rectangle_robot` plus complex noise in the subfamily;
* monodromy loops inside the subfamily with NO target count, until ``--no-progress`` consecutive loops add nothing;
  then ``--extra`` more loops with every known solution tracked around each must add nothing (recorded);
* the trace test on a curve inside the subfamily, in the 12 pose unknowns, every point refined in arbitrary
  precision before the sums, recorded in ``meta["trace_test"]`` with q0, l and W10; a set whose trace test does not
  pass (separation included) is NOT stored (exit status 1); ``--keep FILE`` writes the set and its record (W10
  included) to FILE either way.

Recorded (thirty-fifth session, ``--seed 2 --no-progress 12 --eps 4``): 152 solutions (14 loops, none new in 3 more);
trace test with |W10| = 1160 in the pose unknowns, relative trace 2.6e-15, smallest single-point signal 4.3e-13:
separation 160, passed (15 min).  At eps = 1 the same W10 gave a trace of 1.8e-14 and a smallest signal of 1.0e-13,
separation 5.9: undecided (not stored).  Seed 1's instance (with 8 loops without progress as the stopping rule) held
only 78 solutions, 40 loops did not add any, and the 152 of seed 2 moved there ended 78 there (the same points), 71
at infinity, 2 singular, 1 failed: that seed point had landed on a special member of the subfamily.  Seeds 2 and 3
give 152, and the generic route's certified roots of the flat plate (a member) are 152 distinct points.
PHCpack (``--phc --seed 2``: blackbox on a random complex member, seed 9): mixed volume 5760, 152 regular solutions,
all with every lam_i nonzero, matched both ways with the stored set moved there (28 min); recorded in
``meta["phc"]``.
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

from cdpr_algebra.dgp.parallelogram import (KINDS, PARALLELOGRAM_M, fixed_parameters,  # noqa: E402
                                            parallelogram_path, parallelogram_relations)
from cdpr_algebra.dgp.solve import fast_family  # noqa: E402
from cdpr_algebra.homotopy.monodromy import (MonodromyOptions, monodromy_solve, save_instance,  # noqa: E402
                                             subfamily_point)
from cdpr_algebra.homotopy.trace_test import verify_solution_completeness  # noqa: E402
from cdpr_algebra.model.taut_equations import encode, taut_family  # noqa: E402
from certify_generic_dgp import POSE, trace_options  # noqa: E402
from solve_generic_dgp import complex_rotation  # noqa: E402
from solve_generic_rod import (extra_loop_check, monodromy_arguments, phc_agrees, store_if_certified,  # noqa: E402
                               trace_record)

M = PARALLELOGRAM_M
OFF_CENTRE_G = (0.03, -0.02, -0.15)


def rectangle_robot(m: int = M, kind: str = "centred") -> np.ndarray:
    """Parameters of a unit-size robot in the subfamily: exit points (+-0.5, +-0.35, 0) of a rectangle, a plate
    (+-0.12, +-0.08, 0) with G at its centre (``OFF_CENTRE_G`` for the off-centre kind), in the same order, cables of
    length 0.7, load 1 along -z."""
    if kind.startswith("squares"):
        return square_robot(m, kind)
    A = np.array([[-0.5, -0.35, 0.0], [0.5, -0.35, 0.0], [0.5, 0.35, 0.0], [-0.5, 0.35, 0.0]])
    b = np.array([[-0.12, -0.08, 0.0], [0.12, -0.08, 0.0], [0.12, 0.08, 0.0], [-0.12, 0.08, 0.0]])
    g = np.zeros(3) if kind == "centred" else np.array(OFF_CENTRE_G)
    return np.concatenate([A.ravel(), np.full(m, 0.7 ** 2), b.ravel(), g, [0.0, 0.0, -1.0]])


def square_robot(m: int = M, kind: str = "squares") -> np.ndarray:
    """Parameters of a unit-size robot with two squares, counter-clockwise about z: exit points a, Rot90 a, -a,
    -Rot90 a with a = (0.5, 0.1, 0), platform anchors likewise with (0.12, 0.05, 0), G at ``OFF_CENTRE_G`` (for
    ``squares_axis`` on the axis, (0, 0, -0.15)), cables of length 0.7, load 1 along -z."""
    def square(x, y):
        return np.array([[x, y, 0.0], [-y, x, 0.0], [-x, -y, 0.0], [y, -x, 0.0]])

    g = (0.0, 0.0, OFF_CENTRE_G[2]) if kind == "squares_axis" else OFF_CENTRE_G
    return np.concatenate([square(0.5, 0.1).ravel(), np.full(m, 0.7 ** 2), square(0.12, 0.05).ravel(),
                           g, [0.0, 0.0, -1.0]])


def rectangle_member(rng, noise: float = 0.3, kind: str = "centred") -> np.ndarray:
    """:func:`rectangle_robot` plus relative complex noise inside the subfamily: a random complex member."""
    p = rectangle_robot(kind=kind)
    z = noise * (np.abs(p) + 0.1) * (rng.normal(size=p.size) + 1j * rng.normal(size=p.size))
    return subfamily_point(p, z, fixed_parameters(kind=kind), parallelogram_relations(kind=kind))


def seed_from_squares(p, seed: int) -> np.ndarray:
    """The finite regular roots at the member ``p`` of the squares-with-G-on-the-axis subfamily, tracked from the
    stored squares set (its superfamily: G anywhere), a seed point for the monodromy there (its members have too few
    free parameters, 9 for 10 equations, for :func:`seed_instance` to fit them to a random point)."""
    from cdpr_algebra.dgp.parallelogram import parallelogram_start
    from cdpr_algebra.homotopy.many_targets import solve_targets

    p0, X0 = parallelogram_start("squares")
    (res,) = solve_targets(fast_family(M), p0, X0, [p], seed=seed)
    return np.array([s.x for s in res.solutions if not s.singular])


def solve_generic(seed: int = 1, no_progress: int = 8, extra: int = 3, noise: float = 0.3, verbose: bool = True,
                  eps: float | None = None, coordinates=POSE, kind: str = "centred"):
    fam = fast_family(M)
    fixed, rel = fixed_parameters(kind=kind), parallelogram_relations(kind=kind)
    rng = np.random.default_rng(seed)
    x0 = encode(0.3 * (rng.normal(size=3) + 1j * rng.normal(size=3)), complex_rotation(rng),
                rng.normal(size=M) + 1j * rng.normal(size=M))
    guess = rectangle_member(rng, noise, kind)
    t0 = time.perf_counter()
    known = {}
    if kind == "squares_axis":  # too few free parameters to fit a random point: one root moved from the squares set
        known = dict(parameters=guess, solutions=seed_from_squares(guess, seed)[:1])
        x0 = guess = None
    res = monodromy_solve(fam, seed=seed, x0=x0, p_guess=guess, **known,
                          options=MonodromyOptions(max_loops_no_progress=no_progress, max_loops=120,
                                                   fixed_parameters=fixed, parameter_relations=rel))
    if verbose:
        print(f"m = {M}: {res.summary_line()}", flush=True)
    check, X, new, distinct = extra_loop_check(fam, res, M, seed, extra, fixed, verbose, rel)
    F, J = fam.evaluate_and_jacobian(X, res.parameters)
    meta = {"m": M, "subfamily": "exit points and platform anchors parallelograms with the same diagonals (cables 1, 3 "
                                 "and 2, 4), the anchors' centred on G: A_1 + A_3 = A_2 + A_4 = 0, b'_1 + b'_3 = "
                                 "b'_2 + b'_4 = 0, g' = 0" if kind == "centred" else
                         "exit points and platform anchors parallelograms with the same diagonals (cables 1, 3 and 2, "
                         "4), G anywhere: A_1 + A_3 = A_2 + A_4 = 0, b'_1 + b'_3 = b'_2 + b'_4 = 0" + (
                             "; both squares: A_2 = Rot90(A_1), b'_2 = Rot90(b'_1) about z, A_iz = b'_iz = 0, "
                             "Q d = (0, 0, -1)" if kind.startswith("squares") else "") + (
                             "; G on the axis: g'_x = g'_y = 0" if kind == "squares_axis" else ""), "kind": kind,
            "fixed_parameters": [int(k) for k in fixed], "parameter_relations": [list(map(list, r)) for r in rel],
            "monodromy": res.to_dict(),
            "check": {"extra_loops": check.loops, "paths_tracked": check.paths_tracked, "new_solutions": new,
                      "seconds": check.seconds},
            "distinct": distinct, "max_residual": float(np.max(np.abs(F))),
            "max_jacobian_condition": float(np.max(np.linalg.cond(J))),
            "max_norm": float(np.max(np.abs(X))), "start_point": {"base": "rectangle_robot", "noise": noise,
                                                                  "g": list(rectangle_robot(kind=kind)[28:31])},
            "scale": "unit-size robot: base centred at the origin, lengths / robot size, load Q d with Q = 1"}
    t1 = time.perf_counter()
    o = replace(trace_options(), fixed_parameters=fixed, parameter_relations=rel, polish_condition=0.0)
    o = o if eps is None else replace(o, eps=eps)
    tr = verify_solution_completeness(fam, res.parameters, X, seed=seed, options=o, verbose=verbose,
                                      coordinates=coordinates)
    meta["trace_test"] = trace_record(tr, len(X), seed, None, time.perf_counter() - t1)
    meta["seconds"] = time.perf_counter() - t0
    if verbose:
        t = tr.trace
        print(f"m = {M}: trace test {t.status}: |W10| = {len(tr.W10)}, relative {t.relative:.1e}, detection "
              f"{t.detection:.1e} (separation {t.separation:.1e}, tol {t.tol:.0e}), {meta['trace_test']['seconds']:.0f}"
              f" s {t.reason}", flush=True)
    return res.parameters, X, meta


def run_phc(seed: int = 9, timeout: float = 7200, verbose: bool = True, kind: str = "centred") -> dict:
    """PHCpack's blackbox count on a random complex member of the subfamily (the rectangle robot plus complex noise
    inside it), matched with the stored set moved there (:func:`solve_generic_collinear.phc_count_at`)."""
    from cdpr_algebra.homotopy.monodromy import load_instance
    from solve_generic_collinear import phc_count_at

    p0, X0, _ = load_instance(parallelogram_path(kind), taut_family(M))
    p = rectangle_member(np.random.default_rng(seed), kind=kind)
    return phc_count_at(M, p0, X0, p, seed, timeout, "parallelogram_instance", verbose)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    monodromy_arguments(ap, (M,))
    ap.add_argument("--noise", type=float, default=0.3, help="relative complex noise of the start point")
    ap.add_argument("--eps", type=float, default=None, help="the trace test's pencil to +-EPS (default: trace_options)")
    ap.add_argument("--all-coordinates", action="store_true",
                    help="the trace test in every unknown (default: the 12 pose unknowns)")
    ap.add_argument("--keep", type=Path, default=None, metavar="FILE",
                    help="also write the set and its record to FILE, stored or not (its W10 for a later trace)")
    ap.add_argument("--phc", action="store_true", help="record PHCpack's count next to the stored set (only)")
    ap.add_argument("--kind", choices=KINDS, default="centred", help="the subfamily (default: centred)")
    args = ap.parse_args(argv)
    path = parallelogram_path(args.kind)
    if args.phc:
        from cdpr_algebra.homotopy.monodromy import load_instance

        rec = run_phc(7 + args.seed, kind=args.kind)
        p0, X0, data = load_instance(path, taut_family(M))  # read after the run: the record is added to the latest
        save_instance(path, taut_family(M), p0, X0, **{**data["meta"], "phc": rec})
        return 0 if phc_agrees(rec, len(X0)) else 1
    params, X, meta = solve_generic(seed=args.seed, no_progress=args.no_progress, extra=args.extra, noise=args.noise,
                                    eps=args.eps, coordinates=None if args.all_coordinates else POSE, kind=args.kind)
    print(f"m = {M}: largest solution norm {meta['max_norm']:.1e}", flush=True)
    if args.keep is not None:
        save_instance(args.keep, taut_family(M), params, X, **meta)
    return store_if_certified(path, taut_family(M), params, X, meta)


if __name__ == "__main__":
    raise SystemExit(main())
