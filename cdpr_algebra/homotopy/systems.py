"""Polynomial systems with parameters, compiled once into batched numpy evaluators.

A :class:`PolynomialSystem` is given as sympy expressions ``F(x; p)`` in unknowns ``x`` (n) and
parameters ``p`` (m). It is compiled ONCE (lazily, per evaluator: F; F and dF/dx;
F, dF/dx and dF/dp) into straight-line Python code over numpy arrays: ``sympy.cse`` (without its
``optimizations``, which cost 4x the compile time for no faster code) removes common
subexpressions of the outputs together, integer powers become
products, and the code is turned into a function by ``exec``. Every array operation acts on one
coordinate of ALL points at once (points are stored transposed, shape (n, npaths), so rows are
contiguous), so the cost of one call is (number of operations) x (numpy overhead + npaths flops).

Route chosen by measurement (2 cores, numpy 2.4, complex128, the 12-unknown / 21-parameter DGP
system of ``benchmarks/bench_homotopy.py`` at 156 points, F + dF/dx + dF/dp in one call;
``benchmarks/bench_evaluators.py`` re-measures):

==================================================  ==============
route                                               per call
==================================================  ==============
cse'd straight-line code via ``exec`` (this)          0.42-0.71 ms
sympy ``lambdify(..., cse=True)`` of every entry      1.8-2.9 ms
monomial/coefficient tensors (joint monomials of      ~650 ms
(x, p) by broadcast powers ``prod(z**E)``, then
dense contractions for F, dF/dx, dF/dp; naive)
==================================================  ==============

(two runs on a shared machine; ``python -m cdpr_algebra.homotopy.systems`` re-runs the measurement.) The straight-line code wins
because these systems are sparse and of low degree: a few hundred cheap vector operations, where
the tensor route forms every monomial and its derivatives densely. Not tried: a sparse tensor
route (sparse coefficient matrix times monomials), which should win on DENSE quadratic systems
such as the expanded Study-coordinate Stewart-Gough system (0.9 ms per call here for 8 unknowns,
because each Jacobian entry is a long linear form).

An mpmath evaluator (``sympy.lambdify`` with ``modules="mpmath"``) is built lazily for the few
paths that the tracker retries in higher precision.
"""

from __future__ import annotations

import hashlib
from typing import Sequence

import numpy as np

__all__ = ["PolynomialSystem", "compile_straight_line"]


def _printer():
    """The code printer (a sympy class: built on first use, so that importing the numeric engine does not
    import sympy)."""
    from sympy.printing.pycode import PythonCodePrinter

    class _Printer(PythonCodePrinter):
        """Python code for numpy arrays: integer powers as products, exact rationals as floats."""

        def _print_Pow(self, expr, rational=False):
            b, e = expr.as_base_exp()
            if e.is_Integer and 1 < int(e) <= 8:
                s = self.parenthesize(b, 100)
                return "*".join([s] * int(e))
            if e.is_Integer and int(e) == -1:
                return "(1.0/%s)" % self.parenthesize(b, 100)
            return super()._print_Pow(expr, rational=rational)

        def _print_Rational(self, expr):
            return repr(float(expr.p) / float(expr.q))

        def _print_Integer(self, expr):
            return repr(float(int(expr)))

        def _print_Float(self, expr):
            return repr(float(expr))

        def _print_ImaginaryUnit(self, expr):
            return "1j"

    return _Printer({"fully_qualified_modules": False, "inline": True, "allow_unknown_functions": False})


def compile_straight_line(outputs, inputs, name="_f"):
    """Compile sympy expressions to one numpy function by cse'd straight-line code and ``exec``.

    ``outputs``: list of ``(target, expr)`` where target is a Python lvalue (e.g. ``"J[:, 0, 1]"``)
    written in the generated function. ``inputs``: list of ``(symbol, source)``, the source being a
    Python expression (e.g. ``"X[0]"``). The generated function is ``name(X, P, F, J, JP)``.
    Returns ``(function, source_text)``.
    """
    import sympy as sp

    printer = _printer()
    exprs = [e for _, e in outputs]
    nonconst = [i for i, e in enumerate(exprs) if not e.is_number]
    repl, reduced = sp.cse([exprs[i] for i in nonconst], symbols=sp.numbered_symbols("_c"), optimizations=None)
    lines = [f"def {name}(X, P, F, J, JP):"]
    for sym, src in inputs:
        lines.append(f"    {printer.doprint(sym)} = {src}")
    for sym, e in repl:
        lines.append(f"    {printer.doprint(sym)} = {printer.doprint(e)}")
    red = dict(zip(nonconst, reduced))
    for i, (target, e) in enumerate(outputs):
        code = printer.doprint(red[i]) if i in red else repr(complex(e))
        lines.append(f"    {target} = {code}")
    lines.append("    return None")
    src = "\n".join(lines)
    ns = {"np": np}
    exec(compile(src, f"<cdpr_algebra.homotopy generated {name}>", "exec"), ns)
    return ns[name], src


