"""IGP with assigned orientation of 3-cable robots (seed 004 Sec. 3 and Appendix A).

Given the platform orientation R, find the position x of G (and cable lengths and tensions) such that the
three cable lines and the load line are linearly dependent (rank M <= 3, eq. 3).  Work frame: origin at A_1,
z along the load direction (the paper's k).  Generic case Delta != 0 (Sec. 3.1): the x-coordinate of the single
non-trivial root of p123 (eq. 10), x4 = -E_3/E_4 - (x_1 + x_2 + x_3) (Vieta, equivalent to eq. 12); y4 is the same
formula in the work frame turned by 90 degrees about k (eq. 13-14 by symmetry); z4 from p2 or p3, linear in z.
Case Delta = 0 (Sec. 3.2): p467 from p4 = g, p6, p7 (eq. 16-19), z from p6 or p7.  When this fails, the special
sets of Appendix A are recognised and reported as what they are (vertical line, 1-dof crane, curve on a cylinder,
conic on a plane) or as no solution.

Numeric mode: floats, Newton-polished and verified by the equilibrium residual.  Exact mode (``exact=True``):
sympy Rationals throughout, zero tests exact, the solution checked on all 15 minors of M'(O).
"""

from __future__ import annotations

import time

import numpy as np
import sympy as sp

from cdpr_algebra.model.errors import CdprInputError
from cdpr_algebra.generated import igp_orientation as gen
from cdpr_algebra.certificates.equilibria import with_certificates
from .results import IGPResult, SolutionSet, at_polished_roots, make_solution
from cdpr_algebra.model.pose import rotation_taking
from cdpr_algebra.model.robot import Robot

# Directions (cos, sin) along which a coordinate of G is computed; rational so exact mode stays exact.
_DIRECTIONS = [(1, 0), (0, 1), (sp.Rational(3, 5), sp.Rational(4, 5)), (sp.Rational(-4, 5), sp.Rational(3, 5)),
               (sp.Rational(5, 13), sp.Rational(-12, 13)), (sp.Rational(12, 13), sp.Rational(5, 13))]
_Z_IDX = (2, 4, 8)  # XYZ_MONOMIALS entries x z, y z, z
_XYZ3 = gen.XYZ3_MONOMIALS


# ----------------------------------------------------------------------------------------- frames
def _rational(v) -> sp.Rational:
    """The exact rational a robot-file number stands for.

    The simplest fraction (denominator <= 10^6) that rounds to the same double, e.g. 0.1 -> 1/10 and
    0.9333333333333333 -> 14/15; otherwise the decimal as printed (repr).
    """
    from fractions import Fraction

    v = float(v)
    f = Fraction(v).limit_denominator(10**6)
    if float(f) == v:
        return sp.Rational(f.numerator, f.denominator)
    return sp.Rational(repr(v))


def _load_frame(direction, exact: bool):
    """Rotation W with W d = +z (the paper's k)."""
    d = [_rational(v) for v in direction] if exact else np.asarray(direction, dtype=float)
    if exact:
        if d == [0, 0, 1]:
            return sp.eye(3)
        if d == [0, 0, -1]:
            return sp.diag(1, -1, -1)
        raise CdprInputError("load_direction", "exact mode needs the load direction along +z or -z")
    return rotation_taking(d / np.linalg.norm(d), [0.0, 0.0, 1.0])


