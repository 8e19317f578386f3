"""The direct geometrico-static problem of a 3-cable robot in anchor-point coordinates (Berti, Merlet and
Carricato 2016, Sec. 3.4 formulation, all equations quadratic): a second formulation, independent of
:mod:`cdpr_algebra.model.taut_equations`, used to cross-check the DGP (tests, benchmarks,
``derivations/solve_generic_dgp3.py``).

Unknowns B_1, B_2, B_3 (world coordinates of the anchors)
and lam_i = tau_i / rho_i; equations |B_i - A_i|^2 = rho_i^2, |B_i - B_j|^2 = |b_i' - b_j'|^2,
sum_i lam_i (A_i - B_i) + Q d = 0 and the moment about the world origin
sum_i lam_i B_i x A_i + G x (Q d) = 0 with G = B_1 + a2 (B_2 - B_1) + a3 (B_3 - B_1)
+ a4 (B_2 - B_1) x (B_3 - B_1) (quadratic in B). Parameters (21): A (9), rho^2 (3), the three
squared distances (3), the load vector f = Q d (3), (a2, a3, a4). Generic count 156.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from cdpr_algebra.homotopy.systems import PolynomialSystem

__all__ = ["dgp3_family", "dgp3_parameters", "dgp3_poses"]


def _cross(u, v):
    return [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]


def dgp3_family() -> PolynomialSystem:
    """The 3-cable DGP family (see module doc): 12 unknowns, 21 parameters, 12 quadrics."""
    B = [sp.symbols(f"B{i}x B{i}y B{i}z") for i in (1, 2, 3)]
    lam = sp.symbols("lam1:4")
    A = [sp.symbols(f"A{i}x A{i}y A{i}z") for i in (1, 2, 3)]
    r = sp.symbols("r1:4")
    D = sp.symbols("D12 D13 D23")
    f = sp.symbols("fx fy fz")
    al = sp.symbols("a2 a3 a4")
    eqs = []
    for i in range(3):
        eqs.append(sum((B[i][k] - A[i][k]) ** 2 for k in range(3)) - r[i])
    for (i, j), Dij in zip(((0, 1), (0, 2), (1, 2)), D):
        eqs.append(sum((B[i][k] - B[j][k]) ** 2 for k in range(3)) - Dij)
    for k in range(3):
        eqs.append(sum(lam[i] * (A[i][k] - B[i][k]) for i in range(3)) + f[k])
    u = [B[1][k] - B[0][k] for k in range(3)]
    v = [B[2][k] - B[0][k] for k in range(3)]
    nrm = _cross(u, v)
    G = [B[0][k] + al[0] * u[k] + al[1] * v[k] + al[2] * nrm[k] for k in range(3)]
    mom = [0, 0, 0]
    for i in range(3):
        c = _cross(B[i], A[i])
        mom = [mom[k] + lam[i] * c[k] for k in range(3)]
    gf = _cross(G, f)
    eqs += [mom[k] + gf[k] for k in range(3)]
    xs = [c for b in B for c in b] + list(lam)
    ps = [c for a in A for c in a] + list(r) + list(D) + list(f) + list(al)
    return PolynomialSystem(eqs, xs, ps, name="dgp3_points_tensions")


def dgp3_parameters(robot) -> np.ndarray:
    """The 21 parameters of :func:`dgp3_family` for a 3-cable :class:`~cdpr_algebra.model.robot.Robot` with lengths."""
    if robot.n != 3 or robot.lengths is None:
        raise ValueError("need a 3-cable robot with cable lengths")
    A = np.asarray(robot.base, dtype=float)
    bp = np.asarray(robot.platform, dtype=float)
    r = np.asarray(robot.lengths, dtype=float) ** 2
    D = [np.sum((bp[i] - bp[j]) ** 2) for i, j in ((0, 1), (0, 2), (1, 2))]
    f = robot.load * np.asarray(robot.load_direction, dtype=float)
    u, v = bp[1] - bp[0], bp[2] - bp[0]
    M = np.column_stack([u, v, np.cross(u, v)])
    al = np.linalg.solve(M, np.asarray(robot.com, dtype=float) - bp[0])
    return np.concatenate([A.ravel(), r, D, f, al])


def dgp3_poses(robot, X) -> list:
    """For solutions X (rows: B_1, B_2, B_3, lam) of a real instance: dicts with the platform-frame
    origin, rotation matrix and tensions tau_i = lam_i rho_i (proper rotation fitted to the anchors)."""
    bp = np.asarray(robot.platform, dtype=float)
    out = []
    for x in np.atleast_2d(X):
        Bw = np.real(x[:9]).reshape(3, 3)
        lam = np.real(x[9:12])
        # frames from the anchor triangles (both right-handed): R = Fw Fp^T
        def frame(P):
            e1 = P[1] - P[0]
            e1 = e1 / np.linalg.norm(e1)
            n = np.cross(P[1] - P[0], P[2] - P[0])
            n = n / np.linalg.norm(n)
            return np.column_stack([e1, np.cross(n, e1), n])
        R = frame(Bw) @ frame(bp).T
        origin = Bw[0] - R @ bp[0]
        out.append({"position": origin, "R": R, "tensions": lam * np.asarray(robot.lengths), "lam": lam})
    return out
