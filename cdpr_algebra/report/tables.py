"""Readable text tables of results, laid out like the papers' tables."""

from __future__ import annotations

import numpy as np


def _fmt(v, digits=3) -> str:
    if isinstance(v, (complex, np.complexfloating)) and v.imag != 0:
        return f"{v.real:+.{digits}f}{v.imag:+.{digits}f}i"
    return f"{float(np.real(v)):+.{digits}f}"


def _vec(vs, digits=3) -> str:
    return "(" + ", ".join(_fmt(v, digits) for v in vs) + ")"


def format_table(headers: list[str], rows: list[list[str]]) -> str:
    widths = [max(len(h), *(len(r[i]) for r in rows)) if rows else len(h) for i, h in enumerate(headers)]
    line = "  ".join(h.ljust(w) for h, w in zip(headers, widths))
    out = [line, "  ".join("-" * w for w in widths)]
    out += ["  ".join(c.ljust(w) for c, w in zip(r, widths)) for r in rows]
    return "\n".join(out)


def certified_cell(solution) -> str:
    """'yes', 'boundary' (a tension zero within rounding), 'no' (see the certificate's reason) or '-' (none)."""
    c = getattr(solution, "certificate", None)
    if c is None:
        return "-"
    if c.certified:
        return "yes"
    return "boundary" if "boundary" in (c.reason or "") else "no"


def hessian_cell(solution) -> str:
    """The H_r class proven by the interval certificate, or 'undecided (float: X)' with the floating-point estimate
    X; '-' for a complex solution."""
    label = getattr(solution, "hessian_label", None)
    if label is None:
        return "-"
    if label == "undecided":
        return f"undecided (float: {solution.hessian})" if solution.hessian else "undecided"
    return label


def igp_table(result, include_complex: bool = False) -> str:
    """Seed 004 Tables 1-4 layout: one row per solution, with the interval certificate (certify.py).  The H_r column
    is the class the certificate proves, or 'undecided' with the floating-point estimate labelled as such."""
    sols = result.solutions if include_complex else result.real_solutions
    lines = []
    if result.problem == "orientation":
        headers = ["#", "G (x, y, z)", "(rho_1, rho_2, rho_3)", "(tau_1, tau_2, tau_3)", "H_r", "admissible", "certified"]
        rows = [[str(i + 1), _vec(s.com_position, 4), _vec(s.lengths, 2), _vec(s.tensions, 2), hessian_cell(s),
                 "yes" if s.admissible else "no", certified_cell(s)] for i, s in enumerate(sols)]
    else:
        headers = ["#", "(e0, e1, e2, e3)", "(rho_1, rho_2, rho_3)", "(tau_1, tau_2, tau_3)", "H_r", "admissible",
                   "certified"]
        rows = [[str(i + 1), _vec(s.euler_parameters, 10), _vec(s.lengths, 2), _vec(s.tensions, 2), hessian_cell(s),
                 "yes" if s.admissible else "no", certified_cell(s)] for i, s in enumerate(sols)]
    if rows:
        lines.append(format_table(headers, rows))
        lines += [f"#{i + 1} not certified: {s.certificate.reason}" for i, s in enumerate(sols)
                  if getattr(s, "certificate", None) is not None and not s.certificate.certified]
        lines += [f"#{i + 1}: {s.certificate.extra['zero_tension']['proof']}" for i, s in enumerate(sols)
                  if getattr(s, "certificate", None) is not None and "zero_tension" in s.certificate.extra]
        if any(not s.real for s in sols):
            lines.append("complex solutions: rho_i = sqrt(s_i^H s_i) with s_i = B_i - A_i (the Hermitian norm, seed "
                         "004 Table 4's convention) and tau_i = rho_i (tau_i / rho_i): no robot has these lengths")
    if result.solution_set is not None:
        lines.append(f"solution set: {result.solution_set.kind}: {result.solution_set.description}")
        for k, v in result.solution_set.data.items():
            if k != "work_frame":
                lines.append(f"  {k}: {v}")
    n_real = len(result.real_solutions)
    n_stable = sum(bool(s.stable_proven) and s.admissible for s in result.solutions)
    n_float = sum(bool(s.stable) and s.admissible for s in result.solutions)
    n_undecided = sum(1 for s in result.real_solutions if s.hessian_proven is None)
    summary = (f"{len(result.solutions)} solution(s), {n_real} real, "
               f"{sum(s.admissible for s in result.solutions)} admissible (tensions >= 0), "
               f"{n_stable} admissible and proven stable"
               + (f" ({n_float} by the floating-point H_r)" if n_float != n_stable else "")
               + (f", H_r undecided for {n_undecided}" if n_undecided else "") + ", "
               f"{sum(bool(getattr(s, 'certified', None)) for s in result.solutions)} certified; "
               f"{result.seconds * 1e3:.1f} ms")
    if result.message:
        summary += f"; {result.message}"
    lines.append(summary)
    return "\n".join(lines)
