"""The subproblems of a DGP: the cable lengths checked, and every set of taut cables (Berti, Merlet and
Carricato 2016, Sec. 3: m = 1 .. min(n, 6) taut cables), solved one after the other by any solver."""

from __future__ import annotations

import itertools
import time

import numpy as np

from .errors import CdprInputError

__all__ = ["lengths_and_taut_sets", "solve_each_taut_set"]


def lengths_and_taut_sets(robot, lengths=None, max_m: int = 6):
    """(rho, every 0-based taut set of m = 1 .. min(n, 6, max_m) cables): the subproblems of a DGP (also of the
    interval cross-check); ``lengths`` default to the robot's."""
    if lengths is None:
        if robot.lengths is None:
            raise CdprInputError("lengths", "no cable lengths: give lengths or a robot file with lengths")
        lengths = robot.lengths
    rho = np.asarray(lengths, dtype=float)
    if rho.shape != (robot.n,):
        raise CdprInputError("lengths", f"expected {robot.n} cable lengths, got {rho.size}")
    if not np.all(np.isfinite(rho)) or np.any(rho <= 0):
        raise CdprInputError("lengths", f"cable lengths must be positive finite numbers, got {rho.tolist()}")
    return rho, [c for m in range(1, min(robot.n, 6, max_m) + 1) for c in itertools.combinations(range(robot.n), m)]


def solve_each_taut_set(robot, lengths, max_m, sets, solve_one, progress=None):
    """(rho, [solve_one(rho, c) for every taut set c], seconds), one set after the other: over the 0-based
    ``sets``, or every set of :func:`lengths_and_taut_sets`; ``progress(result, done, total)`` after each."""
    t0 = time.perf_counter()
    rho, every_set = lengths_and_taut_sets(robot, lengths, max_m)
    sets = every_set if sets is None else sets
    out = []
    for k, c in enumerate(sets):
        out.append(solve_one(rho, c))
        if progress:
            progress(out[-1], k + 1, len(sets))
    return rho, out, time.perf_counter() - t0
