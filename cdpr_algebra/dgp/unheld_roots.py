"""Failed paths settled on regular roots that no other path holds, found by Newton's method from the failed paths'
own last estimates.

Why this is an account.  Near t = 0 the solutions of the parameter homotopy form N branches and a run's paths hold
them one to one (a path settled by a detour holds a branch too: its regular endpoint is one no other path ends on).
A regular root of the target system is the limit of exactly one branch.  So a regular root that no settled path
ends on (regular or singular; paths at infinity hold branches that diverge) is the limit of a branch that no
settled path holds: the branch of one of the failed paths.  Found by any means, k distinct such roots account for
k failed paths; which failed path held which is not claimed (the counts are), and a root found twice counts once.

The means here (:func:`settle_on_unheld_roots`): Newton's method (residuals in double-double) for up to
``NEWTON_STEPS`` iterations from each failed path's last estimate, and, for a path whose Cauchy endgame saw a cycle of
two sheets (winding number 2) that did not converge, from the reflection 2 m - x1 of a root x1 found through its
estimate m: the loops of that endgame enclose a branch point near t = 0 where two regular roots x1, x2 meet, and the
mean of the two sheets over a loop is (x1 + x2) / 2 (a symmetric function of the cycle is analytic inside it).
Measured (twentieth session) on the robots of ``tests/large_forces.py`` with m = 6: the two failed paths of each
flagged robot are such a pair (winding number 2, estimate |x| ~ 8e3); Newton from the estimate reaches the
constructed equilibrium (|x| ~ 2e2, condition 1e10) in ~20 iterations, and its reflection the partner root.
A kept root's outcome is ``regular`` with ``retried = "unheld_root"``; it is certified like every other endpoint.

For a real target (:func:`settle_on_conjugates`), the conjugate of a regular root is a regular root (same residual,
same condition number): a non-real regular endpoint whose conjugate no path holds settles a failed path, kept as
the conjugate of an endpoint already accepted (``retried = "conjugate"``), without a Newton test of its own, which in
double precision cannot show convergence where the root is huge (measured, thirty-fourth session: |x| = 5.6e7,
condition 2.8e16, Newton's last update 1.3e-7).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from cdpr_algebra.homotopy.clusters import coincides_with_any
from cdpr_algebra.homotopy.refinement import refine
from cdpr_algebra.homotopy.results import ENDGAME_FAILED, FAILURES, SINGULAR, SUCCESS
from cdpr_algebra.homotopy.solve import group_solutions

__all__ = ["CONJUGATE", "MAX_CONDITION", "NEWTON_STEPS", "SETTLED", "UNHELD_ROOT", "newton_roots", "residual_bound",
           "settle_on_conjugates", "settle_on_found_roots", "settle_on_unheld_roots"]

NEWTON_STEPS = 40  # Newton iterations from an estimate (ill-conditioned roots converge slowly from afar)
SETTLED = 1e-10  # the last Newton update (relative) of a kept root
# the largest condition number of a kept root: Newton's updates, solved in double precision, are then accurate to
# ~0.1 (residuals in double-double), so updates that shrink quadratically to SETTLED show convergence.  Beyond it (the
# roots of tests/large_forces.py with m = 6 and tensions 1e5 times the load reach 1e16) nothing is shown: the path
# stays failed.  1e14 until the twenty-second session: the pair of roots of two such robots (m = 6, K = 1e4 seed 360,
# K = 1e5 seed 361) have condition 1.2e14 and converge from the failed paths' estimates (residual ~1e-17, last update
# ~1e-15); with 1e15 both subproblems are complete and the equilibrium certified.  A kept root is proven or not by
# the endpoint certificates either way.
MAX_CONDITION = 1e15
UNHELD_ROOT = "unheld_root"  # the ``retried`` of a failed path settled by this module
CONJUGATE = "conjugate"  # ... on the conjugate of a regular endpoint (a real target)


ROUNDING_RESIDUAL = 1e-14  # per unit of size: the residual floor of a root rounded to doubles (residual_bound)


def residual_bound(X, residual_tol) -> np.ndarray:
    """The largest relative residual (``refinement.relative_residual``: max |H| / (1 + max |x|)) accepted at the
    points X (rows): ``residual_tol``, or ``ROUNDING_RESIDUAL`` (1 + max |x|) where that is larger.  Why: the DGP's
    equations are quadratic, so the double nearest a root x (off by eps |x|) leaves |H| ~ eps |x|^2 even with
    residuals in double-double, a relative residual ~ eps |x|: a fixed tolerance refuses every root beyond
    |x| ~ 1e8 however well Newton converged.  Measured (twenty-second session): seed 002's taut set {2, 4, 6, 8}, a
    root with |x| = 7.4e7 (condition 9e11; Newton quadratic to 2.5e-14, residual 1.3e-8 > 1e-8; in Study parameters
    residual 2e-13), which both routes' paths then failed to reach."""
    X = np.atleast_2d(X)
    with np.errstate(all="ignore"):
        return np.maximum(residual_tol, ROUNDING_RESIDUAL * (1 + np.max(np.abs(X), axis=1)))


