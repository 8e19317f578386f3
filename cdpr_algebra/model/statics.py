"""Statics of a platform held by m taut cables under a constant load.

Seed 004 eq. (2), (24): the wrench matrix M(P) = [L_1 .. L_m L_e] with L_i = -[s_i; (B_i - P) x s_i],
s_i = B_i - A_i, and L_e = [d; (G - P) x d] for the unit load direction d (seed 004 takes d = k); the platform
is in equilibrium when M [tau_1/rho_1 .. tau_m/rho_m, Q]^T = 0.  Real or complex poses; every function also
takes a stack of poses (leading dimensions on B and G).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


def cross(u, v):
    """u x v over the last axis (faster than np.cross for the small arrays used here)."""
    u = np.asarray(u)
    v = np.asarray(v)
    out = np.empty(np.broadcast_shapes(u.shape, v.shape), dtype=np.result_type(u, v))
    out[..., 0] = u[..., 1] * v[..., 2] - u[..., 2] * v[..., 1]
    out[..., 1] = u[..., 2] * v[..., 0] - u[..., 0] * v[..., 2]
    out[..., 2] = u[..., 0] * v[..., 1] - u[..., 1] * v[..., 0]
    return out


def wrench_matrix(A, B, G, direction, pole=None) -> np.ndarray:
    """The 6 x (m+1) matrix M(P) of seed 004 eq. (24) (rows: force, then moment about ``pole``; default P = O).

    Shapes: A (m, 3), B (..., m, 3), G (..., 3); result (..., 6, m + 1).
    """
    A = np.asarray(A)
    B = np.asarray(B)
    G = np.asarray(G)
    P = np.zeros(3) if pole is None else np.asarray(pole)
    s = B - A
    d = np.broadcast_to(np.asarray(direction), G.shape)
    cables = np.concatenate([-s, -cross(B - P[..., None, :], s)], axis=-1)  # (..., m, 6)
    load = np.concatenate([d, cross(G - P, d)], axis=-1)[..., None, :]  # (..., 1, 6)
    return np.swapaxes(np.concatenate([cables, load], axis=-2), -1, -2)


def cable_lengths(A, B) -> np.ndarray:
    """rho_i = |B_i - A_i|; for complex points sqrt(s^H s) (seed 004 Table 4 convention)."""
    s = np.asarray(B) - np.asarray(A)
    return np.sqrt(np.real(np.sum(np.conj(s) * s, axis=-1)))


@dataclass(frozen=True)
class Equilibrium:
    """Tensions solving M [tau/rho; Q] = 0 in the least-squares sense, and how well they solve it."""

    tensions: np.ndarray  # tau_i (complex if the pose is)
    lengths: np.ndarray  # rho_i
    residual: float | np.ndarray  # |M [tau/rho; Q]| / Q, force residual (moments divided by the length scale)


def equilibrium_tensions(A, B, G, load: float, direction, length_scale: float = 1.0) -> Equilibrium:
    """Cable tensions from force and moment balance about G (6 equations, m unknowns, least squares).

    Seed 004 eq. (4) uses the three force equations only; at a true equilibrium both agree, and the
    least-squares form also reports the residual, so a pose that is not an equilibrium shows it.
    """
    B = np.asarray(B)
    G = np.asarray(G)
    rho = cable_lengths(A, B)
    M = wrench_matrix(A, B, G, direction, pole=G)
    M = M.astype(complex if np.iscomplexobj(M) else float)
    M[..., 3:, :] /= length_scale
    W, w = M[..., :-1], -load * M[..., -1]
    lam = np.einsum("...ij,...j->...i", np.linalg.pinv(W), w)
    res = np.einsum("...ij,...j->...i", W, lam) - w
    tensions = lam * rho
    if np.iscomplexobj(tensions) and np.abs(tensions.imag).max(initial=0.0) == 0.0:
        tensions = np.real(tensions)
    residual = np.linalg.norm(res, axis=-1) / load
    return Equilibrium(tensions, rho, float(residual) if residual.ndim == 0 else residual)
