"""The DGP equations in Study parameters (model.study_equations, generated evaluator) and the re-tracking of failed
paths in them (dgp.study_retrack)."""

from dataclasses import replace

import numpy as np
import pytest

from cdpr_algebra.dgp.normalization import normalized_problem, world_coordinates
from cdpr_algebra import load_robot
from cdpr_algebra.dgp import solve as S
from cdpr_algebra.dgp.kernels import study_fj, study_fjt
from cdpr_algebra.dgp.study_retrack import retrack_failed_in_study, study_chart
from cdpr_algebra.homotopy.results import STEP_TOO_SMALL, SUCCESS
from cdpr_algebra.model.study_equations import from_study, rotation_quaternions, study_family, to_study
from cdpr_algebra.model.taut_equations import taut_family
from kernel_checks import assert_kernels_equal_family

ROOT = __import__("pathlib").Path(__file__).resolve().parent.parent


@pytest.mark.parametrize("m", [2, 3, 4, 5, 6])
def test_study_kernels_equal_sympy_family(m):
    assert_kernels_equal_family(study_family(m), study_fj, study_fjt, np.random.default_rng(10 + m), 2)


def test_quaternions_of_rotations():
    """R(e) of the quaternions found is the rotation, for real rotations (every branch of the formula) and complex
    ones with large entries (exp of a complex skew matrix)."""
    from scipy.linalg import expm

    rng = np.random.default_rng(3)
    Rs = [np.diag([1.0, -1.0, -1.0]), np.diag([-1.0, 1.0, -1.0]), np.diag([-1.0, -1.0, 1.0]), np.eye(3)]
    for _ in range(6):
        w = rng.normal(size=3) * 3 + 1j * rng.normal(size=3) * 4
        K = np.array([[0, -w[2], w[1]], [w[2], 0, -w[0]], [-w[1], w[0], 0]])
        Rs.append(expm(K))
    n = np.array([1.0, 2.0, 2.0]) / 3  # the angle 1 + 8i about n: entries ~ e^8 / 2
    Rs.append(expm((1 + 8j) * np.array([[0, -n[2], n[1]], [n[2], 0, -n[0]], [-n[1], n[0], 0]])))
    Rs = np.array(Rs, dtype=complex)
    assert np.max(np.abs(Rs[-1])) > 1e3  # a complex rotation far from the real ones
    X = np.hstack([rng.normal(size=(len(Rs), 3)), Rs[:, :, 0], Rs[:, :, 1], Rs[:, :, 2], rng.normal(size=(len(Rs), 2))])
    e = rotation_quaternions(Rs)
    assert np.all(np.abs(np.sum(e * e, axis=1)) > 0)
    back = from_study(to_study(X, 2, study_chart()), 2)
    assert np.max(np.abs(back - X) / (1 + np.abs(X))) < 1e-10


@pytest.mark.parametrize("m", [2, 3, 4, 5, 6])
def test_generic_solutions_map_to_study_solutions(m):
    """Every stored generic solution of the taut family, mapped to Study parameters, solves the Study family at the
    same parameters (with the chart), and maps back to itself."""
    p, X = S._generic(m)
    c = study_chart()
    Y = to_study(X, m, c)
    F = study_family(m).evaluate(Y, np.concatenate([p, c]))
    assert np.max(np.abs(F) / (1 + np.max(np.abs(Y), axis=1))[:, None] ** 3) < 1e-9
    assert np.max(np.abs(from_study(Y, m) - X)) <= 1e-9 * (1 + np.max(np.abs(X)))
    assert np.max(np.abs(taut_family(m).evaluate(from_study(Y, m), p))) < 1e-8 * (1 + np.max(np.abs(X))) ** 2


