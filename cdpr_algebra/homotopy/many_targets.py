"""Many-target parameter homotopies: one square polynomial system F(x; p) solved for many parameter vectors in one
batched run.  Every path carries its target's label k as an extra coordinate k / LABEL_SCALE, kept constant by the
equation x_label - k / LABEL_SCALE = 0, so paths of different targets are tracked together by the vectorized
tracker (:func:`.tracker.track_segment`) and the endgame pieces of :mod:`.endgame`:

* :class:`LabelledParameterHomotopy` -- H(Y, t) = F(Y; t p1 + (1 - t) P0[k]) for systems affine in p;
* :class:`ChartTotalDegreeStart` -- the homogenized total-degree start in a projective chart (the generic solve);
* :func:`track_many` -- track, refine, Cauchy endgame where needed, re-track coinciding endpoints;
* :class:`ManyTargetSolver` -- generic solve once, then every target (the robustness radii of cable
  configurations along paths and surfaces use it; the radii at a pose use :func:`track_many` with their own
  batched evaluator).

Generic: imports nothing outside :mod:`cdpr_algebra.homotopy`.
"""

from __future__ import annotations

import itertools

import numpy as np

from .endgame import EndgameOptions, cauchy_endgame, duplicate_groups, refine
from .tracker import TrackerOptions, track_segment

__all__ = ["LABEL_SCALE", "INFINITY_Y0", "ACCEPT_UPDATE", "LabelledParameterHomotopy", "ChartTotalDegreeStart",
           "track_many", "ManyTargetSolver"]

LABEL_SCALE = 1024  # path label k is stored as k / LABEL_SCALE (targets per batch)
INFINITY_Y0 = 1e-5  # chart points with |y0| <= this * |Y| are at infinity
ACCEPT_UPDATE = 1e-9  # a last Newton update below this (relative) counts as settled


def track_many(hom, X0, seed: int = 0, at_infinity=None, tracker=None, accept_update: float = ACCEPT_UPDATE):
    """Track every path of ``hom`` with the engine's tracker and endgame pieces; returns (endpoints, status).

    Phase 1 (t = 1 -> 0.1) with one tightened retry of failed paths; phase 2 (0.1 -> 0) and Newton refinement
    (:func:`.endgame.refine`): quadratic convergence and cond <= 1e10 is ``success``.  Paths that end
    with y0 ~ 0 in the chart are ``at_infinity`` without an endgame (they are of no use for a distance); the
    remaining ones go through the engine's Cauchy endgame (``singular`` when finite).  Nonsingular endpoints of
    one instance that coincide (path jumping) are re-tracked with tightened steps.  ``at_infinity(z)`` flags
    chart points at infinity (a boolean per row; default: none); ``accept_update``: the last Newton update that
    counts as settled (the refinement's 1e-13 floor is too strict for chart points with large coordinates)."""
    if at_infinity is None:
        def at_infinity(z):
            return np.zeros(len(z), dtype=bool)

    tr, eo = tracker or TrackerOptions(), EndgameOptions()
    te = eo.endgame_start

    def run(X, tro):
        N = len(X)
        xend = np.array(X, dtype=complex)
        status = np.full(N, "failed", dtype=object)
        seg = track_segment(hom, X, 1.0, te, tro)
        x1, ok1 = seg.x, seg.status == "success"
        bad = np.flatnonzero(~ok1)
        if bad.size:
            seg_b = track_segment(hom, X[bad], 1.0, te, tro.tightened())
            x1[bad] = seg_b.x
            ok1[bad] = seg_b.status == "success"
        live = np.flatnonzero(ok1)
        xend[~ok1] = x1[~ok1]
        if not live.size:
            return xend, status
        seg2 = track_segment(hom, x1[live], te, 0.0, tro)
        xr, upd, _, cond, quad = refine(hom, seg2.x, 0.0, tol=eo.refine_tol)
        # nonsingular: Newton settled (last update <= accept_update) and the Jacobian is well conditioned
        good = (seg2.status == "success") & ((upd <= accept_update) | quad) & (cond <= eo.singular_condition)
        xend[live] = np.where(good[:, None], xr, seg2.x)
        status[live[good]] = "success"
        rest = live[~good]
        if rest.size:
            inf = at_infinity(xend[rest])
            status[rest[inf]] = "at_infinity"
            rest = rest[~inf]
        if rest.size:
            eg = cauchy_endgame(hom, x1[rest], te, eo, tro)
            xend[rest] = eg.x
            for i, st, xx in zip(rest, eg.status, eg.x):
                if st == "singular":
                    if at_infinity(xx[None, :])[0]:
                        st = "at_infinity"
                    else:
                        xr1, _, _, c1_, q1 = refine(hom, xx[None, :], 0.0, tol=eo.refine_tol)
                        if q1[0] and c1_[0] <= eo.singular_condition:
                            xend[i], st = xr1[0], "success"
                status[i] = st if st in ("success", "singular", "at_infinity") else "failed"
        return xend, status

    X0 = np.asarray(X0, dtype=complex)
    xend, status = run(X0, tr)
    succ = np.flatnonzero(status == "success")
    if succ.size > 1:
        groups = duplicate_groups(xend[succ], 1e-8)
        redo = sorted({int(succ[i]) for g in groups for i in g})
        if redo:
            x2, s2 = run(X0[redo], tr.tightened(10.0))
            xend[redo], status[redo] = x2, s2
    return xend, status


