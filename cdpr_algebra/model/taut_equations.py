"""Equations of the direct geometrico-static problem (DGP) with m taut cables, m = 2 .. 6.

One formulation for every m and every geometry (coplanar platforms included), all equations quadratic.
Unknowns: the platform pose as the position p of the platform-frame origin and the columns u, v, w of R
(R = [u v w], B_i = p + b'_ix u + b'_iy v + b'_iz w, G = p + R g'), and lam_i = tau_i / rho_i:
    u.u = 1, v.v = 1, u.v = 0, w = u x v                          (R is a rotation: 6 equations)
    |B_i - A_i|^2 = rho_i^2                          i = 1..m       (seed 000 eq. 4)
    sum_i lam_i (A_i - B_i) + Q d = 0                               (force balance, seed 000 eq. 5)
    sum_i lam_i B_i x A_i + G x Q d = 0                             (moments about the world origin)
12 + m equations in 12 + m unknowns; the moment pole is the fixed origin so every equation stays quadratic
(the lesson of ../shared/PEERS.md).  Parameters: A_i (3m), rho_i^2 (m), b'_i (3m), g' (3), Q d (3).
"""

from __future__ import annotations

import numpy as np

from cdpr_algebra.homotopy.systems import PolynomialSystem

_FAMILIES: dict[int, PolynomialSystem] = {}


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def taut_unknowns(m: int) -> list:
    """The names of the unknowns of :func:`taut_family` for m taut cables, in order: px py pz (the platform frame's
    origin), ux .. wz (the columns of R), lam1 .. lamm (tau_i / rho_i)."""
    pose = ["px", "py", "pz", "ux", "uy", "uz", "vx", "vy", "vz", "wx", "wy", "wz"]
    return pose + [f"lam{i}" for i in range(1, m + 1)]


def taut_family(m: int) -> PolynomialSystem:
    """The parameterized system for m taut cables (cached)."""
    if m in _FAMILIES:
        return _FAMILIES[m]
    if not 2 <= m <= 6:
        raise ValueError("the homotopy formulation covers m = 2 .. 6 taut cables (m = 1 is analytic)")
    import sympy as sp

    xs = sp.symbols(taut_unknowns(m))
    p, u, v, w, lam = xs[0:3], xs[3:6], xs[6:9], xs[9:12], xs[12:]
    A = [sp.symbols(f"A{i}x A{i}y A{i}z") for i in range(1, m + 1)]
    r2 = sp.symbols(f"rho2_1:{m + 1}")
    b = [sp.symbols(f"b{i}x b{i}y b{i}z") for i in range(1, m + 1)]
    g = sp.symbols("gx gy gz")
    f = sp.symbols("fx fy fz")

    def body(c):
        return [p[k] + c[0] * u[k] + c[1] * v[k] + c[2] * w[k] for k in range(3)]

    uv = _cross(u, v)
    eqs = [sum(x * x for x in u) - 1, sum(x * x for x in v) - 1, sum(x * y for x, y in zip(u, v))]
    eqs += [w[k] - uv[k] for k in range(3)]
    B = [body(bi) for bi in b]
    eqs += [sum((B[i][k] - A[i][k]) ** 2 for k in range(3)) - r2[i] for i in range(m)]
    eqs += [sum(lam[i] * (A[i][k] - B[i][k]) for i in range(m)) + f[k] for k in range(3)]
    G = body(g)
    mom = _cross(G, f)
    for i in range(m):
        c = _cross(B[i], A[i])
        mom = [mom[k] + lam[i] * c[k] for k in range(3)]
    eqs += mom
    xs = list(xs)
    ps = [c for a in A for c in a] + list(r2) + [c for bi in b for c in bi] + list(g) + list(f)
    fam = PolynomialSystem([sp.expand(e) for e in eqs], xs, ps, name=f"dgp_{m}_taut")
    _FAMILIES[m] = fam
    return fam


def taut_parameters(robot, cables, lengths=None) -> np.ndarray:
    """Parameters of :func:`taut_family` for the given 0-based taut ``cables`` of ``robot``."""
    idx = list(cables)
    rho = np.asarray(robot.lengths if lengths is None else lengths, dtype=float)[idx]
    return np.concatenate([robot.base[idx].ravel(), rho ** 2, robot.platform[idx].ravel(), robot.com,
                           robot.load * robot.load_direction])


def decode(X, m: int):
    """Rows of solutions -> (p (k, 3), R (k, 3, 3) with columns u, v, w, lam (k, m))."""
    X = np.atleast_2d(X)
    p = X[:, 0:3]
    R = np.stack([X[:, 3:6], X[:, 6:9], X[:, 9:12]], axis=-1)
    return p, R, X[:, 12:12 + m]


def encode(p, R, lam) -> np.ndarray:
    """(p, R, lam) -> the unknown vector of :func:`taut_family`."""
    R = np.asarray(R)
    return np.concatenate([np.asarray(p), R[:, 0], R[:, 1], R[:, 2], np.asarray(lam)])


def to_cable_frame(X, frame) -> np.ndarray:
    """Rows (p, u, v, w, lam) with the world origin moved to c and the platform frame to cb (``frame`` = (c, cb),
    :attr:`cdpr_algebra.model.robot.Robot.cable_frame`): p' = p + R cb - c, R = [u v w]; the rest unchanged."""
    c, cb = frame
    out = np.array(X, copy=True)
    out[:, :3] = X[:, :3] + X[:, 3:6] * cb[0] + X[:, 6:9] * cb[1] + X[:, 9:12] * cb[2] - c
    return out


def from_cable_frame(X, frame) -> np.ndarray:
    """The inverse of :func:`to_cable_frame`: p = c + p' - R cb."""
    c, cb = frame
    out = np.array(X, copy=True)
    out[:, :3] = c + X[:, :3] - (cb[0] * X[:, 3:6] + cb[1] * X[:, 6:9] + cb[2] * X[:, 9:12])
    return out
