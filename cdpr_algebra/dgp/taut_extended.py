"""Failed paths tracked again from their start points in the taut system, every step in double-double.

Why.  A random robot's 4-cable set can have a conjugate pair of finite roots with |x| ~ 2e7 (thirty-sixth session:
``benchmarks/bench_random_robots.py`` seed 13, taut sets {1, 2, 5, 6} and {2, 3, 5, 6}; the size comes from the anchor
geometry alone: the same roots whatever the cable lengths within 10 %).  Their paths' Jacobians reach condition numbers
of 1e11 near t = 0.03 and double precision loses them in (p, u, v, w, lam) and in Study parameters (there the rotation
lies near N = e . e = 0), double-double included.  With every number in double-double (:mod:`.homotopy.dd_tracker`
over the generated :mod:`cdpr_algebra.generated.taut_equations_dd`) the same step control tracks them from t = 1 to
t = 0 in 1,800-2,600 steps (0.3-0.4 s a path); a double-precision run handed over to double-double where it fails
(:func:`.homotopy.hybrid_tracker.hybrid_track`) did not: its last point, at t ~ 0.03, is too far off the path.

What.  :func:`rescue_in_taut_extended` tracks each failed path (at most ``MAX_PATHS``) along the straight segment from
its start point, at most ``MAX_STEPS`` steps, with the step-size floor ``MIN_STEP``; an endpoint reached at t = 0
(the tracker's last Newton updates there contracting to the floor of double-double) is a candidate root, and
:func:`.unheld_roots.settle_on_found_roots` keeps the candidates that no settled path holds, distinct from each other
(the account of :mod:`.unheld_roots`: a regular root that no settled path holds is the limit of a failed path's branch,
whatever route found it), ``retried = "taut_extended"``.  A kept endpoint is regular only as a claim: the subproblem is
complete once the endpoint certificates prove it a root, unique in its box and distinct from the others (in ball
arithmetic where double precision cannot).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from cdpr_algebra.homotopy.results import FAILURES, SUCCESS

from .taut_system import fast_family
from .unheld_roots import settle_on_found_roots

__all__ = ["TAUT_EXTENDED", "MAX_PATHS", "MAX_STEPS", "MIN_STEP", "rescue_in_taut_extended"]

TAUT_EXTENDED = "taut_extended"  # the ``retried`` of a path settled here
MAX_PATHS = 8  # failed paths per run tracked here (a run with more is near a special robot: module doc of .solve)
MAX_STEPS = 6000  # double-double steps per path (measured: 1,760 and 2,599 for the two paths above)
MIN_STEP = 1e-14  # the step-size floor in s (the double tracker's 1e-13 stops those paths)


def rescue_in_taut_extended(m: int, res, start_parameters, start_solutions, target, options):
    """(``res``, a run of the taut system of m cables from ``start_solutions`` at ``start_parameters`` to ``target``,
    with its failed paths settled on roots reached in double-double (module doc), the number of failed paths left).
    ``options``: the run's SolveOptions (its tracker's tolerances; its endgame's cluster tolerance decides
    coincidence)."""
    from cdpr_algebra.generated.taut_equations_dd import taut_equations
    from cdpr_algebra.homotopy.dd_tracker import CORRECTOR_FLOOR, DoubleDoubleParameterHomotopy
    from cdpr_algebra.homotopy.homotopies import ParameterHomotopy
    from cdpr_algebra.homotopy.refinement import relative_residual

    failed = [i for i, p in enumerate(res.track.paths) if p.status in FAILURES]
    if not failed:
        return res, 0
    system = fast_family(m)
    homotopy = ParameterHomotopy(system, start_parameters, target)
    precise = DoubleDoubleParameterHomotopy.like(homotopy, taut_equations)
    tracker = replace(options.tracker, min_step=MIN_STEP)
    X0 = np.asarray(start_solutions, dtype=complex)
    found, steps = [], {}
    for i in failed[:MAX_PATHS]:
        seg = precise.track(X0[i], 1.0, 0.0, tracker, MAX_STEPS)  # path i starts at start solution i
        steps[i] = seg.steps
        if seg.status == SUCCESS and np.all(np.isfinite(seg.x)):
            found.append(seg.x)
    if found:
        X = np.array(found)
        F, J = system.evaluate_and_jacobian(X, target)
        with np.errstate(all="ignore"):
            residual = relative_residual(F, X)
            condition = np.linalg.cond(J)
        found = [dict(endpoint=x, residual=float(r), condition=float(c),
                      accuracy=float(CORRECTOR_FLOOR * (1 + np.max(np.abs(x)))), retried=TAUT_EXTENDED)
                 for x, r, c in zip(X, residual, condition)]
    paths = list(res.track.paths)
    for i, k in steps.items():
        paths[i] = replace(paths[i], steps=paths[i].steps + k)
    res = replace(res, track=replace(res.track, paths=tuple(paths)))
    return settle_on_found_roots(res, found, options)
