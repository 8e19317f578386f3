"""Issue 15, items 1-2: infinity is decided projectively (no norm threshold), a finite solution is returned
however large, and every path has one outcome (regular, singular, at_infinity, failed) that the counts add up to.

The family a x^2 + x - 1 = 0, y^2 - b = 0 has the roots x = (-1 +- sqrt(1 + 4a)) / (2a), y = +-sqrt(b): at
a = 1e-9 two of its four solutions have |x| ~ 1e9 (finite), at a = 0 they are at infinity, with y0 ~ t (order 1)
along the straight parameter path.
"""

import json
from dataclasses import replace
from pathlib import Path

import numpy as np
import pytest

from cdpr_algebra.dgp import study_retrack
import sympy as sp

from cdpr_algebra.homotopy.endgame import EndgameOptions, SolveOptions
from cdpr_algebra.homotopy.results import OUTCOMES, outcome_counts
from cdpr_algebra.homotopy.solve import solve_parameter_homotopy
from cdpr_algebra.homotopy.systems import PolynomialSystem
from accounting import expected_complete

ROOT = Path(__file__).resolve().parents[1]


def _family():
    x, y, a, b = sp.symbols("x y a b")
    return PolynomialSystem([a * x**2 + x - 1, y**2 - b], [x, y], [a, b], name="large_roots")


def _start(p1):
    a, b = p1
    r = np.sqrt(1 + 4 * a + 0j)
    xs = [(-1 + r) / (2 * a), (-1 - r) / (2 * a)]
    ys = [np.sqrt(b + 0j), -np.sqrt(b + 0j)]
    return np.array([[x, y] for x in xs for y in ys])


P1 = np.array([0.7 + 0.4j, 1.3 - 0.6j])
PROJECTIVE = SolveOptions(endgame=EndgameOptions(projective=True))


@pytest.mark.parametrize("a", [1e-3, 1e-6, 1e-9])
def test_large_finite_solutions_are_returned(a):
    """|x| = 1/a (up to 1e9): finite and accurate, nothing at infinity or failed.  (At a = 1e-9 the large roots are
    1e-9 from the point at infinity that they reach at a = 0: their condition number in the chart is ~1e10, so
    they may be classed singular; they are returned all the same.)"""
    res = solve_parameter_homotopy(_family(), P1, _start(P1), np.array([a, 1.0]), options=PROJECTIVE)
    counts = outcome_counts(res.track.paths)
    assert counts["at_infinity"] == 0 and counts["failed"] == 0
    assert counts["regular"] + counts["singular"] == 4 and (a < 1e-7 or counts["regular"] == 4)
    xs = np.sort([s.x[0].real for s in res.solutions])
    assert len(xs) == 4
    exact = np.sort([(-1 - np.sqrt(1 + 4 * a)) / (2 * a), (-1 + np.sqrt(1 + 4 * a)) / (2 * a)])
    assert np.allclose(xs[::2], exact, rtol=1e-6) and np.allclose(xs[1::2], exact, rtol=1e-6)
    assert np.allclose(sorted(abs(s.x[1].real) for s in res.solutions), 1.0, rtol=1e-9)


def test_at_infinity_is_decided_by_the_homogenizing_coordinate():
    """a = 0: two paths end at infinity, with y0 ~ t^1 (order 1, winding number 1), two at x = 1."""
    res = solve_parameter_homotopy(_family(), P1, _start(P1), np.array([0.0, 1.0]), options=PROJECTIVE)
    counts = outcome_counts(res.track.paths)
    assert counts == {"regular": 2, "singular": 0, "at_infinity": 2, "failed": 0}
    inf = [p for p in res.track.paths if p.status == "at_infinity"]
    assert all(abs(p.order - 1.0) < 0.05 and p.winding_number == 1 for p in inf)
    assert np.allclose(sorted(s.x[0].real for s in res.solutions), [1.0, 1.0], atol=1e-12)
    # which coordinates go to infinity: x ~ 1 / (a t) along the path (a(t) ~ t), y -> +-1 stays finite
    for p in inf:
        assert abs(p.valuation(slice(0, 1)) + 1.0) < 0.05 and abs(p.valuation(slice(1, 2))) < 0.05
        assert abs(p.previous_t) > abs(p.t) > 0