class ChartTotalDegreeStart:
    """H = gamma t G(Y) + (1 - t) F_h(Y; p1) with the homogenized total-degree start G_i = y_i^d_i - y0^d_i; the
    chart equation (last) is kept as is."""

    def __init__(self, Fh, degrees, p1, gamma):
        self.Fh, self.d, self.p1, self.gamma = Fh, np.array(degrees), np.asarray(p1, dtype=complex), complex(gamma)
        self.n = self.neq = Fh.n

    def evaluate_all(self, Y, t):
        F, J = self.Fh.evaluate_and_jacobian(Y, self.p1)
        G = np.zeros_like(F)
        JG = np.zeros_like(J)
        y0 = Y[:, 0]
        for i, d in enumerate(self.d):
            G[:, i] = Y[:, i + 1] ** d - y0 ** d
            JG[:, i, i + 1] = d * Y[:, i + 1] ** (d - 1)
            JG[:, i, 0] = -d * y0 ** (d - 1)
        t = np.asarray(t, dtype=complex)
        a, b = (self.gamma * t)[:, None], (1 - t)[:, None]
        H = a * G + b * F
        Hx = a[..., None] * JG + b[..., None] * J
        H[:, -1], Hx[:, -1] = F[:, -1], J[:, -1]
        Ht = self.gamma * G - F
        Ht[:, -1] = 0
        return H, Hx, Ht

    def evaluate_and_jacobian(self, Y, t):
        return self.evaluate_all(Y, t)[:2]

    def evaluate(self, Y, t):
        return self.evaluate_all(Y, t)[0]


class LabelledParameterHomotopy:
    """H(Y, t) = F_h(Y; t p1 + (1 - t) P0[k]) for many targets P0 (K, m); path label k / LABEL_SCALE last.

    F_h must be affine in the parameters (e.g. the coefficients of a polynomial), so dH/dt = F_h(Y; p1 - p0) -
    F_h(Y; 0): two plain evaluations instead of the parameter Jacobian.  F_h offers ``evaluate(Y, P)`` and
    ``evaluate_and_jacobian(Y, P)`` over batches (a :class:`.systems.PolynomialSystem` does)."""

    def __init__(self, Fh, p1, P0):
        self.Fh, self.p1, self.P0 = Fh, np.asarray(p1, dtype=complex), np.asarray(P0, dtype=complex)
        self.n = self.neq = Fh.n + 1

    def evaluate_all(self, x, t, want_t=True):
        k = np.clip(np.rint(np.nan_to_num(x[:, -1].real * LABEL_SCALE)), 0, len(self.P0) - 1).astype(int)
        t = np.asarray(t, dtype=complex)[:, None]
        p0 = self.P0[k]
        P = t * self.p1 + (1 - t) * p0
        Y = np.ascontiguousarray(x[:, :-1])
        N = len(x)
        H = np.empty((N, self.n), dtype=complex)
        Hx = np.zeros((N, self.n, self.n), dtype=complex)
        F, J = self.Fh.evaluate_and_jacobian(Y, P)
        H[:, :-1] = F
        H[:, -1] = x[:, -1] - k / LABEL_SCALE
        Hx[:, :-1, :-1] = J
        Hx[:, -1, -1] = 1.0
        if not want_t:
            return H, Hx
        Ht = np.zeros((N, self.n), dtype=complex)
        both = self.Fh.evaluate(np.concatenate([Y, Y]), np.concatenate([self.p1 - p0, np.zeros_like(p0)]))
        Ht[:, :-1] = both[:N] - both[N:]
        return H, Hx, Ht

    def evaluate_and_jacobian(self, x, t):
        return self.evaluate_all(x, t, want_t=False)

    def evaluate(self, x, t):
        return self.evaluate_all(x, t, want_t=False)[0]


