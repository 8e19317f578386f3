"""The CLI is a thin layer: its JSON carries the library's numbers (seed 004 Tables 1-2)."""

import json
import subprocess
import sys

import numpy as np
import pytest

from cdpr_algebra.cli.main import main

KEYS = {"position", "com_position", "rotation", "angles", "euler_parameters", "lengths", "tensions", "admissible",
        "hessian", "stable", "real"}


def test_igp_orientation_json(capsys):
    assert main(["igp", "examples/seed004_table1.toml", "--orientation", "0", "0", "0", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    (sol,) = out["solutions"]
    assert KEYS <= set(sol)
    assert np.allclose(sol["com_position"], [5196 / 1805, 2973 / 722, 139299 / 20938], rtol=1e-12)
    assert np.allclose(sol["lengths"], [8.01, 10.36, 9.85], atol=0.005)
    assert sol["hessian"] == ">" and sol["stable"] and sol["admissible"] and sol["real"]
    assert out["solution_set"] is None


def test_igp_orientation_degrees_and_table(capsys):
    assert main(["igp", "examples/seed004_table1.toml", "--orientation", "90", "0", "0", "--degrees", "--json"]) == 0
    deg = json.loads(capsys.readouterr().out)
    assert main(["igp", "examples/seed004_table1.toml", "--orientation", str(np.pi / 2), "0", "0", "--json"]) == 0
    rad = json.loads(capsys.readouterr().out)
    assert np.allclose(deg["solutions"][0]["com_position"], rad["solutions"][0]["com_position"])
    assert main(["igp", "examples/seed004_table2.toml", "--orientation", "0", "0", "0", "--exact"]) == 0
    text = capsys.readouterr().out
    assert "-989/137" in text and "<>" in text and "(+39.37, +42.29, +38.27)" in text


def test_special_set_reported(tmp_path, capsys):
    robot = tmp_path / "fig3a.json"
    robot.write_text(json.dumps({"base": [[0, 0, 0], [8, 0, 0], [0, 7, 0]],
                                 "platform": [[-0.5, -0.5, -1], [1, 0, -1], [0, 1, -1]],
                                 "com": [0, 0, 0], "load": 10, "load_direction": [0, 0, 1]}))
    assert main(["igp", str(robot), "--orientation", "0", "0", "0", "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["solutions"] == [] and out["solution_set"]["kind"] == "vertical_line"


def test_python_dash_m():
    proc = subprocess.run([sys.executable, "-m", "cdpr_algebra", "igp", "examples/seed004_table1.toml",
                           "--orientation", "0", "0", "0"], capture_output=True, text=True)
    assert proc.returncode == 0 and "(+8.01, +10.36, +9.85)" in proc.stdout
    bad = subprocess.run([sys.executable, "-m", "cdpr_algebra", "igp", "missing.toml", "--orientation", "0", "0", "0"],
                         capture_output=True, text=True)
    assert bad.returncode == 2 and "no such file" in bad.stderr and "Traceback" not in bad.stderr


def test_console_exit_skips_only_the_teardown():
    """cli.main.exit_now (how ``cdpr`` and ``python -m cdpr_algebra`` end): the status is kept, atexit callbacks run,
    buffered output is flushed (a whole DGP's JSON through a pipe), the teardown (objects' finalizers) is skipped, and
    a process with another thread still running exits normally, joining it."""
    run = [sys.executable, "-c", "import atexit, sys; atexit.register(lambda: print('atexit ran')); "
           "sys.stdout.write('x' * 100000); from cdpr_algebra.cli.main import exit_now; exit_now(3)"]
    proc = subprocess.run(run, capture_output=True, text=True)
    assert proc.returncode == 3 and proc.stdout == "x" * 100000 + "atexit ran\n"
    teardown = ("class D:\n    def __del__(self):\n        print('teardown')\nd = D()\n"
                "from cdpr_algebra.cli.main import exit_now\nexit_now({})".format)
    assert subprocess.run([sys.executable, "-c", teardown(0)], capture_output=True, text=True).stdout == ""
    plain = subprocess.run([sys.executable, "-c", teardown(0).replace("exit_now(0)", "exit_now")], capture_output=True,
                           text=True)
    assert plain.stdout == "teardown\n"  # the objects' finalizers run in the teardown that exit_now skips
    run = [sys.executable, "-c", "import threading, time; threading.Thread(target=lambda: (time.sleep(0.3), "
           "print('thread done'))).start(); from cdpr_algebra.cli.main import exit_now; exit_now(0)"]
    proc = subprocess.run(run, capture_output=True, text=True)
    assert proc.returncode == 0 and proc.stdout == "thread done\n"
    proc = subprocess.run([sys.executable, "-m", "cdpr_algebra", "dgp", "examples/seed000_test1.toml", "--json"],
                          capture_output=True, text=True)
    out = json.loads(proc.stdout)
    assert proc.returncode == 0 and out["complete"] is True and len(out["subproblems"]) == 7


def test_warm_solves_and_reports(tmp_path, capsys):
    """``cdpr warm`` (run by setup.py at build time) solves the robot by every compiled path and says so; a robot
    without cable lengths is an input error naming the field."""
    assert main(["warm", "examples/seed000_test1.toml"]) == 0
    line = capsys.readouterr().out.strip()
    assert line.startswith("examples/seed000_test1.toml: dgp ") and "interval" in line and "track" in line
    text = open("examples/seed000_test1.toml", encoding="utf-8").read().replace("lengths = [7.5, 10.0, 9.5]", "")
    robot = tmp_path / "no_lengths.toml"
    robot.write_text(text)
    assert main(["warm", str(robot)]) == 2
    assert "lengths" in capsys.readouterr().err


def test_warm_environment_keeps_the_build_environment():
    """setup.py's warm-up sees the built package first and still the path pip gave the build (its isolated
    environment with numpy and numba): with PYTHONPATH replaced, a fresh machine's install cached nothing."""
    import importlib.util
    import os

    spec = importlib.util.spec_from_file_location("cdpr_setup", os.path.join(os.path.dirname(__file__), "..", "setup.py"))
    setup_py = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(setup_py)  # not __main__: setup() is not called
    sep = os.pathsep
    env = setup_py.warm_environment("/build/lib", {"PYTHONPATH": f"/iso/site{sep}/iso/overlay", "NUMBA_CACHE_DIR": "/c",
                                                   "HOME": "/root"})
    assert env["PYTHONPATH"].split(sep) == ["/build/lib", "/iso/site", "/iso/overlay"]
    assert "NUMBA_CACHE_DIR" not in env and env["HOME"] == "/root"
    assert setup_py.warm_environment("/build/lib", {})["PYTHONPATH"] == "/build/lib"


@pytest.mark.parametrize("argv, field, words", [
    (["export", "examples/seed000_test1.toml", "--taut", "1", "2", "3", "--out", "{missing}/x.txt"], "--out",
     "does not exist"),
    (["export", "examples/seed000_test1.toml", "--taut", "1", "2", "3", "--out", "{tmp}"], "--out", "is a directory"),
    (["track", "examples/seed000_test1.toml", "--to", "7.6", "10", "9.5", "--steps", "1", "--plot", "{missing}/p.png"],
     "--plot", "does not exist"),
    (["track", "examples/seed000_test1.toml", "--to", "7.6", "10", "9.5", "--steps", "1", "--plot", "{tmp}/p.txt"],
     "--plot", "ending in .png"),
    (["plot-sweep", "{tmp}/sweep", "--out", "{tmp}/s.png"], "DIR", "not a sweep's header"),
    (["plot-sweep", "{tmp}/sweep", "--out", "{missing}/s.png"], "--out", "does not exist"),
])
def test_files_to_write_or_read_are_checked_before_any_work(tmp_path, capsys, argv, field, words):
    """One line naming the option and exit status 2, never a traceback after the work is done."""
    (tmp_path / "sweep").mkdir()
    (tmp_path / "sweep" / "sweep.json").write_text("garbage")
    argv = [a.format(tmp=tmp_path, missing=tmp_path / "missing") for a in argv]
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert f"field '{field}'" in err and words in err and "Traceback" not in err


@pytest.mark.parametrize("argv, field", [
    (["track", "examples/seed000_test1.toml", "--to", "7.6", "10", "9.5", "--range", "0", "2"], "--range"),
    (["crosscheck", "examples/seed000_test1.toml", "--taut", "1", "2", "3", "--max-m", "2"], "--max-m"),
    (["igp", "examples/seed004_table1.toml", "--position", "1", "2", "3", "--degrees"], "--degrees"),
])
def test_options_that_would_be_ignored_are_refused(capsys, argv, field):
    assert main(argv) == 2
    err = capsys.readouterr().err
    assert f"field '{field}'" in err and "Traceback" not in err


def test_igp_all_says_how_complex_lengths_are_measured(capsys):
    """--all lists the complex roots of the assigned-position IGP; their 'lengths' are the Hermitian norms
    sqrt(s^H s) of s = B - A (seed 004 Table 4's convention), which the table and the JSON say."""
    args = ["igp", "examples/seed000_test1.toml", "--position", "1.1", "0.7", "-1.3", "--all"]
    assert main(args) == 0
    text = capsys.readouterr().out
    assert "Hermitian norm" in text
    assert main(args + ["--json"]) == 0
    sols = json.loads(capsys.readouterr().out)["solutions"]
    cx = [s for s in sols if not s["real"]]
    assert len(sols) == 24 and len(cx) == 20
    assert {s["lengths_norm"] for s in sols if s["real"]} == {"euclidean"}
    from cdpr_algebra.model.robot import load_robot
    robot = load_robot("examples/seed000_test1.toml")
    for s in cx:
        assert s["lengths_norm"].startswith("hermitian")
        G = _complex_array(s["com_position"])
        R = _complex_array(s["rotation"])
        d = G + (robot.platform - robot.com) @ R.T - robot.base
        assert np.allclose(s["lengths"], np.sqrt(np.sum(np.abs(d) ** 2, axis=1)), rtol=1e-9)


def _complex_array(value) -> np.ndarray:
    """The JSON's complex numbers ([re, im] pairs) as a complex array."""
    a = np.asarray(value, dtype=float)
    return a[..., 0] + 1j * a[..., 1]
