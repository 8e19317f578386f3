"""Interval certificates of the reported equilibria (issue 5): existence and uniqueness of the root in a tight box,
and the consequences proven over that box (tension signs, slack cables, pose, class of the reduced Hessian).

Square systems certified (all quadratic, world coordinates of the robot file; :func:`taut_system`):

* **DGP, m = 2..6 taut cables**: exactly the equations of :mod:`cdpr_algebra.model.taut_equations` (unknowns x = (p, u, v, w, lam),
  R = [u v w], lam_i = tau_i / rho_i: rotation (6), cable lengths (m), force balance (3), moments about the world
  origin (3)).
* **DGP, m = 1**: the equilibria form a circle (the platform turns freely about the cable, which lies along the
  load), so the 13 x 13 system of the same form is singular everywhere.  Square sub-formulation: the moment
  component along the load direction d is dropped (given force balance the cable is parallel to d, so the moment
  is Q (G - B_i) x d, always orthogonal to d; two moment components along e1, e2 with (e1, e2, d) independent are
  equivalent to all three), and the turning angle is fixed by the gauge t . (R c) = 0, c a platform vector
  orthogonal to g' - b_i', t = d x (R0 c) for the reported rotation R0.  It certifies the reported point of the
  circle (the middle of the feasible arc), not the whole arc.
* **IGP with assigned orientation** (seed 004 Sec. 3): unknowns (p, lam), R given: force and moment balance
  (6 equations).
* **IGP with assigned position** (seed 004 Sec. 4): unknowns (u, v, w, lam), G given (platform frame moved to G:
  b_i' - g', g' = 0): rotation (6) and balance (6).  Rotation matrix entries instead of Euler parameters: every
  orientation, half-turns (e0 = 0) included, is a regular point of this chart, so no branch is special.

Existence and uniqueness: Krawczyk test with epsilon-inflation (:func:`cdpr_algebra.intervals.balls.krawczyk_certify`) in a box of
width <= 1e-9 relative to the scale of each unknown (L = robot.cable_scale for positions, 1 for rotation entries,
Q / L for lam; positions and lam at least as large as the root's, :func:`_scales`).  DGP roots are certified with
the world origin at the base points' centroid and the platform frame at the platform points' centroid
(:attr:`cdpr_algebra.model.robot.Robot.cable_frame`: an equivalent system, since given force balance moments about c
are moments about the world origin minus c x the load; in the robot's own frames a pose far from the world origin,
or attachment points far from the platform frame's origin, multiply the rotation's and tensions' rounding by those
distances: a platform 1e4 sizes from its frame's origin, tests/large_forces.py, was not certified at any box width),
tried at 53 bits and then at 128 bits with Newton steps in ball arithmetic; a root that
doubles cannot locate within the box (condition numbers of 1e9 and more) is polished first
(:func:`polished_taut_root`) and the DGP reports the polished root.  The roots of the IGP with assigned position are
certified together by compiled Krawczyk rounds (:func:`certify_igp_positions`: the rows and columns of the
system above taken from the generated interval evaluator of the taut system, in outward-rounded double-precision
interval arithmetic, :func:`cdpr_algebra.intervals.real_krawczyk.certify_real_roots`).  Over the certified box, in outward-rounded ball arithmetic (python-flint arb):

* tensions tau_i = lam_i rho_i (IGP: rho_i = |B_i - A_i| enclosed too); sign 'positive', 'negative', or
  'boundary' when the enclosure contains 0 (a tension zero within rounding is never reported as positive; the IGP
  with assigned position proves some of them exactly 0 afterwards, :mod:`.zero_tension`);
* every slack cable j: |B_j - A_j| - rho_j enclosed, slack proven when its upper end is < 0;
* pose: p and R enclosed;
* class of H_r = N^T H N (seed 000 eqs. 28-30, :mod:`cdpr_algebra.model.stability`) from the bordered matrix
  K = [[T H T, T J^T D], [D J T, 0]] (T = diag(1, 1, 1, 1/L, 1/L, 1/L), D = Q / L^2 I, positive scalings): when J
  has full row rank m, In(K) = In(H_r) + (m, m, 0) (N. Gould, Math. Programming 32, 1985), and a nonsingular K
  forces full row rank.  The inertia of K is proven by :func:`cdpr_algebra.intervals.balls.symmetric_inertias`
  (Gershgorin discs of V^T K V, with V the floating-point eigenvectors of mid K, enclosed in floating point with
  a priori rounding bounds; Sylvester's law; the matrices of several roots at once).  A proven inertia gives the
  class '>', '<' or '<>'; a singular H_r ('>=', '<=', e.g. every m = 1 equilibrium, neutral about the cable) is
  'undecided'.

``certified`` is True when existence and uniqueness, every tension sign and every slack cable are proven.
"""

from __future__ import annotations

import threading
from dataclasses import dataclass, field, replace

import numpy as np
from flint import arb, arb_mat

from cdpr_algebra.generated.taut_equations import taut_equations, taut_residual
from cdpr_algebra.model.rod_equations import BINARY
from cdpr_algebra.model.taut_equations import decode, encode, from_cable_frame, to_cable_frame
from cdpr_algebra.intervals.balls import KrawczykResult, bounds, krawczyk_certify, sign, symmetric_inertias
from cdpr_algebra.report.jsonable import jsonable

BOX_RTOL = 1e-9  # max width of the certified box relative to the scale of each unknown
FLINT = threading.RLock()  # python-flint's working precision is global to the process: one thread at a time uses it

# unknowns of the taut system
_P, _U, _V, _W, _LAM = 0, 3, 6, 9, 12


# ------------------------------------------------------------------------------------------ system
def _skew_rows(a):
    """Rows of skew(a) (the operator a x)."""
    return ((0, -a[2], a[1]), (a[2], 0, -a[0]), (-a[1], a[0], 0))


