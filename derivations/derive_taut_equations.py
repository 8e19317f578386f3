"""Generate the numeric evaluators of the DGP equations per taut set from their one sympy source.

Source: :func:`cdpr_algebra.model.taut_equations.taut_family` (Berti, Merlet and Carricato 2016, eqs. 4-5 with the
moment about the world origin, all equations quadratic).  Its equations are a sum over the taut cables of one
per-cable template plus cable-free terms; this script writes that template in factored form (B_i = p + R b'_i,
s_i = B_i - A_i: evaluating s_i rather than the expanded polynomial keeps the digits the expansion would cancel),
checks for every m = 2..6 that the template summed over the cables is the family's equations exactly (sympy),
differentiates it (dF/dx, the directional parameter derivative Ht = dF/dp . dp and the
full dF/dp), and writes plain-arithmetic loop code over the cables, common subexpressions shared (sympy.cse):

    cdpr_algebra/generated/taut_equations.py
        taut_equations(x, p, dp, F, J, Ht, with_ht)   F, the nonzero pattern of J, and Ht when with_ht
        taut_residual(x, p, F)                         F alone
        taut_parameter_jacobian(x, p, JP)              the nonzero pattern of dF/dp
    cdpr_algebra/generated/taut_equations_intervals.py   taut_equations, taut_residual over complex intervals
    cdpr_algebra/generated/taut_residual_dd.py           taut_residual in complex double-double
    cdpr_algebra/generated/taut_equations_dd.py          taut_equations in complex double-double

x = (p, u, v, w, lam_1..lam_m), p = (A_i (3m), rho_i^2 (m), b'_i (3m), g' (3), Q d (3)) in the family's order.
The code uses only + - * and indexing ``F[r]``, ``J[r, c]``, so the same function runs compiled by numba on one
point (``cdpr_algebra.dgp.kernels``), on numpy arrays with one column per point (``dgp.solve.FastTautSystem``), and
on python-flint arb balls in numpy object arrays (``cdpr_algebra.certificates``).  Entries of J, JP outside the
pattern are never written (the caller zeroes them).  Takes a few seconds:

    python derivations/derive_taut_equations.py
"""

from __future__ import annotations

import sys
from pathlib import Path

import sympy as sp

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "derivations"))

from codegen import HEADER, _pow_to_mul, write  # noqa: E402
from cdpr_algebra.model.taut_equations import taut_family  # noqa: E402

TARGET = "cdpr_algebra/generated/taut_equations.py"
INTERVAL_TARGET = "cdpr_algebra/generated/taut_equations_intervals.py"
DD_TARGET = "cdpr_algebra/generated/taut_residual_dd.py"
DD_EQUATIONS_TARGET = "cdpr_algebra/generated/taut_equations_dd.py"
POSE = ["P0", "P1", "P2", "u0", "u1", "u2", "v0", "v1", "v2", "w0", "w1", "w2"]
GLOBAL_PARAMS = ["g0", "g1", "g2", "f0", "f1", "f2"]
CABLE_PARAMS = ["a0", "a1", "a2", "r2", "b0", "b1", "b2"]


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _template():
    """(pose symbols, lam, cable parameter symbols, global parameter symbols, rows 0-5, length row, statics rows'
    cable-free parts (6), statics rows' per-cable parts (6)), in factored form (B = p + R b', s = B - A: the
    code evaluates s, not its expansion, which would cancel digits), checked against the family for m = 2..6."""
    pose = [sp.Symbol(n) for n in POSE]
    P, u, v, w = pose[0:3], pose[3:6], pose[6:9], pose[9:12]
    g, f = [sp.Symbol(n) for n in GLOBAL_PARAMS[:3]], [sp.Symbol(n) for n in GLOBAL_PARAMS[3:]]
    cpar = [sp.Symbol(n) for n in CABLE_PARAMS]
    a, r2, b = cpar[0:3], cpar[3], cpar[4:7]
    lam = sp.Symbol("lam")
    uv = _cross(u, v)
    rot = [u[0] * u[0] + u[1] * u[1] + u[2] * u[2] - 1, v[0] * v[0] + v[1] * v[1] + v[2] * v[2] - 1,
           u[0] * v[0] + u[1] * v[1] + u[2] * v[2]] + [w[k] - uv[k] for k in range(3)]
    B = [P[k] + b[0] * u[k] + b[1] * v[k] + b[2] * w[k] for k in range(3)]
    sv = [B[k] - a[k] for k in range(3)]
    length = sv[0] * sv[0] + sv[1] * sv[1] + sv[2] * sv[2] - r2
    G = [P[k] + g[0] * u[k] + g[1] * v[k] + g[2] * w[k] for k in range(3)]
    glob = list(f) + _cross(G, f)
    part = [-lam * sv[k] for k in range(3)] + [lam * c for c in _cross(B, a)]
    _check(rot, length, glob, part)
    return pose, lam, cpar, list(g) + list(f), rot, length, glob, part