@pytest.mark.parametrize("cables,gamma", [((0, 1), False), ((0, 1, 2), True)])
def test_retracked_paths_end_where_the_taut_paths_end(cables, gamma):
    """Tracked again in Study parameters along the same route (the straight segment, or the gamma drawn from the same
    seed), every path of a Test 1 subproblem ends on the point that the same path reached in (p, u, v, w, lam): each
    path is marked failed, re-tracked, and must come back with its own endpoint (a wrong route or map would swap or
    lose them)."""
    robot = load_robot(ROOT / "examples" / "seed000_test1.toml")
    rho = np.asarray(robot.lengths, float)
    m = len(cables)
    target = normalized_problem(robot, rho, cables)[0]
    seed = 5
    res, failed = S._track(m, target, seed, gamma=gamma)
    assert failed == 0
    paths = res.track.paths
    assert all(p.status == SUCCESS for p in paths)
    marked = replace(res, track=replace(res.track, paths=tuple(replace(p, status=STEP_TOO_SMALL) for p in paths)))
    p_gen, X_gen = S._generic(m)
    again, rescued = retrack_failed_in_study(S.fast_family(m), marked, m, p_gen, X_gen, target, seed, gamma,
                                             S.default_options())
    assert rescued == len(paths)
    for before, after in zip(paths, again.track.paths):
        assert after.status == SUCCESS and after.retried == "study"
        assert np.max(np.abs(after.endpoint - before.endpoint)) <= 1e-8 * (1 + np.max(np.abs(before.endpoint)))
    assert len(again.solutions) == len(paths)


def test_retrack_never_merges():
    """A path whose Study run ends on another path's endpoint stays failed: two paths marked failed, one of them
    also keeping its success (so its point is taken), the other rescued only when its point is new."""
    robot = load_robot(ROOT / "examples" / "seed000_test1.toml")
    rho = np.asarray(robot.lengths, float)
    target = normalized_problem(robot, rho, (0, 1))[0]
    res, _ = S._track(2, target, 0, gamma=False)
    paths = list(res.track.paths)
    # path 1 is marked failed but path 0 is given path 1's endpoint: the point path 1 reaches is already held
    paths[0] = replace(paths[0], endpoint=paths[1].endpoint)
    paths[1] = replace(paths[1], status=STEP_TOO_SMALL)
    marked = replace(res, track=replace(res.track, paths=tuple(paths)))
    p_gen, X_gen = S._generic(2)
    again, rescued = retrack_failed_in_study(S.fast_family(2), marked, 2, p_gen, X_gen, target, 0, False,
                                             S.default_options())
    assert rescued == 0 and again.track.paths[1].status == STEP_TOO_SMALL


def test_study_residual_in_double_double():
    """The generated double-double residual of the Study family rounds to the float residual (random complex points,
    m = 2 and 5), through the tracker's own entry point (compiled.residual_dd of a parameter homotopy, t = 0)."""
    from cdpr_algebra.dgp.study_retrack import fast_study_family
    from cdpr_algebra.homotopy.compiled import residual_dd
    from cdpr_algebra.homotopy.homotopies import ParameterHomotopy

    rng = np.random.default_rng(7)
    for m in (2, 5):
        sys_ = fast_study_family(m)
        p1 = rng.normal(size=sys_.m) + 1j * rng.normal(size=sys_.m)
        p0 = rng.normal(size=sys_.m) + 1j * rng.normal(size=sys_.m)
        X = rng.normal(size=(4, sys_.n)) + 1j * rng.normal(size=(4, sys_.n))
        dd = residual_dd(ParameterHomotopy(sys_, p1, p0))(X, 0.0)
        F = study_family(m).evaluate(X, p0)
        assert np.max(np.abs(dd - F)) <= 1e-12 * (1 + np.max(np.abs(F)))


