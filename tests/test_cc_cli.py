"""``cdpr cc``: the JSON contract carries the library's numbers (seed 002 Sec. IV-B.1), bad input gives one line
naming the option and exit status 2."""

import json
import subprocess
import sys

import numpy as np
import pytest

from cdpr_algebra.cli.main import main

ROBOT = "examples/seed002_8cables.toml"
KEYS = {"cables", "tensions", "radii", "rmin", "safe_nearby", "robust_to_uncertainty", "counterexample"}


def test_pose_json_contract(capsys):
    assert main(["cc", ROBOT, "--position", "0", "1", "2", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["mode"] == "pose" and out["position"] == [0, 1, 2]
    confs = out["configurations"]
    assert sorted(c["cables"] for c in confs) == [[1, 2, 3, 4, 5, 6], [1, 3, 4, 5, 6, 8], [2, 3, 4, 5, 6, 7],
                                                  [3, 4, 5, 6, 7, 8]]
    for c in confs:
        assert KEYS <= set(c)
        assert set(c["radii"]) == {str(k) for k in c["cables"]} | {"singular"}
        assert c["rmin"] == min(c["radii"].values())
        assert c["safe_nearby"] is None and c["robust_to_uncertainty"] is None and c["counterexample"] is None
    # ranked by r_min; [1,2,3,4,5,6] has the smallest r_min (cable 3, 0.755452449) and the printed per-cable values
    assert [c["rmin"] for c in confs] == sorted((c["rmin"] for c in confs), reverse=True)
    last = confs[-1]
    assert last["cables"] == [1, 2, 3, 4, 5, 6] and last["limiting"] == 3
    assert last["rmin"] == pytest.approx(0.755452449, abs=5e-10)
    assert last["radii"]["singular"] == pytest.approx(2.9411453193, rel=1e-9)


def test_configuration_ball_uncertainty_json(capsys):
    assert main(["cc", ROBOT, "--position", "1", "0", "2", "--configuration", "3", "4", "5", "6", "7", "8",
                 "--ball", "0.03", "--uncertainty", "0.0001", "0.0001", "0.0001", "--json"]) == 0
    (c,) = json.loads(capsys.readouterr().out)["configurations"]
    assert c["cables"] == [3, 4, 5, 6, 7, 8] and c["valid"]
    assert c["rmin"] == pytest.approx(0.532477175518869, rel=1e-9) and c["limiting"] == 5
    assert c["safe_nearby"] is True and c["robust_to_uncertainty"] is True and c["counterexample"] is None


def test_invalid_configuration_reported_not_valid(capsys):
    assert main(["cc", ROBOT, "--position", "0", "1", "2", "--configuration", "1", "2", "3", "4", "5", "7",
                 "--json"]) == 0
    (c,) = json.loads(capsys.readouterr().out)["configurations"]
    assert not c["valid"] and c["rmin"] == 0.0 and min(c["tensions"]) < 0
    # r_min is 0 by definition there: its certificate (of the nearest critical point, ~0.0815) does not certify it
    assert c["certified"] is None and c["radius_certificate"]["radius_enclosure"][0] > 0.08
    assert main(["cc", ROBOT, "--position", "0", "1", "2", "--configuration", "1", "2", "3", "4", "5", "7"]) == 0
    text = capsys.readouterr().out
    assert "not valid at the pose (r_min 0)" in text and " yes " not in text.splitlines()[3]


@pytest.mark.parametrize("position", [["0", "1", "20"], ["100", "100", "100"]])
def test_a_pose_without_a_valid_configuration_says_so(capsys, position):
    """Above the base, or far outside it, no 6-cable configuration is valid (the radii were asked of none)."""
    assert main(["cc", ROBOT, "--position", *position]) == 0
    assert "no valid cable configuration" in capsys.readouterr().out
    assert main(["cc", ROBOT, "--position", *position, "--json"]) == 0
    assert all(not c["valid"] for c in json.loads(capsys.readouterr().out)["configurations"])


def test_table(capsys):
    assert main(["cc", ROBOT, "--position", "1", "0", "2"]) == 0
    text = capsys.readouterr().out
    assert "r_min (limiting)" in text and "0.5324771756 (5)" in text and "[1, 4, 5, 6, 7, 8]" in text


@pytest.mark.parametrize("argv,field", [
    (["--trajectory", "cos(t", "sin(t)", "2", "--range", "0", "1"], "--trajectory"),
    (["--trajectory", "cos(t)", "y", "2", "--range", "0", "1"], "--trajectory"),
    (["--trajectory", "cos(t)", "sin(t)", "2"], "--range"),
    (["--surface", "u", "v", "2", "--range", "0", "1"], "--range"),
    (["--position", "0", "1", "2", "--trajectory", "t", "0", "2", "--range", "0", "1"], "--position"),
    (["--trajectory", "t", "0", "2", "--range", "0", "1", "--ball", "0.03"], "--ball"),
    (["--trajectory", "cos(t)", "sin(t)", "2", "--range", "0", "t"], "--range"),
    (["--trajectory", "cos(t)", "sin(t)", "2", "--range", "pi", "pi/2"], "--range"),
    (["--trajectory", "cos(t)", "sin(t)", "2", "--range", "0", "1/0"], "--range"),
    (["--position", "0", "1", "2", "--configuration", "1", "2", "9"], "--configuration"),
    (["--position", "0", "1", "2", "--ball", "-1"], "--ball"),
    (["--position", "0", "1", "2", "--uncertainty", "-1", "0", "0"], "--uncertainty"),
    ([], "--position"),
])
def test_bad_input_one_line_exit_2(capsys, argv, field):
    assert main(["cc", ROBOT] + argv) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and err.startswith("cdpr: error:") and f"'{field}'" in err


def test_range_takes_the_expressions_of_the_path():
    """``--range 0 pi/2`` is the range [0, pi/2] to the last bit, as a path expression would read it."""
    from cdpr_algebra.cc.paths import parse_path

    spec = parse_path(["cos(t)", "sin(t)", "2"], [("0", "pi/2")])
    assert [tuple(r) for r in spec.ranges] == [(0.0, float(np.pi / 2))]
    surf = parse_path(["u", "v", "2"], [("-sqrt(2)", "2*pi"), (0, "1/3")])
    assert [tuple(r) for r in surf.ranges] == [(-float(np.sqrt(2)), float(2 * np.pi)), (0.0, 1 / 3)]


def test_unparsable_trajectory_subprocess():
    proc = subprocess.run([sys.executable, "-m", "cdpr_algebra", "cc", ROBOT, "--trajectory", "cos(t", "sin(t)",
                           "2", "--range", "0", "1.5"], capture_output=True, text=True)
    assert proc.returncode == 2 and proc.stdout == ""
    lines = proc.stderr.strip().splitlines()
    assert len(lines) == 1 and "--trajectory" in lines[0] and "cannot parse 'cos(t'" in lines[0]


def test_failed_paths_give_exit_3_and_name_the_configuration(capsys, monkeypatch):
    """Paths forced to fail (a budget of 3 steps per path in the radii's batched homotopy): the JSON counts them per
    configuration, stderr names the configuration, and the exit status is 3 (incomplete)."""
    from dataclasses import replace

    from cdpr_algebra.cc import cubic_distances
    from cdpr_algebra.homotopy.tracker import TrackerOptions

    options = replace(cubic_distances.batch_options(), tracker=TrackerOptions(predictor_tol=1e-4, max_steps=3))
    monkeypatch.setattr(cubic_distances, "batch_options", lambda: options)
    code = main(["cc", ROBOT, "--position", "1", "0", "2", "--configuration", "3", "4", "5", "6", "7", "8", "--json"])
    out, err = capsys.readouterr()
    entry = json.loads(out)["configurations"][0]
    assert code == 3 and entry["failed_paths"] > 0
    assert "incomplete" in err and "[3, 4, 5, 6, 7, 8]" in err and f"{entry['failed_paths']} failed path" in err