def taut_system(x, A, b, g, f, rho2=None, jacobian: bool = True):
    """F(x) and dF/dx of :func:`cdpr_algebra.model.taut_equations.taut_family` in plain arithmetic (floats, arb balls,
    ...): the generated :func:`cdpr_algebra.generated.taut_equations.taut_equations` on numpy object arrays.

    x = (p, u, v, w, lam_1..lam_m); A, b: m points (world exit points, platform anchors), g: g', f: Q d;
    ``rho2``: the m squared lengths, or None to leave the length equations out (IGP).  Rows: u.u - 1, v.v - 1,
    u.v, w - u x v, [|B_i - A_i|^2 - rho_i^2], sum lam_i (A_i - B_i) + f, sum lam_i B_i x A_i + G x f.
    ``jacobian=False`` returns (F, None).
    """
    m = len(A)
    if rho2 is not None:
        return parameter_taut_system(x, _parameters(A, b, g, f, rho2), jacobian)
    n = 12 + m
    F, J = _evaluate(list(x), _parameters(A, b, g, f, rho2), n, jacobian)
    rows = [r for r in range(n) if not 6 <= r < 6 + m]
    Fl = [F[r] for r in rows]
    if not jacobian:
        return Fl, None
    return Fl, [list(J[r]) for r in rows]


def parameter_taut_system(x, p, jacobian: bool = True):
    """:func:`taut_system` (every row) at the family's parameter vector p = (A_i, rho_i^2, b'_i, g', Q d) of
    :func:`cdpr_algebra.model.taut_equations.taut_family`, entries in any plain arithmetic (e.g. acb balls)."""
    n = len(x)
    F, J = _evaluate(list(x), list(p), n, jacobian)
    return list(F), None if not jacobian else [list(row) for row in J]


def _parameters(A, b, g, f, rho2=None):
    """The parameter vector of the generated evaluator (rho2 None: zeros, the length rows then unused)."""
    return ([c for a in A for c in a] + (list(rho2) if rho2 is not None else [0] * len(A))
            + [c for bi in b for c in bi] + list(g) + list(f))


def _evaluate(x, p, n, jacobian: bool = True):
    """F and J (object arrays, J zero outside its pattern; None without ``jacobian``) of the generated evaluators."""
    F = np.zeros(n, dtype=object)
    if not jacobian:
        taut_residual(x, p, F)
        return F, None
    J = np.zeros((n, n), dtype=object)
    taut_equations(x, p, None, F, J, None, False)
    return F, J


def _select(F, J, rows, cols):
    return [F[i] for i in rows], None if J is None else [[J[i][j] for j in cols] for i in rows]


# ------------------------------------------------------------------------------------- certificate
@dataclass(frozen=True)
class Certificate:
    """What was proven about one reported root (see the module docstring).

    ``box_width``: max width of the certified unknown box in world length units (each width divided by the scale
    of its unknown, times L); ``tension_lower/upper``: n values, 0 for slack cables; ``tension_signs``: per
    cable 'positive' | 'negative' | 'boundary' (enclosure contains 0) | 'zero' (proven exactly 0: the IGP with
    assigned position, :mod:`.zero_tension`) | 'slack' (not in the taut set) | 'unknown' (existence not proven);
    ``slack_margin_lower/upper``: enclosure of |B_j - A_j| - rho_j (NaN for taut cables); ``slack_proven``: every
    slack cable proven slack (vacuously True without slack cables); ``hessian``: 'proven' (``hessian_class`` is
    then the proven class '>', '<' or '<>'; for one taut cable '>=', '<=' or '<>': the spin about the cable line is
    an exact zero of H_r, :func:`_with_neutral_spin`) or 'undecided'.  Enclosures are NaN when existence was not
    proven.
    """

    certified: bool
    reason: str | None
    problem: str
    box_width: float
    position_lower: np.ndarray
    position_upper: np.ndarray
    rotation_lower: np.ndarray
    rotation_upper: np.ndarray
    tension_lower: np.ndarray
    tension_upper: np.ndarray
    tension_signs: tuple
    slack_margin_lower: np.ndarray
    slack_margin_upper: np.ndarray
    slack_proven: bool
    hessian: str
    hessian_class: str | None = None
    exists_unique: bool = False
    iterations: int = 0
    newton_step: float = float("nan")
    extra: dict = field(default_factory=dict)

    def to_dict(self) -> dict:
        """JSON-ready; NaN (not proven, or not applicable) becomes None."""
        return _no_nan(jsonable({
            "certified": self.certified, "reason": self.reason, "problem": self.problem,
            "exists_unique": self.exists_unique, "box_width": self.box_width,
            "position_lower": self.position_lower, "position_upper": self.position_upper,
            "rotation_lower": self.rotation_lower, "rotation_upper": self.rotation_upper,
            "tension_lower": self.tension_lower, "tension_upper": self.tension_upper,
            "tension_signs": list(self.tension_signs),
            "slack_margin_lower": self.slack_margin_lower, "slack_margin_upper": self.slack_margin_upper,
            "slack_proven": self.slack_proven, "hessian": self.hessian, "hessian_class": self.hessian_class,
            "krawczyk_iterations": self.iterations, "newton_step": self.newton_step, **self.extra,
        }))


def _no_nan(v):
    if isinstance(v, float) and v != v:
        return None
    if isinstance(v, list):
        return [_no_nan(x) for x in v]
    if isinstance(v, dict):
        return {k: _no_nan(x) for k, x in v.items()}
    return v


def _nan(*shape):
    return np.full(shape, np.nan)


def _failed(problem, n, reason, kr, taut) -> Certificate:
    signs = tuple("slack" if j not in taut else "unknown" for j in range(n))
    return Certificate(False, reason, problem, float("nan"), _nan(3), _nan(3), _nan(3, 3), _nan(3, 3), _nan(n),
                       _nan(n), signs, _nan(n), _nan(n), False, "undecided", None, False,
                       kr.iterations if kr else 0, kr.newton_step if kr else float("nan"))


def _vec_sub(a, b):
    return [a[k] - b[k] for k in range(3)]