def _check(rot, length, glob, part):
    """The template summed over the cables is the family, for every m."""
    family_names = ["px", "py", "pz", "ux", "uy", "uz", "vx", "vy", "vz", "wx", "wy", "wz", "gx", "gy", "gz",
                    "fx", "fy", "fz"]
    check_template(taut_family, rot, length, glob, part, dict(zip(POSE + GLOBAL_PARAMS, family_names)))


def check_template(family, head, length, glob, part, names):
    """For m = 2..6: ``head`` (the cable-free rows), one ``length`` row per cable and the 6 statics rows (``glob``
    plus ``part`` summed over the cables) are exactly the rows of ``family(m)``.  ``names``: {template symbol: family
    symbol} of the pose unknowns and cable-free parameters; the per-cable symbols (CABLE_PARAMS, lam) are the
    family's A{i}x .. b{i}z, rho2_{i}, lam{i} (as in both DGP families)."""
    for m in range(2, 7):
        fam = family(m)
        S = {str(s): s for s in list(fam.variables) + list(fam.parameters)}
        base = {sp.Symbol(v): S[k] for v, k in names.items()}

        def cable(i):
            d = dict(base)
            d.update({sp.Symbol(v): S[k] for k, v in zip([f"A{i}x", f"A{i}y", f"A{i}z", f"rho2_{i}", f"b{i}x",
                                                           f"b{i}y", f"b{i}z"], CABLE_PARAMS)})
            d[sp.Symbol("lam")] = S[f"lam{i}"]
            return d

        built = [e.xreplace(base) for e in head]
        built += [length.xreplace(cable(i)) for i in range(1, m + 1)]
        built += [glob[k].xreplace(base) + sum(part[k].xreplace(cable(i)) for i in range(1, m + 1)) for k in range(6)]
        bad = [k for k, (a, b) in enumerate(zip(built, fam.equations)) if sp.expand(a - b) != 0]
        if bad:
            raise AssertionError(f"m = {m}: the per-cable template does not give rows {bad} of the family")


def _block(assignments, indent):
    """Lines for [(target, expr)] with common subexpressions shared; targets are code strings, '+=' allowed."""
    return _split_block(assignments, [], indent, [])


def _split_block(main, extra, indent, extra_head):
    """Lines for the assignments ``main`` and, under ``if with_ht:`` (after ``extra_head`` lines), ``extra`` (if any), with
    common subexpressions shared across both (one sympy.cse): temporaries that ``main`` needs come first, the others
    only inside the if-block."""
    exprs = [e for _, e in main] + [e for _, e in extra]
    subs, reduced = sp.cse(exprs, symbols=sp.numbered_symbols("t"), order="none")
    deps = {sym: val.free_symbols for sym, val in subs}
    need = set()
    stack = [x for e in reduced[:len(main)] for x in e.free_symbols if x in deps]
    while stack:
        x = stack.pop()
        if x not in need:
            need.add(x)
            stack.extend(y for y in deps[x] if y in deps)
    pad, pad2 = " " * indent, " " * (indent + 4)

    def line(p, target, e):
        op = "+=" if target.endswith("+") else "="
        return f"{p}{target.rstrip('+').rstrip()} {op} {_pow_to_mul(e)}"

    lines = [f"{pad}{sym} = {_pow_to_mul(val)}" for sym, val in subs if sym in need]
    lines += [line(pad, t, e) for (t, _), e in zip(main, reduced[:len(main)])]
    if not extra:
        return lines
    lines += [f"{pad}if with_ht:"] + [pad2 + h for h in extra_head]
    lines += [f"{pad2}{sym} = {_pow_to_mul(val)}" for sym, val in subs if sym not in need]
    lines += [line(pad2, t, e) for (t, _), e in zip(extra, reduced[len(main):])]
    return lines


def _nonzero(rows, variables):
    """{(row, col): derivative} for the structurally nonzero derivatives (kept factored)."""
    out = {}
    for r, e in enumerate(rows):
        for c, v in enumerate(variables):
            d = sp.diff(e, v)
            if sp.expand(d) != 0:
                out[(r, c)] = sp.factor_terms(d)  # 2*(B - a), not -2*a + 2*B: the evaluation order of s
    return out


