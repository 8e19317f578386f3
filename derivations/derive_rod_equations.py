"""Generate the plain-arithmetic evaluator of the rod system from its one sympy source.

Source: :func:`cdpr_algebra.model.rod_equations.rod_family` (a taut set whose platform anchors and centre of mass
lie on one line).  Its equations are a sum over the taut cables of one per-cable template plus cable-free terms;
this script writes the template, checks for every m = 2..5 that the template summed over the cables is the
family's equations exactly (sympy), differentiates it and writes loop code over the cables:

    cdpr_algebra/generated/rod_equations.py
        rod_equations(x, p, F, J, jacobian)   F and, with ``jacobian``, the nonzero pattern of J = dF/dx

x = (G, u, lam_1..lam_m, mu), p = (A_i (3m), rho_i^2 (m), s_i (m), D.D, Q d (3)) in the family's order.  The code
uses only + - * and indexing, so it runs on floats, complex numpy arrays and interval numbers
(:class:`cdpr_algebra.intervals.complex_krawczyk.ComplexPair`: the rod roots' certificates,
:mod:`cdpr_algebra.certificates.rods`).  Entries of J outside the pattern are never written.  Takes a second:

    python derivations/derive_rod_equations.py
"""

from __future__ import annotations

import sys
from pathlib import Path

import sympy as sp

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "derivations"))

from codegen import HEADER, write  # noqa: E402
from derive_taut_equations import _nonzero, _split_block  # noqa: E402
from cdpr_algebra.model.rod_equations import ROD_M, rod_family  # noqa: E402

TARGET = "cdpr_algebra/generated/rod_equations.py"
POSE = ["G0", "G1", "G2", "u0", "u1", "u2"]


def _template():
    """(pose symbols, lam, mu, cable parameters (a0 a1 a2 r2 s), global parameters (DD f0 f1 f2), the cable-free
    rows (row 0, then the 6 statics rows' cable-free parts), the length row, the statics rows' per-cable parts)."""
    pose = [sp.Symbol(n) for n in POSE]
    G, u = pose[0:3], pose[3:6]
    lam, mu = sp.Symbol("lam"), sp.Symbol("mu")
    a0, a1, a2, r2, s = cpar = sp.symbols("a0 a1 a2 r2 s")
    DD, f0, f1, f2 = gpar = sp.symbols("DD f0 f1 f2")
    a, f = [a0, a1, a2], [f0, f1, f2]
    head = sum(c * c for c in u) - DD
    glob = list(f) + [-mu * u[k] for k in range(3)]
    dv = [G[k] + s * u[k] - a[k] for k in range(3)]
    length = sum(c * c for c in dv) - r2
    part = [-lam * dv[k] for k in range(3)] + [lam * s * (a[k] - G[k]) for k in range(3)]
    _check(pose, lam, mu, cpar, gpar, head, glob, length, part)
    return pose, lam, mu, cpar, gpar, head, glob, length, part


def _check(pose, lam, mu, cpar, gpar, head, glob, length, part):
    """For m = 2..5: the template's rows are exactly the rows of ``rod_family(m)``."""
    for m in ROD_M:
        fam = rod_family(m)
        S = {str(v): v for v in list(fam.variables) + list(fam.parameters)}
        base = dict(zip(pose, [S[n] for n in ("Gx", "Gy", "Gz", "ux", "uy", "uz")]))
        base.update(zip(gpar, [S[n] for n in ("DD", "fx", "fy", "fz")]))
        base[mu] = S["mu"]

        def cable(i):
            d = dict(base)
            d.update(zip(cpar, [S[n] for n in (f"A{i}x", f"A{i}y", f"A{i}z", f"rho2_{i}", f"s{i}")]))
            d[lam] = S[f"lam{i}"]
            return d

        built = [head.xreplace(base)] + [length.xreplace(cable(i)) for i in range(1, m + 1)]
        built += [glob[k].xreplace(base) + sum(part[k].xreplace(cable(i)) for i in range(1, m + 1)) for k in range(6)]
        bad = [k for k, (x, y) in enumerate(zip(built, fam.equations)) if sp.expand(x - y) != 0]
        if bad:
            raise AssertionError(f"m = {m}: the per-cable template does not give rows {bad} of the rod family")


