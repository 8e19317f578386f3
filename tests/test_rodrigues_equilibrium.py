"""The generated 6-cable equilibrium system of the uncertainty criterion (derivations/derive_rodrigues_equilibrium.py):
zero at an equilibrium computed independently (the statics of cc/configurations), Jacobian equal to central
differences, and the length block identical to the first rows of the full system."""

import numpy as np

from cdpr_algebra import load_robot
from cdpr_algebra.cc.configurations import configuration_tensions
from cdpr_algebra.generated.rodrigues_equilibrium import rodrigues_equilibrium, rodrigues_lengths
from cdpr_algebra.model.pose import matrix_from_rodrigues

CABLES = (2, 3, 4, 5, 6, 7)


def _args(robot, z, R0):
    e = z[3:6]
    q = 1.0 / (1.0 + e @ e)
    A = robot.base[list(CABLES)]
    c = robot.platform[list(CABLES)] - robot.com
    R = R0 @ matrix_from_rodrigues(*e)
    rho = np.linalg.norm(A - z[:3] - c @ R.T, axis=1)  # lengths that make the pose exact
    f = -robot.load * np.concatenate([robot.load_direction, np.zeros(3)])
    return q, A.ravel(), c.ravel(), rho, R0.ravel(), f


def test_zero_at_an_equilibrium_and_jacobian_by_differences():
    robot = load_robot("examples/seed002_8cables.toml")
    G = np.array([0.0, 1.0, 2.0])
    cc = configuration_tensions(robot, G, CABLES)
    assert cc.valid
    R0 = np.eye(3)
    A = robot.base[list(CABLES)]
    c = robot.platform[list(CABLES)] - robot.com
    lam = cc.tensions / np.linalg.norm(A - G - c, axis=1)  # tau_i / rho_i
    z = np.concatenate([G, np.zeros(3), lam])
    q, Af, cf, rho, R0f, f = _args(robot, z, R0)
    v = np.array(rodrigues_equilibrium(*z, q, *Af, *cf, *rho, *R0f, *f), dtype=float)
    assert np.abs(v[:12]).max() <= 1e-12 * robot.load * 10
    # Jacobian at a generic point against central differences (rho, f held fixed)
    rng = np.random.default_rng(3)
    z1 = z + 0.05 * rng.normal(size=12)

    def F(zz):
        ee = zz[3:6]
        return np.array(rodrigues_equilibrium(*zz, 1.0 / (1.0 + ee @ ee), *Af, *cf, *rho, *R0f, *f)[:12], dtype=float)

    J = np.array(rodrigues_equilibrium(*z1, 1.0 / (1.0 + z1[3:6] @ z1[3:6]), *Af, *cf, *rho, *R0f, *f)[12:],
                 dtype=float).reshape(12, 12)
    h = 1e-6
    Jd = np.array([(F(z1 + h * e) - F(z1 - h * e)) / (2 * h) for e in np.eye(12)]).T
    assert np.allclose(J, Jd, atol=1e-6 * (1 + np.abs(J).max()))
    # the length block: rows 0-5 and d(statics)/d lam of the full system
    qq = 1.0 / (1.0 + z1[3:6] @ z1[3:6])
    L = np.array(rodrigues_lengths(*z1[:6], qq, *Af, *cf, *rho, *R0f), dtype=float)
    assert np.allclose(L[:6], F(z1)[:6])
    assert np.allclose(L[6:42].reshape(6, 6), J[:6, :6])
    assert np.allclose(L[42:].reshape(6, 6), J[6:, 6:])
