"""Taut sets whose equilibria come in continuous families: regular endpoints that the certificates refuse, tested
for lying on a positive-dimensional solution set, and the platform's motion along it described.

Some robots have taut sets whose equations have a curve (or surface) of solutions instead of isolated roots: with
two taut cables whose anchor points B_i, B_j are collinear with the centre of mass G (a flat platform with G at
its centre, cables on a diagonal), the platform turns freely about the line B_i B_j.  The homotopy's paths then end
at points of that set, which Newton's method does not hold (it moves along the set), so the endpoint certificates
refuse them and the subproblem is incomplete.  This module says why: each such endpoint is tested by
:func:`cdpr_algebra.homotopy.local_dimension.local_dimension` on the normalized taut system (a numerical test,
labelled so), and for the first endpoint found on a positive-dimensional set the tangent of the set is read as a
motion of the platform (:func:`_motion`): the anchor points and centre of mass that it leaves fixed, and whether the
tensions change along it (for dimension > 1, along one direction of the set).

Families of turning equilibria (:func:`_turning_members`): when the motion turns the platform about a line through
every taut anchor point with the tensions unchanged, a solution is the same for every turning angle: the taut
anchors' world positions and the tensions are its invariants.  The endpoints are grouped by them (one group per
family; each regular family attracts two paths of a generic parameter homotopy, the two zeros on its circle of the
first-order change of the equations along the path, so groups of two are expected and the sizes are reported).  A
group with real invariants and positive tensions is a real family of equilibria: its poses are rebuilt from the
invariants (R0 takes the platform's anchor line to the world's, then any turn about it), and the turning angles at
which the other cables stay slack are intersected as for one taut cable (:func:`.one_cable.slack_arcs`).  Each
family with a feasible arc is listed with the pose in the middle of its largest arc, the arcs, and the residual of
the taut equations there (its equations, not the test, make it an equilibrium), and that pose's interval
certificate under a gauge that fixes the turning angle (:func:`cdpr_algebra.certificates.families.
certify_turning_equilibrium`: the point, not the arc).  The subproblem stays incomplete: the list of families rests
on the numerical test, and on every family having drawn a path.

Taut sets of 2 .. 5 cables whose anchors and centre of mass are exactly collinear (in the robot's doubles, or in the
decimals that print them) do not come here: the DGP solves them as a rod (:mod:`.rod`, complete and certified), and
builds their listed families with :func:`turning_member`.  What comes here are the other positive-dimensional
sets, and families of data collinear only up to rounding in any reading.
"""

from __future__ import annotations

from collections import Counter
from dataclasses import dataclass, replace

import numpy as np

from cdpr_algebra.homotopy.clusters import duplicate_groups
from cdpr_algebra.homotopy.local_dimension import local_dimension
from cdpr_algebra.model.pose import angles_from_matrix, rotation_taking
from cdpr_algebra.model.rod_equations import BINARY
from cdpr_algebra.model.stability import stability_classes
from cdpr_algebra.model.taut_equations import decode, encode
from cdpr_algebra.report.jsonable import jsonable
from .normalization import normalized_coordinates, normalized_problem, world_coordinates
from .one_cable import middle_pose, slack_arcs
from .taut_system import fast_family

__all__ = ["FIXED_RTOL", "INVARIANT_RTOL", "LOCAL_DIMENSION", "MAX_TESTED", "ROD", "Family", "FamilyMember",
           "families_of_endpoints", "turning_member", "world_residual"]

LOCAL_DIMENSION = "numerical local dimension test"
ROD = "rod system"
MAX_TESTED = 64  # uncertified endpoints tested per taut set (~10 ms each)
FIXED_RTOL = 1e-6  # a point's speed along the tangent, relative to |omega| L, below which it is fixed by the motion
INVARIANT_RTOL = 1e-6  # endpoints whose invariants (taut anchors / L, tensions / Q) agree to this (relative to each
# coordinate, duplicate_groups) are one family


