"""Paths put at infinity while only their tension multipliers grow: undecided (``endgame_failed``) unless their pose
diverges too (:func:`tension_infinity_undecided`; the DGP's module doc, "Every path ends with one outcome")."""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from cdpr_algebra.homotopy.results import AT_INFINITY, ENDGAME_FAILED

__all__ = ["POSE_DIVERGES", "tension_infinity_undecided"]

POSE_DIVERGES = 0.5  # a pose block that grows like |t|^v with v c <= -this (winding number c) is at infinity itself


def tension_infinity_undecided(res, m, sampled_only: bool = False):
    """``res`` with every path put at infinity while only its tension multipliers grow (max |lam| exceeds the largest
    pose coordinate at its last sample, and the pose block does not grow: ``PathResult.valuation`` v with v c >
    -``POSE_DIVERGES``, c its winding number, or unknown) counted ``endgame_failed``: such a limit needs a wrench
    matrix exactly singular at a finite pose, which double precision cannot establish, and a finite equilibrium with
    huge tensions in a near-double pair across infinity looks the same (its two paths circle the pair's branch point
    at every radius the endgame reaches; tests/large_forces.py, twelfth session: |pose| < 1, |lam| 12-120 at the last
    samples, the root confirmed by 60-digit Newton; twenty-third session: all 14 such paths of the K = 1e5 robots
    have c = 2, pose valuation 0.00, lam valuation -0.45 .. -0.56).  Kept at infinity: paths whose pose diverges too,
    through the rotation (seed 002's 8-cable robot: 401 paths, |pose| >= 80, |lam| / |pose| <= 0.04) or the
    translation (``examples/symmetric_4cables.toml``, {1, 2, 3, 4}: 24 paths, c = 1, both blocks with valuation
    -1.00, the translation isotropic: tests/test_dgp_symmetric.py; they were ``endgame_failed``).

    ``sampled_only``: only the paths whose last two samples are known (``PathResult.previous``), for the run in Study
    parameters (:func:`.study_retrack.track_study_first`), whose paths at infinity without them keep their start
    point as endpoint: since the thirty-first session only those whose samples do not map back to finite taut
    coordinates (before, every limit on N = e . e = 0, the rotation at infinity: the endgame kept its Cauchy estimate
    on N = 0 and the precise endgame no sample; with their samples, seed 002's {1, 2, 5} and {1, 2, 5, 6} show the
    pose diverging, v c = -0.85 .. -1.25, and they stay at infinity).  Its paths that the precise endgame put at
    infinity because (g, lam) grow (``block_at_infinity``) were not tested here until the thirtieth session: on
    robots built around an equilibrium with tensions 1e6 times the load (benchmarks/bench_large_forces.py --m 3
    --K 1e6, seeds 300-303, i.e. robot seeds 330-333) two such paths (winding number 2, pose steady, |lam| ~
    t^-1/2) per robot were at infinity, every subproblem complete and the equilibrium missing; now they fail, 2 of
    the 4 equilibria are found (the failed paths settled on the roots Newton's method reaches,
    :mod:`.unheld_roots`), the other 2 robots say incomplete."""
    paths = list(res.track.paths)

    def pose_stays_finite(p):
        v = p.valuation(slice(0, 12))
        return not (np.isfinite(v) and v * p.winding_number <= -POSE_DIVERGES)

    bad = [i for i, p in enumerate(paths) if p.status == AT_INFINITY and np.all(np.isfinite(p.endpoint))
           and (p.previous is not None or not sampled_only)
           and np.max(np.abs(p.endpoint[12:12 + m])) > np.max(np.abs(p.endpoint[:12])) and pose_stays_finite(p)]
    if not bad:
        return res
    for i in bad:
        paths[i] = replace(paths[i], status=ENDGAME_FAILED)
    return replace(res, track=replace(res.track, paths=tuple(paths)))
