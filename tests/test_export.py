"""cdpr export: a subproblem's equations as text for other solvers; parsed back (sympy) they vanish at our certified
equilibria of that taut set, in every format."""

import json
import re

import numpy as np
import pytest
import sympy as sp

from cdpr_algebra import load_robot
from cdpr_algebra.cli.main import main
from cdpr_algebra.dgp.solve import dgp

ROBOT = "examples/seed000_test1.toml"


def _equations(fmt, text):
    if fmt == "json":
        d = json.loads(text)
        return d["variables"], [sp.sympify(e) for e in d["equations"]]
    if fmt == "phc":
        lines = text.strip().splitlines()
        n = int(lines[0])
        eqs = [sp.sympify(l.rstrip(";").replace("^", "**")) for l in lines[1:]]
        assert len(eqs) == n
        return None, eqs
    body = text.split("Constraints")[1].split("end")[0]
    variables = re.findall(r"^\s+(\w+) in \[", text.split("Constraints")[0], flags=re.M)
    eqs = [sp.sympify(l.strip().rstrip(";").replace("^", "**").replace("= 0", "")) for l in body.strip().splitlines()]
    return variables, eqs


@pytest.mark.parametrize("fmt", ["minibex", "phc", "json"])
def test_exported_equations_vanish_at_our_equilibria(fmt, capsys):
    robot = load_robot(ROBOT)
    sols = [s for s in dgp(robot).solutions if s.taut == (1, 2, 3)]
    assert len(sols) == 6
    assert main(["export", ROBOT, "--taut", "1", "2", "3", "--format", fmt]) == 0
    variables, eqs = _equations(fmt, capsys.readouterr().out)
    assert len(eqs) == 15
    names = ["px", "py", "pz", "ux", "uy", "uz", "vx", "vy", "vz", "wx", "wy", "wz", "lam1", "lam2", "lam3"]
    if variables is not None:
        assert variables == names
    syms = sp.symbols(names)
    for s in sols:
        lam = s.tensions[:3] / robot.lengths[:3]
        vals = list(s.position) + list(s.rotation[:, 0]) + list(s.rotation[:, 1]) + list(s.rotation[:, 2]) + list(lam)
        res = max(abs(float(e.subs(dict(zip(syms, vals))))) for e in eqs)
        assert res <= 1e-9


def test_bad_taut_and_format(capsys):
    assert main(["export", ROBOT, "--taut", "1", "4"]) == 2
    assert "--taut" in capsys.readouterr().err
    assert main(["export", ROBOT, "--taut", "1", "2", "--format", "maple"]) == 2
    assert "--format" in capsys.readouterr().err
    assert main(["export", ROBOT, "--taut", "1"]) == 2
    assert "--taut" in capsys.readouterr().err
