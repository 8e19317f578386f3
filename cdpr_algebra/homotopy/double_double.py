"""Double-double complex arithmetic (numba), for residuals evaluated in about 32 significant digits.

Why.  Near ill-conditioned stretches of a path (condition numbers 1e10..1e12, e.g. large complex solutions near the
singular sets at infinity of the DGP) Newton's method in double precision stalls at cond x eps: the residual F(x),
a sum of terms that cancel, is only known to eps x the size of those terms.  Evaluating that residual alone in
double-double, with x, the Jacobian, its LU and every update still in double, makes Newton converge to the double
point nearest the path again (mixed-precision iterative refinement: it needs cond x eps < 1, not cond x eps <
tolerance).  :mod:`.compiled` switches a path to such residuals when double precision stalls
(``compiled.track_kernel``).  The idea is HomotopyContinuation.jl's extended-precision residual.

Representation: a real double-double is a pair (hi, lo) with |lo| <= ulp(hi) / 2 and value hi + lo; a complex one
the 4-tuple (re hi, re lo, im hi, im lo); arrays of them have a trailing axis of 4.  The operations carry the names
that :func:`cdpr_algebra.intervals.codegen.pair_arithmetic_source` gives the operations of a rewritten evaluator
(``cc_mul``: complex times complex, ``rc_add``: real plus complex, ``r2c``; :data:`OPERATIONS`; the loads and
stores of a rewritten evaluator are those of the interval kernels, whose arrays have the same layout), so the
generated double-double residual of a system is the mechanical rewrite of its float one.  Products use the fused
multiply-add for the exact error of a product (the pair of Dekker's splitting, 1971), sums Knuth's two-sum (the
"sloppy" addition of Hida, Li and Bailey's QD library: relative error a few units of 2^-104 barring cancellation of
the two operands' leading parts).
"""

from __future__ import annotations

import numba as nb
from llvmlite import ir
from numba import types as nbt
from numba.core import cgutils
from numba.extending import intrinsic

__all__ = ["OPERATIONS", "RESIDUAL_SIG", "EQUATIONS_SIG", "to_dd", "to_complex", "dd_parameters"]

_J = dict(cache=True, error_model="numpy")


@nb.njit(**_J)
def _two_sum(a, b):
    s = a + b
    bb = s - a
    return s, (a - (s - bb)) + (b - bb)


@nb.njit(**_J)
def _quick_two_sum(a, b):
    s = a + b
    return s, b - (s - a)


@intrinsic
def _fma(typingctx, a, b, c):
    """a b + c rounded once (LLVM's llvm.fma.f64: the processor's fused multiply-add, or libm's exact fma where the
    processor has none)."""
    if not all(isinstance(v, nbt.Float) for v in (a, b, c)):
        return None
    sig = nbt.float64(nbt.float64, nbt.float64, nbt.float64)

    def codegen(context, builder, signature, args):
        a, b, c = (context.cast(builder, v, t, nbt.float64) for v, t in zip(args, signature.args))
        d = ir.DoubleType()
        fn = cgutils.get_or_insert_function(builder.module, ir.FunctionType(d, [d, d, d]), "llvm.fma.f64")
        return builder.call(fn, [a, b, c])

    return sig, codegen


@nb.njit(**_J)
def _two_prod(a, b):
    """(p, e) with p = fl(a b) and p + e = a b exactly (the fused multiply-add's rounding error of the product: the
    same pair as Dekker's splitting, barring overflow, in 2 operations instead of 17)."""
    p = a * b
    return p, _fma(a, b, -p)


@nb.njit(**_J)
def dd_add(ah, al, bh, bl):
    s, e = _two_sum(ah, bh)
    return _quick_two_sum(s, e + (al + bl))


@nb.njit(**_J)
def dd_mul(ah, al, bh, bl):
    p, e = _two_prod(ah, bh)
    return _quick_two_sum(p, e + (ah * bl + al * bh))


@nb.njit(**_J)
def dd_div(ah, al, bh, bl):
    """(ah + al) / (bh + bl): a quotient, its remainder, and a correction."""
    q1 = ah / bh
    ph, pl = dd_mul(q1, 0.0, bh, bl)
    rh, rl = dd_add(ah, al, -ph, -pl)
    q2 = rh / bh
    return _quick_two_sum(q1, q2)


# complex o complex
@nb.njit(**_J)
def cc_add(a, b):
    rh, rl = dd_add(a[0], a[1], b[0], b[1])
    ih, il = dd_add(a[2], a[3], b[2], b[3])
    return (rh, rl, ih, il)


@nb.njit(**_J)
def cc_sub(a, b):
    rh, rl = dd_add(a[0], a[1], -b[0], -b[1])
    ih, il = dd_add(a[2], a[3], -b[2], -b[3])
    return (rh, rl, ih, il)


@nb.njit(**_J)
def cc_mul(a, b):
    """(ar + i ai)(br + i bi) = (ar br - ai bi) + i (ar bi + ai br)."""
    p1h, p1l = dd_mul(a[0], a[1], b[0], b[1])
    p2h, p2l = dd_mul(a[2], a[3], b[2], b[3])
    p3h, p3l = dd_mul(a[0], a[1], b[2], b[3])
    p4h, p4l = dd_mul(a[2], a[3], b[0], b[1])
    rh, rl = dd_add(p1h, p1l, -p2h, -p2l)
    ih, il = dd_add(p3h, p3l, p4h, p4l)
    return (rh, rl, ih, il)


