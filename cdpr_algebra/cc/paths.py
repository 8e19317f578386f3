"""First criterion of seed 002 along a trajectory (Sec. II-B.2) and over a surface (Sec. II-B.3), constant
orientation; reproduces Sec. IV-C.

The path is given by the position of G as sympy expressions f(p) of one parameter t in [t0, t1] (trajectory) or
of two parameters u in [u0, u1], v in [v0, v1] (surface).  Each parameter is either *polynomial* (the expressions
are polynomials in it) or *angular* (they are polynomials in its cos and sin, after ``expand_trig``: then
c = cos p, s = sin p are the unknowns, with c^2 + s^2 = 1); anything else is refused (CdprInputError).

**Validity along the path** (checked first).  The CC keeps its tensions' signs along the path iff none of its
seven cubics Q (|M| and the |M_i|, :mod:`cdpr_algebra.cc.radii`) vanishes on the path.  On a trajectory Q(f(t)) is a
univariate polynomial (in t, or in tau = tan(p/2) for an angular parameter, with p = pi checked apart): its real
roots in the range are the crossings.  On a surface, Q(f(u, v)) has no zero iff it has none on the four edges
(univariate) and no interior critical point of the other sign (a closed zero curve inside the rectangle would
enclose an extremum of that sign); the interior critical points are solved with the homotopy engine.

**Index.**  For each cubic Q the distance from the path to {Q = 0} is the minimum of |w - f(p)| over w on the
surface and p in the range.  Its interior critical points solve the Lagrange system (parameters as extra unknowns,
seed 002: 7 equations for a trajectory, 8 for a surface)

    w - f(p) - lam grad Q(w) = 0,  Q(w) = 0,  (w - f(p)) . df/dp_j = 0  (j = 1 or 1, 2)   [+ c^2 + s^2 = 1]

(in scaled coordinates), solved for ALL its complex solutions: the system, with the 20 coefficients of the cubic as
parameters, is homogenized (:func:`.homotopy.projective.projectivize`), solved once for random complex coefficients
by a total-degree homotopy in the chart, and the seven cubics of the CC are then reached by one batched parameter
homotopy (the label-coordinate trick of :mod:`cdpr_algebra.cc.radii`).  As the paper says, the minimum may also sit on the
boundary: the end points of a trajectory (pose radii, :func:`cdpr_algebra.cc.radii.cc_radii_many`), the edges of a surface
(trajectory problems) and its corners (poses).  Real singular points z_s of a surface {Q = 0} (grad Q = 0, where the
Lagrange condition fails) are added with their distance to the path (univariate).  The index is the smallest of all
these distances over the seven cubics.
"""

from __future__ import annotations

import time
from dataclasses import dataclass, field

import numpy as np
import sympy as sp

from .cubic_distances import MONOMIALS
from cdpr_algebra.homotopy.many_targets import ManyTargetSolver
from .radii import cc_radii_many, polynomials_batch, radii_by_number
from .configurations import check_pose, configuration_tensions, parse_cables, valid_configurations
from cdpr_algebra.model.errors import CdprInputError
from cdpr_algebra.model.expressions import parse_expression, range_bound
from cdpr_algebra.report.jsonable import jsonable

__all__ = ["PathSpec", "PathRadii", "parse_path", "path_radii", "path_configurations", "crossings"]




# ------------------------------------------------------------------------------------------------ parsing


@dataclass(frozen=True)
class PathSpec:
    """A path: position of G = ``expressions`` (3 sympy expressions) of ``parameters`` (1 or 2 symbols), each in
    ``ranges``; ``kinds[j]`` is 'polynomial' or 'angular'; ``option`` names the field in error messages."""

    expressions: tuple
    parameters: tuple
    ranges: tuple
    kinds: tuple
    option: str = "expressions"

    def point(self, *values) -> np.ndarray:
        subs = dict(zip(self.parameters, values))
        return np.array([float(sp.N(e.subs(subs), 17)) for e in self.expressions])

    def closed(self, j: int) -> bool:
        """True when angular parameter j covers a full turn (no end points)."""
        a, b = self.ranges[j]
        return self.kinds[j] == "angular" and b - a >= 2 * np.pi * (1 - 1e-12)

    def to_dict(self) -> dict:
        return {"expressions": [str(e) for e in self.expressions], "parameters": [str(p) for p in self.parameters],
                "ranges": [list(r) for r in self.ranges], "kinds": list(self.kinds)}


