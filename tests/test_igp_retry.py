"""IGP roots that double-precision interval arithmetic cannot prove (large robots, far positions): the 128-bit retry
with Newton steps in ball arithmetic, and the polished root (certificates.equilibria._retry_with_polish)."""

import numpy as np
import pytest

from cdpr_algebra.igp.orientation import igp_orientation
from cdpr_algebra.igp.position import igp_position
from cdpr_algebra.model.pose import rot_x, rot_y, rot_z
from cdpr_algebra.model.robot import Robot, load_robot


def _scaled(table, base_scale=1.0):
    r = load_robot(f"examples/seed004_table{table}.toml")
    return Robot(np.array(r.base) * base_scale, r.platform, r.com, r.load, r.load_direction, None)


def _inside(lo, hi, v, rtol=0.0):
    v = np.asarray(v, float)
    pad = rtol * np.maximum(1.0, np.abs(v))
    return bool(np.all((np.asarray(lo) - pad <= v) & (v <= np.asarray(hi) + pad)))


@pytest.mark.parametrize("case", ["base_1e4", "far_G"])
def test_ill_conditioned_igp_roots_are_proven_at_128_bits(case):
    """Seed 004 Table 3's robot with its base scaled by 1e4 (scaled condition ~6e17: 3 of 4 real roots unproven in
    double precision), and with G at (2e5, 3e5, 1e5) (its real roots 2e-9 .. 7e-9 off their zeros as doubles
    give them): every real root is proven at 128 bits, the far ones at the polished root, which is reported."""
    robot = _scaled(3, 1e4 if case == "base_1e4" else 1.0)
    G = np.array([7.0, 9.0, 1.0]) * 1e4 if case == "base_1e4" else np.array([2e5, 3e5, 1e5])
    res = igp_position(robot, G)
    real = res.real_solutions
    assert len(real) == 4 and all(s.certified for s in real), [s.certificate.reason for s in real]
    retried = [s for s in real if s.certificate.extra.get("precision_bits") == 128]
    assert retried and (case == "far_G") == all("polished" in s.certificate.extra for s in retried)
    for s in real:  # the reported root (the polished one where polished) is within the box tolerance of the zero
        c = s.certificate
        assert _inside(c.rotation_lower, c.rotation_upper, s.rotation, 1e-9)
        assert _inside(c.tension_lower, c.tension_upper, s.tensions, 1e-8)
        assert s.euler_parameters[0] == 1 and s.residual < 1e-6


def test_the_retry_does_not_prove_a_point_that_is_not_a_root():
    from cdpr_algebra.certificates.equilibria import _igp_position_retry

    robot = _scaled(3)
    G = np.array([2e5, 3e5, 1e5])
    s = igp_position(robot, G).real_solutions[0]
    y0 = np.concatenate([s.rotation.T.ravel(), s.tensions / s.lengths])
    assert _igp_position_retry(robot, G, y0, 1e-9) is not None
    assert _igp_position_retry(robot, G, y0 * (1 + 1e-2), 1e-9) is None


@pytest.mark.parametrize("table,k", [(1, 1e4), (2, 1e3)])
def test_ill_conditioned_assigned_orientation_root_is_proven_at_128_bits(table, k):
    """Tables 1 and 2's robots with their bases scaled by 1e4 and 1e3, turned by (0.3, -0.2, 0.5): the one root
    is not proven in double precision (before the retry: 'Krawczyk test not satisfied', 'Newton step'), it is at
    128 bits; the reported G is inside the proven position enclosure (moved by the platform's centre)."""
    robot = _scaled(table, k)
    R = rot_z(0.5) @ rot_y(-0.2) @ rot_x(0.3)
    (s,) = igp_orientation(robot, R).solutions
    c = s.certificate
    assert s.certified and c.extra.get("precision_bits") == 128, c.reason
    assert _inside(c.position_lower, c.position_upper, s.position, 1e-9)
    assert _inside(c.tension_lower, c.tension_upper, s.tensions, 1e-8) and s.residual < 1e-6
