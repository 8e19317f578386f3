"""Statics of a platform held by m taut cables under a constant load.

Seed 004 eq. (2), (24): the wrench matrix M(P) = [L_1 .. L_m L_e] with L_i = -[s_i; (B_i - P) x s_i],
s_i = B_i - A_i, and L_e = [d; (G - P) x d] for the unit load direction d (seed 004 takes d = k); the platform
is in equilibrium when M [tau_1/rho_1 .. tau_m/rho_m, Q]^T = 0.  Works for real and complex poses.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np


def wrench_matrix(A, B, G, direction, pole=None) -> np.ndarray:
    """The 6 x (m+1) matrix M(P) of seed 004 eq. (24) (rows: force, then moment about ``pole``; default P = O)."""
    A = np.atleast_2d(A)
    B = np.atleast_2d(B)
    P = np.zeros(3) if pole is None else np.asarray(pole)
    s = B - A
    d = np.asarray(direction)
    cols = [np.concatenate([-si, -np.cross(bi - P, si)]) for si, bi in zip(s, B)]
    cols.append(np.concatenate([d, np.cross(np.asarray(G) - P, d)]))
    return np.array(cols).T


def cable_lengths(A, B) -> np.ndarray:
    """rho_i = |B_i - A_i|; for complex points sqrt(s^H s) (seed 004 Table 4 convention)."""
    s = np.atleast_2d(B) - np.atleast_2d(A)
    return np.sqrt(np.real(np.sum(np.conj(s) * s, axis=1)))


@dataclass(frozen=True)
class Equilibrium:
    """Tensions solving M [tau/rho; Q] = 0 in the least-squares sense, and how well they solve it."""

    tensions: np.ndarray  # tau_i (complex if the pose is)
    lengths: np.ndarray  # rho_i
    residual: float  # |M [tau/rho; Q]| / Q, relative force residual (moments divided by the length scale)


def equilibrium_tensions(A, B, G, load: float, direction, length_scale: float = 1.0) -> Equilibrium:
    """Cable tensions from force and moment balance about G (6 equations, m unknowns, least squares).

    Seed 004 eq. (4) uses the three force equations only; at a true equilibrium both agree, and the
    least-squares form also reports the residual, so a pose that is not an equilibrium shows it.
    """
    A = np.atleast_2d(A)
    B = np.atleast_2d(B)
    G = np.asarray(G)
    rho = cable_lengths(A, B)
    M = wrench_matrix(A, B, G, direction, pole=G)
    M = M.astype(complex if np.iscomplexobj(M) else float)
    M[3:, :] /= length_scale
    lam, *_ = np.linalg.lstsq(M[:, :-1], -load * M[:, -1], rcond=None)
    res = M[:, :-1] @ lam + load * M[:, -1]
    tensions = lam * rho
    if not np.iscomplexobj(tensions) or np.abs(tensions.imag).max(initial=0.0) == 0.0:
        tensions = np.real(tensions)
    return Equilibrium(tensions, rho, float(np.linalg.norm(res) / load))
