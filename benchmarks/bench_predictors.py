"""Steps per path of predictors under the tracker's acceptance rule (issue 19 item 2: fewer steps?).

    python -m benchmarks.bench_predictors [--tol 3e-4 1e-3] [--stride 6] [--methods rk4 pade21 taylor3 .. taylor7]

Every ``stride``-th start solution of the stored 4-cable generic set is tracked over phase 1 (t = 1 -> 0.1) of
seed 000 Test 3's taut set {1, 3, 5, 6}, in Python (numpy; the homotopy of ``dgp.solve``), with the acceptance
rule of :mod:`cdpr_algebra.homotopy.tracker` (first Newton update <= the predictor tolerance relative to 1 + |x|,
Newton contracting, the corrector tolerance 1e-8 reached within three updates) and its step-size rule (exponent
1 / (order + 1)), by

* RK4 (the tracker's predictor; four Jacobian factorizations per step);
* Padé (2, 1) per coordinate from the Taylor coefficients x1, x2, x3 of the path (x1 from the tangent, x2 and x3
  from H sampled at 16 points on a circle of radius 0.05 in t: exact for the polynomial homotopy up to rounding;
  one factorization per step), the Taylor polynomial where the Padé denominator is degenerate;
* ``taylorK`` (K = 3 .. 7, ``--methods``): the Taylor polynomial of order K of the path from the coefficients
  x1 .. xK computed the same way (exact: H along the truncated series is a polynomial of degree <= 2K < 16 in s).

Prints the steps and rejected steps of each on the paths every method finishes.  Step counts, not times: the
Python loop is slow.  Measured (thirteenth session, tolerance 3e-4, 35 paths): RK4 1892 steps; Taylor of order
3, 4, 5, 6, 7: 3565, 2691, 2282, 2018, 1853.  A Taylor step needs one LU, K solves and K - 1 coefficient
evaluations; at order 7, where it matches RK4's steps, that is about RK4's cost (3 more LUs, 4 solves, 4
evaluations), so generated Taylor-mode evaluators would not pay.
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

from cdpr_algebra.dgp.normalization import normalized_problem
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

CTOL, MAX_CONTRACTION, SAFETY = 1e-8, 0.2, 0.8


def _homotopy():
    import cdpr_algebra.dgp.solve as S
    from cdpr_algebra.homotopy.start_systems import parameter_homotopy
    from cdpr_algebra.model.robot import load_robot
    from cdpr_algebra.model.taut_sets import lengths_and_taut_sets

    robot = load_robot(ROOT / "examples" / "seed000_test3.toml")
    rho, _ = lengths_and_taut_sets(robot)
    cables = (0, 2, 4, 5)
    target, *_ = normalized_problem(robot, rho, cables)
    p_gen, X_gen = S._generic(len(cables))
    (H,) = parameter_homotopy(S.fast_family(len(cables)), p_gen, target)
    return H, X_gen


def rk4(H, x, t, dt, h):
    def f(xx, tt):
        _, J, Ht = H.evaluate_all(xx[None], np.array([tt]))
        return np.linalg.solve(J[0], -Ht[0] * dt)

    k1 = f(x, t)
    k2 = f(x + 0.5 * h * k1, t + 0.5 * h * dt)
    k3 = f(x + 0.5 * h * k2, t + 0.5 * h * dt)
    k4 = f(x + h * k3, t + h * dt)
    return x + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4)


_W = np.exp(2j * np.pi * np.arange(16) / 16)


def taylor(H, x, t, dt, order=3):
    """x, x1, .., x_order of the path through (x, t) along t + s dt."""
    _, J, Ht = H.evaluate_all(x[None], np.array([t]))
    coeffs = [x, np.linalg.solve(J[0], -Ht[0] * dt)]
    r = 0.05
    for k in range(2, order + 1):
        s = r * _W
        X = sum(coeffs[j][None, :] * s[:, None] ** j for j in range(len(coeffs)))
        G = H.evaluate_and_jacobian(X, t + s * dt)[0]
        ck = (G * _W[:, None] ** (-k)).mean(axis=0) / r ** k
        coeffs.append(np.linalg.solve(J[0], -ck))
    return coeffs


def pade(coeffs, h):
    x0, x1, x2, x3 = coeffs
    out = x0 + h * x1 + h * h * x2 + h ** 3 * x3
    ok = np.abs(x2) > 1e-14 * (1 + np.abs(x0))
    b1 = np.where(ok, -x3 / np.where(ok, x2, 1), 0)
    den = 1 + b1 * h
    ok &= np.abs(den) > 1e-3
    rat = (x0 + (x1 + b1 * x0) * h + (x2 + b1 * x1) * h * h) / np.where(ok, den, 1)
    return np.where(ok, rat, out)


def track(H, x, ptol, method, ta=1.0, tb=0.1, h=0.05, max_steps=3000):
    dt = tb - ta
    s, n, rejected, nrej, cache = 0.0, 0, False, 0, None
    order = 4 if method == "rk4" else 3 if method == "pade21" else int(method[len("taylor"):])
    while s < 1 and n < max_steps:
        ha = min(h, 1 - s)
        t = ta + s * dt
        if method == "rk4":
            xt = rk4(H, x, t, dt, ha)
        elif method == "pade21":
            cache = cache or taylor(H, x, t, dt)
            xt = pade(cache, ha)
        else:
            cache = cache or taylor(H, x, t, dt, order)
            xt = sum(c * ha ** j for j, c in enumerate(cache))
        tn = ta + (s + ha) * dt
        F, J = H.evaluate_and_jacobian(xt[None], np.array([tn]))
        d1 = np.linalg.solve(J[0], -F[0])
        x1 = xt + d1
        d2 = np.linalg.solve(J[0], -H.evaluate_and_jacobian(x1[None], np.array([tn]))[0][0])
        x2 = x1 + d2
        sc = 1 + np.linalg.norm(x2)
        e1, e2 = np.linalg.norm(d1) / sc, np.linalg.norm(d2) / sc
        contracting = e2 <= MAX_CONTRACTION * e1 or (e1 <= 1e-9 and e2 <= 1e-10)
        ok = e1 <= ptol and contracting and e2 <= CTOL
        if not ok and e1 <= ptol and contracting:
            d3 = np.linalg.solve(J[0], -H.evaluate_and_jacobian(x2[None], np.array([tn]))[0][0])
            if np.linalg.norm(d3) / sc <= min(CTOL, MAX_CONTRACTION * e2):
                ok, x2 = True, x2 + d3
        n += 1
        ratio = SAFETY * (ptol / max(e1, 1e-300)) ** (1 / (order + 1))
        if ok:
            x, cache = x2, None
            s = 1.0 if s + ha >= 1 - 1e-15 else s + ha
            hn = min(ha * min(max(ratio, 1.0), 1.0 if rejected else 2.5), 0.25)
        else:
            nrej += 1
            hn = ha * min(max(ratio, 0.1), 0.5)
        h = max(h, hn) if ok and ha < h else hn
        rejected = not ok
    return n, nrej, s >= 1


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--tol", type=float, nargs="+", default=[3e-4, 1e-3])
    ap.add_argument("--stride", type=int, default=6)
    ap.add_argument("--methods", nargs="+", default=["rk4", "pade21"],
                    help="rk4, pade21, taylor3 .. taylor7")
    a = ap.parse_args(argv)
    H, X = _homotopy()
    starts = range(0, len(X), a.stride)
    for tol in a.tol:
        runs = {m: [track(H, X[i].copy(), tol, m) for i in starts] for m in a.methods}
        both = [k for k in range(len(starts)) if all(runs[m][k][2] for m in runs)]
        for method, rs in runs.items():
            print(f"tolerance {tol:.0e}  {method:7s} reached t = 0.1 on {sum(r[2] for r in rs)} of {len(rs)} paths; "
                  f"on the {len(both)} all reach: {sum(rs[k][0] for k in both)} steps, "
                  f"{sum(rs[k][1] for k in both)} rejected", flush=True)

if __name__ == "__main__":
    main()
