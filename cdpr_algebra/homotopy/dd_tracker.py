"""The step of :func:`.flint_tracker.flint_track` compiled in complex double-double arithmetic (numba).

Why.  The same 106 bits as the python-flint tracker, about 30 significant digits: enough for the paths that crawl
near singular sets with condition numbers 1e12 .. 1e17 (module doc of :mod:`.flint_tracker`), in compiled code over
a generated evaluator rewritten into double-double operations (:mod:`.double_double`; e.g.
``cdpr_algebra/generated/study_equations_dd.py``), instead of Python arithmetic on acb numbers.

What.  :func:`dd_track_kernel` tracks one path along t = t_a + s (t_b - t_a) with the parameter path of
:class:`.homotopies.ParameterHomotopy` (p(t) = (g t p1 + (1 - t) p0) / (g t + 1 - t), g = 1: straight) evaluated in
double-double (``double_double.dd_parameters``; dp/dt = (g p1 - p0 - (g - 1) p(t)) / (g t + 1 - t)): Newton's method
at t_a first, then RK4 on dx/ds = -J^-1 Ht (t_b - t_a) and three Newton updates per step, accepted and sized by the
rule of :func:`.flint_tracker.flint_track`; linear systems by Gaussian elimination with partial pivoting in
double-double (:func:`dd_solve`).  Step sizes, norms and tolerances are doubles (only their sizes matter).  The
evaluator is passed as a first-class function of type :data:`EQUATIONS_TYPE` (``compiled.function_address``).
"""

from __future__ import annotations

import numba as nb
import numpy as np
from numba import types as nbt

from .double_double import EQUATIONS_SIG, cc_add, cc_div, cc_mul, cc_sub, cr_mul, dd_parameters, to_complex, to_dd

__all__ = ["EQUATIONS_SIG", "EQUATIONS_TYPE", "DoubleDoubleParameterHomotopy", "dd_solve", "dd_track_kernel",
           "dd_track", "STATUS"]

EQUATIONS_TYPE = nbt.FunctionType(EQUATIONS_SIG)
STATUS = ("success", "too_many_steps", "step_too_small")  # the kernel's status codes 0, 1, 2

_J = dict(cache=True, error_model="numpy", nogil=True)


@nb.njit(**_J)
def _get(a, i):
    return (a[i, 0], a[i, 1], a[i, 2], a[i, 3])


@nb.njit(**_J)
def _put(a, i, v):
    a[i, 0], a[i, 1], a[i, 2], a[i, 3] = v[0], v[1], v[2], v[3]


@nb.njit(**_J)
def dd_solve(J, b, A, x) -> bool:
    """x = J^-1 b (complex double-double: J (n, n, 4), b and x (n, 4)) by Gaussian elimination with partial pivoting
    on the leading parts' moduli, A (n, n, 4) the workspace; False when a pivot is 0."""
    n = b.shape[0]
    A[:] = J
    x[:] = b
    for k in range(n):
        p, best = k, -1.0
        for i in range(k, n):
            v = A[i, k, 0] * A[i, k, 0] + A[i, k, 2] * A[i, k, 2]
            if v > best:
                p, best = i, v
        if not best > 0.0:
            return False
        if p != k:
            for j in range(n):
                for c in range(4):
                    A[k, j, c], A[p, j, c] = A[p, j, c], A[k, j, c]
            for c in range(4):
                x[k, c], x[p, c] = x[p, c], x[k, c]
        piv = (A[k, k, 0], A[k, k, 1], A[k, k, 2], A[k, k, 3])
        xk = _get(x, k)
        for i in range(k + 1, n):
            if A[i, k, 0] == 0.0 and A[i, k, 2] == 0.0 and A[i, k, 1] == 0.0 and A[i, k, 3] == 0.0:
                continue
            f = cc_div((A[i, k, 0], A[i, k, 1], A[i, k, 2], A[i, k, 3]), piv)
            for j in range(k + 1, n):
                v = cc_sub((A[i, j, 0], A[i, j, 1], A[i, j, 2], A[i, j, 3]),
                           cc_mul(f, (A[k, j, 0], A[k, j, 1], A[k, j, 2], A[k, j, 3])))
                A[i, j, 0], A[i, j, 1], A[i, j, 2], A[i, j, 3] = v[0], v[1], v[2], v[3]
            _put(x, i, cc_sub(_get(x, i), cc_mul(f, xk)))
    for i in range(n - 1, -1, -1):
        s = _get(x, i)
        for j in range(i + 1, n):
            s = cc_sub(s, cc_mul((A[i, j, 0], A[i, j, 1], A[i, j, 2], A[i, j, 3]), _get(x, j)))
        _put(x, i, cc_div(s, (A[i, i, 0], A[i, i, 1], A[i, i, 2], A[i, i, 3])))
    for i in range(n):
        if not (np.isfinite(x[i, 0]) and np.isfinite(x[i, 2])):
            return False
    return True


