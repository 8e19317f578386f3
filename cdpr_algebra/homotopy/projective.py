"""Tracking in projective space: the homogenized system on a random affine chart.

F(x) = 0 with x = y / y0 becomes F_h(y0, y) = y0^d_i F_i(y / y0) = 0 plus the chart c0 y0 + c . y = 1 (c random
complex).  Solutions of large norm, far away in affine coordinates, are ordinary points of the chart, so paths
going there are tracked as easily as the others; a path at infinity ends with y0 -> 0.
"""

from __future__ import annotations

import weakref

import numpy as np

from .systems import PolynomialSystem

_CACHE: dict[tuple, tuple] = {}
_NUMERIC: "weakref.WeakKeyDictionary" = weakref.WeakKeyDictionary()  # per hand-written system object


def _chart(n: int, seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    c = rng.normal(size=n + 1) + 1j * rng.normal(size=n + 1)
    return c / np.linalg.norm(c)


class HomogenizedQuadratic:
    """F_h(y0, y) = y0^2 F(y / y0) of a system whose equations all have degree 2, evaluated through the
    system's own (fast) evaluators, plus the chart c . (y0, y) = 1.

    Writing F(x) = C + L x + Q(x) (constant, linear, quadratic parts): F(y) - F(-y) = 2 L y,
    F(y) + F(-y) = 2 (C + Q(y)), so F_h = y0^2 C + y0 L y + Q(y) needs F at y, -y and 0, and likewise
    dF_h/dy = y0 L + DQ(y) from J(y) +- J(-y), dF_h/dy0 = 2 y0 C + L y and dF_h/dp from dF/dp at the three
    points.  No symbolic work, so it serves hand-written evaluators (e.g. the DGP's) at their speed.
    """

    def __init__(self, system, c: np.ndarray):
        if any(d != 2 for d in system.degrees):
            raise ValueError("HomogenizedQuadratic needs every equation of degree 2")
        self.system, self.c = system, np.asarray(c, dtype=complex)
        self.n, self.neq, self.m = system.n + 1, system.neq + 1, system.m
        self.degrees = tuple(system.degrees) + (1,)

    @property
    def name(self) -> str:
        return f"{getattr(self.system, 'name', 'system')}_projective"

    @property
    def hash(self) -> str:
        """The system's hash (asked for only when needed: a lazily built system may be slow to hash)."""
        return f"{getattr(self.system, 'hash', id(self.system))}:quadratic-projective"

    def compiled_kernels(self):
        """When the system has compiled kernels: (its fj, its fjt, LU factor and apply, True), the last entry
        telling the compiled tracker to evaluate the homogenized system through them
        (:func:`.compiled.homogenized_eval`, the chart appended to the parameters); the LU pair is the system's
        ``chart_kernels()`` when it offers them (a solve that uses the structure of its homogenized Jacobian on a
        chart), else dense; None without compiled kernels."""
        get = getattr(self.system, "compiled_kernels", None)
        base = None if get is None else get()
        if base is None:
            return None
        from .compiled import dense_apply, dense_factor

        chart = getattr(self.system, "chart_kernels", None)
        factor, apply = (dense_factor, dense_apply) if chart is None else chart()
        return base[0], base[1], factor, apply, True

    def compiled_residual_dd(self):
        """The system's double-double residual: the compiled tracker homogenizes it on the chart itself."""
        get = getattr(self.system, "compiled_residual_dd", None)
        return get() if get is not None else None

    @property
    def kernel_constants(self) -> np.ndarray:
        """Appended to the parameters given to the compiled kernels: the chart."""
        return self.c

    def _parts(self, Y, p, kind):
        Y = np.atleast_2d(np.asarray(Y, dtype=complex))
        N = len(Y)
        y0, y = Y[:, 0], Y[:, 1:]
        pts = np.concatenate([y, -y, np.zeros_like(y)])
        pp = None if p is None else np.asarray(p, dtype=complex)
        if pp is not None and pp.ndim == 2:
            pp = np.concatenate([pp, pp, pp])
        if kind == 0:
            out = (self.system.evaluate(pts, pp),)
        elif kind == 1:
            out = self.system.evaluate_and_jacobian(pts, pp)
        else:
            out = self.system.evaluate_all(pts, pp)
        return N, y0, y, [(o[:N], o[N:2 * N], o[2 * N:]) for o in out]

    def _assemble(self, Y, p, kind):
        N, y0, y, parts = self._parts(Y, p, kind)
        Fp, Fm, C = parts[0]
        Ly = 0.5 * (Fp - Fm)
        a = y0[:, None]
        F = np.empty((N, self.neq), dtype=complex)
        F[:, :-1] = a * a * C + a * Ly + 0.5 * (Fp + Fm) - C
        F[:, -1] = Y @ self.c - 1
        if kind == 0:
            return (F,)
        Jp, Jm, _ = parts[1]
        J = np.zeros((N, self.neq, self.n), dtype=complex)
        J[:, :-1, 0] = 2 * a * C + Ly
        J[:, :-1, 1:] = a[:, :, None] * 0.5 * (Jp + Jm) + 0.5 * (Jp - Jm)
        J[:, -1, :] = self.c
        if kind == 1:
            return F, J
        Pp, Pm, P0 = parts[2]
        JP = np.zeros((N, self.neq, self.m), dtype=complex)
        aa = a[:, :, None]
        JP[:, :-1, :] = aa * aa * P0 + aa * 0.5 * (Pp - Pm) + 0.5 * (Pp + Pm) - P0
        return F, J, JP

    def evaluate(self, Y, p=None):
        return self._assemble(Y, p, 0)[0]

    def evaluate_and_jacobian(self, Y, p=None):
        return self._assemble(Y, p, 1)

    def evaluate_all(self, Y, p=None):
        return self._assemble(Y, p, 2)

    def mp_functions(self):
        """mpmath evaluators (F_h(Y, p), dF_h/dY, dF_h/dp), the same combination of the system's own
        ``mp_functions`` at y, -y and 0 (Newton's method in arbitrary precision on the chart)."""
        import mpmath

        fF, fJ, fP = self.system.mp_functions()
        n, m = self.system.n, self.m
        c = [mpmath.mpc(complex(v)) for v in self.c]

        def parts(Y, p, f):
            y = [Y[i + 1] for i in range(n)]
            return Y[0], f(y, p), f([-t for t in y], p), f([mpmath.mpc(0)] * n, p)

        def mF(Y, p=()):
            a, Fp, Fm, C = parts(Y, p, fF)
            out = mpmath.matrix(n + 1, 1)
            for i in range(n):
                out[i] = a * a * C[i] + a * (Fp[i] - Fm[i]) / 2 + (Fp[i] + Fm[i]) / 2 - C[i]
            out[n] = mpmath.fsum(ci * Y[j] for j, ci in enumerate(c)) - 1
            return out

        def mJ(Y, p=()):
            a, Fp, Fm, C = parts(Y, p, fF)
            _, Jp, Jm, _ = parts(Y, p, fJ)
            out = mpmath.matrix(n + 1, n + 1)
            for i in range(n):
                out[i, 0] = 2 * a * C[i] + (Fp[i] - Fm[i]) / 2
                for j in range(n):
                    out[i, j + 1] = a * (Jp[i, j] + Jm[i, j]) / 2 + (Jp[i, j] - Jm[i, j]) / 2
            for j, ci in enumerate(c):
                out[n, j] = ci
            return out

        def mP(Y, p=()):
            a, Pp, Pm, P0 = parts(Y, p, fP)
            out = mpmath.matrix(n + 1, m)
            for i in range(n):
                for k in range(m):
                    out[i, k] = a * a * P0[i, k] + a * (Pp[i, k] - Pm[i, k]) / 2 + (Pp[i, k] + Pm[i, k]) / 2 - P0[i, k]
            return out

        return mF, mJ, mP

    def evaluate_directional(self, Y, p, dp):
        """F_h, dF_h/dy and dF_h/dp . dp (same combination of the system's directional derivatives)."""
        if not hasattr(self.system, "evaluate_directional"):
            F, J, JP = self.evaluate_all(Y, p)
            return F, J, np.einsum("nik,nk->ni", JP, np.broadcast_to(np.asarray(dp, dtype=complex), JP.shape[::2]))
        F, J = self._assemble(Y, p, 1)
        Y = np.atleast_2d(np.asarray(Y, dtype=complex))
        N = len(Y)
        y0, y = Y[:, 0:1], Y[:, 1:]
        p3 = np.concatenate([p, p, p]) if np.ndim(p) == 2 else p
        dp3 = np.concatenate([dp, dp, dp]) if np.ndim(dp) == 2 else dp
        D = self.system.evaluate_directional(np.concatenate([y, -y, np.zeros_like(y)]), p3, dp3)[2]
        Dp, Dm, D0 = D[:N], D[N:2 * N], D[2 * N:]
        Ht = np.zeros((N, self.neq), dtype=complex)
        Ht[:, :-1] = y0 * y0 * D0 + y0 * 0.5 * (Dp - Dm) + 0.5 * (Dp + Dm) - D0
        return F, J, Ht


def projectivize(system, seed: int = 20131) -> tuple:
    """(homogenized system with unknowns (y0, y), chart coefficients c (n + 1,)); cached per system and seed.

    A system that is not a compiled :class:`PolynomialSystem` (a hand-written fast evaluator) and whose
    equations all have degree 2 is homogenized numerically (:class:`HomogenizedQuadratic`); otherwise the
    homogenized equations are built with sympy and compiled."""
    if not isinstance(system, PolynomialSystem):
        cached = _NUMERIC.setdefault(system, {})
        if seed not in cached:
            if not all(d == 2 for d in system.degrees):
                raise ValueError("only systems whose equations all have degree 2 are homogenized numerically")
            c = _chart(system.n, seed)
            cached[seed] = (HomogenizedQuadratic(system, c), c)
        return cached[seed]
    key = (system.hash, seed)
    if key in _CACHE:
        return _CACHE[key]
    import sympy as sp

    c = _chart(system.n, seed)
    y0 = sp.Symbol("_y0")
    ys = [sp.Symbol(f"_y_{v}") for v in system.variables]
    eqs = []
    for e, d in zip(system.equations, system.degrees):
        poly = sp.Poly(e, *system.variables)
        eqs.append(sum(coef * y0 ** (d - sum(mon)) * sp.Mul(*[y ** k for y, k in zip(ys, mon)])
                       for mon, coef in poly.terms()))
    cs = [sp.Float(v.real, 17) + sp.I * sp.Float(v.imag, 17) for v in c]
    eqs.append(cs[0] * y0 + sum(ci * y for ci, y in zip(cs[1:], ys)) - 1)
    hom = PolynomialSystem(eqs, [y0] + ys, system.parameters, name=f"{system.name}_projective")
    _CACHE[key] = (hom, c)
    return hom, c


def to_chart(X, c) -> np.ndarray:
    """Affine points (k, n) -> chart points (k, n + 1)."""
    X = np.atleast_2d(np.asarray(X, dtype=complex))
    Y = np.hstack([np.ones((len(X), 1), dtype=complex), X])
    return Y / (Y @ c)[:, None]


def from_chart(Y) -> tuple[np.ndarray, np.ndarray]:
    """Chart points -> (affine points, |y0| / |y| (0 at infinity))."""
    Y = np.atleast_2d(Y)
    y0 = Y[:, 0]
    with np.errstate(all="ignore"):
        X = Y[:, 1:] / y0[:, None]
    return X, np.abs(y0) / np.maximum(np.linalg.norm(Y, axis=1), 1e-300)
