"""Test helper: a robot around a known equilibrium (shared by tests/test_dgp.py and tests/test_dgp_round_trips.py)."""

import numpy as np

from cdpr_algebra.model.pose import matrix_from_angles
from cdpr_algebra.model.robot import Robot


def hang_platform(rng, B, U, G):
    """Anchors and platform frame around an equilibrium whose cable i pulls at B_i along the unit vector U_i (from
    B_i up to A_i), with the centre of mass at G: lengths rho_i drawn in [3, 6], A_i = B_i + rho_i U_i, a random
    rotation R and origin p near G.  Returns (A, b, g, rho, p, R) with b_i = R^T (B_i - p), g = R^T (G - p)."""
    m = len(B)
    rho = rng.uniform(3.0, 6.0, size=m)
    A = B + rho[:, None] * U
    R = matrix_from_angles(*rng.uniform(-np.pi, np.pi, 3) * np.array([1, 0.4, 1]))
    p = G + rng.uniform(-0.2, 0.2, 3)
    return A, (B - p) @ R, R.T @ (G - p), rho, p, R


def all_taut_equilibrium_robot(m, seed):
    """A robot with m cables holding a known equilibrium, all taut (tests/test_dgp_round_trips.py: directions,
    anchors and G chosen so that the wrench balance is a square linear system in the tensions and the free part of
    G, kept when every tension exceeds 0.05 Q).  Returns (robot, p, R, tau)."""
    rng = np.random.default_rng(seed)
    d = np.array([0.0, 0.0, -1.0])
    e1, e2 = np.eye(3)[0], np.eye(3)[1]  # G = G0 + a e1 + b e2: only G's part across d enters the moment
    while True:
        Q = float(rng.uniform(5, 20))
        U = np.array([[*rng.uniform(-0.7, 0.7, 2), 1.0] for _ in range(m)])
        U /= np.linalg.norm(U, axis=1)[:, None]  # unit directions from B_i up to A_i
        B = rng.uniform(-0.5, 0.5, size=(m, 3))
        G0 = np.array([*rng.uniform(-0.2, 0.2, 2), -0.3])
        # force: sum tau_i U_i + Q d = 0; moment about the origin: sum tau_i B_i x U_i + G x Q d = 0
        W = np.vstack([U.T, np.cross(B, U).T])  # 6 x m
        rhs = -np.concatenate([Q * d, np.cross(G0, Q * d)])
        cols = [np.concatenate([np.zeros(3), np.cross(e, Q * d)]) for e in (e1, e2)][: 6 - m]  # free part of G
        M = np.column_stack([W] + cols)
        if abs(np.linalg.det(M)) < 1e-6:
            continue
        z = np.linalg.solve(M, rhs)
        tau = z[:m]
        G = G0 + sum(c * e for c, e in zip(z[m:], (e1, e2)))
        if np.all(tau > 0.05 * Q):
            break
    A, b, g, rho, p, R = hang_platform(rng, B, U, G)
    robot = Robot(A, b, g, Q, d, rho, name=f"equilibrium{m}")
    return robot, p, R, tau
