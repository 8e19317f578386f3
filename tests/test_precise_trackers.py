"""The arbitrary-precision tracker (:mod:`cdpr_algebra.homotopy.flint_tracker`) against paths known in closed form."""

import numpy as np

from cdpr_algebra.homotopy.flint_tracker import FlintParameterHomotopy, flint_track
from cdpr_algebra.homotopy.results import SUCCESS, TOO_MANY_STEPS
from cdpr_algebra.homotopy.tracker import TrackerOptions


def _evaluate(x, p, dp, F, J, Ht, with_ht):
    """F(x; p) = (x0^2 - p0, x1 - p1 x0): the solution x0 = +-sqrt(p0), x1 = p1 x0 (the generated evaluators'
    signature: F, the pattern of J, and Ht = dF/dp . dp)."""
    F[0] = x[0] * x[0] - p[0]
    F[1] = x[1] - p[1] * x[0]
    J[0, 0] = 2 * x[0]
    J[1, 0] = -p[1]
    J[1, 1] = 1 + 0 * x[1]
    if with_ht:
        Ht[0] = -dp[0]
        Ht[1] = -dp[1] * x[0]


def test_flint_track_ends_on_the_closed_form_solution():
    """From p1 = (4, 1) to p0 = (9, 2) along a gamma arc, the root (2, 2) goes to (3, 6) (x0 = sqrt(p0(t)) never
    meets 0 on the arc): the endpoint agrees with it to far below double precision's rounding."""
    h = FlintParameterHomotopy(_evaluate, 2, 2, [4, 1], [9, 2], gamma=np.exp(0.7j))
    seg = flint_track(h, [2, 2], 1.0, 0.0, TrackerOptions(predictor_tol=1e-6), prec=106, max_steps=2000)
    assert seg.status == SUCCESS and seg.t == 0
    assert np.abs(seg.x - np.array([3, 6])).max() <= 1e-14
    # the parameter path is the double tracker's (ParameterHomotopy.parameters_at): halfway on the arc
    half = flint_track(h, [2, 2], 1.0, 0.5, TrackerOptions(predictor_tol=1e-6), prec=106, max_steps=2000)
    g = np.exp(0.7j)
    p = (g * 0.5 * np.array([4, 1]) + 0.5 * np.array([9, 2])) / (g * 0.5 + 0.5)
    root = np.sqrt(p[0]) * np.sign(np.sqrt(p[0]).real)
    assert np.abs(half.x - np.array([root, p[1] * root])).max() <= 1e-12


def test_flint_track_stops_at_its_step_budget():
    """A budget too small for the path: ``too_many_steps`` at the t reached, the point still on the path."""
    h = FlintParameterHomotopy(_evaluate, 2, 2, [4, 1], [9, 2])
    seg = flint_track(h, [2, 2], 1.0, 0.0, TrackerOptions(predictor_tol=1e-8), max_steps=3, initial_step=1e-3)
    assert seg.status == TOO_MANY_STEPS and seg.steps == 3
    t = seg.t.real
    p = t * np.array([4, 1]) + (1 - t) * np.array([9, 2])
    assert 0 < t < 1
    assert np.abs(seg.x - np.array([np.sqrt(p[0]), p[1] * np.sqrt(p[0])])).max() <= 1e-12


# the same system in double-double for the compiled tracker (the operations of a rewritten generated evaluator)
def _toy_dd():
    import numba as nb

    from cdpr_algebra.homotopy.double_double import EQUATIONS_SIG, c_neg, cc_mul, cc_sub
    from cdpr_algebra.intervals.complex_kernels import c_ld, c_st1, c_st2

    @nb.njit(EQUATIONS_SIG)
    def toy(x, p, dp, F, J, Ht, with_ht):
        x0, x1, p0, p1 = c_ld(x, 0), c_ld(x, 1), c_ld(p, 0), c_ld(p, 1)
        c_st1(F, 0, cc_sub(cc_mul(x0, x0), p0))
        c_st1(F, 1, cc_sub(x1, cc_mul(p1, x0)))
        c_st2(J, 0, 0, cc_mul((2.0, 0.0, 0.0, 0.0), x0))
        c_st2(J, 1, 0, c_neg(p1))
        c_st2(J, 1, 1, (1.0, 0.0, 0.0, 0.0))
        if with_ht:
            c_st1(Ht, 0, c_neg(c_ld(dp, 0)))
            c_st1(Ht, 1, c_neg(cc_mul(c_ld(dp, 1), x0)))

    return toy