class _Problem:
    """The data of seed 004 in the work frame: a_i (a_1 = 0), r_i = R (b_i' - g'), scaled by 1/L in numeric mode."""

    def __init__(self, robot: Robot, rotation, exact: bool):
        self.exact = exact
        if exact:
            R = sp.Matrix(rotation).applyfunc(lambda v: v if isinstance(v, sp.Basic) else _rational(v))
            if R.shape != (3, 3) or (R.T * R - sp.eye(3)).applyfunc(sp.simplify) != sp.zeros(3, 3) or R.det() != 1:
                raise CdprInputError("rotation", "exact mode needs an exact rotation matrix (R^T R = I, det R = 1)")
            W = _load_frame(robot.load_direction.tolist(), True)
            A = [sp.Matrix([_rational(v) for v in a]) for a in robot.base]
            b = [sp.Matrix([_rational(v) for v in p]) for p in robot.platform]
            g = sp.Matrix([_rational(v) for v in robot.com])
            self.W, self.R, self.origin, self.scale = W, R, A[0], sp.Integer(1)
            self.a = [W * (Ai - A[0]) for Ai in A]
            self.r = [W * R * (bi - g) for bi in b]
        else:
            R = np.asarray(rotation, dtype=float)
            W = _load_frame(robot.load_direction, False)
            L = robot.size
            self.W, self.R, self.origin, self.scale = W, R, robot.base[0], L
            self.a = [W @ (Ai - robot.base[0]) / L for Ai in robot.base]
            self.r = [W @ R @ (bi - robot.com) / L for bi in robot.platform]

    def params(self, c=1, s=0):
        """The 15 parameters in the work frame turned so that the new x axis is (c, s)."""
        def turn(v):
            return [c * v[0] + s * v[1], -s * v[0] + c * v[1], v[2]]
        return turn(self.a[1]) + turn(self.a[2]) + turn(self.r[0]) + turn(self.r[1]) + turn(self.r[2])

    def trivial(self, c=1, s=0):
        """x-coordinates (along (c, s)) of the trivial solutions x_i = a_i - r_i (eq. 8)."""
        return [c * (a[0] - r[0]) + s * (a[1] - r[1]) for a, r in zip(self.a, self.r)]

    def to_world(self, X):
        """Work-frame point -> world-frame point."""
        if self.exact:
            return self.W.T * (sp.Matrix(X) * self.scale) + self.origin
        return self.W.T @ (np.asarray(X, dtype=float) * self.scale) + self.origin


# ------------------------------------------------------------------------------------- elimination
def _is_zero(v, tol, exact, ref=1.0):
    """Exact zero, or |v| <= tol * ref where ``ref`` is the magnitude of the terms that make up v."""
    return v == 0 if exact else abs(v) <= tol * ref


def _abs_params(params):
    """Reference parameters for relative zero tests: every base coordinate replaced by max |a|, every platform
    coordinate by max |r|.  A formula evaluated there in ``magnitude`` mode bounds the size of the terms that
    make up its value for any robot of that size, so rounding noise is measured against it."""
    sa = max(abs(v) for v in params[:6])
    sr = max(abs(v) for v in params[6:])
    return [sa] * 6 + [sr] * 9


def p123(params, magnitude: bool = False):
    """E_0 .. E_6 of eq. (10) (p1 and p23 through the generated formulas).

    ``magnitude=True``: every stage evaluated on the absolute values of its inputs, an estimate of the size of
    the terms that cancel in each E_h (for relative zero tests in floating point).
    """
    f = _magnitude_fns if magnitude else (lambda name: getattr(gen, name))
    c1 = f("p1_coefficients")(*params)
    c2 = f("p2_coefficients")(*params)
    c3 = f("p3_coefficients")(*params)
    g = f("p23_from_p2_p3")(*c2, *c3)
    return f("p123_from_p1_p23")(*c1, *g, f("t_coefficient")(*params)[0])


def p467(params, magnitude: bool = False):
    """Coefficients of p467 (Sec. 3.2): x^0 .. x^5 (``magnitude`` as in :func:`p123`)."""
    f = _magnitude_fns if magnitude else (lambda name: getattr(gen, name))
    l = f("g_coefficients")(*params)
    h = f("p67_from_p6_p7")(*f("p6_coefficients")(*params), *f("p7_coefficients")(*params))
    return f("p467_from_g_p67")(*h, *l)


def _magnitude_fns(name):
    """The generated term-magnitude bound of ``name`` (arguments must be non-negative)."""
    return getattr(gen, name + "_magnitude")


