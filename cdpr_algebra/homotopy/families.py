"""Polynomial systems with known root counts (tests, benchmarks) and the 3-cable DGP family.

* :func:`katsura` -- Katsura-n: n + 1 unknowns, 2^n isolated solutions (= total degree);
* :func:`cyclic` -- cyclic-n roots (cyclic-5: 70 isolated solutions, total degree 120);
* :func:`stewart_gough` -- forward kinematics of a general 6-6 Gough-Stewart platform in Study
  (soma) coordinates (e, g) in P^7: leg i is |g + e b_i - a_i e|^2 = L_i^2 |e|^2 (quaternion
  products; from B_i = p + R b_i with R b = e b e~/|e|^2, p = g e~/|e|^2), the Study quadric
  g . e = 0 and a random affine patch. Total degree 2^7 = 128; 40 nonsingular solutions (the
  published generic count), the other 88 paths end on the exceptional quadric e . e = 0
  (singular) or at infinity;
* :func:`dgp3_family` -- the direct geometrico-static problem of a 3-cable robot (seed 000 Sec. 3.4
  formulation, all equations quadratic): unknowns B_1, B_2, B_3 (world coordinates of the anchors)
  and lam_i = tau_i / rho_i; equations |B_i - A_i|^2 = rho_i^2, |B_i - B_j|^2 = |b_i' - b_j'|^2,
  sum_i lam_i (A_i - B_i) + Q d = 0 and the moment about the world origin
  sum_i lam_i B_i x A_i + G x (Q d) = 0 with G = B_1 + a2 (B_2 - B_1) + a3 (B_3 - B_1)
  + a4 (B_2 - B_1) x (B_3 - B_1) (quadratic in B). Parameters (21): A (9), rho^2 (3), the three
  squared distances (3), the load vector f = Q d (3), (a2, a3, a4). Generic count 156.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from .systems import PolynomialSystem

__all__ = ["katsura", "cyclic", "stewart_gough", "dgp3_family", "dgp3_parameters", "dgp3_poses"]


def katsura(n: int) -> PolynomialSystem:
    x = sp.symbols(f"x0:{n + 1}")

    def X(i):
        return x[abs(i)] if abs(i) <= n else 0

    eqs = [sum(X(k) for k in range(-n, n + 1)) - 1]
    for m in range(n):
        eqs.append(sum(X(k) * X(m - k) for k in range(-n, n + 1)) - X(m))
    return PolynomialSystem(eqs, x, name=f"katsura{n}")


def cyclic(n: int) -> PolynomialSystem:
    x = sp.symbols(f"x0:{n}")
    eqs = [sum(sp.Mul(*[x[(i + k) % n] for k in range(j)]) for i in range(n)) for j in range(1, n)]
    eqs.append(sp.Mul(*x) - 1)
    return PolynomialSystem(eqs, x, name=f"cyclic{n}")


def _qmul(p, q):
    p0, p1, p2, p3 = p
    q0, q1, q2, q3 = q
    return (p0 * q0 - p1 * q1 - p2 * q2 - p3 * q3, p0 * q1 + p1 * q0 + p2 * q3 - p3 * q2,
            p0 * q2 - p1 * q3 + p2 * q0 + p3 * q1, p0 * q3 + p1 * q2 - p2 * q1 + p3 * q0)


def _num(c):
    c = complex(c)
    return sp.Float(c.real, 17) + (sp.I * sp.Float(c.imag, 17) if c.imag else 0)


def stewart_gough(seed: int = 0) -> PolynomialSystem:
    """A random general 6-6 platform (real data, leg lengths from a random real pose)."""
    rng = np.random.default_rng(seed)
    A = rng.normal(size=(6, 3))
    Bp = rng.normal(size=(6, 3))
    # a real pose: rotation from a random unit quaternion, translation
    q = rng.normal(size=4)
    q /= np.linalg.norm(q)
    w, x, y, z = q
    R = np.array([[1 - 2 * (y * y + z * z), 2 * (x * y - z * w), 2 * (x * z + y * w)],
                  [2 * (x * y + z * w), 1 - 2 * (x * x + z * z), 2 * (y * z - x * w)],
                  [2 * (x * z - y * w), 2 * (y * z + x * w), 1 - 2 * (x * x + y * y)]])
    p = rng.normal(size=3)
    L2 = np.sum((p + Bp @ R.T - A) ** 2, axis=1)
    e = sp.symbols("e0:4")
    g = sp.symbols("g0:4")
    eqs = []
    for i in range(6):
        a = (0,) + tuple(_num(c) for c in A[i])
        b = (0,) + tuple(_num(c) for c in Bp[i])
        v = [gi + u - w_ for gi, u, w_ in zip(g, _qmul(e, b), _qmul(a, e))]
        eqs.append(sp.expand(sum(c * c for c in v) - _num(L2[i]) * sum(c * c for c in e)))
    eqs.append(sum(a * b for a, b in zip(e, g)))
    c = rng.normal(size=8) + 1j * rng.normal(size=8)
    eqs.append(sum(_num(ci) * v for ci, v in zip(c, e + g)) - 1)
    return PolynomialSystem(eqs, list(e) + list(g), name=f"stewart_gough_{seed}")


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
