"""Compiled path tracker (numba): the RK4 / Newton step of :mod:`.tracker`, one path at a time in machine code.

Why. The numpy tracker steps all paths together, so each step costs a fixed ~10 numpy calls per stage
whatever the number of paths; a DGP subproblem needs a few hundred sequential steps, and the per-call
overhead (not arithmetic) dominated its time.  Here every path runs its own loop of compiled scalar code.

:func:`track_kernel`: per path, along t(s) = t_a + s (t_b - t_a), the step of :func:`.tracker.track_segment`
(classical RK4 predictor on dx/ds = -H_x^{-1} H_t dt, Newton corrections, the same acceptance tests,
step-size rule and failure codes) for the parameter homotopy p(t) = (gamma t p1 + (1 - t) p0) / (gamma t + 1 - t)
(gamma = 1: the straight segment), with per-path (p1, p0, gamma) allowed so that paths of several homotopies
of one family can run in one call.  Linear algebra: LU factors with partial pivoting, and two reuses of them
(4 factorizations per step instead of 6): the second and later Newton corrections are chord steps with the
factors of the first (the second update is the same to first order, so the contraction test keeps its meaning;
chord steps contract linearly, hence up to ``TrackerOptions.max_updates`` of them on ill-conditioned stretches),
and after an accepted step those factors (H_x at the predicted point, within the predictor error of the new
point) give the next step's RK4 stage k1; after a rejected step k1 is kept (it does not depend on the step size).
The system enters as four compiled functions with fixed signatures, passed as first-class functions (so the
tracker is compiled and cached once for every system): ``fj(x, p, F, J)`` (F and dF/dx),
``fjt(x, p, dp, F, J, Ht)`` (also Ht = dF/dp . dp), ``factor(J, A, piv) -> bool`` (LU factors of J in the
workspace A; False when singular) and ``apply(J, A, piv, b, out)`` (out = J^{-1} b from them):
:func:`dense_factor` / :func:`dense_apply`, or ones that use the system's structure.  A system offers them by a
method ``compiled_kernels()`` (the DGP: :mod:`cdpr_algebra.dgp.kernels`).  Compiling sympy-generated
fully unrolled straight-line code with numba was measured at 15-30 s for the 3-cable DGP system (821 lines;
110 s for 6 cables); the DGP's evaluator is instead generated as a loop over the cables of a per-cable template
(``derivations/derive_taut_equations.py``), one function for every m, compiled in a few seconds.

numba caches compiled code on disk per source file and does not notice edits of another module that a cached
function calls: after editing this module, delete ``__pycache__/*.nbi`` / ``*.nbc`` next to ``dgp_kernels.py`` too
(a fresh install is safe: every file is new).
"""

from __future__ import annotations

import os

import numpy as np

import numba as nb
from numba import types as nbt

from .double_double import RESIDUAL_SIG, cc_add, cc_mul, cc_sub, dd_parameters, to_complex, to_dd

__all__ = ["available", "track_kernel", "track_segment_compiled", "residual_dd", "lu_factor_sparse_lead",
           "lu_apply_sparse_lead",
           "dense_factor", "dense_apply", "solve_with", "homogenized_eval", "homogenized_eval_typed", "homogenized_workspace", "FACTOR_SIG",
           "APPLY_SIG"]

# status codes of the kernel (mapped to the strings of .results by the caller)
RUNNING, OK, STEP_TOO_SMALL, TOO_MANY_STEPS, DIVERGED = 0, 1, 2, 3, 4


def available() -> bool:
    """False when the environment variable CDPR_ALGEBRA_NO_NUMBA is set (then the numpy tracker runs)."""
    return not os.environ.get("CDPR_ALGEBRA_NO_NUMBA")


# ---------------------------------------------------------------------------------------------
# the tracker
# ---------------------------------------------------------------------------------------------
_C1 = nbt.complex128[::1]
_C2 = nbt.complex128[:, ::1]
_FJ = nbt.FunctionType(nbt.void(_C1, _C1, _C1, _C2))
_FJT = nbt.FunctionType(nbt.void(_C1, _C1, _C1, _C1, _C2, _C1))

_I1 = nbt.int64[::1]
FACTOR_SIG = nbt.boolean(_C2, _C2, _I1)
APPLY_SIG = nbt.void(_C2, _C2, _I1, _C1, _C1)
_FACTOR = nbt.FunctionType(FACTOR_SIG)
_APPLY = nbt.FunctionType(APPLY_SIG)
_RES = nbt.FunctionType(RESIDUAL_SIG)


@nb.njit(RESIDUAL_SIG, cache=True)
def no_residual_dd(x, p, F):
    """The residual argument of :func:`track_kernel` for a system without a double-double residual (never called:
    the kernel's ``opts`` say so)."""
    return