def _prologue(signature: str, doc: list[str]) -> list[str]:
    """The start of a generated function: signature, docstring, the offsets of the parameter blocks, the pose
    unknowns and the cable-free parameters read into locals."""
    lines = ["", "", f"def {signature}:"] + doc
    lines += ["    m = len(x) - 12", "    ia, ir, ib, ig, i_f = 0, 3 * m, 4 * m, 7 * m, 7 * m + 3", "    rf, rm = 6 + m, 9 + m"]
    lines += [f"    {s} = x[{k}]" for k, s in enumerate(POSE)]
    lines += [f"    {s} = p[ig + {k}]" for k, s in enumerate(GLOBAL_PARAMS[:3])]
    lines += [f"    {s} = p[i_f + {k}]" for k, s in enumerate(GLOBAL_PARAMS[3:])]
    return lines


def generate() -> dict[str, str]:
    pose, lam, cpar, gpar, rot, length, glob, part = _template()
    d = {s: sp.Symbol("d" + str(s)) for s in cpar + gpar}
    L = _prologue("taut_equations(x, p, dp, F, J, Ht, with_ht)", [
        '    """F and the nonzero pattern of J = dF/dx of the taut family at one point x (or at the columns of',
        "    arrays), with ``with_ht`` also Ht = dF/dp . dp; J entries outside the pattern are left untouched.\"\"\""])
    # rows 0-5 and the cable-free part of the statics rows
    jr = _nonzero(rot, pose)
    jg = _nonzero(glob, pose)
    jp = _nonzero(part, pose)  # per-cable statics part, pose columns
    acc = sorted(set(jg) | set(jp))  # statics (row, pose column) pattern
    asg = [(f"F[{r}]", e) for r, e in enumerate(rot)] + [(f"J[{r}, {c}]", e) for (r, c), e in sorted(jr.items())]
    asg += [(f"s{k}", e) for k, e in enumerate(glob)]
    asg += [(f"j{r}_{c}", jg.get((r, c), sp.Integer(0))) for r, c in acc]
    hg = [sp.factor_terms(sum(sp.diff(e, s) * d[s] for s in gpar)) for e in glob]
    L += ["    h0 = h1 = h2 = h3 = h4 = h5 = 0.0"]
    head = [f"{d[s]} = dp[ig + {k}]" for k, s in enumerate(gpar[:3])]
    head += [f"{d[s]} = dp[i_f + {k}]" for k, s in enumerate(gpar[3:])]
    head += [f"Ht[{r}] = 0.0" for r in range(6)]
    L += _split_block(asg, [(f"h{k}", e) for k, e in enumerate(hg)], 4, head)
    # the cables
    L += ["    for i in range(m):"]
    L += [f"        {s} = p[ia + 3 * i + {k}]" for k, s in enumerate(cpar[:3])]
    L += ["        r2 = p[ir + i]"]
    L += [f"        {s} = p[ib + 3 * i + {k}]" for k, s in enumerate(cpar[4:])]
    L += ["        lam = x[12 + i]"]
    jl = _nonzero([length], pose)
    asg = [("F[6 + i]", length)] + [(f"J[6 + i, {c}]", e) for (_, c), e in sorted(jl.items())]
    asg += [(f"s{k} +", e) for k, e in enumerate(part)]
    asg += [(f"j{r}_{c} +", e) for (r, c), e in sorted(jp.items())]
    asg += [(f"J[{'rf' if k < 3 else 'rm'} + {k % 3}, 12 + i]", sp.diff(e, lam)) for k, e in enumerate(part)]
    hl = sp.factor_terms(sum(sp.diff(length, s) * d[s] for s in cpar))
    hp = [sp.factor_terms(sum(sp.diff(e, s) * d[s] for s in cpar)) for e in part]
    head = [f"{d[s]} = dp[ia + 3 * i + {k}]" for k, s in enumerate(cpar[:3])]
    head += [f"{d[cpar[3]]} = dp[ir + i]"]
    head += [f"{d[s]} = dp[ib + 3 * i + {k}]" for k, s in enumerate(cpar[4:])]
    L += _split_block(asg, [("Ht[6 + i]", hl)] + [(f"h{k} +", e) for k, e in enumerate(hp)], 8, head)
    L += [f"    F[{'rf' if k < 3 else 'rm'} + {k % 3}] = s{k}" for k in range(6)]
    L += [f"    J[{'rf' if r < 3 else 'rm'} + {r % 3}, {c}] = j{r}_{c}" for r, c in acc]
    L += ["    if with_ht:"]
    L += [f"        Ht[{'rf' if k < 3 else 'rm'} + {k % 3}] = h{k}" for k in range(6)]
    # F alone (the interval residual at a point, where J would be wasted work)
    Fo = _prologue("taut_residual(x, p, F)", [
        '    """F of the taut family at one point x (or at the columns of arrays), without J."""'])
    Fo += _block([(f"F[{r}]", e) for r, e in enumerate(rot)] + [(f"s{k}", e) for k, e in enumerate(glob)], 4)
    Fo += ["    for i in range(m):"]
    Fo += [f"        {s} = p[ia + 3 * i + {k}]" for k, s in enumerate(cpar[:3])]
    Fo += ["        r2 = p[ir + i]"]
    Fo += [f"        {s} = p[ib + 3 * i + {k}]" for k, s in enumerate(cpar[4:])]
    Fo += ["        lam = x[12 + i]"]
    Fo += _block([("F[6 + i]", length)] + [(f"s{k} +", e) for k, e in enumerate(part)], 8)
    Fo += [f"    F[{'rf' if k < 3 else 'rm'} + {k % 3}] = s{k}" for k in range(6)]
    # full parameter Jacobian
    P = _prologue("taut_parameter_jacobian(x, p, JP)", [
        '    """The nonzero pattern of dF/dp of the taut family at x (entries outside it are left untouched)."""'])
    gcol = ["ig + 0", "ig + 1", "ig + 2", "i_f + 0", "i_f + 1", "i_f + 2"]
    asg = [(f"JP[{'rf' if r < 3 else 'rm'} + {r % 3}, {gcol[c]}]", e) for (r, c), e in sorted(_nonzero(glob, gpar).items())]
    P += _block(asg, 4)
    P += ["    for i in range(m):"]
    P += [f"        {s} = p[ia + 3 * i + {k}]" for k, s in enumerate(cpar[:3])]
    P += [f"        {s} = p[ib + 3 * i + {k}]" for k, s in enumerate(cpar[4:])]
    P += ["        lam = x[12 + i]"]
    ccol = ["ia + 3 * i + 0", "ia + 3 * i + 1", "ia + 3 * i + 2", "ir + i", "ib + 3 * i + 0", "ib + 3 * i + 1",
            "ib + 3 * i + 2"]
    asg = [(f"JP[6 + i, {ccol[c]}]", e) for (_, c), e in sorted(_nonzero([length], cpar).items())]
    asg += [(f"JP[{'rf' if r < 3 else 'rm'} + {r % 3}, {ccol[c]}]", e) for (r, c), e in sorted(_nonzero(part, cpar).items())]
    P += _block(asg, 8)
    doc = ('"""Evaluators of the DGP equations per taut set, generated from\n'
           ":func:`cdpr_algebra.model.taut_equations.taut_family` by ``derivations/derive_taut_equations.py``\n"
           "(see its docstring).  Plain arithmetic and indexing: compiled by numba, on numpy columns, on arb balls.\n"
           '"""\n')
    text = HEADER.format(script=Path(__file__).name) + doc + "\n".join(L + Fo + P) + "\n"
    # the residual with the evaluator signature: F at a box's centre in the form (and roundings) of taut_residual
    Fi = [line.replace("def taut_residual(x, p, F):", "def taut_residual(x, p, dp, F, J, Ht, with_ht):") for line in Fo]
    return {TARGET: text, INTERVAL_TARGET: _interval_text("\n".join(L + Fi) + "\n"),
            DD_TARGET: _double_double_text("\n".join(Fo) + "\n"),
            DD_EQUATIONS_TARGET: _double_double_text("\n".join(L) + "\n", _DD_EQUATIONS_DOC, ("taut_equations",),
                                                     flags=("with_ht",), sig="EQUATIONS_SIG")}


