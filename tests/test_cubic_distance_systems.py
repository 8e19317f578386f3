"""The generated distance-to-a-cubic systems (derivations/derive_cubic_distance.py) agree with each other and with
values computed independently: exact rational evaluation, finite differences, a sphere's known distance."""

from fractions import Fraction

import numpy as np

from cdpr_algebra.cc.cubic_distances import distance_to_cubics, evaluate_cubic
from cdpr_algebra.cc.radius_proofs import critical_set_coefficients
from cdpr_algebra.generated.cubic_distance import CRITICAL_SET_ROWS, MONOMIALS, ed_directional_into, lagrange_system

RNG = np.random.default_rng(7)


def _ed(z, c, a, b, d=None):
    """The generated ED system run by plain Python: 6 equations, dF/dz (36), dF/dc . d (6)."""
    out = np.empty(48, dtype=complex)
    ed_directional_into(*z, *c, *a, *b, *(np.zeros(20) if d is None else d), out)
    return out


def _monomials(y):
    return np.array([y[0] ** i * y[1] ** j * y[2] ** k for i, j, k in MONOMIALS])


def test_lagrange_system_is_exact_and_its_jacobian_matches_differences():
    c = [Fraction(int(v), 7) for v in RNG.integers(-20, 20, size=20)]
    y = [Fraction(1, 3), Fraction(-2, 5), Fraction(3, 4)]
    lam = Fraction(5, 11)
    v = lagrange_system(*y, lam, *c)
    P = sum(cm * y[0] ** i * y[1] ** j * y[2] ** k for cm, (i, j, k) in zip(c, MONOMIALS))
    assert v[3] == P  # exact rational arithmetic
    cf, yf = np.array([float(x) for x in c]), np.array([float(x) for x in y] + [float(lam)])
    F = lambda x: np.array(lagrange_system(*x, *cf)[:4], dtype=float)  # noqa: E731
    J = np.array(lagrange_system(*yf, *cf)[4:], dtype=float).reshape(4, 4)
    h = 1e-6
    Jd = np.array([(F(yf + h * e) - F(yf - h * e)) / (2 * h) for e in np.eye(4)]).T
    assert np.allclose(J, Jd, atol=1e-7)
    # the last column of J is -grad P; the first three equations are y - lam grad P
    assert np.allclose(F(yf)[:3], yf[:3] + yf[3] * J[:3, 3])


def test_ed_system_dehomogenizes_to_the_lagrange_system_and_is_linear_in_c():
    c = RNG.normal(size=20)
    y, lam = RNG.normal(size=3), RNG.normal()
    a, b = RNG.normal(size=4), RNG.normal(size=2)
    # z = s (1, y) with a.z = 1, and (mu, lam') = r (1, lam) with b.(mu, lam') = 1
    s = 1.0 / (a[0] + a[1:] @ y)
    r = 1.0 / (b[0] + b[1] * lam)
    z = [s, *(s * y), r, r * lam]
    F = _ed(z, c, a, b)[:6].real
    L = np.array(lagrange_system(*y, lam, *c)[:4], dtype=float)
    # mu y0 y_k - lam' dP^h/dy_k = r s^2 (y_k - lam dP/dy_k); P^h = s^3 P
    assert np.allclose(F[:3], r * s * s * L[:3])
    assert np.isclose(F[3], s ** 3 * L[3])
    assert np.allclose(F[4:], 0, atol=1e-12)
    d = RNG.normal(size=20)
    D = _ed(z, c, a, b, d)[42:].real
    Fd = _ed(z, c + d, a, b)[:6].real
    assert np.allclose(Fd - F, D)


def test_critical_set_rows_give_p_and_the_cross_products_with_the_gradient():
    c = RNG.normal(size=20)
    Cm, Cr = critical_set_coefficients(c, c)
    assert np.all(Cr <= 1e-12 * (1 + np.abs(Cm)))
    assert np.array(CRITICAL_SET_ROWS).shape == (16, 20, 20)
    y = RNG.normal(size=3)
    vals = Cm @ _monomials(y)

    def grad(yy):
        return -np.array(lagrange_system(*yy, 0.0, *c)[4:], dtype=float).reshape(4, 4)[:3, 3]

    def funcs(yy):
        g_ = grad(yy)
        return np.array([evaluate_cubic(c, yy)] + [yy[a_] * g_[b_] - yy[b_] * g_[a_]
                                                   for a_, b_ in ((0, 1), (0, 2), (1, 2))])

    g = grad(y)
    assert np.isclose(vals[0], evaluate_cubic(c, y))
    assert np.allclose(vals[1:4], [y[a_] * g[b_] - y[b_] * g[a_] for a_, b_ in ((0, 1), (0, 2), (1, 2))])
    h = 1e-6
    for v in range(3):
        e = np.eye(3)[v]
        fd = (funcs(y + h * e) - funcs(y - h * e)) / (2 * h)
        assert np.allclose(vals[4 * (v + 1):4 * (v + 2)], fd, atol=1e-6)