@nb.njit(cache=True, error_model="numpy")
def lu_factor_sparse_lead(A, piv, k, m, r):
    """LU factors of A[:k, :k] in place by Gaussian elimination with partial pivoting (pivot rows in piv[:k],
    multipliers below the diagonal; rows are swapped from the pivot column on, so :func:`lu_apply_sparse_lead`
    replays the elimination on a right-hand side).  For a matrix whose first m columns vanish below row r
    (m <= r), the pivot search and elimination of those columns visit rows < r only (the rows below hold exact
    zeros there, so the factors are those of the full elimination).  False for a zero or non-finite pivot."""
    for c in range(k):
        last = r if c < m else k
        p = c
        best = abs(A[c, c].real) + abs(A[c, c].imag)
        for i in range(c + 1, last):
            v = abs(A[i, c].real) + abs(A[i, c].imag)
            if v > best:
                best, p = v, i
        if best == 0.0 or not np.isfinite(best):
            return False
        piv[c] = p
        if p != c:
            for j in range(c, k):
                A[c, j], A[p, j] = A[p, j], A[c, j]
        inv = 1.0 / A[c, c]
        for i in range(c + 1, last):
            f = A[i, c] * inv
            A[i, c] = f
            if f != 0:
                for j in range(c + 1, k):
                    A[i, j] -= f * A[c, j]
    return True


@nb.njit(cache=True, error_model="numpy")
def lu_apply_sparse_lead(A, piv, x, k, m, r):
    """x[:k] <- A[:k, :k]^{-1} x[:k] from the factors of :func:`lu_factor_sparse_lead` (same k, m, r)."""
    for c in range(k):
        last = r if c < m else k
        p = piv[c]
        if p != c:
            x[c], x[p] = x[p], x[c]
        xc = x[c]
        if xc != 0:
            for i in range(c + 1, last):
                x[i] -= A[i, c] * xc
    for c in range(k - 1, -1, -1):
        acc = x[c]
        for j in range(c + 1, k):
            acc -= A[c, j] * x[j]
        x[c] = acc / A[c, c]


@nb.njit(FACTOR_SIG, cache=True, error_model="numpy")
def dense_factor(J, A, piv):
    """LU factors of the square J in the workspace A (J untouched); False when J is (numerically) singular."""
    n = J.shape[0]
    for i in range(n):
        for j in range(n):
            A[i, j] = J[i, j]
    return lu_factor_sparse_lead(A, piv, n, 0, n)


@nb.njit(APPLY_SIG, cache=True, error_model="numpy")
def dense_apply(J, A, piv, b, out):
    """out = J^{-1} b from the factors of :func:`dense_factor`."""
    n = b.shape[0]
    for i in range(n):
        out[i] = b[i]
    lu_apply_sparse_lead(A, piv, out, n, 0, n)


