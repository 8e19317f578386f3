"""DGP with one taut cable (seed 000 Sec. 3.2): the four equilibria and the arcs where the other cables are slack."""

import numpy as np

from cdpr_algebra import Robot, load_robot
from cdpr_algebra.dgp.one_cable import one_cable_equilibria
from cdpr_algebra.model.pose import rotation_about
from cdpr_algebra.model.statics import equilibrium_tensions


def _robot(lengths):
    return Robot(base=[[0, 0, 10], [5, 0, 10], [0, 5, 10]], platform=[[0, 0, 0], [1, 0, 0], [0, 1, 0]],
                 com=[0.2, 0.1, -0.5], load=2.0, lengths=lengths)


def test_four_equilibria_when_the_others_are_long():
    robot = _robot([3.0, 20.0, 20.0])
    sols = one_cable_equilibria(robot, 0)
    assert len(sols) == 4 and sum(s.hanging for s in sols) == 1
    for s in sols:
        B = s.position + robot.platform @ s.rotation.T
        G = s.position + s.rotation @ robot.com
        assert np.isclose(np.linalg.norm(B[0] - robot.base[0]), 3.0)
        assert np.allclose(np.cross(G - B[0], robot.load_direction), 0, atol=1e-12)  # cable line through G
        eq = equilibrium_tensions(robot.base[:1], B[:1], G, robot.load, robot.load_direction)
        assert eq.residual < 1e-12 and np.isclose(eq.tensions[0], s.tension)
        assert np.all(np.linalg.norm(B[1:] - robot.base[1:], axis=1) <= robot.lengths[1:])
        assert s.theta_arcs == ((-np.pi, np.pi),)
    hanging = next(s for s in sols if s.hanging)
    assert hanging.tension == 2.0 and np.allclose(hanging.position + hanging.rotation @ robot.com, [0, 0, 7 - np.linalg.norm([0.2, 0.1, -0.5])])


def test_arcs_are_where_every_other_cable_is_slack():
    robot = _robot([3.0, 5.2, 5.3])
    sols = one_cable_equilibria(robot, 0)
    assert sols
    d = robot.load_direction
    for s in sols:
        (lo, hi), *_ = s.theta_arcs
        assert hi - lo < 2 * np.pi
        for theta in np.linspace(-np.pi, np.pi, 721):
            R = rotation_about(d, theta) @ s.rotation
            B1 = robot.base[0] + (s.position + s.rotation @ robot.platform[0] - robot.base[0])
            B = B1 + (robot.platform - robot.platform[0]) @ R.T
            slack = np.all(np.linalg.norm(B[1:] - robot.base[1:], axis=1) <= robot.lengths[1:] * (1 + 1e-9))
            inside = any(a - 1e-9 <= theta <= b + 1e-9 or a - 1e-9 <= theta + 2 * np.pi <= b + 1e-9 or
                         a - 1e-9 <= theta - 2 * np.pi <= b + 1e-9 for a, b in s.theta_arcs)
            if abs(min(abs(theta - a) for arc in s.theta_arcs for a in arc)) > 1e-3:
                assert slack == inside, theta


def test_none_when_another_cable_is_too_short():
    assert one_cable_equilibria(_robot([3.0, 1.0, 20.0]), 0) == []


def test_seed000_tests_have_no_one_cable_equilibria():
    """Seed 000 Table 1 prints none with 1 taut cable; Table 3 lists no stable one."""
    robot = load_robot("examples/seed000_test1.toml")
    assert all(one_cable_equilibria(robot, i) == [] for i in range(3))
    robot = load_robot("examples/seed000_test3.toml")
    assert not any(s.hanging for i in range(6) for s in one_cable_equilibria(robot, i))


def test_feasible_arcs_are_joined_across_two_pi():
    """The arc intersection cuts an arc crossing 2 pi in two; the reported arcs are the union, joined."""
    from cdpr_algebra.dgp.one_cable import TWO_PI, _merged

    assert _merged([(0.0, 1.0), (5.0, TWO_PI)]) == [(5.0, 1.0 + TWO_PI)]
    assert _merged([(0.0, 1.0), (1.0, 2.0), (3.0, 4.0)]) == [(0.0, 2.0), (3.0, 4.0)]
    assert _merged([(0.0, 0.1), (5.0, 5.0 + TWO_PI - 0.5)]) == [(5.0, 5.0 + TWO_PI - 0.5)]  # one covers the other
    assert _merged([(0.0, 3.0), (3.0, TWO_PI)]) == [(0.0, TWO_PI)]