@nb.njit(**_J)
def _rate(p1, p0, g, t, P, DP):
    """dp/dt at t (P = p(t) in double-double): p1 - p0 on a straight segment, (g p1 - p0 - (g - 1) p) / (g t + 1 - t)
    on a gamma arc."""
    G = (g.real, 0.0, g.imag, 0.0)
    T = (t.real, 0.0, t.imag, 0.0)
    straight = g == 1.0
    s = cc_sub(cc_add(cc_mul(G, T), (1.0, 0.0, 0.0, 0.0)), T)
    gm1 = (g.real - 1.0, 0.0, g.imag, 0.0)
    for k in range(P.shape[0]):
        a = (p1[k].real, 0.0, p1[k].imag, 0.0)
        b = (p0[k].real, 0.0, p0[k].imag, 0.0)
        if straight:
            _put(DP, k, cc_sub(a, b))
        else:
            num = cc_sub(cc_sub(cc_mul(G, a), b), cc_mul(gm1, _get(P, k)))
            _put(DP, k, cc_div(num, s))


@nb.njit(**_J)
def _norm(v) -> float:
    """max_i |v_i| from the leading parts."""
    s = 0.0
    for i in range(v.shape[0]):
        a = np.sqrt(v[i, 0] * v[i, 0] + v[i, 2] * v[i, 2])
        if not a <= s:
            s = a
    return s


@nb.njit(**_J)
def _axpy(x, h, k, out):
    """out = x + h k (h a double)."""
    for i in range(x.shape[0]):
        _put(out, i, cc_add(_get(x, i), cr_mul(_get(k, i), (h, 0.0))))


@nb.njit(**_J)
def _tangent(fe, x, t, dt, p1, p0, g, P, DP, F, Jm, Ht, A, rhs, out) -> bool:
    """out = -J^-1 Ht dt at (x, t)."""
    dd_parameters(p1, p0, g, t, P)
    _rate(p1, p0, g, t, P, DP)
    fe(x, P, DP, F, Jm, Ht, True)
    d = (dt.real, 0.0, dt.imag, 0.0)
    for i in range(rhs.shape[0]):
        v = cc_mul(_get(Ht, i), d)
        _put(rhs, i, (-v[0], -v[1], -v[2], -v[3]))
    return dd_solve(Jm, rhs, A, out)


@nb.njit(**_J)
def _newton(fe, x, t, p1, p0, g, P, DP, F, Jm, Ht, A, rhs, u) -> float:
    """One Newton update of x in place at t: |u| / (1 + |x|) after it, or inf when J is singular."""
    dd_parameters(p1, p0, g, t, P)
    fe(x, P, DP, F, Jm, Ht, False)
    for i in range(rhs.shape[0]):
        _put(rhs, i, (-F[i, 0], -F[i, 1], -F[i, 2], -F[i, 3]))
    if not dd_solve(Jm, rhs, A, u):
        return np.inf
    for i in range(x.shape[0]):
        _put(x, i, cc_add(_get(x, i), _get(u, i)))
    return _norm(u) / (1.0 + _norm(x))