@nb.njit(cache=True, error_model="numpy")
def homogenized_eval(fj, fjt, y, p, dp, F, J, Ht, with_ht, pa, dpa, V, M, known):
    """The homogenized system of a system whose equations all have degree 2, on a chart, from the system's own
    kernels ``fj`` / ``fjt`` (see :class:`.projective.HomogenizedQuadratic`, the numpy twin): unknowns y = (y0, y_1..y_n),
    parameters p = (the system's parameters, chart c (n + 1)); rows 0..n-1 are F_h(y0, y) = y0^2 F(y / y0) =
    y0^2 C + y0 L y + Q(y), from F at y, -y and 0 (F(y) - F(-y) = 2 L y, F(y) + F(-y) = 2 (C + Q(y))), row n the
    chart c . y - 1.  dF_h/dy = y0 L + DQ(y) from J(y) +- J(-y), dF_h/dy0 = 2 y0 C + L y, and Ht (with
    ``with_ht``) the same combination of the system's Ht at the three points (the chart does not move: dp = 0
    on its entries).  J must be zero where the system's kernel writes nothing (its caller zeroes it once).
    Workspace (:func:`homogenized_workspace`, allocated once per track, not per call): pa, dpa (the system's
    parameters), V (9, n) and M (3, n, n), zeroed once (the kernel rewrites the same entries every call and row 2
    of V, the origin, stays zero), and ``known`` (1 entry: 0 nothing, 1 F and J at the origin, 2 also Ht there):
    the values at the origin depend on the parameters only, so while pa (and, for Ht, dpa) are those of the last
    evaluation they are reused (the RK stages k2 and k3 share t, and so do k4 and the Newton corrections: about a
    third fewer evaluations; the same numbers)."""
    n1 = y.shape[0]
    n = n1 - 1
    ma = pa.shape[0]
    same_p = known[0] > 0
    same_dp = known[0] == 2
    for k in range(ma):
        if pa[k] != p[k]:
            same_p = False
            pa[k] = p[k]
        if dpa[k] != dp[k]:
            same_dp = False
            dpa[k] = dp[k]
    xp, xm, x0 = V[0], V[1], V[2]
    Fp, Fm, F0 = V[3], V[4], V[5]
    Hp, Hm, H0 = V[6], V[7], V[8]
    Jp, Jm, J0 = M[0], M[1], M[2]
    for j in range(n):
        xp[j] = y[j + 1]
        xm[j] = -y[j + 1]
    if with_ht:
        fjt(xp, pa, dpa, Fp, Jp, Hp)
        fjt(xm, pa, dpa, Fm, Jm, Hm)
        if not (same_p and same_dp):
            fjt(x0, pa, dpa, F0, J0, H0)
            known[0] = 2
    else:  # no Ht: the cheaper kernel
        fj(xp, pa, Fp, Jp)
        fj(xm, pa, Fm, Jm)
        if not same_p:
            fj(x0, pa, F0, J0)
            known[0] = 1
    y0 = y[0]
    for i in range(n):
        L = 0.5 * (Fp[i] - Fm[i])
        F[i] = y0 * y0 * F0[i] + y0 * L + 0.5 * (Fp[i] + Fm[i]) - F0[i]
        J[i, 0] = 2.0 * y0 * F0[i] + L
        for j in range(n):
            J[i, j + 1] = y0 * 0.5 * (Jp[i, j] + Jm[i, j]) + 0.5 * (Jp[i, j] - Jm[i, j])
        if with_ht:
            Ht[i] = y0 * y0 * H0[i] + y0 * 0.5 * (Hp[i] - Hm[i]) + 0.5 * (Hp[i] + Hm[i]) - H0[i]
    acc = -1.0 + 0j
    for j in range(n1):
        acc += p[ma + j] * y[j]
        J[n, j] = p[ma + j]
    F[n] = acc
    if with_ht:
        Ht[n] = 0.0


@nb.njit(nbt.void(_FJ, _FJT, _C1, _C1, _C1, _C1, _C2, _C1, nbt.boolean, _C1, _C1, _C2, nbt.complex128[:, :, ::1], _I1),
         cache=True, error_model="numpy")
def homogenized_eval_typed(fj, fjt, y, p, dp, F, J, Ht, with_ht, pa, dpa, V, M, known):
    """:func:`homogenized_eval` with the system's kernels as first-class functions of the tracker's signatures, for
    calls from Python (checks and tests): compiled and cached once, as inside :func:`track_kernel` (called with the
    kernels' dispatchers, the untyped function compiles a new specialization, about 100 s, on every run)."""
    homogenized_eval(fj, fjt, y, p, dp, F, J, Ht, with_ht, pa, dpa, V, M, known)


@nb.njit(cache=True)
def homogenized_workspace(n1, mp, hom):
    """(pa, dpa, V, M, known) for :func:`homogenized_eval` of a chart system with n1 unknowns and mp parameters (the
    system's and the chart's); empty when ``hom`` is False."""
    if not hom:
        return (np.zeros(0, np.complex128), np.zeros(0, np.complex128), np.zeros((9, 0), np.complex128),
                np.zeros((3, 0, 0), np.complex128), np.zeros(1, np.int64))
    n = n1 - 1
    return (np.zeros(mp - n1, np.complex128), np.zeros(mp - n1, np.complex128), np.zeros((9, n), np.complex128),
            np.zeros((3, n, n), np.complex128), np.zeros(1, np.int64))


def solve_with(factor, apply, J, b):
    """J^{-1} b by a (factor, apply) pair of compiled kernels, from Python (checks and tests); None when the
    factorization fails (J singular)."""
    J = np.ascontiguousarray(J, dtype=complex)
    n = J.shape[1]
    A = np.zeros((n, n), complex)
    piv = np.zeros(n, np.int64)
    if not factor(J, A, piv):
        return None
    out = np.empty(n, complex)
    apply(J, A, piv, np.ascontiguousarray(b, dtype=complex), out)
    return out


@nb.njit(cache=True)
def _dd_workspace(n1, mp, hom):
    """(Xd, Pd, Fd, S) for :func:`_dd_rhs`: the point, the parameters and F in double-double, and (hom) the system's
    point and its F at y, -y, 0."""
    n = n1 - 1 if hom else n1
    return np.zeros((n1, 4)), np.zeros((mp, 4)), np.zeros((n1, 4)), np.zeros((4, n, 4))


