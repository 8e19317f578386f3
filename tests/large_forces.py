"""Test helper: robots built around a known equilibrium whose cables carry internal forces K times the load.

Construction (m = 4 .. 6 taut cables, load Q along d = -z; m = 3 in :func:`_three_cables`): wrenches w_i = (U_i, B_i x U_i) of unit directions
U_i (from B_i to A_i) and the load wrench (Q d, G x Q d) with G = G0 + a e1 + b e2 (its part across d is free: the
columns c_k = (0, e_k x Q d), as many as 6 - m).  First a *self-stress*: s > 0 and g with sum s_i w_i + sum g_k c_k
= 0, made by choosing cables 1 .. m-1 and s_1 .. s_{m-1} at random and the last cable as the line that balances
them (its direction f = -sum s_i U_i / s_m with s_m = |sum s_i U_i|, its moment m = -(sum s_i B_i x U_i +
sum g_k c_k) / s_m, the Pluecker condition f . m = 0 met by g, or for m = 6 by moving B_1 across U_1, and
B_m = f x m on that line).  Then B_m is moved by delta across U_m: the 6 x 6 matrix M = [w_1 .. w_m, c_k] becomes
invertible with a singular value ~ delta, and the solution of M z = -(Q d, G0 x Q d) has tensions ~ (c / delta) s
+ O(Q): delta is chosen (sign and size) so that the largest tension is K Q.  That is an exact equilibrium (the
residual is checked), regular when delta != 0.
"""

import numpy as np

from cdpr_algebra.dgp.normalization import normalized_coordinates, normalized_problem, world_coordinates
from cdpr_algebra.model.robot import Robot
from equilibria import hang_platform


def _wrench(B, U):
    return np.concatenate([U, np.cross(B, U)])


def _three_cables(rng, K, Q, d):
    """m = 3: cable lines concurrent at C (then the moment balances with G on the load line through C) and
    nearly coplanar directions, U_3 = -(s_1 U_1 + s_2 U_2) / |..| tilted by eps out of their plane: the force
    balance sum tau_i U_i = -Q d has tau ~ (s_1, s_2, |s_1 U_1 + s_2 U_2|) / eps; eps (sign and size) gives
    max tau = K Q."""
    while True:
        U = np.array([[*rng.uniform(-0.7, 0.7, 2), 1.0] for _ in range(2)])
        U /= np.linalg.norm(U, axis=1)[:, None]
        sv = rng.uniform(1.0, 2.0, size=2)
        f = -(sv @ U)
        f /= np.linalg.norm(f)
        n = np.cross(U[0], U[1])
        n /= np.linalg.norm(n)

        def tensions(eps):
            u3 = f + eps * n
            Ua = np.vstack([U, u3 / np.linalg.norm(u3)])
            return Ua, np.linalg.solve(Ua.T, -Q * d)

        Ua, tau = tensions(1e-6)
        eps = 1e-6 * np.max(tau) / (K * Q)
        Ua, tau = tensions(eps)
        if np.all(tau > 0.05 * Q) and abs(np.max(tau) / (K * Q) - 1) <= 0.5:
            break
    C = np.array([*rng.uniform(-0.2, 0.2, 2), 0.0])
    B = C - rng.uniform(0.2, 0.5, size=(3, 1)) * Ua
    G = C + rng.uniform(0.2, 0.5) * d
    return B, Ua, tau, G


