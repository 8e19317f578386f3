"""Floating-point coefficients of the 11 quartics of the IGP with assigned position (seed 004, Carricato 2013, Sec. 4).

The quartics are defined once, in ``derivations/derive_dialytic.py``, which generates
``cdpr_algebra/generated/quartics.py``: the straight-line ``quartic_coefficients`` (any arithmetic; exact mode
uses it with Fractions) and, sharing its first layer ``entry_atoms``, tables describing every quartic as

    p_h = (sum of weighted 3 x 3 determinants of quadratic forms in e) / n,   n = e0^2 + e1^2 + e2^2 + e3^2.

:func:`quartic_matrix` evaluates these tables with a few numpy operations on coefficient arrays (products of forms
as 0/1 maps of outer products, the exact division by n as a fixed integer matrix): the same polynomials as
``quartic_coefficients`` on floats, as accurate (~1e-15 relative to each row), in ~70 us instead of ~180 us.
"""

from __future__ import annotations

from itertools import product

import numpy as np

from cdpr_algebra.generated import quartics as _gq

_NQ = len(_gq.QUARTIC_NAMES)


def _forms(deg):
    """Exponents of the monomials of degree ``deg`` in (e0, e1, e2, e3), in decreasing lexicographic order."""
    return tuple(sorted((m for m in product(range(deg + 1), repeat=4) if sum(m) == deg), reverse=True))


def _product_map(left, right, out):
    """0/1 matrix (len(left) len(right), len(out)): coefficients of f g from the flattened outer product of the
    coefficient vectors of f (over ``left``) and g (over ``right``)."""
    idx = {m: k for k, m in enumerate(out)}
    P = np.zeros((len(left) * len(right), len(out)))
    for a, ma in enumerate(left):
        for b, mb in enumerate(right):
            P[a * len(right) + b, idx[tuple(x + y for x, y in zip(ma, mb))]] = 1.0
    return P


def _division_map(sextic):
    """Integer matrix (84, 35): coefficients of S / n, n = e0^2 + e1^2 + e2^2 + e3^2, from those of a sextic form
    S divisible by n (the recurrence Q_(m - 2 e0) = S_m - sum_k Q_(m - 2 e_k), by decreasing e0-degree)."""
    qi = {m: k for k, m in enumerate(_gq.QUARTIC_MONOMIALS)}
    si = {m: k for k, m in enumerate(sextic)}
    D = np.zeros((len(sextic), len(qi)))
    for q, m in enumerate(_gq.QUARTIC_MONOMIALS):
        D[si[(m[0] + 2,) + m[1:]], q] = 1.0
        for k in (1, 2, 3):
            if m[k] >= 2:
                mk = list(m)
                mk[0] += 2
                mk[k] -= 2
                D[:, q] -= D[:, qi[tuple(mk)]]
    return D


# Vectorized evaluation of the generated tables (see cdpr_algebra/generated/quartics.py): every quartic is
# (sum of weighted 3 x 3 determinants of quadratic forms B_b) / n; det B_b by cofactors along column 0.
_QUAD = _gq.QUADRATIC_MONOMIALS
_SEXTIC = _forms(6)
_P22 = _product_map(_QUAD, _QUAD, _gq.QUARTIC_MONOMIALS)  # (100, 35): quadratic x quadratic
_P24N = _product_map(_QUAD, _gq.QUARTIC_MONOMIALS, _SEXTIC) @ _division_map(_SEXTIC)  # (350, 35): (q x quartic) / n
_BLK = np.array(_gq.DET_BLOCKS, dtype=np.intp)  # (K, 3, 3, 10) indices into v
_NBLK = _BLK.shape[0]
# cofactor of row i: the 2 x 2 minor of columns 1, 2 on the other rows (r, s) = (1, 2), (0, 2), (0, 1):
# B[r, 1] B[s, 2] - B[s, 1] B[r, 2] = A B - C D below
_MIN_A = _BLK[:, [1, 0, 0], 1, :]
_MIN_B = _BLK[:, [2, 2, 1], 2, :]
_MIN_C = _BLK[:, [2, 2, 1], 1, :]
_MIN_D = _BLK[:, [1, 0, 0], 2, :]
_COL0 = np.ascontiguousarray(np.swapaxes(_BLK[:, :, 0, :], 1, 2))  # (K, 10, 3)
_COF_SIGN = np.array([1.0, -1.0, 1.0])[:, None]
_TQ, _TB, _TS, _TW = np.array(_gq.DET_TERMS, dtype=np.intp).T
_NV = 1 + len(_gq.ENTRY_LITERALS)


def quartic_matrix(data) -> np.ndarray:
    """The (11, 35) quartic coefficients for work-frame data (a2, a3, b1, b2, b3, x) (floats).

    The same polynomials as ``quartic_coefficients`` of the generated module (and the same first layer), with
    the determinants evaluated on coefficient arrays by numpy from the generated tables.
    """
    atoms = _gq.entry_atoms(*data)
    v = np.empty(_NV + len(atoms))
    v[0] = 0.0
    v[1:_NV] = _gq.ENTRY_LITERALS
    v[_NV:] = np.fromiter(atoms, float, len(atoms))
    X = v[_MIN_A][..., None] * v[_MIN_B][..., None, :] - v[_MIN_C][..., None] * v[_MIN_D][..., None, :]
    cof = (X.reshape(3 * _NBLK, 100) @ _P22).reshape(_NBLK, 3, 35) * _COF_SIGN  # (K, 3, 35) quartics
    det = (v[_COL0] @ cof).reshape(_NBLK, 350) @ _P24N  # (K, 35): det B_b / n
    W = np.zeros((_NQ, _NBLK))
    W[_TQ, _TB] = _TS * v[_TW]
    return W @ det
