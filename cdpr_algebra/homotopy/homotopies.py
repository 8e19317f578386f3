"""Homotopies H(x, t): start system at t = 1, target system at t = 0, evaluated for many paths.

* :class:`StraightLineHomotopy` -- H(x, t) = gamma t G(x) + (1 - t) F(x) (the "gamma trick": a
  random complex gamma keeps every path regular for t in (0, 1] with probability one).
* :class:`ParameterHomotopy` -- H(x, t) = F(x; p(t)) with the straight segment
  p(t) = t p1 + (1 - t) p0 from start parameters p1 to target parameters p0, or its gamma-trick
  variant p(t) = (gamma t p1 + (1 - t) p0) / (gamma t + (1 - t)).

``t`` is complex and given per path (shape (npaths,)) so that endgames can loop around t = 0.
Every homotopy returns H, dH/dx and dH/dt for a batch of points (``evaluate_all``) and has a
scalar mpmath counterpart (``mp_evaluate_all``) for the high-precision retry.
"""

from __future__ import annotations

import numpy as np

from .systems import PolynomialSystem

__all__ = ["StraightLineHomotopy", "ParameterHomotopy"]


def _params_for(p, npts):
    return None if p is None else np.asarray(p, dtype=complex)


class StraightLineHomotopy:
    """H(x, t) = gamma t G(x; q) + (1 - t) F(x; p): G the start system, F the target system."""

    def __init__(self, start: PolynomialSystem, target: PolynomialSystem, gamma: complex,
                 start_parameters=None, target_parameters=None):
        if start.n != target.n or start.neq != target.neq:
            raise ValueError("start and target systems must have the same shape")
        self.start, self.target, self.gamma = start, target, complex(gamma)
        self.q = None if start_parameters is None else np.asarray(start_parameters, dtype=complex)
        self.p = None if target_parameters is None else np.asarray(target_parameters, dtype=complex)
        self.n = target.n
        self.neq = target.neq

    def evaluate(self, x, t):
        t = np.asarray(t, dtype=complex)[:, None]
        return self.gamma * t * self.start.evaluate(x, self.q) + (1 - t) * self.target.evaluate(x, self.p)

    def evaluate_and_jacobian(self, x, t):
        return self.evaluate_all(x, t)[:2]

    def evaluate_all(self, x, t):
        """H, dH/dx, dH/dt."""
        G, JG = self.start.evaluate_and_jacobian(x, self.q)
        F, JF = self.target.evaluate_and_jacobian(x, self.p)
        t = np.asarray(t, dtype=complex)
        a = self.gamma * t
        b = 1 - t
        H = a[:, None] * G + b[:, None] * F
        Hx = a[:, None, None] * JG + b[:, None, None] * JF
        Ht = self.gamma * G - F
        return H, Hx, Ht

    def mp_evaluate_all(self, x, t):
        import mpmath

        gF, gJ, _ = self.start.mp_functions()
        fF, fJ, _ = self.target.mp_functions()
        q = [] if self.q is None else [mpmath.mpc(v) for v in self.q]
        p = [] if self.p is None else [mpmath.mpc(v) for v in self.p]
        g = mpmath.mpc(self.gamma)
        G, JG, F, JF = gF(x, q), gJ(x, q), fF(x, p), fJ(x, p)
        return g * t * G + (1 - t) * F, g * t * JG + (1 - t) * JF, g * G - F


