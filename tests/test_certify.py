"""Interval certificates (issue 5): Krawczyk existence/uniqueness, tension signs, slack cables, H_r class.

Independent references: the compiled sympy evaluators of model.taut_equations (for the generated interval system),
sqrt(2) in arb, exact rational IGP solutions of seed 004 Tables 1-2, the printed tensions of seed 000 Table 1,
robots built around a known equilibrium with an exactly vanishing tension (Pythagorean lengths, binary
fractions), and the floating-point stability classes of stability.py.
"""

import json
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from flint import arb

from cdpr_algebra import load_robot
from cdpr_algebra.certificates.equilibria import (BOX_RTOL, certify_dgp_solutions, certify_igp_orientation,
                                                  certify_igp_positions, certify_taut_root, taut_system)
from cdpr_algebra.dgp.solve import dgp, solve_taut_set
from cdpr_algebra.model.taut_equations import taut_family
from cdpr_algebra.dgp.one_cable import one_cable_equilibria
from cdpr_algebra.igp.orientation import igp_orientation
from cdpr_algebra.igp.position import igp_position
from cdpr_algebra.intervals.balls import krawczyk_certify, refined_root, symmetric_inertia, symmetric_inertias
from cdpr_algebra.model.robot import Robot
from cdpr_algebra.model.stability import stability_classes
from cdpr_algebra.report.tables import igp_table

ROOT = Path(__file__).resolve().parent.parent
TABLES = json.loads((ROOT / "tests" / "data" / "seed000_tables.json").read_text())["tables"]
TABLE1 = TABLES["1"]["rows"]


def _contains(lo, hi, v, slack=0.0):
    return bool(np.all(np.asarray(lo) - slack <= v) and np.all(v <= np.asarray(hi) + slack))


# --------------------------------------------------------------------------------------- generic tools
@pytest.mark.parametrize("m", [2, 3, 6])
def test_interval_system_is_the_dgp_family(m):
    """The generated F and dF/dx equal the compiled sympy system of model.taut_equations (random points)."""
    fam = taut_family(m)
    rng = np.random.default_rng(m)
    for _ in range(3):
        x = rng.normal(size=12 + m)
        p = rng.normal(size=7 * m + 6)
        F, J = fam.evaluate_and_jacobian(x.astype(complex), p)
        F, J = F.real.ravel(), J.real.reshape(12 + m, 12 + m)
        A, r2, b = p[:3 * m].reshape(m, 3), p[3 * m:4 * m], p[4 * m:7 * m].reshape(m, 3)
        F2, J2 = taut_system(x.tolist(), A.tolist(), b.tolist(), p[7 * m:7 * m + 3].tolist(), p[-3:].tolist(),
                             r2.tolist())
        assert np.allclose(F2, F, atol=1e-12) and np.allclose(np.array(J2, float), J, atol=1e-12)
        # on balls the enclosure contains the float value
        Fb, _ = taut_system([arb(v) for v in x.tolist()], A.tolist(), b.tolist(), p[7 * m:7 * m + 3].tolist(),
                            p[-3:].tolist(), r2.tolist())
        assert all(abs(float(fb) - fr) <= 1e-12 * (1 + abs(fr)) for fb, fr in zip(Fb, F))


def _circle_line(x):
    """x^2 + y^2 = 4, x = y: zero (sqrt 2, sqrt 2)."""
    return [x[0] * x[0] + x[1] * x[1] - 4, x[0] - x[1]]


def _circle_line_jac(x):
    return [[2 * x[0], 2 * x[1]], [1, -1]]


def test_krawczyk_proves_a_known_root():
    kr = krawczyk_certify(_circle_line, _circle_line_jac, [1.4142135623730951] * 2, 1.0)
    assert kr.proven and kr.reason is None
    assert all(e.overlaps(arb(2).sqrt()) and (e * e).contains(2) for e in kr.enclosure)
    assert kr.relative_width(1.0) < 1e-12


