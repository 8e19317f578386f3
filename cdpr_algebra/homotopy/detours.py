"""Detours: a path that failed at t_f is tracked again from its start point around t_f on a half circle in the
complex t-plane, and kept only where the point it reaches cannot belong to another path.

Why a kept point is the path's own.  The solutions of H(x, t) = 0 near a t where the system is regular form N
distinct branches, and the paths of one run hold them one to one.  A detour follows another route, so it ends on
the failed path's own branch unless its half circle encloses a branch point, where it changes to a branch that
another path holds (or another failed path would have held).  So a detour's point is kept only when no other path
holds it, compared at t = te (:func:`phase1_detours`, a failure in (te, 1)): the system at te is generic, every
path's point there is a regular solution, and the kept point is one that no other path reached.

It needs every path of the run (the caller checks it: ``SolveOptions.detour_retry`` and a call given every start
point): a comparison with some of the paths proves nothing.  Arrays are updated in place.
"""

from __future__ import annotations

import numpy as np

from .clusters import coincides_with_any
from .refinement import refine
from .results import SUCCESS
from .tracker import track_segment

__all__ = ["DETOUR_RADII", "DETOUR_CHORDS", "phase1_detours"]

DETOUR_RADII = (0.05, 0.15)  # radii (in t) of the half circles of phase1_detours, the smaller first
DETOUR_CHORDS = 6  # chords of a half circle


def _detours(homotopy, X0, bad, tf, distances, t_end, tr, steps, keep):
    """Track the paths ``bad`` (rows of the start points X0) from t = 1 along the real axis to t_f + d, on a half
    circle about t_f (``DETOUR_CHORDS`` chords) to t_f - d, then straight to ``t_end``, for each radius d in
    ``distances`` (arrays over ``bad``, NaN where that radius is not tried; the smaller radii first), above the
    real axis, then below.  The approach is tracked once, to t_f + the largest d and on to the smaller.
    ``keep(rows, points) -> kept rows`` decides on the points reached at ``t_end``; a kept path is not tried again.
    Steps are added to ``steps``."""
    pending = np.ones(len(bad), dtype=bool)
    starts = {}
    xa, ta, ok = X0[bad].copy(), np.ones(len(bad), dtype=complex), np.ones(len(bad), dtype=bool)
    for r in sorted(range(len(distances)), key=lambda r: -np.nanmax(distances[r], initial=0.0)):
        d = distances[r]
        tb = (tf + np.nan_to_num(d, nan=0.0)).astype(complex)
        a = np.flatnonzero(ok & np.isfinite(d) & (ta != tb))
        if a.size:
            seg = track_segment(homotopy, xa[a], ta[a], tb[a], tr)
            xa[a] = seg.x
            steps[bad[a]] += seg.steps
            ok[a] &= seg.status == SUCCESS
            ta[a] = tb[a]
        starts[r] = (xa.copy(), ok & np.isfinite(d) & (ta == tb))
    for r, side in [(r, s) for r in range(len(distances)) for s in (1.0, -1.0)]:
        xs, ok_r = starts[r]
        sel = np.flatnonzero(ok_r & pending)
        if not sel.size:
            continue
        rows, tfs, ds = bad[sel], tf[sel], distances[r][sel]
        knots = [tfs + ds * np.exp(1j * side * np.pi * k / DETOUR_CHORDS) for k in range(DETOUR_CHORDS + 1)]
        knots.append(np.full(len(rows), t_end, dtype=complex))
        xc = xs[sel].copy()
        live = np.ones(len(rows), dtype=bool)
        for t0, t1 in zip(knots[:-1], knots[1:]):
            a = np.flatnonzero(live & (t0 != t1))
            if not a.size:
                continue
            seg = track_segment(homotopy, xc[a], t0[a], t1[a], tr)
            xc[a] = seg.x
            steps[rows[a]] += seg.steps
            live[a] &= seg.status == SUCCESS
        a = np.flatnonzero(live)
        if a.size:
            kept = set(keep(rows[a], xc[a]))
            pending[sel] &= ~np.isin(rows, list(kept))


def phase1_detours(homotopy, X0, x, status, steps, retried, h, t_fail, te, tr, opts):
    """Paths that failed in phase 1 at t_f in (te, 1) (``t_fail``), tracked again around t_f (module doc) with radius
    d = min(r, 1 - t_f, t_f - te) (tried when d > 1e-3) for r = 0.05 above the real axis, then below, then r = 0.15
    above and below (``DETOUR_RADII``; the larger circle, tried on seed 000 Tests 2 and 3 and seed 002's 8-cable
    robot, rescued 4, 5 and 23 more paths in the same time), then on to te.  A point reached at te is kept
    (``retried = "detour"``) only when Newton's method converges there quadratically with a moderate condition
    number and it is distinct (each coordinate at its own scale, ``endgame.cluster_tol``) from every other path's
    point at te and from the points kept before it."""
    eo = opts.endgame
    bad = np.array([i for i in np.flatnonzero(status != SUCCESS) if te < t_fail[i].real < 1.0], dtype=int)
    if not bad.size:
        return
    tf = t_fail[bad].real
    distances = []
    for r in DETOUR_RADII:
        d = np.minimum(np.minimum(r, 1.0 - tf), tf - te)
        distances.append(np.where(d > 1e-3, d, np.nan))

    def keep(rows, points):
        xr, _, _, cond, quad = refine(homotopy, points, te, tol=eo.refine_tol)
        kept = []
        for j, i in enumerate(rows):
            if quad[j] and cond[j] <= eo.singular_condition and not coincides_with_any(x[status == SUCCESS], xr[j],
                                                                                      eo.cluster_tol):
                x[i], status[i], retried[i], h[i] = xr[j], SUCCESS, "detour", np.nan
                kept.append(i)
        return kept

    _detours(homotopy, X0, bad, tf, distances, te, tr, steps, keep)
