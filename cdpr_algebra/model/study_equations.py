"""The DGP equations with m taut cables in Study's kinematic-mapping parameters (a second chart of the same problem).

Why.  In :mod:`.taut_equations` the rotation is R = [u v w].  Paths of the DGP's parameter homotopies that pass
near the isotropic infinity of the complex rotation group (u.u = 1 with |u| ~ 1e3 .. 1e5, README "What the failed
paths are") meet equilibrated condition numbers of 1e10-1e11 in those coordinates, and double precision loses
them.  With Euler parameters e (a point of P^3, on the chart c . e = 1) the same rotations are
R = Q(e) / N, N = e . e, and such a rotation is an ordinary point with small N / |e|^2 (1e-5 for |R| ~ 1e4).

Unknowns x = (e_0..e_3, g_0..g_3, lam_1..lam_m) (8 + m): e and g are Study's parameters of the pose (quaternion
products; a pure quaternion is a 3-vector), p = 2 g e* / N, and lam_i = tau_i / rho_i as in :mod:`.taut_equations`.
With s_i = e b'_i - A_i e + 2 g (linear) and N B_i = vec((e b'_i + 2 g) e*) (quadratic), since
R b' + p - A = s e* / N and |q e*|^2 = |q|^2 N:

    c . e = 1                                                   (the chart of e)
    e . g = 0                                                   (Study's quadric: p has no scalar part)
    s_i . s_i - rho_i^2 N = 0                  i = 1..m         (|B_i - A_i|^2 = rho_i^2, times N)
    sum_i lam_i (N A_i - N B_i) + N Q d = 0                     (force balance, times N)
    sum_i lam_i (N B_i) x A_i + (N G) x Q d = 0                 (moments about the world origin, times N)

with N G = vec((e g' + 2 g) e*).  8 + m equations of degrees 1, 2, 2 (m), 3 (6).  Parameters: those of
:func:`.taut_equations.taut_family` followed by the chart c (4).  For N != 0 the solutions are those of the taut
family, one to one (e and -e are one point of P^3): :func:`to_study` and :func:`from_study` map them.
"""

from __future__ import annotations

import numpy as np

from cdpr_algebra.homotopy.systems import PolynomialSystem

from .taut_equations import _cross

__all__ = ["study_family", "quaternion_product", "to_study", "from_study", "rotation_quaternions",
           "STUDY_CHART_PARAMETERS"]

STUDY_CHART_PARAMETERS = 4
_FAMILIES: dict[int, PolynomialSystem] = {}


def quaternion_product(a, b):
    """Hamilton's product of two quaternions given as 4 components (scalar first); any ring elements."""
    a0, a1, a2, a3 = a
    b0, b1, b2, b3 = b
    return [a0 * b0 - a1 * b1 - a2 * b2 - a3 * b3,
            a0 * b1 + a1 * b0 + a2 * b3 - a3 * b2,
            a0 * b2 - a1 * b3 + a2 * b0 + a3 * b1,
            a0 * b3 + a1 * b2 - a2 * b1 + a3 * b0]


def _conj(a):
    return [a[0], -a[1], -a[2], -a[3]]


def study_family(m: int) -> PolynomialSystem:
    """The parameterized system of the module doc for m taut cables (cached)."""
    if m in _FAMILIES:
        return _FAMILIES[m]
    if not 2 <= m <= 6:
        raise ValueError("the homotopy formulation covers m = 2 .. 6 taut cables (m = 1 is analytic)")
    import sympy as sp

    e = sp.symbols("e0:4")
    g = sp.symbols("g0:4")
    lam = sp.symbols(f"lam1:{m + 1}")
    A = [sp.symbols(f"A{i}x A{i}y A{i}z") for i in range(1, m + 1)]
    r2 = sp.symbols(f"rho2_1:{m + 1}")
    b = [sp.symbols(f"b{i}x b{i}y b{i}z") for i in range(1, m + 1)]
    gp = sp.symbols("gx gy gz")
    f = sp.symbols("fx fy fz")
    c = sp.symbols("c0:4")
    N = sum(x * x for x in e)
    ec = _conj(e)

    def pure(v):
        return [0, *v]

    def times_n(point):  # N (p + R point) = vec((e point + 2 g) e*)
        q = [x + 2 * y for x, y in zip(quaternion_product(e, pure(point)), g)]
        return quaternion_product(q, ec)[1:]

    eqs = [sum(ci * ei for ci, ei in zip(c, e)) - 1, sum(x * y for x, y in zip(e, g))]
    NB = []
    for i in range(m):
        s = [x - y + 2 * z for x, y, z in zip(quaternion_product(e, pure(b[i])), quaternion_product(pure(A[i]), e), g)]
        eqs.append(sum(x * x for x in s) - r2[i] * N)
        NB.append(times_n(b[i]))
    eqs += [sum(lam[i] * (N * A[i][k] - NB[i][k]) for i in range(m)) + N * f[k] for k in range(3)]
    mom = _cross(times_n(gp), f)
    for i in range(m):
        cc = _cross(NB[i], A[i])
        mom = [mom[k] + lam[i] * cc[k] for k in range(3)]
    eqs += mom
    xs = list(e) + list(g) + list(lam)
    ps = [x for a in A for x in a] + list(r2) + [x for bi in b for x in bi] + list(gp) + list(f) + list(c)
    fam = PolynomialSystem([sp.expand(q) for q in eqs], xs, ps, name=f"dgp_{m}_taut_study")
    _FAMILIES[m] = fam
    return fam


