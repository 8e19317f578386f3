"""Taut sets whose platform anchors and centre of mass lie on one line, solved as a rod (issue 15).

With the taut anchors B_i and the centre of mass G exactly collinear on the platform (a flat plate with G at its
centre and cables on a diagonal, a beam), every equilibrium of the taut set turns freely about that line: the 6-DOF
system's solutions are circles, and its homotopy's endpoints are not isolated roots to certify or count
(:mod:`.positive_dimensional`). The line itself is a 5-DOF body with isolated equilibria: the rod system of
:mod:`cdpr_algebra.model.rod_equations`, one root per family. Here it is solved as every taut set is: a parameter
homotopy from a stored generic solution set (``cdpr_algebra/data/rod_generic_m{m}.json``, m = 2 .. 5, found by
monodromy without a target count, with a trace test and PHCpack's count on another instance recorded,
``derivations/solve_generic_rod.py``) to the robot's normalized problem, every path with one outcome; the regular
endpoints are certified in interval arithmetic (:func:`cdpr_algebra.certificates.rods.certify_rod_roots`: unique in
pairwise disjoint boxes, real or not proven), and the subproblem is complete when no path failed, the outcomes add
up to the generic count and every regular endpoint is certified: then the families are all known. Each real family
with positive tensions is rebuilt as a 6-DOF pose turning about the line, with the turning angles at which the other
cables stay slack (:func:`.positive_dimensional.turning_member`).

Collinearity is decided in exact rational arithmetic (:func:`cdpr_algebra.certificates.families.collinear_exactly`)
on the robot's doubles or, failing that, on the decimals that print them (Python's repr, the numbers of a robot
file): data collinear on paper but not once rounded (a centre of mass at 0.4 of a diagonal) are solved as the robot
read in decimal -- its taut anchors and centre of mass as those decimals, exactly collinear -- and say so
(``Family.reading``). The doubles themselves are off the line by rounding; their 6-DOF system has, near each family,
isolated roots that are artefacts of that rounding, ill-conditioned past what double precision resolves (measured,
twenty-sixth session: the flat plate with G at 0.4 of its diagonal, 21 of 24 paths singular, 3 regular endpoints
refused by the certificates, no real family found, the subproblem incomplete). m = 1 is analytic
(:mod:`.one_cable`); m >= 6 anchors on a line are over-determined by their lengths and stay with the 6-DOF homotopy.
"""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import numpy as np

from cdpr_algebra.generated.rod_equations import rod_equations
from cdpr_algebra.homotopy.results import FAILURES, outcome_counts
from cdpr_algebra.model.rod_equations import BINARY, DECIMAL, ROD_M, line_coordinates, rod_family, rod_parameters
from .positive_dimensional import ROD, Family, turning_member, world_residual
from .taut_system import LazyFamilySystem, QuadraticInParameters

__all__ = ["FastRodSystem", "fast_rod_family", "rod_geometry", "rod_generic_path", "solve_rod_taut_set"]

REAL_TOL = 1e-8  # imaginary parts (relative) under which an uncertified root counts as real
_GENERIC: dict = {}
_FAST: dict = {}


def rod_generic_path(m: int) -> Path:
    return Path(__file__).resolve().parent.parent / "data" / f"rod_generic_m{m}.json"


