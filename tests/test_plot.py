"""Pictures (issue 7): ``cdpr_algebra.report.plot`` and ``cdpr plot``.

The equilibria drawn are the published rows of seed 000 Tables 1-2 (tests/data/seed000_tables.json) made into
DGPSolution records, so the figures are checked against independent data: one panel per row, cable i drawn from
A_i to p + R b_i' (R = Rz Ry Rx written out here), solid exactly for the printed taut set, dashed otherwise.
The CLI runs on a one-cable robot (the DGP is analytic there, so the test is fast).
"""

import json
import struct
from pathlib import Path

import numpy as np
import pytest
from mpl_toolkits.mplot3d.art3d import Poly3DCollection

from cdpr_algebra import CdprInputError, load_robot
from cdpr_algebra.cli.main import main
from cdpr_algebra.dgp.solve import DGPSolution
from cdpr_algebra.igp.orientation import igp_orientation
from cdpr_algebra.report.plot import plot_equilibria, plot_igp_solutions, plot_radius_along_path
from cdpr_algebra.model.robot import Robot

ROOT = Path(__file__).resolve().parents[1]
TABLES = json.loads((ROOT / "tests" / "data" / "seed000_tables.json").read_text())["tables"]


def rot(phi_x, phi_y, phi_z):
    cx, sx, cy, sy, cz, sz = np.cos(phi_x), np.sin(phi_x), np.cos(phi_y), np.sin(phi_y), np.cos(phi_z), np.sin(phi_z)
    Rx = np.array([[1, 0, 0], [0, cx, -sx], [0, sx, cx]])
    Ry = np.array([[cy, 0, sy], [0, 1, 0], [-sy, 0, cy]])
    Rz = np.array([[cz, -sz, 0], [sz, cz, 0], [0, 0, 1]])
    return Rz @ Ry @ Rx


def table_solutions(table):
    rows = TABLES[table]["rows"]
    return [DGPSolution(tuple(r["taut"]), np.array(r["position"]), rot(*r["angles"]), np.array(r["tensions"]),
                        ">" if r["stability"] == ">" else "<>") for r in rows]


def panels(fig):
    return [ax for ax in fig.axes if ax.name == "3d"]


def cables(ax):
    return {line.get_gid(): line for line in ax.lines if (line.get_gid() or "").startswith("cable ")}


@pytest.mark.parametrize("table, robot_file", [("1", "seed000_test1"), ("2", "seed000_test2")])
def test_plot_equilibria_panels_and_cables(table, robot_file):
    robot = load_robot(ROOT / "examples" / f"{robot_file}.toml")
    sols = table_solutions(table)
    fig = plot_equilibria(robot, sols)
    axes = panels(fig)
    assert len(axes) == len(sols)
    assert len(fig.axes) == len(sols) + 1  # one shared colour bar
    tmax = max(s.tensions[i - 1] for s in sols for i in s.taut)
    assert fig.axes[-1].get_ylim() == pytest.approx((0.0, tmax))
    for k, (ax, s) in enumerate(zip(axes, sols)):
        lines = cables(ax)
        assert len(lines) == robot.n == len(ax.lines)
        solid = {int(g.split()[1]) for g, ln in lines.items() if ln.get_linestyle() == "-"}
        dashed = {int(g.split()[1]) for g, ln in lines.items() if ln.get_linestyle() == "--"}
        assert solid == set(s.taut) and dashed == set(range(1, robot.n + 1)) - set(s.taut)
        B = s.position + robot.platform @ s.rotation.T
        for i in range(robot.n):
            xs, ys, zs = lines[f"cable {i + 1}"].get_data_3d()
            np.testing.assert_allclose(np.column_stack([xs, ys, zs]), [robot.base[i], B[i]], atol=1e-12)
        # taut cables: the higher the tension, the later in the colour map (viridis luminance grows)
        taut = sorted(s.taut, key=lambda i: s.tensions[i - 1])
        lum = [np.dot(lines[f"cable {i}"].get_color()[:3], [0.299, 0.587, 0.114]) for i in taut]
        assert lum == sorted(lum)
        title = ax.get_title()
        assert title.startswith(f"#{k + 1} ") and str(list(s.taut)) in title
        assert ("stable" in title and "unstable" not in title) == s.stable
        # the platform is a filled body, equal axes, z drawn downwards when the load acts along +z
        assert any(isinstance(c, Poly3DCollection) for c in ax.collections)
        spans = [np.ptp(lim) for lim in (ax.get_xlim(), ax.get_ylim(), ax.get_zlim())]
        assert max(spans) == pytest.approx(min(spans))
        assert ax.zaxis_inverted() == (robot.load_direction[2] > 0)


