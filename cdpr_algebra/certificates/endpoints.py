"""Krawczyk boxes of the DGP's complex endpoints (issue 15, item 4): every root a taut set's homotopy ends on, proven
unique in its box, the boxes of one taut set compared for disjointness (:func:`certify_endpoints`).

Double-precision interval arithmetic first, compiled over all the roots of one m (:func:`_compiled_krawczyk`);
the roots it does not prove are tried again in complex ball arithmetic (:func:`_retry_in_balls`).  A taut set whose
robot is read in decimal (its platform anchors collinear only in the decimals that print them,
:func:`cdpr_algebra.model.rod_equations.exact_rational`) has its roots proven in ball arithmetic only, with those
decimals enclosed: the doubles are another robot.
"""

from __future__ import annotations

import numpy as np
from flint import arb

from cdpr_algebra.model.rod_equations import BINARY
from cdpr_algebra.model.taut_equations import to_cable_frame

from .equilibria import FLINT, _parameters, _robot_data, _scales, taut_system

__all__ = ["certify_endpoints", "BALL_RETRY_MAX", "BALL_PREC", "BALL_PRECS", "BALL_MAX_MOVE"]


def certify_endpoints(robot, lengths, groups, balls=None, readings=None) -> list:
    """Krawczyk boxes of complex DGP roots (issue 15, item 4), for several taut sets with the same m >= 2 at once.

    ``groups``: list of (0-based taut ``cables``, Z (N, 12 + m) complex roots of their taut system in world
    coordinates (p, u, v, w, lam)); ``lengths``: all n (None: the robot's).  One certification over every root of
    every group (each row with the constants of its own taut set), the Krawczyk rounds compiled
    (:func:`_compiled_krawczyk`, without the GIL).  Returns, per group,
    (:class:`cdpr_algebra.intervals.complex_krawczyk.ComplexRootBoxes`, overlapping (N,) bool): each root proven unique in its box of
    C^(12+m) (real or non-real proven where decidable), and the proven boxes meeting another proven box of the
    same group (those roots are not proven distinct).  The roots are certified in the cable frame
    (:attr:`Robot.cable_frame`: p' = p + R cb - c, the boxes are of those coordinates; distinctness and reality do not
    depend on the frame).  Constants: A_i - c, b'_i - cb, g' - cb, Q d and rho_i^2 enclosed.  ``balls`` (one bool per
    group, default all True): retry the roots of that group that double precision could not certify in ball
    arithmetic.  ``readings`` (one per group, default all BINARY): DECIMAL proves that group's roots as roots of the
    robot read in decimal (b'_i and g' the decimals that print them, enclosed), in ball arithmetic only, whatever
    ``balls`` says (module doc)."""
    from cdpr_algebra.intervals.complex_krawczyk import ComplexRootBoxes, certify_complex_roots
    from cdpr_algebra.intervals.arithmetic import Interval

    groups = [(list(map(int, c)), np.asarray(Z, dtype=complex).reshape(len(Z), 12 + len(c))) for c, Z in groups]
    if not groups:
        return []
    m = len(groups[0][0])
    if any(len(c) != m for c, _ in groups) or m < 2:
        raise ValueError("certify_endpoints: every group needs the same number m >= 2 of taut cables")
    rho = np.asarray(robot.lengths if lengths is None else lengths, dtype=float)
    rows = np.concatenate([np.repeat(np.asarray(c)[None], len(Z), axis=0) for c, Z in groups]).reshape(-1, m)
    frame = robot.cable_frame
    Z = to_cable_frame(np.concatenate([Z for _, Z in groups]).reshape(-1, 12 + m), frame)
    f_float = [robot.load * float(c) for c in robot.load_direction]
    f_iv = [Interval.point(robot.load) * float(c) for c in robot.load_direction]
    constants = {iv: _frame_constants(robot, rows, frame, iv) for iv in (False, True)}

    def system(f, square, iv):
        """The taut system of the rows r with the constants of their taut sets (enclosed with ``iv``; f and rho^2
        as ``square`` makes them)."""
        A_all, b_all, g = constants[iv]

        def evaluate(x, r, jac):
            A = [[a[r] for a in Ai] for Ai in A_all]
            b = [[c[r] for c in bi] for bi in b_all]
            return taut_system(x, A, b, g, f, [square(rho[rows[r][:, i]]) for i in range(m)], jacobian=jac)

        return evaluate

    rigorous = system(f_iv, lambda v: Interval.point(v).sqr(), True)  # rho^2 enclosed
    approximate = system(f_float, lambda v: v ** 2, False)

    scale = _scales(robot, m, range(12 + m), robot.cable_scale)
    boxes = certify_complex_roots(rigorous, approximate, Z, scale,
                                  kernel=_compiled_krawczyk(rho, rows, f_iv, constants[True]))
    readings = [BINARY] * len(groups) if readings is None else list(readings)
    balls = [True] * len(groups) if balls is None else list(balls)
    balls = [bool(f) or r != BINARY for f, r in zip(balls, readings)]
    retry = np.concatenate([np.full(len(Zg), bool(f)) for (_, Zg), f in zip(groups, balls)]).astype(bool)
    group = np.concatenate([np.full(len(Zg), g) for g, (_, Zg) in enumerate(groups)])
    reading = np.concatenate([np.full(len(Zg), r, dtype=object) for (_, Zg), r in zip(groups, readings)])
    if np.any(reading != BINARY):  # the double-precision proofs are of the doubles' robot: not kept
        other = reading != BINARY
        boxes = ComplexRootBoxes(boxes.proven & ~other, boxes.lo, boxes.hi, boxes.real & ~other,
                                 boxes.nonreal & ~other, boxes.center,
                                 tuple("the robot read in decimal: not proven in ball arithmetic" if o else r
                                       for o, r in zip(other, boxes.reason)))
    boxes = _retry_in_balls(robot, rho, rows, Z, scale, boxes, retry, frame, group, reading)
    out, k0 = [], 0
    for _, Zg in groups:
        sl = slice(k0, k0 + len(Zg))
        k0 += len(Zg)
        bg = ComplexRootBoxes(boxes.proven[sl], boxes.lo[sl], boxes.hi[sl], boxes.real[sl], boxes.nonreal[sl],
                              boxes.center[sl], boxes.reason[sl])
        out.append((bg, bg.meeting()))
    return out