def test_dd_track_ends_on_the_closed_form_solution_and_keeps_its_budget():
    from cdpr_algebra.homotopy.dd_tracker import DoubleDoubleParameterHomotopy

    h = DoubleDoubleParameterHomotopy(_toy_dd(), 2, [4, 1], [9, 2], gamma=np.exp(0.7j))
    seg = h.track([2, 2], 1.0, 0.0, TrackerOptions(predictor_tol=1e-6), 2000)
    assert seg.status == SUCCESS and seg.t == 0
    assert np.abs(seg.x - np.array([3, 6])).max() <= 1e-14
    short = DoubleDoubleParameterHomotopy(_toy_dd(), 2, [4, 1], [9, 2]).track(
        [2, 2], 1.0, 0.0, TrackerOptions(predictor_tol=1e-8), 3, initial_step=1e-3)
    assert short.status == TOO_MANY_STEPS and short.steps == 3
    t = short.t.real
    p = t * np.array([4, 1]) + (1 - t) * np.array([9, 2])
    assert 0 < t < 1 and np.abs(short.x - np.array([np.sqrt(p[0]), p[1] * np.sqrt(p[0])])).max() <= 1e-12


def test_dd_solve_beyond_double_precision():
    """A system with condition number ~1e19 whose matrix double precision cannot even hold (two rows differ by 2^-60
    in one entry): J x = b solved in double-double against the exact rational solution (python-flint fmpq)."""
    from flint import fmpq, fmpq_mat

    from cdpr_algebra.homotopy.dd_tracker import dd_solve
    from cdpr_algebra.homotopy.double_double import to_complex

    n = 4
    rng = np.random.default_rng(3)
    J = rng.integers(-9, 10, size=(n, n)).astype(float)
    J[3] = J[2]  # in double-double, row 3 is row 2 plus 2^-60 in its first entry (only the low part carries it)
    b = rng.integers(-9, 10, size=n).astype(float)
    Jd = np.zeros((n, n, 4))
    Jd[:, :, 0] = J
    Jd[3, 0, 1] = 2.0 ** -60
    bd = np.zeros((n, 4))
    bd[:, 0] = b
    x = np.zeros((n, 4))
    assert dd_solve(Jd, bd, np.zeros((n, n, 4)), x)
    got = np.empty(n, dtype=complex)
    to_complex(x, got)
    Je = [[fmpq(*v.as_integer_ratio()) for v in row] for row in J]
    Je[3][0] += fmpq(1, 2 ** 60)
    exact = fmpq_mat(Je).solve(
        fmpq_mat([[fmpq(*v.as_integer_ratio())] for v in b]))
    want = np.array([float(exact[i, 0]) for i in range(n)])
    assert np.abs(want).max() > 1e15  # the ill-conditioning is real
    assert np.all(np.abs(got - want) <= 1e-12 * np.abs(want).max())


def test_study_equations_in_double_double_equal_the_double_ones():
    """The generated double-double Study evaluator (derivations/derive_study_equations.py) rounded to double equals
    the double-precision one (F, J, Ht at a random complex point), for m = 2 and 5."""
    from cdpr_algebra.dgp.study_retrack import fast_study_family
    from cdpr_algebra.generated.study_equations_dd import study_equations
    from cdpr_algebra.homotopy.double_double import to_complex, to_dd

    rng = np.random.default_rng(11)
    for m in (2, 5):
        fam = fast_study_family(m)
        x = rng.normal(size=fam.n) + 1j * rng.normal(size=fam.n)
        p = rng.normal(size=fam.m) + 1j * rng.normal(size=fam.m)
        dp = rng.normal(size=fam.m) + 1j * rng.normal(size=fam.m)
        F, J, H = fam.evaluate_directional(x, p, dp)
        X, P, DP = (np.zeros((len(v), 4)) for v in (x, p, dp))
        for a, v in ((X, x), (P, p), (DP, dp)):
            to_dd(v, a)
        Fd, Jd, Hd = np.zeros((fam.neq, 4)), np.zeros((fam.neq, fam.n, 4)), np.zeros((fam.neq, 4))
        study_equations(X, P, DP, Fd, Jd, Hd, True)
        got = [np.empty(fam.neq, dtype=complex), np.empty(fam.neq * fam.n, dtype=complex),
               np.empty(fam.neq, dtype=complex)]
        to_complex(Fd, got[0])
        to_complex(Jd.reshape(-1, 4), got[1])
        to_complex(Hd, got[2])
        for g, want in zip(got, (F[0], J[0].ravel(), H[0])):
            assert np.abs(g - want).max() <= 1e-12 * (1 + np.abs(want).max())


