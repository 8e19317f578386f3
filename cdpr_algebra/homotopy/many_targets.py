"""The engine's many-target parameter homotopy: one square polynomial system F(x; p), solved for a generic complex
instance p1 once, then for every target parameter vector by :func:`solve_targets` (the DGP per taut set, the
robustness radii of cable configurations at poses, along paths and over surfaces all go through it).

:func:`solve_targets` has one pipeline (:func:`.endgame.run_pipeline`: tracking, refinement, Cauchy endgame,
re-tracking of failed and coinciding paths) and one result per target (:class:`.results.SolveResult`), run in
one of two ways:

* affine systems (the DGP) are tracked target by target by :func:`.solve.solve_parameter_homotopy`, which
  re-tracks suspect paths in projective coordinates and decides infinity in a chart (the DGP's compiled tracker
  runs paths one at a time anyway);
* systems already written in a chart of projective space (``chart=True``: unknowns (y0, y), every endpoint
  decided finite or at infinity by the endgame in that chart, :func:`.endgame.decide_in_chart`) are batched:
  every path carries its target's label k as an extra coordinate k / LABEL_SCALE, kept constant by the equation
  x_label - k / LABEL_SCALE = 0, so the paths of up to LABEL_SCALE targets are tracked together by the
  vectorized tracker (:class:`LabelledParameterHomotopy`): thousands of paths per numpy call instead of tens.
:class:`ManyTargetSolver` adds the generic solve (total degree in a random chart, :class:`ChartTotalDegreeStart`)
for systems given by sympy expressions.

Generic: imports nothing outside :mod:`cdpr_algebra.homotopy`.
"""

from __future__ import annotations

import itertools
import time
from dataclasses import replace

import numpy as np

from .endgame import EndgameOptions, SolveOptions, track_paths
from .results import FAILURES, SolveResult, TrackResult
from .solve import group_solutions, solve_parameter_homotopy
from .tracker import TrackerOptions

__all__ = ["LABEL_SCALE", "LabelledParameterHomotopy", "ChartTotalDegreeStart", "solve_targets", "ManyTargetSolver",
           "chart_options"]

LABEL_SCALE = 1024  # path label k is stored as k / LABEL_SCALE (targets per batch)


SETTLED_UPDATE = 1e-9  # a last Newton update below this (relative) ends a chart path regular (see chart_options)


def chart_options(predictor_tol: float = 1e-5, cauchy: bool = True) -> SolveOptions:
    """Options for homotopies tracked in a projective chart: a path whose last Newton update at t = 0 is below
    SETTLED_UPDATE with a moderate condition number is regular (``EndgameOptions.settled_update``: the 1e-13 floor
    of the refinement is too strict for chart points with large coordinates); double-precision retries of failed
    and coinciding paths (no arbitrary precision: the batched evaluators have none); ``cauchy=False`` for generic
    solves that keep only regular endpoints (``EndgameOptions.cauchy``)."""
    return SolveOptions(tracker=TrackerOptions(predictor_tol=predictor_tol),
                        endgame=EndgameOptions(settled_update=SETTLED_UPDATE, cauchy=cauchy), retry_tight=True,
                        retry_mpmath=False)


class ChartTotalDegreeStart:
    """H = gamma t G(Y) + (1 - t) F_h(Y; p1) with the homogenized total-degree start G_i = y_i^d_i - y0^d_i; the
    chart equation (last) is kept as is."""

    chart = True  # unknowns (y0, y) in a chart: endpoints are decided finite / at infinity there

    def __init__(self, Fh, degrees, p1, gamma):
        self.Fh, self.d, self.p1, self.gamma = Fh, np.array(degrees), np.asarray(p1, dtype=complex), complex(gamma)
        self.n = self.neq = Fh.n

    def start_solutions(self, chart) -> np.ndarray:
        """The start points y_i = root of unity * y0, in the chart ``chart``."""
        from .projective import to_chart

        roots = [np.exp(2j * np.pi * np.arange(d) / d) for d in self.d]
        return to_chart(np.array(list(itertools.product(*roots)), dtype=complex), chart)

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
    """H(Y, t) = F(Y; t p1 + (1 - t) P0[k]) for many targets P0 (K, m); path label k / LABEL_SCALE last.

    F must be affine in the parameters (e.g. the coefficients of a polynomial), so dH/dt = F(Y; p1 - p0) -
    F(Y; 0): two plain evaluations instead of the parameter Jacobian (or none, when F offers
    ``evaluate_directional(Y, P, dP)`` = (F, dF/dY, dF/dp . dP), as the DGP's systems do).  F offers ``evaluate(Y, P)`` and ``evaluate_and_jacobian(Y, P)``
    over batches with one parameter row per point (a :class:`.systems.PolynomialSystem` does).  ``chart``: the
    unknowns of F are chart coordinates (y0 first)."""

    def __init__(self, F, p1, P0, chart: bool = False):
        self.F, self.p1, self.P0 = F, np.asarray(p1, dtype=complex), np.asarray(P0, dtype=complex)
        self.n = self.neq = F.n + 1
        self.chart = True if chart else None

    def labels(self, x) -> np.ndarray:
        k = np.rint(np.nan_to_num(x[:, -1].real * LABEL_SCALE, nan=0.0, posinf=0.0, neginf=0.0))
        return np.clip(k, 0, len(self.P0) - 1).astype(int)

    def evaluate_all(self, x, t, want_t=True):
        k = self.labels(x)
        t = np.asarray(t, dtype=complex)[:, None]
        p0 = self.P0[k]
        P = t * self.p1 + (1 - t) * p0
        Y = np.ascontiguousarray(x[:, :-1])
        N = len(x)
        H = np.empty((N, self.n), dtype=complex)
        Hx = np.zeros((N, self.n, self.n), dtype=complex)
        directional = getattr(self.F, "evaluate_directional", None) if want_t else None
        if directional is not None:
            F, J, D = directional(Y, P, self.p1 - p0)
        else:
            F, J = self.F.evaluate_and_jacobian(Y, P)
        H[:, :-1] = F
        H[:, -1] = x[:, -1] - k / LABEL_SCALE
        Hx[:, :-1, :-1] = J
        Hx[:, -1, -1] = 1.0
        if not want_t:
            return H, Hx
        Ht = np.zeros((N, self.n), dtype=complex)
        if directional is not None:
            Ht[:, :-1] = D
        else:
            both = self.F.evaluate(np.concatenate([Y, Y]), np.concatenate([self.p1 - p0, np.zeros_like(p0)]))
            Ht[:, :-1] = both[:N] - both[N:]
        return H, Hx, Ht

    def evaluate_and_jacobian(self, x, t):
        return self.evaluate_all(x, t, want_t=False)

    def evaluate(self, x, t):
        return self.evaluate_all(x, t, want_t=False)[0]


