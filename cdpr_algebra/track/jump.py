"""Where the robot lands when its equilibrium stops being stable (a fold): the load's potential -Q d . G is
minimized over poses with unilateral cables, |A_i B_i| <= rho_i for every cable (a constrained minimization,
scipy's SLSQP), from the fold pose pushed a little along the reduced Hessian's softest mode; the minimizer's
active cables are its taut set, and the equilibrium there is polished by Newton on that set's equations and
checked (non-negative tensions, stable).
"""

from __future__ import annotations

import numpy as np
from scipy.optimize import minimize

from cdpr_algebra.model.pose import matrix_from_rodrigues
from cdpr_algebra.model.stability import null_space, constraint_jacobian, hessian

from . import branch

PUSHES = (1e-3, 1e-2, 1e-1)  # the fold pose is pushed by these times the robot's size along the softest mode
LEFT_BASIN = 1e-2  # a minimizer farther than this (x size) from the fold pose has left the fold's basin
ACTIVE_TOL = 1e-7  # a cable is taut at the minimizer when rho_i - |A_i B_i| <= this times the robot's size


def _softest_mode(robot, st):
    """(dG, theta) of the reduced Hessian's lowest eigenvector (rotations scaled by the robot's size)."""
    idx = list(st.cables)
    B = st.position + robot.platform[idx] @ st.rotation.T
    G = st.position + st.rotation @ robot.com
    L = robot.size
    T = np.diag([1.0, 1.0, 1.0] + [1.0 / L] * 3)
    H = T @ hessian(robot.base[idx], B, G, st.tensions[idx], st.lengths[idx]) @ T
    N = null_space(constraint_jacobian(robot.base[idx], B, G, st.lengths[idx]) @ T)
    if N.shape[1] == 0:
        return None
    Hr = N.T @ H @ N
    w, V = np.linalg.eigh(0.5 * (Hr + Hr.T))
    d = T @ (N @ V[:, 0])
    return d[:3], d[3:]


def statics_lam(robot, cables, p, R):
    """lam (tau / rho) of the taut cables from the force and moment balance (least squares) and its residual."""
    idx = list(cables)
    B = p + robot.platform[idx] @ R.T
    G = p + R @ robot.com
    S = robot.base[idx] - B
    W = np.concatenate([S, np.cross(B - G, S)], axis=1).T
    rhs = -robot.load * np.concatenate([robot.load_direction, np.zeros(3)])
    lam, *_ = np.linalg.lstsq(W, rhs, rcond=None)
    return lam, float(np.abs(W @ lam - rhs).max() / robot.load)


def land(robot, st, rho, t):
    """The landing equilibrium after the fold state ``st``, at lengths ``rho`` (time ``t``): (TrackState or None,
    why not)."""
    mode = _softest_mode(robot, st)
    G0 = st.position + st.rotation @ robot.com
    R0 = st.rotation
    d = np.asarray(robot.load_direction, dtype=float)

    L = robot.size

    def pose(z):  # z = (p / L, e): position in robot sizes and Rodrigues parameters, both of order 1
        R = R0 @ matrix_from_rodrigues(*z[3:6])
        return z[:3] * L, R

    def potential(z):
        p, R = pose(z)
        return float(-robot.load * d @ (p + R @ robot.com)) / (robot.load * robot.size)

    def slack(z):
        p, R = pose(z)
        B = p + robot.platform @ R.T
        return (rho ** 2 - np.sum((robot.base - B) ** 2, axis=1)) / robot.size ** 2

    if mode is None:
        pushes = [(0.0, np.concatenate([st.position / L, np.zeros(3)]))]
    else:
        dG, th = mode
        n = max(np.linalg.norm(dG), np.linalg.norm(th) * robot.size, 1e-300)
        pushes = []
        for push in PUSHES:
            for sgn in (1.0, -1.0):
                e = sgn * push * robot.size * th / n / 2  # small rotation theta ~ 2 e (Rodrigues)
                R = R0 @ matrix_from_rodrigues(*e)
                p = G0 + sgn * push * robot.size * dG / n - R @ robot.com
                pushes.append((push, np.concatenate([p / L, e])))
    # the smallest push that leaves the fold's basin: the robot falls to the nearest minimum, not the lowest one
    best = None
    for push in sorted({v[0] for v in pushes}):
        found = None
        for _, z0 in (v for v in pushes if v[0] == push):
            res = minimize(potential, z0, method="SLSQP", constraints=[{"type": "ineq", "fun": slack}],
                           options={"ftol": 1e-15, "maxiter": 1000})
            feasible = np.all(slack(res.x) >= -1e-10)
            if not feasible or (not res.success and res.status != 8):  # 8: line search stalled (at the optimum)
                continue
            if found is None or res.fun < found.fun - 1e-12:
                found = res
        if found is None:
            continue
        p_found, _ = pose(found.x)
        best = found
        if np.abs(p_found - st.position).max() > LEFT_BASIN * robot.size:
            break
    if best is None:
        return None, "the constrained minimization of the potential did not converge"
    p, R = pose(best.x)
    B = p + robot.platform @ R.T
    margin = rho - np.linalg.norm(robot.base - B, axis=1)
    cables = tuple(int(i) for i in np.flatnonzero(margin <= ACTIVE_TOL * robot.size))
    if len(cables) < 2:
        return None, f"lands hanging from {len(cables)} cable(s): its turning about the cable is free (not tracked)"
    if len(cables) > 6:
        return None, f"lands with {len(cables)} taut cables (more than 6: redundantly constrained, not tracked)"
    lam, res = statics_lam(robot, cables, p, R)
    x, ok, resid, _ = branch.newton(robot, cables, rho, branch.unknowns(p, R, lam))
    if not ok:
        return None, "Newton did not converge on the landing's taut set"
    s = branch.state(robot, cables, rho, x, t, resid)
    if np.any(s.tensions[list(cables)] < -1e-9 * robot.load):
        return None, f"the landing's tensions are not all >= 0 ({s.tensions[list(cables)]})"
    return s, None
