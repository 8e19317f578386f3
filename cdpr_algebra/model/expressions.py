"""Expressions typed by users: trajectories of the platform (``cdpr cc --path``) or of the cable lengths
(``cdpr track --expressions``) as functions of parameters, and range ends such as ``pi/2``; parsed by sympy with a
closed list of functions, every error naming the option that gave the text."""

from __future__ import annotations

import numpy as np
import sympy as sp

from .errors import CdprInputError

__all__ = ["FUNCTIONS", "parse_expression", "range_bound"]

FUNCTIONS = {"sin": sp.sin, "cos": sp.cos, "tan": sp.tan, "sqrt": sp.sqrt, "exp": sp.exp, "log": sp.log,
             "pi": sp.pi, "E": sp.E, "Abs": sp.Abs, "abs": sp.Abs}


def parse_expression(text: str, names, option: str):
    """A sympy expression in the parameters ``names`` from a string (``^`` is a power; sin, cos, tan, sqrt, exp,
    log, Abs, pi, E); bad input raises CdprInputError naming ``option``."""
    from sympy.parsing.sympy_parser import parse_expr, standard_transformations

    if not isinstance(text, str) or not text.strip():
        raise CdprInputError(option, f"empty expression {text!r}")
    local = {n: sp.Symbol(n, real=True) for n in names}
    local.update(FUNCTIONS)
    try:
        expr = parse_expr(text.replace("^", "**"), local_dict=local, global_dict={"Integer": sp.Integer,
                          "Float": sp.Float, "Rational": sp.Rational, "Symbol": sp.Symbol, "Function": sp.Function},
                          transformations=standard_transformations, evaluate=True)
    except Exception as exc:  # tokenizer, syntax and evaluation errors alike
        raise CdprInputError(option, f"cannot parse {text!r} ({type(exc).__name__}: {exc})".replace("\n", " ")) from None
    if not isinstance(expr, sp.Expr):
        raise CdprInputError(option, f"{text!r} is not an expression")
    extra = sorted(str(s) for s in expr.free_symbols if str(s) not in names)
    if extra:
        expected = (f"the parameter{'s are' if len(names) > 1 else ' is'} {', '.join(names)}" if names
                    else "a constant is expected")
        raise CdprInputError(option, f"unknown symbol {extra[0]!r} in {text!r} ({expected})")
    if expr.atoms(sp.Function) - expr.atoms(sp.sin, sp.cos, sp.tan, sp.exp, sp.log, sp.Abs):
        raise CdprInputError(option, f"unknown function in {text!r}")
    return expr


def range_bound(value, option: str = "ranges") -> float:
    """A range end: a number, or a constant expression (``pi/2``, ``2*pi``, ``sqrt(2)``), as a finite float."""
    if isinstance(value, str):
        expr = parse_expression(value, (), option)
        try:
            value = float(expr.evalf(30))
        except TypeError:
            raise CdprInputError(option, f"{value!r} is not a real constant") from None
    value = float(value)
    if not np.isfinite(value):
        raise CdprInputError(option, f"expected a finite number, got {value}")
    return value
