"""Issue 15: failed paths settled on regular roots that no other path holds (:mod:`cdpr_algebra.dgp.unheld_roots`).

The family a x^2 + x - 1 = 0, y^2 - b = 0 (four regular roots, known in closed form) solved by a parameter homotopy;
some of its paths are then marked failed with inexact last estimates, as a failed endgame leaves them.
"""

from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest
import sympy as sp

from cdpr_algebra.dgp.normalization import normalized_problem
from cdpr_algebra.dgp.unheld_roots import UNHELD_ROOT, settle_on_unheld_roots
from cdpr_algebra.homotopy.endgame import SolveOptions
from cdpr_algebra.homotopy.homotopies import ParameterHomotopy
from cdpr_algebra.homotopy.results import ENDGAME_FAILED, STEP_TOO_SMALL, outcome_counts
from cdpr_algebra.homotopy.solve import solve_parameter_homotopy
from cdpr_algebra.homotopy.systems import PolynomialSystem

ROOT = Path(__file__).resolve().parents[1]
P1 = np.array([0.7 + 0.4j, 1.3 - 0.6j])
P0 = np.array([0.3 - 0.2j, 1.0])
OPTS = SolveOptions(retry_tight=False, retry_mpmath=False)


def _family():
    x, y, a, b = sp.symbols("x y a b")
    return PolynomialSystem([a * x**2 + x - 1, y**2 - b], [x, y], [a, b], name="large_roots")


def _roots(a, b):
    r = np.sqrt(1 + 4 * a + 0j)
    return [np.array([x, y]) for x in ((-1 + r) / (2 * a), (-1 - r) / (2 * a)) for y in (np.sqrt(b + 0j), -np.sqrt(b + 0j))]


@pytest.fixture(scope="module")
def solved():
    fam = _family()
    start = np.array(_roots(*P1))
    res = solve_parameter_homotopy(fam, P1, start, P0, options=OPTS)
    assert outcome_counts(res.track.paths)["regular"] == 4
    return ParameterHomotopy(fam, P1, P0), res


def _failed(res, which, status=STEP_TOO_SMALL, winding=1):
    """``res`` with the paths ``which`` (index -> last estimate) failed."""
    paths = list(res.track.paths)
    for i, e in which.items():
        paths[i] = replace(paths[i], status=status, endpoint=np.asarray(e, dtype=complex), t=0.01 + 0j,
                           winding_number=winding)
    return replace(res, track=replace(res.track, paths=tuple(paths)))


def _index_of(res, root):
    return next(i for i, p in enumerate(res.track.paths) if np.allclose(p.endpoint, root, rtol=1e-10))


def test_failed_paths_end_on_the_roots_nobody_holds(solved):
    hom, res = solved
    r = _roots(*P0)
    i, j = _index_of(res, r[0]), _index_of(res, r[3])
    broken = _failed(res, {i: r[0] * (1 + 1e-3), j: r[3] * (1 - 2e-3)})
    out, left = settle_on_unheld_roots(hom, broken, OPTS, 1e-8)
    assert left == 0 and outcome_counts(out.track.paths)["regular"] == 4
    assert [out.track.paths[k].retried for k in (i, j)] == [UNHELD_ROOT] * 2
    got = sorted(tuple(np.round(p.endpoint, 9)) for p in out.track.paths)
    want = sorted(tuple(np.round(x, 9)) for x in r)
    assert np.allclose(np.array(got), np.array(want), rtol=1e-9)
    assert len(out.solutions) == 4


def test_a_root_another_path_holds_is_refused(solved):
    """The estimate of the failed path lies by a root that path k holds: Newton finds it, and it is not kept."""
    hom, res = solved
    r = _roots(*P0)
    i, k = _index_of(res, r[0]), _index_of(res, r[1])
    out, left = settle_on_unheld_roots(hom, _failed(res, {i: r[1] * (1 + 1e-4)}), OPTS, 1e-8)
    assert left == 1 and out.track.paths[i].status == STEP_TOO_SMALL
    assert np.allclose(out.track.paths[k].endpoint, r[1])