@nb.njit(cache=True, error_model="numpy")
def _dd_rhs(fres, hom, x, p1, p0, g, t, rhs, F, Xd, Pd, Fd, S):
    """rhs = -F(x) at t with F evaluated in double-double and rounded (x, p1, p0, g, t in double; the parameter
    path p(t) in double-double by :func:`.double_double.dd_parameters`); ``hom``: F of the homogenized system on
    the chart that ends the parameters, F_h = y0^2 F(0) + y0 (F(y) - F(-y)) / 2 + (F(y) + F(-y)) / 2 - F(0) and
    the chart row c . y - 1 (:func:`homogenized_eval`), every term in double-double."""
    n1 = x.shape[0]
    if not hom:
        dd_parameters(p1, p0, g, t, Pd)
        to_dd(x, Xd)
        fres(Xd, Pd, Fd)
        to_complex(Fd, F)
    else:
        n = n1 - 1
        ma = p1.shape[0] - n1
        dd_parameters(p1[:ma], p0[:ma], g, t, Pd[:ma])
        Pa = Pd[:ma]
        Y, Fp, Fm, F0 = S[0], S[1], S[2], S[3]
        for j in range(n):
            Y[j, 0], Y[j, 1], Y[j, 2], Y[j, 3] = x[j + 1].real, 0.0, x[j + 1].imag, 0.0
        fres(Y, Pa, Fp)
        for j in range(n):
            Y[j, 0], Y[j, 2] = -Y[j, 0], -Y[j, 2]
        fres(Y, Pa, Fm)
        for j in range(n):
            Y[j, 0], Y[j, 2] = 0.0, 0.0
        fres(Y, Pa, F0)
        y0 = (x[0].real, 0.0, x[0].imag, 0.0)
        y00 = cc_mul(y0, y0)
        for i in range(n):
            fp = (Fp[i, 0], Fp[i, 1], Fp[i, 2], Fp[i, 3])
            fm = (Fm[i, 0], Fm[i, 1], Fm[i, 2], Fm[i, 3])
            f0 = (F0[i, 0], F0[i, 1], F0[i, 2], F0[i, 3])
            d = cc_sub(fp, fm)
            e = cc_add(fp, fm)
            half_d = (0.5 * d[0], 0.5 * d[1], 0.5 * d[2], 0.5 * d[3])
            half_e = (0.5 * e[0], 0.5 * e[1], 0.5 * e[2], 0.5 * e[3])
            v = cc_sub(cc_add(cc_add(cc_mul(y00, f0), cc_mul(y0, half_d)), half_e), f0)
            Fd[i, 0], Fd[i, 1], Fd[i, 2], Fd[i, 3] = v[0], v[1], v[2], v[3]
        acc = (-1.0, 0.0, 0.0, 0.0)
        for j in range(n1):
            c = p1[ma + j]
            acc = cc_add(acc, cc_mul((c.real, 0.0, c.imag, 0.0), (x[j].real, 0.0, x[j].imag, 0.0)))
        Fd[n, 0], Fd[n, 1], Fd[n, 2], Fd[n, 3] = acc[0], acc[1], acc[2], acc[3]
        to_complex(Fd, F)
    for i in range(rhs.shape[0]):
        rhs[i] = -F[i]


@nb.njit(nbt.void(_RES, nbt.boolean, _C2, _C2, _C2, _C1, _C1, _C2), cache=True, error_model="numpy")
def residual_dd_batch(fres, hom, X, P1, P0, G, T, out):
    """Rows of ``out``: F at the rows of X at t = T[i] (the parameter path of :func:`track_kernel`, rows of P1, P0,
    G per point or row 0 for all) evaluated in double-double by :func:`_dd_rhs` and rounded."""
    N, n = X.shape
    Xd, Pd, Fd, Sd = _dd_workspace(n, P1.shape[1], hom)
    rhs = np.empty(n, np.complex128)
    F = np.empty(n, np.complex128)
    for i in range(N):
        r = i if P1.shape[0] == N else 0
        _dd_rhs(fres, hom, X[i], P1[r], P0[r], G[r], T[i], rhs, F, Xd, Pd, Fd, Sd)
        for k in range(n):
            out[i, k] = F[k]


