"""Derive the IGP with assigned orientation of 3-cable robots (seed 004 Sec. 3) and generate
``cdpr_algebra/generated/igp_orientation.py``.

Model (seed 004 Sec. 2-3): O = A_1 (a_1 = 0), load along +k, r_i = R b_i known, G at x = (x, y, z):
    M'(O) = [[x + r_1, r_21 - a_2, r_31 - a_3, k], [0, a_2 x (x + r_2), a_3 x (x + r_3), x x k]]   (eq. 6)
Generated, as plain arithmetic:
* ``minors_M_prime``: the 15 4x4 minors of M'(O) (rows in lexicographic order 1234, 1235, ..., 3456);
* ``p1_coefficients``, ``p2_coefficients``, ``p3_coefficients``: eq. (9a-c), p1 = det M'_1236,
  p2 = det M'_1235, p3 = det M'_1234 (note: the printed forms (9b) and (9c) have their labels swapped:
  det M'_1235 is the one with the monomial x^2, det M'_1234 the one with y^2);
* ``p23_from_p2_p3``: the resultant of p2 and p3 in z (both linear in z), a cubic in (x, y);
* ``p123_from_p1_p23``: the resultant of p1 and p23 in y divided by A02 (the y^2 coefficient of p1,
  which factors the first column of the Sylvester matrix), i.e. p123 of eq. (10) as E_0 .. E_6 (E_5 = E_6 = 0
  for this structure, checked below);
* ``delta``: eq. (7); ``g_coefficients`` (eq. 17, p4 = det M'_{123,124}), ``p6_coefficients`` (det M'_2346),
  ``p7_coefficients`` (det M'_2356) and ``p467_from_g_p67``: the Delta = 0 route of Sec. 3.2 (eq. 16-19),
  p467 = g2^5 p67(x, -(g1 x + g0) / g2) with p67 the resultant of p6 and p7 in z.
The roots of p123 (and of p467) are the trivial solutions x_i = a_i - r_i (eq. 8) and x4; the solver takes x4 from
the sum of the roots, x4 = -E_3 / E_4 - (x_1 + x_2 + x_3), which equals Vieta's product form of eq. (12)
(checked below) without dividing by the trivial roots.
"""

from __future__ import annotations

import itertools
import random
import sys
from pathlib import Path

import sympy as sp

sys.path.insert(0, str(Path(__file__).resolve().parent))
from codegen import HEADER, function_source, function_with_magnitude, write  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent
TARGET = "cdpr_algebra/generated/igp_orientation.py"

x, y, z = sp.symbols("x y z")
PARAMS = sp.symbols("a2x a2y a2z a3x a3y a3z r1x r1y r1z r2x r2y r2z r3x r3y r3z")
MINOR_ROWS = list(itertools.combinations(range(1, 7), 4))
P1_MONOMIALS = [(2, 0), (1, 1), (0, 2), (1, 0), (0, 1), (0, 0)]  # powers of (x, y)
P23_MONOMIALS = [(i, j) for d in range(3, -1, -1) for i in range(d, -1, -1) for j in [d - i]]
XYZ_MONOMIALS = [(i, j, k) for d in range(2, -1, -1) for i in range(d, -1, -1) for j in range(d - i, -1, -1) for k in [d - i - j]]
XYZ_LINEAR_Z = [m for m in XYZ_MONOMIALS]  # full quadratic support in (x, y, z)
P67_MONOMIALS = [(i, j) for d in range(5, -1, -1) for i in range(d, -1, -1) for j in [d - i]]


def model():
    a2 = sp.Matrix(PARAMS[0:3])
    a3 = sp.Matrix(PARAMS[3:6])
    r1, r2, r3 = (sp.Matrix(PARAMS[6 + 3 * i: 9 + 3 * i]) for i in range(3))
    X = sp.Matrix([x, y, z])
    k = sp.Matrix([0, 0, 1])
    cols = [
        (X + r1).col_join(sp.zeros(3, 1)),
        (r2 - r1 - a2).col_join(a2.cross(X + r2)),
        (r3 - r1 - a3).col_join(a3.cross(X + r3)),
        k.col_join(X.cross(k)),
    ]
    return sp.Matrix.hstack(*cols)


