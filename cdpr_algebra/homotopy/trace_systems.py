"""The systems of the trace test (:mod:`.trace_test`): the curve C = {(x, s) : F(x; p0 + s v) = 0} cut by a
hyperplane l(x) = 0 (:class:`TraceSliceSystem`, parameters l) or by a member s l(x) = tau of the pencil
(:class:`TracePencilSystem`, parameter tau), the same pencil on a chart of projective space
(:class:`ChartPencilSystem`), and the maps of witness sets between affine coordinates and a chart
(:func:`coordinate_chart`, :func:`slice_to_chart`, :func:`slice_from_chart`).  Evaluators follow
:class:`.systems.PolynomialSystem` (``evaluate``, ``evaluate_and_jacobian``, ``evaluate_all``,
``evaluate_directional``, ``mp_functions``)."""

from __future__ import annotations

import numpy as np

__all__ = ["TraceSliceSystem", "TracePencilSystem", "ChartPencilSystem", "chart_coordinates", "chart_form",
           "curve_to_chart", "curve_from_chart", "coordinate_chart", "slice_to_chart", "slice_from_chart"]


def _crandn(rng, *shape):
    return (rng.normal(size=shape) + 1j * rng.normal(size=shape)) / np.sqrt(2.0)


class _CurveSystem:
    """F(x; p0 + s v) in the unknowns y = (x, s): values, Jacobian d/d(x, s) (dF/ds = dF/dp . v)."""

    def __init__(self, system, p0, v):
        if system.neq != system.n:
            raise ValueError("the trace test needs a square family (as many equations as unknowns)")
        self.base = system
        self.p0 = np.asarray(p0, dtype=complex)
        self.v = np.asarray(v, dtype=complex)
        if self.p0.shape != (system.m,) or self.v.shape != (system.m,):
            raise ValueError(f"expected {system.m} parameters")
        self.nx = system.n

    def _split(self, y):
        y = np.asarray(y, dtype=complex)
        if y.ndim == 1:
            y = y[None, :]
        x = np.ascontiguousarray(y[:, :self.nx])
        s = y[:, self.nx]
        return y, x, s, self.p0[None, :] + s[:, None] * self.v[None, :]

    def _curve(self, y, jac: bool):
        y, x, s, p = self._split(y)
        if not jac:
            return y, x, s, self.base.evaluate(x, p), None
        directional = getattr(self.base, "evaluate_directional", None)
        if directional is not None:  # F, dF/dx and dF/dp . v without the full dF/dp
            F, J, Fs = directional(x, p, self.v)
        else:
            F, J, JP = self.base.evaluate_all(x, p)
            Fs = np.einsum("nik,k->ni", JP, self.v)
        N = len(y)
        Jy = np.empty((N, self.nx, self.nx + 1), dtype=complex)
        Jy[:, :, :self.nx] = J
        Jy[:, :, self.nx] = Fs
        return y, x, s, F, Jy

    def _mp_curve(self):
        """mpmath evaluators of the curve: (F(y), J(y)) from the base system's ``mp_functions``."""
        import mpmath

        fF, fJ, fP = self.base.mp_functions()
        p0 = [mpmath.mpc(complex(c)) for c in self.p0]
        v = [mpmath.mpc(complex(c)) for c in self.v]
        nx = self.nx

        def curve(y):
            x = [y[i] for i in range(nx)]
            s = y[nx]
            p = [a + s * b for a, b in zip(p0, v)]
            F = fF(x, p)
            J, JP = fJ(x, p), fP(x, p)
            Jy = mpmath.matrix(nx, nx + 1)
            for i in range(nx):
                for j in range(nx):
                    Jy[i, j] = J[i, j]
                Jy[i, nx] = mpmath.fsum(JP[i, k] * v[k] for k in range(len(v)))
            return F, Jy

        return curve


def _bordered(Jc, nx):
    """An (nx + 1) x (nx + 1) mpmath matrix whose first nx rows are the curve's Jacobian Jc (the last row is the
    caller's: the slice or the pencil)."""
    import mpmath

    J = mpmath.matrix(nx + 1, nx + 1)
    for i in range(nx):
        for j in range(nx + 1):
            J[i, j] = Jc[i, j]
    return J