@dataclass(frozen=True)
class FamilyMember:
    """A real family of equilibria turning about the line through the taut anchors: the pose in the middle of its
    largest arc of turning angles at which the other cables stay slack (``position``, ``rotation``), the n
    ``tensions`` (0 on slack cables; the same along the family), the feasible ``arcs`` (radians, relative to that
    pose, turning about ``axis`` (a unit world vector through the first taut anchor) and the relative ``residual``
    of the taut equations at the pose."""

    taut: tuple  # 1-based
    position: np.ndarray
    rotation: np.ndarray
    tensions: np.ndarray
    axis: np.ndarray
    arcs: tuple
    residual: float
    hessian: str  # class of H_r at the pose (floating point; the turn about the axis is a null direction)
    certificate: object = None  # certificates.families.certify_turning_equilibrium of the pose, or None

    @property
    def certified(self) -> bool:
        return bool(self.certificate is not None and self.certificate.certified)

    def to_dict(self) -> dict:
        return {"taut": list(self.taut), "position": jsonable(self.position), "rotation": jsonable(self.rotation),
                "tensions": jsonable(self.tensions), "axis": jsonable(self.axis), "hessian": self.hessian,
                "arcs_degrees": [[float(np.degrees(a)), float(np.degrees(b))] for a, b in self.arcs],
                "residual": self.residual, "certified": self.certified,
                "certificate": None if self.certificate is None else self.certificate.to_dict()}

    def describe(self, fixed=(), method: str = LOCAL_DIMENSION) -> str:
        """One line for the DGP's table: the family, its arcs, and the pose in the middle of the largest; ``method``:
        what says that the taut set's solutions are families."""
        arcs = ", ".join(f"{np.degrees(a):.1f}..{np.degrees(b):.1f}" for a, b in self.arcs)
        through = f"the line through {', '.join(fixed)}" if fixed else "an axis through the taut anchors"
        pose = " ".join(f"{v:.3f}" for v in self.position) + ", angles " + " ".join(
            f"{v:.3f}" for v in angles_from_matrix(self.rotation))
        tau = " ".join(f"{v:.3f}" for v in self.tensions)
        proof = ("that pose certified (interval proof of a gauge-fixed point; the arc is not)" if self.certified
                 else "not certified" + (f": {self.certificate.reason}" if self.certificate is not None else ""))
        return (f"taut {list(self.taut)}: a family of equilibria turning about {through}, the other cables slack "
                f"over turning angles {arcs} deg ({method}); in the middle: position {pose}, "
                f"tensions {tau}, H_r {self.hessian} (residual {self.residual:.1e}); {proof}")


@dataclass(frozen=True)
class Family:
    """The positive-dimensional part of a taut set's solutions as the local dimension test saw it: ``endpoints``
    endpoints (regular ones the certificates refuse, or singular ones) on positive-dimensional sets (of
    ``dimensions``), ``undecided`` endpoints where the test could not tell, ``tested`` endpoints tested; the motion at
    the first one: ``fixed`` the names of the points it leaves fixed ('B1', .., 'G'), ``turns`` (the platform turns,
    not only translates) and ``tensions_change``.  For a taut set solved as a rod (``method`` ROD), one group per
    root of the rod system and ``certified`` those proven distinct."""

    endpoints: int
    dimensions: tuple
    undecided: int
    tested: int
    fixed: tuple
    turns: bool
    tensions_change: bool
    groups: tuple = ()  # endpoints per family of turning equilibria (complex ones too); () when not grouped
    real: int = 0  # of those families, the real ones with positive tensions
    members: tuple = ()  # FamilyMember: the real families with positive tensions and a feasible arc
    method: str = LOCAL_DIMENSION  # or ROD: the families are the roots of the rod system (dgp.rod)
    certified: int | None = None  # ROD: roots of the rod system proven distinct (whole families, real or complex)
    reading: str = BINARY  # ROD: the line's points collinear in the robot's doubles, or "decimal" (dgp.rod)

    def describe(self) -> str:
        if self.method == ROD:
            where = ("exactly, in the robot's binary data" if self.reading == BINARY else
                     "exactly in the decimals that print the robot's data, not in its doubles, off the line by "
                     "rounding: the robot read in decimal is solved")
            return (f"the taut anchors and the centre of mass lie on one line ({where}): "
                    f"every equilibrium turns freely about it; solved as a rod (the line's own equations, dgp.rod): "
                    f"{len(self.groups)} families ({self.certified} proven distinct roots), {self.real} real with "
                    f"positive tensions, {len(self.members)} of them with turning angles at which the other cables "
                    "are slack (listed as families)")
        dims = ", ".join(str(d) for d in self.dimensions)
        text = (f"{self.endpoints} endpoint(s) lie on a positive-dimensional solution set (dimension {dims}, "
                f"numerical local dimension test): continuous families of equilibria, {_motion_words(self)}")
        if not self.groups:
            return text + "; the DGP lists isolated equilibria only, so this taut set's are not listed"
        sizes = ", ".join(f"{k} x {v}" for v, k in sorted(Counter(self.groups).items()))
        return (text + f"; {len(self.groups)} families among the endpoints (endpoints per family: {sizes}), "
                f"{self.real} real with positive tensions, {len(self.members)} of them with turning angles at which "
                "the other cables are slack (listed as families)")

    def to_dict(self) -> dict:
        return {"endpoints": self.endpoints, "dimensions": list(self.dimensions), "undecided": self.undecided,
                "tested": self.tested, "fixed_points": list(self.fixed), "turns": self.turns,
                "tensions_change": self.tensions_change, "test": self.method, "certified": self.certified,
                "reading": self.reading if self.method == ROD else None,
                "families": len(self.groups), "endpoints_per_family": list(self.groups), "real_positive": self.real,
                "members": [f.to_dict() for f in self.members]}