def minor(M, rows, cols=(1, 2, 3, 4)):
    return sp.expand(M.extract([r - 1 for r in rows], [c - 1 for c in cols]).det(method="berkowitz"))


def coefficients(p, gens, monomials):
    P = sp.Poly(p, *gens)
    extra = set(P.monoms()) - set(monomials)
    if extra:
        raise AssertionError(f"unexpected monomials {extra}")
    return [P.coeff_monomial(sp.Mul(*[g ** e for g, e in zip(gens, m)])) for m in monomials]


def generic_poly(prefix, gens, monomials):
    cs = sp.symbols(f"{prefix}0:{len(monomials)}")
    return cs, sum(c * sp.Mul(*[g ** e for g, e in zip(gens, m)]) for c, m in zip(cs, monomials))


def derive():
    M = model()
    minors = [minor(M, rows) for rows in MINOR_ROWS]
    p1 = minor(M, (1, 2, 3, 6))
    p2 = minor(M, (1, 2, 3, 5))
    p3 = minor(M, (1, 2, 3, 4))
    c1 = coefficients(p1, (x, y), P1_MONOMIALS)
    c2 = coefficients(p2, (x, y, z), XYZ_MONOMIALS)
    c3 = coefficients(p3, (x, y, z), XYZ_MONOMIALS)
    assert sp.Poly(p2, z).degree() == 1 and sp.Poly(p3, z).degree() == 1

    # p23 = resultant of p2, p3 in z, from generic coefficients of two (x, y, z)-quadratics linear in z
    u, P2g = generic_poly("u", (x, y, z), XYZ_MONOMIALS)
    v, P3g = generic_poly("v", (x, y, z), XYZ_MONOMIALS)
    P2z = sp.Poly(P2g, z)
    P3z = sp.Poly(P3g, z)
    # z^2 coefficients are zero for p2, p3 (asserted), so use the linear parts
    p23_generic = sp.expand(P2z.coeff_monomial(z) * P3z.coeff_monomial(1) - P3z.coeff_monomial(z) * P2z.coeff_monomial(1))
    p23_generic = p23_generic.subs({u[XYZ_MONOMIALS.index((0, 0, 2))]: 0, v[XYZ_MONOMIALS.index((0, 0, 2))]: 0})
    p23_coeffs_generic = coefficients(p23_generic, (x, y), P23_MONOMIALS)

    # p123 = Res_y(p1, p23) / A02 with the y^3 coefficient of p23 equal to A02 * t
    f, _ = generic_poly("f", (x, y), P1_MONOMIALS)
    g, _ = generic_poly("g", (x, y), P23_MONOMIALS)
    t = sp.Symbol("t")
    fx = {m: c for m, c in zip(P1_MONOMIALS, f)}
    gx = {m: c for m, c in zip(P23_MONOMIALS, g)}
    fy = [sum(c * x ** i for (i, j), c in fx.items() if j == d) for d in range(2, -1, -1)]
    gy = [sum(c * x ** i for (i, j), c in gx.items() if j == d) for d in range(3, -1, -1)]
    A02 = fy[0]
    gy[0] = A02 * t
    S = sp.Matrix([
        [1, fy[1], fy[2], 0, 0],
        [0, fy[0], fy[1], fy[2], 0],
        [0, 0, fy[0], fy[1], fy[2]],
        [t, gy[1], gy[2], gy[3], 0],
        [0, gy[0], gy[1], gy[2], gy[3]],
    ])
    p123_generic = sp.Poly(sp.expand(S.det(method="berkowitz")), x)
    E_generic = [p123_generic.coeff_monomial(x ** h) for h in range(7)]

    # t for our structure: y^3 coefficient of p23 divided by A02
    p23 = sp.expand(sp.Poly(p2, z).coeff_monomial(z) * sp.Poly(p3, z).coeff_monomial(1)
                    - sp.Poly(p3, z).coeff_monomial(z) * sp.Poly(p2, z).coeff_monomial(1))
    y3 = sp.Poly(p23, x, y).coeff_monomial(y ** 3)
    q, r = sp.div(y3, c1[P1_MONOMIALS.index((0, 2))])
    assert r == 0, "A02 must divide the y^3 coefficient of p23"
    t_expr = sp.expand(q)

    # Delta = 0 route
    g_lin = minor(M, (1, 2, 3), (1, 2, 4))
    cg = coefficients(g_lin, (x, y), [(1, 0), (0, 1), (0, 0)])
    p6 = minor(M, (2, 3, 4, 6))
    p7 = minor(M, (2, 3, 5, 6))
    assert sp.Poly(p6, z).degree() == 1 and sp.Poly(p7, z).degree() == 1
    XYZ3 = [(i, j, k) for d in range(3, -1, -1) for i in range(d, -1, -1) for j in range(d - i, -1, -1) for k in [d - i - j]]
    XYZ3 = [m for m in XYZ3 if m[2] <= 1]
    c6 = coefficients(p6, (x, y, z), XYZ3)
    c7 = coefficients(p7, (x, y, z), XYZ3)
    s, P6g = generic_poly("s", (x, y, z), XYZ3)
    w, P7g = generic_poly("w", (x, y, z), XYZ3)
    p67_generic = sp.expand(sp.Poly(P6g, z).coeff_monomial(z) * sp.Poly(P7g, z).coeff_monomial(1)
                            - sp.Poly(P7g, z).coeff_monomial(z) * sp.Poly(P6g, z).coeff_monomial(1))
    p67_coeffs_generic = coefficients(p67_generic, (x, y), P67_MONOMIALS)
    h, P67g = generic_poly("h", (x, y), P67_MONOMIALS)
    gl = sp.symbols("l0:3")
    # p467 = l1^5 * p67(x, -(l0 x + l2) / l1): homogeneous substitution keeps it polynomial
    p467 = sp.expand(sum(c * x ** i * (-(gl[0] * x + gl[2])) ** j * gl[1] ** (5 - j)
                         for c, (i, j) in zip(h, P67_MONOMIALS)))
    p467_coeffs = [sp.Poly(p467, x).coeff_monomial(x ** d) for d in range(6)]

    delta = sp.expand(minor(M, (1, 2, 3), (2, 3, 4)).subs({}))
    return dict(minors=minors, c1=c1, c2=c2, c3=c3, u=u, v=v, p23_coeffs_generic=p23_coeffs_generic,
                f=f, g=g, t=t, E_generic=E_generic, t_expr=t_expr, cg=cg, c6=c6, c7=c7, s=s, w=w,
                p67_coeffs_generic=p67_coeffs_generic, h=h, gl=gl, p467_coeffs=p467_coeffs, delta=delta,
                XYZ3=XYZ3, p1=p1, p2=p2, p3=p3)


