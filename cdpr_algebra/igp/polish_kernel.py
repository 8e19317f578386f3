"""Gauss-Newton polish of candidate Euler parameters on all quartics of the IGP with assigned position
(seed 004, eqs. 21, 23, 27, 28), compiled (numba): step 4 of :mod:`.position`.

For each point e (a row of E, in a chart: only the coordinates ``free`` vary), with F(e) = Q mon(e) the quartics
(coefficients Q (h, 35), monomial exponents ``mono`` (35, 4)) and J = dF/de_free:

    (J^H J + mu I) s = -J^H F,   mu = 1e-14 trace(J^H J) + 1e-300,   e_free <- e_free + s,

until max |s| / max(1, max |e|) < 1e-11 (quadratic convergence: the error left is ~ its square), at most
``iters`` times, or until e is no longer finite.  Then the relative residual max_h |F_h(e)| / (|Q_h| |mon(e)|)
(Euclidean norms; a zero norm counts as 1; +inf for a point that is not finite) is written to ``residual``.
``iters = 0`` only evaluates the residual.  Real points are polished in real arithmetic, complex ones in complex.
"""

from __future__ import annotations

import numba as nb
import numpy as np
from numba import types as nbt

__all__ = ["polish_quartics"]


def _signature(scalar):
    return nbt.void(nbt.float64[:, ::1], nbt.int64[:, ::1], scalar[:, ::1], nbt.int64[::1], nbt.int64,
                    nbt.float64[::1])


@nb.njit(cache=True, nogil=True)
def _powers(e, pw):
    for v in range(4):
        pw[v, 0] = 1.0
        for p in range(1, 5):
            pw[v, p] = pw[v, p - 1] * e[v]


@nb.njit(cache=True, nogil=True)
def _solve_in_place(N, g):
    """N s = g by Gaussian elimination with partial pivoting (N small, overwritten); s replaces g."""
    n = g.size
    for k in range(n):
        p = k
        for i in range(k + 1, n):
            if abs(N[i, k]) > abs(N[p, k]):
                p = i
        if p != k:
            for j in range(n):
                N[k, j], N[p, j] = N[p, j], N[k, j]
            g[k], g[p] = g[p], g[k]
        for i in range(k + 1, n):
            f = N[i, k] / N[k, k]
            for j in range(k, n):
                N[i, j] -= f * N[k, j]
            g[i] -= f * g[k]
    for k in range(n - 1, -1, -1):
        s = g[k]
        for j in range(k + 1, n):
            s -= N[k, j] * g[j]
        g[k] = s / N[k, k]


@nb.njit([_signature(nbt.float64), _signature(nbt.complex128)], cache=True, error_model="numpy", nogil=True)
def polish_quartics(Q, mono, E, free, iters, residual):
    """Polish the rows of E in place (module docstring) and write their relative residuals."""
    K = E.shape[0]
    h, nm = Q.shape
    nf = free.size
    dt = E.dtype
    pw = np.empty((4, 5), dtype=dt)
    mon = np.empty(nm, dtype=dt)
    F = np.empty(h, dtype=dt)
    J = np.empty((h, nf), dtype=dt)
    N = np.empty((nf, nf), dtype=dt)
    g = np.empty(nf, dtype=dt)
    qn = np.empty(h)
    for q in range(h):
        s = 0.0
        for m in range(nm):
            s += Q[q, m] * Q[q, m]
        qn[q] = np.sqrt(s)
    for i in range(K):
        e = E[i]
        for _ in range(iters):
            _powers(e, pw)
            F[:] = 0.0
            J[:] = 0.0
            for m in range(nm):
                a0, a1, a2, a3 = mono[m, 0], mono[m, 1], mono[m, 2], mono[m, 3]
                mv = pw[0, a0] * pw[1, a1] * pw[2, a2] * pw[3, a3]
                for q in range(h):
                    F[q] += Q[q, m] * mv
                for k in range(nf):
                    v = free[k]
                    a = mono[m, v]
                    if a == 0:
                        continue
                    d = float(a)
                    for u in range(4):
                        d = d * (pw[u, mono[m, u] - 1] if u == v else pw[u, mono[m, u]])
                    for q in range(h):
                        J[q, k] += Q[q, m] * d
            trace = 0.0
            for a in range(nf):
                ga = 0.0 * F[0]
                for q in range(h):
                    ga -= np.conj(J[q, a]) * F[q]
                g[a] = ga
                for b in range(nf):
                    s = 0.0 * F[0]
                    for q in range(h):
                        s += np.conj(J[q, a]) * J[q, b]
                    N[a, b] = s
                trace += N[a, a].real
            mu = 1e-14 * trace + 1e-300
            for a in range(nf):
                N[a, a] += mu
            _solve_in_place(N, g)
            step = 0.0
            for k in range(nf):
                if not np.isfinite(g[k]):
                    g[k] = 0.0
                e[free[k]] += g[k]
                step = max(step, abs(g[k]))
            finite = True
            big = 1.0
            for u in range(4):
                finite = finite and np.isfinite(e[u])
                big = max(big, abs(e[u]))
            if not finite or step / big < 1e-11:
                break
        finite = True
        for u in range(4):
            finite = finite and np.isfinite(e[u])
        if not finite:
            residual[i] = np.inf
            continue
        _powers(e, pw)
        mn = 0.0
        for m in range(nm):
            mv = pw[0, mono[m, 0]] * pw[1, mono[m, 1]] * pw[2, mono[m, 2]] * pw[3, mono[m, 3]]
            mon[m] = mv
            mn += abs(mv) ** 2
        mn = np.sqrt(mn)
        worst = 0.0
        for q in range(h):
            f = 0.0 * mon[0]
            for m in range(nm):
                f += Q[q, m] * mon[m]
            scale = mn * qn[q]
            if scale == 0.0:
                scale = 1.0
            r = abs(f) / scale
            if not np.isfinite(r):  # overflow: not a verified root
                worst = np.inf
                break
            worst = max(worst, r)
        residual[i] = worst