def test_distance_to_a_sphere_written_as_a_cubic():
    # P(y) = |y - q|^2 - r^2: the distance from 0 is |q| - r (q outside), attained at q (1 - r / |q|)
    q, r = np.array([0.3, -0.4, 1.2]), 0.5
    coef = {(0, 0, 0): q @ q - r * r, (1, 0, 0): -2 * q[0], (0, 1, 0): -2 * q[1], (0, 0, 1): -2 * q[2],
            (2, 0, 0): 1.0, (0, 2, 0): 1.0, (0, 0, 2): 1.0}
    c = np.array([coef.get(m, 0.0) for m in MONOMIALS])
    (res,) = distance_to_cubics(c[None])
    assert res.failed == 0
    assert abs(res.minimum - (np.linalg.norm(q) - r)) < 1e-10
    assert np.allclose(res.points[0], q * (1 - r / np.linalg.norm(q)), atol=1e-10)


def _nodal_cubic():
    # (y1-1)^2 (y3+1) + (y2-1/2)^2 - (y1-1)^3 - (y3-3/10)^2 (y2-1/2): one singular point, (1, 1/2, 3/10)
    import sympy as sp

    y1, y2, y3 = sp.symbols("y1 y2 y3")
    P = (y1 - 1) ** 2 * (y3 + 1) + (y2 - sp.Rational(1, 2)) ** 2 - (y1 - 1) ** 3 \
        - (y3 - sp.Rational(3, 10)) ** 2 * (y2 - sp.Rational(1, 2))
    poly = sp.Poly(sp.expand(P), y1, y2, y3)
    d = dict(zip(poly.monoms(), poly.coeffs()))
    return np.array([float(d.get(m, 0)) for m in MONOMIALS])


def test_a_path_heading_for_a_node_is_accounted_for_by_the_node():
    from cdpr_algebra.cc.cubic_distances import _singular_point_near

    c = _nodal_cubic()
    node = np.array([1.0, 0.5, 0.3])
    near = node + 1e-4 * np.array([1.0, -2.0, 0.5])
    z = np.concatenate([[0.5], 0.5 * near, [1e-4, 1.0]]).astype(complex)  # chart point, mu small
    y = _singular_point_near(c, z)
    assert y is not None and np.allclose(y, node, atol=1e-4)  # a degenerate node: Newton converges linearly
    # a node of the true surface is a near-node of a cubic with rounded coefficients: still accepted
    rng = np.random.default_rng(2)
    assert _singular_point_near(c * (1 + 1e-12 * rng.normal(size=20)), z) is not None
    # no singular point there once the cubic is perturbed beyond rounding, or when mu is not small
    assert _singular_point_near(c * (1 + 1e-5 * rng.normal(size=20)), z) is None
    assert _singular_point_near(c, np.concatenate([[0.5], 0.5 * near, [0.5, 1.0]]).astype(complex)) is None
    # the distance search lists the node itself
    (res,) = distance_to_cubics(c[None])
    assert res.failed == 0
    k = [i for i, kind in enumerate(res.kinds) if kind == "singular point"]
    assert len(k) == 1 and np.allclose(res.points[k[0]], node, atol=1e-8)


def test_compiled_batch_equals_the_generated_function():
    from cdpr_algebra.cc.ed_kernels import ed_values

    N = 7
    Z = RNG.normal(size=(N, 6)) + 1j * RNG.normal(size=(N, 6))
    C = RNG.normal(size=(N, 20)) + 1j * RNG.normal(size=(N, 20))
    D = RNG.normal(size=(N, 20))
    a, b = RNG.normal(size=4) + 0j, RNG.normal(size=2) + 0j
    got = ed_values(Z, C, a, b, D)
    for k in range(N):
        ref = _ed(Z[k], C[k], a, b, D[k])
        assert np.allclose(got[k], ref, rtol=1e-13, atol=1e-13 * np.abs(ref).max())
    # one shared cubic, no direction
    got1 = ed_values(Z, C[0], a, b)
    assert np.allclose(got1, np.array([_ed(Z[k], C[0], a, b) for k in range(N)]))
