"""Start systems and their start solutions.

* :func:`total_degree` -- G_i(x) = x_i^{d_i} - 1 (Bezout number prod d_i of start solutions: all
  tuples of roots of unity); used with the gamma trick H = gamma t G + (1 - t) F.
* :func:`multi_homogeneous` -- for a partition of the unknowns into groups, the linear-product start
  system G_i = prod_j prod_{k <= d_ij} L_ijk(x_group_j) with random complex affine forms L, where
  d_ij is the degree of F_i in group j. Its start solutions (one linear solve per admissible choice
  of factors) number the m-homogeneous Bezout number, the coefficient of prod a_j^{n_j} in
  prod_i (sum_j d_ij a_j) (n_j = size of group j).
* :func:`parameter_homotopy` -- straight segment in complex parameter space from a solved
  generic instance p1 to target parameters p0, with a random complex detour point (two segments
  p1 -> p_mid -> p0) or the gamma-trick variant p(t) = (gamma t p1 + (1-t) p0)/(gamma t + 1 - t).

Random data comes from ``numpy.random.default_rng(seed)``: the same seed gives the same start system.
"""

from __future__ import annotations

import itertools
from dataclasses import dataclass

import numpy as np

from .homotopies import ParameterHomotopy, StraightLineHomotopy
from .systems import PolynomialSystem

__all__ = ["StartSystem", "total_degree", "multi_homogeneous", "bezout_number", "multi_homogeneous_bezout_number",
           "random_gamma", "parameter_homotopy"]


def random_gamma(rng: np.random.Generator) -> complex:
    """A random point on the unit circle."""
    return complex(np.exp(2j * np.pi * rng.random()))


@dataclass
class StartSystem:
    """A start system G with its start solutions and the straight-line homotopy to a target F."""

    system: PolynomialSystem
    solutions: np.ndarray  # (count, n)
    kind: str

    def homotopy(self, target: PolynomialSystem, gamma: complex, target_parameters=None) -> StraightLineHomotopy:
        return StraightLineHomotopy(self.system, target, gamma, None, target_parameters)


def bezout_number(system: PolynomialSystem) -> int:
    return int(np.prod(system.degrees))


def total_degree(target: PolynomialSystem) -> StartSystem:
    """x_i^{d_i} - 1 = 0, i = 1..n, with all prod d_i start solutions (roots of unity)."""
    if target.neq != target.n:
        raise ValueError("total degree start system needs a square system")
    xs = target.variables
    eqs = [x ** d - 1 for x, d in zip(xs, target.degrees)]
    G = PolynomialSystem(eqs, xs, (), name="total_degree_start")
    roots = [np.exp(2j * np.pi * np.arange(d) / d) for d in target.degrees]
    sols = np.array(list(itertools.product(*roots)), dtype=complex).reshape(-1, target.n)
    return StartSystem(G, sols, "total_degree")


def _group_degrees(system: PolynomialSystem, groups):
    import sympy as sp

    D = np.zeros((system.neq, len(groups)), dtype=int)
    for i, e in enumerate(system.equations):
        for j, g in enumerate(groups):
            D[i, j] = sp.Poly(e, *g).total_degree() if e.has(*g) else 0
    return D


def multi_homogeneous_bezout_number(system: PolynomialSystem, groups) -> int:
    """Coefficient of prod_j a_j^{n_j} in prod_i (sum_j d_ij a_j) (dynamic programming over counts)."""
    D = _group_degrees(system, groups)
    sizes = tuple(len(g) for g in groups)
    table = {tuple(0 for _ in sizes): 1}
    for i in range(system.neq):
        new = {}
        for counts, c in table.items():
            for j, d in enumerate(D[i]):
                if d and counts[j] < sizes[j]:
                    k = list(counts)
                    k[j] += 1
                    new[tuple(k)] = new.get(tuple(k), 0) + c * int(d)
        table = new
    return int(table.get(sizes, 0))


def multi_homogeneous(target: PolynomialSystem, groups, seed: int | None = 0) -> StartSystem:
    """Linear-product start system for the variable ``groups`` (a partition of the unknowns)."""
    import sympy as sp

    groups = [tuple(g) for g in groups]
    allv = [v for g in groups for v in g]
    if sorted(map(str, allv)) != sorted(map(str, target.variables)) or len(allv) != target.n:
        raise ValueError("groups must partition the unknowns")
    rng = np.random.default_rng(seed)
    D = _group_degrees(target, groups)
    pos = {v: k for k, v in enumerate(target.variables)}
    n = target.n
    # forms[i][j] = list of (coefficient vector over the group, constant)
    forms = []
    eqs = []
    for i in range(target.neq):
        fi = []
        expr = sp.Integer(1)
        for j, g in enumerate(groups):
            fl = []
            for _ in range(D[i, j]):
                c = rng.normal(size=len(g)) + 1j * rng.normal(size=len(g))
                c0 = complex(rng.normal() + 1j * rng.normal())
                fl.append((c, c0))
                expr = expr * (sum(sp.Float(ck.real, 17) * v + sp.I * sp.Float(ck.imag, 17) * v for ck, v in zip(c, g))
                               + sp.Float(c0.real, 17) + sp.I * sp.Float(c0.imag, 17))
            fi.append(fl)
        forms.append(fi)
        eqs.append(expr)
    G = PolynomialSystem(eqs, target.variables, (), name="linear_product_start")
    sizes = [len(g) for g in groups]
    sols = []

    def rec(i, counts, chosen):
        if i == target.neq:
            A = np.zeros((n, n), dtype=complex)
            b = np.zeros(n, dtype=complex)
            for r, (j, (c, c0)) in enumerate(chosen):
                for ck, v in zip(c, groups[j]):
                    A[r, pos[v]] = ck
                b[r] = -c0
            sols.append(np.linalg.solve(A, b))
            return
        for j in range(len(groups)):
            if counts[j] < sizes[j]:
                counts[j] += 1
                for form in forms[i][j]:
                    rec(i + 1, counts, chosen + [(j, form)])
                counts[j] -= 1

    rec(0, [0] * len(groups), [])
    return StartSystem(G, np.array(sols, dtype=complex).reshape(-1, n), "multi_homogeneous")


def parameter_homotopy(system: PolynomialSystem, start_parameters, target_parameters, rng=None,
                       detour: bool = False, gamma: bool = False):
    """Homotopies from ``start_parameters`` to ``target_parameters``: a list of one or two segments.

    ``detour``: go through a random complex point p_mid = (p1 + p0)/2 + |p1 - p0| * z (z random complex,
    unit scale) so that the path avoids real discriminant loci; ``gamma``: the gamma-trick variant.
    """
    rng = rng if rng is not None else np.random.default_rng(0)
    p1 = np.asarray(start_parameters, dtype=complex)
    p0 = np.asarray(target_parameters, dtype=complex)
    if gamma:
        return [ParameterHomotopy(system, p1, p0, gamma=random_gamma(rng))]
    if detour:
        scale = np.abs(p1 - p0) + 1e-3 * (1 + np.abs(p0))
        mid = 0.5 * (p1 + p0) + 0.5 * scale * (rng.normal(size=p0.shape) + 1j * rng.normal(size=p0.shape))
        return [ParameterHomotopy(system, p1, mid), ParameterHomotopy(system, mid, p0)]
    return [ParameterHomotopy(system, p1, p0)]