def test_krawczyk_rejects_a_wrong_point_and_a_singular_root():
    kr = krawczyk_certify(_circle_line, _circle_line_jac, [1.4142, 1.4142], 1.0)
    assert not kr.proven and "Newton step" in kr.reason
    # x^2 = 0, y = 0: a double root, Jacobian singular
    kr = krawczyk_certify(lambda x: [x[0] * x[0], x[1]], lambda x: [[2 * x[0], 0], [0, 1]], [0.0, 0.0], 1.0)
    assert not kr.proven and "singular" in kr.reason
    # x^2 = 1e-20 near x = 1e-10 with a box tolerance (1e-9 * scale 1e3) wider than the roots' distance: the
    # box is tight enough to hold one root; its enclosure excludes the other root -1e-10
    kr = krawczyk_certify(lambda x: [x[0] * x[0] - arb(1e-20)], lambda x: [[2 * x[0]]], [1e-10], 1e3)
    assert kr.proven and kr.enclosure[0] > 0
    # x^2 + 1 = 0 has no real root: the Newton step from x = 1e-3 is huge
    kr = krawczyk_certify(lambda x: [x[0] * x[0] + 1], lambda x: [[2 * x[0]]], [1e-3], 1.0)
    assert not kr.proven


def test_newton_steps_in_ball_arithmetic():
    """refined_root: Newton's method with the residual in ball arithmetic takes the five-digit point of the circle
    and the line to sqrt(2) in doubles, and finds nothing for x^2 + 1.  krawczyk_certify with ``refine`` still
    certifies only the given point: it rejects the five-digit point (1e-5 from the zero) and proves the refined
    one."""
    x0 = np.array([1.4142, 1.4142])
    C = np.linalg.inv(np.array(_circle_line_jac(x0), dtype=float))
    y = refined_root(_circle_line, C, x0, 1.0)
    assert np.all(np.abs(y - np.sqrt(2)) <= 4e-16)
    assert refined_root(lambda x: [x[0] * x[0] + 1], [[500.0]], [1e-3], 1.0) is None
    kr = krawczyk_certify(_circle_line, _circle_line_jac, x0, 1.0, refine=8)
    assert not kr.proven and "Newton step" in kr.reason and 1e-6 < kr.newton_step < 1e-4
    kr = krawczyk_certify(_circle_line, _circle_line_jac, y, 1.0, refine=8)
    assert kr.proven and all(e.overlaps(arb(2).sqrt()) for e in kr.enclosure)


def test_symmetric_inertia():
    Q, _ = np.linalg.qr(np.random.default_rng(3).normal(size=(5, 5)))
    K = Q @ np.diag([3.0, -1.0, 2.0, -5.0, 0.5]) @ Q.T
    assert symmetric_inertia([[arb(v) for v in row] for row in K.tolist()]) == (3, 2)
    # balls wide enough to reach a zero eigenvalue: undecided
    assert symmetric_inertia([[arb(v, 0.2) for v in row] for row in K.tolist()]) is None
    Ks = Q @ np.diag([3.0, -1.0, 0.0, -5.0, 0.5]) @ Q.T
    assert symmetric_inertia([[arb(v) for v in row] for row in Ks.tolist()]) is None
    # several at once, as one by one; an eigenvalue 1e-15 |K| (below the a priori float bounds) is decided by the
    # ball-arithmetic retry
    Kt = Q @ np.diag([3.0, -1.0, 1e-15, -5.0, 0.5]) @ Q.T
    balls = [[[arb(v) for v in row] for row in M.tolist()] for M in (K, Ks, Kt)]
    assert symmetric_inertias(balls) == [symmetric_inertia(M) for M in balls] == [(3, 2), None, (3, 2)]


# -------------------------------------------------------------------------------- DGP, seed 000 Test 1
@pytest.fixture(scope="module")
def test1():
    robot = load_robot(ROOT / "examples" / "seed000_test1.toml")
    res = dgp(robot, jobs=1)
    return robot, res, certify_dgp_solutions(robot, res.solutions)


