"""Another generic start instance of the taut system: a route to a taut set's target through other parameters.

Why.  The re-run of a subproblem with a new gamma (:func:`.solve._solve_taut_set`) follows another real path in the
same complex line of parameters, {p_gen + s (target - p_gen)}; a route through another generic instance p_new uses
other lines altogether.  A root whose path, on that line, passes close to a singular set at infinity may be reached
easily from elsewhere.  Measured (twenty-third session) on ``examples/symmetric_4cables.toml``, taut set {1, 2, 3,
4}: one path of both gamma routes, in Study parameters and in the taut system alike, crawls at t ~ 0.25 next to
Study's exceptional set (|g| ~ 600, N / |e|^2 ~ 2e-8) and fails, while its root is well conditioned (condition 7e3,
|x| ~ 15; found by PHCpack's blackbox too); 183 regular endpoints + 32 at infinity + that root = 216.

How it accounts.  The start instance p_new (random complex parameters near the stored generic instance) is solved
once per m and process by the DGP's own run from the stored generic solutions to p_new as its target (the taut
system alone loses paths there, as it does on robots): it serves only when all of them end regular and distinct
there (then they are all its solutions: a generic instance has exactly the generic count).
The run from p_new to the target is another run of the same target, and a regular root of the target is the limit
of exactly one branch of each run, so its regular roots that no path of the kept run holds settle that run's failed
paths (:func:`.unheld_roots.settle_on_unheld_roots`, as the gamma route's do).
"""

from __future__ import annotations

import numpy as np

from cdpr_algebra.homotopy.results import SUCCESS

__all__ = ["OTHER_START_SEED", "OTHER_START_RADIUS", "other_generic_instance"]

OTHER_START_SEED = 65537  # draws the other start instance (any seed serves)
OTHER_START_RADIUS = 0.25  # p_new = p_gen + radius z, z standard complex normal (the stored entries are ~0.2 in size)

_CACHE: dict = {}


def other_generic_instance(track_to, p_gen, X_gen, seed: int = OTHER_START_SEED, fixed=(), relations=()):
    """(p_new, X_new): random complex parameters near the stored generic instance ``p_gen`` and all their solutions
    (taut coordinates), from ``track_to(p_new, seed)``, the DGP's run (:func:`.solve._track`) of the stored generic
    solutions ``X_gen`` to p_new as its target; None when any path fails or two end together (they would not be known
    to be all).  Drawn and tracked with ``seed`` alone, so the same whichever subproblem asks first; cached per
    (size of p_gen, number of solutions, seed): one stored instance per m and start set.  ``fixed``: indices of
    parameters that keep their value (a subfamily's start set stays in its subfamily, :mod:`.collinear_anchors`), and
    ``relations`` the subfamily's linear relations (:mod:`.parallelogram`)."""
    from cdpr_algebra.homotopy.monodromy import subfamily_point

    count = len(X_gen)
    key = (len(p_gen), count, seed, tuple(fixed), tuple(relations))
    if key not in _CACHE:
        rng = np.random.default_rng(seed)
        z = rng.normal(size=p_gen.shape) + 1j * rng.normal(size=p_gen.shape)
        p_new = subfamily_point(p_gen, OTHER_START_RADIUS * z, fixed, relations)
        res = track_to(p_new, seed)
        paths = res.track.paths
        regular = [s for s in res.solutions if not s.singular]
        ok = all(p.status == SUCCESS for p in paths) and len(paths) == len(regular) == count
        _CACHE[key] = (p_new, np.array([p.endpoint for p in paths])) if ok else None
    return _CACHE[key]