def test_the_partner_of_a_two_sheet_cycle_by_reflection(solved):
    """Two failed paths whose endgame saw one cycle of two sheets, both with the cycle's mean as their estimate
    (slightly off, as Cauchy estimates are): Newton from it finds one root, from its reflection through the mean
    the other.  Without the winding number 2 the reflection is not tried and one path stays failed."""
    hom, res = solved
    r = _roots(*P0)
    i, j = _index_of(res, r[0]), _index_of(res, r[2])  # the two x-roots with the same y
    mean = (r[0] + r[2]) / 2
    est = mean + 0.05 * (r[0] - mean)
    out, left = settle_on_unheld_roots(hom, _failed(res, {i: est, j: est}, ENDGAME_FAILED, 2), OPTS, 1e-8)
    assert left == 0
    ends = sorted(tuple(np.round(out.track.paths[k].endpoint, 9)) for k in (i, j))
    assert np.allclose(np.array(ends), np.array(sorted(tuple(np.round(x, 9)) for x in (r[0], r[2]))), rtol=1e-9)
    _, left1 = settle_on_unheld_roots(hom, _failed(res, {i: est, j: est}, ENDGAME_FAILED, 1), OPTS, 1e-8)
    assert left1 == 1


def test_large_force_robot_returns_its_equilibrium(monkeypatch):
    """A 6-cable robot built around an equilibrium with tensions 1e3 times the load (tests/large_forces.py): the two
    paths of a two-sheet cycle fail in the endgame; Newton from their estimate returns the constructed equilibrium
    (before, it was not returned: the subproblem was only flagged incomplete).  Since the thirty-first session the
    Study run's fast finish ends such ill-conditioned roots regular before (``ILL_CONDITIONED_LIMIT``): with it the
    equilibrium is returned too, and without it by the unheld-root step tested here."""
    import cdpr_algebra.dgp.study_retrack as SR
    from cdpr_algebra.dgp.solve import solve_taut_set
    from large_forces import equilibrium_hits, large_force_robot

    robot, p, R, tau = large_force_robot(6, 1e3, 300 + 60)
    for limit in (SR.ILL_CONDITIONED_LIMIT, 0.0):
        monkeypatch.setattr(SR, "ILL_CONDITIONED_LIMIT", limit)
        sub, sols = solve_taut_set(robot, robot.lengths, tuple(range(6)))
        assert limit or sub.retried.get(UNHELD_ROOT, 0) >= 1
        assert len(equilibrium_hits(sols, robot, tuple(range(6)), p, R, tau)[0]) == 1  # bench_large_forces' match
        assert sum(sub.outcomes.values()) == sub.paths == 40 and sub.complete


def test_roots_reached_in_study_parameters_settle_two_failed_paths(monkeypatch):
    """Seed 002's 8-cable robot, taut set {1, 3, 4, 5, 8}: two paths fail near t = 2e-5 where the pose grows without
    bound (N / |e|^2 ~ 3e-7); Newton's method in Study parameters from their last Study points reaches two roots that
    no other path holds (:func:`cdpr_algebra.dgp.study_retrack.study_roots`), and the subproblem is complete.  The
    roots are checked by 50-digit Newton in the taut system (independent of the double-precision refinement), and
    without the Study step the two paths stay failed.  (The endgame in double-double settles these two paths first,
    on the same roots, and since the thirty-first session the Study run's fast finish before it, ending the roots
    regular there (``ILL_CONDITIONED_LIMIT``): both are switched off here.)"""
    import mpmath

    import cdpr_algebra.dgp.solve as S
    import cdpr_algebra.dgp.study_retrack as SR

    monkeypatch.setattr(SR, "PRECISE_ENDGAME_PATHS", 0)
    monkeypatch.setattr(SR, "ILL_CONDITIONED_LIMIT", 0.0)
    from cdpr_algebra.model.robot import load_robot
    from cdpr_algebra.model.taut_equations import taut_family

    robot = load_robot(ROOT / "examples" / "seed002_8cables.toml")
    cables = (0, 2, 3, 4, 7)
    target = normalized_problem(robot, robot.lengths, cables)[0]
    res, failed = S._track(5, target, 0, gamma=False)
    paths = res.track.paths
    assert failed == 0 and outcome_counts(paths) == {"regular": 140, "singular": 0, "at_infinity": 0, "failed": 0}
    found = [p.endpoint for p in paths if p.retried == UNHELD_ROOT]
    others = [p.endpoint for p in paths if p.retried != UNHELD_ROOT]
    assert len(found) == 2
    F, J, _ = taut_family(5).mp_functions()
    with mpmath.workdps(50):
        pt = [mpmath.mpc(complex(v)) for v in target]
        for x0 in found:
            x = mpmath.matrix([mpmath.mpc(complex(v)) for v in x0])
            for _ in range(30):
                d = mpmath.lu_solve(J(list(x), pt), -F(list(x), pt))
                x = x + d
            assert mpmath.norm(d) < mpmath.mpf(10) ** -30  # converged: a root of the system solved
            root = np.array([complex(v) for v in x])
            assert np.max(np.abs(root - x0)) <= 1e-8 * np.max(np.abs(root))
            assert np.max(np.abs(root)) > 1e6  # a large pose, not at infinity
            assert all(np.max(np.abs(root - y)) > 1e-6 * np.max(np.abs(root)) for y in others)
    assert np.max(np.abs(found[0] - found[1])) > 1e-6 * np.max(np.abs(found[0]))
    sub = S.solve_taut_set(robot, robot.lengths, cables)[0]
    assert sub.complete and sub.certified == 140 and sub.retried == {UNHELD_ROOT: 2}


