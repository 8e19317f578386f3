"""Path tracking in arbitrary precision with python-flint, for the few paths that double precision loses.

Why.  Some paths pass, for a long stretch of t, so close to a singular set (on the DGP: complex poses near infinity,
Study's N = e . e -> 0) that their Jacobian's condition number reaches 1e12 .. 1e17.  Double precision then cannot
correct a predicted point to the corrector tolerance (Newton stalls at cond x eps, and double-double residuals help
only while cond x eps < 1): the step shrinks until the path fails (``too_many_steps``, ``step_too_small``).  Such a
path is smooth: with every number carried to ``prec`` bits (106: the precision of double-double) the same step
control tracks it with steps of ordinary size.

How.  :class:`FlintParameterHomotopy` is the parameter homotopy H(x, t) = F(x; p(t)) of
:class:`.homotopies.ParameterHomotopy` (the same p(t): straight segment or gamma arc) over a plain-Python
straight-line evaluator ``evaluate(x, p, dp, F, J, Ht, with_ht)`` (F, dF/dx and dF/dp . dp; the signature of the
generated evaluators, which numba compiles for the double tracker) run on python-flint ``acb`` numbers: the
evaluator is the system's one source, only the number type changes.  Every value is kept as its midpoint (the
radii are not needed: nothing here is a proof; a rescued endpoint is refined and certified like any other).
:func:`flint_track` is the double tracker's scheme (RK4 predictor, Newton corrector, predictor tolerance, step
growth and shrinking: :mod:`.tracker`), with linear systems solved by ``acb_mat.solve(algorithm="approx")``.
:func:`.hybrid_tracker.hybrid_track` tracks in double precision and hands only the stretches where it fails to an
extended-precision twin of the homotopy (this module's, or the compiled double-double one of :mod:`.dd_tracker`,
~15x faster, which the DGP uses).

Cost (measured, eighteenth session, m = 4, 12 unknowns, 106 bits): one evaluation ~0.45 ms, one step ~4 ms (RK4
and three Newton updates: 7 evaluations, 7 solves), against ~10 us in the compiled double tracker.  On the 16 Study
paths that seed 000 Test 3's DGP left failed (all runs of its subproblems), a first version of
:func:`.hybrid_tracker.hybrid_track` (without the Newton updates at the start of :func:`flint_track`) brought 11 to regular endpoints (Newton
quadratic, condition numbers 6e2 .. 2e9) with 0 .. 3200 steps in arbitrary precision; the 5 others still crawled
after 20,000.
"""

from __future__ import annotations

import numpy as np
from flint import acb, acb_mat, ctx  # imported with this module only: nothing on the double-precision path imports it

from .hybrid_tracker import PreciseSegment
from .results import STEP_TOO_SMALL, SUCCESS, TOO_MANY_STEPS

__all__ = ["FlintParameterHomotopy", "flint_track", "PRECISION"]

START_NEWTON = 8  # Newton updates at t_a that put the start point on the path at the working precision
PRECISION = 106  # bits (double-double's): enough for every path measured above; 128 tracked the same ones


def _acb(z):
    z = complex(z)
    return acb(z.real, z.imag)


def _mid(z):
    return acb(z.real.mid(), z.imag.mid())


def _complex(values) -> np.ndarray:
    return np.array([complex(v) for v in values], dtype=complex)


class FlintParameterHomotopy:
    """H(x, t) = F(x; p(t)) with p(1) = p1, p(0) = p0: straight, or with ``gamma`` p(t) = (gamma t p1 + (1 - t) p0)
    / (gamma t + 1 - t) (:meth:`.homotopies.ParameterHomotopy.parameters_at`), evaluated by the plain-Python
    ``evaluate(x, p, dp, F, J, Ht, with_ht)`` on acb numbers (``n`` unknowns, ``neq`` equations; entries of J
    outside the evaluator's pattern stay 0)."""

    def __init__(self, evaluate, n: int, neq: int, p1, p0, gamma=None):
        self.evaluate, self.n, self.neq = evaluate, int(n), int(neq)
        self.p1 = np.asarray(p1, dtype=complex)
        self.p0 = np.asarray(p0, dtype=complex)
        self.gamma = None if gamma is None else complex(gamma)
        self._acb = None

    @classmethod
    def like(cls, homotopy, evaluate) -> "FlintParameterHomotopy":
        """The twin of a :class:`.homotopies.ParameterHomotopy` (same parameter path) over ``evaluate``."""
        return cls(evaluate, homotopy.n, homotopy.neq, homotopy.p1, homotopy.p0, homotopy.gamma)

    def _ends(self):
        """p1, p0 and p1 - p0 as acb (exact: converted from doubles once)."""
        if self._acb is None:
            p1 = [_acb(v) for v in self.p1]
            p0 = [_acb(v) for v in self.p0]
            self._acb = (p1, p0, [a - b for a, b in zip(p1, p0)])
        return self._acb

    def parameters_at(self, t):
        """p(t) and dp/dt as lists of acb (at the working precision)."""
        p1, p0, diff = self._ends()
        if self.gamma is None:
            return [b + t * d for b, d in zip(p0, diff)], diff
        g = _acb(self.gamma)
        s = g * t + (1 - t)
        num = [g * t * a + (1 - t) * b for a, b in zip(p1, p0)]
        p = [_mid(v / s) for v in num]
        dp = [_mid((g * a - b) / s - v * (g - 1) / (s * s)) for a, b, v in zip(p1, p0, num)]
        return p, dp

    def track(self, x0, t_a, t_b, options, max_steps: int, initial_step: float | None = None) -> PreciseSegment:
        """:func:`flint_track` of this homotopy at ``PRECISION`` bits (the interface of :func:`.hybrid_tracker.hybrid_track`)."""
        return flint_track(self, x0, t_a, t_b, options, PRECISION, max_steps, initial_step)

    def evaluate_all(self, x, t, with_ht: bool = True):
        """(F, J, Ht) at the point x (list of acb) and t (acb): object arrays of acb."""
        p, dp = self.parameters_at(t)
        F = np.empty(self.neq, dtype=object)
        J = np.empty((self.neq, self.n), dtype=object)
        J[:] = acb(0)
        Ht = np.empty(self.neq, dtype=object)
        self.evaluate(np.array(x, dtype=object), np.array(p, dtype=object), np.array(dp, dtype=object), F, J, Ht,
                      with_ht)
        return F, J, Ht


