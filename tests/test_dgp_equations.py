"""The DGP formulation (pose columns and lam_i = tau_i / rho_i): square, quadratic, and zero at equilibria."""

import numpy as np
import pytest

from cdpr_algebra import load_robot
from cdpr_algebra.model.taut_equations import decode, encode, taut_family, taut_parameters
from cdpr_algebra.model.pose import matrix_from_angles


@pytest.mark.parametrize("m", [2, 3, 4, 5, 6])
def test_square_and_quadratic(m):
    fam = taut_family(m)
    assert fam.n == fam.neq == 12 + m and max(fam.degrees) == 2 and fam.m == 7 * m + 6


def test_seed000_table1_rows_are_zeros():
    """Each printed row of seed 000 Table 1 (3 taut cables) makes the residual as small as its 3 decimals allow."""
    import json

    robot = load_robot("examples/seed000_test1.toml")
    rows = [r for r in json.load(open("tests/data/seed000_tables.json"))["tables"]["1"]["rows"] if r.get("m") == 3]
    fam = taut_family(3)
    p = taut_parameters(robot, [0, 1, 2])
    assert rows
    for row in rows:
        R = matrix_from_angles(*row["angles"])
        lam = np.array(row["tensions"]) / robot.lengths
        x = encode(row["position"], R, lam)
        F = fam.evaluate(x[None, :], p)[0]
        assert np.abs(F[:6]).max() < 1e-12  # rotation equations hold exactly
        assert np.abs(F).max() < 2e-2  # 3 printed decimals on positions, angles and tensions
        p2, R2, lam2 = decode(x, 3)
        assert np.allclose(R2[0], R) and np.allclose(lam2[0], lam)


def test_exact_equilibrium_is_an_exact_zero():
    rng = np.random.default_rng(4)
    R = matrix_from_angles(*rng.uniform(-0.5, 0.5, 3))
    p = rng.normal(size=3)
    robot_base = rng.normal(size=(4, 3)) + [0, 0, 8]
    platform = rng.normal(size=(4, 3)) * 0.5
    com = rng.normal(size=3) * 0.2
    B = p + platform @ R.T
    G = p + R @ com
    # lam from the 6 x 4 least-squares balance for Q d = (0, 0, -1); F's last 6 entries must be its residual
    f = np.array([0, 0, -1.0])
    W = np.vstack([(robot_base - B).T, np.cross(B, robot_base).T])
    lam = np.linalg.lstsq(W, -np.concatenate([f, np.cross(G, f)]), rcond=None)[0]
    res = W @ lam + np.concatenate([f, np.cross(G, f)])
    from cdpr_algebra import Robot

    robot = Robot(base=robot_base, platform=platform, com=com, load=1.0,
                  lengths=np.linalg.norm(B - robot_base, axis=1))
    F = taut_family(4).evaluate(encode(p, R, lam)[None, :], taut_parameters(robot, range(4)))[0]
    assert np.allclose(F[:10], 0, atol=1e-12)  # rotation + cable equations
    assert np.allclose(F[10:], res, atol=1e-12)  # force and moment equations = the balance residual


@pytest.mark.parametrize("m", [2, 4, 6])
def test_generated_residual_is_the_F_of_the_full_evaluator(m):
    """taut_residual (F alone, for interval residuals) gives F of taut_equations bit for bit, on floats and on
    numpy columns, and both agree with the symbolic family."""
    from cdpr_algebra.generated.taut_equations import taut_equations, taut_residual

    rng = np.random.default_rng(m)
    n, npar = 12 + m, 7 * m + 6
    x, p = rng.normal(size=n), rng.normal(size=npar)
    F, J, F2 = np.zeros(n), np.zeros((n, n)), np.zeros(n)
    taut_equations(list(x), list(p), None, F, J, None, False)
    taut_residual(list(x), list(p), F2)
    assert np.array_equal(F, F2)
    assert np.allclose(F, taut_family(m).evaluate(x[None, :], p)[0].real, rtol=1e-12, atol=1e-12)
    X = rng.normal(size=(n, 5))
    Fc = np.zeros((n, 5))
    taut_residual(list(X), list(p), Fc)
    for k in range(5):
        taut_residual(list(X[:, k]), list(p), F2)
        assert np.array_equal(Fc[:, k], F2)
