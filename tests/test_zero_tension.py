"""Exact zero tensions of the IGP with assigned position (certificates.zero_tension): the three-force plane.

Independent check: the 2-cable equilibria with the platform in the plane through A_1, A_2, G and the load are the
zeros of one function of the turning angle (the force rows are linear in the two multipliers), found here by a scan
and bisection; they must be exactly the IGP's real roots whose tau_3 is proven 0, pose for pose."""

import numpy as np
import pytest
from scipy.optimize import brentq

from cdpr_algebra.certificates.zero_tension import prove_zero_tension, three_force_plane
from cdpr_algebra.cli.main import main
from cdpr_algebra.igp.position import igp_position
from cdpr_algebra.model.robot import Robot

# A_1, A_2, G and the load direction (0, 0, 1) span the vertical plane 4 x - 3 y = 0; A_3 and the platform are
# generic (every number is a double exactly)
BASE = [[0.0, 0, 0], [6, 8, 2], [-2, 9, 1]]
PLATFORM = [[-2, 0.5, -1], [2.5, -0.25, -1.5], [0.5, 2, -0.5]]
COM = [0.25, 0.125, 0.5]
G = np.array([1.5, 2.0, 6.0])


def _robot():
    return Robot(BASE, PLATFORM, COM, 10.0, [0, 0, 1], [10.0, 10.0, 10.0], name="slanted_plane")


def _planar_rotations(robot, G):
    """Rotations of the 2-cable (cables 1, 2) equilibria with the platform plane (b_1, b_2, g') on the plane through
    A_1, A_2, G and the load: roots of the moment about the normal after solving the force rows for the two
    multipliers, by a scan over the turning angle and brentq (both orientations of the plane)."""
    A = np.array(robot.base[:2], float) - G
    B = np.array(robot.platform[:2], float) - np.array(robot.com, float)
    d = np.array(robot.load_direction, float)
    f = robot.load * d
    e1, e3 = d / np.linalg.norm(d), np.cross(A[1] - A[0], d)
    e3 /= np.linalg.norm(e3)
    W = np.column_stack([e1, np.cross(e3, e1), e3])
    f3 = np.cross(B[0], B[1])
    f3 /= np.linalg.norm(f3)
    f1 = B[0] / np.linalg.norm(B[0])
    F = np.column_stack([f1, np.cross(f3, f1), f3])
    out = []
    for flip in (np.eye(3), np.diag([1.0, -1.0, -1.0])):
        def rotation(t):
            c, s = np.cos(t), np.sin(t)
            return W @ np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]]) @ flip @ F.T

        def moment(t):
            Bw = (rotation(t) @ B.T).T
            lam = np.linalg.lstsq(np.column_stack([A[0] - Bw[0], A[1] - Bw[1]]), -f, rcond=None)[0]
            return float(np.dot(sum(l * np.cross(b, a) for l, a, b in zip(lam, A, Bw)), e3))

        ts = np.linspace(0.0, 2 * np.pi, 4001)
        ms = np.array([moment(t) for t in ts])
        for k in np.flatnonzero((np.sign(ms[:-1]) != np.sign(ms[1:])) & (np.abs(ms[:-1]) + np.abs(ms[1:]) < 1e3)):
            out.append(rotation(brentq(moment, ts[k], ts[k + 1], xtol=1e-14)))
    return out


def test_planar_equilibria_are_the_proven_zero_tension_roots():
    robot = _robot()
    res = igp_position(robot, G)
    zero = [s for s in res.real_solutions if s.certificate.tension_signs[2] == "zero"]
    planar = _planar_rotations(robot, G)
    assert len(planar) == 4 and len(zero) == len(planar)
    for R in planar:  # each planar equilibrium is one of them, pose for pose
        assert min(np.max(np.abs(s.rotation - R)) for s in zero) < 1e-9
    for s in zero:
        c = s.certificate
        assert s.certified and c.reason is None and s.tensions[2] == 0
        assert all(g in ("positive", "negative") for g in c.tension_signs[:2])
        z = c.extra["zero_tension"]
        assert z["cable"] == 3 and z["holding"] == [1, 2] and "cables 1, 2" in z["proof"]
        assert z["hessian_of_the_others"] in (">", "<", "<>")
    # the other real roots (if any) keep their proven signs
    assert all(s.certificate.tension_signs[2] in ("positive", "negative") for s in res.real_solutions
               if all(s is not z for z in zero))


def test_off_the_plane_nothing_is_zero():
    """G 1e-6 off the plane: no three-force plane, and every tau_3 is small but of a proven sign."""
    robot = _robot()
    G1 = G + np.array([4.0, -3.0, 0.0]) * 2.0 ** -20
    assert three_force_plane(robot, G1, 2) is None and three_force_plane(robot, G, 2) is not None
    res = igp_position(robot, G1)
    assert len(res.real_solutions) == 4
    for s in res.real_solutions:
        assert s.certified and s.certificate.tension_signs[2] in ("positive", "negative")
        assert 0 < abs(s.tensions[2]) < 1e-4


@pytest.mark.parametrize("what", ["rotation", "cable"])
def test_no_proof_away_from_the_root(what):
    """The proof fails (None) for a pose 1e-6 off the root, and for the wrong cable (no plane through A_2, A_3)."""
    robot = _robot()
    s = next(s for s in igp_position(robot, G).real_solutions if s.certificate.tension_signs[2] == "zero")
    args = [robot, G, s.rotation, s.tensions, s.lengths, 2]
    proof = prove_zero_tension(*args)
    assert proof is not None and proof.cable == 3 and proof.holding == (1, 2)
    if what == "rotation":
        t = 1e-6
        args[2] = s.rotation @ np.array([[np.cos(t), -np.sin(t), 0], [np.sin(t), np.cos(t), 0], [0, 0, 1]])
    else:
        args[5] = 0
    assert prove_zero_tension(*args) is None


def test_cli_table4_exits_zero(capsys):
    status = main(["igp", "examples/seed004_table4.toml", "--position", "5", "0", "6"])
    out = capsys.readouterr().out
    assert status == 0 and out.count("tau_3 = 0 exactly") == 4 and "4 certified" in out