def test_without_the_study_roots_those_paths_stay_failed(monkeypatch):
    import cdpr_algebra.dgp.solve as S
    import cdpr_algebra.dgp.study_retrack as SR
    from cdpr_algebra.model.robot import load_robot

    robot = load_robot(ROOT / "examples" / "seed002_8cables.toml")
    target = normalized_problem(robot, robot.lengths, (0, 2, 3, 4, 7))[0]
    monkeypatch.setattr(SR, "PRECISE_ENDGAME_PATHS", 0)
    monkeypatch.setattr(SR, "ILL_CONDITIONED_LIMIT", 0.0)
    monkeypatch.setattr(S, "study_roots", lambda *a: np.zeros((0, 17), dtype=complex))
    res, failed = S._track(5, target, 0, gamma=False)
    assert failed == 2 and sum(p.retried == UNHELD_ROOT for p in res.track.paths) == 0


def test_the_endgame_in_double_double_reaches_the_same_two_roots(monkeypatch):
    """The same two paths, with the endgame over double-double on (the default): it ends them on one sheet at the
    roots that Newton's method in Study parameters reaches (same points to 1e-8 relative).  (The fast finish's
    rule for ill-conditioned roots, which ends them regular before, is switched off here.)"""
    import cdpr_algebra.dgp.solve as S
    import cdpr_algebra.dgp.study_retrack as SR
    from cdpr_algebra.model.robot import load_robot

    monkeypatch.setattr(SR, "ILL_CONDITIONED_LIMIT", 0.0)

    robot = load_robot(ROOT / "examples" / "seed002_8cables.toml")
    target = normalized_problem(robot, robot.lengths, (0, 2, 3, 4, 7))[0]
    res, failed = S._track(5, target, 0, gamma=False)
    got = [p for p in res.track.paths if p.retried == SR.PRECISE_ENDGAME]
    assert failed == 0 and len(got) == 2 and all(p.status == "success" for p in got)
    p_gen = S._generic(5)[0]
    est = [SR.to_study(p.endpoint[None], 5, SR.study_chart())[0] for p in got]
    roots = SR.study_roots(5, p_gen, target, est)
    assert len(roots) == 2
    for p in got:
        assert min(np.max(np.abs(r - p.endpoint)) for r in roots) <= 1e-8 * np.max(np.abs(p.endpoint))
    # with the rule (the default): the same two paths end regular at the fast finish, on the same roots
    monkeypatch.undo()
    fast, failed = S._track(5, target, 0, gamma=False)
    assert failed == 0
    for p in got:
        q = fast.track.paths[p.index]
        assert q.status == "success" and q.retried == ""
        assert np.max(np.abs(q.endpoint - p.endpoint)) <= 1e-8 * np.max(np.abs(p.endpoint))


def test_failed_paths_settle_on_the_roots_of_the_other_route():
    """Seed 000 Test 1, taut set {1, 2, 3} (156 paths): two paths of a run made to fail (last points far from any
    root) are settled on the regular roots of another run of the same target that no path of the first holds (the
    same roots, found again by Newton's method); a run whose own roots are offered settles nothing."""
    import cdpr_algebra.dgp.solve as S
    from cdpr_algebra.model.robot import load_robot

    robot = load_robot(ROOT / "examples" / "seed000_test1.toml")
    target = normalized_problem(robot, robot.lengths, (0, 1, 2))[0]
    res, failed = S._track(3, target, 0, gamma=False)
    assert failed == 0
    paths = list(res.track.paths)
    lost = [5, 77]
    for i in lost:
        paths[i] = replace(paths[i], status=STEP_TOO_SMALL, endpoint=paths[i].endpoint + 3.0, t=0.4 + 0j)
    bad = replace(res, track=replace(res.track, paths=tuple(paths)))
    settled, left = S._settle_on_other_runs_roots(3, target, bad, res, None)
    assert left == 0 and outcome_counts(settled.track.paths)["regular"] == 156
    assert all(settled.track.paths[i].retried == UNHELD_ROOT for i in lost)
    # the two roots, in some order (which failed path held which is not claimed)
    got = [settled.track.paths[i].endpoint for i in lost]
    for i in lost:
        assert min(np.max(np.abs(g - res.track.paths[i].endpoint)) for g in got) <= 1e-9
    _, left = S._settle_on_other_runs_roots(3, target, bad, bad, None)
    assert left == 2