def test_ill_conditioned_study_limits_are_rescued_and_proven(monkeypatch):
    """Test 2's taut set {1, 2, 4, 6}: 39 of its 216 paths fail in (p, u, v, w, lam).  Tracked in Study parameters,
    most of them end at complex poses with |R| ~ 1e5 whose Study Jacobians have condition numbers 1e12-1e16: the
    endgame calls them singular by the condition number alone (one sheet, winding number 1; 60-digit Newton converges
    quadratically there, sixteenth session), and before they were left failed.  Newton's method in the taut system
    settles them; every regular endpoint of the subproblem, those included, is then proven a root unique in its box,
    the boxes pairwise disjoint (ball arithmetic where double precision does not suffice)."""
    from cdpr_algebra.certificates.endpoints import certify_endpoints
    from cdpr_algebra.dgp import study_retrack as SR

    robot = load_robot(ROOT / "examples" / "seed000_test2.toml")
    rho = np.asarray(robot.lengths, float)
    cables = (0, 1, 3, 5)
    target, c, L, Rw, cb = normalized_problem(robot, rho, cables)
    monkeypatch.setattr(S, "STUDY_FIRST", False)  # the taut system first, then the re-track of its failures
    monkeypatch.setattr(S, "STUDY_RETRACK", False)
    monkeypatch.setattr(S, "UNHELD_ROOTS", False)  # the re-track's own rules are tested here (dgp.unheld_roots: 25 of
    res, failed = S._track(4, target, 0, gamma=False)  # the 39 failed paths settled by Newton from their estimates)
    assert failed >= 30
    p_gen, X_gen = S._generic(4)
    again, rescued = retrack_failed_in_study(S.fast_family(4), res, 4, p_gen, X_gen, target, 0, False,
                                             S.default_options())
    assert rescued >= 30
    kept = [p for p in again.track.paths if p.retried == "study"]
    assert len(kept) == rescued and max(p.condition for p in kept) > 1e10  # beyond the endgame's regular bound
    regular = np.array([p.endpoint for p in again.track.paths if p.status == SUCCESS])
    Z = world_coordinates(regular, 4, c, L, Rw, cb, robot.load)
    ((boxes, over),) = certify_endpoints(robot, rho, [(list(cables), Z)], [True])
    assert boxes.proven.all() and not over.any()
    # without the singular limits of one sheet (the fifteenth session's rule) the fast finish's rule for
    # ill-conditioned roots (ILL_CONDITIONED_LIMIT, thirty-first session) rescues them as well; without both they
    # stay failed
    monkeypatch.setattr(SR, "_limit_of_one_sheet", lambda q, o: False)
    _, alone = retrack_failed_in_study(S.fast_family(4), res, 4, p_gen, X_gen, target, 0, False, S.default_options())
    assert alone >= 30
    monkeypatch.setattr(SR, "ILL_CONDITIONED_LIMIT", 0.0)
    _, before = retrack_failed_in_study(S.fast_family(4), res, 4, p_gen, X_gen, target, 0, False, S.default_options())
    assert before <= rescued - 30
    # the default DGP tracks every path in Study parameters first: 216 regular points, none failed, the same ones
    monkeypatch.undo()
    first, failed = S._track(4, target, 0, gamma=False)
    assert failed == 0 and all(p.status == SUCCESS and p.retried == "" for p in first.track.paths)
    # path by path (the same parameter path: the same solution curve), the same point: to 1e-8 where the re-track
    # ended regular too, to the endgame's accuracy (~1e-7) where it ended singular (its Cauchy estimate)
    for a, b in zip(first.track.paths, again.track.paths):
        d = np.abs(a.endpoint - b.endpoint).max() / (1 + np.abs(b.endpoint).max())
        assert d <= (1e-8 if b.status == SUCCESS else 1e-6), (a.index, b.status, d)


def _fallback_case(monkeypatch, study_failed, taut_points):
    """:func:`track_study_first` on seed 000 Test 1's taut set {1, 2} (24 paths) with the Study run's paths
    ``study_failed`` made failed and the taut system's run replaced: ``taut_points(rows, study) -> {row: endpoint}``
    (``study``: the Study run's endpoints).  Returns (result, the rows the taut system was asked for, per call)."""
    from cdpr_algebra.dgp import study_retrack as SR
    from cdpr_algebra.homotopy.results import PathResult, SolveResult, TrackResult

    robot = load_robot(ROOT / "examples" / "seed000_test1.toml")
    target = normalized_problem(robot, np.asarray(robot.lengths, float), (0, 1))[0]
    p_gen, X_gen = S._generic(2)
    real = SR.retrack_failed_in_study
    seen = {}

    def study_run(*a, **k):
        res, n = real(*a, **k)
        seen["study"] = [p.endpoint for p in res.track.paths]
        paths = tuple(replace(p, status=STEP_TOO_SMALL) if p.index in study_failed else p for p in res.track.paths)
        return replace(res, track=replace(res.track, paths=paths)), n

    calls = []

    def track_taut(rows):
        calls.append(list(rows))
        pts = taut_points(list(rows), seen["study"])
        paths = tuple(PathResult(k, SUCCESS, pts[i], 0j, 1e-16, 10.0, 1e-14, 7) for k, i in enumerate(rows))
        return SolveResult(solutions=(), track=TrackResult(paths=paths, seconds=0.0))

    monkeypatch.setattr(SR, "retrack_failed_in_study", study_run)
    res = SR.track_study_first(S.fast_family(2), 2, p_gen, X_gen, target, 0, False, S.default_options(), track_taut)
    return res, calls, seen["study"]


