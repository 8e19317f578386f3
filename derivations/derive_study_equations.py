"""Generate the numeric evaluator of the DGP equations in Study parameters from their one sympy source.

Source: :func:`cdpr_algebra.model.study_equations.study_family` (the taut-set equations of Berti, Merlet and
Carricato 2016, eqs. 4-5, with the pose in Study's kinematic-mapping parameters (e, g) on a chart c . e = 1; see
that module's docstring).  As for ``derive_taut_equations.py``, the equations are a sum over the taut cables of one
per-cable template plus cable-free terms; this script writes the template in factored form (s_i = e b'_i - A_i e + 2 g,
N B_i = vec((e b'_i + 2 g) e*), N = e . e), checks for every m = 2..6 that the template summed over the cables is the
family's equations exactly (sympy), differentiates it (dF/dx and Ht = dF/dp . dp) and writes plain-arithmetic loop
code over the cables, common subexpressions shared (sympy.cse):

    cdpr_algebra/generated/study_equations.py
        study_equations(x, p, dp, F, J, Ht, with_ht)   F, the nonzero pattern of J, and Ht when with_ht
        study_residual(x, p, F)                         F alone
    cdpr_algebra/generated/study_residual_dd.py         study_residual in complex double-double
    cdpr_algebra/generated/study_equations_dd.py        study_equations in complex double-double

x = (e_0..e_3, g_0..g_3, lam_1..lam_m), p = (A_i (3m), rho_i^2 (m), b'_i (3m), g' (3), Q d (3), c (4)).  Rows: the
chart, Study's quadric, the m lengths, the force (3) and moment (3) balances.  Compiled by numba on one point
(``cdpr_algebra.dgp.kernels``).  Takes a few seconds:

    python derivations/derive_study_equations.py
"""

from __future__ import annotations

import sys
from pathlib import Path

import sympy as sp

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "derivations"))

from codegen import HEADER, write  # noqa: E402
from derive_taut_equations import (_block, _cross, _double_double_text, _nonzero, _split_block,  # noqa: E402
                                   check_template)
from cdpr_algebra.model.study_equations import quaternion_product, study_family  # noqa: E402

TARGET = "cdpr_algebra/generated/study_equations.py"
DD_TARGET = "cdpr_algebra/generated/study_residual_dd.py"
DD_EQUATIONS_TARGET = "cdpr_algebra/generated/study_equations_dd.py"
POSE = ["e0", "e1", "e2", "e3", "G0", "G1", "G2", "G3"]
GLOBAL_PARAMS = ["g0", "g1", "g2", "f0", "f1", "f2", "c0", "c1", "c2", "c3"]
CABLE_PARAMS = ["a0", "a1", "a2", "r2", "b0", "b1", "b2"]


def _template():
    """(pose symbols, lam, cable parameters, global parameters, rows 0-1, length row, statics rows' cable-free parts
    (6), statics rows' per-cable parts (6)), factored, checked against the family for m = 2..6."""
    pose = [sp.Symbol(n) for n in POSE]
    e, G = pose[0:4], pose[4:8]
    gpar = [sp.Symbol(n) for n in GLOBAL_PARAMS]
    g, f, c = gpar[0:3], gpar[3:6], gpar[6:10]
    cpar = [sp.Symbol(n) for n in CABLE_PARAMS]
    a, r2, b = cpar[0:3], cpar[3], cpar[4:7]
    lam = sp.Symbol("lam")
    N = sum(x * x for x in e)
    ec = [e[0], -e[1], -e[2], -e[3]]

    def times_n(point):
        q = [x + 2 * y for x, y in zip(quaternion_product(e, [0, *point]), G)]
        return quaternion_product(q, ec)[1:]

    head = [sum(ci * ei for ci, ei in zip(c, e)) - 1, sum(x * y for x, y in zip(e, G))]
    s = [x - y + 2 * z for x, y, z in zip(quaternion_product(e, [0, *b]), quaternion_product([0, *a], e), G)]
    length = sum(x * x for x in s) - r2 * N
    NB = times_n(b)
    glob = [N * f[k] for k in range(3)] + _cross(times_n(g), f)
    part = [lam * (N * a[k] - NB[k]) for k in range(3)] + [lam * x for x in _cross(NB, a)]
    _check(head, length, glob, part)
    return pose, lam, cpar, gpar, head, length, glob, part


