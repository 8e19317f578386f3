"""Generate the evaluator of the 6-cable equilibrium system of the uncertainty criterion (Merlet's CC paper, Sec. II-D
and IV-D) from one sympy source.

Unknowns z = (G, e, lam) (12): the position of the centre of mass G, the Rodrigues parameters e of R0^T R
(R = R0 R(e), R(e) = I + 2 q (E + E E), E = [e]_x, q = 1 / (1 + e.e); Berti, Merlet and Carricato 2016 eq. 20
with e0 = 1) and lam_i = tau_i / rho_i.  Equations (12): the six cable lengths

    |A_i - G - R c_i|^2 - rho_i^2 = 0          (c_i = b'_i - g')

and the statics, moments about G,

    sum_i lam_i (s_i ; R c_i x s_i) - f = 0     (s_i = A_i - G - R c_i, f = -Q (d ; 0)).

The Jacobian dF/dz is differentiated by sympy, with q a function of e (dq/de_v = -2 e_v q^2), so the generated
code takes q as an argument and uses only + - * (the caller forms q = 1 / (1 + e.e) in its own arithmetic: floats,
numpy arrays or python-flint arb balls).  The wrench matrix of the statics is dF_statics/dlam, and the length
equations with their derivatives in (G, e) are the first six rows: one function serves the Krawczyk proofs of
``cdpr_algebra.cc.uncertainty`` over parameter boxes (balls) and their floating-point preconditioners.

    cdpr_algebra/generated/rodrigues_equilibrium.py
        rodrigues_equilibrium(G0..G2, e0..e2, l0..l5, q, a00..a52, c00..c52, rho0..rho5, r00..r22, f0..f5)
            -> the 12 equations, then the 144 entries of dF/dz row by row
        rodrigues_lengths(G0..G2, e0..e2, q, a00..a52, c00..c52, rho0..rho5, r00..r22)
            -> the 6 length equations, their 36 derivatives in (G, e), the 36 entries of the wrench matrix

Takes a few seconds:

    python derivations/derive_rodrigues_equilibrium.py
"""

from __future__ import annotations

import sys
from pathlib import Path

import sympy as sp

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT / "derivations"))

from codegen import HEADER, function_source, write  # noqa: E402

TARGET = "cdpr_algebra/generated/rodrigues_equilibrium.py"


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def symbols():
    G = list(sp.symbols("G0:3"))
    e = list(sp.symbols("e0:3"))
    lam = list(sp.symbols("l0:6"))
    q = sp.Symbol("q")
    A = [[sp.Symbol(f"a{i}{k}") for k in range(3)] for i in range(6)]
    c = [[sp.Symbol(f"c{i}{k}") for k in range(3)] for i in range(6)]
    rho = list(sp.symbols("rho0:6"))
    R0 = [[sp.Symbol(f"r{i}{k}") for k in range(3)] for i in range(3)]
    f = list(sp.symbols("f0:6"))
    return G, e, lam, q, A, c, rho, R0, f


def equations(G, e, lam, q, A, c, rho, R0, f):
    """The 12 equations (module doc) with q standing for 1 / (1 + e.e)."""
    E = sp.Matrix([[0, -e[2], e[1]], [e[2], 0, -e[0]], [-e[1], e[0], 0]])
    Re = sp.eye(3) + 2 * q * (E + E * E)
    R = sp.Matrix(R0) * Re
    lengths, cols = [], []
    for i in range(6):
        cc = list(R * sp.Matrix(c[i]))
        s = [A[i][k] - G[k] - cc[k] for k in range(3)]
        lengths.append(s[0] * s[0] + s[1] * s[1] + s[2] * s[2] - rho[i] * rho[i])
        cols.append(s + _cross(cc, s))
    statics = [sum(lam[i] * cols[i][a] for i in range(6)) - f[a] for a in range(6)]
    return lengths + statics


def jacobian(eqs, G, e, lam, q):
    """dF/dz with q = q(e), dq/de_v = -2 e_v q^2."""
    rows = []
    for F in eqs:
        dq = sp.diff(F, q)
        row = [sp.diff(F, g) for g in G]
        row += [sp.diff(F, ev) + dq * (-2 * ev * q * q) for ev in e]
        row += [sp.diff(F, lv) for lv in lam]
        rows.append(row)
    return rows


def generate() -> dict:
    G, e, lam, q, A, c, rho, R0, f = symbols()
    eqs = equations(G, e, lam, q, A, c, rho, R0, f)
    J = jacobian(eqs, G, e, lam, q)
    args = G + e + lam + [q] + [v for row in A for v in row] + [v for row in c for v in row] + rho \
        + [v for row in R0 for v in row] + f
    src = function_source("rodrigues_equilibrium", args, eqs + [v for row in J for v in row],
                          "The 12 equations of the 6-cable equilibrium in (G, e, lam), then dF/dz row by row (144); "
                          "q = 1 / (1 + e.e) (module doc).")
    # the length equations, their derivatives in (G, e) and the wrench matrix d(statics)/d lam: the same rows
    pose_args = G + e + [q] + [v for row in A for v in row] + [v for row in c for v in row] + rho \
        + [v for row in R0 for v in row]
    zero = {v: 0 for v in lam + f}
    lengths = eqs[:6] + [J[r][k] for r in range(6) for k in range(6)] \
        + [J[6 + a][6 + i].xreplace(zero) for a in range(6) for i in range(6)]
    src2 = function_source("rodrigues_lengths", pose_args, lengths,
                           "The 6 cable-length equations, their derivatives in (G, e) row by row (36) and the wrench "
                           "matrix (columns (s_i ; R c_i x s_i)) row by row (36): rows 0-5 of rodrigues_equilibrium "
                           "and its block d(statics)/d lam.")
    text = (HEADER.format(script="derive_rodrigues_equilibrium.py")
            + '"""6-cable equilibrium in Rodrigues parameters (see derivations/derive_rodrigues_equilibrium.py)."""\n\n\n'
            + src + "\n\n" + src2)
    return {TARGET: text}


if __name__ == "__main__":
    write(generate(), ROOT)
