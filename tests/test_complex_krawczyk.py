"""Krawczyk certificates of complex roots (issue 15, item 4): systems with exactly known roots, negative controls
(a double root, a non-root, two approximations of one root), and the DGP's endpoint accounting on seed 000 Test 1."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from cdpr_algebra.intervals.complex_krawczyk import certify_complex_roots, overlapping
from cdpr_algebra.model.taut_equations import to_cable_frame

ROOT = Path(__file__).resolve().parents[1]


def _system(z, rows=None, jac=True):
    """(z0 - 1)(z0 - 2) = 0, z1^2 + z0 = 0, z2 - z0 z1 = 0: roots (1, +-i, +-i), (2, +-i sqrt 2, +-2i sqrt 2)."""
    F = [z[0] * z[0] - 3 * z[0] + 2, z[1] * z[1] + z[0], z[2] - z[0] * z[1]]
    return F, [[2 * z[0] - 3, 0, 0], [1, 2 * z[1], 0], [-z[1], -z[0], 1]] if jac else None


EXACT = np.array([[1, s * 1j, s * 1j] for s in (1, -1)] + [[2, s * 1j * np.sqrt(2), s * 2j * np.sqrt(2)] for s in (1, -1)])


def _inside(boxes, Z):
    Y = np.hstack([Z.real, Z.imag])
    return np.all((boxes.lo <= Y) & (Y <= boxes.hi), axis=1)


def test_known_complex_roots_proven_nonreal_and_enclosed():
    rng = np.random.default_rng(1)
    Z = EXACT + 1e-9 * (rng.standard_normal(EXACT.shape) + 1j * rng.standard_normal(EXACT.shape))
    b = certify_complex_roots(_system, _system, Z, np.ones(3))
    assert b.proven.all() and b.nonreal.all() and not b.real.any()
    assert _inside(b, EXACT).all()  # the exact roots lie in their enclosures
    assert not overlapping(b.lo, b.hi).any()
    assert np.max(b.hi - b.lo) <= 1e-6 * 3  # tight boxes (relative width limit, |z| <= 2 sqrt 2)


def test_real_roots_proven_real():
    def f(z, rows=None, jac=True):  # eight real roots: z0 in {+-sqrt 2, +-sqrt 3}, z1 in {0, 1}
        F = [(z[0] * z[0] - 2) * (z[0] * z[0] - 3), z[1] * z[1] - z[1]]
        return F, [[4 * z[0] * z[0] * z[0] - 10 * z[0], 0], [0, 2 * z[1] - 1]] if jac else None

    exact = np.array([[s * np.sqrt(q), t] for s in (1, -1) for q in (2, 3) for t in (0, 1)], dtype=complex)
    b = certify_complex_roots(f, f, exact + 1e-12j, np.ones(2))  # tiny imaginary noise: taken as real
    assert b.proven.all() and b.real.all() and not b.nonreal.any()
    assert _inside(b, exact).all()
    assert np.all(b.lo[:, 2:] == -b.hi[:, 2:])  # conjugation-invariant boxes: the proof of realness


def test_negative_controls():
    def f(z, rows=None, jac=True):
        return [z[0] * z[0], z[1] - 1], [[2 * z[0], 0], [0, 1]] if jac else None  # double root z0 = 0

    b = certify_complex_roots(f, f, np.array([[1e-10, 1.0]]), np.ones(2))
    assert not b.proven[0] and "not proven" in b.reason[0]
    # a point that is no root (1e-3 away from (1, i, i)) and two approximations of one root
    Z = np.array([EXACT[0] + 1e-3, EXACT[2], EXACT[2] * (1 + 1e-13)])
    b = certify_complex_roots(_system, _system, Z, np.ones(3))
    assert not b.proven[0] and b.proven[1] and b.proven[2]
    over = overlapping(b.lo[1:], b.hi[1:])
    assert over.all()  # the same root twice: the boxes meet, the roots are not proven distinct


@pytest.fixture(scope="module")
def test1():
    from cdpr_algebra.model.robot import load_robot

    return load_robot(ROOT / "examples" / "seed000_test1.toml")


def test_dgp_endpoints_certified_and_accounted(test1):
    """Seed 000 Test 1, taut sets {1,2} and {1,2,3}: every regular endpoint is a certified distinct root, the
    certified real ones are the float count of real ones, and the subproblem is complete; JSON carries it."""
    from cdpr_algebra.dgp.solve import solve_taut_set

    for cables in [(0, 1), (0, 1, 2)]:
        sub, _ = solve_taut_set(test1, test1.lengths, cables, certify=False, exclude=False)  # {1, 2} tracked
        assert sub.outcomes["failed"] == 0
        assert sub.certified == sub.outcomes["regular"] == sub.finite - sub.outcomes["singular"] > 0
        assert sub.certified_real == sub.real and sub.uncertified == {}
        assert sub.complete and sub.accounted
        d = sub.to_dict()
        assert d["certified"] == sub.certified and d["certified_real"] == sub.real and d["uncertified"] == {}


def test_dgp_duplicate_endpoint_is_not_complete(test1):
    """An endpoint reported twice (as a merge would) makes the boxes meet: not certified, not complete."""
    from cdpr_algebra.dgp import solve as D

    sub, sols, Z = D._solve_taut_set(test1, test1.lengths, (0, 1, 2))
    Zdup = np.vstack([Z, Z[:1] * (1 + 1e-14)])
    sub_dup = replace(sub, outcomes={**sub.outcomes, "regular": sub.outcomes["regular"] + 1})
    (ok,) = D._with_endpoint_certificates(test1, test1.lengths, [((0, 1, 2), sub, Z)])
    (bad,) = D._with_endpoint_certificates(test1, test1.lengths, [((0, 1, 2), sub_dup, Zdup)])
    assert ok.complete and ok.certified == len(Z)
    assert not bad.complete and bad.certified == len(Z) - 1
    assert sum(bad.uncertified.values()) == 2 and "not proven distinct" in next(iter(bad.uncertified))
    # a root moved off the solution set (beyond BALL_MAX_MOVE): not certified
    Zoff = Z.copy()
    Zoff[3, 0] += 3e-2 * test1.size
    (off,) = D._with_endpoint_certificates(test1, test1.lengths, [((0, 1, 2), sub, Zoff)])
    assert not off.complete and off.certified == len(Z) - 1
    assert "incomplete" not in D.incompleteness(off) and "not certified" in D.incompleteness(off)
    # moved by less: the root near it is proven (ball arithmetic), distinct from the others: complete
    Znear = Z.copy()
    Znear[3, 0] += 1e-5 * test1.size
    (near,) = D._with_endpoint_certificates(test1, test1.lengths, [((0, 1, 2), sub, Znear)])
    assert near.complete and near.certified == len(Z)


def test_ill_conditioned_roots_need_balls():
    """z^2 - 2 z + 1 - 2^-60 = 0 (evaluated as written): roots 1 +- 2^-30, condition ~1e9.  In double precision the
    rounding of z^2 alone (1e-16) exceeds F's values near the roots (not proven); in 256-bit ball arithmetic both
    are proven, real, in disjoint boxes that hold the exact roots."""
    from flint import arb

    from cdpr_algebra.intervals.complex_krawczyk import certify_complex_root_balls

    c = 2.0 ** -60

    def f(z, rows=None, jac=True):
        return [z[0] * z[0] - 2 * z[0] + 1 - c], [[2 * z[0] - 2]] if jac else None

    exact = np.array([[1 + 2.0 ** -30], [1 - 2.0 ** -30]], dtype=complex)
    approx = exact * (1 + 1e-12)
    b = certify_complex_roots(f, f, approx, np.ones(1))
    assert not b.proven.any()
    got = [certify_complex_root_balls(lambda z, jac: f(z, None, jac), z, np.ones(1)) for z in approx]
    assert all(g[0] and g[3] and not g[4] for g in got), [g[5] for g in got]
    lo = np.array([g[1] for g in got])
    hi = np.array([g[2] for g in got])
    for k in range(2):  # the exact roots (floats: 1 +- 2^-30 is exact) lie in their enclosures
        assert arb(lo[k, 0]) <= arb(exact[k, 0].real) <= arb(hi[k, 0])
    assert not overlapping(lo, hi).any()
    # a point that is no root within the width limit is refused in balls too
    bad = certify_complex_root_balls(lambda z, jac: f(z, None, jac), np.array([1 + 1e-3]), np.ones(1))
    assert not bad[0] and "moves the root" in bad[5]
    # allowed to move that far (a root of a nearby system, e.g. with rounded parameters): the nearest root is proven
    far = certify_complex_root_balls(lambda z, jac: f(z, None, jac), np.array([1 + 1e-3]), np.ones(1), max_move=1e-2)
    assert far[0] and arb(far[1][0]) <= arb(exact[0, 0].real) <= arb(far[2][0])


def test_dgp_roots_proven_in_balls_are_enclosed_to_double_precision(monkeypatch):
    """Seed 000 Test 2, taut set {2, 4, 5, 6}: the regular endpoints that double-precision intervals cannot certify
    (condition ~1e10) are proven in ball arithmetic (128 bits, then 256), each in a box one or two ulps wide: Newton's
    method converges because the constants (rho_i^2 among them) are exact (at 256 bits).  (With rho_i^2 rounded to 53
    bits the balls' F kept a radius of 1e-16, Newton ran to its step limit and the boxes came out up to 75 ulps wide.)
    The cap on ball retries holds per group (taut set), not per call: a subproblem's certificate does not depend on
    the subproblems certified with it (one thread certifies every set of an m in one call, two threads one set a
    call)."""
    from cdpr_algebra.certificates import endpoints as EP
    from cdpr_algebra.certificates import equilibria as EQ
    from cdpr_algebra.dgp import solve as D
    from cdpr_algebra.model.robot import load_robot

    robot = load_robot(ROOT / "examples" / "seed000_test2.toml")
    rho = np.asarray(robot.lengths, float)
    cables = (1, 3, 4, 5)
    _, _, Z = D._solve_taut_set(robot, rho, cables)
    ((double, _),) = EP.certify_endpoints(robot, rho, [(cables, Z)], [False])
    bad = np.flatnonzero(~double.proven)
    assert len(bad) >= 10
    boxes = type(double)(double.proven[bad], double.lo[bad], double.hi[bad], double.real[bad], double.nonreal[bad],
                         double.center[bad], tuple(double.reason[k] for k in bad))
    scale = np.broadcast_to(EQ._scales(robot, len(cables), range(12 + len(cables)), robot.cable_scale),
                            (Z.shape[1],))
    frame = robot.cable_frame  # certify_endpoints works in the cable frame
    out = EP._retry_in_balls(robot, rho, np.repeat(np.array(cables)[None], len(bad), axis=0),
                             to_cable_frame(Z[bad], frame), scale, boxes, np.ones(len(bad), bool), frame)
    assert out.proven.all()
    size = np.maximum(np.abs(np.hstack([out.center.real, out.center.imag])), np.hstack([scale, scale]))
    assert ((out.hi - out.lo) / size).max() <= 1e-15
    monkeypatch.setattr(EP, "BALL_RETRY_MAX", 3)
    group = np.arange(len(bad)) % 2  # two taut sets' worth of roots in one call
    capped = EP._retry_in_balls(robot, rho, np.repeat(np.array(cables)[None], len(bad), axis=0),
                                to_cable_frame(Z[bad], frame), scale, boxes, np.ones(len(bad), bool), frame, group)
    assert capped.proven.sum() == 6 and [capped.proven[group == g].sum() for g in (0, 1)] == [3, 3]
    assert all("more than 3 such roots in its taut set" in r for r, ok in zip(capped.reason, capped.proven) if not ok)


# a double-precision endpoint of the DGP of tests/data/huge_root_6cables.toml, taut set {1, 3, 5} (world coordinates
# (p, u, v, w, lam)): the input of the test below
HUGE_ROOT = [(-9667324.524646249 + 7441406.129816798j), (-7443803.329249347 - 9668513.696382299j),
             (-162391.15495623782 + 197290.62786348362j), (72751724.248739 + 17650356.943761144j),
             (-17647984.081265073 + 72769034.93022367j), (1615421.5306135067 + 82250.2305219806j),
             (-7185804.262631792 + 54233173.94060817j), (-54245568.76566881 - 7182738.068635891j),
             (65462.971252875315 + 1180219.1226514531j), (-18173611.967310596 + 49213383.14004993j),
             (-49225624.95376178 - 18173361.111614898j), (-187981.0778455026 + 1117822.3158931886j),
             (-0.0018815748487477457 - 0.002113351709200178j), (0.0014057843983488433 + 0.0033483587924911878j),
             (0.0003991701905537571 - 0.0012314297656117884j)]


def test_a_huge_ill_conditioned_root_is_proven_in_ball_arithmetic():
    """A root with |x| ~ 7.5e7 and condition ~1e18 in double precision, and its conjugate: double-precision intervals
    cannot prove them; in ball arithmetic Newton's first steps from the double-precision point do not shrink (relative
    8.0e-16, 8.9e-16, then 6.8e-15 at 128 bits), so a refinement that stopped when a step did not halve built the box
    around an unrefined point and proved neither (thirty-seventh session, d5a60f5).  Both proven, non-real, in
    disjoint boxes."""
    from cdpr_algebra import load_robot
    from cdpr_algebra.certificates.endpoints import certify_endpoints

    robot = load_robot(ROOT / "tests" / "data" / "huge_root_6cables.toml")
    z = np.array(HUGE_ROOT)
    [(boxes, meeting)] = certify_endpoints(robot, robot.lengths, [((0, 2, 4), np.array([z, z.conj()]))])
    assert boxes.proven.all(), boxes.reason
    assert boxes.nonreal.all() and not meeting.any()
