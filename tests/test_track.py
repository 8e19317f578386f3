"""Tracking the equilibrium along cable-length trajectories (cdpr_algebra.track): every reported state is one of the
DGP's equilibria at its lengths; slack and taut events where the DGP of the smaller taut set says; a fold whose
jump lands on a stable equilibrium of the DGP; bad input named."""

import json

import numpy as np
import pytest

from cdpr_algebra import load_robot
from cdpr_algebra.cli.main import main
from cdpr_algebra.dgp.solve import dgp
from cdpr_algebra.model.errors import CdprInputError
from cdpr_algebra.track.follow import track
from cdpr_algebra.track.trajectory import LengthTrajectory, load_trajectory, straight

ROBOT = "examples/seed000_test1.toml"


@pytest.fixture(scope="module")
def robot():
    return load_robot(ROBOT)


@pytest.fixture(scope="module")
def pay_out_and_back(robot):
    """Test 1's robot paying out cable 1 from 7.5 to 14 and hauling it back."""
    rho0 = robot.lengths.copy()
    rho1 = rho0.copy()
    rho1[0] = 14.0
    traj = LengthTrajectory(np.array([0.0, 1.0, 2.0]), np.array([rho0, rho1, rho0]))
    return traj, track(robot, traj, np.linspace(0, 2, 21))


def _matches_dgp(robot, st, tol=1e-7):
    """The state is among the DGP's admissible equilibria at its lengths, with the same taut set and tensions."""
    res = dgp(robot, st.lengths, certify=False)
    for s in res.solutions:
        if np.abs(s.position - st.position).max() <= tol * robot.size and np.abs(s.rotation - st.rotation).max() <= tol:
            return tuple(s.taut) == st.taut and np.allclose(s.tensions, st.tensions, atol=1e-7 * robot.load) \
                and s.stable == st.stable
    return False


def test_slack_then_taut_at_the_lengths_where_the_two_cable_equilibrium_reaches_cable_1(robot, pay_out_and_back):
    traj, res = pay_out_and_back
    assert res.complete and [e.kind for e in res.events] == ["slack", "taut"]
    slack, taut = res.events
    assert slack.cables == (1,) and taut.cables == (1,)
    # the slack event: tension 1 is zero there, and the DGP of cables {2, 3} at those lengths has the same pose,
    # whose distance |A1 B1| is cable 1's length (cable 1 is just taut)
    assert abs(slack.state.tensions[0]) <= 1e-8 * robot.load
    sub = [s for s in dgp(robot, slack.state.lengths, certify=False).solutions if s.taut == (2, 3) and s.stable]
    assert len(sub) == 1
    assert np.allclose(sub[0].position, slack.state.position, atol=1e-7)
    B1 = sub[0].position + sub[0].rotation @ robot.platform[0]
    assert abs(np.linalg.norm(robot.base[0] - B1) - slack.state.lengths[0]) <= 1e-7
    # hauling back, cable 1 becomes taut at the same length (the 2-cable pose does not depend on rho_1)
    assert abs(taut.state.lengths[0] - slack.state.lengths[0]) <= 1e-7
    assert abs(slack.t + taut.t - 2.0) <= 1e-8  # symmetric trajectory
    # every sampled state and the way back to the start
    assert len(res.steps) == 21
    assert np.allclose(res.steps[-1].position, res.steps[0].position, atol=1e-9)
    assert np.allclose(res.steps[-1].tensions, res.steps[0].tensions, atol=1e-9)


def test_tracked_states_are_dgp_equilibria_and_move_continuously(robot, pay_out_and_back):
    traj, res = pay_out_and_back
    for st in res.steps[::4]:
        assert st.residual <= 1e-12 and st.stable
        assert _matches_dgp(robot, st)
    # continuity: between samples without an event, the platform moves at most a few times the length change
    ev_t = [e.t for e in res.events]
    for a, b in zip(res.steps, res.steps[1:]):
        if any(a.t < t <= b.t for t in ev_t):
            continue
        dl = np.abs(b.lengths - a.lengths).max()
        assert np.abs(b.position - a.position).max() <= 5 * dl + 1e-12


