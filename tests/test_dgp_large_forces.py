"""Issue 15: robots built around a known equilibrium whose cables carry internal forces K = 1e2 .. 1e6 times
the load (tests/large_forces.py), m = 3 .. 6 taut cables.  Such forces need a nearly singular wrench matrix, so
the equilibrium is an ill-conditioned solution of the DGP equations (condition numbers of 1e12 and more were
measured): double precision may not reach it.  What is promised, and checked: the DGP returns the equilibrium
(pose and tensions), or the subproblem says it is incomplete (failed paths, complete false) -- a finite solution
is never dropped silently because it is large; and where the paths all finish, it is returned.
"""

import functools

import numpy as np
import pytest

from cdpr_algebra.dgp.normalization import normalized_coordinates, normalized_problem, world_coordinates
from cdpr_algebra.dgp.solve import solve_taut_set
from large_forces import (equilibrium_hits, large_force_robot, matches, root_of_the_robot_system,
                          root_of_the_solved_system)

# (3, 1e2) is the robot of test_moderate_internal_forces_are_found: one solve (solved_without_certificates) and one
# worker for both
SHARED = pytest.mark.xdist_group("large_forces_3_1e2")
CASES = [pytest.param(3, 1e2, marks=SHARED), (3, 1e4), (3, 1e6), (6, 1e2), (6, 1e4), (6, 1e6),
         pytest.param(4, 1e2, marks=pytest.mark.slow), pytest.param(4, 1e6, marks=pytest.mark.slow),
         pytest.param(5, 1e2, marks=pytest.mark.slow), pytest.param(5, 1e6, marks=pytest.mark.slow)]


@functools.cache
def solved_without_certificates(m, K, seed):
    """(robot, p, R, tau, sub, sols): large_force_robot(m, K, seed) and its taut set of all m cables solved without
    certificates (a cache: two tests read the same ~30-90 s solve)."""
    robot, p, R, tau = large_force_robot(m, K, seed)
    return (robot, p, R, tau, *solve_taut_set(robot, robot.lengths, tuple(range(m)), certify=False))


@pytest.mark.parametrize("m, K", CASES)
def test_large_internal_forces_are_found_or_flagged(m, K):
    robot, p, R, tau, sub, sols = solved_without_certificates(m, K, 100 + m)
    Q = robot.load
    B = p + robot.platform @ R.T
    U = (robot.base - B) / robot.lengths[:, None]
    G = p + R @ robot.com
    # the construction: an exact equilibrium with max tension K Q
    assert 0.5 <= tau.max() / (K * Q) <= 1.5 and np.all(tau > 0)
    scale = tau.max()
    assert np.abs(tau @ U + Q * robot.load_direction).max() <= 1e-9 * scale
    mom = sum(t * np.cross(b, u) for t, b, u in zip(tau, B, U)) + np.cross(G, Q * robot.load_direction)
    assert np.abs(mom).max() <= 1e-9 * scale * robot.size
    assert sum(sub.outcomes.values()) == sub.paths == sub.generic_count
    found = len(equilibrium_hits(sols, robot, tuple(range(m)), p, R, tau)[0]) == 1
    # flagged: failed paths, or regular endpoints not proven roots
    assert found or not sub.complete, (sub.outcomes, [s.position for s in sols])
    if sub.complete:
        assert found


def test_ill_conditioned_equilibrium_is_polished_to_the_robots_root_and_certified():
    """m = 6, K = 1e3 (condition ~1e11): the homotopy solves the normalized system, whose parameters are rounded to
    doubles; its root differs from the robot's own by ~2e-5 in the tensions, beyond the box width limit (1e-6) of a
    certificate.  The endpoint certificates move it (ball arithmetic) and so does the equilibrium's certificate
    (polished_taut_root): the subproblem is complete (every endpoint proven, boxes disjoint) and the equilibrium
    returned is the robot's root (60-digit Newton), certified, with the move recorded."""
    m = 6
    robot, p, R, tau = large_force_robot(m, 1e3, 360)
    cables = tuple(range(m))
    sub, sols = solve_taut_set(robot, robot.lengths, cables, certify=True)
    solved = root_of_the_solved_system(robot, cables, p, R, tau)
    own = root_of_the_robot_system(robot, cables, p, R, tau)
    assert solved is not None and own is not None
    assert np.max(np.abs(solved[2] - own[2]) / own[2]) > 1e-6  # the two systems' roots are that far apart
    assert sub.complete and sub.certified == sub.outcomes["regular"] == sub.generic_count
    (s,) = [s for s in sols if matches(s, *own, robot.size)]
    assert s.certificate.certified and s.certificate.extra["polished"] > 1e-6
    assert not matches(s, *solved, robot.size)


