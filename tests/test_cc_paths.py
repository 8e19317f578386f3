"""First criterion along trajectories and surfaces (seed 002 Sec. II-B.2/3, IV-C).

Oracles: the circular arc x = cos t, y = sin t, z = 2, t in [0, pi/2] with CC [3,4,5,6,7,8] has index
0.532477175518869 (attained at the end point (1, 0, 2)); the planar circle of radius 0.4 centred at (1, 0, 2)
(t in [0, 2 pi], seeds README) has index 0.132477813874347 (cable 5) and 0.1606444664 for cable 6; the interior
values printed for the arc (|J| = 0: 3.0085, cable 7: 4.4942, truncated) and for the circle (cable 8: 4.6332).  Independent
checks: a surface's index against the pose radii on a grid (distance is 1-Lipschitz along the surface), crossings
against the tensions themselves.
"""

import numpy as np
import pytest

from cdpr_algebra import load_robot
from cdpr_algebra.cc.paths import crossings, parse_path, path_configurations, path_radii
from cdpr_algebra.cc.radii import cc_radii_many
from cdpr_algebra.cc.configurations import configuration_tensions
from cdpr_algebra.model.errors import CdprInputError

CC345678 = (2, 3, 4, 5, 6, 7)


@pytest.fixture(scope="module")
def robot():
    return load_robot("examples/seed002_8cables.toml")


def test_parse_kinds_and_points():
    spec = parse_path(["cos(t)", "sin(t)", "2"], [(0, np.pi / 2)])
    assert spec.kinds == ("angular",)
    np.testing.assert_allclose(spec.point(np.pi / 2), [0, 1, 2], atol=1e-15)
    spec = parse_path(["1 + 0.4*cos(2*t)", "sin(t)^2", "2"], [(0, 1)])  # sin/cos of multiples and ^ are fine
    assert spec.kinds == ("angular",)
    spec = parse_path(["u", "v", "2 + u*v"], [(0, 1), (-1, 1)], "--surface")
    assert spec.kinds == ("polynomial", "polynomial")
    spec = parse_path(["u*cos(v)", "u*sin(v)", "2 + u"], [(0, 1), (0, 3)], "--surface")  # a cone
    assert spec.kinds == ("polynomial", "angular")
    np.testing.assert_allclose(spec.point(0.5, np.pi / 2), [0, 0.5, 2.5], atol=1e-15)


@pytest.mark.parametrize("exprs,problem", [
    (["cos(t", "0", "2"], "cannot parse"),
    (["cos(t)", "x", "2"], "unknown symbol 'x'"),
    (["t*cos(t)", "0", "2"], "polynomials in t or in cos(t) and sin(t)"),
    (["exp(t)", "0", "2"], "polynomial"),
    (["1/t", "0", "2"], "polynomial"),
    (["", "0", "2"], "empty"),
])
def test_parse_errors_name_the_field(exprs, problem):
    """The library names its own field (the CLI passes its flag, tests/test_cc_cli.py)."""
    with pytest.raises(CdprInputError) as err:
        parse_path(exprs, [(0, 1)])
    assert err.value.field == "expressions" and problem in str(err.value)
    with pytest.raises(CdprInputError) as err:
        parse_path(exprs, [(0, 1)], option="--trajectory")
    assert err.value.field == "--trajectory"


def test_parse_range_errors():
    with pytest.raises(CdprInputError, match="LO < HI"):
        parse_path(["t", "0", "2"], [(1, 0)])


def test_crossings_of_a_segment_through_the_tension_zero_surface(robot):
    """The segment from (0,1,2) to 2 r_min away along the direction of the nearest point of {tau_3 = 0} (CC [1..6])
    crosses that surface at t = r_min; the tensions computed directly change sign there."""
    (res,) = cc_radii_many(robot, [((0, 1, 2), (0, 1, 2, 3, 4, 5))])
    u = (res.nearest - np.array([0, 1, 2])) / res.rmin
    exprs = [f"{0 + u[0]}*t", f"1 + {u[1]}*t", f"2 + {u[2]}*t"]
    spec = parse_path(exprs, [(0, 2 * res.rmin)])
    cr = crossings(robot, spec, (0, 1, 2, 3, 4, 5))
    ts = [v[0] for name, v in cr if name == 2]
    assert ts and min(ts) == pytest.approx(res.rmin, rel=1e-7)
    before = configuration_tensions(robot, spec.point(0.999 * res.rmin), (0, 1, 2, 3, 4, 5))
    after = configuration_tensions(robot, spec.point(1.001 * res.rmin), (0, 1, 2, 3, 4, 5))
    assert before.valid and not after.valid and after.tensions[2] < 0
    pr = path_radii(robot, spec, (0, 1, 2, 3, 4, 5))
    assert not pr.valid and pr.index == 0.0


@pytest.mark.slow
def test_seed002_circular_arc(robot):
    spec = parse_path(["cos(t)", "sin(t)", "2"], [(0, np.pi / 2)])
    (res,) = path_configurations(robot, spec)  # only [3,4,5,6,7,8] is valid over the whole arc
    assert res.cables == CC345678 and res.valid and res.failed_paths == 0
    assert res.index == pytest.approx(0.532477175518869, rel=1e-9)
    assert res.limiting == 4 and res.where["source"] == "end point"
    np.testing.assert_allclose(res.where["path_point"], [1, 0, 2], atol=1e-12)
    # interior minima printed with 4 decimals (truncated: 3.00856 is printed 3.0085)
    assert 3.0085 <= res.singular < 3.0086
    assert 4.4942 <= res.radii[6] < 4.4943


@pytest.mark.slow
def test_seed002_planar_circle(robot):
    spec = parse_path(["1 + 0.4*cos(t)", "0.4*sin(t)", "2"], [(0, 2 * np.pi)])
    res = path_radii(robot, spec, CC345678)
    assert res.valid and res.failed_paths == 0
    assert res.index == pytest.approx(0.132477813874347, rel=1e-9)
    assert res.limiting == 4 and res.where["source"] == "interior"
    assert res.radii[5] == pytest.approx(0.1606444664, abs=5e-11)
    assert 4.6332 <= res.radii[7] < 4.6333
    # the nearest point is on the circle and at the index from the surface point
    p, q = res.where["path_point"], res.where["surface_point"]
    assert np.linalg.norm(p - [1, 0, 2]) == pytest.approx(0.4, rel=1e-12)
    assert np.linalg.norm(p - q) == pytest.approx(res.index, rel=1e-9)


@pytest.mark.slow
def test_surface_patch_against_pose_radii(robot):
    """Planar patch [0.9, 1.1] x [-0.1, 0.1] at z = 2: the index is the minimum of the pose radius over the patch;
    on a 5 x 5 grid the pose radii are >= the index and, the radius being 1-Lipschitz, within the grid spacing."""
    spec = parse_path(["u", "v", "2"], [(0.9, 1.1), (-0.1, 0.1)], "--surface")
    res = path_radii(robot, spec, CC345678)
    assert res.valid and res.failed_paths == 0
    grid = [(a, b, 2.0) for a in np.linspace(0.9, 1.1, 5) for b in np.linspace(-0.1, 0.1, 5)]
    radii = np.array([r.rmin for r in cc_radii_many(robot, [(g, CC345678) for g in grid])])
    assert radii.min() >= res.index * (1 - 1e-9)
    assert radii.min() - res.index <= 0.05 * np.sqrt(2) / 2 + 1e-12