def test_fold_jumps_to_a_stable_equilibrium_of_the_dgp(robot):
    """Test 1's robot with lengths moving to (6.611, 6.199, 9.867): its stable equilibrium meets an unstable one and
    disappears (a fold at t ~ 0.8035, where the lowest eigenvalue of H_r goes to 0); the robot lands on another
    stable equilibrium of the DGP at the landing's lengths, lower in potential."""
    traj = straight(robot.lengths, [6.611, 6.199, 9.867], robot.n)
    res = track(robot, traj, np.linspace(0, 1, 5))
    kinds = [e.kind for e in res.events]
    assert res.complete and kinds == ["fold", "jump"]
    fold, jump = res.events
    assert 0.80 < fold.t < 0.81 and fold.state.min_eigenvalue < 1e-6 < 1e-4 <= res.steps[0].min_eigenvalue
    # the fold, checked by the DGP: just before it a stable and an unstable equilibrium lie close to the fold pose,
    # just after it neither exists (the pair has merged and vanished)
    def near(t):
        sols = dgp(robot, traj(t), certify=False).solutions
        return [s for s in sols if np.abs(s.position - fold.state.position).max() <= 1e-2 * robot.size]
    before, after = near(fold.t - 1e-7), near(fold.t + 1e-7)
    assert sorted(s.stable for s in before) == [False, True] and after == []
    landing = jump.landing
    assert landing.stable and jump.energy_released > 0
    assert np.abs(landing.position - fold.state.position).max() > 0.01 * robot.size
    assert _matches_dgp(robot, landing)
    # after the jump the robot stays on the new branch: the last sample is a stable DGP equilibrium too
    assert _matches_dgp(robot, res.steps[-1])