def large_force_robot(m: int, K: float, seed: int):
    """(robot, p, R, tau): an m-cable robot holding a known equilibrium with max tau = K Q (module doc)."""
    rng = np.random.default_rng(seed)
    d = np.array([0.0, 0.0, -1.0])
    Q = float(rng.uniform(5, 20))
    if m == 3:
        B, U, tau, G = _three_cables(rng, K, Q, d)
        A, b, gg, rho, p, R = hang_platform(rng, B, U, G)
        return Robot(A, b, gg, Q, d, rho, name=f"large_forces_m3_K{K:g}"), p, R, tau
    E = [np.eye(3)[0], np.eye(3)[1]][: 6 - m]
    C = [np.concatenate([np.zeros(3), np.cross(e, Q * d)]) for e in E]
    while True:
        U = np.array([[*rng.uniform(-0.7, 0.7, 2), 1.0] for _ in range(m - 1)])
        U /= np.linalg.norm(U, axis=1)[:, None]
        B = rng.uniform(-0.5, 0.5, size=(m - 1, 3))
        s = rng.uniform(1.0, 2.0, size=m - 1)
        F = s @ U
        sm = np.linalg.norm(F)
        f = -F / sm
        M0 = s @ np.array([np.cross(Bi, Ui) for Bi, Ui in zip(B, U)])
        # f . m = 0 with m = -(M0 + sum g_k C_k[3:]) / sm
        if m < 6:
            a = np.array([f @ c[3:] for c in C])
            g = np.zeros(len(C))
            k = int(np.argmax(np.abs(a)))
            g[k] = -(f @ M0) / a[k]
        else:
            g = np.zeros(0)
            e = np.cross(U[0], f)
            e /= np.linalg.norm(e)
            # moving B_1 by t e adds t s_1 e x U_1 to M0
            t = -(f @ M0) / (s[0] * (f @ np.cross(e, U[0])))
            B[0] = B[0] + t * e
            M0 = s @ np.array([np.cross(Bi, Ui) for Bi, Ui in zip(B, U)])
        mom = -(M0 + sum(gk * c[3:] for gk, c in zip(g, C))) / sm
        if abs(f @ mom) > 1e-9 * (1 + np.linalg.norm(mom)):
            continue
        Bm = np.cross(f, mom) + rng.uniform(-0.3, 0.3) * f
        Bm_dir = np.cross(f, rng.normal(size=3))
        Bm_dir /= np.linalg.norm(Bm_dir)
        G0 = np.array([*rng.uniform(-0.2, 0.2, 2), -0.3])
        rhs = -np.concatenate([Q * d, np.cross(G0, Q * d)])
        Uall = np.vstack([U, f])

        def matrix(Ball):
            return np.column_stack([_wrench(Bi, Ui) for Bi, Ui in zip(Ball, Uall)] + C)

        def solve(delta):
            Ball = np.vstack([B, Bm + delta * Bm_dir])
            return Ball, np.linalg.solve(matrix(Ball), rhs)

        # tensions ~ c / delta along s: find the sign of c, then scale delta to reach K Q
        Ball, z = solve(1e-6)
        c = z[0] * 1e-6 / s[0]
        delta = c / (K * Q / np.max(np.append(s, sm)))
        Ball, z = solve(delta)
        tau = z[:m]
        if not np.all(tau > 0.05 * Q) or abs(np.max(tau) / (K * Q) - 1) > 0.5:
            continue
        G = G0 + sum(zk * e for zk, e in zip(z[m:], E))
        break
    A, b, gg, rho, p, R = hang_platform(rng, Ball, Uall, G)
    robot = Robot(A, b, gg, Q, d, rho, name=f"large_forces_m{m}_K{K:g}")
    return robot, p, R, tau