@SHARED
def test_moderate_internal_forces_are_found():
    """K = 100 with three cables: the equilibrium is returned with its tensions (4 of the 156 paths fail here,
    measured in the thirtieth session: elsewhere, not on the equilibrium's path)."""
    robot, p, R, tau, sub, sols = solved_without_certificates(3, 1e2, 103)
    hits = [s for s in sols if np.max(np.abs(s.position - p)) <= 1e-6 * robot.size]
    assert len(hits) == 1 and np.allclose(hits[0].tensions, tau, rtol=1e-6)


def _returned_or_incomplete(m, K, seed):
    """The taut set of all m cables of large_force_robot(m, K, seed), with certificates: its outcomes add up, and
    the equilibrium is returned or the subproblem says it is incomplete."""
    robot, p, R, tau = large_force_robot(m, K, seed)
    sub, sols = solve_taut_set(robot, robot.lengths, tuple(range(m)), certify=True)
    assert sum(sub.outcomes.values()) == sub.paths == sub.generic_count
    hits = [s for s in sols if np.max(np.abs(s.position - p)) <= 1e-4 * robot.size]
    assert hits or not sub.complete, sub.outcomes


@pytest.mark.parametrize("m, K, seed", [(6, 1e2, 360), (3, 1e5, 333)])
def test_a_cauchy_mean_that_does_not_solve_the_system_is_not_a_singular_endpoint(m, K, seed):
    """Wrench matrices within ~3e-5 of singular: the equilibrium is a regular root of condition ~1e10 (60-digit
    Newton converges to it quadratically, measured) at the end of two paths that circle a near-double root.  Their
    Cauchy mean solved the chart system to 2e-7 but the affine one only to 5e-4 .. 5e-2, and was reported singular,
    the subproblem complete and the equilibrium missing.  Now such a mean is endgame_failed: the equilibrium is
    returned or the subproblem is incomplete, and every singular endpoint solves the system in affine coordinates."""
    _returned_or_incomplete(m, K, seed)


def test_a_path_is_not_decided_at_infinity_from_estimates_that_did_not_converge():
    """A wrench matrix within 3e-5 of singular, tensions 1e4 times the load: the equilibrium (|lam| ~ 2e4, a regular
    root: 60-digit Newton converges to it, measured) is one of a near-double pair across infinity.  At the twelve
    sample radii (t down to ~6e-9) its two paths still circle the pair's branch point and the Cauchy estimates do not
    settle; the best of them has y0 ~ 0, and the paths were decided at infinity, the subproblem complete without the
    equilibrium.  Sampled further (EndgameOptions.infinity_samples) they are not decided: the equilibrium is
    returned or the subproblem is incomplete."""
    _returned_or_incomplete(6, 1e4, 360)


@pytest.mark.parametrize("m, seed", [(6, 362), (3, 340)])
def test_tensions_alone_going_to_infinity_is_undecided(m, seed):
    """Tensions 1e5 times the load on a nearly singular wrench matrix: the equilibrium (a regular root, confirmed by
    60-digit Newton) is one of a near-double pair across infinity whose two paths converge, at every radius the
    endgame reaches, to their average with y0 ~ 0, and were decided at infinity with only the tension multipliers
    growing.  That needs an exactly singular wrench matrix, which double precision cannot establish: those paths are
    now endgame_failed and the subproblem incomplete (or the equilibrium returned), never complete without it."""
    _returned_or_incomplete(m, 1e5, seed)


