"""The taut-set equations of :mod:`cdpr_algebra.model.taut_equations` as the homotopy engine's system, with the
compiled evaluators generated from them (:class:`FastTautSystem`, one per m: :func:`fast_family`)."""

from __future__ import annotations

import numpy as np

from cdpr_algebra.model.taut_equations import taut_family

__all__ = ["LazyFamilySystem", "QuadraticInParameters", "FastTautSystem", "fast_family"]


class LazyFamilySystem:
    """A system whose numeric evaluators are compiled code and whose sympy family (name, hash, equations, mpmath
    evaluators) is built only when something asks for it (``family_builder(m)``: building one takes ~0.25 s per m,
    and tracking does not need it)."""

    kernel_constants = None  # no constants beyond the parameters (answered here: asking the family builds it)
    family_builder = None

    def __init__(self, m: int):
        self._family = None
        self.mm = m

    @property
    def family(self):
        if self._family is None:
            self._family = type(self).family_builder(self.mm)
        return self._family

    def __getattr__(self, name):
        if name.startswith("__") or name == "_family":
            raise AttributeError(name)
        return getattr(self.family, name)


class QuadraticInParameters:
    """``evaluate_directional`` for a system whose equations all have degree <= 2 in the parameters: the central
    difference (F(x; p + dp) - F(x; p - dp)) / 2 is then the derivative of F along dp exactly (up to rounding), and
    cheaper than dF/dp.  For a class that has ``evaluate`` and ``evaluate_and_jacobian``."""

    def evaluate_directional(self, x, p, dp):
        F, J = self.evaluate_and_jacobian(x, p)
        p, dp = np.asarray(p, dtype=complex), np.asarray(dp, dtype=complex)
        return F, J, 0.5 * (self.evaluate(x, p + dp) - self.evaluate(x, p - dp))


class FastTautSystem(QuadraticInParameters, LazyFamilySystem):
    """:func:`cdpr_algebra.model.taut_equations.taut_family` (m) with compiled evaluators of F, dF/dx, dF/dp generated
    from it (``derivations/derive_taut_equations.py``; checked against the sympy family's own evaluators in
    tests/test_dgp.py).
    Everything else (name, hash, equations, mpmath evaluators, used by the projective retries) is the
    sympy family's."""

    family_builder = staticmethod(taut_family)

    def __init__(self, m: int):
        super().__init__(m)
        self.n = 12 + m  # p, u, v, w, lam
        self.m = 7 * m + 6  # A_i, rho_i^2, b'_i, g', Q d
        self.neq = 12 + m

    @property
    def degrees(self) -> tuple:
        """Every equation has degree 2 in x (as the sympy family says; tests/test_dgp_kernels.py checks it)."""
        return (2,) * self.neq

    def compiled_kernels(self):
        """Numba evaluators and structured linear solve for the compiled tracker (:mod:`cdpr_algebra.dgp.kernels`)."""
        from .kernels import taut_apply, taut_factor, taut_fj, taut_fjt

        return taut_fj, taut_fjt, taut_factor, taut_apply

    def compiled_residual_dd(self):
        """The residual in double-double (:mod:`cdpr_algebra.generated.taut_residual_dd`) for the compiled tracker's
        extended-precision Newton."""
        from cdpr_algebra.generated.taut_residual_dd import taut_residual

        return taut_residual

    def chart_kernels(self):
        """LU factor and apply of the Jacobian of this system homogenized on a chart (the projective retries and
        endgame; :func:`cdpr_algebra.dgp.kernels.chart_factor`)."""
        from .kernels import chart_apply, chart_factor

        return chart_factor, chart_apply

    def _eval(self, x, p, jac: bool, jacp: bool):
        """F, dF/dx (``jac``), dF/dp (``jacp``) at the rows of x: the generated evaluators of
        :mod:`cdpr_algebra.generated.taut_equations`, compiled and looped over the rows (:mod:`.kernels`)."""
        from .kernels import taut_fj_batch, taut_jp_batch

        x = np.asarray(x, dtype=complex)
        if x.ndim == 1:
            x = x[None, :]
        N = len(x)
        X = np.array(x, order="C")
        # writable copies: a read-only array (a broadcast view) would compile the kernels a second time
        P = np.array(np.broadcast_to(np.asarray(p, dtype=complex), (N, self.m)), order="C")
        F = np.empty((N, self.neq), dtype=complex)
        J = np.zeros((N if jac else 1, self.neq, self.n), dtype=complex)
        taut_fj_batch(X, P, F, J, jac)
        if not jacp:
            return F, (J if jac else None), None
        JP = np.zeros((N, self.neq, self.m), dtype=complex)
        taut_jp_batch(X, P, JP)
        return F, J, JP

    def evaluate(self, x, p=None):
        return self._eval(x, p, False, False)[0]

    def evaluate_and_jacobian(self, x, p=None):
        F, J, _ = self._eval(x, p, True, False)
        return F, J

    def evaluate_all(self, x, p=None):
        return self._eval(x, p, True, True)


_FAST: dict = {}


def fast_family(m: int) -> FastTautSystem:
    if m not in _FAST:
        _FAST[m] = FastTautSystem(m)
    return _FAST[m]