def test_study_first_takes_the_taut_outcome_of_what_study_leaves_failed(monkeypatch):
    """A path the Study run leaves failed is tracked in the taut system and takes that outcome (retried "taut");
    a taut endpoint on a point a Study path holds sends that Study path to the taut system too: when it ends on a
    new point there, both stand (the Study run had jumped), else the taut path is path_jumping (nothing merged)."""
    from cdpr_algebra.dgp.study_retrack import TAUT_FALLBACK
    from cdpr_algebra.homotopy.results import PATH_JUMPING, outcome_counts

    # path 3 failed in Study, its taut run ends on its own Study point: kept
    res, calls, study = _fallback_case(monkeypatch, {3}, lambda rows, st: {i: st[i] for i in rows})
    assert calls == [[3]] and res.track.paths[3].status == SUCCESS and res.track.paths[3].retried == TAUT_FALLBACK
    assert res.track.paths[3].steps > 7  # the fake taut run's 7 steps and the Study run's
    assert outcome_counts(res.track.paths)["regular"] == 24 and len(res.solutions) == 24
    # path 3's taut run ends on path 5's Study point, and path 5 ends there in the taut system too: path jumping
    res, calls, study = _fallback_case(monkeypatch, {3}, lambda rows, st: {i: st[5] for i in rows})
    assert calls == [[3], [5]] and res.track.paths[3].status == PATH_JUMPING
    assert res.track.paths[5].status == SUCCESS and res.track.paths[5].retried == ""  # the Study outcome stands
    assert outcome_counts(res.track.paths)["failed"] == 1 and len(res.solutions) == 23
    # ... but path 5 ends on path 3's Study point in the taut system: the Study run of path 5 had jumped
    res, calls, study = _fallback_case(monkeypatch, {3}, lambda rows, st: {i: st[5] if i == 3 else st[3] for i in rows})
    assert calls == [[3], [5]] and res.track.paths[3].status == SUCCESS and res.track.paths[5].status == SUCCESS
    assert res.track.paths[5].retried == TAUT_FALLBACK
    assert outcome_counts(res.track.paths)["regular"] == 24 and len(res.solutions) == 24


def test_limit_of_one_sheet_needs_one_sheet_a_solution_and_a_pose():
    """The Study endgame's ``singular`` limits that the re-track may try to prove: winding number 1, a decent Cauchy
    accuracy, a residual that solves the system, and N = e . e away from 0 beyond that accuracy."""
    from cdpr_algebra.dgp.study_retrack import _limit_of_one_sheet
    from cdpr_algebra.homotopy.endgame import EndgameOptions
    from cdpr_algebra.homotopy.results import AT_INFINITY, SINGULAR, PathResult

    o = EndgameOptions()
    e = np.array([1.0, 0.5j, 0.3, 0.2])  # N / |e|^2 ~ 0.8
    iso = np.array([1.0, 1j, 0.0, 0.0]) + 1e-9  # N ~ 2e-9: a point of the quadric N = 0 to 1e-9
    x = np.concatenate([e, np.ones(6)])

    def path(**kw):
        base = dict(index=0, status=SINGULAR, endpoint=x, t=0j, residual=1e-15, condition=1e13, accuracy=1e-10,
                    steps=10, winding_number=1, retried="")
        return PathResult(**{**base, **kw})

    assert _limit_of_one_sheet(path(), o)
    assert not _limit_of_one_sheet(path(winding_number=2), o)
    assert not _limit_of_one_sheet(path(status=AT_INFINITY), o)
    assert not _limit_of_one_sheet(path(residual=1e-3), o)
    assert not _limit_of_one_sheet(path(accuracy=np.nan), o)
    assert not _limit_of_one_sheet(path(accuracy=1e-3), o)
    assert not _limit_of_one_sheet(path(endpoint=np.concatenate([iso, np.ones(6)]), accuracy=1e-8), o)