def test_cli_json_and_exit_status(capsys, tmp_path):
    assert main(["track", ROBOT, "--to", "14", "10", "9.5", "--steps", "4", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["status"] == "complete" and len(out["steps"]) == 5
    assert out["start"]["dgp_complete"] is True and out["start"]["stable_found"] == 1  # Test 1: one stable
    assert [e["kind"] for e in out["events"]] == ["slack"] and out["events"][0]["cables"] == [1]
    st = out["steps"][-1]
    assert st["taut"] == [2, 3] and st["tensions"][0] == 0 and st["stable"] is True
    # a trajectory file with the same table gives the same states
    f = tmp_path / "traj.csv"
    f.write_text("t, rho1, rho2, rho3\n0, 7.5, 10, 9.5\n1, 14, 10, 9.5\n")
    assert main(["track", ROBOT, "--trajectory", str(f), "--steps", "4", "--json"]) == 0
    out2 = json.loads(capsys.readouterr().out)
    assert np.allclose(out2["steps"][-1]["position"], st["position"], atol=1e-12)
    # a trajectory that ends at a singular wrench matrix or a fold without landing stops with exit status 3
    png = tmp_path / "t.png"
    assert main(["track", ROBOT, "--to", "14", "10", "9.5", "--steps", "2", "--plot", str(png)]) == 0
    assert png.stat().st_size > 1000


@pytest.mark.parametrize("args, flag", [
    (["--to", "14", "10"], "--to"),
    (["--to", "14", "10", "-1"], "--to"),
    (["--lengths", "1", "2", "--to", "14", "10", "9.5"], "--lengths"),
    (["--steps", "0", "--to", "14", "10", "9.5"], "--steps"),
    ([], "--to"),
])
def test_cli_bad_input_names_the_flag(capsys, args, flag):
    assert main(["track", ROBOT] + args) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and flag in err[0]


def test_trajectory_files_with_bad_rows(tmp_path, robot):
    f = tmp_path / "bad.csv"
    f.write_text("t, a, b, c\n0, 7.5, 10, 9.5\n0.5, 8, x, 9.5\n")
    with pytest.raises(CdprInputError, match="line 3"):
        load_trajectory(f, robot.n)
    f.write_text("0, 7.5, 10, 9.5\n0, 8, 10, 9.5\n")
    with pytest.raises(CdprInputError, match="row 2.*increase"):
        load_trajectory(f, robot.n)
    g = tmp_path / "bad.json"
    g.write_text(json.dumps({"t": [0, 1], "lengths": [[7.5, 10, 9.5], [8, 10]]}))
    with pytest.raises(CdprInputError, match="row 2"):
        load_trajectory(g, robot.n)
    g.write_text(json.dumps({"t": [0, 1], "lengths": [[7.5, 10, 9.5]]}))  # was cut to 1 row by zip
    with pytest.raises(CdprInputError, match="2 values of t but 1 rows of lengths"):
        load_trajectory(g, robot.n)


def test_a_start_pose_that_is_not_an_equilibrium_is_refused(robot):
    traj = straight(robot.lengths, [8.0, 10.0, 9.5], robot.n)
    res = dgp(robot, robot.lengths, certify=False)
    s = [s for s in res.solutions if s.stable][0]
    with pytest.raises(CdprInputError, match="start"):
        track(robot, traj, start=(s.position + np.array([0.0, 0.0, -0.05]), s.rotation))  # 4e-3 of its size
    ok = track(robot, traj, np.linspace(0, 1, 3), start=(s.position, s.rotation))
    assert ok.complete and np.allclose(ok.steps[0].position, s.position, atol=1e-9)


def test_expressions_of_t(robot, pay_out_and_back, capsys):
    """rho_1 = 7.5 + 6.5 sin t over [0, pi]: slack where 7.5 + 6.5 sin t reaches the slack length found on the
    piecewise-linear trajectory, taut again at pi minus that t."""
    _, lin = pay_out_and_back
    rho_slack = lin.events[0].state.lengths[0]
    assert main(["track", ROBOT, "--expressions", "7.5 + 6.5*sin(t)", "10", "9.5", "--range", "0", "pi",
                 "--steps", "6", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    (slack, taut) = out["events"]
    t_expected = np.arcsin((rho_slack - 7.5) / 6.5)
    assert abs(slack["t"] - t_expected) <= 1e-8 and abs(taut["t"] - (np.pi - t_expected)) <= 1e-8
    assert out["trajectory"]["expressions"][0] == "6.5*sin(t) + 7.5"
    assert main(["track", ROBOT, "--expressions", "7.5 + 6.5*sin(s)", "10", "9.5"]) == 2
    assert "--expressions" in capsys.readouterr().err
    assert main(["track", ROBOT, "--expressions", "7.5 - 9*t", "10", "9.5"]) == 2
    assert "cable 1" in capsys.readouterr().err
    assert main(["track", ROBOT, "--expressions", "7.5", "10", "9.5", "--range", "1", "0"]) == 2
    assert "--range" in capsys.readouterr().err


def test_animation_has_a_frame_per_state(tmp_path, capsys):
    from PIL import Image

    gif = tmp_path / "a.gif"
    assert main(["track", ROBOT, "--to", "14", "10", "9.5", "--steps", "4", "--animate", str(gif), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    with Image.open(gif) as im:
        assert im.n_frames == len(out["steps"]) + len(out["events"])  # 5 samples and the slack event
    assert main(["track", ROBOT, "--to", "14", "10", "9.5", "--steps", "2", "--animate", str(tmp_path / "a.avi")]) == 2
    assert "--animate" in capsys.readouterr().err


def test_cli_start_pose(robot, capsys):
    """Start from a pose given to the DGP table's 3 decimals (polished by Newton), or refuse one that is not near
    an equilibrium, or an unstable one, naming --start-position."""
    sols = dgp(robot, robot.lengths, certify=False).solutions
    stable = [s for s in sols if s.stable][0]
    unstable = [s for s in sols if not s.stable][0]
    from cdpr_algebra.model.pose import angles_from_matrix

    def args(s, dz=0.0):
        p = np.round(s.position, 3) + [0, 0, dz]
        a = np.round(angles_from_matrix(s.rotation), 3)
        return ["--start-position", *map(str, p), "--start-angles", *map(str, a)]

    assert main(["track", ROBOT, "--to", "8", "10", "9.5", "--steps", "1", "--json"] + args(stable)) == 0
    out = json.loads(capsys.readouterr().out)
    assert np.allclose(out["steps"][0]["position"], stable.position, atol=1e-9)
    assert main(["track", ROBOT, "--to", "8", "10", "9.5"] + args(stable, dz=0.05)) == 2
    err = capsys.readouterr().err
    assert "--start-position" in err and len(err.strip().splitlines()) == 1
    assert main(["track", ROBOT, "--to", "8", "10", "9.5"] + args(unstable)) == 2
    assert "not stable" in capsys.readouterr().err
