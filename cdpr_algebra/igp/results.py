"""Immutable result records of the IGP solvers, each with ``to_dict()`` for JSON."""

from __future__ import annotations

from dataclasses import dataclass, field, replace

import numpy as np

from cdpr_algebra.report.jsonable import jsonable as _jsonable

from cdpr_algebra.model.pose import angles_from_matrix, euler_parameters_from_matrix
from cdpr_algebra.model.stability import stability_classes
from cdpr_algebra.model.statics import equilibrium_tensions


@dataclass(frozen=True)
class IGPSolution:
    """One equilibrium configuration of a 3-cable robot (seed 004 Tables 1-4 row).

    ``position`` is the platform-frame origin, ``com_position`` is G. For a complex (non-real) solution the
    arrays are complex, ``real`` is False, and ``hessian``/``stable`` are None (definiteness is undefined).
    ``residual`` is the relative residual of force and moment balance at the reported pose.

    ``hessian`` (and ``stable``) is the floating-point class of the reduced Hessian, an estimate; the class the
    interval certificate proves is ``hessian_proven`` (None when not proven), and ``hessian_label`` is what the
    tables and the JSON ``"hessian"`` show: the proven class or ``'undecided'``.
    """

    position: np.ndarray
    com_position: np.ndarray
    rotation: np.ndarray
    euler_parameters: np.ndarray  # (e0, e1, e2, e3) as found (e0 = 1: Rodrigues, e0 = 0: half-turn)
    lengths: np.ndarray
    tensions: np.ndarray
    hessian: str | None
    real: bool
    residual: float
    tension_tolerance: float = 0.0
    certified: bool | None = None  # interval certificate (certificates/equilibria.py); None for complex solutions / not run
    certificate: object | None = None  # certify.Certificate

    @property
    def angles(self) -> np.ndarray | None:
        return angles_from_matrix(self.rotation.real) if self.real else None

    @property
    def admissible(self) -> bool:
        """Real, with every tension >= 0 (within ``tension_tolerance``)."""
        return bool(self.real and np.all(np.real(self.tensions) >= -self.tension_tolerance))

    @property
    def stable(self) -> bool | None:
        """Stable by the floating-point class (an estimate; see :attr:`stable_proven`)."""
        return None if self.hessian is None else self.hessian == ">"

    @property
    def hessian_proven(self) -> str | None:
        """The class of H_r proven by the interval certificate ('>', '<' or '<>'), or None."""
        c = self.certificate
        if c is None or getattr(c, "hessian", None) != "proven" or not getattr(c, "hessian_class", None):
            return None
        return c.hessian_class

    @property
    def hessian_label(self) -> str | None:
        """The proven class, 'undecided' for a real solution without one, None for a complex solution."""
        if not self.real:
            return None
        return self.hessian_proven or "undecided"

    @property
    def stable_proven(self) -> bool | None:
        """True / False when the certificate proves the class, None when it is undecided."""
        cls = self.hessian_proven
        return None if cls is None else cls == ">"

    def to_dict(self) -> dict:
        return {
            "position": _jsonable(self.position),
            "com_position": _jsonable(self.com_position),
            "rotation": _jsonable(self.rotation),
            "angles": None if self.angles is None else _jsonable(self.angles),
            "euler_parameters": _jsonable(self.euler_parameters),
            "lengths": _jsonable(self.lengths),
            "lengths_norm": "euclidean" if self.real else "hermitian: sqrt(s^H s), s = B - A (seed 004 Table 4)",
            "tensions": _jsonable(self.tensions),
            "admissible": self.admissible,
            "hessian": self.hessian_label,
            "hessian_float": self.hessian,
            "stable": self.stable_proven,
            "stable_float": self.stable,
            "real": self.real,
            "residual": self.residual,
            "certified": self.certified,
            "certificate": None if self.certificate is None else self.certificate.to_dict(),
        }


def make_solution(robot, com_position, rotation, euler_parameters=None, real_tol: float = 1e-9) -> IGPSolution:
    """Complete one IGP root (G and R known) with lengths, tensions, residual and H_r class (see make_solutions)."""
    eps = None if euler_parameters is None else [euler_parameters]
    return make_solutions(robot, [com_position], [rotation], eps, real_tol)[0]


def at_polished_roots(robot, solutions) -> list:
    """The solutions whose certificate proved the root polished at higher precision
    (``certificate.extra['polished_root']``: (u, v, w, lam) with assigned position, (p, lam) with assigned
    orientation; :mod:`cdpr_algebra.certificates.equilibria`) rebuilt at that root (lengths and tensions from its
    pose), the Euler parameters kept in their chart (the component equal to 1 stays 1)."""
    out = []
    for s in solutions:
        c = s.certificate
        if c is None or "polished_root" not in c.extra:
            out.append(s)
            continue
        y = np.asarray(c.extra["polished_root"], dtype=float)
        if c.problem == "igp_position":
            R, G = np.column_stack([y[0:3], y[3:6], y[6:9]]), np.real(s.com_position)
            e = euler_parameters_from_matrix(R)
            e = e / e[int(np.argmax(np.abs(s.euler_parameters) == 1))]  # the component the chart sets to 1
        else:
            R, e = np.real(s.rotation), s.euler_parameters
            G = y[0:3] + R @ robot.com
        out.append(replace(make_solutions(robot, [G], [R], [e])[0], certified=s.certified, certificate=c))
    return out


