"""Sweeps on dask.distributed (cdpr_algebra.sweep): every grid point once in the Parquet output, the same counts as
direct solves, resumption, errors recorded, a worker killed mid-sweep losing nothing, bad input named."""

import json
import os
import signal
import threading
import time

import numpy as np
import pytest

from cdpr_algebra import load_robot
from cdpr_algebra.cli.main import main
from cdpr_algebra.dgp.solve import dgp
from cdpr_algebra.model.errors import CdprInputError
from cdpr_algebra.sweep import tasks
from cdpr_algebra.sweep.grid import make_grid
from cdpr_algebra.sweep.run import read_table, run_sweep

ROBOT = "examples/seed000_test1.toml"

pytestmark = pytest.mark.xdist_group("sweep")


@pytest.fixture(scope="module")
def robot():
    return load_robot(ROBOT)


def test_dgp_sweep_on_a_local_cluster_resumes(robot, tmp_path, capsys):
    out = tmp_path / "s"
    args = ["sweep", ROBOT, "--vary", "rho1=7.5:8.5:3", "--out", str(out), "--workers", "2", "--batch", "1",
            "--no-certify", "--json"]
    assert main(args) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["solved"] == 3 and summary["written"]["points"] == 3
    pts = sorted(read_table(out, "points").to_pylist(), key=lambda r: r["point"])
    eqs = read_table(out, "equilibria").to_pylist()
    assert [p["point"] for p in pts] == [0, 1, 2]
    for p in pts:
        rho = robot.lengths.copy()
        rho[0] = p["rho1"]
        direct = dgp(robot, rho, certify=False)
        assert p["n_admissible"] == len(direct.solutions) and p["complete"] and p["error"] is None
        assert p["n_stable"] == sum(s.stable for s in direct.solutions)
        mine = sorted((e["x"], e["y"], e["z"]) for e in eqs if e["point"] == p["point"])
        theirs = sorted(tuple(s.position) for s in direct.solutions)
        assert np.allclose(mine, theirs, atol=1e-9)
    # rerun: nothing to do; drop one point's part file: only that point is solved again
    assert main(args) == 0
    assert json.loads(capsys.readouterr().out)["solved"] == 0
    parts = sorted((out / "points").glob("part-*.parquet"))
    victim = next(p for p in parts if read_table_part(p) == [1])
    victim.unlink()
    assert main(args) == 0
    again = json.loads(capsys.readouterr().out)
    assert again["solved"] == 1 and again["resumed"] == 2
    assert sorted(r["point"] for r in read_table(out, "points").to_pylist()) == [0, 1, 2]
    # another sweep in the same directory is refused
    assert main(["sweep", ROBOT, "--vary", "rho2=9:10:2", "--out", str(out), "--workers", "1"]) == 2
    assert "--out" in capsys.readouterr().err
    # the picture
    png = tmp_path / "s.png"
    assert main(["plot-sweep", str(out), "--out", str(png)]) == 0 and png.stat().st_size > 1000


def read_table_part(path):
    import pyarrow.parquet as pq

    return pq.read_table(path).column("point").to_pylist()


def test_a_killed_worker_loses_no_point(robot, tmp_path):
    from dask.distributed import Client, LocalCluster

    grid = make_grid(robot, ["rho1=7.5:9.5:6"])
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=":0") as cluster:
        with Client(cluster) as client:
            pids = list(client.run(os.getpid).values())
            result = {}

            def go():
                result["r"] = run_sweep(robot, grid, tmp_path / "k", scheduler=cluster.scheduler_address, batch=1,
                                        certify=False, progress=False)

            th = threading.Thread(target=go)
            th.start()
            time.sleep(2.0)  # tasks running
            os.kill(pids[0], signal.SIGKILL)
            th.join(timeout=240)
    assert not th.is_alive() and result["r"].solved == 6
    pts = read_table(tmp_path / "k", "points").to_pylist()
    assert sorted(p["point"] for p in pts) == list(range(6))
    assert all(p["error"] is None for p in pts)


def test_a_failing_point_is_recorded_not_dropped(robot, monkeypatch):
    real = tasks.SOLVERS["dgp"]

    def flaky(robot, names, values, certify):
        if values[0] > 8:
            raise ValueError("boom")
        return real(robot, names, values, certify)

    monkeypatch.setitem(tasks.SOLVERS, "dgp", flaky)
    points, eqs = tasks.solve_batch(robot, "dgp", ("rho1",), [(0, (7.5,)), (1, (9.0,))], certify=False)
    assert [p["point"] for p in points] == [0, 1]
    assert points[0]["error"] is None and points[0]["n_admissible"] == 6
    assert "ValueError: boom" in points[1]["error"] and points[1]["complete"] is False
    assert {e["point"] for e in eqs} == {0}