def _coordinate(prob: _Problem, c, s, delta_zero: bool, tol):
    """The coordinate of x4 along (c, s), or (None, reason)."""
    params = prob.params(c, s)
    fn = p467 if delta_zero else p123
    E = fn(params)
    if prob.exact:
        if all(e == 0 for e in E):
            return None, "identically zero"
        if E[5] != 0 if len(E) > 5 else False:
            return None, "degree 5"
        if E[4] == 0:
            return None, "leading coefficient zero"
        return -E[3] / E[4] - sum(prob.trivial(c, s)), None
    size = max(abs(e) for e in E)
    ref = max(abs(e) for e in fn(_abs_params(params), magnitude=True))
    # rounding noise is ~1e-16 of the term bound; a generic robot gives |E| / bound >= ~1e-12, an exactly
    # special one (App. A) <= ~1e-39 (measured): 1e-20 separates the two with wide margins on both sides
    if size <= 1e-20 * ref:
        return None, "identically zero"
    if abs(E[4]) <= 1e-9 * size or (len(E) > 5 and abs(E[5]) > 1e-9 * size):
        return None, "leading coefficient zero"
    return -E[3] / E[4] - sum(prob.trivial(c, s)), None


def _z_equations(prob: _Problem, xy, delta_zero: bool, params=None, magnitude: bool = False):
    """[(coefficient of z, rest)] of the equations linear in z, at (x, y) = xy (``magnitude``: term bounds)."""
    X, Y = xy
    params = prob.params() if params is None else params
    f = _magnitude_fns if magnitude else (lambda name: getattr(gen, name))
    out = []
    if not delta_zero:
        for cs in (f("p2_coefficients")(*params), f("p3_coefficients")(*params)):
            cz = cs[2] * X + cs[4] * Y + cs[8]
            rest = cs[0] * X * X + cs[1] * X * Y + cs[3] * Y * Y + cs[6] * X + cs[7] * Y + cs[9]
            out.append((cz, rest))
    else:
        for cs in (f("p6_coefficients")(*params), f("p7_coefficients")(*params)):
            cz = sum(c * X ** i * Y ** j for c, (i, j, k) in zip(cs, _XYZ3) if k == 1)
            rest = sum(c * X ** i * Y ** j for c, (i, j, k) in zip(cs, _XYZ3) if k == 0)
            out.append((cz, rest))
    return out


# ------------------------------------------------------------------------------------ special sets
def _parallel(u, v, tol, exact):
    cr = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]]
    ref = 1 if exact else float(np.linalg.norm(np.array(u, dtype=float)) * np.linalg.norm(np.array(v, dtype=float)))
    return all(_is_zero(cc, tol, exact, ref) for cc in cr)


def _vertical_line(prob: _Problem, xy, tol) -> SolutionSet | None:
    """The line of G through (x, y) parallel to k, if every point of it solves p1 = p2 = p3 = 0 (App. A:
    Gamma_1 = Gamma_2 = Gamma_3 = 0); a 1-dof crane when it passes through a trivial solution with r_i || k."""
    exact = prob.exact
    X, Y = xy
    params = prob.params()
    c1 = gen.p1_coefficients(*params)
    p1 = sum(c * X ** i * Y ** j for c, (i, j) in zip(c1, gen.P1_MONOMIALS))
    eqs = _z_equations(prob, (X, Y), False)
    if exact:
        refs = [1] * 5
    else:
        ap = _abs_params(params)
        aX = aY = max(abs(X), abs(Y), ap[0])
        refs = [sum(c * aX ** i * aY ** j for c, (i, j) in zip(gen.p1_coefficients_magnitude(*ap), gen.P1_MONOMIALS))]
        refs += [v for e in _z_equations(prob, (aX, aY), False, ap, magnitude=True) for v in e]
    vals = [p1] + [v for e in eqs for v in e]
    if not all(_is_zero(v, tol, exact, r) for v, r in zip(vals, refs)):
        return None
    base_pt = _world_list(prob, [X, Y, 0])
    direction = _dir_list(prob, [0, 0, 1])
    for i in range(3):
        if (_is_zero(prob.a[i][0] - prob.r[i][0] - X, 1e-7, exact) and _is_zero(prob.a[i][1] - prob.r[i][1] - Y, 1e-7, exact)
                and _parallel(prob.r[i], [0, 0, 1], tol, exact)):
            return SolutionSet(
                "crane", f"the robot works as a 1-dof crane: G moves on the vertical line through A_{i + 1}, "
                         f"cable {i + 1} holding the whole load (Carricato 2013, App. A)",
                {"cable": i + 1, "line_point": base_pt, "line_direction": direction})
    return SolutionSet(
        "vertical_line", "G moves on a line parallel to the load direction (Gamma_1 = Gamma_2 = Gamma_3 = 0, "
                         "Carricato 2013, App. A)", {"line_point": base_pt, "line_direction": direction})


