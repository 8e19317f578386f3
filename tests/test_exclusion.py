"""The DGP does not track a taut set that the interval filter proves to hold no admissible equilibrium (issue 19
item 3, cdpr_algebra.dgp.solve.excluded_subproblem): the proof never excludes a set that holds one (robots built
around a known equilibrium, internal forces up to 1e4 times the load, a slack cable exactly at its length), and
on Test 1 the DGP returns the same equilibria with and without it, the excluded sets having none by the
homotopy's own complete run and by the complete interval search."""

import json
from pathlib import Path

import numpy as np
import pytest

from cdpr_algebra.dgp.solve import available_m, dgp, excluded_subproblem, solve_taut_set
from cdpr_algebra.model.robot import Robot, load_robot
from large_forces import large_force_robot

ROOT = Path(__file__).resolve().parents[1]


@pytest.mark.parametrize("m", [3, 4, 5, 6])
@pytest.mark.parametrize("K", [1e0, 1e2, 1e4])
def test_a_set_holding_an_equilibrium_is_never_excluded(m, K):
    robot, p, R, tau = large_force_robot(m, K, 200 + m)
    assert np.all(tau > 0)
    assert excluded_subproblem(robot, robot.lengths, tuple(range(m))) is None


def test_a_slack_cable_exactly_at_its_length_does_not_exclude_the_set():
    """A fourth cable added at the equilibrium of a 3-cable robot with rho_4 = |A_4 - B_4| (taut, tension 0): the
    equilibrium is admissible with cables 1-3 taut (cable 4 passes the slack test), so {1, 2, 3} is not excluded,
    and the DGP's subproblem {1, 2, 3} returns it (the whole DGP of this robot took 2 minutes in the suite for
    nothing more: its sets {1, 3, 4} and {2, 3, 4} each keep a failed path through every rescue)."""
    robot3, p, R, tau = large_force_robot(3, 1e1, 303)
    rng = np.random.default_rng(5)
    b4 = rng.uniform(-0.3, 0.3, 3)
    B4 = p + R @ b4
    A4 = B4 + rng.uniform(3.0, 5.0) * np.array([0.3, -0.2, 1.0]) / np.linalg.norm([0.3, -0.2, 1.0])
    rho4 = float(np.linalg.norm(A4 - B4))
    robot = Robot(np.vstack([robot3.base, A4]), np.vstack([robot3.platform, b4]), robot3.com, robot3.load,
                  robot3.load_direction, np.concatenate([robot3.lengths, [rho4]]), name="boundary4")
    assert excluded_subproblem(robot, robot.lengths, (0, 1, 2)) is None
    if 3 in available_m():  # the taut set's own DGP subproblem (with the slack test of cable 4) returns it
        sub, sols = solve_taut_set(robot, robot.lengths, (0, 1, 2), certify=False)
        assert any(np.max(np.abs(s.position - p)) <= 1e-7 * robot.size for s in sols)


@pytest.mark.skipif(3 not in available_m(), reason="generic set m = 3 not stored")
def test_test1_same_equilibria_with_and_without_exclusion(tmp_path, capsys):
    from cdpr_algebra.bp.search import solve_taut_set_interval
    from cdpr_algebra.cli.main import main

    robot = load_robot(ROOT / "examples" / "seed000_test1.toml")
    fast = dgp(robot, jobs=1, certify=False)
    full = dgp(robot, jobs=1, certify=False, exclude=False)
    excluded = [s for s in fast.subproblems if s.excluded is not None]
    assert excluded and all(s.paths == 0 and s.complete and s.skipped for s in excluded)
    assert fast.complete and full.complete
    key = [(s.taut, tuple(np.round(s.position, 9))) for s in fast.solutions]
    assert key == [(s.taut, tuple(np.round(s.position, 9))) for s in full.solutions] and len(key) == 6
    for s in excluded:  # no admissible equilibrium there, by the homotopy's complete run and the interval search
        sub, sols = full.taut_set(s.taut)
        assert sub.complete and sub.paths > 0 and not sols
        isub = solve_taut_set_interval(robot, robot.lengths, [c - 1 for c in s.taut])
        assert isub.complete and isub.admissible == 0
    # the CLI: the excluded sets in the JSON and the table, --track-all tracks them
    path = tmp_path / "t1.json"
    path.write_text(json.dumps(robot.to_dict()))
    assert main(["dgp", str(path), "--jobs", "1", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert [s["taut"] for s in out["subproblems"] if s["excluded"]] == [list(s.taut) for s in excluded]
    assert main(["dgp", str(path), "--jobs", "1"]) == 0
    text = capsys.readouterr().out
    assert "not tracked" in text and "interval proof" in text
    assert main(["dgp", str(path), "--jobs", "1", "--json", "--track-all"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert not any(s["excluded"] for s in out["subproblems"])
    assert all(s["paths"] > 0 for s in out["subproblems"] if len(s["taut"]) >= 2)
