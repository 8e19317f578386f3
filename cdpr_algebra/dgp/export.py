"""The equations of one DGP subproblem (a taut set of m = 2 .. 6 cables, Berti, Merlet and Carricato 2016 eqs. 4-5
as formulated in :func:`cdpr_algebra.model.taut_equations.taut_family`) with the robot's numbers substituted, for other
solvers: Minibex (IbexSolve), PHCpack's input format, or JSON.

Unknowns: ``px py pz`` (the platform frame's origin), ``ux .. wz`` (the columns of R), ``lam1 .. lamm``
(tau_i / rho_i); 12 + m polynomial equations of degree 2.  Numbers are written with 17 significant digits (they
round-trip to the robot file's doubles).  The Minibex domains: the position within max rho + max |b'| of the exit
points' centroid, R's entries in [-1, 1], lam in [0, 1e8] (admissible tensions)."""

from __future__ import annotations

import json

import numpy as np
import sympy as sp

from cdpr_algebra.model.errors import CdprInputError
from cdpr_algebra.model.taut_equations import taut_family, taut_parameters

FORMATS = ("minibex", "phc", "json")


def subproblem_equations(robot, cables, lengths):
    """(variables, expanded equations with the numbers substituted) for the 0-based taut set ``cables``."""
    m = len(cables)
    if not 2 <= m <= 6:
        raise CdprInputError("--taut", f"export covers 2 to 6 taut cables, got {m}")
    fam = taut_family(m)
    values = taut_parameters(robot, cables, lengths)
    subs = {p: sp.Float(repr(float(v)), 17) for p, v in zip(fam.parameters, values)}
    eqs = [sp.expand(e.xreplace(subs)) for e in fam.equations]
    return list(fam.variables), eqs


def _text(e, power: str) -> str:
    s = sp.sstr(e, full_prec=False)
    return s.replace("**", power)


def export_subproblem(robot, cables, lengths, fmt: str) -> str:
    if fmt not in FORMATS:
        raise CdprInputError("--format", f"expected one of {', '.join(FORMATS)}, got {fmt!r}")
    xs, eqs = subproblem_equations(robot, cables, lengths)
    rho = np.asarray(lengths, dtype=float)
    taut = [c + 1 for c in cables]
    if fmt == "json":
        return json.dumps({"robot": robot.name, "taut": taut, "lengths": rho.tolist(),
                           "variables": [str(x) for x in xs], "equations": [_text(e, "**") for e in eqs],
                           "meaning": {"p": "platform frame origin", "u, v, w": "columns of R",
                                       "lam_i": "tau_i / rho_i"}}, indent=1)
    if fmt == "phc":
        lines = [f"{len(eqs)}"] + [_text(e, "^") + ";" for e in eqs]
        return "\n".join(lines) + "\n"
    idx = list(cables)
    c = robot.base[idx].mean(axis=0)
    R = float(rho[idx].max() + np.linalg.norm(robot.platform - robot.com, axis=1).max() + robot.size)
    dom = {}
    for k, x in enumerate(xs[:3]):
        dom[x] = f"[{float(c[k] - R)!r}, {float(c[k] + R)!r}]"
    for x in xs[3:12]:
        dom[x] = "[-1, 1]"
    for x in xs[12:]:
        dom[x] = "[0, 1e8]"
    lines = [f"// cdpr_algebra: DGP of {robot.name}, taut cables {taut}, lengths {rho.tolist()}",
             "// p: platform frame origin; u, v, w: columns of R; lam_i = tau_i / rho_i", "Variables"]
    lines += [f"  {x} in {dom[x]};" for x in xs]
    lines += ["Constraints"] + [f"  {_text(e, '^')} = 0;" for e in eqs] + ["end"]
    return "\n".join(lines) + "\n"
