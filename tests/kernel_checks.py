"""Shared check of generated compiled evaluators against their sympy family (tests/test_dgp_kernels.py,
tests/test_study_retrack.py)."""

import numpy as np


def assert_kernels_equal_family(fam, fj, fjt, rng, points: int):
    """At ``points`` random complex points and parameters: ``fjt`` gives the family's F, dF/dx and dF/dp . dp to
    1e-13 (relative), and ``fj`` the same F and J (the pattern of J is complete: a stale J is overwritten)."""
    for _ in range(points):
        x = rng.normal(size=fam.n) + 1j * rng.normal(size=fam.n)
        p = rng.normal(size=fam.m) + 1j * rng.normal(size=fam.m)
        dp = rng.normal(size=fam.m) + 1j * rng.normal(size=fam.m)
        F0, J0, JP0 = fam.evaluate_all(x[None], p)
        F = np.empty(fam.neq, complex)
        J = np.zeros((fam.neq, fam.n), complex)
        Ht = np.empty(fam.neq, complex)
        fjt(x, p, dp, F, J, Ht)
        scale = 1 + np.abs(F0).max() + np.abs(J0).max()
        assert np.abs(F - F0[0]).max() <= 1e-13 * scale
        assert np.abs(J - J0[0]).max() <= 1e-13 * scale
        assert np.abs(Ht - JP0[0] @ dp).max() <= 1e-13 * scale * (1 + np.abs(dp).max())
        F2 = np.empty(fam.neq, complex)
        J2 = J.copy()
        fj(x, p, F2, J2)
        assert np.array_equal(F2, F) and np.array_equal(J2, J)
