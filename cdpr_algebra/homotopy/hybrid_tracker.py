"""Path tracking in double precision, with extended precision only on the stretches where double precision fails.

:func:`hybrid_track` tracks a path with the double tracker (:func:`.tracker.track_segment`); where that fails by
its step budget or step-size underflow (a path passing close to a singular set: its Jacobian's condition number
reaches 1e12 .. 1e17 and Newton stalls at cond x eps), it goes on from the last point reached with an
extended-precision twin of the same homotopy (:class:`.dd_tracker.DoubleDoubleParameterHomotopy`, compiled
double-double, which the DGP uses, or :class:`.flint_tracker.FlintParameterHomotopy`, python-flint) for a chunk of
steps, then tries double precision again.  Generic: it knows nothing of the system but the two trackers'
interfaces, and imports neither twin.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .results import STEP_TOO_SMALL, SUCCESS, TOO_MANY_STEPS

__all__ = ["PreciseSegment", "HybridSegment", "hybrid_track"]


@dataclass(frozen=True)
class PreciseSegment:
    """One path tracked by an extended-precision tracker (:func:`.flint_tracker.flint_track`,
    :func:`.dd_tracker.dd_track`): the last point reached (complex), its t, status and steps."""

    x: np.ndarray
    t: complex
    status: str
    steps: int


@dataclass(frozen=True)
class HybridSegment:
    """One path tracked by :func:`hybrid_track`: as :class:`PreciseSegment`, with the steps taken in extended
    precision (``precise_steps``) among all ``steps``."""

    x: np.ndarray
    t: complex
    status: str
    steps: int
    precise_steps: int


def hybrid_track(homotopy, precise, x0, t_a, t_b, options, chunk: int = 200,
                 max_precise_steps: int = 3000) -> HybridSegment:
    """Track x0 from t_a to t_b in double precision (:func:`.tracker.track_segment` on ``homotopy``, ``options``);
    where that fails, on from the last point it reached in extended precision (``precise.track``: a
    :class:`.flint_tracker.FlintParameterHomotopy`, or the compiled double-double twin
    :class:`.dd_tracker.DoubleDoubleParameterHomotopy`, of the same homotopy) for at most ``chunk`` steps, then in
    double precision again, and so on, until t_b is reached, a tracker fails otherwise than by its step budget, or
    ``max_precise_steps`` steps in extended precision are spent (then ``too_many_steps``).  The chunk doubles after
    each round: a path that crawls for thousands of steps in extended precision (measured: 27,000 on a Test 3 path)
    does not pay a failed double-precision run (up to ``options.max_steps`` steps) every ``chunk`` steps.
    ``precise.track(x, t_a, t_b, options, max_steps, initial_step=...)`` returns an object with x, t, status and
    steps (:class:`PreciseSegment`)."""
    from .tracker import track_segment

    x, ta = np.asarray(x0, dtype=complex), complex(t_a)
    steps = psteps = 0
    while True:
        seg = track_segment(homotopy, x[None], ta, t_b, options)
        steps += int(seg.steps[0])
        if seg.status[0] == SUCCESS:
            return HybridSegment(seg.x[0], complex(t_b), SUCCESS, steps, psteps)
        if seg.status[0] not in (STEP_TOO_SMALL, TOO_MANY_STEPS) or not np.all(np.isfinite(seg.x[0])):
            return HybridSegment(seg.x[0], complex(seg.t[0]), str(seg.status[0]), steps, psteps)
        x, ta = seg.x[0], complex(seg.t[0])
        budget = min(chunk, max_precise_steps - psteps)
        chunk *= 2
        if budget <= 0:
            return HybridSegment(x, ta, TOO_MANY_STEPS, steps, psteps)
        pr = precise.track(x, ta, t_b, options, budget, initial_step=min(options.initial_step, 1e-4))
        psteps += pr.steps
        steps += pr.steps
        if pr.status == SUCCESS:
            return HybridSegment(pr.x, complex(t_b), SUCCESS, steps, psteps)
        if pr.status != TOO_MANY_STEPS:
            return HybridSegment(pr.x, pr.t, pr.status, steps, psteps)
        x, ta = pr.x, pr.t