class _FunctionAddress:
    """A compiled function passed to the kernels by the address of numba's C wrapper of it, looked up once, with its
    numba type given as ``_numba_type_`` (numba's typeof protocol) and its address by ``__wrapper_address__``
    (numba's wrapper address protocol; :class:`numba.core.types.function_type.CompileResultWAP` computes it).

    Why.  numba unboxes a dispatcher passed as a first-class function argument by looking up its compile result
    and both its addresses on every call of the kernel, and types any wrapper-address object by building a new
    FunctionType from its signature (a few hundred us per :func:`track_kernel` call with five functions; the
    DGP's endgame and detours make thousands of calls with few paths: 15,677 on seed 002's serial DGP).
    ``benchmarks/bench_segment_call.py`` measures the cost of a call.  It keeps the dispatcher alive."""

    __slots__ = ("dispatcher", "_numba_type_", "_address")

    def __init__(self, dispatcher, fntype):
        from numba.core.types.function_type import CompileResultWAP

        self.dispatcher = dispatcher
        self._numba_type_ = fntype
        self._address = CompileResultWAP(dispatcher.get_compile_result(fntype.signature)).address

    def __wrapper_address__(self):
        return self._address

    def signature(self):
        return self._numba_type_.signature


_ADDRESSES: dict = {}


def function_address(func, fntype):
    """``func`` (a numba dispatcher) as a :class:`_FunctionAddress` of the first-class function type ``fntype``
    (cached per dispatcher and type); other objects as they are."""
    if not isinstance(func, nb.core.registry.CPUDispatcher):
        return func
    key = (id(func), id(fntype))
    got = _ADDRESSES.get(key)
    if got is None or got.dispatcher is not func:
        got = _ADDRESSES[key] = _FunctionAddress(func, fntype)
    return got


def _compiled_parts(homotopy):
    """(fj, fjt, factor, apply, hom, fres) of a homotopy for the compiled tracker: its system's kernels, whether the
    system is homogenized on a chart, and its double-double residual (None when it offers none); None without
    compiled kernels."""
    kernels = getattr(homotopy, "compiled_kernels", None)
    kern = kernels() if kernels is not None else None
    if kern is None:
        return None
    get = getattr(homotopy, "compiled_residual_dd", None)
    fres = get() if get is not None else None
    fj, fjt, factor, apply = (function_address(f, t) for f, t in zip(kern[:4], (_FJ, _FJT, _FACTOR, _APPLY)))
    fres = None if fres is None else function_address(fres, _RES)
    return fj, fjt, factor, apply, bool(kern[4]) if len(kern) > 4 else False, fres


def residual_dd(homotopy):
    """``evaluate(x, t)``: H(x, t) at the rows of x evaluated in double-double and rounded, for a parameter homotopy
    (or its projective twin) whose system offers a double-double residual and compiled kernels; None otherwise."""
    parts = _compiled_parts(homotopy)
    if parts is None or parts[5] is None:
        return None
    hom, fres = parts[4], parts[5]
    P1, P0, G = homotopy.path_parameters()

    def evaluate(x, t):
        X = np.array(x, dtype=complex, order="C")
        T = np.array(np.broadcast_to(np.asarray(t, dtype=complex), (len(X),)), order="C")
        out = np.empty_like(X)
        if len(X):
            residual_dd_batch(fres, hom, X, P1, P0, G, T, out)
        return out

    return evaluate


@nb.njit(cache=True, error_model="numpy")
def _norm(v):
    s = 0.0
    for i in range(v.shape[0]):
        s += v[i].real * v[i].real + v[i].imag * v[i].imag
    return np.sqrt(s)

@nb.njit(cache=True, error_model="numpy", inline="always")
def _params(p1, p0, g, t, p, dp):
    """p(t) = (g t p1 + (1 - t) p0) / (g t + 1 - t) and dp/dt (one complex reciprocal, not two divisions per
    parameter: this runs five times a step)."""
    a = g * t
    b = 1.0 - t
    inv = 1.0 / (a + b)
    for k in range(p.shape[0]):
        pk = (a * p1[k] + b * p0[k]) * inv
        p[k] = pk
        dp[k] = (g * p1[k] - p0[k] - pk * (g - 1.0)) * inv

@nb.njit(cache=True, error_model="numpy", inline="always")
def _lin(ok, apply, J, A, piv, b, out):
    """out = J^{-1} b from factors of J (NaNs when the factorization failed)."""
    if ok:
        apply(J, A, piv, b, out)
    else:
        for i in range(out.shape[0]):
            out[i] = np.nan


@nb.njit(cache=True, error_model="numpy", inline="always")
def _tangent_rhs(fj, fjt, hom, x, t, dt, p1, p0, g, p, dp, F, J, Ht, rhs, ws):
    """rhs = -H_t dt at (x, t) (fjt also writes F and H_x into F and J; ``hom``: of the homogenized system, with
    the workspace ``ws`` of :func:`homogenized_workspace`)."""
    _params(p1, p0, g, t, p, dp)
    if hom:
        homogenized_eval(fj, fjt, x, p, dp, F, J, Ht, True, ws[0], ws[1], ws[2], ws[3], ws[4])
    else:
        fjt(x, p, dp, F, J, Ht)
    for i in range(rhs.shape[0]):
        rhs[i] = -Ht[i] * dt