def _frame_constants(robot, rows, frame, interval: bool):
    """(A, b, g) of the roots' taut sets (``rows``: N x m cable indices) in the frame (c, cb): A_i - c (m x 3 arrays
    over the roots), b'_i - cb, g' - cb; enclosed (:class:`cdpr_algebra.intervals.arithmetic.Interval`) with
    ``interval``, else rounded."""
    from cdpr_algebra.intervals.arithmetic import Interval

    c, cb = frame
    num = Interval.point if interval else (lambda v: v)

    def shifted(values, o):
        return num(values) - num(float(o))

    m = rows.shape[1]
    A = [[shifted(robot.base[rows[:, i], k], c[k]) for k in range(3)] for i in range(m)]
    b = [[shifted(robot.platform[rows[:, i], k], cb[k]) for k in range(3)] for i in range(m)]
    g = [shifted(robot.com[k], cb[k]) for k in range(3)]
    return A, b, g


def _compiled_krawczyk(rho, rows, f_iv, constants):
    """The Krawczyk operator of the taut systems of the roots (``rows``: their taut sets, N x m) over boxes, compiled
    (:func:`cdpr_algebra.intervals.complex_kernels.krawczyk_kernel` on the generated interval evaluator
    :mod:`cdpr_algebra.generated.taut_equations_intervals`), with the constants of :func:`certify_endpoints`
    (``constants``: the enclosed (A, b, g) of :func:`_frame_constants`; rho_i^2 and Q d enclosed).  Same operator
    as the interval objects, without the GIL."""
    from cdpr_algebra.generated.taut_equations_intervals import taut_equations, taut_residual
    from cdpr_algebra.homotopy.compiled import function_address
    from cdpr_algebra.intervals.arithmetic import Interval
    from cdpr_algebra.intervals.complex_kernels import EVALUATOR_TYPE, krawczyk_kernel

    # the evaluators by their addresses, looked up once (as the tracker's: homotopy.compiled.function_address)
    ev, res = function_address(taut_equations, EVALUATOR_TYPE), function_address(taut_residual, EVALUATOR_TYPE)
    m = rows.shape[1]
    A, b, g = constants
    rho2 = [Interval.point(rho[rows[:, i]]).sqr() for i in range(m)]
    params = _parameters(A, b, g, f_iv, rho2)
    P = np.zeros((len(rows), len(params), 4))  # (lo, hi, 0, 0): real intervals
    for k, v in enumerate(params):
        P[:, k, 0], P[:, k, 1] = (v.lo, v.hi) if isinstance(v, Interval) else (v, v)

    def kernel(part, y, r):
        y = np.ascontiguousarray(y, dtype=float)
        K_lo, K_hi = np.empty_like(y), np.empty_like(y)
        ok = np.zeros(len(y), dtype=bool)
        krawczyk_kernel(ev, res, y, np.ascontiguousarray(r, dtype=float), np.ascontiguousarray(P[part]), K_lo, K_hi,
                        ok)
        return Interval(K_lo, K_hi), ok

    return kernel


