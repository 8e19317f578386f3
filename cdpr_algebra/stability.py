"""Stability of an equilibrium from the reduced Hessian (seed 000 eqs. 28-30; Carricato and Merlet 2013).

With r_i = B_i - G, s_i = B_i - A_i and small displacements (dG, theta) of the platform,
H = sum_i tau_i / rho_i [[I, -skew(r_i)], [skew(r_i), (skew(r_i) skew(G - A_i) + skew(G - A_i) skew(r_i)) / 2]]
(eq. 29), J^T has rows [s_i^T, (r_i x s_i)^T] / rho_i (eq. 30), N spans its null space and H_r = N^T H N (eq. 28).
The load does no work in rotations about G, so it adds nothing to H.
"""

from __future__ import annotations

import numpy as np
import scipy.linalg

from .pose import skew

CLASSES = (">", ">=", "<", "<=", "<>")


def hessian(A, B, G, tensions, lengths) -> np.ndarray:
    """The 6 x 6 matrix H of seed 000 eq. (29) (moment pole G)."""
    H = np.zeros((6, 6))
    for a, b, t, rho in zip(np.atleast_2d(A), np.atleast_2d(B), tensions, lengths):
        r = skew(b - G)
        ga = skew(G - a)
        blk = np.block([[np.eye(3), -r], [r, 0.5 * (r @ ga + ga @ r)]])
        H += (t / rho) * blk
    return H


def constraint_jacobian(A, B, G, lengths) -> np.ndarray:
    """J^T of seed 000 eq. (30): rows [s_i^T, ((B_i - G) x s_i)^T] / rho_i."""
    A = np.atleast_2d(A)
    B = np.atleast_2d(B)
    s = B - A
    return np.hstack([s, np.cross(B - G, s)]) / np.asarray(lengths)[:, None]


def reduced_hessian(A, B, G, tensions, lengths, length_scale: float = 1.0) -> np.ndarray:
    """H_r = N^T H N (seed 000 eq. 28), in coordinates (dG, L theta) with L = ``length_scale``.

    Scaling rotations by a length makes every entry a stiffness (force / length), so one tolerance fits all.
    """
    T = np.diag([1.0, 1.0, 1.0] + [1.0 / length_scale] * 3)
    H = T @ hessian(A, B, G, tensions, lengths) @ T
    JT = constraint_jacobian(A, B, G, lengths) @ T
    N = scipy.linalg.null_space(JT) if len(JT) else np.eye(6)
    return N.T @ H @ N


def hessian_class(Hr, scale: float, rtol: float = 1e-8) -> str:
    """'>', '>=', '<', '<=' or '<>' (positive definite ... indefinite).

    Eigenvalues with |lambda| <= rtol * scale count as zero; ``scale`` is a stiffness of the problem
    (e.g. sum tau_i / rho_i + Q / L). An empty H_r (platform fully constrained) is '>'.
    """
    if Hr.size == 0:
        return ">"
    lam = np.linalg.eigvalsh(0.5 * (Hr + Hr.T))
    tol = rtol * scale
    pos = lam > tol
    neg = lam < -tol
    if pos.all():
        return ">"
    if neg.all():
        return "<"
    if pos.any() and neg.any():
        return "<>"
    if not neg.any():
        return ">="
    return "<="
