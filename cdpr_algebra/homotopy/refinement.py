"""Newton refinement of endpoints: :func:`refine` (full double precision, with double-double residuals where the
homotopy offers them) and the relative residual every endpoint reports."""

from __future__ import annotations

import numpy as np

from .tracker import _norm, _solve

__all__ = ["refine", "relative_residual"]


def refine(homotopy, x, t=0.0, max_iter: int = 8, tol: float = 1e-13, extended: bool = True):
    """Newton on H(x, t) = 0 for every point. Returns (x, last_update, residual, condition, quadratic).

    ``condition`` is the 2-norm condition number of dF/dx with columns scaled by max(1, |x_j|) and rows
    normalized (invariant to the scale of each equation and of large coordinates).

    ``quadratic`` is True where Newton reached max(``tol``, 1e-15 cond) (1 + |x|): full double precision
    for that condition number, which on a singular point (linear convergence) does not happen
    within ``max_iter`` iterations.

    With ``extended`` and a homotopy that offers a double-double residual (:func:`.compiled.residual_dd`), the
    residuals are evaluated in double-double (the Jacobians and updates stay in double): Newton then converges to
    full double precision on points whose condition number is up to ~1 / eps, not ~1 / (eps tol).
    """
    x = np.array(x, dtype=complex, copy=True)
    N = len(x)
    tt = np.full(N, t, dtype=complex)
    residual = None
    if extended and getattr(homotopy, "compiled_residual_dd", None) is not None:
        from .compiled import residual_dd

        residual = residual_dd(homotopy)
    upd = np.full(N, np.inf)
    active = np.arange(N)
    prev = np.full(N, np.inf)
    for _ in range(max_iter):
        if not active.size:
            break
        H, Hx = homotopy.evaluate_and_jacobian(x[active], tt[active])
        if residual is not None:
            H = residual(x[active], tt[active])
        d = _solve(Hx, -H)
        e = _norm(d) / (1 + _norm(x[active]))
        good = np.isfinite(e)
        # take the step unless Newton is diverging (update grew by > 2 from a small value)
        take = good & ~((e > 2 * prev[active]) & (prev[active] < 1e-8))
        x[active[take]] += d[take]
        upd[active] = np.where(take, e, upd[active])
        prev[active] = np.where(take, e, prev[active])
        active = active[take & (e > tol)]
    H, Hx = homotopy.evaluate_and_jacobian(x, tt)
    if residual is not None:
        H = residual(x, tt)
    res = relative_residual(H, x)
    with np.errstate(all="ignore"):
        try:
            # scaled condition number: columns by max(1, |x_j|), rows to unit norm, so a regular solution
            # with large coordinates (far from the origin, not at infinity) is not mistaken for a singular one
            Hs = Hx * np.maximum(1.0, np.abs(x))[:, None, :]
            Hs = Hs / np.maximum(np.linalg.norm(Hs, axis=2, keepdims=True), 1e-300)
            cond = np.linalg.cond(Hs)
        except np.linalg.LinAlgError:
            cond = np.full(N, np.inf)
    cond = np.where(np.isfinite(cond), cond, np.inf)
    # full precision: the last update is at the round-off floor of a problem with that condition
    floor = np.maximum(tol, 1e-15 * cond)
    return x, upd, res, cond, upd <= floor


def relative_residual(H, X) -> np.ndarray:
    """max |H| / (1 + max |x|) per row: the residual of points X (rows) with values H, relative to their size, as
    every endpoint reports it."""
    return np.max(np.abs(H), axis=1) / (1 + np.max(np.abs(X), axis=1))