def _solve(J, b):
    """J^{-1} b (midpoints: the approximate solver works on the midpoints of J and b), or None when J is singular at
    the working precision."""
    A = acb_mat(J.tolist() if isinstance(J, np.ndarray) else J)
    B = acb_mat([[v] for v in b])
    try:
        X = A.solve(B, algorithm="approx")
    except ZeroDivisionError:
        return None
    out = [_mid(X[r, 0]) for r in range(len(b))]
    if not all(v.real.is_finite() and v.imag.is_finite() for v in out):
        return None
    return out


def _norm(v) -> float:
    return max(abs(complex(c)) for c in v)


def flint_track(h: FlintParameterHomotopy, x0, t_a, t_b, options, prec: int = PRECISION, max_steps: int = 1000,
                initial_step: float | None = None) -> PreciseSegment:
    """Track x0 (a solution at t_a) along t = t_a + s (t_b - t_a), s: 0 -> 1, at ``prec`` bits: RK4 predictor on
    dx/ds = -H_x^{-1} H_t (t_b - t_a), three Newton updates d1, d2, d3 at t(s + h); accepted when |d1| <=
    ``options.predictor_tol`` (1 + |x|) and Newton contracts (|d2| <= ``options.max_contraction`` |d1|, |d3| <=
    max(that of d2, 2^(20 - prec))); the step grows by up to 2.5 (not right after a rejection) and shrinks by 2 .. 10
    on a rejection (:mod:`.tracker`'s rule, ``options.step_safety``).  ``options`` is a
    :class:`.tracker.TrackerOptions`; ``max_steps`` counts accepted and rejected steps; a step below
    ``options.min_step`` fails with ``step_too_small``.  x0 is first refined by Newton's method at t_a (at most
    ``START_NEWTON`` updates)."""
    o = options
    with ctx.workprec(prec):
        x = [_acb(v) for v in np.asarray(x0, dtype=complex)]
        ta, tb = _acb(t_a), _acb(t_b)
        dt = tb - ta
        s, step = 0.0, float(o.initial_step if initial_step is None else initial_step)
        tol_c = 2.0 ** (20 - prec)
        steps, rejected = 0, False

        def tangent(xx, ss):
            _, J, Ht = h.evaluate_all(xx, ta + acb(ss) * dt)
            return _solve(J, [-v * dt for v in Ht])

        def done(status):
            return PreciseSegment(x=_complex(x), t=complex(ta + acb(s) * dt), status=status, steps=steps)

        # x0 comes from a tracker in double precision that stopped where the condition number reached ~1e17: it may
        # lie off the path by far more than the predictor tolerance, and then every step would be rejected.
        for _ in range(START_NEWTON):
            F, J, _ = h.evaluate_all(x, ta, False)
            u = _solve(J, [-v for v in F])
            if u is None:
                break
            x = [_mid(a + b) for a, b in zip(x, u)]
            if _norm(u) <= tol_c * (1.0 + _norm(x)):
                break

        while s < 1.0:
            if steps >= max_steps:
                return done(TOO_MANY_STEPS)
            steps += 1
            hh = min(step, 1.0 - s)
            d = [np.inf]
            ok = False
            k1 = tangent(x, s)
            k2 = None if k1 is None else tangent([a + b * (hh / 2) for a, b in zip(x, k1)], s + hh / 2)
            k3 = None if k2 is None else tangent([a + b * (hh / 2) for a, b in zip(x, k2)], s + hh / 2)
            k4 = None if k3 is None else tangent([a + b * hh for a, b in zip(x, k3)], s + hh)
            if k4 is not None:
                xc = [_mid(a + (b1 + 2 * b2 + 2 * b3 + b4) * (hh / 6)) for a, b1, b2, b3, b4 in zip(x, k1, k2, k3, k4)]
                tn = ta + acb(s + hh) * dt
                d = []
                for _ in range(3):
                    F, J, _ = h.evaluate_all(xc, tn, False)
                    u = _solve(J, [-v for v in F])
                    if u is None:
                        d = [np.inf]
                        break
                    xc = [_mid(a + b) for a, b in zip(xc, u)]
                    d.append(_norm(u) / (1.0 + _norm(xc)))
                if len(d) == 3:
                    ok = (d[0] <= o.predictor_tol and d[1] <= o.max_contraction * d[0] + tol_c
                          and d[2] <= max(tol_c, o.max_contraction * d[1]))
            if ok:
                x, s = xc, s + hh
                grow = o.step_safety * (o.predictor_tol / max(d[0], 1e-300)) ** 0.2
                step = hh * min(max(grow, 1.0), 1.0 if rejected else 2.5)
            else:
                shrink = 0.25 if not np.isfinite(d[0]) else min(max(o.step_safety * (o.predictor_tol / d[0]) ** 0.2,
                                                                     0.1), 0.5)
                step = hh * shrink
                if step < o.min_step:
                    return done(STEP_TOO_SMALL)
            rejected = not ok
        return PreciseSegment(x=_complex(x), t=complex(t_b), status=SUCCESS, steps=steps)