BALL_RETRY_MAX = 400  # roots per group (taut set) retried in ball arithmetic (milliseconds each)
BALL_PREC = 256  # bits: the constants, and the last attempt of the ball retry
BALL_PRECS = (128, BALL_PREC)  # the ball retry's attempts (the first suffices for condition numbers up to ~1e25)
# How far (relative to the scale) the ball retry's Newton steps may move an endpoint before its box is built.  The
# homotopy solves the robot's equations with normalized parameters rounded to doubles; a root of condition number
# kappa moves by ~kappa x 1e-16 between the two systems (measured: 1e-6 .. 1e-5 in the tensions of
# tests/large_forces.py's robots at kappa ~ 1e11), beyond the box width limit.  The proof is of a root of the robot's
# own equations near the endpoint; what it serves (distinct proven roots counted against the generic count, boxes
# pairwise disjoint) does not depend on the size of the move.
BALL_MAX_MOVE = 1e-3


def _retry_in_balls(robot, rho, rows, Z, scale, boxes, retry, frame=None, group=None, reading=None):
    """The roots that double-precision interval arithmetic could not certify, tested again in complex ball
    arithmetic at ``BALL_PRECS`` bits (128, then 256 where 128 does not prove it)
    (:func:`cdpr_algebra.intervals.complex_krawczyk.certify_complex_root_balls`; only rows with ``retry``, at most
    ``BALL_RETRY_MAX`` of them per ``group`` (one id per row, None: one group), the others keep their reason; a cap per
    group, not per call, so that a subproblem's certificate does not depend on the subproblems certified with it;
    ``frame``: Z's frame, see :func:`certify_endpoints`, None for world coordinates; ``reading``: one per row, the
    robot's reading of :func:`cdpr_algebra.certificates.equilibria._robot_data`, default all BINARY)."""
    from cdpr_algebra.intervals.complex_krawczyk import ComplexRootBoxes

    group = np.zeros(len(Z), dtype=int) if group is None else np.asarray(group)
    todo, capped, seen = [], [], {}
    for k in np.flatnonzero(~boxes.proven & retry):
        if np.all(np.isfinite(Z[k])):
            seen[group[k]] = seen.get(group[k], 0) + 1
            (todo if seen[group[k]] <= BALL_RETRY_MAX else capped).append(k)
    proven, lo, hi = boxes.proven.copy(), boxes.lo.copy(), boxes.hi.copy()
    real, nonreal, reason = boxes.real.copy(), boxes.nonreal.copy(), list(boxes.reason)
    for k in np.flatnonzero(~boxes.proven & ~retry):
        reason[k] += " (not retried in ball arithmetic: its subproblem has failed paths)"
    for k in capped:
        reason[k] += f" (not retried in ball arithmetic: more than {BALL_RETRY_MAX} such roots in its taut set)"
    if todo:
        with FLINT:
            _ball_proofs(robot, rho, rows, Z, scale, todo, proven, lo, hi, real, nonreal, reason, frame, reading)
    return ComplexRootBoxes(proven, lo, hi, real, nonreal, boxes.center, tuple(reason))


def _ball_proofs(robot, rho, rows, Z, scale, todo, proven, lo, hi, real, nonreal, reason, frame=None, reading=None):
    """The ball-arithmetic Krawczyk test of the roots ``todo`` (see :func:`_retry_in_balls`; updates the arrays)."""
    from flint import ctx

    from cdpr_algebra.intervals.complex_krawczyk import certify_complex_root_balls

    with ctx.workprec(BALL_PREC):  # the constants too: rho_i^2 of a double is exact at BALL_PREC bits, not at 53
        f = [arb(robot.load) * arb(float(c)) for c in robot.load_direction]
        for k in todo:
            taut = [int(c) for c in rows[k]]
            A, b, g, _ = _robot_data(robot, taut, arb, frame=frame,  # exact at BALL_PREC (decimals: enclosed)
                                     reading=BINARY if reading is None else reading[k])
            rho2 = [arb(float(rho[i])) * arb(float(rho[i])) for i in taut]

            def system(x, jac, A=A, b=b, rho2=rho2):
                return taut_system(x, A, b, g, f, rho2, jacobian=jac)

            for prec in BALL_PRECS:  # the constants stay exact (BALL_PREC); arithmetic at prec rounds outward
                ok, lk, hk, rk, nk, why = certify_complex_root_balls(system, Z[k], scale, prec=prec,
                                                                     max_move=BALL_MAX_MOVE)
                if ok:
                    break
            if ok:
                proven[k], lo[k], hi[k], real[k], nonreal[k], reason[k] = True, lk, hk, rk, nk, ""
            else:
                reason[k] = why