class PolynomialSystem:
    """A square or overdetermined polynomial system F(x; p) = 0 in unknowns x and parameters p.

    Evaluation methods take ``x`` of shape (npaths, n) and ``p`` of shape (m,) (same parameters for
    every path) or (npaths, m); they return complex128 arrays:

    * :meth:`evaluate` -> F, shape (npaths, neq);
    * :meth:`evaluate_and_jacobian` -> F, dF/dx of shape (npaths, neq, n);
    * :meth:`evaluate_all` -> F, dF/dx, dF/dp of shape (npaths, neq, m).

    ``hash`` is a SHA-256 of the equations, unknowns and parameters (stable across runs), used to
    tie stored solution sets to their system.
    """

    def __init__(self, equations: Sequence, variables: Sequence, parameters: Sequence = (), name: str = "system"):
        import sympy as sp

        self.equations = tuple(sp.sympify(e) for e in equations)
        self.variables = tuple(variables)
        self.parameters = tuple(parameters)
        self.name = name
        if len(set(self.variables) | set(self.parameters)) != len(self.variables) + len(self.parameters):
            raise ValueError("unknowns and parameters must be distinct symbols")
        free = set().union(*(e.free_symbols for e in self.equations)) if self.equations else set()
        extra = free - set(self.variables) - set(self.parameters)
        if extra:
            raise ValueError(f"symbols {sorted(map(str, extra))} are neither unknowns nor parameters")
        self.n = len(self.variables)
        self.m = len(self.parameters)
        self.neq = len(self.equations)
        polys = [sp.Poly(e, *self.variables) for e in self.equations]
        self.degrees = tuple(int(p.total_degree()) for p in polys)
        self._compiled = {}
        self._sources = {}
        self._mp = None
        self.hash = hashlib.sha256(
            repr((tuple(sp.srepr(e) for e in self.equations), tuple(map(str, self.variables)),
                  tuple(map(str, self.parameters)))).encode()
        ).hexdigest()

    def __repr__(self):
        return f"PolynomialSystem({self.name!r}: {self.neq} equations, {self.n} unknowns, {self.m} parameters, degrees {self.degrees})"

    # -- compilation -------------------------------------------------------------------------
    def _outputs(self, kind):
        import sympy as sp

        xs, ps = self.variables, self.parameters
        out = [(f"F[:, {i}]", e) for i, e in enumerate(self.equations)]
        if kind in ("fj", "fjp"):
            for i, e in enumerate(self.equations):
                for j, x in enumerate(xs):
                    d = sp.diff(e, x)
                    if d != 0:
                        out.append((f"J[:, {i}, {j}]", d))
        if kind == "fjp":
            for i, e in enumerate(self.equations):
                for k, p in enumerate(ps):
                    d = sp.diff(e, p)
                    if d != 0:
                        out.append((f"JP[:, {i}, {k}]", d))
        return out

    def _function(self, kind):
        """The compiled evaluator ``kind`` in {"f", "fj", "fjp"} (compiled on first use, then cached)."""
        fn = self._compiled.get(kind)
        if fn is None:
            inputs = [(x, f"X[{i}]") for i, x in enumerate(self.variables)]
            inputs += [(p, f"P[{k}]") for k, p in enumerate(self.parameters)]
            fn, src = compile_straight_line(self._outputs(kind), inputs, "_" + kind.upper())
            self._compiled[kind] = fn
            self._sources[kind] = src
        return fn

    # -- evaluation --------------------------------------------------------------------------
    def _prep(self, x, p):
        x = np.asarray(x, dtype=complex)
        if x.ndim == 1:
            x = x[None, :]
        if x.shape[1] != self.n:
            raise ValueError(f"expected points with {self.n} coordinates, got shape {x.shape}")
        X = np.ascontiguousarray(x.T)
        if self.m:
            if p is None:
                raise ValueError(f"{self.name}: parameters needed ({self.m})")
            p = np.asarray(p, dtype=complex)
            P = p[:, None] if p.ndim == 1 else np.ascontiguousarray(p.T)
        else:
            P = None
        return x.shape[0], X, P

    def evaluate(self, x, p=None) -> np.ndarray:
        N, X, P = self._prep(x, p)
        F = np.empty((N, self.neq), dtype=complex)
        self._function("f")(X, P, F, None, None)
        return F

    def evaluate_and_jacobian(self, x, p=None):
        N, X, P = self._prep(x, p)
        F = np.empty((N, self.neq), dtype=complex)
        J = np.zeros((N, self.neq, self.n), dtype=complex)
        self._function("fj")(X, P, F, J, None)
        return F, J

    def evaluate_all(self, x, p=None):
        N, X, P = self._prep(x, p)
        F = np.empty((N, self.neq), dtype=complex)
        J = np.zeros((N, self.neq, self.n), dtype=complex)
        JP = np.zeros((N, self.neq, self.m), dtype=complex)
        self._function("fjp")(X, P, F, J, JP)
        return F, J, JP

    # -- high precision ----------------------------------------------------------------------
    def mp_functions(self):
        """mpmath evaluators ``(F(x, p) -> list, J(x, p) -> matrix, JP(x, p) -> matrix)`` (lazy)."""
        if self._mp is None:
            import mpmath
            import sympy as sp

            args = list(self.variables) + list(self.parameters)
            F = sp.Matrix(self.equations)
            fF = sp.lambdify(args, list(self.equations), modules="mpmath")
            fJ = sp.lambdify(args, F.jacobian(self.variables).tolist(), modules="mpmath")
            fP = sp.lambdify(args, F.jacobian(self.parameters).tolist(), modules="mpmath") if self.m else None

            def mF(x, p=()):
                return mpmath.matrix(fF(*x, *p))

            def mJ(x, p=()):
                return mpmath.matrix(fJ(*x, *p))

            def mP(x, p=()):
                return mpmath.matrix(fP(*x, *p)) if fP else mpmath.matrix(self.neq, 0)

            self._mp = (mF, mJ, mP)
        return self._mp

    def substitute_parameters(self, p) -> "PolynomialSystem":
        """The system with parameters replaced by numbers (no parameters left)."""
        import sympy as sp

        sub = {s: sp.nsimplify(complex(v)) if complex(v).imag else sp.Float(complex(v).real, 17)
               for s, v in zip(self.parameters, np.asarray(p, dtype=complex))}
        return PolynomialSystem([e.xreplace(sub) for e in self.equations], self.variables, (), self.name)