def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def _cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def _bordered_matrix(A, B, G, lam, L, Q):
    """K = [[T H T, T J^T D], [D J T, 0]] in balls (lists of rows); H of seed 000 eq. (29) with tau_i/rho_i = lam_i,
    J rows [s_i, r_i x s_i] (eq. 30 without the positive factors 1/rho_i, which do not change the inertia)."""
    m = len(A)
    n = 6 + m
    zero = arb(0)
    K = [[zero] * n for _ in range(n)]
    r = [_vec_sub(Bi, G) for Bi in B]
    ga = [_vec_sub(G, Ai) for Ai in A]
    sig = sum(lam, zero)
    iL = arb(1) / L
    iL2 = iL * iL
    for k in range(3):
        K[k][k] = sig
    # sum_i lam_i skew(r_i) = skew(sum_i lam_i r_i)
    S = _skew_rows([sum((lam[i] * r[i][k] for i in range(m)), zero) for k in range(3)])
    for a in range(3):
        for c in range(3):
            K[a][3 + c] = -S[a][c] * iL
            K[3 + a][c] = S[a][c] * iL
    rg = [_dot(r[i], ga[i]) for i in range(m)]
    for a in range(3):
        for c in range(a, 3):  # symmetric
            h = sum((lam[i] * (0.5 * (ga[i][a] * r[i][c] + r[i][a] * ga[i][c]) - (rg[i] if a == c else 0))
                     for i in range(m)), zero)
            K[3 + a][3 + c] = K[3 + c][3 + a] = h * iL2
    D = arb(Q) * iL2
    for i in range(m):
        s = _vec_sub(B[i], A[i])
        rs = _cross(r[i], s)
        row = [s[k] * D for k in range(3)] + [rs[k] * iL * D for k in range(3)]
        K[6 + i][:6] = row
        for j in range(6):
            K[j][6 + i] = row[j]
    return K


def _hessian_class(inertia, borders) -> tuple[str, str | None]:
    """('proven', class) with class '>', '<' or '<>' of the reduced Hessian, or ('undecided', None), from the
    inertia of the bordered matrix K of the m taut cables (None: not proven, or no taut cable); ``borders`` = (m,
    neutral): with ``neutral`` K is bordered once more by the exact zero direction of H_r
    (:func:`_with_neutral_spin`), and the classes are '>=', '<=' or '<>' (that zero eigenvalue included)."""
    m, neutral = borders
    if inertia is None:
        return "undecided", None
    pos, neg = inertia[0] - m - neutral, inertia[1] - m - neutral
    if pos < 0 or neg < 0:  # impossible with full row rank; be safe
        return "undecided", None
    if neg == 0:
        return "proven", ">=" if neutral else ">"
    if pos == 0:
        return "proven", "<=" if neutral else "<"
    return "proven", "<>"


def _with_neutral_spin(K, A, B, L):
    """K of one taut cable (7 x 7, coordinates (dG, L dtheta, multiplier)) bordered by the spin about the cable line,
    w = (0, L (A - B), 0).  Why it is an exact zero of H_r: with one cable of nonzero tension, moment balance puts G
    on the cable line, so turning the platform about that line moves neither B (|B - A| is kept) nor G (the
    potential is kept): every such pose is an equilibrium.  With H_r = H' (+) 0 on span(w) (+) its complement,
    inertia(bordered K) = inertia(H') + (m + 1, m + 1, 0): proving it proves H_r's class with that one zero.  The
    enclosure of A - B contains the true direction, so the proof covers the true matrix."""
    zero = arb(0)
    w = [zero] * 3 + [c * L for c in _vec_sub(A, B)] + [zero]
    return [row + [w[i]] for i, row in enumerate(K)] + [w + [zero]]


def _robot_balls(robot, frame=None, reading: str = BINARY):
    """(A_i, b'_i, g') of all n cables as balls: exact, or in the ``frame`` (c, cb) of :attr:`Robot.cable_frame`
    (A_i - c, b'_i - cb, g' - cb, the differences enclosed); ``reading``: as in :func:`_robot_data`."""
    return _robot_data(robot, range(robot.n), arb, frame=frame, reading=reading)[:3]


def _consequences(problem, robot, taut, lengths, p, R, lam, kr, rel_width, L, extra=None, frame=None,
                  reading: str = BINARY) -> Certificate:
    """Certificate from the certified enclosures: p (3 balls), R (3 x 3 balls), lam (m balls) of the taut cables.
    ``lengths``: all n lengths (floats) or None (IGP: lengths of the taut cables enclosed from the box);
    ``L``: robot.cable_scale; ``frame``: p is the platform-frame origin in the frame (c, cb) of
    :attr:`Robot.cable_frame` (the robot's position c + p - R cb is enclosed for the certificate); ``reading``: the
    robot's doubles or its decimals (:func:`_robot_data`)."""
    balls, position = None, None
    if frame is not None or reading != BINARY:
        balls = _robot_balls(robot, frame, reading)
    if frame is not None:
        c, cb = (list(map(float, v)) for v in frame)
        position = [arb(c[k]) + p[k] - (R[k][0] * cb[0] + R[k][1] * cb[1] + R[k][2] * cb[2]) for k in range(3)]
    return _finish([_enclosures(problem, robot, taut, lengths, p, R, lam, kr, rel_width, L, extra, balls,
                                position)])[0]


def _finish(parts) -> list:
    """Certificates from :func:`_enclosures` results, the inertias of their bordered matrices proven at once."""
    todo = [k for k, (_, K, _) in enumerate(parts) if K is not None]
    inertias = dict(zip(todo, symmetric_inertias([parts[k][1] for k in todo])))
    return [Certificate(**fields, **dict(zip(("hessian", "hessian_class"), _hessian_class(inertias.get(k), borders))))
            for k, (fields, _, borders) in enumerate(parts)]


def boundary_reason(i: int) -> str:
    """The certificate's reason for the 0-based cable i whose tension enclosure contains 0."""
    return f"tension {i + 1} is a boundary case (its enclosure contains 0)"