_DD_EQUATIONS_DOC = (
    "The DGP equations per taut set in double-double: ``taut_equations`` of\n"
    ":mod:`cdpr_algebra.generated.taut_equations` (F, the pattern of J = dF/dx, and Ht = dF/dp . dp with ``with_ht``)\n"
    "rewritten by :func:`cdpr_algebra.intervals.codegen.pair_arithmetic_source` over complex double-double numbers\n"
    "(values are (re hi, re lo, im hi, im lo); x (12 + m, 4), p and dp (7 m + 6, 4), F and Ht (12 + m, 4), J (12 + m,\n"
    "12 + m, 4)), compiled by numba for the double-double path tracker (:mod:`cdpr_algebra.homotopy.dd_tracker`).\n")


def _numba_module(doc: str, body: str, sig: str, imports, names) -> str:
    """A generated module of rewritten evaluators: the header, ``doc``, numba, the signature ``sig`` from the first
    module of ``imports`` and, from each (module, operations) of ``imports``, the operations ``body`` calls; every
    function of ``names`` compiled by numba with ``sig`` (cached, without the GIL)."""
    head = f"import numba as nb\n\nfrom {imports[0][0]} import {sig}\n"
    for module, ops in imports:
        used = sorted(op for op in ops if f"{op}(" in body)
        head += f"from {module} import {', '.join(used)}  # noqa: F401\n"
    for name in names:
        body = body.replace(f"def {name}(", f'@nb.njit({sig}, cache=True, error_model="numpy", nogil=True)\n'
                            f"def {name}(", 1)
    return HEADER.format(script=Path(__file__).name) + '"""' + doc + '"""\n\n' + head + "\n\n" + body