def self_check(d, trials: int = 3) -> None:
    """On random rational robots: E_5 = E_6 = 0, the roots of p123 include the trivial x_i, and the
    sum-of-roots form of x4 equals the product form of eq. (12)."""
    rng = random.Random(2013)
    for _ in range(trials):
        vals = {p: sp.Rational(rng.randint(-60, 60), rng.randint(1, 7)) for p in PARAMS}
        c1 = [c.subs(vals) for c in d["c1"]]
        c2 = [c.subs(vals) for c in d["c2"]]
        c3 = [c.subs(vals) for c in d["c3"]]
        g = [e.subs(dict(zip(d["u"], c2)) | dict(zip(d["v"], c3))) for e in d["p23_coeffs_generic"]]
        tval = d["t_expr"].subs(vals)
        E = [e.subs(dict(zip(d["f"], c1)) | dict(zip(d["g"], g)) | {d["t"]: tval}) for e in d["E_generic"]]
        assert E[5] == 0 and E[6] == 0 and E[4] != 0, E
        xb = [-vals[PARAMS[6]], vals[PARAMS[0]] - vals[PARAMS[9]], vals[PARAMS[3]] - vals[PARAMS[12]]]
        poly = sp.Poly(list(reversed(E[:5])), x)
        for r in xb:
            assert poly.eval(r) == 0
        x4_sum = -E[3] / E[4] - sum(xb)
        x4_prod = E[0] / (E[4] * xb[0] * xb[1] * xb[2])
        assert x4_sum == x4_prod