def test_seed000_test1_every_root_certified(test1):
    robot, res, certs = test1
    L = robot.size
    assert len(res.solutions) == 6
    for s, c in zip(res.solutions, certs):
        assert c.certified and c.exists_unique and c.reason is None, c.reason
        assert c.box_width <= BOX_RTOL * L
        assert c.tension_signs == ("positive",) * 3 and c.slack_proven
        # the reported root lies within the tolerance of the certified box
        assert _contains(c.position_lower, c.position_upper, s.position, BOX_RTOL * L)
        assert _contains(c.rotation_lower, c.rotation_upper, s.rotation, BOX_RTOL)
        assert _contains(c.tension_lower, c.tension_upper, s.tensions, BOX_RTOL * robot.load)
        # class of H_r proven and equal to the floating-point class
        assert c.hessian == "proven" and c.hessian_class == s.hessian


def test_seed000_test1_printed_tensions(test1):
    """Table 1's tensions lie in the certified enclosures widened by 1e-3: the printed rows are 3-digit roundings
    of the equilibria of the unrounded platform, which move the tensions by up to 7e-4 from those of the
    example file's rounded data (tests/test_dgp.py)."""
    robot, res, certs = test1
    for row in TABLE1:
        k = min(range(len(res.solutions)), key=lambda i: np.max(np.abs(res.solutions[i].position - row["position"])))
        c = certs[k]
        assert _contains(c.tension_lower, c.tension_upper, np.array(row["tensions"]), 1e-3), row["conf"]
        if row["stability"] == ">":
            assert c.hessian == "proven" and c.hessian_class == ">"
        else:
            assert c.hessian == "proven" and c.hessian_class in ("<", "<>")


def test_perturbed_roots_fail_with_a_reason(test1):
    robot, res, _ = test1
    L = robot.size
    s = res.solutions[0]
    tau = s.tensions[[0, 1, 2]]
    bad = certify_taut_root(robot, None, [0, 1, 2], s.position + 1e-6 * L * np.array([1.0, 0, 0]), s.rotation, tau)
    assert not bad.certified and not bad.exists_unique and "Newton step" in bad.reason
    assert np.all(np.isnan(bad.tension_lower)) and bad.hessian == "undecided"
    bad = certify_taut_root(robot, None, [0, 1, 2], s.position, s.rotation, tau * (1 + 1e-6))
    assert not bad.certified and bad.reason
    # rounding-level noise is not a reason to fail
    ok = certify_taut_root(robot, None, [0, 1, 2], s.position + 1e-13 * L, s.rotation, tau)
    assert ok.certified


@pytest.mark.slow
def test_seed000_test3_six_taut_cables():
    """Seed 000 Test 3, the subproblem with all 6 cables taut (~15 s): its admissible roots are Table 3 rows 1-3
    (printed to 3 digits), each certified, tensions within rounding, H_r proven positive definite."""
    robot = load_robot(ROOT / "examples" / "seed000_test3.toml")
    _, sols = solve_taut_set(robot, robot.lengths, range(6))
    rows = [r for r in TABLES["3"]["rows"] if len(r["taut"]) == 6]
    assert len(sols) == len(rows) == 3
    certs = certify_dgp_solutions(robot, sols)
    for row in rows:
        k = min(range(3), key=lambda i: np.max(np.abs(sols[i].tensions - row["tensions"])))
        c = certs[k]
        assert c.certified and c.box_width <= BOX_RTOL * robot.size, c.reason
        assert _contains(c.tension_lower, c.tension_upper, np.array(row["tensions"]), 0.5e-3 + 5e-5), row["conf"]
        assert c.hessian == "proven" and c.hessian_class == ">" == row["stability"]