def test_plot_equilibria_empty_and_max_panels():
    robot = load_robot(ROOT / "examples" / "seed000_test2.toml")
    assert "no admissible" in panels(plot_equilibria(robot, []))[0].get_title()
    assert len(panels(plot_equilibria(robot, table_solutions("2"), max_panels=2))) == 2


def test_plot_igp_solutions_position(table3):
    robot, res = table3
    fig = plot_igp_solutions(robot, res)
    assert len(panels(fig)) == 24  # Table 3: 24 real solutions
    for ax in panels(fig):
        assert [ln.get_linestyle() for ln in cables(ax).values()] == ["-"] * 3  # every IGP cable has its length
    # Table 3 prints two configurations with all tensions >= 0 (2 and 6) and one '>' (18, tau_3 < 0)
    adm = panels(plot_igp_solutions(robot, res, select="admissible"))
    assert len(adm) == 2 and all("all tau >= 0" in ax.get_title() for ax in adm)
    both = panels(plot_igp_solutions(robot, res, select="admissible_or_stable"))
    assert len(both) == 3 and sum("H_r >" in ax.get_title() for ax in both) == 1
    assert len(panels(plot_igp_solutions(robot, res, select=lambda s: s.tensions[0] > 10))) == 2  # rows 9, 22
    with pytest.raises(CdprInputError, match="select"):
        plot_igp_solutions(robot, res, select="feasible")


def test_plot_igp_solutions_orientation_and_special_set():
    robot = load_robot(ROOT / "examples" / "seed004_table1.toml")
    (ax,) = panels(plot_igp_solutions(robot, igp_orientation(robot, np.eye(3))))
    assert "H_r >" in ax.get_title() and len(cables(ax)) == 3
    # seed 004 Fig. 3(a): G on the vertical line through (2, 1.75)
    fig3a = Robot(base=[[0, 0, 0], [8, 0, 0], [0, 7, 0]], platform=[[-0.5, -0.5, -1], [1, 0, -1], [0, 1, -1]],
                  com=[0, 0, 0], load=10, load_direction=[0, 0, 1])
    (ax,) = panels(plot_igp_solutions(fig3a, igp_orientation(fig3a, np.eye(3))))
    assert ax.get_title() == "vertical line"
    (line,) = [ln for ln in ax.lines if ln.get_gid() == "solution set"]
    xs, ys, zs = line.get_data_3d()
    np.testing.assert_allclose(xs, 2, atol=1e-12)
    np.testing.assert_allclose(ys, 1.75, atol=1e-12)


def test_plot_radius_along_path():
    ts = np.linspace(0, 2 * np.pi, 40)
    radii = np.array([0.2 + 0.05 * np.sin(ts), 0.15 + 0.05 * np.cos(ts)])
    radii[1, 5:8] = np.nan  # not valid there: a gap
    fig = plot_radius_along_path(ts, radii, ["[1, 2, 3, 4, 5, 6]", "[3, 4, 5, 6, 7, 8]"])
    (ax,) = fig.axes
    assert [ln.get_label() for ln in ax.lines] == ["[1, 2, 3, 4, 5, 6]", "[3, 4, 5, 6, 7, 8]"]
    for ln, r in zip(ax.lines, radii):
        np.testing.assert_array_equal(ln.get_xdata(), ts)
        np.testing.assert_array_equal(ln.get_ydata(), r)
    assert ax.get_legend() is not None
    with pytest.raises(CdprInputError, match="radii"):
        plot_radius_along_path(ts, radii[:, :-1], ["a", "b"])
    with pytest.raises(CdprInputError, match="labels"):
        plot_radius_along_path(ts, radii, ["a"])


