"""Equations of a taut set whose platform anchors and centre of mass lie on one line (a "rod"), m = 2 .. 5.

When the taut anchors B_i and the centre of mass G are collinear on the platform, every equilibrium of the taut
set turns freely about that line (:mod:`cdpr_algebra.dgp.positive_dimensional`): the 6-DOF system of
:func:`.taut_equations.taut_family` has circles of solutions.  The line itself has isolated equilibria; its pose is
G and the world image u = R D of a platform vector D along the line (D = B_far - G, B_far the taut anchor farthest
from G), and B_i = G + s_i u with s_i = (b'_i - g').D / D.D, rational in the robot's data when the points are
exactly collinear (lam_i = tau_i / rho_i as in the 6-DOF system):
    u.u = D.D                                                     (1 equation)
    |G + s_i u - A_i|^2 = rho_i^2                  i = 1..m       (m)
    sum_i lam_i (A_i - G - s_i u) + Q d = 0                       (force balance, 3)
    sum_i lam_i s_i (A_i - G) - mu u = 0                          (moment about G parallel to u, 3)
m + 7 quadratic equations in the m + 7 unknowns (G, u, lam_1..lam_m, mu).  The moment about G of the cable
forces is sum_i s_i u x lam_i (A_i - G - s_i u) = u x V with V = sum_i lam_i s_i (A_i - G); it vanishes iff V is
parallel to u (u.u = D.D makes u nonzero), which the last three rows say with mu = u.V.  One root is one family of
6-DOF equilibria: the platform poses that put its line on (G, u), any turn about it.  m >= 6 taut anchors on a
line are over-determined by the lengths alone (5 degrees of freedom), so the formulation stops at 5.
Parameters: A_i (3m), rho_i^2 (m), s_i (m), D.D (1), Q d (3).
"""

from __future__ import annotations

import numpy as np

from cdpr_algebra.homotopy.systems import PolynomialSystem

__all__ = ["ROD_M", "rod_family", "rod_parameters", "line_coordinates", "exact_rational", "BINARY", "DECIMAL"]

ROD_M = (2, 3, 4, 5)
BINARY = "binary"  # the robot's doubles read exactly
DECIMAL = "decimal"  # each double read as the shortest decimal that prints it (repr): the numbers of a robot file
_FAMILIES: dict[int, PolynomialSystem] = {}


def rod_family(m: int) -> PolynomialSystem:
    """The parameterized rod system for m taut cables (cached; built with sympy on first use)."""
    if m in _FAMILIES:
        return _FAMILIES[m]
    if m not in ROD_M:
        raise ValueError(f"the rod formulation covers m = 2 .. 5 taut cables on a line, not m = {m}")
    import sympy as sp

    G = sp.symbols("Gx Gy Gz")
    u = sp.symbols("ux uy uz")
    lam = sp.symbols(f"lam1:{m + 1}")
    mu = sp.Symbol("mu")
    A = [sp.symbols(f"A{i}x A{i}y A{i}z") for i in range(1, m + 1)]
    r2 = sp.symbols(f"rho2_1:{m + 1}")
    s = sp.symbols(f"s1:{m + 1}")
    c2 = sp.Symbol("DD")
    f = sp.symbols("fx fy fz")
    eqs = [sum(x * x for x in u) - c2]
    eqs += [sum((G[k] + s[i] * u[k] - A[i][k]) ** 2 for k in range(3)) - r2[i] for i in range(m)]
    eqs += [sum(lam[i] * (A[i][k] - G[k] - s[i] * u[k]) for i in range(m)) + f[k] for k in range(3)]
    eqs += [sum(lam[i] * s[i] * (A[i][k] - G[k]) for i in range(m)) - mu * u[k] for k in range(3)]
    xs = list(G) + list(u) + list(lam) + [mu]
    ps = [c for a in A for c in a] + list(r2) + list(s) + [c2] + list(f)
    fam = PolynomialSystem([sp.expand(e) for e in eqs], xs, ps, name=f"rod_{m}_taut")
    _FAMILIES[m] = fam
    return fam


def exact_rational(value, reading: str = BINARY):
    """The double ``value`` as an exact :class:`fractions.Fraction`: its binary value (``BINARY``), or the shortest
    decimal that prints it (``DECIMAL``, Python's repr: 0.1 for the double nearest 1/10)."""
    from fractions import Fraction

    if reading not in (BINARY, DECIMAL):
        raise ValueError(f"reading must be {BINARY!r} or {DECIMAL!r}, not {reading!r}")
    return Fraction(float(value)) if reading == BINARY else Fraction(repr(float(value)))


def line_coordinates(platform_points, com, reading: str = BINARY):
    """(D, s, D.D) of :func:`rod_family` for the platform points (k x 3) and centre of mass ``com`` (doubles, exactly
    collinear in the given ``reading``, :func:`exact_rational`): D = b_far - g with b_far the point farthest from g,
    s_i = (b_i - g).D / D.D, all as exact :class:`fractions.Fraction` (D a tuple); None when every point is at g."""
    g = [exact_rational(v, reading) for v in com]
    b = [[exact_rational(v, reading) - g[k] for k, v in enumerate(p)] for p in platform_points]
    norms = [sum(c * c for c in v) for v in b]
    far = max(range(len(b)), key=lambda k: norms[k])
    if norms[far] == 0:
        return None
    D = tuple(b[far])
    return D, [sum(c * d for c, d in zip(v, D)) / norms[far] for v in b], norms[far]


def rod_parameters(base, rho, s, DD, load_vector) -> np.ndarray:
    """Parameters of :func:`rod_family` (floats): exit points ``base`` (m x 3), lengths ``rho`` (m), ``s`` (m),
    ``DD`` = D.D and the load Q d."""
    return np.concatenate([np.asarray(base, dtype=float).ravel(), np.asarray(rho, dtype=float) ** 2,
                           np.asarray([float(v) for v in s]), [float(DD)], np.asarray(load_vector, dtype=float)])
