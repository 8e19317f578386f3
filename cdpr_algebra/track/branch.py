"""One equilibrium branch: the equations of a taut set (the DGP's, Berti, Merlet and Carricato 2016 eqs. 4-5, from
their one sympy source through the generated evaluators of :func:`cdpr_algebra.dgp.solve.fast_family`, in world
coordinates with lam_i = tau_i / rho_i), Newton's method on them, a predictor along rho(t), and the state with the
quantities whose sign changes are the tracker's events:

* ``slack``: lam_i of a taut cable (tension / length) reaches 0;
* ``taut``: rho_j - |A_j B_j| of a slack cable reaches 0;
* ``fold``: the lowest eigenvalue of the reduced Hessian (Berti et al. 2016 eqs. 28-30, in stiffness units with
  rotations scaled by the robot's size) reaches 0: the equilibrium stops being stable.
"""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from cdpr_algebra.dgp.solve import fast_family
from cdpr_algebra.model.pose import angles_from_matrix
from cdpr_algebra.model.stability import constraint_jacobian, hessian_class, reduced_hessian
from cdpr_algebra.model.taut_equations import encode, taut_parameters
from cdpr_algebra.report.jsonable import jsonable

NEWTON_TOL = 1e-13  # relative size of the last Newton update
NEWTON_ITERS = 12
RESIDUAL_TOL = 1e-15  # max |F| over the size of the terms: the rounding level
FULL_RANK_DET = 1e-12  # |det| of the 6 x 6 constraint Jacobian (unit rows) above this: six independent cables


@dataclass(frozen=True)
class TrackState:
    """An equilibrium at its lengths: pose, tensions (n values, 0 for slack cables), 1-based ``taut`` set, stability
    (``hessian`` class of the reduced Hessian, ``min_eigenvalue`` its lowest eigenvalue over the problem's
    stiffness scale), and ``residual`` of its equations (relative)."""

    t: float
    lengths: np.ndarray
    position: np.ndarray
    rotation: np.ndarray
    tensions: np.ndarray
    taut: tuple
    hessian: str
    min_eigenvalue: float
    residual: float
    x: np.ndarray = field(repr=False, compare=False, default=None)  # the unknowns of the taut set's equations
    events: dict = field(repr=False, compare=False, default=None)  # event_values at this state (set by state())
    parameters: np.ndarray = field(repr=False, compare=False, default=None)  # of the taut set's equations (complex)

    @property
    def stable(self) -> bool:
        return self.hessian == ">"

    @property
    def cables(self) -> tuple:
        """The taut set, 0-based."""
        return tuple(c - 1 for c in self.taut)

    def potential(self, robot) -> float:
        """Potential energy of the load, -Q d . G (G the centre of mass)."""
        return float(-robot.load * robot.load_direction @ (self.position + self.rotation @ robot.com))

    def to_dict(self) -> dict:
        return {"t": self.t, "lengths": jsonable(self.lengths), "position": jsonable(self.position),
                "rotation": jsonable(self.rotation), "angles": jsonable(angles_from_matrix(self.rotation)),
                "tensions": jsonable(self.tensions), "taut": list(self.taut), "stable": self.stable,
                "hessian": self.hessian, "min_eigenvalue": self.min_eigenvalue, "residual": self.residual}


def parameters(robot, cables, rho) -> np.ndarray:
    return taut_parameters(robot, cables, rho)


def unknowns(position, rotation, lam) -> np.ndarray:
    return encode(np.asarray(position, dtype=float), np.asarray(rotation, dtype=float), np.asarray(lam, dtype=float))


def residual_scale(robot) -> float:
    return robot.load * (1 + robot.size) + robot.size ** 2 + 1.0


def newton(robot, cables, rho, x0, tol: float = NEWTON_TOL, iters: int = NEWTON_ITERS):
    """Real Newton on the taut set's equations at lengths rho from x0.  Returns (x, converged, residual, steps)
    with the residual max |F| relative to the size of the equations' terms.  Converged: the last update is below
    ``tol`` (relative), or the residual is at the rounding level (RESIDUAL_TOL) after an update no larger than the
    one before (near a fold the Jacobian is nearly singular and the updates stall above ``tol``)."""
    fam = fast_family(len(cables))
    p = parameters(robot, cables, rho).astype(complex)
    x = np.array(x0, dtype=float)
    scale = residual_scale(robot)
    prev = np.inf
    for k in range(iters):
        F, J = fam.evaluate_and_jacobian(x.astype(complex), p)
        F, J = F[0].real, J[0].real
        try:
            dx = np.linalg.solve(J, -F)
        except np.linalg.LinAlgError:
            return x, False, np.inf, k
        if not np.all(np.isfinite(dx)):
            return x, False, np.inf, k
        x = x + dx
        step = np.abs(dx).max() / (1 + np.abs(x).max())
        if step <= tol:
            F = fam.evaluate(x.astype(complex), p)[0].real
            return x, True, float(np.abs(F).max() / scale), k + 1
        if step <= prev and step <= 1e-6:
            res = float(np.abs(fam.evaluate(x.astype(complex), p)[0].real).max() / scale)
            if res <= RESIDUAL_TOL:
                return x, True, res, k + 1
        prev = step
    F = fam.evaluate(x.astype(complex), p)[0].real
    return x, False, float(np.abs(F).max() / scale), iters


