"""DGP with one taut cable (seed 000 Sec. 3.2, Algorithm 2), solved analytically.

With only cable i taut, the cable line passes through G along the load direction d.  Four equilibria:
B_i = A_i + s1 rho_i d (s1 = +1: tension tau_i = Q >= 0; s1 = -1: tau_i = -Q) and G = B_i + s2 |g' - b_i'| d
(s2 = +1: G hangs below B_i; s2 = -1: inverted).  The platform may still turn by theta about the cable; cable j
stays slack where |B_j(theta) - A_j| <= rho_j, i.e. alpha_j cos(theta) + beta_j sin(theta) <= h_j.  Unlike
Algorithm 2, which tests each cable's minimum distance on its own, the feasible angles of all slack cables are
intersected, so a reported equilibrium has one theta at which every other cable is slack.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from cdpr_algebra.model.pose import rotation_about, rotation_taking

TWO_PI = 2 * np.pi


def _intersect(arcs_a, arcs_b):
    """Intersection of two unions of arcs [lo, hi] (radians, lo in [0, 2pi), hi - lo <= 2pi)."""
    out = []
    for a0, a1 in arcs_a:
        for b0, b1 in arcs_b:
            for shift in (-TWO_PI, 0.0, TWO_PI):
                lo, hi = max(a0, b0 + shift), min(a1, b1 + shift)
                if lo <= hi:
                    out.append((lo % TWO_PI, lo % TWO_PI + (hi - lo)))
    return out


def _merged(arcs):
    """The union of arcs [lo, hi] (lo in [0, 2pi)) as disjoint arcs: touching ones joined, across 2pi too (the
    intersection above cuts an arc that crosses 2pi in two)."""
    arcs = sorted(arcs)
    out = []
    for lo, hi in arcs:
        if out and lo <= out[-1][1] + 1e-12:
            out[-1] = (out[-1][0], max(out[-1][1], hi))
        else:
            out.append((lo, hi))
    if len(out) > 1 and out[-1][1] >= out[0][0] + TWO_PI - 1e-12:
        out = [(out[-1][0], max(out[0][1] + TWO_PI, out[-1][1]))] + out[1:-1]
    if out and out[0][1] - out[0][0] >= TWO_PI - 1e-12:
        return [(0.0, TWO_PI)]
    return out


def slack_arcs(robot, rho, slack, i, Bi, R0, axis, slack_tol: float = 1e-9) -> list:
    """The arcs of angle theta (radians, [lo, hi]) over which the cables ``slack`` stay slack while the platform
    turns by theta about the unit ``axis`` through its anchor point B_i (world position ``Bi``), starting from the
    rotation ``R0``: cable j is slack where |B_j(theta) - A_j| <= rho_j, i.e. alpha_j cos(theta) + beta_j
    sin(theta) <= h_j; [] when no angle keeps them all slack."""
    A, bl = robot.base, robot.platform
    arcs = [(0.0, TWO_PI)]
    for j in slack:
        c = R0 @ (bl[j] - bl[i])
        c_par = float(c @ axis)
        c_perp = c - c_par * axis
        e = Bi - A[j] + c_par * axis
        alpha = float(e @ c_perp)
        beta = float(e @ np.cross(axis, c_perp))
        K = float(e @ e + c_perp @ c_perp)
        h = (rho[j] ** 2 * (1 + slack_tol) - K) / 2
        amp = np.hypot(alpha, beta)
        if h >= amp:
            continue
        if h < -amp:
            return []
        phi = np.arctan2(beta, alpha)
        half = np.arccos(h / amp)
        lo = (phi + half) % TWO_PI
        arcs = _intersect(arcs, [(lo, lo + TWO_PI - 2 * half)])
        if not arcs:
            return []
    return _merged(arcs)


def middle_pose(arcs, axis, R0, Bi, bi):
    """(R, position, arcs relative to it) of the pose in the middle of the largest of ``arcs``: the platform turned
    from ``R0`` by that angle about the unit ``axis`` through its anchor point b_i' (``bi``), held at ``Bi``."""
    lo, hi = max(arcs, key=lambda a: a[1] - a[0])
    theta = 0.5 * (lo + hi)
    R = rotation_about(axis, theta) @ R0
    return R, Bi - R @ bi, tuple((a - theta, b - theta) for a, b in arcs)


@dataclass(frozen=True)
class OneCableEquilibrium:
    cable: int  # 0-based
    position: np.ndarray  # platform-frame origin at the representative angle
    rotation: np.ndarray
    tension: float
    hanging: bool  # G below B_i along the load (the only candidate for stability)
    theta_arcs: tuple  # feasible rotation angles about the cable (radians, relative to the representative)


def one_cable_equilibria(robot, cable: int, lengths=None, slack_tol: float = 1e-9):
    """The equilibria with only ``cable`` taut and every other cable slack (all four sign cases), each with
    the arcs of rotation angle about the cable over which the other cables stay slack; [] if none."""
    rho = np.asarray(robot.lengths if lengths is None else lengths, dtype=float)
    d = robot.load_direction
    A, bl, gl = robot.base, robot.platform, robot.com
    i = cable
    gb = gl - bl[i]
    dist = float(np.linalg.norm(gb))
    out = []
    for s1 in (+1, -1):
        Bi = A[i] + s1 * rho[i] * d
        for s2 in ((+1, -1) if dist > 1e-12 * robot.size else (+1,)):
            R0 = rotation_taking(gb / dist, s2 * d) if dist > 1e-12 * robot.size else np.eye(3)
            arcs = slack_arcs(robot, rho, [j for j in range(robot.n) if j != i], i, Bi, R0, d, slack_tol)
            if not arcs:
                continue
            R, position, relative = middle_pose(arcs, d, R0, Bi, bl[i])
            out.append(OneCableEquilibrium(i, position, R, s1 * robot.load, s1 > 0 and s2 > 0, relative))
    return out