def _motion_words(f: Family) -> str:
    tensions = "the tensions changing" if f.tensions_change else "the tensions unchanged"
    if not f.turns:
        return f"along which the platform translates, {tensions}"
    if len(f.fixed) >= 2:
        return f"along which the platform turns about the line through {', '.join(f.fixed)}, {tensions}"
    if len(f.fixed) == 1:
        return f"along which the platform turns about {f.fixed[0]}, {tensions}"
    return f"along which the platform moves (turning, no anchor point or centre of mass fixed), {tensions}"


def _motion(robot, x, t, m):
    """(names of the points the motion t leaves fixed, turns, tensions change) at the world root x (p, u, v, w,
    lam) with world tangent t: the velocity of a platform point b' is dp + dR b', omega the axial vector of
    dR R^T."""
    p, R, lam = (a[0] for a in decode(x[None], m))
    dp, dR, dlam = (a[0] for a in decode(t[None], m))
    W = dR @ R.T
    W = (W - W.T) / 2
    omega = np.array([W[2, 1], W[0, 2], W[1, 0]])
    L = robot.cable_scale
    speed = max(np.linalg.norm(omega) * L, np.linalg.norm(dp))
    names = [f"B{i + 1}" for i in range(robot.n)] + ["G"]
    points = np.vstack([robot.platform, robot.com])
    fixed = tuple(nm for nm, b in zip(names, points) if np.linalg.norm(dp + dR @ b) <= FIXED_RTOL * speed)
    turns = bool(np.linalg.norm(omega) * L > FIXED_RTOL * speed)
    changes = bool(np.linalg.norm(dlam) > FIXED_RTOL * speed * (np.linalg.norm(lam) / L + 1e-300))
    return fixed, turns, changes


def families_of_endpoints(robot, rho, cables, Z, tension_tol: float = 0.0) -> Family | None:
    """The :class:`Family` of the 0-based taut set ``cables`` from its uncertified regular endpoints ``Z`` (world
    coordinates, rows (p, u, v, w, lam)), at most ``MAX_TESTED`` of them; None when none lies on a
    positive-dimensional set.  ``tension_tol``: the smallest tension counted positive."""
    Z = np.asarray(Z, dtype=complex)
    if not len(Z):
        return None
    m = len(cables)
    target, c, L, Rw, cb = normalized_problem(robot, rho, cables)
    X = normalized_coordinates(Z[:MAX_TESTED], m, c, L, Rw, cb, robot.load)
    fam = fast_family(m)

    def evaluate(x):
        F, J = fam.evaluate_and_jacobian(x[None], target)
        return F[0], J[0]

    on_set, dims, undecided = [], set(), 0
    for x in X:
        r = local_dimension(evaluate, x)
        if r.verdict == "positive_dimensional":
            on_set.append(r)
            dims.add(r.dimension)
        elif r.verdict == "undecided":
            undecided += 1
    if not on_set:
        return None
    first = on_set[0]
    x = world_coordinates(first.point[None], m, c, L, Rw, cb, robot.load)[0]
    # world_coordinates is affine, so its differences map tangents
    t = world_coordinates((first.point + first.tangent[:, 0])[None], m, c, L, Rw, cb, robot.load)[0] - x
    family = Family(len(on_set), tuple(sorted(dims)), undecided, len(X), *_motion(robot, x, t, m))
    anchors = {f"B{i + 1}" for i in cables}
    if family.dimensions != (1,) or not family.turns or family.tensions_change or not anchors <= set(family.fixed):
        return family

    W = world_coordinates(np.array([r.point for r in on_set]), m, c, L, Rw, cb, robot.load)
    return _turning_members(robot, rho, cables, W, family, tension_tol, world_residual(robot, rho, cables))


