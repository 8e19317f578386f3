"""Compiled DGP evaluators (dgp.kernels, generated) against the sympy family, and the compiled tracker against the numpy one."""

import numpy as np
import pytest

from cdpr_algebra.dgp.solve import _generic, fast_family
from cdpr_algebra.model.taut_equations import taut_family
from cdpr_algebra.dgp.kernels import taut_fj, taut_fjt
from cdpr_algebra.homotopy.homotopies import ParameterHomotopy
from cdpr_algebra.homotopy.tracker import TrackerOptions, track_segment
from kernel_checks import assert_kernels_equal_family


@pytest.mark.parametrize("m", [2, 3, 4, 5, 6])
def test_kernels_equal_sympy_family(m):
    assert_kernels_equal_family(taut_family(m), taut_fj, taut_fjt, np.random.default_rng(m), 3)


class _NumpyOnly:
    """The same homotopy without compiled kernels: tracked by the numpy tracker."""

    def __init__(self, hom):
        self.hom = hom

    def __getattr__(self, name):
        if name == "compiled_kernels":
            raise AttributeError(name)
        return getattr(self.hom, name)


@pytest.mark.parametrize("m,gamma", [(2, None), (3, 0.6 + 0.8j)])
def test_compiled_tracker_equals_numpy_tracker(m, gamma):
    p1, X = _generic(m)
    rng = np.random.default_rng(10 + m)
    p0 = p1 + 0.3 * (rng.normal(size=p1.shape) + 1j * rng.normal(size=p1.shape))
    hom = ParameterHomotopy(fast_family(m), p1, p0, gamma=gamma)
    assert hom.compiled_kernels() is not None
    o = TrackerOptions(predictor_tol=1e-4)
    a = track_segment(hom, X, 1.0, 0.1, o)
    b = track_segment(_NumpyOnly(hom), X, 1.0, 0.1, o)
    ok = (a.status == "success") & (b.status == "success")
    assert ok.mean() > 0.95
    assert np.max(np.abs(a.x[ok] - b.x[ok])) <= 1e-8 * (1 + np.abs(b.x[ok]).max())
    # the same step rule (the compiled tracker's chord step and reused factors for k1 change the predictor
    # error estimates slightly): within one step on (almost) every path, and no more steps on average
    print("steps: compiled", a.steps[ok].sum(), "numpy", b.steps[ok].sum(), "equal", np.mean(a.steps[ok] == b.steps[ok]),
          "within 10%", np.mean(np.abs(a.steps[ok] - b.steps[ok]) <= 0.1 * b.steps[ok]))
    assert np.mean(np.abs(a.steps[ok] - b.steps[ok]) <= 0.1 * b.steps[ok]) > 0.9
    assert a.steps[ok].mean() <= 1.02 * b.steps[ok].mean()
    # endpoints solve the target system at t = 0.1
    F = hom.evaluate(a.x[ok], np.full(ok.sum(), 0.1 + 0j))
    assert np.abs(F).max() <= 1e-8


@pytest.mark.parametrize("numpy_tracker", [False, True])
def test_more_newton_updates_accept_more_steps_and_keep_the_endpoints(numpy_tracker):
    """``max_updates``: a step whose Newton updates contract but reach corrector_tol only after the third is
    accepted with 5 updates and rejected (taken again shorter) with 3; the paths end at the same points (measured,
    compiled tracker, 156 paths: 4875 -> 4683 steps, 33 paths shorter, none longer)."""
    p1, X = _generic(3)
    rng = np.random.default_rng(13)
    p0 = p1 + 0.3 * (rng.normal(size=p1.shape) + 1j * rng.normal(size=p1.shape))
    hom = ParameterHomotopy(fast_family(3), p1, p0)
    if numpy_tracker:
        hom, X = _NumpyOnly(hom), X[:40]
    runs = [track_segment(hom, X, 1.0, 0.0, TrackerOptions(predictor_tol=1e-3, max_updates=k)) for k in (3, 5, 2)]
    three, five, two = runs
    ok = (three.status == "success") & (five.status == "success")
    assert ok.mean() > 0.95 and np.array_equal(three.status, five.status)
    assert np.max(np.abs(three.x[ok] - five.x[ok])) <= 1e-7 * (1 + np.abs(three.x[ok]).max())
    assert np.all(five.steps[ok] <= three.steps[ok] + 1)
    if not numpy_tracker:  # chord updates contract linearly (the numpy tracker's full Newton ones seldom need a 4th)
        assert five.steps.sum() < three.steps.sum()
    # two updates: no step may take a third, so no fewer steps than with three
    assert two.steps.sum() > three.steps.sum()