def root_of_the_solved_system(robot, cables, p, R, tau, dps: int = 60):
    """The root, in world coordinates (p, R, tau), of the normalized DGP system that the homotopy solves (its
    parameters are rounded to doubles) nearest the constructed equilibrium: 60-digit Newton from it; None when
    Newton does not converge (updates below 1e-40).  With condition numbers up to ~1e11 this root differs from the
    constructed one by up to ~1e-5 (relative) in the tensions: the rounding of the robot's data, not an error of the
    solver."""
    import mpmath

    import cdpr_algebra.dgp.solve as S
    from cdpr_algebra.model.taut_equations import decode, encode, taut_family

    m = len(cables)
    rho = robot.lengths
    target, c, L, Rw, cb = normalized_problem(robot, rho, cables)
    x0 = normalized_coordinates(encode(p, R, tau / rho[list(cables)])[None], m, c, L, Rw, cb, robot.load)[0]
    F, J, _ = taut_family(m).mp_functions()
    with mpmath.workdps(dps):
        pt = [mpmath.mpc(complex(v)) for v in target]
        x = mpmath.matrix([mpmath.mpc(complex(v)) for v in x0])
        for _ in range(40):
            d = mpmath.lu_solve(J(list(x), pt), -F(list(x), pt))
            x = x + d
            if mpmath.norm(d) < mpmath.mpf(10) ** -40:
                X = np.array([[complex(v) for v in x]])
                pw, Rw_, lam = decode(world_coordinates(X, m, c, L, Rw, cb, robot.load), m)
                return pw[0].real, Rw_[0].real, lam[0].real * rho[list(cables)]
    return None


def root_of_the_robot_system(robot, cables, p, R, tau, dps: int = 60):
    """The root, in world coordinates (p, R, tau), of the robot's own DGP system (its data as the doubles of the
    robot: the system that the certificates prove roots of) nearest the constructed equilibrium: 60-digit Newton from
    it; None when Newton does not converge (updates below 1e-40).  It differs from the constructed equilibrium (whose
    lengths were rounded to doubles) and from :func:`root_of_the_solved_system` (whose parameters were normalized and
    rounded) by up to ~1e-5 (relative) in the tensions at condition numbers ~1e11."""
    import mpmath

    from cdpr_algebra.model.taut_equations import decode, encode, taut_family

    m = len(cables)
    idx = list(cables)
    rho = robot.lengths
    mp = mpmath.mpf
    with mpmath.workdps(dps):
        params = ([mp(float(v)) for v in robot.base[idx].ravel()] + [mp(float(rho[i])) ** 2 for i in idx]
                  + [mp(float(v)) for v in robot.platform[idx].ravel()] + [mp(float(v)) for v in robot.com]
                  + [mp(float(robot.load)) * mp(float(v)) for v in robot.load_direction])
        x0 = encode(p, R, tau / rho[idx])
        F, J, _ = taut_family(m).mp_functions()
        x = mpmath.matrix([mpmath.mpc(complex(v)) for v in x0])
        for _ in range(40):
            d = mpmath.lu_solve(J(list(x), params), -F(list(x), params))
            x = x + d
            if mpmath.norm(d) < mpmath.mpf(10) ** -40:
                pw, Rw, lam = decode(np.array([[complex(v) for v in x]]), m)
                return pw[0].real, Rw[0].real, lam[0].real * rho[idx]
    return None


def matches(s, p, R, tau, size) -> bool:
    """The DGP solution s is the equilibrium (p, R, tau): pose within 1e-6 (of the robot's size), tensions 1e-6
    relative."""
    return (np.max(np.abs(s.position - p)) <= 1e-6 * size and np.max(np.abs(s.rotation - R)) <= 1e-6
            and np.allclose(s.tensions, tau, rtol=1e-6))


def equilibrium_hits(sols, robot, cables, p, R, tau) -> tuple:
    """(the DGP solutions ``sols`` of the 0-based taut set ``cables`` that are the equilibrium (p, R, tau) -- as
    constructed, as the root of the system the homotopy solved (:func:`root_of_the_solved_system`: with condition
    numbers ~1e13 the two differ by ~1e-3) or as the root of the robot's own system -- by :func:`matches`; the root of
    the solved system, None when 60-digit Newton does not reach it)."""
    solved = root_of_the_solved_system(robot, cables, p, R, tau)
    roots = [solved, root_of_the_robot_system(robot, cables, p, R, tau)]
    want = [(p, R, tau)] + [r for r in roots if r is not None]
    return [s for s in sols if any(matches(s, *w, robot.size) for w in want)], solved
