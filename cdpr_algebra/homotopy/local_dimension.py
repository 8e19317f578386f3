"""Numerical local dimension of the solution set of a square system F(x) = 0 at a point (positive-dimensional sets).

At a point x* of a d-dimensional component of F = 0 on which the Jacobian has rank n - d (a reduced component), the
solution set near x* is a complex manifold of dimension d tangent to the null space of J(x*).  The test
(:func:`local_dimension`):

1. x* is refined by Gauss-Newton steps restricted to the numerical rank r of J (the minimum-norm step, which
   does not move along the null space), and r is read from the singular values of the scaled Jacobian
   (columns scaled by ``scale``; the rows as the caller scales them: equilibrating rows at the point would
   hide a row that vanishes there): d = n - r singular values below ``RANK_RTOL`` sigma_1 (a
   point known to ~1e-8, as a singular endpoint is, leaves singular values ~1e-8 where the exact point has 0).
2. x* is displaced by eps (relative to 1 + |x*|) along a random direction of the numerical null space and
   projected back to F = 0 by the same restricted steps, for two eps and ``TRIALS`` directions.  On a reduced
   component of dimension d the projection reaches F = 0 to rounding with the point still ~eps from x* (the
   displacement is along the set).  At an isolated root, however singular, the displaced point's residual
   eps^2 F''(t, t) / 2 has a part no restricted step can reduce, so the projection stalls at a residual that
   grows like eps^2.

The verdict is ``positive_dimensional`` (dimension d >= 1) when every trial reaches a rounding-level residual
(``ON_SET``) at both eps, ~eps away, at a point where J keeps rank <= r; ``regular`` (dimension 0: an isolated
root) when J has full numerical rank at a refined point with a rounding-level residual; ``undecided`` otherwise
(also when the refinement reaches no such point).  Undecided covers isolated singular roots (the
projections stall) and non-reduced components (J has rank below n - d on them, so most null directions leave the
set to second order and the projections stall too): the test does not tell these apart, and says so.  A
numerical test (rounding and a finite eps), not a proof: callers label it so.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from .refinement import relative_residual

__all__ = ["ON_SET", "RANK_RTOL", "STEPS", "TRIALS", "LocalDimension", "local_dimension"]

RANK_RTOL = 1e-6  # a singular value below this times sigma_1 (scaled Jacobian) counts as zero
ON_SET = 1e-11  # relative residual (max |F| / (1 + max |x|)) of a point projected onto the solution set
STEPS = (1e-3, 1e-2)  # displacements eps, relative to 1 + max |x*|: the isolated case then stalls at ~1e-6 .. 1e-4
TRIALS = 3  # random directions of the null space per eps
NEWTON_STEPS = 12  # restricted Gauss-Newton steps per projection (quadratic on a reduced component)


@dataclass(frozen=True)
class LocalDimension:
    """The test's verdict at one point: ``verdict`` 'positive_dimensional', 'regular' or 'undecided';
    ``dimension`` d (the numerical corank of J; 0 when regular, None when undecided); ``point`` the refined point;
    ``tangent`` (n, d) an orthonormal basis of the numerical null space at it (scaled back to x's coordinates, then
    orthonormalized); ``singular_values`` of the scaled Jacobian (relative to sigma_1); ``residuals`` the relative
    residuals reached by the projections (per eps, the largest over the trials)."""

    verdict: str
    dimension: int | None
    point: np.ndarray
    tangent: np.ndarray
    singular_values: np.ndarray
    residuals: tuple

    def to_dict(self) -> dict:
        return {"verdict": self.verdict, "dimension": self.dimension,
                "smallest_singular_values": [float(s) for s in self.singular_values[-3:]],
                "projection_residuals": [float(r) for r in self.residuals]}


def _relative_residual(F, x) -> float:
    return float(relative_residual(F[None], x[None])[0])


class _Scaled:
    """F and J of ``evaluate`` at x = scale * y (J with respect to y)."""

    def __init__(self, evaluate, scale):
        self.evaluate, self.scale = evaluate, scale

    def __call__(self, y):
        F, J = self.evaluate(y * self.scale)
        return np.asarray(F, dtype=complex), np.asarray(J, dtype=complex) * self.scale[None, :]


def _svd(J):
    """(singular values relative to sigma_1, V^H) of J."""
    _, s, Vh = np.linalg.svd(J)
    return s / max(s[0], 1e-300), Vh


def _project(G, y, r, steps=NEWTON_STEPS):
    """Gauss-Newton steps restricted to rank ``r`` from y: (y, relative residual of the unscaled F at y)."""
    best = None
    for _ in range(steps):
        F, J = G(y)
        res = _relative_residual(F, y * G.scale)
        if best is None or res < best[1]:
            best = (y, res)
        if res <= 1e-15:
            break
        U, s, Vh = np.linalg.svd(J)
        step = Vh[:r].conj().T @ ((U[:, :r].conj().T @ F) / s[:r])
        if not np.all(np.isfinite(step)):
            break
        y = y - step
    F, _ = G(y)
    res = _relative_residual(F, y * G.scale)
    return (y, res) if res <= best[1] else best


def local_dimension(evaluate, x0, scale=None, seed: int = 0) -> LocalDimension:
    """The numerical local dimension of {F = 0} at (near) ``x0`` (module doc).  ``evaluate(x)`` -> (F (n,),
    J (n, n)) complex; ``scale`` (n,): the size of each unknown (default 1); ``seed``: the random directions."""
    x0 = np.asarray(x0, dtype=complex)
    n = len(x0)
    scale = np.ones(n) if scale is None else np.asarray(scale, dtype=float)
    G = _Scaled(evaluate, scale)
    y = x0 / scale
    s, _ = _svd(G(y)[1])
    r = int(np.sum(s > RANK_RTOL))
    y, res0 = _project(G, y, r)
    s, Vh = _svd(G(y)[1])
    r = int(np.sum(s > RANK_RTOL))
    d = n - r
    x = y * scale

    def result(verdict, dim, tangent=np.zeros((n, 0), complex), residuals=()):
        return LocalDimension(verdict, dim, x, tangent, s, tuple(residuals))

    if res0 > ON_SET:  # not a point of the solution set (Newton's method did not reach one)
        return result("undecided", None, residuals=(res0,))
    if d == 0:
        return result("regular", 0)
    null = Vh[r:].conj().T  # (n, d), in y
    rng = np.random.default_rng(seed)
    size = 1 + np.max(np.abs(x))
    worst, on_set = [], True
    for eps in STEPS:
        worst_eps = 0.0
        for _ in range(TRIALS):
            c = rng.normal(size=d) + 1j * rng.normal(size=d)
            t = null @ (c / np.linalg.norm(c))
            t = t / np.max(np.abs(t * scale))  # eps is a displacement of x, relative to its size
            y1, res = _project(G, y + eps * size * t, r)
            worst_eps = max(worst_eps, res)
            moved = np.max(np.abs((y1 - y) * scale)) / size
            keeps_rank = _svd(G(y1)[1])[0][r] <= RANK_RTOL
            if not (res <= ON_SET and moved >= 0.5 * eps and keeps_rank):
                on_set = False
        worst.append(worst_eps)
    tangent = null * scale[:, None]
    tangent, _ = np.linalg.qr(tangent)
    if on_set:
        return result("positive_dimensional", d, tangent, worst)
    return result("undecided", None, tangent, worst)