def _jacobian_flag(lines):
    """The lines of :func:`derive_taut_equations._split_block` with its flag named ``jacobian``."""
    return [line.replace("if with_ht:", "if jacobian:") for line in lines]


def generate() -> dict[str, str]:
    pose, lam, mu, cpar, gpar, head, glob, length, part = _template()
    L = ["", "", "def rod_equations(x, p, F, J, jacobian):",
         '    """F and, with ``jacobian``, the nonzero pattern of J = dF/dx of the rod family at x (one point, or the',
         '    columns of arrays); J entries outside the pattern are left untouched."""',
         "    m = len(x) - 7",
         "    ia, ir, i_s, idd, i_f = 0, 3 * m, 4 * m, 5 * m, 5 * m + 1",
         "    rf, rm, jm = 1 + m, 4 + m, 6 + m"]
    L += [f"    {s} = x[{k}]" for k, s in enumerate(POSE)]
    L += ["    mu = x[jm]", "    DD = p[idd]"] + [f"    f{k} = p[i_f + {k}]" for k in range(3)]
    jh = _nonzero([head], pose)
    jg = _nonzero(glob, pose)
    jp = _nonzero(part, pose)
    acc = sorted(set(jg) | set(jp))
    # F first, J under ``if jacobian:``, common subexpressions shared (the helper writes its flag as with_ht)
    L += [f"    j{r}_{c} = 0.0" for r, c in acc if (r, c) not in jg]
    L += _jacobian_flag(_split_block([("F[0]", head)] + [(f"s{k}", e) for k, e in enumerate(glob)],
                                     [(f"J[0, {c}]", e) for (_, c), e in sorted(jh.items())]
                                     + [(f"j{r}_{c}", e) for (r, c), e in sorted(jg.items())]
                                     + [(f"J[rm + {k}, jm]", sp.diff(glob[3 + k], mu)) for k in range(3)], 4, []))
    L += ["    for i in range(m):"]
    L += [f"        {s} = p[ia + 3 * i + {k}]" for k, s in enumerate(cpar[:3])]
    L += ["        r2 = p[ir + i]", "        s = p[i_s + i]", "        lam = x[6 + i]"]
    jl = _nonzero([length], pose)
    L += _jacobian_flag(_split_block(
        [("F[1 + i]", length)] + [(f"s{k} +", e) for k, e in enumerate(part)],
        [(f"J[1 + i, {c}]", e) for (_, c), e in sorted(jl.items())]
        + [(f"j{r}_{c} +", e) for (r, c), e in sorted(jp.items())]
        + [(f"J[{'rf' if k < 3 else 'rm'} + {k % 3}, 6 + i]", sp.diff(e, lam)) for k, e in enumerate(part)], 8, []))
    L += [f"    F[{'rf' if k < 3 else 'rm'} + {k % 3}] = s{k}" for k in range(6)]
    L += ["    if jacobian:"]
    L += [f"        J[{'rf' if r < 3 else 'rm'} + {r % 3}, {c}] = j{r}_{c}" for r, c in acc]
    doc = ('"""Evaluator of the rod system (a taut set whose anchors and centre of mass lie on one line), generated\n'
           "from :func:`cdpr_algebra.model.rod_equations.rod_family` by ``derivations/derive_rod_equations.py`` (see\n"
           "its docstring).  Plain arithmetic and indexing: on floats, numpy columns and interval numbers.\n"
           '"""\n')
    return {TARGET: HEADER.format(script=Path(__file__).name) + doc + "\n".join(L) + "\n"}


if __name__ == "__main__":
    write(generate(), ROOT)