@pytest.mark.parametrize("m", [2, 4, 6])
def test_structured_solve_equals_dense(m):
    from cdpr_algebra.dgp.kernels import taut_apply, taut_factor
    from cdpr_algebra.homotopy.compiled import dense_apply, dense_factor, solve_with

    fam = taut_family(m)
    rng = np.random.default_rng(20 + m)
    x = rng.normal(size=fam.n) + 1j * rng.normal(size=fam.n)
    p = rng.normal(size=fam.m) + 1j * rng.normal(size=fam.m)
    F = np.empty(fam.neq, complex)
    J = np.zeros((fam.neq, fam.n), complex)
    taut_fj(x, p, F, J)
    b = rng.normal(size=fam.n) + 1j * rng.normal(size=fam.n)
    d1 = solve_with(taut_factor, taut_apply, J, b)
    d2 = solve_with(dense_factor, dense_apply, J, b)
    assert np.abs(J @ d1 - b).max() <= 1e-12 * np.abs(b).max() * np.linalg.cond(J)
    assert np.abs(d1 - np.linalg.solve(J, b)).max() <= 1e-10 * np.abs(d2).max()
    assert np.abs(d2 - np.linalg.solve(J, b)).max() <= 1e-10 * np.abs(d2).max()
    # the factors serve several right-hand sides (the tracker reuses them)
    n = fam.n
    A, piv, out = np.zeros((n, n), complex), np.zeros(n, np.int64), np.empty(n, complex)
    assert taut_factor(J, A, piv)
    for _ in range(3):
        b = rng.normal(size=n) + 1j * rng.normal(size=n)
        taut_apply(J, A, piv, b, out)
        assert np.abs(out - np.linalg.solve(J, b)).max() <= 1e-10 * np.abs(out).max()
    # a singular Jacobian (two equal rows) gives None and no silent garbage
    J[7] = J[6]
    d = solve_with(taut_factor, taut_apply, J, b)
    assert d is None or not np.all(np.isfinite(d)) or np.abs(J @ d - b).max() > 1e-6


@pytest.mark.parametrize("m", [2, 4, 6])
def test_chart_solve_equals_dense(m):
    """The structured LU of the chart Jacobian (lam columns first, statics and chart rows on top) solves the
    homogenized system's Jacobian like numpy, for several right-hand sides, also near infinity (y0 = 1e-6, where
    the w block y0 I nearly vanishes)."""
    from cdpr_algebra.dgp.kernels import chart_apply, chart_factor
    from cdpr_algebra.dgp.solve import fast_family
    from cdpr_algebra.homotopy.projective import HomogenizedQuadratic

    fam = fast_family(m)
    rng = np.random.default_rng(40 + m)
    p = rng.normal(size=fam.m) + 1j * rng.normal(size=fam.m)
    Fh = HomogenizedQuadratic(fam, rng.normal(size=fam.n + 1) + 1j * rng.normal(size=fam.n + 1))
    Y = rng.normal(size=(2, fam.n + 1)) + 1j * rng.normal(size=(2, fam.n + 1))
    Y[1, 0] = 1e-6
    _, Js = Fh.evaluate_and_jacobian(Y, p)
    _assert_solves_like_numpy(chart_factor, chart_apply, Js, rng)
    assert Fh.compiled_kernels()[2] is chart_factor


def _assert_solves_like_numpy(factor, apply, Js, rng):
    """factor / apply (a compiled tracker's LU) solve each J of Js like numpy, for three right-hand sides."""
    for J in Js:
        J = np.ascontiguousarray(J)
        n = len(J)
        A, piv, out = np.zeros((n, n), complex), np.zeros(n, np.int64), np.empty(n, complex)
        assert factor(J, A, piv)
        for _ in range(3):
            b = rng.normal(size=n) + 1j * rng.normal(size=n)
            apply(J, A, piv, b, out)
            ref = np.linalg.solve(J, b)
            assert np.abs(out - ref).max() <= 1e-14 * np.linalg.cond(J) * np.abs(ref).max()
            assert np.abs(J @ out - b).max() <= 1e-12 * np.abs(J).max() * np.abs(out).max()