def rotation_quaternions(R) -> np.ndarray:
    """Rows e (k, 4) with R(e) = R for the (complex) rotations R (k, 3, 3), up to sign: for each R the one of the four
    classical formulas (1 + tr R = 4 e_0^2, 1 + 2 R_jj - tr R = 4 e_j^2) with the largest |.|, so no division is
    by a small number."""
    R = np.asarray(R, dtype=complex).reshape(-1, 3, 3)
    t = np.trace(R, axis1=1, axis2=2)
    cand = np.stack([1 + t, 1 + 2 * R[:, 0, 0] - t, 1 + 2 * R[:, 1, 1] - t, 1 + 2 * R[:, 2, 2] - t], axis=1)
    k = np.argmax(np.abs(cand), axis=1)
    s = 2 * np.sqrt(cand[np.arange(len(R)), k])  # 4 e_k
    a = R[:, 2, 1] - R[:, 1, 2]  # 4 e0 e1
    b = R[:, 0, 2] - R[:, 2, 0]  # 4 e0 e2
    c = R[:, 1, 0] - R[:, 0, 1]  # 4 e0 e3
    d = R[:, 0, 1] + R[:, 1, 0]  # 4 e1 e2
    f = R[:, 0, 2] + R[:, 2, 0]  # 4 e1 e3
    g = R[:, 1, 2] + R[:, 2, 1]  # 4 e2 e3
    rows = {0: (s / 4, a / s, b / s, c / s), 1: (a / s, s / 4, d / s, f / s),
            2: (b / s, d / s, s / 4, g / s), 3: (c / s, f / s, g / s, s / 4)}
    out = np.empty((len(R), 4), dtype=complex)
    for j in range(4):
        sel = k == j
        out[sel] = np.stack([v[sel] for v in rows[j]], axis=1)
    return out


def _qmul_rows(a, b):
    return np.stack(quaternion_product(a.T, b.T), axis=1)


def to_study(X, m: int, chart) -> np.ndarray:
    """Rows (p, u, v, w, lam) of :mod:`.taut_equations` -> rows (e, g, lam) of :func:`study_family` on the chart
    c . e = 1 (g = p e / 2, quaternion product)."""
    X = np.atleast_2d(np.asarray(X, dtype=complex))
    R = np.stack([X[:, 3:6], X[:, 6:9], X[:, 9:12]], axis=-1)
    e = rotation_quaternions(R)
    e = e / (e @ np.asarray(chart, dtype=complex))[:, None]
    p = np.hstack([np.zeros((len(X), 1), complex), X[:, 0:3]])
    return np.hstack([e, _qmul_rows(p, e) / 2, X[:, 12:12 + m]])


def from_study(Y, m: int) -> np.ndarray:
    """Rows (e, g, lam) of :func:`study_family` -> rows (p, u, v, w, lam) of :mod:`.taut_equations`: R = Q(e) / N,
    p = 2 vec(g e*) / N (non-finite where N = e . e vanishes)."""
    Y = np.atleast_2d(np.asarray(Y, dtype=complex))
    e, g = Y[:, 0:4], Y[:, 4:8]
    N = np.sum(e * e, axis=1)
    e0, e1, e2, e3 = e.T
    R = np.stack([np.stack([e0 * e0 + e1 * e1 - e2 * e2 - e3 * e3, 2 * (e1 * e2 - e0 * e3), 2 * (e1 * e3 + e0 * e2)], -1),
                  np.stack([2 * (e1 * e2 + e0 * e3), e0 * e0 - e1 * e1 + e2 * e2 - e3 * e3, 2 * (e2 * e3 - e0 * e1)], -1),
                  np.stack([2 * (e1 * e3 - e0 * e2), 2 * (e2 * e3 + e0 * e1), e0 * e0 - e1 * e1 - e2 * e2 + e3 * e3], -1)],
                 axis=1) / N[:, None, None]
    ec = e * np.array([1, -1, -1, -1])
    p = 2 * _qmul_rows(g, ec)[:, 1:] / N[:, None]
    return np.hstack([p, R[:, :, 0], R[:, :, 1], R[:, :, 2], Y[:, 8:8 + m]])
