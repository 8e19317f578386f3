"""Stability of an equilibrium from the reduced Hessian (seed 000 eqs. 28-30; Carricato and Merlet 2013).

With r_i = B_i - G, s_i = B_i - A_i and small displacements (dG, theta) of the platform,
H = sum_i tau_i / rho_i [[I, -skew(r_i)], [skew(r_i), (skew(r_i) skew(G - A_i) + skew(G - A_i) skew(r_i)) / 2]]
(eq. 29), J^T has rows [s_i^T, (r_i x s_i)^T] / rho_i (eq. 30), N spans its null space and H_r = N^T H N (eq. 28).
The load does no work in rotations about G, so it adds nothing to H.  Every function takes a stack of poses
(leading dimensions on B, G, tensions, lengths).
"""

from __future__ import annotations

import numpy as np

from .statics import cross

CLASSES = (">", ">=", "<", "<=", "<>")


def skew_stack(v) -> np.ndarray:
    """skew(v) for v (..., 3) -> (..., 3, 3) (written component by component: this is in the DGP's hot loop)."""
    v = np.asarray(v)
    S = np.zeros(v.shape + (3,), dtype=v.dtype)
    S[..., 0, 1] = -v[..., 2]
    S[..., 0, 2] = v[..., 1]
    S[..., 1, 0] = v[..., 2]
    S[..., 1, 2] = -v[..., 0]
    S[..., 2, 0] = -v[..., 1]
    S[..., 2, 1] = v[..., 0]
    return S


def hessian(A, B, G, tensions, lengths) -> np.ndarray:
    """The 6 x 6 matrix H of seed 000 eq. (29) (moment pole G); shape (..., 6, 6)."""
    B = np.asarray(B)
    G = np.asarray(G)[..., None, :]
    r = skew_stack(B - G)  # (..., m, 3, 3)
    ga = skew_stack(G - np.asarray(A))
    w = (np.asarray(tensions) / np.asarray(lengths))[..., None, None]
    H = np.zeros(B.shape[:-2] + (6, 6), dtype=np.result_type(B, w))
    H[..., :3, :3] = np.sum(w, axis=-3) * np.eye(3)
    H[..., :3, 3:] = -np.sum(w * r, axis=-3)
    H[..., 3:, :3] = np.sum(w * r, axis=-3)
    H[..., 3:, 3:] = 0.5 * np.sum(w * (r @ ga + ga @ r), axis=-3)
    return H


def constraint_jacobian(A, B, G, lengths) -> np.ndarray:
    """J^T of seed 000 eq. (30): rows [s_i^T, ((B_i - G) x s_i)^T] / rho_i; shape (..., m, 6)."""
    B = np.asarray(B)
    s = B - np.asarray(A)
    return np.concatenate([s, cross(B - np.asarray(G)[..., None, :], s)], axis=-1) / np.asarray(lengths)[..., None]


def null_space(JT) -> np.ndarray:
    """Orthonormal null-space basis (..., 6, 6 - rank); stacks must share one rank (else per item)."""
    if JT.shape[-2] == 0:
        return np.broadcast_to(np.eye(6), JT.shape[:-2] + (6, 6))
    _, s, vh = np.linalg.svd(JT, full_matrices=True)
    tol = np.max(s, axis=-1, keepdims=True) * max(JT.shape[-2:]) * np.finfo(float).eps
    rank = np.sum(s > tol, axis=-1)
    if JT.ndim == 2:  # the rank rule of scipy.linalg.null_space, by numpy alone
        return vh[int(rank):, :].T.conj()
    if np.all(rank == JT.shape[-2]):
        return np.swapaxes(vh[..., JT.shape[-2]:, :], -1, -2).conj()
    raise np.linalg.LinAlgError("rank-deficient J^T in a stack: call reduced_hessian per pose")


def reduced_hessian(A, B, G, tensions, lengths, length_scale: float = 1.0) -> np.ndarray:
    """H_r = N^T H N (seed 000 eq. 28), in coordinates (dG, L theta) with L = ``length_scale``.

    Scaling rotations by a length makes every entry a stiffness (force / length), so one tolerance fits all.
    """
    T = np.diag([1.0, 1.0, 1.0] + [1.0 / length_scale] * 3)
    H = T @ hessian(A, B, G, tensions, lengths) @ T
    N = null_space(constraint_jacobian(A, B, G, lengths) @ T)
    return np.swapaxes(N, -1, -2) @ H @ N


def hessian_class(Hr, scale, rtol: float = 1e-8):
    """'>', '>=', '<', '<=' or '<>' (positive definite ... indefinite); a list for a stack.

    Eigenvalues with |lambda| <= rtol * scale count as zero; ``scale`` is a stiffness of the problem
    (e.g. sum |tau_i| / rho_i + Q / L). An empty H_r (platform fully constrained) is '>'.
    """
    Hr = np.asarray(Hr)
    if Hr.shape[-1] == 0:
        return [">"] * int(np.prod(Hr.shape[:-2])) if Hr.ndim > 2 else ">"
    lam = np.linalg.eigvalsh(0.5 * (Hr + np.swapaxes(Hr, -1, -2)))
    tol = rtol * np.asarray(scale, dtype=float)[..., None]
    pos = np.all(lam > tol, axis=-1), np.any(lam > tol, axis=-1)
    neg = np.all(lam < -tol, axis=-1), np.any(lam < -tol, axis=-1)
    out = np.where(pos[0], ">", np.where(neg[0], "<", np.where(pos[1] & neg[1], "<>", np.where(neg[1], "<=", ">="))))
    return out.tolist() if out.ndim else str(out)


def stability_classes(A, B, G, tensions, lengths, load: float, length_scale: float):
    """Class of H_r for one pose or a stack of poses, with the tolerance scale of the problem:
    sum |tau_i| / rho_i + Q / L (a stiffness).  A stack whose J^T ranks differ is done pose by pose."""
    tensions = np.asarray(tensions)
    lengths = np.asarray(lengths)
    try:
        Hr = reduced_hessian(A, B, G, tensions, lengths, length_scale=length_scale)
    except np.linalg.LinAlgError:  # a stack with parallel cables somewhere: one at a time
        Hr = np.array([reduced_hessian(A, b, g, t, ln, length_scale=length_scale)
                       for b, g, t, ln in zip(B, G, tensions, lengths)])
    scale = np.sum(np.abs(tensions) / lengths, axis=-1) + load / length_scale
    return hessian_class(Hr, scale)