def _hat_point(prob: _Problem, tol):
    """(x^, y^) of eq. (A1), or None when delta = n12 + n23 + n31 vanishes."""
    r, a = prob.r, prob.a

    def n(i, j):
        return r[i][0] * r[j][1] - r[i][1] * r[j][0]

    n12, n23, n31 = n(0, 1), n(1, 2), n(2, 0)
    dl = n12 + n23 + n31
    if _is_zero(dl, tol, prob.exact):
        return None
    return ((a[2][0] * n12 + a[1][0] * n31) / dl, (a[2][1] * n12 + a[1][1] * n31) / dl)


def _special_set(prob: _Problem, tol) -> SolutionSet:
    """Appendix A: which positive-dimensional (or empty) set the IGP has when p123 / p467 vanish identically."""
    exact = prob.exact
    params = prob.params()
    hat = _hat_point(prob, tol)
    candidates = [hat] if hat is not None else []
    candidates += [(a[0] - r[0], a[1] - r[1]) for a, r in zip(prob.a, prob.r)]
    for xy in candidates:
        vl = _vertical_line(prob, xy, tol)
        if vl is not None:
            return vl
    c1 = gen.p1_coefficients(*params)
    c1_ref = [1] * 6 if exact else gen.p1_coefficients_magnitude(*_abs_params(params))
    if all(_is_zero(c, tol, exact, r) for c, r in zip(c1, c1_ref)):
        c2 = gen.p2_coefficients(*params)
        c3 = gen.p3_coefficients(*params)
        conic = gen.p23_from_p2_p3(*c2, *c3)
        # back to world length units (work-frame coordinates were divided by L), normalized to max |c| = 1
        conic = [float(c) / float(prob.scale) ** (i + j) for c, (i, j) in zip(conic, gen.P23_MONOMIALS)]
        top = max(abs(c) for c in conic) or 1.0
        conic = [c / top for c in conic]
        return SolutionSet(
            "cylinder_curve",
            "G moves on a curve lying on a cylinder parallel to the load direction: its cross-section is the conic "
            "p23(x, y) = 0 in the work frame (origin A_1, z along the load), z follows from p2 = 0 (Carricato 2013, App. A)",
            {"work_frame": _frame_dict(prob), "conic_monomials": gen.P23_MONOMIALS,
             "conic_coefficients": [_num(v) for v in conic]},
        )
    k = [0, 0, 1]
    for i, j in ((0, 1), (0, 2), (1, 2)):
        ri, rj = prob.r[i], prob.r[j]
        nij = [ri[1] * rj[2] - ri[2] * rj[1], ri[2] * rj[0] - ri[0] * rj[2], ri[0] * rj[1] - ri[1] * rj[0]]
        aij = [prob.a[i][m] - prob.a[j][m] for m in range(3)]
        pij = [aij[1] * k[2] - aij[2] * k[1], aij[2] * k[0] - aij[0] * k[2], aij[0] * k[1] - aij[1] * k[0]]
        if _parallel(nij, pij, tol, exact):
            h = 3 - i - j
            return SolutionSet(
                "planar_conic",
                f"G moves on a conic in the vertical plane through A_{i + 1} and A_{j + 1}; the robot behaves like a 2-2 "
                f"CDPR with cables {i + 1} and {j + 1} holding the load and cable {h + 1} slack (Carricato 2013, App. A)",
                {"cables": [i + 1, j + 1], "slack_cable": h + 1,
                 "plane_point": _world_list(prob, prob.a[i]), "plane_normal": _dir_list(prob, pij)},
            )
    return SolutionSet("undecided", "p123 vanishes identically but no special set of Carricato 2013, App. A applies: "
                                    "the case is flagged, not solved (isolated solutions, a continuum or none: not "
                                    "decided)", {"work_frame": _frame_dict(prob)})