@nb.njit(**_J)
def cc_div(a, b):
    """a / b = a conj(b) / |b|^2."""
    n1h, n1l = dd_mul(b[0], b[1], b[0], b[1])
    n2h, n2l = dd_mul(b[2], b[3], b[2], b[3])
    nh, nl = dd_add(n1h, n1l, n2h, n2l)
    c = cc_mul(a, (b[0], b[1], -b[2], -b[3]))
    rh, rl = dd_div(c[0], c[1], nh, nl)
    ih, il = dd_div(c[2], c[3], nh, nl)
    return (rh, rl, ih, il)


@nb.njit(**_J)
def c_neg(a):
    return (-a[0], -a[1], -a[2], -a[3])


# complex o real, real o complex, real o real
@nb.njit(**_J)
def cr_add(a, b):
    rh, rl = dd_add(a[0], a[1], b[0], b[1])
    return (rh, rl, a[2], a[3])


@nb.njit(**_J)
def rc_add(a, b):
    return cr_add(b, a)


@nb.njit(**_J)
def cr_sub(a, b):
    rh, rl = dd_add(a[0], a[1], -b[0], -b[1])
    return (rh, rl, a[2], a[3])


@nb.njit(**_J)
def rc_sub(a, b):
    rh, rl = dd_add(a[0], a[1], -b[0], -b[1])
    return (rh, rl, -b[2], -b[3])


@nb.njit(**_J)
def cr_mul(a, b):
    rh, rl = dd_mul(a[0], a[1], b[0], b[1])
    ih, il = dd_mul(a[2], a[3], b[0], b[1])
    return (rh, rl, ih, il)


@nb.njit(**_J)
def rc_mul(a, b):
    return cr_mul(b, a)


@nb.njit(**_J)
def rr_add(a, b):
    return dd_add(a[0], a[1], b[0], b[1])


@nb.njit(**_J)
def rr_sub(a, b):
    return dd_add(a[0], a[1], -b[0], -b[1])


@nb.njit(**_J)
def rr_mul(a, b):
    return dd_mul(a[0], a[1], b[0], b[1])


@nb.njit(**_J)
def r_neg(a):
    return (-a[0], -a[1])


@nb.njit(**_J)
def r2c(a):
    return (a[0], a[1], 0.0, 0.0)


# the arithmetic of a rewritten evaluator; its loads and stores (c_ld, r_ld, c_st1, c_st2: tuples from and to arrays
# with a trailing axis of 4) are those of :mod:`cdpr_algebra.intervals.complex_kernels`, the same layout
OPERATIONS = ["cc_add", "cc_sub", "cc_mul", "c_neg", "cr_add", "rc_add", "cr_sub", "rc_sub", "cr_mul", "rc_mul",
              "rr_add", "rr_sub", "rr_mul", "r_neg", "r2c"]

_D2 = nbt.float64[:, ::1]
# (x, p, F) of a rewritten generated residual: x the unknowns, p the parameters, F out (double-double arrays)
RESIDUAL_SIG = nbt.void(_D2, _D2, _D2)
# (x, p, dp, F, J, Ht, with_ht) of a rewritten generated evaluator: F, the pattern of J = dF/dx, and with ``with_ht``
# Ht = dF/dp . dp (the tracker of :mod:`.dd_tracker`)
EQUATIONS_SIG = nbt.void(_D2, _D2, _D2, _D2, nbt.float64[:, :, ::1], _D2, nbt.boolean)


@nb.njit(cache=True, error_model="numpy")
def to_dd(z, out):
    """Complex128 array z -> double-double rows of ``out`` (exact: lo parts zero)."""
    for k in range(z.shape[0]):
        out[k, 0], out[k, 1], out[k, 2], out[k, 3] = z[k].real, 0.0, z[k].imag, 0.0


@nb.njit(cache=True, error_model="numpy")
def to_complex(a, out):
    """Double-double rows of ``a`` rounded to the complex128 array ``out``."""
    for k in range(out.shape[0]):
        out[k] = complex(a[k, 0] + a[k, 1], a[k, 2] + a[k, 3])


@nb.njit(cache=True, error_model="numpy")
def dd_parameters(p1, p0, g, t, out):
    """p(t) = (g t p1 + (1 - t) p0) / (g t + 1 - t) (the parameter path of :mod:`.compiled`, complex128 p1, p0, g,
    t) in double-double, into the rows of ``out``; for g = 1 the straight segment t p1 + (1 - t) p0, no division."""
    T = (t.real, 0.0, t.imag, 0.0)
    one_minus_t = cc_sub((1.0, 0.0, 0.0, 0.0), T)
    G = (g.real, 0.0, g.imag, 0.0)
    straight = g == 1.0
    a = T if straight else cc_mul(G, T)
    den = cc_add(a, one_minus_t)
    for k in range(out.shape[0]):
        v = cc_add(cc_mul(a, (p1[k].real, 0.0, p1[k].imag, 0.0)),
                   cc_mul(one_minus_t, (p0[k].real, 0.0, p0[k].imag, 0.0)))
        if not straight:
            v = cc_div(v, den)
        out[k, 0], out[k, 1], out[k, 2], out[k, 3] = v[0], v[1], v[2], v[3]