def _enclosures(problem, robot, taut, lengths, p, R, lam, kr, rel_width, L, extra=None, balls=None, position=None):
    """The fields of the certificate of :func:`_consequences` but the Hessian's, the bordered matrix K (None
    without taut cables; bordered by the spin about the cable line for one taut cable of nonzero tension) and
    (m, that bordering); ``balls``: :func:`_robot_balls` when already made (in the frame of p);
    ``position``: the enclosure of the platform-frame origin reported (default p)."""
    n = robot.n
    A, bp, gp = balls or _robot_balls(robot)

    def body(c):
        return [p[k] + R[k][0] * c[0] + R[k][1] * c[1] + R[k][2] * c[2] for k in range(3)]

    Bs = [body(bp[j]) for j in range(n)]
    G = body(gp)
    reasons = []
    tau = [arb(0)] * n
    signs = ["slack"] * n
    for k, i in enumerate(taut):
        s_i = _vec_sub(Bs[i], A[i])
        rho_i = arb(float(lengths[i])) if lengths is not None else _dot(s_i, s_i).sqrt()
        tau[i] = lam[k] * rho_i
        signs[i] = sign(tau[i])
        if signs[i] == "boundary":
            reasons.append(boundary_reason(i))
    t_lo, t_hi = bounds(tau)
    s_lo, s_hi = _nan(n), _nan(n)
    slack_ok = True
    for j in range(n):
        if j in taut:
            continue
        d = _vec_sub(Bs[j], A[j])
        margin = _dot(d, d).sqrt() - float(lengths[j])
        (s_lo[j],), (s_hi[j],) = bounds([margin])
        if not margin < 0:
            slack_ok = False
            reasons.append(f"cable {j + 1} not proven slack (|B - A| - rho in [{s_lo[j]:.3g}, {s_hi[j]:.3g}])")
    m = len(taut)
    K = _bordered_matrix([A[i] for i in taut], [Bs[i] for i in taut], G, list(lam), L, robot.load) if m else None
    neutral = m == 1 and signs[taut[0]] in ("positive", "negative")  # the spin is a zero of H_r only then
    if neutral:
        K = _with_neutral_spin(K, A[taut[0]], Bs[taut[0]], L)
    p_lo, p_hi = bounds(p if position is None else position)
    R_lo, R_hi = bounds(R)
    fields = dict(certified=not reasons, reason="; ".join(reasons) or None, problem=problem, box_width=rel_width * L,
                  position_lower=p_lo, position_upper=p_hi, rotation_lower=R_lo, rotation_upper=R_hi,
                  tension_lower=t_lo, tension_upper=t_hi, tension_signs=tuple(signs), slack_margin_lower=s_lo,
                  slack_margin_upper=s_hi, slack_proven=slack_ok, exists_unique=True, iterations=kr.iterations,
                  newton_step=kr.newton_step, extra=extra or {})
    return fields, K, (m, neutral)


def _scales(robot, m, cols, L, x=None):
    """Scale of each unknown (p, u, v, w, lam) in ``cols``: L, 1, Q / L; with the root's values ``x`` (one per
    column), positions at least max |p_k| and multipliers at least max |lam_k|: a floating-point root is only known
    relative to its size (a pose far from the world origin, tensions 1e5 times the load), so a box of width 1e-9
    L or 1e-9 Q / L around it may hold no zero that floats can locate."""
    cols = list(cols)
    s = np.array([L] * 3 + [1.0] * 9 + [robot.load / L] * m)[cols]
    if x is not None:
        x = np.abs(np.asarray(x, dtype=float))
        for group in ([k for k, c in enumerate(cols) if c < _U], [k for k, c in enumerate(cols) if c >= _LAM]):
            if group:
                s[group] = np.maximum(s[group], x[group].max())
    return s


# --------------------------------------------------------------------------------------------- DGP
def _robot_data(robot, taut, num, com_at_origin: bool = False, frame=None, reading: str = BINARY):
    """(A, b, g, f) of the taut cables with numbers made by ``num`` (arb: exact balls; float).
    ``com_at_origin``: platform frame moved to G (b_i' - g', g' = 0; the difference is enclosed for arb);
    ``frame``: (c, cb) of :attr:`Robot.cable_frame`, world origin moved to c and platform frame to cb; ``reading``
    DECIMAL: b_i' and g' as the decimals that print them (``num`` of the repr string: arb encloses it)."""
    c, cb = frame if frame is not None else (np.zeros(3), np.zeros(3))
    point = (lambda v: num(float(v))) if reading == BINARY else (lambda v: num(repr(float(v))))
    A = [[num(float(v)) - num(float(c[k])) for k, v in enumerate(robot.base[i])] for i in taut]
    g = [point(v) - num(float(cb[k])) for k, v in enumerate(robot.com)]
    b = [[point(v) - num(float(cb[k])) for k, v in enumerate(robot.platform[i])] for i in taut]
    if com_at_origin:
        b = [[bi[k] - g[k] for k in range(3)] for bi in b]
        g = [num(0.0)] * 3
    f = [num(robot.load) * float(c) for c in robot.load_direction]
    return A, b, g, f


def _krawczyk(make_system, x0, scale, box_rtol, refine=0):
    """Krawczyk certification of the system built by ``make_system(num) -> system(x, jacobian) -> (F, J)``
    (``num`` = arb for the rigorous evaluators, float for the approximate inverse and Newton step; ``refine``:
    see :func:`cdpr_algebra.intervals.balls.krawczyk_certify`)."""
    sa, sf = make_system(arb), make_system(float)
    return krawczyk_certify(lambda x: sa(x, False)[0], lambda x: sa(x, True)[1], x0, scale, box_rtol,
                            F_float=lambda x: sf(x.tolist(), False)[0], J_float=lambda x: sf(x.tolist(), True)[1],
                            refine=refine)


def certify_taut_root(robot, lengths, cables, position, rotation, tensions, box_rtol: float = BOX_RTOL,
                      reading: str = BINARY) -> Certificate:
    """Certificate of one DGP root with the 0-based taut ``cables`` (m = 1..6), cable ``lengths`` (all n, None:
    the robot's), pose (``position`` of the platform-frame origin, ``rotation``) and the m taut ``tensions``.
    Computed at python-flint's default 53 bits, holding :data:`FLINT` (the working precision is global to the
    process: a 256-bit ball retry in another thread would otherwise change this certificate's boxes).  A root whose
    existence is not proven there is tried again at :data:`RETRY_PREC` bits with the Newton step computed in ball
    arithmetic (``refine`` of :func:`cdpr_algebra.intervals.balls.krawczyk_certify`; the extra field
    ``precision_bits`` says so): on an ill-conditioned system (large internal forces, condition numbers 1e7-1e10)
    the residual in doubles is noise.  Either way the given root must lie within the box tolerance of the proven
    zero; a root that doubles could not locate that well is first polished by :func:`polished_taut_root`.
    ``reading`` DECIMAL: a root of the robot read in decimal (:func:`_robot_data`; ``extra.reading`` says so)."""
    from flint import ctx

    with FLINT, ctx.workprec(53):
        cert = _certify_taut_root(robot, lengths, cables, position, rotation, tensions, box_rtol, reading=reading)
    if cert.exists_unique:
        return cert
    with FLINT, ctx.workprec(RETRY_PREC):
        retry = _certify_taut_root(robot, lengths, cables, position, rotation, tensions, box_rtol, REFINE_STEPS,
                                   reading)
    if not retry.exists_unique:
        return cert
    return replace(retry, extra={**retry.extra, "precision_bits": RETRY_PREC})