def _num(v):
    return float(v) if not isinstance(v, sp.Basic) or v.is_number else str(v)


def _world_list(prob, X):
    w = prob.to_world(X)
    return [_num(v) for v in (list(w) if prob.exact else w.tolist())]


def _dir_list(prob, v):
    """A work-frame direction as a world-frame unit vector."""
    w = np.array([float(t) for t in v])
    w = np.asarray(prob.W, dtype=float).T @ w
    return (w / np.linalg.norm(w)).tolist()


def _frame_dict(prob):
    return {"origin": [_num(v) for v in (list(prob.origin) if prob.exact else prob.origin.tolist())],
            "rotation_world_to_work": [[_num(v) for v in row] for row in
                                       (prob.W.tolist() if prob.exact else prob.W.tolist())],
            "length_unit": _num(prob.scale)}


# ----------------------------------------------------------------------------------------- solving
def _polish(prob: _Problem, X):
    """Newton on the bilinear system sum lam_i s_i = k, sum lam_i r_i x (G - a_i) = 0 (6 x 6), work frame."""
    a = np.array(prob.a, dtype=float)
    r = np.array(prob.r, dtype=float)
    G = np.array(X, dtype=float)
    k = np.array([0.0, 0.0, 1.0])

    def F(G, lam):
        s = G + r - a
        return np.concatenate([lam @ s - k, sum(l * np.cross(ri, G - ai) for l, ri, ai in zip(lam, r, a))])

    s = G + r - a
    lam = np.linalg.lstsq(s.T, k, rcond=None)[0]
    for _ in range(8):
        f = F(G, lam)
        if np.linalg.norm(f) < 1e-15:
            break
        s = G + r - a
        J = np.zeros((6, 6))
        J[:3, :3] = lam.sum() * np.eye(3)
        J[:3, 3:] = s.T
        J[3:, :3] = sum(l * np.array([[0, -ri[2], ri[1]], [ri[2], 0, -ri[0]], [-ri[1], ri[0], 0]]) for l, ri in zip(lam, r))
        J[3:, 3:] = np.array([np.cross(ri, G - ai) for ri, ai in zip(r, a)]).T
        try:
            step = np.linalg.solve(J, -f)
        except np.linalg.LinAlgError:
            break
        G, lam = G + step[:3], lam + step[3:]
    return G


def _locate(prob: _Problem, tol):
    """The work-frame point (x4, y4, z4) of the closed form, or (None, SolutionSet) for App. A cases."""
    exact = prob.exact
    params = prob.params()
    dlt = gen.delta(*params)[0]
    delta_zero = _is_zero(dlt, 1e-9, exact, 1 if exact else gen.delta_magnitude(*_abs_params(params))[0])
    coords, reasons = [], []
    for c, s in _DIRECTIONS:
        val, why = _coordinate(prob, c, s, delta_zero, tol)
        if val is None:
            reasons.append(why)
            if why == "identically zero":
                break
            continue
        coords.append(((c, s), val))
        if len(coords) == 2:
            break
    if len(coords) < 2:
        if "identically zero" in reasons:
            return None, _special_set(prob, tol)
        return None, SolutionSet("empty", "the non-trivial root of p123 is at infinity: no equilibrium with this "
                                          "orientation (Carricato 2013, App. A, empty solution sets)")
    (c1_, s1_), u1 = coords[0]
    (c2_, s2_), u2 = coords[1]
    det = c1_ * s2_ - s1_ * c2_
    X = (u1 * s2_ - s1_ * u2) / det
    Y = (c1_ * u2 - u1 * c2_) / det
    eqs = _z_equations(prob, (X, Y), delta_zero)
    cz, rest = max(eqs, key=lambda e: abs(e[0]))
    if exact:
        zref = 1
    else:
        ap = _abs_params(params)
        aeqs = _z_equations(prob, (max(abs(X), abs(Y), ap[0]),) * 2, delta_zero, ap, magnitude=True)
        zref = max(abs(e[0]) for e in aeqs)
    if _is_zero(cz, 1e-9, exact, zref):
        vl = _vertical_line(prob, (X, Y), 1e-9)
        if vl is not None:
            return None, vl
        return None, SolutionSet("empty", "(x4, y4) does not extend to a finite z (Carricato 2013, App. A, empty "
                                          "solution sets): no equilibrium with this orientation")
    return [X, Y, -rest / cz], None