class TraceSliceSystem(_CurveSystem):
    """[F(x; p0 + s v); l . (x, 1)] in the unknowns (x, s) (n + 1), parameters l (n + 1): C cut by l(x) = 0.

    Evaluators follow :class:`.systems.PolynomialSystem` (``evaluate``, ``evaluate_and_jacobian``,
    ``evaluate_all`` with dG/dl, ``evaluate_directional``, ``mp_functions``)."""

    def __init__(self, system, p0, v, coordinates=None):
        super().__init__(system, p0, v)
        self.coords = np.arange(self.nx) if coordinates is None else np.asarray(coordinates, dtype=int)
        self.n = self.nx + 1
        self.neq = self.nx + 1
        self.m = len(self.coords) + 1
        self.name = f"trace_slice({getattr(system, 'name', 'system')})"

    def _affine(self, x):
        return np.concatenate([x[:, self.coords], np.ones((len(x), 1), dtype=complex)], axis=1)

    def _lin(self, x, l):
        l = np.asarray(l, dtype=complex)
        return np.einsum("nk,nk->n", self._affine(x), np.broadcast_to(l, (len(x), self.m)))

    def evaluate(self, y, l=None):
        y, x, s, F, _ = self._curve(y, False)
        return np.concatenate([F, self._lin(x, l)[:, None]], axis=1)

    def evaluate_and_jacobian(self, y, l=None):
        y, x, s, F, Jc = self._curve(y, True)
        N = len(y)
        l = np.broadcast_to(np.asarray(l, dtype=complex), (N, self.m))
        G = np.concatenate([F, self._lin(x, l)[:, None]], axis=1)
        J = np.zeros((N, self.neq, self.n), dtype=complex)
        J[:, :self.nx, :] = Jc
        J[:, self.nx, self.coords] = l[:, :-1]
        return G, J

    def evaluate_all(self, y, l=None):
        G, J = self.evaluate_and_jacobian(y, l)
        y = np.atleast_2d(np.asarray(y, dtype=complex))
        JP = np.zeros((len(y), self.neq, self.m), dtype=complex)
        JP[:, self.nx, :] = self._affine(y[:, :self.nx])
        return G, J, JP

    def evaluate_directional(self, y, l, dl):
        G, J = self.evaluate_and_jacobian(y, l)
        y = np.atleast_2d(np.asarray(y, dtype=complex))
        Gt = np.zeros_like(G)
        Gt[:, self.nx] = np.einsum("nk,nk->n", self._affine(y[:, :self.nx]),
                                   np.broadcast_to(np.asarray(dl, dtype=complex), (len(y), self.m)))
        return G, J, Gt

    def mp_functions(self):
        import mpmath

        curve = self._mp_curve()
        nx = self.nx
        cs = [int(c) for c in self.coords]
        k = len(cs)

        def mF(y, l):
            F, _ = curve(y)
            return mpmath.matrix(list(F) + [mpmath.fsum(l[j] * y[c] for j, c in enumerate(cs)) + l[k]])

        def mJ(y, l):
            J = _bordered(curve(y)[1], nx)
            for j, c in enumerate(cs):
                J[nx, c] = l[j]
            return J

        def mP(y, l):
            JP = mpmath.matrix(nx + 1, k + 1)
            for j, c in enumerate(cs):
                JP[nx, j] = y[c]
            JP[nx, k] = 1
            return JP

        return mF, mJ, mP