RETRY_PREC = 128  # bits of the second attempt of certify_taut_root and of polished_taut_root
REFINE_STEPS = 8  # Newton steps in ball arithmetic
POLISH_RTOL = 1e-3  # largest move of polished_taut_root, relative to the scale of each unknown (_scales): as BALL_MAX_MOVE


def polished_taut_root(robot, lengths, cables, position, rotation, tensions, max_move: float = POLISH_RTOL,
                       reading: str = BINARY):
    """(position, rotation, m tensions) of the root of the DGP system of the 0-based taut ``cables`` near the given
    one, by Newton's method with the residual in :data:`RETRY_PREC`-bit ball arithmetic in the cable frame
    (:func:`cdpr_algebra.intervals.balls.refined_root`), rounded to doubles; None when it does not converge or moves
    by more than ``max_move`` of the scale of an unknown.  Nothing is proven here: certify the result.  Doubles
    locate a root only to about its condition number times 1e-16 of its size (measured on robots with internal
    forces 1e3-1e4 times the load: moves of 1e-9 to 1.2e-7), too far for a certificate of width 1e-9."""
    from flint import ctx

    from cdpr_algebra.intervals.balls import refined_root

    problem = _taut_problem(robot, lengths, cables, position, rotation, tensions, reading)
    if isinstance(problem, Certificate):
        return None
    x0, make_system, scale, frame, rho, taut = problem
    sf = make_system(float)
    try:
        C = np.linalg.inv(np.asarray(sf(x0.tolist(), True)[1], dtype=float))
    except np.linalg.LinAlgError:
        return None
    with FLINT, ctx.workprec(RETRY_PREC):
        sa = make_system(arb)
        y = refined_root(lambda x: sa(x, False)[0], C, x0, scale, REFINE_STEPS)
    if y is None or not np.all(np.abs(y - x0) <= max_move * scale):
        return None
    p, R, lam = decode(from_cable_frame(y[None], frame), len(taut))
    return p[0], R[0], lam[0] * rho[taut]


def _taut_problem(robot, lengths, cables, position, rotation, tensions, reading: str = BINARY):
    """(x0, make_system, scale, frame, rho, taut) of the DGP root in the cable frame (:attr:`Robot.cable_frame`), or the
    failed Certificate of a taut set without isolated roots."""
    rho = np.asarray(robot.lengths if lengths is None else lengths, dtype=float)
    taut = [int(c) for c in cables]
    m = len(taut)
    tensions = np.asarray(tensions, dtype=float).ravel()
    if tensions.shape != (m,) or not 1 <= m <= 6:
        raise ValueError(f"expected 1..6 taut cables and one tension per taut cable, got {m} cables and "
                         f"{tensions.shape} tensions")
    frame = robot.cable_frame
    R0 = np.asarray(rotation, float)
    x0 = to_cable_frame(encode(np.asarray(position, float), R0, tensions / rho[taut])[None], frame)[0]
    if m >= 2:
        def make_system(num):
            A, b, g, f = _robot_data(robot, taut, num, frame=frame, reading=reading)
            rho2 = [num(float(rho[i])) ** 2 for i in taut]
            return lambda x, jac: taut_system(x, A, b, g, f, rho2, jac)
    else:
        gauge = _one_cable_gauge(robot, taut[0], R0)
        if gauge is None:
            return _failed("dgp", robot.n, "G coincides with the cable anchor: the equilibria of this taut set form "
                                           "a 3-dof family, no isolated root to certify", None, taut)

        def make_system(num):
            A, b, g, f = _robot_data(robot, taut, num, frame=frame, reading=reading)
            return _gauged_system(A, b, g, f, [num(float(rho[taut[0]])) ** 2], *gauge)
    return x0, make_system, _scales(robot, m, range(12 + m), robot.cable_scale, x0), frame, rho, taut


def _certify_taut_root(robot, lengths, cables, position, rotation, tensions, box_rtol, refine=0,
                       reading: str = BINARY):
    problem = _taut_problem(robot, lengths, cables, position, rotation, tensions, reading)
    if isinstance(problem, Certificate):
        return problem
    x0, make_system, scale, frame, rho, taut = problem
    kr = _krawczyk(make_system, x0, scale, box_rtol, refine)
    if not kr.proven:
        return _failed("dgp", robot.n, kr.reason, kr, taut)
    X = kr.enclosure
    R = [[X[_U + k], X[_V + k], X[_W + k]] for k in range(3)]
    return _consequences("dgp", robot, taut, rho, X[0:3], R, X[12:], kr, kr.relative_width(scale),
                         robot.cable_scale, extra=None if reading == BINARY else {"reading": reading}, frame=frame,
                         reading=reading)


def _one_cable_gauge(robot, i, R0):
    """(e1, e2, c, t) of the m = 1 formulation (module docstring), or None when G is at the anchor B_i."""
    gb = robot.com - robot.platform[i]
    if np.linalg.norm(gb) <= 1e-12 * robot.size:
        return None
    return _turning_gauge(robot.load_direction, gb, R0)