def solve_targets(system, start_parameters, start_solutions, targets, seed: int = 0,
                  options: SolveOptions | None = None, chart: bool = False, **single) -> list[SolveResult]:
    """One :class:`.results.SolveResult` per row of ``targets``: the solutions of F(x; p0) = 0 reached from the
    solutions ``start_solutions`` of the generic instance F(x; p1) = 0 (module doc).  Every path has one outcome
    (regular, singular, at infinity, failed) and the solutions are grouped per target
    (:func:`.solve.group_solutions`).  ``single``: further arguments of
    :func:`.solve.solve_parameter_homotopy` for affine systems (``gamma``, ``retries``, ...)."""
    P0 = np.atleast_2d(np.asarray(targets))
    X1 = np.asarray(start_solutions, dtype=complex)
    if not chart:
        return [solve_parameter_homotopy(system, start_parameters, X1, p0, seed=seed, options=options, **single)
                for p0 in P0]
    options = options or chart_options()
    S = len(X1)
    out = []
    for lo in range(0, len(P0), LABEL_SCALE):
        idx = np.arange(lo, min(len(P0), lo + LABEL_SCALE))
        t0 = time.perf_counter()
        X0 = np.concatenate([np.tile(X1, (len(idx), 1)), np.repeat(np.arange(len(idx)) / LABEL_SCALE, S)[:, None]],
                            axis=1)
        hom = LabelledParameterHomotopy(system, start_parameters, P0[idx], chart=chart)
        tr = track_paths(hom, X0, options, seed=seed)
        seconds = (time.perf_counter() - t0) / len(idx)
        for j in range(len(idx)):
            paths = tuple(replace(p, index=p.index - j * S, endpoint=p.endpoint[:-1])
                          for p in tr.paths[j * S:(j + 1) * S])
            track = TrackResult(paths=paths, seconds=seconds, seed=seed, options=tr.options)
            out.append(SolveResult(solutions=group_solutions(track, options.duplicate_tol, options.endgame.cluster_tol),
                                   track=track, start_system="parameter"))
    return out


class ManyTargetSolver:
    """All real solutions of a square polynomial system F(x; c), affine in its parameters c, for many real
    parameter vectors: a generic complex instance solved once (total degree in a random projective chart), then
    every target by :func:`solve_targets` in that chart.  Solutions come back affine; each target's failed
    paths are counted."""

    def __init__(self, system, seed: int = 0):
        from .projective import projectivize

        self.system = system
        self.Fh, self.chart = projectivize(system, seed=20131 + seed)
        self.seed = seed
        self._generic = None

    def generic(self):
        """(p1, the finite regular solutions of F(x; p1) in the chart, paths of the total-degree run that did not end
        regular).  Only regular endpoints are kept (the solutions of a generic instance are regular), so the
        paths that do not finish regular (most go to infinity) skip the Cauchy endgame."""
        if self._generic is not None:
            return self._generic
        rng = np.random.default_rng([self.seed, 2002])
        p1 = rng.normal(size=self.system.m) + 1j * rng.normal(size=self.system.m)
        gamma = np.exp(2j * np.pi * rng.random())
        hom = ChartTotalDegreeStart(self.Fh, self.system.degrees, p1, gamma)
        tr = track_paths(hom, hom.start_solutions(self.chart), chart_options(cauchy=False), seed=self.seed)
        sols = group_solutions(tr)
        S = np.array([s.x for s in sols if not s.singular]).reshape(-1, self.Fh.n)
        self._generic = (p1, S, sum(tr.count(f) for f in FAILURES))
        return self._generic

    def solve(self, P0, real_tol: float = 1e-7):
        """For each real parameter vector: (affine real solutions (k, n), number of failed paths)."""
        p1, S, _ = self.generic()
        P0 = np.atleast_2d(np.asarray(P0, dtype=float))
        out = []
        for res, p in zip(solve_targets(self.Fh, p1, S, P0, seed=self.seed, chart=True), P0):
            Z = np.array([s.x for s in res.solutions]).reshape(-1, self.Fh.n)
            x = Z[:, 1:] / Z[:, :1] if len(Z) else np.zeros((0, self.system.n), dtype=complex)
            real = np.all(np.abs(x.imag) <= real_tol * (1 + np.abs(x)), axis=1)
            failed = sum(1 for q in res.track.paths if q.status in FAILURES)
            out.append((self._polish(x[real].real, p), failed))
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

