"""Tracking in projective space: the homogenized system on a random affine chart.

F(x) = 0 with x = y / y0 becomes F_h(y0, y) = y0^d_i F_i(y / y0) = 0 plus the chart c0 y0 + c . y = 1 (c random
complex).  Solutions of large norm, far away in affine coordinates, are ordinary points of the chart, so paths
going there are tracked as easily as the others; a path at infinity ends with y0 -> 0.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from .systems import PolynomialSystem

_CACHE: dict[tuple, tuple] = {}


def projectivize(system: PolynomialSystem, seed: int = 20131) -> tuple[PolynomialSystem, np.ndarray]:
    """(homogenized system with unknowns (y0, y), chart coefficients c (n + 1,)); cached per system and seed."""
    key = (system.hash, seed)
    if key in _CACHE:
        return _CACHE[key]
    rng = np.random.default_rng(seed)
    c = rng.normal(size=system.n + 1) + 1j * rng.normal(size=system.n + 1)
    c /= np.linalg.norm(c)
    y0 = sp.Symbol("_y0")
    ys = [sp.Symbol(f"_y_{v}") for v in system.variables]
    eqs = []
    for e, d in zip(system.equations, system.degrees):
        poly = sp.Poly(e, *system.variables)
        eqs.append(sum(coef * y0 ** (d - sum(mon)) * sp.Mul(*[y ** k for y, k in zip(ys, mon)])
                       for mon, coef in poly.terms()))
    cs = [sp.Float(v.real, 17) + sp.I * sp.Float(v.imag, 17) for v in c]
    eqs.append(cs[0] * y0 + sum(ci * y for ci, y in zip(cs[1:], ys)) - 1)
    hom = PolynomialSystem(eqs, [y0] + ys, system.parameters, name=f"{system.name}_projective")
    _CACHE[key] = (hom, c)
    return hom, c


def to_chart(X, c) -> np.ndarray:
    """Affine points (k, n) -> chart points (k, n + 1)."""
    X = np.atleast_2d(np.asarray(X, dtype=complex))
    Y = np.hstack([np.ones((len(X), 1), dtype=complex), X])
    return Y / (Y @ c)[:, None]


def from_chart(Y) -> tuple[np.ndarray, np.ndarray]:
    """Chart points -> (affine points, |y0| / |y| (0 at infinity))."""
    Y = np.atleast_2d(Y)
    y0 = Y[:, 0]
    with np.errstate(all="ignore"):
        X = Y[:, 1:] / y0[:, None]
    return X, np.abs(y0) / np.maximum(np.linalg.norm(Y, axis=1), 1e-300)