def tangent(robot, cables, rho0, rho1, x):
    """First-order change of x from lengths rho0 to rho1: -J^{-1} (dF/dp . dp) (the parameters are affine in rho^2,
    so dp = p(rho1) - p(rho0) is exact); None where J is singular."""
    fam = fast_family(len(cables))
    p0 = parameters(robot, cables, rho0)
    dp = parameters(robot, cables, rho1) - p0
    F, J, Fp = fam.evaluate_directional(np.asarray(x, dtype=complex), p0.astype(complex), dp.astype(complex))
    try:
        return np.linalg.solve(J[0].real, -Fp[0].real)
    except np.linalg.LinAlgError:
        return None


def state(robot, cables, rho, x, t: float, residual: float) -> TrackState:
    """The equilibrium of the taut set ``cables`` (0-based) described by x, with its stability."""
    m = len(cables)
    x = np.asarray(x, dtype=float)
    p, R, lam = x[0:3].copy(), x[3:12].reshape(3, 3).T.copy(), x[12:12 + m]  # columns u, v, w (taut_equations.decode)
    idx = list(cables)
    tau = np.zeros(robot.n)
    tau[idx] = lam * rho[idx]
    B = p + robot.platform[idx] @ R.T
    G = p + R @ robot.com
    scale = float(np.sum(np.abs(tau[idx]) / rho[idx]) + robot.load / robot.size)
    if m == 6 and abs(np.linalg.det(constraint_jacobian(robot.base[idx], B, G, rho[idx]))) > FULL_RANK_DET:
        Hr = np.zeros((0, 0))  # six independent taut cables: the platform cannot move, H_r is empty
    else:
        Hr = reduced_hessian(robot.base[idx], B, G, tau[idx], rho[idx], length_scale=robot.size)
    if Hr.shape[-1]:
        ev = np.linalg.eigvalsh(0.5 * (Hr + Hr.T))
        lo = float(ev[0] / scale)
    else:
        lo = np.inf
    st = TrackState(t=float(t), lengths=np.array(rho, dtype=float), position=p, rotation=R, tensions=tau,
                    taut=tuple(c + 1 for c in sorted(cables)), hessian=hessian_class(Hr, scale) if Hr.size else ">",
                    min_eigenvalue=lo, residual=float(residual), x=np.array(x, dtype=float))
    object.__setattr__(st, "events", event_values(robot, st))
    return st


def slack_margins(robot, st: TrackState) -> np.ndarray:
    """rho_j - |A_j B_j| for every cable (>= 0 where a slack cable is slack; 0 on taut cables)."""
    B = st.position + robot.platform @ st.rotation.T
    return st.lengths - np.linalg.norm(robot.base - B, axis=1)


def event_values(robot, st: TrackState) -> dict:
    """The event functions at a state (module doc): {("slack", i): tau_i / Q, ("taut", j): margin_j / size,
    ("fold", None): lowest scaled eigenvalue}; each is > 0 on the side of the current branch."""
    if st.events is not None:
        return st.events
    cables = st.cables
    Q = robot.load
    out = {("slack", i): float(st.tensions[i]) / Q for i in cables}
    slack = [j for j in range(robot.n) if j not in cables]
    if slack:
        B = st.position + robot.platform[slack] @ st.rotation.T
        margins = st.lengths[slack] - np.linalg.norm(robot.base[slack] - B, axis=1)
        L = robot.size
        for j, v in zip(slack, margins):
            out[("taut", j)] = float(v) / L
    out[("fold", None)] = st.min_eigenvalue
    return out


def wrench_condition(robot, st: TrackState) -> float:
    """sigma_min / sigma_max of the taut cables' unit wrenches (0: the wrench matrix lost rank)."""
    idx = list(st.cables)
    B = st.position + robot.platform[idx] @ st.rotation.T
    U = robot.base[idx] - B
    U = U / np.linalg.norm(U, axis=1)[:, None]
    W = np.concatenate([U, np.cross(B - (st.position + st.rotation @ robot.com), U) / robot.size], axis=1)
    s = np.linalg.svd(W, compute_uv=False)
    return float(s[-1] / s[0]) if len(s) else 1.0


def angles(st: TrackState) -> np.ndarray:
    return angles_from_matrix(st.rotation)
