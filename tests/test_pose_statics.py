"""Rotation parametrizations, the wrench matrix and the reduced Hessian."""

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from cdpr_algebra.model.pose import (Pose, angles_from_matrix, euler_parameters_from_matrix, matrix_from_angles,
                               matrix_from_euler_parameters, matrix_from_rodrigues, rodrigues_from_matrix)
from cdpr_algebra.model.stability import hessian_class, reduced_hessian
from cdpr_algebra.model.statics import equilibrium_tensions, wrench_matrix


def test_fixed_axes_angles_match_scipy_extrinsic_xyz():
    rng = np.random.default_rng(1)
    for ang in rng.uniform(-np.pi, np.pi, (50, 3)):
        ang[1] /= 2
        R = matrix_from_angles(*ang)
        assert np.allclose(R, Rotation.from_euler("xyz", ang).as_matrix())  # extrinsic x, then y, then z
        assert np.allclose(angles_from_matrix(R), ang)


def test_euler_parameters_round_trip_and_scale_invariance():
    rng = np.random.default_rng(2)
    for q in rng.normal(size=(50, 4)):
        R = matrix_from_euler_parameters(q)
        assert np.allclose(R.T @ R, np.eye(3)) and np.isclose(np.linalg.det(R), 1)
        assert np.allclose(matrix_from_euler_parameters(3.7 * q), R)
        q2 = euler_parameters_from_matrix(R)
        assert np.allclose(matrix_from_euler_parameters(q2), R)
        assert np.allclose(q2, np.sign(q[0]) * q / np.linalg.norm(q))
        # scipy is scalar-last
        assert np.allclose(R, Rotation.from_quat([q[1], q[2], q[3], q[0]]).as_matrix())


def test_half_turn_e0_zero():
    axis = np.array([1.8939390744332848908, 0, 1])
    R = matrix_from_euler_parameters([0, *axis])
    u = axis / np.linalg.norm(axis)
    assert np.allclose(R, 2 * np.outer(u, u) - np.eye(3))
    assert rodrigues_from_matrix(R) is None
    q = euler_parameters_from_matrix(R)
    assert abs(q[0]) < 1e-15 and np.allclose(np.abs(q[1:]), np.abs(u))


def test_rodrigues():
    e = np.array([0.7634246351375643899, 0.2144041953164012399, 0.4807389069063061451])
    R = matrix_from_rodrigues(*e)
    assert np.allclose(rodrigues_from_matrix(R), e)
    theta = 2 * np.arctan(np.linalg.norm(e))
    assert np.allclose(R, Rotation.from_rotvec(theta * e / np.linalg.norm(e)).as_matrix())


def test_pose_from_com():
    R = matrix_from_angles(0.1, -0.2, 0.3)
    p = Pose.from_com([1, 2, 3], R, [0.3, 0.3, 0.3])
    assert np.allclose(p.transform([0.3, 0.3, 0.3]), [1, 2, 3])


def test_wrench_matrix_change_of_pole():
    """M(P) = [[I, 0], [-skew(P), I]] M(O): a unimodular row operation, so every rank condition is pole-free."""
    from cdpr_algebra.model.pose import skew

    rng = np.random.default_rng(3)
    A, B, G, d = rng.normal(size=(3, 3)), rng.normal(size=(3, 3)), rng.normal(size=3), np.array([0, 0, 1.0])
    M0 = wrench_matrix(A, B, G, d)
    s = B[0] - A[0]
    assert np.allclose(M0[:, 0], -np.concatenate([s, np.cross(B[0], s)]))  # L_i = -[s_i; B_i x s_i]
    assert np.allclose(M0[:, 3], np.concatenate([d, np.cross(G, d)]))  # L_e = [k; G x k]
    for P in rng.normal(size=(3, 3)):
        T = np.block([[np.eye(3), np.zeros((3, 3))], [-skew(P), np.eye(3)]])
        assert np.allclose(wrench_matrix(A, B, G, d, pole=P), T @ M0)


def test_tensions_of_a_hanging_mass():
    # one vertical cable: tension = Q, residual zero
    eq = equilibrium_tensions([[0, 0, 5.0]], [[0, 0, 2.0]], [0, 0, 1.0], 3.0, [0, 0, -1.0])
    assert np.allclose(eq.tensions, [3.0]) and eq.residual < 1e-15 and np.allclose(eq.lengths, [3.0])


@pytest.mark.parametrize("g_z, expected", [(1.0, ">="), (3.0, "<>")])
def test_pendulum_stability(g_z, expected):
    """One taut cable from A = (0,0,5) to B = (0,0,2): G below B is a stable pendulum (rotation about the cable
    costs nothing: '>='), G above B is inverted (indefinite)."""
    A, B, G = np.array([[0, 0, 5.0]]), np.array([[0, 0, 2.0]]), np.array([0, 0, g_z])
    eq = equilibrium_tensions(A, B, G, 1.0, [0, 0, -1.0])
    Hr = reduced_hessian(A, B, G, eq.tensions, eq.lengths)
    assert Hr.shape == (5, 5)
    assert hessian_class(Hr, scale=1.0) == expected


def test_hessian_class_tolerance():
    assert hessian_class(np.diag([1.0, 1e-12]), 1.0) == ">="
    assert hessian_class(np.diag([-1.0, -1e-12]), 1.0) == "<="
    assert hessian_class(np.diag([-1.0, -2.0]), 1.0) == "<"
    assert hessian_class(np.zeros((0, 0)), 1.0) == ">"