# ----------------------------------------------------------------------- DGP, m = 2..6, known equilibria
def _known_equilibrium(m, n_slack, seed):
    """A robot built around a chosen equilibrium with m taut cables: forces f_i = tau_i u_i of cables 1..m-1
    chosen, f_m = -Q d - sum f_i; G moved along e so that the moment M0 = sum (B_i - G) x f_i is orthogonal to f_m,
    then B_m = G + M0 x f_m / |f_m|^2 gives (B_m - G) x f_m = -M0.  Slack cables 20 % longer than their distance.
    Returns (robot, p, R, tau)."""
    rng = np.random.default_rng(seed)
    d = np.array([0.0, 0.0, -1.0])
    Q = float(rng.uniform(5, 20))
    while True:
        U = np.array([[*rng.uniform(-0.6, 0.6, 2), 1.0] for _ in range(m - 1)])
        U /= np.linalg.norm(U, axis=1)[:, None]
        f = U * rng.uniform(0.1, 0.6, size=(m - 1, 1)) * Q / max(m - 1, 1)
        fm = -Q * d - f.sum(axis=0)
        if fm[2] > 0.2 * np.linalg.norm(fm):  # pulls upwards
            break
    f = np.vstack([f, fm])
    B = rng.uniform(-0.5, 0.5, size=(m - 1, 3))
    G0 = np.array([0.0, 0.0, -0.4])
    e = np.array([1.0, 0.0, 0.0])
    Fp = f[:-1].sum(axis=0)
    C = sum(np.cross(B[i], f[i]) for i in range(m - 1))
    # (C - G x Fp) . fm = 0 with G = G0 + s e
    s = ((C - np.cross(G0, Fp)) @ fm) / (np.cross(e, Fp) @ fm)
    G = G0 + s * e
    M0 = C - np.cross(G, Fp)
    Bm = G + np.cross(M0, fm) / (fm @ fm)
    B = np.vstack([B, Bm])
    tau = np.linalg.norm(f, axis=1)
    rho = rng.uniform(2.0, 4.0, size=m)
    A = B + rho[:, None] * f / tau[:, None]
    R = np.linalg.qr(rng.normal(size=(3, 3)))[0]
    R *= np.sign(np.linalg.det(R))
    p = G + rng.uniform(-0.3, 0.3, 3)
    bs = rng.uniform(-0.5, 0.5, size=(n_slack, 3))
    As = p + bs @ R.T + rng.uniform(1.5, 3.0, size=(n_slack, 1)) * np.array([0.3, -0.2, 1.0])
    Bs = p + bs @ R.T
    robot = Robot(np.vstack([A, As]), np.vstack([(B - p) @ R, bs]), R.T @ (G - p), Q, d,
                  np.concatenate([rho, 1.2 * np.linalg.norm(As - Bs, axis=1)]))
    return robot, p, R, tau


@pytest.mark.parametrize("m", [2, 3, 4, 5, 6])
def test_known_equilibria_m_taut(m):
    robot, p, R, tau = _known_equilibrium(m, 2, 100 + m)
    c = certify_taut_root(robot, None, list(range(m)), p, R, tau)
    assert c.certified, c.reason
    assert c.box_width <= BOX_RTOL * robot.size
    assert _contains(c.tension_lower[:m], c.tension_upper[:m], tau, 1e-12 * robot.load)
    assert np.all(c.tension_lower[m:] == 0) and c.tension_signs[m:] == ("slack", "slack")
    assert np.all(c.slack_margin_upper[m:] < 0) and np.all(np.isnan(c.slack_margin_lower[:m]))
    B = p + robot.platform[:m] @ R.T
    cls = stability_classes(robot.base[:m], B, p + R @ robot.com, tau, robot.lengths[:m], robot.load, robot.size)
    assert c.hessian == "proven" and c.hessian_class == cls
    # the same root presented with cable m left out is not an equilibrium of the smaller taut set
    if m >= 3:
        bad = certify_taut_root(robot, None, list(range(m - 1)), p, R, tau[:-1])
        assert not bad.certified and not bad.exists_unique


# ------------------------------------------------------------------------------------ boundary cases
def _boundary_robot():
    """Cables 1, 2 hold the platform (B = (-+5, 0, -1), A = (-+2.5, 0, -7), rho = 6.5, tau = 6.5, Q = 12 along +z,
    G = 0 at p = 0, R = I: forces (+-2.5, 0, -6) sum to (0, 0, -12), moments about G cancel); cable 3 is exactly at
    its length 13 = |(3, 4, 12)|: in the 3-cable system it is taut with tension exactly 0."""
    B = [[-5.0, 0, -1], [5, 0, -1], [0, 2, -1]]
    A = [[-2.5, 0, -7], [2.5, 0, -7], [-3, -2, -13]]
    return Robot(A, B, [0, 0, 0], 12.0, [0, 0, 1], [6.5, 6.5, 13.0])


