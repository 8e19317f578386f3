"""Polynomial systems with known root counts (tests, benchmarks).

* :func:`katsura` -- Katsura-n: n + 1 unknowns, 2^n isolated solutions (= total degree);
* :func:`cyclic` -- cyclic-n roots (cyclic-5: 70 isolated solutions, total degree 120);
* :func:`stewart_gough` -- forward kinematics of a general 6-6 Gough-Stewart platform in Study
  (soma) coordinates (e, g) in P^7: leg i is |g + e b_i - a_i e|^2 = L_i^2 |e|^2 (quaternion
  products; from B_i = p + R b_i with R b = e b e~/|e|^2, p = g e~/|e|^2), the Study quadric
  g . e = 0 and a random affine patch. Total degree 2^7 = 128; 40 nonsingular solutions (the
  published generic count), the other 88 paths end on the exceptional quadric e . e = 0
  (singular) or at infinity.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from .systems import PolynomialSystem

__all__ = ["katsura", "cyclic", "stewart_gough"]


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
