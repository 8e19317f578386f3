"""Krawczyk certificates of real roots of a real square system, a batch at a time, with a compiled operator.

For boxes X = y +/- r (the floats fl(y -+ r)), the Krawczyk operator K(X, y) = y - C F(y) + (I - C J(X)) (X - y)
(any real C) encloses every zero of F in X, and if K(X) lies in the interior of X, F has exactly one zero in X
(R. Krawczyk 1969, R. E. Moore 1977).  Epsilon-inflation (Rump): start from a tiny box around each refined root,
enlarge r from |K(X) - y| until the test passes or r passes the width limit; the rounds of
:func:`.complex_krawczyk._krawczyk_round`, on the real space.  The operator comes from the caller, compiled (e.g.
:func:`.real_kernels.real_subsystem_krawczyk_kernel`), so a batch of roots costs no Python per root.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .balls import NOT_FINITE, SINGULAR, newton_step_reason
from .complex_krawczyk import EPS, START_RTOL, _krawczyk_round

__all__ = ["RealRootBoxes", "certify_real_roots"]


@dataclass(frozen=True)
class RealRootBoxes:
    """Outcome of :func:`certify_real_roots` for N roots of h unknowns.

    ``proven`` (N,): exactly one zero of F in the box; ``lo``, ``hi`` (N, h): its enclosure X cap K(X) (the widest
    box allowed where not proven); ``rounds`` (N,): the inflation round that proved it (0: not proven);
    ``reason`` (N,): why a root is not proven ('' when proven); ``center`` (N, h): the roots the boxes are centred
    on; ``newton_step`` (N,): |C F(x0)| relative to the scale (max over the unknowns; NaN without a Newton step).
    """

    proven: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    rounds: np.ndarray
    reason: tuple
    center: np.ndarray
    newton_step: np.ndarray


def certify_real_roots(kernel, X0, scale, max_rel_width: float = 1e-9, max_iter: int = 10, inverse=None,
                       residual=None) -> RealRootBoxes:
    """Prove that each real root of ``X0`` (N, h) has exactly one zero of F within a box of half-width
    <= ``max_rel_width`` / 2 * ``scale`` (N, h or h: the size of each unknown) around it, as
    :func:`.balls.krawczyk_certify` does for one root.

    ``kernel(rows, y, r) -> (K Interval (len(rows), h), ok (len(rows),) bool)``: the Krawczyk operator over the
    boxes y -+ r of the roots ``rows`` (ok False: C could not be formed; K is then unbounded).  With ``inverse``
    (N, h, h: approximate inverses of the Jacobians at the roots, doubles) and ``residual`` (N, h: F there), the
    boxes are centred on the Newton-refined roots y = x0 - C F(x0), and a root whose Newton step exceeds half the
    width limit is not proven (the proof would be about another point), nor one whose C is not finite; without
    them the caller has refined the roots.  A root with a non-finite coordinate is not proven.
    """
    X0 = np.asarray(X0, dtype=float)
    N, h = X0.shape
    s = np.broadcast_to(np.asarray(scale, dtype=float), (N, h))
    reason = ["" for _ in range(N)]
    finite = np.all(np.isfinite(X0), axis=1) & np.all(np.isfinite(s), axis=1)
    for k in np.flatnonzero(~finite):
        reason[k] = NOT_FINITE
    Y, rel_step = X0, np.full(N, np.nan)
    if inverse is not None:
        C = np.asarray(inverse, dtype=float).reshape(N, h, h)
        with np.errstate(invalid="ignore", over="ignore"):
            step = np.einsum("nij,nj->ni", C, np.asarray(residual, dtype=float).reshape(N, h))
            rel_step = np.max(np.abs(step) / s, axis=1)
        Y = X0 - step
        regular = np.all(np.isfinite(C), axis=(1, 2))
        close = rel_step <= 0.5 * max_rel_width
        for k in np.flatnonzero(finite & ~regular):
            reason[k] = SINGULAR
        for k in np.flatnonzero(finite & regular & ~close):
            reason[k] = newton_step_reason(rel_step[k], max_rel_width)
        finite &= regular & close
    rmax = 0.5 * max_rel_width * s
    r = 4 * EPS * np.abs(Y) + START_RTOL * s
    proven = np.zeros(N, bool)
    rounds = np.zeros(N, int)
    lo, hi = Y - rmax, Y + rmax
    pending = np.flatnonzero(finite)
    for it in range(1, max_iter + 1):
        if not len(pending):
            break
        before = proven[pending].copy()
        kept = _krawczyk_round(None, h, pending, Y, r, rmax, lo, hi, proven, reason, max_rel_width, kernel)
        rounds[pending[proven[pending] & ~before]] = it
        pending = kept
    for k in pending:
        reason[k] = f"Krawczyk test not satisfied after {max_iter} inflations"
    return RealRootBoxes(proven, lo, hi, rounds, tuple(reason), Y, rel_step)