def test_far_centre_of_mass_is_returned_and_complete():
    """m = 5, K = 1e5: the construction puts the centre of mass ~1e4 robot sizes from the attachment points.
    Normalized by robot.size (which includes |b'_i - g'|) every one of the 140 paths failed (thirteenth session);
    normalized by the cable geometry's own scale (dgp.normalization.normalized_problem) all finish and the equilibrium is
    returned with its tensions and certified."""
    robot, p, R, tau = large_force_robot(5, 1e5, 380)
    assert np.linalg.norm(robot.com - robot.platform.mean(axis=0)) > 1e3 * np.ptp(robot.base, axis=0).max()
    sub, sols = solve_taut_set(robot, robot.lengths, tuple(range(5)), certify=True)
    assert sub.complete and sub.outcomes["regular"] == sub.generic_count == 140
    hits = [s for s in sols if np.max(np.abs(s.position - p)) <= 1e-9 * np.abs(p).max()
            and np.max(np.abs(s.rotation - R)) <= 1e-9]
    assert len(hits) == 1 and np.allclose(hits[0].tensions, tau, rtol=1e-6)
    # its certificate: proven in the cable frame (Robot.cable_frame, certificates.equilibria) with box scales from the
    # root's own magnitudes; in the robot's frames with scales L and Q / L no box was proven (thirteenth session)
    c = hits[0].certificate
    assert c.certified and c.tension_signs == ("positive",) * 5
    assert np.all(c.tension_lower[:5] <= tau * (1 + 1e-6)) and np.all(c.tension_upper[:5] >= tau * (1 - 1e-6))
    assert np.all(c.position_upper - c.position_lower <= 1e-10 * np.abs(p).max())
    assert np.all(c.position_lower <= hits[0].position) and np.all(hits[0].position <= c.position_upper)


def test_the_platform_frame_origin_does_not_matter():
    """Seed 000 Test 1 with its platform frame moved 1000 robot sizes away (b'_i and g' shifted by d): the same
    equilibria, cable attachment points B_i and tensions, with the pose's origin moved by -R d."""
    from cdpr_algebra.dgp.solve import dgp
    from cdpr_algebra.model.robot import Robot, load_robot

    robot = load_robot("examples/seed000_test1.toml")
    d = np.array([1.0, -2.0, 0.5]) * 1e3 * robot.size
    moved = Robot(robot.base, robot.platform + d, robot.com + d, robot.load, robot.load_direction, robot.lengths,
                  robot.name)
    a, b = dgp(robot, certify=False), dgp(moved, certify=False)
    assert len(a.solutions) == len(b.solutions) == 6

    def attachments(sol, r):
        return sol.position + r.platform @ sol.rotation.T

    for s in a.solutions:  # each equilibrium has its twin (the order, by position, differs)
        twins = [t for t in b.solutions if t.taut == s.taut and np.allclose(
            attachments(s, robot), attachments(t, moved), rtol=0, atol=1e-9 * robot.size)]
        assert len(twins) == 1
        t = twins[0]
        assert np.allclose(t.position, s.position - s.rotation @ d, rtol=0, atol=1e-9 * np.abs(d).max())
        assert np.allclose(s.tensions, t.tensions, rtol=1e-8, atol=1e-9 * robot.load)
        assert s.hessian == t.hessian