def _turning_gauge(a, arm, R0):
    """(e1, e2, c, t) of :func:`_gauged_system` for turns about the unit world axis ``a`` of the platform's line along
    ``arm``: e1, e2 orthogonal to a and c to arm (unit vectors), t = a x (R0 c) normalized."""
    e1, c = (np.cross(v, np.eye(3)[int(np.argmin(np.abs(v)))]) for v in (a, arm))
    e1, c = e1 / np.linalg.norm(e1), c / np.linalg.norm(c)
    t = np.cross(a, R0 @ c)
    return tuple(v.tolist() for v in (e1, np.cross(a, e1), c, t / np.linalg.norm(t)))


def _gauged_system(A, b, g, f, rho2, e1, e2, c, t):
    """Square system of a taut set whose equilibria turn about an axis (m = 1: the cable; m >= 2: the line of the
    taut anchors and G, :mod:`.families`): rotation (6), lengths (m), force (3), moments along e1, e2, t . (R c) = 0."""
    k0, n = 9 + len(A), 12 + len(A)  # rows of taut_system: rotation 0-5, lengths, force, then the moment at k0

    def system(x, jac=True):
        F, J = taut_system(x, A, b, g, f, rho2, jac)
        Fs = F[:k0] + [sum(e_[k] * F[k0 + k] for k in range(3)) for e_ in (e1, e2)]
        Rc = [c[0] * x[_U + k] + c[1] * x[_V + k] + c[2] * x[_W + k] for k in range(3)]
        Fs.append(sum(t[k] * Rc[k] for k in range(3)))
        if not jac:
            return Fs, None
        Js = J[:k0] + [[sum(e_[k] * J[k0 + k][j] for k in range(3)) for j in range(n)] for e_ in (e1, e2)]
        r = [0] * n
        for k in range(3):
            r[_U + k], r[_V + k], r[_W + k] = c[0] * t[k], c[1] * t[k], c[2] * t[k]
        Js.append(r)
        return Fs, Js

    return system


def certify_taut_roots(robot, lengths, roots, box_rtol: float = BOX_RTOL) -> list:
    """:func:`certify_taut_root` over many roots: ``roots`` = iterable of (cables, position, rotation, tensions)."""
    return [certify_taut_root(robot, lengths, c, p, R, t, box_rtol) for c, p, R, t in roots]


def certify_dgp_solutions(robot, solutions, lengths=None, box_rtol: float = BOX_RTOL) -> list:
    """Certificates of DGP solutions (objects with ``taut`` 1-based, ``position``, ``rotation`` and n ``tensions``,
    e.g. ``dgp(robot).solutions``), in order.  This is the call to add to the DGP (or to run after it)."""
    out = []
    for s in solutions:
        cables = [t - 1 for t in s.taut]
        out.append(certify_taut_root(robot, lengths, cables, s.position, s.rotation,
                                     np.asarray(s.tensions, float)[cables], box_rtol))
    return out


# --------------------------------------------------------------------------------------------- IGP
def certify_igp_orientation(robot, rotation, position, tensions, lengths, box_rtol: float = BOX_RTOL) -> Certificate:
    """IGP with assigned ``rotation`` (seed 004 Sec. 3): unknowns (p, lam), force and moment balance (6 x 6).
    ``position``: the platform-frame origin p of the root; ``tensions``, ``lengths``: its 3 tensions and lengths
    (the starting point lam = tau / rho)."""
    R0 = np.asarray(rotation, float)
    m = robot.n
    L = robot.cable_scale
    cols = [0, 1, 2] + [12 + i for i in range(m)]
    rows = list(range(6, 12))

    def make_system(num):
        A, b, g, f = _robot_data(robot, range(m), num)
        Rx = [num(v) for v in R0.T.ravel().tolist()]  # u, v, w exactly as given
        return lambda y, jac: _select(*taut_system(list(y[:3]) + Rx + list(y[3:]), A, b, g, f, None, jac), rows, cols)

    x0 = np.concatenate([np.asarray(position, float), np.asarray(tensions, float) / np.asarray(lengths, float)])
    scale = _scales(robot, m, cols, L, x0)
    kr = _krawczyk(make_system, x0, scale, box_rtol)
    R = [[arb(float(R0[k][j])) for j in range(3)] for k in range(3)]
    if kr.proven:
        X = kr.enclosure
        return _consequences("igp_orientation", robot, list(range(m)), None, X[0:3], R, X[3:], kr,
                             kr.relative_width(scale), L)
    retry = _retry_with_polish(make_system, x0, lambda y: _scales(robot, m, cols, L, y), box_rtol)
    if retry is None:
        return _failed("igp_orientation", robot.n, kr.reason, kr, list(range(m)))
    kr, scale, extra = retry
    from flint import ctx

    with FLINT, ctx.workprec(RETRY_PREC):
        X = kr.enclosure
        return _consequences("igp_orientation", robot, list(range(m)), None, X[0:3], R, X[3:], kr,
                             kr.relative_width(scale), L, extra)


def certify_igp_position(robot, com_position, rotation, tensions, lengths, box_rtol: float = BOX_RTOL) -> Certificate:
    """IGP with assigned position of G (seed 004 Sec. 4): unknowns (u, v, w, lam), rotation and balance equations
    (12 x 12) with the platform frame moved to G (b_i' - g', g' = 0, p = G)."""
    return certify_igp_positions(robot, com_position, [(rotation, tensions, lengths)], box_rtol)[0]