def test_residual_bound_grows_with_the_size_of_a_root():
    """A fixed tolerance below the floor eps |x| of a root rounded to doubles; the bound follows it beyond."""
    from cdpr_algebra.dgp.unheld_roots import ROUNDING_RESIDUAL, residual_bound

    X = np.array([[1.0, 2.0], [3e2, 1.0], [7.4e7, 1.0j]])
    b = residual_bound(X, 1e-8)
    assert b[0] == b[1] == 1e-8 and np.isclose(b[2], ROUNDING_RESIDUAL * (1 + 7.4e7))
    assert b[2] > 1.3e-8  # the residual of seed 002's root below, Newton quadratic to 2.5e-14


def test_a_root_of_size_1e8_is_kept_and_certified():
    """Seed 002, taut set {2, 4, 6, 8}: a complex root with |x| = 7.4e7 (condition 9e11) reached by the endgame in
    double-double; in taut coordinates Newton converges quadratically but the residual of the nearest doubles is
    1.3e-8, above the fixed 1e-8, and the root was refused, its path failed in both routes.  With the residual bound
    the subproblem is complete and every endpoint is proven (ball arithmetic for that one)."""
    import cdpr_algebra.dgp.solve as S
    from cdpr_algebra.model.robot import load_robot

    robot = load_robot(ROOT / "examples" / "seed002_8cables.toml")
    sub, _ = S.solve_taut_set(robot, robot.lengths, (1, 3, 5, 7), certify=False)
    assert sub.complete and sub.outcomes["failed"] == 0 and sub.certified == 216


def test_conjugates_of_regular_roots_settle_failed_paths():
    """settle_on_conjugates (a real target): a failed path is settled on the conjugate of a non-real regular endpoint
    that no path holds, with that endpoint's residual and condition; a real endpoint, or one whose conjugate is held,
    settles nothing; two failed paths and one such conjugate leave one failed; the outcomes still add up."""
    from cdpr_algebra.dgp.solve import default_options
    from cdpr_algebra.dgp.unheld_roots import CONJUGATE, settle_on_conjugates
    from cdpr_algebra.homotopy.results import SUCCESS, PathResult, SolveResult, TrackResult

    opts = default_options()
    z = np.array([1.0 + 2.0j, -3.0 + 0.5j, 4.0 - 1.0j])
    r = np.array([0.5, 1.5, -2.0]) + 0j
    w = np.array([2.0 + 1.0j, 1.0 - 1.0j, 0.25 + 3.0j])

    def run(*paths):
        track = TrackResult(paths=tuple(PathResult(i, st, x, 0j if st == SUCCESS else 0.3 + 0j, 1e-15, 1e12, 1e-16, 50)
                                        for i, (st, x) in enumerate(paths)), seconds=0.0, seed=0)
        return SolveResult(solutions=(), track=track)

    failed = np.zeros(3, dtype=complex)
    res, left = settle_on_conjugates(run((SUCCESS, z), (SUCCESS, r), (SUCCESS, w), (SUCCESS, np.conj(w)),
                                         (STEP_TOO_SMALL, failed)), opts)
    assert left == 0
    p = res.track.paths[4]
    assert p.status == SUCCESS and p.retried == CONJUGATE and np.array_equal(p.endpoint, np.conj(z))
    assert p.condition == 1e12 and p.residual == 1e-15 and outcome_counts(res.track.paths)["regular"] == 5
    res, left = settle_on_conjugates(run((SUCCESS, z), (STEP_TOO_SMALL, failed), (STEP_TOO_SMALL, failed)), opts)
    assert left == 1 and sum(q.retried == CONJUGATE for q in res.track.paths) == 1
    res, left = settle_on_conjugates(run((SUCCESS, r), (SUCCESS, w), (SUCCESS, np.conj(w)),
                                         (STEP_TOO_SMALL, failed)), opts)
    assert left == 1 and res.track.paths[3].status == STEP_TOO_SMALL