@nb.njit(**_J)
def dd_track_kernel(fe, x0, neq, p1, p0, g, ta, tb, predictor_tol, max_contraction, step_safety, min_step,
                    max_steps, initial_step, start_newton, X, tol_c):
    """Track x0 (complex, a solution at t_a) to t_b (module doc); the last point reached in X (n, 4) double-double.
    ``tol_c``: the Newton update (relative) below which a step's last updates need not contract further.
    Returns (status code: 0 success, 1 too_many_steps, 2 step_too_small; steps; s reached in [0, 1])."""
    n = x0.shape[0]
    P = np.zeros((p1.shape[0], 4))
    DP = np.zeros((p1.shape[0], 4))
    F = np.zeros((neq, 4))
    Jm = np.zeros((neq, n, 4))
    Ht = np.zeros((neq, 4))
    A = np.zeros((n, n, 4))
    rhs = np.zeros((n, 4))
    u = np.zeros((n, 4))
    k1 = np.zeros((n, 4))
    k2 = np.zeros((n, 4))
    k3 = np.zeros((n, 4))
    k4 = np.zeros((n, 4))
    xs = np.zeros((n, 4))
    xc = np.zeros((n, 4))
    to_dd(x0, X)
    dt = tb - ta
    for _ in range(start_newton):  # the start point onto the path at this precision
        d = _newton(fe, X, ta, p1, p0, g, P, DP, F, Jm, Ht, A, rhs, u)
        if not d > tol_c:
            break
    s, step, steps, rejected = 0.0, initial_step, 0, False
    while s < 1.0:
        if steps >= max_steps:
            return 1, steps, s
        steps += 1
        hh = min(step, 1.0 - s)
        ok = False
        d0 = np.inf
        t0 = ta + s * dt
        th = ta + (s + hh / 2) * dt
        t1 = ta + (s + hh) * dt
        good = _tangent(fe, X, t0, dt, p1, p0, g, P, DP, F, Jm, Ht, A, rhs, k1)
        if good:
            _axpy(X, hh / 2, k1, xs)
            good = _tangent(fe, xs, th, dt, p1, p0, g, P, DP, F, Jm, Ht, A, rhs, k2)
        if good:
            _axpy(X, hh / 2, k2, xs)
            good = _tangent(fe, xs, th, dt, p1, p0, g, P, DP, F, Jm, Ht, A, rhs, k3)
        if good:
            _axpy(X, hh, k3, xs)
            good = _tangent(fe, xs, t1, dt, p1, p0, g, P, DP, F, Jm, Ht, A, rhs, k4)
        if good:
            w = (hh / 6, 0.0)
            for i in range(n):
                v = cc_add(cc_add(_get(k1, i), _get(k4, i)), cr_mul(cc_add(_get(k2, i), _get(k3, i)), (2.0, 0.0)))
                _put(xc, i, cc_add(_get(X, i), cr_mul(v, w)))
            d0 = _newton(fe, xc, t1, p1, p0, g, P, DP, F, Jm, Ht, A, rhs, u)
            d1 = _newton(fe, xc, t1, p1, p0, g, P, DP, F, Jm, Ht, A, rhs, u) if np.isfinite(d0) else np.inf
            d2 = _newton(fe, xc, t1, p1, p0, g, P, DP, F, Jm, Ht, A, rhs, u) if np.isfinite(d1) else np.inf
            ok = (d0 <= predictor_tol and d1 <= max_contraction * d0 + tol_c
                  and d2 <= max(tol_c, max_contraction * d1))
        if ok:
            X[:] = xc
            s += hh
            grow = step_safety * (predictor_tol / max(d0, 1e-300)) ** 0.2
            step = hh * min(max(grow, 1.0), 1.0 if rejected else 2.5)
        else:
            if np.isfinite(d0):
                step = hh * min(max(step_safety * (predictor_tol / d0) ** 0.2, 0.1), 0.5)
            else:
                step = hh * 0.25
            if step < min_step:
                return 2, steps, s
        rejected = not ok
    return 0, steps, 1.0


