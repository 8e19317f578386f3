"""Uncertainty criterion (seed 002 Sec. II-D, IV-D).

Oracle: CC [3,4,5,6,7,8] at (0, 1, 2) stays valid with +-5 mm on A, +-1 mm on B, +-5 mm on rho (robot in metres).
Independent checks: random robots in the ranges, their equilibria by plain-numpy Newton (continuation from the
nominal robot), tensions inside the proven bounds; a counterexample re-verified with plain numpy (within the
ranges, cable lengths and statics satisfied, a negative tension).
"""

import numpy as np
import pytest

from cdpr_algebra import load_robot
from cdpr_algebra.cc.uncertainty import uncertainty_check
from cdpr_algebra.model.errors import CdprInputError
from cdpr_algebra.model.pose import matrix_from_angles

CC = (2, 3, 4, 5, 6, 7)


@pytest.fixture(scope="module")
def robot():
    return load_robot("examples/seed002_8cables.toml")


def _equilibrium_numpy(robot, A, b, rho, G0, iters=50):
    """Plain numpy Newton (finite-difference Jacobian) on the 6 lengths with the rotation as fixed-axes angles, then
    the tensions from the statics about G; continuation in 10 steps from the nominal geometry."""
    def pose_res(x, A_, b_, rho_):
        R = matrix_from_angles(*x[3:])
        B = x[:3] + (b_ - robot.com) @ R.T
        return np.linalg.norm(A_ - B, axis=1) - rho_

    A0 = robot.base[list(CC)]
    b0 = robot.platform[list(CC)]
    rho0 = np.linalg.norm(A0 - (G0 + b0 - robot.com), axis=1)
    x = np.concatenate([G0, np.zeros(3)])
    for s in np.linspace(0.1, 1, 10):
        A_, b_, rho_ = A0 + s * (A - A0), b0 + s * (b - b0), rho0 + s * (rho - rho0)
        for _ in range(iters):
            f = pose_res(x, A_, b_, rho_)
            J = np.array([(pose_res(x + h, A_, b_, rho_) - pose_res(x - h, A_, b_, rho_)) / 2e-7
                          for h in np.eye(6) * 1e-7]).T
            dx = np.linalg.solve(J, -f)
            x = x + dx
            if np.abs(dx).max() < 1e-14:
                break
    R = matrix_from_angles(*x[3:])
    B = x[:3] + (b - robot.com) @ R.T
    s = A - B
    M = np.vstack([s.T, np.cross(B - x[:3], s).T])
    lam = np.linalg.solve(M, -robot.load * np.concatenate([robot.load_direction, np.zeros(3)]))
    return x, lam * rho, np.abs(pose_res(x, A, b, rho)).max()


@pytest.mark.slow
def test_seed002_cc345678_robust_to_5mm(robot):
    res = uncertainty_check(robot, (0, 1, 2), CC, dA=0.005, dB=0.001, drho=0.005)
    assert res.robust is True and res.counterexample is None
    assert np.all(res.tension_bounds[:, 0] > 0)  # its time: benchmarks/bench_cc.py (Sec. IV-D uncertainty)


def test_small_tolerances_proven_with_unique_equilibrium(robot):
    """+-0.1 mm: one parametric Krawczyk test proves existence, uniqueness and the tension bounds; random robots in
    the ranges (plain numpy equilibria) have their tensions inside the bounds."""
    d = 1e-4
    res = uncertainty_check(robot, (0, 1, 2), CC, dA=d, dB=d, drho=d)
    assert res.robust is True and res.equilibrium_box["unique"] is True
    lo, hi = res.tension_bounds[:, 0], res.tension_bounds[:, 1]
    rng = np.random.default_rng(0)
    A0, b0 = robot.base[list(CC)], robot.platform[list(CC)]
    rho0 = np.linalg.norm(A0 - (np.array([0, 1, 2]) + b0), axis=1)
    for _ in range(5):
        A = A0 + rng.uniform(-d, d, A0.shape)
        b = b0 + rng.uniform(-d, d, b0.shape)
        rho = rho0 + rng.uniform(-d, d, 6)
        x, tau, res_ = _equilibrium_numpy(robot, A, b, rho, np.array([0.0, 1, 2]))
        assert res_ < 1e-10
        assert np.all(lo <= tau) and np.all(tau <= hi)
        assert np.linalg.norm(x[:3] - [0, 1, 2]) <= res.equilibrium_box["position"]


def test_counterexample_when_tolerances_are_large(robot):
    res = uncertainty_check(robot, (1, 0, 2), CC, dA=0.02, dB=0.005, drho=0.02)
    assert res.robust is False
    cx = res.counterexample
    A, b, rho = np.array(cx["A"]), np.array(cx["platform"]), np.array(cx["lengths"])
    A0, b0 = robot.base[list(CC)], robot.platform[list(CC)]
    rho0 = np.linalg.norm(A0 - (np.array([1.0, 0, 2]) + b0), axis=1)
    assert np.abs(A - A0).max() <= 0.02 + 1e-12 and np.abs(b - b0).max() <= 0.005 + 1e-12
    assert np.abs(rho - rho0).max() <= 0.02 + 1e-12
    x, tau, res_ = _equilibrium_numpy(robot, A, b, rho, np.array([1.0, 0, 2]))
    assert res_ < 1e-9
    np.testing.assert_allclose(x[:3], cx["position"], atol=1e-6)
    np.testing.assert_allclose(tau, cx["tensions"], rtol=1e-6, atol=1e-9)
    assert tau.min() < 0 and CC[int(np.argmin(tau))] + 1 == cx["cable"]


def test_input_errors(robot):
    with pytest.raises(CdprInputError, match="not a valid CC"):
        uncertainty_check(robot, (0, 1, 2), (0, 1, 2, 3, 4, 6))
    with pytest.raises(CdprInputError, match="dA"):
        uncertainty_check(robot, (0, 1, 2), CC, dA=-1)