def make_solutions(robot, com_positions, rotations, euler_parameters=None, real_tol: float = 1e-9) -> list:
    """Complete IGP roots (G_k and R_k known) with lengths, tensions, residual and H_r class, all at once.

    Complex roots are kept complex (``real`` False, no H_r class) unless their imaginary parts are negligible.
    """
    Gs = np.asarray(com_positions)
    Rs = np.asarray(rotations)
    if len(Gs) == 0:
        return []
    g_im = np.abs(np.imag(Gs)).max(axis=-1) <= real_tol * np.maximum(1.0, np.abs(Gs).max(axis=-1))
    r_im = np.abs(np.imag(Rs)).max(axis=(-1, -2)) <= real_tol
    is_real = g_im & r_im
    L = robot.size
    local = robot.platform - robot.com
    out = [None] * len(Gs)
    for mask, dtype in ((is_real, float), (~is_real, complex)):
        idx = np.flatnonzero(mask)
        if len(idx) == 0:
            continue
        G = (np.real(Gs[idx]) if dtype is float else Gs[idx]).astype(dtype)
        R = (np.real(Rs[idx]) if dtype is float else Rs[idx]).astype(dtype)
        B = G[:, None, :] + np.einsum("kij,nj->kni", R, local)
        eq = equilibrium_tensions(robot.base, B, G, robot.load, robot.load_direction, length_scale=L)
        classes = [None] * len(idx)
        if dtype is float:
            # a cable of length 0 (B_i = A_i, e.g. a spurious common root of the IGP quartics) has no line and
            # no tau_i / rho_i: no H_r class there (hessian None; such roots seen so far fail the balance test)
            ok = np.flatnonzero(np.all(eq.lengths > 0, axis=-1))
            if len(ok) == len(idx):
                classes = stability_classes(robot.base, B, G, eq.tensions, eq.lengths, robot.load, L)
            elif len(ok):
                got = stability_classes(robot.base, B[ok], G[ok], eq.tensions[ok], eq.lengths[ok], robot.load, L)
                for j, c in zip(ok, got):
                    classes[j] = c
        residual = np.atleast_1d(eq.residual)
        for j, k in enumerate(idx):
            e = euler_parameters[k] if euler_parameters is not None else euler_parameters_from_matrix(np.real(R[j]))
            out[k] = IGPSolution(
                position=G[j] - R[j] @ robot.com,
                com_position=G[j],
                rotation=R[j],
                euler_parameters=np.asarray(e),
                lengths=eq.lengths[j],
                tensions=eq.tensions[j],
                hessian=classes[j],
                real=dtype is float,
                residual=float(residual[j]),
                tension_tolerance=1e-9 * robot.load,
            )
    return out


@dataclass(frozen=True)
class SolutionSet:
    """A positive-dimensional or empty solution set of the IGP with assigned orientation (seed 004 App. A).

    ``kind`` is one of 'vertical_line', 'cylinder_curve', 'planar_conic', 'crane', 'empty' (proven), or 'undecided'
    (a degenerate case none of these fits: not solved); ``description``
    says it in words; ``data`` holds its parameters (e.g. the (x, y) of a vertical line of G, the conic's
    coefficients), all JSON-ready.
    """

    kind: str
    description: str
    data: dict = field(default_factory=dict)

    def to_dict(self) -> dict:
        return {"kind": self.kind, "description": self.description, **{k: _jsonable(v) for k, v in self.data.items()}}


@dataclass(frozen=True)
class IGPResult:
    """All solutions of one IGP call; ``solution_set`` is set when the answer is not a finite point set."""

    problem: str  # 'orientation' or 'position'
    solutions: tuple
    solution_set: SolutionSet | None = None
    seconds: float = 0.0
    message: str = ""
    generic_count: int | None = None  # isolated solutions of a generic instance (24 with assigned position)
    found: int | None = None  # distinct solutions found, complex included (also where only the real are returned)

    @property
    def real_solutions(self) -> tuple:
        return tuple(s for s in self.solutions if s.real)

    @property
    def status(self) -> str:
        """'solution set' (no isolated solution: ``solution_set`` describes the continuum or says it is empty),
        'undecided' (a degenerate case not solved: ``solution_set.kind`` 'undecided'),
        'incomplete' (fewer solutions found than ``generic_count``: the others lost to rounding, or at infinity for
        this instance -- not decided), 'complete' (every real solution certified), or 'uncertified' (some real
        solution without a certificate)."""
        if self.solution_set is not None:
            return "undecided" if self.solution_set.kind == "undecided" else "solution set"
        if self.generic_count is not None and self.found is not None and self.found < self.generic_count:
            return "incomplete"
        return "complete" if all(s.certified for s in self.real_solutions) else "uncertified"

    def to_dict(self, include_complex: bool = False) -> dict:
        sols = self.solutions if include_complex else self.real_solutions
        return {
            "status": self.status,
            "problem": self.problem,
            "solutions": [s.to_dict() for s in sols],
            "count": {"total": len(self.solutions), "real": len(self.real_solutions), "found": self.found,
                      "generic": self.generic_count,
                      "admissible": sum(s.admissible for s in self.solutions),
                      "stable": sum(bool(s.stable_proven) and s.admissible for s in self.solutions),
                      "stable_float": sum(bool(s.stable) and s.admissible for s in self.solutions)},
            "solution_set": None if self.solution_set is None else self.solution_set.to_dict(),
            "seconds": self.seconds,
            "message": self.message,
        }