def test_zero_tension_is_a_boundary_case():
    robot = _boundary_robot()
    c = certify_taut_root(robot, None, [0, 1, 2], np.zeros(3), np.eye(3), [6.5, 6.5, 0.0])
    assert c.exists_unique and not c.certified
    assert c.tension_signs == ("positive", "positive", "boundary") and "boundary" in c.reason
    assert c.tension_lower[2] <= 0 <= c.tension_upper[2]
    assert _contains(c.tension_lower, c.tension_upper, np.array([6.5, 6.5, 0.0]))


def test_slack_cable_at_its_length_is_not_proven_slack():
    robot = _boundary_robot()
    c = certify_taut_root(robot, None, [0, 1], np.zeros(3), np.eye(3), [6.5, 6.5])
    assert c.exists_unique and not c.certified and not c.slack_proven
    assert c.tension_signs == ("positive", "positive", "slack") and "cable 3 not proven slack" in c.reason
    assert c.slack_margin_lower[2] <= 0 <= c.slack_margin_upper[2]
    # a longer cable 3 is proven slack
    ok = certify_taut_root(robot.with_lengths([6.5, 6.5, 13.1]), None, [0, 1], np.zeros(3), np.eye(3), [6.5, 6.5])
    assert ok.certified and ok.slack_proven and ok.slack_margin_upper[2] < 0
    assert ok.hessian == "proven"
    B = np.array(robot.platform)
    assert ok.hessian_class == stability_classes(robot.base[:2], B[:2], np.zeros(3), [6.5, 6.5], [6.5, 6.5],
                                                 robot.load, robot.size)


def test_one_taut_cable():
    """m = 1: the gauge-fixed square system certifies each equilibrium of dgp_one_cable; the rotation about the
    cable is neutral (an exact zero of H_r), and the class with that zero is proven by bordering it out
    (equilibria._with_neutral_spin): '>=', '<=' or '<>', equal to the floating-point class of model.stability."""
    robot = _boundary_robot().with_lengths([6.5, 30.0, 30.0])
    eqs = one_cable_equilibria(robot, 0)
    assert len(eqs) == 4
    classes = []
    for e in eqs:
        c = certify_taut_root(robot, None, [0], e.position, e.rotation, [e.tension])
        assert c.certified and c.slack_proven, c.reason
        assert c.tension_signs[0] == ("positive" if e.tension > 0 else "negative")
        assert _contains(c.tension_lower[:1], c.tension_upper[:1], e.tension)  # |tau| = Q exactly
        G = e.position + e.rotation @ robot.com
        B = e.position + e.rotation @ robot.platform[0]
        cls = stability_classes(robot.base[:1], B[None], G, [e.tension], [6.5], robot.load, robot.size)
        assert cls in (">=", "<=", "<>")
        assert c.hessian == "proven" and c.hessian_class == cls
        classes.append(cls)
    # hanging (tension > 0, G below B): only the spin is neutral; G above B on a taut cable, or G below B on a
    # strut (tension < 0): one unstable pair; G above B on a strut: all unstable
    assert sorted(classes) == ["<=", "<>", "<>", ">="]
    # G at the anchor: a 3-dof family, said so
    r = Robot(robot.base, robot.platform, robot.platform[0], robot.load, robot.load_direction, robot.lengths)
    c = certify_taut_root(r, None, [0], eqs[0].position, eqs[0].rotation, [r.load])
    assert not c.certified and "3-dof" in c.reason


# ---------------------------------------------------------------------------------- IGP, seed 004
@pytest.mark.parametrize("table, exact_G", [
    (1, [Fraction(5196, 1805), Fraction(2973, 722), Fraction(139299, 20938)]),
    (2, [Fraction(-989, 137), Fraction(-705, 137), Fraction(396757, 10823)]),
])
def test_igp_orientation_tables_1_2(table, exact_G):
    robot = load_robot(ROOT / "examples" / f"seed004_table{table}.toml")
    (s,) = igp_orientation(robot, np.eye(3)).solutions
    c = s.certificate
    assert s.certified and c.certified and c.problem == "igp_orientation"
    # the exact solution (platform frame at G) lies in the certified box
    assert all(Fraction(lo) <= g <= Fraction(hi) for lo, hi, g in zip(c.position_lower, c.position_upper, exact_G))
    assert c.hessian == "proven" and c.hessian_class == s.hessian
    assert c.tension_signs == tuple("positive" if t > 0 else "negative" for t in s.tensions)
    d = s.to_dict()
    assert d["certified"] is True
    assert {"box_width", "tension_lower", "tension_upper", "hessian"} <= set(d["certificate"])