@nb.njit(cache=True, error_model="numpy", inline="always")
def _newton_rhs(fj, fjt, hom, x, p, F, J, rhs, ws):
    """rhs = -F(x) at the parameters p (fj also writes H_x into J; ``hom``: of the homogenized system, workspace
    ``ws``)."""
    if hom:
        homogenized_eval(fj, fjt, x, p, p, F, J, F, False, ws[0], ws[1], ws[2], ws[3], ws[4])
    else:
        fj(x, p, F, J)
    for i in range(rhs.shape[0]):
        rhs[i] = -F[i]


@nb.njit(cache=True, error_model="numpy", inline="always")
def _stage(fj, fjt, hom, factor, apply, x, t, dt, p1, p0, g, p, dp, F, J, Ht, A, piv, rhs, k, ws):
    """k = dx/ds = -H_x^{-1} H_t dt at (x, t), factoring H_x in (J, A, piv); True when it is regular."""
    _tangent_rhs(fj, fjt, hom, x, t, dt, p1, p0, g, p, dp, F, J, Ht, rhs, ws)
    ok = factor(J, A, piv)
    _lin(ok, apply, J, A, piv, rhs, k)
    return ok


@nb.njit(nbt.void(_FJ, _FJT, _FACTOR, _APPLY, _RES, nbt.boolean, _C2, _C2, _C2, _C1, _C1, _C1, nbt.float64[::1],
                  nbt.float64[::1], _C2, nbt.float64[::1], nbt.int64[::1], nbt.int64[::1], nbt.float64[::1],
                  nbt.boolean[::1]),
         cache=True, error_model="numpy", nogil=True)