def parse_path(expressions, ranges, option: str = "expressions") -> PathSpec:
    """Parse 3 expression strings of t (one range) or of u, v (two ranges) into a :class:`PathSpec`; range ends
    are numbers or constant expressions (:func:`range_bound`)."""
    if len(expressions) != 3:
        raise CdprInputError(option, f"expected 3 expressions (x, y, z of G), got {len(expressions)}")
    names = ("t",) if len(ranges) == 1 else ("u", "v")
    if len(ranges) not in (1, 2):
        raise CdprInputError("ranges", f"expected 1 (trajectory) or 2 (surface) ranges, got {len(ranges)}")
    rng = []
    for r in ranges:
        if len(r) != 2:
            raise CdprInputError("ranges", f"expected two ends LO HI, got {list(r)}")
        lo, hi = range_bound(r[0]), range_bound(r[1])
        if not lo < hi:
            raise CdprInputError("ranges", f"expected LO < HI, got {list(r)} = [{lo:g}, {hi:g}]")
        rng.append((lo, hi))
    exprs = [parse_expression(e, names, option) for e in expressions]
    params = tuple(sp.Symbol(n, real=True) for n in names)
    kinds = []
    for p in params:
        trig = [sp.expand_trig(e) for e in exprs]
        has_trig = any(e.has(sp.sin(p)) or e.has(sp.cos(p)) or e.has(sp.tan(p)) for e in trig) or \
            any(a.has(p) for e in trig for a in e.atoms(sp.sin, sp.cos, sp.tan))
        if has_trig:
            c, s = sp.symbols("_c _s")
            ok = True
            for e in trig:
                f = sp.expand(e.subs({sp.sin(p): s, sp.cos(p): c}))
                if f.has(p) or f.has(sp.tan):
                    ok = False
                    break
            if not ok:
                raise CdprInputError(option, f"the expressions must be polynomials in {p} or in cos({p}) and "
                                     f"sin({p}) (multiples of {p} inside sin/cos are fine)")
            kinds.append("angular")
        else:
            try:
                for e in exprs:
                    sp.Poly(e, p)  # the other parameter (and its cos / sin) may appear in the coefficients
            except sp.PolynomialError:
                raise CdprInputError(option, f"the expressions must be polynomials in {p} or in cos({p}) and "
                                     f"sin({p}); got {[str(e) for e in exprs]}") from None
            kinds.append("polynomial")
    for e in exprs:
        if e.atoms(sp.exp, sp.log, sp.Abs) or any(a.is_Pow and not (a.exp.is_Integer and a.exp >= 0)
                                                  for a in sp.expand_trig(e).atoms(sp.Pow) if a.has(*params)):
            raise CdprInputError(option, f"{e} is not a polynomial in the parameters or their cos/sin")
    return PathSpec(tuple(exprs), params, tuple(rng), tuple(kinds), option)


def _polynomial_form(spec: PathSpec):
    """(expressions in the polynomial unknowns, unknowns per parameter, circle equations) of the path."""
    subs, unknowns, circles = {}, [], []
    for p, kind in zip(spec.parameters, spec.kinds):
        if kind == "angular":
            c, s = sp.Symbol(f"c_{p}"), sp.Symbol(f"s_{p}")
            subs[sp.sin(p)], subs[sp.cos(p)] = s, c
            unknowns.append((c, s))
            circles.append(c ** 2 + s ** 2 - 1)
        else:
            q = sp.Symbol(f"q_{p}")
            subs[p] = q
            unknowns.append((q,))
    exprs = []
    for e in spec.expressions:
        e = sp.expand(sp.expand_trig(e))
        e = e.subs({k: v for k, v in subs.items() if k.is_Function})
        e = sp.expand(e.subs({k: v for k, v in subs.items() if not k.is_Function}))
        exprs.append(e)
    return exprs, unknowns, circles


