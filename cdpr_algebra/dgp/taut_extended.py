"""Failed paths tracked again from their start points in the taut system, every step in double-double.

Why.  A random robot's 4-cable set can have a conjugate pair of finite roots with |x| ~ 2e7 (thirty-sixth session:
``benchmarks/bench_random_robots.py`` seed 13, taut sets {1, 2, 5, 6} and {2, 3, 5, 6}; the size comes from the anchor
geometry alone: the same roots whatever the cable lengths within 10 %).  Their paths' Jacobians reach condition numbers
of 1e11 near t = 0.03 and double precision loses them in (p, u, v, w, lam) and in Study parameters (there the rotation
lies near N = e . e = 0), double-double included.  With every number in double-double (:mod:`.homotopy.dd_tracker`
over the generated :mod:`cdpr_algebra.generated.taut_equations_dd`) the same step control tracks them from t = 1 to
t = 0 in 1,800-2,600 steps (0.3-0.4 s a path); a double-precision run handed over to double-double where it fails
(:func:`.homotopy.hybrid_tracker.hybrid_track`) did not: its last point, at t ~ 0.03, is too far off the path.

Larger roots need more.  Two random robots' sets (seed 85's {1, 2, 4}, seed 13's {2, 3, 5, 6}) have conjugate pairs
with |x| = 5.9e8 and 3.8e9.  With the run's predictor tolerance (3e-4 relative to 1 + max |x|, which lets the small
unknowns lam ~ 0.01 move by far more than themselves once |x| ~ 1e8) their double-double tracks stop at t ~ 3e-3,
and so does python-flint at 212 bits; with 3e-5 the first pair is reached (13,000-15,000 steps, 2 s a path), with
3e-6 the second comes within t ~ 3e-7 of the end, where python-flint at 212 bits finishes in 4 steps.

What.  :func:`rescue_in_taut_extended` tracks each failed path (at most ``MAX_PATHS``) along the straight segment from
its start point, at most ``MAX_STEPS[0]`` steps, with the step-size floor ``MIN_STEP``; then, while at most
``TIGHT_MAX_PATHS`` are left, with each predictor tolerance of ``TIGHTER`` in turn, those whose last track stopped by
``step_too_small`` (a track out of steps only crawls: measured, a 3-cable robot of ``tests/test_dgp_round_trips.py``,
two paths at t ~ 0.03 with |x| ~ 1e8 still growing, 14 s of tighter tracks that reached nothing); a track that
stops within ``TAIL_T`` of t = 0 goes on there in python-flint (``TAIL_BITS``, at most ``TAIL_STEPS`` steps).  An
endpoint reached at t = 0 (the tracker's last Newton updates there contracting to its precision's floor) is a
candidate root; it is kept only where the ball Krawczyk test of the endpoint certificates proves a root within
``BALL_MAX_MOVE`` of it, per unknown (:func:`proven_in_balls`).  Why: the trackers measure every update relative to
1 + max |x|, so near a point at infinity with |x| ~ 5e14 a track can end "converged" at t = 0 while the unknowns of
size 1 are anywhere (measured, thirty-seventh session: a square frame with a square plate, G on its axis, taut set
{1, 2, 3}: such an endpoint, relative residual 0.12 at the rounding floor of its size, Newton quadratic in double
precision; Newton at 128 bits moves it by more than half of itself; it was kept as a regular endpoint that the
certificates then refused, the subproblem incomplete with no failed path).  Then
:func:`.unheld_roots.settle_on_found_roots` keeps the candidates that no settled path holds, distinct from each other
(the account of :mod:`.unheld_roots`: a regular root that no settled path holds is the limit of a failed path's branch,
whatever route found it), ``retried = "taut_extended"``.  A kept endpoint is regular only as a claim: the subproblem is
complete once the endpoint certificates prove it a root, unique in its box and distinct from the others (in ball
arithmetic where double precision cannot).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from cdpr_algebra.homotopy.results import FAILURES, STEP_TOO_SMALL, SUCCESS

from .taut_system import fast_family
from .unheld_roots import settle_on_conjugates, settle_on_found_roots

__all__ = ["TAUT_EXTENDED", "MAX_PATHS", "MAX_STEPS", "MIN_STEP", "TIGHTER", "TIGHT_MAX_PATHS", "TAIL_T", "TAIL_BITS",
           "TAIL_STEPS", "proven_in_balls", "rescue_in_taut_extended"]

TAUT_EXTENDED = "taut_extended"  # the ``retried`` of a path settled here
MAX_PATHS = 8  # failed paths per run tracked here (a run with more is near a special robot: module doc of .solve)
MAX_STEPS = (6000, 20000, 20000)  # double-double steps per path in each round (measured: 1,760 .. 15,000, below)
MIN_STEP = 1e-16  # the step-size floor in s (the double tracker's 1e-13 stops those paths)
TIGHTER = (3e-5, 3e-6)  # predictor tolerances tried next, in turn, on the paths still failed ...
TIGHT_MAX_PATHS = 2  # ... when at most this many are left
TAIL_T = 1e-5  # a double-double track stopped within this of t = 0 goes on there in python-flint ...
TAIL_BITS = 212  # ... at this precision, at most TAIL_STEPS steps
TAIL_STEPS = 2000


def proven_in_balls(x, p) -> bool:
    """The candidate root x (normalized unknowns, unit scale) of the taut system with parameters p proven to be near a
    root by the ball Krawczyk test of the endpoint certificates
    (:func:`cdpr_algebra.intervals.complex_krawczyk.certify_complex_root_balls`, at 128 bits, else 256 (``BALL_PRECS``:
    the 3.8e9 pair of the module doc needs 256 here), Newton's method allowed to move it by ``BALL_MAX_MOVE`` of
    max(1, |x_k|) per unknown), p read exactly from its doubles (module doc: why a track's end at t = 0 is not
    enough)."""
    from flint import acb

    from cdpr_algebra.certificates.endpoints import BALL_MAX_MOVE, BALL_PRECS
    from cdpr_algebra.certificates.equilibria import parameter_taut_system
    from cdpr_algebra.intervals.complex_krawczyk import certify_complex_root_balls

    x = np.asarray(x, dtype=complex)
    P = [acb(float(v.real), float(v.imag)) for v in np.asarray(p, dtype=complex)]

    def system(y, jacobian):
        return parameter_taut_system(y, P, jacobian)

    return any(certify_complex_root_balls(system, x, np.ones(len(x)), prec=prec, max_move=BALL_MAX_MOVE)[0]
               for prec in BALL_PRECS)


def rescue_in_taut_extended(m: int, res, start_parameters, start_solutions, target, options, conjugates: bool = False):
    """(``res``, a run of the taut system of m cables from ``start_solutions`` at ``start_parameters`` to ``target``,
    with its failed paths settled on roots reached in double-double (module doc), the number of failed paths left).
    ``options``: the run's SolveOptions (its tracker's tolerances; its endgame's cluster tolerance decides
    coincidence); ``conjugates``: the target is real, so first and after each round the conjugates of the run's roots
    settle what they can (:func:`.unheld_roots.settle_on_conjugates`) before a costlier round."""
    from cdpr_algebra.generated.taut_equations import taut_equations as taut_source
    from cdpr_algebra.generated.taut_equations_dd import taut_equations
    from cdpr_algebra.homotopy.flint_tracker import FlintParameterHomotopy, flint_track
    from cdpr_algebra.homotopy.dd_tracker import CORRECTOR_FLOOR, DoubleDoubleParameterHomotopy
    from cdpr_algebra.homotopy.homotopies import ParameterHomotopy
    from cdpr_algebra.homotopy.refinement import relative_residual

    system = fast_family(m)
    homotopy = ParameterHomotopy(system, start_parameters, target)
    precise = DoubleDoubleParameterHomotopy.like(homotopy, taut_equations)
    tail = FlintParameterHomotopy.like(homotopy, taut_source)
    X0 = np.asarray(start_solutions, dtype=complex)
    left = sum(1 for p in res.track.paths if p.status in FAILURES)
    stopped = {}  # path -> how its last double-double track ended
    if left and conjugates:
        res, left = settle_on_conjugates(res, options)
    for k, ptol in enumerate((options.tracker.predictor_tol,) + TIGHTER):
        if left == 0 or (k and left > TIGHT_MAX_PATHS):
            break
        tracker = replace(options.tracker, min_step=MIN_STEP, predictor_tol=ptol)
        failed = [i for i, p in enumerate(res.track.paths) if p.status in FAILURES][:MAX_PATHS]
        if k:  # a tighter tolerance for the tracks its predecessor stopped (not those out of steps: they only crawl)
            failed = [i for i in failed if stopped.get(i) == STEP_TOO_SMALL]
        found, steps = [], {}
        for i in failed:
            seg = precise.track(X0[i], 1.0, 0.0, tracker, MAX_STEPS[k])  # path i starts at start solution i
            steps[i] = seg.steps
            stopped[i] = seg.status
            if seg.status != SUCCESS and abs(seg.t) <= TAIL_T and np.all(np.isfinite(seg.x)):
                seg = flint_track(tail, seg.x, seg.t, 0.0, tracker, TAIL_BITS, TAIL_STEPS)
                steps[i] += seg.steps
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
                     for x, r, c in zip(X, residual, condition) if proven_in_balls(x, target)]
        paths = list(res.track.paths)
        for i, n in steps.items():
            paths[i] = replace(paths[i], steps=paths[i].steps + n)
        res, left = settle_on_found_roots(replace(res, track=replace(res.track, paths=tuple(paths))), found, options)
        if left and conjugates:
            res, left = settle_on_conjugates(res, options)
    return res, left
