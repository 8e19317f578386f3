"""Test helper: a robot around a known equilibrium (shared by tests/test_dgp.py and tests/test_dgp_round_trips.py)."""

import numpy as np

from cdpr_algebra.model.pose import matrix_from_angles


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