def test_tiny_step_budget_fails_paths_and_counts_add_up():
    """A step budget too small to finish: every path is 'failed' with its reason, none silently dropped."""
    from cdpr_algebra.homotopy.tracker import TrackerOptions

    opts = replace(PROJECTIVE, tracker=TrackerOptions(max_steps=2), retry_tight=False, retry_mpmath=False)
    res = solve_parameter_homotopy(_family(), P1, _start(P1), np.array([1e-6, 1.0]), options=opts, retries=0)
    counts = outcome_counts(res.track.paths)
    assert sum(counts.values()) == 4 and counts["failed"] == 4
    assert {p.status for p in res.track.paths} == {"too_many_steps"}
    assert res.solutions == ()


def test_chart_path_failed_before_the_first_sample_is_not_tracked_again():
    """A path that fails in the chart before t = te * sample_ratio fails with the track's own reason and t: the
    endgame's first segment would retrack the same stretch from the same point, and is not run (its steps would
    show)."""
    from cdpr_algebra.homotopy.endgame import _finish
    from cdpr_algebra.homotopy.projective import to_chart
    from cdpr_algebra.homotopy.start_systems import parameter_homotopy
    from cdpr_algebra.homotopy.tracker import TrackerOptions, track_segment

    (hom,) = parameter_homotopy(_family(), P1, np.array([0.0, 1.0]), rng=np.random.default_rng(0))
    ph = hom.projective()
    te = PROJECTIVE.endgame.endgame_start
    seg = track_segment(ph, to_chart(_start(P1), ph.chart), 1.0, te, PROJECTIVE.tracker)
    assert np.all(seg.status == "success")
    budget = TrackerOptions(max_steps=2)
    x, status, _, _, t, steps, _, _ = _finish(ph, seg.x, PROJECTIVE, budget)
    assert list(status) == ["too_many_steps"] * 4
    assert np.all(np.abs(t) > te * PROJECTIVE.endgame.sample_ratio) and np.all(np.abs(t) < te)
    assert list(steps) == [2] * 4


def test_detour_around_a_near_pole_rescues_a_phase_one_failure():
    """a(t) = t a1 + (1 - t) a0 with a0 = -a1 + 1e-13 passes 5e-14 from 0 at t = 1/2: the large root of
    a x^2 + x - 1 (~ -1/a) passes 1e13 there and its two paths diverge in phase 1.  Tracked again on a half circle
    about the failure (``detour_retry``) they reach t = te on solutions no other path holds, and end on the
    closed-form roots at a0; without the detour they stay failed."""
    from cdpr_algebra.homotopy.endgame import track_paths
    from cdpr_algebra.homotopy.start_systems import parameter_homotopy

    p0 = np.array([-P1[0] + 1e-13, 1.0])
    (hom,) = parameter_homotopy(_family(), P1, p0, rng=np.random.default_rng(0))
    plain = SolveOptions(retry_tight=False, retry_mpmath=False)
    off = track_paths(hom, _start(P1), plain)
    assert outcome_counts(off.paths)["failed"] == 2 and all(p.retried == "" for p in off.paths)
    on = track_paths(hom, _start(P1), replace(plain, detour_retry=True))
    assert outcome_counts(on.paths) == {"regular": 4, "singular": 0, "at_infinity": 0, "failed": 0}
    assert sorted(p.retried for p in on.paths) == ["", "", "detour", "detour"]
    a = p0[0]
    roots = [(-1 + np.sqrt(1 + 4 * a)) / (2 * a), (-1 - np.sqrt(1 + 4 * a)) / (2 * a)]
    want = sorted((x, y) for x in roots for y in (1.0, -1.0))
    got = sorted((p.endpoint[0], p.endpoint[1]) for p in on.paths)
    assert np.allclose(np.array(got, dtype=complex), np.array(want, dtype=complex), rtol=1e-10)


def test_detour_is_refused_where_it_would_duplicate_a_path():
    """The check behind the detour: a point reached at te that another path holds is not kept (given the start
    points twice, the second copy's detoured paths land on the first copy's solutions and stay failed)."""
    from cdpr_algebra.homotopy.endgame import track_paths
    from cdpr_algebra.homotopy.start_systems import parameter_homotopy

    p0 = np.array([-P1[0] + 1e-13, 1.0])
    (hom,) = parameter_homotopy(_family(), P1, p0, rng=np.random.default_rng(0))
    opts = SolveOptions(retry_tight=False, retry_mpmath=False, detour_retry=True, check_path_jumping=False)
    twice = np.vstack([_start(P1), _start(P1)])
    res = track_paths(hom, twice, opts)
    assert sum(p.retried == "detour" for p in res.paths) == 2
    assert outcome_counts(res.paths)["failed"] == 2