def igp_orientation(robot: Robot, rotation, *, exact: bool = False, certify: bool = True) -> IGPResult:
    """All equilibria of a 3-cable robot with the platform orientation ``rotation`` assigned (seed 004 Sec. 3).

    Returns an :class:`IGPResult` with at most one solution, or with ``solution_set`` describing the special
    set of Appendix A (line, curve, conic, crane) or an empty set.  ``exact=True`` reads the robot's numbers as
    exact rationals (see :func:`_rational`) and needs an exact rotation (sympy entries).  A numeric solution is
    Newton-polished and verified by its equilibrium residual; the message says how it was checked.
    ``certify``: attach the interval certificate of :mod:`cdpr_algebra.certificates.equilibria` to the solution (``certified``, ``certificate``).

    The solutions' ``hessian`` is the floating-point class of H_r (an estimate); the class the certificate proves is
    ``hessian_proven``, and the tables and JSON show that class or 'undecided' (:class:`cdpr_algebra.igp.results.IGPSolution`).
    """
    t0 = time.perf_counter()
    if robot.n != 3:
        raise CdprInputError("base", f"the IGP with assigned orientation needs exactly 3 cables, the robot has {robot.n}")
    if not exact:
        from cdpr_algebra.model.pose import check_rotation
        rotation = check_rotation(rotation)
    prob = _Problem(robot, rotation, exact)
    tol = 1e-10

    def done(solutions=(), sset=None, msg=""):
        if certify:
            solutions = at_polished_roots(robot, with_certificates(robot, solutions, "orientation"))
        return IGPResult("orientation", tuple(solutions), sset, time.perf_counter() - t0, msg)

    Xw, sset = _locate(prob, tol)
    if Xw is None:
        return done(sset=sset, msg=sset.kind.replace("_", " "))
    if not exact:
        Xw = list(_polish(prob, Xw))
    s_len = [sum((Xw[m] + prob.r[i][m] - prob.a[i][m]) ** 2 for m in range(3)) for i in range(3)]
    if any(_is_zero(v, 1e-18, exact) for v in s_len):
        return done(sset=SolutionSet("empty", "the only root is a trivial solution (some B_i = A_i, eq. 8): no "
                                              "equilibrium with this orientation"))
    Gw = prob.to_world(Xw)
    if exact:
        minors = gen.minors_M_prime(*prob.params(), *Xw)
        if any(sp.simplify(m) != 0 for m in minors):
            return done(sset=SolutionSet("undecided", "exact check failed: a minor of M'(O) does not vanish at the "
                                                      "point located"), msg="exact check FAILED")
        sol = make_solution(robot, np.array([float(v) for v in Gw]), np.array(prob.R.tolist(), dtype=float))
        return done([sol], None, f"exact: G = {list(Gw)}, all 15 minors of M'(O) vanish there")
    sol = make_solution(robot, Gw, prob.R)
    if sol.residual > 1e-8:
        sset2 = _special_set(prob, 1e-7)
        if sset2.kind not in ("empty", "undecided"):
            return done(sset=sset2, msg=sset2.kind.replace("_", " "))
        return done([sol], None, f"UNVERIFIED: equilibrium residual {sol.residual:.2e} after Newton polishing")
    return done([sol], None, "verified: equilibrium residual %.1e" % sol.residual)