class TracePencilSystem(_CurveSystem):
    """[F(x; p0 + s v); s l . (x, 1) - tau] in the unknowns (x, s), one parameter tau: C cut by the pencil member
    s l(x) = tau; tau = 0 is the union (W01 x {0}) + W10.  (Subclasses weight tau by an unknown, ``_tau_column``.)"""

    _tau_column = None  # tau multiplies this unknown (None: 1)

    def __init__(self, system, p0, v, l, coordinates=None):
        super().__init__(system, p0, v)
        self.coords = np.arange(self.nx) if coordinates is None else np.asarray(coordinates, dtype=int)
        self.l = np.asarray(l, dtype=complex)
        if self.l.shape != (len(self.coords) + 1,):
            raise ValueError(f"expected {len(self.coords) + 1} coefficients of l")
        self.n = self.nx + 1
        self.neq = self.nx + 1
        self.m = 1
        self.name = f"trace_pencil({getattr(system, 'name', 'system')})"

    def _tau(self, tau, N):
        tau = np.asarray(tau, dtype=complex)
        return np.broadcast_to(tau.reshape(-1) if tau.ndim <= 1 else tau[:, 0], (N,))

    def _weight(self, y):
        """The factor of tau in the pencil equation at the rows of y."""
        y = np.atleast_2d(y)
        return np.ones(len(y), dtype=complex) if self._tau_column is None else y[:, self._tau_column]

    def _member(self, x, s, tau):
        return s * (x[:, self.coords] @ self.l[:-1] + self.l[-1]) - self._tau(tau, len(x)) * self._weight(x)

    def evaluate(self, y, tau=None):
        y, x, s, F, _ = self._curve(y, False)
        return np.concatenate([F, self._member(x, s, tau)[:, None]], axis=1)

    def evaluate_and_jacobian(self, y, tau=None):
        y, x, s, F, Jc = self._curve(y, True)
        N = len(y)
        G = np.concatenate([F, self._member(x, s, tau)[:, None]], axis=1)
        J = np.zeros((N, self.neq, self.n), dtype=complex)
        J[:, :self.nx, :] = Jc
        J[:, self.nx, self.coords] = s[:, None] * self.l[None, :-1]
        if self._tau_column is not None:
            J[:, self.nx, self._tau_column] -= self._tau(tau, N)
        J[:, self.nx, self.nx] = x[:, self.coords] @ self.l[:-1] + self.l[-1]
        return G, J

    def evaluate_all(self, y, tau=None):
        G, J = self.evaluate_and_jacobian(y, tau)
        JP = np.zeros((len(G), self.neq, 1), dtype=complex)
        JP[:, self.nx, 0] = -self._weight(y)
        return G, J, JP

    def evaluate_directional(self, y, tau, dtau):
        G, J = self.evaluate_and_jacobian(y, tau)
        Gt = np.zeros_like(G)
        Gt[:, self.nx] = -self._tau(dtau, len(G)) * self._weight(y)
        return G, J, Gt

    def mp_functions(self):
        import mpmath

        curve = self._mp_curve()
        nx = self.nx
        l = [mpmath.mpc(complex(c)) for c in self.l]
        cs = [int(c) for c in self.coords]
        col = self._tau_column

        def lin(y):
            return mpmath.fsum(l[j] * y[c] for j, c in enumerate(cs)) + l[-1]

        def weight(y):
            return 1 if col is None else y[col]

        def mF(y, tau):
            F, _ = curve(y)
            return mpmath.matrix(list(F) + [y[nx] * lin(y) - tau[0] * weight(y)])

        def mJ(y, tau):
            J = _bordered(curve(y)[1], nx)
            for j, c in enumerate(cs):
                J[nx, c] = y[nx] * l[j]
            if col is not None:
                J[nx, col] -= tau[0]
            J[nx, nx] = lin(y)
            return J

        def mP(y, tau):
            JP = mpmath.matrix(nx + 1, 1)
            JP[nx, 0] = -weight(y)
            return JP

        return mF, mJ, mP


class ChartPencilSystem(TracePencilSystem):
    """The pencil of :class:`TracePencilSystem` on a chart of projective space: [F_h(Y; p0 + s v); s l_h(Y) - tau
    y0] in the unknowns (Y, s) of a homogenized system ``hom`` (:class:`.projective.HomogenizedQuadratic`: Y = (y0,
    y), chart c . Y = 1), l_h(Y) = l_1 y_c1 + ... + l_k y_ck + l_{k+1} y0 the homogenization of the affine form l of
    the ``coordinates`` c1..ck of x.  Where y0 != 0 it is the affine pencil s l(x) = tau at x = y / y0: the same
    points, so a path that is lost in affine coordinates (one of very large norm) can be tracked here and its
    endpoint mapped back (:func:`.projective.from_chart`)."""

    _tau_column = 0

    def __init__(self, hom, p0, v, l, coordinates=None):
        cs = np.arange(hom.n - 1) if coordinates is None else np.asarray(coordinates, dtype=int)
        l = np.asarray(l, dtype=complex)
        if l.shape != (len(cs) + 1,):
            raise ValueError(f"expected {len(cs) + 1} coefficients of l")
        super().__init__(hom, p0, v, chart_form(l), chart_coordinates(cs))
        self.name = f"trace_pencil_chart({getattr(hom, 'name', 'system')})"


