"""Generate the evaluators of the distance-to-a-cubic systems of the robustness radii (Merlet) from one sympy source.

A robustness radius is the distance from a pose to a cubic surface P(y) = sum_m c_m y^m = 0 (y = (x - x0) / scale,
monomials y1^i y2^j y3^k of degree <= 3 in ``MONOMIALS`` order).  Its critical points solve the Lagrange system

    y - lam grad P(y) = 0,   P(y) = 0                                     (affine, unknowns y1..y3, lam)

and, homogenized (y = Y / y0, lam = lam' / mu with P^h(y0, Y) = y0^3 P(Y / y0)) in a random chart,

    mu y0 y_k - lam dP^h/dy_k = 0 (k = 1..3),  P^h = 0,  a . (y0..y3) = 1,  b . (mu, lam) = 1

(the projective Euclidean-distance system the batched parameter homotopies track; degree 21 for a generic cubic).
The nearest-ness proof excludes the critical set C = {P = 0, y x grad P = 0}; its four polynomials and their
first derivatives have coefficients (over ``MONOMIALS``) that are integer linear maps of c.

This script writes, from those expressions only (sympy, common subexpressions shared):

    cdpr_algebra/generated/cubic_distance.py
        MONOMIALS                         the exponents (i, j, k), the coefficient order
        ed_directional_into(y0..y3, mu, lam, c0..c19, a0..a3, b0, b1, d0..d19, out)
                                  out[0..47] <- the 6 equations, dF/dz row by row (36), dF/dc . d (6)
        lagrange_system(y1, y2, y3, lam, c0..c19)           -> 4 equations, then dF/d(y, lam) row by row (16)
        CRITICAL_SET_ROWS                 (16, 20, 20) integers: row p, monomial m, coefficient j

The functions use only + - * on their arguments, so they evaluate numpy arrays (one entry per path or point,
``cdpr_algebra.cc.cubic_distances``), floats, and python-flint arb balls (``cdpr_algebra.cc.radius_proofs``).
Takes a few seconds:

    python derivations/derive_cubic_distance.py
"""

from __future__ import annotations

import sys
from pathlib import Path

import sympy as sp

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "derivations"))

from codegen import HEADER, function_into_source, function_source, write  # noqa: E402

TARGET = "cdpr_algebra/generated/cubic_distance.py"
MONOMIALS = tuple((i, j, k) for i in range(4) for j in range(4) for k in range(4) if i + j + k <= 3)


def _symbols():
    y0, y1, y2, y3, mu, lam = sp.symbols("y0 y1 y2 y3 mu lam")
    c = sp.symbols("c0:20")
    d = sp.symbols("d0:20")
    a = sp.symbols("a0:4")
    b = sp.symbols("b0:2")
    return (y0, y1, y2, y3), mu, lam, c, d, a, b


def cubic(c, y):
    """P(y) = sum_m c_m y^m (affine)."""
    return sum(cm * y[0] ** i * y[1] ** j * y[2] ** k for cm, (i, j, k) in zip(c, MONOMIALS))


def cubic_h(c, Y):
    """P^h(y0, y1, y2, y3) = y0^3 P(y / y0)."""
    return sum(cm * Y[0] ** (3 - i - j - k) * Y[1] ** i * Y[2] ** j * Y[3] ** k for cm, (i, j, k) in zip(c, MONOMIALS))


def ed_equations(Y, mu, lam, c, a, b):
    """The projective Lagrange (Euclidean-distance) system, 6 equations in z = (y0, y1, y2, y3, mu, lam)."""
    Ph = cubic_h(c, Y)
    eqs = [mu * Y[0] * Y[k] - lam * sp.diff(Ph, Y[k]) for k in (1, 2, 3)]
    eqs.append(Ph)
    eqs.append(sum(ai * yi for ai, yi in zip(a, Y)) - 1)
    eqs.append(b[0] * mu + b[1] * lam - 1)
    return [sp.expand(e) for e in eqs]


def lagrange_equations(y, lam, c):
    """The affine Lagrange system y - lam grad P(y), P(y)."""
    P = cubic(c, y)
    return [sp.expand(y[k] - lam * sp.diff(P, y[k])) for k in range(3)] + [sp.expand(P)]


def critical_set_rows(y, c):
    """The integer maps c -> coefficients of P, y_a dP/dy_b - y_b dP/dy_a ((a, b) = (1, 2), (1, 3), (2, 3)), then
    d/dy_v of each of these four (v = 1, 2, 3, v-major), over MONOMIALS: a (16, 20, 20) nested tuple."""
    P = cubic(c, y)
    grad = [sp.diff(P, v) for v in y]
    funcs = [P] + [y[a_] * grad[b_] - y[b_] * grad[a_] for a_, b_ in ((0, 1), (0, 2), (1, 2))]
    polys = funcs + [sp.diff(f, y[v]) for v in range(3) for f in funcs]
    rows = []
    for f in polys:
        poly = sp.Poly(sp.expand(f), *y)
        if poly.total_degree() > 3:
            raise ValueError("a polynomial of the critical set has degree > 3")
        coef = dict(zip(poly.monoms(), poly.coeffs()))
        row = []
        for m in MONOMIALS:
            e = sp.expand(coef.get(m, 0))
            row.append(tuple(int(e.coeff(cj)) for cj in c))
            if sp.expand(e - sum(int(e.coeff(cj)) * cj for cj in c)) != 0:
                raise ValueError("a coefficient of the critical set is not linear in c")
        rows.append(tuple(row))
    return tuple(rows)


def _jacobian_rows(eqs, unknowns):
    return [sp.diff(e, u) for e in eqs for u in unknowns]


def generate() -> dict:
    Y, mu, lam, c, d, a, b = _symbols()
    z = list(Y) + [mu, lam]
    ed = ed_equations(Y, mu, lam, c, a, b)
    direction = [sp.expand(sum(sp.diff(e, cj) * dj for cj, dj in zip(c, d))) for e in ed]
    into_src = function_into_source(
        "ed_directional_into", z + list(c) + list(a) + list(b) + list(d), ed + _jacobian_rows(ed, z) + direction,
        "Projective Euclidean-distance system of the cubic c (module doc) into out[0..47]: 6 equations, the 36 "
        "entries of dF/dz row by row, then dF/dc . d (6; F is linear in c).")
    y = list(Y[1:])
    lg = lagrange_equations(y, lam, c)
    lg_src = function_source(
        "lagrange_system", y + [lam] + list(c), lg + _jacobian_rows(lg, y + [lam]),
        "Affine Lagrange system y - lam grad P(y), P(y) of the cubic c: 4 equations, then the 16 entries of "
        "dF/d(y, lam) row by row.")
    rows = critical_set_rows(y, c)
    text = (HEADER.format(script="derive_cubic_distance.py")
            + '"""Distance-to-a-cubic systems of the robustness radii (see derivations/derive_cubic_distance.py)."""\n\n'
            + f"MONOMIALS = {MONOMIALS!r}\n\n\n" + into_src + "\n\n" + lg_src + "\n\n"
            + "# (16, 20, 20): polynomial p of the critical set, monomial m, cubic coefficient j\n"
            + f"CRITICAL_SET_ROWS = {rows!r}\n")
    return {TARGET: text}


if __name__ == "__main__":
    write(generate(), ROOT)
