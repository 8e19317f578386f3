"""The complex-interval rewrite of plain-arithmetic evaluators (intervals/codegen.py) and the compiled Krawczyk
round (intervals/complex_kernels.py) against the Python interval objects they replace in the DGP's endpoint
certificates."""

from pathlib import Path

import numba as nb
import numpy as np
import pytest

from cdpr_algebra.intervals import complex_kernels as CKN
from cdpr_algebra.intervals.codegen import complex_interval_source

ROOT = Path(__file__).resolve().parents[1]

PLAIN = '''
def f(x, p, F, J):
    m = len(x) - 1
    a = p[0]
    t0 = 2*a + 3
    F[0] = t0*x[0] - a*a - x[0]*x[1]
    s = -a
    for i in range(m):
        t0 = x[1 + i]*p[1 + i]
        s += t0*x[0]
        J[0, 1 + i] = x[0]*p[1 + i]
    F[1] = s
'''


def _compile(source):
    ns = {name: getattr(CKN, name) for name in CKN.OPERATIONS}
    exec(complex_interval_source(source, flags=(), real=("p",)), ns)
    return nb.njit(ns["f"])


def test_rewritten_evaluator_encloses_the_complex_values():
    """Over random boxes, F and J of the rewritten function contain the values of the plain function at random
    complex points of the box (real parameters, the loop's temporaries reusing a name of the outer code)."""
    f = _compile(PLAIN)
    plain = {}
    exec(PLAIN, plain)
    rng = np.random.default_rng(7)
    for _ in range(20):
        n = 4
        c = rng.normal(size=n) + 1j * rng.normal(size=n)
        r = 10.0 ** rng.uniform(-12, -2)
        x = np.stack([c.real - r, c.real + r, c.imag - r, c.imag + r], axis=1)
        pv = rng.normal(size=n)
        p = np.stack([pv, pv, 0 * pv, 0 * pv], axis=1)
        F, J = np.zeros((2, 4)), np.zeros((1, n, 4))
        f(x, p, F, J)
        for _ in range(50):
            z = c + r * (rng.uniform(-1, 1, n) + 1j * rng.uniform(-1, 1, n))
            Fz, Jz = np.zeros(2, complex), np.zeros((1, n), complex)
            plain["f"](z, pv, Fz, Jz)
            for got, val in [(F[k], Fz[k]) for k in range(2)] + [(J[0, k], Jz[0, k]) for k in range(1, n)]:
                assert got[0] <= val.real <= got[1] and got[2] <= val.imag <= got[3]
        # a point box gives a tight enclosure of the exact value
        x0 = np.stack([c.real, c.real, c.imag, c.imag], axis=1)
        f(x0, p, F, J)
        assert np.all(F[:, 1] - F[:, 0] <= 1e-13 * (1 + np.abs(F[:, 0])))


def test_rewrite_refuses_what_is_not_plain_arithmetic():
    with pytest.raises(ValueError, match="not plain arithmetic"):
        complex_interval_source("def f(x, F):\n    F[0] = x[0] / x[1]\n")


def test_generated_interval_evaluator_is_the_rewrite_of_the_float_one():
    """The interval evaluators are the rewrite of the generated float ones (the derivation test re-runs the script;
    this checks the F of a point box against the float evaluation)."""
    from cdpr_algebra.generated.taut_equations import taut_equations as F_float
    from cdpr_algebra.generated.taut_equations_intervals import taut_equations, taut_residual

    rng = np.random.default_rng(3)
    for m in (2, 4, 6):
        n = 12 + m
        z = rng.normal(size=n) + 1j * rng.normal(size=n)
        pv = rng.normal(size=7 * m + 6)
        Ff, Jf = np.zeros(n, complex), np.zeros((n, n), complex)
        F_float(z, pv, None, Ff, Jf, None, False)
        x = np.ascontiguousarray(np.stack([z.real, z.real, z.imag, z.imag], axis=1))
        p = np.ascontiguousarray(np.stack([pv, pv, 0 * pv, 0 * pv], axis=1))
        for ev in (taut_equations, taut_residual):
            F, J = np.zeros((n, 4)), np.zeros((n, n, 4))
            ev(x, p, p, F, J, F, False)
            assert np.all((F[:, 0] <= Ff.real) & (Ff.real <= F[:, 1]) & (F[:, 2] <= Ff.imag) & (Ff.imag <= F[:, 3]))
        taut_equations(x, p, p, F, J, F, False)
        assert np.all((J[..., 0] <= Jf.real) & (Jf.real <= J[..., 1]) & (J[..., 2] <= Jf.imag) & (Jf.imag <= J[..., 3]))