class ManyTargetSolver:
    """All real solutions of a square polynomial system F(x; c), affine in its parameters c, for many real
    parameter vectors: a generic complex instance solved once (total degree in a random projective chart), then
    every target reached by labelled parameter homotopies, up to LABEL_SCALE targets per batch.  Solutions come
    back affine; those at infinity (|y0| <= ``infinity_y0`` |Y| in the chart) are dropped, and each target's
    failed paths are counted."""

    def __init__(self, system, seed: int = 0, infinity_y0: float = INFINITY_Y0):
        from .projective import projectivize

        self.system = system
        self.infinity_y0 = float(infinity_y0)
        self.Fh, self.chart = projectivize(system, seed=20131 + seed)
        self.seed = seed
        self._generic = None

    def _at_inf(self, z):
        n1 = self.system.n + 1
        return np.abs(z[:, 0]) <= self.infinity_y0 * np.abs(z[:, :n1]).max(axis=1)

    def generic(self):
        if self._generic is not None:
            return self._generic
        from .projective import to_chart

        rng = np.random.default_rng([self.seed, 2002])
        p1 = rng.normal(size=self.system.m) + 1j * rng.normal(size=self.system.m)
        degs = self.system.degrees
        roots = [np.exp(2j * np.pi * np.arange(d) / d) for d in degs]  # y_i = root * y0
        X = np.array(list(itertools.product(*roots)), dtype=complex)
        Y0 = to_chart(X, self.chart)
        gamma = np.exp(2j * np.pi * rng.random())
        hom = ChartTotalDegreeStart(self.Fh, degs, p1, gamma)
        xend, status = track_many(hom, Y0, self.seed, at_infinity=self._at_inf)
        good = (status == "success") & ~self._at_inf(xend)
        S = xend[good]
        # distinct
        keep = []
        for i in range(len(S)):
            if all(np.abs(S[i] - S[j]).max() > 1e-8 * (1 + np.abs(S[i]).max()) for j in keep):
                keep.append(i)
        self._generic = (p1, S[keep], int(np.sum(status == "failed")))
        return self._generic

    def solve(self, P0, real_tol: float = 1e-7):
        """For each real parameter vector: (affine real solutions (k, n), number of failed paths)."""
        p1, S, _ = self.generic()
        P0 = np.atleast_2d(np.asarray(P0, dtype=float))
        out = []
        for lo in range(0, len(P0), LABEL_SCALE):
            idx = np.arange(lo, min(len(P0), lo + LABEL_SCALE))
            X0 = np.concatenate([np.tile(S, (len(idx), 1)), np.repeat((idx - lo) / LABEL_SCALE, len(S))[:, None]],
                                axis=1)
            hom = LabelledParameterHomotopy(self.Fh, p1, P0[idx])
            xend, status = track_many(hom, X0, self.seed, at_infinity=lambda z: self._at_inf(z[:, :-1]))
            for j, k in enumerate(idx):
                sl = slice(j * len(S), (j + 1) * len(S))
                z, st = xend[sl, :-1], status[sl]
                fin = ((st == "success") | (st == "singular")) & ~self._at_inf(z)
                x = z[fin, 1:] / z[fin, :1]
                real = np.all(np.abs(x.imag) <= real_tol * (1 + np.abs(x)), axis=1)
                xr = self._polish(x[real].real, P0[k])
                out.append((xr, int(np.sum(st == "failed"))))
        return out

    def _polish(self, X, p, iters=4):
        if not len(X):
            return X
        X = X.astype(complex)
        for _ in range(iters):
            F, J = self.system.evaluate_and_jacobian(X, p.astype(complex))
            try:
                d = np.linalg.solve(J, -F[..., None])[..., 0]
            except np.linalg.LinAlgError:
                break
            X = X + d.real
        return X.real