def _toy_homotopies(p0):
    import sympy as sp

    from cdpr_algebra.homotopy.dd_tracker import DoubleDoubleParameterHomotopy
    from cdpr_algebra.homotopy.homotopies import ParameterHomotopy
    from cdpr_algebra.homotopy.systems import PolynomialSystem

    x0, x1, a, b = sp.symbols("x0 x1 a b")
    system = PolynomialSystem([x0**2 - a, x1 - b * x0], [x0, x1], [a, b], name="toy_sqrt")
    hom = ParameterHomotopy(system, np.array([4.0, 1.0]), np.array(p0, dtype=float))
    return hom, DoubleDoubleParameterHomotopy(_toy_dd(), 2, [4, 1], p0)


def test_precise_cauchy_endgame_on_a_double_root_and_a_regular_one():
    """x0^2 = a(t), x1 = b(t) x0 with a(t) = 4 t (a(0) = 0): the paths x0 = +-2 sqrt(t) meet at t = 0, so the loops
    turn twice and their mean is the double root (0, 0); with a(0) = 9 the limit is the regular root (3, 6) on one
    sheet.  Known in closed form."""
    from cdpr_algebra.homotopy.endgame import EndgameOptions
    from cdpr_algebra.homotopy.precise_endgame import precise_cauchy_endgame

    o, tr = EndgameOptions(), TrackerOptions(predictor_tol=1e-5)
    hom, precise = _toy_homotopies([0.0, 2.0])
    t0 = 0.1
    a, b = 4 * t0, t0 * 1 + (1 - t0) * 2
    lim = precise_cauchy_endgame(hom, precise, np.array([np.sqrt(a), b * np.sqrt(a)]), t0, o, tr)
    assert lim.converged and lim.winding == 2 and lim.accuracy <= o.cauchy_tol
    assert np.abs(lim.x).max() <= 1e-8
    hom, precise = _toy_homotopies([9.0, 2.0])
    a = 4 * t0 + 9 * (1 - t0)
    lim = precise_cauchy_endgame(hom, precise, np.array([np.sqrt(a), b * np.sqrt(a)]), t0, o, tr)
    assert lim.converged and lim.winding == 1
    assert np.abs(lim.x - np.array([3, 6])).max() <= 1e-8


def test_double_double_products_are_exact_pairs():
    """The fused multiply-add's two-product (double_double._two_prod): p + e equals a b exactly (rationals) with
    p = fl(a b), over operands of very different magnitudes; a complex double-double product agrees with the exact
    one to the 2^-100 of double-double."""
    from fractions import Fraction

    import numba as nb

    from cdpr_algebra.homotopy.double_double import _two_prod, cc_mul

    @nb.njit
    def products(a, b, p, e):
        for k in range(a.shape[0]):
            p[k], e[k] = _two_prod(a[k], b[k])

    rng = np.random.default_rng(11)
    a = rng.standard_normal(2000) * 10.0 ** rng.integers(-120, 120, 2000)
    b = rng.standard_normal(2000) * 10.0 ** rng.integers(-120, 120, 2000)
    p, e = np.empty(2000), np.empty(2000)
    products(a, b, p, e)
    assert np.array_equal(p, a * b)
    assert all(Fraction(pk) + Fraction(ek) == Fraction(ak) * Fraction(bk) for ak, bk, pk, ek in zip(a, b, p, e))
    assert np.count_nonzero(e) > 1000  # the errors are not trivially 0

    x, y = (1 / 3, 1e-17 / 7, -2 / 9, 3e-18 / 11), (5 / 7, -1e-17 / 3, 1 / 13, 2e-18)
    X = (Fraction(x[0]) + Fraction(x[1]), Fraction(x[2]) + Fraction(x[3]))
    Y = (Fraction(y[0]) + Fraction(y[1]), Fraction(y[2]) + Fraction(y[3]))
    re, im = X[0] * Y[0] - X[1] * Y[1], X[0] * Y[1] + X[1] * Y[0]
    z = nb.njit(lambda u, v: cc_mul(u, v))(x, y)
    assert abs(Fraction(z[0]) + Fraction(z[1]) - re) <= abs(re) * Fraction(1, 2 ** 100)
    assert abs(Fraction(z[2]) + Fraction(z[3]) - im) <= abs(im) * Fraction(1, 2 ** 100)