class FastRodSystem(QuadraticInParameters, LazyFamilySystem):
    """:func:`cdpr_algebra.model.rod_equations.rod_family` (m) evaluated by its generated evaluator
    (:mod:`cdpr_algebra.generated.rod_equations`) on numpy columns, vectorized over the points (every equation has
    degree <= 2 in the parameters A, rho^2, s, D.D, Q d: the directional derivative by central difference); the sympy
    family (name, hash, mpmath evaluators: the engine's projective and arbitrary-precision retries) is built only
    when something asks for it."""

    family_builder = staticmethod(rod_family)
    compiled_kernels = None  # numpy tracking, vectorized over the paths (answered here: asking builds the family)
    compiled_residual_dd = None
    chart_kernels = None

    def __init__(self, m: int):
        super().__init__(m)
        self.n = self.neq = m + 7  # G, u, lam, mu
        self.m = 5 * m + 4  # A_i, rho_i^2, s_i, D.D, Q d

    @property
    def degrees(self) -> tuple:
        return (2,) * self.neq

    def _eval(self, x, p, jac: bool):
        x = np.asarray(x, dtype=complex)
        x = x[None, :] if x.ndim == 1 else x
        N = len(x)
        P = np.asarray(p, dtype=complex)
        # parameters as rows (m, N), a fresh copy: the evaluator accumulates sums in place from parameter entries
        P = np.array(np.broadcast_to(P.T if P.ndim == 2 else P[:, None], (self.m, N)))
        F = np.zeros((self.neq, N), dtype=complex)
        J = np.zeros((self.neq, self.n, N), dtype=complex) if jac else None
        rod_equations(list(x.T), P, F, J, jac)
        return F.T, (np.moveaxis(J, 2, 0) if jac else None)

    def evaluate(self, x, p=None):
        return self._eval(x, p, False)[0]

    def evaluate_and_jacobian(self, x, p=None):
        return self._eval(x, p, True)

    def evaluate_all(self, x, p=None):
        return self.family.evaluate_all(x, p)


def fast_rod_family(m: int) -> FastRodSystem:
    if m not in _FAST:
        _FAST[m] = FastRodSystem(m)
    return _FAST[m]


def _generic(m: int):
    """(parameters, solutions) of the stored generic rod set of ``m``, checked to solve the generated equations (the
    stored hash against the sympy family: tests/test_dgp_rod.py)."""
    if m not in _GENERIC:
        from cdpr_algebra.homotopy.monodromy import load_instance

        p, X, _ = load_instance(rod_generic_path(m), fast_rod_family(m), check_hash=False)
        _GENERIC[m] = (p, X)
    return _GENERIC[m]


def rod_geometry(robot, cables):
    """(s, D.D, reading) with s, D.D fractions (:func:`cdpr_algebra.model.rod_equations.line_coordinates`) when the
    0-based taut ``cables`` (2 .. 5 of them) have platform anchors collinear with the centre of mass, exactly in the
    robot's doubles (reading BINARY) or else in the decimals that print them (DECIMAL), and a stored generic rod set;
    else None."""
    from cdpr_algebra.certificates.families import collinear_exactly

    idx = list(cables)
    if len(idx) not in ROD_M or not rod_generic_path(len(idx)).exists():
        return None
    points = [robot.platform[i] for i in idx] + [robot.com]
    for reading in (BINARY, DECIMAL):
        if collinear_exactly(points, reading):
            line = line_coordinates(robot.platform[idx], robot.com, reading)
            return None if line is None else (*line[1:], reading)
    return None


def _normalized(robot, rho, idx, s, DD):
    """(target parameters, c, L, Rw): the rod problem in the frame of :func:`.normalization.normalized_problem`
    (x' = Rw (x - c) / L, load 1 along -z); u' = Rw u / L, lam' = L lam / Q, mu' = L mu / Q."""
    from .normalization import normalized_problem

    _, c, L, Rw, _ = normalized_problem(robot, rho, idx)
    return (rod_parameters((robot.base[idx] - c) @ Rw.T / L, rho[idx] / L, s, float(DD) / L ** 2, [0.0, 0.0, -1.0]),
            c, L, Rw)


def _world(X, m, c, L, Rw, Q):
    """Roots of the normalized rod problem -> (G, u, lam, mu) of the robot."""
    return np.hstack([c + L * (X[:, 0:3] @ Rw), L * (X[:, 3:6] @ Rw), Q * X[:, 6:6 + m] / L, Q * X[:, 6 + m:] / L])