def exact_solution(robot: Robot, rotation) -> list | None:
    """The exact position of G (world frame, sympy Rationals) for rational data, or None when there is no
    isolated solution.  Checked exactly on all 15 minors of M'(O)."""
    prob = _Problem(robot, rotation, True)
    Xw, _ = _locate(prob, 0)
    if Xw is None or any(sp.simplify(m) != 0 for m in gen.minors_M_prime(*prob.params(), *Xw)):
        return None
    return list(prob.to_world(Xw))


def igp_orientation_batch(robot: Robot, rotations) -> tuple[np.ndarray, np.ndarray]:
    """Vectorized closed form over many orientations (generic case Delta != 0 of Sec. 3.1).

    ``rotations``: (N, 3, 3).  Returns ``(G, ok)``: G (N, 3) world positions of the centre of mass and a mask of
    the orientations where the generic formula applies (Delta, E_4 and the z coefficient clearly non-zero);
    the others are NaN and should go through :func:`igp_orientation`, which handles App. A.  No Newton polish:
    use :func:`igp_orientation` when a certificate of the single pose is wanted.
    """
    if robot.n != 3:
        raise CdprInputError("base", f"the IGP with assigned orientation needs exactly 3 cables, the robot has {robot.n}")
    Rs = np.asarray(rotations, dtype=float)
    if Rs.ndim != 3 or Rs.shape[1:] != (3, 3):
        raise CdprInputError("rotations", f"expected an array of shape (N, 3, 3), got {Rs.shape}")
    W = _load_frame(robot.load_direction, False)
    L = robot.size
    a = [(W @ (A - robot.base[0])) / L for A in robot.base]
    r = [np.einsum("ij,njk,k->ni", W, Rs, b - robot.com) / L for b in robot.platform]  # (N, 3) each

    def params(c, s):
        def turn_const(v):
            return [np.full(len(Rs), c * v[0] + s * v[1]), np.full(len(Rs), -s * v[0] + c * v[1]), np.full(len(Rs), v[2])]

        def turn(v):
            return [c * v[:, 0] + s * v[:, 1], -s * v[:, 0] + c * v[:, 1], v[:, 2]]
        return turn_const(a[1]) + turn_const(a[2]) + turn(r[0]) + turn(r[1]) + turn(r[2])

    coords = []
    ok = np.ones(len(Rs), dtype=bool)
    for c, s in ((1, 0), (0, 1)):
        p = params(c, s)
        E = p123(p)
        size = np.max(np.abs(np.array(E[:5])), axis=0)
        ok &= np.abs(E[4]) > 1e-9 * size
        with np.errstate(divide="ignore", invalid="ignore"):
            triv = sum(c * (ai[0] - ri[:, 0]) + s * (ai[1] - ri[:, 1]) for ai, ri in zip(a, r))
            coords.append(-E[3] / E[4] - triv)
    X, Y = coords
    p = params(1, 0)
    ok &= np.abs(gen.delta(*p)[0]) > 1e-9 * gen.delta_magnitude(*[np.abs(v) for v in p])[0]
    cs2, cs3 = gen.p2_coefficients(*p), gen.p3_coefficients(*p)
    cz2 = cs2[2] * X + cs2[4] * Y + cs2[8]
    cz3 = cs3[2] * X + cs3[4] * Y + cs3[8]
    rest2 = cs2[0] * X * X + cs2[1] * X * Y + cs2[3] * Y * Y + cs2[6] * X + cs2[7] * Y + cs2[9]
    rest3 = cs3[0] * X * X + cs3[1] * X * Y + cs3[3] * Y * Y + cs3[6] * X + cs3[7] * Y + cs3[9]
    use2 = np.abs(cz2) >= np.abs(cz3)
    cz = np.where(use2, cz2, cz3)
    ok &= np.abs(cz) > 1e-12
    with np.errstate(divide="ignore", invalid="ignore"):
        Z = -np.where(use2, rest2, rest3) / cz
    Xw = np.stack([X, Y, Z], axis=1) * L
    G = Xw @ W + robot.base[0]  # W^T applied to rows
    G[~ok] = np.nan
    return G, ok