def _check(head, length, glob, part):
    """The template summed over the cables is the family, for every m."""
    family_names = ["e0", "e1", "e2", "e3", "g0", "g1", "g2", "g3", "gx", "gy", "gz", "fx", "fy", "fz",
                    "c0", "c1", "c2", "c3"]
    check_template(study_family, head, length, glob, part, dict(zip(POSE + GLOBAL_PARAMS, family_names)))


def generate() -> dict[str, str]:
    pose, lam, cpar, gpar, head, length, glob, part = _template()
    d = {s: sp.Symbol("d" + str(s)) for s in cpar + gpar}
    L = _prologue("study_equations(x, p, dp, F, J, Ht, with_ht)", [
        '    """F and the nonzero pattern of J = dF/dx of the Study-parameter family at one point x, with ``with_ht``',
        '    also Ht = dF/dp . dp; J entries outside the pattern are left untouched."""'])
    jh = _nonzero(head, pose)
    jg = _nonzero(glob, pose)
    jp = _nonzero(part, pose)
    acc = sorted(set(jg) | set(jp))
    asg = [(f"F[{r}]", e) for r, e in enumerate(head)] + [(f"J[{r}, {c}]", e) for (r, c), e in sorted(jh.items())]
    asg += [(f"s{k}", e) for k, e in enumerate(glob)]
    asg += [(f"j{r}_{c}", jg.get((r, c), sp.Integer(0))) for r, c in acc]
    hh = [sp.factor_terms(sum(sp.diff(e, s) * d[s] for s in gpar)) for e in head]
    hg = [sp.factor_terms(sum(sp.diff(e, s) * d[s] for s in gpar)) for e in glob]
    L += ["    h0 = h1 = h2 = h3 = h4 = h5 = 0.0"]
    hd = [f"{d[s]} = dp[ig + {k}]" for k, s in enumerate(gpar[:3])]
    hd += [f"{d[s]} = dp[i_f + {k}]" for k, s in enumerate(gpar[3:6])]
    hd += [f"{d[s]} = dp[ic + {k}]" for k, s in enumerate(gpar[6:])]
    L += _split_block(asg, [(f"Ht[{r}]", e) for r, e in enumerate(hh)] + [(f"h{k}", e) for k, e in enumerate(hg)],
                      4, hd)
    L += _cable_loop(cpar)
    jl = _nonzero([length], pose)
    asg = [("F[2 + i]", length)] + [(f"J[2 + i, {c}]", e) for (_, c), e in sorted(jl.items())]
    asg += [(f"s{k} +", e) for k, e in enumerate(part)]
    asg += [(f"j{r}_{c} +", e) for (r, c), e in sorted(jp.items())]
    asg += [(f"J[{'rf' if k < 3 else 'rm'} + {k % 3}, 8 + i]", sp.diff(e, lam)) for k, e in enumerate(part)]
    hl = sp.factor_terms(sum(sp.diff(length, s) * d[s] for s in cpar))
    hp = [sp.factor_terms(sum(sp.diff(e, s) * d[s] for s in cpar)) for e in part]
    hd = [f"{d[s]} = dp[ia + 3 * i + {k}]" for k, s in enumerate(cpar[:3])]
    hd += [f"{d[cpar[3]]} = dp[ir + i]"]
    hd += [f"{d[s]} = dp[ib + 3 * i + {k}]" for k, s in enumerate(cpar[4:])]
    L += _split_block(asg, [("Ht[2 + i]", hl)] + [(f"h{k} +", e) for k, e in enumerate(hp)], 8, hd)
    L += [f"    F[{'rf' if k < 3 else 'rm'} + {k % 3}] = s{k}" for k in range(6)]
    L += [f"    J[{'rf' if r < 3 else 'rm'} + {r % 3}, {c}] = j{r}_{c}" for r, c in acc]
    L += ["    if with_ht:"]
    L += [f"        Ht[{'rf' if k < 3 else 'rm'} + {k % 3}] = h{k}" for k in range(6)]
    Fo = _prologue("study_residual(x, p, F)", ['    """F of the Study-parameter family at one point x, without J."""'])
    Fo += _block([(f"F[{r}]", e) for r, e in enumerate(head)] + [(f"s{k}", e) for k, e in enumerate(glob)], 4)
    Fo += _cable_loop(cpar)
    Fo += _block([("F[2 + i]", length)] + [(f"s{k} +", e) for k, e in enumerate(part)], 8)
    Fo += [f"    F[{'rf' if k < 3 else 'rm'} + {k % 3}] = s{k}" for k in range(6)]
    doc = ('"""Evaluators of the DGP equations per taut set in Study parameters, generated from\n'
           ":func:`cdpr_algebra.model.study_equations.study_family` by ``derivations/derive_study_equations.py``\n"
           "(see its docstring).  Plain arithmetic and indexing: compiled by numba.\n"
           '"""\n')
    return {TARGET: HEADER.format(script=Path(__file__).name) + doc + "\n".join(L + Fo) + "\n",
            DD_TARGET: _double_double_text("\n".join(Fo) + "\n", _DD_DOC, ("study_residual",)),
            DD_EQUATIONS_TARGET: _double_double_text("\n".join(L) + "\n", _DD_EQUATIONS_DOC, ("study_equations",),
                                                     flags=("with_ht",), sig="EQUATIONS_SIG")}