def testill_conditioned_roots_need_full_precision_a_bounded_condition_and_a_pose():
    """``EndgameOptions.ill_conditioned_limit``: a fast-finish endpoint above ``singular_condition`` ends regular only
    with a condition number within the limit, a last Newton update at ``refine_tol`` and, on a system that names
    its coordinate at infinity (Study's N / |e|^2), that coordinate above 1e3 times the update."""
    from types import SimpleNamespace

    from cdpr_algebra.dgp.study_retrack import FastStudySystem
    from cdpr_algebra.homotopy.endgame import EndgameOptions, ill_conditioned_roots

    o = replace(EndgameOptions(), ill_conditioned_limit=1e13)
    pose = np.concatenate([[1.0, 0.5j, 0.3, 0.2], np.ones(6)])  # N / |e|^2 ~ 0.8
    near_inf = np.concatenate([[1.0, 1j, 1e-6, 0.0], np.ones(6)])  # N / |e|^2 ~ 5e-13
    X = np.array([pose, pose, pose, pose, near_inf, pose])
    upd = np.array([1e-15, 1e-15, 1e-12, 1e-15, 1e-15, 1e-15])
    cond = np.array([1e12, 1e14, 1e12, 1e9, 1e12, 1e12])
    hom = SimpleNamespace(system=SimpleNamespace(infinity_coordinate=FastStudySystem.infinity_coordinate))
    got = ill_conditioned_roots(hom, X, upd, cond, o)
    # regular; cond over the limit; update above refine_tol; cond below singular_condition (the usual test's);
    # N vanishing to 1e3 x its update; and without a coordinate at infinity the same pose point passes
    assert got.tolist() == [True, False, False, False, False, True]
    assert ill_conditioned_roots(SimpleNamespace(), X, upd, cond, o).tolist() == [True, False, False, False, True,
                                                                                    True]


@pytest.mark.xdist_group("seed000_test2")
def test_ill_conditioned_study_endpoints_skip_the_cauchy_loops_and_end_where_they_did(monkeypatch):
    """Seed 000 Test 2, taut set {1, 2, 5, 6} (coplanar platform): each of its two Study runs ends 23 paths at roots with
    condition numbers 2e10 .. 2e12 (N / |e|^2 ~ 1e-6).  With ``ILL_CONDITIONED_LIMIT`` they end regular at the fast
    finish, without Cauchy loops; the subproblem's account, its roots and its admissible equilibria are those of
    the run that gave them the loops (limit off), in fewer tracking steps."""
    import cdpr_algebra.dgp.study_retrack as SR
    import cdpr_algebra.homotopy.endgame as E

    robot = load_robot("examples/seed000_test2.toml")
    loops = []
    real_loops = E.cauchy_endgame
    monkeypatch.setattr(E, "cauchy_endgame", lambda *a, **k: loops.append(len(a[1])) or real_loops(*a, **k))

    def run():
        loops.clear()
        sub, _, Z = S._solve_taut_set(robot, robot.lengths, (0, 1, 4, 5), 0, None, exclude=False)
        return sub, Z, sum(loops)

    sub, Z, looped = run()
    monkeypatch.setattr(SR, "ILL_CONDITIONED_LIMIT", 0.0)
    sub0, Z0, looped0 = run()
    assert looped == 0 and looped0 >= 20
    assert sub.outcomes == sub0.outcomes == {"regular": 216, "singular": 0, "at_infinity": 0, "failed": 0}
    assert (sub.finite, sub.real, sub.admissible) == (sub0.finite, sub0.real, sub0.admissible)
    scale = 1 + np.abs(Z0).max(axis=1)
    d = np.abs(Z[:, None, :] - Z0[None, :, :]).max(axis=2) / scale[None, :]
    assert len(Z) == len(Z0) == 216 and np.all(d.min(axis=0) <= 1e-8) and np.all(d.min(axis=1) <= 1e-8)


def _assert_last_samples_at_infinity(paths, m):
    """Every path at infinity of a Study-first run carries its last two samples in taut coordinates (not its start
    point): finite, at radii 0 < |t| < 0.1 with ``previous_t`` = |t| / sample_ratio, and the pose block growing
    (valuation v with v c <= -POSE_DIVERGES: the rotation at infinity), so :func:`.tension_infinity_undecided`
    keeps it at infinity; the start points are the stored generic solutions."""
    from cdpr_algebra.dgp.tension_infinity import POSE_DIVERGES
    from cdpr_algebra.homotopy.results import AT_INFINITY

    X_gen = S._generic(m)[1]
    inf = [p for p in paths if p.status == AT_INFINITY]
    assert inf
    for p in inf:
        assert p.previous is not None and np.all(np.isfinite(p.endpoint)) and np.all(np.isfinite(p.previous))
        assert 0 < abs(p.t) < 0.1 and abs(abs(p.previous_t) - 4 * abs(p.t)) <= 1e-9 * abs(p.t)
        assert np.max(np.abs(p.endpoint - X_gen[p.index])) > 1.0
        assert p.valuation(slice(0, 12)) * p.winding_number <= -POSE_DIVERGES