def track_kernel(fj, fjt, factor, apply, fres, hom, X, P1, P0, G, TA, TB, H0, opts, Xout, Sout, status, steps, Hout,
                 used_dd):
    """Track every row of X from t = TA[i] to TB[i] (see module doc).  ``opts`` = (initial_step, max_step,
    min_step, max_steps, predictor_tol, corrector_tol, max_contraction, max_norm, noise_tol, step_safety,
    extended residual allowed); rows of P1, P0, G are per path when they have as many rows as X, else row 0 serves
    every path.  With ``hom`` the tracked system is the homogenization of (fj, fjt) on the chart that ends the
    parameters (:func:`homogenized_eval`).  ``fres``: the system's residual in double-double
    (:mod:`.double_double`); when allowed, a path whose step had a good predictor (first update within
    predictor_tol) but whose Newton corrections stalled, or stopped only at the round-off floor, takes its Newton
    residuals from ``fres`` from then on (x, the Jacobians, the LU factors and the updates stay in double: mixed
    precision iterative refinement, which converges for condition numbers up to ~1 / eps instead of stalling at
    cond x eps) and the step is taken again; ``used_dd[i]`` says that path i did."""
    N, n = X.shape
    neq = n
    mp = P1.shape[1]
    max_step, min_step, max_steps = opts[1], opts[2], int(opts[3])
    ptol, ctol, mc, max_norm, noise_tol, safety = opts[4], opts[5], opts[6], opts[7], opts[8], opts[9]
    dd_allowed = opts[10] != 0.0
    max_updates = int(opts[11])
    p = np.empty(mp, np.complex128)
    dp = np.empty(mp, np.complex128)
    F = np.empty(neq, np.complex128)
    Ht = np.empty(neq, np.complex128)
    # Jacobian, LU workspace and pivots: of the RK stages (J), of the current point (Jc, for k1), of the
    # first Newton iteration (Jn), and a Jacobian scratch (Js) for evaluations that only need F or Ht
    J = np.zeros((neq, n), np.complex128)
    Jc = np.zeros((neq, n), np.complex128)
    Jn = np.zeros((neq, n), np.complex128)
    Js = np.zeros((neq, n), np.complex128)
    A = np.zeros((n, n), np.complex128)
    Ac = np.zeros((n, n), np.complex128)
    An = np.zeros((n, n), np.complex128)
    piv = np.zeros(n, np.int64)
    pivc = np.zeros(n, np.int64)
    pivn = np.zeros(n, np.int64)
    rhs = np.empty(n, np.complex128)
    k1 = np.empty(n, np.complex128)
    k2 = np.empty(n, np.complex128)
    k3 = np.empty(n, np.complex128)
    k4 = np.empty(n, np.complex128)
    xt = np.empty(n, np.complex128)
    x = np.empty(n, np.complex128)
    d1 = np.empty(n, np.complex128)
    d2 = np.empty(n, np.complex128)
    d3 = np.empty(n, np.complex128)
    x2 = np.empty(n, np.complex128)
    ws = homogenized_workspace(n, mp, hom)
    Xd, Pd, Fd, Sd = _dd_workspace(n, mp, hom)
    for i in range(N):
        r = i if P1.shape[0] == N else 0
        p1, p0, g = P1[r], P0[r], G[r]
        ta, tb = TA[i], TB[i]
        dt = tb - ta
        for c in range(n):
            x[c] = X[i, c]
        s = 0.0
        h = H0[i]
        nsteps = 0
        st = RUNNING
        have_lu = False  # (Jc, Ac, pivc) factor H_x near x (at the predicted point of the last accepted step)
        have_k1 = False  # k1 is that of the current x (after a rejected step)
        rejected = False  # the last step was rejected (the next one does not grow)
        use_dd = False  # Newton residuals in double-double (from the first step where double precision stalled)
        if dt == 0:
            st = OK
        while st == RUNNING:
            ha = min(h, 1.0 - s)
            if not have_k1:
                if have_lu:
                    _tangent_rhs(fj, fjt, hom, x, ta + s * dt, dt, p1, p0, g, p, dp, F, Js, Ht, rhs, ws)
                    apply(Jc, Ac, pivc, rhs, k1)
                else:
                    have_lu = _stage(fj, fjt, hom, factor, apply, x, ta + s * dt, dt, p1, p0, g, p, dp, F, Jc, Ht, Ac, pivc,
                                     rhs, k1, ws)
                have_k1 = True
            for c in range(n):
                xt[c] = x[c] + 0.5 * ha * k1[c]
            _stage(fj, fjt, hom, factor, apply, xt, ta + (s + 0.5 * ha) * dt, dt, p1, p0, g, p, dp, F, J, Ht, A, piv, rhs, k2, ws)
            for c in range(n):
                xt[c] = x[c] + 0.5 * ha * k2[c]
            _stage(fj, fjt, hom, factor, apply, xt, ta + (s + 0.5 * ha) * dt, dt, p1, p0, g, p, dp, F, J, Ht, A, piv, rhs, k3, ws)
            for c in range(n):
                xt[c] = x[c] + ha * k3[c]
            _stage(fj, fjt, hom, factor, apply, xt, ta + (s + ha) * dt, dt, p1, p0, g, p, dp, F, J, Ht, A, piv, rhs, k4, ws)
            for c in range(n):
                xt[c] = x[c] + (ha / 6.0) * (k1[c] + 2.0 * k2[c] + 2.0 * k3[c] + k4[c])
            sn = s + ha
            tn = ta + sn * dt
            _params(p1, p0, g, tn, p, dp)
            # Newton corrections at t(s + h): a Newton step, then chord steps with the same factors
            _newton_rhs(fj, fjt, hom, xt, p, F, Jn, rhs, ws)
            if use_dd:
                _dd_rhs(fres, hom, xt, p1, p0, g, tn, rhs, F, Xd, Pd, Fd, Sd)
            okn = factor(Jn, An, pivn)
            _lin(okn, apply, Jn, An, pivn, rhs, d1)
            for c in range(n):
                xt[c] += d1[c]
            if use_dd:
                _dd_rhs(fres, hom, xt, p1, p0, g, tn, rhs, F, Xd, Pd, Fd, Sd)
            else:
                _newton_rhs(fj, fjt, hom, xt, p, F, Js, rhs, ws)
            _lin(okn, apply, Jn, An, pivn, rhs, d2)
            for c in range(n):
                x2[c] = xt[c] + d2[c]
            scale = 1.0 + _norm(x2)
            e1 = _norm(d1) / scale
            e2 = _norm(d2) / scale
            finite = np.isfinite(e1) and np.isfinite(e2)
            contracting = (e2 <= mc * e1) or (e1 <= 1e-9 and e2 <= 1e-10)
            ok = finite and e1 <= ptol and contracting and e2 <= ctol
            floor_only = False
            if finite and not ok and e1 <= ptol and (contracting or e2 <= noise_tol):
                # more (chord) updates: Newton still contracting towards corrector_tol (each update within
                # max_contraction of the one before), up to max_updates in all; or the round-off floor (an update
                # that does not move away either)
                eprev = e2
                more = contracting
                for _u in range(max_updates - 2):
                    if use_dd:
                        _dd_rhs(fres, hom, x2, p1, p0, g, tn, rhs, F, Xd, Pd, Fd, Sd)
                    else:
                        _newton_rhs(fj, fjt, hom, x2, p, F, Js, rhs, ws)
                    _lin(okn, apply, Jn, An, pivn, rhs, d3)
                    e3 = _norm(d3) / scale
                    if not np.isfinite(e3):
                        break
                    more = more and e3 <= mc * eprev
                    for c in range(n):  # (x2 of a rejected step is not used)
                        x2[c] += d3[c]
                    if more and e3 <= ctol:
                        ok = True
                    elif eprev <= noise_tol and e3 <= 2.0 * eprev and e3 <= noise_tol:
                        ok = True
                        floor_only = True
                    if ok or not more:
                        break
                    eprev = e3
            if dd_allowed and not use_dd and finite and e1 <= ptol and (floor_only or (not ok and e2 <= noise_tol)):
                # the predictor was good but Newton stalled (or stopped at the round-off floor): residuals in
                # double-double from here on, and the same step again
                use_dd = True
                nsteps += 1
                if nsteps >= max_steps:
                    st = TOO_MANY_STEPS
                continue
            if ok:  # the Newton factors become those of the new point (for its k1)
                Jc, Jn = Jn, Jc
                Ac, An = An, Ac
                pivc, pivn = pivn, pivc
                have_lu = okn
                have_k1 = False
            nsteps += 1
            if ok:
                for c in range(n):
                    x[c] = x2[c]
                s = 1.0 if sn >= 1.0 - 1e-15 else sn
            ratio = safety * (ptol / max(e1, 1e-300)) ** 0.2
            if ok:
                hn = min(ha * min(ratio, 1.0 if rejected else 2.5), max_step)  # ratio >= safety: e1 <= ptol
            elif finite:
                hn = ha * min(max(ratio, 0.1), 0.5)
            else:
                hn = ha * 0.25
            if ok and ha < h:
                h = max(h, hn)
            else:
                h = hn
            rejected = not ok
            if s >= 1.0:
                st = OK
            elif ok and scale > max_norm:
                st = DIVERGED
            elif (not ok) and h < min_step:
                st = STEP_TOO_SMALL
            elif nsteps >= max_steps:
                st = TOO_MANY_STEPS
        for c in range(n):
            Xout[i, c] = x[c]
        Sout[i] = s
        status[i] = st
        steps[i] = nsteps
        Hout[i] = h
        used_dd[i] = use_dd


