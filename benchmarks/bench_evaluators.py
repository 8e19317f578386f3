"""The three ways of evaluating a polynomial system that :mod:`cdpr_algebra.homotopy.systems` weighed (its
module doc records the figures): its straight-line code, sympy's ``lambdify`` of dense matrices, and a tensor of
monomials.  Run by hand: ``python -m benchmarks.bench_evaluators`` (median of 200 / 50 / 20 calls).
"""

import sys
import time
from pathlib import Path

import numpy as np
import sympy as sp

sys.path.insert(0, str(Path(__file__).resolve().parent))
sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from bench_homotopy import dgp_family  # noqa: E402
from timing import machine  # noqa: E402


def measure(npts=156, reps=200):
    """Seconds per batched evaluation of F, dF/dx, dF/dp at npts points: straight-line code, lambdify, tensor."""
    sysm = dgp_family()
    rng = np.random.default_rng(0)
    x = rng.normal(size=(npts, sysm.n)) + 1j * rng.normal(size=(npts, sysm.n))
    p = rng.normal(size=(npts, sysm.m)) + 1j * rng.normal(size=(npts, sysm.m))
    sysm.evaluate_all(x, p)  # compile outside the timing
    t0 = time.perf_counter()
    for _ in range(reps):
        sysm.evaluate_all(x, p)
    t_sl = (time.perf_counter() - t0) / reps
    # lambdify of dense matrices
    args = list(sysm.variables) + list(sysm.parameters)
    Fm = sp.Matrix(sysm.equations)
    exprs = list(Fm) + list(Fm.jacobian(sysm.variables)) + list(Fm.jacobian(sysm.parameters))
    lf = sp.lambdify(args, exprs, modules="numpy", cse=True)
    z = np.hstack([x, p]).T
    t0 = time.perf_counter()
    for _ in range(reps // 4):
        [np.broadcast_to(v, (npts,)) for v in lf(*z)]
    t_lam = (time.perf_counter() - t0) / (reps // 4)
    # tensor route: joint monomials of (x, p), coefficient matrices for F, dF/dx, dF/dp
    allv = list(sysm.variables) + list(sysm.parameters)
    polys = [sp.Poly(e, *allv) for e in sysm.equations]
    mons = sorted({mon for P_ in polys for mon in P_.monoms()})
    E = np.array(mons, dtype=float)
    C = np.zeros((len(mons), sysm.neq), dtype=complex)
    idx = {mon: k for k, mon in enumerate(mons)}
    for i, P_ in enumerate(polys):
        for mon, c in P_.terms():
            C[idx[mon], i] = complex(c)
    nv = len(allv)
    # derivative: d/dz_j of z^e = e_j z^(e - u_j): precompute shifted exponents
    Ed = np.maximum(E[None, :, :] - np.eye(nv)[:, None, :], 0)
    coef = E.T  # (nv, nmon)
    t0 = time.perf_counter()
    for _ in range(reps // 10):
        zz = np.hstack([x, p])
        M = np.prod(zz[:, None, :] ** E[None], axis=2)
        F = M @ C
        Md = np.prod(zz[:, None, None, :] ** Ed[None], axis=3) * coef[None]
        Jall = np.einsum("pjk,ki->pij", Md, C)
    t_ten = (time.perf_counter() - t0) / (reps // 10)
    print(machine())
    print(f"straight-line exec: {t_sl * 1e3:.3f} ms; lambdify dense: {t_lam * 1e3:.3f} ms; tensor: {t_ten * 1e3:.3f} ms")


if __name__ == "__main__":
    measure()