CORRECTOR_FLOOR = 2.0 ** -86  # dd_track's default tol_c: Newton contracts to the last bits of double-double


def dd_track(evaluator, neq: int, p1, p0, gamma, x0, t_a, t_b, options, max_steps: int = 1000,
             initial_step: float | None = None, start_newton: int = 8, corrector_floor: float = CORRECTOR_FLOOR):
    """:func:`dd_track_kernel` for one path with a :class:`.tracker.TrackerOptions` ``options``: returns
    (x complex, t reached, status, steps).  ``evaluator``: a rewritten generated evaluator compiled with
    :data:`EQUATIONS_SIG`; ``gamma`` None for a straight segment; ``corrector_floor``: the kernel's ``tol_c``
    (a larger one, e.g. 1e-16, accepts steps whose Newton updates stop at the round-off floor of double-double
    times the condition number: near a singular limit, condition numbers of 1e10 and more)."""
    from .compiled import function_address

    x0 = np.ascontiguousarray(x0, dtype=complex)
    X = np.zeros((len(x0), 4))
    g = 1.0 + 0j if gamma is None else complex(gamma)
    o = options
    code, steps, s = dd_track_kernel(function_address(evaluator, EQUATIONS_TYPE), x0, int(neq),
                                     np.ascontiguousarray(p1, dtype=complex), np.ascontiguousarray(p0, dtype=complex),
                                     g, complex(t_a), complex(t_b), float(o.predictor_tol), float(o.max_contraction),
                                     float(o.step_safety), float(o.min_step), int(max_steps),
                                     float(o.initial_step if initial_step is None else initial_step), int(start_newton),
                                     X, float(corrector_floor))
    x = np.empty(len(x0), dtype=complex)
    to_complex(X, x)
    t = complex(t_b) if code == 0 else complex(t_a) + s * (complex(t_b) - complex(t_a))
    return x, t, STATUS[code], int(steps)


class DoubleDoubleParameterHomotopy:
    """The parameter homotopy of a :class:`.homotopies.ParameterHomotopy` (same p1, p0, gamma) over a rewritten
    double-double evaluator (:data:`EQUATIONS_SIG`), tracked by :func:`dd_track` (the interface of
    :func:`.hybrid_tracker.hybrid_track`)."""

    def __init__(self, evaluator, neq: int, p1, p0, gamma=None, corrector_floor: float = CORRECTOR_FLOOR):
        self.evaluator, self.neq = evaluator, int(neq)
        self.corrector_floor = float(corrector_floor)
        self.p1 = np.ascontiguousarray(p1, dtype=complex)
        self.p0 = np.ascontiguousarray(p0, dtype=complex)
        self.gamma = None if gamma is None else complex(gamma)

    @classmethod
    def like(cls, homotopy, evaluator, corrector_floor: float = CORRECTOR_FLOOR) -> "DoubleDoubleParameterHomotopy":
        return cls(evaluator, homotopy.neq, homotopy.p1, homotopy.p0, homotopy.gamma, corrector_floor)

    def track(self, x0, t_a, t_b, options, max_steps: int, initial_step: float | None = None):
        """:func:`dd_track` from x0 at t_a to t_b: a :class:`.hybrid_tracker.PreciseSegment`."""
        from .hybrid_tracker import PreciseSegment

        x, t, status, steps = dd_track(self.evaluator, self.neq, self.p1, self.p0, self.gamma, x0, t_a, t_b, options,
                                       max_steps, initial_step, corrector_floor=self.corrector_floor)
        return PreciseSegment(x=x, t=t, status=status, steps=steps)