def test_igp_orientation_certificate_rejects_a_wrong_rotation():
    robot = load_robot(ROOT / "examples" / "seed004_table1.toml")
    (s,) = igp_orientation(robot, np.eye(3)).solutions
    R = np.array([[1.0, -1e-6, 0], [1e-6, 1.0, 0], [0, 0, 1.0]])  # the root of another orientation problem
    c = certify_igp_orientation(robot, R, s.position, s.tensions, s.lengths)
    assert not c.certified and not c.exists_unique


def test_igp_position_table3_all_certified(table3):
    robot, res = table3
    real = res.real_solutions
    assert len(real) == 24
    for s in real:
        c = s.certificate
        assert s.certified and c.certified and c.problem == "igp_position", c.reason
        assert c.box_width <= BOX_RTOL * robot.size
        assert _contains(c.rotation_lower, c.rotation_upper, s.rotation, BOX_RTOL)
        assert _contains(c.tension_lower, c.tension_upper, s.tensions, BOX_RTOL * robot.load)
        assert c.tension_signs == tuple("positive" if t > 0 else "negative" for t in s.tensions)
        assert c.hessian == "proven" and c.hessian_class == s.hessian
    assert "certified" in igp_table(res).splitlines()[0]
    assert igp_table(res).splitlines()[-1].count("24 certified") == 1


def _mp_igp_root(robot, G, s, dps=40):
    """The IGP root near the float solution ``s`` refined by Newton's method in mpmath at ``dps`` digits on the
    12 x 12 system (rotation entries, lam) with the platform frame at G, an independent reference point."""
    import mpmath as mp

    with mp.workdps(dps):
        g = [mp.mpf(float(v)) for v in robot.com]
        A = [[mp.mpf(float(v)) for v in a] for a in robot.base]
        b = [[mp.mpf(float(v)) - g[k] for k, v in enumerate(bi)] for bi in robot.platform]
        f = [mp.mpf(robot.load) * mp.mpf(float(c)) for c in robot.load_direction]
        Gm = [mp.mpf(float(v)) for v in G]
        y = [mp.mpf(v) for v in np.asarray(s.rotation, float).T.ravel().tolist()]
        y += [mp.mpf(float(t)) / mp.mpf(float(r)) for t, r in zip(s.tensions, s.lengths)]
        for _ in range(8):
            F, J = taut_system(Gm + y, A, b, [mp.mpf(0)] * 3, f)
            d = mp.lu_solve(mp.matrix([row[3:] for row in J]), mp.matrix(F))
            y = [yk - dk for yk, dk in zip(y, d)]
        assert max(abs(v) for v in taut_system(Gm + y, A, b, [mp.mpf(0)] * 3, f, jacobian=False)[0]) < mp.mpf(10) ** -30
        rho = [mp.sqrt(sum((Gm[k] + sum(y[3 * j + k] * b[i][j] for j in range(3)) - A[i][k]) ** 2 for k in range(3)))
               for i in range(robot.n)]
        return (np.array([[float(y[3 * j + k]) for j in range(3)] for k in range(3)]),
                np.array([float(y[9 + i] * rho[i]) for i in range(robot.n)]))


def test_igp_position_enclosures_hold_the_mpmath_root(table3):
    """The compiled Krawczyk boxes (rows and columns of the generated interval evaluator) and the enclosures of
    rotation and tensions hold the root refined to 40 digits in mpmath, for all 24 roots of Table 3."""
    robot, res = table3
    for s in res.real_solutions:
        R, tau = _mp_igp_root(robot, [7.0, 9.0, 1.0], s)
        c = s.certificate
        assert c.certified, c.reason
        # the 40-digit values rounded to doubles: one rounding (|v| 2^-53) from the enclosed value
        assert _contains(c.rotation_lower, c.rotation_upper, R, 2.0 ** -52)
        assert _contains(c.tension_lower, c.tension_upper, tau, 2.0 ** -52 * np.max(np.abs(tau)))
        assert 0 < c.box_width <= BOX_RTOL * robot.cable_scale and c.iterations >= 1


