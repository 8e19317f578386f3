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
    x, status, _, _, t, steps, _ = _finish(ph, seg.x, PROJECTIVE, budget)
    assert list(status) == ["too_many_steps"] * 4
    assert np.all(np.abs(t) > te * PROJECTIVE.endgame.sample_ratio) and np.all(np.abs(t) < te)
    assert list(steps) == [2] * 4


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