def _angle(c, s, lo):
    """The angle with cosine c and sine s in [lo, lo + 2 pi)."""
    a = np.arctan2(s, c)
    return lo + np.mod(a - lo, 2 * np.pi)


def _in_range(spec: PathSpec, values, tol=1e-9) -> bool:
    for (a, b), v in zip(spec.ranges, values):
        if not (a - tol * (1 + abs(a)) <= v <= b + tol * (1 + abs(b))):
            return False
    return True


# --------------------------------------------------------------------------- batched coefficient-parameter solves


# ------------------------------------------------------------------------------------------------------ index


@dataclass(frozen=True)
class PathRadii:
    """First criterion over a path for one 6-cable CC (cables 0-based; 1-based in ``to_dict``).

    ``valid`` the CC is valid at every point of the path (no crossing); ``crossings`` parameter values where a cubic
    vanishes on the path (trajectory; for a surface, a short description); ``radii[i]`` / ``singular`` the smallest
    distance from the path to {tau_i = 0} / {|J^-T| = 0}; ``index`` their minimum (0 when not valid), ``limiting``
    what attains it, ``where`` = {"parameters", "path_point", "surface_point", "source"} of the minimum (source:
    'interior', 'end point', 'edge', 'corner', 'singular point'); ``failed_paths`` homotopy paths that did not finish.
    """

    cables: tuple
    spec: PathSpec
    valid: bool
    crossings: tuple
    radii: dict
    singular: float
    index: float
    limiting: object
    where: dict
    failed_paths: int
    seconds: float
    tensions_start: np.ndarray = field(default=None)
    where_by_name: dict = field(default=None, compare=False)  # the ``where`` of each cubic's minimum

    def radii_by_number(self) -> dict:
        return radii_by_number(self.radii, self.singular)

    @property
    def status(self) -> str:
        """'incomplete' when homotopy paths failed, else 'float search' (the index is a floating-point value)."""
        return "incomplete" if self.failed_paths else "float search"

    def to_dict(self) -> dict:
        return jsonable({"status": self.status, "cables": [c + 1 for c in self.cables], "path": self.spec.to_dict(),
                         "valid": self.valid,
                         "crossings": list(self.crossings), "radii": self.radii_by_number(), "rmin": self.index,
                         "limiting": self.limiting + 1 if isinstance(self.limiting, (int, np.integer)) else self.limiting,
                         "where": self.where, "failed_paths": self.failed_paths, "seconds": self.seconds,
                         "tensions": self.tensions_start})


def _cubic_expr(c, w):
    return sum(sp.Float(float(cm), 17) * w[0] ** i * w[1] ** j * w[2] ** k for cm, (i, j, k) in zip(c, MONOMIALS))


def _univariate(expr, spec: PathSpec, j: int):
    """Real roots (parameter values in range) of expr(path) for parameter j alone (others substituted already).

    ``expr`` is a sympy expression in the polynomial unknowns of parameter j: q (polynomial) or (c, s) (angular,
    via tau = tan(p / 2); p = pi checked apart)."""
    kind = spec.kinds[j]
    lo, hi = spec.ranges[j]
    p = spec.parameters[j]
    roots = []
    if kind == "polynomial":
        q = sp.Symbol(f"q_{p}")
        poly = sp.Poly(sp.expand(expr), q)
        coeffs = np.array([float(v) for v in poly.all_coeffs()])
        if np.all(coeffs == 0):
            return [lo]
        coeffs = np.trim_zeros(coeffs, "f")
        for r in np.roots(coeffs) if len(coeffs) > 1 else []:
            if abs(r.imag) <= 1e-9 * (1 + abs(r)) and lo <= r.real <= hi:
                roots.append(float(r.real))
    else:
        c, s = sp.Symbol(f"c_{p}"), sp.Symbol(f"s_{p}")
        coeffs = _tau_coefficients(sp.expand(expr), c, s)
        if np.all(coeffs == 0):
            return [lo]
        coeffs = np.trim_zeros(coeffs, "f")
        cand = []
        for r in np.roots(coeffs) if len(coeffs) > 1 else []:
            if abs(r.imag) <= 1e-9 * (1 + abs(r)):
                cand.append(2 * np.arctan(r.real))
        at_pi = float(sp.expand(expr).subs({c: -1, s: 0}))
        if abs(at_pi) <= 1e-12 * (1 + np.abs(coeffs).max()):
            cand.append(np.pi)
        for a in cand:
            a = lo + np.mod(a - lo, 2 * np.pi)
            if a <= hi:
                roots.append(float(a))
    return sorted(roots)