def test_study_limits_on_the_quadric_n_zero_are_at_infinity(monkeypatch):
    """Seed 002's 8-cable robot, taut set {1, 2, 5}: 31 of its 156 paths fail in (p, u, v, w, lam) at t ~ 1e-4 with
    |x| ~ 1e5 (without the Study run's verdict they stayed failed, fifteenth session).  In Study parameters they
    converge (winding number 2) to points of the quadric N = e . e = 0, where no pose is: the rotation R = Q(e) / N
    is at infinity.  The endgame decides them at infinity from ``FastStudySystem.infinity_coordinate`` as it decides
    y0 = 0 in a projective chart (N(t) ~ t^v, v ~ 1/2), and every path is accounted for: 100 regular endpoints and
    56 at infinity, as its neighbour {1, 3, 5} (same m and robot) has."""
    from cdpr_algebra.homotopy.results import AT_INFINITY, outcome_counts

    robot = load_robot(ROOT / "examples" / "seed002_8cables.toml")
    rho = np.asarray(robot.lengths, float)
    target = normalized_problem(robot, rho, (0, 1, 4))[0]
    monkeypatch.setattr(S, "STUDY_FIRST", False)  # the taut system first, then the re-track of its failures
    res, failed = S._track(3, target, 0, gamma=False)
    assert failed == 0 and outcome_counts(res.track.paths) == {"regular": 100, "singular": 0, "at_infinity": 56,
                                                               "failed": 0}
    monkeypatch.setattr(S, "STUDY_FIRST", True)  # the default: the same account from the Study run itself
    first, failed = S._track(3, target, 0, gamma=False)
    assert failed == 0 and outcome_counts(first.track.paths) == outcome_counts(res.track.paths)
    assert {p.index for p in first.track.paths if p.status == AT_INFINITY} == {
        p.index for p in res.track.paths if p.status == AT_INFINITY}
    study = [p for p in res.track.paths if p.retried == "study"]
    assert len(study) >= 25 and all(p.status == AT_INFINITY for p in study)
    assert all(p.winding_number >= 2 and 0 < p.order <= 1 for p in study)
    assert min(np.max(np.abs(p.endpoint)) for p in study) > 1e4  # their last points in (p, u, v, w, lam)
    # the Study run's own paths at infinity: their last samples, not their start points (thirty-first session)
    _assert_last_samples_at_infinity(first.track.paths, 3)


def test_infinity_coordinate_of_study_points():
    """N / |e|^2 is 1 on real Euler parameters, 0 on isotropic ones, and decide_in_chart reads it as y0 / |Y|."""
    from cdpr_algebra.dgp.study_retrack import FastStudySystem
    from cdpr_algebra.homotopy.endgame import EndgameOptions, decide_in_chart

    rng = np.random.default_rng(4)
    real = np.hstack([rng.normal(size=(3, 4)), rng.normal(size=(3, 7))]).astype(complex)
    assert np.allclose(FastStudySystem.infinity_coordinate(real), 1.0)
    iso = real.copy()
    iso[:, :4] = [1.0, 1j, 0.5, 0.5j]
    assert np.max(np.abs(FastStudySystem.infinity_coordinate(iso))) < 1e-15
    o = EndgameOptions()
    # limits on N = 0 whose last two samples shrink like t^(1/2) (ratio 1/4): at infinity, order 1/2
    last, prev = iso.copy(), iso.copy()
    last[:, 0] += 1e-4
    prev[:, 0] += 2e-4
    inf, undecided, order = decide_in_chart(iso, np.full(3, 1e-10), last, prev, o, FastStudySystem.infinity_coordinate)
    assert inf.all() and not undecided.any() and np.allclose(order, 0.5, atol=0.01)
    # the same limits with samples that do not shrink: undecided; a real pose: finite
    inf, undecided, _ = decide_in_chart(iso, np.full(3, 1e-10), last, last, o, FastStudySystem.infinity_coordinate)
    assert not inf.any() and undecided.all()
    inf, undecided, _ = decide_in_chart(real, np.full(3, 1e-10), real, real, o, FastStudySystem.infinity_coordinate)
    assert not inf.any() and not undecided.any()


