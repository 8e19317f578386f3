"""The Cauchy endgame of :mod:`.endgame` for one path at a time over :func:`.hybrid_tracker.hybrid_track` (double
precision, and an extended-precision twin of the homotopy wherever double precision fails).

Why.  A path whose limit at t = 0 is singular (several paths meet there, or it lies on a singular set at infinity)
is ill-conditioned near t = 0: condition numbers grow like a power of 1 / t, and in double precision its tracking
fails (``step_too_small``) before two Cauchy estimates agree to ``cauchy_tol``.  Measured (twenty-first session) on
the Study paths of seed 002's 8-cable robot that the double endgame left failed at t ~ 2e-5: with double-double
where double fails, the loops close at radii 1e-4 .. 1e-5 (winding number 2) and the estimates converge on points
of N = e . e = 0.

What.  :func:`precise_cauchy_endgame` samples the path at the radii t0 ratio^k (``EndgameOptions.sample_ratio``, up
to ``max_samples + infinity_samples`` radii), loops around t = 0 at each (``samples_per_loop`` arcs, up to
``max_winding_number`` turns, closed within ``loop_closure_tol``), and stops when the means of two consecutive loops
agree to ``cauchy_tol`` (relative): the limit, its winding number, the path at the last two radii (for the order of a
coordinate that vanishes there, :func:`.endgame.decide_in_chart`) and the samples of the two loops whose means
agreed (for :func:`.endgame.block_at_infinity`).  It decides nothing itself.  Generic: any
homotopy with a twin that :func:`.hybrid_tracker.hybrid_track` accepts.
"""

from __future__ import annotations

from dataclasses import dataclass, replace

import numpy as np

from .hybrid_tracker import hybrid_track
from .results import SUCCESS

__all__ = ["PreciseLimit", "precise_cauchy_endgame", "relative_change"]


@dataclass(frozen=True)
class PreciseLimit:
    """The outcome of :func:`precise_cauchy_endgame` for one path: ``converged`` when two consecutive Cauchy
    estimates agreed to the endgame's ``cauchy_tol``; ``x`` the last estimate (or the last point reached),
    ``accuracy`` the relative difference of the last two estimates (inf without two), ``winding`` the loops' turns,
    ``xlast`` / ``xprev`` the path at the last two sample radii, ``t`` the last radius reached, ``steps`` all steps
    and ``precise_steps`` those in extended precision; ``loop`` / ``loop_prev`` the samples (rows) of the loops at
    the last radius and at the one before, whose means were the last two estimates (None where they are not)."""

    converged: bool
    x: np.ndarray
    accuracy: float
    winding: int
    xlast: np.ndarray
    xprev: np.ndarray
    t: float
    steps: int
    precise_steps: int
    loop: np.ndarray | None = None
    loop_prev: np.ndarray | None = None


def relative_change(a, b) -> float:
    """|a - b| / (1 + |a|): how far two estimates (or a loop's end from its start) differ, relative to a."""
    return float(np.linalg.norm(a - b) / (1.0 + np.linalg.norm(a)))


def _loops(homotopy, precise, x, r, o, tr, chunk, budget):
    """(samples, turns, closed, steps, precise steps) of the loops of x around t = 0 on |t| = r (the samples' mean
    is the Cauchy estimate)."""
    M = o.samples_per_loop
    samples = []
    z = x.copy()
    steps = psteps = 0
    for j in range(M * o.max_winding_number):
        samples.append(z)
        seg = hybrid_track(homotopy, precise, z, r * np.exp(2j * np.pi * j / M), r * np.exp(2j * np.pi * (j + 1) / M),
                           tr, chunk=chunk, max_precise_steps=max(budget - psteps, 0))
        steps += seg.steps
        psteps += seg.precise_steps
        if seg.status != SUCCESS:
            return None, 0, False, steps, psteps
        z = seg.x
        if (j + 1) % M == 0 and relative_change(x, z) <= o.loop_closure_tol:
            return np.array(samples), (j + 1) // M, True, steps, psteps
    return None, 0, False, steps, psteps


def precise_cauchy_endgame(homotopy, precise, x, t0: float, o, tr, chunk: int = 200,
                           max_precise_steps: int = 20000, settled=None) -> PreciseLimit:
    """The path at x (t = t0, real) followed to its limit at t = 0 (module doc); ``o``: the
    :class:`.endgame.EndgameOptions`, ``tr``: the tracker's options, ``precise``: the extended-precision twin of
    ``homotopy``, at most ``max_precise_steps`` steps in it.  ``settled(loop, loop_prev, turns) -> bool``: where
    given, two agreeing estimates end the endgame only when it holds for their loops (else it samples on, to
    smaller radii)."""
    x = np.asarray(x, dtype=complex)
    r = float(t0)
    nan = np.full_like(x, np.nan)
    xprev = nan
    prev = best = prev_loop = None
    acc, wind = np.inf, 0
    steps = psteps = 0
    loop_tr = replace(tr, max_step=1.0)
    for k in range(o.max_samples + o.infinity_samples):
        seg = hybrid_track(homotopy, precise, x, r, r * o.sample_ratio, tr, chunk=chunk,
                           max_precise_steps=max(max_precise_steps - psteps, 0))
        steps += seg.steps
        psteps += seg.precise_steps
        if seg.status != SUCCESS:
            break
        xprev, x, r = x, seg.x, r * o.sample_ratio
        if k == 0:
            continue
        loop, c, ok, st, pst = _loops(homotopy, precise, x, r, o, loop_tr, chunk, max_precise_steps - psteps)
        steps += st
        psteps += pst
        if not ok:
            prev = None
            continue
        est = loop.mean(axis=0)
        if prev is not None:
            d = relative_change(est, prev)
            if d < acc:
                best, acc, wind = est, d, c
            if d <= o.cauchy_tol and (settled is None or settled(loop, prev_loop, c)):
                return PreciseLimit(True, est, d, c, x, xprev, r, steps, psteps, loop, prev_loop)
        prev, prev_loop = est, loop
    return PreciseLimit(False, x if best is None else best, acc, wind, x, xprev, r, steps, psteps)