def _prologue(signature: str, doc: list[str]) -> list[str]:
    """The start of a generated function: signature, docstring, the offsets of the parameter blocks, the pose
    unknowns and the cable-free parameters read into locals."""
    lines = ["", "", f"def {signature}:"] + doc
    lines += ["    m = len(x) - 8", "    ia, ir, ib, ig, i_f, ic = 0, 3 * m, 4 * m, 7 * m, 7 * m + 3, 7 * m + 6",
              "    rf, rm = 2 + m, 5 + m"]
    lines += [f"    {s} = x[{k}]" for k, s in enumerate(POSE)]
    lines += [f"    {s} = p[ig + {k}]" for k, s in enumerate(GLOBAL_PARAMS[:3])]
    lines += [f"    {s} = p[i_f + {k}]" for k, s in enumerate(GLOBAL_PARAMS[3:6])]
    lines += [f"    {s} = p[ic + {k}]" for k, s in enumerate(GLOBAL_PARAMS[6:])]
    return lines


def _cable_loop(cpar) -> list[str]:
    """The head of the loop over the cables: the cable's parameters and tension multiplier read into locals."""
    lines = ["    for i in range(m):"]
    lines += [f"        {s} = p[ia + 3 * i + {k}]" for k, s in enumerate(cpar[:3])]
    lines += ["        r2 = p[ir + i]"]
    lines += [f"        {s} = p[ib + 3 * i + {k}]" for k, s in enumerate(cpar[4:])]
    lines += ["        lam = x[8 + i]"]
    return lines


_DD_DOC = ("The residual F of the DGP equations per taut set in Study parameters in double-double: ``study_residual``\n"
           "of :mod:`cdpr_algebra.generated.study_equations` rewritten by\n"
           ":func:`cdpr_algebra.intervals.codegen.pair_arithmetic_source` over complex double-double numbers (values\n"
           "are (re hi, re lo, im hi, im lo); x (8 + m, 4), p (7 m + 10, 4), F (8 + m, 4)), compiled by numba for the\n"
           "extended-precision Newton residual of the compiled tracker (:mod:`cdpr_algebra.homotopy.compiled`).\n")

_DD_EQUATIONS_DOC = (
    "The DGP equations per taut set in Study parameters in double-double: ``study_equations`` of\n"
    ":mod:`cdpr_algebra.generated.study_equations` (F, the pattern of J = dF/dx, and Ht = dF/dp . dp with ``with_ht``)\n"
    "rewritten by :func:`cdpr_algebra.intervals.codegen.pair_arithmetic_source` over complex double-double numbers\n"
    "(values are (re hi, re lo, im hi, im lo); x (8 + m, 4), p and dp (7 m + 10, 4), F and Ht (8 + m, 4), J (8 + m,\n"
    "8 + m, 4)), compiled by numba for the double-double path tracker (:mod:`cdpr_algebra.homotopy.dd_tracker`).\n")


if __name__ == "__main__":
    write(generate(), ROOT)