def _interval_text(source: str) -> str:
    """taut_equations rewritten over complex intervals (:func:`cdpr_algebra.intervals.codegen.complex_interval_source`)
    and compiled by numba with the evaluator signature of :func:`cdpr_algebra.intervals.complex_kernels.krawczyk_kernel`."""
    from cdpr_algebra.intervals.codegen import complex_interval_source

    from cdpr_algebra.intervals.complex_kernels import OPERATIONS

    doc = ("The DGP equations per taut set over rectangular complex intervals: ``taut_equations`` and\n"
           "``taut_residual`` (here with the signature of the former) of :mod:`cdpr_algebra.generated.taut_equations`\n"
           "rewritten by\n"
           ":func:`cdpr_algebra.intervals.codegen.complex_interval_source` (values are (re lo, re hi, im lo, im hi);\n"
           "x (12 + m, 4), p (7 m + 6, 4), F (12 + m, 4), J (12 + m, 12 + m, 4); outward-rounded operations of\n"
           ":mod:`cdpr_algebra.intervals.complex_kernels`), compiled by numba for the compiled Krawczyk test of\n"
           ":mod:`cdpr_algebra.certificates.equilibria`.\n")
    return _numba_module(doc, complex_interval_source(source), "EVALUATOR_SIG",
                         [("cdpr_algebra.intervals.complex_kernels", OPERATIONS)], ("taut_equations", "taut_residual"))


def _double_double_text(source: str, doc: str | None = None, names=("taut_residual",), flags=(),
                        sig: str = "RESIDUAL_SIG") -> str:
    """The residual functions ``names`` of ``source`` (taut_residual unless told) rewritten over complex double-double
    numbers (every array complex: the tracker's parameters p(t) are complex;
    :func:`cdpr_algebra.intervals.codegen.pair_arithmetic_source`, constants (v, 0)), compiled by numba with the
    residual signature of :mod:`cdpr_algebra.homotopy.double_double` (or ``sig``, with the boolean arguments
    ``flags`` kept as they are); its loads and stores are the interval kernels'
    (the same array layout: their operations that double-double arithmetic does not define)."""
    from cdpr_algebra.intervals.codegen import pair_arithmetic_source

    from cdpr_algebra.homotopy.double_double import OPERATIONS
    from cdpr_algebra.intervals.complex_kernels import OPERATIONS as INTERVAL_OPERATIONS

    doc = doc or ("The residual F of the DGP equations per taut set in double-double: ``taut_residual`` of\n"
           ":mod:`cdpr_algebra.generated.taut_equations` rewritten by\n"
           ":func:`cdpr_algebra.intervals.codegen.pair_arithmetic_source` over complex double-double numbers (values\n"
           "are (re hi, re lo, im hi, im lo); x (12 + m, 4), p (7 m + 6, 4), F (12 + m, 4); operations of\n"
           ":mod:`cdpr_algebra.homotopy.double_double`, loads and stores of :mod:`cdpr_algebra.intervals.complex_kernels`),\n"
           "compiled by numba for the extended-precision Newton residual of\n"
           "the compiled tracker (:mod:`cdpr_algebra.homotopy.compiled`).\n")
    moves = [op for op in INTERVAL_OPERATIONS if op not in OPERATIONS]
    return _numba_module(doc, pair_arithmetic_source(source, flags=flags, real=(), constant_second=0.0), sig,
                         [("cdpr_algebra.homotopy.double_double", OPERATIONS),
                          ("cdpr_algebra.intervals.complex_kernels", moves)], tuple(names))


if __name__ == "__main__":
    write(generate(), ROOT)