def track_segment_compiled(homotopy, x0, t_a, t_b, options, h0=None):
    """:func:`.tracker.track_segment` for a :class:`~.homotopies.ParameterHomotopy` whose system has compiled
    kernels (``homotopy.compiled_kernels()``); same arguments and :class:`~.tracker.SegmentResult`."""
    from .results import (DIVERGED as S_DIV, RUNNING as S_RUN, STEP_TOO_SMALL as S_SMALL, SUCCESS,
                          TOO_MANY_STEPS as S_MANY, SegmentResult)

    o = options
    fj, fjt, factor, apply, hom, fres = _compiled_parts(homotopy)
    X = np.array(x0, dtype=complex, order="C")  # copies: the kernel needs writable, contiguous arrays
    N, n = X.shape
    TA = np.array(np.broadcast_to(np.asarray(t_a, dtype=complex), (N,)), order="C")
    TB = np.array(np.broadcast_to(np.asarray(t_b, dtype=complex), (N,)), order="C")
    if h0 is None:
        H0 = np.full(N, float(o.initial_step))
    else:
        H0 = np.array(np.clip(np.broadcast_to(np.asarray(h0, dtype=float), (N,)), o.min_step, o.max_step), order="C")
    P1, P0, G = homotopy.path_parameters()
    opts = np.array([o.initial_step, o.max_step, o.min_step, o.max_steps, o.predictor_tol, o.corrector_tol,
                     o.max_contraction, o.max_norm, o.noise_tol, o.step_safety,
                     float(fres is not None and o.extended_residual), o.max_updates], dtype=float)
    Xout = np.empty_like(X)
    S = np.empty(N)
    st = np.empty(N, dtype=np.int64)
    steps = np.empty(N, dtype=np.int64)
    Hout = np.empty(N)
    used = np.zeros(N, dtype=bool)
    if fres is None:
        fres = function_address(no_residual_dd, _RES)
    if N:
        track_kernel(fj, fjt, factor, apply, fres, hom, X, P1, P0, G, TA, TB, H0, opts, Xout, S, st, steps, Hout, used)
    names = np.array([S_RUN, SUCCESS, S_SMALL, S_MANY, S_DIV], dtype=object)
    return SegmentResult(x=Xout, s=S, t=TA + S * (TB - TA), status=names[st], steps=steps, h=Hout, extended=used)