def chart_coordinates(coordinates) -> np.ndarray:
    """Indices in chart unknowns Y = (y0, y) of y0 and of the given ``coordinates`` of x."""
    return np.concatenate([[0], 1 + np.asarray(coordinates, dtype=int)])


def chart_form(l) -> np.ndarray:
    """An affine form l = (l_1..l_k, constant) on x_coordinates as a form on Y at :func:`chart_coordinates`: its
    homogenization (constant, l_1..l_k) on (y0, y_coordinates), with constant term 0."""
    l = np.asarray(l, dtype=complex)
    return np.concatenate([[l[-1]], l[:-1], [0.0]])


def coordinate_chart(n: int, coordinates, seed: int) -> np.ndarray:
    """Coefficients c (n + 1) of a chart c . (y0, y) = 1 of projective space that are random complex on y0 and on
    the ``coordinates`` of y and zero on the other unknowns.  With it, a hyperplane of the chart coordinates
    (y0, y_coordinates) with a constant term (constant = constant x c . Y) is still a hyperplane of the affine
    coordinates x_coordinates: the W10 of the trace test in such a chart is the W10 of an affine hyperplane
    (:func:`slice_from_chart`).  (A chart that mixes in the other unknowns, e.g. tensions with poles along the
    curve, changes the curve that the hyperplanes cut: DGP m = 4, over 2700 points and growing, against 1888.)"""
    rng = np.random.default_rng(seed)
    c = np.zeros(n + 1, dtype=complex)
    idx = chart_coordinates(coordinates)
    c[idx] = _crandn(rng, len(idx))
    return c / np.linalg.norm(c)


def curve_to_chart(Y, c) -> np.ndarray:
    """Points (x, s) of the curve -> (Y, s) on the chart c (:func:`.projective.to_chart` of x, s kept)."""
    from .projective import to_chart

    Y = np.asarray(Y, dtype=complex)
    return np.concatenate([to_chart(Y[:, :-1], c), Y[:, -1:]], axis=1)


def curve_from_chart(Yc) -> tuple[np.ndarray, np.ndarray]:
    """Inverse of :func:`curve_to_chart`: ((x, s) rows, |y0| / |y| per row, 0 at infinity)."""
    from .projective import from_chart

    Yc = np.asarray(Yc, dtype=complex)
    x, ratio = from_chart(Yc[:, :-1])
    return np.concatenate([x, Yc[:, -1:]], axis=1), ratio


def slice_to_chart(W10, l, c):
    """Points (x, s) of the affine slice l(x_coordinates) = 0 -> (points (Y, s) on the chart c, the same hyperplane
    as a form on (y0, y_coordinates) plus constant 0, :func:`chart_form`)."""
    return curve_to_chart(W10, c), chart_form(l)


def slice_from_chart(Wc, lc, c, coordinates):
    """Inverse of :func:`slice_to_chart` for a chart of :func:`coordinate_chart`: points (Y, s) of the slice
    lc . (y0, y_coordinates, 1) = 0 -> (points (x, s), the affine form l on x_coordinates).  On the chart the
    constant is constant x c . Y, and c is zero off (y0, y_coordinates), so the slice is the affine hyperplane
    (lc_0 + k c_0) + sum_j (lc_j + k c_j) x_j = 0 (k the constant)."""
    idx = chart_coordinates(coordinates)
    c = np.asarray(c, dtype=complex)
    off = np.setdiff1d(np.arange(len(c)), idx)
    if np.any(c[off] != 0):
        raise ValueError("the chart must be zero off y0 and the trace coordinates (coordinate_chart)")
    lc = np.asarray(lc, dtype=complex)
    L = lc[:-1] + lc[-1] * c[idx]
    W, ratio = curve_from_chart(Wc)
    if len(ratio) and np.min(ratio) <= 1e-12:
        raise ValueError("a witness point is at infinity (y0 = 0) on the chart")
    return W, np.concatenate([L[1:], [L[0]]])
