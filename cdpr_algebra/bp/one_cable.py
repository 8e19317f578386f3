"""m = 1 (Berti, Merlet and Carricato 2016, Sec. 3.2): the platform hangs from one cable and turns about it; the
turning angle searched by interval bisection in two rational charts of the circle."""

from __future__ import annotations

import time
from fractions import Fraction
import numpy as np
from cdpr_algebra.intervals.arithmetic import Interval, stack
from .model import _F, _Isqrt, _Ivec, _fcross, _fdot, _fsub, _idot
from .results import IntervalSolution, IntervalSubproblem, UndecidedBox


# ---------------------------------------------------------------------------------------------------------------
# m = 1
def _unit_frame(dF):
    """Interval orthonormal frame (X, Y, d^) with X x Y = d^ for the exact direction dF (Gram-Schmidt)."""
    dd = _fdot(dF, dF)
    k = int(np.argmin([abs(float(x)) for x in dF]))
    e = [Fraction(0)] * 3
    e[k] = Fraction(1)
    xF = [e[c] - _fdot(e, dF) * dF[c] / dd for c in range(3)]
    yF = _fcross(dF, xF)
    nd = _Isqrt(dd)
    nx = _Isqrt(_fdot(xF, xF))
    ny = _Isqrt(_fdot(yF, yF))
    return _Ivec(xF) / nx, _Ivec(yF) / ny, _Ivec(dF) / nd


def _solve_one_cable(robot, rho, i, opts, t0):
    """m = 1: the candidates with tension Q > 0 (G below / above B_i on the load line) and a search of the
    turning angle keeping every other cable slack (see the module docstring)."""
    taut1 = (i + 1,)
    n = robot.n
    bF = [_F(b) for b in robot.platform]
    gF = _F(robot.com)
    dF = _F(robot.load_direction)
    v3 = _fsub(gF, bF[i])
    if _fdot(v3, v3) == 0:
        return IntervalSubproblem(taut1, (), (), 0, 0, 0, time.perf_counter() - t0, "interval, m = 1",
                                  "G coincides with the anchor: every orientation is an equilibrium")
    X, Y, D = _unit_frame(dF)
    # platform frame e1', e2', e3' = (g' - b_i') / |..|
    e1p, e2p, e3p = _unit_frame(v3)
    A = Interval.point(np.asarray(robot.base, dtype=float))
    Ai = A[i]
    rho_i = Interval.point(rho[i])
    Bi = Ai + D * rho_i  # tension s1 Q with s1 = +1: B_i = A_i + rho_i d^
    solutions, undecided = [], []
    nboxes = 0
    nbis = 0
    inadm = 2  # the two candidates with B_i = A_i - rho_i d have tension -Q < 0
    for s2 in (+1, -1):
        alphas, betas, hs = [], [], []
        for j in range(n):
            if j == i:
                continue
            w3 = _Ivec(_fsub(bF[j], bF[i]))
            pj, qj, rj = _idot(w3, e1p), _idot(w3, e2p), _idot(w3, e3p)
            w = Bi - Interval(A.lo[j], A.hi[j]) + D * (rj * float(s2))
            wX, wY = _idot(w, X), _idot(w, Y)
            alphas.append((pj * wX + qj * wY * float(s2)) * 2.0)
            betas.append((pj * wY - qj * wX * float(s2)) * 2.0)
            hs.append(Interval.point(rho[j]).sqr() - w.sqr().sum(axis=-1) - pj.sqr() - qj.sqr())
        if alphas:
            al = stack(alphas)
            be = stack(betas)
            hh = stack(hs)
        status, t_found, boxes, bis, und = _one_cable_search(al if alphas else None, be if alphas else None,
                                                             hh if alphas else None, opts)
        nboxes += boxes
        nbis += bis
        # pose at the found angle (floats)
        Xm, Ym, Dm = X.mid, Y.mid, D.mid
        E1p, E2p, E3p = e1p.mid, e2p.mid, e3p.mid
        Bim = Bi.mid
        if status == "admissible" or und:
            chart, t = t_found if t_found is not None else und[0][:2]
            c, s = (1 - t * t) / (1 + t * t), 2 * t / (1 + t * t)
            if chart == 1:
                c, s = -c, -s
            E1 = c * Xm + s * Ym
            E2 = s2 * (-s * Xm + c * Ym)
            R = np.stack([E1, E2, s2 * Dm], axis=1) @ np.stack([E1p, E2p, E3p], axis=1).T
            p = Bim - R @ np.asarray(robot.platform[i], dtype=float)
            tau = np.zeros(n)
            tau[i] = robot.load
        if status == "admissible":
            solutions.append(IntervalSolution(taut1, p, R, tau, 0.0, ("t",), np.array([t]), np.array([t])))
        elif status == "inadmissible":
            inadm += 1
        else:
            for chart, tl, th in und:
                undecided.append(UndecidedBox(taut1, f"turning angle undecided ({'G below' if s2 > 0 else 'G above'} "
                                              f"the anchor, chart {chart})", ("t",), np.array([tl]), np.array([th]),
                                              p, tau))
    return IntervalSubproblem(taut1, tuple(solutions), tuple(undecided), nboxes, nbis, inadm,
                              time.perf_counter() - t0, "interval, m = 1 (turning angle search)")


def _one_cable_search(al, be, hh, opts):
    """Search t in [-1, 1] in two charts for alpha c + beta s <= h (all slack cables): c = +-(1 - t^2)/(1 + t^2),
    s = +-2t/(1 + t^2); multiplied by 1 + t^2 > 0: (-+alpha - h) t^2 +- 2 beta t + (+-alpha - h) <= 0."""
    if al is None:
        return "admissible", (0, 0.0), 1, 0, []
    boxes, bis = 0, 0
    und = []
    for chart, sg in ((0, 1.0), (1, -1.0)):
        a2 = (al * -sg) - hh  # coefficient of t^2
        a1 = be * (2.0 * sg)
        a0 = (al * sg) - hh
        tl = np.array([-1.0])
        th = np.array([1.0])
        while len(tl):
            boxes += len(tl)
            T = Interval(tl[:, None], th[:, None])
            g = a2 * T.sqr() + a1 * T + a0  # (N, ncons)
            inner = np.all(g.hi < 0, axis=1)
            if inner.any():
                k = int(np.flatnonzero(inner)[0])
                return "admissible", (chart, float(0.5 * (tl[k] + th[k]))), boxes, bis, []
            out = np.any(g.lo > 0, axis=1)
            keep = ~out
            tl, th = tl[keep], th[keep]
            tiny = (th - tl) < opts.eps
            for a, b in zip(tl[tiny], th[tiny]):
                und.append((chart, float(a), float(b)))
            tl, th = tl[~tiny], th[~tiny]
            mid = 0.5 * (tl + th)
            bis += len(tl)
            tl, th = np.concatenate([tl, mid]), np.concatenate([mid, th])
    if und:
        return "undecided", None, boxes, bis, und
    return "inadmissible", None, boxes, bis, []
