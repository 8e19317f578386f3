"""Plain-arithmetic evaluators rewritten for rectangular complex intervals, or for double-double numbers (source to
source, for generated code).

A generated evaluator such as ``taut_equations(x, p, dp, F, J, Ht, with_ht)`` uses only ``+ - *``, unary minus,
numeric constants, index arithmetic and subscripts ``x[k]``, ``F[r] = ...``, ``J[r, c] = ...``.
:func:`complex_interval_source` rewrites its source so that numba compiles it over intervals: arrays get a trailing
axis of length 4 (re lo, re hi, im lo, im hi); a value is a complex interval (a 4-tuple) or, when it is known to be
real (numeric constants, entries of the parameter arrays and what is computed from them alone), a real interval
(lo, hi); every operation becomes a call of the outward-rounded operations of :mod:`.complex_kernels` named by the
kinds of its operands (``cr_mul``: complex times real, ...).  A real operand touches only what
:class:`.complex_krawczyk.ComplexPair` touches (re + i im plus a real changes re alone), so the enclosures are
those of the Python objects.  Index arithmetic (``m = len(x) - 12``, ``ia + 3 * i + 0``, loop variables) is left as
it is.  The rewrite is mechanical: the interval evaluator has the same single source as the float one (the
derivation that generated it).

:func:`pair_arithmetic_source` is the same rewrite for any arithmetic on such tuples whose operations carry these
names; it differs only in how a real constant v is written: (v, v) for an interval, (v, 0.0) for a double-double
(hi, lo) (:mod:`cdpr_algebra.homotopy.double_double`, the residuals of the tracker's extended-precision Newton).
"""

from __future__ import annotations

import ast

__all__ = ["complex_interval_source", "pair_arithmetic_source"]


_OPS = {ast.Add: "add", ast.Sub: "sub", ast.Mult: "mul"}


