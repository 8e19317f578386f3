"""IGP with assigned orientation (seed 004 Sec. 3, App. A, Tables 1-2)."""

import numpy as np
import pytest
import sympy as sp

from cdpr_algebra import load_robot
from cdpr_algebra.igp.orientation import exact_solution, igp_orientation, p123, p467, _Problem
from cdpr_algebra.model.pose import matrix_from_angles
from cdpr_algebra.model.robot import Robot

x = sp.Symbol("x")


def test_table1_exact():
    robot = load_robot("examples/seed004_table1.toml")
    G = exact_solution(robot, sp.eye(3))
    assert G == [sp.Rational(5196, 1805), sp.Rational(2973, 722), sp.Rational(139299, 20938)]
    # p123 equals the printed polynomial up to a constant factor
    E = p123(_Problem(robot, sp.eye(3), True).params())
    ours = sp.Poly(sum(e * x ** i for i, e in enumerate(E)), x)
    printed = sp.Poly(sp.Rational(43069563, 1562500) * (5 * x + 3) * (5 * x - 52) * (10 * x - 7) * (1805 * x - 5196), x)
    q, r = sp.div(ours, printed)
    assert r.is_zero and q.is_ground and not q.is_zero


def test_table1_numeric_row():
    robot = load_robot("examples/seed004_table1.toml")
    res = igp_orientation(robot, np.eye(3))
    (s,) = res.solutions
    assert np.allclose(s.com_position, [5196 / 1805, 2973 / 722, 139299 / 20938], rtol=1e-13)
    assert np.allclose(s.lengths, [8.01, 10.36, 9.85], atol=0.005)
    assert np.allclose(s.tensions, [5.05, 4.69, 5.49], atol=0.01)  # 5.4955 printed as 5.49
    assert s.hessian == ">" and s.stable and s.admissible
    assert s.residual < 1e-12


def test_table2_exact_delta_zero():
    robot = load_robot("examples/seed004_table2.toml")
    prob = _Problem(robot, sp.eye(3), True)
    from cdpr_algebra.generated.igp_orientation import delta

    assert delta(*prob.params())[0] == 0
    G = exact_solution(robot, sp.eye(3))
    assert G == [sp.Rational(-989, 137), sp.Rational(-705, 137), sp.Rational(396757, 10823)]
    E = p467(prob.params())
    ours = sp.Poly(sum(e * x ** i for i, e in enumerate(E)), x)
    printed = sp.Poly(sp.Rational(21504, 5) * (x + 1) * (x - 5) * (5 * x - 16) * (137 * x + 989), x)
    q, r = sp.div(ours, printed)
    assert r.is_zero and q.is_ground and not q.is_zero
    res = igp_orientation(robot, np.eye(3))
    (s,) = res.solutions
    assert np.allclose(s.lengths, [39.37, 42.29, 38.27], atol=0.005)
    assert np.allclose(s.tensions, [21.91, -7.70, -4.54], atol=0.005)
    assert s.hessian == "<>" and not s.admissible


def _robot(r, a2=(8, 0, 0), a3=(0, 7, 0)):
    return Robot(base=[[0, 0, 0], list(a2), list(a3)], platform=r, com=[0, 0, 0], load=10, load_direction=[0, 0, 1])


@pytest.mark.parametrize("exact", [False, True])
def test_fig3a_vertical_line(exact):
    robot = _robot([[-0.5, -0.5, -1], [1, 0, -1], [0, 1, -1]])
    res = igp_orientation(robot, sp.eye(3) if exact else np.eye(3), exact=exact)
    assert res.solutions == () and res.solution_set.kind == "vertical_line"
    assert np.allclose(res.solution_set.data["line_point"][:2], [2, 1.75], atol=1e-12)
    assert np.allclose(res.solution_set.data["line_direction"], [0, 0, 1])


@pytest.mark.parametrize("exact", [False, True])
def test_fig3b_vertical_line(exact):
    robot = _robot([[-0.5, -0.5, -1], [1.5, -0.5, -1], [-0.5, 1.25, -1]])
    res = igp_orientation(robot, sp.eye(3) if exact else np.eye(3), exact=exact)
    assert res.solution_set.kind == "vertical_line"
    assert np.allclose(res.solution_set.data["line_point"][:2], [2, 2], atol=1e-12)


