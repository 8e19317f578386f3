"""The numerical local dimension test (cdpr_algebra.homotopy.local_dimension) on systems whose solution sets are
known exactly: reduced components of dimension 1 and 2, a regular root, an isolated singular root and a
non-reduced component (both undecided)."""

import numpy as np

from cdpr_algebra.homotopy.local_dimension import local_dimension


def _circle_system(x):
    """x^2 + y^2 = 1, z = 1 and a combination of the two: a reduced circle (dimension 1) in C^3."""
    c = x[0] ** 2 + x[1] ** 2 - 1
    F = np.array([c, x[2] - 1, 2 * c + 3 * (x[2] - 1)])
    J = np.array([[2 * x[0], 2 * x[1], 0], [0, 0, 1], [4 * x[0], 4 * x[1], 3]])
    return F, J


def _sphere_system(x):
    """x^2 + y^2 + z^2 = 1 three times over: a reduced sphere (dimension 2)."""
    c = x @ x - 1
    F = np.array([c, 2 * c, -c])
    J = np.array([2 * x, 4 * x, -2 * x])
    return F, J


def test_points_on_reduced_components_have_their_dimension():
    a = 0.3 + 0.7j  # a complex point of the circle
    x = np.array([a, np.sqrt(1 - a * a), 1.0]) * (1 + 1e-9)  # slightly off, as an endpoint would be
    r = local_dimension(_circle_system, x)
    assert (r.verdict, r.dimension) == ("positive_dimensional", 1)
    F, _ = _circle_system(r.point)
    assert np.max(np.abs(F)) < 1e-13
    # the tangent is the circle's: orthogonal to the gradient of x^2 + y^2 and to z
    t = r.tangent[:, 0]
    assert abs(2 * r.point[0] * t[0] + 2 * r.point[1] * t[1]) < 1e-12 and abs(t[2]) < 1e-12
    v = np.array([0.2 - 0.1j, 0.5 + 0.3j, 0.0])
    v[2] = np.sqrt(1 - v[0] ** 2 - v[1] ** 2)
    s = local_dimension(_sphere_system, v)
    assert (s.verdict, s.dimension) == ("positive_dimensional", 2)


def test_regular_roots_are_regular_and_singular_ones_undecided():
    def regular(x):  # x^2 = 4, x y = 1: four regular roots
        return np.array([x[0] ** 2 - 4, x[0] * x[1] - 1]), np.array([[2 * x[0], 0], [x[1], x[0]]])

    r = local_dimension(regular, np.array([2.0, 0.5]))
    assert (r.verdict, r.dimension) == ("regular", 0)

    def double(x):  # x^2 = 0, y = x: an isolated double root at the origin
        return np.array([x[0] ** 2, x[1] - x[0]]), np.array([[2 * x[0], 0], [-1, 1]])

    d = local_dimension(double, np.array([1e-9, 1e-9]))
    assert d.verdict == "undecided" and d.dimension is None
    assert d.residuals[-1] > 1e-8  # the projection stalls at ~eps^2

    def non_reduced(x):  # (x^2 + y^2 - 1)^2 = 0, z = 1 twice: the circle with multiplicity 2
        c = x[0] ** 2 + x[1] ** 2 - 1
        F = np.array([c * c, x[2] - 1, x[2] - 1])
        J = np.array([[4 * c * x[0], 4 * c * x[1], 0], [0, 0, 1], [0, 0, 1]])
        return F, J

    a = 0.3 + 0.7j
    u = local_dimension(non_reduced, np.array([a, np.sqrt(1 - a * a), 1.0]))
    assert u.verdict == "undecided"  # never "regular", never a dimension it has not shown


def test_a_point_that_is_no_root_is_undecided():
    def no_root_near(x):  # x^2 + 1 = 0, y = 0 from a real start: Gauss-Newton in complex arithmetic stays real
        return np.array([x[0] ** 2 + 1, x[1]]), np.array([[2 * x[0], 0], [0, 1]])

    r = local_dimension(no_root_near, np.array([0.3, 0.0]))
    assert r.verdict == "undecided" and r.residuals[0] > 1e-3