def _tau_coefficients(e, c, s) -> np.ndarray:
    """Coefficients (highest first) of (1 + tau^2)^D e((1 - tau^2)/(1 + tau^2), 2 tau/(1 + tau^2)), D = deg e."""
    from numpy.polynomial import polynomial as npp

    if not (e.has(c) or e.has(s)):
        return np.array([float(e)])
    poly = sp.Poly(e, c, s)
    D = poly.total_degree()
    out = np.zeros(2 * D + 1)
    P1, P2, P3 = np.array([1.0, 0, -1]), np.array([0, 2.0]), np.array([1.0, 0, 1])  # low order first
    for (a, b), coef in poly.terms():
        term = npp.polymul(npp.polymul(npp.polypow(P1, a), npp.polypow(P2, b)), npp.polypow(P3, D - a - b))
        out[:len(term)] += float(coef) * term
    return out[::-1]


def _path_exprs_scaled(spec: PathSpec, center, h):
    exprs, unknowns, circles = _polynomial_form(spec)
    phi = [sp.expand((e - float(c)) / h) for e, c in zip(exprs, center)]
    return phi, unknowns, circles


def _lagrange_family(phi, unknowns, circles, seed=0) -> ManyTargetSolver:
    """The Lagrange system of min |w - phi(p)|^2 on {Q(w) = 0}, cubic coefficients as parameters."""
    from cdpr_algebra.homotopy.systems import PolynomialSystem

    w = sp.symbols("w1:4")
    lam = sp.Symbol("lam")
    cs = sp.symbols("k0:20")
    Q = sum(ck * w[0] ** i * w[1] ** j * w[2] ** k for ck, (i, j, k) in zip(cs, MONOMIALS))
    d = [w[k] - phi[k] for k in range(3)]
    eqs = [sp.expand(d[k] - lam * sp.diff(Q, w[k])) for k in range(3)] + [Q]
    pvars = []
    for u in unknowns:
        if len(u) == 1:
            dphi = [sp.diff(f, u[0]) for f in phi]
        else:
            c, s = u
            dphi = [-s * sp.diff(f, c) + c * sp.diff(f, s) for f in phi]
        eqs.append(sp.expand(sum(d[k] * dphi[k] for k in range(3))))
        pvars += list(u)
    eqs += circles
    system = PolynomialSystem(eqs, list(w) + [lam] + pvars, cs, name="cc_path_lagrange")
    return ManyTargetSolver(system, seed)


def _params_from(spec: PathSpec, xs):
    """Parameter values (list) from the polynomial unknowns of a solution (after w, lam)."""
    vals, k = [], 0
    for j, kind in enumerate(spec.kinds):
        if kind == "angular":
            vals.append(_angle(xs[k], xs[k + 1], spec.ranges[j][0]))
            k += 2
        else:
            vals.append(float(xs[k]))
            k += 1
    return vals


def crossings(robot, spec: PathSpec, cables, rotation=None, scale=None) -> list:
    """Where the CC's cubics vanish on the path: [(name, parameter values)] (name: cable index or 'singular')."""
    R = check_pose(robot, (0, 0, 0), rotation)[1]
    mid = [0.5 * (a + b) for a, b in spec.ranges]
    center = spec.point(*mid)
    h = robot.size / 10.0 if scale is None else scale
    coef, _ = polynomials_batch(robot, [center], [R], [tuple(cables)], h)
    phi, unknowns, _ = _path_exprs_scaled(spec, center, h)
    names = ["singular"] + list(cables)
    out = []
    for name, c in zip(names, coef[0]):
        Qp = _cubic_expr(c / np.abs(c).max(), phi)
        if len(spec.parameters) == 1:
            for r in _univariate(Qp, spec, 0):
                out.append((name, [r]))
        else:
            out += [(name, v) for v in _surface_zeros(Qp, spec, unknowns)]
    return out