@pytest.mark.parametrize("specs, kind, field", [
    (["rho1=7:8"], None, "--vary"),
    (["rho9=7:8:3"], None, "--vary"),
    (["rho1=7:8:0"], None, "--vary"),
    (["rho1=-1:8:3"], None, "--vary"),
    (["rho1=7:8:3", "x=0:1:2"], None, "--vary"),
    (["rho1=7:8:3", "rho1=7:9:2"], None, "--vary"),
    (["x=0:1:2"], "cc", "--kind"),
    (["phi_x=0:1:2"], "igp", "--vary"),
])
def test_bad_grids_name_the_flag(robot, specs, kind, field):
    with pytest.raises(CdprInputError) as err:
        make_grid(robot, specs, kind)
    assert err.value.field == field


def test_igp_sweep_grid_counts(robot):
    r3 = load_robot("examples/seed004_table3.toml")
    g = make_grid(r3, ["x=6:8:3", "y=9:9:1"])
    assert g.kind == "igp" and g.size == 3
    points, eqs = tasks.solve_batch(r3, "igp", g.names, list(g.points()), certify=False)
    from cdpr_algebra.igp.position import igp_position

    for p in points:
        direct = igp_position(r3, [p["x"], p["y"], 0.0], include_complex=False, certify=False)
        assert p["n_admissible"] == sum(1 for s in direct.real_solutions if s.admissible)


def test_sweep_on_a_scheduler_started_by_the_dask_commands(tmp_path, capsys):
    """``dask scheduler`` and ``dask worker`` processes on this machine, reached through a scheduler file."""
    import subprocess
    import sys

    sched_file = tmp_path / "scheduler.json"
    dask = [sys.executable, "-m", "dask", "scheduler"]  # the `dask scheduler` / `dask worker` commands
    worker = [sys.executable, "-m", "dask", "worker"]
    procs = [subprocess.Popen(dask + ["--scheduler-file", str(sched_file), "--port", "0", "--dashboard-address",
                                      ":0"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)]
    try:
        for _ in range(100):
            if sched_file.exists():
                break
            time.sleep(0.2)
        procs.append(subprocess.Popen(worker + ["--scheduler-file", str(sched_file), "--nthreads", "1"],
                                      stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL))
        assert main(["sweep", ROBOT, "--vary", "rho2=9.5:10.5:2", "--out", str(tmp_path / "d"), "--scheduler",
                     str(sched_file), "--no-certify", "--json"]) == 0
        summary = json.loads(capsys.readouterr().out)
        assert summary["solved"] == 2 and summary["written"]["points"] == 2 and summary["workers"] >= 1
    finally:
        for p in procs[::-1]:
            p.terminate()
        for p in procs:
            p.wait(timeout=30)


def test_cc_sweep_point_is_the_published_table():
    """Merlet's CC paper, 8-cable robot at (0, 1, 2): 4 valid 6-cable configurations; the largest r_min is CC
    [2..7]'s 0.760099942309 (the README erratum)."""
    r8 = load_robot("examples/seed002_8cables.toml")
    g = make_grid(r8, ["x=0:0:1", "y=1:1:1", "z=2:2:1"])
    assert g.kind == "cc"
    points, eqs = tasks.solve_batch(r8, "cc", g.names, list(g.points()), certify=True)
    (p,) = points
    assert p["error"] is None and p["n_admissible"] == 4 and p["complete"]
    assert abs(p["rmin"] - 0.760099942309) < 1e-11
    assert sorted(e["taut"] for e in eqs) == ["1,2,3,4,5,6", "1,3,4,5,6,8", "2,3,4,5,6,7", "3,4,5,6,7,8"]
    assert all(e["certified"] for e in eqs)


def test_workspace_picture_of_a_pose_sweep(tmp_path):
    """plot-sweep of an x, y, z grid draws the workspace (written here without a cluster: the task's rows)."""
    import matplotlib

    from cdpr_algebra.sweep.pictures import sweep_figure
    from cdpr_algebra.sweep.run import _check_same_sweep, _robot_dict, _write

    r3 = load_robot("examples/seed004_table3.toml")
    g = make_grid(r3, ["x=6:8:2", "y=8:9:2", "z=1:2:2"])
    out = tmp_path / "w"
    _check_same_sweep(out, {"robot": _robot_dict(r3), "grid": g.to_dict(), "certify": False, "version": 1})
    points, eqs = tasks.solve_batch(r3, "igp", g.names, list(g.points()), certify=False)
    _write(out, "equilibria", eqs)
    _write(out, "points", points)
    fig = sweep_figure(out, "n_admissible")
    ax = fig.axes[0]
    assert ax.name == "3d" and len(ax.collections[0].get_offsets()) == 8
    matplotlib.pyplot.close(fig)
    with pytest.raises(CdprInputError, match="--value"):
        sweep_figure(out, "nope")