def test_order_at_infinity_is_read_against_the_winding_number():
    """On a path of winding number c the coordinate is a power series in t^(1 / c): a zero has order k / c, k >= 1.
    Samples shrinking like t^(1/8) show a zero on a path of winding number 8 (or of unknown winding number: only
    ``min_order`` applies), not on one of winding number 1 (undecided: a large finite limit not yet settled)."""
    from cdpr_algebra.dgp.study_retrack import FastStudySystem
    from cdpr_algebra.homotopy.endgame import EndgameOptions, decide_in_chart

    iso = np.zeros((3, 11), dtype=complex)
    iso[:, :4] = [1.0, 1j, 0.5, 0.5j]
    iso[:, 4:] = 0.3
    o = EndgameOptions()
    last, prev = iso.copy(), iso.copy()
    last[:, 0] += 1e-4
    prev[:, 0] += 1e-4 * 4 ** 0.125  # ratio of the radii 1/4: order 1/8
    f = FastStudySystem.infinity_coordinate
    acc = np.full(3, 1e-10)
    inf, undecided, order = decide_in_chart(iso, acc, last, prev, o, f)
    assert inf.all() and np.allclose(order, 0.125, atol=0.005)
    inf, undecided, _ = decide_in_chart(iso, acc, last, prev, o, f, winding=[8, 1, 2])
    assert inf.tolist() == [True, False, False] and undecided.tolist() == [False, True, True]


def test_precise_endgame_decides_seed002_paths_at_infinity(monkeypatch):
    """Seed 002's 8-cable robot, taut set {1, 3, 5, 8}: Study paths fail in the double endgame near t ~ 1e-4 (pairs
    meeting on N = 0; five of its eight paths at infinity, six with at most 3 Newton updates a step); the endgame
    over double-double (dgp.study_retrack._precise_endgames) converges on limits with N = 0 (winding number 2) and
    they are at infinity: the subproblem is complete, its regular endpoints and paths at infinity adding up to the
    generic count 216.  Without that step the same paths stay failed."""
    import cdpr_algebra.dgp.solve as S
    import cdpr_algebra.dgp.study_retrack as SR
    from cdpr_algebra.homotopy.results import outcome_counts
    from cdpr_algebra.model.robot import load_robot

    robot = load_robot(ROOT / "examples" / "seed002_8cables.toml")
    target = normalized_problem(robot, robot.lengths, (0, 2, 4, 7))[0]
    res, failed = S._track(4, target, 0, gamma=False)
    paths = res.track.paths
    decided = [p for p in paths if p.retried == SR.PRECISE_ENDGAME]
    assert failed == 0 and len(decided) == 5
    assert all(p.status == "at_infinity" and p.winding_number == 2 and p.order > 0 for p in decided)
    counts = outcome_counts(paths)
    assert counts["failed"] == 0 and counts["regular"] + counts["at_infinity"] == 216
    monkeypatch.setattr(SR, "PRECISE_ENDGAME_PATHS", 0)
    _, failed = S._track(4, target, 0, gamma=False)
    assert failed == len(decided)


def test_precise_endgame_budget_decides_seed002_set_1256(monkeypatch):
    """Seed 002, taut set {1, 2, 5, 6}: 8 paths end at infinity (winding number 2, N(t) ~ t^(k/2), k = 1 .. 3), as in
    every taut set with the symmetric cables 1 and 5; 5 of them need more than 1500 double-double steps of the
    precise endgame before two Cauchy estimates agree.  With the budgets of PRECISE_ENDGAME_STEPS / _BUDGET the
    subproblem is complete; cut to 1500 / 10,000 paths stay failed."""
    import cdpr_algebra.dgp.solve as S
    import cdpr_algebra.dgp.study_retrack as SR
    from cdpr_algebra.homotopy.results import outcome_counts
    from cdpr_algebra.model.robot import load_robot

    robot = load_robot(ROOT / "examples" / "seed002_8cables.toml")
    target = normalized_problem(robot, robot.lengths, (0, 1, 4, 5))[0]
    res, failed = S._track(4, target, 0, gamma=False)
    counts = outcome_counts(res.track.paths)
    assert failed == 0 and counts["at_infinity"] == 8 and counts["regular"] == 208
    inf = [p for p in res.track.paths if p.status == "at_infinity"]
    assert all(p.winding_number == 2 and 0.75 <= p.order * p.winding_number <= 3.25 for p in inf)
    _assert_last_samples_at_infinity(res.track.paths, 4)  # the precise endgame's verdicts keep them too
    monkeypatch.setattr(SR, "PRECISE_ENDGAME_STEPS", 1500)
    monkeypatch.setattr(SR, "PRECISE_ENDGAME_BUDGET", 10000)
    _, failed = S._track(4, target, 0, gamma=False)
    assert failed > 0