def _surface_zeros(Qp, spec: PathSpec, unknowns):
    """Evidence that Q(f(u, v)) vanishes on the rectangle: zeros on the edges, or an interior critical point of
    the other sign than the edges.  Returns a list of parameter pairs (empty: no zero)."""
    found = []
    edge_vals = []
    for j in range(2):
        other = 1 - j
        if spec.closed(other):
            continue
        for end in spec.ranges[other]:
            sub = _fix_parameter(Qp, spec, unknowns, other, end)
            for r in _univariate(sub, spec, j):
                vals = [0.0, 0.0]
                vals[j], vals[other] = r, end
                found.append(vals)
    if found:
        return found
    # sign on the boundary (or anywhere, if both parameters are closed)
    g = sp.lambdify([v for u in unknowns for v in u], Qp, "numpy")
    ref = g(*_unknown_values(spec, [spec.ranges[0][0], spec.ranges[1][0]]))
    edge_vals.append(ref)
    # interior critical points of g over the rectangle (homotopy engine, total degree)
    from cdpr_algebra.homotopy.solve import solve
    from cdpr_algebra.homotopy.systems import PolynomialSystem

    xs = [v for u in unknowns for v in u]
    eqs = []
    for u in unknowns:
        if len(u) == 1:
            eqs.append(sp.expand(sp.diff(Qp, u[0])))
        else:
            c, s = u
            eqs.append(sp.expand(-s * sp.diff(Qp, c) + c * sp.diff(Qp, s)))
            eqs.append(c ** 2 + s ** 2 - 1)
    res = solve(PolynomialSystem(eqs, xs, (), name="cc_surface_critical"), seed=0)
    for sol in res.solutions:
        x = sol.x
        if np.abs(x.imag).max() > 1e-7 * (1 + np.abs(x).max()):
            continue
        vals = _params_from(spec, x.real)
        if _in_range(spec, vals) and np.sign(g(*x.real)) != np.sign(ref):
            found.append(vals)
    return found


def _unknown_values(spec: PathSpec, values):
    out = []
    for kind, v in zip(spec.kinds, values):
        out += [np.cos(v), np.sin(v)] if kind == "angular" else [v]
    return out


def _fix_parameter(expr, spec: PathSpec, unknowns, j, value):
    u = unknowns[j]
    if len(u) == 1:
        return sp.expand(expr.subs(u[0], value))
    return sp.expand(expr.subs({u[0]: float(np.cos(value)), u[1]: float(np.sin(value))}))


def _singular_points(C) -> list:
    """Real singular points (grad Q = 0 on Q = 0) of each cubic of C (K, 20): the mu = 0 endpoints of the pose
    distance homotopy of :mod:`cdpr_algebra.cc.radii` (any point would do as the pose; the origin is used)."""
    from .cubic_distances import distance_to_cubics

    out = []
    for cd in distance_to_cubics(np.atleast_2d(C)):
        out.append(np.array([p for p, k in zip(cd.points, cd.kinds) if k == "singular point"]).reshape(-1, 3))
    return out