def _failing_in_the_endgame_zone(monkeypatch, rows, t_fail=0.05):
    """The fast finish (the track t = te -> 0 of :func:`cdpr_algebra.homotopy.endgame._finish`) of the paths in
    ``rows`` (of that call) stops with ``too_many_steps`` at t_fail; every other track is the real one (the
    detours' too: :mod:`cdpr_algebra.homotopy.detours` has its own binding)."""
    import cdpr_algebra.homotopy.endgame as eg

    real = eg.track_segment
    te = EndgameOptions().endgame_start

    def failing(homotopy, x0, t_a, t_b, options=None, h0=None):
        r = real(homotopy, x0, t_a, t_b, options, h0)
        if np.all(np.asarray(t_a) == te) and np.all(np.asarray(t_b) == 0.0):
            status, t = r.status.copy(), np.array(r.t, dtype=complex, copy=True)
            status[rows], t[rows] = "too_many_steps", t_fail
            r = replace(r, status=status, t=t)
        return r

    monkeypatch.setattr(eg, "track_segment", failing)


def test_endgame_detour_rescues_a_failure_in_the_endgame_zone(monkeypatch):
    """Two paths stop at t = 0.05 in the fast finish (forced): they fail there with that reason and t, without a
    second try by the Cauchy endgame over the same stretch (affine homotopy); with ``detour_retry`` they are tracked
    again from t = 1 around t = 0.05 to t = 0 and kept on regular roots that no other path holds: the closed-form
    roots at a0."""
    from cdpr_algebra.homotopy.endgame import track_paths
    from cdpr_algebra.homotopy.start_systems import parameter_homotopy

    p0 = np.array([0.3 - 0.2j, 1.0])
    (hom,) = parameter_homotopy(_family(), P1, p0, rng=np.random.default_rng(0))
    _failing_in_the_endgame_zone(monkeypatch, [0, 1])
    plain = SolveOptions(retry_tight=False, retry_mpmath=False)
    off = track_paths(hom, _start(P1), plain)
    assert outcome_counts(off.paths)["failed"] == 2
    assert [(p.status, p.t) for p in off.paths[:2]] == [("too_many_steps", 0.05)] * 2
    on = track_paths(hom, _start(P1), replace(plain, detour_retry=True))
    assert outcome_counts(on.paths) == {"regular": 4, "singular": 0, "at_infinity": 0, "failed": 0}
    assert [p.retried for p in on.paths] == ["endgame_detour", "endgame_detour", "", ""]
    assert all(p.steps > q.steps for p, q in zip(on.paths[:2], off.paths[:2]))  # the detours' steps count
    a = p0[0]
    roots = [(-1 + np.sqrt(1 + 4 * a)) / (2 * a), (-1 - np.sqrt(1 + 4 * a)) / (2 * a)]
    want = sorted((x, y) for x in roots for y in (1.0, -1.0))
    got = sorted((p.endpoint[0], p.endpoint[1]) for p in on.paths)
    assert np.allclose(np.array(got, dtype=complex), np.array(want, dtype=complex), rtol=1e-10)


def test_endgame_detour_is_refused_on_a_point_another_path_holds(monkeypatch):
    """The start points twice, the second copy's fast finish stopped (forced): their detours reach the roots that
    the first copy holds, and are not kept."""
    from cdpr_algebra.homotopy.endgame import track_paths
    from cdpr_algebra.homotopy.start_systems import parameter_homotopy

    (hom,) = parameter_homotopy(_family(), P1, np.array([0.3 - 0.2j, 1.0]), rng=np.random.default_rng(0))
    _failing_in_the_endgame_zone(monkeypatch, [4, 5, 6, 7])
    opts = SolveOptions(retry_tight=False, retry_mpmath=False, detour_retry=True, check_path_jumping=False)
    res = track_paths(hom, np.vstack([_start(P1), _start(P1)]), opts)
    assert [p.status for p in res.paths[:4]] == ["success"] * 4
    assert [p.status for p in res.paths[4:]] == ["too_many_steps"] * 4
    assert not any(p.retried for p in res.paths)
    assert all(q.steps > p.steps for p, q in zip(res.paths[:4], res.paths[4:]))  # their detours were tracked


@pytest.fixture(scope="module")
def test1():
    from cdpr_algebra.model.robot import load_robot

    return load_robot(ROOT / "examples" / "seed000_test1.toml")