@pytest.mark.parametrize("example, cables", [("seed000_test1.toml", (0, 1, 2)), ("seed000_test3.toml", (1, 2, 3, 4))])
def test_compiled_krawczyk_proves_what_the_interval_objects_prove(example, cables, monkeypatch):
    """The DGP endpoints of a taut set certified with the compiled Krawczyk round and with the Python interval
    objects: the same roots proven, each box holding the other's centre, widths within 10 %."""
    from cdpr_algebra.certificates import endpoints as EQ
    from cdpr_algebra.dgp import solve as D
    from cdpr_algebra.model.robot import load_robot

    robot = load_robot(ROOT / "examples" / example)
    rho = np.asarray(robot.lengths, float)
    _, _, Z = D._solve_taut_set(robot, rho, cables)
    assert len(Z) >= 100
    ((fast, _),) = EQ.certify_endpoints(robot, rho, [(cables, Z)], [False])
    monkeypatch.setattr(EQ, "_compiled_krawczyk", lambda *a: None)
    ((slow, _),) = EQ.certify_endpoints(robot, rho, [(cables, Z)], [False])
    # (about 10 % of Test 3's {2, 3, 4, 5} endpoints are complex rotations with |R| ~ 1e3-1e4, ill-conditioned
    # beyond double precision's Krawczyk test: the ball retry proves them)
    assert fast.proven.sum() >= 0.8 * len(Z)
    assert np.array_equal(fast.proven, slow.proven)
    k = fast.proven
    for a, b in ((fast, slow), (slow, fast)):
        mid = 0.5 * (b.lo[k] + b.hi[k])
        assert np.all((a.lo[k] <= mid) & (mid <= a.hi[k]))
    ratio = (fast.hi[k] - fast.lo[k]) / (slow.hi[k] - slow.lo[k])
    assert 0.9 <= np.median(ratio) <= 1.1


def _sqrt2_kernel(ok_value=True):
    """The Krawczyk operator of x^2 - 2 (one unknown) over the boxes y -+ r in the Python interval objects, C the
    inverse of 2 y: a kernel for certify_real_roots."""
    from cdpr_algebra.intervals.arithmetic import Interval

    def kernel(part, y, r):
        X = Interval(y - r, y + r)
        C = 1.0 / (2.0 * y)
        Fy = Interval.point(y).sqr() - 2.0
        K = (Interval.point(y) - Fy * C) + (1.0 - (2.0 * X) * C) * (X - Interval.point(y))
        return K, np.full(len(y), ok_value)

    return kernel


def test_certify_real_roots_encloses_sqrt2_and_counts_its_failures():
    """The epsilon-inflation driver of the compiled real Krawczyk rounds: the box proven around sqrt(2) (double
    nearest, and a point 1e-13 off) holds the exact root (arb), within the width limit; a root whose operator cannot
    be formed, or a non-finite one, is not proven and says why."""
    from flint import arb

    from cdpr_algebra.intervals.real_krawczyk import certify_real_roots

    Y = np.array([[np.sqrt(2.0)], [np.sqrt(2.0) + 1e-13], [np.nan]])
    boxes = certify_real_roots(_sqrt2_kernel(), Y, 1.0, max_rel_width=1e-9)
    assert boxes.proven.tolist() == [True, True, False] and "not finite" in boxes.reason[2]
    root = arb(2).sqrt()
    for k in (0, 1):
        assert arb(boxes.lo[k, 0]) < root < arb(boxes.hi[k, 0]) and boxes.rounds[k] >= 1
        assert boxes.hi[k, 0] - boxes.lo[k, 0] <= 1e-9
    bad = certify_real_roots(_sqrt2_kernel(False), Y[:1], 1.0, max_rel_width=1e-9)
    assert not bad.proven[0] and bad.rounds[0] == 0 and "not proven" in bad.reason[0]