class _Rewrite(ast.NodeTransformer):
    """The rewrite of one function: ``arrays`` its value arrays (``real`` ones hold real intervals), ``index`` its
    index names, ``complex_names`` the names that ever hold a complex value (the others hold real ones)."""

    def __init__(self, arrays, real, index, complex_names, second=None):
        self.arrays, self.real, self.index, self.cplx = arrays, real, index, complex_names
        self.second = second  # the second entry of a real constant v: None for v itself (an interval), or a number

    # ---- classification
    def is_index(self, node) -> bool:
        """An expression of integers only (constants, index names, len(...), their sums and products)."""
        if isinstance(node, ast.Constant):
            return isinstance(node.value, int) and not isinstance(node.value, bool)
        if isinstance(node, ast.Name):
            return node.id in self.index
        if isinstance(node, ast.BinOp):
            return self.is_index(node.left) and self.is_index(node.right)
        if isinstance(node, ast.UnaryOp):
            return self.is_index(node.operand)
        if isinstance(node, ast.Call):
            return isinstance(node.func, ast.Name) and node.func.id == "len"
        if isinstance(node, ast.Tuple):
            return all(self.is_index(e) for e in node.elts)
        return False

    # ---- value expressions: (new node, True when complex)
    def value(self, node):
        if isinstance(node, ast.Constant):
            if isinstance(node.value, bool) or not isinstance(node.value, (int, float)):
                raise ValueError(f"constant {node.value!r} in a value expression")
            v = float(node.value)
            w = v if self.second is None else float(self.second)
            return ast.Tuple([ast.Constant(v), ast.Constant(w)], ast.Load()), False
        if isinstance(node, ast.Name):
            if node.id in self.index:
                raise ValueError(f"index name {node.id!r} used as a value")
            return node, node.id in self.cplx
        if isinstance(node, ast.BinOp):
            op = _OPS.get(type(node.op))
            if op is None:
                raise ValueError(f"operation {type(node.op).__name__} is not plain arithmetic")
            (a, ca), (b, cb) = self.value(node.left), self.value(node.right)
            return _call(("c" if ca else "r") + ("c" if cb else "r") + "_" + op, a, b), ca or cb
        if isinstance(node, ast.UnaryOp):
            if isinstance(node.op, ast.USub):
                a, ca = self.value(node.operand)
                return _call("c_neg" if ca else "r_neg", a), ca
            if isinstance(node.op, ast.UAdd):
                return self.value(node.operand)
        if isinstance(node, ast.Subscript) and isinstance(node.value, ast.Name) and node.value.id in self.arrays:
            real = node.value.id in self.real
            return _call("r_ld" if real else "c_ld", node.value, node.slice), not real
        raise ValueError(f"unsupported expression {ast.unparse(node)!r}")

    def complex_value(self, node):
        v, c = self.value(node)
        return v if c else _call("r2c", v)

    # ---- statements
    def visit_Assign(self, node):
        if all(isinstance(t, ast.Name) and t.id in self.index for t in _targets(node)):
            if not self.is_index(node.value):
                raise ValueError(f"index name assigned a value: {ast.unparse(node)!r}")
            return node
        names = [t for t in node.targets if isinstance(t, ast.Name)]
        stores = [t for t in node.targets if not isinstance(t, ast.Name)]
        kinds = {t.id in self.cplx for t in names}
        if len(kinds) > 1:
            raise ValueError(f"real and complex names assigned together: {ast.unparse(node)!r}")
        out = []
        if names:
            rhs = self.complex_value(node.value) if kinds == {True} else self.value(node.value)[0]
            out.append(ast.Assign(targets=names, value=rhs))
        for t in stores:
            out.append(self.store(t, self.complex_value(ast.Name(names[0].id, ast.Load()) if names else node.value)))
        return out

    def visit_AugAssign(self, node):
        if not isinstance(node.op, ast.Add):
            raise ValueError("only += is rewritten")
        if isinstance(node.target, ast.Name):
            new = ast.BinOp(ast.Name(node.target.id, ast.Load()), ast.Add(), node.value)
            rhs = self.complex_value(new) if node.target.id in self.cplx else self.value(new)[0]
            return ast.Assign(targets=[ast.Name(node.target.id, ast.Store())], value=rhs)
        new = ast.BinOp(ast.Subscript(node.target.value, node.target.slice, ast.Load()), ast.Add(), node.value)
        return self.store(node.target, self.complex_value(new))

    def store(self, target, value):
        if not (isinstance(target, ast.Subscript) and isinstance(target.value, ast.Name)
                and target.value.id in self.arrays and target.value.id not in self.real):
            raise ValueError(f"unsupported assignment target {ast.unparse(target)!r}")
        sl = target.slice
        if isinstance(sl, ast.Tuple) and len(sl.elts) == 2:
            return ast.Expr(_call("c_st2", ast.Name(target.value.id, ast.Load()), sl.elts[0], sl.elts[1], value))
        return ast.Expr(_call("c_st1", ast.Name(target.value.id, ast.Load()), sl, value))


def _complex_names(fn, arrays, real, index) -> set:
    """The value names that ever hold a complex value (a fixpoint over the assignments)."""
    cplx: set = set()
    changed = True
    while changed:
        changed = False
        probe = _Rewrite(arrays, real, index, cplx)
        for node in ast.walk(fn):
            if isinstance(node, ast.Assign):
                names = [t.id for t in node.targets if isinstance(t, ast.Name) and t.id not in index]
                value = node.value
            elif isinstance(node, ast.AugAssign) and isinstance(node.target, ast.Name):
                names = [node.target.id]
                value = ast.BinOp(ast.Name(node.target.id, ast.Load()), ast.Add(), node.value)
            else:
                continue
            if not names or probe.is_index(value) and all(n in index for n in names):
                continue
            if probe.value(value)[1] and not set(names) <= cplx:
                cplx |= set(names)
                changed = True
    return cplx


def _call(name, *args):
    return ast.Call(ast.Name(name, ast.Load()), list(args), [])


def _targets(node: ast.Assign) -> list:
    """The target nodes of an assignment, tuples unpacked (``a, b = ...``, ``a = b = ...``)."""
    return [e for t in node.targets for e in (t.elts if isinstance(t, ast.Tuple) else [t])]