class ParameterHomotopy:
    """H(x, t) = F(x; p(t)), p(1) = start parameters p1, p(0) = target parameters p0."""

    def __init__(self, system: PolynomialSystem, start_parameters, target_parameters, gamma: complex | None = None):
        self.system = system
        self.p1 = np.asarray(start_parameters, dtype=complex)
        self.p0 = np.asarray(target_parameters, dtype=complex)
        if self.p1.shape != (system.m,) or self.p0.shape != (system.m,):
            raise ValueError(f"expected {system.m} parameters")
        self.gamma = None if gamma is None else complex(gamma)
        self.n = system.n
        self.neq = system.neq
        self.chart = None  # set on the projective twin: its unknowns are (y0, y) on this chart

    def projective(self, seed: int = 20131) -> "ParameterHomotopy":
        """The same parameter path for the homogenized system on a random chart (:func:`.projective.projectivize`);
        its ``chart`` attribute holds the chart's coefficients."""
        from .projective import projectivize

        proj, c = projectivize(self.system, seed)
        h = ParameterHomotopy(proj, self.p1, self.p0, gamma=self.gamma)
        h.chart = c
        return h

    def parameters_at(self, t):
        """p(t) for an array of t: shape (len(t), m); and dp/dt of the same shape."""
        t = np.asarray(t, dtype=complex)[:, None]
        if self.gamma is None:
            p = t * self.p1 + (1 - t) * self.p0
            dp = np.broadcast_to(self.p1 - self.p0, p.shape)
        else:
            a, b = self.gamma * t, 1 - t
            s = a + b
            num = a * self.p1 + b * self.p0
            p = num / s
            dp = (self.gamma * self.p1 - self.p0) / s - num * (self.gamma - 1) / s**2
        return p, dp

    def compiled_kernels(self):
        """The system's compiled kernels ``(fj, fjt, factor, apply)`` for :mod:`.compiled`, or None (numpy tracking)."""
        from . import compiled

        get = getattr(self.system, "compiled_kernels", None)
        return get() if get is not None and compiled.available() else None

    def compiled_residual_dd(self):
        """The system's residual in double-double for the compiled tracker's extended-precision Newton, or None."""
        get = getattr(self.system, "compiled_residual_dd", None)
        return get() if get is not None else None

    def path_parameters(self):
        """(p1, p0, gamma) as arrays of one row for :func:`.compiled.track_kernel` (gamma 1: straight segment)."""
        g = 1.0 if self.gamma is None else self.gamma
        extra = getattr(self.system, "kernel_constants", None)  # e.g. the chart of a homogenized system
        p1, p0 = self.p1, self.p0
        if extra is not None:
            p1, p0 = np.concatenate([p1, extra]), np.concatenate([p0, extra])
        return np.array(p1[None, :], order="C"), np.array(p0[None, :], order="C"), np.array([g], dtype=complex)

    def evaluate(self, x, t):
        p, _ = self.parameters_at(t)
        return self.system.evaluate(x, p)

    def evaluate_and_jacobian(self, x, t):
        p, _ = self.parameters_at(t)
        return self.system.evaluate_and_jacobian(x, p)

    def evaluate_all(self, x, t):
        p, dp = self.parameters_at(t)
        directional = getattr(self.system, "evaluate_directional", None)
        if directional is not None:  # F, dF/dx and dF/dp . dp without the full dF/dp
            return directional(x, p, dp)
        F, J, JP = self.system.evaluate_all(x, p)
        return F, J, np.einsum("nik,nk->ni", JP, dp)

    def mp_evaluate_all(self, x, t):
        import mpmath

        fF, fJ, fP = self.system.mp_functions()
        p1 = [mpmath.mpc(v) for v in self.p1]
        p0 = [mpmath.mpc(v) for v in self.p0]
        if self.gamma is None:
            p = [t * a + (1 - t) * b for a, b in zip(p1, p0)]
            dp = [a - b for a, b in zip(p1, p0)]
        else:
            g = mpmath.mpc(self.gamma)
            s = g * t + (1 - t)
            p = [(g * t * a + (1 - t) * b) / s for a, b in zip(p1, p0)]
            dp = [(g * a - b) / s - (g * t * a + (1 - t) * b) * (g - 1) / s**2 for a, b in zip(p1, p0)]
        F, J, JP = fF(x, p), fJ(x, p), fP(x, p)
        return F, J, JP * mpmath.matrix(dp)