# ----------------------------------------------------------------------------------------- cdpr plot
ONE_CABLE = """name = "one_cable"
base = [[0.0, 0.0, 3.0]]
platform = [[0.3, 0.1, 0.0]]
com = [0.0, 0.0, -0.2]
load = 2.0
lengths = [2.5]
"""


@pytest.fixture
def one_cable(tmp_path):
    path = tmp_path / "one_cable.toml"
    path.write_text(ONE_CABLE)
    return path


# A platform hanging from one cable (load along -z): force balance makes the cable vertical, B right below A,
# and the moment about B vanishes only with G on that vertical line, below B or above it: 2 equilibria for any
# length, both with tension Q.
ONE_CABLE_EQUILIBRIA = 2


def test_cli_plot_png(one_cable, tmp_path, capsys):
    out = tmp_path / "eq.png"
    assert main(["plot", str(one_cable), "--out", str(out), "--jobs", "1"]) == 0
    data = out.read_bytes()
    assert data[:8] == b"\x89PNG\r\n\x1a\n" and len(data) > 10_000
    width, height = struct.unpack(">II", data[16:24])
    assert width > height > 200  # the two equilibria side by side
    assert f"wrote {out}" in capsys.readouterr().out


def test_cli_plot_svg_default_lengths_override(one_cable, tmp_path, capsys):
    out = tmp_path / "eq.svg"
    assert main(["plot", str(one_cable), "--out", str(out), "--lengths", "2.0"]) == 0
    text = out.read_text()
    assert text.lstrip().startswith("<?xml") and "<svg" in text
    assert text.count('id="cable 1"') == ONE_CABLE_EQUILIBRIA  # one drawn cable per equilibrium panel
    assert "2.000" in capsys.readouterr().out  # tension Q = 2 in the table


def test_cli_plot_default_output_name(one_cable, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    assert main(["plot", str(one_cable)]) == 0
    assert (tmp_path / "one_cable_equilibria.png").stat().st_size > 0


@pytest.mark.parametrize("args, field", [
    (["--out", "eq.pdf"], "--out"),
    (["--out", "eq"], "--out"),
    (["--out", "no/such/dir/eq.png"], "--out"),
    (["--lengths", "1", "2"], "--lengths"),
    (["--lengths", "-1"], "--lengths"),
    (["--jobs", "0"], "--jobs"),
])
def test_cli_plot_bad_input_one_line_exit_2(one_cable, tmp_path, monkeypatch, capsys, args, field):
    monkeypatch.chdir(tmp_path)
    assert main(["plot", str(one_cable), *args]) == 2
    err = capsys.readouterr().err
    assert err.count("\n") == 1 and err.startswith("cdpr: error:") and f"'{field}'" in err
    assert not list(tmp_path.glob("*.png"))


def test_cli_plot_of_an_incomplete_dgp_exits_3(tmp_path, capsys, monkeypatch):
    """As `cdpr dgp`: when a subproblem is not proven complete (here paths forced to fail by a step budget of 3), the
    picture is still written, stderr says which taut sets may miss equilibria, and the exit status is 3."""
    from dataclasses import replace
    from pathlib import Path

    import cdpr_algebra.dgp.solve as dgp_mod

    base = dgp_mod.default_options()
    monkeypatch.setattr(dgp_mod, "default_options", lambda extended=False: replace(
        base, tracker=replace(base.tracker, max_steps=3)))
    monkeypatch.setattr(dgp_mod, "PROJECTIVE_RETRIES", 0)
    monkeypatch.setattr(dgp_mod, "UNHELD_ROOTS", False)  # failed paths stay failed (no Newton from their estimates)
    robot = Path(__file__).resolve().parents[1] / "examples" / "seed000_test1.toml"
    out = tmp_path / "eq.png"
    assert main(["plot", str(robot), "--out", str(out), "--jobs", "1"]) == 3
    cap = capsys.readouterr()
    assert out.stat().st_size > 0 and f"wrote {out}" in cap.out
    assert "incomplete" in cap.err and "[1, 2, 3]" in cap.err