def test_dgp_subproblem_outcomes_add_up(test1):
    from cdpr_algebra.dgp.solve import dgp

    res = dgp(test1, jobs=1, max_m=3, certify=False)
    for s in res.subproblems:
        assert set(s.outcomes) == set(OUTCOMES) and sum(s.outcomes.values()) == s.paths
        assert sum(s.failures.values()) == s.outcomes["failed"]
        assert s.complete == expected_complete(s)
    d = res.to_dict()
    assert d["outcomes"] == {k: sum(s.outcomes[k] for s in res.subproblems) for k in OUTCOMES}
    assert d["complete"] == res.complete and d["incomplete"] == [list(s.taut) for s in res.incomplete]


def test_forced_failures_make_the_dgp_incomplete_and_the_cli_exit_3(test1, tmp_path, capsys, monkeypatch):
    """A tiny step budget: the subproblems with m >= 2 report failed paths, complete false; `cdpr dgp` names them
    on stderr and exits 3 (JSON too)."""
    import cdpr_algebra.dgp.solve as dgp_mod
    from cdpr_algebra.cli.main import INCOMPLETE, main
    from cdpr_algebra.homotopy.tracker import TrackerOptions

    base = dgp_mod.default_options()
    tiny = replace(base, tracker=replace(base.tracker, max_steps=3))
    monkeypatch.setattr(dgp_mod, "default_options", lambda: tiny)
    monkeypatch.setattr(dgp_mod, "PROJECTIVE_RETRIES", 0)
    monkeypatch.setattr(dgp_mod, "UNHELD_ROOTS", False)  # failed paths stay failed (no Newton from their estimates)
    monkeypatch.setattr(study_retrack, "PRECISE_ENDGAME_PATHS", 0)  # nor the endgame over double-double
    res = dgp_mod.dgp(test1, jobs=1, max_m=2, certify=False, exclude=False)  # track the sets of no equilibrium too
    two = [s for s in res.subproblems if len(s.taut) == 2]
    assert two and all(not s.complete and s.failed_paths > 0 for s in two)
    assert all(s.complete for s in res.subproblems if len(s.taut) == 1)
    path = tmp_path / "t1.json"
    path.write_text(json.dumps(test1.to_dict()))
    assert main(["dgp", str(path), "--jobs", "1", "--json"]) == INCOMPLETE == 3
    cap = capsys.readouterr()
    out = json.loads(cap.out)
    assert out["complete"] is False and [1, 2, 3] in out["incomplete"]
    assert "incomplete" in cap.err and "[1, 2, 3]" in cap.err


def test_detours_complete_a_marionet_subproblem(monkeypatch):
    """Seed 000 Test 3 (MARIONET-VR), taut set {2, 3, 6}: 4 of its 156 paths fail before the endgame zone; with the
    detours (the DGP's default) every path ends regular and every endpoint is certified, so the subproblem is
    complete; without them (nor the re-run with a new gamma, the double-double rescue of the last failed paths and
    the conjugates of the roots found, which complete it too) it is not."""
    import cdpr_algebra.dgp.solve as S
    from cdpr_algebra.dgp.solve import default_options, solve_taut_set
    from cdpr_algebra.model.robot import load_robot

    robot = load_robot(ROOT / "examples" / "seed000_test3.toml")
    with_detours, _ = solve_taut_set(robot, robot.lengths, (1, 2, 5), certify=False)
    assert default_options().detour_retry
    assert with_detours.complete and with_detours.certified == with_detours.paths == 156
    monkeypatch.setattr(S, "AUTO_RESCUE_MAX_FAILED", 0)
    monkeypatch.setattr(S, "RERUN_MAX_FAILED", 0)
    monkeypatch.setattr(S, "CONJUGATE_ROOTS", False)  # nor the conjugates of the roots found
    without, _ = solve_taut_set(robot, robot.lengths, (1, 2, 5), certify=False,
                                options=replace(default_options(), detour_retry=False))
    assert not without.complete and without.outcomes["failed"] > 0


def test_endgame_detours_complete_the_last_marionet_subproblem():
    """Seed 000 Test 3, taut set {1, 2, 5, 6}: two of its Study paths crawl near t = 0.04 (N / |e|^2 ~ 1e-5 .. 1e-7)
    until their step budget runs out, and so did every re-run with another gamma; the detours around those points
    (issue 15, twentieth session) end them on regular roots that no other path holds, and every endpoint is
    certified."""
    from cdpr_algebra.dgp.solve import solve_taut_set
    from cdpr_algebra.model.robot import load_robot

    robot = load_robot(ROOT / "examples" / "seed000_test3.toml")
    sub, _ = solve_taut_set(robot, robot.lengths, (0, 1, 4, 5))
    assert sub.retried.get("endgame_detour", 0) >= 1
    assert sub.complete and sub.failed_paths == 0 and sub.certified == sub.paths == 216