def generate() -> dict[str, str]:
    d = derive()
    self_check(d)
    P = list(PARAMS)
    parts = [
        HEADER.format(script=Path(__file__).name),
        '"""IGP with assigned orientation of 3-cable robots (seed 004 Sec. 3): minors of M\'(O) and elimination.\n\n'
        "Parameters: a2, a3 (a1 = 0), r_i = R b_i; load along +k. See derivations/derive_igp_orientation.py.\n"
        '"""\n',
        f"MINOR_ROWS = {MINOR_ROWS!r}\n",
        f"P1_MONOMIALS = {P1_MONOMIALS!r}  # powers of (x, y)\n",
        f"XYZ_MONOMIALS = {XYZ_MONOMIALS!r}  # powers of (x, y, z) for p2, p3\n",
        f"P23_MONOMIALS = {P23_MONOMIALS!r}\n",
        f"XYZ3_MONOMIALS = {d['XYZ3']!r}  # powers of (x, y, z) for p6, p7\n",
        f"P67_MONOMIALS = {P67_MONOMIALS!r}\n\n",
        function_source("minors_M_prime", P + [x, y, z], d["minors"], "The 15 4x4 minors of M'(O) (eq. 6), rows as in MINOR_ROWS."),
        function_with_magnitude("delta", P, [d["delta"]], "Delta = det M'_{123,234}(O), eq. (7)."),
        function_with_magnitude("p1_coefficients", P, d["c1"], "p1 = det M'_1236 (eq. 9a), coefficients of P1_MONOMIALS."),
        function_with_magnitude("p2_coefficients", P, d["c2"], "p2 = det M'_1235, coefficients of XYZ_MONOMIALS."),
        function_with_magnitude("p3_coefficients", P, d["c3"], "p3 = det M'_1234, coefficients of XYZ_MONOMIALS."),
        function_with_magnitude("t_coefficient", P, [d["t_expr"]], "t = (y^3 coefficient of p23) / A02."),
        function_with_magnitude("p23_from_p2_p3", list(d["u"]) + list(d["v"]), d["p23_coeffs_generic"],
                        "Resultant of p2 (coefficients u) and p3 (v) in z: coefficients of P23_MONOMIALS."),
        function_with_magnitude("p123_from_p1_p23", list(d["f"]) + list(d["g"]) + [d["t"]], d["E_generic"],
                        "p123 = Res_y(p1, p23) / A02 (eq. 10): E_0 .. E_6 (E_5 = E_6 = 0 here)."),
        function_with_magnitude("g_coefficients", P, d["cg"], "p4 = g = det M'_{123,124}(O) (eq. 17): coefficients of x, y, 1."),
        function_with_magnitude("p6_coefficients", P, d["c6"], "p6 = det M'_2346 (eq. 19b), coefficients of XYZ3_MONOMIALS."),
        function_with_magnitude("p7_coefficients", P, d["c7"], "p7 = det M'_2356 (eq. 19c), coefficients of XYZ3_MONOMIALS."),
        function_with_magnitude("p67_from_p6_p7", list(d["s"]) + list(d["w"]), d["p67_coeffs_generic"],
                        "Resultant of p6 and p7 in z: coefficients of P67_MONOMIALS."),
        function_with_magnitude("p467_from_g_p67", list(d["h"]) + list(d["gl"]), d["p467_coeffs"],
                        "p467 = l1^5 p67(x, -(l0 x + l2) / l1) for g = l0 x + l1 y + l2: coefficients of x^0 .. x^5."),
    ]
    return {TARGET: "\n\n".join(p.rstrip("\n") + "\n" for p in parts)}


if __name__ == "__main__":
    write(generate(), ROOT)