def certify_igp_positions(robot, com_position, roots, box_rtol: float = BOX_RTOL) -> list:
    """:func:`certify_igp_position` for many roots at one position of G: ``roots`` = (rotation, tensions,
    lengths) each; a root that double precision does not prove is tried again by :func:`_igp_position_retry`.  The floating-point F and J (the Newton step) are evaluated for every root at once, and the
    Krawczyk rounds of all roots are compiled (:func:`cdpr_algebra.intervals.real_krawczyk.certify_real_roots` with
    :func:`_compiled_subsystem_krawczyk`: rows and columns of the generated interval evaluator of the taut system,
    p = G fixed); the consequences are proven in ball arithmetic."""
    from flint import ctx

    from cdpr_algebra.intervals.real_krawczyk import certify_real_roots

    m = robot.n
    L = robot.cable_scale
    n = 12 + m
    rows = list(range(6)) + list(range(6 + m, n))
    cols = _igp_position_columns(robot)
    Gf = np.asarray(com_position, float).tolist()
    roots = list(roots)
    if not roots:
        return []
    N = len(roots)
    Y = np.array([np.concatenate([np.asarray(R, float).T.ravel(), np.asarray(t, float) / np.asarray(rho, float)])
                  for R, t, rho in roots]).reshape(N, n - 3)
    F0, J0 = _float_systems(Gf, Y, _parameters(*_robot_data(robot, range(m), float, com_at_origin=True)), rows, cols)
    S = np.array([igp_position_scales(robot, Y[j]) for j in range(N)]).reshape(N, n - 3)
    boxes = certify_real_roots(_compiled_subsystem_krawczyk(robot, Gf, rows, cols), Y, S, box_rtol,
                               inverse=_inverses(J0), residual=F0)
    G = [arb(v) for v in Gf]
    balls = _robot_balls(robot)
    gp = balls[2]
    out, parts, proven = [], [], []
    def part(X, kr, scale, extra=None):
        R = [[X[i], X[3 + i], X[6 + i]] for i in range(3)]
        p = [G[i] - (R[i][0] * gp[0] + R[i][1] * gp[1] + R[i][2] * gp[2]) for i in range(3)]
        return _enclosures("igp_position", robot, list(range(m)), None, p, R, X[9:], kr, kr.relative_width(scale),
                           L, extra, balls=balls)

    for j in range(N):
        center, rounds, step = boxes.center[j], int(boxes.rounds[j]), float(boxes.newton_step[j])
        if not boxes.proven[j]:
            retry = _igp_position_retry(robot, Gf, Y[j], box_rtol)
            if retry is not None:
                kr, scale, extra = retry
                proven.append(len(out))
                out.append(None)
                with FLINT, ctx.workprec(RETRY_PREC):
                    parts.append(part(kr.enclosure, kr, scale, extra))
                continue
            kr = KrawczykResult(False, None, None, center, rounds, step, boxes.reason[j])
            out.append(_failed("igp_position", robot.n, kr.reason, kr, list(range(m))))
            continue
        X = [arb(lo_).union(arb(hi_)) for lo_, hi_ in zip(boxes.lo[j].tolist(), boxes.hi[j].tolist())]
        proven.append(len(out))
        out.append(None)
        parts.append(part(X, KrawczykResult(True, X, None, center, rounds, step), S[j]))
    for j, c in zip(proven, _finish(parts)):
        out[j] = c
    return out


IGP_POLISH_RTOL = 1e-7  # largest polish of an IGP root (relative to the scale): 10x the 7.4e-9 measured far away


def _igp_position_columns(robot) -> list:
    """The unknowns (u, v, w, lam) of the IGP with assigned position among those (p, u, v, w, lam) of the taut system."""
    return list(range(3, 12 + robot.n))


def igp_position_scales(robot, y):
    """:func:`_scales` of the IGP unknowns y = (u, v, w, lam) with assigned position."""
    return _scales(robot, robot.n, _igp_position_columns(robot), robot.cable_scale, y)


def igp_position_system(robot, com_position):
    """``make(num) -> system(y, jacobian) -> (F, J)``: the 12 x 12 system of the IGP with assigned position in
    plain arithmetic (``num`` = arb or float), unknowns y = (u, v, w, lam), the platform frame at G
    (:func:`certify_igp_position`)."""
    cols = _igp_position_columns(robot)

    def make(num):
        A, b, g, f = _robot_data(robot, range(robot.n), num, com_at_origin=True)
        p = [num(float(v)) for v in com_position]
        return lambda y, jac: _select(*taut_system(p + list(y), A, b, g, f, None, jac), range(12), cols)
    return make


def _igp_position_retry(robot, G, y0, box_rtol):
    """:func:`_retry_with_polish` of an IGP root with assigned position (G; y0 = (u, v, w, lam))."""
    return _retry_with_polish(igp_position_system(robot, G), y0, lambda y: igp_position_scales(robot, y), box_rtol)


def _retry_with_polish(make, y0, scales, box_rtol):
    """(KrawczykResult, scale, extra) of an IGP root y0 of the system built by ``make`` (as :func:`_krawczyk`;
    ``scales(y)``: the scale of each unknown at y) that the double-precision test did not prove, proven at
    :data:`RETRY_PREC` bits with Newton steps in ball arithmetic (``extra.precision_bits``); or, when the root as
    reported is farther from the zero than the box tolerance (doubles locate an ill-conditioned root only to its
    condition number times 1e-16), at the root polished by Newton's method with the residual at that precision
    (moves up to :data:`IGP_POLISH_RTOL` of the scale; ``extra.polished`` the move, ``extra.polished_root`` the
    polished unknowns, which the IGP reports instead); None when neither is proven.  Measured (thirty-third
    session): seed 004 Table 3's robot with its base scaled by 1e4 (scaled condition number 6e17), assigned
    position: 3 of its 4 real roots were not proven in double precision, all 4 are here; at G = (2e5, 3e5, 1e5) its
    4 real roots were 2e-9 .. 7e-9 (relative) off their zeros, and are proven once polished.  Assigned orientation,
    Tables 1 and 2's robots with their bases scaled by 1 .. 1e5 at two orientations: 9 of 20 roots proven in double
    precision, 20 of 20 here (11 retried)."""
    from flint import ctx

    from cdpr_algebra.intervals.balls import refined_root

    scale = scales(y0)
    with FLINT, ctx.workprec(RETRY_PREC):
        kr = _krawczyk(make, y0, scale, box_rtol, REFINE_STEPS)
        if kr.proven:
            return kr, scale, {"precision_bits": RETRY_PREC}
        sf, sa = make(float), make(arb)
        try:
            C = np.linalg.inv(np.asarray(sf(list(y0), True)[1], dtype=float))
        except np.linalg.LinAlgError:
            return None
        if not np.all(np.isfinite(C)):
            return None
        y = refined_root(lambda x: sa(x, False)[0], C, y0, scale, REFINE_STEPS)
        if y is None or not np.all(np.abs(y - y0) <= IGP_POLISH_RTOL * scale):
            return None
        scale = scales(y)
        kr = _krawczyk(make, y, scale, box_rtol, REFINE_STEPS)
        if not kr.proven:
            return None
    move = float(np.max(np.abs(y - y0) / scale))
    return kr, scale, {"precision_bits": RETRY_PREC, "polished": move, "polished_root": [float(v) for v in y]}