def _track(m, target, seed, gamma, options):
    from cdpr_algebra.homotopy.endgame import SolveOptions
    from cdpr_algebra.homotopy.solve import solve_parameter_homotopy

    p0, X0 = _generic(m)
    res = solve_parameter_homotopy(fast_rod_family(m), p0, X0, target, seed=seed, gamma=gamma,
                                   options=options or SolveOptions(retry_mpmath=False))
    return res, sum(1 for p in res.track.paths if p.status in FAILURES)


def solve_rod_taut_set(robot, rho, cables, geometry, seed: int = 0, options=None, tension_tol: float = 0.0):
    """The DGPSubproblem fields of the 0-based taut ``cables`` solved as a rod (module doc): a dict of keyword
    arguments (paths, finite, real, admissible = 0, outcomes, failures, complete, generic_count, certified,
    certified_real, uncertified, family, retried) with ``geometry`` = :func:`rod_geometry`."""
    from cdpr_algebra.certificates.rods import certify_rod_roots

    s, DD, reading = geometry
    idx = list(cables)
    m = len(idx)
    rho = np.asarray(rho, dtype=float)
    target, c, L, Rw = _normalized(robot, rho, idx, s, DD)
    res, failed = _track(m, target, seed, False, options)
    retried = {}
    if failed:  # another route (gamma trick); the run with fewer failed paths is kept (each run is a whole account)
        res2, failed2 = _track(m, target, seed + 7919, True, options)
        if failed2 < failed:
            res, failed = res2, failed2
            retried["gamma route"] = len(res.track.paths)
    paths = res.track.paths
    outcomes = outcome_counts(paths)
    failures = dict(Counter(p.status for p in paths if p.status in FAILURES))
    retried.update(Counter(p.retried for p in paths if p.retried))
    singular = np.array([x.singular for x in res.solutions], dtype=bool)
    W = _world(np.array([x.x for x in res.solutions]).reshape(-1, m + 7), m, c, L, Rw, robot.load)
    Z = W[~singular]  # regular endpoints: certified
    boxes, over = certify_rod_roots(robot, rho, idx, s, DD, Z)
    ok, why = boxes.distinct(over)
    certified = int(ok.sum())
    accounted = failed == 0 and sum(outcomes.values()) == len(_generic(m)[1])
    complete = accounted and certified == len(Z) == outcomes["regular"]
    # the families: every finite root (singular ones too, uncertified) that is real -- proven, or within REAL_TOL
    # where not proven -- with positive tensions
    W[~singular] = np.where(boxes.proven[:, None], boxes.center, Z) if len(Z) else Z
    proven_real = np.zeros(len(W), bool)
    proven_real[~singular] = boxes.real
    unproven = np.ones(len(W), bool)
    unproven[~singular] = ~boxes.proven
    real = proven_real | (unproven & np.all(np.abs(W.imag) <= REAL_TOL * (1 + np.abs(W.real)), axis=1))
    residual = world_residual(robot, rho, idx)
    members, positive = [], 0
    sf = np.array([float(v) for v in s])
    for y in W[real].real:
        G, u, lam = y[0:3], y[3:6], y[6:6 + m]
        tau = lam * rho[idx]
        if np.any(tau <= tension_tol):
            continue
        positive += 1
        member = turning_member(robot, rho, idx, G + sf[:, None] * u, tau, residual, reading)
        if member is not None:
            members.append(member)
    finite = len(W)
    family = Family(len(W), (1,), 0, 0, tuple(f"B{i + 1}" for i in idx) + ("G",), True, False,
                    groups=(1,) * finite, real=positive, members=tuple(members), method=ROD, certified=certified,
                    reading=reading)
    return dict(paths=len(paths), finite=finite, real=int(np.sum(real)), admissible=0, outcomes=outcomes,
                failures=failures, complete=complete, generic_count=len(_generic(m)[1]), certified=certified,
                certified_real=int(np.sum(ok & boxes.real)), uncertified=why, family=family,
                retried=dict(retried))