def test_last_failed_path_rescued_in_double_double(monkeypatch):
    """Seed 002, taut set {2, 3, 6, 7}: one phase-1 crawl near Study's exceptional set fails in both routes (gamma
    re-run) and in the taut system; left alone it is tracked once more in double-double where double fails (the
    rescue of --mpmath-retry, automatic for at most AUTO_RESCUE_MAX_FAILED failed paths; without the route from
    another generic instance, which settles it first) and the subproblem is
    complete, every endpoint certified.  Without the automatic rescue the path stays failed.  (With the gamma re-run,
    the other route's roots settle it first: tests/test_dgp_large_forces.py, the routes' rescues.)"""
    import cdpr_algebra.dgp.solve as S
    from cdpr_algebra.model.robot import load_robot

    robot = load_robot(ROOT / "examples" / "seed002_8cables.toml")
    monkeypatch.setattr(S, "OTHER_START", False)  # the route from another generic instance settles it first
    monkeypatch.setattr(S, "RERUN_MAX_FAILED", 0)  # and so do the roots of the gamma re-run's route
    monkeypatch.setattr(S, "EXTENDED_MAX_FAILED", 0)  # and the double-double track in (p, u, v, w, lam)
    sub, _ = S.solve_taut_set(robot, robot.lengths, (1, 2, 5, 6), certify=False)
    assert sub.complete and sub.outcomes["failed"] == 0 and sub.retried.get("study_extended") == 1
    assert sub.certified == sub.outcomes["regular"] == 216
    monkeypatch.setattr(S, "AUTO_RESCUE_MAX_FAILED", 0)
    monkeypatch.setattr(S, "CONJUGATE_ROOTS", False)  # its root's conjugate is held: it settles the path too
    sub, _ = S.solve_taut_set(robot, robot.lengths, (1, 2, 5, 6), certify=False)
    assert not sub.complete and sub.outcomes["failed"] == 1


@pytest.mark.parametrize("taut_extended", [True, False])
def test_a_conjugate_pair_of_huge_roots_is_reached_by_both_routes_rescues(taut_extended, monkeypatch):
    """A random 5-cable robot built around an all-taut equilibrium (tests/equilibria.py, seed 303), taut set
    {2, 3, 4}: 154 roots in double precision; the other two, a complex conjugate pair with |x| ~ 8.5e6 (condition
    ~2e13 in Study parameters, ~1e16 in (p, u, v, w, lam)), are the limits of paths that fail in both routes (straight
    and gamma).  Tracked again from their start points in double-double in (p, u, v, w, lam) (dgp.taut_extended, the
    default since the thirty-sixth session) they reach them.  Without that step: the double-double rescue in Study
    parameters of each route reaches one of them (Newton quadratic to full precision in Study parameters, N clearly
    nonzero: regular, beyond the endgame's singular_condition): the kept route's settles its own path, the other
    route's root settles the last one.  Either way complete: 156 distinct regular roots, every one proven (the pair in
    ball arithmetic), and the pair is a conjugate pair of huge roots.  Before: 2 failed paths."""
    from equilibria import all_taut_equilibrium_robot

    if not taut_extended:
        monkeypatch.setattr(S, "EXTENDED_MAX_FAILED", 0)
    robot, _, _, _ = all_taut_equilibrium_robot(5, 303)
    sub, Z, proven = S.taut_set_roots(robot, robot.lengths, (1, 2, 3))
    assert sub.complete and sub.paths == 156 and sub.outcomes["regular"] == 156 and sub.outcomes["failed"] == 0
    assert sub.certified == 156 and np.all(proven) and len(Z) == 156
    if taut_extended:
        assert sub.retried.get("taut_extended", 0) >= 2
    else:
        assert sub.retried.get("study_extended") == 1 and sub.retried.get("unheld_root") == 1
    huge = Z[np.abs(Z).max(axis=1) > 1e6]
    assert len(huge) == 2 and np.abs(Z).max() < 1e7
    scale = np.abs(huge).max()
    assert np.max(np.abs(huge[0] - np.conj(huge[1]))) <= 1e-8 * scale