def _point_path_distance(spec: PathSpec, phi, unknowns, z):
    """min over the path of |z - phi(p)| (scaled units) and the parameters attaining it: univariate/bivariate
    critical points plus end points (trajectories only; surfaces use their edges and a 2x2 solve)."""
    diff2 = sp.expand(sum((z[k] - phi[k]) ** 2 for k in range(3)))
    f = sp.lambdify([v for u in unknowns for v in u], diff2, "numpy")
    cands = []
    if len(spec.parameters) == 1:
        u = unknowns[0]
        if len(u) == 1:
            dd = sp.diff(diff2, u[0])
        else:
            dd = -u[1] * sp.diff(diff2, u[0]) + u[0] * sp.diff(diff2, u[1])
        cands += [[r] for r in _univariate(dd, spec, 0)]
        if not spec.closed(0):
            cands += [[spec.ranges[0][0]], [spec.ranges[0][1]]]
    else:
        # coarse but safe: the distance to a singular point is a rare candidate; take the min over edges and interior
        # critical points of |z - phi|^2 by the same machinery as the surface zeros
        from cdpr_algebra.homotopy.solve import solve
        from cdpr_algebra.homotopy.systems import PolynomialSystem

        xs = [v for uu in unknowns for v in uu]
        eqs = []
        for uu in unknowns:
            if len(uu) == 1:
                eqs.append(sp.expand(sp.diff(diff2, uu[0])))
            else:
                eqs.append(sp.expand(-uu[1] * sp.diff(diff2, uu[0]) + uu[0] * sp.diff(diff2, uu[1])))
                eqs.append(uu[0] ** 2 + uu[1] ** 2 - 1)
        for sol in solve(PolynomialSystem(eqs, xs, (), name="cc_point_surface"), seed=0).solutions:
            x = sol.x
            if np.abs(x.imag).max() <= 1e-7 * (1 + np.abs(x).max()):
                vals = _params_from(spec, x.real)
                if _in_range(spec, vals):
                    cands.append(vals)
        for j in range(2):
            other = 1 - j
            if spec.closed(other):
                continue
            for end in spec.ranges[other]:
                sub = _fix_parameter(diff2, spec, unknowns, other, end)
                u = unknowns[j]
                dd = sp.diff(sub, u[0]) if len(u) == 1 else -u[1] * sp.diff(sub, u[0]) + u[0] * sp.diff(sub, u[1])
                for r in _univariate(dd, spec, j):
                    vals = [0.0, 0.0]
                    vals[j], vals[other] = r, end
                    cands.append(vals)
                if not spec.closed(j):
                    for e2 in spec.ranges[j]:
                        vals = [0.0, 0.0]
                        vals[j], vals[other] = e2, end
                        cands.append(vals)
    best = (np.inf, None)
    for vals in cands:
        d = float(np.sqrt(max(f(*_unknown_values(spec, vals)), 0.0)))
        if d < best[0]:
            best = (d, vals)
    return best


def path_radii(robot, spec: PathSpec, cables, rotation=None, scale: float | None = None, seed: int = 0,
               _edge_of=None) -> PathRadii:
    """Seed 002 Sec. II-B.2 / II-B.3 for the 6-cable CC ``cables`` (0-based) along ``spec``.

    (``_edge_of``: internal, the surface's singular points in world coordinates when ``spec`` is one of its edges;
    the validity was checked on the surface.)"""
    t0 = time.perf_counter()
    R = check_pose(robot, (0, 0, 0), rotation)[1]
    cables = tuple(cables)
    if len(cables) != 6:
        raise CdprInputError("configuration", f"the index is defined for 6-cable configurations, got {len(cables)}")
    nparam = len(spec.parameters)
    start_vals = [a for a, _ in spec.ranges]
    tensions = configuration_tensions(robot, spec.point(*start_vals), cables, R)
    cross = crossings(robot, spec, cables, R, scale) if _edge_of is None else []
    valid = (tensions.valid and not cross) if _edge_of is None else True
    mid = [0.5 * (a + b) for a, b in spec.ranges]
    center = spec.point(*mid)
    h = robot.size / 10.0 if scale is None else float(scale)
    names = ["singular"] + list(cables)
    best = {nm: (np.inf, None) for nm in names}
    failed = 0

    def offer(nm, d, where):
        if d < best[nm][0]:
            best[nm] = (d, where)

    if valid:
        coef, _ = polynomials_batch(robot, [center], [R], [cables], h)
        C = coef[0] / np.abs(coef[0]).max(axis=1)[:, None]
        phi, unknowns, circles = _path_exprs_scaled(spec, center, h)
        fam = _lagrange_family(phi, unknowns, circles, seed)
        sols = fam.solve(C)
        phif = sp.lambdify([v for u in unknowns for v in u], phi, "numpy")
        for nm, (X, nf) in zip(names, sols):
            failed += nf
            for x in X:
                vals = _params_from(spec, x[4:])
                if not _in_range(spec, vals):
                    continue
                pp = np.array(phif(*x[4:]), dtype=float)
                offer(nm, h * float(np.linalg.norm(x[:3] - pp)),
                      {"parameters": vals, "path_point": center + h * pp, "surface_point": center + h * x[:3],
                       "source": "interior"})
        # singular points of the surfaces (world coordinates; computed once for a surface and its edges)
        sing_world = _edge_of if _edge_of is not None else \
            {nm: center + h * pts for nm, pts in zip(names, _singular_points(C))}
        for nm in names:
            for zw in sing_world[nm]:
                d, vals = _point_path_distance(spec, phi, unknowns, (zw - center) / h)
                if vals is not None:
                    offer(nm, h * d, {"parameters": vals, "path_point": spec.point(*vals),
                                      "surface_point": zw, "source": "singular point"})
        # boundary: end points / edges / corners
        if nparam == 1:
            if not spec.closed(0):
                ends = [[spec.ranges[0][0]], [spec.ranges[0][1]]]
                rad = cc_radii_many(robot, [(spec.point(*e), cables, R) for e in ends], seed=seed)
                for e, rr in zip(ends, rad):
                    failed += rr.failed_paths
                    for nm in names:
                        d = rr.singular if nm == "singular" else rr.radii[nm]
                        offer(nm, d, {"parameters": e, "path_point": rr.position,
                                      "surface_point": rr.points[nm], "source": "end point"})
        else:
            for j in range(2):
                other = 1 - j
                if spec.closed(other):
                    continue
                for end in spec.ranges[other]:
                    sub = _edge_spec(spec, other, end)
                    er = path_radii(robot, sub, cables, R, scale, seed, _edge_of=sing_world)
                    failed += er.failed_paths
                    for nm in names:
                        d = er.singular if nm == "singular" else er.radii[nm]
                        offer(nm, d, _edge_where(er, nm, j, other, end))
    radii = {c: best[c][0] for c in cables}
    sing = best["singular"][0]
    lim = min(names, key=lambda nm: best[nm][0])
    index = best[lim][0] if valid else 0.0
    where = best[lim][1] or {}
    return PathRadii(cables, spec, valid, tuple(_fmt_cross(cr) for cr in cross), radii, sing, index,
                     lim, where, failed, time.perf_counter() - t0, tensions.tensions, {nm: best[nm][1] for nm in names})