def test_an_ill_conditioned_equilibrium_is_polished_and_certified():
    """m = 6, K = 1e3: the system's condition number is about 1e9, so doubles know the root only to ~1e-8 of its
    size, and no box of relative width 1e-9 around the constructed (rounded) equilibrium holds a zero: its
    certificate fails, even at 128 bits.  Newton's method with the residual in 128-bit balls polishes it
    (polished_taut_root), and the polished root is certified; the DGP reports the polished root, inside its
    certificate's tolerance, with the constructed tensions to 1e-6."""
    from cdpr_algebra.certificates.equilibria import certify_taut_root, polished_taut_root

    robot, p, R, tau = large_force_robot(6, 1e3, 391)
    first = certify_taut_root(robot, None, range(6), p, R, tau)
    assert not first.exists_unique and "Newton step" in first.reason
    pp, RR, tt = polished_taut_root(robot, None, range(6), p, R, tau)
    assert 0 < np.abs(tt - tau).max() <= 1e-6 * tau.max() and np.abs(pp - p).max() <= 1e-6 * robot.cable_scale
    cert = certify_taut_root(robot, None, range(6), pp, RR, tt)
    assert cert.certified and cert.tension_signs == ("positive",) * 6
    assert np.all(cert.tension_lower <= tt) and np.all(tt <= cert.tension_upper)
    sub, sols = solve_taut_set(robot, robot.lengths, tuple(range(6)))
    hits = [s for s in sols if np.allclose(s.tensions, tau, rtol=1e-6)]
    assert len(hits) == 1 and hits[0].certified
    c, s = hits[0].certificate, hits[0]
    assert 1e-10 < c.extra["polished"] <= 1e-6 and c.to_dict()["polished"] == c.extra["polished"]
    for value, lo, hi in ((s.position, c.position_lower, c.position_upper), (s.tensions, c.tension_lower,
                                                                              c.tension_upper)):
        slack = 1e-9 * np.abs(value).max()  # the reported root lies within the box tolerance of the proven zero
        assert np.all(lo - slack <= value) and np.all(value <= hi + slack)


def test_far_platform_frame_endpoints_are_certified():
    """m = 4, K = 1e5: the platform points lie 1.7e4 cable-geometry sizes from the platform frame's origin.  In the
    robot's own frames 4 of the 215 regular endpoints were proven distinct roots (rotation errors multiplied by that
    distance); in the cable frame (Robot.cable_frame, certificates.equilibria) every one is."""
    robot, _, _, _ = large_force_robot(4, 1e5, 370)
    assert np.linalg.norm(robot.platform.mean(axis=0)) > 1e3 * robot.cable_scale
    sub, _ = solve_taut_set(robot, robot.lengths, tuple(range(4)), certify=False)
    assert sub.certified == sub.outcomes["regular"] >= 200


def test_normalized_coordinates_invert_world_coordinates():
    """dgp.normalization's map to the normalized problem (normalized_coordinates) and back (world_coordinates) are inverse
    on random complex rows, and the constructed equilibrium of a far-centre-of-mass robot maps to a root of the
    normalized system the tracker solves (residual at rounding level)."""
    import cdpr_algebra.dgp.solve as D
    from cdpr_algebra.model.taut_equations import encode

    m = 5
    robot, p, R, tau = large_force_robot(m, 1e5, 380)
    target, c, L, Rw, cb = normalized_problem(robot, robot.lengths, range(m))
    rng = np.random.default_rng(7)
    X = rng.normal(size=(4, 12 + m)) + 1j * rng.normal(size=(4, 12 + m))
    for Y in (world_coordinates(normalized_coordinates(X, m, c, L, Rw, cb, robot.load), m, c, L, Rw, cb,
                                   robot.load),
              normalized_coordinates(world_coordinates(X, m, c, L, Rw, cb, robot.load), m, c, L, Rw, cb,
                                        robot.load)):
        assert np.allclose(Y, X, rtol=0, atol=1e-9 * np.abs(X).max())
    x = normalized_coordinates(encode(p, R, tau / robot.lengths)[None], m, c, L, Rw, cb, robot.load)
    F, _ = D.fast_family(m).evaluate_and_jacobian(x.astype(complex), target)
    assert np.abs(F).max() <= 1e-9 * np.abs(x).max() ** 2