def test_homogenized_eval_reuses_the_origin_only_for_the_same_parameters():
    """homogenized_eval keeps F, J (and Ht) at the origin while the parameters (and their derivative) are those of
    its last call: calls that change p, dp and the kind of evaluation in one workspace give, call by call, exactly
    what a fresh workspace gives, F and J equal the numpy twin (HomogenizedQuadratic), and a call with the same
    parameters does take the origin from the workspace (a value planted there shows in its result)."""
    from cdpr_algebra.homotopy.compiled import homogenized_eval_typed as homogenized_eval, homogenized_workspace
    from cdpr_algebra.homotopy.projective import HomogenizedQuadratic

    m = 3
    fam = fast_family(m)
    rng = np.random.default_rng(7)
    n1 = fam.n + 1
    c = rng.normal(size=n1) + 1j * rng.normal(size=n1)
    Fh = HomogenizedQuadratic(fam, c)
    ps = [rng.normal(size=fam.m) + 1j * rng.normal(size=fam.m) for _ in range(2)]
    dps = [rng.normal(size=fam.m) + 1j * rng.normal(size=fam.m) for _ in range(2)]
    y = rng.normal(size=n1) + 1j * rng.normal(size=n1)

    def call(ws, a, b):
        """b None: F and J only (the Newton evaluation), else also Ht with dp = dps[b]."""
        F, Ht = np.empty(n1, complex), np.empty(n1, complex)
        J = np.zeros((n1, n1), complex)
        pc = np.concatenate([ps[a], c])
        dpc = pc if b is None else np.concatenate([dps[b], np.zeros(n1)])
        homogenized_eval(taut_fj, taut_fjt, y, pc, dpc, F, J, F if b is None else Ht, b is not None, *ws)
        return F, J, None if b is None else Ht

    ws = homogenized_workspace(n1, fam.m + n1, True)
    for a, b in [(0, 0), (0, None), (0, 0), (0, 1), (1, None), (0, 0), (0, 0), (0, None)]:
        got = call(ws, a, b)
        ref = call(homogenized_workspace(n1, fam.m + n1, True), a, b)
        for u, v in zip(got, ref):
            assert (u is None and v is None) or np.array_equal(u, v)
        F0, J0 = Fh.evaluate_and_jacobian(y[None], ps[a])
        assert np.abs(got[0] - F0[0]).max() <= 1e-12 * (1 + np.abs(F0).max())
        assert np.abs(got[1] - J0[0]).max() <= 1e-12 * (1 + np.abs(J0).max())
    ws[2][5, 0] += 1.0  # F at the origin, as kept: the same parameters again read it
    assert not np.array_equal(call(ws, 0, None)[0], ref[0])


@pytest.mark.parametrize("m", [2, 4, 6])
def test_study_solve_equals_dense(m):
    """The structured LU of the Study Jacobian (lam columns first, the statics rows on top) solves it like numpy, for
    several right-hand sides, also near N = 0 (e nearly isotropic), where the Study paths that are hard to track
    run."""
    from cdpr_algebra.dgp.kernels import study_apply, study_factor
    from cdpr_algebra.dgp.study_retrack import fast_study_family

    fam = fast_study_family(m)
    rng = np.random.default_rng(50 + m)
    p = rng.normal(size=fam.m) + 1j * rng.normal(size=fam.m)
    X = rng.normal(size=(2, fam.n)) + 1j * rng.normal(size=(2, fam.n))
    X[1, :4] = [1.0, 1j, 1e-3, 0.2]  # e . e = 1e-6 + 0.04 - ... nearly isotropic in its first two entries
    _, Js = fam.evaluate_and_jacobian(X, p)
    assert np.all(Js[:, : m + 2, 8:] == 0)  # lam enters the statics rows only
    _assert_solves_like_numpy(study_factor, study_apply, Js, rng)
    assert fam.compiled_kernels()[2] is study_factor