def _index_names(fn: ast.FunctionDef) -> set:
    """Names that hold integers for indexing: the names inside subscripts and ``range(...)`` calls, loop variables,
    and (transitively) the names their assignments read."""
    index: set = set()
    for node in ast.walk(fn):
        if isinstance(node, ast.For) and isinstance(node.target, ast.Name):
            index.add(node.target.id)
        roots = []
        if isinstance(node, ast.Subscript):
            roots.append(node.slice)
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id == "range":
            roots += node.args
        for r in roots:
            index |= {n.id for n in ast.walk(r) if isinstance(n, ast.Name)}
    changed = True
    while changed:
        changed = False
        for node in ast.walk(fn):
            if not isinstance(node, ast.Assign):
                continue
            names = {e.id for e in _targets(node) if isinstance(e, ast.Name)}
            if names & index:
                reads = {n.id for n in ast.walk(node.value) if isinstance(n, ast.Name)} - {"len"}
                if not reads <= index:
                    index |= reads
                    changed = True
    return index


def _localize_loops(fn: ast.FunctionDef) -> None:
    """Rename, inside each ``for`` body, the names the body defines before any read (its local temporaries, e.g.
    the common subexpressions ``t0, t1, ...`` that the code outside the loop also uses for other values) to
    ``name__<k>``: one kind (real or complex) per name.  Names the body reads first or accumulates (``s0 += ...``)
    are left alone."""
    for k, loop in enumerate([n for n in ast.walk(fn) if isinstance(n, ast.For)]):
        local, seen = set(), set()
        for stmt in loop.body:
            reads = {n.id for n in ast.walk(stmt) if isinstance(n, ast.Name) and isinstance(n.ctx, ast.Load)}
            if isinstance(stmt, ast.AugAssign) and isinstance(stmt.target, ast.Name):
                reads.add(stmt.target.id)
            seen |= reads
            if isinstance(stmt, ast.Assign):
                for e in _targets(stmt):
                    if isinstance(e, ast.Name) and e.id not in seen:
                        local.add(e.id)
                        seen.add(e.id)
        for node in ast.walk(ast.Module(body=loop.body, type_ignores=[])):
            if isinstance(node, ast.Name) and node.id in local:
                node.id = f"{node.id}__{k}"


def complex_interval_source(source: str, flags=("with_ht",), real=("p", "dp")) -> str:
    """The source of every function in ``source`` rewritten over complex intervals (module doc).  Arguments
    named in ``flags`` keep their meaning (booleans); every other argument is an array of values, complex
    intervals except those named in ``real`` (real intervals (lo, hi); entries (lo, hi, 0, 0) of an array with
    the trailing axis of 4).  Raises ValueError on anything but plain arithmetic."""
    return pair_arithmetic_source(source, flags, real)


def pair_arithmetic_source(source: str, flags=("with_ht",), real=("p", "dp"), constant_second=None) -> str:
    """:func:`complex_interval_source` with real constants v written (v, ``constant_second``) (None: (v, v)), for
    another arithmetic on the same tuples (module doc)."""
    tree = ast.parse(source)
    out = []
    for fn in tree.body:
        if not isinstance(fn, ast.FunctionDef):
            continue
        arrays = {a.arg for a in fn.args.args if a.arg not in flags}
        _localize_loops(fn)
        index = _index_names(fn) - arrays
        real_arrays = {a for a in arrays if a in real}
        rw = _Rewrite(arrays, real_arrays, index, _complex_names(fn, arrays, real_arrays, index), constant_second)
        body = fn.body
        if body and isinstance(body[0], ast.Expr) and isinstance(body[0].value, ast.Constant):
            body = body[1:]  # the docstring is replaced by the caller's
        fn.body = _block(rw, body)
        out.append(fn)
    return "\n\n\n".join(ast.unparse(ast.fix_missing_locations(f)) for f in out) + "\n"


def _block(rw, stmts) -> list:
    """The statements ``stmts`` rewritten (the bodies of ``for`` and ``if`` recursively, in place)."""
    out = []
    for stmt in stmts:
        if isinstance(stmt, (ast.For, ast.If)):
            stmt.body, stmt.orelse = _block(rw, stmt.body), _block(rw, stmt.orelse)
            out.append(stmt)
        else:
            r = rw.visit(stmt)
            out += r if isinstance(r, list) else [r]
    return out