def test_pair_of_condition_1e14_settles_the_last_two_paths(monkeypatch):
    """m = 6, K = 1e4 (seed 360): the equilibrium and its partner (tensions of both signs) have condition numbers
    ~1.2e14; their two paths fail in both routes, and Newton's method from the paths' last estimates converges to
    them (residual ~1e-17, last update ~1e-15).  Kept up to unheld_roots.MAX_CONDITION (1e15), the subproblem is
    complete and the equilibrium certified; at the former bound 1e14 the two paths stay failed, unless tracked again
    in double-double from their start points (dgp.taut_extended), which reaches both."""
    import cdpr_algebra.dgp.unheld_roots as U
    from cdpr_algebra.dgp.taut_extended import MAX_PATHS

    m = 6
    robot, p, R, tau = large_force_robot(m, 1e4, 360)
    cables = tuple(range(m))
    own = root_of_the_robot_system(robot, cables, p, R, tau)
    sub, sols = solve_taut_set(robot, robot.lengths, cables, certify=True)
    assert sub.complete and sub.retried.get("unheld_root") == 2
    (s,) = [s for s in sols if matches(s, *own, robot.size)]
    assert s.certificate.certified
    import cdpr_algebra.dgp.solve as D

    monkeypatch.setattr(U, "MAX_CONDITION", 1e14)
    monkeypatch.setattr(D, "AUTO_RESCUE_MAX_FAILED", 0)  # the double-double rescue reaches them too
    monkeypatch.setattr(D, "EXTENDED_MAX_FAILED", 0)  # and so do the double-double tracks in (p, u, v, w, lam)
    sub, _ = solve_taut_set(robot, robot.lengths, cables, certify=False)
    assert not sub.complete and sub.outcomes["failed"] == 2
    monkeypatch.setattr(D, "EXTENDED_MAX_FAILED", MAX_PATHS)  # (the default)
    sub, _ = solve_taut_set(robot, robot.lengths, cables, certify=False)
    assert sub.complete and sub.retried.get("taut_extended") == 2


def test_tension_only_growth_in_the_study_run_is_not_at_infinity():
    """m = 3, K = 1e6 (the robots of benchmarks/bench_large_forces.py --m 3 --K 1e6): the equilibrium (|lam| ~ 2e6 in
    the normalized system, a regular root) is one of a near-double pair whose two paths, tracked in Study parameters,
    circle the pair's branch point at every radius the precise endgame reaches: pose steady, |lam| ~ t^-1/2.  The
    Study run put them at infinity ((g, lam) unbounded) without the test that the taut system's paths get
    (dgp.tension_infinity), and all four robots said complete without their equilibrium (thirtieth session).  Now
    those paths fail and are settled on the roots Newton's method reaches (dgp.unheld_roots): for seed 302 the
    equilibrium is returned, certified, and the subproblem complete; seed 301 returns it or says incomplete."""
    robot, p, R, tau = large_force_robot(3, 1e6, 302)
    cables = (0, 1, 2)
    sub, sols = solve_taut_set(robot, robot.lengths, cables, certify=True)
    assert sum(sub.outcomes.values()) == sub.paths == sub.generic_count
    hits, _ = equilibrium_hits(sols, robot, cables, p, R, tau)
    assert len(hits) == 1 and hits[0].certified and sub.complete
    assert tau.max() >= 0.5e6 * robot.load  # the tensions are as built
    _returned_or_incomplete(3, 1e6, 301)


def test_real_polish_does_not_move_an_ill_conditioned_root():
    """m = 6, K = 1e6 (bench_large_forces --m 6 --K 1e6, seed 363): the equilibrium is among the 40 proven endpoints
    (2e-16 from the root of the solved system), but the real Newton polish of the admissible endpoints, in double
    precision at a condition number ~1e14, moved its tensions by 0.2 %; its certificate failed and it was returned
    off the root (thirtieth session).  The polish now keeps an update only where it does not increase the residual:
    the equilibrium is returned certified, its box holding the robot's own root (60-digit Newton)."""
    robot, p, R, tau = large_force_robot(6, 1e6, 363)
    cables = tuple(range(6))
    sub, sols = solve_taut_set(robot, robot.lengths, cables, certify=True)
    own = root_of_the_robot_system(robot, cables, p, R, tau)
    assert own is not None
    (s,) = [s for s in sols if matches(s, *own, robot.size)]
    c = s.certificate
    assert s.certified and c.tension_signs == ("positive",) * 6
    assert np.all(c.tension_lower[:6] <= own[2]) and np.all(own[2] <= c.tension_upper[:6])