def _fmt_cross(cr):
    name, vals = cr
    return {"cubic": "singular" if name == "singular" else int(name) + 1, "parameters": [float(v) for v in vals]}


def _edge_spec(spec: PathSpec, j: int, value: float) -> PathSpec:
    """The trajectory obtained by fixing parameter j of a surface at ``value`` (parameter renamed t)."""
    keep = 1 - j
    t = sp.Symbol("t", real=True)
    exprs = tuple(e.subs(spec.parameters[j], value).subs(spec.parameters[keep], t) for e in spec.expressions)
    return PathSpec(exprs, (t,), (spec.ranges[keep],), (spec.kinds[keep],), spec.option)


def _edge_where(er: PathRadii, nm, j, other, end):
    w = (er.where_by_name or {}).get(nm)
    if not w:
        return {"source": "edge"}
    vals = [0.0, 0.0]
    vals[j], vals[other] = w["parameters"][0], end
    src = "corner" if w.get("source") == "end point" else "edge"
    return {"parameters": vals, "path_point": w["path_point"], "surface_point": w["surface_point"], "source": src}


def path_configurations(robot, spec: PathSpec, rotation=None, cables=None, seed: int = 0) -> list[PathRadii]:
    """The 6-cable CCs valid over the whole path (candidates: those valid at the start), each with its index,
    ranked by index (larger first).  With ``cables`` (1-based numbers), only that CC (valid or not)."""
    R = check_pose(robot, (0, 0, 0), rotation)[1]
    if cables is not None:
        S = parse_cables(robot, cables, "cables", size=6)
        return [path_radii(robot, spec, S, R, seed=seed)]
    start = spec.point(*[a for a, _ in spec.ranges])
    cands = [c.cables for c in valid_configurations(robot, start, R, sizes=[6])]
    out = []
    for S in cands:
        if crossings(robot, spec, S, R):
            continue
        out.append(path_radii(robot, spec, S, R, seed=seed))
    return sorted(out, key=lambda r: -r.index)
