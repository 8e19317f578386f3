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

from .complex_krawczyk import EPS, START_RTOL, _krawczyk_round

__all__ = ["RealRootBoxes", "certify_real_roots"]


@dataclass(frozen=True)
class RealRootBoxes:
    """Outcome of :func:`certify_real_roots` for N roots of h unknowns.

    ``proven`` (N,): exactly one zero of F in the box; ``lo``, ``hi`` (N, h): its enclosure X cap K(X) (the widest
    box allowed where not proven); ``rounds`` (N,): the inflation round that proved it (0: not proven);
    ``reason`` (N,): why a root is not proven ('' when proven).
    """

    proven: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    rounds: np.ndarray
    reason: tuple


def certify_real_roots(kernel, Y, scale, max_rel_width: float = 1e-9, max_iter: int = 10) -> RealRootBoxes:
    """Prove that each refined real root y of ``Y`` (N, h) has exactly one zero of F within a box of half-width
    <= ``max_rel_width`` / 2 * ``scale`` (N, h or h: the size of each unknown) around it.

    ``kernel(rows, y, r) -> (K Interval (len(rows), h), ok (len(rows),) bool)``: the Krawczyk operator over the
    boxes y -+ r of the roots ``rows`` of Y (ok False: C could not be formed; K is then unbounded).  The caller
    refines the roots (Newton) and checks that the refined root is the reported one; a root with a non-finite
    coordinate is not proven.
    """
    Y = np.asarray(Y, dtype=float)
    N, h = Y.shape
    s = np.broadcast_to(np.asarray(scale, dtype=float), (N, h))
    rmax = 0.5 * max_rel_width * s
    r = 4 * EPS * np.abs(Y) + START_RTOL * s
    proven = np.zeros(N, bool)
    rounds = np.zeros(N, int)
    lo, hi = Y - rmax, Y + rmax
    reason = ["" for _ in range(N)]
    finite = np.all(np.isfinite(Y), axis=1) & np.all(np.isfinite(s), axis=1)
    for k in np.flatnonzero(~finite):
        reason[k] = "the root is not finite"
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
    return RealRootBoxes(proven, lo, hi, rounds, tuple(reason))