def _igp_kernels():
    """The compiled pieces of :func:`certify_igp_positions`: (the Krawczyk kernel, the addresses of the generated
    interval evaluators of the taut system and of its residual), loaded from numba's cache (or compiled)."""
    from cdpr_algebra.generated.taut_equations_intervals import taut_equations as ev_iv, taut_residual as res_iv
    from cdpr_algebra.homotopy.compiled import function_address
    from cdpr_algebra.intervals.complex_kernels import EVALUATOR_TYPE
    from cdpr_algebra.intervals.real_kernels import real_subsystem_krawczyk_kernel

    return (real_subsystem_krawczyk_kernel, function_address(ev_iv, EVALUATOR_TYPE),
            function_address(res_iv, EVALUATOR_TYPE))


def load_igp_kernels() -> None:
    """Load (from numba's cache) or compile the kernels of :func:`certify_igp_positions` now (~0.5 s a process)."""
    _igp_kernels()


def _compiled_subsystem_krawczyk(robot, G, rows, cols):
    """The Krawczyk operator of the IGP with assigned position over real boxes of (u, v, w, lam), compiled
    (:func:`cdpr_algebra.intervals.real_kernels.real_subsystem_krawczyk_kernel`): rows ``rows`` and columns
    ``cols`` of the generated interval evaluator :mod:`cdpr_algebra.generated.taut_equations_intervals` of the
    taut system with all m = n cables, the platform frame moved to G (b_i' - g' enclosed, g' = 0), p = G exact,
    Q d enclosed (the length rows, not used, get rho_i^2 = 0).  Returns kernel(part, y, r) -> (K, ok), the same
    operator for every root (``part`` unused)."""
    from cdpr_algebra.intervals.arithmetic import Interval

    real_subsystem_krawczyk_kernel, ev, res = _igp_kernels()
    m = robot.n
    A, b, g, f = _robot_data(robot, range(m), Interval.point, com_at_origin=True)
    params = _parameters(A, b, g, f, None)
    P = np.zeros((1, len(params), 4))  # (lo, hi, 0, 0): real intervals
    for k, v in enumerate(params):
        v = v if isinstance(v, Interval) else Interval.point(v)
        P[0, k, 0], P[0, k, 1] = float(v.lo), float(v.hi)
    X0 = np.zeros((1, 12 + m))
    X0[0, :3] = G
    rows_, cols_ = np.asarray(rows, dtype=np.int64), np.asarray(cols, dtype=np.int64)

    def kernel(part, y, r):
        y = np.ascontiguousarray(y, dtype=float)
        K_lo, K_hi = np.empty_like(y), np.empty_like(y)
        ok = np.zeros(len(y), dtype=bool)
        N = len(y)
        real_subsystem_krawczyk_kernel(ev, res, y, np.ascontiguousarray(r, dtype=float),
                                       np.repeat(P, N, axis=0), np.repeat(X0, N, axis=0), rows_, cols_, K_lo, K_hi,
                                       ok)
        return Interval(K_lo, K_hi), ok

    return kernel


COLUMNS_FROM = 16  # points from which one evaluation on numpy columns beats one evaluation per point


def _float_systems(head, Y, p, rows, cols):
    """F (N, rows) and J (N, rows, cols) in floats of the generated evaluator at the N points x = head + Y[k]."""
    N, n = len(Y), len(head) + Y.shape[1]
    if N >= COLUMNS_FROM:
        F, J = np.zeros((n, N)), np.zeros((n, n, N))
        taut_equations(list(head) + list(Y.T), p, None, F, J, None, False)
        F, J = F.T, J.transpose(2, 0, 1)
    else:
        F, J = np.zeros((N, n)), np.zeros((N, n, n))
        for k in range(N):
            taut_equations(list(head) + Y[k].tolist(), p, None, F[k], J[k], None, False)
    return np.ascontiguousarray(F[:, rows]), np.ascontiguousarray(J[:, rows][:, :, cols])


def _inverses(Js):
    """Inverses of a stack of matrices (NaN for a singular one)."""
    try:
        return np.linalg.inv(Js)
    except np.linalg.LinAlgError:
        out = np.full_like(Js, np.nan)
        for k, Jk in enumerate(Js):
            try:
                out[k] = np.linalg.inv(Jk)
            except np.linalg.LinAlgError:
                pass
        return out


def certify_igp_solution(robot, solution, problem: str, box_rtol: float = BOX_RTOL) -> Certificate | None:
    """Certificate of a real :class:`cdpr_algebra.igp.results.IGPSolution` of the IGP ``problem`` ('orientation' or 'position');
    None for a complex solution."""
    if not solution.real:
        return None
    args = (np.real(solution.tensions), np.real(solution.lengths), box_rtol)
    if problem == "orientation":
        return certify_igp_orientation(robot, np.real(solution.rotation), np.real(solution.position), *args)
    if problem == "position":
        return certify_igp_position(robot, np.real(solution.com_position), np.real(solution.rotation), *args)
    raise ValueError(f"unknown IGP problem {problem!r}")


def with_certificates(robot, solutions, problem: str) -> list:
    """The IGP solutions with ``certified`` and ``certificate`` filled in (real ones; complex ones keep None)."""
    solutions = list(solutions)
    if problem == "position":  # the real roots of each position of G at once
        certs = [None] * len(solutions)
        groups = {}
        for k, s in enumerate(solutions):
            if s.real:
                groups.setdefault(tuple(np.real(s.com_position).tolist()), []).append(k)
        for G, ks in groups.items():
            roots = [(np.real(solutions[k].rotation), np.real(solutions[k].tensions), np.real(solutions[k].lengths))
                     for k in ks]
            for k, c in zip(ks, certify_igp_positions(robot, G, roots)):
                certs[k] = c
    else:
        certs = [certify_igp_solution(robot, s, problem) for s in solutions]
    return [s if c is None else replace(s, certified=c.certified, certificate=c) for s, c in zip(solutions, certs)]
