"""Detours: a path that failed at t_f is tracked again from its start point around t_f on a half circle in the
complex t-plane, and kept only where the point it reaches cannot belong to another path.

Why a kept point is the path's own.  The solutions of H(x, t) = 0 near a t where the system is regular form N
distinct branches, and the paths of one run hold them one to one.  A detour follows another route, so it ends on
the failed path's own branch unless its half circle encloses a branch point, where it changes to a branch that
another path holds (or another failed path would have held).  So a detour's point is kept only when no other path
holds it, compared

* at t = te (:func:`phase1_detours`, a failure in (te, 1)): the system at te is generic, every path's point there is
  a regular solution, and the kept point is one that no other path reached;
* at t = 0 (:func:`endgame_detours`, a failure in (0, te] or one that the first kind left): only a regular solution
  of the target (Newton quadratic, moderate condition number) that differs from every other path's regular or
  singular endpoint is kept.  A regular root is the limit of exactly one branch, whatever the route; no path of
  the run ends there, so its branch is held by no settled path (paths at infinity and singular endpoints hold
  other branches).  Measured (twentieth session): the Study paths of seed 000 Test 3 that crawled for 3000 steps
  near t = 0.03-0.09 (N / |e|^2 ~ 1e-7 .. 1e-5) reach regular roots around t_f in 100-600 steps, the two sides on
  the two branches that meet there; Test 3 became complete without re-runs of its subproblems.

Both need every path of the run (the caller checks it: ``SolveOptions.detour_retry`` and a call given every start
point): a comparison with some of the paths proves nothing.  Arrays are updated in place.
"""

from __future__ import annotations

import numpy as np

from .clusters import coincides_with_any
from .refinement import refine
from .results import SINGULAR, STEP_TOO_SMALL, SUCCESS, TOO_MANY_STEPS
from .tracker import track_segment

__all__ = ["DETOUR_RADII", "DETOUR_CHORDS", "ENDGAME_DETOUR_FRACTIONS", "phase1_detours", "endgame_detours"]

DETOUR_RADII = (0.05, 0.15)  # radii (in t) of the half circles of phase1_detours, the smaller first
DETOUR_CHORDS = 6  # chords of a half circle
ENDGAME_DETOUR_FRACTIONS = (0.5, 0.8)  # radii of endgame_detours' half circles, fractions of min(t_f, 1 - t_f)
ENDGAME_DETOUR = "endgame_detour"  # the ``retried`` of a path kept by endgame_detours (phase1_detours: "detour")


def _detours(homotopy, X0, bad, tf, distances, t_end, tr, opts, x, status, steps, held, keep, at_infinity=None):
    """Track the paths ``bad`` (rows of the start points X0) from t = 1 along the real axis to t_f + d, on a half
    circle about t_f (``DETOUR_CHORDS`` chords) to t_f - d, then straight to ``t_end``, for each radius d in
    ``distances`` (arrays over ``bad``, NaN where that radius is not tried; the smaller radii first), above the
    real axis, then below.  The approach is tracked once, to t_f + the largest d and on to the smaller.  A point
    reached at ``t_end`` is kept when Newton's method converges there quadratically with condition number <=
    ``endgame.singular_condition``, it is not at infinity (``at_infinity(Y, accuracy)``, when given) and it differs
    (each coordinate at its own scale, ``endgame.cluster_tol``) from the points ``x`` of every path whose status is
    one of ``held`` (those kept before it included): ``keep(row, point, last update)`` records it (its status
    becomes ``success``), and the path is not tried again.  Steps are added to ``steps``."""
    eo = opts.endgame
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
        if not a.size:
            continue
        xr, upd, _, cond, quad = refine(homotopy, xc[a], t_end, tol=eo.refine_tol)
        good = quad & (cond <= eo.singular_condition)
        if at_infinity is not None and good.any():
            good[good] &= ~at_infinity(xr[good], upd[good])
        for j, k in enumerate(a):
            if good[j] and not coincides_with_any(x[np.isin(status, held)], xr[j], eo.cluster_tol):
                status[rows[k]] = SUCCESS
                keep(rows[k], xr[j], upd[j])
                pending[sel[k]] = False


def phase1_detours(homotopy, X0, x, status, steps, retried, h, t_fail, te, tr, opts):
    """Paths that failed in phase 1 at t_f in (te, 1) (``t_fail``), tracked again around t_f (module doc) with radius
    d = min(r, 1 - t_f, t_f - te) (tried when d > 1e-3) for r = 0.05 above the real axis, then below, then r = 0.15
    above and below (``DETOUR_RADII``; the larger circle, tried on seed 000 Tests 2 and 3 and seed 002's 8-cable
    robot, rescued 4, 5 and 23 more paths in the same time), then on to te.  A point reached at te is kept
    (``retried = "detour"``) only when Newton's method converges there quadratically with a moderate condition
    number and it is distinct (each coordinate at its own scale, ``endgame.cluster_tol``) from every other path's
    point at te and from the points kept before it."""
    bad = np.array([i for i in np.flatnonzero(status != SUCCESS) if te < t_fail[i].real < 1.0], dtype=int)
    if not bad.size:
        return
    tf = t_fail[bad].real
    distances = []
    for r in DETOUR_RADII:
        d = np.minimum(np.minimum(r, 1.0 - tf), tf - te)
        distances.append(np.where(d > 1e-3, d, np.nan))

    def keep(i, point, _update):
        x[i], retried[i], h[i] = point, "detour", np.nan

    _detours(homotopy, X0, bad, tf, distances, te, tr, opts, x, status, steps, (SUCCESS,), keep)


def endgame_detours(homotopy, X0, x, status, steps, retried, acc, tfin, tr, opts, at_infinity=None):
    """Paths whose tracking failed (``step_too_small``, ``too_many_steps``) at t_f = ``tfin`` in (0, 1) after phase 1
    and its detours: tracked again around t_f (module doc) with radius d = f min(t_f, 1 - t_f) for the fractions f
    of ``ENDGAME_DETOUR_FRACTIONS`` (above, then below the real axis), then straight to t = 0.  The endpoint is kept
    (``retried = "endgame_detour"``, status ``success``, ``acc`` its last Newton update, ``tfin`` 0) only when
    Newton's method converges there quadratically with condition number <= ``endgame.singular_condition``, it is
    not at infinity (``at_infinity(Y, accuracy)``, for homotopies in a projective chart), and it differs from every
    other path's regular or singular endpoint and from those kept before it."""
    bad = np.array([i for i in np.flatnonzero(np.isin(status, (STEP_TOO_SMALL, TOO_MANY_STEPS)))
                    if 0.0 < tfin[i].real < 1.0 and tfin[i].imag == 0.0], dtype=int)
    if not bad.size:
        return
    tf = tfin[bad].real
    distances = [f * np.minimum(tf, 1.0 - tf) for f in ENDGAME_DETOUR_FRACTIONS]

    def keep(i, point, update):
        x[i], retried[i], acc[i], tfin[i] = point, ENDGAME_DETOUR, update, 0.0

    _detours(homotopy, X0, bad, tf, distances, 0.0, tr, opts, x, status, steps, (SUCCESS, SINGULAR), keep,
             at_infinity)