def newton_roots(homotopy, X, residual_tol, max_condition: float | None = None):
    """Rows X refined at t = 0 (at most ``NEWTON_STEPS`` iterations): (points, their (residual, condition, last
    update), mask of Newton-quadratic finite roots with a last update <= ``SETTLED``, condition number <=
    ``max_condition`` (default ``MAX_CONDITION``) and residual within :func:`residual_bound` of tol)."""
    X = np.asarray(X, dtype=complex).reshape(-1, homotopy.n)
    if not len(X):
        return X, [], np.zeros(0, dtype=bool)
    with np.errstate(all="ignore"):
        x, upd, res, cond, quad = refine(homotopy, X, 0.0, max_iter=NEWTON_STEPS)
    limit = MAX_CONDITION if max_condition is None else max_condition
    good = quad & (upd <= SETTLED) & (cond <= limit) & (res <= residual_bound(x, residual_tol))
    good &= np.all(np.isfinite(x), axis=1)
    return x, list(zip(res, cond, upd)), good


def settle_on_unheld_roots(homotopy, result, options, residual_tol: float, more_estimates=(),
                           max_condition: float | None = None):
    """(``result`` with its failed paths settled on distinct regular roots that no other path holds (module doc), the
    number of failed paths left).  ``homotopy``: the parameter homotopy whose target is the system at t = 0 (its
    ``n`` unknowns; endpoints in its coordinates); ``options``: the run's SolveOptions (``endgame.cluster_tol``
    decides coincidence, ``duplicate_tol`` the grouping); ``residual_tol``: the largest relative residual of a
    kept root; ``more_estimates``: other points to start Newton's method from (e.g. roots found in other
    coordinates, :func:`.study_retrack.study_roots`), kept by the same tests, with ``max_condition`` for them."""
    paths, failed, held = _failed_and_held(result)
    if not failed:
        return result, 0
    tol = options.endgame.cluster_tol
    found = []  # (root, (residual, condition, last update))

    def keep(x, info):
        if not coincides_with_any(held, x, tol) and not coincides_with_any([f for f, _ in found], x, tol):
            found.append((x, info))

    starts = [i for i in failed if np.all(np.isfinite(paths[i].endpoint))]
    X, info, good = newton_roots(homotopy, [paths[i].endpoint for i in starts], residual_tol)
    roots = {i: x for i, x, g in zip(starts, X, good) if g}
    for x, inf, g in zip(X, info, good):
        if g:
            keep(x, inf)
    pairs = [2 * paths[i].endpoint - x for i, x in roots.items()
             if paths[i].status == ENDGAME_FAILED and paths[i].winding_number == 2]
    Y, info, good = newton_roots(homotopy, pairs + [np.asarray(x, dtype=complex) for x in more_estimates], residual_tol,
                                 max_condition)
    for y, inf, g in zip(Y, info, good):
        if g:
            keep(y, inf)
    return _settled(result, paths, failed, [dict(endpoint=x, residual=float(res), condition=float(cond),
                                                 accuracy=float(upd), retried=UNHELD_ROOT)
                                            for x, (res, cond, upd) in found], options)


def settle_on_conjugates(result, options):
    """(``result``, a run to a target with real coefficients, with its failed paths settled on the conjugates of its
    non-real regular endpoints that no path holds, the number of failed paths left): module doc.  Each kept
    conjugate takes the residual, condition and accuracy of the endpoint it mirrors."""
    return settle_on_found_roots(result, [dict(endpoint=np.conj(p.endpoint), residual=p.residual, condition=p.condition,
                                               accuracy=p.accuracy, retried=CONJUGATE)
                                          for p in result.track.paths
                                          if p.status == SUCCESS and np.any(np.imag(p.endpoint) != 0)], options)


def settle_on_found_roots(result, found, options):
    """(``result`` with its failed paths settled on the roots ``found`` (dicts of PathResult fields: endpoint,
    residual, condition, accuracy, retried; found by any route, e.g. :mod:`.taut_extended`) that no settled path holds,
    each counted once (the account of the module doc), the number of failed paths left)."""
    paths, failed, held = _failed_and_held(result)
    if not failed:
        return result, 0
    tol = options.endgame.cluster_tol
    kept = []
    for fields in found:
        x = fields["endpoint"]
        if not coincides_with_any(held, x, tol) and not coincides_with_any([f["endpoint"] for f in kept], x, tol):
            kept.append(fields)
    return _settled(result, paths, failed, kept, options)


def _failed_and_held(result):
    """(the run's paths (a list), the indices of its failed ones, the endpoints that settled paths hold)."""
    paths = list(result.track.paths)
    return (paths, [i for i, p in enumerate(paths) if p.status in FAILURES],
            [p.endpoint for p in paths if p.status in (SUCCESS, SINGULAR)])


def _settled(result, paths, failed, found, options):
    """(``result`` with its failed paths ``failed`` given, in order, the regular outcomes ``found`` (PathResult
    fields: endpoint, residual, condition, accuracy, retried), the number of failed paths left)."""
    if not found:
        return result, len(failed)
    for i, fields in zip(failed, found):
        paths[i] = replace(paths[i], status=SUCCESS, t=0j, winding_number=1, **fields)
    track = replace(result.track, paths=tuple(paths))
    left = len(failed) - min(len(found), len(failed))
    return replace(result, track=track, solutions=group_solutions(track, options.duplicate_tol,
                                                                  options.endgame.cluster_tol)), left