def test_igp_position_certificates_of_bad_roots(table3):
    """certify_igp_positions on a batch with a good root, a root moved by 1e-6 and a root with a NaN: only the
    first is certified, the others say why, in their places."""
    robot, res = table3
    s = res.real_solutions[0]
    R = np.asarray(s.rotation, float)
    moved = R @ np.array([[1.0, -1e-6, 0], [1e-6, 1.0, 0], [0, 0, 1.0]])
    roots = [(R, s.tensions, s.lengths), (moved, s.tensions, s.lengths), (R * np.nan, s.tensions, s.lengths)]
    good, off, bad = certify_igp_positions(robot, [7.0, 9.0, 1.0], roots)
    assert good.certified and good.hessian == "proven"
    assert not off.certified and not off.exists_unique and "Newton step" in off.reason and off.newton_step > 1e-9
    assert not bad.certified and "not finite" in bad.reason
    assert all(t == "unknown" for t in off.tension_signs + bad.tension_signs)


def test_igp_position_table4_zero_tension():
    """Table 4: G lies in the vertical plane through A_1, A_2 and every real solution is a 2-2 configuration
    with tau_3 = 0 (printed 0): the Krawczyk box alone leaves tau_3 a boundary case; the three-force plane proves it
    exactly 0 (certificates.zero_tension), so each is certified, with tau_3 = 0 in the table and the JSON."""
    robot = load_robot(ROOT / "examples" / "seed004_table4.toml")
    res = igp_position(robot, [5, 0, 6])
    real = res.real_solutions
    assert len(real) == 4
    for s in real:
        c = s.certificate
        assert c.exists_unique and s.certified and c.certified and c.reason is None
        assert c.tension_signs == ("positive", "positive", "zero") and "tau_3 = 0 exactly" in c.extra["zero_tension"]["proof"]
        assert s.tensions[2] == 0 and c.tension_lower[2] == c.tension_upper[2] == 0
        assert c.hessian == "proven" and c.hessian_class == s.hessian
    text = igp_table(res)
    assert "boundary" not in text and text.count("tau_3 = 0 exactly") == 4
    # complex solutions carry no certificate
    assert all(s.certificate is None and s.certified is None for s in res.solutions if not s.real)
    out = res.to_dict(include_complex=True)
    json.dumps(out)
    assert [s["certificate"]["tension_signs"][2] for s in out["solutions"] if s["certificate"]] == ["zero"] * 4


def test_root_certificate_is_not_changed_by_a_ball_retry_in_another_thread():
    """python-flint's working precision is global to the process: while another thread holds it at 256 bits (as the
    endpoints' ball retry does), a DGP root's certificate waits for it (certificates.equilibria.FLINT) and is
    computed at 53 bits, equal to the one computed alone (at 256 bits its boxes came out tighter than the reported
    double-precision tensions: seed 000 Tests 2 and 3 failed their consistency check once the threads interleaved)."""
    import threading
    import time

    from flint import ctx

    from cdpr_algebra.certificates import equilibria as EQ

    robot = load_robot(ROOT / "examples" / "seed000_test1.toml")
    s = dgp(robot, jobs=1).solutions[0]
    taut = [t - 1 for t in s.taut]
    alone = certify_taut_root(robot, None, taut, s.position, s.rotation, s.tensions[taut])
    held = threading.Event()

    def hold():
        with EQ.FLINT, ctx.workprec(256):
            held.set()
            time.sleep(0.3)

    th = threading.Thread(target=hold)
    th.start()
    held.wait()
    during = certify_taut_root(robot, None, taut, s.position, s.rotation, s.tensions[taut])
    th.join()
    assert ctx.prec == 53
    np.testing.assert_array_equal(during.tension_lower, alone.tension_lower)
    np.testing.assert_array_equal(during.tension_upper, alone.tension_upper)
    assert during.box_width == alone.box_width