def world_residual(robot, rho, cables):
    """residual(x): the relative residual of the 0-based taut set's normalized 6-DOF system at the world root x
    (p, u, v, w, lam)."""
    m = len(cables)
    target, c, L, Rw, cb = normalized_problem(robot, rho, cables)
    fam = fast_family(m)

    def residual(x):
        xn = normalized_coordinates(np.asarray(x, dtype=complex)[None], m, c, L, Rw, cb, robot.load)
        return float(np.max(np.abs(fam.evaluate(xn, target)[0])) / (1 + np.max(np.abs(xn))))

    return residual


def _turning_members(robot, rho, cables, W, family, tension_tol, residual) -> Family:
    """``family`` with its endpoints W (world coordinates, on the set) grouped into families of turning equilibria
    (endpoints whose invariants agree: :func:`cdpr_algebra.homotopy.clusters.duplicate_groups`) and the real ones
    with positive tensions rebuilt and certified (module doc; :mod:`cdpr_algebra.certificates.families`);
    ``residual(x)``: relative residual of a world root."""
    m = len(cables)
    idx = list(cables)
    L, Q = robot.cable_scale, robot.load
    p, R, lam = decode(W, m)
    B = p[:, None, :] + np.einsum("kij,mj->kmi", R, robot.platform[idx])  # (N, m, 3) taut anchors
    inv = np.hstack([B.reshape(len(W), -1) / L, lam * rho[idx] / Q])
    groups = duplicate_groups(inv, INVARIANT_RTOL)
    grouped = {k for g in groups for k in g}
    groups = sorted([sorted(g) for g in groups] + [[k] for k in range(len(inv)) if k not in grouped])
    members, real = [], 0
    for g in groups:
        v = inv[g[0]]
        tau = lam[g[0]] * rho[idx]
        if np.max(np.abs(v.imag)) > INVARIANT_RTOL * (1 + np.max(np.abs(v))) or np.any(tau.real <= tension_tol):
            continue
        real += 1
        member = turning_member(robot, rho, idx, B[g[0]].real, tau.real, residual)
        if member is not None:
            members.append(member)
    return replace(family, groups=tuple(len(g) for g in groups), real=real, members=tuple(members))


def turning_member(robot, rho, idx, B, tau, residual, reading: str = BINARY) -> FamilyMember | None:
    """The :class:`FamilyMember` of the real family of the 0-based taut cables ``idx`` whose taut anchors are at the
    world points ``B`` (m x 3) with the positive ``tau`` (m): R0 takes the platform's anchor line to the world's,
    the turning angles at which the other cables stay slack (:func:`.one_cable.slack_arcs`), the pose in the middle
    of the largest arc with its residual (``residual(x)`` of a world root (p, u, v, w, lam)), H_r class and
    certificate (:func:`cdpr_algebra.certificates.families.certify_turning_equilibrium`, in the robot's ``reading``);
    None without a feasible arc."""
    from cdpr_algebra.certificates.families import certify_turning_equilibrium

    far = int(np.argmax(np.linalg.norm(B - B[0], axis=1)))
    axis = (B[far] - B[0]) / np.linalg.norm(B[far] - B[0])
    arm = robot.platform[idx[far]] - robot.platform[idx[0]]
    R0 = rotation_taking(arm / np.linalg.norm(arm), axis)
    others = [j for j in range(robot.n) if j not in idx]
    arcs = slack_arcs(robot, rho, others, idx[0], B[0], R0, axis)
    if not arcs:
        return None
    Rt, pt, relative = middle_pose(arcs, axis, R0, B[0], robot.platform[idx[0]])
    tensions = np.zeros(robot.n)
    tensions[idx] = tau
    cls = stability_classes(robot.base[idx], pt + robot.platform[idx] @ Rt.T, pt + Rt @ robot.com, tau, rho[idx],
                            robot.load, robot.size)
    return FamilyMember(tuple(i + 1 for i in idx), pt, Rt, tensions, axis, relative,
                        residual(encode(pt, Rt, tau / rho[idx])), cls,
                        certify_turning_equilibrium(robot, rho, idx, pt, Rt, tau, reading=reading))