@pytest.mark.parametrize("exact", [False, True])
def test_fig4_cylinder_curve(exact):
    robot = _robot([[-2 / 3, -2 / 3, -3 / 2], [14 / 15, -2 / 3, -1 / 2], [-2 / 3, 11 / 15, -1]])
    res = igp_orientation(robot, sp.eye(3) if exact else np.eye(3), exact=exact)
    assert res.solution_set.kind == "cylinder_curve"
    c = dict(zip(map(tuple, res.solution_set.data["conic_monomials"]), res.solution_set.data["conic_coefficients"]))
    printed = {(2, 0): 735, (1, 1): 567, (0, 2): -420, (1, 0): -6062, (0, 1): 2534, (0, 0): 1960}
    ratio = c[(2, 0)] / 735
    for m, v in printed.items():
        assert c[m] == pytest.approx(ratio * v, rel=1e-9)
    for m in [(3, 0), (2, 1), (1, 2), (0, 3)]:
        assert abs(c[m]) < 1e-12


@pytest.mark.parametrize("exact", [False, True])
def test_crane(exact):
    robot = _robot([[0, 0, -1], [1, 0.25, -1], [0.25, 1, -1.5]])
    res = igp_orientation(robot, sp.eye(3) if exact else np.eye(3), exact=exact)
    assert res.solution_set.kind == "crane" and res.solution_set.data["cable"] == 1
    assert np.allclose(res.solution_set.data["line_point"][:2], [0, 0], atol=1e-12)


@pytest.mark.parametrize("exact", [False, True])
def test_planar_conic(exact):
    # plane G B1 B2 parallel to the vertical plane through A1 and A2 (y = 0)
    robot = _robot([[0.5, 0, -1], [-0.5, 0, -1.25], [0.25, 1, -1.5]])
    res = igp_orientation(robot, sp.eye(3) if exact else np.eye(3), exact=exact)
    assert res.solution_set.kind == "planar_conic"
    assert res.solution_set.data["cables"] == [1, 2] and res.solution_set.data["slack_cable"] == 3


def _random_robot(rng, direction=(0, 0, -1)):
    base = rng.uniform(-5, 5, (3, 3)) + np.array([0, 0, 6])
    plat = rng.uniform(-1, 1, (3, 3))
    com = rng.uniform(-0.3, 0.3, 3)
    return Robot(base=base, platform=plat, com=com, load=rng.uniform(1, 20), load_direction=list(direction))


def test_random_geometries_residual_and_rigid_motion():
    rng = np.random.default_rng(7)
    checked = 0
    for _ in range(20):
        robot = _random_robot(rng)
        R = matrix_from_angles(*rng.uniform(-0.6, 0.6, 3))
        res = igp_orientation(robot, R)
        if not res.solutions:
            continue
        (s,) = res.solutions
        assert s.residual < 1e-9
        # s_i x R-independent check: B_i lie at the computed lengths
        B = s.position + robot.platform @ s.rotation.T
        assert np.allclose(np.linalg.norm(B - robot.base, axis=1), s.lengths, rtol=1e-12)
        # rigid motion of the world frame (rotation W, translation t), load direction rotated with it
        W = matrix_from_angles(*rng.uniform(-np.pi, np.pi, 3))
        t = rng.uniform(-3, 3, 3)
        moved = Robot(base=robot.base @ W.T + t, platform=robot.platform, com=robot.com, load=robot.load,
                      load_direction=(W @ robot.load_direction).tolist())
        res2 = igp_orientation(moved, W @ R)
        (s2,) = res2.solutions
        assert np.allclose(s2.com_position, W @ s.com_position + t, rtol=1e-9, atol=1e-9 * robot.size)
        assert np.allclose(s2.lengths, s.lengths, rtol=1e-9)
        assert np.allclose(s2.tensions, s.tensions, rtol=1e-8, atol=1e-9 * robot.load)
        assert s2.hessian == s.hessian
        checked += 1
    assert checked >= 15


def test_wrong_cable_count():
    robot = load_robot("examples/seed000_test2.toml")
    from cdpr_algebra import CdprInputError

    with pytest.raises(CdprInputError, match="exactly 3 cables"):
        igp_orientation(robot, np.eye(3))


def test_a_degenerate_case_none_of_the_special_sets_fits_is_undecided(capsys):
    """Test 1's robot (seed 000) at the identity: p123 vanishes identically and none of the special sets of
    Carricato 2013 App. A applies.  Not solved, so not 'empty': the result is undecided and the command exits 3."""
    from pathlib import Path

    from cdpr_algebra.cli.main import main

    path = Path(__file__).resolve().parents[1] / "examples" / "seed000_test1.toml"
    res = igp_orientation(load_robot(path), np.eye(3))
    assert res.solution_set is not None and res.solution_set.kind == "undecided" and res.status == "undecided"
    assert res.to_dict()["status"] == "undecided" and not res.solutions
    assert main(["igp", str(path), "--orientation", "0", "0", "0"]) == 3
    assert "undecided" in capsys.readouterr().err
